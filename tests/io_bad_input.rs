//! Bad input at the reader level, one test per class, for `.vtu`, TetGen and medit files:
//! truncated file, NaN coordinate, index out of range, repeated vertex in a tet, a non-tet
//! cell, a face shared by three tets, garbage bytes. Each must give an error whose message
//! names the file, where, and the problem; none may panic.

mod io_support;

use io_support::*;
use mtcut::io::{VtuOptions, parse_medit, parse_tetgen, parse_vtu, read_mesh, write_vtu};
use std::path::Path;

/// Five points and two tets (the second given negatively oriented): a valid mesh.
const POINTS: [[f64; 3]; 5] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 1.0, 1.0],
];
const TETS: [[i64; 4]; 2] = [[0, 1, 2, 3], [1, 2, 4, 3]];

/// Points for three tets around face (0, 1, 2): apexes 3, 4, 5 on both sides.
const FAN_POINTS: [[f64; 3]; 6] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.2, 0.2, 1.0],
    [0.2, 0.2, -1.0],
    [0.3, 0.3, 2.0],
];
const FAN_TETS: [[i64; 4]; 3] = [[0, 1, 2, 3], [0, 1, 2, 4], [0, 1, 2, 5]];

/// An ASCII `.vtu` with the given points (as text, so a test can write "nan"), cells
/// (connectivity, offsets and types as given).
fn vtu_text(points: &[[String; 3]], cells: &[Vec<i64>], types: &[u8]) -> String {
    let pts: Vec<String> = points.iter().map(|p| p.join(" ")).collect();
    let conn: Vec<String> = cells.iter().flatten().map(i64::to_string).collect();
    let mut end = 0;
    let offsets: Vec<String> = cells
        .iter()
        .map(|c| {
            end += c.len();
            end.to_string()
        })
        .collect();
    let types: Vec<String> = types.iter().map(u8::to_string).collect();
    format!(
        r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="{}" NumberOfCells="{}">
      <Points>
        <DataArray type="Float64" NumberOfComponents="3" format="ascii">
          {}
        </DataArray>
      </Points>
      <Cells>
        <DataArray type="Int64" Name="connectivity" format="ascii">{}</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">{}</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">{}</DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
"#,
        points.len(),
        cells.len(),
        pts.join("\n          "),
        conn.join(" "),
        offsets.join(" "),
        types.join(" ")
    )
}

fn text_points(points: &[[f64; 3]]) -> Vec<[String; 3]> {
    points.iter().map(|p| p.map(|x| format!("{x:?}"))).collect()
}

fn tets_of(tets: &[[i64; 4]]) -> Vec<Vec<i64>> {
    tets.iter().map(|t| t.to_vec()).collect()
}

