//! What a C caller pays per `mtcut_mt_cut`, side by side with the Rust cut of the same
//! polygons in the same run: the model of fandisk (and of fandisk-1m when its mesh is
//! found) is loaded through the C ABI and cut by [`CALLS`] small squares, one call each,
//! moving across the body; the same squares cut one [`MtCutter`] made of the same model.
//! Each call asks for the cut's statistics (and must cut the cells the Rust cut does). The
//! first call prepares the model for cutting (kept in the handle for the next calls), as
//! [`MtCutter::new`] does, so it is reported apart.
//!
//! `cargo bench --bench ffi_calls -- [LARGE_DIR]` (default /work/large; fandisk-1m is
//! skipped with a note when `LARGE_DIR/fandisk-1m.node` is missing). Prints one JSON object
//! on stdout.

use mtcut::cut::MtCutter;
use mtcut::ffi::{MTCUT_STATUS_OK, mtcut_cut_stats, mtcut_mt_cut, mtcut_mt_free, mtcut_mt_load};
use mtcut::geom::{Aabb, CutPolygon, DVec3};
use mtcut::mt::{BuildOptions, Mt};
use serde_json::{Value, json};
use std::ffi::CString;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Cuts per model.
const CALLS: usize = 12;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Squares of half-size 2% of the diagonal across the body's middle, in planes x = const.
fn squares(b: &Aabb) -> Vec<Vec<DVec3>> {
    let d = b.max - b.min;
    let r = 0.02 * d.length();
    let (y, z) = (b.min.y + 0.5 * d.y, b.min.z + 0.5 * d.z);
    (0..CALLS)
        .map(|k| {
            let x = b.min.x + d.x * (0.2 + 0.6 * k as f64 / CALLS as f64);
            vec![
                DVec3::new(x, y - r, z - r),
                DVec3::new(x, y + r, z - r),
                DVec3::new(x, y + r, z + r),
                DVec3::new(x, y - r, z + r),
            ]
        })
        .collect()
}

fn measure(name: &str, mt: Mt, scratch: &Path) -> Value {
    let b = Aabb::from_points(mt.positions());
    let path = scratch.join(format!("{name}.mt"));
    mt.save(&path).expect("save");
    let squares = squares(&b);

    let c_path = CString::new(path.to_str().expect("a UTF-8 path")).expect("no NUL");
    let mut handle = std::ptr::null_mut();
    // SAFETY: a NUL-terminated path and a writable handle pointer.
    assert_eq!(
        unsafe { mtcut_mt_load(c_path.as_ptr(), &mut handle) },
        MTCUT_STATUS_OK
    );
    // Each call asks for the cut's statistics, as a host reporting them would.
    let (mut calls, mut c_cells) = (Vec::new(), Vec::new());
    for square in &squares {
        let xyz: Vec<f64> = square.iter().flat_map(|p| p.to_array()).collect();
        let mut stats = mtcut_cut_stats {
            struct_size: size_of::<mtcut_cut_stats>(),
            ..Default::default()
        };
        let t = Instant::now();
        // SAFETY: a live handle, 3 x 4 readable doubles, a writable sized stats struct.
        let status = unsafe { mtcut_mt_cut(handle, xyz.as_ptr(), 4, &mut stats) };
        calls.push(t.elapsed().as_secs_f64() * 1e3);
        assert_eq!(status, MTCUT_STATUS_OK);
        c_cells.push(stats.tets_cut);
    }
    // SAFETY: the live handle, not used after.
    unsafe { mtcut_mt_free(handle) };

    let t = Instant::now();
    let mut cutter = MtCutter::new(mt, MtCutter::DEFAULT_OPTIONS).expect("options");
    let prepare = t.elapsed().as_secs_f64() * 1e3;
    let mut rust = Vec::new();
    let mut cells = Vec::new();
    for square in &squares {
        let polygon = CutPolygon::new(square).expect("a square");
        let t = Instant::now();
        let stats = cutter.cut(&polygon).expect("cut");
        rust.push(t.elapsed().as_secs_f64() * 1e3);
        cells.push(stats.tets_cut);
    }
    assert_eq!(
        c_cells, cells,
        "{name}: the C calls cut other cells than the Rust cut"
    );
    let later = median(calls[1..].to_vec());
    let rust_median = median(rust.clone());
    eprintln!(
        "{name}: first call {:.1} ms (Rust prepare {prepare:.1} + cut {:.1}), later calls \
         median {later:.2} ms, Rust cut median {rust_median:.2} ms",
        calls[0], rust[0]
    );
    json!({
        "mesh": name,
        "pool_tets": cutter.mt().nb_tets(),
        "calls": CALLS,
        "cells_per_cut": cells,
        "c_call_ms": calls,
        "c_first_call_ms": calls[0],
        "c_later_calls_median_ms": later,
        "rust_prepare_ms": prepare,
        "rust_cut_ms": rust,
        "rust_cut_median_ms": rust_median,
        "later_calls_over_rust": later / rust_median,
    })
}

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let large = std::env::args()
        .skip(1)
        .find(|a| !a.starts_with("--"))
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/work/large"));
    let scratch = std::env::temp_dir().join(format!("mtcut-ffi-calls-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).expect("scratch folder");
    let mut rows = Vec::new();
    let mut notes = Vec::new();
    for (name, base) in [
        ("fandisk", root.join("tests/data/fandisk")),
        ("fandisk-1m", large.join("fandisk-1m")),
    ] {
        let node = base.with_extension("node");
        if !node.exists() {
            notes.push(format!("{name} skipped: {} not found", node.display()));
            continue;
        }
        eprintln!("{name}: building its MT ...");
        let (mesh, _) = mtcut::io::read_mesh(&node).expect("mesh");
        let (mt, _) = Mt::build(&mesh, &BuildOptions::DEFAULT).expect("build");
        drop(mesh);
        rows.push(measure(name, mt, &scratch));
    }
    let _ = std::fs::remove_dir_all(&scratch);
    println!(
        "{}",
        serde_json::to_string_pretty(&json!({ "models": rows, "notes": notes })).expect("json")
    );
}
