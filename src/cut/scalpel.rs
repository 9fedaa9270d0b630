//! Progressive scalpel cuts of an MT (paper §5's interaction, direct form): a straight
//! blade moved in time steps, each step cutting every level of the MT with the area the
//! blade swept since the last step ([`scalpel_sweep`](crate::geom::scalpel_sweep): one
//! quadrilateral, or two triangles when the sweep is not planar), so an incision grows step
//! by step and may end inside the body. The time-critical form, where each step cuts the
//! simulation's current mesh first and the MT later, is [`super::LiveMt`] given the same
//! sweeps.
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
//!   same tilt in 24 steps), and for a turning blade whose edge ends inside pinion or
//!   liver, some steps would break a fragment where the levels disagree on the last
//!   crack's end. The MT cut checks each fragment it changed and refuses such a step
//!   ([`CutError::MtInconsistent`]), the MT left as it was; the CLI stops there (or, with
//!   `--skip-refused`, begins a new crack a tenth of the way into the step,
//!   [`Scalpel::step_after_gap`], and when that is refused too moves the blade on without
//!   cutting, [`Scalpel::skip_to`]).
//! * **A refused sweep is cut as another split of it.** A non-planar sweep is two
//!   triangles, the second continuing the first at an angle along a diagonal; where the
//!   levels disagree at that diagonal, they often agree at the other. [`Scalpel::step`]
//!   cuts a sweep the MT refuses as its next split ([`scalpel_sweep_splits`]: the other
//!   diagonal's triangles, then each pair in the other order), each tried on the MT as
//!   the step found it, and refuses the step only when none is taken
//!   ([`ScalpelStep::split`] says which was cut). The crack then follows the other fold
//!   of the blade's twisted sweep, no farther from the swept surface than the first; a
//!   refused step costs up to four MT cuts and a copy of the cutter per split. The blade
//!   tilting in 20 steps, whose 11th step was refused, takes every step so.
//!   [`super::LiveMt::cut_sweep`] does the same on a body at rest: its current mesh is
//!   cut first, with the first split, and replaced by the MT's extraction when the MT
//!   takes another.
//! * Random paths (turning, leaning, through the body or ending inside it; the plain-mesh
//!   engine takes every step of them, tests/cut_scalpel.rs) still meet refusals: 25, 28
//!   and 29 of 100 paths on fandisk's, pinion's and liver's MTs have a step refused (46,
//!   36 and 37 with the first split only), and, with the refused steps skipped, 212, 148
//!   and 279 of their 6,111 steps are (395, 268 and 395); tests/mt_scalpel.rs has 25 per
//!   mesh as an ignored known failure. Most come in runs along a path, where the blade's
//!   end passes close to the body's boundary. On an MT of one level (the mesh alone) 0, 0
//!   and 2 of 25 paths still do (4, 2 and 4 with the first split; another ignored test):
//!   the MT cut's copies of a turning tip are not yet the plain engine's. Only polygons
//!   continuing the last one at an angle are
//!   refused, the more often the steeper the angle (5 % below 2°, 30 % to 8°, 75–86 %
//!   above), and a leaning blade's two triangles per step meet at steep angles (its
//!   lean's change along the blade over the step's advance). See the README, "A scalpel
//!   on a plain mesh", for what was tried.
//!
//! # Steps smaller than the tets
//!
//! Each cut that extends a crack splits again the tets at its front, which the last cut
//! left partially cut. A blade moved in steps much shorter than the mesh's edges (a
//! simulation's frame rate) does so at every step, and the front fills with ever thinner
//! tets. Measured with the plain-mesh engine and [`CutOptions::SCALPEL`], a straight blade
//! crossing three quarters of fandisk (its median edge 4.4 % of that distance): in 30 steps
//! the mesh gains 9,252 tets, in 300 steps 190,257, its smallest dihedral angle going from
//! 6e-3° to 5e-4°. An [`Incision`] with a `min_advance` defers a step until the blade is
//! that far from where the crack ends, then cuts everything swept since in one polygon:
//! with half the median edge, the 300 steps make 43 cuts and 11,989 tets (with one edge,
//! 22 cuts and 7,584 tets). On an MT it also spares the levels steps at an angle: a
//! blade turning by 0.5° per step, refused at step 41, 56 and 42 of fandisk's, pinion's
//! and liver's MTs when cut at every step (where the levels disagree, or an extraction
//! between the finest and the coarsest would be pinched at a crack tip: see
//! [`super::mt_cut`]'s limits), goes through all 128 steps of fandisk's and
//! pinion's deferred at half an edge (liver's refuses step 48, and takes them all at one
//! edge). The price is a crack lagging the blade by less than `min_advance`;
//! [`Incision::catch_up`] cuts what is left at the end of a path.

