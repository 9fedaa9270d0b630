//! Binary data of VTK XML files: base64 text, the size headers, and compressed blocks.
//!
//! Uncompressed data is `[n bytes][data]`; compressed data is `[nb][nu][np][nc_1..nc_nb]`
//! followed by `nb` blocks, each compressed alone: `nu` bytes per block before compression,
//! `np` for a shorter last block (0 when the last block is full), `nc_i` bytes of block `i`
//! after compression. The header integers are `header_type` wide. Blocks are independent,
//! so both directions run them in parallel (rayon), each into its own slice of the output.
//!
//! Every size in a header is checked against the bytes actually present and against what
//! the array must hold before anything is allocated: damaged input gives a message, never
//! a panic or an absurd allocation.

use super::format::{BLOCK_SIZE, ByteOrder, Compressor, HeaderType};
use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use rayon::prelude::*;
use std::borrow::Cow;
use std::io::Write;

/// How the binary data of a file is laid out (attributes of `VTKFile`).
#[derive(Clone, Copy, Debug)]
pub struct Layout {
    pub header: HeaderType,
    pub order: ByteOrder,
    pub compressor: Compressor,
}

/// Decodes base64 text that may be several streams one after the other, each with its own
/// `=` padding: VTK encodes a compressed array's header and its blocks as two streams.
/// Whitespace (line breaks some writers insert) is ignored.
pub fn decode_base64(text: &[u8]) -> Result<Vec<u8>, String> {
    let compact: Cow<[u8]> = if text.iter().any(u8::is_ascii_whitespace) {
        Cow::Owned(
            text.iter()
                .copied()
                .filter(|c| !c.is_ascii_whitespace())
                .collect(),
        )
    } else {
        Cow::Borrowed(text)
    };
    let mut out = Vec::with_capacity(compact.len() / 4 * 3 + 3);
    let mut start = 0;
    while start < compact.len() {
        let mut end = compact[start..]
            .iter()
            .position(|&c| c == b'=')
            .map_or(compact.len(), |p| start + p);
        while end < compact.len() && compact[end] == b'=' {
            end += 1;
        }
        STANDARD
            .decode_vec(&compact[start..end], &mut out)
            .map_err(|e| {
                format!("invalid base64 in the stream starting at character {start}: {e}")
            })?;
        start = end;
    }
    Ok(out)
}

/// Reads header integer `k` (0-based) of `bytes`; `None` when `bytes` is too short.
fn header_value(bytes: &[u8], k: usize, layout: &Layout) -> Option<u64> {
    let w = layout.header.size();
    let c = bytes.get(k * w..(k + 1) * w)?;
    Some(match (layout.header, layout.order) {
        (HeaderType::U32, ByteOrder::Little) => u32::from_le_bytes(c.try_into().ok()?) as u64,
        (HeaderType::U32, ByteOrder::Big) => u32::from_be_bytes(c.try_into().ok()?) as u64,
        (HeaderType::U64, ByteOrder::Little) => u64::from_le_bytes(c.try_into().ok()?),
        (HeaderType::U64, ByteOrder::Big) => u64::from_be_bytes(c.try_into().ok()?),
    })
}

fn truncated(what: &str, need: u64, have: usize) -> String {
    format!("truncated data: {what} needs {need} bytes, only {have} remain in the file")
}

/// The `expected` bytes of one array whose binary data (size header first) starts at
/// `bytes[0]`; `bytes` may run past the array's end (appended data holds every array).
pub fn read_array<'a>(
    bytes: &'a [u8],
    layout: &Layout,
    expected: usize,
) -> Result<Cow<'a, [u8]>, String> {
    let w = layout.header.size();
    if layout.compressor == Compressor::None {
        let n = header_value(bytes, 0, layout)
            .ok_or_else(|| truncated("the size header", w as u64, bytes.len()))?;
        if n != expected as u64 {
            return Err(format!(
                "the size header says {n} bytes, but the array needs {expected}"
            ));
        }
        return bytes
            .get(w..w + expected)
            .map(Cow::Borrowed)
            .ok_or_else(|| truncated("the array", (w + expected) as u64, bytes.len()));
    }
    let head = |k| {
        header_value(bytes, k, layout)
            .ok_or_else(|| truncated("the compression header", ((k + 1) * w) as u64, bytes.len()))
    };
    let (nb, nu, np) = (head(0)?, head(1)?, head(2)?);
    let total = match (nb, np) {
        (0, _) => Some(0),
        (_, 0) => nb.checked_mul(nu),
        _ => (nb - 1).checked_mul(nu).and_then(|x| x.checked_add(np)),
    };
    if np > nu || total != Some(expected as u64) {
        return Err(format!(
            "the compression header ({nb} blocks of {nu} bytes, last block {np}) does not \
             describe the {expected} bytes the array needs"
        ));
    }
    // Only now is `nb` known to be sane enough to read its block sizes.
    let header_len = (nb as usize)
        .checked_add(3)
        .and_then(|k| k.checked_mul(w))
        .filter(|&l| l <= bytes.len())
        .ok_or_else(|| truncated("the compression header", (nb + 3) * w as u64, bytes.len()))?;
    let mut blocks = Vec::with_capacity(nb as usize);
    let mut at = header_len;
    for k in 0..nb as usize {
        let nc = head(3 + k)? as usize;
        let end = at
            .checked_add(nc)
            .filter(|&e| e <= bytes.len())
            .ok_or_else(|| {
                format!(
                    "truncated data: block {} of {nb} ends past the end of the file",
                    k + 1
                )
            })?;
        let raw = if k + 1 == nb as usize && np != 0 {
            np
        } else {
            nu
        } as usize;
        if raw
            > nc.saturating_mul(layout.compressor.max_ratio())
                .saturating_add(64)
        {
            return Err(format!(
                "block {} of {nb} claims {raw} bytes from {nc} compressed bytes, more than {} \
                 compression can produce: the header is damaged",
                k + 1,
                layout.compressor.label()
            ));
        }
        blocks.push(&bytes[at..end]);
        at = end;
    }
    let mut out = vec![0u8; expected];
    out.par_chunks_mut(nu.max(1) as usize)
        .zip(blocks.par_iter())
        .enumerate()
        .try_for_each(|(k, (dst, src))| {
            decompress_block(layout.compressor, src, dst)
                .map_err(|e| format!("block {} of {nb}: {e}", k + 1))
        })?;
    Ok(Cow::Owned(out))
}

