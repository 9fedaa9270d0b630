//! `mtcut_live`: the time-critical cut of a deformed body (paper section 5, `cut::LiveMt`) - a
//! model at rest and the simulation's current mesh, whose positions the host sets every
//! time step; a cut is made on the current mesh at once and on the model later.

use super::cut::{corners, cut_failure, mtcut_cut_stats, points, polygon_failure};
use super::guard::{Out, OutSlice, deref, deref_mut, run, run_count};
use super::mesh::mtcut_mesh;
use super::mt::{extract_failure, mt_ref, mtcut_extract_options, mtcut_mt};
use super::status::{Failure, FfiResult, MTCUT_STATUS_PENDING_WORK, mtcut_status};
use super::versioned::{Versioned, VersionedOut, read_optional};
use crate::cut::{CutError, LiveError, LiveMt, PendingBudget, Scalpel};
use crate::geom::{CutPolygon, SWEEP_PLANARITY, scalpel_sweep_splits};
use crate::mt::Mt;
use std::mem::offset_of;
use std::time::Duration;

/// A model with the simulation's current mesh (opaque): made by `mtcut_live_new`,
/// released with `mtcut_live_free`. The current mesh is an extraction of the model; the
/// host moves its vertices (`mtcut_live_set_positions`) and cuts it
/// (`mtcut_live_cut`: the current mesh at once, the model later through
/// `mtcut_live_process_pending`). Each current vertex is named by its model vertex
/// (`mtcut_live_copy_mt_vertex_ids`), so the host can map its own per-vertex state.
pub struct mtcut_live {
    live: LiveMt,
}

/// The live model behind a handle argument.
///
/// # Safety
/// A non-NULL `live` must be a live handle from this library.
unsafe fn live_ref<'a>(live: *const mtcut_live) -> FfiResult<&'a LiveMt> {
    // SAFETY: forwarded contract.
    Ok(&unsafe { deref(live, "live") }?.live)
}

/// # Safety
/// A non-NULL `live` must be a live handle from this library, used by no other thread.
unsafe fn live_mut<'a>(live: *mut mtcut_live) -> FfiResult<&'a mut LiveMt> {
    // SAFETY: forwarded contract.
    Ok(&mut unsafe { deref_mut(live, "live") }?.live)
}

fn live_failure(e: LiveError) -> Failure {
    match e {
        LiveError::Cut(e) => cut_failure(e),
        LiveError::Extract(e) => extract_failure(e),
        e @ LiveError::Pending { .. } => Failure::new(MTCUT_STATUS_PENDING_WORK, e.to_string()),
        e @ LiveError::Polygon(_) => Failure::invalid(e.to_string()),
    }
}

/// A live model on a copy of `mt` (the caller keeps its handle), the current mesh
/// extracted as `options_or_null` asks (NULL: the input mesh) and at rest, into `*out`.
/// Cuts use the options of a scalpel (the MT cut's, with the smallest face-point margin,
/// so a blade swept in steps continues its crack).
///
/// # Safety
/// `mt` must be a live model handle; a non-NULL `options_or_null` a readable
/// `mtcut_extract_options` with `struct_size` set; `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_new(
    mt: *const mtcut_mt,
    options_or_null: *const mtcut_extract_options,
    out: *mut *mut mtcut_live,
) -> mtcut_status {
    run("mtcut_live_new", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mt, options, out) = unsafe {
            (
                mt_ref(mt)?,
                read_optional(
                    options_or_null,
                    "options_or_null",
                    mtcut_extract_options::DEFAULT,
                )?,
                Out::new(out, "out")?,
            )
        };
        let live = LiveMt::new(Mt::clone(mt), &options.to_options()?, Scalpel::OPTIONS)
            .map_err(live_failure)?;
        out.write(Box::into_raw(Box::new(mtcut_live { live })));
        Ok(())
    })
}

/// Vertices of the current mesh (0 for a NULL handle).
///
/// # Safety
/// A non-NULL `live` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_vertex_count(live: *const mtcut_live) -> usize {
    // SAFETY: the caller's contract, forwarded to the check.
    run_count("mtcut_live_vertex_count", || {
        Ok(unsafe { live_ref(live) }?.mesh().nb_vertices())
    })
}

