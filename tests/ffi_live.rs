//! The C ABI of the time-critical cut (`mtcut_live_*`), called as C would call it: a bent
//! fandisk cut frontier first, the queue processed by budget, model ids back on every
//! vertex, resolution changes refused while work is pending, a cut the model refuses
//! counted in the report, a scalpel's sweep the model refuses taken as another split of
//! it, or, refused whole, swept again past a gap, and bad arguments refused with a status
//! and a message, outputs untouched.

mod blades;
mod common;
mod ffi_common;

use ffi_common::{ok, refused};
use mtcut::ffi::*;
use std::ffi::CString;
use std::ptr;

struct Live(*mut mtcut_live);
impl Drop for Live {
    fn drop(&mut self) {
        unsafe { mtcut_live_free(self.0) }
    }
}

/// A live fandisk at a middle resolution.
fn live() -> Live {
    live_of("fandisk.node")
}

/// A live model of a shared mesh at a middle resolution.
fn live_of(mesh: &str) -> Live {
    let path = CString::new(common::data(mesh).to_str().unwrap()).unwrap();
    unsafe {
        let mut mesh = ptr::null_mut();
        ok(mtcut_mesh_read(path.as_ptr(), &mut mesh));
        let mut mt = ptr::null_mut();
        ok(mtcut_mt_build(mesh, ptr::null(), &mut mt));
        mtcut_mesh_free(mesh);
        let mut st = mtcut_mt_stats {
            struct_size: size_of::<mtcut_mt_stats>(),
            ..Default::default()
        };
        ok(mtcut_mt_statistics(mt, &mut st));
        let mut eo: mtcut_extract_options = std::mem::zeroed();
        eo.struct_size = size_of::<mtcut_extract_options>();
        ok(mtcut_extract_options_default(&mut eo));
        eo.threshold = (st.min_error * st.max_error).sqrt();
        let mut live = ptr::null_mut();
        ok(mtcut_live_new(mt, &eo, &mut live));
        mtcut_mt_free(mt); // the live model holds its own copy
        Live(live)
    }
}

fn positions(l: &Live) -> Vec<f64> {
    let n = unsafe { mtcut_live_vertex_count(l.0) };
    let mut xyz = vec![0.0; 3 * n];
    ok(unsafe { mtcut_live_copy_positions(l.0, xyz.as_mut_ptr(), n) });
    xyz
}

fn ids(l: &Live) -> Vec<u32> {
    let n = unsafe { mtcut_live_vertex_count(l.0) };
    let mut ids = vec![0; n];
    ok(unsafe { mtcut_live_copy_mt_vertex_ids(l.0, ids.as_mut_ptr(), n) });
    ids
}

fn valid_mesh(l: &Live) -> bool {
    unsafe {
        let mut m = ptr::null_mut();
        ok(mtcut_live_mesh(l.0, &mut m));
        let mut valid = false;
        ok(mtcut_mesh_validate(
            m,
            &mut valid,
            ptr::null_mut(),
            0,
            ptr::null_mut(),
        ));
        mtcut_mesh_free(m);
        valid
    }
}

