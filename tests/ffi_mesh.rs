//! The C ABI's mesh functions, called as C would call them: results, statuses, messages,
//! and the rule that a failed call writes nothing the caller owns.
//!
//! `unsafe` here is the C caller's side of the contract (live handles, buffers as long as
//! the capacities given); every call goes through the small wrappers below.

mod common;

use mtcut::ffi::*;
use std::ffi::{CStr, CString, c_char};
use std::ptr;

/// A unit cube split into six tets around its diagonal 0–7 (vertex i at (i&1, i>>1&1,
/// i>>2&1)); three of the six are given with negative orientation.
const CUBE_XYZ: [f64; 24] = [
    0., 0., 0., 1., 0., 0., 0., 1., 0., 1., 1., 0., 0., 0., 1., 1., 0., 1., 0., 1., 1., 1., 1., 1.,
];
const CUBE_TETS: [u32; 24] = [
    0, 1, 3, 7, 0, 1, 5, 7, 0, 2, 3, 7, 0, 2, 6, 7, 0, 4, 5, 7, 0, 4, 6, 7,
];

/// Owns a mesh handle for the test's duration.
struct Mesh(*mut mtcut_mesh);

impl Drop for Mesh {
    fn drop(&mut self) {
        unsafe { mtcut_mesh_free(self.0) }
    }
}

fn last_error() -> String {
    unsafe { CStr::from_ptr(mtcut_last_error_message()) }
        .to_str()
        .expect("messages are UTF-8")
        .to_owned()
}

/// Asserts `status` is `expected` and, for a failure, that the message names `function`
/// and contains `needle`.
#[track_caller]
fn expect(status: mtcut_status, expected: mtcut_status, function: &str, needle: &str) {
    let message = last_error();
    assert_eq!(status, expected, "message: {message}");
    if expected == MTCUT_STATUS_OK {
        assert_eq!(message, "", "a success clears the message");
    } else {
        assert!(
            message.starts_with(&format!("{function}: ")) && message.contains(needle),
            "{message:?} should name {function} and contain {needle:?}"
        );
    }
}

fn from_arrays(xyz: &[f64], tets: &[u32]) -> Result<Mesh, (mtcut_status, String)> {
    let mut out = ptr::null_mut();
    let s = unsafe {
        mtcut_mesh_from_arrays(
            xyz.as_ptr(),
            xyz.len() / 3,
            tets.as_ptr(),
            tets.len() / 4,
            &mut out,
        )
    };
    if s == MTCUT_STATUS_OK {
        Ok(Mesh(out))
    } else {
        assert!(out.is_null(), "out written on failure");
        Err((s, last_error()))
    }
}

fn cube() -> Mesh {
    from_arrays(&CUBE_XYZ, &CUBE_TETS).expect("the cube is a valid mesh")
}

/// Two unit cubes, the second shifted by (3, 0, 0): two components.
fn two_cubes() -> Mesh {
    let mut xyz = CUBE_XYZ.to_vec();
    xyz.extend(CUBE_XYZ.chunks(3).flat_map(|p| [p[0] + 3.0, p[1], p[2]]));
    let mut tets = CUBE_TETS.to_vec();
    tets.extend(CUBE_TETS.iter().map(|v| v + 8));
    from_arrays(&xyz, &tets).expect("two cubes")
}

fn vertices(m: &Mesh) -> Vec<f64> {
    let n = unsafe { mtcut_mesh_vertex_count(m.0) };
    let mut xyz = vec![0.0; 3 * n];
    let s = unsafe { mtcut_mesh_copy_vertices(m.0, xyz.as_mut_ptr(), n) };
    expect(s, MTCUT_STATUS_OK, "", "");
    xyz
}

fn tets(m: &Mesh) -> Vec<u32> {
    let n = unsafe { mtcut_mesh_tet_count(m.0) };
    let mut t = vec![0; 4 * n];
    let s = unsafe { mtcut_mesh_copy_tets(m.0, t.as_mut_ptr(), n) };
    expect(s, MTCUT_STATUS_OK, "", "");
    t
}

fn signed_volume(xyz: &[f64], t: &[u32]) -> f64 {
    let p = |i: usize| {
        let v = t[i] as usize;
        [xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]]
    };
    let (a, b, c, d) = (p(0), p(1), p(2), p(3));
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]))
        / 6.0
}

fn validate(m: &Mesh) -> (bool, String) {
    let (mut valid, mut len) = (false, 0usize);
    let mut buf = vec![0 as c_char; 4096];
    let s = unsafe { mtcut_mesh_validate(m.0, &mut valid, buf.as_mut_ptr(), buf.len(), &mut len) };
    expect(s, MTCUT_STATUS_OK, "", "");
    let text = unsafe { CStr::from_ptr(buf.as_ptr()) }
        .to_str()
        .unwrap()
        .to_owned();
    assert_eq!(text.len(), len.min(buf.len() - 1));
    (valid, text)
}

