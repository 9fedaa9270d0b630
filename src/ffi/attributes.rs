//! Per-vertex and per-tet attribute columns: named arrays of doubles, 1 to 9 components
//! per element, carried along by the library's operations and written to files.

use super::guard::{Out, OutSlice, c_str, deref_mut, run, slice};
use super::mesh::{flat_len, mesh_ref, mtcut_mesh};
use super::status::{Failure, FfiResult, MTCUT_STATUS_NOT_FOUND, mtcut_status};
use super::strings::StringOut;
use crate::mesh::{Attribute, Attributes, TetMesh};
use std::ffi::c_char;

/// Which elements an attribute column belongs to (a `uint32_t`; other values are refused
/// with `MTCUT_STATUS_INVALID_ARGUMENT`).
pub type mtcut_location = u32;

/// One row per vertex (VTK's point data).
pub const MTCUT_LOCATION_VERTEX: mtcut_location = 0;
/// One row per tet (VTK's cell data).
pub const MTCUT_LOCATION_TET: mtcut_location = 1;

/// The most components an attribute column may have (a 3x3 tensor).
pub const MTCUT_MAX_COMPONENTS: usize = 9;

/// The columns at `location` and the number of elements they have rows for.
fn columns(mesh: &TetMesh, location: mtcut_location) -> FfiResult<(&Attributes, usize)> {
    match location {
        MTCUT_LOCATION_VERTEX => Ok((&mesh.point_data, mesh.nb_vertices())),
        MTCUT_LOCATION_TET => Ok((&mesh.cell_data, mesh.nb_tets())),
        _ => Err(bad_location(location)),
    }
}

fn columns_mut(
    mesh: &mut TetMesh,
    location: mtcut_location,
) -> FfiResult<(&mut Attributes, usize)> {
    let (vertices, tets) = (mesh.nb_vertices(), mesh.nb_tets());
    match location {
        MTCUT_LOCATION_VERTEX => Ok((&mut mesh.point_data, vertices)),
        MTCUT_LOCATION_TET => Ok((&mut mesh.cell_data, tets)),
        _ => Err(bad_location(location)),
    }
}

fn bad_location(location: mtcut_location) -> Failure {
    Failure::invalid(format!(
        "location {location} is neither MTCUT_LOCATION_VERTEX (0) nor MTCUT_LOCATION_TET (1)"
    ))
}

fn location_name(location: mtcut_location) -> &'static str {
    if location == MTCUT_LOCATION_VERTEX {
        "vertex"
    } else {
        "tet"
    }
}

/// An attribute name argument: non-empty UTF-8 (file formats store names as text).
///
/// # Safety
/// A non-NULL `name` must be a NUL-terminated string.
unsafe fn name_arg<'a>(name: *const c_char) -> FfiResult<&'a str> {
    // SAFETY: forwarded contract.
    let name = unsafe { c_str(name, "name") }?;
    let name = name
        .to_str()
        .map_err(|_| Failure::invalid("argument `name` is not valid UTF-8"))?;
    if name.is_empty() {
        return Err(Failure::invalid("argument `name` is empty"));
    }
    Ok(name)
}

fn find<'a>(
    columns: &'a Attributes,
    name: &str,
    location: mtcut_location,
) -> FfiResult<&'a Attribute> {
    columns.get(name).ok_or_else(|| {
        Failure::new(
            MTCUT_STATUS_NOT_FOUND,
            format!("no {} attribute named \"{name}\"", location_name(location)),
        )
    })
}

/// Sets the attribute column `name` at `location` from `values`: `n_elements` rows (which
/// must equal the mesh's vertex or tet count) of `components` doubles each (1 to
/// `MTCUT_MAX_COMPONENTS`), element-major. A column of the same name is replaced. The
/// values are copied. `name` must be non-empty UTF-8.
///
/// # Safety
/// `mesh` must be a live mesh handle used by no other thread during the call; `name` a
/// NUL-terminated string; `values` readable for `n_elements x components` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_set_attribute(
    mesh: *mut mtcut_mesh,
    location: mtcut_location,
    name: *const c_char,
    values: *const f64,
    n_elements: usize,
    components: usize,
) -> mtcut_status {
    run("mtcut_mesh_set_attribute", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, name) = unsafe {
            (
                deref_mut(mesh, "mesh")?.mesh_for_attributes(),
                name_arg(name)?,
            )
        };
        let (columns, rows) = columns_mut(mesh, location)?;
        // The counts first: wrong ones must not make the library read past `values`.
        if !(1..=MTCUT_MAX_COMPONENTS).contains(&components) {
            return Err(Failure::invalid(format!(
                "components is {components}; it must be 1 to {MTCUT_MAX_COMPONENTS}"
            )));
        }
        if n_elements != rows {
            return Err(Failure::invalid(format!(
                "n_elements is {n_elements}, the mesh has {rows} {}s",
                location_name(location)
            )));
        }
        // SAFETY: the caller's contract, forwarded to the checks.
        let values = unsafe {
            slice(
                values,
                flat_len(n_elements, components, "values")?,
                "values",
            )
        }?;
        let column = Attribute::new(name, components, values.to_vec()).ok_or_else(|| {
            Failure::invalid(format!(
                "components is {components}; it must be 1 to {MTCUT_MAX_COMPONENTS}"
            ))
        })?;
        columns.insert(column);
        Ok(())
    })
}

