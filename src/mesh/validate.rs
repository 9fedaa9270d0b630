//! `TetMesh::validate`: every invariant of DESIGN.md §5 for a single mesh, each violation
//! class reported with its count and first examples, so a failing test or a rejected file
//! says what is wrong and where.

use super::adjacency::{face_vertices, match_faces};
use super::{TetId, TetMesh, VertexId};
use crate::geom::{Aabb, DVec3, Sign, orient2d, orient3d};
use rayon::prelude::*;
use std::fmt;

/// How many examples each violation class keeps.
const EXAMPLES: usize = 5;

/// How a report numbers vertices and tets in its examples: from 0, as the mesh does
/// ([`Numbering::ZERO`]), or as the file the mesh was read from numbers its nodes and
/// tetrahedra (TetGen's files from 0 or 1, medit's from 1), so that a rejected file's
/// message names the numbers its author sees.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Numbering {
    /// The number of vertex 0.
    pub first_vertex: u64,
    /// The number of tet 0.
    pub first_tet: u64,
}

impl Numbering {
    /// The mesh's own ids.
    pub const ZERO: Numbering = Numbering {
        first_vertex: 0,
        first_tet: 0,
    };

    fn vertex(self, v: impl Into<u64>) -> u64 {
        v.into() + self.first_vertex
    }

    fn tet(self, t: usize) -> u64 {
        t as u64 + self.first_tet
    }

    /// Vertices as "(a, b, c)".
    fn vertex_list(self, vs: &[VertexId]) -> String {
        let ids: Vec<String> = vs.iter().map(|v| self.vertex(v.0).to_string()).collect();
        format!("({})", ids.join(", "))
    }
}

/// A class of invariant violation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ViolationKind {
    NonFiniteCoordinate,
    IndexOutOfRange,
    RepeatedVertex,
    NonPositiveOrientation,
    FaceOverShared,
    FaceSameOrientation,
    NonManifoldBoundary,
    HangingVertex,
    AttributeLength,
    UnusedVertex,
    /// A vertex of one lip of a crack inside a face of the other lip: a later cut
    /// subdivided the lips differently. No T-junction (the lips are apart), so only a
    /// warning.
    LipsApart,
}

/// Whether a violation makes the mesh invalid or is only worth knowing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
}

impl ViolationKind {
    pub fn severity(self) -> Severity {
        match self {
            ViolationKind::UnusedVertex | ViolationKind::LipsApart => Severity::Warning,
            _ => Severity::Error,
        }
    }

    /// What one instance is, for messages ("3 tets with non-positive orientation").
    fn describe(self) -> &'static str {
        match self {
            ViolationKind::NonFiniteCoordinate => "vertices with a NaN or infinite coordinate",
            ViolationKind::IndexOutOfRange => "tets with a vertex index out of range",
            ViolationKind::RepeatedVertex => "tets using a vertex more than once",
            ViolationKind::NonPositiveOrientation => {
                "tets with non-positive orientation (inverted or flat)"
            }
            ViolationKind::FaceOverShared => "faces shared by more than two tets",
            ViolationKind::FaceSameOrientation => {
                "faces shared by two tets with the same orientation (overlapping tets)"
            }
            ViolationKind::NonManifoldBoundary => "non-manifold boundary edges or vertices",
            ViolationKind::HangingVertex => {
                "hanging vertices (lying inside a boundary face or edge they are not part of)"
            }
            ViolationKind::AttributeLength => "attribute columns of the wrong length",
            ViolationKind::UnusedVertex => "unused vertices (used by no tet)",
            ViolationKind::LipsApart => {
                "crack lip vertices inside a face of the opposite lip (lips subdivided \
                 differently)"
            }
        }
    }
}

/// One violation class: how many instances, and the first few.
#[derive(Clone, Debug, PartialEq)]
pub struct Violation {
    pub kind: ViolationKind,
    pub count: usize,
    pub examples: Vec<String>,
}

/// Everything `validate` found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ValidationReport {
    pub violations: Vec<Violation>,
}

impl ValidationReport {
    fn add(&mut self, kind: ViolationKind, example: impl FnOnce() -> String) {
        match self.violations.iter_mut().find(|v| v.kind == kind) {
            Some(v) => {
                v.count += 1;
                if v.examples.len() < EXAMPLES {
                    v.examples.push(example());
                }
            }
            None => self.violations.push(Violation {
                kind,
                count: 1,
                examples: vec![example()],
            }),
        }
    }

