//! What a host asks about a mesh: validity, volume, bounding box, boundary, element
//! quality, connected components.

use super::guard::{Out, deref, run};
use super::mesh::{mesh_ref, mtcut_mesh};
use super::status::{Failure, FfiResult, mtcut_status};
use super::strings::StringOut;
use super::versioned::{Versioned, VersionedOut};
use crate::mesh::{Severity, TetId};
use std::ffi::c_char;
use std::mem::offset_of;

/// Checks every invariant of `mesh` (orientation, face sharing, manifold boundary, no
/// hanging vertex, finite coordinates, attribute lengths): meshes are valid when made,
/// but `mtcut_mesh_set_vertices` can invert tets. `*valid` receives the verdict. The
/// message ("valid mesh", or "invalid mesh: " and each problem with its count and first
/// examples; warnings such as unused vertices follow) is a diagnostic, so it is truncated
/// like `snprintf` to `message_capacity` bytes with its NUL; `message_or_null` may be NULL
/// (with `message_capacity` 0) to skip it. `*message_length_or_null`, if given, receives
/// the full length without the NUL.
///
/// # Safety
/// `mesh` must be a live mesh handle; `valid` writable; a non-NULL `message_or_null`
/// writable for `message_capacity` bytes; a non-NULL `message_length_or_null` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_validate(
    mesh: *const mtcut_mesh,
    valid: *mut bool,
    message_or_null: *mut c_char,
    message_capacity: usize,
    message_length_or_null: *mut usize,
) -> mtcut_status {
    run("mtcut_mesh_validate", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let mesh = unsafe { mesh_ref(mesh) }?;
        let check = || {
            let report = mesh.validate();
            let mut text = report.to_string();
            let warnings = report.lines(Severity::Warning);
            if !warnings.is_empty() {
                text = format!("{text}; warnings: {}", warnings.join("; "));
            }
            (report.is_valid(), text)
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

/// The outputs of a `*_validate` function, checked before anything is computed: `check`
/// (the verdict and its message) runs only when they are good; the message is truncated
/// like `snprintf` and its full length written when asked for.
///
/// # Safety
/// `valid` writable; a non-NULL `message_or_null` writable for `message_capacity` bytes; a
/// non-NULL `message_length_or_null` writable.
pub(super) unsafe fn write_verdict(
    valid: *mut bool,
    message_or_null: *mut c_char,
    message_capacity: usize,
    message_length_or_null: *mut usize,
    check: impl FnOnce() -> (bool, String),
) -> FfiResult<()> {
    // SAFETY: the caller's contract, forwarded to the checks.
    let (valid, message, length) = unsafe {
        (
            Out::new(valid, "valid")?,
            StringOut::new(message_or_null, message_capacity, "message_or_null")?,
            Out::optional(message_length_or_null, "message_length_or_null")?,
        )
    };
    let (verdict, text) = check();
    message.write_truncated(&text)?;
    valid.write(verdict);
    if let Some(length) = length {
        length.write(text.len());
    }
    Ok(())
}

/// Total volume (the sum of the tets' volumes) into `*volume`.
///
/// # Safety
/// `mesh` must be a live mesh handle; `volume` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_volume(
    mesh: *const mtcut_mesh,
    volume: *mut f64,
) -> mtcut_status {
    run("mtcut_mesh_volume", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, volume) = unsafe { (mesh_ref(mesh)?, Out::new(volume, "volume")?) };
        volume.write(mesh.volume());
        Ok(())
    })
}

/// The median length of the tets' edges (each counted once per tet holding it) into
/// `*length`: a typical edge, the unit in which to defer a scalpel's short steps (see
/// `mtcut_blade_advance`). A mesh without tets gives `MTCUT_STATUS_INVALID_ARGUMENT`,
/// nothing written.
///
/// # Safety
/// `mesh` must be a live mesh handle; `length` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_median_edge_length(
    mesh: *const mtcut_mesh,
    length: *mut f64,
) -> mtcut_status {
    run("mtcut_mesh_median_edge_length", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, length) = unsafe { (mesh_ref(mesh)?, Out::new(length, "length")?) };
        let median = mesh
            .median_edge_length()
            .ok_or_else(|| Failure::invalid("mesh: it has no tets, so no edges to measure"))?;
        length.write(median);
        Ok(())
    })
}

/// The axis-aligned bounding box of all vertices: `min_xyz` and `max_xyz` receive three
/// doubles each.
///
/// # Safety
/// `mesh` must be a live mesh handle; `min_xyz` and `max_xyz` writable for 3 doubles each.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_bounding_box(
    mesh: *const mtcut_mesh,
    min_xyz: *mut f64,
    max_xyz: *mut f64,
) -> mtcut_status {
    run("mtcut_mesh_bounding_box", || {
        // SAFETY: the caller's contract, forwarded to the checks; three doubles are an
        // array the caller promised, written through `[f64; 3]` (alignment of f64).
        let (mesh, lo, hi) = unsafe {
            (
                mesh_ref(mesh)?,
                Out::new(min_xyz.cast::<[f64; 3]>(), "min_xyz")?,
                Out::new(max_xyz.cast::<[f64; 3]>(), "max_xyz")?,
            )
        };
        let b = mesh.bbox();
        lo.write(b.min.to_array());
        hi.write(b.max.to_array());
        Ok(())
    })
}

