//! `mtcut_mt`: the Multi-Tessellation (paper §2) - built from a mesh with options and a
//! progress callback that can cancel, saved and loaded, described by its statistics, and
//! cut into variable-resolution meshes: by threshold, focus region and budget, from
//! scratch or kept up to date incrementally by an `mtcut_frontier`.

use super::cut::{corners, cut_failure, mtcut_cut_stats, points, polygon_failure};
use super::guard::{Out, c_str, deref, deref_mut, run, run_count};
use super::measure::write_verdict;
use super::mesh::{mesh_ref, mtcut_mesh, path_arg};
use super::status::{
    Failure, FfiResult, MTCUT_STATUS_CANCELLED, MTCUT_STATUS_INTERNAL_PANIC,
    MTCUT_STATUS_INVALID_MESH, MTCUT_STATUS_IO_ERROR, MTCUT_STATUS_PARSE_ERROR,
    MTCUT_STATUS_UNSUPPORTED_FORMAT, mtcut_status,
};
use super::versioned::{Versioned, VersionedOut, read_optional};
use crate::cut::{MtCutStats, MtCutter, RoiError, RoiRegion, region_of_interest};
use crate::geom::{Aabb, CutPolygon, DVec3};
use crate::mt::{
    BoundaryError, BuildError, BuildOptions, ErrorMetric, ExtractError, ExtractOptions, Frontier,
    GHOST, Mt, MtFileError, MtFileErrorKind, Region,
};
use std::ffi::{c_char, c_int, c_void};
use std::mem::offset_of;
use std::ops::ControlFlow;
use std::sync::Arc;

/// A Multi-Tessellation (opaque): every level of detail of a tet mesh and the DAG of
/// fragments (simplification steps) saying how they fit together (paper section 2). Made
/// by `mtcut_mt_build` or `mtcut_mt_load`, released with `mtcut_mt_free`. Extracted meshes
/// are independent `mtcut_mesh` handles with the cell data "mt_fragment", "mt_error" and
/// "mt_level" (the fragment that created each tet, its error and DAG level) and the point
/// data "mt_vertex" (each vertex's id in the model), besides the input's own columns.
pub struct mtcut_mt {
    /// Shared with the frontiers made from it, which may outlive the handle. `None` only
    /// when a cut panicked while it held the model.
    mt: Option<Arc<Mt>>,
    /// What the first `mtcut_mt_cut` prepared for cutting this model (vertex scales,
    /// fragment hierarchy, per-tet links: linear in the model's size), kept for the next
    /// ones without a model of its own: each cut lends it `mt`.
    cutter: Option<MtCutter>,
    /// The model's tets over all levels, ghosts left out (`tets_after` of a cut's
    /// statistics): counted when a cut's statistics first ask for it (a pass over the
    /// model), then kept by each cut's balance (tets created less tets replaced).
    pool_tets: Option<usize>,
}

impl mtcut_mt {
    pub(super) fn boxed(mt: Mt) -> *mut mtcut_mt {
        Box::into_raw(Box::new(mtcut_mt {
            mt: Some(Arc::new(mt)),
            cutter: None,
            pool_tets: None,
        }))
    }

    fn model(&self) -> FfiResult<&Arc<Mt>> {
        self.mt.as_ref().ok_or_else(|| {
            Failure::new(
                MTCUT_STATUS_INTERNAL_PANIC,
                "the model was lost by an internal panic in an earlier mtcut_mt_cut",
            )
        })
    }
}

/// The model behind a handle argument.
///
/// # Safety
/// A non-NULL `mt` must be a live handle from this library.
pub(super) unsafe fn mt_ref<'a>(mt: *const mtcut_mt) -> FfiResult<&'a Arc<Mt>> {
    // SAFETY: forwarded contract.
    unsafe { deref(mt, "mt") }?.model()
}

/// The per-tet error a build ranks simplification steps by (a `uint32_t`; other values are
/// refused with `MTCUT_STATUS_INVALID_ARGUMENT`).
pub type mtcut_error_metric = u32;

/// The volume a collapse changes, relative to the local size (the paper's). The default.
pub const MTCUT_ERROR_METRIC_VOLUME: mtcut_error_metric = 0;
/// The distance of the boundary to the input's boundary surface, plus a small size term.
pub const MTCUT_ERROR_METRIC_BOUNDARY: mtcut_error_metric = 1;
/// One minus the mean-ratio quality of the created tets.
pub const MTCUT_ERROR_METRIC_QUALITY: mtcut_error_metric = 2;

/// A build's progress callback: called about once per round of simplification with the
/// estimated fraction of the work done (0 to 1, never decreasing) and the `user` pointer
/// of the options. Returning nonzero cancels the build (`MTCUT_STATUS_CANCELLED`, no
/// model made). It runs on the thread that called `mtcut_mt_build` and must return
/// normally (no C++ exception, no longjmp across mtcut).
pub type mtcut_progress_callback =
    Option<unsafe extern "C" fn(user: *mut c_void, fraction: f64) -> c_int>;

