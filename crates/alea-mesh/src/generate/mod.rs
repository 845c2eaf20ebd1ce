//! Mesh generators: structured rectangles and boxes, multi-block mapped quads, ready-made shapes
//! (including the thesis's two blade-root models), extrusion.

mod blade_root;
mod extrude;
mod multiblock;
mod shapes;
mod structured;
mod turbine;

pub use blade_root::{BladeRootParams, blade_root_simple};
pub use extrude::extrude;
pub use multiblock::{Block, Curve, CurveFn, multiblock};
pub use shapes::{DovetailParams, annulus_sector, dovetail_root_and_disk, plate_with_hole};
pub use structured::{box_mesh, rectangle};
pub use turbine::{TurbineParams, turbine_2d};
