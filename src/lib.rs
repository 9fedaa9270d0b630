//! # mtcut — multiresolution tetrahedral meshes that can be cut
//!
//! mtcut implements "Enabling cuts on multiresolution representation" (Ganovelli, Cignoni,
//! Montani, Scopigno, The Visual Computer 17, 2001) for C++ finite-element and
//! surgery-simulation codes, in Rust behind a stable C ABI.
//!
//! ## Pipeline
//!
//! 1. **Read** a tet mesh ([`io`]: TetGen `.node/.ele`, VTK `.vtu`, medit `.mesh`) into a
//!    [`mesh::TetMesh`], checked and repaired (negative tets re-oriented) on the way in.
//! 2. **Build** the Multi-Tessellation: a DAG of fragments recorded while the mesh is
//!    simplified by edge collapses (paper §2).
//! 3. **Extract** conforming meshes at any resolution, per region.
//! 4. **Cut** with planar convex polygons: every tet of every level of detail the polygon
//!    crosses is replaced from look-up tables, and the DAG is updated (paper §3–§4).
//! 5. **Write** `.vtu` for ParaView, or hand the arrays to the host through the C ABI.
//!
//! ## Tolerance model
//!
//! Sign decisions (orientation, side of a plane) are exact ([`geom`]). Closeness decisions
//! (snapping a cut to a vertex, planarity of a polygon) use one relative
//! [`geom::Tolerance`], scaled by a local length; there are no absolute epsilons.
//!
//! ## Layers (dependencies point down only)
//!
//! `geom` (predicates, planes, cutting polygons) ← `mesh` (TetMesh, tables, adjacency,
//! validation) ← `io`, `mt` (the multiresolution model: build, extract, validate, `.mt`
//! files), `cut` (classification, split tables, separation); [`ffi`], the C ABI, sits on top
//! and is the only module allowed `unsafe` code, besides the one call of the CPU's prefetch
//! hint in `cut` (the time-critical cut's). See ARCHITECTURE.md.

#![deny(unsafe_code)]

pub mod cut;
// The C ABI dereferences the caller's pointers: that is its whole job, and only its job.
#[allow(unsafe_code)]
pub mod ffi;
pub mod geom;
pub mod io;
pub mod mesh;
pub mod mt;
mod rng;
