//! The cut of a plain [`TetMesh`]: the paper's steps 1 and 2 (§3) on one mesh, with the
//! acceleration structure kept between cuts.

use super::bielser::Bielser17Nodes;
use super::bvh::{Candidates, QueryBuffers, QueryOptions, TetBvh};
use super::classify::{
    CrackTips, CutScratch, CutSession, NONE, OriginPositions, StateCache, TetClass, VertexOrigin,
    extend_twinned, mark_glued,
};
use super::components::Components;
use super::options::{CutError, CutOptions, Scheme};
use super::pockets;
use super::report::{CutResult, CutStats, CutTimes, SplitRecord};
use super::split::{Children, extend_twin_roots, split_tet, twin_roots};
use super::tables::{NEG, ON, POS, Side};
use super::unglue::{
    Copies, LinkSlots, ParentAt, ParentPlan, PlanScratch, StarEntry, entry_at_vertex,
    plan_by_parents, plan_vertex,
};
use crate::geom::{CutPolygon, DVec3, Sign};
use crate::mesh::fxhash::FxBuild;
use crate::mesh::tables::TET_EDGES;
use crate::mesh::{Attribute, Attributes, Tet, TetId, TetMesh, VertexId, corners};
use std::collections::{HashMap, HashSet};
use std::time::{Duration, Instant};

/// The per-tet column marking tets created by cuts: the 1-based number of the cut that
/// created the tet (within the meshes this library cut), 0 for tets not created by a cut.
pub const CUT_COLUMN: &str = "mtcut:cut";

/// The largest snapping tolerance a cut is planned again with when its plan would make a
/// flat tet (see [`Cutter::cut`]): the engine's default, which the quality measures of the
/// random cuts were made with.
pub const RETRY_SNAP: f64 = 0.2;

/// The largest number of vertices or tets a mesh may reach while it is cut: ids are `u32`,
/// and a cut in progress uses the ids from 2³¹ on as provisional ids for its new points.
const MAX_ELEMENTS: usize = (1 << 31) - 1;

/// The scale of each vertex: the length of its longest incident edge (0 for an unused
/// vertex). Snapping distances are relative to it.
pub fn vertex_scales(mesh: &TetMesh) -> Vec<f64> {
    let pos = mesh.positions();
    let mut s = vec![0.0f64; pos.len()];
    for t in mesh.tets() {
        for [a, b] in TET_EDGES {
            let (u, v) = (t[a].idx(), t[b].idx());
            let l = pos[u].distance(pos[v]);
            s[u] = s[u].max(l);
            s[v] = s[v].max(l);
        }
    }
    s
}

/// A mesh ready to be cut many times: the mesh, its vertex scales and its tet hierarchy,
/// all kept up to date by each cut, so a cut costs time in proportion to the tets it
/// touches, not to the mesh.
#[derive(Clone)]
pub struct Cutter {
    mesh: TetMesh,
    scales: Vec<f64>,
    /// The twin root of each vertex, which orders the vertices of split tets
    /// ([`canonical_order_at`](super::split::canonical_order_at)): the lowest id at its
    /// position when the cutter was made, kept up to date by each cut. `None` for an MT
    /// frontier, ordered by id as the MT cut orders it.
    roots: Option<Vec<u32>>,
    /// Per vertex, whether another vertex may lie at its position (bit for bit), for
    /// placing new vertices ([`OriginPositions::compute`]): known for a plain mesh from
    /// its twin roots, kept up to date by each cut; `None` (not known: every new vertex is
    /// placed through the table) for an MT frontier, and once positions are set.
    twinned: Option<Vec<bool>>,
    bvh: TetBvh,
    scratch: CutScratch,
    state_cache: StateCache,
    /// While a cut indexes its snapped vertices ([`StarIndex`]), the index of each; `NONE`
    /// for every other vertex (and for all once the index is built).
    snapped_slot: Vec<u32>,
    /// Per vertex, the number of tets holding it, kept up to date by every cut, and the
    /// scratch of [`pockets::enclosing_snapped`] ([`pockets::valences`]); empty while the
    /// options continue cracks (an MT frontier, a scalpel: the rule is not applied, and a
    /// scalpel step does not pay for the upkeep).
    valence: Vec<[u32; 2]>,
    /// Scratch of the copy planning ([`plan_by_parents`]).
    links: LinkSlots,
    buffers: CutBuffers,
    options: CutOptions,
    cuts_applied: u32,
    build_time: Duration,
    /// The face points this cutter's cuts made, kept when cracks are continued
    /// ([`CutOptions::continue_cracks`]); `None` for an MT frontier, which decides as the
    /// MT cut does, and that does not take crack tips (see [`super::mt_cut`]'s limits).
    tips: Option<CrackTips>,
    /// For an MT frontier: per vertex, whether it lies on an earlier crack, as the MT cut
    /// takes them (`StateClassifier::with_crack_vertices`), kept up to date with the
    /// vertices this cutter's cuts add. `None` for a plain mesh.
    crack: Option<Vec<bool>>,
    /// Whether the next cut takes the `crack` vertices on its plane outside it as `OUT`
    /// (false only during a [`cut_glued`](Self::cut_glued) that does not: see
    /// [`super::mt_cut::continues_a_crack_plane`]).
    crack_out: bool,
    /// During [`cut_glued`](Self::cut_glued): per vertex, whether it counts as lying in the
    /// polygon's plane, and the farthest of those from it.
    glued: Vec<bool>,
    glue_reach: Option<f64>,
}

/// The lists a cut fills, kept from one cut to the next (cleared, their room kept): a cold
/// scalpel step allocating them anew paid the allocator (malloc, vectors growing, first
/// touches of fresh pages); kept, the step is 3-8% faster (measured on the scalpel bench;
/// the rest of a cold step is cache misses). A new cutter gives them room for a cut
/// through its mesh ([`CutBuffers::reserve`]); a clone gets that room, not their contents
/// (each cut fills them anew).
#[derive(Default)]
struct CutBuffers {
    /// The (splits, candidates) [`CutBuffers::reserve`] made room for.
    room: (usize, usize),
    query: QueryBuffers,
    found: Candidates,
    /// The candidates' vertices and classes.
    tets: Vec<Tet>,
    classes: Vec<TetClass>,
    /// The candidates split, their children, and each candidate's children (`NONE`: none).
    split_at: Vec<usize>,
    children: Vec<Children>,
    child_of: Vec<u32>,
    star: StarIndex,
    plan: PlanBuffers,
    /// The snapped vertices, and those a plan pass examines.
    snapped: Vec<VertexId>,
    examine: Vec<VertexId>,
    /// Per candidate, the slot of its second child; per appended tet, its parent.
    first_appended: Vec<u32>,
    appended_parents: Vec<u32>,
    new_positions: OriginPositions,
}

impl CutBuffers {
    /// Room, its memory mapped, for a cut splitting about `splits` tets among
    /// `candidates`, so that such a cut neither grows these lists nor faults their pages
    /// in (a fresh fandisk-1m cutter's cut through the middle met about 2,000 page faults,
    /// 200 with this room).
    fn reserve(&mut self, splits: usize, candidates: usize) {
        use crate::mesh::reserve_mapped;
        self.room = (self.room.0.max(splits), self.room.1.max(candidates));
        self.query.reserve(2 * candidates);
        reserve_mapped(&mut self.found.tets, candidates);
        reserve_mapped(&mut self.found.states, candidates);
        reserve_mapped(&mut self.tets, candidates);
        reserve_mapped(&mut self.classes, candidates);
        reserve_mapped(&mut self.child_of, candidates);
        reserve_mapped(&mut self.first_appended, candidates);
        reserve_mapped(&mut self.split_at, splits);
        reserve_mapped(&mut self.children, splits + splits / 2);
        reserve_mapped(&mut self.appended_parents, 4 * splits);
        // Cuts through the shared meshes put each candidate in the stars of 1.5 snapped
        // vertices, one snapped vertex per 13–16 candidates, and 1.03 new points per split
        // tet: room for a little more.
        self.star.reserve(candidates);
        reserve_mapped(&mut self.snapped, candidates / 8);
        reserve_mapped(&mut self.examine, candidates / 8);
        self.new_positions.reserve(splits + splits / 2);
    }

