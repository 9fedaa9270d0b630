//! Step 1 of the paper's cut (§3): find the tets the cut may touch, through a bounding-volume
//! hierarchy over tets that lives as long as the mesh and is kept up to date as cuts add
//! tets.
//!
//! Cuts only ever replace a tet by children lying inside it, so the hierarchy never needs
//! refitting: a split tet's first child takes its slot and the others are chained after it
//! in the same leaf (`next`). Each node also keeps the largest vertex scale below it, so a
//! query knows how far from the plane a vertex may be and still be snapped onto the cut.

use super::classify::{CrackTips, StateCache, StateClassifier, is_candidate};
use super::prefetch::prefetch;
use crate::geom::{Aabb, CutPolygon, DVec3, Tolerance};
use crate::mesh::{Tet, TetId};

/// Tets per leaf at build time.
const LEAF_SIZE: usize = 4;

/// How many tets ahead of the one it classifies a query asks for vertex positions: enough
/// for the misses of several tets to overlap, few enough that the lines are still cached
/// when their tet's turn comes.
const PREFETCH_AHEAD: usize = 8;

/// One cache line (aligned): a query run with cold caches waits for one line per node.
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
struct Node {
    bbox: Aabb,
    max_scale: f64,
    /// Leaf (`count > 0`): the start of its range of `items`; inner node (`count == 0`):
    /// its right child (the left one is `self + 1`).
    link: u32,
    count: u32,
}

const _: () = assert!(std::mem::size_of::<Node>() == 64);

impl Node {
    /// A leaf's range of `items`.
    fn items(&self) -> std::ops::Range<usize> {
        self.link as usize..(self.link + self.count) as usize
    }
}

/// The hierarchy (see the module docs).
#[derive(Clone, Debug, Default)]
pub struct TetBvh {
    nodes: Vec<Node>,
    /// Leaf contents: the first tet of each chain.
    items: Vec<TetId>,
    /// Per tet slot: the next tet of its leaf's chain.
    next: Vec<TetId>,
}

/// How a query runs: in parallel over subtrees (then without the buffers), or on one
/// thread; either way with a cache of the states of vertices near the plane.
pub struct QueryOptions<'c> {
    pub parallel: bool,
    pub cache: &'c mut StateCache,
    pub buffers: &'c mut QueryBuffers,
    /// The classifier's contour band ([`StateClassifier::with_contour_band`]; 0: none).
    pub contour_band: f64,
    /// Crack tips and their reach ([`StateClassifier::with_crack_tips`]; none: `None`).
    pub tips: Option<(&'c CrackTips, f64)>,
    /// Vertices of earlier cracks ([`StateClassifier::with_crack_vertices`]; none: `None`).
    pub crack: Option<&'c [bool]>,
    /// Vertices counting as lying in the plane, and the farthest of them from it
    /// ([`StateClassifier::with_glued`]; none: `None`).
    pub glued: Option<(&'c [bool], f64)>,
}

/// What a query found: candidate tets with their vertex states, and how many tets it
/// classified on the way.
#[derive(Clone, Debug, Default)]
pub struct Candidates {
    pub tets: Vec<TetId>,
    pub states: Vec<[u8; 4]>,
    pub tested: usize,
}

/// The lists a query on one thread fills on its way (nodes of a level, leaves, tets),
/// kept by the caller from one query to the next, so that a query does not allocate (with
/// the other buffers kept this way, a cold scalpel step 3-8% faster).
#[derive(Clone, Debug, Default)]
pub struct QueryBuffers {
    leaves: Vec<u32>,
    level: Vec<u32>,
    below: Vec<u32>,
    firsts: Vec<TetId>,
    list: Vec<TetId>,
}

impl QueryBuffers {
    /// Room for a query listing about `tets` tets, its memory mapped.
    pub fn reserve(&mut self, tets: usize) {
        use crate::mesh::reserve_mapped;
        reserve_mapped(&mut self.firsts, tets);
        reserve_mapped(&mut self.list, tets);
        reserve_mapped(&mut self.leaves, tets / LEAF_SIZE);
        reserve_mapped(&mut self.level, tets / LEAF_SIZE);
        reserve_mapped(&mut self.below, tets / LEAF_SIZE);
    }
}

struct Query<'a> {
    positions: &'a [DVec3],
    scales: &'a [f64],
    tets: &'a [Tet],
    states: StateClassifier<'a>,
    /// C's bounding box.
    cbox: Aabb,
    normal: DVec3,
    abs_normal: DVec3,
    offset: f64,
    /// The snapping tolerance (or the crack tips' reach, when larger): a vertex on the cut
    /// is within `reach × scale` of the plane, and (its projection being within that
    /// distance of C) within twice that of C's box.
    reach: f64,
    /// The contour band: vertices on the plane that far (relative to their scale) outside
    /// C are on the cut too.
    band: f64,
    /// Rounding slack of the floating-point box tests, at the scene's coordinate scale.
    slack: f64,
    /// How far from the plane a glued vertex lies at most (0: none).
    glue_reach: f64,
}

