//! Shared helpers of the cut tests: meshes, seeded random polygons of every kind the
//! acceptance asks for, the invariant checks made after every cut, quality measures, and
//! the shrinker that reduces a failing case before reporting it.

#![allow(dead_code)]

use mtcut::cut::{Components, CutOptions, CutResult, Cutter, VertexOrigin, vertex_scales};
use mtcut::geom::{CutPolygon, DVec3, Sign, orient3d};
use mtcut::mesh::tables::{TET_EDGES, TET_FACES};
use mtcut::mesh::{TetId, TetMesh, VertexId};
use std::sync::OnceLock;

pub const MESHES: [&str; 3] = ["fandisk", "pinion", "liver"];

/// A shared mesh of tests/data, read once per test binary.
pub fn mesh(name: &str) -> &'static TetMesh {
    static CACHE: [OnceLock<TetMesh>; 3] = [OnceLock::new(), OnceLock::new(), OnceLock::new()];
    let i = MESHES
        .iter()
        .position(|&m| m == name)
        .expect("a shared mesh");
    CACHE[i].get_or_init(|| {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data")
            .join(format!("{name}.node"));
        mtcut::io::read_mesh(path).expect("shared mesh").0
    })
}

/// SplitMix64: small, seeded, reproducible.
#[derive(Clone)]
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    pub fn unit(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
    pub fn direction(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }
}

/// The kinds of cutting polygons the acceptance asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A polygon larger than the body: the cut goes straight through.
    Through,
    /// A polygon whose contour lies inside the body: the crack ends inside.
    Partial,
    /// A polygon about the size of one tet.
    Tiny,
    /// A triangle whose corners are mesh vertices: the plane passes exactly through them.
    Vertices,
    /// A triangle with a mesh edge as a side: the plane contains the edge exactly.
    AlongEdge,
    /// A triangle lying exactly in the plane of a mesh face (a face itself, or the largest
    /// triangle of boundary vertices coplanar with a boundary face).
    AlongFace,
}

impl Kind {
    pub const ALL: [Kind; 6] = [
        Kind::Through,
        Kind::Partial,
        Kind::Tiny,
        Kind::Vertices,
        Kind::AlongEdge,
        Kind::AlongFace,
    ];

    /// A kind drawn with the weights of the random suites.
    pub fn draw(rng: &mut Rng) -> Kind {
        match rng.below(100) {
            0..=29 => Kind::Through,
            30..=54 => Kind::Partial,
            55..=74 => Kind::Tiny,
            75..=84 => Kind::Vertices,
            85..=92 => Kind::AlongEdge,
            _ => Kind::AlongFace,
        }
    }
}

/// A polygon with `n` corners on the circle of centre `c`, radius `r`, in the plane of
/// normal `n`, at angles jittered by up to `jitter` of a step (0: regular, whose inscribed
/// circle has radius `r cos(π/n)`).
pub fn disk(rng: &mut Rng, c: DVec3, normal: DVec3, r: f64, n: usize, jitter: f64) -> Vec<DVec3> {
    let u = normal.any_orthonormal_vector();
    let w = normal.cross(u);
    let phase = rng.range(0.0, std::f64::consts::TAU);
    let step = std::f64::consts::TAU / n as f64;
    (0..n)
        .map(|k| {
            let a = phase + step * (k as f64 + rng.range(-jitter, jitter));
            c + (u * a.cos() + w * a.sin()) * r
        })
        .collect()
}

fn centroid(mesh: &TetMesh, t: usize) -> DVec3 {
    mesh.tet_positions(TetId::from_usize(t))
        .iter()
        .sum::<DVec3>()
        / 4.0
}

fn longest_edge(mesh: &TetMesh, t: usize) -> f64 {
    let p = mesh.tet_positions(TetId::from_usize(t));
    TET_EDGES
        .iter()
        .map(|&[a, b]| p[a].distance(p[b]))
        .fold(0.0, f64::max)
}

