//! 3D fixtures: a manufactured solution on the unit cube, exact error norms, meshes.

use std::f64::consts::PI;

use alea_fem::{Analysis, Material, Model, Quadrature, kinematics::point_geometry};
use alea_mesh::{CellType, Mesh, generate};

use super::{E, NU};

/// Lame constants of the test material.
pub fn lame3() -> (f64, f64) {
    (
        E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU)),
        E / (2.0 * (1.0 + NU)),
    )
}

/// Amplitude and frequencies of each component: `u_c = A_c prod_d sin(k_cd pi x_d)`, zero on
/// the boundary of the unit cube.
const TERMS: [(f64, [f64; 3]); 3] = [
    (1.0, [1.0, 1.0, 1.0]),
    (0.5, [1.0, 2.0, 1.0]),
    (0.4, [1.0, 1.0, 2.0]),
];

/// `(u, grad u, second derivatives)` of the manufactured solution: `g[c][i] = d u_c / d x_i`,
/// `h[c][i][j] = d^2 u_c / d x_i d x_j`.
#[allow(clippy::type_complexity)]
pub fn exact3(x: [f64; 3]) -> ([f64; 3], [[f64; 3]; 3], [[[f64; 3]; 3]; 3]) {
    let mut u = [0.0; 3];
    let mut g = [[0.0; 3]; 3];
    let mut h = [[[0.0; 3]; 3]; 3];
    for (c, (a, k)) in TERMS.iter().enumerate() {
        let s: Vec<f64> = (0..3).map(|d| (k[d] * PI * x[d]).sin()).collect();
        let co: Vec<f64> = (0..3).map(|d| (k[d] * PI * x[d]).cos()).collect();
        let w: Vec<f64> = (0..3).map(|d| k[d] * PI).collect();
        u[c] = a * s[0] * s[1] * s[2];
        for i in 0..3 {
            let mut gi = a * w[i] * co[i];
            for d in 0..3 {
                if d != i {
                    gi *= s[d];
                }
            }
            g[c][i] = gi;
            for j in 0..3 {
                let mut v = *a;
                for d in 0..3 {
                    v *= if d == i && d == j {
                        -w[d] * w[d] * s[d]
                    } else if d == i || d == j {
                        w[d] * co[d]
                    } else {
                        s[d]
                    };
                }
                h[c][i][j] = v;
            }
        }
    }
    (u, g, h)
}

/// Body force `f = -div sigma(u)` of [`exact3`].
pub fn body3(x: [f64; 3]) -> [f64; 3] {
    let (lam, mu) = lame3();
    let (_, _, h) = exact3(x);
    let mut f = [0.0; 3];
    for (i, fi) in f.iter_mut().enumerate() {
        let grad_div: f64 = (0..3).map(|c| h[c][c][i]).sum();
        let lap: f64 = (0..3).map(|j| h[i][j][j]).sum();
        *fi = -((lam + mu) * grad_div + mu * lap);
    }
    f
}

/// Exact stress tensor.
pub fn exact_stress3(x: [f64; 3]) -> [[f64; 3]; 3] {
    let (lam, mu) = lame3();
    let (_, g, _) = exact3(x);
    let tr = g[0][0] + g[1][1] + g[2][2];
    let mut s = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            s[i][j] = mu * (g[i][j] + g[j][i]);
        }
        s[i][i] += lam * tr;
    }
    s
}

/// Exact traction `sigma n`.
pub fn exact_traction3(x: [f64; 3], n: [f64; 3]) -> [f64; 3] {
    let s = exact_stress3(x);
    [0, 1, 2].map(|i| s[i][0] * n[0] + s[i][1] * n[1] + s[i][2] * n[2])
}

/// `||u_ex - u_h||_K` by high-order quadrature on every cell.
pub fn true_error3(model: &Model, u: &[f64]) -> f64 {
    let mesh = &model.mesh;
    let (lam, mu) = lame3();
    let mut sum = 0.0;
    for c in 0..mesh.num_cells() {
        let kind = mesh.cell_type(c);
        let coords = model.cell_coords(c);
        let nodes = mesh.cell_nodes(c);
        let q = match kind {
            CellType::Hex8 => Quadrature::tensor(3, 6),
            _ => Quadrature::tetrahedron(10),
        };
        for (xi, w) in q.points.iter().zip(&q.weights) {
            let g = point_geometry(kind, &coords, *xi);
            let (_, ge, _) = exact3(g.x);
            let mut d = ge;
            for (a, &n) in nodes.iter().enumerate() {
                for c2 in 0..3 {
                    for i in 0..3 {
                        d[c2][i] -= g.grad[a][i] * u[3 * n + c2];
                    }
                }
            }
            let tr = d[0][0] + d[1][1] + d[2][2];
            let mut e2 = 0.0;
            for i in 0..3 {
                for j in 0..3 {
                    e2 += (0.5 * (d[i][j] + d[j][i])).powi(2);
                }
            }
            sum += w * g.det * (lam * tr * tr + 2.0 * mu * e2);
        }
    }
    sum.sqrt()
}

/// Unit-cube mesh, optionally with interior nodes moved by up to `distortion * h` (Hex8 and
/// Tet4 only: quadratic cells keep straight edges by moving mid nodes with their edge).
pub fn cube(n: usize, kind: CellType, distortion: f64) -> Mesh {
    let mut m = generate::box_mesh([1.0; 3], [n; 3], kind).unwrap();
    let h = 1.0 / n as f64;
    if distortion > 0.0 {
        for x in m.coords.iter_mut() {
            let interior = (0..3).all(|d| x[d] > 1e-12 && x[d] < 1.0 - 1e-12);
            if interior {
                let mut r = [0.0; 3];
                for (d, rd) in r.iter_mut().enumerate() {
                    let s = (x[0] * (12.9898 + 3.1 * d as f64)
                        + x[1] * (78.233 - 5.3 * d as f64)
                        + x[2] * (37.719 + 1.7 * d as f64))
                        .sin()
                        * 43758.5453;
                    *rd = s - s.floor() - 0.5;
                }
                for d in 0..3 {
                    x[d] += 2.0 * distortion * h * r[d];
                }
            }
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
            let mut mids = Vec::new();
            for (_, _, nodes) in m.cells() {
                for (a, b, c) in EDGES {
                    mids.push((nodes[a], nodes[b], nodes[c]));
                }
            }
            for (a, b, c) in mids {
                let (xa, xb) = (m.coords[a], m.coords[b]);
                m.coords[c] = [0, 1, 2].map(|d| 0.5 * (xa[d] + xb[d]));
            }
        }
    }
    m
}

/// A 3D model with the test material.
pub fn solid_model(mesh: Mesh) -> Model {
    let mut m = Model::new(mesh, Analysis::Solid).unwrap();
    m.set_material_all(Material::new(E, NU, 0.0).unwrap());
    m
}
