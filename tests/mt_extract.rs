//! Extraction (selective refinement over the DAG): focus regions, budgets, and the
//! incremental frontier, which must give exactly what from-scratch extraction gives.

mod mt_common;

use mt_common::{MESHES, Rng, built};
use mtcut::geom::{Aabb, DVec3};
use mtcut::mesh::{FragmentId, TetMesh};
use mtcut::mt::{ExtractError, ExtractOptions, Extraction, Frontier, Mt, Region};

/// Finite positive fragment errors, sorted.
fn errors(mt: &Mt) -> Vec<f64> {
    let mut e: Vec<f64> = (0..mt.nb_fragments())
        .map(|f| mt.fragment_error(FragmentId::from_usize(f)))
        .filter(|e| e.is_finite() && *e > 0.0)
        .collect();
    e.sort_by(f64::total_cmp);
    e
}

/// Mean volume of the tets whose centroid lies inside / outside `region`.
fn mean_volumes(m: &TetMesh, region: &Region) -> (f64, f64, usize, usize) {
    let (mut vi, mut ni, mut vo, mut no) = (0.0, 0, 0.0, 0);
    for t in 0..m.nb_tets() {
        let t = mtcut::mesh::TetId::from_usize(t);
        let p = m.tet_positions(t);
        let c = (p[0] + p[1] + p[2] + p[3]) / 4.0;
        if region.contains(c) {
            vi += m.tet_volume(t);
            ni += 1;
        } else {
            vo += m.tet_volume(t);
            no += 1;
        }
    }
    (vi / ni.max(1) as f64, vo / no.max(1) as f64, ni, no)
}

#[test]
fn focus_is_finer_inside_than_outside() {
    for name in MESHES {
        let (input, mt, _) = built(name);
        let bbox = input.bbox();
        let e = errors(mt);
        let coarse = e[e.len() * 9 / 10];
        let regions = [
            Region::Sphere {
                center: bbox.min + bbox.extent() * DVec3::new(0.3, 0.5, 0.5),
                radius: 0.2 * bbox.diagonal(),
            },
            Region::Box(Aabb {
                min: bbox.min + bbox.extent() * 0.55,
                max: bbox.min + bbox.extent() * 0.95,
            }),
        ];
        for region in regions {
            let options = ExtractOptions::threshold(coarse).with_focus(region, 0.0);
            let x = mt.extract(&options).unwrap();
            let v = x.mesh.validate();
            assert!(v.is_valid(), "{name}: {v}");
            let (inside, outside, ni, no) = mean_volumes(&x.mesh, &region);
            eprintln!(
                "{name} {region:?}: {} tets; mean tet volume inside {inside:.3e} ({ni} tets), \
                 outside {outside:.3e} ({no} tets), ratio {:.1}",
                x.stats.tets,
                outside / inside
            );
            assert!(ni > 0 && no > 0);
            assert!(inside < outside, "{name}: not finer inside the focus");
            // The focus refines: more tets than the same threshold without it.
            let uniform = mt.extract(&ExtractOptions::threshold(coarse)).unwrap();
            assert!(x.stats.tets > uniform.stats.tets);
        }
    }
}

#[test]
fn budgets_are_respected_and_grow_monotonically() {
    for name in MESHES {
        let (input, mt, _) = built(name);
        let coarsest = mt.coarsest_tets();
        let mut previous = 0;
        for k in 1..=8 {
            let budget = coarsest + (input.nb_tets() - coarsest) * k / 8;
            let x = mt
                .extract(&ExtractOptions::DEFAULT.with_budget(Some(budget)))
                .unwrap();
            assert!(x.stats.budget_met);
            assert!(
                x.stats.tets <= budget,
                "{name}: {} > {budget}",
                x.stats.tets
            );
            assert!(x.stats.tets >= previous);
            let v = x.mesh.validate();
            assert!(v.is_valid(), "{name} budget {budget}: {v}");
            previous = x.stats.tets;
        }
        assert_eq!(
            previous,
            input.nb_tets(),
            "{name}: a budget of the input size gives it"
        );
        let tight = mt
            .extract(&ExtractOptions::DEFAULT.with_budget(Some(coarsest / 2)))
            .unwrap();
        assert!(!tight.stats.budget_met);
        assert_eq!(tight.stats.tets, coarsest);
        // A budget caps a threshold extraction and never refines beyond it.
        let e = errors(mt);
        let t = ExtractOptions::threshold(e[e.len() / 2]);
        let plain = mt.extract(&t).unwrap();
        let capped = mt.extract(&t.with_budget(Some(input.nb_tets()))).unwrap();
        assert_eq!(plain.tet_ids, capped.tet_ids);
        // Budgets past i64 (SIZE_MAX from a C host meaning "no limit") are no limit.
        for huge in [1usize << 63, usize::MAX] {
            let x = mt.extract(&t.with_budget(Some(huge))).unwrap();
            assert!(x.stats.budget_met, "{name}: budget {huge}");
            assert_eq!(plain.tet_ids, x.tet_ids, "{name}: budget {huge}");
        }
    }
}

