//! Building an MT by simplification (paper §2): half-edge collapses taken from a lazily
//! invalidated priority queue, each recorded as one fragment; then the record is frozen
//! into the flat store of [`Mt`].
//!
//! **Queue.** Each vertex has at most one live candidate (its best direction, with the
//! vertex's *ticket*: re-evaluating a vertex invalidates its older entries, and an entry
//! whose other end changed since is dropped and its vertex re-evaluated). Evaluation ranks
//! directions by the errors of the tets they would create; the exact rules, which are most
//! of the cost, run only for candidates selected into a round (VCGlib's is-feasible at pop).
//!
//! **Rounds.** Collapses are taken in *rounds* of independent collapses: popping candidates
//! in priority order, a collapse is selected only if neither of its vertices lies in the
//! closed star of a collapse already selected in the round (those are deferred). Selected
//! collapses have disjoint floors and none consumes another's ceiling, so they are
//! independent fragments of the DAG: the depth grows by about one per round, not one per
//! collapse. A round also stops at a candidate whose priority exceeds
//! [`BuildOptions::batch_ratio`] times the round's first, so the order of errors is kept
//! within that factor. The round's selections are then checked against the exact rules in
//! parallel (independent collapses do not affect each other's checks); those that fail give
//! way to their vertex's best legal collapse, queued for later. The vertices whose stars
//! changed are re-evaluated in parallel (rayon), and the stars a round changes are updated
//! in parallel; everything else is sequential and in a fixed order, so the result does
//! not depend on the number of threads, nor on how the input numbers its vertices and
//! tets (the build renumbers them by position first).
//!
//! **Rules** (in `collapse.rs`): no created tet inverted or flat (exact `orient3d`); no
//! created tet below the quality floor unless the star already was; the link condition on
//! the closed complex (mesh plus ghosts); boundary vertices move along boundary edges only,
//! feature-line vertices along their line only, corners never; the boundary stays within
//! the tolerance of the original surface both ways (points of the original surface —
//! vertices, edge midpoints, face centroids — to the new faces, and points of the new faces
//! on a grid to the original surface) and no boundary face turns by more than the feature
//! angle.

mod collapse;
mod link;
mod surface;

pub use collapse::Rejections;

use super::error::{BoundaryError, ErrorMetric, QualityError, TetError, VolumeError};
use super::{CutHistory, FragmentKind, MAX_ELEMENTS, Mt, MtInfo, MtParts};
use crate::geom::{DVec3, Tolerance};
use crate::mesh::fxhash::FxBuild;
use crate::mesh::tables::TET_FACES;
use crate::mesh::{Attribute, Attributes, FragmentId, Tet, TetMesh, VertexId};
use crate::mt::GHOST;
use collapse::{Candidate, Incident, Simplifier};
use rayon::prelude::*;
use std::cmp::{Ordering, Reverse};
use std::collections::{BinaryHeap, HashMap, HashSet};
use std::ops::ControlFlow;
use std::time::Instant;
use surface::{Surface, VertexClass, feature_edges};

/// How to build an MT. Every field documents its default ([`BuildOptions::DEFAULT`]).
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct BuildOptions {
    /// The per-tet error. Default: [`ErrorMetric::Volume`] (the paper's).
    pub error: ErrorMetric,
    /// How far the boundary of any level may stray from the input's boundary surface,
    /// relative to the input's bounding-box diagonal. Default 0.005 (0.5 %): a coarse
    /// fandisk stays visually the same part while shrinking below 5 % of its tets.
    pub boundary_tolerance: Tolerance,
    /// Keep boundary feature edges (as lines) and corners. Default `true`.
    pub preserve_features: bool,
    /// A boundary edge whose two faces' normals differ by more than this angle (degrees)
    /// is a feature; no boundary face may turn by more than it in one collapse. Default 30
    /// (VTK's `vtkFeatureEdges` default).
    pub feature_angle_degrees: f64,
    /// Mean-ratio quality floor (0..1): a collapse may not create a tet worse than this
    /// unless the tets it removes already were. Default 0.02 (forbids near-flat slivers,
    /// leaves the simplifier free otherwise).
    pub min_quality: f64,
    /// Stop when the mesh has at most this many tets. Default `None`: until no legal
    /// collapse is left.
    pub target_tets: Option<usize>,
    /// A round of independent collapses stops at a candidate whose priority exceeds this
    /// factor times the round's first priority (≥ 1; +∞ makes each round a maximal
    /// independent set). Default 4.
    pub batch_ratio: f64,
}

