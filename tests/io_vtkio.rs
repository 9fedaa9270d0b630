//! Cross-check with vtkio, an independent Rust implementation of VTK's XML formats: it reads
//! the .vtu files we write (in the encodings it supports: inline base64 and ASCII) with the
//! same points and cells, and we read the files it writes identically.

mod common;
use common::{data, scratch};
use mtcut::io::{VtuCompression, VtuEncoding, VtuOptions, read_mesh, write_vtu};
use mtcut::mesh::TetMesh;
use vtkio::model::{
    Attributes, CellType, Cells, DataSet, Piece, UnstructuredGridPiece, Version, VertexNumbers,
};

/// Points and tets of a vtkio data set holding one inline unstructured-grid piece.
fn vtkio_arrays(vtk: vtkio::Vtk) -> (Vec<f64>, Vec<u64>, Vec<CellType>) {
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        panic!("not an unstructured grid");
    };
    let [Piece::Inline(piece)] = <[_; 1]>::try_from(pieces).expect("one piece") else {
        panic!("piece not inline");
    };
    let points = piece.points.cast_into::<f64>().expect("numeric points");
    let (connectivity, _offsets) = piece.cells.cell_verts.into_xml();
    (points, connectivity, piece.cells.types)
}

fn flat(mesh: &TetMesh) -> (Vec<f64>, Vec<u64>) {
    let p = mesh.positions().iter().flat_map(|p| p.to_array()).collect();
    let t = mesh.tets().iter().flatten().map(|v| v.0 as u64).collect();
    (p, t)
}

#[test]
fn vtkio_reads_what_we_write() {
    let dir = scratch("vtkio-reads");
    let (mesh, _) = read_mesh(data("fandisk.node")).unwrap();
    let (points, tets) = flat(&mesh);
    for (name, options) in [
        (
            "base64-zlib",
            VtuOptions::DEFAULT.with_encoding(VtuEncoding::InlineBase64),
        ),
        (
            "base64-raw",
            VtuOptions::DEFAULT
                .with_encoding(VtuEncoding::InlineBase64)
                .with_compression(VtuCompression::None),
        ),
        ("ascii", VtuOptions::ASCII),
    ] {
        let path = dir.join(format!("{name}.vtu"));
        write_vtu(&path, &mesh, &options).unwrap();
        let vtk = vtkio::Vtk::import(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        let (p, c, types) = vtkio_arrays(vtk);
        assert_eq!(p, points, "{name}: points");
        assert_eq!(c, tets, "{name}: connectivity");
        assert!(types.iter().all(|t| *t == CellType::Tetra), "{name}: types");
    }
}

#[test]
fn we_read_what_vtkio_writes() {
    let dir = scratch("vtkio-writes");
    let (mesh, _) = read_mesh(data("liver.ele")).unwrap();
    let (points, tets) = flat(&mesh);
    let piece = UnstructuredGridPiece {
        points: points.clone().into(),
        cells: Cells {
            cell_verts: VertexNumbers::XML {
                connectivity: tets.clone(),
                offsets: (1..=mesh.nb_tets() as u64).map(|i| 4 * i).collect(),
            },
            types: vec![CellType::Tetra; mesh.nb_tets()],
        },
        data: Attributes::new(),
    };
    let vtk = vtkio::Vtk {
        version: Version::new_xml(1, 0),
        byte_order: vtkio::model::ByteOrder::LittleEndian,
        title: String::new(),
        file_path: None,
        data: DataSet::inline(piece),
    };
    let path = dir.join("by-vtkio.vtu");
    vtk.export(&path).unwrap();
    let (back, report) = read_mesh(&path).unwrap();
    assert_eq!(report.reoriented_tets, 0);
    assert_eq!(flat(&back), (points, tets));
}
