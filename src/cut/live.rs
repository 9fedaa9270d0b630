//! Time-critical cutting of a deformable body (paper §5).
//!
//! A simulation works on one mesh extracted from the MT — the *current mesh* — whose
//! vertices it moves every time step. [`LiveMt`] keeps that mesh, at the positions the host
//! sets ([`LiveMt::set_positions`]), next to the MT, which stays in the rest shape. A cut
//! ([`LiveMt::cut`]) is given in the current (deformed) space and runs in two parts:
//!
//! 1. **Frontier first.** Only the current mesh is cut, at its current positions, by the
//!    plain-mesh engine ([`Cutter::for_mt_frontier`]: the hierarchy finds the tets, cost in
//!    proportion to them; the MT's vertex scales and the MT cut's rules for vertices on the
//!    plane, so it decides as the MT cut will on those tets). The call returns with the
//!    current mesh updated. Each new vertex is a linear combination of older ones (the cut
//!    surface CS of the paper: edge points by their parameter, face points by their
//!    weights, copies), so its rest position follows from the same coefficients.
//! 2. **The rest of the MT, later.** The cut is queued, with the deformation it was made
//!    in (the current mesh's rest and current positions, snapshotted only when they are
//!    about to change while the cut waits). [`LiveMt::process_pending`] cuts the MT with
//!    it: every pool vertex is placed in the space the cut was given in — vertices of the
//!    current mesh where the host put them; vertices made by earlier cuts of this model by
//!    the combinations they were made as (so an earlier crack lies, on every level, where
//!    those cuts put it, and a blade continuing it meets its tips on its contour as at
//!    rest); the others by the displacement of the current tet holding them at rest — and
//!    [`MtCutter::cut_deformed`] makes every decision there, placing new vertices at rest
//!    by the same parameters. Each tet of each level is cut by one plane in that space (CS
//!    pulled back to rest space through the tet's own affine map), so the levels stay
//!    consistent, and the tets of the current frontier are cut exactly as the first part
//!    cut them. Consecutive cuts with no change of positions between them reuse one
//!    placement. An undeformed body needs none: the MT is cut by the polygon itself,
//!    exactly as [`MtCutter::cut`] would.
//!
//! Once the queue is empty (before, the current mesh holds cuts the MT does not have yet),
//! the MT's extraction at the live resolution must hold exactly the current tets (matched
//! by their vertices' rest positions): the current mesh *maps back exactly*, and
//! [`LiveMt::mt_vertex_ids`] names the MT vertex of each current vertex again. Where the
//! two parts decided differently, the current mesh is replaced by that extraction, the
//! host's positions carried over by MT vertex, and the report says so
//! ([`PendingReport::remeshed`]).
//!
//! While cuts are pending the resolution cannot change ([`LiveMt::set_resolution`] refuses,
//! naming the pending cuts), as the paper requires; the current mesh stays usable, and can
//! be moved and cut again.
//!
//! # Limits (measured in tests/mt_live.rs)
//!
//! * A deformation may fold a tet of another level (its placed vertices inverted) that the
//!   cut meets: such a cut cannot be made in the deformed space. It is made at rest with
//!   the polygon mapped by the affine map that best fits the deformation around it
//!   ([`PendingReport::folded`]); the frontier's cut then does not map back, and the
//!   current mesh is replaced by the extraction. That polygon lies close to the plane of
//!   the blade's earlier steps without lying in it, where the MT cut's checks of the
//!   fragments it changed can miss a whole mesh left pinched: the finest, the coarsest
//!   and the live resolution's meshes are extracted and checked after it, and a cut
//!   leaving one invalid is given back (the MT as it was, from a copy taken before) and
//!   refused like the others. (Measured once, a second fallback of the liver bent 5 %
//!   more per step, close to the first fallback's plane: it pinched the coarsest and the
//!   live resolution's meshes. Since the MT cut analyses the coarsest mesh's snapped
//!   vertices as the finest's and makes a polygon that close in the earlier plane, that
//!   cut is valid, and no stress run since — bends growing by 2 % to 20 % per step on
//!   the three shared meshes — has made one this check refuses; the MT cut's own checks
//!   still refuse some fallbacks.)
//! * A body moving *between* the steps of one incision: the vertices the last steps made
//!   (their crack's lips and tips, on every level) were made in the blade's plane, but the
//!   motion has moved them off it by more than any snapping distance, so the next step
//!   would meet that crack on either side of its plane, differently on each level (the MT
//!   refused such steps). When the body has moved since the last cut given in a plane, a
//!   cut given in the same plane takes the vertices the cuts in it made or duplicated as
//!   lying in it (`StateClassifier::with_glued`: their state is that of their projection
//!   onto it), the frontier-first cut and the MT cut alike, so the step continues the crack
//!   and maps back. Measured (tests/mt_live.rs, and blades crossing the shared meshes in 16
//!   steps while the bend grows by 2 % to 100 % of its first amount per step, or swings by
//!   30 %): the only steps refused were a fold's fallback cut at rest and a step after one
//!   (that cut's crack does not lie in the plane: nothing is glued in it after); before,
//!   the liver refused steps at the gentlest motion. A blade
//!   *turning* between the steps of a deformed body is handled only while the body does
//!   not move between them: the MT cut continues a cut at an angle only in the frame it
//!   was made in (see [`super::mt_cut`]'s limits). After a motion, some such steps are
//!   refused — [`process_pending`](LiveMt::process_pending) drops the cut and reports it
//!   ([`PendingReport::refused`]), the current mesh extracted again without it — and the
//!   others leave the two cracks apart. Measured (a vertical blade on an arc turning 8°
//!   per step across each shared mesh, 15 steps, the queue drained after each): at rest
//!   nothing is refused and the corner comes off (the current mesh replaced 1, 2 and 4
//!   times on fandisk, pinion and liver, where the two parts decided a step differently);
//!   the body bent by 0.5 % of its diagonal before the sweep, nothing is refused on
//!   fandisk, which loses its corner with every step mapped back (tests/mt_live.rs), and 1
//!   and 2 steps on pinion and liver, which stay in one piece (3, 4 and 4 steps were
//!   refused, every other one from the fourth, before the MT kept deformed cuts with their
//!   frame); bent 2 % more at every step, one step is refused (pinion's) but the body
//!   stays in one piece on the three meshes, joined through faces (likely where two
//!   steps' cracks fail to meet: the motion moves the last crack's end off the line the
//!   next step begins on, and nothing glues it for a step at an angle). A host that sets
//!   the positions before every step, as a simulation does, gives the MT a new frame
//!   each time even with the same bend: its positions of the vertices the last cut made
//!   replace those the cut interpolated, and the pool vertices not in the current mesh
//!   are placed through them. Then 3, 4 and 4 steps are refused (the steps' cracks meet
//!   without the turning tips' decisions, leaving faces doubled in a fragment), as before
//!   cuts were recorded with their frame. Tried: mapping the last cut's polygon into the
//!   new frame by an affine fit of the placed pool, and the step's start with it, so the
//!   MT continues it at an angle across frames: the growing bend then had 3, 4 and 3
//!   steps refused (the MT's checks: a coarsest mesh pinched, faces doubled).
//! * At rest too, a step continuing the last one at an angle is refused where the direct
//!   MT cut refuses it ([`super::scalpel`]'s limits): on random scalpel paths (100 per
//!   shared mesh, each cut drained before the next), 423, 288 and 420 of 6,111 steps on
//!   fandisk, pinion and liver were dropped, the model and the current mesh valid, each
//!   such step's incision missing from both (the frontier's cut undone by the
//!   extraction), each polygon given alone ([`LiveMt::cut`]). Given as whole sweeps
//!   ([`LiveMt::cut_sweep`]: a refused sweep taken as another split where the MT takes
//!   one, the current mesh then extracted again), the first 25 paths per mesh lose 119,
//!   81 and 134 of their 1,758 steps instead of 170, 106 and 178 (37, 14 and 38 sweeps
//!   taken as another split). The queued work pays for it: processing the queue took
//!   34.0, 23.9 and 43.0 s over those paths instead of 15.2, 13.5 and 16.7, a refused or
//!   re-split step 150–200 ms instead of 47–61 (the cuts of the other splits, each on a
//!   copy of the cutter), the others 1.0–2.2 s more in all (a copy of the cutter per sweep
//!   of two triangles meeting the body's box, a few milliseconds each on these MTs).
//! * A cut given close to the plane of an earlier cut of the model without lying in it
//!   (within [`PLANE_SNAP`] of the model's size, a blade re-entering an incision) is made
//!   in that plane, on the current mesh and on the MT alike ([`LiveCut::moved_to_plane`];
//!   see [`super::mt_cut`]'s limits for why). The earlier cuts are this model's and those
//!   the MT's cut record keeps the planes of (cuts at rest before the live model was
//!   made, a model saved and loaded).
//! * A queued cut is processed whole: [`process_pending`](LiveMt::process_pending) checks
//!   its budget between cuts, so it may overrun by one cut (the DAG update of a cut is one
//!   step over all its fragments, [`super::mt_cut`]).
//! * A queued cut the MT refuses (a model outgrowing its ids, a fold whose fallback polygon
//!   is degenerate) stays queued, the MT unchanged, and every later
//!   [`process_pending`](LiveMt::process_pending) reports the same error: the current
//!   mesh, already cut, stays usable, but the resolution cannot change again.
//! * A resolution given as a budget may extract another frontier after a cut (cuts add
//!   tets): then the current mesh is replaced rather than matched.
//! * Vertices that a resolution change brings in (not in the current mesh before) are
//!   placed by the displacement of the current tet containing them at rest; the host's
//!   own state (velocities, stresses) for them must be interpolated by the host, which
//!   [`LiveMt::mt_vertex_ids`] lets it do.

