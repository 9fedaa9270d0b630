//! A frontier kept between extractions, updated incrementally (frame coherence).
//!
//! [`Frontier`] holds the applied/refined state of every fragment and the extracted mesh
//! in *slots*: every tet and vertex keeps its slot while it stays in the mesh, freed slots
//! are reused, so a host can keep per-slot simulation state across updates (and map it
//! with [`Frontier::tet_slots`] / [`Frontier::vertex_slots`], which give pool ids).
//!
//! An update touches only what changes. The fragments whose threshold changed — found
//! among those whose box meets the old or the new focus region (through a BVH over
//! fragment boxes), and those whose error lies between an old and a new uniform threshold
//! (in an error-sorted index) — are the only places a decision can flip; from them:
//! * *refine*: those now wanting refinement, closed under "successor of", un-applied
//!   coarse to fine (each swaps its ceiling for its floor);
//! * *coarsen*: those no longer wanting it, applied fine to coarse (by level) once all the
//!   fragments they depend on are applied, and then their successors in turn.
//!
//! The result is exactly the from-scratch extraction (tests check it on random
//! sequences). Budget requests have no locality: they compute the target set globally and
//! then apply only the difference.

use super::bvh::FragmentBvh;
use super::extract::{ExtractError, ExtractOptions, Extraction, Focus};
use super::{FragmentKind, GHOST, Mt};
use crate::geom::Aabb;
use crate::mesh::{FragmentId, TetId, VertexId};
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::time::Instant;

const NONE: u32 = u32::MAX;

/// What an update changed.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrontierUpdate {
    /// Fragments examined because their threshold may have changed.
    pub candidates: usize,
    /// Fragments un-applied (finer) and applied (coarser).
    pub refined: usize,
    pub coarsened: usize,
    pub tets_added: usize,
    pub tets_removed: usize,
    pub seconds: f64,
}

/// An extracted mesh kept up to date incrementally (see the [module docs](self)).
#[derive(Clone, Debug)]
pub struct Frontier {
    options: ExtractOptions,
    refined: Vec<bool>,
    budget_met: bool,
    // Tets: pool tet → slot, slot → pool tet / creator / local corners.
    slot_of_tet: Vec<u32>,
    tets: Vec<TetId>,
    creators: Vec<FragmentId>,
    local: Vec<[u32; 4]>,
    free_tets: Vec<u32>,
    live_tets: usize,
    // Vertices: pool vertex → slot and number of tets using it (side by side: an update
    // reads both for every corner it touches), slot → pool vertex.
    vertex_state: Vec<VertexState>,
    vertices: Vec<VertexId>,
    free_vertices: Vec<u32>,
    /// Pool vertices whose use count fell to zero during the current update.
    unused: Vec<VertexId>,
    live_vertices: usize,
    // Indexes for finding candidates, built on first need.
    bvh: Option<FragmentBvh>,
    by_error: Option<Vec<u32>>,
    mark: Vec<bool>,
}

impl Frontier {
    /// The frontier `options` ask for, from scratch.
    pub fn new(mt: &Mt, options: &ExtractOptions) -> Result<Frontier, ExtractError> {
        options.check()?;
        let (refined, budget_met) = mt.refined_set(options);
        let mut f = Frontier {
            options: *options,
            refined,
            budget_met,
            slot_of_tet: vec![NONE; mt.nb_tets()],
            tets: Vec::new(),
            creators: Vec::new(),
            local: Vec::new(),
            free_tets: Vec::new(),
            live_tets: 0,
            vertex_state: vec![
                VertexState {
                    slot: NONE,
                    uses: 0
                };
                mt.nb_vertices()
            ],
            vertices: Vec::new(),
            free_vertices: Vec::new(),
            unused: Vec::new(),
            live_vertices: 0,
            bvh: None,
            by_error: None,
            mark: vec![false; mt.nb_fragments()],
        };
        let (tets, creators) = mt.frontier_tets(&f.refined);
        for (t, c) in tets.into_iter().zip(creators) {
            f.add_tet(mt, t, c);
        }
        Ok(f)
    }

    pub fn options(&self) -> &ExtractOptions {
        &self.options
    }

    /// Tets in the mesh.
    pub fn nb_tets(&self) -> usize {
        self.live_tets
    }

    /// Vertices in the mesh.
    pub fn nb_vertices(&self) -> usize {
        self.live_vertices
    }

    /// Whether fragment `f` is refined (not applied).
    pub fn is_refined(&self, f: FragmentId) -> bool {
        self.refined[f.idx()]
    }

    /// `false` when the request's budget could not be met (the coarsest mesh exceeds it).
    pub fn budget_met(&self) -> bool {
        self.budget_met
    }

