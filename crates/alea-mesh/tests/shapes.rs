//! Shape builders: areas against closed forms, validity, conformity, groups.

mod common;

use std::f64::consts::PI;

use alea_mesh::CellType::{self, *};
use alea_mesh::generate::{
    DovetailParams, annulus_sector, dovetail_root_and_disk, plate_with_hole,
};
use common::*;

/// Area removed by the polygonal (order 1) or parabolic (order 2) approximation of a circular arc
/// of radius r split into chords subtending `angles`: sum of the triangles (0, P_k, P_k+1), plus
/// for parabolas Archimedes' 4/3 of the triangle (P_k, P_mid, P_k+1).
fn sector_area(r: f64, angles: &[f64], order: usize) -> f64 {
    angles
        .iter()
        .map(|&d| {
            let tri = 0.5 * r * r * d.sin();
            if order == 1 {
                tri
            } else {
                tri + 4.0 / 3.0 * 0.5 * r * r * (2.0 * (d / 2.0).sin() - d.sin())
            }
        })
        .sum()
}

#[test]
fn plate_with_hole_area_groups_and_validity() {
    let (a, l) = (1.0, 5.0);
    for kind in [Quad4, Quad8, Tri3, Tri6] {
        let (n_arc, n_rad) = (7, 6);
        let m = plate_with_hole(a, l, n_arc, n_rad, 4.0, kind).unwrap();
        m.validate().unwrap();
        assert_positive_jacobians(&m);
        assert_conforming(&m);
        assert_groups_outward(&m);
        let cells_per_quad = if matches!(kind, Tri3 | Tri6) { 2 } else { 1 };
        assert_eq!(m.num_cells(), n_arc * n_rad * cells_per_quad);
        // Arc chords: 3 in the lower block (0..45 deg), 4 in the upper one.
        let mut angles = vec![PI / 4.0 / 3.0; 3];
        angles.extend(vec![PI / 4.0 / 4.0; 4]);
        let exact = l * l - sector_area(a, &angles, kind.order());
        let area = m.measure();
        assert!(
            (area - exact).abs() < 1e-12 * l * l,
            "{kind}: {area} vs {exact}"
        );
        // And both tend to the true area.
        assert!((area - (l * l - PI * a * a / 4.0)).abs() < 2e-2);
        // Groups.
        let names: Vec<&String> = m.facet_groups.keys().collect();
        assert_eq!(names, ["hole", "right", "top", "xsym", "ysym"]);
        assert_eq!(m.cell_group("domain").unwrap().len(), m.num_cells());
        for x in group_coords(&m, "hole") {
            assert!(((x[0] * x[0] + x[1] * x[1]).sqrt() - a).abs() < 1e-12);
        }
        for (g, d, v) in [
            ("xsym", 0, 0.0),
            ("ysym", 1, 0.0),
            ("right", 0, l),
            ("top", 1, l),
        ] {
            for x in group_coords(&m, g) {
                assert!((x[d] - v).abs() < 1e-12, "{g}: {x:?}");
            }
        }
        assert_eq!(m.facet_group("hole").unwrap().len(), n_arc);
        assert_eq!(m.facet_group("right").unwrap().len(), 3);
        assert_eq!(m.facet_group("top").unwrap().len(), 4);
        assert_eq!(m.facet_group("ysym").unwrap().len(), n_rad);
        // Every boundary facet is in a group.
        let total: usize = m.facet_groups.values().map(|v| v.len()).sum();
        assert_eq!(total, m.boundary_facets().len());
    }
}

/// Corner angles and edge-length ratio of each cell's corner quadrilateral.
fn shape_stats(m: &alea_mesh::Mesh) -> (f64, f64, f64) {
    let (mut amin, mut amax, mut ar) = (180.0f64, 0.0f64, 0.0f64);
    for (_, kind, nodes) in m.cells() {
        let k = kind.num_corners();
        let p: Vec<[f64; 3]> = nodes[..k].iter().map(|&n| m.coords[n]).collect();
        let mut lens = Vec::new();
        for i in 0..k {
            let (a, b, c) = (p[(i + k - 1) % k], p[i], p[(i + 1) % k]);
            let u = [a[0] - b[0], a[1] - b[1]];
            let v = [c[0] - b[0], c[1] - b[1]];
            let nu = u[0].hypot(u[1]);
            let nv = v[0].hypot(v[1]);
            let ang = ((u[0] * v[0] + u[1] * v[1]) / (nu * nv))
                .acos()
                .to_degrees();
            amin = amin.min(ang);
            amax = amax.max(ang);
            lens.push(nv);
        }
        let lmax = lens.iter().cloned().fold(0.0, f64::max);
        let lmin = lens.iter().cloned().fold(f64::INFINITY, f64::min);
        ar = ar.max(lmax / lmin);
    }
    (amin, amax, ar)
}