use super::classify::{OriginPositions, VertexOrigin, origin_positions};
use super::cutter::Cutter;
use super::mt_cut::{MtCutStats, MtCutter, continues_a_crack_plane};
use super::options::{CutError, CutOptions};
use super::report::CutStats;
use crate::geom::{Aabb, CutPolygon, DVec3, PLANE_SNAP, PolygonError, snap_to_plane};
use crate::mesh::fxhash::FxBuild;
use crate::mesh::{Tet, TetMesh, VertexId};
use crate::mt::{ExtractError, ExtractOptions, Mt};
use std::collections::{HashMap, VecDeque};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Why a live operation was refused (nothing changed).
#[derive(Debug, thiserror::Error)]
pub enum LiveError {
    #[error(transparent)]
    Cut(#[from] CutError),
    #[error(transparent)]
    Extract(#[from] ExtractError),
    #[error("the cut mapped to rest space is not a cutting polygon: {0}")]
    Polygon(#[from] PolygonError),
    #[error(
        "{cuts} cut(s) are still pending: process them (process_pending) before changing \
         the resolution"
    )]
    Pending { cuts: usize },
}

/// How much queued work [`LiveMt::process_pending`] may do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PendingBudget {
    /// Start no further cut once this many fragments have been processed.
    Fragments(usize),
    /// Start no further cut once this much time has passed.
    Time(Duration),
    /// Everything queued.
    All,
}

/// What [`LiveMt::process_pending`] did.
#[derive(Clone, Debug, Default)]
pub struct PendingReport {
    /// The MT cuts made, in order.
    pub cuts: Vec<MtCutStats>,
    /// Fragments they involved.
    pub fragments: usize,
    /// Cuts still queued.
    pub cuts_left: usize,
    /// The current mesh was replaced by the MT's extraction (its vertex and tet numbering
    /// changed; positions carried over by MT vertex): see the module docs.
    pub remeshed: bool,
    /// Cuts whose deformation folded a tet of the MT they meet, made at rest instead with
    /// the polygon mapped by the affine map closest to the deformation around it (their
    /// frontier cut then does not map back: the current mesh is replaced).
    pub folded: usize,
    /// Cuts the MT refused ([`CutError::MtInconsistent`]: it is as it was without them),
    /// dropped from the queue; the current mesh, which had them, is then replaced by the
    /// MT's extraction (`remeshed`).
    pub refused: Vec<CutError>,
    /// Scalpel sweeps ([`LiveMt::cut_sweep`]) the MT refused as the current mesh was cut
    /// and took as another split of them: the current mesh is then replaced by the MT's
    /// extraction (`remeshed`).
    pub other_splits: usize,
    pub seconds: f64,
}

/// What the frontier-first part of a cut did.
#[derive(Clone, Debug)]
pub struct LiveCut {
    /// The cut of the current mesh.
    pub stats: CutStats,
    /// Cuts queued for the rest of the MT, this one included.
    pub pending: usize,
    /// Time of the whole call (the current mesh's cut and the bookkeeping).
    pub seconds: f64,
    /// The polygon lay close to the plane of an earlier cut of this model (or of a crack
    /// the MT's record keeps) without lying in it, and was cut in that plane
    /// ([`PLANE_SNAP`]), here and on the MT.
    pub moved_to_plane: bool,
}

/// The current mesh as a queued cut saw it: how rest space mapped to the space its polygon
/// was given in.
struct Deformation {
    tets: Vec<Tet>,
    rest: Vec<DVec3>,
    current: Vec<DVec3>,
}

enum Frame {
    /// Rest space (the body was undeformed).
    Rest,
    /// The current mesh as it is now (snapshotted before it changes).
    Now,
    Snapshot(Arc<Deformation>),
}

struct PendingCut {
    polygon: CutPolygon,
    frame: Frame,
    /// The positions' epoch the cut was made in.
    epoch: u64,
    /// The cut changed the current mesh.
    changed: bool,
    /// The first polygon of a scalpel sweep ([`LiveMt::cut_sweep`]): the sweep's polygons
    /// queued from this one (1 for a lone cut), and the other ways of splitting it, which
    /// the MT may take where it refuses these.
    group: usize,
    alternatives: Vec<Vec<CutPolygon>>,
}

/// An MT with a current mesh that a simulation deforms and cuts (see the [module
/// docs](self)).
pub struct LiveMt {
    cutter: MtCutter,
    resolution: ExtractOptions,
    current: Cutter,
    rest: Vec<DVec3>,
    /// MT vertex of each current vertex; [`VertexId::INVALID`] while its cut is pending.
    mt_vertex: Vec<VertexId>,
    /// Some current position differs from its rest position.
    deformed: bool,
    /// Every current position is its rest position bit for bit (not just equal: a zero's
    /// sign may differ): a cut's new vertices then lie at rest where the current mesh put
    /// them, and are not placed a second time.
    at_rest: bool,
    pending: VecDeque<PendingCut>,
    /// A queued cut was decided differently on the MT: replace the current mesh once the
    /// queue is empty.
    remesh_due: bool,
    /// A processed cut changed the MT or the current mesh: match them once the queue is
    /// empty (before, the current mesh holds cuts the MT does not have yet).
    match_due: bool,
    /// Per MT vertex made by a cut of this model: the combination it was made as (indexed
    /// from `first_cut_vertex`).
    cut_origins: Vec<VertexOrigin>,
    first_cut_vertex: usize,
    /// Where each cut's origins end in `cut_origins` (a cut's new vertices are placed
    /// together, as [`origin_positions`] places them at rest).
    cut_ends: Vec<usize>,
    /// Incremented by every change of positions.
    epoch: u64,
    /// The pool placed for the last deformed cut, and its epoch: later cuts of the same
    /// epoch extend it rather than place the pool again, so every vertex stays exactly
    /// where the earlier cuts saw it (a blade continuing a crack meets its tips where they
    /// were made).
    placement: Option<(u64, Vec<DVec3>)>,
    /// The rest positions of a frontier-first cut's new vertices (a deformed body's), kept
    /// for the next cut so that it does not allocate them.
    new_rest: OriginPositions,
    /// The planes cuts were given in, each once: the steps of a blade moved in its own
    /// plane share one.
    planes: Vec<CutPlane>,
}

/// A plane cuts of a live model were given in, and the vertices they made in it: when the
/// body has moved since the last of them, a cut given in the plane takes those vertices as
/// lying in it (`StateClassifier::with_glued`), the MT cut and the frontier-first cut alike.
struct CutPlane {
    /// Unit normal and a point.
    normal: DVec3,
    point: DVec3,
    /// A cut given in it was made at rest by another polygon (a fold, see the limits): its
    /// crack does not lie in the plane, so nothing is glued in it any more.
    broken: bool,
    /// The MT vertices the cuts given in it made or duplicated, and the positions' epoch
    /// of the last of those cuts on the MT.
    mt: Vec<VertexId>,
    mt_epoch: u64,
    /// The same for the current mesh's vertices and frontier-first cuts.
    current: Vec<VertexId>,
    current_epoch: u64,
}

impl CutPlane {
    /// A plane no cut of this model was given in yet.
    fn new(normal: DVec3, point: DVec3) -> CutPlane {
        CutPlane {
            normal,
            point,
            broken: false,
            mt: Vec::new(),
            mt_epoch: u64::MAX,
            current: Vec::new(),
            current_epoch: u64::MAX,
        }
    }
}