#[test]
fn bad_requests_are_refused() {
    let (_, mt, _) = built("pinion");
    let nan = ExtractOptions::threshold(f64::NAN);
    assert!(matches!(
        mt.extract(&nan),
        Err(ExtractError::InvalidOptions(_))
    ));
    let negative = ExtractOptions::threshold(-1.0);
    assert!(
        mt.extract(&negative)
            .unwrap_err()
            .to_string()
            .contains("threshold")
    );
    let sphere = Region::Sphere {
        center: DVec3::ZERO,
        radius: -1.0,
    };
    let bad_focus = ExtractOptions::DEFAULT.with_focus(sphere, 0.0);
    assert!(
        mt.extract(&bad_focus)
            .unwrap_err()
            .to_string()
            .contains("radius")
    );
    assert!(Frontier::new(mt, &bad_focus).is_err());
}

fn same_mesh(a: &Extraction, b: &Extraction) -> bool {
    a.mesh == b.mesh && a.tet_ids == b.tet_ids && a.vertex_ids == b.vertex_ids
}

/// Reduces a failing sequence of requests to one update: a frontier made from scratch for
/// an earlier request, updated once to the last. Falls back to the last two requests.
fn minimal_failing_pair(mt: &Mt, history: &[ExtractOptions]) -> (ExtractOptions, ExtractOptions) {
    let last = history[history.len() - 1];
    let expect = mt.extract(&last).unwrap();
    for from in &history[..history.len() - 1] {
        let mut f = Frontier::new(mt, from).unwrap();
        f.update(mt, &last).unwrap();
        if !same_mesh(&f.to_extraction(mt), &expect) {
            return (*from, last);
        }
    }
    (history[history.len().saturating_sub(2)], last)
}

/// A random request: uniform threshold from the error distribution, often a focus
/// (sphere or box) somewhere in the bounding box with a finer threshold.
fn random_request(rng: &mut Rng, bbox: &Aabb, e: &[f64]) -> ExtractOptions {
    let pick = |rng: &mut Rng| {
        if rng.below(8) == 0 {
            [0.0, f64::INFINITY][rng.below(2)]
        } else {
            e[rng.below(e.len())]
        }
    };
    let mut o = ExtractOptions::threshold(pick(rng));
    if rng.below(4) != 0 {
        let c = bbox.min + bbox.extent() * DVec3::new(rng.f64(), rng.f64(), rng.f64());
        let r = bbox.diagonal() * (0.05 + 0.3 * rng.f64());
        let region = if rng.below(2) == 0 {
            Region::Sphere {
                center: c,
                radius: r,
            }
        } else {
            Region::Box(Aabb {
                min: c - DVec3::splat(r),
                max: c + DVec3::splat(r * 0.5),
            })
        };
        o = o.with_focus(region, pick(rng) * rng.f64());
    }
    o
}

/// Moves a request a little: the focus shifts, or one threshold changes.
fn nudge(rng: &mut Rng, o: &ExtractOptions, bbox: &Aabb, e: &[f64]) -> ExtractOptions {
    let mut n = *o;
    match (rng.below(3), o.focus) {
        (0, Some(mut f)) => {
            let d = bbox.extent()
                * 0.05
                * DVec3::new(rng.f64() - 0.5, rng.f64() - 0.5, rng.f64() - 0.5);
            f.region = match f.region {
                Region::Sphere { center, radius } => Region::Sphere {
                    center: center + d,
                    radius,
                },
                Region::Box(b) => Region::Box(Aabb {
                    min: b.min + d,
                    max: b.max + d,
                }),
            };
            n.focus = Some(f);
        }
        (1, _) => n.threshold = e[rng.below(e.len())],
        _ => return random_request(rng, bbox, e),
    }
    n
}

