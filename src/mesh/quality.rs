//! Element quality: dihedral angles, volume, aspect ratio — per tet and summarised.
//!
//! The aspect ratio is the normalised radius ratio R / (3 r) (circumradius over three times
//! the inradius): 1 for the regular tet, growing without bound as a tet flattens. It is the
//! measure FEM codes watch because the stiffness matrix's conditioning follows it.

use super::tables::{FACES_OF_EDGE, TET_EDGES, TET_FACES};
use super::{TetId, TetMesh};
use crate::geom::{DVec3, signed_volume_inexact, triangle_area, triangle_normal};

/// Quality of one tet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TetQuality {
    /// Smallest interior dihedral angle, in degrees.
    pub min_dihedral_deg: f64,
    /// Largest interior dihedral angle, in degrees.
    pub max_dihedral_deg: f64,
    /// Signed volume.
    pub volume: f64,
    /// R / (3 r): 1 for the regular tet, infinite for a flat one.
    pub aspect_ratio: f64,
}

/// Quality of the tet with corners `p` (positively oriented for meaningful angles).
pub fn tet_quality(p: [DVec3; 4]) -> TetQuality {
    let volume = signed_volume_inexact(p[0], p[1], p[2], p[3]);
    // Angles and the aspect ratio do not depend on the tet's place or size: they are
    // measured on the tet moved to the origin and scaled to a unit longest edge, so that
    // the products below (up to the eighth power of a length) neither overflow nor
    // underflow however large or small the mesh's coordinates (at 1e40 the aspect ratio
    // came out infinite, at 1e-40 wrong).
    let longest = TET_EDGES
        .iter()
        .map(|&[a, b]| (p[a] - p[b]).length())
        .fold(0.0, f64::max);
    let p = if longest > 0.0 && longest.is_finite() {
        p.map(|x| (x - p[0]) / longest)
    } else {
        p
    };
    let unit_volume = signed_volume_inexact(p[0], p[1], p[2], p[3]);
    let normals = TET_FACES.map(|f| triangle_normal(p[f[0]], p[f[1]], p[f[2]]));
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for faces in FACES_OF_EDGE {
        let (a, b) = (normals[faces[0]], normals[faces[1]]);
        let cos = (a.dot(b) / (a.length() * b.length())).clamp(-1.0, 1.0);
        // Interior dihedral angle = π − angle between the outward normals.
        let angle = (std::f64::consts::PI - cos.acos()).to_degrees();
        let angle = if angle.is_nan() { 0.0 } else { angle };
        lo = lo.min(angle);
        hi = hi.max(angle);
    }
    let area: f64 = TET_FACES
        .iter()
        .map(|f| triangle_area(p[f[0]], p[f[1]], p[f[2]]))
        .sum();
    let inradius = 3.0 * unit_volume.abs() / area;
    // Circumradius from the products of opposite edge lengths (edge e and 5 − e).
    let len = TET_EDGES.map(|[a, b]| (p[a] - p[b]).length());
    let (x, y, z) = (len[0] * len[5], len[1] * len[4], len[2] * len[3]);
    let prod = (x + y + z) * (x + y - z) * (x - y + z) * (-x + y + z);
    let circumradius = prod.max(0.0).sqrt() / (24.0 * unit_volume.abs());
    let aspect_ratio = if inradius > 0.0 && circumradius.is_finite() {
        circumradius / (3.0 * inradius)
    } else {
        f64::INFINITY
    };
    TetQuality {
        min_dihedral_deg: lo,
        max_dihedral_deg: hi,
        volume,
        aspect_ratio,
    }
}

/// Quality of a whole mesh, summarised.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QualitySummary {
    pub tets: usize,
    pub min_dihedral_deg: f64,
    pub max_dihedral_deg: f64,
    pub min_volume: f64,
    pub max_volume: f64,
    pub mean_volume: f64,
    pub max_aspect_ratio: f64,
    pub mean_aspect_ratio: f64,
    /// Tets with a dihedral angle below 5°: the slivers FEM codes care about.
    pub tets_below_5deg: usize,
}

impl TetMesh {
    /// Quality of tet `t`.
    pub fn tet_quality(&self, t: TetId) -> TetQuality {
        tet_quality(self.tet_positions(t))
    }

