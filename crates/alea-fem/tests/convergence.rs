//! Manufactured-solution convergence rates for every element (second rung of the verification
//! ladder, after the patch tests of `patch.rs`).
//!
//! Reference: the a-priori estimates of conforming Lagrange/serendipity elements, e.g. Ciarlet,
//! *The Finite Element Method for Elliptic Problems* (1978), Thm 3.2.2 and 3.2.5;
//! Brenner & Scott, *The Mathematical Theory of Finite Element Methods* (3rd ed.), 5.4 and 5.7;
//! Arnold, Boffi & Falk, *Approximation by quadrilateral finite elements*, Math. Comp. 71 (2002)
//! for Q8 on asymptotically parallelogram meshes: for elements of degree `p` and a smooth `u`,
//! `|u - u_h|_E = O(h^p)` and `||u - u_h||_L2 = O(h^(p+1))`.
//!
//! Exact solution: a sum of plane waves per component,
//! `u_i(x) = sum_w a_w sin(k_w . x + phi_w)` (waves listed in `waves`, |k| about 1.6 pi in 2D and
//! 1 pi in 3D), on the unit square
//! `[0, 1]^2` (T3, T6, Q4, Q8 in plane strain and plane stress) or the unit cube (Tet4, Tet10,
//! Hex8). `u_exact` is imposed at every boundary node (`Constraints::fix_component_with` on
//! `xmin ... zmax`), and the body force `b = -div sigma(u)` is applied.
//!
//! Body force. For `sigma = lambda tr(eps) I + 2 mu eps`,
//! `div sigma = mu lap(u) + (lambda + mu) grad(div u)`, so with `H^i = hess(u_i)`
//! `b_i = -(mu sum_j H^i_jj + (lambda + mu) sum_j H^j_ij)`.
//! 3D and plane strain use `lambda = E nu / ((1 + nu)(1 - 2 nu))`, `mu = E / (2 (1 + nu))`.
//! Plane stress has the same form with `lambda* = 2 lambda mu / (lambda + 2 mu) = E nu / (1 - nu^2)`
//! (then `lambda* + 2 mu = E / (1 - nu^2)`, the plane-stress `D_11`). For a plane wave
//! `a sin(k.x + phi)`, `hess = -a sin(k.x + phi) k k^T`. The test
//! `body_force_is_minus_div_sigma` checks this formula against central differences of the
//! crate's own `Material::stress` for the three analysis types.
//!
//! Errors, integrated cell by cell with `Quadrature::for_cell(kind, 2p + 3)` (`w det J`, no
//! thickness): `||e||_L2^2 = int |u - u_h|^2`, `|e|_E^2 = int (eps - eps_h) . D (eps - eps_h)`,
//! both relative to the same norms of `u`. The least-squares slope of `log err` versus `log h`
//! over the three finest meshes must be within 0.1 of `p + 1` (L2) and `p` (energy).
//!
//! Absolute cap, on every mesh (a rate alone misses an error that converges at the right rate
//! to a wrong field, e.g. a wrong factor in the stiffness that is also in the load): by Galerkin
//! orthogonality the FE solution is the best approximation in the energy norm among fields with
//! the same boundary nodal values, so `|u - u_h|_E <= |u - I_h u|_E` with `I_h` the nodal
//! interpolant of the closed-form `u` - checked with 2 % slack (load quadrature, and inexact
//! stiffness quadrature on curved cells). The L2 error must stay below 3 times the
//! interpolant's (in practice it is within 20 %).
//!
//! Distorted variant (Q4, T6, Q8): every node of the structured mesh (mid-edge nodes included,
//! so cells become curved) is moved by the smooth map
//! `x -> x + 0.05 sin(pi x) sin(2 pi y)`, `y -> y + 0.04 sin(2 pi x) sin(pi y)`, which keeps
//! the unit square and its sides, so cells are asymptotically parallelograms and the rates stay
//! optimal.
//!
//! ```text
//!   meshes (2D): n x n cells, n = 4, 8, 16, 32        u = u_exact on the whole boundary
//!   +---+---+---+---+                                  b = -div sigma(u_exact) inside
//!   |   |   |   |   |
//!   +---+---+---+---+     3D: n^3 hexahedra (or 6 n^3 tetrahedra), n = 2, 4, 8 (Tet10),
//!   ...                        n = 4, 8, 16 (Tet4), n = 3, 6, 12 (Hex8)
//! ```
//!
//! Observed slopes (L2 / energy, three finest meshes): T3 1.97 / 0.99, T6 3.01 / 1.99,
//! Q4 2.00 / 1.00, Q8 3.00 / 2.00 (plane strain and plane stress alike), distorted Q4
//! 1.99 / 1.00, distorted T6 3.02 / 1.98, distorted Q8 3.00 / 2.00, Tet4 1.97 / 0.99, Tet10
//! 3.00 / 1.97, Hex8 2.00 / 1.01;
//! the energy error never exceeds the interpolant's (ratio 0.95 to 1.00).

