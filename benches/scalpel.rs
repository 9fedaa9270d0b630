//! Scalpel step latency (issue 7's benchmark): a blade spanning fandisk's depth crosses it
//! in steps, side by side with VTK's clip (`vtkTableBasedClipDataSet`, both sides, via
//! /usr/bin/python3 and scripts/vtk/cut_vtk_clip.py) of the whole finest fandisk mesh by
//! the blade's plane, in the same run.
//!
//! * `time_critical`: [`LiveMt`] with its current mesh at the median fragment error; the
//!   blade crosses in [`TC_STEPS`] steps (about 100 current tets cut per step). Each step's
//!   frontier-first cut ([`LiveMt::cut`]) is timed, then the queued MT cut
//!   ([`LiveMt::process_pending`]), reported per fragment it involved. Once at rest, once
//!   with the body bent under the same blade (positions set before the sweep), once moving
//!   (positions set before every step, as a simulation's frame does: a rotation and a
//!   scaling that change from step to step, setting them timed apart), and once at rest
//!   with the queue processed only after the last step (`at_rest_queued`: no model cut
//!   between steps to empty the caches).
//! * `direct`: [`Scalpel`], every level of the MT cut at each of 100 steps (the paper's
//!   non-time-critical update, the baseline).
//!
//! * `vtk_clip_local`: for scale, not a target, VTK's clip (the same script) of what a
//!   step works on: the current tets whose boxes meet the middle step's polygon's box,
//!   just before that step, by its plane; each time-critical row divides its median step
//!   by it (`step_median_over_local_vtk`). Also VTK's clip of one of those tets alone: on
//!   this machine about as long (0.4 ms), VTK's cost per call rather than per cell.
//!
//! Targets (issue 7): frontier-first step median ≤ 0.01× and p99 ≤ 0.03× VTK's clip.
//!
//! `cargo bench --bench scalpel` prints one JSON object on stdout.

use mtcut::cut::{Blade, LiveMt, PendingBudget, Scalpel};
use mtcut::geom::{Aabb, DVec3, Tolerance, scalpel_sweep};
use mtcut::mesh::{Tet, TetMesh};
use mtcut::mt::{BuildOptions, ExtractOptions, Mt};
use serde_json::{Value, json};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

const STEPS: usize = 100;
/// Steps of the time-critical sweep: about 100 current tets cut per step.
const TC_STEPS: usize = 30;

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
    let c = b.center();
    let direct_blades = blade_at(&mesh, STEPS);
    let blade = |k: usize| direct_blades[k];
    let blades = blade_at(&mesh, TC_STEPS);
    let live_at_rest = time_critical(&mt, &blades, Body::Rest, true);
    let live_bent = time_critical(&mt, &blades, Body::Bent, true);
    let live_moving = time_critical(&mt, &blades, Body::Moving, true);
    let live_queued = time_critical(&mt, &blades, Body::Rest, false);
    let local = vtk_clip_local(root, &mt, &blades);
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
    let vtk_ms = vtk_clip(root, &base, c, normal, 9).and_then(|v| v["median_ms"].as_f64());
    let ratio = |x: f64| vtk_ms.map(|v| x / v);
    let local_ms = local["median_ms"].as_f64();
    let med = |f: &dyn Fn(&(f64, f64, usize)) -> f64| {
        let mut v: Vec<f64> = parts.iter().map(f).collect();
        v.sort_by(f64::total_cmp);
        percentile(&v, 0.5)
    };
    let last = parts.last().copied().unwrap_or_default();
    let tc = |v: &Value| {
        let mut v = v.clone();
        let m = v["step_ms_median"].as_f64().unwrap_or(f64::NAN);
        let p = v["step_ms_p99"].as_f64().unwrap_or(f64::NAN);
        v["step_median_over_vtk"] = json!(ratio(m));
        v["step_p99_over_vtk"] = json!(ratio(p));
        v["step_median_over_local_vtk"] = json!(local_ms.map(|l| m / l));
        v["target_median_met"] = json!(ratio(m).map(|r| r <= 0.01));
        v["target_p99_met"] = json!(ratio(p).map(|r| r <= 0.03));
        v
    };
    let report = json!({
        "mesh": "fandisk",
        "vtk_clip_whole_mesh_ms": vtk_ms,
        "vtk_clip_local": local,
        "targets": "frontier-first step median <= 0.01x and p99 <= 0.03x VTK's whole-mesh clip",
        "time_critical": {
            "at_rest": tc(&live_at_rest),
            "bent": tc(&live_bent),
            "moving": tc(&live_moving),
            "at_rest_queued": tc(&live_queued),
        },
        "direct": json!({
        "steps": STEPS,
        "steps_cutting": ms.len(),
        "tets_cut_per_step_median": percentile(&cells_sorted.iter().map(|&x| x as f64).collect::<Vec<_>>(), 0.5),
        "step_ms_median": median,
        "step_ms_p99": p99,
        "split_ms_median": med(&|p| p.0),
        "dag_ms_median": med(&|p| p.1),
        "fragments_involved_median": med(&|p| p.2 as f64),
        "last_step": {"split_ms": last.0, "dag_ms": last.1, "fragments_involved": last.2},
        "step_median_over_vtk": ratio(median),
        "step_p99_over_vtk": ratio(p99),
        "valid_after_last_step": valid,
        "components_after": components,
        }),
        "threads": rayon::current_num_threads(),
    });
    println!("{report}");
}