    /// No error-class violation (warnings allowed).
    pub fn is_valid(&self) -> bool {
        self.violations
            .iter()
            .all(|v| v.kind.severity() == Severity::Warning)
    }

    /// Number of instances of `kind`.
    pub fn count(&self, kind: ViolationKind) -> usize {
        self.violations
            .iter()
            .find(|v| v.kind == kind)
            .map_or(0, |v| v.count)
    }

    /// One human-readable line per violation class of the given severity.
    pub fn lines(&self, severity: Severity) -> Vec<String> {
        self.violations
            .iter()
            .filter(|v| v.kind.severity() == severity)
            .map(|v| {
                format!(
                    "{} {} (first: {})",
                    v.count,
                    v.kind.describe(),
                    v.examples.join("; ")
                )
            })
            .collect()
    }
}

impl fmt::Display for ValidationReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let errors = self.lines(Severity::Error);
        if errors.is_empty() {
            return write!(f, "valid mesh");
        }
        write!(f, "invalid mesh: {}", errors.join("; "))
    }
}

pub(super) fn validate(mesh: &TetMesh) -> ValidationReport {
    validate_with(mesh, true, Numbering::ZERO)
}

/// [`validate`], with the per-tet checks (repeated vertices, orientation) made only when
/// `check_tets` (`TetMesh::from_arrays` has just made them itself, tet by tet), and the
/// examples numbered by `num`.
pub(super) fn validate_with(mesh: &TetMesh, check_tets: bool, num: Numbering) -> ValidationReport {
    let mut r = ValidationReport::default();
    let pos = mesh.positions();
    let tets = mesh.tets();
    for (i, p) in pos.iter().enumerate() {
        if !p.is_finite() {
            r.add(ViolationKind::NonFiniteCoordinate, || {
                format!("vertex {}", num.vertex(i as u64))
            });
        }
    }
    let n = pos.len();
    let mut in_range = true;
    for (t, tet) in tets.iter().enumerate() {
        if let Some(v) = tet.iter().find(|v| v.idx() >= n) {
            in_range = false;
            r.add(ViolationKind::IndexOutOfRange, || {
                format!("tet {} uses vertex {} of {n}", num.tet(t), num.vertex(v.0))
            });
        }
    }
    check_attributes(mesh, &mut r);
    if !in_range {
        // Topology cannot be examined without positions for every index.
        return r;
    }
    if check_tets {
        check_tets_alone(mesh, num, &mut r);
    }
    let mut used = vec![false; n];
    for tet in tets {
        for v in tet {
            used[v.idx()] = true;
        }
    }
    for (v, u) in used.iter().enumerate() {
        if !u {
            r.add(ViolationKind::UnusedVertex, || {
                format!("vertex {}", num.vertex(v as u64))
            });
        }
    }
    let faces = match_faces(n, tets, false);
    for &(t, f, owners) in &faces.overshared {
        r.add(ViolationKind::FaceOverShared, || {
            let fv = face_vertices(&mesh.tet(t), f as usize);
            let t = num.tet(t.idx());
            format!("face {} of tet {t} has {owners} tets", num.vertex_list(&fv))
        });
    }
    for &(t, f, u) in &faces.same_orientation {
        r.add(ViolationKind::FaceSameOrientation, || {
            let fv = face_vertices(&mesh.tet(t), f as usize);
            let (t, u) = (num.tet(t.idx()), num.tet(u.idx()));
            format!("face {} of tet {t} and tet {u}", num.vertex_list(&fv))
        });
    }
    let boundary: Vec<[VertexId; 3]> = faces
        .boundary
        .iter()
        .map(|b| face_vertices(&mesh.tet(b.tet), b.face as usize))
        .collect();
    check_manifold(n, &boundary, num, &mut r);
    check_hanging(pos, &boundary, num, &mut r);
    r
}

