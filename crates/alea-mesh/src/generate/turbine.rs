//! The thesis's 2D turbine blade root / disk model (5.2.3, figure 5.11) in four substructures:
//! disk halves `D1` (x < 0), `D2` (x > 0) and blade-root halves `A1`, `A2`, with the contact
//! lines `I1 = D1-A1`, `I2 = D2-A2` and the perfect interfaces `D1-D2`, `A1-A2` on x = 0.
//!
//! The disk's centre is the origin, the blade axis is +y, the sector spans `|angle from +y| <=
//! half_angle`. Right half (the left one is its mirror image, numbers 2 -> 1):
//!
//! ```text
//!  y                A2_top
//!  ^            +-----+-----+             shank: half width w_n, height shank_height
//!  |    A2_side |  A1 | A2  |
//!  |    D2_rim  |     |     |  D2_rim
//!  |   .-------A+-----+-----+A-------.F   A = (w_n, sqrt(r_rim^2 - w_n^2)), on the rim
//!  |   |        \     |     /        |    A-B: contact line I2 (I2_root / I2_disk), length
//!  |   |   D1    \    |    /   D2    |         contact_length, at flank_angle from +y
//!  |   |          +---+---+B         | K  B-B': D2_runout, free flank below the contact
//!  |   |              |    \ B'      |    B'-C: D2_fillet, the slot fillet (radius r_f,
//!  |   |        A2_bottom  ( P       | L         tangent to the flank and to the bottom:
//!  |   |              | .__.' C      |         the highest-curvature zone)
//!  |   |              |E  D2_slot_bottom     C-E: slot bottom; E-H: D1-D2 cut (D2_cut)
//!  |   |              |              |    D2_side: sector side F-G (normal constraint)
//!  |   '--------------+--------------' G  D2_bottom: arc r = r_inner (fixed)
//!  |                  H
//!  +----------------------------------> x
//! ```
//! The flank is a straight line from the neck `A` on the rim, going down and out at
//! `flank_angle` from +y. The root touches it over `contact_length` (A to B, where the root's
//! bottom corner is); the disk's flank runs on for `runout` (B to B') and turns into the slot
//! bottom through a circular fillet of radius `fillet_radius` tangent to both (B' to C, a turn
//! of 90 degrees + `flank_angle`): the disk's slot has **no corner** (its only corners are on
//! the rim and the sector sides), so the von Mises stress on the fillet is finite and
//! mesh-converging. The root's bottom (at B's height) clears the fillet, which stays below it.
//!
//! Defaults (mm): r_inner 170, r_rim 200, half angle 7.5 degrees (24 blades), neck half width
//! 8, flank angle 35 degrees, contact length 8 (the thesis's contact line x in [7, 15] mm),
//! runout 2, fillet radius 3, shank height 15.
//!
//! Mesh: with the default counts and `Quad8` cells, 22 364 dof (5 396 per disk half, 5 786
//! per root half: the thesis's 5 400 and 5 800). Per half, the disk is four mapped blocks (the lobe beside the contact, the lobe
//! beside the runout and the upper half of the fillet, and two blocks below the slot, meeting
//! at the fillet's mid-point P); the root is two (the flank trapezoid and the shank). The cells
//! shrink toward the slot surface (gradings `lobe_grading`, `below_grading`). The halves are
//! meshed separately and appended: the cut x = 0 and the contact lines carry **distinct,
//! coincident** nodes, ready for node-to-node interfaces.
//!
//! Groups (each facet group also as a node group of the same name):
//! - cells `D1`, `D2`, `A1`, `A2`;
//! - contact lines `I1_disk`, `I1_root`, `I2_disk`, `I2_root` (outward from their part);
//! - cuts on x = 0: `D1_cut`, `D2_cut`, `A1_cut`, `A2_cut`;
//! - disk: `D*_side` (sector sides), `D*_bottom` (r = r_inner), `D*_rim`, `D*_runout`,
//!   `D*_fillet`, `D*_slot_bottom`;
//! - root: `A*_top` (blade load), `A*_side` (shank sides), `A*_bottom` (facing the slot).

use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::Arc;

use super::multiblock::{Block, Curve, multiblock};
use super::shapes::{mirror_x_renamed, positive};
use crate::{CellType, Facet, Mesh, MeshError};

