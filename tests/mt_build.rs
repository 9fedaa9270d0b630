//! Building the MT (paper §2): on each shared mesh the MT is valid, its finest frontier is
//! the input, its coarsest is small and close to the input's boundary, and every frontier
//! in between is a valid mesh.

mod mt_common;

use mt_common::{MESHES, boundary_deviation, built, mesh, tets_in_mt_ids};
use mtcut::geom::DVec3;
use mtcut::mesh::{Attribute, FragmentId, TetMesh};
use mtcut::mt::{
    BuildError, BuildOptions, BuildPhase, CELL_ERROR, CELL_FRAGMENT, ErrorMetric, ExtractOptions,
    FragmentKind, Mt, POINT_VERTEX, TetError, TetSample,
};
use std::ops::ControlFlow;
use std::sync::Arc;

#[test]
fn each_shared_mesh_gives_a_valid_mt() {
    for name in MESHES {
        let (input, mt, stats) = built(name);
        let report = mt.validate();
        assert!(report.is_valid(), "{name}: {report}");
        eprintln!("{name}: {}", stats.to_json());
        assert_eq!(mt.nb_components(), 1);
        assert_eq!(stats.input_tets, input.nb_tets());
        assert!(stats.collapses > 0 && stats.dag_depth > 0);
        assert!(
            (stats.dag_depth as usize) < stats.collapses / 10,
            "{name}: batches should keep the DAG shallow ({} deep for {} collapses)",
            stats.dag_depth,
            stats.collapses
        );
    }
}

#[test]
fn the_summary_brackets_the_thresholds() {
    for name in MESHES {
        let (input, mt, _) = built(name);
        let s = mt.summary();
        assert_eq!(s.finest_tets, input.nb_tets());
        let steps: Vec<f64> = (0..mt.nb_fragments())
            .map(FragmentId::from_usize)
            .filter(|&f| mt.fragment_kind(f) == FragmentKind::Collapse)
            .map(|f| mt.fragment_error(f))
            .collect();
        assert_eq!(
            s.min_error,
            steps.iter().copied().fold(f64::INFINITY, f64::min)
        );
        assert_eq!(s.max_error, steps.iter().copied().fold(0.0, f64::max));
        // Below the smallest step error: the finest mesh; at the largest: the coarsest.
        let below = mt
            .extract(&ExtractOptions::threshold(0.5 * s.min_error))
            .unwrap();
        assert_eq!(below.mesh.nb_tets(), s.finest_tets, "{name}");
        let top = mt.extract(&ExtractOptions::threshold(s.max_error)).unwrap();
        assert_eq!(top.mesh.nb_tets(), s.coarsest_tets, "{name}");
    }
}

#[test]
fn finest_frontier_is_the_input_mesh() {
    for name in MESHES {
        let (input, mt, _) = built(name);
        let e = mt.extract(&ExtractOptions::FINEST).unwrap();
        let mut expect: Vec<[u32; 4]> = input.tets().iter().map(|t| t.map(|v| v.0)).collect();
        expect.sort_unstable();
        assert_eq!(tets_in_mt_ids(&e), expect, "{name}");
        for (local, v) in e.vertex_ids.iter().enumerate() {
            assert_eq!(e.mesh.positions()[local], input.position(*v), "{name}");
        }
        assert!(e.mesh.validate().is_valid());
        // The root made every finest tet: error 0.
        let err = &e.mesh.cell_data.get(CELL_ERROR).unwrap().values;
        assert!(err.iter().all(|&x| x == 0.0), "{name}");
    }
}

