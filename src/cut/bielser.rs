//! The 1:17 splitting scheme of Bielser, Maiwald and Gross (1999), the paper's baseline
//! (§4.1, Fig. 5): every cut tet becomes a central tet (its four face nodes) plus four
//! seven-faced polyhedra around its vertices, each coned from its vertex into four tets.
//!
//! Nodes: one per face (its centroid), and on every edge one node per end — the two at the
//! same position, at the crossing for a crossed edge and at the midpoint otherwise —
//! distinct for a cut edge (the cut opens there) and merged otherwise. Nodes are shared by
//! the split tets around an edge or face.
//!
//! What it guarantees: every child is positively oriented (each child's volume is a fixed
//! positive multiple of products of the edge parameters, whatever the crossings), and the
//! children tile the parent, so the volume adds up. What it does not: a split tet's faces
//! are subdivided while its unsplit neighbours' are not, so the mesh is not conforming
//! (the paper's second objection to it) — `TetMesh::validate` reports hanging vertices and
//! non-manifold boundary edges there; and the parts stay joined through the shared face
//! nodes, so a cut straight through does not separate them. It exists to count the cells
//! the paper compares its tables with.

use super::classify::{CutSession, NONE, TetClass, VertexOrigin};
use super::split::Children;
use super::tables::{CASES, CutCase, NEG, POS, Side, config_index};
use crate::geom::{DVec3, signed_volume_inexact};
use crate::mesh::tables::{EDGE_OF_VERTICES, TET_EDGES, TET_FACES};
use crate::mesh::{Tet, VertexId};
use std::collections::HashMap;
use std::sync::OnceLock;

/// Children per split tet.
pub const CHILDREN: usize = 17;

/// Local points of the pattern: 0..4 vertices; `4 + 2e + k` the node of edge `e` at its
/// end `TET_EDGES[e][k]`; `16 + f` the node of face `f`.
fn pattern() -> &'static [[u8; 4]; CHILDREN] {
    static PATTERN: OnceLock<[[u8; 4]; CHILDREN]> = OnceLock::new();
    PATTERN.get_or_init(|| {
        let node = |i: usize, e: usize| (4 + 2 * e + usize::from(TET_EDGES[e][1] == i)) as u8;
        let mut out: Vec<[u8; 4]> = Vec::with_capacity(CHILDREN);
        for (i, edge_to) in EDGE_OF_VERTICES.iter().enumerate() {
            for j in (0..4).filter(|&j| j != i) {
                let e = edge_to[j];
                let others: Vec<usize> = (0..4).filter(|&k| k != i && k != j).collect();
                out.push([
                    i as u8,
                    node(i, e),
                    16 + others[0] as u8,
                    16 + others[1] as u8,
                ]);
            }
            let faces: Vec<u8> = (0..4).filter(|&f| f != i).map(|f| 16 + f as u8).collect();
            out.push([i as u8, faces[0], faces[1], faces[2]]);
        }
        out.push([16, 17, 18, 19]);
        // Orient on a reference tet: the sign of each child's volume does not depend on
        // the node positions (see the module docs).
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let pos = |l: u8| -> DVec3 {
            match l {
                0..=3 => p[l as usize],
                4..=15 => {
                    let [a, b] = TET_EDGES[(l as usize - 4) / 2];
                    (p[a] + p[b]) * 0.5
                }
                _ => {
                    TET_FACES[l as usize - 16]
                        .iter()
                        .map(|&k| p[k])
                        .sum::<DVec3>()
                        / 3.0
                }
            }
        };
        let mut res = [[0u8; 4]; CHILDREN];
        for (k, c) in out.iter().enumerate() {
            let [a, b, cc, d] = c.map(pos);
            res[k] = if signed_volume_inexact(a, b, cc, d) > 0.0 {
                *c
            } else {
                [c[0], c[1], c[3], c[2]]
            };
        }
        res
    })
}

/// The shared nodes of the 1:17 scheme for one cut.
#[derive(Default)]
pub struct Bielser17Nodes {
    /// The merged node of an uncut edge, by (low, high) id.
    edge: HashMap<(VertexId, VertexId), VertexId>,
    /// The two nodes of a cut edge: (positive side, negative side).
    cut_edge: HashMap<(VertexId, VertexId), (VertexId, VertexId)>,
    face: HashMap<[VertexId; 3], VertexId>,
}

