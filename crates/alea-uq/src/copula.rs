//! More copulas behind [`JointLaw`]: Student (elliptical, any dimension), Clayton (Archimedean,
//! any dimension), Gumbel and Frank (Archimedean, bivariate). Each is given with its marginals
//! `F_i`; `x_to_unit` is the Rosenblatt transform `v_k = C(u_k | u_1, ..., u_{k-1})` of the
//! copula applied to `u_i = F_i(x_i)`, `unit_to_x` its inverse, and
//! `pdf(x) = c(u) prod_i f_i(x_i)`.
//!
//! * **Student** (`nu` degrees of freedom, correlation `R = L L^T`): `z_i = T_nu^-1(u_i)`,
//!   `w = L^-1 z`; given the first `k` variables, `w_k sqrt((nu + k)/(nu + q_k))` is Student with
//!   `nu + k` degrees of freedom, `q_k = w_1^2 + ... + w_k^2` (conditional law of the
//!   multivariate t), so `v_k = T_{nu+k}(w_k sqrt((nu + k)/(nu + q_k)))`. Density
//!   `c = t_{R,nu}(z) / prod t_nu(z_i)`, `ln t_{R,nu}(z) = ln Gamma((nu+d)/2) - ln Gamma(nu/2)
//!   - (d/2) ln(nu pi) - ln|L| - (nu+d)/2 ln(1 + |w|^2/nu)`. Kendall's tau `(2/pi) asin rho`.
//! * **Clayton** (`theta > 0`, or `-1 < theta < 0` for two variables, where
//!   `C = max(S_2, 0)^(-1/theta)` and the density and the conditional laws vanish where
//!   `S_2 <= 0`): `C(u) = (S_d)^(-1/theta)`, `S_k = sum_{i<=k} u_i^-theta - k + 1`;
//!   `v_k = (S_k / S_{k-1})^(-1/theta - (k-1))` (1-based `k`), inverse
//!   `u_k = (S_{k-1} (v_k^(-1/(1/theta + k - 1)) - 1) + 1)^(-1/theta)`; density
//!   `c = prod_{k<d} (1 + k theta) prod u_i^(-theta-1) S_d^(-1/theta - d)`. Tau `theta/(theta+2)`.
//! * **Gumbel** (`theta >= 1`): `C = exp(-A^(1/theta))`, `A = x^theta + y^theta`,
//!   `x = -ln u`, `y = -ln v`; `C(v | u) = C A^(1/theta - 1) x^(theta-1) / u`, inverted in `v`
//!   by safeguarded Newton (its derivative in `v` is the density); density
//!   `c = C (x y)^(theta-1) A^(1/theta - 2) (A^(1/theta) + theta - 1) / (u v)`.
//!   Tau `1 - 1/theta`.
//! * **Frank** (`theta != 0`): `C = -ln(1 + (e^(-theta u) - 1)(e^(-theta v) - 1)/(e^-theta - 1))/theta`;
//!   `C(v | u) = e^(-theta u)(e^(-theta v) - 1) / ((e^-theta - 1) + (e^(-theta u) - 1)(e^(-theta v) - 1))`,
//!   inverse `v = -ln(1 + w (e^-theta - 1) / (w + (1 - w) e^(-theta u)))/theta`; density
//!   `c = theta (1 - e^-theta) e^(-theta (u + v)) / ((1 - e^-theta) - (1 - e^(-theta u))(1 - e^(-theta v)))^2`.

use crate::error::{Result, UqError, check_len, invalid};
use crate::joint::JointLaw;
use crate::law::Marginal;
use crate::special::{
    ln_gamma, ln_student_pdf, norm_cdf, safeguarded_newton, student_cdf, student_quantile,
};
use std::sync::Arc;

/// Clamp a probability away from 0 and 1 (the copula formulas take logarithms and powers).
fn clamp01(u: f64) -> f64 {
    u.clamp(1e-300, 1.0 - f64::EPSILON / 2.0)
}

