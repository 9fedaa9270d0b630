//! `mtcut cut MODEL.mt` and `mtcut extract --component K`: a model cut straight through
//! becomes two independent components, the written model is valid on reload, and the
//! parts' finest levels add up to the input's volume; bad input (bad polygons, options
//! meant for meshes, a component out of range) fails with a message and writes nothing;
//! and a sequence of cuts gives a valid model (the CLI validates after every cut and would
//! refuse to write a broken one, as for a blade continuing a crack in its own plane, the
//! MT cut's known limit).

mod cli_support;
mod common;

use cli_support::{close, fails, has_keys, json, ok, read_valid, s};
use common::{data, mtcut, scratch};
use mtcut::geom::DVec3;
use mtcut::mesh::TetMesh;
use std::path::PathBuf;
use std::sync::OnceLock;

/// A square polygon `"x,y,z;..."` spanned by `u` and `v` (half-side 1 each) around `c`.
fn square(c: DVec3, u: DVec3, v: DVec3) -> String {
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|&(a, b)| {
            let p = c + a * u + b * v;
            format!("{:?},{:?},{:?}", p.x, p.y, p.z)
        })
        .collect::<Vec<_>>()
        .join(";")
}

fn liver() -> TetMesh {
    mtcut::io::read_mesh(data("liver.node")).unwrap().0
}

/// The horizontal plane through the liver's box centre, as the demo cuts it.
fn through_liver() -> String {
    let b = liver().bbox();
    let r = b.diagonal();
    square(b.center(), DVec3::X * r, DVec3::Y * r)
}

/// The liver's model, built once by `mtcut build`.
fn liver_model() -> &'static PathBuf {
    static MODEL: OnceLock<PathBuf> = OnceLock::new();
    MODEL.get_or_init(|| {
        let out = scratch("cli_mt_cut liver model").join("liver.mt");
        ok(&["build", s(&data("liver.node")), "-o", s(&out)]);
        out
    })
}

/// The liver's model cut through by the demo plane, with the cut's JSON report.
fn cut_through() -> &'static (PathBuf, serde_json::Value) {
    static CUT: OnceLock<(PathBuf, serde_json::Value)> = OnceLock::new();
    CUT.get_or_init(|| {
        let out = scratch("cli_mt_cut liver cut").join("cut.mt");
        let j = json(&[
            "cut",
            s(liver_model()),
            "--polygon",
            &through_liver(),
            "-o",
            s(&out),
            "--json",
        ]);
        (out, j)
    })
}

