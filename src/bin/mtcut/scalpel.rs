//! `mtcut scalpel MODEL.mt --path PATH.json -o DIR [--threshold E | --budget N]
//! [--save OUT.mt] [--json]`: a scalpel moved through a model in time steps
//! ([`mtcut::cut::Scalpel`]), each step cutting every level with the area the blade swept.
//! After each step the model is validated (exhaustively) and the current mesh (the finest,
//! or the chosen resolution) is checked (valid, the bodies a cut separated allowed to touch:
//! [`mtcut::cut::Components::validate_bodies`]) and written to `DIR/step-NNNN.vtu` (step 0:
//! before the first cut), listed with its time step in `DIR/scalpel.pvd` for ParaView.
//!
//! `PATH.json` is a list of blade positions, one per time step, each two 3-D points (the
//! blade's ends): `[[[x,y,z],[x,y,z]], [[x,y,z],[x,y,z]], ...]`, at least two.
//!
//! With `--time-critical` each step runs as a simulation would run it
//! ([`mtcut::cut::LiveMt`], paper §5): the current mesh is cut first (and written), then
//! the rest of the model; the statistics give both times.
//!
//! A sweep cut as two triangles (a blade that tilts as it moves) that the model refuses is
//! cut as another split of it first ([`Scalpel::step`]: along the other diagonal, each pair
//! in either order; `split` per step in `--json`, 0 for the first). With `--time-critical`
//! the current mesh is cut with the first split, and the model with the first it takes
//! ([`LiveMt::cut_sweep`]): when that is another, the current mesh is replaced by the
//! model's extraction (`other_splits` 1 and `remeshed` in the step's `--json`). A step the model
//! refuses (see [`mtcut::cut::scalpel`]'s limits: a path that turns or
//! tilts, whose sweeps meet at an angle, is refused by the MT cut where it would break the
//! coarser levels) or that leaves an invalid model or current mesh stops the run with an
//! error naming the step and the meshes written: the steps before it (time-critical, that
//! step's current mesh too, written before the model's cut) stay written and listed, and
//! `--save` writes nothing. With `--skip-refused` the run goes on instead: a new crack
//! is begun a tenth of the way into the refused step and cut from there
//! ([`Scalpel::step_after_gap`]; `gap` 0.1 for that step in `--json`), leaving a bridge
//! that wide in the incision, and when that is refused too the step is skipped: the model
//! stays as it was, the step's mesh is written (unchanged) so the series keeps one mesh
//! per time step, and the blade moves on without cutting ([`Scalpel::skip_to`]: the next
//! step begins a crack where the blade is). Time-critical, a sweep none of whose splits
//! the model takes is dropped from the model (the triangle before the refused one kept)
//! and from the current mesh, which is extracted again ([`LiveMt::process_pending`]);
//! when nothing of the step was kept, a new crack is then begun a tenth of the way into
//! it, cut frontier first and on the model as any step (`gap` 0.1 when taken), else its
//! area is left uncut (where the first triangle was kept, a new crack from a tenth of the
//! way would cross its crack). The summary lists the refused steps (a warning
//! on stderr, `refused_steps` in `--json`). A step that leaves an invalid model or mesh
//! still stops the run.
//!
//! `--min-advance F` defers a step until the blade is F × the median edge length of the
//! mesh (a model's finest mesh) from where the incision ends, then cuts all the area swept
//! since ([`mtcut::cut::Incision`]): a path of steps much shorter than the edges otherwise
//! fills the crack's front with slivers. The last step cuts what is left. 0, the default,
//! cuts every step.
//!
//! Given a mesh instead of a model (any readable mesh file), the scalpel cuts the mesh
//! itself, each step continuing the crack of the earlier ones
//! ([`mtcut::cut::CutOptions::SCALPEL`]: a blade that turns or tilts works there), the mesh
//! validated after each step; `--save` then names a mesh file for the cut mesh.

