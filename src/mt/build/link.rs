//! The link condition for an edge collapse (Dey, Edelsbrunner, Guha, Nekhayev 1999): the
//! collapse of edge `vw` keeps a 3-manifold a 3-manifold iff `Lk(v) ∩ Lk(w) = Lk(vw)`.
//!
//! The condition is checked on the *closed* complex (mesh plus ghost tets joining every
//! boundary triangle to the ghost vertex), where it covers the boundary cases too: for two
//! boundary vertices, the ghost vertex lies in both links, and it lies in `Lk(vw)` only when
//! `vw` is a boundary edge.
//!
//! `Lk(vw)` has no triangles, so the test is: no triangle in both links (two tets `vxyz`,
//! `wxyz` would become one), every edge in both links spans a tet `vwxy`, and every vertex
//! in both links spans a triangle `vwx`.

use super::collapse::Incident;
use crate::mt::GHOST;

/// Marks and buffers reused between calls (one set per worker thread). Marks are
/// generation counters, so "clearing" a set is incrementing a number.
#[derive(Default)]
pub(super) struct LinkScratch {
    /// `in_star[x] == generation_v`: x is a neighbour of the vertex being evaluated.
    in_star: Vec<u32>,
    generation_v: u32,
    /// `in_common[x] == generation_c`: x is a common neighbour of v and w.
    in_common: Vec<u32>,
    generation_c: u32,
    /// Whether the ghost vertex neighbours v / is a common neighbour.
    ghost_v: bool,
    ghost_common: bool,
    ring: Vec<u32>,
    edges_v: Vec<(u32, u32)>,
    edges_w: Vec<(u32, u32)>,
    edges_vw: Vec<(u32, u32)>,
    faces_v: Vec<[u32; 3]>,
    faces_w: Vec<[u32; 3]>,
}

impl LinkScratch {
    /// Starts the neighbour set of a new vertex, for a mesh of `nv` vertices.
    pub(super) fn begin(&mut self, nv: usize) {
        if self.in_star.len() < nv {
            self.in_star.resize(nv, 0);
            self.in_common.resize(nv, 0);
        }
        self.generation_v = self.generation_v.wrapping_add(1);
        if self.generation_v == 0 {
            self.in_star.fill(0);
            self.generation_v = 1;
        }
        self.ghost_v = false;
    }

    /// Adds `x` to the neighbour set; true if it was not there yet.
    #[inline]
    pub(super) fn insert(&mut self, x: u32) -> bool {
        if x == GHOST.0 {
            let new = !self.ghost_v;
            self.ghost_v = true;
            return new;
        }
        let m = &mut self.in_star[x as usize];
        let new = *m != self.generation_v;
        *m = self.generation_v;
        new
    }

    #[inline]
    fn neighbour(&self, x: u32) -> bool {
        if x == GHOST.0 {
            self.ghost_v
        } else {
            self.in_star[x as usize] == self.generation_v
        }
    }

    #[inline]
    fn common(&self, x: u32) -> bool {
        if x == GHOST.0 {
            self.ghost_common
        } else {
            self.in_common[x as usize] == self.generation_c
        }
    }
}

/// Edges and triangles of the link of `x` (faces opposite `x` in its star) whose
/// vertices are all common neighbours.
fn link_parts_within(
    star: &[Incident],
    x: u32,
    s: &LinkScratch,
    edges: &mut Vec<(u32, u32)>,
    faces: &mut Vec<[u32; 3]>,
) {
    edges.clear();
    faces.clear();
    for inc in star {
        let mut f = [0u32; 3];
        let mut k = 0;
        for v in &inc.tet {
            if v.0 != x && k < 3 {
                f[k] = v.0;
                k += 1;
            }
        }
        let inside = f.map(|v| s.common(v));
        for (a, b) in [(0, 1), (0, 2), (1, 2)] {
            if inside[a] && inside[b] {
                edges.push((f[a].min(f[b]), f[a].max(f[b])));
            }
        }
        if inside.iter().all(|&i| i) {
            f.sort_unstable();
            faces.push(f);
        }
    }
    edges.sort_unstable();
    edges.dedup();
    faces.sort_unstable();
}

/// Whether every element of `a` that is also in `b` is in `allowed` (all three sorted).
fn intersection_within<T: Ord>(a: &[T], b: &[T], allowed: &[T]) -> bool {
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                if allowed.binary_search(&a[i]).is_err() {
                    return false;
                }
                i += 1;
                j += 1;
            }
        }
    }
    true
}

