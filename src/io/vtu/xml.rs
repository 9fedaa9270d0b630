//! The XML part of a `.vtu` file: which arrays it has, their types and where their data
//! is. The scan stops at `<AppendedData>`: what follows may be raw binary, which is not
//! XML, and is located by byte offsets instead.

use super::binary::Layout;
use super::format::{ByteOrder, Compressor, HeaderType, Scalar};
use quick_xml::events::{BytesStart, Event};
use std::borrow::Cow;

/// Where a `DataArray` sits in a `Piece`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Section {
    Points,
    Cells,
    PointData,
    CellData,
}

impl Section {
    fn from_tag(tag: &[u8]) -> Option<Section> {
        Some(match tag {
            b"Points" => Section::Points,
            b"Cells" => Section::Cells,
            b"PointData" => Section::PointData,
            b"CellData" => Section::CellData,
            _ => return None,
        })
    }

    pub fn name(self) -> &'static str {
        match self {
            Section::Points => "Points",
            Section::Cells => "Cells",
            Section::PointData => "PointData",
            Section::CellData => "CellData",
        }
    }
}

/// A `DataArray`'s `format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Ascii,
    Binary,
    Appended { offset: usize },
}

/// One `DataArray` as declared.
#[derive(Debug)]
pub struct ArrayDecl<'a> {
    pub section: Section,
    pub name: Option<String>,
    pub scalar: Scalar,
    pub components: usize,
    pub format: Format,
    /// The text directly inside the element (inline data), in pieces.
    pub text: Vec<Cow<'a, [u8]>>,
    /// Byte position of the element in the file, for line numbers in messages.
    pub pos: usize,
}

impl ArrayDecl<'_> {
    /// How messages name this array.
    pub fn label(&self) -> String {
        match &self.name {
            Some(n) => format!("DataArray '{n}' in {}", self.section.name()),
            None => format!("unnamed DataArray in {}", self.section.name()),
        }
    }

    /// The inline text, joined (pieces are separated by child elements VTK writes, such
    /// as `<InformationKey>`).
    pub fn joined_text(&self) -> Cow<'_, [u8]> {
        match self.text.as_slice() {
            [] => Cow::Borrowed(&[]),
            [one] => Cow::Borrowed(one.as_ref()),
            many => Cow::Owned(many.join(&b' ')),
        }
    }
}

/// The `<AppendedData>` section.
#[derive(Debug)]
pub struct Appended {
    pub base64: bool,
    /// Position of the first data byte (after the `_` marker).
    pub start: usize,
    /// End of the data: the end of the file for raw data, the end of the base64 text.
    pub end: usize,
}

/// The XML of a `.vtu`: layout, counts, arrays, appended data.
#[derive(Debug)]
pub struct Header<'a> {
    pub layout: Layout,
    pub n_points: usize,
    pub n_cells: usize,
    pub arrays: Vec<ArrayDecl<'a>>,
    pub appended: Option<Appended>,
}

/// An error at a byte position of the file (turned into a line number by the caller).
#[derive(Debug)]
pub struct XmlError {
    pub pos: usize,
    pub message: String,
}

fn err(pos: usize, message: impl Into<String>) -> XmlError {
    XmlError {
        pos,
        message: message.into(),
    }
}

fn attr(e: &BytesStart, key: &str, pos: usize) -> Result<Option<String>, XmlError> {
    for a in e.attributes() {
        let a = a.map_err(|x| err(pos, format!("bad attribute in <{}>: {x}", tag_name(e))))?;
        if a.key.as_ref() == key.as_bytes() {
            let v = a.unescape_value().map_err(|x| {
                err(
                    pos,
                    format!("bad value of attribute {key} in <{}>: {x}", tag_name(e)),
                )
            })?;
            return Ok(Some(v.into_owned()));
        }
    }
    Ok(None)
}

fn tag_name(e: &BytesStart) -> String {
    String::from_utf8_lossy(e.name().as_ref()).into_owned()
}