impl LiveMt {
    /// A live model on `mt` (which should be valid), its current mesh extracted at
    /// `resolution` and at rest, cut with `options` (an MT cut's: see [`MtCutter::new`]).
    pub fn new(
        mt: Mt,
        resolution: &ExtractOptions,
        options: CutOptions,
    ) -> Result<LiveMt, LiveError> {
        let e = mt.extract(resolution)?;
        let cutter = MtCutter::new(mt, options)?;
        let rest = e.mesh.positions().to_vec();
        let current = current_cutter(&cutter, e.mesh, &e.vertex_ids)?;
        let first_cut_vertex = cutter.mt().nb_vertices();
        // The planes of the cracks the MT's earlier cuts made at rest (its cut record): a
        // cut close to one is moved onto it here as the MT cut moves it, so the current
        // mesh's cut maps back (not moved, it was remeshed when the queue drained).
        let planes = cutter.mt().info().cuts.made.planes.iter();
        let planes = planes.map(|&[n, p]| CutPlane::new(n, p)).collect();
        let mut live = LiveMt {
            cut_origins: Vec::new(),
            first_cut_vertex,
            cut_ends: Vec::new(),
            epoch: 0,
            placement: None,
            new_rest: OriginPositions::default(),
            planes,
            cutter,
            resolution: *resolution,
            current,
            rest,
            mt_vertex: e.vertex_ids,
            deformed: false,
            at_rest: true,
            pending: VecDeque::new(),
            remesh_due: false,
            match_due: false,
        };
        live.keep_room();
        Ok(live)
    }

    /// Keeps room in the current mesh's arrays, and in the rest positions and MT ids that
    /// grow with its vertices, for the next frontier-first cuts ([`ROOM`]), its memory
    /// mapped: their reallocation (a copy of each) and the faults of fresh pages stay out
    /// of the time-critical cut. Without it, a live model's first cut grew the rest
    /// positions; with the room reserved but not mapped, a scalpel step met about 3 page
    /// faults, 1.5 once mapped (the rest: the cut's own lists growing to a larger cut).
    fn keep_room(&mut self) {
        self.current.keep_room(ROOM);
        let room = (self.rest.len() as f64 * ROOM).ceil() as usize;
        self.rest.reserve(room);
        self.mt_vertex.reserve(room);
        crate::mesh::touch_spare(&mut self.rest);
        crate::mesh::touch_spare(&mut self.mt_vertex);
    }

    /// The MT, in rest space, with every cut processed so far.
    pub fn mt(&self) -> &Mt {
        self.cutter.mt()
    }

    /// The current mesh, at the current positions.
    pub fn mesh(&self) -> &TetMesh {
        self.current.mesh()
    }

    /// Rest position of each current vertex.
    pub fn rest_positions(&self) -> &[DVec3] {
        &self.rest
    }

    /// MT vertex of each current vertex ([`VertexId::INVALID`] for vertices made by a cut
    /// still pending).
    pub fn mt_vertex_ids(&self) -> &[VertexId] {
        &self.mt_vertex
    }

    pub fn resolution(&self) -> &ExtractOptions {
        &self.resolution
    }

    /// Cuts queued for the rest of the MT.
    pub fn pending_cuts(&self) -> usize {
        self.pending.len()
    }

    /// Sets the current (deformed) position of every current vertex. Refused, with
    /// nothing changed, when the count is wrong, a coordinate is not finite or a tet would
    /// be inverted or flat.
    pub fn set_positions(&mut self, positions: &[DVec3]) -> Result<(), LiveError> {
        // Validates before anything changes; the snapshot copies the old positions.
        if positions.len() != self.rest.len() {
            return Err(CutError::PositionCount {
                count: positions.len(),
                expected: self.rest.len(),
            }
            .into());
        }
        self.freeze_pending();
        self.current.set_positions(positions)?;
        self.epoch += 1;
        self.deformed = positions != self.rest.as_slice();
        let bits = |p: &DVec3| p.to_array().map(f64::to_bits);
        self.at_rest = !self.deformed
            && positions
                .iter()
                .zip(&self.rest)
                .all(|(p, r)| bits(p) == bits(r));
        Ok(())
    }

    /// The frontier-first cut (see the [module docs](self)): cuts the current mesh with
    /// `polygon`, given in the current space, queues the rest of the MT and returns.
    pub fn cut(&mut self, polygon: &CutPolygon) -> Result<LiveCut, LiveError> {
        let start = Instant::now();
        // Close to an earlier cut's plane without lying in it (a blade re-entering an
        // incision): cut in that plane, here and on the MT alike (see `snap_to_plane`).
        let planes = self.planes.iter().map(|p| (p.normal, p.point));
        let in_plane = snap_to_plane(
            polygon,
            planes,
            PLANE_SNAP * self.cutter.bounds().diagonal(),
        );
        let polygon = in_plane.as_ref().unwrap_or(polygon);
        self.freeze_pending();
        let n = self.rest.len();
        let glued = match self.plane_of(polygon).map(|k| &self.planes[k]) {
            Some(p) if self.deformed && p.current_epoch != self.epoch => &p.current[..],
            _ => &[],
        };
        // Earlier cracks' vertices on the plane outside the polygon are `OUT` as the MT
        // cut will take them, at rest after the cuts queued before this one.
        let crack_out = self.deformed || {
            let recorded = self.cutter.mt().info().cuts.made.planes.iter();
            let queued = self
                .pending
                .iter()
                .filter(|p| matches!(p.frame, Frame::Rest))
                .map(|p| (p.polygon.normal(), p.polygon.plane().points[0]));
            continues_a_crack_plane(polygon, recorded.map(|&[n, p]| (n, p)).chain(queued))
        };
        let r = self.current.cut_glued(polygon, glued, crack_out)?;
        let added = if self.at_rest {
            &self.current.mesh().positions()[n..]
        } else {
            self.new_rest.compute(&self.rest, &r.origins, None)
        };
        debug_assert_eq!(n + added.len(), self.current.mesh().nb_vertices());
        debug_assert!(!self.at_rest || added == origin_positions(&self.rest, &r.origins));
        self.rest.extend_from_slice(added);
        self.mt_vertex.resize(self.rest.len(), VertexId::INVALID);
        let (k, epoch) = (self.plane_index(polygon), self.epoch);
        let plane = &mut self.planes[k];
        plane.current_epoch = epoch;
        if !plane.broken {
            glue_made(&mut plane.current, n, &r.origins);
        }
        self.pending.push_back(PendingCut {
            polygon: polygon.clone(),
            frame: if self.deformed {
                Frame::Now
            } else {
                Frame::Rest
            },
            epoch: self.epoch,
            changed: r.stats.tets_cut > 0 || r.stats.vertex_copies > 0,
            group: 1,
            alternatives: Vec::new(),
        });
        Ok(LiveCut {
            stats: r.stats,
            pending: self.pending.len(),
            seconds: start.elapsed().as_secs_f64(),
            moved_to_plane: in_plane.is_some(),
        })
    }

    /// The frontier-first cut of a scalpel's sweep given as every way of splitting it
    /// ([`crate::geom::scalpel_sweep_splits`], [`super::Incision::step_sweep`]): the
    /// current mesh is cut with the first split's polygons ([`cut`](Self::cut), one
    /// [`LiveCut`] each), and the MT later with the first split it takes. Where the MT
    /// refuses the first split ([`CutError::MtInconsistent`]: the second of two triangles
    /// meeting the first at an angle, see [`super::scalpel`]'s limits),
    /// [`process_pending`](Self::process_pending) cuts it with the next, as
    /// [`super::Scalpel::step`] does, on the MT as the sweep found it (a copy of the
    /// cutter taken before the sweep, put back between tries), and the current mesh is
    /// then replaced by the MT's extraction ([`PendingReport::other_splits`]); when none
    /// is taken, the MT keeps what lone cuts of the first split's polygons would have left
    /// (the refused one dropped, [`PendingReport::refused`]). Only a body at rest has its
    /// sweeps so retried (the others' polygons are queued as given to `cut`: a deformed
    /// body's queued cut is made in the frame it was given in, which another split does
    /// not have). The price is paid in `process_pending`, which processes such a sweep
    /// whole (its budget may overrun by one sweep): a copy of the cutter per sweep of two
    /// triangles that meets the body's box, and up to three more splits' cuts, each
    /// tried on a copy, for a refused one (measured in the module docs' limits). On error
    /// (a polygon the current mesh refuses) the polygons before it stay cut and queued,
    /// as with `cut`.
    pub fn cut_sweep(&mut self, splits: &[Vec<CutPolygon>]) -> Result<Vec<LiveCut>, LiveError> {
        // No split, or a first one of no polygon: nothing to cut (other empty splits are
        // not tried either).
        let Some(first) = splits.first().filter(|f| !f.is_empty()) else {
            return Ok(Vec::new());
        };
        let queued = self.pending.len();
        let cuts = first
            .iter()
            .map(|p| self.cut(p))
            .collect::<Result<Vec<_>, _>>()?;
        let alternatives: Vec<Vec<CutPolygon>> = splits[1..]
            .iter()
            .filter(|s| !s.is_empty())
            .cloned()
            .collect();
        if !self.deformed && (first.len() > 1 || !alternatives.is_empty()) {
            let head = &mut self.pending[queued];
            head.group = first.len();
            head.alternatives = alternatives;
        }
        Ok(cuts)
    }

