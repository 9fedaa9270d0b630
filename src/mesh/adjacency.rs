//! Face adjacency and vertex stars.
//!
//! Faces are matched at their smallest vertex: bucketed by it (a counting sort, linear),
//! then sorted within each small bucket. Vertex ranges are matched by parallel tasks that
//! share nothing; every task reads the tets sequentially, because on large meshes random
//! access to tets, not comparisons, is the cost.

use super::tables::TET_FACES;
use super::{Tet, TetId, TetMesh, VertexId};
use rayon::prelude::*;

/// Tets around each vertex, in CSR form.
#[derive(Clone, Debug, Default)]
pub struct VertexStars {
    offsets: Vec<u32>,
    tets: Vec<TetId>,
}

impl VertexStars {
    /// Stars of `n_vertices` vertices in `tets` (indices must be in range).
    pub fn new(n_vertices: usize, tets: &[Tet]) -> VertexStars {
        let mut offsets = vec![0u32; n_vertices + 1];
        for t in tets {
            for v in t {
                offsets[v.idx() + 1] += 1;
            }
        }
        for i in 0..n_vertices {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut out = vec![TetId::INVALID; tets.len() * 4];
        for (i, t) in tets.iter().enumerate() {
            for v in t {
                let slot = &mut fill[v.idx()];
                out[*slot as usize] = TetId::from_usize(i);
                *slot += 1;
            }
        }
        VertexStars { offsets, tets: out }
    }

    /// The tets incident to `v`, in increasing id order.
    #[inline]
    pub fn star(&self, v: VertexId) -> &[TetId] {
        let (a, b) = (self.offsets[v.idx()], self.offsets[v.idx() + 1]);
        &self.tets[a as usize..b as usize]
    }
}

/// A boundary triangle: face `face` (0..4, opposite local vertex `face`) of tet `tet`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BoundaryFace {
    pub tet: TetId,
    pub face: u8,
}

/// For each tet and each of its four faces, the tet across that face (or
/// [`TetId::INVALID`] on the boundary), plus the faces that break the "at most two tets,
/// opposite orientations" rule, found on the way.
#[derive(Clone, Debug, Default)]
pub struct FaceAdjacency {
    /// `neighbors[t][f]`: the tet sharing face `f` of tet `t`.
    pub neighbors: Vec<[TetId; 4]>,
    /// Faces owned by more than two tets: (tet, face, number of owners).
    pub overshared: Vec<(TetId, u8, usize)>,
    /// Faces shared by two tets with the same orientation (tets overlapping): (tet, face,
    /// other tet), listed once per pair.
    pub same_orientation: Vec<(TetId, u8, TetId)>,
}

/// Vertices of face `f` of tet `t`, outward-oriented.
#[inline]
pub fn face_vertices(t: &Tet, f: usize) -> [VertexId; 3] {
    TET_FACES[f].map(|i| t[i])
}

/// Whether the face `(x, y, z)` (as a tet orients it) is an even permutation of its
/// vertices in increasing order: two tets sharing a face with opposite orientations (the
/// valid case) see it with opposite parities.
#[inline]
fn even_parity([x, y, z]: [VertexId; 3]) -> bool {
    if x < y && x < z {
        y < z
    } else if y < z {
        z < x
    } else {
        x < y
    }
}

/// The faces of a tet soup matched with one another: the boundary, the faces breaking the
/// "at most two tets, opposite orientations" rule, and (on request) each tet's neighbours.
#[derive(Clone, Debug, Default)]
pub(crate) struct FaceMatching {
    /// Faces with a single owner, in (tet, face) order.
    pub boundary: Vec<BoundaryFace>,
    /// As [`FaceAdjacency::overshared`].
    pub overshared: Vec<(TetId, u8, usize)>,
    /// As [`FaceAdjacency::same_orientation`].
    pub same_orientation: Vec<(TetId, u8, TetId)>,
    /// For each owner of a shared face, the other owner with the smallest id: (tet, face,
    /// other). Filled only when asked for.
    pub links: Vec<(TetId, u8, TetId)>,
}

