//! Writing a [`TetMesh`] as a `.vtu` file.

use super::binary::{ByteSource, Packing, pack};
use super::format::{Compressor, HeaderType, Scalar, VTK_TETRA};
use crate::geom::DVec3;
use crate::io::error::IoError;
use crate::mesh::{Attribute, Tet, TetMesh};
use std::fmt::Write as _;
use std::ops::Range;
use std::path::Path;

/// How array data is stored in the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum VtuEncoding {
    /// Binary data appended raw after the XML (`<AppendedData encoding="raw">`): the
    /// smallest and fastest form, and what ParaView writes by default.
    AppendedRaw,
    /// Binary data base64-encoded inside each `<DataArray>`: the file stays valid XML.
    InlineBase64,
    /// Numbers as text; shortest decimal forms that read back to the same doubles.
    /// (VTK's own ASCII reader cannot read NaN or infinite values; binary can.)
    Ascii,
}

/// How binary data is compressed (ignored for [`VtuEncoding::Ascii`]). Data is compressed
/// in blocks of 32 KiB, as VTK does, on all cores.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum VtuCompression {
    None,
    /// zlib (`vtkZLibDataCompressor`) at `level` 1 (fastest) to 9 (smallest).
    Zlib {
        level: u32,
    },
    /// LZ4 (`vtkLZ4DataCompressor`): fastest to read and write, larger files.
    Lz4,
    /// LZMA (`vtkLZMADataCompressor`) at preset `level` 0..9: smallest files, slow.
    Lzma {
        level: u32,
    },
}

/// Options of [`write_vtu`]. Start from [`VtuOptions::DEFAULT`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct VtuOptions {
    /// Default: [`VtuEncoding::AppendedRaw`].
    pub encoding: VtuEncoding,
    /// Default: zlib at level 2. On fandisk-1m, level 2 gives a file 8% larger than VTK's
    /// default (level 5) and, compressed on all cores, writes it about ten times faster
    /// than VTK (benches/io_vs_vtk.rs); level 1 is twice as fast again but its file is
    /// 46% larger.
    pub compression: VtuCompression,
}

impl VtuOptions {
    /// Appended raw binary, zlib level 2.
    pub const DEFAULT: VtuOptions = VtuOptions {
        encoding: VtuEncoding::AppendedRaw,
        compression: VtuCompression::Zlib { level: 2 },
    };

    /// ASCII text (no compression).
    pub const ASCII: VtuOptions = VtuOptions {
        encoding: VtuEncoding::Ascii,
        compression: VtuCompression::None,
    };

    pub const fn with_encoding(mut self, encoding: VtuEncoding) -> VtuOptions {
        self.encoding = encoding;
        self
    }

    pub const fn with_compression(mut self, compression: VtuCompression) -> VtuOptions {
        self.compression = compression;
        self
    }
}

impl Default for VtuOptions {
    fn default() -> VtuOptions {
        VtuOptions::DEFAULT
    }
}

/// One array to write: its declaration and where its values come from.
struct Array<'a> {
    name: String,
    scalar: Scalar,
    components: usize,
    values: Values<'a>,
}

