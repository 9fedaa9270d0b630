//! `mtcut_mesh`: a tetrahedral mesh handle - made from arrays or files, copied back to
//! arrays, written, deformed, cloned, freed.

use super::guard::{Out, OutSlice, c_str, deref, deref_mut, run, run_count, slice};
use super::status::{Failure, FfiResult, mtcut_status};
use crate::cut::{CrackTips, CutError, CutOptions, Cutter};
use crate::geom::{DVec3, out_of_range_text, supported};
use crate::mesh::{MeshError, TetMesh};
use std::ffi::{CStr, c_char};
use std::path::PathBuf;
use std::sync::OnceLock;

/// A tetrahedral mesh (opaque): vertex positions, tets as four vertex indices each
/// (positively oriented: `(b-a) . ((c-a) x (d-a)) > 0`, VTK's convention), and named
/// per-vertex and per-tet attribute columns of doubles. Every `mtcut_mesh` is valid when
/// made (checked on the way in). Created by `mtcut_mesh_from_arrays`, `mtcut_mesh_read`,
/// `mtcut_mesh_clone` or `mtcut_mesh_extract_component`; owned by the caller, released
/// with `mtcut_mesh_free`. Functions taking a `const mtcut_mesh *` may run on one mesh
/// from several threads at once; the others need exclusive access. After its first cut a
/// mesh keeps what cutting it needs (a hierarchy over its tets, vertex scales, the crack
/// tips), so later cuts cost time in proportion to the tets they touch, not to the mesh;
/// `mtcut_mesh_set_vertices` drops it (rebuilt at the next cut). Its connected components
/// are found once, on the first request, and kept until it is cut.
pub struct mtcut_mesh {
    state: MeshState,
    /// Its components through faces (count, component of each tet), found on the first
    /// request and kept until a cut changes the tets (moving the vertices or editing
    /// attributes leaves them): a host taking K components out pays one matching of the
    /// mesh's faces (about 0.27 s on fandisk-1m), not K + 1.
    components: OnceLock<(usize, Vec<u32>)>,
}

/// A mesh handle's contents.
enum MeshState {
    /// The mesh, and the crack tips its earlier cuts made (vertex ids, which only cuts
    /// change: they append), so a scalpel's next step continues them.
    Plain { mesh: TetMesh, tips: CrackTips },
    /// After a cut: the cutter holding the mesh with its hierarchy, vertex scales and crack
    /// tips, kept for the next cut, which then costs time in proportion to the tets it
    /// touches instead of a rebuild in proportion to the mesh (measured on fandisk-1m:
    /// 0.4 s of preparation against 23 ms for the cut). Moving the vertices
    /// (`mtcut_mesh_set_vertices`) drops it; attribute edits keep it.
    Cutting(Box<Cutter>),
}

impl mtcut_mesh {
    pub(crate) fn boxed(mesh: TetMesh) -> *mut mtcut_mesh {
        Box::into_raw(Box::new(mtcut_mesh {
            state: MeshState::Plain {
                mesh,
                tips: CrackTips::default(),
            },
            components: OnceLock::new(),
        }))
    }

    /// The mesh's components through faces: their count and each tet's (see the field).
    pub(crate) fn components(&self) -> &(usize, Vec<u32>) {
        self.components
            .get_or_init(|| self.mesh().adjacency().components())
    }

    /// The mesh.
    pub(crate) fn mesh(&self) -> &TetMesh {
        match &self.state {
            MeshState::Plain { mesh, .. } => mesh,
            MeshState::Cutting(c) => c.mesh(),
        }
    }

    /// The mesh, to change its attribute columns only (a kept cutter stays valid).
    pub(crate) fn mesh_for_attributes(&mut self) -> &mut TetMesh {
        match &mut self.state {
            MeshState::Plain { mesh, .. } => mesh,
            MeshState::Cutting(c) => c.mesh_for_attributes(),
        }
    }

