//! The side topology a cell family gives the equilibrated-traction kernel: the sides `Gamma`
//! of the cells (edges in 2D, faces in 3D), each oriented by its first cell (`eta_(E,Gamma) =
//! +1` there, `-1` in the second cell of an interior side), and the node-to-cell and
//! node-to-side incidences the node systems (3.22) are written on.

use alea_mesh::Mesh;

use super::vector::Frame;

/// One side: its cells (one on the boundary, two inside) and its nodes in slot order.
pub trait Side: Sync {
    /// `(cell, local facet index)`; the first cell defines the orientation.
    fn cells(&self) -> &[(usize, usize)];

    /// The nodes in slot order.
    fn nodes(&self) -> impl Iterator<Item = usize> + '_;

    /// Position of node `i` among the nodes.
    fn slot(&self, i: usize) -> Option<usize> {
        self.nodes().position(|n| n == i)
    }
}

/// The incidence lists of a side topology.
pub struct Incidence<'a> {
    /// For each cell, its sides with their signs `eta`.
    pub cell_sides: &'a [Vec<(usize, f64)>],
    /// For each node, the cells around it.
    pub node_cells: &'a [Vec<usize>],
    /// For each node, the sides around it.
    pub node_sides: &'a [Vec<usize>],
}

/// Sides and incidences of a mesh of one cell family (`D` the spatial dimension).
pub trait SideTopology<const D: usize>: Sync {
    /// The type of a side.
    type Side: Side;

    /// The name of a side in messages (`"edge"`, `"face"`).
    const SIDE: &'static str;

    /// Every side once.
    fn sides(&self) -> &[Self::Side];

    /// Number of sides.
    fn num_sides(&self) -> usize {
        self.sides().len()
    }

    /// True for a side with one cell.
    fn is_boundary(&self, s: usize) -> bool {
        self.sides()[s].cells().len() == 1
    }

    /// Position of node `i` among the nodes of side `s`.
    fn slot(&self, s: usize, i: usize) -> Option<usize> {
        self.sides()[s].slot(i)
    }

    /// The nodes of side `s` in slot order.
    fn side_nodes(&self, s: usize) -> impl Iterator<Item = usize> + '_ {
        self.sides()[s].nodes()
    }

    /// The incidence lists.
    fn incidence(&self) -> Incidence<'_>;

    /// The sides of cell `c` with their signs `eta`.
    fn cell_sides(&self, c: usize) -> &[(usize, f64)] {
        &self.incidence().cell_sides[c]
    }

    /// The cells around node `i`.
    fn node_cells(&self, i: usize) -> &[usize] {
        &self.incidence().node_cells[i]
    }

    /// The sides around node `i`.
    fn node_sides(&self, i: usize) -> &[usize] {
        &self.incidence().node_sides[i]
    }

    /// Measure of side `s` (chord length of an edge, area of a face): the weight `|Gamma|` of the
    /// Ladeveze-Leguillon minimisation `sum (b - b_bar)^2 / |Gamma|`.
    fn measure(&self, mesh: &Mesh, s: usize) -> f64;

    /// The frame of a node from the first `nfree` rows of `free` (its free directions, as the
    /// constraints give them; `nfree = D` for an unconstrained node, 0 for a fixed one).
    fn complete_frame(free: [[f64; D]; D], nfree: usize) -> Frame<D>;
}
