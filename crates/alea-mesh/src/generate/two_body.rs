//! Two-body meshes for the classic contact benchmarks, with named contact faces whose nodes
//! coincide one to one (what the node-to-node interfaces of `alea-latin` pair):
//!
//! ```text
//!  stacked_blocks                 block_on_incline (the same, rotated by `angle`)
//!  +-----------+ upper_top                      __--+
//!  |   upper   |                          __--    /
//!  +-----------+ upper_bottom      __--+--  upper/
//!  +-----------+ lower_top        +--    \  __--
//!  |   lower   |                   \ lower\-
//!  +-----------+ lower_bottom       \__--
//!
//!  concentric_rings (sector 0 <= theta <= angle)
//!     outer ring: outer_contact (r = r_contact) .. outer_outer (r = r_out)
//!     inner ring: inner_inner (r = r_in) .. inner_contact (r = r_contact)
//! ```
//!
//! - [`stacked_blocks`]: two rectangles `[0, width] x [-h_lower, 0]` and `[0, width] x [0,
//!   h_upper]`, `n_x` cells across both, separate nodes on `y = 0`. Cell groups `lower`,
//!   `upper`; facet and node groups `<body>_bottom`, `<body>_top`, `<body>_left`,
//!   `<body>_right`. Benchmarks: full slip (a block pressed and dragged: the tangential
//!   resultant is `mu` times the normal one), stick/slip thresholds.
//! - [`block_on_incline`]: the same rotated counter-clockwise by `angle` about the origin, so
//!   the contact plane rises at `angle` (NAFEMS CGS-4-like: a block of weight `G` on an incline
//!   pushed by a horizontal force `F` starts to slide up at `F/G = (tan a + mu) / (1 - mu tan
//!   a)`).
//! - [`concentric_rings`]: two annular sectors (exact polar grids) meeting at `r_contact`, the
//!   same `n_theta` on both so the contact arcs match. Cell groups `inner`, `outer`; facet and
//!   node groups `inner_inner`, `inner_contact`, `inner_side0` (`theta = 0`), `inner_side1`
//!   (`theta = angle`), `outer_contact`, `outer_outer`, `outer_side0`, `outer_side1`. With a
//!   negative initial gap `-delta` on the contact it is the shrink fit of Lame's thick
//!   cylinders.
//!
//! - [`cylinder_on_block`]: Hertz's line contact the way a node-to-node interface can take it:
//!   both bodies meshed **flat** on `y = 0` with coincident nodes over `|x| <= a` (uniform
//!   `n x n` cells in an `a x a` square at the contact, graded outward in `m` cells to the far
//!   boundaries `|x| = l`, `y = -l` / `y = +l`), the cylinder's profile entering as the
//!   interface's initial gap `g0(x) = R - sqrt(R^2 - x^2)` - exactly Hertz's half-space model,
//!   valid for a contact half-width `b << R`. Cell groups `block` (`y <= 0`), `cylinder`
//!   (`y >= 0`); facet and node groups `<body>_contact` (`|x| <= a` on `y = 0`), `<body>_free`
//!   (the rest of `y = 0`), `<body>_far` (`y = -l` / `+l`), `<body>_far_side` (`|x| = l`) and,
//!   for the half model `x >= 0`, `<body>_sym` (`x = 0`).

use crate::generate::{Block, annulus_sector, first_cell_grading, multiblock, rectangle};
use crate::{CellType, Mesh, MeshError};

/// Renames every group of `mesh` through `rename` (groups it maps to `None` are dropped).
fn rename_groups(mesh: &mut Mesh, rename: impl Fn(&str) -> Option<String>) {
    let cells = std::mem::take(&mut mesh.cell_groups);
    mesh.cell_groups = cells
        .into_iter()
        .filter_map(|(k, v)| rename(&k).map(|n| (n, v)))
        .collect();
    let facets = std::mem::take(&mut mesh.facet_groups);
    mesh.facet_groups = facets
        .into_iter()
        .filter_map(|(k, v)| rename(&k).map(|n| (n, v)))
        .collect();
    let nodes = std::mem::take(&mut mesh.node_groups);
    mesh.node_groups = nodes
        .into_iter()
        .filter_map(|(k, v)| rename(&k).map(|n| (n, v)))
        .collect();
}