/// Tets of the current mesh (0 for a NULL handle).
///
/// # Safety
/// A non-NULL `live` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_tet_count(live: *const mtcut_live) -> usize {
    // SAFETY: the caller's contract, forwarded to the check.
    run_count("mtcut_live_tet_count", || {
        Ok(unsafe { live_ref(live) }?.mesh().nb_tets())
    })
}

/// Cuts queued for the model (0 for a NULL handle).
///
/// # Safety
/// A non-NULL `live` must be a live handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_pending_cuts(live: *const mtcut_live) -> usize {
    // SAFETY: the caller's contract, forwarded to the check.
    run_count("mtcut_live_pending_cuts", || {
        Ok(unsafe { live_ref(live) }?.pending_cuts())
    })
}

/// Copies the current positions (three doubles per vertex) into `xyz`, which holds
/// `capacity_vertices` vertices; fewer than `mtcut_live_vertex_count` gives
/// `MTCUT_STATUS_BUFFER_TOO_SMALL`, nothing written.
///
/// # Safety
/// `live` must be a live handle; `xyz` writable for `3 x capacity_vertices` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_copy_positions(
    live: *const mtcut_live,
    xyz: *mut f64,
    capacity_vertices: usize,
) -> mtcut_status {
    run("mtcut_live_copy_positions", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (live, xyz) = unsafe {
            (
                live_ref(live)?,
                OutSlice::new(xyz, capacity_vertices, "xyz")?,
            )
        };
        let flat: Vec<f64> = live
            .mesh()
            .positions()
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        xyz.write(&flat, 3, "vertices")
    })
}

/// Copies the rest positions of the current vertices (three doubles per vertex), as
/// `mtcut_live_copy_positions` does.
///
/// # Safety
/// `live` must be a live handle; `xyz` writable for `3 x capacity_vertices` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_copy_rest_positions(
    live: *const mtcut_live,
    xyz: *mut f64,
    capacity_vertices: usize,
) -> mtcut_status {
    run("mtcut_live_copy_rest_positions", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (live, xyz) = unsafe {
            (
                live_ref(live)?,
                OutSlice::new(xyz, capacity_vertices, "xyz")?,
            )
        };
        let flat: Vec<f64> = live
            .rest_positions()
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        xyz.write(&flat, 3, "vertices")
    })
}

/// Copies the current tets (four 0-based vertex indices per tet) into `tets`, which holds
/// `capacity_tets` tets; too small gives `MTCUT_STATUS_BUFFER_TOO_SMALL`, nothing written.
///
/// # Safety
/// `live` must be a live handle; `tets` writable for `4 x capacity_tets` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_copy_tets(
    live: *const mtcut_live,
    tets: *mut u32,
    capacity_tets: usize,
) -> mtcut_status {
    run("mtcut_live_copy_tets", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (live, tets) =
            unsafe { (live_ref(live)?, OutSlice::new(tets, capacity_tets, "tets")?) };
        let flat: Vec<u32> = live
            .mesh()
            .tets()
            .iter()
            .flat_map(|t| t.map(|v| v.0))
            .collect();
        tets.write(&flat, 4, "tets")
    })
}

/// Copies the model vertex of each current vertex into `ids` (`UINT32_MAX` for a vertex
/// made by a cut the model has not processed yet), which holds `capacity_vertices` values;
/// too small gives `MTCUT_STATUS_BUFFER_TOO_SMALL`, nothing written.
///
/// # Safety
/// `live` must be a live handle; `ids` writable for `capacity_vertices` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_copy_mt_vertex_ids(
    live: *const mtcut_live,
    ids: *mut u32,
    capacity_vertices: usize,
) -> mtcut_status {
    run("mtcut_live_copy_mt_vertex_ids", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (live, ids) = unsafe {
            (
                live_ref(live)?,
                OutSlice::new(ids, capacity_vertices, "ids")?,
            )
        };
        let flat: Vec<u32> = live.mt_vertex_ids().iter().map(|v| v.0).collect();
        ids.write(&flat, 1, "vertices")
    })
}

