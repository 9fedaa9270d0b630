//! `Mt::validate`: every MT invariant of DESIGN.md §5, exhaustively, each violation class
//! with its count and first examples.
//!
//! * the store is consistent (ids in range, arcs partition the pool, columns agree);
//! * each tet has exactly one creator and one destroyer (each lies in exactly one arc), and
//!   no arc is empty;
//! * the DAG is acyclic and the stored levels are its longest paths; roots have no floor,
//!   drains no ceiling, every collapse both;
//! * errors: roots 0, drains +∞, and never decreasing along an arc;
//! * every non-ghost pool tet is positively oriented (exact);
//! * every fragment's floor and ceiling are each conforming and have the same oriented
//!   boundary triangles (ghosts included, so they cover the same region of the closed
//!   complex); a root's ceiling and a drain's floor are closed;
//! * fragment boxes are the boxes of their floor and ceiling;
//! * the finest and coarsest frontiers are valid meshes ([`crate::mesh::TetMesh::validate`]).

use super::extract::ExtractOptions;
use super::{FragmentKind, GHOST, Mt};
use crate::geom::{Aabb, Sign, orient3d};
use crate::mesh::tables::{TET_FACES, oriented_face};
use crate::mesh::{FragmentId, Tet, TetId};
use rayon::prelude::*;
use std::fmt;

const EXAMPLES: usize = 5;

/// A class of MT invariant violation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MtViolationKind {
    /// Inconsistent store (ids out of range, arcs not partitioning the pool...).
    Structure,
    EmptyArc,
    Cycle,
    LevelMismatch,
    /// A root with a floor, a drain with a ceiling, a collapse without floor or ceiling,
    /// or no root/drain at all.
    FragmentKind,
    ErrorValue,
    ErrorNotMonotone,
    TetOrientation,
    /// Within a floor or a ceiling, a face shared by two tets with the same orientation.
    FragmentNotConforming,
    /// Floor and ceiling with different boundary triangles.
    FragmentBoundary,
    BboxMismatch,
    /// The finest or coarsest frontier is not a valid mesh.
    Frontier,
}

/// One violation class: how many instances, and the first few.
#[derive(Clone, Debug, PartialEq)]
pub struct MtViolation {
    pub kind: MtViolationKind,
    pub count: usize,
    pub examples: Vec<String>,
}

/// Everything [`Mt::validate`] found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MtValidationReport {
    pub violations: Vec<MtViolation>,
}

impl MtValidationReport {
    fn add(&mut self, kind: MtViolationKind, example: impl FnOnce() -> String) {
        match self.violations.iter_mut().find(|v| v.kind == kind) {
            Some(v) => {
                v.count += 1;
                if v.examples.len() < EXAMPLES {
                    v.examples.push(example());
                }
            }
            None => self.violations.push(MtViolation {
                kind,
                count: 1,
                examples: vec![example()],
            }),
        }
    }

    pub fn is_valid(&self) -> bool {
        self.violations.is_empty()
    }

    pub fn count(&self, kind: MtViolationKind) -> usize {
        self.violations
            .iter()
            .find(|v| v.kind == kind)
            .map_or(0, |v| v.count)
    }
}

impl fmt::Display for MtValidationReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.violations.is_empty() {
            return write!(f, "valid MT");
        }
        let lines: Vec<String> = self.violations.iter().map(|v| v.to_string()).collect();
        write!(f, "invalid MT: {}", lines.join("; "))
    }
}

impl fmt::Display for MtViolation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} × {:?} (first: {})",
            self.count,
            self.kind,
            self.examples.join("; ")
        )
    }
}

/// An oriented triangle as one sortable key: its vertices in increasing order, then one bit
/// for the orientation (0 when `oriented_face` gives them in that order). The two
/// orientations of a triangle sort next to each other, so one sort pairs every face with
/// its opposite (no search), and sorting one integer is faster than sorting triples.
fn face_key(t: Tet, f: [usize; 3]) -> u128 {
    let [a, b, c] = oriented_face(t[f[0]].0, t[f[1]].0, t[f[2]].0);
    let (lo, hi, flipped) = if b < c { (b, c, 0) } else { (c, b, 1) };
    (u128::from(a) << 65) | (u128::from(lo) << 33) | (u128::from(hi) << 1) | flipped
}

