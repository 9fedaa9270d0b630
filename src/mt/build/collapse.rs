//! The half-edge collapse as a local modification (VCGlib's `LocalModification` shape):
//! [`Simplifier::evaluate`] finds a vertex's best legal collapse and its priority,
//! [`Simplifier::is_up_to_date`] tells a queued candidate from a stale one,
//! [`Simplifier::is_feasible`] applies every rule (through [`Simplifier::check`] for queued
//! candidates), [`Simplifier::execute`] performs it and
//! records one fragment (paper §2: destroyed = the star of the removed vertex, created =
//! the tets that replace it).
//!
//! The working mesh is the closed complex: real tets plus ghost tets on the boundary
//! (see the module docs of [`crate::mt`]), so a boundary collapse is the same substitution
//! `v → w` as an interior one, and the link condition covers both.

use super::link::{LinkScratch, link_condition};
use super::surface::{Surface, VertexClass, edge_key, point_triangle_distance};
use crate::geom::{DVec3, Sign, orient3d, triangle_normal};
use crate::mesh::fxhash::FxBuild;
use crate::mesh::tables::TET_FACES;
use crate::mesh::{Tet, VertexId};
use crate::mt::GHOST;
use crate::mt::error::{TetError, TetSample, mean_ratio_cubed};
use rayon::prelude::*;
use std::collections::{HashMap, HashSet};

/// The nearest neighbours a vertex's collapse is tried onto. Each try reads the vertex's
/// whole star, so a vertex of valence V costs V² per evaluation, and it is evaluated
/// again after each collapse around it: the apex of a cone of 2,000 tets took a minute to
/// simplify, of 5,000 most of an hour. The shared meshes and their million-tet versions
/// never give a vertex more than 63 neighbours during simplification, so their MTs are
/// the same with this bound.
const MAX_TARGETS: usize = 128;

/// A queued collapse of `v` onto `w`, valid while neither vertex's star has changed.
#[derive(Clone, Copy, Debug)]
pub(super) struct Candidate {
    pub v: u32,
    pub w: u32,
    /// Largest error of the tets the collapse creates.
    pub priority: f64,
    pub stamp_v: u32,
    pub stamp_w: u32,
    /// Whether the exact rules ([`Simplifier::is_feasible`]) were checked. Candidates whose
    /// priority does not depend on the check (interior vertices, and boundary vertices
    /// under a metric that ignores the boundary deviation) are queued unchecked and checked
    /// once selected for a round: most are invalidated by nearby collapses before then,
    /// and the exact rules are most of the cost.
    pub checked: bool,
    /// Which evaluation of `v` this is (set when queued; see `simplify`).
    pub ticket: u32,
}

impl Candidate {
    /// A placeholder for a vertex without a queued candidate (never read: its ticket is
    /// never live).
    pub const NONE: Candidate = Candidate {
        v: u32::MAX,
        w: u32::MAX,
        priority: f64::INFINITY,
        stamp_v: 0,
        stamp_w: 0,
        checked: false,
        ticket: u32::MAX,
    };
}

/// Why candidate collapses were turned down, counted for the build statistics.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rejections {
    /// A created tet would be inverted or flat (exact orientation).
    pub orientation: usize,
    /// A created tet would be worse than the quality floor.
    pub quality: usize,
    /// The link condition fails (the collapse would change the topology).
    pub link: usize,
    /// The boundary would move beyond the tolerance, fold, or lose a feature.
    pub boundary: usize,
    /// A value the error metric returned that is not finite and ≥ 0 (the build stops).
    pub bad_error: Option<f64>,
}

impl Rejections {
    pub(super) fn add(&mut self, o: &Rejections) {
        self.orientation += o.orientation;
        self.quality += o.quality;
        self.link += o.link;
        self.boundary += o.boundary;
        self.bad_error = self.bad_error.or(o.bad_error);
    }
}

// Each worker thread's buffers, kept across rounds (their marks are sized to the mesh).
thread_local! {
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::default());
}

/// Runs `f` with this thread's scratch buffers.
pub(super) fn with_scratch<R>(f: impl FnOnce(&mut Scratch) -> R) -> R {
    SCRATCH.with(|s| f(&mut s.borrow_mut()))
}

