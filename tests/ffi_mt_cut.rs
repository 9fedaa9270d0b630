//! The C ABI's cut and Multi-Tessellation functions, called as C would call them: results
//! checked against the geometry and against the library, statuses and messages of refused
//! calls, outputs untouched on failure, cancellation through the progress callback, and
//! seeded random bad inputs answered with a status, never a panic.
//!
//! `unsafe` here is the C caller's side of the contract; every call goes through the small
//! wrappers below.

mod blades;
mod common;
mod ffi_common;

use ffi_common::{last_error, ok, refused};
use mtcut::ffi::*;
use std::ffi::{CStr, CString, c_int, c_void};
use std::ptr;

const CUBE_XYZ: [f64; 24] = [
    0., 0., 0., 1., 0., 0., 0., 1., 0., 1., 1., 0., 0., 0., 1., 1., 0., 1., 0., 1., 1., 1., 1., 1.,
];
const CUBE_TETS: [u32; 24] = [
    0, 1, 3, 7, 0, 1, 5, 7, 0, 2, 3, 7, 0, 2, 6, 7, 0, 4, 5, 7, 0, 4, 6, 7,
];
/// A triangle containing the cube's section at z = 0.5.
const ACROSS: [f64; 9] = [-1., -1., 0.5, 5., -1., 0.5, -1., 5., 0.5];

struct Mesh(*mut mtcut_mesh);
impl Drop for Mesh {
    fn drop(&mut self) {
        unsafe { mtcut_mesh_free(self.0) }
    }
}
struct Model(*mut mtcut_mt);
impl Drop for Model {
    fn drop(&mut self) {
        unsafe { mtcut_mt_free(self.0) }
    }
}
struct Front(*mut mtcut_frontier);
impl Drop for Front {
    fn drop(&mut self) {
        unsafe { mtcut_frontier_free(self.0) }
    }
}

fn cube() -> Mesh {
    let mut out = ptr::null_mut();
    ok(unsafe { mtcut_mesh_from_arrays(CUBE_XYZ.as_ptr(), 8, CUBE_TETS.as_ptr(), 6, &mut out) });
    Mesh(out)
}

fn read(name: &str) -> Mesh {
    let path = CString::new(common::data(name).to_str().unwrap()).unwrap();
    let mut out = ptr::null_mut();
    ok(unsafe { mtcut_mesh_read(path.as_ptr(), &mut out) });
    Mesh(out)
}

fn tet_count(m: &Mesh) -> usize {
    unsafe { mtcut_mesh_tet_count(m.0) }
}

fn volume(m: &Mesh) -> f64 {
    let mut v = 0.0;
    ok(unsafe { mtcut_mesh_volume(m.0, &mut v) });
    v
}

fn components(m: &Mesh) -> usize {
    let mut c = 0;
    ok(unsafe { mtcut_mesh_component_count(m.0, &mut c) });
    c
}

/// The mesh is valid (every invariant), or the test fails with the report.
#[track_caller]
fn assert_valid(m: &Mesh, case: &str) {
    let mut valid = false;
    let mut buf = [0 as std::ffi::c_char; 1024];
    ok(unsafe {
        mtcut_mesh_validate(
            m.0,
            &mut valid,
            buf.as_mut_ptr(),
            buf.len(),
            ptr::null_mut(),
        )
    });
    let text = unsafe { CStr::from_ptr(buf.as_ptr()) }.to_string_lossy();
    assert!(valid, "{case}: {text}");
}

fn column(m: &Mesh, location: mtcut_location, name: &CStr) -> Vec<f64> {
    let mut components = 0;
    ok(unsafe { mtcut_mesh_attribute_components(m.0, location, name.as_ptr(), &mut components) });
    let rows = if location == MTCUT_LOCATION_TET {
        tet_count(m)
    } else {
        unsafe { mtcut_mesh_vertex_count(m.0) }
    };
    let mut v = vec![0.0; rows * components];
    ok(unsafe { mtcut_mesh_copy_attribute(m.0, location, name.as_ptr(), v.as_mut_ptr(), v.len()) });
    v
}

fn cut_stats() -> mtcut_cut_stats {
    mtcut_cut_stats {
        struct_size: size_of::<mtcut_cut_stats>(),
        ..Default::default()
    }
}

fn cut_options() -> mtcut_cut_options {
    let mut o: mtcut_cut_options = unsafe { std::mem::zeroed() };
    o.struct_size = size_of::<mtcut_cut_options>();
    ok(unsafe { mtcut_cut_options_default(&mut o) });
    o
}

fn build_options() -> mtcut_build_options {
    let mut o: mtcut_build_options = unsafe { std::mem::zeroed() };
    o.struct_size = size_of::<mtcut_build_options>();
    ok(unsafe { mtcut_build_options_default(&mut o) });
    o
}

fn extract_options() -> mtcut_extract_options {
    let mut o: mtcut_extract_options = unsafe { std::mem::zeroed() };
    o.struct_size = size_of::<mtcut_extract_options>();
    ok(unsafe { mtcut_extract_options_default(&mut o) });
    o
}

fn build(m: &Mesh, options: Option<&mtcut_build_options>) -> Model {
    let mut out = ptr::null_mut();
    let o = options.map_or(ptr::null(), |o| o as *const _);
    ok(unsafe { mtcut_mt_build(m.0, o, &mut out) });
    Model(out)
}

fn mt_stats(mt: &Model) -> mtcut_mt_stats {
    let mut s = mtcut_mt_stats {
        struct_size: size_of::<mtcut_mt_stats>(),
        ..Default::default()
    };
    ok(unsafe { mtcut_mt_statistics(mt.0, &mut s) });
    s
}

fn extract(mt: &Model, o: &mtcut_extract_options) -> (Mesh, mtcut_extract_stats) {
    let mut s = mtcut_extract_stats {
        struct_size: size_of::<mtcut_extract_stats>(),
        ..Default::default()
    };
    let mut out = ptr::null_mut();
    ok(unsafe { mtcut_mt_extract(mt.0, o, &mut s, &mut out) });
    (Mesh(out), s)
}

fn arrays(m: &Mesh) -> (Vec<f64>, Vec<u32>) {
    let (nv, nt) = unsafe { (mtcut_mesh_vertex_count(m.0), mtcut_mesh_tet_count(m.0)) };
    let (mut xyz, mut tets) = (vec![0.0; 3 * nv], vec![0u32; 4 * nt]);
    ok(unsafe { mtcut_mesh_copy_vertices(m.0, xyz.as_mut_ptr(), nv) });
    ok(unsafe { mtcut_mesh_copy_tets(m.0, tets.as_mut_ptr(), nt) });
    (xyz, tets)
}

#[test]
fn a_cut_across_the_cube_splits_it_in_two_and_keeps_its_volume() {
    let m = cube();
    let mut s = cut_stats();
    ok(unsafe { mtcut_mesh_cut(m.0, ACROSS.as_ptr(), 3, &mut s) });
    assert_valid(&m, "cut cube");
    assert_eq!(components(&m), 2);
    assert_eq!(s.components, 2);
    assert!((volume(&m) - 1.0).abs() < 1e-12, "volume {}", volume(&m));
    assert_eq!(s.tets_cut, 6, "the plane crosses every tet of the cube");
    assert_eq!(s.tets_after, tet_count(&m));
    assert_eq!(s.vertices_after, unsafe { mtcut_mesh_vertex_count(m.0) });
    assert_eq!(s.tets_after, 6 - s.tets_cut + s.tets_created);
    assert_eq!(
        s.vertices_added,
        s.cut_points + s.face_points + s.vertex_copies
    );
    assert!(s.tets_tested >= s.tets_candidate && s.tets_candidate >= s.tets_cut);
    assert!(s.seconds_cut >= 0.0 && s.seconds_build >= 0.0);
    // The cut numbers the tets it made.
    let cut = column(&m, MTCUT_LOCATION_TET, c"mtcut:cut");
    assert_eq!(cut.iter().filter(|&&c| c == 1.0).count(), s.tets_created);
    // The two halves: each a valid mesh of volume 1/2.
    for k in 0..2 {
        let mut out = ptr::null_mut();
        ok(unsafe { mtcut_mesh_extract_component(m.0, k, &mut out) });
        let half = Mesh(out);
        assert_valid(&half, "half");
        assert!((volume(&half) - 0.5).abs() < 1e-12);
    }
}