#[test]
fn a_model_cut_through_becomes_two_components_that_keep_the_volume() {
    let (out, j) = cut_through();
    has_keys(
        j,
        &[
            "input",
            "kind",
            "cuts",
            "components",
            "valid",
            "output",
            "seconds",
        ],
    );
    assert_eq!(j["kind"], "mt");
    assert_eq!(j["input_components"], 1);
    assert_eq!(j["components"], 2, "{j}");
    assert_eq!(j["valid"], true);
    assert_eq!(j["output"], s(out));
    let cuts = j["cuts"].as_array().unwrap();
    assert_eq!(cuts.len(), 1);
    let c = &cuts[0];
    has_keys(
        c,
        &[
            "polygon",
            "points",
            "fragments_involved",
            "fragments_split",
            "tets_cut",
            "tets_created",
            "vertices_added",
            "components",
            "time",
        ],
    );
    assert_eq!(c["polygon"], 0);
    assert_eq!(c["components"], 2);
    assert!(c["tets_cut"].as_u64().unwrap() > 0);
    assert!(c["tets_created"].as_u64().unwrap() > c["tets_cut"].as_u64().unwrap());
    assert!(c["fragments_split"].as_u64().unwrap() > 0);

    // Reloaded, the model is valid (info validates exhaustively) and has two components.
    let info = json(&["info", s(out), "--json"]);
    assert_eq!(info["kind"], "mt");
    assert_eq!(info["valid"], true, "{info}");
    assert_eq!(info["components"], 2);
    // The cut's plane is kept in the file: a later cut close to it is made in it.
    assert_eq!(info["crack_planes"], 1, "{info}");

    // The parts' finest levels: valid meshes in one piece each, volumes adding up to the
    // input's; the coarsest: valid too.
    let dir = out.parent().unwrap();
    let input = liver().volume();
    let mut finest = 0.0;
    let mut coarsest = 0.0;
    for k in 0..2 {
        for (level, sum) in [("finest", &mut finest), ("coarsest", &mut coarsest)] {
            let path = dir.join(format!("part-{k}-{level}.vtu"));
            let k_text = k.to_string();
            let e = json(&[
                "extract",
                s(out),
                "--level",
                level,
                "--component",
                &k_text,
                "-o",
                s(&path),
                "--json",
            ]);
            assert_eq!(e["component"], k);
            assert_eq!(e["components"], 2);
            let mesh = read_valid(&path);
            assert_eq!(mesh.nb_tets() as u64, e["tets"].as_u64().unwrap());
            assert_eq!(mtcut::cut::Components::of(&mesh).count, 1, "{level} {k}");
            *sum += mesh.volume();
        }
    }
    assert!(
        close(finest, input, 1e-12),
        "finest parts {finest} vs input {input}"
    );
    // The coarsest level of the uncut model has its own volume (the simplification moved
    // the boundary within tolerance); its parts must add up to it.
    let whole = dir.join("whole-coarsest.vtu");
    let e = json(&[
        "extract",
        s(liver_model()),
        "--level",
        "coarsest",
        "-o",
        s(&whole),
        "--json",
    ]);
    let whole_coarsest = e["volume"].as_f64().unwrap();
    assert!(
        close(coarsest, whole_coarsest, 1e-12),
        "coarsest parts {coarsest} vs uncut coarsest {whole_coarsest}"
    );
    // Without --component, the whole cut model: both parts in one mesh.
    let both = dir.join("both.vtu");
    let e = json(&[
        "extract",
        s(out),
        "--level",
        "finest",
        "-o",
        s(&both),
        "--json",
    ]);
    assert_eq!(e["components"], 2);
    assert!(e["component"].is_null());
    assert!(close(read_valid(&both).volume(), input, 1e-12));
}

#[test]
fn text_reports_say_what_the_cut_did() {
    let dir = scratch("cli_mt_cut text");
    let out = dir.join("cut.mt");
    let text = ok(&[
        "cut",
        s(liver_model()),
        "--polygon",
        &through_liver(),
        "-o",
        s(&out),
    ]);
    for needle in [
        "every level",
        "polygon 0",
        "fragments involved",
        "tets cut",
        "vertices added",
        "2 component(s)",
        "valid after every cut",
        "wrote",
    ] {
        assert!(text.contains(needle), "lacks '{needle}': {text}");
    }
    let info = ok(&["info", s(&out)]);
    assert!(info.contains("2 component(s)"), "{info}");
    assert!(info.contains("1 crack plane(s)"), "{info}");
    let part = dir.join("part.vtu");
    let text = ok(&[
        "extract",
        s(&out),
        "--level",
        "coarsest",
        "--component",
        "1",
        "-o",
        s(&part),
    ]);
    assert!(text.contains("from component 1 of"), "{text}");
    read_valid(&part);
}

#[test]
fn bad_input_to_a_model_cut_writes_nothing() {
    let dir = scratch("cli_mt_cut bad input");
    let out = dir.join("never.mt");
    let model = s(liver_model());
    let good = through_liver();
    // Bad polygons are named, before the model is read.
    for (bad, needle) in [
        ("0,0,0;1,0,0", "at least 3 points, got 2"),
        ("0,0,0;1,0,0;2,0,0", "degenerate"),
        ("0,0,0;1,x,0;0,1,0", "'x' is not a number"),
    ] {
        fails(
            &[
                "cut",
                model,
                "--polygon",
                &good,
                "--polygon",
                bad,
                "-o",
                s(&out),
            ],
            &["polygon 1 (2nd of 2", needle],
        );
        assert!(!out.exists(), "{bad}");
    }
    // Options meant for meshes are refused by name.
    fails(
        &[
            "cut",
            model,
            "--polygon",
            &good,
            "-o",
            s(&out),
            "--separate",
        ],
        &["--separate", "--component"],
    );
    fails(
        &[
            "cut",
            model,
            "--polygon",
            &good,
            "-o",
            s(&out),
            "--scheme",
            "bielser17",
        ],
        &["bielser17", "look-up tables"],
    );
    assert!(!out.exists());
    // A model is not written under a mesh's name.
    let vtu = dir.join("never.vtu");
    fails(
        &["cut", model, "--polygon", &good, "-o", s(&vtu)],
        &["never.vtu", ".mt"],
    );
    assert!(!vtu.exists());
    // A file that starts like a model but is not one.
    let broken = dir.join("broken.mt");
    let mut bytes = std::fs::read(liver_model()).unwrap();
    bytes.truncate(bytes.len() / 2);
    std::fs::write(&broken, bytes).unwrap();
    fails(
        &["cut", s(&broken), "--polygon", &good, "-o", s(&out)],
        &["broken.mt"],
    );
    assert!(!out.exists());
}

