//! `mtcut`: the command-line tool. Each subcommand lives in its own file and maps onto the
//! library's API; this file only parses arguments and turns errors into exit codes.

/// `println!` that returns the write error to the caller (as `?` does) instead of
/// panicking: `mtcut info x.vtu | head -1` closes the pipe early, which is not an error
/// worth more than a quiet exit (see `main`).
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout(), $($arg)*)?;
    }};
}

/// A measure in a text report: the shortest decimal that reads back to the same double,
/// in scientific notation outside 1e-4..1e16 (a mesh at 1e50 had its volume printed as
/// 142 digits).
fn number(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 || !a.is_finite() || (1e-4..1e16).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

mod build;
mod convert;
mod cut;
mod cut_model;
mod demo;
mod extract;
mod info;
mod parse;
mod roi;
mod scalpel;

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
    /// Print a mesh's size, volume, boundary, quality and validation result, or an .mt
    /// model's summary.
    Info(info::Args),
    /// Convert a mesh between formats (.vtu, .node/.ele, .mesh in; .vtu, .node/.ele out).
    Convert(convert::Args),
    /// Build the multiresolution model (.mt) of a mesh by edge-collapse simplification.
    Build(build::Args),
    /// Extract a mesh at a chosen resolution from an .mt model.
    Extract(extract::Args),
    /// Cut a mesh, or every level of an .mt model, with planar convex polygons, applied in
    /// order.
    Cut(cut::Args),
    /// Restrict an .mt model to a box or a sphere (everything outside omitted), as a model
    /// of its own.
    Roi(roi::Args),
    /// Move a scalpel through an .mt model, or through a mesh, in time steps (a blade
    /// position per step, from a JSON file), writing the current mesh after each step as a
    /// ParaView time series.
    Scalpel(scalpel::Args),
    /// Run the main job on the embedded liver model and write the results to a folder.
    Demo(demo::Args),
}

/// Errors are reported as `mtcut: error: ...` on stderr with exit code 1; usage errors
/// (unknown or conflicting options, unparsable numbers) are clap's (exit code 2).
pub type CliResult = Result<(), Box<dyn std::error::Error>>;

/// A bad option value found after the command line was parsed (a polygon whose text is
/// not numbers): exit code 2, as for the usage errors the parser finds.
#[derive(Debug)]
pub struct Usage(pub String);

impl std::fmt::Display for Usage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Usage {}

fn main() -> ExitCode {
    // Past a file-size limit (`ulimit -f`) a write then fails with "File too large",
    // reported naming the file, instead of the process being killed by SIGXFSZ; the files
    // it was replacing are kept either way (the library writes through temporary files).
    // SAFETY: setting a signal's disposition to SIG_IGN, before any thread is started.
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Info(a) => info::run(a),
        Command::Convert(a) => convert::run(a),
        Command::Build(a) => build::run(a),
        Command::Extract(a) => extract::run(a),
        Command::Cut(a) => cut::run(a),
        Command::Roi(a) => roi::run(a),
        Command::Scalpel(a) => scalpel::run(a),
        Command::Demo(a) => demo::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // The reader went away (a closed pipe): nothing more to say to anyone.
            let broken_pipe = e
                .downcast_ref::<std::io::Error>()
                .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe);
            if broken_pipe {
                return ExitCode::SUCCESS;
            }
            eprintln!("mtcut: error: {e}");
            if e.is::<Usage>() {
                ExitCode::from(2)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}
