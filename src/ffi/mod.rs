//! The stable C ABI: `extern "C"` functions over opaque handles, declared in
//! `include/mtcut.h` (generated from this module by a pinned cbindgen; never edit it by
//! hand, run `scripts/gen-header.sh`).
//!
//! This layer owns the boundary between C and the library, and nothing else: it turns C
//! arguments into Rust values (checking every pointer, length and enum), calls the library,
//! and turns results into status codes, messages and C outputs. It holds no algorithm; it
//! is the only module of the crate allowed to contain `unsafe` code.
//!
//! Conventions (DESIGN.md §7; stated for C users in the header's preamble, `cbindgen.toml`):
//! * opaque handles (`mtcut_mesh`, `mtcut_mt`, `mtcut_frontier`, `mtcut_live`), created by `mtcut_<object>_<verb>` functions into an
//!   `out` argument and released by `mtcut_<object>_free`;
//! * every fallible function returns an `mtcut_status` with a fixed value
//!   (module `status`), and leaves a message for `mtcut_last_error_message` (module
//!   `error`);
//! * every entry point runs behind a panic boundary (module `guard`): a panic would otherwise
//!   unwind into C, which aborts the host program;
//! * outputs are written only on success, and nothing the caller owns is modified on
//!   failure;
//! * enums arrive as `uint32_t` and are validated before use, because an out-of-range
//!   value in a Rust enum is undefined behaviour;
//! * structs that may grow start with `struct_size` (module `versioned`).

#![allow(non_camel_case_types)]

// The header lists the exported items in this order (cbindgen follows it; the blank lines
// keep rustfmt from sorting them): status and errors, versions, meshes, their measures,
// their attributes, cuts, multi-tessellations.
mod status;

mod error;

mod version;

mod mesh;

mod measure;

mod attributes;

mod cut;

mod mt;

mod live;

mod guard;
mod strings;
mod versioned;

pub use attributes::*;
pub use cut::*;
pub use error::*;
pub use live::*;
pub use measure::*;
pub use mesh::*;
pub use mt::*;
pub use status::*;
pub use version::*;