fn check_marginals(what: &'static str, m: &[Arc<dyn Marginal>], d: Option<usize>) -> Result<()> {
    if m.is_empty() {
        return Err(invalid(what, "marginals", "non-empty", 0.0));
    }
    if let Some(d) = d {
        check_len(what, "marginals", d, m.len())?;
    }
    Ok(())
}

fn bounds(m: &[Arc<dyn Marginal>]) -> (Vec<f64>, Vec<f64>) {
    m.iter().map(|l| l.support()).unzip()
}

/// Student copula.
#[derive(Debug, Clone)]
pub struct StudentCopula {
    marginals: Vec<Arc<dyn Marginal>>,
    chol: Vec<f64>,
    nu: f64,
    ln_const: f64,
}

impl StudentCopula {
    /// `corr`: row-major `d x d` correlation matrix; `nu > 0` degrees of freedom.
    ///
    /// # Errors
    /// If sizes disagree, `nu <= 0`, or `corr` is not a correlation matrix (symmetric, unit
    /// diagonal, positive definite).
    pub fn new(marginals: Vec<Arc<dyn Marginal>>, corr: Vec<f64>, nu: f64) -> Result<Self> {
        let what = "student copula";
        check_marginals(what, &marginals, None)?;
        if !(nu > 0.0 && nu.is_finite()) {
            return Err(invalid(what, "nu", "> 0", nu));
        }
        // Reuse the Gaussian copula's checks of the correlation matrix.
        let g = crate::joint::GaussianCopula::new(marginals.clone(), corr).map_err(|e| {
            UqError::Invalid {
                what,
                message: e.to_string(),
            }
        })?;
        let d = marginals.len();
        let chol = crate::linalg::cholesky(what, g.correlation(), d)?;
        let ln_det_l: f64 = (0..d).map(|i| chol[i * d + i].ln()).sum();
        let df = d as f64;
        let ln_const = ln_gamma(0.5 * (nu + df))
            - ln_gamma(0.5 * nu)
            - 0.5 * df * (nu * std::f64::consts::PI).ln()
            - ln_det_l;
        Ok(Self {
            marginals,
            chol,
            nu,
            ln_const,
        })
    }
    /// Degrees of freedom.
    pub fn nu(&self) -> f64 {
        self.nu
    }
}

/// The marginal's quantile at `u` (clamped to `[0, 1]`); where a conditional inversion rounds
/// `u` to 0 or 1 and the law is unbounded there, the quantile at `Phi(-+Z_TAIL)` instead
/// (probability 1.2e-16 beyond: [`crate::law::Marginal::quantile_of_normal`]), so that a draw
/// or a point of the standard normal space never maps to an infinite coordinate.
fn finite_quantile(m: &dyn Marginal, u: f64) -> f64 {
    let x = m.quantile(u.clamp(0.0, 1.0));
    if x.is_finite() || u.is_nan() {
        return x;
    }
    let t = crate::law::Z_TAIL;
    m.quantile(u.clamp(norm_cdf(-t), norm_cdf(t)))
}

