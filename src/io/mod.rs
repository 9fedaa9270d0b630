//! Files in and out: TetGen `.node/.ele`.
//!
//! Readers turn files into a checked [`TetMesh`] (through [`TetMesh::from_arrays`], so
//! negative tets are re-oriented and invalid meshes rejected) and report what they
//! repaired; every error names the file, the line or element, and the problem.

mod error;
mod tetgen;

pub use error::{IoError, IoErrorKind};
pub use tetgen::{parse_tetgen, read_tetgen, write_tetgen};

use crate::mesh::{ImportReport, TetMesh};
use std::path::Path;

/// Reads a mesh, choosing the format from the extension: `.node` or `.ele` (TetGen; the
/// other file of the pair is found beside it).
pub fn read_mesh(path: impl AsRef<Path>) -> Result<(TetMesh, ImportReport), IoError> {
    let path = path.as_ref();
    match extension(path).as_str() {
        "node" | "ele" => read_tetgen(path),
        _ => Err(IoError::new(path, IoErrorKind::UnknownFormat)),
    }
}

/// Writes a mesh, choosing the format from the extension: `.node` or `.ele` (writes both).
pub fn write_mesh(path: impl AsRef<Path>, mesh: &TetMesh) -> Result<(), IoError> {
    let path = path.as_ref();
    match extension(path).as_str() {
        "node" | "ele" => write_tetgen(path, mesh),
        _ => Err(IoError::new(path, IoErrorKind::UnknownFormat)),
    }
}

fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}
