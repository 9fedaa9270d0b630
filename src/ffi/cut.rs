//! Cutting a mesh: by a planar convex polygon (paper §3), or by the surface a straight
//! blade sweeps during one time step (the scalpel sweep), with the cut's statistics.

use super::guard::{Out, OutSlice, deref_mut, run, slice};
use super::mesh::{flat_len, mtcut_mesh};
use super::status::{Failure, FfiResult, MTCUT_STATUS_INVALID_MESH, mtcut_status};
use super::versioned::{Versioned, VersionedOut, read_optional};
use crate::cut::{CutError, CutOptions, CutStats, Scheme};
use crate::geom::{CutPolygon, DVec3, PolygonError, SWEEP_PLANARITY, Tolerance, scalpel_sweep};
use std::mem::offset_of;

/// How cut tets are replaced (a `uint32_t`; other values are refused with
/// `MTCUT_STATUS_INVALID_ARGUMENT`).
pub type mtcut_cut_scheme = u32;

/// The paper's look-up tables (section 4.2): a minimal conforming tetrahedralization of
/// each cut tet. The default.
pub const MTCUT_CUT_SCHEME_LUT: mtcut_cut_scheme = 0;
/// The 1:17 scheme of Bielser et al. (1999), the paper's baseline: 17 tets per cut tet.
pub const MTCUT_CUT_SCHEME_BIELSER17: mtcut_cut_scheme = 1;

/// Options of a cut. A versioned struct: set `struct_size` to `sizeof(mtcut_cut_options)`
/// and fill it with `mtcut_cut_options_default` before changing fields.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct mtcut_cut_options {
    /// Set by the caller to `sizeof(mtcut_cut_options)`.
    pub struct_size: usize,
    /// An `MTCUT_CUT_SCHEME_*` value. Default `MTCUT_CUT_SCHEME_LUT`.
    pub scheme: mtcut_cut_scheme,
    /// Snapping tolerance, relative to each vertex's longest incident edge, in [1e-9, 0.25]: a
    /// vertex closer than that to the cut is taken to lie on it, so every cut point divides
    /// its edge at a parameter in (snap, 1 - snap) and no child is a sliver. The cut
    /// surface may then pass up to snap x edge length off the plane; no vertex moves.
    /// Default 0.2.
    pub snap: f64,
    /// Crack tips inside a face stay at least this fraction of their segment from its
    /// ends, in [0.01, 0.5] (nearer, children come out flat). Default 0.5 (the middle:
    /// best element quality; smaller values follow the polygon's contour more closely,
    /// which a blade swept in steps needs for its cracks to join).
    pub face_point_margin: f64,
    /// Nonzero: count the connected components after the cut (a pass over the whole
    /// mesh), reported in `mtcut_cut_stats.components`. Default 1.
    pub count_components: u32,
    /// Nonzero: continue the cracks of earlier cuts of this mesh handle, as a scalpel moved
    /// in steps needs (vertices on the plane just outside the polygon and the crack tips of
    /// earlier cuts near it count as on the cut; see `mtcut_cut_options_scalpel`). Default
    /// 0 (`mtcut_cut_options_default`), 1 (`mtcut_cut_options_scalpel`). A caller whose
    /// struct ends before this field (built against an older header) gets 0 for a cut, 1
    /// for a scalpel sweep.
    pub continue_cracks: u32,
}

// SAFETY: repr(C), `struct_size: usize` first; every field takes any bit pattern (the
// scheme is validated after reading); FIRST_SIZE is within the struct.
unsafe impl Versioned for mtcut_cut_options {
    const NAME: &'static str = "mtcut_cut_options";
    const FIRST_SIZE: usize = offset_of!(mtcut_cut_options, count_components) + size_of::<u32>();
}

impl mtcut_cut_options {
    const DEFAULT: mtcut_cut_options = mtcut_cut_options {
        struct_size: size_of::<mtcut_cut_options>(),
        scheme: MTCUT_CUT_SCHEME_LUT,
        snap: CutOptions::DEFAULT.snap.relative,
        face_point_margin: CutOptions::DEFAULT.face_point_margin,
        count_components: CutOptions::DEFAULT.count_components as u32,
        continue_cracks: CutOptions::DEFAULT.continue_cracks as u32,
    };

