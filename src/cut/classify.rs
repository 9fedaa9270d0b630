//! Step 2 of the paper's cut (§3), first half: classify every vertex, edge and face the
//! cut meets, **once**, and allocate the new vertices in a canonical order.
//!
//! A [`CutSession`] belongs to one cutting polygon. Its caches are keyed by *global*
//! vertex ids (edges by their two ids, faces by their three), so tets handed to it in any
//! number of batches — one level of a Multi-Tessellation after another, the frontier first
//! and the rest later — share one cut point per edge and one face point per face. Lookups
//! go through per-vertex lists hanging off the lowest id of the element, in arrays stamped
//! with the session's epoch ([`CutScratch`]), so nothing is hashed and nothing is cleared
//! between cuts.
//!
//! Classification is a pure function of positions and vertex scales: asking again gives
//! the same answer, whichever tet asks first. Until [`CutSession::allocate`] gives the new
//! points their ids (in canonical order), splitting uses provisional ids that
//! [`CutSession::resolve`] maps to the final ones; so the tets around a vertex can be
//! classified again ([`CutSession::forget_vertices`]) before anything is committed.

use super::tables::{NEG, ON, OUT, POS, config_index, face_points, is_crossed};
use crate::geom::{CutPolygon, DVec3, Sign, Tolerance};
use crate::mesh::fxhash::FxBuild;
use crate::mesh::tables::{EDGE_OF_VERTICES, TET_EDGES, TET_FACES};
use crate::mesh::{Tet, VertexId};
use std::collections::HashMap;
use std::sync::atomic::{AtomicU32, Ordering};

/// Fills `flags` (one per vertex, `nb_vertices` long) with the vertices `glued` and returns
/// the farthest of them from `polygon`'s plane, at `position`: the two arguments of
/// [`StateClassifier::with_glued`], as the frontier-first cut and the MT cut both build them.
pub(crate) fn mark_glued(
    flags: &mut Vec<bool>,
    nb_vertices: usize,
    glued: &[VertexId],
    polygon: &CutPolygon,
    position: impl Fn(VertexId) -> DVec3,
) -> f64 {
    flags.clear();
    flags.resize(nb_vertices, false);
    let mut reach = 0.0f64;
    for &v in glued {
        flags[v.idx()] = true;
        reach = reach.max(polygon.signed_distance(position(v)).abs());
    }
    reach
}

/// "No record".
pub(crate) const NONE: u32 = u32::MAX;

/// Where a vertex added by a cut comes from: the linear combination that gives its position
/// (and its per-vertex attributes) from older vertices. The deformable cut of paper §5
/// keeps these to map the cut surface between deformed and rest positions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum VertexOrigin {
    /// A cut point on edge `a`–`b` (`a < b`): `(1 - t) a + t b`; `side` is the side of the
    /// cut whose tets use this copy.
    Edge {
        a: VertexId,
        b: VertexId,
        t: f64,
        positive: bool,
    },
    /// A face point (crack tip) in face `v` (`v[0] < v[1] < v[2]`): `Σ w[k] v[k]`.
    Face { v: [VertexId; 3], w: [f64; 3] },
    /// A copy of a vertex on the cut, for the tets of another side ([`super::unglue`]).
    Copy { of: VertexId },
}

/// One edge crossed by the cut plane.
#[derive(Clone, Copy, Debug)]
pub(crate) struct EdgeRec {
    pub lo: VertexId,
    pub hi: VertexId,
    /// Next record in the list of `lo`.
    next: u32,
    /// Crossing parameter from `lo`.
    pub t: f64,
    /// Crossed strictly inside C: the edge is cut.
    pub cut: bool,
    /// Cut-point copies on the positive / negative side (INVALID until allocated).
    pub plus: VertexId,
    pub minus: VertexId,
}

/// An end of the segment where the plane meets a face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum SectionEnd {
    Vertex(VertexId),
    Edge(u32),
}

/// One face holding a face point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FaceRec {
    /// Sorted vertex ids.
    pub v: [VertexId; 3],
    next: u32,
    /// Section segment ends, inside end first.
    pub ends: [SectionEnd; 2],
    pub w: [f64; 3],
    pub id: VertexId,
    /// Dropped by [`CutSession::forget_vertices`]: never found, never allocated.
    pub dead: bool,
}

/// Provisional ids ([`CutSession::edge_points`] and [`CutSession::face_point`] before
/// allocation) have this bit set; ids of a pool stay below it.
pub(crate) const PROVISIONAL: u32 = 1 << 31;
/// Provisional face-point ids have this bit set too.
const PROVISIONAL_FACE: u32 = 1 << 30;

/// A per-vertex cache of states for one cut (epoch-stamped: never cleared), for the
/// vertices near the plane that many tets share. Shared by the threads of a parallel
/// query: entries are atomic, and threads racing on a vertex compute the same state, so
/// relaxed order is enough (and as cheap as a plain load or store).
#[derive(Debug, Default)]
pub struct StateCache {
    /// The current cut's epoch (below 2²⁴).
    epoch: u32,
    /// Per vertex: the epoch of the cut that computed its state (bits 8 and up) and the
    /// state (bits 0–7). In one word, a vertex costs one cache miss, not two.
    entries: Vec<AtomicU32>,
}

impl Clone for StateCache {
    fn clone(&self) -> StateCache {
        StateCache {
            epoch: self.epoch,
            entries: self
                .entries
                .iter()
                .map(|e| AtomicU32::new(e.load(Ordering::Relaxed)))
                .collect(),
        }
    }
}

impl StateCache {
    /// Starts a new cut over a pool of `n_vertices`.
    pub fn begin(&mut self, n_vertices: usize) {
        self.epoch += 1;
        if self.epoch == 1 << 24 {
            // Wrapped after 16 million cuts: old epochs could collide, start afresh.
            self.entries.iter_mut().for_each(|e| *e.get_mut() = 0);
            self.epoch = 1;
        }
        self.reserve(n_vertices);
    }

    /// Makes room for `n_vertices` (done ahead, the first cut does not pay for it).
    pub fn reserve(&mut self, n_vertices: usize) {
        if self.entries.len() < n_vertices {
            self.entries.resize_with(n_vertices, || AtomicU32::new(0));
        }
    }

