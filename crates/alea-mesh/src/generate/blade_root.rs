//! The thesis's simple blade-root / disk assembly (chapter 2.3, figure 2.9): a dovetail root
//! `S2` held between two disk parts `S1` (left) and `S3` (right) by two inclined contact faces
//! (flanks) `G1 = S1-S2` and `G2 = S2-S3`. The thesis gives no dimensions; ours (mm):
//!
//! ```text
//!                       S2_left  +--------+  S2_top (y = h + hs)
//!                                |   S2   |  S2_right
//!   (-W,h) +---------------------+--------+---------------------+ (W,h)
//!          |  S1_top        (-n,h)        (n,h)         S3_top  |
//!          |                   /            \                   |
//!   S1_left|  S1          G1  /      S2      \  G2         S3   | S3_right
//!          |                 /   45 deg  --> |\ <-- flank angle |
//!          |                (                 )  <- root corners rounded, radius r_c
//!   (-W,0) +---------------+-----------------+------------------+ (W,0)
//!           S1_bottom  (-b,0)   S2_bottom   (b,0)   S3_bottom
//! ```
//! Defaults: `W = 38`, `b = 18` (root bottom half width), `n = 8` (neck half width), `h = 10`
//! (flank height), `hs = 15` (shank height): the flanks make `alpha = atan((b - n) / h) = 45`
//! degrees with the vertical and are `h / cos(alpha) = 14.14` long.
//!
//! **Why this geometry.** With the thesis's loads (pressure `p` on the root's bottom face, the
//! same pressure `F` pushing on both shank sides) the root is pushed up its flanks and held by
//! the wedge. Over the thesis's laws (`mu ~ TN(0.5, 0.2)` on `[0.1, 0.9]`, `E2 ~ TN(240e3,
//! 10e3)` on `[210e3, 270e3]`) the flanks slide over their whole contact zone for `mu <= 0.7`
//! and a stick zone opens in their middle from `mu ~ 0.75` (the thesis's "stick at high mu,
//! slip held by the geometry at low mu"). The friction work on a flank rises with `mu` while
//! the root slides, then drops where it sticks: coefficient of variation 0.40 over the laws
//! (thesis: 0.23), its mean and std measured in `examples/blade-root-simple-comparison.toml`.
//! A steeper flank (35 degrees) keeps the flanks sliding at every `mu <= 0.9` (no stick); a
//! flatter one (50 degrees) sticks from `mu ~ 0.6` and the work varies by a factor 4.
//!
//! **Rounded root corners.** Each root bottom corner (angle `90 - alpha` degrees) is rounded
//! with a radius `r_c` (1 mm in the examples). The rounding is not meshed: like the thesis's
//! shape defects (2.2.3.2) it enters the contact law as an initial normal gap along the flank,
//! the parabolic approximation of the arc tangent to the flank at `d = r_c / tan((90 - alpha) /
//! 2)` from the corner (`d = 2.414 r_c` at 45 degrees):
//! `g0(s) = max(0, d - s)^2 / (2 r_c)`, `s = y / cos(alpha)` the distance from the root's bottom
//! corner along the flank. Without it the sharp root corner bears on the disk's corner at a
//! single node: a point contact whose force and slip follow the mesh (the work at `mu = 0.9`
//! moved by 2.5 % between the 2x and 4x refinements of the examples' mesh, not monotonically).
//! With it the contact zone ends on the flank itself, where the pressure falls to zero.
//!
//! The parts are meshed separately (multi-block, straight edges, uniform spacing) and appended
//! without merging: the flanks carry **distinct, coincident** nodes on each side, ready for
//! node-to-node contact interfaces.
//!
//! Groups: cells `S1`, `S2`, `S3`; facets (and nodes) `S1_bottom`, `S1_left`, `S1_top`,
//! `G1_disk` (S1's flank), `G1_root`, `G2_root` (S2's flanks), `S2_bottom`, `S2_left`,
//! `S2_right`, `S2_top`, `G2_disk` (S3's flank), `S3_bottom`, `S3_right`, `S3_top`.

use crate::generate::{Block, multiblock};
use crate::{CellType, Mesh, MeshError};

/// Dimensions and cell counts of [`blade_root_simple`].
#[derive(Clone, Debug, PartialEq)]
pub struct BladeRootParams {
    /// Half width of the whole assembly (outer faces of S1 and S3 at x = -W, W). Default 38.
    pub half_width: f64,
    /// Half width of the root's bottom face. Default 18.
    pub bottom_half_width: f64,
    /// Half width of the root at the neck. Default 8.
    pub neck_half_width: f64,
    /// Height of the flanks. Default 10.
    pub flank_height: f64,
    /// Height of the root's shank above the disk parts. Default 15.
    pub shank_height: f64,
    /// Cells along each flank. Default 36.
    pub n_flank: usize,
    /// Cells across each disk part. Default 45.
    pub n_side: usize,
    /// Cells across the root. Default 36.
    pub n_root: usize,
    /// Cells along the shank. Default 27.
    pub n_shank: usize,
}

impl Default for BladeRootParams {
    fn default() -> Self {
        BladeRootParams {
            half_width: 38.0,
            bottom_half_width: 18.0,
            neck_half_width: 8.0,
            flank_height: 10.0,
            shank_height: 15.0,
            n_flank: 36,
            n_side: 45,
            n_root: 36,
            n_shank: 27,
        }
    }
}

