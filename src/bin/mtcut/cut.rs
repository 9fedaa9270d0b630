//! `mtcut cut MESH --polygon "x,y,z;x,y,z;x,y,z[;...]" [--polygon ...]... [--scheme
//! lut|bielser17] -o OUT.vtu [--separate] [--json]`: cuts a plain mesh with planar convex
//! polygons, in the order given (paper §3–§4), and writes the result whole or one file
//! per connected component. A model (`.mt`, recognised as `info` does) is cut level by
//! level instead, see [`crate::cut_model`].
//!
//! Every polygon is parsed and checked before the mesh is read, and the result is checked
//! before anything is written, so a bad polygon or a failed cut writes nothing.

use crate::CliResult;
use crate::parse;
use mtcut::cut::{Components, CutOptions, CutStats, Cutter, Scheme};
use mtcut::geom::CutPolygon;
use mtcut::io::{read_mesh, write_mesh, write_meshes};
use mtcut::mesh::{Severity, TetId, TetMesh};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// How cut tets are replaced.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SchemeName {
    /// The paper's look-up tables: conforming, fewest tets.
    Lut,
    /// Bielser et al.'s 1:17 split, for comparison: not conforming (hanging vertices), so
    /// its output does not validate.
    Bielser17,
}

impl SchemeName {
    fn scheme(self) -> Scheme {
        match self {
            SchemeName::Lut => Scheme::Lut,
            SchemeName::Bielser17 => Scheme::Bielser17,
        }
    }
}

#[derive(clap::Args)]
pub struct Args {
    /// Input mesh (.vtu, .node/.ele, .mesh) or model (.mt).
    pub mesh: PathBuf,
    /// A planar convex cutting polygon: its corners in order, "x,y,z;x,y,z;x,y,z[;...]".
    /// Repeat to cut several times; polygons are applied in the order given and counted
    /// from 0 in messages.
    #[arg(
        long,
        value_name = "POINTS",
        required = true,
        allow_hyphen_values = true
    )]
    pub polygon: Vec<String>,
    /// Replacement scheme for cut tets (a model is always cut with the tables).
    #[arg(long, value_enum, default_value = "lut")]
    pub scheme: SchemeName,
    /// The mesh to write (.vtu or .node/.ele); with --separate, the name the parts'
    /// names are made from (OUT-0.vtu, OUT-1.vtu, ...). For a model: the cut model (.mt).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Write each connected component to its own file (OUT-0, OUT-1, ... in the order of
    /// their lowest tet) instead of one file. Meshes only.
    #[arg(long)]
    pub separate: bool,
    /// The polygons are the consecutive sweeps of a scalpel (each begins where the last
    /// ended): cut with the scalpel's options, each continuing the crack of the earlier
    /// ones (cracks continued, face points at the smallest margin, almost no snapping).
    /// Meshes only (`mtcut scalpel` moves a blade through a model).
    #[arg(long)]
    pub scalpel: bool,
    /// Print one JSON object on stdout instead of text.
    #[arg(long)]
    pub json: bool,
}

/// How messages name polygon `i` (0-based) of `n`: "polygon 1 (2nd of 3, "…")".
pub fn polygon_name(i: usize, n: usize, text: &str) -> String {
    let k = i + 1;
    let suffix = match (k % 10, k % 100) {
        (1, r) if r != 11 => "st",
        (2, r) if r != 12 => "nd",
        (3, r) if r != 13 => "rd",
        _ => "th",
    };
    // A long text (thousands of corners) is quoted by its start: the message stays a line.
    const QUOTED: usize = 80;
    let quoted = match text.char_indices().nth(QUOTED) {
        Some((end, _)) => format!("{}...\" ({} characters)", &text[..end], text.len()),
        None => format!("{text}\""),
    };
    format!("polygon {i} ({k}{suffix} of {n}, \"{quoted})")
}

/// The checked polygons; an error names the polygon, its text and the problem. Text that
/// is not numbers is bad usage (exit code 2, as for any unparsable option); numbers that
/// make no polygon (collinear, beyond 1e50) are bad input.
pub fn polygons(texts: &[String]) -> Result<Vec<CutPolygon>, Box<dyn std::error::Error>> {
    let n = texts.len();
    texts
        .iter()
        .enumerate()
        .map(|(i, text)| {
            let name = || polygon_name(i, n, text);
            let corners =
                parse::corners(text).map_err(|e| crate::Usage(format!("{}: {e}", name())))?;
            CutPolygon::new(&corners).map_err(|e| format!("{}: {e}", name()).into())
        })
        .collect()
}

/// `OUT-k.ext` for part `k` of `OUT.ext`.
pub fn part_path(output: &Path, k: usize) -> PathBuf {
    let stem = output
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = match output.extension() {
        Some(ext) => format!("{stem}-{k}.{}", ext.to_string_lossy()),
        None => format!("{stem}-{k}"),
    };
    output.with_file_name(name)
}

/// A cut mesh's parts: the components, their sizes and volumes.
pub struct Parts {
    pub components: Components,
    pub tets: Vec<usize>,
    pub volumes: Vec<f64>,
}

impl Parts {
    pub fn of(mesh: &TetMesh) -> Parts {
        // Through shared vertices: a cut mesh is valid, where this finds the components
        // through faces at a fraction of the cost.
        let components = Components::through_vertices(mesh);
        let mut volumes = vec![0.0; components.count];
        for (t, &l) in components.label.iter().enumerate() {
            volumes[l as usize] += mesh.tet_volume(TetId::from_usize(t));
        }
        Parts {
            tets: components.sizes(),
            volumes,
            components,
        }
    }
}