#[test]
fn cube_from_arrays_round_trips_reoriented() {
    let m = cube();
    assert_eq!(unsafe { mtcut_mesh_vertex_count(m.0) }, 8);
    assert_eq!(unsafe { mtcut_mesh_tet_count(m.0) }, 6);
    assert_eq!(vertices(&m), CUBE_XYZ);
    let t = tets(&m);
    for (given, got) in CUBE_TETS.chunks(4).zip(t.chunks(4)) {
        let mut a = given.to_vec();
        let mut b = got.to_vec();
        a.sort();
        b.sort();
        assert_eq!(a, b, "same vertices");
        assert!(
            signed_volume(&CUBE_XYZ, got) > 0.0,
            "positively oriented: {got:?}"
        );
    }
    assert_eq!(validate(&m), (true, "valid mesh".to_owned()));
}

#[test]
fn measures_of_the_cube() {
    let m = cube();
    let mut volume = 0.0;
    expect(
        unsafe { mtcut_mesh_volume(m.0, &mut volume) },
        MTCUT_STATUS_OK,
        "",
        "",
    );
    assert!((volume - 1.0).abs() < 1e-15);
    let (mut lo, mut hi) = ([9.0; 3], [9.0; 3]);
    let s = unsafe { mtcut_mesh_bounding_box(m.0, lo.as_mut_ptr(), hi.as_mut_ptr()) };
    expect(s, MTCUT_STATUS_OK, "", "");
    assert_eq!((lo, hi), ([0.0; 3], [1.0; 3]));
    let (mut faces, mut area) = (0usize, 0.0);
    let s = unsafe { mtcut_mesh_boundary(m.0, &mut faces, &mut area) };
    expect(s, MTCUT_STATUS_OK, "", "");
    assert_eq!(faces, 12);
    assert!((area - 6.0).abs() < 1e-12);
    let mut components = 0usize;
    let s = unsafe { mtcut_mesh_component_count(m.0, &mut components) };
    expect(s, MTCUT_STATUS_OK, "", "");
    assert_eq!(components, 1);
    // 36 tet edges: 18 of length 1, 12 of √2, 6 of √3; the 19th shortest is √2.
    let mut edge = 0.0;
    let s = unsafe { mtcut_mesh_median_edge_length(m.0, &mut edge) };
    expect(s, MTCUT_STATUS_OK, "", "");
    assert_eq!(edge, 2f64.sqrt());

    let mut q: mtcut_quality = unsafe { std::mem::zeroed() };
    q.struct_size = size_of::<mtcut_quality>();
    expect(
        unsafe { mtcut_mesh_quality(m.0, &mut q) },
        MTCUT_STATUS_OK,
        "",
        "",
    );
    assert_eq!(q.struct_size, size_of::<mtcut_quality>());
    assert_eq!(q.tets, 6);
    // Every Kuhn tet of a cube has dihedral angles of 45°, 60° and 90°.
    assert!((q.min_dihedral_deg - 45.0).abs() < 1e-9, "{q:?}");
    assert!((q.max_dihedral_deg - 90.0).abs() < 1e-9, "{q:?}");
    assert!((q.mean_volume - 1.0 / 6.0).abs() < 1e-15);
    assert_eq!(q.tets_below_5deg, 0);
    assert!(q.max_aspect_ratio >= 1.0 && q.mean_aspect_ratio <= q.max_aspect_ratio);
}

#[test]
fn quality_refuses_unknown_struct_sizes_untouched() {
    let m = cube();
    for size in [0, 8, size_of::<mtcut_quality>() + 8] {
        let mut q: mtcut_quality = unsafe { std::mem::zeroed() };
        q.struct_size = size;
        q.tets = 77;
        let s = unsafe { mtcut_mesh_quality(m.0, &mut q) };
        expect(
            s,
            MTCUT_STATUS_INVALID_ARGUMENT,
            "mtcut_mesh_quality",
            "struct_size",
        );
        assert_eq!((q.struct_size, q.tets), (size, 77));
    }
}

#[test]
fn invalid_arrays_are_refused_with_the_culprit() {
    let mut bad = CUBE_TETS;
    bad[5] = 8;
    let (s, msg) = from_arrays(&CUBE_XYZ, &bad).err().unwrap();
    assert_eq!(s, MTCUT_STATUS_INVALID_MESH);
    assert!(msg.contains("tet 1 uses vertex index 8"), "{msg}");

    let mut nan = CUBE_XYZ;
    nan[7] = f64::NAN;
    let (s, msg) = from_arrays(&nan, &CUBE_TETS).err().unwrap();
    assert_eq!(s, MTCUT_STATUS_INVALID_MESH);
    assert!(msg.contains("vertex 2"), "{msg}");

    let (s, msg) = from_arrays(&CUBE_XYZ, &[]).err().unwrap();
    assert_eq!(s, MTCUT_STATUS_INVALID_MESH);
    assert!(msg.contains("no tetrahedra"), "{msg}");

    // The same tet twice: a face shared with the same orientation.
    let (s, _) = from_arrays(&CUBE_XYZ, &[0, 1, 3, 7, 0, 1, 3, 7])
        .err()
        .unwrap();
    assert_eq!(s, MTCUT_STATUS_INVALID_MESH);

    let mut out = ptr::null_mut();
    let s = unsafe {
        mtcut_mesh_from_arrays(
            CUBE_XYZ.as_ptr(),
            usize::MAX,
            CUBE_TETS.as_ptr(),
            6,
            &mut out,
        )
    };
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_from_arrays",
        "do not fit",
    );
    assert!(out.is_null());
}

