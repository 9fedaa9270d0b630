//! Reading a `.vtu` into a checked [`TetMesh`].

use super::binary::{decode_base64, read_array};
use super::format::{VTK_TETRA, cell_type_name};
use super::values::{first_mismatch, integer_at, parse_ascii, to_f64, to_index_groups, to_points};
use super::xml::{ArrayDecl, Format, Header, Section, XmlError, scan};
use crate::io::error::{FileTerms, IoError, invalid_mesh};
use crate::mesh::{Attribute, Attributes, ImportReport, Numbering, TetMesh};
use std::borrow::Cow;
use std::path::Path;

/// Reads a `.vtu` file (VTK XML UnstructuredGrid) holding only tetrahedra.
///
/// Every variant VTK and ParaView write is read: ASCII, inline base64, appended base64 or
/// raw; uncompressed or zlib / LZ4 / LZMA compressed; UInt32 or UInt64 headers; either
/// byte order; any numeric type for points, cells and data arrays. Point and cell data
/// arrays become f64 attribute columns. The mesh goes through [`TetMesh::from_arrays`]:
/// negative tets are re-oriented and counted, invalid meshes rejected.
pub fn read_vtu(path: &Path) -> Result<(TetMesh, ImportReport), IoError> {
    let bytes = std::fs::read(path).map_err(|e| IoError::new(path, e))?;
    parse_vtu(&bytes, path)
}

/// Reads a `.vtu` from memory; errors name `path`.
pub fn parse_vtu(bytes: &[u8], path: &Path) -> Result<(TetMesh, ImportReport), IoError> {
    Reader { bytes, path }.read()
}

struct Reader<'a> {
    bytes: &'a [u8],
    path: &'a Path,
}

/// The line (1-based) of byte position `pos`.
fn line_of(bytes: &[u8], pos: usize) -> usize {
    1 + bytes[..pos.min(bytes.len())]
        .iter()
        .filter(|&&c| c == b'\n')
        .count()
}

impl<'a> Reader<'a> {
    fn at(&self, pos: usize, message: impl Into<String>) -> IoError {
        IoError::at_line(self.path, line_of(self.bytes, pos), message)
    }

    fn array_error(&self, a: &ArrayDecl, message: impl std::fmt::Display) -> IoError {
        self.at(a.pos, format!("{}: {message}", a.label()))
    }

    fn read(&self) -> Result<(TetMesh, ImportReport), IoError> {
        let header = scan(self.bytes).map_err(|XmlError { pos, message }| self.at(pos, message))?;
        let n = header.n_points;
        let m = header.n_cells;
        if n >= u32::MAX as usize || m >= u32::MAX as usize {
            return Err(IoError::malformed(
                self.path,
                format!(
                    "{n} points and {m} cells: more than mtcut's limit of {} of either",
                    u32::MAX - 1
                ),
            ));
        }
        let find = |section: Section, name: Option<&str>| {
            header
                .arrays
                .iter()
                .find(|a| a.section == section && (name.is_none() || a.name.as_deref() == name))
        };
        let missing = |what: &str| IoError::malformed(self.path, format!("no {what} array"));
        let points = find(Section::Points, None).ok_or_else(|| missing("Points"))?;
        let conn = find(Section::Cells, Some("connectivity"))
            .ok_or_else(|| missing("Cells 'connectivity'"))?;
        let offsets =
            find(Section::Cells, Some("offsets")).ok_or_else(|| missing("Cells 'offsets'"))?;
        let types = find(Section::Cells, Some("types")).ok_or_else(|| missing("Cells 'types'"))?;

        // The cell types first: a mesh of other cells is rejected for that, clearly, before
        // its connectivity is misread as tetrahedra.
        let type_bytes = self.decode(&header, types, m, 1)?;
        if let Some(k) = first_mismatch(&type_bytes, types.scalar, header.layout.order, |_| {
            VTK_TETRA as i128
        }) {
            let t = integer_at(&type_bytes, types.scalar, header.layout.order, k).unwrap_or(-1);
            return Err(self.array_error(
                types,
                format!(
                    "cell {k} has type {t} ({}); mtcut reads only tetrahedra (VTK_TETRA = 10)",
                    cell_type_name(t as i64)
                ),
            ));
        }
        let offset_bytes = self.decode(&header, offsets, m, 1)?;
        if let Some(k) = first_mismatch(&offset_bytes, offsets.scalar, header.layout.order, |k| {
            4 * (k as i128 + 1)
        }) {
            let o = integer_at(&offset_bytes, offsets.scalar, header.layout.order, k);
            return Err(self.array_error(
                offsets,
                format!(
                    "cell {k} ends at connectivity offset {}; with 4 points per tetrahedron it \
                     must end at {}",
                    o.map_or("(not an integer)".to_string(), |o| o.to_string()),
                    4 * (k + 1)
                ),
            ));
        }
        let conn_bytes = self.decode(&header, conn, 4 * m, 1)?;
        let tets = to_index_groups::<4>(&conn_bytes, conn.scalar, header.layout.order, n).map_err(
            |(k, v)| {
                self.array_error(
                    conn,
                    format!(
                        "cell {} refers to point {v}, but the file has {n} points (0..{})",
                        k / 4,
                        n.max(1) - 1
                    ),
                )
            },
        )?;
        drop(conn_bytes);
        if points.components != 3 {
            return Err(self.array_error(
                points,
                format!("{} components; points have 3", points.components),
            ));
        }
        let point_bytes = self.decode(&header, points, n, 3)?;
        let positions = to_points(&point_bytes, points.scalar, header.layout.order);
        drop(point_bytes);
        let point_data = self.attributes(&header, Section::PointData, n)?;
        let cell_data = self.attributes(&header, Section::CellData, m)?;

        let terms = FileTerms {
            vertex: "point",
            vertices: "points",
            tets: "cells",
            numbering: Numbering::ZERO,
            tet_note: "",
        };
        let (mut mesh, report) = TetMesh::from_arrays(positions, tets)
            .map_err(|e| invalid_mesh(self.path, e, &terms, |t| format!("cell {t}")))?;
        mesh.point_data = point_data;
        mesh.cell_data = cell_data;
        Ok((mesh, report))
    }