/// How to build a Multi-Tessellation. A versioned struct: set `struct_size` to
/// `sizeof(mtcut_build_options)` and fill it with `mtcut_build_options_default` before
/// changing fields.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub struct mtcut_build_options {
    /// Set by the caller to `sizeof(mtcut_build_options)`.
    pub struct_size: usize,
    /// An `MTCUT_ERROR_METRIC_*` value. Default `MTCUT_ERROR_METRIC_VOLUME`.
    pub error_metric: mtcut_error_metric,
    /// How far the boundary of any level may stray from the input's boundary, relative to
    /// the input's bounding-box diagonal (finite, >= 0). Default 0.005.
    pub boundary_tolerance: f64,
    /// Nonzero: keep boundary feature edges (as lines) and corners. Default 1.
    pub preserve_features: u32,
    /// Dihedral angle in degrees (0 to 180) above which a boundary edge is a feature; no
    /// boundary face turns by more than it in one step. Default 30.
    pub feature_angle_degrees: f64,
    /// Mean-ratio quality floor (0 to 1) of the tets a step may create. Default 0.02.
    pub min_quality: f64,
    /// Stop simplifying when the mesh has at most this many tets; 0: simplify while a
    /// legal step is left. Default 0.
    pub target_tets: usize,
    /// Progress callback, or NULL. Default NULL.
    pub progress_or_null: mtcut_progress_callback,
    /// Handed to the callback as is. Default NULL.
    pub user: *mut c_void,
}

// SAFETY: repr(C), `struct_size: usize` first; every field takes any bit pattern (numbers,
// a nullable function pointer, a raw pointer; the metric is validated after reading);
// FIRST_SIZE is within the struct.
unsafe impl Versioned for mtcut_build_options {
    const NAME: &'static str = "mtcut_build_options";
    const FIRST_SIZE: usize = offset_of!(mtcut_build_options, user) + size_of::<*mut c_void>();
}

impl mtcut_build_options {
    const DEFAULT: mtcut_build_options = mtcut_build_options {
        struct_size: size_of::<mtcut_build_options>(),
        error_metric: MTCUT_ERROR_METRIC_VOLUME,
        boundary_tolerance: BuildOptions::DEFAULT.boundary_tolerance.relative,
        preserve_features: BuildOptions::DEFAULT.preserve_features as u32,
        feature_angle_degrees: BuildOptions::DEFAULT.feature_angle_degrees,
        min_quality: BuildOptions::DEFAULT.min_quality,
        target_tets: 0,
        progress_or_null: None,
        user: std::ptr::null_mut(),
    };

    /// The library's options (their ranges are checked by the build).
    fn to_options(self) -> FfiResult<BuildOptions> {
        let error = match self.error_metric {
            MTCUT_ERROR_METRIC_VOLUME => ErrorMetric::Volume,
            MTCUT_ERROR_METRIC_BOUNDARY => ErrorMetric::Boundary(BoundaryError::DEFAULT),
            MTCUT_ERROR_METRIC_QUALITY => ErrorMetric::Quality,
            m => {
                return Err(Failure::invalid(format!(
                    "mtcut_build_options.error_metric is {m}: not an MTCUT_ERROR_METRIC_* \
                     value (0 to 2)"
                )));
            }
        };
        Ok(BuildOptions::DEFAULT
            .with_error(error)
            .with_boundary_tolerance(self.boundary_tolerance)
            .with_preserve_features(self.preserve_features != 0)
            .with_feature_angle_degrees(self.feature_angle_degrees)
            .with_min_quality(self.min_quality)
            .with_target_tets((self.target_tets != 0).then_some(self.target_tets)))
    }
}

/// Fills the fields of `*options` within `options->struct_size` (which the caller sets
/// first) with their defaults.
///
/// # Safety
/// `options` must be a writable `mtcut_build_options` whose `struct_size` is set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_build_options_default(
    options: *mut mtcut_build_options,
) -> mtcut_status {
    run("mtcut_build_options_default", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let out = VersionedOut::new(unsafe { Out::new(options, "options") }?)?;
        out.write(mtcut_build_options::DEFAULT);
        Ok(())
    })
}

fn build_failure(e: BuildError) -> Failure {
    let status = match &e {
        BuildError::Cancelled => MTCUT_STATUS_CANCELLED,
        BuildError::InvalidMesh(_) | BuildError::EmptyMesh => MTCUT_STATUS_INVALID_MESH,
        BuildError::InvalidOptions(_) | BuildError::TooLarge { .. } => {
            return Failure::invalid(e.to_string());
        }
        BuildError::BadErrorValue { .. } | BuildError::Internal(_) => MTCUT_STATUS_INTERNAL_PANIC,
    };
    Failure::new(status, e.to_string())
}

/// Builds the Multi-Tessellation of `mesh` by simplification (paper section 2), with
/// `options_or_null` (NULL: the defaults). The mesh's vertex and tet attribute columns
/// are kept by the model and appear in extracted meshes. Errors:
/// `MTCUT_STATUS_INVALID_ARGUMENT` (an option out of range, named in the message),
/// `MTCUT_STATUS_INVALID_MESH` (a mesh moved into an invalid state by
/// `mtcut_mesh_set_vertices`), `MTCUT_STATUS_CANCELLED` (the progress callback returned
/// nonzero). On success `*out` receives a new model to free with `mtcut_mt_free`.
///
/// # Safety
/// `mesh` must be a live mesh handle; a non-NULL `options_or_null` a readable
/// `mtcut_build_options` with `struct_size` set (and a valid callback, if any); `out` a
/// writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mt_build(
    mesh: *const mtcut_mesh,
    options_or_null: *const mtcut_build_options,
    out: *mut *mut mtcut_mt,
) -> mtcut_status {
    run("mtcut_mt_build", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, options, out) = unsafe {
            (
                mesh_ref(mesh)?,
                read_optional(
                    options_or_null,
                    "options_or_null",
                    mtcut_build_options::DEFAULT,
                )?,
                Out::new(out, "out")?,
            )
        };
        let (callback, user) = (options.progress_or_null, options.user);
        let build = options.to_options()?;
        let mut progress = |p: &crate::mt::BuildProgress| match callback {
            // SAFETY: the caller's callback with the caller's pointer (its contract).
            Some(f) if unsafe { f(user, p.fraction) } != 0 => ControlFlow::Break(()),
            _ => ControlFlow::Continue(()),
        };
        let (mt, _) =
            Mt::build_with_progress(mesh, &build, &mut progress).map_err(build_failure)?;
        out.write(mtcut_mt::boxed(mt));
        Ok(())
    })
}

