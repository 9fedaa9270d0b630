//! The split tables: embedded = generated, and every entry checked independently of the
//! generator — it tiles its tet for random positions of the new points, subdivides each
//! face exactly as the neighbour across it does (the shared-face rule, quadrilaterals cut
//! at their lowest vertex), and labels its children with the side they lie on.

use mtcut::cut::table_gen::{generate, render};
use mtcut::cut::tables::{
    CutCase, NB_CONFIGS, NEG, ON, OUT, POS, SIDE_NEGATIVE, SIDE_POSITIVE, config_of_index, entry,
    face_points, is_crossed, is_valid_config,
};
use mtcut::mesh::tables::{EDGE_OF_VERTICES, TET_EDGES, TET_FACES};
use std::collections::{BTreeMap, BTreeSet};

#[test]
fn embedded_tables_are_the_generated_ones() {
    let fresh = render(&generate());
    let embedded = include_str!("../src/cut/tables_generated.rs");
    assert!(
        fresh == embedded,
        "src/cut/tables_generated.rs is stale: run \
         `cargo run --example gen_cut_tables > src/cut/tables_generated.rs`"
    );
}

/// SplitMix64.
struct Rng(u64);
impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        (((z ^ (z >> 31)) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
}

/// Barycentric coordinates of the 20 local points for one random placement: cut points
/// anywhere inside their edges (crossings of uncut edges too), face points anywhere on their
/// face's section segment — from its end in C (a snapped vertex or a cut edge's point) to
/// its end out of C (an uncut edge's crossing), which is where the cut puts them.
fn random_points(rng: &mut Rng, states: [u8; 4], mask: u8, extreme: bool) -> [[f64; 4]; 20] {
    let mut b = [[0.0; 4]; 20];
    for (i, row) in b.iter_mut().take(4).enumerate() {
        row[i] = 1.0;
    }
    let param = |rng: &mut Rng| {
        let u = rng.unit();
        if extreme {
            if u < 0.5 {
                1e-3 * u
            } else {
                1.0 - 1e-3 * (1.0 - u)
            }
        } else {
            u
        }
    };
    let mut crossing = [[0.0; 4]; 6];
    for (e, &[a, c]) in TET_EDGES.iter().enumerate() {
        let t = param(rng);
        crossing[e][a] = 1.0 - t;
        crossing[e][c] = t;
        b[4 + 2 * e] = crossing[e];
        b[5 + 2 * e] = crossing[e];
    }
    let fp = face_points(states, mask);
    for (f, face) in TET_FACES.iter().enumerate() {
        if !fp[f] {
            continue;
        }
        let (mut inside, mut outside) = (None, None);
        for k in 0..3 {
            let (a, c) = (face[k], face[(k + 1) % 3]);
            let mut v = [0.0; 4];
            v[a] = 1.0;
            match states[a] {
                ON => inside = Some(v),
                OUT => outside = Some(v),
                _ => {}
            }
            let e = EDGE_OF_VERTICES[a][c];
            if is_crossed(states[a], states[c]) {
                if mask & (1 << e) != 0 {
                    inside = Some(crossing[e]);
                } else {
                    outside = Some(crossing[e]);
                }
            }
        }
        let (i, o) = (
            inside.expect("an inside end"),
            outside.expect("an outside end"),
        );
        let s = param(rng);
        b[16 + f] = std::array::from_fn(|k| (1.0 - s) * i[k] + s * o[k]);
    }
    b
}

fn det(m: [[f64; 4]; 4]) -> f64 {
    let mut a = m;
    let mut d = 1.0;
    for c in 0..4 {
        let p = (c..4)
            .max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))
            .unwrap_or(c);
        if a[p][c] == 0.0 {
            return 0.0;
        }
        if p != c {
            a.swap(p, c);
            d = -d;
        }
        d *= a[c][c];
        let pivot = a[c];
        for row in a.iter_mut().skip(c + 1) {
            let k = row[c] / pivot[c];
            for (x, y) in row.iter_mut().zip(pivot).skip(c) {
                *x -= k * y;
            }
        }
    }
    d
}

fn split_configs() -> Vec<usize> {
    (0..NB_CONFIGS)
        .filter(|&c| !entry(c).0.is_empty())
        .collect()
}

#[test]
fn exactly_the_cut_configurations_have_entries() {
    for c in 0..NB_CONFIGS {
        let (states, mask) = config_of_index(c);
        let split = is_valid_config(states, mask) && CutCase::of_config(states, mask).is_some();
        assert_eq!(
            !entry(c).0.is_empty(),
            split,
            "configuration {states:?}/{mask:06b}"
        );
    }
}

