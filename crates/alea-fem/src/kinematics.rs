//! Geometry of a cell at a reference point: Jacobian, physical shape-function gradients, and
//! the strain-displacement operator.
//!
//! With `x(xi) = sum_i N_i(xi) x_i`, `J_kl = dx_l/dxi_k = sum_i dN_i/dxi_k x_il`, and the
//! physical gradients are `grad N_i = J^-1 dN_i/dxi`. Element dofs are node-major:
//! local dof `a * dim + c` is component `c` of node `a`.

use alea_mesh::CellType;
use alea_mesh::vec3::{cross, norm};

use crate::reference::{MAX_NODES, shape};

/// Shape values and physical gradients at one point of a cell.
#[derive(Clone, Debug)]
pub struct PointGeometry {
    /// Number of nodes.
    pub nn: usize,
    /// Shape function values.
    pub n: [f64; MAX_NODES],
    /// Physical gradients `dN_i/dx_k`.
    pub grad: [[f64; 3]; MAX_NODES],
    /// Physical point.
    pub x: [f64; 3],
    /// Jacobian determinant (signed).
    pub det: f64,
}

/// Evaluates the geometry of a `dim`-dimensional cell at `xi`; `coords` are the cell's nodes.
pub fn point_geometry(kind: CellType, coords: &[[f64; 3]], xi: [f64; 3]) -> PointGeometry {
    let nn = kind.num_nodes();
    let dim = kind.dim();
    let mut g = PointGeometry {
        nn,
        n: [0.0; MAX_NODES],
        grad: [[0.0; 3]; MAX_NODES],
        x: [0.0; 3],
        det: 0.0,
    };
    let mut dn = [[0.0; 3]; MAX_NODES];
    shape(kind, xi, &mut g.n, &mut dn);
    let mut j = [[0.0; 3]; 3];
    for i in 0..nn {
        for l in 0..3 {
            g.x[l] += g.n[i] * coords[i][l];
        }
        for k in 0..dim {
            for l in 0..dim {
                j[k][l] += dn[i][k] * coords[i][l];
            }
        }
    }
    if dim == 2 {
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let inv = [
            [j[1][1] / det, -j[0][1] / det],
            [-j[1][0] / det, j[0][0] / det],
        ];
        for i in 0..nn {
            // grad_l = sum_k (J^-1)_lk dn_k, with J^-1 the inverse of J (J_kl = dx_l/dxi_k).
            g.grad[i][0] = inv[0][0] * dn[i][0] + inv[0][1] * dn[i][1];
            g.grad[i][1] = inv[1][0] * dn[i][0] + inv[1][1] * dn[i][1];
        }
        g.det = det;
    } else {
        let det = j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
            - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
            + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
        let mut inv = [[0.0; 3]; 3];
        for r in 0..3 {
            for c in 0..3 {
                let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
                let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
                // inv[c][r] = cofactor(r, c) / det
                inv[c][r] = (j[r1][c1] * j[r2][c2] - j[r1][c2] * j[r2][c1]) / det;
            }
        }
        for i in 0..nn {
            for l in 0..3 {
                g.grad[i][l] = inv[l][0] * dn[i][0] + inv[l][1] * dn[i][1] + inv[l][2] * dn[i][2];
            }
        }
        g.det = det;
    }
    g
}

/// Fills `b` (row-major, `n_voigt x (nn * dim)`) with the strain-displacement operator at a
/// point: `eps = B u_e`.
pub fn strain_operator(g: &PointGeometry, dim: usize, b: &mut [f64]) {
    let ncol = g.nn * dim;
    b[..ncol * if dim == 2 { 3 } else { 6 }].fill(0.0);
    for a in 0..g.nn {
        let [gx, gy, gz] = g.grad[a];
        if dim == 2 {
            let c = a * 2;
            b[c] = gx; // e_xx
            b[ncol + c + 1] = gy; // e_yy
            b[2 * ncol + c] = gy; // g_xy
            b[2 * ncol + c + 1] = gx;
        } else {
            let c = a * 3;
            b[c] = gx;
            b[ncol + c + 1] = gy;
            b[2 * ncol + c + 2] = gz;
            b[3 * ncol + c + 1] = gz; // g_yz
            b[3 * ncol + c + 2] = gy;
            b[4 * ncol + c] = gz; // g_xz
            b[4 * ncol + c + 2] = gx;
            b[5 * ncol + c] = gy; // g_xy
            b[5 * ncol + c + 1] = gx;
        }
    }
}

/// Geometry of a facet (line in 2D, surface in 3D) at a reference point: shape values, point,
/// unit normal (from the facet's node order: `(t_y, -t_x)` in 2D, `dx/dr x dx/ds` in 3D) and
/// the surface measure factor `|t|` or `|dx/dr x dx/ds|`.
#[derive(Clone, Debug)]
pub struct FacetGeometry {
    /// Shape function values on the facet's nodes.
    pub n: [f64; MAX_NODES],
    /// Physical point.
    pub x: [f64; 3],
    /// Unit normal.
    pub normal: [f64; 3],
    /// Measure factor (multiply by the reference weight; in 2D also by the thickness).
    pub jac: f64,
}

/// Evaluates a facet's geometry at reference point `xi`.
pub fn facet_geometry(kind: CellType, coords: &[[f64; 3]], xi: [f64; 3]) -> FacetGeometry {
    let nn = kind.num_nodes();
    let mut n = [0.0; MAX_NODES];
    let mut dn = [[0.0; 3]; MAX_NODES];
    shape(kind, xi, &mut n, &mut dn);
    let mut x = [0.0; 3];
    let mut t1 = [0.0; 3];
    let mut t2 = [0.0; 3];
    for i in 0..nn {
        for l in 0..3 {
            x[l] += n[i] * coords[i][l];
            t1[l] += dn[i][0] * coords[i][l];
            t2[l] += dn[i][1] * coords[i][l];
        }
    }
    let (normal, jac) = if kind.dim() == 1 {
        let len = (t1[0] * t1[0] + t1[1] * t1[1]).sqrt();
        ([t1[1] / len, -t1[0] / len, 0.0], len)
    } else {
        let c = cross(&t1, &t2);
        let len = norm(&c);
        ([c[0] / len, c[1] / len, c[2] / len], len)
    };
    FacetGeometry { n, x, normal, jac }
}