impl mtcut_cut_stats {
    /// A cut of the model in the plain-mesh statistics (the counts are over every level);
    /// `tets_after` and `vertices_after` are the model's, as `mtcut_mt_statistics` counts
    /// them (every level, no ghosts); the build and component times zero.
    fn of_mt(s: &MtCutStats, mt: &Mt, pool_tets: usize) -> mtcut_cut_stats {
        mtcut_cut_stats {
            struct_size: size_of::<mtcut_cut_stats>(),
            tets_tested: s.tets_tested,
            tets_candidate: s.tets_candidate,
            tets_cut: s.tets_cut,
            tets_created: s.tets_created,
            vertices_added: s.vertices_added,
            cut_points: s.cut_points,
            face_points: s.face_points,
            vertex_copies: s.vertex_copies,
            vertices_snapped: s.vertices_snapped,
            tets_after: pool_tets,
            vertices_after: mt.nb_vertices(),
            components: s.components,
            seconds_build: 0.0,
            seconds_cut: s.time.total,
            seconds_components: 0.0,
            polygons_moved_to_plane: usize::from(s.moved_to_plane),
        }
    }
}

/// Cuts every level of detail of the model with the planar convex polygon whose
/// `n_points` corners, in order around it, are at `polygon_xyz` (paper section 3): every
/// tet of every level the polygon crosses is replaced, the fragments whose parts it
/// leaves in different bodies are split, and a body cut straight through becomes
/// independent models in the same handle (`mtcut_mt_statistics` counts them as
/// components). Polygon rules as in `mtcut_mesh_cut`. `stats_or_null`, if given, receives the counts over all levels
/// (`tets_after`/`vertices_after`: the model's tets and vertices over all levels). A
/// polygon close to the plane of a crack an earlier cut made at rest (the model keeps every
/// such plane) without lying in it is cut in that plane (`polygons_moved_to_plane`).
///
/// The model keeps the record of its last cuts (saved with it by `mtcut_mt_save`): a call
/// whose polygon begins where the last one's crack ended, at an angle (a turning or
/// tilting blade moved call by call), continues that crack.
///
/// Before it keeps a cut, the cut checks the floor and ceiling of every fragment it
/// changed and the orientation of every tet it made (what `Mt::validate` checks of them;
/// the rest of the model it did not change): a cut the model refuses (some steps at
/// steep angles to the last crack, or turning near where an incision ending inside the
/// body stops: a known limit) gives `MTCUT_STATUS_INVALID_MESH` naming the fragment, and
/// the model is unchanged. The first cut of a model prepares it for cutting (a cost
/// linear in its size, kept in the handle for the next cuts); later cuts cost in
/// proportion to what they change, unless frontiers made since the last cut still share
/// the model (it is then copied). Frontiers made earlier keep extracting
/// from the model as it was when they were made. The two lips of a crack ending inside
/// the body are always extracted at the same resolution. After a cut straight through, a
/// focus extraction of the whole model may show the two bodies touching along the crack
/// at different resolutions, which `mtcut_mesh_validate` reports as hanging vertices
/// between them; each component from `mtcut_mt_component` is valid on its own.
///
/// # Safety
/// `mt` must be a live model handle used by no other thread during the call;
/// `polygon_xyz` readable for `3 x n_points` doubles; a non-NULL `stats_or_null` writable
/// with its `struct_size` set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mt_cut(
    mt: *mut mtcut_mt,
    polygon_xyz: *const f64,
    n_points: usize,
    stats_or_null: *mut mtcut_cut_stats,
) -> mtcut_status {
    run("mtcut_mt_cut", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (handle, corners, stats) = unsafe {
            (
                deref_mut(mt, "mt")?,
                corners(polygon_xyz, n_points, "polygon_xyz")?,
                Out::optional(stats_or_null, "stats_or_null")?,
            )
        };
        let stats = stats.map(VersionedOut::new).transpose()?;
        let polygon = CutPolygon::new(&corners).map_err(|e| polygon_failure(e, "polygon_xyz"))?;
        handle.model()?;
        // The handle's model is lent to the cutter (copied if frontiers share it) and
        // given back, cut or, when the cut is refused, byte for byte as it was. Only a
        // panic inside the cut loses it (the handle then says so).
        let shared = handle.mt.take().expect("checked above");
        let model = Arc::try_unwrap(shared).unwrap_or_else(|shared| Mt::clone(&shared));
        let mut cutter = match handle.cutter.take() {
            Some(mut cutter) => {
                cutter.put_mt(model);
                cutter
            }
            None => MtCutter::new(model, MtCutter::DEFAULT_OPTIONS)
                .expect("the default options are an MT cutter's"),
        };
        let result = cutter.cut(&polygon);
        handle.mt = Some(Arc::new(cutter.take_mt()));
        handle.cutter = Some(cutter);
        let result = result.map_err(cut_failure)?;
        let cut = Arc::clone(handle.model()?);
        debug_assert!(cut.validate().is_valid(), "{}", cut.validate());
        handle.pool_tets = handle
            .pool_tets
            .map(|n| n + result.tets_created - result.tets_cut);
        if let Some(out) = stats {
            let pool_tets = *handle.pool_tets.get_or_insert_with(|| {
                cut.nb_tets() - cut.tets().iter().filter(|t| t[3] == GHOST).count()
            });
            debug_assert_eq!(pool_tets, cut.summary().pool_tets);
            out.write(mtcut_cut_stats::of_mt(&result, &cut, pool_tets));
        }
        Ok(())
    })
}

