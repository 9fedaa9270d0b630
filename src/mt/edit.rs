//! Editing an MT in place: the open form that cuts modify, and the sub-MTs (independent
//! components) a cut straight through leaves in one store.
//!
//! An [`OpenMt`] is the store with one creator and one destroyer *per tet* instead of
//! contiguous arcs: tets can then be replaced in place, appended, and relabelled freely
//! (the paper's expanded arcs, §3). [`OpenMt::close`] sorts the pool back into arcs and
//! assembles the MT, deriving levels, boxes and arc lists with the same code as a build or
//! a load, so an edit cannot leave them inconsistent. Appended vertices and tets need
//! attribute rows; the editor pushes them (interpolated for vertices, inherited for tets,
//! zeros for ghosts).
//!
//! This module knows nothing of cuts: the cut layer (`crate::cut::mt`) decides what to
//! change.

use super::{FragmentKind, GHOST, Mt, MtInfo, MtParts};
use crate::geom::DVec3;
use crate::mesh::{Attributes, FragmentId, Tet, TetId, VertexId};

/// An MT opened for editing (see the [module docs](self)).
#[derive(Clone, Debug)]
pub struct OpenMt {
    pub positions: Vec<DVec3>,
    pub point_data: Attributes,
    /// Every tet of every level, ghosts included.
    pub tets: Vec<Tet>,
    pub cell_data: Attributes,
    /// Creator and destroyer of each tet.
    pub creator: Vec<FragmentId>,
    pub destroyer: Vec<FragmentId>,
    pub kind: Vec<FragmentKind>,
    pub error: Vec<f64>,
    pub info: MtInfo,
}

impl Mt {
    /// The open form of this MT (per-tet creator and destroyer).
    pub fn open(self) -> OpenMt {
        let nt = self.nb_tets();
        let mut creator = Vec::with_capacity(nt);
        let mut destroyer = Vec::with_capacity(nt);
        for (a, c, d) in self.arcs() {
            let n = self.arc_tets(a).len();
            creator.extend(std::iter::repeat_n(c, n));
            destroyer.extend(std::iter::repeat_n(d, n));
        }
        OpenMt {
            positions: self.positions,
            point_data: self.point_data,
            tets: self.tets,
            cell_data: self.cell_data,
            creator,
            destroyer,
            kind: self.kind,
            error: self.error,
            info: self.info,
        }
    }

    /// The weakly connected component of each fragment in the DAG (numbered by their
    /// smallest fragment id), and their number. A body cut straight through at every level
    /// becomes separate components, each with its own roots and drains.
    pub fn fragment_components(&self) -> (usize, Vec<u32>) {
        let nf = self.nb_fragments();
        let mut parent: Vec<u32> = (0..nf as u32).collect();
        fn find(p: &mut [u32], mut i: u32) -> u32 {
            while p[i as usize] != i {
                p[i as usize] = p[p[i as usize] as usize];
                i = p[i as usize];
            }
            i
        }
        for (_, c, d) in self.arcs() {
            let (x, y) = (find(&mut parent, c.0), find(&mut parent, d.0));
            if x != y {
                parent[x.max(y) as usize] = x.min(y);
            }
        }
        let mut label = vec![u32::MAX; nf];
        let mut n = 0u32;
        for f in 0..nf as u32 {
            let r = find(&mut parent, f) as usize;
            if label[r] == u32::MAX {
                label[r] = n;
                n += 1;
            }
            label[f as usize] = label[r];
        }
        (n as usize, label)
    }

    /// Independent component `k` (see [`fragment_components`](Self::fragment_components))
    /// as an MT of its own: its fragments, the tets they create and destroy, and the
    /// vertices those use, renumbered in their order here. `None` when `k` is out of range.
    pub fn component(&self, k: usize) -> Option<Mt> {
        let (n, label) = self.fragment_components();
        if k >= n {
            return None;
        }
        let keep_f: Vec<usize> = (0..self.nb_fragments())
            .filter(|&f| label[f] as usize == k)
            .collect();
        let keep_t: Vec<usize> = (0..self.nb_tets())
            .filter(|&t| label[self.tet_creator(TetId::from_usize(t)).idx()] as usize == k)
            .collect();
        Some(self.restrict(&keep_f, &keep_t))
    }

    /// Components `ks` (see [`fragment_components`](Self::fragment_components); indices
    /// out of range are ignored) as one MT: their fragments, tets and vertices, in their
    /// order here.
    pub fn select_components(&self, ks: &[usize]) -> Mt {
        let (n, label) = self.fragment_components();
        let mut wanted = vec![false; n];
        for &k in ks.iter().filter(|&&k| k < n) {
            wanted[k] = true;
        }
        let keep_f: Vec<usize> = (0..self.nb_fragments())
            .filter(|&f| wanted[label[f] as usize])
            .collect();
        let mut keep_t: Vec<usize> = self
            .arcs()
            .filter(|&(_, c, _)| wanted[label[c.idx()] as usize])
            .flat_map(|(a, _, _)| self.arc_tets(a))
            .collect();
        keep_t.sort_unstable();
        self.restrict(&keep_f, &keep_t)
    }

