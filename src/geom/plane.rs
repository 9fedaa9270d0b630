//! Oriented planes.

use super::predicates::{Sign, orient3d};
use glam::DVec3;

/// An oriented plane, kept both as three points it passes through (for exact side tests)
/// and as a unit normal and offset (for distances and intersection points).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Three non-collinear points spanning the plane, counter-clockwise seen from the
    /// positive side.
    pub points: [DVec3; 3],
    /// Unit normal, pointing to the positive side.
    pub normal: DVec3,
    /// `normal · x = offset` on the plane.
    pub offset: f64,
}

impl Plane {
    /// The plane through `a`, `b`, `c` (counter-clockwise seen from the positive side), or
    /// `None` when they are collinear or not finite.
    pub fn from_points(a: DVec3, b: DVec3, c: DVec3) -> Option<Plane> {
        let n = (b - a).cross(c - a);
        let len = n.length();
        if !(len.is_finite() && len > 0.0) {
            return None;
        }
        let normal = n / len;
        Some(Plane {
            points: [a, b, c],
            normal,
            offset: normal.dot(a),
        })
    }

    /// Exact side of `p`: the sign of orient3d(points, p), so two calls on the same point
    /// always agree with each other and with every other exact predicate.
    pub fn side(&self, p: DVec3) -> Sign {
        let [a, b, c] = self.points;
        orient3d(a, b, c, p)
    }

    /// Signed distance of `p` (floating point).
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) - self.offset
    }

    /// Parameter `t` in [0, 1] where the segment `p + t (q - p)` meets the plane, from the
    /// signed distances; `None` when the segment is parallel to it.
    pub fn segment_parameter(&self, p: DVec3, q: DVec3) -> Option<f64> {
        let (dp, dq) = (self.signed_distance(p), self.signed_distance(q));
        let den = dp - dq;
        (den != 0.0).then(|| (dp / den).clamp(0.0, 1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn side_and_distance_agree() {
        let pl = Plane::from_points(DVec3::ZERO, DVec3::X, DVec3::Y).unwrap();
        assert_eq!(pl.side(DVec3::new(0.3, 0.3, 2.0)), Sign::Positive);
        assert_eq!(pl.side(DVec3::new(0.3, 0.3, -2.0)), Sign::Negative);
        assert_eq!(pl.side(DVec3::new(5.0, -3.0, 0.0)), Sign::Zero);
        assert!((pl.signed_distance(DVec3::new(0.0, 0.0, 2.0)) - 2.0).abs() < 1e-15);
        let t = pl
            .segment_parameter(DVec3::new(0.0, 0.0, -1.0), DVec3::new(0.0, 0.0, 3.0))
            .unwrap();
        assert!((t - 0.25).abs() < 1e-15);
        assert!(Plane::from_points(DVec3::ZERO, DVec3::X, DVec3::X * 2.0).is_none());
    }
}
