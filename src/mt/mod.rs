//! # The Multi-Tessellation (paper §2)
//!
//! This layer owns the multiresolution model: how it is stored ([`Mt`]), built by
//! simplifying a [`TetMesh`](crate::mesh::TetMesh) ([`Mt::build`]), checked ([`Mt::validate`]), cut into
//! variable-resolution meshes ([`Mt::extract`], [`Frontier`]) and saved ([`Mt::save`],
//! [`Mt::load`]). It uses `geom` and `mesh` only; it knows nothing of cuts, files other
//! than its own `.mt` format, or the C ABI.
//!
//! ## The store
//!
//! * **One vertex pool.** Half-edge collapses keep vertex positions, so every level of detail
//!   indexes the input's vertices (pool vertex `i` is input vertex `i`). Per-vertex
//!   attributes of the input live here, one row per pool vertex.
//! * **One tet pool** holding every tet of every level, each as its four vertex ids — plus
//!   *ghost tets*: for every boundary triangle `(a, b, c)` (outward) of every level, the tet
//!   `(a, b, c, GHOST)` joining it to a virtual vertex outside the mesh. Ghosts make the
//!   mesh a closed complex, so a collapse that moves the boundary still has a floor and a
//!   ceiling with the same boundary (the MT condition of paper §2, which would otherwise
//!   fail on the boundary), and the DAG records the dependencies that boundary changes
//!   create. Ghosts are never extracted. Per-tet attributes of the input live here too, one
//!   row per pool tet, inherited by the tets that replace them.
//! * **Arcs.** The pool is ordered so that the tets created by fragment `i` and destroyed by
//!   fragment `j` are contiguous: that run is the paper's arc `(Σi, Σj, Fj ∩ Σi)`. Arcs are
//!   sorted by creator, then destroyer, so an arc is stored as its start and destroyer only:
//!   the arcs of creator `i` are a range ([`Mt::out_arcs`]). Each tet therefore has exactly
//!   one creator and one destroyer ([`Mt::tet_creator`], [`Mt::tet_destroyer`], by binary
//!   search) without a per-tet column: at about three pool tets per input tet, two `u32`
//!   columns would cost 24 bytes per input tet, against a budget of 100 for the whole
//!   model (a creator column per arc would cost 4.7).
//! * **Fragments** (DAG nodes): kind (root, collapse, drain), error, level (longest path
//!   from a root), bounding box of floor and ceiling, their out-arcs (a range) and their
//!   predecessors (the creators of their in-arcs, one per arc, from which
//!   [`Mt::in_arcs`] finds the arcs).
//!   The root creates the input mesh (and its ghosts); the drain destroys the coarsest mesh.
//!   Several root/drain pairs may coexist ([`Mt::roots`], [`Mt::drains`]): a body cut
//!   through becomes independent MTs within one store.
//!
//! What the store keeps is only the primary data (pool, arcs, kinds, errors); levels,
//! bounding boxes and the arc lists are derived when an `Mt` is assembled, so the file
//! format cannot make them inconsistent.
//!
//! ## Errors and frontiers
//!
//! Each fragment has one error, at least the errors of the fragments it depends on (the
//! creators of its floor): errors grow along the DAG, so "every fragment of error ≤ ε
//! applied" is a consistent frontier and threshold extraction is well defined.
//! A *frontier* is a set `S` of applied fragments closed under dependencies (roots always
//! in, drains never); its mesh is the set of arcs from `S` to the rest.
//!
//! ## Designed for cuts (paper §3)
//!
//! Cuts (`crate::cut::MtCutter`, in the layer above) open the store ([`Mt::open`], [`OpenMt`]: one creator
//! and destroyer per tet), replace and append tets, append vertices with interpolated
//! attribute rows and fragments split in parts, and close it again ([`OpenMt::close`]),
//! which sorts the pool back into arcs and re-derives everything else. [`Mt::canonical_form`] compares two MTs independently
//! of vertex, tet and fragment numbering.

pub mod build;
pub mod bvh;
pub mod canonical;
mod csr;
pub mod edit;
pub mod error;
pub mod extract;
pub mod file;
pub mod frontier;
pub mod history;
pub mod validate;

pub use build::{BuildError, BuildOptions, BuildPhase, BuildProgress, BuildStats, Rejections};
pub use bvh::{Bvh, FragmentBvh, FragmentHit, Region};
pub use canonical::{CanonicalFragment, CanonicalMt, TetKey};
pub use edit::OpenMt;
pub(crate) use edit::TetLinks;
pub use error::{BoundaryError, ErrorMetric, QualityError, TetError, TetSample, VolumeError};
pub use extract::{
    CELL_ERROR, CELL_FRAGMENT, CELL_LEVEL, ExtractError, ExtractOptions, ExtractStats, Extraction,
    Focus, POINT_VERTEX,
};
pub use file::{MT_FILE_VERSION, MT_MAGIC, MtFileError, MtFileErrorKind};
pub use frontier::{Frontier, FrontierUpdate};
pub use history::CutHistory;
pub use validate::{MtValidationReport, MtViolation, MtViolationKind};

