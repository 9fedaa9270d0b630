//! The `mtcut` command line: info, convert, demo, and bad input (non-zero exit, a message
//! naming the problem, never a panic).

mod common;
use common::{data, mtcut, scratch, vtk_python, vtk_script};
use serde_json::Value;
use std::path::Path;

fn stdout(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}
fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn info_json(path: &Path) -> Value {
    let o = mtcut(&["info", path.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    serde_json::from_str(&stdout(&o)).expect("one JSON object")
}

#[test]
fn info_json_has_the_documented_keys() {
    let j = info_json(&data("fandisk.node"));
    for key in [
        "vertices",
        "tets",
        "volume",
        "boundary_faces",
        "boundary_area",
        "reoriented_tets",
        "unused_vertices",
        "valid",
        "problems",
    ] {
        assert!(j.get(key).is_some(), "missing key {key}: {j}");
    }
    assert_eq!(j["vertices"], 9038);
    assert_eq!(j["valid"], true);
    assert_eq!(j["problems"].as_array().unwrap().len(), 0);
}

#[test]
fn info_agrees_with_vtk() {
    if !vtk_python() {
        return;
    }
    for name in ["fandisk", "pinion", "liver"] {
        let path = data(&format!("{name}.node"));
        let ours = info_json(&path);
        let reference: Value =
            serde_json::from_str(&vtk_script("info_reference.py", &[path.to_str().unwrap()]))
                .unwrap();
        assert_eq!(ours["tets"], reference["tets"], "{name}");
        assert_eq!(
            ours["boundary_faces"], reference["boundary_faces"],
            "{name}"
        );
        let (a, b) = (
            ours["volume"].as_f64().unwrap(),
            reference["volume"].as_f64().unwrap(),
        );
        assert!(
            (a - b).abs() <= 1e-12 * b.abs(),
            "{name}: volume {a} vs VTK {b}"
        );
    }
}

#[test]
fn info_text_reports_validity() {
    let o = mtcut(&["info", data("pinion.ele").to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("tets       35696"), "{text}");
    assert!(text.contains("valid      yes"), "{text}");
}

#[test]
fn convert_to_tetgen_round_trips() {
    let dir = scratch("convert");
    let out = dir.join("copy.node");
    let o = mtcut(&[
        "convert",
        data("liver.node").to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).starts_with("wrote "), "the report on stdout");
    // medit files are read, not written: refused before anything is read.
    let o = mtcut(&[
        "convert",
        data("liver.node").to_str().unwrap(),
        "-o",
        dir.join("copy.mesh").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("unknown output format"),
        "{}",
        stderr(&o)
    );
    let a = info_json(&data("liver.node"));
    let b = info_json(&out);
    for key in [
        "vertices",
        "tets",
        "volume",
        "boundary_faces",
        "boundary_area",
    ] {
        assert_eq!(a[key], b[key], "{key}");
    }
}

/// Writes a TetGen pair `name.node/.ele` with the given bodies (headers included).
fn tetgen_pair(dir: &Path, name: &str, node: &str, ele: &str) -> std::path::PathBuf {
    std::fs::write(dir.join(format!("{name}.node")), node).unwrap();
    std::fs::write(dir.join(format!("{name}.ele")), ele).unwrap();
    dir.join(format!("{name}.node"))
}

const NODES5: &str = "5 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 0 0 -1\n";

/// Runs `info` on a bad input: it must fail with a message containing every one of
/// `needles`, and must not panic.
fn rejects(path: &Path, needles: &[&str]) {
    for json in [false, true] {
        let mut args = vec!["info", path.to_str().unwrap()];
        if json {
            args.push("--json");
        }
        let o = mtcut(&args);
        let err = stderr(&o);
        assert_eq!(
            o.status.code(),
            Some(1),
            "exit code for {}: {err}",
            path.display()
        );
        assert!(!err.contains("panicked"), "panic: {err}");
        for n in needles {
            assert!(err.contains(n), "message lacks '{n}': {err}");
        }
        if json {
            let j: Value = serde_json::from_str(&stdout(&o)).expect("a JSON verdict");
            assert_eq!(j["valid"], false);
        }
    }
}

#[test]
fn bad_input_truncated_file() {
    let dir = scratch("truncated");
    let full = std::fs::read_to_string(data("fandisk.ele")).unwrap();
    let cut = &full[..full.len() / 2];
    std::fs::copy(data("fandisk.node"), dir.join("t.node")).unwrap();
    std::fs::write(dir.join("t.ele"), cut).unwrap();
    rejects(&dir.join("t.node"), &["t.ele", "truncated"]);
}

#[test]
fn bad_input_nan_coordinate() {
    let dir = scratch("nan");
    let node = NODES5.replace("2 0 1 0", "2 0 nan 0");
    let p = tetgen_pair(&dir, "m", &node, "2 4 0\n0 0 1 2 3\n1 0 2 1 4\n");
    rejects(&p, &["m.node", "line 4", "NaN"]);
}

#[test]
fn bad_input_index_out_of_range() {
    let dir = scratch("range");
    let p = tetgen_pair(&dir, "m", NODES5, "2 4 0\n0 0 1 2 3\n1 0 2 1 7\n");
    rejects(&p, &["m.ele", "line 3", "node 7"]);
}

#[test]
fn bad_input_repeated_vertex() {
    let dir = scratch("repeated");
    let p = tetgen_pair(&dir, "m", NODES5, "2 4 0\n0 0 1 2 3\n1 0 2 2 4\n");
    rejects(&p, &["m.ele", "tetrahedron 1", "more than once"]);
}

#[test]
fn bad_input_face_shared_by_three_tets() {
    let dir = scratch("three");
    let node = format!("{}5 0.2 0.2 2\n", NODES5.replacen("5 3", "6 3", 1));
    let p = tetgen_pair(&dir, "m", &node, "3 4 0\n0 0 1 2 3\n1 0 2 1 4\n2 0 1 2 5\n");
    rejects(&p, &["m.ele", "faces shared by more than two tets"]);
}

#[test]
fn bad_input_garbage_bytes() {
    let dir = scratch("garbage");
    let bytes: Vec<u8> = (0..4096u32)
        .map(|i| (i.wrapping_mul(2654435761) >> 13) as u8)
        .collect();
    std::fs::write(dir.join("g.node"), &bytes).unwrap();
    std::fs::write(dir.join("g.ele"), &bytes).unwrap();
    rejects(&dir.join("g.node"), &["g.node"]);
}

#[test]
fn bad_input_missing_file_and_unknown_format() {
    let dir = scratch("missing");
    rejects(&dir.join("nothing.node"), &["nothing.node"]);
    std::fs::write(dir.join("x.stl"), "solid x").unwrap();
    rejects(&dir.join("x.stl"), &["x.stl", "unknown mesh format"]);
}

#[test]
fn bad_input_non_tet_cell_in_vtu() {
    let dir = scratch("non-tet-vtu");
    // A tet and a hexahedron (VTK type 12) in an ASCII .vtu.
    let vtu = r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt32">
  <UnstructuredGrid>
    <Piece NumberOfPoints="8" NumberOfCells="2">
      <Points>
        <DataArray type="Float64" NumberOfComponents="3" format="ascii">
          0 0 0  1 0 0  1 1 0  0 1 0  0 0 1  1 0 1  1 1 1  0 1 1
        </DataArray>
      </Points>
      <Cells>
        <DataArray type="Int64" Name="connectivity" format="ascii">0 1 3 4  0 1 2 3 4 5 6 7</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">4 12</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">10 12</DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
"#;
    let path = dir.join("mixed.vtu");
    std::fs::write(&path, vtu).unwrap();
    rejects(&path, &["mixed.vtu", "cell 1", "type 12"]);
}

/// A demo told to write into a file refuses at once, naming it, and keeps the file.
#[test]
fn demo_into_a_file_is_refused_before_any_work() {
    let dir = scratch("demo-into-file");
    let file = dir.join("not-a-folder");
    std::fs::write(&file, "kept").unwrap();
    let o = mtcut(&["demo", "-o", file.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("not-a-folder: exists and is not a folder"),
        "{err}"
    );
    assert!(
        stdout(&o).is_empty(),
        "work done before refusing: {}",
        stdout(&o)
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "kept");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn demo_builds_extracts_cuts_and_lists_its_outputs() {
    let dir = scratch("demo");
    let o = mtcut(&["demo", "-o", dir.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    for needle in [
        "embedded model: liver",
        "valid      yes",
        "MT ",
        "levels",
        "cut        the MT",
        "2 parts; valid",
        "demo.pvd",
    ] {
        assert!(text.contains(needle), "lacks '{needle}': {text}");
    }
    let read = |name: &str| {
        let (mesh, _) = mtcut::io::read_mesh(dir.join(name)).expect(name);
        assert!(mesh.validate().is_valid(), "{name}");
        mesh
    };
    let (input, _) = mtcut::io::read_mesh(data("liver.node")).unwrap();
    let finest = read("liver-finest.vtu");
    let middle = read("liver-middle.vtu");
    let coarsest = read("liver-coarsest.vtu");
    assert_eq!(finest.nb_tets(), input.nb_tets());
    assert!(coarsest.nb_tets() < middle.nb_tets() && middle.nb_tets() < finest.nb_tets());
    for m in [&finest, &middle, &coarsest] {
        assert!(m.point_data.get(mtcut::mt::POINT_VERTEX).is_some());
        assert!(m.cell_data.get(mtcut::mt::CELL_ERROR).is_some());
    }
    // The MT cut through: two parts, each one piece at its finest and coarsest level; the
    // finest parts add up to the input's volume, the coarsest to the uncut coarsest level's.
    let mut volumes = [0.0, 0.0];
    for k in 0..2 {
        for (i, level) in ["finest", "coarsest"].iter().enumerate() {
            let part = read(&format!("liver-part-{k}-{level}.vtu"));
            assert_eq!(mtcut::cut::Components::of(&part).count, 1, "{k} {level}");
            volumes[i] += part.volume();
        }
    }
    assert!(!dir.join("liver-part-2-finest.vtu").exists());
    assert!((volumes[0] - input.volume()).abs() <= 1e-12 * input.volume());
    assert!((volumes[1] - coarsest.volume()).abs() <= 1e-12 * coarsest.volume());
    // Every step carries the same arrays (ParaView colours them alike; pvbatch-check.py).
    let names = |m: &mtcut::mesh::TetMesh| {
        let mut p: Vec<String> = m.point_data.iter().map(|a| a.name.clone()).collect();
        let mut c: Vec<String> = m.cell_data.iter().map(|a| a.name.clone()).collect();
        p.sort();
        c.sort();
        (p, c)
    };
    let first = names(&finest);
    // The collection lists exactly the .vtu files written, and each exists.
    let pvd = std::fs::read_to_string(dir.join("demo.pvd")).unwrap();
    let listed: Vec<&str> = pvd
        .split("file=\"")
        .skip(1)
        .map(|r| r.split('"').next().unwrap())
        .collect();
    let mut written: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| {
            n.ends_with(".vtu")
                && !n.starts_with("liver-scalpel-")
                && !n.starts_with("liver-curve-")
        })
        .collect();
    written.sort();
    let mut listed_sorted: Vec<String> = listed.iter().map(|s| s.to_string()).collect();
    listed_sorted.sort();
    assert_eq!(listed_sorted, written);
    assert_eq!(listed.len(), 7);
    for name in &listed {
        assert_eq!(names(&read(name)), first, "{name}");
    }
    // The scalpel's time series: 13 meshes (before the first step, then after each), one
    // piece until the blade has crossed the model, two at the end.
    let pvd = std::fs::read_to_string(dir.join("scalpel.pvd")).unwrap();
    let series: Vec<&str> = pvd
        .split("file=\"")
        .skip(1)
        .map(|r| r.split('"').next().unwrap())
        .collect();
    assert_eq!(series.len(), 13, "{pvd}");
    assert!(
        text.contains("scalpel    a blade across the MT in 12 steps"),
        "{text}"
    );
    let pieces: Vec<usize> = series
        .iter()
        .map(|name| {
            let m = read(name);
            assert_eq!(names(&m), first, "{name}");
            mtcut::cut::Components::of(&m).count
        })
        .collect();
    assert_eq!(pieces.first(), Some(&1), "{pieces:?}");
    assert_eq!(pieces.last(), Some(&2), "{pieces:?}");
    // The curved incision in the middle level: 17 meshes (before, then after each of 16
    // steps), each valid with the same arrays; the corner comes off at the end.
    let pvd = std::fs::read_to_string(dir.join("curve.pvd")).unwrap();
    let series: Vec<&str> = pvd
        .split("file=\"")
        .skip(1)
        .map(|r| r.split('"').next().unwrap())
        .collect();
    assert_eq!(series.len(), 17, "{pvd}");
    assert!(text.contains("curve      a blade turning"), "{text}");
    let curve: Vec<mtcut::mesh::TetMesh> = series.iter().map(|name| read(name)).collect();
    assert_eq!(curve[0].nb_tets(), middle.nb_tets());
    for m in &curve {
        assert_eq!(names(m), names(&curve[0]));
        assert!((m.volume() - middle.volume()).abs() <= 1e-12 * middle.volume());
    }
    assert_eq!(mtcut::cut::Components::of(&curve[0]).count, 1);
    assert_eq!(mtcut::cut::Components::of(&curve[16]).count, 2);
    // The model is there, valid, and its finest level is the input.
    let j = info_json(&dir.join("liver.mt"));
    assert_eq!(j["kind"], "mt");
    assert_eq!(j["valid"], true);
    assert_eq!(j["finest_tets"], input.nb_tets());
    assert_eq!(j["components"], 1);
    // The cut model too, with its two components.
    let j = info_json(&dir.join("liver-cut.mt"));
    assert_eq!(j["valid"], true);
    assert_eq!(j["components"], 2);
    assert!(dir.join("liver-quality.json").exists());
}

/// A reader that stops early (`mtcut info MESH | head -1`) closes the pipe: mtcut stops
/// quietly, without a panic message.
#[test]
fn a_closed_output_pipe_is_no_panic() {
    use std::process::{Command, Stdio};
    let (fandisk, liver) = (data("fandisk.node"), data("liver.node"));
    for args in [
        vec!["info", fandisk.to_str().unwrap()],
        vec!["info", liver.to_str().unwrap(), "--json"],
    ] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_mtcut"))
            .args(&args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("mtcut runs");
        // Close the read end before mtcut (still reading the mesh) writes anything.
        drop(child.stdout.take());
        let o = child.wait_with_output().expect("mtcut ends");
        let err = stderr(&o);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(o.status.code().is_some(), "{args:?}: killed by a signal");
        assert!(o.status.success(), "{args:?}: {:?} {err}", o.status);
    }
}

/// Runs `mtcut args` under a file-size limit of `kib` KiB (`ulimit -f` in bash).
fn mtcut_limited(kib: u64, args: &[&str]) -> std::process::Output {
    std::process::Command::new("bash")
        .arg("-c")
        .arg(format!("ulimit -f {kib} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_mtcut"))
        .args(args)
        .output()
        .expect("bash runs")
}

/// A write that fails part way (here past a file-size limit; a full disk alike) is
/// reported naming the file, and the files it was to replace are kept as they were: a
/// model cut in place, a .vtu, and both files of a TetGen pair when the second fails.
#[test]
fn a_failed_write_keeps_the_files_it_was_replacing() {
    let dir = scratch("failed write");
    let s = |p: &Path| p.to_str().unwrap().to_string();
    let read = |p: &Path| std::fs::read(p).unwrap();
    let leftovers = || {
        std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains("tmp"))
            .collect::<Vec<_>>()
    };
    let check = |o: std::process::Output, path: &Path| {
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(err.contains(&s(path)), "{err}");
        assert!(err.contains("File too large"), "{err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(leftovers().is_empty(), "{:?}", leftovers());
    };
    let (small, large) = (s(&data("pinion-coarse.node")), s(&data("liver.node")));

    // A model cut and written over itself.
    let model = dir.join("model.mt");
    let o = mtcut(&["build", &small, "-o", &s(&model)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let before = read(&model);
    let polygon = "-100,-100,0.1;100,-100,0.1;100,100,0.1;-100,100,0.1";
    let limit = before.len() as u64 / 1024;
    let args = ["cut", &s(&model), "--polygon", polygon, "-o", &s(&model)];
    check(mtcut_limited(limit, &args), &model);
    assert!(read(&model) == before, "the model was changed");
    // Without the limit the same command replaces it.
    let o = mtcut(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(read(&model) != before);

    // A .vtu replaced by a larger one.
    let vtu = dir.join("mesh.vtu");
    let o = mtcut(&["convert", &small, "-o", &s(&vtu)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let before = read(&vtu);
    let limit = before.len() as u64 / 1024 + 1;
    check(
        mtcut_limited(limit, &["convert", &large, "-o", &s(&vtu)]),
        &vtu,
    );
    assert!(read(&vtu) == before, "the .vtu was changed");

    // A TetGen pair whose .node fits under the limit and whose .ele does not.
    let sizes = dir.join("sizes.node");
    let o = mtcut(&["convert", &large, "-o", &s(&sizes)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let node_len = std::fs::metadata(&sizes).unwrap().len();
    let ele_len = std::fs::metadata(sizes.with_extension("ele"))
        .unwrap()
        .len();
    assert!(node_len + 4096 < ele_len, "{node_len} {ele_len}");
    let pair = dir.join("pair.node");
    let o = mtcut(&["convert", &small, "-o", &s(&pair)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (node, ele) = (read(&pair), read(&pair.with_extension("ele")));
    let limit = (node_len + ele_len) / 2 / 1024;
    check(
        mtcut_limited(limit, &["convert", &large, "-o", &s(&pair)]),
        &pair.with_extension("ele"),
    );
    assert!(read(&pair) == node, "the .node was replaced");
    assert!(
        read(&pair.with_extension("ele")) == ele,
        "the .ele was changed"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
