//! Selective refinement over the DAG: which fragments to apply for a requested resolution,
//! and the mesh of the resulting frontier.
//!
//! A request ([`ExtractOptions`]) gives a threshold `τ(f)` for every fragment: the focus
//! threshold if the fragment's box meets the focus region, the uniform threshold elsewhere.
//! A collapse fragment *wants refinement* when its error exceeds `τ(f)`; the drain always
//! does, roots never. The refined set `U` is the closure of those under "successor of"
//! (a fragment consuming tets of a refined fragment must be refined too), and the frontier
//! is every arc from an applied fragment into `U`. Because errors grow along the DAG, for
//! a uniform threshold this is exactly "every fragment of error ≤ ε applied": the coarsest
//! frontier whose tets all have error ≤ ε.
//!
//! With a budget, fragments are refined in decreasing order of demand (error ÷ threshold,
//! raised along the DAG, ties by error then level) while the mesh stays within the budget,
//! and never beyond what the thresholds ask: the budget caps the threshold extraction.

use super::bvh::Region;
use super::{FragmentKind, Mt};
use crate::geom::Aabb;
use crate::mesh::{Attribute, Attributes, FragmentId, Tet, TetId, TetMesh, VertexId};
use rayon::prelude::*;
use std::time::Instant;

/// Cell data name: the fragment that created the tet.
pub const CELL_FRAGMENT: &str = "mt_fragment";
/// Cell data name: the error of the fragment that created the tet.
pub const CELL_ERROR: &str = "mt_error";
/// Cell data name: the level (DAG depth) of the fragment that created the tet.
pub const CELL_LEVEL: &str = "mt_level";
/// Point data name: the MT (pool) vertex id of each extracted vertex.
pub const POINT_VERTEX: &str = "mt_vertex";

/// A region with its own threshold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Focus {
    pub region: Region,
    /// Error threshold for fragments whose box meets the region.
    pub threshold: f64,
}

/// What to extract. Defaults ([`ExtractOptions::DEFAULT`]): threshold 0 (the finest mesh),
/// no focus, no budget.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct ExtractOptions {
    /// Uniform error threshold (≥ 0; +∞ gives the coarsest mesh). Default 0.
    pub threshold: f64,
    /// A region with its own threshold. Default none.
    pub focus: Option<Focus>,
    /// At most this many tets. Default none.
    pub budget: Option<usize>,
}

impl ExtractOptions {
    pub const DEFAULT: ExtractOptions = ExtractOptions {
        threshold: 0.0,
        focus: None,
        budget: None,
    };
    /// The full-resolution mesh.
    pub const FINEST: ExtractOptions = ExtractOptions::DEFAULT;
    /// The coarsest mesh.
    pub const COARSEST: ExtractOptions = ExtractOptions {
        threshold: f64::INFINITY,
        focus: None,
        budget: None,
    };

    /// Uniform threshold `e`.
    pub fn threshold(e: f64) -> ExtractOptions {
        ExtractOptions {
            threshold: e,
            ..ExtractOptions::DEFAULT
        }
    }
    pub fn with_threshold(mut self, e: f64) -> Self {
        self.threshold = e;
        self
    }
    pub fn with_focus(mut self, region: Region, threshold: f64) -> Self {
        self.focus = Some(Focus { region, threshold });
        self
    }
    pub fn without_focus(mut self) -> Self {
        self.focus = None;
        self
    }
    pub fn with_budget(mut self, budget: Option<usize>) -> Self {
        self.budget = budget;
        self
    }

    pub(crate) fn check(&self) -> Result<(), ExtractError> {
        let bad = |m: String| Err(ExtractError::InvalidOptions(m));
        let ok_threshold = |t: f64| t >= 0.0; // false for NaN
        if !ok_threshold(self.threshold) {
            return bad(format!("threshold {} (must be ≥ 0)", self.threshold));
        }
        if let Some(f) = &self.focus {
            if !ok_threshold(f.threshold) {
                return bad(format!("focus threshold {} (must be ≥ 0)", f.threshold));
            }
            match f.region {
                Region::Sphere { center, radius } => {
                    if !(center.is_finite() && radius >= 0.0 && radius.is_finite()) {
                        return bad(format!(
                            "focus sphere at {center} with radius {radius} (finite centre, radius ≥ 0)"
                        ));
                    }
                }
                Region::Box(b) => {
                    if !b.min.is_finite() || !b.max.is_finite() || b.is_empty() {
                        return bad(format!(
                            "focus box {} .. {} (finite, min ≤ max)",
                            b.min, b.max
                        ));
                    }
                }
            }
        }
        Ok(())
    }