    /// A cut through a mesh of `n` tets meets about `n^(2/3)` of them (a plane section of
    /// a body of `n` cells of about equal size): a square through the middle of fandisk
    /// splits 0.75 times that many, among 3.5 times that many candidates (the snapped
    /// vertices' stars with them), and of fandisk-1m 0.9 times that many. Room for
    /// `n^(2/3)` split tets among four times as many candidates.
    fn reserve_for_mesh(&mut self, n: usize) {
        let section = (n as f64).powf(2.0 / 3.0).ceil() as usize;
        self.reserve(section, 4 * section);
    }
}

impl Clone for CutBuffers {
    fn clone(&self) -> CutBuffers {
        let mut b = CutBuffers::default();
        b.reserve(self.room.0, self.room.1);
        b
    }
}

/// A snapped vertex's plan counted as this many candidates' classification against
/// [`CutOptions::parallel_threshold`]: with the default threshold, fandisk's 290 snapped
/// vertices (of a cut through it) took longer on two cores than on one, fandisk-1m's 2360
/// a fifth less (measured, alternated runs).
const PLAN_WEIGHT: usize = 4;
/// Chunks a plan pass on both cores is split into (a few per core, for balance).
const PLAN_CHUNKS: usize = 8;

/// The lists of a plan pass ([`Cutter::plan_pass`]), kept as [`CutBuffers`] are.
#[derive(Clone, Default)]
struct PlanBuffers {
    /// The tets around a vertex, whole ([`plan_by_parents`]) or their children
    /// ([`plan_vertex`]).
    around: Vec<ParentAt>,
    /// Per tet of `around`, its tets around the vertex on the negative side: bit `c` for
    /// its child `c` when split, bit 0 for itself when whole.
    negative: Vec<u16>,
    entries: Vec<StarEntry>,
    scratch: PlanScratch,
    /// Lists of copies' tets given back once a cut has made its copies, taken again by
    /// the next plans: a list per copied vertex was most of a scalpel step's allocations.
    spare: Vec<Vec<TetId>>,
}

/// Lists [`PlanBuffers::spare`] keeps at most.
const SPARE_LISTS: usize = 1 << 12;

/// The snapped vertices of a cut (sorted) and where each lies in the candidates: the
/// (candidate, local index) pairs of vertex `vertices[i]` are `at[start[i]..start[i + 1]]`,
/// in candidate order. Built once per cut: unsnapping a vertex changes the classes of the
/// tets around it but not which candidates hold the vertices still snapped, so every plan
/// pass reads its vertices' runs here instead of scanning the candidates again.
#[derive(Clone, Default)]
struct StarIndex {
    vertices: Vec<VertexId>,
    start: Vec<u32>,
    at: Vec<(u32, u8)>,
    /// Every (vertex, candidate, local index) on the cut, in candidate order: the
    /// candidates are read once, the index made from these.
    found: Vec<(VertexId, u32, u8)>,
}

impl StarIndex {
    /// Indexes the snapped vertices of `tets` (whose classes are `classes`), reusing this
    /// index's room. `mark` is a per-vertex scratch array holding `NONE` everywhere, as it
    /// is left.
    fn build(&mut self, tets: &[Tet], classes: &[TetClass], mark: &mut [u32]) {
        let StarIndex {
            vertices,
            start,
            at,
            found,
        } = self;
        vertices.clear();
        found.clear();
        // (A vertex on the cut makes its tet touch the cut.)
        for (k, (tet, c)) in tets.iter().zip(classes).enumerate() {
            for (j, &s) in c.states.iter().enumerate() {
                if s == ON {
                    let v = tet[j];
                    if mark[v.idx()] == NONE {
                        mark[v.idx()] = 0;
                        vertices.push(v);
                    }
                    found.push((v, k as u32, j as u8));
                }
            }
        }
        vertices.sort_unstable();
        for (i, v) in vertices.iter().enumerate() {
            mark[v.idx()] = i as u32;
        }
        // A counting sort: candidates stay in order within each run. `start[i + 1]` counts
        // run i, then (summed) is where run i + 1 begins; `start[i]` is run i's cursor
        // while filling, which leaves it where run i ends: shifted back after.
        start.clear();
        start.resize(vertices.len() + 1, 0);
        for &(v, _, _) in found.iter() {
            start[mark[v.idx()] as usize + 1] += 1;
        }
        for i in 0..vertices.len() {
            start[i + 1] += start[i];
        }
        at.clear();
        at.resize(found.len(), (0, 0));
        for &(v, k, j) in found.iter() {
            let cursor = &mut start[mark[v.idx()] as usize];
            at[*cursor as usize] = (k, j);
            *cursor += 1;
        }
        start.rotate_right(1);
        start[0] = 0;
        for v in vertices.iter() {
            mark[v.idx()] = NONE;
        }
    }

    /// Room, its memory mapped, for the stars of about `candidates` candidates.
    fn reserve(&mut self, candidates: usize) {
        use crate::mesh::reserve_mapped;
        reserve_mapped(&mut self.found, 2 * candidates);
        reserve_mapped(&mut self.at, 2 * candidates);
        reserve_mapped(&mut self.vertices, candidates / 8);
        reserve_mapped(&mut self.start, candidates / 8 + 1);
    }

    /// The (candidate, local index) pairs of snapped vertex `v`.
    fn run(&self, v: VertexId) -> &[(u32, u8)] {
        match self.vertices.binary_search(&v) {
            Ok(i) => &self.at[self.start[i] as usize..self.start[i + 1] as usize],
            Err(_) => &[],
        }
    }
}

impl Cutter {
    /// Prepares `mesh` (which should be valid: see [`TetMesh::validate`]) for cutting with
    /// `options`. Adds the [`CUT_COLUMN`] cell column if missing.
    pub fn new(mesh: TetMesh, options: CutOptions) -> Result<Cutter, CutError> {
        options.check()?;
        Ok(Cutter::prepare(mesh, options))
    }

    /// A cutter for a mesh extracted from an MT (a frontier), deciding as
    /// [`MtCutter`](super::MtCutter) decides on the same tets: with the MT's vertex `scales`
    /// (one per vertex, [`MtCutter::vertex_scales`](super::MtCutter::vertex_scales) of
    /// each vertex's MT vertex: they place face points), which vertices lie on earlier
    /// cracks (`crack`, one flag per vertex,
    /// [`MtCutter::crack_vertices`](super::MtCutter::crack_vertices) of each vertex's MT
    /// vertex) and the MT cut's rules for continuing cracks
    /// ([`CutOptions::continue_cracks`], set whatever `options` say, but without taking
    /// crack tips, as the MT cut), so a blade swept in steps continues its crack. Options
    /// as the MT cut takes them.
    pub fn for_mt_frontier(
        mesh: TetMesh,
        scales: Vec<f64>,
        crack: Vec<bool>,
        options: CutOptions,
    ) -> Result<Cutter, CutError> {
        options.check()?;
        if scales.len() != mesh.nb_vertices() {
            return Err(CutError::InvalidOption {
                option: "scales",
                value: scales.len() as f64,
                expected: "one scale per vertex",
            });
        }
        if let Some(&bad) = scales.iter().find(|s| !(s.is_finite() && **s >= 0.0)) {
            return Err(CutError::InvalidOption {
                option: "scales",
                value: bad,
                expected: "finite and non-negative",
            });
        }
        if crack.len() != mesh.nb_vertices() {
            return Err(CutError::InvalidOption {
                option: "crack",
                value: crack.len() as f64,
                expected: "one flag per vertex",
            });
        }
        let options = options.with_continue_cracks(true);
        let mut cutter = Cutter::prepare_with(mesh, scales, options, false);
        cutter.tips = None;
        cutter.crack = Some(crack);
        Ok(cutter)
    }

    /// [`new`](Self::new) with options already checked.
    fn prepare(mesh: TetMesh, options: CutOptions) -> Cutter {
        let scales = vertex_scales(&mesh);
        Cutter::prepare_with(mesh, scales, options, true)
    }