/// Geometry and mesh density of [`turbine_2d`]. Lengths in mm in the defaults (any
/// consistent unit works), angles in radians.
#[derive(Clone, Debug, PartialEq)]
pub struct TurbineParams {
    /// Inner radius of the disk sector (fixed). Default 170.
    pub r_inner: f64,
    /// Rim radius. Default 200.
    pub r_rim: f64,
    /// Half angle of the sector. Default pi/24 (7.5 degrees).
    pub half_angle: f64,
    /// Half width of the root at the neck, on the rim. Default 8.
    pub neck_half_width: f64,
    /// Angle of the flanks with the blade axis (radians). Default 35 degrees.
    pub flank_angle: f64,
    /// Length of each contact line (from the neck to the root's bottom corner). Default 8.
    pub contact_length: f64,
    /// Free length of the disk's flank below the contact, before the fillet. Default 2.
    pub runout: f64,
    /// Radius of the slot fillet. Default 3.
    pub fillet_radius: f64,
    /// Height of the root's shank above the rim. Default 15.
    pub shank_height: f64,
    /// Cells along each contact line. Default 24.
    pub n_flank: usize,
    /// Cells along each runout. Default 6.
    pub n_runout: usize,
    /// Cells along each fillet (even). Default 18.
    pub n_fillet: usize,
    /// Cells across each disk lobe, from the slot to the sector side. Default 12.
    pub n_lobe: usize,
    /// Cells along each half slot bottom. Default 8.
    pub n_slot: usize,
    /// Cells from the slot down to the inner radius. Default 13.
    pub n_below: usize,
    /// Cells across each root half. Default 20.
    pub n_root: usize,
    /// Cells along the shank. Default 22.
    pub n_shank: usize,
    /// Ratio of the cell sizes at the sector side and at the slot, across the lobes. Default 4.
    pub lobe_grading: f64,
    /// Ratio of the cell sizes at the inner radius and at the slot, below it. Default 4.
    pub below_grading: f64,
}

impl Default for TurbineParams {
    fn default() -> Self {
        TurbineParams {
            r_inner: 170.0,
            r_rim: 200.0,
            half_angle: PI / 24.0,
            neck_half_width: 8.0,
            flank_angle: 35f64.to_radians(),
            contact_length: 8.0,
            runout: 2.0,
            fillet_radius: 3.0,
            shank_height: 15.0,
            n_flank: 24,
            n_runout: 6,
            n_fillet: 18,
            n_lobe: 12,
            n_slot: 8,
            n_below: 13,
            n_root: 20,
            n_shank: 22,
            lobe_grading: 4.0,
            below_grading: 4.0,
        }
    }
}

/// Key points of the right half.
#[derive(Clone, Copy, Debug)]
struct Points {
    a: [f64; 2],
    b: [f64; 2],
    bp: [f64; 2],
    centre: [f64; 2],
    p: [f64; 2],
    c: [f64; 2],
    e: [f64; 2],
    ys: f64,
    /// Angles of B', P and C on the fillet circle.
    th: [f64; 3],
}

impl TurbineParams {
    /// The neck point `A` on the rim (right half).
    pub fn neck(&self) -> [f64; 2] {
        let w = self.neck_half_width;
        [w, (self.r_rim * self.r_rim - w * w).sqrt()]
    }

    /// The root's bottom corner `B`, end of the right contact line.
    pub fn contact_end(&self) -> [f64; 2] {
        let a = self.neck();
        let (s, c) = self.flank_angle.sin_cos();
        [
            a[0] + self.contact_length * s,
            a[1] - self.contact_length * c,
        ]
    }

    /// Centre of the right slot fillet.
    pub fn fillet_centre(&self) -> [f64; 2] {
        self.points().centre
    }

    fn points(&self) -> Points {
        let (s, c) = self.flank_angle.sin_cos();
        let a = self.neck();
        let b = self.contact_end();
        let bp = [b[0] + self.runout * s, b[1] - self.runout * c];
        let r = self.fillet_radius;
        // The slot interior is on the -normal side: centre at B' - r (cos, sin).
        let centre = [bp[0] - r * c, bp[1] - r * s];
        let th0 = self.flank_angle; // B' = centre + r (cos th0, sin th0)
        let th2 = -FRAC_PI_2; // C, bottom of the circle
        let th1 = 0.5 * (th0 + th2);
        let at = |t: f64| [centre[0] + r * t.cos(), centre[1] + r * t.sin()];
        let ys = centre[1] - r;
        Points {
            a,
            b,
            bp,
            centre,
            p: at(th1),
            c: at(th2),
            e: [0.0, ys],
            ys,
            th: [th0, th1, th2],
        }
    }

