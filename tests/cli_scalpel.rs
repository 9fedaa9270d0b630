//! `mtcut scalpel MODEL.mt --path PATH.json -o DIR`: a straight blade crossing fandisk in
//! 12 steps writes 13 valid meshes listed in a .pvd, the body parts at the step the blade
//! leaves it, and the saved model is valid with two components; bad path files fail with
//! a message naming the problem; a turning path stops at the step that breaks the model,
//! keeping the steps before it and saving nothing; a turning blade saved halfway goes on
//! turning on the saved model. Given a mesh, the scalpel cuts the mesh itself, and a
//! turning blade works.

mod blades;
mod cli_support;
mod common;

use cli_support::{fails, json, ok, read_valid, s};
use common::{data, scratch};
use mtcut::cut::Components;
use mtcut::geom::Aabb;
use mtcut::mt::Mt;
use std::path::Path;

/// Blade positions as the path file holds them.
fn write_path(path: &Path, blades: &[[[f64; 3]; 2]]) {
    std::fs::write(path, serde_json::to_string(blades).unwrap()).unwrap();
}

/// `mtcut scalpel MODEL --path PATH -o OUT --save SAVED`, then `extra`.
fn scalpel_args<'a>(
    model: &'a Path,
    path: &'a Path,
    out: &'a Path,
    saved: &'a Path,
    extra: &[&'a str],
) -> Vec<&'a str> {
    let mut a = vec![
        "scalpel",
        s(model),
        "--path",
        s(path),
        "-o",
        s(out),
        "--save",
        s(saved),
    ];
    a.extend_from_slice(extra);
    a
}

fn fandisk_model(dir: &Path) -> (std::path::PathBuf, Aabb) {
    let model = dir.join("fandisk.mt");
    ok(&["build", s(&data("fandisk.node")), "-o", s(&model)]);
    let b = Aabb::from_points(Mt::load(&model).unwrap().positions());
    (model, b)
}

/// Fandisk's model in `dir` and a path file of a blade tilting as it crosses it in
/// `steps` steps (`blades::tilting_in`). In 24, the model refuses the ninth step however
/// its sweep is split into triangles; in 20, it refuses the eleventh's default split and
/// takes another.
fn tilting_path(dir: &Path, steps: usize) -> (std::path::PathBuf, std::path::PathBuf) {
    let (model, b) = fandisk_model(dir);
    let blades: Vec<[[f64; 3]; 2]> = (0..=steps)
        .map(|k| blades::tilting_in(&b, k, steps).map(|p| p.to_array()))
        .collect();
    let path = dir.join("tilt.json");
    write_path(&path, &blades);
    (model, path)
}

/// A blade crossing the model's box in 12 steps, in one plane.
fn straight_blade(b: &Aabb) -> Vec<[[f64; 3]; 2]> {
    let (c, d) = (b.center(), b.max - b.min);
    (0..=12)
        .map(|k| {
            let x = b.min.x - 0.05 * d.x + 1.1 * d.x * k as f64 / 12.0;
            [
                [x, c.y + 0.013 * d.y, b.min.z - 0.1 * d.z],
                [x, c.y - 0.011 * d.y, b.max.z + 0.1 * d.z],
            ]
        })
        .collect()
}

