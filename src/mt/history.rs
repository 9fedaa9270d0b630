//! What the cuts of an MT leave for later cuts to read, kept with the MT (in [`MtInfo`],
//! saved in the `.mt` file) so that a cut made by a new cutter — after the MT was saved and
//! loaded, handed through the C ABI, or split into components — decides as the cutter that
//! made the earlier cuts would have.
//!
//! This layer only stores, checks and renumbers the record; the cut layer
//! (`crate::cut::mt_cut`) writes and reads it: the length each vertex's tolerances are
//! measured by (derived again from a cut finest mesh it would differ near the cracks),
//! which vertices cuts appended (all lie on cracks), the plane of every crack made at rest
//! (a cut close to one is made in it), and, for the last few cuts (at rest or at the
//! deformed positions they were made at), the polygon and what each appended vertex is (a
//! tip, a lip of either side, a copy where two cracks meet) and the tips of earlier cracks
//! the cut took onto its own — what a cut continuing one of them at an angle (a turning or
//! tilting scalpel, paper §5) needs.
//!
//! [`MtInfo`]: super::MtInfo

use crate::geom::{CutPolygon, DVec3, lies_in_plane};
use crate::mesh::VertexId;

/// The cut record of an MT (see the [module docs](self)).
#[derive(Clone, Debug, PartialEq)]
pub struct CutHistory {
    /// Vertices from this id on were appended by cuts: every one lies on a crack.
    pub(crate) cut_vertices_from: u32,
    /// The last cuts, oldest first (at most [`Made::RECENT`]).
    pub(crate) made: Made,
    /// Per vertex, the length a cut measures its tolerances by (the cut layer's vertex
    /// scales): set when the MT is first prepared for cutting, extended by each cut; empty
    /// before (derived from the finest mesh then).
    pub(crate) scales: Vec<f64>,
}

/// The last cuts of an MT, oldest first: what a later cut that continues one at
/// an angle reads (the cut layer's `TurnTips`); and the planes of all the cuts at rest
/// that made a crack, each once: a later cut close to one of them is made in it (the cut
/// layer's `snap_to_plane`), however many cuts came between. A deformed body's cuts are
/// kept with their frame (their polygons lie in the deformed space): only a cut in the
/// same frame continues one of those at an angle; their planes are not kept.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Made {
    pub(crate) cuts: Vec<MadeBy>,
    /// Unit normal and a point of each plane, in the order the cuts first met them.
    pub(crate) planes: Vec<[DVec3; 2]>,
}

/// One cut: its polygon (in the frame it was made in) and the vertices it appended.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct MadeBy {
    pub(crate) polygon: CutPolygon,
    /// The first vertex the cut appended, and the kind of each (a byte per vertex: one of
    /// the cut layer's kinds, below [`KINDS`]).
    pub(crate) first: u32,
    pub(crate) kinds: Vec<u8>,
    /// The frame the cut was made in: 0 at rest, else a fingerprint of the deformed
    /// positions of the vertices before it (a later cut in the same frame may continue it
    /// at an angle).
    pub(crate) frame: u64,
    /// The tips of earlier cuts this cut took onto its crack, sorted.
    pub(crate) taken: Vec<VertexId>,
}

/// How many kinds of appended vertex the record distinguishes.
pub(crate) const KINDS: u8 = 4;

impl Made {
    /// How many of the last cuts are kept: a cut is checked for continuing one of these at
    /// an angle (a blade's step continues the step before it; a tilting blade's second
    /// triangle, the first).
    pub(crate) const RECENT: usize = 8;

    /// Keeps the plane of `polygon`, a crack's, unless the polygon lies in a plane kept.
    pub(crate) fn keep_plane(&mut self, polygon: &CutPolygon) {
        if !lies_in_plane(polygon, self.planes.iter().map(|&[n, p]| (n, p))) {
            let plane = polygon.plane();
            self.planes.push([plane.normal, plane.points[0]]);
        }
    }
}

impl CutHistory {
    /// The record of an MT no cut has changed, with `nb_vertices` vertices.
    pub(crate) fn new(nb_vertices: usize) -> CutHistory {
        CutHistory {
            cut_vertices_from: nb_vertices as u32,
            made: Made::default(),
            scales: Vec::new(),
        }
    }

    /// How many cuts the record describes (the last ones; at most 8).
    pub fn cuts_kept(&self) -> usize {
        self.made.cuts.len()
    }

    /// How many planes the record keeps (those of every cut at rest that made a crack,
    /// each once).
    pub fn planes_kept(&self) -> usize {
        self.made.planes.len()
    }

    /// The first vertex appended by a cut (every vertex from it on lies on a crack; the
    /// vertex count when none has).
    pub fn cut_vertices_from(&self) -> usize {
        self.cut_vertices_from as usize
    }

    /// The vertex scales recorded (see the field's docs; empty before the MT was first
    /// prepared for cutting).
    pub fn vertex_scales(&self) -> &[f64] {
        &self.scales
    }

