//! Helpers of the MT cut tests: the invariants checked after every cut of an MT.
#![allow(dead_code)]

use mtcut::cut::MtCutter;
use mtcut::geom::{Aabb, CutPolygon, DVec3, Sign};
use mtcut::mesh::TetMesh;
use mtcut::mesh::tables::TET_EDGES;
use mtcut::mt::{ExtractOptions, Mt, Region};
use rayon::prelude::*;

/// SplitMix64 (seeded, reproducible).
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
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}

/// Volume of the finest and of the coarsest mesh.
pub fn extreme_volumes(mt: &Mt) -> (f64, f64) {
    let v = |o: &ExtractOptions| mt.extract(o).expect("extraction").mesh.volume();
    (v(&ExtractOptions::FINEST), v(&ExtractOptions::COARSEST))
}

/// The extraction requests the acceptance asks for: `thresholds` uniform thresholds spread
/// over the fragment errors (0 and +∞ included) and `regions` random focus regions.
pub fn requests(mt: &Mt, thresholds: usize, regions: usize, rng: &mut Rng) -> Vec<ExtractOptions> {
    let mut errors: Vec<f64> = (0..mt.nb_fragments())
        .map(|f| mt.fragment_error(mtcut::mesh::FragmentId::from_usize(f)))
        .filter(|e| e.is_finite())
        .collect();
    errors.sort_by(f64::total_cmp);
    let mut out = vec![ExtractOptions::FINEST, ExtractOptions::COARSEST];
    for k in 1..thresholds.saturating_sub(1) {
        let e = errors[(errors.len() - 1) * k / (thresholds - 1)];
        out.push(ExtractOptions::threshold(e));
    }
    let b = mtcut::geom::Aabb::from_points(mt.positions());
    let coarse = errors.last().copied().unwrap_or(0.0);
    for _ in 0..regions {
        let c = b.min + (b.max - b.min) * DVec3::new(rng.unit(), rng.unit(), rng.unit());
        let r = b.diagonal() * (0.05 + 0.2 * rng.unit());
        out.push(ExtractOptions::threshold(coarse).with_focus(
            Region::Sphere {
                center: c,
                radius: r,
            },
            0.0,
        ));
    }
    out
}

/// How far (relative to its scale) from a cut's plane a crack tip it continues may lie: 1.5
/// × the MT cut's face-point margin (`mt_cut::tip_reach`).
const TIP_REACH: f64 = 1.5 * mtcut::cut::MIN_FACE_POINT_MARGIN;

/// How far (relative to its scale) past its polygon's contour a cut may leave a crack tip:
/// twice the face-point margin (`mt_cut::contour_band`). A cut continuing that crack begins
/// on that contour, so the tip may lie this far inside the new polygon.
const TIP_BAND: f64 = 2.0 * mtcut::cut::MIN_FACE_POINT_MARGIN;

