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
    /// [`canonical_order_at`]): what [`super::unglue`] looks the entry up by.
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

/// The canonical order of a tet by id: `perm[i]` is the local index of the `i`-th smallest
/// vertex id; `odd` tells whether that permutation is odd (the 1:17 scheme's, and an
/// MT's, see [`canonical_order_at`]).
#[inline]
pub fn canonical_order(tet: &Tet) -> ([usize; 4], bool) {
    sort_order(tet.map(|v| v.0))
}

/// The canonical order of a tet for the tables: `perm[i]` is the local index of the
/// `i`-th vertex in the global order of the shared-face rule (§4.2, Fig. 8b), `odd` tells
/// whether that permutation is odd (the sorted tet is then negatively oriented).
///
/// That global order is by *twin root* (`roots[v]`: the lowest id among a vertex and the
/// copies cuts made of it, which share its position: see [`twin_roots`]), ids breaking
/// ties; for a vertex no cut copied the root is its own id, so the order is the ids'
/// everywhere but on the lips of cracks. Any global order makes neighbours agree on a shared face; this one also makes
/// the two lips of a crack agree. They are copies of each other, whose ids differ, so by
/// ids alone a later cut crossing both lips could split a lip face along one diagonal and
/// its twin on the other lip along the other: a cut after that, crossing those
/// diagonals, left a vertex of one lip inside a face of the other. Six parallel cuts of
/// pinion-coarse 0.03 apart did so with the default options (tests/cut_engine.rs,
/// `parallel_slices_split_both_lips_alike`). Two vertices of one tet never share a
/// root (they would share a position), so the ids never decide within a valid tet.
///
/// `roots` `None` orders by id, as an MT's cut does (and the cut of a current mesh
/// extracted from it, which must decide alike): a cutter made of a saved MT must decide as
/// the one that cut it, and the saved MT has positions, not which vertex a cut copied —
/// positions do not tell copies apart from cut points of several levels that land on one
/// position (collinear edges, measured on pinion). An MT's lips stay in their planes (its
/// snapping is at most 1e-4), and where a later cut subdivides them differently,
/// `TetMesh::validate` tells the lips apart (a warning, `ViolationKind::LipsApart`).
#[inline]
pub fn canonical_order_at(tet: &Tet, roots: Option<&[u32]>) -> ([usize; 4], bool) {
    match roots {
        Some(roots) => sort_order(tet.map(|v| (roots[v.idx()], v.0))),
        None => canonical_order(tet),
    }
}

/// The twin root of every vertex (see [`canonical_order_at`]): the lowest id among the
/// vertices at its position (a vertex and the copies cuts made of it share one, bit for
/// bit). Cuts extend the list as they add vertices ([`extend_twin_roots`]).
pub fn twin_roots(positions: &[crate::geom::DVec3]) -> Vec<u32> {
    let mut order: Vec<u32> = (0..positions.len() as u32).collect();
    let key = |i: u32| positions[i as usize].to_array().map(f64::to_bits);
    order.sort_unstable_by_key(|&i| (key(i), i));
    let mut roots: Vec<u32> = (0..positions.len() as u32).collect();
    for w in order.windows(2) {
        if key(w[0]) == key(w[1]) {
            roots[w[1] as usize] = roots[w[0] as usize];
        }
    }
    roots
}

/// Appends the twin roots of the vertices a cut added, numbered from `roots.len()` in the
/// order of their `origins`: a copy takes its original's root, a cut point's negative copy
/// its positive copy's (numbered just before it, [`CutSession::allocate`]), and every other
/// new vertex its own id.
pub fn extend_twin_roots(
    roots: &mut Vec<u32>,
    origins: impl IntoIterator<Item = super::classify::VertexOrigin>,
) {
    use super::classify::VertexOrigin;
    for o in origins {
        let id = roots.len();
        let root = match o {
            VertexOrigin::Edge {
                positive: false, ..
            } => roots[id - 1],
            VertexOrigin::Copy { of } => roots[of.idx()],
            _ => id as u32,
        };
        roots.push(root);
    }
}

/// `perm[i]` is the index of the `i`-th smallest of `keys` (distinct), and whether that
/// permutation is odd.
#[inline]
fn sort_order<K: PartialOrd>(keys: [K; 4]) -> ([usize; 4], bool) {
    let mut perm = [0usize; 4];
    let mut inversions = 0;
    for i in 0..4 {
        let mut rank = 0;
        for j in 0..4 {
            if keys[j] < keys[i] {
                rank += 1;
            }
        }
        perm[rank] = i;
        for j in i + 1..4 {
            if keys[j] < keys[i] {
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
/// leaves `out` alone) when the tet is not split. `roots` holds the twin root of every
/// vertex of the mesh before the cut, which orders the tet's vertices (`None`: their ids;
/// [`canonical_order_at`]).
pub fn split_tet(
    session: &CutSession<'_>,
    tet: &Tet,
    class: &TetClass,
    roots: Option<&[u32]>,
    out: &mut Children,
) -> bool {
    if !class.is_split() {
        return false;
    }
    let (perm, odd) = canonical_order_at(tet, roots);
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