    const SCALPEL: mtcut_cut_options = mtcut_cut_options {
        struct_size: size_of::<mtcut_cut_options>(),
        scheme: MTCUT_CUT_SCHEME_LUT,
        snap: CutOptions::SCALPEL.snap.relative,
        face_point_margin: CutOptions::SCALPEL.face_point_margin,
        count_components: CutOptions::SCALPEL.count_components as u32,
        continue_cracks: CutOptions::SCALPEL.continue_cracks as u32,
    };

    /// The library's options, every value checked.
    fn to_options(self) -> FfiResult<CutOptions> {
        let scheme = match self.scheme {
            MTCUT_CUT_SCHEME_LUT => Scheme::Lut,
            MTCUT_CUT_SCHEME_BIELSER17 => Scheme::Bielser17,
            s => {
                return Err(Failure::invalid(format!(
                    "mtcut_cut_options.scheme is {s}: neither MTCUT_CUT_SCHEME_LUT (0) nor \
                     MTCUT_CUT_SCHEME_BIELSER17 (1)"
                )));
            }
        };
        let options = CutOptions::DEFAULT
            .with_scheme(scheme)
            .with_snap(Tolerance {
                relative: self.snap,
            })
            .with_face_point_margin(self.face_point_margin)
            .with_count_components(self.count_components != 0)
            .with_continue_cracks(self.continue_cracks != 0);
        options.check().map_err(cut_failure)?;
        Ok(options)
    }
}

/// Fills the fields of `*options` within `options->struct_size` (which the caller sets
/// first) with their defaults.
///
/// # Safety
/// `options` must be a writable `mtcut_cut_options` whose `struct_size` is set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_cut_options_default(
    options: *mut mtcut_cut_options,
) -> mtcut_status {
    run("mtcut_cut_options_default", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let out = VersionedOut::new(unsafe { Out::new(options, "options") }?)?;
        out.write(mtcut_cut_options::DEFAULT);
        Ok(())
    })
}

/// Fills the fields of `*options` within `options->struct_size` (which the caller sets
/// first) with the options of a scalpel moved in steps (cracks continued, face points at
/// the smallest margin 0.01, snap 1e-6; the default of `mtcut_mesh_scalpel_sweep`): each
/// step continues the crack of the last, whether the blade moves straight, turns or
/// tilts. With the default options such steps leave bridges of material and loose chips,
/// and from about 30 steps across a body flat tets.
///
/// # Safety
/// `options` must be a writable `mtcut_cut_options` whose `struct_size` is set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_cut_options_scalpel(
    options: *mut mtcut_cut_options,
) -> mtcut_status {
    run("mtcut_cut_options_scalpel", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let out = VersionedOut::new(unsafe { Out::new(options, "options") }?)?;
        out.write(mtcut_cut_options::SCALPEL);
        Ok(())
    })
}

/// What a cut did. A versioned struct: set `struct_size` to `sizeof(mtcut_cut_stats)`
/// before the call. Times are wall-clock seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct mtcut_cut_stats {
    /// Set by the caller to `sizeof(mtcut_cut_stats)`; never written by the library.
    pub struct_size: usize,
    /// Tets whose vertices were classified against the cut (reached through the tets'
    /// bounding-box hierarchy).
    pub tets_tested: usize,
    /// Tets the cut's plane crosses or that touch the cut at a vertex.
    pub tets_candidate: usize,
    /// Tets replaced.
    pub tets_cut: usize,
    /// Tets created to replace them.
    pub tets_created: usize,
    /// Vertices added: cut points (two copies per cut edge), crack tips inside faces, and
    /// copies of vertices the cut passes through.
    pub vertices_added: usize,
    /// Cut-point copies among them.
    pub cut_points: usize,
    /// Crack tips inside faces among them.
    pub face_points: usize,
    /// Copies of vertices the cut passes through among them.
    pub vertex_copies: usize,
    /// Distinct vertices snapped onto the cut.
    pub vertices_snapped: usize,
    /// Tets and vertices of the mesh after the cut.
    pub tets_after: usize,
    pub vertices_after: usize,
    /// Connected components after the cut; `SIZE_MAX` when they were not counted
    /// (`mtcut_cut_options.count_components` 0).
    pub components: usize,
    /// Building the tets' hierarchy and the vertices' scales: on a mesh's first cut (and
    /// the first after `mtcut_mesh_set_vertices`), 0 on the others, which reuse them.
    pub seconds_build: f64,
    /// The cut itself: finding the candidates, classifying, splitting, separating.
    pub seconds_cut: f64,
    /// Counting the components.
    pub seconds_components: f64,
    /// Second version. Polygons of the call that lay close to the plane of an earlier cut
    /// of the model (every corner within 1e-5 of its bounding-box diagonal, the normal
    /// within 1e-3 rad) without lying in it, and were cut in that plane, their corners
    /// projected onto it (`mtcut_mt_cut`, `mtcut_live_cut`; a blade re-entering an
    /// incision); 0 for plain meshes. A caller whose `struct_size` ends before it (the
    /// first version) does not get it.
    pub polygons_moved_to_plane: usize,
}

