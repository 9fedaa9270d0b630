//! `mtcut convert IN -o OUT`: any readable format to .vtu or .node/.ele, by extension.

use crate::{CliResult, parse};
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
    // Before reading: a .mesh (or any other) output is refused as one mtcut cannot write.
    parse::mesh_output(&args.output)?;
    let (mesh, report) = read_mesh(&args.input)?;
    write_mesh(&args.output, &mesh)?;
    // The report on stdout, as every command's.
    out!(
        "wrote {} ({} vertices, {} tets; {} tets re-oriented, {} unused vertices kept)",
        args.output.display(),
        mesh.nb_vertices(),
        mesh.nb_tets(),
        report.reoriented_tets,
        report.unused_vertices
    );
    Ok(())
}