#[test]
fn fine_kirsch_q8_mesh_is_well_shaped() {
    // Typical Kirsch set-up: L = 10 a, 48 cells on the quarter arc, radial grading ~ L/a.
    let m = plate_with_hole(1.0, 10.0, 48, 32, 10.0, Quad8).unwrap();
    assert_positive_jacobians(&m);
    let (amin, amax, ar) = shape_stats(&m);
    assert!(amin > 40.0 && amax < 140.0, "angles {amin}..{amax}");
    assert!(ar < 6.0, "aspect ratio {ar}");
    // Cells at the hole are nearly square: radial size ~ arc length.
    let hole = m.facet_group("hole").unwrap();
    let arc_h = PI / 2.0 / 48.0;
    for f in hole {
        let (p, q) = (m.coords[f.nodes[0]], m.coords[f.nodes[1]]);
        let h = (p[0] - q[0]).hypot(p[1] - q[1]);
        assert!((h / arc_h - 1.0).abs() < 0.01);
    }
    // Q8 mid-side nodes on the hole lie on the circle.
    for f in hole {
        let x = m.coords[f.nodes[2]];
        assert!((x[0].hypot(x[1]) - 1.0).abs() < 1e-12);
    }
}

#[test]
fn annulus_sector_area_and_groups() {
    let (ri, ro, ang) = (2.0, 5.0, PI / 3.0);
    for kind in [Quad4, Quad8, Tri3, Tri6] {
        let (nr, nt) = (4, 9);
        let m = annulus_sector(ri, ro, ang, nr, nt, kind).unwrap();
        m.validate().unwrap();
        assert_positive_jacobians(&m);
        assert_conforming(&m);
        assert_groups_outward(&m);
        let d = vec![ang / nt as f64; nt];
        let exact = sector_area(ro, &d, kind.order()) - sector_area(ri, &d, kind.order());
        assert!((m.measure() - exact).abs() < 1e-12 * ro * ro, "{kind}");
        let true_area = 0.5 * ang * (ro * ro - ri * ri);
        assert!((m.measure() - true_area).abs() < 1e-2 * true_area);
        for (g, r) in [("inner", ri), ("outer", ro)] {
            for x in group_coords(&m, g) {
                assert!((x[0].hypot(x[1]) - r).abs() < 1e-12);
            }
        }
        for x in group_coords(&m, "side0") {
            assert!(x[1].abs() < 1e-12 && x[0] > 0.0);
        }
        for x in group_coords(&m, "side1") {
            assert!((x[1].atan2(x[0]) - ang).abs() < 1e-12);
        }
        assert_eq!(m.facet_group("outer").unwrap().len(), nt);
        assert_eq!(m.facet_group("side1").unwrap().len(), nr);
        // Polar grid: every interior node lies on one of the radii r_in + i (r_out - r_in)/nr
        // (or half-way for mid-side nodes).
        let step = (ro - ri) / nr as f64 / 2.0;
        for x in &m.coords {
            let q = (x[0].hypot(x[1]) - ri) / step;
            assert!((q - q.round()).abs() < 1e-9);
        }
    }
}

#[test]
fn annulus_sector_large_angle_and_bad_input() {
    let m = annulus_sector(1.0, 2.0, 1.5 * PI, 2, 12, Quad8).unwrap();
    assert_positive_jacobians(&m);
    let exact = 0.75 * PI * 3.0;
    assert!((m.measure() - exact).abs() < 1e-3 * exact);
    assert!(annulus_sector(2.0, 1.0, 1.0, 2, 2, Quad4).is_err());
    assert!(annulus_sector(1.0, 2.0, 7.0, 2, 2, Quad4).is_err());
    assert!(annulus_sector(1.0, 2.0, 1.0, 0, 2, Quad4).is_err());
    assert!(annulus_sector(1.0, 2.0, 1.0, 2, 2, Hex8).is_err());
    assert!(plate_with_hole(2.0, 1.0, 4, 4, 1.0, Quad4).is_err());
    assert!(plate_with_hole(0.5, 1.0, 1, 4, 1.0, Quad4).is_err());
    assert!(plate_with_hole(0.5, 1.0, 4, 4, f64::NAN, Quad4).is_err());
    let _: CellType = Quad4;
}

