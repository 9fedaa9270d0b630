//! Files in and out: VTK `.vtu`, TetGen `.node/.ele`, medit `.mesh`, ParaView `.pvd`.
//!
//! Readers turn files into a checked [`TetMesh`] (through [`TetMesh::from_arrays`], so
//! negative tets are re-oriented and invalid meshes rejected) and report what they
//! repaired; every error names the file, the line or element, and the problem. Readers
//! never panic, whatever the bytes. This layer sits on `mesh` and knows nothing of the MT
//! or of cuts.

mod error;
mod medit;
mod pvd;
mod replace;
mod tetgen;
mod vtu;

pub use error::{IoError, IoErrorKind};
pub use medit::{MEDIT_REF, parse_medit, read_medit};
pub use pvd::{PvdEntry, write_pvd};
pub(crate) use replace::write_files;
pub use tetgen::{parse_tetgen, read_tetgen, write_tetgen};
pub use vtu::{
    VtuCompression, VtuEncoding, VtuOptions, encode_vtu, parse_vtu, read_vtu, write_vtu,
};

use crate::mesh::{ImportReport, TetMesh};
use std::path::Path;

/// Reads a mesh, choosing the format from the extension: `.vtu`, `.node` or `.ele`
/// (TetGen; the other file of the pair is found beside it), `.mesh` (medit).
pub fn read_mesh(path: impl AsRef<Path>) -> Result<(TetMesh, ImportReport), IoError> {
    let path = path.as_ref();
    match extension(path).as_str() {
        "vtu" => read_vtu(path),
        "node" | "ele" => read_tetgen(path),
        "mesh" => read_medit(path),
        _ => Err(IoError::new(path, IoErrorKind::UnknownFormat)),
    }
}

/// Writes a mesh, choosing the format from the extension: `.vtu` (with
/// [`VtuOptions::DEFAULT`]: binary, zlib-compressed) or `.node` / `.ele` (writes both).
pub fn write_mesh(path: impl AsRef<Path>, mesh: &TetMesh) -> Result<(), IoError> {
    let path = path.as_ref();
    match extension(path).as_str() {
        "vtu" => write_vtu(path, mesh, &VtuOptions::DEFAULT),
        "node" | "ele" => write_tetgen(path, mesh),
        _ => Err(IoError::new(path, IoErrorKind::UnknownOutputFormat)),
    }
}

fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}