use super::mt_cut::{MtCutStats, MtCutter};
use super::options::{CutError, CutOptions};
use crate::geom::{CutPolygon, DVec3, PolygonError, SWEEP_PLANARITY, scalpel_sweep_splits};
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
    #[error("min_advance is {0}: expected a finite length >= 0 (0 cuts every step)")]
    MinAdvance(f64),
    #[error("the gap is {0}: expected a fraction of the step strictly between 0 and 1")]
    Gap(f64),
}

/// How far a blade at `to` has moved from `from` across its own line: the larger distance
/// of `to`'s two ends from the line through `from` (a blade sliding along its edge sweeps
/// nothing; one turning about its middle has moved as far as its ends).
pub fn blade_advance(from: Blade, to: Blade) -> f64 {
    let axis = from[1] - from[0];
    let off_line = |p: DVec3| {
        let d = p - from[0];
        let len2 = axis.length_squared();
        if len2 > 0.0 {
            (d - axis * (d.dot(axis) / len2)).length()
        } else {
            d.length()
        }
    };
    off_line(to[0]).max(off_line(to[1]))
}

/// A blade moving through a body in steps, and where its crack ends (see the [module
/// docs](self#steps-smaller-than-the-tets)): a step is cut from where the crack ends to
/// the blade's new position, or deferred while the blade is less than `min_advance` from
/// that end ([`blade_advance`]). With `min_advance` 0 every step that moves the blade is
/// cut, which is what [`Scalpel`] does by default.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Incision {
    blade: Blade,
    end: Blade,
    min_advance: f64,
}

impl Incision {
    /// An incision about to start, its blade at `blade`.
    pub fn new(blade: Blade, min_advance: f64) -> Result<Incision, ScalpelError> {
        crate::geom::check_points(&blade)?;
        let mut incision = Incision {
            blade,
            end: blade,
            min_advance: 0.0,
        };
        incision.set_min_advance(min_advance)?;
        Ok(incision)
    }

    /// Defers, from now on, the steps that leave the blade less than `min_advance` from
    /// where the crack ends (a finite length ≥ 0; otherwise refused, nothing changed).
    pub fn set_min_advance(&mut self, min_advance: f64) -> Result<(), ScalpelError> {
        if !(min_advance.is_finite() && min_advance >= 0.0) {
            return Err(ScalpelError::MinAdvance(min_advance));
        }
        self.min_advance = min_advance;
        Ok(())
    }

    /// Where the blade is.
    pub fn blade(&self) -> Blade {
        self.blade
    }

    /// Where the crack ends: the blade's position at the last step that cut.
    pub fn end(&self) -> Blade {
        self.end
    }

    pub fn min_advance(&self) -> f64 {
        self.min_advance
    }

    /// Whether steps were deferred: the blade is not where the crack ends.
    pub fn is_behind(&self) -> bool {
        self.blade != self.end
    }