use crate::CliResult;
use crate::parse;
use mtcut::cut::{
    Blade, Components, CutError, CutOptions, Cutter, Incision, LiveMt, PendingBudget, Scalpel,
    ScalpelError, ScalpelStep,
};
use mtcut::geom::{CutPolygon, DVec3};
use mtcut::io::{PvdEntry, read_mesh, write_mesh, write_pvd};
use mtcut::mesh::TetMesh;
use mtcut::mt::{ExtractOptions, Mt};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// At most one resolution for the current mesh.
#[derive(clap::Args, Debug)]
#[group(multiple = false)]
pub struct Resolution {
    /// The current mesh at this error threshold (default: the finest mesh).
    #[arg(long, value_name = "E", allow_hyphen_values = true, value_parser = parse::threshold)]
    threshold: Option<f64>,
    /// The current mesh with at most N tets.
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = parse::count)]
    budget: Option<usize>,
}

#[derive(clap::Args)]
pub struct Args {
    /// The model (.mt), or a mesh (.vtu, .node/.ele, .mesh) to cut itself.
    model: PathBuf,
    /// The blade's positions over time: a JSON list of at least two positions, one per
    /// time step, each the blade's two ends: [[[x,y,z],[x,y,z]], [[x,y,z],[x,y,z]], ...].
    #[arg(long, value_name = "PATH.json")]
    path: PathBuf,
    /// Folder for the time series (created if missing).
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    #[command(flatten)]
    resolution: Resolution,
    /// Cut the current mesh first at each step, the rest of the model after (paper §5's
    /// time-critical cut), timing both.
    #[arg(long)]
    time_critical: bool,
    /// Also write the cut model after the last step (.mt; for a mesh: the cut mesh, .vtu
    /// or .node/.ele).
    #[arg(long, value_name = "OUT.mt")]
    save: Option<PathBuf>,
    /// Defer a step until the blade is F × the median edge length from where the incision
    /// ends (0: cut every step); the last step cuts what is left.
    #[arg(long, value_name = "F", default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse::min_advance)]
    min_advance: f64,
    /// Go on past a step the model refuses (the model as it was; see above) instead of
    /// stopping the run: cut it again from a tenth of the way into it, or skip it when that
    /// is refused too, and report those steps. For a model only.
    #[arg(long)]
    skip_refused: bool,
    /// Print the statistics as one JSON object.
    #[arg(long)]
    json: bool,
}

/// The fraction of a refused step left uncut when a new crack is begun past it
/// (`--skip-refused`; [`Scalpel::step_after_gap`]).
const RESTART_GAP: f64 = 0.1;

/// Whether `e`, an error of a scalpel step, is the model refusing the cut (the model as
/// it was), which `--skip-refused` skips.
fn is_refusal(e: &ScalpelError) -> bool {
    matches!(e, ScalpelError::Cut(CutError::MtInconsistent { .. }))
}

/// The incision of a run: its blade at the path's start, deferring steps shorter than
/// `--min-advance` edges of `mesh` (computed only when asked).
fn incision(
    args: &Args,
    start: Blade,
    mesh: impl FnOnce() -> Result<TetMesh, String>,
) -> Result<Incision, Box<dyn std::error::Error>> {
    let length = if args.min_advance > 0.0 {
        let mesh = mesh()?;
        let edge = mesh.median_edge_length().ok_or_else(|| {
            format!(
                "{}: no tets to measure --min-advance by",
                args.model.display()
            )
        })?;
        args.min_advance * edge
    } else {
        0.0
    };
    Ok(Incision::new(start, length)?)
}

/// A model's finest mesh, what `--min-advance` measures edges on.
fn finest(mt: &Mt) -> Result<TetMesh, String> {
    mt.extract(&ExtractOptions::FINEST)
        .map(|e| e.mesh)
        .map_err(|e| e.to_string())
}

