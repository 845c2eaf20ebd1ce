//! Edges of a 2D mesh of Tri3/Quad4/Tri6/Quad8 cells: each edge once, oriented outward from its
//! first cell, with its one or two cells and its mid-side node (quadratic cells); node-to-edge
//! and node-to-cell incidences. Edges must be straight (a quadratic edge's mid node at the
//! middle of its end nodes).

use std::collections::HashMap;

use alea_mesh::{CellType, Mesh};

use crate::CreError;

/// One edge of the mesh.
#[derive(Clone, Debug)]
pub struct Edge {
    /// End nodes, in the (outward, counter-clockwise) order of the first cell's facet.
    pub nodes: [usize; 2],
    /// Mid-side node of a quadratic edge.
    pub mid: Option<usize>,
    /// `(cell, local facet index)`: the first cell defines the orientation (`eta = +1`); an
    /// interior edge has a second cell (`eta = -1`).
    pub cells: Vec<(usize, usize)>,
}

impl Edge {
    /// True for a boundary edge (one cell).
    pub fn is_boundary(&self) -> bool {
        self.cells.len() == 1
    }

    /// Position of node `i` on the edge: 0 and 1 for the ends, 2 for the mid node.
    pub fn slot(&self, i: usize) -> Option<usize> {
        if self.nodes[0] == i {
            Some(0)
        } else if self.nodes[1] == i {
            Some(1)
        } else if self.mid == Some(i) {
            Some(2)
        } else {
            None
        }
    }

    /// All nodes (ends, then mid node).
    pub fn all_nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.nodes.iter().copied().chain(self.mid)
    }

    /// Edge shape functions at `s in [0, 1]` (ends, mid; the mid entry is 0 on a linear edge).
    pub fn shape(&self, s: f64) -> [f64; 3] {
        if self.mid.is_some() {
            [
                (1.0 - s) * (1.0 - 2.0 * s),
                s * (2.0 * s - 1.0),
                4.0 * s * (1.0 - s),
            ]
        } else {
            [1.0 - s, s, 0.0]
        }
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
    /// Builds the topology; every cell must be a Tri3, Quad4, Tri6 or Quad8 with straight edges.
    pub fn new(mesh: &Mesh) -> Result<Self, CreError> {
        let mut edges: Vec<Edge> = Vec::new();
        let mut index = HashMap::new();
        let mut cell_edges = Vec::with_capacity(mesh.num_cells());
        let mut node_cells = vec![Vec::new(); mesh.num_nodes()];
        for (c, kind, nodes) in mesh.cells() {
            if !matches!(
                kind,
                CellType::Tri3 | CellType::Quad4 | CellType::Tri6 | CellType::Quad8
            ) {
                return Err(CreError::UnsupportedCell {
                    cell: c,
                    kind: kind.to_string(),
                });
            }
            let mut ce = Vec::new();
            for (l, (_, loc)) in kind.facets().iter().enumerate() {
                let (a, b) = (nodes[loc[0]], nodes[loc[1]]);
                let mid = loc.get(2).map(|&k| nodes[k]);
                if let Some(m) = mid {
                    let (xa, xb, xm) = (mesh.coords[a], mesh.coords[b], mesh.coords[m]);
                    let len = ((xb[0] - xa[0]).powi(2) + (xb[1] - xa[1]).powi(2)).sqrt();
                    let off = ((xm[0] - 0.5 * (xa[0] + xb[0])).powi(2)
                        + (xm[1] - 0.5 * (xa[1] + xb[1])).powi(2))
                    .sqrt();
                    if off > 1e-8 * len {
                        return Err(CreError::Invalid(format!(
                            "cell {c}: curved edge ({a}, {m}, {b}) (mid node off the chord by {off:e}); only straight edges are supported"
                        )));
                    }
                }
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
                            mid,
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
            for n in edge.all_nodes() {
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
