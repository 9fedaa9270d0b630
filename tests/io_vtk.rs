//! Cross-checks against VTK itself (VTK 9.1 through `/usr/bin/python3` and
//! `scripts/vtk/vtu_tool.py`):
//! * VTK's `vtkXMLUnstructuredGridReader` reads every kind of `.vtu` mtcut writes and
//!   holds exactly mtcut's points, cells and data arrays;
//! * every kind of `.vtu` VTK's own writer produces (its defaults, ParaView's appended raw,
//!   ASCII, inline binary, every compressor, UInt64 headers, Float32 points, big-endian)
//!   is read by mtcut with exactly the points, cells and data VTK wrote.
//!
//! Without VTK's Python these tests print "skipped" (and fail when `CI` is set).

mod io_support;

use io_support::*;
use mtcut::io::{VtuCompression, VtuEncoding, VtuOptions, read_mesh, write_vtu};

#[test]
fn vtk_reads_every_kind_of_vtu_we_write() {
    if !vtk_available() {
        return;
    }
    let dir = Scratch::new("vtk-reads-ours");
    let raw = VtuOptions::DEFAULT;
    let b64 = raw.with_encoding(VtuEncoding::InlineBase64);
    let kinds = [
        ("default", raw),
        ("ascii", VtuOptions::ASCII),
        ("raw-none", raw.with_compression(VtuCompression::None)),
        (
            "raw-zlib9",
            raw.with_compression(VtuCompression::Zlib { level: 9 }),
        ),
        ("raw-lz4", raw.with_compression(VtuCompression::Lz4)),
        (
            "raw-lzma",
            raw.with_compression(VtuCompression::Lzma { level: 1 }),
        ),
        ("base64-zlib", b64),
        ("base64-none", b64.with_compression(VtuCompression::None)),
        ("base64-lz4", b64.with_compression(VtuCompression::Lz4)),
    ];
    let mut cases = Vec::new();
    let fandisk = with_attributes(tetgen_mesh("fandisk"));
    for (label, options) in kinds {
        cases.push((format!("fandisk-{label}"), fandisk.clone(), options));
    }
    for name in ["pinion", "liver"] {
        let mesh = tetgen_mesh(name);
        cases.push((format!("{name}-default"), mesh.clone(), VtuOptions::DEFAULT));
        cases.push((format!("{name}-ascii"), mesh, VtuOptions::ASCII));
    }
    let mut args = vec!["dump".to_string()];
    for (label, mesh, options) in &cases {
        let path = dir.path(&format!("{label}.vtu"));
        write_vtu(&path, mesh, options).unwrap();
        args.push(path.to_string_lossy().into_owned());
        args.push(
            dir.path(&format!("{label}.dump"))
                .to_string_lossy()
                .into_owned(),
        );
    }
    run_vtu_tool(&args.iter().map(String::as_str).collect::<Vec<_>>());
    for (label, mesh, _) in &cases {
        VtkDump::load(&dir.path(&format!("{label}.dump"))).assert_matches(mesh, 0, label);
        eprintln!("VTK read {label}.vtu identically");
    }
}

#[test]
fn we_read_every_kind_of_vtu_vtk_writes() {
    if !vtk_available() {
        return;
    }
    let dir = Scratch::new("we-read-vtk");
    let modes = [
        "default",
        "raw-zlib",
        "raw-none",
        "raw-lz4",
        "raw-lzma",
        "raw-zlib-uint64",
        "raw-zlib-float32",
        "raw-zlib-bigendian",
        "binary-zlib",
        "binary-none",
        "base64-none",
        "ascii",
    ];
    let mut jobs: Vec<(&str, Vec<&str>)> = vec![("fandisk", modes.to_vec())];
    jobs.push(("pinion", vec!["raw-zlib", "ascii"]));
    jobs.push(("liver", vec!["raw-zlib", "binary-zlib"]));
    for (name, modes) in jobs {
        let node = data(&format!("{name}.node"));
        let ele = data(&format!("{name}.ele"));
        let out = dir.path(name);
        let mut args = vec![
            "write",
            node.to_str().unwrap(),
            ele.to_str().unwrap(),
            out.to_str().unwrap(),
        ];
        args.extend(&modes);
        run_vtu_tool(&args);
        let (reference, ref_report) = read_mesh(&node).unwrap();
        for mode in modes {
            let what = format!("{name} {mode}");
            let (mesh, report) = read_mesh(out.join(format!("{mode}.vtu")))
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            let dump = VtkDump::load(&out.join(format!("{mode}.dump")));
            dump.assert_matches(&mesh, report.reoriented_tets, &what);
            // Same mesh as mtcut's own reading of the TetGen files (positions through
            // Float32 when VTK wrote Float32).
            assert_eq!(report, ref_report, "{what}");
            assert_eq!(mesh.tets(), reference.tets(), "{what}");
            let expected: Vec<f64> = reference
                .positions()
                .iter()
                .flat_map(|p| p.to_array())
                .map(|x| {
                    if dump.points_type == "float" {
                        x as f32 as f64
                    } else {
                        x
                    }
                })
                .collect();
            let got: Vec<f64> = mesh.positions().iter().flat_map(|p| p.to_array()).collect();
            assert_same_values(&got, &expected, &format!("{what}: positions vs TetGen"));
            eprintln!("read VTK's {name} {mode}.vtu identically");
        }
    }
}
