//! The one error type of the file layer: which file, where in it, and what is wrong.

use crate::geom::out_of_range_text;
use crate::mesh::{MeshError, Numbering};
use std::fmt;
use std::path::{Path, PathBuf};

/// What went wrong, without the file name (which [`IoError`] adds).
#[derive(Debug, thiserror::Error)]
pub enum IoErrorKind {
    #[error("{0}")]
    Os(#[from] std::io::Error),
    #[error("unknown mesh format (expected .vtu, .node/.ele or .mesh)")]
    UnknownFormat,
    /// A mesh to write under an extension mtcut does not write (medit's `.mesh` is read
    /// only).
    #[error("unknown output format (mtcut writes .vtu, or .node/.ele)")]
    UnknownOutputFormat,
    /// A syntax or content error at a line (1-based) of a text file.
    #[error("line {line}: {message}")]
    AtLine { line: usize, message: String },
    /// A content error not tied to a line (binary data, XML structure).
    #[error("{0}")]
    Malformed(String),
    /// The mesh is readable but invalid. `message` names the culprit in the file's own
    /// words and numbers (its line, node and tetrahedron numbers: TetGen's and medit's
    /// count from 1 where the mesh's ids count from 0); `source` is the mesh's error.
    #[error("{message}")]
    InvalidMesh {
        message: String,
        #[source]
        source: MeshError,
    },
}

/// How a reader names what a file holds, for [`invalid_mesh`].
pub(crate) struct FileTerms<'a> {
    /// What the file calls a vertex ("node", "vertex", "point"), and vertices.
    pub vertex: &'a str,
    pub vertices: &'a str,
    /// What it calls tets ("tetrahedra", "cells").
    pub tets: &'a str,
    /// How it numbers them.
    pub numbering: Numbering,
    /// Said of a validation report's tet numbers when they are not the file's (", ...").
    pub tet_note: &'a str,
}

/// The error of a file whose mesh `TetMesh::from_arrays_numbered` rejected with `e`, in
/// the file's terms; `tet_at(t)` names tet `t` as the file does (its line and number), as
/// the subject of a sentence. Without this, a message read "line 3, tetrahedron 2: tet 1
/// uses vertex 4 more than once" for the file's node 5.
pub(crate) fn invalid_mesh(
    path: &Path,
    e: MeshError,
    terms: &FileTerms<'_>,
    tet_at: impl Fn(usize) -> String,
) -> IoError {
    let FileTerms {
        vertex: vw,
        vertices: vws,
        tets: tws,
        numbering: num,
        tet_note,
    } = *terms;
    let v = |i: u64| i + num.first_vertex;
    let message = match &e {
        MeshError::RepeatedVertex { tet, vertex } => {
            format!(
                "{} uses {vw} {} more than once",
                tet_at(*tet),
                v(*vertex as u64)
            )
        }
        MeshError::DegenerateTet { tet } => format!(
            "{} is degenerate: its four {vws} are coplanar (zero volume)",
            tet_at(*tet)
        ),
        MeshError::IndexOutOfRange {
            tet,
            index,
            n_vertices,
        } => format!(
            "{} uses {vw} {}, but the {vws} are numbered {}..{}",
            tet_at(*tet),
            v(*index),
            v(0),
            (*n_vertices as u64 + num.first_vertex).saturating_sub(1)
        ),
        MeshError::NonFiniteCoordinate { vertex } => {
            format!(
                "{vw} {} has a NaN or infinite coordinate",
                v(*vertex as u64)
            )
        }
        MeshError::CoordinateOutOfRange { vertex, value } => format!(
            "{vw} {} {}: rescale the mesh",
            v(*vertex as u64),
            out_of_range_text(*value)
        ),
        MeshError::Invalid(report) => format!(
            "{report}; numbered as in the file (vertices are its {vws}, tets its {tws}{tet_note})"
        ),
        MeshError::Empty | MeshError::TooLarge { .. } | MeshError::TooSmall { .. } => e.to_string(),
    };
    IoError::new(path, IoErrorKind::InvalidMesh { message, source: e })
}

/// A file error: the path and what is wrong.
#[derive(Debug)]
pub struct IoError {
    pub path: PathBuf,
    pub kind: IoErrorKind,
}

impl IoError {
    pub fn new(path: &Path, kind: impl Into<IoErrorKind>) -> IoError {
        IoError {
            path: path.to_path_buf(),
            kind: kind.into(),
        }
    }

    pub(crate) fn at_line(path: &Path, line: usize, message: impl Into<String>) -> IoError {
        IoError::new(
            path,
            IoErrorKind::AtLine {
                line,
                message: message.into(),
            },
        )
    }

    pub(crate) fn malformed(path: &Path, message: impl Into<String>) -> IoError {
        IoError::new(path, IoErrorKind::Malformed(message.into()))
    }
}

impl fmt::Display for IoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.kind)
    }
}

impl std::error::Error for IoError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.kind.source()
    }
}
