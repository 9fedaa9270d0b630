//! Parts a cut would leave floating in the crack (snapping artefacts).
//!
//! Snapping is decided per vertex, relative to each vertex's scale (its longest edge), and
//! that leaves two kinds of parts the exact plane does not make. A simulation would get a
//! free body from each.
//!
//! * The four vertices of a tet with long edges around it can all be snapped onto the cut.
//!   Left whole, such a tet lies in the cut and takes the side of its centroid; but its
//!   neighbours through faces (each with a fourth vertex off the cut) may all lie on the
//!   other side, and then it is joined to nothing on its own side: a single tet. Such a
//!   tet now takes its neighbours' side ([`in_cut_sides`]). Over 300 random planes
//!   straight through liver (default options, tests/cut_pockets.rs) the single-tet parts
//!   went from 58 to 9 (8 with the rule below); over another 300 from 59 to 7.
//! * Vertices just off the plane, not snapped, whose other neighbours are all snapped or
//!   across cut edges are enclosed with their stars (6 tets around one vertex on
//!   fandisk-1m cut by z = 0; 15 tets around five vertices along a tooth of pinion). Some
//!   of those snapped neighbours lie on their side of the exact plane (an interior vertex
//!   lies inside its neighbours' hull): they are now left unsnapped
//!   ([`enclosing_snapped`]), with their coincident copies on earlier cracks (as pinched
//!   vertices are), or a face point on one lip of an old crack would lie inside the other
//!   lip's face. Whether the cut's candidates hold every tet around a vertex is read from
//!   the vertex valences the cutter keeps. Parts below 1e-5 of the volume over 300
//!   planes through liver: 20 → 11 (the exact plane's own caps off liver's bumps among
//!   them); pinion 1 → 0. Over 300 other planes, cuts leaving more parts than the same
//!   cut with the smallest snap: fandisk 5 → 3, pinion 28 → 17, liver 40 → 16 (the
//!   exact plane also makes parts there, caps along the boundary, which no rule here
//!   removes).
//!
//! # Limits
//!
//! * A tet lying in the cut next to another one keeps its centroid's side: in a crack
//!   continued step by step, such tets near the earlier crack are joined to their side
//!   through one another, and deciding them by their other neighbours left a swept body
//!   in one piece.
//! * A group of more than [`MAX_GROUP`] vertices is left enclosed (taken for a side of a
//!   thin body), as is a group whose snapped neighbours on its side lie closer to the
//!   plane than [`MIN_UNSNAP`] of their scale.
//! * Snapping the enclosed vertices instead bends the crack farther than their own
//!   snapping distance: edges would cross C strictly inside it.
//! * The MT cut, and the plain cut continuing cracks (an MT frontier, a scalpel), which
//!   decides as the MT cut does, keep the centroid's side and the snapped vertices. The
//!   MT cut's snap is at most [`super::mt_cut::MAX_MT_SNAP`] (1e-6 of a vertex's scale
//!   by default): over 60 random planes through each shared MT, none left more parts
//!   than the exact plane.

use super::classify::TetClass;
use super::tables::{NEG, ON, OUT, POS, Side};
use crate::geom::{CutPolygon, DVec3, Sign};
use crate::mesh::fxhash::FxBuild;
use crate::mesh::tables::EDGE_OF_VERTICES;
use crate::mesh::{Tet, VertexId};
use std::collections::HashMap;