/// Counts a mesh or a polygon cannot have are refused before the arrays are read: a
/// wrong count must neither read past the caller's array nor copy gigabytes (these read
/// past the end, crashed or aborted on memory before).
#[test]
fn counts_are_checked_before_the_arrays_are_read() {
    let mut out = ptr::null_mut();
    let s = unsafe {
        mtcut_mesh_from_arrays(CUBE_XYZ.as_ptr(), 1 << 33, CUBE_TETS.as_ptr(), 6, &mut out)
    };
    expect(
        s,
        MTCUT_STATUS_INVALID_MESH,
        "mtcut_mesh_from_arrays",
        "4294967294",
    );
    assert!(out.is_null());
    let m = cube();
    let values = [1.0; 8];
    for components in [10, 1 << 28] {
        let s = unsafe {
            mtcut_mesh_set_attribute(
                m.0,
                MTCUT_LOCATION_VERTEX,
                c"t".as_ptr(),
                values.as_ptr(),
                8,
                components,
            )
        };
        expect(
            s,
            MTCUT_STATUS_INVALID_ARGUMENT,
            "mtcut_mesh_set_attribute",
            "components",
        );
    }
    let triangle = [0.5, -1.0, -1.0, 0.5, 3.0, -1.0, 0.5, -1.0, 3.0];
    let s = unsafe { mtcut_mesh_cut(m.0, triangle.as_ptr(), 1 << 40, ptr::null_mut()) };
    expect(s, MTCUT_STATUS_INVALID_ARGUMENT, "mtcut_mesh_cut", "4096");
    assert_eq!(
        unsafe { mtcut_mesh_tet_count(m.0) },
        6,
        "the cube unchanged"
    );
}

#[test]
fn failed_copies_write_nothing() {
    let m = cube();
    let mut xyz = [-1.0; 21];
    let s = unsafe { mtcut_mesh_copy_vertices(m.0, xyz.as_mut_ptr(), 7) };
    expect(
        s,
        MTCUT_STATUS_BUFFER_TOO_SMALL,
        "mtcut_mesh_copy_vertices",
        "holds 7 vertices, 8 are needed",
    );
    assert!(xyz.iter().all(|&v| v == -1.0));
    let mut t = [99u32; 20];
    let s = unsafe { mtcut_mesh_copy_tets(m.0, t.as_mut_ptr(), 5) };
    expect(
        s,
        MTCUT_STATUS_BUFFER_TOO_SMALL,
        "mtcut_mesh_copy_tets",
        "6 are needed",
    );
    assert!(t.iter().all(|&v| v == 99));
    let s = unsafe { mtcut_mesh_copy_tets(ptr::null(), t.as_mut_ptr(), 5) };
    expect(
        s,
        MTCUT_STATUS_NULL_ARGUMENT,
        "mtcut_mesh_copy_tets",
        "`mesh` is NULL",
    );
    assert_eq!(unsafe { mtcut_mesh_vertex_count(ptr::null()) }, 0);
    assert_eq!(
        last_error(),
        "mtcut_mesh_vertex_count: argument `mesh` is NULL"
    );
}

fn set(
    m: &Mesh,
    location: mtcut_location,
    name: &CStr,
    values: &[f64],
    n: usize,
    k: usize,
) -> mtcut_status {
    unsafe { mtcut_mesh_set_attribute(m.0, location, name.as_ptr(), values.as_ptr(), n, k) }
}

fn names(m: &Mesh, location: mtcut_location) -> Vec<String> {
    let mut count = 0usize;
    let s = unsafe { mtcut_mesh_attribute_count(m.0, location, &mut count) };
    expect(s, MTCUT_STATUS_OK, "", "");
    (0..count)
        .map(|i| {
            let mut len = 0usize;
            let s = unsafe {
                mtcut_mesh_attribute_name(m.0, location, i, ptr::null_mut(), 0, &mut len)
            };
            expect(
                s,
                MTCUT_STATUS_BUFFER_TOO_SMALL,
                "mtcut_mesh_attribute_name",
                "needs",
            );
            let mut buf = vec![1 as c_char; len + 1];
            let s = unsafe {
                mtcut_mesh_attribute_name(
                    m.0,
                    location,
                    i,
                    buf.as_mut_ptr(),
                    len + 1,
                    ptr::null_mut(),
                )
            };
            expect(s, MTCUT_STATUS_OK, "", "");
            unsafe { CStr::from_ptr(buf.as_ptr()) }
                .to_str()
                .unwrap()
                .to_owned()
        })
        .collect()
}