/// The boundary surface: `*face_count` receives its number of triangles, `*area` its area.
///
/// # Safety
/// `mesh` must be a live mesh handle; `face_count` and `area` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_boundary(
    mesh: *const mtcut_mesh,
    face_count: *mut usize,
    area: *mut f64,
) -> mtcut_status {
    run("mtcut_mesh_boundary", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, count, area) = unsafe {
            (
                mesh_ref(mesh)?,
                Out::new(face_count, "face_count")?,
                Out::new(area, "area")?,
            )
        };
        let boundary = mesh.boundary();
        count.write(boundary.triangles.len());
        area.write(boundary.area);
        Ok(())
    })
}

/// Element quality over the whole mesh. A versioned struct: set `struct_size` to
/// `sizeof(mtcut_quality)` before the call (see "Structs that grow" above).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct mtcut_quality {
    /// Set by the caller to `sizeof(mtcut_quality)`; never written by the library.
    pub struct_size: usize,
    /// Number of tets measured.
    pub tets: usize,
    /// Smallest interior dihedral angle, in degrees.
    pub min_dihedral_deg: f64,
    /// Largest interior dihedral angle, in degrees.
    pub max_dihedral_deg: f64,
    /// Smallest tet volume.
    pub min_volume: f64,
    /// Largest tet volume.
    pub max_volume: f64,
    /// Mean tet volume.
    pub mean_volume: f64,
    /// Largest aspect ratio, the normalised radius ratio R / (3 r): 1 for the regular tet,
    /// infinite for a flat one.
    pub max_aspect_ratio: f64,
    /// Mean aspect ratio.
    pub mean_aspect_ratio: f64,
    /// Tets with a dihedral angle below 5 degrees (slivers).
    pub tets_below_5deg: usize,
}

// SAFETY: repr(C), `struct_size: usize` first; FIRST_SIZE is within the struct.
unsafe impl Versioned for mtcut_quality {
    const NAME: &'static str = "mtcut_quality";
    const FIRST_SIZE: usize = offset_of!(mtcut_quality, tets_below_5deg) + size_of::<usize>();
}

/// Element quality: fills the fields of `*quality` that lie within `quality->struct_size`
/// (which the caller sets first).
///
/// # Safety
/// `mesh` must be a live mesh handle; `quality` a writable `mtcut_quality` whose
/// `struct_size` is set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_quality(
    mesh: *const mtcut_mesh,
    quality: *mut mtcut_quality,
) -> mtcut_status {
    run("mtcut_mesh_quality", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, out) = unsafe { (mesh_ref(mesh)?, Out::new(quality, "quality")?) };
        let out = VersionedOut::new(out)?;
        let q = mesh.quality();
        out.write(mtcut_quality {
            struct_size: size_of::<mtcut_quality>(),
            tets: q.tets,
            min_dihedral_deg: q.min_dihedral_deg,
            max_dihedral_deg: q.max_dihedral_deg,
            min_volume: q.min_volume,
            max_volume: q.max_volume,
            mean_volume: q.mean_volume,
            max_aspect_ratio: q.max_aspect_ratio,
            mean_aspect_ratio: q.mean_aspect_ratio,
            tets_below_5deg: q.tets_below_5deg,
        });
        Ok(())
    })
}

/// Number of connected components (tets connected through shared faces) into `*count`.
/// Found on the first call (a matching of the mesh's faces) and kept with the mesh until
/// it is cut: later calls, and `mtcut_mesh_extract_component`, reuse them.
///
/// # Safety
/// `mesh` must be a live mesh handle; `count` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_component_count(
    mesh: *const mtcut_mesh,
    count: *mut usize,
) -> mtcut_status {
    run("mtcut_mesh_component_count", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, count) = unsafe { (deref(mesh, "mesh")?, Out::new(count, "count")?) };
        count.write(mesh.components().0);
        Ok(())
    })
}

/// Component `component` (0-based; components are numbered in the order of their
/// lowest-numbered tet) as a new mesh in `*out`: its tets in their order, the vertices
/// they use in their order, and the attribute rows of both. An index not below
/// `mtcut_mesh_component_count` gives `MTCUT_STATUS_INVALID_ARGUMENT`.
///
/// # Safety
/// `mesh` must be a live mesh handle; `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_extract_component(
    mesh: *const mtcut_mesh,
    component: usize,
    out: *mut *mut mtcut_mesh,
) -> mtcut_status {
    run("mtcut_mesh_extract_component", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (handle, out) = unsafe { (deref(mesh, "mesh")?, Out::new(out, "out")?) };
        let &(count, ref label) = handle.components();
        if component >= count {
            return Err(Failure::invalid(format!(
                "component {component} does not exist: the mesh has {count}"
            )));
        }
        let tets: Vec<TetId> = (0..label.len())
            .filter(|&t| label[t] as usize == component)
            .map(TetId::from_usize)
            .collect();
        out.write(mtcut_mesh::boxed(handle.mesh().submesh(&tets)?));
        Ok(())
    })
}
