//! Cutting tetrahedral meshes with planar convex polygons (paper §3–§4).
//!
//! This layer owns the cut of tets: classification against a [`CutPolygon`], the split
//! tables and their generator, the replacement of cut tets, the separation of the sides,
//! the 1:17 baseline, and — for a plain [`TetMesh`] — the acceleration structure and the
//! connected components. It builds on `geom` (every sign is an exact predicate there) and
//! `mesh`; neither of those, nor `mt`, imports it. Its core ([`CutSession`],
//! [`split::split_tet`]) works on tets given as global vertex ids over a shared, appendable
//! vertex pool, so the MT layer can apply it to every level of detail.
//!
//! # The cut, step by step (paper §3)
//!
//! 1. **Candidates** ([`bvh`]): the tets whose vertices straddle C's plane or touch the cut,
//!    found through a hierarchy over tets that lives with the mesh; cuts only put children
//!    inside their parents, so it is never refitted. Cost: proportional to the tets near
//!    the plane, not to the mesh.
//! 2. **Classify** ([`classify`]), each element once: every vertex gets a state — `ON` when
//!    snapped onto the cut, else its exact side; every crossed edge is cut or not (exactly:
//!    does the segment cross the plane strictly inside C) with its crossing parameter;
//!    every face whose section segment has one end in C and one out gets a face point (the
//!    crack tip). Records are keyed by global vertex ids, so all tets sharing an edge or a
//!    face, in any number of batches, share its points. New vertices get ids in a canonical
//!    order (cut edges by id pair, then faces by id triple), whatever the processing order.
//! 3. **Split** ([`split`], [`tables`]): each cut tet, its vertices sorted by id, is looked
//!    up by configuration (vertex states and cut edges) in tables made by a program in the
//!    repository ([`table_gen`], checked by `tests/cut_tables.rs`) and replaced by their
//!    children, each knowing its side of the cut.
//! 4. **Separate** ([`unglue`]): vertices snapped onto the cut get one copy per group of
//!    tets around them that the cut surface separates (below).
//!
//! [`Cutter`] does all of this on one [`TetMesh`], keeping the hierarchy between cuts;
//! [`cut_mesh`] is the one-shot form. [`Components`] extracts the parts as meshes.
//!
//! # Tolerances
//!
//! Signs are exact. Closeness is relative to each vertex's *scale*, its longest incident
//! edge ([`vertex_scales`]; vertices made by cuts take the largest scale they are made
//! from). A vertex within `snap × scale` of the plane whose projection is within that
//! distance of C is snapped: the cut passes through it. So every cut point divides its edge
//! at a parameter in (`snap`, 1 − `snap`), and no child is a sliver of a near-miss. The
//! price is a cut surface that may pass up to `snap × scale` off the plane (no vertex
//! moves: volumes are exact). Face points are placed so they stay within the same distance
//! of the plane. The default `snap` (0.2) and face-point placement come from the quality
//! targets; see [`CutOptions`] for the numbers.
//!
//! # Which vertices are duplicated
//!
//! * A **cut point** (on an edge crossed strictly inside C) always has two copies, one per
//!   side: C is a full disk around it, so the tets around its edge are all split there.
//! * A **face point** never has: it is the crack tip (paper Fig. 4c–e).
//! * A **snapped vertex** is an original vertex the cut passes through. Every tet the plane
//!   crosses at it has it inside its crack polygon, so the tables split that tet and no
//!   child straddles there; every tet around the vertex is then on one side. The vertex gets
//!   one copy per group of tets around it connected through faces *not* on the cut surface
//!   (a face between a positive and a negative tet is on it). The group holding positive
//!   tets keeps the id. For an interior vertex the groups are exactly the two sides (the
//!   cut faces around it form one closed curve on its link sphere); a boundary vertex may
//!   have two groups on one side. A group whose link is not a disk (an annulus: a boundary
//!   vertex snapped onto a plane running just above the boundary, the layer between them
//!   pinched to a point) cannot be separated by copies: such a vertex is left unsnapped
//!   and the tets around it planned again ([`Cutter::cut`]); its cut points then keep
//!   `snap` away from it.
//!
//! ## For the Multi-Tessellation ([`mt_cut`])
//!
//! The same vertex is used by tets of several levels, so its duplication must be decided
//! once, for all of them. The engine gives what that needs: [`CutSession`] (classification
//! cached per vertex, edge and face across batches; provisional ids until
//! [`CutSession::allocate`]; [`CutSession::forget_vertices`] to unsnap), a vertex's state
//! from positions alone ([`classify::StateClassifier`]), children with their side and their
//! snapped vertices ([`split::Children`]), and every new vertex's linear combination
//! ([`VertexOrigin`]: edge point `(a, b, t)`, face point `(a, b, c, w)`, copy of `v`), which
//! also interpolates attributes and maps the cut surface between rest and deformed
//! positions. The rule this module's analysis supports: a snapped vertex gets one copy per
//! side — positive tets keep the vertex, negative tets of every level use its one negative
//! copy — which is exactly the grouping above for interior vertices on every level; a
//! snapped boundary vertex whose groups on some level are not one disk per side is
//! unsnapped, for all levels, before ids are allocated (run [`unglue::plan_copies`] on each
//! level's star). The 1:17 scheme is not meant for the MT.
//!
//! [`roi`] makes region-of-interest sub-MTs with the MT cut (paper §7).

pub mod bielser;
pub mod bvh;
pub mod classify;
pub mod components;
pub mod cutter;
pub mod live;
pub mod mt_cut;
pub mod options;
mod pockets;
mod prefetch;
pub mod report;
pub mod roi;
pub mod scalpel;
pub mod split;
mod stamps;
pub mod table_gen;
pub mod tables;
pub mod unglue;

pub use classify::{CrackTips, CutScratch, CutSession, TetClass, VertexOrigin};
pub use components::{Components, InvalidBodies};
pub use cutter::{CUT_COLUMN, Cutter, RETRY_SNAP, cut_mesh, vertex_scales};
pub use live::{LiveCut, LiveError, LiveMt, PendingBudget, PendingReport};
pub use mt_cut::{MtCutStats, MtCutTimes, MtCutter};
pub use options::{CutError, CutOptions, MIN_FACE_POINT_MARGIN, MIN_SNAP, Scheme};
pub use report::{CutResult, CutStats, CutTimes, SplitRecord};
pub use roi::{RoiError, RoiRegion, RoiStats, region_of_interest};
pub use scalpel::{Blade, Incision, Scalpel, ScalpelError, ScalpelStep, blade_advance};
pub use tables::{CutCase, Side};

#[cfg(doc)]
use crate::geom::CutPolygon;
#[cfg(doc)]
use crate::mesh::TetMesh;
