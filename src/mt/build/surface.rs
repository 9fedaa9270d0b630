//! The input's boundary surface, kept fixed during the build: a BVH over its triangles for
//! "how far is this point from the original boundary" (the coarse-to-original half of the
//! boundary deviation), and the feature edges and corners found on it.

use crate::geom::{Aabb, DVec3};
use crate::mesh::VertexId;
use crate::mt::bvh::Bvh;
use std::cell::Cell;
use std::collections::HashMap;

/// The original boundary surface.
pub(super) struct Surface {
    positions: Vec<DVec3>,
    tris: Vec<[DVec3; 3]>,
    bvh: Bvh,
    /// Triangles around each vertex (CSR): seeds for nearest-triangle searches.
    around_offsets: Vec<u32>,
    around: Vec<u32>,
}

impl Surface {
    pub(super) fn new(positions: &[DVec3], faces: &[[VertexId; 3]]) -> Surface {
        let tris: Vec<[DVec3; 3]> = faces
            .iter()
            .map(|f| f.map(|v| positions[v.idx()]))
            .collect();
        let boxes: Vec<Aabb> = tris.iter().map(Aabb::from_points).collect();
        let mut around_offsets = vec![0u32; positions.len() + 1];
        for f in faces {
            for v in f {
                around_offsets[v.idx() + 1] += 1;
            }
        }
        for i in 0..positions.len() {
            around_offsets[i + 1] += around_offsets[i];
        }
        let mut fill = around_offsets.clone();
        let mut around = vec![0u32; faces.len() * 3];
        for (k, f) in faces.iter().enumerate() {
            for v in f {
                around[fill[v.idx()] as usize] = k as u32;
                fill[v.idx()] += 1;
            }
        }
        Surface {
            positions: positions.to_vec(),
            bvh: Bvh::new(&boxes),
            tris,
            around_offsets,
            around,
        }
    }

    /// An upper bound of the distance from `p` to the surface when one at most `radius`
    /// is found, else `None` (then the distance exceeds `radius`).
    ///
    /// Cheap guesses come first, each giving an upper bound of the distance (which keeps
    /// every decision on the safe side): the triangle `hint` (the answer for a previous,
    /// nearby point; updated), then the original triangles around the seed vertex nearest
    /// to `p`; only when none is within `radius` is the hierarchy searched, nearest first.
    pub(super) fn distance_within(
        &self,
        p: DVec3,
        radius: f64,
        seeds: &[u32],
        hint: &mut u32,
    ) -> Option<f64> {
        // Neighbouring samples are usually nearest to the same original triangle.
        if let Some(t) = self.tris.get(*hint as usize) {
            let d = point_triangle_distance(p, t);
            if d <= radius {
                return Some(d);
            }
        }
        let nearest_seed = seeds.iter().copied().min_by(|&a, &b| {
            let (da, db) = (
                (self.positions[a as usize] - p).length_squared(),
                (self.positions[b as usize] - p).length_squared(),
            );
            da.total_cmp(&db).then(a.cmp(&b))
        });
        let mut start = radius;
        let mut found_seed = false;
        if let Some(v) = nearest_seed {
            let (a, b) = (
                self.around_offsets[v as usize] as usize,
                self.around_offsets[v as usize + 1] as usize,
            );
            for &k in &self.around[a..b] {
                let d = point_triangle_distance(p, &self.tris[k as usize]);
                if d <= start {
                    start = d;
                    found_seed = true;
                    *hint = k;
                }
            }
        }
        if found_seed {
            return Some(start);
        }
        let best = Cell::new(start);
        let found = Cell::new(found_seed);
        let nearest = Cell::new(*hint);
        self.bvh.query_nearest(
            |b| box_distance_squared(b, p).sqrt(),
            || best.get(),
            |i| {
                let d = point_triangle_distance(p, &self.tris[i as usize]);
                if d <= best.get() {
                    best.set(d);
                    found.set(true);
                    nearest.set(i);
                }
            },
        );
        if found.get() {
            *hint = nearest.get();
        }
        found.get().then(|| best.get())
    }
}

/// Subdivisions per edge of the grid a new boundary face is sampled on.
const GRID: u8 = 8;

/// The grid points of a new boundary face other than its corners, as barycentric
/// coordinates (in `1 / GRID`) of its second and third corner.
const GRID_POINTS: [(u8, u8); ((GRID as usize + 1) * (GRID as usize + 2)) / 2 - 3] = {
    let mut out = [(0u8, 0u8); ((GRID as usize + 1) * (GRID as usize + 2)) / 2 - 3];
    let mut k = 0;
    let mut i = 0;
    while i <= GRID {
        let mut j = 0;
        while i + j <= GRID {
            let corner = (i == 0 && j == 0) || i == GRID || j == GRID;
            if !corner {
                out[k] = (i, j);
                k += 1;
            }
            j += 1;
        }
        i += 1;
    }
    out
};