/// Repeated vertices and orientation, tet by tet (in parallel; violations are rare and
/// reported in tet order).
fn check_tets_alone(mesh: &TetMesh, num: Numbering, r: &mut ValidationReport) {
    let pos = mesh.positions();
    let bad: Vec<(usize, ViolationKind)> = mesh
        .tets()
        .par_iter()
        .enumerate()
        .filter_map(|(t, tet)| {
            if (0..4).any(|a| (a + 1..4).any(|b| tet[a] == tet[b])) {
                return Some((t, ViolationKind::RepeatedVertex));
            }
            let [a, b, c, d] = tet.map(|v| pos[v.idx()]);
            (orient3d(a, b, c, d) != Sign::Positive)
                .then_some((t, ViolationKind::NonPositiveOrientation))
        })
        .collect();
    for (t, kind) in bad {
        r.add(kind, || match kind {
            ViolationKind::RepeatedVertex => {
                format!("tet {} {}", num.tet(t), num.vertex_list(&mesh.tets()[t]))
            }
            _ => format!(
                "tet {} (volume {:e})",
                num.tet(t),
                mesh.tet_volume(TetId::from_usize(t))
            ),
        });
    }
}

fn check_attributes(mesh: &TetMesh, r: &mut ValidationReport) {
    for (kind, attrs, n) in [
        ("point", &mesh.point_data, mesh.nb_vertices()),
        ("cell", &mesh.cell_data, mesh.nb_tets()),
    ] {
        for a in attrs.iter().filter(|a| a.len() != n) {
            r.add(ViolationKind::AttributeLength, || {
                format!(
                    "{kind} data '{}' has {} rows for {n} elements",
                    a.name,
                    a.len()
                )
            });
        }
    }
}

/// Every boundary edge must bound exactly two boundary faces, traversed in opposite
/// directions, and the boundary faces around each boundary vertex must form one fan.
/// Both are read from the corners of the boundary faces grouped by vertex (a counting
/// sort): at vertex `a`, a corner's face goes `a -> next -> prev`, so edge `(a, w)` bounds
/// one face per corner with `next == w` (traversing it away from `a`) or `prev == w`
/// (towards `a`).
/// Corners around a vertex up to which [`check_manifold`] scans them rather than sorting.
const FEW_CORNERS: usize = 48;

fn check_manifold(
    n_vertices: usize,
    boundary: &[[VertexId; 3]],
    num: Numbering,
    r: &mut ValidationReport,
) {
    let mut start = vec![0u32; n_vertices + 1];
    for v in boundary.iter().flatten() {
        start[v.idx() + 1] += 1;
    }
    for i in 0..n_vertices {
        start[i + 1] += start[i];
    }
    // (next, prev) of each corner, grouped by corner vertex.
    let mut corners = vec![(VertexId::INVALID, VertexId::INVALID); 3 * boundary.len()];
    let mut fill = start.clone();
    for f in boundary {
        for k in 0..3 {
            let slot = &mut fill[f[k].idx()];
            corners[*slot as usize] = (f[(k + 1) % 3], f[(k + 2) % 3]);
            *slot += 1;
        }
    }
    let around = |a: usize| &corners[start[a] as usize..start[a + 1] as usize];
    // (low, high, faces on the edge, traversals away from low). A vertex with few corners
    // (nearly all) scans them for each of its edges; one with many (the apex of a fan of
    // 50,000 boundary faces took 5 s so) has its corners' far ends sorted, so that the
    // faces on each edge are counted in k log k for k corners.
    let mut bad_edges: Vec<(VertexId, VertexId, usize, usize)> = Vec::new();
    let (mut nexts, mut prevs, mut far) = (Vec::new(), Vec::new(), Vec::new());
    let count = |sorted: &[VertexId], w: VertexId| {
        sorted.partition_point(|&x| x <= w) - sorted.partition_point(|&x| x < w)
    };
    for a in 0..n_vertices {
        let cs = around(a);
        let va = VertexId::from_usize(a);
        if cs.len() <= FEW_CORNERS {
            for (i, &(next, prev)) in cs.iter().enumerate() {
                for (k, w) in [next, prev].into_iter().enumerate() {
                    // Each edge once: from its lower end, at the first corner naming it.
                    let named_before =
                        cs[..i].iter().any(|c| c.0 == w || c.1 == w) || (k == 1 && next == w);
                    if w <= va || named_before {
                        continue;
                    }
                    let away = cs.iter().filter(|c| c.0 == w).count();
                    let towards = cs.iter().filter(|c| c.1 == w).count();
                    if away != 1 || towards != 1 {
                        bad_edges.push((va, w, away + towards, away));
                    }
                }
            }
            continue;
        }
        nexts.clear();
        nexts.extend(cs.iter().map(|c| c.0));
        nexts.sort_unstable();
        prevs.clear();
        prevs.extend(cs.iter().map(|c| c.1));
        prevs.sort_unstable();
        // Each edge once: from its lower end.
        far.clear();
        far.extend(nexts.iter().chain(&prevs).copied().filter(|&w| w > va));
        far.sort_unstable();
        far.dedup();
        for &w in &far {
            let (away, towards) = (count(&nexts, w), count(&prevs, w));
            if away != 1 || towards != 1 {
                bad_edges.push((va, w, away + towards, away));
            }
        }
    }
    bad_edges.sort_unstable();
    for &(lo, hi, faces, _) in &bad_edges {
        r.add(ViolationKind::NonManifoldBoundary, || {
            format!(
                "edge ({}, {}) bounds {faces} boundary faces{}",
                num.vertex(lo.0),
                num.vertex(hi.0),
                if faces == 2 {
                    " with the same direction"
                } else {
                    ""
                }
            )
        });
    }
    if !bad_edges.is_empty() {
        // Fans are only well defined once every edge is manifold.
        return;
    }
    let mut seen = Vec::new();
    // Per vertex with many corners, its corners by their `next` end: every edge being
    // manifold here, each far end is the `next` of exactly one corner, found by a binary
    // search instead of a scan.
    let mut by_next: Vec<(VertexId, u32)> = Vec::new();
    for a in 0..n_vertices {
        // The link of the vertex: edges next -> prev; count the cycles of that permutation.
        let run = around(a);
        seen.clear();
        seen.resize(run.len(), false);
        let many = run.len() > FEW_CORNERS;
        if many {
            by_next.clear();
            by_next.extend(run.iter().enumerate().map(|(i, l)| (l.0, i as u32)));
            by_next.sort_unstable();
        }
        let corner_after = |next: VertexId| {
            if many {
                let j = by_next.partition_point(|&(w, _)| w < next);
                by_next
                    .get(j)
                    .filter(|&&(w, _)| w == next)
                    .map(|&(_, k)| k as usize)
            } else {
                run.iter().position(|l| l.0 == next)
            }
        };
        let mut cycles = 0;
        for s in 0..run.len() {
            if seen[s] {
                continue;
            }
            cycles += 1;
            let mut i = s;
            while !seen[i] {
                seen[i] = true;
                match corner_after(run[i].1) {
                    Some(j) => i = j,
                    None => break,
                }
            }
        }
        if cycles > 1 {
            r.add(ViolationKind::NonManifoldBoundary, || {
                let a = num.vertex(a as u64);
                format!("vertex {a} joins {cycles} separate boundary fans")
            });
        }
    }
}