fn column(m: &Mesh, location: mtcut_location, name: &CStr) -> Vec<f64> {
    let mut k = 0usize;
    let s = unsafe { mtcut_mesh_attribute_components(m.0, location, name.as_ptr(), &mut k) };
    expect(s, MTCUT_STATUS_OK, "", "");
    let n = if location == MTCUT_LOCATION_VERTEX {
        unsafe { mtcut_mesh_vertex_count(m.0) }
    } else {
        unsafe { mtcut_mesh_tet_count(m.0) }
    };
    let mut values = vec![f64::NAN; n * k];
    let s = unsafe {
        mtcut_mesh_copy_attribute(
            m.0,
            location,
            name.as_ptr(),
            values.as_mut_ptr(),
            values.len(),
        )
    };
    expect(s, MTCUT_STATUS_OK, "", "");
    values
}

#[test]
fn attributes_in_and_out() {
    let m = cube();
    let temperature: Vec<f64> = (0..8).map(|i| 20.0 + i as f64).collect();
    let displacement: Vec<f64> = (0..24).map(|i| i as f64 * 0.5).collect();
    let material = [1.0, 1.0, 2.0, 2.0, 3.0, 3.0];
    expect(
        set(
            &m,
            MTCUT_LOCATION_VERTEX,
            c"temperature",
            &temperature,
            8,
            1,
        ),
        MTCUT_STATUS_OK,
        "",
        "",
    );
    expect(
        set(
            &m,
            MTCUT_LOCATION_VERTEX,
            c"displacement",
            &displacement,
            8,
            3,
        ),
        MTCUT_STATUS_OK,
        "",
        "",
    );
    expect(
        set(&m, MTCUT_LOCATION_TET, c"material", &material, 6, 1),
        MTCUT_STATUS_OK,
        "",
        "",
    );
    assert_eq!(
        names(&m, MTCUT_LOCATION_VERTEX),
        ["temperature", "displacement"]
    );
    assert_eq!(names(&m, MTCUT_LOCATION_TET), ["material"]);
    assert_eq!(
        column(&m, MTCUT_LOCATION_VERTEX, c"displacement"),
        displacement
    );
    assert_eq!(column(&m, MTCUT_LOCATION_TET, c"material"), material);

    // Same name: replaced, with a new component count.
    expect(
        set(
            &m,
            MTCUT_LOCATION_VERTEX,
            c"temperature",
            &displacement,
            8,
            3,
        ),
        MTCUT_STATUS_OK,
        "",
        "",
    );
    assert_eq!(
        column(&m, MTCUT_LOCATION_VERTEX, c"temperature"),
        displacement
    );
    assert_eq!(names(&m, MTCUT_LOCATION_VERTEX).len(), 2);

    // Refusals leave the columns as they were.
    let s = set(&m, MTCUT_LOCATION_TET, c"material", &temperature, 8, 1);
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_set_attribute",
        "n_elements is 8, the mesh has 6 tets",
    );
    let s = set(&m, MTCUT_LOCATION_VERTEX, c"wide", &vec![0.0; 80], 8, 10);
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_set_attribute",
        "components is 10",
    );
    let s = set(&m, 2, c"x", &temperature, 8, 1);
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_set_attribute",
        "location 2",
    );
    let s = set(&m, MTCUT_LOCATION_VERTEX, c"", &temperature, 8, 1);
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_set_attribute",
        "empty",
    );
    let s = set(&m, MTCUT_LOCATION_VERTEX, c"\xff", &temperature, 8, 1);
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_set_attribute",
        "UTF-8",
    );
    assert_eq!(column(&m, MTCUT_LOCATION_TET, c"material"), material);

    let mut small = [7.0; 5];
    let s = unsafe {
        mtcut_mesh_copy_attribute(
            m.0,
            MTCUT_LOCATION_TET,
            c"material".as_ptr(),
            small.as_mut_ptr(),
            5,
        )
    };
    expect(
        s,
        MTCUT_STATUS_BUFFER_TOO_SMALL,
        "mtcut_mesh_copy_attribute",
        "holds 5 values, 6 are needed",
    );
    assert_eq!(small, [7.0; 5]);
    let mut k = 42usize;
    let s = unsafe {
        mtcut_mesh_attribute_components(m.0, MTCUT_LOCATION_TET, c"temperature".as_ptr(), &mut k)
    };
    expect(
        s,
        MTCUT_STATUS_NOT_FOUND,
        "mtcut_mesh_attribute_components",
        "no tet attribute named \"temperature\"",
    );
    assert_eq!(k, 42);
    let mut buf = [5 as c_char; 4];
    let mut len = 0usize;
    let s = unsafe {
        mtcut_mesh_attribute_name(m.0, MTCUT_LOCATION_VERTEX, 1, buf.as_mut_ptr(), 4, &mut len)
    };
    expect(
        s,
        MTCUT_STATUS_BUFFER_TOO_SMALL,
        "mtcut_mesh_attribute_name",
        "needs 13 bytes",
    );
    assert_eq!((buf, len), ([5; 4], 12));
    let s = unsafe {
        mtcut_mesh_attribute_name(m.0, MTCUT_LOCATION_VERTEX, 2, buf.as_mut_ptr(), 4, &mut len)
    };
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_attribute_name",
        "index 2 is past the end",
    );

    let s =
        unsafe { mtcut_mesh_remove_attribute(m.0, MTCUT_LOCATION_VERTEX, c"temperature".as_ptr()) };
    expect(s, MTCUT_STATUS_OK, "", "");
    assert_eq!(names(&m, MTCUT_LOCATION_VERTEX), ["displacement"]);
    let s =
        unsafe { mtcut_mesh_remove_attribute(m.0, MTCUT_LOCATION_VERTEX, c"temperature".as_ptr()) };
    expect(
        s,
        MTCUT_STATUS_NOT_FOUND,
        "mtcut_mesh_remove_attribute",
        "temperature",
    );
}

