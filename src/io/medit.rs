//! medit `.mesh` files (ASCII), as gmsh, CGAL, TetGen (`-g`) and MMG write them.
//!
//! A file is a sequence of keyword sections: `MeshVersionFormatted v`, `Dimension 3`,
//! `Vertices n` (then `x y z ref` each), `Tetrahedra m` (then `a b c d ref`, 1-based),
//! and sections this reader skips (boundary triangles, edges, corners, ridges, normals,
//! required entities...), closed by `End`. Keywords are case-insensitive; `#` starts a
//! comment. Vertex references become point data `medit:ref`, tetrahedron references cell
//! data `medit:ref`. Other volume elements (hexahedra, prisms, pyramids, quadratic
//! tetrahedra) are rejected: mtcut meshes are linear tetrahedra only.

use super::error::{FileTerms, IoError, invalid_mesh};
use crate::geom::{DVec3, coordinate_out_of_range, out_of_range_text};
use crate::mesh::{Attribute, ImportReport, Numbering, TetMesh};
use std::path::Path;

/// The name of the attribute columns holding medit references.
pub const MEDIT_REF: &str = "medit:ref";

/// Reads a medit `.mesh` file holding tetrahedra.
pub fn read_medit(path: &Path) -> Result<(TetMesh, ImportReport), IoError> {
    let bytes = std::fs::read(path).map_err(|e| IoError::new(path, e))?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        IoError::malformed(
            path,
            format!(
                "not a text file (invalid UTF-8 at byte {}); binary .meshb is not supported",
                e.valid_up_to()
            ),
        )
    })?;
    parse_medit(text, path)
}

/// Whitespace-separated tokens with their 1-based line numbers, comments removed.
struct Tokens<'a> {
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
    current: std::str::SplitAsciiWhitespace<'a>,
    line: usize,
    path: &'a Path,
}

impl<'a> Tokens<'a> {
    fn new(text: &'a str, path: &'a Path) -> Tokens<'a> {
        Tokens {
            lines: text.lines().enumerate(),
            current: "".split_ascii_whitespace(),
            line: 1,
            path,
        }
    }

    /// The next token, which must exist: `what` says what was expected.
    fn expect(&mut self, what: &str) -> Result<(usize, &'a str), IoError> {
        self.next().ok_or_else(|| {
            IoError::at_line(
                self.path,
                self.line,
                format!("truncated file: expected {what}, found the end of the file"),
            )
        })
    }

    /// The next token parsed as a `T` (`what` names it in messages).
    fn number<T: std::str::FromStr>(&mut self, what: &str) -> Result<T, IoError> {
        let (line, t) = self.expect(what)?;
        t.parse()
            .map_err(|_| IoError::at_line(self.path, line, format!("'{t}' is not a valid {what}")))
    }
}

