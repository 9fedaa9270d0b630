//! Region-of-interest sub-MTs (paper §7, last paragraph): "with our algorithm, we can
//! easily create an MT which corresponds to the specified region of interest, omitting
//! everything outside that region".
//!
//! [`region_of_interest`] does exactly that with the MT cut: it cuts a copy of the MT
//! ([`MtCutter`], every level and the DAG) along each plane bounding the region, with a
//! polygon covering the whole body, so every plane separates the body at every level; after
//! each plane the independent components outside it are dropped, so the next plane cuts
//! only what is left, and those inside every plane are the sub-MT. The result
//! is an MT of its own (roots and drains included) whose every extraction lies in the
//! region, and it is validated before it is returned.
//!
//! * A **box** is bounded by its six face planes (planes the body lies wholly inside of
//!   are skipped).
//! * A **sphere** is bounded by the 14 planes of a circumscribing polyhedron: the six
//!   faces of its bounding cube and the eight planes at distance `r` normal to the cube's
//!   diagonals (a truncated cube). The sub-MT holds everything inside the sphere and what
//!   lies between the sphere and that polyhedron: at most 0.24 `r` beyond the sphere (the
//!   polyhedron's farthest points, where a cube face meets two corner planes, such as
//!   `(r, (√3 - 1) r, 0)` from the centre, lie 1.24 `r` from it).
//!
//! A component lies wholly on one side of every plane once all planes have cut: the test
//! for "inside" is the centroid of any of its tets.

use super::mt_cut::{MtCutStats, MtCutter};
use super::options::CutError;
use crate::geom::{Aabb, CutPolygon, DVec3};
use crate::mt::{GHOST, Mt};
use std::time::Instant;

/// The region a sub-MT keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RoiRegion {
    /// An axis-aligned box.
    Box(Aabb),
    /// A sphere (bounded by a circumscribing polyhedron: see the [module docs](self)).
    Sphere { center: DVec3, radius: f64 },
}

impl RoiRegion {
    /// The bounding planes as (outward unit normal, offset): inside is `n · x ≤ offset`.
    fn planes(&self) -> Vec<(DVec3, f64)> {
        let faces = |b: &Aabb| {
            let mut p = Vec::with_capacity(6);
            for axis in 0..3 {
                let e = DVec3::AXES[axis];
                p.push((-e, -b.min[axis]));
                p.push((e, b.max[axis]));
            }
            p
        };
        match *self {
            RoiRegion::Box(b) => faces(&b),
            RoiRegion::Sphere { center, radius } => {
                let cube = Aabb {
                    min: center - DVec3::splat(radius),
                    max: center + DVec3::splat(radius),
                };
                let mut p = faces(&cube);
                for sx in [-1.0, 1.0] {
                    for sy in [-1.0, 1.0] {
                        for sz in [-1.0, 1.0] {
                            let n = DVec3::new(sx, sy, sz).normalize();
                            p.push((n, n.dot(center) + radius));
                        }
                    }
                }
                p
            }
        }
    }