use alea_fem::kinematics::{point_geometry, strain_operator};
use alea_fem::{
    Analysis, Constraints, Loads, Material, Model, Ordering, Quadrature, solve_elastic,
};
use alea_mesh::{CellType, Mesh, generate};

const E: f64 = 210e3;
const NU: f64 = 0.3;

/// Plane waves `(component, amplitude, wave vector, phase)`.
fn waves(dim: usize) -> Vec<(usize, f64, [f64; 3], f64)> {
    use std::f64::consts::PI;
    let mut w = vec![
        (0, 1.0e-3, [1.3 * PI, 0.7 * PI, 0.5 * PI], 0.3),
        (0, 0.5e-3, [0.6 * PI, -1.1 * PI, 0.9 * PI], 1.1),
        (1, 0.8e-3, [-0.9 * PI, 1.2 * PI, 0.4 * PI], -0.4),
        (1, 0.4e-3, [1.0 * PI, 0.5 * PI, -0.8 * PI], 0.8),
        (2, 0.7e-3, [0.8 * PI, -0.6 * PI, 1.2 * PI], 0.5),
        (2, 0.3e-3, [-0.5 * PI, 0.9 * PI, 0.7 * PI], -1.2),
    ];
    w.retain(|t| t.0 < dim);
    for t in &mut w {
        if dim == 2 {
            t.2[2] = 0.0;
        } else {
            // Longer waves in 3D, where the meshes are coarser (k h <= 0.4 on the first mesh).
            t.2 = t.2.map(|k| 0.6 * k);
        }
    }
    w
}

/// The manufactured field and its derivatives.
struct Exact {
    dim: usize,
    waves: Vec<(usize, f64, [f64; 3], f64)>,
}

impl Exact {
    fn new(dim: usize) -> Self {
        Exact {
            dim,
            waves: waves(dim),
        }
    }

    fn phase(k: &[f64; 3], phi: f64, x: [f64; 3]) -> f64 {
        k[0] * x[0] + k[1] * x[1] + k[2] * x[2] + phi
    }

    fn u(&self, x: [f64; 3]) -> [f64; 3] {
        let mut u = [0.0; 3];
        for (c, a, k, phi) in &self.waves {
            u[*c] += a * Self::phase(k, *phi, x).sin();
        }
        u
    }

    /// `g[i][j] = du_i/dx_j`.
    fn grad(&self, x: [f64; 3]) -> [[f64; 3]; 3] {
        let mut g = [[0.0; 3]; 3];
        for (c, a, k, phi) in &self.waves {
            let s = a * Self::phase(k, *phi, x).cos();
            for j in 0..3 {
                g[*c][j] += s * k[j];
            }
        }
        g
    }

    /// `h[i][j][l] = d^2 u_i / dx_j dx_l`.
    fn hess(&self, x: [f64; 3]) -> [[[f64; 3]; 3]; 3] {
        let mut h = [[[0.0; 3]; 3]; 3];
        for (c, a, k, phi) in &self.waves {
            let s = -a * Self::phase(k, *phi, x).sin();
            for j in 0..3 {
                for l in 0..3 {
                    h[*c][j][l] += s * k[j] * k[l];
                }
            }
        }
        h
    }