impl JointLaw for StudentCopula {
    fn dim(&self) -> usize {
        self.marginals.len()
    }
    fn pdf(&self, x: &[f64]) -> f64 {
        let d = self.dim();
        let mut lnf = 0.0;
        let mut w = vec![0.0; d];
        let mut q = 0.0;
        let mut ln_marg_t = 0.0;
        for k in 0..d {
            let f = self.marginals[k].pdf(x[k]);
            if !(f > 0.0) {
                return 0.0;
            }
            lnf += f.ln();
            let z = student_quantile(clamp01(self.marginals[k].cdf(x[k])), self.nu);
            ln_marg_t += ln_student_pdf(z, self.nu);
            let s: f64 = (0..k).map(|j| self.chol[k * d + j] * w[j]).sum();
            w[k] = (z - s) / self.chol[k * d + k];
            q += w[k] * w[k];
        }
        let ln_joint = self.ln_const - 0.5 * (self.nu + d as f64) * (q / self.nu).ln_1p();
        (ln_joint - ln_marg_t + lnf).exp()
    }
    fn x_to_unit(&self, x: &[f64], v: &mut [f64]) {
        let d = self.dim();
        let mut w = vec![0.0; d];
        let mut q = 0.0;
        for k in 0..d {
            let z = student_quantile(clamp01(self.marginals[k].cdf(x[k])), self.nu);
            let s: f64 = (0..k).map(|j| self.chol[k * d + j] * w[j]).sum();
            w[k] = (z - s) / self.chol[k * d + k];
            let kf = k as f64;
            v[k] = student_cdf(w[k] * ((self.nu + kf) / (self.nu + q)).sqrt(), self.nu + kf);
            q += w[k] * w[k];
        }
    }
    fn unit_to_x(&self, v: &[f64], x: &mut [f64]) {
        let d = self.dim();
        let mut w = vec![0.0; d];
        let mut q = 0.0;
        for k in 0..d {
            let kf = k as f64;
            w[k] = student_quantile(clamp01(v[k]), self.nu + kf)
                * ((self.nu + q) / (self.nu + kf)).sqrt();
            q += w[k] * w[k];
            let z: f64 = (0..=k).map(|j| self.chol[k * d + j] * w[j]).sum();
            x[k] = finite_quantile(self.marginals[k].as_ref(), student_cdf(z, self.nu));
        }
    }
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        bounds(&self.marginals)
    }
}

/// Clayton copula in any dimension.
#[derive(Debug, Clone)]
pub struct ClaytonCopula {
    marginals: Vec<Arc<dyn Marginal>>,
    theta: f64,
}

impl ClaytonCopula {
    /// `theta > 0` in any dimension; `-1 < theta < 0` (negative dependence, Kendall's tau down
    /// to -1/3 at theta = -1/2 and towards -1 as theta -> -1) for two variables, where
    /// `C = max(S_2, 0)^(-1/theta)` is a copula (it is not one in higher dimensions).
    ///
    /// # Errors
    /// If `theta` is 0, not finite, `<= -1`, negative with more than two marginals, or there
    /// are no marginals.
    pub fn new(marginals: Vec<Arc<dyn Marginal>>, theta: f64) -> Result<Self> {
        let what = "clayton copula";
        check_marginals(what, &marginals, None)?;
        let valid = theta.is_finite()
            && (theta > 0.0 || (theta > -1.0 && theta < 0.0 && marginals.len() == 2));
        if !valid {
            return Err(invalid(
                what,
                "theta",
                "> 0, or in (-1, 0) for two variables",
                theta,
            ));
        }
        Ok(Self { marginals, theta })
    }
    /// `C(u)` on the unit cube (`max(S_d, 0)^(-1/theta)`: 0 where `S_d <= 0`, for `theta < 0`).
    pub fn copula_cdf(&self, u: &[f64]) -> f64 {
        let s: f64 =
            u.iter().map(|&v| clamp01(v).powf(-self.theta)).sum::<f64>() - u.len() as f64 + 1.0;
        if s <= 0.0 {
            return 0.0;
        }
        s.powf(-1.0 / self.theta)
    }
}

