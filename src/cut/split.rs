//! Step 2 of the paper's cut (§3), second half: replace a classified tet by the tets of its
//! table entry (§4.2, Fig. 6).

use super::classify::{CutSession, NONE, TetClass};
use super::tables::Side;
use super::tables::{CASES, CutCase, ON, config_index, entry, side_of_code};
use crate::mesh::tables::EDGE_OF_VERTICES;
use crate::mesh::{Tet, VertexId};

/// Largest number of children of a split tet (the 1:17 scheme; table entries have at
/// most 13).
pub const MAX_CHILDREN: usize = 17;

/// [`Children::config`] of children not made by the tables (the 1:17 scheme).
pub const NO_CONFIG: u16 = u16::MAX;

/// The children of one split tet: global vertex ids, positively oriented, with their side,
/// and which of their vertices lie on the cut (bit `k` for vertex `k`: these are the
/// vertices [`super::unglue`] may duplicate).
#[derive(Clone, Copy, Debug)]
pub struct Children {
    pub case: CutCase,
    /// The table configuration the children come from ([`NO_CONFIG`]: not from the
    /// tables), and the canonical index of each of the parent's local vertices (see
    /// [`canonical_order`]): what [`super::unglue`] looks the entry up by.
    pub config: u16,
    pub rank: [u8; 4],
    pub len: usize,
    pub tets: [Tet; MAX_CHILDREN],
    pub sides: [Side; MAX_CHILDREN],
    pub on_cut: [u8; MAX_CHILDREN],
}

impl Children {
    /// An empty buffer.
    pub fn new() -> Children {
        Children {
            case: CutCase::A,
            config: NO_CONFIG,
            rank: [0; 4],
            len: 0,
            tets: [[VertexId::INVALID; 4]; MAX_CHILDREN],
            sides: [Side::Straddle; MAX_CHILDREN],
            on_cut: [0; MAX_CHILDREN],
        }
    }

    /// The children as (tet, side) pairs.
    pub fn iter(&self) -> impl Iterator<Item = (Tet, Side)> + '_ {
        (0..self.len).map(|k| (self.tets[k], self.sides[k]))
    }
}

/// The canonical order of a tet: `perm[i]` is the local index of the `i`-th smallest
/// vertex id; `odd` tells whether that permutation is odd (the sorted tet is then
/// negatively oriented).
#[inline]
pub fn canonical_order(tet: &Tet) -> ([usize; 4], bool) {
    let mut perm = [0usize; 4];
    let mut inversions = 0;
    for i in 0..4 {
        let mut rank = 0;
        for j in 0..4 {
            if tet[j] < tet[i] {
                rank += 1;
            }
        }
        perm[rank] = i;
        for j in i + 1..4 {
            if tet[j] < tet[i] {
                inversions += 1;
            }
        }
    }
    (perm, inversions % 2 == 1)
}

impl Default for Children {
    fn default() -> Self {
        Children::new()
    }
}

/// Writes into `out` the children replacing `tet` (positively oriented, global ids)
/// classified as `class`, whose new points `session` has allocated. Returns false (and
/// leaves `out` alone) when the tet is not split.
pub fn split_tet(
    session: &CutSession<'_>,
    tet: &Tet,
    class: &TetClass,
    out: &mut Children,
) -> bool {
    if !class.is_split() {
        return false;
    }
    let (perm, odd) = canonical_order(tet);
    let states = [
        class.states[perm[0]],
        class.states[perm[1]],
        class.states[perm[2]],
        class.states[perm[3]],
    ];
    let mut cut_mask = 0u8;
    let mut points = [VertexId::INVALID; 20];
    for i in 0..4 {
        points[i] = tet[perm[i]];
    }
    for (e, &[i, j]) in crate::mesh::tables::TET_EDGES.iter().enumerate() {
        let orig = EDGE_OF_VERTICES[perm[i]][perm[j]];
        if class.cut_mask & (1 << orig) != 0 {
            cut_mask |= 1 << e;
            let (plus, minus) = session.edge_points(class.edges[orig]);
            points[4 + 2 * e] = plus;
            points[5 + 2 * e] = minus;
        }
    }
    for f in 0..4 {
        // Canonical face f is opposite canonical vertex f, i.e. original face perm[f].
        if class.face_mask & (1 << perm[f]) != 0 {
            debug_assert!(class.faces[perm[f]] != NONE);
            points[16 + f] = session.face_point(class.faces[perm[f]]);
        }
    }
    let config = config_index(states, cut_mask);
    let (locals, sides) = entry(config);
    debug_assert!(
        !locals.is_empty(),
        "split configuration without table entry"
    );
    out.case = CutCase::ALL[CASES[config] as usize];
    out.config = config as u16;
    for (i, &p) in perm.iter().enumerate() {
        out.rank[p] = i as u8;
    }
    out.len = locals.len();
    let touches = class.touches_cut();
    for (k, (c, &s)) in locals.iter().zip(sides).enumerate() {
        // A mirrored canonical tet is mirrored back by swapping the last two vertices.
        let c = if odd { [c[0], c[1], c[3], c[2]] } else { *c };
        out.tets[k] = [
            points[c[0] as usize],
            points[c[1] as usize],
            points[c[2] as usize],
            points[c[3] as usize],
        ];
        out.sides[k] = side_of_code(s);
        let mut on = 0u8;
        if touches {
            for (slot, &p) in c.iter().enumerate() {
                if p < 4 && states[p as usize] == ON {
                    on |= 1 << slot;
                }
            }
        }
        out.on_cut[k] = on;
    }
    true
}
