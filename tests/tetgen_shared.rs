//! The shared meshes load, validate, and survive a TetGen write/read round trip.

use mtcut::io::{read_mesh, write_mesh};

const MESHES: [&str; 3] = ["fandisk", "pinion", "liver"];

fn data(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

#[test]
fn shared_meshes_are_valid() {
    for name in MESHES {
        let (mesh, report) = read_mesh(data(&format!("{name}.node"))).unwrap();
        let v = mesh.validate();
        assert!(v.is_valid(), "{name}: {v}");
        assert!(mesh.nb_tets() > 35_000, "{name}");
        assert_eq!(report.unused_vertices, 0, "{name}");
        eprintln!(
            "{name}: {} vertices, {} tets, {} re-oriented",
            mesh.nb_vertices(),
            mesh.nb_tets(),
            report.reoriented_tets
        );
    }
}

#[test]
fn tetgen_round_trip_is_exact() {
    let dir = std::env::temp_dir().join(format!("mtcut-tetgen-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in MESHES {
        let (mesh, _) = read_mesh(data(&format!("{name}.ele"))).unwrap();
        let out = dir.join(format!("{name}.node"));
        write_mesh(&out, &mesh).unwrap();
        let (back, report) = read_mesh(&out).unwrap();
        assert_eq!(report.reoriented_tets, 0);
        assert_eq!(back.positions(), mesh.positions(), "{name}");
        assert_eq!(back.tets(), mesh.tets(), "{name}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