impl BuildOptions {
    pub const DEFAULT: BuildOptions = BuildOptions {
        error: ErrorMetric::Volume,
        boundary_tolerance: Tolerance { relative: 0.005 },
        preserve_features: true,
        feature_angle_degrees: 30.0,
        min_quality: 0.02,
        target_tets: None,
        batch_ratio: 4.0,
    };

    pub fn with_error(mut self, error: ErrorMetric) -> Self {
        self.error = error;
        self
    }
    pub fn with_boundary_tolerance(mut self, relative: f64) -> Self {
        self.boundary_tolerance = Tolerance { relative };
        self
    }
    pub fn with_preserve_features(mut self, keep: bool) -> Self {
        self.preserve_features = keep;
        self
    }
    pub fn with_feature_angle_degrees(mut self, degrees: f64) -> Self {
        self.feature_angle_degrees = degrees;
        self
    }
    pub fn with_min_quality(mut self, q: f64) -> Self {
        self.min_quality = q;
        self
    }
    pub fn with_target_tets(mut self, target: Option<usize>) -> Self {
        self.target_tets = target;
        self
    }
    pub fn with_batch_ratio(mut self, ratio: f64) -> Self {
        self.batch_ratio = ratio;
        self
    }

    fn check(&self) -> Result<(), BuildError> {
        let bad = |what: String| Err(BuildError::InvalidOptions(what));
        let t = self.boundary_tolerance.relative;
        if !(t.is_finite() && t >= 0.0) {
            return bad(format!("boundary tolerance {t} (must be finite and ≥ 0)"));
        }
        let a = self.feature_angle_degrees;
        if !(0.0..=180.0).contains(&a) {
            return bad(format!(
                "feature angle {a} degrees (must be within 0..=180)"
            ));
        }
        let q = self.min_quality;
        if !(0.0..=1.0).contains(&q) {
            return bad(format!("quality floor {q} (must be within 0..=1)"));
        }
        let r = self.batch_ratio;
        if r.is_nan() || r < 1.0 {
            return bad(format!("batch ratio {r} (must be ≥ 1)"));
        }
        Ok(())
    }
}

impl Default for BuildOptions {
    fn default() -> Self {
        BuildOptions::DEFAULT
    }
}

/// Where a build is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BuildPhase {
    /// Collapsing edges.
    Simplify,
    /// Turning the record into the flat store.
    Freeze,
    Done,
}

/// What the progress callback is told, about once per round.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuildProgress {
    pub phase: BuildPhase,
    /// Estimated fraction of the work done, 0..=1, never decreasing.
    pub fraction: f64,
    /// Tets of the current (coarsening) mesh.
    pub live_tets: usize,
    /// Fragments recorded so far.
    pub fragments: usize,
}

/// Why a build failed. Nothing half-built is ever returned.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BuildError {
    #[error("build cancelled by the progress callback")]
    Cancelled,
    #[error("invalid build option: {0}")]
    InvalidOptions(String),
    #[error("the input mesh is invalid: {0}")]
    InvalidMesh(String),
    #[error("the input mesh has no tetrahedra")]
    EmptyMesh,
    #[error("the model would exceed {max} vertices, tets or fragments")]
    TooLarge { max: usize },
    #[error("error metric '{metric}' returned {value}, but errors must be finite and ≥ 0")]
    BadErrorValue { metric: String, value: f64 },
    #[error("internal error while freezing the MT (a bug): {0}")]
    Internal(String),
}

/// What a build did.
#[derive(Clone, Debug, PartialEq)]
pub struct BuildStats {
    pub input_tets: usize,
    pub input_vertices: usize,
    /// Collapses performed (fragments other than root and drain).
    pub collapses: usize,
    /// Rounds of independent collapses.
    pub rounds: usize,
    /// Tets and vertices of the coarsest mesh.
    pub coarsest_tets: usize,
    pub coarsest_vertices: usize,
    /// Non-ghost tets in the pool (all levels) and ghost tets.
    pub pool_tets: usize,
    pub ghost_tets: usize,
    pub arcs: usize,
    pub fragments: usize,
    pub dag_depth: u32,
    /// Candidate collapses turned down, by rule.
    pub rejected: Rejections,
    pub heap_bytes: usize,
    pub seconds: f64,
}

impl BuildStats {
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "input_tets": self.input_tets,
            "input_vertices": self.input_vertices,
            "collapses": self.collapses,
            "rounds": self.rounds,
            "coarsest_tets": self.coarsest_tets,
            "coarsest_vertices": self.coarsest_vertices,
            "pool_tets": self.pool_tets,
            "ghost_tets": self.ghost_tets,
            "arcs": self.arcs,
            "fragments": self.fragments,
            "dag_depth": self.dag_depth,
            "rejected": {
                "orientation": self.rejected.orientation,
                "quality": self.rejected.quality,
                "link": self.rejected.link,
                "boundary": self.rejected.boundary,
            },
            "heap_bytes": self.heap_bytes,
            "seconds": self.seconds,
        })
    }
}

