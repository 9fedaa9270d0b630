//! The paper's Table 2 (§6), reproduced: cuts of growing size on the MTs of fandisk,
//! pinion and liver, each applied to a fresh copy of the MT: fragments involved, input
//! cells (tets of any level replaced), cells the 1:17 scheme would create (17 each) and
//! cells the tables create, time to split the cells, time to update the DAG, total, and
//! total ÷ VTK's clip (`vtkTableBasedClipDataSet`, both sides, via /usr/bin/python3 and
//! scripts/vtk/cut_vtk_clip.py, as benches/cut_vs_vtk.rs) of the finest mesh by the same
//! plane, in the same run; and, apart, the time to make the cutter (`MtCutter::new`: vertex
//! scales, the fragments earlier cuts left cracked, the hierarchy over fragments, the open
//! form's per-tet links, room in the pool), paid once per cutter, not per cut. Then a
//! linear fit of total time against input cells, one cut on the fandisk-1m MT scaled from
//! fandisk's middle cut by the ratio of mean edge lengths (its MT having more levels, it
//! cuts about twice the cells), one sized to cut as many cells as fandisk's middle cut
//! (found by trial cuts, rescaling the square by the square root of the ratio of cells), and
//! a second cut continuing the first on the same cutter (a blade's next step).
//!
//! `cargo bench --bench table2 -- [LARGE_DIR]` (default /work/large; the 1m row is skipped
//! with a note when `LARGE_DIR/fandisk-1m.node` is missing). Prints one JSON object on
//! stdout and the table in markdown on stderr. Times are medians over repetitions, each on
//! a fresh copy of the MT (copying is not timed).

use mtcut::cut::{MtCutStats, MtCutter};
use mtcut::geom::{CutPolygon, DVec3, Sign, orient3d};
use mtcut::mesh::{TetId, TetMesh};
use mtcut::mt::{BuildOptions, Mt};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

const PYTHON: &str = "/usr/bin/python3";
/// Half-sizes of the square cuts, in bounding-box diagonals (the last goes through).
const SIZES: [f64; 5] = [0.04, 0.08, 0.15, 0.3, 2.0];
const REPS: usize = 5;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The benchmark plane, with a fixed oblique normal: through the centre of the bounding
/// box where a tet holds it, else through the centroid of the tet nearest to it (the
/// pinion's centre lies in its bore, where the two smallest squares met no tet).
fn plane_of(mesh: &TetMesh) -> (DVec3, DVec3) {
    let c = mesh.bbox().center();
    let normal = DVec3::new(0.3, 0.5, 0.8).normalize();
    let tets = (0..mesh.nb_tets()).map(|t| mesh.tet_positions(TetId::from_usize(t)));
    let holds = |[a, b, d, e]: [DVec3; 4]| {
        [
            orient3d(c, b, d, e),
            orient3d(a, c, d, e),
            orient3d(a, b, c, e),
            orient3d(a, b, d, c),
        ]
        .iter()
        .all(|&s| s != Sign::Negative)
    };
    if tets.clone().any(holds) {
        return (c, normal);
    }
    let centroid = |p: [DVec3; 4]| (p[0] + p[1] + p[2] + p[3]) * 0.25;
    let nearest = tets
        .map(centroid)
        .min_by(|p, q| p.distance_squared(c).total_cmp(&q.distance_squared(c)))
        .unwrap_or(c);
    (nearest, normal)
}

fn square(origin: DVec3, normal: DVec3, r: f64) -> CutPolygon {
    let u = normal.any_orthonormal_vector();
    let w = normal.cross(u);
    CutPolygon::new(&[
        origin + (u + w) * r,
        origin + (w - u) * r,
        origin - (u + w) * r,
        origin + (u - w) * r,
    ])
    .expect("a square is a valid polygon")
}

