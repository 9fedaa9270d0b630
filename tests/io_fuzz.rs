//! Fuzz-style robustness: real files (every kind mtcut writes, every kind VTK writes when
//! VTK's Python is present, TetGen and medit files), truncated at many offsets and with
//! bytes changed at random, must be read as `Ok` or `Err`, never a panic. Seeded; a panic
//! reports the seed, the file and the one mutation that causes it (a single truncation
//! or byte change: already the smallest failing input).

mod io_support;

use io_support::*;
use mtcut::io::{
    VtuCompression, VtuEncoding, VtuOptions, encode_vtu, parse_medit, parse_tetgen, parse_vtu,
};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

const SEED: u64 = 0x6d74_6375_7421;
const TRUNCATIONS: usize = 300;
const FLIPS: usize = 300;

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Runs `parse` on truncations and single-byte changes of `bytes`; panics, naming the
/// mutation, if `parse` panics on any of them.
fn fuzz(name: &str, bytes: &[u8], seed: u64, parse: &dyn Fn(&[u8])) {
    let mut rng = Rng(seed ^ name.len() as u64 ^ (bytes.len() as u64) << 20);
    let run = |what: String, input: &[u8]| {
        if catch_unwind(AssertUnwindSafe(|| parse(input))).is_err() {
            panic!("{name}: panic on {what} (seed {seed:#x}); reproduce by applying that mutation");
        }
    };
    for k in 0..TRUNCATIONS {
        // Evenly spread offsets plus random ones, so every region of the file is cut.
        let at = if k % 2 == 0 {
            k * bytes.len() / TRUNCATIONS
        } else {
            rng.below(bytes.len())
        };
        run(format!("truncation to {at} bytes"), &bytes[..at]);
    }
    let mut copy = bytes.to_vec();
    for _ in 0..FLIPS {
        let at = rng.below(bytes.len());
        let value = (rng.next() >> 8) as u8;
        let old = copy[at];
        copy[at] = value;
        run(format!("byte {at} set to {value:#04x}"), &copy);
        copy[at] = old;
    }
}

fn vtu_parser(label: &'static str) -> impl Fn(&[u8]) {
    move |b: &[u8]| {
        let _ = parse_vtu(b, Path::new(label));
    }
}

#[test]
fn vtu_files_we_write_never_panic_when_damaged() {
    let mesh = with_attributes(mtcut::io::read_mesh(data("pinion-coarse.node")).unwrap().0);
    let raw = VtuOptions::DEFAULT;
    let b64 = raw.with_encoding(VtuEncoding::InlineBase64);
    for (label, options) in [
        ("raw-zlib", raw),
        ("raw-none", raw.with_compression(VtuCompression::None)),
        ("raw-lz4", raw.with_compression(VtuCompression::Lz4)),
        (
            "raw-lzma",
            raw.with_compression(VtuCompression::Lzma { level: 1 }),
        ),
        ("base64-zlib", b64),
        ("base64-none", b64.with_compression(VtuCompression::None)),
        ("ascii", VtuOptions::ASCII),
    ] {
        let mut bytes = Vec::new();
        encode_vtu(&mesh, &options, &mut bytes).unwrap();
        // The undamaged file reads back.
        parse_vtu(&bytes, Path::new(label)).unwrap();
        fuzz(label, &bytes, SEED, &vtu_parser("fuzz.vtu"));
    }
}

#[test]
fn vtu_files_vtk_writes_never_panic_when_damaged() {
    if !vtk_available() {
        return;
    }
    let dir = Scratch::new("fuzz-vtk");
    let modes = [
        "default",
        "raw-zlib",
        "raw-lz4",
        "raw-lzma",
        "raw-zlib-uint64",
        "raw-zlib-bigendian",
        "binary-zlib",
        "binary-none",
        "base64-none",
        "ascii",
    ];
    let node = data("pinion-coarse.node");
    let ele = data("pinion-coarse.ele");
    let out = dir.path("vtk");
    let mut args = vec![
        node.to_str().unwrap(),
        ele.to_str().unwrap(),
        out.to_str().unwrap(),
    ];
    args.insert(0, "write");
    args.extend(modes);
    run_vtu_tool(&args);
    for mode in modes {
        let bytes = std::fs::read(out.join(format!("{mode}.vtu"))).unwrap();
        parse_vtu(&bytes, Path::new(mode)).unwrap();
        fuzz(mode, &bytes, SEED, &vtu_parser("fuzz.vtu"));
    }
}

#[test]
fn text_formats_never_panic_when_damaged() {
    let node = std::fs::read(data("pinion-coarse.node")).unwrap();
    let ele = std::fs::read(data("pinion-coarse.ele")).unwrap();
    let mesh = std::fs::read(data("pinion-coarse.mesh")).unwrap();
    // The readers take text; damaged bytes that are not UTF-8 are refused before parsing.
    let text = |b: &[u8]| String::from_utf8(b.to_vec()).ok();
    let ele_text = text(&ele).unwrap();
    let node_text = text(&node).unwrap();
    fuzz("pinion-coarse.node", &node, SEED, &|b: &[u8]| {
        if let Some(t) = text(b) {
            let _ = parse_tetgen(&t, &ele_text, Path::new("fuzz"));
        }
    });
    fuzz("pinion-coarse.ele", &ele, SEED, &|b: &[u8]| {
        if let Some(t) = text(b) {
            let _ = parse_tetgen(&node_text, &t, Path::new("fuzz"));
        }
    });
    fuzz("pinion-coarse.mesh", &mesh, SEED, &|b: &[u8]| {
        if let Some(t) = text(b) {
            let _ = parse_medit(&t, Path::new("fuzz.mesh"));
        }
    });
}
