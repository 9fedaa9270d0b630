//! ParaView collection files (`.pvd`): time series and multi-part outputs as one file
//! ParaView opens, listing `.vtu` files with their time step and part number.

use super::error::IoError;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One data set of a collection: `file` at time `timestep`, as part `part` (parts of one
/// time step are shown together, e.g. the two halves of a cut object).
#[derive(Clone, Debug, PartialEq)]
pub struct PvdEntry {
    pub timestep: f64,
    pub part: u32,
    /// The data file; a relative path is relative to the `.pvd` file's directory, which
    /// is how ParaView resolves it.
    pub file: PathBuf,
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Writes a `.pvd` collection listing `entries` in the given order.
pub fn write_pvd(path: &Path, entries: &[PvdEntry]) -> Result<(), IoError> {
    let mut x = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for e in entries {
        if !e.timestep.is_finite() {
            return Err(IoError::malformed(
                path,
                format!(
                    "time step {} of '{}' is not a finite number",
                    e.timestep,
                    e.file.display()
                ),
            ));
        }
        let file = e.file.to_str().ok_or_else(|| {
            IoError::malformed(
                path,
                format!("file name '{}' is not valid UTF-8", e.file.display()),
            )
        })?;
        // `{:?}` writes the shortest decimal that reads back to the same double.
        let _ = writeln!(
            x,
            "    <DataSet timestep=\"{:?}\" group=\"\" part=\"{}\" file=\"{}\"/>",
            e.timestep,
            e.part,
            escape(file)
        );
    }
    x.push_str("  </Collection>\n</VTKFile>\n");
    crate::io::write_files(&[(path, x.as_bytes())]).map_err(|(_, e)| IoError::new(path, e))
}
