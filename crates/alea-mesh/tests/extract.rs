//! Sub-mesh extraction and appending.

mod common;

use alea_mesh::CellType::*;
use alea_mesh::generate::{plate_with_hole, rectangle};
use common::*;

/// A 4 x 2 rectangle of width 4 split into "left" (x < 2) and "right" cell groups.
fn split_rectangle(kind: alea_mesh::CellType) -> alea_mesh::Mesh {
    let mut m = rectangle(4.0, 2.0, 4, 2, kind).unwrap();
    let (mut left, mut right) = (Vec::new(), Vec::new());
    for c in 0..m.num_cells() {
        let k = m.cell_type(c).num_corners();
        let xc: f64 = m.cell_nodes(c)[..k]
            .iter()
            .map(|&n| m.coords[n][0])
            .sum::<f64>()
            / k as f64;
        if xc < 2.0 {
            left.push(c)
        } else {
            right.push(c)
        }
    }
    m.add_cells_to_group("left", left);
    m.add_cells_to_group("right", right);
    // An interface facet group along x = 2, oriented from the right part (outward of "right").
    let iface: Vec<alea_mesh::Facet> = m
        .cells()
        .filter(|(c, _, _)| m.cell_group("right").unwrap().contains(c))
        .flat_map(|(_, kind, nodes)| {
            kind.facets().iter().map(move |(fk, loc)| alea_mesh::Facet {
                kind: *fk,
                nodes: loc.iter().map(|&i| nodes[i]).collect(),
            })
        })
        .filter(|f| {
            f.nodes
                .iter()
                .all(|&n| (m.coords[n][0] - 2.0).abs() < 1e-12)
        })
        .collect();
    assert_eq!(iface.len(), 2);
    let nodes: Vec<usize> = iface.iter().flat_map(|f| f.nodes.clone()).collect();
    m.add_facets_to_group("iface", iface);
    m.add_nodes_to_group("iface", nodes);
    m
}

#[test]
fn extract_left_part() {
    for kind in [Quad4, Quad8, Tri3, Tri6] {
        let m = split_rectangle(kind);
        let (sub, map) = m.extract(&["left"]).unwrap();
        sub.validate().unwrap();
        assert_eq!(sub.num_cells(), m.cell_group("left").unwrap().len());
        assert!(map.windows(2).all(|w| w[0] < w[1]));
        for (new, &old) in map.iter().enumerate() {
            assert_eq!(sub.coords[new], m.coords[old]);
            assert!(m.coords[old][0] <= 2.0 + 1e-12);
        }
        // Every parent node with x <= 2 is in the left part.
        let expected = m.coords.iter().filter(|x| x[0] <= 2.0 + 1e-12).count();
        assert_eq!(sub.num_nodes(), expected);
        assert!((sub.measure() - 4.0).abs() < 1e-12);
        assert_positive_jacobians(&sub);
        // Groups: "right" and "xmax" are gone, "left" and "domain" hold all cells.
        assert!(!sub.cell_groups.contains_key("right"));
        assert_eq!(sub.cell_group("left").unwrap().len(), sub.num_cells());
        assert_eq!(sub.cell_group("domain").unwrap().len(), sub.num_cells());
        assert!(!sub.facet_groups.contains_key("xmax"));
        assert!(!sub.node_groups.contains_key("xmax"));
        assert_eq!(sub.facet_group("xmin").unwrap().len(), 2);
        assert_eq!(sub.facet_group("ymin").unwrap().len(), 2);
        assert_eq!(
            sub.node_groups["ymin"].len(),
            if kind.order() == 2 { 5 } else { 3 }
        );
        // The interface facets are kept, re-oriented outward from the left part.
        let iface = sub.facet_group("iface").unwrap();
        assert_eq!(iface.len(), 2);
        let b = boundary_set(&sub);
        for f in iface {
            assert!(b.contains(&f.nodes));
        }
        assert_groups_outward(&sub);
    }
}

#[test]
fn extract_then_append_restores_cells() {
    let m = plate_with_hole(1.0, 4.0, 6, 4, 2.0, Quad8).unwrap();
    let (all, map) = m.extract(&["domain"]).unwrap();
    assert_eq!(all.num_nodes(), m.num_nodes());
    assert_eq!(map, (0..m.num_nodes()).collect::<Vec<_>>());
    assert_eq!(all.facet_groups, m.facet_groups);
    let parts = split_rectangle(Quad4);
    let (l, _) = parts.extract(&["left"]).unwrap();
    let (r, _) = parts.extract(&["right"]).unwrap();
    let mut joined = l.clone();
    let off = joined.append(&r).unwrap();
    assert_eq!(off, l.num_nodes());
    assert_eq!(joined.num_cells(), parts.num_cells());
    // The interface nodes are duplicated (not merged).
    assert_eq!(joined.num_nodes(), parts.num_nodes() + 3);
    assert_eq!(joined.facet_group("iface").unwrap().len(), 4);
    assert!(m.extract(&["nope"]).is_err());
    assert!(m.extract(&[]).is_err());
    assert!(joined.append(&alea_mesh::Mesh::new(3)).is_err());
}

#[test]
fn cell_map_relates_sub_cells_to_parent_cells() {
    let m = split_rectangle(Quad8);
    let (sub, nodes, cells) = m.extract_with_cells(&["right"]).unwrap();
    assert_eq!(cells, m.cell_group("right").unwrap());
    for (new, &old) in cells.iter().enumerate() {
        let parent: Vec<usize> = m.cell_nodes(old).to_vec();
        let mapped: Vec<usize> = sub.cell_nodes(new).iter().map(|&n| nodes[n]).collect();
        assert_eq!(parent, mapped);
    }
}