#[test]
fn thresholds_give_valid_meshes_coarsening_monotonically() {
    for name in MESHES {
        let (_, mt, _) = built(name);
        let coarsest = mt.extract(&ExtractOptions::COARSEST).unwrap();
        let v = coarsest.mesh.validate();
        assert!(v.is_valid(), "{name} coarsest: {v}");
        assert_eq!(coarsest.stats.tets, mt.coarsest_tets());
        let errors: Vec<f64> = (0..mt.nb_fragments())
            .map(|f| mt.fragment_error(FragmentId::from_usize(f)))
            .filter(|e| e.is_finite() && *e > 0.0)
            .collect();
        let lo = errors.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = errors.iter().copied().fold(0.0, f64::max);
        let mut previous = mt.extract(&ExtractOptions::FINEST).unwrap().stats.tets;
        let mut counts = vec![previous];
        for k in 0..20 {
            // Geometric spacing between the smallest and the largest error.
            let eps = lo * (hi / lo).powf(k as f64 / 19.0);
            let e = mt.extract(&ExtractOptions::threshold(eps)).unwrap();
            let v = e.mesh.validate();
            assert!(v.is_valid(), "{name} at threshold {eps}: {v}");
            assert!(
                e.stats.tets <= previous,
                "{name}: more tets at a larger threshold"
            );
            assert!(
                e.stats.max_error <= eps,
                "{name}: a tet of error {} > {eps}",
                e.stats.max_error
            );
            previous = e.stats.tets;
            counts.push(previous);
        }
        assert_eq!(
            previous, coarsest.stats.tets,
            "{name}: the largest error gives the coarsest"
        );
        eprintln!("{name}: tets at 20 thresholds: {counts:?}");
    }
}

#[test]
fn coarsest_fandisk_is_small_and_within_the_boundary_tolerance() {
    let (input, mt, stats) = built("fandisk");
    let coarsest = mt.extract(&ExtractOptions::COARSEST).unwrap();
    let fraction = coarsest.stats.tets as f64 / input.nb_tets() as f64;
    let diag = input.bbox().diagonal();
    let tol = BuildOptions::DEFAULT.boundary_tolerance.relative;
    let (coarse_to_input, input_to_coarse) = boundary_deviation(input, &coarsest.mesh, 8);
    eprintln!(
        "fandisk coarsest: {} of {} tets ({:.2} %), {} vertices; boundary deviation \
         coarse→input {:.5} and input→coarse {:.5} of the diagonal (tolerance {tol}); {} s",
        coarsest.stats.tets,
        input.nb_tets(),
        100.0 * fraction,
        coarsest.stats.vertices,
        coarse_to_input / diag,
        input_to_coarse / diag,
        stats.seconds
    );
    assert!(
        fraction <= 0.05,
        "coarsest has {:.2} % of the tets",
        100.0 * fraction
    );
    assert!(
        coarse_to_input <= tol * diag,
        "coarse boundary strays {coarse_to_input}"
    );
    assert!(
        input_to_coarse <= tol * diag,
        "input boundary strays {input_to_coarse}"
    );
}

/// Corners of the input boundary: vertices on one or more than two feature edges
/// (dihedral angle above the default feature angle), found here independently of the
/// build.
fn corners(m: &TetMesh, angle_degrees: f64) -> Vec<u32> {
    let tris = m.adjacency().boundary_faces();
    let mut normals: std::collections::HashMap<(u32, u32), Vec<DVec3>> = Default::default();
    for b in &tris {
        let t = m.tet(b.tet);
        let f = mtcut::mesh::tables::TET_FACES[b.face as usize].map(|k| t[k]);
        let p = f.map(|v| m.position(v));
        let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
        for k in 0..3 {
            let (a, c) = (f[k].0, f[(k + 1) % 3].0);
            normals.entry((a.min(c), a.max(c))).or_default().push(n);
        }
    }
    let cos = angle_degrees.to_radians().cos();
    let mut degree: std::collections::HashMap<u32, usize> = Default::default();
    for ((a, b), n) in &normals {
        if n[0].dot(n[1]) < cos {
            *degree.entry(*a).or_default() += 1;
            *degree.entry(*b).or_default() += 1;
        }
    }
    let mut c: Vec<u32> = degree
        .into_iter()
        .filter(|&(_, d)| d != 2)
        .map(|(v, _)| v)
        .collect();
    c.sort_unstable();
    c
}

