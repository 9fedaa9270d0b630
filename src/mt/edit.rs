//! Editing an MT in place: the open form that cuts modify, and the sub-MTs (independent
//! components) a cut straight through leaves in one store.
//!
//! An [`OpenMt`] is the store with one creator and one destroyer *per tet* instead of
//! contiguous arcs: tets can then be replaced in place, appended, and relabelled freely
//! (the paper's expanded arcs, §3). [`OpenMt::close`] sorts the pool back into arcs and
//! assembles the MT, deriving levels, boxes and arc lists with the same code as a build or
//! a load, so an edit cannot leave them inconsistent. Three exceptions keep the cost of a
//! small edit of a large MT near the size of the edit: the sort is a merge in place when
//! little moved (the creators and destroyers change only through
//! [`OpenMt::set_creator`] and [`OpenMt::set_destroyer`], which list the tets they
//! relabel, so the tets not listed are still in the opened MT's arc order and are not
//! read); an editor that lists the fragments whose box it may have changed
//! ([`OpenMt::changed_fragments`]) keeps the others' boxes, save those that a tet it
//! wrote reaches out of (a new point rounded past them) — the cut does; `Mt::validate`
//! checks every box; and when the arcs come back joining the same fragments as when
//! opened (an edit that adds no fragment and only moves tets into arcs the MT had), the
//! arcs' ranges are updated from the moved tets alone and the DAG's tables are the opened
//! MT's (`Mt::validate` derives levels again and compares). Appended vertices and tets need
//! attribute rows; the editor pushes them (interpolated for vertices, inherited for tets,
//! zeros for ghosts).
//!
//! This module knows nothing of cuts: the cut layer (`crate::cut::mt`) decides what to
//! change.

use super::{BoxFrame, FragmentKind, GHOST, KnownBoxes, KnownDag, Mt, MtInfo, MtParts, QuantBox};
use crate::geom::DVec3;
use crate::mesh::{Attributes, FragmentId, Tet, TetId, VertexId};
use rayon::prelude::*;

/// An MT opened for editing (see the [module docs](self)).
#[derive(Clone, Debug)]
pub struct OpenMt {
    pub positions: Vec<DVec3>,
    pub point_data: Attributes,
    /// Every tet of every level, ghosts included.
    pub tets: Vec<Tet>,
    pub cell_data: Attributes,
    /// Creator and destroyer of each tet: read with [`creator`](Self::creator) and
    /// [`destroyer`](Self::destroyer), changed only through the setters, which list the
    /// tets they relabel (`Opened::relabelled`).
    creator: Vec<FragmentId>,
    destroyer: Vec<FragmentId>,
    pub kind: Vec<FragmentKind>,
    pub error: Vec<f64>,
    pub info: MtInfo,
    /// Fragments whose box an edit may have changed, when the editor keeps count (`None`:
    /// unknown, every fragment box is derived again when closing). Fragments added count
    /// without being listed; any other fragment keeps the box it had when opened, so an
    /// editor that lists fragments must list every one whose floor and ceiling no longer
    /// span the same box (`Mt::validate` compares every box with its tets). Replacing a tet
    /// by tets that tile it, as a cut does, keeps the box: each corner of the tet is a
    /// corner of one of them.
    pub changed_fragments: Option<Vec<u32>>,
    /// Tets of the opened MT's pool an edit wrote in place (their indices when opened), when
    /// the editor keeps count (`None`: unknown). Closing checks that every tet names
    /// vertices of the pool: only these and the tets appended when listed (the others
    /// were checked when the opened MT was assembled), else every tet of the pool — a
    /// pass over it that costs a large MT's small edit more than the edit (27 ms for 3.8 M
    /// tets, measured on a cut of the fandisk-1m MT).
    pub written_tets: Option<Vec<u32>>,
    opened: Opened,
}

/// What an [`OpenMt`] knows of the MT it was opened from: nothing for one made of parts
/// (closing then sorts the whole pool and derives everything).
#[derive(Clone, Debug, Default)]
struct Opened {
    /// How many leading tets were in arc order when the MT was opened (0: unknown).
    sorted: usize,
    /// Every tet below `sorted` whose creator or destroyer was set since opening (repeats
    /// allowed): the tets not listed are where the opened MT's arcs had them.
    relabelled: Vec<u32>,
    /// The fragment boxes when opened, and the pool's vertex count then.
    boxes: Option<(BoxFrame, Vec<QuantBox>, usize)>,
    /// The DAG tables when opened (kept if the arcs are).
    dag: Option<KnownDag>,
    /// The arcs' tet ranges when opened (`arc_start`), updated in place by a close that
    /// keeps the arcs.
    arcs: Option<Vec<u32>>,
}

/// The room an edit of a pool of `n` elements is given to append to it: an eighth more.
pub(crate) fn edit_room(n: usize) -> usize {
    n / 8 + 1024
}

/// The creator and destroyer of every pool tet of an MT, in pool order: what [`Mt::open`]
/// derives from the arcs, kept by an editor that edits the same MT again
/// ([`OpenMt::close_keeping_links`], [`Mt::open_with`]) so that opening it costs nothing.
#[derive(Clone)]
pub(crate) struct TetLinks {
    creator: Vec<FragmentId>,
    destroyer: Vec<FragmentId>,
}

