//! `TetMesh::validate`: every invariant of DESIGN.md §5 for a single mesh, each violation
//! class reported with its count and first examples, so a failing test or a rejected file
//! says what is wrong and where.

use super::adjacency::face_vertices;
use super::{FaceAdjacency, TetId, TetMesh, VertexId};
use crate::geom::{Aabb, DVec3, Sign, orient2d, orient3d};
use std::fmt;

/// How many examples each violation class keeps.
const EXAMPLES: usize = 5;

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
            ViolationKind::UnusedVertex => Severity::Warning,
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

/// Vertex ids as "(a, b, c)".
fn ids(v: &[VertexId]) -> String {
    let list: Vec<String> = v.iter().map(|x| x.to_string()).collect();
    format!("({})", list.join(", "))
}

pub(super) fn validate(mesh: &TetMesh) -> ValidationReport {
    let mut r = ValidationReport::default();
    let pos = mesh.positions();
    let tets = mesh.tets();
    for (i, p) in pos.iter().enumerate() {
        if !p.is_finite() {
            r.add(ViolationKind::NonFiniteCoordinate, || format!("vertex {i}"));
        }
    }
    let n = pos.len();
    let mut in_range = true;
    for (t, tet) in tets.iter().enumerate() {
        if let Some(v) = tet.iter().find(|v| v.idx() >= n) {
            in_range = false;
            r.add(ViolationKind::IndexOutOfRange, || {
                format!("tet {t} uses vertex {v} of {n}")
            });
        }
    }
    check_attributes(mesh, &mut r);
    if !in_range {
        // Topology cannot be examined without positions for every index.
        return r;
    }
    let mut used = vec![false; n];
    for (t, tet) in tets.iter().enumerate() {
        for v in tet {
            used[v.idx()] = true;
        }
        if (0..4).any(|a| (a + 1..4).any(|b| tet[a] == tet[b])) {
            r.add(ViolationKind::RepeatedVertex, || {
                format!("tet {t} {}", ids(tet))
            });
            continue;
        }
        let [a, b, c, d] = tet.map(|v| pos[v.idx()]);
        if orient3d(a, b, c, d) != Sign::Positive {
            r.add(ViolationKind::NonPositiveOrientation, || {
                format!(
                    "tet {t} (volume {:e})",
                    mesh.tet_volume(TetId::from_usize(t))
                )
            });
        }
    }
    for (v, u) in used.iter().enumerate() {
        if !u {
            r.add(ViolationKind::UnusedVertex, || format!("vertex {v}"));
        }
    }
    let adj = FaceAdjacency::new(mesh);
    for &(t, f, owners) in &adj.overshared {
        r.add(ViolationKind::FaceOverShared, || {
            let fv = face_vertices(&mesh.tet(t), f as usize);
            format!("face {} of tet {t} has {owners} tets", ids(&fv))
        });
    }
    for &(t, f, u) in &adj.same_orientation {
        r.add(ViolationKind::FaceSameOrientation, || {
            format!("face {f} of tet {t} and tet {u}")
        });
    }
    let boundary: Vec<[VertexId; 3]> = adj
        .boundary_faces()
        .iter()
        .map(|b| face_vertices(&mesh.tet(b.tet), b.face as usize))
        .collect();
    check_manifold(&boundary, &mut r);
    check_hanging(pos, &boundary, &mut r);
    r
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
fn check_manifold(boundary: &[[VertexId; 3]], r: &mut ValidationReport) {
    // (low, high, forward?) for each directed boundary edge.
    let mut edges: Vec<(VertexId, VertexId, bool)> = Vec::with_capacity(boundary.len() * 3);
    // (vertex, link edge) for each corner of each boundary face.
    let mut links: Vec<(VertexId, VertexId, VertexId)> = Vec::with_capacity(boundary.len() * 3);
    for f in boundary {
        for k in 0..3 {
            let (a, b, c) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
            edges.push((a.min(b), a.max(b), a < b));
            links.push((a, b, c));
        }
    }
    edges.sort_unstable();
    let mut bad_edges = false;
    for run in edges.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        if run.len() != 2 || run[0].2 == run[1].2 {
            bad_edges = true;
            r.add(ViolationKind::NonManifoldBoundary, || {
                format!(
                    "edge ({}, {}) bounds {} boundary faces{}",
                    run[0].0,
                    run[0].1,
                    run.len(),
                    if run.len() == 2 {
                        " with the same direction"
                    } else {
                        ""
                    }
                )
            });
        }
    }
    if bad_edges {
        // Fans are only well defined once every edge is manifold.
        return;
    }
    links.sort_unstable();
    for run in links.chunk_by(|x, y| x.0 == y.0) {
        // The link of the vertex: edges x -> y; count the cycles of that permutation.
        let mut seen = vec![false; run.len()];
        let mut cycles = 0;
        for s in 0..run.len() {
            if seen[s] {
                continue;
            }
            cycles += 1;
            let mut i = s;
            while !seen[i] {
                seen[i] = true;
                let next = run[i].2;
                match run.iter().position(|l| l.1 == next) {
                    Some(j) => i = j,
                    None => break,
                }
            }
        }
        if cycles > 1 {
            r.add(ViolationKind::NonManifoldBoundary, || {
                format!("vertex {} joins {cycles} separate boundary fans", run[0].0)
            });
        }
    }
}