impl Surface {
    /// Whether every point of triangle `t` on the grid of [`GRID`] subdivisions per edge
    /// (its corners excepted: they are vertices of the surface) lies within `radius` of
    /// the surface; if so, an upper bound of their largest distance.
    ///
    /// The distance to the surface is 1-Lipschitz, so a point searched for with bound
    /// `u` vouches for every point within `radius - u` of it (with bound `u` plus the
    /// distance between them): most grid points of a face that is small next to the
    /// tolerance need no search of their own. The answer is the same as searching every
    /// grid point; only the bound reported can be larger.
    pub(super) fn grid_within(&self, t: [DVec3; 3], radius: f64, seeds: &[u32]) -> Option<f64> {
        let g = GRID as f64;
        let mut hint = u32::MAX;
        let mut deviation = 0.0f64;
        // Searched points with their bounds, newest last (a few: neighbours come in order).
        let mut anchors: [(DVec3, f64); 4] = [(DVec3::ZERO, f64::INFINITY); 4];
        let mut next = 0;
        for (i, j) in GRID_POINTS {
            let (a, b) = (i as f64 / g, j as f64 / g);
            let q = t[0] * (1.0 - a - b) + t[1] * a + t[2] * b;
            let vouched = anchors.iter().find_map(|&(p, u)| {
                let d = u + (q - p).length();
                (d <= radius).then_some(d)
            });
            let d = match vouched {
                Some(d) => d,
                None => {
                    let d = self.distance_within(q, radius, seeds, &mut hint)?;
                    anchors[next % anchors.len()] = (q, d);
                    next += 1;
                    d
                }
            };
            deviation = deviation.max(d);
        }
        Some(deviation)
    }
}

fn box_distance_squared(b: &Aabb, p: DVec3) -> f64 {
    (p.clamp(b.min, b.max) - p).length_squared()
}

/// Distance from `p` to the closed triangle `t` (Ericson, Real-Time Collision Detection,
/// §5.1.5: the closest point by Voronoi region). A degenerate triangle falls back to its
/// edges.
pub(crate) fn point_triangle_distance(p: DVec3, t: &[DVec3; 3]) -> f64 {
    let [a, b, c] = *t;
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return segment_distance(p, a, b);
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return segment_distance(p, a, c);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return segment_distance(p, b, c);
    }
    let sum = va + vb + vc;
    if sum.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return segment_distance(p, a, b)
            .min(segment_distance(p, b, c))
            .min(segment_distance(p, c, a));
    }
    let q = a + ab * (vb / sum) + ac * (vc / sum);
    (p - q).length()
}

fn segment_distance(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let s = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * s)).length()
}

/// A vertex's role in the build, which decides where it may collapse.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum VertexClass {
    /// Not on the boundary: collapses onto any neighbour.
    Interior,
    /// On the boundary, on no feature edge: collapses along a boundary edge.
    Smooth,
    /// On exactly two feature edges: collapses along one of them (the feature line stays).
    Crease,
    /// On one or more than two feature edges: never removed.
    Corner,
    /// Removed by a collapse.
    Removed,
}

/// Sorted key of an undirected edge.
#[inline]
pub(super) fn edge_key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// Feature edges of the boundary `faces` (outward triangles of a closed 2-manifold): edges
/// whose two faces' normals differ by more than `angle_degrees`.
pub(super) fn feature_edges(
    positions: &[DVec3],
    faces: &[[VertexId; 3]],
    angle_degrees: f64,
) -> Vec<(u32, u32)> {
    let cos_limit = angle_degrees.to_radians().cos();
    let mut normals: HashMap<(u32, u32), DVec3> = HashMap::with_capacity(faces.len() * 2);
    let mut out = Vec::new();
    for f in faces {
        let [a, b, c] = f.map(|v| positions[v.idx()]);
        let n = (b - a).cross(c - a).normalize_or_zero();
        for k in 0..3 {
            let e = edge_key(f[k].0, f[(k + 1) % 3].0);
            match normals.remove(&e) {
                Some(m) => {
                    if n.dot(m) < cos_limit {
                        out.push(e);
                    }
                }
                None => {
                    normals.insert(e, n);
                }
            }
        }
    }
    out.sort_unstable();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_to_triangle_regions() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        assert_eq!(point_triangle_distance(DVec3::new(0.2, 0.2, 3.0), &t), 3.0);
        assert_eq!(
            point_triangle_distance(DVec3::new(-1.0, -1.0, 0.0), &t),
            2f64.sqrt()
        );
        assert!((point_triangle_distance(DVec3::new(0.5, -2.0, 0.0), &t) - 2.0).abs() < 1e-15);
        let d = point_triangle_distance(DVec3::new(1.0, 1.0, 0.0), &t);
        assert!((d - 0.5f64.sqrt()).abs() < 1e-15);
        let flat = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert_eq!(
            point_triangle_distance(DVec3::new(1.0, 1.0, 0.0), &flat),
            1.0
        );
    }

    #[test]
    fn surface_distance_is_bounded_by_radius() {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
        let s = Surface::new(&p, &[[VertexId(0), VertexId(1), VertexId(2)]]);
        let q = DVec3::new(0.25, 0.25, 0.5);
        let mut hint = u32::MAX;
        assert_eq!(s.distance_within(q, 1.0, &[], &mut hint), Some(0.5));
        assert_eq!(hint, 0);
        assert_eq!(s.distance_within(q, 0.4, &[], &mut hint), None);
        let mut none = u32::MAX;
        assert_eq!(s.distance_within(q, 1.0, &[1], &mut none), Some(0.5));
    }
}
