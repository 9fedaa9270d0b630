//! `mtcut build`, `mtcut extract` and `mtcut info` on `.mt` models: happy paths with the
//! outputs read back and checked against the input, and every bad-input class (non-zero
//! exit, a message naming the problem, no panic, nothing written).

mod cli_support;
mod common;

use cli_support::{close, fails, has_keys, json, ok, read_valid, s, stderr};
use common::{data, mtcut, scratch};
use mtcut::mt::{CELL_ERROR, CELL_FRAGMENT, CELL_LEVEL, POINT_VERTEX};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The model of tests/data/fandisk, built once by `mtcut build --json`, with the build's
/// JSON report.
fn fandisk_model() -> &'static (PathBuf, Value) {
    static MODEL: OnceLock<(PathBuf, Value)> = OnceLock::new();
    MODEL.get_or_init(|| {
        let dir = scratch("cli_mt fandisk model");
        let out = dir.join("fandisk.mt");
        let j = json(&["build", s(&data("fandisk.node")), "-o", s(&out), "--json"]);
        (out, j)
    })
}

fn info_mt(path: &Path) -> Value {
    json(&["info", s(path), "--json"])
}

/// Runs `extract` on the fandisk model with `request` (plus `--json`) into `out`.
fn extract(request: &[&str], out: &Path) -> Value {
    let (model, _) = fandisk_model();
    let mut args = vec!["extract", s(model)];
    args.extend_from_slice(request);
    args.extend_from_slice(&["-o", s(out), "--json"]);
    json(&args)
}

#[test]
fn build_json_has_the_documented_keys_and_agrees_with_info() {
    let (model, b) = fandisk_model();
    has_keys(
        b,
        &[
            "input_tets",
            "input_vertices",
            "collapses",
            "rounds",
            "fragments",
            "pool_tets",
            "ghost_tets",
            "arcs",
            "dag_depth",
            "coarsest_tets",
            "coarsest_vertices",
            "heap_bytes",
            "seconds",
            "input",
            "output",
            "error_metric",
            "boundary_tolerance",
            "file_bytes",
        ],
    );
    assert_eq!(b["input_tets"], 35827);
    assert_eq!(b["error_metric"], "volume");
    assert_eq!(
        b["file_bytes"].as_u64().unwrap(),
        std::fs::metadata(model).unwrap().len()
    );
    let i = info_mt(model);
    has_keys(
        &i,
        &[
            "kind",
            "file_version",
            "vertices",
            "pool_tets",
            "fragments",
            "dag_depth",
            "components",
            "finest_tets",
            "coarsest_tets",
            "min_error",
            "max_error",
            "error_metric",
            "valid",
            "problems",
            "cut_vertices_from",
            "cuts_recorded",
            "crack_planes",
        ],
    );
    assert_eq!(i["kind"], "mt");
    assert_eq!(i["file_version"], 3);
    assert_eq!(i["cuts_recorded"], 0);
    assert_eq!(i["crack_planes"], 0);
    assert_eq!(i["cut_vertices_from"], i["vertices"]);
    assert_eq!(i["valid"], true, "{i}");
    assert_eq!(i["components"], 1);
    assert_eq!(i["vertices"], 9038);
    assert_eq!(i["finest_tets"], b["input_tets"]);
    for key in ["fragments", "pool_tets", "dag_depth", "coarsest_tets"] {
        assert_eq!(i[key], b[key], "{key}");
    }
    let (lo, hi) = (
        i["min_error"].as_f64().unwrap(),
        i["max_error"].as_f64().unwrap(),
    );
    assert!(0.0 < lo && lo <= hi, "error range {lo} .. {hi}");
    // Issue 3's target for the coarsest fandisk: at most 5% of the input.
    assert!(b["coarsest_tets"].as_u64().unwrap() * 20 <= 35827, "{b}");
}

