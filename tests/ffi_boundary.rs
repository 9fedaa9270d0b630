//! Every `extern "C"` function of src/ffi runs its body behind the panic boundary
//! (`run` / `run_count`, which also record the message under the function's own name), or
//! is one of the few that cannot fail. A function added without it would let a panic
//! unwind into C, which aborts the host.

use std::path::Path;

/// Functions that need no boundary: they return static data, or catch panics themselves
/// (the `*_free` functions, which have no status to report with).
const NO_STATUS: [&str; 10] = [
    "mtcut_status_message",
    "mtcut_last_error_message",
    "mtcut_version",
    "mtcut_version_major",
    "mtcut_version_minor",
    "mtcut_version_patch",
    "mtcut_mesh_free",
    "mtcut_mt_free",
    "mtcut_frontier_free",
    "mtcut_live_free",
];

#[test]
fn every_entry_point_is_guarded_under_its_own_name() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/ffi");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let source = std::fs::read_to_string(&path).unwrap();
        for (start, _) in source.match_indices("extern \"C\" fn ") {
            let rest = &source[start + "extern \"C\" fn ".len()..];
            let name = &rest[..rest.find('(').unwrap()];
            // The body: up to the first line that closes an item.
            let body = &rest[..rest.find("\n}\n").unwrap_or(rest.len())];
            seen += 1;
            if NO_STATUS.contains(&name) {
                assert!(
                    !body.contains("run(") && !body.contains("run_count("),
                    "{name} is listed as unguarded but uses the boundary: update NO_STATUS"
                );
                continue;
            }
            let guarded = body.contains(&format!("run(\"{name}\""))
                || body.contains(&format!("run_count(\"{name}\""));
            assert!(
                guarded,
                "{}: {name} does not run its body through guard::run(\"{name}\", ...)",
                path.display()
            );
        }
    }
    assert!(seen >= 30, "found only {seen} extern \"C\" functions");
}