#[test]
fn a_component_out_of_range_is_named_with_the_count() {
    let (cut, _) = cut_through();
    let dir = scratch("cli_mt_cut component range");
    let out = dir.join("never.vtu");
    fails(
        &[
            "extract",
            s(cut),
            "--level",
            "finest",
            "--component",
            "2",
            "-o",
            s(&out),
        ],
        &["component 2 out of range", "2 component(s)"],
    );
    fails(
        &[
            "extract",
            s(liver_model()),
            "--level",
            "finest",
            "--component",
            "1",
            "-o",
            s(&out),
        ],
        &["component 1 out of range", "1 component(s)"],
    );
    // Not a number: clap's usage error.
    let o = mtcut(&[
        "extract",
        s(cut),
        "--level",
        "finest",
        "--component",
        "-1",
        "-o",
        s(&out),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!out.exists());
}

/// A tiny seeded generator (SplitMix64) for the cut sequences.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e3779b97f4a7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn unit(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(self.next(), self.next(), self.next()) * 2.0 - DVec3::ONE;
            if (0.1..1.0).contains(&v.length()) {
                return v.normalize();
            }
        }
    }
}

#[test]
fn after_a_sequence_of_cuts_the_model_is_valid() {
    let b = liver().bbox();
    let size = b.max - b.min;
    let dir = scratch("cli_mt_cut sequences");
    for seed in 1..=4u64 {
        let mut rng = Rng(seed);
        let polygons: Vec<String> = (0..5)
            .map(|_| {
                let c = b.min + size * (0.2 + 0.6 * DVec3::new(rng.next(), rng.next(), rng.next()));
                let n = rng.unit();
                let u = n.any_orthonormal_vector();
                let r = b.diagonal() * (0.1 + 0.5 * rng.next());
                square(c, u * r, n.cross(u) * r)
            })
            .collect();
        let out = dir.join(format!("seq-{seed}.mt"));
        let mut args = vec!["cut", s(liver_model())];
        for p in &polygons {
            args.extend_from_slice(&["--polygon", p]);
        }
        args.extend_from_slice(&["-o", s(&out), "--json"]);
        let o = mtcut(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            o.status.success(),
            "seed {seed}, polygons {polygons:?}: {err}"
        );
        let info = json(&["info", s(&out), "--json"]);
        assert_eq!(info["valid"], true, "seed {seed}: {info}");
    }
}

#[test]
fn a_whole_focus_extraction_of_a_model_cut_through_is_valid_or_refused_for_its_parts() {
    let (cut, _) = cut_through();
    let dir = scratch("cli_mt_cut whole focus");
    let b = liver().bbox();
    let c = b.center();
    let focus = format!("{:?},{:?},{:?},{:?}", c.x, c.y, c.z, 0.2 * b.diagonal());
    let out = dir.join("focus.vtu");
    let args = [
        "extract",
        s(cut),
        "--threshold",
        "inf",
        "--focus",
        &focus,
        "--focus-threshold",
        "0",
        "-o",
        s(&out),
    ];
    // Each side of the crack is refined as its own component, so the two parts may meet
    // there at different resolutions, which as one mesh is not valid: refused, pointing at
    // --component, with nothing written.
    let o = mtcut(&args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("panicked"), "{err}");
    if o.status.success() {
        read_valid(&out);
    } else {
        assert_eq!(o.status.code(), Some(1), "{err}");
        for needle in [
            "2 components meet along a cut at different resolutions",
            "each part on its own is valid",
            "--component K (0 to 1)",
            "nothing written",
        ] {
            assert!(err.contains(needle), "lacks '{needle}': {err}");
        }
        assert!(!out.exists());
    }
    // Each component on its own: valid.
    for k in ["0", "1"] {
        let mut a = args.to_vec();
        a.extend_from_slice(&["--component", k]);
        ok(&a);
        read_valid(&out);
    }
}

