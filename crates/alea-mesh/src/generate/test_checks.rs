//! Checks shared by the generators' unit tests: group measures and coincident interface nodes.

use crate::Mesh;
use crate::vec3::{norm, sub};

/// Sum of the measures (area in 2D, volume in 3D) of the cells of group `g`.
pub(super) fn group_measure(m: &Mesh, g: &str) -> f64 {
    m.cell_group(g)
        .unwrap()
        .iter()
        .map(|&c| m.cell_measure(c))
        .sum()
}

/// Every node of `s1` has a partner of `s2` within `tol` (and the groups have as many nodes);
/// `distinct`: the two groups share no node.
pub(super) fn assert_coincident(m: &Mesh, s1: &str, s2: &str, tol: f64, distinct: bool) {
    let (na, nb) = (m.group_nodes(s1).unwrap(), m.group_nodes(s2).unwrap());
    assert_eq!(na.len(), nb.len(), "{s1} / {s2}");
    for &i in &na {
        assert!(
            !distinct || !nb.contains(&i),
            "{s1}: node {i} is also on {s2}"
        );
        let d = nb
            .iter()
            .map(|&j| norm(&sub(&m.coords[i], &m.coords[j])))
            .fold(f64::INFINITY, f64::min);
        assert!(d < tol, "{s1}: node {i} has no partner on {s2}");
    }
}