impl TetBvh {
    /// Builds the hierarchy over `tets` (median splits along the longest axis of the
    /// centroids' box). `scales[v]` is vertex `v`'s scale (see [`super::vertex_scales`]).
    ///
    /// The splits move the tets' centroids with their ids (not ids into a table of
    /// centroids, read at random on every level: 0.6 s of random reads on a million
    /// tets), on both cores below the first levels (each subtree's nodes have their place
    /// in the depth-first order in advance: a median split fixes every subtree's size);
    /// boxes and scales are then gathered from the leaves up.
    pub fn build(positions: &[DVec3], scales: &[f64], tets: &[Tet]) -> TetBvh {
        use rayon::prelude::*;
        let tet_box = |t: &Tet| Aabb::from_points(t.iter().map(|v| &positions[v.idx()]));
        let mut order: Vec<(DVec3, u32)> = tets
            .par_iter()
            .enumerate()
            .map(|(i, t)| (tet_box(t).center(), i as u32))
            .collect();
        let empty = Node {
            bbox: Aabb::EMPTY,
            max_scale: 0.0,
            link: 0,
            count: 0,
        };
        let mut nodes = vec![empty; subtree_nodes(tets.len())];
        if !tets.is_empty() {
            split(&mut order, &mut nodes, 0, 0);
        }
        // Leaves, then inner nodes from the last (children come after their parent).
        let items: Vec<TetId> = order.iter().map(|&(_, i)| TetId(i)).collect();
        nodes.par_iter_mut().filter(|n| n.count > 0).for_each(|n| {
            for &t in &items[n.items()] {
                let tet = &tets[t.idx()];
                n.bbox = n.bbox.union(&tet_box(tet));
                let s = tet.iter().map(|v| scales[v.idx()]).fold(0.0, f64::max);
                n.max_scale = n.max_scale.max(s);
            }
        });
        for i in (0..nodes.len()).rev() {
            if nodes[i].count == 0 {
                let (l, r) = (nodes[i + 1], nodes[nodes[i].link as usize]);
                nodes[i].bbox = l.bbox.union(&r.bbox);
                nodes[i].max_scale = l.max_scale.max(r.max_scale);
            }
        }
        TetBvh {
            nodes,
            items,
            next: vec![TetId::INVALID; tets.len()],
        }
    }

