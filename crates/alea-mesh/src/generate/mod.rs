//! Mesh generators: structured rectangles and boxes, multi-block mapped quads, extrusion.

mod structured;

pub use structured::{box_mesh, rectangle};