    /// Moves the blade to `to` without cutting, and the crack's end with it: the next step
    /// begins a crack at `to`, the area from where the crack ended to `to` left uncut (a
    /// step the model refused, skipped: see [`Scalpel::skip_to`]).
    pub fn skip_to(&mut self, to: Blade) -> Result<(), PolygonError> {
        crate::geom::check_points(&to)?;
        self.blade = to;
        self.end = to;
        Ok(())
    }

    /// Moves the blade to `to`, passing `cut` the polygons to cut: the area swept from
    /// where the crack ends (one quadrilateral, or two triangles when not planar), or none
    /// when the step is deferred or the blade ends where the crack does. Returns whether
    /// it cut. On an error (of the sweep, or the first returned by `cut`) the incision is
    /// as it was.
    pub fn step<E: From<PolygonError>>(
        &mut self,
        to: Blade,
        cut: impl FnMut(&CutPolygon) -> Result<(), E>,
    ) -> Result<bool, E> {
        self.step_split(to, 0, cut)
    }

    /// [`step`](Self::step), cutting the `split`th way of splitting the sweep
    /// ([`scalpel_sweep_splits`]; `split` below [`splits_to`](Self::splits_to)'s length).
    fn step_split<E: From<PolygonError>>(
        &mut self,
        to: Blade,
        split: usize,
        cut: impl FnMut(&CutPolygon) -> Result<(), E>,
    ) -> Result<bool, E> {
        crate::geom::check_points(&to)?;
        if self.defers(to) {
            self.blade = to;
            return Ok(false);
        }
        self.cut_to(to, split, cut)
    }

    /// Whether a step to `to` is deferred (see [`step`](Self::step)).
    fn defers(&self, to: Blade) -> bool {
        blade_advance(self.end, to) < self.min_advance
    }

    /// The ways a step to `to` may cut the sweep (`catch_up`: what
    /// [`catch_up`](Self::catch_up) cuts, `to` being the blade), as the number of polygons
    /// of each ([`scalpel_sweep_splits`]): none when deferred or when the blade ends where
    /// the crack does, nor for a sweep that is no polygon (the step fails on it before
    /// cutting anything).
    fn splits_to(&self, to: Blade, catch_up: bool) -> Vec<usize> {
        if (!catch_up && self.defers(to)) || to == self.end {
            return Vec::new();
        }
        scalpel_sweep_splits(self.end, to, SWEEP_PLANARITY)
            .map_or(Vec::new(), |s| s.iter().map(Vec::len).collect())
    }

    /// Cuts what deferred steps left (nothing when none were): the crack then ends at the
    /// blade. Returns whether it cut.
    pub fn catch_up<E: From<PolygonError>>(
        &mut self,
        cut: impl FnMut(&CutPolygon) -> Result<(), E>,
    ) -> Result<bool, E> {
        self.catch_up_split(0, cut)
    }

    /// [`catch_up`](Self::catch_up) cutting the `split`th way of splitting the sweep.
    fn catch_up_split<E: From<PolygonError>>(
        &mut self,
        split: usize,
        cut: impl FnMut(&CutPolygon) -> Result<(), E>,
    ) -> Result<bool, E> {
        self.cut_to(self.blade, split, cut)
    }

    fn cut_to<E: From<PolygonError>>(
        &mut self,
        to: Blade,
        split: usize,
        mut cut: impl FnMut(&CutPolygon) -> Result<(), E>,
    ) -> Result<bool, E> {
        self.sweep_to(to, |mut splits| {
            splits.swap_remove(split).iter().try_for_each(&mut cut)
        })
    }

    /// [`step`](Self::step), passing `cut` every way of splitting the sweep at once
    /// ([`scalpel_sweep_splits`]: the first is what `step` cuts), for a cut that tries the
    /// others itself when the first is refused ([`super::LiveMt::cut_sweep`]); `cut` is
    /// not called when the step is deferred or the blade ends where the crack does.
    pub fn step_sweep<E: From<PolygonError>>(
        &mut self,
        to: Blade,
        cut: impl FnOnce(Vec<Vec<CutPolygon>>) -> Result<(), E>,
    ) -> Result<bool, E> {
        crate::geom::check_points(&to)?;
        if self.defers(to) {
            self.blade = to;
            return Ok(false);
        }
        self.sweep_to(to, cut)
    }