#[test]
fn a_bent_body_is_cut_frontier_first_then_the_model_catches_up() {
    let l = live();
    let n = unsafe { mtcut_live_vertex_count(l.0) };
    // Bend: x moves with sin(z), by 0.2% of the size (no tet inverted).
    let mut xyz = positions(&l);
    for p in xyz.chunks_mut(3) {
        p[0] += 0.002 * (3.0 * p[2]).sin();
    }
    ok(unsafe { mtcut_live_set_positions(l.0, xyz.as_ptr(), n) });
    assert_eq!(positions(&l), xyz);
    let mut rest = vec![0.0; 3 * n];
    ok(unsafe { mtcut_live_copy_rest_positions(l.0, rest.as_mut_ptr(), n) });
    assert_ne!(rest, xyz);

    // Straight through the middle, given where the body lies.
    let square = [
        -5.0, -5.0, 0.01, 5.0, -5.0, 0.01, 5.0, 5.0, 0.01, -5.0, 5.0, 0.01,
    ];
    let mut cs = mtcut_cut_stats {
        struct_size: size_of::<mtcut_cut_stats>(),
        ..Default::default()
    };
    ok(unsafe { mtcut_live_cut(l.0, square.as_ptr(), 4, &mut cs) });
    assert!(cs.tets_cut > 0 && cs.seconds_cut > 0.0, "{cs:?}");
    assert_eq!(unsafe { mtcut_live_pending_cuts(l.0) }, 1);
    assert_eq!(unsafe { mtcut_live_tet_count(l.0) }, cs.tets_after);
    assert!(valid_mesh(&l));
    // New vertices have no model vertex yet.
    assert!(ids(&l).contains(&u32::MAX));

    // While pending, the resolution stays.
    refused(
        unsafe { mtcut_live_set_resolution(l.0, ptr::null()) },
        MTCUT_STATUS_PENDING_WORK,
        "mtcut_live_set_resolution",
        "1 cut(s) are still pending",
    );
    let mut r = mtcut_pending_report {
        struct_size: size_of::<mtcut_pending_report>(),
        ..Default::default()
    };
    ok(unsafe { mtcut_live_process_pending(l.0, 1, 0.0, &mut r) });
    assert_eq!((r.cuts_done, r.cuts_left, r.remeshed), (1, 0, 0), "{r:?}");
    assert!(r.fragments > 0 && r.seconds > 0.0, "{r:?}");
    assert!(
        !ids(&l).contains(&u32::MAX),
        "every vertex named by its model vertex"
    );
    assert!(valid_mesh(&l));
    unsafe {
        let mut mt = ptr::null_mut();
        ok(mtcut_live_mt(l.0, &mut mt));
        let mut st = mtcut_mt_stats {
            struct_size: size_of::<mtcut_mt_stats>(),
            ..Default::default()
        };
        ok(mtcut_mt_statistics(mt, &mut st));
        // (The model's own validation is tests/mt_live.rs's, on the Rust side.)
        assert_eq!(st.components, 2, "the cut went through");
        mtcut_mt_free(mt);
    }
    // A square 1e-7 off that plane (a blade re-entering the cut) is made in it, here and
    // on the model: reported, nothing remeshed.
    let mut again = square;
    for k in 0..4 {
        again[3 * k + 2] += 1e-7;
    }
    let mut cs = mtcut_cut_stats {
        struct_size: size_of::<mtcut_cut_stats>(),
        ..Default::default()
    };
    ok(unsafe { mtcut_live_cut(l.0, again.as_ptr(), 4, &mut cs) });
    assert_eq!(cs.polygons_moved_to_plane, 1, "{cs:?}");
    ok(unsafe { mtcut_live_process_pending(l.0, 1, 0.0, &mut r) });
    assert_eq!((r.cuts_done, r.cuts_left, r.remeshed), (1, 0, 0), "{r:?}");
    assert!(valid_mesh(&l));
    // Nothing pending: a new resolution is taken.
    ok(unsafe { mtcut_live_set_resolution(l.0, ptr::null()) });
    assert!(valid_mesh(&l));
}

/// The blade tilting as it crosses the live model's current mesh in 20 steps
/// (tests/mt_scalpel.rs), whose steep steps the model refuses as their default triangles.
fn tilting_path(l: &Live) -> Vec<mtcut::cut::Blade> {
    let xyz = positions(l);
    let corners: Vec<mtcut::geom::DVec3> = xyz
        .chunks(3)
        .map(|p| mtcut::geom::DVec3::new(p[0], p[1], p[2]))
        .collect();
    let b = mtcut::geom::Aabb::from_points(corners.iter());
    (0..=20).map(|k| blades::tilting_in(&b, k, 20)).collect()
}

