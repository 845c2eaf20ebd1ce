//! Ready-made 2D shapes built with the multi-block generator ([`super::multiblock`]).
//!
//! Lengths are in any consistent unit (the examples use mm). `kind` is one of `Quad4`, `Quad8`,
//! `Tri3`, `Tri6`. All cells are counter-clockwise; facet groups are oriented outward and each
//! has a node group of the same name.

use std::f64::consts::FRAC_1_SQRT_2;
use std::sync::Arc;

use super::multiblock::{Block, Curve, Prepared, distribution, multiblock};
use crate::{CellType, Mesh, MeshError};

pub(super) fn positive(name: &str, v: f64) -> Result<(), MeshError> {
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

/// Mirror image of a block in the plane x = 0 (the generator re-orders it counter-clockwise),
/// with `_left` and `_right` swapped in its edge group names.
fn mirror_x(b: &Block) -> Block {
    mirror_x_renamed(b, &|n: &str| {
        n.replace("_right", "\u{0}")
            .replace("_left", "_right")
            .replace('\u{0}', "_left")
    })
}

/// Mirror image of a block in the plane x = 0, its cell and edge group names passed through
/// `rename`.
pub(super) fn mirror_x_renamed(b: &Block, rename: &dyn Fn(&str) -> String) -> Block {
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
    out.edge_groups = b.edge_groups.clone().map(|g| g.map(|n| rename(&n)));
    out.cell_group = b.cell_group.as_ref().map(|n| rename(n));
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
/// Mesh: the root is two blocks per half (flank trapezoid, shank); each half of the disk is
/// four blocks (the lobe beside the flank, the lobe beside the slot wall, and two blocks below
/// the slot) meeting at the fillet's mid-point, where the fillet is not tangent to a block edge.
/// The wall/fillet and fillet/bottom junctions are mesh nodes, and the cells along the slot
/// bottom shrink toward the fillet to about the size of those on the wall. With the default
/// counts all corner angles are within 50-130 degrees.
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
    // The fillet: centre oc, from C = (wb, ys + rf) (end of the straight wall) to
    // D = (wb - rf, ys) (start of the flat bottom); P = its mid-point, where the blocks meet
    // (splitting at D would give a block corner of ~0 degrees, the fillet being tangent there).
    let oc = [wb - rf, ys + rf];
    let c45 = std::f64::consts::FRAC_1_SQRT_2;
    let pm = [oc[0] + rf * c45, oc[1] - rf * c45];
    let d = [wb - rf, ys];
    let k = side(norm(b));
    let l = side(norm(pm));
    let f = side(p.r_rim);
    let g = side(p.r_inner);
    let mx = pm[0];
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
    let quarter = std::f64::consts::FRAC_PI_4;
    // Upper slot edge B -> C -> P (wall, upper half of the fillet); lower edge P -> D -> E
    // (lower half of the fillet, flat bottom). Both by arc length.
    // Cells along P -> E shrink toward the fillet down to about the size of those along B -> P.
    let upper_len = (p.slot_gap - rf) + quarter * rf;
    let lower_len = quarter * rf + (wb - rf);
    let g_slot = grading_for_last(p.n_slot, lower_len, upper_len / p.n_wall as f64);
    // Node parameters along the two edges: B -> P is uniform (t of the lower lobe block, whose
    // edge 3 runs backwards: same set), P -> E is s of the inner block reversed.
    let upper_nodes = distribution(p.n_wall, 1.0);
    let lower_nodes: Vec<f64> = distribution(p.n_slot, g_slot)
        .iter()
        .rev()
        .map(|s| 1.0 - s)
        .collect();
    let upper = path(
        vec![
            Prepared::Line(b, [wb, ys + rf]),
            Prepared::Arc {
                c: oc,
                r: rf,
                th0: 0.0,
                sweep: -quarter,
            },
        ],
        &upper_nodes,
    );
    let lower = path(
        vec![
            Prepared::Arc {
                c: oc,
                r: rf,
                th0: -quarter,
                sweep: -quarter,
            },
            Prepared::Line(d, e),
        ],
        &lower_nodes,
    );
    // Disk, right half.
    let lobe_up = Block::new([b, k, f, a], [p.n_lobe, p.n_flank])
        .edge(2, origin_arc(p.r_rim, true))
        .group("disk")
        .edge_group(1, "disk_side_right")
        .edge_group(2, "disk_rim")
        .edge_group(3, "flank_right_disk");
    let lobe_low = Block::new([pm, l, k, b], [p.n_lobe, p.n_wall])
        .edge(3, upper)
        .group("disk")
        .edge_group(1, "disk_side_right")
        .edge_group(3, "slot");
    let below_out = Block::new([m, g, l, pm], [p.n_lobe, p.n_below])
        .edge(0, origin_arc(p.r_inner, false))
        .group("disk")
        .edge_group(0, "disk_bottom")
        .edge_group(1, "disk_side_right");
    // Corners E, H, M, P so that s runs from the axis to the fillet (graded).
    let below_in = Block::new([h, m, pm, e], [p.n_slot, p.n_below])
        .edge(0, origin_arc(p.r_inner, false))
        .edge(2, lower)
        .grading(g_slot, 1.0)
        .group("disk")
        .edge_group(0, "disk_bottom")
        .edge_group(2, "slot");
    let right = [lobe_up, lobe_low, below_out, below_in];
    let mut disk_blocks: Vec<Block> = right.iter().map(mirror_x).collect();
    disk_blocks.extend(right);
    let mut mesh = multiblock(&disk_blocks, kind)?;
    // Split the free slot surface: the flat bottom (y = ys, |x| <= wb - rf) and the rest (walls
    // and fillets).
    let slot = mesh.facet_groups.remove("slot").unwrap_or_default();
    mesh.node_groups.remove("slot");
    let tol = 1e-9 * p.r_rim;
    let (flat, fillet): (Vec<_>, Vec<_>) = slot.into_iter().partition(|fc| {
        fc.nodes.iter().all(|&n| {
            let x = mesh.coords[n];
            (x[1] - ys).abs() <= tol && x[0].abs() <= wb - rf + tol
        })
    });
    for (name, facets) in [("slot_bottom", flat), ("slot_fillet", fillet)] {
        let nodes: Vec<usize> = facets.iter().flat_map(|fc| fc.nodes.clone()).collect();
        mesh.add_nodes_to_group(name, nodes);
        mesh.add_facets_to_group(name, facets);
    }
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

/// A parametric curve through consecutive segments (lines and arcs; zero-length ones dropped), uniform in arc
/// length within each segment. The junctions between segments are moved to the nearest of the
/// parameters `nodes` (increasing, from 0 to 1: where the mesh will have nodes) so that they
/// are mesh nodes (no cell straddles a change of curvature), when there are enough of them;
/// otherwise the curve is uniform in arc length overall.
fn path(segs: Vec<Prepared>, nodes: &[f64]) -> Curve {
    let (segs, lens): (Vec<Prepared>, Vec<f64>) = segs
        .into_iter()
        .filter_map(|s| s.length().filter(|&l| l > 0.0).map(|l| (s, l)))
        .unzip();
    let total: f64 = lens.iter().sum();
    // Breakpoints u_k of the segments: arc-length fractions, snapped to node parameters.
    let mut breaks = vec![0.0];
    let mut acc = 0.0;
    let inner: Vec<f64> = nodes
        .iter()
        .copied()
        .filter(|&u| u > 0.0 && u < 1.0)
        .collect();
    let mut next_free = 0;
    let mut snapped = inner.len() + 1 >= segs.len();
    for l in &lens[..lens.len().saturating_sub(1)] {
        acc += l;
        let frac = acc / total;
        // Nearest unused inner node parameter, leaving enough for the remaining junctions.
        let remaining = segs.len() - breaks.len() - 1;
        let hi = inner.len().saturating_sub(remaining);
        match (next_free..hi)
            .min_by(|&i, &j| (inner[i] - frac).abs().total_cmp(&(inner[j] - frac).abs()))
        {
            Some(i) if snapped => {
                breaks.push(inner[i]);
                next_free = i + 1;
            }
            _ => {
                snapped = false;
                breaks.push(frac);
            }
        }
    }
    breaks.push(1.0);
    if !snapped {
        breaks.clear();
        let mut acc = 0.0;
        breaks.push(0.0);
        for l in &lens {
            acc += l;
            breaks.push(acc / total);
        }
    }
    Curve::Param(Arc::new(move |u: f64| {
        let u = u.clamp(0.0, 1.0);
        let last = segs.len() - 1;
        let i = (0..=last).find(|&i| u <= breaks[i + 1]).unwrap_or(last);
        let w = (u - breaks[i]) / (breaks[i + 1] - breaks[i]);
        segs[i].eval(w.clamp(0.0, 1.0))
    }))
}

/// The grading (ratio last / first cell size) of `n` cells over a length `len` whose last cell
/// has about the size `last` (1 if uniform cells are already that small).
fn grading_for_last(n: usize, len: f64, last: f64) -> f64 {
    if n < 2 || len / n as f64 <= last {
        return 1.0;
    }
    let last_of = |g: f64| {
        let r = g.powf(1.0 / (n as f64 - 1.0));
        let first = len * (r - 1.0) / (r.powi(n as i32) - 1.0);
        first * r.powi(n as i32 - 1)
    };
    let (mut lo, mut hi) = (1e-3, 1.0 - 1e-12);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if last_of(mid) > last {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    lo
}
