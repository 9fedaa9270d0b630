//! A form of an MT independent of how it is numbered, for comparing two MTs made by
//! different processing orders (cuts applied fragment by fragment in any order must give
//! the same MT, paper §3).
//!
//! Vertices are named by their coordinates (bit patterns, so equal means identical), tets
//! by the sorted names of their corners, fragments by their kind, error and the sorted
//! lists of tets they create and destroy; the fragments are then sorted. Vertex, tet and
//! fragment ids, pool order and arc order all disappear, while the DAG does not: an arc is
//! a tet named in one fragment's created list and another's destroyed list.

use super::{GHOST, Mt};
use crate::mesh::{FragmentId, TetId};

/// A tet: the coordinate bit patterns of its corners, sorted (the ghost vertex is
/// `[u64::MAX; 3]`). Orientation is implied by the positions.
pub type TetKey = [[u64; 3]; 4];

/// A fragment, numbering-free.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct CanonicalFragment {
    /// [`super::FragmentKind`] code: 0 root, 1 collapse, 2 drain.
    pub kind: u8,
    /// Bit pattern of the fragment's error.
    pub error_bits: u64,
    pub created: Vec<TetKey>,
    pub destroyed: Vec<TetKey>,
}

/// An MT, numbering-free: its fragments, sorted.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct CanonicalMt {
    pub fragments: Vec<CanonicalFragment>,
}

impl Mt {
    /// The canonical form (see the [module docs](self)). Costs about the size of the MT.
    pub fn canonical_form(&self) -> CanonicalMt {
        let key = |t: TetId| -> TetKey {
            let mut k = self.tet(t).map(|v| {
                if v == GHOST {
                    [u64::MAX; 3]
                } else {
                    self.position(v).to_array().map(f64::to_bits)
                }
            });
            k.sort_unstable();
            k
        };
        let mut fragments: Vec<CanonicalFragment> = (0..self.nb_fragments())
            .map(|f| {
                let f = FragmentId::from_usize(f);
                let mut created: Vec<TetKey> = self.created_tets(f).map(key).collect();
                let mut destroyed: Vec<TetKey> = self.destroyed_tets(f).map(key).collect();
                created.sort_unstable();
                destroyed.sort_unstable();
                CanonicalFragment {
                    kind: self.fragment_kind(f).code(),
                    error_bits: self.fragment_error(f).to_bits(),
                    created,
                    destroyed,
                }
            })
            .collect();
        fragments.sort_unstable();
        CanonicalMt { fragments }
    }
}