#[test]
fn options_choose_the_scheme_and_the_snapping() {
    let lut = cube();
    let b17 = cube();
    let mut o = cut_options();
    assert_eq!(
        (o.scheme, o.snap, o.face_point_margin, o.count_components),
        (MTCUT_CUT_SCHEME_LUT, 0.2, 0.5, 1)
    );
    let (mut s1, mut s2) = (cut_stats(), cut_stats());
    ok(unsafe { mtcut_mesh_cut_with_options(lut.0, ACROSS.as_ptr(), 3, &o, &mut s1) });
    o.scheme = MTCUT_CUT_SCHEME_BIELSER17;
    o.count_components = 0;
    ok(unsafe { mtcut_mesh_cut_with_options(b17.0, ACROSS.as_ptr(), 3, &o, &mut s2) });
    assert_eq!(s2.tets_created, 17 * s2.tets_cut, "1:17");
    assert!(s1.tets_created < s2.tets_created);
    assert_eq!(s2.components, usize::MAX, "not counted");
    assert!((volume(&b17) - 1.0).abs() < 1e-12);
    // NULL options are the defaults: the same result as the LUT cut.
    let again = cube();
    let mut s3 = cut_stats();
    ok(unsafe { mtcut_mesh_cut_with_options(again.0, ACROSS.as_ptr(), 3, ptr::null(), &mut s3) });
    assert_eq!(arrays(&again), arrays(&lut));
    assert_eq!(
        (s3.tets_created, s3.vertices_added),
        (s1.tets_created, s1.vertices_added)
    );
}

#[test]
fn an_older_stats_struct_gets_only_its_fields() {
    // A program compiled against the first version of mtcut_cut_stats (ending with
    // `seconds_components`) passes that size: it gets those fields, nothing past them.
    let first_version = std::mem::offset_of!(mtcut_cut_stats, polygons_moved_to_plane);
    let m = cube();
    let mut s = cut_stats();
    s.struct_size = first_version;
    s.polygons_moved_to_plane = 77;
    ok(unsafe { mtcut_mesh_cut(m.0, ACROSS.as_ptr(), 3, &mut s) });
    assert!(s.tets_cut > 0 && s.tets_after > 6, "{s:?}");
    assert_eq!(
        s.polygons_moved_to_plane, 77,
        "written past the caller's struct_size"
    );
    // Sizes below the first version are refused, the mesh left alone.
    let m = cube();
    let mut s = cut_stats();
    s.struct_size = first_version - 8;
    let st = unsafe { mtcut_mesh_cut(m.0, ACROSS.as_ptr(), 3, &mut s) };
    refused(
        st,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_cut",
        "sizeof(mtcut_cut_stats)",
    );
    assert_eq!(tet_count(&m), 6, "a refused cut leaves the mesh alone");
    assert_eq!(s.tets_cut, 0);
}

#[test]
fn a_scalpel_sweep_cuts_where_the_blade_went() {
    // The blade, a segment along y through the whole cube at x = 0.5, moves down from
    // above the cube to z = 0.4: a vertical planar sweep, one quadrilateral, cutting the
    // top of the cube without separating it.
    let m = cube();
    let start = [0.5, -1.0, 1.5, 0.5, 2.0, 1.5];
    let end = [0.5, -1.0, 0.4, 0.5, 2.0, 0.4];
    let mut s = cut_stats();
    ok(unsafe { mtcut_mesh_scalpel_sweep(m.0, start.as_ptr(), end.as_ptr(), ptr::null(), &mut s) });
    assert_valid(&m, "partial sweep");
    assert!(s.tets_cut > 0);
    assert_eq!(components(&m), 1, "a partial cut leaves one piece");
    assert!((volume(&m) - 1.0).abs() < 1e-12);
    // A skewed sweep (the ends move by different amounts, out of plane): two triangles.
    let m2 = cube();
    let start = [-1.0, 0.5, 2.0, 2.0, 0.5, 2.0];
    let end = [-1.0, 0.2, -1.0, 2.0, 0.8, -1.5];
    let mut s2 = cut_stats();
    ok(unsafe {
        mtcut_mesh_scalpel_sweep(m2.0, start.as_ptr(), end.as_ptr(), ptr::null(), &mut s2)
    });
    assert_valid(&m2, "skewed sweep");
    assert_eq!(s2.tets_after, tet_count(&m2));
    assert!((volume(&m2) - 1.0).abs() < 1e-12);
}

#[test]
fn a_turning_blade_swept_step_by_step_continues_its_crack() {
    // A vertical blade moving along an arc through the liver, 8° per call, from outside
    // the body (-x) to outside (-y): each call continues the crack of the last (the handle
    // keeps its crack tips; NULL options are the scalpel's), so the corner comes off: two
    // parts, the mesh valid after every step.
    let m = read("liver.node");
    let (mut lo, mut hi) = ([0.0; 3], [0.0; 3]);
    ok(unsafe { mtcut_mesh_bounding_box(m.0, lo.as_mut_ptr(), hi.as_mut_ptr()) });
    let v0 = volume(&m);
    let d = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    let r = 0.6 * d[0].max(d[1]);
    let centre = [lo[0] - 0.1 * d[0], 0.5 * (lo[1] + hi[1]) - r];
    let blade = |k: usize| {
        let a = (98.0 - 8.0 * k as f64).to_radians();
        let (x, y) = (centre[0] + r * a.cos(), centre[1] + r * a.sin());
        [x, y, lo[2] - 0.1 * d[2], x, y, hi[2] + 0.1 * d[2]]
    };
    for k in 0..16 {
        let (start, end) = (blade(k), blade(k + 1));
        let mut s = cut_stats();
        ok(unsafe {
            mtcut_mesh_scalpel_sweep(m.0, start.as_ptr(), end.as_ptr(), ptr::null(), &mut s)
        });
        assert_valid(&m, &format!("step {k}"));
        assert!((volume(&m) - v0).abs() <= 1e-12 * v0, "step {k}");
    }
    assert_eq!(components(&m), 2, "the corner did not come off");
    // The same steps without continuing cracks leave bridges: the body stays in one part.
    let m = read("liver.node");
    let mut o = cut_options();
    ok(unsafe { mtcut_cut_options_scalpel(&mut o) });
    o.continue_cracks = 0;
    for k in 0..16 {
        let (start, end) = (blade(k), blade(k + 1));
        ok(unsafe {
            mtcut_mesh_scalpel_sweep(m.0, start.as_ptr(), end.as_ptr(), &o, ptr::null_mut())
        });
    }
    assert_eq!(components(&m), 1);
}

#[test]
fn components_are_kept_until_the_mesh_is_cut() {
    // A handle finds its components once and keeps them: moving the vertices leaves them,
    // a clone carries them, a cut finds them again.
    let m = cube();
    assert_eq!(components(&m), 1);
    let n = unsafe { mtcut_mesh_vertex_count(m.0) };
    let mut xyz = vec![0.0; 3 * n];
    ok(unsafe { mtcut_mesh_copy_vertices(m.0, xyz.as_mut_ptr(), n) });
    ok(unsafe { mtcut_mesh_set_vertices(m.0, xyz.as_ptr(), n) });
    assert_eq!(components(&m), 1);
    let mut copy = ptr::null_mut();
    ok(unsafe { mtcut_mesh_clone(m.0, &mut copy) });
    let copy = Mesh(copy);
    let mut s = cut_stats();
    ok(unsafe { mtcut_mesh_cut(m.0, ACROSS.as_ptr(), 3, &mut s) });
    assert_eq!(components(&m), 2);
    for k in 0..2 {
        let mut out = ptr::null_mut();
        ok(unsafe { mtcut_mesh_extract_component(m.0, k, &mut out) });
        let half = Mesh(out);
        assert!((volume(&half) - 0.5).abs() < 1e-12);
    }
    assert_eq!(components(&copy), 1);
    let mut out = ptr::null_mut();
    refused(
        unsafe { mtcut_mesh_extract_component(copy.0, 1, &mut out) },
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mesh_extract_component",
        "the mesh has 1",
    );
    ok(unsafe { mtcut_mesh_cut(copy.0, ACROSS.as_ptr(), 3, &mut s) });
    assert_eq!(components(&copy), 2);
}

