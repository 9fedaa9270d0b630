//! Separating the mesh at the vertices snapped onto the cut.
//!
//! Cut points are duplicated by the tables (one copy per side) and face points never are
//! (they are the crack tip). A vertex snapped onto the cut (`ON`) is an original vertex
//! that the cut surface passes through; after splitting, every tet around it lies on one
//! side — a tet the plane crosses at an `ON` vertex always has that vertex inside its crack
//! polygon, so the tables split it and none of its children straddles there. The vertex
//! then needs one copy per group of tets around it that are connected through faces not on
//! the cut surface; a face between a positive and a negative tet is on the cut surface
//! (its vertices can only be on the cut).
//!
//! For an interior vertex the groups are the two sides; a boundary vertex can have two
//! groups on one side (a saddle of the boundary that the plane meets twice around it),
//! which this rule also handles. The first group (positive side first, then in the order
//! the tets were listed) keeps the vertex; the others get copies, allocated in vertex
//! order.
//!
//! One configuration cannot be separated by copies: a group whose tets surround the vertex
//! without reaching around it as a disk — its link (the faces opposite the vertex) is an
//! annulus, not a disk. It happens when a boundary vertex is snapped onto a plane running
//! just above the boundary: the layer between boundary and cut thins to nothing at the
//! vertex. Such vertices are reported as *pinched*; the cut then leaves them unsnapped
//! ([`super::Cutter::cut`]).
//!
//! [`plan_vertex`] decides from the tets around the vertex after splitting (the children).
//! The plain-mesh cutter first asks [`plan_by_parents`], which decides the common cases
//! from the tets before splitting and the tables' properties (fewer tets, no children
//! listed, bit sets instead of hashing), and falls back to the children when it cannot
//! tell; in debug builds every decision is checked against the children's.

use super::stamps::Stamps;
use super::tables::{
    NB_CONFIGS, NEG, ON, POS, SIDE_NEGATIVE, SIDE_POSITIVE, Side, config_of_index, entry,
};
use crate::mesh::tables::TET_EDGES;
use crate::mesh::{Tet, TetId, VertexId};

/// A tet around an `ON` vertex: its slot, vertices and side.
#[derive(Clone, Copy, Debug)]
pub struct StarEntry {
    pub vertex: VertexId,
    pub tet: TetId,
    pub verts: Tet,
    pub side: Side,
}

/// The copies to make, and the vertices that copies cannot separate.
#[derive(Debug, Default)]
pub struct Copies {
    /// (vertex, the tets that take a new copy of it), in allocation order.
    pub groups: Vec<(VertexId, Vec<TetId>)>,
    /// Vertices with a group of tets whose link is not a disk.
    pub pinched: Vec<VertexId>,
}

fn find(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        parent[i as usize] = parent[parent[i as usize] as usize];
        i = parent[i as usize];
    }
    i
}