// SAFETY: repr(C), `struct_size: usize` first; FIRST_SIZE is within the struct.
unsafe impl Versioned for mtcut_cut_stats {
    const NAME: &'static str = "mtcut_cut_stats";
    const FIRST_SIZE: usize = offset_of!(mtcut_cut_stats, seconds_components) + size_of::<f64>();
}

impl mtcut_cut_stats {
    /// Adds a cut's statistics to these (several polygons of one sweep): counts and times
    /// add up, the mesh's state is the last one's.
    pub(super) fn add(&mut self, s: &CutStats, build_seconds: f64) {
        self.tets_tested += s.tets_tested;
        self.tets_candidate += s.tets_candidate;
        self.tets_cut += s.tets_cut;
        self.tets_created += s.tets_created;
        self.vertices_added += s.vertices_added;
        self.cut_points += s.cut_points;
        self.face_points += s.face_points;
        self.vertex_copies += s.vertex_copies;
        self.vertices_snapped += s.vertices_snapped;
        self.tets_after = s.tets_after;
        self.vertices_after = s.vertices_after;
        self.components = s.components.unwrap_or(usize::MAX);
        self.seconds_build = build_seconds;
        self.seconds_cut += s.time.cut;
        self.seconds_components += s.time.components;
    }
}

pub(crate) fn cut_failure(e: CutError) -> Failure {
    match e {
        CutError::InvertedTet { .. } | CutError::MtInconsistent { .. } => {
            Failure::new(MTCUT_STATUS_INVALID_MESH, e.to_string())
        }
        e => Failure::invalid(e.to_string()),
    }
}

pub(super) fn polygon_failure(e: PolygonError, arg: &str) -> Failure {
    Failure::invalid(format!("argument `{arg}`: {e}"))
}

/// The `n` corners of a polygon at `xyz`; more than a polygon may have are refused before
/// anything is read (a wrong count must not make the library read past the caller's array).
///
/// # Safety
/// A non-NULL `xyz` must point to `3 x n` readable doubles.
pub(super) unsafe fn corners(xyz: *const f64, n: usize, arg: &str) -> FfiResult<Vec<DVec3>> {
    if n > crate::geom::MAX_POLYGON_POINTS {
        return Err(polygon_failure(
            PolygonError::TooManyPoints { count: n },
            arg,
        ));
    }
    // SAFETY: forwarded contract.
    unsafe { points(xyz, n, arg) }
}

/// `n` points of three coordinates at `xyz`.
///
/// # Safety
/// A non-NULL `xyz` must point to `3 x n` readable doubles.
pub(super) unsafe fn points(xyz: *const f64, n: usize, arg: &str) -> FfiResult<Vec<DVec3>> {
    // SAFETY: forwarded contract.
    let flat: &[f64] = unsafe { slice(xyz, flat_len(n, 3, "points")?, arg) }?;
    Ok(flat
        .chunks_exact(3)
        .map(|p| DVec3::new(p[0], p[1], p[2]))
        .collect())
}