/// Checks every invariant of the model (`Mt::validate`: the store's structure, the DAG
/// acyclic with consistent levels and errors, every tet positively oriented, every
/// fragment's floor and ceiling conforming with the same boundary, the finest and
/// coarsest meshes valid): exhaustive, so linear-logarithmic in the model's size plus two
/// extractions. Models are valid when built, loaded, and after every cut (each cut checks
/// what it changed); this is the whole check, for a host's own tests or debug builds.
/// `*valid` receives the verdict; the message ("valid MT", or "invalid MT: " and each
/// violation with its count and first examples) is truncated like `snprintf` to
/// `message_capacity` bytes with its NUL; `message_or_null` may be NULL (with
/// `message_capacity` 0) to skip it. `*message_length_or_null`, if given, receives the
/// full length without the NUL.
///
/// # Safety
/// `mt` must be a live model handle; `valid` writable; a non-NULL `message_or_null`
/// writable for `message_capacity` bytes; a non-NULL `message_length_or_null` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mt_validate(
    mt: *const mtcut_mt,
    valid: *mut bool,
    message_or_null: *mut c_char,
    message_capacity: usize,
    message_length_or_null: *mut usize,
) -> mtcut_status {
    run("mtcut_mt_validate", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let mt = unsafe { mt_ref(mt) }?;
        let check = || {
            let report = mt.validate();
            (report.is_valid(), report.to_string())
        };
        // SAFETY: as above.
        unsafe {
            write_verdict(
                valid,
                message_or_null,
                message_capacity,
                message_length_or_null,
                check,
            )
        }
    })
}

/// Component `k` (from 0; `mtcut_mt_statistics` counts them) of a model that cuts
/// separated into independent models, as a model of its own: `*out` receives a new
/// handle. `MTCUT_STATUS_INVALID_ARGUMENT` when `k` is not below the count (as for
/// `mtcut_mesh_extract_component`).
///
/// # Safety
/// `mt` must be a live model handle; `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mt_component(
    mt: *const mtcut_mt,
    k: usize,
    out: *mut *mut mtcut_mt,
) -> mtcut_status {
    run("mtcut_mt_component", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mt, out) = unsafe { (mt_ref(mt)?, Out::new(out, "out")?) };
        let n = mt.nb_components();
        let part = mt.component(k).ok_or_else(|| {
            Failure::invalid(format!(
                "argument `k`: component {k} asked for, the model has {n}"
            ))
        })?;
        out.write(mtcut_mt::boxed(part));
        Ok(())
    })
}

/// The sub-model of `mt` inside the axis-aligned box from `box_min` to `box_max` (three
/// doubles each, every min below its max): a model of the region of interest with
/// everything outside omitted (paper section 7). Every level of a copy of the model is cut
/// along each face plane of the box that crosses the body, and the independent bodies
/// lying inside are kept: a model of its own, roots and drains included, whose every
/// extraction lies in the box; it is validated before it is returned. `mt` is not changed.
/// On success `*out` receives a new handle. Errors: `MTCUT_STATUS_INVALID_ARGUMENT` for
/// a box not finite, empty or flat, or not meeting the body (`*out` untouched);
/// `MTCUT_STATUS_INVALID_MESH` when a plane's cut is refused (naming the plane and the
/// fragment) or the sub-model fails its validation. Costs a copy of the model and a cut
/// of every level per plane.
///
/// # Safety
/// `mt` must be a live model handle; `box_min` and `box_max` readable for three doubles
/// each; `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mt_roi_box(
    mt: *const mtcut_mt,
    box_min: *const f64,
    box_max: *const f64,
    out: *mut *mut mtcut_mt,
) -> mtcut_status {
    run("mtcut_mt_roi_box", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mt, min, max, out) = unsafe {
            (
                mt_ref(mt)?,
                points(box_min, 1, "box_min")?,
                points(box_max, 1, "box_max")?,
                Out::new(out, "out")?,
            )
        };
        let region = RoiRegion::Box(Aabb {
            min: min[0],
            max: max[0],
        });
        let (sub, _) = region_of_interest(mt, &region)
            .map_err(|e| roi_failure(e, "arguments `box_min`, `box_max`"))?;
        out.write(mtcut_mt::boxed(sub));
        Ok(())
    })
}

