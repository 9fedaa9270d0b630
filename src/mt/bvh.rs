//! A bounding-volume hierarchy over boxes: the spatial index of the MT layer.
//!
//! One structure serves two queries: the build asks "how far is this point from the
//! original boundary surface" (boxes of boundary triangles), and extraction asks "which
//! fragments does this focus region touch" (boxes of fragments, [`FragmentBvh`]). The cut
//! layer's step 1 (find every tet a polygon crosses, paper §3) is the same query over
//! fragments then their tets.
//!
//! Built top-down by median split of the box centres along the longest axis; leaves hold up
//! to four items. Nodes are stored depth-first, the left child right after its
//! parent, so a traversal walks memory mostly forwards.

use super::{BoxFrame, FragmentKind, Mt, QuantBox};
use crate::geom::{Aabb, DVec3};
use crate::mesh::FragmentId;

/// Items per leaf.
const LEAF_SIZE: usize = 4;

#[derive(Clone, Debug, PartialEq)]
struct Node {
    bbox: Aabb,
    /// Leaf: first item in `items`. Inner node: index of the right child (the left child
    /// is the next node).
    first: u32,
    /// Items in the leaf; 0 for an inner node.
    count: u32,
}

/// A BVH over a list of boxes; queries report item indices into that list.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bvh {
    nodes: Vec<Node>,
    items: Vec<u32>,
}

impl Bvh {
    /// The hierarchy of `boxes` (empty boxes are never reported by queries).
    pub fn new(boxes: &[Aabb]) -> Bvh {
        let mut items: Vec<u32> = (0..boxes.len() as u32)
            .filter(|&i| !boxes[i as usize].is_empty())
            .collect();
        let mut nodes = Vec::with_capacity(2 * items.len() / LEAF_SIZE + 1);
        if !items.is_empty() {
            let n = items.len();
            build(boxes, &mut items, 0, n, &mut nodes);
        }
        Bvh { nodes, items }
    }

    /// Calls `on_item` for every item in a leaf reached by descending only into nodes whose
    /// box satisfies `descend`.
    pub fn query(&self, descend: impl FnMut(&Aabb) -> bool, mut on_item: impl FnMut(u32)) {
        self.walk(descend, |range| {
            for &item in &self.items[range] {
                on_item(item);
            }
        });
    }

    /// [`Bvh::query`] by leaves: `on_leaf` gets the leaf's range of positions in `items`.
    fn walk(
        &self,
        mut descend: impl FnMut(&Aabb) -> bool,
        mut on_leaf: impl FnMut(std::ops::Range<usize>),
    ) {
        if self.nodes.is_empty() {
            return;
        }
        // Depth-first with both children pushed: at most one pending node per level, and
        // the median split bounds the depth by log2 of the item count.
        let mut stack = [0u32; 96];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let i = stack[top];
            let node = &self.nodes[i as usize];
            if !descend(&node.bbox) {
                continue;
            }
            if node.count > 0 {
                let s = node.first as usize;
                on_leaf(s..s + node.count as usize);
            } else {
                stack[top] = node.first;
                stack[top + 1] = i + 1;
                top += 2;
            }
        }
    }

    /// Nearest-first search: visits the leaves whose `lower_bound` (a lower bound of the
    /// distance to anything in a box) is at most `limit()` (which `on_item` may shrink),
    /// the nearer child of each node first.
    pub fn query_nearest(
        &self,
        mut lower_bound: impl FnMut(&Aabb) -> f64,
        mut limit: impl FnMut() -> f64,
        mut on_item: impl FnMut(u32),
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = [(0u32, 0.0f64); 96];
        let mut top = 1;
        stack[0] = (0, lower_bound(&self.nodes[0].bbox));
        while top > 0 {
            top -= 1;
            let (i, d) = stack[top];
            if d > limit() {
                continue;
            }
            let node = &self.nodes[i as usize];
            if node.count > 0 {
                let s = node.first as usize;
                for &item in &self.items[s..s + node.count as usize] {
                    on_item(item);
                }
            } else {
                let (l, r) = (i + 1, node.first);
                let (dl, dr) = (
                    lower_bound(&self.nodes[l as usize].bbox),
                    lower_bound(&self.nodes[r as usize].bbox),
                );
                // Push the farther child first so the nearer one is visited next.
                let (near, far) = if dl <= dr {
                    ((l, dl), (r, dr))
                } else {
                    ((r, dr), (l, dl))
                };
                stack[top] = far;
                stack[top + 1] = near;
                top += 2;
            }
        }
    }

    pub fn heap_bytes(&self) -> usize {
        self.nodes.capacity() * std::mem::size_of::<Node>() + self.items.capacity() * 4
    }
}