/// Below this many tets the matching runs on one thread.
const PARALLEL_MIN_TETS: usize = 1 << 15;

/// Faces per partition: a partition's faces and its hash table stay in a core's L2 cache.
const PARTITION_FACES: usize = 1 << 13;

/// A face as matched: `(b << 32 | c, a_local << 35 | tet << 3 | face << 1 | parity)` where
/// `a < b < c` are its vertices, `a_local` is `a` minus the first vertex of its partition
/// (below 2^29, as there are at least 8 partitions of at most 2^32 vertices), and
/// `parity` is whether the tet orients it as an even permutation of `(a, b, c)`.
type Entry = (u64, u64);

#[inline]
fn entry_tet(e: u64) -> TetId {
    TetId((e >> 3) as u32)
}

#[inline]
fn entry_face(e: u64) -> u8 {
    ((e >> 1) & 3) as u8
}

/// Calls `emit(smallest vertex, face)` for the four faces of `t`: the three faces around
/// its smallest vertex have that vertex as smallest, the face opposite it the second
/// smallest.
#[inline]
fn for_each_face(t: &Tet, mut emit: impl FnMut(VertexId, usize)) {
    let mut at = 0;
    for k in 1..4 {
        if t[k] < t[at] {
            at = k;
        }
    }
    let mut second = VertexId::INVALID;
    for k in (0..4).filter(|&k| k != at) {
        second = second.min(t[k]);
        emit(t[at], k);
    }
    emit(second, at);
}

/// Matches the faces of `tets` (indices below `n_vertices`).
///
/// A radix partition of the faces by their smallest vertex (sequential writes into one
/// stream per partition, in parallel over ranges of tets), then, in parallel over
/// partitions, a hash table per partition pairs the faces; both fit in cache. Random
/// access to a large array, not comparisons, is what costs on a million tets, and this
/// makes none. A partition where a face has more than two owners (an invalid mesh) is
/// sorted instead, which reports every owner.
pub(crate) fn match_faces(n_vertices: usize, tets: &[Tet], want_links: bool) -> FaceMatching {
    let n_faces = 4 * tets.len();
    let parts = n_faces.div_ceil(PARTITION_FACES).clamp(8, 1 << 16);
    let span = n_vertices.div_ceil(parts).max(1);
    let threads = if tets.len() < PARALLEL_MIN_TETS {
        1
    } else {
        rayon::current_num_threads().max(1)
    };
    let chunk = tets.len().div_ceil(threads).max(1);
    let tet_chunks: Vec<&[Tet]> = tets.chunks(chunk).collect();
    let counts: Vec<Vec<usize>> = tet_chunks
        .par_iter()
        .map(|c| {
            let mut count = vec![0usize; parts];
            for t in *c {
                for_each_face(t, |a, _| count[a.idx() / span] += 1);
            }
            count
        })
        .collect();

    // One array, partition-major then chunk: each chunk writes its own slices of it.
    let mut entries: Vec<Entry> = vec![(0, 0); n_faces];
    let mut per_chunk: Vec<Vec<&mut [Entry]>> =
        counts.iter().map(|_| Vec::with_capacity(parts)).collect();
    let mut partitions: Vec<usize> = Vec::with_capacity(parts);
    {
        let mut rest: &mut [Entry] = &mut entries;
        for p in 0..parts {
            partitions.push(counts.iter().map(|c| c[p]).sum());
            for (k, c) in counts.iter().enumerate() {
                let (head, tail) = std::mem::take(&mut rest).split_at_mut(c[p]);
                per_chunk[k].push(head);
                rest = tail;
            }
        }
        tet_chunks
            .par_iter()
            .zip(per_chunk.into_par_iter())
            .enumerate()
            .for_each(|(k, (c, mut slices))| {
                let mut cursor = vec![0usize; parts];
                for (i, t) in c.iter().enumerate() {
                    let tet = (k * chunk + i) as u64;
                    for_each_face(t, |a, f| {
                        let fv = face_vertices(t, f);
                        // Sorted, the face is (a, b, c): `a` is its smallest vertex.
                        let [_, b, c] = {
                            let mut s = fv;
                            s.sort_unstable();
                            s
                        };
                        let p = a.idx() / span;
                        let local = (a.idx() - p * span) as u64;
                        slices[p][cursor[p]] = (
                            (b.0 as u64) << 32 | c.0 as u64,
                            local << 35 | tet << 3 | (f as u64) << 1 | even_parity(fv) as u64,
                        );
                        cursor[p] += 1;
                    });
                }
            });
    }

    let mut slices: Vec<&mut [Entry]> = Vec::with_capacity(parts);
    let mut rest: &mut [Entry] = &mut entries;
    for &len in &partitions {
        let (head, tail) = std::mem::take(&mut rest).split_at_mut(len);
        slices.push(head);
        rest = tail;
    }
    let found: Vec<FaceMatching> = slices
        .into_par_iter()
        .map_init(
            || (Vec::new(), Vec::new()),
            |(table, mate), faces| match_partition(faces, table, mate, want_links),
        )
        .collect();
    let mut out = FaceMatching::default();
    for p in found {
        out.boundary.extend(p.boundary);
        out.overshared.extend(p.overshared);
        out.same_orientation.extend(p.same_orientation);
        out.links.extend(p.links);
    }
    out.boundary.par_sort_unstable_by_key(|b| (b.tet, b.face));
    out.overshared.sort_unstable_by_key(|&(t, f, _)| (t, f));
    out.same_orientation.sort_unstable();
    out
}