/// Groups the tets around each `ON` vertex and decides the copies (see the module docs).
/// `entries` lists every tet around every vertex of `on_cut` (sorted, distinct), in a
/// deterministic order; `slot(v)` is the position of `v` in `on_cut`.
pub fn plan_copies(
    on_cut: &[VertexId],
    entries: &[StarEntry],
    slot: impl Fn(VertexId) -> usize,
) -> Copies {
    // Bucket the entries by vertex (a counting sort: stable, linear).
    let mut start = vec![0usize; on_cut.len() + 1];
    for e in entries {
        start[slot(e.vertex) + 1] += 1;
    }
    for i in 0..on_cut.len() {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut sorted = entries.to_vec();
    for e in entries {
        let s = slot(e.vertex);
        sorted[fill[s]] = *e;
        fill[s] += 1;
    }
    let mut out = Copies::default();
    let mut scratch = PlanScratch::default();
    for (w, &v) in start.windows(2).zip(on_cut) {
        plan_vertex(v, &sorted[w[0]..w[1]], &mut scratch, &mut out);
    }
    out
}

/// Scratch space of the copy planning, reused from one vertex to the next.
#[derive(Clone, Default)]
pub struct PlanScratch {
    faces: FaceTable,
    verts: FaceTable,
    parent: Vec<u32>,
    shared: Vec<u32>,
    count: Vec<[i64; 3]>,
    others: Vec<[VertexId; 3]>,
}

/// The copies of one `ON` vertex `v` from the tets around it (`run`, in a deterministic
/// order), appended to `out` (see the module docs).
pub fn plan_vertex(v: VertexId, run: &[StarEntry], s: &mut PlanScratch, out: &mut Copies) {
    let has_pos = run.iter().any(|e| e.side == Side::Positive);
    let has_neg = run.iter().any(|e| e.side == Side::Negative);
    if !(has_pos && has_neg) {
        return;
    }
    let PlanScratch {
        faces,
        verts,
        parent,
        shared,
        count,
        others,
    } = s;
    let n = run.len();
    parent.clear();
    parent.extend(0..n as u32);
    faces.reset(n * 3);
    others.clear();
    shared.clear();
    // Faces (v, x, y) met twice: the link edges two tets share.
    let mut matched = 0;
    for (k, e) in run.iter().enumerate() {
        let mut o = [VertexId::INVALID; 3];
        let mut m = 0;
        for &x in &e.verts {
            if x != v && m < 3 {
                o[m] = x;
                m += 1;
            }
        }
        debug_assert_eq!(m, 3, "tet {} does not hold vertex {v}", e.tet);
        others.push(o);
        for (a, b) in [(0, 1), (0, 2), (1, 2)] {
            let (x, y) = (o[a].min(o[b]), o[a].max(o[b]));
            let key = (x.0 as u64) << 32 | y.0 as u64;
            // The other tet through face (v, x, y), if seen: same side joins groups.
            if let Some(j) = faces.insert(key, k as u32) {
                matched += 1;
                if run[j as usize].side == e.side {
                    shared.push(j);
                    union(parent, j, k as u32);
                }
            }
        }
    }
    for k in 0..n as u32 {
        let r = find(parent, k);
        parent[k as usize] = r;
    }
    let groups = (0..n).filter(|&k| parent[k] == k as u32).count();
    // An interior vertex (every face around it met twice: its link is a sphere) split
    // into exactly two groups has a single curve of cut faces around it, and two disks
    // on either side (Jordan–Schoenflies): nothing to check. Otherwise a group's link
    // is a disk (or a sphere) when its Euler characteristic V - E + F is 1 (or 2):
    // F = its tets, E = 3F minus the link edges two of them share, V = the distinct
    // vertices of its link triangles. count[root] = [F, shared edges, V].
    let interior = 2 * matched == 3 * n;
    if !(interior && groups == 2) {
        count.clear();
        count.resize(n, [0; 3]);
        for &j in shared.iter() {
            count[parent[j as usize] as usize][1] += 1;
        }
        verts.reset(n * 3);
        for (k, o) in others.iter().enumerate() {
            let root = parent[k];
            count[root as usize][0] += 1;
            for &x in o {
                if verts.insert((root as u64) << 32 | x.0 as u64, 0).is_none() {
                    count[root as usize][2] += 1;
                }
            }
        }
        let pinched = (0..n).any(|r| {
            let [f, e, vv] = count[r];
            let chi = vv - (3 * f - e) + f;
            parent[r] == r as u32 && chi != 1 && chi != 2
        });
        if pinched {
            out.pinched.push(v);
            return;
        }
    }
    // Groups in order: positive side first, then by first entry (unions keep the
    // smaller index as root, so a root is its group's first entry).
    let mut roots: Vec<(bool, u32)> = (0..n as u32)
        .filter(|&k| parent[k as usize] == k)
        .map(|k| (run[k as usize].side != Side::Positive, k))
        .collect();
    roots.sort_unstable();
    for &(_, root) in roots.iter().skip(1) {
        let members: Vec<TetId> = (0..n)
            .filter(|&k| parent[k] == root)
            .map(|k| run[k].tet)
            .collect();
        out.groups.push((v, members));
    }
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        parent[ra.max(rb) as usize] = ra.min(rb);
    }
}