    /// [`catch_up`](Self::catch_up), passing `cut` every split of the sweep as
    /// [`step_sweep`](Self::step_sweep) does.
    pub fn catch_up_sweep<E: From<PolygonError>>(
        &mut self,
        cut: impl FnOnce(Vec<Vec<CutPolygon>>) -> Result<(), E>,
    ) -> Result<bool, E> {
        self.sweep_to(self.blade, cut)
    }

    /// Cuts the sweep from where the crack ends to `to` by `cut`, given all its splits;
    /// the crack then ends at `to`.
    fn sweep_to<E: From<PolygonError>>(
        &mut self,
        to: Blade,
        cut: impl FnOnce(Vec<Vec<CutPolygon>>) -> Result<(), E>,
    ) -> Result<bool, E> {
        if to == self.end {
            self.blade = to;
            return Ok(false);
        }
        cut(scalpel_sweep_splits(self.end, to, SWEEP_PLANARITY)?)?;
        self.blade = to;
        self.end = to;
        Ok(true)
    }
}

/// What one step did: the polygons cut (one or two; none for a deferred step) and their
/// statistics.
#[derive(Clone, Debug, Default)]
pub struct ScalpelStep {
    pub cuts: Vec<MtCutStats>,
    /// Which way of splitting the sweep was cut ([`scalpel_sweep_splits`]): 0, the first
    /// ([`crate::geom::scalpel_sweep`]'s), unless the MT refused those before it (see
    /// [`Scalpel::step`]).
    pub split: usize,
    /// The blade moved less than the scalpel's `min_advance` from where the crack ends:
    /// nothing was cut, and a later step (or [`Scalpel::catch_up`]) cuts the area.
    pub deferred: bool,
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
    incision: Incision,
}

impl Scalpel {
    /// The MT cut options of a scalpel: [`MtCutter::DEFAULT_OPTIONS`] (see the module
    /// docs); the same as [`CutOptions::SCALPEL`] for a plain mesh.
    pub const OPTIONS: CutOptions = MtCutter::DEFAULT_OPTIONS;

    /// A scalpel on `mt` (which should be valid), its blade at `blade`, cutting every step
    /// (a `min_advance` of 0: see [`Scalpel::set_min_advance`]).
    pub fn new(mt: Mt, blade: Blade) -> Result<Scalpel, ScalpelError> {
        Ok(Scalpel {
            incision: Incision::new(blade, 0.0)?,
            cutter: MtCutter::new(mt, Scalpel::OPTIONS)?,
        })
    }

    /// Defers the steps that leave the blade less than `min_advance` (a length) from where
    /// its crack ends ([`Incision`]; half the median edge of the finest mesh,
    /// [`crate::mesh::TetMesh::median_edge_length`], keeps a blade moved in tiny steps from
    /// filling the crack's front with slivers). A value that is not a finite length ≥ 0 is
    /// refused, the scalpel unchanged.
    pub fn set_min_advance(&mut self, min_advance: f64) -> Result<(), ScalpelError> {
        self.incision.set_min_advance(min_advance)
    }