/// Number of attribute columns at `location` into `*count`.
///
/// # Safety
/// `mesh` must be a live mesh handle; `count` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_attribute_count(
    mesh: *const mtcut_mesh,
    location: mtcut_location,
    count: *mut usize,
) -> mtcut_status {
    run("mtcut_mesh_attribute_count", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, count) = unsafe { (mesh_ref(mesh)?, Out::new(count, "count")?) };
        count.write(columns(mesh, location)?.0.iter().count());
        Ok(())
    })
}

/// The name of column `index` (0-based, below `mtcut_mesh_attribute_count`) at
/// `location`, copied with its NUL into `name`, which holds `capacity` bytes. A name is
/// copied whole or not at all: when it does not fit, `MTCUT_STATUS_BUFFER_TOO_SMALL` and
/// only `*length_or_null` is written. `name` may be NULL with `capacity` 0 to ask for the
/// length. `*length_or_null`, if given, receives the name's length without the NUL.
///
/// # Safety
/// `mesh` must be a live mesh handle; a non-NULL `name` writable for `capacity` bytes; a
/// non-NULL `length_or_null` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_attribute_name(
    mesh: *const mtcut_mesh,
    location: mtcut_location,
    index: usize,
    name: *mut c_char,
    capacity: usize,
    length_or_null: *mut usize,
) -> mtcut_status {
    run("mtcut_mesh_attribute_name", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, out, length) = unsafe {
            (
                mesh_ref(mesh)?,
                StringOut::new(name, capacity, "name")?,
                Out::optional(length_or_null, "length_or_null")?,
            )
        };
        let (columns, _) = columns(mesh, location)?;
        let count = columns.iter().count();
        let column = columns.iter().nth(index).ok_or_else(|| {
            Failure::invalid(format!(
                "index {index} is past the end: the mesh has {count} {} attributes",
                location_name(location)
            ))
        })?;
        if column.name.contains('\0') {
            return Err(Failure::invalid(format!(
                "the name of {} attribute {index} contains a NUL byte and cannot be returned \
                 as a C string",
                location_name(location)
            )));
        }
        if let Some(length) = length {
            length.write(column.name.len());
        }
        out.write_whole(&column.name, "the attribute name")
    })
}

/// The number of components of column `name` at `location` into `*components`
/// (`MTCUT_STATUS_NOT_FOUND` when there is no such column).
///
/// # Safety
/// `mesh` must be a live mesh handle; `name` a NUL-terminated string; `components`
/// writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_attribute_components(
    mesh: *const mtcut_mesh,
    location: mtcut_location,
    name: *const c_char,
    components: *mut usize,
) -> mtcut_status {
    run("mtcut_mesh_attribute_components", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, name, out) = unsafe {
            (
                mesh_ref(mesh)?,
                name_arg(name)?,
                Out::new(components, "components")?,
            )
        };
        let column = find(columns(mesh, location)?.0, name, location)?;
        out.write(column.components);
        Ok(())
    })
}

/// Copies column `name` at `location` into `values`, which holds `capacity_values`
/// doubles: element count x components are needed (element-major), else
/// `MTCUT_STATUS_BUFFER_TOO_SMALL` and nothing written. `MTCUT_STATUS_NOT_FOUND` when
/// there is no such column.
///
/// # Safety
/// `mesh` must be a live mesh handle; `name` a NUL-terminated string; `values` writable
/// for `capacity_values` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_copy_attribute(
    mesh: *const mtcut_mesh,
    location: mtcut_location,
    name: *const c_char,
    values: *mut f64,
    capacity_values: usize,
) -> mtcut_status {
    run("mtcut_mesh_copy_attribute", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, name, out) = unsafe {
            (
                mesh_ref(mesh)?,
                name_arg(name)?,
                OutSlice::new(values, capacity_values, "values")?,
            )
        };
        let column = find(columns(mesh, location)?.0, name, location)?;
        out.write(&column.values, 1, "values")
    })
}

/// Removes column `name` at `location` (`MTCUT_STATUS_NOT_FOUND` when there is none).
///
/// # Safety
/// `mesh` must be a live mesh handle used by no other thread during the call; `name` a
/// NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mtcut_mesh_remove_attribute(
    mesh: *mut mtcut_mesh,
    location: mtcut_location,
    name: *const c_char,
) -> mtcut_status {
    run("mtcut_mesh_remove_attribute", || {
        // SAFETY: the caller's contract, forwarded to the checks.
        let (mesh, name) = unsafe {
            (
                deref_mut(mesh, "mesh")?.mesh_for_attributes(),
                name_arg(name)?,
            )
        };
        let (columns, _) = columns_mut(mesh, location)?;
        find(columns, name, location)?;
        columns.remove(name);
        Ok(())
    })
}