impl<'a> Iterator for Tokens<'a> {
    type Item = (usize, &'a str);
    fn next(&mut self) -> Option<(usize, &'a str)> {
        loop {
            if let Some(t) = self.current.next() {
                return Some((self.line, t));
            }
            let (i, l) = self.lines.next()?;
            self.line = i + 1;
            self.current = l.split('#').next().unwrap_or("").split_ascii_whitespace();
        }
    }
}

/// Tokens per entry of the sections that are skipped; `None` for sections whose entries
/// are volume elements this reader refuses.
fn skipped_section(keyword: &str) -> Option<(usize, Option<&'static str>)> {
    Some(match keyword {
        "edges" => (3, None),
        "triangles" => (4, None),
        "quadrilaterals" => (5, None),
        "corners"
        | "ridges"
        | "requiredvertices"
        | "requirededges"
        | "requiredtriangles"
        | "requiredquadrilaterals"
        | "requiredtetrahedra" => (1, None),
        "normals" | "tangents" => (3, None),
        "normalatvertices" | "tangentatvertices" => (2, None),
        "normalattrianglevertices" | "normalatquadrilateralvertices" | "tangentatedgevertices" => {
            (3, None)
        }
        "edgesp2" => (4, None),
        "trianglesp2" => (7, None),
        "quadrilateralsq2" => (10, None),
        "hexahedra" => (9, Some("hexahedra")),
        "prisms" => (7, Some("prisms")),
        "pyramids" => (6, Some("pyramids")),
        "tetrahedrap2" => (11, Some("quadratic tetrahedra")),
        "hexahedraq2" => (28, Some("quadratic hexahedra")),
        _ => return None,
    })
}

/// Parses the text of a medit file; errors name `path`.
pub fn parse_medit(text: &str, path: &Path) -> Result<(TetMesh, ImportReport), IoError> {
    let mut tokens = Tokens::new(text, path);
    let at = |line: usize, m: String| IoError::at_line(path, line, m);
    let mut dimension = None;
    let mut positions: Vec<DVec3> = Vec::new();
    let mut vertex_refs: Vec<f64> = Vec::new();
    let mut have_vertices = false;
    let mut tets: Vec<[u32; 4]> = Vec::new();
    let mut raw_tets: Vec<([i64; 4], usize)> = Vec::new();
    let mut tet_refs: Vec<f64> = Vec::new();
    let mut ended = false;
    while let Some((line, word)) = tokens.next() {
        let keyword = word.to_ascii_lowercase();
        match keyword.as_str() {
            "meshversionformatted" => {
                let v: u32 = tokens.number("version number")?;
                if !(1..=3).contains(&v) {
                    return Err(at(
                        line,
                        format!("MeshVersionFormatted {v}; expected 1, 2 or 3"),
                    ));
                }
            }
            "dimension" => {
                let d: u32 = tokens.number("dimension")?;
                if d != 3 {
                    return Err(at(line, format!("Dimension {d}; mtcut reads 3D meshes")));
                }
                dimension = Some(d);
            }
            "vertices" => {
                if dimension.is_none() {
                    return Err(at(line, "Vertices before Dimension".into()));
                }
                if have_vertices {
                    return Err(at(line, "a second Vertices section".into()));
                }
                have_vertices = true;
                let n: usize = tokens.number("vertex count")?;
                if n >= u32::MAX as usize {
                    return Err(at(line, format!("{n} vertices: more than mtcut's limit")));
                }
                // Capacity bounded by the text: a damaged count must not allocate.
                positions.reserve(n.min(text.len() / 8));
                vertex_refs.reserve(n.min(text.len() / 8));
                for i in 0..n {
                    let mut xyz = [0.0; 3];
                    for c in xyz.iter_mut() {
                        *c = tokens.number("coordinate")?;
                    }
                    let first_line = tokens.line;
                    let p = DVec3::from_array(xyz);
                    if !p.is_finite() {
                        return Err(at(
                            first_line,
                            format!("vertex {} has a NaN or infinite coordinate", i + 1),
                        ));
                    }
                    if let Some(value) = coordinate_out_of_range(p) {
                        return Err(at(
                            first_line,
                            format!(
                                "vertex {} {}: rescale the mesh",
                                i + 1,
                                out_of_range_text(value)
                            ),
                        ));
                    }
                    positions.push(p);
                    let r: i64 = tokens.number("vertex reference")?;
                    vertex_refs.push(r as f64);
                }
            }
            "tetrahedra" => {
                if !raw_tets.is_empty() {
                    return Err(at(line, "a second Tetrahedra section".into()));
                }
                let m: usize = tokens.number("tetrahedron count")?;
                if m >= u32::MAX as usize {
                    return Err(at(line, format!("{m} tetrahedra: more than mtcut's limit")));
                }
                raw_tets.reserve(m.min(text.len() / 10));
                tet_refs.reserve(m.min(text.len() / 10));
                for _ in 0..m {
                    let mut ids = [0i64; 4];
                    for v in ids.iter_mut() {
                        *v = tokens.number("vertex index")?;
                    }
                    raw_tets.push((ids, tokens.line));
                    let r: i64 = tokens.number("tetrahedron reference")?;
                    tet_refs.push(r as f64);
                }
            }
            "end" => {
                ended = true;
                break;
            }
            _ => match skipped_section(&keyword) {
                Some((per, refused)) => {
                    let count: usize = tokens.number(&format!("size of section {word}"))?;
                    if let Some(what) = refused.filter(|_| count > 0) {
                        return Err(at(
                            line,
                            format!(
                                "the mesh has {count} {what}; mtcut reads only linear tetrahedra"
                            ),
                        ));
                    }
                    let tokens_needed = count.checked_mul(per).ok_or_else(|| {
                        at(
                            line,
                            format!("section {word} of {count} entries is too large"),
                        )
                    })?;
                    for _ in 0..tokens_needed {
                        tokens.expect(&format!("the entries of section {word}"))?;
                    }
                }
                None => {
                    return Err(at(
                        line,
                        format!("unknown keyword '{word}' (not a medit section this reader knows)"),
                    ));
                }
            },
        }
    }
    if !ended {
        return Err(IoError::at_line(
            path,
            tokens.line,
            "truncated file: no End keyword",
        ));
    }
    if !have_vertices {
        return Err(IoError::malformed(path, "no Vertices section"));
    }
    let n = positions.len();
    tets.reserve_exact(raw_tets.len());
    for (i, (ids, line)) in raw_tets.iter().enumerate() {
        let mut t = [0u32; 4];
        for (k, &v) in ids.iter().enumerate() {
            if v < 1 || v as u64 > n as u64 {
                return Err(at(
                    *line,
                    format!(
                        "tetrahedron {} uses vertex {v}, but vertices are numbered 1..{n}",
                        i + 1
                    ),
                ));
            }
            t[k] = (v - 1) as u32;
        }
        tets.push(t);
    }
    let terms = FileTerms {
        vertex: "vertex",
        vertices: "vertices",
        tets: "tetrahedra",
        numbering: Numbering {
            first_vertex: 1,
            first_tet: 1,
        },
        tet_note: "",
    };
    let (mut mesh, report) = TetMesh::from_arrays_numbered(positions, tets, terms.numbering)
        .map_err(|e| {
            invalid_mesh(path, e, &terms, |t| {
                format!("line {}: tetrahedron {}", raw_tets[t].1, t + 1)
            })
        })?;
    mesh.point_data
        .insert(Attribute::new(MEDIT_REF, 1, vertex_refs).expect("one reference per vertex"));
    mesh.cell_data
        .insert(Attribute::new(MEDIT_REF, 1, tet_refs).expect("one reference per tetrahedron"));
    Ok((mesh, report))
}