    /// Prepares the cutter; `twin_order`: split tets ordered by twin root (else by id).
    fn prepare_with(
        mut mesh: TetMesh,
        scales: Vec<f64>,
        options: CutOptions,
        twin_order: bool,
    ) -> Cutter {
        super::classify::build_tables();
        let start = Instant::now();
        let bvh = TetBvh::build(mesh.positions(), &scales, mesh.tets());
        let roots = twin_order.then(|| twin_roots(mesh.positions()));
        let twinned = roots.as_deref().map(|roots| {
            let mut twinned = vec![false; roots.len()];
            for (v, &r) in roots.iter().enumerate() {
                if r as usize != v {
                    twinned[v] = true;
                    twinned[r as usize] = true;
                }
            }
            twinned
        });
        let valence = if options.continue_cracks {
            Vec::new()
        } else {
            pockets::valences(mesh.nb_vertices(), mesh.tets())
        };
        let build_time = start.elapsed();
        let n = mesh.nb_tets();
        let cuts_applied = match mesh.cell_data.get(CUT_COLUMN) {
            Some(c) if c.components == 1 && c.len() == n => {
                c.values.iter().fold(0.0f64, |m, &x| m.max(x)) as u32
            }
            _ => {
                mesh.cell_data.insert(Attribute {
                    name: CUT_COLUMN.to_string(),
                    components: 1,
                    values: vec![0.0; n],
                });
                0
            }
        };
        let mut cutter = Cutter {
            mesh,
            scales,
            roots,
            twinned,
            bvh,
            scratch: CutScratch::new(),
            state_cache: StateCache::default(),
            snapped_slot: Vec::new(),
            valence,
            links: LinkSlots::default(),
            buffers: CutBuffers::default(),
            options,
            cuts_applied,
            build_time,
            tips: Some(CrackTips::default()),
            crack: None,
            crack_out: true,
            glued: Vec::new(),
            glue_reach: None,
        };
        cutter.reserve_scratch(cutter.mesh.nb_vertices());
        cutter.buffers.reserve_for_mesh(n);
        cutter
    }

    pub fn mesh(&self) -> &TetMesh {
        &self.mesh
    }

    pub fn into_mesh(self) -> TetMesh {
        self.mesh
    }

    /// The mesh, for the C ABI's attribute edits only: its attribute columns may change
    /// (the cutter keeps them as long as the mesh's elements, as every cut does), never
    /// its positions or tets, which the hierarchy and scales describe.
    pub(crate) fn mesh_for_attributes(&mut self) -> &mut TetMesh {
        &mut self.mesh
    }

    pub fn options(&self) -> &CutOptions {
        &self.options
    }

    /// Changes the options of the next cuts.
    pub fn set_options(&mut self, options: CutOptions) -> Result<(), CutError> {
        options.check()?;
        self.options = options;
        if options.continue_cracks {
            self.valence = Vec::new();
        } else if self.valence.is_empty() {
            self.valence = pockets::valences(self.mesh.nb_vertices(), self.mesh.tets());
        }
        Ok(())
    }

    /// Moves the vertices to `positions` (one per vertex: a deformed body), keeping the
    /// mesh's topology, its vertex scales (so snapping distances stay those of the rest
    /// shape) and its hierarchy (refitted). Refused, with the mesh unchanged, when the count
    /// is wrong, a coordinate is not finite, or a tet would be inverted or flat (exact
    /// orientation): cut tables need positively oriented tets.
    pub fn set_positions(&mut self, positions: &[DVec3]) -> Result<(), CutError> {
        use rayon::prelude::*;
        check_positions(positions, self.mesh.nb_vertices())?;
        let inverted_tet = |t: &Tet| {
            let [a, b, c, d] = corners(t, |v| positions[v.idx()]);
            crate::geom::orient3d(a, b, c, d) != Sign::Positive
        };
        // On one core below `PARALLEL_ORIENT` tets: a moving fandisk's current mesh
        // (22,690 tets) was checked in 0.38 ms so, in 0.60–0.66 on both.
        let tets = self.mesh.tets();
        let inverted = if tets.len() < PARALLEL_ORIENT {
            tets.iter().position(inverted_tet)
        } else {
            tets.par_iter().position_first(inverted_tet)
        };
        if let Some(tet) = inverted {
            return Err(CutError::InvertedTet { tet });
        }
        self.mesh.positions_mut().copy_from_slice(positions);
        self.bvh.refit(self.mesh.positions(), self.mesh.tets());
        // Any two vertices may have been moved onto one another.
        self.twinned = None;
        Ok(())
    }

    /// Makes room for `tets` more tets and `vertices` more vertices, so that the next cuts
    /// adding up to that many do not reallocate the mesh's arrays (a simulation calls it
    /// once, sized for the cuts it expects; without it arrays grow by doubling). The room's
    /// memory is mapped here too (each page written once), so those cuts do not pay for
    /// page faults either: memory for the room is taken now, not as cuts fill it.
    pub fn reserve(&mut self, tets: usize, vertices: usize) {
        use crate::mesh::touch_spare;
        self.mesh.reserve_mapped(tets, vertices);
        self.scales.reserve(vertices);
        touch_spare(&mut self.scales);
        if let Some(roots) = self.roots.as_mut() {
            roots.reserve(vertices);
            touch_spare(roots);
        }
        if let Some(twinned) = self.twinned.as_mut() {
            twinned.reserve(vertices);
            touch_spare(twinned);
        }
        if !self.valence.is_empty() {
            self.valence.reserve(vertices);
            touch_spare(&mut self.valence);
        }
        self.bvh.reserve_tets(self.mesh.nb_tets() + tets);
        self.reserve_scratch(self.mesh.nb_vertices() + vertices);
    }

    /// Makes sure at least `fraction` of the current tets and vertices can be appended
    /// without reallocating ([`reserve`](Self::reserve) when fewer can): a caller with
    /// spare time between cuts keeps reallocation (a copy of every array) out of them.
    pub fn keep_room(&mut self, fraction: f64) {
        let (tets, vertices) = self.mesh.spare();
        let mut vertices = vertices
            .min(self.scales.capacity() - self.scales.len())
            .min(
                self.roots
                    .as_ref()
                    .map_or(usize::MAX, |r| r.capacity() - r.len()),
            )
            .min(
                self.twinned
                    .as_ref()
                    .map_or(usize::MAX, |t| t.capacity() - t.len()),
            );
        if !self.valence.is_empty() {
            vertices = vertices.min(self.valence.capacity() - self.valence.len());
        }
        let want_tets = (self.mesh.nb_tets() as f64 * fraction).ceil() as usize;
        let want_vertices = (self.mesh.nb_vertices() as f64 * fraction).ceil() as usize;
        if tets < want_tets || vertices < want_vertices {
            self.reserve(want_tets, want_vertices);
        }
    }

    /// Sizes the per-vertex scratch arrays of the cut for `n_vertices`.
    fn reserve_scratch(&mut self, n_vertices: usize) {
        self.scratch.reserve(n_vertices);
        self.state_cache.reserve(n_vertices);
        if self.snapped_slot.len() < n_vertices {
            self.snapped_slot.resize(n_vertices, NONE);
        }
    }

    /// Time spent building the vertex scales and the hierarchy.
    pub fn build_time(&self) -> Duration {
        self.build_time
    }

    /// The scale of each vertex (see [`vertex_scales`]); vertices added by cuts take the
    /// largest scale of the vertices they are made from.
    pub fn vertex_scales(&self) -> &[f64] {
        &self.scales
    }

    /// The crack tips this cutter's cuts made (face points), which its later cuts take as on
    /// the cut near their polygon when they continue cracks
    /// ([`CutOptions::continue_cracks`]); `None` for an MT frontier
    /// ([`Cutter::for_mt_frontier`]), which does not take them.
    pub fn crack_tips(&self) -> Option<&CrackTips> {
        self.tips.as_ref()
    }

    /// Replaces the crack tips (a mesh cut earlier by another cutter whose tips were kept:
    /// [`crack_tips`](Self::crack_tips)), so that this cutter's cuts continue those cracks.
    /// Ignored by an MT frontier.
    pub fn set_crack_tips(&mut self, tips: CrackTips) {
        if self.tips.is_some() {
            self.tips = Some(tips);
        }
    }

    /// Number of cuts applied so far (the value [`CUT_COLUMN`] gives the tets of the next
    /// cut, minus one).
    pub fn cuts_applied(&self) -> u32 {
        self.cuts_applied
    }