pub fn run(args: Args) -> CliResult {
    if crate::info::is_model(&args.mesh) {
        return crate::cut_model::run(args);
    }
    parse::mesh_output(&args.output)?;
    let polys = polygons(&args.polygon)?;
    let t_read = Instant::now();
    let (mesh, _report) = read_mesh(&args.mesh)?;
    let read_seconds = t_read.elapsed().as_secs_f64();
    let (tets_before, vertices_before, volume_before) =
        (mesh.nb_tets(), mesh.nb_vertices(), mesh.volume());
    let base = if args.scalpel {
        CutOptions::SCALPEL
    } else {
        CutOptions::DEFAULT
    };
    let options = base.with_scheme(args.scheme.scheme());
    let mut cutter = Cutter::new(mesh, options)?;
    let prepare_seconds = cutter.build_time().as_secs_f64();
    let mut stats: Vec<CutStats> = Vec::with_capacity(polys.len());
    for (i, p) in polys.iter().enumerate() {
        let r = cutter.cut(p).map_err(|e| {
            let name = polygon_name(i, polys.len(), &args.polygon[i]);
            format!("{name}: {e} (nothing written)")
        })?;
        // A cut through vertices and along faces cuts no tet but separates them (copies).
        if r.stats.tets_cut == 0 && r.stats.vertices_added == 0 && !args.json {
            eprintln!("mtcut: warning: polygon {i} does not cut the mesh");
        }
        stats.push(r.stats);
    }
    let mesh = cutter.into_mesh();
    let validation = mesh.validate();
    let problems = validation.lines(Severity::Error);
    // The tables keep the mesh conforming; the 1:17 scheme does not by design (the
    // paper's objection to it), so only a table cut that breaks an invariant is an error.
    if !problems.is_empty() && args.scheme == SchemeName::Lut {
        return Err(format!(
            "internal error: the cut left an invalid mesh, nothing written ({})",
            problems.join("; ")
        )
        .into());
    }
    let parts = Parts::of(&mesh);
    let t_write = Instant::now();
    let outputs: Vec<PathBuf> = if args.separate {
        let meshes = parts.components.extract_all(&mesh);
        let paths: Vec<PathBuf> = (0..meshes.len())
            .map(|k| part_path(&args.output, k))
            .collect();
        // All parts or none: a failure on one leaves none of them behind.
        let files: Vec<_> = paths.iter().map(PathBuf::as_path).zip(&meshes).collect();
        write_meshes(&files)?;
        paths
    } else {
        write_mesh(&args.output, &mesh)?;
        vec![args.output.clone()]
    };
    let write_seconds = t_write.elapsed().as_secs_f64();
    let cut_seconds: f64 = stats.iter().map(|s| s.time.cut).sum();
    if args.json {
        let cuts: Vec<Value> = stats
            .iter()
            .zip(&polys)
            .enumerate()
            .map(|(i, (s, p))| cut_json(s.to_json(), i, p))
            .collect();
        let j = json!({
            "input": args.mesh.display().to_string(),
            "scheme": options.scheme.name(),
            "input_tets": tets_before,
            "input_vertices": vertices_before,
            "volume_before": volume_before,
            "cuts": cuts,
            "tets": mesh.nb_tets(),
            "vertices": mesh.nb_vertices(),
            "volume": mesh.volume(),
            "components": parts.components.count,
            "component_tets": parts.tets,
            "component_volumes": parts.volumes,
            "valid": problems.is_empty(),
            "problems": problems,
            "outputs": outputs.iter().map(|p| p.display().to_string()).collect::<Vec<_>>(),
            "seconds": {
                "read": read_seconds,
                "prepare": prepare_seconds,
                "cut": cut_seconds,
                "write": write_seconds,
            },
        });
        out!("{j}");
        return Ok(());
    }
    out!(
        "cut        {} with {} polygon(s), {} scheme",
        args.mesh.display(),
        polys.len(),
        options.scheme.name()
    );
    for (i, s) in stats.iter().enumerate() {
        out!(
            "polygon {i}  {} tets cut ({} tested), {} created, {} vertices added, {:.4} s",
            s.tets_cut,
            s.tets_tested,
            s.tets_created,
            s.vertices_added,
            s.time.cut
        );
    }
    out!(
        "result     {} tets, {} vertices; volume {} (before {})",
        mesh.nb_tets(),
        mesh.nb_vertices(),
        crate::number(mesh.volume()),
        crate::number(volume_before)
    );
    // The first few parts; --json lists them all.
    const SHOWN: usize = 8;
    let mut sizes: Vec<String> = parts
        .tets
        .iter()
        .zip(&parts.volumes)
        .take(SHOWN)
        .map(|(n, v)| format!("{n} tets (volume {v:.6e})"))
        .collect();
    if parts.components.count > SHOWN {
        sizes.push(format!("{} more", parts.components.count - SHOWN));
    }
    out!(
        "components {}: {}",
        parts.components.count,
        sizes.join(", ")
    );
    if !problems.is_empty() {
        out!(
            "valid      no, as expected of the 1:17 scheme ({})",
            problems.join("; ")
        );
    }
    let names: Vec<String> = outputs.iter().map(|p| p.display().to_string()).collect();
    out!("wrote      {}", names.join(", "));
    out!(
        "time       cut {cut_seconds:.4} s (read {read_seconds:.3} s, prepare {prepare_seconds:.3} s, write {write_seconds:.3} s)"
    );
    Ok(())
}

/// One polygon's statistics in `--json`, with the polygon's index and corners.
pub fn cut_json(mut stats: Value, index: usize, polygon: &CutPolygon) -> Value {
    if let Some(o) = stats.as_object_mut() {
        o.insert("polygon".into(), json!(index));
        let points: Vec<[f64; 3]> = polygon.points().iter().map(|q| q.to_array()).collect();
        o.insert("points".into(), json!(points));
    }
    stats
}