    /// The threshold that applies to a fragment with box `b`.
    #[inline]
    pub(crate) fn tau(&self, b: &Aabb) -> f64 {
        match &self.focus {
            Some(f) if f.region.intersects(b) => f.threshold,
            _ => self.threshold,
        }
    }
}

impl Default for ExtractOptions {
    fn default() -> Self {
        ExtractOptions::DEFAULT
    }
}

/// Why an extraction was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ExtractError {
    #[error("invalid extraction option: {0}")]
    InvalidOptions(String),
}

/// Numbers about one extraction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExtractStats {
    pub tets: usize,
    pub vertices: usize,
    /// Fragments refined (not applied), drains included.
    pub refined_fragments: usize,
    /// Largest error of the fragments that created the extracted tets.
    pub max_error: f64,
    /// `false` when even the coarsest mesh exceeds the budget (it is returned anyway).
    pub budget_met: bool,
    pub seconds: f64,
}

impl ExtractStats {
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "tets": self.tets,
            "vertices": self.vertices,
            "refined_fragments": self.refined_fragments,
            "max_error": self.max_error,
            "budget_met": self.budget_met,
            "seconds": self.seconds,
        })
    }
}

/// An extracted mesh: a valid [`TetMesh`] with cell data [`CELL_FRAGMENT`], [`CELL_ERROR`],
/// [`CELL_LEVEL`] (plus the input's cell data, inherited) and point data [`POINT_VERTEX`]
/// (plus the input's point data); and the pool ids of its tets and vertices. Tets come in
/// increasing pool id, vertices in increasing MT vertex id.
#[derive(Clone, Debug, PartialEq)]
pub struct Extraction {
    pub mesh: TetMesh,
    /// Pool tet of each mesh tet.
    pub tet_ids: Vec<TetId>,
    /// MT vertex of each mesh vertex.
    pub vertex_ids: Vec<VertexId>,
    pub stats: ExtractStats,
}

impl Mt {
    /// Extracts the mesh `options` ask for (see the [module docs](self)).
    pub fn extract(&self, options: &ExtractOptions) -> Result<Extraction, ExtractError> {
        let start = Instant::now();
        options.check()?;
        let (refined, budget_met) = self.refined_set(options);
        let (tet_ids, creators) = self.frontier_tets(&refined);
        let mut e = self.assemble_extraction(&tet_ids, &creators);
        e.stats.refined_fragments = refined.iter().filter(|r| **r).count();
        e.stats.budget_met = budget_met;
        e.stats.seconds = start.elapsed().as_secs_f64();
        Ok(e)
    }

    /// The pool tets of the mesh [`extract`](Self::extract) gives (its tets in the same
    /// order, by MT vertex), without assembling that mesh.
    pub(crate) fn extract_tets(&self, options: &ExtractOptions) -> Result<Vec<Tet>, ExtractError> {
        options.check()?;
        let (refined, _) = self.refined_set(options);
        let (tet_ids, _) = self.frontier_tets(&refined);
        Ok(tet_ids.iter().map(|t| self.tets[t.idx()]).collect())
    }

    /// Whether fragment `f` wants refinement under `options` (before closure).
    #[inline]
    pub(crate) fn wants_refinement(&self, f: usize, options: &ExtractOptions) -> bool {
        match self.kind[f] {
            FragmentKind::Root => false,
            FragmentKind::Drain => true,
            FragmentKind::Collapse => {
                self.error[f] > options.tau(&self.fragment_bbox(FragmentId::from_usize(f)))
            }
        }
    }

    /// The refined set `U` for `options` (per fragment), and whether the budget was met.
    pub(crate) fn refined_set(&self, options: &ExtractOptions) -> (Vec<bool>, bool) {
        let refined = self.threshold_set(options);
        match options.budget {
            None => (refined, true),
            Some(budget) => self.budget_set(options, refined, budget),
        }
    }

