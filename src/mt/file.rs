//! The `.mt` file: an MT saved whole, little-endian, versioned and checksummed.
//!
//! ```text
//! offset  size  field
//!      0     8  magic "MTCUTMT\0"
//!      8     4  format version (u32), currently 3 (versions 1 and 2 are read too)
//!     12     4  flags (u32), 0 (reserved)
//!     16     8  payload length in bytes (u64)
//!     24     4  CRC-32 (IEEE 802.3) of the payload (u32)
//!     28     4  reserved (u32), 0
//!     32     …  payload
//! ```
//!
//! Payload, in order (strings are a u32 byte length then UTF-8; counts are u64):
//! build info (error metric name, boundary tolerance f64, preserve-features u8, feature
//! angle f64, input tets u64); counts of vertices, tets, arcs, fragments; positions
//! (3 f64 each); tets (4 u32 each, ghost vertex `u32::MAX - 1`); arc starts (arcs + 1 u32),
//! arc creators, arc destroyers (u32 each); fragment kinds (u8 each: 0 root, 1 collapse,
//! 2 drain) and errors (f64 each); point data then cell data, each a u32 column count then
//! per column its name, its component count (u32) and its values (u64 count, f64 each);
//! then (version 2) the cut record ([`CutHistory`]): the first vertex appended by a cut
//! (u32), the number of cuts kept (u64), and per cut its polygon (u64 point count, 3 f64
//! each), first appended vertex (u32), kinds of its appended vertices (u64 count, a u8
//! each), the tips it took (u64 count, u32 each) and (version 3) the frame it was made in
//! (u64, 0 at rest), then the vertex scales (u64 count, 0 or the vertex count, f64 each);
//! then (version 3) the planes of the cracks made at rest (u64 count, each a unit normal
//! and a point, 6 f64). A version 2 file has its cuts made at rest and takes the planes
//! of those it kept (the last eight); a version 1 file (written before cuts were
//! recorded) loads with an empty record: every vertex as built, none made by a cut.
//!
//! Only primary data is stored; levels, boxes and arc lists are derived on loading by the
//! same code that assembles a freshly built MT, which also checks every index, and the
//! model is then validated whole ([`Mt::validate`]), so a file that passes the checksum
//! but holds no consistent model (written wrong, or edited and sealed again) is rejected
//! with a message instead of giving invalid meshes or failing later. Validating costs
//! about four times the parsing (a model of 1M input tets: 0.27 s to parse, 1.0 s to
//! validate).
//!
//! The checksum is CRC-32 (through `flate2`, already a dependency for compressed VTK
//! output): it detects every burst error up to 32 bits and any other corruption with
//! probability 1 − 2⁻³², which is what a file format needs against truncated copies and
//! flipped bits; it is not a defence against deliberate tampering.

use super::history::{CutHistory, Made, MadeBy};
use super::{FragmentKind, MAX_ELEMENTS, Mt, MtInfo, MtParts};
use crate::geom::{CutPolygon, DVec3};
use crate::mesh::{Attribute, Attributes, FragmentId, Tet, VertexId};
use std::fmt;
use std::path::{Path, PathBuf};

/// First bytes of every `.mt` file.
pub const MT_MAGIC: [u8; 8] = *b"MTCUTMT\0";
/// The format version this library writes; it reads this one and every earlier one.
pub const MT_FILE_VERSION: u32 = 3;
const HEADER: usize = 32;

/// What is wrong with an `.mt` file.
#[derive(Debug, thiserror::Error)]
pub enum MtFileErrorKind {
    #[error("{0}")]
    Os(#[from] std::io::Error),
    #[error("not an mtcut model (wrong magic bytes, in hex {found:02x?})")]
    WrongMagic { found: Vec<u8> },
    #[error(
        "format version {found} is not supported (this library reads versions 1 to {supported})"
    )]
    UnsupportedVersion { found: u32, supported: u32 },
    #[error("truncated: {expected} bytes expected, {found} present")]
    Truncated { expected: u64, found: u64 },
    #[error("{extra} unexpected bytes after the payload")]
    TrailingBytes { extra: u64 },
    #[error(
        "checksum mismatch (stored {stored:08x}, computed {computed:08x}): the file is corrupt"
    )]
    ChecksumMismatch { stored: u32, computed: u32 },
    #[error("corrupt content: {0}")]
    Corrupt(String),
}