/// Median times (ms: making the cutter, then the cut's split, DAG and total) and the
/// statistics of one cut, each repetition on a fresh copy (cut first, untimed, by `before`
/// when given: the cut is then the cutter's second).
fn time_cut(
    mt: &Mt,
    before: Option<&CutPolygon>,
    polygon: &CutPolygon,
    reps: usize,
) -> Result<(MtCutStats, [f64; 4]), String> {
    let (mut prepare, mut split, mut dag, mut total) = (vec![], vec![], vec![], vec![]);
    let mut last = None;
    for _ in 0..reps {
        let copy = mt.clone();
        let start = Instant::now();
        let mut c = MtCutter::new(copy, MtCutter::DEFAULT_OPTIONS).map_err(|e| e.to_string())?;
        prepare.push(start.elapsed().as_secs_f64() * 1e3);
        if let Some(p) = before {
            c.cut(p).map_err(|e| e.to_string())?;
        }
        let s = c.cut(polygon).map_err(|e| e.to_string())?;
        split.push((s.time.query + s.time.split) * 1e3);
        dag.push(s.time.dag * 1e3);
        total.push(s.time.total * 1e3);
        last = Some(s);
    }
    let s = last.ok_or("no repetition")?;
    Ok((
        s,
        [median(prepare), median(split), median(dag), median(total)],
    ))
}

/// The square of `normal`'s plane through `origin` cutting about `want` input cells on
/// `mt` (within 5 %, after at most four trial cuts, each rescaling the half-size by the
/// square root of the ratio of cells: cells grow with the area cut), starting from
/// half-size `r`, which cut `got`; its half-size and [`time_cut`]'s statistics and times.
fn same_cells(
    mt: &Mt,
    origin: DVec3,
    normal: DVec3,
    mut r: f64,
    mut got: usize,
    want: usize,
) -> Result<(f64, MtCutStats, [f64; 4]), String> {
    for _ in 0..4 {
        if got.abs_diff(want) * 20 <= want {
            break;
        }
        r *= (want as f64 / got.max(1) as f64).sqrt();
        got = time_cut(mt, None, &square(origin, normal, r), 1)?
            .0
            .tets_cut;
    }
    let (s, times) = time_cut(mt, None, &square(origin, normal, r), 3)?;
    Ok((r, s, times))
}