    /// Cuts the mesh with `polygon`: every tet C crosses is replaced by tets C does not
    /// cross (paper §3 steps 1–2), the cut points are duplicated for the two sides, and the
    /// vertices the cut passes through are duplicated where the sides separate.
    ///
    /// The cut is planned in full before the mesh changes. A snapped vertex that copies
    /// cannot separate (a "pinched" one, see [`super::unglue`]) is left unsnapped: only the
    /// tets around it are classified and split again, and the plan checked again. This
    /// keeps the result a manifold mesh. So are, on a plain mesh, the snapped vertices that
    /// would enclose vertices just off the cut with their stars (a part the exact plane
    /// does not make). Every new tet's orientation is then checked exactly at its vertices'
    /// rounded positions (with the look-up tables; the 1:17 scheme's output is not
    /// checked): a plane passing a vertex closer than the snapping distance allows yet too
    /// close for floating point (a small `snap`, as a scalpel's) can make a child flat
    /// once its points are rounded. Such a cut is planned again with
    /// `snap` a hundred times larger, up to [`RETRY_SNAP`] (the vertex is then snapped
    /// onto the cut: no child near it; `stats.snap` says which was used), and refused
    /// ([`CutError::FlatChild`]) only when that still fails; the mesh is left unchanged
    /// until a plan passes. Measured with [`CutOptions::SCALPEL`] on 100 random scalpel
    /// paths per shared mesh (tests/cut_scalpel.rs): without the retries 5, 1 and 11 paths
    /// (fandisk, pinion, liver) met a cut that would have made a flat tet; with them, no
    /// cut was refused and every step left a valid mesh.
    pub fn cut(&mut self, polygon: &CutPolygon) -> Result<CutResult, CutError> {
        let mut opts = self.options;
        loop {
            match self.cut_with(polygon, opts) {
                Err(CutError::FlatChild { .. } | CutError::HangingVertex { .. })
                    if opts.snap.relative < RETRY_SNAP =>
                {
                    opts.snap.relative = (opts.snap.relative * 100.0).min(RETRY_SNAP);
                }
                r => return r,
            }
        }
    }

    /// [`cut`](Self::cut), the vertices `glued` counting as lying in the polygon's plane
    /// wherever they are ([`StateClassifier::with_glued`](super::classify::StateClassifier::with_glued)): the
    /// frontier-first step of a blade continuing, in its plane, a crack that the body's
    /// motion has moved off it ([`super::live`]), decided as the MT cut decides it
    /// ([`MtCutter::cut_deformed`](super::MtCutter::cut_deformed)); earlier cracks'
    /// vertices on the plane outside the polygon taken as `OUT` only when `crack_out`
    /// (as the MT cut takes them: [`super::mt_cut::continues_a_crack_plane`]).
    pub(crate) fn cut_glued(
        &mut self,
        polygon: &CutPolygon,
        glued: &[VertexId],
        crack_out: bool,
    ) -> Result<CutResult, CutError> {
        self.crack_out = crack_out;
        let result = self.cut_glued_as_set(polygon, glued);
        self.crack_out = true;
        result
    }

    /// [`cut_glued`](Self::cut_glued) with `crack_out` set.
    fn cut_glued_as_set(
        &mut self,
        polygon: &CutPolygon,
        glued: &[VertexId],
    ) -> Result<CutResult, CutError> {
        if glued.is_empty() {
            return self.cut(polygon);
        }
        let mut flags = std::mem::take(&mut self.glued);
        let mesh = &self.mesh;
        let reach = mark_glued(&mut flags, mesh.nb_vertices(), glued, polygon, |v| {
            mesh.position(v)
        });
        self.glued = flags;
        self.glue_reach = Some(reach);
        let result = self.cut(polygon);
        self.glue_reach = None;
        result
    }

    /// [`cut`](Self::cut) with these options.
    fn cut_with(&mut self, polygon: &CutPolygon, opts: CutOptions) -> Result<CutResult, CutError> {
        let mut buffers = std::mem::take(&mut self.buffers);
        let result = self.cut_with_buffers(polygon, opts, &mut buffers);
        self.buffers = buffers;
        result
    }

    /// [`cut_with`](Self::cut_with) filling `buffers`.
    fn cut_with_buffers(
        &mut self,
        polygon: &CutPolygon,
        opts: CutOptions,
        buffers: &mut CutBuffers,
    ) -> Result<CutResult, CutError> {
        let CutBuffers {
            room: _,
            query,
            found,
            tets,
            classes,
            split_at,
            children,
            child_of,
            star,
            plan,
            snapped,
            examine,
            first_appended,
            appended_parents,
            new_positions,
        } = buffers;
        let start = Instant::now();
        let mut times = CutTimes::default();
        let n_vertices = self.mesh.nb_vertices();
        let n_tets = self.mesh.nb_tets();
        let par = |n: usize| n >= opts.parallel_threshold;

        // Step 1: candidates, in the hierarchy's depth-first order (deterministic: the
        // hierarchy only depends on the mesh and the cuts applied to it).
        self.bvh.candidates(
            self.mesh.positions(),
            &self.scales,
            self.mesh.tets(),
            polygon,
            opts.snap,
            QueryOptions {
                parallel: n_tets / 32 >= opts.parallel_threshold,
                cache: &mut self.state_cache,
                buffers: query,
                contour_band: if opts.continue_cracks {
                    super::mt_cut::contour_band(&opts)
                } else {
                    0.0
                },
                tips: self
                    .tips
                    .as_ref()
                    .filter(|_| opts.continue_cracks)
                    .map(|t| (t, super::mt_cut::tip_reach(&opts))),
                crack: self.crack.as_deref().filter(|_| self.crack_out),
                glued: self.glue_reach.map(|r| (&self.glued[..], r)),
            },
            found,
        );
        let Candidates {
            tets: cand,
            states,
            tested,
        } = found;
        if opts.continue_cracks {
            let mesh = &self.mesh;
            super::mt_cut::settle_plane_vertices(
                polygon,
                opts,
                mesh.positions(),
                &self.scales,
                cand,
                states,
                // Lips decided alike on a plain mesh only: an MT's frontier (the cutter
                // without crack tips) decides as the MT does.
                self.tips.is_some(),
                |t| mesh.tet(t),
            );
        }
        let cand = &*cand;
        tets.clear();
        tets.extend(cand.iter().map(|t| self.mesh.tet(*t)));
        let tets = &*tets;
        times.query = start.elapsed().as_secs_f64();

        // Step 2a: classify every edge and face once.
        let t = Instant::now();
        let positions = self.mesh.positions();
        let roots = self.roots.as_deref();
        let mut session = CutSession::new(
            polygon,
            opts.snap,
            opts.face_point_margin,
            &mut self.scratch,
            n_vertices,
        );
        let parallel = par(tets.len());
        session.classify_into(positions, &self.scales, tets, states, parallel, classes);
        times.classify += t.elapsed().as_secs_f64();

        // Step 2b planned: children (with provisional ids for new points), and the copies
        // of snapped vertices; vertices that copies cannot separate are unsnapped and their
        // tets planned again.
        let t = Instant::now();
        let bielser = match opts.scheme {
            Scheme::Lut => None,
            Scheme::Bielser17 => Some(Bielser17Nodes::allocate(
                &session,
                tets,
                classes,
                VertexId::from_usize(n_vertices),
            )),
        };
        let split_one = |session: &CutSession<'_>, k: usize, class: &TetClass| -> Children {
            let mut c = Children::new();
            match &bielser {
                None => split_tet(session, &tets[k], class, roots, &mut c),
                Some((nodes, _)) => nodes.split(&tets[k], class, &mut c),
            };
            c
        };
        split_at.clear();
        split_at.extend((0..tets.len()).filter(|&k| classes[k].is_split()));
        // With room for the tets unsnapping splits again (each pass redoes a few), so that
        // pushing them does not move every child planned so far.
        children.clear();
        children.reserve(split_at.len() + split_at.len() / 4 + 16);
        if par(split_at.len()) {
            use rayon::prelude::*;
            children.par_extend(
                split_at
                    .par_iter()
                    .map(|&k| split_one(&session, k, &classes[k])),
            );
        } else {
            children.extend(
                split_at
                    .iter()
                    .map(|&k| split_one(&session, k, &classes[k])),
            );
        }
        // children[child_of[k]] are candidate k's children (NONE: not split).
        child_of.clear();
        child_of.resize(tets.len(), NONE);
        for (i, &k) in split_at.iter().enumerate() {
            child_of[k] = i as u32;
        }
        times.split += t.elapsed().as_secs_f64();