    /// Cuts the MT with queued cuts, oldest first, while `budget` lasts (checked before
    /// each cut, a sweep's polygons cut together: see the module docs' limits).
    pub fn process_pending(&mut self, budget: PendingBudget) -> Result<PendingReport, LiveError> {
        let start = Instant::now();
        let mut report = PendingReport::default();
        while let Some(front) = self.pending.front() {
            let spent = match budget {
                PendingBudget::Fragments(n) => report.fragments >= n,
                PendingBudget::Time(d) => start.elapsed() >= d,
                PendingBudget::All => false,
            };
            if spent {
                break;
            }
            if front.group > 1 || !front.alternatives.is_empty() {
                self.process_sweep(&mut report);
                continue;
            }
            // The polygon the MT was cut by when a fold made it fall back to one at rest.
            let mut fallback: Option<CutPolygon> = None;
            let made = match &front.frame {
                Frame::Rest => self.cutter.cut(&front.polygon),
                frame => {
                    let now;
                    let d = match frame {
                        Frame::Snapshot(d) => d.as_ref(),
                        _ => {
                            now = self.snapshot();
                            &now
                        }
                    };
                    let placed = match self.placement.take() {
                        Some((e, mut placed)) if e == front.epoch => {
                            self.extend_placement(&mut placed);
                            placed
                        }
                        _ => self.place_pool(d),
                    };
                    let glued = match self.plane_of(&front.polygon).map(|k| &self.planes[k]) {
                        Some(p) if p.mt_epoch != front.epoch => &p.mt[..],
                        _ => &[],
                    };
                    let made = match self.cutter.cut_deformed(&front.polygon, &placed, glued) {
                        Err(CutError::DeformationFolds { .. }) => {
                            report.folded += 1;
                            self.remesh_due = true;
                            let at_rest = rest_polygon(&front.polygon, d)?;
                            let made = cut_checked(&mut self.cutter, &self.resolution, &at_rest);
                            fallback = Some(at_rest);
                            made
                        }
                        r => r,
                    };
                    self.placement = Some((front.epoch, placed));
                    made
                }
            };
            let stats = match made {
                Err(e @ CutError::MtInconsistent { .. }) => {
                    // The MT cannot take this cut and gave it back unchanged: the current
                    // mesh, which has it, is extracted again from the MT (without it).
                    self.pending.pop_front();
                    self.remesh_due = true;
                    report.refused.push(e);
                    continue;
                }
                r => r?,
            };
            let front = self.pending.pop_front().expect("the front cut");
            let origins = self.cutter.last_origins().to_vec();
            self.record(&front, fallback.is_some(), &origins, stats, &mut report);
        }
        if self.pending.is_empty() && self.match_due {
            self.match_due = false;
            if !self.remesh_due && !self.resolve()? {
                self.remesh_due = true;
            }
        }
        if self.pending.is_empty() && self.remesh_due {
            self.remesh()?;
            self.remesh_due = false;
            report.remeshed = true;
        }
        report.cuts_left = self.pending.len();
        self.keep_room();
        report.seconds = start.elapsed().as_secs_f64();
        Ok(report)
    }

    /// Keeps what an MT cut of the queued cut `cut` made (`origins`: its new vertices'
    /// combinations, [`MtCutter::last_origins`]; `fallback`: made at rest by another
    /// polygon, a fold's) for the cuts after it, and reports it.
    fn record(
        &mut self,
        cut: &PendingCut,
        fallback: bool,
        origins: &[VertexOrigin],
        stats: MtCutStats,
        report: &mut PendingReport,
    ) {
        let first = self.first_cut_vertex + self.cut_origins.len();
        let k = self.plane_index(&cut.polygon);
        let plane = &mut self.planes[k];
        plane.mt_epoch = cut.epoch;
        if fallback {
            // The crack this cut left in the MT does not lie in its plane: the blade's
            // next steps in it meet that crack as they would at rest, nothing glued.
            plane.broken = true;
            plane.mt = Vec::new();
            plane.current = Vec::new();
        } else if !plane.broken {
            glue_made(&mut plane.mt, first, origins);
        }
        self.cut_origins.extend_from_slice(origins);
        self.cut_ends.push(self.cut_origins.len());
        if let Some((_, placed)) = &mut self.placement {
            let mut p = std::mem::take(placed);
            self.extend_placement(&mut p);
            self.placement.as_mut().expect("just seen").1 = p;
        }
        report.fragments += stats.fragments_involved;
        report.cuts.push(stats);
        // A cut that changed neither the MT nor the current mesh leaves the match as is.
        self.match_due |= cut.changed
            || stats.tets_cut > 0
            || stats.vertex_copies > 0
            || stats.ghosts_split > 0
            || stats.crack_ghosts > 0;
    }

    /// Cuts the MT with the scalpel sweep at the front of the queue (queued at rest by
    /// [`cut_sweep`](Self::cut_sweep)): its first split, or where the MT refuses that, the
    /// next it takes, each tried on the MT as the sweep found it (a copy of the cutter
    /// taken before the first, for sweeps whose box meets the body's). When none is
    /// taken, the first split's polygons before the refused one are kept cut and that one
    /// is dropped, as lone cuts would be; the polygons after it, and the whole sweep when
    /// the first split fails otherwise than by a refusal, are left queued as lone cuts,
    /// which the caller's loop cuts as it cuts any other.
    fn process_sweep(&mut self, report: &mut PendingReport) {
        let head = &self.pending[0];
        let n = head.group;
        let first: Vec<CutPolygon> = self
            .pending
            .iter()
            .take(n)
            .map(|p| p.polygon.clone())
            .collect();
        // A sweep missing the body's box cuts nothing and cannot be refused.
        let reach = first.iter().fold(Aabb::EMPTY, |b, p| b.union(&p.bbox()));
        if !reach.intersects(&self.cutter.bounds()) {
            return self.unbundle(n);
        }
        let mut splits = vec![first];
        splits.extend(head.alternatives.iter().cloned());
        let saved = self.cutter.snapshot();
        // `self.cutter` is as the sweep found it (a cut the MT refuses gives itself back).
        let mut fresh = true;
        // What the first split took before the MT refused it: the cutter, the cuts, why.
        let mut partial = None;
        let mut refusal = None;
        for (k, split) in splits.iter().enumerate() {
            if !fresh {
                self.cutter = saved.snapshot();
            }
            let mut made = Vec::new();
            let mut failed = None;
            for polygon in split {
                match self.cutter.cut(polygon) {
                    Ok(stats) => made.push((stats, self.cutter.last_origins().to_vec())),
                    Err(e) => {
                        failed = Some(e);
                        break;
                    }
                }
            }
            let Some(e) = failed else {
                return self.take_split(k, &splits[k], made, report);
            };
            fresh = made.is_empty();
            if k == 0 {
                // Another split is tried only where the MT refused the first (anything else
                // is met again by the lone cuts, as it would be without the sweep).
                if !matches!(e, CutError::MtInconsistent { .. }) {
                    self.cutter = saved;
                    return self.unbundle(n);
                }
                if !made.is_empty() {
                    partial = Some((std::mem::replace(&mut self.cutter, saved.snapshot()), made));
                    fresh = true;
                }
                refusal = Some(e);
            }
        }
        // None taken: as the lone cuts of the first split would have gone.
        let e = refusal.expect("the first split was refused");
        let taken = match partial {
            Some((cutter, made)) => {
                self.cutter = cutter;
                made
            }
            None => {
                self.cutter = saved;
                Vec::new()
            }
        };
        let kept = taken.len();
        for (stats, origins) in taken {
            let cut = self
                .pending
                .pop_front()
                .expect("a cut the first split took");
            self.record(&cut, false, &origins, stats, report);
        }
        self.pending.pop_front();
        report.refused.push(e);
        self.remesh_due = true;
        self.unbundle(n - kept - 1);
    }