/// A tet around an `ON` vertex seen whole, before its children: what the fast path of the
/// copy planning ([`plan_by_parents`]) reads.
#[derive(Clone, Copy, Debug)]
pub struct ParentAt {
    /// The tet's vertices and their states.
    pub verts: Tet,
    pub states: [u8; 4],
    /// The local index of the `ON` vertex.
    pub j: u8,
    /// The sides of its tets around the vertex, bit 0 positive, bit 1 negative: those of
    /// its children there when split, its own side when whole.
    pub sides: u8,
    /// Whether its table entry is regular at the vertex ([`entry_at_vertex`]; always true
    /// for a whole tet).
    pub regular: bool,
}

/// What [`plan_by_parents`] found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParentPlan {
    /// The tets around lie on one side: no copy.
    Keep,
    /// The tets form exactly two groups, the positive and the negative ones, each
    /// reaching around the vertex as a disk: the negative tets' children around it take a
    /// copy.
    CopyNegative,
    /// Not decided here: plan from the children ([`plan_vertex`]).
    Children,
}

/// The side bit of a state for [`ParentAt::sides`] (none for `ON`).
#[inline]
fn side_bit(state: u8) -> u8 {
    match state {
        POS => 1,
        NEG => 2,
        _ => 0,
    }
}

/// Slots of the small hash table mapping a link's vertices to their indices: twice the
/// most vertices a link may have (64), so probes stay short.
const LINK_TABLE: usize = 128;

/// Scratch of [`plan_by_parents`], kept by the cutter from one cut to the next: each link
/// vertex's index, in a small hash table of the link's own (a table per mesh vertex, read
/// at scattered places, cost a cache miss per link vertex on a million-tet mesh: the plan
/// of a vertex took twice as long there as on a 40k-tet one), and the link's edges as bit
/// sets (only the first entries, as many as the link's vertices, are used and cleared).
#[derive(Clone, Debug)]
pub struct LinkSlots {
    /// Vertex id in each slot, valid where `epoch` holds the current link's.
    keys: [u32; LINK_TABLE],
    epoch: [u32; LINK_TABLE],
    index: [u8; LINK_TABLE],
    current: u32,
    /// Link edges met once, twice, and the joins of [`plan_by_parents`].
    adj: [u64; 64],
    adj2: [u64; 64],
    join: [u64; 64],
    /// Link edges between two corners on the cut, packed (bits 8 and up: the edge's ends
    /// and the triangle's side, compared as one key; bits 0-7: the corner or tet standing
    /// for the triangle).
    in_plane: Vec<u32>,
}

impl Default for LinkSlots {
    fn default() -> Self {
        LinkSlots {
            keys: [0; LINK_TABLE],
            epoch: [0; LINK_TABLE],
            index: [0; LINK_TABLE],
            current: 0,
            adj: [0; 64],
            adj2: [0; 64],
            join: [0; 64],
            in_plane: Vec::new(),
        }
    }
}

impl LinkSlots {
    /// Starts a new link: every slot free.
    fn begin(&mut self) {
        self.current = self.current.wrapping_add(1);
        if self.current == 0 {
            self.epoch = [0; LINK_TABLE];
            self.current = 1;
        }
    }

    /// The index of `v` in this link, the next free one (counted by `m`, its bit sets
    /// cleared) if new; `None` past 64 vertices.
    #[inline]
    fn get(&mut self, v: VertexId, m: &mut usize) -> Option<usize> {
        // Fibonacci hashing; linear probing (at most 64 of the 128 slots are taken).
        let mut h = (v.0.wrapping_mul(0x9e37_79b9) >> 25) as usize;
        loop {
            if self.epoch[h] != self.current {
                if *m == 64 {
                    return None;
                }
                self.epoch[h] = self.current;
                self.keys[h] = v.0;
                self.index[h] = *m as u8;
                self.adj[*m] = 0;
                self.adj2[*m] = 0;
                *m += 1;
                return Some(self.index[h] as usize);
            }
            if self.keys[h] == v.0 {
                return Some(self.index[h] as usize);
            }
            h = (h + 1) % LINK_TABLE;
        }
    }
}

