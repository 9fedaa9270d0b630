//! Face adjacency and vertex stars.
//!
//! Faces are matched through vertex stars (the tets around a vertex) rather than a global
//! hash or sort of all faces: each tet looks for the other owner of each of its faces among
//! the tets around that face's vertex with the smallest star. This is linear in the mesh
//! size, allocation-light, and runs on all cores (each tet writes only its own row).

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

/// Whether `(x, y, z)` is a cyclic rotation of `(a, b, c)`.
#[inline]
fn same_cycle(a: [VertexId; 3], x: [VertexId; 3]) -> bool {
    x == a || x == [a[1], a[2], a[0]] || x == [a[2], a[0], a[1]]
}

/// Vertices of face `f` of tet `t`, outward-oriented.
#[inline]
pub fn face_vertices(t: &Tet, f: usize) -> [VertexId; 3] {
    TET_FACES[f].map(|i| t[i])
}

struct TetRow {
    neighbors: [TetId; 4],
    overshared: Vec<(u8, usize)>,
    same_orientation: Vec<(u8, TetId)>,
}

impl FaceAdjacency {
    /// Adjacency of `mesh` (its indices must be in range, which every `TetMesh` guarantees).
    pub fn new(mesh: &TetMesh) -> FaceAdjacency {
        Self::from_tets(mesh.nb_vertices(), mesh.tets())
    }

    /// Adjacency of a tet soup over `n_vertices` vertices.
    pub fn from_tets(n_vertices: usize, tets: &[Tet]) -> FaceAdjacency {
        let stars = VertexStars::new(n_vertices, tets);
        let rows: Vec<TetRow> = (0..tets.len())
            .into_par_iter()
            .map(|i| {
                let t = &tets[i];
                let mut row = TetRow {
                    neighbors: [TetId::INVALID; 4],
                    overshared: Vec::new(),
                    same_orientation: Vec::new(),
                };
                for f in 0..4 {
                    let fv = face_vertices(t, f);
                    let pivot = *fv
                        .iter()
                        .min_by_key(|v| stars.star(**v).len())
                        .expect("a face has three vertices");
                    let mut owners = 1;
                    for &u in stars.star(pivot) {
                        if u.idx() == i {
                            continue;
                        }
                        let tu = &tets[u.idx()];
                        if !fv.iter().all(|v| tu.contains(v)) {
                            continue;
                        }
                        owners += 1;
                        if row.neighbors[f] == TetId::INVALID {
                            row.neighbors[f] = u;
                        }
                        // The face as tet u orients it: opposite the vertex not on it.
                        let g = (0..4).find(|&k| !fv.contains(&tu[k])).unwrap_or(0);
                        if same_cycle(fv, face_vertices(tu, g)) && i < u.idx() {
                            row.same_orientation.push((f as u8, u));
                        }
                    }
                    if owners > 2 {
                        row.overshared.push((f as u8, owners));
                    }
                }
                row
            })
            .collect();
        let mut adj = FaceAdjacency {
            neighbors: Vec::with_capacity(rows.len()),
            overshared: Vec::new(),
            same_orientation: Vec::new(),
        };
        for (i, row) in rows.into_iter().enumerate() {
            let t = TetId::from_usize(i);
            adj.neighbors.push(row.neighbors);
            adj.overshared
                .extend(row.overshared.into_iter().map(|(f, n)| (t, f, n)));
            adj.same_orientation
                .extend(row.same_orientation.into_iter().map(|(f, u)| (t, f, u)));
        }
        adj
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
}