use crate::geom::{Aabb, DVec3};
use crate::mesh::{Attributes, FragmentId, Tet, TetId, VertexId};
use csr::Csr;
pub use csr::{Row as ArcList, RowIter as ArcIter};
use rayon::prelude::*;
use std::ops::Range;

/// The virtual vertex outside the mesh that ghost tets join boundary triangles to. It has
/// no position; a ghost tet is `(a, b, c, GHOST)` with `(a, b, c)` the boundary triangle,
/// oriented outwards (so the ghost is "positively oriented" towards the outside).
pub const GHOST: VertexId = VertexId(u32::MAX - 1);

/// Largest number of vertices, tets, arcs or fragments an MT may hold (ids are `u32`, and
/// the two largest values are reserved for [`GHOST`] and `INVALID`).
pub const MAX_ELEMENTS: usize = (u32::MAX - 2) as usize;

/// What a DAG node is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FragmentKind {
    /// Creates the full-resolution input mesh; always applied.
    Root,
    /// One simplification step: destroys its floor, creates its ceiling.
    Collapse,
    /// Destroys the coarsest mesh; never applied.
    Drain,
}

impl FragmentKind {
    pub(crate) fn code(self) -> u8 {
        match self {
            FragmentKind::Root => 0,
            FragmentKind::Collapse => 1,
            FragmentKind::Drain => 2,
        }
    }

    pub(crate) fn from_code(c: u8) -> Option<FragmentKind> {
        match c {
            0 => Some(FragmentKind::Root),
            1 => Some(FragmentKind::Collapse),
            2 => Some(FragmentKind::Drain),
            _ => None,
        }
    }
}

/// How an MT was made: kept in the `.mt` file and shown by `mtcut info`.
#[derive(Clone, Debug, PartialEq)]
pub struct MtInfo {
    /// Name of the error metric ([`TetError::name`]).
    pub error_metric: String,
    /// Boundary tolerance, relative to the input's bounding-box diagonal.
    pub boundary_tolerance: f64,
    /// Whether boundary feature edges and corners were kept.
    pub preserve_features: bool,
    /// Dihedral angle (degrees) above which a boundary edge counted as a feature.
    pub feature_angle_degrees: f64,
    /// Tets of the input mesh.
    pub input_tets: usize,
    /// What the cuts made so far leave for later cuts (see [`CutHistory`]).
    pub cuts: CutHistory,
}

/// The primary data of an MT, from which [`Mt::assemble`] derives the rest.
pub(crate) struct MtParts {
    pub positions: Vec<DVec3>,
    pub point_data: Attributes,
    pub tets: Vec<Tet>,
    pub cell_data: Attributes,
    pub arc_start: Vec<u32>,
    pub arc_creator: Vec<FragmentId>,
    pub arc_destroyer: Vec<FragmentId>,
    pub kind: Vec<FragmentKind>,
    pub error: Vec<f64>,
    pub info: MtInfo,
    /// Boxes still known from before an edit (see [`KnownBoxes`]); `None`: derive all.
    pub known_boxes: Option<KnownBoxes>,
    /// Whether the pool keeps spare capacity (an edit's) instead of being made to fit.
    pub keep_room: bool,
    /// `Some`: the arcs are those of the MT an edit opened, unchanged, with its DAG tables
    /// (`arc_creator` and `arc_destroyer` are left empty; only `arc_start` is new). Their
    /// creators and destroyers were checked when that MT was assembled.
    pub kept_arcs: Option<KnownDag>,
    /// Whether every tet is known to name vertices of the pool only (checked by the
    /// editor's close on the tets it wrote); `false`: [`Mt::assemble`] checks every tet.
    pub vertex_ids_checked: bool,
}

/// The derived DAG tables of an MT opened for editing ([`edit::OpenMt`]): when the edit
/// leaves every arc joining the same fragments (a cut that splits none only adds tets to
/// arcs), successors, predecessors and levels are these, not derived again over the whole
/// DAG.
#[derive(Clone, Debug)]
pub(crate) struct KnownDag {
    pub out_start: Vec<u32>,
    pub arc_destroyer: Vec<FragmentId>,
    pub preds: Csr,
    pub level: Vec<u32>,
}

/// Fragment boxes an edited MT keeps: those of the fragments the edit did not touch, in
/// the frame they were quantised in. Used only while the new frame is the same.
#[derive(Clone, Debug)]
pub(crate) struct KnownBoxes {
    pub frame: BoxFrame,
    pub boxes: Vec<QuantBox>,
    /// Per fragment (of `boxes`): whether its floor or ceiling changed (box re-derived).
    /// Fragments past the end are new, so derived too.
    pub changed: Vec<bool>,
}

