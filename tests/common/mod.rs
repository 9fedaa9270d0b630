//! Helpers shared by the integration tests.
#![allow(dead_code)] // each test binary uses a different subset

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A file of tests/data.
pub fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// A fresh scratch folder for one test. Its name is a hash of `test`, so that no message
/// naming a file in it can contain a word a test looks for.
pub fn scratch(test: &str) -> PathBuf {
    let h = test.bytes().fold(0xcbf29ce484222325u64, |h, b| {
        (h ^ b as u64).wrapping_mul(0x100000001b3)
    });
    let dir = std::env::temp_dir().join(format!("mtcut-{h:016x}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// Runs the `mtcut` binary with `args`.
pub fn mtcut(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mtcut"))
        .args(args)
        .output()
        .expect("mtcut runs")
}

/// Whether VTK's Python is available. Missing VTK fails the test under CI (which installs
/// it) and skips it, loudly, elsewhere.
pub fn vtk_python() -> bool {
    let ok = Command::new("/usr/bin/python3")
        .args(["-c", "import vtk"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    if !ok {
        assert!(
            std::env::var_os("CI").is_none(),
            "VTK's Python (/usr/bin/python3 with python3-vtk9) is required under CI"
        );
        eprintln!("skipped: VTK Python not found (apt-get install python3-vtk9)");
    }
    ok
}

/// Runs a script of scripts/vtk with VTK's Python; returns its stdout.
pub fn vtk_script(script: &str, args: &[&str]) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scripts/vtk")
        .join(script);
    let out = Command::new("/usr/bin/python3")
        .arg(&path)
        .args(args)
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "{script} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8 output")
}