    /// Recomputes every box for new `positions` of the same tets (a deformed mesh: the
    /// tree's shape, built for the old positions, is kept, so queries stay correct and
    /// slow down only as far as the deformation scrambles it). Scales are kept.
    pub fn refit(&mut self, positions: &[DVec3], tets: &[Tet]) {
        let tet_box =
            |t: TetId| Aabb::from_points(tets[t.idx()].iter().map(|v| &positions[v.idx()]));
        // Nodes are stored in depth-first preorder: children after their parent.
        for i in (0..self.nodes.len()).rev() {
            let n = self.nodes[i];
            let bbox = if n.count > 0 {
                let mut b = Aabb::EMPTY;
                for k in n.items() {
                    let mut t = self.items[k];
                    while t.is_valid() {
                        b = b.union(&tet_box(t));
                        t = self.next[t.idx()];
                    }
                }
                b
            } else {
                self.nodes[i + 1]
                    .bbox
                    .union(&self.nodes[n.link as usize].bbox)
            };
            self.nodes[i].bbox = bbox;
        }
    }

    /// Makes room for tet slots up to `n` (before [`add_children`](Self::add_children)).
    pub fn reserve_tets(&mut self, n: usize) {
        if self.next.len() < n {
            self.next.resize(n, TetId::INVALID);
        }
    }

    /// Records that tet `parent` was split and its children other than the first (which
    /// took `parent`'s slot) are `extra`: they join `parent`'s leaf.
    pub fn add_children(&mut self, parent: TetId, extra: impl IntoIterator<Item = TetId>) {
        let mut prev = parent;
        let tail = self.next[parent.idx()];
        for c in extra {
            if self.next.len() <= c.idx() {
                self.next.resize(c.idx() + 1, TetId::INVALID);
            }
            self.next[prev.idx()] = c;
            prev = c;
        }
        self.next[prev.idx()] = tail;
    }

    /// The tets the cut by `polygon` may touch: those whose vertices straddle its plane or
    /// include a vertex snapped onto it, in a deterministic order (depth first; parallel
    /// over subtrees when `parallel`, with the same result), in `out` (cleared first: a
    /// caller keeps it from one query to the next).
    #[allow(clippy::too_many_arguments)]
    pub fn candidates(
        &self,
        positions: &[DVec3],
        scales: &[f64],
        tets: &[Tet],
        polygon: &CutPolygon,
        snap: Tolerance,
        options: QueryOptions<'_>,
        out: &mut Candidates,
    ) {
        let QueryOptions {
            parallel,
            cache,
            buffers,
            contour_band,
            tips,
            crack,
            glued,
        } = options;
        out.tets.clear();
        out.states.clear();
        out.tested = 0;
        if self.nodes.is_empty() {
            return;
        }
        let root = &self.nodes[0];
        let coord = root.bbox.min.abs().max(root.bbox.max.abs()).max_element();
        let mut states = StateClassifier::new(polygon, snap, &root.bbox, root.max_scale)
            .with_contour_band(contour_band);
        let mut reach = snap.relative;
        if let Some((tips, tip_reach)) = tips {
            states = states.with_crack_tips(tips, tip_reach);
            reach = reach.max(tip_reach);
        }
        if let Some(crack) = crack {
            states = states.with_crack_vertices(crack);
        }
        let mut glue_reach = 0.0;
        if let Some((glued, reach)) = glued {
            states = states.with_glued(glued, reach);
            glue_reach = reach;
        }
        let q = Query {
            positions,
            scales,
            tets,
            states,
            cbox: polygon.bbox(),
            normal: polygon.normal(),
            abs_normal: polygon.normal().abs(),
            offset: polygon.plane().offset,
            reach,
            band: contour_band,
            slack: 64.0 * f64::EPSILON * (coord + polygon.bbox().max.abs().max_element()),
            glue_reach,
        };
        cache.begin(positions.len());
        if parallel {
            self.visit_parallel(&q, 0, 0, out, cache);
        } else {
            self.visit(&q, 0, out, cache, buffers);
        }
    }

