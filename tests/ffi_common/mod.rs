//! Helpers shared by the C ABI tests: the last error message, and asserting a success or
//! a refusal as a C caller sees them.
#![allow(dead_code)] // each test binary uses its own subset

use mtcut::ffi::*;
use std::ffi::CStr;

pub fn last_error() -> String {
    unsafe { CStr::from_ptr(mtcut_last_error_message()) }
        .to_str()
        .unwrap()
        .to_owned()
}

#[track_caller]
pub fn ok(status: mtcut_status) {
    assert_eq!(status, MTCUT_STATUS_OK, "{}", last_error());
}

/// Asserts a refusal: `expected`, with a message naming `function` and containing `needle`.
#[track_caller]
pub fn refused(status: mtcut_status, expected: mtcut_status, function: &str, needle: &str) {
    let message = last_error();
    assert_eq!(status, expected, "message: {message}");
    assert!(
        message.starts_with(&format!("{function}: ")) && message.contains(needle),
        "{message:?} should name {function} and contain {needle:?}"
    );
}