/// Parameters of [`stacked_blocks`] and [`block_on_incline`] (lengths in the user's unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StackedBlocks {
    /// Width of both blocks (x).
    pub width: f64,
    /// Height of the lower block.
    pub h_lower: f64,
    /// Height of the upper block.
    pub h_upper: f64,
    /// Cells across (both blocks, so the contact nodes coincide).
    pub n_x: usize,
    /// Cells up the lower block.
    pub n_lower: usize,
    /// Cells up the upper block.
    pub n_upper: usize,
}

impl Default for StackedBlocks {
    fn default() -> Self {
        StackedBlocks {
            width: 40.0,
            h_lower: 20.0,
            h_upper: 20.0,
            n_x: 16,
            n_lower: 8,
            n_upper: 8,
        }
    }
}

/// Two blocks stacked on `y = 0` (module doc).
///
/// # Errors
/// [`MeshError::Invalid`] for non-positive sizes or counts, or a 3D `kind`.
pub fn stacked_blocks(p: &StackedBlocks, kind: CellType) -> Result<Mesh, MeshError> {
    for (name, v) in [
        ("width", p.width),
        ("h_lower", p.h_lower),
        ("h_upper", p.h_upper),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(MeshError::Invalid(format!(
                "stacked blocks: {name} must be a finite length > 0, got {v}"
            )));
        }
    }
    let body = |h: f64, ny: usize, y0: f64, name: &'static str| -> Result<Mesh, MeshError> {
        let mut m = rectangle(p.width, h, p.n_x, ny, kind)?;
        for x in &mut m.coords {
            x[1] += y0;
        }
        rename_groups(&mut m, |g| {
            Some(match g {
                "domain" => name.to_string(),
                "xmin" => format!("{name}_left"),
                "xmax" => format!("{name}_right"),
                "ymin" => format!("{name}_bottom"),
                "ymax" => format!("{name}_top"),
                _ => return None,
            })
        });
        Ok(m)
    };
    let mut mesh = body(p.h_lower, p.n_lower, -p.h_lower, "lower")?;
    mesh.append(&body(p.h_upper, p.n_upper, 0.0, "upper")?)?;
    Ok(mesh)
}

/// [`stacked_blocks`] rotated counter-clockwise by `angle` (radians) about the origin: the
/// contact plane rises at `angle` (module doc).
///
/// # Errors
/// As [`stacked_blocks`]; `angle` must be in `(-pi/2, pi/2)`.
pub fn block_on_incline(p: &StackedBlocks, angle: f64, kind: CellType) -> Result<Mesh, MeshError> {
    if !(angle.is_finite() && angle.abs() < std::f64::consts::FRAC_PI_2) {
        return Err(MeshError::Invalid(format!(
            "block on incline: the angle must be in (-90, 90) degrees, got {} degrees",
            angle.to_degrees()
        )));
    }
    let mut mesh = stacked_blocks(p, kind)?;
    let (c, s) = (angle.cos(), angle.sin());
    for x in &mut mesh.coords {
        let (a, b) = (x[0], x[1]);
        x[0] = c * a - s * b;
        x[1] = s * a + c * b;
    }
    Ok(mesh)
}

/// Parameters of [`concentric_rings`] (lengths in the user's unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConcentricRings {
    /// Inner radius of the inner ring.
    pub r_in: f64,
    /// Radius of the contact (outer radius of the inner ring, inner radius of the outer one).
    pub r_contact: f64,
    /// Outer radius of the outer ring.
    pub r_out: f64,
    /// Opening of the sector (radians), `< 2 pi`.
    pub angle: f64,
    /// Cells across the inner ring.
    pub n_inner: usize,
    /// Cells across the outer ring.
    pub n_outer: usize,
    /// Cells around (both rings).
    pub n_theta: usize,
}

impl Default for ConcentricRings {
    fn default() -> Self {
        ConcentricRings {
            r_in: 50.0,
            r_contact: 80.0,
            r_out: 120.0,
            angle: std::f64::consts::FRAC_PI_2,
            n_inner: 8,
            n_outer: 8,
            n_theta: 16,
        }
    }
}