    /// The sweep at the front of the queue, or what is left of it (`left` polygons), as
    /// lone cuts.
    fn unbundle(&mut self, left: usize) {
        if left > 0 {
            let head = &mut self.pending[0];
            head.group = 1;
            head.alternatives = Vec::new();
        }
    }

    /// Keeps the `k`th split of the sweep at the front of the queue, which the MT took
    /// (`made`: each polygon's cut and new vertices), in place of its queued polygons.
    fn take_split(
        &mut self,
        k: usize,
        split: &[CutPolygon],
        made: Vec<(MtCutStats, Vec<VertexOrigin>)>,
        report: &mut PendingReport,
    ) {
        let members: Vec<PendingCut> = self.pending.drain(..self.pending[0].group).collect();
        if k == 0 {
            for (cut, (stats, origins)) in members.iter().zip(made) {
                self.record(cut, false, &origins, stats, report);
            }
            return;
        }
        // The current mesh was cut with the first split: replaced once the queue is empty.
        report.other_splits += 1;
        self.remesh_due = true;
        for (polygon, (stats, origins)) in split.iter().zip(made) {
            let cut = PendingCut {
                polygon: polygon.clone(),
                frame: Frame::Rest,
                epoch: members[0].epoch,
                changed: true,
                group: 1,
                alternatives: Vec::new(),
            };
            self.record(&cut, false, &origins, stats, report);
        }
    }

    /// Extracts the current mesh at `resolution` (refused while cuts are pending), its
    /// vertices at the positions the current deformation gives them (see the module docs).
    pub fn set_resolution(&mut self, resolution: &ExtractOptions) -> Result<(), LiveError> {
        if !self.pending.is_empty() {
            return Err(LiveError::Pending {
                cuts: self.pending.len(),
            });
        }
        resolution.check()?;
        self.resolution = *resolution;
        self.remesh()
    }

    /// The MT, after processing every queued cut.
    pub fn into_mt(mut self) -> Result<Mt, LiveError> {
        self.process_pending(PendingBudget::All)?;
        Ok(self.cutter.into_mt())
    }

    /// Before the current mesh changes: queued cuts made in it take a copy of it.
    fn freeze_pending(&mut self) {
        if !self.pending.iter().any(|p| matches!(p.frame, Frame::Now)) {
            return;
        }
        let snapshot = Arc::new(self.snapshot());
        for p in self.pending.iter_mut() {
            if matches!(p.frame, Frame::Now) {
                p.frame = Frame::Snapshot(snapshot.clone());
            }
        }
    }

    /// The current mesh as it is, with its rest positions.
    fn snapshot(&self) -> Deformation {
        Deformation {
            tets: self.current.mesh().tets().to_vec(),
            rest: self.rest.clone(),
            current: self.current.mesh().positions().to_vec(),
        }
    }

    /// Every pool vertex placed in the space of `d`'s current positions (see the module
    /// docs): vertices of the current mesh exactly where the host put them; vertices made
    /// by earlier cuts of this model by the combinations they were made as, so an earlier
    /// crack on every level lies where those cuts put it in this space (a blade continuing
    /// it meets its tips on its contour, as at rest); the others by the current tet holding
    /// them at rest.
    fn place_pool(&self, d: &Deformation) -> Vec<DVec3> {
        let mt = self.cutter.mt();
        let mut host: Vec<Option<DVec3>> = vec![None; mt.nb_vertices()];
        for (i, &v) in self.mt_vertex.iter().enumerate().take(d.current.len()) {
            if v.is_valid() && d.rest[i] == mt.position(v) {
                host[v.idx()] = Some(d.current[i]);
            }
        }
        let mut locator = Locator::new(&d.rest, &d.tets);
        let mut placed: Vec<DVec3> = host[..self.first_cut_vertex]
            .iter()
            .enumerate()
            .map(|(v, h)| h.unwrap_or_else(|| locator.map(mt.positions()[v], &d.current)))
            .collect();
        self.extend_placement(&mut placed);
        for (p, h) in placed.iter_mut().zip(&host).skip(self.first_cut_vertex) {
            if let Some(h) = h {
                *p = *h;
            }
        }
        placed
    }

    /// The plane `polygon` lies in, among those of earlier cuts (normals parallel and its
    /// first point on the plane, to 1e-9 of its coordinates and size).
    fn plane_of(&self, polygon: &CutPolygon) -> Option<usize> {
        let (n, q) = (polygon.normal(), polygon.points()[0]);
        let b = polygon.bbox();
        let tolerance = 1e-9 * (q.abs().max_element() + (b.max - b.min).length());
        self.planes.iter().position(|p| {
            p.normal.cross(n).length() <= 1e-9 && p.normal.dot(q - p.point).abs() <= tolerance
        })
    }

    /// [`plane_of`](Self::plane_of), the plane added when new.
    fn plane_index(&mut self, polygon: &CutPolygon) -> usize {
        self.plane_of(polygon).unwrap_or_else(|| {
            self.planes
                .push(CutPlane::new(polygon.normal(), polygon.plane().points[0]));
            self.planes.len() - 1
        })
    }

    /// Places the pool's vertices after those of `placed` (all made by cuts of this model,
    /// `placed` ending where a cut's vertices begin) by the combinations they were made as,
    /// a cut's vertices together as [`origin_positions`] places them at rest (points at the
    /// same place, seen from the two lips of a crack, equal to the bit).
    fn extend_placement(&self, placed: &mut Vec<DVec3>) {
        let mut start = placed.len() - self.first_cut_vertex;
        let first = self.cut_ends.partition_point(|&e| e <= start);
        for &end in &self.cut_ends[first..] {
            let made = origin_positions(placed, &self.cut_origins[start..end]);
            placed.extend(made);
            start = end;
        }
    }

    /// Names the MT vertex of every current vertex, the queue empty: the MT's extraction
    /// at the live resolution must hold exactly the current tets (matched by the rest
    /// positions of their vertices: no two tets of a valid mesh have the same four), each
    /// current vertex then being the extraction's vertex at its place in the matched tets.
    /// False (ids unchanged) when the current mesh does not map back exactly.
    fn resolve(&mut self) -> Result<bool, LiveError> {
        let mt = self.cutter.mt();
        let extracted = mt.extract_tets(&self.resolution)?;
        let (tets, rest) = (self.current.mesh().tets(), &self.rest[..]);
        if extracted.len() != tets.len() {
            return Ok(false);
        }
        let at = mt.positions();
        let by_positions = || {
            let all = vec![VertexId::INVALID; rest.len()];
            let n = tets.len();
            resolve_by_positions(tets, rest, &extracted, at, 0..n, 0..n, all)
        };
        let ids = match resolve_by_ids(tets, rest, &self.mt_vertex, &extracted, at) {
            Some(ids) => {
                debug_assert_eq!(Some(&ids), by_positions().as_ref());
                Some(ids)
            }
            None => by_positions(),
        };
        Ok(match ids {
            Some(ids) => {
                self.mt_vertex = ids;
                true
            }
            None => false,
        })
    }

    /// Replaces the current mesh by the MT's extraction at the current resolution, each
    /// vertex at its current position (by MT vertex) or placed through the current
    /// deformation.
    fn remesh(&mut self) -> Result<(), LiveError> {
        let e = self.cutter.mt().extract(&self.resolution)?;
        let mut current: HashMap<VertexId, DVec3, FxBuild> = HashMap::default();
        for (i, &v) in self.mt_vertex.iter().enumerate() {
            if v.is_valid() {
                current.insert(v, self.current.mesh().position(VertexId::from_usize(i)));
            }
        }
        let mut locator = Locator::new(&self.rest, self.current.mesh().tets());
        let positions: Vec<DVec3> = e
            .vertex_ids
            .iter()
            .zip(e.mesh.positions())
            .map(|(v, &p)| {
                current
                    .get(v)
                    .copied()
                    .unwrap_or_else(|| locator.map(p, self.current.mesh().positions()))
            })
            .collect();
        let rest = e.mesh.positions().to_vec();
        let mut cutter = current_cutter(&self.cutter, e.mesh, &e.vertex_ids)?;
        // A deformation placing some new vertex badly (inverted tets) leaves the mesh at
        // rest: the host sets positions again.
        let deformed = positions != rest && cutter.set_positions(&positions).is_ok();
        self.current = cutter;
        self.rest = rest;
        self.mt_vertex = e.vertex_ids;
        // The current mesh's vertices are numbered anew: its glued ones are the MT's.
        let mut current_of = vec![VertexId::INVALID; self.cutter.mt().nb_vertices()];
        for (i, v) in self.mt_vertex.iter().enumerate() {
            current_of[v.idx()] = VertexId::from_usize(i);
        }
        for p in &mut self.planes {
            p.current.clear();
            p.current.extend(
                p.mt.iter()
                    .map(|v| current_of[v.idx()])
                    .filter(|v| v.is_valid()),
            );
        }
        self.keep_room();
        self.deformed = deformed;
        // Not deformed, the mesh holds the extraction's own positions.
        self.at_rest = !deformed;
        // The vertices new to the current mesh were placed here, not by earlier placements.
        self.epoch += 1;
        Ok(())
    }
}