/// The value sources the writer needs; each converts its values to bytes on demand.
enum Values<'a> {
    F64(&'a [f64]),
    Points(&'a [DVec3]),
    /// Tet vertex ids as Int32 (`false`) or Int64 (`true`).
    Connectivity(&'a [Tet], bool),
    /// End offsets of `n` tetrahedra, as Int32 or Int64.
    Offsets(usize, bool),
    /// `n` cell types, all `VTK_TETRA`.
    Types(usize),
}

impl Values<'_> {
    fn count(&self) -> usize {
        match self {
            Values::F64(v) => v.len(),
            Values::Points(p) => 3 * p.len(),
            Values::Connectivity(t, _) => 4 * t.len(),
            Values::Offsets(n, _) | Values::Types(n) => *n,
        }
    }

    fn size(&self) -> usize {
        match self {
            Values::F64(_) | Values::Points(_) => 8,
            Values::Connectivity(_, wide) | Values::Offsets(_, wide) => {
                if *wide {
                    8
                } else {
                    4
                }
            }
            Values::Types(_) => 1,
        }
    }

    /// Value `i` as text (ASCII files).
    fn text(&self, i: usize, out: &mut String) {
        // Writing to a String cannot fail.
        let _ = match self {
            Values::F64(v) => write_f64(v[i], out),
            Values::Points(p) => write_f64(p[i / 3][i % 3], out),
            Values::Connectivity(t, _) => write!(out, "{}", t[i / 4][i % 4].0),
            Values::Offsets(_, _) => write!(out, "{}", 4 * (i as u64 + 1)),
            Values::Types(_) => write!(out, "{VTK_TETRA}"),
        };
    }
}

fn write_f64(v: f64, out: &mut String) -> std::fmt::Result {
    if v.is_nan() {
        out.push_str("nan");
        Ok(())
    } else {
        // `{:?}` is the shortest decimal that reads back to the same double; "inf" and
        // "-inf" for infinities.
        write!(out, "{v:?}")
    }
}

impl ByteSource for Values<'_> {
    fn len(&self) -> usize {
        self.count() * self.size()
    }

    fn fill(&self, range: Range<usize>, out: &mut Vec<u8>) {
        let values = range.start / self.size()..range.end / self.size();
        match *self {
            Values::F64(v) => {
                for x in &v[values] {
                    out.extend_from_slice(&x.to_le_bytes());
                }
            }
            Values::Points(p) => {
                for i in values {
                    out.extend_from_slice(&p[i / 3][i % 3].to_le_bytes());
                }
            }
            Values::Connectivity(t, wide) => {
                for i in values {
                    let v = t[i / 4][i % 4].0;
                    if wide {
                        out.extend_from_slice(&(v as i64).to_le_bytes());
                    } else {
                        out.extend_from_slice(&(v as i32).to_le_bytes());
                    }
                }
            }
            Values::Offsets(_, wide) => {
                for i in values {
                    let v = 4 * (i as u64 + 1);
                    if wide {
                        out.extend_from_slice(&(v as i64).to_le_bytes());
                    } else {
                        out.extend_from_slice(&(v as i32).to_le_bytes());
                    }
                }
            }
            Values::Types(_) => out.extend(values.map(|_| VTK_TETRA)),
        }
    }
}

/// XML-escapes an attribute value.
fn escape(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&apos;"),
            c => o.push(c),
        }
    }
    o
}

fn attribute_array(a: &Attribute) -> Array<'_> {
    Array {
        name: a.name.clone(),
        scalar: Scalar::F64,
        components: a.components,
        values: Values::F64(&a.values),
    }
}

/// Writes `mesh` as a `.vtu` file: points, tetrahedra (`VTK_TETRA`), and every point and
/// cell data column as a Float64 array. Files are read by VTK 9.1 and ParaView.
pub fn write_vtu(path: &Path, mesh: &TetMesh, options: &VtuOptions) -> Result<(), IoError> {
    let mut out = Vec::new();
    encode_vtu(mesh, options, &mut out).map_err(|e| IoError::malformed(path, e))?;
    crate::io::write_files(&[(path, &out)]).map_err(|(_, e)| IoError::new(path, e))
}

