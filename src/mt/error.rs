//! Per-tet error (paper §2.1): how badly a tet of a simplified level approximates the input.
//!
//! The error is pluggable ([`TetError`]): the build evaluates it on every tet a collapse
//! would create, uses the largest value as the collapse's priority, and records it as the
//! fragment's error — raised to the errors of the fragments it depends on, so errors grow
//! along the DAG and threshold extraction is well defined. Built in: [`VolumeError`] (the
//! paper's), [`BoundaryError`] and [`QualityError`]. All three are dimensionless (relative
//! to the input's size), so one threshold means the same on a mesh in metres or millimetres.

use crate::geom::{DVec3, signed_volume_inexact};
use std::fmt;
use std::sync::Arc;

/// A tet the build asks the error of, with the context a metric may use.
#[derive(Clone, Copy, Debug)]
pub struct TetSample {
    /// The four corners, positively oriented.
    pub corners: [DVec3; 4],
    /// Largest distance from the input's boundary surface of the faces of this tet that the
    /// collapse being evaluated puts on the boundary (0 when it puts none there; faces
    /// already on the boundary were accounted for by the step that made them, and errors
    /// are raised along the DAG).
    pub boundary_deviation: f64,
    /// The input's bounding-box diagonal: the length scale.
    pub scale: f64,
    /// The input's total volume: the volume scale.
    pub volume: f64,
}

/// A per-tet error. Values must be finite and ≥ 0 (the build rejects others with an error
/// naming the metric); larger means coarser.
pub trait TetError: Send + Sync {
    /// Short name, stored in `.mt` files (`volume`, `boundary`, `quality` are taken).
    fn name(&self) -> &str;
    fn tet_error(&self, tet: &TetSample) -> f64;
    /// Whether [`TetSample::boundary_deviation`] can change the result. When it cannot,
    /// the build ranks boundary collapses before measuring the deviation (which it must
    /// still do, to respect the tolerance), a large saving. Default `true`.
    fn uses_boundary_deviation(&self) -> bool {
        true
    }
}

/// The paper's error (§2.1): the tet's volume, as a fraction of the input's volume.
#[derive(Clone, Copy, Debug, Default)]
pub struct VolumeError;

impl TetError for VolumeError {
    fn name(&self) -> &str {
        "volume"
    }

    fn tet_error(&self, t: &TetSample) -> f64 {
        let [a, b, c, d] = t.corners;
        signed_volume_inexact(a, b, c, d).abs() / t.volume
    }

    fn uses_boundary_deviation(&self) -> bool {
        false
    }
}

/// Boundary fidelity combined with size: `max(deviation, size_weight × longest edge)`,
/// both relative to the bounding-box diagonal. Tets whose new boundary faces stray from the
/// input surface are expensive; interior tets still refine with size, so a threshold
/// extraction is fine near the surface where it matters and graded inside.
#[derive(Clone, Copy, Debug)]
pub struct BoundaryError {
    /// Weight of the size term. Default 0.02: a tet 1/10 of the model long costs as much
    /// as a boundary off by 1/500 of it.
    pub size_weight: f64,
}

impl BoundaryError {
    pub const DEFAULT: BoundaryError = BoundaryError { size_weight: 0.02 };
}

impl Default for BoundaryError {
    fn default() -> Self {
        BoundaryError::DEFAULT
    }
}

impl TetError for BoundaryError {
    fn name(&self) -> &str {
        "boundary"
    }

    fn tet_error(&self, t: &TetSample) -> f64 {
        let c = t.corners;
        let mut longest = 0.0f64;
        for i in 0..4 {
            for j in i + 1..4 {
                longest = longest.max((c[i] - c[j]).length_squared());
            }
        }
        (t.boundary_deviation / t.scale).max(self.size_weight * longest.sqrt() / t.scale)
    }
}

/// Element quality for FEM: root-mean-square edge length (relative to the diagonal)
/// divided by the mean-ratio quality (1 for a regular tet, → 0 for a sliver). Large and
/// badly shaped tets cost most, so the simplifier prefers collapses that make good tets.
#[derive(Clone, Copy, Debug, Default)]
pub struct QualityError;

impl TetError for QualityError {
    fn name(&self) -> &str {
        "quality"
    }

    fn tet_error(&self, t: &TetSample) -> f64 {
        let q = mean_ratio(t.corners);
        let rms = (edge_length_squares(t.corners) / 6.0).sqrt();
        if q > 0.0 { rms / t.scale / q } else { f64::MAX }
    }

