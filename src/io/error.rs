//! The one error type of the file layer: which file, where in it, and what is wrong.

use crate::mesh::MeshError;
use std::fmt;
use std::path::{Path, PathBuf};

/// What went wrong, without the file name (which [`IoError`] adds).
#[derive(Debug, thiserror::Error)]
pub enum IoErrorKind {
    #[error("{0}")]
    Os(#[from] std::io::Error),
    #[error("unknown mesh format (expected .vtu, .node/.ele or .mesh)")]
    UnknownFormat,
    /// A syntax or content error at a line (1-based) of a text file.
    #[error("line {line}: {message}")]
    AtLine { line: usize, message: String },
    /// A content error not tied to a line (binary data, XML structure).
    #[error("{0}")]
    Malformed(String),
    /// The mesh is readable but invalid; `element` says how the file numbers the culprit.
    #[error("{element}: {source}")]
    InvalidMesh {
        element: String,
        #[source]
        source: MeshError,
    },
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
