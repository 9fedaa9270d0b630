//! The generator of the split tables (`src/cut/tables_generated.rs`).
//!
//! Run `cargo run --example gen_cut_tables > src/cut/tables_generated.rs`; the test
//! `tests/cut_tables.rs` regenerates the tables and fails when the embedded file differs.
//!
//! # What an entry must satisfy (paper §4.2)
//!
//! For a configuration of the canonical tet (vertices sorted in the global order, see
//! [`super::tables`]):
//!
//! * the children tile the tet: no overlap, no gap, volumes adding up;
//! * each face of the tet is subdivided exactly as the neighbour across it subdivides it
//!   ([`face_triangles`]: fan from the face point, two triangles around a slit ending at a
//!   snapped vertex, or a triangle plus a quadrilateral cut along the diagonal at its
//!   lowest vertex — Fig. 8);
//! * the crack polygon K (the part of the section inside C) is a union of child faces, seen
//!   from the positive side with the positive copies of the cut points and from the
//!   negative side with the negative copies (the cut opens along K);
//! * every child is positively oriented **for every position** of the cut points along
//!   their edges and of the face points along their faces' section segments (the segment
//!   where the plane meets the face, from its end in C to its end out of C — the crossing of
//!   an uncut edge, itself anywhere along that edge) — the tables know no geometry. Face
//!   points anywhere in their faces would be asking too much: the D-opposite
//!   configurations have no such tiling (the search finds none up to 16 tets), and the
//!   cut never places a face point off its segment.
//!
//! An [`OUT`] vertex (on the plane outside C: an earlier crack's, see [`super::tables`]) is
//! a section point outside C. Between it and an `ON` vertex the section runs along their
//! edge, which holds no point: the crack polygon goes straight from the `ON` vertex to the
//! next point in C or face point, and when that leaves it fewer than three points (the
//! `ON` vertex and one face point), the tet holds no crack: its children only bring the
//! face point in, and the sides meet at the `ON` vertex, whose copies open the faces in
//! the plane between it and the `OUT` vertex.
//!
//! # How it is found
//!
//! The crack opens the tet along K into a *slit domain* whose boundary is the subdivided
//! faces plus K twice. Candidate children are the 4-subsets of the local points whose
//! barycentric determinant (their volume as a fraction of the parent's) keeps one sign over
//! many sampled positions, extremes included, that never mix a copy of one side with a
//! vertex of the other, and that have a vertex off the cut plane (sampled positions are
//! independent, but the points on the cut are in fact coplanar: a child made of them only
//! would be flat). A depth-first exact cover then closes the boundary face by face
//! (each open face is closed by a candidate having it as an outward face); positive tets
//! whose faces match pairwise and whose free faces are exactly the domain boundary tile the
//! domain (the covering degree is the winding number of the boundary, 1 inside). Depth is
//! increased until a tiling exists, so entries are minimal; every triangulation of K is
//! tried, and among minimal tilings the one with the best mean minimum dihedral angle over
//! sampled positions wins (ties: first found, the search being deterministic).
//!
//! # Steiner points
//!
//! None is needed: every configuration has a tiling with the points above. The paper's
//! Schönhardt prism (Fig. 9) only arises when the three quadrilaterals of a prism take
//! diagonals forming a cycle; with diagonals at the lowest vertex of a global order they
//! never do (Dompierre et al. 1999: the lowest vertex of the prism lies on two of its
//! quadrilaterals, whose diagonals both start there, and coning from it works). The
//! generator would report a configuration without tiling instead of emitting it.

use super::tables::{
    CutCase, NB_CONFIGS, NEG, ON, OUT, POS, Side, config_index, edge_point, face_point,
    face_points, is_crossed, is_valid_config,
};
use crate::mesh::tables::{EDGE_OF_VERTICES, TET_EDGES, TET_FACES};
use crate::rng::Rng;
use std::collections::HashMap;
use std::fmt::Write;

/// One generated table entry.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    pub config: usize,
    pub case: CutCase,
    /// Children as local point ids, positively oriented in a positive canonical tet.
    pub children: Vec<[u8; 4]>,
    pub sides: Vec<Side>,
}