#[test]
fn a_mesh_keeps_its_cutter_between_cuts() {
    // The first cut prepares the hierarchy and scales (reported), later ones reuse them:
    // the result is the Rust `Cutter`'s, kept across the same cuts; an attribute edit
    // between cuts keeps the cutter, moving the vertices drops it (rebuilt at the next
    // cut), and a clone carries the crack tips.
    use mtcut::cut::{CutOptions, Cutter};
    use mtcut::geom::{CutPolygon, DVec3};
    let m = read("liver.node");
    let input = mtcut::io::read_mesh(common::data("liver.node")).unwrap().0;
    let b = input.bbox();
    let (c, d) = (b.center(), b.max - b.min);
    let squares: Vec<[f64; 12]> = (0..3)
        .map(|k| {
            let z = c.z + (k as f64 - 1.0) * 0.2 * d.z;
            let (x0, x1, y0, y1) = (b.min.x - 1.0, b.max.x + 1.0, b.min.y - 1.0, c.y);
            [x0, y0, z, x1, y0, z + 1.0, x1, y1, z + 1.0, x0, y1, z]
        })
        .collect();
    let mut reference = Cutter::new(input.clone(), CutOptions::DEFAULT).unwrap();
    for (k, sq) in squares.iter().enumerate() {
        let mut s = cut_stats();
        ok(unsafe { mtcut_mesh_cut(m.0, sq.as_ptr(), 4, &mut s) });
        assert_eq!(
            s.seconds_build > 0.0,
            k == 0,
            "cut {k}: {}",
            s.seconds_build
        );
        let corners: Vec<DVec3> = sq.chunks(3).map(|p| DVec3::new(p[0], p[1], p[2])).collect();
        reference.cut(&CutPolygon::new(&corners).unwrap()).unwrap();
        assert_eq!(tet_count(&m), reference.mesh().nb_tets(), "cut {k}");
        if k == 0 {
            // An attribute edit keeps the cutter.
            let temp = vec![1.0; unsafe { mtcut_mesh_vertex_count(m.0) }];
            let name = CString::new("temperature").unwrap();
            ok(unsafe {
                mtcut_mesh_set_attribute(
                    m.0,
                    MTCUT_LOCATION_VERTEX,
                    name.as_ptr(),
                    temp.as_ptr(),
                    temp.len(),
                    1,
                )
            });
        }
    }
    assert_valid(&m, "three cuts");
    let n = unsafe { mtcut_mesh_vertex_count(m.0) };
    let mut xyz = vec![0.0; 3 * n];
    ok(unsafe { mtcut_mesh_copy_vertices(m.0, xyz.as_mut_ptr(), n) });
    let moved = reference.mesh().positions();
    for (p, q) in xyz.chunks(3).zip(moved) {
        assert_eq!(
            [p[0], p[1], p[2]],
            q.to_array(),
            "the C mesh is the Rust cutter's"
        );
    }
    // Moving the vertices (here: a translation) drops the cutter; the next cut rebuilds it.
    for x in xyz.iter_mut().step_by(3) {
        *x += 0.5;
    }
    ok(unsafe { mtcut_mesh_set_vertices(m.0, xyz.as_ptr(), n) });
    let mut s = cut_stats();
    let mut sq = squares[1];
    for x in sq.iter_mut().step_by(3) {
        *x += 0.5;
    }
    sq[2] += 0.1 * d.z;
    sq[5] += 0.1 * d.z;
    sq[8] += 0.1 * d.z;
    sq[11] += 0.1 * d.z;
    ok(unsafe { mtcut_mesh_cut(m.0, sq.as_ptr(), 4, &mut s) });
    assert!(
        s.seconds_build > 0.0,
        "moved vertices: the hierarchy is rebuilt"
    );
    assert_valid(&m, "after moving");
    let mut copy = ptr::null_mut();
    ok(unsafe { mtcut_mesh_clone(m.0, &mut copy) });
    let copy = Mesh(copy);
    assert_eq!(tet_count(&copy), tet_count(&m));
    assert_valid(&copy, "clone");
}

#[test]
fn an_extracted_mesh_carries_the_model_columns_and_can_be_cut() {
    let input = read("pinion-coarse.node");
    let mt = build(&input, None);
    let st = mt_stats(&mt);
    assert_eq!(st.input_tets, tet_count(&input));
    assert_eq!(st.components, 1);
    assert!(st.coarsest_tets < st.input_tets && st.fragments > 2 && st.dag_depth >= 2);
    assert!(0.0 < st.min_error && st.min_error <= st.max_error);
    assert!(st.heap_bytes > 0 && st.tets >= st.input_tets);

    let mut out = ptr::null_mut();
    ok(unsafe { mtcut_mt_extract_threshold(mt.0, 0.0, &mut out) });
    let finest = Mesh(out);
    assert_eq!(tet_count(&finest), st.input_tets);
    assert!((volume(&finest) - volume(&input)).abs() < 1e-9 * volume(&input));
    ok(unsafe { mtcut_mt_extract_threshold(mt.0, f64::INFINITY, &mut out) });
    let coarsest = Mesh(out);
    assert_eq!(tet_count(&coarsest), st.coarsest_tets);
    assert_valid(&coarsest, "coarsest");

    let middle_error = (st.min_error * st.max_error).sqrt();
    ok(unsafe { mtcut_mt_extract_threshold(mt.0, middle_error, &mut out) });
    let middle = Mesh(out);
    assert_valid(&middle, "middle");
    let n = tet_count(&middle);
    assert!(st.coarsest_tets < n && n < st.input_tets, "{n}");
    let errors = column(&middle, MTCUT_LOCATION_TET, c"mt_error");
    assert!(
        errors.iter().all(|&e| e <= middle_error),
        "tets within the threshold"
    );
    assert_eq!(column(&middle, MTCUT_LOCATION_TET, c"mt_fragment").len(), n);
    assert_eq!(column(&middle, MTCUT_LOCATION_TET, c"mt_level").len(), n);
    let ids = column(&middle, MTCUT_LOCATION_VERTEX, c"mt_vertex");
    assert!(
        ids.windows(2).all(|w| w[0] < w[1]),
        "vertices in model order"
    );

    // Cut the extracted mesh through its middle.
    let (lo, hi) = {
        let (mut lo, mut hi) = ([0.0; 3], [0.0; 3]);
        ok(unsafe { mtcut_mesh_bounding_box(middle.0, lo.as_mut_ptr(), hi.as_mut_ptr()) });
        (lo, hi)
    };
    let c = [
        (lo[0] + hi[0]) / 2.0,
        (lo[1] + hi[1]) / 2.0,
        (lo[2] + hi[2]) / 2.0,
    ];
    let r = 2.0 * (hi[0] - lo[0] + hi[1] - lo[1] + hi[2] - lo[2]);
    let square = [
        c[0] - r,
        c[1] - r,
        c[2] + 0.013,
        c[0] + r,
        c[1] - r,
        c[2] + 0.013,
        c[0] + r,
        c[1] + r,
        c[2] + 0.013,
        c[0] - r,
        c[1] + r,
        c[2] + 0.013,
    ];
    let before = volume(&middle);
    let mut s = cut_stats();
    ok(unsafe { mtcut_mesh_cut(middle.0, square.as_ptr(), 4, &mut s) });
    assert_valid(&middle, "cut extraction");
    assert!(s.tets_cut > 0 && s.components >= 2);
    assert!((volume(&middle) - before).abs() < 1e-9 * before);
    assert_eq!(
        column(&middle, MTCUT_LOCATION_TET, c"mt_error").len(),
        tet_count(&middle)
    );
}