/// Heap entry: lowest priority first, then lowest vertex id (a total, deterministic order:
/// a vertex has one live entry, its latest ticket, so live entries never tie). The
/// candidate itself waits in `latest` (one per vertex): 16-byte entries keep the heap's
/// sift-downs, the serial part of the build, in fewer cache lines.
#[derive(Clone, Copy)]
struct Queued {
    priority: f64,
    v: u32,
    ticket: u32,
}

impl Queued {
    fn of(c: &Candidate) -> Reverse<Queued> {
        Reverse(Queued {
            priority: c.priority,
            v: c.v,
            ticket: c.ticket,
        })
    }
}

impl PartialEq for Queued {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Queued {}
impl PartialOrd for Queued {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Queued {
    fn cmp(&self, o: &Self) -> Ordering {
        self.priority
            .total_cmp(&o.priority)
            .then(self.v.cmp(&o.v))
            .then(self.ticket.cmp(&o.ticket))
    }
}

impl Mt {
    /// Builds the MT of `mesh` with `options` (see [`BuildOptions`]).
    pub fn build(mesh: &TetMesh, options: &BuildOptions) -> Result<(Mt, BuildStats), BuildError> {
        Mt::build_with_progress(mesh, options, &mut |_| ControlFlow::Continue(()))
    }

