//! The vocabulary of VTK's XML format that reader and writer share: scalar types, byte
//! order, the size header of binary data, and the block compressors.

/// VTK's cell type number for a linear tetrahedron (`VTK_TETRA`).
pub const VTK_TETRA: u8 = 10;

/// Bytes per block before compression: VTK's own default (`vtkXMLWriter::BlockSize`).
pub const BLOCK_SIZE: usize = 1 << 15;

/// The scalar type of a `DataArray` (its `type` attribute).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F32,
    F64,
}

impl Scalar {
    /// The type named by a `type` attribute; VTK's legacy names (`Int`, `Float`, ...) as
    /// well, which old writers still use.
    pub fn from_name(name: &str) -> Option<Scalar> {
        Some(match name {
            "Int8" | "Char" => Scalar::I8,
            "UInt8" | "UnsignedChar" => Scalar::U8,
            "Int16" | "Short" => Scalar::I16,
            "UInt16" | "UnsignedShort" => Scalar::U16,
            "Int32" | "Int" => Scalar::I32,
            "UInt32" | "UnsignedInt" => Scalar::U32,
            "Int64" | "Long" | "LongLong" | "IdType" => Scalar::I64,
            "UInt64" | "UnsignedLong" | "UnsignedLongLong" => Scalar::U64,
            "Float32" | "Float" => Scalar::F32,
            "Float64" | "Double" => Scalar::F64,
            _ => return None,
        })
    }

    pub fn name(self) -> &'static str {
        match self {
            Scalar::I8 => "Int8",
            Scalar::U8 => "UInt8",
            Scalar::I16 => "Int16",
            Scalar::U16 => "UInt16",
            Scalar::I32 => "Int32",
            Scalar::U32 => "UInt32",
            Scalar::I64 => "Int64",
            Scalar::U64 => "UInt64",
            Scalar::F32 => "Float32",
            Scalar::F64 => "Float64",
        }
    }

    /// Bytes per value.
    pub fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::I64 | Scalar::U64 | Scalar::F64 => 8,
        }
    }
}

/// The `byte_order` of binary data.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ByteOrder {
    Little,
    Big,
}

/// The integer type of the size headers in front of binary data (`header_type`; VTK
/// assumes `UInt32` when the attribute is missing).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HeaderType {
    U32,
    U64,
}

impl HeaderType {
    pub fn size(self) -> usize {
        match self {
            HeaderType::U32 => 4,
            HeaderType::U64 => 8,
        }
    }
}

/// How binary data blocks are compressed (`compressor`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compressor {
    None,
    /// `vtkZLibDataCompressor`: each block a zlib stream.
    Zlib,
    /// `vtkLZ4DataCompressor`: each block a raw LZ4 block (no frame).
    Lz4,
    /// `vtkLZMADataCompressor`: each block an `.xz` stream.
    Lzma,
}

impl Compressor {
    pub fn from_name(name: &str) -> Option<Compressor> {
        Some(match name {
            "" => Compressor::None,
            "vtkZLibDataCompressor" => Compressor::Zlib,
            "vtkLZ4DataCompressor" => Compressor::Lz4,
            "vtkLZMADataCompressor" => Compressor::Lzma,
            _ => return None,
        })
    }

    pub fn name(self) -> &'static str {
        match self {
            Compressor::None => "",
            Compressor::Zlib => "vtkZLibDataCompressor",
            Compressor::Lz4 => "vtkLZ4DataCompressor",
            Compressor::Lzma => "vtkLZMADataCompressor",
        }
    }

    /// What a message calls it.
    pub fn label(self) -> &'static str {
        match self {
            Compressor::None => "uncompressed",
            Compressor::Zlib => "zlib",
            Compressor::Lz4 => "LZ4",
            Compressor::Lzma => "LZMA",
        }
    }

    /// An upper bound of uncompressed / compressed size for one block. For zlib (deflate:
    /// 1032) and LZ4 (255) these are the formats' own limits; for LZMA a generous bound
    /// above what liblzma reaches on constant data (about 6,500 on 16 MiB of zeros). A
    /// header claiming more is corrupt; checking it first keeps a damaged header from
    /// making the reader allocate far more memory than the file could ever hold.
    pub fn max_ratio(self) -> usize {
        match self {
            Compressor::None => 1,
            Compressor::Zlib => 1032,
            Compressor::Lz4 => 256,
            Compressor::Lzma => 1 << 14,
        }
    }
}

/// The name of a VTK cell type, for messages about cells that are not tetrahedra.
pub fn cell_type_name(t: i64) -> &'static str {
    match t {
        1 => "VTK_VERTEX",
        2 => "VTK_POLY_VERTEX",
        3 => "VTK_LINE",
        4 => "VTK_POLY_LINE",
        5 => "VTK_TRIANGLE",
        6 => "VTK_TRIANGLE_STRIP",
        7 => "VTK_POLYGON",
        8 => "VTK_PIXEL",
        9 => "VTK_QUAD",
        10 => "VTK_TETRA",
        11 => "VTK_VOXEL",
        12 => "VTK_HEXAHEDRON",
        13 => "VTK_WEDGE",
        14 => "VTK_PYRAMID",
        21 => "VTK_QUADRATIC_EDGE",
        22 => "VTK_QUADRATIC_TRIANGLE",
        23 => "VTK_QUADRATIC_QUAD",
        24 => "VTK_QUADRATIC_TETRA",
        25 => "VTK_QUADRATIC_HEXAHEDRON",
        42 => "VTK_POLYHEDRON",
        71 => "VTK_LAGRANGE_TETRAHEDRON",
        _ => "an unknown cell type",
    }
}