/// Pairs the faces of one partition with a hash table (open addressing) of indices into
/// `faces`; `mate[i]` is the other owner of face `i`.
fn match_partition(
    faces: &mut [Entry],
    table: &mut Vec<u32>,
    mate: &mut Vec<u32>,
    want_links: bool,
) -> FaceMatching {
    const NONE: u32 = u32::MAX;
    let bits = (2 * faces.len())
        .next_power_of_two()
        .max(16)
        .trailing_zeros();
    let mask = (1usize << bits) - 1;
    table.clear();
    table.resize(1 << bits, NONE);
    mate.clear();
    mate.resize(faces.len(), NONE);
    let same = |x: &Entry, y: &Entry| x.0 == y.0 && x.1 >> 35 == y.1 >> 35;
    let mut overshared = false;
    'faces: for i in 0..faces.len() {
        let e = faces[i];
        let hash = (e.0 ^ (e.1 >> 35).rotate_left(29)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        let mut h = (hash >> (64 - bits)) as usize;
        loop {
            let j = table[h];
            if j == NONE {
                table[h] = i as u32;
                continue 'faces;
            }
            if same(&faces[j as usize], &e) {
                if mate[j as usize] != NONE {
                    overshared = true;
                    break 'faces;
                }
                mate[j as usize] = i as u32;
                mate[i] = j;
                continue 'faces;
            }
            h = (h + 1) & mask;
        }
    }
    if overshared {
        return match_sorted(faces, want_links);
    }
    let mut out = FaceMatching::default();
    for (i, &m) in mate.iter().enumerate() {
        let x = faces[i].1;
        if m == NONE {
            out.boundary.push(BoundaryFace {
                tet: entry_tet(x),
                face: entry_face(x),
            });
            continue;
        }
        if (m as usize) < i {
            continue;
        }
        let y = faces[m as usize].1;
        let (lo, hi) = if entry_tet(x) <= entry_tet(y) {
            (x, y)
        } else {
            (y, x)
        };
        if want_links {
            out.links
                .push((entry_tet(lo), entry_face(lo), entry_tet(hi)));
            out.links
                .push((entry_tet(hi), entry_face(hi), entry_tet(lo)));
        }
        if lo & 1 == hi & 1 {
            out.same_orientation
                .push((entry_tet(lo), entry_face(lo), entry_tet(hi)));
        }
    }
    out
}