/// The bits of a tet's rest positions, sorted: the key [`LiveMt::resolve`] matches tets by.
fn position_key(ps: [DVec3; 4]) -> [[u64; 3]; 4] {
    let mut k = ps.map(|p| p.to_array().map(f64::to_bits));
    k.sort_unstable();
    k
}

/// [`LiveMt::resolve`]'s matching, from what the current mesh already knows: tets whose
/// vertices all have MT vertices (all but those a cut made since the last match) are
/// matched by those, their rest positions compared bit for bit; only the others, with the
/// `extracted` tets left over (pool tets, by MT vertex, at positions `at`), by rest
/// positions ([`resolve_by_positions`]). What it returns is what matching every tet by
/// positions gives (the same tets, every one of their positions equal, so the same
/// vertices); None where it cannot tell (a cut that gave a known vertex's tets another MT
/// vertex), for matching by positions to decide. The extracted tets are bucketed by their
/// first current vertex, not hashed: a table as large as the mesh, filled at random, cost
/// most of the matching.
fn resolve_by_ids(
    tets: &[Tet],
    rest: &[DVec3],
    mt_vertex: &[VertexId],
    extracted: &[Tet],
    at: &[DVec3],
) -> Option<Vec<VertexId>> {
    const UNKNOWN: u32 = u32::MAX;
    // The current vertex of each MT vertex the current mesh knows.
    let mut current_of = vec![UNKNOWN; at.len()];
    for (v, m) in mt_vertex.iter().enumerate() {
        if m.is_valid() && std::mem::replace(current_of.get_mut(m.idx())?, v as u32) != UNKNOWN {
            return None;
        }
    }
    // Each extracted tet by the current vertices of its MT vertices, sorted (UNKNOWN
    // last), and the extracted tets of known vertices listed by their first one.
    let keys: Vec<[u32; 4]> = extracted
        .iter()
        .map(|t| {
            let mut k = t.map(|m| current_of[m.idx()]);
            k.sort_unstable();
            k
        })
        .collect();
    let mut start = vec![0u32; rest.len() + 2];
    for k in keys.iter().filter(|k| k[3] != UNKNOWN) {
        start[k[0] as usize + 2] += 1;
    }
    for i in 2..start.len() {
        start[i] += start[i - 1];
    }
    let mut listed = vec![0u32; start[rest.len() + 1] as usize];
    for (i, k) in keys.iter().enumerate().filter(|(_, k)| k[3] != UNKNOWN) {
        let next = &mut start[k[0] as usize + 1];
        listed[*next as usize] = i as u32;
        *next += 1;
    }
    // Now listed[start[v]..start[v + 1]] are the extracted tets whose first vertex is v.
    let bits = |p: DVec3| p.to_array().map(f64::to_bits);
    let mut ids = vec![VertexId::INVALID; rest.len()];
    let mut used = vec![false; extracted.len()];
    let mut left: Vec<usize> = Vec::new();
    for (k, tet) in tets.iter().enumerate() {
        if tet.iter().any(|v| !mt_vertex[v.idx()].is_valid()) {
            left.push(k);
            continue;
        }
        let mut key = tet.map(|v| v.0);
        key.sort_unstable();
        let first = key[0] as usize;
        let bucket = &listed[start[first] as usize..start[first + 1] as usize];
        let &found = bucket.iter().find(|&&i| keys[i as usize] == key)?;
        if std::mem::replace(&mut used[found as usize], true) {
            return None;
        }
        for &v in tet {
            let m = mt_vertex[v.idx()];
            if bits(at[m.idx()]) != bits(rest[v.idx()]) {
                return None;
            }
            ids[v.idx()] = m;
        }
    }
    if used.iter().filter(|u| !**u).count() != left.len() {
        return None;
    }
    let unused = (0..used.len()).filter(|&i| !used[i]);
    resolve_by_positions(tets, rest, extracted, at, left.into_iter(), unused, ids)
}

/// [`LiveMt::resolve`]'s matching by rest positions, of the `current` tets among the
/// `extracted` ones listed (pool tets, by MT vertex, at positions `at`), `ids` holding the
/// vertices matched so far.
fn resolve_by_positions(
    tets: &[Tet],
    rest: &[DVec3],
    extracted: &[Tet],
    at: &[DVec3],
    current: impl Iterator<Item = usize>,
    listed: impl Iterator<Item = usize>,
    mut ids: Vec<VertexId>,
) -> Option<Vec<VertexId>> {
    let by_key: HashMap<[[u64; 3]; 4], usize, FxBuild> = listed
        .map(|i| (position_key(extracted[i].map(|m| at[m.idx()])), i))
        .collect();
    for k in current {
        let tet = tets[k];
        let &found = by_key.get(&position_key(tet.map(|v| rest[v.idx()])))?;
        let found = extracted[found];
        for &v in &tet {
            let &m = found.iter().find(|m| at[m.idx()] == rest[v.idx()])?;
            let id = &mut ids[v.idx()];
            if id.is_valid() && *id != m {
                return None;
            }
            *id = m;
        }
    }
    ids.iter().all(|v| v.is_valid()).then_some(ids)
}

/// The MT cut at rest by `polygon` that a fold falls back to, given back (as a refused cut)
/// when it leaves the finest, the coarsest or the live `resolution`'s mesh invalid. Such a
/// polygon, mapped from the deformed space, lies close to the plane of the blade's earlier
/// steps without lying in it, where the MT cut's own checks (of the fragments it changed,
/// and of the finest and coarsest meshes' snapped vertices) miss what it can do to a mesh
/// between: measured once, before those vertices were analysed on the coarsest mesh too
/// and polygons that close were cut in the earlier plane (see the module docs). The check
/// extracts those meshes; a fold is rare.
fn cut_checked(
    cutter: &mut MtCutter,
    resolution: &ExtractOptions,
    polygon: &CutPolygon,
) -> Result<MtCutStats, CutError> {
    let before = cutter.mt().clone();
    let stats = cutter.cut(polygon)?;
    let mt = cutter.mt();
    let first = |f: &[crate::mesh::FragmentId]| f.first().map_or(0, |f| f.idx());
    for (name, options, fragment) in [
        ("finest", ExtractOptions::FINEST, first(mt.roots())),
        ("coarsest", ExtractOptions::COARSEST, first(mt.drains())),
        ("current", *resolution, first(mt.roots())),
    ] {
        let problem = match cutter.mt().extract(&options) {
            Ok(e) => {
                let v = e.mesh.validate();
                (!v.is_valid()).then(|| v.to_string())
            }
            Err(e) => Some(e.to_string()),
        };
        if let Some(problem) = problem {
            let options = *cutter.options();
            *cutter = MtCutter::new(before, options)?;
            return Err(CutError::MtInconsistent {
                fragment,
                detail: format!(
                    "the cut at rest a fold fell back to would leave the {name} mesh invalid \
                     ({problem}): refused, the MT as it was"
                ),
            });
        }
    }
    Ok(stats)
}

/// Adds to `glued` the vertices a cut made (`origins`, numbered from `first`) and those it
/// duplicated.
fn glue_made(glued: &mut Vec<VertexId>, first: usize, origins: &[VertexOrigin]) {
    glued.extend((0..origins.len()).map(|i| VertexId::from_usize(first + i)));
    glued.extend(origins.iter().filter_map(|o| match o {
        VertexOrigin::Copy { of } => Some(*of),
        _ => None,
    }));
}

/// The cutter of a current mesh extracted from `mt`'s MT (MT vertices `ids`): with the MT's
/// options and vertex scales, so it decides as the MT cut decides on those tets.
fn current_cutter(mt: &MtCutter, mesh: TetMesh, ids: &[VertexId]) -> Result<Cutter, CutError> {
    let (all_scales, all_crack) = (mt.vertex_scales(), mt.crack_vertices());
    let scales = ids.iter().map(|v| all_scales[v.idx()]).collect();
    let crack = ids.iter().map(|v| all_crack[v.idx()]).collect();
    // Components are the MT's business (`Mt::nb_components`): counting them on every
    // frontier-first cut would cost a pass over the current mesh.
    let options = mt.options().with_count_components(false);
    Cutter::for_mt_frontier(mesh, scales, crack, options)
}