fn sorted_coords(m: &alea_mesh::Mesh, nodes: &[usize]) -> Vec<[i64; 2]> {
    let mut v: Vec<[i64; 2]> = nodes
        .iter()
        .map(|&n| {
            [
                (m.coords[n][0] * 1e8).round() as i64,
                (m.coords[n][1] * 1e8).round() as i64,
            ]
        })
        .collect();
    v.sort_unstable();
    v
}

/// Exact area of the disk sector with its slot (true curved geometry).
fn dovetail_disk_area(p: &DovetailParams) -> f64 {
    let (wn, wb, rf) = (p.neck_half_width, p.bottom_half_width, p.fillet_radius);
    let sector = p.half_angle * (p.r_rim.powi(2) - p.r_inner.powi(2));
    // Slot inside the rim circle: trapezoid between the flanks, rectangle down to the slot
    // bottom, circular segment above the chord A_L A_R, minus the two fillet corners.
    let phi = 2.0 * (wn / p.r_rim).asin();
    let segment = 0.5 * p.r_rim.powi(2) * (phi - phi.sin());
    let slot = (wn + wb) * p.flank_height + 2.0 * wb * p.slot_gap + segment
        - 2.0 * (rf * rf - PI * rf * rf / 4.0);
    sector - slot
}

#[test]
fn dovetail_parts_groups_and_areas() {
    let p = DovetailParams::default();
    for kind in [Quad4, Quad8, Tri6] {
        let m = dovetail_root_and_disk(&p, kind).unwrap();
        m.validate().unwrap();
        assert_positive_jacobians(&m);
        assert_conforming(&m);
        assert_groups_outward(&m);
        if kind == Quad4 {
            let (amin, amax, _) = shape_stats(&m);
            assert!(amin > 45.0 && amax < 135.0, "corner angles {amin}..{amax}");
        }
        let root = m.cell_group("root").unwrap();
        let disk = m.cell_group("disk").unwrap();
        assert_eq!(root.len() + disk.len(), m.num_cells());
        let area = |cells: &[usize]| cells.iter().map(|&c| m.cell_measure(c)).sum::<f64>();
        // The root has straight edges: exact area (w_n + w_b) h_f + 2 w_n h_s.
        assert!((area(root) - 528.0).abs() < 1e-9, "{}", area(root));
        let exact = dovetail_disk_area(&p);
        let tol = if kind == Quad4 { 2e-3 } else { 2e-5 };
        assert!(
            (area(disk) / exact - 1.0).abs() < tol,
            "{kind}: {} vs {exact}",
            area(disk)
        );
        // Flanks: root side and disk side have coincident but distinct nodes, node for node.
        for side in ["left", "right"] {
            let r = m.group_nodes(&format!("flank_{side}_root")).unwrap();
            let d = m.group_nodes(&format!("flank_{side}_disk")).unwrap();
            assert_eq!(r.len(), p.n_flank * kind.order() + 1);
            assert!(r.iter().all(|n| !d.contains(n)));
            assert_eq!(sorted_coords(&m, &r), sorted_coords(&m, &d));
            // The flank is the segment from (w_b, y_B) to (w_n, y_A), mirrored for the left.
            let sgn = if side == "left" { -1.0 } else { 1.0 };
            let ya = (200f64.powi(2) - 64.0).sqrt();
            for &n in &r {
                let x = m.coords[n];
                let t = (ya - x[1]) / 12.0;
                assert!(
                    (x[0] - sgn * (8.0 + 8.0 * t)).abs() < 1e-9
                        && (-1e-12..=1.0 + 1e-12).contains(&t)
                );
            }
        }
        // The only coincident nodes are the flank pairs.
        let all = sorted_coords(&m, &(0..m.num_nodes()).collect::<Vec<_>>());
        let dup = all.windows(2).filter(|w| w[0] == w[1]).count();
        assert_eq!(dup, 2 * (p.n_flank * kind.order() + 1));
        // Sector sides on the radial lines at +-half_angle; bottom on r_inner.
        let (s, c) = p.half_angle.sin_cos();
        for x in group_coords(&m, "disk_side_right") {
            assert!((x[0] * c - x[1] * s).abs() < 1e-9);
        }
        for x in group_coords(&m, "disk_side_left") {
            assert!((x[0] * c + x[1] * s).abs() < 1e-9);
        }
        for x in group_coords(&m, "disk_bottom") {
            assert!((x[0].hypot(x[1]) - p.r_inner).abs() < 1e-9);
        }
        for x in group_coords(&m, "disk_rim") {
            assert!((x[0].hypot(x[1]) - p.r_rim).abs() < 1e-9);
        }
        for name in [
            "root_top",
            "root_sides",
            "root_bottom",
            "slot_bottom",
            "slot_fillet",
        ] {
            assert!(!m.facet_group(name).unwrap().is_empty());
        }
        // The parts are separate substructures.
        let (r, _) = m.extract(&["root"]).unwrap();
        let (d, _) = m.extract(&["disk"]).unwrap();
        assert!(
            r.facet_groups.contains_key("flank_left_root")
                && !r.facet_groups.contains_key("flank_left_disk")
        );
        assert!(
            d.facet_groups.contains_key("flank_right_disk")
                && !d.facet_groups.contains_key("root_top")
        );
        assert_eq!(r.num_nodes() + d.num_nodes(), m.num_nodes());
    }
}

