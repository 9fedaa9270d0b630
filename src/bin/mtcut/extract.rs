//! `mtcut extract MODEL.mt (--threshold E | --budget N | --level finest|coarsest)
//! [--focus x,y,z,r --focus-threshold E2] [--component K] -o OUT.vtu [--json]`: a mesh at
//! the requested resolution (selective refinement over the DAG, paper §2), written with its
//! cell data (creating fragment, its error and level) and each vertex's MT vertex id. With
//! `--component K`, from independent component K of a cut model only (its fragments and
//! vertices renumbered from 0, so the ids are those of the component's own MT).
//!
//! The extracted mesh is validated before it is written, and an invalid one is refused
//! with its first problem: extractions of a cut model are not yet valid in every case.

use crate::CliResult;
use crate::parse::{self, Sphere};
use mtcut::cut::Components;
use mtcut::io::write_mesh;
use mtcut::mesh::Severity;
use mtcut::mt::{
    CELL_ERROR, CELL_FRAGMENT, CELL_LEVEL, ExtractOptions, Extraction, Mt, POINT_VERTEX, Region,
};
use serde_json::{Value, json};
use std::path::PathBuf;
use std::time::Instant;

/// A named level of detail.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Level {
    /// The full-resolution input mesh.
    Finest,
    /// The coarsest mesh the build reached.
    Coarsest,
}

/// Exactly one way of choosing the resolution.
#[derive(clap::Args, Debug)]
#[group(required = true, multiple = false)]
pub struct Resolution {
    /// Uniform error threshold: the coarsest mesh whose tets all have error ≤ E (a number
    /// ≥ 0; `inf` gives the coarsest mesh).
    #[arg(long, value_name = "E", allow_hyphen_values = true, value_parser = parse::threshold)]
    threshold: Option<f64>,
    /// At most N tets: the finest mesh within that budget.
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = parse::count)]
    budget: Option<usize>,
    /// A named level.
    #[arg(long, value_enum)]
    level: Option<Level>,
}

#[derive(clap::Args)]
pub struct Args {
    /// The model (.mt, written by `mtcut build`).
    model: PathBuf,
    #[command(flatten)]
    resolution: Resolution,
    /// A sphere (centre x,y,z and radius r) where --focus-threshold applies instead.
    #[arg(long, value_name = "x,y,z,r", allow_hyphen_values = true, value_parser = parse::sphere, requires = "focus_threshold")]
    focus: Option<Sphere>,
    /// The error threshold inside the --focus sphere (a number ≥ 0).
    #[arg(long, value_name = "E2", allow_hyphen_values = true, value_parser = parse::threshold, requires = "focus")]
    focus_threshold: Option<f64>,
    /// Extract from independent component K only (0-based; a model cut straight through
    /// has several, `mtcut info` counts them).
    #[arg(long, value_name = "K")]
    component: Option<usize>,
    /// The mesh to write: .vtu (data arrays by name), or .node/.ele (as unnamed attributes).
    #[arg(short, long)]
    output: PathBuf,
    /// Print one JSON object on stdout instead of text.
    #[arg(long)]
    json: bool,
}

impl Args {
    fn options(&self) -> ExtractOptions {
        let r = &self.resolution;
        let mut o = match (r.threshold, r.budget, r.level) {
            (Some(e), _, _) => ExtractOptions::threshold(e),
            (_, Some(n), _) => ExtractOptions::FINEST.with_budget(Some(n)),
            (_, _, Some(Level::Coarsest)) => ExtractOptions::COARSEST,
            _ => ExtractOptions::FINEST,
        };
        if let (Some(s), Some(e2)) = (self.focus, self.focus_threshold) {
            o = o.with_focus(
                Region::Sphere {
                    center: s.center,
                    radius: s.radius,
                },
                e2,
            );
        }
        o
    }

    /// The request as JSON (thresholds of +∞ print as the string "inf").
    fn request_json(&self) -> Value {
        let num = |x: f64| {
            if x.is_finite() {
                json!(x)
            } else {
                json!("inf")
            }
        };
        let r = &self.resolution;
        json!({
            "threshold": r.threshold.map(num),
            "budget": r.budget,
            "level": r.level.map(|l| match l {
                Level::Finest => "finest",
                Level::Coarsest => "coarsest",
            }),
            "focus": self.focus.map(|s| json!({
                "center": s.center.to_array(),
                "radius": s.radius,
            })),
            "focus_threshold": self.focus_threshold.map(num),
        })
    }
}

