//! The distribution of per-point interface terms to the cells whose facets carry them
//! (`alea_latin::interface::distribute_to_cells`): with the side's own lumped weights the cell
//! values add up to the point terms, each cell gets the measure of its side facets, and cells
//! off the side get nothing.

use alea_latin::interface::{distribute_to_cells, facet_shares, side_geometry};
use alea_mesh::CellType;
use alea_mesh::generate::rectangle;

#[test]
fn cell_terms_add_up_to_the_point_terms_on_the_cells_of_the_side() {
    for kind in [CellType::Quad4, CellType::Quad8, CellType::Tri6] {
        let (lx, th) = (2.0, 0.5);
        let mesh = rectangle(lx, 1.0, 5, 3, kind).unwrap();
        let side = side_geometry(&mesh, "ymax", th).unwrap();
        // Terms m_p (x_p^2, 1) at each point: densities x^2 and 1 at the nodes.
        let terms: Vec<[f64; 2]> = side
            .nodes
            .iter()
            .zip(&side.weights)
            .map(|(&n, &m)| [m * mesh.coords[n][0].powi(2), m])
            .collect();
        let mut cells = vec![[0.0; 3]; mesh.num_cells()];
        let facets = facet_shares(&mesh, "ymax", th).unwrap();
        let on_side: Vec<usize> = facets.iter().map(|f| f.cell).collect();
        distribute_to_cells(facets, &side.nodes, &terms, &side.weights, &mut cells);
        for k in 0..2 {
            let want: f64 = terms.iter().map(|t| t[k]).sum();
            let got: f64 = cells.iter().map(|c| c[k]).sum();
            assert!(
                (got - want).abs() < 1e-12 * want,
                "{kind:?} term {k}: {got} vs {want}"
            );
        }
        let measure: f64 = cells.iter().map(|c| c[2]).sum();
        assert!(
            (measure - lx * th).abs() < 1e-12,
            "{kind:?}: measure {measure}"
        );
        for (c, v) in cells.iter().enumerate() {
            if on_side.contains(&c) {
                assert!(
                    v[1] > 0.0 && v[2] > 0.0,
                    "{kind:?}: cell {c} on the side got {v:?}"
                );
                // The density 1 gives each cell its facet measure.
                assert!((v[1] - v[2]).abs() < 1e-12, "{kind:?}: cell {c} {v:?}");
            } else {
                assert_eq!(*v, [0.0; 3], "{kind:?}: cell {c} is off the side");
            }
        }
    }
}