    /// Pool tet in each tet slot ([`TetId::INVALID`] for a free slot).
    pub fn tet_slots(&self) -> &[TetId] {
        &self.tets
    }

    /// Corners of each tet slot, as vertex slots (meaningless for a free slot).
    pub fn local_tets(&self) -> &[[u32; 4]] {
        &self.local
    }

    /// MT vertex in each vertex slot ([`VertexId::INVALID`] for a free slot).
    pub fn vertex_slots(&self) -> &[VertexId] {
        &self.vertices
    }

    /// The slot of pool tet `t`, if it is in the mesh.
    pub fn slot_of_tet(&self, t: TetId) -> Option<u32> {
        self.slot_of_tet
            .get(t.idx())
            .copied()
            .filter(|&s| s != NONE)
    }

    /// The slot of MT vertex `v`, if it is in the mesh.
    pub fn slot_of_vertex(&self, v: VertexId) -> Option<u32> {
        self.vertex_state
            .get(v.idx())
            .map(|s| s.slot)
            .filter(|&s| s != NONE)
    }

    /// The mesh as an [`Extraction`], in the same order as [`Mt::extract`] gives it (tets by
    /// pool id, vertices by MT id), so the two compare equal.
    pub fn to_extraction(&self, mt: &Mt) -> Extraction {
        let mut pairs: Vec<(TetId, FragmentId)> = self
            .tets
            .iter()
            .zip(&self.creators)
            .filter(|(t, _)| t.is_valid())
            .map(|(t, c)| (*t, *c))
            .collect();
        pairs.sort_unstable_by_key(|p| p.0);
        let (tets, creators): (Vec<TetId>, Vec<FragmentId>) = pairs.into_iter().unzip();
        let mut e = mt.assemble_extraction(&tets, &creators);
        e.stats.refined_fragments = self.refined.iter().filter(|r| **r).count();
        e.stats.budget_met = self.budget_met;
        e
    }

    /// Moves the frontier to what `options` ask for, touching only what changes.
    pub fn update(
        &mut self,
        mt: &Mt,
        options: &ExtractOptions,
    ) -> Result<FrontierUpdate, ExtractError> {
        let start = Instant::now();
        options.check()?;
        let mut stats = FrontierUpdate::default();
        if options.budget.is_some() || self.options.budget.is_some() {
            self.update_globally(mt, options, &mut stats);
        } else {
            self.update_locally(mt, options, &mut stats);
        }
        self.options = *options;
        stats.seconds = start.elapsed().as_secs_f64();
        Ok(stats)
    }

    fn update_globally(&mut self, mt: &Mt, options: &ExtractOptions, stats: &mut FrontierUpdate) {
        let (target, met) = mt.refined_set(options);
        let changed: Vec<u32> = (0..mt.nb_fragments() as u32)
            .filter(|&f| target[f as usize] != self.refined[f as usize])
            .collect();
        stats.candidates = mt.nb_fragments();
        self.refined = target;
        self.apply(mt, &changed, stats);
        self.budget_met = met;
    }

    fn update_locally(&mut self, mt: &Mt, options: &ExtractOptions, stats: &mut FrontierUpdate) {
        let candidates = self.candidates(mt, options);
        stats.candidates = candidates.len();
        // Fragment states first; the mesh follows once, from the net change (a fragment
        // refined through several levels in one update never shows its middle levels).
        let mut changed: Vec<u32> = Vec::new();
        // Refine: candidates now wanting refinement, and everything that depends on them.
        let mut stack: Vec<u32> = candidates
            .iter()
            .filter(|&&(f, wants)| wants && !self.refined[f as usize])
            .map(|&(f, _)| f)
            .collect();
        for &f in &stack {
            self.refined[f as usize] = true;
            changed.push(f);
        }
        while let Some(f) = stack.pop() {
            for a in mt.out_arcs(FragmentId(f)) {
                let d = mt.arc_destroyer(a as usize).0;
                if !self.refined[d as usize] {
                    self.refined[d as usize] = true;
                    changed.push(d);
                    stack.push(d);
                }
            }
        }
        // Coarsen: candidates no longer wanting refinement, fine to coarse (by level),
        // each once all it depends on is applied; applying one may free its successors.
        // Only fragments that may be applied enter the heap (requests do not change
        // during the update, so that is decided once, at the push).
        let coarsenable = |refined: &[bool], f: usize| {
            refined[f] && mt.kind[f] == FragmentKind::Collapse && !mt.wants_refinement(f, options)
        };
        let mut heap: BinaryHeap<Reverse<(u32, u32)>> = candidates
            .iter()
            .filter(|&&(f, wants)| !wants && self.refined[f as usize])
            .map(|&(f, _)| Reverse((mt.level[f as usize], f)))
            .collect();
        while let Some(Reverse((_, f))) = heap.pop() {
            let fu = f as usize;
            // Pushed once per applied predecessor: only the first pop applies it.
            if !self.refined[fu] {
                continue;
            }
            let ready = mt
                .predecessors(FragmentId(f))
                .iter()
                .all(|c| !self.refined[c as usize]);
            if !ready {
                continue;
            }
            self.refined[fu] = false;
            changed.push(f);
            for a in mt.out_arcs(FragmentId(f)) {
                let d = mt.arc_destroyer(a as usize);
                if coarsenable(&self.refined, d.idx()) {
                    heap.push(Reverse((mt.level[d.idx()], d.0)));
                }
            }
        }
        self.apply(mt, &changed, stats);
    }

