//! The cut engine beyond random cuts: axis-aligned cuts of a structured grid (cuts exactly
//! through vertices, along edges and faces), sequences of cuts crossing earlier ones,
//! identical results on one and on all cores, attribute interpolation and the cut-cell
//! marker, components extracted and written alone, the 1:17 baseline's guarantees, and the
//! errors of bad polygons and options. Every cut is followed by `validate()`.

mod cut_common;
mod mtcut_common;

use cut_common::*;
use mtcut::cut::{
    CUT_COLUMN, Components, CutCase, CutError, CutOptions, Cutter, MIN_FACE_POINT_MARGIN, MIN_SNAP,
    Scheme, VertexOrigin, cut_mesh,
};
use mtcut::geom::{CutPolygon, DVec3, PolygonError, Tolerance, scalpel_sweep};
use mtcut::mesh::{Attribute, TetMesh, ViolationKind};
use mtcut::mt::POINT_VERTEX;

fn assert_valid(m: &TetMesh, what: &str) {
    let r = m.validate();
    assert!(r.is_valid(), "{what}: {r}");
}

#[test]
fn grid_cut_along_a_layer_of_faces_separates_without_splitting() {
    // The plane x = 2 holds a whole layer of grid faces: every vertex on it is on the cut,
    // no tet is split, and the two halves come apart by duplicating those vertices.
    let n = 5;
    let grid = grid_mesh(n);
    let mut m = grid.clone();
    let c = square(DVec3::new(2.0, 2.5, 2.5), DVec3::X, 10.0);
    let r = cut_mesh(&mut m, &c, &CutOptions::DEFAULT).expect("cut");
    assert_valid(&m, "x = 2");
    assert_eq!(r.stats.tets_cut, 0);
    assert_eq!(r.stats.vertex_copies, (n + 1) * (n + 1));
    let comps = Components::of(&m);
    assert_eq!(comps.count, 2);
    let parts = comps.extract_all(&m);
    let mut volumes: Vec<f64> = parts.iter().map(|p| p.volume()).collect();
    volumes.sort_by(f64::total_cmp);
    assert!((volumes[0] - 50.0).abs() < 1e-12 * 125.0 && (volumes[1] - 75.0).abs() < 1e-12 * 125.0);
    for p in &parts {
        assert_valid(p, "part");
    }
}

#[test]
fn grid_cuts_through_cells_vertices_and_diagonals() {
    let n = 4;
    let grid = grid_mesh(n);
    let volume = grid.volume();
    let cases = [
        // Through cell middles: crossings at exactly half edges.
        (DVec3::new(1.5, 2.0, 2.0), DVec3::X),
        (DVec3::new(2.0, 2.0, 2.5), DVec3::Z),
        // Diagonal planes through grid vertices, edges and faces.
        (
            DVec3::new(2.0, 2.0, 2.0),
            DVec3::new(1.0, 1.0, 0.0).normalize(),
        ),
        (
            DVec3::new(2.0, 2.0, 2.0),
            DVec3::new(1.0, -1.0, 0.0).normalize(),
        ),
        (
            DVec3::new(2.0, 2.0, 2.0),
            DVec3::new(1.0, 1.0, 1.0).normalize(),
        ),
        (
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(1.0, -1.0, 1.0).normalize(),
        ),
    ];
    for (c, normal) in cases {
        for (r, through) in [(20.0, true), (1.3, false)] {
            let polygon = square(c, normal, r);
            let mut m = grid.clone();
            let res = cut_mesh(&mut m, &polygon, &CutOptions::DEFAULT).expect("cut");
            let what = format!("plane through {c} normal {normal}, half-size {r}");
            assert_valid(&m, &what);
            assert!((m.volume() - volume).abs() <= 1e-12 * volume, "{what}");
            if through {
                assert!(res.stats.components.unwrap_or(0) >= 2, "{what}");
            }
            check_cut(
                &grid,
                &vertex_scales_of(&grid),
                &m,
                &polygon,
                &res,
                &CutOptions::DEFAULT,
                through,
            )
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        }
    }
}

fn vertex_scales_of(m: &TetMesh) -> Vec<f64> {
    mtcut::cut::vertex_scales(m)
}

