//! Options of a cut, and its errors.

use crate::geom::Tolerance;

/// How cut tets are replaced.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Scheme {
    /// The paper's look-up tables (§4.2): a minimal conforming tetrahedralization per
    /// configuration.
    Lut,
    /// The 1:17 scheme of Bielser et al. (1999), the paper's baseline (Fig. 5): 17 tets per
    /// cut tet, not conforming ([`super::bielser`]).
    Bielser17,
}

impl Scheme {
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Lut => "lut",
            Scheme::Bielser17 => "bielser17",
        }
    }
}

/// The smallest `snap` accepted: rounding in the vertex-to-plane distance stays far below
/// it for meshes whose coordinates are not many orders of magnitude larger than their
/// edges. With 0, a plane through vertices exactly (up to rounding) made flat tets.
pub const MIN_SNAP: f64 = 1e-9;

/// The smallest `face_point_margin` a cut accepts. Face points nearer an end of their
/// segment make flat or inverted children once rounded: measured with a blade swept
/// across fandisk and liver, 0 gave flat tets at the first sweep and 1e-6 one flat tet,
/// while 0.01 stayed valid (tests/cut_engine.rs, `a_blade_swept_across_the_body_separates_it`).
pub const MIN_FACE_POINT_MARGIN: f64 = 0.01;

/// Options of a cut. Build from [`CutOptions::DEFAULT`] with the `with_*` methods.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct CutOptions {
    /// Replacement scheme. Default: [`Scheme::Lut`].
    pub scheme: Scheme,
    /// Snapping tolerance, relative to each vertex's scale (its longest incident edge): a
    /// vertex closer than `snap × scale` to the plane, whose projection is within the same
    /// distance of C, is taken to lie on the cut, and the cut passes through it instead of
    /// creating a cut point next to it. This guarantees that every cut point divides its
    /// edge at a parameter in (snap, 1 - snap), at the price of a cut surface that may pass
    /// up to `snap × scale` off the plane (the volume is unchanged: no vertex moves).
    ///
    /// Default: 0.2. Thin children come from planes passing close to vertices. Measured over
    /// the 3,000 random cuts of the test suite on the shared meshes (whose own smallest
    /// dihedral angles are 4.7°–6.2°), the smallest dihedral angle of a created tet is
    /// 1.23° with 0.2 (the target is 1°), 0.8° with 0.15, 0.27° with 0.1 and 0.1° with
    /// 0.05; the smallest child/parent volume ratio is 5e-3 with 0.2 (1.25e-4 with 0.05).
    /// The cost: a crack surface bent towards the snapped vertices, whose area differs from
    /// the plane section's by up to 9% with 0.2 (tests/cut_vtk.rs prints it). Values must
    /// be in [[`MIN_SNAP`], 0.25]: below that, a vertex on the plane up to rounding would
    /// not be snapped and its edges would be cut at its very position (flat tets).
    pub snap: Tolerance,
    /// Face points (crack tips, paper Fig. 4c–e) are placed where C's contour crosses the
    /// segment where the plane meets their face, but no closer to its ends than this
    /// fraction of it; that segment's end out of C (an uncut edge's crossing) is moved
    /// towards the middle of its edge by up to this fraction of the edge, as far as the
    /// face point stays within snapping distance of the plane
    /// ([`super::CutSession`]'s face points).
    ///
    /// Default: 0.5, the middle: the contour's position inside a tet is not followed (the
    /// tables approximate C's contour by the mesh anyway, with an error of a tet's size,
    /// paper §4.1), and crack tips make no thin tets. Smaller values follow the contour
    /// more closely at a price in quality (over the same cuts, with the default `snap`:
    /// 0.4 gives a 1.17° smallest angle, 0.25 gives 0.44°). Values must be in
    /// [[`MIN_FACE_POINT_MARGIN`], 0.5].
    pub face_point_margin: f64,
    /// Count the connected components after the cut (a pass over the whole mesh's tets,
    /// joining their vertices: [`super::Components::count_through_vertices`], timed on its
    /// own). Default: true.
    pub count_components: bool,
    /// Phases with at least this many items (tets, edges) run on all cores, with results
    /// identical to one thread; 0 always, `usize::MAX` never. Default: 4096 (below it the
    /// cost of waking threads exceeds the gain).
    pub parallel_threshold: usize,
    /// Continue the cracks of earlier cuts (a scalpel moved in steps, each step cutting the
    /// area the blade swept since the last): the rules the MT cut always applies, for a
    /// [`super::Cutter`] too. Vertices on the plane just outside C's contour (the last
    /// step's crack tips there) count as on the cut (the *contour band*); vertices on the
    /// plane outside C take the side of their neighbours (the lips of an earlier cut in the
    /// same plane, whose exact side is rounding noise); and crack tips of earlier cuts near
    /// C count as on the cut (when the blade turns or tilts; see
    /// [`super::classify::StateClassifier::with_crack_tips`]). Default: false, for
    /// independent cuts; [`CutOptions::SCALPEL`] sets it.
    pub continue_cracks: bool,
}