fn vtu_err(text: &str) -> String {
    match parse_vtu(text.as_bytes(), Path::new("bad.vtu")) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn assert_mentions(message: &str, parts: &[&str]) {
    for p in parts {
        assert!(message.contains(p), "message lacks '{p}': {message}");
    }
}

#[test]
fn the_valid_base_files_are_accepted() {
    let text = vtu_text(&text_points(&POINTS), &tets_of(&TETS), &[10, 10]);
    let (mesh, report) = parse_vtu(text.as_bytes(), Path::new("ok.vtu")).unwrap();
    assert_eq!((mesh.nb_tets(), report.reoriented_tets), (2, 1));
    let (mesh, _) =
        parse_tetgen(&node_text(&POINTS, ""), &ele_text(&TETS), Path::new("ok")).unwrap();
    assert_eq!(mesh.nb_tets(), 2);
    let (mesh, _) = parse_medit(&medit_text(&POINTS, &TETS, ""), Path::new("ok.mesh")).unwrap();
    assert_eq!(mesh.nb_tets(), 2);
}

// ---- .vtu --------------------------------------------------------------------------

/// Point data arrays without a name, or with an empty one, are named by their place: no
/// column can be named "" (found through the C ABI: it made a column no call could name).
#[test]
fn unnamed_vtu_arrays_are_named_by_their_place() {
    let text = vtu_text(&text_points(&POINTS), &tets_of(&TETS), &[10, 10]);
    let n = POINTS.len();
    let values = vec!["1"; n].join(" ");
    let data = format!(
        "<PointData>\n<DataArray type=\"Float64\" Name=\"\" format=\"ascii\">{values}</DataArray>\n\
         <DataArray type=\"Float64\" format=\"ascii\">{values}</DataArray>\n</PointData>\n<Points>"
    );
    let text = text.replacen("<Points>", &data, 1);
    let (mesh, _) = parse_vtu(text.as_bytes(), Path::new("unnamed.vtu")).unwrap();
    let names: Vec<&str> = mesh.point_data.iter().map(|a| a.name.as_str()).collect();
    assert_eq!(names.len(), 2, "{names:?}");
    assert!(names.iter().all(|n| !n.is_empty()), "{names:?}");
}

#[test]
fn vtu_truncated_file() {
    // ASCII: the XML ends inside an element.
    let text = vtu_text(&text_points(&POINTS), &tets_of(&TETS), &[10, 10]);
    let m = vtu_err(&text[..text.len() * 2 / 3]);
    assert_mentions(&m, &["bad.vtu", "line ", "truncated"]);
    // Binary (appended raw, zlib): the data ends early.
    let dir = Scratch::new("bad-trunc");
    let path = dir.path("fandisk.vtu");
    write_vtu(&path, &tetgen_mesh("fandisk"), &VtuOptions::DEFAULT).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let err = parse_vtu(&bytes[..bytes.len() - 5000], &path)
        .unwrap_err()
        .to_string();
    assert_mentions(&err, &["fandisk.vtu", "line ", "DataArray", "truncated"]);
}

#[test]
fn vtu_nan_coordinate() {
    let mut pts = text_points(&POINTS);
    pts[3][1] = "nan".into();
    let m = vtu_err(&vtu_text(&pts, &tets_of(&TETS), &[10, 10]));
    assert_mentions(&m, &["bad.vtu", "point 3", "NaN"]);
}

#[test]
fn vtu_index_out_of_range() {
    let m = vtu_err(&vtu_text(
        &text_points(&POINTS),
        &[vec![0, 1, 2, 3], vec![1, 2, 7, 3]],
        &[10, 10],
    ));
    assert_mentions(
        &m,
        &["bad.vtu", "connectivity", "cell 1", "point 7", "5 points"],
    );
    let m = vtu_err(&vtu_text(
        &text_points(&POINTS),
        &[vec![0, 1, 2, 3], vec![1, -2, 4, 3]],
        &[10, 10],
    ));
    assert_mentions(&m, &["cell 1", "point -2"]);
}

#[test]
fn vtu_repeated_vertex_in_a_tet() {
    let m = vtu_err(&vtu_text(
        &text_points(&POINTS),
        &[vec![0, 1, 2, 3], vec![1, 2, 2, 3]],
        &[10, 10],
    ));
    assert_mentions(&m, &["bad.vtu", "cell 1 uses point 2 more than once"]);
}

#[test]
fn vtu_non_tet_cell() {
    // A hexahedron among tetrahedra.
    let cells = vec![vec![0, 1, 2, 3], vec![0, 1, 2, 3, 4, 0, 1, 2]];
    let m = vtu_err(&vtu_text(&text_points(&POINTS), &cells, &[10, 12]));
    assert_mentions(
        &m,
        &[
            "bad.vtu",
            "types",
            "cell 1",
            "type 12",
            "VTK_HEXAHEDRON",
            "only tetrahedra",
        ],
    );
    // A triangle.
    let m = vtu_err(&vtu_text(&text_points(&POINTS), &[vec![0, 1, 2]], &[5]));
    assert_mentions(&m, &["cell 0", "VTK_TRIANGLE"]);
}

#[test]
fn vtu_face_shared_by_three_tets() {
    let m = vtu_err(&vtu_text(
        &text_points(&FAN_POINTS),
        &tets_of(&FAN_TETS),
        &[10, 10, 10],
    ));
    assert_mentions(
        &m,
        &[
            "bad.vtu",
            "faces shared by more than two tets",
            "has 3 tets",
        ],
    );
}

#[test]
fn vtu_garbage_bytes() {
    let garbage: Vec<u8> = (0..4000u32)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
        .collect();
    let e = parse_vtu(&garbage, Path::new("garbage.vtu"))
        .unwrap_err()
        .to_string();
    assert_mentions(&e, &["garbage.vtu"]);
    let e = parse_vtu(b"hello, not xml", Path::new("text.vtu"))
        .unwrap_err()
        .to_string();
    assert_mentions(&e, &["text.vtu", "not a VTK XML file"]);
    let e = parse_vtu(b"", Path::new("empty.vtu"))
        .unwrap_err()
        .to_string();
    assert_mentions(&e, &["empty.vtu", "not a VTK XML file"]);
    // Other VTK XML files are named for what they are.
    let e = parse_vtu(b"<VTKFile type=\"PolyData\"></VTKFile>", Path::new("p.vtu"))
        .unwrap_err()
        .to_string();
    assert_mentions(&e, &["VTK PolyData file"]);
}

#[test]
fn vtu_damaged_binary_data() {
    let dir = Scratch::new("bad-binary");
    let path = dir.path("liver.vtu");
    write_vtu(&path, &tetgen_mesh("liver"), &VtuOptions::DEFAULT).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let data = bytes
        .windows(5)
        .position(|w| w == b"\n   _")
        .map(|p| p + 5)
        .unwrap();
    // Zero a run of compressed bytes in the first array's first block.
    let mut bad = bytes.clone();
    let at = data + 200;
    bad[at..at + 64].fill(0);
    let e = parse_vtu(&bad, &path).unwrap_err().to_string();
    assert_mentions(
        &e,
        &["liver.vtu", "DataArray", "block 1", "decompression failed"],
    );
    // A wrong offset.
    let text =
        String::from_utf8_lossy(&bytes[..data]).replace("offset=\"0\"", "offset=\"999999999\"");
    let mut bad = text.into_bytes();
    bad.extend_from_slice(&bytes[data..]);
    let e = parse_vtu(&bad, &path).unwrap_err().to_string();
    assert_mentions(&e, &["offset 999999999", "past the end"]);
}

// ---- TetGen ------------------------------------------------------------------------

fn node_text(points: &[[f64; 3]], nan_at: &str) -> String {
    let mut s = format!("{} 3 0 0\n", points.len());
    for (i, p) in points.iter().enumerate() {
        if i.to_string() == nan_at {
            s += &format!("{i} {} nan {}\n", p[0], p[2]);
        } else {
            s += &format!("{i} {} {} {}\n", p[0], p[1], p[2]);
        }
    }
    s
}

fn ele_text(tets: &[[i64; 4]]) -> String {
    let mut s = format!("{} 4 0\n", tets.len());
    for (i, t) in tets.iter().enumerate() {
        s += &format!("{i} {} {} {} {}\n", t[0], t[1], t[2], t[3]);
    }
    s
}

fn tetgen_err(node: &str, ele: &str) -> String {
    match parse_tetgen(node, ele, Path::new("bad.node")) {
        Ok(_) => panic!("accepted:\n{node}\n{ele}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn tetgen_bad_input_classes() {
    let (node, ele) = (node_text(&POINTS, ""), ele_text(&TETS));
    // Truncated.
    let without_last_line = &node[..node.trim_end().rfind('\n').unwrap() + 1];
    let m = tetgen_err(without_last_line, &ele);
    assert_mentions(&m, &["bad.node", "truncated", "5 nodes", "has 4"]);
    let m = tetgen_err(&node[..node.len() - 6], &ele);
    assert_mentions(&m, &["bad.node", "line 6", "expected 3 coordinate"]);
    let m = tetgen_err(&node, &ele[..ele.len() - 3]);
    assert_mentions(&m, &["bad.ele", "line 3"]);
    // NaN.
    let m = tetgen_err(&node_text(&POINTS, "2"), &ele);
    assert_mentions(&m, &["bad.node", "line 4", "node 2", "NaN"]);
    // Index out of range.
    let m = tetgen_err(&node, &ele_text(&[[0, 1, 2, 3], [1, 2, 9, 3]]));
    assert_mentions(&m, &["bad.ele", "line 3", "tetrahedron 1", "node 9"]);
    // Repeated vertex.
    let m = tetgen_err(&node, &ele_text(&[[0, 1, 2, 3], [1, 2, 1, 3]]));
    assert_mentions(
        &m,
        &[
            "bad.ele",
            "line 3: tetrahedron 1 uses node 1 more than once",
        ],
    );
    // Face shared by three tets.
    let m = tetgen_err(&node_text(&FAN_POINTS, ""), &ele_text(&FAN_TETS));
    assert_mentions(&m, &["bad.ele", "faces shared by more than two tets"]);
    // Absurd header counts: a message, not an allocation.
    let m = tetgen_err(&node.replacen("5 3 0 0", "99999999999999 3 0 0", 1), &ele);
    assert_mentions(&m, &["bad.node", "truncated", "99999999999999 nodes"]);
    let m = tetgen_err(&node.replacen("5 3 0 0", "5 3 99999999999999 0", 1), &ele);
    assert_mentions(&m, &["bad.node", "line 1", "attributes per node"]);
    let m = tetgen_err(&node, &ele.replacen("2 4 0", "2 4 99999999999999", 1));
    assert_mentions(&m, &["bad.ele", "line 1", "attributes per tetrahedron"]);
    // Garbage.
    let m = tetgen_err("\u{1}\u{2}garbage ### \n x y z", &ele);
    assert_mentions(&m, &["bad.node", "line 1", "not a valid count"]);
}

#[test]
fn tetgen_garbage_file_is_not_text() {
    let dir = Scratch::new("bad-tetgen");
    std::fs::write(dir.path("g.node"), [0xff, 0xfe, 0x00, 0x80, 0x41]).unwrap();
    std::fs::write(dir.path("g.ele"), "1 4 0\n0 0 1 2 3\n").unwrap();
    let m = read_mesh(dir.path("g.node")).unwrap_err().to_string();
    assert_mentions(&m, &["g.node", "not a text file"]);
}

// ---- medit -------------------------------------------------------------------------

fn medit_text(points: &[[f64; 3]], tets: &[[i64; 4]], extra: &str) -> String {
    let mut s = String::from("MeshVersionFormatted 2\nDimension 3\nVertices\n");
    s += &format!("{}\n", points.len());
    for p in points {
        s += &format!("{} {} {} 0\n", p[0], p[1], p[2]);
    }
    s += &format!("Tetrahedra\n{}\n", tets.len());
    for t in tets {
        s += &format!("{} {} {} {} 1\n", t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1);
    }
    s + extra + "End\n"
}

fn medit_err(text: &str) -> String {
    match parse_medit(text, Path::new("bad.mesh")) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn medit_bad_input_classes() {
    let good = medit_text(&POINTS, &TETS, "");
    // Truncated: inside a section, and without End.
    let m = medit_err(&good[..good.len() - 20]);
    assert_mentions(&m, &["bad.mesh", "line ", "truncated"]);
    let m = medit_err(good.trim_end_matches("End\n"));
    assert_mentions(&m, &["bad.mesh", "truncated", "no End"]);
    // NaN.
    let m = medit_err(&good.replacen("0 1 0 0", "0 nan 0 0", 1));
    assert_mentions(&m, &["bad.mesh", "line 7", "vertex 3", "NaN"]);
    // Index out of range.
    let m = medit_err(&medit_text(&POINTS, &[[0, 1, 2, 3], [1, 2, 8, 3]], ""));
    assert_mentions(
        &m,
        &["bad.mesh", "line 13", "tetrahedron 2", "vertex 9", "1..5"],
    );
    // Repeated vertex.
    let m = medit_err(&medit_text(&POINTS, &[[0, 1, 2, 3], [1, 3, 4, 3]], ""));
    assert_mentions(
        &m,
        &[
            "bad.mesh",
            "line 13: tetrahedron 2 uses vertex 4 more than once",
        ],
    );
    // Face shared by three tets.
    let m = medit_err(&medit_text(&FAN_POINTS, &FAN_TETS, ""));
    assert_mentions(&m, &["bad.mesh", "faces shared by more than two tets"]);
    // Other volume cells.
    let m = medit_err(&medit_text(
        &POINTS,
        &TETS,
        "Hexahedra\n1\n1 2 3 4 5 1 2 3 0\n",
    ));
    assert_mentions(
        &m,
        &[
            "bad.mesh",
            "line 14",
            "1 hexahedra",
            "only linear tetrahedra",
        ],
    );
    // Garbage.
    let m = medit_err("MeshVersionFormatted 1\nDimension 3\nVerticez\n3\n");
    assert_mentions(&m, &["bad.mesh", "line 3", "unknown keyword 'Verticez'"]);
    let m = medit_err("\u{7f}\u{3}binary?");
    assert_mentions(&m, &["bad.mesh", "line 1", "unknown keyword"]);
    let m = medit_err("MeshVersionFormatted 2\nDimension 2\n");
    assert_mentions(&m, &["line 2", "Dimension 2"]);
    // Absurd counts: a message, not an allocation.
    let m = medit_err("MeshVersionFormatted 2\nDimension 3\nVertices\n99999999999999\n0 0 0 0\n");
    assert_mentions(&m, &["line 3", "99999999999999 vertices"]);
    let m = medit_err("MeshVersionFormatted 2\nDimension 3\nVertices\n999999999\n0 0 0 0\n");
    assert_mentions(&m, &["line 5", "truncated"]);
    let m = medit_err(&good.replacen("Tetrahedra\n2", "Tetrahedra\n5000000000", 1));
    assert_mentions(&m, &["line 10", "5000000000 tetrahedra"]);
}

#[test]
fn vtu_bad_base64_and_wrong_sizes() {
    let mesh = tetgen_mesh("pinion");
    let mut bytes = Vec::new();
    let b64 = VtuOptions::DEFAULT.with_encoding(mtcut::io::VtuEncoding::InlineBase64);
    mtcut::io::encode_vtu(&mesh, &b64, &mut bytes).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    // A character outside the base64 alphabet inside the Points data.
    let points = text.find("Name=\"Points\"").unwrap();
    let data = points + text[points..].find(">\n").unwrap() + 20;
    let mut bad = text.clone();
    bad.replace_range(data..data + 1, "#");
    let e = parse_vtu(bad.as_bytes(), Path::new("b64.vtu"))
        .unwrap_err()
        .to_string();
    assert_mentions(
        &e,
        &["b64.vtu", "line ", "DataArray 'Points'", "invalid base64"],
    );
    // Counts in the XML that do not match the data.
    let n = mesh.nb_vertices();
    let bad = text.replacen(
        &format!("NumberOfPoints=\"{n}\""),
        &format!("NumberOfPoints=\"{}\"", n + 1),
        1,
    );
    let e = parse_vtu(bad.as_bytes(), Path::new("b64.vtu"))
        .unwrap_err()
        .to_string();
    assert_mentions(&e, &["b64.vtu", "DataArray 'Points'", "does not describe"]);
    let ascii = vtu_text(&text_points(&POINTS), &tets_of(&TETS), &[10, 10]).replacen(
        "NumberOfCells=\"2\"",
        "NumberOfCells=\"3\"",
        1,
    );
    let e = vtu_err(&ascii);
    assert_mentions(&e, &["DataArray 'types'", "2 values, expected 3"]);
}

// ---- numbering -----------------------------------------------------------------

/// Two tets sharing only a vertex (0): a boundary pinched there.
const BOWTIE_POINTS: [[f64; 3]; 7] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [-1.0, 0.0, 0.0],
    [0.0, -1.0, 0.0],
    [0.0, 0.0, -1.0],
];
const BOWTIE_TETS: [[i64; 4]; 2] = [[0, 1, 2, 3], [0, 4, 6, 5]];

/// A file numbering its nodes and tetrahedra from 1 (as TetGen may, and medit always
/// does) gets messages in its own numbers, not the mesh's ids from 0.
#[test]
fn messages_number_as_the_file_does() {
    let from_one = |points: &[[f64; 3]], tets: &[[i64; 4]], first_tet: i64| {
        let mut node = format!("{} 3 0 0\n", points.len());
        for (i, p) in points.iter().enumerate() {
            node += &format!("{} {} {} {}\n", i + 1, p[0], p[1], p[2]);
        }
        let mut ele = format!("{} 4 0\n", tets.len());
        for (i, t) in tets.iter().enumerate() {
            let [a, b, c, d] = t.map(|v| v + 1);
            ele += &format!("{} {a} {b} {c} {d}\n", first_tet + i as i64);
        }
        (node, ele)
    };
    // Repeated node 5 (id 4) in the second tetrahedron.
    let (node, ele) = from_one(&BOWTIE_POINTS, &[[0, 1, 2, 3], [4, 4, 6, 5]], 1);
    let m = tetgen_err(&node, &ele);
    assert_mentions(
        &m,
        &[
            "bad.ele",
            "line 3: tetrahedron 2 uses node 5 more than once",
        ],
    );
    // A flat second tetrahedron.
    let mut flat = BOWTIE_POINTS;
    flat[6] = [-1.0, -1.0, 0.0];
    let (node, ele) = from_one(&flat, &BOWTIE_TETS, 1);
    let m = tetgen_err(&node, &ele);
    assert_mentions(
        &m,
        &[
            "line 3: tetrahedron 2 is degenerate",
            "four nodes are coplanar",
        ],
    );
    // The bow tie: the pinched vertex is node 1, the report's tets numbered from 1 too.
    let (node, ele) = from_one(&BOWTIE_POINTS, &BOWTIE_TETS, 1);
    let m = tetgen_err(&node, &ele);
    assert_mentions(
        &m,
        &[
            "vertex 1 joins 2 separate boundary fans",
            "numbered as in the file (vertices are its nodes, tets its tetrahedra)",
        ],
    );
    // Tetrahedra numbered out of sequence: the report says how it numbers them.
    let (node, mut ele) = from_one(&BOWTIE_POINTS, &BOWTIE_TETS, 1);
    ele = ele.replacen("\n2 ", "\n7 ", 1);
    let m = tetgen_err(&node, &ele);
    assert_mentions(
        &m,
        &["vertex 1 joins", "by their order in the .ele file from 0"],
    );
    // The same bow tie from medit (numbered from 1) and .vtu (from 0).
    let m = medit_err(&medit_text(&BOWTIE_POINTS, &BOWTIE_TETS, ""));
    assert_mentions(&m, &["bad.mesh", "vertex 1 joins 2 separate boundary fans"]);
    let cells = tets_of(&BOWTIE_TETS);
    let m = vtu_err(&vtu_text(&text_points(&BOWTIE_POINTS), &cells, &[10, 10]));
    assert_mentions(
        &m,
        &[
            "vertex 0 joins 2 separate boundary fans",
            "vertices are its points, tets its cells",
        ],
    );
}

/// A coordinate beyond the supported ±1e50, or a mesh smaller than 1e-50 across: refused
/// by the readers naming the line and node, not taken for degenerate tets.
#[test]
fn coordinates_beyond_the_supported_range() {
    let (node, ele) = (node_text(&POINTS, ""), ele_text(&TETS));
    let m = tetgen_err(&node.replacen("\n2 0 1 0\n", "\n2 0 1e60 0\n", 1), &ele);
    assert_mentions(
        &m,
        &[
            "bad.node",
            "line 4",
            "node 2 has coordinate 1e60",
            "larger in magnitude than the 1e50",
        ],
    );
    let good = medit_text(&POINTS, &TETS, "");
    let m = medit_err(&good.replacen("0 1 0 0", "0 -3e55 0 0", 1));
    assert_mentions(&m, &["bad.mesh", "line 7", "vertex 3 has coordinate -3e55"]);
    let tiny: Vec<[f64; 3]> = POINTS.iter().map(|p| p.map(|x| x * 1e-60)).collect();
    let m = tetgen_err(&node_text(&tiny, ""), &ele);
    assert_mentions(&m, &["bad.ele", "below the 1e-50 mtcut supports"]);
    let m = vtu_err(&vtu_text(&text_points(&tiny), &tets_of(&TETS), &[10, 10]));
    assert_mentions(&m, &["bad.vtu", "below the 1e-50 mtcut supports"]);
}
