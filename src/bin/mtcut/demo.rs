//! `mtcut demo [-o DIR]`: the main job on the embedded default model (a liver meshed by
//! TetGen from CGAL's segmented CT image; see assets/README.md), needing no files and no
//! system packages: check the model, build its Multi-Tessellation (paper §2), extract
//! three levels of detail, cut the finest straight through (paper §3–§4) and write it all
//! with a ParaView collection listing the outputs.

use crate::CliResult;
use crate::build::{build_with_bar, progress_bar};
use crate::cut::{Parts, part_path};
use crate::info::MeshInfo;
use flate2::read::GzDecoder;
use mtcut::cut::{CUT_COLUMN, CutOptions, CutStats, VertexOrigin, cut_mesh};
use mtcut::geom::{Aabb, CutPolygon, DVec3};
use mtcut::io::{PvdEntry, parse_tetgen, write_mesh, write_pvd};
use mtcut::mesh::{Attribute, ImportReport, TetMesh};
use mtcut::mt::{BuildOptions, ExtractOptions, POINT_VERTEX};
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

/// The demo's cut of the finest level, into its connected parts. Today this is the
/// plain-mesh engine on the finest extraction (which is exactly the input mesh); when the
/// MT itself can be cut, this function becomes "cut the MT, extract its finest level" and
/// nothing else in the demo changes.
fn cut_finest(
    finest: &TetMesh,
    polygon: &CutPolygon,
) -> Result<(TetMesh, CutStats), Box<dyn Error>> {
    let mut mesh = finest.clone();
    let result = cut_mesh(&mut mesh, polygon, &CutOptions::DEFAULT)?;
    // MT vertex ids are not quantities to interpolate: a copy of a vertex the cut passes
    // through is still that MT vertex; a point the cut made on an edge or a face is none
    // (-1). The column stays, so every step of demo.pvd carries the same arrays.
    if let Some(ids) = mesh.point_data.get_mut(POINT_VERTEX) {
        let first = result.first_new_vertex.idx();
        for (k, origin) in result.origins.iter().enumerate() {
            ids.values[first + k] = match origin {
                VertexOrigin::Copy { of } => ids.values[of.idx()],
                VertexOrigin::Edge { .. } | VertexOrigin::Face { .. } => -1.0,
            };
        }
    }
    Ok((mesh, result.stats))
}

/// Writes `mesh` to `dir/name` and returns the path relative to `dir` (for the .pvd).
fn write_in(dir: &Path, name: &str, mesh: &TetMesh) -> Result<PathBuf, Box<dyn Error>> {
    write_mesh(dir.join(name), mesh)?;
    Ok(PathBuf::from(name))
}

pub fn run(args: Args) -> CliResult {
    let start = Instant::now();
    let dir = &args.output;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let (mesh, report) = liver()?;

    // The model and its quality report.
    let info = MeshInfo::of(&mesh, report);
    let quality = dir.join("liver-quality.json");
    std::fs::write(
        &quality,
        serde_json::to_string_pretty(&info.to_json())? + "\n",
    )
    .map_err(|e| format!("{}: {e}", quality.display()))?;
    println!("embedded model: liver");
    info.print_text();

    // The Multi-Tessellation.
    let bar = progress_bar(false);
    let (mt, build) = build_with_bar(&mesh, &BuildOptions::DEFAULT, &bar)?;
    let model = dir.join("liver.mt");
    mt.save(&model)?;

    // Three levels of detail: the middle one has the geometric mean of the extremes' sizes,
    // the best mesh within that budget.
    let finest = mt.extract(&ExtractOptions::FINEST)?;
    let coarsest = mt.extract(&ExtractOptions::COARSEST)?;
    let middle_budget = ((finest.stats.tets as f64) * (coarsest.stats.tets as f64)).sqrt() as usize;
    let middle = mt.extract(&ExtractOptions::FINEST.with_budget(Some(middle_budget)))?;
    let mut entries = Vec::new();
    for (step, (name, level)) in [
        ("liver-finest.vtu", &finest),
        ("liver-middle.vtu", &middle),
        ("liver-coarsest.vtu", &coarsest),
    ]
    .into_iter()
    .enumerate()
    {
        // The levels carry the cut column too (0: made by no cut), so every step of the
        // .pvd has the same arrays and ParaView can colour them all alike.
        let mut level = level.mesh.clone();
        let zeros = vec![0.0; level.nb_tets()];
        level.cell_data.insert(
            Attribute::new(CUT_COLUMN, 1, zeros).ok_or("the cut column could not be made")?,
        );
        entries.push(PvdEntry {
            timestep: step as f64,
            part: 0,
            file: write_in(dir, name, &level)?,
        });
    }

    // A cut straight through the finest level; each part in its own file.
    let polygon = demo_polygon(&mesh.bbox())?;
    let (cut, cut_stats) = cut_finest(&finest.mesh, &polygon)?;
    let parts = Parts::of(&cut);
    for (k, part) in parts.components.extract_all(&cut).iter().enumerate() {
        let name = part_path(Path::new("liver-cut.vtu"), k);
        let name = name.to_string_lossy();
        entries.push(PvdEntry {
            timestep: 3.0,
            part: k as u32,
            file: write_in(dir, &name, part)?,
        });
    }
    let pvd = dir.join("demo.pvd");
    write_pvd(&pvd, &entries)?;

    println!(
        "MT         {} fragments, DAG depth {}, {} tets over all levels; built in {:.2} s",
        build.fragments, build.dag_depth, build.pool_tets, build.seconds
    );
    println!(
        "levels     finest {} tets, middle {} tets (error ≤ {:.3e}), coarsest {} tets",
        finest.stats.tets, middle.stats.tets, middle.stats.max_error, coarsest.stats.tets
    );
    let sizes: Vec<String> = parts.tets.iter().map(|n| n.to_string()).collect();
    println!(
        "cut        plane z = {:.3}: {} tets cut, {} created; {} parts ({} tets); volume {} before, {} after",
        polygon.points()[0].z,
        cut_stats.tets_cut,
        cut_stats.tets_created,
        parts.components.count,
        sizes.join(" + "),
        finest.mesh.volume(),
        cut.volume()
    );
    println!(
        "wrote      {} (open it in ParaView: time steps 0-2 are the levels, 3 the cut parts), \
         {}, {} and {} .vtu files",
        pvd.display(),
        model.display(),
        quality.display(),
        entries.len()
    );
    println!("time       {:.2} s in all", start.elapsed().as_secs_f64());
    Ok(())
}