/// A random cutting polygon of `kind` for `mesh`.
pub fn random_polygon(mesh: &TetMesh, kind: Kind, rng: &mut Rng) -> CutPolygon {
    let diag = mesh.bbox().diagonal();
    let pos = mesh.positions();
    for _ in 0..1000 {
        let t = rng.below(mesh.nb_tets());
        let points: Vec<DVec3> = match kind {
            Kind::Through => {
                let n = rng.direction();
                // Regular, inscribed circle at least 1.5 diagonals: covers the body.
                let k = rng.range(3.0, 7.0) as usize;
                disk(rng, centroid(mesh, t), n, 3.0 * diag, k, 0.0)
            }
            Kind::Partial => {
                let n = rng.direction();
                let r = rng.range(0.05, 0.35) * diag;
                let k = rng.range(3.0, 8.0) as usize;
                disk(rng, centroid(mesh, t), n, r, k, 0.3)
            }
            Kind::Tiny => {
                let n = rng.direction();
                let r = rng.range(0.2, 2.0) * longest_edge(mesh, t);
                let k = rng.range(3.0, 6.0) as usize;
                disk(rng, centroid(mesh, t), n, r, k, 0.3)
            }
            Kind::Vertices => {
                let v = [0, 1, 2].map(|_| pos[rng.below(pos.len())]);
                v.to_vec()
            }
            Kind::AlongEdge => {
                let tet = mesh.tet(TetId::from_usize(t));
                let [a, b] = TET_EDGES[rng.below(6)];
                vec![
                    pos[tet[a].idx()],
                    pos[tet[b].idx()],
                    pos[rng.below(pos.len())],
                ]
            }
            Kind::AlongFace => along_face(mesh, t, rng),
        };
        if let Ok(p) = CutPolygon::new(&points) {
            return p;
        }
    }
    panic!("no valid {kind:?} polygon found");
}

/// A triangle in the plane of a face of tet `t`: the face itself, or (for a boundary face)
/// the largest triangle of boundary vertices exactly coplanar with it.
fn along_face(mesh: &TetMesh, t: usize, rng: &mut Rng) -> Vec<DVec3> {
    let tet = mesh.tet(TetId::from_usize(t));
    let f = TET_FACES[rng.below(4)].map(|k| mesh.position(tet[k]));
    if rng.below(2) == 0 {
        return f.to_vec();
    }
    let coplanar: Vec<DVec3> = boundary_vertices(mesh)
        .iter()
        .map(|v| mesh.position(*v))
        .filter(|&p| orient3d(f[0], f[1], f[2], p) == Sign::Zero)
        .collect();
    if coplanar.len() < 3 {
        return f.to_vec();
    }
    // The farthest pair, then the point farthest from their line.
    let (mut a, mut b, mut best) = (coplanar[0], coplanar[1], 0.0);
    for &p in &coplanar {
        for &q in &coplanar {
            let d = p.distance(q);
            if d > best {
                (a, b, best) = (p, q, d);
            }
        }
    }
    let c = coplanar
        .iter()
        .copied()
        .max_by(|p, q| {
            let dp = (b - a).cross(*p - a).length();
            let dq = (b - a).cross(*q - a).length();
            dp.total_cmp(&dq)
        })
        .unwrap_or(f[2]);
    vec![a, b, c]
}

fn boundary_vertices(mesh: &TetMesh) -> &'static [VertexId] {
    static CACHE: [OnceLock<Vec<VertexId>>; 4] = [
        OnceLock::new(),
        OnceLock::new(),
        OnceLock::new(),
        OnceLock::new(),
    ];
    let slot = MESHES
        .iter()
        .position(|&m| std::ptr::eq(self::mesh(m), mesh))
        .unwrap_or(3);
    let compute = || {
        let adj = mesh.adjacency();
        let mut v: Vec<VertexId> = adj
            .boundary_faces()
            .iter()
            .flat_map(|b| {
                let tet = mesh.tet(b.tet);
                TET_FACES[b.face as usize].map(|k| tet[k])
            })
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    if slot == 3 {
        // Not a cached mesh: leak one computation (tests only).
        return Box::leak(compute().into_boxed_slice());
    }
    CACHE[slot].get_or_init(compute)
}