    /// The mesh, to move its vertices: a kept cutter (its hierarchy holds the old
    /// positions) is dropped, its crack tips kept.
    pub(crate) fn mesh_for_positions(&mut self) -> &mut TetMesh {
        let empty = MeshState::Plain {
            mesh: TetMesh::default(),
            tips: CrackTips::default(),
        };
        self.state = match std::mem::replace(&mut self.state, empty) {
            MeshState::Cutting(c) => MeshState::Plain {
                tips: c.crack_tips().cloned().unwrap_or_default(),
                mesh: c.into_mesh(),
            },
            plain => plain,
        };
        let MeshState::Plain { mesh, .. } = &mut self.state else {
            unreachable!("the state was just made plain")
        };
        mesh
    }

    /// A copy of the mesh and its crack tips, as a new handle's contents (the cutter is not
    /// copied: the copy makes its own on its first cut).
    pub(crate) fn copy(&self) -> mtcut_mesh {
        let tips = match &self.state {
            MeshState::Plain { tips, .. } => tips.clone(),
            MeshState::Cutting(c) => c.crack_tips().cloned().unwrap_or_default(),
        };
        mtcut_mesh {
            state: MeshState::Plain {
                mesh: self.mesh().clone(),
                tips,
            },
            components: self.components.clone(),
        }
    }

    /// The handle's cutter with `options` (made, and kept, on the first cut). Returns the
    /// seconds spent preparing it (0 when kept from an earlier cut).
    pub(crate) fn cutter(&mut self, options: CutOptions) -> Result<(&mut Cutter, f64), CutError> {
        // The caller cuts: the tets change.
        self.components.take();
        let mut build = 0.0;
        if let MeshState::Plain { mesh, tips } = &mut self.state {
            options.check()?;
            // The tables need positively oriented tets, and mtcut_mesh_set_vertices takes
            // whatever positions a simulation computed: a mesh it inverted is refused here,
            // naming the tet, instead of failing later as a flat child of some cut tet.
            if let Some(tet) = first_non_positive(mesh) {
                return Err(CutError::InvertedTet { tet });
            }
            let mut c = Cutter::new(std::mem::take(mesh), options)?;
            c.set_crack_tips(std::mem::take(tips));
            build = c.build_time().as_secs_f64();
            self.state = MeshState::Cutting(Box::new(c));
        }
        match &mut self.state {
            MeshState::Cutting(c) => {
                c.set_options(options)?;
                Ok((c, build))
            }
            MeshState::Plain { .. } => unreachable!("a cutter was just made"),
        }
    }
}

/// The first tet that is not positively oriented (exactly), if any. On one thread: a
/// few milliseconds on a million tets, next to the cutter's preparation, and no use of the
/// thread pool (whose per-thread buffers tests/ffi_leaks.rs would see as growth).
fn first_non_positive(mesh: &TetMesh) -> Option<usize> {
    let p = mesh.positions();
    mesh.tets().iter().position(|t| {
        let [a, b, c, d] = t.map(|v| p[v.idx()]);
        crate::geom::orient3d(a, b, c, d) != crate::geom::Sign::Positive
    })
}

/// The mesh behind a handle argument.
///
/// # Safety
/// A non-NULL `mesh` must be a live handle from this library.
pub(crate) unsafe fn mesh_ref<'a>(mesh: *const mtcut_mesh) -> FfiResult<&'a TetMesh> {
    // SAFETY: forwarded contract.
    Ok(unsafe { deref(mesh, "mesh") }?.mesh())
}

/// A file path argument. Paths are bytes on Unix, so any bytes are accepted there.
pub(crate) fn path_arg(path: &CStr) -> FfiResult<PathBuf> {
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        Ok(PathBuf::from(std::ffi::OsStr::from_bytes(path.to_bytes())))
    }
    #[cfg(not(unix))]
    {
        path.to_str()
            .map(PathBuf::from)
            .map_err(|_| Failure::invalid("argument `path` is not valid UTF-8"))
    }
}