    /// Voigt strain (engineering shears) of the exact field.
    fn strain(&self, x: [f64; 3]) -> Vec<f64> {
        let g = self.grad(x);
        if self.dim == 2 {
            vec![g[0][0], g[1][1], g[0][1] + g[1][0]]
        } else {
            vec![
                g[0][0],
                g[1][1],
                g[2][2],
                g[1][2] + g[2][1],
                g[0][2] + g[2][0],
                g[0][1] + g[1][0],
            ]
        }
    }

    /// `b = -div sigma(u)` from the closed form `mu lap u + (lambda + mu) grad div u`.
    fn body_force(&self, x: [f64; 3], analysis: Analysis) -> [f64; 3] {
        let (lam, mu) = lame(analysis);
        let h = self.hess(x);
        let d = self.dim;
        let mut b = [0.0; 3];
        for (i, bi) in b.iter_mut().enumerate().take(d) {
            let lap: f64 = (0..d).map(|j| h[i][j][j]).sum();
            let grad_div: f64 = (0..d).map(|j| h[j][i][j]).sum();
            *bi = -(mu * lap + (lam + mu) * grad_div);
        }
        b
    }
}

/// Lame constants written out here, independently of the crate (plane stress: `lambda*`).
fn lame(analysis: Analysis) -> (f64, f64) {
    let lam = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
    let mu = E / (2.0 * (1.0 + NU));
    match analysis {
        Analysis::PlaneStress { .. } => (2.0 * lam * mu / (lam + 2.0 * mu), mu),
        _ => (lam, mu),
    }
}

/// Relative errors of one solve: `(L2, energy, L2 of I_h u, energy of I_h u)`.
#[derive(Clone, Copy, Debug)]
struct Errors {
    l2: f64,
    energy: f64,
    l2_interp: f64,
    energy_interp: f64,
}

/// Integrates the L2 and energy errors of the nodal field `uh` and of the nodal interpolant.
fn errors(model: &Model, ex: &Exact, uh: &[f64]) -> Errors {
    let mesh = &model.mesh;
    let dim = mesh.dim;
    let mat = model.material(0).unwrap();
    let d = mat.hooke(model.analysis);
    let nv = model.analysis.n_voigt();
    let ui: Vec<f64> = mesh
        .coords
        .iter()
        .flat_map(|&x| ex.u(x)[..dim].to_vec())
        .collect();
    // [err_l2, err_e, norm_l2, norm_e, interp_l2, interp_e]
    let mut acc = [0.0; 6];
    let mut b = vec![0.0; nv * 10 * dim];
    for (c, kind, nodes) in mesh.cells() {
        let coords = model.cell_coords(c);
        let q = Quadrature::for_cell(kind, 2 * kind.order() + 3);
        let m = nodes.len() * dim;
        for (xi, w) in q.points.iter().zip(&q.weights) {
            let g = point_geometry(kind, &coords, *xi);
            strain_operator(&g, dim, &mut b);
            let wd = w * g.det;
            let ue = ex.u(g.x);
            let ee = ex.strain(g.x);
            for (field, l2_slot, e_slot) in [(uh, 0, 1), (ui.as_slice(), 4, 5)] {
                let mut u = [0.0; 3];
                let mut eps = vec![0.0; nv];
                for (a, &n) in nodes.iter().enumerate() {
                    for k in 0..dim {
                        let v = field[n * dim + k];
                        u[k] += g.n[a] * v;
                        for (r, e) in eps.iter_mut().enumerate() {
                            *e += b[r * m + a * dim + k] * v;
                        }
                    }
                }
                let du: f64 = (0..dim).map(|k| (ue[k] - u[k]).powi(2)).sum();
                let de: Vec<f64> = (0..nv).map(|r| ee[r] - eps[r]).collect();
                acc[l2_slot] += wd * du;
                acc[e_slot] += wd * quad_form(&d, &de);
            }
            acc[2] += wd * (0..dim).map(|k| ue[k] * ue[k]).sum::<f64>();
            acc[3] += wd * quad_form(&d, &ee);
        }
    }
    Errors {
        l2: (acc[0] / acc[2]).sqrt(),
        energy: (acc[1] / acc[3]).sqrt(),
        l2_interp: (acc[4] / acc[2]).sqrt(),
        energy_interp: (acc[5] / acc[3]).sqrt(),
    }
}