/// The sub-model of `mt` inside the sphere of centre `center` (three doubles) and radius
/// `radius` (finite, > 0), as `mtcut_mt_roi_box` makes it for a box. The model is cut
/// along the 14 planes of a polyhedron around the sphere (its bounding cube with the
/// corners cut off at distance `radius` from the centre), so the sub-model also keeps
/// what lies between the sphere and that polyhedron (at most 0.24 x `radius` beyond the
/// sphere, where a cube face meets two corner planes). Errors as `mtcut_mt_roi_box`'s.
///
/// # Safety
/// `mt` must be a live model handle; `center` readable for three doubles; `out` a
/// writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mt_roi_sphere(
    mt: *const mtcut_mt,
    center: *const f64,
    radius: f64,
    out: *mut *mut mtcut_mt,
) -> mtcut_status {
    run("mtcut_mt_roi_sphere", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mt, center, out) = unsafe {
            (
                mt_ref(mt)?,
                points(center, 1, "center")?,
                Out::new(out, "out")?,
            )
        };
        let region = RoiRegion::Sphere {
            center: center[0],
            radius,
        };
        let (sub, _) = region_of_interest(mt, &region)
            .map_err(|e| roi_failure(e, "arguments `center`, `radius`"))?;
        out.write(mtcut_mt::boxed(sub));
        Ok(())
    })
}

/// The status of a refused region of interest: the region's fault (`args` names its
/// arguments) or the model's.
fn roi_failure(e: RoiError, args: &str) -> Failure {
    match e {
        RoiError::InvalidRegion(_) | RoiError::Misses { .. } | RoiError::NothingInside { .. } => {
            Failure::invalid(format!("{args}: {e}"))
        }
        RoiError::Cut { .. } | RoiError::Invalid(_) => {
            Failure::new(MTCUT_STATUS_INVALID_MESH, e.to_string())
        }
    }
}

fn file_failure(e: MtFileError) -> Failure {
    let status = match &e.kind {
        MtFileErrorKind::Os(_) => MTCUT_STATUS_IO_ERROR,
        MtFileErrorKind::WrongMagic { .. } | MtFileErrorKind::UnsupportedVersion { .. } => {
            MTCUT_STATUS_UNSUPPORTED_FORMAT
        }
        MtFileErrorKind::Truncated { .. }
        | MtFileErrorKind::TrailingBytes { .. }
        | MtFileErrorKind::ChecksumMismatch { .. }
        | MtFileErrorKind::Corrupt(_) => MTCUT_STATUS_PARSE_ERROR,
    };
    Failure::new(status, e.to_string())
}

/// Writes the model to `path` in mtcut's binary `.mt` format (checksummed; any file name).
/// `MTCUT_STATUS_IO_ERROR` when the file cannot be written.
///
/// # Safety
/// `mt` must be a live model handle; `path` a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mt_save(mt: *const mtcut_mt, path: *const c_char) -> mtcut_status {
    run("mtcut_mt_save", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mt, path) = unsafe { (mt_ref(mt)?, c_str(path, "path")?) };
        mt.save(path_arg(path)?).map_err(file_failure)
    })
}

/// Reads a model written by `mtcut_mt_save`. Errors: `MTCUT_STATUS_IO_ERROR` (cannot
/// read), `MTCUT_STATUS_UNSUPPORTED_FORMAT` (not an `.mt` file, or a format version this
/// library does not read), `MTCUT_STATUS_PARSE_ERROR` (truncated or corrupt: the checksum
/// or the content's consistency fails). On success `*out` receives a new model.
///
/// # Safety
/// `path` must be a NUL-terminated string; `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mt_load(
    path: *const c_char,
    out: *mut *mut mtcut_mt,
) -> mtcut_status {
    run("mtcut_mt_load", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (path, out) = unsafe { (c_str(path, "path")?, Out::new(out, "out")?) };
        let mt = Mt::load(path_arg(path)?).map_err(file_failure)?;
        out.write(mtcut_mt::boxed(mt));
        Ok(())
    })
}

/// Releases a model. NULL is allowed (nothing happens). Frontiers made from it stay
/// usable (they share the model). Using the handle afterwards, or freeing it twice, is
/// undefined behaviour.
///
/// # Safety
/// A non-NULL `mt` must be a live handle from this library, not used after the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mt_free(mt: *mut mtcut_mt) {
    if mt.is_null() {
        return;
    }
    // As in mtcut_mesh_free: no status to report a panic with, and dropping cannot panic.
    let _ = std::panic::catch_unwind(|| {
        // SAFETY: a live handle made by Box::into_raw (the caller's contract).
        drop(unsafe { Box::from_raw(mt) });
    });
}

/// Numbers describing a model. A versioned struct: set `struct_size` to
/// `sizeof(mtcut_mt_stats)` before the call.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct mtcut_mt_stats {
    /// Set by the caller to `sizeof(mtcut_mt_stats)`; never written by the library.
    pub struct_size: usize,
    /// Vertices of the model (those of the input mesh).
    pub vertices: usize,
    /// Tets of every level together.
    pub tets: usize,
    /// Tets of the input (finest) and of the coarsest mesh.
    pub input_tets: usize,
    pub coarsest_tets: usize,
    /// Fragments: the simplification steps, plus one root and one drain per component.
    pub fragments: usize,
    /// Length of the longest chain of dependent fragments.
    pub dag_depth: usize,
    /// Independent models held (connected parts of the input).
    pub components: usize,
    /// Smallest and largest error of a simplification step: thresholds below the first
    /// extract the input mesh, at or above the second the coarsest one (0 and 0 when no
    /// step was possible).
    pub min_error: f64,
    pub max_error: f64,
    /// Memory the model holds, in bytes.
    pub heap_bytes: usize,
}

