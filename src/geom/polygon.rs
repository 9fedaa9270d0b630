//! The cutting shape: a planar convex polygon C (paper §3), and the scalpel-sweep helper
//! that turns one time step of a blade into such polygons.
//!
//! The polygon keeps its points as given and an exact [`Plane`] through three of them, so
//! that side-of-plane and "does this segment cross C inside C" are exact predicates (the
//! same answer every time they are asked about the same points, which is what lets every
//! tet around an edge agree on whether the edge is cut). Floating-point helpers
//! (distances, the parameter where a segment leaves C) are used only for positions and
//! closeness, never for signs.

use super::predicates::{Sign, orient2d, orient3d};
use super::{Aabb, Plane, Tolerance};
use glam::DVec3;

/// Why a polygon was rejected. Point indices are 0-based positions in the list given.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PolygonError {
    #[error("a cutting polygon needs at least 3 points, got {count}")]
    TooFewPoints { count: usize },
    #[error(
        "a cutting polygon has at most {} points, got {count}: give fewer corners",
        MAX_POLYGON_POINTS
    )]
    TooManyPoints { count: usize },
    #[error("point {index} has a NaN or infinite coordinate")]
    NonFinite { index: usize },
    #[error("point {index} {}", super::out_of_range_text(*value))]
    OutOfRange { index: usize, value: f64 },
    #[error("points {first} and {second} are the same point: give each corner once")]
    RepeatedPoint { first: usize, second: usize },
    #[error("the polygon is degenerate (its points are collinear or its area is zero at its size)")]
    Degenerate,
    #[error(
        "the polygon is not planar: point {index} is {distance:e} from its plane, more than the \
         {allowed:e} allowed (tolerance × diameter); split it into triangles"
    )]
    NotPlanar {
        index: usize,
        distance: f64,
        allowed: f64,
    },
    #[error(
        "the polygon is not convex at point {index} (or winds more than once): give the \
         corners of a convex polygon in order around it"
    )]
    NotConvex { index: usize },
    #[error("the scalpel sweep folds over itself (its two segments cross): use smaller steps")]
    FoldedSweep,
}

/// A planar convex polygon: the cutting shape C.
#[derive(Clone, Debug, PartialEq)]
pub struct CutPolygon {
    points: Vec<DVec3>,
    plane: Plane,
    /// Unit in-plane normal of edge `i` (from point `i` to `i + 1`), pointing into C.
    inward: Vec<DVec3>,
    /// `inward[i] · points[i]`.
    inward_offset: Vec<f64>,
    diameter: f64,
    bbox: Aabb,
    /// Error bounds of the floating-point signed distance (see `side_filtered`): the
    /// largest coordinate of the plane's points, and the possible error of its unit normal.
    coord_scale: f64,
    normal_error: f64,
    /// Largest distance of a corner to the exact plane (C's departure from planarity).
    planarity: f64,
}

/// The most corners a cutting polygon may have. Checking a polygon compares every pair of
/// corners (its diameter, repeated corners, the widest triangle for its plane): 40 ms at
/// this size, where 30,000 corners took 2 s and a million would take most of an hour. A
/// scalpel's sweep has 3 or 4; a disk drawn with a few hundred is round to the eye.
pub const MAX_POLYGON_POINTS: usize = 4096;

impl CutPolygon {
    /// The planarity tolerance [`new`](Self::new) uses: points within 1e-6 × diameter of the
    /// polygon's plane. Exact inputs pass; coordinates typed with six or more significant
    /// digits pass; a visibly bent quadrilateral does not (split it in two triangles, as
    /// [`scalpel_sweep`] does).
    pub const DEFAULT_PLANARITY: Tolerance = Tolerance { relative: 1e-6 };

    /// A polygon from its corners in order (either direction), checked with
    /// [`DEFAULT_PLANARITY`](Self::DEFAULT_PLANARITY).
    pub fn new(points: &[DVec3]) -> Result<CutPolygon, PolygonError> {
        Self::with_tolerance(points, Self::DEFAULT_PLANARITY)
    }