/// A point of the section polygon S: an `ON` vertex or the crossing of a crossed edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum SecPt {
    Vertex(usize),
    Edge(usize),
}

/// The four-vertex barycentric coordinates of the local points, given the sampled edge
/// parameters `t` (position of the crossing from the lower local vertex, for cut and uncut
/// crossed edges alike) and face-point parameters `s` (position along the face's section
/// segment, from its inside end).
#[derive(Clone, Debug)]
struct Geometry {
    bary: [[f64; 4]; 20],
}

/// Everything derived from a configuration.
struct Analysis {
    states: [u8; 4],
    cut_mask: u8,
    face_point: [bool; 4],
    /// Section points in cyclic order.
    section: Vec<SecPt>,
    /// Crack polygon K in cyclic order, as (point on the positive side, on the negative
    /// side): equal for `ON` vertices and face points, the two copies for cut points.
    crack: Vec<(u8, u8)>,
    /// For each face with a face point: (inside end, outside end) of its section segment.
    face_segment: [Option<(SecPt, SecPt)>; 4],
}

fn is_cut(cut_mask: u8, e: usize) -> bool {
    cut_mask & (1 << e) != 0
}

fn sec_inside(a: &Analysis, p: SecPt) -> bool {
    match p {
        SecPt::Vertex(i) => a.states[i] == ON,
        SecPt::Edge(e) => is_cut(a.cut_mask, e),
    }
}

/// Local vertices of a section point.
fn sec_vertices(p: SecPt) -> Vec<usize> {
    match p {
        SecPt::Vertex(i) => vec![i],
        SecPt::Edge(e) => TET_EDGES[e].to_vec(),
    }
}

/// The face holding both section points (they must share one).
fn common_face(p: SecPt, q: SecPt) -> Option<usize> {
    let mut vs = sec_vertices(p);
    for v in sec_vertices(q) {
        if !vs.contains(&v) {
            vs.push(v);
        }
    }
    if vs.len() != 3 {
        // Two ON vertices share an edge (two faces); S-edges between them carry no face
        // point, so no single face is needed.
        return None;
    }
    (0..4).find(|f| !vs.contains(f))
}

fn analyze(states: [u8; 4], cut_mask: u8) -> Analysis {
    let mut pts: Vec<SecPt> = (0..4)
        .filter(|&i| states[i] == ON || states[i] == OUT)
        .map(SecPt::Vertex)
        .collect();
    pts.extend(
        (0..6)
            .filter(|&e| is_crossed(states[TET_EDGES[e][0]], states[TET_EDGES[e][1]]))
            .map(SecPt::Edge),
    );
    // Cyclic order: consecutive section points share a face of the tet.
    let adjacent = |p: SecPt, q: SecPt| match (p, q) {
        (SecPt::Edge(e1), SecPt::Edge(e2)) => e1 + e2 != 5,
        _ => true,
    };
    let mut section = Vec::with_capacity(pts.len());
    if !pts.is_empty() {
        section.push(pts[0]);
        let mut used = vec![false; pts.len()];
        used[0] = true;
        while section.len() < pts.len() {
            let last = section[section.len() - 1];
            let next = (0..pts.len())
                .find(|&k| !used[k] && adjacent(last, pts[k]))
                .expect("the section polygon is a cycle");
            used[next] = true;
            section.push(pts[next]);
        }
    }
    let mut a = Analysis {
        states,
        cut_mask,
        face_point: face_points(states, cut_mask),
        section,
        crack: Vec::new(),
        face_segment: [None; 4],
    };
    let n = a.section.len();
    if n >= 3 {
        for k in 0..n {
            let (p, q) = (a.section[k], a.section[(k + 1) % n]);
            let (ip, iq) = (sec_inside(&a, p), sec_inside(&a, q));
            if ip {
                a.crack.push(match p {
                    SecPt::Vertex(i) => (i as u8, i as u8),
                    SecPt::Edge(e) => (edge_point(e, true), edge_point(e, false)),
                });
            }
            // An `ON` and an `OUT` vertex: the section runs along their edge, which holds
            // no point; the crack ends at the `ON` vertex.
            let along_edge = matches!((p, q), (SecPt::Vertex(_), SecPt::Vertex(_)));
            if ip != iq && !along_edge {
                let f = common_face(p, q).expect("an in/out section edge lies on one face");
                assert!(
                    a.face_point[f],
                    "face point rule disagrees with the section"
                );
                a.face_segment[f] = Some(if ip { (p, q) } else { (q, p) });
                a.crack.push((face_point(f), face_point(f)));
            }
        }
    }
    a
}