// SAFETY: repr(C), `struct_size: usize` first; FIRST_SIZE is within the struct.
unsafe impl Versioned for mtcut_mt_stats {
    const NAME: &'static str = "mtcut_mt_stats";
    const FIRST_SIZE: usize = offset_of!(mtcut_mt_stats, heap_bytes) + size_of::<usize>();
}

/// The model's statistics: fills the fields of `*stats` within `stats->struct_size`.
///
/// # Safety
/// `mt` must be a live model handle; `stats` a writable `mtcut_mt_stats` whose
/// `struct_size` is set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mt_statistics(
    mt: *const mtcut_mt,
    stats: *mut mtcut_mt_stats,
) -> mtcut_status {
    run("mtcut_mt_statistics", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mt, out) = unsafe { (mt_ref(mt)?, Out::new(stats, "stats")?) };
        let out = VersionedOut::new(out)?;
        let s = mt.summary();
        out.write(mtcut_mt_stats {
            struct_size: size_of::<mtcut_mt_stats>(),
            vertices: s.vertices,
            tets: s.pool_tets,
            input_tets: s.input_tets,
            coarsest_tets: s.coarsest_tets,
            fragments: s.fragments,
            dag_depth: s.dag_depth as usize,
            components: s.components,
            min_error: s.min_error,
            max_error: s.max_error,
            heap_bytes: s.heap_bytes,
        });
        Ok(())
    })
}

/// Where an extraction uses its focus threshold (a `uint32_t`; other values are refused
/// with `MTCUT_STATUS_INVALID_ARGUMENT`).
pub type mtcut_focus_kind = u32;

/// No focus: the uniform threshold everywhere.
pub const MTCUT_FOCUS_NONE: mtcut_focus_kind = 0;
/// A sphere: `focus_center`, `focus_radius`.
pub const MTCUT_FOCUS_SPHERE: mtcut_focus_kind = 1;
/// An axis-aligned box: `focus_min`, `focus_max`.
pub const MTCUT_FOCUS_BOX: mtcut_focus_kind = 2;

/// What to extract from a model. A versioned struct: set `struct_size` to
/// `sizeof(mtcut_extract_options)` and fill it with `mtcut_extract_options_default` before
/// changing fields. The defaults extract the finest (input) mesh.
///
/// Each fragment (simplification step) is applied when its error is at most the threshold
/// that applies to it: `focus_threshold` if its box meets the focus region, `threshold`
/// elsewhere. Errors grow along the DAG, so this is a consistent mesh: the coarsest whose
/// tets all have error at most their threshold.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct mtcut_extract_options {
    /// Set by the caller to `sizeof(mtcut_extract_options)`.
    pub struct_size: usize,
    /// Uniform error threshold (>= 0; infinity gives the coarsest mesh). Default 0.
    pub threshold: f64,
    /// An `MTCUT_FOCUS_*` value. Default `MTCUT_FOCUS_NONE`.
    pub focus: mtcut_focus_kind,
    /// Error threshold inside the focus region (>= 0), usually below `threshold`.
    /// Default 0.
    pub focus_threshold: f64,
    /// Sphere focus: centre (finite) and radius (finite, >= 0). Default the origin, 0.
    pub focus_center: [f64; 3],
    pub focus_radius: f64,
    /// Box focus: corners (finite, min <= max on each axis). Default the origin twice.
    pub focus_min: [f64; 3],
    pub focus_max: [f64; 3],
    /// At most this many tets (fragments are refined in decreasing order of need while
    /// the mesh stays within it, never beyond what the thresholds ask); 0: no budget. When
    /// even the coarsest mesh is larger, it is returned and `budget_met` says so.
    /// Default 0.
    pub budget: usize,
}

// SAFETY: repr(C), `struct_size: usize` first; every field takes any bit pattern (the
// focus kind is validated after reading); FIRST_SIZE is within the struct.
unsafe impl Versioned for mtcut_extract_options {
    const NAME: &'static str = "mtcut_extract_options";
    const FIRST_SIZE: usize = offset_of!(mtcut_extract_options, budget) + size_of::<usize>();
}

impl mtcut_extract_options {
    pub(super) const DEFAULT: mtcut_extract_options = mtcut_extract_options {
        struct_size: size_of::<mtcut_extract_options>(),
        threshold: ExtractOptions::DEFAULT.threshold,
        focus: MTCUT_FOCUS_NONE,
        focus_threshold: 0.0,
        focus_center: [0.0; 3],
        focus_radius: 0.0,
        focus_min: [0.0; 3],
        focus_max: [0.0; 3],
        budget: 0,
    };

    /// The library's options (their ranges are checked by the extraction).
    pub(super) fn to_options(self) -> FfiResult<ExtractOptions> {
        let region = match self.focus {
            MTCUT_FOCUS_NONE => None,
            MTCUT_FOCUS_SPHERE => Some(Region::Sphere {
                center: DVec3::from_array(self.focus_center),
                radius: self.focus_radius,
            }),
            MTCUT_FOCUS_BOX => Some(Region::Box(Aabb {
                min: DVec3::from_array(self.focus_min),
                max: DVec3::from_array(self.focus_max),
            })),
            k => {
                return Err(Failure::invalid(format!(
                    "mtcut_extract_options.focus is {k}: not an MTCUT_FOCUS_* value (0 to 2)"
                )));
            }
        };
        let mut options = ExtractOptions::threshold(self.threshold)
            .with_budget((self.budget != 0).then_some(self.budget));
        if let Some(region) = region {
            options = options.with_focus(region, self.focus_threshold);
        }
        Ok(options)
    }
}