    /// The cached state of `v`, computed by `f` on first request in this cut.
    #[inline]
    pub fn get(&self, v: VertexId, f: impl FnOnce() -> u8) -> u8 {
        let entry = &self.entries[v.idx()];
        let mut e = entry.load(Ordering::Relaxed);
        if e >> 8 != self.epoch {
            e = self.epoch << 8 | u32::from(f());
            entry.store(e, Ordering::Relaxed);
        }
        e as u8
    }
}

/// The vertices that are crack tips: face points made by earlier cuts (paper Fig. 4c–e),
/// where a partial cut ends, and the copies later cuts made of them. A cut that continues
/// the crack (a scalpel's next step, whose polygon begins where the last one ended) takes
/// the tips within reach of its polygon as on the cut, so the two cracks join there (see
/// [`StateClassifier::with_crack_tips`]).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CrackTips {
    bits: Vec<u64>,
}

impl CrackTips {
    /// Marks `v` as a crack tip.
    pub fn insert(&mut self, v: VertexId) {
        let (w, b) = (v.idx() / 64, v.idx() % 64);
        if self.bits.len() <= w {
            self.bits.resize(w + 1, 0);
        }
        self.bits[w] |= 1 << b;
    }

    /// Whether `v` is a crack tip.
    #[inline]
    pub fn contains(&self, v: VertexId) -> bool {
        self.bits
            .get(v.idx() / 64)
            .is_some_and(|w| w & (1 << (v.idx() % 64)) != 0)
    }

    /// Marks the face points among the vertices a cut added (`origins[k]` is vertex
    /// `first + k`).
    pub fn insert_face_points(&mut self, first: VertexId, origins: &[VertexOrigin]) {
        for (k, o) in origins.iter().enumerate() {
            if matches!(o, VertexOrigin::Face { .. }) {
                self.insert(VertexId::from_usize(first.idx() + k));
            }
        }
    }

    /// Whether no vertex is a crack tip.
    pub fn is_empty(&self) -> bool {
        self.bits.iter().all(|&w| w == 0)
    }
}

/// Per-vertex arrays reused by every cut (epoch-stamped: never cleared). Owned by the mesh
/// or MT that is cut, grown as vertices are added. Also the room of a session's edge and
/// face records, handed back when the session ends (grown anew by every cut before: with
/// the other buffers kept this way, a cold scalpel step 3-8% faster).
#[derive(Clone, Debug, Default)]
pub struct CutScratch {
    /// The current session's epoch.
    epoch: u32,
    /// Per vertex: the epoch of the last session that used it, then the heads of its edge
    /// and face lists in that session. Side by side, a vertex costs one cache miss, not
    /// three (separate arrays made most of the classification's time in a cold step).
    heads: Vec<[u32; 3]>,
    edges: Vec<EdgeRec>,
    faces: Vec<FaceRec>,
}

impl CutScratch {
    pub fn new() -> CutScratch {
        CutScratch::default()
    }

    fn begin(&mut self, n_vertices: usize) {
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            // Wrapped after 4 billion sessions: old epochs could collide, start afresh.
            self.heads.fill([0, NONE, NONE]);
            self.epoch = 1;
        }
        self.reserve(n_vertices);
    }

    /// Makes room for `n_vertices` (done ahead, the first cut does not pay for it).
    pub(crate) fn reserve(&mut self, n_vertices: usize) {
        if self.heads.len() < n_vertices {
            self.heads.resize(n_vertices, [0, NONE, NONE]);
        }
    }
}

/// The classification of one tet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TetClass {
    /// Vertex states ([`NEG`], [`ON`], [`POS`]) in the tet's local order.
    pub states: [u8; 4],
    /// Cut edges, bit `e` for local edge `e`.
    pub cut_mask: u8,
    /// Face points, bit `f` for local face `f`.
    pub face_mask: u8,
    /// Edge record of each crossed local edge.
    pub(crate) edges: [u32; 6],
    /// Face record of each local face holding a face point.
    pub(crate) faces: [u32; 4],
}

impl TetClass {
    /// Whether the tables replace this tet.
    #[inline]
    pub fn is_split(&self) -> bool {
        self.cut_mask != 0 || self.face_mask != 0
    }

    /// Whether a vertex of the tet lies on the cut.
    #[inline]
    pub fn touches_cut(&self) -> bool {
        self.states[0] == ON || self.states[1] == ON || self.states[2] == ON || self.states[3] == ON
    }
}

/// Vertex state: snapped onto the cut (`ON`) when within `snap × scale` of the plane and
/// its projection within the same distance of C; otherwise its exact side, a vertex
/// exactly on the plane outside C counting as positive (it is not cut, so its side only
/// has to be consistent).
#[inline]
pub fn vertex_state(polygon: &CutPolygon, snap: Tolerance, p: DVec3, scale: f64) -> u8 {
    vertex_state_in_band(polygon, snap, 0.0, false, p, scale)
}

/// How far from the plane, in rounding bounds of the signed distance
/// ([`CutPolygon::filter_bound`]), a vertex still lies on it: the points an earlier cut
/// made in the same plane (an incision the blade extends, or crosses) lie on the new
/// polygon's plane up to the rounding of their interpolation and of the two planes' normals,
/// a few bounds; their exact sides are that noise. Far below any snapping distance, so an
/// edge from such a vertex meets the plane at the vertex, outside C.
pub const ON_PLANE_ROUNDING: f64 = 64.0;

/// [`vertex_state`], a vertex on the plane also counting as on the cut when its projection
/// lies within `band × scale` outside C (see [`StateClassifier::with_contour_band`]), and
/// as [`OUT`] only when `crack` (a vertex of an earlier crack, see
/// [`StateClassifier::with_crack_vertices`]); otherwise, on the plane outside C, positive.
fn vertex_state_in_band(
    polygon: &CutPolygon,
    snap: Tolerance,
    band: f64,
    crack: bool,
    p: DVec3,
    scale: f64,
) -> u8 {
    let d = polygon.signed_distance(p);
    let r = snap.distance(scale);
    if d.abs() <= r && polygon.projection_distance(p) <= r.max(band * scale) {
        return ON;
    }
    if crack && d.abs() <= ON_PLANE_ROUNDING * polygon.filter_bound(p.abs().max_element()) {
        return OUT;
    }
    match polygon.side_filtered(p, d) {
        Sign::Negative => NEG,
        _ => POS,
    }
}

