//! Orientation predicates. `orient3d` and `orient2d` are exact (Shewchuk's adaptive
//! arithmetic): their sign is the sign of the true determinant of the given doubles.

use glam::DVec3;
use robust::{Coord, Coord3D};

/// The sign of an exact predicate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    Negative,
    Zero,
    Positive,
}

impl Sign {
    fn of(x: f64) -> Sign {
        if x > 0.0 {
            Sign::Positive
        } else if x < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }

    pub fn flip(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }
}

fn c3(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// Exact orientation of the tetrahedron (a, b, c, d).
///
/// `Positive` when `d` lies on the side of the plane (a, b, c) that the right-hand normal
/// `(b - a) × (c - a)` points to, i.e. when the signed volume is positive. This is VTK's
/// convention for `VTK_TETRA` and the one every tet of a [`TetMesh`](crate::mesh::TetMesh)
/// satisfies. (Shewchuk's `orient3d` has the opposite sign; the flip is made here, once.)
pub fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
    Sign::of(-robust::orient3d(c3(a), c3(b), c3(c), c3(d)))
}

/// Exact orientation of the triangle (a, b, c) in the plane: `Positive` when counter-clockwise.
pub fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Sign {
    let p = |q: [f64; 2]| Coord { x: q[0], y: q[1] };
    Sign::of(robust::orient2d(p(a), p(b), p(c)))
}

/// Signed volume of the tetrahedron (a, b, c, d): `(b - a) · ((c - a) × (d - a)) / 6`.
/// Floating point, not exact: use [`orient3d`] for sign decisions.
pub fn signed_volume_inexact(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    (b - a).dot((c - a).cross(d - a)) / 6.0
}

/// Signed volume whose sign always agrees with [`orient3d`]: the floating-point value,
/// except that it is 0 exactly when the exact predicate says the points are coplanar, and
/// its sign is forced to the exact one when rounding got it wrong (then its magnitude is
/// below rounding error anyway).
pub fn signed_volume(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    let v = signed_volume_inexact(a, b, c, d);
    match orient3d(a, b, c, d) {
        Sign::Zero => 0.0,
        Sign::Positive => v.abs().max(f64::MIN_POSITIVE),
        Sign::Negative => -v.abs().max(f64::MIN_POSITIVE),
    }
}

/// Right-hand normal of the triangle (a, b, c), of length twice its area (not normalised).
pub fn triangle_normal(a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    (b - a).cross(c - a)
}

/// Area of the triangle (a, b, c).
pub fn triangle_area(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    0.5 * triangle_normal(a, b, c).length()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_tet_is_positive_like_vtk() {
        let o = DVec3::ZERO;
        let (x, y, z) = (DVec3::X, DVec3::Y, DVec3::Z);
        assert_eq!(orient3d(o, x, y, z), Sign::Positive);
        assert_eq!(orient3d(o, y, x, z), Sign::Negative);
        assert!((signed_volume(o, x, y, z) - 1.0 / 6.0).abs() < 1e-15);
    }

    #[test]
    fn exact_on_nearly_coplanar_points() {
        // d is on the plane z = 0 up to the last bit: rounding would give noise,
        // the exact predicate gives Zero for the truly coplanar point.
        let a = DVec3::new(0.1, 0.2, 0.0);
        let b = DVec3::new(1e8 + 0.3, 0.7, 0.0);
        let c = DVec3::new(0.5, 1e-8, 0.0);
        let d = DVec3::new(12345.678, -98765.4321, 0.0);
        assert_eq!(orient3d(a, b, c, d), Sign::Zero);
        assert_eq!(signed_volume(a, b, c, d), 0.0);
        let d_up = DVec3::new(12345.678, -98765.4321, f64::MIN_POSITIVE);
        assert_ne!(orient3d(a, b, c, d_up), Sign::Zero);
    }

    #[test]
    fn orient2d_counter_clockwise() {
        assert_eq!(orient2d([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]), Sign::Positive);
        assert_eq!(orient2d([0.0, 0.0], [1.0, 1.0], [2.0, 2.0]), Sign::Zero);
    }
}