#[test]
fn sequences_of_cuts_crossing_earlier_cuts() {
    // One mesh, cut again and again: each cut crosses the cracks and parts made before.
    for (k, name) in MESHES.iter().enumerate() {
        let input = mesh(name);
        let volume = input.volume();
        let options = CutOptions::DEFAULT;
        let mut cutter = Cutter::new(input.clone(), options).expect("options");
        let mut rng = Rng(77 + k as u64);
        let mut polygons: Vec<CutPolygon> = Vec::new();
        for step in 0..25 {
            let kind = [Kind::Through, Kind::Partial, Kind::Tiny, Kind::Partial][step % 4];
            let polygon = random_polygon(input, kind, &mut rng);
            polygons.push(polygon.clone());
            let before = cutter.mesh().clone();
            let scales = cutter.vertex_scales().to_vec();
            let res = cutter.cut(&polygon).expect("cut");
            check_cut(
                &before,
                &scales,
                cutter.mesh(),
                &polygon,
                &res,
                &options,
                false,
            )
            .unwrap_or_else(|e| panic!("{name}, cut {step} ({kind:?}): {e}"));
            // No earlier polygon crossed either (up to the crack tips' band, see
            // `mtcut_common::crossing`).
            let (mesh, scales) = (cutter.mesh(), cutter.vertex_scales());
            let near = |u: usize, p: &CutPolygon| {
                p.signed_distance(mesh.positions()[u]).abs()
                    <= options.snap.distance(scales[u]) * 1.0001
            };
            if let Some(m) = mtcut_common::crossing(mesh, &polygons, near, |u| scales[u]) {
                panic!("{name}, after cut {step} ({kind:?}): {m}");
            }
            let v = cutter.mesh().volume();
            assert!((v - volume).abs() <= 1e-12 * volume, "{name}, cut {step}");
        }
        let marks = cutter
            .mesh()
            .cell_data
            .get(CUT_COLUMN)
            .expect("marker column");
        assert_eq!(marks.values.iter().fold(0.0f64, |a, &b| a.max(b)), 25.0);
    }
}

/// Parallel slices close together, with the default snapping: a slice bends its crack
/// towards vertices up to 0.2 of their longest edge away, so the next slices cut across
/// earlier cracks, through both lips. The two lips are split alike, their vertices ordered
/// by twin root (`mtcut::cut::split::canonical_order_at`), so no vertex of one lies inside
/// a face of the other. Ordered by id (a vertex and its copy order differently), the sixth
/// slice of pinion-coarse left 6 such vertices (and `validate` took them for hanging
/// vertices then).
#[test]
fn parallel_slices_split_both_lips_alike() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pinion-coarse.node");
    let input = mtcut::io::read_mesh(path).expect("pinion-coarse").0;
    let volume = input.volume();
    let mut cutter = Cutter::new(input, CutOptions::DEFAULT).expect("options");
    for z in [-0.6118, -0.5176, -0.4863, -0.4549, -0.4235, -0.3922] {
        let corner = |x: f64, y: f64| DVec3::new(x, y, z);
        let slice = CutPolygon::new(&[
            corner(-2.0, -2.0),
            corner(2.0, -2.0),
            corner(2.0, 2.0),
            corner(-2.0, 2.0),
        ])
        .expect("a square");
        let r = cutter.cut(&slice).expect("cut");
        assert!(r.stats.tets_cut > 0, "z = {z} cuts the body");
        let report = cutter.mesh().validate();
        assert!(report.is_valid(), "after the slice at z = {z}: {report}");
        let apart = report.count(ViolationKind::LipsApart);
        assert_eq!(
            apart, 0,
            "after the slice at z = {z}: lips split differently"
        );
        let v = cutter.mesh().volume();
        assert!((v - volume).abs() <= 1e-12 * volume, "z = {z}: volume {v}");
    }
}