/// Whether the vertices of `set` are joined by the edges `adj` (bit sets) within `set`.
fn connected(set: u64, adj: &[u64; 64]) -> bool {
    let mut reach = set & set.wrapping_neg();
    let mut front = reach;
    while front != 0 {
        let mut next = 0;
        let mut f = front;
        while f != 0 {
            next |= adj[f.trailing_zeros() as usize];
            f &= f - 1;
        }
        front = next & set & !reach;
        reach |= front;
    }
    reach == set
}

/// The copies of an `ON` vertex decided from the tets around it (`around`; `n_vertices`
/// the mesh's vertex count), without looking at their children: the common case of a
/// vertex the cut passes through. Gives what [`plan_vertex`] gives from the children, or
/// [`ParentPlan::Children`] when it cannot tell.
///
/// Why the two agree. Each tet contributes a triangle to the vertex's link (the face
/// opposite it). A split tet's children on one side around the vertex are joined to one
/// another through faces at the vertex, their link is a disk, and each face of the tet at
/// the vertex is divided among children of exactly the sides its two other corners lie on
/// (a table entry with these properties at the vertex is *regular*: [`entry_at_vertex`],
/// checked on every entry at first use). So the children of one side around the vertex
/// form one group exactly when the link triangles with a corner on that side do, joined
/// through edges with an end on that side — that is, when the link vertices of that side
/// are joined by link edges among themselves (the triangles around such a vertex are
/// joined through its edges; two joined triangles have corners of that side in common or
/// adjacent). A face at the vertex met twice among the tets is met twice among the
/// children, so the vertex is interior in both views. The Euler characteristic of a
/// group's link, which [`plan_vertex`] counts on the children, is counted here on the
/// triangles' parts on that side (a disk each, glued along the edges they share; vertices
/// their corners on that side or on the cut and the points where link edges cross the
/// plane). Two whole tets through a face at the vertex lying in the plane (a link edge
/// between two corners on the cut) are joined when on one side, as their children are.
/// Links with a tet lying in the plane (three corners on the cut), an irregular entry,
/// more than 64 vertices or an edge in three triangles are left to the children.
pub fn plan_by_parents(around: &[ParentAt], links: &mut LinkSlots) -> ParentPlan {
    let sides = around.iter().fold(0, |m, a| m | a.sides);
    if sides != 3 {
        return ParentPlan::Keep;
    }
    if around.iter().any(|a| !a.regular) {
        return ParentPlan::Children;
    }
    links.begin();
    let mut m = 0usize;
    let (mut pos, mut neg) = (0u64, 0u64);
    // Link edges, and those met twice.
    let (mut edges, mut twice) = (0i64, 0i64);
    // Per side: triangles, their corners on that side or on the cut, the number of
    // vertices of their parts on that side summed over triangles, and crossed edges.
    let (mut f, mut corners, mut k, mut crossed) = ([0i64; 2], [0u64; 2], [0i64; 2], [0i64; 2]);
    // Link edges between two corners on the cut (faces at the vertex lying in the plane,
    // between whole tets): (ends, the third corner, the side).
    links.in_plane.clear();
    // Tets lying in the plane (a link triangle with its three corners on the cut, whole,
    // on the side of its centroid) stand for themselves in the connectivity below, as
    // extra link vertices: `virt` of them.
    let mut virt = 0usize;
    for a in around {
        let o = OTHERS[a.j as usize];
        let mut c = [0usize; 3];
        let (mut bits, mut counts) = ([0u64; 3], [0i64; 3]);
        for i in 0..3 {
            match links.get(a.verts[o[i]], &mut m) {
                Some(x) => c[i] = x,
                None => return ParentPlan::Children,
            }
            // Index 0 positive, 1 negative, 2 on the cut.
            let s = match a.states[o[i]] {
                POS => 0,
                NEG => 1,
                _ => 2,
            };
            bits[s] |= 1 << c[i];
            counts[s] += 1;
        }
        if counts[2] == 3 {
            if m == 64 || a.sides == 3 {
                return ParentPlan::Children;
            }
            links.adj[m] = 0;
            links.adj2[m] = 0;
            bits[a.sides as usize - 1] = 1 << m;
            m += 1;
            virt += 1;
        } else if u8::from(bits[0] != 0) | u8::from(bits[1] != 0) << 1 != a.sides {
            return ParentPlan::Children;
        }
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            let (x, y) = (c[i], c[j]);
            if links.adj2[x] & 1 << y != 0 {
                return ParentPlan::Children;
            }
            if links.adj[x] & 1 << y != 0 {
                links.adj2[x] |= 1 << y;
                links.adj2[y] |= 1 << x;
                twice += 1;
            } else {
                links.adj[x] |= 1 << y;
                links.adj[y] |= 1 << x;
                edges += 1;
            }
        }
        if counts[2] >= 2 {
            // Its edges between two corners on the cut, with the corner (or the tet) standing
            // for it.
            let x = (bits[0] | bits[1]).trailing_zeros() as usize;
            for (i, j) in [(0, 1), (0, 2), (1, 2)] {
                if bits[2] & 1 << c[i] != 0 && bits[2] & 1 << c[j] != 0 {
                    let (lo, hi) = (c[i].min(c[j]) as u32, c[i].max(c[j]) as u32);
                    let key = (lo << 6 | hi) << 2 | u32::from(a.sides);
                    links.in_plane.push(key << 8 | x as u32);
                }
            }
        }
        pos |= bits[0];
        neg |= bits[1];
        let cross = counts[0] * counts[1];
        for side in 0..2 {
            if bits[side] != 0 {
                f[side] += 1;
                // (A tet in the plane has only its corners on the cut.)
                corners[side] |= if counts[2] == 3 {
                    bits[2]
                } else {
                    bits[side] | bits[2]
                };
                k[side] += counts[side] + counts[2] + cross;
                crossed[side] += cross;
            }
        }
    }
    // Two whole tets of one side through a face in the plane are joined: their third
    // corners are, for the connectivity below, and the edge is glued.
    links.join[..m].copy_from_slice(&links.adj[..m]);
    let mut glued_in_plane = [0i64; 2];
    let in_plane = &links.in_plane;
    for (i, &e) in in_plane.iter().enumerate() {
        let (x, side) = ((e & 0xff) as usize, (e >> 8) & 3);
        for &f in &in_plane[i + 1..] {
            if e >> 8 == f >> 8 {
                let w = (f & 0xff) as usize;
                links.join[x] |= 1 << w;
                links.join[w] |= 1 << x;
                glued_in_plane[side as usize - 1] += 1;
            }
        }
    }
    let n = around.len() as i64;
    let interior = edges == twice;
    // The whole link: a sphere around an interior vertex, a disk around a boundary one.
    let chi = (m - virt) as i64 - edges + n;
    if chi != if interior { 2 } else { 1 }
        || !connected(pos, &links.join)
        || !connected(neg, &links.join)
    {
        return ParentPlan::Children;
    }
    if interior {
        return ParentPlan::CopyNegative;
    }
    let adj2 = &links.adj2;
    let sum_over = |set: u64, f: &dyn Fn(usize) -> u32| -> i64 {
        let mut s = 0;
        let mut b = set;
        while b != 0 {
            s += i64::from(f(b.trailing_zeros() as usize));
            b &= b - 1;
        }
        s
    };
    // Link edges met twice with a crossing point (one end on each side).
    let crossed_twice = sum_over(pos, &|i| (adj2[i] & neg).count_ones());
    for (side, set) in [(0, pos), (1, neg)] {
        // Gluings: edges met twice with an end on this side.
        let glued = sum_over(set, &|i| (adj2[i] & set).count_ones()) / 2
            + sum_over(set, &|i| (adj2[i] & !set).count_ones())
            + glued_in_plane[side];
        let v = i64::from(corners[side].count_ones()) + crossed[side] - crossed_twice;
        let chi = v - (k[side] - glued) + f[side];
        if chi != 1 && chi != 2 {
            return ParentPlan::Children;
        }
    }
    ParentPlan::CopyNegative
}