/// VTK's clip of what a step works on, for scale (not a target): the tets of the current
/// mesh whose boxes meet the box of the sweep's middle polygon, just before the at-rest
/// sweep cuts it (the earlier steps cut, the queue not drained), clipped by that polygon's
/// plane with the same script as the whole mesh; and, to tell its cost per call from its
/// cost per cell, VTK's clip of the first of those tets the plane crosses, alone.
fn vtk_clip_local(root: &Path, mt: &Mt, blades: &[Blade]) -> Value {
    let mut live =
        LiveMt::new(mt.clone(), &median_resolution(mt), Scalpel::OPTIONS).expect("live model");
    let polygons: Vec<_> = blades
        .windows(2)
        .flat_map(|w| scalpel_sweep(w[0], w[1], Tolerance { relative: 1e-9 }).expect("sweep"))
        .collect();
    let middle = polygons.len() / 2;
    for polygon in &polygons[..middle] {
        live.cut(polygon).expect("frontier-first cut");
    }
    let polygon = &polygons[middle];
    let mesh = live.mesh();
    let reach = polygon.bbox();
    let corners = |t: &Tet| t.map(|v| mesh.position(v));
    let tets: Vec<Tet> = mesh
        .tets()
        .iter()
        .filter(|t| Aabb::from_points(&corners(t)).intersects(&reach))
        .copied()
        .collect();
    let (o, n) = (polygon.points()[0], polygon.normal());
    let crossed = tets.iter().find(|t| {
        let d = corners(t).map(|p| (p - o).dot(n));
        d.iter().any(|&x| x > 0.0) && d.iter().any(|&x| x < 0.0)
    });
    let clip = |tets: &[Tet], name: &str| {
        let base =
            std::env::temp_dir().join(format!("mtcut-scalpel-{name}-{}", std::process::id()));
        let out = write_tetgen(&base, mesh, tets)
            .ok()
            .and_then(|_| vtk_clip(root, &base, o, n, 51));
        for ext in ["node", "ele"] {
            let _ = std::fs::remove_file(base.with_extension(ext));
        }
        out
    };
    let local = clip(&tets, "local");
    let one = crossed.and_then(|t| clip(std::slice::from_ref(t), "one"));
    json!({
        "what": "VTK's clip of the current tets whose boxes meet the middle step's polygon's box, by its plane, and of one of them it crosses alone (for scale, not a target)",
        "cells": tets.len(),
        "cells_crossed": local.as_ref().map(|c| c["cells_crossed"].clone()),
        "median_ms": local.as_ref().map(|c| c["median_ms"].clone()),
        "one_crossed_tet_median_ms": one.as_ref().map(|c| c["median_ms"].clone()),
    })
}

