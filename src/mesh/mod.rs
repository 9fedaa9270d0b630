//! The tetrahedral mesh: [`TetMesh`], stored as structure of arrays, with its local tables,
//! face adjacency, validation and attribute columns.
//!
//! This layer owns what a single conforming tet mesh is and how to check it
//! ([`TetMesh::validate`], DESIGN.md §5). It knows nothing of the MT or of cuts; those
//! layers build `TetMesh`es and call `validate` in their tests.

mod adjacency;
mod attributes;
mod boundary;
pub(crate) mod fxhash;
mod ids;
mod quality;
mod submesh;
pub mod tables;
mod validate;

pub use adjacency::{BoundaryFace, FaceAdjacency, VertexStars};
pub use attributes::{Attribute, Attributes};
pub use boundary::Boundary;
pub(crate) use ids::corners;
pub use ids::{FragmentId, Tet, TetId, VertexId};
pub use quality::{QualitySummary, TetQuality, tet_quality};
pub(crate) use validate::{Numbering, boundary_hits};
pub use validate::{Severity, ValidationReport, Violation, ViolationKind};

use crate::geom::{
    Aabb, DVec3, MIN_MESH_SIZE, Sign, first_unsupported, orient3d, signed_volume_inexact,
};
use rayon::prelude::*;

/// A tetrahedral mesh: positions, tets (four vertex ids each, positively oriented), and
/// named per-vertex and per-tet attribute columns.
///
/// Invariants (checked by [`validate`](Self::validate), guaranteed for meshes made by
/// [`from_arrays`](Self::from_arrays) and by the library's algorithms): every tet
/// positively oriented with four distinct in-range vertices, every triangle shared by at
/// most two tets with opposite orientations, the boundary a closed 2-manifold without
/// hanging vertices, all coordinates finite, attribute columns as long as their elements.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TetMesh {
    positions: Vec<DVec3>,
    tets: Vec<Tet>,
    /// Per-vertex attribute columns (one row per vertex).
    pub point_data: Attributes,
    /// Per-tet attribute columns (one row per tet).
    pub cell_data: Attributes,
}

/// What `from_arrays` found about one tet given.
#[derive(Clone, Copy)]
enum TetCheck {
    Positive,
    Reoriented,
    OutOfRange,
    Repeated,
    Degenerate,
}

/// What [`TetMesh::from_arrays`] repaired or noticed while accepting a mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ImportReport {
    /// Tets given with negative orientation and re-oriented (two vertices swapped).
    pub reoriented_tets: usize,
    /// Vertices used by no tet: kept (their ids stay valid), reported as a warning.
    pub unused_vertices: usize,
}

/// Why a mesh was rejected. Indices are 0-based positions in the arrays given.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshError {
    #[error("the mesh has no tetrahedra")]
    Empty,
    #[error("vertex {vertex} has a coordinate that is NaN or infinite")]
    NonFiniteCoordinate { vertex: usize },
    #[error(
        "vertex {vertex} {}: rescale the mesh (to metres or millimetres, say)",
        crate::geom::out_of_range_text(*value)
    )]
    CoordinateOutOfRange { vertex: usize, value: f64 },
    #[error(
        "the mesh is {diagonal:e} across (its bounding box's diagonal), below the {:e} mtcut \
         supports: rescale it",
        crate::geom::MIN_MESH_SIZE
    )]
    TooSmall { diagonal: f64 },
    #[error("tet {tet} uses vertex index {index}, but the mesh has {n_vertices} vertices")]
    IndexOutOfRange {
        tet: usize,
        index: u64,
        n_vertices: usize,
    },
    #[error("tet {tet} uses vertex {vertex} more than once")]
    RepeatedVertex { tet: usize, vertex: u32 },
    #[error("tet {tet} is degenerate: its four vertices are coplanar (zero volume)")]
    DegenerateTet { tet: usize },
    #[error("the mesh has more than {max} vertices or tets")]
    TooLarge { max: u32 },
    #[error("{0}")]
    Invalid(ValidationReport),
}

impl TetMesh {
    /// A mesh from arrays given by a user or a file, checked: coordinates finite, indices in
    /// range, four distinct vertices per tet, no zero-volume tet; negatively oriented tets
    /// are re-oriented (counted in the report); then the whole mesh is validated and
    /// rejected if any invariant fails (faces shared by three tets, non-manifold boundary,
    /// hanging vertices...). Unused vertices are kept and reported.
    pub fn from_arrays(
        positions: Vec<DVec3>,
        tets: Vec<[u32; 4]>,
    ) -> Result<(TetMesh, ImportReport), MeshError> {
        Self::from_arrays_numbered(positions, tets, Numbering::ZERO)
    }