/// Decompresses one block into exactly `out.len()` bytes.
fn decompress_block(c: Compressor, src: &[u8], out: &mut [u8]) -> Result<(), String> {
    let n = out.len();
    let got = match c {
        Compressor::None => {
            out.copy_from_slice(src.get(..n).ok_or("block shorter than its size")?);
            n
        }
        Compressor::Zlib => {
            let mut d = flate2::Decompress::new(true);
            let status = d
                .decompress(src, out, flate2::FlushDecompress::Finish)
                .map_err(|e| format!("zlib decompression failed: {e}"))?;
            if status != flate2::Status::StreamEnd {
                return Err(format!(
                    "zlib decompression failed: the stream does not end after the {n} bytes \
                     the header announces"
                ));
            }
            d.total_out() as usize
        }
        Compressor::Lz4 => lz4_flex::block::decompress_into(src, out)
            .map_err(|e| format!("LZ4 decompression failed: {e}"))?,
        Compressor::Lzma => {
            let mut s = xz2::stream::Stream::new_stream_decoder(u64::MAX, 0)
                .map_err(|e| format!("LZMA decoder: {e}"))?;
            let status = s
                .process(src, out, xz2::stream::Action::Finish)
                .map_err(|e| format!("LZMA decompression failed: {e}"))?;
            if status != xz2::stream::Status::StreamEnd {
                return Err(format!(
                    "LZMA decompression failed: the stream does not end after the {n} bytes \
                     the header announces"
                ));
            }
            s.total_out() as usize
        }
    };
    if got != n {
        return Err(format!(
            "{} decompression gave {got} bytes, the header announces {n}",
            c.label()
        ));
    }
    Ok(())
}

/// The bytes of one array to write, produced block by block so that a large array never
/// exists as one byte buffer (values are converted inside the parallel compression).
pub trait ByteSource: Sync {
    /// Total bytes.
    fn len(&self) -> usize;
    /// Appends bytes `range` to `out`; ranges start and end on value boundaries.
    fn fill(&self, range: std::ops::Range<usize>, out: &mut Vec<u8>);
}

/// Compression of written data.
#[derive(Clone, Copy, Debug)]
pub struct Packing {
    pub header: HeaderType,
    pub compressor: Compressor,
    pub level: u32,
}

fn push_header(out: &mut Vec<u8>, header: HeaderType, v: usize) {
    match header {
        HeaderType::U32 => out.extend_from_slice(&(v as u32).to_le_bytes()),
        HeaderType::U64 => out.extend_from_slice(&(v as u64).to_le_bytes()),
    }
}

/// One array as written: its size header and its data, both little-endian binary.
pub struct Packed {
    pub header: Vec<u8>,
    pub blocks: Vec<Vec<u8>>,
}

impl Packed {
    pub fn len(&self) -> usize {
        self.header.len() + self.blocks.iter().map(Vec::len).sum::<usize>()
    }

    pub fn write_raw(&self, w: &mut impl Write) -> std::io::Result<()> {
        w.write_all(&self.header)?;
        for b in &self.blocks {
            w.write_all(b)?;
        }
        Ok(())
    }

    /// As VTK writes base64: a compressed array's header and its blocks as two streams,
    /// an uncompressed array's header and data as one.
    pub fn to_base64(&self, compressed: bool) -> String {
        let data: Vec<u8> = self.blocks.concat();
        if compressed {
            let mut s = STANDARD.encode(&self.header);
            STANDARD.encode_string(&data, &mut s);
            s
        } else {
            let mut all = self.header.clone();
            all.extend_from_slice(&data);
            STANDARD.encode(&all)
        }
    }
}

