//! Cutting a Multi-Tessellation (paper §3): every level of detail and the DAG.
//!
//! [`MtCutter`] owns an [`Mt`] and cuts it with planar convex polygons. After a cut, every
//! mesh extracted from the MT — any threshold, any focus region — is cut by the polygon,
//! and a body cut straight through becomes independent MTs in the same store
//! ([`Mt::nb_components`], [`Mt::component`]).
//!
//! # The three steps
//!
//! 1. **Candidates, over all levels.** Every tet of the pool (not only a frontier) that C
//!    may cross: fragments are found through a hierarchy over their boxes
//!    ([`crate::mt::FragmentBvh`], built with the cutter) against C's box and plane, then
//!    the tets each fragment creates (every tet has exactly one creator, so each is met
//!    once) are tested by their box and vertex states, as the plain-mesh engine does
//!    ([`super::classify`]). The root, whose box is the whole body, is not searched
//!    tet by tet: each tet it creates lies in the floor of the fragment destroying it, so
//!    it is reached through that fragment's box (or, kept to the coarsest mesh, through
//!    the drain). Fragment boxes are re-derived by [`OpenMt::close`] after each cut, and
//!    only shrink (children lie inside their parents), so the hierarchy built once stays
//!    conservative; a fragment a cut splits off is found through its origin's entry.
//! 2. **Replace, with one classification for the whole pool.** All candidates of all
//!    levels go to one [`CutSession`]: its records are keyed by global vertex ids, so an
//!    edge or a face shared by tets of several levels gets one cut point (one per side)
//!    and one face point, and every tet is split by the engine's tables
//!    ([`super::split::split_tet`]; no second split implementation). Vertex states, hence
//!    snapping, depend on the position and the vertex's scale only: one decision per
//!    vertex for all levels. Scales are the longest incident edge in the *finest* mesh
//!    (every pool vertex is in it when the MT is built; vertices made by cuts take the
//!    largest scale of the vertices they are made of), as the plain-mesh engine would have
//!    them there: scales over all levels would snap whole fine tets onto the cut, with
//!    a crack surface far off the plane. The price: on coarse edges, longer than the
//!    scale, a cut point may lie closer to an end than `snap` of the edge, so coarse
//!    levels may get thinner children than the finest one (orientation is still checked
//!    exactly by `Mt::validate`).
//!
//!    With the MT's `snap` (at most [`MAX_MT_SNAP`], default 1e-6), "snapped" means on
//!    the plane up to rounding: degenerate cuts (through vertices, along edges and faces).
//!
//!    **A cut continuing an earlier one in its plane** (a blade swept in steps, each
//!    step cutting the quadrilateral it swept, an incision extended, or a second one in
//!    the plane of the first) meets the earlier crack's vertices on its plane: its tips
//!    (face points, which the face-point margin keeps off the earlier contour) on the new
//!    polygon's contour, and the lips behind it. Three rules keep every level consistent
//!    there. A vertex on the plane within a *contour band* outside C (twice the
//!    face-point margin, at most 5% of the vertex's scale: `contour_band`) counts as on
//!    the cut, so the earlier tips join the crack and are duplicated once surrounded by
//!    it, instead of being met by new tips a rounding error away. A vertex of an earlier
//!    crack ([`MtCutter::crack_vertices`]) on the plane up to rounding farther outside C
//!    is on neither side ([`OUT`]) when the cut lies in the plane of an earlier crack
//!    (`continues_a_crack_plane`; elsewhere such vertices lie on the line where another
//!    crack meets this plane and keep their sides): no edge at it is crossed and no face with two
//!    vertices on the plane holds a face point, so the two lips and the tips they share
//!    see the same faces alike; with their exact sides, rounding noise, a lip
//!    face next to a snapped vertex got a face point where the other lip's face, at the
//!    same place, did not (tests/mt_scalpel.rs, the T and X incisions). Any other vertex
//!    within snapping distance of the plane outside C is not cut; it takes the side of the
//!    other vertices of its tets when those all lie on one side (one decision per cluster
//!    of such vertices joined by edges), so a lip tet is not taken for a tet C crosses and
//!    split into children lying flat between the lips (`settle_plane_vertices`;
//!    tests/mtcut_cut.rs, `a_blade_swept_across_the_mt_stays_valid`).
//!
//!    **Which snapped vertices are duplicated** is decided once per vertex over all
//!    levels: a vertex the cut passes through gets one copy, used by the negative tets of
//!    every level, when tets of both sides surround it and none of its tets, on any level,
//!    straddles the cut there (a straddling tet is a crack tip: a partial cut ends at that
//!    vertex on some level, so the vertex stays shared). Cut points have their two copies
//!    from the engine; face points are tips and never copied.
//!
//!    **Ghost tets** (the MT's closure of each level's boundary, see [`crate::mt`]) follow
//!    their triangle: a ghost whose boundary triangle the cut subdivides is replaced by one
//!    ghost per sub-triangle (the faces of the adjacent tet's children that lie in it), on
//!    the side of its child; a ghost touching a duplicated vertex takes the copy of its
//!    side. The crack surface is new boundary: every face of a new tet that no tet or
//!    ghost of the pool matches gets a ghost with the tet's creator and destroyer, so each
//!    fragment's floor and ceiling, ghosts included, keep the same boundary.
//! 3. **The DAG.** Each new tet inherits its parent's creator and destroyer. Then the
//!    floor and ceiling of each fragment involved (tets, ghosts included) are split into
//!    local parts, joined through shared vertices (and a part found on one level only —
//!    a piece cut free inside the fragment — joined with the parts of the other level
//!    occupying the same space). A fragment is involved when the cut changed one of its
//!    tets, or when it is *cracked*: an earlier cut left it in several parts that one
//!    body joined through other fragments (a crack ending inside the body). The cut that
//!    finally separates that body may touch none of its tets — a blade swept in steps
//!    separates it at the last step, far from the first ones — so cracked fragments
//!    (remembered by the cutter, found again when it is created) take part in every cut
//!    that leaves a root in several parts. A cut that leaves every root one part (a crack
//!    ending inside the body: its lips meet at its tips) separates nothing — every part
//!    has floor tets, whose creators' parts have theirs, down to a root's ceiling — and
//!    the cracked fragments it did not touch are left out (on a blade swept in 100 steps
//!    across fandisk, about 80 fragments involved at the median step instead of about
//!    460, the DAG step's median 40–43 ms → 20–24 ms). Parts are then grouped by *body*:
//!    the parts and the untouched fragments joined through the tets between them (the
//!    arcs; those between untouched fragments are followed only when the tets of the
//!    involved fragments leave some fragment's parts apart, as a cut separating the body
//!    does). A fragment
//!    whose parts lie in `k` bodies becomes `k` fragments (the first keeps its id, the
//!    others are appended with its kind and error), each creating and destroying the tets
//!    of its parts. The paper's `UpdateIncomingArcs` / `UpdateOutgoingArcs` are this
//!    relabelling seen from the arcs: arcs are re-derived from the tets' creators and
//!    destroyers when the MT is closed. Processing a fragment reads only its own tets and
//!    writes only their links to it, so any order gives the same MT
//!    ([`MtCutter::cut_in_order`] lets tests check this).
//!
//!    A root is the exception that keeps a small cut of a large MT small: its ceiling is
//!    a whole finest mesh. When it was one part and the tets the cut made of its own form
//!    one piece (a crack ending inside the body: the lips meet at its tips, which are
//!    never duplicated), it is still one part, and takes part like a fragment not
//!    involved, its ceiling not read. A cut separating the finest mesh splits it like
//!    the others.
//!
//!    Why by body and not by local part (the paper splits a fragment wherever C separates
//!    it): a crack ending inside the body separates the regions of the fragments it
//!    crosses locally, yet both lips belong to one body. Split there, the two lips would
//!    be separate fragments, refined independently by a focus extraction, and the lips
//!    would meet at different resolutions (the vertices of the finer lip lying inside the
//!    faces of the coarser one). Kept whole, every extraction refines both lips together
//!    and they match, as after a cut of a plain mesh. Where a cut separates the body, the
//!    parts are in different bodies and become independent MTs, as the paper's split
//!    does.
//!
//! # Limits
//!
//! * **Almost no snapping** (`snap` at most [`MAX_MT_SNAP`]; [`MtCutter::DEFAULT_OPTIONS`]
//!   has 1e-6, enough to keep cut points off the vertices' rounding, where 0 made inverted
//!   children in the tests). Snapping a vertex near the plane onto the cut bends the cut
//!   surface through it, and the side of a tet whose other vertices are all snapped is
//!   the side of its remaining vertex: two tets of different levels on the same side of a
//!   snapped triangle can then take different sides,
//!   so a fragment's floor sees the crack open at a face of its region's boundary where its
//!   ceiling sees it closed — the MT condition (floor and ceiling with the same boundary)
//!   breaks. Measured on the shared meshes with the engine's default 0.2; fixing it needs
//!   the side of such tets decided per face across levels, which is not done. Vertices
//!   exactly on the plane (degenerate cuts) are still on the cut, consistently. The price
//!   of so small a `snap` is quality: cut points can lie arbitrarily close to an edge's ends, so
//!   children can be thin (every orientation is still exact, and checked by
//!   `Mt::validate`). A cut that would make a flat child or leave a vertex hanging is
//!   planned once more with `snap` a hundred times larger, up to [`MAX_MT_SNAP`]
//!   ([`MtCutter::cut`]), where the plain-mesh engine goes on to 0.2.
//! * A vertex exactly on the cut whose tets in the finest or in the coarsest mesh do not
//!   form one group per side (the engine's *pinched* vertices and boundary saddles) is left
//!   unsnapped on every level, as the engine does on a plain mesh. The meshes between are
//!   not analysed for that decision; once the DAG is updated, every extraction's star at
//!   each vertex on the cut (and its copy) is examined, and a cut that would leave one
//!   pinched is refused (`pinched_between`, below). (Before that check, a liver's live
//!   resolution was once left pinched by a fold's fallback cut, [`super::live`], which also
//!   pinched the coarsest mesh before it was analysed; that polygon, close to an earlier
//!   cut's plane, is now cut in that plane, and valid.)
//! * A crack continued in its plane reaching a vertex of an earlier crack in another plane,
//!   on this cut's plane just outside C (`OUT`: such a vertex is not cut), can divide that
//!   vertex's tets on one lip and pinch the finest or the coarsest mesh there. The cut is
//!   then refused ([`CutError::MtInconsistent`], before the MT changes); the plain-mesh
//!   engine, given the same cuts, ends that crack short of the vertex. Found by random
//!   partial cuts through the vertices of a Kuhn grid (tests/mtcut_cut.rs).
//! * A cut whose points lie nearly on one line where it meets an earlier crack's tips
//!   (a Kuhn grid's cracks, whose tips lie a face-point margin off their planes) can put
//!   one of them inside a coarse crack face: a hanging vertex in the finest or the
//!   coarsest mesh, which the fragments' floors and ceilings do not show. The cut looks
//!   for one among the faces it wrote on those two meshes and the vertices it made
//!   (`Changed::hanging`) and is refused if it finds one. The meshes between them are not
//!   examined (nor does `Mt::validate` examine them).
//! * Closing the MT after a cut (the pool merged back into arcs after a read-only check
//!   of its order, levels and arc lists derived again, the vertex ids of every tet
//!   checked) costs time in proportion to the pool and the DAG, not to the cut: the DAG
//!   step of a cut of 76 cells on the fandisk-1m MT (3.8 M pool tets) took 30–47 ms. So
//!   do grouping parts by body when a cut separates them (a pass over the DAG's arcs), a
//!   cut that separates a finest mesh (its root's ceiling is read), and counting the
//!   components after a cut that splits fragments. What the first cut would also pay in
//!   proportion to the pool is paid when the cutter is made ([`MtCutter::new`]): the open
//!   form's creator and destroyer per pool tet (kept from cut to cut: 8 bytes per pool
//!   tet) and room for an eighth more tets and vertices in the pool (kept by each close),
//!   so appending does not copy it. Measured in `benches/table2.rs`.
//! * Every level is cut, so the pool grows with every cut by several tets per tet cut on
//!   every level (the tests' 50 random cuts through fandisk take its pool from 0.15 M to
//!   5.9 M tets).
//! * The contour band extends a crack beyond C by up to 5% of an edge, where vertices lie
//!   on C's plane just outside it (also on a fresh mesh cut through its vertices).
//! * A crack follows C up to a tet's size near C's contour (the tips, as on a plain
//!   mesh): a later cut can cross an earlier polygon in that band.
//! * **A cut close to an earlier crack's plane is made in that plane.** A polygon whose
//!   corners all lie within [`PLANE_SNAP`] (1e-5) of the model's bounding-box diagonal from
//!   the plane of a crack an earlier cut at rest made (the record keeps each such plane
//!   once, in the `.mt` file too, however many cuts followed), its normal
//!   within [`PLANE_SNAP_ANGLE`](crate::geom::PLANE_SNAP_ANGLE) of that plane's, and not in
//!   it already (to 1e-9), is projected onto that plane before anything is decided
//!   ([`MtCutStats::moved_to_plane`]; the corners move by at most that distance). Such a
//!   polygon meets the earlier crack's lips and tips on either side of its plane by
//!   amounts below any snapping distance, which the levels decided differently: measured,
//!   a second band overlapping a partial first one, offset by 1e-12 to 1e-5 of the
//!   diagonal and tilted by 1e-9 to 1e-5, in three planes through the three shared meshes,
//!   was refused in 52 of 180 cases; in none once moved (and with eight cuts elsewhere
//!   between the two bands, 12 of 60 were refused while only the last eight cuts' planes
//!   were kept; none now). Snapping the crack's vertices
//!   onto the new plane instead (within 1e-5 or 1e-4 of their scale) was refused more. A
//!   cut of a deformed body (`cut_deformed`) is not moved here: the live model moves its
//!   polygons where they were given ([`super::live`]).
//! * **Two cracks meeting at an angle: handled where the levels agree, refused elsewhere.**
//!   A step at an angle to the last (a turning path; a tilting blade, whose sweeps are two
//!   triangles) begins on the line where the last crack ended, and that crack's tips on
//!   the line lie on both planes. Around such a tip the two cracks together, not the new
//!   plane, divide the tets: into the convex wedge between them and the rest. When a cut's
//!   polygon shares an edge with one of the last cuts at rest at an angle (`Made`, kept
//!   in the MT's cut record: a cutter made of an MT saved and loaded reads it too), the
//!   tips that cut made within the tip reach of the new polygon
//!   ([`StateClassifier::with_crack_tips`], as the plain engine takes them) are on this
//!   cut, each gets one copy, and every tet holding it takes the copy or not by whether
//!   its corner at the tip lies in the wedge (`TurnTips`): from its side of the new cut
//!   and its vertices' sides of the earlier plane — a lip vertex of the earlier crack by
//!   the lip it is on, a tip the earlier cut itself took from the cut before it (and its
//!   copy) as on that crack, any other by its position — so every level decides alike.
//!   (Those taken tips lie up to the tip reach off the earlier plane, on its crack, which
//!   bends through them: by position, coarse and fine tets around a tip decided apart.)
//!   Tets joined through a face at the tip that lies on no crack (of any level: they
//!   meet in some extracted mesh) then keep the tip alike, a group holding tets of both
//!   kinds keeping it: near the corner where a blade ending inside the body turned, a
//!   coarse level's earlier crack ends short of the line the new polygon begins on (its
//!   tips there lie on faces cutting the corner), so tets beyond that end join the wedge
//!   to the rest, and the tip is a crack tip on that level. Where the tip is so kept whole
//!   while the finest or the coarsest mesh has cracks all around it, that mesh would be
//!   pinched there (two fans of crack faces meeting at a point, which the fragments'
//!   floors and ceilings do not show): the cut is refused before the MT changes.
//!   Measured (tests/mt_scalpel.rs; 4° and 16° in runs of other paths): an incision
//!   turning by 8° or 30° per step through the body's depth, stopped inside and extended
//!   through each shared mesh, keeps every level valid and cuts a corner off each, as the
//!   plain engine does; a blade tilting back and forth across them in 10 steps separates
//!   each; a turning blade ending inside fandisk works. Still refused: some steps at
//!   steeper angles (the same tilt in 20 steps, on the three meshes) and of a turning
//!   blade ending inside pinion or liver (a shallow incision turning by 4°, 8° and 16°
//!   per step, each refused step skipped: 2, 1 and 1 of its 17 steps on pinion, 6, 4 and
//!   2 on liver, measured again in stop 64; 1, 1, 1 and 7, 4, 2 in stop 41; 3, 1, 1 and
//!   8, 4, 2 some stops before; 5, 2
//!   and 1 on pinion before tets were joined), where one level needs a tip whole and another
//!   needs it split, which one copy per tip cannot give. Tried and dropped: deciding the
//!   copies by the groups tets form around each tip (joined through faces), the same over
//!   all levels, instead of by position — the two cracks' fronts leave slivers between
//!   them that join the groups, so tips kept no copy and the boundary was pinched at
//!   them; keeping a tip whole wherever two tets across a face on no crack decided apart
//!   (the finest mesh pinched at some, on a 20-step tilt of fandisk); counting this cut's
//!   own points as on the earlier plane (more steps refused); a taken tip as a lip of the
//!   side its tets keep (every 20-step tilt cut, but on fandisk the bodies' tets then held
//!   each other's vertices on coarser levels, and the MT stayed one component). The
//!   smallest case found: a triangle ending on a vertical line through the body, then a
//!   triangle continuing it from that line at any angle from 0.5° to 30° (continuing it
//!   in its plane is taken), is refused at 1 of 12 lines tried on pinion and 2 on liver,
//!   none on fandisk. On liver's first (4°): near the first triangle's corner a coarse
//!   tet holds tips of two of its contour edges, so one of its faces is made of three
//!   tips (in the crack's plane, inside the first triangle, never opened); it joins tets
//!   inside and outside the wedge, the tip stays whole there, and the cracks open all
//!   around the edge between two tips on the line: boundary faces doubled in a
//!   fragment's ceiling. Not joining
//!   tets through faces made only of the earlier cut's vertices gave that tip a copy, and
//!   the fragment's floor and ceiling then differed at 8 faces around it; with ghosts
//!   also on such faces once the tets on their two sides decide apart, one of liver's two
//!   lines was taken, but the random scalpel paths of [`super::scalpel`]'s limits (40 per
//!   mesh) were refused at 589 of 1,488 polygons instead of 592: not kept. A cut of
//!   a deformed body (`cut_deformed`) is recorded with its frame (a fingerprint of the
//!   positions it decided at, `Frames`): a step continuing it at an angle at the same
//!   positions (the body not moved between) is decided as at rest, in that frame; a
//!   step after the body moved finds no cut in its frame to turn from, and is refused
//!   or leaves the cracks apart (one continuing it in its plane after the body moved
//!   takes the earlier crack's vertices as lying in it: `glued`, see [`super::live`]).
//!   Before, every such step was refused. The pinch check above looks at the finest and
//!   coarsest meshes; after the DAG update every extraction's star at the vertices on the
//!   cut is examined too (`pinched_between`: the sets of fragments around each vertex
//!   closed under the DAG's order), since a blade turning by 0.5° per step, cut
//!   at every step, was left with an extraction between them pinched at a tip (a vertex
//!   joining two boundary fans) at step 41 of 128 on fandisk (the mesh of the 7/9
//!   quantile of fragment errors) and 60 on pinion, as the tests sample extractions; the
//!   steps refused now are 41 on fandisk and 56 on pinion (tests/mt_scalpel.rs), and
//!   deferring steps to half a median edge, as [`super::Incision`] does, takes them all.
//!   A step failing the checks is not left in the MT: before closing, every fragment the
//!   cut changed has its floor and ceiling checked for the same boundary (a fragment it
//!   split, whole, none holding a face twice; one it did not split, from the tets its
//!   floor and ceiling lost and gained), and every tet the cut made for a positive
//!   orientation (what `Mt::validate` checks, read from what the cut changed only:
//!   `Changed::check`), and
//!   the stars above are examined; a cut failing them is given back, the MT byte for byte
//!   as before, and refused with [`CutError::MtInconsistent`].
//! * **Crack tips off the plane are not taken** otherwise (a cut continuing an earlier
//!   one in its plane, or crossing it): tried, tips snapped onto a cut up to 1.5 × the
//!   contour band off its plane broke the floor/ceiling conformity of fragments in random
//!   cut sequences (tests/cli_mt_cut.rs, tests/mt_live.rs).

use super::classify::is_candidate;
use super::classify::{CrackTips, CutScratch, CutSession, NONE, StateClassifier, TetClass};
use super::classify::{VertexOrigin, mark_glued, origin_positions};
use super::cutter::{push_origin_rows, unsnap, with_twins};
use super::options::{CutError, CutOptions};
use super::split::{Children, split_tet};
use super::stamps::Stamps;
use super::tables::{NEG, ON, OUT, POS, Side};
use super::unglue::{StarEntry, plan_copies};
use crate::geom::{Aabb, CutPolygon, DVec3, PLANE_SNAP, Sign, lies_in_plane, snap_to_plane};
use crate::mesh::fxhash::FxBuild;
use crate::mesh::tables::{TET_EDGES, TET_FACES, flip_face, oriented_face};
use crate::mesh::{FragmentId, Tet, TetId, VertexId, boundary_hits, corners};
use crate::mt::history::{Made, MadeBy};
use crate::mt::{FragmentBvh, FragmentKind, GHOST, KnownDag, Mt, OpenMt, TetLinks};
use rayon::prelude::*;
use std::collections::{HashMap, HashSet};
use std::time::Instant;