/// A crack ending against an earlier one: on a Kuhn grid, a scalpel's cut in the plane
/// y = 3, then one in x + y = 9, whose plane meets the first crack along the body's edge
/// x = 6 and whose contour crosses that edge at z = 2.57. The second crack ends there with
/// a crack tip in a lip face of the first, on the side it cuts. The vertices of that edge
/// lie in both planes, one copy on each lip; each lip's star alone leaned to a different
/// side of the second plane, so the other lip kept its face whole and the lips differed
/// there (which `validate` tells apart from a hanging vertex and warns about). Coincident
/// vertices on the two lips now decide alike (a plane crossing the crack, not separating
/// its lips): the other lip gets the same tip, and the lips stay alike for a later cut
/// crossing them (see `random_partial_scalpel_cuts_seed_852`).
#[test]
fn a_crack_ending_against_an_earlier_one_tips_both_lips_alike() {
    let mut cutter = Cutter::new(kuhn_grid(6), CutOptions::SCALPEL).expect("options");
    let polygons = [
        [
            [12.09927881647388, 3.0, 4.699096907691184],
            [12.09927881647388, 3.0, -0.6828781670184503],
            [2.0331076716833056, 3.0, -0.6828781670184503],
            [2.0331076716833056, 3.0, 4.699096907691184],
        ],
        [
            [7.917299046672652, 1.0827009533273464, 5.285665899452383],
            [1.9987317447729644, 7.001268255227037, -3.0844522487120942],
            [0.562635298946353, 8.437364701053648, -1.0535051781483016],
            [6.481202600846041, 2.518797399153958, 7.316612970016175],
        ],
    ];
    for (k, corners) in polygons.iter().enumerate() {
        let polygon = CutPolygon::new(&corners.map(DVec3::from_array)).expect("polygon");
        let r = cutter.cut(&polygon).expect("cut");
        assert!(r.stats.tets_cut > 0, "cut {k} cuts the grid");
        assert_valid(cutter.mesh(), &format!("after cut {k}"));
    }
    assert_eq!(
        cutter.mesh().validate().count(ViolationKind::LipsApart),
        0,
        "the lips differ"
    );
    // The tip the test is about: a vertex of the second cut at (6, 3, 2.57), in the plane
    // of the first crack, once on each lip, at one position.
    let m = cutter.mesh();
    let tips: Vec<DVec3> = (0..m.nb_vertices())
        .map(|v| m.position(mtcut::mesh::VertexId::from_usize(v)))
        .filter(|p| p.y == 3.0 && (p.x - 6.0).abs() < 1e-4 && (p.z - 2.574).abs() < 1e-3)
        .collect();
    assert_eq!(
        tips.len(),
        2,
        "the tip on each lip of the first crack: {tips:?}"
    );
    assert_eq!(tips[0], tips[1]);
}

/// Seeded sequences of partial cuts through a Kuhn grid's vertices (or half-way between
/// them), normals along the axes and the diagonals: after every cut the mesh is valid
/// (crack lips apart allowed). Degenerate on purpose: planes hold grid vertices, edges and
/// faces, and cross earlier cracks along them. A cut may be refused (a flat child); none
/// may leave an invalid mesh. With the default options and the scalpel's.
#[test]
fn random_partial_cuts_through_grid_vertices_keep_the_grid_valid() {
    grid_stress(CutOptions::DEFAULT);
}

#[test]
fn random_partial_scalpel_cuts_through_grid_vertices_keep_the_grid_valid() {
    grid_stress(CutOptions::SCALPEL);
}

/// Seed 852 of the runs above (beyond the 200 the test makes), with the scalpel's options:
/// the fifth cut (x + z = 5) lies in the plane of the third; on the lips of the second's
/// crack (z = 1), coincident vertices on that plane outside C took different sides (each
/// lip's star leaned its own way), so the fifth cut put a crack tip in one lip's face only,
/// and the seventh (y = 2.5), crossing both lips there, split them differently: two
/// hanging vertices, 1.8e-6 of the grid's spacing from the other lip's face. The two lips
/// now decide alike.
#[test]
fn random_partial_scalpel_cuts_seed_852() {
    let (cuts, _) = grid_run(CutOptions::SCALPEL, 852);
    assert!(cuts >= 7, "{cuts} cuts made");
}

/// Seed 2443, with the scalpel's options: the tenth cut (y = 0.5) crosses the meeting of
/// the first crack (x = y, whose contour crossed a grid edge in its plane, each face around
/// it getting its own tip a face-point margin inside) with the eighth (x + z = 5); cut
/// points of those cracks on different edges lie there within 2e-6 of one another and of
/// the tenth plane, closer than the scalpel's snapping, and the two lips' edges were cut at
/// points a few 1e-6 apart: two hanging vertices, the cut returned as a success. A plain
/// cut continuing cracks now looks for a vertex it makes hanging in a face it makes and,
/// finding one, cuts again with the snapping raised a hundredfold (as for a flat child:
/// 1e-6 to 1e-4 of the local edge length), which snaps those points onto the tenth plane;
/// every cut leaves the grid valid.
#[test]
fn random_partial_scalpel_cuts_seed_2443() {
    let (cuts, refused) = grid_run(CutOptions::SCALPEL, 2443);
    assert_eq!((cuts, refused), (10, 0));
}

