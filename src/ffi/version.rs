//! The library's version, for the header (macros: the version compiled against) and at run
//! time (functions: the version loaded).
//!
//! The macros are literals because cbindgen reads source, not `env!`; the assertions below
//! stop the build when Cargo.toml's version moves without them, and a test compares the
//! header's macros with Cargo.toml.

use std::ffi::c_char;

/// Major version of the header: the ABI (and the shared library's SONAME,
/// `libmtcut.so.MAJOR`) stays compatible while it is unchanged.
pub const MTCUT_VERSION_MAJOR: u32 = 0;
/// Minor version of the header: grows when functions or struct fields are added.
pub const MTCUT_VERSION_MINOR: u32 = 1;
/// Patch version of the header.
pub const MTCUT_VERSION_PATCH: u32 = 0;

/// Parses a decimal number at compile time (Cargo's version components).
const fn parse_u32(s: &str) -> u32 {
    let bytes = s.as_bytes();
    let mut value = 0u32;
    let mut i = 0;
    while i < bytes.len() {
        assert!(bytes[i].is_ascii_digit(), "not a decimal number");
        value = value * 10 + (bytes[i] - b'0') as u32;
        i += 1;
    }
    value
}

const _: () = assert!(
    MTCUT_VERSION_MAJOR == parse_u32(env!("CARGO_PKG_VERSION_MAJOR"))
        && MTCUT_VERSION_MINOR == parse_u32(env!("CARGO_PKG_VERSION_MINOR"))
        && MTCUT_VERSION_PATCH == parse_u32(env!("CARGO_PKG_VERSION_PATCH")),
    "Cargo.toml's version changed: update MTCUT_VERSION_* in src/ffi/version.rs and run \
     scripts/gen-header.sh"
);

/// The version of the loaded library, as "MAJOR.MINOR.PATCH" (a static string; never
/// NULL). Compare with `MTCUT_VERSION_STRING`, the version of the header compiled against.
#[unsafe(no_mangle)]
pub extern "C" fn mtcut_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// The major version of the loaded library.
#[unsafe(no_mangle)]
pub extern "C" fn mtcut_version_major() -> u32 {
    MTCUT_VERSION_MAJOR
}

/// The minor version of the loaded library.
#[unsafe(no_mangle)]
pub extern "C" fn mtcut_version_minor() -> u32 {
    MTCUT_VERSION_MINOR
}

/// The patch version of the loaded library.
#[unsafe(no_mangle)]
pub extern "C" fn mtcut_version_patch() -> u32 {
    MTCUT_VERSION_PATCH
}