/// The copy of edge `e`'s cut point on the side of local vertex `v` (an end of `e`).
fn copy_toward(states: [u8; 4], e: usize, v: usize) -> u8 {
    edge_point(e, states[v] == POS)
}

/// The triangles subdividing face `f` of a tet in configuration (`states`, `cut_mask`),
/// oriented like the face (outward), in local point ids. This is the shared-face rule:
/// it only depends on the face's own vertex states, cut edges and vertex order, so the two
/// tets sharing a face produce the same triangles.
pub fn face_triangles(states: [u8; 4], cut_mask: u8, f: usize) -> Vec<[u8; 3]> {
    let v = TET_FACES[f];
    // Boundary cycle of the face, each cut edge opened into its two copies.
    let mut cycle: Vec<u8> = Vec::with_capacity(7);
    let mut slit_after = [false; 7];
    for k in 0..3 {
        let (u, w) = (v[k], v[(k + 1) % 3]);
        cycle.push(u as u8);
        let e = EDGE_OF_VERTICES[u][w];
        if is_cut(cut_mask, e) {
            cycle.push(copy_toward(states, e, u));
            slit_after[cycle.len() - 1] = true;
            cycle.push(copy_toward(states, e, w));
        }
    }
    let n = cycle.len();
    let cuts = (n - 3) / 2;
    if face_points(states, cut_mask)[f] {
        // Fig. 8a: every corner of the opened face joined to the face point.
        let fp = face_point(f);
        return (0..n)
            .filter(|&k| !slit_after[k])
            .map(|k| [cycle[k], cycle[(k + 1) % n], fp])
            .collect();
    }
    match cuts {
        0 => vec![[v[0] as u8, v[1] as u8, v[2] as u8]],
        1 => {
            // The slit runs from the cut point to the ON vertex opposite it.
            let k = (0..n).find(|&k| slit_after[k]).expect("one slit");
            let (before, after) = (cycle[k], cycle[(k + 1) % n]);
            let apex = cycle[(k + 3) % n];
            debug_assert!(states[apex as usize] == ON);
            vec![
                [cycle[(k + n - 1) % n], before, apex],
                [after, cycle[(k + 2) % n], apex],
            ]
        }
        _ => {
            // Two cut edges around the lone vertex `a`: the triangle at `a` and a
            // quadrilateral cut along the diagonal at its lowest vertex (Fig. 8b). Its
            // lowest vertex is an original vertex: cut points are always newer.
            // The lone vertex: the original vertex between two cut-point copies.
            let ka = (0..n)
                .find(|&k| cycle[k] < 4 && cycle[(k + 1) % n] >= 4 && cycle[(k + n - 1) % n] >= 4)
                .expect("a face with two cut edges has a lone vertex");
            let a = cycle[ka];
            let (x_a, y_a) = (cycle[(ka + 1) % n], cycle[(ka + n - 1) % n]);
            let (x_b, b, c, y_c) = (
                cycle[(ka + 2) % n],
                cycle[(ka + 3) % n],
                cycle[(ka + 4) % n],
                cycle[(ka + 5) % n],
            );
            debug_assert!(a < 4 && b < 4 && c < 4);
            let mut tris = vec![[a, x_a, y_a]];
            if b < c {
                tris.push([x_b, b, y_c]);
                tris.push([b, c, y_c]);
            } else {
                tris.push([x_b, b, c]);
                tris.push([x_b, c, y_c]);
            }
            tris
        }
    }
}