/// [`vertex_state`] with a fast path: one dot product decides every vertex farther from
/// the plane than any snapping distance and any rounding error of that dot product, which
/// is most of them. Same answers as `vertex_state`, always.
#[derive(Clone, Copy, Debug)]
pub struct StateClassifier<'a> {
    polygon: &'a CutPolygon,
    snap: Tolerance,
    normal: DVec3,
    offset: f64,
    /// Rounding bound of the dot product over the whole mesh (times [`ON_PLANE_ROUNDING`]
    /// with crack vertices: nearer than this a vertex may be [`OUT`]).
    filter: f64,
    /// Beyond this distance no vertex of the pool can be snapped.
    far: f64,
    /// Relative width of the band outside C's contour where a vertex on the plane still
    /// counts as on the cut (0 unless [`with_contour_band`](Self::with_contour_band)).
    band: f64,
    /// Crack tips of earlier cuts, and how far from C (relative to their scale) they are
    /// taken as on the cut ([`with_crack_tips`](Self::with_crack_tips)).
    tips: Option<&'a CrackTips>,
    tip_reach: f64,
    max_scale: f64,
    /// Per vertex: whether it lies on an earlier crack
    /// ([`with_crack_vertices`](Self::with_crack_vertices)).
    crack: Option<&'a [bool]>,
    /// Per vertex: whether it counts as lying in the plane ([`with_glued`](Self::with_glued)).
    glued: Option<&'a [bool]>,
}

impl<'a> StateClassifier<'a> {
    /// A classifier for vertices inside `bounds` whose scales are at most `max_scale`.
    pub fn new(
        polygon: &'a CutPolygon,
        snap: Tolerance,
        bounds: &crate::geom::Aabb,
        max_scale: f64,
    ) -> StateClassifier<'a> {
        let extent = bounds.min.abs().max(bounds.max.abs()).max_element();
        let filter = polygon.filter_bound(extent);
        StateClassifier {
            polygon,
            snap,
            normal: polygon.plane().normal,
            offset: polygon.plane().offset,
            filter,
            far: snap.distance(max_scale).max(filter),
            band: 0.0,
            tips: None,
            tip_reach: 0.0,
            max_scale,
            crack: None,
            glued: None,
        }
    }

    /// Vertices of earlier cracks (`crack[v]`: cut points, face points, and the vertices
    /// snapped and duplicated) lying on the plane up to rounding ([`ON_PLANE_ROUNDING`])
    /// outside C are [`OUT`] instead of taking their exact side, which is rounding noise for
    /// them: the lips and tips of an incision the blade extends in its own plane. Other
    /// vertices on the plane outside C keep counting as positive: an `OUT` vertex shared by
    /// both sides lets the crack open along the faces in the plane between it and a
    /// snapped vertex, which joins a new crack to an earlier one but would, at a vertex
    /// of the body the plane merely passes through, open the body outside C.
    pub fn with_crack_vertices(mut self, crack: &'a [bool]) -> Self {
        self.crack = Some(crack);
        self.filter *= ON_PLANE_ROUNDING;
        self.far = self.far.max(self.filter);
        self
    }

    /// Vertices on the plane (within snapping distance) whose projection lies outside C
    /// by at most `relative` × their scale count as on the cut too. Cuts that continue
    /// cracks (MT cuts, plain-mesh scalpels) use it so that a cut continuing an earlier one
    /// in the same plane takes the earlier crack tips on its contour (which lie about the
    /// face-point margin off the earlier contour) as part of the crack (see
    /// [`super::mt_cut`] and `mt_cut::contour_band`).
    pub fn with_contour_band(mut self, relative: f64) -> Self {
        self.band = relative;
        self
    }

    /// Crack tips of earlier cuts within `reach` × their scale of C (in space: off the
    /// plane and outside C's contour alike) count as on the cut. A scalpel's step begins
    /// on the edge where the last step's polygon ended, and that step's crack tips lie up
    /// to the face-point margin from it, in the last step's plane; when the blade turns or
    /// tilts they are off the new plane, so neither snapping (almost none on an MT) nor the
    /// contour band reaches them, and the two cracks would not join: a bridge of material
    /// would be left at every step. Only tips are taken so: other vertices near C keep the
    /// usual rules. The plain-mesh engine takes them ([`super::CutOptions::continue_cracks`]);
    /// the MT cut takes those of a cut it continues at an angle (see [`super::mt_cut`]'s
    /// limits).
    pub fn with_crack_tips(mut self, tips: &'a CrackTips, reach: f64) -> Self {
        if !tips.is_empty() && reach > 0.0 {
            self.tips = Some(tips);
            self.tip_reach = reach;
            self.far = self.far.max(reach * self.max_scale);
        }
        self
    }

    /// Vertices with `glued[v]` count as lying in the plane wherever they are (their
    /// state is that of their projection onto it: on the cut inside C and its contour
    /// band, [`OUT`] outside); `reach` is the farthest of them from the plane. For a body
    /// that moved between two steps of a blade in one plane ([`super::live`]): the
    /// vertices of the last steps' crack were made in that plane but the motion has moved
    /// them off it, by amounts no snapping distance allows, so the new step would meet
    /// that crack's tips and lips on either side of its plane, differently on each level.
    pub fn with_glued(mut self, glued: &'a [bool], reach: f64) -> Self {
        self.glued = Some(glued);
        self.far = self.far.max(reach);
        self
    }

    /// Whether `v` counts as lying in the plane ([`with_glued`](Self::with_glued)).
    #[inline]
    fn is_glued(&self, v: VertexId) -> bool {
        self.glued.is_some_and(|g| g.get(v.idx()) == Some(&true))
    }

    /// Whether `v` is a crack tip within the tip reach of the plane (`d` its distance).
    #[inline]
    fn tip_near(&self, v: VertexId, d: f64, scale: f64) -> bool {
        self.tips
            .is_some_and(|t| d.abs() <= self.tip_reach * scale && t.contains(v))
    }

    #[inline(always)]
    pub fn vertex(&self, v: VertexId, p: DVec3, scale: f64) -> u8 {
        let d = self.normal.dot(p) - self.offset;
        if self.is_glued(v) {
            return self.near(v, p - self.normal * d, scale);
        }
        let fast = self.snap.distance(scale).max(self.filter);
        if d.abs() <= fast || self.tip_near(v, d, scale) {
            self.near(v, p, scale)
        } else if d > 0.0 {
            POS
        } else {
            NEG
        }
    }

    /// The cutting polygon.
    pub fn polygon(&self) -> &'a CutPolygon {
        self.polygon
    }

    /// The snapping tolerance.
    pub fn snap(&self) -> Tolerance {
        self.snap
    }

    /// [`vertex`](Self::vertex) for vertex `v` of a pool, reading its scale only when the
    /// vertex is close enough to the plane for it to matter.
    #[inline(always)]
    pub fn pool_vertex(&self, positions: &[DVec3], scales: &[f64], v: VertexId) -> u8 {
        let p = positions[v.idx()];
        let d = self.normal.dot(p) - self.offset;
        if d > self.far {
            POS
        } else if d < -self.far {
            NEG
        } else {
            self.vertex(v, p, scales[v.idx()])
        }
    }

    #[cold]
    #[inline(never)]
    fn near(&self, v: VertexId, p: DVec3, scale: f64) -> u8 {
        let crack = self.crack.is_some_and(|c| c.get(v.idx()) == Some(&true)) || self.is_glued(v);
        let state = vertex_state_in_band(self.polygon, self.snap, self.band, crack, p, scale);
        if state != ON && self.tip_near(v, self.polygon.signed_distance(p), scale) {
            let reach = self.tip_reach * scale;
            if self.polygon.projection_distance(p) <= reach {
                return ON;
            }
        }
        state
    }

    /// The states of a tet's vertices. Branch-free unless a vertex is near the plane (a
    /// data-dependent branch per vertex would stall on every cache miss: the positions of a
    /// tet's vertices are scattered in memory).
    #[inline]
    pub fn tet(&self, positions: &[DVec3], scales: &[f64], tet: &Tet) -> [u8; 4] {
        self.tet_with(positions, tet, |v| {
            self.vertex(v, positions[v.idx()], scales[v.idx()])
        })
    }

    /// [`tet`](Self::tet), asking `near` for the state of each vertex close enough to the
    /// plane to need more than one dot product (a caller may cache those).
    #[inline]
    pub fn tet_with(
        &self,
        positions: &[DVec3],
        tet: &Tet,
        mut near: impl FnMut(VertexId) -> u8,
    ) -> [u8; 4] {
        let dist = |v: VertexId| self.normal.dot(positions[v.idx()]) - self.offset;
        let d = [dist(tet[0]), dist(tet[1]), dist(tet[2]), dist(tet[3])];
        let close = [
            d[0].abs() <= self.far,
            d[1].abs() <= self.far,
            d[2].abs() <= self.far,
            d[3].abs() <= self.far,
        ];
        let side = |x: f64| if x > 0.0 { POS } else { NEG };
        if !(close[0] | close[1] | close[2] | close[3]) {
            return [side(d[0]), side(d[1]), side(d[2]), side(d[3])];
        }
        let mut out = [0u8; 4];
        for j in 0..4 {
            out[j] = if !close[j] {
                if d[j] > 0.0 { POS } else { NEG }
            } else {
                near(tet[j])
            };
        }
        out
    }
}