/// The link condition for collapsing `v` onto `w`, given their stars (pool tet ids into
/// `tets`, ghosts included) and, in `s`, the neighbour set of `v` (see
/// [`LinkScratch::begin`]).
///
/// Every simplex of `Lk(v) ∩ Lk(w)` has its vertices among the common neighbours of `v`
/// and `w`, a handful, so the links are only examined there: the common neighbours must be
/// exactly the vertices of `Lk(vw)` (the ring around `vw`, always among them, so counting
/// suffices), the link edges among them shared by both links must be edges of `Lk(vw)`,
/// and no link triangle may be shared.
pub(super) fn link_condition(
    star_v: &[Incident],
    star_w: &[Incident],
    v: u32,
    w: u32,
    s: &mut LinkScratch,
) -> bool {
    s.generation_c = s.generation_c.wrapping_add(1);
    if s.generation_c == 0 {
        s.in_common.fill(0);
        s.generation_c = 1;
    }
    s.ghost_common = false;
    let mut common = 0usize;
    for inc in star_w {
        for x in &inc.tet {
            let x = x.0;
            if x == w || x == v || !s.neighbour(x) {
                continue;
            }
            if x == GHOST.0 {
                if !s.ghost_common {
                    s.ghost_common = true;
                    common += 1;
                }
            } else if s.in_common[x as usize] != s.generation_c {
                s.in_common[x as usize] = s.generation_c;
                common += 1;
            }
        }
    }
    s.ring.clear();
    s.edges_vw.clear();
    for inc in star_v {
        let tet = &inc.tet;
        if !tet.iter().any(|x| x.0 == w) {
            continue;
        }
        let mut e = [0u32; 2];
        let mut k = 0;
        for x in tet {
            if x.0 != v && x.0 != w && k < 2 {
                e[k] = x.0;
                k += 1;
            }
        }
        s.ring.extend(e);
        s.edges_vw.push((e[0].min(e[1]), e[0].max(e[1])));
    }
    s.ring.sort_unstable();
    s.ring.dedup();
    if common != s.ring.len() {
        return false;
    }
    s.edges_vw.sort_unstable();
    s.edges_vw.dedup();
    let (mut ev, mut fv) = (
        std::mem::take(&mut s.edges_v),
        std::mem::take(&mut s.faces_v),
    );
    let (mut ew, mut fw) = (
        std::mem::take(&mut s.edges_w),
        std::mem::take(&mut s.faces_w),
    );
    link_parts_within(star_v, v, s, &mut ev, &mut fv);
    link_parts_within(star_w, w, s, &mut ew, &mut fw);
    let ok = intersection_within(&ev, &ew, &s.edges_vw) && intersection_within(&fv, &fw, &[]);
    (s.edges_v, s.faces_v, s.edges_w, s.faces_w) = (ev, fv, ew, fw);
    ok
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Tet, VertexId};

    fn tet(a: u32, b: u32, c: u32, d: u32) -> Tet {
        [VertexId(a), VertexId(b), VertexId(c), VertexId(d)]
    }

    /// Two tets sharing face (1,2,3) with apexes 0 and 4, closed by ghosts (vertex 9).
    fn bipyramid() -> Vec<Tet> {
        vec![
            tet(0, 1, 2, 3),
            tet(1, 4, 2, 3),
            // ghosts on the six boundary faces
            tet(0, 2, 1, 9),
            tet(0, 1, 3, 9),
            tet(0, 3, 2, 9),
            tet(4, 1, 2, 9),
            tet(4, 3, 1, 9),
            tet(4, 2, 3, 9),
        ]
    }

    fn star(tets: &[Tet], v: u32) -> Vec<Incident> {
        (0..tets.len() as u32)
            .filter(|&t| tets[t as usize].iter().any(|x| x.0 == v))
            .map(|t| Incident {
                id: t,
                tet: tets[t as usize],
            })
            .collect()
    }

    fn check(t: &[Tet], v: u32, w: u32) -> bool {
        let mut s = LinkScratch::default();
        s.begin(10);
        for inc in &star(t, v) {
            for x in &inc.tet {
                if x.0 != v {
                    s.insert(x.0);
                }
            }
        }
        link_condition(&star(t, v), &star(t, w), v, w, &mut s)
    }

    #[test]
    fn boundary_edge_of_bipyramid_collapses_but_apexes_do_not_merge() {
        let mut t = bipyramid();
        for tet in &mut t {
            for x in tet.iter_mut() {
                if x.0 == 9 {
                    *x = GHOST;
                }
            }
        }
        // Edge (0,1) is an edge of the bipyramid: collapsible.
        assert!(check(&t, 0, 1));
        // Apexes 0 and 4 are not joined by an edge, and share the link triangle (1,2,3):
        // merging them would make two tets one.
        assert!(!check(&t, 0, 4));
    }
}