/// Barycentric coordinates of every local point for sampled parameters.
fn geometry(a: &Analysis, t: &[f64; 6], s: &[f64; 4]) -> Geometry {
    let mut bary = [[0.0; 4]; 20];
    for (i, row) in bary.iter_mut().take(4).enumerate() {
        row[i] = 1.0;
    }
    let sec = |p: SecPt| -> [f64; 4] {
        let mut b = [0.0; 4];
        match p {
            SecPt::Vertex(i) => b[i] = 1.0,
            SecPt::Edge(e) => {
                let [u, w] = TET_EDGES[e];
                b[u] = 1.0 - t[e];
                b[w] = t[e];
            }
        }
        b
    };
    for e in 0..6 {
        let b = sec(SecPt::Edge(e));
        bary[edge_point(e, true) as usize] = b;
        bary[edge_point(e, false) as usize] = b;
    }
    for f in 0..4 {
        if let Some((pin, pout)) = a.face_segment[f] {
            let (bi, bo) = (sec(pin), sec(pout));
            bary[face_point(f) as usize] =
                std::array::from_fn(|k| (1.0 - s[f]) * bi[k] + s[f] * bo[k]);
        }
    }
    Geometry { bary }
}

fn det4(m: [[f64; 4]; 4]) -> f64 {
    let sub = |r: [usize; 3], c: [usize; 3]| {
        m[r[0]][c[0]] * (m[r[1]][c[1]] * m[r[2]][c[2]] - m[r[1]][c[2]] * m[r[2]][c[1]])
            - m[r[0]][c[1]] * (m[r[1]][c[0]] * m[r[2]][c[2]] - m[r[1]][c[2]] * m[r[2]][c[0]])
            + m[r[0]][c[2]] * (m[r[1]][c[0]] * m[r[2]][c[1]] - m[r[1]][c[1]] * m[r[2]][c[0]])
    };
    let r = [1, 2, 3];
    m[0][0] * sub(r, [1, 2, 3]) - m[0][1] * sub(r, [0, 2, 3]) + m[0][2] * sub(r, [0, 1, 3])
        - m[0][3] * sub(r, [0, 1, 2])
}

/// Volume of a child as a fraction of its parent's.
fn child_fraction(g: &Geometry, c: [u8; 4]) -> f64 {
    det4(c.map(|p| g.bary[p as usize]))
}

/// Sampled parameter sets: every combination of extremes, then random ones.
fn samples(a: &Analysis, rng: &mut Rng, random: usize) -> Vec<Geometry> {
    let crossed: Vec<usize> = (0..6)
        .filter(|&e| is_crossed(a.states[TET_EDGES[e][0]], a.states[TET_EDGES[e][1]]))
        .collect();
    let faces: Vec<usize> = (0..4).filter(|&f| a.face_point[f]).collect();
    let nparams = crossed.len() + faces.len();
    let mut out = Vec::new();
    let mut push = |vals: &[f64]| {
        let mut t = [0.5; 6];
        let mut s = [0.5; 4];
        for (k, &e) in crossed.iter().enumerate() {
            t[e] = vals[k];
        }
        for (k, &f) in faces.iter().enumerate() {
            s[f] = vals[crossed.len() + k];
        }
        out.push(geometry(a, &t, &s));
    };
    for bits in 0..(1u32 << nparams) {
        let vals: Vec<f64> = (0..nparams)
            .map(|k| if bits & (1 << k) != 0 { 0.999 } else { 0.001 })
            .collect();
        push(&vals);
    }
    for _ in 0..random {
        let vals: Vec<f64> = (0..nparams).map(|_| rng.unit()).collect();
        push(&vals);
    }
    out
}

/// Side of a local point: +1, -1, or 0 (on the cut).
fn point_side(states: [u8; 4], p: u8) -> i8 {
    match p {
        0..=3 => match states[p as usize] {
            POS => 1,
            NEG => -1,
            _ => 0,
        },
        4..=15 => {
            if (p - 4) % 2 == 0 {
                1
            } else {
                -1
            }
        }
        _ => 0,
    }
}

fn side_of_child(states: [u8; 4], c: [u8; 4]) -> Side {
    let pos = c.iter().any(|&p| point_side(states, p) > 0);
    let neg = c.iter().any(|&p| point_side(states, p) < 0);
    match (pos, neg) {
        (true, false) => Side::Positive,
        (false, true) => Side::Negative,
        _ => Side::Straddle,
    }
}