/// Builds the tables [`crossed_mask`] and [`face_mask`] read (once per process: 0.3 ms
/// for the face points of all 16,384 configurations), so that they are not built by the
/// first cut, whose latency a time-critical host counts: called when a cutter is made.
pub(crate) fn build_tables() {
    crossed_mask([POS; 4]);
    face_mask([POS; 4], 0);
}

/// The crossed edges of a tet in these states (bit `e` for local edge `e`).
#[inline]
pub fn crossed_mask(states: [u8; 4]) -> u8 {
    static TABLE: std::sync::OnceLock<[u8; 256]> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| {
        std::array::from_fn(|code| {
            let (s, _) = super::tables::config_of_index(code * 64);
            let mut m = 0;
            for (e, &[a, b]) in TET_EDGES.iter().enumerate() {
                if is_crossed(s[a], s[b]) {
                    m |= 1 << e;
                }
            }
            m
        })
    });
    table[config_index(states, 0) / 64]
}

/// The faces holding a face point (bit `f` for local face `f`) of a tet in these states
/// with these cut edges ([`super::tables::face_has_point`], tabulated).
#[inline]
pub fn face_mask(states: [u8; 4], cut_mask: u8) -> u8 {
    static TABLE: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| {
        (0..super::tables::NB_CONFIGS)
            .map(|c| {
                let (s, m) = super::tables::config_of_index(c);
                face_points(s, m)
                    .iter()
                    .enumerate()
                    .fold(0u8, |acc, (f, &p)| acc | (u8::from(p) << f))
            })
            .collect()
    });
    table[config_index(states, cut_mask)]
}

/// Whether a tet in these states needs classifying (the plane crosses it, or a vertex is
/// on the cut).
#[inline]
pub fn is_candidate(states: [u8; 4]) -> bool {
    // One bit per state present.
    let present = (1u8 << states[0]) | (1 << states[1]) | (1 << states[2]) | (1 << states[3]);
    present & (1 << ON) != 0 || present & ((1 << POS) | (1 << NEG)) == (1 << POS) | (1 << NEG)
}

/// The classification state of one cut polygon (see the module docs).
pub struct CutSession<'a> {
    pub(crate) polygon: &'a CutPolygon,
    pub(crate) snap: Tolerance,
    face_margin: f64,
    scratch: &'a mut CutScratch,
    pub(crate) edges: Vec<EdgeRec>,
    pub(crate) faces: Vec<FaceRec>,
    /// Records not yet classified / allocated.
    edges_classified: usize,
    faces_computed: usize,
    edges_allocated: usize,
    faces_allocated: usize,
}

