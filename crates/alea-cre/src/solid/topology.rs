//! Faces of a 3D mesh of Tet4/Tet10/Hex8 cells: each face once, oriented outward from its first
//! cell, with its one or two cells, the local indices of its nodes in each of them (to map a
//! face point into either cell's reference coordinates), its area; node-to-face and
//! node-to-cell incidences. Tet10 edges must be straight (mid nodes at the middle of their
//! edge); Hex8 faces may be warped (the geometry is the bilinear face).

use std::collections::HashMap;

use alea_fem::Quadrature;
use alea_fem::kinematics::{FacetGeometry, facet_geometry};
use alea_fem::reference::{MAX_NODES, node_coords, shape};
use alea_mesh::{CellType, Mesh};

use crate::CreError;

/// One face of the mesh.
#[derive(Clone, Debug)]
pub struct Face {
    /// `Tri3`, `Tri6` or `Quad4`.
    pub kind: CellType,
    /// Nodes in the (outward) order of the first cell's facet: corners, then mid-edge nodes.
    pub nodes: Vec<usize>,
    /// `(cell, local facet index)`: the first cell defines the orientation (`eta = +1`); an
    /// interior face has a second cell (`eta = -1`).
    pub cells: Vec<(usize, usize)>,
    /// For each cell of `cells`, the local index in that cell of each node of `nodes`.
    pub local_nodes: Vec<Vec<usize>>,
    /// Area.
    pub area: f64,
}

impl Face {
    /// True for a boundary face (one cell).
    pub fn is_boundary(&self) -> bool {
        self.cells.len() == 1
    }

    /// Position of node `i` in `nodes`.
    pub fn slot(&self, i: usize) -> Option<usize> {
        self.nodes.iter().position(|&n| n == i)
    }

    /// Sorted corner nodes (the face's key).
    pub fn key(&self) -> Vec<usize> {
        let mut k = self.nodes[..self.kind.num_corners()].to_vec();
        k.sort_unstable();
        k
    }

    /// Geometry at face reference point `rs`: shape values of the face nodes, point, outward unit
    /// normal of the first cell, area factor.
    pub fn geometry(&self, mesh: &Mesh, rs: [f64; 3]) -> FacetGeometry {
        let mut coords = [[0.0; 3]; MAX_NODES];
        for (x, &n) in coords.iter_mut().zip(&self.nodes) {
            *x = mesh.coords[n];
        }
        facet_geometry(self.kind, &coords[..self.nodes.len()], rs)
    }

    /// Reference coordinates, in the `k`-th cell of `cells`, of the face point of face
    /// reference coordinates `rs` (the reference faces are flat and the face's corner shape
    /// functions map them exactly).
    pub fn cell_point(&self, mesh: &Mesh, k: usize, rs: [f64; 3]) -> [f64; 3] {
        let (cell, _) = self.cells[k];
        let refs = node_coords(mesh.cell_type(cell));
        let lin = if self.kind == CellType::Quad4 {
            CellType::Quad4
        } else {
            CellType::Tri3
        };
        let mut n = [0.0; MAX_NODES];
        let mut dn = [[0.0; 3]; MAX_NODES];
        shape(lin, rs, &mut n, &mut dn);
        let mut xi = [0.0; 3];
        for a in 0..lin.num_nodes() {
            let r = refs[self.local_nodes[k][a]];
            for d in 0..3 {
                xi[d] += n[a] * r[d];
            }
        }
        xi
    }
}

/// Faces and incidences.
#[derive(Clone, Debug)]
pub struct FaceTopology {
    /// Every face once.
    pub faces: Vec<Face>,
    /// For each cell, its faces in local facet order, with the sign `eta` (+1 if the cell is the
    /// face's first cell).
    pub cell_faces: Vec<Vec<(usize, f64)>>,
    /// Faces incident to each node.
    pub node_faces: Vec<Vec<usize>>,
    /// Cells incident to each node.
    pub node_cells: Vec<Vec<usize>>,
    index: HashMap<Vec<usize>, usize>,
}