        let mut unsnapped: Vec<VertexId> = Vec::new();
        let mut passes = 0;
        // Vertices whose stars changed since the last pass (None: all).
        let mut redo: Option<Vec<VertexId>> = None;
        let mut copies = Copies::default();
        // The snapped vertices (sorted); unsnapping only removes some. Indexing them is
        // part of planning their copies (timed with it).
        let t = Instant::now();
        if self.snapped_slot.len() < n_vertices {
            self.snapped_slot.resize(n_vertices, NONE);
        }
        star.build(tets, classes, &mut self.snapped_slot);
        snapped.clear();
        snapped.extend_from_slice(&star.vertices);
        times.unglue += t.elapsed().as_secs_f64();
        let mut in_cut: Vec<(usize, Side)> = Vec::new();
        loop {
            passes += 1;
            let t = Instant::now();
            if opts.scheme == Scheme::Lut {
                // A cut continuing cracks decides as the MT cut does (see `pockets`).
                if !opts.continue_cracks {
                    let sides =
                        pockets::in_cut_sides(self.mesh.positions(), polygon, tets, classes);
                    if sides != in_cut {
                        // A tet's side changed: every snapped vertex is planned again.
                        redo = None;
                        in_cut = sides;
                    }
                }
                // A later pass examines only the vertices whose stars changed.
                examine.clear();
                match &redo {
                    None => examine.extend_from_slice(snapped),
                    Some(r) => examine.extend(
                        r.iter()
                            .copied()
                            .filter(|v| snapped.binary_search(v).is_ok()),
                    ),
                }
                let mesh = &self.mesh;
                let in_cut = &in_cut[..];
                let pass =
                    |vertices: &[VertexId], links: &mut LinkSlots, plan: &mut PlanBuffers| {
                        Self::plan_pass(
                            mesh, polygon, tets, classes, children, child_of, in_cut, vertices,
                            star, links, plan,
                        )
                    };
                // Each vertex is planned from its own star: in chunks on both cores when
                // there are enough, concatenated in vertex order (the same plans). None
                // at all (a parallel threshold of 0, a cut snapping no vertex) is planned
                // here: chunks of zero vertices would panic.
                let update = if !examine.is_empty() && par(PLAN_WEIGHT * examine.len()) {
                    use rayon::prelude::*;
                    let parts: Vec<Copies> = examine
                        .par_chunks(examine.len().div_ceil(PLAN_CHUNKS))
                        .map_init(
                            || (LinkSlots::default(), PlanBuffers::default()),
                            |(links, plan), chunk| pass(chunk, links, plan),
                        )
                        .collect();
                    Copies::concat(parts)
                } else {
                    pass(examine, &mut self.links, plan)
                };
                copies = match &redo {
                    None => update,
                    Some(r) => std::mem::take(&mut copies).merge(r, update),
                };
            }
            // Vertices to leave unsnapped: the pinched ones; once there are none, those
            // enclosing vertices just off the cut (see `pockets`; the valences it reads are
            // kept exactly when the options do not continue cracks).
            let mut unsnapping = std::mem::take(&mut copies.pinched);
            if unsnapping.is_empty() && opts.scheme == Scheme::Lut && !opts.continue_cracks {
                unsnapping = pockets::enclosing_snapped(
                    positions,
                    &self.scales,
                    polygon,
                    tets,
                    classes,
                    snapped,
                    &mut self.valence,
                );
            }
            times.unglue += t.elapsed().as_secs_f64();
            if unsnapping.is_empty() {
                break;
            }
            let t = Instant::now();
            unsnapping.sort_unstable();
            unsnapping.dedup();
            let unsnapping = with_twins(unsnapping, snapped, positions);
            let affected = unsnap(&mut session, positions, polygon, &unsnapping, tets, states);
            unsnapped.extend_from_slice(&unsnapping);
            snapped.retain(|v| unsnapping.binary_search(v).is_err());
            let sub_tets: Vec<Tet> = affected.iter().map(|&k| tets[k]).collect();
            let sub_states: Vec<[u8; 4]> = affected.iter().map(|&k| states[k]).collect();
            let sub = session.classify(positions, &self.scales, &sub_tets, &sub_states, false);
            let mut changed: Vec<VertexId> = unsnapping;
            for (&k, class) in affected.iter().zip(sub) {
                classes[k] = class;
                child_of[k] = if class.is_split() {
                    children.push(split_one(&session, k, &classes[k]));
                    (children.len() - 1) as u32
                } else {
                    NONE
                };
                changed.extend(tets[k].iter().copied());
            }
            changed.sort_unstable();
            changed.dedup();
            redo = Some(changed);
            times.classify += t.elapsed().as_secs_f64();
        }

        // Ids for the new points, in canonical order.
        let t = Instant::now();
        let first = VertexId::from_usize(n_vertices);
        let mut origins = match &bielser {
            None => session.allocate(first),
            Some((_, o)) => o.clone(),
        };
        // The copies are appended below: room now, rather than a reallocation then.
        origins.reserve(copies.groups.len());
        let live = || {
            child_of
                .iter()
                .filter(|&&i| i != NONE)
                .map(|&i| &children[i as usize])
        };
        let split_count = live().count();
        let created_count: usize = live().map(|c| c.len).sum();
        if n_vertices + origins.len() + copies.groups.len() > MAX_ELEMENTS
            || n_tets + created_count > MAX_ELEMENTS
        {
            return Err(CutError::TooLarge {
                max: MAX_ELEMENTS as u32,
            });
        }
        let (edges_crossed, edges_cut) = session.edge_counts();
        // Commit: new vertices, children, copies.
        first_appended.clear();
        first_appended.resize(tets.len(), 0);
        let mut next = n_tets as u32;
        for (k, &i) in child_of.iter().enumerate() {
            if i != NONE {
                first_appended[k] = next;
                next += children[i as usize].len as u32 - 1;
            }
        }
        let slot = |virtual_slot: TetId| -> TetId {
            let (k, c) = (virtual_slot.idx() / 32, virtual_slot.idx() % 32);
            if c == 0 {
                cand[k]
            } else {
                TetId(first_appended[k] + c as u32 - 1)
            }
        };
        for &i in child_of.iter().filter(|&&i| i != NONE) {
            let c = &mut children[i as usize];
            for t in c.tets[..c.len].iter_mut() {
                *t = corners(t, |v| session.resolve(v));
            }
        }
        drop(session);
        // New vertices are combinations of older ones only: their positions (as rounded,
        // which is what the mesh will hold) can be computed before anything changes.
        let new_positions =
            new_positions.compute(self.mesh.positions(), &origins, self.twinned.as_deref());
        debug_assert_eq!(
            new_positions,
            super::classify::origin_positions(self.mesh.positions(), &origins),
            "new vertices placed without the table where no end is twinned, as with it"
        );
        times.classify += t.elapsed().as_secs_f64();

        // Every child positively oriented, exactly, at those positions: the tables make
        // positive children for any position of the cut points on their edges and of the
        // face points in their faces, but a point rounded onto a neighbour (a face point
        // placed by the margin next to a snapped vertex, say) makes a flat or inverted
        // one. Such a cut is refused, the mesh unchanged, rather than leaving an invalid
        // mesh. (The 1:17 scheme, a baseline whose output is not a valid mesh anyway —
        // it does not conform — makes flat children at snapped vertices by design.)
        let t = Instant::now();
        let at = |v: VertexId| {
            if v.idx() < n_vertices {
                self.mesh.position(v)
            } else {
                new_positions[v.idx() - n_vertices]
            }
        };
        let flat = |k: usize| {
            let i = child_of[k];
            i != NONE && {
                let c = &children[i as usize];
                c.tets[..c.len].iter().any(|t| {
                    let [a, b, c, d] = corners(t, at);
                    crate::geom::orient3d(a, b, c, d) != Sign::Positive
                })
            }
        };
        let bad = if opts.scheme != Scheme::Lut {
            None
        } else if par(created_count) {
            use rayon::prelude::*;
            (0..tets.len()).into_par_iter().find_first(|&k| flat(k))
        } else {
            (0..tets.len()).find(|&k| flat(k))
        };
        if let Some(k) = bad {
            return Err(CutError::FlatChild {
                tet: cand[k].idx(),
                case: children[child_of[k] as usize].case.name(),
            });
        }
        // A crack continued across earlier ones (the scalpel's options on a plain mesh)
        // can meet their tips and cut points where they lie within 1e-6 of one another
        // and of its plane (a Kuhn grid's cracks, their tips a face-point margin off their
        // planes), and cut two lips' edges at points that far apart: a vertex it made
        // hanging in a face it made. Looked for here, before anything changes (an MT's
        // frontier is checked by the MT cut instead, which decides as it does).
        if opts.continue_cracks && self.tips.is_some() && opts.scheme == Scheme::Lut {
            let tet_at = |k: usize, c: usize| match child_of[k] {
                NONE => tets[k],
                i => children[i as usize].tets[c],
            };
            if let Some(v) = hanging_made(
                n_vertices,
                |v| match v.idx().checked_sub(n_vertices) {
                    None => self.mesh.position(v),
                    Some(i) => match new_positions.get(i) {
                        Some(&p) => p,
                        None => self.mesh.position(copies.groups[i - new_positions.len()].0),
                    },
                },
                (0..tets.len()).flat_map(|k| {
                    let n = match child_of[k] {
                        NONE => 1,
                        i => children[i as usize].len,
                    };
                    (0..n).map(move |c| (TetId((32 * k + c) as u32), tet_at(k, c)))
                }),
                &copies.groups,
                n_vertices + new_positions.len(),
            ) {
                return Err(CutError::HangingVertex { vertex: v.idx() });
            }
        }
        times.split += t.elapsed().as_secs_f64();

