//! Helpers shared by the MT tests: loading the shared meshes, building their MTs once per
//! test binary, a seeded random generator, and an independent measurement of how far two
//! boundary surfaces are from each other.
#![allow(dead_code)] // each test binary uses its own subset

use mtcut::geom::{Aabb, DVec3};
use mtcut::mesh::TetMesh;
use mtcut::mesh::tables::TET_FACES;
use mtcut::mt::{BuildOptions, BuildStats, Bvh, Mt};
use std::cell::Cell;
use std::sync::OnceLock;

pub const MESHES: [&str; 3] = ["fandisk", "pinion", "liver"];

pub fn data(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

pub fn mesh(name: &str) -> TetMesh {
    mtcut::io::read_mesh(data(&format!("{name}.node")))
        .unwrap_or_else(|e| panic!("{e}"))
        .0
}

/// A shared mesh, its MT (default options) and the build's statistics.
pub type Built = (TetMesh, Mt, BuildStats);

/// The input mesh and its MT, built once per test binary (tests running in parallel wait
/// for the first build instead of repeating it).
pub fn built(name: &str) -> &'static Built {
    static CACHE: [OnceLock<Built>; 3] = [OnceLock::new(), OnceLock::new(), OnceLock::new()];
    let k = MESHES
        .iter()
        .position(|m| *m == name)
        .unwrap_or_else(|| panic!("{name} is not a shared mesh"));
    CACHE[k].get_or_init(|| {
        let m = mesh(name);
        let (mt, stats) =
            Mt::build(&m, &BuildOptions::DEFAULT).unwrap_or_else(|e| panic!("{name}: {e}"));
        (m, mt, stats)
    })
}

/// SplitMix64: small, seeded, reproducible.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}

/// The boundary triangles of a mesh, outward.
pub fn boundary_triangles(m: &TetMesh) -> Vec<[DVec3; 3]> {
    m.adjacency()
        .boundary_faces()
        .iter()
        .map(|b| {
            let t = m.tet(b.tet);
            TET_FACES[b.face as usize].map(|k| m.position(t[k]))
        })
        .collect()
}

/// Distance from `p` to the triangle `t`, by projection onto its plane (clamped to the
/// edges when outside): written independently of the library's own distance.
fn distance_to_triangle(p: DVec3, t: &[DVec3; 3]) -> f64 {
    let [a, b, c] = *t;
    let n = (b - a).cross(c - a);
    let n2 = n.length_squared();
    if n2 > 0.0 {
        let q = p - n * ((p - a).dot(n) / n2);
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(u, v)| (v - u).cross(q - u).dot(n) >= 0.0);
        if inside {
            return (p - q).length();
        }
    }
    let seg = |u: DVec3, v: DVec3| {
        let d = v - u;
        let l = d.length_squared();
        let s = if l > 0.0 {
            ((p - u).dot(d) / l).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p - (u + d * s)).length()
    };
    seg(a, b).min(seg(b, c)).min(seg(c, a))
}

/// A triangle surface with a hierarchy for nearest-distance queries.
pub struct Surface {
    tris: Vec<[DVec3; 3]>,
    bvh: Bvh,
}

impl Surface {
    pub fn new(tris: Vec<[DVec3; 3]>) -> Surface {
        let boxes: Vec<Aabb> = tris.iter().map(|t| Aabb::from_points(t.iter())).collect();
        Surface {
            bvh: Bvh::new(&boxes),
            tris,
        }
    }

    pub fn distance(&self, p: DVec3) -> f64 {
        let best = Cell::new(f64::INFINITY);
        self.bvh.query(
            |b| (p.clamp(b.min, b.max) - p).length() <= best.get(),
            |i| {
                let d = distance_to_triangle(p, &self.tris[i as usize]);
                if d < best.get() {
                    best.set(d);
                }
            },
        );
        best.get()
    }
}

/// Points of triangle `t` on a barycentric grid with `n` subdivisions per edge.
pub fn grid_points(t: &[DVec3; 3], n: usize) -> impl Iterator<Item = DVec3> + '_ {
    (0..=n).flat_map(move |i| {
        (0..=n - i).map(move |j| {
            let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
            t[0] * (1.0 - u - v) + t[1] * u + t[2] * v
        })
    })
}

/// Hausdorff-style deviation between two boundary surfaces, each direction sampled on a
/// grid with `n` subdivisions per triangle edge: (max distance from points of `b` to `a`,
/// max distance from points of `a` to `b`).
pub fn boundary_deviation(a: &TetMesh, b: &TetMesh, n: usize) -> (f64, f64) {
    let ta = boundary_triangles(a);
    let tb = boundary_triangles(b);
    let (sa, sb) = (Surface::new(ta.clone()), Surface::new(tb.clone()));
    let b_to_a = tb
        .iter()
        .flat_map(|t| grid_points(t, n))
        .map(|p| sa.distance(p))
        .fold(0.0, f64::max);
    let a_to_b = ta
        .iter()
        .flat_map(|t| grid_points(t, n))
        .map(|p| sb.distance(p))
        .fold(0.0, f64::max);
    (b_to_a, a_to_b)
}

/// The tets of an extraction as quadruples of MT (= input) vertex ids, sorted.
pub fn tets_in_mt_ids(e: &mtcut::mt::Extraction) -> Vec<[u32; 4]> {
    let mut v: Vec<[u32; 4]> = e
        .mesh
        .tets()
        .iter()
        .map(|t| t.map(|x| e.vertex_ids[x.idx()].0))
        .collect();
    v.sort_unstable();
    v
}
