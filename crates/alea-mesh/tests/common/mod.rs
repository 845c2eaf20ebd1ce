//! Checks shared by the integration tests: validity, conformity and facet orientation, computed
//! from the mesh alone (no generator internals).
#![allow(dead_code)]

use std::collections::{HashMap, HashSet};

use alea_mesh::Mesh;

/// Every cell has a positive Jacobian at its nodes.
pub fn assert_positive_jacobians(m: &Mesh) {
    for c in 0..m.num_cells() {
        let j = m.cell_min_jacobian(c);
        assert!(j > 0.0, "cell {c} ({}) has min det J = {j}", m.cell_type(c));
    }
}

/// Conformity: every facet (by corner key) is shared by at most two cells, and the two cells
/// see it with opposite orientations (consistent orientation); mid-side nodes agree.
pub fn assert_conforming(m: &Mesh) {
    let mut seen: HashMap<Vec<usize>, Vec<Vec<usize>>> = HashMap::new();
    for (_, kind, nodes) in m.cells() {
        for (_, loc) in kind.facets() {
            let f: Vec<usize> = loc.iter().map(|&i| nodes[i]).collect();
            let mut k: Vec<usize> = f.clone();
            k.sort_unstable();
            seen.entry(k).or_default().push(f);
        }
    }
    for (k, fs) in &seen {
        assert!(fs.len() <= 2, "facet {k:?} shared by {} cells", fs.len());
        if fs.len() == 2 {
            assert_ne!(
                fs[0], fs[1],
                "facet {k:?} has the same orientation in both cells"
            );
        }
    }
}

/// Node vectors of the outward boundary facets.
pub fn boundary_set(m: &Mesh) -> HashSet<Vec<usize>> {
    m.boundary_facets()
        .into_iter()
        .map(|b| b.facet.nodes)
        .collect()
}

/// Every facet of every facet group is an outward boundary facet (same node order), and the
/// node group of the same name holds exactly the group's facet nodes.
pub fn assert_groups_outward(m: &Mesh) {
    let b = boundary_set(m);
    for (name, facets) in &m.facet_groups {
        assert!(!facets.is_empty(), "facet group {name} is empty");
        for f in facets {
            assert!(
                b.contains(&f.nodes),
                "facet {:?} of {name} is not an outward boundary facet",
                f.nodes
            );
        }
        let mut nodes: Vec<usize> = facets.iter().flat_map(|f| f.nodes.clone()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        assert_eq!(m.node_groups.get(name), Some(&nodes), "node group {name}");
    }
}

/// Nodes of a group (from its facets).
pub fn group_coords(m: &Mesh, name: &str) -> Vec<[f64; 3]> {
    m.group_nodes(name)
        .unwrap()
        .iter()
        .map(|&n| m.coords[n])
        .collect()
}