/// Two concentric annular sectors meeting at `r_contact` (module doc).
///
/// # Errors
/// [`MeshError::Invalid`] unless `0 < r_in < r_contact < r_out`, `0 < angle < 2 pi` and the
/// counts are positive.
pub fn concentric_rings(p: &ConcentricRings, kind: CellType) -> Result<Mesh, MeshError> {
    if !(p.r_in > 0.0 && p.r_in < p.r_contact && p.r_contact < p.r_out && p.r_out.is_finite()) {
        return Err(MeshError::Invalid(format!(
            "concentric rings need 0 < r_in < r_contact < r_out, got {}, {}, {}",
            p.r_in, p.r_contact, p.r_out
        )));
    }
    let ring =
        |r0: f64, r1: f64, n: usize, name: &'static str, lo: &'static str, hi: &'static str| {
            let mut m = annulus_sector(r0, r1, p.angle, n, p.n_theta, kind)?;
            rename_groups(&mut m, |g| {
                Some(match g {
                    "domain" => name.to_string(),
                    "inner" => format!("{name}_{lo}"),
                    "outer" => format!("{name}_{hi}"),
                    "side0" => format!("{name}_side0"),
                    "side1" => format!("{name}_side1"),
                    _ => return None,
                })
            });
            Ok::<Mesh, MeshError>(m)
        };
    let mut mesh = ring(p.r_in, p.r_contact, p.n_inner, "inner", "inner", "contact")?;
    mesh.append(&ring(
        p.r_contact,
        p.r_out,
        p.n_outer,
        "outer",
        "contact",
        "outer",
    )?)?;
    Ok(mesh)
}

/// Parameters of [`cylinder_on_block`] (lengths in the user's unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CylinderOnBlock {
    /// Half-length of the refined contact strip (and depth of the fine square); choose
    /// `a ~ 2 b` for a Hertz half-width `b`.
    pub a: f64,
    /// Half-size of each body (`l >> b`, e.g. `25 b`).
    pub l: f64,
    /// Cells across the fine square (`h = a / n`).
    pub n: usize,
    /// Graded cells from the fine square to the far boundaries.
    pub m: usize,
    /// Half model `x >= 0` (with `<body>_sym` groups on `x = 0`).
    pub half: bool,
}

impl Default for CylinderOnBlock {
    fn default() -> Self {
        CylinderOnBlock {
            a: 2.0,
            l: 25.0,
            n: 40,
            m: 30,
            half: true,
        }
    }
}

/// A cylinder on a block, meshed flat with coincident contact nodes (module doc).
///
/// # Errors
/// [`MeshError::Invalid`] unless `0 < a`, `l > a + m h` (the outer cells are coarser than the
/// fine ones) and the counts are positive.
pub fn cylinder_on_block(p: &CylinderOnBlock, kind: CellType) -> Result<Mesh, MeshError> {
    let (a, l, n, m) = (p.a, p.l, p.n, p.m);
    if !(a > 0.0 && l.is_finite() && n > 0 && m > 0 && l - a > m as f64 * a / n as f64) {
        return Err(MeshError::Invalid(format!(
            "cylinder on block needs a > 0, n, m >= 1 and l - a > m a / n (outer cells coarser than the contact cells), got a = {a}, l = {l}, n = {n}, m = {m}"
        )));
    }
    let g = first_cell_grading(l - a, a / n as f64, m);
    let body = |upper: bool| -> Result<Mesh, MeshError> {
        let name = if upper { "cylinder" } else { "block" };
        let group = |s: &str| format!("{name}_{s}");
        let mut inner = Block::new([[0.0, -a], [a, -a], [a, 0.0], [0.0, 0.0]], [n, n])
            .group(name)
            .edge_group(2, &group("contact"));
        let right = Block::new([[a, -a], [l, -l], [l, 0.0], [a, 0.0]], [m, n])
            .grading(g, 1.0)
            .group(name)
            .edge_group(1, &group("far_side"))
            .edge_group(2, &group("free"));
        let mut below = Block::new([[0.0, -l], [l, -l], [a, -a], [0.0, -a]], [n, m])
            .grading(1.0, 1.0 / g)
            .group(name)
            .edge_group(0, &group("far"));
        if p.half {
            inner = inner.edge_group(3, &group("sym"));
            below = below.edge_group(3, &group("sym"));
        }
        let mut blocks = vec![inner, right, below];
        let map = |b: &Block, f: &dyn Fn([f64; 2]) -> [f64; 2]| {
            let mut out = b.clone();
            out.corners = b.corners.map(f);
            out
        };
        if !p.half {
            let mirrored: Vec<Block> = blocks.iter().map(|b| map(b, &|q| [-q[0], q[1]])).collect();
            blocks.extend(mirrored);
        }
        if upper {
            blocks = blocks.iter().map(|b| map(b, &|q| [q[0], -q[1]])).collect();
        }
        multiblock(&blocks, kind)
    };
    let mut mesh = body(false)?;
    mesh.append(&body(true)?)?;
    Ok(mesh)
}
