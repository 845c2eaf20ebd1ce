//! Edges of a 2D mesh of Tri3/Quad4/Tri6/Quad8 cells: each edge once, oriented outward from its
//! first cell, with its one or two cells and its mid-side node (quadratic cells); node-to-edge
//! and node-to-cell incidences.
//!
//! A quadratic edge whose mid node is off the middle of its end nodes is **curved**: its
//! geometry is the isoparametric one of the cells, `x(s) = N_0(s) x_a + N_1(s) x_b + N_2(s)
//! x_m`, `s in [0, 1]` ([`Edge::shape`]), with the tangent `x'(s)`, the length element
//! `J(s) = |x'(s)|` and the normal `n(s) = (x'_y, -x'_x) / J` ([`Edge::point`]). On a straight
//! edge these reduce to the chord's (`J = L`, constant `n`). How densities live on curved edges:
//! [`crate::eet::phase1`].

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
    /// Node coordinates `[x_a, x_b, x_m]` (2D; `x_m` the middle of the chord on a 2-node edge).
    pub coords: [[f64; 2]; 3],
    /// True for a quadratic edge whose mid node is off the middle of the chord (by more than
    /// `1e-8` of the chord length).
    pub curved: bool,
}

/// A point of an edge at parameter `s in [0, 1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgePoint {
    /// Physical point `x(s)`.
    pub x: [f64; 3],
    /// Unit normal `n(s)` (outward for the edge's first cell).
    pub n: [f64; 2],
    /// Length element `J(s) = |dx/ds|` (`dS = J ds`; the chord length on a straight edge).
    pub jac: f64,
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

    /// Chord length `|x_b - x_a|`.
    pub fn chord(&self) -> f64 {
        let [xa, xb, _] = self.coords;
        ((xb[0] - xa[0]).powi(2) + (xb[1] - xa[1]).powi(2)).sqrt()
    }

    /// Point, normal and length element at `s in [0, 1]` on the (isoparametric) edge.
    pub fn point(&self, s: f64) -> EdgePoint {
        point_on(&self.coords, self.curved, s)
    }
}

/// [`Edge::point`] of the edge with node coordinates `[x_a, x_b, x_m]`.
fn point_on(coords: &[[f64; 2]; 3], curved: bool, s: f64) -> EdgePoint {
    let [xa, xb, xm] = *coords;
    let (x, t) = if curved {
        let sh = [
            (1.0 - s) * (1.0 - 2.0 * s),
            s * (2.0 * s - 1.0),
            4.0 * s * (1.0 - s),
        ];
        let d = [4.0 * s - 3.0, 4.0 * s - 1.0, 4.0 - 8.0 * s];
        let mut x = [0.0; 3];
        let mut t = [0.0; 2];
        for (k, p) in [xa, xb, xm].iter().enumerate() {
            for c in 0..2 {
                x[c] += sh[k] * p[c];
                t[c] += d[k] * p[c];
            }
        }
        (x, t)
    } else {
        (
            [
                (1.0 - s) * xa[0] + s * xb[0],
                (1.0 - s) * xa[1] + s * xb[1],
                0.0,
            ],
            [xb[0] - xa[0], xb[1] - xa[1]],
        )
    };
    let jac = (t[0] * t[0] + t[1] * t[1]).sqrt();
    EdgePoint {
        x,
        n: [t[1] / jac, -t[0] / jac],
        jac,
    }
}

/// [`Edge::point`] of the facet with nodes `nodes` (`[a, b]` or `[a, b, mid]`) of `mesh`.
pub(crate) fn facet_point_at(mesh: &Mesh, nodes: &[usize], s: f64) -> EdgePoint {
    let (xa, xb) = (mesh.coords[nodes[0]], mesh.coords[nodes[1]]);
    let xm = match nodes.get(2) {
        Some(&m) => mesh.coords[m],
        None => [0.5 * (xa[0] + xb[0]), 0.5 * (xa[1] + xb[1]), 0.0],
    };
    let curved = nodes.len() == 3 && is_curved(xa, xb, xm);
    point_on(&[[xa[0], xa[1]], [xb[0], xb[1]], [xm[0], xm[1]]], curved, s)
}

/// True if the mid node `xm` of the quadratic edge `(xa, xb)` is off the middle of the chord
/// (by more than `1e-8` of its length).
fn is_curved(xa: [f64; 3], xb: [f64; 3], xm: [f64; 3]) -> bool {
    let len = ((xb[0] - xa[0]).powi(2) + (xb[1] - xa[1]).powi(2)).sqrt();
    let off =
        ((xm[0] - 0.5 * (xa[0] + xb[0])).powi(2) + (xm[1] - 0.5 * (xa[1] + xb[1])).powi(2)).sqrt();
    off > 1e-8 * len
}

/// True if cell `c` of `mesh` (2D) has a curved edge (a quadratic facet whose mid node is off
/// the middle of its chord). The phase-2 rules of such cells are richer
/// ([`crate::eet::phase2::Phase2Rules::volume`]).
pub fn cell_is_curved(mesh: &Mesh, c: usize) -> bool {
    let kind = mesh.cell_type(c);
    let nodes = mesh.cell_nodes(c);
    kind.facets().iter().any(|(_, loc)| {
        loc.len() == 3
            && is_curved(
                mesh.coords[nodes[loc[0]]],
                mesh.coords[nodes[loc[1]]],
                mesh.coords[nodes[loc[2]]],
            )
    })
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
    /// Builds the topology; every cell must be a Tri3, Quad4, Tri6 or Quad8 (quadratic edges
    /// may be curved).
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
                        let (xa, xb) = (mesh.coords[a], mesh.coords[b]);
                        let xm = match mid {
                            Some(m) => mesh.coords[m],
                            None => [0.5 * (xa[0] + xb[0]), 0.5 * (xa[1] + xb[1]), 0.0],
                        };
                        edges.push(Edge {
                            nodes: [a, b],
                            mid,
                            cells: vec![(c, l)],
                            coords: [[xa[0], xa[1]], [xb[0], xb[1]], [xm[0], xm[1]]],
                            curved: mid.is_some() && is_curved(xa, xb, xm),
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

    /// Outward unit normal (w.r.t. the first cell), length and end points of the **chord** of
    /// edge `e` (the edge itself when straight; see [`Edge::point`] for curved edges).
    pub fn geometry(&self, mesh: &Mesh, e: usize) -> ([f64; 2], f64, [[f64; 3]; 2]) {
        let [a, b] = self.edges[e].nodes;
        let (xa, xb) = (mesh.coords[a], mesh.coords[b]);
        let t = [xb[0] - xa[0], xb[1] - xa[1]];
        let len = (t[0] * t[0] + t[1] * t[1]).sqrt();
        ([t[1] / len, -t[0] / len], len, [xa, xb])
    }
}