    /// The same geometry with every cell count multiplied by `factor` (`n_fillet` kept even).
    pub fn refined(&self, factor: usize) -> Self {
        let f = factor.max(1);
        TurbineParams {
            n_flank: self.n_flank * f,
            n_runout: self.n_runout * f,
            n_fillet: self.n_fillet * f,
            n_lobe: self.n_lobe * f,
            n_slot: self.n_slot * f,
            n_below: self.n_below * f,
            n_root: self.n_root * f,
            n_shank: self.n_shank * f,
            ..self.clone()
        }
    }
}

/// A curve made of consecutive pieces, piece `k` taking the parameter interval
/// `[breaks[k], breaks[k + 1]]` (each piece uniform in its own parameter).
fn pieces(parts: Vec<Arc<dyn Fn(f64) -> [f64; 2] + Send + Sync>>, breaks: Vec<f64>) -> Curve {
    Curve::Param(Arc::new(move |u: f64| {
        let u = u.clamp(0.0, 1.0);
        let last = parts.len() - 1;
        let k = (0..=last).find(|&k| u <= breaks[k + 1]).unwrap_or(last);
        let w = ((u - breaks[k]) / (breaks[k + 1] - breaks[k])).clamp(0.0, 1.0);
        parts[k](w)
    }))
}

fn segment(a: [f64; 2], b: [f64; 2]) -> Arc<dyn Fn(f64) -> [f64; 2] + Send + Sync> {
    Arc::new(move |w| [a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])])
}

fn arc(centre: [f64; 2], r: f64, from: f64, to: f64) -> Arc<dyn Fn(f64) -> [f64; 2] + Send + Sync> {
    Arc::new(move |w| {
        let t = from + w * (to - from);
        [centre[0] + r * t.cos(), centre[1] + r * t.sin()]
    })
}