/// `n` elements of `k` values each: the length of the flat array, if it fits.
pub(crate) fn flat_len(n: usize, k: usize, what: &str) -> FfiResult<usize> {
    n.checked_mul(k)
        .ok_or_else(|| Failure::invalid(format!("{n} {what} do not fit in memory")))
}

/// Makes a mesh from flat arrays: `xyz` holds `3 x n_vertices` coordinates (x, y, z of
/// vertex 0, then of vertex 1...), `tets` holds `4 x n_tets` 0-based vertex indices. The
/// mesh is checked: coordinates finite and of magnitude at most 1e50 (a bounding-box
/// diagonal of at least 1e-50), indices in range, four distinct vertices per tet, no flat
/// tet, every face shared by at most two tets with opposite orientations, a manifold
/// boundary without hanging vertices; otherwise `MTCUT_STATUS_INVALID_MESH` with the
/// first culprit in the message. Negatively oriented tets are re-oriented (their
/// last two vertices swapped: `mtcut_mesh_copy_tets` shows it). Vertices used by no tet
/// are kept. The arrays are copied; the caller keeps them. On success `*out` receives a
/// new mesh to free with `mtcut_mesh_free`; on failure it is not written.
///
/// # Safety
/// `xyz` and `tets` must point to that many readable values; `out` to a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_from_arrays(
    xyz: *const f64,
    n_vertices: usize,
    tets: *const u32,
    n_tets: usize,
    out: *mut *mut mtcut_mesh,
) -> mtcut_status {
    run("mtcut_mesh_from_arrays", || {
        let (xyz_len, tets_len) = (
            flat_len(n_vertices, 3, "vertices")?,
            flat_len(n_tets, 4, "tets")?,
        );
        // Sizes a mesh cannot have are refused before anything is read or copied (the
        // copy of a huge count would abort on memory).
        if n_vertices >= u32::MAX as usize || n_tets >= u32::MAX as usize {
            return Err(MeshError::TooLarge { max: u32::MAX - 1 }.into());
        }
        // SAFETY: the caller's contract, forwarded to the checks.
        let (xyz, tets, out) = unsafe {
            (
                slice(xyz, xyz_len, "xyz")?,
                slice(tets, tets_len, "tets")?,
                Out::new(out, "out")?,
            )
        };
        let positions = xyz
            .chunks_exact(3)
            .map(|p| DVec3::new(p[0], p[1], p[2]))
            .collect();
        let cells = tets
            .chunks_exact(4)
            .map(|t| [t[0], t[1], t[2], t[3]])
            .collect();
        let (mesh, _) = TetMesh::from_arrays(positions, cells)?;
        out.write(mtcut_mesh::boxed(mesh));
        Ok(())
    })
}

/// Reads a mesh file, the format chosen by the extension: `.vtu` (VTK XML unstructured
/// grid, every encoding and compressor VTK writes; tets only), `.node` or `.ele` (TetGen;
/// the other file of the pair is read from beside it), `.mesh` (medit). The mesh is
/// checked as in `mtcut_mesh_from_arrays`; the point and cell data of a `.vtu` become
/// vertex and tet attribute columns. Errors: `MTCUT_STATUS_IO_ERROR` (cannot open),
/// `MTCUT_STATUS_UNSUPPORTED_FORMAT`, `MTCUT_STATUS_PARSE_ERROR` (the message names the
/// file and line), `MTCUT_STATUS_INVALID_MESH`. On success `*out` receives a new mesh.
///
/// # Safety
/// `path` must be a NUL-terminated string; `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_read(
    path: *const c_char,
    out: *mut *mut mtcut_mesh,
) -> mtcut_status {
    run("mtcut_mesh_read", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (path, out) = unsafe { (c_str(path, "path")?, Out::new(out, "out")?) };
        let (mesh, _) = crate::io::read_mesh(path_arg(path)?)?;
        out.write(mtcut_mesh::boxed(mesh));
        Ok(())
    })
}