/// Per-thread buffers for evaluation.
#[derive(Default)]
pub(super) struct Scratch {
    neighbours: Vec<u32>,
    star: Vec<StarTet>,
    failed: Vec<u32>,
    order: Vec<(f64, u32)>,
    link: LinkScratch,
    faces: Vec<NewFace>,
    /// Where the last boundary check put each charged point (an index into `faces`, in
    /// [`Simplifier::for_each_charged_point`]'s order); see [`Simplifier::check`].
    pub placed: Vec<u32>,
}

/// A tet in a vertex's star: its pool id and, inline, its vertices, so that a star is read
/// in one sweep instead of one random pool access per tet (the pool is large and grows at
/// its end, far from the input's tets).
#[derive(Clone, Copy, Debug)]
pub(super) struct Incident {
    pub id: u32,
    pub tet: Tet,
}

/// A non-ghost tet of the star being evaluated, with the plane of its face opposite the
/// vertex.
struct StarTet {
    tet: Tet,
    normal: DVec3,
    anchor: DVec3,
}

/// A boundary triangle a collapse creates: the ghost it comes from, its corners (outward),
/// its distance from the original surface.
#[derive(Clone, Copy, Debug)]
struct NewFace {
    from: u32,
    corners: [u32; 3],
    /// The corners' positions (every charged point is measured against them).
    at: [DVec3; 3],
    deviation: f64,
}

/// The simplifier's state: the MT being recorded (pool with creator/destroyer columns) and
/// the current mesh (stars, boundary bookkeeping).
pub(super) struct Simplifier<'a, E: TetError + ?Sized> {
    pub metric: &'a E,
    /// Positions in the build's own vertex order (spatially sorted, see `setup`).
    pub pos: Vec<DVec3>,
    /// Input bounding-box diagonal and volume (the error's scales).
    pub scale: f64,
    pub volume: f64,
    /// Largest boundary deviation allowed (absolute).
    pub tol: f64,
    /// A new boundary face may turn by at most the feature angle: its cosine.
    pub cos_turn: f64,
    pub min_quality: f64,

    // The recorded MT: every tet ever made, creation order.
    pub tets: Vec<Tet>,
    pub creator: Vec<u32>,
    /// The fragment that destroyed each tet; `u32::MAX` while it is in the current mesh.
    pub destroyer: Vec<u32>,
    /// The floor tet each created tet replaces (`u32::MAX` for the root's tets): cell data
    /// is inherited along it.
    pub source: Vec<u32>,
    /// Per fragment (index = fragment id), the largest error of its created tets.
    pub raw_error: Vec<f64>,

    // The current mesh.
    pub stars: Vec<Vec<Incident>>,
    /// Scratch of `execute_round`: each changed vertex's position in its list.
    pub bucket: Vec<u32>,
    pub stamp: Vec<u32>,
    pub class: Vec<VertexClass>,
    pub features: HashSet<(u32, u32), FxBuild>,
    /// Points of the original boundary surface (removed vertices, centroids and edge
    /// midpoints of original faces gone from the boundary), each charged to a current
    /// boundary face (keyed by its ghost tet) within the tolerance of it: the
    /// original-to-coarse half of the boundary deviation. Faces still original answer for
    /// their own points implicitly.
    pub charges: HashMap<u32, Vec<DVec3>, FxBuild>,
    /// Tets made by the root (input tets and their ghosts): ids below this.
    pub root_tets: u32,
    pub surface: Surface,
    /// Live non-ghost tets.
    pub live_real: usize,
}

#[inline]
fn is_ghost(t: &Tet) -> bool {
    t[3] == GHOST
}

#[inline]
fn contains(t: &Tet, x: u32) -> bool {
    t.iter().any(|v| v.0 == x)
}

/// `t` with `v` replaced by `w` (orientation kept: the substitution is positional).
#[inline]
fn substitute(t: &Tet, v: u32, w: u32) -> Tet {
    t.map(|x| if x.0 == v { VertexId(w) } else { x })
}