impl Mt {
    /// The creator and destroyer of every pool tet, derived from the arcs, for
    /// [`open_with`](Self::open_with): an editor that derives them before its first edit
    /// (when it is made) keeps that edit in proportion to its size.
    pub(crate) fn tet_links(&self) -> TetLinks {
        let nt = self.nb_tets();
        // Written once, run by run, with room for the tets an edit appends (a cut appends a
        // few per tet it splits) so appending does not copy them.
        let room = nt + edit_room(nt);
        let mut creator = Vec::with_capacity(room);
        let mut destroyer = Vec::with_capacity(room);
        for (a, c, d) in self.arcs() {
            let n = self.arc_tets(a).len();
            creator.extend(std::iter::repeat_n(c, n));
            destroyer.extend(std::iter::repeat_n(d, n));
        }
        TetLinks { creator, destroyer }
    }

    /// Makes room in the pool for the tets and vertices an edit appends
    /// ([`edit_room`] of each), so that the first edit does not copy the pool to a larger
    /// one ([`OpenMt::close`] keeps the room for the next).
    pub(crate) fn reserve_edit_room(&mut self) {
        let (nt, nv) = (self.nb_tets(), self.nb_vertices());
        self.tets.reserve(edit_room(nt));
        self.cell_data.reserve(edit_room(nt));
        self.positions.reserve(edit_room(nv));
        self.point_data.reserve(edit_room(nv));
    }

    /// The open form of this MT (per-tet creator and destroyer).
    pub fn open(self) -> OpenMt {
        self.open_with(None)
    }