/// What one cut must satisfy; `Err` says which invariant broke.
pub struct Checked {
    /// Smallest dihedral angle (degrees) and smallest child/parent volume ratio of the
    /// tets the cut created.
    pub min_dihedral: f64,
    pub min_volume_ratio: f64,
    pub created: usize,
}

/// Dihedral angles of a tet, in degrees.
pub fn min_dihedral_deg(p: [DVec3; 4]) -> f64 {
    let n: Vec<DVec3> = TET_FACES
        .iter()
        .map(|f| (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]).normalize())
        .collect();
    let mut m = f64::INFINITY;
    for i in 0..4 {
        for j in i + 1..4 {
            m = m.min((-n[i].dot(n[j])).clamp(-1.0, 1.0).acos());
        }
    }
    m.to_degrees()
}

/// The scale of every vertex of `after`, as the engine defines it: the longest incident
/// edge in `before` for old vertices, the largest of their origins' for new ones.
pub fn scales_after(before: &TetMesh, before_scales: &[f64], result: &CutResult) -> Vec<f64> {
    let mut s = before_scales.to_vec();
    s.truncate(before.nb_vertices());
    for o in &result.origins {
        let h = match *o {
            VertexOrigin::Edge { a, b, .. } => s[a.idx()].max(s[b.idx()]),
            VertexOrigin::Face { v, .. } => v.iter().map(|x| s[x.idx()]).fold(0.0, f64::max),
            VertexOrigin::Copy { of } => s[of.idx()],
        };
        s.push(h);
    }
    s
}

/// The invariants after a cut of `before` (scales `scales`) into `after` by `polygon`:
/// valid mesh; same volume (1e-12 relative); no edge crossing C strictly inside C, except
/// at a vertex within snapping distance of the plane; when `through`, parts sharing no
/// vertex.
pub fn check_cut(
    before: &TetMesh,
    scales: &[f64],
    after: &TetMesh,
    polygon: &CutPolygon,
    result: &CutResult,
    options: &CutOptions,
    through: bool,
) -> Result<Checked, String> {
    let report = after.validate();
    if !report.is_valid() {
        return Err(format!("validate: {report}"));
    }
    let (v0, v1) = (before.volume(), after.volume());
    if (v1 - v0).abs() > 1e-12 * v0.abs() {
        return Err(format!(
            "volume {v1} after, {v0} before (relative {:e})",
            (v1 - v0).abs() / v0.abs()
        ));
    }
    let h = scales_after(before, scales, result);
    let pos = after.positions();
    let near = |v: VertexId| {
        polygon.signed_distance(pos[v.idx()]).abs() <= options.snap.distance(h[v.idx()]) * 1.0001
    };
    for (t, tet) in after.tets().iter().enumerate() {
        let sides = tet.map(|v| polygon.side(pos[v.idx()]));
        if !(sides.contains(&Sign::Positive) && sides.contains(&Sign::Negative)) {
            continue;
        }
        for [a, b] in TET_EDGES {
            let (u, w) = (tet[a], tet[b]);
            if sides[a] != Sign::Zero
                && sides[b] != Sign::Zero
                && sides[a] != sides[b]
                && polygon.segment_crosses_inside(pos[u.idx()], pos[w.idx()])
                && !near(u)
                && !near(w)
            {
                return Err(format!(
                    "edge {u}-{w} of tet {t} crosses C strictly inside it ({:?} - {:?})",
                    pos[u.idx()],
                    pos[w.idx()]
                ));
            }
        }
    }
    if through {
        let comps = Components::of(after);
        if comps.count < 2 {
            return Err("a cut straight through left one part".into());
        }
        if Components::through_vertices(after) != comps {
            return Err("the components through vertices differ from those through faces".into());
        }
        if result.stats.components.is_some_and(|n| n != comps.count) {
            return Err(format!(
                "the cut counted {:?} components",
                result.stats.components
            ));
        }
        let mut owner = vec![u32::MAX; after.nb_vertices()];
        for (t, tet) in after.tets().iter().enumerate() {
            for v in tet {
                let c = comps.label[t];
                if owner[v.idx()] == u32::MAX {
                    owner[v.idx()] = c;
                } else if owner[v.idx()] != c {
                    return Err(format!(
                        "vertex {v} is shared by parts {} and {c}",
                        owner[v.idx()]
                    ));
                }
            }
        }
    }
    let mut min_dihedral = f64::INFINITY;
    let mut min_volume_ratio = f64::INFINITY;
    let mut created = 0;
    for s in &result.splits {
        let parent = before.tet_volume(s.parent);
        for c in s.child_slots() {
            created += 1;
            min_dihedral = min_dihedral.min(min_dihedral_deg(after.tet_positions(c)));
            min_volume_ratio = min_volume_ratio.min(after.tet_volume(c) / parent);
        }
    }
    Ok(Checked {
        min_dihedral,
        min_volume_ratio,
        created,
    })
}

