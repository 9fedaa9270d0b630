//! The boundary surface of a tet mesh: its triangles (outward-oriented) and area.

use super::adjacency::face_vertices;
use super::{FaceAdjacency, TetMesh, VertexId};
use crate::geom::triangle_area;

/// Boundary triangles of a mesh, each outward-oriented (right-hand normal pointing out of
/// the volume).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Boundary {
    pub triangles: Vec<[VertexId; 3]>,
    pub area: f64,
}

impl TetMesh {
    /// The boundary, from a face adjacency already computed for this mesh.
    pub fn boundary_with(&self, adj: &FaceAdjacency) -> Boundary {
        let triangles: Vec<[VertexId; 3]> = adj
            .boundary_faces()
            .iter()
            .map(|b| face_vertices(&self.tet(b.tet), b.face as usize))
            .collect();
        let area = triangles
            .iter()
            .map(|t| {
                triangle_area(
                    self.position(t[0]),
                    self.position(t[1]),
                    self.position(t[2]),
                )
            })
            .sum();
        Boundary { triangles, area }
    }

    /// The boundary (computes the face adjacency).
    pub fn boundary(&self) -> Boundary {
        self.boundary_with(&self.adjacency())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec3;

    #[test]
    fn corner_tet_boundary() {
        let (m, _) = TetMesh::from_arrays(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            vec![[0, 1, 2, 3]],
        )
        .unwrap();
        let b = m.boundary();
        assert_eq!(b.triangles.len(), 4);
        let expected = 1.5 + 3f64.sqrt() / 2.0;
        assert!((b.area - expected).abs() < 1e-15);
    }
}