/// Sets the current (deformed) position of every current vertex: `xyz` holds
/// `n_vertices` points, exactly `mtcut_live_vertex_count`. A wrong count, a coordinate
/// that is not finite or larger in magnitude than 1e50, or a tet the positions would
/// invert or flatten gives `MTCUT_STATUS_INVALID_ARGUMENT` naming it, and nothing
/// changes.
///
/// # Safety
/// `live` must be a live handle used by no other thread; `xyz` readable for
/// `3 x n_vertices` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_set_positions(
    live: *mut mtcut_live,
    xyz: *const f64,
    n_vertices: usize,
) -> mtcut_status {
    run("mtcut_live_set_positions", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let live = unsafe { live_mut(live) }?;
        // The count first: a wrong one must not make the library read past `xyz`.
        let expected = live.mesh().nb_vertices();
        if n_vertices != expected {
            let e = CutError::PositionCount {
                count: n_vertices,
                expected,
            };
            return Err(Failure::invalid(e.to_string()));
        }
        // SAFETY: the caller's contract, forwarded to the check.
        let positions = unsafe { points(xyz, n_vertices, "xyz") }?;
        // Positions that would invert a tet are a bad argument, not a bad mesh: the
        // current mesh is unchanged.
        live.set_positions(&positions).map_err(|e| match e {
            LiveError::Cut(e @ CutError::InvertedTet { .. }) => Failure::invalid(e.to_string()),
            e => live_failure(e),
        })
    })
}

/// The frontier-first cut: cuts the current mesh, at its current positions, with the
/// planar convex polygon of `n_points` corners at `polygon_xyz` (given where the body
/// lies now), and queues the cut of the model. `stats_or_null` receives the current
/// mesh's cut (`seconds_cut`: the whole call; `polygons_moved_to_plane`: 1 when the
/// polygon lay close to the plane of an earlier cut of this model without lying in it,
/// and was cut in that plane, here and on the model). A polygon that is not planar and
/// convex gives `MTCUT_STATUS_INVALID_ARGUMENT`, nothing changed.
///
/// # Safety
/// `live` must be a live handle used by no other thread; `polygon_xyz` readable for
/// `3 x n_points` doubles; a non-NULL `stats_or_null` writable with `struct_size` set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_cut(
    live: *mut mtcut_live,
    polygon_xyz: *const f64,
    n_points: usize,
    stats_or_null: *mut mtcut_cut_stats,
) -> mtcut_status {
    run("mtcut_live_cut", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (live, corners, stats) = unsafe {
            (
                live_mut(live)?,
                corners(polygon_xyz, n_points, "polygon_xyz")?,
                Out::optional(stats_or_null, "stats_or_null")?,
            )
        };
        let stats = stats.map(VersionedOut::new).transpose()?;
        let polygon = CutPolygon::new(&corners).map_err(|e| polygon_failure(e, "polygon_xyz"))?;
        let cut = live.cut(&polygon).map_err(live_failure)?;
        if let Some(out) = stats {
            let mut c = mtcut_cut_stats::default();
            c.add(&cut.stats, 0.0);
            c.seconds_cut = cut.seconds;
            c.polygons_moved_to_plane = usize::from(cut.moved_to_plane);
            out.write(c);
        }
        Ok(())
    })
}