        let t = Instant::now();
        add_vertices(&mut self.mesh, &mut self.scales, new_positions, &origins);
        let keep_valences = !self.valence.is_empty();
        if keep_valences {
            self.valence.resize(self.mesh.nb_vertices(), [0; 2]);
        }
        if let Some(tips) = self.tips.as_mut() {
            tips.insert_face_points(first, &origins);
        }
        if let Some(crack) = self.crack.as_mut() {
            crack.resize(self.mesh.nb_vertices(), true);
        }
        self.cuts_applied += 1;
        let mark = self.cuts_applied as f64;
        let mut by_case = [0usize; 10];
        appended_parents.clear();
        appended_parents.reserve(created_count);
        let mut records: Vec<SplitRecord> = Vec::with_capacity(split_count);
        self.bvh.reserve_tets(n_tets + created_count);
        for (k, &i) in child_of.iter().enumerate() {
            if i == NONE {
                continue;
            }
            let ch = &children[i as usize];
            let parent = cand[k];
            by_case[ch.case as usize] += 1;
            // Valences: the parent's corners (scattered in memory) are updated once each,
            // by the number of children holding them less one; the new points (appended
            // together) as the children use them.
            if keep_valences {
                let corners = tets[k];
                let mut kept = [0u32; 4];
                for v in ch.tets[..ch.len].iter().flatten() {
                    match corners.iter().position(|c| c == v) {
                        Some(i) => kept[i] += 1,
                        None => self.valence[v.idx()][0] += 1,
                    }
                }
                for (c, n) in corners.iter().zip(kept) {
                    let x = &mut self.valence[c.idx()][0];
                    *x = *x + n - 1;
                }
            }
            self.mesh.tets_mut()[parent.idx()] = ch.tets[0];
            let first_extra = self.mesh.nb_tets();
            debug_assert_eq!(first_extra as u32, first_appended[k]);
            for &t in &ch.tets[1..ch.len] {
                self.mesh.push_tet(t);
            }
            records.push(SplitRecord {
                parent,
                first_appended: TetId::from_usize(first_extra),
                children: ch.len as u8,
                case: ch.case,
            });
            appended_parents.extend(std::iter::repeat_n(parent.0, ch.len - 1));
            self.bvh.add_children(
                parent,
                (first_extra..first_extra + ch.len - 1).map(TetId::from_usize),
            );
        }
        if let Some(col) = self.mesh.cell_data.get_mut(CUT_COLUMN) {
            for r in &records {
                col.values[r.parent.idx()] = mark;
            }
        }
        self.mesh.cell_data.push_copies(appended_parents);
        times.split += t.elapsed().as_secs_f64();

        let t = Instant::now();
        let vertex_copies = copies.groups.len();
        for (v, members) in copies.groups {
            let copy = self.mesh.push_vertex(self.mesh.position(v));
            self.scales.push(self.scales[v.idx()]);
            if let Some(crack) = self.crack.as_mut() {
                crack[v.idx()] = true;
                crack.push(true);
            }
            self.mesh.point_data.push_copy(v.idx());
            // A tip this cut passes through is copied once per side; the copies, at the
            // tip's position, are decided as the tip is by later cuts (on the cut near a
            // polygon continuing the crack), or one lip's edges from it are cut and the
            // coincident edges of the other lip not.
            if let Some(tips) = self.tips.as_mut().filter(|t| t.contains(v)) {
                tips.insert(copy);
            }
            origins.push(VertexOrigin::Copy { of: v });
            if keep_valences {
                self.valence.push([members.len() as u32, 0]);
                self.valence[v.idx()][0] -= members.len() as u32;
            }
            let all = self.mesh.tets_mut();
            for &m in &members {
                for x in all[slot(m).idx()].iter_mut() {
                    if *x == v {
                        *x = copy;
                    }
                }
            }
            if plan.spare.len() < SPARE_LISTS {
                plan.spare.push(members);
            }
        }
        if let Some(roots) = self.roots.as_mut() {
            extend_twin_roots(roots, origins.iter().copied());
            debug_assert_eq!(roots.len(), self.mesh.nb_vertices());
        }
        if let Some(twinned) = self.twinned.as_mut() {
            extend_twinned(twinned, &origins);
            debug_assert_eq!(twinned.len(), self.mesh.nb_vertices());
        }
        debug_assert!(
            !keep_valences
                || self.valence == pockets::valences(self.mesh.nb_vertices(), self.mesh.tets()),
            "vertex valences kept up to date"
        );
        times.unglue += t.elapsed().as_secs_f64();
        times.cut = start.elapsed().as_secs_f64();

        let t = Instant::now();
        let components = opts
            .count_components
            .then(|| Components::count_through_vertices(&self.mesh));
        times.components = t.elapsed().as_secs_f64();

