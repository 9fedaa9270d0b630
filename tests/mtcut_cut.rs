//! Cutting the MT (issue 6): after every cut the MT is valid, the finest and coarsest
//! meshes keep their volume, and extractions at 10 thresholds and 5 random focus regions
//! are valid meshes crossed by none of the polygons applied. Cuts of every kind
//! (through, partial, tiny, through vertices, along an edge, along a face) on the three
//! shared meshes, sequences of 50 cuts, any fragment order giving the same MT,
//! independent components, and the `.mt` file.

mod cut_common;
mod mt_common;
mod mtcut_common;

use cut_common::{Kind, random_polygon};
use mtcut::cut::{CutError, CutOptions, MtCutter};
use mtcut::geom::CutPolygon;
use mtcut::mesh::FragmentId;
use mtcut::mt::{ExtractOptions, Mt};
use mtcut_common::*;

fn cutter(name: &str) -> MtCutter {
    MtCutter::new(mt_common::built(name).1.clone(), MtCutter::DEFAULT_OPTIONS)
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Cuts `cutter` with `polygon` and checks everything; panics naming the case.
fn cut_and_check(
    cutter: &mut MtCutter,
    volumes: (f64, f64),
    polygons: &mut Vec<CutPolygon>,
    polygon: CutPolygon,
    regions: Option<usize>,
    rng: &mut Rng,
    case: &str,
) {
    let stats = cutter
        .cut(&polygon)
        .unwrap_or_else(|e| panic!("{case}: cut refused: {e}"));
    polygons.push(polygon);
    // `regions`: None for no extraction check, else that many focus regions too.
    let req = match regions {
        Some(r) => requests(cutter.mt(), 10, r, rng),
        None => Vec::new(),
    };
    if let Err(m) = check_after_cut(cutter, volumes, polygons, &req) {
        panic!(
            "{case}: {m}\nstats {}\npolygon {:?}",
            stats.to_json(),
            polygons.last().map(|p| p.points().to_vec())
        );
    }
}

fn every_kind(regions: usize) {
    for name in mt_common::MESHES {
        let mesh = cut_common::mesh(name);
        let volumes = extreme_volumes(&mt_common::built(name).1);
        for kind in Kind::ALL {
            for seed in 0..2u64 {
                let mut rng = cut_common::Rng(1000 * seed + kind as u64);
                let polygon = random_polygon(mesh, kind, &mut rng);
                let mut c = cutter(name);
                let case = format!("{name} {kind:?} seed {seed}");
                cut_and_check(
                    &mut c,
                    volumes,
                    &mut Vec::new(),
                    polygon,
                    Some(regions),
                    &mut Rng(seed),
                    &case,
                );
                if kind == Kind::Through {
                    assert!(
                        c.mt().nb_components() >= 2,
                        "{case}: a cut straight through left {} component",
                        c.mt().nb_components()
                    );
                }
            }
        }
    }
}

/// 50 cuts in a row on each mesh, validated after every one; extractions (10 thresholds,
/// `regions` focus regions) checked against every polygon so far after every `every`-th
/// cut and the last (the full check after each of the 150 cuts runs in
/// `sequences_full_check`, ignored: `cargo test --test mtcut_cut -- --ignored
/// sequences_full_check`); at the end, every extraction's star at every vertex the cuts
/// made.
fn sequence(name: &str, seed: u64, every: usize, regions: usize) {
    let mesh = cut_common::mesh(name);
    let volumes = extreme_volumes(&mt_common::built(name).1);
    let mut c = cutter(name);
    let mut rng = cut_common::Rng(seed);
    let mut polygons = Vec::new();
    for i in 0..50 {
        let kind = Kind::draw(&mut rng);
        let polygon = random_polygon(mesh, kind, &mut rng);
        let case = format!("{name} sequence seed {seed}, cut {i} ({kind:?})");
        let extract = i % every == every - 1 || i == 49;
        cut_and_check(
            &mut c,
            volumes,
            &mut polygons,
            polygon,
            extract.then_some(regions),
            &mut Rng(seed + i as u64),
            &case,
        );
    }
    // Every extraction, beyond those sampled after the cuts: none is pinched at a vertex the
    // cuts made (read in the order of the DAG after them, apart from the MT cut's own
    // check, which reads the order before each cut).
    if let Some(m) = pinched_extraction(c.mt(), mesh.nb_vertices(), 1 << 14) {
        panic!("{name} sequence seed {seed}, after 50 cuts: an extraction is pinched: {m}");
    }
}

/// Every kind of cut on every mesh, each on a fresh MT: validate, volumes, and 10
/// uniform-threshold extractions valid and uncrossed.
#[test]
fn every_kind_on_every_mesh() {
    every_kind(0);
}

/// The same with 5 random focus regions per cut too.
#[test]
fn every_kind_on_every_mesh_with_focus() {
    every_kind(5);
}

#[test]
#[ignore = "long (1-2 minutes each): scripts/test.sh runs them apart from the rest"]
fn sequence_of_50_cuts_fandisk() {
    sequence("fandisk", 11, 5, 5);
}

#[test]
#[ignore = "long, see sequence_of_50_cuts_fandisk"]
fn sequence_of_50_cuts_pinion() {
    sequence("pinion", 12, 5, 5);
}

#[test]
#[ignore = "long, see sequence_of_50_cuts_fandisk"]
fn sequence_of_50_cuts_liver() {
    sequence("liver", 13, 5, 5);
}

#[test]
#[ignore = "long (576 s in the test profile on two cores): every extraction check, focus \
            regions included, after each of 150 cuts"]
fn sequences_full_check() {
    for (k, name) in mt_common::MESHES.iter().enumerate() {
        sequence(name, 21 + k as u64, 1, 5);
    }
}

#[test]
fn any_fragment_order_gives_the_same_mt() {
    for name in mt_common::MESHES {
        let mesh = cut_common::mesh(name);
        for kind in [Kind::Through, Kind::Partial, Kind::Vertices] {
            let mut rng = cut_common::Rng(77 + kind as u64);
            let polygon = random_polygon(mesh, kind, &mut rng);
            let mut reference = cutter(name);
            reference.cut(&polygon).expect("cut");
            let expected = reference.mt().canonical_form();
            for seed in 1..4u64 {
                let mut c = cutter(name);
                let key = move |f: FragmentId| {
                    let mut r = Rng(seed.wrapping_mul(0x9E37) ^ f.0 as u64);
                    r.next_u64()
                };
                c.cut_in_order(&polygon, Some(&key)).expect("cut");
                assert!(
                    c.mt().validate().is_valid(),
                    "{name} {kind:?} order seed {seed}"
                );
                assert!(
                    c.mt().canonical_form() == expected,
                    "{name} {kind:?}: fragment order seed {seed} gave another MT"
                );
            }
        }
    }
}

#[test]
fn cut_through_gives_independent_mts_that_survive_the_file() {
    let name = "fandisk";
    let mesh = cut_common::mesh(name);
    let mut rng = cut_common::Rng(5);
    let polygon = random_polygon(mesh, Kind::Through, &mut rng);
    let mut c = cutter(name);
    let stats = c.cut(&polygon).expect("cut");
    let mt = c.mt();
    assert_eq!(stats.components, mt.nb_components());
    assert!(mt.nb_components() >= 2, "{}", stats.to_json());
    let (finest, coarsest) = extreme_volumes(mt);
    let (mut sum_f, mut sum_c) = (0.0, 0.0);
    for k in 0..mt.nb_components() {
        let part = mt.component(k).expect("component in range");
        assert!(
            part.validate().is_valid(),
            "component {k}: {}",
            part.validate()
        );
        assert_eq!(part.nb_components(), 1, "component {k}");
        assert!(!part.roots().is_empty() && !part.drains().is_empty());
        let (f, c) = extreme_volumes(&part);
        sum_f += f;
        sum_c += c;
    }
    assert!(mt.component(mt.nb_components()).is_none());
    assert!(
        (sum_f - finest).abs() <= 1e-12 * finest,
        "{sum_f} vs {finest}"
    );
    assert!(
        (sum_c - coarsest).abs() <= 1e-12 * coarsest,
        "{sum_c} vs {coarsest}"
    );
    let dir = std::env::temp_dir().join(format!("mtcut-mtcut-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("cut.mt");
    mt.save(&path).expect("save");
    let back = Mt::load(&path).expect("load");
    assert!(back == *mt, "the .mt file changed the cut MT");
    assert_eq!(back.nb_components(), mt.nb_components());
    let e = back
        .component(1)
        .expect("second part")
        .extract(&ExtractOptions::COARSEST)
        .expect("extract");
    assert!(e.mesh.validate().is_valid());
    // A damaged file of a cut MT is still rejected with a message.
    let mut bytes = std::fs::read(&path).expect("read");
    let n = bytes.len();
    bytes[n / 2] ^= 0x40;
    std::fs::write(&path, &bytes).expect("write");
    let err = Mt::load(&path).expect_err("corrupt file loaded");
    assert!(err.to_string().contains("checksum"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn options_the_mt_cannot_honour_are_refused() {
    let mt = mt_common::built("fandisk").1.clone();
    for (opts, what) in [
        (CutOptions::DEFAULT, "snap"),
        (
            MtCutter::DEFAULT_OPTIONS.with_scheme(mtcut::cut::Scheme::Bielser17),
            "scheme",
        ),
    ] {
        match MtCutter::new(mt.clone(), opts) {
            Err(CutError::InvalidOption { option, .. }) => assert_eq!(option, what),
            Err(e) => panic!("{what}: {e}"),
            Ok(_) => panic!("{what}: accepted"),
        }
    }
}

/// A square through the middle of `mt`'s box in a tilted plane, the square next to it in
/// that plane (continuing its crack), and a cut straight through in the same plane.
fn squares_in_a_plane(mt: &Mt) -> [CutPolygon; 3] {
    use mtcut::geom::DVec3;
    let b = mtcut::geom::Aabb::from_points(mt.positions());
    let (c, d) = (b.center(), b.max - b.min);
    let square = |cx: f64, h: f64| {
        let p = |x: f64, y: f64| DVec3::new(x, y, c.z + 0.07 * (x - c.x) + 0.04 * (y - c.y));
        let corners = [(-h, -h), (h, -h), (h, h), (-h, h)];
        CutPolygon::new(&corners.map(|(dx, dy)| p(cx + dx, c.y + dy))).expect("square")
    };
    let h = 0.15 * d.length();
    [
        square(c.x, h),
        square(c.x + 2.0 * h, h),
        square(c.x, 3.0 * d.length()),
    ]
}

/// With the default options: a square cut, the square next to it in its plane, then a cut
/// straight through in the same plane ([`squares_in_a_plane`]). With the engine's
/// face-point margin of 0.5 the second left fragments with a face twice on the three
/// shared meshes (see the next test).
#[test]
fn a_cut_continuing_an_earlier_one_in_its_plane_stays_valid() {
    for name in mt_common::MESHES {
        let mt = &mt_common::built(name).1;
        let volumes = extreme_volumes(mt);
        let mut c = cutter(name);
        let mut polygons = Vec::new();
        let mut rng = Rng(5);
        for (k, p) in squares_in_a_plane(mt).into_iter().enumerate() {
            let case = format!("{name}, cut {k}");
            cut_and_check(&mut c, volumes, &mut polygons, p, Some(1), &mut rng, &case);
        }
        assert!(c.mt().nb_components() >= 2, "{name}: not cut through");
    }
}

/// The check of the fragments a cut changed, on a collapse fragment: with a face-point
/// margin of 0.5 (not the MT cut's default), the second of [`squares_in_a_plane`] would
/// leave a fragment of fandisk's MT with a face twice. It is refused, naming that
/// fragment, and the MT is byte for byte as before. (Should such cuts become valid with
/// that margin, this test needs another cut the check refuses.)
#[test]
fn a_cut_leaving_a_fragment_with_a_face_twice_is_refused() {
    let mt = mt_common::built("fandisk").1.clone();
    let [first, second, _] = squares_in_a_plane(&mt);
    let options = MtCutter::DEFAULT_OPTIONS.with_face_point_margin(0.5);
    let mut c = MtCutter::new(mt, options).expect("options");
    c.cut(&first).expect("first square");
    assert!(c.mt().validate().is_valid());
    let before = c.mt().to_bytes();
    match c.cut(&second) {
        Err(CutError::MtInconsistent { fragment, detail }) => {
            let kind = c.mt().fragment_kind(FragmentId::from_usize(fragment));
            assert_eq!(kind, mtcut::mt::FragmentKind::Collapse, "{detail}");
            assert!(detail.contains("doubled"), "{detail}");
        }
        other => panic!("expected a refusal, got {other:?}"),
    }
    assert!(
        c.mt().to_bytes() == before,
        "the refused cut changed the MT"
    );
    assert!(c.mt().validate().is_valid());
}

/// A second cut overlapping a partial first one nearly in its plane — offset by 1e-9 of the
/// model's size and tilted by 1e-6, or offset by 1e-7 — is made in the first one's plane
/// (`moved_to_plane`): the MT valid, every extraction crossed by neither polygon as cut.
/// Before, both were refused on liver and the first on fandisk (the levels met the
/// crack's lips on either side of the new plane, differently). A cut offset by 1e-3 is not
/// moved.
#[test]
fn a_cut_close_to_an_earlier_cracks_plane_is_made_in_that_plane() {
    use mtcut::geom::Aabb;
    for name in mt_common::MESHES {
        let mt = &mt_common::built(name).1;
        let volumes = extreme_volumes(mt);
        let b = Aabb::from_points(mt.positions());
        let mut rng = Rng(11);
        for (eps, tilt, moved) in [(1e-9, 1e-6, true), (1e-7, 0.0, true), (1e-3, 0.0, false)] {
            let case = format!("{name}, offset {eps:e}, tilt {tilt:e}");
            let mut c = cutter(name);
            let mut polygons = Vec::new();
            let [first, given] = nearly_coplanar_bands(b.center(), b.diagonal(), eps, tilt);
            cut_and_check(
                &mut c,
                volumes,
                &mut polygons,
                first.clone(),
                None,
                &mut rng,
                &case,
            );
            let stats = c
                .cut(&given)
                .unwrap_or_else(|e| panic!("{case}: second cut refused: {e}"));
            assert_eq!(stats.moved_to_plane, moved, "{case}");
            // The polygon the MT was cut by: the given one, projected onto the first's
            // plane when moved.
            polygons.push(if moved {
                projected_onto(&given, &first)
            } else {
                given
            });
            let req = requests(c.mt(), 10, 2, &mut rng);
            check_after_cut(&c, volumes, &polygons, &req).unwrap_or_else(|m| panic!("{case}: {m}"));
        }
    }
}

/// The same after eight other cuts with cracks of their own (small squares away from the
/// bands, each in its own plane), so that the first band is no longer among the cuts the
/// record keeps: its plane is (every crack's plane at rest is kept), and the second band,
/// offset by 1e-9 of the model's size and tilted by 5e-6, or offset by 1e-7, is made in
/// it. Before, 12 of 60 such second cuts (three meshes, five offsets, four tilts) were
/// refused, among them both cases here on fandisk and the second on liver.
#[test]
fn a_cut_close_to_an_older_cracks_plane_is_made_in_it_after_other_cuts() {
    use mtcut::geom::{Aabb, DVec3};
    for name in mt_common::MESHES {
        let mt = &mt_common::built(name).1;
        let volumes = extreme_volumes(mt);
        let b = Aabb::from_points(mt.positions());
        let (c0, d) = (b.center(), b.diagonal());
        let band_normal = DVec3::new(0.3, 0.5, 0.8).normalize();
        let far: Vec<DVec3> = mt
            .positions()
            .iter()
            .copied()
            .filter(|p| band_normal.dot(*p - c0).abs() > 0.2 * d)
            .collect();
        let mut rng = Rng(13);
        for (eps, tilt) in [(1e-9, 5e-6), (1e-7, 0.0)] {
            let case = format!("{name}, offset {eps:e}, tilt {tilt:e}");
            let mut c = cutter(name);
            let [first, given] = nearly_coplanar_bands(c0, d, eps, tilt);
            let mut polygons = vec![first.clone()];
            c.cut(&first)
                .unwrap_or_else(|e| panic!("{case}: first cut refused: {e}"));
            let mut others = 0;
            for k in 0..64 {
                if others == 8 {
                    break;
                }
                let o = far[(k * 7919) % far.len()];
                let n = DVec3::new(1.0, 0.2 * k as f64, 0.1).normalize();
                let (u, r) = (n.any_orthonormal_vector(), 0.04 * d);
                let w = n.cross(u);
                let square = CutPolygon::new(&[
                    o + (u + w) * r,
                    o + (w - u) * r,
                    o - (u + w) * r,
                    o + (u - w) * r,
                ])
                .expect("square");
                let nv = c.mt().nb_vertices();
                c.cut(&square)
                    .unwrap_or_else(|e| panic!("{case}: square {k} refused: {e}"));
                if c.mt().nb_vertices() > nv {
                    others += 1;
                    polygons.push(square);
                }
            }
            let record = &c.mt().info().cuts;
            assert_eq!(record.cuts_kept(), 8, "{case}: the first band still kept");
            assert_eq!(record.planes_kept(), 9, "{case}");
            let stats = c
                .cut(&given)
                .unwrap_or_else(|e| panic!("{case}: second band refused: {e}"));
            assert!(stats.moved_to_plane, "{case}");
            polygons.push(projected_onto(&given, &first));
            let req = requests(c.mt(), 10, 2, &mut rng);
            check_after_cut(&c, volumes, &polygons, &req).unwrap_or_else(|m| panic!("{case}: {m}"));
        }
    }
}

/// A blade swept across the MT in 12 steps, each cutting the quadrilateral it swept (the
/// plain-mesh engine passes the same test: tests/cut_engine.rs). The progressive scalpel
/// of issue 7 needs it.
#[test]
fn a_blade_swept_across_the_mt_stays_valid() {
    use mtcut::geom::{DVec3, Tolerance, scalpel_sweep};
    let options = MtCutter::DEFAULT_OPTIONS;
    for name in mt_common::MESHES {
        let mt = mt_common::built(name).1.clone();
        let volumes = extreme_volumes(&mt);
        let b = mtcut::geom::Aabb::from_points(mt.positions());
        let (c, d) = (b.center(), b.max - b.min);
        let blade = |x: f64| {
            [
                DVec3::new(x, c.y + 0.013 * d.y, b.min.z - 0.1 * d.z),
                DVec3::new(x, c.y - 0.011 * d.y, b.max.z + 0.1 * d.z),
            ]
        };
        let x = |k: usize| b.min.x - 0.05 * d.x + 1.1 * d.x * k as f64 / 12.0;
        let mut cutter = MtCutter::new(mt, options).expect("options");
        let mut polygons = Vec::new();
        for k in 0..12 {
            let sweep = scalpel_sweep(blade(x(k)), blade(x(k + 1)), Tolerance { relative: 1e-9 })
                .expect("sweep");
            for polygon in sweep {
                cutter.cut(&polygon).expect("cut");
                polygons.push(polygon);
            }
            let req = requests(cutter.mt(), 10, 0, &mut Rng(k as u64));
            if let Err(m) = check_after_cut(&cutter, volumes, &polygons, &req) {
                panic!("{name}, step {k}: {m}");
            }
        }
        assert!(
            cutter.mt().nb_components() >= 2,
            "{name}: the blade did not separate"
        );
    }
}

/// A new point can round an ulp beyond the points it combines: here a face point lands at
/// z = 2 + 4.4e-16 on a grid whose vertices (integers) lie on the steps fragment boxes are
/// stored in, beyond the box of a fragment whose tets the cut wrote but did not split.
/// Found through the C ABI: `validate` reported the box as stale after a successful cut.
#[test]
fn a_new_point_rounding_past_a_fragments_box_grows_the_box() {
    use mtcut::geom::DVec3;
    let grid = cut_common::kuhn_grid(6);
    let mt = Mt::build(&grid, &mtcut::mt::BuildOptions::DEFAULT)
        .expect("built")
        .0;
    let triangle = CutPolygon::new(&[
        DVec3::new(-0.30000000000000004, 3.0, 3.5999999999999996),
        DVec3::new(0.28346481902525733, 2.9616409468947973, 3.5999999999999996),
        DVec3::new(0.1784648190252573, 2.9616409468947973, -0.6000000000000001),
    ])
    .expect("a triangle");
    let mut cutter = MtCutter::new(mt, MtCutter::DEFAULT_OPTIONS).expect("options");
    cutter.cut(&triangle).expect("cut");
    let report = cutter.mt().validate();
    assert!(report.is_valid(), "{report}");
}

/// Seeded partial cuts through a Kuhn grid's vertices on its MT: the plain engine's
/// degenerate runs (tests/cut_engine.rs), same seeds, planes holding grid edges and faces
/// and crossing earlier cracks along them. Some runs meet a cut the MT refuses within 10
/// cuts (cracks of different levels that do not agree); a refused cut must leave the MT
/// byte for byte as it was, and every cut taken must leave it valid (`Mt::validate`: every
/// fragment, the finest and the coarsest mesh). Seeds 0–99, and 155, whose fifth cut
/// leaves two points 1 ulp apart, one just inside a boundary face at the other: `validate`
/// took it for a hanging vertex (see the README). They take 828 cuts, 51 runs all ten;
/// while every earlier crack's vertex on a cut's plane counted as `OUT`, far fewer (29 of
/// seeds 0–299 were refused at their second cut); without the cut's own look for a
/// hanging vertex, seeds 4, 14, 60, 83 and 98 would now be taken with one in the coarsest
/// mesh.
#[test]
fn random_partial_cuts_through_grid_vertices_keep_the_mt_valid() {
    let mt = Mt::build(&cut_common::kuhn_grid(6), &mtcut::mt::BuildOptions::DEFAULT)
        .expect("built")
        .0;
    let (mut cuts, mut refused) = (0, 0);
    for seed in (0..100).chain([155]) {
        let mut rng = cut_common::Rng(seed * 7919 + 13);
        let mut c = MtCutter::new(mt.clone(), MtCutter::DEFAULT_OPTIONS).expect("options");
        for k in 0..10 {
            let Some(polygon) = cut_common::grid_partial_polygon(&mut rng, 6) else {
                continue;
            };
            let before = c.mt().to_bytes();
            match c.cut(&polygon) {
                Ok(_) => cuts += 1,
                Err(CutError::MtInconsistent { .. } | CutError::FlatChild { .. }) => {
                    assert!(
                        c.mt().to_bytes() == before,
                        "seed {seed}, cut {k}: the refused cut changed the MT"
                    );
                    refused += 1;
                    break;
                }
                Err(e) => panic!("seed {seed}, cut {k}: {e}"),
            }
            let report = c.mt().validate();
            assert!(report.is_valid(), "seed {seed}, cut {k}: {report}");
        }
    }
    assert!(cuts >= 750, "{cuts} cuts made, {refused} refused");
}

/// A crack reaching a vertex of an earlier crack in another plane: random partial cuts
/// through the vertices of a Kuhn grid, the fourth (the plane x − y = −2) ending 0.4 short
/// of the vertex (0, 2, 5), which lies in its plane on the lip of the second (x + z = 5).
/// When an earlier crack's vertex on the plane counted as `OUT` whatever the earlier
/// crack's plane, the fourth cut's crack faces reached that vertex and divided its tets on
/// that lip, the finest mesh pinched there (two fans of boundary faces at one point), and
/// the cut was refused. A crack in another plane meets this one along a line: its vertices
/// there keep their sides (`continues_a_crack_plane`), and the cut is taken, the MT valid.
#[test]
fn a_crack_ending_near_a_vertex_of_an_earlier_crack_in_another_plane_is_taken() {
    use mtcut::geom::DVec3;
    let grid = cut_common::kuhn_grid(6);
    let mt = Mt::build(&grid, &mtcut::mt::BuildOptions::DEFAULT)
        .expect("built")
        .0;
    let polygons = [
        [
            [7.597082354237791, -1.804782385384828, -1.2922999688529617],
            [5.912513458469667, 4.482114322472012, -5.894627780941678],
            [-2.9537305887318404, 6.857817254816904, 0.5959133339149352],
            [-1.2691616929637157, 0.5709205469600644, 5.198241146003651],
        ],
        [
            [3.985941304701671, 1.4087722584450768, 1.014058695298329],
            [3.985941304701671, 6.799398784507278, 1.014058695298329],
            [-0.36332520835701043, 6.799398784507278, 5.36332520835701],
            [-0.36332520835701043, 1.4087722584450768, 5.36332520835701],
        ],
        [
            [10.316142358697967, -4.316142358697967, 2.066306827682638],
            [7.836538439361997, -1.8365384393619955, -1.4403826643557736],
            [0.431781343444102, 5.568218656555898, 9.031525246769727],
            [2.911385262780072, 3.0886147372199275, 12.538214738808138],
        ],
        [
            [-0.733696722446735, 1.2663032775532632, -5.6629845057772314],
            [4.070156083427588, 6.070156083427589, 1.130689283934286],
            [0.8829099466969783, 2.882909946696979, 5.638135997119969],
            [
                -3.9209428591773454,
                -1.9209428591773472,
                -1.1555377925915487,
            ],
        ],
    ]
    .map(|c| CutPolygon::new(&c.map(DVec3::from_array)).expect("polygon"));
    let mut c = MtCutter::new(mt, MtCutter::DEFAULT_OPTIONS).expect("options");
    for (k, p) in polygons[..3].iter().enumerate() {
        c.cut(p).expect("cut");
        let report = c.mt().validate();
        assert!(report.is_valid(), "after cut {k}: {report}");
    }
    c.cut(&polygons[3]).expect("the fourth cut");
    let report = c.mt().validate();
    assert!(report.is_valid(), "after the fourth cut: {report}");
}

/// A crack continued in its own plane that would divide an earlier crack's vertex: Kuhn-grid
/// seed 72 of `random_partial_cuts_through_grid_vertices_keep_the_mt_valid`, whose fourth
/// cut lies in the plane of the first (x + y = 9; the second is x + z = 9, the third
/// x + y = 5), so the first crack's vertices on it outside the polygon are `OUT` (the lips
/// and tips of a crack continued in its own plane). Its crack faces would reach one of
/// them and divide its tets: the finest mesh pinched there. The cut is refused, the MT
/// unchanged and valid.
#[test]
fn a_crack_dividing_an_earlier_cracks_vertex_is_refused() {
    grid_run_refused_at(72, 3, "finest mesh would be pinched");
}

/// A cut whose crack would leave a vertex hanging in the coarsest mesh: Kuhn-grid seed 98
/// (as above), whose sixth cut (y = 3.5) meets the second crack (x = y) near its tips,
/// which lie a face-point margin (2.2e-6) off that plane; the sixth cut's points there lie
/// nearly on one line, one of them inside a coarse crack face by 2e-8 (a T-junction the fragments' floors and
/// ceilings do not show: they match face by face). Before the cut looked for hanging
/// vertices it was taken and `Mt::validate` found the coarsest mesh invalid; it is
/// refused, the MT unchanged and valid.
#[test]
fn a_cut_leaving_a_hanging_vertex_is_refused() {
    grid_run_refused_at(98, 5, "coarsest mesh would have a hanging vertex");
}

/// Replays the Kuhn-grid run of `seed` (`random_partial_cuts_through_grid_vertices_keep_the_mt_valid`'s
/// draws, each one a polygon): its first `taken` cuts leave the MT valid, the next is
/// refused with a detail holding `why`, the MT as it was and valid.
fn grid_run_refused_at(seed: u64, taken: usize, why: &str) {
    let mt = Mt::build(&cut_common::kuhn_grid(6), &mtcut::mt::BuildOptions::DEFAULT)
        .expect("built")
        .0;
    let mut rng = cut_common::Rng(seed * 7919 + 13);
    let polygons: Vec<CutPolygon> = (0..=taken)
        .map(|_| cut_common::grid_partial_polygon(&mut rng, 6).expect("a polygon"))
        .collect();
    let mut c = MtCutter::new(mt, MtCutter::DEFAULT_OPTIONS).expect("options");
    for (k, p) in polygons[..taken].iter().enumerate() {
        c.cut(p).expect("cut");
        let report = c.mt().validate();
        assert!(report.is_valid(), "after cut {k}: {report}");
    }
    let before = c.mt().to_bytes();
    match c.cut(&polygons[taken]) {
        Err(CutError::MtInconsistent { detail, .. }) => {
            assert!(detail.contains(why), "{detail}");
        }
        Ok(_) => {
            let report = c.mt().validate();
            panic!("expected a refusal; the cut was kept: {report}");
        }
        Err(e) => panic!("expected a refusal ({why}), got {e}"),
    }
    assert!(
        c.mt().to_bytes() == before,
        "the refused cut changed the MT"
    );
    assert!(c.mt().validate().is_valid());
}

/// Three cuts straight through fandisk: the MT should hold one independent component per
/// piece the cuts leave (the same at the finest and the coarsest level).
#[test]
fn mt_components_follow_the_pieces() {
    use mtcut::geom::{Aabb, DVec3};
    let mt = mt_common::built("fandisk").1.clone();
    let b = Aabb::from_points(mt.positions());
    let (e, reach) = (b.max - b.min, 2.0 * b.diagonal() + 1.0);
    let plane = |n: DVec3, offset: f64| {
        let origin = b.center() - n * (n.dot(b.center()) - offset);
        let u = n.any_orthonormal_vector() * reach;
        let w = n.cross(u);
        CutPolygon::new(&[
            origin - u - w,
            origin + u - w,
            origin + u + w,
            origin - u + w,
        ])
        .expect("square")
    };
    let mut c = MtCutter::new(mt, MtCutter::DEFAULT_OPTIONS).expect("options");
    for p in [
        plane(DVec3::X, b.min.x + 0.25 * e.x),
        plane(DVec3::Y, b.min.y + 0.65 * e.y),
        plane(DVec3::Z, b.min.z + 0.65 * e.z),
    ] {
        c.cut(&p).expect("cut");
        let finest = c
            .mt()
            .extract(&ExtractOptions::FINEST)
            .expect("finest")
            .mesh;
        let pieces = mtcut::cut::Components::of(&finest).count;
        assert_eq!(c.mt().nb_components(), pieces);
    }
}
