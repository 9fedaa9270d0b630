//! Sub-meshes: a selection of tets (one connected component, say) as a mesh of its own,
//! with the vertices it uses and the attribute rows of both.

use super::{MeshError, TetId, TetMesh, VertexId};

impl TetMesh {
    /// The mesh made of the tets `tets` (in that order) and of the vertices they use (in
    /// increasing id order), with their per-vertex and per-tet attribute rows. The result
    /// is validated like any new mesh: a selection that is not a valid mesh by itself (two
    /// tets touching only along an edge, a tet listed twice) is rejected. Every id in
    /// `tets` must be a tet of this mesh.
    pub fn submesh(&self, tets: &[TetId]) -> Result<TetMesh, MeshError> {
        let mut used = vec![false; self.nb_vertices()];
        for &t in tets {
            for v in self.tet(t) {
                used[v.idx()] = true;
            }
        }
        let mut new_id = vec![u32::MAX; self.nb_vertices()];
        let mut kept = Vec::new();
        for (old, _) in used.iter().enumerate().filter(|(_, u)| **u) {
            new_id[old] = kept.len() as u32;
            kept.push(old);
        }
        let positions = kept.iter().map(|&v| self.positions[v]).collect();
        let cells = tets
            .iter()
            .map(|&t| self.tet(t).map(|v: VertexId| new_id[v.idx()]))
            .collect();
        let (mut mesh, _) = TetMesh::from_arrays(positions, cells)?;
        mesh.point_data = self.point_data.select(&kept);
        let rows: Vec<usize> = tets.iter().map(|t| t.idx()).collect();
        mesh.cell_data = self.cell_data.select(&rows);
        Ok(mesh)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec3;
    use crate::mesh::Attribute;

    /// Two unit-corner tets far apart: two components.
    fn two_islands() -> TetMesh {
        let mut p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        p.extend(p.clone().iter().map(|q| *q + DVec3::splat(5.0)));
        let (mut m, _) = TetMesh::from_arrays(p, vec![[0, 1, 2, 3], [4, 5, 6, 7]]).unwrap();
        m.point_data
            .insert(Attribute::new("id", 1, (0..8).map(f64::from).collect()).unwrap());
        m.cell_data
            .insert(Attribute::new("t", 2, vec![1.0, 2.0, 3.0, 4.0]).unwrap());
        m
    }

    #[test]
    fn component_keeps_its_vertices_and_rows() {
        let m = two_islands();
        let (count, label) = m.adjacency().components();
        assert_eq!((count, label), (2, vec![0, 1]));
        let s = m.submesh(&[TetId(1)]).unwrap();
        assert!(s.validate().is_valid());
        assert_eq!((s.nb_vertices(), s.nb_tets()), (4, 1));
        assert_eq!(s.position(VertexId(0)), DVec3::splat(5.0));
        assert_eq!(
            s.point_data.get("id").unwrap().values,
            vec![4.0, 5.0, 6.0, 7.0]
        );
        assert_eq!(s.cell_data.get("t").unwrap().values, vec![3.0, 4.0]);
        assert_eq!(s.volume(), m.tet_volume(TetId(1)));
    }

    #[test]
    fn selection_that_is_not_a_mesh_is_rejected() {
        let m = two_islands();
        assert!(m.submesh(&[TetId(0), TetId(0)]).is_err());
        assert_eq!(m.submesh(&[]), Err(MeshError::Empty));
    }
}
