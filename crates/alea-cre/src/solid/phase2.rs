//! EET phase 2 in 3D (thesis (3.23)): on every element, the Neumann problem
//! `div sigma_hat + f = 0` in `E`, `sigma_hat n = eta_E F_hat` on `dE`, solved in displacement
//! with the complete polynomial space of degree `p + k` on the element itself, rigid modes
//! removed ([`super::poly`]); then `theta_E^2 = ||sigma_hat - sigma_h||^2_{K^-1,E} = int_E
//! (eps(v) - eps_h) : K (eps(v) - eps_h)`.
//!
//! With an isotropic material (`lambda`, `mu` of the cell), the stiffness of two vector basis
//! functions `phi_a e_c` and `phi_b e_d` is `lambda G_cd[a][b] + mu (delta_cd sum_e G_ee[a][b] +
//! G_dc[a][b])` with the scalar integrals `G_pq[a][b] = int_E d_p phi_a d_q phi_b` (six blocks of
//! `n_s x n_s`, `G_qp = G_pq^T`, computed as products `B_p^T B_q` of the weighted gradient
//! tables by faer's matrix product), and the load is `L_c[a] = int_E f_c phi_a + sum_faces int eta
//! F_hat_c phi_a`: the local matrices cost `O(n_s^2)` per quadrature point instead of
//! `O((3 n_s)^2)`. Volume rules: collapsed Gauss of degree `2 (p + k) - 1` on tetrahedra (exact
//! for the stiffness on affine cells), `p + k + 1` Gauss points per direction on hexahedra;
//! faces: degree `2 p + k + 2` (the density of degree `p` times the test functions, plus a
//! margin for non-polynomial data).
//!
//! The discrete solution satisfies the Neumann problem only weakly: `sigma_hat` is exactly
//! statically admissible only in the limit of the exact local solution (thesis 3.1.1.4 b,
//! remark), as in 2D.

use alea_fem::{Model, Quadrature, kinematics::point_geometry};
use alea_mesh::CellType;

use super::phase1::FaceTractions;
use super::poly::{PolySpace3, ScalarPoint, voigt_index};
use faer::linalg::matmul::matmul;
use faer::linalg::solvers::Solve;
use faer::{Accum, Mat, MatRef, Par, Side};

use crate::CreError;
use crate::contribution::{ElementContribution, balance_defect};
use crate::data::VectorField;
use crate::fe::check_jacobian;

/// The admissible stress of one 3D element: `sigma_hat = K eps(sum_c sum_s u[c][s] phi_s e_c)`.
#[derive(Clone, Debug)]
pub struct SolidElementStress {
    /// The local displacement space.
    pub space: PolySpace3,
    /// Scalar coefficients of each displacement component.
    pub u: [Vec<f64>; 3],
    /// Lame constants `(lambda, mu)` of the cell.
    pub lame: (f64, f64),
}

impl SolidElementStress {
    /// Displacement gradient `grad[c][d] = d u_c / d x_d` at physical point `x`.
    fn gradient(&self, p: &ScalarPoint) -> [[f64; 3]; 3] {
        let mut g = [[0.0; 3]; 3];
        for c in 0..3 {
            for (s, gr) in p.grad.iter().enumerate() {
                let a = self.u[c][s];
                for d in 0..3 {
                    g[c][d] += a * gr[d];
                }
            }
        }
        g
    }

    /// `sigma_hat = [xx, yy, zz, yz, xz, xy]` at physical point `x`.
    pub fn stress(&self, x: [f64; 3]) -> [f64; 6] {
        let mut p = ScalarPoint::default();
        self.space.eval(x, false, &mut p);
        let g = self.gradient(&p);
        let (lam, mu) = self.lame;
        let tr = g[0][0] + g[1][1] + g[2][2];
        [
            lam * tr + 2.0 * mu * g[0][0],
            lam * tr + 2.0 * mu * g[1][1],
            lam * tr + 2.0 * mu * g[2][2],
            mu * (g[1][2] + g[2][1]),
            mu * (g[0][2] + g[2][0]),
            mu * (g[0][1] + g[1][0]),
        ]
    }

    /// `div sigma_hat` at physical point `x`.
    pub fn divergence(&self, x: [f64; 3]) -> [f64; 3] {
        let mut p = ScalarPoint::default();
        self.space.eval(x, true, &mut p);
        // Second derivatives of each component: h[c] = [xx, yy, zz, yz, xz, xy].
        let mut h = [[0.0; 6]; 3];
        for c in 0..3 {
            for (s, hs) in p.hess.iter().enumerate() {
                for k in 0..6 {
                    h[c][k] += self.u[c][s] * hs[k];
                }
            }
        }
        let d2 = |c: usize, i: usize, j: usize| -> f64 { h[c][voigt_index(i, j)] };
        let (lam, mu) = self.lame;
        // div sigma = (lambda + mu) grad div u + mu lap u.
        let mut out = [0.0; 3];
        for (i, o) in out.iter_mut().enumerate() {
            let grad_div: f64 = (0..3).map(|c| d2(c, c, i)).sum();
            let lap: f64 = (0..3).map(|j| d2(i, j, j)).sum();
            *o = (lam + mu) * grad_div + mu * lap;
        }
        out
    }
}