/// The bytes of a `.vtu` file for `mesh`, appended to `out`.
pub fn encode_vtu(mesh: &TetMesh, options: &VtuOptions, out: &mut Vec<u8>) -> Result<(), String> {
    let m = mesh.nb_tets();
    // Int32 indices while they fit: half the bytes of VTK's Int64, same meaning to readers.
    let wide_ids = mesh.nb_vertices() > i32::MAX as usize;
    let wide_offsets = 4 * m > i32::MAX as usize;
    let id_scalar = |wide| if wide { Scalar::I64 } else { Scalar::I32 };
    let point_arrays: Vec<Array> = mesh.point_data.iter().map(attribute_array).collect();
    let cell_arrays: Vec<Array> = mesh.cell_data.iter().map(attribute_array).collect();
    let points = Array {
        name: "Points".into(),
        scalar: Scalar::F64,
        components: 3,
        values: Values::Points(mesh.positions()),
    };
    let cells = [
        Array {
            name: "connectivity".into(),
            scalar: id_scalar(wide_ids),
            components: 1,
            values: Values::Connectivity(mesh.tets(), wide_ids),
        },
        Array {
            name: "offsets".into(),
            scalar: id_scalar(wide_offsets),
            components: 1,
            values: Values::Offsets(m, wide_offsets),
        },
        Array {
            name: "types".into(),
            scalar: Scalar::U8,
            components: 1,
            values: Values::Types(m),
        },
    ];
    // Sections in the order VTK writes them.
    let sections: [(&str, Vec<&Array>); 4] = [
        ("PointData", point_arrays.iter().collect()),
        ("CellData", cell_arrays.iter().collect()),
        ("Points", vec![&points]),
        ("Cells", cells.iter().collect()),
    ];
    let all: Vec<&Array> = sections
        .iter()
        .flat_map(|(_, a)| a.iter().copied())
        .collect();

    let (compressor, level) = match options.compression {
        VtuCompression::None => (Compressor::None, 0),
        VtuCompression::Zlib { level } => (Compressor::Zlib, level),
        VtuCompression::Lz4 => (Compressor::Lz4, 0),
        VtuCompression::Lzma { level } => (Compressor::Lzma, level),
    };
    let ascii = options.encoding == VtuEncoding::Ascii;
    let compressor = if ascii { Compressor::None } else { compressor };
    let header = HeaderType::U64;
    let packed = if ascii {
        Vec::new()
    } else {
        let sources: Vec<&dyn ByteSource> =
            all.iter().map(|a| &a.values as &dyn ByteSource).collect();
        pack(
            &sources,
            Packing {
                header,
                compressor,
                level,
            },
        )?
    };

    let mut x = String::new();
    x.push_str("<?xml version=\"1.0\"?>\n");
    let _ = write!(
        x,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\""
    );
    if compressor != Compressor::None {
        let _ = write!(x, " compressor=\"{}\"", compressor.name());
    }
    x.push_str(">\n  <UnstructuredGrid>\n");
    let _ = writeln!(
        x,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{m}\">",
        mesh.nb_vertices()
    );
    let mut index = 0;
    let mut offset = 0;
    for (section, arrays) in &sections {
        let _ = writeln!(x, "      <{section}>");
        for a in arrays {
            let _ = write!(
                x,
                "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" ",
                a.scalar.name(),
                escape(&a.name),
                a.components
            );
            match options.encoding {
                VtuEncoding::AppendedRaw => {
                    let _ = writeln!(x, "format=\"appended\" offset=\"{offset}\"/>");
                    offset += packed[index].len();
                }
                VtuEncoding::InlineBase64 => {
                    let _ = writeln!(
                        x,
                        "format=\"binary\">\n          {}\n        </DataArray>",
                        packed[index].to_base64(compressor != Compressor::None)
                    );
                }
                VtuEncoding::Ascii => {
                    x.push_str("format=\"ascii\">\n");
                    let per_line = a.components.max(if a.components == 1 { 6 } else { 1 });
                    for i in 0..a.values.count() {
                        if i % per_line == 0 {
                            x.push_str("          ");
                        }
                        a.values.text(i, &mut x);
                        x.push(if (i + 1) % per_line == 0 { '\n' } else { ' ' });
                    }
                    if a.values.count() % per_line != 0 {
                        x.push('\n');
                    }
                    x.push_str("        </DataArray>\n");
                }
            }
            index += 1;
        }
        let _ = writeln!(x, "      </{section}>");
    }
    x.push_str("    </Piece>\n  </UnstructuredGrid>\n");
    if options.encoding == VtuEncoding::AppendedRaw {
        x.push_str("  <AppendedData encoding=\"raw\">\n   _");
        out.reserve(x.len() + offset + 40);
        out.extend_from_slice(x.as_bytes());
        for p in &packed {
            p.write_raw(out).map_err(|e| e.to_string())?;
        }
        out.extend_from_slice(b"\n  </AppendedData>\n</VTKFile>\n");
    } else {
        x.push_str("</VTKFile>\n");
        out.extend_from_slice(x.as_bytes());
    }
    Ok(())
}