    /// Whether a node can hold a candidate: its box meets the plane and C's box, both grown
    /// by the largest snapping distance below it.
    #[inline]
    fn node_may_touch(&self, q: &Query<'_>, n: &Node) -> bool {
        let plane_margin = q.reach * n.max_scale + q.slack + q.glue_reach;
        let r = 2.0 * plane_margin + q.band * n.max_scale;
        let b = &n.bbox;
        if b.min.x > q.cbox.max.x + r
            || b.min.y > q.cbox.max.y + r
            || b.min.z > q.cbox.max.z + r
            || b.max.x < q.cbox.min.x - r
            || b.max.y < q.cbox.min.y - r
            || b.max.z < q.cbox.min.z - r
        {
            return false;
        }
        let c = (b.min + b.max) * 0.5;
        let e = (b.max - b.min) * 0.5;
        (q.normal.dot(c) - q.offset).abs() <= q.abs_normal.dot(e) + plane_margin
    }

    /// The tets of the leaves the cut may touch, in depth-first order, then their vertex
    /// states. In passes, so that a step run with cold caches waits for few misses in turn:
    /// each pass asks early for the lines the next one reads (see [`super::prefetch`]).
    /// The tree is walked one level at a time, the nodes of the next level asked for while
    /// the current one is tested (a depth-first walk would wait for every node it visits),
    /// then the leaves' tets and chain links, the chained tets, and, while classifying,
    /// the positions of the tets a few places ahead. Same tets, same order, same states as
    /// classifying leaf by leaf in a depth-first walk.
    fn visit(
        &self,
        q: &Query<'_>,
        node: u32,
        out: &mut Candidates,
        cache: &StateCache,
        buffers: &mut QueryBuffers,
    ) {
        let QueryBuffers {
            leaves,
            level,
            below,
            firsts,
            list,
        } = buffers;
        leaves.clear();
        level.clear();
        level.push(node);
        below.clear();
        while !level.is_empty() {
            for &i in level.iter() {
                let n = &self.nodes[i as usize];
                if !self.node_may_touch(q, n) {
                    continue;
                }
                if n.count > 0 {
                    prefetch(&self.items[n.link as usize]);
                    leaves.push(i);
                } else {
                    prefetch(&self.nodes[i as usize + 1]);
                    prefetch(&self.nodes[n.link as usize]);
                    below.extend([i + 1, n.link]);
                }
            }
            std::mem::swap(level, below);
            below.clear();
        }
        // Nodes are stored in depth-first preorder: by index is the depth-first order.
        leaves.sort_unstable();
        firsts.clear();
        firsts.reserve(LEAF_SIZE * leaves.len());
        for &i in leaves.iter() {
            let n = &self.nodes[i as usize];
            for &t in &self.items[n.items()] {
                prefetch(&q.tets[t.idx()]);
                prefetch(&self.next[t.idx()]);
                firsts.push(t);
            }
        }
        list.clear();
        list.reserve(2 * firsts.len());
        for &first in firsts.iter() {
            let mut t = first;
            while t.is_valid() {
                list.push(t);
                t = self.next[t.idx()];
                if t.is_valid() {
                    prefetch(&q.tets[t.idx()]);
                }
            }
        }
        let prefetch_vertices = |t: TetId| {
            for v in &q.tets[t.idx()] {
                prefetch(&q.positions[v.idx()]);
            }
        };
        list.iter()
            .take(PREFETCH_AHEAD)
            .for_each(|&t| prefetch_vertices(t));
        for (i, &t) in list.iter().enumerate() {
            if let Some(&ahead) = list.get(i + PREFETCH_AHEAD) {
                prefetch_vertices(ahead);
            }
            let tet = &q.tets[t.idx()];
            let near = |v: crate::mesh::VertexId| {
                q.states.vertex(v, q.positions[v.idx()], q.scales[v.idx()])
            };
            let states = q
                .states
                .tet_with(q.positions, tet, |v| cache.get(v, || near(v)));
            out.tested += 1;
            if is_candidate(states) {
                out.tets.push(t);
                out.states.push(states);
            }
        }
    }