/// An `.mt` file error: the path and what is wrong.
#[derive(Debug)]
pub struct MtFileError {
    pub path: PathBuf,
    pub kind: MtFileErrorKind,
}

impl fmt::Display for MtFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.kind)
    }
}

impl std::error::Error for MtFileError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.kind.source()
    }
}

impl Mt {
    /// Writes the MT to `path` (see the [format](self)).
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), MtFileError> {
        let path = path.as_ref();
        crate::io::write_files(&[(path, &self.to_bytes())]).map_err(|(_, e)| MtFileError {
            path: path.to_path_buf(),
            kind: e.into(),
        })
    }

    /// Reads an MT written by [`save`](Self::save).
    pub fn load(path: impl AsRef<Path>) -> Result<Mt, MtFileError> {
        let path = path.as_ref();
        let err = |kind: MtFileErrorKind| MtFileError {
            path: path.to_path_buf(),
            kind,
        };
        let bytes = std::fs::read(path).map_err(|e| err(e.into()))?;
        Mt::from_bytes(&bytes).map_err(err)
    }

    /// The file's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut w = Writer(Vec::with_capacity(self.heap_bytes() + 1024));
        w.string(&self.info.error_metric);
        w.f64(self.info.boundary_tolerance);
        w.0.push(u8::from(self.info.preserve_features));
        w.f64(self.info.feature_angle_degrees);
        w.u64(self.info.input_tets as u64);
        for n in [
            self.nb_vertices(),
            self.nb_tets(),
            self.nb_arcs(),
            self.nb_fragments(),
        ] {
            w.u64(n as u64);
        }
        for p in &self.positions {
            for x in p.to_array() {
                w.f64(x);
            }
        }
        for t in &self.tets {
            for v in t {
                w.u32(v.0);
            }
        }
        for &s in &self.arc_start {
            w.u32(s);
        }
        for (_, c, _) in self.arcs() {
            w.u32(c.0);
        }
        for f in &self.arc_destroyer {
            w.u32(f.0);
        }
        w.0.extend(self.kind.iter().map(|k| k.code()));
        for &e in &self.error {
            w.f64(e);
        }
        for attrs in [&self.point_data, &self.cell_data] {
            w.u32(attrs.iter().count() as u32);
            for c in attrs.iter() {
                w.string(&c.name);
                w.u32(c.components as u32);
                w.u64(c.values.len() as u64);
                for &x in &c.values {
                    w.f64(x);
                }
            }
        }
        let cuts = &self.info.cuts;
        w.u32(cuts.cut_vertices_from);
        w.u64(cuts.made.cuts.len() as u64);
        for c in &cuts.made.cuts {
            w.u64(c.polygon.points().len() as u64);
            for p in c.polygon.points() {
                for x in p.to_array() {
                    w.f64(x);
                }
            }
            w.u32(c.first);
            w.u64(c.kinds.len() as u64);
            w.0.extend_from_slice(&c.kinds);
            w.u64(c.taken.len() as u64);
            for v in &c.taken {
                w.u32(v.0);
            }
            w.u64(c.frame);
        }
        w.u64(cuts.scales.len() as u64);
        for &x in &cuts.scales {
            w.f64(x);
        }
        w.u64(cuts.made.planes.len() as u64);
        for plane in &cuts.made.planes {
            for x in plane.iter().flat_map(|v| v.to_array()) {
                w.f64(x);
            }
        }
        let payload = w.0;
        let mut crc = flate2::Crc::new();
        crc.update(&payload);
        let mut out = Vec::with_capacity(HEADER + payload.len());
        out.extend_from_slice(&MT_MAGIC);
        out.extend_from_slice(&MT_FILE_VERSION.to_le_bytes());
        out.extend_from_slice(&0u32.to_le_bytes());
        out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
        out.extend_from_slice(&crc.sum().to_le_bytes());
        out.extend_from_slice(&0u32.to_le_bytes());
        out.extend_from_slice(&payload);
        out
    }

    /// Parses the bytes of an `.mt` file, checking magic, version, length and checksum
    /// first, then every index.
    pub fn from_bytes(bytes: &[u8]) -> Result<Mt, MtFileErrorKind> {
        if bytes.len() < HEADER {
            if bytes.len() >= 8 && bytes[..8] != MT_MAGIC {
                return Err(MtFileErrorKind::WrongMagic {
                    found: bytes[..8].to_vec(),
                });
            }
            return Err(MtFileErrorKind::Truncated {
                expected: HEADER as u64,
                found: bytes.len() as u64,
            });
        }
        if bytes[..8] != MT_MAGIC {
            return Err(MtFileErrorKind::WrongMagic {
                found: bytes[..8].to_vec(),
            });
        }
        let word = |at: usize| {
            u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
        };
        let version = word(8);
        if !(1..=MT_FILE_VERSION).contains(&version) {
            return Err(MtFileErrorKind::UnsupportedVersion {
                found: version,
                supported: MT_FILE_VERSION,
            });
        }
        let mut len_bytes = [0u8; 8];
        len_bytes.copy_from_slice(&bytes[16..24]);
        let len = u64::from_le_bytes(len_bytes);
        let present = (bytes.len() - HEADER) as u64;
        if present < len {
            return Err(MtFileErrorKind::Truncated {
                expected: HEADER as u64 + len,
                found: bytes.len() as u64,
            });
        }
        if present > len {
            return Err(MtFileErrorKind::TrailingBytes {
                extra: present - len,
            });
        }
        let payload = &bytes[HEADER..];
        let mut crc = flate2::Crc::new();
        crc.update(payload);
        let (stored, computed) = (word(24), crc.sum());
        if stored != computed {
            return Err(MtFileErrorKind::ChecksumMismatch { stored, computed });
        }
        if word(12) != 0 || word(28) != 0 {
            return Err(MtFileErrorKind::Corrupt(
                "reserved header fields are not zero".into(),
            ));
        }
        let mt = parse(payload, version).map_err(MtFileErrorKind::Corrupt)?;
        // A well-sealed file can still hold a model that is not one (written by a faulty
        // tool, or edited and sealed again): every invariant is checked, so that nothing
        // built on a loaded model (extractions, cuts) meets an inconsistent one.
        let report = mt.validate();
        if !report.is_valid() {
            return Err(MtFileErrorKind::Corrupt(format!(
                "the model is not consistent: {report}"
            )));
        }
        Ok(mt)
    }
}

