//! Region-of-interest sub-MTs (issue 6, paper §7): the MT cut along the region's planes,
//! the components inside kept. The sub-MT validates and survives the file; every
//! extraction is a valid mesh inside the region; the finest and coarsest extractions have
//! the volume of the input's finest and coarsest meshes clipped by the region, the finest
//! cross-checked with VTK's clip.

mod common;
mod cut_common;
mod mt_common;
mod mtcut_common;

use mtcut::cut::{RoiError, RoiRegion, region_of_interest};
use mtcut::geom::{Aabb, DVec3};
use mtcut::mt::{ExtractOptions, Mt};

/// A box over the middle of `mt`'s bounding box: `lo`..`hi` as fractions of its extent.
fn sub_box(mt: &Mt, lo: f64, hi: f64) -> Aabb {
    let b = Aabb::from_points(mt.positions());
    let e = b.max - b.min;
    Aabb {
        min: b.min + e * lo,
        max: b.min + e * hi,
    }
}

/// Every extraction valid and inside the box (up to the MT cut's snapping, 1e-6 of the
/// longest edge).
fn check_sub(sub: &Mt, b: &Aabb, case: &str) {
    let report = sub.validate();
    assert!(report.is_valid(), "{case}: {report}");
    let slack = 1e-6 * Aabb::from_points(sub.positions()).diagonal();
    // Ten uniform thresholds, 0 and +∞ included (no focus regions: the rng is unused).
    for o in mtcut_common::requests(sub, 10, 0, &mut mtcut_common::Rng(1)) {
        let e = sub.extract(&o).expect("extraction");
        let v = e.mesh.validate();
        assert!(v.is_valid(), "{case}, {o:?}: {v}");
        for p in e.mesh.positions() {
            assert!(
                p.cmpge(b.min - slack).all() && p.cmple(b.max + slack).all(),
                "{case}, {o:?}: vertex {p} outside the box {} .. {}",
                b.min,
                b.max
            );
        }
    }
    let path = std::env::temp_dir().join(format!("mtcut-roi-{}.mt", std::process::id()));
    sub.save(&path).expect("save");
    let back = Mt::load(&path).expect("load");
    std::fs::remove_file(&path).ok();
    assert!(
        back.canonical_form() == sub.canonical_form(),
        "{case}: file round trip"
    );
}