/// Whether two vertices hold one point up to the rounding of the points a cut makes (each
/// coordinate within 4 ulps): a vertex there is at a face's corner, not inside the face.
/// One point of a crack made on both lips of an earlier crack, from faces of the two lips
/// triangulated differently (an MT's levels), can round 1 ulp apart on each (a Kuhn-grid
/// run, tests/mtcut_cut.rs), as two coincident copies would not.
fn same_point(a: DVec3, b: DVec3) -> bool {
    let ulps = 4.0 * f64::EPSILON;
    (a - b).abs().cmple(a.abs().max(b.abs()) * ulps).all()
}

/// A boundary vertex lying strictly inside a boundary face or edge it does not belong to is
/// a T-junction: the mesh is not conforming there (see [`boundary_hits`]).
fn check_hanging(
    pos: &[DVec3],
    boundary: &[[VertexId; 3]],
    num: Numbering,
    r: &mut ValidationReport,
) {
    let mut on_boundary = vec![false; pos.len()];
    for v in boundary.iter().flatten() {
        on_boundary[v.idx()] = true;
    }
    let points = (0..pos.len())
        .filter(|&v| on_boundary[v])
        .map(VertexId::from_usize)
        .collect();
    let BoundaryHits {
        mut lips,
        mut hanging,
    } = boundary_hits(pos, boundary, points);
    lips.sort_unstable();
    lips.dedup_by_key(|h| h.0);
    for (v, fi) in lips {
        r.add(ViolationKind::LipsApart, || {
            format!(
                "vertex {} lies on face {} of the other lip",
                num.vertex(v.0),
                num.vertex_list(&boundary[fi as usize])
            )
        });
    }
    // One report per vertex, naming the first face it lies on.
    hanging.sort_unstable();
    hanging.dedup_by_key(|h| h.0);
    for (v, fi) in hanging {
        r.add(ViolationKind::HangingVertex, || {
            format!(
                "vertex {} lies on boundary face {}",
                num.vertex(v.0),
                num.vertex_list(&boundary[fi as usize])
            )
        });
    }
}

