//! `.vtu` round trips through mtcut's own writer and reader: the shared meshes come back
//! bitwise identical (coordinates, tets, attribute columns) in every encoding and
//! compression the writer offers, and `read_mesh`/`write_mesh` dispatch on `.vtu`.

mod io_support;

use io_support::*;
use mtcut::io::{VtuCompression, VtuEncoding, VtuOptions, read_mesh, write_mesh, write_vtu};

fn all_options() -> Vec<(&'static str, VtuOptions)> {
    let raw = VtuOptions::DEFAULT;
    let b64 = VtuOptions::DEFAULT.with_encoding(VtuEncoding::InlineBase64);
    vec![
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
    ]
}

#[test]
fn shared_meshes_round_trip_bitwise_in_default_and_ascii() {
    let dir = Scratch::new("vtu-rt");
    for name in MESHES {
        let mesh = tetgen_mesh(name);
        for (label, options) in [
            ("default", VtuOptions::DEFAULT),
            ("ascii", VtuOptions::ASCII),
        ] {
            let path = dir.path(&format!("{name}-{label}.vtu"));
            write_vtu(&path, &mesh, &options).unwrap();
            let (back, report) = read_mesh(&path).unwrap();
            assert_eq!(report.reoriented_tets, 0, "{name} {label}");
            assert_same_mesh(&mesh, &back, &format!("{name} {label}"));
            assert!(back.validate().is_valid());
        }
    }
}

#[test]
fn every_writer_option_round_trips_with_attributes() {
    let dir = Scratch::new("vtu-opts");
    let mesh = with_attributes(tetgen_mesh("fandisk"));
    for (label, options) in all_options() {
        let path = dir.path(&format!("{label}.vtu"));
        write_vtu(&path, &mesh, &options).unwrap();
        let (back, _) = read_mesh(&path).unwrap();
        assert_same_mesh(&mesh, &back, label);
    }
}

#[test]
fn write_mesh_dispatches_on_vtu_and_tetgen_round_trip_stays_exact() {
    let dir = Scratch::new("vtu-dispatch");
    let mesh = tetgen_mesh("liver");
    let vtu = dir.path("liver.vtu");
    write_mesh(&vtu, &mesh).unwrap();
    let (from_vtu, _) = read_mesh(&vtu).unwrap();
    let ele = dir.path("liver.ele");
    write_mesh(&ele, &from_vtu).unwrap();
    let (from_tetgen, _) = read_mesh(dir.path("liver.node")).unwrap();
    assert_same_mesh(&mesh, &from_tetgen, "tetgen -> vtu -> tetgen");
    let err = write_mesh(dir.path("liver.obj"), &mesh)
        .unwrap_err()
        .to_string();
    assert!(err.contains("unknown output format"), "{err}");
}