/// Times of one MT cut, in seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MtCutTimes {
    /// Step 1: finding the candidate tets of every level.
    pub query: f64,
    /// Step 2: classifying and splitting cells, duplicating vertices, ghosts (the paper's
    /// "split" column, which includes finding the cells).
    pub split: f64,
    /// Step 3: relabelling, splitting fragments and closing the MT into arcs (the paper's
    /// "DAG" column).
    pub dag: f64,
    /// The whole cut.
    pub total: f64,
}

/// Statistics of one MT cut (Table 2's columns and more).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MtCutStats {
    /// Fragments whose floor or ceiling holds a tet the cut changed.
    pub fragments_involved: usize,
    /// Of those, the fragments the cut split (their parts lie in different bodies; each
    /// became two or more).
    pub fragments_split: usize,
    /// Fragments appended by the splits.
    pub fragments_added: usize,
    /// Non-ghost tets whose vertex states were computed.
    pub tets_tested: usize,
    /// Tets of any level that touch the cut or that its plane crosses near C.
    pub tets_candidate: usize,
    /// Tets of any level replaced by the tables (the paper's "input cells").
    pub tets_cut: usize,
    /// Tets those were replaced by (the tables' output).
    pub tets_created: usize,
    /// Tets the 1:17 scheme of Bielser et al. would have created for the same cells
    /// (17 each, the paper's baseline column).
    pub tets_created_1_17: usize,
    /// Ghost tets subdivided, and ghosts added on the crack surface.
    pub ghosts_split: usize,
    pub crack_ghosts: usize,
    /// New vertices: cut points (two per cut edge), face points and copies of snapped
    /// vertices.
    pub vertices_added: usize,
    /// Of those: cut points (on edges, one per side), crack tips inside faces, and copies
    /// of snapped vertices.
    pub cut_points: usize,
    pub face_points: usize,
    pub vertex_copies: usize,
    pub vertices_snapped: usize,
    /// Snapped vertices left shared because a tet of some level straddles there.
    pub vertices_tips: usize,
    /// Vertices left unsnapped: in the finest or the coarsest mesh their tets do not form
    /// one group per side, which one copy per side cannot separate.
    pub vertices_unsnapped: usize,
    /// The polygon lay close to the plane of an earlier crack made at rest without lying in
    /// it, and was cut in that plane ([`PLANE_SNAP`]).
    pub moved_to_plane: bool,
    /// Independent MTs after the cut.
    pub components: usize,
    /// The snapping tolerance the cut was planned with: the options', or up to
    /// [`MAX_MT_SNAP`] when it would have made a flat tet or a hanging vertex (see
    /// [`MtCutter::cut`]).
    pub snap: f64,
    pub time: MtCutTimes,
}

impl MtCutStats {
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "fragments_involved": self.fragments_involved,
            "fragments_split": self.fragments_split,
            "fragments_added": self.fragments_added,
            "tets_tested": self.tets_tested,
            "tets_candidate": self.tets_candidate,
            "tets_cut": self.tets_cut,
            "tets_created": self.tets_created,
            "tets_created_1_17": self.tets_created_1_17,
            "ghosts_split": self.ghosts_split,
            "crack_ghosts": self.crack_ghosts,
            "vertices_added": self.vertices_added,
            "cut_points": self.cut_points,
            "face_points": self.face_points,
            "vertex_copies": self.vertex_copies,
            "vertices_snapped": self.vertices_snapped,
            "vertices_tips": self.vertices_tips,
            "vertices_unsnapped": self.vertices_unsnapped,
            "moved_to_plane": self.moved_to_plane,
            "components": self.components,
            "snap": self.snap,
            "time": {
                "query": self.time.query,
                "split": self.time.split,
                "dag": self.time.dag,
                "total": self.time.total,
            },
        })
    }
}

/// An MT ready to be cut many times (see the [module docs](self)).
pub struct MtCutter {
    /// Always `Some` between calls (taken while a cut commits).
    mt: Option<Mt>,
    /// Longest incident edge of each vertex in the finest mesh (see the module docs): the
    /// MT's (its `CutHistory`'s), held here while a cut runs, empty between cuts.
    scales: Vec<f64>,
    max_scale: f64,
    bounds: Aabb,
    scratch: CutScratch,
    options: CutOptions,
    /// Per fragment: whether its floor and ceiling form several parts (see
    /// [`split_fragment`]) that one body still joins through other fragments. Such a
    /// fragment is involved in every later cut that leaves a root in several parts (see
    /// the module docs): the cut that separates the body may not
    /// touch it.
    cracked: Vec<bool>,
    /// Where each vertex the last cut appended comes from (see
    /// [`MtCutter::last_origins`]).
    last_origins: Vec<VertexOrigin>,
    /// The collapse fragments by box, built with the cutter (step 1). Cuts replace tets by
    /// children inside them, so a fragment's box only shrinks and the hierarchy's boxes,
    /// grown by `fragment_bvh_slack` (for the quantisation of the boxes and for rounding
    /// of new points on the body's bounding box), stay conservative.
    fragment_bvh: FragmentBvh,
    fragment_bvh_slack: DVec3,
    /// Per fragment: the next fragment a cut split off the same hierarchy entry (`NONE`:
    /// the last); each split-off fragment's box lies in its origin's.
    split_off: Vec<u32>,
    /// The creator and destroyer of each pool tet of `mt` (8 bytes per pool tet), derived
    /// when the cutter is made and kept from each cut's close, so that a cut opens the MT
    /// without deriving them (`None` only while a cut has the MT open).
    links: Option<TetLinks>,
    /// The MT's number of independent components (changed only by a cut that splits
    /// fragments).
    components: usize,
    /// Per vertex: whether it lies on a crack ([`MtCutter::crack_vertices`]).
    crack: Vec<bool>,
    /// Per-vertex scratch of step 3's grouping of tets into pieces, kept from cut to cut
    /// (a table over the pool: allocating it per cut would cost in proportion to the
    /// pool).
    pieces: Pieces,
}

/// Largest `snap` an MT cut accepts (see the module docs, "Limits").
pub const MAX_MT_SNAP: f64 = 1e-4;

/// A face as an oriented triangle, rotated so its smallest id comes first.
type FaceKey = [u32; 3];

/// The outward faces of a tet, oriented.
fn faces_of(t: &Tet) -> [FaceKey; 4] {
    TET_FACES.map(|f| oriented_face(t[f[0]].0, t[f[1]].0, t[f[2]].0))
}

fn find(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        parent[i as usize] = parent[parent[i as usize] as usize];
        i = parent[i as usize];
    }
    i
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (x, y) = (find(parent, a), find(parent, b));
    if x != y {
        parent[x.max(y) as usize] = x.min(y);
    }
}

impl MtCutter {
    /// The options of an MT cut: the engine's defaults with `snap` 1e-6 (vertices are on
    /// the cut only when on its plane up to rounding, inside C), cracks continued (an MT
    /// cut always continues the cracks of earlier cuts, whatever
    /// [`CutOptions::continue_cracks`] says) and face points at the smallest margin
    /// ([`MIN_FACE_POINT_MARGIN`](super::MIN_FACE_POINT_MARGIN): a crack's tips follow its
    /// polygon's contour). With the engine's margin of 0.5 (tips in the middle of their
    /// segments, up to half a face inside C), a cut continuing an earlier one in its plane
    /// (a square next to the last) met tips beyond the contour band and left fragments
    /// with a face twice on all three shared meshes (tests/mtcut_cut.rs). The same options
    /// as [`CutOptions::SCALPEL`]'s for a plain mesh.
    pub const DEFAULT_OPTIONS: CutOptions = CutOptions {
        snap: crate::geom::Tolerance { relative: 1e-6 },
        face_point_margin: super::MIN_FACE_POINT_MARGIN,
        continue_cracks: true,
        ..CutOptions::DEFAULT
    };

    /// Prepares `mt` (which should be valid: [`Mt::validate`]) for cutting with `options`
    /// (start from [`MtCutter::DEFAULT_OPTIONS`]): vertex scales, the hierarchy over
    /// fragment boxes, the fragments earlier cuts left cracked, the per-tet links of the
    /// open form and room in the pool, so that cuts cost in proportion to what they
    /// change (see the module docs' limits for what does not). Only
    /// [`Scheme::Lut`](super::Scheme::Lut) is supported (the 1:17 scheme does not conform
    /// across tets, which the levels of an MT need), and `snap` at most [`MAX_MT_SNAP`]
    /// (see the module docs, "Limits").
    pub fn new(mt: Mt, options: CutOptions) -> Result<MtCutter, CutError> {
        options.check()?;
        if options.snap.relative > MAX_MT_SNAP {
            return Err(CutError::InvalidOption {
                option: "snap",
                value: options.snap.relative,
                expected: "at most 1e-4 for an MT (see the module docs: snapping off the \
                           plane bends the cut surface differently on each level)",
            });
        }
        if options.scheme != super::Scheme::Lut {
            return Err(CutError::InvalidOption {
                option: "scheme",
                value: 1.0,
                expected: "the look-up tables (the 1:17 scheme is not conforming)",
            });
        }
        super::classify::build_tables();
        let mut mt = mt;
        // Scales a cut recorded in the MT (see `CutHistory`): what the cutter that made the
        // cuts measured by; derived again they would differ near the cracks (their edges
        // are split), and a cut would decide otherwise.
        let recorded = std::mem::take(&mut mt.cut_history_mut().scales);
        let scales = if recorded.len() == mt.nb_vertices() {
            recorded
        } else {
            finest_edge_scales(&mt)
        };
        let max_scale = scales.iter().copied().fold(0.0, f64::max);
        let bounds = Aabb::from_points(mt.positions());
        let cracked = cracked_fragments(&mt);
        let fragment_bvh = FragmentBvh::new(&mt);
        // Four steps of the boxes' 16-bit quantisation.
        let fragment_bvh_slack = (bounds.max - bounds.min) * (4.0 / f64::from(u16::MAX));
        let split_off = vec![NONE; mt.nb_fragments()];
        // What the first cut would pay for in proportion to the pool, paid here: the
        // per-tet links of the open form, and room to append to the pool.
        let links = Some(mt.tet_links());
        let mut crack = shared_positions(mt.positions());
        let from = mt.info().cuts.cut_vertices_from().min(crack.len());
        crack[from..].fill(true);
        let components = mt.nb_components();
        mt.reserve_edit_room();
        mt.cut_history_mut().scales = scales;
        Ok(MtCutter {
            mt: Some(mt),
            scales: Vec::new(),
            max_scale,
            bounds,
            scratch: CutScratch::new(),
            options,
            cracked,
            last_origins: Vec::new(),
            fragment_bvh,
            fragment_bvh_slack,
            split_off,
            links,
            components,
            crack,
            pieces: Pieces::new(0),
        })
    }

    /// A copy of the cutter to go back to: the MT and every table a cut reads or changes,
    /// its scratch left empty (grown again by the next cut). A scalpel step cutting two
    /// triangles takes one before the first, and goes back to it when the second is
    /// refused ([`super::Scalpel::step`]), so that a refused step changes nothing.
    pub(crate) fn snapshot(&self) -> MtCutter {
        MtCutter {
            mt: Some(self.mt().clone()),
            scales: self.scales.clone(),
            max_scale: self.max_scale,
            bounds: self.bounds,
            scratch: CutScratch::new(),
            options: self.options,
            cracked: self.cracked.clone(),
            last_origins: self.last_origins.clone(),
            fragment_bvh: self.fragment_bvh.clone(),
            fragment_bvh_slack: self.fragment_bvh_slack,
            split_off: self.split_off.clone(),
            links: self.links.clone(),
            components: self.components,
            crack: self.crack.clone(),
            pieces: Pieces::new(0),
        }
    }

    /// The bounding box of the MT's vertices at rest.
    pub(crate) fn bounds(&self) -> Aabb {
        self.bounds
    }

    pub fn mt(&self) -> &Mt {
        self.mt
            .as_ref()
            .expect("MtCutter holds its MT between cuts")
    }

    /// Per MT vertex: whether it lies on a crack — appended by a cut (cut points, face
    /// points, copies: every vertex from the MT's
    /// [`CutHistory::cut_vertices_from`](crate::mt::CutHistory::cut_vertices_from) on),
    /// or sharing its position with another vertex (a copied vertex, and the lips of
    /// cracks in an MT saved before cuts were recorded, whose face points are then not
    /// recognised). A cut in the plane of an earlier crack takes these as neither side
    /// when they lie on its plane outside its polygon
    /// ([`StateClassifier::with_crack_vertices`]).
    pub fn crack_vertices(&self) -> &[bool] {
        &self.crack
    }

    pub fn into_mt(self) -> Mt {
        self.mt.expect("MtCutter holds its MT between cuts")
    }

    /// Takes the MT out, the cutter keeping what it prepared for it, for a holder that
    /// shares the MT between cuts (the C ABI's model handle, whose frontiers keep the
    /// model as it was): the cutter cannot cut until [`put_mt`](Self::put_mt) gives it
    /// back, or an exact copy of it.
    pub(crate) fn take_mt(&mut self) -> Mt {
        self.mt.take().expect("MtCutter holds its MT between cuts")
    }

    /// Gives back the MT [`take_mt`](Self::take_mt) took (or an exact copy of it).
    pub(crate) fn put_mt(&mut self, mt: Mt) {
        debug_assert!(self.mt.is_none(), "the cutter already holds an MT");
        debug_assert_eq!(
            mt.nb_fragments(),
            self.split_off.len(),
            "not the cutter's MT"
        );
        self.mt = Some(mt);
    }

    pub fn options(&self) -> &CutOptions {
        &self.options
    }

    /// The scale of each vertex (longest incident edge in the finest mesh when the MT was
    /// first prepared for cutting; vertices made by cuts take the largest scale of the
    /// vertices they are made of). Kept in the MT's cut record.
    pub fn vertex_scales(&self) -> &[f64] {
        &self.mt().info().cuts.scales
    }

    /// The vertices the last cut appended to the pool, in order from the pool's vertex
    /// count before it: each a linear combination of older vertices (cut points, face
    /// points, copies). The deformable cut (paper §5, [`super::live`]) places them in the
    /// deformed space by the same combinations.
    pub fn last_origins(&self) -> &[VertexOrigin] {
        &self.last_origins
    }

    /// Cuts every level of the MT with `polygon` and updates the DAG (see the
    /// [module docs](self)). The cut is planned in full before the MT changes. One that
    /// would make a tet flat once its points are rounded, or leave a vertex it makes
    /// hanging in a crack face, is planned again with `snap` a hundred times larger, up to
    /// [`MAX_MT_SNAP`] (`stats.snap` says which was used), as [`super::Cutter::cut`]
    /// retries on a plain mesh, and refused when that still fails. On an MT of one level
    /// (a shared mesh alone) moved along the random scalpel paths of tests/mt_scalpel.rs,
    /// this took one more path of 25 per mesh on fandisk and none more elsewhere; the
    /// plain engine's further retries (up to 0.2) would have taken one more on liver, but
    /// snapping that far bends the cut differently on each level (see the limits).
    pub fn cut(&mut self, polygon: &CutPolygon) -> Result<MtCutStats, CutError> {
        self.cut_with(polygon, None, None)
    }

    /// [`cut`](Self::cut) of the MT as it lies deformed: `positions` gives every pool
    /// vertex a position (a deformed body, paper §5) and `polygon` is given in that space.
    /// Every decision of the cut (vertex sides, snapping, where each edge and face is cut,
    /// as parameters and weights) is made at those positions; the new vertices are placed
    /// by the same parameters and weights between the vertices' own (rest) positions. Each
    /// tet is cut by one plane in the deformed space, which in rest space is the plane
    /// pulled back through the tet's own affine map: levels stay consistent (an edge's
    /// cut point is shared by every tet of every level through it), and where `positions`
    /// equal the rest positions the cut is exactly [`cut`](Self::cut). Refused
    /// ([`CutError::DeformationFolds`]) when `positions` invert a tet the cut would touch.
    ///
    /// The vertices `glued` count as lying in the polygon's plane wherever `positions` put
    /// them (their state is that of their projection onto it): the vertices earlier cuts
    /// made in that plane, which a motion of the body since has moved off it, for a blade
    /// continuing its crack in steps ([`super::live`]; empty: none). A vertex id out of
    /// the pool is refused ([`CutError::InvalidOption`]).
    pub fn cut_deformed(
        &mut self,
        polygon: &CutPolygon,
        positions: &[DVec3],
        glued: &[VertexId],
    ) -> Result<MtCutStats, CutError> {
        let nv = self.mt().nb_vertices();
        super::cutter::check_positions(positions, nv)?;
        if let Some(v) = glued.iter().find(|v| v.idx() >= nv) {
            return Err(CutError::InvalidOption {
                option: "glued",
                value: v.idx() as f64,
                expected: "vertex ids of the MT",
            });
        }
        self.cut_with(polygon, None, Some((positions, glued)))
    }

    /// [`cut`](Self::cut), processing the involved fragments of step 3 in the order of
    /// `key(fragment)` (ascending) instead of by id: the result must not depend on it.
    pub fn cut_in_order(
        &mut self,
        polygon: &CutPolygon,
        key: Option<&dyn Fn(FragmentId) -> u64>,
    ) -> Result<MtCutStats, CutError> {
        self.cut_with(polygon, key, None)
    }

    /// The cut, in fragment order `key`, deciding at `deformed` positions when given
    /// (see [`cut_deformed`](Self::cut_deformed)).
    fn cut_with(
        &mut self,
        polygon: &CutPolygon,
        key: Option<&dyn Fn(FragmentId) -> u64>,
        deformed: Option<(&[DVec3], &[VertexId])>,
    ) -> Result<MtCutStats, CutError> {
        // The vertex scales and the record of the last cuts travel with the MT (saved with
        // it, read by any cutter made of it): taken out while the MT is open, given back
        // whatever happens (a refused cut leaves them as they were).
        let history = self.mt_mut().cut_history_mut();
        let mut made = std::mem::take(&mut history.made);
        self.scales = std::mem::take(&mut history.scales);
        // A cut refused for a flat child or a hanging vertex is planned again with `snap`
        // a hundred times larger, up to `MAX_MT_SNAP`, as the plain-mesh engine retries
        // (`Cutter::cut`, which goes on up to 0.2): the vertex the plane passed too close
        // to is then on the cut. The MT is as it was after a refusal; the time reported
        // is the attempts' together.
        let start = Instant::now();
        let mut opts = self.options;
        let mut result = loop {
            let mut snap_may_help = false;
            let r = self.cut_recording(polygon, key, deformed, &mut made, opts, &mut snap_may_help);
            if r.is_err() && snap_may_help && opts.snap.relative < MAX_MT_SNAP {
                opts.snap.relative = (opts.snap.relative * 100.0).min(MAX_MT_SNAP);
                continue;
            }
            break r;
        };
        if let Ok(stats) = &mut result {
            stats.time.total = start.elapsed().as_secs_f64();
        }
        let scales = std::mem::take(&mut self.scales);
        let history = self.mt_mut().cut_history_mut();
        history.made = made;
        history.scales = scales;
        result
    }

    /// Calls `test` on every pool tet (ghosts included) of a fragment whose box meets
    /// `box_meets`, at rest: the collapse fragments through the hierarchy (its boxes grown
    /// to stay conservative, see `fragment_bvh`), each checked by its current box. A tet
    /// is reached once: through its creator, or, created by a root, through its destroyer
    /// (whose floor holds it) or as one of the root's tets in the coarsest mesh.
    fn tets_meeting(
        &self,
        mt: &Mt,
        box_meets: impl Fn(&Aabb) -> bool,
        mut test: impl FnMut(TetId),
    ) {
        let grow = self.fragment_bvh_slack;
        let mut hits: Vec<FragmentId> = Vec::new();
        self.fragment_bvh.query(
            |b| {
                box_meets(&Aabb {
                    min: b.min - grow,
                    max: b.max + grow,
                })
            },
            |hit| {
                let mut f = hit.fragment.0;
                while f != NONE {
                    if box_meets(&mt.fragment_bbox(FragmentId(f))) {
                        hits.push(FragmentId(f));
                    }
                    f = self.split_off[f as usize];
                }
            },
        );
        for &g in &hits {
            mt.created_tets(g).for_each(&mut test);
        }
        for &r in mt.roots() {
            for &g in hits.iter().chain(mt.drains()) {
                if let Some(a) = mt.arc_between(r, g) {
                    mt.arc_tets(a).map(TetId::from_usize).for_each(&mut test);
                }
            }
        }
    }

    fn mt_mut(&mut self) -> &mut Mt {
        self.mt
            .as_mut()
            .expect("MtCutter holds its MT between cuts")
    }