    /// Brings the mesh in line with the fragment states after the fragments in `changed`
    /// flipped (each listed once per flip). An arc is in the frontier iff its creator is
    /// applied and its destroyer refined; only arcs touching a fragment whose state
    /// differs from before the update can have changed, and each is visited once.
    fn apply(&mut self, mt: &Mt, changed: &[u32], stats: &mut FrontierUpdate) {
        // Net flips: a fragment listed an even number of times is back where it was.
        let mut flipped: Vec<u32> = Vec::with_capacity(changed.len());
        for &f in changed {
            self.mark[f as usize] = !self.mark[f as usize];
        }
        for &f in changed {
            if self.mark[f as usize] {
                flipped.push(f);
                self.mark[f as usize] = false;
            }
        }
        for &f in &flipped {
            self.mark[f as usize] = true;
        }
        let before = |s: &Self, x: FragmentId| s.refined[x.idx()] != s.mark[x.idx()];
        // Arcs entering and leaving the mesh, each with its creator.
        let mut added: Vec<(u32, FragmentId)> = Vec::new();
        let mut removed: Vec<(u32, FragmentId)> = Vec::new();
        for &f in &flipped {
            if self.refined[f as usize] {
                stats.refined += 1;
            } else {
                stats.coarsened += 1;
            }
            let fid = FragmentId(f);
            let outs = mt
                .out_arcs(fid)
                .into_iter()
                .map(|a| (Some(a), fid, mt.arc_destroyer(a as usize)));
            // An arc between two flipped fragments is visited from its creator only.
            let ins = mt
                .predecessors(fid)
                .into_iter()
                .filter(|&c| !self.mark[c as usize])
                .map(|c| (None, FragmentId(c), fid));
            for (arc, c, d) in outs.chain(ins) {
                let was = !before(self, c) && before(self, d);
                let now = !self.refined[c.idx()] && self.refined[d.idx()];
                if now != was {
                    // An in-arc is looked up only when its tets move.
                    let Some(a) = arc.or_else(|| mt.arc_between(c, d).map(|a| a as u32)) else {
                        continue;
                    };
                    if now {
                        added.push((a, c));
                    } else {
                        removed.push((a, c));
                    }
                }
            }
        }
        for &f in &flipped {
            self.mark[f as usize] = false;
        }
        // Removals first, so additions reuse the slots just freed (still in cache); a
        // vertex whose last tet leaves is only released at the end, if no incoming tet
        // took it up again, so a vertex that stays in the mesh keeps its slot.
        for &(a, _) in &removed {
            for t in mt.arc_tets(a as usize) {
                stats.tets_removed += usize::from(self.remove_tet(mt, TetId::from_usize(t)));
            }
        }
        for &(a, c) in &added {
            for t in mt.arc_tets(a as usize) {
                stats.tets_added += usize::from(self.add_tet(mt, TetId::from_usize(t), c));
            }
        }
        let unused = std::mem::take(&mut self.unused);
        for &v in &unused {
            let state = &mut self.vertex_state[v.idx()];
            if state.uses == 0 {
                let s = state.slot;
                state.slot = NONE;
                self.vertices[s as usize] = VertexId::INVALID;
                self.free_vertices.push(s);
                self.live_vertices -= 1;
            }
        }
        self.unused = unused;
        self.unused.clear();
    }