        let cut_points = origins
            .iter()
            .filter(|o| matches!(o, VertexOrigin::Edge { .. }))
            .count();
        let face_points = origins
            .iter()
            .filter(|o| matches!(o, VertexOrigin::Face { .. }))
            .count();
        let stats = CutStats {
            scheme: opts.scheme,
            snap: opts.snap.relative,
            tets_tested: *tested,
            tets_candidate: cand.len(),
            tets_cut: split_count,
            tets_cut_by_case: by_case,
            tets_created: created_count,
            vertices_added: origins.len(),
            cut_points,
            face_points,
            vertex_copies,
            vertices_snapped: snapped.len(),
            vertices_unsnapped: unsnapped.len(),
            plan_passes: passes,
            edges_crossed,
            edges_cut,
            tets_after: self.mesh.nb_tets(),
            vertices_after: self.mesh.nb_vertices(),
            components,
            time: times,
        };
        Ok(CutResult {
            stats,
            first_new_vertex: first,
            origins,
            splits: records,
        })
    }

    /// The copies of the snapped vertices `examine` (their candidates in `star`), from the
    /// candidates around them as planned so far: each vertex decided from the tets around
    /// it when [`plan_by_parents`] can, from their children otherwise ([`plan_vertex`]).
    /// The tets taking a copy are named by virtual slots: candidate `k`'s child `c` is
    /// `32 k + c` (child 0 of a split tet, and an unsplit tet, take the tet's slot).
    #[allow(clippy::too_many_arguments)]
    fn plan_pass(
        mesh: &TetMesh,
        polygon: &CutPolygon,
        tets: &[Tet],
        classes: &[TetClass],
        children: &[Children],
        child_of: &[u32],
        in_cut: &[(usize, Side)],
        examine: &[VertexId],
        star: &StarIndex,
        links: &mut LinkSlots,
        buffers: &mut PlanBuffers,
    ) -> Copies {
        // The side of a whole candidate around a snapped vertex (`Side` of `unsplit_side`),
        // or, lying in the cut, the side `in_cut` gives it.
        let whole_side = |k: usize| match in_cut.binary_search_by_key(&k, |&(j, _)| j) {
            Ok(i) => in_cut[i].1,
            Err(_) => Self::unsplit_side(mesh, polygon, &tets[k], &classes[k].states),
        };
        let mut out = Copies::default();
        out.groups.reserve(examine.len());
        let PlanBuffers {
            around,
            negative,
            entries,
            scratch,
            spare,
        } = buffers;
        // The tets around v made from candidate k, with their virtual slots and sides: its
        // children through v when split, itself when whole.
        let around_v = |v: VertexId, k: usize, f: &mut dyn FnMut(TetId, Tet, Side)| {
            if child_of[k] == NONE {
                f(TetId((32 * k) as u32), tets[k], whole_side(k));
            } else {
                let ch = &children[child_of[k] as usize];
                for c in 0..ch.len {
                    if ch.tets[c].contains(&v) {
                        f(TetId((32 * k + c) as u32), ch.tets[c], ch.sides[c]);
                    }
                }
            }
        };
        for &v in examine {
            let run = star.run(v);
            around.clear();
            negative.clear();
            for &(k, j) in run {
                let (k, c) = (k as usize, &classes[k as usize]);
                around.push(if child_of[k] == NONE {
                    let positive = whole_side(k) == Side::Positive;
                    negative.push(u16::from(!positive));
                    ParentAt {
                        verts: tets[k],
                        states: c.states,
                        j,
                        sides: if positive { 1 } else { 2 },
                        regular: true,
                    }
                } else {
                    let ch = &children[child_of[k] as usize];
                    let at = entry_at_vertex(ch.config);
                    let r = ch.rank[j as usize] as usize;
                    negative.push(at.negative[r]);
                    ParentAt {
                        verts: tets[k],
                        states: c.states,
                        j,
                        sides: (at.sides >> (2 * r)) & 3,
                        regular: at.regular & (1 << r) != 0,
                    }
                });
            }
            let from_children =
                |entries: &mut Vec<StarEntry>, out: &mut Copies, scratch: &mut PlanScratch| {
                    entries.clear();
                    for &(k, _) in run {
                        around_v(v, k as usize, &mut |tet, verts, side| {
                            entries.push(StarEntry {
                                vertex: v,
                                tet,
                                verts,
                                side,
                            })
                        });
                    }
                    plan_vertex(v, entries, scratch, out);
                };
            let plan = plan_by_parents(around, links);
            let groups_before = out.groups.len();
            match plan {
                ParentPlan::Keep => {}
                ParentPlan::CopyNegative => {
                    // The children holding the vertex on the negative side, from the
                    // table entries (in the order `around_v` lists them).
                    let mut members = spare.pop().unwrap_or_default();
                    members.clear();
                    members.reserve(2 * run.len());
                    for (&(k, _), &mask) in run.iter().zip(negative.iter()) {
                        let mut m = mask;
                        while m != 0 {
                            let c = m.trailing_zeros();
                            members.push(TetId(32 * k + c));
                            m &= m - 1;
                        }
                    }
                    out.groups.push((v, members));
                }
                ParentPlan::Children => from_children(entries, &mut out, scratch),
            }
            if cfg!(debug_assertions) && plan != ParentPlan::Children {
                let mut check = Copies::default();
                from_children(entries, &mut check, scratch);
                debug_assert!(
                    check.pinched.is_empty() && check.groups[..] == out.groups[groups_before..],
                    "vertex {v}: planned from its tets as {plan:?}, from their children as {check:?}"
                );
            }
        }
        out
    }

    /// The side of a tet the tables leave whole but that touches the cut at a vertex: the
    /// side of its other vertices; a tet with all four vertices snapped (lying in the cut)
    /// goes to the side of its centroid, unless its neighbours decide
    /// ([`pockets::in_cut_sides`]).
    fn unsplit_side(mesh: &TetMesh, polygon: &CutPolygon, tet: &Tet, states: &[u8; 4]) -> Side {
        let present = (1u8 << states[0]) | (1 << states[1]) | (1 << states[2]) | (1 << states[3]);
        if present & (1 << POS) != 0 {
            debug_assert!(
                present & (1 << NEG) == 0,
                "an unsplit tet straddles at a snapped vertex"
            );
            return Side::Positive;
        }
        if present & (1 << NEG) != 0 {
            return Side::Negative;
        }
        pockets::centroid_side(mesh.positions(), polygon, tet)
    }
}

/// Tets from which [`Cutter::set_positions`] checks their orientation on both cores.
const PARALLEL_ORIENT: usize = 1 << 16;

/// Positions given for `expected` vertices: as many, all finite.
pub(crate) fn check_positions(positions: &[DVec3], expected: usize) -> Result<(), CutError> {
    if positions.len() != expected {
        return Err(CutError::PositionCount {
            count: positions.len(),
            expected,
        });
    }
    match crate::geom::first_unsupported(positions) {
        Some((vertex, value)) if !value.is_finite() => Err(CutError::NonFinitePosition { vertex }),
        Some((vertex, value)) => Err(CutError::PositionOutOfRange { vertex, value }),
        None => Ok(()),
    }
}

/// The first vertex a cut would make (id `first_new` or above: cut and face points, then
/// copies from `first_copy`) lying strictly inside a boundary face the cut makes that it is
/// not a corner of, other than a face of the other lip of a crack (as `TetMesh::validate`
/// finds a hanging vertex). `slots` lists the tets after the cut where it changes the mesh
/// (by virtual slot: the candidate's index × 32 + the child's, in increasing order),
/// before `groups` gives the copies of its snapped vertices (`groups[i]`: the vertex and
/// the slots taking copy `first_copy + i`); `position` places old and new vertices. A face
/// holding a new vertex is held only by such tets, so the faces among them held once are
/// boundary faces; those of old vertices only are passed over (their other tet is
/// unchanged). Sorted arrays, not hash maps, hold the tets and count the faces: on the
/// random scalpel paths of tests/cut_scalpel.rs the check took 9-17 % less time (still
/// about a third of a plain scalpel step; see the README).
fn hanging_made(
    first_new: usize,
    position: impl Fn(VertexId) -> DVec3,
    slots: impl Iterator<Item = (TetId, Tet)>,
    groups: &[(VertexId, Vec<TetId>)],
    first_copy: usize,
) -> Option<VertexId> {
    // The tets after the cut by slot, copies in place.
    let mut after: Vec<(TetId, Tet)> = slots.collect();
    debug_assert!(after.windows(2).all(|w| w[0].0 < w[1].0));
    for (i, (v, members)) in groups.iter().enumerate() {
        let copy = VertexId::from_usize(first_copy + i);
        for m in members {
            if let Ok(k) = after.binary_search_by_key(m, |a| a.0) {
                for x in after[k].1.iter_mut().filter(|x| **x == *v) {
                    *x = copy;
                }
            }
        }
    }
    // The faces holding a new vertex, sorted by their corners (packed, lowest first): those
    // held once are boundary faces.
    let is_new = |v: VertexId| v.idx() >= first_new;
    let mut keys: Vec<u128> = Vec::with_capacity(4 * after.len());
    for (_, t) in &after {
        if !t.iter().any(|&v| is_new(v)) {
            continue;
        }
        for f in crate::mesh::tables::TET_FACES {
            let [a, b, c] = f.map(|j| t[j].0);
            if [a, b, c].iter().any(|&v| is_new(VertexId(v))) {
                let (lo, hi) = (a.min(b), a.max(b));
                let (lo, mid, hi) = if c < lo {
                    (c, lo, hi)
                } else if c < hi {
                    (lo, c, hi)
                } else {
                    (lo, hi, c)
                };
                keys.push(u128::from(lo) << 64 | u128::from(mid) << 32 | u128::from(hi));
            }
        }
    }
    keys.sort_unstable();
    // Local ids: the vertices of the boundary faces.
    let mut local: HashMap<VertexId, VertexId, FxBuild> = HashMap::default();
    let mut ids: Vec<VertexId> = Vec::new();
    let mut faces: Vec<[VertexId; 3]> = Vec::new();
    for run in keys.chunk_by(|a, b| a == b).filter(|run| run.len() == 1) {
        let key = run[0];
        let face = [(key >> 64) as u32, (key >> 32) as u32, key as u32];
        faces.push(face.map(|v| {
            *local.entry(VertexId(v)).or_insert_with(|| {
                ids.push(VertexId(v));
                VertexId::from_usize(ids.len() - 1)
            })
        }));
    }
    let pos: Vec<DVec3> = ids.iter().map(|&v| position(v)).collect();
    let points = (0..ids.len())
        .filter(|&i| ids[i].idx() >= first_new)
        .map(VertexId::from_usize)
        .collect();
    let hits = crate::mesh::boundary_hits(&pos, &faces, points);
    hits.hanging.iter().map(|&(v, _)| ids[v.idx()]).min()
}