struct Writer(Vec<u8>);

impl Writer {
    fn u32(&mut self, x: u32) {
        self.0.extend_from_slice(&x.to_le_bytes());
    }
    fn u64(&mut self, x: u64) {
        self.0.extend_from_slice(&x.to_le_bytes());
    }
    fn f64(&mut self, x: f64) {
        self.0.extend_from_slice(&x.to_le_bytes());
    }
    fn string(&mut self, s: &str) {
        self.u32(s.len() as u32);
        self.0.extend_from_slice(s.as_bytes());
    }
}

/// A cursor over the payload; every read says what it was reading when the data ran out.
struct Reader<'a> {
    data: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], String> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.data.len());
        match end {
            Some(e) => {
                let s = &self.data[self.at..e];
                self.at = e;
                Ok(s)
            }
            None => Err(format!(
                "payload ends at byte {} while reading {what}",
                self.data.len()
            )),
        }
    }
    fn u8(&mut self, what: &str) -> Result<u8, String> {
        Ok(self.take(1, what)?[0])
    }
    fn u32(&mut self, what: &str) -> Result<u32, String> {
        let b = self.take(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }
    fn u64(&mut self, what: &str) -> Result<u64, String> {
        let mut a = [0u8; 8];
        a.copy_from_slice(self.take(8, what)?);
        Ok(u64::from_le_bytes(a))
    }
    fn f64(&mut self, what: &str) -> Result<f64, String> {
        Ok(f64::from_bits(self.u64(what)?))
    }
    fn string(&mut self, what: &str) -> Result<String, String> {
        let n = self.u32(what)? as usize;
        let b = self.take(n, what)?;
        String::from_utf8(b.to_vec()).map_err(|_| format!("{what} is not UTF-8"))
    }
    /// A count, checked against what the rest of the payload can hold at `bytes_each`.
    fn count(&mut self, what: &str, bytes_each: usize) -> Result<usize, String> {
        let n = self.u64(what)?;
        let room = (self.data.len() - self.at) as u64 / bytes_each.max(1) as u64;
        if n > room || n > MAX_ELEMENTS as u64 {
            return Err(format!("{what} is {n}, more than the file can hold"));
        }
        Ok(n as usize)
    }
    fn u32s(&mut self, n: usize, what: &str) -> Result<Vec<u32>, String> {
        let b = self.take(n.checked_mul(4).ok_or("size overflow")?, what)?;
        Ok(b.chunks_exact(4)
            .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect())
    }
    fn f64s(&mut self, n: usize, what: &str) -> Result<Vec<f64>, String> {
        let b = self.take(n.checked_mul(8).ok_or("size overflow")?, what)?;
        Ok(b.chunks_exact(8)
            .map(|c| {
                let mut a = [0u8; 8];
                a.copy_from_slice(c);
                f64::from_le_bytes(a)
            })
            .collect())
    }
    /// The cut record of a file of `version` (2 or later); its indices are checked with
    /// the rest by [`Mt::assemble`].
    fn cut_history(&mut self, version: u32) -> Result<CutHistory, String> {
        let cut_vertices_from = self.u32("first vertex made by a cut")?;
        let n = self.count("cuts recorded", 40)?;
        let mut cuts = Vec::with_capacity(n.min(Made::RECENT));
        for i in 0..n {
            let np = self.count(&format!("cut {i}'s polygon point count"), 24)?;
            let coords = self.f64s(np * 3, &format!("cut {i}'s polygon"))?;
            let points: Vec<DVec3> = coords
                .chunks_exact(3)
                .map(|c| DVec3::new(c[0], c[1], c[2]))
                .collect();
            let polygon = CutPolygon::new(&points)
                .map_err(|e| format!("cut record: cut {i}'s polygon: {e}"))?;
            let first = self.u32(&format!("cut {i}'s first vertex"))?;
            let nk = self.count(&format!("cut {i}'s vertex count"), 1)?;
            let kinds = self.take(nk, &format!("cut {i}'s vertex kinds"))?.to_vec();
            let nt = self.count(&format!("cut {i}'s taken tip count"), 4)?;
            let taken = self
                .u32s(nt, &format!("cut {i}'s taken tips"))?
                .into_iter()
                .map(VertexId)
                .collect();
            let frame = match version {
                2 => 0,
                _ => self.u64(&format!("cut {i}'s frame"))?,
            };
            cuts.push(MadeBy {
                polygon,
                frame,
                first,
                kinds,
                taken,
            });
        }
        let ns = self.count("vertex scale count", 8)?;
        let scales = self.f64s(ns, "vertex scales")?;
        let mut made = Made {
            cuts,
            planes: Vec::new(),
        };
        match version {
            // Before planes were kept: those of the cuts kept.
            2 => {
                let cuts = std::mem::take(&mut made.cuts);
                for c in &cuts {
                    made.keep_plane(&c.polygon);
                }
                made.cuts = cuts;
            }
            _ => {
                let np = self.count("cut plane count", 48)?;
                made.planes = self
                    .f64s(np * 6, "cut planes")?
                    .chunks_exact(6)
                    .map(|c| [DVec3::new(c[0], c[1], c[2]), DVec3::new(c[3], c[4], c[5])])
                    .collect();
            }
        }
        Ok(CutHistory {
            cut_vertices_from,
            made,
            scales,
        })
    }

    fn attributes(&mut self, what: &str) -> Result<Attributes, String> {
        let n = self.u32(what)?;
        let mut out = Attributes::new();
        for k in 0..n {
            let name = self.string(&format!("{what} column {k} name"))?;
            let comps = self.u32(&format!("{what} '{name}' components"))? as usize;
            let len = self.count(&format!("{what} '{name}' length"), 8)?;
            let values = self.f64s(len, &format!("{what} '{name}' values"))?;
            let col = Attribute::new(name.clone(), comps, values).ok_or_else(|| {
                format!("{what} '{name}': {comps} components do not divide its values")
            })?;
            out.insert(col);
        }
        Ok(out)
    }
}

