//! The coordinate range mtcut supports (`geom::MAX_COORDINATE`, `geom::MIN_MESH_SIZE`): a
//! mesh scaled by a power of two near either end is read, measured, cut and simplified
//! exactly as at its own size (scaling by a power of two is exact in floating point, so
//! every decision must come out the same), and anything beyond the range is refused with
//! a message naming the coordinate, not taken for degenerate tets or a flat polygon.

use mtcut::cut::{CutError, CutOptions, Cutter, MtCutter};
use mtcut::geom::{
    CutPolygon, DVec3, MAX_COORDINATE, MIN_MESH_SIZE, PolygonError, Tolerance, scalpel_sweep,
};
use mtcut::mesh::{MeshError, TetMesh};
use mtcut::mt::{BuildOptions, ExtractOptions, Mt};
use std::path::Path;

fn pinion() -> TetMesh {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pinion-coarse.node");
    mtcut::io::read_mesh(path).expect("pinion-coarse").0
}

fn scaled(mesh: &TetMesh, s: f64) -> TetMesh {
    let positions = mesh.positions().iter().map(|p| *p * s).collect();
    let tets = mesh.tets().iter().map(|t| t.map(|v| v.0)).collect();
    TetMesh::from_arrays(positions, tets)
        .expect("scaled mesh")
        .0
}

/// A square through the mesh, tilted so that it crosses tets in general position.
fn square(mesh: &TetMesh) -> CutPolygon {
    let b = mesh.bbox();
    let (c, r) = (b.center(), b.diagonal());
    let n = DVec3::new(0.2, 1.0, 0.3).normalize();
    let u = n.any_orthonormal_vector();
    let w = n.cross(u);
    CutPolygon::new(&[
        c + (u + w) * r,
        c + (w - u) * r,
        c - (u + w) * r,
        c + (u - w) * r,
    ])
    .expect("square")
}

#[test]
fn a_mesh_at_either_end_of_the_range_is_cut_as_at_its_own_size() {
    let mesh = pinion();
    // The default snapping (this coarse mesh's vertices near the plane all snap: the cut
    // only separates) and almost none (tets split).
    for options in [CutOptions::DEFAULT, CutOptions::SCALPEL] {
        let mut unit = Cutter::new(mesh.clone(), options).expect("cutter");
        let cut = unit.cut(&square(&mesh)).expect("cut");
        let changed = cut.stats.tets_cut + cut.stats.vertex_copies;
        assert!(changed > 0, "{:?}", cut.stats);
        let q = unit.mesh().quality();
        // 2^163 (1.2e49: the square reaches 3.1e49) and 2^-166 (1.1e-50), within the
        // range at both ends.
        for s in [2f64.powi(163), 2f64.powi(-166)] {
            let big = scaled(&mesh, s);
            assert!(big.bbox().max.abs().max_element() <= MAX_COORDINATE);
            assert!(big.bbox().diagonal() >= MIN_MESH_SIZE);
            let mut c = Cutter::new(big.clone(), options).expect("cutter");
            let r = c.cut(&square(&big)).expect("cut at scale");
            assert_eq!(r.stats.tets_cut, cut.stats.tets_cut, "scale {s:e}");
            assert_eq!(c.mesh().tets(), unit.mesh().tets(), "scale {s:e}");
            for (p, u) in c.mesh().positions().iter().zip(unit.mesh().positions()) {
                assert_eq!(*p, *u * s, "scale {s:e}");
            }
            assert!(c.mesh().validate().is_valid(), "scale {s:e}");
            let qs = c.mesh().quality();
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
            assert!(
                close(qs.min_dihedral_deg, q.min_dihedral_deg),
                "scale {s:e}"
            );
            assert!(
                close(qs.max_aspect_ratio, q.max_aspect_ratio),
                "scale {s:e}"
            );
            assert!(
                close(qs.mean_aspect_ratio, q.mean_aspect_ratio),
                "scale {s:e}"
            );
        }
    }
}

#[test]
fn an_mt_at_either_end_of_the_range_is_built_and_cut_as_at_its_own_size() {
    let mesh = pinion();
    let build = |m: &TetMesh| Mt::build(m, &BuildOptions::DEFAULT).expect("build").0;
    let cut = |mt: Mt, m: &TetMesh| {
        let mut cutter = MtCutter::new(mt, MtCutter::DEFAULT_OPTIONS).expect("MT cutter");
        let stats = cutter.cut(&square(m)).expect("MT cut");
        (cutter.mt().clone(), stats.tets_cut)
    };
    let (mt, cells) = cut(build(&mesh), &mesh);
    assert!(cells > 0);
    // 2^163 (1.2e49: the square reaches 3.1e49) and 2^-166 (1.1e-50).
    for s in [2f64.powi(163), 2f64.powi(-166)] {
        let m = scaled(&mesh, s);
        let (big, big_cells) = cut(build(&m), &m);
        assert_eq!(big_cells, cells, "scale {s:e}");
        assert_eq!(big.nb_fragments(), mt.nb_fragments(), "scale {s:e}");
        assert_eq!(big.nb_components(), mt.nb_components(), "scale {s:e}");
        assert!(big.validate().is_valid(), "scale {s:e}");
        for options in [ExtractOptions::FINEST, ExtractOptions::COARSEST] {
            let (a, b) = (
                mt.extract(&options).unwrap(),
                big.extract(&options).unwrap(),
            );
            assert_eq!(a.mesh.tets(), b.mesh.tets(), "scale {s:e}");
        }
    }
}

#[test]
fn coordinates_beyond_the_range_are_refused_by_name() {
    let mesh = pinion();
    // Meshes.
    let err = |s: f64| {
        let positions = mesh.positions().iter().map(|p| *p * s).collect();
        let tets = mesh.tets().iter().map(|t| t.map(|v| v.0)).collect();
        TetMesh::from_arrays(positions, tets).unwrap_err()
    };
    match err(1e60) {
        MeshError::CoordinateOutOfRange { value, .. } => assert!(value.abs() > 1e50),
        e => panic!("{e}"),
    }
    assert!(
        err(1e60)
            .to_string()
            .contains("larger in magnitude than the 1e50")
    );
    match err(1e-60) {
        MeshError::TooSmall { diagonal } => assert!(diagonal < 1e-50),
        e => panic!("{e}"),
    }
    // Polygons and sweeps.
    let far = DVec3::new(1e60, 0.0, 0.0);
    let e = CutPolygon::new(&[DVec3::ZERO, DVec3::X, far]).unwrap_err();
    assert_eq!(
        e,
        PolygonError::OutOfRange {
            index: 2,
            value: 1e60
        }
    );
    assert!(e.to_string().contains("point 2 has coordinate 1e60"), "{e}");
    let e = scalpel_sweep(
        [DVec3::ZERO, DVec3::Z],
        [far, DVec3::X],
        Tolerance { relative: 1e-9 },
    )
    .unwrap_err();
    assert!(matches!(e, PolygonError::OutOfRange { .. }), "{e}");
    // Deformed positions: refused, the mesh unchanged.
    let mut cutter = Cutter::new(mesh.clone(), CutOptions::DEFAULT).expect("cutter");
    let mut moved = mesh.positions().to_vec();
    moved[7].y = -2e50;
    match cutter.set_positions(&moved) {
        Err(CutError::PositionOutOfRange { vertex: 7, value }) => assert_eq!(value, -2e50),
        r => panic!("{r:?}"),
    }
    assert_eq!(cutter.mesh().positions(), mesh.positions());
}