/// The candidates whose four vertices are snapped (`classes`' states all `ON`) that the
/// side of their centroid would leave alone: every neighbour through a face (a candidate
/// holding three of their vertices snapped and a fourth off the cut) on the other side,
/// none lying in the cut too. That other side, by candidate index, sorted; the others
/// keep the centroid's side (a tet lying in the cut next to another is left as it was: in
/// a crack continued step by step, such tets near the earlier crack are joined to their
/// side through one another).
pub(crate) fn in_cut_sides(
    positions: &[DVec3],
    polygon: &CutPolygon,
    tets: &[Tet],
    classes: &[TetClass],
) -> Vec<(usize, Side)> {
    // Every candidate's states are read, once per plan pass: as one word each.
    let all_on = u32::from_le_bytes([ON; 4]);
    let lying: Vec<usize> = (0..tets.len())
        .filter(|&k| u32::from_le_bytes(classes[k].states) == all_on)
        .collect();
    if lying.is_empty() {
        return Vec::new();
    }
    // States other than `ON`: the bytes of the word that differ from `all_on`.
    let off = |c: &TetClass| {
        let x = u32::from_le_bytes(c.states) ^ all_on;
        ((((x & 0x7f7f_7f7f) + 0x7f7f_7f7f) | x) & 0x8080_8080).count_ones()
    };
    let face = |t: &Tet, skip: usize| {
        let mut f = [0u32; 3];
        let mut m = 0;
        for (j, v) in t.iter().enumerate() {
            if j != skip {
                f[m] = v.0;
                m += 1;
            }
        }
        f.sort_unstable();
        f
    };
    // Their faces, each naming the lying tets through it (two lying tets may share one).
    let mut faces: HashMap<[u32; 3], [u32; 2], FxBuild> = HashMap::default();
    for (i, &k) in lying.iter().enumerate() {
        for skip in 0..4 {
            let e = faces.entry(face(&tets[k], skip)).or_insert([u32::MAX; 2]);
            e[usize::from(e[0] != u32::MAX)] = i as u32;
        }
    }
    // Per lying tet: neighbours seen on the positive and on the negative side, and
    // whether one lies in the cut too.
    let mut seen = vec![[false; 2]; lying.len()];
    let mut next_to_lying = vec![false; lying.len()];
    for names in faces.values().filter(|n| n[1] != u32::MAX) {
        next_to_lying[names[0] as usize] = true;
        next_to_lying[names[1] as usize] = true;
    }
    // Their vertices: a face holding none is passed over without hashing it.
    let mut corners: Vec<u32> = lying.iter().flat_map(|&k| tets[k].map(|v| v.0)).collect();
    corners.sort_unstable();
    corners.dedup();
    for (t, c) in tets.iter().zip(classes) {
        if off(c) != 1 {
            continue;
        }
        let j = c.states.iter().position(|&s| s != ON).unwrap_or(0);
        if corners.binary_search(&t[(j + 1) % 4].0).is_err() {
            continue;
        }
        let side = match c.states[j] {
            POS => 0,
            NEG => 1,
            _ => continue,
        };
        if let Some(names) = faces.get(&face(t, j)) {
            for &i in names.iter().filter(|&&i| i != u32::MAX) {
                seen[i as usize][side] = true;
            }
        }
    }
    lying
        .iter()
        .enumerate()
        .filter(|&(i, _)| !next_to_lying[i])
        .filter_map(
            |(i, &k)| match (seen[i], centroid_side(positions, polygon, &tets[k])) {
                ([true, false], Side::Negative) => Some((k, Side::Positive)),
                ([false, true], Side::Positive) => Some((k, Side::Negative)),
                _ => None,
            },
        )
        .collect()
}

/// The distance to the plane, relative to its scale, below which [`enclosing_snapped`]
/// leaves a vertex snapped.
const MIN_UNSNAP: f64 = 1e-5;

/// Per configuration (vertex states, two bits each, and cut-edge mask, as
/// `TetClass::states` and `TetClass::cut_mask`): the corners off the cut (`NEG`, `POS`),
/// bits 0-3, and those of them a candidate joins to a vertex across an edge the cut does
/// not cut or outside C (`OUT`), bits 4-7. Read once per candidate instead of branching
/// per corner ([`enclosing_snapped`] reads every candidate's corners).
static CORNERS: [u8; 256 * 64] = corner_table();

const fn corner_table() -> [u8; 256 * 64] {
    let mut table = [0u8; 256 * 64];
    let mut config = 0;
    while config < 256 * 64 {
        let (packed, mask) = (config & 255, config >> 8);
        let mut bits = 0u8;
        let mut j = 0;
        while j < 4 {
            let s = (packed >> (2 * j)) as u8 & 3;
            if s == NEG || s == POS {
                bits |= 1 << j;
                let mut i = 0;
                while i < 4 {
                    if i != j {
                        let o = (packed >> (2 * i)) as u8 & 3;
                        let cut = mask & (1 << EDGE_OF_VERTICES[i][j]) != 0;
                        if o == OUT || (o ^ s == NEG ^ POS && !cut) {
                            bits |= 16 << j;
                        }
                    }
                    i += 1;
                }
            }
            j += 1;
        }
        table[config] = bits;
        config += 1;
    }
    table
}

/// [`CORNERS`]' entry for a candidate.
#[inline]
fn corners(c: &TetClass) -> u8 {
    let packed = c.states[0] | c.states[1] << 2 | c.states[2] << 4 | c.states[3] << 6;
    CORNERS[usize::from(packed) | usize::from(c.cut_mask) << 8]
}

