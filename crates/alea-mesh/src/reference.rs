//! Shape functions and their reference derivatives for every cell type (no mesh involved), for
//! the finite elements (`alea_fem::reference` is this module) and the cell geometry of meshes.
//!
//! Reference cells and node orders are those of [`CellType`] (VTK order) and of
//! `alea_fem::quadrature`. Lagrange/serendipity functions:
//! - Line2 `(1 -+ xi)/2`; Line3 `xi(xi-1)/2, xi(xi+1)/2, 1 - xi^2`.
//! - Tri3/Tet4 barycentric `L`; Tri6/Tet10 corners `L_i (2 L_i - 1)`, mid-edge `4 L_i L_j`.
//! - Quad4/Hex8 (bi/tri)linear; Quad8 serendipity: corners
//!   `(1 + xi xi_i)(1 + eta eta_i)(xi xi_i + eta eta_i - 1)/4`, mid-sides `(1 - xi^2)(1 + eta eta_i)/2`
//!   and `(1 + xi xi_i)(1 - eta^2)/2`.

use crate::CellType;

const QUAD_CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
const HEX_CORNERS: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];
const TET10_EDGES: [(usize, usize); 6] = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)];

/// Evaluates shape functions `n[i]` and reference derivatives `dn[i][k] = dN_i/dxi_k` at `xi`.
///
/// # Panics
/// If `n` or `dn` are shorter than the number of nodes.
pub fn shape(kind: CellType, xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    let [r, s, t] = xi;
    match kind {
        CellType::Line2 => {
            n[0] = 0.5 * (1.0 - r);
            n[1] = 0.5 * (1.0 + r);
            dn[0] = [-0.5, 0.0, 0.0];
            dn[1] = [0.5, 0.0, 0.0];
        }
        CellType::Line3 => {
            n[0] = 0.5 * r * (r - 1.0);
            n[1] = 0.5 * r * (r + 1.0);
            n[2] = 1.0 - r * r;
            dn[0] = [r - 0.5, 0.0, 0.0];
            dn[1] = [r + 0.5, 0.0, 0.0];
            dn[2] = [-2.0 * r, 0.0, 0.0];
        }
        CellType::Tri3 => {
            n[0] = 1.0 - r - s;
            n[1] = r;
            n[2] = s;
            dn[0] = [-1.0, -1.0, 0.0];
            dn[1] = [1.0, 0.0, 0.0];
            dn[2] = [0.0, 1.0, 0.0];
        }
        CellType::Tri6 => {
            let l = [1.0 - r - s, r, s];
            let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
            for i in 0..3 {
                n[i] = l[i] * (2.0 * l[i] - 1.0);
                let f = 4.0 * l[i] - 1.0;
                dn[i] = [f * dl[i][0], f * dl[i][1], 0.0];
            }
            for (m, (a, b)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
                n[3 + m] = 4.0 * l[a] * l[b];
                dn[3 + m] = [
                    4.0 * (dl[a][0] * l[b] + l[a] * dl[b][0]),
                    4.0 * (dl[a][1] * l[b] + l[a] * dl[b][1]),
                    0.0,
                ];
            }
        }
        CellType::Quad4 => {
            for (i, c) in QUAD_CORNERS.iter().enumerate() {
                n[i] = 0.25 * (1.0 + c[0] * r) * (1.0 + c[1] * s);
                dn[i] = [
                    0.25 * c[0] * (1.0 + c[1] * s),
                    0.25 * c[1] * (1.0 + c[0] * r),
                    0.0,
                ];
            }
        }
        CellType::Quad8 => {
            for (i, c) in QUAD_CORNERS.iter().enumerate() {
                let (a, b) = (1.0 + c[0] * r, 1.0 + c[1] * s);
                let g = c[0] * r + c[1] * s - 1.0;
                n[i] = 0.25 * a * b * g;
                dn[i] = [0.25 * c[0] * b * (g + a), 0.25 * c[1] * a * (g + b), 0.0];
            }
            // Mid-sides: 4 (0,-1), 5 (1,0), 6 (0,1), 7 (-1,0).
            for (m, eta) in [(4, -1.0), (6, 1.0)] {
                n[m] = 0.5 * (1.0 - r * r) * (1.0 + eta * s);
                dn[m] = [-r * (1.0 + eta * s), 0.5 * eta * (1.0 - r * r), 0.0];
            }
            for (m, xi_m) in [(5, 1.0), (7, -1.0)] {
                n[m] = 0.5 * (1.0 + xi_m * r) * (1.0 - s * s);
                dn[m] = [0.5 * xi_m * (1.0 - s * s), -s * (1.0 + xi_m * r), 0.0];
            }
        }
        CellType::Tet4 => {
            n[0] = 1.0 - r - s - t;
            n[1] = r;
            n[2] = s;
            n[3] = t;
            dn[0] = [-1.0, -1.0, -1.0];
            dn[1] = [1.0, 0.0, 0.0];
            dn[2] = [0.0, 1.0, 0.0];
            dn[3] = [0.0, 0.0, 1.0];
        }
        CellType::Tet10 => {
            let l = [1.0 - r - s - t, r, s, t];
            let dl = [
                [-1.0, -1.0, -1.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
            ];
            for i in 0..4 {
                n[i] = l[i] * (2.0 * l[i] - 1.0);
                let f = 4.0 * l[i] - 1.0;
                dn[i] = [f * dl[i][0], f * dl[i][1], f * dl[i][2]];
            }
            for (m, &(a, b)) in TET10_EDGES.iter().enumerate() {
                n[4 + m] = 4.0 * l[a] * l[b];
                for k in 0..3 {
                    dn[4 + m][k] = 4.0 * (dl[a][k] * l[b] + l[a] * dl[b][k]);
                }
            }
        }
        CellType::Hex8 => {
            for (i, c) in HEX_CORNERS.iter().enumerate() {
                let (a, b, d) = (1.0 + c[0] * r, 1.0 + c[1] * s, 1.0 + c[2] * t);
                n[i] = 0.125 * a * b * d;
                dn[i] = [
                    0.125 * c[0] * b * d,
                    0.125 * c[1] * a * d,
                    0.125 * c[2] * a * b,
                ];
            }
        }
    }
}

/// Reference coordinates of the nodes of `kind`.
pub fn node_coords(kind: CellType) -> Vec<[f64; 3]> {
    match kind {
        CellType::Line2 => vec![[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
        CellType::Line3 => vec![[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        CellType::Tri3 => vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        CellType::Tri6 => vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.0, 0.5, 0.0],
        ],
        CellType::Quad4 => QUAD_CORNERS.iter().map(|c| [c[0], c[1], 0.0]).collect(),
        CellType::Quad8 => {
            let mut v: Vec<[f64; 3]> = QUAD_CORNERS.iter().map(|c| [c[0], c[1], 0.0]).collect();
            v.extend([
                [0.0, -1.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [-1.0, 0.0, 0.0],
            ]);
            v
        }
        CellType::Tet4 => vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
        CellType::Tet10 => {
            let c = node_coords(CellType::Tet4);
            let mut v = c.clone();
            for (a, b) in TET10_EDGES {
                v.push([
                    0.5 * (c[a][0] + c[b][0]),
                    0.5 * (c[a][1] + c[b][1]),
                    0.5 * (c[a][2] + c[b][2]),
                ]);
            }
            v
        }
        CellType::Hex8 => HEX_CORNERS.to_vec(),
    }
}

/// Reference measure (length, area or volume) of the reference cell.
pub fn reference_measure(kind: CellType) -> f64 {
    match kind {
        CellType::Line2 | CellType::Line3 => 2.0,
        CellType::Tri3 | CellType::Tri6 => 0.5,
        CellType::Quad4 | CellType::Quad8 => 4.0,
        CellType::Tet4 | CellType::Tet10 => 1.0 / 6.0,
        CellType::Hex8 => 8.0,
    }
}

/// Maximum number of nodes of any cell type (sizes of stack buffers).
pub const MAX_NODES: usize = 10;

#[cfg(test)]
mod tests {
    use super::*;
    const ALL: [CellType; 9] = [
        CellType::Line2,
        CellType::Line3,
        CellType::Tri3,
        CellType::Tri6,
        CellType::Quad4,
        CellType::Quad8,
        CellType::Tet4,
        CellType::Tet10,
        CellType::Hex8,
    ];

    #[test]
    fn kronecker_partition_of_unity_and_derivatives() {
        for kind in ALL {
            let nn = kind.num_nodes();
            let mut n = [0.0; MAX_NODES];
            let mut dn = [[0.0; 3]; MAX_NODES];
            let nodes = node_coords(kind);
            for (j, &x) in nodes.iter().enumerate() {
                shape(kind, x, &mut n, &mut dn);
                for i in 0..nn {
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((n[i] - want).abs() < 1e-14, "{kind} N{i} at node {j}");
                }
            }
            // Finite-difference check of the derivatives at an interior point.
            let x0 = [0.21, 0.17, 0.13];
            shape(kind, x0, &mut n, &mut dn);
            let sum: f64 = n[..nn].iter().sum();
            assert!((sum - 1.0).abs() < 1e-14, "{kind} partition of unity");
            let h = 1e-6;
            for k in 0..kind.dim() {
                let mut xp = x0;
                let mut xm = x0;
                xp[k] += h;
                xm[k] -= h;
                let mut np = [0.0; MAX_NODES];
                let mut nm = [0.0; MAX_NODES];
                let mut scratch = [[0.0; 3]; MAX_NODES];
                shape(kind, xp, &mut np, &mut scratch);
                shape(kind, xm, &mut nm, &mut scratch);
                for i in 0..nn {
                    let fd = (np[i] - nm[i]) / (2.0 * h);
                    assert!((fd - dn[i][k]).abs() < 1e-8, "{kind} dN{i}/dxi{k}");
                }
            }
        }
    }
}