#[test]
fn components_are_extracted_with_their_attributes() {
    let m = two_cubes();
    let ids: Vec<f64> = (0..16).map(f64::from).collect();
    let tet_ids: Vec<f64> = (0..12).map(f64::from).collect();
    expect(
        set(&m, MTCUT_LOCATION_VERTEX, c"id", &ids, 16, 1),
        MTCUT_STATUS_OK,
        "",
        "",
    );
    expect(
        set(&m, MTCUT_LOCATION_TET, c"tid", &tet_ids, 12, 1),
        MTCUT_STATUS_OK,
        "",
        "",
    );
    let mut count = 0usize;
    expect(
        unsafe { mtcut_mesh_component_count(m.0, &mut count) },
        MTCUT_STATUS_OK,
        "",
        "",
    );
    assert_eq!(count, 2);
    let mut out = ptr::null_mut();
    expect(
        unsafe { mtcut_mesh_extract_component(m.0, 1, &mut out) },
        MTCUT_STATUS_OK,
        "",
        "",
    );
    let part = Mesh(out);
    assert!(validate(&part).0);
    assert_eq!(unsafe { mtcut_mesh_vertex_count(part.0) }, 8);
    assert_eq!(
        column(&part, MTCUT_LOCATION_VERTEX, c"id"),
        (8..16).map(f64::from).collect::<Vec<_>>()
    );
    assert_eq!(
        column(&part, MTCUT_LOCATION_TET, c"tid"),
        (6..12).map(f64::from).collect::<Vec<_>>()
    );
    let (mut lo, mut hi) = ([0.0; 3], [0.0; 3]);
    expect(
        unsafe { mtcut_mesh_bounding_box(part.0, lo.as_mut_ptr(), hi.as_mut_ptr()) },
        MTCUT_STATUS_OK,
        "",
        "",
    );
    assert_eq!((lo, hi), ([3.0, 0.0, 0.0], [4.0, 1.0, 1.0]));

    let mut untouched = ptr::dangling_mut::<mtcut_mesh>();
    let s = unsafe { mtcut_mesh_extract_component(m.0, 2, &mut untouched) };
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_extract_component",
        "the mesh has 2",
    );
    assert_eq!(untouched, ptr::dangling_mut());
}

#[test]
fn clone_is_deep_and_set_vertices_is_checked() {
    let m = cube();
    let mut out = ptr::null_mut();
    expect(
        unsafe { mtcut_mesh_clone(m.0, &mut out) },
        MTCUT_STATUS_OK,
        "",
        "",
    );
    let copy = Mesh(out);

    // Push vertex 7 through the opposite corner: tets invert; the original is unchanged.
    let mut moved = CUBE_XYZ;
    moved[21..24].copy_from_slice(&[-1.0, -1.0, -1.0]);
    let s = unsafe { mtcut_mesh_set_vertices(copy.0, moved.as_ptr(), 8) };
    expect(s, MTCUT_STATUS_OK, "", "");
    assert_eq!(vertices(&copy), moved);
    assert_eq!(vertices(&m), CUBE_XYZ);
    let (valid, message) = validate(&copy);
    assert!(!valid && message.starts_with("invalid mesh: "), "{message}");
    assert!(message.contains("non-positive orientation"), "{message}");

    // Truncated like snprintf; the full length reported.
    let mut short = [1 as c_char; 8];
    let (mut valid, mut len) = (true, 0usize);
    let s = unsafe { mtcut_mesh_validate(copy.0, &mut valid, short.as_mut_ptr(), 8, &mut len) };
    expect(s, MTCUT_STATUS_OK, "", "");
    assert_eq!(unsafe { CStr::from_ptr(short.as_ptr()) }, c"invalid");
    assert_eq!((valid, len), (false, message.len()));

    let mut nan = CUBE_XYZ;
    nan[4] = f64::INFINITY;
    let s = unsafe { mtcut_mesh_set_vertices(copy.0, nan.as_ptr(), 8) };
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_set_vertices",
        "vertex 1",
    );
    let mut far = CUBE_XYZ;
    far[7] = -1e60;
    let s = unsafe { mtcut_mesh_set_vertices(copy.0, far.as_ptr(), 8) };
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_set_vertices",
        "vertex 2 has coordinate -1e60, larger in magnitude than the 1e50",
    );
    let s = unsafe { mtcut_mesh_set_vertices(copy.0, CUBE_XYZ.as_ptr(), 7) };
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_set_vertices",
        "the mesh has 8 vertices",
    );
    assert_eq!(vertices(&copy), moved);
}

