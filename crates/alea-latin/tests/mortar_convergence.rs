//! Perfect non-matching interfaces converge to the exact solution at the finite-element rate.
//!
//! Manufactured solution on the unit square (cube): `u_i = s(x) = prod_k sin(pi x_k)` for every
//! component `i`, which vanishes on the whole boundary (clamped), with the body force
//! `b = -div sigma(u) = -[(lambda + mu) H 1 + mu tr(H) 1]`, `H` the Hessian of `s` (Navier's
//! equation). The domain is cut at `y = 1/2` (`z = 1/2` in 3D) into two substructures meshed
//! independently with `2 k` and `3 k` cells across (2D), `2 k` and `3 k` per direction (3D):
//! no interface node of one side faces a node of the other, so the interface is paired by the
//! dual mortar ([`alea_latin::mortar`]). The error in the energy norm,
//! `||u - u_h||_E^2 = int (eps - eps_h) : C : (eps - eps_h)`, is integrated cell by cell on both
//! substructures.
//!
//! Goal (dual-mortar theory, Wohlmuth 2000: optimal a priori estimates): the fitted log-log
//! slope of the energy error against `h = 1 / (2 k)` is the FE rate of the elements (1 for
//! Q4/T3/hexahedra, 2 for Q8), and the error stays within 30 % of the larger error of the conforming
//! meshes made of either side's cells (the substructured solution does not lose accuracy at the
//! interface).

mod common;

use alea_fem::kinematics::{point_geometry, strain_operator};
use alea_fem::{
    Analysis, Constraints, Loads, Material, Model, Ordering, Quadrature, solve_elastic,
};
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, PairingKind, RunInput, RunStatus,
    Substructure,
};
use alea_mesh::{CellType, Mesh, generate};
use std::f64::consts::PI;

const E: f64 = 100.0;
const NU: f64 = 0.3;

fn s_and_derivatives(x: [f64; 3], dim: usize) -> (f64, [f64; 3], [[f64; 3]; 3]) {
    let sn: Vec<f64> = (0..dim).map(|k| (PI * x[k]).sin()).collect();
    let cs: Vec<f64> = (0..dim).map(|k| (PI * x[k]).cos()).collect();
    let prod = |skip: &[usize]| -> f64 {
        (0..dim)
            .filter(|k| !skip.contains(k))
            .map(|k| sn[k])
            .product()
    };
    let s = prod(&[]);
    let mut g = [0.0; 3];
    let mut h = [[0.0; 3]; 3];
    for j in 0..dim {
        g[j] = PI * cs[j] * prod(&[j]);
        for k in 0..dim {
            h[j][k] = if j == k {
                -PI * PI * s
            } else {
                PI * PI * cs[j] * cs[k] * prod(&[j, k])
            };
        }
    }
    (s, g, h)
}

fn lame() -> (f64, f64) {
    (
        E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU)),
        E / (2.0 * (1.0 + NU)),
    )
}

fn body_force(x: [f64; 3], dim: usize) -> [f64; 3] {
    let (lam, mu) = lame();
    let (_, _, h) = s_and_derivatives(x, dim);
    let tr: f64 = (0..dim).map(|j| h[j][j]).sum();
    let mut b = [0.0; 3];
    for i in 0..dim {
        let row: f64 = (0..dim).map(|j| h[i][j]).sum();
        b[i] = -((lam + mu) * row + mu * tr);
    }
    b
}

/// Exact engineering strains in the crate's Voigt order.
fn strain(x: [f64; 3], dim: usize) -> Vec<f64> {
    let (_, g, _) = s_and_derivatives(x, dim);
    if dim == 2 {
        vec![g[0], g[1], g[0] + g[1]]
    } else {
        vec![g[0], g[1], g[2], g[1] + g[2], g[0] + g[2], g[0] + g[1]]
    }
}

fn analysis(dim: usize) -> Analysis {
    if dim == 2 {
        Analysis::PlaneStrain { thickness: 1.0 }
    } else {
        Analysis::Solid
    }
}

/// Squared energy error of `u` on `model`, and the squared energy of the exact solution there.
fn energy_error(model: &Model, u: &[f64]) -> (f64, f64) {
    let mesh = &model.mesh;
    let dim = mesh.dim;
    let d = model.material(0).unwrap().hooke(model.analysis);
    let nv = d.len().isqrt();
    let mut b = vec![0.0; nv * 10 * dim];
    let (mut err, mut norm) = (0.0, 0.0);
    for (c, kind, nodes) in mesh.cells() {
        let coords = model.cell_coords(c);
        let q = Quadrature::for_cell(kind, 2 * kind.order() + 3);
        let m = nodes.len() * dim;
        for (xi, w) in q.points.iter().zip(&q.weights) {
            let g = point_geometry(kind, &coords, *xi);
            strain_operator(&g, dim, &mut b);
            let mut eps = vec![0.0; nv];
            for (a, &n) in nodes.iter().enumerate() {
                for k in 0..dim {
                    for (r, e) in eps.iter_mut().enumerate() {
                        *e += b[r * m + a * dim + k] * u[n * dim + k];
                    }
                }
            }
            let ex = strain(g.x, dim);
            let de: Vec<f64> = (0..nv).map(|r| ex[r] - eps[r]).collect();
            let form = |v: &[f64]| -> f64 {
                (0..nv)
                    .map(|i| v[i] * (0..nv).map(|j| d[i * nv + j] * v[j]).sum::<f64>())
                    .sum()
            };
            err += w * g.det * form(&de);
            norm += w * g.det * form(&ex);
        }
    }
    (err, norm)
}

