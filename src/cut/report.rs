//! What a cut did: statistics, timings, and the new vertices' origins.

use super::classify::VertexOrigin;
use super::options::Scheme;
use super::tables::CutCase;
use crate::mesh::{TetId, VertexId};

/// Wall-clock time of each step, in seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CutTimes {
    /// Building the acceleration structure ([`super::cut_mesh`] only; a
    /// [`super::Cutter`] reports it once, in [`super::Cutter::build_time`]).
    pub build: f64,
    /// Step 1: finding the tets the cut may touch (hierarchy traversal, vertex states).
    pub query: f64,
    /// Step 2a: classifying edges and faces, placing and allocating the new vertices.
    pub classify: f64,
    /// Step 2b: replacing the cut tets from the tables.
    pub split: f64,
    /// Duplicating the vertices snapped onto the cut ([`super::unglue`]).
    pub unglue: f64,
    /// Counting connected components (when asked).
    pub components: f64,
    /// Query + classify + split + unglue: the cut itself.
    pub cut: f64,
}

/// Statistics of one cut.
#[derive(Clone, Debug, PartialEq)]
pub struct CutStats {
    pub scheme: Scheme,
    /// The snapping tolerance the cut was made with: the options', or larger when a plan
    /// at it would have made a flat tet (see [`super::Cutter::cut`]).
    pub snap: f64,
    /// Tets whose vertices were classified (the hierarchy's leaves reached).
    pub tets_tested: usize,
    /// Tets the plane crosses or that touch the cut at a vertex.
    pub tets_candidate: usize,
    /// Tets replaced.
    pub tets_cut: usize,
    /// Tets replaced, per configuration ([`CutCase::ALL`] order).
    pub tets_cut_by_case: [usize; 10],
    /// Tets created (replacing the cut ones).
    pub tets_created: usize,
    /// Vertices added: cut points, face points and copies of snapped vertices.
    pub vertices_added: usize,
    /// Cut-point copies (two per cut edge; for the 1:17 scheme, all its edge nodes).
    pub cut_points: usize,
    /// Face points (for the 1:17 scheme, its face nodes).
    pub face_points: usize,
    /// Copies of snapped vertices made to separate the sides.
    pub vertex_copies: usize,
    /// Distinct vertices snapped onto the cut.
    pub vertices_snapped: usize,
    /// Vertices within snapping distance left unsnapped because the sides could not be
    /// separated at them ([`super::unglue`]: a pinch).
    pub vertices_unsnapped: usize,
    /// Times the cut was planned: 1, plus one per round of unsnapping.
    pub plan_passes: usize,
    /// Edges crossed by the plane, and the cut ones among them (crossed inside C).
    pub edges_crossed: usize,
    pub edges_cut: usize,
    /// Tets and vertices of the mesh after the cut.
    pub tets_after: usize,
    pub vertices_after: usize,
    /// Connected components after the cut, when counted.
    pub components: Option<usize>,
    pub time: CutTimes,
}

impl CutStats {
    /// Tets cut in configuration `case`.
    pub fn cut_in(&self, case: CutCase) -> usize {
        CutCase::ALL
            .iter()
            .position(|&c| c == case)
            .map_or(0, |i| self.tets_cut_by_case[i])
    }

    /// The statistics as JSON (for `--json` reports and benchmarks).
    pub fn to_json(&self) -> serde_json::Value {
        let cases: serde_json::Map<String, serde_json::Value> = CutCase::ALL
            .iter()
            .zip(self.tets_cut_by_case)
            .map(|(c, n)| (c.name().to_string(), n.into()))
            .collect();
        serde_json::json!({
            "scheme": self.scheme.name(),
            "snap": self.snap,
            "tets_tested": self.tets_tested,
            "tets_candidate": self.tets_candidate,
            "tets_cut": self.tets_cut,
            "tets_cut_by_case": cases,
            "tets_created": self.tets_created,
            "vertices_added": self.vertices_added,
            "cut_points": self.cut_points,
            "face_points": self.face_points,
            "vertex_copies": self.vertex_copies,
            "vertices_snapped": self.vertices_snapped,
            "vertices_unsnapped": self.vertices_unsnapped,
            "plan_passes": self.plan_passes,
            "edges_crossed": self.edges_crossed,
            "edges_cut": self.edges_cut,
            "tets_after": self.tets_after,
            "vertices_after": self.vertices_after,
            "components": self.components,
            "time_s": {
                "build": self.time.build,
                "query": self.time.query,
                "classify": self.time.classify,
                "split": self.time.split,
                "unglue": self.time.unglue,
                "components": self.time.components,
                "cut": self.time.cut,
            },
        })
    }
}

/// A tet the cut replaced (paper §3: R(σ)): its first child took its slot `parent`, the
/// others are `first_appended .. first_appended + children - 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SplitRecord {
    pub parent: TetId,
    pub first_appended: TetId,
    pub children: u8,
    pub case: CutCase,
}

impl SplitRecord {
    /// The slots of the children.
    pub fn child_slots(&self) -> impl Iterator<Item = TetId> + '_ {
        std::iter::once(self.parent).chain(
            (0..self.children.saturating_sub(1) as u32).map(|k| TetId(self.first_appended.0 + k)),
        )
    }
}

/// The outcome of a cut.
#[derive(Clone, Debug, PartialEq)]
pub struct CutResult {
    pub stats: CutStats,
    /// The first vertex the cut added; vertex `first_new_vertex + k` comes from
    /// `origins[k]`.
    pub first_new_vertex: VertexId,
    pub origins: Vec<VertexOrigin>,
    /// The tets replaced, in the order they were processed.
    pub splits: Vec<SplitRecord>,
}