/// The vertices of [`boundary_hits`]'s points lying strictly inside a boundary face they
/// are not part of, each with the index of such a face: on the other lip of a crack, or
/// hanging (a T-junction).
pub(crate) struct BoundaryHits {
    pub lips: Vec<(VertexId, u32)>,
    pub hanging: Vec<(VertexId, u32)>,
}

/// Which of `points` (boundary vertices) lie strictly inside a face of `boundary` that they
/// are not part of. Exact predicates decide; a k-d tree over the points finds those in each
/// face's box (in parallel over faces) in time that follows the vertices found, however
/// unevenly they are spread — a cut's crack packs many small faces into a small region,
/// where a uniform grid's cells overflow. [`TetMesh::validate`] asks it of a whole mesh's
/// boundary; the MT cut of the faces it wrote on its finest and coarsest meshes and the
/// vertices it made (whose boundary faces are all among those).
pub(crate) fn boundary_hits(
    pos: &[DVec3],
    boundary: &[[VertexId; 3]],
    points: Vec<VertexId>,
) -> BoundaryHits {
    if boundary.is_empty() || points.is_empty() {
        return BoundaryHits {
            lips: Vec::new(),
            hanging: Vec::new(),
        };
    }
    let tree = PointTree::new(points.into_iter().map(|v| (pos[v.idx()], v)).collect());
    // (vertex, face) for every vertex lying on a face it is not part of.
    let on_face = |(fi, f): (usize, &[VertexId; 3])| {
        let [a, b, q] = f.map(|w| pos[w.idx()]);
        let mut found = Vec::new();
        // A face without area in its projection holds no point strictly.
        let Some(projected) = ProjectedTriangle::new(a, b, q) else {
            return found;
        };
        let fb = Aabb::from_points([a, b, q].iter());
        tree.visit_in(&fb, |p, v| {
            // Cheapest exact tests first. On flat CAD boundaries many candidates are
            // coplanar with the face, where orient3d is exactly zero and takes its slow
            // exact path; the projected-triangle test (a point in the triangle projects
            // into its projection) rejects them before.
            if !f.contains(&v)
                && ![a, b, q].iter().any(|&c| same_point(p, c))
                && projected.contains(p)
                && orient3d(a, b, q, p) == Sign::Zero
            {
                found.push((v, fi as u32));
            }
        });
        found
    };
    // The faces one cut makes (84 on average over the random scalpel paths of
    // tests/cut_scalpel.rs, a few thousand at most) are tested on this thread: with the
    // pool, the plain-mesh scalpel's steps took 5-16 % longer.
    let hits: Vec<(VertexId, u32)> = if boundary.len() < PARALLEL_FACES {
        boundary.iter().enumerate().flat_map(on_face).collect()
    } else {
        boundary
            .par_iter()
            .enumerate()
            .flat_map_iter(on_face)
            .collect()
    };
    // The two lips of a crack lie on each other but are not joined: a later cut may
    // subdivide one lip and not the other (a crack tip on a lip face, where the cut ends
    // against the earlier crack), leaving a vertex of one lip inside a face of the other.
    // That is no T-junction, only worth knowing. A vertex is on the opposite lip of face
    // `f` when a boundary face at it holds a *twin* of a corner of `f` (another vertex at
    // that corner's position: the copies a cut makes); a vertex hanging in a face of its
    // own surface is surrounded by that face's corners themselves.
    let mut apart = vec![false; hits.len()];
    if !hits.is_empty() {
        let mut at: Vec<(VertexId, u32)> = Vec::new();
        let candidates: std::collections::HashSet<VertexId> = hits.iter().map(|h| h.0).collect();
        for (fi, f) in boundary.iter().enumerate() {
            for &v in f.iter().filter(|v| candidates.contains(v)) {
                at.push((v, fi as u32));
            }
        }
        at.sort_unstable();
        let faces_at = |v: VertexId| {
            let start = at.partition_point(|x| x.0 < v);
            at[start..]
                .iter()
                .take_while(move |x| x.0 == v)
                .map(|x| &boundary[x.1 as usize])
        };
        for (h, &(v, fi)) in apart.iter_mut().zip(&hits) {
            let f = &boundary[fi as usize];
            let twin = |w: VertexId| f.iter().any(|&x| x != w && pos[x.idx()] == pos[w.idx()]);
            *h = faces_at(v).any(|g| g.iter().any(|&w| w != v && twin(w)));
        }
    }
    let (mut lips, mut hanging) = (Vec::new(), Vec::new());
    for (h, apart) in hits.into_iter().zip(apart) {
        if apart { lips.push(h) } else { hanging.push(h) }
    }
    BoundaryHits { lips, hanging }
}