impl JointLaw for ClaytonCopula {
    fn dim(&self) -> usize {
        self.marginals.len()
    }
    fn pdf(&self, x: &[f64]) -> f64 {
        let d = self.dim();
        let t = self.theta;
        let mut ln = 0.0;
        let mut s = 1.0 - d as f64;
        for k in 0..d {
            let f = self.marginals[k].pdf(x[k]);
            if !(f > 0.0) {
                return 0.0;
            }
            let u = clamp01(self.marginals[k].cdf(x[k]));
            ln += f.ln() + (1.0 + k as f64 * t).ln() - (t + 1.0) * u.ln();
            s += u.powf(-t);
        }
        // theta < 0: no mass where S_2 <= 0.
        if s <= 0.0 {
            return 0.0;
        }
        (ln - (1.0 / t + d as f64) * s.ln()).exp()
    }
    fn x_to_unit(&self, x: &[f64], v: &mut [f64]) {
        let t = self.theta;
        let mut s_prev = 1.0; // S_0 = 1 (empty sum - 0 + 1)
        for k in 0..self.dim() {
            let u = clamp01(self.marginals[k].cdf(x[k]));
            let s = s_prev + u.powf(-t) - 1.0;
            v[k] = if k == 0 {
                u
            } else if s <= 0.0 {
                // theta < 0, below the support's boundary: C(v | u) = 0.
                0.0
            } else {
                (s / s_prev).powf(-1.0 / t - k as f64)
            };
            s_prev = s;
        }
    }
    fn unit_to_x(&self, v: &[f64], x: &mut [f64]) {
        let t = self.theta;
        let mut s_prev = 1.0;
        for k in 0..self.dim() {
            let vk = clamp01(v[k]);
            let u = if k == 0 {
                vk
            } else {
                let e = -1.0 / (1.0 / t + k as f64);
                (s_prev * (vk.powf(e) - 1.0) + 1.0).powf(-1.0 / t)
            };
            s_prev += clamp01(u).powf(-t) - 1.0;
            x[k] = finite_quantile(self.marginals[k].as_ref(), u);
        }
    }
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        bounds(&self.marginals)
    }
}

/// Gumbel copula of two variables.
#[derive(Debug, Clone)]
pub struct GumbelCopula {
    marginals: Vec<Arc<dyn Marginal>>,
    theta: f64,
}

impl GumbelCopula {
    /// # Errors
    /// If `theta < 1` or there are not exactly two marginals.
    pub fn new(marginals: Vec<Arc<dyn Marginal>>, theta: f64) -> Result<Self> {
        let what = "gumbel copula";
        check_marginals(what, &marginals, Some(2))?;
        if !(theta >= 1.0 && theta.is_finite()) {
            return Err(invalid(what, "theta", ">= 1", theta));
        }
        Ok(Self { marginals, theta })
    }
    /// `C(u, v)`.
    pub fn copula_cdf(&self, u: &[f64]) -> f64 {
        let (x, y) = (-clamp01(u[0]).ln(), -clamp01(u[1]).ln());
        (-(x.powf(self.theta) + y.powf(self.theta)).powf(1.0 / self.theta)).exp()
    }
    fn density(&self, u: f64, v: f64) -> f64 {
        let t = self.theta;
        let (x, y) = (-u.ln(), -v.ln());
        let a = x.powf(t) + y.powf(t);
        let m = a.powf(1.0 / t);
        ((-m).exp() * (x * y).powf(t - 1.0) * a.powf(1.0 / t - 2.0) * (m + t - 1.0)) / (u * v)
    }
    /// `C(v | u) = dC/du`.
    fn h(&self, u: f64, v: f64) -> f64 {
        let t = self.theta;
        let (x, y) = (-u.ln(), -v.ln());
        let a = x.powf(t) + y.powf(t);
        (-a.powf(1.0 / t)).exp() * a.powf(1.0 / t - 1.0) * x.powf(t - 1.0) / u
    }
}

