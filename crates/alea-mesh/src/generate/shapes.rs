//! Ready-made 2D shapes built with the multi-block generator ([`super::multiblock`]).
//!
//! Lengths are in any consistent unit (the examples use mm). `kind` is one of `Quad4`, `Quad8`,
//! `Tri3`, `Tri6`. All cells are counter-clockwise; facet groups are oriented outward and each
//! has a node group of the same name.

use std::f64::consts::FRAC_1_SQRT_2;
use std::sync::Arc;

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

/// Mirror image of a block in the plane x = 0 (the generator re-orders it counter-clockwise).
fn mirror_x(b: &Block) -> Block {
    let m = |p: [f64; 2]| [-p[0], p[1]];
    let mut out = b.clone();
    out.corners = b.corners.map(m);
    for (e, src) in out.edges.iter_mut().zip(&b.edges) {
        *e = match src {
            Curve::Line => Curve::Line,
            Curve::Arc {
                center,
                radius,
                ccw,
            } => Curve::Arc {
                center: m(*center),
                radius: *radius,
                ccw: !ccw,
            },
            Curve::ArcThrough(p) => Curve::ArcThrough(m(*p)),
            Curve::Polyline(p) => Curve::Polyline(p.iter().map(|&q| m(q)).collect()),
            Curve::Spline(p) => Curve::Spline(p.iter().map(|&q| m(q)).collect()),
            Curve::Param(f) => {
                let f = f.clone();
                Curve::Param(Arc::new(move |u| m(f(u))))
            }
        };
    }
    let swap = |s: &Option<String>| {
        s.as_ref().map(|n| {
            n.replace("_right", "\u{0}")
                .replace("_left", "_right")
                .replace('\u{0}', "_left")
        })
    };
    out.edge_groups = b.edge_groups.clone().map(|g| swap(&g));
    out
}

/// Geometry and mesh density of [`dovetail_root_and_disk`]. Lengths in mm in the default
/// (any consistent unit works), angles in radians.
#[derive(Clone, Debug, PartialEq)]
pub struct DovetailParams {
    /// Inner radius of the disk sector (the "disk_bottom" arc). Default 170.
    pub r_inner: f64,
    /// Outer (rim) radius of the disk. Default 200.
    pub r_rim: f64,
    /// Half angle of the disk sector (pi / number of blades). Default pi/24 (24 blades, 7.5 deg).
    pub half_angle: f64,
    /// Half width of the root at the neck, where the flanks meet the rim. Default 8.
    pub neck_half_width: f64,
    /// Half width of the root at its bottom (wider than the neck: a dovetail). Default 16.
    pub bottom_half_width: f64,
    /// Radial height of the flanks (contact faces), from the root bottom to the neck. Default 12.
    pub flank_height: f64,
    /// Radial gap between the root bottom and the slot bottom. Default 4.
    pub slot_gap: f64,
    /// Radius of the fillet between the slot wall and the slot bottom (0: sharp corner;
    /// at most `slot_gap`). Default 2.5.
    pub fillet_radius: f64,
    /// Height of the root's shank above the neck, up to the loaded "root_top". Default 15.
    pub shank_height: f64,
    /// Cells along each flank (the contact faces). Default 8.
    pub n_flank: usize,
    /// Cells across half the root. Default 4.
    pub n_root: usize,
    /// Cells along the shank height. Default 5.
    pub n_shank: usize,
    /// Cells across a disk lobe (from the flank to the sector side). Default 4.
    pub n_lobe: usize,
    /// Cells along the slot wall and its fillet. Default 4.
    pub n_wall: usize,
    /// Cells across half the slot bottom. Default 5.
    pub n_slot: usize,
    /// Cells from the slot bottom down to the inner radius. Default 6.
    pub n_below: usize,
}

impl Default for DovetailParams {
    fn default() -> Self {
        DovetailParams {
            r_inner: 170.0,
            r_rim: 200.0,
            half_angle: std::f64::consts::PI / 24.0,
            neck_half_width: 8.0,
            bottom_half_width: 16.0,
            flank_height: 12.0,
            slot_gap: 4.0,
            fillet_radius: 2.5,
            shank_height: 15.0,
            n_flank: 8,
            n_root: 4,
            n_shank: 5,
            n_lobe: 4,
            n_wall: 4,
            n_slot: 5,
            n_below: 6,
        }
    }
}

impl DovetailParams {
    /// The same geometry with every cell count multiplied by `factor`.
    pub fn refined(&self, factor: usize) -> Self {
        let f = factor.max(1);
        DovetailParams {
            n_flank: self.n_flank * f,
            n_root: self.n_root * f,
            n_shank: self.n_shank * f,
            n_lobe: self.n_lobe * f,
            n_wall: self.n_wall * f,
            n_slot: self.n_slot * f,
            n_below: self.n_below * f,
            ..self.clone()
        }
    }
}