#[test]
fn focus_and_budget_extractions() {
    let input = read("pinion-coarse.node");
    let mt = build(&input, None);
    let st = mt_stats(&mt);
    let mut o = extract_options();
    o.threshold = f64::INFINITY;
    let (coarse, cs) = extract(&mt, &o);
    assert_eq!(
        (tet_count(&coarse), cs.tets),
        (st.coarsest_tets, st.coarsest_tets)
    );
    // Full resolution in a sphere around one vertex of the input, coarse elsewhere.
    let (xyz, _) = arrays(&input);
    o.focus = MTCUT_FOCUS_SPHERE;
    o.focus_center = [xyz[0], xyz[1], xyz[2]];
    o.focus_radius = 1e-3;
    o.focus_threshold = 0.0;
    let (focused, fs) = extract(&mt, &o);
    assert_valid(&focused, "focus");
    assert!(
        fs.tets > st.coarsest_tets && fs.tets < st.input_tets,
        "{}",
        fs.tets
    );
    assert_eq!(fs.tets, tet_count(&focused));
    assert_eq!(fs.budget_met, 1);
    // The same region as a box.
    o.focus = MTCUT_FOCUS_BOX;
    o.focus_min = [xyz[0] - 1e-3, xyz[1] - 1e-3, xyz[2] - 1e-3];
    o.focus_max = [xyz[0] + 1e-3, xyz[1] + 1e-3, xyz[2] + 1e-3];
    let (boxed, _) = extract(&mt, &o);
    assert_valid(&boxed, "box focus");
    // A budget between the coarsest and the finest mesh caps a full-resolution request.
    let budget = (st.coarsest_tets + st.input_tets) / 2;
    let mut b = extract_options();
    b.budget = budget;
    let (capped, bs) = extract(&mt, &b);
    assert_valid(&capped, "budget");
    assert!(
        bs.tets <= budget && bs.tets > st.coarsest_tets,
        "{}",
        bs.tets
    );
    assert_eq!(bs.budget_met, 1);
    b.budget = 1;
    let (_, tiny) = extract(&mt, &b);
    assert_eq!((tiny.budget_met, tiny.tets), (0, st.coarsest_tets));
}

#[test]
fn a_frontier_follows_its_options_as_a_fresh_extraction_would() {
    let input = read("pinion-coarse.node");
    let mt = build(&input, None);
    let st = mt_stats(&mt);
    let mut o = extract_options();
    o.threshold = f64::INFINITY;
    let mut out = ptr::null_mut();
    ok(unsafe { mtcut_frontier_new(mt.0, &o, &mut out) });
    let f = Front(out);
    assert_eq!(unsafe { mtcut_frontier_tet_count(f.0) }, st.coarsest_tets);
    let (xyz, _) = arrays(&input);
    o.focus = MTCUT_FOCUS_SPHERE;
    o.focus_threshold = 0.0;
    o.focus_radius = 2e-3;
    // The focus moves along the input's first vertices; after each move the frontier's
    // mesh is the fresh extraction's.
    for k in 0..4 {
        o.focus_center = [xyz[3 * k * 10], xyz[3 * k * 10 + 1], xyz[3 * k * 10 + 2]];
        let mut u = mtcut_frontier_update_stats {
            struct_size: size_of::<mtcut_frontier_update_stats>(),
            ..Default::default()
        };
        ok(unsafe { mtcut_frontier_update(f.0, &o, &mut u) });
        let mut out = ptr::null_mut();
        ok(unsafe { mtcut_frontier_mesh(f.0, &mut out) });
        let incremental = Mesh(out);
        let (fresh, _) = extract(&mt, &o);
        assert_eq!(arrays(&incremental), arrays(&fresh), "move {k}");
        assert_eq!(u.tets, tet_count(&fresh));
        assert_valid(&incremental, "frontier");
    }
    // The frontier shares the model: freeing the handle first is allowed.
    drop(mt);
    o.focus = MTCUT_FOCUS_NONE;
    ok(unsafe { mtcut_frontier_update(f.0, &o, ptr::null_mut()) });
    assert_eq!(unsafe { mtcut_frontier_tet_count(f.0) }, st.coarsest_tets);
}

#[test]
fn a_saved_model_loads_as_the_same_model() {
    let input = read("pinion-coarse.node");
    let mt = build(&input, None);
    let dir = common::scratch("ffi-mt-save");
    let path = CString::new(dir.join("pinion.mt").to_str().unwrap()).unwrap();
    ok(unsafe { mtcut_mt_save(mt.0, path.as_ptr()) });
    let mut out = ptr::null_mut();
    ok(unsafe { mtcut_mt_load(path.as_ptr(), &mut out) });
    let back = Model(out);
    let (a, b) = (mt_stats(&mt), mt_stats(&back));
    assert_eq!(
        (
            a.vertices,
            a.tets,
            a.fragments,
            a.dag_depth,
            a.min_error,
            a.max_error
        ),
        (
            b.vertices,
            b.tets,
            b.fragments,
            b.dag_depth,
            b.min_error,
            b.max_error
        )
    );
    let mut o = extract_options();
    o.threshold = (a.min_error * a.max_error).sqrt();
    assert_eq!(arrays(&extract(&mt, &o).0), arrays(&extract(&back, &o).0));
    // A damaged file is refused with a parse error naming it.
    let mut bytes = std::fs::read(dir.join("pinion.mt")).unwrap();
    let n = bytes.len();
    bytes[n / 2] ^= 0x55;
    std::fs::write(dir.join("bad.mt"), &bytes).unwrap();
    let bad = CString::new(dir.join("bad.mt").to_str().unwrap()).unwrap();
    let mut out = ptr::null_mut();
    let s = unsafe { mtcut_mt_load(bad.as_ptr(), &mut out) };
    refused(s, MTCUT_STATUS_PARSE_ERROR, "mtcut_mt_load", "bad.mt");
    assert!(out.is_null());
}

struct Progress {
    fractions: Vec<f64>,
    cancel_at: usize,
}

unsafe extern "C" fn record(user: *mut c_void, fraction: f64) -> c_int {
    let p = unsafe { &mut *(user as *mut Progress) };
    p.fractions.push(fraction);
    c_int::from(p.fractions.len() >= p.cancel_at)
}

#[test]
fn the_progress_callback_reports_and_cancels() {
    let input = read("pinion-coarse.node");
    let mut p = Progress {
        fractions: Vec::new(),
        cancel_at: usize::MAX,
    };
    let mut o = build_options();
    o.progress_or_null = Some(record);
    o.user = (&mut p as *mut Progress).cast();
    let full = build(&input, Some(&o));
    let calls = p.fractions.len();
    assert!(calls >= 3, "{calls} calls");
    assert!(
        p.fractions.windows(2).all(|w| w[0] <= w[1]),
        "{:?}",
        p.fractions
    );
    assert!(p.fractions.iter().all(|f| (0.0..=1.0).contains(f)));
    assert_eq!(p.fractions.last(), Some(&1.0));
    drop(full);
    // Cancelled at every call in turn: no model, the callback not called again.
    for cancel_at in 1..=calls {
        p.fractions.clear();
        p.cancel_at = cancel_at;
        let sentinel = 0x10 as *mut mtcut_mt;
        let mut out = sentinel;
        let s = unsafe { mtcut_mt_build(input.0, &o, &mut out) };
        refused(s, MTCUT_STATUS_CANCELLED, "mtcut_mt_build", "cancelled");
        assert_eq!(out, sentinel, "out untouched");
        assert_eq!(p.fractions.len(), cancel_at);
    }
}

#[test]
fn build_options_are_checked_and_target_stops_early() {
    let input = read("pinion-coarse.node");
    let mut o = build_options();
    let mut out = ptr::null_mut();
    type Edit = fn(&mut mtcut_build_options);
    let edits: [(&str, Edit); 4] = [
        ("error_metric", |o| o.error_metric = 9),
        ("boundary tolerance", |o| o.boundary_tolerance = f64::NAN),
        ("feature angle", |o| o.feature_angle_degrees = 200.0),
        ("quality floor", |o| o.min_quality = -0.5),
    ];
    for (field, set) in edits {
        let mut bad = o;
        set(&mut bad);
        let s = unsafe { mtcut_mt_build(input.0, &bad, &mut out) };
        refused(s, MTCUT_STATUS_INVALID_ARGUMENT, "mtcut_mt_build", field);
        assert!(out.is_null());
    }
    o.target_tets = tet_count(&input) / 2;
    o.error_metric = MTCUT_ERROR_METRIC_QUALITY;
    let half = build(&input, Some(&o));
    let st = mt_stats(&half);
    assert!(
        st.coarsest_tets <= o.target_tets && st.coarsest_tets > o.target_tets / 2,
        "{} for a target of {}",
        st.coarsest_tets,
        o.target_tets
    );
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
    /// A coordinate: usually in or near the cube, sometimes NaN, infinite or huge.
    fn coordinate(&mut self) -> f64 {
        match self.below(20) {
            0 => f64::NAN,
            1 => f64::INFINITY,
            2 => -1e300,
            3 => 0.5,
            _ => self.below(9) as f64 / 4.0 - 0.5,
        }
    }
}