#[test]
fn build_text_reports_the_numbers_and_shows_no_bar_when_piped() {
    let dir = scratch("cli_mt build text");
    let out = dir.join("p.mt");
    let o = mtcut(&["build", s(&data("pinion-coarse.node")), "-o", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = cli_support::stdout(&o);
    for needle in ["fragments", "MT tets", "DAG depth", "coarsest", "time"] {
        assert!(text.contains(needle), "lacks '{needle}': {text}");
    }
    // stderr is a pipe here: the progress bar must stay hidden.
    assert_eq!(stderr(&o), "", "something drawn on a non-terminal stderr");
    assert_eq!(info_mt(&out)["valid"], true);
}

#[test]
fn build_with_each_error_metric() {
    let dir = scratch("cli_mt metrics");
    for metric in ["volume", "boundary", "quality"] {
        let out = dir.join(format!("{metric}.mt"));
        let b = json(&[
            "build",
            s(&data("pinion-coarse.node")),
            "-o",
            s(&out),
            "--error",
            metric,
            "--json",
        ]);
        assert_eq!(b["error_metric"], metric);
        let i = info_mt(&out);
        assert_eq!(i["error_metric"], metric);
        assert_eq!(i["valid"], true, "{metric}: {i}");
        assert!(
            b["coarsest_tets"].as_u64() < b["input_tets"].as_u64(),
            "{b}"
        );
    }
}

#[test]
fn build_target_tets_stops_early() {
    let dir = scratch("cli_mt target");
    let out = dir.join("t.mt");
    let b = json(&[
        "build",
        s(&data("pinion-coarse.node")),
        "-o",
        s(&out),
        "--target-tets",
        "900",
        "--json",
    ]);
    let coarsest = b["coarsest_tets"].as_u64().unwrap();
    assert!(coarsest <= 900 && coarsest > 700, "{b}");
}

#[test]
fn info_recognises_a_model_by_its_magic_bytes() {
    let (model, _) = fandisk_model();
    let dir = scratch("cli_mt magic");
    let disguised = dir.join("model.vtu");
    std::fs::copy(model, &disguised).unwrap();
    assert_eq!(info_mt(&disguised)["kind"], "mt");
    let text = ok(&["info", s(&disguised)]);
    for needle in [
        "file version 3",
        "cuts       none",
        "fragments",
        "DAG depth",
        "coarsest",
        "valid      yes",
    ] {
        assert!(text.contains(needle), "lacks '{needle}': {text}");
    }
}

#[test]
fn finest_extraction_is_exactly_the_input_mesh() {
    let dir = scratch("cli_mt finest");
    let out = dir.join("finest.vtu");
    let j = extract(&["--level", "finest"], &out);
    has_keys(
        &j,
        &[
            "tets",
            "vertices",
            "volume",
            "max_error",
            "refined_fragments",
            "budget_met",
            "seconds",
            "model",
            "output",
            "request",
        ],
    );
    let finest = read_valid(&out);
    let (input, _) = mtcut::io::read_mesh(data("fandisk.node")).unwrap();
    assert_eq!(j["tets"], input.nb_tets());
    assert_eq!(finest.nb_tets(), input.nb_tets());
    assert!(close(j["volume"].as_f64().unwrap(), input.volume(), 1e-12));
    for name in [CELL_FRAGMENT, CELL_ERROR, CELL_LEVEL] {
        let c = finest.cell_data.get(name).expect(name);
        assert_eq!(c.len(), finest.nb_tets(), "{name}");
    }
    // Through the MT vertex ids, the same vertices (bitwise) and the same tets.
    let ids = finest.point_data.get(POINT_VERTEX).expect(POINT_VERTEX);
    let id = |v: usize| ids.values[v] as usize;
    for (v, p) in finest.positions().iter().enumerate() {
        assert_eq!(*p, input.positions()[id(v)], "vertex {v}");
    }
    let sorted = |t: [usize; 4]| {
        let mut t = t;
        t.sort_unstable();
        t
    };
    let mut ours: Vec<[usize; 4]> = finest
        .tets()
        .iter()
        .map(|t| sorted(t.map(|v| id(v.idx()))))
        .collect();
    let mut theirs: Vec<[usize; 4]> = input
        .tets()
        .iter()
        .map(|t| sorted(t.map(|v| v.idx())))
        .collect();
    ours.sort_unstable();
    theirs.sort_unstable();
    assert!(
        ours == theirs,
        "the finest extraction differs from the input"
    );
}

#[test]
fn thresholds_give_valid_meshes_with_non_increasing_sizes() {
    let (model, b) = fandisk_model();
    let i = info_mt(model);
    let (lo, hi) = (
        i["min_error"].as_f64().unwrap(),
        i["max_error"].as_f64().unwrap(),
    );
    let dir = scratch("cli_mt thresholds");
    let coarsest_out = dir.join("coarsest.vtu");
    let c = extract(&["--level", "coarsest"], &coarsest_out);
    assert_eq!(c["tets"], b["coarsest_tets"]);
    assert_eq!(
        read_valid(&coarsest_out).nb_tets(),
        c["tets"].as_u64().unwrap() as usize
    );
    let mut previous = b["input_tets"].as_u64().unwrap();
    for k in 0..=6 {
        let e = lo * (hi / lo).powf(k as f64 / 6.0);
        let out = dir.join(format!("t{k}.vtu"));
        let j = extract(&["--threshold", &format!("{e:e}")], &out);
        let tets = j["tets"].as_u64().unwrap();
        assert!(
            tets <= previous,
            "threshold {e}: {tets} tets after {previous}"
        );
        assert!(j["max_error"].as_f64().unwrap() <= e, "{j}");
        let mesh = read_valid(&out);
        assert_eq!(mesh.nb_tets() as u64, tets);
        assert!(close(mesh.volume(), j["volume"].as_f64().unwrap(), 1e-12));
        previous = tets;
    }
    assert_eq!(
        previous,
        c["tets"].as_u64().unwrap(),
        "the largest error gives the coarsest"
    );
    // `inf` is the coarsest mesh too.
    let j = extract(&["--threshold", "inf"], &dir.join("inf.vtu"));
    assert_eq!(j["tets"], c["tets"]);
}

#[test]
fn budget_caps_the_size() {
    let (_, b) = fandisk_model();
    let dir = scratch("cli_mt budget");
    let (fine, coarse) = (
        b["input_tets"].as_u64().unwrap(),
        b["coarsest_tets"].as_u64().unwrap(),
    );
    let n = (fine + coarse) / 2;
    let out = dir.join("b.vtu");
    let j = extract(&["--budget", &n.to_string()], &out);
    assert_eq!(j["budget_met"], true);
    let tets = j["tets"].as_u64().unwrap();
    assert!(
        tets <= n && tets > coarse,
        "{tets} tets for a budget of {n}"
    );
    assert_eq!(read_valid(&out).nb_tets() as u64, tets);
    // Below the coarsest size: the coarsest mesh, flagged, with a warning in text mode.
    let j = extract(&["--budget", "10"], &dir.join("small.vtu"));
    assert_eq!(j["budget_met"], false);
    assert_eq!(j["tets"], b["coarsest_tets"]);
    let (model, _) = fandisk_model();
    let o = mtcut(&[
        "extract",
        s(model),
        "--budget",
        "10",
        "-o",
        s(&dir.join("small2.vtu")),
    ]);
    assert!(o.status.success());
    assert!(stderr(&o).contains("exceeds the budget"), "{}", stderr(&o));
}

#[test]
fn focus_is_finer_inside_than_outside() {
    let (input, _) = mtcut::io::read_mesh(data("fandisk.node")).unwrap();
    // A small sphere around a vertex of the body (the box's centre may be outside it).
    let (c, r) = (input.positions()[0], 0.1 * input.bbox().diagonal());
    let (model, _) = fandisk_model();
    let hi = info_mt(model)["max_error"].as_f64().unwrap();
    let dir = scratch("cli_mt focus");
    let out = dir.join("f.vtu");
    let focus = format!("{},{},{},{}", c.x, c.y, c.z, r);
    let j = extract(
        &[
            "--threshold",
            &format!("{hi:e}"),
            "--focus",
            &focus,
            "--focus-threshold",
            "0",
        ],
        &out,
    );
    assert_eq!(j["request"]["focus"]["radius"], r);
    let mesh = read_valid(&out);
    let (mut vin, mut nin, mut vout, mut nout) = (0.0, 0usize, 0.0, 0usize);
    for t in 0..mesh.nb_tets() {
        let id = mtcut::mesh::TetId::from_usize(t);
        let p = mesh.tet_positions(id);
        let centroid = (p[0] + p[1] + p[2] + p[3]) / 4.0;
        if centroid.distance(c) < r {
            vin += mesh.tet_volume(id);
            nin += 1;
        } else {
            vout += mesh.tet_volume(id);
            nout += 1;
        }
    }
    assert!(nin > 0 && nout > 0, "{nin} tets inside, {nout} outside");
    let (mean_in, mean_out) = (vin / nin as f64, vout / nout as f64);
    assert!(
        mean_in * 4.0 < mean_out,
        "mean tet volume {mean_in} inside the focus, {mean_out} outside"
    );
}

#[test]
fn extract_text_names_the_output_and_the_data() {
    let (model, _) = fandisk_model();
    let dir = scratch("cli_mt extract text");
    let out = dir.join("x.vtu");
    let text = ok(&["extract", s(model), "--level", "coarsest", "-o", s(&out)]);
    for needle in [
        "extracted",
        "tets",
        "volume",
        "mt_fragment",
        "mt_vertex",
        "time",
    ] {
        assert!(text.contains(needle), "lacks '{needle}': {text}");
    }
    // TetGen output keeps the data as attributes.
    let node = dir.join("x.node");
    ok(&["extract", s(model), "--level", "coarsest", "-o", s(&node)]);
    let mesh = read_valid(&node);
    assert_eq!(mesh.point_data.iter().count(), 1);
    assert_eq!(mesh.cell_data.iter().count(), 3);
}

// ---- bad input ----

/// A copy of the fandisk model with `edit` applied to its bytes.
fn edited_model(dir: &Path, name: &str, edit: impl FnOnce(&mut Vec<u8>)) -> PathBuf {
    let (model, _) = fandisk_model();
    let mut bytes = std::fs::read(model).unwrap();
    edit(&mut bytes);
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// `extract` and `info` (text and JSON) on a bad model fail naming `needles`; nothing is
/// written.
fn model_rejected(path: &Path, needles: &[&str]) {
    let out = path.with_extension("out.vtu");
    fails(
        &["extract", s(path), "--level", "finest", "-o", s(&out)],
        needles,
    );
    assert!(!out.exists());
    fails(&["info", s(path)], needles);
    let o = mtcut(&["info", s(path), "--json"]);
    assert_eq!(o.status.code(), Some(1));
    let j: Value = serde_json::from_str(&cli_support::stdout(&o)).expect("a JSON verdict");
    assert_eq!(j["valid"], false);
}

#[test]
fn bad_model_files() {
    let dir = scratch("cli_mt bad models");
    model_rejected(&dir.join("missing.mt"), &["missing.mt", "No such file"]);
    let p = edited_model(&dir, "trunc.mt", |b| b.truncate(b.len() / 3));
    model_rejected(&p, &["trunc.mt", "truncated"]);
    let p = edited_model(&dir, "short.mt", |b| b.truncate(12));
    model_rejected(&p, &["short.mt", "truncated"]);
    let p = edited_model(&dir, "magic.mt", |b| b[0] = b'X');
    model_rejected(&p, &["magic.mt", "not an mtcut model"]);
    let p = edited_model(&dir, "version.mt", |b| b[8] = 7);
    model_rejected(&p, &["version.mt", "version 7"]);
    let p = edited_model(&dir, "flip.mt", |b| {
        let k = b.len() / 2;
        b[k] ^= 0x10;
    });
    model_rejected(&p, &["flip.mt", "checksum"]);
    // A mesh named like a model.
    let p = dir.join("mesh.mt");
    std::fs::copy(data("pinion-coarse.node"), &p).unwrap();
    model_rejected(&p, &["mesh.mt", "not an mtcut model"]);
}

#[test]
fn extract_rejects_bad_numbers_and_conflicting_options() {
    let (model, _) = fandisk_model();
    let dir = scratch("cli_mt bad options");
    let out = dir.join("never.vtu");
    let m = s(model);
    let o = s(&out);
    let cases: &[(&[&str], &[&str])] = &[
        (
            &["--threshold", "abc"],
            &["--threshold", "'abc' is not a number"],
        ),
        (&["--threshold", "-1"], &["--threshold", "≥ 0"]),
        (&["--threshold", "nan"], &["--threshold", "NaN"]),
        (&["--budget", "0"], &["--budget", "at least 1"]),
        (&["--budget", "1.5"], &["--budget", "whole number"]),
        (&["--budget", "-3"], &["--budget", "whole number"]),
        (&["--level", "medium"], &["--level", "medium"]),
        (&[], &["required", "--threshold", "--budget", "--level"]),
        (
            &["--threshold", "1", "--budget", "5"],
            &["cannot be used with"],
        ),
        (
            &["--level", "finest", "--threshold", "1"],
            &["cannot be used with"],
        ),
        (
            &["--threshold", "1", "--focus", "1,2,3,4"],
            &["--focus-threshold"],
        ),
        (
            &["--threshold", "1", "--focus-threshold", "0"],
            &["--focus"],
        ),
        (
            &[
                "--threshold",
                "1",
                "--focus",
                "1,2,3",
                "--focus-threshold",
                "0",
            ],
            &["--focus", "expected 4"],
        ),
        (
            &[
                "--threshold",
                "1",
                "--focus",
                "1,2,3,-1",
                "--focus-threshold",
                "0",
            ],
            &["--focus", "radius -1"],
        ),
        (
            &[
                "--threshold",
                "1",
                "--focus",
                "1,inf,3,1",
                "--focus-threshold",
                "0",
            ],
            &["--focus", "not finite"],
        ),
        (
            &[
                "--threshold",
                "1",
                "--focus",
                "1,2,3,1",
                "--focus-threshold",
                "x",
            ],
            &["--focus-threshold", "'x' is not a number"],
        ),
    ];
    for (extra, needles) in cases {
        let mut args = vec!["extract", m];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["-o", o]);
        let err = fails(&args, needles);
        assert!(!out.exists(), "{extra:?} wrote {}: {err}", out.display());
    }
    fails(
        &[
            "extract",
            m,
            "--level",
            "finest",
            "-o",
            s(&dir.join("x.stl")),
        ],
        &["x.stl", "unknown output format"],
    );
}

#[test]
fn build_rejects_bad_input() {
    let dir = scratch("cli_mt bad build");
    let out = dir.join("never.mt");
    let o = s(&out);
    let mesh = data("pinion-coarse.node");
    let m = s(&mesh);
    fails(
        &["build", s(&dir.join("nothing.node")), "-o", o],
        &["nothing.node"],
    );
    fails(
        &["build", m, "-o", o, "--error", "area"],
        &["--error", "area"],
    );
    fails(
        &["build", m, "-o", o, "--boundary-tolerance", "-0.1"],
        &["--boundary-tolerance", "tolerance"],
    );
    fails(
        &["build", m, "-o", o, "--boundary-tolerance", "inf"],
        &["--boundary-tolerance", "tolerance"],
    );
    fails(
        &["build", m, "-o", o, "--target-tets", "lots"],
        &["--target-tets"],
    );
    fails(&["build", m], &["--output"]);
    fails(
        &["build", m, "-o", s(&dir.join("model.vtu"))],
        &["model.vtu", "name it .mt"],
    );
    assert!(!dir.join("model.vtu").exists());
    assert!(!out.exists());
    fails(
        &["build", m, "-o", s(&dir.join("no/such/dir/m.mt"))],
        &["m.mt", "folder", "does not exist"],
    );
    // An invalid mesh (a tet using a vertex twice) is rejected by the reader.
    std::fs::write(
        dir.join("bad.node"),
        "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n",
    )
    .unwrap();
    std::fs::write(dir.join("bad.ele"), "1 4 0\n0 0 1 1 3\n").unwrap();
    fails(
        &["build", s(&dir.join("bad.node")), "-o", o],
        &["bad.ele", "more than once"],
    );
    assert!(!out.exists());
}
