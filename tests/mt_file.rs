//! The `.mt` file: save → load gives the same MT, cut record included; files of the first
//! format version still load; damaged files are refused with a clear error; and
//! `validate` catches what a well-checksummed but wrong file would hide.

mod mt_common;

use mt_common::{MESHES, built};
use mtcut::mt::{MT_FILE_VERSION, MT_MAGIC, Mt, MtFileErrorKind};

const HEADER: usize = 32;

fn temp_dir(test: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("mtcut-{test}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn save_then_load_is_identical() {
    let dir = temp_dir("roundtrip");
    for name in MESHES {
        let (_, mt, _) = built(name);
        let path = dir.join(format!("{name}.mt"));
        mt.save(&path).unwrap();
        let back = Mt::load(&path).unwrap();
        assert!(back == *mt, "{name}: loaded MT differs");
        assert_eq!(back.canonical_form(), mt.canonical_form());
        assert!(back.validate().is_valid());
        let size = std::fs::metadata(&path).unwrap().len();
        eprintln!(
            "{name}: {size} bytes on disk, {} in memory",
            mt.heap_bytes()
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Rewrites the header checksum after a payload edit (a file that was written wrong, not
/// damaged on the way).
fn reseal(bytes: &mut [u8]) {
    let mut crc = flate2::Crc::new();
    crc.update(&bytes[HEADER..]);
    bytes[24..28].copy_from_slice(&crc.sum().to_le_bytes());
}

#[test]
fn damaged_files_are_refused_with_the_reason() {
    let (_, mt, _) = built("pinion");
    let good = mt.to_bytes();
    assert_eq!(&good[..8], &MT_MAGIC);

    let mut magic = good.clone();
    magic[0] = b'X';
    let e = Mt::from_bytes(&magic).unwrap_err();
    assert!(matches!(e, MtFileErrorKind::WrongMagic { .. }), "{e}");
    assert!(
        Mt::from_bytes(b"solid ascii stl file")
            .unwrap_err()
            .to_string()
            .contains("magic")
    );

    let mut version = good.clone();
    version[8..12].copy_from_slice(&(MT_FILE_VERSION + 1).to_le_bytes());
    let e = Mt::from_bytes(&version).unwrap_err();
    assert!(
        matches!(e, MtFileErrorKind::UnsupportedVersion { found, .. } if found == MT_FILE_VERSION + 1),
        "{e}"
    );

    for cut in [0, 7, HEADER - 1, HEADER, good.len() / 2, good.len() - 1] {
        let e = Mt::from_bytes(&good[..cut]).unwrap_err();
        assert!(
            matches!(e, MtFileErrorKind::Truncated { .. }),
            "cut at {cut}: {e}"
        );
        assert!(e.to_string().contains("truncated"), "{e}");
    }

    let mut longer = good.clone();
    longer.push(0);
    assert!(matches!(
        Mt::from_bytes(&longer).unwrap_err(),
        MtFileErrorKind::TrailingBytes { extra: 1 }
    ));

    for at in [HEADER, HEADER + 1000, good.len() / 2, good.len() - 3] {
        let mut flipped = good.clone();
        flipped[at] ^= 0x10;
        let e = Mt::from_bytes(&flipped).unwrap_err();
        assert!(
            matches!(e, MtFileErrorKind::ChecksumMismatch { .. }),
            "byte {at}: {e}"
        );
        assert!(e.to_string().contains("checksum"), "{e}");
    }

    let dir = temp_dir("damaged");
    let path = dir.join("missing.mt");
    let e = Mt::load(&path).unwrap_err();
    assert!(e.to_string().contains("missing.mt"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Offset in the payload of the counts (vertices, tets, arcs, fragments): after the info
/// block.
fn counts_offset(bytes: &[u8]) -> usize {
    let name_len = u32::from_le_bytes(bytes[HEADER..HEADER + 4].try_into().unwrap()) as usize;
    HEADER + 4 + name_len + 8 + 1 + 8 + 8
}

fn count(bytes: &[u8], k: usize) -> usize {
    let at = counts_offset(bytes) + 8 * k;
    u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap()) as usize
}

/// Offset in the payload of the tet array: after the info block, the counts and the
/// positions.
fn tets_offset(bytes: &[u8]) -> usize {
    counts_offset(bytes) + 32 + count(bytes, 0) * 24
}

#[test]
fn well_sealed_but_inconsistent_files_are_refused() {
    let (_, mt, _) = built("pinion");
    let good = mt.to_bytes();
    let at = tets_offset(&good);

    // A vertex index beyond the pool: refused on loading, with what and where.
    let mut out_of_range = good.clone();
    out_of_range[at..at + 4].copy_from_slice(&u32::MAX.wrapping_sub(7).to_le_bytes());
    reseal(&mut out_of_range);
    let e = Mt::from_bytes(&out_of_range).unwrap_err();
    assert!(matches!(e, MtFileErrorKind::Corrupt(_)), "{e}");
    assert!(e.to_string().contains("tet 0"), "{e}");

    // Arcs out of (creator, destroyer) order (the store derives each arc's creator from
    // that order): refused, naming the arc.
    let (nt, na) = (count(&good, 1), count(&good, 2));
    let creators = at + nt * 16 + (na + 1) * 4;
    let mut unordered = good.clone();
    let last = creators + (na - 1) * 4;
    let (first, end): ([u8; 4], [u8; 4]) = (
        unordered[creators..creators + 4].try_into().unwrap(),
        unordered[last..last + 4].try_into().unwrap(),
    );
    assert_ne!(first, end);
    unordered[creators..creators + 4].copy_from_slice(&end);
    unordered[last..last + 4].copy_from_slice(&first);
    reseal(&mut unordered);
    let e = Mt::from_bytes(&unordered).unwrap_err();
    assert!(matches!(e, MtFileErrorKind::Corrupt(_)), "{e}");
    assert!(e.to_string().contains("(creator, destroyer) order"), "{e}");

    // Two corners of a tet swapped: structurally fine, geometrically inverted, and the
    // fragments around it no longer fit: the validation on loading says so.
    let mut swapped = good.clone();
    let (a, b) = (at + 4, at + 8);
    let tmp: [u8; 4] = swapped[a..a + 4].try_into().unwrap();
    swapped.copy_within(b..b + 4, a);
    swapped[b..b + 4].copy_from_slice(&tmp);
    reseal(&mut swapped);
    let e = Mt::from_bytes(&swapped).unwrap_err();
    assert!(matches!(e, MtFileErrorKind::Corrupt(_)), "{e}");
    for needle in ["not consistent", "TetOrientation", "FragmentBoundary"] {
        assert!(e.to_string().contains(needle), "{needle}: {e}");
    }

    // A tet using a vertex twice (found through the C ABI: it loaded, and extractions
    // holding it were invalid meshes).
    let mut doubled = good.clone();
    doubled.copy_within(at..at + 4, at + 4);
    reseal(&mut doubled);
    let e = Mt::from_bytes(&doubled).unwrap_err();
    assert!(e.to_string().contains("not consistent"), "{e}");
}

#[test]
fn attributes_survive_the_file() {
    let mut input = mt_common::mesh("fandisk");
    let n = input.nb_vertices();
    let velocity: Vec<f64> = (0..3 * n).map(|i| i as f64 * 0.5).collect();
    input
        .point_data
        .insert(mtcut::mesh::Attribute::new("velocity", 3, velocity).unwrap());
    let region: Vec<f64> = (0..input.nb_tets()).map(|t| (t % 7) as f64).collect();
    input
        .cell_data
        .insert(mtcut::mesh::Attribute::new("region", 1, region).unwrap());
    let options = mtcut::mt::BuildOptions::DEFAULT.with_target_tets(Some(input.nb_tets() / 3));
    let (mt, _) = Mt::build(&input, &options).unwrap();
    let back = Mt::from_bytes(&mt.to_bytes()).unwrap();
    assert!(back == mt);
    assert_eq!(back.point_data().get("velocity").unwrap().components, 3);
    assert!(back.validate().is_valid());
}

/// Bytes at the end of the payload that hold the cut record of an MT no cut changed and no
/// cutter prepared: the first vertex made by a cut (u32), no cuts (u64), no scales (u64),
/// no crack planes (u64).
const EMPTY_RECORD: usize = 4 + 8 + 8 + 8;

/// A file written before cuts were recorded (format version 1: the same payload without the
/// cut record) loads as the MT it holds, with no vertex made by a cut.
#[test]
fn a_version_1_file_still_loads() {
    let (_, mt, _) = built("pinion");
    let mut bytes = mt.to_bytes();
    bytes.truncate(bytes.len() - EMPTY_RECORD);
    bytes[8..12].copy_from_slice(&1u32.to_le_bytes());
    let len = (bytes.len() - HEADER) as u64;
    bytes[16..24].copy_from_slice(&len.to_le_bytes());
    reseal(&mut bytes);
    let back = Mt::from_bytes(&bytes).unwrap();
    assert!(back == *mt, "the version 1 file loads another MT");
    assert_eq!(back.info().cuts.cut_vertices_from(), back.nb_vertices());
}

/// A cut model keeps, through the file, what later cuts read (its cut record: the vertices
/// cuts made, the last cuts' polygons and vertex kinds, the vertex scales): the loaded MT
/// equals the saved one, record included. A record that does not fit the pool is refused.
#[test]
fn a_cut_model_keeps_its_cut_record() {
    let (_, mt, _) = built("fandisk");
    let b = mtcut::geom::Aabb::from_points(mt.positions());
    let (c, d) = (b.center(), b.max - b.min);
    let mut cutter =
        mtcut::cut::MtCutter::new(mt.clone(), mtcut::cut::MtCutter::DEFAULT_OPTIONS).unwrap();
    let p = |x: f64, z: f64| mtcut::geom::DVec3::new(x, c.y + 0.05 * (x - c.x), z);
    let (z0, z1) = (b.min.z - 0.1 * d.z, b.max.z + 0.1 * d.z);
    let (x0, x1) = (b.min.x - 0.1 * d.x, c.x);
    let square = mtcut::geom::CutPolygon::new(&[p(x0, z0), p(x1, z0), p(x1, z1), p(x0, z1)]);
    cutter.cut(&square.unwrap()).unwrap();
    let cut = cutter.into_mt();
    let record = &cut.info().cuts;
    assert_eq!(record.cut_vertices_from(), mt.nb_vertices());
    assert!(cut.nb_vertices() > mt.nb_vertices());
    assert_eq!(record.cuts_kept(), 1);
    assert_eq!(record.planes_kept(), 1);
    assert_eq!(record.vertex_scales().len(), cut.nb_vertices());
    let bytes = cut.to_bytes();
    let back = Mt::from_bytes(&bytes).unwrap();
    assert!(back == cut, "the loaded MT differs from the saved one");
    assert!(back.validate().is_valid());

    // The first vertex made by a cut, beyond the pool: refused, naming the record.
    let (_, uncut, _) = built("pinion");
    let mut beyond = uncut.to_bytes();
    let at = beyond.len() - EMPTY_RECORD;
    let nv = uncut.nb_vertices() as u32;
    beyond[at..at + 4].copy_from_slice(&(nv + 5).to_le_bytes());
    reseal(&mut beyond);
    let e = Mt::from_bytes(&beyond).unwrap_err();
    assert!(matches!(e, MtFileErrorKind::Corrupt(_)), "{e}");
    assert!(e.to_string().contains("cut record"), "{e}");

    // A crack plane whose normal is not finite: refused, naming the record.
    let mut nan = bytes.clone();
    let at = nan.len() - 48;
    nan[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
    reseal(&mut nan);
    let e = Mt::from_bytes(&nan).unwrap_err();
    assert!(matches!(e, MtFileErrorKind::Corrupt(_)), "{e}");
    assert!(e.to_string().contains("cut record: plane 0"), "{e}");

    // Written by version 2 (the same payload without the cut's frame, 0 at rest, and the
    // planes): the planes are those of the cuts it kept, here the one cut's.
    let mut v2 = bytes.clone();
    v2.truncate(v2.len() - (8 + 48));
    let frame_at = v2.len() - (8 + 8 * cut.nb_vertices()) - 8;
    assert_eq!(v2[frame_at..frame_at + 8], [0; 8]);
    v2.drain(frame_at..frame_at + 8);
    v2[8..12].copy_from_slice(&2u32.to_le_bytes());
    let len = (v2.len() - HEADER) as u64;
    v2[16..24].copy_from_slice(&len.to_le_bytes());
    reseal(&mut v2);
    let back = Mt::from_bytes(&v2).unwrap();
    assert!(back == cut, "the version 2 file loads another MT");
}
