//! Nothing the C API hands out stays allocated once freed: every handle (mesh, model,
//! frontier) released through its `mtcut_*_free`, every failed call, leaves the heap as it
//! found it. Measured with a counting allocator over this whole test binary (one test, so
//! no other test allocates meanwhile). valgrind checks the same on the C examples.

mod common;

use mtcut::ffi::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::ffi::CString;
use std::ptr;
use std::sync::atomic::{AtomicIsize, Ordering};

struct Counting;

static LIVE: AtomicIsize = AtomicIsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        LIVE.fetch_add(l.size() as isize, Ordering::SeqCst);
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        LIVE.fetch_sub(l.size() as isize, Ordering::SeqCst);
        unsafe { System.dealloc(p, l) }
    }
    unsafe fn alloc_zeroed(&self, l: Layout) -> *mut u8 {
        LIVE.fetch_add(l.size() as isize, Ordering::SeqCst);
        unsafe { System.alloc_zeroed(l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
        LIVE.fetch_add(new as isize - l.size() as isize, Ordering::SeqCst);
        unsafe { System.realloc(p, l, new) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

fn ok(s: mtcut_status) {
    assert_eq!(s, MTCUT_STATUS_OK);
}

/// One session of a host: a mesh read, a model built (with a progress callback), saved,
/// loaded, extracted three ways, a frontier moved, an extraction cut and its components
/// taken apart; failures on the way; everything freed. Returns the fewest tets of the
/// meshes it made, to size what a leaked handle would hold at least.
fn session(dir: &std::path::Path) -> usize {
    let path = CString::new(common::data("pinion-coarse.node").to_str().unwrap()).unwrap();
    let saved = CString::new(dir.join("m.mt").to_str().unwrap()).unwrap();
    unsafe {
        let mut mesh = ptr::null_mut();
        ok(mtcut_mesh_read(path.as_ptr(), &mut mesh));
        let mut bo: mtcut_build_options = std::mem::zeroed();
        bo.struct_size = size_of::<mtcut_build_options>();
        ok(mtcut_build_options_default(&mut bo));
        let mut mt = ptr::null_mut();
        ok(mtcut_mt_build(mesh, &bo, &mut mt));
        ok(mtcut_mt_save(mt, saved.as_ptr()));
        let mut loaded = ptr::null_mut();
        ok(mtcut_mt_load(saved.as_ptr(), &mut loaded));
        let mut st = mtcut_mt_stats {
            struct_size: size_of::<mtcut_mt_stats>(),
            ..Default::default()
        };
        ok(mtcut_mt_statistics(loaded, &mut st));

        let mut eo: mtcut_extract_options = std::mem::zeroed();
        eo.struct_size = size_of::<mtcut_extract_options>();
        ok(mtcut_extract_options_default(&mut eo));
        eo.threshold = (st.min_error * st.max_error).sqrt();
        let mut extracted = ptr::null_mut();
        ok(mtcut_mt_extract(
            loaded,
            &eo,
            ptr::null_mut(),
            &mut extracted,
        ));
        let mut coarse = ptr::null_mut();
        ok(mtcut_mt_extract_threshold(mt, f64::INFINITY, &mut coarse));
        let mut frontier = ptr::null_mut();
        ok(mtcut_frontier_new(mt, &eo, &mut frontier));
        eo.focus = MTCUT_FOCUS_SPHERE;
        eo.focus_radius = 0.01;
        eo.focus_threshold = 0.0;
        ok(mtcut_frontier_update(frontier, &eo, ptr::null_mut()));
        eo.budget = 100;
        ok(mtcut_frontier_update(frontier, &eo, ptr::null_mut()));
        let mut from_frontier = ptr::null_mut();
        ok(mtcut_frontier_mesh(frontier, &mut from_frontier));
        mtcut_mt_free(mt); // before the frontier: it shares the model

        let (mut lo, mut hi) = ([0.0; 3], [0.0; 3]);
        ok(mtcut_mesh_bounding_box(
            extracted,
            lo.as_mut_ptr(),
            hi.as_mut_ptr(),
        ));
        let z = (lo[2] + hi[2]) / 2.0 + 1e-3;
        let tri = [-1e3, -1e3, z, 1e3, -1e3, z, 0.0, 1e3, z];
        let mut cs = mtcut_cut_stats {
            struct_size: size_of::<mtcut_cut_stats>(),
            ..Default::default()
        };
        ok(mtcut_mesh_cut(extracted, tri.as_ptr(), 3, &mut cs));
        let sweep = [
            [-1e3, 0.0, hi[2] + 1.0, 1e3, 0.0, hi[2] + 1.0],
            [-1e3, 0.0, z, 1e3, 0.0, z],
        ];
        ok(mtcut_mesh_scalpel_sweep(
            coarse,
            sweep[0].as_ptr(),
            sweep[1].as_ptr(),
            ptr::null(),
            &mut cs,
        ));
        let mut part = ptr::null_mut();
        ok(mtcut_mesh_extract_component(extracted, 1, &mut part));

        // A live model: moved, cut frontier first, its queue processed, copied out.
        let mut live = ptr::null_mut();
        ok(mtcut_live_new(loaded, ptr::null(), &mut live));
        let n = mtcut_live_vertex_count(live);
        let mut xyz = vec![0.0; 3 * n];
        ok(mtcut_live_copy_positions(live, xyz.as_mut_ptr(), n));
        for p in xyz.chunks_mut(3) {
            p[0] += 1e-3 * p[2];
        }
        ok(mtcut_live_set_positions(live, xyz.as_ptr(), n));
        ok(mtcut_live_cut(live, tri.as_ptr(), 3, ptr::null_mut()));
        let mut live_mesh = ptr::null_mut();
        ok(mtcut_live_mesh(live, &mut live_mesh));
        ok(mtcut_live_process_pending(live, 0, 0.0, ptr::null_mut()));
        let mut live_mt = ptr::null_mut();
        ok(mtcut_live_mt(live, &mut live_mt));
        mtcut_mt_free(live_mt);
        mtcut_live_free(live);

        // Failures allocate messages and scratch; they must not keep them.
        let mut none = ptr::null_mut();
        assert_ne!(
            mtcut_mesh_cut(extracted, tri.as_ptr(), 2, ptr::null_mut()),
            MTCUT_STATUS_OK
        );
        assert_ne!(
            mtcut_mt_extract_threshold(loaded, -1.0, &mut none),
            MTCUT_STATUS_OK
        );
        bo.min_quality = 5.0;
        let mut no_model = ptr::null_mut();
        assert_ne!(mtcut_mt_build(mesh, &bo, &mut no_model), MTCUT_STATUS_OK);

        let meshes = [mesh, extracted, coarse, from_frontier, part, live_mesh];
        let fewest = meshes
            .iter()
            .map(|&m| mtcut_mesh_tet_count(m))
            .min()
            .unwrap_or(0);
        for m in meshes {
            mtcut_mesh_free(m);
        }
        mtcut_frontier_free(frontier);
        mtcut_mt_free(loaded);
        fewest
    }
}

#[test]
fn every_handle_freed_leaves_the_heap_as_it_was() {
    let dir = common::scratch("ffi-leaks");
    // The first sessions set up what lives for the whole process (the thread pool, this
    // thread's error message buffer, lazily built statics).
    session(&dir);
    session(&dir);
    let settled = LIVE.load(Ordering::SeqCst);
    let (mut fewest, mut previous) = (0, settled);
    for k in 0..10 {
        fewest = session(&dir);
        let live = LIVE.load(Ordering::SeqCst);
        println!("after session {}: {:+} bytes", k + 3, live - previous);
        previous = live;
    }
    let grown = previous - settled;
    // A leaked handle repeats every session and holds at least its tets (16 bytes each)
    // and its vertices: more than 10 x 4 KiB here. What the thread pool frees lazily
    // (its queues' buffers go through epoch-based reclamation) shows as a few dozen bytes
    // coming and going between sessions; it stays far below that.
    let smallest_handle = 16 * fewest as isize;
    println!(
        "heap after 10 more sessions: {grown:+} bytes; the smallest mesh holds > {smallest_handle}"
    );
    assert!(
        smallest_handle > 4096,
        "the session's meshes are too small to tell"
    );
    assert!(
        grown < 4096,
        "the heap grew by {grown} bytes over 10 sessions: something is not freed"
    );
}