impl Bielser17Nodes {
    /// Allocates, in canonical order from `first`, the nodes of every split tet in
    /// `tets`/`classes`, and returns their origins.
    pub fn allocate(
        session: &CutSession<'_>,
        tets: &[Tet],
        classes: &[TetClass],
        first: VertexId,
    ) -> (Bielser17Nodes, Vec<VertexOrigin>) {
        let mut edges: Vec<(VertexId, VertexId, f64, bool)> = Vec::new();
        let mut faces: Vec<[VertexId; 3]> = Vec::new();
        for (tet, class) in tets.iter().zip(classes) {
            if !class.is_split() {
                continue;
            }
            for (e, &[a, b]) in TET_EDGES.iter().enumerate() {
                let (lo, hi) = if tet[a] < tet[b] {
                    (tet[a], tet[b])
                } else {
                    (tet[b], tet[a])
                };
                let r = class.edges[e];
                let (t, cut) = if r == NONE {
                    (0.5, false)
                } else {
                    let rec = &session.edges[r as usize];
                    (rec.t, rec.cut)
                };
                edges.push((lo, hi, t, cut));
            }
            for f in TET_FACES {
                let mut v = f.map(|k| tet[k]);
                v.sort_unstable();
                faces.push(v);
            }
        }
        edges.sort_unstable_by_key(|e| (e.0, e.1));
        edges.dedup_by_key(|e| (e.0, e.1));
        faces.sort_unstable();
        faces.dedup();
        let mut nodes = Bielser17Nodes::default();
        let mut origins = Vec::new();
        let mut next = first.0;
        for (lo, hi, t, cut) in edges {
            if cut {
                nodes
                    .cut_edge
                    .insert((lo, hi), (VertexId(next), VertexId(next + 1)));
                next += 2;
                for positive in [true, false] {
                    origins.push(VertexOrigin::Edge {
                        a: lo,
                        b: hi,
                        t,
                        positive,
                    });
                }
            } else {
                nodes.edge.insert((lo, hi), VertexId(next));
                next += 1;
                origins.push(VertexOrigin::Edge {
                    a: lo,
                    b: hi,
                    t,
                    positive: true,
                });
            }
        }
        for v in faces {
            nodes.face.insert(v, VertexId(next));
            next += 1;
            origins.push(VertexOrigin::Face {
                v,
                w: [1.0 / 3.0; 3],
            });
        }
        (nodes, origins)
    }

    /// Writes into `out` the 17 children of a split tet; false when the tet is not split.
    pub fn split(&self, tet: &Tet, class: &TetClass, out: &mut Children) -> bool {
        if !class.is_split() {
            return false;
        }
        let mut points = [VertexId::INVALID; 20];
        points[..4].copy_from_slice(tet);
        for (e, &[a, b]) in TET_EDGES.iter().enumerate() {
            let key = if tet[a] < tet[b] {
                (tet[a], tet[b])
            } else {
                (tet[b], tet[a])
            };
            if let Some(&(plus, minus)) = self.cut_edge.get(&key) {
                for (k, end) in [a, b].into_iter().enumerate() {
                    points[4 + 2 * e + k] = if class.states[end] == POS {
                        plus
                    } else {
                        minus
                    };
                }
            } else if let Some(&n) = self.edge.get(&key) {
                points[4 + 2 * e] = n;
                points[5 + 2 * e] = n;
            } else {
                return false;
            }
        }
        for (f, lv) in TET_FACES.iter().enumerate() {
            let mut v = lv.map(|k| tet[k]);
            v.sort_unstable();
            match self.face.get(&v) {
                Some(&n) => points[16 + f] = n,
                None => return false,
            }
        }
        let config = config_index(canonical_states(tet, class), canonical_mask(tet, class));
        out.case = CutCase::ALL[CASES[config] as usize];
        out.len = CHILDREN;
        for (k, c) in pattern().iter().enumerate() {
            out.tets[k] = c.map(|p| points[p as usize]);
            out.sides[k] = if k < 16 {
                match class.states[k / 4] {
                    POS => Side::Positive,
                    NEG => Side::Negative,
                    _ => Side::Straddle,
                }
            } else {
                Side::Straddle
            };
            out.on_cut[k] = 0;
        }
        true
    }
}

fn canonical_states(tet: &Tet, class: &TetClass) -> [u8; 4] {
    let (perm, _) = super::split::canonical_order(tet);
    perm.map(|i| class.states[i])
}

fn canonical_mask(tet: &Tet, class: &TetClass) -> u8 {
    let (perm, _) = super::split::canonical_order(tet);
    let mut m = 0u8;
    for (e, &[i, j]) in TET_EDGES.iter().enumerate() {
        if class.cut_mask & (1 << EDGE_OF_VERTICES[perm[i]][perm[j]]) != 0 {
            m |= 1 << e;
        }
    }
    m
}
