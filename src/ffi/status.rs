//! Status codes: fixed numeric values, never renumbered; new codes get new numbers.
//!
//! The type is a plain `uint32_t` with `#define`d values rather than a Rust enum, because a
//! C caller can hand any number back to `mtcut_status_message`, and an out-of-range value
//! in a Rust enum would be undefined behaviour.

use crate::io::{IoError, IoErrorKind};
use crate::mesh::MeshError;
use std::ffi::c_char;

/// The result of every fallible mtcut function: `MTCUT_STATUS_OK` (0) or one of the
/// `MTCUT_STATUS_*` error codes below, whose values never change. On an error,
/// `mtcut_last_error_message()` says what went wrong.
pub type mtcut_status = u32;

/// Success.
pub const MTCUT_STATUS_OK: mtcut_status = 0;
/// A pointer argument that may not be NULL was NULL.
pub const MTCUT_STATUS_NULL_ARGUMENT: mtcut_status = 1;
/// An argument is out of its range: an unknown enum value, a count that does not match,
/// an index past the end, an empty or non-UTF-8 name, a non-finite coordinate, a
/// `struct_size` this library does not know.
pub const MTCUT_STATUS_INVALID_ARGUMENT: mtcut_status = 2;
/// An output buffer is smaller than the data; nothing was written to it (the functions
/// that report the size needed say how).
pub const MTCUT_STATUS_BUFFER_TOO_SMALL: mtcut_status = 3;
/// A named thing (an attribute column) does not exist.
pub const MTCUT_STATUS_NOT_FOUND: mtcut_status = 4;
/// The arrays or the file describe no valid tetrahedral mesh (an index out of range, a
/// flat tet, a face shared by three tets, a non-manifold boundary...).
pub const MTCUT_STATUS_INVALID_MESH: mtcut_status = 5;
/// The operating system refused a file operation (missing file, no permission, disk full).
pub const MTCUT_STATUS_IO_ERROR: mtcut_status = 6;
/// A file's content is malformed (syntax, truncated data, bad numbers).
pub const MTCUT_STATUS_PARSE_ERROR: mtcut_status = 7;
/// A file name's extension names no format mtcut reads or writes.
pub const MTCUT_STATUS_UNSUPPORTED_FORMAT: mtcut_status = 8;
/// A long operation was stopped by its progress callback.
pub const MTCUT_STATUS_CANCELLED: mtcut_status = 9;
/// A resolution change was refused because queued cut work is still pending on the
/// model (finish it first).
pub const MTCUT_STATUS_PENDING_WORK: mtcut_status = 10;
/// A bug in mtcut: a panic was caught at the boundary instead of aborting the host. The
/// handles passed to the failed call can still be freed, but their content should not be
/// trusted; please report the message.
pub const MTCUT_STATUS_INTERNAL_PANIC: mtcut_status = 11;

/// A static, NUL-terminated description of `status` (never NULL; unknown codes get
/// "unknown status code"). The text describes the code in general; the specific cause
/// of the last failure is in `mtcut_last_error_message()`.
#[unsafe(no_mangle)]
pub extern "C" fn mtcut_status_message(status: mtcut_status) -> *const c_char {
    let text: &'static std::ffi::CStr = match status {
        MTCUT_STATUS_OK => c"success",
        MTCUT_STATUS_NULL_ARGUMENT => c"a required pointer argument was NULL",
        MTCUT_STATUS_INVALID_ARGUMENT => c"an argument is out of its range",
        MTCUT_STATUS_BUFFER_TOO_SMALL => c"the output buffer is too small",
        MTCUT_STATUS_NOT_FOUND => c"no such attribute",
        MTCUT_STATUS_INVALID_MESH => c"the input is not a valid tetrahedral mesh",
        MTCUT_STATUS_IO_ERROR => c"a file could not be read or written",
        MTCUT_STATUS_PARSE_ERROR => c"a file's content is malformed",
        MTCUT_STATUS_UNSUPPORTED_FORMAT => c"unsupported file format",
        MTCUT_STATUS_CANCELLED => c"cancelled by the progress callback",
        MTCUT_STATUS_PENDING_WORK => c"refused while queued cut work is pending",
        MTCUT_STATUS_INTERNAL_PANIC => c"internal error in mtcut (a bug; please report it)",
        _ => c"unknown status code",
    };
    text.as_ptr()
}

/// A failed call: its status and the specific message for `mtcut_last_error_message`.
#[derive(Debug)]
pub(crate) struct Failure {
    pub status: mtcut_status,
    pub message: String,
}

impl Failure {
    pub fn new(status: mtcut_status, message: impl Into<String>) -> Failure {
        Failure {
            status,
            message: message.into(),
        }
    }

    pub fn invalid(message: impl Into<String>) -> Failure {
        Failure::new(MTCUT_STATUS_INVALID_ARGUMENT, message)
    }
}

impl From<MeshError> for Failure {
    fn from(e: MeshError) -> Failure {
        Failure::new(MTCUT_STATUS_INVALID_MESH, e.to_string())
    }
}

impl From<IoError> for Failure {
    fn from(e: IoError) -> Failure {
        let status = match &e.kind {
            IoErrorKind::Os(_) => MTCUT_STATUS_IO_ERROR,
            IoErrorKind::UnknownFormat | IoErrorKind::UnknownOutputFormat => {
                MTCUT_STATUS_UNSUPPORTED_FORMAT
            }
            IoErrorKind::AtLine { .. } | IoErrorKind::Malformed(_) => MTCUT_STATUS_PARSE_ERROR,
            IoErrorKind::InvalidMesh { .. } => MTCUT_STATUS_INVALID_MESH,
        };
        Failure::new(status, e.to_string())
    }
}

pub(crate) type FfiResult<T> = Result<T, Failure>;

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    #[test]
    fn every_code_has_its_own_message() {
        let text = |s| unsafe { CStr::from_ptr(mtcut_status_message(s)) }.to_owned();
        let known: Vec<_> = (0..=MTCUT_STATUS_INTERNAL_PANIC).map(text).collect();
        let unknown = text(MTCUT_STATUS_INTERNAL_PANIC + 1);
        for (i, t) in known.iter().enumerate() {
            assert!(!t.is_empty() && *t != unknown, "code {i}");
            assert_eq!(known.iter().filter(|u| *u == t).count(), 1, "code {i}");
        }
        assert_eq!(text(u32::MAX), unknown);
    }
}
