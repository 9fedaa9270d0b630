//! Connected components of a cut mesh, each extractable as a mesh of its own.

use crate::mesh::{FaceAdjacency, TetMesh, VertexId};

/// The connected components of a mesh (tets joined through shared faces).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Components {
    /// Number of components.
    pub count: usize,
    /// Component of each tet, numbered in order of their lowest tet.
    pub label: Vec<u32>,
}

impl Components {
    /// The components of `mesh`.
    pub fn of(mesh: &TetMesh) -> Components {
        let (count, label) = FaceAdjacency::new(mesh).components();
        Components { count, label }
    }

    /// Number of tets of each component.
    pub fn sizes(&self) -> Vec<usize> {
        let mut s = vec![0; self.count];
        for &l in &self.label {
            s[l as usize] += 1;
        }
        s
    }

    /// Component `k` of `mesh` (which these components were computed for) as a mesh of its
    /// own: its tets in order, the vertices they use renumbered in increasing old id, and
    /// the point and cell data of those. `None` when `k` is out of range.
    pub fn extract(&self, mesh: &TetMesh, k: usize) -> Option<TetMesh> {
        if k >= self.count {
            return None;
        }
        let keep_tets: Vec<usize> = (0..mesh.nb_tets())
            .filter(|&t| self.label[t] as usize == k)
            .collect();
        let mut new_id = vec![u32::MAX; mesh.nb_vertices()];
        for &t in &keep_tets {
            for v in mesh.tets()[t] {
                new_id[v.idx()] = 0;
            }
        }
        let mut keep_vertices = Vec::new();
        for (v, id) in new_id.iter_mut().enumerate() {
            if *id == 0 {
                *id = keep_vertices.len() as u32;
                keep_vertices.push(v);
            }
        }
        let positions = keep_vertices.iter().map(|&v| mesh.positions()[v]).collect();
        let tets = keep_tets
            .iter()
            .map(|&t| mesh.tets()[t].map(|v| VertexId(new_id[v.idx()])))
            .collect();
        let mut out = TetMesh::from_parts(positions, tets);
        out.point_data = mesh.point_data.select(&keep_vertices);
        out.cell_data = mesh.cell_data.select(&keep_tets);
        Some(out)
    }

    /// Every component as a mesh of its own, in component order.
    pub fn extract_all(&self, mesh: &TetMesh) -> Vec<TetMesh> {
        (0..self.count)
            .filter_map(|k| self.extract(mesh, k))
            .collect()
    }
}
