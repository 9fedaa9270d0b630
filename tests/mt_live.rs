//! Time-critical cutting of a deformable body (issue 7, items 1–3): the frontier-first cut
//! of the current mesh, the queue of MT work, equivalence with the direct MT cut for an
//! undeformed body, and for a deformed body a valid rest-space MT onto which the current
//! mesh maps back exactly. The MT and the current mesh are validated after every step.

mod blades;
mod cut_common;
mod mt_common;
mod mtcut_common;

use cut_common::{Kind, Rng, random_polygon};
use mtcut::cut::{CutError, Incision, LiveError, LiveMt, MtCutter, PendingBudget, Scalpel};
use mtcut::geom::{CutPolygon, DVec3, SWEEP_PLANARITY, scalpel_sweep};
use mtcut::mesh::TetMesh;
use mtcut::mt::{ExtractOptions, Mt};

/// A resolution between the finest and the coarsest mesh: the median fragment error.
fn middle(mt: &Mt) -> ExtractOptions {
    let mut e: Vec<f64> = (0..mt.nb_fragments())
        .map(|f| mt.fragment_error(mtcut::mesh::FragmentId::from_usize(f)))
        .filter(|e| e.is_finite() && *e > 0.0)
        .collect();
    e.sort_by(f64::total_cmp);
    ExtractOptions::threshold(e[e.len() / 2])
}