impl FaceTopology {
    /// Builds the topology; every cell must be a Tet4, Tet10 or Hex8, Tet10 edges straight.
    pub fn new(mesh: &Mesh) -> Result<Self, CreError> {
        let mut faces: Vec<Face> = Vec::new();
        let mut index: HashMap<Vec<usize>, usize> = HashMap::new();
        let mut cell_faces = Vec::with_capacity(mesh.num_cells());
        let mut node_cells = vec![Vec::new(); mesh.num_nodes()];
        for (c, kind, nodes) in mesh.cells() {
            if !matches!(kind, CellType::Tet4 | CellType::Tet10 | CellType::Hex8) {
                return Err(CreError::UnsupportedCell {
                    cell: c,
                    kind: kind.to_string(),
                });
            }
            if kind == CellType::Tet10 {
                const EDGES: [(usize, usize, usize); 6] = [
                    (0, 1, 4),
                    (1, 2, 5),
                    (2, 0, 6),
                    (0, 3, 7),
                    (1, 3, 8),
                    (2, 3, 9),
                ];
                for (a, b, m) in EDGES {
                    let (xa, xb, xm) = (
                        mesh.coords[nodes[a]],
                        mesh.coords[nodes[b]],
                        mesh.coords[nodes[m]],
                    );
                    let len = (0..3).map(|d| (xb[d] - xa[d]).powi(2)).sum::<f64>().sqrt();
                    let off = (0..3)
                        .map(|d| (xm[d] - 0.5 * (xa[d] + xb[d])).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    if off > 1e-8 * len {
                        return Err(CreError::Invalid(format!(
                            "cell {c}: curved edge ({}, {}, {}) (mid node off the chord by {off:e}); only straight edges are supported",
                            nodes[a], nodes[m], nodes[b]
                        )));
                    }
                }
            }
            let mut cf = Vec::new();
            for (l, (fk, loc)) in kind.facets().iter().enumerate() {
                let fnodes: Vec<usize> = loc.iter().map(|&i| nodes[i]).collect();
                let mut key = fnodes[..fk.num_corners()].to_vec();
                key.sort_unstable();
                let local: Vec<usize> = loc.to_vec();
                match index.get(&key) {
                    Some(&f) => {
                        let face: &mut Face = &mut faces[f];
                        if face.cells.len() >= 2 {
                            return Err(CreError::Invalid(format!(
                                "face {key:?} is shared by more than two cells"
                            )));
                        }
                        // Local indices in this cell of the face's nodes (in the face's order).
                        let mut mine = Vec::with_capacity(face.nodes.len());
                        for &n in &face.nodes {
                            let k = fnodes.iter().position(|&m| m == n).ok_or_else(|| {
                                CreError::Invalid(format!(
                                    "face {key:?}: cells {} and {c} disagree on its nodes",
                                    face.cells[0].0
                                ))
                            })?;
                            mine.push(local[k]);
                        }
                        face.cells.push((c, l));
                        face.local_nodes.push(mine);
                        cf.push((f, -1.0));
                    }
                    None => {
                        index.insert(key, faces.len());
                        cf.push((faces.len(), 1.0));
                        faces.push(Face {
                            kind: *fk,
                            nodes: fnodes,
                            cells: vec![(c, l)],
                            local_nodes: vec![local],
                            area: 0.0,
                        });
                    }
                }
            }
            for &n in nodes {
                node_cells[n].push(c);
            }
            cell_faces.push(cf);
        }
        let mut node_faces = vec![Vec::new(); mesh.num_nodes()];
        for (f, face) in faces.iter_mut().enumerate() {
            for &n in &face.nodes {
                node_faces[n].push(f);
            }
            let rule = Quadrature::for_cell(face.kind, 4);
            face.area = rule
                .points
                .iter()
                .zip(&rule.weights)
                .map(|(rs, w)| w * face.geometry(mesh, *rs).jac)
                .sum();
            if !(face.area > 0.0 && face.area.is_finite()) {
                return Err(CreError::Invalid(format!(
                    "face {:?} has area {}",
                    face.nodes, face.area
                )));
            }
        }
        Ok(FaceTopology {
            faces,
            cell_faces,
            node_faces,
            node_cells,
            index,
        })
    }

    /// The face whose corner nodes are `corners` (any order), if any.
    pub fn find(&self, corners: &[usize]) -> Option<usize> {
        let mut k = corners.to_vec();
        k.sort_unstable();
        self.index.get(&k).copied()
    }
}

/// Consistent face mass `int N_a N_b dS` (row-major, `nn x nn`) of face `face`.
pub fn face_mass(mesh: &Mesh, face: &Face) -> Vec<f64> {
    let nn = face.nodes.len();
    let rule = Quadrature::for_cell(face.kind, 2 * face.kind.order() + 2);
    let mut m = vec![0.0; nn * nn];
    for (rs, w) in rule.points.iter().zip(&rule.weights) {
        let g = face.geometry(mesh, *rs);
        for a in 0..nn {
            for b in 0..nn {
                m[a * nn + b] += w * g.jac * g.n[a] * g.n[b];
            }
        }
    }
    m
}
