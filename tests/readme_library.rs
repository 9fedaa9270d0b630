//! The README's "Library" example, run as written (keep the two in step): reading,
//! building the MT, extracting with a focus, and cutting a mesh straight through.

use mtcut::cut::{Components, CutOptions, cut_mesh};
use mtcut::geom::{CutPolygon, DVec3};
use mtcut::mt::{BuildOptions, ExtractOptions, Mt, Region};

#[test]
fn readme_library_example_runs() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::temp_dir().join(format!("mtcut-readme-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/fandisk.node");
    // --- README begins
    let (mesh, _report) = mtcut::io::read_mesh(&path)?; // checked, re-oriented
    assert!(mesh.validate().is_valid());

    // The multiresolution model (paper §2), and a mesh fine near a point, coarse elsewhere.
    let (mt, _stats) = Mt::build(&mesh, &BuildOptions::DEFAULT)?;
    let focus = Region::Sphere {
        center: mesh.bbox().center(),
        radius: 0.1 * mesh.bbox().diagonal(),
    };
    let lod = mt.extract(&ExtractOptions::COARSEST.with_focus(focus, 0.0))?;
    mtcut::io::write_mesh(dir.join("focus.vtu"), &lod.mesh)?;

    // A cut straight through the body with a planar convex polygon (paper §3–§4).
    let (c, d) = (mesh.bbox().center(), mesh.bbox().diagonal());
    let polygon = CutPolygon::new(&[
        c + DVec3::new(-d, -d, 0.0),
        c + DVec3::new(d, -d, 0.0),
        c + DVec3::new(d, d, 0.0),
        c + DVec3::new(-d, d, 0.0),
    ])?;
    let mut cut = mesh.clone();
    let result = cut_mesh(&mut cut, &polygon, &CutOptions::DEFAULT)?;
    let parts = Components::of(&cut);
    println!("{} tets cut, {} parts", result.stats.tets_cut, parts.count);
    // --- README ends
    assert!(lod.mesh.validate().is_valid());
    assert!(cut.validate().is_valid());
    assert_eq!(parts.count, 2);
    assert!(lod.mesh.nb_tets() < mesh.nb_tets());
    std::fs::remove_dir_all(&dir)?;
    Ok(())
}
