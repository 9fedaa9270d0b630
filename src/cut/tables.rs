//! The split tables (paper §4.2, Fig. 6, Table 1): for every way a tetrahedron can meet
//! the cut, the tetrahedra that replace it.
//!
//! # Canonical tetrahedron
//!
//! A tet is looked up with its four vertices **sorted in a global order** (local vertex `i`
//! is the `i`-th smallest; the order of ids, except that on a plain mesh a vertex a cut
//! copied sorts as the vertex it was copied from, so that the two lips of a crack sort
//! alike: [`super::split::canonical_order_at`]). The shared-face rule of the paper (a quadrilateral face takes
//! the diagonal at its lowest vertex, Fig. 8b) then depends only on local indices, so one
//! table entry per configuration suffices. When sorting is an odd permutation the sorted
//! tet is negatively oriented; every child is then mirrored (two vertices swapped), which
//! keeps it positive because a child's volume is a fixed multiple of its parent's (see the
//! generator, [`super::table_gen`]).
//!
//! # Configuration
//!
//! Each vertex is [`NEG`], [`ON`] (snapped onto the cut inside C), [`POS`] or [`OUT`] (on
//! the plane outside C: an earlier crack's vertex); an edge whose ends are `NEG` and `POS`
//! is *crossed* by the plane, and *cut* when it is crossed strictly inside C. A
//! configuration is the four states plus the cut-edge mask; everything else (section
//! polygon, face points, crack polygon) follows from it ([`face_has_point`]).
//!
//! # Local points of a child
//!
//! `0..4`: the tet's vertices; `4 + 2e` / `5 + 2e`: the copy of the cut point of edge `e` on
//! the `POS` / `NEG` side (cut points are duplicated, paper §4.2); `16 + f`: the face point
//! of face `f` (never duplicated: it is the crack tip, Fig. 4c–e).

use crate::mesh::tables::{TET_EDGES, TET_FACES};

/// Vertex state: strictly on the negative side of the cut plane.
pub const NEG: u8 = 0;
/// Vertex state: on the cut (on the plane within tolerance, inside C within tolerance).
pub const ON: u8 = 1;
/// Vertex state: strictly on the positive side of the cut plane (or exactly on the plane
/// but outside C, a symbolic perturbation that costs nothing: such a vertex is not cut).
pub const POS: u8 = 2;
/// Vertex state: on the plane to rounding but outside C — the vertices of an earlier
/// crack in the same plane that the new polygon does not cover (its lips and tips). Edges
/// at such a vertex are never crossed (the plane meets them at the vertex, outside C),
/// and a face with two vertices on the plane never holds a face point (the plane meets it
/// along that edge). An exact side would be rounding noise: the two lips of the old
/// crack, which share its tips, would then disagree about faces they both touch.
pub const OUT: u8 = 3;

/// Number of configurations: 4⁴ vertex states × 2⁶ cut-edge masks (most masks are invalid).
pub const NB_CONFIGS: usize = 256 * 64;

/// Number of local point slots (4 vertices, 6 × 2 edge-point copies, 4 face points).
pub const NB_LOCAL_POINTS: usize = 20;

/// Local id of the copy of edge `e`'s cut point on the positive (`plus`) or negative side.
#[inline]
pub const fn edge_point(e: usize, plus: bool) -> u8 {
    (4 + 2 * e + if plus { 0 } else { 1 }) as u8
}

/// Local id of the face point of face `f`.
#[inline]
pub const fn face_point(f: usize) -> u8 {
    (16 + f) as u8
}

/// Index of a configuration in the tables.
#[inline]
pub fn config_index(states: [u8; 4], cut_mask: u8) -> usize {
    let code = states[0] as usize
        | (states[1] as usize) << 2
        | (states[2] as usize) << 4
        | (states[3] as usize) << 6;
    code * 64 + cut_mask as usize
}