#[test]
fn feature_corners_survive_to_the_coarsest_mesh() {
    let (input, mt, _) = built("fandisk");
    let coarse = mt.extract(&ExtractOptions::COARSEST).unwrap();
    let kept: std::collections::HashSet<u32> = coarse.vertex_ids.iter().map(|v| v.0).collect();
    let c = corners(input, BuildOptions::DEFAULT.feature_angle_degrees);
    assert!(!c.is_empty());
    let lost: Vec<&u32> = c.iter().filter(|v| !kept.contains(v)).collect();
    assert!(lost.is_empty(), "corners removed: {lost:?}");
}

#[test]
fn build_does_not_depend_on_the_number_of_threads() {
    let input = mesh("pinion");
    let options = BuildOptions::DEFAULT;
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| Mt::build(&input, &options).unwrap().0);
    let (_, many, _) = built("pinion");
    assert!(
        one == *many,
        "one thread and the default pool built different MTs"
    );
}

#[test]
fn canonical_form_ignores_numbering() {
    // The same mesh with its vertices and tets listed in another order: a different MT
    // numbering of the same simplification.
    let input = mesh("fandisk");
    let n = input.nb_vertices();
    let perm: Vec<u32> = (0..n as u32).map(|i| (i * 7919) % n as u32).collect();
    let mut positions = vec![DVec3::ZERO; n];
    for (old, &new) in perm.iter().enumerate() {
        positions[new as usize] = input.positions()[old];
    }
    let mut tets: Vec<[u32; 4]> = input
        .tets()
        .iter()
        .map(|t| t.map(|v| perm[v.idx()]))
        .collect();
    tets.reverse();
    let (shuffled, _) = TetMesh::from_arrays(positions, tets).unwrap();
    let (a, _) = Mt::build(&shuffled, &BuildOptions::DEFAULT).unwrap();
    let (_, b, _) = built("fandisk");
    assert!(a != *b, "numbering differs, so the stores differ");
    assert_eq!(a.canonical_form(), b.canonical_form());
}

#[test]
fn progress_is_reported_and_cancelling_hands_out_nothing() {
    let input = mesh("liver");
    let mut seen = Vec::new();
    let (mt, _) = Mt::build_with_progress(&input, &BuildOptions::DEFAULT, &mut |p| {
        seen.push(*p);
        ControlFlow::Continue(())
    })
    .unwrap();
    assert!(seen.len() > 3);
    assert!(seen.windows(2).all(|w| w[0].fraction <= w[1].fraction));
    let last = seen.last().unwrap();
    assert_eq!((last.phase, last.fraction), (BuildPhase::Done, 1.0));
    assert_eq!(last.fragments, mt.nb_fragments());
    let mut calls = 0;
    let r = Mt::build_with_progress(&input, &BuildOptions::DEFAULT, &mut |_| {
        calls += 1;
        if calls == 3 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    });
    assert_eq!(r.unwrap_err(), BuildError::Cancelled);
    assert_eq!(calls, 3);
}

#[test]
fn target_size_stops_the_build() {
    let input = mesh("pinion");
    let target = input.nb_tets() / 2;
    let (mt, stats) = Mt::build(
        &input,
        &BuildOptions::DEFAULT.with_target_tets(Some(target)),
    )
    .unwrap();
    assert!(mt.validate().is_valid());
    assert!(stats.coarsest_tets <= target);
    // Stopped soon after reaching it: the last round overshoots by less than a round.
    assert!(
        stats.coarsest_tets > target / 2,
        "{} tets",
        stats.coarsest_tets
    );
}

#[test]
fn every_error_metric_gives_a_valid_mt_with_errors_growing_along_the_dag() {
    let input = mesh("fandisk");
    for metric in ["boundary", "quality"] {
        let options = BuildOptions::DEFAULT
            .with_error(ErrorMetric::from_name(metric).unwrap())
            .with_target_tets(Some(input.nb_tets() / 4));
        let (mt, stats) = Mt::build(&input, &options).unwrap();
        let report = mt.validate();
        assert!(report.is_valid(), "{metric}: {report}");
        assert_eq!(mt.info().error_metric, metric);
        for a in 0..mt.nb_arcs() {
            assert!(mt.fragment_error(mt.arc_creator(a)) <= mt.fragment_error(mt.arc_destroyer(a)));
        }
        eprintln!("{metric}: {}", stats.to_json());
    }
}