fn live(name: &str) -> LiveMt {
    let mt = mt_common::built(name).1.clone();
    let r = middle(&mt);
    LiveMt::new(mt, &r, MtCutter::DEFAULT_OPTIONS).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A live model of shared mesh `name` at the middle resolution, cut with a scalpel's
/// options.
fn scalpel_live(name: &str) -> LiveMt {
    let mt = mt_common::built(name).1.clone();
    let r = middle(&mt);
    LiveMt::new(mt, &r, mtcut::cut::Scalpel::OPTIONS).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The tets of `mesh` as sorted rest positions (bit patterns): numbering-free.
fn tet_keys(mesh: &TetMesh, rest: &[DVec3]) -> Vec<[[u64; 3]; 4]> {
    let mut keys: Vec<[[u64; 3]; 4]> = mesh
        .tets()
        .iter()
        .map(|t| {
            let mut k = t.map(|v| rest[v.idx()].to_array().map(f64::to_bits));
            k.sort_unstable();
            k
        })
        .collect();
    keys.sort_unstable();
    keys
}

/// The current mesh is valid, the MT too, and (nothing pending) the current mesh at rest is
/// exactly the MT's extraction at the live resolution, each current vertex named by the MT
/// vertex at its rest position.
fn check(l: &LiveMt, case: &str) {
    let v = l.mesh().validate();
    assert!(v.is_valid(), "{case}: current mesh: {v}");
    let r = l.mt().validate();
    assert!(r.is_valid(), "{case}: MT: {r}");
    if l.pending_cuts() > 0 {
        return;
    }
    let e = l.mt().extract(l.resolution()).expect("extract");
    assert_eq!(
        tet_keys(l.mesh(), l.rest_positions()),
        tet_keys(&e.mesh, e.mesh.positions()),
        "{case}: the current mesh at rest is not the MT's extraction"
    );
    for (i, v) in l.mt_vertex_ids().iter().enumerate() {
        assert!(v.is_valid(), "{case}: current vertex {i} has no MT vertex");
        assert_eq!(
            l.mt().position(*v),
            l.rest_positions()[i],
            "{case}: vertex {i}"
        );
    }
}

/// A smooth bend of the body (no tet inverted): x moves with sin(y), z with cos(x).
fn bend(rest: &[DVec3], amount: f64, diag: f64) -> Vec<DVec3> {
    let k = std::f64::consts::TAU / diag;
    rest.iter()
        .map(|p| {
            p + DVec3::new(
                amount * diag * (k * p.y).sin(),
                0.0,
                amount * diag * (k * p.x).cos(),
            )
        })
        .collect()
}

fn diag(mesh: &TetMesh) -> f64 {
    let b = mesh.bbox();
    (b.max - b.min).length()
}

fn cuts(name: &str, seed: u64, n: usize) -> Vec<CutPolygon> {
    let mesh = cut_common::mesh(name);
    let mut rng = Rng(seed);
    (0..n)
        .map(|i| {
            let kind = [Kind::Through, Kind::Partial, Kind::Tiny][i % 3];
            random_polygon(mesh, kind, &mut rng)
        })
        .collect()
}

#[test]
fn undeformed_time_critical_cuts_give_the_direct_cuts_mt() {
    for name in mt_common::MESHES {
        let polygons = cuts(name, 7, 4);
        let mut l = live(name);
        let mut direct = MtCutter::new(mt_common::built(name).1.clone(), MtCutter::DEFAULT_OPTIONS)
            .expect("cutter");
        for (i, p) in polygons.iter().enumerate() {
            let case = format!("{name} cut {i}");
            let c = l.cut(p).unwrap_or_else(|e| panic!("{case}: {e}"));
            assert_eq!(c.pending, 1, "{case}");
            check(&l, &format!("{case}, frontier first"));
            let r = l
                .process_pending(PendingBudget::All)
                .unwrap_or_else(|e| panic!("{case}: {e}"));
            assert_eq!((r.cuts.len(), r.cuts_left), (1, 0), "{case}");
            assert!(
                !r.remeshed,
                "{case}: the current mesh did not map back onto the MT"
            );
            direct.cut(p).expect("direct cut");
            assert!(
                l.mt().canonical_form() == direct.mt().canonical_form(),
                "{case}: the MT differs from the direct cut's"
            );
            check(&l, &case);
        }
    }
}

#[test]
fn queued_cuts_are_processed_within_their_budget_and_block_resolution_changes() {
    let name = "fandisk";
    let mut l = live(name);
    let polygons = cuts(name, 11, 3);
    for p in &polygons {
        l.cut(p).expect("cut");
        check(&l, "queued");
    }
    assert_eq!(l.pending_cuts(), 3);
    let before = l.mesh().clone();
    match l.set_resolution(&ExtractOptions::COARSEST) {
        Err(LiveError::Pending { cuts: 3 }) => {}
        other => panic!("resolution change while pending: {other:?}"),
    }
    assert!(
        *l.mesh() == before,
        "a refused resolution change changed the mesh"
    );
    // One fragment of budget: exactly one cut per call (each involves fragments).
    for left in (0..3).rev() {
        let r = l
            .process_pending(PendingBudget::Fragments(1))
            .expect("process");
        assert_eq!((r.cuts.len(), r.cuts_left, r.remeshed), (1, left, false));
        assert!(r.fragments > 0);
        check(&l, &format!("{left} left"));
    }
    let r = l
        .process_pending(PendingBudget::Time(std::time::Duration::ZERO))
        .expect("no-op");
    assert!(r.cuts.is_empty() && !r.remeshed);
    let mut direct =
        MtCutter::new(mt_common::built(name).1.clone(), MtCutter::DEFAULT_OPTIONS).expect("cutter");
    for p in &polygons {
        direct.cut(p).expect("direct");
    }
    assert!(l.mt().canonical_form() == direct.mt().canonical_form());
    // Nothing pending: the resolution changes, ids name the MT's vertices.
    l.set_resolution(&ExtractOptions::COARSEST)
        .expect("coarsest");
    check(&l, "coarsest");
}

#[test]
fn a_deformed_body_is_cut_where_it_lies_and_maps_back_exactly() {
    for name in mt_common::MESHES {
        let mut l = live(name);
        let d = diag(l.mesh());
        let rest = l.rest_positions().to_vec();
        l.set_positions(&bend(&rest, 0.005, d)).expect("bend");
        let b = l.mesh().bbox();
        let c = (b.min + b.max) * 0.5;
        // Through the bent body's middle, then a partial cut across it.
        let through = cut_common::square(c, DVec3::new(0.3, 1.0, 0.2).normalize(), d);
        let partial = cut_common::square(c, DVec3::new(1.0, 0.1, -0.3).normalize(), 0.15 * d);
        for (i, p) in [through, partial].iter().enumerate() {
            let case = format!("{name} deformed cut {i}");
            let stats = l.cut(p).unwrap_or_else(|e| panic!("{case}: {e}")).stats;
            assert!(stats.tets_cut > 0, "{case}: nothing cut");
            check(&l, &format!("{case}, frontier first"));
            // The body moves on before the MT catches up: the cut stays where it was made.
            let now = l.mesh().positions().to_vec();
            let moved: Vec<DVec3> = now.iter().map(|p| *p + DVec3::splat(0.01 * d)).collect();
            l.set_positions(&moved).expect("move");
            let r = l
                .process_pending(PendingBudget::All)
                .unwrap_or_else(|e| panic!("{case}: {e}"));
            assert!(
                !r.remeshed,
                "{case}: the current mesh did not map back onto the MT"
            );
            check(&l, &case);
            // The current mesh kept the host's positions.
            assert!(
                l.mesh().positions()[..now.len()] == moved[..],
                "{case}: positions lost"
            );
        }
        // The through cut separated the body on every level.
        assert!(
            l.mt().nb_components() >= 2,
            "{name}: {} components",
            l.mt().nb_components()
        );
    }
}

#[test]
fn bad_positions_are_refused_and_change_nothing() {
    let mut l = live("pinion");
    let rest = l.rest_positions().to_vec();
    let n = rest.len();
    let before = l.mesh().clone();
    let err = |r: Result<(), LiveError>| match r {
        Err(LiveError::Cut(e)) => e,
        other => panic!("expected a refusal, got {other:?}"),
    };
    assert_eq!(
        err(l.set_positions(&rest[..n - 1])),
        CutError::PositionCount {
            count: n - 1,
            expected: n
        }
    );
    let mut nan = rest.clone();
    nan[5].y = f64::NAN;
    assert_eq!(
        err(l.set_positions(&nan)),
        CutError::NonFinitePosition { vertex: 5 }
    );
    // Swapping two vertices of a tet inverts it.
    let t = l.mesh().tets()[0];
    let mut inverted = rest.clone();
    inverted.swap(t[0].idx(), t[1].idx());
    assert!(matches!(
        err(l.set_positions(&inverted)),
        CutError::InvertedTet { .. }
    ));
    assert!(*l.mesh() == before, "a refused update changed the mesh");
}

#[test]
fn degenerate_cuts_keep_the_mt_equal_to_the_direct_cut_and_the_mesh_its_extraction() {
    // Through vertices, along edges and faces: the frontier's cut may decide otherwise
    // than the MT's at vertices on the plane; then the current mesh is replaced by the
    // MT's extraction (reported), and stays exactly that extraction.
    let mut remeshed = 0;
    for name in mt_common::MESHES {
        let mesh = cut_common::mesh(name);
        let mut rng = Rng(23);
        let mut l = live(name);
        let mut direct = MtCutter::new(mt_common::built(name).1.clone(), MtCutter::DEFAULT_OPTIONS)
            .expect("cutter");
        for (i, kind) in [Kind::Vertices, Kind::AlongEdge, Kind::AlongFace]
            .into_iter()
            .enumerate()
        {
            let p = random_polygon(mesh, kind, &mut rng);
            let case = format!("{name} {kind:?} {i}");
            l.cut(&p).unwrap_or_else(|e| panic!("{case}: {e}"));
            check(&l, &format!("{case}, frontier first"));
            let r = l
                .process_pending(PendingBudget::All)
                .unwrap_or_else(|e| panic!("{case}: {e}"));
            remeshed += usize::from(r.remeshed);
            direct.cut(&p).expect("direct");
            assert!(
                l.mt().canonical_form() == direct.mt().canonical_form(),
                "{case}: MT differs"
            );
            check(&l, &case);
        }
    }
    eprintln!("degenerate cuts remeshed: {remeshed} of 9");
}

/// The blade of tests/mtcut_cut.rs's sweep across the MT (a plane of no special direction:
/// the MT cut's known failures are elsewhere, tests/mt_scalpel.rs), crossing `mt` in
/// `steps` planar sweeps.
fn sweep(mt: &Mt, steps: usize) -> Vec<CutPolygon> {
    let b = mtcut::geom::Aabb::from_points(mt.positions());
    let (c, d) = (b.center(), b.max - b.min);
    let blade = |k: usize| {
        let x = b.min.x - 0.05 * d.x + 1.1 * d.x * k as f64 / steps as f64;
        [
            DVec3::new(x, c.y + 0.013 * d.y, b.min.z - 0.1 * d.z),
            DVec3::new(x, c.y - 0.011 * d.y, b.max.z + 0.1 * d.z),
        ]
    };
    (0..steps)
        .map(|k| {
            let s = mtcut::geom::scalpel_sweep(
                blade(k),
                blade(k + 1),
                mtcut::geom::Tolerance { relative: 1e-9 },
            )
            .expect("sweep");
            assert_eq!(s.len(), 1, "a planar sweep");
            s[0].clone()
        })
        .collect()
}

#[test]
fn a_blade_swept_through_the_live_model_cuts_frontier_first_at_every_step() {
    // The scalpel of issue 7 item 4 on the live model: the blade crosses the body in the
    // plane z = middle in 8 steps; each step cuts the current mesh at once and the MT
    // after; the body separates at the end.
    for name in mt_common::MESHES {
        let mut l = scalpel_live(name);
        let mut remeshed = 0;
        for (k, p) in sweep(l.mt(), 8).iter().enumerate() {
            let case = format!("{name} step {k}");
            l.cut(p).unwrap_or_else(|e| panic!("{case}: {e}"));
            check(&l, &format!("{case}, frontier first"));
            let r = l
                .process_pending(PendingBudget::All)
                .unwrap_or_else(|e| panic!("{case}: {e}"));
            remeshed += usize::from(r.remeshed);
            check(&l, &case);
        }
        assert_eq!(
            mtcut::cut::Components::of(l.mesh()).count,
            2,
            "{name}: the blade crossed the body"
        );
        eprintln!("{name}: steps remeshed {remeshed} of 8");
    }
}

/// The blade of [`sweep`] crossing `name` in 8 steps, the body bent by `amount(step)` of its
/// diagonal before each step (`None`: left as it is); every step maps back exactly and
/// leaves the MT and the current mesh valid. Returns the live model.
fn bent_sweep(name: &str, steps: usize, amount: impl Fn(usize) -> Option<f64>) -> LiveMt {
    let mut l = scalpel_live(name);
    let d = diag(l.mesh());
    for (k, p) in sweep(l.mt(), steps).iter().enumerate() {
        let case = format!("{name} step {k}");
        if let Some(a) = amount(k) {
            let rest = l.rest_positions().to_vec();
            l.set_positions(&bend(&rest, a, d))
                .unwrap_or_else(|e| panic!("{case}: {e}"));
        }
        l.cut(p).unwrap_or_else(|e| panic!("{case}: {e}"));
        check(&l, &format!("{case}, frontier first"));
        let r = l
            .process_pending(PendingBudget::All)
            .unwrap_or_else(|e| panic!("{case}: {e}"));
        assert!(
            !r.remeshed && r.folded == 0,
            "{case}: remeshed {} folded {}",
            r.remeshed,
            r.folded
        );
        check(&l, &case);
    }
    l
}

#[test]
fn a_blade_swept_through_a_bent_body_keeps_the_mt_valid_and_maps_back() {
    // The body bent by 0.5% of its diagonal while the blade crosses it: each step is cut
    // where the body lies, the MT at rest, and the current mesh maps back exactly every
    // time; the body separates.
    for name in mt_common::MESHES {
        let l = bent_sweep(name, 8, |k| (k == 0).then_some(0.005));
        assert_eq!(
            mtcut::cut::Components::of(l.mesh()).count,
            2,
            "{name}: not separated"
        );
        assert!(l.mt().nb_components() >= 2, "{name}: MT not separated");
    }
}

#[test]
fn a_blade_swept_through_a_moving_deformed_body_keeps_the_mt_valid_and_maps_back() {
    // The body bends more at every step (0.5% of its diagonal, then 2% more per step: thin
    // children of the cuts must not invert), so the crack the last steps left has moved
    // off the blade's plane when the next step continues it; the vertices those steps made
    // in that plane count as lying in it (`StateClassifier::with_glued`), on every level
    // and in the current mesh alike: no step is refused or remeshed. (The blade's sweeps
    // are given in world space: each starts where the blade was, not where the crack moved
    // to, so bridges may stay; separation is not expected.)
    for name in mt_common::MESHES {
        bent_sweep(name, 8, |k| Some(0.005 * (1.0 + 0.02 * k as f64)));
    }
}

#[test]
fn a_blade_swept_through_a_body_swinging_between_steps_keeps_the_mt_valid_and_maps_back() {
    // The bend swings by up to 30 % of its amount from step to step (back and forth: the
    // crack of the last steps lies on either side of the blade's plane), the blade crossing
    // in 12 steps. (Not the liver: this bend inverts thin children of its cuts, which the
    // live model refuses as positions.)
    for name in ["fandisk", "pinion"] {
        bent_sweep(name, 12, |k| Some(0.005 * (1.0 + 0.3 * (k as f64).sin())));
    }
}

#[test]
fn a_cut_the_mt_refuses_is_dropped_and_the_current_mesh_extracted_again() {
    // A blade tilting across the live fandisk in 20 steps, at rest (the MT cut's steep-tilt
    // limit, tests/mt_scalpel.rs: the MT refuses some steps' cuts). A refused cut is
    // dropped from the queue and reported, the MT is byte for byte as before it, and the
    // current mesh, which had it, is replaced by the MT's extraction: both valid, the
    // current mesh mapped back; the next steps go on.
    let mut l = scalpel_live("fandisk");
    let b = mtcut::geom::Aabb::from_points(l.mt().positions());
    let path: Vec<_> = (0..=20).map(|k| blades::tilting_in(&b, k, 20)).collect();
    // Each polygon of a sweep queued and processed alone, so that a refused one is the
    // whole of its queue; on until two more polygons after the first refused one.
    let polygons = path
        .windows(2)
        .flat_map(|w| scalpel_sweep(w[0], w[1], SWEEP_PLANARITY).expect("sweep"));
    let (mut refused, mut after) = (0, 0);
    for (k, p) in polygons.enumerate() {
        let case = format!("fandisk polygon {k}");
        l.cut(&p).unwrap_or_else(|e| panic!("{case}: {e}"));
        let before = l.mt().to_bytes();
        let r = l
            .process_pending(PendingBudget::All)
            .unwrap_or_else(|e| panic!("{case}: {e}"));
        if !r.refused.is_empty() {
            refused += 1;
            assert!(
                matches!(r.refused[..], [CutError::MtInconsistent { .. }]),
                "{case}: {:?}",
                r.refused
            );
            assert!(r.remeshed && r.cuts.is_empty(), "{case}: {r:?}");
            assert!(
                l.mt().to_bytes() == before,
                "{case}: a refused cut changed the MT"
            );
        } else if refused > 0 {
            after += 1;
        }
        check(&l, &case);
        if after == 2 {
            break;
        }
    }
    // When MT cuts take steeper tilts, this test needs another refused cut.
    assert!(refused > 0, "no cut refused");
    assert_eq!(after, 2, "no cut after the refused one");
}

/// The same tilting blade, each sweep given whole (`LiveMt::cut_sweep`, every split of it):
/// where the MT refuses the first split (the 11th step's second triangle), it takes another
/// as `Scalpel::step` does, the current mesh cut with the first replaced by the MT's
/// extraction. No step is dropped, the MT is after every step what the direct scalpel
/// makes of the same path (canonically), and both meshes are valid, the current one mapped
/// back.
#[test]
fn a_sweep_the_mt_refuses_is_taken_as_another_split() {
    let mut l = scalpel_live("fandisk");
    let b = mtcut::geom::Aabb::from_points(l.mt().positions());
    let path: Vec<_> = (0..=20).map(|k| blades::tilting_in(&b, k, 20)).collect();
    let mut direct = Scalpel::new(mt_common::built("fandisk").1.clone(), path[0]).unwrap();
    let mut incision = Incision::new(path[0], 0.0).expect("incision");
    // No split, or an empty first one, cuts nothing.
    let some = scalpel_sweep(path[0], path[1], SWEEP_PLANARITY).expect("sweep");
    assert!(l.cut_sweep(&[]).expect("no split").is_empty());
    assert!(l.cut_sweep(&[vec![], some]).expect("empty").is_empty());
    assert_eq!(l.pending_cuts(), 0);
    let mut other = Vec::new();
    for (k, &to) in path.iter().enumerate().skip(1) {
        let case = format!("fandisk step {k}");
        let mut polygons = 0;
        incision
            .step_sweep(to, |splits| {
                polygons = l.cut_sweep(&splits)?.len();
                Ok::<_, LiveError>(())
            })
            .unwrap_or_else(|e| panic!("{case}: {e}"));
        assert_eq!(l.pending_cuts(), polygons, "{case}");
        let r = l
            .process_pending(PendingBudget::All)
            .unwrap_or_else(|e| panic!("{case}: {e}"));
        assert!(r.refused.is_empty(), "{case}: {:?}", r.refused);
        let step = direct
            .step(to)
            .unwrap_or_else(|e| panic!("{case}: direct: {e}"));
        assert_eq!(r.other_splits, usize::from(step.split > 0), "{case}");
        if r.other_splits > 0 {
            assert!(r.remeshed, "{case}: {r:?}");
            other.push(k);
        }
        assert!(
            l.mt().canonical_form() == direct.mt().canonical_form(),
            "{case}: the MT differs from the direct scalpel's"
        );
        check(&l, &case);
    }
    assert!(other.contains(&11), "steps cut as another split: {other:?}");
}

#[test]
fn fold_fallbacks_of_a_growing_bend_keep_every_mesh_valid() {
    // The liver bent more by 5 % of the bend at every step of a blade crossing it in 16:
    // two steps fold tets of other levels and fall back to a cut at rest, each followed by
    // a check of the finest, the coarsest and the live resolution's meshes (a fallback
    // leaving one invalid is given back and refused). The second fallback's polygon lies
    // close to the first's plane without lying in it: it pinched the live resolution's
    // mesh and was refused until polygons that close are cut in the earlier plane
    // (`mtcut::geom::PLANE_SNAP`); now both are kept. The MT and the current mesh stay
    // valid at every step, the current mesh mapped back.
    let mut l = scalpel_live("liver");
    let d = diag(l.mesh());
    let mut folded = 0;
    for (k, p) in sweep(l.mt(), 16).iter().enumerate().take(10) {
        let case = format!("liver step {k}");
        let rest = l.rest_positions().to_vec();
        l.set_positions(&bend(&rest, 0.005 * (1.0 + 0.05 * k as f64), d))
            .unwrap_or_else(|e| panic!("{case}: {e}"));
        l.cut(p).unwrap_or_else(|e| panic!("{case}: {e}"));
        let r = l
            .process_pending(PendingBudget::All)
            .unwrap_or_else(|e| panic!("{case}: {e}"));
        if r.folded > 0 {
            folded += 1;
            assert!(r.refused.is_empty() && r.remeshed, "{case}: {r:?}");
        }
        check(&l, &case);
    }
    assert_eq!(folded, 2, "not two fold fallbacks");
}

#[test]
fn a_deformation_folding_tets_of_other_levels_falls_back_to_a_rest_cut() {
    // A 1% bend of the liver folds MT tets the blade's first sweep meets (measured: two);
    // that cut is made at rest with the polygon mapped by the best-fitting affine map, and
    // the current mesh is replaced by the MT's extraction. Everything stays valid.
    let mut l = scalpel_live("liver");
    let d = diag(l.mesh());
    let rest = l.rest_positions().to_vec();
    l.set_positions(&bend(&rest, 0.01, d)).expect("bend");
    let p = &sweep(l.mt(), 8)[0];
    l.cut(p).expect("cut");
    check(&l, "frontier first");
    let r = l.process_pending(PendingBudget::All).expect("pending");
    assert_eq!((r.folded, r.remeshed), (1, true));
    check(&l, "after the fallback");
}

/// A cut overlapping an earlier partial one nearly in its plane (offset by 1e-9 of the
/// model's size and tilted by 1e-6: a blade re-entering the incision) is made in that
/// plane on the current mesh and on the MT alike, at rest and in a bent body: nothing
/// refused, the current mesh mapped back.
#[test]
fn a_cut_close_to_an_earlier_cuts_plane_is_made_in_it_here_and_on_the_mt() {
    for name in mt_common::MESHES {
        for bent in [false, true] {
            let case = format!("{name}, bent {bent}");
            let mut l = live(name);
            let d = diag(l.mesh());
            if bent {
                let rest = l.rest_positions().to_vec();
                l.set_positions(&bend(&rest, 0.005, d)).expect("bend");
            }
            let c = l.mesh().bbox().center();
            let [first, second] = mtcut_common::nearly_coplanar_bands(c, d, 1e-9, 1e-6);
            let first = l.cut(&first).expect("first cut");
            assert!(!first.moved_to_plane && first.stats.tets_cut > 0, "{case}");
            let r = l
                .process_pending(PendingBudget::All)
                .expect("first pending");
            assert!(r.refused.is_empty() && !r.remeshed, "{case}: first: {r:?}");
            check(&l, &format!("{case}, first"));
            let second = l.cut(&second).expect("second cut");
            assert!(second.moved_to_plane && second.stats.tets_cut > 0, "{case}");
            let r = l
                .process_pending(PendingBudget::All)
                .expect("second pending");
            assert!(r.refused.is_empty() && !r.remeshed, "{case}: second: {r:?}");
            check(&l, &format!("{case}, second"));
        }
    }
}

/// The same when the first cut was made on the MT before the live model (a model saved
/// and loaded, say): the live model takes the planes of the MT's earlier cracks from its
/// cut record, so the second cut is moved onto the first's plane on the current mesh as on
/// the MT, and the current mesh maps back. Before, only the MT cut moved it, and the
/// current mesh was replaced by the MT's extraction when the queue drained (`remeshed`:
/// a new numbering for the host), on every shared mesh.
#[test]
fn a_live_model_takes_the_planes_of_the_mts_earlier_cracks() {
    for name in mt_common::MESHES {
        let mt = mt_common::built(name).1.clone();
        let b = mtcut::geom::Aabb::from_points(mt.positions());
        let [first, second] =
            mtcut_common::nearly_coplanar_bands(b.center(), b.diagonal(), 1e-7, 0.0);
        let mut c = MtCutter::new(mt, MtCutter::DEFAULT_OPTIONS).expect("cutter");
        c.cut(&first).expect("first cut");
        let mt = Mt::from_bytes(&c.into_mt().to_bytes()).expect("saved and loaded");
        let resolution = middle(&mt);
        let mut l = LiveMt::new(mt, &resolution, MtCutter::DEFAULT_OPTIONS).expect("live");
        let cut = l.cut(&second).expect("second cut");
        assert!(cut.moved_to_plane && cut.stats.tets_cut > 0, "{name}");
        let r = l.process_pending(PendingBudget::All).expect("pending");
        assert!(r.refused.is_empty() && !r.remeshed, "{name}: {r:?}");
        assert!(r.cuts.iter().all(|s| !s.moved_to_plane), "{name}: {r:?}");
        check(&l, name);
    }
}

/// A blade turning by 8° per step across fandisk (a vertical blade on an arc, 15 steps)
/// under a body bent by 0.5 % of its diagonal before the sweep: each step continues the
/// last at an angle in the same deformed frame (the MT's cut record keeps a deformed
/// body's cuts with the frame they were made in), so no step is refused, every step maps
/// back, and the corner comes off; the model, saved and loaded, keeps that record. Before,
/// steps 3, 5 and 7 were refused and the body stayed whole.
#[test]
fn a_blade_turning_across_a_bent_body_takes_every_step() {
    let mut l = scalpel_live("fandisk");
    let b = mtcut::geom::Aabb::from_points(l.mt().positions());
    let d = diag(l.mesh());
    let rest = l.rest_positions().to_vec();
    l.set_positions(&bend(&rest, 0.005, d)).expect("bend");
    let path = blades::turning_by_8(&b, 15);
    for (k, w) in path.windows(2).enumerate() {
        for p in scalpel_sweep(w[0], w[1], SWEEP_PLANARITY).expect("sweep") {
            let case = format!("step {k}");
            l.cut(&p).unwrap_or_else(|e| panic!("{case}: {e}"));
            let r = l
                .process_pending(PendingBudget::All)
                .unwrap_or_else(|e| panic!("{case}: {e}"));
            assert!(r.refused.is_empty() && !r.remeshed, "{case}: {r:?}");
            check(&l, &case);
        }
    }
    assert_eq!(l.mt().nb_components(), 2);
    let mt = l.into_mt().expect("into_mt");
    let back = Mt::from_bytes(&mt.to_bytes()).expect("saved and loaded");
    assert!(back == mt, "the loaded model differs");
}

/// The blade of `a_blade_turning_across_a_bent_body_takes_every_step` under a host that
/// sets the positions before every step, as a simulation does: the same bend every time,
/// or one growing by 2 % per step. The host's positions of the vertices the last cut made
/// replace those the cut interpolated, and the pool is placed through them, so the MT sees
/// another frame at every step and does not continue the last cut at an angle.
/// Measured: the same bend, 3, 4 and 4 steps refused on fandisk, pinion and liver (the
/// steps' cracks meet without the turning tips' decisions: faces doubled in a fragment's
/// floor or ceiling); a growing bend, none refused on fandisk and liver, one on pinion,
/// and every body stays in one piece (the cracks do not meet). Mapping the last cut's
/// polygon into the new frame by an affine fit (and the step's start with it) made the MT
/// continue it across frames, and refused 3, 4 and 3 steps of the growing bend.
#[test]
#[ignore = "KNOWN FAILURE (issue 7 open): a turning blade in a body whose positions are \
            set between the steps is refused at some steps or leaves the body whole"]
fn a_blade_turning_across_a_body_moved_between_steps_separates_it() {
    for name in mt_common::MESHES {
        for growth in [0.0, 0.02] {
            let case = format!("{name}, bend growing by {growth} per step");
            let mut l = scalpel_live(name);
            let b = mtcut::geom::Aabb::from_points(l.mt().positions());
            let d = diag(l.mesh());
            let path = blades::turning_by_8(&b, 15);
            for (k, w) in path.windows(2).enumerate() {
                let rest = l.rest_positions().to_vec();
                // Refused when it would invert a sliver the cuts made (pinion's growing
                // bend from step 9): the body stays where it was, as a host's would.
                match l.set_positions(&bend(&rest, 0.005 * (1.0 + growth * k as f64), d)) {
                    Ok(()) | Err(LiveError::Cut(CutError::InvertedTet { .. })) => {}
                    Err(e) => panic!("{case}, step {k}: {e}"),
                }
                for p in scalpel_sweep(w[0], w[1], SWEEP_PLANARITY).expect("sweep") {
                    l.cut(&p)
                        .unwrap_or_else(|e| panic!("{case}, step {k}: {e}"));
                    let r = l
                        .process_pending(PendingBudget::All)
                        .unwrap_or_else(|e| panic!("{case}, step {k}: {e}"));
                    assert!(r.refused.is_empty(), "{case}, step {k}: {:?}", r.refused);
                    check(&l, &format!("{case}, step {k}"));
                }
            }
            assert_eq!(l.mt().nb_components(), 2, "{case}: not separated");
        }
    }
}