/// The blade positions of a path file.
fn read_path(path: &Path) -> Result<Vec<Blade>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let value: Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: not JSON: {e}", path.display()))?;
    let bad = |what: String| {
        format!(
            "{}: {what}; expected a list of blade positions, each two points [x,y,z]: \
             [[[x,y,z],[x,y,z]], ...]",
            path.display()
        )
    };
    let steps = value
        .as_array()
        .ok_or_else(|| bad("the top level is not a list".into()))?;
    let point = |v: &Value, k: usize, e: usize| -> Result<DVec3, String> {
        let c = v
            .as_array()
            .filter(|c| c.len() == 3)
            .ok_or_else(|| bad(format!("position {k}, end {e} is not three numbers")))?;
        let mut x = [0.0; 3];
        for (i, n) in c.iter().enumerate() {
            x[i] = n
                .as_f64()
                .filter(|f| f.is_finite())
                .ok_or_else(|| bad(format!("position {k}, end {e}: {n} is not a finite number")))?;
        }
        Ok(DVec3::from_array(x))
    };
    let blades = steps
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let ends = s
                .as_array()
                .filter(|e| e.len() == 2)
                .ok_or_else(|| bad(format!("position {k} is not two points")))?;
            let blade = [point(&ends[0], k, 0)?, point(&ends[1], k, 1)?];
            if blade[0] == blade[1] {
                return Err(bad(format!("position {k}: both ends are the same point")));
            }
            Ok(blade)
        })
        .collect::<Result<Vec<Blade>, String>>()?;
    if blades.len() < 2 {
        return Err(bad(format!(
            "{} position(s): a path needs two at least",
            blades.len()
        )));
    }
    Ok(blades)
}