    /// [`from_arrays`](Self::from_arrays) for a file reader: a rejected mesh's validation
    /// report numbers vertices and tets as the file does (`numbering`).
    pub(crate) fn from_arrays_numbered(
        positions: Vec<DVec3>,
        tets: Vec<[u32; 4]>,
        numbering: Numbering,
    ) -> Result<(TetMesh, ImportReport), MeshError> {
        if tets.is_empty() {
            return Err(MeshError::Empty);
        }
        if positions.len() >= u32::MAX as usize || tets.len() >= u32::MAX as usize {
            return Err(MeshError::TooLarge { max: u32::MAX - 1 });
        }
        // One parallel pass finds the first vertex with a coordinate mtcut cannot take.
        let unsupported = |p: &DVec3| first_unsupported(std::slice::from_ref(p)).is_some();
        if let Some(vertex) = positions.par_iter().position_first(unsupported) {
            let value = first_unsupported(&positions[vertex..=vertex]).map_or(f64::NAN, |b| b.1);
            return Err(if value.is_finite() {
                MeshError::CoordinateOutOfRange { vertex, value }
            } else {
                MeshError::NonFiniteCoordinate { vertex }
            });
        }
        let diagonal = Aabb::from_points(&positions).diagonal();
        if diagonal < MIN_MESH_SIZE {
            return Err(MeshError::TooSmall { diagonal });
        }
        let n = positions.len();
        // Tet by tet, in parallel: what is wrong with it or how it is oriented. The first
        // failing tet in the given order is then reported.
        let checks: Vec<TetCheck> = tets
            .par_iter()
            .map(|tet| {
                if tet.iter().any(|&i| i as usize >= n) {
                    return TetCheck::OutOfRange;
                }
                if (0..4).any(|a| (a + 1..4).any(|b| tet[a] == tet[b])) {
                    return TetCheck::Repeated;
                }
                let p = tet.map(|i| positions[i as usize]);
                match orient3d(p[0], p[1], p[2], p[3]) {
                    Sign::Positive => TetCheck::Positive,
                    Sign::Negative => TetCheck::Reoriented,
                    Sign::Zero => TetCheck::Degenerate,
                }
            })
            .collect();
        let mut report = ImportReport::default();
        for (t, check) in checks.iter().enumerate() {
            match check {
                TetCheck::Positive => {}
                TetCheck::Reoriented => report.reoriented_tets += 1,
                TetCheck::OutOfRange => {
                    let index = tets[t]
                        .iter()
                        .copied()
                        .find(|&i| i as usize >= n)
                        .unwrap_or(0);
                    return Err(MeshError::IndexOutOfRange {
                        tet: t,
                        index: index as u64,
                        n_vertices: n,
                    });
                }
                TetCheck::Repeated => {
                    let tet = tets[t];
                    let vertex = (0..4)
                        .find_map(|a| (a + 1..4).find(|&b| tet[a] == tet[b]).map(|_| tet[a]))
                        .unwrap_or(tet[0]);
                    return Err(MeshError::RepeatedVertex { tet: t, vertex });
                }
                TetCheck::Degenerate => return Err(MeshError::DegenerateTet { tet: t }),
            }
        }
        // Negative tets become positive by swapping their last two vertices.
        let out: Vec<Tet> = tets
            .par_iter()
            .zip(checks.par_iter())
            .map(|(t, check)| match check {
                TetCheck::Reoriented => [t[0], t[1], t[3], t[2]].map(VertexId),
                _ => t.map(VertexId),
            })
            .collect();
        drop(tets);
        let mesh = TetMesh {
            positions,
            tets: out,
            point_data: Attributes::new(),
            cell_data: Attributes::new(),
        };
        let validation = validate::validate_with(&mesh, false, numbering);
        if !validation.is_valid() {
            return Err(MeshError::Invalid(validation));
        }
        report.unused_vertices = validation.count(ViolationKind::UnusedVertex);
        Ok((mesh, report))
    }

    /// A mesh from arrays the library built itself and knows to be consistent (indices in
    /// range); no checks beyond a debug assertion. Callers validate in their tests.
    pub(crate) fn from_parts(positions: Vec<DVec3>, tets: Vec<Tet>) -> TetMesh {
        debug_assert!(
            tets.iter()
                .all(|t| t.iter().all(|v| v.idx() < positions.len()))
        );
        TetMesh {
            positions,
            tets,
            point_data: Attributes::new(),
            cell_data: Attributes::new(),
        }
    }

    pub fn nb_vertices(&self) -> usize {
        self.positions.len()
    }

    pub fn nb_tets(&self) -> usize {
        self.tets.len()
    }

    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    pub fn tets(&self) -> &[Tet] {
        &self.tets
    }

    #[inline]
    pub fn position(&self, v: VertexId) -> DVec3 {
        self.positions[v.idx()]
    }

    #[inline]
    pub fn tet(&self, t: TetId) -> Tet {
        self.tets[t.idx()]
    }