pub(super) fn extract_failure(e: ExtractError) -> Failure {
    Failure::invalid(e.to_string())
}

/// Fills the fields of `*options` within `options->struct_size` (which the caller sets
/// first) with their defaults.
///
/// # Safety
/// `options` must be a writable `mtcut_extract_options` whose `struct_size` is set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_extract_options_default(
    options: *mut mtcut_extract_options,
) -> mtcut_status {
    run("mtcut_extract_options_default", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let out = VersionedOut::new(unsafe { Out::new(options, "options") }?)?;
        out.write(mtcut_extract_options::DEFAULT);
        Ok(())
    })
}

/// What an extraction gave. A versioned struct: set `struct_size` to
/// `sizeof(mtcut_extract_stats)` before the call.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct mtcut_extract_stats {
    /// Set by the caller to `sizeof(mtcut_extract_stats)`; never written by the library.
    pub struct_size: usize,
    pub tets: usize,
    pub vertices: usize,
    /// Fragments not applied (drains included).
    pub refined_fragments: usize,
    /// Largest error of the fragments that created the extracted tets.
    pub max_error: f64,
    /// 0 when even the coarsest mesh exceeds the budget; 1 otherwise.
    pub budget_met: u32,
    /// Wall-clock time of the extraction.
    pub seconds: f64,
}

// SAFETY: repr(C), `struct_size: usize` first; FIRST_SIZE is within the struct.
unsafe impl Versioned for mtcut_extract_stats {
    const NAME: &'static str = "mtcut_extract_stats";
    const FIRST_SIZE: usize = offset_of!(mtcut_extract_stats, seconds) + size_of::<f64>();
}

fn extract_stats(s: &crate::mt::ExtractStats) -> mtcut_extract_stats {
    mtcut_extract_stats {
        struct_size: size_of::<mtcut_extract_stats>(),
        tets: s.tets,
        vertices: s.vertices,
        refined_fragments: s.refined_fragments,
        max_error: s.max_error,
        budget_met: u32::from(s.budget_met),
        seconds: s.seconds,
    }
}

/// The mesh at uniform error `threshold` (>= 0): every simplification step of error at
/// most `threshold` applied. 0 gives the input mesh, `INFINITY` the coarsest. A negative
/// or NaN threshold gives `MTCUT_STATUS_INVALID_ARGUMENT`. On success `*out` receives a
/// new mesh (with the model's cell and point data, see `mtcut_mt`).
///
/// # Safety
/// `mt` must be a live model handle; `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mt_extract_threshold(
    mt: *const mtcut_mt,
    threshold: f64,
    out: *mut *mut mtcut_mesh,
) -> mtcut_status {
    run("mtcut_mt_extract_threshold", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mt, out) = unsafe { (mt_ref(mt)?, Out::new(out, "out")?) };
        let e = mt
            .extract(&ExtractOptions::threshold(threshold))
            .map_err(extract_failure)?;
        out.write(mtcut_mesh::boxed(e.mesh));
        Ok(())
    })
}

/// The mesh `options_or_null` ask for (NULL: the defaults, the input mesh): uniform
/// threshold, a focus region with its own threshold, a budget. Invalid options (a
/// negative threshold, an unknown focus kind, a non-finite or inside-out region) give
/// `MTCUT_STATUS_INVALID_ARGUMENT` naming the field. On success `*out` receives a new
/// mesh and `stats_or_null`, if given, the numbers.
///
/// # Safety
/// `mt` must be a live model handle; a non-NULL `options_or_null` a readable
/// `mtcut_extract_options` with `struct_size` set; a non-NULL `stats_or_null` writable;
/// `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mt_extract(
    mt: *const mtcut_mt,
    options_or_null: *const mtcut_extract_options,
    stats_or_null: *mut mtcut_extract_stats,
    out: *mut *mut mtcut_mesh,
) -> mtcut_status {
    run("mtcut_mt_extract", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mt, options, stats, out) = unsafe {
            (
                mt_ref(mt)?,
                read_optional(
                    options_or_null,
                    "options_or_null",
                    mtcut_extract_options::DEFAULT,
                )?,
                Out::optional(stats_or_null, "stats_or_null")?,
                Out::new(out, "out")?,
            )
        };
        let stats = stats.map(VersionedOut::new).transpose()?;
        let e = mt
            .extract(&options.to_options()?)
            .map_err(extract_failure)?;
        if let Some(s) = stats {
            s.write(extract_stats(&e.stats));
        }
        out.write(mtcut_mesh::boxed(e.mesh));
        Ok(())
    })
}

/// An extraction kept up to date incrementally (opaque): moving its focus or thresholds
/// touches only the fragments whose decision changes, and gives exactly the mesh a fresh
/// extraction would. Made by `mtcut_frontier_new`, released with `mtcut_frontier_free`.
/// It shares the model (read-only), which stays alive while the frontier does.
pub struct mtcut_frontier {
    mt: Arc<Mt>,
    frontier: Frontier,
}

/// A frontier at what `options_or_null` ask for (NULL: the input mesh), into `*out`.
/// Options are checked as in `mtcut_mt_extract`.
///
/// # Safety
/// `mt` must be a live model handle; a non-NULL `options_or_null` a readable
/// `mtcut_extract_options` with `struct_size` set; `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_frontier_new(
    mt: *const mtcut_mt,
    options_or_null: *const mtcut_extract_options,
    out: *mut *mut mtcut_frontier,
) -> mtcut_status {
    run("mtcut_frontier_new", || {
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
        let frontier = Frontier::new(mt, &options.to_options()?).map_err(extract_failure)?;
        out.write(Box::into_raw(Box::new(mtcut_frontier {
            mt: Arc::clone(mt),
            frontier,
        })));
        Ok(())
    })
}