impl<'a> CutSession<'a> {
    /// A session for `polygon` over a vertex pool of (at least) `n_vertices` vertices.
    /// `snap` is the snapping tolerance (relative to vertex scales), `face_margin` the
    /// smallest distance, as a fraction of the segment, between a face point and the ends
    /// of the segment it lies on.
    pub fn new(
        polygon: &'a CutPolygon,
        snap: Tolerance,
        face_margin: f64,
        scratch: &'a mut CutScratch,
        n_vertices: usize,
    ) -> CutSession<'a> {
        scratch.begin(n_vertices);
        let (mut edges, mut faces) = (
            std::mem::take(&mut scratch.edges),
            std::mem::take(&mut scratch.faces),
        );
        edges.clear();
        faces.clear();
        CutSession {
            polygon,
            snap,
            face_margin,
            scratch,
            edges,
            faces,
            edges_classified: 0,
            faces_computed: 0,
            edges_allocated: 0,
            faces_allocated: 0,
        }
    }

    /// A vertex classifier for this cut, for vertices inside `bounds` whose scales are at
    /// most `max_scale`.
    pub fn classifier(&self, bounds: &crate::geom::Aabb, max_scale: f64) -> StateClassifier<'a> {
        StateClassifier::new(self.polygon, self.snap, bounds, max_scale)
    }

    fn head(&mut self, v: VertexId, face: bool) -> &mut u32 {
        let epoch = self.scratch.epoch;
        let h = &mut self.scratch.heads[v.idx()];
        if h[0] != epoch {
            *h = [epoch, NONE, NONE];
        }
        &mut h[1 + usize::from(face)]
    }

    /// The record of edge `a`–`b`, created (unclassified) if new.
    fn edge_record(&mut self, a: VertexId, b: VertexId) -> u32 {
        let (lo, hi) = if a < b { (a, b) } else { (b, a) };
        let mut r = *self.head(lo, false);
        while r != NONE {
            let e = &self.edges[r as usize];
            if e.hi == hi {
                return r;
            }
            r = e.next;
        }
        let id = self.edges.len() as u32;
        let head = self.head(lo, false);
        let next = *head;
        *head = id;
        self.edges.push(EdgeRec {
            lo,
            hi,
            next,
            t: 0.0,
            cut: false,
            plus: VertexId::INVALID,
            minus: VertexId::INVALID,
        });
        id
    }

    fn face_record(&mut self, v: [VertexId; 3], ends: [SectionEnd; 2]) -> u32 {
        let mut r = *self.head(v[0], true);
        while r != NONE {
            let f = &self.faces[r as usize];
            if f.v == v && !f.dead {
                return r;
            }
            r = f.next;
        }
        let id = self.faces.len() as u32;
        let head = self.head(v[0], true);
        let next = *head;
        *head = id;
        self.faces.push(FaceRec {
            v,
            next,
            ends,
            w: [0.0; 3],
            id: VertexId::INVALID,
            dead: false,
        });
        id
    }

    /// Forgets the face points of faces containing a vertex of `vertices` (sorted), whose
    /// state is about to change (the cut leaves them unsnapped): the tets around them are
    /// then classified again, and make new records. Only unallocated records may be
    /// forgotten. One pass over the records, whatever the number of vertices.
    pub fn forget_vertices(&mut self, vertices: &[VertexId]) {
        debug_assert!(vertices.windows(2).all(|w| w[0] < w[1]));
        for f in &mut self.faces[self.faces_allocated..] {
            if f.v.iter().any(|v| vertices.binary_search(v).is_ok()) {
                f.dead = true;
            }
        }
    }

    /// Classifies a batch of tets (their states already computed, see
    /// [`StateClassifier::tet`]):
    /// edges first (once each, whichever batch meets them first), then faces. Returns one
    /// [`TetClass`] per tet. The pool must hold every vertex the tets use.
    pub fn classify(
        &mut self,
        positions: &[DVec3],
        scales: &[f64],
        tets: &[Tet],
        states: &[[u8; 4]],
        parallel: bool,
    ) -> Vec<TetClass> {
        let mut classes = Vec::with_capacity(tets.len());
        self.classify_into(positions, scales, tets, states, parallel, &mut classes);
        classes
    }

    /// [`classify`](Self::classify) into `classes` (cleared first), whose room a caller
    /// keeps from one cut to the next.
    pub fn classify_into(
        &mut self,
        positions: &[DVec3],
        scales: &[f64],
        tets: &[Tet],
        states: &[[u8; 4]],
        parallel: bool,
        classes: &mut Vec<TetClass>,
    ) {
        self.scratch.reserve(positions.len());
        classes.clear();
        classes.reserve(tets.len());
        for (tet, &st) in tets.iter().zip(states) {
            let mut edges = [NONE; 6];
            let mut crossed = crossed_mask(st);
            while crossed != 0 {
                let e = crossed.trailing_zeros() as usize;
                crossed &= crossed - 1;
                let [a, b] = TET_EDGES[e];
                edges[e] = self.edge_record(tet[a], tet[b]);
            }
            classes.push(TetClass {
                states: st,
                cut_mask: 0,
                face_mask: 0,
                edges,
                faces: [NONE; 4],
            });
        }
        self.classify_new_edges(positions, parallel);
        for (tet, class) in tets.iter().zip(classes.iter_mut()) {
            for e in 0..6 {
                let r = class.edges[e];
                if r != NONE && self.edges[r as usize].cut {
                    class.cut_mask |= 1 << e;
                }
            }
            class.face_mask = face_mask(class.states, class.cut_mask);
            for (f, &lv) in TET_FACES.iter().enumerate() {
                if class.face_mask & (1 << f) != 0 {
                    let ends = self.section_ends(tet, class, lv);
                    let mut v = lv.map(|i| tet[i]);
                    v.sort_unstable();
                    class.faces[f] = self.face_record(v, ends);
                }
            }
        }
        self.compute_new_faces(positions, scales, parallel);
    }

    /// The ends of the segment where the plane meets the face `lv` of a tet, the inside end
    /// (an ON vertex or a cut edge's point) first.
    fn section_ends(&self, tet: &Tet, class: &TetClass, lv: [usize; 3]) -> [SectionEnd; 2] {
        let mut inside = None;
        let mut outside = None;
        for k in 0..3 {
            let (a, b) = (lv[k], lv[(k + 1) % 3]);
            match class.states[a] {
                ON => inside = Some(SectionEnd::Vertex(tet[a])),
                OUT => outside = Some(SectionEnd::Vertex(tet[a])),
                _ => {}
            }
            let e = EDGE_OF_VERTICES[a][b];
            if class.edges[e] != NONE {
                let end = SectionEnd::Edge(class.edges[e]);
                if class.cut_mask & (1 << e) != 0 {
                    inside = Some(end);
                } else {
                    outside = Some(end);
                }
            }
        }
        match (inside, outside) {
            (Some(i), Some(o)) => [i, o],
            _ => unreachable!("a face with a face point has one inside and one outside end"),
        }
    }

    /// Classifies the edges recorded since the last call: crossing parameter, and cut or
    /// not (exactly). A cut point is kept `snap` away from its edge's ends: snapping
    /// already guarantees it for vertices that could snap, and the clamp covers the ones a
    /// cut leaves unsnapped (see [`super::Cutter::cut`]), whose cut points then pass the
    /// plane by at most the snapping distance instead of making slivers.
    fn classify_new_edges(&mut self, positions: &[DVec3], parallel: bool) {
        let polygon = self.polygon;
        let keep = self.snap.relative.min(0.5);
        let work = |e: &mut EdgeRec| {
            let (p, q) = (positions[e.lo.idx()], positions[e.hi.idx()]);
            let (dp, dq) = (polygon.signed_distance(p), polygon.signed_distance(q));
            let den = dp - dq;
            e.t = if den != 0.0 {
                (dp / den).clamp(0.0, 1.0)
            } else {
                0.5
            };
            e.cut = polygon.segment_crosses_inside_filtered(p, q, dp, dq);
            if e.cut {
                e.t = e.t.clamp(keep, 1.0 - keep);
            }
        };
        let new = &mut self.edges[self.edges_classified..];
        if parallel {
            use rayon::prelude::*;
            new.par_iter_mut().for_each(work);
        } else {
            new.iter_mut().for_each(work);
        }
        self.edges_classified = self.edges.len();
    }

    fn end_position(&self, positions: &[DVec3], end: SectionEnd) -> DVec3 {
        match end {
            SectionEnd::Vertex(v) => positions[v.idx()],
            SectionEnd::Edge(r) => {
                let e = &self.edges[r as usize];
                let (p, q) = (positions[e.lo.idx()], positions[e.hi.idx()]);
                p + (q - p) * e.t
            }
        }
    }

    /// Barycentric weights of a section end with respect to the sorted face `v`; an uncut
    /// edge's crossing taken at parameter `t`.
    fn end_weights(&self, v: [VertexId; 3], end: SectionEnd, t: f64) -> [f64; 3] {
        let mut w = [0.0; 3];
        let slot = |x: VertexId| v.iter().position(|&y| y == x).unwrap_or(0);
        match end {
            SectionEnd::Vertex(x) => w[slot(x)] = 1.0,
            SectionEnd::Edge(r) => {
                let e = &self.edges[r as usize];
                w[slot(e.lo)] += 1.0 - t;
                w[slot(e.hi)] += t;
            }
        }
        w
    }

    /// Face points of the faces recorded since the last call (see also
    /// [`super::options::CutOptions::face_point_margin`]).
    ///
    /// The face point lies on the segment from the face's section end in C to a point of
    /// its uncut edge: where C's contour crosses the segment, kept `face_margin` from its
    /// ends. The segment's outside end is the uncut edge's crossing moved towards the
    /// edge's middle (by `face_margin` of the edge), as far as that keeps the face point
    /// within 90% of the snapping distance of the plane: a crossing near a vertex would put
    /// the face point next to an edge of its face (a thin or flat child), while a face
    /// point far from the plane would make edges from the crack tip cross the plane inside
    /// C by more than snapped vertices do. The true crossing is always allowed (its face
    /// point is off the plane only as much as the inside end, a snapped vertex, is).
    fn compute_new_faces(&mut self, positions: &[DVec3], scales: &[f64], parallel: bool) {
        let start = self.faces_computed;
        let computed: Vec<[f64; 3]> = {
            let this = &*self;
            let work = |f: &FaceRec| {
                let pi = this.end_position(positions, f.ends[0]);
                let po = this.end_position(positions, f.ends[1]);
                let margin = this.face_margin;
                let s = this
                    .polygon
                    .contour_parameter(pi, po)
                    .clamp(margin, 1.0 - margin);
                let t = match f.ends[1] {
                    SectionEnd::Edge(r) => {
                        let e = &this.edges[r as usize];
                        let d = |v: VertexId| this.polygon.signed_distance(positions[v.idx()]);
                        let (dlo, dhi, din) = (d(e.lo), d(e.hi), this.polygon.signed_distance(pi));
                        let h = f.v.iter().map(|x| scales[x.idx()]).fold(0.0, f64::max);
                        let budget = 0.9 * this.snap.distance(h);
                        // Face-point distance (1 - s) din + s (dlo + t (dhi - dlo)) within
                        // ±budget: an interval of t around the true crossing.
                        let slope = s * (dhi - dlo);
                        let base = (1.0 - s) * din + s * dlo;
                        let (a, b) = ((-budget - base) / slope, (budget - base) / slope);
                        let (lo, hi) = (a.min(b).max(0.0), a.max(b).min(1.0));
                        let wanted = e.t.clamp(margin, 1.0 - margin);
                        if lo <= hi { wanted.clamp(lo, hi) } else { e.t }
                    }
                    SectionEnd::Vertex(_) => 0.0,
                };
                let t_in = match f.ends[0] {
                    SectionEnd::Edge(r) => this.edges[r as usize].t,
                    SectionEnd::Vertex(_) => 0.0,
                };
                let (wi, wo) = (
                    this.end_weights(f.v, f.ends[0], t_in),
                    this.end_weights(f.v, f.ends[1], t),
                );
                std::array::from_fn(|k| (1.0 - s) * wi[k] + s * wo[k])
            };
            if parallel {
                use rayon::prelude::*;
                self.faces[start..].par_iter().map(work).collect()
            } else {
                self.faces[start..].iter().map(work).collect()
            }
        };
        for (f, w) in self.faces[start..].iter_mut().zip(computed) {
            f.w = w;
        }
        self.faces_computed = self.faces.len();
    }

    /// Allocates ids for the cut points and face points recorded since the last call, in
    /// canonical order (cut edges by their id pair, positive copy first, then faces by
    /// their id triple), starting at `first`. Returns each new vertex's origin in id order.
    pub fn allocate(&mut self, first: VertexId) -> Vec<VertexOrigin> {
        let mut order: Vec<u32> = (self.edges_allocated..self.edges.len())
            .filter(|&r| self.edges[r].cut)
            .map(|r| r as u32)
            .collect();
        order.sort_unstable_by_key(|&r| {
            let e = &self.edges[r as usize];
            (e.lo, e.hi)
        });
        let mut faces: Vec<u32> = (self.faces_allocated..self.faces.len())
            .filter(|&r| !self.faces[r].dead)
            .map(|r| r as u32)
            .collect();
        faces.sort_unstable_by_key(|&r| self.faces[r as usize].v);
        let mut out = Vec::with_capacity(order.len() * 2 + faces.len());
        let mut next = first.0;
        for r in order {
            let e = &mut self.edges[r as usize];
            e.plus = VertexId(next);
            e.minus = VertexId(next + 1);
            next += 2;
            for positive in [true, false] {
                out.push(VertexOrigin::Edge {
                    a: e.lo,
                    b: e.hi,
                    t: e.t,
                    positive,
                });
            }
        }
        for r in faces {
            let f = &mut self.faces[r as usize];
            f.id = VertexId(next);
            next += 1;
            out.push(VertexOrigin::Face { v: f.v, w: f.w });
        }
        self.edges_allocated = self.edges.len();
        self.faces_allocated = self.faces.len();
        out
    }

    /// The cut-point copies of a cut edge record.
    #[inline]
    pub(crate) fn edge_points(&self, r: u32) -> (VertexId, VertexId) {
        let e = &self.edges[r as usize];
        if e.plus.is_valid() {
            (e.plus, e.minus)
        } else {
            (
                VertexId(PROVISIONAL | (2 * r)),
                VertexId(PROVISIONAL | (2 * r + 1)),
            )
        }
    }

    #[inline]
    pub(crate) fn face_point(&self, r: u32) -> VertexId {
        let f = &self.faces[r as usize];
        if f.id.is_valid() {
            f.id
        } else {
            VertexId(PROVISIONAL | PROVISIONAL_FACE | r)
        }
    }

    /// The allocated id of a vertex id handed out before allocation (ids below
    /// 2³¹, the provisional range, are returned as they are).
    #[inline]
    pub fn resolve(&self, v: VertexId) -> VertexId {
        if v.0 & PROVISIONAL == 0 {
            return v;
        }
        if v.0 & PROVISIONAL_FACE != 0 {
            return self.faces[(v.0 & !(PROVISIONAL | PROVISIONAL_FACE)) as usize].id;
        }
        let r = (v.0 & !PROVISIONAL) as usize;
        let e = &self.edges[r / 2];
        if r % 2 == 0 { e.plus } else { e.minus }
    }

    /// Number of edges the plane crosses among those classified so far, and how many are
    /// cut.
    pub fn edge_counts(&self) -> (usize, usize) {
        (
            self.edges.len(),
            self.edges.iter().filter(|e| e.cut).count(),
        )
    }

    /// Number of face points recorded so far.
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }
}