fn grid_stress(options: CutOptions) {
    const RUNS: u64 = 200;
    let (mut cuts, mut refused) = (0, 0);
    for seed in 0..RUNS {
        let (c, r) = grid_run(options, seed);
        cuts += c;
        refused += r;
    }
    assert!(
        cuts > 8 * RUNS as usize,
        "{cuts} cuts made, {refused} refused"
    );
}

/// One seeded run of up to 10 cuts (see `grid_stress`), the grid valid after each: cuts
/// made and refused (a refusal ends the run).
fn grid_run(options: CutOptions, seed: u64) -> (usize, usize) {
    let (mut cuts, mut refused) = (0, 0);
    let mut rng = Rng(seed * 7919 + 13);
    let mut cutter = Cutter::new(kuhn_grid(6), options).expect("options");
    for k in 0..10 {
        let Some(polygon) = grid_partial_polygon(&mut rng, 6) else {
            continue;
        };
        match cutter.cut(&polygon) {
            Ok(_) => cuts += 1,
            Err(CutError::FlatChild { .. } | CutError::HangingVertex { .. }) => {
                refused += 1;
                break;
            }
            Err(e) => panic!("seed {seed}, cut {k}: {e}"),
        }
        assert_valid(cutter.mesh(), &format!("seed {seed}, cut {k}"));
    }
    (cuts, refused)
}

/// A crack tip copied by a later cut: scalpel cuts through a Kuhn grid. The seventh (z = 5)
/// ends at x = 3.49, leaving crack tips there; the eighth, in the same plane, overlaps it
/// up to x = 3.59, passes through a tip and copies it (one copy per lip); the ninth
/// (x = 3.5) crosses both lips next to it. The tip itself counted as on the ninth cut (a
/// tip near a polygon continuing cracks is), its copies did not, so one lip's edge from
/// the tip was cut and the coincident edge of the other lip not: 30 hanging vertices. A
/// tip's copies are tips too.
#[test]
fn copies_of_a_crack_tip_are_decided_as_the_tip() {
    let mut cutter = Cutter::new(kuhn_grid(6), CutOptions::SCALPEL).expect("options");
    let polygons = [
        [
            [8.164630548672276, 1.9271104188259436, 3.908259032501781],
            [6.458261655851171, 8.295365823289359, -0.7536274791405309],
            [3.1199294977844723, 9.189869229110178, 1.6902012731053493],
            [4.826298390605578, 2.8216138246467626, 6.352087784747661],
        ],
        [
            [7.008491023962877, 0.9267248559089838, -0.9352158798718602],
            [6.409220326241449, 3.163233547292604, -2.5724538735340525],
            [-1.2976905583098526, 5.2282940949467545, 3.0693964633630975],
            [-0.6984198605884244, 2.991785403563134, 4.70663445702529],
        ],
        [
            [3.0, -5.754257153545846, -3.724390665170687],
            [3.0, 1.637646372824503, -3.724390665170687],
            [3.0, 1.637646372824503, 8.010295005307038],
            [3.0, -5.754257153545846, 8.010295005307038],
        ],
        [
            [0.9689257070358004, 1.0310742929641994, 0.44392276884171483],
            [-0.709071225948436, 2.7090712259484366, -1.92912325140505],
            [-3.8590951643607037, 5.8590951643607045, 2.52568332409749],
            [-2.181098231376467, 4.181098231376467, 4.898729344344255],
        ],
        [
            [2.0, -6.337176037098462, -5.032343014494232],
            [2.0, 8.18888004934145, -5.032343014494232],
            [2.0, 8.18888004934145, 6.696281605793835],
            [2.0, -6.337176037098462, 6.696281605793835],
        ],
        [
            [6.706786126425627, 1.5, 8.16396428055241],
            [6.706786126425627, 1.5, 0.1520075956967304],
            [4.107556040464983, 1.5, 0.1520075956967304],
            [4.107556040464983, 1.5, 8.16396428055241],
        ],
        [
            [8.91479155665441, -0.6982191110930893, 5.0],
            [8.91479155665441, 8.76087636272857, 5.0],
            [3.489697653331932, 8.76087636272857, 5.0],
            [3.489697653331932, -0.6982191110930893, 5.0],
        ],
        [
            [3.59051232339175, 1.9973157165015136, 5.0],
            [3.59051232339175, 5.620736170932454, 5.0],
            [-3.0099630755236593, 5.620736170932454, 5.0],
            [-3.0099630755236593, 1.9973157165015136, 5.0],
        ],
        [
            [3.5, -0.19866605456413122, -0.24955470235840593],
            [3.5, 9.681372063392574, -0.24955470235840593],
            [3.5, 9.681372063392574, 5.881926437215019],
            [3.5, -0.19866605456413122, 5.881926437215019],
        ],
    ];
    for (k, corners) in polygons.iter().enumerate() {
        let polygon = CutPolygon::new(&corners.map(DVec3::from_array)).expect("polygon");
        cutter.cut(&polygon).expect("cut");
        assert_valid(cutter.mesh(), &format!("after cut {k}"));
    }
}