/// Writes a mesh file, the format chosen by the extension: `.vtu` (as
/// `mtcut_mesh_write_vtu`), `.node` or `.ele` (TetGen; writes both files of the pair,
/// without attributes).
///
/// # Safety
/// `mesh` must be a live mesh handle, `path` a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_write(
    mesh: *const mtcut_mesh,
    path: *const c_char,
) -> mtcut_status {
    run("mtcut_mesh_write", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, path) = unsafe { (mesh_ref(mesh)?, c_str(path, "path")?) };
        crate::io::write_mesh(path_arg(path)?, mesh)?;
        Ok(())
    })
}

/// Writes a VTK XML unstructured grid (`.vtu`, for ParaView and VTK: binary appended
/// data, zlib-compressed), with the mesh's attribute columns as point and cell data. The
/// file name must end in `.vtu` (`MTCUT_STATUS_INVALID_ARGUMENT` otherwise), so that a
/// file is never written under another format's name.
///
/// # Safety
/// `mesh` must be a live mesh handle, `path` a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_write_vtu(
    mesh: *const mtcut_mesh,
    path: *const c_char,
) -> mtcut_status {
    run("mtcut_mesh_write_vtu", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, path) = unsafe { (mesh_ref(mesh)?, c_str(path, "path")?) };
        let path = path_arg(path)?;
        let is_vtu = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("vtu"));
        if !is_vtu {
            return Err(Failure::invalid(format!(
                "{}: the file name must end in .vtu",
                path.display()
            )));
        }
        crate::io::write_vtu(&path, mesh, &crate::io::VtuOptions::DEFAULT)?;
        Ok(())
    })
}

/// Number of vertices; 0 (with the last error set) when `mesh` is NULL.
///
/// # Safety
/// A non-NULL `mesh` must be a live mesh handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_vertex_count(mesh: *const mtcut_mesh) -> usize {
    // SAFETY: the caller's contract, forwarded to the checks.
    run_count("mtcut_mesh_vertex_count", || {
        Ok(unsafe { mesh_ref(mesh) }?.nb_vertices())
    })
}

/// Number of tets; 0 (with the last error set) when `mesh` is NULL.
///
/// # Safety
/// A non-NULL `mesh` must be a live mesh handle.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_tet_count(mesh: *const mtcut_mesh) -> usize {
    // SAFETY: the caller's contract, forwarded to the checks.
    run_count("mtcut_mesh_tet_count", || {
        Ok(unsafe { mesh_ref(mesh) }?.nb_tets())
    })
}

/// Copies the vertex coordinates into `xyz` (x, y, z of vertex 0, then vertex 1...),
/// which holds `capacity_vertices` vertices (`3 x capacity_vertices` doubles). Fewer than
/// `mtcut_mesh_vertex_count` gives `MTCUT_STATUS_BUFFER_TOO_SMALL`, nothing written.
///
/// # Safety
/// `mesh` must be a live mesh handle; `xyz` writable for `3 x capacity_vertices` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_copy_vertices(
    mesh: *const mtcut_mesh,
    xyz: *mut f64,
    capacity_vertices: usize,
) -> mtcut_status {
    run("mtcut_mesh_copy_vertices", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, xyz) = unsafe {
            (
                mesh_ref(mesh)?,
                OutSlice::new(xyz, capacity_vertices, "xyz")?,
            )
        };
        let flat: Vec<f64> = mesh.positions().iter().flat_map(|p| p.to_array()).collect();
        xyz.write(&flat, 3, "vertices")
    })
}