/// Boundary faces from which [`boundary_hits`] tests them on both cores.
const PARALLEL_FACES: usize = 4096;

/// A static k-d tree over points: halved at the median of the longest side of each
/// node's box down to leaves of at most [`PointTree::LEAF`] points, nodes numbered as in a
/// heap (the children of `n` are `2n + 1` and `2n + 2`).
struct PointTree {
    points: Vec<(DVec3, VertexId)>,
    boxes: Vec<Aabb>,
}

impl PointTree {
    const LEAF: usize = 8;

    fn new(mut points: Vec<(DVec3, VertexId)>) -> PointTree {
        let leaves = points.len().div_ceil(Self::LEAF).max(1);
        let mut boxes = vec![Aabb::EMPTY; 2 * leaves.next_power_of_two()];
        Self::build(&mut points, 0, &mut boxes);
        PointTree { points, boxes }
    }

    fn build(points: &mut [(DVec3, VertexId)], node: usize, boxes: &mut [Aabb]) {
        let b = Aabb::from_points(points.iter().map(|(p, _)| p));
        boxes[node] = b;
        if points.len() <= Self::LEAF {
            return;
        }
        let e = b.extent();
        let axis = if e.x >= e.y && e.x >= e.z {
            0
        } else if e.y >= e.z {
            1
        } else {
            2
        };
        let mid = points.len() / 2;
        points.select_nth_unstable_by(mid, |p, q| p.0[axis].total_cmp(&q.0[axis]));
        let (left, right) = points.split_at_mut(mid);
        Self::build(left, 2 * node + 1, boxes);
        Self::build(right, 2 * node + 2, boxes);
    }

    /// Calls `f` on every point in the closed box `b`.
    fn visit_in(&self, b: &Aabb, mut f: impl FnMut(DVec3, VertexId)) {
        // Depth-first with a fixed stack: a node's size halves at each level, so the depth
        // is at most 64 and a stack entry waits per level.
        let mut stack = [(0usize, 0usize, 0usize); 64];
        stack[0] = (0, 0, self.points.len());
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let (node, lo, hi) = stack[top];
            if !self.boxes[node].intersects(b) {
                continue;
            }
            if hi - lo <= Self::LEAF {
                for &(p, v) in &self.points[lo..hi] {
                    if b.contains(p) {
                        f(p, v);
                    }
                }
            } else {
                let mid = lo + (hi - lo) / 2;
                stack[top] = (2 * node + 2, mid, hi);
                stack[top + 1] = (2 * node + 1, lo, mid);
                top += 2;
            }
        }
    }
}

/// A triangle projected onto the coordinate plane it projects to without collapsing, for
/// exact point-in-triangle tests of points coplanar with it.
struct ProjectedTriangle {
    axes: (usize, usize),
    corners: [[f64; 2]; 3],
    /// The orientation of the projected triangle (never zero).
    sign: Sign,
}

impl ProjectedTriangle {
    /// None when the projection is degenerate (a triangle without area).
    fn new(a: DVec3, b: DVec3, c: DVec3) -> Option<ProjectedTriangle> {
        let n = (b - a).cross(c - a).abs();
        let axes = if n.x >= n.y && n.x >= n.z {
            (1, 2)
        } else if n.y >= n.z {
            (2, 0)
        } else {
            (0, 1)
        };
        let corners = [a, b, c].map(|q| [q[axes.0], q[axes.1]]);
        let sign = orient2d(corners[0], corners[1], corners[2]);
        (sign != Sign::Zero).then_some(ProjectedTriangle {
            axes,
            corners,
            sign,
        })
    }