/// Checks the extraction before it is written: extractions of a cut model are not yet
/// valid in every case (focus regions after a cut, see `mtcut::cut::MtCutter`'s limits),
/// and a mesh that does not validate is never written (mtcut itself would not read it
/// back). The error names the first problem. When the model has several components (a
/// body cut through), each side of the crack is refined as its own component and the
/// parts may meet there at different resolutions: the error then says whether each part
/// on its own is valid, so that `--component K` gives it.
fn check(mt: &Mt, e: &Extraction) -> Result<(), String> {
    let problems = e.mesh.validate().lines(Severity::Error);
    if problems.is_empty() {
        return Ok(());
    }
    let not_valid = |what: String, problems: &[String]| {
        format!(
            "{what} is not valid ({} kind(s) of problem, first: {}); nothing written",
            problems.len(),
            problems.first().map_or("", String::as_str)
        )
    };
    let (count, of_fragment) = mt.fragment_components();
    let fragments = match e.mesh.cell_data.get(CELL_FRAGMENT) {
        Some(f) if count >= 2 => f,
        _ => return Err(not_valid("the extracted mesh".into(), &problems)),
    };
    let label = fragments
        .values
        .iter()
        .map(|&f| of_fragment[f as usize])
        .collect();
    let parts = Components { count, label };
    for k in 0..count {
        let part = parts.extract(&e.mesh, k).ok_or("component out of range")?;
        let part_problems = part.validate().lines(Severity::Error);
        if !part_problems.is_empty() {
            return Err(not_valid(
                format!("the part of component {k} in the extracted mesh"),
                &part_problems,
            ));
        }
    }
    Err(format!(
        "the model's {count} components meet along a cut at different resolutions in this \
         mesh, which as one mesh is not valid ({}); each part on its own is valid: extract \
         it with --component K (0 to {}); nothing written",
        problems.first().map_or("", String::as_str),
        count - 1
    ))
}

pub fn run(args: Args) -> CliResult {
    parse::mesh_output(&args.output)?;
    let t_load = Instant::now();
    let mt = Mt::load(&args.model)?;
    let components = mt.nb_components();
    let mt = match args.component {
        None => mt,
        Some(k) => mt.component(k).ok_or_else(|| {
            format!(
                "{}: component {k} out of range: the model has {components} component(s), numbered from 0",
                args.model.display()
            )
        })?,
    };
    let load_seconds = t_load.elapsed().as_secs_f64();
    let e = mt.extract(&args.options())?;
    let t_check = Instant::now();
    check(&mt, &e).map_err(|m| format!("{}: {m}", args.model.display()))?;
    let check_seconds = t_check.elapsed().as_secs_f64();
    let t_write = Instant::now();
    write_mesh(&args.output, &e.mesh)?;
    let write_seconds = t_write.elapsed().as_secs_f64();
    let volume = e.mesh.volume();
    if !e.stats.budget_met && !args.json {
        eprintln!(
            "mtcut: warning: even the coarsest mesh ({} tets) exceeds the budget; it was written anyway",
            e.stats.tets
        );
    }
    if args.json {
        let mut j = e.stats.to_json();
        if let Some(o) = j.as_object_mut() {
            o.insert("model".into(), json!(args.model.display().to_string()));
            o.insert("output".into(), json!(args.output.display().to_string()));
            o.insert("request".into(), args.request_json());
            o.insert("component".into(), json!(args.component));
            o.insert("components".into(), json!(components));
            o.insert("volume".into(), json!(volume));
            o.insert("input_tets".into(), json!(mt.info().input_tets));
            o.insert("load_seconds".into(), json!(load_seconds));
            o.insert("write_seconds".into(), json!(write_seconds));
            o.insert("check_seconds".into(), json!(check_seconds));
        }
        out!("{j}");
    } else {
        print_text(&args, &mt, &e, volume, load_seconds, write_seconds)?;
    }
    Ok(())
}

fn print_text(
    args: &Args,
    mt: &Mt,
    e: &Extraction,
    volume: f64,
    load_seconds: f64,
    write_seconds: f64,
) -> crate::CliResult {
    let s = &e.stats;
    match args.component {
        Some(k) => out!(
            "extracted  {} from component {k} of {}",
            args.output.display(),
            args.model.display()
        ),
        None => out!(
            "extracted  {} from {}",
            args.output.display(),
            args.model.display()
        ),
    }
    out!(
        "mesh       {} tets ({:.1}% of the finest {}), {} vertices, volume {}",
        s.tets,
        100.0 * s.tets as f64 / mt.info().input_tets.max(1) as f64,
        mt.info().input_tets,
        s.vertices,
        crate::number(volume)
    );
    out!(
        "error      up to {:e}; {} fragment(s) refined (their collapses not applied)",
        s.max_error,
        s.refined_fragments
    );
    out!("data       cells: {CELL_FRAGMENT}, {CELL_ERROR}, {CELL_LEVEL}; points: {POINT_VERTEX}");
    out!(
        "time       extract {:.4} s (load {:.3} s, write {:.3} s)",
        s.seconds,
        load_seconds,
        write_seconds
    );
    Ok(())
}
