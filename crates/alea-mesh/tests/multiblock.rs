//! Multi-block generator: conformity across blocks, curves, grading, orientation, errors.

mod common;

use std::f64::consts::PI;
use std::sync::Arc;

use alea_mesh::CellType::*;
use alea_mesh::MeshError;
use alea_mesh::generate::{Block, Curve, multiblock};
use common::*;

fn unit(x0: f64, y0: f64) -> [[f64; 2]; 4] {
    [
        [x0, y0],
        [x0 + 1.0, y0],
        [x0 + 1.0, y0 + 1.0],
        [x0, y0 + 1.0],
    ]
}

#[test]
fn two_blocks_share_an_edge_and_merge_nodes() {
    for kind in [Quad4, Quad8, Tri3, Tri6] {
        let a = Block::new(unit(0.0, 0.0), [2, 3])
            .group("a")
            .edge_group(3, "left");
        let b = Block::new(unit(1.0, 0.0), [4, 3])
            .group("b")
            .edge_group(1, "right");
        let m = multiblock(&[a, b], kind).unwrap();
        assert_positive_jacobians(&m);
        assert_conforming(&m);
        assert_groups_outward(&m);
        let expected_nodes = match kind {
            Quad4 | Tri3 => 7 * 4,
            Quad8 => 13 * 7 - 6 * 3,
            _ => 13 * 7,
        };
        assert_eq!(m.num_nodes(), expected_nodes, "{kind}");
        assert!((m.measure() - 2.0).abs() < 1e-12);
        // Boundary = outer rectangle only (no internal boundary along x = 1).
        let per = if kind.num_corners() == 3 { 2 } else { 1 };
        assert_eq!(m.boundary_facets().len(), 2 * 6 + 2 * 3);
        assert_eq!(m.cell_group("a").unwrap().len(), 6 * per);
        assert_eq!(m.cell_group("b").unwrap().len(), 12 * per);
    }
}

#[test]
fn four_blocks_around_a_point_and_corner_only_neighbours() {
    // 2 x 2 blocks meeting at (1, 1): diagonal blocks share only a corner.
    let blocks: Vec<Block> = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
        .iter()
        .map(|&(x, y)| Block::new(unit(x, y), [3, 2]))
        .collect();
    let m = multiblock(&blocks, Quad8).unwrap();
    assert_conforming(&m);
    assert_eq!(m.num_nodes(), 13 * 9 - 6 * 4);
    assert_eq!(m.boundary_facets().len(), 2 * 6 + 2 * 4);
}

#[test]
fn mismatched_shared_edge_is_an_error() {
    let a = Block::new(unit(0.0, 0.0), [2, 3]);
    let b = Block::new(unit(1.0, 0.0), [2, 2]);
    let e = multiblock(&[a.clone(), b], Quad4).unwrap_err();
    assert!(
        matches!(&e, MeshError::Invalid(m) if m.contains("shared")),
        "{e}"
    );
    // Same count, mirrored grading on the shared edge: node positions differ.
    let b = Block::new(unit(1.0, 0.0), [2, 3]).grading(1.0, 2.0);
    let e = multiblock(&[a.clone(), b], Quad4).unwrap_err();
    assert!(
        matches!(&e, MeshError::Invalid(m) if m.contains("grading")),
        "{e}"
    );
    // The same grading on both sides is fine.
    let a2 = a.clone().grading(1.0, 2.0);
    let b = Block::new(unit(1.0, 0.0), [5, 3]).grading(1.0, 2.0);
    assert_conforming(&multiblock(&[a2, b], Quad4).unwrap());
}

#[test]
fn grading_is_the_ratio_of_last_to_first_cell() {
    let m = multiblock(
        &[
            Block::new([[0.0, 0.0], [15.0, 0.0], [15.0, 1.0], [0.0, 1.0]], [4, 1])
                .grading(8.0, 1.0)
                .edge_group(0, "bottom"),
        ],
        Quad4,
    )
    .unwrap();
    let mut xs: Vec<f64> = group_coords(&m, "bottom").iter().map(|x| x[0]).collect();
    xs.sort_by(f64::total_cmp);
    // Sizes 1, 2, 4, 8 for a total of 15.
    let h: Vec<f64> = xs.windows(2).map(|w| w[1] - w[0]).collect();
    for (k, hk) in h.iter().enumerate() {
        assert!((hk - 2f64.powi(k as i32)).abs() < 1e-12, "{h:?}");
    }
}

#[test]
fn clockwise_block_is_reoriented_with_its_groups() {
    // Corners given clockwise; edge 0 is the left side (0,0)->(0,1).
    let b = Block::new([[0.0, 0.0], [0.0, 1.0], [2.0, 1.0], [2.0, 0.0]], [3, 5])
        .edge_group(0, "left")
        .edge_group(1, "top")
        .group("g");
    for kind in [Quad4, Quad8, Tri6] {
        let m = multiblock(std::slice::from_ref(&b), kind).unwrap();
        assert_positive_jacobians(&m);
        assert_groups_outward(&m);
        assert!((m.measure() - 2.0).abs() < 1e-12);
        assert_eq!(m.facet_group("left").unwrap().len(), 3);
        assert_eq!(m.facet_group("top").unwrap().len(), 5);
        for x in group_coords(&m, "left") {
            assert!(x[0].abs() < 1e-15);
        }
    }
}