    /// Whether `p`, coplanar with the triangle, lies in the closed triangle. Exact: it does
    /// unless one of the three sub-triangles at `p` has the opposite orientation (their
    /// determinants add up to the triangle's, so they cannot all be opposite); the first
    /// one found decides, which for most points is the first or second.
    fn contains(&self, p: DVec3) -> bool {
        let q = [p[self.axes.0], p[self.axes.1]];
        let [a, b, c] = self.corners;
        let opposite = self.sign.flip();
        orient2d(a, b, q) != opposite
            && orient2d(b, c, q) != opposite
            && orient2d(c, a, q) != opposite
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    fn cube_corner_mesh() -> (Vec<DVec3>, Vec<[u32; 4]>) {
        let p = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            DVec3::new(1.0, 1.0, 1.0),
        ];
        // The second tet is given negatively oriented.
        (p, vec![[0, 1, 2, 3], [1, 2, 4, 3]])
    }

    #[test]
    fn valid_mesh_reports_nothing() {
        let (p, t) = cube_corner_mesh();
        let (m, rep) = TetMesh::from_arrays(p, t).unwrap();
        assert_eq!(rep.reoriented_tets, 1);
        let v = m.validate();
        assert!(v.is_valid(), "{v}");
        assert!(v.violations.is_empty(), "{v:?}");
    }

    #[test]
    fn hanging_vertex_is_found() {
        // Tet A = (0,1,2,3); on its face (1,2,3) sit two tets splitting that face at the
        // midpoint m of edge (1,2): a T-junction.
        let mut p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        p.push(DVec3::new(1.0, 1.0, 1.0)); // 4: apex beyond face (1,2,3)
        p.push(DVec3::new(0.5, 0.5, 0.0)); // 5: midpoint of edge (1,2)
        let tets = vec![[0, 1, 2, 3], [1, 4, 5, 3], [5, 4, 2, 3]];
        let err = TetMesh::from_arrays(p, tets).unwrap_err();
        match err {
            crate::mesh::MeshError::Invalid(r) => {
                assert!(r.count(ViolationKind::HangingVertex) >= 1, "{r}")
            }
            e => panic!("unexpected {e}"),
        }
    }

    #[test]
    fn lips_of_a_crack_subdivided_differently_are_only_a_warning() {
        // The T-junction above, the upper tets holding copies of vertices 1, 2 and 3 (6, 7,
        // 8): a crack along face (1, 2, 3), its upper lip split at m, the lower not.
        let mut p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        p.push(DVec3::new(1.0, 1.0, 1.0));
        p.push(DVec3::new(0.5, 0.5, 0.0));
        p.extend([DVec3::X, DVec3::Y, DVec3::Z]);
        let tets = vec![[0, 1, 2, 3], [6, 4, 5, 8], [5, 4, 7, 8]];
        let (m, _) = TetMesh::from_arrays(p, tets).expect("valid: the lips are apart");
        let r = m.validate();
        assert!(r.is_valid(), "{r}");
        assert_eq!(r.count(ViolationKind::LipsApart), 1, "{r:?}");
        assert_eq!(r.count(ViolationKind::HangingVertex), 0, "{r:?}");
    }

    /// Points coplanar with a triangle, at exactly representable barycentric coordinates
    /// (s, t) on small integer corners: in the closed triangle exactly when s ≥ 0, t ≥ 0
    /// and s + t ≤ 1, edges and corners included.
    #[test]
    fn projected_triangle_contains_exactly_its_closed_points() {
        let mut rng = Rng(11);
        let mut int = |n: i64| (rng.below(2 * n as u64 + 1) as i64 - n) as f64;
        let mut checked = [0usize; 2];
        for _ in 0..2000 {
            let [a, b, c] = [0; 3].map(|_| DVec3::new(int(8), int(8), int(8)));
            let Some(tri) = ProjectedTriangle::new(a, b, c) else {
                assert_eq!((b - a).cross(c - a), DVec3::ZERO, "{a} {b} {c}");
                continue;
            };
            for _ in 0..20 {
                let (s, t) = (int(12) / 8.0, int(12) / 8.0);
                let p = a + (b - a) * s + (c - a) * t;
                let inside = s >= 0.0 && t >= 0.0 && s + t <= 1.0;
                assert_eq!(tri.contains(p), inside, "{a} {b} {c}: s {s} t {t}");
                checked[usize::from(inside)] += 1;
            }
        }
        assert!(checked.iter().all(|&n| n > 1000), "{checked:?}");
    }