/// Phase-2 result of one 3D element.
pub type SolidElementResult = ElementContribution<SolidElementStress>;

/// Quadrature rules of the 3D local problems of one degree (built once, shared by all cells).
#[derive(Clone, Debug)]
pub struct SolidRules {
    /// Local polynomial degree `p + k`.
    pub degree: usize,
    tet: Quadrature,
    hex: Quadrature,
    tri: Quadrature,
    quad: Quadrature,
}

impl SolidRules {
    /// Rules for local degree `degree` on cells of order `order` (1: Tet4/Hex8, 2: Tet10).
    pub fn new(degree: usize, order: usize) -> Self {
        SolidRules {
            degree,
            tet: Quadrature::tetrahedron(2 * degree - 1),
            hex: Quadrature::tensor(3, degree + 1),
            tri: Quadrature::triangle(degree + 2 * order + 2),
            quad: Quadrature::for_cell(CellType::Quad4, degree + 2 * order + 2),
        }
    }
}

/// A volume quadrature point kept for `theta_E`: weight `w det J`, FE displacement gradient,
/// gradients of the scalar basis.
type VolumePoint = (f64, [[f64; 3]; 3], Vec<[f64; 3]>);

/// Solves the local problem of 3D cell `c` and evaluates its contribution.
pub fn element(
    model: &Model,
    c: usize,
    u: &[f64],
    body: Option<&VectorField>,
    tr: &FaceTractions,
    rules: &SolidRules,
) -> Result<SolidElementResult, CreError> {
    let mesh = &model.mesh;
    let kind = mesh.cell_type(c);
    let coords = model.cell_coords(c);
    let nodes = mesh.cell_nodes(c);
    let ue: Vec<[f64; 3]> = nodes
        .iter()
        .map(|&n| [u[3 * n], u[3 * n + 1], u[3 * n + 2]])
        .collect();
    let (lam, mu) = model.material(c)?.lame();
    let space = PolySpace3::new(rules.degree, &coords);
    let ns = space.num_scalar();
    let rule = if kind == CellType::Hex8 {
        &rules.hex
    } else {
        &rules.tet
    };
    // Scalar integrals G_pq = B_p^T B_q with B_d[q][s] = sqrt(w_q det_q) d_d phi_s(x_q)
    // (column-major npts x ns), for (p, q) in PAIRS (Voigt order, `voigt_index`).
    const PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)];
    let npts = rule.len();
    let mut bmat = [
        vec![0.0; npts * ns],
        vec![0.0; npts * ns],
        vec![0.0; npts * ns],
    ];
    let mut load = [vec![0.0; ns], vec![0.0; ns], vec![0.0; ns]];
    let mut p = ScalarPoint::default();
    let ctr = space.center;
    let (mut res, mut abs_sum) = ([0.0; 6], 0.0);
    // Per point: weight, FE displacement gradient, scalar gradients (for theta).
    let mut pts: Vec<VolumePoint> = Vec::with_capacity(rule.len());
    for (q, (xi, w)) in rule.points.iter().zip(&rule.weights).enumerate() {
        let g = point_geometry(kind, &coords, *xi);
        check_jacobian(&g, c, kind)?;
        let wd = w * g.det;
        let mut gh = [[0.0; 3]; 3];
        for (a, ua) in ue.iter().enumerate() {
            for cc in 0..3 {
                for d in 0..3 {
                    gh[cc][d] += ua[cc] * g.grad[a][d];
                }
            }
        }
        space.eval(g.x, false, &mut p);
        let sw = wd.sqrt();
        for (s, gr) in p.grad.iter().enumerate() {
            for d in 0..3 {
                bmat[d][s * npts + q] = sw * gr[d];
            }
        }
        if let Some(b) = body {
            let f = b(g.x);
            for cc in 0..3 {
                for s in 0..ns {
                    load[cc][s] += wd * f[cc] * p.val[s];
                }
            }
            add_resultant(&mut res, &mut abs_sum, wd, g.x, ctr, f);
        }
        pts.push((wd, gh, p.grad.clone()));
    }
    // Face loads.
    for &(f, eta) in &tr.topo.cell_faces[c] {
        let face = &tr.topo.faces[f];
        let frule = if face.kind == CellType::Quad4 {
            &rules.quad
        } else {
            &rules.tri
        };
        for (rs, w) in frule.points.iter().zip(&frule.weights) {
            let g = face.geometry(mesh, *rs);
            let t = tr.traction(f, &g.n[..face.nodes.len()], g.x, g.normal);
            let t = [eta * t[0], eta * t[1], eta * t[2]];
            let ws = w * g.jac;
            space.eval(g.x, false, &mut p);
            for cc in 0..3 {
                for s in 0..ns {
                    load[cc][s] += ws * t[cc] * p.val[s];
                }
            }
            add_resultant(&mut res, &mut abs_sum, ws, g.x, ctr, t);
        }
    }
    let gmat: Vec<Mat<f64>> = PAIRS
        .iter()
        .map(|&(pp, qq)| {
            let bp = MatRef::from_column_major_slice(&bmat[pp], npts, ns);
            let bq = MatRef::from_column_major_slice(&bmat[qq], npts, ns);
            let mut g = Mat::<f64>::zeros(ns, ns);
            matmul(
                g.as_mut(),
                Accum::Replace,
                bp.transpose(),
                bq,
                1.0,
                Par::Seq,
            );
            g
        })
        .collect();
    let h = space.scale;
    let balance_defect = balance_defect(&res[..3], &res[3..], h, abs_sum);
    // G_pq[a][b] for any p, q (G_qp = G_pq^T).
    let gval = |pp: usize, qq: usize, a: usize, b: usize| -> f64 {
        let k = voigt_index(pp, qq);
        if pp > qq {
            gmat[k][(b, a)]
        } else {
            gmat[k][(a, b)]
        }
    };
    let block = |cc: usize, a: usize, d: usize, b: usize| -> f64 {
        let mut v = lam * gval(cc, d, a, b) + mu * gval(d, cc, a, b);
        if cc == d {
            v += mu * (gmat[0][(a, b)] + gmat[1][(a, b)] + gmat[2][(a, b)]);
        }
        v
    };
    let nb = space.len();
    let mut kmat = Mat::<f64>::zeros(nb, nb);
    let mut l = Mat::<f64>::zeros(nb, 1);
    for (i, fi) in space.funcs.iter().enumerate() {
        for &(ci, si, ai) in &fi.terms[..fi.nterms] {
            l[(i, 0)] += ai * load[ci][si];
        }
        for j in i..nb {
            let fj = &space.funcs[j];
            let mut v = 0.0;
            for &(ci, si, ai) in &fi.terms[..fi.nterms] {
                for &(cj, sj, aj) in &fj.terms[..fj.nterms] {
                    v += ai * aj * block(ci, si, cj, sj);
                }
            }
            kmat[(i, j)] = v;
            kmat[(j, i)] = v;
        }
    }
    let llt = kmat
        .llt(Side::Lower)
        .map_err(|_| CreError::LocalSolve { cell: c })?;
    llt.solve_in_place(l.as_mut());
    let v: Vec<f64> = (0..nb).map(|i| l[(i, 0)]).collect();
    if v.iter().any(|x| !x.is_finite()) {
        return Err(CreError::LocalSolve { cell: c });
    }
    let coeffs = space.expand(&v);
    let (mut theta2, mut energy2) = (0.0, 0.0);
    let energy = |g: &[[f64; 3]; 3]| -> f64 {
        let tr = g[0][0] + g[1][1] + g[2][2];
        let mut e2 = 0.0;
        for i in 0..3 {
            for j in 0..3 {
                let e = 0.5 * (g[i][j] + g[j][i]);
                e2 += e * e;
            }
        }
        lam * tr * tr + 2.0 * mu * e2
    };
    for (wd, gh, grads) in &pts {
        let mut gv = [[0.0; 3]; 3];
        for cc in 0..3 {
            for (s, gr) in grads.iter().enumerate() {
                let a = coeffs[cc][s];
                for d in 0..3 {
                    gv[cc][d] += a * gr[d];
                }
            }
        }
        let mut diff = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                diff[i][j] = gv[i][j] - gh[i][j];
            }
        }
        theta2 += wd * energy(&diff);
        energy2 += wd * energy(gh);
    }
    Ok(SolidElementResult {
        theta2,
        energy2,
        balance_defect,
        stress: SolidElementStress {
            space,
            u: coeffs,
            lame: (lam, mu),
        },
    })
}

/// Adds the force `w f` at `x` to the force and moment (about `ctr`) resultants.
fn add_resultant(
    res: &mut [f64; 6],
    abs_sum: &mut f64,
    w: f64,
    x: [f64; 3],
    ctr: [f64; 3],
    f: [f64; 3],
) {
    let r = [x[0] - ctr[0], x[1] - ctr[1], x[2] - ctr[2]];
    for k in 0..3 {
        res[k] += w * f[k];
    }
    res[3] += w * (r[1] * f[2] - r[2] * f[1]);
    res[4] += w * (r[2] * f[0] - r[0] * f[2]);
    res[5] += w * (r[0] * f[1] - r[1] * f[0]);
    *abs_sum += w.abs() * (f[0].abs() + f[1].abs() + f[2].abs());
}
