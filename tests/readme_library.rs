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

/// The README's time-critical example, run as written.
#[test]
fn readme_time_critical_example_runs() -> Result<(), Box<dyn std::error::Error>> {
    use mtcut::cut::{LiveMt, MtCutter, PendingBudget};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/fandisk.node");
    let (mesh, _) = mtcut::io::read_mesh(&path)?;
    let (mt, _) = Mt::build(&mesh, &BuildOptions::DEFAULT)?;
    let (c, d) = (mesh.bbox().center(), mesh.bbox().diagonal());
    let polygon = CutPolygon::new(&[
        c + DVec3::new(-d, -d, 0.0),
        c + DVec3::new(d, -d, 0.0),
        c + DVec3::new(d, d, 0.0),
        c + DVec3::new(-d, d, 0.0),
    ])?;
    // --- README time-critical begins
    // The simulation's mesh: an extraction of the MT, moved by the host every time step.
    let mut live = LiveMt::new(
        mt,
        &ExtractOptions::threshold(1e-4),
        MtCutter::DEFAULT_OPTIONS,
    )?;
    let moved: Vec<DVec3> = live
        .rest_positions()
        .iter()
        .map(|p| *p + DVec3::new(0.0, 0.0, 0.002 * d * (p.x / d).sin()))
        .collect();
    live.set_positions(&moved)?;
    // Frontier first: returns as soon as the current mesh is cut where it lies.
    let step = live.cut(&polygon)?;
    println!(
        "{} current tets cut in {:.1} ms",
        step.stats.tets_cut,
        step.seconds * 1e3
    );
    // Later time steps: the rest of the MT, a few fragments at a time.
    while live.pending_cuts() > 0 {
        live.process_pending(PendingBudget::Fragments(200))?;
    }
    // Each current vertex is named by its MT vertex again (for the host's FEM state).
    assert!(live.mt_vertex_ids().iter().all(|v| v.is_valid()));
    // --- README time-critical ends
    assert!(live.mesh().validate().is_valid());
    assert!(live.mt().validate().is_valid());
    assert_eq!(Components::of(live.mesh()).count, 2);
    Ok(())
}

/// The README's plain-mesh scalpel example, run as written.
#[test]
fn readme_plain_scalpel_example_runs() -> Result<(), Box<dyn std::error::Error>> {
    use mtcut::cut::Cutter;
    use mtcut::geom::{Tolerance, scalpel_sweep};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/liver.node");
    let (mesh, _) = mtcut::io::read_mesh(&path)?;
    let b = mesh.bbox();
    let (c, d) = (b.center(), b.max - b.min);
    // A vertical blade crossing the liver in x, in 40 time steps.
    let blade_positions: Vec<[DVec3; 2]> = (0..=40)
        .map(|k| {
            let x = b.min.x - 0.01 * d.x + 1.02 * d.x * f64::from(k) / 40.0;
            [
                DVec3::new(x, c.y, b.min.z - 0.1 * d.z),
                DVec3::new(x, c.y + 0.02 * d.y, b.max.z + 0.1 * d.z),
            ]
        })
        .collect();
    // --- README scalpel begins
    let mut scalpel = Cutter::new(mesh.clone(), CutOptions::SCALPEL)?;
    for w in blade_positions.windows(2) {
        for polygon in scalpel_sweep(w[0], w[1], Tolerance { relative: 1e-9 })? {
            scalpel.cut(&polygon)?;
        }
    }
    // --- README scalpel ends
    assert!(scalpel.mesh().validate().is_valid());
    assert_eq!(Components::of(scalpel.mesh()).count, 2);
    Ok(())
}

/// The README's deferring scalpel example, run as written: a blade crossing the liver in
/// 400 steps far shorter than its edges.
#[test]
fn readme_incision_example_runs() -> Result<(), Box<dyn std::error::Error>> {
    use mtcut::cut::{Cutter, Incision, ScalpelError};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/liver.node");
    let (mesh, _) = mtcut::io::read_mesh(&path)?;
    let b = mesh.bbox();
    let (c, d) = (b.center(), b.max - b.min);
    let blade_positions: Vec<[DVec3; 2]> = (0..=400)
        .map(|k| {
            let x = b.min.x - 0.01 * d.x + 1.02 * d.x * f64::from(k) / 400.0;
            [
                DVec3::new(x, c.y, b.min.z - 0.1 * d.z),
                DVec3::new(x, c.y + 0.02 * d.y, b.max.z + 0.1 * d.z),
            ]
        })
        .collect();
    let mut scalpel = Cutter::new(mesh.clone(), CutOptions::SCALPEL)?;
    // --- README incision begins
    let edge = mesh.median_edge_length().expect("a mesh with tets");
    let mut incision = Incision::new(blade_positions[0], 0.5 * edge)?;
    for &to in &blade_positions[1..] {
        incision.step(to, |polygon| -> Result<(), ScalpelError> {
            scalpel.cut(polygon)?;
            Ok(())
        })?;
    }
    incision.catch_up(|polygon| -> Result<(), ScalpelError> {
        scalpel.cut(polygon)?;
        Ok(())
    })?;
    // --- README incision ends
    assert!(scalpel.mesh().validate().is_valid());
    assert_eq!(Components::of(scalpel.mesh()).count, 2);
    assert_eq!(incision.end(), blade_positions[400]);
    Ok(())
}
