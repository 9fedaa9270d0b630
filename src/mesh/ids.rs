//! Index newtypes. Plain `u32` would let a tet index a vertex array; these do not.
//! All are `repr(transparent)` over `u32`, so slices of them are slices of `u32` for the
//! C ABI, and `INVALID` (`u32::MAX`) marks "none".

macro_rules! id_type {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
        #[repr(transparent)]
        pub struct $name(pub u32);

        impl $name {
            /// "None": never a valid index.
            pub const INVALID: $name = $name(u32::MAX);

            /// The index as a `usize`, for indexing arrays.
            #[inline]
            pub fn idx(self) -> usize {
                self.0 as usize
            }

            /// Whether this is not [`INVALID`](Self::INVALID).
            #[inline]
            pub fn is_valid(self) -> bool {
                self.0 != u32::MAX
            }

            /// The id of array position `i`; panics if `i` does not fit (an internal
            /// invariant: pools are kept below `u32::MAX` entries by their owners).
            #[inline]
            pub fn from_usize(i: usize) -> $name {
                debug_assert!(i < u32::MAX as usize);
                $name(i as u32)
            }
        }

        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                write!(f, "{}", self.0)
            }
        }
    };
}

id_type!(
    /// A vertex of a mesh or of an MT's vertex pool.
    VertexId
);
id_type!(
    /// A tetrahedron of a mesh or of an MT's tet pool.
    TetId
);
id_type!(
    /// A fragment (a node of the MT's DAG).
    FragmentId
);

/// A tetrahedron as its four vertices, positively oriented (see [`crate::geom::orient3d`]).
pub type Tet = [VertexId; 4];

/// `f` of each corner of `t`, in order: what `t.map(f)` gives, built element by element
/// and always inlined. In the hot loops of a cut, `map` was sometimes left a call whose
/// result the caller read back from the stack (a stalled load): a live model's setting of
/// positions took 1.3 ms instead of 0.9 once code elsewhere changed that choice.
#[inline(always)]
pub(crate) fn corners<T>(t: &Tet, f: impl Fn(VertexId) -> T) -> [T; 4] {
    [f(t[0]), f(t[1]), f(t[2]), f(t[3])]
}