    /// [`open`](Self::open), taking the per-tet creators and destroyers from `links`: they
    /// must be those [`OpenMt::close_keeping_links`] returned with this very MT (checked
    /// against the arcs in debug builds; links of another length are not used).
    pub(crate) fn open_with(self, links: Option<TetLinks>) -> OpenMt {
        let nt = self.nb_tets();
        let nv = self.positions.len();
        let TetLinks { creator, destroyer } = match links {
            Some(l) if l.creator.len() == nt && l.destroyer.len() == nt => {
                debug_assert!(
                    self.arcs().all(|(a, c, d)| {
                        let r = self.arc_tets(a);
                        l.creator[r.clone()].iter().all(|&x| x == c)
                            && l.destroyer[r].iter().all(|&x| x == d)
                    }),
                    "links kept from another MT"
                );
                l
            }
            _ => self.tet_links(),
        };
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
            changed_fragments: None,
            written_tets: None,
            opened: Opened {
                sorted: nt,
                relabelled: Vec::new(),
                boxes: Some((self.frame, self.bbox, nv)),
                dag: Some(KnownDag {
                    out_start: self.out_start,
                    arc_destroyer: self.arc_destroyer,
                    preds: self.preds,
                    level: self.level,
                }),
                arcs: Some(self.arc_start),
            },
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
            info: MtInfo {
                cuts: self.info.cuts.renumbered(&new_v),
                ..self.info.clone()
            },
            changed_fragments: None,
            written_tets: None,
            opened: Opened::default(),
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
    /// The creator of each tet, in pool order.
    pub fn creator(&self) -> &[FragmentId] {
        &self.creator
    }

    /// The destroyer of each tet, in pool order.
    pub fn destroyer(&self) -> &[FragmentId] {
        &self.destroyer
    }

    /// Makes fragment `f` the creator of tet `t` (panics when `t` is not a tet).
    pub fn set_creator(&mut self, t: usize, f: FragmentId) {
        self.creator[t] = f;
        self.note_relabelled(t);
    }

    /// Makes fragment `f` the destroyer of tet `t` (panics when `t` is not a tet).
    pub fn set_destroyer(&mut self, t: usize, f: FragmentId) {
        self.destroyer[t] = f;
        self.note_relabelled(t);
    }

    fn note_relabelled(&mut self, t: usize) {
        if t < self.opened.sorted {
            self.opened.relabelled.push(t as u32);
        }
    }

    /// The tets below the opened MT's pool length whose creator or destroyer was set since
    /// it was opened (repeats allowed; the others are where its arcs had them).
    pub(crate) fn relabelled(&self) -> &[u32] {
        &self.opened.relabelled
    }

    /// Appends `tet`, created by `creator` and destroyed by `destroyer` (its attribute
    /// rows are the caller's to push).
    pub fn push_tet(&mut self, tet: Tet, creator: FragmentId, destroyer: FragmentId) {
        self.tets.push(tet);
        self.creator.push(creator);
        self.destroyer.push(destroyer);
    }

    /// Drops the tets from `n` on, with their creators, destroyers and attribute rows.
    pub fn truncate_tets(&mut self, n: usize) {
        self.tets.truncate(n);
        self.creator.truncate(n);
        self.destroyer.truncate(n);
        self.cell_data.truncate(n);
    }

    /// The DAG tables of the MT this was opened from (successors by `out_start` and
    /// `arc_destroyer`, levels), lent to an editor that reads the DAG as it was before the
    /// edit; [`restore_dag`](Self::restore_dag) gives them back for [`close`](Self::close)
    /// to reuse (else they are derived again). `None` for an MT not opened from one.
    pub(crate) fn take_dag(&mut self) -> Option<KnownDag> {
        self.opened.dag.take()
    }

    pub(crate) fn restore_dag(&mut self, dag: KnownDag) {
        self.opened.dag = Some(dag);
    }

    /// Sorts the pool into arcs (by creator, then destroyer, then current position: stable)
    /// and assembles the MT. An edit of a small part of an opened MT is reordered in place
    /// (see `Merge`). Errors say what is inconsistent (an editing bug).
    pub fn close(self) -> Result<Mt, String> {
        self.close_keeping_links().map(|(mt, _)| mt)
    }

    /// [`close`](Self::close), returning also the creator and destroyer of each tet of the
    /// closed MT, for [`Mt::open_with`].
    pub(crate) fn close_keeping_links(self) -> Result<(Mt, TetLinks), String> {
        let nt = self.tets.len();
        if self.creator.len() != nt || self.destroyer.len() != nt {
            return Err(format!(
                "{nt} tets with {} creators and {} destroyers",
                self.creator.len(),
                self.destroyer.len()
            ));
        }
        // Fragment ids out of range are found per arc by `Mt::assemble` (every tet's
        // creator and destroyer make an arc): sorting does not index with them.
        if let Some(c) = self.cell_data.mismatched(nt) {
            return Err(format!(
                "{nt} tets with {} values of cell data {:?} in {} components",
                c.values.len(),
                c.name,
                c.components
            ));
        }
        let mut this = self;
        // Vertex ids checked here, before the pool is reordered, when the editor listed
        // the tets it wrote; else by `Mt::assemble`, over the whole pool.
        let written = this.written_tets.take();
        if let Some(written) = &written {
            let nv = this.positions.len();
            let opened = this.opened.sorted.min(nt);
            let tets = &this.tets;
            let listed = written.iter().map(|&t| t as usize).filter(|&t| t < opened);
            if let Some((t, v)) = listed
                .chain(opened..nt)
                .find_map(|t| super::bad_vertex(&tets[t], nv).map(|v| (t, v)))
            {
                return Err(format!("tet {t} uses vertex {v}, but the pool has {nv}"));
            }
        }
        let known_boxes = match (this.opened.boxes.take(), this.changed_fragments.take()) {
            (Some((frame, boxes, nv)), Some(listed)) => {
                let mut changed = vec![false; boxes.len()];
                for f in listed {
                    if let Some(c) = changed.get_mut(f as usize) {
                        *c = true;
                    }
                }
                Some((
                    KnownBoxes {
                        frame,
                        boxes,
                        changed,
                    },
                    nv,
                ))
            }
            _ => None,
        };
        // The editor lists the fragments whose tets it moved or split; but a vertex it
        // added can round an ulp beyond the points it combines (a face point past its
        // face's box), past the kept box of a fragment it did not list: the added vertices
        // of the tets written or appended are checked against their fragments' kept boxes
        // (the older ones are corners of the tets they replace, inside already; without
        // the list of tets written, every box is derived).
        let known_boxes = known_boxes
            .zip(written.as_ref())
            .map(|((mut k, nv), written)| {
                let opened = this.opened.sorted.min(nt);
                let written = written.iter().map(|&t| t as usize).filter(|&t| t < opened);
                for t in written.chain(opened..nt) {
                    for f in [this.creator[t].idx(), this.destroyer[t].idx()] {
                        if f >= k.boxes.len() || k.changed[f] {
                            continue;
                        }
                        // Exactly `enclose(p) ⊆ box`: the box decoded with `enclose`'s arithmetic.
                        let b = k.frame.expand(k.boxes[f]);
                        let inside = |v: &VertexId| {
                            let p = this.positions[v.idx()];
                            p.cmpge(b.min).all() && p.cmple(b.max).all()
                        };
                        let mut added = this.tets[t]
                            .iter()
                            .filter(|v| **v != GHOST && v.idx() >= nv);
                        if !added.all(inside) {
                            k.changed[f] = true;
                        }
                    }
                }
                k
            });
        let merge = Merge::plan(
            &this.creator,
            &this.destroyer,
            this.opened.sorted,
            &this.opened.relabelled,
            this.opened.dag.as_ref().zip(this.opened.arcs.as_deref()),
        );
        // No fragment added, every moved tet joining an arc the opened MT had, none
        // emptied: the same arcs, their ranges updated from the moved tets alone (checked
        // below).
        let kept_starts = match (&merge, &this.opened.dag, this.opened.arcs.take()) {
            (Some(m), Some(dag), Some(starts)) if dag.level.len() == this.kind.len() => m
                .kept_arcs(
                    &this.creator,
                    &this.destroyer,
                    this.opened.sorted,
                    dag,
                    starts,
                ),
            _ => None,
        };
        let (tets, cell_data, creator, destroyer) = match merge {
            Some(m) => {
                // Most of the pool is in place: reorder in place, the columns on both cores,
                // as many bytes per tet on each (each is a pass over memory, and a pool of
                // millions of tets moves at the memory's pace): the tets on one, the links
                // on the other, each cell column where fewer bytes are moved so far.
                let (tets, creator, destroyer) =
                    (&mut this.tets, &mut this.creator, &mut this.destroyer);
                let (mut one, mut other) = (Vec::new(), Vec::new());
                let mut bytes = [size_of::<Tet>(), 2 * size_of::<FragmentId>()];
                for c in this.cell_data.iter_mut() {
                    let side = usize::from(bytes[1] < bytes[0]);
                    bytes[side] += c.components * size_of::<f64>();
                    [&mut one, &mut other][side].push(c);
                }
                rayon::join(
                    || {
                        m.apply(tets, 1);
                        for c in one {
                            m.apply(&mut c.values, c.components);
                        }
                    },
                    || {
                        m.apply(creator, 1);
                        m.apply(destroyer, 1);
                        for c in other {
                            m.apply(&mut c.values, c.components);
                        }
                    },
                );
                (this.tets, this.cell_data, this.creator, this.destroyer)
            }
            None => {
                // The stable sort by arc, as a sort by (arc, index): each key computed once,
                // sorted and gathered on both cores (a cut separating fandisk's MT relabels
                // most of its pool of about 0.2 M tets: this branch 13 -> 9 ms). A merge
                // sort, which follows the runs of the pool still in order: an unstable one
                // took 9 ms on the cut of Table 2's 0.3 square, against 5.5 before and 6
                // with this one.
                let key = |t: usize| arc_key(&this.creator, &this.destroyer, t);
                let mut order: Vec<(u64, u32)> = (0..nt)
                    .into_par_iter()
                    .map(|t| (key(t), t as u32))
                    .collect();
                order.par_sort();
                let keep: Vec<usize> = order.iter().map(|&(_, t)| t as usize).collect();
                let ((tets, cell_data), (creator, destroyer)) = rayon::join(
                    || {
                        (
                            keep.iter().map(|&t| this.tets[t]).collect(),
                            this.cell_data.select(&keep),
                        )
                    },
                    || {
                        (
                            keep.iter().map(|&t| this.creator[t]).collect(),
                            keep.iter().map(|&t| this.destroyer[t]).collect(),
                        )
                    },
                );
                (tets, cell_data, creator, destroyer)
            }
        };
        debug_assert!(
            kept_starts
                .as_ref()
                .is_none_or(|s| *s == arcs_of(&creator, &destroyer).0),
            "arc ranges updated from the moved tets differ from the pool's"
        );
        let arcs_kept = kept_starts.is_some();
        let (arc_start, arc_creator, arc_destroyer) = match kept_starts {
            Some(starts) => (starts, Vec::new(), Vec::new()),
            None => arcs_of(&creator, &destroyer),
        };
        let OpenMt {
            positions,
            point_data,
            kind,
            error,
            info,
            opened,
            ..
        } = this;
        let links = TetLinks { creator, destroyer };
        Mt::assemble(MtParts {
            positions,
            point_data,
            tets,
            cell_data,
            arc_start,
            arc_creator,
            arc_destroyer,
            kind,
            error,
            info,
            known_boxes,
            keep_room: true,
            kept_arcs: opened.dag.filter(|_| arcs_kept),
            vertex_ids_checked: written.is_some(),
        })
        .map(|mt| (mt, links))
    }
}

/// The arcs of a pool in arc order, as (starts with one extra entry, creators,
/// destroyers): an arc starts where a tet's (creator, destroyer) differs from the one
/// before it. Found in blocks on both cores (a pass over every tet of the pool).
fn arcs_of(
    creator: &[FragmentId],
    destroyer: &[FragmentId],
) -> (Vec<u32>, Vec<FragmentId>, Vec<FragmentId>) {
    let nt = creator.len();
    let mut arc_start: Vec<u32> = (0..nt)
        .into_par_iter()
        .with_min_len(1 << 14)
        .filter(|&t| t == 0 || (creator[t], destroyer[t]) != (creator[t - 1], destroyer[t - 1]))
        .map(|t| t as u32)
        .collect();
    let arc_creator: Vec<FragmentId> = arc_start.par_iter().map(|&t| creator[t as usize]).collect();
    let arc_destroyer: Vec<FragmentId> = arc_start
        .par_iter()
        .map(|&t| destroyer[t as usize])
        .collect();
    arc_start.push(nt as u32);
    (arc_start, arc_creator, arc_destroyer)
}

/// A tet's arc, as one sortable number: creator, then destroyer.
#[inline]
fn arc_key(creator: &[FragmentId], destroyer: &[FragmentId], t: usize) -> u64 {
    arc_of(creator[t], destroyer[t])
}

/// An arc, as one sortable number: creator, then destroyer.
#[inline]
fn arc_of(creator: FragmentId, destroyer: FragmentId) -> u64 {
    (creator.0 as u64) << 32 | destroyer.0 as u64
}

/// Whether `starts` can be the ranges of `dag`'s arcs over a pool whose first `sorted`
/// tets are in arc order (one more than the arcs, the last at `sorted`).
fn ranges_fit(dag: &KnownDag, starts: &[u32], sorted: usize) -> bool {
    let na = dag.arc_destroyer.len();
    starts.len() == na + 1 && starts[na] as usize == sorted
}

/// The arc of `dag` from fragment `creator` to `destroyer`, or where it would be: the first
/// arc not before it in (creator, destroyer) order, and whether it is that arc.
fn arc_at(dag: &KnownDag, creator: usize, destroyer: FragmentId) -> (usize, bool) {
    match dag.out_start.get(creator..creator + 2) {
        Some(&[lo, hi]) => {
            let of_c = &dag.arc_destroyer[lo as usize..hi as usize];
            let i = of_c.partition_point(|&g| g < destroyer);
            (lo as usize + i, of_c.get(i) == Some(&destroyer))
        }
        _ => (dag.arc_destroyer.len(), false),
    }
}

/// Moved tets sorted on both cores above this many ([`Merge::plan`]).
const PARALLEL_SORT: usize = 1 << 16;

/// The reordering [`OpenMt::close`] makes when most of the pool is still in arc order
/// (an edit changes a small part of it): the tets an edit may have moved (relabelled, or
/// appended) are sorted alone, and merged in place with the others — still in the opened
/// MT's arc order, as nothing changes a creator or destroyer without listing the tet —
/// each moved tet placed by a search among the others (the others are not read beyond
/// that search: no pass over the pool). The result is the stable sort of the whole pool
/// by arc; each element moves at most twice, and only the moved ones are copied aside (a
/// fresh copy of a pool of millions of tets is mostly page faults).
struct Merge {
    /// The moved tets by index, ascending.
    by_index: Vec<u32>,
    /// The moved tets in their final order (by arc, then index).
    sorted: Vec<u32>,
    /// The final position of each of `sorted` (ascending).
    pos: Vec<u32>,
}

impl Merge {
    /// `None` when most of the pool moved. `relabelled`: every tet below `opened_sorted`
    /// whose creator or destroyer changed (the tets from `opened_sorted` on count as
    /// moved); the tets below it were in arc order when opened. `arcs`: the opened MT's
    /// DAG tables and arc ranges, when known (the moved tets are then placed from them,
    /// without reading the pool).
    fn plan(
        creator: &[FragmentId],
        destroyer: &[FragmentId],
        opened_sorted: usize,
        relabelled: &[u32],
        arcs: Option<(&KnownDag, &[u32])>,
    ) -> Option<Merge> {
        let nt = creator.len();
        let sorted_end = opened_sorted.min(nt);
        let mut by_index: Vec<u32> = relabelled
            .iter()
            .copied()
            .filter(|&t| (t as usize) < sorted_end)
            .collect();
        by_index.sort_unstable();
        by_index.dedup();
        by_index.extend(sorted_end as u32..nt as u32);
        if by_index.len() > nt / 4 {
            return None;
        }
        let key = |t: u32| (arc_key(creator, destroyer, t as usize), t);
        let mut keyed: Vec<(u64, u32)> = by_index.iter().map(|&t| key(t)).collect();
        // On both cores only when there are many: waking the other thread cost more than
        // sorting a cut's few thousand (0.14-0.26 ms against 0.1 on fandisk's MT).
        if keyed.len() > PARALLEL_SORT {
            keyed.par_sort_unstable();
        } else {
            keyed.sort_unstable();
        }
        let moved = by_index.as_slice();
        // Each moved tet goes after the others before it in order: the first of them not
        // before it is found by galloping from where the moved tet before it went, then
        // bisecting (the next run's first tet stands for the moved ones a probe lands on).
        // Debug builds run it always (see below), so check the others' order here.
        let searched = || -> Vec<u32> {
            // The others, as runs between moved tets.
            let mut runs: Vec<(u32, u32)> = Vec::new();
            let mut start = 0u32;
            for end in moved.iter().copied().chain(std::iter::once(nt as u32)) {
                if start < end {
                    runs.push((start, end));
                }
                start = end + 1;
            }
            debug_assert!(
                runs.iter()
                    .all(|&(a, b)| (a + 1..b).all(|t| key(t - 1).0 <= key(t).0))
                    && runs.windows(2).all(|w| key(w[0].1 - 1) <= key(w[1].0)),
                "a tet not listed as relabelled is out of arc order"
            );
            let others_from = |x: (u64, u32), mut lo: u32| -> u32 {
                let first_at = |i: u32| {
                    let r = runs.partition_point(|&(_, e)| e <= i);
                    runs.get(r).map_or(nt as u32, |&(s, _)| s.max(i))
                };
                let before = |i: u32| {
                    let u = first_at(i);
                    (u < nt as u32 && key(u) < x).then_some(u)
                };
                let mut step = 1u32;
                let mut hi = loop {
                    let probe = lo.saturating_add(step).min(nt as u32);
                    match before(probe) {
                        Some(u) => {
                            lo = u + 1;
                            step = step.saturating_mul(2);
                        }
                        _ => break probe,
                    }
                };
                while lo < hi {
                    let mid = lo + (hi - lo) / 2;
                    match before(mid) {
                        // The others from `hi` on are not before `x`: `u < hi`.
                        Some(u) => lo = u + 1,
                        None => hi = mid,
                    }
                }
                lo
            };
            keyed
                .par_chunks(1 << 12)
                .enumerate()
                .flat_map_iter(|(c, chunk)| {
                    let (mut lo, mut moved_before) = (0u32, 0usize);
                    chunk.iter().enumerate().map(move |(j, &x)| {
                        lo = others_from(x, lo);
                        moved_before += moved[moved_before..].partition_point(|&m| m < lo);
                        lo - moved_before as u32 + ((c << 12) + j) as u32
                    })
                })
                .collect()
        };
        // With the opened MT's arcs, each is placed from them instead: a search among
        // the arcs, where the search above reads the pool (millions of tets on a large
        // MT) at random.
        let from_arcs = arcs.filter(|(dag, starts)| ranges_fit(dag, starts, sorted_end));
        let pos: Vec<u32> = match from_arcs {
            Some((dag, starts)) => {
                // Appended tets of one arc (most moved tets, in runs) go to one place.
                let mut last: Option<(u64, u32)> = None;
                let mut place = |x: (u64, u32)| match last {
                    Some((key, p)) if key == x.0 && x.1 as usize >= sorted_end => p,
                    _ => {
                        let p = Self::place(dag, starts, moved, sorted_end, x);
                        last = (x.1 as usize >= sorted_end).then_some((x.0, p));
                        p
                    }
                };
                let placed = keyed.iter().enumerate();
                let pos: Vec<u32> = placed.map(|(j, &x)| place(x) + j as u32).collect();
                debug_assert_eq!(pos, searched(), "moved tets placed from the arcs");
                pos
            }
            None => searched(),
        };
        let sorted: Vec<u32> = keyed.into_iter().map(|(_, t)| t).collect();
        Some(Merge {
            by_index,
            sorted,
            pos,
        })
    }