    /// Closure of the fragments wanting refinement under "successor of".
    fn threshold_set(&self, options: &ExtractOptions) -> Vec<bool> {
        let nf = self.nb_fragments();
        let mut refined: Vec<bool> = (0..nf)
            .into_par_iter()
            .map(|f| self.wants_refinement(f, options))
            .collect();
        let mut stack: Vec<u32> = (0..nf as u32).filter(|&f| refined[f as usize]).collect();
        while let Some(f) = stack.pop() {
            for a in self.out_arcs(FragmentId(f)) {
                let d = self.arc_destroyer[a as usize].idx();
                if !refined[d] {
                    refined[d] = true;
                    stack.push(d as u32);
                }
            }
        }
        refined
    }

    /// The longest prefix, in decreasing demand, of the threshold set `wanted` that fits in
    /// `budget` tets. Every prefix of that order is closed under "successor of": a
    /// successor's demand is at least its predecessor's (demand is raised along the DAG),
    /// and on ties its error is at least as large and its level larger.
    fn budget_set(
        &self,
        options: &ExtractOptions,
        wanted: Vec<bool>,
        budget: usize,
    ) -> (Vec<bool>, bool) {
        let nf = self.nb_fragments();
        let mut demand = vec![f64::NEG_INFINITY; nf];
        for f in self.topological_order() {
            let f = f as usize;
            let own = match self.kind[f] {
                FragmentKind::Root => f64::NEG_INFINITY,
                FragmentKind::Drain => f64::INFINITY,
                FragmentKind::Collapse => ratio(
                    self.error[f],
                    options.tau(&self.fragment_bbox(FragmentId::from_usize(f))),
                ),
            };
            demand[f] = self
                .predecessors(FragmentId::from_usize(f))
                .iter()
                .fold(own, |m, c| m.max(demand[c as usize]));
        }
        // Net change in real tets when a fragment is refined: its floor appears, its
        // ceiling goes.
        let mut delta = vec![0i64; nf];
        for (a, c, d) in self.arcs() {
            let real = self.tets[self.arc_tets(a)]
                .iter()
                .filter(|t| t[3] != super::GHOST)
                .count() as i64;
            delta[d.idx()] += real;
            delta[c.idx()] -= real;
        }
        let mut order: Vec<u32> = (0..nf as u32).filter(|&f| wanted[f as usize]).collect();
        order.sort_unstable_by(|&x, &y| {
            let (x, y) = (x as usize, y as usize);
            demand[y]
                .total_cmp(&demand[x])
                .then(self.error[y].total_cmp(&self.error[x]))
                .then(self.level[y].cmp(&self.level[x]))
                .then(x.cmp(&y))
        });
        let mut refined = vec![false; nf];
        // Budgets beyond i64 (a host's SIZE_MAX for "no limit") are no limit: `as` would
        // wrap them negative.
        let budget = i64::try_from(budget).unwrap_or(i64::MAX);
        let mut count = 0i64;
        let mut met = true;
        for &f in &order {
            let f = f as usize;
            let next = count + delta[f];
            if self.kind[f] == FragmentKind::Drain {
                // The coarsest mesh is the least any extraction gives.
                met &= next <= budget;
            } else if next > budget {
                break;
            }
            refined[f] = true;
            count = next;
        }
        (refined, met)
    }

    /// Fragments in increasing level (a topological order).
    pub(crate) fn topological_order(&self) -> Vec<u32> {
        let mut order: Vec<u32> = (0..self.nb_fragments() as u32).collect();
        order.sort_by_key(|&f| self.level[f as usize]);
        order
    }