    /// The MTs of every component, in component order.
    pub fn components(&self) -> Vec<Mt> {
        let (n, _) = self.fragment_components();
        (0..n).filter_map(|k| self.component(k)).collect()
    }

    /// The MT made of fragments `keep_f` and pool tets `keep_t` (both increasing; every
    /// kept tet's creator and destroyer kept), vertices compacted.
    fn restrict(&self, keep_f: &[usize], keep_t: &[usize]) -> Mt {
        let mut new_f = vec![u32::MAX; self.nb_fragments()];
        for (i, &f) in keep_f.iter().enumerate() {
            new_f[f] = i as u32;
        }
        let mut new_v = vec![u32::MAX; self.nb_vertices()];
        for &t in keep_t {
            for v in self.tets[t].iter().filter(|v| **v != GHOST) {
                new_v[v.idx()] = 0;
            }
        }
        let mut keep_v = Vec::new();
        for (v, slot) in new_v.iter_mut().enumerate() {
            if *slot == 0 {
                *slot = keep_v.len() as u32;
                keep_v.push(v);
            }
        }
        let mut open = OpenMt {
            positions: keep_v.iter().map(|&v| self.positions[v]).collect(),
            point_data: self.point_data.select(&keep_v),
            tets: keep_t
                .iter()
                .map(|&t| {
                    self.tets[t].map(|v| {
                        if v == GHOST {
                            GHOST
                        } else {
                            VertexId(new_v[v.idx()])
                        }
                    })
                })
                .collect(),
            cell_data: self.cell_data.select(keep_t),
            creator: Vec::with_capacity(keep_t.len()),
            destroyer: Vec::with_capacity(keep_t.len()),
            kind: keep_f.iter().map(|&f| self.kind[f]).collect(),
            error: keep_f.iter().map(|&f| self.error[f]).collect(),
            info: self.info.clone(),
        };
        for &t in keep_t {
            let t = TetId::from_usize(t);
            open.creator
                .push(FragmentId(new_f[self.tet_creator(t).idx()]));
            open.destroyer
                .push(FragmentId(new_f[self.tet_destroyer(t).idx()]));
        }
        open.close()
            .unwrap_or_else(|e| panic!("a component of a valid MT is inconsistent: {e}"))
    }
}

impl OpenMt {
    /// Sorts the pool into arcs (by creator, then destroyer, then current position: stable)
    /// and assembles the MT. Errors say what is inconsistent (an editing bug).
    pub fn close(self) -> Result<Mt, String> {
        let nt = self.tets.len();
        if self.creator.len() != nt || self.destroyer.len() != nt {
            return Err(format!(
                "{nt} tets with {} creators and {} destroyers",
                self.creator.len(),
                self.destroyer.len()
            ));
        }
        let nf = self.kind.len();
        if let Some(t) =
            (0..nt).find(|&t| self.creator[t].idx() >= nf || self.destroyer[t].idx() >= nf)
        {
            return Err(format!(
                "tet {t} joins fragments {} and {}, but there are {nf}",
                self.creator[t], self.destroyer[t]
            ));
        }
        let key = |t: usize| (self.creator[t].0 as u64) << 32 | self.destroyer[t].0 as u64;
        let mut order: Vec<u32> = (0..nt as u32).collect();
        // Mostly sorted (only edited tets moved): the stable merge sort runs in near-linear
        // time on such input.
        order.sort_by_key(|&t| key(t as usize));
        let mut arc_start = Vec::new();
        let mut arc_creator = Vec::new();
        let mut arc_destroyer = Vec::new();
        let mut prev = u64::MAX;
        for (i, &t) in order.iter().enumerate() {
            let k = key(t as usize);
            if k != prev {
                arc_start.push(i as u32);
                arc_creator.push(self.creator[t as usize]);
                arc_destroyer.push(self.destroyer[t as usize]);
                prev = k;
            }
        }
        arc_start.push(nt as u32);
        let sorted = order.windows(2).all(|w| w[0] < w[1]);
        let (tets, cell_data) = if sorted {
            (self.tets, self.cell_data)
        } else {
            let keep: Vec<usize> = order.iter().map(|&t| t as usize).collect();
            (
                keep.iter().map(|&t| self.tets[t]).collect(),
                self.cell_data.select(&keep),
            )
        };
        Mt::assemble(MtParts {
            positions: self.positions,
            point_data: self.point_data,
            tets,
            cell_data,
            arc_start,
            arc_creator,
            arc_destroyer,
            kind: self.kind,
            error: self.error,
            info: self.info,
        })
    }
}