/// A custom metric: the longest edge.
struct LongestEdge;
impl TetError for LongestEdge {
    fn name(&self) -> &str {
        "longest-edge"
    }
    fn tet_error(&self, t: &TetSample) -> f64 {
        let c = t.corners;
        let mut m = 0.0f64;
        for i in 0..4 {
            for j in i + 1..4 {
                m = m.max((c[i] - c[j]).length());
            }
        }
        m / t.scale
    }
}

struct Broken;
impl TetError for Broken {
    fn name(&self) -> &str {
        "broken"
    }
    fn tet_error(&self, _: &TetSample) -> f64 {
        f64::NAN
    }
}

#[test]
fn custom_metrics_plug_in_and_bad_values_are_refused() {
    let input = mesh("pinion");
    let options = BuildOptions::DEFAULT
        .with_error(ErrorMetric::Custom(Arc::new(LongestEdge)))
        .with_target_tets(Some(input.nb_tets() / 3));
    let (mt, _) = Mt::build(&input, &options).unwrap();
    assert!(mt.validate().is_valid());
    assert_eq!(mt.info().error_metric, "longest-edge");
    let err = Mt::build(
        &input,
        &BuildOptions::DEFAULT.with_error(ErrorMetric::Custom(Arc::new(Broken))),
    )
    .unwrap_err();
    assert!(matches!(err, BuildError::BadErrorValue { .. }), "{err}");
    assert!(err.to_string().contains("broken"), "{err}");
}

#[test]
fn bad_options_and_bad_input_are_refused_with_a_reason() {
    let input = mesh("pinion");
    for (options, what) in [
        (
            BuildOptions::DEFAULT.with_boundary_tolerance(-1.0),
            "tolerance",
        ),
        (
            BuildOptions::DEFAULT.with_feature_angle_degrees(200.0),
            "angle",
        ),
        (BuildOptions::DEFAULT.with_min_quality(1.5), "quality"),
        (BuildOptions::DEFAULT.with_batch_ratio(0.5), "batch"),
    ] {
        let e = Mt::build(&input, &options).unwrap_err();
        assert!(matches!(e, BuildError::InvalidOptions(_)), "{e}");
        assert!(e.to_string().contains(what), "{e}");
    }
    let mut moved = input.clone();
    let t = moved.tet(mtcut::mesh::TetId(0));
    let (a, b) = (moved.position(t[0]), moved.position(t[1]));
    moved.positions_mut()[t[0].idx()] = b;
    moved.positions_mut()[t[1].idx()] = a;
    let e = Mt::build(&moved, &BuildOptions::DEFAULT).unwrap_err();
    assert!(matches!(e, BuildError::InvalidMesh(_)), "{e}");
    assert!(e.to_string().contains("tet"), "{e}");
}

