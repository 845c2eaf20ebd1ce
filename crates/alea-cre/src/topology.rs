//! Edges of a 2D mesh of Tri3/Quad4 cells: each edge once, oriented outward from its first
//! cell, with its one or two cells; node-to-edge and node-to-cell incidences.

use std::collections::HashMap;

use alea_mesh::{CellType, Mesh};

use crate::CreError;

/// One edge of the mesh.
#[derive(Clone, Debug)]
pub struct Edge {
    /// End nodes, in the (outward, counter-clockwise) order of the first cell's facet.
    pub nodes: [usize; 2],
    /// `(cell, local facet index)`: the first cell defines the orientation (`eta = +1`); an
    /// interior edge has a second cell (`eta = -1`).
    pub cells: Vec<(usize, usize)>,
}

impl Edge {
    /// True for a boundary edge (one cell).
    pub fn is_boundary(&self) -> bool {
        self.cells.len() == 1
    }
}

/// Edges and incidences.
#[derive(Clone, Debug)]
pub struct Topology {
    /// Every edge once.
    pub edges: Vec<Edge>,
    /// For each cell, its edges in local facet order, with the sign `eta` (+1 if the cell is the
    /// edge's first cell).
    pub cell_edges: Vec<Vec<(usize, f64)>>,
    /// Edges incident to each node.
    pub node_edges: Vec<Vec<usize>>,
    /// Cells incident to each node.
    pub node_cells: Vec<Vec<usize>>,
    index: HashMap<[usize; 2], usize>,
}

fn key(a: usize, b: usize) -> [usize; 2] {
    if a < b { [a, b] } else { [b, a] }
}

impl Topology {
    /// Builds the topology; every cell must be a Tri3 or Quad4.
    pub fn new(mesh: &Mesh) -> Result<Self, CreError> {
        let mut edges: Vec<Edge> = Vec::new();
        let mut index = HashMap::new();
        let mut cell_edges = Vec::with_capacity(mesh.num_cells());
        let mut node_cells = vec![Vec::new(); mesh.num_nodes()];
        for (c, kind, nodes) in mesh.cells() {
            if !matches!(kind, CellType::Tri3 | CellType::Quad4) {
                return Err(CreError::UnsupportedCell {
                    cell: c,
                    kind: kind.to_string(),
                });
            }
            let mut ce = Vec::new();
            for (l, (_, loc)) in kind.facets().iter().enumerate() {
                let (a, b) = (nodes[loc[0]], nodes[loc[1]]);
                match index.get(&key(a, b)) {
                    Some(&e) => {
                        let edge: &mut Edge = &mut edges[e];
                        if edge.cells.len() >= 2 {
                            return Err(CreError::Invalid(format!(
                                "edge ({a}, {b}) is shared by more than two cells"
                            )));
                        }
                        edge.cells.push((c, l));
                        ce.push((e, -1.0));
                    }
                    None => {
                        index.insert(key(a, b), edges.len());
                        ce.push((edges.len(), 1.0));
                        edges.push(Edge {
                            nodes: [a, b],
                            cells: vec![(c, l)],
                        });
                    }
                }
            }
            for &n in nodes {
                node_cells[n].push(c);
            }
            cell_edges.push(ce);
        }
        let mut node_edges = vec![Vec::new(); mesh.num_nodes()];
        for (e, edge) in edges.iter().enumerate() {
            for &n in &edge.nodes {
                node_edges[n].push(e);
            }
        }
        Ok(Topology {
            edges,
            cell_edges,
            node_edges,
            node_cells,
            index,
        })
    }

    /// The edge joining nodes `a` and `b`, if any.
    pub fn find(&self, a: usize, b: usize) -> Option<usize> {
        self.index.get(&key(a, b)).copied()
    }

    /// Outward unit normal (w.r.t. the first cell), length and end points of edge `e`.
    pub fn geometry(&self, mesh: &Mesh, e: usize) -> ([f64; 2], f64, [[f64; 3]; 2]) {
        let [a, b] = self.edges[e].nodes;
        let (xa, xb) = (mesh.coords[a], mesh.coords[b]);
        let t = [xb[0] - xa[0], xb[1] - xa[1]];
        let len = (t[0] * t[0] + t[1] * t[1]).sqrt();
        ([t[1] / len, -t[0] / len], len, [xa, xb])
    }
}
