//! VTK XML UnstructuredGrid (`.vtu`) files holding tetrahedra: reader and writer.
//!
//! The reader is this crate's own code for every variant, not vtkio's: vtkio 0.7.0-rc2
//! cannot read raw appended data (ParaView's default), and it panics on files VTK writes
//! (a compressed array with no blocks) and on damaged data, where a reader must answer
//! with a message. Only the XML part of a file goes through an XML parser (quick-xml);
//! appended data is located by offsets, so raw binary never meets the parser.
//!
//! The writer is ours too, for speed: values are converted to bytes block by block inside
//! a parallel compression pass (rayon), so no full byte copy of an array is ever made.
//!
//! * [`format`]: scalar types, byte order, headers, compressors.
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