impl<E: TetError + ?Sized> Simplifier<'_, E> {
    #[inline]
    fn corners(&self, t: &Tet) -> [DVec3; 4] {
        t.map(|x| self.pos[x.idx()])
    }

    fn sample(&self, corners: [DVec3; 4], deviation: f64) -> TetSample {
        TetSample {
            corners,
            boundary_deviation: deviation,
            scale: self.scale,
            volume: self.volume,
        }
    }

    /// Whether a queued candidate still describes the current mesh.
    pub(super) fn is_up_to_date(&self, c: &Candidate) -> bool {
        self.class[c.v as usize] != VertexClass::Removed
            && self.class[c.w as usize] != VertexClass::Removed
            && self.stamp[c.v as usize] == c.stamp_v
            && self.stamp[c.w as usize] == c.stamp_w
    }

    /// Whether `vw` is a boundary edge: some ghost around `v` contains `w`.
    fn is_boundary_edge(&self, v: u32, w: u32) -> bool {
        self.stars[v as usize]
            .iter()
            .any(|inc| is_ghost(&inc.tet) && contains(&inc.tet, w))
    }

    /// The directions `v` may collapse in, by its role: anywhere from the interior, along
    /// the boundary from a smooth boundary vertex, along its feature line from a crease
    /// vertex (`line` holds its two feature neighbours), nowhere from a corner.
    fn allowed(&self, v: u32, w: u32, line: &[u32]) -> bool {
        match self.class[v as usize] {
            VertexClass::Interior => true,
            VertexClass::Smooth => {
                self.class[w as usize] != VertexClass::Interior && self.is_boundary_edge(v, w)
            }
            // Along the line, unless the line is a triangle v, w, x: collapsing it would
            // leave w and x with one feature edge each.
            VertexClass::Crease => {
                line.contains(&w)
                    && line
                        .iter()
                        .all(|&x| x == w || !self.features.contains(&edge_key(w, x)))
            }
            VertexClass::Corner | VertexClass::Removed => false,
        }
    }

    /// The neighbours of `v` joined to it by a feature edge.
    fn feature_neighbours(&self, v: u32, neighbours: &[u32]) -> Vec<u32> {
        neighbours
            .iter()
            .copied()
            .filter(|&x| self.features.contains(&edge_key(v, x)))
            .collect()
    }

    /// The best legal collapse of `v` (lowest priority), or `None`.
    ///
    /// Priorities come from floating-point volumes and errors. With `checked`, the exact
    /// rules then run on the best direction (they rarely fail; on failure the next best is
    /// tried); without, the best is returned unchecked (see [`Candidate::checked`]) unless
    /// the metric needs the boundary deviation, which only the check measures. The search
    /// is branch and bound: directions are tried shortest edge first, and one is abandoned
    /// as soon as a tet's error reaches the best priority so far.
    pub(super) fn evaluate(
        &self,
        v: u32,
        checked: bool,
        s: &mut Scratch,
        rej: &mut Rejections,
    ) -> Option<Candidate> {
        if matches!(
            self.class[v as usize],
            VertexClass::Corner | VertexClass::Removed
        ) {
            return None;
        }
        let pv = self.pos[v as usize];
        s.neighbours.clear();
        s.star.clear();
        s.link.begin(self.pos.len());
        for inc in &self.stars[v as usize] {
            let tet = inc.tet;
            for x in &tet {
                if x.0 != v && s.link.insert(x.0) && *x != GHOST {
                    s.neighbours.push(x.0);
                }
            }
            if is_ghost(&tet) {
                continue;
            }
            // The tet's volume is linear in v's position: (n · (x - a)) / 6 with n the
            // inward normal of the face opposite v.
            let k = tet.iter().position(|x| x.0 == v).unwrap_or(0);
            let [i, j, l] = TET_FACES[k];
            let (a, b, c) = (
                self.pos[tet[i].idx()],
                self.pos[tet[j].idx()],
                self.pos[tet[l].idx()],
            );
            s.star.push(StarTet {
                tet,
                normal: (c - a).cross(b - a),
                anchor: a,
            });
        }
        let line = if self.class[v as usize] == VertexClass::Crease {
            self.feature_neighbours(v, &s.neighbours)
        } else {
            Vec::new()
        };
        s.order.clear();
        for &w in &s.neighbours {
            if self.allowed(v, w, &line) {
                let d = (self.pos[w as usize] - pv).length_squared();
                s.order.push((d, w));
            }
        }
        s.order
            .sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        s.order.truncate(MAX_TARGETS);
        // Boundary vertices are checked at once when the metric's priority depends on the
        // boundary deviation (which only the check measures).
        let ranked_before_check = self.class[v as usize] == VertexClass::Interior
            || !self.metric.uses_boundary_deviation();
        let order = std::mem::take(&mut s.order);
        let best = if ranked_before_check {
            self.best_ranked(v, &order, checked, s, rej)
        } else {
            self.best_boundary(v, &order, s, rej)
        };
        s.order = order;
        best
    }

    /// The largest error of the tets collapsing `v` onto `w` creates, or `None` if one is
    /// inverted or flat (floating point) or, with `bound`, as soon as an error reaches it.
    fn cheap_priority(
        &self,
        v: u32,
        w: u32,
        s: &Scratch,
        bound: f64,
        rej: &mut Rejections,
    ) -> Option<f64> {
        let pw = self.pos[w as usize];
        let mut priority = 0.0f64;
        // One pass: a direction is dropped at its first inverted tet or, once it cannot
        // beat the bound, at its first tet reaching it.
        for st in &s.star {
            if contains(&st.tet, w) {
                continue;
            }
            if st.normal.dot(pw - st.anchor) <= 0.0 {
                rej.orientation += 1;
                return None;
            }
            let c = self.corners(&substitute(&st.tet, v, w));
            let e = self.metric.tet_error(&self.sample(c, 0.0));
            if !(e.is_finite() && e >= 0.0) {
                rej.bad_error.get_or_insert(e);
                return None;
            }
            priority = priority.max(e);
            if priority >= bound {
                return None;
            }
        }
        Some(priority)
    }

    fn candidate(&self, v: u32, w: u32, priority: f64, checked: bool) -> Candidate {
        Candidate {
            v,
            w,
            priority,
            stamp_v: self.stamp[v as usize],
            stamp_w: self.stamp[w as usize],
            checked,
            ticket: 0,
        }
    }

    /// A queued candidate, checked against the exact rules: itself (with its exact
    /// priority) if it passes, else the best candidate of its vertex that passes them all.
    /// When it passes, `s.placed` holds where its boundary points go (what
    /// [`Simplifier::execute`] needs): the placement is worked out here, in the round's
    /// parallel checks, instead of again in the sequential execution.
    pub(super) fn check(
        &self,
        c: &Candidate,
        s: &mut Scratch,
        rej: &mut Rejections,
    ) -> Option<Candidate> {
        s.placed.clear();
        if c.checked {
            // Checked when evaluated, and nothing around it changed since: the boundary
            // check passes again and places the points.
            if self.class[c.v as usize] != VertexClass::Interior {
                s.faces.clear();
                let passed = self.boundary_check(c.v, c.w, s);
                debug_assert!(passed, "a checked candidate fails its boundary check");
            }
            return Some(*c);
        }
        // The link test needs v's neighbour set, which evaluation leaves in the scratch of
        // the thread that evaluated; this may be another thread.
        s.link.begin(self.pos.len());
        for inc in &self.stars[c.v as usize] {
            for x in &inc.tet {
                if x.0 != c.v {
                    s.link.insert(x.0);
                }
            }
        }
        match self.is_feasible(c.v, c.w, s, rej) {
            Some(priority) => Some(Candidate {
                priority,
                checked: true,
                ..*c
            }),
            None => {
                let mut c = self.evaluate(c.v, true, s, rej)?;
                c.checked = true;
                Some(c)
            }
        }
    }

    /// Branch and bound over the directions of `v`, ranked by the errors alone; with
    /// `checked`, the best is checked against the exact rules (and the next best tried on
    /// failure).
    fn best_ranked(
        &self,
        v: u32,
        order: &[(f64, u32)],
        checked: bool,
        s: &mut Scratch,
        rej: &mut Rejections,
    ) -> Option<Candidate> {
        s.failed.clear();
        loop {
            let mut best: Option<(f64, u32)> = None;
            for &(_, w) in order {
                if s.failed.contains(&w) {
                    continue;
                }
                let bound = best.map_or(f64::INFINITY, |b| b.0);
                if let Some(p) = self.cheap_priority(v, w, s, bound, rej) {
                    best = Some((p, w));
                }
            }
            let (priority, w) = best?;
            if !checked {
                return Some(self.candidate(v, w, priority, false));
            }
            match self.is_feasible(v, w, s, rej) {
                Some(priority) => return Some(self.candidate(v, w, priority, true)),
                None => s.failed.push(w),
            }
        }
    }

    /// Boundary vertices: the exact priority depends on the boundary deviation, so the
    /// cheap priorities are lower bounds; feasible directions are tried in their order
    /// until the bound reaches the best found.
    fn best_boundary(
        &self,
        v: u32,
        order: &[(f64, u32)],
        s: &mut Scratch,
        rej: &mut Rejections,
    ) -> Option<Candidate> {
        let mut bounds: Vec<(f64, u32)> = order
            .iter()
            .filter_map(|&(_, w)| {
                self.cheap_priority(v, w, s, f64::INFINITY, rej)
                    .map(|p| (p, w))
            })
            .collect();
        bounds.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut best: Option<Candidate> = None;
        for (lower_bound, w) in bounds {
            if best.is_some_and(|b| lower_bound >= b.priority) {
                break;
            }
            if let Some(priority) = self.is_feasible(v, w, s, rej) {
                if best.is_none_or(|b| priority < b.priority) {
                    best = Some(self.candidate(v, w, priority, true));
                }
            }
        }
        best
    }

    /// Every rule for collapsing `v` onto `w`; on success the collapse's priority (the
    /// largest error of the tets it creates, boundary deviation included).
    pub(super) fn is_feasible(
        &self,
        v: u32,
        w: u32,
        s: &mut Scratch,
        rej: &mut Rejections,
    ) -> Option<f64> {
        let star = &self.stars[v as usize];
        // No created tet may be inverted or flat: exact orientation. No created tet may be
        // worse than the quality floor, unless the star already was.
        let mut worst_new = f64::INFINITY;
        let mut worst_old = f64::INFINITY;
        for inc in star {
            let tet = &inc.tet;
            if is_ghost(tet) {
                continue;
            }
            worst_old = worst_old.min(mean_ratio_cubed(self.corners(tet)));
            if contains(tet, w) {
                continue;
            }
            let c = self.corners(&substitute(tet, v, w));
            if orient3d(c[0], c[1], c[2], c[3]) != Sign::Positive {
                rej.orientation += 1;
                return None;
            }
            worst_new = worst_new.min(mean_ratio_cubed(c));
        }
        if worst_new < self.min_quality.powi(3).min(worst_old) {
            rej.quality += 1;
            return None;
        }
        if !link_condition(star, &self.stars[w as usize], v, w, &mut s.link) {
            rej.link += 1;
            return None;
        }
        s.faces.clear();
        if self.class[v as usize] != VertexClass::Interior && !self.boundary_check(v, w, s) {
            rej.boundary += 1;
            return None;
        }
        // The priority, now with the deviation of the boundary faces each tet gets.
        let mut priority = 0.0f64;
        for inc in star {
            let tet = &inc.tet;
            if is_ghost(tet) || contains(tet, w) {
                continue;
            }
            let nt = substitute(tet, v, w);
            let mut deviation = 0.0f64;
            for f in &s.faces {
                if f.corners.iter().all(|x| contains(&nt, *x)) {
                    deviation = deviation.max(f.deviation);
                }
            }
            let e = self
                .metric
                .tet_error(&self.sample(self.corners(&nt), deviation));
            if !(e.is_finite() && e >= 0.0) {
                rej.bad_error.get_or_insert(e);
                return None;
            }
            priority = priority.max(e);
        }
        Some(priority)
    }

    /// The boundary rules for a boundary vertex `v` collapsing onto `w`: every new boundary
    /// face non-degenerate and turned by at most the feature angle from the face it
    /// replaces; every original boundary vertex this patch answers for within the tolerance
    /// of the new faces; sample points of the new faces within the tolerance of the
    /// original surface. Fills `s.faces` with the new faces and their deviations.
    fn boundary_check(&self, v: u32, w: u32, s: &mut Scratch) -> bool {
        let star = &self.stars[v as usize];
        for inc in star {
            let g = &inc.tet;
            if !is_ghost(g) || contains(g, w) {
                continue;
            }
            let old = [g[0].0, g[1].0, g[2].0];
            let new = old.map(|x| if x == v { w } else { x });
            let p = |f: [u32; 3]| f.map(|x| self.pos[x as usize]);
            let (po, pn) = (p(old), p(new));
            let (no, nn) = (
                triangle_normal(po[0], po[1], po[2]),
                triangle_normal(pn[0], pn[1], pn[2]),
            );
            let len = nn.length() * no.length();
            let degenerate = len.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater);
            if degenerate || nn.dot(no) < self.cos_turn * len {
                return false;
            }
            // Coarse-to-original: points of the new face on a grid (its corners are
            // original vertices, on the original surface by definition).
            let seeds = [new[0], new[1], new[2], v];
            let Some(deviation) = self.surface.grid_within(pn, self.tol, &seeds) else {
                return false;
            };
            s.faces.push(NewFace {
                from: inc.id,
                corners: new,
                at: pn,
                deviation,
            });
        }
        if s.faces.is_empty() {
            return false;
        }
        // Original-to-coarse: every point of the original surface this patch answers for
        // within the tolerance of the new faces.
        let mut ok = true;
        s.placed.clear();
        self.for_each_charged_point(v, |from, q| {
            if !ok {
                return;
            }
            match self.place(&s.faces, from, q) {
                Some((k, d)) => {
                    s.faces[k].deviation = s.faces[k].deviation.max(d);
                    s.placed.push(k as u32);
                }
                None => ok = false,
            }
        });
        ok
    }

    /// The new face a point charged to ghost `from` goes to, and its distance: the face
    /// made from `from` when the point is within the tolerance of it (an upper bound of the
    /// distance to the patch, enough for every decision), else the nearest; `None` when
    /// even that is beyond the tolerance.
    fn place(&self, faces: &[NewFace], from: u32, q: DVec3) -> Option<(usize, f64)> {
        if let Some(k) = faces.iter().position(|f| f.from == from) {
            let d = point_triangle_distance(q, &faces[k].at);
            if d <= self.tol {
                return Some((k, d));
            }
        }
        let mut best = (0, f64::INFINITY);
        for (k, f) in faces.iter().enumerate() {
            let d = point_triangle_distance(q, &f.at);
            if d < best.1 {
                best = (k, d);
            }
        }
        (best.1 <= self.tol).then_some(best)
    }

    /// The points of the original surface the ghosts around `v` answer for, with the ghost
    /// each is charged to (`u32::MAX` for `v` itself): `v`; for a ghost still an original
    /// face (made by the root), its centroid and the midpoints of the edges it owns (an
    /// edge is owned by the face that runs it from its lower to its higher vertex id);
    /// for other ghosts, the points charged to them when they were made.
    fn for_each_charged_point(&self, v: u32, mut f: impl FnMut(u32, DVec3)) {
        f(u32::MAX, self.pos[v as usize]);
        for inc in &self.stars[v as usize] {
            if !is_ghost(&inc.tet) {
                continue;
            }
            if inc.id < self.root_tets {
                let c = [inc.tet[0].0, inc.tet[1].0, inc.tet[2].0];
                let p = c.map(|x| self.pos[x as usize]);
                f(inc.id, (p[0] + p[1] + p[2]) / 3.0);
                for k in 0..3 {
                    if c[k] < c[(k + 1) % 3] {
                        f(inc.id, (p[k] + p[(k + 1) % 3]) * 0.5);
                    }
                }
            } else if let Some(points) = self.charges.get(&inc.id) {
                for q in points {
                    f(inc.id, *q);
                }
            }
        }
    }

    /// Performs the collapses of one round (independent: disjoint floors, none consuming
    /// another's ceiling), recording one fragment each, in order. The bookkeeping is
    /// sequential; the stars, where the time goes (one cache miss per star), are updated
    /// in one parallel pass: a tet leaves a star iff it has a vertex removed in this round,
    /// and new tets join the stars of their vertices in pool order, exactly as one collapse
    /// after the other would leave them. The vertices whose star changed are put in
    /// `changed` (sorted).
    pub(super) fn execute_round(
        &mut self,
        round: &[(Candidate, Vec<u32>)],
        changed: &mut Vec<u32>,
    ) {
        changed.clear();
        let mut incoming: Vec<(u32, Incident)> = Vec::new();
        for (c, placed) in round {
            self.execute(c, placed, changed, &mut incoming);
        }
        changed.sort_unstable();
        changed.dedup();
        // The new incidences by vertex (every vertex of a new tet is in `changed`), each
        // vertex's in pool order, by a counting sort: `incoming` is already in pool order.
        for (k, &x) in changed.iter().enumerate() {
            self.bucket[x as usize] = k as u32;
        }
        let mut start = vec![0u32; changed.len() + 1];
        for (x, _) in &incoming {
            debug_assert!(changed.binary_search(x).is_ok(), "vertex {x} of a new tet");
            start[self.bucket[*x as usize] as usize + 1] += 1;
        }
        for k in 0..changed.len() {
            start[k + 1] += start[k];
        }
        let mut fill = start.clone();
        let mut sorted: Vec<Incident> = incoming.iter().map(|p| p.1).collect();
        for (x, inc) in &incoming {
            let k = &mut fill[self.bucket[*x as usize] as usize];
            sorted[*k as usize] = *inc;
            *k += 1;
        }
        // The changed stars are taken out, updated in parallel and put back.
        let mut work: Vec<Vec<Incident>> = changed
            .iter()
            .map(|&x| std::mem::take(&mut self.stars[x as usize]))
            .collect();
        let class = &self.class;
        work.par_iter_mut().enumerate().for_each(|(k, star)| {
            star.retain(|inc| {
                !inc.tet
                    .iter()
                    .any(|y| *y != GHOST && class[y.idx()] == VertexClass::Removed)
            });
            star.extend_from_slice(&sorted[start[k] as usize..start[k + 1] as usize]);
        });
        for (&x, star) in changed.iter().zip(work) {
            self.stars[x as usize] = star;
            self.stamp[x as usize] = self.stamp[x as usize].wrapping_add(1);
        }
    }

    /// Collapses `c.v` onto `c.w`, recording the next fragment: the record and the
    /// boundary bookkeeping; the stars of the other vertices are left to `execute_round`
    /// (their new incidences go to `incoming`, the vertices to `changed`).
    /// `placed`: where the check put each point the boundary patch answers for (see
    /// [`Simplifier::check`]).
    fn execute(
        &mut self,
        c: &Candidate,
        placed: &[u32],
        changed: &mut Vec<u32>,
        incoming: &mut Vec<(u32, Incident)>,
    ) {
        let fragment = self.raw_error.len() as u32;
        let (v, w) = (c.v, c.w);
        let v_class = self.class[v as usize];
        let boundary = v_class != VertexClass::Interior;
        // The points of the original surface this patch answers for, by the new boundary
        // face they are charged to from now on (the new ghosts, in floor order).
        let mut per_face: Vec<Vec<DVec3>> = Vec::new();
        if boundary {
            let faces = self.stars[v as usize]
                .iter()
                .filter(|inc| is_ghost(&inc.tet) && !contains(&inc.tet, w))
                .count();
            per_face.resize_with(faces, Vec::new);
            let mut i = 0;
            self.for_each_charged_point(v, |_, q| {
                per_face[placed[i] as usize].push(q);
                i += 1;
            });
            debug_assert_eq!(i, placed.len(), "the check placed other points");
        }
        let floor = std::mem::take(&mut self.stars[v as usize]);
        let first_changed = changed.len();
        for inc in &floor {
            let (t, tet) = (inc.id, inc.tet);
            for x in tet {
                if x.0 != v && x != GHOST {
                    changed.push(x.0);
                }
            }
            self.destroyer[t as usize] = fragment;
            if boundary && is_ghost(&tet) {
                self.charges.remove(&t);
            }
            if !is_ghost(&tet) && contains(&tet, w) {
                self.live_real -= 1;
            }
        }
        let mut new_ghosts: Vec<u32> = Vec::new();
        for inc in &floor {
            let (t, tet) = (inc.id, inc.tet);
            if contains(&tet, w) {
                continue;
            }
            let nt = substitute(&tet, v, w);
            let id = self.tets.len() as u32;
            self.tets.push(nt);
            self.creator.push(fragment);
            self.destroyer.push(u32::MAX);
            self.source.push(t);
            for x in nt {
                if x != GHOST {
                    incoming.push((x.0, Incident { id, tet: nt }));
                }
            }
            if is_ghost(&nt) {
                new_ghosts.push(id);
            }
        }
        self.class[v as usize] = VertexClass::Removed;
        self.stamp[v as usize] = self.stamp[v as usize].wrapping_add(1);
        if v_class == VertexClass::Crease {
            // Moving along the feature line: v's other feature edge now starts at w.
            let line = self.feature_neighbours(v, &changed[first_changed..]);
            for &x in &line {
                self.features.remove(&edge_key(v, x));
                if x != w {
                    self.features.insert(edge_key(w, x));
                }
            }
        }
        for (g, points) in new_ghosts.into_iter().zip(per_face) {
            if !points.is_empty() {
                self.charges.insert(g, points);
            }
        }
        self.raw_error.push(c.priority);
    }
}