#[test]
fn every_entry_tiles_its_tet_for_any_positions_of_the_new_points() {
    let mut rng = Rng(0x7AB1E5);
    for c in split_configs() {
        let (children, _) = entry(c);
        let (states, mask) = config_of_index(c);
        for sample in 0..400 {
            let b = random_points(&mut rng, states, mask, sample % 2 == 1);
            let mut total = 0.0;
            for ch in children {
                let v = det(ch.map(|p| b[p as usize]));
                assert!(
                    v > 0.0,
                    "configuration {:?}: child {ch:?} has volume fraction {v:e} (sample {sample})",
                    config_of_index(c)
                );
                total += v;
            }
            assert!(
                (total - 1.0).abs() < 1e-12,
                "configuration {:?}: children add up to {total}",
                config_of_index(c)
            );
        }
    }
}

/// A point of a face in face-local terms: vertex by rank within the face, cut-point copy by
/// the ranks of its edge and its side, or the face point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum FaceLabel {
    Vertex(usize),
    Copy(usize, usize, bool),
    Point,
}

#[test]
fn neighbours_subdivide_shared_faces_alike() {
    // Two tets sharing a face see the same states, cut flags and vertex order on it; the
    // triangles they put on it must then be the same, whatever their other vertices.
    type Signature = (Vec<u8>, Vec<bool>);
    let mut seen: BTreeMap<Signature, BTreeSet<[FaceLabel; 3]>> = BTreeMap::new();
    for c in split_configs() {
        let (states, mask) = config_of_index(c);
        let (children, _) = entry(c);
        for (f, face) in TET_FACES.iter().enumerate() {
            let mut verts = *face;
            verts.sort_unstable(); // local index order is global id order
            let rank = |i: usize| verts.iter().position(|&x| x == i);
            let label = |p: u8| -> Option<FaceLabel> {
                match p {
                    0..=3 => rank(p as usize).map(FaceLabel::Vertex),
                    4..=15 => {
                        let e = (p as usize - 4) / 2;
                        let [a, b] = TET_EDGES[e];
                        let (ra, rb) = (rank(a)?, rank(b)?);
                        Some(FaceLabel::Copy(ra.min(rb), ra.max(rb), (p - 4) % 2 == 0))
                    }
                    _ => (p as usize - 16 == f).then_some(FaceLabel::Point),
                }
            };
            let mut tris = BTreeSet::new();
            for ch in children {
                for g in TET_FACES {
                    let pts = g.map(|k| ch[k]);
                    if let (Some(a), Some(b), Some(d)) =
                        (label(pts[0]), label(pts[1]), label(pts[2]))
                    {
                        let mut t = [a, b, d];
                        t.sort_unstable();
                        tris.insert(t);
                    }
                }
            }
            let sig_states: Vec<u8> = verts.iter().map(|&i| states[i]).collect();
            let sig_cuts: Vec<bool> = [(0, 1), (0, 2), (1, 2)]
                .iter()
                .map(|&(x, y)| mask & (1 << EDGE_OF_VERTICES[verts[x]][verts[y]]) != 0)
                .collect();
            // The quadrilateral of a face with two cut edges takes its diagonal at its lowest
            // vertex (Fig. 8b): that vertex is in three of the face's triangles.
            if sig_cuts.iter().filter(|&&x| x).count() == 2 {
                let lone = (0..3)
                    .find(|&r| {
                        [(0, 1), (0, 2), (1, 2)]
                            .iter()
                            .zip(&sig_cuts)
                            .filter(|&(&(x, y), &cut)| cut && (x == r || y == r))
                            .count()
                            == 2
                    })
                    .expect("a lone vertex");
                let lowest = (0..3).find(|&r| r != lone).expect("quad vertices");
                let uses = tris
                    .iter()
                    .filter(|t| t.contains(&FaceLabel::Vertex(lowest)))
                    .count();
                assert_eq!(
                    uses, 2,
                    "configuration {states:?}/{mask:06b}, face {f}: quadrilateral diagonal not at its lowest vertex: {tris:?}"
                );
            }
            match seen.get(&(sig_states.clone(), sig_cuts.clone())) {
                Some(prev) => assert_eq!(
                    prev, &tris,
                    "face {sig_states:?}/{sig_cuts:?} subdivided two ways"
                ),
                None => {
                    seen.insert((sig_states, sig_cuts), tris);
                }
            }
        }
    }
}