/// The states and cut mask of configuration `index` (inverse of [`config_index`]).
pub fn config_of_index(index: usize) -> ([u8; 4], u8) {
    let (code, mask) = (index / 64, (index % 64) as u8);
    let s = [code & 3, code >> 2 & 3, code >> 4 & 3, code >> 6 & 3].map(|x| x as u8);
    (s, mask)
}

/// Whether the edge joining two vertices of these states is crossed by the plane.
#[inline]
pub fn is_crossed(a: u8, b: u8) -> bool {
    (a == NEG && b == POS) || (a == POS && b == NEG)
}

/// Whether a face whose three vertices have `states` and whose edges (`k` joins vertices
/// `k` and `k+1 mod 3`) have cut flags `cut` holds a face point.
///
/// The plane meets the face in a segment whose ends are the face's `ON` and `OUT` vertices
/// and the crossing points of its crossed edges; an end is *in* C when it is an `ON` vertex
/// or the point of a cut edge. C's contour crosses the segment exactly when one end is in
/// and the other out — a face with exactly one cut edge in the paper's words (§4.1),
/// extended to segments ending at a vertex on the plane. A segment joining two vertices on
/// the plane is an edge of the face, not its inside: no face point. Both tets sharing a
/// face call this with the same data, so they agree.
pub fn face_has_point(states: [u8; 3], cut: [bool; 3]) -> bool {
    let mut ends = 0;
    let mut inside = 0;
    let mut on_plane = 0;
    for k in 0..3 {
        if states[k] == ON || states[k] == OUT {
            ends += 1;
            on_plane += 1;
            inside += usize::from(states[k] == ON);
        }
        if is_crossed(states[k], states[(k + 1) % 3]) {
            ends += 1;
            if cut[k] {
                inside += 1;
            }
        }
    }
    ends == 2 && inside == 1 && on_plane < 2
}

/// Face-point flags of the four faces of a tet in configuration (`states`, `cut_mask`).
pub fn face_points(states: [u8; 4], cut_mask: u8) -> [bool; 4] {
    std::array::from_fn(|f| {
        let v = TET_FACES[f];
        let cut = std::array::from_fn(|k| {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            let e = crate::mesh::tables::EDGE_OF_VERTICES[a][b];
            cut_mask & (1 << e) != 0
        });
        face_has_point(v.map(|i| states[i]), cut)
    })
}

/// Whether `cut_mask` only flags crossed edges of a tet with these states.
pub fn is_valid_config(states: [u8; 4], cut_mask: u8) -> bool {
    (0..6).all(|e| {
        let [a, b] = TET_EDGES[e];
        cut_mask & (1 << e) == 0 || is_crossed(states[a], states[b])
    })
}

/// The side of the cut a child lies on (paper §3: the fragment pieces Σ¹, Σ²).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    /// Every vertex on the positive side or on the cut.
    Positive,
    /// Every vertex on the negative side or on the cut.
    Negative,
    /// Vertices on both sides: a tet at the tip of a partial cut, joining the two sides
    /// around the crack's end (only in partial configurations, and in uncut tets that C's
    /// plane crosses outside C).
    Straddle,
}

/// How a tet meets the cut (paper Fig. 4 and Table 1, extended to snapped vertices).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[repr(u8)]
pub enum CutCase {
    /// Three cut edges around one vertex: split in two (Fig. 4a).
    A,
    /// Four cut edges: split in two (Fig. 4b).
    B,
    /// One cut edge: partial cut (Fig. 4c).
    C,
    /// Two cut edges sharing a vertex: partial cut (Fig. 4d).
    D,
    /// Two opposite cut edges of a quadrilateral section: partial cut (the crack crosses
    /// the section as a strip; four face points).
    DOpposite,
    /// Three cut edges of a quadrilateral section: partial cut (Fig. 4e).
    E,
    /// The cut passes through one vertex and splits the tet in two.
    Vertex1,
    /// The cut passes through one vertex and ends inside the tet.
    Vertex1Partial,
    /// The cut passes through two vertices (along an edge) and splits the tet in two.
    Vertex2,
    /// The cut passes along an edge and ends inside the tet.
    Vertex2Partial,
}