/// A 2D dovetail blade root seated in the slot of a disk sector: two separate parts whose
/// flanks touch with **distinct, coincident nodes** (the interface is not merged).
///
/// The disk's centre is the origin; the blade axis is +y; the sector spans
/// `|angle from +y| <= half_angle`. Right half (the left one is its mirror image):
///
/// ```text
///  y                 root_top
///  ^             +------+------+            shank: half width w_n, height shank_height
///  |  root_sides |      |      |
///  |   disk_rim  |      |      |  disk_rim
///  |  .---------A+------+------+A---------.F    A = (w_n, sqrt(r_rim^2 - w_n^2)), on the rim
///  |  |          \  root       /          |     flanks A-B: "flank_right_root" (root side)
///  |  |  disk     \           /   disk    |             and "flank_right_disk" (disk side)
///  |  |  lobe      \         /    lobe    | K   B = (w_b, y_A - flank_height)
///  |  |            B+---+---+B            |     root_bottom B-B (free: gap below)
///  |  |             | slot  |  (wall)     |     slot wall B-C, fillet C-D of radius r_f,
///  |  |             `.__+__.' D (fillet)  | L   slot bottom D-D at y_B - slot_gap
///  |  |                 |                 |     disk_side_right: radial line F-G at angle
///  |  |   disk          |                 |       half_angle from +y (normal constraint)
///  |  '-----------------+-----------------' G   disk_bottom: arc r = r_inner
///  |      disk_bottom   H
///  +------------------------------------> x
/// ```
/// Default geometry (mm): r_inner 170, r_rim 200, half angle 7.5 deg (24 blades), neck half
/// width 8, bottom half width 16, flank height 12 (flank angle atan(8/12) = 33.7 deg from the
/// radial direction), slot gap 4, fillet radius 2.5, shank height 15. Root area
/// (w_n + w_b) h_f + 2 w_n h_s = 528 mm^2.
///
/// Groups:
/// - cell groups `"root"` and `"disk"` (separate substructures: use [`Mesh::extract`]);
/// - contact facet groups `"flank_left_root"`, `"flank_right_root"` (root side, outward from the
///   root) and `"flank_left_disk"`, `"flank_right_disk"` (disk side, outward from the disk), with
///   node for node coincident (but distinct) nodes on each flank;
/// - root: `"root_top"` (y = y_A + shank_height: blade load), `"root_sides"` (shank sides),
///   `"root_bottom"` (free, facing the slot bottom across the gap);
/// - disk: `"disk_side_left"`, `"disk_side_right"` (the sector's radial symmetry sides),
///   `"disk_bottom"` (r = r_inner), `"disk_rim"` (r = r_rim, free), `"slot_fillet"` (slot walls
///   and fillets, free), `"slot_bottom"` (free).
///
/// Every facet group has a node group of the same name.
///
/// # Errors
/// [`MeshError::Invalid`] for non-positive or inconsistent dimensions (the neck must be narrower
/// than the bottom, the root must fit in the sector, the fillet radius must not exceed the
/// slot gap or the bottom half width, the slot bottom must stay outside `r_inner`), zero counts,
/// or a non-2D `kind`.
pub fn dovetail_root_and_disk(p: &DovetailParams, kind: CellType) -> Result<Mesh, MeshError> {
    for (name, v) in [
        ("r_inner", p.r_inner),
        ("r_rim", p.r_rim),
        ("half_angle", p.half_angle),
        ("neck_half_width", p.neck_half_width),
        ("bottom_half_width", p.bottom_half_width),
        ("flank_height", p.flank_height),
        ("slot_gap", p.slot_gap),
        ("shank_height", p.shank_height),
    ] {
        positive(name, v)?;
    }
    let counts = [
        p.n_flank, p.n_root, p.n_shank, p.n_lobe, p.n_wall, p.n_slot, p.n_below,
    ];
    if counts.contains(&0) {
        return Err(MeshError::Invalid(format!(
            "dovetail cell counts must be >= 1, got {counts:?}"
        )));
    }
    let bad = |m: String| Err(MeshError::Invalid(format!("dovetail geometry: {m}")));
    let (wn, wb, rf) = (p.neck_half_width, p.bottom_half_width, p.fillet_radius);
    if p.half_angle >= std::f64::consts::FRAC_PI_4 {
        return bad(format!("half_angle {} must be below pi/4", p.half_angle));
    }
    if wn >= wb {
        return bad(format!(
            "the neck half width {wn} must be smaller than the bottom half width {wb}"
        ));
    }
    if !(rf.is_finite() && rf >= 0.0 && rf <= p.slot_gap && rf < wb) {
        return bad(format!(
            "fillet radius {rf} must be in [0, min(slot_gap, bottom_half_width))"
        ));
    }
    if wn >= p.r_rim {
        return bad("the neck is wider than the rim radius".into());
    }
    let ya = (p.r_rim * p.r_rim - wn * wn).sqrt();
    let yb = ya - p.flank_height;
    let ys = yb - p.slot_gap;
    let yt = ya + p.shank_height;
    let (sa, ca) = p.half_angle.sin_cos();
    let side = |r: f64| [r * sa, r * ca];
    let norm = |q: [f64; 2]| q[0].hypot(q[1]);
    let a = [wn, ya];
    let b = [wb, yb];
    let d = [wb - rf, ys];
    let k = side(norm(b));
    let l = side(norm(d));
    let f = side(p.r_rim);
    let g = side(p.r_inner);
    let mx = wb - rf;
    if p.r_inner <= mx {
        return bad(format!(
            "r_inner {} must exceed the slot half width {mx}",
            p.r_inner
        ));
    }
    let m = [mx, (p.r_inner * p.r_inner - mx * mx).sqrt()];
    let h = [0.0, p.r_inner];
    let e = [0.0, ys];
    // The root must fit in the sector with room for a lobe, and the slot above r_inner.
    let margin = 0.05 * wb;
    if k[0] - wb < margin || l[0] - wb < margin || f[0] - wn < margin {
        return bad(format!(
            "the root (bottom half width {wb}) does not fit in the sector: its side is at x = {:.3} at the root bottom",
            k[0]
        ));
    }
    if ys - m[1] < 0.05 * p.slot_gap.max(p.flank_height) {
        return bad(format!(
            "the slot bottom (y = {ys:.3}) must lie well above the inner radius {}",
            p.r_inner
        ));
    }
    let origin_arc = |r: f64, ccw: bool| Curve::Arc {
        center: [0.0, 0.0],
        radius: r,
        ccw,
    };
    // Slot wall B -> C then fillet C -> D, by arc length.
    let wall = if rf == 0.0 {
        Curve::Line
    } else {
        let lw = p.slot_gap - rf;
        let lf = std::f64::consts::FRAC_PI_2 * rf;
        let oc = [wb - rf, ys + rf];
        Curve::Param(Arc::new(move |u: f64| {
            let s = u * (lw + lf);
            if s <= lw {
                [wb, yb - s]
            } else {
                let phi = (s - lw) / rf;
                [oc[0] + rf * phi.cos(), oc[1] - rf * phi.sin()]
            }
        }))
    };
    // Disk, right half.
    let lobe_up = Block::new([b, k, f, a], [p.n_lobe, p.n_flank])
        .edge(2, origin_arc(p.r_rim, true))
        .group("disk")
        .edge_group(1, "disk_side_right")
        .edge_group(2, "disk_rim")
        .edge_group(3, "flank_right_disk");
    let lobe_low = Block::new([d, l, k, b], [p.n_lobe, p.n_wall])
        .edge(3, wall)
        .group("disk")
        .edge_group(1, "disk_side_right")
        .edge_group(3, "slot_fillet");
    let below_out = Block::new([m, g, l, d], [p.n_lobe, p.n_below])
        .edge(0, origin_arc(p.r_inner, false))
        .group("disk")
        .edge_group(0, "disk_bottom")
        .edge_group(1, "disk_side_right");
    let below_in = Block::new([h, m, d, e], [p.n_slot, p.n_below])
        .edge(0, origin_arc(p.r_inner, false))
        .group("disk")
        .edge_group(0, "disk_bottom")
        .edge_group(2, "slot_bottom");
    let right = [lobe_up, lobe_low, below_out, below_in];
    let mut disk_blocks: Vec<Block> = right.iter().map(mirror_x).collect();
    disk_blocks.extend(right);
    let mut mesh = multiblock(&disk_blocks, kind)?;
    // Root, right half.
    let q0 = [0.0, yb];
    let n0 = [0.0, ya];
    let flank = Block::new([q0, b, a, n0], [p.n_root, p.n_flank])
        .group("root")
        .edge_group(0, "root_bottom")
        .edge_group(1, "flank_right_root");
    let shank = Block::new([n0, a, [wn, yt], [0.0, yt]], [p.n_root, p.n_shank])
        .group("root")
        .edge_group(1, "root_sides")
        .edge_group(2, "root_top");
    let right = [flank, shank];
    let mut root_blocks: Vec<Block> = right.iter().map(mirror_x).collect();
    root_blocks.extend(right);
    let root = multiblock(&root_blocks, kind)?;
    mesh.append(&root)?;
    Ok(mesh)
}