    /// Moves the blade to `to`, cutting the area swept since the crack's end, or deferring
    /// the step (see [`Scalpel::set_min_advance`]). A blade that did not move cuts
    /// nothing. A sweep the MT refuses ([`CutError::MtInconsistent`]) is cut as its next
    /// split ([`scalpel_sweep_splits`]; the module docs' limits), and the step refused,
    /// with the first split's error, only when none is taken. On error the blade and the
    /// MT stay as they were, byte for byte, also when
    /// the second triangle of a non-planar sweep is refused after the first was cut: the
    /// step then goes back to a copy of the cutter taken before the first. The copy is
    /// taken for non-planar steps only and costs in proportion to the MT: 0.4–1.4 ms on
    /// the shared meshes' MTs (150–270 k pool tets) against 15–95 ms for such a step
    /// through the body (a blade tilting across them in 10 steps).
    pub fn step(&mut self, to: Blade) -> Result<ScalpelStep, ScalpelError> {
        if to == self.incision.blade() {
            return Ok(ScalpelStep {
                cuts: Vec::new(),
                split: 0,
                deferred: self.incision.is_behind(),
            });
        }
        let splits = self.incision.splits_to(to, false);
        let (cuts, split) =
            self.whole_step(&splits, |incision, k, cut| incision.step_split(to, k, cut))?;
        Ok(ScalpelStep {
            cuts,
            split,
            // A step that cut leaves the crack at the blade.
            deferred: self.incision.is_behind(),
        })
    }

    /// Cuts the area deferred steps left, so the crack ends at the blade (at the end of a
    /// path); nothing when none was deferred. On error, as [`step`](Self::step).
    pub fn catch_up(&mut self) -> Result<ScalpelStep, ScalpelError> {
        let splits = self.incision.splits_to(self.incision.blade(), true);
        let (cuts, split) =
            self.whole_step(&splits, |incision, k, cut| incision.catch_up_split(k, cut))?;
        Ok(ScalpelStep {
            cuts,
            split,
            deferred: false,
        })
    }

    /// Runs `step` on the incision with the cutter's cut, all of it or none: with more
    /// than one polygon to cut, a copy of the cutter is taken first and put back when a
    /// later polygon fails after an earlier one was cut (a polygon that fails alone gives
    /// its cut back itself, [`MtCutter::cut`]). `splits` are the polygon counts of the
    /// sweep's splits: when the MT refuses the first ([`CutError::MtInconsistent`]), the
    /// others are tried in turn; when none is taken, the first one's refusal is returned
    /// (that of [`crate::geom::scalpel_sweep`]'s polygons). Returns the cuts and the split
    /// cut.
    fn whole_step(
        &mut self,
        splits: &[usize],
        mut step: impl FnMut(
            &mut Incision,
            usize,
            &mut dyn FnMut(&CutPolygon) -> Result<(), ScalpelError>,
        ) -> Result<bool, ScalpelError>,
    ) -> Result<(Vec<MtCutStats>, usize), ScalpelError> {
        let mut k = 0;
        let mut first_refusal = None;
        loop {
            let saved = (splits.get(k).copied().unwrap_or(0) > 1).then(|| self.cutter.snapshot());
            let mut cuts = Vec::new();
            let result = step(
                &mut self.incision,
                k,
                &mut cut_into(&mut self.cutter, &mut cuts),
            );
            match result {
                Ok(_) => return Ok((cuts, k)),
                Err(e) => {
                    if let Some(saved) = saved.filter(|_| !cuts.is_empty()) {
                        self.cutter = saved;
                    }
                    // Another split is tried once the first was refused, whatever stops
                    // the later ones; the first's refusal is what the step reports.
                    let first = match first_refusal.take() {
                        Some(first) => first,
                        None if matches!(e, ScalpelError::Cut(CutError::MtInconsistent { .. })) => {
                            e
                        }
                        None => return Err(e),
                    };
                    if k + 1 >= splits.len() {
                        return Err(first);
                    }
                    first_refusal = Some(first);
                    k += 1;
                }
            }
        }
    }

    pub fn blade(&self) -> Blade {
        self.incision.blade()
    }

    /// Moves the blade to `to` without cutting ([`Incision::skip_to`]): after a step the
    /// MT refused, the next step then begins a new crack at `to` instead of sweeping again
    /// from where the crack ends, which continues the last polygon at the angle that was
    /// refused (measured in the module docs' limits), and the refused step's area stays
    /// uncut.
    pub fn skip_to(&mut self, to: Blade) -> Result<(), ScalpelError> {
        Ok(self.incision.skip_to(to)?)
    }