/// Random polygons and sweeps (NaN and infinite corners, repeated and collinear corners,
/// non-planar and non-convex ones, too few) and random option values: each call returns OK
/// or INVALID_ARGUMENT with a message, never a panic; an accepted cut leaves a valid mesh
/// of the same volume, a refused one the mesh unchanged.
#[test]
fn random_cuts_and_options_never_panic() {
    let (mut accepted, mut refusals) = (0, 0);
    for seed in 1..=400u64 {
        let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15));
        let m = cube();
        let (n, corners) = if rng.below(2) == 0 {
            let n = rng.below(6) as usize;
            (n, (0..3 * n).map(|_| rng.coordinate()).collect())
        } else {
            // A square of side 6 around a point of the cube, in a random plane, maybe with
            // one corner spoiled.
            let c =
                [rng.coordinate(), rng.coordinate(), rng.coordinate()].map(|x| x.clamp(0.0, 1.0));
            let u = [1.0, rng.below(5) as f64 / 4.0, rng.below(3) as f64 / 2.0];
            let v = [-(u[1] + u[2]) / 2.0, 1.0, 1.0];
            let v = [v[0], v[1] - u[1] * v[0] / 1.0, v[2]];
            let mut corners = Vec::new();
            for (a, b) in [(-3.0, -3.0), (3.0, -3.0), (3.0, 3.0), (-3.0, 3.0)] {
                for k in 0..3 {
                    corners.push(c[k] + a * u[k] + b * v[k]);
                }
            }
            if rng.below(3) == 0 {
                let i = rng.below(12) as usize;
                corners[i] = rng.coordinate();
            }
            (4, corners)
        };
        let mut o = cut_options();
        match rng.below(8) {
            0 => o.scheme = rng.below(4) as u32,
            // 0 is refused (below the smallest snap, flat tets would result: seed 131).
            1 => {
                o.snap = [0.0, 1e-9, 0.05, 0.25, 0.26, -0.1, f64::NAN, f64::INFINITY]
                    [rng.below(8) as usize]
            }
            2 => o.face_point_margin = rng.coordinate(),
            3 => o.struct_size = rng.below(2 * size_of::<mtcut_cut_options>() as u64) as usize,
            _ => {}
        }
        let mut s = cut_stats();
        let before = arrays(&m);
        let (status, what) = if seed % 3 == 0 && n >= 4 {
            let st = unsafe {
                mtcut_mesh_scalpel_sweep(m.0, corners.as_ptr(), corners[6..].as_ptr(), &o, &mut s)
            };
            (st, "mtcut_mesh_scalpel_sweep")
        } else {
            let st = unsafe { mtcut_mesh_cut_with_options(m.0, corners.as_ptr(), n, &o, &mut s) };
            (st, "mtcut_mesh_cut_with_options")
        };
        let case = format!("seed {seed}: {what} corners {corners:?}, options {o:?}");
        if status == MTCUT_STATUS_OK {
            accepted += 1;
            // The 1:17 scheme is not conforming (hanging vertices, by design): its meshes
            // fail validation; the volume still holds.
            if o.scheme != MTCUT_CUT_SCHEME_BIELSER17 {
                assert_valid(&m, &case);
            }
            assert!((volume(&m) - 1.0).abs() < 1e-12, "{case}");
            assert_eq!(s.tets_after, tet_count(&m), "{case}");
        } else {
            refusals += 1;
            refused(status, MTCUT_STATUS_INVALID_ARGUMENT, what, "");
            assert_eq!(arrays(&m), before, "{case}: a refused cut changed the mesh");
            assert_eq!(s.tets_after, 0, "{case}: stats written on failure");
        }
    }
    assert!(
        accepted > 20 && refusals > 100,
        "{accepted} accepted, {refusals} refused"
    );
}

/// Random extraction options on a small model: OK (a valid mesh) or INVALID_ARGUMENT,
/// never a panic, and a frontier refusing an update keeps its mesh.
#[test]
fn random_extraction_options_never_panic() {
    let mt = build(&cube(), None);
    let mut out = ptr::null_mut();
    ok(unsafe { mtcut_frontier_new(mt.0, ptr::null(), &mut out) });
    let f = Front(out);
    let mut accepted = 0;
    for seed in 1..=300u64 {
        let mut rng = Rng(seed.wrapping_mul(0x517c_c1b7_2722_0a95));
        let mut o = extract_options();
        o.threshold = rng.coordinate();
        o.focus = rng.below(4) as u32;
        o.focus_threshold = rng.coordinate();
        o.focus_center = [rng.coordinate(), rng.coordinate(), rng.coordinate()];
        o.focus_radius = rng.coordinate();
        o.focus_min = [rng.coordinate(), rng.coordinate(), rng.coordinate()];
        o.focus_max = [rng.coordinate(), rng.coordinate(), rng.coordinate()];
        o.budget = rng.below(8) as usize;
        if rng.below(10) == 0 {
            o.struct_size = rng.below(256) as usize;
        }
        let case = format!("seed {seed}: {o:?}");
        let mut mesh = ptr::null_mut();
        let s = unsafe { mtcut_mt_extract(mt.0, &o, ptr::null_mut(), &mut mesh) };
        let before = unsafe { mtcut_frontier_tet_count(f.0) };
        let u = unsafe { mtcut_frontier_update(f.0, &o, ptr::null_mut()) };
        assert_eq!(s, u, "{case}: extraction and frontier disagree");
        if s == MTCUT_STATUS_OK {
            accepted += 1;
            let m = Mesh(mesh);
            assert_valid(&m, &case);
            assert_eq!(
                tet_count(&m),
                unsafe { mtcut_frontier_tet_count(f.0) },
                "{case}"
            );
        } else {
            assert_eq!(s, MTCUT_STATUS_INVALID_ARGUMENT, "{case}: {}", last_error());
            assert!(mesh.is_null(), "{case}");
            assert_eq!(unsafe { mtcut_frontier_tet_count(f.0) }, before, "{case}");
        }
    }
    assert!(accepted > 30, "only {accepted} accepted");
}

fn mt_cut(mt: &Model, polygon: &[f64]) -> (mtcut_status, mtcut_cut_stats) {
    let mut s = cut_stats();
    let status = unsafe { mtcut_mt_cut(mt.0, polygon.as_ptr(), polygon.len() / 3, &mut s) };
    (status, s)
}

