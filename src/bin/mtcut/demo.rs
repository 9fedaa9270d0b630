//! `mtcut demo [-o DIR]`: the main job on the embedded default model (a liver meshed by
//! TetGen from CGAL's segmented CT image; see assets/README.md), needing no files and no
//! system packages: check the model, build its Multi-Tessellation (paper §2), extract
//! three levels of detail, cut the MT straight through (every level and the DAG, paper
//! §3), extract the finest and the coarsest level of each part, move a scalpel across
//! the model in steps (each cutting every level with the area the blade swept), make a
//! curved incision in the middle level as a plain mesh (a blade turning as it moves), and
//! write it all with ParaView collections listing the outputs (`demo.pvd`; `scalpel.pvd`
//! and `curve.pvd`, the two time series).
//!
//! Every step of the collection is an MT extraction, so all carry the same arrays (the
//! MT's cell and point columns; a cut copies them onto the tets and vertices it makes),
//! as ParaView needs to colour them alike. Everything is computed and checked before the
//! first file is written.

use crate::CliResult;
use crate::build::{build_with_bar, progress_bar};
use crate::info::MeshInfo;
use crate::parse;
use flate2::read::GzDecoder;
use mtcut::cut::{Blade, Components, CutOptions, Cutter, MtCutter, Scalpel};
use mtcut::geom::{Aabb, CutPolygon, DVec3, SWEEP_PLANARITY, scalpel_sweep};
use mtcut::io::{PvdEntry, parse_tetgen, write_mesh, write_pvd};
use mtcut::mesh::{ImportReport, TetMesh};
use mtcut::mt::{BuildOptions, ExtractOptions, Extraction};
use std::error::Error;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::time::Instant;

const LIVER_NODE_GZ: &[u8] = include_bytes!("../../../assets/liver.node.gz");
const LIVER_ELE_GZ: &[u8] = include_bytes!("../../../assets/liver.ele.gz");

#[derive(clap::Args)]
pub struct Args {
    /// Folder for the outputs (created if missing).
    #[arg(short, long, default_value = "mtcut-demo")]
    output: PathBuf,
}

fn gunzip(bytes: &[u8]) -> Result<String, std::io::Error> {
    let mut text = String::new();
    GzDecoder::new(bytes).read_to_string(&mut text)?;
    Ok(text)
}

/// The embedded liver model.
pub fn liver() -> Result<(TetMesh, ImportReport), Box<dyn Error>> {
    let node = gunzip(LIVER_NODE_GZ)?;
    let ele = gunzip(LIVER_ELE_GZ)?;
    Ok(parse_tetgen(&node, &ele, Path::new("<embedded>/liver"))?)
}

/// The demo's cutting polygon: a square in the horizontal plane through the centre of the
/// model's bounding box, wide enough to cut the whole body in two (on the embedded liver
/// this plane gives two parts; the planes through the centre across x or y also cut off
/// tiny pieces, which makes a poorer first picture).
fn demo_polygon(bbox: &Aabb) -> Result<CutPolygon, Box<dyn Error>> {
    let c = bbox.center();
    let r = bbox.diagonal();
    let corners = [(-r, -r), (r, -r), (r, r), (-r, r)].map(|(x, y)| c + DVec3::new(x, y, 0.0));
    Ok(CutPolygon::new(&corners)?)
}

/// Writes `mesh` to `dir/name` and returns the path relative to `dir` (for the .pvd).
/// Steps of the demo scalpel.
const SCALPEL_STEPS: usize = 12;

/// The demo scalpel's blade at step `k`: a segment spanning the model in z (slightly
/// slanted in y), moving along x from before the model to beyond it.
fn demo_blade(bbox: &Aabb, k: usize) -> Blade {
    let (c, d) = (bbox.center(), bbox.max - bbox.min);
    let x = bbox.min.x - 0.05 * d.x + 1.1 * d.x * k as f64 / SCALPEL_STEPS as f64;
    [
        DVec3::new(x, c.y + 0.013 * d.y, bbox.min.z - 0.1 * d.z),
        DVec3::new(x, c.y - 0.011 * d.y, bbox.max.z + 0.1 * d.z),
    ]
}

/// Steps of the demo's curved incision.
const CURVE_STEPS: usize = 16;

/// The curved incision's blade at step `k`: a segment spanning the model in z, moving
/// along an arc around a centre off the model's (-x, -y) corner, 8° per step, from
/// outside the model to outside: it cuts that corner off.
fn curve_blade(bbox: &Aabb, k: usize) -> Blade {
    let (c, d) = (bbox.center(), bbox.max - bbox.min);
    let r = 0.6 * d.x.max(d.y);
    let a = (98.0 - 8.0 * k as f64).to_radians();
    let (x, y) = (bbox.min.x - 0.1 * d.x + r * a.cos(), c.y - r + r * a.sin());
    [
        DVec3::new(x, y, bbox.min.z - 0.1 * d.z),
        DVec3::new(x, y, bbox.max.z + 0.1 * d.z),
    ]
}

