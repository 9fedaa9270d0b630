//! VTK XML UnstructuredGrid (`.vtu`) files holding tetrahedra: reader and writer.
//!
//! Both are this crate's own code, not vtkio's (0.7.0-rc2), for every variant:
//! * vtkio cannot read raw appended data, the default of ParaView's writer;
//! * where it can read (ASCII, base64), it was slower on fandisk-1m (inline base64 + zlib:
//!   216 ms to vtkio's own model, before any copy into a `TetMesh`, against about 150 ms
//!   for this reader's whole decoding, one thread each), and it panics on a compressed
//!   array with no blocks, which VTK writes for empty arrays;
//! * one reader for all encodings keeps one set of checks and messages.
//!
//! Only the XML part of a file goes through an XML parser (quick-xml); appended data is
//! located by offsets, so raw binary never meets the parser. The writer converts values to
//! bytes block by block inside a parallel compression pass (rayon), so no full byte copy of
//! an array is made, and VTK 9.1 reads everything it writes (tests/io_vtk.rs).
//!
//! * [`format`](mod@format): scalar types, byte order, headers, compressors.
//! * [`binary`]: base64, size headers, compressed blocks (both directions).
//! * [`xml`]: the scan of the XML part.
//! * [`values`]: typed conversions of array bytes.

mod binary;
mod format;
mod read;
mod values;
mod write;
mod xml;

pub use read::{parse_vtu, read_vtu};
pub use write::{VtuCompression, VtuEncoding, VtuOptions, encode_vtu, write_vtu};