fn block(dim: usize, n: usize, kind: CellType, upper: bool) -> Mesh {
    let mut m = if dim == 2 {
        generate::rectangle(1.0, 0.5, n, n.div_ceil(2), kind).unwrap()
    } else {
        generate::box_mesh([1.0, 1.0, 0.5], [n, n, n.div_ceil(2)], kind).unwrap()
    };
    if upper {
        for x in m.coords.iter_mut() {
            x[dim - 1] += 0.5;
        }
    }
    m
}

fn clamped_model(mesh: Mesh, skip: &str) -> (Model, Constraints) {
    let dim = mesh.dim;
    let mut model = Model::new(mesh, analysis(dim)).unwrap();
    model.set_material_all(Material::new(E, NU, 0.0).unwrap());
    let mut c = Constraints::new();
    let sides: &[&str] = if dim == 2 {
        &["xmin", "xmax", "ymin", "ymax"]
    } else {
        &["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"]
    };
    for s in sides.iter().filter(|s| **s != skip) {
        c.clamp(&model.mesh, s).unwrap();
    }
    (model, c)
}

fn loaded(name: &str, model: Model, constraints: Constraints) -> Substructure {
    let dim = model.mesh.dim;
    let mut l = Loads::new(&model);
    l.body_force(&model, None, |x, _| body_force(x, dim))
        .unwrap();
    Substructure {
        name: name.into(),
        model,
        constraints,
        load_cases: vec![l.f],
    }
}

/// Relative energy error of the two-substructure mortar solution with `n1` and `n2` cells
/// across, and the larger of the errors of conforming single-domain solutions with either
/// side's cells.
fn errors(dim: usize, n1: usize, k1: CellType, n2: usize, k2: CellType) -> (f64, f64) {
    let (lo_side, hi_side) = if dim == 2 {
        ("ymax", "ymin")
    } else {
        ("zmax", "zmin")
    };
    let (m1, c1) = clamped_model(block(dim, n1, k1, false), lo_side);
    let (m2, c2) = clamped_model(block(dim, n2, k2, true), hi_side);
    let subs = vec![loaded("lower", m1, c1), loaded("upper", m2, c2)];
    let mut solver = LatinSolver::new(
        Assembly {
            subs,
            interfaces: vec![InterfaceSpec::perfect("cut", 0, lo_side, 1, hi_side)],
        },
        LatinOptions {
            tolerance: 1e-9,
            max_iterations: 5000,
            ..Default::default()
        },
    )
    .unwrap();
    let r = solver.run(&RunInput::default()).unwrap();
    assert_eq!(r.status, RunStatus::Converged);
    assert_eq!(r.interfaces[0].pairing.kind, PairingKind::Mortar);
    let (mut err, mut norm) = (0.0, 0.0);
    for s in 0..2 {
        let (e, n) = energy_error(solver.model(s), &r.displacements[s]);
        err += e;
        norm += n;
    }
    // Conforming references: one mesh of the unit square (cube) with either side's cells.
    let conforming = |n: usize, kind: CellType| -> f64 {
        let whole = if dim == 2 {
            generate::rectangle(1.0, 1.0, n, 2 * n.div_ceil(2), kind).unwrap()
        } else {
            generate::box_mesh([1.0, 1.0, 1.0], [n, n, 2 * n.div_ceil(2)], kind).unwrap()
        };
        let (m, c) = clamped_model(whole, "");
        let s = loaded("whole", m, c);
        let mut loads = Loads::new(&s.model);
        loads.f.copy_from_slice(&s.load_cases[0]);
        let sol = solve_elastic(&s.model, &s.constraints, &loads, Ordering::Metis).unwrap();
        let (e, n) = energy_error(&s.model, &sol.u);
        (e / n).sqrt()
    };
    let reference = conforming(n1, k1).max(conforming(n2, k2));
    eprintln!(
        "{dim}D {n1} x {k1:?} | {n2} x {k2:?}: {} iterations, energy error {:.4e} (conforming, \
         worse side: {reference:.4e})",
        r.iterations,
        (err / norm).sqrt(),
    );
    ((err / norm).sqrt(), reference)
}

/// Least-squares slope of `log y` against `log x`.
fn slope(x: &[f64], y: &[f64]) -> f64 {
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let n = x.len() as f64;
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

fn check_rate(dim: usize, k1: CellType, k2: CellType, ks: &[usize], rate: f64) {
    let mut h = Vec::new();
    let mut e = Vec::new();
    for &k in ks {
        let (em, ec) = errors(dim, 2 * k, k1, 3 * k, k2);
        assert!(em < 1.3 * ec, "mortar error {em} vs conforming {ec}");
        h.push(1.0 / (2 * k) as f64);
        e.push(em);
    }
    let p = slope(&h, &e);
    eprintln!("{dim}D {k1:?} | {k2:?}: fitted energy rate {p:.3} (FE rate {rate})");
    assert!((p - rate).abs() < 0.1, "fitted rate {p}, expected {rate}");
}

#[test]
fn q4_against_q4_converges_at_rate_one() {
    check_rate(2, CellType::Quad4, CellType::Quad4, &[2, 4, 8, 16], 1.0);
}

#[test]
fn q8_against_t6_converges_at_rate_two() {
    check_rate(2, CellType::Quad8, CellType::Tri6, &[1, 2, 4, 8], 2.0);
}

#[test]
fn hexahedra_against_tetrahedra_converge_at_rate_one() {
    check_rate(3, CellType::Hex8, CellType::Tet4, &[2, 3, 4], 1.0);
}