    /// [`cut_with`](Self::cut_with), reading and adding to the record `made`.
    fn cut_recording(
        &mut self,
        polygon: &CutPolygon,
        key: Option<&dyn Fn(FragmentId) -> u64>,
        deformed: Option<(&[DVec3], &[VertexId])>,
        made: &mut Made,
        opts: CutOptions,
        snap_may_help: &mut bool,
    ) -> Result<MtCutStats, CutError> {
        let start = Instant::now();
        let mut stats = MtCutStats {
            snap: opts.snap.relative,
            ..MtCutStats::default()
        };
        let mt = self
            .mt
            .as_ref()
            .expect("MtCutter holds its MT between cuts");
        let nv = mt.nb_vertices();
        // Where the cut's decisions are made: rest positions, or the deformed ones (whose
        // bounds are not the fragments' boxes: those are not used then). Deformed positions
        // equal to the rest ones (a body at rest) are the cut at rest, boxes included.
        let (deformed, glued) = match deformed {
            Some((p, glued)) if p != mt.positions() => (Some(p), glued),
            _ => (None, &[][..]),
        };
        let positions = deformed.unwrap_or(mt.positions());
        // A polygon close to the plane of one of the last cuts at rest, without lying in
        // it (a blade re-entering an incision), is cut in that plane (see `snap_to_plane`).
        let in_plane = match deformed {
            None => made.near_plane(polygon, PLANE_SNAP * self.bounds.diagonal()),
            Some(_) => None,
        };
        stats.moved_to_plane = in_plane.is_some();
        let polygon = in_plane.as_ref().unwrap_or(polygon);
        let bounds = match deformed {
            Some(p) => Aabb::from_points(p),
            None => self.bounds,
        };

        // Step 1: fragments by box, then the tets they create by vertex states.
        // Earlier polygons this one continues at an angle (see `TurnTips`), made in its
        // frame (at rest, or at the same deformed positions): their tips near the edge
        // they share are on this cut.
        let mut frames = Frames::new(deformed);
        let turning: Vec<Turning> =
            made.turning(polygon, self.max_scale, |first| frames.before(first));
        let mut turning_tips = CrackTips::default();
        for t in &turning {
            made.tips(t.cut).for_each(|v| turning_tips.insert(v));
        }
        let mut classifier = StateClassifier::new(polygon, opts.snap, &bounds, self.max_scale)
            .with_contour_band(contour_band(&opts));
        if deformed.is_some()
            || continues_a_crack_plane(polygon, made.planes.iter().map(|&[n, p]| (n, p)))
        {
            classifier = classifier.with_crack_vertices(&self.crack);
        }
        if !turning.is_empty() {
            classifier = classifier.with_crack_tips(&turning_tips, tip_reach(&opts));
        }
        let mut glue_flags: Vec<bool> = Vec::new();
        let mut glue_reach = 0.0f64;
        if !glued.is_empty() {
            glue_reach = mark_glued(&mut glue_flags, nv, glued, polygon, |v| positions[v.idx()]);
            classifier = classifier.with_glued(&glue_flags, glue_reach);
        }
        let coord = bounds.min.abs().max(self.bounds.max.abs()).max_element();
        let slack = 64.0 * f64::EPSILON * (coord + polygon.bbox().max.abs().max_element());
        let margin =
            (2.0 * opts.snap.relative + contour_band(&opts)) * self.max_scale + slack + glue_reach;
        let cbox = polygon.bbox();
        let grown = Aabb {
            min: cbox.min - DVec3::splat(margin),
            max: cbox.max + DVec3::splat(margin),
        };
        let normal = polygon.normal();
        let offset = polygon.plane().offset;
        let box_meets = |b: &Aabb| {
            if !b.intersects(&grown) {
                return false;
            }
            let c = (b.min + b.max) * 0.5;
            let e = (b.max - b.min) * 0.5;
            (normal.dot(c) - offset).abs() <= normal.abs().dot(e) + margin
        };
        // Ghosts whose triangle meets C's neighbourhood: the only ones the cut can
        // subdivide (their face has a cut point) or give copies (a vertex on the cut).
        // Other tets are tested, and candidates with their vertices' states.
        let meets = |t: TetId| -> Met {
            let tet = mt.tet(t);
            if tet[3] == GHOST {
                let triangle = [0, 1, 2].map(|j| positions[tet[j].idx()]);
                return if box_meets(&Aabb::from_points(&triangle)) {
                    Met::Ghost
                } else {
                    Met::No
                };
            }
            let s = classifier.tet(positions, &self.scales, &tet);
            if is_candidate(s) && box_meets(&Aabb::from_points(&tet.map(|v| positions[v.idx()]))) {
                Met::Candidate(s)
            } else {
                Met::Tested
            }
        };
        let (mut found, mut ghosts) = (Vec::new(), Vec::new());
        let mut test = |t: TetId| match meets(t) {
            Met::Ghost => ghosts.push(t.0),
            Met::No => {}
            Met::Tested => stats.tets_tested += 1,
            Met::Candidate(s) => {
                stats.tets_tested += 1;
                found.push((t, s));
            }
        };
        match deformed {
            // The boxes hold at rest. A tet deformed lies in its box at rest grown by the
            // largest displacement of a vertex, so the hierarchy finds it with its boxes
            // grown so (and by the rounding of coordinates at rest); a pass over every
            // tet of every fragment took 9 ms of each queued cut of the scalpel bench's
            // bent fandisk, where this finds the same tets (debug builds compare).
            Some(p) => {
                let at_rest_coord = self.bounds.min.abs().max(self.bounds.max.abs());
                let reach = p
                    .iter()
                    .zip(mt.positions())
                    .map(|(a, b)| (*a - *b).abs().max_element())
                    .fold(0.0, f64::max)
                    + slack
                    + 64.0 * f64::EPSILON * at_rest_coord.max_element();
                let at_rest = |b: &Aabb| {
                    box_meets(&Aabb {
                        min: b.min - DVec3::splat(reach),
                        max: b.max + DVec3::splat(reach),
                    })
                };
                self.tets_meeting(mt, at_rest, &mut test);
                #[cfg(debug_assertions)]
                {
                    let (mut all, mut all_ghosts) = (Vec::new(), Vec::new());
                    for f in (0..mt.nb_fragments()).map(FragmentId::from_usize) {
                        if mt.fragment_kind(f) != FragmentKind::Drain {
                            mt.created_tets(f).for_each(|t| match meets(t) {
                                Met::Ghost => all_ghosts.push(t.0),
                                Met::Candidate(s) => all.push((t, s)),
                                _ => {}
                            });
                        }
                    }
                    let mut seen = found.clone();
                    let mut seen_ghosts = ghosts.clone();
                    for v in [&mut all, &mut seen] {
                        v.sort_unstable_by_key(|&(t, _)| t);
                    }
                    all_ghosts.sort_unstable();
                    seen_ghosts.sort_unstable();
                    assert!(
                        all == seen && all_ghosts == seen_ghosts,
                        "a deformed cut's tets found through the hierarchy are not those of \
                         every fragment"
                    );
                }
            }
            None => self.tets_meeting(mt, box_meets, &mut test),
        }
        // Pool order, as a pass over the fragments in id order finds them.
        found.sort_unstable_by_key(|&(t, _)| t);
        ghosts.sort_unstable();
        let (mut cand, mut states): (Vec<TetId>, Vec<[u8; 4]>) = found.into_iter().unzip();
        settle_plane_vertices(
            polygon,
            opts,
            positions,
            &self.scales,
            &mut cand,
            &mut states,
            false,
            |t| mt.tet(t),
        );
        if cand.is_empty() {
            // Nothing to cut: the MT stays as it is (closing it again would cost a pass
            // over the pool for the same store).
            self.last_origins.clear();
            stats.components = self.components;
            stats.time.query = start.elapsed().as_secs_f64();
            stats.time.total = stats.time.query;
            return Ok(stats);
        }
        let tets: Vec<Tet> = cand.iter().map(|&t| mt.tet(t)).collect();
        if deformed.is_some() {
            // The deformed positions place each tet by its vertices; a tet they fold has no
            // plane section the tables could make at rest.
            let folded = tets.iter().position(|t| {
                let [a, b, c, d] = corners(t, |v| positions[v.idx()]);
                crate::geom::orient3d(a, b, c, d) != crate::geom::Sign::Positive
            });
            if let Some(k) = folded {
                return Err(CutError::DeformationFolds { tet: cand[k].idx() });
            }
        }
        stats.tets_candidate = cand.len();
        stats.time.query = start.elapsed().as_secs_f64();

        // Step 2: one classification for all levels, then the tables.
        let t_split = Instant::now();
        let par = tets.len() >= opts.parallel_threshold;
        let mut session = CutSession::new(
            polygon,
            opts.snap,
            opts.face_point_margin,
            &mut self.scratch,
            nv,
        );
        let mut classes = session.classify(positions, &self.scales, &tets, &states, par);
        let mut children: Vec<Children> = Vec::new();
        let mut child_of = vec![NONE; tets.len()];
        let split_into =
            |session: &CutSession<'_>, k: usize, class: &TetClass, children: &mut Vec<Children>| {
                let mut c = Children::new();
                // Ordered by id (see `canonical_order_at`'s note on MTs).
                if split_tet(session, &tets[k], class, None, &mut c) {
                    children.push(c);
                    (children.len() - 1) as u32
                } else {
                    NONE
                }
            };
        for k in 0..tets.len() {
            child_of[k] = split_into(&session, k, &classes[k], &mut children);
        }
        // Snapped vertices whose tets in the finest or the coarsest mesh do not form one
        // group per side (the engine's analysis, [`super::unglue`], of each) are left
        // unsnapped on every level, and the tets around them classified and split again,
        // as the plain-mesh engine does.
        let finest: Vec<bool> = cand
            .iter()
            .map(|&t| mt.fragment_kind(mt.tet_creator(t)) == FragmentKind::Root)
            .collect();
        // Tips of an earlier crack at an angle to this cut, on the line where it ended
        // (see `TurnTips`): their two groups are the two sides of both cracks together,
        // not the sides of this cut, so they are not unsnapped for having several groups
        // on a side. A pinched one (a group whose link is not a disk: no copy can
        // separate it) is unsnapped like any other, as the plain-mesh engine does: on
        // an MT of one level (the finest mesh alone) kept as a turning tip, it made the
        // first difference from the plain engine's result on the same random scalpel
        // paths and left the tip's copy pinched a few steps later (25 paths per shared
        // mesh: 6, 6 and 6 met a refused step, 5, 2 and 4 with this rule).
        let mut turn = TurnTips::new(&tets, &states, &turning, made, 1e-6 * self.max_scale);
        let coarsest: Vec<bool> = cand
            .iter()
            .map(|&t| mt.fragment_kind(mt.tet_destroyer(t)) == FragmentKind::Drain)
            .collect();
        let mut star: Vec<StarEntry> = Vec::new();
        let mut on_cut: Vec<VertexId> = Vec::new();
        loop {
            let mut bad: Vec<VertexId> = Vec::new();
            let mut pinched: Vec<VertexId> = Vec::new();
            let mut snapped: Vec<VertexId> = Vec::new();
            for level in [&finest, &coarsest] {
                star.clear();
                on_cut.clear();
                for (k, class) in classes.iter().enumerate() {
                    if !level[k] || !class.touches_cut() {
                        continue;
                    }
                    for (&s, &v) in class.states.iter().zip(&tets[k]) {
                        if s == ON {
                            on_cut.push(v);
                        }
                    }
                    match child_of[k] {
                        NONE => {
                            let side = side_of_states(&tets[k], class.states, positions, polygon);
                            for j in (0..4).filter(|&j| class.states[j] == ON) {
                                star.push(StarEntry {
                                    vertex: tets[k][j],
                                    tet: TetId((32 * k) as u32),
                                    verts: tets[k],
                                    side,
                                });
                            }
                        }
                        i => {
                            let ch = &children[i as usize];
                            for c in 0..ch.len {
                                for j in (0..4).filter(|&j| ch.on_cut[c] & (1 << j) != 0) {
                                    star.push(StarEntry {
                                        vertex: ch.tets[c][j],
                                        tet: TetId((32 * k + c) as u32),
                                        verts: ch.tets[c],
                                        side: ch.sides[c],
                                    });
                                }
                            }
                        }
                    }
                }
                on_cut.sort_unstable();
                on_cut.dedup();
                let plan = plan_copies(&on_cut, &star, |v| on_cut.binary_search(&v).unwrap_or(0));
                pinched.extend(plan.pinched);
                for w in plan.groups.windows(2) {
                    if w[0].0 == w[1].0 {
                        bad.push(w[0].0);
                    }
                }
                snapped.extend_from_slice(&on_cut);
            }
            bad.retain(|&v| !turn.has(v));
            bad.append(&mut pinched);
            bad.sort_unstable();
            bad.dedup();
            if bad.is_empty() {
                break;
            }
            snapped.sort_unstable();
            snapped.dedup();
            let bad = with_twins(bad, &snapped, positions);
            stats.vertices_unsnapped += bad.len();
            let affected = unsnap(&mut session, positions, polygon, &bad, &tets, &mut states);
            let sub_tets: Vec<Tet> = affected.iter().map(|&k| tets[k]).collect();
            let sub_states: Vec<[u8; 4]> = affected.iter().map(|&k| states[k]).collect();
            let sub = session.classify(positions, &self.scales, &sub_tets, &sub_states, false);
            for (&k, class) in affected.iter().zip(sub) {
                classes[k] = class;
                child_of[k] = split_into(&session, k, &classes[k], &mut children);
            }
        }
        if stats.vertices_unsnapped > 0 {
            // An unsnapped turning tip is off this cut: not taken onto its crack.
            turn = TurnTips::new(&tets, &states, &turning, made, 1e-6 * self.max_scale);
        }
        let first_new = VertexId::from_usize(nv);
        let origins = session.allocate(first_new);
        let mut live: Vec<Children> = Vec::new();
        for slot in child_of.iter_mut().filter(|i| **i != NONE) {
            let mut c = children[*slot as usize];
            for t in c.tets[..c.len].iter_mut() {
                *t = corners(t, |v| session.resolve(v));
            }
            *slot = live.len() as u32;
            live.push(c);
        }
        let children = live;
        drop(session);
        stats.tets_cut = children.len();
        stats.tets_created = children.iter().map(|c| c.len).sum();
        stats.tets_created_1_17 = 17 * children.len();

        // Snapped vertices: the sides around each over all levels.
        let unsplit: Vec<Side> = (0..tets.len())
            .map(|k| side_of_states(&tets[k], classes[k].states, positions, polygon))
            .collect();
        let unsplit_side = |k: usize| unsplit[k];
        // Per snapped vertex: seen positive, negative, straddling.
        let mut around: HashMap<VertexId, [bool; 3], FxBuild> = HashMap::default();
        let mut note = |v: VertexId, side: Side| {
            let e = around.entry(v).or_default();
            match side {
                Side::Positive => e[0] = true,
                Side::Negative => e[1] = true,
                Side::Straddle => e[2] = true,
            }
        };
        for (k, class) in classes.iter().enumerate() {
            if !class.touches_cut() {
                continue;
            }
            let on: Vec<VertexId> = (0..4)
                .filter(|&j| class.states[j] == ON)
                .map(|j| tets[k][j])
                .collect();
            match child_of[k] {
                NONE => {
                    let side = unsplit_side(k);
                    for &v in &on {
                        note(v, side);
                    }
                }
                i => {
                    let ch = &children[i as usize];
                    for c in 0..ch.len {
                        for &v in on.iter().filter(|v| ch.tets[c].contains(v)) {
                            note(v, ch.sides[c]);
                        }
                    }
                }
            }
        }
        let mut snapped: Vec<VertexId> = around.keys().copied().collect();
        snapped.sort_unstable();
        stats.vertices_snapped = snapped.len();
        let is_cut_vertex =
            |v: VertexId| v.0 != GHOST.0 && (v >= first_new || around.contains_key(&v));
        // `OUT` vertices of the tets the cut changes: a crack opening from a snapped vertex
        // may reach one (an earlier crack's vertex in the same plane), so the faces of the
        // opening hold them; faces made of them only are the earlier crack's, not this cut's.
        let mut out_vertices: Vec<VertexId> = Vec::new();
        for (k, class) in classes.iter().enumerate() {
            if child_of[k] != NONE || class.touches_cut() {
                let out = (0..4).filter(|&j| class.states[j] == OUT);
                out_vertices.extend(out.map(|j| tets[k][j]));
            }
        }
        out_vertices.sort_unstable();
        out_vertices.dedup();
        // Per vertex, for the crack's faces: bit 0 on this cut (made or snapped by it), bit
        // 1 on this cut or an `OUT` vertex. A triangle lies on the crack when every corner
        // has bit 1 and one has bit 0.
        let crack_mark = |v: VertexId| -> u8 {
            if is_cut_vertex(v) {
                3
            } else {
                u8::from(out_vertices.binary_search(&v).is_ok()) << 1
            }
        };
        let marks_on_crack =
            |m: [u8; 3]| m.iter().all(|&x| x & 2 != 0) && m.iter().any(|&x| x & 1 != 0);
        let on_crack = |f: [VertexId; 3]| marks_on_crack(f.map(crack_mark));
        // Per turning tip, whether tets of every level hold it outside and inside the wedge
        // (then it takes a copy), and which tets keep it (`keeps`).
        let mut turn_groups: HashMap<VertexId, [bool; 2], FxBuild> = HashMap::default();
        let mut keeps: HashMap<(VertexId, Tet), bool, FxBuild> = HashMap::default();
        if !turn.is_empty() {
            let early = origin_positions(positions, &origins);
            let pos = |v: VertexId| {
                if v.idx() < nv {
                    positions[v.idx()]
                } else {
                    early[v.idx() - nv]
                }
            };
            let mut at_tip: Vec<TipHolder> = Vec::new();
            for (k, class) in classes.iter().enumerate() {
                if !class.touches_cut() {
                    continue;
                }
                let coarsest = mt.fragment_kind(mt.tet_destroyer(cand[k])) == FragmentKind::Drain;
                let levels = u8::from(finest[k]) | u8::from(coarsest) << 1;
                let mut see = |t: &Tet, side: Side| {
                    for &v in t.iter().filter(|&&v| turn.has(v)) {
                        at_tip.push(TipHolder {
                            tip: v,
                            tet: *t,
                            side,
                            in_wedge: turn.in_wedge(v, t, side, &pos),
                            levels,
                            owner: mt.tet_creator(cand[k]),
                        });
                    }
                };
                match child_of[k] {
                    NONE => see(&tets[k], unsplit_side(k)),
                    i => {
                        let ch = &children[i as usize];
                        for c in 0..ch.len {
                            see(&ch.tets[c], ch.sides[c]);
                        }
                    }
                }
            }
            // Tets joined through a face at the tip on no crack must keep it alike: where
            // the cracks end near it (a level whose earlier crack ends short of the line
            // the new polygon begins on, near a corner of a blade ending inside the body),
            // tets beyond their ends join the wedge to the rest, and the whole group
            // keeps the tip there, as a tip of a plain crack.
            let mut parent: Vec<u32> = (0..at_tip.len() as u32).collect();
            // The first tet holding each face at a tip (tets of several levels may hold
            // it on one side): all tets on both sides of a face are joined.
            let mut by_face: HashMap<(VertexId, FaceKey), u32, FxBuild> = HashMap::default();
            for (i, h) in at_tip.iter().enumerate() {
                for f in h.faces() {
                    by_face.entry((h.tip, f)).or_insert(i as u32);
                }
            }
            for (i, h) in at_tip.iter().enumerate() {
                for f in h.faces() {
                    if let Some(&j) = by_face.get(&(h.tip, flip_face(f))) {
                        if !on_crack(f.map(VertexId)) {
                            union(&mut parent, i as u32, j);
                            union(&mut parent, i as u32, by_face[&(h.tip, f)]);
                        }
                    }
                }
            }
            let mut mixed: HashMap<u32, [bool; 2], FxBuild> = HashMap::default();
            for (i, h) in at_tip.iter().enumerate() {
                let r = find(&mut parent, i as u32);
                mixed.entry(r).or_default()[usize::from(h.in_wedge)] = true;
            }
            // Holders (indices into `at_tip`) of the tips a group kept against position.
            let mut forced: Vec<usize> = Vec::new();
            for (i, h) in at_tip.iter().enumerate() {
                let r = find(&mut parent, i as u32);
                let keep = h.in_wedge || mixed[&r] == [true, true];
                if keep != h.in_wedge {
                    forced.push(i);
                }
                keeps.insert((h.tip, h.tet), keep);
                turn_groups.entry(h.tip).or_default()[usize::from(keep)] = true;
            }
            // A tip kept whole on a level where the cracks surround it would pinch that
            // level's boundary there (two fans of crack faces meeting at one point), which
            // the check of the fragments' floors and ceilings does not see: the finest and
            // coarsest meshes are checked here (as `Mt::validate` checks them), and such a
            // cut refused before the MT changes.
            forced.sort_unstable_by_key(|&i| at_tip[i].tip);
            forced.dedup_by_key(|i| at_tip[*i].tip);
            // Other snapped vertices get a copy for the negative side when tets of both
            // sides and no straddling tet hold them (as decided below).
            let copy = |u: VertexId, t: &Tet, side: Side| match keeps.get(&(u, *t)) {
                Some(&keep) => !keep,
                None => side == Side::Negative && around.get(&u) == Some(&[true, true, false]),
            };
            for &i in &forced {
                let v = at_tip[i].tip;
                for (bit, name) in [(1, "finest"), (2, "coarsest")] {
                    let star = at_tip.iter().filter(|h| h.levels & bit != 0 && h.tip == v);
                    let Some(first) = star.clone().next() else {
                        continue;
                    };
                    let fans = tip_fans(v, star.map(|h| (h.tet, h.side)), &copy);
                    if fans.iter().any(|&n| n > 1) {
                        return Err(CutError::MtInconsistent {
                            fragment: first.owner.idx(),
                            detail: format!(
                                "its {name} mesh would be pinched at vertex {}: crack faces \
                                 around it in separate fans",
                                v.0
                            ),
                        });
                    }
                }
            }
        }
        let mut copy_of: HashMap<VertexId, VertexId, FxBuild> = HashMap::default();
        let mut copies: Vec<VertexId> = Vec::new();
        for &v in &snapped {
            let [p, n, s] = around[&v];
            let copy = match turn_groups.get(&v) {
                Some(&[out, inside]) => out && inside,
                None if s => {
                    stats.vertices_tips += 1;
                    false
                }
                None => p && n,
            };
            if copy {
                copy_of.insert(v, VertexId::from_usize(nv + origins.len() + copies.len()));
                copies.push(v);
            }
        }
        stats.vertex_copies = copies.len();
        stats.vertices_added = origins.len() + copies.len();
        for o in &origins {
            match o {
                VertexOrigin::Edge { .. } => stats.cut_points += 1,
                VertexOrigin::Face { .. } => stats.face_points += 1,
                VertexOrigin::Copy { .. } => stats.vertex_copies += 1,
            }
        }
        // The tets of the negative side take the copies, except around a turning tip:
        // there the tets outside the wedge between the two cracks do (`holder` is the real
        // tet whose side `t` is on: itself, or the tet a ghost's triangle bounds). A tet
        // not seen above is put in or out of the wedge at the positions the cut decided
        // at: `at` (the pool at rest, new vertices included), or a deformed body's.
        let frame_at: Option<Vec<DVec3>> = deformed.filter(|_| !turn.is_empty()).map(|p| {
            let mut at = p[..nv].to_vec();
            at.extend(origin_positions(p, &origins));
            at.extend(copies.iter().map(|v| p[v.idx()]));
            at
        });
        let for_side = |t: Tet, side: Side, holder: &Tet, at: &[DVec3]| -> Tet {
            let at = frame_at.as_deref().unwrap_or(at);
            t.map(|v| match copy_of.get(&v) {
                Some(&c) if turn_groups.contains_key(&v) => {
                    let keep = keeps.get(&(v, *holder)).copied().unwrap_or_else(|| {
                        turn.in_wedge(v, holder, side, &|u: VertexId| at[u.idx()])
                    });
                    if keep { v } else { c }
                }
                Some(&c) if side == Side::Negative => c,
                _ => v,
            })
        };