/// The frontier-first cut of a scalpel's sweep in one time step, given where the body lies
/// now: the blade from `start_xyz[0..3]` to `start_xyz[3..6]` at the start of the step and
/// from `end_xyz[0..3]` to `end_xyz[3..6]` at its end (corresponding ends). The current mesh
/// is cut with the polygons `mtcut_scalpel_sweep_polygons` gives (one quadrilateral, or two
/// triangles), and the model is queued. For a body at rest (no positions set that differ
/// from the rest positions), where the model refuses those polygons (two triangles meeting
/// at an angle the coarser levels cannot take), `mtcut_live_process_pending` cuts it with
/// another split of the same sweep (the other diagonal's triangles, or either pair in the
/// other order) and replaces the current mesh by the model's extraction
/// (`other_splits` in its report); calling `mtcut_live_cut` once per polygon gives up
/// that step instead (`refused`). A step whose every split the model refuses (`refused`,
/// no cut done) is missing from the model and, extracted again, from the current mesh: a
/// host may sweep it again from a fraction of the way into it (`start_xyz` moved a tenth
/// of the way to `end_xyz`), a new crack leaving that bridge uncut, as `mtcut scalpel
/// --time-critical --skip-refused` does (on a shallow incision turning by 4 degrees a step
/// across liver, every step refused whole is taken so). `stats_or_null` receives the
/// current mesh's cuts added up (as `mtcut_live_cut` gives one's). A blade that does not
/// move, a sweep folding over itself or a coordinate that is not finite gives
/// `MTCUT_STATUS_INVALID_ARGUMENT`, nothing changed.
///
/// # Safety
/// `live` must be a live handle used by no other thread; `start_xyz` and `end_xyz`
/// readable for 6 doubles each; a non-NULL `stats_or_null` writable with `struct_size`
/// set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_scalpel_sweep(
    live: *mut mtcut_live,
    start_xyz: *const f64,
    end_xyz: *const f64,
    stats_or_null: *mut mtcut_cut_stats,
) -> mtcut_status {
    run("mtcut_live_scalpel_sweep", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (live, start, end, stats) = unsafe {
            (
                live_mut(live)?,
                points(start_xyz, 2, "start_xyz")?,
                points(end_xyz, 2, "end_xyz")?,
                Out::optional(stats_or_null, "stats_or_null")?,
            )
        };
        let stats = stats.map(VersionedOut::new).transpose()?;
        let splits = scalpel_sweep_splits([start[0], start[1]], [end[0], end[1]], SWEEP_PLANARITY)
            .map_err(|e| polygon_failure(e, "start_xyz/end_xyz"))?;
        let cuts = live.cut_sweep(&splits).map_err(live_failure)?;
        if let Some(out) = stats {
            let mut c = mtcut_cut_stats::default();
            for cut in &cuts {
                c.add(&cut.stats, 0.0);
                c.polygons_moved_to_plane += usize::from(cut.moved_to_plane);
            }
            // As `mtcut_live_cut`'s: the whole calls' time.
            c.seconds_cut = cuts.iter().map(|cut| cut.seconds).sum();
            out.write(c);
        }
        Ok(())
    })
}

/// What `mtcut_live_process_pending` did. A versioned struct: set `struct_size` to
/// `sizeof(mtcut_pending_report)`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct mtcut_pending_report {
    /// Set by the caller to `sizeof(mtcut_pending_report)`; never written by the library.
    pub struct_size: usize,
    /// Cuts of the model made by the call.
    pub cuts_done: usize,
    /// Fragments (simplification steps) they involved.
    pub fragments: usize,
    /// Cuts still queued.
    pub cuts_left: usize,
    /// 1 when the current mesh was replaced by the model's extraction at its resolution
    /// (the model decided otherwise than the frontier-first cut): its vertex and tet
    /// numbering changed, positions were carried over by model vertex.
    pub remeshed: i32,
    /// Cuts made at rest because the deformation folded a tet of the model they meet.
    pub folded: usize,
    pub seconds: f64,
    /// Cuts the model refused (it would have been left inconsistent: a cut beginning
    /// where an earlier crack ends, at an angle to it), dropped from the queue; the model
    /// is as it was without them, and the current mesh, which had them, was replaced by
    /// its extraction (`remeshed` is 1). Added after `seconds`: callers built against a
    /// header without it pass a smaller `struct_size` and are not written it.
    pub refused: usize,
    /// Scalpel sweeps (`mtcut_live_scalpel_sweep`) the model refused as the current mesh
    /// was cut and took as another split of them; the current mesh was then replaced by
    /// its extraction (`remeshed` is 1). Added after `refused`, as it was.
    pub other_splits: usize,
}

// SAFETY: repr(C), `struct_size: usize` first; FIRST_SIZE is within the struct.
unsafe impl Versioned for mtcut_pending_report {
    const NAME: &'static str = "mtcut_pending_report";
    const FIRST_SIZE: usize = offset_of!(mtcut_pending_report, seconds) + size_of::<f64>();
}