fn count_attr(e: &BytesStart, key: &str, pos: usize) -> Result<usize, XmlError> {
    let v = attr(e, key, pos)?
        .ok_or_else(|| err(pos, format!("<{}> has no {key} attribute", tag_name(e))))?;
    v.trim()
        .parse()
        .map_err(|_| err(pos, format!("{key}=\"{v}\" is not a count")))
}

fn data_array<'a>(e: &BytesStart, section: Section, pos: usize) -> Result<ArrayDecl<'a>, XmlError> {
    let name = attr(e, "Name", pos)?;
    let label = match &name {
        Some(n) => format!("DataArray '{n}'"),
        None => "DataArray".to_string(),
    };
    let ty = attr(e, "type", pos)?.ok_or_else(|| err(pos, format!("{label} has no type")))?;
    let scalar = Scalar::from_name(&ty).ok_or_else(|| {
        err(
            pos,
            format!("{label} has type \"{ty}\"; mtcut reads numeric arrays (Int8..UInt64, Float32, Float64)"),
        )
    })?;
    let components = match attr(e, "NumberOfComponents", pos)? {
        None => 1,
        Some(v) => v.trim().parse().map_err(|_| {
            err(
                pos,
                format!("{label}: NumberOfComponents=\"{v}\" is not a count"),
            )
        })?,
    };
    let format = match attr(e, "format", pos)?.as_deref() {
        Some("ascii") => Format::Ascii,
        Some("binary") => Format::Binary,
        Some("appended") => {
            let v = attr(e, "offset", pos)?
                .ok_or_else(|| err(pos, format!("{label} is appended but has no offset")))?;
            Format::Appended {
                offset: v
                    .trim()
                    .parse()
                    .map_err(|_| err(pos, format!("{label}: offset=\"{v}\" is not an offset")))?,
            }
        }
        Some(f) => return Err(err(pos, format!("{label} has unknown format \"{f}\""))),
        None => return Err(err(pos, format!("{label} has no format"))),
    };
    Ok(ArrayDecl {
        section,
        name,
        scalar,
        components,
        format,
        text: Vec::new(),
        pos,
    })
}

/// Scans the XML of `bytes` (a whole `.vtu` file).
pub fn scan(bytes: &[u8]) -> Result<Header<'_>, XmlError> {
    let mut reader = quick_xml::Reader::from_reader(bytes);
    reader.config_mut().trim_text(false);
    let mut stack: Vec<Vec<u8>> = Vec::new();
    let mut layout = None;
    let mut piece: Option<(usize, usize)> = None;
    let mut arrays: Vec<ArrayDecl> = Vec::new();
    // Depth of the DataArray element currently open (whose direct text is its data).
    let mut open_array: Option<usize> = None;
    let mut appended = None;
    loop {
        let before = reader.buffer_position() as usize;
        let event = reader
            .read_event()
            .map_err(|e| err(reader.error_position() as usize, format!("XML error: {e}")))?;
        let pos = reader.buffer_position() as usize;
        let (start, empty) = match &event {
            Event::Start(e) => (Some(e), false),
            Event::Empty(e) => (Some(e), true),
            _ => (None, false),
        };
        if let Some(e) = start {
            let name = e.name().as_ref().to_vec();
            let path: Vec<&[u8]> = stack.iter().map(Vec::as_slice).collect();
            match (path.as_slice(), name.as_slice()) {
                ([], b"VTKFile") => layout = Some(file_attributes(e, before)?),
                ([], _) => {
                    return Err(err(
                        before,
                        format!(
                            "the root element is <{}>, not <VTKFile>: not a VTK XML file",
                            tag_name(e)
                        ),
                    ));
                }
                ([b"VTKFile"], b"AppendedData") => {
                    appended = Some(appended_section(e, bytes, pos, before)?);
                    break;
                }
                ([b"VTKFile", b"UnstructuredGrid"], b"Piece") => {
                    if piece.is_some() {
                        return Err(err(
                            before,
                            "the file has several pieces; mtcut reads single-piece .vtu files \
                             (merge the pieces first, e.g. with ParaView's Merge Blocks)",
                        ));
                    }
                    piece = Some((
                        count_attr(e, "NumberOfPoints", before)?,
                        count_attr(e, "NumberOfCells", before)?,
                    ));
                }
                ([b"VTKFile", b"UnstructuredGrid", b"Piece", sec], b"DataArray") => {
                    if let Some(section) = Section::from_tag(sec) {
                        arrays.push(data_array(e, section, before)?);
                        if !empty {
                            open_array = Some(stack.len() + 1);
                        }
                    }
                }
                _ => {}
            }
            if !empty {
                stack.push(name);
            }
            continue;
        }
        match event {
            Event::End(_) => {
                if open_array == Some(stack.len()) {
                    open_array = None;
                }
                stack.pop();
            }
            Event::Text(t) if open_array == Some(stack.len()) => {
                if let Some(a) = arrays.last_mut() {
                    a.text.push(t.into_inner());
                }
            }
            Event::CData(t) if open_array == Some(stack.len()) => {
                if let Some(a) = arrays.last_mut() {
                    a.text.push(t.into_inner());
                }
            }
            Event::Eof => {
                if !stack.is_empty() {
                    return Err(err(pos, "truncated file: the XML ends inside an element"));
                }
                break;
            }
            _ => {}
        }
    }
    let layout = layout.ok_or_else(|| err(0, "no <VTKFile> element: not a VTK XML file"))?;
    let (n_points, n_cells) =
        piece.ok_or_else(|| err(bytes.len(), "no <UnstructuredGrid><Piece> element"))?;
    Ok(Header {
        layout,
        n_points,
        n_cells,
        arrays,
        appended,
    })
}