/// Copies the tets into `tets` (four 0-based vertex indices per tet, positively
/// oriented), which holds `capacity_tets` tets (`4 x capacity_tets` values). Fewer than
/// `mtcut_mesh_tet_count` gives `MTCUT_STATUS_BUFFER_TOO_SMALL`, nothing written.
///
/// # Safety
/// `mesh` must be a live mesh handle; `tets` writable for `4 x capacity_tets` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_copy_tets(
    mesh: *const mtcut_mesh,
    tets: *mut u32,
    capacity_tets: usize,
) -> mtcut_status {
    run("mtcut_mesh_copy_tets", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, out) = unsafe { (mesh_ref(mesh)?, OutSlice::new(tets, capacity_tets, "tets")?) };
        let flat: Vec<u32> = mesh.tets().iter().flat_map(|t| t.map(|v| v.0)).collect();
        out.write(&flat, 4, "tets")
    })
}

/// Moves the vertices to `xyz` (`3 x n_vertices` coordinates; `n_vertices` must equal
/// the mesh's vertex count): the deformed configuration a simulation computed. The
/// coordinates must be finite and of magnitude at most 1e50; anything else is refused
/// and the mesh left unchanged.
/// Moving vertices can invert tets: `mtcut_mesh_validate` reports it, and the next cut
/// refuses such a mesh (`MTCUT_STATUS_INVALID_MESH`, naming the tet; the mesh is kept
/// as it is, so other positions can be set).
///
/// # Safety
/// `mesh` must be a live mesh handle used by no other thread during the call; `xyz`
/// readable for `3 x n_vertices` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_set_vertices(
    mesh: *mut mtcut_mesh,
    xyz: *const f64,
    n_vertices: usize,
) -> mtcut_status {
    run("mtcut_mesh_set_vertices", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, xyz) = unsafe {
            (
                deref_mut(mesh, "mesh")?.mesh_for_positions(),
                slice(xyz, flat_len(n_vertices, 3, "vertices")?, "xyz")?,
            )
        };
        if n_vertices != mesh.nb_vertices() {
            return Err(Failure::invalid(format!(
                "n_vertices is {n_vertices}, the mesh has {} vertices",
                mesh.nb_vertices()
            )));
        }
        if let Some(i) = xyz.iter().position(|&c| !supported(c)) {
            return Err(Failure::invalid(if xyz[i].is_finite() {
                format!("vertex {} {}", i / 3, out_of_range_text(xyz[i]))
            } else {
                format!("vertex {} has a coordinate that is NaN or infinite", i / 3)
            }));
        }
        for (p, c) in mesh.positions_mut().iter_mut().zip(xyz.chunks_exact(3)) {
            *p = DVec3::new(c[0], c[1], c[2]);
        }
        Ok(())
    })
}

/// A deep copy of `mesh` (geometry, attributes, and the crack tips its cuts made, so a
/// scalpel can go on in the copy) into `*out`, to free with `mtcut_mesh_free`.
///
/// # Safety
/// `mesh` must be a live mesh handle; `out` a writable pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_clone(
    mesh: *const mtcut_mesh,
    out: *mut *mut mtcut_mesh,
) -> mtcut_status {
    run("mtcut_mesh_clone", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, out) = unsafe { (deref(mesh, "mesh")?, Out::new(out, "out")?) };
        out.write(Box::into_raw(Box::new(mesh.copy())));
        Ok(())
    })
}

/// Releases a mesh. NULL is allowed (nothing happens). Using the handle afterwards, or
/// freeing it twice, is undefined behaviour.
///
/// # Safety
/// A non-NULL `mesh` must be a live handle from this library, not used after the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_free(mesh: *mut mtcut_mesh) {
    if mesh.is_null() {
        return;
    }
    // A panic in a destructor must not unwind into C either; there is no status to
    // report it with, and dropping plain vectors cannot panic, so the result is dropped.
    let _ = std::panic::catch_unwind(|| {
        // SAFETY: a live handle made by Box::into_raw (the caller's contract).
        drop(unsafe { Box::from_raw(mesh) });
    });
}
