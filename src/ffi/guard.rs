//! The panic boundary and the argument checks every entry point goes through.
//!
//! Each `extern "C"` function is a thin shell: it names itself and hands a closure to
//! [`run`] (or [`run_count`]). The closure first checks every argument (NULL, alignment,
//! lengths) with the helpers here, then does the work, then writes the outputs - so a
//! failure leaves the caller's memory untouched. `run` catches panics, which must never
//! unwind into C, and records the message of any failure for `mtcut_last_error_message`.

use super::error;
use super::status::{
    Failure, FfiResult, MTCUT_STATUS_INTERNAL_PANIC, MTCUT_STATUS_NULL_ARGUMENT, MTCUT_STATUS_OK,
    mtcut_status,
};
use std::any::Any;
use std::ffi::{CStr, c_char};
use std::panic::{AssertUnwindSafe, catch_unwind};

/// Runs `body` for the C function `function`: its status on return, the message recorded.
pub(crate) fn run(function: &'static str, body: impl FnOnce() -> FfiResult<()>) -> mtcut_status {
    match catch(function, body) {
        Ok(()) => MTCUT_STATUS_OK,
        Err(status) => status,
    }
}

/// Like [`run`], for functions that return a count directly: 0 on failure (the message
/// recorded as usual).
pub(crate) fn run_count(function: &'static str, body: impl FnOnce() -> FfiResult<usize>) -> usize {
    catch(function, body).unwrap_or(0)
}

fn catch<T>(
    function: &'static str,
    body: impl FnOnce() -> FfiResult<T>,
) -> Result<T, mtcut_status> {
    // AssertUnwindSafe: after a panic the handles involved are reported as untrustworthy
    // (MTCUT_STATUS_INTERNAL_PANIC's documentation); nothing else is shared.
    let failure = match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(value)) => {
            error::clear();
            return Ok(value);
        }
        Ok(Err(failure)) => failure,
        Err(payload) => Failure::new(
            MTCUT_STATUS_INTERNAL_PANIC,
            format!("internal panic: {}", panic_text(payload.as_ref())),
        ),
    };
    error::set(function, &failure.message);
    Err(failure.status)
}

fn panic_text(payload: &(dyn Any + Send)) -> &str {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s
    } else {
        "(no message)"
    }
}

fn null(arg: &str) -> Failure {
    Failure::new(
        MTCUT_STATUS_NULL_ARGUMENT,
        format!("argument `{arg}` is NULL"),
    )
}

fn check_ptr<T>(p: *const T, arg: &str) -> FfiResult<()> {
    if p.is_null() {
        return Err(null(arg));
    }
    if !p.is_aligned() {
        return Err(Failure::invalid(format!(
            "argument `{arg}` is not aligned for its type ({} bytes)",
            align_of::<T>()
        )));
    }
    Ok(())
}

/// `p` as a reference, after the NULL and alignment checks.
///
/// # Safety
/// A non-NULL `p` must point to a live `T` that nothing mutates while the reference lives.
pub(crate) unsafe fn deref<'a, T>(p: *const T, arg: &str) -> FfiResult<&'a T> {
    check_ptr(p, arg)?;
    // SAFETY: non-NULL and aligned (checked); validity is the caller's contract.
    Ok(unsafe { &*p })
}

/// `p` as a mutable reference, after the NULL and alignment checks.
///
/// # Safety
/// A non-NULL `p` must point to a live `T` that nothing else accesses while the reference
/// lives.
pub(crate) unsafe fn deref_mut<'a, T>(p: *mut T, arg: &str) -> FfiResult<&'a mut T> {
    check_ptr(p, arg)?;
    // SAFETY: non-NULL and aligned (checked); exclusivity is the caller's contract.
    Ok(unsafe { &mut *p })
}

/// `len` elements at `p`, after the NULL, alignment and size checks.
///
/// # Safety
/// A non-NULL `p` must point to `len` initialised elements that nothing mutates while the
/// slice lives.
pub(crate) unsafe fn slice<'a, T>(p: *const T, len: usize, arg: &str) -> FfiResult<&'a [T]> {
    check_ptr(p, arg)?;
    if len
        .checked_mul(size_of::<T>())
        .is_none_or(|b| b > isize::MAX as usize)
    {
        return Err(Failure::invalid(format!(
            "argument `{arg}`: {len} elements do not fit in memory"
        )));
    }
    // SAFETY: non-NULL, aligned, size in range (checked); the elements are the caller's
    // contract.
    Ok(unsafe { std::slice::from_raw_parts(p, len) })
}