/// The most vertices a group enclosed together may have ([`enclosing_snapped`]): the
/// pockets snapping makes are thin layers of a few vertices along the boundary; a larger
/// group held only by candidates is a side of a thin body, which the exact plane cuts
/// off too.
const MAX_GROUP: usize = 32;

/// Per vertex of `tets` (`n_vertices` of them): the number of tets holding it (the
/// candidates of a cut hold every tet around a vertex when they hold that many), and
/// [`enclosing_snapped`]'s scratch, zero. Side by side: the scratch is read with the
/// valence, from one cache line (apart, the valences' reads were most of its time).
pub(crate) fn valences(n_vertices: usize, tets: &[Tet]) -> Vec<[u32; 2]> {
    let mut valence = vec![[0u32; 2]; n_vertices];
    for v in tets.iter().flatten() {
        valence[v.idx()][0] += 1;
    }
    valence
}

/// The snapped vertices (of `snapped`, sorted) to leave unsnapped so that no vertex just
/// off the cut is enclosed with its star. Vertices off the cut (`NEG`, `POS`) joined by
/// edges on their side make groups; a group is enclosed when the candidates hold every
/// tet around its vertices (`valence`) and none of them joins a vertex of the group to a
/// vertex off the group: one on its side outside it, or one across an edge the cut does
/// not cut (outside C), or one outside C (`OUT`). The crack then surrounds the group's
/// stars: a part of its own. Around interior vertices the exact plane cannot do that
/// (they lie inside their neighbours' hull), so some snapped neighbour lies on their
/// side: the snapped neighbours whose exact side is the group's (the edges to them lie on
/// its side of the exact plane) are returned, to be unsnapped. A group on the boundary
/// whose snapped neighbours all lie beyond the plane is a cap the exact plane cuts off
/// too, as is a group of more than [`MAX_GROUP`] vertices: they return nothing. A
/// neighbour closer to the plane than [`MIN_UNSNAP`] of its scale stays snapped: the cut
/// points on its edges would make children below a millionth of their parents' volume,
/// or flat ones once rounded (a cut then refused).
///
/// `valence` is as [`valences`] makes it: its scratch is zero before and after.
pub(crate) fn enclosing_snapped(
    positions: &[DVec3],
    scales: &[f64],
    polygon: &CutPolygon,
    tets: &[Tet],
    classes: &[TetClass],
    snapped: &[VertexId],
    valence: &mut [[u32; 2]],
) -> Vec<VertexId> {
    // The scratch's flags, above the number of candidates holding the vertex: a candidate
    // joins it to a vertex off its group; it is a group member (its index below).
    const OPEN: u32 = 1 << 31;
    const MEMBER: u32 = 1 << 30;
    const INDEX: u32 = MEMBER - 1;
    if snapped.is_empty() {
        return Vec::new();
    }
    let off = |s: u8| s == NEG || s == POS;
    // The candidates holding each vertex off the cut, and whether one opens it (without
    // branching on either: both are common and unpredictable).
    let all: Vec<u8> = classes.iter().map(corners).collect();
    for (t, &c) in tets.iter().zip(&all) {
        for (j, v) in t.iter().enumerate() {
            let x = &mut valence[v.idx()][1];
            *x = (*x + u32::from((c >> j) & 1)) | (OPEN * u32::from((c >> (4 + j)) & 1));
        }
    }
    // The vertices all of whose tets are candidates, none opening them: the members (a
    // vertex on the cut has a count of 0, below its valence).
    let mut members: Vec<VertexId> = Vec::new();
    for t in tets {
        for &v in t {
            let [n, x] = &mut valence[v.idx()];
            if *x == *n {
                *x = MEMBER | members.len() as u32;
                members.push(v);
            }
        }
    }
    let mut out: Vec<VertexId> = Vec::new();
    if !members.is_empty() {
        // Groups: members joined by edges on their side (union-find); a group with a
        // member joined so to a vertex not a member is open.
        let mut parent: Vec<u32> = (0..members.len() as u32).collect();
        let mut opened = vec![false; members.len()];
        fn root(parent: &mut [u32], mut i: u32) -> u32 {
            while parent[i as usize] != i {
                parent[i as usize] = parent[parent[i as usize] as usize];
                i = parent[i as usize];
            }
            i
        }
        let member = |x: u32| (x & MEMBER != 0).then_some(x & INDEX);
        for (t, c) in tets.iter().zip(classes) {
            if t.iter().all(|v| valence[v.idx()][1] & MEMBER == 0) {
                continue;
            }
            for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
                if !off(c.states[i]) || c.states[i] != c.states[j] {
                    continue;
                }
                match (
                    member(valence[t[i].idx()][1]),
                    member(valence[t[j].idx()][1]),
                ) {
                    (Some(a), Some(b)) => {
                        let (a, b) = (root(&mut parent, a), root(&mut parent, b));
                        parent[a as usize] = b;
                    }
                    (Some(a), None) | (None, Some(a)) => opened[a as usize] = true,
                    (None, None) => {}
                }
            }
        }
        let mut size = vec![0usize; members.len()];
        for i in 0..members.len() as u32 {
            let r = root(&mut parent, i) as usize;
            size[r] += 1;
            opened[r] |= opened[i as usize];
        }
        let enclosed: Vec<bool> = (0..members.len() as u32)
            .map(|i| {
                let r = root(&mut parent, i) as usize;
                !opened[r] && size[r] <= MAX_GROUP
            })
            .collect();
        // Their snapped neighbours on their side.
        if enclosed.contains(&true) {
            for (t, c) in tets.iter().zip(classes) {
                if t.iter().all(|v| valence[v.idx()][1] & MEMBER == 0) {
                    continue;
                }
                for j in (0..4).filter(|&j| off(c.states[j])) {
                    let Some(m) = member(valence[t[j].idx()][1]) else {
                        continue;
                    };
                    if !enclosed[m as usize] {
                        continue;
                    }
                    let side = if c.states[j] == POS {
                        Sign::Positive
                    } else {
                        Sign::Negative
                    };
                    out.extend(
                        (0..4)
                            .filter(|&i| c.states[i] == ON)
                            .map(|i| t[i])
                            .filter(|u| snapped.binary_search(u).is_ok())
                            .filter(|u| {
                                let p = positions[u.idx()];
                                polygon.side(p) == side
                                    && polygon.signed_distance(p).abs()
                                        > MIN_UNSNAP * scales[u.idx()]
                            }),
                    );
                }
            }
        }
    }
    for t in tets {
        for v in t {
            valence[v.idx()][1] = 0;
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// The side of a tet lying in the cut by default: its centroid's.
pub(crate) fn centroid_side(positions: &[DVec3], polygon: &CutPolygon, tet: &Tet) -> Side {
    let c = tet.iter().map(|v| positions[v.idx()]).sum::<DVec3>() * 0.25;
    if polygon.signed_distance(c) < 0.0 {
        Side::Negative
    } else {
        Side::Positive
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A triangle in the plane z = 0, covering the tests' vertices.
    fn plane_z0() -> CutPolygon {
        CutPolygon::new(&[
            DVec3::new(-5.0, -5.0, 0.0),
            DVec3::new(5.0, -5.0, 0.0),
            DVec3::new(0.0, 5.0, 0.0),
        ])
        .unwrap()
    }

    fn class(states: [u8; 4]) -> TetClass {
        TetClass {
            states,
            cut_mask: 0,
            face_mask: 0,
            edges: [u32::MAX; 6],
            faces: [u32::MAX; 4],
        }
    }

    #[test]
    fn a_tet_lying_in_the_cut_takes_the_side_its_neighbours_agree_on() {
        // Tet 0 lies in the cut z = 0 (its corners snapped, its centroid below); tets 1-4
        // hold one face of it each and a fourth vertex above or below.
        let positions = vec![
            DVec3::new(0.0, 0.0, -0.02),
            DVec3::new(1.0, 0.0, -0.01),
            DVec3::new(0.0, 1.0, 0.01),
            DVec3::new(0.3, 0.3, -0.03),
            DVec3::new(0.2, 0.2, 1.0),
            DVec3::new(0.2, 0.2, -1.0),
        ];
        let polygon = plane_z0();
        let t = |v: [u32; 4]| v.map(VertexId);
        let lying = (t([0, 1, 2, 3]), class([ON; 4]));
        let faces = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];
        let around = |fourth: [u32; 4]| -> (Vec<Tet>, Vec<TetClass>) {
            let mut tets = vec![lying.0];
            let mut classes = vec![lying.1];
            for (f, x) in faces.iter().zip(fourth) {
                tets.push(t([f[0], f[1], f[2], x]));
                let s = if positions[x as usize].z > 0.0 {
                    POS
                } else {
                    NEG
                };
                classes.push(class([ON, ON, ON, s]));
            }
            (tets, classes)
        };
        let (tets, classes) = around([4; 4]);
        assert_eq!(
            in_cut_sides(&positions, &polygon, &tets, &classes),
            [(0, Side::Positive)]
        );
        // Neighbours on both sides, or all on its centroid's: it keeps its centroid's side.
        for fourth in [[4, 4, 4, 5], [5; 4]] {
            let (tets, classes) = around(fourth);
            assert!(in_cut_sides(&positions, &polygon, &tets, &classes).is_empty());
        }
        // Next to another tet lying in the cut: left as it was.
        let (mut tets, mut classes) = around([4; 4]);
        tets[4] = t([0, 1, 2, 5]);
        classes[4] = class([ON; 4]);
        assert!(in_cut_sides(&positions, &polygon, &tets, &classes).is_empty());
    }

    #[test]
    fn vertices_enclosed_by_snapped_neighbours_on_their_side_unsnap_them() {
        // Vertex 0 on the body's top, just above the cut z = 0 and not snapped; its four
        // neighbours on the top (1-4) snapped, vertex 5 below across a cut edge: its star
        // (tets 0, i, i + 1, 5) would be a part of its own. Vertices 5 and 6, below, have
        // a tet that is not a candidate (its valence counts it).
        let star = |ring_z: f64| {
            let mut p = vec![DVec3::new(0.0, 0.0, 0.02)];
            p.extend(
                [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)]
                    .map(|(x, y)| DVec3::new(x, y, ring_z)),
            );
            p.extend([
                DVec3::new(0.0, 0.0, -1.0),
                DVec3::new(0.5, 0.5, -2.0),
                DVec3::new(0.5, 0.5, 0.5),
            ]);
            p
        };
        let polygon = plane_z0();
        let t = |v: [u32; 4]| v.map(VertexId);
        let mut tets: Vec<Tet> = (0..4).map(|i| t([0, 1 + i, 1 + (i + 1) % 4, 5])).collect();
        tets.push(t([5, 1, 2, 6]));
        let mut cut = class([POS, ON, ON, NEG]);
        cut.cut_mask = 1 << EDGE_OF_VERTICES[0][3];
        let mut classes = vec![cut; 4];
        classes.push(class([NEG, ON, ON, NEG]));
        let snapped: Vec<VertexId> = (1..5).map(VertexId).collect();
        // `outside`: vertices with one more tet than the candidates hold.
        let run = |z: f64, tets: &[Tet], classes: &[TetClass], outside: &[usize]| {
            let positions = star(z);
            let scales = vec![1.0; positions.len()];
            let mut valence = valences(positions.len(), tets);
            for &v in outside {
                valence[v][0] += 1;
            }
            let out = enclosing_snapped(
                &positions,
                &scales,
                &polygon,
                tets,
                classes,
                &snapped,
                &mut valence,
            );
            assert!(valence.iter().all(|v| v[1] == 0), "scratch left clean");
            out
        };
        // The ring above the plane: it is unsnapped.
        assert_eq!(run(0.03, &tets, &classes, &[5, 6]), snapped);
        // The ring below: a cap the exact plane cuts off too, left alone; so is a ring too
        // close to the plane.
        assert!(run(-0.03, &tets, &classes, &[5, 6]).is_empty());
        assert!(run(1e-6, &tets, &classes, &[5, 6]).is_empty());
        // Vertex 5 enclosed as well (all its tets candidates, with vertex 6): the ring
        // below is the group {5, 6}'s neighbours on its side.
        assert_eq!(run(-0.03, &tets, &classes, &[]), snapped);
        // The edge down not cut (outside C): vertex 0 keeps its side through it.
        let mut uncut = classes.clone();
        uncut[0].cut_mask = 0;
        assert!(run(0.03, &tets, &uncut, &[5, 6]).is_empty());
        // A neighbour off the cut on its side (vertex 7, in one more candidate) joins it
        // to the rest of its side, unless all of vertex 7's tets are candidates too: then
        // the two are enclosed together.
        tets.push(t([0, 1, 2, 7]));
        classes.push(class([POS, ON, ON, POS]));
        assert!(run(0.03, &tets, &classes, &[5, 6, 7]).is_empty());
        assert_eq!(run(0.03, &tets, &classes, &[5, 6]), snapped);
    }
}
