//! Geometry: exact-when-needed predicates, planes, and the one [`Tolerance`] type.
//!
//! This layer knows no topology. Every *sign* decision the library makes (is a tet
//! positively oriented, which side of a plane is a point on) is made here, so that two
//! callers asking the same question about the same points always get the same answer:
//! that is what keeps neighbouring tets consistent when a cut classifies shared edges.
//!
//! Exact answers come from Shewchuk's adaptive predicates (the `robust` crate); functions
//! that are *not* exact say so in their name (`*_inexact`).

mod plane;
mod polygon;
mod predicates;
mod tolerance;

pub use plane::Plane;
pub use polygon::{
    CutPolygon, MAX_POLYGON_POINTS, PLANE_SNAP, PLANE_SNAP_ANGLE, PolygonError, SWEEP_PLANARITY,
    scalpel_sweep, scalpel_sweep_splits,
};
pub(crate) use polygon::{check_points, lies_in_plane, snap_to_plane};
pub use predicates::{
    Sign, orient2d, orient3d, signed_volume, signed_volume_inexact, triangle_area, triangle_normal,
};
pub use tolerance::Tolerance;

/// The position type used throughout the library (glam's double-precision 3-vector).
pub use glam::DVec3;

/// The largest coordinate magnitude mtcut accepts, in meshes, positions and polygons. The
/// exact predicates and the cut's measures multiply up to four coordinate differences
/// together: from about 1e75 on they overflow (a polygon of that size was refused as
/// flat, tets at 1e150 were taken for degenerate). No mesh in any physical unit comes
/// near; the whole pipeline is tested at 1e50.
pub const MAX_COORDINATE: f64 = 1e50;

/// The smallest bounding-box diagonal of a mesh mtcut accepts: below about 1e-75 the
/// same products underflow (tets at 1e-150 were taken for degenerate); tested at 1e-50.
pub const MIN_MESH_SIZE: f64 = 1e-50;

/// The coordinate of `p` beyond ±[`MAX_COORDINATE`], if any (`p` finite).
pub fn coordinate_out_of_range(p: DVec3) -> Option<f64> {
    p.to_array().into_iter().find(|c| c.abs() > MAX_COORDINATE)
}

/// Whether mtcut takes `c` as a coordinate: finite and within ±[`MAX_COORDINATE`].
pub(crate) fn supported(c: f64) -> bool {
    c.is_finite() && c.abs() <= MAX_COORDINATE
}

/// The first of `points` with a coordinate mtcut cannot take, in one pass: its index and
/// the coordinate (NaN or infinite, or beyond ±[`MAX_COORDINATE`]).
pub(crate) fn first_unsupported(points: &[DVec3]) -> Option<(usize, f64)> {
    points.iter().enumerate().find_map(|(i, p)| {
        let bad = p.to_array().into_iter().find(|&c| !supported(c))?;
        Some((i, bad))
    })
}

/// How every message words a coordinate beyond the range: "has coordinate 1e60, larger in
/// magnitude than the 1e50 mtcut supports".
pub(crate) fn out_of_range_text(value: f64) -> String {
    format!(
        "has coordinate {value:e}, larger in magnitude than the {MAX_COORDINATE:e} mtcut supports"
    )
}

/// An axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: DVec3,
    pub max: DVec3,
}

impl Aabb {
    /// The empty box: growing it by any point gives that point's box.
    pub const EMPTY: Aabb = Aabb {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    };

    /// The smallest box containing every point of `points` (EMPTY for none).
    pub fn from_points<'a>(points: impl IntoIterator<Item = &'a DVec3>) -> Aabb {
        let mut b = Aabb::EMPTY;
        for p in points {
            b.grow(*p);
        }
        b
    }

    pub fn grow(&mut self, p: DVec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    pub fn extent(&self) -> DVec3 {
        if self.is_empty() {
            DVec3::ZERO
        } else {
            self.max - self.min
        }
    }

    /// Length of the diagonal; 0 for an empty box.
    pub fn diagonal(&self) -> f64 {
        self.extent().length()
    }

    pub fn center(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }

    pub fn contains(&self, p: DVec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    pub fn intersects(&self, other: &Aabb) -> bool {
        self.min.cmple(other.max).all() && other.min.cmple(self.max).all()
    }
}