    /// What is inconsistent with a pool of `nb_vertices` vertices: what a file that passed
    /// its checksum but was written wrong would hold.
    pub(crate) fn check(&self, nb_vertices: usize) -> Result<(), String> {
        if !self.scales.is_empty() && self.scales.len() != nb_vertices {
            return Err(format!(
                "cut record: {} vertex scales for {nb_vertices} vertices",
                self.scales.len()
            ));
        }
        if let Some(v) = self
            .scales
            .iter()
            .position(|s| !(s.is_finite() && *s >= 0.0))
        {
            return Err(format!(
                "cut record: vertex {v} has scale {}, not a finite length",
                self.scales[v]
            ));
        }
        for (i, [n, p]) in self.made.planes.iter().enumerate() {
            if !(n.is_finite() && p.is_finite() && (n.length() - 1.0).abs() <= 1e-9) {
                return Err(format!(
                    "cut record: plane {i} (normal {n}, point {p}) has no finite unit normal \
                     and finite point"
                ));
            }
        }
        let nv = nb_vertices as u64;
        if u64::from(self.cut_vertices_from) > nv {
            return Err(format!(
                "cut record: vertices from {} made by cuts, but the pool has {nv}",
                self.cut_vertices_from
            ));
        }
        if self.made.cuts.len() > Made::RECENT {
            return Err(format!(
                "cut record: {} cuts, more than the {} kept",
                self.made.cuts.len(),
                Made::RECENT
            ));
        }
        let mut end = u64::from(self.cut_vertices_from);
        for (i, c) in self.made.cuts.iter().enumerate() {
            let first = u64::from(c.first);
            if first < end || first + c.kinds.len() as u64 > nv {
                return Err(format!(
                    "cut record: cut {i} appended vertices {first}..{}, not after {end} and \
                     within the {nv} of the pool",
                    first + c.kinds.len() as u64
                ));
            }
            end = first + c.kinds.len() as u64;
            if let Some(k) = c.kinds.iter().find(|&&k| k >= KINDS) {
                return Err(format!(
                    "cut record: cut {i} has a vertex of unknown kind {k}"
                ));
            }
            if c.taken.windows(2).any(|w| w[0] >= w[1]) {
                return Err(format!("cut record: cut {i}'s taken tips are not sorted"));
            }
            if let Some(v) = c.taken.iter().find(|v| u64::from(v.0) >= first) {
                return Err(format!(
                    "cut record: cut {i} took vertex {v}, not made before it"
                ));
            }
        }
        Ok(())
    }

    /// The record of the MT made of the vertices `new_id` keeps (`new_id[v]`: the new id of
    /// vertex `v`, increasing over the kept ones; `u32::MAX`: dropped), as
    /// [`Mt::component`](super::Mt::component) renumbers them. A cut's kept vertices stay
    /// consecutive (no kept vertex lies between them); a cut none of whose vertices is kept
    /// is dropped. The planes are all kept (they name no vertex: a cut of this part close
    /// to the plane of a crack left in another part is moved onto it, by at most
    /// [`PLANE_SNAP`](crate::geom::PLANE_SNAP) of the diagonal, as before the split).
    pub(crate) fn renumbered(&self, new_id: &[u32]) -> CutHistory {
        let kept = |v: usize| new_id[v] != u32::MAX;
        let from = self.cut_vertices_from as usize;
        let cut_vertices_from = (0..from).filter(|&v| kept(v)).count() as u32;
        let cuts = self.made.cuts.iter().filter_map(|c| {
            let range = c.first as usize..c.first as usize + c.kinds.len();
            let first = range.clone().find(|&v| kept(v))?;
            Some(MadeBy {
                polygon: c.polygon.clone(),
                frame: c.frame,
                first: new_id[first],
                kinds: range
                    .filter(|&v| kept(v))
                    .map(|v| c.kinds[v - c.first as usize])
                    .collect(),
                taken: c
                    .taken
                    .iter()
                    .filter(|v| kept(v.idx()))
                    .map(|v| VertexId(new_id[v.idx()]))
                    .collect(),
            })
        });
        let scales = match self.scales.is_empty() {
            true => Vec::new(),
            false => (0..new_id.len())
                .filter(|&v| kept(v))
                .map(|v| self.scales[v])
                .collect(),
        };
        CutHistory {
            cut_vertices_from,
            made: Made {
                cuts: cuts.collect(),
                planes: self.made.planes.clone(),
            },
            scales,
        }
    }

    /// Heap bytes held.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.scales.capacity() * 8
            + self.made.planes.capacity() * std::mem::size_of::<[DVec3; 2]>()
            + self
                .made
                .cuts
                .iter()
                .map(|c| {
                    // A polygon holds its points, their edges' inward normals and offsets.
                    std::mem::size_of::<MadeBy>()
                        + c.polygon.points().len() * (24 + 24 + 8)
                        + c.kinds.capacity()
                        + c.taken.capacity() * 4
                })
                .sum::<usize>()
    }
}

impl super::Mt {
    /// The cut record, for the cut layer to read and extend.
    pub(crate) fn cut_history_mut(&mut self) -> &mut CutHistory {
        &mut self.info.cuts
    }
}