#[test]
fn focus_extractions_after_a_partial_cut_are_valid() {
    let b = liver().bbox();
    let c = b.center();
    let r = 0.2 * b.diagonal();
    let dir = scratch("cli_mt_cut partial focus");
    let model = dir.join("slit.mt");
    // A slit: a square in the plane y = centre, ending inside the body.
    let j = json(&[
        "cut",
        s(liver_model()),
        "--polygon",
        &square(c, DVec3::X * r, DVec3::Z * r),
        "-o",
        s(&model),
        "--json",
    ]);
    assert_eq!(j["components"], 1, "a slit does not separate: {j}");
    let out = dir.join("focus.vtu");
    for (k, f) in [(-1.0, 0.3), (1.0, 0.3), (0.0, 0.1), (0.0, 0.5)]
        .iter()
        .enumerate()
    {
        let centre = c + DVec3::X * (f.0 * r);
        let focus = format!("{:?},{:?},{:?},{:?}", centre.x, centre.y, centre.z, f.1 * r);
        let o = mtcut(&[
            "extract",
            s(&model),
            "--threshold",
            "inf",
            "--focus",
            &focus,
            "--focus-threshold",
            "0",
            "-o",
            s(&out),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        // Both lips of the slit come from the same fragments: refined together.
        assert!(o.status.success(), "focus {k}: {err}");
        read_valid(&out);
        std::fs::remove_file(&out).unwrap();
    }
    // And uniform thresholds.
    for t in ["0", "1e-5", "1e-4", "inf"] {
        ok(&["extract", s(&model), "--threshold", t, "-o", s(&out)]);
        read_valid(&out);
    }
}

#[test]
fn a_polygon_missing_the_model_changes_nothing_and_warns() {
    let dir = scratch("cli_mt_cut miss");
    let out = dir.join("same.mt");
    let b = liver().bbox();
    let far = square(b.max + DVec3::ONE * b.diagonal(), DVec3::X, DVec3::Y);
    let o = mtcut(&["cut", s(liver_model()), "--polygon", &far, "-o", s(&out)]);
    assert!(o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("polygon 0 does not cut the model"), "{err}");
    let before = json(&["info", s(liver_model()), "--json"]);
    let after = json(&["info", s(&out), "--json"]);
    assert_eq!(after["valid"], true);
    for key in ["vertices", "pool_tets", "fragments", "components"] {
        assert_eq!(after[key], before[key], "{key}");
    }
}

#[test]
fn a_polygon_close_to_an_earlier_cuts_plane_is_cut_in_it_and_said_so() {
    // A half-plane through the liver, then a square overlapping it 1e-7 of the diagonal
    // above its plane (a blade re-entering the cut).
    let dir = scratch("cli_mt_cut near plane");
    let b = liver().bbox();
    let (c, r) = (b.center(), b.diagonal());
    let first = square(
        c - DVec3::X * (0.25 * r),
        DVec3::X * (0.25 * r),
        DVec3::Y * r,
    );
    let lifted = c + DVec3::X * (0.125 * r) + DVec3::Z * (1e-7 * r);
    let second = square(lifted, DVec3::X * (0.25 * r), DVec3::Y * r);
    let args = |out: &PathBuf| {
        let polygons = ["--polygon", &first, "--polygon", &second];
        let mut a = vec!["cut".to_string(), s(liver_model()).to_string()];
        a.extend(polygons.iter().map(|p| p.to_string()));
        a.extend(["-o".to_string(), s(out).to_string()]);
        a
    };
    let out = dir.join("text.mt");
    let a = args(&out);
    let o = mtcut(&a.iter().map(String::as_str).collect::<Vec<_>>());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("polygon 1 lay close to an earlier cut's plane"),
        "{err}"
    );
    assert!(!err.contains("polygon 0 lay"), "{err}");
    let mut a = args(&dir.join("json.mt"));
    a.push("--json".to_string());
    let j = json(&a.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(j["cuts"][0]["moved_to_plane"], false, "{j}");
    assert_eq!(j["cuts"][1]["moved_to_plane"], true, "{j}");
    let info = json(&["info", s(&out), "--json"]);
    assert_eq!(info["valid"], true, "{info}");
}