/// Applies `polygons` in turn to `mesh`. Everything has been checked: the only failures
/// left are a mesh whose vertices were moved so that a tet is inverted (found before the
/// first cut), a mesh outgrowing its ids (2^31 vertices or tets) and a cut that would make
/// a flat tet, which each cut detects before it changes anything.
fn cut_with(
    mesh: &mut mtcut_mesh,
    polygons: &[CutPolygon],
    options: CutOptions,
) -> FfiResult<mtcut_cut_stats> {
    let (cutter, build) = mesh.cutter(options).map_err(cut_failure)?;
    let mut stats = mtcut_cut_stats::default();
    let mut result = Ok(());
    for p in polygons {
        match cutter.cut(p) {
            Ok(r) => stats.add(&r.stats, build),
            Err(e) => {
                result = Err(cut_failure(e));
                break;
            }
        }
    }
    result.map(|()| stats)
}

/// Cuts `mesh` with the planar convex polygon whose `n_points` corners, in order around
/// it, are at `polygon_xyz` (x, y, z of each), with the default options: every tet the
/// polygon crosses is replaced by tets it does not cross, and the two sides of the cut
/// get their own copies of the vertices on it (the mesh may fall apart into several
/// components: `mtcut_mesh_component_count`). The polygon must have 3 to
/// `MTCUT_POLYGON_MAX_POINTS` distinct, finite corners of magnitude at most 1e50, be
/// planar (within 1e-6 of its diameter) and convex; otherwise
/// `MTCUT_STATUS_INVALID_ARGUMENT` says which corner is wrong and the mesh is unchanged.
/// Attribute rows of new vertices are interpolated (an extraction's vertex ids,
/// "mt_vertex", are -1 at points the cut makes and copied at duplicated vertices); new
/// tets inherit their parent's rows, and the tet column "mtcut:cut" numbers the cut that
/// created each tet (0: none).
/// `stats_or_null`, if given (with `struct_size` set), receives the statistics.
///
/// # Safety
/// `mesh` must be a live mesh handle used by no other thread during the call;
/// `polygon_xyz` readable for `3 x n_points` doubles; a non-NULL `stats_or_null` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_cut(
    mesh: *mut mtcut_mesh,
    polygon_xyz: *const f64,
    n_points: usize,
    stats_or_null: *mut mtcut_cut_stats,
) -> mtcut_status {
    run("mtcut_mesh_cut", || {
        // SAFETY: the caller's contract, forwarded.
        unsafe { cut_polygon(mesh, polygon_xyz, n_points, std::ptr::null(), stats_or_null) }
    })
}

/// `mtcut_mesh_cut` with options (`options_or_null` NULL: the defaults).
///
/// # Safety
/// As `mtcut_mesh_cut`; a non-NULL `options_or_null` must be a readable
/// `mtcut_cut_options` with `struct_size` set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_cut_with_options(
    mesh: *mut mtcut_mesh,
    polygon_xyz: *const f64,
    n_points: usize,
    options_or_null: *const mtcut_cut_options,
    stats_or_null: *mut mtcut_cut_stats,
) -> mtcut_status {
    run("mtcut_mesh_cut_with_options", || {
        // SAFETY: the caller's contract, forwarded.
        unsafe { cut_polygon(mesh, polygon_xyz, n_points, options_or_null, stats_or_null) }
    })
}

/// The body of both polygon cuts.
///
/// # Safety
/// As `mtcut_mesh_cut_with_options`.
unsafe fn cut_polygon(
    mesh: *mut mtcut_mesh,
    polygon_xyz: *const f64,
    n_points: usize,
    options: *const mtcut_cut_options,
    stats: *mut mtcut_cut_stats,
) -> FfiResult<()> {
    // SAFETY: the caller's contract, forwarded to the checks.
    let (mesh, corners, options, stats) = unsafe {
        (
            deref_mut(mesh, "mesh")?,
            corners(polygon_xyz, n_points, "polygon_xyz")?,
            read_optional(options, "options_or_null", mtcut_cut_options::DEFAULT)?,
            Out::optional(stats, "stats_or_null")?,
        )
    };
    let stats = stats.map(VersionedOut::new).transpose()?;
    let options = options.to_options()?;
    let polygon = CutPolygon::new(&corners).map_err(|e| polygon_failure(e, "polygon_xyz"))?;
    let result = cut_with(mesh, &[polygon], options)?;
    if let Some(out) = stats {
        out.write(result);
    }
    Ok(())
}