/// The outward faces of `tets` that are not matched by an opposite face of another of
/// them (the boundary, as sorted [`face_key`]s), and the number of faces met twice with
/// one orientation.
fn boundary_of(tets: impl Iterator<Item = Tet>, buf: &mut Vec<u128>) -> (Vec<u128>, usize) {
    buf.clear();
    for t in tets {
        buf.extend(TET_FACES.map(|f| face_key(t, f)));
    }
    buf.sort_unstable();
    let mut same = 0;
    let mut out = Vec::new();
    // Runs of one triangle: a face is on the boundary when its opposite is absent.
    let mut i = 0;
    while i < buf.len() {
        let tri = buf[i] >> 1;
        let end = i + buf[i..].iter().take_while(|&&k| k >> 1 == tri).count();
        let run = &buf[i..end];
        same += run.windows(2).filter(|w| w[0] == w[1]).count();
        if run.first().map(|k| k & 1) == run.last().map(|k| k & 1) {
            out.extend_from_slice(run);
        }
        i = end;
    }
    (out, same)
}

/// What [`Mt::validate`] found in one fragment's floor and ceiling.
struct FragmentCheck {
    /// Faces met twice with one orientation, in the floor and in the ceiling.
    doubled: (usize, usize),
    /// Boundary triangles of the floor and of the ceiling.
    boundaries: (usize, usize),
    boundary_differs: bool,
    bbox_differs: bool,
}

impl FragmentCheck {
    fn is_ok(&self) -> bool {
        self.doubled == (0, 0) && !self.boundary_differs && !self.bbox_differs
    }
}

impl Mt {
    /// Fragment `f`'s floor and ceiling: each conforming, the same boundary, and the
    /// fragment's box theirs. `buf` is scratch space.
    fn check_fragment(&self, f: usize, buf: &mut Vec<u128>) -> FragmentCheck {
        let fid = FragmentId::from_usize(f);
        // The box grows as the faces are listed: one pass over each side's tets.
        let mut b = Aabb::EMPTY;
        let mut grow = |t: &Tet| {
            for v in t.iter().filter(|v| **v != GHOST) {
                b.grow(self.positions[v.idx()]);
            }
        };
        let floor = self.destroyed_tets(fid).map(|t| self.tet(t));
        let (floor_b, floor_same) = boundary_of(floor.inspect(&mut grow), buf);
        let ceiling = self.created_tets(fid).map(|t| self.tet(t));
        let (ceil_b, ceil_same) = boundary_of(ceiling.inspect(&mut grow), buf);
        FragmentCheck {
            doubled: (floor_same, ceil_same),
            boundaries: (floor_b.len(), ceil_b.len()),
            boundary_differs: floor_b != ceil_b,
            bbox_differs: self.frame.enclose(&b) != self.bbox[f],
        }
    }