/// Every phase forced onto all cores (threshold 0) and kept on one (`usize::MAX`): the
/// same meshes, cut after cut, with the engine's default snapping and with almost none (a
/// cut then snaps no vertex: a parallel pass over no vertices panicked once).
#[test]
fn one_thread_and_all_cores_give_the_same_mesh() {
    let input = mesh("fandisk");
    let mut rng = Rng(4242);
    for options in [CutOptions::DEFAULT, CutOptions::SCALPEL] {
        let cutter = |threshold: usize| {
            Cutter::new(input.clone(), options.with_parallel_threshold(threshold)).expect("options")
        };
        let (mut seq, mut par) = (cutter(usize::MAX), cutter(0));
        let kinds = [Kind::Through, Kind::Partial, Kind::Vertices];
        for step in 0..12 {
            let kind = if step < kinds.len() {
                kinds[step]
            } else {
                Kind::draw(&mut rng)
            };
            let polygon = random_polygon(seq.mesh(), kind, &mut rng);
            let (a, b) = (seq.cut(&polygon), par.cut(&polygon));
            match (a, b) {
                (Ok(a), Ok(b)) => {
                    assert_eq!(a.origins, b.origins, "cut {step} ({kind:?})");
                    assert_eq!(a.splits, b.splits, "cut {step} ({kind:?})");
                }
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
                (a, b) => panic!("cut {step} ({kind:?}): {:?} and {:?}", a.err(), b.err()),
            }
            assert!(
                seq.mesh() == par.mesh(),
                "cut {step} ({kind:?}): meshes differ between one and all cores"
            );
        }
        assert_valid(par.mesh(), "parallel cuts");
    }
}

#[test]
fn attributes_follow_the_cut() {
    // A linear point field stays linear (interpolated at cut points and face points,
    // copied at duplicated vertices); cell data is inherited; created tets are marked.
    let mut m = mesh("pinion").clone();
    let f = |p: DVec3| 2.0 * p.x - 3.0 * p.y + 0.5 * p.z + 1.0;
    let values: Vec<f64> = m.positions().iter().map(|&p| f(p)).collect();
    m.point_data
        .insert(Attribute::new("f", 1, values).expect("column"));
    // An extraction's MT vertex ids are names, not quantities: not interpolated.
    let vertex_ids: Vec<f64> = (0..m.nb_vertices()).map(|v| v as f64).collect();
    m.point_data
        .insert(Attribute::new(POINT_VERTEX, 1, vertex_ids).expect("column"));
    let ids: Vec<f64> = (0..m.nb_tets()).map(|t| t as f64).collect();
    m.cell_data
        .insert(Attribute::new("id", 1, ids).expect("column"));
    let before = m.nb_tets();
    let before_vertices = m.nb_vertices();
    let mut rng = Rng(99);
    let polygon = random_polygon(mesh("pinion"), Kind::Partial, &mut rng);
    let r = cut_mesh(&mut m, &polygon, &CutOptions::DEFAULT).expect("cut");
    assert_valid(&m, "pinion");
    assert!(r.stats.cut_points > 0 && r.stats.face_points > 0);
    let col = &m.point_data.get("f").expect("f").values;
    for (v, p) in m.positions().iter().enumerate() {
        assert!((col[v] - f(*p)).abs() < 1e-9, "vertex {v}");
    }
    let marks = &m.cell_data.get(CUT_COLUMN).expect("marker").values;
    let id = &m.cell_data.get("id").expect("id").values;
    let mut marked = 0;
    for s in &r.splits {
        for c in s.child_slots() {
            assert_eq!(marks[c.idx()], 1.0);
            assert_eq!(id[c.idx()], s.parent.0 as f64, "inherited");
            marked += 1;
        }
    }
    assert_eq!(marked, r.stats.tets_created);
    assert_eq!(marks.iter().filter(|&&x| x == 1.0).count(), marked);
    assert_eq!(
        m.nb_tets(),
        before - r.stats.tets_cut + r.stats.tets_created
    );
    // Origins describe every new vertex: positions are their linear combinations.
    for (k, o) in r.origins.iter().enumerate() {
        let v = r.first_new_vertex.idx() + k;
        let p = match *o {
            VertexOrigin::Edge { a, b, t, .. } => {
                m.positions()[a.idx()].lerp(m.positions()[b.idx()], t)
            }
            VertexOrigin::Face { v: f, w } => (0..3)
                .map(|i| m.positions()[f[i].idx()] * w[i])
                .sum::<DVec3>(),
            VertexOrigin::Copy { of } => m.positions()[of.idx()],
        };
        assert!((p - m.positions()[v]).length() < 1e-12, "vertex {v}");
    }
    let named = &m.point_data.get(POINT_VERTEX).expect("ids").values;
    assert!(
        named[..before_vertices]
            .iter()
            .enumerate()
            .all(|(v, &id)| id == v as f64)
    );
    for (k, o) in r.origins.iter().enumerate() {
        let id = named[r.first_new_vertex.idx() + k];
        match *o {
            VertexOrigin::Copy { of } => assert_eq!(id, of.0 as f64, "a copy keeps its id"),
            _ => assert_eq!(id, -1.0, "a cut point names no MT vertex"),
        }
    }
}

