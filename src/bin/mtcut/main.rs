//! `mtcut`: the command-line tool. Each subcommand lives in its own file and maps onto the
//! library's API; this file only parses arguments and turns errors into exit codes.

mod convert;
mod demo;
mod info;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Multiresolution tetrahedral meshes that can be cut.
#[derive(Parser)]
#[command(name = "mtcut", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print a mesh's size, volume, boundary, quality and validation result.
    Info(info::Args),
    /// Convert a mesh between formats (.vtu, .node/.ele, .mesh in; .vtu, .node/.ele out).
    Convert(convert::Args),
    /// Run the main job on the embedded liver model and write the results to a folder.
    Demo(demo::Args),
}

/// Errors are reported as `mtcut: error: ...` on stderr with exit code 1; usage errors
/// are clap's (exit code 2).
pub type CliResult = Result<(), Box<dyn std::error::Error>>;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Info(a) => info::run(a),
        Command::Convert(a) => convert::run(a),
        Command::Demo(a) => demo::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("mtcut: error: {e}");
            ExitCode::FAILURE
        }
    }
}
