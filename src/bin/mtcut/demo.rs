//! `mtcut demo [-o DIR]`: the main job on the embedded default model (a liver meshed by
//! TetGen from CGAL's segmented CT image; see assets/README.md), needing no files and no
//! system packages.

use crate::CliResult;
use crate::info::MeshInfo;
use flate2::read::GzDecoder;
use mtcut::io::{parse_tetgen, write_mesh};
use mtcut::mesh::{ImportReport, TetMesh};
use std::io::Read;
use std::path::{Path, PathBuf};

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
pub fn liver() -> Result<(TetMesh, ImportReport), Box<dyn std::error::Error>> {
    let node = gunzip(LIVER_NODE_GZ)?;
    let ele = gunzip(LIVER_ELE_GZ)?;
    Ok(parse_tetgen(&node, &ele, Path::new("<embedded>/liver"))?)
}

pub fn run(args: Args) -> CliResult {
    let dir = &args.output;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let (mesh, report) = liver()?;
    let model = dir.join("liver.vtu");
    write_mesh(&model, &mesh)?;
    let info = MeshInfo::of(&mesh, report);
    let quality = dir.join("liver-quality.json");
    std::fs::write(
        &quality,
        serde_json::to_string_pretty(&info.to_json())? + "\n",
    )
    .map_err(|e| format!("{}: {e}", quality.display()))?;
    println!("embedded model: liver");
    info.print_text();
    println!("wrote {} and {}", model.display(), quality.display());
    Ok(())
}