#[test]
fn components_are_extracted_and_written_alone() {
    let input = mesh("liver");
    let mut m = input.clone();
    let c = square(
        input.bbox().center(),
        DVec3::new(0.2, 0.9, 0.3).normalize(),
        1e3,
    );
    let r = cut_mesh(&mut m, &c, &CutOptions::DEFAULT).expect("cut");
    assert_valid(&m, "liver");
    let comps = Components::of(&m);
    assert_eq!(Some(comps.count), r.stats.components);
    assert!(comps.count >= 2);
    let parts = comps.extract_all(&m);
    let total: f64 = parts.iter().map(|p| p.volume()).sum();
    assert!((total - input.volume()).abs() <= 1e-12 * input.volume());
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/cut-components");
    std::fs::create_dir_all(&dir).expect("output dir");
    for (k, p) in parts.iter().enumerate() {
        assert_valid(p, "component");
        assert_eq!(Components::of(p).count, 1);
        let file = dir.join(format!("liver-{k}.node"));
        mtcut::io::write_mesh(&file, p).expect("write");
        let (back, _) = mtcut::io::read_mesh(&file).expect("read back");
        assert_eq!(back.nb_tets(), p.nb_tets());
    }
    assert!(comps.extract(&m, comps.count).is_none());
}

#[test]
fn the_1_17_scheme_keeps_volume_and_orientation_but_not_conformity() {
    // What the paper says of it (§4.1): 17 tets per cut tet, not a simplicial complex.
    let input = mesh("fandisk");
    let mut m = input.clone();
    let c = square(
        input.bbox().center(),
        DVec3::new(0.3, 0.5, 0.8).normalize(),
        10.0,
    );
    let opts = CutOptions::DEFAULT.with_scheme(Scheme::Bielser17);
    let r = cut_mesh(&mut m, &c, &opts).expect("cut");
    assert_eq!(r.stats.tets_created, 17 * r.stats.tets_cut);
    assert!((m.volume() - input.volume()).abs() <= 1e-12 * input.volume());
    let report = m.validate();
    assert_eq!(
        report.count(ViolationKind::NonPositiveOrientation),
        0,
        "{report}"
    );
    assert!(report.count(ViolationKind::HangingVertex) > 0, "{report}");
}