/// A NUL-terminated string argument.
///
/// # Safety
/// A non-NULL `p` must point to a NUL-terminated string that lives through the call.
pub(crate) unsafe fn c_str<'a>(p: *const c_char, arg: &str) -> FfiResult<&'a CStr> {
    if p.is_null() {
        return Err(null(arg));
    }
    // SAFETY: non-NULL (checked); termination is the caller's contract.
    Ok(unsafe { CStr::from_ptr(p) })
}

/// An output location, checked (NULL, alignment) before any work is done and written
/// only once the work has succeeded.
pub(crate) struct Out<T> {
    p: *mut T,
}

impl<T> Out<T> {
    /// # Safety
    /// A non-NULL `p` must be valid for writing a `T` until [`write`](Self::write).
    pub unsafe fn new(p: *mut T, arg: &str) -> FfiResult<Out<T>> {
        check_ptr(p, arg)?;
        Ok(Out { p })
    }

    /// An output the caller may pass as NULL to say it does not want it.
    ///
    /// # Safety
    /// As [`new`](Self::new).
    pub unsafe fn optional(p: *mut T, arg: &str) -> FfiResult<Option<Out<T>>> {
        if p.is_null() {
            return Ok(None);
        }
        // SAFETY: forwarded contract.
        unsafe { Out::new(p, arg) }.map(Some)
    }

    pub fn write(self, value: T) {
        // SAFETY: checked non-NULL and aligned in `new`; writable per its contract. `write`
        // does not drop the old content, which may be uninitialised C memory.
        unsafe { self.p.write(value) }
    }

    pub fn as_ptr(&self) -> *mut T {
        self.p
    }
}

/// An output array of `capacity` elements, checked before any work is done.
pub(crate) struct OutSlice<T> {
    p: *mut T,
    capacity: usize,
    arg: &'static str,
}

impl<T: Copy> OutSlice<T> {
    /// # Safety
    /// A non-NULL `p` must be valid for writing `capacity` elements until
    /// [`write`](Self::write).
    pub unsafe fn new(p: *mut T, capacity: usize, arg: &'static str) -> FfiResult<OutSlice<T>> {
        check_ptr(p, arg)?;
        Ok(OutSlice { p, capacity, arg })
    }

    /// Copies `values` to the start of the array, or fails with
    /// `MTCUT_STATUS_BUFFER_TOO_SMALL` (writing nothing) when they do not fit; `unit`
    /// names what the capacity counts, for the message.
    pub fn write(self, values: &[T], per_unit: usize, unit: &str) -> FfiResult<()> {
        if values.len() > self.capacity.saturating_mul(per_unit) {
            return Err(Failure::new(
                super::status::MTCUT_STATUS_BUFFER_TOO_SMALL,
                format!(
                    "argument `{}` holds {} {unit}, {} are needed",
                    self.arg,
                    self.capacity,
                    values.len() / per_unit
                ),
            ));
        }
        // SAFETY: checked non-NULL and aligned in `new`; the caller promised `capacity`
        // writable elements and we write at most that many (checked just above). C memory
        // never overlaps the library's own vectors.
        unsafe { std::ptr::copy_nonoverlapping(values.as_ptr(), self.p, values.len()) };
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ffi::mtcut_last_error_message;

    #[test]
    fn a_panic_becomes_a_status_and_a_message() {
        let status = run("mtcut_test", || panic!("boom {}", 42));
        assert_eq!(status, MTCUT_STATUS_INTERNAL_PANIC);
        let message = unsafe { CStr::from_ptr(mtcut_last_error_message()) };
        assert_eq!(
            message.to_str().unwrap(),
            "mtcut_test: internal panic: boom 42"
        );
        assert_eq!(run_count("mtcut_test", || panic!("static")), 0);
        assert_eq!(run("mtcut_test", || Ok(())), MTCUT_STATUS_OK);
        assert_eq!(unsafe { CStr::from_ptr(mtcut_last_error_message()) }, c"");
    }

    #[test]
    fn misaligned_pointers_are_refused() {
        let buffer = [0u64; 2];
        let p = (buffer.as_ptr() as *const u8).wrapping_add(1) as *const f64;
        let err = unsafe { slice(p, 1, "xyz") }.unwrap_err();
        assert_eq!(err.status, crate::ffi::MTCUT_STATUS_INVALID_ARGUMENT);
        assert!(
            err.message.contains("`xyz` is not aligned"),
            "{}",
            err.message
        );
        let err = unsafe { slice(std::ptr::dangling::<f64>(), usize::MAX / 4, "xyz") }.unwrap_err();
        assert!(err.message.contains("do not fit"), "{}", err.message);
    }
}