    /// Begins a new crack `gap` of the way from where the crack ends to `to` (a fraction
    /// of the sweep, its blade's ends moved alike) and cuts from there to `to`, as
    /// [`step`](Self::step) would: after a step the MT refused, the incision then keeps a
    /// bridge of that fraction of the step, where [`skip_to`](Self::skip_to) leaves the
    /// whole step uncut. A step continuing the last crack at an angle is what the MT
    /// refuses (the module docs' limits); a crack begun apart from it is often taken. On
    /// error (a `gap` not strictly between 0 and 1, or that cut refused too) the scalpel
    /// is as it was, the crack where it ended. Measured (a release probe, `gap` 0.1, what
    /// `mtcut scalpel --skip-refused` tries): a shallow incision turning by 4°, 8° or 16°
    /// per step, whose refused steps `skip_to` leaves uncut (2, 1 and 1 of 17 on pinion,
    /// 6, 4 and 2 on liver), leaves none so: those and some after them are cut from a
    /// tenth of the way (3, 3 and 1 steps on pinion, 12, 7 and 1 on liver), each leaving
    /// a bridge; on 25 random paths per shared mesh, the steps left uncut go from 115, 70
    /// and 127 to 113, 65 and 120.
    pub fn step_after_gap(&mut self, to: Blade, gap: f64) -> Result<ScalpelStep, ScalpelError> {
        if !(gap > 0.0 && gap < 1.0) {
            return Err(ScalpelError::Gap(gap));
        }
        let (was, end) = (self.incision, self.incision.end());
        self.incision
            .skip_to([end[0].lerp(to[0], gap), end[1].lerp(to[1], gap)])?;
        self.step(to).inspect_err(|_| self.incision = was)
    }

    /// The blade and where its crack ends.
    pub fn incision(&self) -> &Incision {
        &self.incision
    }

    pub fn mt(&self) -> &Mt {
        self.cutter.mt()
    }

    /// The MT's cutter (its options, vertex scales and last cut's new vertices).
    pub fn cutter(&self) -> &MtCutter {
        &self.cutter
    }

    /// The MT (deferred steps not cut: see [`Scalpel::catch_up`]).
    pub fn into_mt(self) -> Mt {
        self.cutter.into_mt()
    }
}