/// The general matching of one partition, for faces with any number of owners: sorted
/// by face, each run holds one face's owners in tet order.
fn match_sorted(faces: &mut [Entry], want_links: bool) -> FaceMatching {
    faces.sort_unstable_by_key(|e| (e.1 >> 35, e.0, e.1));
    let mut out = FaceMatching::default();
    for run in faces.chunk_by(|x, y| x.0 == y.0 && x.1 >> 35 == y.1 >> 35) {
        if run.len() == 1 {
            out.boundary.push(BoundaryFace {
                tet: entry_tet(run[0].1),
                face: entry_face(run[0].1),
            });
            continue;
        }
        for (k, &(_, e)) in run.iter().enumerate() {
            if want_links {
                let other = if k == 0 { run[1].1 } else { run[0].1 };
                out.links
                    .push((entry_tet(e), entry_face(e), entry_tet(other)));
            }
            if run.len() > 2 {
                out.overshared
                    .push((entry_tet(e), entry_face(e), run.len()));
            }
            for &(_, later) in &run[k + 1..] {
                if later & 1 == e & 1 {
                    out.same_orientation
                        .push((entry_tet(e), entry_face(e), entry_tet(later)));
                }
            }
        }
    }
    out
}

impl FaceAdjacency {
    /// Adjacency of `mesh` (its indices must be in range, which every `TetMesh` guarantees).
    pub fn new(mesh: &TetMesh) -> FaceAdjacency {
        Self::from_tets(mesh.nb_vertices(), mesh.tets())
    }

    /// Adjacency of a tet soup over `n_vertices` vertices (see `match_faces` for how).
    pub fn from_tets(n_vertices: usize, tets: &[Tet]) -> FaceAdjacency {
        let m = match_faces(n_vertices, tets, true);
        let mut neighbors = vec![[TetId::INVALID; 4]; tets.len()];
        for &(t, f, other) in &m.links {
            neighbors[t.idx()][f as usize] = other;
        }
        FaceAdjacency {
            neighbors,
            overshared: m.overshared,
            same_orientation: m.same_orientation,
        }
    }

    /// The faces with no tet on the other side, in (tet, face) order.
    pub fn boundary_faces(&self) -> Vec<BoundaryFace> {
        let mut out = Vec::new();
        for (t, row) in self.neighbors.iter().enumerate() {
            for (f, n) in row.iter().enumerate() {
                if !n.is_valid() {
                    out.push(BoundaryFace {
                        tet: TetId::from_usize(t),
                        face: f as u8,
                    });
                }
            }
        }
        out
    }

    /// Connected components through shared faces: (number of components, component of
    /// each tet). Components are numbered in order of their lowest tet.
    pub fn components(&self) -> (usize, Vec<u32>) {
        let n = self.neighbors.len();
        let mut label = vec![u32::MAX; n];
        let mut count = 0u32;
        let mut stack = Vec::new();
        for seed in 0..n {
            if label[seed] != u32::MAX {
                continue;
            }
            label[seed] = count;
            stack.push(seed);
            while let Some(t) = stack.pop() {
                for u in self.neighbors[t] {
                    if u.is_valid() && label[u.idx()] == u32::MAX {
                        label[u.idx()] = count;
                        stack.push(u.idx());
                    }
                }
            }
            count += 1;
        }
        (count as usize, label)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec3;

    /// Two tets sharing face (1, 2, 3).
    fn two_tets() -> TetMesh {
        let p = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            DVec3::new(1.0, 1.0, 1.0),
        ];
        TetMesh::from_arrays(p, vec![[0, 1, 2, 3], [1, 4, 2, 3]])
            .unwrap()
            .0
    }