/// An edge of `mesh` crossing one of `polygons` strictly inside it, away from vertices
/// within snapping distance of the plane (`near(v, polygon)`).
///
/// The last polygon is held strictly. An earlier one may be crossed near its contour
/// (within twice the larger `scale` of the edge's ends, the longest edge the input mesh had
/// at those vertices): the tables end a crack at face points placed between C's contour and
/// the section's inner end (`CutOptions::face_point_margin`, paper §4.1: the contour is
/// followed up to a tet's size), so a band of C along its contour, inside the tip tets, is
/// not cut, and a later cut subdividing a tip tet can make an edge crossing C there.
/// Farther inside C the crack is exact, and any crossing fails, but at a vertex the crack
/// may bend through: one within the tip reach of C's plane and contour (a crack tip of an
/// earlier step taken onto a cut continuing it at an angle).
pub fn crossing(
    mesh: &TetMesh,
    polygons: &[CutPolygon],
    near: impl Fn(usize, &CutPolygon) -> bool + Sync,
    scale: impl Fn(usize) -> f64 + Sync,
) -> Option<String> {
    let pos = mesh.positions();
    let last = polygons.len().saturating_sub(1);
    // Each edge once (a mesh's edges are shared by about five tets each), with the first
    // tet holding it, for the message.
    let mut edges: Vec<(usize, usize, usize)> = mesh
        .tets()
        .iter()
        .enumerate()
        .flat_map(|(t, tet)| {
            TET_EDGES.map(|[a, b]| {
                let (u, w) = (tet[a].idx(), tet[b].idx());
                (u.min(w), u.max(w), t)
            })
        })
        .collect();
    edges.par_sort_unstable();
    edges.dedup_by_key(|&mut (u, w, _)| (u, w));
    // The polygons on all cores; the first failure in polygon order is reported.
    (0..polygons.len()).into_par_iter().find_map_first(|k| {
        let polygon = &polygons[k];
        let side: Vec<Sign> = pos
            .iter()
            .map(|&p| polygon.side_filtered(p, polygon.signed_distance(p)))
            .collect();
        // An edge crossing C has a point of C, so its box meets C's box (exact: the boxes
        // hold the coordinates themselves).
        let cbox = Aabb::from_points(polygon.points());
        for &(u, w, t) in &edges {
            if side[u] == Sign::Zero
                || side[w] == Sign::Zero
                || side[u] == side[w]
                || !cbox.intersects(&Aabb::from_points([&pos[u], &pos[w]]))
                || near(u, polygon)
                || near(w, polygon)
                || !polygon.segment_crosses_inside(pos[u], pos[w])
            {
                continue;
            }
            let (du, dw) = (
                polygon.signed_distance(pos[u]),
                polygon.signed_distance(pos[w]),
            );
            let x = pos[u] + (pos[w] - pos[u]) * (du / (du - dw));
            // Distance of the crossing from C's contour (C is convex).
            let band = polygon.inside_margin(x);
            if k < last && band <= 2.0 * scale(u).max(scale(w)) {
                continue;
            }
            // A crack tip of an earlier step that this one continues at an angle is
            // taken onto the cut within the tip reach of C's plane (`mt_cut`'s
            // `TurnTips`): the crack bends through it, so an edge from it may cross the
            // plane near it (farther along an edge almost in the plane) without crossing
            // the crack. Such a tip lies near C's contour, up to the band an earlier cut
            // leaves its tips in on the inner side, or farther where that cut's face was
            // long: then it is known by lying in an earlier polygon's plane (up to
            // rounding) outside that polygon, where a cut leaves only its tips.
            let earlier_tip = |v: usize| {
                polygons[..k].iter().any(|q| {
                    q.signed_distance(pos[v]).abs() <= 1e-9 * scale(v)
                        && q.inside_margin(pos[v]) < 0.0
                })
            };
            let bent = |v: usize, d: f64| {
                let reach = TIP_REACH * scale(v);
                d.abs() <= reach
                    && polygon.projection_distance(pos[v]) <= reach
                    && (polygon.inside_margin(pos[v]) <= TIP_BAND * scale(v) || earlier_tip(v))
            };
            if bent(u, du) || bent(w, dw) {
                continue;
            }
            return Some(format!(
                "polygon {k}: edge {u}-{w} of tet {t} crosses it inside ({:?} - {:?}, \
                 distances {du:e} {dw:e}, {band:e} inside C's contour)",
                pos[u], pos[w],
            ));
        }
        None
    })
}

/// A valid mesh, or one whose only flaw is vertices of one part lying on the boundary of
/// another part: bodies a cut separated, in contact along the crack (a focus extraction
/// may show the two sides at different resolutions). Each part must then be valid alone.
pub fn valid_mesh(mesh: &TetMesh) -> Result<(), String> {
    mtcut::cut::Components::validate_bodies(mesh).map_err(|e| e.to_string())
}

/// Every invariant after a cut: MT valid; finest and coarsest volumes kept (1e-12
/// relative); every requested extraction a valid mesh crossed by none of `polygons`.
pub fn check_after_cut(
    cutter: &MtCutter,
    volumes: (f64, f64),
    polygons: &[CutPolygon],
    requests: &[ExtractOptions],
) -> Result<(), String> {
    let mt = cutter.mt();
    let report = mt.validate();
    if !report.is_valid() {
        return Err(format!("MT validate: {report}"));
    }
    let (f, c) = extreme_volumes(mt);
    for (what, now, before) in [("finest", f, volumes.0), ("coarsest", c, volumes.1)] {
        if (now - before).abs() > 1e-12 * before.abs() {
            return Err(format!(
                "{what} volume {now}, was {before} (relative {:e})",
                (now - before).abs() / before.abs()
            ));
        }
    }
    let scales = cutter.vertex_scales();
    let snap = cutter.options().snap;
    for o in requests {
        let e = mt.extract(o).map_err(|e| e.to_string())?;
        valid_mesh(&e.mesh).map_err(|m| format!("extraction {o:?}: {m}"))?;
        let near = |u: usize, p: &CutPolygon| {
            let id = e.vertex_ids[u].idx();
            p.signed_distance(e.mesh.positions()[u]).abs()
                <= snap.distance(scales[id]).max(1e-9 * scales[id]) * 1.0001
        };
        let scale = |u: usize| scales[e.vertex_ids[u].idx()];
        if let Some(m) = crossing(&e.mesh, polygons, near, scale) {
            return Err(format!("extraction {o:?}: {m}"));
        }
    }
    Ok(())
}