impl BladeRootParams {
    /// Angle of the flanks with the vertical, `atan((b - n) / h)` (radians).
    pub fn flank_angle(&self) -> f64 {
        ((self.bottom_half_width - self.neck_half_width) / self.flank_height).atan()
    }

    /// Distance from a root bottom corner, along the flank, at which an arc of radius
    /// `corner_radius` rounding that corner is tangent to the flank:
    /// `r_c / tan((pi/2 - alpha) / 2)`.
    pub fn corner_tangency(&self, corner_radius: f64) -> f64 {
        corner_radius / (0.5 * (std::f64::consts::FRAC_PI_2 - self.flank_angle())).tan()
    }
}

/// Meshes the three parts. `kind` is `Quad4`, `Quad8`, `Tri3` or `Tri6`.
///
/// # Errors
/// [`MeshError::Invalid`] if the dimensions are not positive, the root is not a dovetail
/// (`neck < bottom < W`), or a count is zero.
pub fn blade_root_simple(p: &BladeRootParams, kind: CellType) -> Result<Mesh, MeshError> {
    let (w, b, n, h, hs) = (
        p.half_width,
        p.bottom_half_width,
        p.neck_half_width,
        p.flank_height,
        p.shank_height,
    );
    let ok = [w, b, n, h, hs].iter().all(|v| v.is_finite() && *v > 0.0) && n < b && b < w;
    if !ok {
        return Err(MeshError::Invalid(format!(
            "blade root: need 0 < neck ({n}) < bottom ({b}) < half width ({w}) and positive heights ({h}, {hs})"
        )));
    }
    if [p.n_flank, p.n_side, p.n_root, p.n_shank].contains(&0) {
        return Err(MeshError::Invalid(
            "blade root: cell counts must be positive".into(),
        ));
    }
    let s1 = multiblock(
        &[Block::new(
            [[-w, 0.0], [-b, 0.0], [-n, h], [-w, h]],
            [p.n_side, p.n_flank],
        )
        .group("S1")
        .edge_group(0, "S1_bottom")
        .edge_group(1, "G1_disk")
        .edge_group(2, "S1_top")
        .edge_group(3, "S1_left")],
        kind,
    )?;
    let s2 = multiblock(
        &[
            Block::new(
                [[-b, 0.0], [b, 0.0], [n, h], [-n, h]],
                [p.n_root, p.n_flank],
            )
            .group("S2")
            .edge_group(0, "S2_bottom")
            .edge_group(1, "G2_root")
            .edge_group(3, "G1_root"),
            Block::new(
                [[-n, h], [n, h], [n, h + hs], [-n, h + hs]],
                [p.n_root, p.n_shank],
            )
            .group("S2")
            .edge_group(1, "S2_right")
            .edge_group(2, "S2_top")
            .edge_group(3, "S2_left"),
        ],
        kind,
    )?;
    let s3 = multiblock(
        &[
            Block::new([[b, 0.0], [w, 0.0], [w, h], [n, h]], [p.n_side, p.n_flank])
                .group("S3")
                .edge_group(0, "S3_bottom")
                .edge_group(1, "S3_right")
                .edge_group(2, "S3_top")
                .edge_group(3, "G2_disk"),
        ],
        kind,
    )?;
    let mut mesh = s1;
    mesh.append(&s2)?;
    mesh.append(&s3)?;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::test_checks::{assert_coincident, group_measure};

    #[test]
    fn default_flanks_are_at_45_degrees_and_the_corner_arc_is_tangent_where_stated() {
        let p = BladeRootParams::default();
        assert!((p.flank_angle().to_degrees() - 45.0).abs() < 1e-12);
        // An arc of radius r inscribed in the corner of angle theta = 90 - alpha touches both
        // sides at r / tan(theta / 2) from the vertex: 2.414 r at 45 degrees.
        assert!((p.corner_tangency(1.0) - (1.0 + 2f64.sqrt())).abs() < 1e-12);
    }

    #[test]
    fn parts_areas_and_coincident_flanks() {
        let p = BladeRootParams {
            n_flank: 16,
            n_side: 20,
            n_root: 16,
            n_shank: 12,
            ..BladeRootParams::default()
        };
        for kind in [CellType::Quad4, CellType::Quad8] {
            let m = blade_root_simple(&p, kind).unwrap();
            let area = |g: &str| group_measure(&m, g);
            let (w, b, n, h, hs) = (38.0, 18.0, 8.0, 10.0, 15.0);
            let side = w * h - 0.5 * (b + n) * h;
            assert!((area("S1") - side).abs() < 1e-9 * side);
            assert!((area("S3") - side).abs() < 1e-9 * side);
            let root = (b + n) * h + 2.0 * n * hs;
            assert!((area("S2") - root).abs() < 1e-9 * root);
            // Flanks: same positions on both sides, distinct nodes.
            for (a, c) in [("G1_disk", "G1_root"), ("G2_root", "G2_disk")] {
                assert_coincident(&m, a, c, 1e-12, true);
            }
            // Positive Jacobians everywhere.
            for c in 0..m.num_cells() {
                assert!(m.cell_min_jacobian(c) > 0.0);
            }
        }
    }
}