impl Drop for CutSession<'_> {
    /// Hands the records' room back to the scratch, for the next session.
    fn drop(&mut self) {
        self.scratch.edges = std::mem::take(&mut self.edges);
        self.scratch.faces = std::mem::take(&mut self.faces);
    }
}

/// The positions of new vertices from their origins (in id order), equal to the bit where
/// they coincide: cut points on edges, and face points in faces, whose ends lie at the
/// same positions (the two lips of an earlier crack, where both are cut again: an edge
/// from a duplicated vertex to a crack tip, seen from each side) take the position of the
/// first of them. Computed from differently ordered ends, they would differ by a rounding,
/// and the point of one lip would lie inside a face of the other instead of on its corner.
pub fn origin_positions(positions: &[DVec3], origins: &[VertexOrigin]) -> Vec<DVec3> {
    let mut out = OriginPositions::default();
    out.compute(positions, origins, None);
    out.positions
}

/// [`origin_positions`] with its table and result kept from one call to the next (cleared,
/// their room kept): a cut called it with a table and a vector allocated anew.
#[derive(Clone, Debug, Default)]
pub struct OriginPositions {
    /// The first position of each edge or face (keyed by its ends' bits).
    first: HashMap<[[u64; 3]; 3], DVec3, FxBuild>,
    positions: Vec<DVec3>,
}