    /// Checks every invariant (see the [module docs](self)); tests call it after every
    /// operation. Exhaustive: linear-logarithmic in the pool size, plus two extractions.
    pub fn validate(&self) -> MtValidationReport {
        let mut r = MtValidationReport::default();
        let nf = self.nb_fragments();
        let na = self.nb_arcs();
        // Structure: what `assemble` checked, re-checked (the store is private, but this is
        // the exhaustive check).
        let parts_ok = self.arc_start.len() == na + 1
            && self.arc_destroyer.len() == na
            && self.arc_start.first() == Some(&0)
            && self.arc_start.last().map(|&s| s as usize) == Some(self.nb_tets())
            && self.arc_start.windows(2).all(|w| w[0] <= w[1])
            && self.out_start.len() == nf + 1
            && self.out_start.first() == Some(&0)
            && self.out_start.last().map(|&s| s as usize) == Some(na)
            && self.out_start.windows(2).all(|w| w[0] <= w[1])
            && self.error.len() == nf
            && self.level.len() == nf
            && self.bbox.len() == nf
            && self.point_data.mismatched(self.nb_vertices()).is_none()
            && self.cell_data.mismatched(self.nb_tets()).is_none();
        if !parts_ok {
            r.add(MtViolationKind::Structure, || {
                "column lengths or arc starts inconsistent".into()
            });
            return r;
        }
        let mut prev: Option<(FragmentId, FragmentId)> = None;
        for (a, c, d) in self.arcs() {
            if d.idx() >= nf || c == d || prev.is_some_and(|p| p >= (c, d)) {
                r.add(MtViolationKind::Structure, || {
                    format!("arc {a}: {c} → {d}, after {prev:?} in (creator, destroyer) order")
                });
            }
            if self.arc_tets(a).is_empty() {
                r.add(MtViolationKind::EmptyArc, || format!("arc {a}: {c} → {d}"));
            }
            prev = Some((c, d));
        }
        // The predecessor lists are the arcs seen from their destroyers.
        let mut preds = 0;
        for f in 0..nf {
            let fid = FragmentId::from_usize(f);
            for c in self.predecessors(fid) {
                preds += 1;
                if c as usize >= nf || self.arc_between(FragmentId(c), fid).is_none() {
                    r.add(MtViolationKind::Structure, || {
                        format!("fragment {f} lists predecessor {c} without an arc from it")
                    });
                }
            }
        }
        if preds != na {
            r.add(MtViolationKind::Structure, || {
                format!("{preds} predecessors listed for {na} arcs")
            });
        }
        for (t, tet) in self.tets.iter().enumerate() {
            let in_range = tet
                .iter()
                .enumerate()
                .all(|(k, v)| v.idx() < self.nb_vertices() || (*v == GHOST && k == 3));
            let distinct = (0..4).all(|i| (i + 1..4).all(|j| tet[i] != tet[j]));
            if !in_range || !distinct {
                r.add(MtViolationKind::Structure, || format!("tet {t} {tet:?}"));
            }
        }
        if !r.is_valid() {
            return r;
        }
        // Kinds and the DAG.
        // Each independent MT (DAG component) has its roots and drains; a cut may split a
        // root or a drain without separating the whole DAG.
        let (nc, label) = self.fragment_components();
        let mut has = vec![(false, false); nc];
        for &f in &self.roots {
            has[label[f.idx()] as usize].0 = true;
        }
        for &f in &self.drains {
            has[label[f.idx()] as usize].1 = true;
        }
        for (k, &(root, drain)) in has.iter().enumerate() {
            if !(root && drain) {
                r.add(MtViolationKind::FragmentKind, || {
                    format!("component {k}: root {root}, drain {drain}")
                });
            }
        }
        for f in 0..nf {
            let fid = FragmentId::from_usize(f);
            let (floor, ceiling) = (self.predecessors(fid).len(), self.out_arcs(fid).len());
            let bad = match self.kind[f] {
                FragmentKind::Root => floor > 0 || ceiling == 0,
                FragmentKind::Drain => ceiling > 0 || floor == 0,
                FragmentKind::Collapse => floor == 0 || ceiling == 0,
            };
            if bad {
                r.add(MtViolationKind::FragmentKind, || {
                    format!(
                        "{:?} fragment {f} with {floor} in-arcs, {ceiling} out-arcs",
                        self.kind[f]
                    )
                });
            }
        }
        match super::levels(nf, &self.preds) {
            None => r.add(MtViolationKind::Cycle, || "the DAG has a cycle".into()),
            Some(levels) => {
                for f in (0..nf).filter(|&f| levels[f] != self.level[f]) {
                    r.add(MtViolationKind::LevelMismatch, || {
                        format!("fragment {f}: stored {} vs {}", self.level[f], levels[f])
                    });
                }
            }
        }
        // Errors.
        for f in 0..nf {
            let e = self.error[f];
            let ok = match self.kind[f] {
                FragmentKind::Root => e == 0.0,
                FragmentKind::Drain => e == f64::INFINITY,
                FragmentKind::Collapse => e.is_finite() && e >= 0.0,
            };
            if !ok {
                r.add(MtViolationKind::ErrorValue, || {
                    format!("{:?} fragment {f} has error {e}", self.kind[f])
                });
            }
        }
        for (_, c, d) in self.arcs() {
            if self.error[c.idx()] > self.error[d.idx()] {
                r.add(MtViolationKind::ErrorNotMonotone, || {
                    format!(
                        "fragment {d} (error {}) depends on {c} (error {})",
                        self.error[d.idx()],
                        self.error[c.idx()]
                    )
                });
            }
        }
        // Geometry of every tet of every level, and the floor and ceiling of every
        // fragment: on all cores (the pool has millions of tets after a few cuts), the
        // findings gathered in id order so the report is the same on one thread.
        let inverted: Vec<usize> = (0..self.tets.len())
            .into_par_iter()
            .filter(|&t| {
                let tet = self.tets[t];
                tet[3] != GHOST && {
                    let [a, b, c, d] = tet.map(|v| self.positions[v.idx()]);
                    orient3d(a, b, c, d) != Sign::Positive
                }
            })
            .collect();
        for t in inverted {
            r.add(MtViolationKind::TetOrientation, || {
                format!(
                    "tet {t} {:?} (creator {})",
                    self.tets[t],
                    self.tet_creator(TetId::from_usize(t))
                )
            });
        }
        let fragments: Vec<(usize, FragmentCheck)> = (0..nf)
            .into_par_iter()
            .map_init(Vec::new, |buf, f| (f, self.check_fragment(f, buf)))
            .filter(|(_, c)| !c.is_ok())
            .collect();
        for (f, c) in fragments {
            let FragmentCheck {
                doubled: (floor_same, ceil_same),
                boundaries: (floor_len, ceil_len),
                boundary_differs,
                bbox_differs,
            } = c;
            if floor_same + ceil_same > 0 {
                r.add(MtViolationKind::FragmentNotConforming, || {
                    format!(
                        "fragment {f}: {floor_same} floor and {ceil_same} ceiling faces doubled"
                    )
                });
            }
            if boundary_differs {
                r.add(MtViolationKind::FragmentBoundary, || {
                    format!(
                        "{:?} fragment {f}: floor boundary has {floor_len} triangles, \
                         ceiling {ceil_len}",
                        self.kind[f],
                    )
                });
            }
            if bbox_differs {
                r.add(MtViolationKind::BboxMismatch, || format!("fragment {f}"));
            }
        }
        // The extreme frontiers.
        for (name, options) in [
            ("finest", ExtractOptions::FINEST),
            ("coarsest", ExtractOptions::COARSEST),
        ] {
            match self.extract(&options) {
                Ok(e) => {
                    let v = e.mesh.validate();
                    if !v.is_valid() {
                        r.add(MtViolationKind::Frontier, || format!("{name} mesh: {v}"));
                    }
                }
                Err(e) => r.add(MtViolationKind::Frontier, || format!("{name}: {e}")),
            }
        }
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::VertexId;
    use crate::mesh::tables::flip_face;
    use crate::rng::Rng;

    /// The oriented face a [`face_key`] stands for.
    fn face_of(k: u128) -> [u32; 3] {
        let (a, lo, hi) = ((k >> 65) as u32, (k >> 33) as u32, (k >> 1) as u32);
        if k & 1 == 0 { [a, lo, hi] } else { [a, hi, lo] }
    }

    /// `boundary_of` against the definition: every face (with its multiplicity) whose
    /// opposite no tet has, and the faces met twice with one orientation; on random sets of
    /// tets over a few vertices, so that shared, opposite and repeated faces all occur.
    #[test]
    fn boundary_of_follows_its_definition() {
        let mut rng = Rng(7);
        let mut next = |n: u32| rng.below(u64::from(n)) as u32;
        let mut buf = Vec::new();
        for case in 0..2000 {
            let count = 1 + next(8) as usize;
            let tets: Vec<Tet> = (0..count)
                .map(|_| {
                    loop {
                        let t = [next(6), next(6), next(6), next(6)];
                        if (0..4).all(|i| (i + 1..4).all(|j| t[i] != t[j])) {
                            break t.map(VertexId);
                        }
                    }
                })
                .collect();
            let mut faces: Vec<[u32; 3]> = tets
                .iter()
                .flat_map(|t| TET_FACES.map(|f| oriented_face(t[f[0]].0, t[f[1]].0, t[f[2]].0)))
                .collect();
            faces.sort_unstable();
            let same = faces.windows(2).filter(|w| w[0] == w[1]).count();
            let mut expected: Vec<[u32; 3]> = faces
                .iter()
                .copied()
                .filter(|f| faces.binary_search(&flip_face(*f)).is_err())
                .collect();
            expected.sort_unstable();
            let (out, got_same) = boundary_of(tets.iter().copied(), &mut buf);
            let mut got: Vec<[u32; 3]> = out.into_iter().map(face_of).collect();
            got.sort_unstable();
            assert_eq!((got, got_same), (expected, same), "case {case}: {tets:?}");
        }
    }
}