/// A square well beyond the body, in the plane z = `z`.
fn square_at(m: &Mesh, z: f64) -> Vec<f64> {
    let (xyz, _) = arrays(m);
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for p in xyz.chunks_exact(3) {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let d = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let (a, b) = ([lo[0] - d, lo[1] - d], [hi[0] + d, hi[1] + d]);
    vec![a[0], a[1], z, b[0], a[1], z, b[0], b[1], z, a[0], b[1], z]
}

#[test]
fn a_model_cut_through_becomes_two_models_and_keeps_its_volume() {
    let input = read("liver.node");
    let (xyz, _) = arrays(&input);
    let zs: Vec<f64> = xyz.chunks_exact(3).map(|p| p[2]).collect();
    let (zmin, zmax) = zs
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &z| (a.min(z), b.max(z)));
    let mt = build(&input, None);
    let before = mt_stats(&mt);
    assert_eq!(before.components, 1);
    // Simplification moves the boundary (within the build's tolerance): each level keeps
    // its own volume through the cut, so compare with the same level before.
    let level_volume = |mt: &Model, threshold: f64| {
        let mut out = ptr::null_mut();
        ok(unsafe { mtcut_mt_extract_threshold(mt.0, threshold, &mut out) });
        let m = Mesh(out);
        assert_valid(&m, "an extraction");
        (volume(&m), components(&m))
    };
    let volumes_before = [level_volume(&mt, 0.0).0, level_volume(&mt, f64::INFINITY).0];
    // A frontier made before the cut keeps the model it was made from.
    let mut frontier = ptr::null_mut();
    ok(unsafe { mtcut_frontier_new(mt.0, &extract_options(), &mut frontier) });
    let frontier = Front(frontier);

    // A bad polygon leaves the model as it was.
    let flat = [0., 0., 0., 1., 0., 0., 2., 0., 0.];
    let (status, s) = mt_cut(&mt, &flat);
    refused(
        status,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mt_cut",
        "polygon_xyz",
    );
    assert_eq!(s.tets_cut, 0);
    assert_eq!(mt_stats(&mt), before);

    let (status, s) = mt_cut(&mt, &square_at(&input, 0.5 * (zmin + zmax)));
    ok(status);
    assert!(s.tets_cut > 0 && s.tets_created > s.tets_cut, "{s:?}");
    assert_eq!(
        s.vertices_added,
        s.cut_points + s.face_points + s.vertex_copies
    );
    assert_eq!(s.components, 2);
    let after = mt_stats(&mt);
    assert_eq!(after.components, 2);
    assert_eq!(after.tets, s.tets_after);

    // Finest and coarsest meshes keep their volume; the parts are separate bodies.
    let v0 = volume(&input);
    assert!((volumes_before[0] - v0).abs() <= 1e-12 * v0);
    for (threshold, before) in [0.0, f64::INFINITY].into_iter().zip(volumes_before) {
        let (v, parts) = level_volume(&mt, threshold);
        assert_eq!(parts, 2);
        assert!((v - before).abs() <= 1e-12 * before, "{v} vs {before}");
    }
    // Each component is a model of its own; their finest meshes add up to the input.
    let mut total = 0.0;
    for k in 0..2 {
        let mut out = ptr::null_mut();
        ok(unsafe { mtcut_mt_component(mt.0, k, &mut out) });
        let part = Model(out);
        assert_eq!(mt_stats(&part).components, 1);
        let mut mesh = ptr::null_mut();
        ok(unsafe { mtcut_mt_extract_threshold(part.0, 0.0, &mut mesh) });
        let mesh = Mesh(mesh);
        assert_valid(&mesh, "a component's finest mesh");
        total += volume(&mesh);
    }
    assert!((total - v0).abs() <= 1e-12 * v0, "{total} vs {v0}");
    let mut out = ptr::null_mut();
    let status = unsafe { mtcut_mt_component(mt.0, 2, &mut out) };
    refused(
        status,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_mt_component",
        "has 2",
    );
    assert!(out.is_null());

    let mut old = ptr::null_mut();
    ok(unsafe { mtcut_frontier_mesh(frontier.0, &mut old) });
    let old = Mesh(old);
    assert_eq!(tet_count(&old), tet_count(&input));
    assert_eq!(components(&old), 1);
}

/// Positions a simulation set that invert a tet: the next cut is refused with a message
/// naming the tet, the mesh kept as set (and cut once the positions are good again).
#[test]
fn a_cut_of_a_mesh_moved_into_inverted_tets_is_refused() {
    let m = cube();
    let mut s = cut_stats();
    ok(unsafe { mtcut_mesh_cut(m.0, ACROSS.as_ptr(), 3, &mut s) });
    let n = unsafe { mtcut_mesh_vertex_count(m.0) };
    let mut good = vec![0.0; 3 * n];
    ok(unsafe { mtcut_mesh_copy_vertices(m.0, good.as_mut_ptr(), n) });
    let tets_before = tet_count(&m);
    // Vertex 7 (the far corner, in every tet) pulled through the opposite corner.
    let mut bad = good.clone();
    bad[21..24].copy_from_slice(&[-1.0, -1.0, -1.0]);
    ok(unsafe { mtcut_mesh_set_vertices(m.0, bad.as_ptr(), n) });
    let other: [f64; 9] = [-1., -1., 0.25, 5., -1., 0.25, -1., 5., 0.25];
    let status = unsafe { mtcut_mesh_cut(m.0, other.as_ptr(), 3, &mut s) };
    refused(
        status,
        MTCUT_STATUS_INVALID_MESH,
        "mtcut_mesh_cut",
        "would be inverted or flat",
    );
    assert_eq!(tet_count(&m), tets_before, "nothing cut");
    let mut now = vec![0.0; 3 * n];
    ok(unsafe { mtcut_mesh_copy_vertices(m.0, now.as_mut_ptr(), n) });
    assert_eq!(now, bad, "the positions as set");
    ok(unsafe { mtcut_mesh_set_vertices(m.0, good.as_ptr(), n) });
    ok(unsafe { mtcut_mesh_cut(m.0, other.as_ptr(), 3, &mut s) });
    assert!(tet_count(&m) > tets_before);
    assert_valid(&m, "cut after the positions were restored");
}

/// A turning blade cut into a model one `mtcut_mt_cut` call per step: the model carries
/// what a step continuing the last at an angle needs (its cut record), so each call, made
/// on the model as the last one left it, continues the crack, and the corner comes off.
#[test]
fn a_model_cut_by_a_turning_blade_call_by_call_loses_its_corner() {
    let input = read("liver.node");
    let (mut lo, mut hi) = ([0.0; 3], [0.0; 3]);
    ok(unsafe { mtcut_mesh_bounding_box(input.0, lo.as_mut_ptr(), hi.as_mut_ptr()) });
    let mt = build(&input, None);
    let d = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    let r = 0.6 * d[0].max(d[1]);
    let centre = [lo[0] - 0.1 * d[0], 0.5 * (lo[1] + hi[1]) - r];
    let at = |k: usize| {
        let a = (98.0 - 8.0 * k as f64).to_radians();
        (centre[0] + r * a.cos(), centre[1] + r * a.sin())
    };
    let (z0, z1) = (lo[2] - 0.1 * d[2], hi[2] + 0.1 * d[2]);
    for k in 0..16 {
        let ((x0, y0), (x1, y1)) = (at(k), at(k + 1));
        let quad = [x0, y0, z0, x1, y1, z0, x1, y1, z1, x0, y0, z1];
        let (status, _) = mt_cut(&mt, &quad);
        assert_eq!(status, MTCUT_STATUS_OK, "step {k}: {}", last_error());
    }
    assert_eq!(mt_stats(&mt).components, 2, "the corner did not come off");
}

/// The model as `mtcut_mt_save` writes it.
fn saved(mt: &Model, dir: &std::path::Path) -> Vec<u8> {
    let path = dir.join("model.mt");
    let c_path = CString::new(path.to_str().unwrap()).unwrap();
    ok(unsafe { mtcut_mt_save(mt.0, c_path.as_ptr()) });
    std::fs::read(path).unwrap()
}

