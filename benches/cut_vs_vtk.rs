//! Our cut of a plain mesh (both sides, conforming tets) against VTK 9.1's
//! `vtkTableBasedClipDataSet` with GenerateClippedOutput on (both sides, tets and wedges),
//! same mesh and same plane, side by side in one run; prints one JSON object.
//!
//! `cargo bench --bench cut_vs_vtk -- [LARGE_DIR]`: fandisk and liver from tests/data, and
//! fandisk-1m from LARGE_DIR (default /work/large; generated there with
//! ../shared/data/make-large.sh when missing). Times are medians over repetitions; ours is
//! the whole `Cutter::cut` (query, classify, split, unglue) on a prepared mesh, whose
//! one-time preparation (vertex scales and tet hierarchy) is reported apart, as is counting
//! components. VTK's is `Update()` alone, timed inside the Python script.

use mtcut::cut::{CutOptions, Cutter};
use mtcut::geom::{CutPolygon, DVec3};
use mtcut::mesh::TetMesh;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

const PYTHON: &str = "/usr/bin/python3";

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn ensure_large(dir: &Path, root: &Path) -> Result<(), String> {
    if dir.join("fandisk-1m.ele").exists() {
        return Ok(());
    }
    let script = root.join("../shared/data/make-large.sh");
    eprintln!("generating the large meshes into {} ...", dir.display());
    let status = Command::new("bash")
        .arg(&script)
        .arg(dir)
        .status()
        .map_err(|e| format!("cannot run {}: {e}", script.display()))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("{} failed", script.display()))
    }
}

fn bench(name: &str, base: &Path, reps: usize, root: &Path) -> Result<Value, String> {
    let t = Instant::now();
    let (mesh, _) =
        mtcut::io::read_mesh(base.with_extension("node")).map_err(|e| format!("{name}: {e}"))?;
    let load_s = t.elapsed().as_secs_f64();
    let (origin, normal) = plane_of(&mesh);
    let u = normal.any_orthonormal_vector();
    let w = normal.cross(u);
    let r = 2.0 * mesh.bbox().diagonal();
    let polygon = CutPolygon::new(&[
        origin + (u + w) * r,
        origin + (w - u) * r,
        origin - (u + w) * r,
        origin + (u - w) * r,
    ])
    .map_err(|e| e.to_string())?;

    // Ours.
    let options = CutOptions::DEFAULT.with_count_components(false);
    let prepared = Cutter::new(mesh.clone(), options).map_err(|e| e.to_string())?;
    let build_ms = prepared.build_time().as_secs_f64() * 1e3;
    let (mut total, mut query, mut classify, mut split, mut unglue) =
        (vec![], vec![], vec![], vec![], vec![]);
    let mut last = None;
    for _ in 0..reps {
        let mut c = prepared.clone();
        // A simulation keeps its mesh's arrays between cuts; a fresh clone has none spare.
        c.reserve(mesh.nb_tets() / 4, mesh.nb_vertices() / 4);
        let t = Instant::now();
        let res = c.cut(&polygon).map_err(|e| e.to_string())?;
        total.push(t.elapsed().as_secs_f64() * 1e3);
        let s = &res.stats;
        query.push(s.time.query * 1e3);
        classify.push(s.time.classify * 1e3);
        split.push(s.time.split * 1e3);
        unglue.push(s.time.unglue * 1e3);
        last = Some(res.stats);
    }
    let stats = last.ok_or("no repetition")?;
    let mut with_components = prepared.clone();
    with_components
        .set_options(options.with_count_components(true))
        .map_err(|e| e.to_string())?;
    let components = with_components.cut(&polygon).map_err(|e| e.to_string())?;
    let ours_ms = median(total.clone());

    // VTK.
    let out = Command::new(PYTHON)
        .arg(root.join("scripts/vtk/cut_vtk_clip.py"))
        .arg(base)
        .args([origin.x, origin.y, origin.z, normal.x, normal.y, normal.z].map(|x| x.to_string()))
        .arg(reps.to_string())
        .output()
        .map_err(|e| format!("cannot run {PYTHON}: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "VTK script failed: {}",
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    let vtk: Value = serde_json::from_slice(&out.stdout).map_err(|e| e.to_string())?;
    let vtk_ms = vtk["median_ms"].as_f64().ok_or("no VTK time")?;
    Ok(json!({
        "mesh": name,
        "tets": mesh.nb_tets(),
        "vertices": mesh.nb_vertices(),
        "plane": { "origin": origin.to_array(), "normal": normal.to_array() },
        "repetitions": reps,
        "ours": {
            "cut_ms_median": ours_ms,
            "cut_ms_min": total.iter().copied().fold(f64::INFINITY, f64::min),
            "phases_ms_median": {
                "query": median(query),
                "classify": median(classify),
                "split": median(split),
                "unglue": median(unglue),
            },
            "tets_tested": stats.tets_tested,
            "tets_cut": stats.tets_cut,
            "tets_created": stats.tets_created,
            "vertices_added": stats.vertices_added,
            "us_per_cut_tet": ours_ms * 1e3 / stats.tets_cut.max(1) as f64,
            "build_ms": build_ms,
            "components": components.stats.components,
            "components_ms": components.stats.time.components * 1e3,
            "mesh_load_s": load_s,
        },
        "vtk": vtk,
        "ratio_ours_over_vtk": ours_ms / vtk_ms,
        "us_per_crossed_cell_vtk": vtk_ms * 1e3 / vtk["cells_crossed"].as_f64().unwrap_or(1.0).max(1.0),
    }))
}

/// The benchmark plane: through the centre of the bounding box, a fixed oblique normal.
fn plane_of(mesh: &TetMesh) -> (DVec3, DVec3) {
    (mesh.bbox().center(), DVec3::new(0.3, 0.5, 0.8).normalize())
}

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    let large = args
        .first()
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/work/large"));
    let mut cases: Vec<(String, PathBuf, usize)> = vec![
        ("fandisk".into(), root.join("tests/data/fandisk"), 41),
        ("liver".into(), root.join("tests/data/liver"), 41),
    ];
    let mut errors = Vec::new();
    match ensure_large(&large, &root) {
        Ok(()) => cases.push(("fandisk-1m".into(), large.join("fandisk-1m"), 9)),
        Err(e) => errors.push(e),
    }
    let mut results = Vec::new();
    for (name, base, reps) in cases {
        eprintln!("{name} ...");
        match bench(&name, &base, reps, &root) {
            Ok(v) => results.push(v),
            Err(e) => errors.push(e),
        }
    }
    let target = 0.1;
    let met = !results.is_empty()
        && errors.is_empty()
        && results.iter().all(|r| {
            r["ratio_ours_over_vtk"]
                .as_f64()
                .is_some_and(|x| x <= target)
        });
    let out = json!({
        "benchmark": "cut_vs_vtk",
        "target_ratio": target,
        "target_met": met,
        "results": results,
        "errors": errors,
    });
    println!("{}", serde_json::to_string_pretty(&out).unwrap_or_default());
}