fn read(path: &std::path::Path) -> Result<Mesh, (mtcut_status, String)> {
    let c = CString::new(path.as_os_str().as_encoded_bytes()).unwrap();
    let mut out = ptr::null_mut();
    let s = unsafe { mtcut_mesh_read(c.as_ptr(), &mut out) };
    if s == MTCUT_STATUS_OK {
        Ok(Mesh(out))
    } else {
        assert!(out.is_null());
        Err((s, last_error()))
    }
}

fn write(m: &Mesh, path: &std::path::Path) -> mtcut_status {
    let c = CString::new(path.as_os_str().as_encoded_bytes()).unwrap();
    unsafe { mtcut_mesh_write(m.0, c.as_ptr()) }
}

#[test]
fn files_read_and_written() {
    let m = read(&common::data("fandisk.node")).expect("fandisk reads");
    let (reference, _) = mtcut::io::read_mesh(common::data("fandisk.node")).unwrap();
    assert_eq!(unsafe { mtcut_mesh_tet_count(m.0) }, reference.nb_tets());
    assert_eq!(
        unsafe { mtcut_mesh_vertex_count(m.0) },
        reference.nb_vertices()
    );

    let dir = common::scratch("ffi-files");
    let c = cube();
    expect(write(&c, &dir.join("cube.node")), MTCUT_STATUS_OK, "", "");
    let back = read(&dir.join("cube.ele")).expect("written cube reads back");
    assert_eq!(vertices(&back), CUBE_XYZ);
    assert_eq!(tets(&back), tets(&c));

    let s = write(&c, &dir.join("cube.stl"));
    expect(
        s,
        MTCUT_STATUS_UNSUPPORTED_FORMAT,
        "mtcut_mesh_write",
        "cube.stl",
    );
    let s = write(&c, &dir.join("missing-dir/cube.node"));
    expect(s, MTCUT_STATUS_IO_ERROR, "mtcut_mesh_write", "missing-dir");
    let name = CString::new(dir.join("cube.node").as_os_str().as_encoded_bytes()).unwrap();
    let s = unsafe { mtcut_mesh_write_vtu(c.0, name.as_ptr()) };
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_write_vtu",
        "must end in .vtu",
    );

    let (s, msg) = read(&dir.join("nothing.node")).err().unwrap();
    assert_eq!(s, MTCUT_STATUS_IO_ERROR, "{msg}");
    assert!(msg.contains("nothing.node"), "{msg}");
    let (s, _) = read(&dir.join("cube.obj")).err().unwrap();
    assert_eq!(s, MTCUT_STATUS_UNSUPPORTED_FORMAT);
    std::fs::write(dir.join("bad.node"), "8 3 0 0\n0 0 0 zero\n").unwrap();
    std::fs::copy(dir.join("cube.ele"), dir.join("bad.ele")).unwrap();
    let (s, msg) = read(&dir.join("bad.node")).err().unwrap();
    assert_eq!(s, MTCUT_STATUS_PARSE_ERROR, "{msg}");
    assert!(msg.contains("bad.node") && msg.contains("line 2"), "{msg}");
    // A flat tet: all four vertices in the plane z = 0.
    std::fs::write(
        dir.join("flat.node"),
        "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 1 1 0\n",
    )
    .unwrap();
    std::fs::write(dir.join("flat.ele"), "1 4 0\n0 0 1 2 3\n").unwrap();
    let (s, msg) = read(&dir.join("flat.node")).err().unwrap();
    assert_eq!(s, MTCUT_STATUS_INVALID_MESH, "{msg}");
}

#[test]
fn const_functions_run_from_many_threads() {
    let m = two_cubes();
    let handle = m.0 as usize;
    let results: Vec<(usize, f64, usize)> = std::thread::scope(|s| {
        let workers: Vec<_> = (0..4)
            .map(|_| {
                s.spawn(move || {
                    let mesh = handle as *const mtcut_mesh;
                    let (mut v, mut c) = (0.0, 0usize);
                    assert_eq!(unsafe { mtcut_mesh_volume(mesh, &mut v) }, MTCUT_STATUS_OK);
                    assert_eq!(
                        unsafe { mtcut_mesh_component_count(mesh, &mut c) },
                        MTCUT_STATUS_OK
                    );
                    // Each thread's failure message is its own.
                    assert_eq!(
                        unsafe { mtcut_mesh_volume(mesh, ptr::null_mut()) },
                        MTCUT_STATUS_NULL_ARGUMENT
                    );
                    assert_eq!(last_error(), "mtcut_mesh_volume: argument `volume` is NULL");
                    (unsafe { mtcut_mesh_tet_count(mesh) }, v, c)
                })
            })
            .collect();
        workers.into_iter().map(|w| w.join().unwrap()).collect()
    });
    assert!(results.iter().all(|r| *r == (12, 2.0, 2)), "{results:?}");
}