impl OriginPositions {
    /// Room, its memory mapped, for placing `n` new vertices.
    pub fn reserve(&mut self, n: usize) {
        crate::mesh::reserve_mapped(&mut self.positions, n);
    }

    /// [`origin_positions`] of `origins` from `positions`. `twinned`, when known, tells per
    /// vertex whether another vertex may lie at its position: an origin none of whose ends
    /// is twinned shares its place with no other origin but its own twin (a cut point's
    /// other copy: the same ends and parameter, so the same rounding), and is placed
    /// without the table. A cut of a part of the mesh no earlier cut reached then hashes
    /// nothing (a fresh fandisk-1m cutter's cut through the middle spent a tenth of its
    /// main thread's time filling the table, most of it faulting the table's pages in).
    pub fn compute(
        &mut self,
        positions: &[DVec3],
        origins: &[VertexOrigin],
        twinned: Option<&[bool]>,
    ) -> &[DVec3] {
        let bits = |v: VertexId| positions[v.idx()].to_array().map(f64::to_bits);
        let alone = |v: &VertexId| twinned.is_some_and(|t| !t[v.idx()]);
        let first = &mut self.first;
        first.clear();
        if twinned.is_none() {
            first.reserve(origins.len());
        }
        self.positions.clear();
        // Edges and faces keyed apart: an edge's third corner is a value no finite
        // coordinate has.
        self.positions.extend(origins.iter().map(|o| {
            let p = origin_position(positions, o);
            let key = match *o {
                VertexOrigin::Edge { a, b, .. } if !(alone(&a) && alone(&b)) => {
                    let mut k = [bits(a), bits(b)];
                    k.sort_unstable();
                    [k[0], k[1], [u64::MAX; 3]]
                }
                VertexOrigin::Face { v, .. } if !v.iter().all(alone) => {
                    let mut k = v.map(bits);
                    k.sort_unstable();
                    k
                }
                _ => return p,
            };
            *first.entry(key).or_insert(p)
        }));
        &self.positions
    }
}