#[test]
fn a_cut_the_model_refuses_is_counted_in_the_report() {
    // The blade tilting as it crosses fandisk in 20 steps (tests/mt_scalpel.rs): the model
    // refuses steps that meet the last one's crack at a steep angle (the known limit). The
    // report counts them (`refused`), the queue is empty, the current mesh was replaced by
    // the model's extraction: valid, every vertex named. A caller passing the report's
    // older size (without `refused`) is not written past `seconds`.
    let l = live();
    let path = tilting_path(&l);
    let report = |size: usize| mtcut_pending_report {
        struct_size: size,
        refused: 777,
        ..Default::default()
    };
    let mut refused_steps = 0;
    for (k, w) in path.windows(2).enumerate() {
        let tolerance = mtcut::geom::Tolerance { relative: 1e-9 };
        let sweep = mtcut::geom::scalpel_sweep(w[0], w[1], tolerance).expect("sweep");
        for polygon in &sweep {
            let corners: Vec<f64> = polygon.points().iter().flat_map(|p| p.to_array()).collect();
            let n = polygon.points().len();
            ok(unsafe { mtcut_live_cut(l.0, corners.as_ptr(), n, ptr::null_mut()) });
        }
        let mut r = report(size_of::<mtcut_pending_report>());
        ok(unsafe { mtcut_live_process_pending(l.0, 0, 0.0, &mut r) });
        assert_eq!(r.cuts_left, 0, "step {k}: {r:?}");
        assert_eq!(r.cuts_done + r.refused, sweep.len(), "step {k}: {r:?}");
        if r.refused > 0 {
            refused_steps += 1;
            assert_eq!(r.remeshed, 1, "step {k}: {r:?}");
        }
        assert!(valid_mesh(&l), "step {k}");
        assert!(!ids(&l).contains(&u32::MAX), "step {k}: a vertex not named");
    }
    // When MT cuts learn to tilt, this test needs another cut the model refuses.
    assert!(refused_steps > 0, "no cut refused");
    // The older report: nothing written after `seconds`.
    let square = [
        -5.0, -5.0, 0.01, 5.0, -5.0, 0.01, 5.0, 5.0, 0.01, -5.0, 5.0, 0.01,
    ];
    ok(unsafe { mtcut_live_cut(l.0, square.as_ptr(), 4, ptr::null_mut()) });
    let mut r = report(std::mem::offset_of!(mtcut_pending_report, refused));
    ok(unsafe { mtcut_live_process_pending(l.0, 0, 0.0, &mut r) });
    assert_eq!((r.cuts_done, r.refused), (1, 777), "{r:?}");
}

#[test]
fn a_sweep_the_model_refuses_is_cut_as_another_split() {
    // The same tilting blade given as whole sweeps (`mtcut_live_scalpel_sweep`): where the
    // model refuses a sweep's two triangles it takes another split of the sweep, the
    // current mesh replaced by its extraction. No step is refused; every mesh valid, every
    // vertex named. A caller passing the report's older size (without `other_splits`) is
    // not written it.
    let l = live();
    let path: Vec<[f64; 6]> = tilting_path(&l)
        .into_iter()
        .map(|[p, q]| [p.x, p.y, p.z, q.x, q.y, q.z])
        .collect();
    let (mut other_splits, mut tets_cut) = (Vec::new(), 0);
    for (k, w) in path.windows(2).enumerate() {
        let mut cs = mtcut_cut_stats {
            struct_size: size_of::<mtcut_cut_stats>(),
            ..Default::default()
        };
        ok(unsafe { mtcut_live_scalpel_sweep(l.0, w[0].as_ptr(), w[1].as_ptr(), &mut cs) });
        assert!(
            cs.seconds_cut > 0.0 && cs.tets_after > 0,
            "step {k}: {cs:?}"
        );
        tets_cut += cs.tets_cut;
        let mut r = mtcut_pending_report {
            struct_size: size_of::<mtcut_pending_report>(),
            ..Default::default()
        };
        ok(unsafe { mtcut_live_process_pending(l.0, 0, 0.0, &mut r) });
        assert_eq!((r.cuts_left, r.refused), (0, 0), "step {k}: {r:?}");
        if r.other_splits > 0 {
            assert_eq!(r.remeshed, 1, "step {k}: {r:?}");
            other_splits.push(k);
        }
        assert!(valid_mesh(&l), "step {k}");
        assert!(!ids(&l).contains(&u32::MAX), "step {k}: a vertex not named");
    }
    // When MT cuts take the tilt's first splits, this test needs another path.
    assert!(!other_splits.is_empty(), "no sweep cut as another split");
    assert!(tets_cut > 1000, "{tets_cut} current tets cut");
    // A blade that does not move sweeps nothing; NULL ends; the older report.
    let (a, z) = (path[3], path[4]);
    let s = unsafe { mtcut_live_scalpel_sweep(l.0, a.as_ptr(), a.as_ptr(), ptr::null_mut()) };
    refused(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_live_scalpel_sweep",
        "start_xyz/end_xyz",
    );
    let s = unsafe { mtcut_live_scalpel_sweep(l.0, ptr::null(), z.as_ptr(), ptr::null_mut()) };
    refused(
        s,
        MTCUT_STATUS_NULL_ARGUMENT,
        "mtcut_live_scalpel_sweep",
        "start_xyz",
    );
    assert_eq!(unsafe { mtcut_live_pending_cuts(l.0) }, 0);
    let square = [
        -5.0, -5.0, 0.01, 5.0, -5.0, 0.01, 5.0, 5.0, 0.01, -5.0, 5.0, 0.01,
    ];
    ok(unsafe { mtcut_live_cut(l.0, square.as_ptr(), 4, ptr::null_mut()) });
    let mut r = mtcut_pending_report {
        struct_size: std::mem::offset_of!(mtcut_pending_report, other_splits),
        other_splits: 777,
        ..Default::default()
    };
    ok(unsafe { mtcut_live_process_pending(l.0, 0, 0.0, &mut r) });
    assert_eq!((r.cuts_done, r.other_splits), (1, 777), "{r:?}");
}