#[test]
fn a_box_gives_a_valid_sub_mt_inside_it_on_every_shared_mesh() {
    for name in mt_common::MESHES {
        let mt = &mt_common::built(name).1;
        let b = sub_box(mt, 0.3, 0.7);
        let (sub, stats) =
            region_of_interest(mt, &RoiRegion::Box(b)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(stats.planes, 6);
        // The planes cut what the earlier ones left: a last one may find it all inside.
        assert!(
            (5..=6).contains(&stats.planes_cut),
            "{name}: {}",
            stats.to_json()
        );
        assert!(stats.components_kept >= 1 && stats.components_dropped >= 1);
        assert!(
            sub.nb_tets()
                < stats.tets_before + stats.cuts.iter().map(|c| c.tets_created).sum::<usize>()
        );
        check_sub(&sub, &b, name);
        // The input is untouched.
        assert!(mt.validate().is_valid());
    }
}

#[test]
fn the_finest_volume_is_vtks_clip_of_the_finest_mesh() {
    if !common::vtk_python() {
        return;
    }
    let dir = common::scratch("mt_roi vtk");
    for name in mt_common::MESHES {
        let mt = &mt_common::built(name).1;
        let b = sub_box(mt, 0.25, 0.65);
        let (sub, _) = region_of_interest(mt, &RoiRegion::Box(b)).expect("sub-MT");
        let ours = sub.extract(&ExtractOptions::FINEST).unwrap().mesh.volume();
        let finest = mt.extract(&ExtractOptions::FINEST).unwrap().mesh;
        let path = dir.join(format!("{name}-finest.vtu"));
        mtcut::io::write_mesh(&path, &finest).expect("write");
        let coords: Vec<String> = b
            .min
            .to_array()
            .iter()
            .chain(&b.max.to_array())
            .map(|x| format!("{x:?}"))
            .collect();
        let mut args = vec![path.to_str().unwrap()];
        args.extend(coords.iter().map(String::as_str));
        let out: serde_json::Value =
            serde_json::from_str(&common::vtk_script("roi_box_clip.py", &args)).expect("json");
        let theirs = out["volume"].as_f64().expect("volume");
        assert!(
            (ours - theirs).abs() <= 1e-9 * theirs.abs(),
            "{name}: sub-MT finest volume {ours}, VTK's clip {theirs}"
        );
    }
}

#[test]
fn a_sphere_keeps_everything_inside_it() {
    let name = "liver";
    let mt = &mt_common::built(name).1;
    let bb = Aabb::from_points(mt.positions());
    let (center, radius) = (bb.center(), 0.2 * bb.diagonal());
    let (sub, stats) =
        region_of_interest(mt, &RoiRegion::Sphere { center, radius }).expect("sub-MT");
    assert_eq!(stats.planes, 14);
    // Each plane cuts only what the earlier ones left inside: the tets the 14 cuts make
    // stay of the order of the model's (cutting the whole body along every plane made a
    // 6,000-tet model's pool a million tets, a 140,000-tet one's many millions).
    let created: usize = stats.cuts.iter().map(|c| c.tets_created).sum();
    assert!(
        created < 2 * stats.tets_before,
        "{created} tets made from {}",
        stats.tets_before
    );
    // Inside the circumscribing polyhedron, hence its box.
    let cube = Aabb {
        min: center - DVec3::splat(radius),
        max: center + DVec3::splat(radius),
    };
    check_sub(&sub, &cube, "liver sphere");
    // Every finest tet of the input inside the sphere is in the sub-MT's finest mesh:
    // compare volumes inside the sphere by the tets' centroids.
    let finest = sub.extract(&ExtractOptions::FINEST).unwrap().mesh;
    let input = mt.extract(&ExtractOptions::FINEST).unwrap().mesh;
    let inside_volume = |m: &mtcut::mesh::TetMesh, r: f64| -> f64 {
        m.tets()
            .iter()
            .filter(|t| {
                let c: DVec3 = t.iter().map(|v| m.positions()[v.idx()]).sum::<DVec3>() * 0.25;
                c.distance(center) < r
            })
            .map(|t| {
                let p = t.map(|v| m.positions()[v.idx()]);
                mtcut::geom::signed_volume(p[0], p[1], p[2], p[3])
            })
            .sum()
    };
    // Tets well inside (half the radius) are untouched by the cuts: same volume.
    let (a, b) = (
        inside_volume(&finest, 0.5 * radius),
        inside_volume(&input, 0.5 * radius),
    );
    assert!((a - b).abs() <= 1e-9 * b, "{a} vs {b}");
}

#[test]
fn a_box_holding_the_body_changes_nothing_and_one_missing_it_is_refused() {
    let mt = &mt_common::built("fandisk").1;
    let bb = Aabb::from_points(mt.positions());
    let grown = Aabb {
        min: bb.min - DVec3::splat(0.1),
        max: bb.max + DVec3::splat(0.1),
    };
    let (sub, stats) = region_of_interest(mt, &RoiRegion::Box(grown)).expect("sub-MT");
    assert_eq!(stats.planes_cut, 0);
    assert!(sub.canonical_form() == mt.canonical_form());
    let away = Aabb {
        min: bb.max + DVec3::splat(1.0),
        max: bb.max + DVec3::splat(2.0),
    };
    assert!(matches!(
        region_of_interest(mt, &RoiRegion::Box(away)),
        Err(RoiError::Misses { .. })
    ));
    let flat = Aabb {
        min: bb.min,
        max: DVec3::new(bb.min.x, bb.max.y, bb.max.z),
    };
    assert!(matches!(
        region_of_interest(mt, &RoiRegion::Box(flat)),
        Err(RoiError::InvalidRegion(_))
    ));
    // A box far smaller than the tet it lies in: inside the body, but nothing of it is
    // left inside once cut (the cut snaps at 1e-6 of an edge), which the error says
    // rather than "does not meet the body".
    let finest = mt.extract(&ExtractOptions::FINEST).unwrap().mesh;
    let c = finest.tets()[0]
        .map(|v| finest.position(v))
        .iter()
        .sum::<DVec3>()
        * 0.25;
    let tiny = Aabb {
        min: c - DVec3::splat(1e-9),
        max: c + DVec3::splat(1e-9),
    };
    let e = region_of_interest(mt, &RoiRegion::Box(tiny)).unwrap_err();
    assert!(matches!(e, RoiError::NothingInside { .. }), "{e}");
    assert!(e.to_string().contains("too small"), "{e}");
    let nan = RoiRegion::Sphere {
        center: DVec3::new(f64::NAN, 0.0, 0.0),
        radius: 1.0,
    };
    assert!(matches!(
        region_of_interest(mt, &nan),
        Err(RoiError::InvalidRegion(_))
    ));
}

#[test]
fn a_box_through_grid_vertices_works() {
    // Faces exactly through vertices of a grid (degenerate cuts at every level).
    let grid = Mt::build(&cut_common::grid_mesh(6), &mtcut::mt::BuildOptions::DEFAULT)
        .expect("build")
        .0;
    let b = Aabb {
        min: DVec3::new(1.0, 1.0, 1.0),
        max: DVec3::new(4.0, 5.0, 3.0),
    };
    let (sub, _) = region_of_interest(&grid, &RoiRegion::Box(b)).expect("sub-MT");
    check_sub(&sub, &b, "grid");
    let v = sub.extract(&ExtractOptions::FINEST).unwrap().mesh.volume();
    assert!((v - 24.0).abs() <= 1e-9, "volume {v}, expected 3 × 4 × 2");
}
