//! The thesis's simple blade-root / disk assembly (chapter 2.3): a dovetail root `S2` held
//! between two disk parts `S1` (left) and `S3` (right) by two inclined contact faces
//! (flanks) `G1 = S1-S2` and `G2 = S2-S3`. The thesis does not give dimensions; ours (mm):
//!
//! ```text
//!                     S2_left  +------+  S2_top (y = h + hs)
//!                              |  S2  |  S2_right
//!  (-W,h) +--------------------+------+--------------------+ (W,h)
//!         |  S1_top       (-n,h)      (n,h)        S3_top  |
//!  S1_left|   S1         G1  /  S2     \  G2          S3   | S3_right
//!         |                 /           \                  |
//!  (-W,0) +----------------+-------------+-----------------+ (W,0)
//!          S1_bottom   (-b,0)  S2_bottom  (b,0)   S3_bottom
//! ```
//! Defaults: `W = 35`, `b = 15` (root bottom half width), `n = 8` (neck half width), `h = 10`
//! (flank height), `hs = 15` (shank height): the flanks make 35 degrees with the vertical.
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
    /// Half width of the whole assembly (outer faces of S1 and S3 at x = -W, W). Default 35.
    pub half_width: f64,
    /// Half width of the root's bottom face. Default 15.
    pub bottom_half_width: f64,
    /// Half width of the root at the neck. Default 8.
    pub neck_half_width: f64,
    /// Height of the flanks. Default 10.
    pub flank_height: f64,
    /// Height of the root's shank above the disk parts. Default 15.
    pub shank_height: f64,
    /// Cells along each flank. Default 16.
    pub n_flank: usize,
    /// Cells across each disk part. Default 20.
    pub n_side: usize,
    /// Cells across the root. Default 16.
    pub n_root: usize,
    /// Cells along the shank. Default 12.
    pub n_shank: usize,
}

impl Default for BladeRootParams {
    fn default() -> Self {
        BladeRootParams {
            half_width: 35.0,
            bottom_half_width: 15.0,
            neck_half_width: 8.0,
            flank_height: 10.0,
            shank_height: 15.0,
            n_flank: 16,
            n_side: 20,
            n_root: 16,
            n_shank: 12,
        }
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

    #[test]
    fn parts_areas_and_coincident_flanks() {
        let p = BladeRootParams::default();
        for kind in [CellType::Quad4, CellType::Quad8] {
            let m = blade_root_simple(&p, kind).unwrap();
            let area = |g: &str| -> f64 {
                m.cell_group(g)
                    .unwrap()
                    .iter()
                    .map(|&c| m.cell_measure(c))
                    .sum()
            };
            let (w, b, n, h, hs) = (35.0, 15.0, 8.0, 10.0, 15.0);
            let side = w * h - 0.5 * (b + n) * h;
            assert!((area("S1") - side).abs() < 1e-9 * side);
            assert!((area("S3") - side).abs() < 1e-9 * side);
            let root = (b + n) * h + 2.0 * n * hs;
            assert!((area("S2") - root).abs() < 1e-9 * root);
            // Flanks: same positions on both sides, distinct nodes.
            for (a, c) in [("G1_disk", "G1_root"), ("G2_root", "G2_disk")] {
                let na = m.group_nodes(a).unwrap();
                let nc = m.group_nodes(c).unwrap();
                assert_eq!(na.len(), nc.len());
                assert!(na.iter().all(|x| !nc.contains(x)));
                for &i in &na {
                    let d = nc
                        .iter()
                        .map(|&j| {
                            let (u, v) = (m.coords[i], m.coords[j]);
                            ((u[0] - v[0]).powi(2) + (u[1] - v[1]).powi(2)).sqrt()
                        })
                        .fold(f64::INFINITY, f64::min);
                    assert!(d < 1e-12, "{a}: node {i} has no partner on {c}");
                }
            }
            // Positive Jacobians everywhere.
            for c in 0..m.num_cells() {
                assert!(m.cell_min_jacobian(c) > 0.0);
            }
        }
    }
}