/// Reduces a failing case (`fails(mesh, polygon)` true) to a small one and reports it:
/// the mesh is cut down to the tets near the polygon (as long as the part is itself a valid
/// mesh and still fails), then, if `shrink_polygon` (not for cuts that must go straight
/// through), the polygon is shrunk towards its centroid. The small case
/// is written to `target/cut-failures/` as TetGen files; the message names the seed, the
/// polygon's corners and that file.
pub fn shrink_and_report(
    seed: u64,
    what: &str,
    mesh: &TetMesh,
    polygon: &CutPolygon,
    shrink_polygon: bool,
    fails: impl Fn(&TetMesh, &CutPolygon) -> bool,
) -> String {
    let mut m = mesh.clone();
    let mut p = polygon.clone();
    // Keep tets within a box around the polygon's plane region; halve it while it fails.
    let pb = polygon.bbox();
    let mut radius = m.bbox().diagonal();
    for _ in 0..30 {
        radius *= 0.6;
        let centre = pb.center().clamp(m.bbox().min, m.bbox().max);
        let keep: Vec<usize> = (0..m.nb_tets())
            .filter(|&t| {
                m.tet_positions(TetId::from_usize(t))
                    .iter()
                    .any(|q| (*q - centre).abs().max_element() <= radius)
            })
            .collect();
        if keep.is_empty() || keep.len() == m.nb_tets() {
            continue;
        }
        let tets: Vec<[u32; 4]> = keep.iter().map(|&t| m.tets()[t].map(|v| v.0)).collect();
        let Ok((sub, _)) = TetMesh::from_arrays(m.positions().to_vec(), tets) else {
            continue;
        };
        if fails(&sub, &p) {
            m = sub;
        }
    }
    for _ in 0..if shrink_polygon { 20 } else { 0 } {
        let c = p.points().iter().sum::<DVec3>() / p.points().len() as f64;
        let smaller: Vec<DVec3> = p.points().iter().map(|q| c + (*q - c) * 0.7).collect();
        match CutPolygon::new(&smaller) {
            Ok(s) if fails(&m, &s) => p = s,
            _ => break,
        }
    }
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/cut-failures");
    let file = dir.join(format!("seed-{seed}.node"));
    let written = std::fs::create_dir_all(&dir)
        .ok()
        .and_then(|_| mtcut::io::write_mesh(&file, &m).ok())
        .map_or("(could not write it)".to_string(), |_| {
            file.display().to_string()
        });
    format!(
        "{what}\n  seed {seed}; smallest failing case: {} tets (written to {written}), polygon {:?}",
        m.nb_tets(),
        p.points()
    )
}

/// A cutter ready for `mesh`, kept per mesh so each random cut starts from a clone.
pub fn prepared(mesh: &TetMesh, options: CutOptions) -> (Cutter, Vec<f64>) {
    let cutter = Cutter::new(mesh.clone(), options).expect("options are valid");
    let scales = vertex_scales(mesh);
    (cutter, scales)
}