fn write_in(dir: &Path, name: &str, mesh: &TetMesh) -> Result<PathBuf, Box<dyn Error>> {
    write_mesh(dir.join(name), mesh)?;
    Ok(PathBuf::from(name))
}

/// One part of the cut model: its finest and coarsest extractions.
struct Part {
    finest: Extraction,
    coarsest: Extraction,
}

pub fn run(args: Args) -> CliResult {
    let start = Instant::now();
    let dir = &args.output;
    parse::output_folder(dir)?;
    let (mesh, report) = liver()?;
    let info = MeshInfo::of(&mesh, report);
    out!("embedded model: liver");
    info.print_text()?;

    // The Multi-Tessellation.
    let bar = progress_bar(false);
    let (mt, build) = build_with_bar(&mesh, &BuildOptions::DEFAULT, &bar)?;

    // Three levels of detail: the middle one has the geometric mean of the extremes' sizes,
    // the best mesh within that budget.
    let finest = mt.extract(&ExtractOptions::FINEST)?;
    let coarsest = mt.extract(&ExtractOptions::COARSEST)?;
    let middle_budget = ((finest.stats.tets as f64) * (coarsest.stats.tets as f64)).sqrt() as usize;
    let middle = mt.extract(&ExtractOptions::FINEST.with_budget(Some(middle_budget)))?;

    // A cut of the MT straight through, checked: the MT cut's known limits concern
    // sequences of cuts, but a broken model must never be written, so the demo stops here
    // with the first violation if this one fails.
    let polygon = demo_polygon(&mesh.bbox())?;
    let mut cutter = MtCutter::new(mt.clone(), MtCutter::DEFAULT_OPTIONS)?;
    let cut_stats = cutter.cut(&polygon)?;
    let t_validate = Instant::now();
    let validation = cutter.mt().validate();
    let validate_seconds = t_validate.elapsed().as_secs_f64();
    if !validation.is_valid() {
        return Err(format!(
            "the MT cut of the demo plane left an invalid model, nothing written: {validation}"
        )
        .into());
    }
    let cut = cutter.into_mt();
    let parts = cut
        .components()
        .iter()
        .map(|c| {
            Ok(Part {
                finest: c.extract(&ExtractOptions::FINEST)?,
                coarsest: c.extract(&ExtractOptions::COARSEST)?,
            })
        })
        .collect::<Result<Vec<Part>, Box<dyn Error>>>()?;

    // A scalpel opening the model: a blade crossing it in 12 steps, each cutting what it
    // swept (every level), the model checked after each; the current mesh (at the middle
    // budget) after each step is a time series of its own.
    let current = ExtractOptions::FINEST.with_budget(Some(middle_budget));
    let mut scalpel = Scalpel::new(mt.clone(), demo_blade(&mesh.bbox(), 0))?;
    let mut scalpel_meshes = vec![scalpel.mt().extract(&current)?];
    let mut scalpel_seconds = 0.0;
    for k in 1..=SCALPEL_STEPS {
        let step = scalpel.step(demo_blade(&mesh.bbox(), k))?;
        scalpel_seconds += step.seconds();
        let report = scalpel.mt().validate();
        if !report.is_valid() {
            return Err(format!(
                "the demo scalpel's step {k} left an invalid model, nothing written: {report}"
            )
            .into());
        }
        scalpel_meshes.push(scalpel.mt().extract(&current)?);
    }
    let scalpel_components = scalpel.mt().nb_components();

    // A curved incision in the middle level as a plain mesh (a simulation's mesh): a blade
    // turning as it moves, each step continuing the crack (the scalpel's options), the
    // mesh checked after each step.
    let mut curve = Cutter::new(middle.mesh.clone(), CutOptions::SCALPEL)?;
    let mut curve_meshes = vec![curve.mesh().clone()];
    for k in 1..=CURVE_STEPS {
        let sweep = scalpel_sweep(
            curve_blade(&mesh.bbox(), k - 1),
            curve_blade(&mesh.bbox(), k),
            SWEEP_PLANARITY,
        )?;
        for polygon in &sweep {
            curve.cut(polygon)?;
        }
        let report = curve.mesh().validate();
        if !report.is_valid() {
            return Err(format!(
                "the demo's curved incision left an invalid mesh at step {k}, nothing \
                 written: {report}"
            )
            .into());
        }
        curve_meshes.push(curve.mesh().clone());
    }
    let curve_parts = Components::of(curve.mesh()).count;

    // Everything checked: write.
    let quality = dir.join("liver-quality.json");
    std::fs::write(
        &quality,
        serde_json::to_string_pretty(&info.to_json())? + "\n",
    )
    .map_err(|e| format!("{}: {e}", quality.display()))?;
    let model = dir.join("liver.mt");
    mt.save(&model)?;
    let cut_model = dir.join("liver-cut.mt");
    cut.save(&cut_model)?;
    let mut entries = Vec::new();
    for (step, (name, level)) in [
        ("liver-finest.vtu", &finest),
        ("liver-middle.vtu", &middle),
        ("liver-coarsest.vtu", &coarsest),
    ]
    .into_iter()
    .enumerate()
    {
        entries.push(PvdEntry {
            timestep: step as f64,
            part: 0,
            file: write_in(dir, name, &level.mesh)?,
        });
    }
    // Step 3: the parts at their finest level, step 4 at their coarsest.
    for (k, part) in parts.iter().enumerate() {
        for (step, level, e) in [
            (3.0, "finest", &part.finest),
            (4.0, "coarsest", &part.coarsest),
        ] {
            entries.push(PvdEntry {
                timestep: step,
                part: k as u32,
                file: write_in(dir, &format!("liver-part-{k}-{level}.vtu"), &e.mesh)?,
            });
        }
    }
    entries.sort_by(|a, b| a.timestep.total_cmp(&b.timestep).then(a.part.cmp(&b.part)));
    let pvd = dir.join("demo.pvd");
    write_pvd(&pvd, &entries)?;
    let scalpel_entries = scalpel_meshes
        .iter()
        .enumerate()
        .map(|(k, e)| {
            Ok(PvdEntry {
                timestep: k as f64,
                part: 0,
                file: write_in(dir, &format!("liver-scalpel-{k:02}.vtu"), &e.mesh)?,
            })
        })
        .collect::<Result<Vec<PvdEntry>, Box<dyn Error>>>()?;
    let scalpel_pvd = dir.join("scalpel.pvd");
    write_pvd(&scalpel_pvd, &scalpel_entries)?;
    let curve_entries = curve_meshes
        .iter()
        .enumerate()
        .map(|(k, m)| {
            Ok(PvdEntry {
                timestep: k as f64,
                part: 0,
                file: write_in(dir, &format!("liver-curve-{k:02}.vtu"), m)?,
            })
        })
        .collect::<Result<Vec<PvdEntry>, Box<dyn Error>>>()?;
    let curve_pvd = dir.join("curve.pvd");
    write_pvd(&curve_pvd, &curve_entries)?;

    out!(
        "MT         {} fragments, DAG depth {}, {} tets over all levels; built in {:.2} s",
        build.fragments,
        build.dag_depth,
        build.pool_tets,
        build.seconds
    );
    out!(
        "levels     finest {} tets, middle {} tets (error ≤ {:.3e}), coarsest {} tets",
        finest.stats.tets,
        middle.stats.tets,
        middle.stats.max_error,
        coarsest.stats.tets
    );
    out!(
        "cut        the MT, plane z = {:.3}: {} fragments involved ({} split), {} tets cut over \
         all levels, {} created; {} parts; valid; {:.3} s (validate {:.3} s)",
        polygon.points()[0].z,
        cut_stats.fragments_involved,
        cut_stats.fragments_split,
        cut_stats.tets_cut,
        cut_stats.tets_created,
        parts.len(),
        cut_stats.time.total,
        validate_seconds
    );
    let sizes = |f: fn(&Part) -> &Extraction| {
        parts
            .iter()
            .map(|p| f(p).stats.tets.to_string())
            .collect::<Vec<_>>()
            .join(" + ")
    };
    let volume =
        |f: fn(&Part) -> &Extraction| parts.iter().map(|p| f(p).mesh.volume()).sum::<f64>();
    out!(
        "parts      finest {} tets, volume {} (uncut {}); coarsest {} tets, volume {} (uncut {})",
        sizes(|p| &p.finest),
        volume(|p| &p.finest),
        finest.mesh.volume(),
        sizes(|p| &p.coarsest),
        volume(|p| &p.coarsest),
        coarsest.mesh.volume()
    );
    out!(
        "wrote      {} (open it in ParaView: time steps 0-2 are the levels, 3 and 4 the cut \
         parts at their finest and coarsest), {}, {}, {} and {} .vtu files",
        pvd.display(),
        model.display(),
        cut_model.display(),
        quality.display(),
        entries.len()
    );
    out!(
        "scalpel    a blade across the MT in {SCALPEL_STEPS} steps, every level cut at each: \
         {scalpel_components} parts at the end; valid after every step; {scalpel_seconds:.3} s \
         of cutting; {} ({} meshes at the middle budget)",
        scalpel_pvd.display(),
        scalpel_entries.len()
    );
    out!(
        "curve      a blade turning 8° per step through the middle level (a plain mesh) in \
         {CURVE_STEPS} steps, each continuing the crack: {curve_parts} parts at the end; valid \
         after every step; {} ({} meshes)",
        curve_pvd.display(),
        curve_entries.len()
    );
    out!("time       {:.2} s in all", start.elapsed().as_secs_f64());
    Ok(())
}