impl JointLaw for GumbelCopula {
    fn dim(&self) -> usize {
        2
    }
    fn pdf(&self, x: &[f64]) -> f64 {
        let (f0, f1) = (self.marginals[0].pdf(x[0]), self.marginals[1].pdf(x[1]));
        if !(f0 > 0.0 && f1 > 0.0) {
            return 0.0;
        }
        let u = clamp01(self.marginals[0].cdf(x[0]));
        let v = clamp01(self.marginals[1].cdf(x[1]));
        self.density(u, v) * f0 * f1
    }
    fn x_to_unit(&self, x: &[f64], w: &mut [f64]) {
        let u = clamp01(self.marginals[0].cdf(x[0]));
        let v = clamp01(self.marginals[1].cdf(x[1]));
        w[0] = u;
        w[1] = self.h(u, v).clamp(0.0, 1.0);
    }
    fn unit_to_x(&self, w: &[f64], x: &mut [f64]) {
        let u = clamp01(w[0]);
        let p = w[1].clamp(0.0, 1.0);
        let v = safeguarded_newton(
            p,
            0.0,
            1.0,
            0.5,
            |v| self.h(u, clamp01(v)),
            |v| self.density(u, clamp01(v)),
        );
        x[0] = finite_quantile(self.marginals[0].as_ref(), u);
        x[1] = finite_quantile(self.marginals[1].as_ref(), v);
    }
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        bounds(&self.marginals)
    }
}

/// Frank copula of two variables.
#[derive(Debug, Clone)]
pub struct FrankCopula {
    marginals: Vec<Arc<dyn Marginal>>,
    theta: f64,
}

impl FrankCopula {
    /// # Errors
    /// If `theta` is 0 or not finite, or there are not exactly two marginals.
    pub fn new(marginals: Vec<Arc<dyn Marginal>>, theta: f64) -> Result<Self> {
        let what = "frank copula";
        check_marginals(what, &marginals, Some(2))?;
        if !(theta.is_finite() && theta != 0.0) {
            return Err(invalid(what, "theta", "finite and != 0", theta));
        }
        Ok(Self { marginals, theta })
    }
    /// `C(u, v)`.
    pub fn copula_cdf(&self, u: &[f64]) -> f64 {
        let t = self.theta;
        let num = (-t * u[0]).exp_m1() * (-t * u[1]).exp_m1();
        -(num / (-t).exp_m1()).ln_1p() / t
    }
    fn density(&self, u: f64, v: f64) -> f64 {
        let t = self.theta;
        let e = -(-t).exp_m1(); // 1 - e^-theta
        let den = e - (-t * u).exp_m1() * (-t * v).exp_m1();
        t * e * (-t * (u + v)).exp() / (den * den)
    }
}

impl JointLaw for FrankCopula {
    fn dim(&self) -> usize {
        2
    }
    fn pdf(&self, x: &[f64]) -> f64 {
        let (f0, f1) = (self.marginals[0].pdf(x[0]), self.marginals[1].pdf(x[1]));
        if !(f0 > 0.0 && f1 > 0.0) {
            return 0.0;
        }
        let u = self.marginals[0].cdf(x[0]).clamp(0.0, 1.0);
        let v = self.marginals[1].cdf(x[1]).clamp(0.0, 1.0);
        self.density(u, v) * f0 * f1
    }
    fn x_to_unit(&self, x: &[f64], w: &mut [f64]) {
        let t = self.theta;
        let u = self.marginals[0].cdf(x[0]).clamp(0.0, 1.0);
        let v = self.marginals[1].cdf(x[1]).clamp(0.0, 1.0);
        let (a, b) = ((-t * u).exp_m1(), (-t * v).exp_m1());
        w[0] = u;
        w[1] = ((a + 1.0) * b / ((-t).exp_m1() + a * b)).clamp(0.0, 1.0);
    }
    fn unit_to_x(&self, w: &[f64], x: &mut [f64]) {
        let t = self.theta;
        let (u, p) = (w[0].clamp(0.0, 1.0), w[1].clamp(0.0, 1.0));
        let eu = (-t * u).exp();
        let v = -(p * (-t).exp_m1() / (p + (1.0 - p) * eu)).ln_1p() / t;
        x[0] = finite_quantile(self.marginals[0].as_ref(), u);
        x[1] = finite_quantile(self.marginals[1].as_ref(), v);
    }
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        bounds(&self.marginals)
    }
}