impl CutOptions {
    pub const DEFAULT: CutOptions = CutOptions {
        scheme: Scheme::Lut,
        snap: Tolerance { relative: 0.2 },
        face_point_margin: 0.5,
        count_components: true,
        parallel_threshold: 4096,
        continue_cracks: false,
    };

    /// The options of a scalpel moved in steps over a plain mesh: cracks continued
    /// ([`continue_cracks`](Self::continue_cracks)), face points at the smallest margin (a
    /// step's crack tips follow its contour, where the next step begins) and almost no
    /// snapping (1e-6: the lips of the last step lie on the next step's plane, and
    /// snapping them, or vertices near them, onto the cut bends the crack through the lip
    /// tets and makes flat children). The same as the MT scalpel's
    /// ([`super::Scalpel::OPTIONS`]), so a frontier and its model cut alike. Measured on
    /// the shared meshes (tests/cut_scalpel.rs): a blade crossing the body in 7 to 250
    /// steps, straight, turning or tilting, leaves it valid after every step and in exactly
    /// two parts; with [`DEFAULT`](Self::DEFAULT)'s 0.2 snap and 0.5 margin the same
    /// sweeps leave bridges and chips, and from about 30 steps flat tets.
    pub const SCALPEL: CutOptions = CutOptions {
        snap: Tolerance { relative: 1e-6 },
        face_point_margin: MIN_FACE_POINT_MARGIN,
        continue_cracks: true,
        ..CutOptions::DEFAULT
    };

    pub fn with_scheme(mut self, scheme: Scheme) -> Self {
        self.scheme = scheme;
        self
    }

    pub fn with_snap(mut self, snap: Tolerance) -> Self {
        self.snap = snap;
        self
    }

    pub fn with_face_point_margin(mut self, margin: f64) -> Self {
        self.face_point_margin = margin;
        self
    }

    pub fn with_count_components(mut self, count: bool) -> Self {
        self.count_components = count;
        self
    }

    pub fn with_parallel_threshold(mut self, threshold: usize) -> Self {
        self.parallel_threshold = threshold;
        self
    }

    pub fn with_continue_cracks(mut self, continue_cracks: bool) -> Self {
        self.continue_cracks = continue_cracks;
        self
    }

    /// Checks every value against its documented range.
    pub fn check(&self) -> Result<(), CutError> {
        let s = self.snap.relative;
        if !(s.is_finite() && (MIN_SNAP..=0.25).contains(&s)) {
            return Err(CutError::InvalidOption {
                option: "snap",
                value: s,
                expected: "a fraction of the local edge length in [1e-9, 0.25] (below 1e-9 \
                           a vertex on the plane up to rounding is not snapped, and flat \
                           tets result)",
            });
        }
        let m = self.face_point_margin;
        if !(m.is_finite() && (MIN_FACE_POINT_MARGIN..=0.5).contains(&m)) {
            return Err(CutError::InvalidOption {
                option: "face_point_margin",
                value: m,
                expected: "a fraction of the segment in [0.01, 0.5] (nearer its ends, face \
                           points make flat children)",
            });
        }
        Ok(())
    }
}

impl Default for CutOptions {
    fn default() -> Self {
        CutOptions::DEFAULT
    }
}

/// Why a cut was refused (the mesh is left unchanged).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CutError {
    #[error("cut option '{option}' is {value}: expected {expected}")]
    InvalidOption {
        option: &'static str,
        value: f64,
        expected: &'static str,
    },
    #[error(
        "the cut would make the mesh exceed {max} vertices or tets: compact or coarsen it \
         first"
    )]
    TooLarge { max: u32 },
    #[error("{count} positions given for a mesh of {expected} vertices")]
    PositionCount { count: usize, expected: usize },
    #[error("position of vertex {vertex} is not finite")]
    NonFinitePosition { vertex: usize },
    #[error("position of vertex {vertex} {}", crate::geom::out_of_range_text(*value))]
    PositionOutOfRange { vertex: usize, value: f64 },
    #[error("tet {tet} would be inverted or flat at the new positions")]
    InvertedTet { tet: usize },
    #[error("the deformed positions fold tet {tet} of the MT, which the cut meets")]
    DeformationFolds { tet: usize },
    #[error(
        "the cut would replace tet {tet} (configuration {case}) by a flat or inverted tet \
         (its new points round onto each other), even with the snapping tolerance raised \
         to 0.2"
    )]
    FlatChild { tet: usize, case: &'static str },
    #[error(
        "the cut would leave vertex {vertex} it makes hanging in a crack face (its points \
         on earlier cracks' lips round a millionth apart), even with the snapping tolerance \
         raised to 0.2"
    )]
    HangingVertex { vertex: usize },
    #[error(
        "the cut would leave fragment {fragment} of the MT inconsistent ({detail}): refused, \
         the MT is as it was before the cut. Known causes: a cut beginning where an earlier \
         crack ends, at an angle to it (a turning or tilting blade), which MT cuts support \
         only where every level agrees on where that crack ended; a cut crossing earlier \
         cracks where their vertices and edges lie exactly on its plane (a structured grid \
         cut along its planes)"
    )]
    MtInconsistent { fragment: usize, detail: String },
}