#[test]
fn attributes_travel_with_their_vertices_and_tets() {
    let mut input = mesh("liver");
    let temperature: Vec<f64> = input.positions().iter().map(|p| p.x).collect();
    input
        .point_data
        .insert(Attribute::new("temperature", 1, temperature).unwrap());
    let region: Vec<f64> = (0..input.nb_tets()).map(|t| (t % 3) as f64).collect();
    input
        .cell_data
        .insert(Attribute::new("region", 1, region.clone()).unwrap());
    let (mt, _) = Mt::build(&input, &BuildOptions::DEFAULT).unwrap();
    assert!(mt.validate().is_valid());
    let finest = mt.extract(&ExtractOptions::FINEST).unwrap();
    // Every finest tet carries its input tet's region, found by its vertices.
    let by_vertices: std::collections::HashMap<[u32; 4], f64> = input
        .tets()
        .iter()
        .zip(&region)
        .map(|(t, r)| (t.map(|v| v.0), *r))
        .collect();
    let got = &finest.mesh.cell_data.get("region").unwrap().values;
    for (t, r) in finest.mesh.tets().iter().zip(got) {
        let key = t.map(|v| finest.vertex_ids[v.idx()].0);
        assert_eq!(by_vertices[&key], *r);
    }
    // Every extracted vertex carries its own temperature and MT id, at every level.
    for options in [ExtractOptions::FINEST, ExtractOptions::COARSEST] {
        let e = mt.extract(&options).unwrap();
        let temp = &e.mesh.point_data.get("temperature").unwrap().values;
        let ids = &e.mesh.point_data.get(POINT_VERTEX).unwrap().values;
        for (k, v) in e.vertex_ids.iter().enumerate() {
            assert_eq!(temp[k], input.position(*v).x);
            assert_eq!(ids[k], v.0 as f64);
        }
        // Coarse tets inherit a region of the tets they replace.
        let regions = &e.mesh.cell_data.get("region").unwrap().values;
        assert!(regions.iter().all(|r| [0.0, 1.0, 2.0].contains(r)));
        let frags = &e.mesh.cell_data.get(CELL_FRAGMENT).unwrap().values;
        for (f, t) in frags.iter().zip(&e.tet_ids) {
            assert_eq!(*f as u32, mt.tet_creator(*t).0);
        }
    }
}

#[test]
fn root_and_drain_close_the_dag() {
    let (input, mt, _) = built("pinion");
    let root = mt.roots()[0];
    let drain = mt.drains()[0];
    assert_eq!(mt.fragment_kind(root), FragmentKind::Root);
    assert_eq!(mt.fragment_kind(drain), FragmentKind::Drain);
    assert_eq!(mt.fragment_level(root), 0);
    assert_eq!(mt.fragment_level(drain), mt.dag_depth());
    assert_eq!(mt.fragment_error(root), 0.0);
    assert_eq!(mt.fragment_error(drain), f64::INFINITY);
    let root_real = mt.created_tets(root).filter(|t| !mt.is_ghost(*t)).count();
    assert_eq!(root_real, input.nb_tets());
    for t in mt.created_tets(root).take(100) {
        assert_eq!(mt.tet_creator(t), root);
    }
}

/// An `n³` grid of unit cubes, each split into six tets around its main diagonal (Kuhn).
fn kuhn_cube(n: usize) -> TetMesh {
    let id = |i: usize, j: usize, k: usize| (i + (n + 1) * (j + (n + 1) * k)) as u32;
    let mut positions = Vec::new();
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                positions.push(DVec3::new(i as f64, j as f64, k as f64));
            }
        }
    }
    let mut tets = Vec::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let c = |b: usize| id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
                // The six paths from corner 0 to corner 7 along the axes.
                for (a, b) in [(1, 3), (1, 5), (2, 3), (2, 6), (4, 5), (4, 6)] {
                    tets.push([c(0), c(a), c(b), c(7)]);
                }
            }
        }
    }
    TetMesh::from_arrays(positions, tets).unwrap().0
}

#[test]
fn a_subdivided_cube_coarsens_to_a_few_tets_with_its_volume() {
    let input = kuhn_cube(4);
    let (mt, stats) = Mt::build(&input, &BuildOptions::DEFAULT).unwrap();
    let report = mt.validate();
    assert!(report.is_valid(), "{report}");
    let coarse = mt.extract(&ExtractOptions::COARSEST).unwrap();
    assert!(coarse.mesh.validate().is_valid());
    // Flat faces and straight edges: the boundary does not move at all, so neither does
    // the volume.
    assert!(
        (coarse.mesh.volume() - 64.0).abs() < 1e-9,
        "{}",
        coarse.mesh.volume()
    );
    assert_eq!(boundary_deviation(&input, &coarse.mesh, 4), (0.0, 0.0));
    eprintln!(
        "cube: {} tets → {} ({})",
        input.nb_tets(),
        coarse.stats.tets,
        stats.to_json()
    );
    // The eight corners stay; greedy simplification may leave a vertex or two more.
    let corner = |p: DVec3| p.to_array().iter().all(|&c| c == 0.0 || c == 4.0);
    let corners = coarse
        .mesh
        .positions()
        .iter()
        .filter(|p| corner(**p))
        .count();
    assert_eq!(corners, 8);
    assert!(coarse.stats.tets <= 12, "{} tets left", coarse.stats.tets);
}

