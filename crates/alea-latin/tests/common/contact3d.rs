//! Meshes for the point-contact tests (Hertz and Cattaneo-Mindlin spheres): bodies whose contact
//! faces are meshed **flat** on `z = 0` with node-for-node coincident nodes over the fine square
//! `[0, a]^2` (quarter model) or `[-a, a] x [0, a]` (half model), graded outward to the far
//! faces (`alea_mesh::generate::corner_refined_blocks`); the sphere's curvature goes into the
//! initial gap `g0 = r^2 / (2 R)` of the interface (see the test headers).
//!
//! ```text
//!   z = +l  +-----------far_z-----------+   upper body ("sphere") = mirror image in z = 0
//!           |         .      .          |
//!   z = 0   +==contact==+-----free------+   <- fine cube [0, a]^3 (h = a / n) under it,
//!           |  cube   '     frustum     |      graded frusta around it (m cells outward)
//!           |     .         -z          |
//!   z = -l  +-----------far_z-----------+   lower body ("flat")
//!          x=0          a               l
//! ```
//! Groups of each body: cell group `"body"`; facet/node groups `"contact"`, `"free"` (the rest
//! of `z = 0`), `"far_x"`, `"far_y"`, `"far_z"`, `"sym_y"` (`y = 0`) and, for the quarter
//! model, `"sym_x"` (`x = 0`; the half model spans `-l <= x <= l`, its far faces in x are both
//! `"far_x"`).

use alea_mesh::generate::{HexBlock, corner_refined_blocks, multiblock_hex};
use alea_mesh::{CellType, Mesh};

/// Mesh layout.
#[derive(Clone, Copy, Debug)]
pub struct PointLayout {
    /// Size of the fine cube around the contact.
    pub a: f64,
    /// Size of each body.
    pub l: f64,
    /// Cells across the fine cube (`h = a / n`).
    pub n: usize,
    /// Cells of the graded frusta.
    pub m: usize,
    /// Quarter model `x, y >= 0` (`true`) or half model `y >= 0` (`false`).
    pub quarter: bool,
}

impl PointLayout {
    /// Fine cell size.
    pub fn h(&self) -> f64 {
        self.a / self.n as f64
    }

    fn blocks(&self, upper: bool) -> Vec<HexBlock> {
        let mut blocks = corner_refined_blocks(self.a, self.l, self.n, self.m).unwrap();
        if !self.quarter {
            for b in blocks.iter_mut() {
                for g in b.face_groups.iter_mut() {
                    if g.as_deref() == Some("sym_x") {
                        *g = None;
                    }
                }
            }
            let mirrored: Vec<HexBlock> = blocks
                .iter()
                .map(|b| b.mapped(|x| [-x[0], x[1], x[2]]))
                .collect();
            blocks.extend(mirrored);
        }
        if upper {
            blocks = blocks
                .iter()
                .map(|b| b.mapped(|x| [x[0], x[1], -x[2]]))
                .collect();
        }
        blocks
    }

    /// The lower body (`z <= 0`).
    pub fn lower(&self) -> Mesh {
        multiblock_hex(&self.blocks(false)).unwrap()
    }

    /// The upper body (`z >= 0`).
    pub fn upper(&self) -> Mesh {
        multiblock_hex(&self.blocks(true)).unwrap()
    }

    /// A thin slab of one layer of cells of thickness `t` under the fine square only
    /// (`z in [-t, 0]`), with the same contact grid: groups `"contact"` (top), `"base"`
    /// (bottom), `"sym_x"` and `"sym_y"`.
    pub fn slab(&self, t: f64) -> Mesh {
        let x0 = if self.quarter { 0.0 } else { -self.a };
        let nx = if self.quarter { self.n } else { 2 * self.n };
        let b = HexBlock::cuboid([x0, 0.0, -t], [self.a, self.a, 0.0], [nx, self.n, 1])
            .group("body")
            .face_group(2, "sym_y")
            .face_group(4, "base")
            .face_group(5, "contact");
        let b = if self.quarter {
            b.face_group(0, "sym_x")
        } else {
            b
        };
        let m = multiblock_hex(&[b]).unwrap();
        debug_assert!(m.cell_types_present() == vec![CellType::Hex8]);
        m
    }
}
