//! FORM and SORM in the standard normal space.
//!
//! **FORM** (Hasofer-Lind; improved HL-RF of Zhang & Der Kiureghian, Proc. IFIP 1997): from
//! `u_k`, with `G_k = G(u_k)` and its gradient `d_k` (central finite differences), the HL-RF
//! point is `u_HL = ((d_k . u_k - G_k) / |d_k|^2) d_k`; the step `u_{k+1} = u_k + lambda (u_HL -
//! u_k)` takes the largest `lambda = 2^-j` that decreases the merit function
//! `m(u) = |u|^2 / 2 + c |G(u)|`, `c = 2 |u_k| / |d_k| + 10`. Converged when the step is below
//! `tol (1 + |u|)` and `|G| <= tol |G(0)|`. Then `beta = sign(G(0)) |u*|` and
//! `P_f ~ Phi(-beta)`; `alpha = -d / |d|` at `u*` (the importance factors are `alpha_i^2`).
//!
//! **SORM**: the Hessian `H` of `G` at `u*` by finite differences of the gradient; with an
//! orthonormal frame `R` whose last axis is `alpha`, the principal curvatures `kappa_i` are the
//! eigenvalues (cyclic Jacobi) of the leading `(d-1) x (d-1)` block of `R^T H R / |d|`
//! (positive when the limit state curves away from the origin, i.e. a smaller failure domain).
//! Breitung (1984): `P_B = Phi(-beta) prod_i (1 + beta kappa_i)^-1/2`. Tvedt (1990):
//! `P_T = A1 + A2 + A3`, `A1 = P_B`,
//! `A2 = (beta Phi(-beta) - phi(beta)) [prod (1 + beta kappa_i)^-1/2 - prod (1 + (beta + 1) kappa_i)^-1/2]`,
//! `A3 = (beta + 1) (beta Phi(-beta) - phi(beta)) [prod (1 + beta kappa_i)^-1/2 - Re prod (1 + (beta + i) kappa_i)^-1/2]`.
//! Both need `1 + beta kappa_i > 0`.

use super::LimitState;
use crate::eigen::{JacobiStop, jacobi_sweeps};
use crate::error::{Result, UqError, invalid};
use crate::special::{norm_cdf, norm_pdf};
use rayon::prelude::*;

/// Options of [`form`].
#[derive(Debug, Clone, PartialEq)]
pub struct FormOptions {
    /// Largest number of HL-RF iterations (default 100).
    pub max_iter: usize,
    /// Relative tolerance on the step and on `|G| / |G(0)|` (default 1e-6).
    pub tol: f64,
    /// Finite-difference step in the standard normal space (default 1e-4).
    pub step: f64,
    /// Starting point in the standard normal space (default: the origin). Needed when the
    /// gradient vanishes at the origin by symmetry (several design points).
    pub start: Option<Vec<f64>>,
}

impl Default for FormOptions {
    fn default() -> Self {
        Self {
            max_iter: 100,
            tol: 1e-6,
            step: 1e-4,
            start: None,
        }
    }
}

/// Result of [`form`].
#[derive(Debug, Clone, PartialEq)]
pub struct FormResult {
    /// Reliability index `beta` (negative if the origin fails).
    pub beta: f64,
    /// `Phi(-beta)`.
    pub pf: f64,
    /// Design point in the standard normal space.
    pub u_star: Vec<f64>,
    /// Design point in the physical space.
    pub x_star: Vec<f64>,
    /// Unit vector from the origin towards failure, `-grad G / |grad G|` at `u*`.
    pub alpha: Vec<f64>,
    /// `|grad G(u*)|`.
    pub grad_norm: f64,
    /// HL-RF iterations.
    pub iterations: usize,
    /// Evaluations of the limit state.
    pub evaluations: usize,
}

impl FormResult {
    /// Importance factors `alpha_i^2` (sum 1).
    pub fn importance_factors(&self) -> Vec<f64> {
        self.alpha.iter().map(|a| a * a).collect()
    }
}

