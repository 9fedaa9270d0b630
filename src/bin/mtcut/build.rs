//! `mtcut build MESH -o MODEL.mt [--error volume|boundary|quality] [--json]`: the
//! multiresolution model of a mesh (paper §2), with a progress bar on stderr.

use crate::CliResult;
use crate::parse;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use mtcut::io::read_mesh;
use mtcut::mt::{BuildOptions, BuildProgress, BuildStats, ErrorMetric, Mt};
use serde_json::json;
use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The per-tet error a build ranks collapses by.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum ErrorName {
    /// Proportional to volume (the paper's).
    Volume,
    /// Deviation of boundary faces from the input's boundary surface, combined with size.
    Boundary,
    /// Element quality (mean ratio).
    Quality,
}

impl ErrorName {
    fn metric(self) -> ErrorMetric {
        let name = match self {
            ErrorName::Volume => "volume",
            ErrorName::Boundary => "boundary",
            ErrorName::Quality => "quality",
        };
        ErrorMetric::from_name(name).expect("the three built-in metrics have these names")
    }
}

#[derive(clap::Args)]
pub struct Args {
    /// Input mesh (.vtu, .node/.ele, .mesh).
    mesh: PathBuf,
    /// The model to write (.mt).
    #[arg(short, long)]
    output: PathBuf,
    /// Per-tet error metric.
    #[arg(long, value_enum, default_value = "volume")]
    error: ErrorName,
    /// How far any level's boundary may stray from the input's, relative to the input's
    /// bounding-box diagonal (default: the library's, 0.005).
    #[arg(long, value_name = "REL", allow_hyphen_values = true, value_parser = parse::tolerance)]
    boundary_tolerance: Option<f64>,
    /// Stop simplifying when the mesh has at most this many tets (default: until no legal
    /// collapse is left).
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = parse::count)]
    target_tets: Option<usize>,
    /// Print one JSON object on stdout instead of text (no progress bar).
    #[arg(long)]
    json: bool,
    /// No progress bar.
    #[arg(short, long)]
    quiet: bool,
}

/// A progress bar on stderr, or a hidden one when stderr is not a terminal or `quiet`.
pub fn progress_bar(quiet: bool) -> ProgressBar {
    let target = if quiet || !std::io::stderr().is_terminal() {
        ProgressDrawTarget::hidden()
    } else {
        ProgressDrawTarget::stderr()
    };
    let bar = ProgressBar::with_draw_target(Some(1000), target);
    bar.set_style(
        ProgressStyle::with_template("{spinner} building [{wide_bar}] {percent:>3}% {msg}")
            .expect("a constant, valid template")
            .progress_chars("=> "),
    );
    bar
}

/// Builds the MT of `mesh`, showing progress on `bar` (cleared when the build ends).
pub fn build_with_bar(
    mesh: &mtcut::mesh::TetMesh,
    options: &BuildOptions,
    bar: &ProgressBar,
) -> Result<(Mt, BuildStats), mtcut::mt::BuildError> {
    let result = Mt::build_with_progress(mesh, options, &mut |p: &BuildProgress| {
        bar.set_position((p.fraction.clamp(0.0, 1.0) * 1000.0) as u64);
        bar.set_message(format!("{} tets, {} fragments", p.live_tets, p.fragments));
        ControlFlow::Continue(())
    });
    bar.finish_and_clear();
    result
}

fn file_size(path: &Path) -> u64 {
    std::fs::metadata(path).map(|m| m.len()).unwrap_or(0)
}

pub fn run(args: Args) -> CliResult {
    parse::model_output(&args.output)?;
    let t_read = Instant::now();
    let (mesh, _report) = read_mesh(&args.mesh)?;
    let read_seconds = t_read.elapsed().as_secs_f64();
    let mut options = BuildOptions::DEFAULT
        .with_error(args.error.metric())
        .with_target_tets(args.target_tets);
    if let Some(t) = args.boundary_tolerance {
        options = options.with_boundary_tolerance(t);
    }
    let bar = progress_bar(args.quiet || args.json);
    let (mt, stats) = build_with_bar(&mesh, &options, &bar)
        .map_err(|e| format!("{}: {e}", args.mesh.display()))?;
    let t_save = Instant::now();
    mt.save(&args.output)?;
    let save_seconds = t_save.elapsed().as_secs_f64();
    let bytes = file_size(&args.output);
    if args.json {
        let mut j = stats.to_json();
        if let Some(o) = j.as_object_mut() {
            o.insert("input".into(), json!(args.mesh.display().to_string()));
            o.insert("output".into(), json!(args.output.display().to_string()));
            o.insert("error_metric".into(), json!(mt.info().error_metric));
            o.insert(
                "boundary_tolerance".into(),
                json!(options.boundary_tolerance.relative),
            );
            o.insert("file_bytes".into(), json!(bytes));
            o.insert("read_seconds".into(), json!(read_seconds));
            o.insert("save_seconds".into(), json!(save_seconds));
        }
        out!("{j}");
    } else {
        print_text(&args, &mt, &stats, bytes, read_seconds, save_seconds)?;
    }
    Ok(())
}

fn print_text(
    args: &Args,
    mt: &Mt,
    s: &BuildStats,
    bytes: u64,
    read_seconds: f64,
    save_seconds: f64,
) -> crate::CliResult {
    out!(
        "built      {} from {} ({} error)",
        args.output.display(),
        args.mesh.display(),
        mt.info().error_metric
    );
    out!(
        "input      {} tets, {} vertices",
        s.input_tets,
        s.input_vertices
    );
    out!(
        "fragments  {} ({} collapses in {} rounds, plus root and drain)",
        s.fragments,
        s.collapses,
        s.rounds
    );
    out!(
        "MT tets    {} over all levels (plus {} ghost tets), {} arcs",
        s.pool_tets,
        s.ghost_tets,
        s.arcs
    );
    out!("DAG depth  {}", s.dag_depth);
    out!(
        "coarsest   {} tets, {} vertices ({:.1}% of the input tets)",
        s.coarsest_tets,
        s.coarsest_vertices,
        100.0 * s.coarsest_tets as f64 / s.input_tets.max(1) as f64
    );
    out!(
        "size       {:.1} bytes per input tet in memory, {} bytes on disk",
        s.heap_bytes as f64 / s.input_tets.max(1) as f64,
        bytes
    );
    out!(
        "time       build {:.3} s (read {:.3} s, save {:.3} s)",
        s.seconds,
        read_seconds,
        save_seconds
    );
    Ok(())
}
