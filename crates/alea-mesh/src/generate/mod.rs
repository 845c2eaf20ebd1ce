//! Mesh generators: structured rectangles and boxes, multi-block mapped quads, multi-block graded
//! hexahedra, ready-made shapes (including the thesis's two blade-root models), two-body contact
//! benchmarks, extrusion (also of the four-part turbine, [`turbine_3d`]).

mod blade_root;
mod extrude;
mod hexblock;
mod multiblock;
mod shapes;
mod structured;
#[cfg(test)]
mod test_checks;
mod turbine;
mod turbine_3d;
mod two_body;

pub use blade_root::{BladeRootParams, blade_root_simple};
pub use extrude::extrude;
pub use hexblock::{
    HexBlock, corner_refined_blocks, first_cell_grading, grading_for_first_cell, multiblock_hex,
};
pub use multiblock::{Block, Curve, CurveFn, multiblock};
pub use shapes::{DovetailParams, annulus_sector, dovetail_root_and_disk, plate_with_hole};
pub use structured::{box_mesh, rectangle};
pub use turbine::{TurbineParams, turbine_2d};
pub use turbine_3d::turbine_3d;
pub use two_body::{
    ConcentricRings, CylinderOnBlock, StackedBlocks, block_on_incline, concentric_rings,
    cylinder_on_block, stacked_blocks,
};