/// A handle keeps what its first cut prepared for the next calls: a blade tilting across
/// liver in 20 steps, cut one call per polygon, gives byte for byte the model one Rust
/// `MtCutter` gives after each polygon — also when frontiers made between calls still share
/// the model (a cut then works on a copy, each frontier keeps the model it was made from).
/// The steps the model refuses (the known limit at steep angles, tests/mt_scalpel.rs) are
/// refused alike, naming the fragment, the model byte for byte as before, and the next
/// calls go on from there.
#[test]
fn a_model_keeps_its_cutter_between_calls() {
    use mtcut::cut::{CutError, MtCutter};
    let dir = common::scratch("ffi-mt-cutter");
    let input = read("liver.node");
    let mt = build(&input, None);
    let rust = mtcut::mt::Mt::from_bytes(&saved(&mt, &dir)).expect("a saved model");
    let mut cutter = MtCutter::new(rust, MtCutter::DEFAULT_OPTIONS).expect("options");
    let b = mtcut::geom::Aabb::from_points(cutter.mt().positions());
    let path: Vec<mtcut::cut::Blade> = (0..=20).map(|k| blades::tilting_in(&b, k, 20)).collect();
    let tolerance = mtcut::geom::Tolerance { relative: 1e-9 };
    let (mut refusals, mut frontiers) = (0, Vec::new());
    for (k, w) in path.windows(2).enumerate() {
        // The polygons as a C host gets them, and as the Rust scalpel cuts them.
        let swept = sweep_polygons(&w[0], &w[1]).expect("sweep");
        let rust_sweep = mtcut::geom::scalpel_sweep(w[0], w[1], tolerance).expect("sweep");
        assert_eq!(swept.len(), rust_sweep.len(), "step {k}");
        for (corners, polygon) in swept.into_iter().zip(rust_sweep) {
            let rust_corners: Vec<f64> =
                polygon.points().iter().flat_map(|p| p.to_array()).collect();
            assert_eq!(corners, rust_corners, "step {k}");
            let before = saved(&mt, &dir);
            let (status, s) = mt_cut(&mt, &corners);
            match cutter.cut(&polygon) {
                Ok(stats) => {
                    assert_eq!(status, MTCUT_STATUS_OK, "step {k}: {}", last_error());
                    assert_eq!(
                        (s.tets_cut, s.components),
                        (stats.tets_cut, stats.components)
                    );
                    assert_eq!(s.tets_after, mt_stats(&mt).tets, "step {k}");
                }
                Err(CutError::MtInconsistent { .. }) => {
                    refused(
                        status,
                        MTCUT_STATUS_INVALID_MESH,
                        "mtcut_mt_cut",
                        "fragment",
                    );
                    assert!(
                        saved(&mt, &dir) == before,
                        "step {k}: the refused cut changed it"
                    );
                    refusals += 1;
                }
                Err(e) => panic!("step {k}: {e}"),
            }
            assert!(
                saved(&mt, &dir) == cutter.mt().to_bytes(),
                "step {k}: models differ"
            );
        }
        if k % 4 == 1 {
            let mut f = ptr::null_mut();
            ok(unsafe { mtcut_frontier_new(mt.0, &extract_options(), &mut f) });
            let f = Front(f);
            let mesh = frontier_arrays(&f);
            frontiers.push((f, mesh));
        }
    }
    assert!(
        refusals > 0,
        "no step refused: this test needs another refused cut"
    );
    let report = cutter.mt().validate();
    assert!(report.is_valid(), "{report}");
    // The whole check through the C ABI, its message truncated like snprintf.
    let (mut valid, mut len, mut buf) = (false, 0usize, [0 as std::ffi::c_char; 4]);
    let buf_ptr = buf.as_mut_ptr();
    ok(unsafe { mtcut_mt_validate(mt.0, &mut valid, buf_ptr, buf.len(), &mut len) });
    let text = unsafe { CStr::from_ptr(buf.as_ptr()) }.to_str().unwrap();
    assert!(
        valid && text == "val" && len == "valid MT".len(),
        "{valid} {text:?} {len}"
    );
    // Each frontier still extracts the model it was made from, as it was.
    for (f, mesh) in &frontiers {
        ok(unsafe { mtcut_frontier_update(f.0, &extract_options(), ptr::null_mut()) });
        assert!(frontier_arrays(f) == *mesh, "a frontier saw a later cut");
    }
}

fn frontier_arrays(f: &Front) -> (Vec<f64>, Vec<u32>) {
    let mut out = ptr::null_mut();
    ok(unsafe { mtcut_frontier_mesh(f.0, &mut out) });
    arrays(&Mesh(out))
}

/// `mtcut_mt_roi_box` and `mtcut_mt_roi_sphere` give the sub-model the Rust
/// `region_of_interest` gives, byte for byte, valid, inside the region, the model they were
/// given unchanged; bad regions are refused naming their arguments, `*out` untouched.
#[test]
fn a_region_of_interest_through_the_c_abi() {
    use mtcut::cut::{RoiRegion, region_of_interest};
    use mtcut::geom::{Aabb, DVec3};
    let dir = common::scratch("ffi-mt-roi");
    let input = read("pinion.node");
    let mt = build(&input, None);
    let before = saved(&mt, &dir);
    let rust = mtcut::mt::Mt::from_bytes(&before).expect("a saved model");
    let (mut lo, mut hi) = ([0.0; 3], [0.0; 3]);
    ok(unsafe { mtcut_mesh_bounding_box(input.0, lo.as_mut_ptr(), hi.as_mut_ptr()) });
    let at = |f: f64| -> [f64; 3] { std::array::from_fn(|i| lo[i] + f * (hi[i] - lo[i])) };
    let (min, max) = (at(0.25), at(0.7));
    let centre = at(0.5);
    let radius = 0.3 * (0..3).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt();
    let regions = [
        RoiRegion::Box(Aabb {
            min: DVec3::from_array(min),
            max: DVec3::from_array(max),
        }),
        RoiRegion::Sphere {
            center: DVec3::from_array(centre),
            radius,
        },
    ];
    for region in regions {
        let mut out = ptr::null_mut();
        ok(match region {
            RoiRegion::Box(_) => unsafe {
                mtcut_mt_roi_box(mt.0, min.as_ptr(), max.as_ptr(), &mut out)
            },
            RoiRegion::Sphere { .. } => unsafe {
                mtcut_mt_roi_sphere(mt.0, centre.as_ptr(), radius, &mut out)
            },
        });
        let sub = Model(out);
        let (expected, stats) = region_of_interest(&rust, &region).expect("Rust sub-model");
        assert!(
            stats.planes_cut > 0 && stats.components_dropped > 0,
            "{stats:?}"
        );
        assert!(
            saved(&sub, &dir) == expected.to_bytes(),
            "{region:?}: not the Rust sub-model"
        );
        let mut valid = false;
        ok(unsafe { mtcut_mt_validate(sub.0, &mut valid, ptr::null_mut(), 0, ptr::null_mut()) });
        assert!(valid, "{region:?}: the sub-model is not valid");
        // Its finest mesh lies in the region (the sphere's: within the polyhedron around
        // it, at most 1.24 radii from the centre), up to the cut's snapping.
        let mut finest = ptr::null_mut();
        ok(unsafe { mtcut_mt_extract_threshold(sub.0, 0.0, &mut finest) });
        let finest = Mesh(finest);
        assert_valid(&finest, "the sub-model's finest mesh");
        let (xyz, _) = arrays(&finest);
        let slack = 1e-6 * radius;
        for p in xyz.chunks_exact(3).map(|p| DVec3::new(p[0], p[1], p[2])) {
            let inside = match region {
                RoiRegion::Box(b) => p.cmpge(b.min - slack).all() && p.cmple(b.max + slack).all(),
                RoiRegion::Sphere { center, radius } => {
                    p.distance(center) <= 1.2394 * radius + slack
                }
            };
            assert!(inside, "{region:?}: vertex {p} outside the region");
        }
    }
    assert!(saved(&mt, &dir) == before, "the model given changed");

    // Bad regions: refused, naming the arguments, `*out` untouched.
    let far = at(3.0);
    let nan = [f64::NAN, 0.0, 0.0];
    let boxes: [([f64; 3], [f64; 3], &str); 4] = [
        (nan, max, "not finite"),
        (min, min, "empty or flat"),
        (max, min, "empty or flat"),
        (far, at(4.0), "does not meet the body"),
    ];
    for (a, b, needle) in boxes {
        let mut out = ptr::null_mut();
        let status = unsafe { mtcut_mt_roi_box(mt.0, a.as_ptr(), b.as_ptr(), &mut out) };
        refused(
            status,
            MTCUT_STATUS_INVALID_ARGUMENT,
            "mtcut_mt_roi_box",
            needle,
        );
        assert!(
            last_error().contains("`box_min`, `box_max`"),
            "{}",
            last_error()
        );
        assert!(out.is_null());
    }
    let spheres: [([f64; 3], f64, &str); 4] = [
        (centre, 0.0, "radius"),
        (centre, -1.0, "radius"),
        (centre, f64::NAN, "radius"),
        (far, radius, "does not meet the body"),
    ];
    for (c, r, needle) in spheres {
        let mut out = ptr::null_mut();
        let status = unsafe { mtcut_mt_roi_sphere(mt.0, c.as_ptr(), r, &mut out) };
        refused(
            status,
            MTCUT_STATUS_INVALID_ARGUMENT,
            "mtcut_mt_roi_sphere",
            needle,
        );
        assert!(out.is_null());
    }
    let mut out = ptr::null_mut();
    let status = unsafe { mtcut_mt_roi_box(ptr::null(), min.as_ptr(), max.as_ptr(), &mut out) };
    refused(
        status,
        MTCUT_STATUS_NULL_ARGUMENT,
        "mtcut_mt_roi_box",
        "`mt`",
    );
    let status = unsafe { mtcut_mt_roi_sphere(mt.0, ptr::null(), radius, &mut out) };
    refused(
        status,
        MTCUT_STATUS_NULL_ARGUMENT,
        "mtcut_mt_roi_sphere",
        "`center`",
    );
    assert!(out.is_null());
    assert!(
        saved(&mt, &dir) == before,
        "a refused region changed the model"
    );
}