#[test]
fn a_straight_blade_opens_the_model_step_by_step() {
    let dir = scratch("cli_scalpel_straight");
    let (model, b) = fandisk_model(&dir);
    let blades = straight_blade(&b);
    let path = dir.join("path.json");
    write_path(&path, &blades);
    let out = dir.join("series");
    let saved = dir.join("cut.mt");
    let j = json(&scalpel_args(&model, &path, &out, &saved, &["--json"]));
    let steps = j["steps"].as_array().expect("steps");
    assert_eq!(steps.len(), 12, "{j}");
    assert_eq!(j["components"], 2, "{j}");
    let pvd = std::fs::read_to_string(out.join("scalpel.pvd")).expect("pvd");
    let mut before = 0;
    for k in 0..=12 {
        let name = format!("step-{k:04}.vtu");
        assert!(pvd.contains(&name), "{name} not listed:\n{pvd}");
        let mesh = read_valid(&out.join(&name));
        let parts = Components::of(&mesh).count;
        // One piece until the blade has crossed the body, two after.
        assert!(parts >= before && parts <= 2, "step {k}: {parts} pieces");
        before = parts;
        if k == 0 {
            assert_eq!(parts, 1);
        }
    }
    assert_eq!(before, 2, "the blade did not separate the body");
    let back = Mt::load(&saved).expect("saved model");
    assert!(back.validate().is_valid());
    assert_eq!(back.nb_components(), 2);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_path_files_are_refused_by_name() {
    let dir = scratch("cli_scalpel_bad");
    let (model, b) = fandisk_model(&dir);
    let out = dir.join("series");
    for (name, text, needle) in [
        ("not-json.json", "[[1,2", "not JSON"),
        ("object.json", "{\"a\": 1}", "top level is not a list"),
        ("one.json", "[[[0,0,0],[0,0,1]]]", "needs two at least"),
        (
            "short.json",
            "[[[0,0,0],[0,0,1]], [[0,0],[0,0,1]]]",
            "position 1, end 0",
        ),
        (
            "text.json",
            "[[[0,0,0],[0,0,1]], [[0,\"x\",0],[0,0,1]]]",
            "not a finite number",
        ),
        (
            "same.json",
            "[[[0,0,0],[0,0,0]], [[1,0,0],[1,0,1]]]",
            "same point",
        ),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        fails(
            &["scalpel", s(&model), "--path", s(&path), "-o", s(&out)],
            &[needle],
        );
    }
    fails(
        &[
            "scalpel",
            s(&model),
            "--path",
            s(&dir.join("missing.json")),
            "-o",
            s(&out),
        ],
        &["missing.json"],
    );
    assert!(!out.exists(), "a refused path wrote outputs");
    // An output that is a file, not a folder, is refused before the first step, and the
    // file is kept.
    let path = dir.join("good.json");
    write_path(&path, &straight_blade(&b));
    let file = dir.join("a-file");
    std::fs::write(&file, "kept").unwrap();
    fails(
        &["scalpel", s(&model), "--path", s(&path), "-o", s(&file)],
        &["a-file", "exists and is not a folder"],
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "kept");
    std::fs::remove_dir_all(&dir).ok();
}

/// A blade tilting as it crosses fandisk in 24 steps (as tests/mt_scalpel.rs's in 20)
/// would break the MT's levels at its ninth step (a known limit of the MT cut, see
/// `mtcut::cut::scalpel`), which the MT cut refuses: the run stops there, with the steps
/// before it written and listed, and saves nothing.
#[test]
fn a_step_that_breaks_the_model_stops_the_run() {
    let dir = scratch("cli_scalpel_tilt");
    let (model, path) = tilting_path(&dir, 24);
    let out = dir.join("series");
    let saved = dir.join("never.mt");
    let err = fails(
        &[
            "scalpel",
            s(&model),
            "--path",
            s(&path),
            "-o",
            s(&out),
            "--save",
            s(&saved),
        ],
        &[
            "step 9",
            "refused, the MT is as it was",
            "steps 0-8 written",
            "nothing saved",
        ],
    );
    assert!(!saved.exists(), "{err}");
    let pvd = std::fs::read_to_string(out.join("scalpel.pvd")).expect("pvd");
    for k in 0..=8 {
        let name = format!("step-{k:04}.vtu");
        assert!(pvd.contains(&name), "{name} not listed");
        read_valid(&out.join(&name));
    }
    assert!(!pvd.contains("step-0009.vtu"));
    std::fs::remove_dir_all(&dir).ok();
}

/// The blade tilting across fandisk in 20 steps: its eleventh sweep's default triangles
/// are refused by the model, another split of that sweep is taken (`split` in `--json`,
/// named in the step's line), and the run cuts every step, the model valid and saved.
/// Time-critical, the current mesh is cut with the default triangles and the model with
/// the other split (`other_splits`), the current mesh then extracted again: no step
/// refused either.
#[test]
fn a_refused_split_of_a_sweep_is_cut_as_another() {
    let dir = scratch("cli_scalpel_split");
    let (model, path) = tilting_path(&dir, 20);
    let (out, saved) = (dir.join("series"), dir.join("cut.mt"));
    let mut args = scalpel_args(&model, &path, &out, &saved, &[]);
    let stdout = ok(&args);
    assert!(stdout.contains("split"), "{stdout}");
    assert!(Mt::load(&saved).expect("saved").validate().is_valid());
    args.push("--json");
    let j = json(&args);
    assert_eq!(j["refused_steps"].as_array().map(Vec::len), Some(0), "{j}");
    let steps = j["steps"].as_array().expect("steps");
    let split = |k: usize| steps[k - 1]["split"].as_u64().expect("split");
    assert!(split(11) > 0, "{}", steps[10]);
    assert_eq!(split(10), 0, "{}", steps[9]);
    read_valid(&out.join("step-0020.vtu"));
    let live = dir.join("live");
    let args = scalpel_args(&model, &path, &live, &saved, &["--time-critical"]);
    let stdout = ok(&args);
    assert!(stdout.contains("another split"), "{stdout}");
    let mut args = args;
    args.push("--json");
    let j = json(&args);
    assert_eq!(j["refused_steps"].as_array().map(Vec::len), Some(0), "{j}");
    let steps = j["steps"].as_array().expect("steps");
    let step = &steps[10];
    assert_eq!(step["other_splits"].as_u64(), Some(1), "{step}");
    assert_eq!(step["remeshed"].as_bool(), Some(true), "{step}");
    assert!(Mt::load(&saved).expect("saved").validate().is_valid());
    read_valid(&live.join("step-0020.vtu"));
    std::fs::remove_dir_all(&dir).ok();
}

/// A shallow incision (from above liver down to mid-depth) turning by 4° per step: the
/// model refuses some of the steps continuing the last at that angle; with
/// `--skip-refused` each is cut again from a tenth of the way into it, as a new crack
/// (`gap_steps`, and `gap` 0.1 in the step), leaving a bridge that wide rather than the
/// whole step uncut, the model valid after every step; time-critical too.
#[test]
fn skip_refused_cuts_a_refused_step_again_past_a_gap() {
    let dir = scratch("cli_scalpel_gap");
    let model = dir.join("liver.mt");
    ok(&["build", s(&data("liver.node")), "-o", s(&model)]);
    let b = Aabb::from_points(Mt::load(&model).unwrap().positions());
    let blades: Vec<[[f64; 3]; 2]> = blades::shallow_turning(&b, 4.0)
        .into_iter()
        .map(|blade| blade.map(|p| p.to_array()))
        .collect();
    let path = dir.join("turn.json");
    write_path(&path, &blades);
    let (out, saved) = (dir.join("series"), dir.join("cut.mt"));
    let mut args = scalpel_args(&model, &path, &out, &saved, &[]);
    args.extend(["--skip-refused", "--json"]);
    let j = json(&args);
    let refused = j["refused_steps"].as_array().expect("refused_steps");
    assert!(!refused.is_empty(), "no step refused: {j}");
    assert_eq!(j["gap_steps"].as_array(), Some(refused), "{j}");
    let steps = j["steps"].as_array().expect("steps");
    for k in refused {
        let step = &steps[k.as_u64().expect("a step") as usize - 1];
        assert_eq!(step["gap"].as_f64(), Some(0.1), "{step}");
        assert!(step["tets_cut"].as_u64() > Some(0), "{step}");
    }
    assert!(Mt::load(&saved).expect("saved").validate().is_valid());
    read_valid(&out.join("step-0017.vtu"));
    // Time-critical: a step the model refuses whole is cut again from a tenth of the way,
    // frontier first and on the model.
    let live = dir.join("live");
    let mut args = scalpel_args(&model, &path, &live, &saved, &["--time-critical"]);
    args.extend(["--skip-refused", "--json"]);
    let j = json(&args);
    let gaps = j["gap_steps"].as_array().expect("gap_steps");
    assert!(!gaps.is_empty(), "no step cut again past a gap: {j}");
    let steps = j["steps"].as_array().expect("steps");
    for k in gaps {
        let step = &steps[k.as_u64().expect("a step") as usize - 1];
        assert_eq!(step["gap"].as_f64(), Some(0.1), "{step}");
        assert!(step["refused"].is_string(), "{step}");
        assert!(step["current_tets_cut"].as_u64() > Some(0), "{step}");
    }
    assert!(Mt::load(&saved).expect("saved").validate().is_valid());
    read_valid(&live.join("step-0017.vtu"));
    std::fs::remove_dir_all(&dir).ok();
}

/// The same tilting blade with `--skip-refused`: the run goes on past the steps the model
/// refuses (step 9 first), warning on stderr and listing them (`refused_steps`), the
/// blade moving on without cutting, so that a later step cuts again; it writes one valid
/// mesh per time step (a skipped step's unchanged) and saves a valid model; run
/// time-critical too. A mesh, which the plain engine cuts whole, refuses the option.
#[test]
fn skip_refused_goes_on_past_the_steps_the_model_refuses() {
    let dir = scratch("cli_scalpel_skip");
    let (model, path) = tilting_path(&dir, 24);
    let saved = dir.join("skipped.mt");
    for (name, extra) in [("direct", &[][..]), ("live", &["--time-critical"][..])] {
        let out = dir.join(name);
        let mut args = scalpel_args(&model, &path, &out, &saved, extra);
        args.push("--skip-refused");
        let o = common::mtcut(&args);
        let (stdout, stderr) = (cli_support::stdout(&o), cli_support::stderr(&o));
        assert!(o.status.success(), "{name}: {stderr}");
        assert!(
            stderr.contains("step 9") && stderr.contains("refused"),
            "{name}: {stderr}"
        );
        assert!(stdout.contains("refused and skipped"), "{name}: {stdout}");
        let pvd = std::fs::read_to_string(out.join("scalpel.pvd")).expect("pvd");
        for k in 0..=24 {
            let name = format!("step-{k:04}.vtu");
            assert!(pvd.contains(&name), "{name} not listed");
            read_valid(&out.join(&name));
        }
        let mt = Mt::load(&saved).expect("saved model");
        assert!(mt.validate().is_valid(), "{name}: saved model invalid");
        args.push("--json");
        let j = json(&args);
        let refused = j["refused_steps"].as_array().expect("refused_steps");
        assert_eq!(refused[0], 9, "{name}: {j}");
        let steps = j["steps"].as_array().expect("steps");
        assert!(steps[8]["refused"].is_string(), "{name}: {}", steps[8]);
        assert!(steps[7]["refused"].is_null(), "{name}: {}", steps[7]);
        let cuts_again = steps[9..]
            .iter()
            .any(|s| s["refused"].is_null() && s["polygons"].as_u64() > Some(0));
        assert!(cuts_again, "{name}: no step cut after the first skipped");
    }
    let mesh_out = dir.join("mesh");
    fails(
        &[
            "scalpel",
            s(&data("fandisk.node")),
            "--path",
            s(&path),
            "-o",
            s(&mesh_out),
            "--skip-refused",
        ],
        &["--skip-refused is for a model"],
    );
    assert!(!mesh_out.exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// A blade turning by 0.5° per step, cut at every step: step 41 would leave a mesh between
/// the finest and the coarsest pinched at a crack tip (before the MT cut looked for that,
/// it was taken, and the mesh written at the 7/9 quantile of fragment errors was pinched).
/// The model refuses it, naming the flaw: the run stops there, the steps before it written
/// and valid, nothing saved; run time-critical, that step's current mesh is written too.
#[test]
fn a_step_that_would_pinch_a_coarser_mesh_stops_the_run() {
    let dir = scratch("cli_scalpel_pinched");
    let (model, b) = fandisk_model(&dir);
    let blades: Vec<[[f64; 3]; 2]> = (0..=48)
        .map(|k| blades::on_arc(&b, -8.0 + 0.5 * k as f64).map(|p| p.to_array()))
        .collect();
    let path = dir.join("turn.json");
    write_path(&path, &blades);
    let out = dir.join("series");
    let saved = dir.join("never.mt");
    let err = fails(
        &scalpel_args(&model, &path, &out, &saved, &[]),
        &[
            "step 41",
            "between its finest and coarsest meshes would be pinched",
            "refused, the MT is as it was",
            "steps 0-40 written",
            "nothing saved",
        ],
    );
    assert!(!saved.exists(), "{err}");
    let pvd = std::fs::read_to_string(out.join("scalpel.pvd")).expect("pvd");
    for k in [0, 40] {
        read_valid(&out.join(format!("step-{k:04}.vtu")));
    }
    assert!(pvd.contains("step-0040.vtu") && !pvd.contains("step-0041.vtu"));
    // Time-critical, step 41's current mesh is cut and written before the model's cut,
    // which refuses it: the message says so.
    let out = dir.join("time-critical");
    let err = fails(
        &scalpel_args(&model, &path, &out, &saved, &["--time-critical"]),
        &[
            "step 41",
            "between its finest and coarsest meshes would be pinched",
            "steps 0-41 written",
            "nothing saved",
        ],
    );
    assert!(!saved.exists(), "{err}");
    let pvd = std::fs::read_to_string(out.join("scalpel.pvd")).expect("pvd");
    assert!(pvd.contains("step-0041.vtu") && !pvd.contains("step-0042.vtu"));
    std::fs::remove_dir_all(&dir).ok();
}

/// A turning blade run in two sittings: the first run turns by 8° per step and stops
/// inside the body (`--save`), the second, on the saved model, goes on turning from where
/// the first stopped (its first step continues the saved crack at an angle: the model
/// carries the record of its last cuts) until the corner comes off.
#[test]
fn a_turning_blade_resumed_on_the_saved_model_continues_its_crack() {
    let dir = scratch("cli_scalpel_resumed");
    let (model, b) = fandisk_model(&dir);
    let at = |k: usize| blades::on_arc(&b, -8.0 + 8.0 * k as f64).map(|p| p.to_array());
    let first: Vec<[[f64; 3]; 2]> = (0..6).map(at).collect();
    let rest: Vec<[[f64; 3]; 2]> = (5..16).map(at).collect();
    let (p1, p2) = (dir.join("first.json"), dir.join("rest.json"));
    write_path(&p1, &first);
    write_path(&p2, &rest);
    let (half, whole) = (dir.join("half.mt"), dir.join("whole.mt"));
    let j = json(&scalpel_args(
        &model,
        &p1,
        &dir.join("s1"),
        &half,
        &["--json"],
    ));
    assert_eq!(j["components"], 1, "{j}");
    let j = json(&scalpel_args(
        &half,
        &p2,
        &dir.join("s2"),
        &whole,
        &["--json"],
    ));
    assert_eq!(j["steps"].as_array().expect("steps").len(), 10, "{j}");
    assert_eq!(j["components"], 2, "the corner did not come off: {j}");
    let back = Mt::load(&whole).expect("saved model");
    assert!(back.validate().is_valid());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn time_critical_steps_cut_the_current_mesh_first() {
    let dir = scratch("cli_scalpel_time_critical");
    let (model, b) = fandisk_model(&dir);
    let path = dir.join("path.json");
    write_path(&path, &straight_blade(&b));
    let (out, saved) = (dir.join("series"), dir.join("cut.mt"));
    let j = json(&scalpel_args(
        &model,
        &path,
        &out,
        &saved,
        &["--time-critical", "--threshold", "1e-4", "--json"],
    ));
    assert_eq!(j["time_critical"], true, "{j}");
    let steps = j["steps"].as_array().expect("steps");
    assert_eq!(steps.len(), 12, "{j}");
    for st in steps {
        assert!(st["seconds_frontier_first"].as_f64().is_some(), "{st}");
        assert!(st["seconds_pending"].as_f64().is_some(), "{st}");
        assert_eq!(st["remeshed"], false, "{st}");
    }
    assert!(
        steps
            .iter()
            .any(|st| st["current_tets_cut"].as_u64() > Some(0))
    );
    // Each step's current mesh: valid, one piece until the blade has crossed, two after.
    let mut before = 0;
    for k in 0..=12 {
        let mesh = read_valid(&out.join(format!("step-{k:04}.vtu")));
        let parts = Components::of(&mesh).count;
        assert!(parts >= before && parts <= 2, "step {k}: {parts} pieces");
        before = parts;
    }
    assert_eq!(before, 2, "the blade did not separate the body");
    let back = Mt::load(&saved).expect("saved model");
    assert!(back.validate().is_valid());
    assert_eq!(back.nb_components(), 2);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_turning_blade_cuts_a_plain_mesh_step_by_step() {
    // Given a mesh, the scalpel cuts the mesh itself, each step continuing the crack: a
    // vertical blade turning by 8° per step cuts a corner off the liver (two parts at the
    // end, every step's mesh valid), where a model's scalpel stops at the first turn.
    let dir = scratch("cli_scalpel_mesh");
    let liver = data("liver.node");
    let b = mtcut::io::read_mesh(&liver).unwrap().0.bbox();
    let (c, d) = (b.center(), b.max - b.min);
    let r = 0.6 * d.x.max(d.y);
    let centre = [b.min.x - 0.1 * d.x, c.y - r];
    let blades: Vec<[[f64; 3]; 2]> = (0..=16)
        .map(|k| {
            let a = (98.0 - 8.0 * k as f64).to_radians();
            let (x, y) = (centre[0] + r * a.cos(), centre[1] + r * a.sin());
            [[x, y, b.min.z - 0.1 * d.z], [x, y, b.max.z + 0.1 * d.z]]
        })
        .collect();
    let path = dir.join("path.json");
    write_path(&path, &blades);
    let (out, saved) = (dir.join("series"), dir.join("cut.vtu"));
    let j = json(&scalpel_args(&liver, &path, &out, &saved, &["--json"]));
    assert_eq!(j["steps"].as_array().expect("steps").len(), 16, "{j}");
    assert_eq!(j["components"], 2, "{j}");
    let pvd = std::fs::read_to_string(out.join("scalpel.pvd")).expect("pvd");
    for k in 0..=16 {
        let name = format!("step-{k:04}.vtu");
        assert!(pvd.contains(&name), "{name} not listed");
        read_valid(&out.join(&name));
    }
    let cut = read_valid(&saved);
    assert_eq!(Components::of(&cut).count, 2);

    // Options of a model are refused for a mesh, as is a model's file name for --save.
    let series = dir.join("refused");
    for (extra, needle) in [
        (&["--threshold", "0.1"][..], "--threshold"),
        (&["--time-critical"][..], "--time-critical"),
    ] {
        let mut a = vec!["scalpel", s(&liver), "--path", s(&path), "-o", s(&series)];
        a.extend_from_slice(extra);
        fails(&a, &[needle, "nothing written"]);
    }
    let as_model = dir.join("cut.mt");
    fails(
        &scalpel_args(&liver, &path, &series, &as_model, &[]),
        &["unknown output format"],
    );
    assert!(!series.exists(), "a refused run wrote its folder");
}

/// A blade that does not move during a step cuts nothing there, on a mesh as on a model
/// (the mesh's run failed on a degenerate sweep); a budget below the coarsest mesh is met
/// by writing it anyway, with a warning and `budget_met` false (it was silent).
#[test]
fn a_pause_cuts_nothing_and_a_missed_budget_is_reported() {
    let dir = scratch("cli_scalpel_pause");
    let mesh = data("pinion-coarse.node");
    let model = dir.join("pinion.mt");
    ok(&["build", s(&mesh), "-o", s(&model)]);
    let b = [-2.0, -2.0, 0.1];
    let blades = [
        [b, [2.0, -2.0, 0.1]],
        [b, [2.0, -2.0, 0.1]],
        [[-2.0, 2.0, 0.1], [2.0, 2.0, 0.1]],
    ];
    let path = dir.join("path.json");
    write_path(&path, &blades);
    for input in [&mesh, &model] {
        let out = dir.join("series");
        let j = json(&[
            "scalpel",
            s(input),
            "--path",
            s(&path),
            "-o",
            s(&out),
            "--json",
        ]);
        let steps = j["steps"].as_array().expect("steps");
        assert_eq!(steps[0]["polygons"], 0, "{j}");
        assert_eq!(steps[0]["seconds"].as_f64().unwrap().to_bits(), 0, "{j}");
        assert!(steps[1]["polygons"].as_u64() > Some(0), "{j}");
        assert_eq!(j["components"], 2, "{j}");
    }
    let out = dir.join("budget");
    let args = [
        "scalpel",
        s(&model),
        "--path",
        s(&path),
        "-o",
        s(&out),
        "--budget",
        "10",
    ];
    let o = common::mtcut(&args);
    assert!(o.status.success(), "{}", cli_support::stderr(&o));
    let err = cli_support::stderr(&o);
    assert!(err.contains("step 2: even the coarsest mesh"), "{err}");
    let mut with_json = args.to_vec();
    with_json.push("--json");
    let j = json(&with_json);
    assert_eq!(j["steps"][1]["budget_met"], false, "{j}");
    // A --save into a folder that does not exist is refused before the first step.
    let (out, save) = (dir.join("never"), dir.join("none").join("cut.mt"));
    fails(
        &scalpel_args(&model, &path, &out, &save, &[]),
        &["does not exist"],
    );
    assert!(!out.exists(), "the refused run wrote its series");
}

/// `--min-advance F` defers steps until the blade is F median edges from where its crack
/// ends, and the last step cuts what is left: a straight blade crossing pinion-coarse in
/// 40 short steps, as a mesh, as a model and time-critical, leaves two parts with most
/// steps deferred (each reported), and the step that caught up cut. A negative or NaN F
/// is refused before any work.
#[test]
fn min_advance_defers_short_steps_and_the_last_step_catches_up() {
    let dir = scratch("cli_scalpel_min_advance");
    let mesh = data("pinion-coarse.node");
    let model = dir.join("pinion.mt");
    ok(&["build", s(&mesh), "-o", s(&model)]);
    let b = mtcut::io::read_mesh(&mesh).unwrap().0.bbox();
    let (c, d) = (b.center(), b.max - b.min);
    let blades: Vec<[[f64; 3]; 2]> = (0..=40)
        .map(|k| {
            let x = b.min.x - 0.02 * d.x + 1.04 * d.x * k as f64 / 40.0;
            [
                [x, c.y + 0.013 * d.y, b.min.z - 0.1 * d.z],
                [x, c.y - 0.011 * d.y, b.max.z + 0.1 * d.z],
            ]
        })
        .collect();
    let path = dir.join("path.json");
    write_path(&path, &blades);
    for (input, extra) in [
        (&mesh, &[][..]),
        (&model, &[][..]),
        (&model, &["--time-critical"][..]),
    ] {
        let out = dir.join("series");
        let mut a = vec!["scalpel", s(input), "--path", s(&path), "-o", s(&out)];
        a.extend_from_slice(&["--min-advance", "1.5", "--json"]);
        a.extend_from_slice(extra);
        let j = json(&a);
        let steps = j["steps"].as_array().expect("steps");
        let deferred = steps.iter().filter(|s| s["deferred"] == true).count();
        assert!(
            deferred >= 20,
            "{input:?} {extra:?}: {deferred} deferred: {j}"
        );
        for s in steps.iter().filter(|s| s["deferred"] == true) {
            assert_eq!(s["polygons"], 0, "{s}");
        }
        assert_eq!(steps[39]["deferred"], false, "{j}");
        assert!(
            steps[39]["polygons"].as_u64() > Some(0),
            "the last step caught up: {j}"
        );
        assert_eq!(j["components"], 2, "{input:?} {extra:?}: {j}");
        std::fs::remove_dir_all(&out).ok();
    }
    for bad in ["-1", "NaN", "inf"] {
        let out = dir.join("refused");
        fails(
            &[
                "scalpel",
                s(&mesh),
                "--path",
                s(&path),
                "-o",
                s(&out),
                "--min-advance",
                bad,
            ],
            &["--min-advance"],
        );
        assert!(!out.exists(), "a refused run wrote its folder");
    }
    std::fs::remove_dir_all(&dir).ok();
}