impl CutCase {
    /// Every case, in table order.
    pub const ALL: [CutCase; 10] = [
        CutCase::A,
        CutCase::B,
        CutCase::C,
        CutCase::D,
        CutCase::DOpposite,
        CutCase::E,
        CutCase::Vertex1,
        CutCase::Vertex1Partial,
        CutCase::Vertex2,
        CutCase::Vertex2Partial,
    ];

    /// A short name for reports.
    pub fn name(self) -> &'static str {
        match self {
            CutCase::A => "A",
            CutCase::B => "B",
            CutCase::C => "C",
            CutCase::D => "D",
            CutCase::DOpposite => "D-opposite",
            CutCase::E => "E",
            CutCase::Vertex1 => "vertex",
            CutCase::Vertex1Partial => "vertex-partial",
            CutCase::Vertex2 => "edge",
            CutCase::Vertex2Partial => "edge-partial",
        }
    }

    /// The case of a configuration that the tables split, or `None` when the tet is left
    /// whole (no cut edge and no face point).
    pub fn of_config(states: [u8; 4], cut_mask: u8) -> Option<CutCase> {
        let fp = face_points(states, cut_mask);
        if cut_mask == 0 && !fp.contains(&true) {
            return None;
        }
        let on = states.iter().filter(|&&s| s == ON).count();
        let crossed = (0..6)
            .filter(|&e| is_crossed(states[TET_EDGES[e][0]], states[TET_EDGES[e][1]]))
            .count();
        let cuts = cut_mask.count_ones() as usize;
        Some(match (on, crossed, cuts) {
            (0, 3, 3) => CutCase::A,
            (0, 4, 4) => CutCase::B,
            (0, 4, 3) => CutCase::E,
            (0, _, 1) => CutCase::C,
            (0, _, 2) => {
                let edges: Vec<usize> = (0..6).filter(|&e| cut_mask & (1 << e) != 0).collect();
                if edges[0] + edges[1] == 5 {
                    CutCase::DOpposite
                } else {
                    CutCase::D
                }
            }
            (1, c, k) if c == k && !fp.contains(&true) => CutCase::Vertex1,
            (1, _, _) => CutCase::Vertex1Partial,
            (_, c, k) if c == k && !fp.contains(&true) => CutCase::Vertex2,
            _ => CutCase::Vertex2Partial,
        })
    }
}

/// The generated tables: `OFFSETS[c]..OFFSETS[c + 1]` are the children of configuration
/// `c` in `CHILDREN` / `SIDES` (empty: the tet is not split), `CASES[c]` its case index in
/// [`CutCase::ALL`] (255: not split or invalid).
mod generated {
    include!("tables_generated.rs");
}

pub use generated::{CASES, CHILDREN, OFFSETS, SIDES};

/// Side codes stored in [`SIDES`].
pub const SIDE_POSITIVE: u8 = 0;
pub const SIDE_NEGATIVE: u8 = 1;
pub const SIDE_STRADDLE: u8 = 2;

/// The side of a side code stored in [`SIDES`].
#[inline]
pub fn side_of_code(code: u8) -> Side {
    match code {
        SIDE_POSITIVE => Side::Positive,
        SIDE_NEGATIVE => Side::Negative,
        _ => Side::Straddle,
    }
}

/// The children of configuration `config` (local point ids, positively oriented for a
/// positively oriented canonical tet) and their side codes.
#[inline]
pub fn entry(config: usize) -> (&'static [[u8; 4]], &'static [u8]) {
    let (a, b) = (OFFSETS[config] as usize, OFFSETS[config + 1] as usize);
    (&CHILDREN[a..b], &SIDES[a..b])
}