#[test]
fn a_sweep_refused_whole_is_cut_again_past_a_gap() {
    // A shallow incision turning by 4° per step across liver (tests/cli_scalpel.rs): the
    // model refuses some steps whole, every split of their sweeps (`refused`, no cut done),
    // and the current mesh is extracted again without them. Swept again from a tenth of
    // the way into the step, as a new crack (what `mtcut scalpel --time-critical
    // --skip-refused` does), each is taken, leaving a bridge that wide uncut; the model
    // and the current mesh valid after every step, every vertex named.
    let l = live_of("liver.node");
    let xyz = positions(&l);
    let corners: Vec<mtcut::geom::DVec3> = xyz
        .chunks(3)
        .map(|p| mtcut::geom::DVec3::new(p[0], p[1], p[2]))
        .collect();
    let b = mtcut::geom::Aabb::from_points(corners.iter());
    let path = blades::shallow_turning(&b, 4.0);
    let flat = |[p, q]: mtcut::cut::Blade| [p.x, p.y, p.z, q.x, q.y, q.z];
    let sweep = |from: mtcut::cut::Blade, to: mtcut::cut::Blade| {
        ok(unsafe {
            mtcut_live_scalpel_sweep(l.0, flat(from).as_ptr(), flat(to).as_ptr(), ptr::null_mut())
        });
        let mut r = mtcut_pending_report {
            struct_size: size_of::<mtcut_pending_report>(),
            ..Default::default()
        };
        ok(unsafe { mtcut_live_process_pending(l.0, 0, 0.0, &mut r) });
        assert_eq!(r.cuts_left, 0, "{r:?}");
        r
    };
    let mut again = Vec::new();
    for (k, w) in path.windows(2).enumerate() {
        let r = sweep(w[0], w[1]);
        if r.refused > 0 && r.cuts_done == 0 {
            assert_eq!(r.remeshed, 1, "step {k}: {r:?}");
            let gap = [0, 1].map(|i| w[0][i].lerp(w[1][i], 0.1));
            let r = sweep(gap, w[1]);
            assert_eq!(r.refused, 0, "step {k} past the gap: {r:?}");
            assert!(r.cuts_done > 0, "step {k} past the gap: {r:?}");
            again.push(k);
        }
        assert!(valid_mesh(&l), "step {k}");
        assert!(!ids(&l).contains(&u32::MAX), "step {k}: a vertex not named");
        unsafe {
            let mut mt = ptr::null_mut();
            ok(mtcut_live_mt(l.0, &mut mt));
            let mut valid = false;
            ok(mtcut_mt_validate(
                mt,
                &mut valid,
                ptr::null_mut(),
                0,
                ptr::null_mut(),
            ));
            mtcut_mt_free(mt);
            assert!(valid, "step {k}: the model");
        }
    }
    // When the model takes every step of this incision, this test needs another path.
    assert!(!again.is_empty(), "no step refused whole");
}

