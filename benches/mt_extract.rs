//! Extraction benchmark: from-scratch extraction throughput (output tets per second) at the
//! finest, a middle and the coarsest resolution; incremental extraction after moving a
//! focus by 5 % of the bounding-box diagonal, against from-scratch extraction of the same
//! request. Prints one JSON object.
//!
//! `cargo bench --bench mt_extract -- [LARGE_DIR] [--skip-large]` (fandisk-1m.node from
//! LARGE_DIR, default /work/large).

use mtcut::geom::DVec3;
use mtcut::mesh::{FragmentId, TetMesh, VertexId};
use mtcut::mt::{BuildOptions, ExtractOptions, Frontier, Mt, Region};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::time::Instant;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn time<T>(f: impl FnOnce() -> T) -> (f64, T) {
    let t = Instant::now();
    let r = f();
    (t.elapsed().as_secs_f64(), r)
}

fn median_error(mt: &Mt) -> f64 {
    let mut e: Vec<f64> = (0..mt.nb_fragments())
        .map(|f| mt.fragment_error(FragmentId::from_usize(f)))
        .filter(|e| e.is_finite() && *e > 0.0)
        .collect();
    e.sort_by(f64::total_cmp);
    e[e.len() / 2]
}

fn bench(name: &str, mesh: &TetMesh, runs: usize) -> Value {
    let (build_seconds, built) = time(|| Mt::build(mesh, &BuildOptions::DEFAULT));
    let mt = match built {
        Ok((mt, _)) => mt,
        Err(e) => return json!({"mesh": name, "error": e.to_string()}),
    };
    let mid = median_error(&mt);
    let mut scratch = Vec::new();
    for (label, options) in [
        ("finest", ExtractOptions::FINEST),
        ("middle", ExtractOptions::threshold(mid)),
        ("coarsest", ExtractOptions::COARSEST),
    ] {
        let mut secs = Vec::new();
        let mut tets = 0;
        for _ in 0..runs {
            let (s, e) = time(|| mt.extract(&options));
            tets = e.map(|e| e.stats.tets).unwrap_or(0);
            secs.push(s);
        }
        let s = median(secs);
        scratch.push(json!({
            "level": label,
            "tets": tets,
            "seconds": s,
            "output_tets_per_second": tets as f64 / s,
        }));
    }
    // Incremental: a focus sphere (full resolution inside, the median error outside)
    // moved back and forth by 5 % of the bounding-box diagonal, for two sphere sizes.
    let incremental: Vec<Value> = [0.05, 0.1]
        .iter()
        .map(|&radius| focus_moves(&mt, mesh, mid, radius, runs))
        .collect();
    json!({
        "mesh": name,
        "input_tets": mesh.nb_tets(),
        "build_seconds": build_seconds,
        "from_scratch": scratch,
        "incremental_focus_moves": incremental,
    })
}

/// Moves a focus sphere of `radius` (fraction of the diagonal) back and forth by 5 % of the
/// diagonal; medians of the incremental update, of the update followed by writing the mesh
/// out, and of from-scratch extraction of the same request.
fn focus_moves(mt: &Mt, mesh: &TetMesh, outside: f64, radius: f64, runs: usize) -> Value {
    let bbox = mesh.bbox();
    let diag = bbox.diagonal();
    let target = bbox.min + bbox.extent() * DVec3::new(0.3, 0.4, 0.5);
    let start = (0..mesh.nb_vertices())
        .map(|v| mesh.position(VertexId::from_usize(v)))
        .min_by(|a, b| (*a - target).length().total_cmp(&(*b - target).length()))
        .unwrap_or(target);
    let step = DVec3::new(1.0, 1.0, 0.0).normalize() * 0.05 * diag;
    let request = |k: usize| {
        let center = start + step * (k % 2) as f64;
        ExtractOptions::threshold(outside).with_focus(
            Region::Sphere {
                center,
                radius: radius * diag,
            },
            0.0,
        )
    };
    let mut frontier = match Frontier::new(mt, &request(0)) {
        Ok(f) => f,
        Err(e) => return json!({"error": e.to_string()}),
    };
    let (mut inc, mut inc_mesh, mut full) = (Vec::new(), Vec::new(), Vec::new());
    let (mut changed, mut tets, mut agree) = (Vec::new(), 0, true);
    for k in 1..=2 * runs.max(5) {
        let r = request(k);
        let (s, u) = time(|| frontier.update(mt, &r));
        let (s2, _) = time(|| frontier.to_extraction(mt));
        let (s3, e) = time(|| mt.extract(&r));
        if let (Ok(u), Ok(e)) = (u, e) {
            agree &= frontier.nb_tets() == e.stats.tets;
            changed.push((u.tets_added + u.tets_removed) as f64);
            tets = e.stats.tets;
        }
        inc.push(s);
        inc_mesh.push(s + s2);
        full.push(s3);
    }
    let (inc, inc_mesh, full) = (median(inc), median(inc_mesh), median(full));
    json!({
        "focus_radius_over_diagonal": radius,
        "move_over_diagonal": 0.05,
        "tets": tets,
        "tets_changed_median": median(changed),
        "update_seconds": inc,
        "update_and_mesh_seconds": inc_mesh,
        "from_scratch_seconds": full,
        "speedup_update": full / inc,
        "speedup_update_and_mesh": full / inc_mesh,
        "same_tet_count_as_scratch": agree,
    })
}

fn main() {
    let mut large = PathBuf::from("/work/large");
    let mut skip_large = false;
    for a in std::env::args().skip(1) {
        match a.as_str() {
            "--skip-large" => skip_large = true,
            "--bench" => {}
            other => large = PathBuf::from(other),
        }
    }
    let mut out = Vec::new();
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut inputs: Vec<(String, PathBuf, usize)> = ["fandisk", "pinion", "liver"]
        .iter()
        .map(|n| (n.to_string(), repo.join(format!("tests/data/{n}.node")), 21))
        .collect();
    if !skip_large {
        inputs.push(("fandisk-1m".into(), large.join("fandisk-1m.node"), 5));
    }
    for (name, path, runs) in inputs {
        match mtcut::io::read_mesh(&path) {
            Ok((mesh, _)) => out.push(bench(&name, &mesh, runs)),
            Err(e) => out.push(json!({"mesh": name, "error": e.to_string()})),
        }
    }
    let best_rate = out
        .iter()
        .flat_map(|m| m["from_scratch"].as_array().cloned().unwrap_or_default())
        .filter_map(|x| x["output_tets_per_second"].as_f64())
        .fold(0.0, f64::max);
    let speedups: Vec<f64> = out
        .iter()
        .flat_map(|m| {
            m["incremental_focus_moves"]
                .as_array()
                .cloned()
                .unwrap_or_default()
        })
        .filter_map(|x| x["speedup_update"].as_f64())
        .collect();
    let worst_speedup = speedups.iter().copied().fold(f64::INFINITY, f64::min);
    let report = json!({
        "threads": rayon::current_num_threads(),
        "loadavg": std::fs::read_to_string("/proc/loadavg").unwrap_or_default().trim(),
        "meshes": out,
        "best_output_tets_per_second": best_rate,
        "target_10m_tets_per_second_met": best_rate >= 1e7,
        "worst_incremental_speedup": worst_speedup,
        "target_incremental_5x_met": worst_speedup >= 5.0,
    });
    println!(
        "{}",
        serde_json::to_string_pretty(&report).unwrap_or_default()
    );
}