/// Meshes the four parts. `kind` is `Quad4`, `Quad8`, `Tri3` or `Tri6`.
///
/// # Errors
/// [`MeshError::Invalid`] for non-positive dimensions or counts, an odd `n_fillet`, a flank
/// angle outside (0, 80) degrees, a root that does not fit in the sector or a slot that reaches
/// the inner radius.
pub fn turbine_2d(p: &TurbineParams, kind: CellType) -> Result<Mesh, MeshError> {
    for (name, v) in [
        ("r_inner", p.r_inner),
        ("r_rim", p.r_rim),
        ("half_angle", p.half_angle),
        ("neck_half_width", p.neck_half_width),
        ("flank_angle", p.flank_angle),
        ("contact_length", p.contact_length),
        ("runout", p.runout),
        ("fillet_radius", p.fillet_radius),
        ("shank_height", p.shank_height),
        ("lobe_grading", p.lobe_grading),
        ("below_grading", p.below_grading),
    ] {
        positive(name, v)?;
    }
    let counts = [
        p.n_flank, p.n_runout, p.n_fillet, p.n_lobe, p.n_slot, p.n_below, p.n_root, p.n_shank,
    ];
    if counts.contains(&0) || !p.n_fillet.is_multiple_of(2) {
        return Err(MeshError::Invalid(format!(
            "turbine_2d cell counts must be >= 1 and n_fillet even, got {counts:?}"
        )));
    }
    let bad = |m: String| Err(MeshError::Invalid(format!("turbine_2d geometry: {m}")));
    if p.flank_angle >= 80f64.to_radians() {
        return bad(format!(
            "flank angle {} degrees must be below 80",
            p.flank_angle.to_degrees()
        ));
    }
    if p.half_angle >= std::f64::consts::FRAC_PI_4 || p.r_inner >= p.r_rim {
        return bad(format!(
            "need half_angle < pi/4 and r_inner < r_rim, got {} and {} / {}",
            p.half_angle, p.r_inner, p.r_rim
        ));
    }
    if p.neck_half_width >= p.r_rim * p.half_angle.sin() {
        return bad("the neck is wider than the sector at the rim".into());
    }
    let q = p.points();
    let (sa, ca) = p.half_angle.sin_cos();
    let side = |r: f64| [r * sa, r * ca];
    let norm = |v: [f64; 2]| v[0].hypot(v[1]);
    let k = side(norm(q.b));
    let l = side(norm(q.p));
    let f = side(p.r_rim);
    let g = side(p.r_inner);
    // The slot's rightmost point is on the fillet (angle 0) when the fillet turns past it.
    let rightmost = if q.th[0] > 0.0 {
        [q.centre[0] + p.fillet_radius, q.centre[1]]
    } else {
        q.bp
    };
    for (what, pt) in [
        ("B", q.b),
        ("B'", q.bp),
        ("P", q.p),
        ("the fillet", rightmost),
    ] {
        let s = side(norm(pt));
        if s[0] - pt[0] < 0.05 * p.contact_length {
            return bad(format!(
                "the slot does not fit in the sector: {what} at x = {:.3}, the sector side at x = {:.3} there",
                pt[0], s[0]
            ));
        }
    }
    let m = [q.p[0], (p.r_inner * p.r_inner - q.p[0] * q.p[0]).sqrt()];
    if q.ys - m[1] < 0.05 * p.contact_length {
        return bad(format!(
            "the slot bottom (y = {:.3}) must lie well above the inner radius {}",
            q.ys, p.r_inner
        ));
    }
    let h = [0.0, p.r_inner];
    let origin_arc = |r: f64, ccw: bool| Curve::Arc {
        center: [0.0, 0.0],
        radius: r,
        ccw,
    };
    let nh = p.n_fillet / 2;
    let r = p.fillet_radius;
    // Lobe beside the runout: edge 3 from B down the runout to B', then the fillet to P.
    let u1 = p.n_runout as f64 / (p.n_runout + nh) as f64;
    let runout_fillet = pieces(
        vec![segment(q.b, q.bp), arc(q.centre, r, q.th[0], q.th[1])],
        vec![0.0, u1, 1.0],
    );
    // Below the slot: edge 2 from P along the fillet to C, then the bottom to E.
    let u2 = nh as f64 / (nh + p.n_slot) as f64;
    let fillet_bottom = pieces(
        vec![arc(q.centre, r, q.th[1], q.th[2]), segment(q.c, q.e)],
        vec![0.0, u2, 1.0],
    );
    let gl = p.lobe_grading;
    let gb = 1.0 / p.below_grading;
    let lobe_up = Block::new([q.b, k, f, q.a], [p.n_lobe, p.n_flank])
        .edge(2, origin_arc(p.r_rim, true))
        .grading(gl, 1.0)
        .group("D2")
        .edge_group(1, "D2_side")
        .edge_group(2, "D2_rim")
        .edge_group(3, "I2_disk");
    let lobe_low = Block::new([q.p, l, k, q.b], [p.n_lobe, p.n_runout + nh])
        .edge(3, runout_fillet)
        .grading(gl, 1.0)
        .group("D2")
        .edge_group(1, "D2_side")
        .edge_group(3, "D2_slot");
    let below_out = Block::new([m, g, l, q.p], [p.n_lobe, p.n_below])
        .edge(0, origin_arc(p.r_inner, false))
        .grading(gl, gb)
        .group("D2")
        .edge_group(0, "D2_bottom")
        .edge_group(1, "D2_side");
    let below_in = Block::new([h, m, q.p, q.e], [nh + p.n_slot, p.n_below])
        .edge(0, origin_arc(p.r_inner, false))
        .edge(2, fillet_bottom)
        .grading(1.0, gb)
        .group("D2")
        .edge_group(0, "D2_bottom")
        .edge_group(2, "D2_slot")
        .edge_group(3, "D2_cut");
    let disk_right = vec![lobe_up, lobe_low, below_out, below_in];
    // Root, right half.
    let yt = q.a[1] + p.shank_height;
    let q0 = [0.0, q.b[1]];
    let n0 = [0.0, q.a[1]];
    let flank = Block::new([q0, q.b, q.a, n0], [p.n_root, p.n_flank])
        .group("A2")
        .edge_group(0, "A2_bottom")
        .edge_group(1, "I2_root")
        .edge_group(3, "A2_cut");
    let shank = Block::new([n0, q.a, [q.a[0], yt], [0.0, yt]], [p.n_root, p.n_shank])
        .group("A2")
        .edge_group(1, "A2_side")
        .edge_group(2, "A2_top")
        .edge_group(3, "A2_cut");
    let root_right = vec![flank, shank];
    let to_left = |n: &str| {
        n.replacen("D2", "D1", 1)
            .replacen("A2", "A1", 1)
            .replacen("I2", "I1", 1)
    };
    let left = |blocks: &[Block]| -> Vec<Block> {
        blocks
            .iter()
            .map(|b| mirror_x_renamed(b, &to_left))
            .collect()
    };
    let mut mesh = multiblock(&left(&disk_right), kind)?;
    for part in [
        multiblock(&disk_right, kind)?,
        multiblock(&left(&root_right), kind)?,
        multiblock(&root_right, kind)?,
    ] {
        mesh.append(&part)?;
    }
    // Split each slot surface into runout, fillet and bottom.
    let tol = 1e-7 * p.r_rim;
    for half in ["D1", "D2"] {
        let slot_name = format!("{half}_slot");
        let slot = mesh.facet_groups.remove(&slot_name).unwrap_or_default();
        mesh.node_groups.remove(&slot_name);
        let sign = if half == "D1" { -1.0 } else { 1.0 };
        let centre = [sign * q.centre[0], q.centre[1]];
        let on_circle = |x: [f64; 3]| ((x[0] - centre[0]).hypot(x[1] - centre[1]) - r).abs() <= tol;
        let on_bottom = |x: [f64; 3]| (x[1] - q.ys).abs() <= tol;
        let mut parts: [Vec<Facet>; 3] = [Vec::new(), Vec::new(), Vec::new()];
        for fc in slot {
            let corners = &fc.nodes[..fc.kind.num_corners()];
            let all =
                |pred: &dyn Fn([f64; 3]) -> bool| corners.iter().all(|&n| pred(mesh.coords[n]));
            let i = if all(&on_circle) {
                1
            } else if all(&on_bottom) {
                2
            } else {
                0
            };
            parts[i].push(fc);
        }
        for (name, facets) in ["runout", "fillet", "slot_bottom"].iter().zip(parts) {
            let name = format!("{half}_{name}");
            let nodes: Vec<usize> = facets.iter().flat_map(|fc| fc.nodes.clone()).collect();
            mesh.add_nodes_to_group(&name, nodes);
            mesh.add_facets_to_group(&name, facets);
        }
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::test_checks::{assert_coincident, group_measure};

    fn group_length(m: &Mesh, g: &str) -> f64 {
        m.facet_group(g)
            .unwrap()
            .iter()
            .map(|f| {
                let (a, b) = (m.coords[f.nodes[0]], m.coords[f.nodes[1]]);
                (a[0] - b[0]).hypot(a[1] - b[1])
            })
            .sum()
    }

    #[test]
    fn four_parts_coincident_interfaces_and_a_smooth_slot() {
        let p = TurbineParams {
            n_flank: 8,
            n_runout: 2,
            n_fillet: 8,
            n_lobe: 5,
            n_slot: 4,
            n_below: 5,
            n_root: 4,
            n_shank: 4,
            ..TurbineParams::default()
        };
        let m = turbine_2d(&p, CellType::Quad4).unwrap();
        for g in ["D1", "D2", "A1", "A2"] {
            assert!(!m.cell_group(g).unwrap().is_empty(), "{g}");
        }
        for c in 0..m.num_cells() {
            assert!(m.cell_min_jacobian(c) > 0.0);
        }
        // Mirror symmetry of the areas; the root area is the trapezoid plus the shank.
        let area = |g: &str| group_measure(&m, g);
        assert!((area("D1") - area("D2")).abs() < 1e-9 * area("D2"));
        let (a, b) = (p.neck(), p.contact_end());
        let root = (a[0] + b[0]) * (a[1] - b[1]) + 2.0 * a[0] * p.shank_height;
        assert!((area("A1") + area("A2") - root).abs() < 1e-9 * root);
        // Coincident, distinct nodes on every interface.
        for (s1, s2) in [
            ("I1_disk", "I1_root"),
            ("I2_disk", "I2_root"),
            ("D1_cut", "D2_cut"),
            ("A1_cut", "A2_cut"),
        ] {
            assert_coincident(&m, s1, s2, 1e-9, true);
        }
        // Lengths: contact line, runout, fillet arc (chords of the arc: slightly shorter).
        let sweep = p.flank_angle + FRAC_PI_2;
        for half in ["1", "2"] {
            let lc = group_length(&m, &format!("I{half}_disk"));
            assert!((lc - p.contact_length).abs() < 1e-9, "{lc}");
            let lr = group_length(&m, &format!("D{half}_runout"));
            assert!((lr - p.runout).abs() < 1e-9, "{lr}");
            let lf = group_length(&m, &format!("D{half}_fillet"));
            let arc_len = p.fillet_radius * sweep;
            assert!(lf < arc_len && lf > 0.99 * arc_len, "{lf} vs {arc_len}");
            assert_eq!(m.facet_group(&format!("D{half}_fillet")).unwrap().len(), 8);
        }
        // The fillet is tangent to the runout at B' and to the bottom at C: the slot has no
        // corner there (the facet directions turn by less than 360 / n degrees).
        let pts = p.points();
        let centre = pts.centre;
        for &n in &m.group_nodes("D2_fillet").unwrap() {
            let x = m.coords[n];
            let d = (x[0] - centre[0]).hypot(x[1] - centre[1]);
            assert!((d - p.fillet_radius).abs() < 1e-9);
        }
    }
}
