//! include/mtcut.h: up to date with src/ffi, versioned like Cargo.toml, valid C99 and C++17,
//! and every function in it exercised by the C NULL-argument test.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn header() -> String {
    std::fs::read_to_string(root().join("include/mtcut.h")).expect("include/mtcut.h")
}

/// Whether the pinned cbindgen is installed. Missing, it fails the test under CI (whose
/// script installs it) and skips it, loudly, elsewhere.
fn pinned_cbindgen() -> bool {
    let pin = std::fs::read_to_string(root().join("scripts/cbindgen-version")).unwrap();
    let found = Command::new("cbindgen")
        .arg("--version")
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
        .unwrap_or_default();
    let ok = found == format!("cbindgen {}", pin.trim());
    if !ok {
        assert!(
            std::env::var_os("CI").is_none(),
            "cbindgen {} is required under CI (found {found:?}); scripts/gen-header.sh --install-cbindgen",
            pin.trim()
        );
        eprintln!(
            "skipped: cbindgen {} not found (scripts/gen-header.sh --install-cbindgen)",
            pin.trim()
        );
    }
    ok
}

#[test]
fn header_is_up_to_date() {
    if !pinned_cbindgen() {
        return;
    }
    let fresh = common::scratch("ffi-header").join("mtcut.h");
    let out = Command::new(root().join("scripts/gen-header.sh"))
        .arg(&fresh)
        .output()
        .expect("scripts/gen-header.sh runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let fresh = std::fs::read_to_string(&fresh).unwrap();
    if fresh != header() {
        let first = fresh
            .lines()
            .zip(header().lines())
            .position(|(a, b)| a != b)
            .map_or("the end".to_owned(), |l| format!("line {}", l + 1));
        panic!("include/mtcut.h is stale (first difference at {first}): run scripts/gen-header.sh");
    }
}

/// The value of `#define NAME value` in the header.
fn define(header: &str, name: &str) -> String {
    let prefix = format!("#define {name} ");
    header
        .lines()
        .find_map(|l| l.strip_prefix(&prefix))
        .unwrap_or_else(|| panic!("no #define {name} in the header"))
        .trim()
        .to_owned()
}

/// Compiles `source` (C or C++ by `lang`) against the header with every warning an error,
/// runs the program when `run`, and returns its output.
fn compile(lang: &str, source: &str, run: bool) -> String {
    let dir = common::scratch(&format!("ffi-compile-{lang}-{run}"));
    let (compiler, ext, std) = match lang {
        "c" => ("cc", "c", "-std=c99"),
        _ => ("c++", "cpp", "-std=c++17"),
    };
    let src = dir.join(format!("main.{ext}"));
    std::fs::write(&src, source).unwrap();
    let exe = dir.join("main");
    let mut cmd = Command::new(compiler);
    cmd.args([std, "-pedantic", "-Wall", "-Wextra", "-Werror", "-I"])
        .arg(root().join("include"))
        .arg(&src);
    if run {
        cmd.arg("-o").arg(&exe);
    } else {
        cmd.arg("-fsyntax-only");
    }
    let out = cmd.output().unwrap_or_else(|e| panic!("{compiler}: {e}"));
    assert!(
        out.status.success(),
        "{compiler} {std} rejects the header:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    if !run {
        return String::new();
    }
    let out = Command::new(&exe).output().unwrap();
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn version_macros_match_cargo_toml() {
    let h = header();
    let toml = std::fs::read_to_string(root().join("Cargo.toml")).unwrap();
    let version = toml
        .lines()
        .find_map(|l| l.strip_prefix("version = \""))
        .and_then(|v| v.strip_suffix('"'))
        .expect("Cargo.toml has a version");
    let parts: Vec<&str> = version.split('.').collect();
    assert_eq!(define(&h, "MTCUT_VERSION_MAJOR"), parts[0]);
    assert_eq!(define(&h, "MTCUT_VERSION_MINOR"), parts[1]);
    assert_eq!(define(&h, "MTCUT_VERSION_PATCH"), parts[2]);
    // The string macro is assembled by the preprocessor: ask a compiler what it says.
    let printed = compile(
        "c",
        "#include <stdio.h>\n#include \"mtcut.h\"\nint main(void) { puts(MTCUT_VERSION_STRING); return 0; }\n",
        true,
    );
    assert_eq!(printed.trim(), version);
}

#[test]
fn header_compiles_as_c99_and_cpp17() {
    // Every declaration used, so that the compilers check the types, not only the syntax.
    let uses = "mtcut_mesh *m = 0; mtcut_mt *mt = 0; mtcut_frontier *f = 0; mtcut_quality q; \
                mtcut_location loc = MTCUT_LOCATION_TET; mtcut_status s = MTCUT_STATUS_OK; \
                mtcut_cut_options co; mtcut_cut_stats cs; mtcut_build_options bo; \
                mtcut_mt_stats ms; mtcut_extract_options eo; mtcut_extract_stats es; \
                mtcut_frontier_update_stats fs; mtcut_progress_callback cb = 0; \
                mtcut_cut_scheme sc = MTCUT_CUT_SCHEME_BIELSER17; \
                mtcut_error_metric em = MTCUT_ERROR_METRIC_QUALITY; \
                mtcut_focus_kind fk = MTCUT_FOCUS_BOX; \
                (void)m; (void)mt; (void)f; (void)loc; (void)s; q.struct_size = sizeof q; (void)q; \
                co.struct_size = sizeof co; (void)co; cs.struct_size = sizeof cs; (void)cs; \
                bo.struct_size = sizeof bo; bo.progress_or_null = cb; (void)bo; \
                ms.struct_size = sizeof ms; (void)ms; eo.struct_size = sizeof eo; (void)eo; \
                es.struct_size = sizeof es; (void)es; fs.struct_size = sizeof fs; (void)fs; \
                (void)sc; (void)em; (void)fk;";
    compile(
        "c",
        &format!("#include \"mtcut.h\"\nint main(void) {{ {uses} return 0; }}\n"),
        false,
    );
    compile(
        "cpp",
        &format!("#include \"mtcut.h\"\nint main() {{ {uses} return 0; }}\n"),
        false,
    );
}

#[test]
fn header_is_ascii() {
    // Compilers on other platforms read headers in the local code page.
    let h = header();
    if let Some((line, text)) = h.lines().enumerate().find(|(_, l)| !l.is_ascii()) {
        panic!("line {} of include/mtcut.h is not ASCII: {text}", line + 1);
    }
}

/// Names of the functions the header declares.
fn header_functions(header: &str) -> Vec<String> {
    header
        .lines()
        .filter(|l| !l.starts_with(' ') && !l.starts_with('#') && !l.starts_with('/'))
        .filter_map(|l| {
            let open = l.find('(')?;
            let name = l[..open].rsplit([' ', '*']).next()?;
            name.starts_with("mtcut_").then(|| name.to_owned())
        })
        .collect()
}

#[test]
fn null_argument_test_calls_every_function() {
    let functions = header_functions(&header());
    assert!(functions.len() >= 30, "found only {functions:?}");
    let test: PathBuf = root().join("c-examples/null_args.c");
    let source = std::fs::read_to_string(&test).expect("c-examples/null_args.c");
    let missing: Vec<&String> = functions
        .iter()
        .filter(|f| !source.contains(&format!("{f}(")))
        .collect();
    assert!(
        missing.is_empty(),
        "c-examples/null_args.c does not call {missing:?}: add a NULL/invalid-argument check"
    );
}