/// Cuts `mesh` along the surface a straight blade sweeps in one time step: the segment
/// from `start_xyz[0..3]` to `start_xyz[3..6]` at the start of the step, and from
/// `end_xyz[0..3]` to `end_xyz[3..6]` at its end (corresponding ends). The swept
/// quadrilateral is cut as one polygon when it is planar (within 1e-9 of its size) and
/// convex, else as two triangles (along its shorter diagonal): the polygons
/// `mtcut_scalpel_sweep_polygons` gives; an end that does not move makes it one
/// triangle. A blade that does not move, or a sweep that folds over itself, gives
/// `MTCUT_STATUS_INVALID_ARGUMENT` with the mesh unchanged. Called once per time step on
/// the same handle, each step continues the crack the earlier ones made (the handle keeps
/// its crack tips): with NULL options those of `mtcut_cut_options_scalpel`, which a blade
/// moving straight, turning or tilting needs; start from them to change options. Steps
/// much shorter than the mesh's edges fill the crack's front with slivers: see
/// `mtcut_blade_advance` for deferring them.
/// Statistics as in `mtcut_mesh_cut_with_options`; for two triangles the counts and times
/// add up. (The one
/// failure found after the first triangle was applied: the second would make the mesh
/// exceed 2^31 vertices or tets; the mesh then keeps the first triangle's cut.)
///
/// # Safety
/// `mesh` must be a live mesh handle used by no other thread during the call; `start_xyz`
/// and `end_xyz` readable for 6 doubles each; a non-NULL `options_or_null` a readable
/// `mtcut_cut_options` with `struct_size` set; a non-NULL `stats_or_null` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_scalpel_sweep(
    mesh: *mut mtcut_mesh,
    start_xyz: *const f64,
    end_xyz: *const f64,
    options_or_null: *const mtcut_cut_options,
    stats_or_null: *mut mtcut_cut_stats,
) -> mtcut_status {
    run("mtcut_mesh_scalpel_sweep", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, start, end, options, stats) = unsafe {
            (
                deref_mut(mesh, "mesh")?,
                points(start_xyz, 2, "start_xyz")?,
                points(end_xyz, 2, "end_xyz")?,
                read_optional(
                    options_or_null,
                    "options_or_null",
                    mtcut_cut_options::SCALPEL,
                )?,
                Out::optional(stats_or_null, "stats_or_null")?,
            )
        };
        let stats = stats.map(VersionedOut::new).transpose()?;
        let options = options.to_options()?;
        let polygons = sweep(&start, &end)?;
        let result = cut_with(mesh, &polygons, options)?;
        if let Some(out) = stats {
            out.write(result);
        }
        Ok(())
    })
}

/// How far a blade has moved across its own line: the larger distance of `to_xyz`'s two
/// ends (`to_xyz[0..3]`, `to_xyz[3..6]`) from the line through `from_xyz`'s, into
/// `*advance` (a blade sliding along its edge has not moved; one turning about its middle
/// has moved as far as its ends). A blade moved in steps much shorter than the mesh's
/// edges splits the tets at its crack's front again at every step, filling it with
/// slivers; a host defers a step while the advance from where its crack ends (the end of
/// the last sweep it cut) is below about half `mtcut_mesh_median_edge_length`, then cuts
/// the sweep from there, and at the end of its path cuts what is left (as
/// `mtcut::cut::Incision` and `mtcut scalpel --min-advance` do; see the README, "A scalpel
/// on a plain mesh"). A coordinate that is not finite or larger in magnitude than 1e50
/// gives `MTCUT_STATUS_INVALID_ARGUMENT`, nothing written.
///
/// # Safety
/// `from_xyz` and `to_xyz` readable for 6 doubles each; `advance` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_blade_advance(
    from_xyz: *const f64,
    to_xyz: *const f64,
    advance: *mut f64,
) -> mtcut_status {
    run("mtcut_blade_advance", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (from, to, advance) = unsafe {
            (
                points(from_xyz, 2, "from_xyz")?,
                points(to_xyz, 2, "to_xyz")?,
                Out::new(advance, "advance")?,
            )
        };
        crate::geom::check_points(&from).map_err(|e| polygon_failure(e, "from_xyz"))?;
        crate::geom::check_points(&to).map_err(|e| polygon_failure(e, "to_xyz"))?;
        advance.write(crate::cut::blade_advance(
            [from[0], from[1]],
            [to[0], to[1]],
        ));
        Ok(())
    })
}