pub fn run(args: Args) -> CliResult {
    if !crate::info::is_model(&args.model) {
        return run_mesh(&args);
    }
    if let Some(save) = &args.save {
        parse::model_output(save)?;
    }
    let blades = read_path(&args.path)?;
    let options = match (args.resolution.threshold, args.resolution.budget) {
        (Some(e), _) => ExtractOptions::threshold(e),
        (_, Some(n)) => ExtractOptions::FINEST.with_budget(Some(n)),
        _ => ExtractOptions::FINEST,
    };
    let mt = parse::valid_model(&args.model)?;
    parse::output_folder(&args.output)?;
    if args.time_critical {
        return run_time_critical(&args, mt, &blades, &options);
    }
    let min_advance = incision(&args, blades[0], || finest(&mt))?.min_advance();
    let mut scalpel = Scalpel::new(mt, blades[0])?;
    scalpel.set_min_advance(min_advance)?;
    let mut series = Series::new(&args.output);
    let mut steps: Vec<Value> = Vec::new();
    // Writes step k's mesh, valid as the model's bodies (an error otherwise, nothing
    // written); whether it met the budget (as `extract`, a coarsest mesh over it is
    // written anyway, with a warning).
    let write_step =
        |k: usize, mt: &Mt, series: &mut Series| -> Result<bool, Box<dyn std::error::Error>> {
            let e = mt.extract(&options)?;
            if let Err(report) = Components::validate_bodies(&e.mesh) {
                return Err(series.invalid(k, "current mesh", &report));
            }
            if !e.stats.budget_met && !args.json {
                eprintln!(
                    "mtcut: warning: step {k}: even the coarsest mesh ({} tets) exceeds the \
                 budget; it was written anyway",
                    e.stats.tets
                );
            }
            series.write(k, &e.mesh)?;
            Ok(e.stats.budget_met)
        };
    write_step(0, scalpel.mt(), &mut series)?;
    let start = Instant::now();
    let (mut refused_steps, mut gap_steps): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
    for (k, &to) in blades.iter().enumerate().skip(1) {
        // A refused step, with --skip-refused, leaves the model as it was; a new crack is
        // then begun a tenth of the way into the step and cut from there
        // (`Scalpel::step_after_gap`: a bridge that wide instead of the whole step), or,
        // when that is refused too, the blade moves on without cutting
        // (`Scalpel::skip_to`), so that the next step begins a crack at the blade rather
        // than sweeping again from the refused angle.
        let mut refusal: Option<String> = None;
        let mut gap = None;
        let refused = |r: &Result<ScalpelStep, ScalpelError>| {
            args.skip_refused && r.as_ref().is_err_and(is_refusal)
        };
        let r = scalpel.step(to);
        let mut step = if refused(&r) {
            refusal = r.err().map(|e| e.to_string());
            match scalpel.step_after_gap(to, RESTART_GAP) {
                Ok(s) => {
                    gap = Some(RESTART_GAP);
                    s
                }
                Err(_) => {
                    scalpel.skip_to(to).map_err(|e| series.failed(k, &e))?;
                    ScalpelStep::default()
                }
            }
        } else {
            r.map_err(|e| series.failed(k, &e))?
        };
        if k + 1 == blades.len() {
            let r = scalpel.catch_up();
            let rest = if refused(&r) {
                refusal = refusal.or(r.err().map(|e| e.to_string()));
                scalpel.skip_to(to).map_err(|e| series.failed(k, &e))?;
                ScalpelStep::default()
            } else {
                r.map_err(|e| series.failed(k, &e))?
            };
            // At most one of the two cut: the step, or the catch-up of a deferred step.
            if !rest.cuts.is_empty() {
                step.split = rest.split;
            }
            step.cuts.extend(rest.cuts);
            step.deferred = rest.deferred;
        }
        if let Some(e) = &refusal {
            refused_steps.push(k);
            if gap.is_some() {
                gap_steps.push(k);
            }
            if !args.json {
                match gap {
                    Some(g) => eprintln!(
                        "mtcut: warning: step {k} refused; cut again from {g} of the way into \
                         it (the rest left uncut, a bridge): {e}"
                    ),
                    None => {
                        eprintln!("mtcut: warning: step {k} skipped (its area left uncut): {e}")
                    }
                }
            }
        }
        let t_validate = Instant::now();
        let report = scalpel.mt().validate();
        let validate_seconds = t_validate.elapsed().as_secs_f64();
        if !report.is_valid() {
            return Err(series.invalid(k, "model", &report));
        }
        let budget_met = write_step(k, scalpel.mt(), &mut series)?;
        let components = scalpel.mt().nb_components();
        if args.json {
            steps.push(json!({
                "step": k,
                "refused": refusal,
                "gap": gap,
                "budget_met": budget_met,
                "deferred": step.deferred,
                "polygons": step.cuts.len(),
                "split": step.split,
                "tets_cut": step.tets_cut(),
                "cuts": step.cuts.iter().map(|s| s.to_json()).collect::<Vec<_>>(),
                "components": components,
                "seconds": step.seconds(),
                "seconds_validate": validate_seconds,
            }));
        } else {
            out!(
                "step {k:<4}  {} polygon(s){}, {} tets cut, {} component(s), {:.4} s (validate \
                 {validate_seconds:.3} s)",
                step.cuts.len(),
                if let Some(g) = gap {
                    format!(" (refused; cut from {g} of the way into it, a bridge left)")
                } else if refusal.is_some() {
                    " (refused, skipped)".to_string()
                } else if step.deferred {
                    " (deferred)".to_string()
                } else if step.split > 0 {
                    format!(
                        " (split {} of the sweep: the ones before refused)",
                        step.split
                    )
                } else {
                    String::new()
                },
                step.tets_cut(),
                components,
                step.seconds()
            );
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    finish(
        &args,
        scalpel.into_mt(),
        steps,
        &series,
        seconds,
        &refused_steps,
        &gap_steps,
    )
}

/// After the last step: saves the model if asked, prints the run's summary.
fn finish(
    args: &Args,
    mt: Mt,
    steps: Vec<Value>,
    series: &Series,
    seconds: f64,
    refused_steps: &[usize],
    gap_steps: &[usize],
) -> CliResult {
    if let Some(save) = &args.save {
        mt.save(save)?;
    }
    let (pvd, meshes) = (&series.pvd, series.len());
    if args.json {
        out!(
            "{}",
            json!({
                "input": args.model.display().to_string(),
                "time_critical": args.time_critical,
                "steps": steps,
                "components": mt.nb_components(),
                "refused_steps": refused_steps,
                "gap_steps": gap_steps,
                "valid": true,
                "pvd": pvd.display().to_string(),
                "saved": args.save.as_ref().map(|p| p.display().to_string()),
                "seconds": seconds,
            })
        );
        return Ok(());
    }
    out!(
        "scalpel    {} steps{}{}, {} component(s), valid after every step; {:.3} s",
        meshes - 1,
        if args.time_critical {
            " (time-critical)"
        } else {
            ""
        },
        match (refused_steps.len(), gap_steps.len()) {
            (0, _) => String::new(),
            (n, 0) => format!(", {n} refused and skipped ({refused_steps:?})"),
            (n, g) => format!(
                ", {n} refused ({refused_steps:?}): {g} cut again from {RESTART_GAP} of the way \
                 into them ({gap_steps:?}), the others skipped"
            ),
        },
        mt.nb_components(),
        seconds
    );
    out!("wrote      {} ({meshes} meshes)", pvd.display());
    if let Some(save) = &args.save {
        out!("saved      {}", save.display());
    }
    Ok(())
}

/// `--time-critical`: each step cuts the current mesh first ([`LiveMt::cut`], the mesh
/// written then), then the queued MT cut ([`LiveMt::process_pending`]), then validates both.
fn run_time_critical(args: &Args, mt: Mt, blades: &[Blade], options: &ExtractOptions) -> CliResult {
    let mut incision = incision(args, blades[0], || finest(&mt))?;
    let mut live = LiveMt::new(mt, options, Scalpel::OPTIONS)?;
    let mut series = Series::new(&args.output);
    series.write(0, live.mesh())?;
    let start = Instant::now();
    let mut steps: Vec<Value> = Vec::new();
    let (mut refused_steps, mut gap_steps) = (Vec::new(), Vec::new());
    for (k, &to) in blades.iter().enumerate().skip(1) {
        let mut counts = Frontier::default();
        let end = incision.end();
        incision
            .step_sweep(to, frontier(&mut live, &mut counts))
            .map_err(|e| series.failed(k, &e))?;
        if k + 1 == blades.len() {
            incision
                .catch_up_sweep(frontier(&mut live, &mut counts))
                .map_err(|e| series.failed(k, &e))?;
        }
        series.write(k, live.mesh())?;
        let mut r = live
            .process_pending(PendingBudget::All)
            .map_err(|e| series.failed(k, &e))?;
        // The model refused a cut (and is as it was, the current mesh extracted again):
        // stop as a step that broke it would, or go on with --skip-refused. When nothing
        // of the step was kept, a new crack is begun a tenth of the way into it and cut
        // from there, as `Scalpel::step_after_gap` does (the model and the current mesh
        // are as before the step).
        let refusal = r.refused.first().map(|e| e.to_string());
        let mut gap = None;
        if let Some(e) = &refusal {
            if !args.skip_refused {
                return Err(series.failed(k, e).into());
            }
            refused_steps.push(k);
            if r.cuts.is_empty() && !incision.is_behind() && end != incision.blade() {
                let to = incision.blade();
                let from = [
                    end[0].lerp(to[0], RESTART_GAP),
                    end[1].lerp(to[1], RESTART_GAP),
                ];
                incision.skip_to(from).map_err(|e| series.failed(k, &e))?;
                incision
                    .step_sweep(to, frontier(&mut live, &mut counts))
                    .map_err(|e| series.failed(k, &e))?;
                let again = live
                    .process_pending(PendingBudget::All)
                    .map_err(|e| series.failed(k, &e))?;
                if again.refused.is_empty() {
                    gap = Some(RESTART_GAP);
                    gap_steps.push(k);
                }
                r.cuts.extend(again.cuts);
                r.fragments += again.fragments;
                r.remeshed |= again.remeshed;
                r.folded += again.folded;
                r.other_splits += again.other_splits;
                r.seconds += again.seconds;
            }
            if !args.json {
                match gap {
                    Some(g) => eprintln!(
                        "mtcut: warning: step {k}: the model's cut was refused; cut again from \
                         {g} of the way into the step (the rest left uncut, a bridge): {e}"
                    ),
                    None => eprintln!(
                        "mtcut: warning: step {k}: the model's cut was refused and dropped: {e}"
                    ),
                }
            }
        }
        let Frontier {
            polygons,
            seconds: frontier_s,
            tets_cut,
        } = counts;
        let t_validate = Instant::now();
        let (model, mesh) = (
            live.mt().validate(),
            Components::validate_bodies(live.mesh()),
        );
        let validate_seconds = t_validate.elapsed().as_secs_f64();
        if !model.is_valid() {
            return Err(series.invalid(k, "model", &model));
        }
        if let Err(report) = mesh {
            return Err(series.invalid(k, "current mesh", &report));
        }
        if args.json {
            steps.push(json!({
                "step": k,
                "refused": refusal,
                "gap": gap,
                "deferred": incision.is_behind(),
                "polygons": polygons,
                "current_tets_cut": tets_cut,
                "seconds_frontier_first": frontier_s,
                "seconds_pending": r.seconds,
                "fragments": r.fragments,
                "remeshed": r.remeshed,
                "other_splits": r.other_splits,
                "folded": r.folded,
                "cuts": r.cuts.iter().map(|s| s.to_json()).collect::<Vec<_>>(),
                "components": live.mt().nb_components(),
                "seconds_validate": validate_seconds,
            }));
        } else {
            out!(
                "step {k:<4}  {tets_cut} current tets cut in {:.3} ms; model: {} fragments in \
                 {:.4} s{}; {} component(s)",
                frontier_s * 1e3,
                r.fragments,
                r.seconds,
                match (r.remeshed, r.other_splits) {
                    (true, 0) => ", current mesh replaced by the model's",
                    (true, _) => {
                        ", cut as another split of the sweep, current mesh replaced by the \
                         model's"
                    }
                    _ => "",
                },
                live.mt().nb_components()
            );
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    finish(
        args,
        live.into_mt()?,
        steps,
        &series,
        seconds,
        &refused_steps,
        &gap_steps,
    )
}

/// What the frontier-first cuts of a time-critical step did.
#[derive(Default)]
struct Frontier {
    polygons: usize,
    seconds: f64,
    tets_cut: usize,
}

/// The frontier-first cut of a sweep's splits ([`LiveMt::cut_sweep`]), counted in `counts`.
fn frontier<'a>(
    live: &'a mut LiveMt,
    counts: &'a mut Frontier,
) -> impl FnMut(Vec<Vec<CutPolygon>>) -> Result<(), Box<dyn std::error::Error>> + 'a {
    move |splits| {
        for c in live.cut_sweep(&splits)? {
            counts.polygons += 1;
            counts.seconds += c.seconds;
            counts.tets_cut += c.stats.tets_cut;
        }
        Ok(())
    }
}

/// A scalpel through a mesh (not a model): each step cuts the mesh with the area the blade
/// swept, continuing the crack ([`CutOptions::SCALPEL`]); the mesh is validated and
/// written after each step.
fn run_mesh(args: &Args) -> CliResult {
    let refused = |option: &str| -> CliResult {
        Err(format!(
            "{}: {option} is for a model (.mt); a mesh is cut at its own resolution, as a \
             simulation's mesh; nothing written",
            args.model.display()
        )
        .into())
    };
    if args.resolution.threshold.is_some() || args.resolution.budget.is_some() {
        return refused("--threshold/--budget");
    }
    if args.time_critical {
        return refused("--time-critical");
    }
    if args.skip_refused {
        return refused("--skip-refused");
    }
    if let Some(save) = &args.save {
        parse::mesh_output(save)?;
    }
    let blades = read_path(&args.path)?;
    let (mesh, _) = read_mesh(&args.model)?;
    parse::output_folder(&args.output)?;
    let mut incision = incision(args, blades[0], || Ok(mesh.clone()))?;
    let mut cutter = Cutter::new(mesh, CutOptions::SCALPEL)?;
    let mut series = Series::new(&args.output);
    series.write(0, cutter.mesh())?;
    let start = Instant::now();
    let mut steps: Vec<Value> = Vec::new();
    let mut components = 1;
    for (k, &to) in blades.iter().enumerate().skip(1) {
        // A blade that did not move sweeps nothing: a step without cuts, as for a model.
        let (mut seconds, mut tets_cut) = (0.0, 0);
        let mut cuts: Vec<Value> = Vec::new();
        let mut cut = |polygon: &CutPolygon| -> Result<(), Box<dyn std::error::Error>> {
            let r = cutter.cut(polygon)?;
            seconds += r.stats.time.cut;
            tets_cut += r.stats.tets_cut;
            components = r.stats.components.unwrap_or(components);
            cuts.push(r.stats.to_json());
            Ok(())
        };
        incision
            .step(to, &mut cut)
            .map_err(|e| series.failed(k, &e))?;
        if k + 1 == blades.len() {
            incision
                .catch_up(&mut cut)
                .map_err(|e| series.failed(k, &e))?;
        }
        // A step that cut leaves the crack at the blade.
        let deferred = incision.is_behind();
        let t_validate = Instant::now();
        let report = cutter.mesh().validate();
        let validate_seconds = t_validate.elapsed().as_secs_f64();
        if !report.is_valid() {
            return Err(series.invalid(k, "mesh", &report));
        }
        series.write(k, cutter.mesh())?;
        if args.json {
            steps.push(json!({
                "step": k,
                "deferred": deferred,
                "polygons": cuts.len(),
                "tets_cut": tets_cut,
                "cuts": cuts,
                "components": components,
                "seconds": seconds,
                "seconds_validate": validate_seconds,
            }));
        } else {
            out!(
                "step {k:<4}  {} polygon(s){}, {tets_cut} tets cut, {components} component(s), \
                 {seconds:.4} s (validate {validate_seconds:.3} s)",
                cuts.len(),
                if deferred { " (deferred)" } else { "" }
            );
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    let mesh = cutter.into_mesh();
    if let Some(save) = &args.save {
        write_mesh(save, &mesh)?;
    }
    if args.json {
        out!(
            "{}",
            json!({
                "input": args.model.display().to_string(),
                "steps": steps,
                "components": components,
                "tets": mesh.nb_tets(),
                "valid": true,
                "pvd": series.pvd.display().to_string(),
                "saved": args.save.as_ref().map(|p| p.display().to_string()),
                "seconds": seconds,
            })
        );
        return Ok(());
    }
    out!(
        "scalpel    {} steps through the mesh, {components} component(s), valid after every \
         step; {seconds:.3} s",
        series.len() - 1
    );
    out!(
        "wrote      {} ({} meshes)",
        series.pvd.display(),
        series.len()
    );
    if let Some(save) = &args.save {
        out!("saved      {}", save.display());
    }
    Ok(())
}

/// The time series of a run: `DIR/step-NNNN.vtu`, listed in `DIR/scalpel.pvd`, the list
/// rewritten after each step (so the steps before a failure stay listed).
struct Series {
    dir: PathBuf,
    pvd: PathBuf,
    entries: Vec<PvdEntry>,
}

impl Series {
    fn new(dir: &Path) -> Series {
        Series {
            dir: dir.to_path_buf(),
            pvd: dir.join("scalpel.pvd"),
            entries: Vec::new(),
        }
    }

    /// Writes step `k`'s mesh and lists it.
    fn write(&mut self, k: usize, mesh: &TetMesh) -> CliResult {
        let name = format!("step-{k:04}.vtu");
        write_mesh(self.dir.join(&name), mesh)?;
        self.entries.push(PvdEntry {
            timestep: k as f64,
            part: 0,
            file: PathBuf::from(name),
        });
        write_pvd(&self.pvd, &self.entries)?;
        Ok(())
    }

    /// Meshes written.
    fn len(&self) -> usize {
        self.entries.len()
    }

    /// The error of step `k`: what went wrong, and what the run leaves behind (the meshes
    /// written so far; a time-critical step's own mesh is written before its queued model
    /// cut).
    fn failed(&self, k: usize, e: &dyn std::fmt::Display) -> String {
        match self.len() {
            0 => format!("step {k}: {e}; nothing written, nothing saved"),
            n => format!(
                "step {k}: {e}; steps 0-{} written to {}, nothing saved",
                n - 1,
                self.dir.display()
            ),
        }
    }

    /// The error of step `k` that left an invalid `what` (model or mesh).
    fn invalid(
        &self,
        k: usize,
        what: &str,
        report: &dyn std::fmt::Display,
    ) -> Box<dyn std::error::Error> {
        self.failed(k, &format!("the cut left an invalid {what} ({report})"))
            .into()
    }
}