/// `mtcut_scalpel_sweep_polygons` of a blade moving from `start` to `end`: each polygon's
/// corners, or the status and message of a refusal.
fn sweep_polygons(
    start: &[mtcut::geom::DVec3; 2],
    end: &[mtcut::geom::DVec3; 2],
) -> Result<Vec<Vec<f64>>, (mtcut_status, String)> {
    let flat =
        |b: &[mtcut::geom::DVec3; 2]| -> Vec<f64> { b.iter().flat_map(|p| p.to_array()).collect() };
    let (start, end) = (flat(start), flat(end));
    let mut xyz = [f64::NAN; 3 * MTCUT_SWEEP_MAX_POINTS];
    let (mut counts, mut n) = ([usize::MAX; 2], usize::MAX);
    let status = unsafe {
        mtcut_scalpel_sweep_polygons(
            start.as_ptr(),
            end.as_ptr(),
            xyz.as_mut_ptr(),
            counts.as_mut_ptr(),
            &mut n,
        )
    };
    if status != MTCUT_STATUS_OK {
        assert!(
            n == usize::MAX && counts == [usize::MAX; 2] && xyz.iter().all(|x| x.is_nan()),
            "a refused sweep wrote its outputs"
        );
        return Err((status, last_error()));
    }
    assert!(n == 1 || n == 2, "{n} polygons");
    let mut polygons = Vec::new();
    let mut at = 0;
    for &c in &counts[..n] {
        assert!(c == 3 || c == 4, "a polygon of {c} corners");
        polygons.push(xyz[3 * at..3 * (at + c)].to_vec());
        at += c;
    }
    Ok(polygons)
}

/// The sweep polygons a C host gets: one quadrilateral for a planar sweep, one triangle
/// when an end stays, two triangles for a twisted one (what the Rust scalpel cuts, see
/// the tilting blade above); a blade that does not move, a folded sweep, a coordinate that
/// is not finite and NULL outputs are refused, nothing written.
#[test]
fn a_sweep_gives_the_polygons_the_scalpel_cuts() {
    use mtcut::geom::{DVec3, SWEEP_PLANARITY, scalpel_sweep};
    let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let start = [v(0., 0., 0.), v(0., 0., 1.)];
    let cases: [([DVec3; 2], usize); 3] = [
        ([v(1., 0., 0.), v(1., 0., 1.)], 1),
        ([v(0., 0., 0.), v(1., 0., 1.)], 1),
        ([v(1., 0.3, 0.), v(1., -0.3, 1.)], 2),
    ];
    for (end, n) in cases {
        let swept = sweep_polygons(&start, &end).expect("a sweep");
        let rust = scalpel_sweep(start, end, SWEEP_PLANARITY).expect("a sweep");
        assert_eq!(swept.len(), n, "{end:?}");
        for (c, p) in swept.iter().zip(&rust) {
            let corners: Vec<f64> = p.points().iter().flat_map(|q| q.to_array()).collect();
            assert_eq!(c, &corners);
        }
    }
    // A blade that does not move, one whose ends swap sides (a bow tie), a NaN.
    let folded = [v(1., 0., 1.), v(1., 0., 0.)];
    let nan = [v(f64::NAN, 0., 0.), v(1., 0., 1.)];
    for (end, needle) in [(start, "start_xyz/end_xyz"), (folded, "start_xyz/end_xyz")] {
        let (status, message) = sweep_polygons(&start, &end).expect_err("refused");
        assert_eq!(status, MTCUT_STATUS_INVALID_ARGUMENT, "{message}");
        assert!(message.contains(needle), "{message}");
    }
    let (status, message) = sweep_polygons(&start, &nan).expect_err("refused");
    assert_eq!(status, MTCUT_STATUS_INVALID_ARGUMENT, "{message}");
    let (a, b) = ([0.0; 6], [1.0, 0.0, 0.0, 1.0, 0.0, 1.0]);
    let (mut xyz, mut counts, mut n) = ([0.0; 18], [0usize; 2], 0usize);
    let (x, c, m) = (xyz.as_mut_ptr(), counts.as_mut_ptr(), &mut n as *mut usize);
    let null_cases: [(usize, &str); 5] = [
        (0, "`start_xyz`"),
        (1, "`end_xyz`"),
        (2, "`polygons_xyz`"),
        (3, "`point_counts`"),
        (4, "`n_polygons`"),
    ];
    for (k, needle) in null_cases {
        let nul = |i: usize| k == i;
        let status = unsafe {
            mtcut_scalpel_sweep_polygons(
                if nul(0) { ptr::null() } else { a.as_ptr() },
                if nul(1) { ptr::null() } else { b.as_ptr() },
                if nul(2) { ptr::null_mut() } else { x },
                if nul(3) { ptr::null_mut() } else { c },
                if nul(4) { ptr::null_mut() } else { m },
            )
        };
        refused(
            status,
            MTCUT_STATUS_NULL_ARGUMENT,
            "mtcut_scalpel_sweep_polygons",
            needle,
        );
    }
    assert!(
        n == 0 && counts == [0, 0] && xyz == [0.0; 18],
        "a refused call wrote"
    );
}

/// A second cut overlapping a partial first one nearly in its plane (offset by 1e-9 of the
/// diagonal, tilted by about 4e-6) is made in that plane and reported in
/// `polygons_moved_to_plane`; a caller with the first version of `mtcut_cut_stats` (its
/// `struct_size` ending before that field) gets the rest and not that field.
#[test]
fn a_cut_close_to_an_earlier_cuts_plane_is_moved_into_it_and_reported() {
    let input = read("fandisk.node");
    let (xyz, _) = arrays(&input);
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for p in xyz.chunks_exact(3) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    let diag = size.iter().map(|s| s * s).sum::<f64>().sqrt();
    let (xc, zc) = (0.5 * (lo[0] + hi[0]), lo[2] + 0.5123 * size[2]);
    // A band across y, from x0 to x1, at height z0 at x0 and z1 at x1.
    let band = |x0: f64, x1: f64, z0: f64, z1: f64| {
        let (y0, y1) = (lo[1] - size[1], hi[1] + size[1]);
        vec![x0, y0, z0, x1, y0, z1, x1, y1, z1, x0, y1, z0]
    };
    let mt = build(&input, None);
    let (status, first) = mt_cut(&mt, &band(lo[0] - size[0], xc, zc, zc));
    assert_eq!(status, MTCUT_STATUS_OK, "first cut: {}", last_error());
    assert!(first.tets_cut > 0 && first.polygons_moved_to_plane == 0);
    let (x0, x1) = (xc - 0.05 * size[0], xc + 0.2 * size[0]);
    let z0 = zc + 1e-9 * diag;
    let (status, second) = mt_cut(&mt, &band(x0, x1, z0, z0 + 1e-6 * diag));
    assert_eq!(status, MTCUT_STATUS_OK, "second cut: {}", last_error());
    assert!(second.tets_cut > 0 && second.polygons_moved_to_plane == 1);
    // The first version of the struct: the new field is left as the caller set it.
    let mut old = cut_stats();
    old.struct_size = std::mem::offset_of!(mtcut_cut_stats, polygons_moved_to_plane);
    old.polygons_moved_to_plane = 77;
    let third = band(
        xc + 0.15 * size[0],
        xc + 0.3 * size[0],
        zc - 1e-8 * diag,
        zc - 1e-8 * diag,
    );
    let status = unsafe { mtcut_mt_cut(mt.0, third.as_ptr(), 4, &mut old) };
    assert_eq!(status, MTCUT_STATUS_OK, "third cut: {}", last_error());
    assert!(old.tets_cut > 0, "the older struct got the counts");
    assert_eq!(
        old.polygons_moved_to_plane, 77,
        "written past the caller's struct_size"
    );
    let mut valid = false;
    ok(unsafe { mtcut_mt_validate(mt.0, &mut valid, ptr::null_mut(), 0, ptr::null_mut()) });
    assert!(valid, "the model is not valid");
}