/// The polygons a blade sweeps from `start` to `end` (two points each), as the C ABI's
/// scalpel functions cut them.
fn sweep(start: &[DVec3], end: &[DVec3]) -> FfiResult<Vec<CutPolygon>> {
    scalpel_sweep([start[0], start[1]], [end[0], end[1]], SWEEP_PLANARITY)
        .map_err(|e| polygon_failure(e, "start_xyz/end_xyz"))
}

/// The most corners the polygons of one sweep have together (two triangles), for the
/// output of `mtcut_scalpel_sweep_polygons`.
pub const MTCUT_SWEEP_MAX_POINTS: usize = 6;

/// The most corners a cutting polygon may have (more are refused with
/// `MTCUT_STATUS_INVALID_ARGUMENT`: checking a polygon compares every pair of corners).
pub const MTCUT_POLYGON_MAX_POINTS: usize = 4096;
const _: () = assert!(MTCUT_POLYGON_MAX_POINTS == crate::geom::MAX_POLYGON_POINTS);

/// The planar convex polygons a straight blade sweeps in one time step, in the order to
/// cut them: what `mtcut_mesh_scalpel_sweep` cuts, and what a host moving a scalpel
/// through a model cuts with `mtcut_mt_cut` (or `mtcut_live_cut`), one call per polygon.
/// The blade is the segment from `start_xyz[0..3]` to `start_xyz[3..6]` at the start of
/// the step and from `end_xyz[0..3]` to `end_xyz[3..6]` at its end (corresponding ends).
/// The sweep is one quadrilateral when it is planar (within 1e-9 of its size) and convex,
/// one triangle when an end does not move, and two triangles otherwise (along its shorter
/// diagonal, or along the other when that one would fold). `polygons_xyz` (room for
/// `3 x MTCUT_SWEEP_MAX_POINTS` doubles) receives the corners, polygon after polygon, in
/// order around each; `point_counts` (room for 2) the number of corners of each;
/// `*n_polygons` 1 or 2. A blade that does not move, a sweep folding over itself or a
/// coordinate that is not finite or larger in magnitude than 1e50 gives
/// `MTCUT_STATUS_INVALID_ARGUMENT`, nothing written.
///
/// # Safety
/// `start_xyz` and `end_xyz` readable for 6 doubles each; `polygons_xyz` writable for
/// `3 x MTCUT_SWEEP_MAX_POINTS` doubles, `point_counts` for 2 `size_t`, `n_polygons` for
/// one.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_scalpel_sweep_polygons(
    start_xyz: *const f64,
    end_xyz: *const f64,
    polygons_xyz: *mut f64,
    point_counts: *mut usize,
    n_polygons: *mut usize,
) -> mtcut_status {
    run("mtcut_scalpel_sweep_polygons", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (start, end, xyz, counts, n) = unsafe {
            (
                points(start_xyz, 2, "start_xyz")?,
                points(end_xyz, 2, "end_xyz")?,
                OutSlice::new(polygons_xyz, MTCUT_SWEEP_MAX_POINTS, "polygons_xyz")?,
                OutSlice::new(point_counts, 2, "point_counts")?,
                Out::new(n_polygons, "n_polygons")?,
            )
        };
        let polygons = sweep(&start, &end)?;
        // Plain loops: a flat_map over coordinate arrays made memcheck report reads of
        // uninitialised memory inside the iterator (valgrind 3.19, release build).
        let mut corners: Vec<f64> = Vec::with_capacity(3 * MTCUT_SWEEP_MAX_POINTS);
        for p in &polygons {
            for q in p.points() {
                corners.extend_from_slice(&q.to_array());
            }
        }
        let sizes: Vec<usize> = polygons.iter().map(|p| p.points().len()).collect();
        // At most two triangles or one quadrilateral: both fit.
        xyz.write(&corners, 3, "points")?;
        counts.write(&sizes, 1, "polygons")?;
        n.write(polygons.len());
        Ok(())
    })
}