/// A Multi-Tessellation: every level of detail of a tet mesh and the DAG that says how they
/// fit together. See the [module documentation](self) for the layout.
#[derive(Clone, Debug, PartialEq)]
pub struct Mt {
    positions: Vec<DVec3>,
    point_data: Attributes,
    tets: Vec<Tet>,
    cell_data: Attributes,
    /// `arc_start[a]..arc_start[a + 1]` are the pool tets of arc `a`; one extra entry.
    arc_start: Vec<u32>,
    arc_destroyer: Vec<FragmentId>,
    kind: Vec<FragmentKind>,
    error: Vec<f64>,
    info: MtInfo,
    // Derived by `assemble`.
    level: Vec<u32>,
    /// The box every fragment box is quantised on (see [`QuantBox`]).
    frame: BoxFrame,
    bbox: Vec<QuantBox>,
    /// `out_start[f]..out_start[f + 1]` are the arcs `f` creates (arcs are sorted by
    /// creator); one extra entry.
    out_start: Vec<u32>,
    /// By destroyer, the creators of its in-arcs (sorted: arcs are sorted by creator).
    preds: Csr,
    roots: Vec<FragmentId>,
    drains: Vec<FragmentId>,
}

impl Mt {
    /// Checks the structure of `parts` (everything later code indexes with) and derives
    /// levels, boxes and arc lists. Errors say what is inconsistent; they are reported as
    /// file corruption by the loader and are internal bugs anywhere else.
    pub(crate) fn assemble(mut p: MtParts) -> Result<Mt, String> {
        let nv = p.positions.len();
        let nt = p.tets.len();
        let nf = p.kind.len();
        let kept = p.kept_arcs.take();
        if let Some(k) = &kept
            && (k.out_start.len() != nf + 1 || k.level.len() != nf)
        {
            return Err(format!(
                "arcs kept from an MT of {} fragments, not {nf}",
                k.level.len()
            ));
        }
        let na = match &kept {
            Some(k) => k.arc_destroyer.len(),
            None => p.arc_creator.len(),
        };
        for (what, n) in [
            ("vertices", nv),
            ("tets", nt),
            ("arcs", na),
            ("fragments", nf),
        ] {
            if n > MAX_ELEMENTS {
                return Err(format!(
                    "{n} {what}, more than the {MAX_ELEMENTS} supported"
                ));
            }
        }
        let destroyers = kept.as_ref().map_or(p.arc_destroyer.len(), |_| na);
        if destroyers != na || p.arc_start.len() != na + 1 {
            return Err(format!(
                "arc columns of different lengths ({} starts, {} creators, {} destroyers)",
                p.arc_start.len(),
                na,
                destroyers
            ));
        }
        if p.error.len() != nf {
            return Err(format!("{} errors for {nf} fragments", p.error.len()));
        }
        if p.arc_start[0] != 0 || p.arc_start[na] as usize != nt {
            return Err(format!(
                "arcs cover tets {}..{} of a pool of {nt}",
                p.arc_start[0], p.arc_start[na]
            ));
        }
        // Arcs kept from the MT an edit opened are that MT's (checked when it was
        // assembled), their ranges shifted by the tets the edit moved (`OpenMt::close`,
        // which empties none): checked in debug builds only, as a pass over them would
        // cost a large MT's small edit more than the edit.
        debug_assert!(
            kept.is_none() || p.arc_start.windows(2).all(|w| w[0] <= w[1]),
            "kept arc ranges out of order"
        );
        let new_arcs = if kept.is_none() { na } else { 0 };
        if let Some(a) = (0..new_arcs).find(|&a| p.arc_start[a] > p.arc_start[a + 1]) {
            return Err(format!("arc {a} ends before it starts"));
        }
        for a in 0..new_arcs {
            let (c, d) = (p.arc_creator[a], p.arc_destroyer[a]);
            if c.idx() >= nf || d.idx() >= nf {
                return Err(format!(
                    "arc {a} joins fragments {c} and {d}, but there are {nf}"
                ));
            }
            if c == d {
                return Err(format!("arc {a} goes from fragment {c} to itself"));
            }
        }
        p.info.cuts.check(nv)?;
        if let Some((t, v)) = (!p.vertex_ids_checked)
            .then(|| first_bad_vertex(&p.tets, nv))
            .flatten()
        {
            return Err(format!("tet {t} uses vertex {v}, but the pool has {nv}"));
        }
        if let Some(c) = p.point_data.mismatched(nv) {
            return Err(format!(
                "point data '{}' has {} rows for {nv} vertices",
                c.name,
                c.len()
            ));
        }
        if let Some(c) = p.cell_data.mismatched(nt) {
            return Err(format!(
                "cell data '{}' has {} rows for {nt} tets",
                c.name,
                c.len()
            ));
        }
        // Sorted by (creator, destroyer), each pair once: what lets the creator column go
        // (the builder and `OpenMt::close` write arcs in this order; a file that does not
        // is corrupt).
        if let Some(a) = (1..new_arcs).find(|&a| {
            (p.arc_creator[a - 1], p.arc_destroyer[a - 1]) >= (p.arc_creator[a], p.arc_destroyer[a])
        }) {
            return Err(format!(
                "arc {a} ({} -> {}) is not after arc {} ({} -> {}) in (creator, destroyer) order",
                p.arc_creator[a],
                p.arc_destroyer[a],
                a - 1,
                p.arc_creator[a - 1],
                p.arc_destroyer[a - 1]
            ));
        }
        // Arcs kept from the MT an edit opened: the same DAG, so the same successors,
        // predecessors and levels.
        let (out_start, mut arc_destroyer, preds, known_level) = match kept {
            Some(k) => (k.out_start, k.arc_destroyer, k.preds, Some(k.level)),
            None => {
                let mut out_start = vec![0u32; nf + 1];
                for c in &p.arc_creator {
                    out_start[c.idx() + 1] += 1;
                }
                for f in 0..nf {
                    out_start[f + 1] += out_start[f];
                }
                let arc_destroyer = std::mem::take(&mut p.arc_destroyer);
                let preds = Csr::from_pairs(
                    nf,
                    (0..na).map(|a| (arc_destroyer[a].0, p.arc_creator[a].0)),
                );
                (out_start, arc_destroyer, preds, None)
            }
        };
        p.arc_start.shrink_to_fit();
        arc_destroyer.shrink_to_fit();
        // An edited pool keeps the room its edit was given (`edit::edit_room`) for the
        // next one, which then appends there instead of copying the pool twice (to shrink
        // it, then to grow it again: 60 MB each way for a pool of 3.8 M tets). A built or
        // loaded MT is made to fit.
        let keep = |len: usize, cap: usize| p.keep_room && cap <= len + 2 * edit::edit_room(len);
        if !keep(p.tets.len(), p.tets.capacity()) {
            p.tets.shrink_to_fit();
        }
        if !keep(p.positions.len(), p.positions.capacity()) {
            p.positions.shrink_to_fit();
        }
        p.kind.shrink_to_fit();
        p.error.shrink_to_fit();
        for f in 0..nf {
            let e = p.error[f];
            match p.kind[f] {
                FragmentKind::Root if !preds.row(f).is_empty() => {
                    return Err(format!("root fragment {f} destroys tets"));
                }
                FragmentKind::Drain if out_start[f] != out_start[f + 1] => {
                    return Err(format!("drain fragment {f} creates tets"));
                }
                FragmentKind::Drain if e.is_nan() => {
                    return Err(format!("fragment {f} has error NaN"));
                }
                FragmentKind::Root | FragmentKind::Collapse if !(e.is_finite() && e >= 0.0) => {
                    return Err(format!("fragment {f} has error {e}"));
                }
                _ => {}
            }
        }
        // Successors straight from the arcs (sorted by creator, each pair once), where the
        // predecessor lists came from: no second table to build.
        let level = match known_level {
            Some(level) => level,
            None => levels_with(nf, &preds, |f| {
                arc_destroyer[out_start[f] as usize..out_start[f + 1] as usize]
                    .iter()
                    .map(|d| d.0)
            })
            .ok_or_else(|| "the DAG has a cycle".to_string())?,
        };
        let arc_box = |a: u32| {
            let a = a as usize;
            let mut b = Aabb::EMPTY;
            for t in &p.tets[p.arc_start[a] as usize..p.arc_start[a + 1] as usize] {
                for v in t.iter().filter(|v| **v != GHOST) {
                    b.grow(p.positions[v.idx()]);
                }
            }
            b
        };
        let frame = BoxFrame::of(&p.positions);
        // Kept boxes hold in the same frame only (new vertices lie inside the body, but
        // a rounding may move its bounding box).
        let known = p.known_boxes.take().filter(|k| k.frame == frame);
        let bbox: Vec<QuantBox> = (0..nf)
            .into_par_iter()
            .map(|f| {
                if let Some(k) = &known
                    && f < k.boxes.len()
                    && !k.changed[f]
                {
                    return k.boxes[f];
                }
                let f32 = f as u32;
                let ins = preds
                    .row(f)
                    .into_iter()
                    .filter_map(|c| arc_between(&out_start, &arc_destroyer, c, f32));
                let b = (out_start[f]..out_start[f + 1])
                    .chain(ins)
                    .fold(Aabb::EMPTY, |b, a| b.union(&arc_box(a)));
                frame.enclose(&b)
            })
            .collect();
        let of_kind = |k: FragmentKind| -> Vec<FragmentId> {
            (0..nf)
                .filter(|&f| p.kind[f] == k)
                .map(FragmentId::from_usize)
                .collect()
        };
        let roots = of_kind(FragmentKind::Root);
        let drains = of_kind(FragmentKind::Drain);
        Ok(Mt {
            positions: p.positions,
            point_data: p.point_data,
            tets: p.tets,
            cell_data: p.cell_data,
            arc_start: p.arc_start,
            arc_destroyer,
            kind: p.kind,
            error: p.error,
            info: p.info,
            level,
            frame,
            bbox,
            out_start,
            preds,
            roots,
            drains,
        })
    }

