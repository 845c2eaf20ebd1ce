//! Shared fixtures: the manufactured solution, exact error norms, meshes.
#![allow(dead_code)]

use std::f64::consts::PI;

use alea_fem::{Analysis, Material, Model, Quadrature, kinematics::point_geometry};
use alea_mesh::{CellType, Mesh, generate};

pub mod solid;

pub const E: f64 = 1000.0;
pub const NU: f64 = 0.3;

/// Lame constants of the 2D analysis (plane stress uses the reduced lambda).
pub fn lame(analysis: Analysis) -> (f64, f64) {
    let lam = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
    let mu = E / (2.0 * (1.0 + NU));
    match analysis {
        Analysis::PlaneStress { .. } => (2.0 * lam * mu / (lam + 2.0 * mu), mu),
        _ => (lam, mu),
    }
}

/// `u = (sin(pi x) sin(pi y), 1/2 sin(pi x) sin(2 pi y))`: zero on the boundary of the unit
/// square. Returns `(u, [u_x,x, u_x,y, u_y,x, u_y,y])`.
pub fn exact(x: [f64; 3]) -> ([f64; 2], [f64; 4]) {
    let (sx, cx) = (PI * x[0]).sin_cos();
    let (sy, cy) = (PI * x[1]).sin_cos();
    let (s2y, c2y) = (2.0 * PI * x[1]).sin_cos();
    (
        [sx * sy, 0.5 * sx * s2y],
        [
            PI * cx * sy,
            PI * sx * cy,
            0.5 * PI * cx * s2y,
            PI * sx * c2y,
        ],
    )
}

/// Body force `f = -div sigma(u)` of [`exact`].
pub fn body(analysis: Analysis) -> impl Fn([f64; 3]) -> [f64; 3] + Send + Sync + Copy {
    let (lam, mu) = lame(analysis);
    move |x: [f64; 3]| {
        let (sx, cx) = (PI * x[0]).sin_cos();
        let (sy, cy) = (PI * x[1]).sin_cos();
        let (s2y, c2y) = (2.0 * PI * x[1]).sin_cos();
        let a = sx * sy;
        let b = 0.5 * sx * s2y;
        let p2 = PI * PI;
        let (axx, ayy, axy) = (-p2 * a, -p2 * a, p2 * cx * cy);
        let (bxx, byy, bxy) = (-p2 * b, -4.0 * p2 * b, p2 * cx * c2y);
        let ddx = axx + bxy;
        let ddy = axy + byy;
        [
            -((lam + mu) * ddx + mu * (axx + ayy)),
            -((lam + mu) * ddy + mu * (bxx + byy)),
            0.0,
        ]
    }
}

/// Exact stress `[s_xx, s_yy, s_xy]`.
pub fn exact_stress(analysis: Analysis, x: [f64; 3]) -> [f64; 3] {
    let (lam, mu) = lame(analysis);
    let (_, g) = exact(x);
    let tr = g[0] + g[3];
    [
        lam * tr + 2.0 * mu * g[0],
        lam * tr + 2.0 * mu * g[3],
        mu * (g[1] + g[2]),
    ]
}

/// Exact traction `sigma n`.
pub fn exact_traction(
    analysis: Analysis,
) -> impl Fn([f64; 3], [f64; 3]) -> [f64; 3] + Send + Sync + Copy {
    move |x, n| {
        let s = exact_stress(analysis, x);
        [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1], 0.0]
    }
}

/// `||u_ex - u_h||_K` by high-order quadrature on every cell.
pub fn true_error(model: &Model, u: &[f64]) -> f64 {
    let mesh = &model.mesh;
    let (lam, mu) = lame(model.analysis);
    let th = model.analysis.thickness();
    let mut sum = 0.0;
    for c in 0..mesh.num_cells() {
        let kind = mesh.cell_type(c);
        let coords = model.cell_coords(c);
        let nodes = mesh.cell_nodes(c);
        let q = match kind {
            CellType::Tri3 | CellType::Tri6 => Quadrature::triangle(14),
            _ => Quadrature::tensor(2, 8),
        };
        for (xi, w) in q.points.iter().zip(&q.weights) {
            let g = point_geometry(kind, &coords, *xi);
            let mut gh = [0.0; 4];
            for (a, &n) in nodes.iter().enumerate() {
                for comp in 0..2 {
                    let ua = u[2 * n + comp];
                    gh[2 * comp] += g.grad[a][0] * ua;
                    gh[2 * comp + 1] += g.grad[a][1] * ua;
                }
            }
            let (_, ge) = exact(g.x);
            let d: Vec<f64> = (0..4).map(|k| ge[k] - gh[k]).collect();
            let (exx, eyy, gxy) = (d[0], d[3], d[1] + d[2]);
            let e2 =
                lam * (exx + eyy).powi(2) + 2.0 * mu * (exx * exx + eyy * eyy) + mu * gxy * gxy;
            sum += w * g.det * th * e2;
        }
    }
    sum.sqrt()
}

/// Unit-square mesh, optionally with interior nodes moved by up to `distortion * h`.
pub fn square(n: usize, kind: CellType, distortion: f64) -> Mesh {
    let mut m = generate::rectangle(1.0, 1.0, n, n, kind).unwrap();
    let h = 1.0 / n as f64;
    for x in m.coords.iter_mut() {
        let interior = x[0] > 1e-12 && x[0] < 1.0 - 1e-12 && x[1] > 1e-12 && x[1] < 1.0 - 1e-12;
        if interior && distortion > 0.0 {
            // Deterministic pseudo-random perturbation.
            let s = (x[0] * 12.9898 + x[1] * 78.233).sin() * 43758.5453;
            let r1 = s - s.floor() - 0.5;
            let t = (x[0] * 39.3468 + x[1] * 11.135).sin() * 24634.6345;
            let r2 = t - t.floor() - 0.5;
            x[0] += 2.0 * distortion * h * r1;
            x[1] += 2.0 * distortion * h * r2;
        }
    }
    // Quadratic cells: mid-side nodes back to the middle of their (straight) edges.
    if kind.order() == 2 {
        let mut mids = Vec::new();
        for (_, k, nodes) in m.cells() {
            for (_, loc) in k.facets() {
                mids.push((nodes[loc[0]], nodes[loc[1]], nodes[loc[2]]));
            }
        }
        for (a, b, c) in mids {
            let (xa, xb) = (m.coords[a], m.coords[b]);
            m.coords[c] = [0.5 * (xa[0] + xb[0]), 0.5 * (xa[1] + xb[1]), 0.0];
        }
    }
    m
}

/// A model with the test material.
pub fn model(mesh: Mesh, analysis: Analysis) -> Model {
    let mut m = Model::new(mesh, analysis).unwrap();
    m.set_material_all(Material::new(E, NU, 0.0).unwrap());
    m
}

/// Least-squares slope of `log y` against `log x`.
pub fn slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let mx = lx.iter().sum::<f64>() / n;
    let my = ly.iter().sum::<f64>() / n;
    let num: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let den: f64 = lx.iter().map(|a| (a - mx) * (a - mx)).sum();
    num / den
}