        // Sub-triangles of every subdivided face of a split tet, keyed by the face as the
        // tet sees it from inside (outward orientation): what a ghost on that face becomes.
        // Which faces of its parent (face `f` is opposite local vertex `f`) a child's
        // vertex lies on, as a bit mask: a vertex of the parent on the three others, a cut
        // point on the two holding its edge, a face point on its face. A child's face lies
        // in the parent's faces of the mask its three vertices share.
        let faces_under = |x: VertexId, parent: &Tet| -> u8 {
            let local = |y: VertexId| parent.iter().position(|&p| p == y);
            if let Some(j) = local(x) {
                return 0b1111 & !(1 << j);
            }
            if x < first_new {
                return 0;
            }
            let ends: &[VertexId] = match &origins[x.idx() - nv] {
                VertexOrigin::Edge { a, b, .. } => &[*a, *b],
                VertexOrigin::Face { v, .. } => v,
                VertexOrigin::Copy { .. } => return 0,
            };
            ends.iter()
                .try_fold(0b1111, |m, &y| local(y).map(|j| m & !(1 << j)))
                .unwrap_or(0)
        };
        // Only the ghosts' triangles are looked up (below, subdividing the ghosts): the
        // other faces of the split tets, most of them, are not listed.
        let ghost_faces: HashSet<FaceKey, FxBuild> = ghosts
            .iter()
            .map(|&g| {
                let t = mt.tet(TetId(g));
                oriented_face(t[0].0, t[1].0, t[2].0)
            })
            .collect();
        let mut sub_faces: HashMap<FaceKey, Vec<(Tet, Side, Tet)>, FxBuild> = HashMap::default();
        for (k, &i) in child_of.iter().enumerate() {
            if i == NONE {
                continue;
            }
            let ch = &children[i as usize];
            let parent = tets[k];
            let keys = TET_FACES.map(|lf| {
                let face = lf.map(|j| parent[j].0);
                oriented_face(face[0], face[1], face[2])
            });
            let wanted =
                keys.map(|key| ghost_faces.contains(&key) && !sub_faces.contains_key(&key));
            if wanted == [false; 4] {
                continue;
            }
            let mut subs: [Vec<(Tet, Side, Tet)>; 4] = Default::default();
            for c in 0..ch.len {
                let t = ch.tets[c];
                let under = t.map(|x| faces_under(x, &parent));
                for cf in TET_FACES {
                    let shared = under[cf[0]] & under[cf[1]] & under[cf[2]];
                    for f in (0..4).filter(|&f| shared & (1 << f) != 0 && wanted[f]) {
                        subs[f].push(([t[cf[0]], t[cf[1]], t[cf[2]], GHOST], ch.sides[c], t));
                    }
                }
            }
            for (f, list) in subs.into_iter().enumerate() {
                if wanted[f] && list.len() > 1 {
                    sub_faces.insert(keys[f], list);
                }
            }
        }
        // The side of the tets holding faces with a snapped vertex (for ghosts not
        // subdivided but touching a duplicated vertex).
        let mut face_side: HashMap<FaceKey, (Side, Tet), FxBuild> = HashMap::default();
        for (k, class) in classes.iter().enumerate() {
            if !class.touches_cut() {
                continue;
            }
            match child_of[k] {
                NONE => {
                    for f in faces_of(&tets[k]) {
                        face_side.insert(f, (unsplit_side(k), tets[k]));
                    }
                }
                i => {
                    let ch = &children[i as usize];
                    for c in 0..ch.len {
                        for f in faces_of(&ch.tets[c]) {
                            face_side.insert(f, (ch.sides[c], ch.tets[c]));
                        }
                    }
                }
            }
        }
        // An earlier crack's vertex on this plane outside C (`OUT`) is not cut, yet a crack
        // face of this cut can reach it: a crack continued in its plane joins the earlier
        // one there, the vertex's tets all on one side. Where the earlier crack lies in
        // another plane, the vertex has tets on both sides, and this crack's faces can
        // divide its tets on one lip in two: that mesh is pinched there, two fans of
        // boundary faces meeting at one point, which the fragments' floors and ceilings do
        // not show (measured: random partial cuts through the vertices of a Kuhn grid,
        // tests/mtcut_cut.rs, a cut in the plane x + y = 9 a second time). At each such
        // vertex the finest and the coarsest meshes are checked (the whole star, found
        // through the fragment hierarchy), and such a cut refused before the MT changes.
        {
            let is_out = |v: &VertexId| out_vertices.binary_search(v).is_ok();
            let level_bits = |t: TetId| {
                u8::from(mt.fragment_kind(mt.tet_creator(t)) == FragmentKind::Root)
                    | u8::from(mt.fragment_kind(mt.tet_destroyer(t)) == FragmentKind::Drain) << 1
            };
            // The candidates holding an `OUT` vertex, in the finest or the coarsest mesh
            // (levels: bit 0, bit 1).
            let holders: Vec<(usize, u8)> = (0..tets.len())
                .filter(|&k| finest[k] || coarsest[k])
                .filter(|&k| tets[k].iter().any(is_out))
                .map(|k| (k, u8::from(finest[k]) | u8::from(coarsest[k]) << 1))
                .collect();
            let side_bits = |s: Side| match s {
                Side::Positive => 1u8,
                Side::Negative => 2,
                Side::Straddle => 3,
            };
            // Calls `f(corner, vertex index in out_vertices, tet, side)` for each tet
            // candidate `k` becomes that holds its `OUT` vertex at `corner`, before the
            // tets take copies (which changes no face's being on the crack: a copy, like
            // its vertex, is on the cut).
            let each_at_out = |k: usize, f: &mut dyn FnMut(usize, usize, &Tet, Side)| {
                for (j, v) in tets[k].iter().enumerate() {
                    let Ok(i) = out_vertices.binary_search(v) else {
                        continue;
                    };
                    match child_of[k] {
                        NONE => f(j, i, &tets[k], unsplit_side(k)),
                        c => {
                            let ch = &children[c as usize];
                            for c in (0..ch.len).filter(|&c| ch.tets[c].contains(v)) {
                                let corner = ch.tets[c].iter().position(|x| x == v).unwrap_or(0);
                                f(corner, i, &ch.tets[c], ch.sides[c]);
                            }
                        }
                    }
                }
            };
            // Per `OUT` vertex and level: the sides of the tets holding it (bit 0 positive,
            // bit 1 negative).
            let mut sides = vec![[0u8; 2]; out_vertices.len()];
            for &(k, levels) in &holders {
                each_at_out(k, &mut |_, i, _, side| {
                    for l in (0..2).filter(|l| levels >> l & 1 != 0) {
                        sides[i][l] |= side_bits(side);
                    }
                });
            }
            // Those with tets on both sides where a crack face of this cut reaches them,
            // as (vertex, level bit).
            let mut check: Vec<(VertexId, u8)> = Vec::new();
            if sides.iter().flatten().any(|&s| s == 3) {
                for &(k, levels) in &holders {
                    each_at_out(k, &mut |j, i, t, _| {
                        for l in (0..2).filter(|l| levels >> l & 1 != 0 && sides[i][*l] == 3) {
                            // The faces at corner j: all but the one opposite it.
                            let reached = TET_FACES
                                .iter()
                                .enumerate()
                                .any(|(f, lf)| f != j && on_crack(lf.map(|x| t[x])));
                            if reached {
                                check.push((out_vertices[i], 1 << l));
                            }
                        }
                    });
                }
                check.sort_unstable();
                check.dedup();
            }
            if !check.is_empty() {
                let mut vertices: Vec<VertexId> = check.iter().map(|c| c.0).collect();
                vertices.dedup();
                let rest = mt.positions();
                let near = Aabb::from_points(vertices.iter().map(|v| &rest[v.idx()]));
                // (vertex, tet) for every real tet holding one of them.
                let mut holding: Vec<(VertexId, TetId)> = Vec::new();
                self.tets_meeting(
                    mt,
                    |b| b.intersects(&near),
                    |t| {
                        let tet = mt.tet(t);
                        if tet[3] != GHOST {
                            for &v in tet.iter().filter(|v| vertices.binary_search(v).is_ok()) {
                                holding.push((v, t));
                            }
                        }
                    },
                );
                holding.sort_unstable();
                // The positions `for_side` reads for a turning tip in a tet it has no
                // decision for (the pool's, new vertices included), made if needed.
                let at_rest: std::cell::OnceCell<Vec<DVec3>> = std::cell::OnceCell::new();
                let at = || -> &[DVec3] {
                    if turn.is_empty() {
                        return positions;
                    }
                    at_rest.get_or_init(|| {
                        let mut p = positions.to_vec();
                        p.extend(origin_positions(positions, &origins));
                        p.extend(copies.iter().map(|v| positions[v.idx()]));
                        p
                    })
                };
                for &(v, bit) in &check {
                    let from = holding.partition_point(|h| h.0 < v);
                    let star_tets = holding[from..].iter().take_while(|h| h.0 == v).map(|h| h.1);
                    let mut star: Vec<(Tet, Side)> = Vec::new();
                    for t in star_tets.filter(|&t| level_bits(t) & bit != 0) {
                        match cand.binary_search(&t) {
                            // What the cut makes of it, with the copies taken (an `OUT`
                            // vertex has none: the tets holding it still do).
                            Ok(k) => each_at_out(k, &mut |_, i, c, side| {
                                if out_vertices[i] == v {
                                    star.push((for_side(*c, side, c, at()), side));
                                }
                            }),
                            Err(_) => star.push((mt.tet(t), Side::Positive)),
                        }
                    }
                    if tip_fans(v, star.into_iter(), &|_, _, _| false)[0] > 1 {
                        let owner = holding[from].1;
                        return Err(CutError::MtInconsistent {
                            fragment: mt.tet_creator(owner).idx(),
                            detail: format!(
                                "its {} mesh would be pinched at vertex {}: this cut's crack \
                                 reaches it, on an earlier crack, and divides its tets",
                                if bit == 1 { "finest" } else { "coarsest" },
                                v.0
                            ),
                        });
                    }
                }
            }
        }
        let n_tets = mt.nb_tets();
        let created_total = stats.tets_created;
        if nv + stats.vertices_added > crate::mt::MAX_ELEMENTS
            || n_tets + created_total * 2 > crate::mt::MAX_ELEMENTS
        {
            return Err(CutError::TooLarge {
                max: crate::mt::MAX_ELEMENTS as u32,
            });
        }

        // Commit: from here on the MT changes.
        // The floor and ceiling of every fragment the DAG update may involve (creators and
        // destroyers of the candidates and ghosts, and the cracked fragments), as ranges
        // of the pool before the cut: a tet replaced in place keeps its index and its arc,
        // and appended tets are added to them later. What step 3 reads instead of a pass
        // over the pool.
        let mut spans: HashMap<u32, Spans, FxBuild> = HashMap::default();
        {
            let mut note = |f: FragmentId| {
                spans.entry(f.0).or_insert_with(|| Spans::of(mt, f));
            };
            for t in cand.iter().copied().chain(ghosts.iter().map(|&g| TetId(g))) {
                let a = mt.tet_arc(t);
                note(mt.arc_creator(a));
                note(mt.arc_destroyer(a));
            }
            for f in (0..self.cracked.len()).filter(|&f| self.cracked[f]) {
                note(FragmentId::from_usize(f));
            }
        }
        let roots_before = mt.roots().to_vec();
        let mut open: OpenMt = self
            .mt
            .take()
            .expect("MtCutter holds its MT")
            .open_with(self.links.take());
        // The DAG as it was before the cut, read in step 3 and given back before closing
        // (unchanged unless fragments split: then the closed MT derives it again).
        let dag = Reach {
            dag: open
                .take_dag()
                .expect("an MT opened by open_with keeps its DAG tables"),
        };
        let lengths = (self.scales.len(), self.crack.len());
        let new_positions = origin_positions(&open.positions, &origins);
        open.positions.extend(new_positions);
        push_origin_rows(&mut open.point_data, &mut self.scales, &origins);
        let crack_was: Vec<(VertexId, bool)> =
            copies.iter().map(|&v| (v, self.crack[v.idx()])).collect();
        self.crack.resize(open.positions.len(), true);
        for &v in &copies {
            let p = open.positions[v.idx()];
            open.positions.push(p);
            open.point_data.push_copy(v.idx());
            self.scales.push(self.scales[v.idx()]);
            self.crack[v.idx()] = true;
            self.crack.push(true);
        }
        // Real tets: children in place of their parents, unsplit tets on the negative side
        // take copies. `touched` lists every real tet the cut changed or may have made a
        // crack face of.
        let mut touched: Vec<u32> = Vec::new();
        let mut appended_parents: Vec<u32> = Vec::new();
        let mut replaced: Vec<Replaced> = Vec::new();
        let mut keep = |open: &OpenMt, t: usize, tet: Tet| {
            replaced.push((t as u32, tet, open.creator()[t], open.destroyer()[t]));
        };
        for (k, &parent) in cand.iter().enumerate() {
            match child_of[k] {
                NONE => {
                    if classes[k].touches_cut() {
                        let side = unsplit_side(k);
                        keep(&open, parent.idx(), tets[k]);
                        open.tets[parent.idx()] =
                            for_side(tets[k], side, &tets[k], &open.positions);
                        touched.push(parent.0);
                    }
                }
                i => {
                    let ch = &children[i as usize];
                    keep(&open, parent.idx(), tets[k]);
                    open.tets[parent.idx()] =
                        for_side(ch.tets[0], ch.sides[0], &ch.tets[0], &open.positions);
                    touched.push(parent.0);
                    let (c, d) = (open.creator()[parent.idx()], open.destroyer()[parent.idx()]);
                    for j in 1..ch.len {
                        touched.push(open.tets.len() as u32);
                        let child = for_side(ch.tets[j], ch.sides[j], &ch.tets[j], &open.positions);
                        open.push_tet(child, c, d);
                        appended_parents.push(parent.0);
                    }
                }
            }
        }
        open.cell_data.push_copies(&appended_parents);
        // Ghosts: subdivided with their triangle, or given the copies of their side.
        let mut ghost_touched: Vec<u32> = Vec::new();
        let mut appended_parents: Vec<u32> = Vec::new();
        let n_pool = open.tets.len();
        for &g in &ghosts {
            let g = g as usize;
            let tet = open.tets[g];
            let key = oriented_face(tet[0].0, tet[1].0, tet[2].0);
            if let Some(subs) = sub_faces.get(&key) {
                stats.ghosts_split += 1;
                let (c, d) = (open.creator()[g], open.destroyer()[g]);
                keep(&open, g, tet);
                open.tets[g] = for_side(subs[0].0, subs[0].1, &subs[0].2, &open.positions);
                ghost_touched.push(g as u32);
                for &(t, side, holder) in &subs[1..] {
                    ghost_touched.push(open.tets.len() as u32);
                    let sub = for_side(t, side, &holder, &open.positions);
                    open.push_tet(sub, c, d);
                    appended_parents.push(g as u32);
                }
            } else if tet[..3].iter().any(|v| around.contains_key(v)) {
                let (side, holder) = face_side
                    .get(&key)
                    .copied()
                    .unwrap_or((Side::Positive, tet));
                keep(&open, g, tet);
                open.tets[g] = for_side(tet, side, &holder, &open.positions);
                ghost_touched.push(g as u32);
            }
        }
        open.cell_data.push_copies(&appended_parents);
        // Crack faces: faces of changed tets, all of whose vertices lie on the cut, that no
        // tet or ghost able to coexist with them in a frontier matches. (A tet of another
        // level may hold the opposite face on the other side of the crack: snapping bends
        // the cut surface differently on each level.)
        // The tets and ghosts holding each crack face: the first in the map, the others
        // chained (`holders`: tet, next; u32::MAX ends), one allocation for all.
        let mut present: HashMap<FaceKey, u32, FxBuild> = HashMap::default();
        let mut holders: Vec<(u32, u32)> = Vec::new();
        // Per touched tet, its faces on the crack as `on_crack` finds them (bit `i`: the
        // face opposite corner `i`, as `TET_FACES` lists them), from one look-up per
        // corner instead of three per face.
        let crack_faces = |t: &Tet| -> u8 {
            let marks = t.map(crack_mark);
            (0..4)
                .filter(|&i| marks_on_crack(TET_FACES[i].map(|j| marks[j])))
                .fold(0, |m, i| m | 1 << i)
        };
        let touched_crack: Vec<u8> = touched
            .iter()
            .map(|&t| crack_faces(&open.tets[t as usize]))
            .collect();
        let nb_crack_faces: u32 = touched_crack.iter().map(|m| m.count_ones()).sum();
        present.reserve(nb_crack_faces as usize);
        holders.reserve(nb_crack_faces as usize);
        let mut hold = |f: FaceKey, t: u32| {
            let at = holders.len() as u32;
            let next = present.insert(f, at).unwrap_or(u32::MAX);
            holders.push((t, next));
        };
        for (&t, &on) in touched.iter().zip(&touched_crack) {
            let tet = open.tets[t as usize];
            for (i, lf) in TET_FACES.iter().enumerate() {
                if on & (1 << i) != 0 {
                    hold(oriented_face(tet[lf[0]].0, tet[lf[1]].0, tet[lf[2]].0), t);
                }
            }
        }
        for &g in &ghost_touched {
            let t = open.tets[g as usize];
            if on_crack([t[0], t[1], t[2]]) {
                hold(flip_face(oriented_face(t[0].0, t[1].0, t[2].0)), g);
            }
        }
        let coexist = |a: usize, b: usize| {
            !dag.reaches(open.destroyer()[a], open.creator()[b])
                && !dag.reaches(open.destroyer()[b], open.creator()[a])
        };
        let mut crack: Vec<(Tet, FragmentId, FragmentId)> = Vec::new();
        for (&t, &on) in touched.iter().zip(&touched_crack) {
            let tet = open.tets[t as usize];
            for (i, lf) in TET_FACES.iter().enumerate() {
                if on & (1 << i) == 0 {
                    continue;
                }
                let f = oriented_face(tet[lf[0]].0, tet[lf[1]].0, tet[lf[2]].0);
                let mut at = present.get(&flip_face(f)).copied().unwrap_or(u32::MAX);
                let mut matched = false;
                while at != u32::MAX && !matched {
                    let (o, next) = holders[at as usize];
                    matched = coexist(t as usize, o as usize);
                    at = next;
                }
                if !matched {
                    let g = [tet[lf[0]], tet[lf[1]], tet[lf[2]], GHOST];
                    crack.push((g, open.creator()[t as usize], open.destroyer()[t as usize]));
                    ghost_touched.push((n_pool + appended_parents.len() + crack.len() - 1) as u32);
                }
            }
        }
        stats.crack_ghosts = crack.len();
        for (g, c, d) in crack {
            open.push_tet(g, c, d);
        }
        open.cell_data.push_zeros(stats.crack_ghosts);
        stats.time.split = t_split.elapsed().as_secs_f64();

