//! `mtcut cut MODEL.mt --polygon ... [--polygon ...]... -o OUT.mt [--json]`: cuts every
//! level of a Multi-Tessellation and its DAG (paper §3) with planar convex polygons, in
//! the order given, and writes the cut model. A body cut straight through becomes
//! independent components (`mtcut extract --component K` reads one).
//!
//! The MT is validated before the first cut and after each one ([`Mt::validate`], which is
//! exhaustive): a broken model must never be written, and the MT cut has known failures
//! (a blade continuing a crack in its own plane, see `mtcut::cut::MtCutter`'s limits). The
//! first failing polygon is named with the first violation, and nothing is written.

use crate::CliResult;
use crate::cut::{Args, SchemeName, cut_json, polygon_name, polygons};
use crate::parse;
use mtcut::cut::{MtCutStats, MtCutter};
use mtcut::mt::{Mt, MtValidationReport};
use serde_json::{Value, json};
use std::time::Instant;

/// The first violation of a failed validation, for one line of an error message.
fn first_violation(report: &MtValidationReport) -> String {
    match report.violations.first() {
        Some(v) => format!(
            "{} × {:?}, first: {}",
            v.count,
            v.kind,
            v.examples.first().map_or("(no example)", String::as_str)
        ),
        None => "no violation".to_string(),
    }
}

pub fn run(args: Args) -> CliResult {
    if args.scheme == SchemeName::Bielser17 {
        return Err(format!(
            "{}: a model is cut with the look-up tables only (--scheme bielser17 does not \
             conform across tets, which the levels of an MT need); nothing written",
            args.mesh.display()
        )
        .into());
    }
    if args.scalpel {
        return Err(format!(
            "{}: --scalpel cuts a mesh; to move a scalpel through a model use `mtcut \
             scalpel MODEL.mt --path PATH.json`; nothing written",
            args.mesh.display()
        )
        .into());
    }
    if args.separate {
        return Err(format!(
            "{}: --separate writes meshes, but a cut model is written whole as one .mt; \
             extract each part with `mtcut extract OUT.mt --component K`; nothing written",
            args.mesh.display()
        )
        .into());
    }
    parse::model_output(&args.output)?;
    let polys = polygons(&args.polygon)?;
    let t_load = Instant::now();
    // Loading validates the model: the cuts never start from a broken one.
    let mt = Mt::load(&args.mesh)?;
    let load_seconds = t_load.elapsed().as_secs_f64();
    let mut validate_seconds = 0.0;
    let (components_before, vertices_before) = (mt.nb_components(), mt.nb_vertices());
    let mut cutter = MtCutter::new(mt, MtCutter::DEFAULT_OPTIONS)?;
    let mut stats: Vec<MtCutStats> = Vec::with_capacity(polys.len());
    for (i, p) in polys.iter().enumerate() {
        let name = || polygon_name(i, polys.len(), &args.polygon[i]);
        let s = cutter
            .cut(p)
            .map_err(|e| format!("{}: {e} (nothing written)", name()))?;
        let t_validate = Instant::now();
        let report = cutter.mt().validate();
        validate_seconds += t_validate.elapsed().as_secs_f64();
        if !report.is_valid() {
            return Err(format!(
                "{}: the MT cut left an invalid model ({}); nothing written",
                name(),
                first_violation(&report)
            )
            .into());
        }
        // A cut through vertices and along faces cuts no tet but separates them (copies).
        if s.tets_cut == 0 && s.vertices_added == 0 && !args.json {
            eprintln!("mtcut: warning: polygon {i} does not cut the model");
        }
        if s.moved_to_plane && !args.json {
            eprintln!(
                "mtcut: note: polygon {i} lay close to an earlier cut's plane (within {:e} of \
                 the model's diagonal): it was cut in that plane",
                mtcut::geom::PLANE_SNAP
            );
        }
        stats.push(s);
    }
    let mt = cutter.into_mt();
    let t_write = Instant::now();
    mt.save(&args.output)?;
    let write_seconds = t_write.elapsed().as_secs_f64();
    let components = mt.nb_components();
    let cut_seconds: f64 = stats.iter().map(|s| s.time.total).sum();
    if args.json {
        let cuts: Vec<Value> = stats
            .iter()
            .zip(&polys)
            .enumerate()
            .map(|(i, (s, p))| cut_json(s.to_json(), i, p))
            .collect();
        let j = json!({
            "input": args.mesh.display().to_string(),
            "kind": "mt",
            "input_components": components_before,
            "input_vertices": vertices_before,
            "cuts": cuts,
            "vertices": mt.nb_vertices(),
            "fragments": mt.nb_fragments(),
            "components": components,
            "valid": true,
            "output": args.output.display().to_string(),
            "seconds": {
                "load": load_seconds,
                "cut": cut_seconds,
                "validate": validate_seconds,
                "write": write_seconds,
            },
        });
        out!("{j}");
        return Ok(());
    }
    out!(
        "cut        model {} with {} polygon(s), every level",
        args.mesh.display(),
        polys.len()
    );
    for (i, s) in stats.iter().enumerate() {
        out!(
            "polygon {i}  {} fragments involved ({} split), {} tets cut, {} created, {} \
             vertices added; {} component(s); {:.4} s (split {:.4} s, DAG {:.4} s)",
            s.fragments_involved,
            s.fragments_split,
            s.tets_cut,
            s.tets_created,
            s.vertices_added,
            s.components,
            s.time.total,
            s.time.split,
            s.time.dag
        );
    }
    out!(
        "result     {} fragments, {} vertices, {} component(s) (before {}); valid after \
         every cut",
        mt.nb_fragments(),
        mt.nb_vertices(),
        components,
        components_before
    );
    out!("wrote      {}", args.output.display());
    out!(
        "time       cut {cut_seconds:.4} s (load {load_seconds:.3} s, validate \
         {validate_seconds:.3} s, write {write_seconds:.3} s)"
    );
    Ok(())
}