/// What a frontier update changed. A versioned struct: set `struct_size` to
/// `sizeof(mtcut_frontier_update_stats)` before the call.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct mtcut_frontier_update_stats {
    /// Set by the caller; never written by the library.
    pub struct_size: usize,
    /// Fragments examined because their threshold may have changed.
    pub candidates: usize,
    /// Fragments un-applied (the mesh got finer there) and applied (coarser).
    pub refined: usize,
    pub coarsened: usize,
    /// Tets that entered and left the mesh.
    pub tets_added: usize,
    pub tets_removed: usize,
    /// Tets in the mesh after the update.
    pub tets: usize,
    /// Wall-clock time of the update.
    pub seconds: f64,
}

// SAFETY: repr(C), `struct_size: usize` first; FIRST_SIZE is within the struct.
unsafe impl Versioned for mtcut_frontier_update_stats {
    const NAME: &'static str = "mtcut_frontier_update_stats";
    const FIRST_SIZE: usize = offset_of!(mtcut_frontier_update_stats, seconds) + size_of::<f64>();
}

/// Moves the frontier to what `options` ask for (required: the new focus, thresholds or
/// budget), touching only what changes. Invalid options are refused as in
/// `mtcut_mt_extract`, the frontier unchanged. `stats_or_null`, if given, receives what
/// changed.
///
/// # Safety
/// `frontier` must be a live frontier handle used by no other thread during the call;
/// `options` a readable `mtcut_extract_options` with `struct_size` set; a non-NULL
/// `stats_or_null` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_frontier_update(
    frontier: *mut mtcut_frontier,
    options: *const mtcut_extract_options,
    stats_or_null: *mut mtcut_frontier_update_stats,
) -> mtcut_status {
    run("mtcut_frontier_update", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (f, options, stats) = unsafe {
            (
                deref_mut(frontier, "frontier")?,
                deref(options, "options")?,
                Out::optional(stats_or_null, "stats_or_null")?,
            )
        };
        // SAFETY: `options` is non-NULL and aligned (checked just above).
        let options = unsafe {
            read_optional(
                options as *const mtcut_extract_options,
                "options",
                mtcut_extract_options::DEFAULT,
            )
        }?;
        let stats = stats.map(VersionedOut::new).transpose()?;
        let options = options.to_options()?;
        let u = f
            .frontier
            .update(&f.mt, &options)
            .map_err(extract_failure)?;
        if let Some(s) = stats {
            s.write(mtcut_frontier_update_stats {
                struct_size: size_of::<mtcut_frontier_update_stats>(),
                candidates: u.candidates,
                refined: u.refined,
                coarsened: u.coarsened,
                tets_added: u.tets_added,
                tets_removed: u.tets_removed,
                tets: f.frontier.nb_tets(),
                seconds: u.seconds,
            });
        }
        Ok(())
    })
}

/// Number of tets in the frontier's mesh; 0 (with the last error set) when `frontier` is
/// NULL.
///
/// # Safety
/// A non-NULL `frontier` must be a live frontier handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_frontier_tet_count(frontier: *const mtcut_frontier) -> usize {
    run_count("mtcut_frontier_tet_count", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        Ok(unsafe { deref(frontier, "frontier") }?.frontier.nb_tets())
    })
}

/// The frontier's current mesh as a new mesh in `*out` (tets in increasing model id, with
/// the model's cell and point data, as `mtcut_mt_extract` gives).
///
/// # Safety
/// `frontier` must be a live frontier handle; `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_frontier_mesh(
    frontier: *const mtcut_frontier,
    out: *mut *mut mtcut_mesh,
) -> mtcut_status {
    run("mtcut_frontier_mesh", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (f, out) = unsafe { (deref(frontier, "frontier")?, Out::new(out, "out")?) };
        out.write(mtcut_mesh::boxed(f.frontier.to_extraction(&f.mt).mesh));
        Ok(())
    })
}

/// Releases a frontier. NULL is allowed (nothing happens).
///
/// # Safety
/// A non-NULL `frontier` must be a live handle from this library, not used after the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_frontier_free(frontier: *mut mtcut_frontier) {
    if frontier.is_null() {
        return;
    }
    let _ = std::panic::catch_unwind(|| {
        // SAFETY: a live handle made by Box::into_raw (the caller's contract).
        drop(unsafe { Box::from_raw(frontier) });
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn option_defaults_are_the_library_defaults() {
        let b = mtcut_build_options::DEFAULT.to_options().unwrap();
        let d = BuildOptions::DEFAULT;
        assert_eq!(
            (
                b.boundary_tolerance,
                b.preserve_features,
                b.feature_angle_degrees,
                b.min_quality,
                b.target_tets
            ),
            (
                d.boundary_tolerance,
                d.preserve_features,
                d.feature_angle_degrees,
                d.min_quality,
                d.target_tets
            )
        );
        assert_eq!(b.error.name(), d.error.name());
        let e = mtcut_extract_options::DEFAULT.to_options().unwrap();
        assert_eq!(e, ExtractOptions::DEFAULT);
    }
}