        // Step 3: split every involved fragment by the components of its floor and ceiling.
        let t_dag = Instant::now();
        let nf = open.kind.len();
        // (A cut that changed no tet separates nothing: then no fragment is involved.)
        let changed_any = !touched.is_empty() || !ghost_touched.is_empty();
        let mut involved: Vec<bool> = vec![false; nf];
        for &t in touched.iter().chain(&ghost_touched) {
            involved[open.creator()[t as usize].idx()] = true;
            involved[open.destroyer()[t as usize].idx()] = true;
        }
        // A root (its ceiling is a whole finest mesh) that was one part stays one part
        // when what the cut made of its tets is one piece (joined through shared
        // vertices: the lips of a crack through a tip, never duplicated): every other tet
        // of it shares a vertex with that piece or with tets that do, as before the cut
        // (a vertex the cut duplicated lies on the cut, so every tet holding it is a
        // changed one). It then takes part like a fragment not involved, without a pass
        // over its ceiling; otherwise (a cut separating the finest mesh, say) it is split
        // like the others.
        let mut whole_roots = 0;
        // Whether every root is one part after the cut (cracked roots are not).
        let mut roots_whole = true;
        let pieces = &mut self.pieces;
        pieces.fit(open.positions.len());
        for &r in &roots_before {
            if self.cracked.get(r.idx()).copied().unwrap_or(false) {
                roots_whole = false;
                continue;
            }
            if !involved[r.idx()] {
                continue;
            }
            let made: Vec<u32> = touched
                .iter()
                .chain(&ghost_touched)
                .copied()
                .filter(|&t| open.creator()[t as usize] == r)
                .collect();
            if !pieces.one_piece(&open.tets, made.iter().copied()) {
                roots_whole = false;
            } else {
                involved[r.idx()] = false;
                whole_roots += 1;
                debug_assert!(
                    {
                        let ceiling: Vec<u32> = (0..open.tets.len() as u32)
                            .filter(|&t| open.creator()[t as usize] == r)
                            .collect();
                        let mut scratch = Pieces::new(open.positions.len());
                        split_fragment(&open.tets, &open.positions, &[], &ceiling, &mut scratch)
                            .iter()
                            .all(|&p| p == 0)
                    },
                    "root {r} taken whole, but its ceiling is in several parts"
                );
            }
        }
        // The cracked fragments the cut did not touch take part only when a root is no
        // longer one part. While every root is one part, nothing is separated: each part
        // of a fragment has floor tets (its region's lower side), whose creators' parts
        // have theirs, down to a root's ceiling, so every part lies in the body of the
        // root it lay in before, and no fragment splits. Their parts, which the cut did
        // not change, are then not read again (on a scalpel's later steps most of the
        // fragments cracked so far: a DAG step growing with the incision's length).
        if changed_any && !roots_whole {
            for (f, &c) in self.cracked.iter().enumerate() {
                involved[f] |= c;
            }
        }
        let mut order: Vec<FragmentId> = (0..nf)
            .filter(|&f| involved[f])
            .map(FragmentId::from_usize)
            .collect();
        if let Some(key) = key {
            order.sort_by_key(|&f| (key(f), f));
        }
        stats.fragments_involved = order.len() + whole_roots;
        let mut slot = vec![u32::MAX; nf];
        for (i, f) in order.iter().enumerate() {
            slot[f.idx()] = i as u32;
        }
        // Bodies: the fragments, and the parts below, joined through the tets between them
        // (the arcs). Between fragments not involved, the arcs before the cut still hold:
        // joined only when the parts' own tets leave some fragment's parts apart (below),
        // as a pass over every arc of the DAG costs more than the rest of a small cut on a
        // large MT.
        let mut body: Vec<u32> = (0..nf as u32).collect();
        // Floor and ceiling of each involved fragment, in pool order: its ranges before
        // the cut, then the tets appended.
        let mut floor: Vec<Vec<u32>> = Vec::with_capacity(order.len());
        let mut ceiling: Vec<Vec<u32>> = Vec::with_capacity(order.len());
        for f in &order {
            let s = &spans[&f.0];
            ceiling.push(s.ceiling.clone().map(|t| t as u32).collect());
            floor.push(
                s.floor
                    .iter()
                    .flat_map(|r| r.clone().map(|t| t as u32))
                    .collect(),
            );
        }
        for t in n_tets..open.tets.len() {
            let (c, d) = (
                slot[open.creator()[t].idx()],
                slot[open.destroyer()[t].idx()],
            );
            if c != u32::MAX {
                ceiling[c as usize].push(t as u32);
            }
            if d != u32::MAX {
                floor[d as usize].push(t as u32);
            }
        }
        // The local parts of each involved fragment, each with a provisional id after the
        // fragments': `first_part[i] + p` for part `p` of fragment `order[i]`.
        let mut parts: Vec<Vec<u32>> = Vec::with_capacity(order.len());
        let mut first_part: Vec<u32> = Vec::with_capacity(order.len() + 1);
        let mut next = nf as u32;
        for i in 0..order.len() {
            let p = split_fragment(&open.tets, &open.positions, &floor[i], &ceiling[i], pieces);
            first_part.push(next);
            next += p.iter().map(|&x| x + 1).max().unwrap_or(1);
            parts.push(p);
        }
        first_part.push(next);
        // Parts of one fragment that stay in one body are not separated (see the module
        // docs): only parts in different bodies become different fragments.
        body.extend(nf as u32..next);
        // Each tet joins the part above it (in its creator's ceiling) to the part below it
        // (in its destroyer's floor); a fragment not involved is its own part. Floors
        // first: the part below each tet whose creator is involved too, for the ceilings.
        let mut below_of: HashMap<u32, u32, FxBuild> = HashMap::default();
        for (i, list) in floor.iter().enumerate() {
            for (j, &t) in list.iter().enumerate() {
                let below = first_part[i] + parts[i][j];
                let c = open.creator()[t as usize];
                if slot[c.idx()] == u32::MAX {
                    union(&mut body, c.0, below);
                } else {
                    below_of.insert(t, below);
                }
            }
        }
        for (i, list) in ceiling.iter().enumerate() {
            let nfl = floor[i].len();
            for (j, &t) in list.iter().enumerate() {
                let above = first_part[i] + parts[i][nfl + j];
                let below = match below_of.get(&t) {
                    Some(&b) => b,
                    None => open.destroyer()[t as usize].0,
                };
                union(&mut body, above, below);
            }
        }
        // Parts joined through the tets of the involved fragments lie in one body whatever
        // the rest of the DAG says; parts left apart may still be joined through fragments
        // not involved.
        let apart = (0..order.len()).any(|i| {
            let root = find(&mut body, first_part[i]);
            (first_part[i] + 1..first_part[i + 1]).any(|p| find(&mut body, p) != root)
        });
        if apart {
            for f in 0..dag.dag.level.len() {
                if !involved[f] {
                    for g in dag.succ(f).filter(|&g| !involved[g as usize]) {
                        union(&mut body, f as u32, g);
                    }
                }
            }
        }
        let cracked_was = self.cracked.clone();
        self.cracked.resize(nf, false);
        let mut split: Vec<FragmentId> = Vec::new();
        // The fragment each added fragment was split off.
        let mut born: Vec<FragmentId> = Vec::new();
        for (i, &f) in order.iter().enumerate() {
            let n_parts = first_part[i + 1] - first_part[i];
            self.cracked[f.idx()] = n_parts > 1;
            if n_parts < 2 {
                continue;
            }
            // Group the parts by body, numbered by first appearance.
            let mut group: Vec<u32> = Vec::with_capacity(n_parts as usize);
            let mut roots: Vec<u32> = Vec::new();
            for p in 0..n_parts {
                let r = find(&mut body, first_part[i] + p);
                let g = match roots.iter().position(|&x| x == r) {
                    Some(g) => g,
                    None => {
                        roots.push(r);
                        roots.len() - 1
                    }
                };
                group.push(g as u32);
            }
            let n_groups = roots.len() as u32;
            if n_groups < 2 {
                continue;
            }
            // Each new fragment is cracked when its group holds several parts.
            let mut sizes = vec![0u32; n_groups as usize];
            for &g in &group {
                sizes[g as usize] += 1;
            }
            self.cracked[f.idx()] = sizes[0] > 1;
            self.cracked.extend(sizes[1..].iter().map(|&n| n > 1));
            stats.fragments_split += 1;
            split.push(f);
            let first_new_fragment = open.kind.len() as u32;
            for _ in 1..n_groups {
                let n = open.kind.len();
                open.kind.push(open.kind[f.idx()]);
                open.error.push(open.error[f.idx()]);
                // Chained after `f`: found through `f`'s hierarchy entry.
                debug_assert_eq!(self.split_off.len(), n);
                self.split_off.push(self.split_off[f.idx()]);
                self.split_off[f.idx()] = n as u32;
                born.push(f);
            }
            stats.fragments_added += (n_groups - 1) as usize;
            let id = |p: u32| match group[p as usize] {
                0 => f,
                g => FragmentId(first_new_fragment + g - 1),
            };
            let nfl = floor[i].len();
            for (j, &t) in floor[i].iter().enumerate() {
                let g = id(parts[i][j]);
                if g != f {
                    open.set_destroyer(t as usize, g);
                }
            }
            for (j, &t) in ceiling[i].iter().enumerate() {
                let g = id(parts[i][nfl + j]);
                if g != f {
                    open.set_creator(t as usize, g);
                }
            }
        }
        debug_assert!(
            !roots_whole || split.is_empty(),
            "every root is one part, yet fragments {split:?} split"
        );
        // The MT condition (paper §2: a fragment's floor and ceiling bound the same region)
        // where the cut changed it. A cut breaking it is given back and refused, never left
        // in the MT: cuts the engine does not handle yet (see the module docs' limits) get
        // an error instead of an invalid MT.
        let changed = Changed {
            n_tets,
            nf,
            nv,
            replaced: &replaced,
            born: &born,
        };
        // Every extraction's star at the vertices this cut put on its surface (the
        // finest and coarsest meshes were analysed when deciding their copies; the meshes
        // between can still be pinched there: `pinched_between`).
        let problem = changed.flat(&open).or_else(|| changed.hanging(&open));
        *snap_may_help = problem.is_some();
        let problem = problem
            .or_else(|| changed.check(&open, &order, &floor, &ceiling).err())
            .or_else(|| {
                let mut on_surface: Vec<VertexId> =
                    snapped.iter().chain(copy_of.values()).copied().collect();
                on_surface.sort_unstable();
                pinched_between(&open, &dag, |f| changed.origin(f), &on_surface, &touched).map(
                    |(f, v)| {
                        let detail = format!(
                            "an extraction between its finest and coarsest meshes would be \
                         pinched at vertex {}: crack faces around it in separate fans",
                            v.0
                        );
                        (f.idx(), detail)
                    },
                )
            });
        if let Some((fragment, detail)) = problem {
            drop(floor);
            drop(ceiling);
            self.give_back(
                open,
                GivenBack {
                    nv,
                    lengths,
                    replaced,
                    born,
                    crack_was,
                    cracked: cracked_was,
                },
                n_tets,
                nf,
                dag.dag,
            );
            return Err(CutError::MtInconsistent { fragment, detail });
        }
        // A tet the tables replaced is tiled by its children (a ghost's triangle by its
        // sub-triangles; crack ghosts lie inside): only a fragment that gave tets to the
        // fragments split off it has a new box (and those, added, get theirs), or one
        // that a new point rounded past (closing checks the tets written).
        open.changed_fragments = Some(split.iter().map(|f| f.0).collect());
        // Every tet written in place was kept for giving back: those and the appended ones
        // are the tets whose vertex ids closing checks.
        open.written_tets = Some(replaced.iter().map(|r| r.0).collect());
        open.restore_dag(dag.dag);
        let (mt, links) = open
            .close_keeping_links()
            .unwrap_or_else(|e| panic!("the MT cut left an inconsistent store: {e}"));
        self.links = Some(links);
        // A cut splitting no fragment keeps every arc: the components stay.
        if stats.fragments_split > 0 {
            self.components = mt.nb_components();
        }
        debug_assert_eq!(
            self.components,
            mt.nb_components(),
            "the components counted before a cut that split no fragment changed"
        );
        stats.components = self.components;
        self.mt = Some(mt);
        let taken = turn.taken();
        made.record(
            polygon,
            nv,
            &origins,
            &copies,
            taken,
            frames.before(nv as u32),
        );
        self.last_origins = origins;
        self.last_origins
            .extend(copies.iter().map(|&of| VertexOrigin::Copy { of }));
        stats.time.dag = t_dag.elapsed().as_secs_f64();
        stats.time.total = start.elapsed().as_secs_f64();
        Ok(stats)
    }
}

/// The snapped vertices of a cut that are tips of an earlier crack made at an angle to it
/// (paper §5's scalpel turning or tilting between steps): the new polygon begins on the
/// line where the earlier one ended, and that crack's tips on the line lie on both planes.
/// Around such a tip the two cracks together divide the tets into a wedge — on the side
/// of the earlier plane where the new polygon lies and on the side of the new plane where
/// the earlier polygon lies — and the rest; the tip takes one copy for the rest. Each tet's
/// group follows from its side of the new cut and its vertices' sides of the earlier plane
/// (`in_wedge`), the same on every level.
struct TurnTips<'a> {
    /// Per turning tip: the cut that made it (in `made`), its polygon, and the wedge's
    /// side of each plane.
    tips: HashMap<VertexId, (u32, &'a CutPolygon, Sign, Sign), FxBuild>,
    made: &'a Made,
    /// Points this close to a plane are on it: the tips and the earlier crack's lips lie
    /// on it up to rounding.
    tolerance: f64,
}

impl<'a> TurnTips<'a> {
    /// The turning tips among the vertices on the cut (`ON`) of the candidates `tets`
    /// (vertex states `states`), made by the `turning` cuts.
    fn new(
        tets: &[Tet],
        states: &[[u8; 4]],
        turning: &[Turning],
        made: &'a Made,
        tolerance: f64,
    ) -> TurnTips<'a> {
        let mut tips: HashMap<VertexId, (u32, &CutPolygon, Sign, Sign), FxBuild> =
            HashMap::default();
        if !turning.is_empty() {
            let on_cut = tets
                .iter()
                .zip(states)
                .flat_map(|(t, st)| (0..4).filter(|&j| st[j] == ON).map(|j| t[j]));
            for v in on_cut {
                let Some((i, TIP)) = made.kind(v) else {
                    continue;
                };
                if let Some(t) = turning.iter().find(|t| t.cut == i) {
                    let old = &made.cuts[i as usize].polygon;
                    tips.insert(v, (i, old, t.s_old, t.s_new));
                }
            }
        }
        TurnTips {
            tips,
            made,
            tolerance,
        }
    }

    fn is_empty(&self) -> bool {
        self.tips.is_empty()
    }

    fn has(&self, v: VertexId) -> bool {
        self.tips.contains_key(&v)
    }

    /// The turning tips, sorted: what the cut took onto its crack ([`MadeBy::taken`]).
    fn taken(&self) -> Vec<VertexId> {
        let mut taken: Vec<VertexId> = self.tips.keys().copied().collect();
        taken.sort_unstable();
        taken
    }

    /// Whether tet `t`, holding turning tip `v` and on `side` of this cut, lies in the
    /// wedge between the two cracks: on the wedge's side of this cut (a tet crossed by
    /// its plane outside C lies beyond the earlier crack, outside), and with every other
    /// vertex on the wedge's side of the earlier polygon's plane or on it — a lip vertex
    /// of the earlier crack by the lip it is on (lips lie in that plane, where positions
    /// would decide by rounding), any other by its position. The wedge is convex and no
    /// tet crosses a crack, so the tet's corner at `v` lies in it when every edge from `v`
    /// does.
    fn in_wedge(&self, v: VertexId, t: &Tet, side: Side, pos: &impl Fn(VertexId) -> DVec3) -> bool {
        let (i, old, s_old, s_new) = self.tips[&v];
        let new_side = match side {
            Side::Positive => Sign::Positive,
            Side::Negative => Sign::Negative,
            Side::Straddle => return false,
        };
        if new_side != s_new {
            return false;
        }
        // The tet's corner at `v` lies in the wedge when every edge from `v` does: the
        // wedge is convex, and no tet crosses a crack.
        t.iter().filter(|&&u| u != GHOST && u != v).all(|&u| {
            let a = match self.made.kind(u) {
                Some((j, LIP_POSITIVE)) if j == i => Sign::Positive,
                Some((j, LIP_NEGATIVE)) if j == i => Sign::Negative,
                // The earlier crack bent through the tips it took (and their copies), up
                // to the tip reach off its plane: on that crack, where positions would
                // put them on a side.
                Some((j, JUNCTION)) if j == i => Sign::Zero,
                _ if self.made.cuts[i as usize].took(u) => Sign::Zero,
                _ => {
                    let d = old.signed_distance(pos(u));
                    if d.abs() <= self.tolerance {
                        Sign::Zero
                    } else if d > 0.0 {
                        Sign::Positive
                    } else {
                        Sign::Negative
                    }
                }
            };
            a == Sign::Zero || a == s_old
        })
    }
}

/// A tet holding a turning tip, among the tets the cut leaves (a split tet's children).
struct TipHolder {
    tip: VertexId,
    tet: Tet,
    side: Side,
    /// Inside the wedge between the earlier crack and this one, by position.
    in_wedge: bool,
    /// Bit 0: the tet is in the finest mesh; bit 1: in the coarsest.
    levels: u8,
    /// The fragment that created it, named when the cut is refused.
    owner: FragmentId,
}

impl TipHolder {
    /// Its faces at the tip.
    fn faces(&self) -> impl Iterator<Item = FaceKey> + '_ {
        faces_of(&self.tet)
            .into_iter()
            .filter(|f| f.contains(&self.tip.0))
    }
}

/// The boundary fans at turning tip `v` in `star` (the tets of one mesh holding it, with
/// their sides of the cut), once each tet takes the copies it will (`copy`: whether tet
/// `t` on a side takes vertex `u`'s copy): per vertex, the tip and its copy, how many
/// separate chains the edges opposite it in the boundary faces around it form (more than
/// one: the mesh is pinched there).
fn tip_fans(
    v: VertexId,
    star: impl Iterator<Item = (Tet, Side)>,
    copy: &impl Fn(VertexId, &Tet, Side) -> bool,
) -> [usize; 2] {
    let mut links: [Vec<(u64, u64)>; 2] = Default::default();
    for (t, side) in star {
        // A vertex as it will be: its id, and whether it is the copy.
        let m = t.map(|u| u64::from(u.0) << 1 | u64::from(copy(u, &t, side)));
        for lf in TET_FACES {
            let [a, b, c] = lf.map(|j| m[j]);
            let (x, edge) = if a >> 1 == u64::from(v.0) {
                (a, (b, c))
            } else if b >> 1 == u64::from(v.0) {
                (b, (c, a))
            } else if c >> 1 == u64::from(v.0) {
                (c, (a, b))
            } else {
                continue;
            };
            links[(x & 1) as usize].push(edge);
        }
    }
    links.map(|mut edges| {
        edges.sort_unstable();
        let boundary: Vec<(u64, u64)> = edges
            .iter()
            .filter(|&&(a, b)| edges.binary_search(&(b, a)).is_err())
            .copied()
            .collect();
        let mut ends: Vec<u64> = boundary.iter().flat_map(|&(a, b)| [a, b]).collect();
        ends.sort_unstable();
        ends.dedup();
        let at = |x: u64| ends.binary_search(&x).unwrap_or(0) as u32;
        let mut parent: Vec<u32> = (0..ends.len() as u32).collect();
        for &(a, b) in &boundary {
            union(&mut parent, at(a), at(b));
        }
        (0..ends.len() as u32)
            .filter(|&i| find(&mut parent, i) == i)
            .count()
    })
}

/// What step 1 of a cut found a pool tet to be.
enum Met {
    /// A ghost whose triangle meets the polygon's neighbourhood.
    Ghost,
    /// A ghost that does not.
    No,
    /// A tet tested and not a candidate.
    Tested,
    /// A candidate, with its vertices' states.
    Candidate([u8; 4]),
}

/// Down-closed fragment sets examined per vertex by [`pinched_between`] at most: the
/// others of a vertex whose tets span more levels are not examined.
const MAX_STAR_SETS: usize = 1 << 14;