/// The three local vertices of a tet other than each one.
const OTHERS: [[usize; 3]; 4] = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];

/// What a table entry is at each of its canonical vertices on the cut
/// ([`entry_at_vertex`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AtVertex {
    /// Bit `i`: the entry is regular at canonical vertex `i` (see [`plan_by_parents`]).
    pub regular: u8,
    /// Bits `2i`, `2i + 1`: the sides (positive, negative) of the children at vertex `i`.
    pub sides: u8,
    /// Per canonical vertex, the children on the negative side holding it (bit `c` for
    /// the entry's `c`-th tet): those taking its copy when the negative side is copied.
    pub negative: [u16; 4],
}

/// What the entry of table configuration `config` (a [`super::split::Children::config`])
/// is at each canonical vertex on the cut. Computed from the tables the first time a
/// configuration is asked for (a cut meets a few dozen of the thousands).
pub fn entry_at_vertex(config: u16) -> AtVertex {
    use std::sync::OnceLock;
    static TABLE: OnceLock<Box<[OnceLock<AtVertex>]>> = OnceLock::new();
    let table = TABLE.get_or_init(|| (0..NB_CONFIGS).map(|_| OnceLock::new()).collect());
    match table.get(config as usize) {
        Some(slot) => *slot.get_or_init(|| regularity(config as usize)),
        None => AtVertex::default(),
    }
}