    // ---- vertex pool ----

    pub fn nb_vertices(&self) -> usize {
        self.positions.len()
    }

    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    #[inline]
    pub fn position(&self, v: VertexId) -> DVec3 {
        self.positions[v.idx()]
    }

    /// Per-vertex attributes, one row per pool vertex (the input's point data).
    pub fn point_data(&self) -> &Attributes {
        &self.point_data
    }

    // ---- tet pool ----

    /// Tets in the pool: every level, ghosts included.
    pub fn nb_tets(&self) -> usize {
        self.tets.len()
    }

    pub fn tets(&self) -> &[Tet] {
        &self.tets
    }

    #[inline]
    pub fn tet(&self, t: TetId) -> Tet {
        self.tets[t.idx()]
    }

    /// Whether `t` is a ghost tet (a boundary triangle joined to [`GHOST`]).
    #[inline]
    pub fn is_ghost(&self, t: TetId) -> bool {
        self.tets[t.idx()][3] == GHOST
    }

    /// Per-tet attributes, one row per pool tet (inherited from the input's cell data; 0 on
    /// ghosts, which are never extracted).
    pub fn cell_data(&self) -> &Attributes {
        &self.cell_data
    }

    // ---- arcs ----

    pub fn nb_arcs(&self) -> usize {
        self.arc_destroyer.len()
    }