/// The share of its size a current mesh keeps free for the tets and vertices of the next
/// frontier-first cuts (made with the mesh, topped up by [`LiveMt::process_pending`]), so
/// that none of them pays for copying the mesh's arrays to larger ones.
const ROOM: f64 = 0.25;

/// `polygon` (given in `d`'s current space) mapped to rest space by the affine map that
/// best fits (least squares) the current→rest map of the current vertices around it (those
/// in its box grown by a tenth of its size; all of them if fewer than four).
fn rest_polygon(polygon: &CutPolygon, d: &Deformation) -> Result<CutPolygon, LiveError> {
    use glam::{DMat4, DVec4};
    let b = polygon.bbox();
    let grow = DVec3::splat(0.1 * (b.max - b.min).length());
    let near = |p: &DVec3| p.cmpge(b.min - grow).all() && p.cmple(b.max + grow).all();
    let mut pairs: Vec<(DVec3, DVec3)> = d
        .current
        .iter()
        .zip(&d.rest)
        .filter(|(c, _)| near(c))
        .map(|(c, r)| (*c, *r))
        .collect();
    if pairs.len() < 4 {
        pairs = d
            .current
            .iter()
            .copied()
            .zip(d.rest.iter().copied())
            .collect();
    }
    // Normal equations of rest = M [current; 1], centred for conditioning.
    let n = pairs.len().max(1) as f64;
    let (cc, rc) = pairs
        .iter()
        .fold((DVec3::ZERO, DVec3::ZERO), |(a, b), (c, r)| {
            (a + *c, b + *r)
        });
    let (cc, rc) = (cc / n, rc / n);
    let mut xtx = DMat4::ZERO;
    let mut xty = [DVec4::ZERO; 3];
    for (c, r) in &pairs {
        let x = (*c - cc).extend(1.0);
        for i in 0..4 {
            *xtx.col_mut(i) += x * x[i];
        }
        for k in 0..3 {
            xty[k] += x * (r[k] - rc[k]);
        }
    }
    let map: Box<dyn Fn(DVec3) -> DVec3> = if xtx.determinant().abs() > 1e-30 {
        let inv = xtx.inverse();
        let rows = xty.map(|y| inv * y);
        Box::new(move |p: DVec3| {
            let x = (p - cc).extend(1.0);
            rc + DVec3::new(rows[0].dot(x), rows[1].dot(x), rows[2].dot(x))
        })
    } else {
        Box::new(move |p: DVec3| p - cc + rc)
    };
    let mapped: Vec<DVec3> = polygon.points().iter().map(|&p| map(p)).collect();
    Ok(CutPolygon::new(&mapped)?)
}

/// Point location among tets at rest, through a uniform grid: maps a rest point by the
/// displacement of the tet holding it (or, outside every tet, of the nearest by barycentric
/// coordinates among the tets of the nearest non-empty cells).
struct Locator<'a> {
    rest: &'a [DVec3],
    tets: &'a [Tet],
    bounds: Aabb,
    cell: f64,
    dims: [usize; 3],
    /// The tets of cell `c` are `cells[starts[c]..starts[c + 1]]`.
    cells: Vec<u32>,
    starts: Vec<u32>,
    /// Each tet's box at rest.
    boxes: Vec<Aabb>,
    /// Each tet's first vertex at rest, and the rows that give the barycentric coordinates
    /// of its other three from a point's offset to it ([`Locator::barycentric`]).
    frames: Vec<[DVec3; 4]>,
    /// Per tet, the last search that looked at it ([`Locator::map`]).
    seen: Vec<u32>,
    search: u32,
}

/// Barycentric coordinates all above this: the tet holds the point well inside, and
/// [`Locator::map`] takes it without looking further.
const SURELY_INSIDE: f64 = 1e-6;

