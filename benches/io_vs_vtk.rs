//! `.vtu` write and read, mtcut against VTK 9.1, on fandisk-1m (about 1M tets).
//!
//!     cargo bench --bench io_vs_vtk -- DIR [REPEATS]
//!
//! DIR holds fandisk-1m.node/.ele; they are generated there with
//! ../shared/data/make-large.sh when missing. REPEATS rounds (default 3) each time every
//! step once, ours and VTK's in turn, and the minimum over rounds is kept. VTK's times come
//! from `scripts/vtk/bench_vtk.py`, measured inside Python (interpreter start-up
//! excluded), in the same run on the same mesh: VTK writes in ParaView's default mode
//! (appended raw, VTK's default zlib compression) and reads that file back.
//! `ours_validate_s` is `TetMesh::from_arrays` alone on the same arrays (it includes
//! copying them); `ours_read_without_validation_s` is the rest of our read. Prints one
//! JSON object: all times in seconds, and the ratios ours / VTK (< 1: ours faster).

use mtcut::io::{VtuOptions, parse_vtu, read_mesh, write_vtu};
use mtcut::mesh::TetMesh;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

fn best<T>(repeats: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..repeats {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        last = Some(r);
    }
    (best, last.expect("at least one repeat"))
}

/// Every round's time of each step, in seconds.
#[derive(Default)]
struct Times {
    write: Vec<f64>,
    read: Vec<f64>,
    read_vtk_file: Vec<f64>,
    validate: Vec<f64>,
    vtk_write: Vec<f64>,
    vtk_read: Vec<f64>,
    vtk_read_ours: Vec<f64>,
}

fn read_vtu_file(path: &Path) -> TetMesh {
    let bytes = std::fs::read(path).expect("read file");
    parse_vtu(&bytes, path).unwrap_or_else(|e| panic!("{e}")).0
}

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    let dir = PathBuf::from(args.first().map_or("/work/large", String::as_str));
    let repeats: usize = args
        .get(1)
        .map_or(3, |r| r.parse().expect("REPEATS is a number"));
    let node = dir.join("fandisk-1m.node");
    if !node.exists() {
        let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/make-large.sh");
        eprintln!("generating {} with {}", node.display(), script.display());
        let ok = Command::new(&script)
            .arg(&dir)
            .status()
            .is_ok_and(|s| s.success());
        assert!(ok, "{} {} failed", script.display(), dir.display());
    }
    let scratch = std::env::temp_dir().join(format!("mtcut-bench-io-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).expect("scratch dir");
    let ours = scratch.join("ours.vtu");
    let theirs = scratch.join("vtk.vtu");

    let (tetgen_read_s, (mesh, _)) = best(1, || read_mesh(&node).expect("read fandisk-1m"));
    // The tets as a file gives them, for timing TetMesh::from_arrays (the validation part
    // of reading) on its own.
    let tets: Vec<[u32; 4]> = mesh.tets().iter().map(|t| t.map(|v| v.0)).collect();
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/vtk/bench_vtk.py");

    // Every round times each step once, ours and VTK's in turn, so that load changes on a
    // shared machine hit both sides alike; the minimum over rounds is kept.
    let mut t = Times::default();
    let mut vtk_version = serde_json::Value::Null;
    let mut vtk_file_bytes = serde_json::Value::Null;
    for _ in 0..repeats {
        t.write.push(
            best(1, || {
                write_vtu(&ours, &mesh, &VtuOptions::DEFAULT).expect("write")
            })
            .0,
        );
        let (s, back) = best(1, || read_vtu_file(&ours));
        assert_eq!(back.positions(), mesh.positions());
        assert_eq!(back.tets(), mesh.tets());
        t.read.push(s);
        let out = Command::new("/usr/bin/python3")
            .arg(&script)
            .arg(&ours)
            .arg(&theirs)
            .arg("1")
            .output()
            .expect("run VTK's Python");
        assert!(
            out.status.success(),
            "bench_vtk.py failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let vtk: serde_json::Value =
            serde_json::from_slice(&out.stdout).expect("JSON from bench_vtk.py");
        let f = |k: &str| vtk[k].as_f64().expect("VTK time");
        t.vtk_write.push(f("write_s"));
        t.vtk_read.push(f("read_s"));
        t.vtk_read_ours.push(f("read_ours_s"));
        vtk_version = vtk["vtk_version"].clone();
        vtk_file_bytes = vtk["file_bytes"].clone();
        let (s, from_vtk) = best(1, || read_vtu_file(&theirs));
        assert_eq!(from_vtk.positions(), mesh.positions());
        assert_eq!(from_vtk.tets(), mesh.tets());
        t.read_vtk_file.push(s);
        t.validate.push(
            best(1, || {
                TetMesh::from_arrays(mesh.positions().to_vec(), tets.clone()).expect("valid")
            })
            .0,
        );
    }
    let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
    let (write_s, read_s, read_vtk_file_s, validate_s) = (
        min(&t.write),
        min(&t.read),
        min(&t.read_vtk_file),
        min(&t.validate),
    );
    let (vtk_write_s, vtk_read_s, vtk_read_ours_s) =
        (min(&t.vtk_write), min(&t.vtk_read), min(&t.vtk_read_ours));
    let json = serde_json::json!({
        "mesh": "fandisk-1m",
        "vertices": mesh.nb_vertices(),
        "tets": mesh.nb_tets(),
        "threads": rayon::current_num_threads(),
        "repeats": repeats,
        "vtk_version": vtk_version,
        "tetgen_read_s": tetgen_read_s,
        "ours_write_s": write_s,
        "ours_file_bytes": std::fs::metadata(&ours).map(|m| m.len()).unwrap_or(0),
        "ours_read_s": read_s,
        "ours_validate_s": validate_s,
        "ours_read_without_validation_s": read_s - validate_s,
        "ours_read_vtk_file_s": read_vtk_file_s,
        "vtk_write_s": vtk_write_s,
        "vtk_file_bytes": vtk_file_bytes,
        "vtk_read_s": vtk_read_s,
        "vtk_read_ours_s": vtk_read_ours_s,
        "ratio_write": write_s / vtk_write_s,
        "ratio_read": read_s / vtk_read_s,
        "ratio_read_vtk_file": read_vtk_file_s / vtk_read_s,
        "ratio_read_without_validation": (read_s - validate_s) / vtk_read_s,
    });
    println!("{json}");
    let _ = std::fs::remove_dir_all(&scratch);
}