    /// The fragments whose threshold can differ between the current and the new options
    /// (all of them collapses), each with whether it wants refinement under the new ones.
    fn candidates(&mut self, mt: &Mt, new: &ExtractOptions) -> Vec<(u32, bool)> {
        let old = self.options;
        let mut out: Vec<(u32, bool)> = Vec::new();
        let mark = &mut self.mark;
        let mut add = |f: u32, wants: bool, out: &mut Vec<(u32, bool)>| {
            if !mark[f as usize] {
                mark[f as usize] = true;
                out.push((f, wants));
            }
        };
        if old.threshold != new.threshold {
            let by_error = self.by_error.get_or_insert_with(|| {
                let mut v: Vec<u32> = (0..mt.nb_fragments() as u32)
                    .filter(|&f| mt.kind[f as usize] == FragmentKind::Collapse)
                    .collect();
                v.sort_unstable_by(|&a, &b| mt.error[a as usize].total_cmp(&mt.error[b as usize]));
                v
            });
            let (lo, hi) = (
                old.threshold.min(new.threshold),
                old.threshold.max(new.threshold),
            );
            let from = by_error.partition_point(|&f| mt.error[f as usize] <= lo);
            let to = by_error.partition_point(|&f| mt.error[f as usize] <= hi);
            for &f in &by_error[from..to] {
                add(f, mt.wants_refinement(f as usize, new), &mut out);
            }
        }
        if old.focus != new.focus {
            // Only fragments whose threshold differs, in one walk over both regions: a
            // node whose box lies inside both regions with the same focus threshold keeps
            // that threshold for everything under it, so the walk skips the (large)
            // overlap of a focus moved a little.
            let bvh = self.bvh.get_or_insert_with(|| FragmentBvh::new(mt));
            let meets = |f: &Option<Focus>, b: &Aabb| f.is_some_and(|f| f.region.intersects(b));
            let unchanged_inside = match (old.focus, new.focus) {
                (Some(a), Some(b)) if a.threshold == b.threshold => Some((a.region, b.region)),
                _ => None,
            };
            bvh.query(
                |b| {
                    (meets(&old.focus, b) || meets(&new.focus, b))
                        && !unchanged_inside
                            .is_some_and(|(ra, rb)| ra.contains_box(b) && rb.contains_box(b))
                },
                |hit| {
                    let tau = new.tau(&hit.bbox);
                    if old.tau(&hit.bbox) != tau {
                        add(hit.fragment.0, hit.error > tau, &mut out)
                    }
                },
            );
        }
        for &(f, _) in &out {
            self.mark[f as usize] = false;
        }
        out
    }

    /// Puts pool tet `t` (created by `creator`) in the mesh; ghosts are not meshed.
    fn add_tet(&mut self, mt: &Mt, t: TetId, creator: FragmentId) -> bool {
        let tet = mt.tet(t);
        if tet[3] == GHOST {
            return false;
        }
        debug_assert_eq!(self.slot_of_tet[t.idx()], NONE);
        let corners = tet.map(|v| self.use_vertex(v));
        let slot = match self.free_tets.pop() {
            Some(s) => {
                let s = s as usize;
                self.tets[s] = t;
                self.creators[s] = creator;
                self.local[s] = corners;
                s
            }
            None => {
                self.tets.push(t);
                self.creators.push(creator);
                self.local.push(corners);
                self.tets.len() - 1
            }
        };
        self.slot_of_tet[t.idx()] = slot as u32;
        self.live_tets += 1;
        true
    }

    /// Takes pool tet `t` out of the mesh; ghosts (never in it) are skipped.
    fn remove_tet(&mut self, mt: &Mt, t: TetId) -> bool {
        let tet = mt.tet(t);
        if tet[3] == GHOST {
            return false;
        }
        let slot = self.slot_of_tet[t.idx()];
        debug_assert_ne!(slot, NONE, "tet {t} is not in the frontier");
        self.slot_of_tet[t.idx()] = NONE;
        self.tets[slot as usize] = TetId::INVALID;
        self.free_tets.push(slot);
        self.live_tets -= 1;
        for v in tet {
            self.release_vertex(v);
        }
        true
    }

    fn use_vertex(&mut self, v: VertexId) -> u32 {
        let state = &mut self.vertex_state[v.idx()];
        state.uses += 1;
        if state.slot != NONE {
            return state.slot;
        }
        let s = match self.free_vertices.pop() {
            Some(s) => {
                self.vertices[s as usize] = v;
                s
            }
            None => {
                self.vertices.push(v);
                (self.vertices.len() - 1) as u32
            }
        };
        state.slot = s;
        self.live_vertices += 1;
        s
    }

    /// One tet fewer uses `v`; at none it is listed for release at the end of the update.
    fn release_vertex(&mut self, v: VertexId) {
        let state = &mut self.vertex_state[v.idx()];
        state.uses -= 1;
        if state.uses == 0 {
            self.unused.push(v);
        }
    }
}

/// Where a pool vertex sits in the mesh and how many of its tets use it.
#[derive(Clone, Copy, Debug)]
struct VertexState {
    slot: u32,
    uses: u32,
}