impl<'a> Locator<'a> {
    fn new(rest: &'a [DVec3], tets: &'a [Tet]) -> Locator<'a> {
        let bounds = Aabb::from_points(tets.iter().flatten().map(|v| &rest[v.idx()]));
        let extent = (bounds.max - bounds.min).max(DVec3::splat(f64::MIN_POSITIVE));
        // About two tets per cell.
        let cell = (extent.x * extent.y * extent.z / (tets.len().max(1) as f64 / 2.0))
            .cbrt()
            .max(extent.max_element() / 256.0);
        let dims = (extent / cell)
            .ceil()
            .as_uvec3()
            .max(glam::UVec3::ONE)
            .to_array();
        let dims = dims.map(|d| d as usize);
        let mut loc = Locator {
            rest,
            tets,
            bounds,
            cell,
            dims,
            cells: Vec::new(),
            starts: vec![0; dims[0] * dims[1] * dims[2] + 2],
            boxes: Vec::with_capacity(tets.len()),
            frames: Vec::with_capacity(tets.len()),
            seen: vec![0; tets.len()],
            search: 0,
        };
        for t in tets {
            let bx = Aabb::from_points(t.iter().map(|v| &rest[v.idx()]));
            loc.boxes.push(bx);
            // The coordinate of vertex k is the volume of the tet with the point in its
            // place over the tet's: for k = 1, 2, 3 the offset dotted with a cross product
            // of two edges from the first vertex, over that volume.
            let [a, b, c, d] = t.map(|v| rest[v.idx()]);
            let (ab, ac, ad) = (b - a, c - a, d - a);
            let total = ab.dot(ac.cross(ad));
            loc.frames.push([
                a,
                ac.cross(ad) / total,
                ad.cross(ab) / total,
                ab.cross(ac) / total,
            ]);
            loc.each_cell(&bx, |loc, c| loc.starts[c + 2] += 1);
        }
        // The cells' tets listed one cell after another (a list per cell, allocated
        // apart, took most of the building): counted above, then placed.
        for c in 2..loc.starts.len() {
            loc.starts[c] += loc.starts[c - 1];
        }
        loc.cells = vec![0; loc.starts[loc.starts.len() - 1] as usize];
        for t in 0..tets.len() {
            let bx = loc.boxes[t];
            loc.each_cell(&bx, |loc, c| {
                let next = &mut loc.starts[c + 1];
                loc.cells[*next as usize] = t as u32;
                *next += 1;
            });
        }
        loc
    }

    /// Calls `f` with each cell (index) that box `b` overlaps.
    fn each_cell(&mut self, b: &Aabb, mut f: impl FnMut(&mut Self, usize)) {
        let (lo, hi) = (self.cell_of(b.min), self.cell_of(b.max));
        for z in lo[2]..=hi[2] {
            for y in lo[1]..=hi[1] {
                for x in lo[0]..=hi[0] {
                    let c = self.index([x, y, z]);
                    f(self, c);
                }
            }
        }
    }

    /// The tets whose boxes overlap cell `c`.
    fn cell(&self, c: usize) -> &[u32] {
        &self.cells[self.starts[c] as usize..self.starts[c + 1] as usize]
    }

    fn cell_of(&self, p: DVec3) -> [usize; 3] {
        let c = (p - self.bounds.min) / self.cell;
        [0, 1, 2].map(|k| (c[k].max(0.0) as usize).min(self.dims[k] - 1))
    }

    fn index(&self, c: [usize; 3]) -> usize {
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }

    /// Barycentric coordinates of `p` in tet `t` at rest.
    fn barycentric(&self, t: usize, p: DVec3) -> [f64; 4] {
        let [a, r1, r2, r3] = self.frames[t];
        let o = p - a;
        let w = [r1.dot(o), r2.dot(o), r3.dot(o)];
        [1.0 - (w[0] + w[1] + w[2]), w[0], w[1], w[2]]
    }

    /// `p` (at rest) mapped to `current` positions.
    fn map(&mut self, p: DVec3, current: &[DVec3]) -> DVec3 {
        let home = self.cell_of(p);
        // Most points lie well inside one tet of their cell: the first such tet, among
        // those whose box holds the point, is taken. The search below (for points near a
        // face, or outside every tet) computes the coordinates of every tet of the cell
        // to take the one holding the point furthest inside, which cost most of placing a
        // deformed body's pool; the two take the same tet but where rounding makes a
        // sliver seem to hold a point another tet holds.
        let inside = self.cell(self.index(home)).iter().find(|&&t| {
            self.boxes[t as usize].contains(p)
                && (self.barycentric(t as usize, p))
                    .iter()
                    .all(|&w| w > SURELY_INSIDE)
        });
        if let Some(&t) = inside {
            return self.shifted(t as usize, p, current);
        }
        let mut best: Option<(f64, usize)> = None;
        let reach = self.dims.iter().copied().max().unwrap_or(1);
        // A tet in several of the cells searched is looked at once (the first time: the
        // best is only replaced by a larger value): two looks in three were repeats around
        // the points outside every tet of a moving fandisk's current mesh.
        self.search = self.search.wrapping_add(1);
        if self.search == 0 {
            self.seen.fill(0);
            self.search = 1;
        }
        for r in 0..=reach {
            let lo = home.map(|c| c.saturating_sub(r));
            let hi = [0, 1, 2].map(|k| (home[k] + r).min(self.dims[k] - 1));
            for z in lo[2]..=hi[2] {
                for y in lo[1]..=hi[1] {
                    for x in lo[0]..=hi[0] {
                        let on_shell = [x, y, z]
                            .iter()
                            .zip(&home)
                            .any(|(&c, &h)| c.abs_diff(h) == r);
                        if !on_shell {
                            continue;
                        }
                        let cell = self.index([x, y, z]);
                        let [from, to] = [cell, cell + 1].map(|c| self.starts[c] as usize);
                        for &t in &self.cells[from..to] {
                            let seen = &mut self.seen[t as usize];
                            if *seen == self.search {
                                continue;
                            }
                            *seen = self.search;
                            let w = self.barycentric(t as usize, p);
                            let m = w.iter().copied().fold(f64::INFINITY, f64::min);
                            if best.is_none_or(|(b, _)| m > b) {
                                best = Some((m, t as usize));
                            }
                        }
                    }
                }
            }
            // Inside a tet, or something found one ring out (nearer cells are done).
            if best.is_some_and(|(m, _)| m >= 0.0) || (best.is_some() && r >= 1) {
                break;
            }
        }
        match best {
            Some((_, t)) => self.shifted(t, p, current),
            None => p,
        }
    }

    /// `p` moved by the displacement of tet `t` there.
    fn shifted(&self, t: usize, p: DVec3, current: &[DVec3]) -> DVec3 {
        // Displacement interpolated at the point of the tet nearest `p` (barycentric
        // coordinates clamped): inside the tet the tet's affine map, outside it a
        // translation continuing the boundary's, which folds far fewer tets reaching out of
        // the current mesh (coarse levels do) than extrapolating the affine map would.
        let tet = self.tets[t];
        let w = self.barycentric(t, p).map(|x| x.max(0.0));
        let sum: f64 = w.iter().sum();
        let shift: DVec3 = (0..4)
            .map(|k| (current[tet[k].idx()] - self.rest[tet[k].idx()]) * (w[k] / sum))
            .sum();
        p + shift
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mt::BuildOptions;

    /// A point inside the mesh is moved by the tet holding it furthest inside, found
    /// among all tets; one outside every tet by some tet near it; each tet's coordinates
    /// as the volumes they are ratios of give them.
    #[test]
    fn the_locator_moves_a_point_by_the_tet_holding_it() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/pinion-coarse.node");
        let (mesh, _) = crate::io::read_mesh(path).expect("pinion-coarse");
        let (rest, tets) = (mesh.positions(), mesh.tets());
        let b = mesh.bbox();
        let (c, d) = (b.center(), b.max - b.min);
        // An affine motion and a bend: the shift differs from tet to tet.
        let current: Vec<DVec3> = rest
            .iter()
            .map(|&p| {
                let q = p - c;
                p + DVec3::new(0.01 * q.y, -0.02 * q.x, 0.03 * q.z) + 0.01 * d * (q.x / d.x).sin()
            })
            .collect();
        let vol = |a: DVec3, b: DVec3, c: DVec3, d: DVec3| (b - a).dot((c - a).cross(d - a));
        let mut locator = Locator::new(rest, tets);
        let mut rng = crate::rng::Rng(17);
        let (mut inside, mut outside) = (0, 0);
        for _ in 0..4000 {
            let p = b.min + (b.max - b.min) * DVec3::new(rng.unit(), rng.unit(), rng.unit());
            let least = |t: &Tet| {
                let [a, b, c, d] = t.map(|v| rest[v.idx()]);
                let total = vol(a, b, c, d);
                let w = [
                    vol(p, b, c, d),
                    vol(a, p, c, d),
                    vol(a, b, p, d),
                    vol(a, b, c, p),
                ];
                w.map(|x| x / total)
                    .into_iter()
                    .fold(f64::INFINITY, f64::min)
            };
            let (k, m) = (0..tets.len())
                .map(|k| (k, least(&tets[k])))
                .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
            let moved = locator.map(p, &current);
            if m > 1e-3 {
                inside += 1;
                let w = locator.barycentric(k, p);
                let shift: DVec3 = (0..4)
                    .map(|j| (current[tets[k][j].idx()] - rest[tets[k][j].idx()]) * w[j])
                    .sum();
                assert!((moved - (p + shift)).length() <= 1e-12 * d.length(), "{p}");
            } else if m < -1e-3 {
                outside += 1;
                // Clamped coordinates of a tet near it: a shift within the bodies' shifts.
                let largest = (0..rest.len())
                    .map(|v| (current[v] - rest[v]).length())
                    .fold(0.0, f64::max);
                assert!((moved - p).length() <= largest * (1.0 + 1e-12), "{p}");
            }
        }
        assert!(
            inside > 500 && outside > 500,
            "{inside} inside, {outside} outside"
        );
    }

    /// Matching by MT vertices gives what matching by positions gives, and leaves to it a
    /// current mesh whose known vertices do not name the MT vertices of its tets.
    #[test]
    fn matching_by_ids_agrees_with_matching_by_positions() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/pinion-coarse.node");
        let (mesh, _) = crate::io::read_mesh(path).expect("pinion-coarse");
        let (mt, _) = Mt::build(&mesh, &BuildOptions::DEFAULT).expect("MT");
        let mut live = LiveMt::new(mt, &ExtractOptions::FINEST, MtCutter::DEFAULT_OPTIONS)
            .expect("live model");
        let b = live.mesh().bbox();
        let (c, d) = (b.center(), b.max - b.min);
        let p = |x: f64, y: f64| DVec3::new(c.x + x * d.x, c.y + y * d.y, c.z + 0.013 * d.z);
        let square = [p(-0.3, -0.3), p(0.3, -0.3), p(0.3, 0.3), p(-0.3, 0.3)];
        let cut = live
            .cut(&CutPolygon::new(&square).expect("square"))
            .expect("cut");
        assert!(
            cut.stats.vertex_copies + cut.stats.vertices_added > 0,
            "nothing cut"
        );
        let new = live.mt_vertex.iter().filter(|v| !v.is_valid()).count();
        assert!(new > 0, "the cut made no current vertex");
        live.process_pending(PendingBudget::All).expect("pending");
        let matched = live.mt_vertex.clone();
        assert!(matched.iter().all(|v| v.is_valid()));

        let e = live
            .mt()
            .extract_tets(&ExtractOptions::FINEST)
            .expect("extract");
        let at = &live.mt().positions().to_vec()[..];
        let tets = &live.mesh().tets().to_vec()[..];
        let all = || vec![VertexId::INVALID; live.rest.len()];
        let n = tets.len();
        let by_positions = resolve_by_positions(tets, &live.rest, &e, at, 0..n, 0..n, all());
        assert_eq!(by_positions.as_ref(), Some(&matched));
        // The cut's vertices forgotten: matched again, by ids and positions together.
        let mut known = matched.clone();
        for v in known.iter_mut().skip(live.rest.len() - new) {
            *v = VertexId::INVALID;
        }
        assert_eq!(
            resolve_by_ids(tets, &live.rest, &known, &e, at).as_ref(),
            Some(&matched)
        );
        // Two vertices the cut did not make swapped, of one tet (its key unchanged, its
        // positions not), or of two tets apart (keys the extraction does not have): not
        // matched by ids; matched by positions again.
        let old = live.rest.len() - new;
        let t = *tets
            .iter()
            .find(|t| t.iter().all(|v| v.idx() < old))
            .expect("uncut");
        let apart = tets
            .iter()
            .find(|u| u.iter().all(|v| v.idx() < old && !t.contains(v)))
            .expect("an uncut tet apart");
        for (i, j) in [(t[0], t[1]), (t[0], apart[0])] {
            let mut swapped = matched.clone();
            swapped.swap(i.idx(), j.idx());
            assert_eq!(resolve_by_ids(tets, &live.rest, &swapped, &e, at), None);
            live.mt_vertex = swapped;
            assert!(live.resolve().expect("resolve"));
            assert_eq!(live.mt_vertex, matched);
        }
    }
}
