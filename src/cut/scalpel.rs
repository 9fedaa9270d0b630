//! Progressive scalpel cuts of an MT (paper §5's interaction, direct form): a straight
//! blade moved in time steps, each step cutting every level of the MT with the area the
//! blade swept since the last step ([`scalpel_sweep`]: one quadrilateral, or two triangles
//! when the sweep is not planar), so an incision grows step by step and may end inside the
//! body. The time-critical form, where each step cuts the simulation's current mesh first
//! and the MT later, is [`super::LiveMt`] given the same sweeps.
//!
//! The MT cut runs with [`MtCutter::DEFAULT_OPTIONS`], whose face-point margin is the
//! smallest ([`super::MIN_FACE_POINT_MARGIN`]): each step continues the last one's crack,
//! whose tips then lie within the contour band of the new polygon (see
//! [`super::mt_cut`]; with the engine's default margin, tips in the middle of their faces
//! lie beyond it and the levels disagree).
//!
//! # Limits (measured; tests/mtcut_cut.rs and tests/mt_scalpel.rs)
//!
//! * A blade moving in its own plane (every step coplanar with the last, cutting through
//!   the body's depth) keeps every level valid and separates the body when it has crossed
//!   it.
//! * So do an incision ending inside the body and extended later, and a second incision
//!   ending on the first (T) or crossing it (X), in any plane (tests/mt_scalpel.rs).
//! * A step at an angle to the last (a turning path, a tilting blade) meets the last
//!   step's crack at an angle: the tips where it ended take one copy each, for the tets
//!   outside the wedge between the two cracks ([`super::mt_cut`]'s limits). An incision
//!   turning by 8° per step keeps every level valid on the three shared meshes while it
//!   stays inside, and cuts a corner off each when extended; a blade tilting back and
//!   forth across them in 10 steps separates each. At steeper angles between steps (the
//!   same tilt in 20 steps), and for a turning blade whose edge ends inside pinion or
//!   liver, some steps would break a fragment where the levels disagree on the last
//!   crack's end. The MT cut checks each fragment it changed and refuses such a step
//!   ([`CutError::MtInconsistent`]), the MT left as it was; the CLI stops there.

use super::mt_cut::{MtCutStats, MtCutter};
use super::options::{CutError, CutOptions};
use crate::geom::{DVec3, PolygonError, SWEEP_PLANARITY, scalpel_sweep};
use crate::mt::Mt;

/// A blade position: the segment between two points (the cutting edge).
pub type Blade = [DVec3; 2];

/// Why a scalpel step failed.
#[derive(Debug, thiserror::Error)]
pub enum ScalpelError {
    #[error("the blade's sweep is not a cutting polygon: {0}")]
    Sweep(#[from] PolygonError),
    #[error(transparent)]
    Cut(#[from] CutError),
}

/// What one step did: the polygons cut (one or two) and their statistics.
#[derive(Clone, Debug, Default)]
pub struct ScalpelStep {
    pub cuts: Vec<MtCutStats>,
}

impl ScalpelStep {
    /// Tets of any level the step replaced.
    pub fn tets_cut(&self) -> usize {
        self.cuts.iter().map(|s| s.tets_cut).sum()
    }

    /// Seconds the step took (its cuts).
    pub fn seconds(&self) -> f64 {
        // Folded from +0: an empty float sum is -0, printed "-0.0000 s" for a pause.
        self.cuts.iter().fold(0.0, |t, s| t + s.time.total)
    }
}

/// An MT and a blade moving through it (see the [module docs](self)).
pub struct Scalpel {
    cutter: MtCutter,
    blade: Blade,
}

impl Scalpel {
    /// The MT cut options of a scalpel: [`MtCutter::DEFAULT_OPTIONS`] (see the module
    /// docs); the same as [`CutOptions::SCALPEL`] for a plain mesh.
    pub const OPTIONS: CutOptions = MtCutter::DEFAULT_OPTIONS;

    /// A scalpel on `mt` (which should be valid), its blade at `blade`.
    pub fn new(mt: Mt, blade: Blade) -> Result<Scalpel, ScalpelError> {
        crate::geom::check_points(&blade)?;
        Ok(Scalpel {
            cutter: MtCutter::new(mt, Scalpel::OPTIONS)?,
            blade,
        })
    }

    /// Moves the blade to `to`, cutting the area it sweeps. A blade that did not move cuts
    /// nothing. On error the blade stays where it was and so does the MT, except after a
    /// non-planar sweep whose second triangle failed (the first was cut).
    pub fn step(&mut self, to: Blade) -> Result<ScalpelStep, ScalpelError> {
        if to == self.blade {
            return Ok(ScalpelStep::default());
        }
        let polygons = scalpel_sweep(self.blade, to, SWEEP_PLANARITY)?;
        let mut step = ScalpelStep::default();
        for p in &polygons {
            step.cuts.push(self.cutter.cut(p)?);
        }
        self.blade = to;
        Ok(step)
    }

    pub fn blade(&self) -> Blade {
        self.blade
    }

    pub fn mt(&self) -> &Mt {
        self.cutter.mt()
    }

    pub fn into_mt(self) -> Mt {
        self.cutter.into_mt()
    }
}