/// An oriented triangle as a key: the sorted triple and the parity of the permutation.
fn half_face(t: [u8; 3]) -> u32 {
    let mut s = t;
    let mut parity = 0;
    for i in 0..3 {
        for j in 0..2 - i {
            if s[j] > s[j + 1] {
                s.swap(j, j + 1);
                parity ^= 1;
            }
        }
    }
    ((s[0] as u32 * 32 + s[1] as u32) * 32 + s[2] as u32) * 2 + parity
}

fn reversed(h: u32) -> u32 {
    h ^ 1
}

/// The outward faces of a positively oriented tet.
fn outward_faces(c: [u8; 4]) -> [u32; 4] {
    TET_FACES.map(|f| half_face(f.map(|i| c[i])))
}

/// Triangulations of a convex polygon with `n` vertices (indices into it).
fn polygon_triangulations(n: usize) -> Vec<Vec<[usize; 3]>> {
    fn rec(lo: usize, hi: usize) -> Vec<Vec<[usize; 3]>> {
        if hi - lo < 2 {
            return vec![Vec::new()];
        }
        let mut out = Vec::new();
        for m in lo + 1..hi {
            for l in rec(lo, m) {
                for r in rec(m, hi) {
                    let mut t = vec![[lo, m, hi]];
                    t.extend(l.iter().copied());
                    t.extend(r.iter().copied());
                    out.push(t);
                }
            }
        }
        out
    }
    rec(0, n - 1)
}

/// Search nodes allowed per (configuration, crack triangulation, depth); the largest
/// search needs a few thousand. Exceeding it is a bug, not a reason to emit a non-minimal
/// entry.
const NODE_BUDGET: usize = 5_000_000;

/// Exact-cover search for minimal tilings.
struct Search<'a> {
    cands: &'a [[u8; 4]],
    faces: &'a [[u32; 4]],
    by_face: &'a HashMap<u32, Vec<usize>>,
    boundary: &'a [u32],
    need: Vec<u32>,
    filled: Vec<u32>,
    chosen: Vec<usize>,
    solutions: Vec<Vec<usize>>,
    cap: usize,
    nodes: usize,
}

impl Search<'_> {
    fn fits(&self, c: usize) -> bool {
        self.faces[c].iter().all(|&g| {
            !self.filled.contains(&g)
                && (self.need.contains(&g) || !self.boundary.contains(&reversed(g)))
        })
    }

    fn run(&mut self, limit: usize) {
        self.nodes += 1;
        if self.solutions.len() >= self.cap {
            return;
        }
        assert!(
            self.nodes <= NODE_BUDGET,
            "table search exceeded its node budget: minimality would not be proven"
        );
        if self.need.is_empty() {
            self.solutions.push(self.chosen.clone());
            return;
        }
        if self.chosen.len() + self.need.len().div_ceil(4) > limit {
            return;
        }
        // The open face with the fewest fitting candidates.
        let mut best: Option<(usize, Vec<usize>)> = None;
        for &h in &self.need {
            let fit: Vec<usize> = self
                .by_face
                .get(&h)
                .map(|v| v.iter().copied().filter(|&c| self.fits(c)).collect())
                .unwrap_or_default();
            if best.as_ref().is_none_or(|(n, _)| fit.len() < *n) {
                let n = fit.len();
                best = Some((n, fit));
                if n == 0 {
                    return;
                }
            }
        }
        let Some((_, options)) = best else { return };
        for c in options {
            let faces = self.faces[c];
            let mut added = Vec::new();
            let mut removed = Vec::new();
            for g in faces {
                if let Some(k) = self.need.iter().position(|&x| x == g) {
                    self.need.swap_remove(k);
                    removed.push(g);
                } else {
                    self.need.push(reversed(g));
                    added.push(reversed(g));
                }
                self.filled.push(g);
            }
            self.chosen.push(c);
            self.run(limit);
            self.chosen.pop();
            for _ in 0..4 {
                self.filled.pop();
            }
            for g in added {
                let k = self.need.iter().position(|&x| x == g).expect("added need");
                self.need.swap_remove(k);
            }
            self.need.extend(removed);
        }
    }
}