    /// Every arc as (arc, creator, destroyer), in arc order (by creator, then destroyer).
    pub fn arcs(&self) -> impl Iterator<Item = (usize, FragmentId, FragmentId)> + '_ {
        (0..self.nb_fragments()).flat_map(move |f| {
            (self.out_start[f]..self.out_start[f + 1]).map(move |a| {
                (
                    a as usize,
                    FragmentId::from_usize(f),
                    self.arc_destroyer[a as usize],
                )
            })
        })
    }

    /// The arc from `c` to `d`, if any (binary search among `c`'s out-arcs).
    #[inline]
    pub fn arc_between(&self, c: FragmentId, d: FragmentId) -> Option<usize> {
        arc_between(&self.out_start, &self.arc_destroyer, c.0, d.0).map(|a| a as usize)
    }

    /// The pool tets of arc `a` (contiguous).
    #[inline]
    pub fn arc_tets(&self, a: usize) -> Range<usize> {
        self.arc_start[a] as usize..self.arc_start[a + 1] as usize
    }

    /// The creator of arc `a` (binary search over the creators' arc ranges; where the
    /// creator is at hand, iterate [`Mt::out_arcs`] or [`Mt::arcs`] instead).
    pub fn arc_creator(&self, a: usize) -> FragmentId {
        FragmentId((self.out_start.partition_point(|&s| s <= a as u32) - 1) as u32)
    }

    #[inline]
    pub fn arc_destroyer(&self, a: usize) -> FragmentId {
        self.arc_destroyer[a]
    }

    /// The arc holding tet `t` (binary search over the arc starts).
    pub fn tet_arc(&self, t: TetId) -> usize {
        self.arc_start.partition_point(|&s| s <= t.0) - 1
    }

    /// The fragment that created tet `t`.
    pub fn tet_creator(&self, t: TetId) -> FragmentId {
        self.arc_creator(self.tet_arc(t))
    }

    /// The fragment that destroys tet `t`.
    pub fn tet_destroyer(&self, t: TetId) -> FragmentId {
        self.arc_destroyer[self.tet_arc(t)]
    }

    // ---- fragments ----

    pub fn nb_fragments(&self) -> usize {
        self.kind.len()
    }

    #[inline]
    pub fn fragment_kind(&self, f: FragmentId) -> FragmentKind {
        self.kind[f.idx()]
    }

    /// The fragment's error: at least the errors of the fragments it depends on; 0 for
    /// roots, +∞ for drains.
    #[inline]
    pub fn fragment_error(&self, f: FragmentId) -> f64 {
        self.error[f.idx()]
    }

    /// Length of the longest path from a root to `f` (roots: 0).
    #[inline]
    pub fn fragment_level(&self, f: FragmentId) -> u32 {
        self.level[f.idx()]
    }

    /// Bounding box of the fragment's floor and ceiling (ghost vertex excluded).
    #[inline]
    pub fn fragment_bbox(&self, f: FragmentId) -> Aabb {
        self.frame.expand(self.bbox[f.idx()])
    }

    /// Arcs leaving `f`: its ceiling, grouped by the fragment that destroys each part.
    #[inline]
    pub fn out_arcs(&self, f: FragmentId) -> ArcList<'_> {
        ArcList::Range(self.out_start[f.idx()]..self.out_start[f.idx() + 1])
    }

    /// The DAG as flat tables: `out_start` (the arcs fragment `f` creates are
    /// `out_start[f]..out_start[f + 1]`), each arc's destroyer, and each fragment's level;
    /// copies, for an editor that consumes the MT and still asks about the DAG before
    /// the edit.
    /// The fragments `f` depends on: the creators of its in-arcs, one per arc, sorted.
    #[inline]
    pub fn predecessors(&self, f: FragmentId) -> ArcList<'_> {
        self.preds.row(f.idx())
    }

    /// Arcs entering `f`: its floor, grouped by the fragment that created each part (in
    /// the order of [`Mt::predecessors`]).
    pub fn in_arcs(&self, f: FragmentId) -> impl Iterator<Item = u32> + '_ {
        // Every predecessor has its arc: both lists come from the same arcs in `assemble`.
        self.preds
            .row(f.idx())
            .into_iter()
            .filter_map(move |c| arc_between(&self.out_start, &self.arc_destroyer, c, f.0))
    }

    /// The tets `f` creates (its ceiling), ghosts included.
    pub fn created_tets(&self, f: FragmentId) -> impl Iterator<Item = TetId> + '_ {
        self.out_arcs(f)
            .into_iter()
            .flat_map(|a| self.arc_tets(a as usize).map(TetId::from_usize))
    }

    /// The tets `f` destroys (its floor), ghosts included.
    pub fn destroyed_tets(&self, f: FragmentId) -> impl Iterator<Item = TetId> + '_ {
        self.in_arcs(f)
            .flat_map(|a| self.arc_tets(a as usize).map(TetId::from_usize))
    }

    /// The fragments creating the full-resolution meshes (one per independent MT).
    pub fn roots(&self) -> &[FragmentId] {
        &self.roots
    }

    /// The fragments destroying the coarsest meshes (one per independent MT).
    pub fn drains(&self) -> &[FragmentId] {
        &self.drains
    }

    /// Number of independent MTs held in this store: the weakly connected components of
    /// the DAG ([`Mt::fragment_components`]; extract one with [`Mt::component`]).
    pub fn nb_components(&self) -> usize {
        self.fragment_components().0
    }

    /// The longest root-to-drain path.
    pub fn dag_depth(&self) -> u32 {
        self.drains
            .iter()
            .map(|d| self.level[d.idx()])
            .max()
            .unwrap_or(0)
    }

    pub fn info(&self) -> &MtInfo {
        &self.info
    }

    /// Number of non-ghost tets in the floors of the drains: the coarsest mesh's size.
    pub fn coarsest_tets(&self) -> usize {
        self.drains
            .iter()
            .flat_map(|&d| self.destroyed_tets(d))
            .filter(|&t| !self.is_ghost(t))
            .count()
    }

    /// Bytes of heap memory held by this MT (capacities, so what the allocator gave).
    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of;
        let attrs = |a: &Attributes| -> usize {
            a.iter()
                .map(|c| c.values.capacity() * 8 + c.name.capacity())
                .sum()
        };
        self.positions.capacity() * size_of::<DVec3>()
            + attrs(&self.point_data)
            + self.tets.capacity() * size_of::<Tet>()
            + attrs(&self.cell_data)
            + self.arc_start.capacity() * 4
            + self.arc_destroyer.capacity() * 4
            + self.kind.capacity() * size_of::<FragmentKind>()
            + self.error.capacity() * 8
            + self.info.error_metric.capacity()
            + self.info.cuts.heap_bytes()
            + self.level.capacity() * 4
            + self.bbox.capacity() * size_of::<QuantBox>()
            + self.out_start.capacity() * 4
            + self.preds.heap_bytes()
            + (self.roots.capacity() + self.drains.capacity()) * 4
    }

    /// The numbers `mtcut info` prints.
    pub fn summary(&self) -> MtSummary {
        let ghosts = self.tets.iter().filter(|t| t[3] == GHOST).count();
        let max_error = self
            .error
            .iter()
            .copied()
            .filter(|e| e.is_finite())
            .fold(0.0, f64::max);
        let min_error = (0..self.nb_fragments())
            .filter(|&f| self.kind[f] == FragmentKind::Collapse)
            .map(|f| self.error[f])
            .reduce(f64::min)
            .unwrap_or(0.0);
        let finest_tets = self
            .roots()
            .iter()
            .flat_map(|&r| self.created_tets(r))
            .filter(|&t| !self.is_ghost(t))
            .count();
        let bytes = self.heap_bytes();
        MtSummary {
            vertices: self.nb_vertices(),
            pool_tets: self.nb_tets() - ghosts,
            ghost_tets: ghosts,
            arcs: self.nb_arcs(),
            fragments: self.nb_fragments(),
            components: self.nb_components(),
            dag_depth: self.dag_depth(),
            input_tets: self.info.input_tets,
            finest_tets,
            coarsest_tets: self.coarsest_tets(),
            min_error,
            max_error,
            heap_bytes: bytes,
            bytes_per_input_tet: bytes as f64 / self.info.input_tets.max(1) as f64,
            bbox: Aabb::from_points(&self.positions),
            info: self.info.clone(),
        }
    }
}