/// Appends the vertices of `origins` to `mesh` (their `positions`, interpolated point
/// data) and their scales to `scales`.
fn add_vertices(
    mesh: &mut TetMesh,
    scales: &mut Vec<f64>,
    positions: &[DVec3],
    origins: &[VertexOrigin],
) {
    mesh.positions_vec_mut().extend_from_slice(positions);
    push_origin_rows(&mut mesh.point_data, scales, origins);
}

/// Point columns that name a vertex rather than measure a quantity (an extraction's MT
/// vertex ids): interpolating them would make ids that name nothing. A point a cut makes
/// on an edge or a face gets -1 (no such vertex); a copy keeps its original's id.
const ID_COLUMNS: [&str; 1] = [crate::mt::POINT_VERTEX];

/// `vertices` (sorted, distinct), to be unsnapped, with every vertex of `snapped` at the
/// same position as one of them: the copies an earlier cut made of a vertex (one per lip
/// of its crack, coincident) are unsnapped together. Unsnapped alone, one lip's edges
/// from it could be cut while the other lip's are not: a face point on one lip, inside
/// the coincident face of the other (a hanging vertex). Shared with the MT cut.
pub(crate) fn with_twins(
    vertices: Vec<VertexId>,
    snapped: &[VertexId],
    positions: &[DVec3],
) -> Vec<VertexId> {
    let key = |v: &VertexId| positions[v.idx()].to_array().map(f64::to_bits);
    let at: HashSet<[u64; 3], FxBuild> = vertices.iter().map(key).collect();
    let mut all = vertices;
    all.extend(snapped.iter().filter(|v| at.contains(&key(v))));
    all.sort_unstable();
    all.dedup();
    all
}

/// Leaves `vertices` (sorted, distinct), snapped so far, unsnapped: each takes the state
/// [`unsnapped_state`] gives it (its twins among them the same, from all their tets) in
/// every candidate of `tets` using it (in `states`), and
/// the session forgets the records made with it. Returns the candidates touched (sorted,
/// distinct), to be classified again. Shared with the MT cut.
pub(crate) fn unsnap(
    session: &mut CutSession<'_>,
    positions: &[DVec3],
    polygon: &CutPolygon,
    vertices: &[VertexId],
    tets: &[Tet],
    states: &mut [[u8; 4]],
) -> Vec<usize> {
    debug_assert!(vertices.windows(2).all(|w| w[0] < w[1]));
    // Twins (copies at one position, one per lip of an earlier crack) take one state, from
    // all their tets: decided apart, each by its own lip's neighbours, one lip's edge from
    // it could be crossed and the coincident edge of the other lip not, leaving a cut
    // point of one lip inside a face of the other.
    let mut twin_group: Vec<usize> = (0..vertices.len()).collect();
    let mut first_at: HashMap<[u64; 3], usize, FxBuild> = HashMap::default();
    for (i, v) in vertices.iter().enumerate() {
        let key = positions[v.idx()].to_array().map(f64::to_bits);
        twin_group[i] = *first_at.entry(key).or_insert(i);
    }
    // (twin group, candidate, corner), grouped: one pass over the candidates.
    let mut uses: Vec<(usize, usize, usize)> = Vec::new();
    let (Some(&lo), Some(&hi)) = (vertices.first(), vertices.last()) else {
        return Vec::new();
    };
    for (k, tet) in tets.iter().enumerate() {
        for (j, v) in tet.iter().enumerate() {
            if (lo..=hi).contains(v) {
                if let Ok(i) = vertices.binary_search(v) {
                    uses.push((twin_group[i], k, j));
                }
            }
        }
    }
    uses.sort_unstable();
    for group in uses.chunk_by(|a, b| a.0 == b.0) {
        let v = vertices[group[0].0];
        let around = group.iter().map(|&(_, k, _)| &tets[k]);
        let state = unsnapped_state(positions, polygon, v, around);
        for &(_, k, j) in group {
            states[k][j] = state;
        }
    }
    session.forget_vertices(vertices);
    let mut affected: Vec<usize> = uses.iter().map(|&(_, k, _)| k).collect();
    affected.sort_unstable();
    affected.dedup();
    affected
}

/// The state of a snapped vertex left unsnapped: its exact side; for a vertex exactly on
/// the plane, the side of its neighbours (in the tets `around` it) off the plane when they
/// are all on one side (then no edge from it crosses the plane at it, which would make a
/// cut point coincide with it), positive otherwise.
fn unsnapped_state<'t>(
    positions: &[DVec3],
    polygon: &CutPolygon,
    v: VertexId,
    around: impl Iterator<Item = &'t Tet>,
) -> u8 {
    match polygon.side(positions[v.idx()]) {
        Sign::Negative => return NEG,
        Sign::Positive => return POS,
        Sign::Zero => {}
    }
    let (mut pos, mut neg) = (false, false);
    // Ghost corners of an MT's closing tets have no position.
    for x in around.flatten().filter_map(|x| positions.get(x.idx())) {
        match polygon.side(*x) {
            Sign::Positive => pos = true,
            Sign::Negative => neg = true,
            Sign::Zero => {}
        }
    }
    if neg && !pos { NEG } else { POS }
}

/// Appends the point-data rows and scales of the vertices of `origins` (interpolated from
/// the vertices they are made of; the largest scale of those; id columns as above). Shared
/// with the MT cut.
pub(crate) fn push_origin_rows(
    point_data: &mut Attributes,
    scales: &mut Vec<f64>,
    origins: &[VertexOrigin],
) {
    for o in origins {
        let scale = match *o {
            VertexOrigin::Edge { a, b, t, .. } => {
                point_data.push_lerp(a.idx(), b.idx(), t);
                scales[a.idx()].max(scales[b.idx()])
            }
            VertexOrigin::Face { v, w } => {
                point_data.push_combination(&[
                    (v[0].idx(), w[0]),
                    (v[1].idx(), w[1]),
                    (v[2].idx(), w[2]),
                ]);
                v.iter().map(|x| scales[x.idx()]).fold(0.0, f64::max)
            }
            VertexOrigin::Copy { of } => {
                point_data.push_copy(of.idx());
                scales[of.idx()]
            }
        };
        scales.push(scale);
    }
    for name in ID_COLUMNS {
        if let Some(ids) = point_data.get_mut(name).filter(|c| c.components == 1) {
            let first = ids.len() - origins.len();
            for (k, o) in origins.iter().enumerate() {
                if !matches!(o, VertexOrigin::Copy { .. }) {
                    ids.values[first + k] = -1.0;
                }
            }
        }
    }
}

/// Cuts `mesh` with `polygon` once (building the acceleration structure, timed in
/// `stats.time.build`). To apply many cuts, keep a [`Cutter`].
pub fn cut_mesh(
    mesh: &mut TetMesh,
    polygon: &CutPolygon,
    options: &CutOptions,
) -> Result<CutResult, CutError> {
    options.check()?;
    let mut cutter = Cutter::prepare(std::mem::take(mesh), *options);
    let result = cutter.cut(polygon);
    let build = cutter.build_time().as_secs_f64();
    *mesh = cutter.into_mesh();
    let mut result = result?;
    result.stats.time.build = build;
    Ok(result)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `hanging_made` on two tets the cut changed: one holding a new vertex (5) whose face
    /// (5, 1, 2) covers the origin, the other taking the copy (6) of vertex 0, at the
    /// origin, in place of 0. The copy lies strictly inside that face and is none of its
    /// corners: hanging. Without the copy the second tet holds no new vertex and nothing
    /// hangs.
    #[test]
    fn a_copy_inside_a_face_the_cut_makes_hangs() {
        let v = VertexId;
        let positions = [
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            -DVec3::Z,
            DVec3::new(-1.0, -1.0, 0.0),
        ];
        // The copy stands where vertex 0 does.
        let position = |x: VertexId| positions[if x == v(6) { 0 } else { x.idx() }];
        let slots = || {
            [
                (TetId(0), [v(5), v(1), v(2), v(3)]),
                (TetId(32), [v(0), v(1), v(2), v(4)]),
            ]
            .into_iter()
        };
        let copies = [(v(0), vec![TetId(32)])];
        assert_eq!(hanging_made(5, position, slots(), &copies, 6), Some(v(6)));
        assert_eq!(hanging_made(5, position, slots(), &[], 6), None);
    }
}
