//! Seeded random cuts of the shared meshes: 1,000 per mesh, each from a clone of the input
//! (long run: `cargo test --release --test cut_random -- --ignored`, 10,000 per mesh).
//!
//! After every cut: the mesh is valid (conforming, positively oriented, manifold boundary,
//! no hanging vertex), its volume is unchanged (1e-12 relative), no edge crosses C strictly
//! inside C (exact predicates; only an edge with an end within snapping distance of the
//! plane may), and a cut straight through leaves parts that share no vertex. The same cut is
//! made with the 1:17 scheme to compare cell counts. The quality of the created tets and
//! the cell ratio are printed (`--nocapture`) and held to their targets (the long run only
//! prints them).

mod cut_common;

use cut_common::*;
use mtcut::cut::{CutOptions, Cutter, Scheme};
use mtcut::geom::CutPolygon;
use mtcut::mesh::TetMesh;

#[derive(Default)]
struct Tally {
    cuts: usize,
    lut: usize,
    bielser: usize,
    min_dihedral: f64,
    min_volume_ratio: f64,
}

fn fails(mesh: &TetMesh, polygon: &CutPolygon, options: &CutOptions, through: bool) -> bool {
    let (mut cutter, scales) = prepared(mesh, *options);
    match cutter.cut(polygon) {
        Ok(r) => check_cut(mesh, &scales, cutter.mesh(), polygon, &r, options, through).is_err(),
        Err(_) => true,
    }
}

/// `targets`: hold the quality and cell-ratio targets (the long run only reports them: its
/// tail goes below the 1° target, see the report).
fn random_suite(name: &str, first_seed: u64, cuts: u64, targets: bool) {
    let mesh = mesh(name);
    let options = CutOptions::DEFAULT.with_count_components(false);
    let (base, scales) = prepared(mesh, options);
    let base17 =
        Cutter::new(mesh.clone(), options.with_scheme(Scheme::Bielser17)).expect("valid options");
    let mut tally: Vec<(Kind, Tally)> = Kind::ALL
        .iter()
        .map(|&k| {
            (
                k,
                Tally {
                    min_dihedral: f64::INFINITY,
                    min_volume_ratio: f64::INFINITY,
                    ..Tally::default()
                },
            )
        })
        .collect();
    let volume = mesh.volume();
    for seed in first_seed..first_seed + cuts {
        let mut rng = Rng(seed);
        let kind = Kind::draw(&mut rng);
        let polygon = random_polygon(mesh, kind, &mut rng);
        let through = kind == Kind::Through;
        let mut cutter = base.clone();
        let result = cutter.cut(&polygon).expect("cut");
        let checked = match check_cut(
            mesh,
            &scales,
            cutter.mesh(),
            &polygon,
            &result,
            &options,
            through,
        ) {
            Ok(c) => c,
            Err(e) => panic!(
                "{}",
                shrink_and_report(
                    seed,
                    &format!("{name}: {kind:?} cut broke an invariant: {e}"),
                    mesh,
                    &polygon,
                    !through,
                    |m, p| fails(m, p, &options, through),
                )
            ),
        };
        let mut c17 = base17.clone();
        let r17 = c17.cut(&polygon).expect("1:17 cut");
        let v17 = c17.mesh().volume();
        assert!(
            (v17 - volume).abs() <= 1e-12 * volume,
            "seed {seed}: the 1:17 scheme changed the volume to {v17} from {volume}"
        );
        let t = &mut tally.iter_mut().find(|(k, _)| *k == kind).expect("kind").1;
        t.cuts += 1;
        t.lut += result.stats.tets_created;
        t.bielser += r17.stats.tets_created;
        t.min_dihedral = t.min_dihedral.min(checked.min_dihedral);
        t.min_volume_ratio = t.min_volume_ratio.min(checked.min_volume_ratio);
    }
    let (mut lut, mut b17, mut dih, mut vr) = (0, 0, f64::INFINITY, f64::INFINITY);
    for (k, t) in &tally {
        eprintln!(
            "{name} {k:>10?}: {:4} cuts, created {:7} (tables) vs {:7} (1:17), ratio {:.3}; \
             min dihedral {:.2}°, min volume ratio {:.2e}",
            t.cuts,
            t.lut,
            t.bielser,
            t.lut as f64 / t.bielser.max(1) as f64,
            t.min_dihedral,
            t.min_volume_ratio
        );
        lut += t.lut;
        b17 += t.bielser;
        dih = dih.min(t.min_dihedral);
        vr = vr.min(t.min_volume_ratio);
    }
    let through = &tally[0].1;
    let through_ratio = through.lut as f64 / through.bielser.max(1) as f64;
    eprintln!(
        "{name} all: created {lut} (tables) vs {b17} (1:17), ratio {:.3} (through cuts {:.3}); \
         min dihedral {dih:.2}°, min volume ratio {vr:.2e}",
        lut as f64 / b17 as f64,
        through_ratio
    );
    if !targets {
        return;
    }
    assert!(
        dih >= 1.0,
        "{name}: a created tet has a {dih}° dihedral angle"
    );
    assert!(
        vr >= 1e-6,
        "{name}: a created tet has {vr:e} of its parent's volume"
    );
    assert!(
        through_ratio <= 0.27,
        "{name}: tables create {through_ratio} as many tets as 1:17 on through cuts"
    );
}

#[test]
fn random_cuts_fandisk() {
    random_suite("fandisk", 1_000_000, 1000, true);
}

#[test]
fn random_cuts_pinion() {
    random_suite("pinion", 2_000_000, 1000, true);
}

#[test]
fn random_cuts_liver() {
    random_suite("liver", 3_000_000, 1000, true);
}

#[test]
#[ignore = "long: 10,000 cuts per mesh (MTCUT_LONG_MESH=name for one); --release -- --ignored"]
fn random_cuts_long() {
    let only = std::env::var("MTCUT_LONG_MESH").ok();
    for (k, name) in MESHES.iter().enumerate() {
        if only.as_deref().is_none_or(|m| m == *name) {
            random_suite(name, 10_000_000 * (k as u64 + 1), 10_000, false);
        }
    }
}