/// A fragment's bounding box, 16 bits per coordinate on the MT's [`BoxFrame`], rounded
/// outwards so it still contains what the double-precision box contained: 12 bytes instead
/// of 48. Fragment boxes only steer region queries and the search for the fragments a cut
/// meets, which a box larger by 1/65535 of the model does not change in practice; at a
/// few hundred thousand fragments their size matters (the MT's memory budget is 100
/// bytes per input tet).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct QuantBox {
    min: [u16; 3],
    max: [u16; 3],
}

impl QuantBox {
    /// A box holding nothing (a fragment without real vertices).
    const EMPTY: QuantBox = QuantBox {
        min: [u16::MAX; 3],
        max: [0; 3],
    };
}

/// The box of every vertex of an MT, divided into 65535 steps per axis (the last step
/// reaching at least to its far side).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct BoxFrame {
    min: DVec3,
    step: DVec3,
}

impl BoxFrame {
    const STEPS: u16 = u16::MAX;

    fn of(positions: &[DVec3]) -> BoxFrame {
        let b = Aabb::from_points(positions);
        if b.is_empty() {
            return BoxFrame::default();
        }
        let mut step = (b.max - b.min) / f64::from(Self::STEPS);
        for axis in 0..3 {
            // One expression decodes every coordinate (no branch for the far end): the
            // last step must reach the far side despite rounding.
            while b.min[axis] + f64::from(Self::STEPS) * step[axis] < b.max[axis] {
                // The next larger double (step > 0 here: the axis is not flat).
                step[axis] = f64::from_bits(step[axis].to_bits() + 1);
            }
        }
        BoxFrame { min: b.min, step }
    }