/// Two overlapping bands across a body whose bounding box has centre `c` and diagonal
/// `d`: the first in the plane with normal (0.3, 0.5, 0.8) through `c` moved by 0.0123 d
/// along it, from -d to 0 along a direction `u` of that plane; the second from -0.05 d to
/// 0.2 d along `u`, `offset` × d off that plane and tilted by `tilt` radians towards `u`.
/// A second cut nearly in the first one's plane (a blade re-entering an incision).
pub fn nearly_coplanar_bands(c: DVec3, d: f64, offset: f64, tilt: f64) -> [CutPolygon; 2] {
    let n = DVec3::new(0.3, 0.5, 0.8).normalize();
    let u = n.any_orthonormal_vector();
    let o = c + n * (0.0123 * d);
    let band = |o: DVec3, n2: DVec3, a0: f64, a1: f64| {
        let u2 = (u - n2 * n2.dot(u)).normalize();
        let w2 = n2.cross(u2);
        let corners = [(a0, -1.0), (a1, -1.0), (a1, 1.0), (a0, 1.0)];
        CutPolygon::new(&corners.map(|(a, s)| o + u2 * a + w2 * (s * d))).expect("band")
    };
    let tilted = (n + u * tilt).normalize();
    [
        band(o, n, -d, 0.0),
        band(o + n * (offset * d), tilted, -0.05 * d, 0.2 * d),
    ]
}

/// `polygon` with its corners projected onto the plane of `onto`: the polygon a cut moved
/// onto an earlier crack's plane was made by.
pub fn projected_onto(polygon: &CutPolygon, onto: &CutPolygon) -> CutPolygon {
    let plane = onto.plane();
    let corners: Vec<DVec3> = polygon
        .points()
        .iter()
        .map(|&p| p - plane.normal * plane.normal.dot(p - plane.points[0]))
        .collect();
    CutPolygon::new(&corners).expect("projected polygon")
}