fn build(boxes: &[Aabb], items: &mut [u32], lo: usize, hi: usize, nodes: &mut Vec<Node>) {
    let mut bbox = Aabb::EMPTY;
    let mut centres = Aabb::EMPTY;
    for &i in &items[lo..hi] {
        let b = &boxes[i as usize];
        bbox = bbox.union(b);
        centres.grow(b.center());
    }
    let me = nodes.len();
    nodes.push(Node {
        bbox,
        first: lo as u32,
        count: (hi - lo) as u32,
    });
    if hi - lo <= LEAF_SIZE {
        return;
    }
    let e = centres.extent();
    let axis = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let mid = (lo + hi) / 2;
    items[lo..hi].select_nth_unstable_by(mid - lo, |&a, &b| {
        boxes[a as usize].center()[axis].total_cmp(&boxes[b as usize].center()[axis])
    });
    build(boxes, items, lo, mid, nodes);
    let right = nodes.len() as u32;
    build(boxes, items, mid, hi, nodes);
    nodes[me].first = right;
    nodes[me].count = 0;
}

/// A region of interest: where an extraction uses its focus threshold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Region {
    Sphere { center: DVec3, radius: f64 },
    Box(Aabb),
}

impl Region {
    /// Whether the region and the box share a point (closed sets).
    pub fn intersects(&self, b: &Aabb) -> bool {
        match self {
            Region::Sphere { center, radius } => {
                let q = center.clamp(b.min, b.max);
                (q - *center).length_squared() <= radius * radius
            }
            Region::Box(r) => r.intersects(b),
        }
    }

    /// Whether the whole box lies in the (closed) region.
    pub fn contains_box(&self, b: &Aabb) -> bool {
        match self {
            Region::Sphere { center, radius } => {
                // The corner farthest from the centre decides.
                let far = (*center - b.min).abs().max((b.max - *center).abs());
                far.length_squared() <= radius * radius
            }
            Region::Box(r) => r.contains(b.min) && r.contains(b.max),
        }
    }

    /// Whether `p` lies in the (closed) region.
    pub fn contains(&self, p: DVec3) -> bool {
        match self {
            Region::Sphere { center, radius } => (p - *center).length_squared() <= radius * radius,
            Region::Box(r) => r.contains(p),
        }
    }

    /// The region's bounding box.
    pub fn bbox(&self) -> Aabb {
        match self {
            Region::Sphere { center, radius } => Aabb {
                min: *center - DVec3::splat(*radius),
                max: *center + DVec3::splat(*radius),
            },
            Region::Box(b) => *b,
        }
    }
}

/// A BVH over the bounding boxes of an MT's fragments (roots and drains left out: they
/// span everything and are decided by their kind, not by position).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FragmentBvh {
    bvh: Bvh,
    /// Box and error of each item, in the hierarchy's item order: a walk reads them with
    /// the leaf instead of from fragment rows scattered over the MT (which, cold after an
    /// extraction, cost a cache miss each).
    entries: Vec<(QuantBox, f64)>,
    /// The MT's frame, to expand the boxes exactly as [`Mt::fragment_bbox`] does.
    frame: BoxFrame,
}

/// A fragment a [`FragmentBvh`] walk reached.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FragmentHit {
    pub fragment: FragmentId,
    /// The fragment's box, as [`Mt::fragment_bbox`] gives it.
    pub bbox: Aabb,
    /// The fragment's error, as [`Mt::fragment_error`] gives it.
    pub error: f64,
}