    /// [`build`](Self::build), calling `progress` about once per round of collapses;
    /// returning `ControlFlow::Break(())` cancels the build ([`BuildError::Cancelled`]).
    pub fn build_with_progress(
        mesh: &TetMesh,
        options: &BuildOptions,
        progress: &mut dyn FnMut(&BuildProgress) -> ControlFlow<()>,
    ) -> Result<(Mt, BuildStats), BuildError> {
        options.check()?;
        match &options.error {
            ErrorMetric::Volume => run(mesh, options, &VolumeError, progress),
            ErrorMetric::Boundary(b) => run(mesh, options, b as &BoundaryError, progress),
            ErrorMetric::Quality => run(mesh, options, &QualityError, progress),
            ErrorMetric::Custom(c) => run(mesh, options, c.as_ref(), progress),
        }
    }
}

fn run<E: TetError + ?Sized>(
    mesh: &TetMesh,
    options: &BuildOptions,
    metric: &E,
    progress: &mut dyn FnMut(&BuildProgress) -> ControlFlow<()>,
) -> Result<(Mt, BuildStats), BuildError> {
    let start = Instant::now();
    if mesh.nb_tets() == 0 {
        return Err(BuildError::EmptyMesh);
    }
    check_input(mesh)?;
    if mesh.nb_vertices() > MAX_ELEMENTS || mesh.nb_tets() > MAX_ELEMENTS {
        return Err(BuildError::TooLarge { max: MAX_ELEMENTS });
    }
    let (mut sim, renumbering) = setup(mesh, options, metric);
    let mut stats = BuildStats {
        input_tets: mesh.nb_tets(),
        input_vertices: mesh.nb_vertices(),
        collapses: 0,
        rounds: 0,
        coarsest_tets: 0,
        coarsest_vertices: 0,
        pool_tets: 0,
        ghost_tets: 0,
        arcs: 0,
        fragments: 0,
        dag_depth: 0,
        rejected: Rejections::default(),
        heap_bytes: 0,
        seconds: 0.0,
    };
    simplify(&mut sim, options, &mut stats, progress)?;
    let report = |fraction: f64, phase: BuildPhase, sim_live: usize, frags: usize| BuildProgress {
        phase,
        fraction,
        live_tets: sim_live,
        fragments: frags,
    };
    if progress(&report(
        0.95,
        BuildPhase::Freeze,
        sim.live_real,
        sim.raw_error.len(),
    ))
    .is_break()
    {
        return Err(BuildError::Cancelled);
    }
    stats.coarsest_vertices = sim
        .class
        .iter()
        .zip(&sim.stars)
        .filter(|(c, s)| **c != VertexClass::Removed && !s.is_empty())
        .count();
    let info = MtInfo {
        error_metric: metric.name().to_string(),
        boundary_tolerance: options.boundary_tolerance.relative,
        preserve_features: options.preserve_features,
        feature_angle_degrees: options.feature_angle_degrees,
        input_tets: mesh.nb_tets(),
        cuts: CutHistory::new(mesh.nb_vertices()),
    };
    let mt = freeze(sim, &renumbering, mesh, info)?;
    let summary = mt.summary();
    stats.coarsest_tets = summary.coarsest_tets;
    stats.pool_tets = summary.pool_tets;
    stats.ghost_tets = summary.ghost_tets;
    stats.arcs = summary.arcs;
    stats.fragments = summary.fragments;
    stats.dag_depth = summary.dag_depth;
    stats.heap_bytes = summary.heap_bytes;
    stats.seconds = start.elapsed().as_secs_f64();
    if progress(&report(
        1.0,
        BuildPhase::Done,
        stats.coarsest_tets,
        stats.fragments,
    ))
    .is_break()
    {
        return Err(BuildError::Cancelled);
    }
    Ok((mt, stats))
}

/// The build's own numbering: vertices sorted along a Morton curve and tets by their first
/// vertex, so that neighbouring elements are near in memory (TetGen numbers vertices in
/// insertion order, which scatters every star over the whole mesh). `freeze` maps back.
struct Renumbering {
    /// Input id of each build vertex.
    vertex_of: Vec<u32>,
    /// Input id of each of the root's non-ghost build tets.
    tet_of: Vec<u32>,
}

/// Morton code of `p` in `bbox` (21 bits per axis).
fn morton(p: DVec3, bbox: &crate::geom::Aabb) -> u64 {
    let e = bbox.extent().max(DVec3::splat(f64::MIN_POSITIVE));
    let q = ((p - bbox.min) / e * ((1u64 << 21) - 1) as f64)
        .clamp(DVec3::ZERO, DVec3::splat(((1u64 << 21) - 1) as f64));
    let spread = |x: u64| {
        let mut x = x & 0x1f_ffff;
        x = (x | (x << 32)) & 0x1f_0000_0000_ffff;
        x = (x | (x << 16)) & 0x1f_0000_ff00_00ff;
        x = (x | (x << 8)) & 0x100f_00f0_0f00_f00f;
        x = (x | (x << 4)) & 0x10c3_0c30_c30c_30c3;
        x = (x | (x << 2)) & 0x1249_2492_4924_9249;
        x
    };
    spread(q.x as u64) | (spread(q.y as u64) << 1) | (spread(q.z as u64) << 2)
}

/// A `TetMesh` was validated when it was made; only its positions can have changed since
/// ([`TetMesh::positions_mut`]), so those are re-checked: finite, every tet positively
/// oriented (exact).
fn check_input(mesh: &TetMesh) -> Result<(), BuildError> {
    if let Some(v) = mesh.positions().iter().position(|p| !p.is_finite()) {
        return Err(BuildError::InvalidMesh(format!(
            "vertex {v} has a NaN or infinite coordinate"
        )));
    }
    let bad = (0..mesh.nb_tets()).into_par_iter().find_first(|&t| {
        let [a, b, c, d] = mesh.tet_positions(crate::mesh::TetId::from_usize(t));
        crate::geom::orient3d(a, b, c, d) != crate::geom::Sign::Positive
    });
    match bad {
        Some(t) => Err(BuildError::InvalidMesh(format!(
            "tet {t} is inverted or flat (were positions moved?)"
        ))),
        None => Ok(()),
    }
}

/// The boundary triangles (outward) of a valid tet mesh: the faces met once. Found by
/// sorting all faces by their vertex sets, in parallel.
fn boundary_faces(tets: &[Tet]) -> Vec<[VertexId; 3]> {
    let mut keyed: Vec<([u32; 3], u32)> = (0..tets.len() * 4)
        .into_par_iter()
        .map(|i| {
            let (t, f) = (i / 4, i % 4);
            let mut k = TET_FACES[f].map(|j| tets[t][j].0);
            k.sort_unstable();
            (k, i as u32)
        })
        .collect();
    keyed.par_sort_unstable();
    let mut faces = Vec::new();
    let mut i = 0;
    while i < keyed.len() {
        let mut j = i + 1;
        while j < keyed.len() && keyed[j].0 == keyed[i].0 {
            j += 1;
        }
        if j - i == 1 {
            let (t, f) = (keyed[i].1 as usize / 4, keyed[i].1 as usize % 4);
            faces.push(TET_FACES[f].map(|k| tets[t][k]));
        }
        i = j;
    }
    faces
}

/// The simplifier's initial state: the input tets and one ghost per boundary face (all
/// created by the root, fragment 0), stars, vertex roles, the original surface.
fn setup<'a, E: TetError + ?Sized>(
    mesh: &TetMesh,
    options: &BuildOptions,
    metric: &'a E,
) -> (Simplifier<'a, E>, Renumbering) {
    let nv = mesh.nb_vertices();
    let bbox = mesh.bbox();
    let mut vertex_of: Vec<u32> = (0..nv as u32).collect();
    let codes: Vec<u64> = mesh
        .positions()
        .par_iter()
        .map(|p| morton(*p, &bbox))
        .collect();
    // Ties (equal codes) are broken by the coordinates, so the order, and with it the whole
    // build, does not depend on how the input happens to number its vertices and tets.
    let bits = |v: u32| mesh.positions()[v as usize].to_array().map(f64::to_bits);
    vertex_of.sort_unstable_by_key(|&v| (codes[v as usize], bits(v), v));
    let mut new_id = vec![0u32; nv];
    for (i, &v) in vertex_of.iter().enumerate() {
        new_id[v as usize] = i as u32;
    }
    let pos: Vec<DVec3> = vertex_of
        .iter()
        .map(|&v| mesh.positions()[v as usize])
        .collect();
    let renumber = |t: &Tet| t.map(|v| VertexId(new_id[v.idx()]));
    let tet_of: Vec<u32> = (0..mesh.nb_tets() as u32).collect();
    let mut keyed: Vec<([u32; 4], u32)> = tet_of
        .iter()
        .map(|&t| {
            let mut k = renumber(&mesh.tets()[t as usize]).map(|v| v.0);
            k.sort_unstable();
            (k, t)
        })
        .collect();
    keyed.par_sort_unstable();
    let tet_of: Vec<u32> = keyed.into_iter().map(|(_, t)| t).collect();
    let mut tets: Vec<Tet> = tet_of
        .iter()
        .map(|&t| renumber(&mesh.tets()[t as usize]))
        .collect();
    let faces = boundary_faces(&tets);
    tets.extend(faces.iter().map(|f| [f[0], f[1], f[2], GHOST]));
    let n = tets.len();
    // Stars from the incidences sorted by vertex (in parallel), each star in tet order.
    let mut incidences: Vec<(u32, u32)> = tets
        .par_iter()
        .enumerate()
        .flat_map_iter(|(t, tet)| {
            tet.iter()
                .filter(|x| **x != GHOST)
                .map(move |x| (x.0, t as u32))
        })
        .collect();
    incidences.par_sort_unstable();
    let starts: Vec<usize> = (0..=nv as u32)
        .into_par_iter()
        .map(|v| incidences.partition_point(|p| p.0 < v))
        .collect();
    let stars: Vec<Vec<Incident>> = (0..nv)
        .into_par_iter()
        .map(|v| {
            incidences[starts[v]..starts[v + 1]]
                .iter()
                .map(|&(_, t)| Incident {
                    id: t,
                    tet: tets[t as usize],
                })
                .collect()
        })
        .collect();
    drop(incidences);
    let features: HashSet<(u32, u32), FxBuild> = if options.preserve_features {
        feature_edges(&pos, &faces, options.feature_angle_degrees)
            .into_iter()
            .collect()
    } else {
        HashSet::default()
    };
    let mut on_boundary = vec![false; nv];
    for f in &faces {
        for v in f {
            on_boundary[v.idx()] = true;
        }
    }
    let mut feature_degree = vec![0u32; nv];
    for &(a, b) in &features {
        feature_degree[a as usize] += 1;
        feature_degree[b as usize] += 1;
    }
    let class: Vec<VertexClass> = (0..nv)
        .map(|v| {
            if stars[v].is_empty() {
                VertexClass::Removed
            } else if !on_boundary[v] {
                VertexClass::Interior
            } else {
                match feature_degree[v] {
                    0 => VertexClass::Smooth,
                    2 => VertexClass::Crease,
                    _ => VertexClass::Corner,
                }
            }
        })
        .collect();
    let scale = bbox.diagonal();
    let sim = Simplifier {
        metric,
        scale,
        // Summed in the build's own order, so the error scale does not depend on the
        // input's numbering either.
        volume: tets
            .iter()
            .filter(|t| t[3] != GHOST)
            .map(|t| {
                let [a, b, c, d] = t.map(|v| pos[v.idx()]);
                crate::geom::signed_volume_inexact(a, b, c, d)
            })
            .sum(),
        tol: options.boundary_tolerance.distance(scale),
        cos_turn: options.feature_angle_degrees.to_radians().cos(),
        min_quality: options.min_quality,
        surface: Surface::new(&pos, &faces),
        pos,
        creator: vec![0; n],
        destroyer: vec![u32::MAX; n],
        source: vec![u32::MAX; n],
        raw_error: vec![0.0],
        tets,
        stars,
        bucket: vec![0; nv],
        stamp: vec![0; nv],
        class,
        features,
        charges: HashMap::default(),
        root_tets: n as u32,
        live_real: mesh.nb_tets(),
    };
    (sim, Renumbering { vertex_of, tet_of })
}

/// The rounds of independent collapses (see the module docs).
fn simplify<E: TetError + ?Sized>(
    sim: &mut Simplifier<'_, E>,
    options: &BuildOptions,
    stats: &mut BuildStats,
    progress: &mut dyn FnMut(&BuildProgress) -> ControlFlow<()>,
) -> Result<(), BuildError> {
    let nv = sim.stars.len();
    let target = options.target_tets.unwrap_or(0);
    let initial = sim.live_real;
    let mut heap: BinaryHeap<Reverse<Queued>> = BinaryHeap::new();
    let mut dirty: Vec<u32> = (0..nv as u32).collect();
    let mut is_dirty = vec![true; nv];
    let mut locked = vec![false; nv];
    // Each vertex's latest evaluation: queued candidates with an older ticket are stale.
    let mut tickets = vec![0u32; nv];
    // The candidate of each vertex's latest ticket (what its live heap entry stands for).
    let mut latest: Vec<Candidate> = vec![Candidate::NONE; nv];
    let mut lock_list: Vec<u32> = Vec::new();
    let mut changed: Vec<u32> = Vec::new();
    let mut fraction = 0.0f64;
    let mut removed = 0usize;
    loop {
        // Re-evaluate every vertex whose star changed, on all cores, in vertex order (the
        // build's numbering is spatial, so neighbours share cache lines).
        dirty.sort_unstable();
        let results: Vec<(Option<Candidate>, Rejections)> = {
            let s: &Simplifier<'_, E> = sim;
            dirty
                .par_iter()
                .map(|&v| {
                    let mut rej = Rejections::default();
                    let c =
                        collapse::with_scratch(|scratch| s.evaluate(v, false, scratch, &mut rej));
                    (c, rej)
                })
                .collect()
        };
        for (&v, (c, rej)) in dirty.iter().zip(results) {
            if let Some(value) = rej.bad_error {
                return Err(BuildError::BadErrorValue {
                    metric: sim.metric.name().to_string(),
                    value,
                });
            }
            stats.rejected.add(&rej);
            // A new evaluation supersedes every queued candidate of v.
            tickets[v as usize] = tickets[v as usize].wrapping_add(1);
            if let Some(mut c) = c {
                if !(c.priority.is_finite() && c.priority >= 0.0) {
                    return Err(BuildError::BadErrorValue {
                        metric: sim.metric.name().to_string(),
                        value: c.priority,
                    });
                }
                c.ticket = tickets[v as usize];
                heap.push(Queued::of(&c));
                latest[v as usize] = c;
            }
        }
        for &v in &dirty {
            is_dirty[v as usize] = false;
        }
        dirty.clear();
        if sim.live_real <= target {
            break;
        }
        // One round: independent collapses in priority order.
        let mut selected: Vec<Candidate> = Vec::new();
        let mut deferred: Vec<Candidate> = Vec::new();
        let mut limit: Option<f64> = None;
        let mut projected = sim.live_real;
        while let Some(Reverse(q)) = heap.pop() {
            let v = q.v as usize;
            if sim.class[v] == VertexClass::Removed || tickets[v] != q.ticket {
                // Stale: v was re-evaluated since (or has nothing left to do).
                continue;
            }
            let c = latest[v];
            let w = c.w as usize;
            if !sim.is_up_to_date(&c) {
                // w changed under this candidate: evaluate v again.
                if !is_dirty[v] {
                    is_dirty[v] = true;
                    dirty.push(c.v);
                }
                continue;
            }
            match limit {
                None => limit = Some(c.priority * options.batch_ratio),
                Some(l) if c.priority > l => {
                    heap.push(Reverse(q));
                    break;
                }
                Some(_) => {}
            }
            if locked[v] || locked[w] {
                deferred.push(c);
                continue;
            }
            for inc in &sim.stars[v] {
                let tet = &inc.tet;
                for x in tet {
                    if *x != GHOST && !locked[x.idx()] {
                        locked[x.idx()] = true;
                        lock_list.push(x.0);
                    }
                }
                if tet[3] != GHOST && tet.iter().any(|x| x.0 == c.w) {
                    projected -= 1;
                }
            }
            selected.push(c);
            if projected <= target {
                break;
            }
        }
        if selected.is_empty() && dirty.is_empty() {
            break;
        }
        // The exact rules for the round's unchecked candidates, in parallel: they are
        // independent, so each is checked against the mesh as it is now. A candidate that
        // fails leaves its (locked) neighbourhood alone this round; its vertex's best
        // legal collapse, if any, is queued instead.
        let checks: Vec<(Option<Candidate>, Rejections, Vec<u32>)> = {
            let s: &Simplifier<'_, E> = sim;
            selected
                .par_iter()
                .map(|c| {
                    let mut rej = Rejections::default();
                    collapse::with_scratch(|scratch| {
                        let r = s.check(c, scratch, &mut rej);
                        (r, rej, std::mem::take(&mut scratch.placed))
                    })
                })
                .collect()
        };
        let mut accepted = Vec::with_capacity(selected.len());
        for (c, (r, rej, placed)) in selected.iter().zip(checks) {
            if let Some(value) = rej.bad_error {
                return Err(BuildError::BadErrorValue {
                    metric: sim.metric.name().to_string(),
                    value,
                });
            }
            stats.rejected.add(&rej);
            match r {
                Some(k) if k.w == c.w => accepted.push((k, placed)),
                Some(mut other) => {
                    let t = &mut tickets[c.v as usize];
                    *t = t.wrapping_add(1);
                    other.ticket = *t;
                    heap.push(Queued::of(&other));
                    latest[c.v as usize] = other;
                }
                None => {
                    let t = &mut tickets[c.v as usize];
                    *t = t.wrapping_add(1);
                }
            }
        }
        let selected = accepted;
        stats.rounds += usize::from(!selected.is_empty());
        if sim.raw_error.len() + selected.len() >= MAX_ELEMENTS - 1
            || sim.tets.len() + 64 * selected.len() >= MAX_ELEMENTS
        {
            return Err(BuildError::TooLarge { max: MAX_ELEMENTS });
        }
        sim.execute_round(&selected, &mut changed);
        removed += selected.len();
        // Only the vertices whose star changed need a new evaluation.
        for &x in &changed {
            if sim.class[x as usize] != VertexClass::Removed && !is_dirty[x as usize] {
                is_dirty[x as usize] = true;
                dirty.push(x);
            }
        }
        for c in deferred {
            heap.push(Queued::of(&c));
        }
        for &x in &lock_list {
            locked[x as usize] = false;
        }
        lock_list.clear();
        stats.collapses = removed;
        let estimate = if target > 0 {
            (initial - sim.live_real) as f64 / (initial - target.min(initial - 1)) as f64
        } else {
            removed as f64 / (removed + heap.len()).max(1) as f64
        };
        fraction = fraction.max(0.95 * estimate.clamp(0.0, 1.0));
        let p = BuildProgress {
            phase: BuildPhase::Simplify,
            fraction,
            live_tets: sim.live_real,
            fragments: sim.raw_error.len(),
        };
        if progress(&p).is_break() {
            return Err(BuildError::Cancelled);
        }
    }
    stats.collapses = removed;
    Ok(())
}

/// Record → store: close the DAG with the drain, order the pool by (creator, destroyer) so
/// every arc is a contiguous run, raise errors along the DAG, inherit cell data.
fn freeze<E: TetError + ?Sized>(
    sim: Simplifier<'_, E>,
    renumbering: &Renumbering,
    mesh: &TetMesh,
    info: MtInfo,
) -> Result<Mt, BuildError> {
    let Simplifier {
        pos,
        tets,
        mut creator,
        mut destroyer,
        source,
        raw_error,
        ..
    } = sim;
    let drain = raw_error.len() as u32;
    let nf = raw_error.len() + 1;
    for d in destroyer.iter_mut() {
        if *d == u32::MAX {
            *d = drain;
        }
    }
    // Errors grow along the DAG: a fragment's error is at least that of every fragment that
    // created part of its floor. Execution order is a topological order (a collapse
    // consumes only tets made before it), so one pass over the floors in that order does.
    let floors = crate::mt::csr::Csr::from_pairs(
        nf,
        (0..tets.len() as u32).map(|t| (destroyer[t as usize], t)),
    );
    let mut error = raw_error;
    error.push(f64::INFINITY);
    for f in 1..nf - 1 {
        let m = floors
            .row(f)
            .into_iter()
            .map(|t| error[creator[t as usize] as usize])
            .fold(error[f], f64::max);
        error[f] = m;
    }
    // Fragments renumbered along a Morton curve of their ceiling's centre (root first, drain
    // last): fragments near in space are near in memory, and so, through the pool order
    // below, are their arcs and tets, which is what incremental extraction and cuts walk.
    // Boxes of the ceilings (enough to place a fragment): the pool is still in creation
    // order, so each fragment's ceiling is one run of it.
    let runs: Vec<usize> = (0..=nf as u32)
        .into_par_iter()
        .map(|f| creator.partition_point(|&c| c < f))
        .collect();
    let boxes: Vec<crate::geom::Aabb> = (0..nf)
        .into_par_iter()
        .map(|f| {
            crate::geom::Aabb::from_points(
                tets[runs[f]..runs[f + 1]]
                    .iter()
                    .flatten()
                    .filter(|v| **v != GHOST)
                    .map(|v| &pos[v.idx()]),
            )
        })
        .collect();
    let scale = crate::geom::Aabb::from_points(&pos);
    let code = |f: usize| -> u64 {
        if f == 0 {
            0
        } else if f == nf - 1 || boxes[f].is_empty() {
            u64::MAX
        } else {
            morton(boxes[f].center(), &scale)
        }
    };
    let mut by_space: Vec<u32> = (0..nf as u32).collect();
    by_space.sort_unstable_by_key(|&f| (f as usize == nf - 1, code(f as usize), f));
    let mut new_id = vec![0u32; nf];
    for (k, &f) in by_space.iter().enumerate() {
        new_id[f as usize] = k as u32;
    }
    for c in creator.iter_mut().chain(destroyer.iter_mut()) {
        *c = new_id[*c as usize];
    }
    let error: Vec<f64> = by_space.iter().map(|&f| error[f as usize]).collect();
    // The pool by (creator, destroyer, creation): each fragment's ceiling is one run of the
    // creation order, so the runs in the new fragment order are already by creator; each
    // run is then sorted by destroyer (a sort of the whole pool cost a third of `freeze`).
    let mut order: Vec<u32> = Vec::with_capacity(tets.len());
    for &f in &by_space {
        order.extend(runs[f as usize] as u32..runs[f as usize + 1] as u32);
    }
    let mut ceilings: Vec<&mut [u32]> = Vec::with_capacity(nf);
    let mut rest: &mut [u32] = &mut order;
    for &f in &by_space {
        let (run, tail) = rest.split_at_mut(runs[f as usize + 1] - runs[f as usize]);
        ceilings.push(run);
        rest = tail;
    }
    ceilings.into_par_iter().for_each(|run| {
        if run.len() > 1 << 16 {
            run.par_sort_unstable_by_key(|&t| (destroyer[t as usize], t));
        } else {
            run.sort_unstable_by_key(|&t| (destroyer[t as usize], t));
        }
    });
    let vertex_of = &renumbering.vertex_of;
    let new_tets: Vec<Tet> = order
        .par_iter()
        .map(|&t| {
            tets[t as usize].map(|v| {
                if v == GHOST {
                    v
                } else {
                    VertexId(vertex_of[v.idx()])
                }
            })
        })
        .collect();
    let mut arc_start = vec![0u32];
    let mut arc_creator = Vec::new();
    let mut arc_destroyer = Vec::new();
    let mut prev: Option<(u32, u32)> = None;
    for (i, &t) in order.iter().enumerate() {
        let key = (creator[t as usize], destroyer[t as usize]);
        if prev != Some(key) {
            if prev.is_some() {
                arc_start.push(i as u32);
            }
            arc_creator.push(FragmentId(key.0));
            arc_destroyer.push(FragmentId(key.1));
            prev = Some(key);
        }
    }
    arc_start.push(order.len() as u32);
    let mut kind = vec![FragmentKind::Collapse; nf];
    kind[0] = FragmentKind::Root;
    kind[nf - 1] = FragmentKind::Drain;
    // Cell data: each tet inherits the row of the input tet it descends from (ghosts, which
    // descend from none and are never extracted, get zeros: a NaN would make the MT
    // unequal to itself).
    let n_input = mesh.nb_tets();
    let mut cell_data = Attributes::new();
    if !mesh.cell_data.is_empty() {
        let mut base = vec![u32::MAX; tets.len()];
        for t in 0..tets.len() {
            base[t] = if t < n_input {
                renumbering.tet_of[t]
            } else if source[t] != u32::MAX {
                base[source[t] as usize]
            } else {
                u32::MAX
            };
        }
        for col in mesh.cell_data.iter() {
            let k = col.components;
            let mut values = Vec::with_capacity(order.len() * k);
            for &t in &order {
                match base[t as usize] {
                    u32::MAX => values.extend(std::iter::repeat_n(0.0, k)),
                    b => values.extend_from_slice(col.get(b as usize)),
                }
            }
            if let Some(a) = Attribute::new(col.name.clone(), k, values) {
                cell_data.insert(a);
            }
        }
    }
    let positions: Vec<DVec3> = mesh.positions().to_vec();
    Mt::assemble(MtParts {
        positions,
        point_data: mesh.point_data.clone(),
        tets: new_tets,
        cell_data,
        arc_start,
        arc_creator,
        arc_destroyer,
        kind,
        error,
        info,
        known_boxes: None,
        keep_room: false,
        kept_arcs: None,
        vertex_ids_checked: false,
    })
    .map_err(BuildError::Internal)
}
