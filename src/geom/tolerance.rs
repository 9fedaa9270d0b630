//! The one tolerance of the library.
//!
//! Every "close enough" decision (a cut snapped to a vertex, a polygon accepted as planar,
//! a boundary allowed to move during simplification) is a *relative* tolerance: a fraction
//! of a local length scale (the edges around a vertex, the polygon's diameter, the mesh's
//! bounding box). Absolute epsilons break as soon as a mesh arrives in millimetres instead
//! of metres, so there are none: code asks a `Tolerance` for a distance, given the scale.

/// A relative tolerance: distances below `relative × scale` count as zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Fraction of the local length scale under which two things count as coincident.
    pub relative: f64,
}

impl Tolerance {
    /// The library's default: 1e-9 of the local length scale. Small enough that no
    /// geometry a user meant is merged, large enough to absorb the rounding of an
    /// intersection computed in doubles.
    pub const DEFAULT: Tolerance = Tolerance { relative: 1e-9 };

    /// A tolerance of `relative` (must be finite and ≥ 0).
    pub fn new(relative: f64) -> Option<Tolerance> {
        (relative.is_finite() && relative >= 0.0).then_some(Tolerance { relative })
    }

    /// The absolute distance this tolerance allows at length scale `scale`.
    pub fn distance(&self, scale: f64) -> f64 {
        self.relative * scale
    }

    /// Whether `value` is negligible at length scale `scale`.
    pub fn is_zero(&self, value: f64, scale: f64) -> bool {
        value.abs() <= self.distance(scale)
    }
}

impl Default for Tolerance {
    fn default() -> Self {
        Tolerance::DEFAULT
    }
}