    /// Parallel depth-first traversal: the two subtrees of the top levels are visited in
    /// parallel and their results concatenated left then right, as `visit` would list
    /// them.
    fn visit_parallel(
        &self,
        q: &Query<'_>,
        node: u32,
        depth: u32,
        out: &mut Candidates,
        cache: &StateCache,
    ) {
        let n = &self.nodes[node as usize];
        if !self.node_may_touch(q, n) {
            return;
        }
        if n.count > 0 || depth >= 6 {
            return self.visit(q, node, out, cache, &mut QueryBuffers::default());
        }
        let (mut a, mut b) = (Candidates::default(), Candidates::default());
        rayon::join(
            || self.visit_parallel(q, node + 1, depth + 1, &mut a, cache),
            || self.visit_parallel(q, n.link, depth + 1, &mut b, cache),
        );
        for part in [a, b] {
            out.tets.extend(part.tets);
            out.states.extend(part.states);
            out.tested += part.tested;
        }
    }
}

/// Nodes of the hierarchy over `n` tets: a leaf, or a node over two halves.
fn subtree_nodes(n: usize) -> usize {
    subtree_nodes_pair(n).0
}

/// The nodes over `n` and over `n + 1` tets: the halves of both are among `n / 2` and
/// `n / 2 + 1` tets, so one step per level (the plain recursion visits every node).
fn subtree_nodes_pair(n: usize) -> (usize, usize) {
    let small = |k: usize| usize::from(k > 0);
    if n < LEAF_SIZE {
        return (small(n), small(n + 1));
    }
    let (a, b) = subtree_nodes_pair(n / 2);
    let even = n % 2 == 0;
    let this = match (n <= LEAF_SIZE, even) {
        (true, _) => 1,
        (false, true) => 1 + 2 * a,
        (false, false) => 1 + a + b,
    };
    let next = if even { 1 + a + b } else { 1 + 2 * b };
    (this, next)
}

/// Subtrees over this many tets or more are built on both cores.
const PARALLEL_BUILD: usize = 1 << 14;

/// Builds the subtree over `order` (centroids and tet ids, left in the leaves' order)
/// into `nodes`, its slice of the depth-first node order, which starts at node `id`; its
/// leaves' items start at `first`. Leaves get their range of items, inner nodes their
/// right child (boxes come later).
fn split(order: &mut [(DVec3, u32)], nodes: &mut [Node], id: u32, first: u32) {
    let n = order.len();
    if n <= LEAF_SIZE {
        nodes[0].link = first;
        nodes[0].count = n as u32;
        return;
    }
    let mut cbox = Aabb::EMPTY;
    for &(c, _) in order.iter() {
        cbox.grow(c);
    }
    let axis = cbox.extent().max_position();
    let mid = n / 2;
    order.select_nth_unstable_by(mid, |a, b| a.0[axis].total_cmp(&b.0[axis]));
    let left_nodes = subtree_nodes(mid);
    let right_id = id + 1 + left_nodes as u32;
    nodes[0].link = right_id;
    let (left, right) = order.split_at_mut(mid);
    let (left_nodes, right_nodes) = nodes[1..].split_at_mut(left_nodes);
    let right_first = first + mid as u32;
    if n >= PARALLEL_BUILD {
        rayon::join(
            || split(left, left_nodes, id + 1, first),
            || split(right, right_nodes, right_id, right_first),
        );
    } else {
        split(left, left_nodes, id + 1, first);
        split(right, right_nodes, right_id, right_first);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn subtree_node_counts_follow_the_median_splits() {
        fn plain(n: usize) -> usize {
            match n {
                0 => 0,
                n if n <= LEAF_SIZE => 1,
                n => 1 + plain(n / 2) + plain(n - n / 2),
            }
        }
        for n in 0..5000 {
            assert_eq!(subtree_nodes(n), plain(n), "{n} tets");
        }
    }
}