/// The first vertex from `first` on (the vertices cuts made) that some extraction of `mt`
/// leaves pinched: its tets there in separate boundary fans. Every extraction's star at a
/// vertex is read from a down-closed set of the fragments creating or destroying its tets,
/// in the order of the DAG after the cuts (the MT cut's own check reads the order of the
/// DAG before each cut, through the fragment each part was split off): all such sets are
/// tried, up to `max_sets` per vertex.
pub fn pinched_extraction(mt: &Mt, first: usize, max_sets: usize) -> Option<String> {
    use mtcut::mesh::{FragmentId, TetId};
    use mtcut::mt::FragmentKind;
    let nv = mt.nb_vertices();
    let mut around: Vec<(u32, u32)> = Vec::new();
    for t in 0..mt.nb_tets() {
        let id = TetId::from_usize(t);
        if mt.is_ghost(id) {
            continue;
        }
        for v in mt.tet(id) {
            if v.idx() >= first && v.idx() < nv {
                around.push((v.0, t as u32));
            }
        }
    }
    around.sort_unstable();
    for run in around.chunk_by(|a, b| a.0 == b.0) {
        let v = run[0].0;
        let tets: Vec<TetId> = run.iter().map(|r| TetId(r.1)).collect();
        let mut frags: Vec<FragmentId> = tets
            .iter()
            .flat_map(|&t| [mt.tet_creator(t), mt.tet_destroyer(t)])
            .collect();
        frags.sort_unstable();
        frags.dedup();
        let at = |f: FragmentId| frags.binary_search(&f).expect("a fragment around");
        let top = frags
            .iter()
            .map(|&f| mt.fragment_level(f))
            .max()
            .unwrap_or(0);
        // needs[i]: the fragments around the vertex that fragment i depends on in the DAG.
        let mut needs: Vec<Vec<usize>> = vec![Vec::new(); frags.len()];
        for (i, &g) in frags.iter().enumerate() {
            let mut seen = std::collections::HashSet::new();
            let mut stack = vec![g];
            while let Some(x) = stack.pop() {
                for a in mt.out_arcs(x).iter() {
                    let d = mt.arc_destroyer(a as usize);
                    if mt.fragment_level(d) <= top && seen.insert(d) {
                        stack.push(d);
                        if let Ok(j) = frags.binary_search(&d) {
                            needs[j].push(i);
                        }
                    }
                }
            }
        }
        let mut order: Vec<usize> = (0..frags.len()).collect();
        order.sort_by_key(|&i| mt.fragment_level(frags[i]));
        let kinds: Vec<FragmentKind> = frags.iter().map(|&f| mt.fragment_kind(f)).collect();
        let star_tets: Vec<(usize, usize, [u32; 4])> = tets
            .iter()
            .map(|&t| {
                (
                    at(mt.tet_creator(t)),
                    at(mt.tet_destroyer(t)),
                    mt.tet(t).map(|x| x.0),
                )
            })
            .collect();
        let mut applied = vec![false; frags.len()];
        let mut budget = max_sets;
        if let Some(m) = closed_sets(0, &order, &needs, &kinds, &mut applied, &mut budget, &|a| {
            let star: Vec<[u32; 4]> = star_tets
                .iter()
                .filter(|s| a[s.0] && !a[s.1])
                .map(|s| s.2)
                .collect();
            let fans = boundary_fans(v, &star);
            (fans > 1).then(|| {
                format!(
                    "vertex {v}: {fans} boundary fans in the extraction applying {a:?} of {frags:?}"
                )
            })
        }) {
            return Some(m);
        }
    }
    None
}

/// Depth-first over the down-closed sets (see [`pinched_extraction`]): the first message
/// `check` gives.
fn closed_sets(
    k: usize,
    order: &[usize],
    needs: &[Vec<usize>],
    kinds: &[mtcut::mt::FragmentKind],
    applied: &mut [bool],
    budget: &mut usize,
    check: &dyn Fn(&[bool]) -> Option<String>,
) -> Option<String> {
    use mtcut::mt::FragmentKind;
    if *budget == 0 {
        return None;
    }
    let Some(&i) = order.get(k) else {
        *budget -= 1;
        return check(applied);
    };
    if kinds[i] != FragmentKind::Root {
        if let Some(m) = closed_sets(k + 1, order, needs, kinds, applied, budget, check) {
            return Some(m);
        }
    }
    if kinds[i] != FragmentKind::Drain && needs[i].iter().all(|&x| applied[x]) {
        applied[i] = true;
        let m = closed_sets(k + 1, order, needs, kinds, applied, budget, check);
        applied[i] = false;
        return m;
    }
    None
}

/// How many separate chains the boundary edges of `v`'s link form in `star` (its tets).
fn boundary_fans(v: u32, star: &[[u32; 4]]) -> usize {
    const FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];
    let mut edges: Vec<(u32, u32)> = Vec::new();
    for t in star {
        for f in FACES {
            let [a, b, c] = f.map(|j| t[j]);
            let e = match v {
                _ if a == v => (b, c),
                _ if b == v => (c, a),
                _ if c == v => (a, b),
                _ => continue,
            };
            edges.push(e);
        }
    }
    edges.sort_unstable();
    let boundary: Vec<(u32, u32)> = edges
        .iter()
        .filter(|&&(a, b)| edges.binary_search(&(b, a)).is_err())
        .copied()
        .collect();
    let mut ends: Vec<u32> = boundary.iter().flat_map(|&(a, b)| [a, b]).collect();
    ends.sort_unstable();
    ends.dedup();
    let mut parent: Vec<usize> = (0..ends.len()).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for &(a, b) in &boundary {
        let (x, y) = (
            ends.binary_search(&a).unwrap(),
            ends.binary_search(&b).unwrap(),
        );
        let (rx, ry) = (root(&mut parent, x), root(&mut parent, y));
        parent[rx] = ry;
    }
    (0..ends.len())
        .filter(|&i| root(&mut parent, i) == i)
        .count()
}