/// Cuts the model with the queued cuts, oldest first, while the budget lasts: with
/// `max_fragments` > 0, no further cut is started once that many fragments were
/// processed; else with `max_seconds` > 0, once that much time has passed; with both 0,
/// everything queued. The budget is checked between cuts (a cut is processed whole).
/// A negative or non-finite `max_seconds` gives `MTCUT_STATUS_INVALID_ARGUMENT`.
///
/// # Safety
/// `live` must be a live handle used by no other thread; a non-NULL `report_or_null`
/// writable with `struct_size` set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_process_pending(
    live: *mut mtcut_live,
    max_fragments: usize,
    max_seconds: f64,
    report_or_null: *mut mtcut_pending_report,
) -> mtcut_status {
    run("mtcut_live_process_pending", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (live, report) = unsafe {
            (
                live_mut(live)?,
                Out::optional(report_or_null, "report_or_null")?,
            )
        };
        let report = report.map(VersionedOut::new).transpose()?;
        if !(max_seconds.is_finite() && max_seconds >= 0.0) {
            return Err(Failure::invalid(format!(
                "argument `max_seconds` is {max_seconds}: expected a finite time, 0 or more"
            )));
        }
        let budget = match (max_fragments, max_seconds) {
            (0, 0.0) => PendingBudget::All,
            (0, s) => PendingBudget::Time(Duration::from_secs_f64(s)),
            (n, _) => PendingBudget::Fragments(n),
        };
        let r = live.process_pending(budget).map_err(live_failure)?;
        if let Some(out) = report {
            out.write(mtcut_pending_report {
                struct_size: 0,
                cuts_done: r.cuts.len(),
                fragments: r.fragments,
                cuts_left: r.cuts_left,
                remeshed: i32::from(r.remeshed),
                folded: r.folded,
                seconds: r.seconds,
                refused: r.refused.len(),
                other_splits: r.other_splits,
            });
        }
        Ok(())
    })
}

/// Extracts the current mesh again as `options_or_null` asks (NULL: the input mesh), its
/// vertices kept where the host put them (by model vertex; vertices new to it placed by
/// the deformation around them). Refused with `MTCUT_STATUS_PENDING_WORK` while cuts are
/// queued (paper section 5: the resolution cannot change until the model has them all), and with
/// `MTCUT_STATUS_INVALID_ARGUMENT` for invalid options; nothing changes then.
///
/// # Safety
/// `live` must be a live handle used by no other thread; a non-NULL `options_or_null` a
/// readable `mtcut_extract_options` with `struct_size` set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_set_resolution(
    live: *mut mtcut_live,
    options_or_null: *const mtcut_extract_options,
) -> mtcut_status {
    run("mtcut_live_set_resolution", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (live, options) = unsafe {
            (
                live_mut(live)?,
                read_optional(
                    options_or_null,
                    "options_or_null",
                    mtcut_extract_options::DEFAULT,
                )?,
            )
        };
        live.set_resolution(&options.to_options()?)
            .map_err(live_failure)
    })
}

/// A copy of the current mesh (at the current positions) into `*out`: a new mesh handle.
///
/// # Safety
/// `live` must be a live handle; `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_mesh(
    live: *const mtcut_live,
    out: *mut *mut mtcut_mesh,
) -> mtcut_status {
    run("mtcut_live_mesh", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (live, out) = unsafe { (live_ref(live)?, Out::new(out, "out")?) };
        out.write(mtcut_mesh::boxed(live.mesh().clone()));
        Ok(())
    })
}

/// A copy of the model as it is now, at rest, into `*out`: a new model handle. Cuts still
/// queued are not in it (process them first).
///
/// # Safety
/// `live` must be a live handle; `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_mt(
    live: *const mtcut_live,
    out: *mut *mut mtcut_mt,
) -> mtcut_status {
    run("mtcut_live_mt", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (live, out) = unsafe { (live_ref(live)?, Out::new(out, "out")?) };
        out.write(mtcut_mt::boxed(live.mt().clone()));
        Ok(())
    })
}

/// Releases a live model (NULL is ignored).
///
/// # Safety
/// A non-NULL `live` must be a live handle, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_live_free(live: *mut mtcut_live) {
    if live.is_null() {
        return;
    }
    let _ = std::panic::catch_unwind(|| {
        // SAFETY: a live handle made by Box::into_raw (the caller's contract).
        drop(unsafe { Box::from_raw(live) });
    });
}