impl FragmentBvh {
    pub fn new(mt: &Mt) -> FragmentBvh {
        let boxes: Vec<Aabb> = (0..mt.nb_fragments())
            .map(|f| {
                let f = FragmentId::from_usize(f);
                match mt.fragment_kind(f) {
                    FragmentKind::Collapse => mt.fragment_bbox(f),
                    FragmentKind::Root | FragmentKind::Drain => Aabb::EMPTY,
                }
            })
            .collect();
        let bvh = Bvh::new(&boxes);
        let entries = bvh
            .items
            .iter()
            .map(|&i| (mt.bbox[i as usize], mt.error[i as usize]))
            .collect();
        FragmentBvh {
            bvh,
            entries,
            frame: mt.frame,
        }
    }

    /// Calls `on_hit` for every fragment in a leaf reached by descending only into nodes
    /// whose box satisfies `descend` (see [`Bvh::query`]).
    pub fn query(&self, descend: impl FnMut(&Aabb) -> bool, mut on_hit: impl FnMut(FragmentHit)) {
        self.bvh.walk(descend, |range| {
            for k in range {
                let (bbox, error) = self.entries[k];
                on_hit(FragmentHit {
                    fragment: FragmentId(self.bvh.items[k]),
                    bbox: self.frame.expand(bbox),
                    error,
                });
            }
        });
    }

    /// Calls `f` for every fragment of `mt` (the MT this hierarchy was built from) whose
    /// box meets `region`.
    pub fn for_each_in(&self, mt: &Mt, region: &Region, mut f: impl FnMut(FragmentId)) {
        let rb = region.bbox();
        self.bvh.query(
            |b| b.intersects(&rb) && region.intersects(b),
            |i| {
                let frag = FragmentId(i);
                if region.intersects(&mt.fragment_bbox(frag)) {
                    f(frag)
                }
            },
        );
    }

    pub fn heap_bytes(&self) -> usize {
        self.bvh.heap_bytes() + self.entries.capacity() * std::mem::size_of::<(QuantBox, f64)>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn query_finds_exactly_the_intersecting_boxes() {
        let boxes: Vec<Aabb> = (0..100)
            .map(|i| {
                let p = DVec3::new((i % 10) as f64, (i / 10) as f64, 0.0);
                Aabb {
                    min: p,
                    max: p + DVec3::splat(0.5),
                }
            })
            .collect();
        let bvh = Bvh::new(&boxes);
        let region = Region::Sphere {
            center: DVec3::new(4.2, 4.2, 0.0),
            radius: 1.1,
        };
        let mut found = Vec::new();
        bvh.query(
            |b| region.intersects(b),
            |i| {
                if region.intersects(&boxes[i as usize]) {
                    found.push(i)
                }
            },
        );
        found.sort();
        let expect: Vec<u32> = (0..100)
            .filter(|&i| region.intersects(&boxes[i as usize]))
            .collect();
        assert_eq!(found, expect);
        assert!(expect.len() >= 4);
    }

    #[test]
    fn contains_box_agrees_with_the_corners() {
        let b = Aabb {
            min: DVec3::new(0.0, 0.0, 0.0),
            max: DVec3::new(1.0, 2.0, 3.0),
        };
        let corners: Vec<DVec3> = (0..8)
            .map(|k| {
                DVec3::select(
                    glam::BVec3::new(k & 1 != 0, k & 2 != 0, k & 4 != 0),
                    b.max,
                    b.min,
                )
            })
            .collect();
        for (center, radius) in [
            (DVec3::new(0.5, 1.0, 1.5), 1.9),
            (DVec3::new(0.5, 1.0, 1.5), 1.8),
            (DVec3::new(3.0, -1.0, 0.0), 4.0),
            (DVec3::new(3.0, -1.0, 0.0), 6.0),
        ] {
            let s = Region::Sphere { center, radius };
            assert_eq!(s.contains_box(&b), corners.iter().all(|&c| s.contains(c)));
        }
        let inside = Region::Box(Aabb {
            min: DVec3::splat(-1.0),
            max: DVec3::splat(3.0),
        });
        let across = Region::Box(Aabb {
            min: DVec3::splat(0.5),
            max: DVec3::splat(4.0),
        });
        assert!(inside.contains_box(&b));
        assert!(!across.contains_box(&b));
    }
}