/// The first of `vertices` (the vertices a cut put on its surface, and their copies; the
/// real tets around them among `touched`) that some extraction of the opened MT would
/// leave pinched (crack faces around it in separate fans), with a fragment creating a tet
/// around it. The finest and coarsest meshes are analysed before the cut decides its
/// copies; the meshes between are examined here, after the DAG update: a vertex's star in
/// an extraction is the tets around it whose creator is applied and whose destroyer is
/// not, so the stars of the extractions are those of the down-closed sets of the
/// fragments around the vertex (the root applied, the drain not). The order is the DAG's
/// before the cut (`dag`), read through the fragment each one was split off (`origin`):
/// a cut only removes arcs between the parts it splits a fragment into, so every set
/// closed under that order is an extraction's; a pinch needing two parts of ordered
/// fragments applied apart is not seen. (The order of the vertex's own tets alone, each
/// creator before its destroyer, was tried: it admits sets no extraction has, and refused
/// cuts of the 50-cut random sequences on pinion and liver whose every extraction was
/// valid.) Cost: timed around its call over the scalpel bench's direct sweep of fandisk
/// (100 steps, 80 cuts, 88,914 vertices examined), 0.30–0.38 s of a 4.7–5.7 s sweep, about
/// 4 µs per vertex and 7 % of a step; the sweep with the check skipped took 0.2–0.8 s less
/// in four alternated runs. Two rewrites were measured and dropped, as they changed
/// nothing: searching each fragment's successors once per cut instead of once per vertex,
/// and counting a set's fans from precomputed face pairs instead of sorting its faces
/// (callgrind: 7.78 → 7.83 G instructions for 40 steps). The frontier-first step does not
/// run it.
fn pinched_between(
    open: &OpenMt,
    dag: &Reach,
    origin: impl Fn(FragmentId) -> FragmentId,
    vertices: &[VertexId],
    touched: &[u32],
) -> Option<(FragmentId, VertexId)> {
    if vertices.is_empty() {
        return None;
    }
    let (creator, destroyer) = (open.creator(), open.destroyer());
    // Every tet around a vertex on the cut touches the cut: `touched` (the real tets the
    // cut changed or may have made a crack face of) holds them all.
    let mut around: Vec<(VertexId, u32)> = Vec::new();
    for &t in touched {
        for &v in &open.tets[t as usize] {
            if vertices.binary_search(&v).is_ok() {
                around.push((v, t));
            }
        }
    }
    around.sort_unstable();
    let level = &dag.dag.level;
    for run in around.chunk_by(|a, b| a.0 == b.0) {
        let v = run[0].0;
        let tets: Vec<u32> = run.iter().map(|r| r.1).collect();
        let mut frags: Vec<FragmentId> = tets
            .iter()
            .flat_map(|&t| [creator[t as usize], destroyer[t as usize]])
            .collect();
        frags.sort_unstable();
        frags.dedup();
        let at = |f: FragmentId| frags.binary_search(&f).unwrap_or(0);
        let n = frags.len();
        let kinds: Vec<FragmentKind> = frags.iter().map(|f| open.kind[f.idx()]).collect();
        let origins: Vec<FragmentId> = frags.iter().map(|&f| origin(f)).collect();
        // before[j]: the collapse fragments around the vertex that fragment j depends on
        // (the root is always applied, the drain never: neither constrains the others).
        let top = origins.iter().map(|f| level[f.idx()]).max().unwrap_or(0);
        let mut before: Vec<Vec<usize>> = vec![Vec::new(); n];
        for i in (0..n).filter(|&i| kinds[i] == FragmentKind::Collapse) {
            let mut seen: HashSet<u32, FxBuild> = HashSet::default();
            let mut stack = vec![origins[i].0];
            while let Some(f) = stack.pop() {
                for g in dag.succ(f as usize) {
                    if level[g as usize] <= top && seen.insert(g) {
                        stack.push(g);
                    }
                }
            }
            for j in 0..n {
                if kinds[j] == FragmentKind::Collapse
                    && origins[j] != origins[i]
                    && seen.contains(&origins[j].0)
                {
                    before[j].push(i);
                }
            }
        }
        // Decided in an order where a fragment comes after those it depends on.
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by_key(|&i| (kinds[i] != FragmentKind::Root, level[origins[i].idx()]));
        let mut applied = vec![false; n];
        let mut budget = MAX_STAR_SETS;
        let mut pinched_star = |applied: &[bool]| {
            let star = tets.iter().filter_map(|&t| {
                let (c, d) = (at(creator[t as usize]), at(destroyer[t as usize]));
                (applied[c] && !applied[d]).then_some((open.tets[t as usize], Side::Positive))
            });
            tip_fans(v, star, &|_: VertexId, _: &Tet, _: Side| false)[0] > 1
        };
        let sets = StarSets {
            order: &order,
            before: &before,
            kinds: &kinds,
        };
        if sets.any(0, &mut applied, &mut budget, &mut pinched_star) {
            return Some((creator[tets[0] as usize], v));
        }
    }
    None
}

/// The sets of fragments around a vertex closed under an order ([`pinched_between`]).
struct StarSets<'a> {
    /// The fragments (indices), each after those it needs.
    order: &'a [usize],
    /// Per fragment, those that must be applied with it.
    before: &'a [Vec<usize>],
    kinds: &'a [FragmentKind],
}

impl StarSets<'_> {
    /// Whether `found` holds for some closed set deciding `order[k..]` after `applied`
    /// (`budget`: the sets left to examine; none when it runs out).
    fn any(
        &self,
        k: usize,
        applied: &mut [bool],
        budget: &mut usize,
        found: &mut impl FnMut(&[bool]) -> bool,
    ) -> bool {
        if *budget == 0 {
            return false;
        }
        let Some(&i) = self.order.get(k) else {
            *budget -= 1;
            return found(applied);
        };
        let kind = self.kinds[i];
        if kind != FragmentKind::Root && self.any(k + 1, applied, budget, found) {
            return true;
        }
        if kind != FragmentKind::Drain && self.before[i].iter().all(|&x| applied[x]) {
            applied[i] = true;
            let hit = self.any(k + 1, applied, budget, found);
            applied[i] = false;
            return hit;
        }
        false
    }
}

/// Kinds of the vertices a cut appended, as `Made` keeps them.
const TIP: u8 = 0;
const LIP_POSITIVE: u8 = 1;
const LIP_NEGATIVE: u8 = 2;
/// A turning tip's copy: where two cracks meet, on no lip.
const JUNCTION: u8 = 3;
const _: () = assert!(JUNCTION < crate::mt::history::KINDS);

impl MadeBy {
    fn took(&self, v: VertexId) -> bool {
        self.taken.binary_search(&v).is_ok()
    }
}

impl Made {
    /// Keeps what a cut by `polygon` appended from vertex `first`: `origins`, then a copy
    /// of each of `copies`; `taken`: the turning tips it took (sorted). Its plane joins the
    /// planes kept unless it lies in one of them.
    fn record(
        &mut self,
        polygon: &CutPolygon,
        first: usize,
        origins: &[VertexOrigin],
        copies: &[VertexId],
        taken: Vec<VertexId>,
        frame: u64,
    ) {
        if origins.is_empty() && copies.is_empty() {
            return;
        }
        let kinds = origins
            .iter()
            .map(|o| match o {
                VertexOrigin::Face { .. } => TIP,
                VertexOrigin::Edge { positive: true, .. } => LIP_POSITIVE,
                VertexOrigin::Edge { .. } => LIP_NEGATIVE,
                VertexOrigin::Copy { .. } => JUNCTION,
            })
            .chain(copies.iter().map(|&of| {
                if taken.binary_search(&of).is_ok() {
                    JUNCTION
                } else {
                    LIP_NEGATIVE
                }
            }))
            .collect();
        self.cuts.push(MadeBy {
            polygon: polygon.clone(),
            frame,
            first: first as u32,
            kinds,
            taken,
        });
        if self.cuts.len() > Made::RECENT {
            self.cuts.remove(0);
        }
        if frame == AT_REST {
            self.keep_plane(polygon);
        }
    }

    /// `polygon` moved onto the plane of an earlier crack it lies close to, within
    /// `distance`, without lying in it ([`snap_to_plane`]).
    fn near_plane(&self, polygon: &CutPolygon, distance: f64) -> Option<CutPolygon> {
        snap_to_plane(polygon, self.planes.iter().map(|&[n, p]| (n, p)), distance)
    }

    /// The cut that appended `v` (an index in `cuts`) and its kind, if a kept cut did.
    fn kind(&self, v: VertexId) -> Option<(u32, u8)> {
        let i = self
            .cuts
            .partition_point(|c| c.first <= v.0)
            .checked_sub(1)?;
        let c = &self.cuts[i];
        c.kinds
            .get((v.0 - c.first) as usize)
            .map(|&k| (i as u32, k))
    }

    /// The kept cuts (the last [`Made::RECENT`]) whose polygon `polygon` continues at an
    /// angle (`turns_from`), among those made in the frame `frame(first)` gives for a
    /// cut's first vertex (asked in increasing order).
    fn turning(
        &self,
        polygon: &CutPolygon,
        scale: f64,
        mut frame: impl FnMut(u32) -> u64,
    ) -> Vec<Turning> {
        (0..self.cuts.len() as u32)
            .filter(|&cut| {
                let c = &self.cuts[cut as usize];
                c.frame == frame(c.first)
            })
            .filter_map(|cut| {
                let (s_old, s_new) = turns_from(&self.cuts[cut as usize].polygon, polygon, scale)?;
                Some(Turning { cut, s_old, s_new })
            })
            .collect()
    }

    /// The tips cut `i` made.
    fn tips(&self, i: u32) -> impl Iterator<Item = VertexId> + '_ {
        let c = &self.cuts[i as usize];
        (0..c.kinds.len())
            .filter(|&k| c.kinds[k] == TIP)
            .map(move |k| VertexId(c.first + k as u32))
    }
}

/// [`MadeBy::frame`] of a cut made at rest.
const AT_REST: u64 = 0;

/// The frames of cuts ([`MadeBy::frame`]) as the positions a cut decides at see them: at
/// rest, [`AT_REST`]; deformed, a fingerprint of the positions of the vertices before a
/// cut's first (never `AT_REST`), so that a later cut in the same deformed frame (the
/// body not moved since: a placement extended by the cuts between, see
/// [`super::live`]) finds the earlier one in its frame. Asked for prefixes of growing
/// length, it reads each position once.
struct Frames<'p> {
    deformed: Option<&'p [DVec3]>,
    hash: u64,
    read: usize,
}

impl<'p> Frames<'p> {
    fn new(deformed: Option<&'p [DVec3]>) -> Frames<'p> {
        Frames {
            deformed,
            hash: 0xcbf2_9ce4_8422_2325,
            read: 0,
        }
    }

    /// The frame seen by the vertices before `first` (not below an earlier call's).
    fn before(&mut self, first: u32) -> u64 {
        let Some(p) = self.deformed else {
            return AT_REST;
        };
        let end = (first as usize).min(p.len());
        debug_assert!(end >= self.read, "frames asked for growing prefixes");
        for x in p[self.read.min(end)..end].iter().flat_map(|v| v.to_array()) {
            self.hash = (self.hash ^ x.to_bits())
                .wrapping_mul(0x0000_0100_0000_01b3)
                .rotate_left(17);
        }
        self.read = self.read.max(end);
        self.hash | 1
    }
}

/// The sides of the wedge between an earlier crack (`old`) and a cut continuing it at an
/// angle (`new`): the side of the old plane where the new polygon lies, and of the new
/// plane where the old polygon lies (by their centroids).
fn wedge_sides(old: &CutPolygon, new: &CutPolygon) -> (Sign, Sign) {
    let centroid =
        |p: &CutPolygon| p.points().iter().copied().sum::<DVec3>() / p.points().len() as f64;
    (old.side(centroid(new)), new.side(centroid(old)))
}

/// A kept cut that a new one continues at an angle, with the wedge's sides (`wedge_sides`).
struct Turning {
    cut: u32,
    s_old: Sign,
    s_new: Sign,
}

/// The wedge's sides when `new` continues `old` at an angle: they share an edge (two
/// corners, to within `scale` × 1e-9) and their planes differ by more than rounding
/// (polygons meant to lie in one plane, a straight blade's steps, have normals apart by
/// ~1e-16: they continue in the plane, as before).
fn turns_from(old: &CutPolygon, new: &CutPolygon, scale: f64) -> Option<(Sign, Sign)> {
    if old.normal().cross(new.normal()).length() <= 1e-9 {
        return None;
    }
    let tolerance = 1e-9 * scale;
    let shared = old
        .points()
        .iter()
        .filter(|p| new.points().iter().any(|q| p.distance(*q) <= tolerance))
        .count();
    let (a, b) = wedge_sides(old, new);
    (shared >= 2 && a != Sign::Zero && b != Sign::Zero).then_some((a, b))
}

/// The fragment `g` comes from: itself when it is one of the `nf` before the cut, else
/// the one it was split off (`born`, in the order the cut appended them).
fn origin_of(g: FragmentId, nf: usize, born: &[FragmentId]) -> FragmentId {
    match g.idx().checked_sub(nf) {
        Some(k) => born[k],
        None => g,
    }
}

/// A pool tet a cut wrote in place: its index, and its tet, creator and destroyer before.
type Replaced = (u32, Tet, FragmentId, FragmentId);

/// What a cut changed in the opened MT, for checking the MT condition there
/// ([`Changed::check`]).
struct Changed<'a> {
    /// Pool tets, fragments and vertices before the cut: those after were appended.
    n_tets: usize,
    nf: usize,
    nv: usize,
    replaced: &'a [Replaced],
    /// The fragment each appended fragment was split off.
    born: &'a [FragmentId],
}

impl Changed<'_> {
    /// The fragment each fragment comes from: itself, or the one it was split off.
    fn origin(&self, g: FragmentId) -> FragmentId {
        origin_of(g, self.nf, self.born)
    }

    /// Scratch of [`Changed::check`] for one thread.
    fn check_scratch(&self) -> CheckScratch {
        (
            FaceCounts::default(),
            DeltaCounts::default(),
            FaceCounts::default(),
            vec![false; self.nv],
        )
    }

    /// The fragment (and what is wrong) that, after the cut, holds the first tet the cut
    /// made flat or inverted (rounding can put a new point on a face of its tet).
    fn flat(&self, open: &OpenMt) -> Option<(usize, String)> {
        let made = self.replaced.iter().map(|r| r.0 as usize);
        made.chain(self.n_tets..open.tets.len()).find_map(|t| {
            let tet = open.tets[t];
            if tet[3] == GHOST {
                return None;
            }
            let [a, b, c, d] = tet.map(|v| open.positions[v.idx()]);
            let flat = crate::geom::orient3d(a, b, c, d) != crate::geom::Sign::Positive;
            flat.then(|| {
                let detail = format!("a tet it made, {tet:?}, is flat or inverted");
                (open.creator()[t].idx(), detail)
            })
        })
    }

    /// The first fragment (and what is wrong with it) whose floor and ceiling, after the
    /// cut, do not have the same boundary or hold a face twice (what `Mt::validate`
    /// checks of every fragment), read from what the cut changed.
    /// A collapse fragment the cut split is checked whole, with each one split off it
    /// (`floor` and `ceiling` list them, as step 3 read them). One it changed without
    /// splitting is checked from what changed ([`Delta::check`]): its floor and ceiling
    /// had the same boundary before the cut, so they still do when what the cut took out
    /// of and put into its floor adds up, face by face with orientation, to what it took
    /// out of and put into its ceiling, and a face held twice is a face of a tet put in.
    /// Read whole, the fragments along an incision, which every step of a scalpel adds
    /// tets to, cost more at each step (this check 10–11 ms per step of a blade crossing
    /// fandisk in 100 steps read whole, 8 ms from what changed); debug builds check each
    /// such fragment whole as well, and fail when the two disagree. A root's ceiling and a
    /// drain's floor are whole meshes, closed by their ghosts, and were closed before the
    /// cut: they stay closed when the tets the cut made of them (in place and appended)
    /// have the boundary of the tets it replaced, none twice.
    fn check(
        &self,
        open: &OpenMt,
        order: &[FragmentId],
        floor: &[Vec<u32>],
        ceiling: &[Vec<u32>],
    ) -> Result<(), (usize, String)> {
        let whole = |f: FragmentId, above: bool| match open.kind[f.idx()] {
            FragmentKind::Root => above,
            FragmentKind::Drain => !above,
            FragmentKind::Collapse => false,
        };
        // Per root or drain: the tets it had where the cut wrote, and those it has now.
        let mut sides: HashMap<u32, (Vec<Tet>, Vec<Tet>), FxBuild> = HashMap::default();
        for &(_, old, c, d) in self.replaced {
            for (f, above) in [(c, true), (d, false)] {
                if whole(f, above) {
                    sides.entry(f.0).or_default().0.push(old);
                }
            }
        }
        let now = self.replaced.iter().map(|r| r.0 as usize);
        for t in now.chain(self.n_tets..open.tets.len()) {
            let (c, d) = (open.creator()[t], open.destroyer()[t]);
            for (f, above) in [(self.origin(c), true), (self.origin(d), false)] {
                if whole(f, above) {
                    sides.entry(f.0).or_default().1.push(open.tets[t]);
                }
            }
        }
        let mut sides: Vec<_> = sides.into_iter().collect();
        sides.sort_unstable_by_key(|s| s.0);
        let mut counts = FaceCounts::default();
        for (f, (old, new)) in sides {
            let c = Boundaries::compare(old.into_iter(), new.into_iter(), &mut counts);
            if !c.same || c.doubled[1] > c.doubled[0] {
                let what = match open.kind[f as usize] {
                    FragmentKind::Root => "ceiling (a finest mesh)",
                    _ => "floor (a coarsest mesh)",
                };
                return Err((
                    f as usize,
                    format!(
                        "the tets the cut made of its {what} have {} boundary faces and {} \
                         faces doubled, the tets they replace {} and {}: its floor and \
                         ceiling do not match",
                        c.boundary[1], c.doubled[1], c.boundary[0], c.doubled[0]
                    ),
                ));
            }
        }
        // Collapse fragments, each with the fragments split off it, on both cores. Those
        // the cut neither wrote a tet of nor split (involved as cracked by earlier cuts, as
        // most are on a scalpel's later steps) keep the tets, and the boundary, they had.
        // Per fragment before the cut (dense: one look-up per tet below, where hashing
        // each took a fifth of this check): whether the cut wrote a tet of it, or split it.
        let mut wrote = vec![false; self.nf];
        for r in self.replaced {
            wrote[r.2.idx()] = true;
            wrote[r.3.idx()] = true;
        }
        for t in self.n_tets..open.tets.len() {
            let (c, d) = (open.creator()[t], open.destroyer()[t]);
            wrote[self.origin(c).idx()] = true;
            wrote[self.origin(d).idx()] = true;
        }
        let mut split = vec![false; self.nf];
        for f in self.born {
            split[f.idx()] = true;
        }
        let was_split = |f: FragmentId| split.get(f.idx()).copied().unwrap_or(false);
        // Per collapse fragment changed and not split: the tets its floor and its ceiling
        // lost and gained (`deltas[slot[f]]`).
        let mut slot = vec![u32::MAX; self.nf];
        let mut deltas: Vec<Delta> = Vec::new();
        {
            let mut note = |f: FragmentId, gained: bool, level: usize, tet: Tet| {
                if f.idx() < self.nf
                    && open.kind[f.idx()] == FragmentKind::Collapse
                    && !split[f.idx()]
                {
                    if slot[f.idx()] == u32::MAX {
                        slot[f.idx()] = deltas.len() as u32;
                        deltas.push(Delta::default());
                    }
                    let d = &mut deltas[slot[f.idx()] as usize];
                    let lists = if gained { &mut d.gained } else { &mut d.lost };
                    lists[level].push(tet);
                }
            };
            for &(t, old, c, d) in self.replaced {
                note(d, false, 0, old);
                note(c, false, 1, old);
                let t = t as usize;
                note(open.destroyer()[t], true, 0, open.tets[t]);
                note(open.creator()[t], true, 1, open.tets[t]);
            }
            for t in self.n_tets..open.tets.len() {
                note(open.destroyer()[t], true, 0, open.tets[t]);
                note(open.creator()[t], true, 1, open.tets[t]);
            }
        }
        let whole_check = |counts: &mut FaceCounts, i: usize| -> Option<(usize, String)> {
            let f = order[i];
            // The fragment and those split off it.
            let mut ids: Vec<FragmentId> = Vec::new();
            if was_split(f) {
                let links = floor[i].iter().map(|&t| open.destroyer()[t as usize]);
                ids.extend(links.chain(ceiling[i].iter().map(|&t| open.creator()[t as usize])));
                ids.retain(|&g| g != f);
                ids.sort_unstable();
                ids.dedup();
            }
            counts.reserve(4 * (floor[i].len() + ceiling[i].len()));
            for g in std::iter::once(f).chain(ids) {
                let c = Boundaries::compare(
                    linked(&floor[i], open.destroyer(), g, &open.tets),
                    linked(&ceiling[i], open.creator(), g, &open.tets),
                    counts,
                );
                if !c.same || c.doubled != [0, 0] {
                    let detail = format!(
                        "floor boundary {} triangles, ceiling {}; {} floor and {} ceiling \
                         faces doubled",
                        c.boundary[0], c.boundary[1], c.doubled[0], c.doubled[1]
                    );
                    return Some((g.idx(), detail));
                }
            }
            None
        };
        let check_one = |scratch: &mut CheckScratch, i: usize| -> Option<(usize, String)> {
            let f = order[i];
            if open.kind[f.idx()] != FragmentKind::Collapse
                || !(was_split(f) || wrote.get(f.idx()).copied().unwrap_or(false))
            {
                return None;
            }
            let (counts, delta_counts, old_faces, marks) = scratch;
            let Some(delta) = slot.get(f.idx()).and_then(|&k| deltas.get(k as usize)) else {
                return whole_check(counts, i);
            };
            let found = delta
                .check(
                    open,
                    self.nv,
                    [&floor[i], &ceiling[i]],
                    delta_counts,
                    old_faces,
                    marks,
                )
                .map(|detail| (f.idx(), detail));
            #[cfg(debug_assertions)]
            {
                let whole = whole_check(counts, i);
                assert_eq!(
                    found.is_some(),
                    whole.is_some(),
                    "fragment {f}: checked from what changed {found:?}, checked whole {whole:?}"
                );
            }
            found
        };
        // One table of face counts per thread, kept from fragment to fragment.
        let first_bad = if order.len() > 64 {
            let each = (0..order.len())
                .into_par_iter()
                .map_init(|| self.check_scratch(), check_one);
            each.find_first(Option::is_some).flatten()
        } else {
            let mut scratch = self.check_scratch();
            (0..order.len()).find_map(|i| check_one(&mut scratch, i))
        };
        first_bad.map_or(Ok(()), Err)
    }
}

