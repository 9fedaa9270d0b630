//! Cutting tetrahedral meshes with planar convex polygons (paper §3–§4).
pub mod bielser;
pub mod bvh;
pub mod classify;
pub mod components;
pub mod cutter;
pub mod options;
pub mod report;
pub mod split;
pub mod table_gen;
pub mod tables;
pub mod unglue;

pub use classify::{CutScratch, CutSession, TetClass, VertexOrigin};
pub use components::Components;
pub use cutter::{CUT_COLUMN, Cutter, cut_mesh, vertex_scales};
pub use options::{CutError, CutOptions, Scheme};
pub use report::{CutResult, CutStats, CutTimes, SplitRecord};
pub use tables::{CutCase, Side};
