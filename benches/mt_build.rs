//! Build benchmark: MT build time and input tets per second on the shared meshes and on
//! fandisk-1m, side by side with TetGen making fandisk-1m from fandisk.off in the same run;
//! MT memory per input tet. Prints one JSON object.
//!
//! `cargo bench --bench mt_build -- [LARGE_DIR] [--off PATH] [--script PATH] [--skip-large]`
//!
//! * `LARGE_DIR`: where fandisk-1m.node/.ele are (default /work/large). If missing they
//!   are generated there with `--script` (default /work/shared/data/make-large.sh).
//! * `--off`: the fandisk surface TetGen meshes (default /work/shared/data/fandisk.off);
//!   it is copied to a temporary directory and meshed with `tetgen -pq1.414a3.3e-7Q`, the
//!   command that made fandisk-1m.

use mtcut::mt::{BuildOptions, BuildStats, Mt};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

fn repo(p: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(p)
}

/// CPU seconds (user + system, all threads) this process has used so far, from
/// /proc/self/stat (clock ticks of 1/100 s, the Linux default); `None` elsewhere.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which may contain spaces) start after the last ')'.
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

fn loadavg() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .unwrap_or_default()
        .trim()
        .to_string()
}

/// Builds `path`'s mesh `runs` times; the statistics of the fastest run.
fn bench_build(name: &str, path: &Path, runs: usize) -> Value {
    let t = Instant::now();
    let (mesh, _) = match mtcut::io::read_mesh(path) {
        Ok(m) => m,
        Err(e) => return json!({"mesh": name, "error": e.to_string()}),
    };
    let read = t.elapsed().as_secs_f64();
    let mut best: Option<(f64, Option<f64>, BuildStats, usize, usize)> = None;
    for _ in 0..runs {
        let cpu = cpu_seconds();
        let t = Instant::now();
        let (mt, stats) = match Mt::build(&mesh, &BuildOptions::DEFAULT) {
            Ok(r) => r,
            Err(e) => return json!({"mesh": name, "error": e.to_string()}),
        };
        let s = t.elapsed().as_secs_f64();
        let cpu = cpu.zip(cpu_seconds()).map(|(a, b)| b - a);
        if best.as_ref().is_none_or(|b| s < b.0) {
            best = Some((s, cpu, stats, mt.heap_bytes(), mt.summary().coarsest_tets));
        }
    }
    let Some((seconds, cpu, stats, bytes, coarsest)) = best else {
        return json!({"mesh": name, "error": "no run"});
    };
    json!({
        "mesh": name,
        "input_tets": stats.input_tets,
        "input_vertices": stats.input_vertices,
        "read_seconds": read,
        "runs": runs,
        "build_seconds": seconds,
        "build_cpu_seconds": cpu,
        "input_tets_per_second": stats.input_tets as f64 / seconds,
        "mt_heap_bytes": bytes,
        "mt_bytes_per_input_tet": bytes as f64 / stats.input_tets as f64,
        "coarsest_tets": coarsest,
        "coarsest_fraction": coarsest as f64 / stats.input_tets as f64,
        "stats": stats.to_json(),
    })
}