    #[test]
    fn shared_face_found_once_each_way() {
        let m = two_tets();
        let adj = m.adjacency();
        assert_eq!(adj.neighbors[0][0], TetId(1));
        assert_eq!(adj.neighbors[1].iter().filter(|n| n.is_valid()).count(), 1);
        assert_eq!(adj.boundary_faces().len(), 6);
        assert!(adj.overshared.is_empty() && adj.same_orientation.is_empty());
        assert_eq!(adj.components().0, 1);
    }

    /// The matching by brute force: a map from each face (sorted vertices) to its owners.
    fn reference(tets: &[Tet]) -> FaceAdjacency {
        use std::collections::BTreeMap;
        let mut owners: BTreeMap<[VertexId; 3], Vec<(usize, usize)>> = BTreeMap::new();
        for (t, tet) in tets.iter().enumerate() {
            for f in 0..4 {
                let mut key = face_vertices(tet, f);
                key.sort_unstable();
                owners.entry(key).or_default().push((t, f));
            }
        }
        let mut adj = FaceAdjacency {
            neighbors: vec![[TetId::INVALID; 4]; tets.len()],
            ..FaceAdjacency::default()
        };
        for list in owners.values() {
            for (k, &(t, f)) in list.iter().enumerate() {
                if list.len() > 1 {
                    let other = if k == 0 { list[1].0 } else { list[0].0 };
                    adj.neighbors[t][f] = TetId::from_usize(other);
                }
                if list.len() > 2 {
                    adj.overshared
                        .push((TetId::from_usize(t), f as u8, list.len()));
                }
                for &(u, g) in &list[k + 1..] {
                    let (a, b) = (face_vertices(&tets[t], f), face_vertices(&tets[u], g));
                    if even_parity(a) == even_parity(b) {
                        adj.same_orientation.push((
                            TetId::from_usize(t),
                            f as u8,
                            TetId::from_usize(u),
                        ));
                    }
                }
            }
        }
        adj.overshared.sort_unstable_by_key(|&(t, f, _)| (t, f));
        adj.same_orientation.sort_unstable();
        adj
    }

    /// A seeded soup of tets over few vertices: faces shared by 1, 2, 3 or more tets with
    /// both orientations, and tets repeating a vertex.
    fn soup(seed: u64, n_tets: usize, n_vertices: u32) -> Vec<Tet> {
        let mut x = seed;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % n_vertices as u64) as u32
        };
        (0..n_tets)
            .map(|_| [next(), next(), next(), next()].map(VertexId))
            .collect()
    }

    #[test]
    fn matching_agrees_with_brute_force_on_random_soups() {
        // Small soups run on one thread; the large one takes the parallel path.
        for (seed, n_tets, n_vertices) in [
            (1, 200, 9),
            (2, 3000, 40),
            (3, 70_000, 4000),
            (4, 5000, 1 << 20),
        ] {
            let mut tets = soup(seed, n_tets, n_vertices);
            if seed == 4 {
                // Faces with exactly two owners (the hash path), some of them with the same
                // orientation: copies of tets, with an even or an odd permutation.
                let copies: Vec<Tet> = tets[..100]
                    .iter()
                    .enumerate()
                    .map(|(k, t)| {
                        if k % 2 == 0 {
                            [t[1], t[2], t[0], t[3]]
                        } else {
                            [t[1], t[0], t[2], t[3]]
                        }
                    })
                    .collect();
                tets.extend(copies);
            }
            let got = FaceAdjacency::from_tets(n_vertices as usize, &tets);
            let want = reference(&tets);
            assert_eq!(got.neighbors, want.neighbors, "seed {seed}");
            assert_eq!(got.overshared, want.overshared, "seed {seed}");
            assert_eq!(got.same_orientation, want.same_orientation, "seed {seed}");
            let boundary = match_faces(n_vertices as usize, &tets, false).boundary;
            assert_eq!(boundary, got.boundary_faces(), "seed {seed}");
        }
    }
}
