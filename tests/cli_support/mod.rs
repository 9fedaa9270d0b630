//! Helpers of the command-line tests (tests/cli*.rs): run `mtcut`, check its exit, its
//! messages and its JSON, and read back and validate what it wrote.
#![allow(dead_code)] // each test binary uses a different subset

use crate::common::mtcut;
use mtcut::mesh::TetMesh;
use serde_json::Value;
use std::path::Path;
use std::process::Output;

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `p` as a `&str` (test paths are UTF-8).
pub fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 test path")
}

/// Runs `mtcut args`, which must succeed; returns its stdout.
pub fn ok(args: &[&str]) -> String {
    let o = mtcut(args);
    assert!(
        o.status.success(),
        "mtcut {args:?} failed ({:?}): {}",
        o.status.code(),
        stderr(&o)
    );
    assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
    stdout(&o)
}

/// Runs `mtcut args` (which must include `--json`) and parses its stdout as one object.
pub fn json(args: &[&str]) -> Value {
    let out = ok(args);
    let v: Value = serde_json::from_str(&out)
        .unwrap_or_else(|e| panic!("mtcut {args:?}: not one JSON object ({e}): {out}"));
    assert!(v.is_object(), "{v}");
    v
}

/// Asserts every key is present in `j`.
pub fn has_keys(j: &Value, keys: &[&str]) {
    for k in keys {
        assert!(j.get(k).is_some(), "missing key '{k}' in {j}");
    }
}

/// Runs `mtcut args`, which must fail with a non-zero exit and a message on stderr
/// containing every one of `needles` (case-sensitive), without panicking; returns stderr.
pub fn fails(args: &[&str], needles: &[&str]) -> String {
    let o = mtcut(args);
    let err = stderr(&o);
    assert!(
        !o.status.success(),
        "mtcut {args:?} should fail; stdout: {}",
        stdout(&o)
    );
    assert!(
        matches!(o.status.code(), Some(1) | Some(2)),
        "exit code {:?} (a signal?): {err}",
        o.status.code()
    );
    assert!(!err.contains("panicked"), "panic: {err}");
    for n in needles {
        assert!(
            err.contains(n),
            "mtcut {args:?}: message lacks '{n}': {err}"
        );
    }
    err
}

/// Reads a mesh mtcut wrote, checks it is valid, and returns it.
pub fn read_valid(path: &Path) -> TetMesh {
    let (mesh, report) = mtcut::io::read_mesh(path)
        .unwrap_or_else(|e| panic!("reading back {}: {e}", path.display()));
    let v = mesh.validate();
    assert!(v.is_valid(), "{}: {v:?}", path.display());
    assert_eq!(report.reoriented_tets, 0, "{}", path.display());
    mesh
}

/// |a - b| ≤ rel × |b|.
pub fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs()
}