    fn uses_boundary_deviation(&self) -> bool {
        false
    }
}

fn edge_length_squares(c: [DVec3; 4]) -> f64 {
    let mut s = 0.0;
    for i in 0..4 {
        for j in i + 1..4 {
            s += (c[i] - c[j]).length_squared();
        }
    }
    s
}

/// Mean-ratio quality of a tet, `12 (3V)^(2/3) / Σ lᵢⱼ²`: 1 for a regular tet, 0 for a flat
/// one, negative for an inverted one (floating point; orientation is decided exactly
/// elsewhere).
pub fn mean_ratio(c: [DVec3; 4]) -> f64 {
    let v = signed_volume_inexact(c[0], c[1], c[2], c[3]);
    let s = edge_length_squares(c);
    if s <= 0.0 {
        return 0.0;
    }
    let c = (3.0 * v.abs()).cbrt();
    12.0 * c * c / s * v.signum()
}

/// The cube of [`mean_ratio`], `1728 (3V)² / (Σ lᵢⱼ²)³` with the sign of the volume:
/// compares like the mean ratio without a cube root.
pub fn mean_ratio_cubed(c: [DVec3; 4]) -> f64 {
    let v = signed_volume_inexact(c[0], c[1], c[2], c[3]);
    let s = edge_length_squares(c);
    if s <= 0.0 {
        return 0.0;
    }
    1728.0 * 9.0 * v * v / (s * s * s) * v.signum()
}

/// The error a build uses: one of the built-ins, or a custom metric.
#[derive(Clone)]
pub enum ErrorMetric {
    Volume,
    Boundary(BoundaryError),
    Quality,
    Custom(Arc<dyn TetError>),
}

impl ErrorMetric {
    /// `volume`, `boundary` or `quality` (with default parameters).
    pub fn from_name(name: &str) -> Option<ErrorMetric> {
        match name {
            "volume" => Some(ErrorMetric::Volume),
            "boundary" => Some(ErrorMetric::Boundary(BoundaryError::DEFAULT)),
            "quality" => Some(ErrorMetric::Quality),
            _ => None,
        }
    }

    pub fn name(&self) -> &str {
        match self {
            ErrorMetric::Volume => VolumeError.name(),
            ErrorMetric::Boundary(b) => b.name(),
            ErrorMetric::Quality => QualityError.name(),
            ErrorMetric::Custom(c) => c.name(),
        }
    }
}

impl fmt::Debug for ErrorMetric {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ErrorMetric::Boundary(b) => write!(f, "Boundary({b:?})"),
            other => write!(f, "{}", other.name()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn regular() -> [DVec3; 4] {
        [
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(-1.0, -1.0, 1.0),
        ]
    }

    #[test]
    fn mean_ratio_is_one_for_regular_and_zero_for_flat() {
        let c = regular();
        let v = signed_volume_inexact(c[0], c[1], c[2], c[3]);
        let c = if v > 0.0 { c } else { [c[0], c[2], c[1], c[3]] };
        assert!((mean_ratio(c) - 1.0).abs() < 1e-12);
        let flat = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)];
        assert_eq!(mean_ratio(flat), 0.0);
        let skinny = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z * 0.1];
        let q = mean_ratio(skinny);
        assert!((mean_ratio_cubed(skinny) - q * q * q).abs() < 1e-12);
    }

    #[test]
    fn builtin_errors_are_relative() {
        let c = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let s = TetSample {
            corners: c,
            boundary_deviation: 0.0,
            scale: 2.0,
            volume: 1.0 / 3.0,
        };
        assert!((VolumeError.tet_error(&s) - 0.5).abs() < 1e-15);
        // Scaling everything by 10 leaves every error unchanged.
        let big = TetSample {
            corners: c.map(|p| p * 10.0),
            boundary_deviation: 0.0,
            scale: 20.0,
            volume: 1000.0 / 3.0,
        };
        for m in [
            &VolumeError as &dyn TetError,
            &BoundaryError::DEFAULT,
            &QualityError,
        ] {
            let (a, b) = (m.tet_error(&s), m.tet_error(&big));
            assert!((a - b).abs() <= 1e-12 * a.abs(), "{}: {a} vs {b}", m.name());
        }
        let dev = TetSample {
            boundary_deviation: 1.0,
            ..s
        };
        assert_eq!(BoundaryError::DEFAULT.tet_error(&dev), 0.5);
    }
}