/// Minimum dihedral angle (radians) of the tet with these corners.
fn min_dihedral(p: [[f64; 3]; 4]) -> f64 {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let normals: Vec<[f64; 3]> = TET_FACES
        .iter()
        .map(|f| {
            let n = cross(sub(p[f[1]], p[f[0]]), sub(p[f[2]], p[f[0]]));
            let l = dot(n, n).sqrt();
            [n[0] / l, n[1] / l, n[2] / l]
        })
        .collect();
    let mut m = f64::INFINITY;
    for i in 0..4 {
        for j in i + 1..4 {
            let c = (-dot(normals[i], normals[j])).clamp(-1.0, 1.0);
            m = m.min(c.acos());
        }
    }
    m
}

/// Corners of a regular, positively oriented tet (quality is measured on it).
const REGULAR: [[f64; 3]; 4] = [
    [1.0, 1.0, 1.0],
    [1.0, -1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [-1.0, 1.0, -1.0],
];

fn position(g: &Geometry, p: u8) -> [f64; 3] {
    let b = g.bary[p as usize];
    std::array::from_fn(|k| (0..4).map(|i| b[i] * REGULAR[i][k]).sum())
}

/// Plausible placements for judging quality: a plane crossing the tet as the states say
/// (signed distances of at least a tenth of the largest, as snapping ensures), crossings
/// where that plane puts them, face points in the middle half of their segments, uncut
/// crossings kept in the middle half of their edges (as the cut places them).
fn realistic_samples(a: &Analysis, rng: &mut Rng, n: usize) -> Vec<Geometry> {
    (0..n)
        .map(|_| {
            let d: [f64; 4] = std::array::from_fn(|i| match a.states[i] {
                POS => 0.1 + 0.9 * rng.unit(),
                NEG => -0.1 - 0.9 * rng.unit(),
                _ => 0.0,
            });
            let t: [f64; 6] = std::array::from_fn(|e| {
                let [u, w] = TET_EDGES[e];
                if is_crossed(a.states[u], a.states[w]) {
                    let t = d[u] / (d[u] - d[w]);
                    if is_cut(a.cut_mask, e) {
                        t
                    } else {
                        t.clamp(0.25, 0.75)
                    }
                } else {
                    0.5
                }
            });
            let s: [f64; 4] = std::array::from_fn(|_| 0.25 + 0.5 * rng.unit());
            geometry(a, &t, &s)
        })
        .collect()
}

/// The smallest child dihedral angle over `geoms`, and its mean: the tie-break among
/// minimal tilings (worst case first).
fn quality(geoms: &[Geometry], children: &[[u8; 4]]) -> (f64, f64) {
    let per: Vec<f64> = geoms
        .iter()
        .map(|g| {
            children
                .iter()
                .map(|c| min_dihedral(c.map(|p| position(g, p))))
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    let worst = per.iter().copied().fold(f64::INFINITY, f64::min);
    (worst, per.iter().sum::<f64>() / per.len() as f64)
}

/// The seed of a configuration's samples: its index in the tables before the [`OUT`] state
/// (three states, `3⁴ × 64` configurations) when it has no `OUT` vertex, so those entries
/// stay what they were; past that range otherwise.
fn sample_seed(states: [u8; 4], cut_mask: u8) -> usize {
    if states.contains(&OUT) {
        81 * 64 + config_index(states, cut_mask)
    } else {
        let code = states[0] as usize
            + 3 * states[1] as usize
            + 9 * states[2] as usize
            + 27 * states[3] as usize;
        code * 64 + cut_mask as usize
    }
}

/// Generates the entry of one configuration, or `None` when the tet is not split.
/// Panics if a split configuration has no tiling (it would need a Steiner point); the
/// module docs explain why that does not happen, and the tests check it.
pub fn generate_entry(states: [u8; 4], cut_mask: u8) -> Option<Entry> {
    if !is_valid_config(states, cut_mask) {
        return None;
    }
    let case = CutCase::of_config(states, cut_mask)?;
    let a = analyze(states, cut_mask);
    let config = config_index(states, cut_mask);
    let seed = sample_seed(states, cut_mask) as u64;
    let mut rng = Rng(0x5EED_0000 + seed);
    let geoms = samples(&a, &mut rng, 256);
    let quality_geoms = realistic_samples(&a, &mut Rng(0xC0FFEE + seed), 256);
    // Points present.
    let mut points: Vec<u8> = (0..4).collect();
    for e in 0..6 {
        if is_cut(cut_mask, e) {
            points.push(edge_point(e, true));
            points.push(edge_point(e, false));
        }
    }
    for f in 0..4 {
        if a.face_point[f] {
            points.push(face_point(f));
        }
    }
    // Candidate children: sign-definite, never mixing one side's copy with the other side.
    let mut cands: Vec<[u8; 4]> = Vec::new();
    let n = points.len();
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                for l in k + 1..n {
                    let c = [points[i], points[j], points[k], points[l]];
                    let copies_pos = c.iter().any(|&p| (4..16).contains(&p) && (p - 4) % 2 == 0);
                    let copies_neg = c.iter().any(|&p| (4..16).contains(&p) && (p - 4) % 2 == 1);
                    let side_pos = c.iter().any(|&p| point_side(states, p) > 0);
                    let side_neg = c.iter().any(|&p| point_side(states, p) < 0);
                    if (copies_pos && side_neg) || (copies_neg && side_pos) {
                        continue;
                    }
                    // Cut points, face points and snapped vertices all lie on the cut plane
                    // (up to snapping): a child made of them only is flat, whatever its
                    // barycentric volume for unconstrained positions says.
                    if !c
                        .iter()
                        .any(|&p| p < 4 && matches!(states[p as usize], POS | NEG))
                    {
                        continue;
                    }
                    let mut sign = 0.0f64;
                    let mut definite = true;
                    for g in &geoms {
                        let d = child_fraction(g, c);
                        if d == 0.0 || (sign != 0.0 && d.signum() != sign) {
                            definite = false;
                            break;
                        }
                        sign = d.signum();
                    }
                    if definite {
                        cands.push(if sign > 0.0 {
                            c
                        } else {
                            [c[0], c[1], c[3], c[2]]
                        });
                    }
                }
            }
        }
    }
    let faces: Vec<[u32; 4]> = cands.iter().map(|&c| outward_faces(c)).collect();
    let mut by_face: HashMap<u32, Vec<usize>> = HashMap::new();
    for (ci, fs) in faces.iter().enumerate() {
        for &h in fs {
            by_face.entry(h).or_default().push(ci);
        }
    }
    // Boundary of the slit domain: subdivided faces, then K from both sides.
    let mut face_bdry: Vec<u32> = Vec::new();
    for f in 0..4 {
        face_bdry.extend(
            face_triangles(states, cut_mask, f)
                .into_iter()
                .map(half_face),
        );
    }
    let mid = geometry(&a, &[0.5; 6], &[0.5; 4]);
    let neg_vertex = (0..4)
        .find(|&i| states[i] == NEG)
        .expect("a split tet has a NEG vertex") as u8;
    // (children count, quality, children) of the best tiling so far.
    type Best = (usize, (f64, f64), Vec<[u8; 4]>);
    let mut best: Option<Best> = None;
    // A crack of fewer than three points has no area: an `ON` vertex whose section
    // neighbours are out of C, one of them an `OUT` vertex (the crack reaches this tet at
    // the vertex and the face point beside it, and opens nowhere inside it).
    let m = a.crack.len();
    let triangulations = if m < 3 {
        vec![Vec::new()]
    } else {
        polygon_triangulations(m)
    };
    for tri in triangulations {
        let mut bdry = face_bdry.clone();
        for t in &tri {
            let plus = t.map(|k| a.crack[k].0);
            let minus = t.map(|k| a.crack[k].1);
            // Oriented outward of the positive region: its normal points to the NEG side.
            let toward_neg = child_fraction(&mid, [plus[0], plus[1], plus[2], neg_vertex]) > 0.0;
            let (p, q) = if toward_neg {
                (plus, [minus[0], minus[2], minus[1]])
            } else {
                ([plus[0], plus[2], plus[1]], minus)
            };
            bdry.push(half_face(p));
            bdry.push(half_face(q));
        }
        for limit in 1..=16 {
            if best.as_ref().is_some_and(|b| limit > b.0) {
                break;
            }
            let mut s = Search {
                cands: &cands,
                faces: &faces,
                by_face: &by_face,
                boundary: &bdry,
                need: bdry.clone(),
                filled: Vec::new(),
                chosen: Vec::new(),
                solutions: Vec::new(),
                cap: 64,
                nodes: 0,
            };
            s.run(limit);
            if s.solutions.is_empty() {
                continue;
            }
            for sol in s.solutions {
                let mut children: Vec<[u8; 4]> = sol.iter().map(|&c| s.cands[c]).collect();
                children.sort_unstable();
                let q = quality(&quality_geoms, &children);
                let better = match &best {
                    None => true,
                    Some((bn, bq, _)) => {
                        children.len() < *bn
                            || (children.len() == *bn
                                && (q.0 > bq.0 + 1e-12
                                    || (q.0 >= bq.0 - 1e-12 && q.1 > bq.1 + 1e-12)))
                    }
                };
                if better {
                    best = Some((children.len(), q, children));
                }
            }
            break;
        }
    }
    let (_, _, children) = best.unwrap_or_else(|| {
        panic!("configuration {states:?}/{cut_mask:06b} has no tiling without a Steiner point")
    });
    let sides = children.iter().map(|&c| side_of_child(states, c)).collect();
    Some(Entry {
        config,
        case,
        children,
        sides,
    })
}

