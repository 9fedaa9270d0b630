//! Gives the shared library its SONAME, `libmtcut.so.MAJOR`: without one (a Rust cdylib
//! has none by default) programs record the bare file name they linked against, and the
//! usual libmtcut.so → libmtcut.so.MAJOR → libmtcut.so.MAJOR.MINOR.PATCH links of an
//! install would not let two major versions live side by side.

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    let major = std::env::var("CARGO_PKG_VERSION_MAJOR").unwrap_or_default();
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    // ELF platforms whose linkers take -soname; macOS (install names) and Windows (DLLs)
    // have other mechanisms.
    if matches!(
        os.as_str(),
        "linux" | "android" | "freebsd" | "netbsd" | "openbsd"
    ) {
        println!("cargo::rustc-cdylib-link-arg=-Wl,-soname,libmtcut.so.{major}");
    }
}