    /// Coordinate `q` on `axis`.
    #[inline]
    fn at(&self, axis: usize, q: u16) -> f64 {
        self.min[axis] + f64::from(q) * self.step[axis]
    }

    /// The smallest quantised box containing `b` (which lies in the frame).
    pub(crate) fn enclose(&self, b: &Aabb) -> QuantBox {
        if b.is_empty() {
            return QuantBox::EMPTY;
        }
        let guess = |axis: usize, x: f64| -> u16 {
            let step = self.step[axis];
            let t = if step > 0.0 {
                (x - self.min[axis]) / step
            } else {
                0.0
            };
            // `as` saturates (NaN to 0); the loops below settle the rest.
            t.clamp(0.0, f64::from(Self::STEPS)) as u16
        };
        let mut out = QuantBox::EMPTY;
        for axis in 0..3 {
            // The guess is off by at most a step of rounding; the loops settle it with the
            // very arithmetic `expand` uses, so the result encloses `b` exactly.
            let (lo, hi) = (b.min[axis], b.max[axis]);
            let mut q = guess(axis, lo);
            while q > 0 && self.at(axis, q) > lo {
                q -= 1;
            }
            out.min[axis] = q;
            let mut q = guess(axis, hi);
            while q < Self::STEPS && self.at(axis, q) < hi {
                q += 1;
            }
            out.max[axis] = q;
        }
        out
    }

    pub(crate) fn expand(&self, q: QuantBox) -> Aabb {
        if q == QuantBox::EMPTY {
            return Aabb::EMPTY;
        }
        // Component-wise, the arithmetic of `at`.
        let at = |q: [u16; 3]| self.min + DVec3::from_array(q.map(f64::from)) * self.step;
        Aabb {
            min: at(q.min),
            max: at(q.max),
        }
    }
}

/// The arc from `c` to `d`: `c`'s out-arcs are a range sorted by destroyer.
fn arc_between(out_start: &[u32], arc_destroyer: &[FragmentId], c: u32, d: u32) -> Option<u32> {
    let (lo, hi) = (out_start[c as usize], out_start[c as usize + 1]);
    arc_destroyer[lo as usize..hi as usize]
        .binary_search_by_key(&d, |x| x.0)
        .ok()
        .map(|k| lo + k as u32)
}

/// Levels (longest path from a root) by Kahn's algorithm; `None` when the arcs have a cycle.
fn levels(nf: usize, preds: &Csr) -> Option<Vec<u32>> {
    // Successor lists, built here from the predecessors to stay independent of the MT's
    // out-arcs (`validate` checks those against each other).
    let out = Csr::from_pairs(
        nf,
        (0..nf as u32).flat_map(|f| preds.row(f as usize).into_iter().map(move |c| (c, f))),
    );
    levels_with(nf, preds, |f| out.row(f))
}

/// [`levels`] with the successors of each fragment given (each once, as many as the
/// fragments it appears in the predecessor lists of).
/// The first tet (and its vertex) that names no vertex of a pool of `nv` (a ghost's fourth
/// vertex excepted). A pass over every tet of the pool each time an MT is assembled: in
/// blocks on both cores, each block checked without a branch per vertex.
fn first_bad_vertex(tets: &[Tet], nv: usize) -> Option<(usize, VertexId)> {
    const BLOCK: usize = 1 << 14;
    let n = nv as u64;
    let bad = |t: &Tet| {
        (t[0].0 as u64 >= n)
            | (t[1].0 as u64 >= n)
            | (t[2].0 as u64 >= n)
            | ((t[3].0 as u64 >= n) & (t[3] != GHOST))
    };
    let block = tets
        .par_chunks(BLOCK)
        .position_first(|b| b.iter().fold(false, |acc, t| acc | bad(t)))?;
    let t = block * BLOCK + tets[block * BLOCK..].iter().position(bad)?;
    Some((t, bad_vertex(&tets[t], nv)?))
}

/// The vertex of `tet` that names no vertex of a pool of `nv`, if any (a ghost's fourth
/// vertex excepted).
pub(crate) fn bad_vertex(tet: &Tet, nv: usize) -> Option<VertexId> {
    (0..4)
        .find(|&k| !(tet[k].idx() < nv || (tet[k] == GHOST && k == 3)))
        .map(|k| tet[k])
}

