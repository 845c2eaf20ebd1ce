//! Multi-block hexahedral generator: conformity across blocks, grading, mirrored blocks, the
//! corner-refined octant, errors.

mod common;

use alea_mesh::MeshError;
use alea_mesh::generate::{
    HexBlock, corner_refined_blocks, grading_for_first_cell, multiblock_hex,
};
use common::*;

#[test]
fn two_cuboids_share_a_face_and_merge_nodes() {
    let a = HexBlock::cuboid([0.0; 3], [1.0, 1.0, 1.0], [2, 3, 2])
        .group("a")
        .face_group(0, "left");
    let b = HexBlock::cuboid([1.0, 0.0, 0.0], [3.0, 1.0, 1.0], [4, 3, 2])
        .grading([2.0, 1.0, 1.0])
        .group("b")
        .face_group(1, "right")
        .face_group(5, "top");
    let m = multiblock_hex(&[a, b]).unwrap();
    assert_positive_jacobians(&m);
    assert_conforming(&m);
    assert_groups_outward(&m);
    assert_eq!(m.num_nodes(), 7 * 4 * 3);
    assert_eq!(m.num_cells(), 12 + 24);
    assert!((m.measure() - 3.0).abs() < 1e-12);
    assert_eq!(m.cell_group("a").unwrap().len(), 12);
    assert_eq!(m.facet_group("top").unwrap().len(), 12);
    // Grading 2 along x in block b: first cell (at x = 1) half the last (at x = 3).
    let mut xs: Vec<f64> = m
        .coords
        .iter()
        .map(|x| x[0])
        .filter(|&x| x >= 1.0)
        .collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    assert_eq!(xs.len(), 5);
    let (first, last) = (xs[1] - xs[0], xs[4] - xs[3]);
    assert!((last / first - 2.0).abs() < 1e-12, "{first} {last}");
    for x in group_coords(&m, "right") {
        assert!((x[0] - 3.0).abs() < 1e-12);
    }
}

#[test]
fn mirrored_blocks_are_reoriented() {
    let a = HexBlock::cuboid([0.0; 3], [1.0, 1.0, 1.0], [2, 2, 2]).face_group(4, "bottom");
    let b = a.mapped(|x| [-x[0], x[1], x[2]]);
    let c = a.mapped(|x| [x[0], x[1], -x[2]]);
    let m = multiblock_hex(&[a, b, c]).unwrap();
    assert_positive_jacobians(&m);
    assert_conforming(&m);
    assert!((m.measure() - 3.0).abs() < 1e-12);
    // "bottom" is z = 0 for a and b (outward -z) and z = 0 for c (outward +z)... but z = 0 is
    // shared by a and c, so those faces are interior: only b's part is a boundary face.
    let bnd = boundary_set(&m);
    let on_boundary = m
        .facet_group("bottom")
        .unwrap()
        .iter()
        .filter(|f| bnd.contains(&f.nodes))
        .count();
    assert_eq!(on_boundary, 4);
}