impl Changed<'_> {
    /// The first vertex this cut made that would hang in the finest or the coarsest mesh
    /// (lie strictly inside a boundary face it is not a corner of, other than a face of
    /// the other lip of a crack), as `Mt::validate` finds it, named with the fragment
    /// holding that face. The fragments' floors and ceilings can match face by face and
    /// still hold such a T-junction: on a Kuhn grid, where the tips of an earlier crack
    /// lie a face-point margin off a grid plane, a later cut in another plane made points
    /// nearly collinear on its crack, one inside a coarse crack face by 2e-8. Only the
    /// faces the cut wrote are read, with the vertices it made: every boundary face at
    /// such a vertex was written by the cut, so a vertex on the other lip is told apart.
    fn hanging(&self, open: &OpenMt) -> Option<(usize, String)> {
        let written = self
            .replaced
            .iter()
            .map(|r| r.0 as usize)
            .chain(self.n_tets..open.tets.len());
        for (name, kind) in [
            ("finest", FragmentKind::Root),
            ("coarsest", FragmentKind::Drain),
        ] {
            let mut faces: Vec<[VertexId; 3]> = Vec::new();
            let mut owners: Vec<FragmentId> = Vec::new();
            let mut points: Vec<VertexId> = Vec::new();
            for t in written.clone() {
                let tet = open.tets[t];
                if tet[3] != GHOST {
                    continue;
                }
                let link = match kind {
                    FragmentKind::Root => open.creator()[t],
                    _ => open.destroyer()[t],
                };
                if open.kind[self.origin(link).idx()] != kind {
                    continue;
                }
                let face = [tet[0], tet[1], tet[2]];
                faces.push(face);
                owners.push(link);
                points.extend(face.into_iter().filter(|v| v.idx() >= self.nv));
            }
            points.sort_unstable();
            points.dedup();
            let hits = boundary_hits(&open.positions, &faces, points);
            if let Some(&(v, fi)) = hits.hanging.iter().min() {
                let f = faces[fi as usize];
                return Some((
                    owners[fi as usize].idx(),
                    format!(
                        "its {name} mesh would have a hanging vertex: vertex {} lies inside \
                         boundary face ({}, {}, {})",
                        v.0, f[0].0, f[1].0, f[2].0
                    ),
                ));
            }
        }
        None
    }
}

/// The tets a cut took out of and put into the floor (`[0]`) and the ceiling (`[1]`) of a
/// collapse fragment it changed without splitting it ([`Changed::check`]).
#[derive(Default)]
struct Delta {
    lost: [Vec<Tet>; 2],
    gained: [Vec<Tet>; 2],
}

/// A face of a tet, by its sorted vertices, and whether its orientation is the odd order
/// of them (sorted counting the swaps: an odd count is the opposite orientation).
#[inline]
fn face_key(t: &Tet, f: [usize; 3]) -> ([u32; 3], usize) {
    let [x, y, z] = f.map(|j| t[j].0);
    let (x, y, s0) = if x > y { (y, x, 1) } else { (x, y, 0) };
    let (y, z, s1) = if y > z { (z, y, 1) } else { (y, z, 0) };
    let (x, y, s2) = if x > y { (y, x, 1) } else { (x, y, 0) };
    ([x, y, z], (s0 + s1 + s2) & 1)
}

impl Delta {
    /// What is wrong, if anything, with the fragment after the cut, given that its floor
    /// and ceiling had the same boundary before, none holding a face twice, and that
    /// `lists` are its floor and ceiling now (pool indices). `nv`: the pool's vertices
    /// before the cut.
    ///
    /// * The same boundary: the floor's boundary changed by what it gained less what it
    ///   lost, as a sum of oriented faces, and so did the ceiling's; they stay equal when
    ///   the two changes are equal, face by face.
    /// * No face twice: only a face of a gained tet can be held twice. One with a vertex
    ///   the cut made is held only by tets the cut wrote (all gained); one of older
    ///   vertices (or the ghost vertex) is counted over the whole list, whose tets are
    ///   passed over unless three of their vertices are of such faces (`marks`).
    fn check(
        &self,
        open: &OpenMt,
        nv: usize,
        lists: [&[u32]; 2],
        counts: &mut DeltaCounts,
        old_faces: &mut FaceCounts,
        marks: &mut [bool],
    ) -> Option<String> {
        // One table for every test below: per face, how often the floor gained it, the
        // ceiling gained it, the floor lost it and the ceiling lost it, by orientation
        // (each face of a changed tet hashed once, where a table per test hashed the
        // gained tets' faces twice).
        counts.clear();
        let changed = [
            &self.gained[0],
            &self.gained[1],
            &self.lost[0],
            &self.lost[1],
        ];
        for (which, tets) in changed.into_iter().enumerate() {
            for t in tets {
                for f in TET_FACES {
                    let (key, odd) = face_key(t, f);
                    let n = &mut counts.entry(key).or_default()[which][odd];
                    *n = n.saturating_add(1);
                }
            }
        }
        let sum = |[even, odd]: [u16; 2]| i32::from(even) - i32::from(odd);
        let differ = counts
            .values()
            .filter(|n| sum(n[0]) + sum(n[3]) != sum(n[1]) + sum(n[2]))
            .count();
        if differ > 0 {
            return Some(format!(
                "what the cut changed of its floor and of its ceiling differs at {differ} \
                 faces: they would not have the same boundary"
            ));
        }
        let older = |v: u32| v == GHOST.0 || (v as usize) < nv;
        for (level, what) in ["floor", "ceiling"].into_iter().enumerate() {
            old_faces.clear();
            // Faces with a vertex the cut made, held twice with one orientation.
            let mut twice = 0;
            for (key, n) in counts.iter() {
                let gained = n[level];
                if gained == [0, 0] {
                    continue;
                }
                if key.iter().all(|&v| older(v)) {
                    old_faces.entry(*key).or_default();
                    for &v in key.iter().filter(|&&v| v != GHOST.0) {
                        marks[v as usize] = true;
                    }
                } else if gained.iter().any(|&c| c > 1) {
                    twice += 1;
                }
            }
            if !old_faces.is_empty() {
                let marked = |v: VertexId| v == GHOST || (v.idx() < nv && marks[v.idx()]);
                for &t in lists[level] {
                    let t = &open.tets[t as usize];
                    if t.iter().filter(|&&v| marked(v)).count() < 3 {
                        continue;
                    }
                    for f in TET_FACES {
                        let (key, odd) = face_key(t, f);
                        if let Some(n) = old_faces.get_mut(&key) {
                            n[0][odd] = n[0][odd].saturating_add(1);
                        }
                    }
                }
                for key in old_faces.keys() {
                    for v in key.iter().filter(|&&v| VertexId(v) != GHOST) {
                        marks[*v as usize] = false;
                    }
                }
            }
            twice += old_faces
                .values()
                .filter(|n| n[0].iter().any(|&c| c > 1))
                .count();
            if twice > 0 {
                return Some(format!(
                    "{twice} {what} faces doubled (held twice with one orientation)"
                ));
            }
        }
        None
    }
}

/// The tets of `list` whose link (creator or destroyer) is `g`.
fn linked<'a>(
    list: &'a [u32],
    link: &'a [FragmentId],
    g: FragmentId,
    tets: &'a [Tet],
) -> impl Iterator<Item = Tet> + 'a {
    let list = list.iter().filter(move |&&t| link[t as usize] == g);
    list.map(|&t| tets[t as usize])
}

/// Per triangle (its vertices sorted), how often each of two sets of tets holds it with
/// each orientation.
type FaceCounts = HashMap<[u32; 3], [[u16; 2]; 2], FxBuild>;

/// Per triangle (its vertices sorted), how often four sets of tets hold it with each
/// orientation ([`Delta::check`]).
type DeltaCounts = HashMap<[u32; 3], [[u16; 2]; 4], FxBuild>;

/// Scratch of [`Changed::check`] for one thread: the tables of whole checks and of
/// [`Delta::check`], and a mark per vertex from before the cut.
type CheckScratch = (FaceCounts, DeltaCounts, FaceCounts, Vec<bool>);

/// Two sets of tets compared face by face (a fragment's floor and ceiling; what a cut made
/// of a closed mesh and what it replaced), as `Mt::validate` compares a fragment's floor
/// and ceiling: each set's boundary is the oriented faces whose opposite it does not hold.
struct Boundaries {
    /// Whether the two boundaries are the same oriented triangles.
    same: bool,
    /// Per set: its boundary faces, and its faces held twice with one orientation.
    boundary: [usize; 2],
    doubled: [usize; 2],
}

impl Boundaries {
    /// The faces of both sets counted by their sorted vertices, per set and orientation
    /// (even or odd order of the sorted vertices), in `counts` (a hash table: sorting them
    /// cost twice as much), then one pass over the triangles met.
    fn compare(
        a: impl Iterator<Item = Tet>,
        b: impl Iterator<Item = Tet>,
        counts: &mut FaceCounts,
    ) -> Boundaries {
        fn count(counts: &mut FaceCounts, set: usize, tets: impl Iterator<Item = Tet>) {
            for t in tets {
                for f in TET_FACES {
                    let (key, odd) = face_key(&t, f);
                    let n = &mut counts.entry(key).or_default()[set][odd];
                    *n = n.saturating_add(1);
                }
            }
        }
        counts.clear();
        count(counts, 0, a);
        count(counts, 1, b);
        let mut r = Boundaries {
            same: true,
            boundary: [0; 2],
            doubled: [0; 2],
        };
        for n in counts.values() {
            let mut open_side = [None; 2];
            for set in 0..2 {
                let [even, odd] = n[set].map(usize::from);
                r.doubled[set] += even.saturating_sub(1) + odd.saturating_sub(1);
                open_side[set] = match (even, odd) {
                    (0, 0) => None,
                    (_, 0) => Some(0),
                    (0, _) => Some(1),
                    _ => None,
                };
                r.boundary[set] += match open_side[set] {
                    Some(0) => even,
                    Some(_) => odd,
                    None => 0,
                };
            }
            r.same &= open_side[0] == open_side[1];
        }
        r
    }
}

/// What [`MtCutter::give_back`] needs, besides the open MT, to undo a cut.
struct GivenBack {
    /// Vertices before the cut, and the lengths of the cutter's vertex scales and crack
    /// flags then.
    nv: usize,
    lengths: (usize, usize),
    replaced: Vec<Replaced>,
    born: Vec<FragmentId>,
    /// The crack flags the cut set on vertices it duplicated, as they were.
    crack_was: Vec<(VertexId, bool)>,
    /// The cracked fragments, as they were.
    cracked: Vec<bool>,
}

impl MtCutter {
    /// Undoes a cut refused after it opened the MT and wrote in it: what it appended is
    /// dropped, what it wrote in place written back, fragments split off given back to
    /// their origins, and the MT closed as it was (nothing moved: the arcs, boxes and DAG
    /// kept), with the cutter's own tables as they were.
    fn give_back(
        &mut self,
        mut open: OpenMt,
        undo: GivenBack,
        n_tets: usize,
        nf: usize,
        dag: KnownDag,
    ) {
        for &(t, tet, c, d) in &undo.replaced {
            let t = t as usize;
            open.tets[t] = tet;
            open.set_creator(t, c);
            open.set_destroyer(t, d);
        }
        // Every tet the cut relabelled goes back to the fragments it was split off.
        let origin = |g: FragmentId| origin_of(g, nf, &undo.born);
        let relabelled = open.relabelled().to_vec();
        for t in relabelled.into_iter().map(|t| t as usize) {
            let (c, d) = (open.creator()[t], open.destroyer()[t]);
            open.set_creator(t, origin(c));
            open.set_destroyer(t, origin(d));
        }
        open.truncate_tets(n_tets);
        open.positions.truncate(undo.nv);
        open.point_data.truncate(undo.nv);
        open.kind.truncate(nf);
        open.error.truncate(nf);
        open.changed_fragments = Some(Vec::new());
        open.written_tets = Some(undo.replaced.iter().map(|r| r.0).collect());
        open.restore_dag(dag);
        for (k, &f) in undo.born.iter().enumerate().rev() {
            self.split_off[f.idx()] = self.split_off[nf + k];
        }
        self.split_off.truncate(nf);
        self.cracked = undo.cracked;
        self.scales.truncate(undo.lengths.0);
        for &(v, was) in &undo.crack_was {
            self.crack[v.idx()] = was;
        }
        self.crack.truncate(undo.lengths.1);
        let (mt, links) = open
            .close_keeping_links()
            .unwrap_or_else(|e| panic!("an MT cut given back left an inconsistent store: {e}"));
        self.links = Some(links);
        self.mt = Some(mt);
    }
}

/// [`MtCutter::cracked`] of a loaded or built MT: the fragments whose floor and ceiling form
/// several parts. A collapse fragment none of whose tets holds a vertex a cut appended is
/// as its simplification step made it, one piece (its floor and ceiling are the stars of
/// the collapsed edge and of the vertex it became), and is passed over after reading its
/// tets' vertex ids: on a fresh MT only the roots and drains are joined (0.29 s → less
/// than a tenth of it for the fandisk-1m MT's 3.8 M pool tets). Of the others, most are one
/// piece of tets sharing vertices, which a table by vertex shows at once; the rest go
/// through [`split_fragment`]. On all cores: paid each time a cutter is made.
fn cracked_fragments(mt: &Mt) -> Vec<bool> {
    cracked_among(mt, true)
}

/// [`cracked_fragments`], joining every fragment's tets when `skip_uncut` is false.
fn cracked_among(mt: &Mt, skip_uncut: bool) -> Vec<bool> {
    use rayon::prelude::*;
    let tets = mt.tets();
    let nv = mt.nb_vertices();
    let from = mt.info().cuts.cut_vertices_from() as u32;
    let uncut = |t: &Tet| t.iter().all(|&v| v == GHOST || v.0 < from);
    // Large jobs: each starts with a table the size of the vertex pool.
    let min_len = (mt.nb_fragments() / 16).max(1);
    (0..mt.nb_fragments())
        .into_par_iter()
        .with_min_len(min_len)
        .map_init(
            || (Pieces::new(nv), Vec::new()),
            |(pieces, arcs), f| {
                let f = FragmentId::from_usize(f);
                // The floor's and the ceiling's arcs, found once (an in-arc is a search
                // among its creator's arcs), their tets read in place: most fragments are
                // one piece, and are done without collecting anything.
                arcs.clear();
                arcs.extend(mt.in_arcs(f).chain(mt.out_arcs(f)));
                let list = arcs.iter().flat_map(|&a| mt.arc_tets(a as usize));
                if skip_uncut
                    && mt.fragment_kind(f) == FragmentKind::Collapse
                    && list.clone().all(|t| uncut(&tets[t]))
                {
                    return false;
                }
                if pieces.one_piece(tets, list.map(|t| t as u32)) {
                    return false;
                }
                let floor: Vec<u32> = mt.destroyed_tets(f).map(|t| t.0).collect();
                let ceiling: Vec<u32> = mt.created_tets(f).map(|t| t.0).collect();
                let parts = split_fragment(tets, mt.positions(), &floor, &ceiling, pieces);
                parts.iter().any(|&p| p > 0)
            },
        )
        .collect()
}

/// A fragment's ceiling (contiguous: arcs are sorted by creator) and floor (one range per
/// in-arc, in pool order) as ranges of the pool.
struct Spans {
    ceiling: std::ops::Range<usize>,
    floor: Vec<std::ops::Range<usize>>,
}

impl Spans {
    fn of(mt: &Mt, f: FragmentId) -> Spans {
        let mut out = mt.out_arcs(f).into_iter();
        let ceiling = match (out.next(), out.last()) {
            (None, _) => 0..0,
            (Some(a), last) => {
                mt.arc_tets(a as usize).start..mt.arc_tets(last.unwrap_or(a) as usize).end
            }
        };
        let mut floor: Vec<std::ops::Range<usize>> =
            mt.in_arcs(f).map(|a| mt.arc_tets(a as usize)).collect();
        floor.sort_unstable_by_key(|r| r.start);
        Spans { ceiling, floor }
    }
}

/// Scratch of [`cracked_fragments`] and of the whole-root test: per vertex, the first tet
/// of the current list holding it (valid where marked in the current pass).
struct Pieces {
    first: Vec<u32>,
    stamps: Stamps,
    parent: Vec<u32>,
}

impl Pieces {
    /// Scratch for lists of tets over a pool of `vertices` vertices.
    fn new(vertices: usize) -> Pieces {
        let mut pieces = Pieces {
            first: Vec::new(),
            stamps: Stamps::default(),
            parent: Vec::new(),
        };
        pieces.fit(vertices);
        pieces
    }

    /// Room for a pool grown to `vertices` vertices.
    fn fit(&mut self, vertices: usize) {
        self.stamps.resize(vertices);
        self.first.resize(vertices, 0);
    }

    /// Starts a list: no vertex met yet.
    fn begin(&mut self) {
        self.stamps.begin();
    }

    /// The first tet (`i`, its place in the list) met at `v` since [`begin`](Self::begin),
    /// if an earlier one was (else `i` is now).
    #[inline]
    fn first_at(&mut self, v: VertexId, i: u32) -> Option<u32> {
        if self.stamps.mark(v.idx()) {
            self.first[v.idx()] = i;
            None
        } else {
            Some(self.first[v.idx()])
        }
    }

    /// Whether the tets `list` are joined into one piece through shared vertices.
    fn one_piece(&mut self, tets: &[Tet], list: impl Iterator<Item = u32>) -> bool {
        self.begin();
        self.parent.clear();
        let mut pieces = 0u32;
        for t in list {
            let i = self.parent.len() as u32;
            self.parent.push(i);
            pieces += 1;
            for &v in tets[t as usize].iter().filter(|v| **v != GHOST) {
                if let Some(o) = self.first_at(v, i) {
                    let (x, y) = (find(&mut self.parent, o), find(&mut self.parent, i));
                    if x != y {
                        self.parent[x.max(y) as usize] = x.min(y);
                        pieces -= 1;
                    }
                }
            }
        }
        pieces <= 1
    }
}

/// "Is fragment `b` a successor of `a` (or `a` itself)?" over the DAG before the cut: a
/// depth-first search from `a` pruned by levels (a successor has a larger level).
struct Reach {
    /// Successors of `f`: `arc_destroyer[out_start[f]..out_start[f + 1]]` (each once: an
    /// MT has one arc per pair of fragments); levels bound the searches.
    dag: KnownDag,
}

impl Reach {
    fn succ(&self, f: usize) -> impl Iterator<Item = u32> + '_ {
        let d = &self.dag;
        d.arc_destroyer[d.out_start[f] as usize..d.out_start[f + 1] as usize]
            .iter()
            .map(|g| g.0)
    }

    fn reaches(&self, a: FragmentId, b: FragmentId) -> bool {
        if a == b {
            return true;
        }
        let level = &self.dag.level;
        let target = level[b.idx()];
        let mut seen: HashSet<u32, FxBuild> = HashSet::default();
        let mut stack = vec![a.0];
        while let Some(f) = stack.pop() {
            for g in self.succ(f as usize) {
                if g == b.0 {
                    return true;
                }
                if level[g as usize] < target && seen.insert(g) {
                    stack.push(g);
                }
            }
        }
        false
    }
}

/// The most, relative to a vertex's scale, that the contour band and the crack-tip reach take,
/// whatever the face-point margin: 5%. Chosen, not derived: above the scalpel's needs (its margin,
/// 0.01, gives a 2% band and a 1.5% reach) and far below the default snap (0.2), so that cuts with
/// the default margin (0.5, face points mid-segment) reach barely past C's contour.
const CRACK_REACH_CAP: f64 = 0.05;

/// Whether a cut by `polygon` at rest takes the vertices of earlier cracks lying on its
/// plane outside it as [`OUT`] (`StateClassifier::with_crack_vertices`):
/// when it lies in the plane of an earlier crack made at rest (`planes`, each a unit
/// normal and a point: the MT's record),
/// or when no such plane is recorded (an MT saved before planes were: its cracks' planes
/// are unknown). `OUT` is for a crack continued in its own plane, whose lips and tips all
/// lie on the new plane and whose exact sides there would be rounding noise. A crack in
/// another plane meets the new plane along a line only, and its vertices on that line
/// (a Kuhn grid puts some there exactly) keep their sides like any vertex: taken as
/// `OUT`, a vertex of it outside the polygon drew the new crack along a whole coarse face
/// up to the earlier crack (the face's `ON` corner reaching two `OUT` ones), without
/// copies there on any level, and the cut was refused (faces doubled); 29 of 300 seeded
/// Kuhn-grid runs were refused at their second cut, and 8 of 300 took all ten cuts,
/// 152 since. Deformed cuts keep `OUT` as before (their cracks' planes are not recorded).
pub(crate) fn continues_a_crack_plane(
    polygon: &CutPolygon,
    planes: impl IntoIterator<Item = (DVec3, DVec3)>,
) -> bool {
    let mut planes = planes.into_iter().peekable();
    planes.peek().is_none() || lies_in_plane(polygon, planes)
}