#[test]
fn children_carry_the_side_they_lie_on() {
    for c in split_configs() {
        let (states, _) = config_of_index(c);
        let (children, sides) = entry(c);
        for (ch, &s) in children.iter().zip(sides) {
            let pos = ch.iter().any(|&p| {
                (p < 4 && states[p as usize] == POS) || ((4..16).contains(&p) && (p - 4) % 2 == 0)
            });
            let neg = ch.iter().any(|&p| {
                (p < 4 && states[p as usize] == NEG) || ((4..16).contains(&p) && (p - 4) % 2 == 1)
            });
            // Copies of a cut point are used only on their own side.
            let plus_copy = ch.iter().any(|&p| (4..16).contains(&p) && (p - 4) % 2 == 0);
            let minus_copy = ch.iter().any(|&p| (4..16).contains(&p) && (p - 4) % 2 == 1);
            assert!(
                !(plus_copy && neg || minus_copy && pos),
                "{ch:?} in {states:?}"
            );
            match s {
                SIDE_POSITIVE => assert!(pos && !neg),
                SIDE_NEGATIVE => assert!(neg && !pos),
                _ => assert!(pos && neg),
            }
            // Cut points, face points and snapped vertices are coplanar in fact: a child
            // needs a vertex off the cut to have volume.
            assert!(
                ch.iter().any(|&p| p < 4 && states[p as usize] != ON),
                "{ch:?} lies in the cut plane in {states:?}"
            );
            // A child touching a vertex on the cut never straddles: the unglue step relies
            // on it.
            if ch.iter().any(|&p| p < 4 && states[p as usize] == ON) {
                assert!(
                    !(pos && neg),
                    "{ch:?} straddles at a snapped vertex in {states:?}"
                );
            }
        }
    }
}

#[test]
fn face_points_follow_the_section() {
    // A face holds a face point exactly when C's contour must cross it: its section segment
    // has one end in C and one out (Fig. 4c–e), and is not an edge of the face (an `ON`
    // vertex and an `OUT` one: the contour crosses the edge, which holds no point).
    for c in split_configs() {
        let (states, mask) = config_of_index(c);
        let fp = face_points(states, mask);
        for (f, face) in TET_FACES.iter().enumerate() {
            let mut ends_in = 0;
            let mut ends = 0;
            let mut vertex_ends = 0;
            for k in 0..3 {
                let (a, b) = (face[k], face[(k + 1) % 3]);
                if states[a] == ON || states[a] == OUT {
                    ends += 1;
                    vertex_ends += 1;
                    ends_in += usize::from(states[a] == ON);
                }
                if is_crossed(states[a], states[b]) {
                    ends += 1;
                    ends_in += usize::from(mask & (1 << EDGE_OF_VERTICES[a][b]) != 0);
                }
            }
            // Two ends at vertices: the plane meets the face along an edge, not inside.
            assert_eq!(
                fp[f],
                ends == 2 && ends_in == 1 && vertex_ends < 2,
                "{states:?}/{mask:06b} face {f}"
            );
        }
    }
}

#[test]
fn entry_sizes_match_the_paper() {
    // Table 1 of the paper: A 4 tets, B 6, C 6, D 8, E 9; no Steiner point anywhere (the
    // Schönhardt case cannot arise with diagonals at the lowest vertex). E needs 10 for half
    // of its vertex orders when the tables must hold for every position of the new points.
    let mut sizes: BTreeMap<CutCase, BTreeSet<usize>> = BTreeMap::new();
    for c in split_configs() {
        let (states, mask) = config_of_index(c);
        let case = CutCase::of_config(states, mask).expect("split");
        sizes.entry(case).or_default().insert(entry(c).0.len());
        assert!(
            entry(c).0.iter().flatten().all(|&p| p < 20),
            "no Steiner point"
        );
    }
    for (case, s) in &sizes {
        eprintln!("{:>15}: {s:?} children", case.name());
    }
    let only = |c: CutCase| sizes[&c].iter().copied().collect::<Vec<_>>();
    assert_eq!(only(CutCase::A), vec![4]);
    assert_eq!(only(CutCase::B), vec![6]);
    assert_eq!(only(CutCase::C), vec![6]);
    assert_eq!(only(CutCase::D), vec![8]);
    assert_eq!(only(CutCase::E), vec![9, 10]);
}