#[test]
fn o_grid_disc_with_arcs() {
    // A disc of radius 1: a central square and four blocks bounded by quarter arcs, given
    // alternately with Arc and ArcThrough.
    let (r, s) = (1.0, 0.4);
    let q = |k: usize| -> ([f64; 2], [f64; 2]) {
        let th = PI / 4.0 + k as f64 * PI / 2.0;
        (
            [s * th.cos() * 2f64.sqrt(), s * th.sin() * 2f64.sqrt()],
            [r * th.cos(), r * th.sin()],
        )
    };
    let n = 6;
    let mut blocks = vec![Block::new([q(3).0, q(0).0, q(1).0, q(2).0], [n, n]).group("core")];
    for k in 0..4 {
        let (i0, o0) = q((k + 3) % 4);
        let (i1, o1) = q(k);
        let mid = (PI / 2.0) * k as f64;
        let arc = if k % 2 == 0 {
            Curve::Arc {
                center: [0.0, 0.0],
                radius: r,
                ccw: true,
            }
        } else {
            Curve::ArcThrough([r * mid.cos(), r * mid.sin()])
        };
        blocks.push(
            Block::new([i0, o0, o1, i1], [3, n])
                .edge(1, arc)
                .edge_group(1, "rim")
                .group("ring"),
        );
    }
    for kind in [Quad4, Quad8] {
        let m = multiblock(&blocks, kind).unwrap();
        assert_positive_jacobians(&m);
        assert_conforming(&m);
        assert_groups_outward(&m);
        assert_eq!(m.boundary_facets().len(), 4 * n);
        let chords = vec![PI / 2.0 / n as f64; 4 * n];
        let polygon: f64 = chords.iter().map(|d| 0.5 * d.sin()).sum();
        let exact = if kind == Quad4 {
            polygon
        } else {
            polygon
                + chords
                    .iter()
                    .map(|d| 4.0 / 3.0 * 0.5 * (2.0 * (d / 2.0).sin() - d.sin()))
                    .sum::<f64>()
        };
        assert!((m.measure() - exact).abs() < 1e-12, "{kind}");
        for x in group_coords(&m, "rim") {
            assert!((x[0].hypot(x[1]) - r).abs() < 1e-12);
        }
    }
}

#[test]
fn polyline_spline_and_parametric_edges() {
    // Roof-shaped top edge: area 1 + 1/4 exactly when a node falls on the apex.
    let roof = Block::new(unit(0.0, 0.0), [4, 2]).edge(2, Curve::Polyline(vec![[0.5, 1.5]]));
    let m = multiblock(&[roof], Quad4).unwrap();
    assert!((m.measure() - 1.25).abs() < 1e-12);
    // A spline through (0.5, 1.2): symmetric node set, passing through the apex.
    let sp = Block::new(unit(0.0, 0.0), [4, 2])
        .edge(2, Curve::Spline(vec![[0.5, 1.2]]))
        .edge_group(2, "top");
    let m = multiblock(&[sp], Quad8).unwrap();
    assert_positive_jacobians(&m);
    let top = group_coords(&m, "top");
    assert!(
        top.iter()
            .any(|x| (x[0] - 0.5).abs() < 1e-12 && (x[1] - 1.2).abs() < 1e-12)
    );
    for x in &top {
        assert!(
            top.iter()
                .any(|y| (y[0] - (1.0 - x[0])).abs() < 1e-12 && (y[1] - x[1]).abs() < 1e-12)
        );
    }
    assert!(m.measure() > 1.0 && m.measure() < 1.2);
    // A parametric quarter circle as the right edge of a quarter-disc-like block.
    let f: alea_mesh::generate::CurveFn = Arc::new(|u: f64| {
        let th = u * PI / 2.0;
        [th.cos(), th.sin()]
    });
    let b = Block::new([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.3]], [8, 8])
        .edge(1, Curve::Param(f.clone()));
    let m = multiblock(&[b], Quad8).unwrap();
    assert_positive_jacobians(&m);
    let chords = [PI / 2.0 / 8.0; 8];
    let exact: f64 = chords
        .iter()
        .map(|d| 0.5 * d.sin() + 4.0 / 3.0 * 0.5 * (2.0 * (d / 2.0).sin() - d.sin()))
        .sum();
    assert!((m.measure() - exact).abs() < 1e-12);
    // Wrong end point of the closure.
    let b = Block::new([[0.0, 0.0], [1.0, 0.0], [0.0, 1.1], [0.0, 0.3]], [2, 2])
        .edge(1, Curve::Param(f));
    assert!(multiblock(&[b], Quad4).is_err());
}

#[test]
fn bad_blocks_are_errors() {
    // Arc end off the circle.
    let b = Block::new(unit(0.0, 0.0), [2, 2]).edge(
        1,
        Curve::Arc {
            center: [0.0, 0.0],
            radius: 1.0,
            ccw: true,
        },
    );
    assert!(multiblock(&[b], Quad4).is_err());
    // Bow-tie (folded) block.
    let b = Block::new([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]], [2, 2]);
    assert!(multiblock(&[b], Quad4).is_err());
    // Collinear arc-through point.
    let b = Block::new(unit(0.0, 0.0), [2, 2]).edge(0, Curve::ArcThrough([0.5, 0.0]));
    assert!(multiblock(&[b], Quad4).is_err());
    assert!(multiblock(&[Block::new(unit(0.0, 0.0), [0, 2])], Quad4).is_err());
    assert!(
        multiblock(
            &[Block::new(unit(0.0, 0.0), [1, 2]).grading(-1.0, 1.0)],
            Quad4
        )
        .is_err()
    );
    assert!(multiblock(&[Block::new(unit(0.0, 0.0), [1, 2])], Hex8).is_err());
    assert!(multiblock(&[], Quad4).is_err());
    // Overlapping edge with different counts and different curves -> unmerged coincident nodes.
    let a = Block::new(unit(0.0, 0.0), [2, 2]);
    let b = Block::new(unit(0.0, 0.0), [2, 2]).edge(2, Curve::ArcThrough([0.5, 1.2]));
    assert!(multiblock(&[a, b], Quad4).is_err());
}