fn vtk_clip_ms(base: &Path, origin: DVec3, normal: DVec3, root: &Path) -> Result<f64, String> {
    let out = Command::new(PYTHON)
        .arg(root.join("scripts/vtk/cut_vtk_clip.py"))
        .arg(base)
        .args([origin.x, origin.y, origin.z, normal.x, normal.y, normal.z].map(|x| x.to_string()))
        .arg("9")
        .output()
        .map_err(|e| format!("cannot run {PYTHON}: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "VTK script failed: {}",
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    let vtk: Value = serde_json::from_slice(&out.stdout).map_err(|e| e.to_string())?;
    vtk["median_ms"]
        .as_f64()
        .ok_or_else(|| "no VTK time".into())
}

fn load_and_build(base: &Path) -> Result<(TetMesh, Mt), String> {
    let (mesh, _) = mtcut::io::read_mesh(base.with_extension("node"))
        .map_err(|e| format!("{}: {e}", base.display()))?;
    let (mt, _) = Mt::build(&mesh, &BuildOptions::DEFAULT).map_err(|e| e.to_string())?;
    Ok((mesh, mt))
}

/// Least squares `y = a + b x`, with r².
fn fit(points: &[(f64, f64)]) -> (f64, f64, f64) {
    let n = points.len() as f64;
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
    let (mx, my) = (sx / n, sy / n);
    let sxx: f64 = points.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    let sxy: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let syy: f64 = points.iter().map(|(_, y)| (y - my) * (y - my)).sum();
    let b = sxy / sxx;
    (my - b * mx, b, sxy * sxy / (sxx * syy))
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
    let mut rows = Vec::new();
    let mut errors: Vec<String> = Vec::new();
    let mut md = String::from(
        "| mesh | cut (× diag) | fragments | input cells | created 1:17 | created tables | \
         tables/1:17 | split ms | DAG ms | total ms | total ÷ VTK clip | prepare ms |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut points = Vec::new();
    let mut fandisk_mid: Option<(usize, f64, usize)> = None;
    for name in ["fandisk", "pinion", "liver"] {
        eprintln!("{name} ...");
        let base = root.join("tests/data").join(name);
        let (mesh, mt) = match load_and_build(&base) {
            Ok(x) => x,
            Err(e) => {
                errors.push(e);
                continue;
            }
        };
        let (origin, normal) = plane_of(&mesh);
        let vtk_ms = match vtk_clip_ms(&base, origin, normal, &root) {
            Ok(v) => v,
            Err(e) => {
                errors.push(e);
                f64::NAN
            }
        };
        let diag = mesh.bbox().diagonal();
        for (k, &size) in SIZES.iter().enumerate() {
            let polygon = square(origin, normal, size * diag);
            let (s, [prepare, split, dag, total]) = match time_cut(&mt, None, &polygon, REPS) {
                Ok(x) => x,
                Err(e) => {
                    errors.push(format!("{name} size {size}: {e}"));
                    continue;
                }
            };
            let ratio = s.tets_created as f64 / s.tets_created_1_17.max(1) as f64;
            md.push_str(&format!(
                "| {name} | {size} | {} | {} | {} | {} | {ratio:.3} | {split:.1} | {dag:.1} | \
                 {total:.1} | {:.2} | {prepare:.1} |\n",
                s.fragments_involved,
                s.tets_cut,
                s.tets_created_1_17,
                s.tets_created,
                total / vtk_ms
            ));
            points.push((s.tets_cut as f64, total));
            if name == "fandisk" && k == 2 {
                fandisk_mid = Some((s.tets_cut, total, mesh.nb_tets()));
            }
            rows.push(json!({
                "mesh": name,
                "size_diagonals": size,
                "mt_tets": mt.nb_tets(),
                "mt_fragments": mt.nb_fragments(),
                "fragments_involved": s.fragments_involved,
                "fragments_split": s.fragments_split,
                "input_cells": s.tets_cut,
                "created_1_17": s.tets_created_1_17,
                "created_tables": s.tets_created,
                "tables_over_1_17": ratio,
                "split_ms": split,
                "dag_ms": dag,
                "total_ms": total,
                "vtk_clip_finest_ms": vtk_ms,
                "total_over_vtk": total / vtk_ms,
                "prepare_ms": prepare,
                "components_after": s.components,
                "stats": s.to_json(),
            }));
        }
    }
    let (a, b, r2) = if points.len() >= 2 {
        fit(&points)
    } else {
        (f64::NAN, f64::NAN, f64::NAN)
    };
    // The same-size cut on the fandisk-1m MT: the middle cut's polygon shrunk by the ratio
    // of mean edge lengths, so it cuts about as many cells.
    let mut large_row = Value::Null;
    let mut next_line = String::new();
    let node = large.join("fandisk-1m.node");
    match (fandisk_mid, node.exists()) {
        (Some((cells, ms, small_tets)), true) => {
            eprintln!("fandisk-1m (building its MT) ...");
            match load_and_build(&large.join("fandisk-1m")) {
                Ok((mesh, mt)) => {
                    let (origin, normal) = plane_of(&mesh);
                    let shrink = (small_tets as f64 / mesh.nb_tets() as f64).cbrt();
                    let r = SIZES[2] * shrink * mesh.bbox().diagonal();
                    let polygon = square(origin, normal, r);
                    // The next step of a blade: the same square moved along its plane by
                    // its width, continuing the first cut's crack, on the same cutter.
                    let next = square(
                        origin + normal.any_orthonormal_vector() * 2.0 * r,
                        normal,
                        r,
                    );
                    match time_cut(&mt, None, &polygon, 3) {
                        Ok((s, [prepare, split, dag, total])) => {
                            md.push_str(&format!(
                                "| fandisk-1m | {:.4} | {} | {} | {} | {} | {:.3} | {split:.1} | \
                                 {dag:.1} | {total:.1} | – | {prepare:.1} |\n",
                                SIZES[2] * shrink,
                                s.fragments_involved,
                                s.tets_cut,
                                s.tets_created_1_17,
                                s.tets_created,
                                s.tets_created as f64 / s.tets_created_1_17.max(1) as f64
                            ));
                            large_row = json!({
                                "mesh": "fandisk-1m",
                                "mt_tets": mt.nb_tets(),
                                "input_cells": s.tets_cut,
                                "split_ms": split,
                                "dag_ms": dag,
                                "total_ms": total,
                                "prepare_ms": prepare,
                                "fandisk_same_size_cells": cells,
                                "fandisk_same_size_ms": ms,
                                "ratio_over_fandisk": total / ms,
                                "per_cell_ratio_over_fandisk":
                                    (total / s.tets_cut.max(1) as f64) / (ms / cells.max(1) as f64),
                            });
                            match same_cells(&mt, origin, normal, r, s.tets_cut, cells) {
                                Ok((size, c, [_, split, dag, total])) => {
                                    let size = size / mesh.bbox().diagonal();
                                    md.push_str(&format!(
                                        "| fandisk-1m | {size:.4} | {} | {} | {} | {} | {:.3} | \
                                         {split:.1} | {dag:.1} | {total:.1} | – | – |\n",
                                        c.fragments_involved,
                                        c.tets_cut,
                                        c.tets_created_1_17,
                                        c.tets_created,
                                        c.tets_created as f64 / c.tets_created_1_17.max(1) as f64
                                    ));
                                    large_row["same_cells"] = json!({
                                        "size_diagonals": size,
                                        "input_cells": c.tets_cut,
                                        "split_ms": split,
                                        "dag_ms": dag,
                                        "total_ms": total,
                                        "ratio_over_fandisk": total / ms,
                                    });
                                }
                                Err(e) => errors.push(format!("fandisk-1m, same cells: {e}")),
                            }
                            match time_cut(&mt, Some(&polygon), &next, 3) {
                                Ok((n, [_, split, dag, next_total])) => {
                                    next_line = format!(
                                        "\nfandisk-1m, a second cut on the same cutter (the same square \
                                         moved by its width along its plane, continuing the first \
                                         crack): {} input cells, split {split:.1} ms, DAG {dag:.1} ms, \
                                         total {next_total:.1} ms (the first: {total:.1} ms)\n",
                                        n.tets_cut
                                    );
                                    large_row["next_cut"] = json!({
                                        "input_cells": n.tets_cut,
                                        "split_ms": split,
                                        "dag_ms": dag,
                                        "total_ms": next_total,
                                    });
                                }
                                Err(e) => errors.push(format!("fandisk-1m, second cut: {e}")),
                            }
                        }
                        Err(e) => errors.push(format!("fandisk-1m: {e}")),
                    }
                }
                Err(e) => errors.push(e),
            }
        }
        (_, false) => errors.push(format!("{} missing: 1m row skipped", node.display())),
        (None, true) => errors.push("no fandisk middle cut to compare with".into()),
    }
    md.push_str(&format!(
        "\nLinear fit of total time against input cells over all rows: total ≈ {a:.2} ms + \
         {:.3} µs × cells, r² = {r2:.3}\n",
        b * 1e3
    ));
    md.push_str(&next_line);
    eprintln!("\n{md}");
    let out = json!({
        "benchmark": "table2",
        "rows": rows,
        "fit_total_ms_vs_cells": { "intercept_ms": a, "slope_ms_per_cell": b, "r2": r2 },
        "fandisk_1m": large_row,
        "markdown": md,
        "errors": errors,
    });
    println!("{out}");
}