    /// The non-ghost tets of the frontier of `refined` (arcs from applied fragments into
    /// refined ones), in pool order, with their creators.
    pub(crate) fn frontier_tets(&self, refined: &[bool]) -> (Vec<TetId>, Vec<FragmentId>) {
        // Every frontier arc enters a refined fragment: when the refined fragments have
        // few arcs in (coarse extractions), look there instead of at every arc.
        let refined_list: Vec<u32> = (0..refined.len() as u32)
            .into_par_iter()
            .filter(|&f| refined[f as usize])
            .collect();
        let arcs_in: usize = refined_list
            .iter()
            .map(|&f| self.predecessors(FragmentId(f)).len())
            .sum();
        // (arc, creator) in arc order.
        let arcs: Vec<(u32, FragmentId)> = if arcs_in * 4 < self.nb_arcs() {
            let mut v: Vec<(u32, FragmentId)> = refined_list
                .iter()
                .flat_map(|&f| {
                    self.predecessors(FragmentId(f))
                        .into_iter()
                        .filter(|&c| !refined[c as usize])
                        .filter_map(move |c| {
                            let (c, f) = (FragmentId(c), FragmentId(f));
                            self.arc_between(c, f).map(|a| (a as u32, c))
                        })
                })
                .collect();
            v.sort_unstable_by_key(|p| p.0);
            v
        } else {
            (0..refined.len() as u32)
                .into_par_iter()
                .filter(|&c| !refined[c as usize])
                .flat_map_iter(|c| {
                    self.out_arcs(FragmentId(c))
                        .into_iter()
                        .filter(|&a| refined[self.arc_destroyer[a as usize].idx()])
                        .map(move |a| (a, FragmentId(c)))
                })
                .collect()
        };
        let mut tets = Vec::new();
        let mut creators = Vec::new();
        for &(a, c) in &arcs {
            for t in self.arc_tets(a as usize) {
                if self.tets[t][3] != super::GHOST {
                    tets.push(TetId::from_usize(t));
                    creators.push(c);
                }
            }
        }
        (tets, creators)
    }

    /// The mesh of the given pool tets (in the given order, with their creators): vertices
    /// compacted in increasing MT id, attribute columns attached.
    pub(crate) fn assemble_extraction(
        &self,
        tet_ids: &[TetId],
        creators: &[FragmentId],
    ) -> Extraction {
        let nv = self.nb_vertices();
        let mut local = vec![u32::MAX; nv];
        for t in tet_ids {
            for v in &self.tets[t.idx()] {
                local[v.idx()] = 0;
            }
        }
        let mut vertex_ids = Vec::new();
        for (v, l) in local.iter_mut().enumerate() {
            if *l == 0 {
                *l = vertex_ids.len() as u32;
                vertex_ids.push(VertexId::from_usize(v));
            }
        }
        let tets: Vec<Tet> = tet_ids
            .par_iter()
            .map(|t| self.tets[t.idx()].map(|v| VertexId(local[v.idx()])))
            .collect();
        let positions = vertex_ids.iter().map(|v| self.positions[v.idx()]).collect();
        let mut mesh = TetMesh::from_parts(positions, tets);
        let keep_v: Vec<usize> = vertex_ids.iter().map(|v| v.idx()).collect();
        mesh.point_data = self.point_data.select(&keep_v);
        mesh.point_data.insert(column(
            POINT_VERTEX,
            vertex_ids.iter().map(|v| v.0 as f64).collect(),
        ));
        let keep_t: Vec<usize> = tet_ids.iter().map(|t| t.idx()).collect();
        let mut cells: Attributes = self.cell_data.select(&keep_t);
        cells.insert(column(
            CELL_FRAGMENT,
            creators.iter().map(|c| c.0 as f64).collect(),
        ));
        cells.insert(column(
            CELL_ERROR,
            creators.iter().map(|c| self.error[c.idx()]).collect(),
        ));
        cells.insert(column(
            CELL_LEVEL,
            creators
                .iter()
                .map(|c| self.level[c.idx()] as f64)
                .collect(),
        ));
        mesh.cell_data = cells;
        let max_error = creators
            .iter()
            .map(|c| self.error[c.idx()])
            .fold(0.0, f64::max);
        Extraction {
            stats: ExtractStats {
                tets: tet_ids.len(),
                vertices: vertex_ids.len(),
                refined_fragments: 0,
                max_error,
                budget_met: true,
                seconds: 0.0,
            },
            mesh,
            tet_ids: tet_ids.to_vec(),
            vertex_ids,
        }
    }
}

/// Demand of a fragment of error `e` under threshold `tau`: `e / tau`, with `x / 0 = +∞`
/// for `x > 0`, `0 / 0 = 0` and `x / +∞ = 0`.
fn ratio(e: f64, tau: f64) -> f64 {
    if e <= 0.0 || tau == f64::INFINITY {
        0.0
    } else if tau == 0.0 {
        f64::INFINITY
    } else {
        e / tau
    }
}

fn column(name: &str, values: Vec<f64>) -> Attribute {
    Attribute {
        name: name.to_string(),
        components: 1,
        values,
    }
}
