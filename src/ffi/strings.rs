//! Strings going out to C, into a buffer the caller owns.
//!
//! Two rules, both stated in the header: *data* (an attribute name) is copied whole or not
//! at all (`MTCUT_STATUS_BUFFER_TOO_SMALL`), because a truncated name would silently name
//! something else; *diagnostics* (a validation message) are truncated like `snprintf`,
//! because a shortened message is still a message. Either way the caller learns the full
//! length (without the NUL) to size a buffer, and the result is always NUL-terminated.

use super::guard::OutSlice;
use super::status::{Failure, FfiResult, MTCUT_STATUS_BUFFER_TOO_SMALL};
use std::ffi::c_char;

/// Where a string goes: `capacity` bytes at `buffer` (NULL allowed when `capacity` is 0,
/// to ask for the length only).
pub(crate) struct StringOut {
    buffer: Option<OutSlice<c_char>>,
    capacity: usize,
}

impl StringOut {
    /// # Safety
    /// A non-NULL `buffer` must be valid for writing `capacity` bytes.
    pub unsafe fn new(buffer: *mut c_char, capacity: usize, arg: &'static str) -> FfiResult<Self> {
        let buffer = if buffer.is_null() && capacity == 0 {
            None
        } else {
            // SAFETY: forwarded contract.
            Some(unsafe { OutSlice::new(buffer, capacity, arg) }?)
        };
        Ok(StringOut { buffer, capacity })
    }

    /// Copies all of `text` and a NUL, or fails with `MTCUT_STATUS_BUFFER_TOO_SMALL`
    /// writing nothing.
    pub fn write_whole(self, text: &str, what: &str) -> FfiResult<()> {
        let bytes = nul_terminated(text);
        match self.buffer {
            Some(out) if bytes.len() <= self.capacity => out.write(&bytes, 1, "bytes"),
            _ => Err(Failure::new(
                MTCUT_STATUS_BUFFER_TOO_SMALL,
                format!(
                    "{what} needs {} bytes with its NUL, the buffer has {}",
                    bytes.len(),
                    self.capacity
                ),
            )),
        }
    }

    /// Copies as much of `text` as fits (cut at a character boundary) and a NUL; with no
    /// buffer, writes nothing.
    pub fn write_truncated(self, text: &str) -> FfiResult<()> {
        let Some(out) = self.buffer else {
            return Ok(());
        };
        let mut end = text.len().min(self.capacity.saturating_sub(1));
        while !text.is_char_boundary(end) {
            end -= 1;
        }
        out.write(&nul_terminated(&text[..end]), 1, "bytes")
    }
}

/// `text` as C bytes with a final NUL.
fn nul_terminated(text: &str) -> Vec<c_char> {
    text.bytes()
        .map(|b| b as c_char)
        .chain(std::iter::once(0))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    #[test]
    fn whole_or_nothing_and_truncation_at_a_char_boundary() {
        let mut buf = [b'x' as c_char; 6];
        let out = unsafe { StringOut::new(buf.as_mut_ptr(), 5, "name") }.unwrap();
        let err = out.write_whole("hello", "the name").unwrap_err();
        assert_eq!(err.status, MTCUT_STATUS_BUFFER_TOO_SMALL);
        assert!(buf.iter().all(|&b| b == b'x' as c_char));
        let out = unsafe { StringOut::new(buf.as_mut_ptr(), 6, "name") }.unwrap();
        out.write_whole("hello", "the name").unwrap();
        assert_eq!(unsafe { CStr::from_ptr(buf.as_ptr()) }, c"hello");
        // "é" is two bytes: a 3-byte buffer holds "a" and the NUL, not half of "é".
        let out = unsafe { StringOut::new(buf.as_mut_ptr(), 3, "m") }.unwrap();
        out.write_truncated("aé").unwrap();
        assert_eq!(unsafe { CStr::from_ptr(buf.as_ptr()) }, c"a");
        let none = unsafe { StringOut::new(std::ptr::null_mut(), 0, "m") }.unwrap();
        none.write_truncated("anything").unwrap();
    }
}
