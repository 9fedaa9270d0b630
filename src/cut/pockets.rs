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
    let on = |c: &TetClass| c.states.iter().filter(|&&s| s == ON).count();
    let lying: Vec<usize> = (0..tets.len()).filter(|&k| on(&classes[k]) == 4).collect();
    if lying.is_empty() {
        return Vec::new();
    }
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
    for (t, c) in tets.iter().zip(classes) {
        if on(c) != 3 {
            continue;
        }
        let j = c.states.iter().position(|&s| s != ON).unwrap_or(0);
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
        .filter_map(|(i, &k)| {
            let c = tets[k].iter().map(|v| positions[v.idx()]).sum::<DVec3>() * 0.25;
            let centroid_negative = polygon.signed_distance(c) < 0.0;
            match seen[i] {
                [true, false] if centroid_negative => Some((k, Side::Positive)),
                [false, true] if !centroid_negative => Some((k, Side::Negative)),
                _ => None,
            }
        })
        .collect()
}
