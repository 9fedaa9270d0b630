//! `mtcut convert IN -o OUT`: any readable format to .vtu or .node/.ele, by extension.

use crate::CliResult;
use mtcut::io::{read_mesh, write_mesh};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Input mesh (.vtu, .node/.ele, .mesh).
    input: PathBuf,
    /// Output mesh: .vtu, or .node/.ele (writes both files of the pair).
    #[arg(short, long)]
    output: PathBuf,
}

pub fn run(args: Args) -> CliResult {
    let (mesh, report) = read_mesh(&args.input)?;
    write_mesh(&args.output, &mesh)?;
    eprintln!(
        "wrote {} ({} vertices, {} tets; {} tets re-oriented, {} unused vertices kept)",
        args.output.display(),
        mesh.nb_vertices(),
        mesh.nb_tets(),
        report.reoriented_tets,
        report.unused_vertices
    );
    Ok(())
}