    /// Local vertex `lv` (0..4) of tet `t`.
    #[inline]
    pub fn tet_vertex(&self, t: TetId, lv: usize) -> VertexId {
        self.tets[t.idx()][lv]
    }

    /// The four corner positions of tet `t`.
    #[inline]
    pub fn tet_positions(&self, t: TetId) -> [DVec3; 4] {
        self.tets[t.idx()].map(|v| self.positions[v.idx()])
    }

    /// Signed volume of tet `t` (positive in a valid mesh).
    pub fn tet_volume(&self, t: TetId) -> f64 {
        let [a, b, c, d] = self.tet_positions(t);
        signed_volume_inexact(a, b, c, d)
    }

    /// Total volume: the sum of the tets' signed volumes.
    pub fn volume(&self) -> f64 {
        (0..self.tets.len())
            .map(|t| self.tet_volume(TetId::from_usize(t)))
            .sum()
    }

    /// Bounding box of all vertices (used or not).
    pub fn bbox(&self) -> Aabb {
        Aabb::from_points(&self.positions)
    }

    /// Mutable positions: for deforming a mesh in place. Moving vertices can invert tets;
    /// that is the caller's responsibility (validate() reports it).
    pub fn positions_mut(&mut self) -> &mut [DVec3] {
        &mut self.positions
    }

    /// Makes room for `tets` more tets and `vertices` more vertices (with their attribute
    /// rows), so that appending them does not reallocate.
    pub fn reserve(&mut self, tets: usize, vertices: usize) {
        self.tets.reserve(tets);
        self.positions.reserve(vertices);
        self.cell_data.reserve(tets);
        self.point_data.reserve(vertices);
    }

    /// [`reserve`](Self::reserve), with the room's memory mapped now ([`touch_spare`]):
    /// for a cutter whose next cuts append to it in a time-critical step.
    pub(crate) fn reserve_mapped(&mut self, tets: usize, vertices: usize) {
        self.reserve(tets, vertices);
        touch_spare(&mut self.tets);
        touch_spare(&mut self.positions);
        self.cell_data.touch_spare();
        self.point_data.touch_spare();
    }

    /// How many tets and vertices can still be appended without reallocating: the
    /// attribute columns count too (they grow apart from the geometry, so one may be full
    /// while the other has room).
    pub(crate) fn spare(&self) -> (usize, usize) {
        let tets = self.tets.capacity() - self.tets.len();
        let vertices = self.positions.capacity() - self.positions.len();
        (
            self.cell_data.spare().map_or(tets, |c| c.min(tets)),
            self.point_data
                .spare()
                .map_or(vertices, |c| c.min(vertices)),
        )
    }

    /// Appends a vertex (attribute rows are the caller's: see [`Attributes::push_lerp`]).
    pub(crate) fn push_vertex(&mut self, p: DVec3) -> VertexId {
        self.positions.push(p);
        VertexId::from_usize(self.positions.len() - 1)
    }

    /// Appends a tet (attribute rows are the caller's: see [`Attributes::push_copy`]).
    pub(crate) fn push_tet(&mut self, t: Tet) -> TetId {
        self.tets.push(t);
        TetId::from_usize(self.tets.len() - 1)
    }

    /// Mutable tets, for algorithms that replace tets in place (cuts).
    pub(crate) fn tets_mut(&mut self) -> &mut Vec<Tet> {
        &mut self.tets
    }

    /// Mutable positions vector, for algorithms that append vertices in bulk.
    pub(crate) fn positions_vec_mut(&mut self) -> &mut Vec<DVec3> {
        &mut self.positions
    }

    /// Face adjacency of this mesh (computed, not cached).
    pub fn adjacency(&self) -> FaceAdjacency {
        FaceAdjacency::new(self)
    }

    /// Checks every invariant and reports every violation class with counts and first
    /// examples (DESIGN.md §5).
    pub fn validate(&self) -> ValidationReport {
        validate::validate(self)
    }
}

/// Room for `n` elements in `v` (its length included), every page of it mapped now: one
/// element of each page of the spare capacity is written (zeros, which stay spare), since
/// `Vec::reserve` only reserves addresses and the cut that first appends to each page
/// would pay for its fault (a live model's scalpel step met about 3 per step, half of them
/// in the room kept for it).
pub(crate) fn reserve_mapped<T>(v: &mut Vec<T>, n: usize) {
    v.reserve(n.saturating_sub(v.len()));
    touch_spare(v);
}

/// Writes one element of every page of `v`'s spare capacity (see [`reserve_mapped`]).
pub(crate) fn touch_spare<T>(v: &mut Vec<T>) {
    let step = (4096 / std::mem::size_of::<T>().max(1)).max(1);
    for slot in v.spare_capacity_mut().iter_mut().step_by(step) {
        *slot = std::mem::MaybeUninit::zeroed();
    }
}