/// VTK's clip (scripts/vtk/cut_vtk_clip.py, `repetitions` times) of the TetGen mesh
/// `base` by the plane through `origin` of normal `normal`: the script's JSON, or None when
/// it could not run.
fn vtk_clip(
    root: &Path,
    base: &Path,
    origin: DVec3,
    normal: DVec3,
    repetitions: usize,
) -> Option<Value> {
    let (o, n) = (origin, normal);
    let out = Command::new("/usr/bin/python3")
        .arg(root.join("scripts/vtk/cut_vtk_clip.py"))
        .arg(base)
        .args([o.x, o.y, o.z, n.x, n.y, n.z].map(|x| x.to_string()))
        .arg(repetitions.to_string())
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| serde_json::from_slice::<Value>(&out.stdout).ok())
        .flatten()
}

/// `tets` of `mesh` as TetGen files `base`.node and `base`.ele (their vertices renumbered
/// in order of use), which the VTK script reads. Written here rather than through
/// `TetMesh::submesh` and `mtcut::io::write_tetgen`: tets taken by their boxes need not
/// make a valid mesh (two may meet at an edge only), which `submesh` rejects.
fn write_tetgen(base: &Path, mesh: &TetMesh, tets: &[Tet]) -> std::io::Result<()> {
    let mut index = vec![u32::MAX; mesh.nb_vertices()];
    let mut used = Vec::new();
    let mut ele = format!("{} 4 0\n", tets.len());
    for (i, t) in tets.iter().enumerate() {
        let ids = t.map(|v| {
            if index[v.idx()] == u32::MAX {
                index[v.idx()] = used.len() as u32;
                used.push(mesh.position(v));
            }
            index[v.idx()]
        });
        ele += &format!("{i} {} {} {} {}\n", ids[0], ids[1], ids[2], ids[3]);
    }
    let mut node = format!("{} 3 0 0\n", used.len());
    for (i, p) in used.iter().enumerate() {
        node += &format!("{i} {:e} {:e} {:e}\n", p.x, p.y, p.z);
    }
    std::fs::write(base.with_extension("node"), node)?;
    std::fs::write(base.with_extension("ele"), ele)
}

/// The extraction threshold of the live models: the median fragment error.
fn median_resolution(mt: &Mt) -> ExtractOptions {
    let mut errors: Vec<f64> = (0..mt.nb_fragments())
        .map(|f| mt.fragment_error(mtcut::mesh::FragmentId::from_usize(f)))
        .filter(|e| e.is_finite() && *e > 0.0)
        .collect();
    errors.sort_by(f64::total_cmp);
    ExtractOptions::threshold(errors[errors.len() / 2])
}

/// The blade positions of a sweep across `mesh` in `steps` steps (the direct sweep's blade).
fn blade_at(mesh: &mtcut::mesh::TetMesh, steps: usize) -> Vec<Blade> {
    let b = mesh.bbox();
    let (c, d) = (b.center(), b.max - b.min);
    (0..=steps)
        .map(|k| {
            let x = b.min.x - 0.01 * d.x + 1.02 * d.x * k as f64 / steps as f64;
            [
                DVec3::new(x, c.y + 0.013 * d.y, b.min.z - 0.1 * d.z),
                DVec3::new(x, c.y - 0.011 * d.y, b.max.z + 0.1 * d.z),
            ]
        })
        .collect()
}

/// The time-critical sweep (see the module docs): per step the frontier-first latency,
/// then the queued work per fragment.
/// How the body lies while the blade crosses it.
#[derive(Clone, Copy, PartialEq)]
enum Body {
    Rest,
    /// Bent once, before the sweep.
    Bent,
    /// Moved before every step.
    Moving,
}