/// Marks, in `twinned` (one flag per vertex, extended here), which of the vertices a cut
/// added may share their position with another vertex, and the vertices it copied: for
/// [`OriginPositions::compute`], so erring on the side of `true` only costs hashing.
/// `origins` are those of the vertices numbered from `twinned.len()`. Cut points come in
/// coincident pairs; a copy coincides with its original; a face point is placed through
/// the table, possibly onto another, when a corner of its face is twinned.
pub fn extend_twinned(twinned: &mut Vec<bool>, origins: &[VertexOrigin]) {
    for o in origins {
        if let VertexOrigin::Copy { of } = *o {
            twinned[of.idx()] = true;
        }
    }
    for o in origins {
        let twin = match *o {
            VertexOrigin::Face { v, .. } => v.iter().any(|x| twinned[x.idx()]),
            _ => true,
        };
        twinned.push(twin);
    }
}

/// The position of a new vertex from its origin.
fn origin_position(positions: &[DVec3], origin: &VertexOrigin) -> DVec3 {
    match *origin {
        VertexOrigin::Edge { a, b, t, .. } => {
            let (p, q) = (positions[a.idx()], positions[b.idx()]);
            p + (q - p) * t
        }
        VertexOrigin::Face { v, w } => {
            positions[v[0].idx()] * w[0]
                + positions[v[1].idx()] * w[1]
                + positions[v[2].idx()] * w[2]
        }
        VertexOrigin::Copy { of } => positions[of.idx()],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Aabb;

    /// The two lips of a crack, each cut along its copy of one edge: vertices 2 and 3 are
    /// the copies of 1 and 0, so the lips' edges run in opposite directions and their cut
    /// points, computed apart, differ by a rounding. Known as twinned, the ends send both
    /// through the table (one position); an edge without twinned ends is placed directly,
    /// and its cut points' pair coincides all the same.
    #[test]
    fn cut_points_of_coincident_edges_share_a_position_when_their_ends_are_twinned() {
        let (p, q) = (DVec3::new(0.1, 0.7, 0.3), DVec3::new(1.3, 0.2, 0.9));
        let positions = [
            p,
            q,
            q,
            p,
            DVec3::new(2.0, 2.0, 2.0),
            DVec3::new(0.5, 1.5, 2.5),
        ];
        let edge = |a: u32, b: u32, t: f64, positive: bool| VertexOrigin::Edge {
            a: VertexId(a),
            b: VertexId(b),
            t,
            positive,
        };
        let t = 0.3;
        let origins = [
            edge(0, 1, t, true),
            edge(0, 1, t, false),
            edge(2, 3, 1.0 - t, true),
            edge(4, 5, 0.6, true),
            edge(4, 5, 0.6, false),
        ];
        let apart = [0, 2].map(|i| origin_position(&positions, &origins[i]));
        assert_ne!(apart[0], apart[1], "the example needs a rounding apart");
        let table = origin_positions(&positions, &origins);
        assert_eq!(table[2], table[0]);
        let mut placed = OriginPositions::default();
        let twinned = [true, true, true, true, false, false];
        assert_eq!(
            placed.compute(&positions, &origins, Some(&twinned)),
            &table[..]
        );
        // Not knowing the twins (all flags false) would place the lips apart.
        let unknown = [false; 6];
        assert_ne!(
            placed.compute(&positions, &origins, Some(&unknown))[2],
            table[0]
        );

        // Extending the flags: cut points and copies are twinned, with the copies'
        // originals; a face point only where a corner of its face is.
        let mut flags = vec![false; 5];
        extend_twinned(
            &mut flags,
            &[
                edge(0, 4, 0.5, true),
                VertexOrigin::Face {
                    v: [VertexId(0), VertexId(3), VertexId(4)],
                    w: [0.2, 0.3, 0.5],
                },
                VertexOrigin::Copy { of: VertexId(1) },
                VertexOrigin::Face {
                    v: [VertexId(0), VertexId(1), VertexId(4)],
                    w: [0.2, 0.3, 0.5],
                },
            ],
        );
        assert_eq!(
            flags,
            [false, true, false, false, false, true, false, true, true]
        );
    }

    /// Glued vertices take the state of their projection onto the plane (on the cut inside
    /// C, `OUT` outside), on either side and through the tet classification's fast path;
    /// the others keep their exact sides.
    #[test]
    fn glued_vertices_count_as_lying_in_the_plane() {
        let c = CutPolygon::new(&[
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ])
        .expect("square");
        let positions = [
            DVec3::new(0.5, 0.5, 1e-3),
            DVec3::new(0.5, 0.5, -1e-3),
            DVec3::new(2.0, 0.5, 1e-3),
            DVec3::new(0.5, 0.5, 1e-3),
        ];
        let scales = [1.0; 4];
        let glued = [true, true, true, false];
        let bounds = Aabb::from_points(&positions);
        let snap = Tolerance { relative: 1e-6 };
        let plain = StateClassifier::new(&c, snap, &bounds, 1.0);
        let glue = plain.with_glued(&glued, 1e-3);
        let tet = [0, 1, 2, 3].map(VertexId);
        assert_eq!(plain.tet(&positions, &scales, &tet), [POS, NEG, POS, POS]);
        assert_eq!(glue.tet(&positions, &scales, &tet), [ON, ON, OUT, POS]);
        for (v, expected) in [(0, ON), (1, ON), (2, OUT), (3, POS)] {
            let id = VertexId(v);
            assert_eq!(glue.vertex(id, positions[v as usize], 1.0), expected);
            assert_eq!(glue.pool_vertex(&positions, &scales, id), expected);
        }
    }
}