/// [`entry_at_vertex`] of one configuration.
fn regularity(config: usize) -> AtVertex {
    let (states, _) = config_of_index(config);
    let (locals, codes) = entry(config);
    let mut out = AtVertex::default();
    // Whether local point `p` lies on the parent's face `f` (the one opposite vertex f).
    let on_face = |p: u8, f: usize| -> bool {
        let p = p as usize;
        match p {
            0..4 => p != f,
            4..16 => {
                let [a, b] = TET_EDGES[(p - 4) / 2];
                a != f && b != f
            }
            _ => p - 16 == f,
        }
    };
    for i in 0..4 {
        if states[i] != ON || locals.is_empty() {
            continue;
        }
        let at: Vec<usize> = (0..locals.len())
            .filter(|&c| locals[c].contains(&(i as u8)))
            .collect();
        let bit_of = |c: usize| match codes[c] {
            SIDE_POSITIVE => 1u8,
            SIDE_NEGATIVE => 2,
            _ => 4,
        };
        let mask = at.iter().fold(0, |m, &c| m | bit_of(c));
        out.sides |= (mask & 3) << (2 * i);
        out.negative[i] = at
            .iter()
            .filter(|&&c| codes[c] == SIDE_NEGATIVE)
            .fold(0, |m, &c| m | 1 << c);
        let mut ok = mask & 4 == 0;
        // One group per side through faces at the vertex (two children sharing three
        // points share a face).
        let mut parent: Vec<u32> = (0..at.len() as u32).collect();
        for x in 0..at.len() {
            for y in x + 1..at.len() {
                let (a, b) = (&locals[at[x]], &locals[at[y]]);
                let common = a.iter().filter(|p| b.contains(p)).count();
                if common == 3 && codes[at[x]] == codes[at[y]] {
                    union(&mut parent, x as u32, y as u32);
                }
            }
        }
        let groups = (0..at.len() as u32)
            .filter(|&x| find(&mut parent, x) == x)
            .count();
        ok &= groups == (mask & 3).count_ones() as usize;
        // The sides there are those of the other corners.
        ok &= mask & 3
            == (0..4)
                .filter(|&x| x != i)
                .fold(0, |m, x| m | side_bit(states[x]));
        // Each side's link at the vertex (the children's faces opposite it) is a disk.
        for side in [1u8, 2] {
            let tris: Vec<Vec<u8>> = at
                .iter()
                .filter(|&&c| bit_of(c) == side)
                .map(|&c| {
                    locals[c]
                        .iter()
                        .copied()
                        .filter(|&p| p != i as u8)
                        .collect()
                })
                .collect();
            if tris.is_empty() {
                continue;
            }
            let mut points: Vec<u8> = tris.iter().flatten().copied().collect();
            points.sort_unstable();
            points.dedup();
            let mut edges: Vec<(u8, u8)> = tris
                .iter()
                .flat_map(|t| [(t[0], t[1]), (t[0], t[2]), (t[1], t[2])])
                .map(|(a, b)| (a.min(b), a.max(b)))
                .collect();
            edges.sort_unstable();
            edges.dedup();
            ok &= points.len() as i64 - edges.len() as i64 + tris.len() as i64 == 1;
        }
        // Each face at the vertex divided among children of its corners' sides.
        for f in (0..4).filter(|&f| f != i) {
            let expected = (0..4)
                .filter(|&x| x != i && x != f)
                .fold(0, |m, x| m | side_bit(states[x]));
            let mut found = 0u8;
            for &c in &at {
                let l = &locals[c];
                for drop in 0..4 {
                    let face: Vec<u8> = (0..4).filter(|&k| k != drop).map(|k| l[k]).collect();
                    if face.contains(&(i as u8)) && face.iter().all(|&p| on_face(p, f)) {
                        found |= bit_of(c);
                    }
                }
            }
            ok &= expected != 0 && found == expected;
        }
        if ok {
            out.regular |= 1 << i;
        }
    }
    out
}