    /// A polygon from its corners in order, checked: at least 3 (at most
    /// [`MAX_POLYGON_POINTS`]) finite, distinct points,
    /// non-zero area, every point within `planarity × diameter` of the plane, convex and
    /// winding once. The positive side of its plane is the one its right-hand normal
    /// (corners counter-clockwise) points to.
    pub fn with_tolerance(
        points: &[DVec3],
        planarity: Tolerance,
    ) -> Result<CutPolygon, PolygonError> {
        let n = points.len();
        if n < 3 {
            return Err(PolygonError::TooFewPoints { count: n });
        }
        if n > MAX_POLYGON_POINTS {
            return Err(PolygonError::TooManyPoints { count: n });
        }
        check_points(points)?;
        for i in 0..n {
            for j in i + 1..n {
                if points[i] == points[j] {
                    return Err(PolygonError::RepeatedPoint {
                        first: i,
                        second: j,
                    });
                }
            }
        }
        let bbox = Aabb::from_points(points);
        let mut diameter = 0.0f64;
        for i in 0..n {
            for j in i + 1..n {
                diameter = diameter.max(points[i].distance(points[j]));
            }
        }
        // Newell's normal: robust for any planar polygon, twice the area in length.
        let centroid = points.iter().copied().sum::<DVec3>() / n as f64;
        let mut newell = DVec3::ZERO;
        for i in 0..n {
            let (a, b) = (points[i] - centroid, points[(i + 1) % n] - centroid);
            newell += a.cross(b);
        }
        let area = 0.5 * newell.length();
        let scale = planarity.distance(diameter);
        if !(area.is_finite() && area > scale * scale) {
            return Err(PolygonError::Degenerate);
        }
        let normal = newell.normalize();
        let allowed = planarity.distance(diameter);
        for (index, p) in points.iter().enumerate() {
            let distance = (*p - centroid).dot(normal).abs();
            if distance > allowed {
                return Err(PolygonError::NotPlanar {
                    index,
                    distance,
                    allowed,
                });
            }
        }
        // Convexity, exactly, in the coordinate plane the polygon projects to best; the
        // projection keeps the doubles as they are (one coordinate dropped), so orient2d is
        // exact on them.
        let axis = normal.abs().max_position();
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        let flip = normal[axis] < 0.0;
        let pr = |p: DVec3| [p[u], p[v]];
        let mut turns = 0;
        for i in 0..n {
            let (a, b, c) = (points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
            let s = orient2d(pr(a), pr(b), pr(c));
            let s = if flip { s.flip() } else { s };
            match s {
                Sign::Negative => return Err(PolygonError::NotConvex { index: i }),
                Sign::Positive => turns += 1,
                Sign::Zero => {}
            }
        }
        if turns < 3 {
            return Err(PolygonError::Degenerate);
        }
        // Winding once: the exterior angles of a convex polygon add up to one turn.
        let mut total = 0.0;
        for i in 0..n {
            let (a, b, c) = (points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
            let (d1, d2) = (b - a, c - b);
            total += d1.cross(d2).dot(normal).atan2(d1.dot(d2));
        }
        if total > 3.0 * std::f64::consts::PI {
            return Err(PolygonError::NotConvex { index: 0 });
        }
        // The exact plane: through the corner 0 and the pair spanning the largest triangle
        // with it, ordered like the polygon so its normal agrees with Newell's.
        let mut best = (0.0, 1, 2);
        for i in 1..n {
            for j in i + 1..n {
                let a = (points[i] - points[0])
                    .cross(points[j] - points[0])
                    .length();
                if a > best.0 {
                    best = (a, i, j);
                }
            }
        }
        let plane = Plane::from_points(points[0], points[best.1], points[best.2])
            .ok_or(PolygonError::Degenerate)?;
        let [c0, c1, c2] = plane.points;
        let coord_scale = [c0, c1, c2]
            .iter()
            .map(|c| c.abs().max_element())
            .fold(0.0, f64::max);
        let longest = c0.distance(c1).max(c1.distance(c2)).max(c2.distance(c0));
        let height = best.0 / longest;
        // The normal comes from differences of coordinates known to ε × coord_scale, over a
        // triangle of this height: its direction is off by at most a few such ratios.
        let normal_error = 16.0 * f64::EPSILON * coord_scale / height;
        let planarity = points
            .iter()
            .map(|p| plane.signed_distance(*p).abs())
            .fold(0.0, f64::max)
            + 16.0 * f64::EPSILON * coord_scale
            + normal_error * coord_scale * 4.0;
        let mut inward = Vec::with_capacity(n);
        let mut inward_offset = Vec::with_capacity(n);
        for i in 0..n {
            let (a, b) = (points[i], points[(i + 1) % n]);
            let m = plane.normal.cross(b - a).normalize();
            inward.push(m);
            inward_offset.push(m.dot(a));
        }
        Ok(CutPolygon {
            points: points.to_vec(),
            plane,
            inward,
            inward_offset,
            diameter,
            bbox,
            coord_scale,
            normal_error,
            planarity,
        })
    }

    /// The corners, as given.
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// The exact plane of the polygon.
    pub fn plane(&self) -> &Plane {
        &self.plane
    }

    /// Unit normal, pointing to the positive side.
    pub fn normal(&self) -> DVec3 {
        self.plane.normal
    }

    /// Largest distance between two corners.
    pub fn diameter(&self) -> f64 {
        self.diameter
    }

    /// Bounding box of the corners.
    pub fn bbox(&self) -> Aabb {
        self.bbox
    }

    /// Exact side of `p` with respect to the plane.
    #[inline]
    pub fn side(&self, p: DVec3) -> Sign {
        self.plane.side(p)
    }

    /// The exact side of `p` (as [`side`](Self::side)), given `d =
    /// signed_distance(p)`: the sign of `d` when it exceeds a bound on its rounding error
    /// (the dot products', and the normal's direction error over the distance from the
    /// plane's points), the exact predicate otherwise. Equal to `side(p)` always; much
    /// cheaper for points away from the plane.
    #[inline]
    pub fn side_filtered(&self, p: DVec3, d: f64) -> Sign {
        let bound = 16.0 * f64::EPSILON * (p.abs().max_element() + self.coord_scale)
            + self.normal_error * (p - self.plane.points[0]).abs().max_element() * 2.0;
        if d > bound {
            Sign::Positive
        } else if d < -bound {
            Sign::Negative
        } else {
            self.plane.side(p)
        }
    }

    /// A bound on the rounding error of [`signed_distance`](Self::signed_distance) for
    /// every point whose coordinates are at most `extent` in magnitude: beyond it, the sign
    /// of the distance is the exact side.
    pub fn filter_bound(&self, extent: f64) -> f64 {
        16.0 * f64::EPSILON * (extent + self.coord_scale)
            + self.normal_error * (extent + self.coord_scale) * 4.0
    }

    /// Signed distance of `p` to the plane (floating point).
    #[inline]
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        self.plane.signed_distance(p)
    }

    /// How far inside C the projection of `p` on the plane is: the smallest distance to an
    /// edge line, negative outside (floating point; for closeness decisions).
    #[inline]
    pub fn inside_margin(&self, p: DVec3) -> f64 {
        let mut m = f64::INFINITY;
        for (n, o) in self.inward.iter().zip(&self.inward_offset) {
            m = m.min(n.dot(p) - o);
        }
        m
    }

    /// Distance from the projection of `p` on the plane to C (0 inside; floating point).
    pub fn projection_distance(&self, p: DVec3) -> f64 {
        if self.inside_margin(p) >= 0.0 {
            return 0.0;
        }
        let q = p - self.plane.normal * self.signed_distance(p);
        let n = self.points.len();
        let mut best = f64::INFINITY;
        for i in 0..n {
            let (a, b) = (self.points[i], self.points[(i + 1) % n]);
            let ab = b - a;
            let t = ((q - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
            best = best.min(q.distance(a + ab * t));
        }
        best
    }

    /// Exactly: whether the segment `a`–`b`, whose ends lie strictly on opposite sides of
    /// the plane, crosses it strictly inside C. The line `ab` passes on the inner side of
    /// every edge line of C: `orient3d(a, b, cᵢ, cᵢ₊₁)` has one non-zero sign for all `i`.
    /// A crossing on C's contour is not strictly inside.
    ///
    /// A segment whose ends both lie beyond one edge line of C, by more than rounding and
    /// C's departure from planarity, does not cross inside C (every point of it lies
    /// beyond that line), and is decided so before the orientations: for a segment lying
    /// in the plane within rounding, C's corners (rarely exactly coplanar: a plane through
    /// grid points with a diagonal normal) each make an edge's orientation test with a
    /// slightly different plane, and the signs are noise. Such an edge "crossed" far from C
    /// is cut in the tets a query reaches and left whole in the others.
    pub fn segment_crosses_inside(&self, a: DVec3, b: DVec3) -> bool {
        let f = self.filter_bound(a.abs().max(b.abs()).max_element());
        let slack = 4.0 * (self.planarity + f);
        let beyond = |(m, o): (&DVec3, &f64)| m.dot(a) - o < -slack && m.dot(b) - o < -slack;
        if self.inward.iter().zip(&self.inward_offset).any(beyond) {
            return false;
        }
        let n = self.points.len();
        let mut sign = Sign::Zero;
        for i in 0..n {
            let s = orient3d(a, b, self.points[i], self.points[(i + 1) % n]);
            if s == Sign::Zero || (sign != Sign::Zero && s != sign) {
                return false;
            }
            sign = s;
        }
        true
    }

    /// [`segment_crosses_inside`](Self::segment_crosses_inside), given the signed distances
    /// `da`, `db` of the ends: decided from the floating-point crossing point when it is
    /// farther from C's contour than every error that could make the exact predicate
    /// disagree (rounding of the crossing, C's own departure from planarity magnified by
    /// how obliquely the segment meets the plane), exactly otherwise. Always equal to
    /// `segment_crosses_inside(a, b)`.
    pub fn segment_crosses_inside_filtered(&self, a: DVec3, b: DVec3, da: f64, db: f64) -> bool {
        let den = da - db;
        let len = a.distance(b);
        if den.abs() > 1e-3 * len {
            let x = a + (b - a) * (da / den);
            let margin = self.inside_margin(x);
            // An error h across the plane (C's corners off it, rounded distances) moves the
            // crossing by h × len / |den| along the segment; rounding moves the rest by f.
            let f = self.filter_bound(a.abs().max(b.abs()).max_element());
            let slack = (self.planarity + f) * (len / den.abs()) * 4.0 + f;
            if margin > slack {
                return true;
            }
            if margin < -slack {
                return false;
            }
        }
        self.segment_crosses_inside(a, b)
    }

    /// The parameter `s` in [0, 1] where the segment from `inside` to `outside` (both on or
    /// near the plane) leaves C: the first edge line it crosses (floating point).
    pub fn contour_parameter(&self, inside: DVec3, outside: DVec3) -> f64 {
        let mut s = 1.0f64;
        for (n, o) in self.inward.iter().zip(&self.inward_offset) {
            let (gi, go) = (n.dot(inside) - o, n.dot(outside) - o);
            if go < 0.0 && gi > go {
                s = s.min(gi / (gi - go));
            }
        }
        s.clamp(0.0, 1.0)
    }
}

/// The planarity tolerance of the scalpels' sweeps ([`scalpel_sweep`] as
/// [`crate::cut::Scalpel`], the `mtcut scalpel` command and the C ABI's sweep functions
/// call it): a convex sweep planar within 1e-9 of its size is one quadrilateral, a twisted
/// one two triangles, so a blade moved by the same positions is cut alike by all of them.
pub const SWEEP_PLANARITY: Tolerance = Tolerance { relative: 1e-9 };

/// How far from an earlier cut's plane, relative to the model's bounding-box diagonal, a
/// polygon cutting a multiresolution model is still cut in that plane (the MT cut's and
/// the live model's limits, `mtcut::cut::mt_cut` and `mtcut::cut::live`).
pub const PLANE_SNAP: f64 = 1e-5;

/// The largest angle (radians) between such a polygon and the earlier cut's plane
/// ([`PLANE_SNAP`]).
pub const PLANE_SNAP_ANGLE: f64 = 1e-3;

/// `polygon` moved onto the nearest of `planes` (each a unit normal and a point: earlier
/// cuts' planes) it lies close to without lying in it: its normal within
/// [`PLANE_SNAP_ANGLE`] of the plane's (either orientation), every corner within
/// `distance` of it, some corner farther than rounding (1e-9 of the corners' coordinates
/// and of the polygon's size, the tolerance by which steps of a blade continuing in one
/// plane are told apart). The corners are projected in their order, so the polygon keeps
/// its orientation. `None` when no plane is close, when the polygon already lies in one of
/// them, or when its projection is not a valid polygon.
///
/// Why: a cut overlapping an earlier crack nearly in its plane (offset by 1e-7 of the
/// model's size, or tilted by 1e-6) meets that crack's lips and tips on either side of its
/// plane by amounts below any snapping distance, and different levels of a
/// multiresolution model then disagree on where it passes (measured: 52 of 180 such cuts
/// refused on the three shared meshes); in the crack's plane, none is.
pub(crate) fn snap_to_plane(
    polygon: &CutPolygon,
    planes: impl Iterator<Item = (DVec3, DVec3)>,
    distance: f64,
) -> Option<CutPolygon> {
    let rounding = in_plane_rounding(polygon);
    let mut nearest: Option<(f64, DVec3, DVec3)> = None;
    for (normal, point) in planes {
        let Some(far) = plane_offset(polygon, normal, point) else {
            continue;
        };
        if far <= rounding {
            return None;
        }
        if far <= distance && nearest.is_none_or(|(f, _, _)| far < f) {
            nearest = Some((far, normal, point));
        }
    }
    let (_, normal, point) = nearest?;
    let projected: Vec<DVec3> = polygon
        .points()
        .iter()
        .map(|p| *p - normal * normal.dot(*p - point))
        .collect();
    CutPolygon::new(&projected).ok()
}

/// Whether `polygon` lies in one of `planes` (each a unit normal and a point) to the
/// rounding by which [`snap_to_plane`] leaves it in place: a cut in a plane already
/// recorded.
pub(crate) fn lies_in_plane(
    polygon: &CutPolygon,
    mut planes: impl Iterator<Item = (DVec3, DVec3)>,
) -> bool {
    let rounding = in_plane_rounding(polygon);
    planes.any(|(normal, point)| {
        plane_offset(polygon, normal, point).is_some_and(|far| far <= rounding)
    })
}

/// How far `polygon`'s farthest corner lies from the plane through `point` with unit
/// `normal`; `None` when their normals differ by more than [`PLANE_SNAP_ANGLE`].
fn plane_offset(polygon: &CutPolygon, normal: DVec3, point: DVec3) -> Option<f64> {
    if polygon.normal().cross(normal).length() > PLANE_SNAP_ANGLE.sin() {
        return None;
    }
    Some(
        polygon
            .points()
            .iter()
            .map(|p| normal.dot(*p - point).abs())
            .fold(0.0, f64::max),
    )
}

/// The distance below which `polygon` lies in a plane: 1e-9 of its corners' coordinates
/// and of its size (see [`snap_to_plane`]).
fn in_plane_rounding(polygon: &CutPolygon) -> f64 {
    let b = polygon.bbox();
    1e-9 * (b.min.abs().max(b.max.abs()).max_element() + polygon.diameter())
}

/// Every point finite and within ±[`MAX_COORDINATE`](super::MAX_COORDINATE).
pub(crate) fn check_points(points: &[DVec3]) -> Result<(), PolygonError> {
    match super::first_unsupported(points) {
        Some((index, value)) if !value.is_finite() => Err(PolygonError::NonFinite { index }),
        Some((index, value)) => Err(PolygonError::OutOfRange { index, value }),
        None => Ok(()),
    }
}

/// The polygons swept by a straight blade moving during one time step: the segment
/// `start[0]`–`start[1]` at t0 and `end[0]`–`end[1]` at t1 (corresponding ends). One
/// quadrilateral when it is planar (within `planarity` of its size) and convex; otherwise
/// two triangles (along the shorter diagonal, or from the reflex corner of a planar
/// non-convex quadrilateral). Zero-area triangles (an end that did not move) are dropped.
/// The first of [`scalpel_sweep_splits`].
pub fn scalpel_sweep(
    start: [DVec3; 2],
    end: [DVec3; 2],
    planarity: Tolerance,
) -> Result<Vec<CutPolygon>, PolygonError> {
    scalpel_sweep_splits(start, end, planarity).map(|mut splits| splits.swap_remove(0))
}

/// Every way of cutting what [`scalpel_sweep`] cuts, its own first: one quadrilateral or
/// triangle alone; two triangles along the shorter diagonal, then along the longer one
/// (when its triangles do not fold over each other: a planar non-convex quadrilateral
/// splits at its reflex corner only), then each such pair in the other order. A
/// multiresolution model may refuse the second of two triangles where it meets the first
/// at an angle and take another split of the same sweep (`mtcut::cut::Scalpel::step`):
/// the area cut is the same up to the triangles' fold.
pub fn scalpel_sweep_splits(
    start: [DVec3; 2],
    end: [DVec3; 2],
    planarity: Tolerance,
) -> Result<Vec<Vec<CutPolygon>>, PolygonError> {
    let quad = [start[0], start[1], end[1], end[0]];
    check_points(&quad)?;
    match (start[0] == end[0], start[1] == end[1]) {
        (true, true) => return Err(PolygonError::Degenerate),
        (true, false) => {
            return CutPolygon::with_tolerance(&quad[..3], planarity).map(|p| vec![vec![p]]);
        }
        (false, true) => {
            return CutPolygon::with_tolerance(&[quad[0], quad[1], quad[3]], planarity)
                .map(|p| vec![vec![p]]);
        }
        (false, false) => {}
    }
    if let Ok(p) = CutPolygon::with_tolerance(&quad, planarity) {
        return Ok(vec![vec![p]]);
    }
    // A planar non-convex quadrilateral only splits along the diagonal at its reflex
    // corner (the other gives triangles facing opposite ways), and one whose both splits
    // face opposite ways folds over itself.
    let shorter = if quad[0].distance(quad[2]) <= quad[1].distance(quad[3]) {
        0
    } else {
        1
    };
    let mut last = PolygonError::FoldedSweep;
    let mut splits = Vec::with_capacity(4);
    for k in [shorter, 1 - shorter] {
        let tris = [
            [quad[k], quad[k + 1], quad[k + 2]],
            [quad[k], quad[k + 2], quad[(k + 3) % 4]],
        ];
        match two_triangles(&tris, planarity) {
            Ok(out) if same_orientation(&out) => splits.push(out),
            Ok(_) => {}
            Err(e) => last = e,
        }
    }
    if splits.is_empty() {
        return Err(last);
    }
    let reversed: Vec<Vec<CutPolygon>> = splits
        .iter()
        .filter(|s| s.len() == 2)
        .map(|s| vec![s[1].clone(), s[0].clone()])
        .collect();
    splits.extend(reversed);
    Ok(splits)
}

fn two_triangles(
    tris: &[[DVec3; 3]; 2],
    planarity: Tolerance,
) -> Result<Vec<CutPolygon>, PolygonError> {
    let mut out = Vec::with_capacity(2);
    for t in tris {
        match CutPolygon::with_tolerance(t, planarity) {
            Ok(p) => out.push(p),
            Err(PolygonError::Degenerate) | Err(PolygonError::RepeatedPoint { .. }) => {}
            Err(e) => return Err(e),
        }
    }
    if out.is_empty() {
        return Err(PolygonError::Degenerate);
    }
    Ok(out)
}

/// Whether two triangles of a split planar quadrilateral face the same way (they do not
/// overlap then).
fn same_orientation(tris: &[CutPolygon]) -> bool {
    tris.len() < 2 || tris[0].normal().dot(tris[1].normal()) > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Vec<DVec3> {
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ]
    }

    #[test]
    fn square_is_accepted_and_oriented() {
        let c = CutPolygon::new(&square()).unwrap();
        assert!((c.normal() - DVec3::Z).length() < 1e-15);
        assert_eq!(c.side(DVec3::new(0.5, 0.5, 1.0)), Sign::Positive);
        assert!((c.inside_margin(DVec3::new(0.25, 0.5, 3.0)) - 0.25).abs() < 1e-15);
        assert!(c.inside_margin(DVec3::new(1.5, 0.5, 0.0)) < 0.0);
        // Clockwise input: same polygon, the other side positive.
        let mut cw = square();
        cw.reverse();
        let c2 = CutPolygon::new(&cw).unwrap();
        assert_eq!(c2.side(DVec3::new(0.5, 0.5, 1.0)), Sign::Negative);
    }

    #[test]
    fn bad_polygons_are_named() {
        let s = square();
        assert_eq!(
            CutPolygon::new(&s[..2]),
            Err(PolygonError::TooFewPoints { count: 2 })
        );
        // A disk of as many corners as allowed, and one more.
        let disk = |n: usize| -> Vec<DVec3> {
            (0..n)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / n as f64;
                    DVec3::new(a.cos(), a.sin(), 0.0)
                })
                .collect()
        };
        assert!(CutPolygon::new(&disk(MAX_POLYGON_POINTS)).is_ok());
        let e = CutPolygon::new(&disk(MAX_POLYGON_POINTS + 1)).unwrap_err();
        assert_eq!(e, PolygonError::TooManyPoints { count: 4097 });
        assert!(
            e.to_string().contains("at most 4096 points, got 4097"),
            "{e}"
        );
        let mut nan = s.clone();
        nan[2].y = f64::NAN;
        assert_eq!(
            CutPolygon::new(&nan),
            Err(PolygonError::NonFinite { index: 2 })
        );
        let mut rep = s.clone();
        rep[3] = rep[1];
        assert!(matches!(
            CutPolygon::new(&rep),
            Err(PolygonError::RepeatedPoint {
                first: 1,
                second: 3
            })
        ));
        let line = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert_eq!(CutPolygon::new(&line), Err(PolygonError::Degenerate));
        let mut bent = s.clone();
        bent[2].z = 0.01;
        assert!(matches!(
            CutPolygon::new(&bent),
            Err(PolygonError::NotPlanar { .. })
        ));
        let dart = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.5, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.3, 0.5, 0.0),
        ];
        assert!(matches!(
            CutPolygon::new(&dart),
            Err(PolygonError::NotConvex { index: 3 })
        ));
        // A pentagram's corners turn the same way but wind twice.
        let star: Vec<DVec3> = (0..5)
            .map(|k| {
                let a = k as f64 * 4.0 * std::f64::consts::PI / 5.0;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        assert!(matches!(
            CutPolygon::new(&star),
            Err(PolygonError::NotConvex { .. })
        ));
    }

    #[test]
    fn segment_crossing_is_exact_on_the_contour() {
        let c = CutPolygon::new(&square()).unwrap();
        let up = |x: f64, y: f64| DVec3::new(x, y, 1.0);
        let down = |x: f64, y: f64| DVec3::new(x, y, -1.0);
        assert!(c.segment_crosses_inside(up(0.5, 0.5), down(0.5, 0.5)));
        assert!(c.segment_crosses_inside(down(0.1, 0.9), up(0.2, 0.8)));
        // Through the contour exactly: not strictly inside.
        assert!(!c.segment_crosses_inside(up(1.0, 0.5), down(1.0, 0.5)));
        assert!(!c.segment_crosses_inside(up(1.5, 0.5), down(1.5, 0.5)));
        let s = c.contour_parameter(DVec3::new(0.5, 0.5, 0.0), DVec3::new(1.5, 0.5, 0.0));
        assert!((s - 0.5).abs() < 1e-15);
    }

    /// A segment lying in the plane to rounding, 3 units beyond C: its ends' sides of the
    /// exact plane are rounding, and each of C's edges (corners not exactly coplanar)
    /// orients it against a slightly different plane; it does not cross inside C.
    #[test]
    fn a_segment_in_the_plane_far_beyond_c_does_not_cross_it() {
        let c = CutPolygon::new(&[
            DVec3::new(3.570094865175389, 2.5700948651753883, -7.656265604737321),
            DVec3::new(8.151435061419807, 7.151435061419807, -1.1772721653634481),
            DVec3::new(5.521885042394584, 4.521885042394585, 2.5414731344804524),
            DVec3::new(
                0.9405448461501664,
                -0.059455153849834436,
                -3.9375203048934204,
            ),
        ])
        .unwrap();
        let (a, b) = (DVec3::new(4.0, 3.0, 4.0), DVec3::new(4.0, 3.0, 5.0));
        assert_ne!(
            c.side(a),
            c.side(b),
            "the ends lie on either side, by rounding"
        );
        assert!(!c.segment_crosses_inside(a, b));
        let (da, db) = (c.signed_distance(a), c.signed_distance(b));
        assert!(!c.segment_crosses_inside_filtered(a, b, da, db));
    }

    #[test]
    fn sweeps_give_a_quad_or_two_triangles() {
        let z = Tolerance::new(1e-9).unwrap();
        let flat = scalpel_sweep(
            [DVec3::ZERO, DVec3::X],
            [DVec3::Y, DVec3::new(1.0, 1.0, 0.0)],
            z,
        )
        .unwrap();
        assert_eq!(flat.len(), 1);
        assert_eq!(flat[0].points().len(), 4);
        let twisted = scalpel_sweep(
            [DVec3::ZERO, DVec3::X],
            [DVec3::Y, DVec3::new(1.0, 1.0, 0.5)],
            z,
        )
        .unwrap();
        assert_eq!(twisted.len(), 2);
        let pivot = scalpel_sweep([DVec3::ZERO, DVec3::X], [DVec3::ZERO, DVec3::Y], z).unwrap();
        assert_eq!(pivot.len(), 1);
        assert_eq!(pivot[0].points().len(), 3);
        let crossed = scalpel_sweep(
            [DVec3::ZERO, DVec3::X],
            [DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            z,
        );
        assert_eq!(crossed, Err(PolygonError::FoldedSweep));
        assert!(scalpel_sweep([DVec3::ZERO, DVec3::X], [DVec3::ZERO, DVec3::X], z).is_err());
    }

    #[test]
    fn a_twisted_sweep_splits_four_ways_and_a_flat_one_one_way() {
        let z = Tolerance::new(1e-9).unwrap();
        let (start, end) = (
            [DVec3::ZERO, DVec3::X],
            [DVec3::Y, DVec3::new(1.0, 1.0, 0.5)],
        );
        let splits = scalpel_sweep_splits(start, end, z).unwrap();
        assert_eq!(splits[0], scalpel_sweep(start, end, z).unwrap());
        assert_eq!(splits.len(), 4);
        let corners = |s: &[CutPolygon]| -> Vec<Vec<DVec3>> {
            s.iter().map(|p| p.points().to_vec()).collect()
        };
        // Along the other diagonal: no triangle of the first split.
        assert!(
            corners(&splits[1])
                .iter()
                .all(|t| !corners(&splits[0]).contains(t))
        );
        // Then each pair in the other order.
        for (k, r) in [(0, 2), (1, 3)] {
            let mut back = corners(&splits[k]);
            back.reverse();
            assert_eq!(corners(&splits[r]), back);
        }
        // Each: two triangles of the quadrilateral's corners, sharing a diagonal.
        let quad = [start[0], start[1], end[1], end[0]];
        for s in &splits {
            let [t0, t1] = [&s[0], &s[1]].map(|p| p.points().to_vec());
            assert!(t0.iter().chain(&t1).all(|p| quad.contains(p)));
            assert!(quad.iter().all(|p| t0.contains(p) || t1.contains(p)));
            assert_eq!(t0.iter().filter(|p| t1.contains(p)).count(), 2);
        }
        let flat = scalpel_sweep_splits(start, [DVec3::Y, DVec3::new(1.0, 1.0, 0.0)], z).unwrap();
        assert_eq!(flat.len(), 1);
    }
}