    fn check(&self) -> Result<(), RoiError> {
        let bad = |m: String| Err(RoiError::InvalidRegion(m));
        match *self {
            RoiRegion::Box(b) => {
                if !b.min.is_finite() || !b.max.is_finite() {
                    return bad(format!("box {} .. {} is not finite", b.min, b.max));
                }
                if !(b.min.cmplt(b.max).all()) {
                    return bad(format!(
                        "box {} .. {} is empty or flat (every min < max)",
                        b.min, b.max
                    ));
                }
            }
            RoiRegion::Sphere { center, radius } => {
                if !(center.is_finite() && radius.is_finite() && radius > 0.0) {
                    return bad(format!(
                        "sphere at {center} with radius {radius} (finite centre, radius > 0)"
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Why no sub-MT was made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RoiError {
    #[error("invalid region: {0}")]
    InvalidRegion(String),
    #[error("the region does not meet the body (bounding box {min} .. {max})")]
    Misses { min: DVec3, max: DVec3 },
    /// The region meets the body's bounding box, but no part of the body was inside it
    /// once cut along its planes.
    #[error(
        "no part of the body lies inside the region (body's bounding box {min} .. {max}): \
         the region lies in a hole or a concavity of the body, or is too small for the cut \
         to resolve there (points closer to a plane than 1e-6 of their edges' length are \
         snapped onto it)"
    )]
    NothingInside { min: DVec3, max: DVec3 },
    #[error("cutting along plane {plane} of the region: {}", cut_text(error))]
    Cut { plane: usize, error: CutError },
    #[error("the sub-MT is not valid ({0})")]
    Invalid(String),
}

/// What making a sub-MT did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RoiStats {
    /// Bounding planes of the region, and those that cut the body (the others leave it
    /// wholly inside).
    pub planes: usize,
    pub planes_cut: usize,
    /// Independent components after the cuts, kept (inside) and dropped.
    pub components_kept: usize,
    pub components_dropped: usize,
    pub tets_before: usize,
    pub tets_after: usize,
    pub fragments_before: usize,
    pub fragments_after: usize,
    /// The cut along each plane that cut the body.
    pub cuts: Vec<MtCutStats>,
    pub seconds: f64,
}

impl RoiStats {
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "planes": self.planes,
            "planes_cut": self.planes_cut,
            "components_kept": self.components_kept,
            "components_dropped": self.components_dropped,
            "tets_before": self.tets_before,
            "tets_after": self.tets_after,
            "fragments_before": self.fragments_before,
            "fragments_after": self.fragments_after,
            "cuts": self.cuts.iter().map(MtCutStats::to_json).collect::<Vec<_>>(),
            "seconds": self.seconds,
        })
    }
}

/// The sub-MT of `mt` inside `region` (see the [module docs](self)); `mt` is not changed.
pub fn region_of_interest(mt: &Mt, region: &RoiRegion) -> Result<(Mt, RoiStats), RoiError> {
    let start = Instant::now();
    region.check()?;
    let bounds = Aabb::from_points(mt.positions());
    let planes = region.planes();
    let mut stats = RoiStats {
        planes: planes.len(),
        tets_before: mt.nb_tets(),
        fragments_before: mt.nb_fragments(),
        ..RoiStats::default()
    };
    // A polygon on each plane reaching past the body's box on every side.
    let reach = 2.0 * bounds.diagonal() + 1.0;
    let corners = bounds_corners(&bounds);
    let mut sub = mt.clone();
    for (k, &(n, offset)) in planes.iter().enumerate() {
        let d: Vec<f64> = corners.iter().map(|c| n.dot(*c) - offset).collect();
        if d.iter().all(|&x| x >= 0.0) {
            return Err(RoiError::Misses {
                min: bounds.min,
                max: bounds.max,
            });
        }
        // Planes are tested against what is left of the body, which shrinks as they cut.
        let left = bounds_corners(&Aabb::from_points(sub.positions()));
        if left.iter().all(|c| n.dot(*c) <= offset) {
            continue;
        }
        let origin = bounds.center() - n * (n.dot(bounds.center()) - offset);
        let u = n.any_orthonormal_vector() * reach;
        let w = n.cross(u);
        let square = [
            origin - u - w,
            origin + u - w,
            origin + u + w,
            origin - u + w,
        ];
        let polygon = CutPolygon::new(&square)
            .map_err(|e| RoiError::InvalidRegion(format!("plane {k} gives no polygon: {e}")))?;
        let mut cutter = MtCutter::new(sub, MtCutter::DEFAULT_OPTIONS)
            .map_err(|error| RoiError::Cut { plane: k, error })?;
        let s = cutter
            .cut(&polygon)
            .map_err(|error| RoiError::Cut { plane: k, error })?;
        stats.planes_cut += 1;
        stats.cuts.push(s);
        // The plane cut the body through at every level: each component lies on one side
        // of it. Those outside are dropped now, so that the next planes cut only what
        // is left (cut whole, the body grew with every plane: 14 planes of a sphere made
        // a 6,000-tet model's pool a million tets).
        let cut = cutter.into_mt();
        let samples = component_samples(&cut);
        let keep: Vec<usize> = (0..samples.len())
            .filter(|&c| samples[c].is_some_and(|p| n.dot(p) <= offset))
            .collect();
        if keep.is_empty() {
            return Err(RoiError::NothingInside {
                min: bounds.min,
                max: bounds.max,
            });
        }
        stats.components_dropped += samples.len() - keep.len();
        sub = if keep.len() < samples.len() {
            cut.select_components(&keep)
        } else {
            cut
        };
    }
    stats.components_kept = sub.nb_components();
    let report = sub.validate();
    if !report.is_valid() {
        return Err(RoiError::Invalid(report.to_string()));
    }
    stats.tets_after = sub.nb_tets();
    stats.fragments_after = sub.nb_fragments();
    stats.seconds = start.elapsed().as_secs_f64();
    Ok((sub, stats))
}

/// A cut's error as a region's plane meets it: the MT cut's refusal names a scalpel's
/// known cause, which is not what a region's planes (each through the whole body) do.
fn cut_text(e: &CutError) -> String {
    match e {
        CutError::MtInconsistent { fragment, detail } => format!(
            "the MT cut would leave fragment {fragment} inconsistent ({detail}) and was \
             refused; seen with regions far smaller than the tets around them, where the \
             planes cut the same few tets again and again: a larger region may be cut"
        ),
        e => e.to_string(),
    }
}

/// A point inside each independent component of `mt` (the centroid of the first real tet
/// it creates; `None` for a component without one).
fn component_samples(mt: &Mt) -> Vec<Option<DVec3>> {
    let (count, label) = mt.fragment_components();
    let mut sample: Vec<Option<DVec3>> = vec![None; count];
    for (a, c, _) in mt.arcs() {
        let k = label[c.idx()] as usize;
        if sample[k].is_some() {
            continue;
        }
        let real = mt
            .arc_tets(a)
            .map(|t| mt.tet(crate::mesh::TetId::from_usize(t)))
            .find(|tet| tet[3] != GHOST);
        if let Some(tet) = real {
            sample[k] = Some(tet.iter().map(|v| mt.positions()[v.idx()]).sum::<DVec3>() * 0.25);
        }
    }
    sample
}

fn bounds_corners(b: &Aabb) -> [DVec3; 8] {
    std::array::from_fn(|i| {
        DVec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        )
    })
}