/// A small open-addressing table from a key (a face, a vertex of a group) to the first
/// value stored with it, reused for every vertex (a star has a few dozen tets: sorting them
/// would cost more). Entries are stamped with a generation, so clearing is free.
#[derive(Clone, Default)]
struct FaceTable {
    keys: Vec<u64>,
    values: Vec<u32>,
    stamps: Stamps,
    mask: usize,
}

impl FaceTable {
    fn reset(&mut self, n: usize) {
        let size = (2 * n).next_power_of_two().max(16);
        if size > self.keys.len() {
            self.keys.resize(size, 0);
            self.values.resize(size, 0);
            self.stamps.resize(size);
        }
        self.stamps.begin();
        self.mask = size - 1;
    }

    /// Inserts `key -> value`, or returns the value already there.
    #[inline]
    fn insert(&mut self, key: u64, value: u32) -> Option<u32> {
        let mut i = (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 40) as usize & self.mask;
        loop {
            if self.stamps.mark(i) {
                self.keys[i] = key;
                self.values[i] = value;
                return None;
            }
            if self.keys[i] == key {
                return Some(self.values[i]);
            }
            i = (i + 1) & self.mask;
        }
    }
}

impl Copies {
    /// The copies of consecutive runs of vertices, planned apart, as one plan.
    pub fn concat(parts: Vec<Copies>) -> Copies {
        let mut all = Copies::default();
        for part in parts {
            all.groups.extend(part.groups);
            all.pinched.extend(part.pinched);
        }
        all
    }

    /// These copies with the plans of the vertices in `redone` (sorted) replaced by
    /// `update`'s, still in vertex order.
    pub fn merge(self, redone: &[VertexId], update: Copies) -> Copies {
        let keep = |v: &VertexId| redone.binary_search(v).is_err();
        let mut groups: Vec<(VertexId, Vec<TetId>)> = self
            .groups
            .into_iter()
            .filter(|(v, _)| keep(v))
            .chain(update.groups)
            .collect();
        groups.sort_by_key(|(v, _)| *v);
        let mut pinched: Vec<VertexId> = self
            .pinched
            .into_iter()
            .filter(|v| keep(v))
            .chain(update.pinched)
            .collect();
        pinched.sort_unstable();
        Copies { groups, pinched }
    }
}