fn file_attributes(e: &BytesStart, pos: usize) -> Result<Layout, XmlError> {
    match attr(e, "type", pos)?.as_deref() {
        Some("UnstructuredGrid") => {}
        Some(t) => {
            return Err(err(
                pos,
                format!(
                    "this is a VTK {t} file; mtcut reads tetrahedral UnstructuredGrid (.vtu) files"
                ),
            ));
        }
        None => return Err(err(pos, "<VTKFile> has no type attribute")),
    }
    let order = match attr(e, "byte_order", pos)?.as_deref() {
        None | Some("LittleEndian") => ByteOrder::Little,
        Some("BigEndian") => ByteOrder::Big,
        Some(o) => return Err(err(pos, format!("unknown byte_order \"{o}\""))),
    };
    let header = match attr(e, "header_type", pos)?.as_deref() {
        None | Some("UInt32") => HeaderType::U32,
        Some("UInt64") => HeaderType::U64,
        Some(h) => {
            return Err(err(
                pos,
                format!("unknown header_type \"{h}\" (UInt32 or UInt64)"),
            ));
        }
    };
    let compressor = match attr(e, "compressor", pos)? {
        None => Compressor::None,
        Some(c) => Compressor::from_name(&c)
            .ok_or_else(|| err(pos, format!("unknown compressor \"{c}\"")))?,
    };
    Ok(Layout {
        header,
        order,
        compressor,
    })
}

fn appended_section(
    e: &BytesStart,
    bytes: &[u8],
    after_tag: usize,
    pos: usize,
) -> Result<Appended, XmlError> {
    let base64 = match attr(e, "encoding", pos)?.as_deref() {
        Some("raw") => false,
        Some("base64") => true,
        Some(x) => {
            return Err(err(
                pos,
                format!("<AppendedData> has unknown encoding \"{x}\""),
            ));
        }
        None => return Err(err(pos, "<AppendedData> has no encoding")),
    };
    let rest = bytes.get(after_tag..).unwrap_or(&[]);
    let marker = rest
        .iter()
        .position(|c| !c.is_ascii_whitespace())
        .filter(|&i| rest[i] == b'_')
        .ok_or_else(|| {
            err(
                after_tag,
                "<AppendedData> does not start with the '_' marker",
            )
        })?;
    let start = after_tag + marker + 1;
    let end = if base64 {
        start
            + bytes[start..]
                .iter()
                .position(|&c| c == b'<' || c.is_ascii_whitespace())
                .unwrap_or(bytes.len() - start)
    } else {
        bytes.len()
    };
    Ok(Appended { base64, start, end })
}
