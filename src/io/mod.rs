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
    write_meshes(&[(path.as_ref(), mesh)])
}

/// Writes several meshes, each as [`write_mesh`] would, all or none: every file is
/// written beside its destination first and they replace what was there only once all
/// are written, so a failure (a full disk, a destination that is a folder) leaves no part
/// of the set behind (`mtcut cut --separate` writes its parts so).
pub fn write_meshes(meshes: &[(&Path, &TetMesh)]) -> Result<(), IoError> {
    let mut files: Vec<(std::path::PathBuf, Vec<u8>)> = Vec::new();
    for &(path, mesh) in meshes {
        match extension(path).as_str() {
            "vtu" => {
                let mut out = Vec::new();
                encode_vtu(mesh, &VtuOptions::DEFAULT, &mut out)
                    .map_err(|e| IoError::malformed(path, e))?;
                files.push((path.to_path_buf(), out));
            }
            "node" | "ele" => files.extend(tetgen::tetgen_files(path, mesh)),
            _ => return Err(IoError::new(path, IoErrorKind::UnknownOutputFormat)),
        }
    }
    let list: Vec<(&Path, &[u8])> = files.iter().map(|(p, b)| (p.as_path(), &b[..])).collect();
    write_files(&list).map_err(|(i, e)| IoError::new(list[i].0, e))
}

fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}