#[test]
fn statistics_add_up() {
    let input = mesh("fandisk");
    let mut m = input.clone();
    let c = square(input.bbox().center(), DVec3::new(0.6, 0.0, 0.8), 0.3);
    let r = cut_mesh(&mut m, &c, &CutOptions::DEFAULT).expect("cut");
    let s = &r.stats;
    assert_eq!(s.tets_cut_by_case.iter().sum::<usize>(), s.tets_cut);
    assert!(s.cut_in(CutCase::A) + s.cut_in(CutCase::B) > 0);
    assert!(
        s.cut_in(CutCase::C) + s.cut_in(CutCase::D) + s.cut_in(CutCase::E) > 0,
        "partial cut"
    );
    assert_eq!(
        s.vertices_added,
        s.cut_points + s.face_points + s.vertex_copies
    );
    assert_eq!(s.cut_points, 2 * s.edges_cut);
    assert_eq!(s.tets_after, m.nb_tets());
    assert_eq!(s.vertices_after, m.nb_vertices());
    assert!(s.tets_tested >= s.tets_candidate && s.tets_candidate >= s.tets_cut);
    assert!(s.time.build > 0.0 && s.time.cut > 0.0);
    let json = s.to_json();
    assert_eq!(json["tets_cut"], s.tets_cut);
}

#[test]
fn bad_input_is_refused_with_a_reason() {
    let p = |v: &[[f64; 3]]| v.iter().map(|a| DVec3::from_array(*a)).collect::<Vec<_>>();
    assert!(matches!(
        CutPolygon::new(&p(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])),
        Err(PolygonError::TooFewPoints { count: 2 })
    ));
    let bent = CutPolygon::new(&p(&[
        [0., 0., 0.],
        [1., 0., 0.],
        [1., 1., 0.1],
        [0., 1., 0.],
    ]));
    let msg = bent.expect_err("not planar").to_string();
    assert!(
        msg.contains("not planar") && msg.contains("split it into triangles"),
        "{msg}"
    );
    // The same bent quadrilateral as a blade sweep: two triangles.
    let sweep = scalpel_sweep(
        [DVec3::ZERO, DVec3::X],
        [DVec3::Y, DVec3::new(1.0, 1.0, 0.1)],
        Tolerance::DEFAULT,
    )
    .expect("sweep");
    assert_eq!(sweep.len(), 2);
    let mut m = mesh("fandisk").clone();
    let c = square(DVec3::ZERO, DVec3::Z, 1.0);
    let bad = CutOptions::DEFAULT.with_snap(Tolerance { relative: 0.5 });
    let before = m.clone();
    let err = cut_mesh(&mut m, &c, &bad).expect_err("refused");
    assert!(
        matches!(err, CutError::InvalidOption { option: "snap", .. }),
        "{err}"
    );
    assert!(m == before, "a refused cut leaves the mesh alone");
    // No snapping at all is refused: a plane through vertices up to rounding would cut
    // their edges at their very position (flat tets; a unit-cube case found by the C API's
    // random test). The smallest accepted value cuts that case validly.
    let cube = cut_common::kuhn_grid(1);
    let through_vertices = CutPolygon::new(&[
        DVec3::new(-1.875, -4.03125, -4.5),
        DVec3::new(4.125, -2.53125, -1.5),
        DVec3::new(1.875, 4.03125, 4.5),
        DVec3::new(-4.125, 2.53125, 1.5),
    ])
    .expect("planar convex quad");
    let mut m = cube.clone();
    let none = CutOptions::DEFAULT.with_snap(Tolerance { relative: 0.0 });
    assert!(cut_mesh(&mut m, &through_vertices, &none).is_err());
    assert!(m == cube);
    let least = CutOptions::DEFAULT.with_snap(Tolerance { relative: MIN_SNAP });
    let r = cut_mesh(&mut m, &through_vertices, &least).expect("cut");
    assert!(r.stats.tets_cut > 0);
    let report = m.validate();
    assert!(report.is_valid(), "{report}");
    assert!(
        Cutter::new(
            before.clone(),
            CutOptions::DEFAULT.with_face_point_margin(-1.0)
        )
        .is_err()
    );
    // Nearer the ends than MIN_FACE_POINT_MARGIN, face points make flat children.
    assert!(Cutter::new(before, CutOptions::DEFAULT.with_face_point_margin(0.0)).is_err());
}