#[test]
fn corner_refined_octant_is_conforming_and_fills_the_box() {
    let (a, l, n, m) = (1.0, 8.0, 4, 5);
    let blocks = corner_refined_blocks(a, l, n, m).unwrap();
    let mesh = multiblock_hex(&blocks).unwrap();
    assert_positive_jacobians(&mesh);
    assert_conforming(&mesh);
    assert_groups_outward(&mesh);
    assert_eq!(mesh.num_cells(), n * n * n + 3 * n * n * m);
    assert!((mesh.measure() - l * l * l).abs() < 1e-9 * l * l * l);
    // Every boundary face lies on a face of the box: blocks that did not match would leave
    // faces (hanging nodes) inside.
    let tol = 1e-9 * l;
    for b in mesh.boundary_facets() {
        let xs: Vec<[f64; 3]> = b.facet.nodes.iter().map(|&i| mesh.coords[i]).collect();
        let on = |d: usize, v: f64| xs.iter().all(|x| (x[d] - v).abs() < tol);
        assert!(
            on(0, 0.0) || on(0, l) || on(1, 0.0) || on(1, l) || on(2, 0.0) || on(2, -l),
            "boundary face {xs:?} inside the box"
        );
    }
    // The contact face is the uniform n x n grid of [0, a]^2 on z = 0.
    let contact = group_coords(&mesh, "contact");
    assert_eq!(contact.len(), (n + 1) * (n + 1));
    for x in &contact {
        assert!(x[2].abs() < tol && x[0] <= a + tol && x[1] <= a + tol);
        let (i, j) = (x[0] * n as f64 / a, x[1] * n as f64 / a);
        assert!((i - i.round()).abs() < 1e-9 && (j - j.round()).abs() < 1e-9);
    }
    // The first graded cell is as long as a fine cell.
    let mut xs: Vec<f64> = group_coords(&mesh, "sym_y")
        .iter()
        .filter(|x| x[2].abs() < tol)
        .map(|x| x[0])
        .collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup_by(|p, q| (*p - *q).abs() < tol);
    assert_eq!(xs.len(), n + m + 1);
    let h = a / n as f64;
    assert!((xs[n + 1] - xs[n] - h).abs() < 1e-9, "{xs:?}");
    assert!((xs[n + m] - l).abs() < tol);
    // The groups cover the box faces: areas.
    let area = |g: &str| -> f64 {
        mesh.facet_group(g)
            .unwrap()
            .iter()
            .map(|f| {
                let x: Vec<[f64; 3]> = f.nodes.iter().map(|&i| mesh.coords[i]).collect();
                let d1 = [x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]];
                let d2 = [x[3][0] - x[1][0], x[3][1] - x[1][1], x[3][2] - x[1][2]];
                let c = [
                    d1[1] * d2[2] - d1[2] * d2[1],
                    d1[2] * d2[0] - d1[0] * d2[2],
                    d1[0] * d2[1] - d1[1] * d2[0],
                ];
                0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
            })
            .sum()
    };
    for (g, want) in [
        ("contact", a * a),
        ("free", l * l - a * a),
        ("sym_x", l * l),
        ("sym_y", l * l),
        ("far_x", l * l),
        ("far_y", l * l),
        ("far_z", l * l),
    ] {
        assert!((area(g) - want).abs() < 1e-9 * l * l, "{g}: {}", area(g));
    }
}

#[test]
fn grading_for_first_cell_matches_the_progression() {
    let g = grading_for_first_cell(10.0, 0.25, 8).unwrap();
    let r = g.powf(1.0 / 7.0);
    let total: f64 = (0..8).map(|i| 0.25 * r.powi(i)).sum();
    assert!((total - 10.0).abs() < 1e-9);
    assert!(grading_for_first_cell(1.0, 0.25, 4).is_err());
    assert!(grading_for_first_cell(1.0, 0.25, 1).is_err());
}

#[test]
fn bad_blocks_are_errors() {
    let ok = HexBlock::cuboid([0.0; 3], [1.0; 3], [1, 1, 1]);
    let check = |blocks: &[HexBlock], what: &str| match multiblock_hex(blocks) {
        Err(MeshError::Invalid(m)) => assert!(m.contains(what), "{m}"),
        other => panic!("expected an error with '{what}', got {other:?}"),
    };
    check(&[], "needs blocks");
    let mut b = ok.clone();
    b.n = [1, 0, 1];
    check(&[b], "cell counts");
    check(&[ok.clone().grading([1.0, -1.0, 1.0])], "gradings");
    let mut b = ok.clone();
    b.corners[6] = [f64::NAN, 0.0, 0.0];
    check(&[b], "non-finite");
    // A corner pushed through the opposite face: the block folds.
    let mut b = ok.clone();
    b.corners[6] = [-0.5, -0.5, -0.5];
    check(&[b], "non-positive Jacobian");
    // The same block twice: overlapping.
    let b = HexBlock::cuboid([0.0; 3], [1.0; 3], [2, 2, 2]);
    check(&[b.clone(), b], "more than two cells");
    assert!(corner_refined_blocks(1.0, 0.5, 2, 3).is_err());
    assert!(corner_refined_blocks(1.0, 2.0, 2, 3).is_err());
}
