//! Tets a cut would leave floating alone in the crack (a snapping artefact).
//!
//! Snapping is decided per vertex, relative to each vertex's scale (its longest edge): the
//! four vertices of a tet with long edges around it can all be snapped onto the cut. Left
//! whole, such a tet lies in the cut and takes the side of its centroid; but its
//! neighbours through faces (each with a fourth vertex off the cut) may all lie on the
//! other side, and then it is joined to nothing on its own side: the cut leaves it a
//! part of its own, a single tet that the exact plane does not cut off. A simulation
//! would get a free body. Such a tet now takes its neighbours' side ([`in_cut_sides`]).
//! Over 300 random planes straight through liver (default options, tests/cut_pockets.rs)
//! the single-tet parts went from 58 to 9; over another 300 from 59 to 7, the parts below
//! 1e-5 of the volume from 80 to 28.
//!
//! # Limits
//!
//! * A tet lying in the cut next to another one keeps its centroid's side: in a crack
//!   continued step by step, such tets near the earlier crack are joined to their side
//!   through one another, and deciding them by their other neighbours left a swept body
//!   in one piece.
//! * A vertex just off the plane whose neighbours are all snapped (some beyond it) or
//!   across cut edges is enclosed the same way, with its star (2 such parts on fandisk,
//!   3 on pinion, over 300 planes each). Snapping it too bends the crack farther than
//!   its own snapping distance (edges then cross C strictly inside it); unsnapping the
//!   neighbours on its side must unsnap their coincident copies from earlier cracks
//!   with them (as [`super::Cutter::cut`] does for pinched vertices) or leaves hanging
//!   vertices. Not done.
//! * The MT cut, and the plain cut continuing cracks (an MT frontier, a scalpel), which
//!   decides as the MT cut does, keep the centroid's side.

use super::classify::TetClass;
use super::tables::{NEG, ON, POS, Side};
use crate::geom::{CutPolygon, DVec3};
use crate::mesh::Tet;
use crate::mesh::fxhash::FxBuild;
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
    use crate::mesh::VertexId;

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
        let polygon = CutPolygon::new(&[
            DVec3::new(-5.0, -5.0, 0.0),
            DVec3::new(5.0, -5.0, 0.0),
            DVec3::new(0.0, 5.0, 0.0),
        ])
        .unwrap();
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
}