#[test]
fn a_blade_swept_across_the_body_separates_it() {
    // A blade (a segment longer than the body is high) swept across it in 12 steps, each
    // step cutting the quadrilateral it swept: the cracks of consecutive steps must join,
    // so the body ends in two parts, valid after every step. With face points at the
    // smallest margin the tips follow each step's contour, where the next step begins.
    let options = CutOptions::DEFAULT.with_face_point_margin(MIN_FACE_POINT_MARGIN);
    for name in ["fandisk", "liver"] {
        let input = mesh(name);
        let (b, volume) = (input.bbox(), input.volume());
        let (c, d) = (b.center(), b.max - b.min);
        let blade = |x: f64| {
            [
                DVec3::new(x, c.y + 0.013 * d.y, b.min.z - 0.1 * d.z),
                DVec3::new(x, c.y - 0.011 * d.y, b.max.z + 0.1 * d.z),
            ]
        };
        let x = |k: usize| b.min.x - 0.05 * d.x + 1.1 * d.x * k as f64 / 12.0;
        let mut cutter = Cutter::new(input.clone(), options).expect("options");
        for k in 0..12 {
            let sweep = scalpel_sweep(blade(x(k)), blade(x(k + 1)), Tolerance { relative: 1e-9 })
                .expect("sweep");
            for polygon in &sweep {
                cutter.cut(polygon).expect("cut");
            }
            let report = cutter.mesh().validate();
            assert!(report.is_valid(), "{name}, step {k}: {report}");
            let v = cutter.mesh().volume();
            assert!((v - volume).abs() <= 1e-12 * volume, "{name}, step {k}");
        }
        let parts = Components::of(cutter.mesh()).count;
        assert_eq!(parts, 2, "{name}: the swept blade left {parts} parts");
    }
}

#[test]
fn batches_and_order_do_not_change_the_points() {
    // The core the MT builds on: tets classified in one batch or several, in any order,
    // share one cut point per edge and one face point per face, get the same canonical
    // ids and the same children.
    use mtcut::cut::classify::is_candidate;
    use mtcut::cut::split::{Children, split_tet};
    use mtcut::cut::{CutScratch, CutSession};
    let input = mesh("pinion");
    let scales = mtcut::cut::vertex_scales(input);
    let max_scale = scales.iter().fold(0.0f64, |a, &b| a.max(b));
    let mut rng = Rng(31337);
    let polygon = random_polygon(input, Kind::Partial, &mut rng);
    let opts = CutOptions::DEFAULT;
    let roots = mtcut::cut::split::twin_roots(input.positions());
    let run = |order: &[usize], batches: usize| {
        let mut scratch = CutScratch::new();
        let mut s = CutSession::new(
            &polygon,
            opts.snap,
            opts.face_point_margin,
            &mut scratch,
            input.nb_vertices(),
        );
        let classifier = s.classifier(&input.bbox(), max_scale);
        let tets: Vec<_> = order.iter().map(|&k| input.tets()[k]).collect();
        let states: Vec<[u8; 4]> = tets
            .iter()
            .map(|t| classifier.tet(input.positions(), &scales, t))
            .collect();
        let mut classes = Vec::new();
        let chunk = tets.len().div_ceil(batches);
        for (ts, st) in tets.chunks(chunk).zip(states.chunks(chunk)) {
            classes.extend(s.classify(input.positions(), &scales, ts, st, false));
        }
        let origins = s.allocate(mtcut::mesh::VertexId::from_usize(input.nb_vertices()));
        let mut children: Vec<(usize, Vec<[u32; 4]>)> = Vec::new();
        for ((&k, t), c) in order.iter().zip(&tets).zip(&classes) {
            let mut ch = Children::new();
            if split_tet(&s, t, c, Some(&roots), &mut ch) {
                let mut v: Vec<[u32; 4]> =
                    ch.tets[..ch.len].iter().map(|x| x.map(|y| y.0)).collect();
                v.sort_unstable();
                children.push((k, v));
            }
        }
        children.sort_unstable();
        (origins, children)
    };
    let all: Vec<usize> = (0..input.nb_tets())
        .filter(|&k| {
            let t = input.tets()[k];
            let st = t.map(|v| {
                mtcut::cut::classify::vertex_state(
                    &polygon,
                    opts.snap,
                    input.position(v),
                    scales[v.idx()],
                )
            });
            is_candidate(st)
        })
        .collect();
    assert!(all.len() > 50);
    let (o1, c1) = run(&all, 1);
    let mut shuffled = all.clone();
    for i in (1..shuffled.len()).rev() {
        shuffled.swap(i, rng.below(i + 1));
    }
    let (o2, c2) = run(&shuffled, 5);
    assert_eq!(o1, o2, "new points differ");
    assert_eq!(c1, c2, "children differ");
    assert!(!c1.is_empty());
}
