//! Ready-made 2D shapes built with the multi-block generator ([`super::multiblock`]).
//!
//! Lengths are in any consistent unit (the examples use mm). `kind` is one of `Quad4`, `Quad8`,
//! `Tri3`, `Tri6`. All cells are counter-clockwise; facet groups are oriented outward and each
//! has a node group of the same name.

use std::f64::consts::FRAC_1_SQRT_2;

use super::multiblock::{Block, Curve, multiblock};
use crate::{CellType, Mesh, MeshError};

fn positive(name: &str, v: f64) -> Result<(), MeshError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(MeshError::Invalid(format!(
            "{name} must be positive and finite, got {v}"
        )))
    }
}

/// Quarter of a square plate `[0, L]^2` (`L = half_width`) with a circular hole of radius
/// `a = radius` centred at the origin: the symmetric quarter of the Kirsch problem.
///
/// ```text
///  y
///  L +-----------------+        two blocks split by the diagonal from (a/sqrt2, a/sqrt2) to (L, L);
///    |  top         .  |        n_arc cells along the quarter arc (n_arc / 2 in the lower block,
///    |           .     |        the rest in the upper one), n_radial cells from the hole to the
///  xsym       .        | right  outer edges in both blocks.
///    |     .           |
///  a +.                |
///    |  '. hole        |
///    +----+------------+ x
///    0    a  ysym      L
/// ```
/// `grading` is the ratio of the outermost to the innermost radial cell size (> 1 refines toward
/// the hole; about `L / a` gives cells of nearly constant aspect ratio along the radius).
///
/// Groups: cell group `"domain"`; facet (and node) groups `"hole"` (the arc), `"xsym"` (edge on
/// x = 0, the symmetry plane normal to x), `"ysym"` (edge on y = 0), `"right"` (x = L), `"top"`
/// (y = L).
///
/// # Errors
/// [`MeshError::Invalid`] unless `0 < radius < half_width`, `n_arc >= 2`, `n_radial >= 1`,
/// `grading > 0`, and `kind` is 2D.
pub fn plate_with_hole(
    radius: f64,
    half_width: f64,
    n_arc: usize,
    n_radial: usize,
    grading: f64,
    kind: CellType,
) -> Result<Mesh, MeshError> {
    positive("radius", radius)?;
    positive("half_width", half_width)?;
    positive("grading", grading)?;
    if radius >= half_width {
        return Err(MeshError::Invalid(format!(
            "the hole radius {radius} must be smaller than the half width {half_width}"
        )));
    }
    if n_arc < 2 || n_radial < 1 {
        return Err(MeshError::Invalid(format!(
            "plate_with_hole needs n_arc >= 2 and n_radial >= 1, got {n_arc} and {n_radial}"
        )));
    }
    let (a, l) = (radius, half_width);
    let d = a * FRAC_1_SQRT_2;
    let n_low = n_arc / 2;
    let n_up = n_arc - n_low;
    let arc = Curve::Arc {
        center: [0.0, 0.0],
        radius: a,
        ccw: false,
    };
    // Lower block: s radial (hole -> outside), t from angle 0 to 45 degrees.
    let lower = Block::new([[a, 0.0], [l, 0.0], [l, l], [d, d]], [n_radial, n_low])
        .edge(3, arc.clone())
        .grading(grading, 1.0)
        .group("domain")
        .edge_group(0, "ysym")
        .edge_group(1, "right")
        .edge_group(3, "hole");
    // Upper block: s radial along the diagonal, t from 45 to 90 degrees.
    let upper = Block::new([[d, d], [l, l], [0.0, l], [0.0, a]], [n_radial, n_up])
        .edge(3, arc)
        .grading(grading, 1.0)
        .group("domain")
        .edge_group(1, "top")
        .edge_group(2, "xsym")
        .edge_group(3, "hole");
    multiblock(&[lower, upper], kind)
}

/// Annular sector `r_in <= r <= r_out`, `0 <= theta <= angle_rad` (centre at the origin, first
/// side along +x), `n_radial x n_theta` cells (an exact polar grid: the Coons patch of two
/// concentric arcs and two radial segments).
///
/// ```text
///            side1 (theta = angle)
///              \
///        outer  \____
///          .-'   \   '.
///       .'   inner\    \
///      +-----------+----+--- x
///      0    side0  r_in r_out
/// ```
/// Groups: cell group `"domain"`; facet (and node) groups `"inner"` (r = r_in), `"outer"`
/// (r = r_out), `"side0"` (theta = 0), `"side1"` (theta = angle).
///
/// # Errors
/// [`MeshError::Invalid`] unless `0 < r_in < r_out`, `0 < angle_rad < 2 pi`, counts >= 1 and
/// `kind` is 2D.
pub fn annulus_sector(
    r_in: f64,
    r_out: f64,
    angle_rad: f64,
    n_radial: usize,
    n_theta: usize,
    kind: CellType,
) -> Result<Mesh, MeshError> {
    positive("r_in", r_in)?;
    positive("r_out", r_out)?;
    positive("angle_rad", angle_rad)?;
    if r_in >= r_out || angle_rad >= 2.0 * std::f64::consts::PI {
        return Err(MeshError::Invalid(format!(
            "annulus_sector needs r_in < r_out and angle < 2 pi, got r_in = {r_in}, r_out = {r_out}, angle = {angle_rad}"
        )));
    }
    if n_radial < 1 || n_theta < 1 {
        return Err(MeshError::Invalid(format!(
            "annulus_sector needs at least one cell per direction, got {n_radial} x {n_theta}"
        )));
    }
    let (c, s) = (angle_rad.cos(), angle_rad.sin());
    let block = Block::new(
        [
            [r_in, 0.0],
            [r_out, 0.0],
            [r_out * c, r_out * s],
            [r_in * c, r_in * s],
        ],
        [n_radial, n_theta],
    )
    .edge(
        1,
        Curve::Arc {
            center: [0.0, 0.0],
            radius: r_out,
            ccw: true,
        },
    )
    .edge(
        3,
        Curve::Arc {
            center: [0.0, 0.0],
            radius: r_in,
            ccw: false,
        },
    )
    .group("domain")
    .edge_group(0, "side0")
    .edge_group(1, "outer")
    .edge_group(2, "side1")
    .edge_group(3, "inner");
    multiblock(&[block], kind)
}
