//! Cell geometry: Jacobian determinants of the isoparametric map and cell measures.
//!
//! The map from the reference cell is x(xi) = sum_a N_a(xi) x_a with the VTK-ordered nodes.
//! Reference cells: triangles and tetrahedra on the unit simplex (xi_i >= 0, sum <= 1), quads and
//! hexahedra on [-1, 1]^d. In 2D only x and y are used. `det J` is positive for a cell oriented
//! counter-clockwise (2D) or right-handed (3D). These are quality checks for meshes (orientation,
//! areas), on the shape functions of [`crate::reference`].

use crate::reference::{MAX_NODES, node_coords, shape};
use crate::{CellType, Mesh};

/// det J of the map of a cell with node coordinates `x` at reference point `xi` (2D cells use
/// x and y; 1D cells give the length scale |dx/dxi|).
pub(crate) fn jacobian_det(kind: CellType, x: &[[f64; 3]], xi: [f64; 3]) -> f64 {
    let (mut n, mut d) = ([0.0; MAX_NODES], [[0.0; 3]; MAX_NODES]);
    shape(kind, xi, &mut n, &mut d);
    let mut j = [[0.0; 3]; 3]; // j[i][k] = dx_i / dxi_k
    for (a, da) in d[..kind.num_nodes()].iter().enumerate() {
        for i in 0..3 {
            for k in 0..3 {
                j[i][k] += x[a][i] * da[k];
            }
        }
    }
    match kind.dim() {
        1 => (j[0][0] * j[0][0] + j[1][0] * j[1][0] + j[2][0] * j[2][0]).sqrt(),
        2 => j[0][0] * j[1][1] - j[0][1] * j[1][0],
        _ => {
            j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
                - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0])
        }
    }
}

/// Quadrature rule (points, weights) on the reference cell, exact enough for the measure of
/// cells of the type (degree 5 per direction on quads/hexes, 4 on triangles, 3 on tetrahedra).
fn quadrature(kind: CellType) -> Vec<([f64; 3], f64)> {
    use CellType::*;
    let g3 = [
        (-(0.6f64).sqrt(), 5.0 / 9.0),
        (0.0, 8.0 / 9.0),
        ((0.6f64).sqrt(), 5.0 / 9.0),
    ];
    match kind {
        Line2 | Line3 => g3.iter().map(|&(p, w)| ([p, 0.0, 0.0], w)).collect(),
        Quad4 | Quad8 => {
            let mut q = Vec::new();
            for &(a, wa) in &g3 {
                for &(b, wb) in &g3 {
                    q.push(([a, b, 0.0], wa * wb));
                }
            }
            q
        }
        Hex8 => {
            let mut q = Vec::new();
            for &(a, wa) in &g3 {
                for &(b, wb) in &g3 {
                    for &(c, wc) in &g3 {
                        q.push(([a, b, c], wa * wb * wc));
                    }
                }
            }
            q
        }
        Tri3 | Tri6 => {
            // Strang-Fix / Dunavant 6-point rule, degree 4 (weights sum to 1/2).
            let (a1, w1) = (0.445_948_490_915_965, 0.223_381_589_678_011);
            let (a2, w2) = (0.091_576_213_509_771, 0.109_951_743_655_322);
            let mut q = Vec::new();
            for (a, w) in [(a1, w1), (a2, w2)] {
                let b = 1.0 - 2.0 * a;
                for p in [[a, a, 0.0], [b, a, 0.0], [a, b, 0.0]] {
                    q.push((p, 0.5 * w));
                }
            }
            q
        }
        Tet4 | Tet10 => {
            // Keast degree-3 rule (5 points).
            let mut q = vec![([0.25, 0.25, 0.25], -4.0 / 30.0)];
            let (a, b) = (1.0 / 6.0, 0.5);
            for p in [[a, a, a], [b, a, a], [a, b, a], [a, a, b]] {
                q.push((p, 9.0 / 120.0));
            }
            q
        }
    }
}

impl Mesh {
    /// Coordinates of the nodes of cell `c`.
    pub fn cell_coords(&self, c: usize) -> Vec<[f64; 3]> {
        self.cell_nodes(c).iter().map(|&n| self.coords[n]).collect()
    }

    /// Area (2D) or volume (3D) of cell `c`, integrated with a Gauss rule on the
    /// isoparametric map (exact for straight-sided cells and for quadratic cells' curved sides).
    pub fn cell_measure(&self, c: usize) -> f64 {
        let kind = self.cell_type(c);
        let x = self.cell_coords(c);
        quadrature(kind)
            .iter()
            .map(|&(p, w)| w * jacobian_det(kind, &x, p))
            .sum()
    }

    /// Smallest det J of cell `c` over its nodes (and centre): positive for a valid,
    /// counter-clockwise (2D) or right-handed (3D) cell.
    pub fn cell_min_jacobian(&self, c: usize) -> f64 {
        let kind = self.cell_type(c);
        let x = self.cell_coords(c);
        let mut pts = node_coords(kind);
        let n = pts.len() as f64;
        let mut centre = [0.0; 3];
        for p in &pts {
            for d in 0..3 {
                centre[d] += p[d] / n;
            }
        }
        pts.push(centre);
        pts.iter()
            .map(|&p| jacobian_det(kind, &x, p))
            .fold(f64::INFINITY, f64::min)
    }

    /// Sum of the cell measures: the area (2D) or volume (3D) of the mesh.
    pub fn measure(&self) -> f64 {
        (0..self.num_cells()).map(|c| self.cell_measure(c)).sum()
    }
}