    /// Quality over all tets (an empty mesh gives NaN means and infinite extremes).
    pub fn quality(&self) -> QualitySummary {
        let mut s = QualitySummary {
            tets: self.nb_tets(),
            min_dihedral_deg: f64::INFINITY,
            max_dihedral_deg: 0.0,
            min_volume: f64::INFINITY,
            max_volume: f64::NEG_INFINITY,
            mean_volume: 0.0,
            max_aspect_ratio: 0.0,
            mean_aspect_ratio: 0.0,
            tets_below_5deg: 0,
        };
        for t in 0..self.nb_tets() {
            let q = self.tet_quality(TetId::from_usize(t));
            s.min_dihedral_deg = s.min_dihedral_deg.min(q.min_dihedral_deg);
            s.max_dihedral_deg = s.max_dihedral_deg.max(q.max_dihedral_deg);
            s.min_volume = s.min_volume.min(q.volume);
            s.max_volume = s.max_volume.max(q.volume);
            s.mean_volume += q.volume;
            s.max_aspect_ratio = s.max_aspect_ratio.max(q.aspect_ratio);
            s.mean_aspect_ratio += q.aspect_ratio;
            s.tets_below_5deg += usize::from(q.min_dihedral_deg < 5.0);
        }
        s.mean_volume /= s.tets as f64;
        s.mean_aspect_ratio /= s.tets as f64;
        s
    }

    /// The median length of the tets' edges (each edge counted once per tet holding it), a
    /// typical edge of the mesh: the unit of a scalpel's `min_advance`
    /// ([`crate::cut::Incision`]). None for a mesh without tets.
    pub fn median_edge_length(&self) -> Option<f64> {
        let p = self.positions();
        let mut lengths: Vec<f64> = self
            .tets()
            .iter()
            .flat_map(|t| TET_EDGES.map(|[a, b]| p[t[a].idx()].distance(p[t[b].idx()])))
            .collect();
        if lengths.is_empty() {
            return None;
        }
        let mid = lengths.len() / 2;
        Some(*lengths.select_nth_unstable_by(mid, f64::total_cmp).1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regular_tet_is_ideal() {
        let p = [
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(-1.0, -1.0, 1.0),
        ];
        let q = tet_quality(p);
        let ideal = (1.0f64 / 3.0).acos().to_degrees(); // 70.53°
        assert!((q.min_dihedral_deg - ideal).abs() < 1e-9, "{q:?}");
        assert!((q.max_dihedral_deg - ideal).abs() < 1e-9);
        assert!((q.aspect_ratio - 1.0).abs() < 1e-12);
        assert!((q.volume - 8.0 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn corner_tet_has_right_angles() {
        let q = tet_quality([DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z]);
        assert!((q.max_dihedral_deg - 90.0).abs() < 1e-9);
        assert!((q.min_dihedral_deg - 54.735_610_317_245_35).abs() < 1e-9);
        assert!(q.aspect_ratio > 1.0);
    }

    /// The same tet at any scale and place: the same angles and aspect ratio, its volume
    /// scaled by the cube.
    #[test]
    fn quality_does_not_depend_on_scale() {
        let p = [
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(0.4, 0.9, 0.1),
            DVec3::new(1.3, 0.1, 0.2),
            DVec3::new(0.5, 0.4, 0.05),
        ];
        let q = tet_quality(p);
        assert!(q.volume > 0.0 && q.aspect_ratio > 1.0, "{q:?}");
        for s in [1e-100, 1e-40, 1e40, 1e100] {
            let r = tet_quality(p.map(|x| x * s + DVec3::splat(3.0 * s)));
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
            assert!(close(r.min_dihedral_deg, q.min_dihedral_deg), "{s}: {r:?}");
            assert!(close(r.max_dihedral_deg, q.max_dihedral_deg), "{s}: {r:?}");
            assert!(close(r.aspect_ratio, q.aspect_ratio), "{s}: {r:?}");
            assert!(close(r.volume, q.volume * s * s * s), "{s}: {r:?}");
        }
    }

    #[test]
    fn flat_tet_has_infinite_aspect_ratio() {
        let q = tet_quality([DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)]);
        assert!(q.aspect_ratio.is_infinite());
        assert_eq!(q.volume, 0.0);
    }
}
