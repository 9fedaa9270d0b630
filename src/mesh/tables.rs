//! Local tables of a tetrahedron (the `VofE`/`FofE` tables of VCGlib), in one place.
//!
//! Vertices are numbered 0..4 in a positively oriented tet. Face `f` is opposite vertex
//! `f`, listed counter-clockwise seen from outside (its right-hand normal points out).
//! Edge `e` joins `TET_EDGES[e]`; edge `5 - e` is the edge opposite `e`.

/// Vertices of face `f` (opposite vertex `f`), outward-oriented.
pub const TET_FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// Vertices of edge `e`, lower local index first.
pub const TET_EDGES: [[usize; 2]; 6] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];

/// `EDGE_OF_VERTICES[a][b]`: the edge joining local vertices `a` and `b` (`usize::MAX` on
/// the diagonal).
pub const EDGE_OF_VERTICES: [[usize; 4]; 4] = [
    [usize::MAX, 0, 1, 2],
    [0, usize::MAX, 3, 4],
    [1, 3, usize::MAX, 5],
    [2, 4, 5, usize::MAX],
];

/// The two faces containing edge `e`: the faces opposite the vertices *not* on the edge.
pub const FACES_OF_EDGE: [[usize; 2]; 6] = [[2, 3], [1, 3], [1, 2], [0, 3], [0, 2], [0, 1]];

/// The three edges of face `f`.
pub const EDGES_OF_FACE: [[usize; 3]; 4] = [[3, 4, 5], [1, 2, 5], [0, 2, 4], [0, 1, 3]];

/// The edge opposite edge `e` (sharing no vertex with it).
#[inline]
pub const fn opposite_edge(e: usize) -> usize {
    5 - e
}

/// An oriented triangle as a key: rotated so its smallest vertex comes first, so two
/// rotations of the same oriented triangle compare equal and the opposite orientation
/// does not ([`flip_face`] gives that one).
pub const fn oriented_face(a: u32, b: u32, c: u32) -> [u32; 3] {
    if a < b && a < c {
        [a, b, c]
    } else if b < c {
        [b, c, a]
    } else {
        [c, a, b]
    }
}

/// The key of the same triangle with the opposite orientation.
pub const fn flip_face(f: [u32; 3]) -> [u32; 3] {
    oriented_face(f[0], f[2], f[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{DVec3, Sign, orient3d, triangle_normal};

    #[test]
    fn faces_point_outwards() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        assert_eq!(orient3d(p[0], p[1], p[2], p[3]), Sign::Positive);
        let centroid = (p[0] + p[1] + p[2] + p[3]) / 4.0;
        for (f, face) in TET_FACES.iter().enumerate() {
            assert!(!face.contains(&f));
            let n = triangle_normal(p[face[0]], p[face[1]], p[face[2]]);
            assert!(
                n.dot(p[face[0]] - centroid) > 0.0,
                "face {f} points inwards"
            );
        }
    }

    #[test]
    fn edge_tables_agree() {
        for (e, &[a, b]) in TET_EDGES.iter().enumerate() {
            assert_eq!(EDGE_OF_VERTICES[a][b], e);
            assert_eq!(EDGE_OF_VERTICES[b][a], e);
            let [oa, ob] = TET_EDGES[opposite_edge(e)];
            assert!(oa != a && oa != b && ob != a && ob != b);
            for f in FACES_OF_EDGE[e] {
                assert!(TET_FACES[f].contains(&a) && TET_FACES[f].contains(&b));
                assert!(EDGES_OF_FACE[f].contains(&e));
            }
        }
        for (f, edges) in EDGES_OF_FACE.iter().enumerate() {
            for &e in edges {
                assert!(!TET_EDGES[e].contains(&f));
            }
        }
    }
}