/// Packs several arrays, compressing all their blocks in one parallel pass.
pub fn pack(sources: &[&dyn ByteSource], p: Packing) -> Result<Vec<Packed>, String> {
    let jobs: Vec<(usize, usize)> = sources
        .iter()
        .enumerate()
        .flat_map(|(a, s)| {
            let blocks = if p.compressor == Compressor::None {
                1
            } else {
                s.len().div_ceil(BLOCK_SIZE)
            };
            (0..blocks).map(move |b| (a, b))
        })
        .collect();
    let compressed: Vec<Vec<u8>> = jobs
        .par_iter()
        .map(|&(a, b)| {
            let s = sources[a];
            let mut raw = Vec::new();
            if p.compressor == Compressor::None {
                raw.reserve_exact(s.len());
                s.fill(0..s.len(), &mut raw);
                return Ok(raw);
            }
            let start = b * BLOCK_SIZE;
            let end = (start + BLOCK_SIZE).min(s.len());
            raw.reserve_exact(end - start);
            s.fill(start..end, &mut raw);
            compress_block(p.compressor, p.level, &raw)
        })
        .collect::<Result<_, String>>()?;
    let mut compressed = compressed.into_iter();
    let mut out = Vec::with_capacity(sources.len());
    for s in sources {
        let mut header = Vec::new();
        if p.compressor == Compressor::None {
            push_header(&mut header, p.header, s.len());
            out.push(Packed {
                header,
                blocks: compressed.by_ref().take(1).collect(),
            });
            continue;
        }
        let nb = s.len().div_ceil(BLOCK_SIZE);
        let blocks: Vec<Vec<u8>> = compressed.by_ref().take(nb).collect();
        let last = s.len() % BLOCK_SIZE;
        for v in [nb, BLOCK_SIZE, last] {
            push_header(&mut header, p.header, v);
        }
        for b in &blocks {
            push_header(&mut header, p.header, b.len());
        }
        out.push(Packed { header, blocks });
    }
    Ok(out)
}

fn compress_block(c: Compressor, level: u32, raw: &[u8]) -> Result<Vec<u8>, String> {
    match c {
        Compressor::None => Ok(raw.to_vec()),
        Compressor::Zlib => {
            let mut e = flate2::write::ZlibEncoder::new(
                Vec::with_capacity(raw.len() / 2),
                flate2::Compression::new(level.min(9)),
            );
            e.write_all(raw)
                .and_then(|_| e.finish())
                .map_err(|e| format!("zlib compression failed: {e}"))
        }
        Compressor::Lz4 => Ok(lz4_flex::block::compress(raw)),
        Compressor::Lzma => {
            let stream =
                xz2::stream::Stream::new_easy_encoder(level.min(9), xz2::stream::Check::Crc64)
                    .map_err(|e| format!("LZMA encoder: {e}"))?;
            let mut e =
                xz2::write::XzEncoder::new_stream(Vec::with_capacity(raw.len() / 2), stream);
            e.write_all(raw)
                .and_then(|_| e.finish())
                .map_err(|e| format!("LZMA compression failed: {e}"))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Bytes(Vec<u8>);
    impl ByteSource for Bytes {
        fn len(&self) -> usize {
            self.0.len()
        }
        fn fill(&self, range: std::ops::Range<usize>, out: &mut Vec<u8>) {
            out.extend_from_slice(&self.0[range]);
        }
    }

    #[test]
    fn packed_arrays_read_back_for_every_compressor_and_header() {
        // Three blocks and a bit, so the short last block is exercised.
        let data: Vec<u8> = (0..3 * BLOCK_SIZE + 1000)
            .map(|i| (i * 7 % 251) as u8)
            .collect();
        for compressor in [
            Compressor::None,
            Compressor::Zlib,
            Compressor::Lz4,
            Compressor::Lzma,
        ] {
            for header in [HeaderType::U32, HeaderType::U64] {
                let p = Packing {
                    header,
                    compressor,
                    level: 1,
                };
                let packed = pack(&[&Bytes(data.clone())], p).unwrap();
                let mut raw = Vec::new();
                packed[0].write_raw(&mut raw).unwrap();
                let layout = Layout {
                    header,
                    order: ByteOrder::Little,
                    compressor,
                };
                assert_eq!(read_array(&raw, &layout, data.len()).unwrap(), &data[..]);
                let b64 = packed[0].to_base64(compressor != Compressor::None);
                let decoded = decode_base64(b64.as_bytes()).unwrap();
                assert_eq!(
                    read_array(&decoded, &layout, data.len()).unwrap(),
                    &data[..]
                );
                // Asking for another size is an error, not a panic.
                assert!(read_array(&raw, &layout, data.len() + 1).is_err());
                assert!(read_array(&raw[..raw.len() / 2], &layout, data.len()).is_err());
            }
        }
    }

    #[test]
    fn concatenated_base64_streams_decode_as_one() {
        let mut s = STANDARD.encode([1u8, 2, 3, 4]);
        s.push_str(&STANDARD.encode([5u8, 6]));
        s.insert(3, '\n');
        assert_eq!(decode_base64(s.as_bytes()).unwrap(), vec![1, 2, 3, 4, 5, 6]);
        assert!(decode_base64(b"AQID$").is_err());
    }
}