/// Runs TetGen on a copy of `off` in a temporary directory; wall seconds and tets made.
fn bench_tetgen(off: &Path) -> Value {
    let dir = std::env::temp_dir().join(format!("mtcut-bench-tetgen-{}", std::process::id()));
    if let Err(e) = std::fs::create_dir_all(&dir) {
        return json!({"error": e.to_string()});
    }
    let copy = dir.join("fandisk.off");
    if let Err(e) = std::fs::copy(off, &copy) {
        return json!({"error": format!("{}: {e}", off.display())});
    }
    let args = ["-pq1.414a3.3e-7Q", "fandisk.off"];
    // Through /usr/bin/time when present, for TetGen's CPU seconds too.
    let timed = Path::new("/usr/bin/time").exists();
    let t = Instant::now();
    let out = if timed {
        Command::new("/usr/bin/time")
            .args(["-f", "%U %S", "tetgen"])
            .args(args)
            .current_dir(&dir)
            .output()
    } else {
        Command::new("tetgen").args(args).current_dir(&dir).output()
    };
    let seconds = t.elapsed().as_secs_f64();
    let result = match out {
        Ok(o) if o.status.success() => {
            let tets = std::fs::read_to_string(dir.join("fandisk.1.ele"))
                .ok()
                .and_then(|s| {
                    s.split_whitespace()
                        .next()
                        .and_then(|x| x.parse::<u64>().ok())
                });
            let cpu = timed
                .then(|| {
                    let err = String::from_utf8_lossy(&o.stderr);
                    let last = err.lines().last()?.to_string();
                    let v: Vec<f64> = last
                        .split_whitespace()
                        .filter_map(|x| x.parse().ok())
                        .collect();
                    (v.len() == 2).then(|| v[0] + v[1])
                })
                .flatten();
            json!({
                "command": format!("tetgen {}", args.join(" ")),
                "seconds": seconds,
                "cpu_seconds": cpu,
                "tets": tets,
            })
        }
        Ok(o) => json!({"error": format!("tetgen failed: {}", String::from_utf8_lossy(&o.stderr))}),
        Err(e) => json!({"error": format!("tetgen not runnable: {e}")}),
    };
    let _ = std::fs::remove_dir_all(&dir);
    result
}

fn main() {
    let mut large = PathBuf::from("/work/large");
    let mut off = PathBuf::from("/work/shared/data/fandisk.off");
    let mut script = PathBuf::from("/work/shared/data/make-large.sh");
    let mut skip_large = false;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--off" => off = args.next().map(PathBuf::from).unwrap_or(off),
            "--script" => script = args.next().map(PathBuf::from).unwrap_or(script),
            "--skip-large" => skip_large = true,
            "--bench" => {}
            other => large = PathBuf::from(other),
        }
    }
    let mut meshes = Vec::new();
    for name in ["fandisk", "pinion", "liver"] {
        meshes.push(bench_build(
            name,
            &repo(&format!("tests/data/{name}.node")),
            3,
        ));
    }
    let mut report = json!({
        "threads": rayon::current_num_threads(),
        "loadavg_before": loadavg(),
    });
    if !skip_large {
        let node = large.join("fandisk-1m.node");
        if !node.exists() {
            let status = Command::new(&script).arg(&large).status();
            report["generated_large"] = json!(format!(
                "{} {}: {status:?}",
                script.display(),
                large.display()
            ));
        }
        let ours = bench_build("fandisk-1m", &node, 1);
        let tetgen = bench_tetgen(&off);
        if let (Some(a), Some(b)) = (ours["build_seconds"].as_f64(), tetgen["seconds"].as_f64()) {
            report["fandisk_1m_build_over_tetgen"] = json!(a / b);
            report["target_build_le_tetgen_met"] = json!(a <= b);
        }
        if let (Some(a), Some(b)) = (
            ours["build_cpu_seconds"].as_f64(),
            tetgen["cpu_seconds"].as_f64(),
        ) {
            report["fandisk_1m_build_cpu_over_tetgen_cpu"] = json!(a / b);
        }
        report["tetgen_fandisk_1m"] = tetgen;
        meshes.push(ours);
    }
    let worst_memory = meshes
        .iter()
        .filter_map(|m| m["mt_bytes_per_input_tet"].as_f64())
        .fold(0.0, f64::max);
    report["meshes"] = Value::Array(meshes);
    report["worst_mt_bytes_per_input_tet"] = json!(worst_memory);
    report["target_memory_le_100_met"] = json!(worst_memory <= 100.0);
    report["loadavg_after"] = json!(loadavg());
    println!(
        "{}",
        serde_json::to_string_pretty(&report).unwrap_or_default()
    );
}