#[test]
fn incremental_updates_equal_extraction_from_scratch() {
    for (m, name) in MESHES.iter().enumerate() {
        let (input, mt, _) = built(name);
        let bbox = input.bbox();
        let e = errors(mt);
        for run in 0..4u64 {
            let seed = 0x5eed_0000 + 16 * m as u64 + run;
            let mut rng = Rng(seed);
            let mut request = random_request(&mut rng, &bbox, &e);
            let mut frontier = Frontier::new(mt, &request).unwrap();
            let mut history = vec![request];
            for step in 0..25 {
                request = nudge(&mut rng, &request, &bbox, &e);
                history.push(request);
                let stats = frontier.update(mt, &request).unwrap();
                let scratch = mt.extract(&request).unwrap();
                let incremental = frontier.to_extraction(mt);
                if !same_mesh(&incremental, &scratch) {
                    let (from, to) = minimal_failing_pair(mt, &history);
                    panic!(
                        "{name}, seed {seed:#x}, step {step}: incremental ({} tets) differs from \
                         scratch ({} tets) after {stats:?}; smallest failing input: a frontier \
                         made for {from:?} updated to {to:?}",
                        incremental.stats.tets, scratch.stats.tets
                    );
                }
                assert_eq!(frontier.nb_tets(), scratch.stats.tets);
                if step % 8 == 0 {
                    let v = incremental.mesh.validate();
                    assert!(v.is_valid(), "{name}, seed {seed:#x}, step {step}: {v}");
                }
            }
        }
    }
}

#[test]
fn incremental_updates_with_budgets_equal_extraction_from_scratch() {
    let (input, mt, _) = built("fandisk");
    let bbox = input.bbox();
    let e = errors(mt);
    let seed = 0xb0d6e7;
    let mut rng = Rng(seed);
    let mut frontier = Frontier::new(mt, &ExtractOptions::COARSEST).unwrap();
    for step in 0..12 {
        let mut request = random_request(&mut rng, &bbox, &e);
        if step % 2 == 0 {
            let budget = mt.coarsest_tets() + rng.below(input.nb_tets());
            request = request.with_budget(Some(budget));
        }
        frontier.update(mt, &request).unwrap();
        let scratch = mt.extract(&request).unwrap();
        assert!(
            same_mesh(&frontier.to_extraction(mt), &scratch),
            "seed {seed:#x}, step {step}: {request:?}"
        );
        assert_eq!(frontier.budget_met(), scratch.stats.budget_met);
    }
}

#[test]
fn frontier_slots_map_to_pool_ids_and_stay_put() {
    let (input, mt, _) = built("pinion");
    let bbox = input.bbox();
    let e = errors(mt);
    let start = ExtractOptions::threshold(e[e.len() / 2]);
    let mut f = Frontier::new(mt, &start).unwrap();
    let before: Vec<_> = f.tet_slots().to_vec();
    // Centred on a vertex of the mesh (the middle of the gear is its hole).
    let focus = Region::Sphere {
        center: input.position(mtcut::mesh::VertexId(0)),
        radius: 0.1 * bbox.diagonal(),
    };
    let stats = f.update(mt, &start.with_focus(focus, 0.0)).unwrap();
    assert!(stats.refined > 0 && stats.tets_added > 0);
    assert!(stats.candidates < mt.nb_fragments() / 2, "{stats:?}");
    // Tets that stayed keep their slots; every live slot maps back to its pool tet.
    for (slot, t) in f.tet_slots().iter().enumerate() {
        if t.is_valid() {
            assert_eq!(f.slot_of_tet(*t), Some(slot as u32));
            let corners = f.local_tets()[slot].map(|s| f.vertex_slots()[s as usize]);
            assert_eq!(corners, mt.tet(*t));
        }
    }
    let kept = before
        .iter()
        .enumerate()
        .filter(|(s, t)| t.is_valid() && f.tet_slots()[*s] == **t)
        .count();
    assert!(kept > 0);
    for (slot, v) in f.vertex_slots().iter().enumerate() {
        if v.is_valid() {
            assert_eq!(f.slot_of_vertex(*v), Some(slot as u32));
        }
    }
}