    /// The k-d tree finds exactly the points in a box, ties on the box's faces included,
    /// on clustered points with repeated coordinates.
    #[test]
    fn point_tree_finds_the_points_in_a_box() {
        let mut rng = Rng(3);
        let mut unit = || rng.below(17) as f64 / 16.0;
        let points: Vec<(DVec3, VertexId)> = (0..500)
            .map(|i| {
                let scale = if i % 3 == 0 { 0.05 } else { 1.0 };
                let p = DVec3::new(unit(), unit(), unit()) * scale;
                (p, VertexId::from_usize(i))
            })
            .collect();
        let tree = PointTree::new(points.clone());
        for _ in 0..300 {
            let (a, b) = (
                DVec3::new(unit(), unit(), unit()),
                DVec3::new(unit(), unit(), unit()),
            );
            let b = Aabb::from_points([a * 0.3, b * 0.3].iter());
            let mut got = Vec::new();
            tree.visit_in(&b, |_, v| got.push(v));
            got.sort_unstable();
            let expected: Vec<VertexId> = points
                .iter()
                .filter(|(p, _)| b.contains(*p))
                .map(|&(_, v)| v)
                .collect();
            assert_eq!(got, expected);
        }
    }

    #[test]
    fn pinched_vertex_is_non_manifold() {
        // Two tets meeting at a single vertex.
        let p = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            -DVec3::X,
            -DVec3::Y,
            -DVec3::Z,
        ];
        let err = TetMesh::from_arrays(p, vec![[0, 1, 2, 3], [0, 4, 5, 6]]).unwrap_err();
        assert!(err.to_string().contains("boundary fans"), "{err}");
    }

    /// Cones of `n` tets around the axis from `apex` to a point above it: the apex and
    /// that point have `n` boundary corners each, many more than [`FEW_CORNERS`].
    fn cones(n: usize, apexes: &[f64]) -> (Vec<DVec3>, Vec<[u32; 4]>) {
        let (mut p, mut t) = (Vec::new(), Vec::new());
        for (c, &z) in apexes.iter().enumerate() {
            let s = if c == 0 { 1.0 } else { -1.0 };
            let base = p.len() as u32;
            p.push(DVec3::new(0.0, 0.0, z));
            p.push(DVec3::new(0.0, 0.0, z + s));
            for i in 0..n {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                p.push(DVec3::new(a.cos(), a.sin(), z + 0.5 * s));
            }
            let ring = |i: usize| base + 2 + (i % n) as u32;
            t.extend((0..n).map(|i| [base, base + 1, ring(i), ring(i + 1)]));
        }
        (p, t)
    }

    /// Vertices with many corners take the sorted path (a fan of 50,000 boundary faces
    /// took 5 s with the scan): the same answers as with few.
    #[test]
    fn vertices_with_many_corners_are_checked_alike() {
        for n in [FEW_CORNERS / 2, 10 * FEW_CORNERS] {
            let (p, t) = cones(n, &[0.0]);
            let (m, _) = TetMesh::from_arrays(p, t).unwrap();
            assert!(m.validate().is_valid(), "{n}");
            // Two cones apex to apex (the second one's vertices renumbered onto the first
            // apex): the apex joins two fans.
            let (p, mut t) = cones(n, &[0.0, 0.0]);
            let second = n as u32 + 2;
            for tet in t.iter_mut().skip(n) {
                tet.iter_mut()
                    .filter(|v| **v == second)
                    .for_each(|v| *v = 0);
            }
            let e = TetMesh::from_arrays(p, t).unwrap_err().to_string();
            assert!(
                e.contains("vertex 0 joins 2 separate boundary fans"),
                "{n}: {e}"
            );
            // A tet touching the cone along the edge from the apex to a ring vertex only:
            // that edge bounds four boundary faces.
            let (mut p, mut t) = cones(n, &[0.0]);
            p.push(DVec3::new(0.5, -1.0, -1.0));
            p.push(DVec3::new(1.5, -2.0, 0.3));
            let k = p.len() as u32;
            t.push([0, 2, k - 2, k - 1]);
            let e = TetMesh::from_arrays(p, t).unwrap_err().to_string();
            assert!(
                e.contains("edge (0, 2) bounds 4 boundary faces"),
                "{n}: {e}"
            );
        }
    }

    #[test]
    fn unused_vertex_is_a_warning() {
        let (mut p, t) = cube_corner_mesh();
        p.push(DVec3::splat(9.0));
        let (m, rep) = TetMesh::from_arrays(p, t).unwrap();
        assert_eq!(rep.unused_vertices, 1);
        let v = m.validate();
        assert!(v.is_valid());
        assert_eq!(v.count(ViolationKind::UnusedVertex), 1);
    }
}