fn levels_with<I: IntoIterator<Item = u32>>(
    nf: usize,
    preds: &Csr,
    out: impl Fn(usize) -> I,
) -> Option<Vec<u32>> {
    let mut pending: Vec<u32> = (0..nf).map(|f| preds.row(f).len() as u32).collect();
    let mut level = vec![0u32; nf];
    let mut ready: Vec<u32> = (0..nf as u32)
        .filter(|&f| pending[f as usize] == 0)
        .collect();
    let mut done = 0;
    while let Some(f) = ready.pop() {
        done += 1;
        for g in out(f as usize) {
            let g = g as usize;
            level[g] = level[g].max(level[f as usize] + 1);
            pending[g] -= 1;
            if pending[g] == 0 {
                ready.push(g as u32);
            }
        }
    }
    (done == nf).then_some(level)
}

/// What `mtcut info` prints about an MT (see [`MtSummary::to_json`]).
#[derive(Clone, Debug, PartialEq)]
pub struct MtSummary {
    pub vertices: usize,
    /// Non-ghost tets in the pool (all levels).
    pub pool_tets: usize,
    pub ghost_tets: usize,
    pub arcs: usize,
    /// Fragments, root and drain included.
    pub fragments: usize,
    pub components: usize,
    pub dag_depth: u32,
    pub input_tets: usize,
    /// Tets of the finest mesh (the input's, plus what cuts made of them) and of the
    /// coarsest.
    pub finest_tets: usize,
    pub coarsest_tets: usize,
    /// Smallest error of a simplification step (0 when there is none): thresholds below it
    /// extract the finest mesh.
    pub min_error: f64,
    /// Largest finite fragment error: thresholds at or above it extract the coarsest mesh.
    pub max_error: f64,
    pub heap_bytes: usize,
    pub bytes_per_input_tet: f64,
    pub bbox: Aabb,
    pub info: MtInfo,
}

impl MtSummary {
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "vertices": self.vertices,
            "pool_tets": self.pool_tets,
            "ghost_tets": self.ghost_tets,
            "arcs": self.arcs,
            "fragments": self.fragments,
            "components": self.components,
            "dag_depth": self.dag_depth,
            "input_tets": self.input_tets,
            "finest_tets": self.finest_tets,
            "coarsest_tets": self.coarsest_tets,
            "min_error": self.min_error,
            "max_error": self.max_error,
            "heap_bytes": self.heap_bytes,
            "bytes_per_input_tet": self.bytes_per_input_tet,
            "bbox": [self.bbox.min.to_array(), self.bbox.max.to_array()],
            "error_metric": self.info.error_metric,
            "boundary_tolerance": self.info.boundary_tolerance,
            "preserve_features": self.info.preserve_features,
            "feature_angle_degrees": self.info.feature_angle_degrees,
            "cut_vertices_from": self.info.cuts.cut_vertices_from(),
            "cuts_recorded": self.info.cuts.cuts_kept(),
            "crack_planes": self.info.cuts.planes_kept(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantised_boxes_enclose_and_stay_within_a_step() {
        let pts = [
            DVec3::new(-3.0, 1e6, 0.1),
            DVec3::new(7.5, 1e6 + 0.25, 0.1 + 1e-9),
        ];
        let frame = BoxFrame::of(&pts);
        let whole = Aabb::from_points(&pts);
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut unit = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..10_000 {
            let p =
                |u: f64, v: f64, w: f64| whole.min + (whole.max - whole.min) * DVec3::new(u, v, w);
            let (a, b) = (p(unit(), unit(), unit()), p(unit(), unit(), unit()));
            let b = Aabb {
                min: a.min(b),
                max: a.max(b),
            };
            let q = frame.enclose(&b);
            let e = frame.expand(q);
            assert!(
                e.min.cmple(b.min).all() && e.max.cmpge(b.max).all(),
                "{b:?} -> {e:?}"
            );
            let slack = (whole.max - whole.min) / 65535.0 * 1.001;
            assert!((b.min - e.min).cmple(slack).all() && (e.max - b.max).cmple(slack).all());
        }
        // The frame's own box (to within rounding of its far side), a point, nothing.
        let e = frame.expand(frame.enclose(&whole));
        assert!(e.min == whole.min && e.max.cmpge(whole.max).all());
        assert!(
            (e.max - whole.max)
                .cmple((whole.max - whole.min) * 1e-12)
                .all()
        );
        let point = Aabb {
            min: pts[1],
            max: pts[1],
        };
        let e = frame.expand(frame.enclose(&point));
        assert!(e.min.cmple(point.min).all() && e.max.cmpge(point.max).all());
        assert!(frame.expand(frame.enclose(&Aabb::EMPTY)).is_empty());
        // A frame flat in one axis (all boxes span it).
        let flat = BoxFrame::of(&[DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0)]);
        let q = flat.enclose(&Aabb {
            min: DVec3::new(0.25, 0.5, 0.0),
            max: DVec3::new(0.5, 0.75, 0.0),
        });
        let e = flat.expand(q);
        assert!(e.min.z <= 0.0 && e.max.z >= 0.0);
    }
}