fn time_critical(mt: &Mt, blades: &[Blade], body: Body, drain_each_step: bool) -> Value {
    let mut live =
        LiveMt::new(mt.clone(), &median_resolution(mt), Scalpel::OPTIONS).expect("live model");
    let current_tets = live.mesh().nb_tets();
    if body == Body::Bent {
        // A bend of 0.5% of the diagonal (no tet inverted) under the same blade.
        let b = live.mesh().bbox();
        let diag = (b.max - b.min).length();
        let k = std::f64::consts::TAU / diag;
        let bend = |p: DVec3| {
            p + DVec3::new(
                0.005 * diag * (k * p.y).sin(),
                0.0,
                0.005 * diag * (k * p.x).cos(),
            )
        };
        let moved: Vec<DVec3> = live.rest_positions().iter().map(|&p| bend(p)).collect();
        live.set_positions(&moved).expect("bend");
    }
    let (mut step_ms, mut cells) = (Vec::new(), Vec::new());
    let (mut pending_ms, mut fragments, mut remeshed) = (0.0, 0usize, 0usize);
    let mut per_fragment_us: Vec<f64> = Vec::new();
    let mut set_ms: Vec<f64> = Vec::new();
    // A small rotation about the vertical axis and a scaling about the body's centre,
    // changing from step to step (affine: no tet inverted).
    let center = live.mesh().bbox().center();
    let motion = |k: usize, p: DVec3| {
        let (turn, scale) = (0.002 * (k % 7) as f64, 1.0 + 0.001 * (k % 5) as f64);
        let d = p - center;
        let (sin, cos) = turn.sin_cos();
        center + DVec3::new(cos * d.x - sin * d.y, sin * d.x + cos * d.y, d.z) * scale
    };
    let mut frame = 0;
    // The queued work, timed per fragment it involves.
    let mut drain = |live: &mut LiveMt| {
        let t = Instant::now();
        let r = live.process_pending(PendingBudget::All).expect("pending");
        let p = t.elapsed().as_secs_f64() * 1e3;
        pending_ms += p;
        fragments += r.fragments;
        remeshed += usize::from(r.remeshed);
        if r.fragments > 0 {
            per_fragment_us.push(p * 1e3 / r.fragments as f64);
        }
    };
    for w in blades.windows(2) {
        for polygon in scalpel_sweep(w[0], w[1], Tolerance { relative: 1e-9 }).expect("sweep") {
            if body == Body::Moving {
                frame += 1;
                let moved: Vec<DVec3> = live
                    .rest_positions()
                    .iter()
                    .map(|&p| motion(frame, p))
                    .collect();
                let t = Instant::now();
                live.set_positions(&moved).expect("move");
                set_ms.push(t.elapsed().as_secs_f64() * 1e3);
            }
            let t = Instant::now();
            let cut = live.cut(&polygon).expect("frontier-first cut");
            let ms = t.elapsed().as_secs_f64() * 1e3;
            if cut.stats.tets_cut > 0 {
                step_ms.push(ms);
                cells.push(cut.stats.tets_cut as f64);
            }
            if drain_each_step {
                drain(&mut live);
            }
        }
    }
    drain(&mut live);
    let valid = live.mesh().validate().is_valid() && live.mt().validate().is_valid();
    let sorted = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v
    };
    let (step_ms, cells, per_fragment_us) =
        (sorted(step_ms), sorted(cells), sorted(per_fragment_us));
    let set_ms = sorted(set_ms);
    json!({
        "steps": blades.len() - 1,
        "steps_cutting": step_ms.len(),
        "current_tets_before": current_tets,
        "current_tets_cut_per_step_median": percentile(&cells, 0.5),
        "step_ms_median": percentile(&step_ms, 0.5),
        "step_ms_p99": percentile(&step_ms, 0.99),
        "pending_ms_total": pending_ms,
        "pending_fragments_total": fragments,
        "pending_us_per_fragment_median": percentile(&per_fragment_us, 0.5),
        "pending_us_per_fragment_overall": pending_ms * 1e3 / fragments.max(1) as f64,
        "remeshed_steps": remeshed,
        "set_positions_ms_median": (!set_ms.is_empty()).then(|| percentile(&set_ms, 0.5)),
        "valid_after_last_step": valid,
        "components_after": live.mt().nb_components(),
    })
}