    /// How many tets not moved go before the moved tet `t` with arc key `x` (the stable
    /// order: by arc, then index), from the opened MT's arcs: those of the arcs before
    /// `x`'s, and of `x`'s those before `t` (all of them when `t` was appended), less
    /// the relabelled ones among them (`moved` below `sorted_end`).
    fn place(
        dag: &KnownDag,
        starts: &[u32],
        moved: &[u32],
        sorted_end: usize,
        x: (u64, u32),
    ) -> u32 {
        let (key, t) = x;
        let (a, same) = arc_at(dag, (key >> 32) as usize, FragmentId(key as u32));
        let (first, end) = (starts[a], if same { starts[a + 1] } else { starts[a] });
        // (`max`, `min`: no panic, as `clamp` would on ranges out of order.)
        let q = if (t as usize) < sorted_end {
            t.max(first).min(end)
        } else {
            end
        };
        q - moved.partition_point(|&m| m < q) as u32
    }

    /// The arcs' tet ranges after this reordering, updated from `starts` (those of the MT
    /// opened, whose arcs `dag` describes; `creator`, `destroyer` before reordering) when
    /// every moved tet joins an arc that MT had and no arc is left empty: the same arcs.
    /// `None` otherwise. Proportional to the moved tets and the arcs after the first one
    /// they change, not to the pool.
    fn kept_arcs(
        &self,
        creator: &[FragmentId],
        destroyer: &[FragmentId],
        opened_sorted: usize,
        dag: &KnownDag,
        mut starts: Vec<u32>,
    ) -> Option<Vec<u32>> {
        let na = dag.arc_destroyer.len();
        if !ranges_fit(dag, &starts, opened_sorted) {
            return None;
        }
        let arc_of = |t: u32| -> Option<u32> {
            let (a, same) = arc_at(dag, creator[t as usize].idx(), destroyer[t as usize]);
            same.then_some(a as u32)
        };
        // Per arc, tets in (+1: moved there) and out (-1: moved from there, when it was
        // in the opened pool), by arc: the moved tets in their final order are in arc
        // order, and so are those moved out, by index in the opened pool.
        let gained = self.sorted.iter().map(|&t| arc_of(t).map(|a| (a, 1)));
        let gained: Vec<(u32, i32)> = gained.collect::<Option<_>>()?;
        let lost = self
            .by_index
            .iter()
            .take_while(|&&t| (t as usize) < opened_sorted)
            .map(|&t| ((starts.partition_point(|&s| s <= t) - 1) as u32, -1));
        let mut delta: Vec<(u32, i32)> = Vec::with_capacity(gained.len() + self.by_index.len());
        let mut gained = gained.into_iter().peekable();
        for l in lost {
            while let Some(g) = gained.next_if(|g| g.0 <= l.0) {
                delta.push(g);
            }
            delta.push(l);
        }
        delta.extend(gained);
        // Arc `a` starts after the tets gained and lost by the arcs before it: the arcs
        // from one changed arc to the next shifted alike, a run at a time (the arcs after
        // the first changed are most of an MT's; with the placing from the arcs, a small
        // cut on fandisk-1m's MT planned its close in 0.4 ms instead of 1.5-2.8).
        let mut shift = 0i64;
        let mut k = 0;
        while k < delta.len() {
            let a = delta[k].0 as usize;
            while k < delta.len() && delta[k].0 as usize == a {
                shift += i64::from(delta[k].1);
                k += 1;
            }
            let next = delta.get(k).map_or(na, |d| d.0 as usize);
            let run = &mut starts[a + 1..=next];
            let fits = |s: &u32| u32::try_from(i64::from(*s) + shift).is_ok();
            if !(run.first().is_none_or(fits) && run.last().is_none_or(fits)) {
                return None;
            }
            // In range at both ends of a non-decreasing run: everywhere.
            let add = shift as u32;
            for s in run {
                *s = s.wrapping_add(add);
            }
        }
        let emptied = delta
            .iter()
            .any(|&(a, _)| starts[a as usize] >= starts[a as usize + 1]);
        (!emptied).then_some(starts)
    }