#[test]
fn a_single_tet_is_its_own_coarsest_mesh() {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    let (input, _) = TetMesh::from_arrays(p, vec![[0, 1, 2, 3]]).unwrap();
    let (mt, stats) = Mt::build(&input, &BuildOptions::DEFAULT).unwrap();
    assert!(mt.validate().is_valid());
    assert_eq!(stats.collapses, 0);
    assert_eq!(mt.nb_fragments(), 2);
    assert_eq!(
        mt.extract(&ExtractOptions::COARSEST)
            .unwrap()
            .mesh
            .nb_tets(),
        1
    );
}

/// Closing an opened MT checks every tet's vertex ids: all of them when the editor says
/// nothing, else the tets it listed as written and those it appended (the others were
/// checked when the MT was assembled). A vertex beyond the pool is an error naming the
/// tet, never a panic later.
#[test]
fn closing_an_edit_checks_the_vertex_ids_it_wrote() {
    let (_, mt, _) = built("pinion");
    let nv = mt.nb_vertices() as u32;
    let beyond = mtcut::mesh::VertexId(nv + 3);
    // Unlisted: the whole pool is checked.
    let mut open = mt.clone().open();
    open.tets[10][0] = beyond;
    let e = open.close().unwrap_err();
    assert!(
        e.contains("tet") && e.contains(&format!("{}", nv + 3)),
        "{e}"
    );
    // Listed as written.
    let mut open = mt.clone().open();
    open.tets[10][1] = beyond;
    open.written_tets = Some(vec![3, 10]);
    let e = open.close().unwrap_err();
    assert!(e.contains("tet 10"), "{e}");
    // Appended (a copy of tet 0, with the same creator and destroyer, one vertex beyond).
    let mut open = mt.clone().open();
    let mut t = open.tets[0];
    t[2] = beyond;
    let (c, d) = (open.creator()[0], open.destroyer()[0]);
    open.push_tet(t, c, d);
    open.cell_data.push_copies(&[0]);
    open.written_tets = Some(Vec::new());
    let e = open.close().unwrap_err();
    assert!(e.contains(&format!("{}", nv + 3)), "{e}");
    // Nothing wrong: the same MT back.
    let mut open = mt.clone().open();
    open.written_tets = Some(vec![10]);
    assert!(open.close().unwrap() == *mt);
}

/// A vertex of very high valence (the apex and the top of a cone of 2,000 tets around
/// its axis, as a structured cylindrical grid has on its axis): each collapse of the apex
/// is tried onto its nearest neighbours only, so building takes about a second, not a
/// minute (it grew with the cube of the valence), and the MT is valid.
#[test]
fn a_cone_of_many_tets_is_simplified() {
    let n = 2000;
    let mut positions = vec![DVec3::ZERO, DVec3::new(0.0, 0.0, 1.0)];
    positions.extend((0..n).map(|i| {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        DVec3::new(a.cos(), a.sin(), 0.5)
    }));
    let ring = |i: usize| 2 + (i % n) as u32;
    let tets = (0..n).map(|i| [0, 1, ring(i), ring(i + 1)]).collect();
    let (mesh, _) = TetMesh::from_arrays(positions, tets).expect("cone");
    let (mt, _) = Mt::build(&mesh, &BuildOptions::DEFAULT).expect("build");
    assert!(mt.nb_fragments() > n / 2, "{} fragments", mt.nb_fragments());
    let report = mt.validate();
    assert!(report.is_valid(), "{report}");
    let coarse = mt.extract(&ExtractOptions::COARSEST).expect("coarsest");
    assert!(
        coarse.mesh.nb_tets() < n / 10,
        "{} tets",
        coarse.mesh.nb_tets()
    );
    assert!(coarse.mesh.validate().is_valid());
}