/// The payload of a file of format `version`.
fn parse(payload: &[u8], version: u32) -> Result<Mt, String> {
    let mut r = Reader {
        data: payload,
        at: 0,
    };
    let mut info = MtInfo {
        error_metric: r.string("error metric name")?,
        boundary_tolerance: r.f64("boundary tolerance")?,
        preserve_features: r.u8("preserve-features flag")? != 0,
        feature_angle_degrees: r.f64("feature angle")?,
        input_tets: r.u64("input tet count")? as usize,
        cuts: CutHistory::new(0),
    };
    let nv = r.count("vertex count", 24)?;
    let nt = r.count("tet count", 16)?;
    let na = r.count("arc count", 12)?;
    let nf = r.count("fragment count", 9)?;
    let coords = r.f64s(nv * 3, "positions")?;
    let positions: Vec<DVec3> = coords
        .chunks_exact(3)
        .map(|c| DVec3::new(c[0], c[1], c[2]))
        .collect();
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(format!("vertex {i} has a NaN or infinite coordinate"));
    }
    let ids = r.u32s(nt * 4, "tets")?;
    let tets: Vec<Tet> = ids
        .chunks_exact(4)
        .map(|c| {
            [
                VertexId(c[0]),
                VertexId(c[1]),
                VertexId(c[2]),
                VertexId(c[3]),
            ]
        })
        .collect();
    let arc_start = r.u32s(na + 1, "arc starts")?;
    let arc_creator: Vec<FragmentId> = r
        .u32s(na, "arc creators")?
        .into_iter()
        .map(FragmentId)
        .collect();
    let arc_destroyer: Vec<FragmentId> = r
        .u32s(na, "arc destroyers")?
        .into_iter()
        .map(FragmentId)
        .collect();
    let kind = r
        .take(nf, "fragment kinds")?
        .iter()
        .enumerate()
        .map(|(f, &c)| {
            FragmentKind::from_code(c).ok_or_else(|| format!("fragment {f} has unknown kind {c}"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let error = r.f64s(nf, "fragment errors")?;
    let point_data = r.attributes("point data")?;
    let cell_data = r.attributes("cell data")?;
    info.cuts = match version {
        1 => CutHistory::new(nv),
        v => r.cut_history(v)?,
    };
    if r.at != payload.len() {
        return Err(format!(
            "{} bytes left over after the {}",
            payload.len() - r.at,
            if version == 1 {
                "cell data"
            } else {
                "cut record"
            }
        ));
    }
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
        known_boxes: None,
        keep_room: false,
        kept_arcs: None,
        vertex_ids_checked: false,
    })
}