/// A structured grid of `n × n × n` unit cubes with integer coordinates, each cube split
/// into six tets around its main diagonal (Kuhn/Freudenthal: conforming across cubes).
pub fn grid_mesh(n: usize) -> TetMesh {
    let id = |i: usize, j: usize, k: usize| (i + (n + 1) * (j + (n + 1) * k)) as u32;
    let mut positions = Vec::new();
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                positions.push(DVec3::new(i as f64, j as f64, k as f64));
            }
        }
    }
    let mut tets = Vec::new();
    let axes = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
    let perms = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                for p in perms {
                    let mut c = [i, j, k];
                    let mut tet = [id(c[0], c[1], c[2]); 4];
                    for (s, &a) in p.iter().enumerate() {
                        for d in 0..3 {
                            c[d] += axes[a][d];
                        }
                        tet[s + 1] = id(c[0], c[1], c[2]);
                    }
                    tets.push(tet);
                }
            }
        }
    }
    TetMesh::from_arrays(positions, tets)
        .expect("a valid grid")
        .0
}

/// The same grid as [`grid_mesh`], its tets listed as the C examples list them: per cube
/// (x fastest, then y, then z; a vertex's id is `i + (n + 1) (j + (n + 1) k)`), the six
/// tets of the Kuhn table around the diagonal from corner 0 to corner 7 (corner `c` at
/// `(c & 1, c >> 1 & 1, c >> 2 & 1)`). An MT built from it differs from one built from
/// [`grid_mesh`] (the order of the tets steers the simplification), so cases found through
/// the C ABI are replayed on it.
pub fn kuhn_grid(n: usize) -> TetMesh {
    const KUHN: [[usize; 4]; 6] = [
        [0, 1, 3, 7],
        [0, 1, 5, 7],
        [0, 2, 3, 7],
        [0, 2, 6, 7],
        [0, 4, 5, 7],
        [0, 4, 6, 7],
    ];
    let id = |i: usize, j: usize, k: usize| (i + (n + 1) * (j + (n + 1) * k)) as u32;
    let mut positions = Vec::new();
    let mut tets = Vec::new();
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                positions.push(DVec3::new(i as f64, j as f64, k as f64));
                if i < n && j < n && k < n {
                    for t in KUHN {
                        tets.push(t.map(|c| id(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1))));
                    }
                }
            }
        }
    }
    TetMesh::from_arrays(positions, tets)
        .expect("a valid grid")
        .0
}

/// A seeded partial cut of a Kuhn grid of `n` cells per side (see [`kuhn_grid`]) for the
/// degenerate stress runs: a rectangle through a grid vertex (or, one time in three or so,
/// the point half a cell beyond it along the diagonal), its normal along an axis or a
/// diagonal, reaching 0–8 cells from that point each way; `None` for a degenerate
/// rectangle (the random draws still advance).
pub fn grid_partial_polygon(rng: &mut Rng, n: usize) -> Option<CutPolygon> {
    let normals = [
        DVec3::X,
        DVec3::Y,
        DVec3::Z,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 1.0),
        DVec3::new(1.0, 0.0, 1.0),
        DVec3::new(1.0, -1.0, 0.0),
        DVec3::new(1.0, 1.0, 1.0),
    ]
    .map(DVec3::normalize);
    let normal = normals[rng.below(normals.len())];
    let mut at = || rng.below(n + 1) as f64;
    let mut p0 = DVec3::new(at(), at(), at());
    if rng.unit() < 0.3 {
        p0 += DVec3::splat(0.5);
    }
    let u = normal.any_orthonormal_vector();
    let w = normal.cross(u);
    let (a0, a1) = (-rng.range(0.0, 8.0), rng.range(0.0, 8.0));
    let (b0, b1) = (-rng.range(0.0, 8.0), rng.range(0.0, 8.0));
    let corners = [(a0, b0), (a1, b0), (a1, b1), (a0, b1)].map(|(a, b)| p0 + u * a + w * b);
    CutPolygon::new(&corners).ok()
}

/// A square of half-size `r` centred at `c`, in the plane of unit normal `normal`.
pub fn square(c: DVec3, normal: DVec3, r: f64) -> CutPolygon {
    let u = normal.any_orthonormal_vector();
    let w = normal.cross(u);
    CutPolygon::new(&[
        c + (u + w) * r,
        c + (w - u) * r,
        c - (u + w) * r,
        c + (u - w) * r,
    ])
    .expect("a square")
}
