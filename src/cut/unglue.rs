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

use super::tables::Side;
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
    let mut faces = FaceTable::default();
    let mut verts = FaceTable::default();
    let mut parent: Vec<u32> = Vec::new();
    let mut shared: Vec<u32> = Vec::new();
    let mut count: Vec<[i64; 3]> = Vec::new();
    let mut others: Vec<[VertexId; 3]> = Vec::new();
    for (w, &v) in start.windows(2).zip(on_cut) {
        let run = &sorted[w[0]..w[1]];
        let has_pos = run.iter().any(|e| e.side == Side::Positive);
        let has_neg = run.iter().any(|e| e.side == Side::Negative);
        if !(has_pos && has_neg) {
            continue;
        }
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
                        let (ri, rj) = (find(&mut parent, j), find(&mut parent, k as u32));
                        if ri != rj {
                            parent[ri.max(rj) as usize] = ri.min(rj);
                        }
                    }
                }
            }
        }
        for k in 0..n as u32 {
            let r = find(&mut parent, k);
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
            for &j in &shared {
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
                continue;
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
    out
}

/// A small open-addressing table from a key (a face, a vertex of a group) to the first
/// value stored with it, reused for every vertex (a star has a few dozen tets: sorting them
/// would cost more). Entries are stamped with a generation, so clearing is free.
#[derive(Default)]
struct FaceTable {
    keys: Vec<u64>,
    values: Vec<u32>,
    stamps: Vec<u32>,
    generation: u32,
    mask: usize,
}

impl FaceTable {
    fn reset(&mut self, n: usize) {
        let size = (2 * n).next_power_of_two().max(16);
        if size > self.keys.len() {
            self.keys.resize(size, 0);
            self.values.resize(size, 0);
            self.stamps.clear();
            self.stamps.resize(size, 0);
            self.generation = 0;
        }
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.stamps.iter_mut().for_each(|s| *s = 0);
            self.generation = 1;
        }
        self.mask = size - 1;
    }

    /// Inserts `key -> value`, or returns the value already there.
    #[inline]
    fn insert(&mut self, key: u64, value: u32) -> Option<u32> {
        let mut i = (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 40) as usize & self.mask;
        loop {
            if self.stamps[i] != self.generation {
                self.stamps[i] = self.generation;
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
