//! The last error message, one per thread.
//!
//! Kept per thread so that two host threads calling mtcut at once never see each other's
//! messages. The buffer is reused: a successful call empties it without allocating.

use std::cell::RefCell;
use std::ffi::c_char;

thread_local! {
    /// The message bytes followed by one NUL; never contains another NUL.
    static LAST_ERROR: RefCell<Vec<u8>> = RefCell::new(vec![0]);
}

/// Replaces this thread's message with `function: message` (interior NULs, which C could
/// not show, become spaces).
pub(crate) fn set(function: &str, message: &str) {
    // `try_with` fails only while the thread is being torn down; there is nobody left to
    // read a message then.
    let _ = LAST_ERROR.try_with(|m| {
        let mut m = m.borrow_mut();
        m.clear();
        m.extend_from_slice(function.as_bytes());
        m.extend_from_slice(b": ");
        m.extend(message.bytes().map(|b| if b == 0 { b' ' } else { b }));
        m.push(0);
    });
}

/// Empties this thread's message (after a successful call).
pub(crate) fn clear() {
    let _ = LAST_ERROR.try_with(|m| {
        let mut m = m.borrow_mut();
        m.clear();
        m.push(0);
    });
}

/// The message of the last failed mtcut call on this thread, or "" when the last call
/// succeeded. Every function that returns an `mtcut_status` (or a count that can report
/// a NULL argument) replaces it; `mtcut_status_message`, `mtcut_last_error_message`,
/// `mtcut_version*` and `mtcut_*_free` leave it alone. Never NULL. The pointer stays
/// valid, and the text unchanged, until the next call of a function that replaces it on
/// the same thread; copy it to keep it longer. Do not free it.
#[unsafe(no_mangle)]
pub extern "C" fn mtcut_last_error_message() -> *const c_char {
    LAST_ERROR
        .try_with(|m| m.borrow().as_ptr().cast::<c_char>())
        .unwrap_or(c"".as_ptr())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    fn last() -> String {
        unsafe { CStr::from_ptr(mtcut_last_error_message()) }
            .to_str()
            .unwrap()
            .to_owned()
    }

    #[test]
    fn message_is_per_thread_and_cleared_by_success() {
        set("f", "bad\0input");
        assert_eq!(last(), "f: bad input");
        let other = std::thread::spawn(|| {
            let before = last();
            set("g", "other thread");
            (before, last())
        })
        .join()
        .unwrap();
        assert_eq!(other, (String::new(), "g: other thread".to_owned()));
        assert_eq!(last(), "f: bad input");
        clear();
        assert_eq!(last(), "");
    }
}