/// What an [`Incision`] of a [`Scalpel`] cuts with: `cutter`, each cut's statistics
/// appended to `cuts`.
fn cut_into<'a>(
    cutter: &'a mut MtCutter,
    cuts: &'a mut Vec<MtCutStats>,
) -> impl FnMut(&CutPolygon) -> Result<(), ScalpelError> + 'a {
    move |polygon| {
        cuts.push(cutter.cut(polygon)?);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn blade(x: f64) -> Blade {
        [DVec3::new(x, 0.0, -1.0), DVec3::new(x, 0.0, 1.0)]
    }

    /// The polygons an incision passes to its cut, as their corner lists.
    fn stepped(
        incision: &mut Incision,
        to: Blade,
        catch_up: bool,
    ) -> Result<Vec<Vec<DVec3>>, PolygonError> {
        let mut cut = Vec::new();
        let mut take = |p: &CutPolygon| -> Result<(), PolygonError> {
            cut.push(p.points().to_vec());
            Ok(())
        };
        if catch_up {
            incision.catch_up(&mut take)?;
        } else {
            incision.step(to, &mut take)?;
        }
        Ok(cut)
    }

    #[test]
    fn advance_is_measured_across_the_blade() {
        let from = blade(0.0);
        assert_eq!(blade_advance(from, blade(0.25)), 0.25);
        // Sliding along its own line sweeps nothing.
        let slid = from.map(|p| p + DVec3::new(0.0, 0.0, 3.0));
        assert_eq!(blade_advance(from, slid), 0.0);
        // Turning about its middle: as far as its ends moved.
        let turned = [DVec3::new(-0.5, 0.0, -1.0), DVec3::new(0.5, 0.0, 1.0)];
        assert_eq!(blade_advance(from, turned), 0.5);
    }

    #[test]
    fn short_steps_are_deferred_and_cut_together_from_where_the_crack_ends() {
        let mut incision = Incision::new(blade(0.0), 0.3).unwrap();
        assert!(
            stepped(&mut incision, blade(0.1), false)
                .unwrap()
                .is_empty()
        );
        assert!(
            stepped(&mut incision, blade(0.2), false)
                .unwrap()
                .is_empty()
        );
        assert!(incision.is_behind());
        assert_eq!(incision.end(), blade(0.0));
        // 0.35 from the crack's end: one quadrilateral from it.
        let cut = stepped(&mut incision, blade(0.35), false).unwrap();
        assert_eq!(cut.len(), 1);
        let xs: Vec<f64> = cut[0].iter().map(|p| p.x).collect();
        assert!(xs.contains(&0.0) && xs.contains(&0.35), "{xs:?}");
        assert!(!incision.is_behind());
        // Left behind at the end of a path: caught up.
        assert!(
            stepped(&mut incision, blade(0.5), false)
                .unwrap()
                .is_empty()
        );
        let cut = stepped(&mut incision, blade(0.5), true).unwrap();
        assert_eq!(cut.len(), 1);
        assert_eq!(incision.end(), blade(0.5));
        assert!(stepped(&mut incision, blade(0.5), true).unwrap().is_empty());
    }

    #[test]
    fn without_min_advance_every_move_is_cut() {
        let mut incision = Incision::new(blade(0.0), 0.0).unwrap();
        for k in 1..4 {
            let cut = stepped(&mut incision, blade(1e-3 * k as f64), false).unwrap();
            assert_eq!(cut.len(), 1);
        }
        // A blade that did not move cuts nothing.
        assert!(
            stepped(&mut incision, blade(3e-3), false)
                .unwrap()
                .is_empty()
        );
    }

    #[test]
    fn a_failed_cut_leaves_the_incision_as_it_was() {
        let mut incision = Incision::new(blade(0.0), 0.1).unwrap();
        let was = incision;
        let failed = incision.step(blade(0.5), |_| Err(PolygonError::Degenerate));
        assert!(failed.is_err());
        assert_eq!(incision, was);
        // A bad position too.
        let bad = [DVec3::new(f64::NAN, 0.0, 0.0), DVec3::Z];
        assert!(incision.step(bad, |_| Ok::<(), PolygonError>(())).is_err());
        assert_eq!(incision, was);
    }

    #[test]
    fn a_skipped_step_moves_the_crack_end_without_cutting() {
        let mut incision = Incision::new(blade(0.0), 0.0).unwrap();
        stepped(&mut incision, blade(0.2), false).unwrap();
        incision.skip_to(blade(0.5)).unwrap();
        assert_eq!((incision.blade(), incision.end()), (blade(0.5), blade(0.5)));
        // The next step begins at the skipped-to blade: the area 0.2..0.5 stays uncut.
        let cut = stepped(&mut incision, blade(0.7), false).unwrap();
        let xs: Vec<f64> = cut[0].iter().map(|p| p.x).collect();
        assert!(xs.iter().all(|&x| x == 0.5 || x == 0.7), "{xs:?}");
        // A bad position is refused, the incision as it was.
        let was = incision;
        let bad = [DVec3::new(0.0, f64::INFINITY, 0.0), DVec3::Z];
        assert!(incision.skip_to(bad).is_err());
        assert_eq!(incision, was);
    }

    #[test]
    fn min_advance_must_be_a_length() {
        for bad in [-1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                Incision::new(blade(0.0), bad),
                Err(ScalpelError::MinAdvance(_))
            ));
        }
    }
}
