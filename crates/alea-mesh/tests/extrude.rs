//! Extrusion: a rectangle extruded equals the structured box; volumes; groups; errors.

mod common;

use std::collections::{BTreeSet, HashMap};

use alea_mesh::CellType::*;
use alea_mesh::Mesh;
use alea_mesh::generate::{box_mesh, extrude, plate_with_hole, rectangle};
use common::*;

fn key(x: [f64; 3]) -> [i64; 3] {
    x.map(|v| (v * 1e9).round() as i64)
}

fn sorted_keys(m: &Mesh, nodes: &[usize]) -> Vec<[i64; 3]> {
    let mut v: Vec<[i64; 3]> = nodes.iter().map(|&n| key(m.coords[n])).collect();
    v.sort_unstable();
    v
}

#[test]
fn extruded_rectangle_equals_box() {
    let r = rectangle(2.0, 1.0, 4, 2, Quad4).unwrap();
    let e = extrude(&r, 3, 1.5).unwrap();
    let b = box_mesh([2.0, 1.0, 1.5], [4, 2, 3], Hex8).unwrap();
    e.validate().unwrap();
    assert_positive_jacobians(&e);
    assert_conforming(&e);
    assert_groups_outward(&e);
    assert_eq!(e.num_nodes(), b.num_nodes());
    assert_eq!(e.num_cells(), b.num_cells());
    let index: HashMap<[i64; 3], usize> = e
        .coords
        .iter()
        .enumerate()
        .map(|(i, &x)| (key(x), i))
        .collect();
    let map: Vec<usize> = b.coords.iter().map(|&x| index[&key(x)]).collect();
    // Same hexahedra with the same node order (both VTK, bottom then top).
    let cells = |m: &Mesh, f: &dyn Fn(usize) -> usize| -> BTreeSet<Vec<usize>> {
        m.cells()
            .map(|(_, _, n)| n.iter().map(|&i| f(i)).collect())
            .collect()
    };
    assert_eq!(cells(&b, &|i| map[i]), cells(&e, &|i| i));
    for name in ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"] {
        let faces = |m: &Mesh, f: &dyn Fn(usize) -> usize| -> BTreeSet<Vec<usize>> {
            m.facet_group(name)
                .unwrap()
                .iter()
                .map(|fc| {
                    let mut v: Vec<usize> = fc.nodes.iter().map(|&i| f(i)).collect();
                    v.sort_unstable();
                    v
                })
                .collect()
        };
        assert_eq!(faces(&b, &|i| map[i]), faces(&e, &|i| i), "{name}");
        assert_eq!(
            sorted_keys(&b, &b.node_groups[name]),
            sorted_keys(&e, &e.node_groups[name]),
            "node group {name}"
        );
    }
    assert_eq!(e.cell_group("domain").unwrap().len(), e.num_cells());
    assert!((e.measure() - 3.0).abs() < 1e-12);
}

#[test]
fn extruded_plate_volume_and_groups() {
    let p = plate_with_hole(1.0, 4.0, 8, 6, 3.0, Quad4).unwrap();
    let e = extrude(&p, 2, 0.5).unwrap();
    assert_positive_jacobians(&e);
    assert_groups_outward(&e);
    assert!((e.measure() - 0.5 * p.measure()).abs() < 1e-12);
    assert_eq!(e.facet_group("hole").unwrap().len(), 8 * 2);
    assert_eq!(e.node_groups["hole"].len(), 9 * 3);
    for x in group_coords(&e, "hole") {
        assert!((x[0].hypot(x[1]) - 1.0).abs() < 1e-12);
    }
    for x in group_coords(&e, "zmax") {
        assert_eq!(x[2], 0.5);
    }
}

#[test]
fn extrusion_errors() {
    let t = rectangle(1.0, 1.0, 2, 2, Tri3).unwrap();
    assert!(extrude(&t, 2, 1.0).is_err());
    let q8 = rectangle(1.0, 1.0, 2, 2, Quad8).unwrap();
    assert!(extrude(&q8, 2, 1.0).is_err());
    let q = rectangle(1.0, 1.0, 2, 2, Quad4).unwrap();
    assert!(extrude(&q, 0, 1.0).is_err());
    assert!(extrude(&q, 2, -1.0).is_err());
    let b = box_mesh([1.0; 3], [1; 3], Hex8).unwrap();
    assert!(extrude(&b, 1, 1.0).is_err());
}