#[test]
fn versions_agree() {
    let v = unsafe { CStr::from_ptr(mtcut_version()) }.to_str().unwrap();
    assert_eq!(v, env!("CARGO_PKG_VERSION"));
    let numbers = format!(
        "{}.{}.{}",
        mtcut_version_major(),
        mtcut_version_minor(),
        mtcut_version_patch()
    );
    assert_eq!(numbers, v);
}

/// A small deterministic generator (xorshift64*), so a failing case is named by its seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// Random arrays — duplicate and out-of-range indices, NaN and infinite coordinates,
/// coincident points, cube corners — are answered with OK or INVALID_MESH, never a panic;
/// every mesh accepted is valid and answers every query.
#[test]
fn random_arrays_never_panic_and_accepted_meshes_are_valid() {
    let mut accepted = 0;
    for seed in 1..=1000u64 {
        let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15));
        let (n, mut xyz, mut tets) = if seed % 2 == 0 {
            // Random points on a 3x3x3 grid: coincident and coplanar points are common.
            let n = 4 + rng.below(6) as usize;
            let xyz: Vec<f64> = (0..3 * n).map(|_| rng.below(3) as f64).collect();
            let tets: Vec<u32> = (0..4 * (1 + rng.below(4) / 2))
                .map(|_| rng.below(n as u64) as u32)
                .collect();
            (n, xyz, tets)
        } else {
            // A random subset of two cubes' tets, each with its vertices in random order
            // (orientation flips), one vertex maybe moved: touching along edges and
            // vertices, inverted and overlapping tets are common.
            let mut xyz = CUBE_XYZ.to_vec();
            xyz.extend(CUBE_XYZ.chunks(3).flat_map(|p| [p[0] + 1.0, p[1], p[2]]));
            let mut tets = Vec::new();
            for (i, t) in CUBE_TETS.chunks(4).chain(CUBE_TETS.chunks(4)).enumerate() {
                if rng.below(8) > 0 {
                    let mut t = t.to_vec();
                    if rng.below(3) == 0 {
                        t.swap(rng.below(4) as usize, rng.below(4) as usize);
                    }
                    let shift = if i >= 6 { 8 } else { 0 };
                    tets.extend(t.iter().map(|v| v + shift));
                }
            }
            if rng.below(4) == 0 {
                let v = rng.below(16) as usize;
                xyz[3 * v] += 0.5;
            }
            if tets.is_empty() {
                tets.extend_from_slice(&CUBE_TETS[..4]);
            }
            (16, xyz, tets)
        };
        let (coordinate, index) = (
            rng.below(xyz.len() as u64) as usize,
            rng.below(tets.len() as u64) as usize,
        );
        match rng.below(8) {
            0 => xyz[coordinate] = f64::NAN,
            1 => xyz[coordinate] = f64::NEG_INFINITY,
            2 => tets[index] = n as u32,
            3 => tets.clear(),
            _ => {}
        }
        let case = format!("seed {seed}: xyz {xyz:?}, tets {tets:?}");
        let mesh = match from_arrays(&xyz, &tets) {
            Ok(mesh) => mesh,
            Err((status, message)) => {
                assert_eq!(status, MTCUT_STATUS_INVALID_MESH, "{case}: {message}");
                continue;
            }
        };
        accepted += 1;
        let (valid, message) = validate(&mesh);
        assert!(valid, "{case}: {message}");
        let (mut volume, mut faces, mut area, mut count) = (0.0, 0usize, 0.0, 0usize);
        let mut q: mtcut_quality = unsafe { std::mem::zeroed() };
        q.struct_size = size_of::<mtcut_quality>();
        let statuses = unsafe {
            [
                mtcut_mesh_volume(mesh.0, &mut volume),
                mtcut_mesh_boundary(mesh.0, &mut faces, &mut area),
                mtcut_mesh_quality(mesh.0, &mut q),
                mtcut_mesh_component_count(mesh.0, &mut count),
            ]
        };
        assert_eq!(statuses, [MTCUT_STATUS_OK; 4], "{case}");
        assert!(volume > 0.0 && faces >= 4 && count >= 1, "{case}");
        for c in 0..count {
            let mut out = ptr::null_mut();
            let s = unsafe { mtcut_mesh_extract_component(mesh.0, c, &mut out) };
            assert_eq!(
                s,
                MTCUT_STATUS_OK,
                "{case}: component {c}: {}",
                last_error()
            );
            let part = Mesh(out);
            assert!(validate(&part).0, "{case}: component {c}");
        }
    }
    assert!(
        accepted > 100,
        "only {accepted} random meshes were valid: the generator is too harsh"
    );
}

fn write_vtu(m: &Mesh, path: &std::path::Path) -> mtcut_status {
    let c = CString::new(path.as_os_str().as_encoded_bytes()).unwrap();
    unsafe { mtcut_mesh_write_vtu(m.0, c.as_ptr()) }
}