/// Every split configuration's entry, in configuration order.
pub fn generate() -> Vec<Entry> {
    (0..NB_CONFIGS)
        .filter_map(|c| {
            let (s, m) = super::tables::config_of_index(c);
            generate_entry(s, m)
        })
        .collect()
}

/// The Rust source of `tables_generated.rs` for `entries`.
pub fn render(entries: &[Entry]) -> String {
    let mut offsets = vec![0u16; NB_CONFIGS + 1];
    let mut cases = vec![255u8; NB_CONFIGS];
    let mut children: Vec<[u8; 4]> = Vec::new();
    let mut sides: Vec<u8> = Vec::new();
    let mut next = entries.iter().peekable();
    for c in 0..NB_CONFIGS {
        offsets[c] = children.len() as u16;
        if let Some(e) = next.next_if(|e| e.config == c) {
            cases[c] = CutCase::ALL
                .iter()
                .position(|&k| k == e.case)
                .unwrap_or(255) as u8;
            children.extend(e.children.iter().copied());
            sides.extend(e.sides.iter().map(|s| match s {
                Side::Positive => super::tables::SIDE_POSITIVE,
                Side::Negative => super::tables::SIDE_NEGATIVE,
                Side::Straddle => super::tables::SIDE_STRADDLE,
            }));
        }
    }
    offsets[NB_CONFIGS] = children.len() as u16;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// @generated by `cargo run --example gen_cut_tables` (src/cut/table_gen.rs).\n\
         // Do not edit: tests/cut_tables.rs regenerates this file and compares.\n\
         // {} split configurations, {} children.\n",
        entries.len(),
        children.len()
    );
    let _ = writeln!(s, "pub static OFFSETS: [u16; {}] = [", NB_CONFIGS + 1);
    for chunk in offsets.chunks(16) {
        let line: Vec<String> = chunk.iter().map(|x| x.to_string()).collect();
        let _ = writeln!(s, "    {},", line.join(", "));
    }
    let _ = writeln!(s, "];\n\npub static CASES: [u8; {NB_CONFIGS}] = [");
    for chunk in cases.chunks(16) {
        let line: Vec<String> = chunk.iter().map(|x| x.to_string()).collect();
        let _ = writeln!(s, "    {},", line.join(", "));
    }
    let _ = writeln!(
        s,
        "];\n\npub static CHILDREN: [[u8; 4]; {}] = [",
        children.len()
    );
    for chunk in children.chunks(6) {
        let line: Vec<String> = chunk
            .iter()
            .map(|c| format!("[{}, {}, {}, {}]", c[0], c[1], c[2], c[3]))
            .collect();
        let _ = writeln!(s, "    {},", line.join(", "));
    }
    let _ = writeln!(s, "];\n\npub static SIDES: [u8; {}] = [", sides.len());
    for chunk in sides.chunks(24) {
        let line: Vec<String> = chunk.iter().map(|x| x.to_string()).collect();
        let _ = writeln!(s, "    {},", line.join(", "));
    }
    let _ = writeln!(s, "];");
    s
}