#[test]
fn bad_arguments_are_refused_and_change_nothing() {
    let l = live();
    let n = unsafe { mtcut_live_vertex_count(l.0) };
    let xyz = positions(&l);
    let name = "mtcut_live_set_positions";
    let s = unsafe { mtcut_live_set_positions(l.0, xyz.as_ptr(), n - 1) };
    refused(s, MTCUT_STATUS_INVALID_ARGUMENT, name, "positions given");
    // A count far past the array is refused before it is read.
    let s = unsafe { mtcut_live_set_positions(l.0, xyz.as_ptr(), 1 << 28) };
    refused(s, MTCUT_STATUS_INVALID_ARGUMENT, name, "positions given");
    // Positions inverting every tet (the body mirrored) are a bad argument.
    let mirrored: Vec<f64> = xyz.iter().map(|x| -x).collect();
    let s = unsafe { mtcut_live_set_positions(l.0, mirrored.as_ptr(), n) };
    refused(s, MTCUT_STATUS_INVALID_ARGUMENT, name, "inverted");
    let mut nan = xyz.clone();
    nan[7] = f64::NAN;
    let s = unsafe { mtcut_live_set_positions(l.0, nan.as_ptr(), n) };
    refused(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        name,
        "vertex 2 is not finite",
    );
    let s = unsafe { mtcut_live_set_positions(l.0, ptr::null(), n) };
    refused(s, MTCUT_STATUS_NULL_ARGUMENT, name, "xyz");
    let s = unsafe { mtcut_live_set_positions(ptr::null_mut(), xyz.as_ptr(), n) };
    refused(s, MTCUT_STATUS_NULL_ARGUMENT, name, "live");
    assert_eq!(positions(&l), xyz, "positions unchanged");

    // Too small an output: nothing written.
    let mut small = vec![-1.0; 3 * (n - 1)];
    let s = unsafe { mtcut_live_copy_positions(l.0, small.as_mut_ptr(), n - 1) };
    refused(
        s,
        MTCUT_STATUS_BUFFER_TOO_SMALL,
        "mtcut_live_copy_positions",
        "xyz",
    );
    assert!(small.iter().all(|&x| x == -1.0));

    // A polygon with two corners, a negative time budget.
    let two = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0];
    let s = unsafe { mtcut_live_cut(l.0, two.as_ptr(), 2, ptr::null_mut()) };
    refused(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_live_cut",
        "polygon_xyz",
    );
    let s = unsafe { mtcut_live_cut(l.0, two.as_ptr(), 1 << 40, ptr::null_mut()) };
    refused(s, MTCUT_STATUS_INVALID_ARGUMENT, "mtcut_live_cut", "4096");
    assert_eq!(unsafe { mtcut_live_pending_cuts(l.0) }, 0);
    let s = unsafe { mtcut_live_process_pending(l.0, 0, -1.0, ptr::null_mut()) };
    refused(
        s,
        MTCUT_STATUS_INVALID_ARGUMENT,
        "mtcut_live_process_pending",
        "max_seconds",
    );
    let mut out = ptr::null_mut();
    let s = unsafe { mtcut_live_new(ptr::null(), ptr::null(), &mut out) };
    refused(s, MTCUT_STATUS_NULL_ARGUMENT, "mtcut_live_new", "mt");
    assert!(out.is_null());
    assert_eq!(unsafe { mtcut_live_vertex_count(ptr::null()) }, 0);
    unsafe { mtcut_live_free(ptr::null_mut()) };
}