#[test]
fn dovetail_fillet_variant_and_bad_geometry() {
    let p = DovetailParams::default().refined(2);
    let sharp = DovetailParams {
        fillet_radius: 0.0,
        ..p.clone()
    };
    let a = |q: &DovetailParams| {
        let m = dovetail_root_and_disk(q, Quad8).unwrap();
        assert_positive_jacobians(&m);
        m.cell_group("disk")
            .unwrap()
            .iter()
            .map(|&c| m.cell_measure(c))
            .sum::<f64>()
    };
    let (af, a0) = (a(&p), a(&sharp));
    // The fillets add 2 (r^2 - pi r^2 / 4) of material to the disk.
    let rf = p.fillet_radius;
    assert!(
        ((af - a0) - 2.0 * (rf * rf - PI * rf * rf / 4.0)).abs() < 2e-4,
        "{}",
        af - a0
    );
    assert!((af / dovetail_disk_area(&p) - 1.0).abs() < 1e-6);
    // Fillet nodes lie on the fillet circle or on the straight wall.
    let m = dovetail_root_and_disk(&p, Quad8).unwrap();
    let yb = (200f64.powi(2) - 64.0).sqrt() - 12.0;
    let ys = yb - 4.0;
    for x in group_coords(&m, "slot_fillet") {
        let on_wall = (x[0].abs() - 16.0).abs() < 1e-9 && x[1] >= ys + rf - 1e-9;
        let on_arc = ((x[0].abs() - (16.0 - rf)).hypot(x[1] - (ys + rf)) - rf).abs() < 1e-9;
        assert!(on_wall || on_arc, "{x:?}");
    }
    // The wall/fillet and fillet/bottom junctions are mesh nodes (no cell straddles them), and
    // the flat bottom group holds only y = ys nodes.
    for sx in [-1.0, 1.0] {
        for target in [[sx * 16.0, ys + rf], [sx * (16.0 - rf), ys]] {
            assert!(
                m.coords
                    .iter()
                    .any(|x| (x[0] - target[0]).abs() < 1e-9 && (x[1] - target[1]).abs() < 1e-9),
                "no node at {target:?}"
            );
        }
    }
    for x in group_coords(&m, "slot_bottom") {
        assert!((x[1] - ys).abs() < 1e-9 && x[0].abs() <= 16.0 - rf + 1e-9);
    }
    for bad in [
        DovetailParams {
            neck_half_width: 20.0,
            ..Default::default()
        },
        DovetailParams {
            fillet_radius: 5.0,
            ..Default::default()
        },
        DovetailParams {
            bottom_half_width: 30.0,
            ..Default::default()
        },
        DovetailParams {
            r_inner: 190.0,
            ..Default::default()
        },
        DovetailParams {
            n_flank: 0,
            ..Default::default()
        },
        DovetailParams {
            half_angle: -1.0,
            ..Default::default()
        },
    ] {
        assert!(dovetail_root_and_disk(&bad, Quad4).is_err(), "{bad:?}");
    }
}
