//! medit `.mesh` reading (a hand-written file using the format's liberties, and the file
//! TetGen itself writes with `-g`, compared with the same mesh read from TetGen's
//! `.node/.ele`), and the `.pvd` collection writer.
//!
//! tests/data/pinion-coarse.{node,ele,mesh}: `tetgen -pgQ pinion.off` (TetGen 1.5, Debian),
//! pinion.off from ../shared/data.

mod io_support;

use io_support::*;
use mtcut::io::{MEDIT_REF, PvdEntry, parse_medit, read_mesh, write_pvd};
use std::path::{Path, PathBuf};

#[test]
fn hand_written_medit_file_with_comments_skipped_sections_and_any_case() {
    let text = "\
# a comment line
meshversionformatted
2
DIMENSION
3   # dimension on its own line, as gmsh writes it

Vertices
5
0 0 0 1
1 0 0 1   # trailing comment
0 1 0 2
0 0 1 2
1 1 1 3
Corners 1 1
Ridges 2 1 2
RequiredVertices 1 5
Edges
2
1 2 7
2 3 7
Triangles
1
1 2 3 4
NormalAtVertices 1 1 1
Normals 1 0 0 1
Tetrahedra
2
1 2 3 4 10
2 3 5 4 20
END
anything after End is ignored
";
    let (mesh, report) = parse_medit(text, Path::new("hand.mesh")).unwrap();
    assert_eq!(mesh.nb_vertices(), 5);
    assert_eq!(mesh.nb_tets(), 2);
    // The second tet is given negatively oriented and comes back re-oriented.
    assert_eq!(report.reoriented_tets, 1);
    let tets: Vec<[u32; 4]> = mesh.tets().iter().map(|t| t.map(|v| v.0)).collect();
    assert_eq!(tets, vec![[0, 1, 2, 3], [1, 2, 3, 4]]);
    assert_eq!(mesh.positions()[4].to_array(), [1.0, 1.0, 1.0]);
    assert_eq!(
        mesh.point_data.get(MEDIT_REF).unwrap().values,
        vec![1.0, 1.0, 2.0, 2.0, 3.0]
    );
    assert_eq!(
        mesh.cell_data.get(MEDIT_REF).unwrap().values,
        vec![10.0, 20.0]
    );
    assert!(mesh.validate().is_valid());
}

#[test]
fn tetgen_written_medit_file_matches_tetgen_node_ele() {
    let (from_medit, medit_report) = read_mesh(data("pinion-coarse.mesh")).unwrap();
    let (from_tetgen, tetgen_report) = read_mesh(data("pinion-coarse.node")).unwrap();
    assert_eq!(medit_report, tetgen_report);
    assert_eq!(from_medit.positions(), from_tetgen.positions());
    assert_eq!(from_medit.tets(), from_tetgen.tets());
    assert_eq!(from_medit.nb_tets(), 1247);
    let refs = from_medit.cell_data.get(MEDIT_REF).unwrap();
    assert_eq!(refs.len(), 1247);
    assert!(from_medit.validate().is_valid());
}

#[test]
fn pvd_lists_time_steps_and_parts_in_order_with_escaped_names() {
    let dir = Scratch::new("pvd");
    let path = dir.path("series.pvd");
    let entries = vec![
        PvdEntry {
            timestep: 0.0,
            part: 0,
            file: PathBuf::from("cut_000_left.vtu"),
        },
        PvdEntry {
            timestep: 0.0,
            part: 1,
            file: PathBuf::from("cut_000_right.vtu"),
        },
        PvdEntry {
            timestep: 0.1,
            part: 0,
            file: PathBuf::from("a&b <1>.vtu"),
        },
    ];
    write_pvd(&path, &entries).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    // Read it back with an XML parser: the attributes of every DataSet, in order.
    let mut reader = quick_xml::Reader::from_str(&text);
    let mut sets = Vec::new();
    let mut root = None;
    loop {
        match reader.read_event().unwrap() {
            quick_xml::events::Event::Eof => break,
            quick_xml::events::Event::Start(e) | quick_xml::events::Event::Empty(e) => {
                let attr = |k: &str| {
                    e.try_get_attribute(k)
                        .unwrap()
                        .map(|a| a.unescape_value().unwrap().into_owned())
                };
                match e.name().as_ref() {
                    b"VTKFile" => root = attr("type"),
                    b"DataSet" => sets.push((
                        attr("timestep").unwrap().parse::<f64>().unwrap(),
                        attr("part").unwrap().parse::<u32>().unwrap(),
                        PathBuf::from(attr("file").unwrap()),
                    )),
                    _ => {}
                }
            }
            _ => {}
        }
    }
    assert_eq!(root.as_deref(), Some("Collection"));
    let expected: Vec<(f64, u32, PathBuf)> = entries
        .iter()
        .map(|e| (e.timestep, e.part, e.file.clone()))
        .collect();
    assert_eq!(sets, expected);
    let bad = [PvdEntry {
        timestep: f64::NAN,
        part: 0,
        file: PathBuf::from("x.vtu"),
    }];
    let e = write_pvd(&dir.path("bad.pvd"), &bad)
        .unwrap_err()
        .to_string();
    assert!(e.contains("not a finite number"), "{e}");
}