/// The contour band ([`StateClassifier::with_contour_band`]) of a cut that continues cracks: every
/// MT cut, and a plain-mesh cut with [`continue_cracks`](CutOptions::continue_cracks). Twice the
/// face-point margin, at most [`CRACK_REACH_CAP`]. A crack tip lies inside the contour where its
/// cut ended by up to the margin of its section segment (the clamp of its place on the segment),
/// plus up to the margin of its face's uncut edge (the segment's outer end moved along that edge);
/// on an MT's coarse levels both are longer than the tip's scale (taken from the finest mesh, so
/// that every level decides alike). With the margin alone, a blade moved in an axis-aligned plane
/// (tests/mt_scalpel.rs) met a tip 1.27 margins of its scale inside the last step's contour:
/// outside the band, it joined both lips of the earlier crack in one cluster of
/// `settle_plane_vertices`, whose sides were then rounding noise. Twice the margin is a measured
/// width, not a bound: a tip on a coarse face more than twice its scale long can lie farther in.
pub(crate) fn contour_band(opts: &CutOptions) -> f64 {
    (2.0 * opts.face_point_margin).min(CRACK_REACH_CAP)
}

/// How far from C (relative to their scale) the crack tips of earlier cuts count as on the cut, for
/// the plain-mesh engine ([`StateClassifier::with_crack_tips`]): 1.5 face-point margins, the margin
/// taken at most [`CRACK_REACH_CAP`]. On a plain mesh a tip's section segment is no longer than its
/// scale, so the tip lies within about the margin of it from the contour where its cut ended (more
/// only where the segment's outer end moved, see [`contour_band`]), and a cut beginning on that
/// contour, in whatever plane, passes within the margin of it; half as much again for rounding.
pub(crate) fn tip_reach(opts: &CutOptions) -> f64 {
    1.5 * opts.face_point_margin.min(CRACK_REACH_CAP)
}

/// Vertices within snapping distance of C's plane but outside C (and its contour band:
/// not cut, so only their side matters) take the side of their neighbours when every
/// candidate tet around them, on every level, has its other vertices off the plane on that
/// one side; their exact side is kept otherwise. Such vertices are on the plane up to
/// rounding: the lips of an earlier cut in the same plane (a blade swept in steps: its
/// earlier cut points lie just behind the new polygon). Their exact side is then rounding
/// noise, and a lip tet holding one on the wrong side of its lip, with crack tips of the
/// earlier cut on the new polygon's contour, would be taken for a tet C crosses and split
/// into children lying flat between the lips, joining both lips (differently on each
/// level: the MT condition breaks). The decision is taken per cluster of such vertices
/// joined by edges of candidate tets, so every tet sharing an edge or a face still sees
/// the same states there, and no edge between two of them is taken for crossed when
/// their exact sides agree; with `lips_alike` (a plain mesh), both lips of a crack that
/// C's plane crosses get the same states ([`same_decision_on_both_lips`]). Tets the new
/// states leave neither straddling nor touching the cut are dropped from the candidates.
#[allow(clippy::too_many_arguments)]
pub(crate) fn settle_plane_vertices(
    polygon: &CutPolygon,
    opts: CutOptions,
    positions: &[DVec3],
    scales: &[f64],
    cand: &mut Vec<TetId>,
    states: &mut Vec<[u8; 4]>,
    lips_alike: bool,
    tet_of: impl Fn(TetId) -> Tet,
) {
    let near = |v: VertexId, s: u8| {
        (s == POS || s == NEG)
            && polygon.signed_distance(positions[v.idx()]).abs()
                <= opts.snap.distance(scales[v.idx()])
    };
    // Vertices on the plane outside C, numbered; clusters of them joined by the edges of
    // candidate tets (one decision per cluster, so no edge between two of them is taken
    // for crossed when their exact sides agree: its crossing would lie off the edge); the
    // sides (bit per state) of the other vertices of their tets.
    // (A sorted list, not a hash map: a few hundred vertices, looked up by binary search.)
    let mut flags: Vec<u8> = Vec::with_capacity(cand.len());
    let mut index: Vec<VertexId> = Vec::new();
    for (&t, s) in cand.iter().zip(states.iter()) {
        let tet = tet_of(t);
        let mut flag = 0u8;
        for j in 0..4 {
            if near(tet[j], s[j]) {
                flag |= 1 << j;
                index.push(tet[j]);
            }
        }
        flags.push(flag);
    }
    if index.is_empty() {
        return;
    }
    index.sort_unstable();
    index.dedup();
    let slot = |v: VertexId| index.binary_search(&v).expect("a listed vertex") as u32;
    let mut parent: Vec<u32> = (0..index.len() as u32).collect();
    let mut sides: Vec<u8> = vec![0; index.len()];
    for ((&t, s), &flag) in cand.iter().zip(states.iter()).zip(&flags) {
        if flag == 0 {
            continue;
        }
        let tet = tet_of(t);
        let mut others = 0u8;
        for j in (0..4).filter(|&j| flag & (1 << j) == 0 && (s[j] == POS || s[j] == NEG)) {
            others |= 1 << s[j];
        }
        let mut first = None;
        for j in (0..4).filter(|&j| flag & (1 << j) != 0) {
            let i = slot(tet[j]);
            sides[i as usize] |= others;
            match first {
                None => first = Some(i),
                Some(f) => union(&mut parent, f, i),
            }
        }
    }
    let mut cluster = vec![0u8; parent.len()];
    for i in 0..parent.len() as u32 {
        let r = find(&mut parent, i);
        cluster[r as usize] |= sides[i as usize];
    }
    if lips_alike {
        same_decision_on_both_lips(&index, positions, &mut parent, &mut cluster);
    }
    let mut keep = 0;
    for k in 0..cand.len() {
        let (t, mut s) = (cand[k], states[k]);
        if flags[k] != 0 {
            let tet = tet_of(t);
            for j in (0..4).filter(|&j| flags[k] & (1 << j) != 0) {
                let r = find(&mut parent, slot(tet[j]));
                match cluster[r as usize] {
                    x if x == 1 << POS => s[j] = POS,
                    x if x == 1 << NEG => s[j] = NEG,
                    _ => {}
                }
            }
        }
        if is_candidate(s) {
            cand[keep] = t;
            states[keep] = s;
            keep += 1;
        }
    }
    cand.truncate(keep);
    states.truncate(keep);
}

/// On a plain mesh, the clusters of [`settle_plane_vertices`] holding coincident vertices
/// (a crack's vertex and its copy on the other lip) are joined, unless each leans wholly
/// to a side and the sides differ: then C's plane separates the lips (a blade continuing
/// its own crack), and each copy takes its own lip's side. Otherwise each lip's star
/// alone can lean to a different side where C's plane crosses the crack: a crack tip is
/// then placed in one lip's face and not in the other's, and a later cut crossing both
/// lips there splits them differently (hanging vertices: a Kuhn-grid sequence,
/// tests/cut_engine.rs). Not on an MT, nor on a live MT's frontier, which decides as the
/// MT does: there joining them made the fragment check refuse incisions taken otherwise
/// (a T-shaped incision and a deferred scalpel on fandisk, tests/mt_scalpel.rs).
fn same_decision_on_both_lips(
    index: &[VertexId],
    positions: &[DVec3],
    parent: &mut [u32],
    cluster: &mut [u8],
) {
    let bits = |i: u32| {
        positions[index[i as usize].idx()]
            .to_array()
            .map(f64::to_bits)
    };
    let mut by_position: Vec<u32> = (0..index.len() as u32).collect();
    by_position.sort_unstable_by_key(|&i| bits(i));
    let both = (1 << POS) | (1 << NEG);
    for group in by_position.chunk_by(|&a, &b| bits(a) == bits(b)) {
        if group.len() < 2 {
            continue;
        }
        let leanings = group.iter().map(|&i| cluster[find(parent, i) as usize]);
        let (all, mixed) = leanings.fold((0u8, false), |(all, mixed), s| {
            (all | s, mixed || s == both)
        });
        if all == both && !mixed {
            continue;
        }
        for &i in &group[1..] {
            let (x, y) = (find(parent, group[0]), find(parent, i));
            if x != y {
                let (r, o) = (x.min(y), x.max(y));
                parent[o as usize] = r;
                cluster[r as usize] |= cluster[o as usize];
            }
        }
    }
}

/// The side of a tet the tables leave whole: the side of its vertices off the cut
/// ([`Side::Straddle`] when both occur: C's plane crosses it outside C, or it is a crack
/// tip); a tet with all four vertices snapped (a sliver lying in the cut) goes to the side
/// of its centroid. As the plain-mesh engine decides.
fn side_of_states(tet: &Tet, states: [u8; 4], positions: &[DVec3], polygon: &CutPolygon) -> Side {
    match (states.contains(&POS), states.contains(&NEG)) {
        (true, true) => Side::Straddle,
        (true, false) => Side::Positive,
        (false, true) => Side::Negative,
        (false, false) => {
            let c: DVec3 = tet.iter().map(|v| positions[v.idx()]).sum::<DVec3>() * 0.25;
            if polygon.signed_distance(c) < 0.0 {
                Side::Negative
            } else {
                Side::Positive
            }
        }
    }
}

/// The connected parts of a fragment: its floor and ceiling tets (ghosts included) joined
/// through shared vertices. A cut straight through gives the two sides disjoint vertex
/// sets (every vertex on the crack is duplicated), so sharing a vertex means not
/// separated; joining floor to ceiling by vertices (rather than by boundary faces) also
/// pairs a piece the cut isolated inside the fragment's floor, closed by its ghosts and
/// sharing no face with the ceiling, with the piece replacing it in the ceiling, as long as
/// the two share a vertex of the fragment's boundary.
///
/// A piece cut free inside the fragment's region (several cuts can carve a chunk off the
/// body there) touches no other fragment: its floor and ceiling share no vertex (their
/// crack points lie on different edges), and would become a fragment destroying tets and
/// creating none plus one creating tets and destroying none. Such a part, with a floor and
/// no ceiling or the reverse, is joined with the parts of the other level that occupy the
/// same space: those holding the centroid of one of its tets, or a tet of which holds the
/// centroid of one of its own (exact point-in-tet tests).
///
/// Returns the part of each floor tet then each ceiling tet, numbered by first appearance.
fn split_fragment(
    tets: &[Tet],
    positions: &[DVec3],
    floor: &[u32],
    ceiling: &[u32],
    scratch: &mut Pieces,
) -> Vec<u32> {
    let n = floor.len() + ceiling.len();
    let mut parent: Vec<u32> = (0..n as u32).collect();
    let all: Vec<u32> = floor.iter().chain(ceiling).copied().collect();
    // The first tet met at each vertex, in a table over the pool's vertices kept from
    // fragment to fragment (a hash map per fragment cost a cut of the fandisk-1m MT, with
    // its thousand fragments involved, more than the rest of the grouping).
    scratch.begin();
    for (i, &t) in all.iter().enumerate() {
        for &v in tets[t as usize].iter().filter(|v| **v != GHOST) {
            if let Some(o) = scratch.first_at(v, i as u32) {
                union(&mut parent, i as u32, o);
            }
        }
    }
    // Parts present on one level only.
    let nfl = floor.len() as u32;
    let mut levels = vec![[false; 2]; n];
    for i in 0..n as u32 {
        let r = find(&mut parent, i) as usize;
        levels[r][(i >= nfl) as usize] = true;
    }
    // (A root has no floor and a drain no ceiling: nothing to pair there.)
    let both = !floor.is_empty() && !ceiling.is_empty();
    let orphans: Vec<u32> = (0..n as u32)
        .filter(|&i| {
            if !both {
                return false;
            }
            let l = levels[find(&mut parent, i) as usize];
            !(l[0] && l[1]) && tets[all[i as usize] as usize][3] != GHOST
        })
        .collect();
    if !orphans.is_empty() {
        let corners = |i: u32| tets[all[i as usize] as usize].map(|v| positions[v.idx()]);
        let real = |i: u32| tets[all[i as usize] as usize][3] != GHOST;
        // Centroid and box of every real tet (ghosts have neither).
        let shape: Vec<(DVec3, Aabb)> = (0..n as u32)
            .map(|i| {
                if !real(i) {
                    return (DVec3::ZERO, Aabb::EMPTY);
                }
                let c = corners(i);
                ((c[0] + c[1] + c[2] + c[3]) * 0.25, Aabb::from_points(&c))
            })
            .collect();
        let holds = |i: u32, p: DVec3| {
            if !shape[i as usize].1.contains(p) {
                return false;
            }
            let c = corners(i);
            (0..4).all(|j| {
                let mut q = c;
                q[j] = p;
                crate::geom::orient3d(q[0], q[1], q[2], q[3]) != crate::geom::Sign::Negative
            })
        };
        for &i in &orphans {
            let others = if i < nfl { nfl..n as u32 } else { 0..nfl };
            for j in others.filter(|&j| real(j)) {
                if holds(j, shape[i as usize].0) || holds(i, shape[j as usize].0) {
                    union(&mut parent, i, j);
                }
            }
        }
        // What is left exists on one level only: a sliver of the body between the
        // boundaries of the floor and the ceiling (a collapse moves the boundary). Closed
        // by its own ghosts, it leaves the boundary of any part unchanged: it joins the part
        // of the nearest tet of the other level.
        for i in 0..n as u32 {
            levels[i as usize] = [false; 2];
        }
        for i in 0..n as u32 {
            let r = find(&mut parent, i) as usize;
            levels[r][(i >= nfl) as usize] = true;
        }
        for &i in &orphans {
            let l = levels[find(&mut parent, i) as usize];
            if l[0] && l[1] {
                continue;
            }
            let centroid = shape[i as usize].0;
            let others = if i < nfl { nfl..n as u32 } else { 0..nfl };
            let nearest = others
                .filter(|&j| real(j))
                .map(|j| (centroid.distance_squared(shape[j as usize].0), j))
                .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            if let Some((_, j)) = nearest {
                union(&mut parent, i, j);
                let r = find(&mut parent, i) as usize;
                levels[r] = [true; 2];
            }
        }
    }
    let mut label = vec![u32::MAX; n];
    let mut next = 0;
    (0..n as u32)
        .map(|i| {
            let r = find(&mut parent, i) as usize;
            if label[r] == u32::MAX {
                label[r] = next;
                next += 1;
            }
            label[r]
        })
        .collect()
}

/// Per vertex: whether another vertex has the same position (bit for bit).
/// The longest edge at each vertex in the finest mesh (see the module docs).
fn finest_edge_scales(mt: &Mt) -> Vec<f64> {
    let mut scales = vec![0.0f64; mt.nb_vertices()];
    let finest = mt
        .roots()
        .iter()
        .flat_map(|&r| mt.created_tets(r))
        .map(|t| mt.tet(t))
        .filter(|t| t[3] != GHOST);
    for t in finest {
        for [a, b] in TET_EDGES {
            let (u, v) = (t[a].idx(), t[b].idx());
            let l = mt.positions()[u].distance(mt.positions()[v]);
            scales[u] = scales[u].max(l);
            scales[v] = scales[v].max(l);
        }
    }
    scales
}

fn shared_positions(positions: &[DVec3]) -> Vec<bool> {
    let mut order: Vec<u32> = (0..positions.len() as u32).collect();
    let key = |i: u32| positions[i as usize].to_array().map(f64::to_bits);
    order.sort_unstable_by_key(|&i| key(i));
    let mut shared = vec![false; positions.len()];
    for w in order.windows(2) {
        if key(w[0]) == key(w[1]) {
            shared[w[0] as usize] = true;
            shared[w[1] as usize] = true;
        }
    }
    shared
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tet(ids: [u32; 4]) -> Tet {
        ids.map(VertexId)
    }

    /// Fans at tip 0 of tets on the positive side, taking the tip's copy where `copied`.
    fn fans(tets: &[[u32; 4]], copied: &[[u32; 4]]) -> [usize; 2] {
        let star = tets.iter().map(|&t| (tet(t), Side::Positive));
        tip_fans(VertexId(0), star, &|u: VertexId, t: &Tet, _: Side| {
            u.0 == 0 && copied.iter().any(|&c| tet(c) == *t)
        })
    }

    /// The collapse fragments no cut touched are passed over, and found one piece when
    /// joined: on a fresh MT, after a cut ending inside the body (which leaves fragments
    /// cracked) and after one through it.
    #[test]
    fn fragments_no_cut_touched_are_one_piece() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/pinion-coarse.node");
        let (mesh, _) = crate::io::read_mesh(path).expect("pinion-coarse");
        let (mt, _) = Mt::build(&mesh, &crate::mt::BuildOptions::DEFAULT).expect("MT");
        let mut cutter = MtCutter::new(mt, MtCutter::DEFAULT_OPTIONS).expect("options");
        let b = Aabb::from_points(cutter.mt().positions());
        let (c, d) = (b.center(), b.max - b.min);
        let square = |z: f64, half: f64| {
            let p = |x: f64, y: f64| DVec3::new(c.x + x * d.x, c.y + y * d.y, z);
            CutPolygon::new(&[
                p(-half, -half),
                p(half, -half),
                p(half, half),
                p(-half, half),
            ])
            .expect("square")
        };
        let mut cracked_seen = false;
        for polygon in [square(c.z, 0.3), square(c.z + 0.2 * d.z, 0.8)] {
            let mt = cutter.mt();
            let fast = cracked_fragments(mt);
            assert_eq!(fast, cracked_among(mt, false));
            cracked_seen |= fast.contains(&true);
            cutter.cut(&polygon).expect("cut");
        }
        let mt = cutter.mt();
        assert_eq!(cracked_fragments(mt), cracked_among(mt, false));
        assert!(
            cracked_seen,
            "no cut left a fragment cracked: the test shows nothing"
        );
    }

    /// The fragment sets a vertex's stars are read from: the root always applied, the
    /// drain never, a fragment only with those before it; no more than the budget.
    #[test]
    fn star_sets_are_the_closed_sets_of_the_order() {
        use FragmentKind::{Collapse, Drain, Root};
        let count = |kinds: &[FragmentKind], before: &[Vec<usize>], budget: usize| {
            let mut order: Vec<usize> = (0..kinds.len()).collect();
            order.sort_by_key(|&i| before[i].len());
            let sets = StarSets {
                order: &order,
                before,
                kinds,
            };
            let mut seen: Vec<Vec<bool>> = Vec::new();
            let mut budget = budget;
            let mut applied = vec![false; kinds.len()];
            let hit = sets.any(0, &mut applied, &mut budget, &mut |a: &[bool]| {
                seen.push(a.to_vec());
                false
            });
            assert!(!hit);
            seen
        };
        // A chain root -> a -> drain: the root alone, or with a.
        let chain = count(
            &[Root, Collapse, Drain],
            &[vec![], vec![0], vec![0, 1]],
            100,
        );
        assert_eq!(chain, [vec![true, false, false], vec![true, true, false]]);
        // A diamond root -> a, b -> drain: a and b each with or without the other.
        let before = [vec![], vec![0], vec![0], vec![0, 1, 2]];
        let diamond = count(&[Root, Collapse, Collapse, Drain], &before, 100);
        assert_eq!(diamond.len(), 4);
        assert!(diamond.iter().all(|a| a[0] && !a[3]));
        // The budget stops the search.
        assert_eq!(
            count(&[Root, Collapse, Collapse, Drain], &before, 3).len(),
            3
        );
    }

    #[test]
    fn tets_around_a_tip_are_counted_in_boundary_fans() {
        // One tet: its three faces at the tip close a single fan.
        assert_eq!(fans(&[[0, 1, 2, 3]], &[]), [1, 0]);
        // Two tets across a face at the tip: still one fan.
        assert_eq!(fans(&[[0, 1, 2, 3], [0, 2, 1, 4]], &[]), [1, 0]);
        // Two tets meeting only at the tip: pinched, two fans.
        assert_eq!(fans(&[[0, 1, 2, 3], [0, 4, 5, 6]], &[]), [2, 0]);
        // The same two tets, one taking the tip's copy: one fan each.
        assert_eq!(fans(&[[0, 1, 2, 3], [0, 4, 5, 6]], &[[0, 4, 5, 6]]), [1, 1]);
        // Across a face, one taking the copy: the face opens, one fan each.
        assert_eq!(fans(&[[0, 1, 2, 3], [0, 2, 1, 4]], &[[0, 2, 1, 4]]), [1, 1]);
        // A closed star (the tip inside the mesh): no boundary, no fan.
        let octahedron = [
            [0, 1, 2, 5],
            [0, 2, 3, 5],
            [0, 3, 4, 5],
            [0, 4, 1, 5],
            [0, 2, 1, 6],
            [0, 3, 2, 6],
            [0, 4, 3, 6],
            [0, 1, 4, 6],
        ];
        assert_eq!(fans(&octahedron, &[]), [0, 0]);
    }
}