/// A boundary vertex lying strictly inside a boundary face or edge it does not belong to is
/// a T-junction: the mesh is not conforming there. Exact predicates decide; a uniform grid
/// over the boundary faces keeps it linear.
fn check_hanging(pos: &[DVec3], boundary: &[[VertexId; 3]], r: &mut ValidationReport) {
    if boundary.is_empty() {
        return;
    }
    let bbox = Aabb::from_points(boundary.iter().flatten().map(|v| &pos[v.idx()]));
    let total_len: f64 = boundary
        .iter()
        .map(|f| (pos[f[0].idx()] - pos[f[1].idx()]).length())
        .sum();
    let cell = (total_len / boundary.len() as f64).max(bbox.diagonal() / 1024.0);
    if cell.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return;
    }
    let dims = ((bbox.extent() / cell).floor().as_uvec3() + 1).min(glam::UVec3::splat(1024));
    let index =
        |p: DVec3| -> glam::UVec3 { ((p - bbox.min) / cell).floor().as_uvec3().min(dims - 1) };
    let flat = |c: glam::UVec3| (c.x + dims.x * (c.y + dims.y * c.z)) as usize;
    let ncells = (dims.x * dims.y * dims.z) as usize;
    let mut counts = vec![0u32; ncells + 1];
    let cells_of = |f: &[VertexId; 3]| {
        let b = Aabb::from_points(f.iter().map(|v| &pos[v.idx()]));
        let (lo, hi) = (index(b.min), index(b.max));
        (lo.z..=hi.z).flat_map(move |z| {
            (lo.y..=hi.y).flat_map(move |y| (lo.x..=hi.x).map(move |x| glam::UVec3::new(x, y, z)))
        })
    };
    for f in boundary {
        for c in cells_of(f) {
            counts[flat(c) + 1] += 1;
        }
    }
    for i in 0..ncells {
        counts[i + 1] += counts[i];
    }
    let mut fill = counts.clone();
    let mut items = vec![0u32; counts[ncells] as usize];
    for (fi, f) in boundary.iter().enumerate() {
        for c in cells_of(f) {
            let s = &mut fill[flat(c)];
            items[*s as usize] = fi as u32;
            *s += 1;
        }
    }
    let mut vertices: Vec<VertexId> = boundary.iter().flatten().copied().collect();
    vertices.sort_unstable();
    vertices.dedup();
    for v in vertices {
        let p = pos[v.idx()];
        let c = flat(index(p));
        for &fi in &items[counts[c] as usize..counts[c + 1] as usize] {
            let f = &boundary[fi as usize];
            if f.contains(&v) {
                continue;
            }
            let [a, b, q] = f.map(|w| pos[w.idx()]);
            if p == a || p == b || p == q || orient3d(a, b, q, p) != Sign::Zero {
                continue;
            }
            if point_in_coplanar_triangle(p, a, b, q) {
                r.add(ViolationKind::HangingVertex, || {
                    format!("vertex {v} lies on boundary face {}", ids(f))
                });
                break;
            }
        }
    }
}

/// Whether `p`, coplanar with the triangle (a, b, c), lies in the closed triangle. Exact:
/// the test is made in the coordinate plane the triangle projects to without collapsing.
fn point_in_coplanar_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> bool {
    let n = (b - a).cross(c - a).abs();
    let (i, j) = if n.x >= n.y && n.x >= n.z {
        (1, 2)
    } else if n.y >= n.z {
        (2, 0)
    } else {
        (0, 1)
    };
    let pr = |q: DVec3| [q[i], q[j]];
    let s = [
        orient2d(pr(a), pr(b), pr(p)),
        orient2d(pr(b), pr(c), pr(p)),
        orient2d(pr(c), pr(a), pr(p)),
    ];
    !(s.contains(&Sign::Positive) && s.contains(&Sign::Negative))
        && orient2d(pr(a), pr(b), pr(c)) != Sign::Zero
}

#[cfg(test)]
mod tests {
    use super::*;

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