    /// Reorders `v`, `width` values per tet.
    fn apply<T: Copy>(&self, v: &mut [T], width: usize) {
        let n = v.len() / width;
        let aside: Vec<T> = self
            .sorted
            .iter()
            .flat_map(|&t| {
                v[t as usize * width..(t as usize + 1) * width]
                    .iter()
                    .copied()
            })
            .collect();
        // Close up the others, run by run (each moves left or stays).
        let mut kept = 0usize;
        let mut start = 0usize;
        for end in self
            .by_index
            .iter()
            .map(|&t| t as usize)
            .chain(std::iter::once(n))
        {
            let len = end - start;
            v.copy_within(start * width..end * width, kept * width);
            kept += len;
            start = end + 1;
        }
        // Put the moved ones back from the end, shifting the others right past them.
        let mut out = n;
        for (j, &p) in self.pos.iter().enumerate().rev() {
            let p = p as usize;
            let shift = out - p - 1;
            v.copy_within((kept - shift) * width..kept * width, (p + 1) * width);
            kept -= shift;
            v[p * width..(p + 1) * width].copy_from_slice(&aside[j * width..(j + 1) * width]);
            out = p;
        }
        debug_assert_eq!(kept, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Seeded numbers below `n` (xorshift64).
    fn xorshift(mut seed: u64) -> impl FnMut(u64) -> u64 {
        move |n| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed % n
        }
    }

    /// One round of [`merge_is_the_stable_sort`]: a pool of `n` tets in arc order (`arcs`
    /// distinct creators; ties are common), up to `edits` of them relabelled (listed, some
    /// twice, and now and then to the arc they had) and up to `edits` appended. Whether
    /// the in-place path was taken.
    fn merge_round(
        rand: &mut impl FnMut(u64) -> u64,
        round: usize,
        n: usize,
        arcs: u64,
        edits: usize,
    ) -> bool {
        let mut keys: Vec<(u32, u32)> = (0..n)
            .map(|_| (rand(arcs) as u32, rand(4) as u32))
            .collect();
        keys.sort();
        let mut said: Vec<u32> = Vec::new();
        for _ in 0..rand(1 + edits as u64) {
            let t = rand(n as u64) as usize;
            if round % 7 != 0 {
                keys[t] = (rand(arcs + 2) as u32, rand(8) as u32);
            }
            said.push(t as u32);
            if round % 3 == 0 {
                said.push(t as u32);
            }
        }
        for _ in 0..rand(1 + edits as u64 * 4 / 5) {
            keys.push((rand(arcs + 2) as u32, rand(8) as u32));
        }
        let creator: Vec<FragmentId> = keys.iter().map(|k| FragmentId(k.0)).collect();
        let destroyer: Vec<FragmentId> = keys.iter().map(|k| FragmentId(k.1)).collect();
        let mut expected: Vec<usize> = (0..keys.len()).collect();
        expected.sort_by_key(|&t| keys[t]);
        let Some(m) = Merge::plan(&creator, &destroyer, n, &said, None) else {
            return false;
        };
        let mut ids: Vec<u32> = (0..keys.len() as u32).collect();
        m.apply(&mut ids, 1);
        assert_eq!(ids, expected.iter().map(|&t| t as u32).collect::<Vec<_>>());
        // Several values per tet move together.
        let mut wide: Vec<f64> = (0..keys.len())
            .flat_map(|t| [t as f64, -(t as f64)])
            .collect();
        m.apply(&mut wide, 2);
        let want: Vec<f64> = expected
            .iter()
            .flat_map(|&t| [t as f64, -(t as f64)])
            .collect();
        assert_eq!(wide, want);
        true
    }

    /// The in-place reordering is the stable sort by arc: small pools, and pools large
    /// enough that the placement of the moved tets runs in several blocks.
    #[test]
    fn merge_is_the_stable_sort() {
        let mut rand = xorshift(0x9e37_79b9_7f4a_7c15);
        let merged = (0..300)
            .filter(|&round| {
                let n = 1 + rand(400) as usize;
                merge_round(&mut rand, round, n, 6, n / 8)
            })
            .count();
        assert!(merged > 100, "only {merged} rounds took the in-place path");
        // From a tenth of the pool moved down to a few tets (runs longer than a block).
        let merged = (0..12)
            .filter(|&round| {
                let n = 60_000 + rand(60_000) as usize;
                merge_round(&mut rand, round, n, 2_000, (n / 10) >> round)
            })
            .count();
        assert!(
            merged > 4,
            "only {merged} large rounds took the in-place path"
        );
    }

    /// Creators and destroyers change only through the setters, which list the tets for
    /// closing: an MT opened, relabelled and appended to, then closed, has its pool in arc
    /// order, the same as a full sort of it.
    #[test]
    fn setters_list_what_closing_merges() {
        let mut rand = xorshift(0x5851_f42d_4c95_7f2d);
        let n = 400;
        let mut keys: Vec<(u32, u32)> = (0..n)
            .map(|_| (rand(5) as u32, 5 + rand(3) as u32))
            .collect();
        keys.sort();
        let tet = |t: usize| [VertexId(t as u32); 4];
        let mut open = OpenMt {
            positions: Vec::new(),
            point_data: Attributes::default(),
            tets: (0..n).map(tet).collect(),
            cell_data: Attributes::default(),
            creator: keys.iter().map(|k| FragmentId(k.0)).collect(),
            destroyer: keys.iter().map(|k| FragmentId(k.1)).collect(),
            kind: Vec::new(),
            error: Vec::new(),
            info: MtInfo {
                error_metric: String::new(),
                boundary_tolerance: 0.0,
                preserve_features: false,
                feature_angle_degrees: 0.0,
                input_tets: n,
                cuts: crate::mt::CutHistory::new(0),
            },
            changed_fragments: None,
            written_tets: None,
            opened: Opened {
                sorted: n,
                ..Opened::default()
            },
        };
        for _ in 0..20 {
            let t = rand(n as u64) as usize;
            open.set_creator(t, FragmentId(rand(5) as u32));
            open.set_destroyer(t, FragmentId(5 + rand(3) as u32));
        }
        open.push_tet(tet(n), FragmentId(2), FragmentId(6));
        let mut expected: Vec<usize> = (0..=n).collect();
        expected.sort_by_key(|&t| (open.creator[t], open.destroyer[t]));
        let m = Merge::plan(&open.creator, &open.destroyer, n, open.relabelled(), None)
            .expect("a small edit is merged in place");
        let mut ids: Vec<Tet> = open.tets.clone();
        m.apply(&mut ids, 1);
        assert_eq!(ids, expected.iter().map(|&t| tet(t)).collect::<Vec<_>>());
        open.truncate_tets(n);
        assert_eq!(
            (
                open.tets.len(),
                open.creator().len(),
                open.destroyer().len()
            ),
            (n, n, n)
        );
    }

    /// Arc ranges updated from the moved tets are the arcs a scan of the reordered pool
    /// finds; edits that make a new arc or empty one are not kept.
    #[test]
    fn kept_arcs_are_the_scanned_arcs() {
        let mut rand = xorshift(0x2545_f491_4f6c_dd1d);
        let (mut kept, mut refused) = (0, 0);
        for round in 0..400 {
            let n = 1 + rand(300) as usize;
            let mut keys: Vec<(u32, u32)> = (0..n)
                .map(|_| (rand(6) as u32, 6 + rand(4) as u32))
                .collect();
            keys.sort();
            let ids = |keys: &[(u32, u32)]| -> (Vec<FragmentId>, Vec<FragmentId>) {
                (
                    keys.iter().map(|k| FragmentId(k.0)).collect(),
                    keys.iter().map(|k| FragmentId(k.1)).collect(),
                )
            };
            let (c0, d0) = ids(&keys);
            let (starts, arc_creator, arc_destroyer) = arcs_of(&c0, &d0);
            let nf = 10;
            let mut out_start = vec![0u32; nf + 1];
            for c in &arc_creator {
                out_start[c.idx() + 1] += 1;
            }
            for f in 0..nf {
                out_start[f + 1] += out_start[f];
            }
            let dag = KnownDag {
                out_start,
                arc_destroyer,
                preds: Default::default(),
                level: vec![0; nf],
            };
            // Edits: mostly into arcs the pool has (a new one now and then).
            let existing = keys.clone();
            let pick = |rand: &mut dyn FnMut(u64) -> u64| {
                if rand(10) == 0 {
                    (rand(6) as u32, 6 + rand(4) as u32)
                } else {
                    existing[rand(existing.len() as u64) as usize]
                }
            };
            let mut said: Vec<u32> = Vec::new();
            for _ in 0..rand(1 + n as u64 / 8) {
                let t = rand(n as u64) as usize;
                keys[t] = pick(&mut rand);
                said.push(t as u32);
            }
            for _ in 0..rand(1 + n as u64 / 6) {
                keys.push(pick(&mut rand));
            }
            let (mut creator, mut destroyer) = ids(&keys);
            // Placed from the arcs (debug builds compare with the search of the pool).
            let arcs = Some((&dag, &starts[..]));
            let Some(m) = Merge::plan(&creator, &destroyer, n, &said, arcs) else {
                continue;
            };
            let starts = m.kept_arcs(&creator, &destroyer, n, &dag, starts);
            m.apply(&mut creator, 1);
            m.apply(&mut destroyer, 1);
            keys.sort();
            assert_eq!(
                (creator.clone(), destroyer.clone()),
                ids(&keys),
                "round {round}"
            );
            match starts {
                Some(s) => {
                    kept += 1;
                    let (scanned, sc, sd) = arcs_of(&creator, &destroyer);
                    assert_eq!(s, scanned, "round {round}");
                    assert_eq!(sd, dag.arc_destroyer, "round {round}");
                    assert_eq!(sc.len(), dag.arc_destroyer.len());
                }
                // Ranges are refused only for other arcs.
                None => {
                    refused += 1;
                    let (_, sc, sd) = arcs_of(&creator, &destroyer);
                    let same = sd == dag.arc_destroyer
                        && sc.windows(2).all(|w| w[0] <= w[1])
                        && (0..nf).all(|f| {
                            sc.iter().filter(|c| c.idx() == f).count()
                                == (dag.out_start[f + 1] - dag.out_start[f]) as usize
                        });
                    assert!(!same, "round {round}: the same arcs, not kept");
                }
            }
        }
        assert!(kept > 100 && refused > 20, "kept {kept}, refused {refused}");
    }
}
