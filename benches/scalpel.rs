//! Scalpel step latency (issue 7's benchmark, as far as it can be measured today): a blade
//! spanning fandisk's depth crosses it in 100 steps, each step cutting every level of the
//! MT with the area it swept ([`mtcut::cut::Scalpel`]); median and p99 latency of a step,
//! side by side with VTK's clip (`vtkTableBasedClipDataSet`, both sides, via
//! /usr/bin/python3 and scripts/vtk/cut_vtk_clip.py) of the whole finest fandisk mesh by
//! the blade's plane, in the same run.
//!
//! The targets are for the *time-critical* step (the current frontier first, the
//! rest of the MT queued), which is not built: the step measured here is the direct cut of
//! every level, so the comparison is the baseline the time-critical cut has to beat.
//!
//! `cargo bench --bench scalpel` prints one JSON object on stdout.

use mtcut::cut::{Blade, Scalpel};
use mtcut::geom::DVec3;
use mtcut::mt::{BuildOptions, Mt};
use serde_json::{Value, json};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

const STEPS: usize = 100;

fn percentile(sorted: &[f64], p: f64) -> f64 {
    let k = ((sorted.len() - 1) as f64 * p).round() as usize;
    sorted[k]
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let base = root.join("tests/data/fandisk");
    let (mesh, _) = mtcut::io::read_mesh(base.with_extension("node")).expect("fandisk");
    let (mt, _) = Mt::build(&mesh, &BuildOptions::DEFAULT).expect("build");
    let b = mesh.bbox();
    let (c, d) = (b.center(), b.max - b.min);
    let blade = |k: usize| -> Blade {
        let x = b.min.x - 0.01 * d.x + 1.02 * d.x * k as f64 / STEPS as f64;
        [
            DVec3::new(x, c.y + 0.013 * d.y, b.min.z - 0.1 * d.z),
            DVec3::new(x, c.y - 0.011 * d.y, b.max.z + 0.1 * d.z),
        ]
    };
    let mut scalpel = Scalpel::new(mt, blade(0)).expect("scalpel");
    let mut ms: Vec<f64> = Vec::new();
    let mut cells: Vec<usize> = Vec::new();
    // Per step: (query + split, DAG) milliseconds and fragments involved.
    let mut parts: Vec<(f64, f64, usize)> = Vec::new();
    for k in 1..=STEPS {
        let t = Instant::now();
        let step = scalpel.step(blade(k)).expect("step");
        let elapsed = t.elapsed().as_secs_f64() * 1e3;
        if step.tets_cut() > 0 {
            ms.push(elapsed);
            cells.push(step.tets_cut());
            let sum = |f: &dyn Fn(&mtcut::cut::MtCutStats) -> f64| {
                step.cuts.iter().map(f).sum::<f64>() * 1e3
            };
            parts.push((
                sum(&|s| s.time.query + s.time.split),
                sum(&|s| s.time.dag),
                step.cuts.iter().map(|s| s.fragments_involved).sum(),
            ));
        }
    }
    let valid = scalpel.mt().validate().is_valid();
    let components = scalpel.mt().nb_components();
    let mut sorted = ms.clone();
    sorted.sort_by(f64::total_cmp);
    let (median, p99) = (percentile(&sorted, 0.5), percentile(&sorted, 0.99));
    let mut cells_sorted = cells.clone();
    cells_sorted.sort_unstable();
    // VTK's clip of the whole finest mesh by the blade's plane (normal from the sweep).
    let p = [blade(0)[0], blade(0)[1], blade(1)[0]];
    let normal = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
    let vtk = Command::new("/usr/bin/python3")
        .arg(root.join("scripts/vtk/cut_vtk_clip.py"))
        .arg(&base)
        .args([c.x, c.y, c.z, normal.x, normal.y, normal.z].map(|x| x.to_string()))
        .arg("9")
        .output();
    let vtk_ms = match vtk {
        Ok(o) if o.status.success() => serde_json::from_slice::<Value>(&o.stdout)
            .ok()
            .and_then(|v| v["median_ms"].as_f64()),
        _ => None,
    };
    let ratio = |x: f64| vtk_ms.map(|v| x / v);
    let med = |f: &dyn Fn(&(f64, f64, usize)) -> f64| {
        let mut v: Vec<f64> = parts.iter().map(f).collect();
        v.sort_by(f64::total_cmp);
        percentile(&v, 0.5)
    };
    let last = parts.last().copied().unwrap_or_default();
    let report = json!({
        "mesh": "fandisk",
        "steps": STEPS,
        "steps_cutting": ms.len(),
        "tets_cut_per_step_median": percentile(&cells_sorted.iter().map(|&x| x as f64).collect::<Vec<_>>(), 0.5),
        "step_ms_median": median,
        "step_ms_p99": p99,
        "split_ms_median": med(&|p| p.0),
        "dag_ms_median": med(&|p| p.1),
        "fragments_involved_median": med(&|p| p.2 as f64),
        "last_step": {"split_ms": last.0, "dag_ms": last.1, "fragments_involved": last.2},
        "vtk_clip_whole_mesh_ms": vtk_ms,
        "step_median_over_vtk": ratio(median),
        "step_p99_over_vtk": ratio(p99),
        "targets": "time-critical step median <= 0.01x and p99 <= 0.03x VTK (not built: this is the direct step of every level)",
        "target_median_met": ratio(median).map(|r| r <= 0.01),
        "target_p99_met": ratio(p99).map(|r| r <= 0.03),
        "valid_after_last_step": valid,
        "components_after": components,
        "threads": rayon::current_num_threads(),
    });
    println!("{report}");
}