/// Result of [`sorm`].
#[derive(Debug, Clone, PartialEq)]
pub struct SormResult {
    /// The FORM result it starts from.
    pub form: FormResult,
    /// Principal curvatures of the limit state at the design point.
    pub curvatures: Vec<f64>,
    /// Breitung's approximation.
    pub pf_breitung: f64,
    /// Tvedt's three-term approximation.
    pub pf_tvedt: f64,
    /// Evaluations of the limit state (FORM included).
    pub evaluations: usize,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// Central-difference gradient of `G` at `u` (2d evaluations, in parallel).
fn gradient(ls: &LimitState, u: &[f64], h: f64) -> Vec<f64> {
    (0..u.len())
        .into_par_iter()
        .map(|i| {
            let mut up = u.to_vec();
            up[i] += h;
            let gp = ls.eval_u(&up);
            up[i] -= 2.0 * h;
            let gm = ls.eval_u(&up);
            (gp - gm) / (2.0 * h)
        })
        .collect()
}

fn not_finite(what: &'static str, at: &str) -> UqError {
    UqError::Invalid {
        what,
        message: format!("the limit state is not finite at {at}"),
    }
}

/// FORM: design point, reliability index and `Phi(-beta)` (see the module docs).
///
/// # Errors
/// If the options are out of range, the limit state is not finite at a visited point, its
/// gradient vanishes, or the iteration does not converge within `max_iter`.
pub fn form(ls: &LimitState, opts: &FormOptions) -> Result<FormResult> {
    let what = "FORM";
    if !(opts.step > 0.0 && opts.step.is_finite()) {
        return Err(invalid(what, "step", "> 0", opts.step));
    }
    if !(opts.tol > 0.0) {
        return Err(invalid(what, "tol", "> 0", opts.tol));
    }
    let start = ls.calls();
    let d = ls.dim();
    let origin = vec![0.0; d];
    let g0 = ls.eval_u(&origin);
    if !g0.is_finite() {
        return Err(not_finite(what, "the median point"));
    }
    let gscale = g0.abs().max(f64::MIN_POSITIVE);
    let mut u = match &opts.start {
        Some(s) => {
            crate::error::check_len(what, "start", d, s.len())?;
            s.clone()
        }
        None => origin,
    };
    let mut g = if opts.start.is_some() {
        ls.eval_u(&u)
    } else {
        g0
    };
    if !g.is_finite() {
        return Err(not_finite(what, "the starting point"));
    }
    for it in 1..=opts.max_iter {
        let grad = gradient(ls, &u, opts.step);
        let gn = norm(&grad);
        if !(gn > 0.0 && gn.is_finite()) {
            return Err(UqError::Invalid {
                what,
                message: format!("the gradient of the limit state is {gn} at iteration {it}"),
            });
        }
        let s = (dot(&grad, &u) - g) / (gn * gn);
        let dir: Vec<f64> = grad.iter().zip(&u).map(|(gi, ui)| s * gi - ui).collect();
        let c = 2.0 * norm(&u) / gn + 10.0;
        let merit = |uu: &[f64], gg: f64| 0.5 * dot(uu, uu) + c * gg.abs();
        let m0 = merit(&u, g);
        // Armijo: m(u + l d) <= m(u) - 1e-4 l |d|^2 (d is a descent direction of m).
        let mut lambda = 1.0;
        let (mut un, mut gnew);
        loop {
            un = u
                .iter()
                .zip(&dir)
                .map(|(a, b)| a + lambda * b)
                .collect::<Vec<_>>();
            gnew = ls.eval_u(&un);
            if gnew.is_finite() && merit(&un, gnew) <= m0 - 1e-4 * lambda * dot(&dir, &dir) {
                break;
            }
            lambda *= 0.5;
            if lambda < 1e-6 {
                break;
            }
        }
        if !gnew.is_finite() {
            return Err(not_finite(what, &format!("u = {un:?}")));
        }
        let step = norm(&dir) * lambda;
        u = un;
        g = gnew;
        if step <= opts.tol * (1.0 + norm(&u)) && g.abs() <= opts.tol * gscale.max(1e-300) {
            let grad = gradient(ls, &u, opts.step);
            let gn = norm(&grad);
            let alpha: Vec<f64> = grad.iter().map(|v| -v / gn).collect();
            let beta = norm(&u) * if g0 >= 0.0 { 1.0 } else { -1.0 };
            let mut x = vec![0.0; d];
            ls.law().standard_normal_to_x(&u, &mut x);
            return Ok(FormResult {
                beta,
                pf: norm_cdf(-beta),
                u_star: u,
                x_star: x,
                alpha,
                grad_norm: gn,
                iterations: it,
                evaluations: ls.calls() - start,
            });
        }
    }
    Err(UqError::Invalid {
        what,
        message: format!(
            "no convergence in {} iterations (|G| = {g:.3e}, |u| = {:.4})",
            opts.max_iter,
            norm(&u)
        ),
    })
}

/// SORM (Breitung and Tvedt) from a FORM result, with the Hessian by central differences of
/// the limit state's values (`2 d^2 + 1` more evaluations).
///
/// # Errors
/// As [`form`], or if a curvature makes `1 + beta kappa <= 0` (the parabolic approximation
/// does not exist).
pub fn sorm(ls: &LimitState, opts: &FormOptions) -> Result<SormResult> {
    let f = form(ls, opts)?;
    sorm_at(ls, f, opts)
}

/// SORM at a design point `f` that [`form`] found with the options `opts` (only `opts.step`
/// is used): the Hessian there (`2 d^2 + 1` evaluations), the curvatures, Breitung and Tvedt.
/// [`SormResult::evaluations`] counts `f`'s evaluations too.
///
/// # Errors
/// If a curvature makes `1 + beta kappa <= 0`, or `f` has the wrong dimension.
pub fn sorm_at(ls: &LimitState, f: FormResult, opts: &FormOptions) -> Result<SormResult> {
    crate::error::check_len("SORM", "design point", ls.dim(), f.u_star.len())?;
    let start = ls.calls();
    let d = ls.dim();
    let h = opts.step.max(1e-3) * 10.0;
    // Hessian by central differences of the values (second order, `2 d^2 + 1` evaluations;
    // central differences of a central-difference gradient took `4 d^2`):
    // H_ii = (G(u + h e_i) - 2 G(u) + G(u - h e_i)) / h^2,
    // H_ij = (G(++) - G(+-) - G(-+) + G(--)) / (4 h^2).
    let g0 = ls.eval_u(&f.u_star);
    let at = |steps: &[(usize, f64)]| {
        let mut u = f.u_star.clone();
        for &(i, s) in steps {
            u[i] += s;
        }
        ls.eval_u(&u)
    };
    let mut hess = vec![0.0; d * d];
    for i in 0..d {
        hess[i * d + i] = (at(&[(i, h)]) - 2.0 * g0 + at(&[(i, -h)])) / (h * h);
        for j in 0..i {
            let v = (at(&[(i, h), (j, h)]) - at(&[(i, h), (j, -h)]) - at(&[(i, -h), (j, h)])
                + at(&[(i, -h), (j, -h)]))
                / (4.0 * h * h);
            hess[i * d + j] = v;
            hess[j * d + i] = v;
        }
    }
    // Orthonormal frame with last axis alpha: Householder reflection mapping e_d to alpha.
    let frame = frame_with_last_axis(&f.alpha);
    // B = R^T H R / |grad|, leading (d-1) block.
    let m = d - 1;
    let mut b = vec![0.0; m * m];
    for p in 0..m {
        for q in 0..m {
            let mut s = 0.0;
            for i in 0..d {
                for j in 0..d {
                    s += frame[i * d + p] * hess[i * d + j] * frame[j * d + q];
                }
            }
            b[p * m + q] = s / f.grad_norm;
        }
    }
    let curvatures = symmetric_eigenvalues(b, m);
    let beta = f.beta;
    for &k in &curvatures {
        if !(1.0 + beta * k > 0.0) {
            return Err(UqError::Invalid {
                what: "SORM",
                message: format!(
                    "curvature {k:.4} with beta {beta:.4}: 1 + beta kappa <= 0, no parabolic approximation"
                ),
            });
        }
    }
    let (pb, pt) = breitung_tvedt(beta, &curvatures);
    let f_evaluations = f.evaluations;
    Ok(SormResult {
        form: f,
        curvatures,
        pf_breitung: pb,
        pf_tvedt: pt,
        evaluations: f_evaluations + ls.calls() - start,
    })
}

/// Breitung's and Tvedt's approximations for reliability index `beta` and curvatures `kappa`.
pub fn breitung_tvedt(beta: f64, kappa: &[f64]) -> (f64, f64) {
    let phi_b = norm_cdf(-beta);
    let prod = |t: f64| {
        kappa
            .iter()
            .map(|k| (1.0 + t * k).powf(-0.5))
            .product::<f64>()
    };
    let p0 = prod(beta);
    let pb = phi_b * p0;
    let c = beta * phi_b - norm_pdf(beta);
    let a2 = c * (p0 - prod(beta + 1.0));
    // Re prod (1 + (beta + i) kappa)^-1/2: complex principal square roots.
    let (mut re, mut im) = (1.0, 0.0);
    for &k in kappa {
        // z = 1 + beta k + i k ; z^-1/2 = |z|^-1/2 exp(-i arg(z)/2)
        let (zr, zi) = (1.0 + beta * k, k);
        let r = (zr * zr + zi * zi).sqrt().powf(-0.5);
        let th = -0.5 * zi.atan2(zr);
        let (wr, wi) = (r * th.cos(), r * th.sin());
        let nr = re * wr - im * wi;
        im = re * wi + im * wr;
        re = nr;
    }
    let a3 = (beta + 1.0) * c * (p0 - re);
    (pb, pb + a2 + a3)
}

/// Row-major `d x d` orthogonal matrix whose last column is the unit vector `a`.
fn frame_with_last_axis(a: &[f64]) -> Vec<f64> {
    let d = a.len();
    // Householder H = I - 2 v v^T / v^T v with v = e_d - a maps e_d to a (H symmetric).
    let mut v: Vec<f64> = a.iter().map(|x| -x).collect();
    v[d - 1] += 1.0;
    let vv = dot(&v, &v);
    let mut h = vec![0.0; d * d];
    for i in 0..d {
        for j in 0..d {
            let e = if i == j { 1.0 } else { 0.0 };
            h[i * d + j] = if vv > 1e-300 {
                e - 2.0 * v[i] * v[j] / vv
            } else {
                e
            };
        }
    }
    h
}

/// Eigenvalues of a symmetric `n x n` matrix (row-major) by cyclic Jacobi rotations, ascending.
pub(crate) fn symmetric_eigenvalues(mut a: Vec<f64>, n: usize) -> Vec<f64> {
    let stop = JacobiStop {
        max_sweeps: 100,
        skip_below: 1e-300,
        converged: |a: &[f64]| {
            let off: f64 = (0..n)
                .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
                .map(|(i, j)| a[i * n + j].powi(2))
                .sum();
            let diag: f64 = (0..n).map(|i| a[i * n + i].powi(2)).sum();
            off <= 1e-30 * diag.max(1e-300)
        },
    };
    jacobi_sweeps(&mut a, None, n, &stop);
    let mut e: Vec<f64> = (0..n).map(|i| a[i * n + i]).collect();
    e.sort_by(f64::total_cmp);
    e
}
