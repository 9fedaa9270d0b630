//! `mtcut roi MODEL.mt (--box ... | --sphere ...) -o SUB.mt`: the written sub-model is
//! valid on reload, its extractions lie in the region and its finest level has the
//! volume the region holds of the input's finest mesh (by the library's own clip, which
//! tests/mt_roi.rs cross-checks with VTK); bad regions fail with a message and write
//! nothing.

mod cli_support;
mod common;

use cli_support::{close, fails, has_keys, json, ok, read_valid, s};
use common::{data, scratch};
use mtcut::geom::Aabb;
use mtcut::mt::Mt;

#[test]
fn a_box_and_a_sphere_give_valid_sub_models_inside_them() {
    let dir = scratch("cli_roi");
    let model = dir.join("liver.mt");
    ok(&["build", s(&data("liver.node")), "-o", s(&model)]);
    let mt = Mt::load(&model).expect("model");
    let b = Aabb::from_points(mt.positions());
    let e = b.max - b.min;
    let (lo, hi) = (b.min + e * 0.3, b.min + e * 0.7);
    let arg = format!(
        "{:?},{:?},{:?},{:?},{:?},{:?}",
        lo.x, lo.y, lo.z, hi.x, hi.y, hi.z
    );
    let sub = dir.join("sub.mt");
    let j = json(&["roi", s(&model), "--box", &arg, "-o", s(&sub), "--json"]);
    has_keys(
        &j,
        &[
            "planes",
            "planes_cut",
            "components_kept",
            "components_dropped",
            "tets_after",
            "valid",
        ],
    );
    assert!((1..=6).contains(&j["planes_cut"].as_u64().unwrap()), "{j}");
    assert_eq!(j["components"], 1, "{j}");
    let back = Mt::load(&sub).expect("sub-model");
    assert!(back.validate().is_valid());
    let slack = 1e-6 * b.diagonal();
    for level in ["finest", "coarsest"] {
        let out = dir.join(format!("sub-{level}.vtu"));
        ok(&["extract", s(&sub), "--level", level, "-o", s(&out)]);
        let m = read_valid(&out);
        for p in m.positions() {
            assert!(
                p.cmpge(lo - slack).all() && p.cmple(hi + slack).all(),
                "{level}: {p}"
            );
        }
    }
    // The finest level holds what the box holds of the input's finest mesh: that mesh
    // cut through along the six planes, the tets inside summed.
    let mut finest = mt.extract(&mtcut::mt::ExtractOptions::FINEST).unwrap().mesh;
    for axis in 0..3 {
        for x in [lo[axis], hi[axis]] {
            cut_through(&mut finest, mtcut::geom::DVec3::AXES[axis], x);
        }
    }
    let inside: f64 = finest
        .tets()
        .iter()
        .map(|t| t.map(|v| finest.position(v)))
        .filter(|p| {
            let c = (p[0] + p[1] + p[2] + p[3]) * 0.25;
            c.cmpge(lo).all() && c.cmple(hi).all()
        })
        .map(|p| mtcut::geom::signed_volume(p[0], p[1], p[2], p[3]))
        .sum();
    let ours = read_valid(&dir.join("sub-finest.vtu")).volume();
    assert!(close(ours, inside, 1e-9), "{ours} vs {inside}");

    let c = b.center();
    let sphere = format!("{:?},{:?},{:?},{:?}", c.x, c.y, c.z, 0.2 * b.diagonal());
    let sub2 = dir.join("sphere.mt");
    let text = ok(&["roi", s(&model), "--sphere", &sphere, "-o", s(&sub2)]);
    assert!(
        text.contains("14 planes") && text.contains("valid"),
        "{text}"
    );
    assert!(
        Mt::load(&sub2)
            .expect("sphere sub-model")
            .validate()
            .is_valid()
    );
}

/// Cuts `mesh` straight through along the plane `n · x = o`, snapping as the MT cut does
/// (the plain engine's default snapping bends the cut surface by up to 0.2 of an edge).
fn cut_through(mesh: &mut mtcut::mesh::TetMesh, n: mtcut::geom::DVec3, o: f64) {
    let b = mesh.bbox();
    let r = 2.0 * b.diagonal() + 1.0;
    let origin = b.center() - n * (n.dot(b.center()) - o);
    let u = n.any_orthonormal_vector() * r;
    let w = n.cross(u);
    let poly = mtcut::geom::CutPolygon::new(&[
        origin - u - w,
        origin + u - w,
        origin + u + w,
        origin - u + w,
    ])
    .expect("square");
    mtcut::cut::cut_mesh(mesh, &poly, &mtcut::cut::MtCutter::DEFAULT_OPTIONS).expect("cut");
}

#[test]
fn bad_regions_write_nothing() {
    let dir = scratch("cli_roi bad");
    let model = dir.join("liver.mt");
    ok(&["build", s(&data("liver.node")), "-o", s(&model)]);
    let out = dir.join("x.mt");
    fails(
        &["roi", s(&model), "--box", "1,2,3", "-o", s(&out)],
        &["expected 6"],
    );
    fails(
        &["roi", s(&model), "--box", "1,1,1,0,0,0", "-o", s(&out)],
        &["empty or flat"],
    );
    fails(
        &[
            "roi",
            s(&model),
            "--box",
            "1e6,1e6,1e6,2e6,2e6,2e6",
            "-o",
            s(&out),
        ],
        &["does not meet the body"],
    );
    fails(
        &["roi", s(&model), "--box", "nan,0,0,1,1,1", "-o", s(&out)],
        &["not finite"],
    );
    fails(&["roi", s(&model), "-o", s(&out)], &["--box"]);
    // A sphere of radius 0 is bad usage, as a negative one (exit 2 from the parser).
    let o = common::mtcut(&["roi", s(&model), "--sphere", "0,0,0,0", "-o", s(&out)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(cli_support::stderr(&o).contains("radius > 0"));
    fails(
        &[
            "roi",
            s(&model),
            "--box",
            "0,0,0,1,1,1",
            "--sphere",
            "0,0,0,1",
            "-o",
            s(&out),
        ],
        &["cannot be used with"],
    );
    fails(
        &[
            "roi",
            s(&model),
            "--box",
            "0,0,0,1,1,1",
            "-o",
            s(&dir.join("x.vtu")),
        ],
        &["name it .mt"],
    );
    fails(
        &[
            "roi",
            s(&dir.join("missing.mt")),
            "--box",
            "0,0,0,1,1,1",
            "-o",
            s(&out),
        ],
        &["missing.mt"],
    );
    assert!(!out.exists());
}
