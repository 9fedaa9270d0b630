//! TetGen `.node` / `.ele` files.
//!
//! `.node`: a header `n 3 n_attributes n_boundary_markers`, then `id x y z [attributes]
//! [marker]`. `.ele`: a header `n 4 n_attributes`, then `id a b c d [attributes]`. `#`
//! starts a comment anywhere. Ids start at 0 or 1: the first node id in the file is the
//! base, as TetGen itself decides. Node attributes and markers become point data
//! (`attribute_K`, `boundary_marker`), element attributes cell data (`attribute_K`).

use super::error::{FileTerms, IoError, invalid_mesh};
use crate::geom::{DVec3, coordinate_out_of_range, out_of_range_text};
use crate::mesh::{Attribute, ImportReport, Numbering, TetMesh};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The `.node` and `.ele` paths of a pair, given either of them.
fn pair(path: &Path) -> (PathBuf, PathBuf) {
    (path.with_extension("node"), path.with_extension("ele"))
}

/// Lines with their 1-based numbers, comments and blank lines removed.
fn content_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines().enumerate().filter_map(|(i, l)| {
        let l = l.split('#').next().unwrap_or("").trim();
        (!l.is_empty()).then_some((i + 1, l))
    })
}

fn read_text(path: &Path) -> Result<String, IoError> {
    let bytes = std::fs::read(path).map_err(|e| IoError::new(path, e))?;
    String::from_utf8(bytes).map_err(|e| {
        IoError::malformed(
            path,
            format!(
                "not a text file (invalid UTF-8 at byte {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// Parses the next `count` whitespace-separated numbers of a line. Missing values on the
/// file's last line mean the file was cut short, and the message says so.
fn numbers<T: std::str::FromStr>(
    (path, last_line): (&Path, usize),
    line: usize,
    fields: &mut std::str::SplitAsciiWhitespace<'_>,
    count: usize,
    what: &str,
) -> Result<Vec<T>, IoError> {
    (0..count)
        .map(|k| {
            let f = fields.next().ok_or_else(|| {
                let cut = if line == last_line {
                    " (the file ends here: truncated)"
                } else {
                    ""
                };
                IoError::at_line(
                    path,
                    line,
                    format!("expected {count} {what} values, found {k}{cut}"),
                )
            })?;
            f.parse::<T>()
                .map_err(|_| IoError::at_line(path, line, format!("'{f}' is not a valid {what}")))
        })
        .collect()
}

/// Reads a TetGen `.node/.ele` pair given either path.
pub fn read_tetgen(path: &Path) -> Result<(TetMesh, ImportReport), IoError> {
    let (node_path, ele_path) = pair(path);
    let node_text = read_text(&node_path)?;
    let ele_text = read_text(&ele_path)?;
    parse_tetgen(&node_text, &ele_text, path)
}

/// Parses the text of a TetGen pair; errors name `path` with `.node` or `.ele` (the files
/// the texts came from, or a label for embedded data).
pub fn parse_tetgen(
    node_text: &str,
    ele_text: &str,
    path: &Path,
) -> Result<(TetMesh, ImportReport), IoError> {
    let (node_path, ele_path) = pair(path);
    let last_content_line = |text: &str| content_lines(text).last().map_or(0, |(l, _)| l);
    let node_file = (node_path.as_path(), last_content_line(node_text));
    let ele_file = (ele_path.as_path(), last_content_line(ele_text));
    let mut lines = content_lines(node_text);
    let (hl, header) = lines
        .next()
        .ok_or_else(|| IoError::malformed(&node_path, "empty file: no header line"))?;
    let mut f = header.split_ascii_whitespace();
    let h: Vec<usize> = numbers(node_file, hl, &mut f, 1, "count")?;
    let n = h[0];
    let rest: Vec<usize> = f
        .map(|x| {
            x.parse()
                .map_err(|_| IoError::at_line(&node_path, hl, format!("'{x}' is not a count")))
        })
        .collect::<Result<_, _>>()?;
    let dim = rest.first().copied().unwrap_or(3);
    let n_attr = rest.get(1).copied().unwrap_or(0);
    let n_marker = rest.get(2).copied().unwrap_or(0).min(1);
    if dim != 3 {
        return Err(IoError::at_line(
            &node_path,
            hl,
            format!("dimension {dim}, expected 3"),
        ));
    }
    // Header counts are checked against the text before anything is allocated: a damaged
    // header must give a message, not an absurd allocation. A node line has at least 8
    // characters, an attribute at least 2.
    if n_attr > node_text.len() / 2 {
        return Err(IoError::at_line(
            &node_path,
            hl,
            format!("{n_attr} attributes per node: more than the file holds"),
        ));
    }
    let rows = n.min(node_text.len() / 8);
    let mut positions = Vec::with_capacity(rows);
    let mut attrs = vec![Vec::with_capacity(rows); n_attr];
    let mut markers = Vec::with_capacity(if n_marker > 0 { rows } else { 0 });
    let mut base = 0u64;
    for i in 0..n {
        let (ln, l) = lines.next().ok_or_else(|| {
            IoError::malformed(
                &node_path,
                format!("truncated: header announces {n} nodes, file has {i}"),
            )
        })?;
        let mut f = l.split_ascii_whitespace();
        let id: Vec<u64> = numbers(node_file, ln, &mut f, 1, "node id")?;
        if i == 0 {
            base = id[0];
            if base > 1 {
                return Err(IoError::at_line(
                    &node_path,
                    ln,
                    format!("first node id is {base}; expected 0 or 1"),
                ));
            }
        }
        if id[0] != base + i as u64 {
            return Err(IoError::at_line(
                &node_path,
                ln,
                format!(
                    "node id {} out of sequence (expected {})",
                    id[0],
                    base + i as u64
                ),
            ));
        }
        let xyz: Vec<f64> = numbers(node_file, ln, &mut f, 3, "coordinate")?;
        let p = DVec3::new(xyz[0], xyz[1], xyz[2]);
        if !p.is_finite() {
            return Err(IoError::at_line(
                &node_path,
                ln,
                format!("node {} has a NaN or infinite coordinate", id[0]),
            ));
        }
        if let Some(value) = coordinate_out_of_range(p) {
            return Err(IoError::at_line(
                &node_path,
                ln,
                format!(
                    "node {} {}: rescale the mesh",
                    id[0],
                    out_of_range_text(value)
                ),
            ));
        }
        positions.push(p);
        let a: Vec<f64> = numbers(node_file, ln, &mut f, n_attr, "attribute")?;
        for (col, v) in attrs.iter_mut().zip(a) {
            col.push(v);
        }
        if n_marker > 0 {
            markers.push(numbers::<f64>(node_file, ln, &mut f, 1, "boundary marker")?[0]);
        }
    }

    let mut lines = content_lines(ele_text);
    let (hl, header) = lines
        .next()
        .ok_or_else(|| IoError::malformed(&ele_path, "empty file: no header line"))?;
    let mut f = header.split_ascii_whitespace();
    let m = numbers::<usize>(ele_file, hl, &mut f, 1, "count")?[0];
    let per: usize = f.next().map_or(Ok(4), |x| {
        x.parse()
            .map_err(|_| IoError::at_line(&ele_path, hl, format!("'{x}' is not a count")))
    })?;
    let n_eattr: usize = f.next().map_or(Ok(0), |x| {
        x.parse()
            .map_err(|_| IoError::at_line(&ele_path, hl, format!("'{x}' is not a count")))
    })?;
    if per != 4 {
        return Err(IoError::at_line(
            &ele_path,
            hl,
            format!("{per} nodes per tetrahedron; only linear (4-node) tetrahedra are supported"),
        ));
    }
    if n_eattr > ele_text.len() / 2 {
        return Err(IoError::at_line(
            &ele_path,
            hl,
            format!("{n_eattr} attributes per tetrahedron: more than the file holds"),
        ));
    }
    // A tetrahedron line has at least 10 characters.
    let rows = m.min(ele_text.len() / 10);
    let mut tets = Vec::with_capacity(rows);
    let mut eattrs = vec![Vec::with_capacity(rows); n_eattr];
    let mut tet_lines = Vec::with_capacity(rows);
    for i in 0..m {
        let (ln, l) = lines.next().ok_or_else(|| {
            IoError::malformed(
                &ele_path,
                format!("truncated: header announces {m} tetrahedra, file has {i}"),
            )
        })?;
        let mut f = l.split_ascii_whitespace();
        let id = numbers::<u64>(ele_file, ln, &mut f, 1, "element id")?[0];
        let v: Vec<u64> = numbers(ele_file, ln, &mut f, 4, "node index")?;
        let mut tet = [0u32; 4];
        for (k, &x) in v.iter().enumerate() {
            if x < base || x - base >= n as u64 {
                return Err(IoError::at_line(
                    &ele_path,
                    ln,
                    format!(
                        "tetrahedron {id} uses node {x}, but nodes are numbered {base}..{}",
                        base + n as u64 - 1
                    ),
                ));
            }
            tet[k] = (x - base) as u32;
        }
        tets.push(tet);
        tet_lines.push((ln, id));
        let a: Vec<f64> = numbers(ele_file, ln, &mut f, n_eattr, "attribute")?;
        for (col, x) in eattrs.iter_mut().zip(a) {
            col.push(x);
        }
    }

    // Tetrahedra numbered in sequence from the first id (as TetGen writes them) are named
    // by those numbers in a validation report; otherwise by their order in the file.
    let first_tet = tet_lines.first().map_or(0, |&(_, id)| id);
    let in_sequence = tet_lines
        .iter()
        .enumerate()
        .all(|(k, &(_, id))| id == first_tet + k as u64);
    let terms = FileTerms {
        vertex: "node",
        vertices: "nodes",
        tets: "tetrahedra",
        numbering: Numbering {
            first_vertex: base,
            first_tet: if in_sequence { first_tet } else { 0 },
        },
        tet_note: if in_sequence {
            ""
        } else {
            ", by their order in the .ele file from 0: its ids are not in sequence"
        },
    };
    let (mut mesh, report) = TetMesh::from_arrays_numbered(positions, tets, terms.numbering)
        .map_err(|e| {
            invalid_mesh(&ele_path, e, &terms, |t| {
                let (ln, id) = tet_lines[t];
                format!("line {ln}: tetrahedron {id}")
            })
        })?;
    for (k, col) in attrs.into_iter().enumerate() {
        mesh.point_data
            .insert(Attribute::new(format!("attribute_{k}"), 1, col).expect("scalar column"));
    }
    if n_marker > 0 {
        mesh.point_data
            .insert(Attribute::new("boundary_marker", 1, markers).expect("scalar column"));
    }
    for (k, col) in eattrs.into_iter().enumerate() {
        mesh.cell_data
            .insert(Attribute::new(format!("attribute_{k}"), 1, col).expect("scalar column"));
    }
    Ok((mesh, report))
}

/// Writes `mesh` as a TetGen pair (0-based ids) next to `path` (`.node` and `.ele`).
/// Scalar point data become node attributes and scalar cell data element attributes, in
/// column order; vector columns cannot be expressed in TetGen files and are left out.
pub fn write_tetgen(path: &Path, mesh: &TetMesh) -> Result<(), IoError> {
    let [(node_path, node), (ele_path, ele)] = tetgen_files(path, mesh);
    // Both files replaced together: never a new .node beside an old .ele.
    let files = [(&*node_path, &node[..]), (&*ele_path, &ele[..])];
    crate::io::write_files(&files).map_err(|(i, e)| IoError::new(files[i].0, e))
}

/// The paths and bytes of the TetGen pair for `mesh` next to `path` (see
/// [`write_tetgen`]), made in memory so that both files can be replaced together.
pub(crate) fn tetgen_files(path: &Path, mesh: &TetMesh) -> [(PathBuf, Vec<u8>); 2] {
    let (node_path, ele_path) = pair(path);
    let scalar = |a: &&Attribute| a.components == 1;
    let pattrs: Vec<&Attribute> = mesh.point_data.iter().filter(scalar).collect();
    let cattrs: Vec<&Attribute> = mesh.cell_data.iter().filter(scalar).collect();
    let (mut node, mut ele) = (Vec::new(), Vec::new());
    write_nodes(&mut node, mesh, &pattrs)
        .and_then(|()| write_elements(&mut ele, mesh, &cattrs))
        .expect("writing into memory does not fail");
    [(node_path, node), (ele_path, ele)]
}

fn write_nodes(w: &mut Vec<u8>, mesh: &TetMesh, attrs: &[&Attribute]) -> std::io::Result<()> {
    writeln!(w, "{} 3 {} 0", mesh.nb_vertices(), attrs.len())?;
    for (i, p) in mesh.positions().iter().enumerate() {
        // `{:?}` prints the shortest decimal that reads back to the same double.
        write!(w, "{i} {:?} {:?} {:?}", p.x, p.y, p.z)?;
        for a in attrs {
            write!(w, " {:?}", a.values[i])?;
        }
        writeln!(w)?;
    }
    writeln!(w, "# written by mtcut {}", env!("CARGO_PKG_VERSION"))
}

fn write_elements(w: &mut Vec<u8>, mesh: &TetMesh, attrs: &[&Attribute]) -> std::io::Result<()> {
    writeln!(w, "{} 4 {}", mesh.nb_tets(), attrs.len())?;
    for (i, t) in mesh.tets().iter().enumerate() {
        write!(w, "{i} {} {} {} {}", t[0], t[1], t[2], t[3])?;
        for a in attrs {
            write!(w, " {:?}", a.values[i])?;
        }
        writeln!(w)?;
    }
    writeln!(w, "# written by mtcut {}", env!("CARGO_PKG_VERSION"))
}