#[test]
fn vtu_written_and_read_back_with_attributes() {
    let m = cube();
    let temperature: Vec<f64> = (0..8).map(|i| 0.5 * i as f64).collect();
    let stress: Vec<f64> = (0..54).map(|i| i as f64 - 20.0).collect();
    expect(
        set(
            &m,
            MTCUT_LOCATION_VERTEX,
            c"temperature",
            &temperature,
            8,
            1,
        ),
        MTCUT_STATUS_OK,
        "",
        "",
    );
    expect(
        set(&m, MTCUT_LOCATION_TET, c"stress", &stress, 6, 9),
        MTCUT_STATUS_OK,
        "",
        "",
    );
    let dir = common::scratch("ffi-vtu");
    expect(
        write_vtu(&m, &dir.join("cube.vtu")),
        MTCUT_STATUS_OK,
        "",
        "",
    );
    // mtcut_mesh_write picks the same writer from the extension.
    expect(write(&m, &dir.join("same.vtu")), MTCUT_STATUS_OK, "", "");
    for name in ["cube.vtu", "same.vtu"] {
        let back = read(&dir.join(name)).expect("the .vtu reads back");
        assert_eq!(vertices(&back), CUBE_XYZ);
        assert_eq!(tets(&back), tets(&m));
        assert_eq!(
            column(&back, MTCUT_LOCATION_VERTEX, c"temperature"),
            temperature
        );
        assert_eq!(column(&back, MTCUT_LOCATION_TET, c"stress"), stress);
    }
    let s = write_vtu(&m, &dir.join("missing-dir/cube.vtu"));
    expect(
        s,
        MTCUT_STATUS_IO_ERROR,
        "mtcut_mesh_write_vtu",
        "missing-dir",
    );
    std::fs::write(
        dir.join("broken.vtu"),
        "<VTKFile type=\"UnstructuredGrid\">",
    )
    .unwrap();
    let (s, msg) = read(&dir.join("broken.vtu")).err().unwrap();
    assert_eq!(s, MTCUT_STATUS_PARSE_ERROR, "{msg}");
    assert!(msg.contains("broken.vtu"), "{msg}");
}

/// A file written by VTK's own writer (appended raw binary, zlib), as a VTK-based host
/// hands it over: c-examples/data/box.vtu (scripts/vtk/make_c_example_input.py).
#[test]
fn vtk_written_vtu_reads_with_its_arrays() {
    let box_vtu = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("c-examples/data/box.vtu");
    let m = read(&box_vtu).expect("VTK's box reads");
    assert_eq!(unsafe { mtcut_mesh_vertex_count(m.0) }, 96);
    assert_eq!(unsafe { mtcut_mesh_tet_count(m.0) }, 225);
    let mut volume = 0.0;
    expect(
        unsafe { mtcut_mesh_volume(m.0, &mut volume) },
        MTCUT_STATUS_OK,
        "",
        "",
    );
    assert!((volume - 2.0).abs() < 1e-12, "{volume}");
    assert_eq!(
        names(&m, MTCUT_LOCATION_VERTEX),
        ["temperature", "displacement"]
    );
    assert_eq!(names(&m, MTCUT_LOCATION_TET), ["material"]);
    let xyz = vertices(&m);
    let temperature = column(&m, MTCUT_LOCATION_VERTEX, c"temperature");
    for (p, t) in xyz.chunks(3).zip(&temperature) {
        // The generator wrote 20 + 40 x as 32-bit floats.
        assert!((t - (20.0 + 40.0 * p[0])).abs() < 1e-4, "{t} at {p:?}");
    }
    let material = column(&m, MTCUT_LOCATION_TET, c"material");
    assert!(material.iter().all(|&v| v == 1.0 || v == 2.0));
}

/// A blade's advance across its own line: a translation, a slide along the blade (no
/// advance), a turn about its middle; a NaN end is refused, nothing written.
#[test]
fn blade_advance_is_measured_across_the_blade() {
    let from = [0.0, 0.0, -1.0, 0.0, 0.0, 1.0];
    let advance = |to: [f64; 6]| {
        let mut a = -1.0;
        let s = unsafe { mtcut_blade_advance(from.as_ptr(), to.as_ptr(), &mut a) };
        (s, a)
    };
    assert_eq!(
        advance([0.25, 0.0, -1.0, 0.25, 0.0, 1.0]),
        (MTCUT_STATUS_OK, 0.25)
    );
    assert_eq!(
        advance([0.0, 0.0, 2.0, 0.0, 0.0, 4.0]),
        (MTCUT_STATUS_OK, 0.0)
    );
    assert_eq!(
        advance([-0.5, 0.0, -1.0, 0.5, 0.0, 1.0]),
        (MTCUT_STATUS_OK, 0.5)
    );
    let (s, a) = advance([f64::NAN, 0.0, -1.0, 0.0, 0.0, 1.0]);
    expect(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_blade_advance",
        "to_xyz",
    );
    assert_eq!(a, -1.0);
}