    /// The data arrays of `section`, each with `rows` tuples.
    fn attributes(
        &self,
        header: &Header,
        section: Section,
        rows: usize,
    ) -> Result<Attributes, IoError> {
        let mut out = Attributes::new();
        for (k, a) in header
            .arrays
            .iter()
            .filter(|a| a.section == section)
            .enumerate()
        {
            if !(1..=9).contains(&a.components) {
                return Err(self.array_error(
                    a,
                    format!(
                        "{} components; mtcut keeps 1 to 9 per attribute",
                        a.components
                    ),
                ));
            }
            // An array without a name, or with an empty one (no attribute can be named
            // "": the API looks columns up by name), is named by its place.
            let name = a
                .name
                .clone()
                .filter(|n| !n.is_empty())
                .unwrap_or_else(|| format!("{}_{k}", section.name()));
            if out.get(&name).is_some() {
                return Err(self.array_error(
                    a,
                    format!("a second {} array named '{name}'", section.name()),
                ));
            }
            let bytes = self.decode(header, a, rows, a.components)?;
            let values = to_f64(&bytes, a.scalar, header.layout.order);
            let column = Attribute::new(name, a.components, values)
                .ok_or_else(|| self.array_error(a, "values are not whole tuples"))?;
            out.insert(column);
        }
        Ok(out)
    }

    /// The bytes of array `a`, which must hold `tuples × components` values, in the
    /// file's byte order (ASCII data is parsed into that order too).
    fn decode<'h>(
        &self,
        header: &'h Header<'a>,
        a: &'h ArrayDecl<'a>,
        tuples: usize,
        components: usize,
    ) -> Result<Cow<'h, [u8]>, IoError> {
        if a.components != components {
            return Err(self.array_error(
                a,
                format!("{} components, expected {components}", a.components),
            ));
        }
        let count = tuples
            .checked_mul(components)
            .ok_or_else(|| self.array_error(a, "too many values"))?;
        let expected = count
            .checked_mul(a.scalar.size())
            .ok_or_else(|| self.array_error(a, "too many values"))?;
        let layout = &header.layout;
        let bytes: Cow<[u8]> = match a.format {
            Format::Ascii => {
                let text = a.joined_text();
                let parsed = parse_ascii(&text, a.scalar, layout.order).map_err(|(k, v)| {
                    self.array_error(
                        a,
                        format!("value {k} '{v}' is not a valid {}", a.scalar.name()),
                    )
                })?;
                let got = parsed.len() / a.scalar.size();
                if got != count {
                    return Err(self.array_error(a, format!("{got} values, expected {count}")));
                }
                Cow::Owned(parsed)
            }
            Format::Binary => {
                let decoded =
                    decode_base64(&a.joined_text()).map_err(|e| self.array_error(a, e))?;
                Cow::Owned(
                    read_array(&decoded, layout, expected)
                        .map_err(|e| self.array_error(a, e))?
                        .into_owned(),
                )
            }
            Format::Appended { offset } => {
                let app = header.appended.as_ref().ok_or_else(|| {
                    self.array_error(a, "format is appended, but the file has no <AppendedData>")
                })?;
                let start = app
                    .start
                    .checked_add(offset)
                    .filter(|&s| s <= app.end)
                    .ok_or_else(|| {
                        self.array_error(
                            a,
                            format!(
                                "offset {offset} is past the end of the appended data ({} \
                                 bytes): the file is truncated or the offset is wrong",
                                app.end - app.start
                            ),
                        )
                    })?;
                if app.base64 {
                    // Offsets count base64 characters; the array's text ends where the
                    // next array's begins.
                    let end = header
                        .arrays
                        .iter()
                        .filter_map(|b| match b.format {
                            Format::Appended { offset: o } if o > offset => Some(app.start + o),
                            _ => None,
                        })
                        .filter(|&e| e <= app.end)
                        .min()
                        .unwrap_or(app.end);
                    let decoded = decode_base64(&self.bytes[start..end])
                        .map_err(|e| self.array_error(a, e))?;
                    Cow::Owned(
                        read_array(&decoded, layout, expected)
                            .map_err(|e| self.array_error(a, e))?
                            .into_owned(),
                    )
                } else {
                    read_array(&self.bytes[start..app.end], layout, expected)
                        .map_err(|e| self.array_error(a, e))?
                }
            }
        };
        Ok(bytes)
    }
}