fn quad_form(d: &[f64], v: &[f64]) -> f64 {
    let n = v.len();
    (0..n)
        .map(|i| v[i] * (0..n).map(|j| d[i * n + j] * v[j]).sum::<f64>())
        .sum()
}

/// Solves the manufactured problem on `mesh` and returns the relative errors.
fn solve(mesh: Mesh, analysis: Analysis) -> Errors {
    let dim = mesh.dim;
    let ex = Exact::new(dim);
    let mut model = Model::new(mesh, analysis).unwrap();
    model.set_material_all(Material::new(E, NU, 0.0).unwrap());
    let mut cons = Constraints::new();
    let sides: &[&str] = if dim == 2 {
        &["xmin", "xmax", "ymin", "ymax"]
    } else {
        &["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"]
    };
    for s in sides {
        for c in 0..dim {
            cons.fix_component_with(&model.mesh, s, c, |x| ex.u(x)[c])
                .unwrap();
        }
    }
    let mut loads = Loads::new(&model);
    loads
        .body_force(&model, None, |x, _| ex.body_force(x, analysis))
        .unwrap();
    let sol = solve_elastic(&model, &cons, &loads, Ordering::Metis).unwrap();
    errors(&model, &ex, &sol.u)
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

/// The smooth distortion of the unit square (identity on its boundary).
fn distort(mesh: &mut Mesh) {
    use std::f64::consts::PI;
    for x in &mut mesh.coords {
        let (a, b) = (x[0], x[1]);
        x[0] = a + 0.05 * (PI * a).sin() * (2.0 * PI * b).sin();
        x[1] = b + 0.04 * (2.0 * PI * a).sin() * (PI * b).sin();
    }
}

/// Runs a mesh sequence and checks rates and caps; returns `(L2 slope, energy slope)`.
fn check_rates(
    label: &str,
    p: usize,
    ns: &[usize],
    make: impl Fn(usize) -> Mesh,
    analysis: Analysis,
) -> (f64, f64) {
    let mut hs = Vec::new();
    let mut l2 = Vec::new();
    let mut en = Vec::new();
    for &n in ns {
        let e = solve(make(n), analysis);
        eprintln!(
            "{label:<28} n = {n:>2}: L2 {:.3e} (interp {:.3e})  energy {:.3e} (interp {:.3e})",
            e.l2, e.l2_interp, e.energy, e.energy_interp
        );
        assert!(
            e.energy <= 1.02 * e.energy_interp,
            "{label} n = {n}: energy error {:.3e} above the best-approximation bound {:.3e}",
            e.energy,
            e.energy_interp
        );
        assert!(
            e.l2 <= 3.0 * e.l2_interp,
            "{label} n = {n}: L2 error {:.3e} vs interpolation error {:.3e}",
            e.l2,
            e.l2_interp
        );
        hs.push(1.0 / n as f64);
        l2.push(e.l2);
        en.push(e.energy);
    }
    // Fit over the three finest meshes (the asymptotic range; the first 2D mesh, 4 x 4, is
    // only used for the caps).
    let k = hs.len().saturating_sub(3);
    let (s_l2, s_en) = (slope(&hs[k..], &l2[k..]), slope(&hs[k..], &en[k..]));
    eprintln!(
        "{label:<28} slopes: L2 {s_l2:.3} (want {}), energy {s_en:.3} (want {p})",
        p + 1
    );
    assert!(
        (s_l2 - (p + 1) as f64).abs() < 0.1,
        "{label}: L2 slope {s_l2:.3}, expected {}",
        p + 1
    );
    assert!(
        (s_en - p as f64).abs() < 0.1,
        "{label}: energy slope {s_en:.3}, expected {p}"
    );
    (s_l2, s_en)
}

const STRAIN: Analysis = Analysis::PlaneStrain { thickness: 1.0 };
const STRESS: Analysis = Analysis::PlaneStress { thickness: 0.5 };

#[test]
fn body_force_is_minus_div_sigma() {
    // Central differences (h = 1e-5, error O(h^2 |u'''|) ~ 1e-10 relative) of the crate's
    // stress, against the closed-form body force used by every other test here.
    for analysis in [STRAIN, STRESS, Analysis::Solid] {
        let dim = analysis.dim();
        let ex = Exact::new(dim);
        let mat = Material::new(E, NU, 0.0).unwrap();
        let sigma = |x: [f64; 3]| {
            let s = mat.stress(analysis, &ex.strain(x));
            // Voigt [xx, yy, zz, yz, xz, xy] -> tensor.
            [[s[0], s[5], s[4]], [s[5], s[1], s[3]], [s[4], s[3], s[2]]]
        };
        for x in [[0.2, 0.7, 0.4], [0.9, 0.1, 0.6], [0.5, 0.5, 0.5]] {
            let x = if dim == 2 { [x[0], x[1], 0.0] } else { x };
            let h = 1e-5;
            let b = ex.body_force(x, analysis);
            let scale = E * 1e-3 * 10.0;
            for (i, bi) in b.iter().enumerate().take(dim) {
                let mut div = 0.0;
                for j in 0..dim {
                    let (mut xp, mut xm) = (x, x);
                    xp[j] += h;
                    xm[j] -= h;
                    div += (sigma(xp)[i][j] - sigma(xm)[i][j]) / (2.0 * h);
                }
                assert!(
                    (bi + div).abs() < 1e-7 * scale,
                    "{analysis:?} at {x:?}: b_{i} = {bi} but -div sigma = {}",
                    -div
                );
            }
        }
    }
}

#[test]
fn linear_triangles_t3() {
    for analysis in [STRAIN, STRESS] {
        check_rates(
            &format!("T3 {analysis:?}"),
            1,
            &[4, 8, 16, 32],
            |n| generate::rectangle(1.0, 1.0, n, n, CellType::Tri3).unwrap(),
            analysis,
        );
    }
}

#[test]
fn quadratic_triangles_t6() {
    for analysis in [STRAIN, STRESS] {
        check_rates(
            &format!("T6 {analysis:?}"),
            2,
            &[4, 8, 16, 32],
            |n| generate::rectangle(1.0, 1.0, n, n, CellType::Tri6).unwrap(),
            analysis,
        );
    }
}

#[test]
fn bilinear_quads_q4() {
    for analysis in [STRAIN, STRESS] {
        check_rates(
            &format!("Q4 {analysis:?}"),
            1,
            &[4, 8, 16, 32],
            |n| generate::rectangle(1.0, 1.0, n, n, CellType::Quad4).unwrap(),
            analysis,
        );
    }
}

#[test]
fn serendipity_quads_q8() {
    for analysis in [STRAIN, STRESS] {
        check_rates(
            &format!("Q8 {analysis:?}"),
            2,
            &[4, 8, 16, 32],
            |n| generate::rectangle(1.0, 1.0, n, n, CellType::Quad8).unwrap(),
            analysis,
        );
    }
}

#[test]
fn distorted_meshes_keep_optimal_rates() {
    for (kind, p, analysis) in [
        (CellType::Quad4, 1, STRAIN),
        (CellType::Tri6, 2, STRESS),
        (CellType::Quad8, 2, STRAIN),
    ] {
        check_rates(
            &format!("{kind} distorted {analysis:?}"),
            p,
            &[4, 8, 16, 32],
            |n| {
                let mut m = generate::rectangle(1.0, 1.0, n, n, kind).unwrap();
                distort(&mut m);
                m
            },
            analysis,
        );
    }
}

#[test]
fn linear_tetrahedra_tet4() {
    check_rates(
        "Tet4 solid",
        1,
        &[4, 8, 16],
        |n| generate::box_mesh([1.0; 3], [n; 3], CellType::Tet4).unwrap(),
        Analysis::Solid,
    );
}

#[test]
fn quadratic_tetrahedra_tet10() {
    check_rates(
        "Tet10 solid",
        2,
        &[2, 4, 8],
        |n| generate::box_mesh([1.0; 3], [n; 3], CellType::Tet10).unwrap(),
        Analysis::Solid,
    );
}

#[test]
fn trilinear_hexahedra_hex8() {
    check_rates(
        "Hex8 solid",
        1,
        &[3, 6, 12],
        |n| generate::box_mesh([1.0; 3], [n; 3], CellType::Hex8).unwrap(),
        Analysis::Solid,
    );
}
