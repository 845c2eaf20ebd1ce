//! The two-body generators: both bodies present with their groups, contact faces whose nodes
//! coincide one to one (what node-to-node interfaces pair), the geometry each promises (the
//! incline's slope, the rings' radii, the flat Hertz strip), positive cells.

use alea_mesh::generate::{
    ConcentricRings, CylinderOnBlock, StackedBlocks, block_on_incline, concentric_rings,
    cylinder_on_block, stacked_blocks,
};
use alea_mesh::{CellType, Mesh};

/// Sorted coordinates of the nodes of a facet group.
fn face(mesh: &Mesh, group: &str) -> Vec<[f64; 3]> {
    let mut nodes: Vec<usize> = mesh
        .facet_group(group)
        .unwrap()
        .iter()
        .flat_map(|f| f.nodes.clone())
        .collect();
    nodes.sort_unstable();
    nodes.dedup();
    let mut x: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
    x.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    x
}

fn coincide(mesh: &Mesh, g1: &str, g2: &str, tol: f64) -> usize {
    let (a, b) = (face(mesh, g1), face(mesh, g2));
    assert_eq!(a.len(), b.len(), "{g1} / {g2}");
    for (p, q) in a.iter().zip(&b) {
        let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
        assert!(d <= tol, "{g1} / {g2}: {p:?} vs {q:?}");
    }
    a.len()
}

fn positive_cells(mesh: &Mesh) {
    for c in 0..mesh.num_cells() {
        assert!(mesh.cell_min_jacobian(c) > 0.0, "cell {c}");
    }
}

#[test]
fn stacked_blocks_and_incline() {
    let p = StackedBlocks::default();
    let m = stacked_blocks(&p, CellType::Quad4).unwrap();
    assert_eq!(m.num_cells(), p.n_x * (p.n_lower + p.n_upper));
    assert_eq!(coincide(&m, "lower_top", "upper_bottom", 0.0), p.n_x + 1);
    assert!(face(&m, "lower_top").iter().all(|x| x[1] == 0.0));
    positive_cells(&m);
    let a = 20f64.to_radians();
    let m = block_on_incline(&p, a, CellType::Quad4).unwrap();
    coincide(&m, "lower_top", "upper_bottom", 1e-12);
    let top = face(&m, "lower_top");
    let (first, last) = (top[0], top[top.len() - 1]);
    let slope = (last[1] - first[1]).atan2(last[0] - first[0]);
    assert!((slope - a).abs() < 1e-12, "{slope}");
    positive_cells(&m);
    assert!(block_on_incline(&p, 2.0, CellType::Quad4).is_err());
}

#[test]
fn concentric_rings_meet_at_the_contact_radius() {
    let p = ConcentricRings::default();
    let m = concentric_rings(&p, CellType::Quad8).unwrap();
    let n = coincide(&m, "inner_contact", "outer_contact", 1e-9);
    assert_eq!(n, 2 * p.n_theta + 1);
    for (g, r) in [
        ("inner_inner", p.r_in),
        ("inner_contact", p.r_contact),
        ("outer_outer", p.r_out),
    ] {
        for x in face(&m, g) {
            assert!(
                ((x[0] * x[0] + x[1] * x[1]).sqrt() - r).abs() < 1e-9 * r,
                "{g}"
            );
        }
    }
    assert_eq!(m.cell_group("inner").unwrap().len(), p.n_inner * p.n_theta);
    positive_cells(&m);
}

#[test]
fn cylinder_on_block_has_a_flat_matching_strip() {
    let p = CylinderOnBlock {
        n: 10,
        m: 8,
        ..CylinderOnBlock::default()
    };
    for half in [true, false] {
        let m = cylinder_on_block(&CylinderOnBlock { half, ..p }, CellType::Quad4).unwrap();
        let n = coincide(&m, "block_contact", "cylinder_contact", 0.0);
        assert_eq!(n, if half { p.n + 1 } else { 2 * p.n + 1 });
        assert!(
            face(&m, "block_contact")
                .iter()
                .all(|x| x[1] == 0.0 && x[0].abs() <= p.a)
        );
        assert!(
            face(&m, "cylinder_far")
                .iter()
                .all(|x| (x[1] - p.l).abs() < 1e-12)
        );
        assert_eq!(m.facet_group("block_sym").is_ok(), half);
        positive_cells(&m);
    }
    assert!(cylinder_on_block(&CylinderOnBlock { l: 2.5, ..p }, CellType::Quad4).is_err());
}
