//! Joint laws of random vectors and their isoprobabilistic maps.
//!
//! Every joint law implements [`JointLaw`], whose central pair is the map `T` to independent
//! uniform variables on the unit cube and its inverse:
//!
//! * [`Independent`]: `u_i = F_i(x_i)`; `f(x) = prod_i f_i(x_i)`.
//! * [`GaussianCopula`] (Nataf): `z_i = Phi^-1(F_i(x_i))`, `z ~ N(0, R)`, `y = L^-1 z` with
//!   `R = L L^T`, `u = Phi(y)`; density
//!   `f(x) = |R|^-1/2 exp(-z^T (R^-1 - I) z / 2) prod_i f_i(x_i)`.
//!   [`JointLaw::x_to_standard_normal`] gives `y`, the independent standard normal variables.
//! * [`BoxDensity`]: a user density on a box (a closure or a tabulated grid), normalised
//!   numerically. Its isoprobabilistic map is the Rosenblatt transform
//!   `u_1 = F(x_1)`, `u_2 = F(x_2 | x_1)`, ... of a piecewise-constant approximation of the density
//!   on a regular grid of `n^d` cells (exact for that approximation: conditional cdfs are piecewise
//!   linear). `pdf` returns the normalised user density itself.
//! * [`ProductJoint`]: mutually independent blocks of variables, each with its own joint law
//!   (a study's copula of its parameters beside the independent KL variables of its fields).

use crate::error::{Result, UqError, check_len, invalid};
use crate::law::Marginal;
use crate::quadrature::QuadratureRule;
use crate::rng::open01;
use crate::special::{norm_cdf, norm_quantile};
use rand::RngCore;
use std::sync::Arc;

mod product;
pub use product::ProductJoint;

/// A probability law on `R^d` with an isoprobabilistic map to the unit cube.
pub trait JointLaw: Send + Sync + std::fmt::Debug {
    /// Number of variables.
    fn dim(&self) -> usize;
    /// Joint density at `x`.
    fn pdf(&self, x: &[f64]) -> f64;
    /// Map `x` to independent `U(0, 1)` variables `u`.
    fn x_to_unit(&self, x: &[f64], u: &mut [f64]);
    /// Inverse map: `u` in the unit cube to `x`.
    fn unit_to_x(&self, u: &[f64], x: &mut [f64]);
    /// Map `x` to independent standard normal variables `y` (`y_i = Phi^-1(u_i)`); for the
    /// Gaussian copula this is the Nataf transform.
    fn x_to_standard_normal(&self, x: &[f64], y: &mut [f64]) {
        self.x_to_unit(x, y);
        for v in y.iter_mut() {
            *v = norm_quantile(*v);
        }
    }
    /// Inverse of [`JointLaw::x_to_standard_normal`]. By default `u_i = Phi(y_i)` through
    /// [`JointLaw::unit_to_x`], with `y_i` at most [`crate::law::Z_TAIL`] so that `u_i < 1`
    /// (beyond it `Phi` rounds to 1 and a law unbounded above would give an infinite `x`).
    fn standard_normal_to_x(&self, y: &[f64], x: &mut [f64]) {
        let u: Vec<f64> = y
            .iter()
            .map(|&v| norm_cdf(v.min(crate::law::Z_TAIL)))
            .collect();
        self.unit_to_x(&u, x);
    }
    /// Smallest box containing the support (bounds may be infinite).
    fn bounds(&self) -> (Vec<f64>, Vec<f64>);
    /// `true` if the variables are independent.
    fn is_independent(&self) -> bool {
        false
    }
    /// One draw into `x` (`u` uniform on the cube, then [`JointLaw::unit_to_x`]).
    fn sample(&self, rng: &mut dyn RngCore, x: &mut [f64]) {
        let mut u = [0.0; 16];
        let mut heap;
        let u: &mut [f64] = if self.dim() <= 16 {
            &mut u[..self.dim()]
        } else {
            heap = vec![0.0; self.dim()];
            &mut heap
        };
        for v in u.iter_mut() {
            *v = open01(rng);
        }
        self.unit_to_x(u, x);
    }
    /// Probability of the box `[lo, hi]` (finite bounds): by default a 6-point tensor
    /// Gauss-Legendre rule on the density.
    fn box_probability(&self, lo: &[f64], hi: &[f64]) -> f64 {
        match QuadratureRule::gauss_legendre_box(lo, hi, 6) {
            Ok(r) => r.integrate(|x| self.pdf(x)),
            Err(_) => f64::NAN,
        }
    }
}

/// Independent marginals.
#[derive(Debug, Clone)]
pub struct Independent {
    marginals: Vec<Arc<dyn Marginal>>,
}

impl Independent {
    /// # Errors
    /// If `marginals` is empty.
    pub fn new(marginals: Vec<Arc<dyn Marginal>>) -> Result<Self> {
        if marginals.is_empty() {
            return Err(invalid(
                "independent joint law",
                "marginals",
                "non-empty",
                0.0,
            ));
        }
        Ok(Self { marginals })
    }
    /// The marginals.
    pub fn marginals(&self) -> &[Arc<dyn Marginal>] {
        &self.marginals
    }
}

impl JointLaw for Independent {
    fn dim(&self) -> usize {
        self.marginals.len()
    }
    fn pdf(&self, x: &[f64]) -> f64 {
        self.marginals
            .iter()
            .zip(x)
            .map(|(m, &v)| m.pdf(v))
            .product()
    }
    fn x_to_unit(&self, x: &[f64], u: &mut [f64]) {
        for ((m, &v), o) in self.marginals.iter().zip(x).zip(u) {
            *o = m.cdf(v);
        }
    }
    fn unit_to_x(&self, u: &[f64], x: &mut [f64]) {
        for ((m, &v), o) in self.marginals.iter().zip(u).zip(x) {
            *o = m.quantile(v);
        }
    }
    fn standard_normal_to_x(&self, y: &[f64], x: &mut [f64]) {
        for ((m, &v), o) in self.marginals.iter().zip(y).zip(x) {
            *o = m.quantile_of_normal(v);
        }
    }
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        self.marginals.iter().map(|m| m.support()).unzip()
    }
    fn is_independent(&self) -> bool {
        true
    }
    fn box_probability(&self, lo: &[f64], hi: &[f64]) -> f64 {
        self.marginals
            .iter()
            .zip(lo.iter().zip(hi))
            .map(|(m, (&a, &b))| m.interval_probability(a, b))
            .product()
    }
}

/// Gaussian copula (Nataf transform) with correlation matrix `R` of the normal scores.
#[derive(Debug, Clone)]
pub struct GaussianCopula {
    marginals: Vec<Arc<dyn Marginal>>,
    corr: Vec<f64>,
    chol: Vec<f64>,
    /// `R^-1 - I`, row-major.
    rinv_minus_i: Vec<f64>,
    inv_sqrt_det: f64,
}

impl GaussianCopula {
    /// `corr`: row-major `d x d` correlation matrix of the normal scores `z`.
    ///
    /// # Errors
    /// If sizes disagree, `corr` is not symmetric with unit diagonal and entries in `[-1, 1]`,
    /// or not positive definite.
    pub fn new(marginals: Vec<Arc<dyn Marginal>>, corr: Vec<f64>) -> Result<Self> {
        let what = "gaussian copula";
        let d = marginals.len();
        if d == 0 {
            return Err(invalid(what, "marginals", "non-empty", 0.0));
        }
        check_len(what, "correlation", d * d, corr.len())?;
        for i in 0..d {
            if (corr[i * d + i] - 1.0).abs() > 1e-12 {
                return Err(invalid(what, "correlation diagonal", "1", corr[i * d + i]));
            }
            for j in 0..i {
                let (a, b) = (corr[i * d + j], corr[j * d + i]);
                if (a - b).abs() > 1e-12 {
                    return Err(UqError::Invalid {
                        what,
                        message: format!("correlation is not symmetric at ({i}, {j}): {a} vs {b}"),
                    });
                }
                if !(-1.0..=1.0).contains(&a) {
                    return Err(invalid(what, "correlation entry", "in [-1, 1]", a));
                }
            }
        }
        let chol = crate::linalg::cholesky(what, &corr, d).map_err(|_| UqError::Invalid {
            what,
            message: "correlation matrix is not symmetric positive definite".into(),
        })?;
        // R^-1 = L^-T L^-1 by solving column by column.
        let mut rinv = vec![0.0; d * d];
        for c in 0..d {
            let mut y = vec![0.0; d];
            for i in 0..d {
                let mut s = if i == c { 1.0 } else { 0.0 };
                for k in 0..i {
                    s -= chol[i * d + k] * y[k];
                }
                y[i] = s / chol[i * d + i];
            }
            let mut x = vec![0.0; d];
            for i in (0..d).rev() {
                let mut s = y[i];
                for k in (i + 1)..d {
                    s -= chol[k * d + i] * x[k];
                }
                x[i] = s / chol[i * d + i];
            }
            for i in 0..d {
                rinv[i * d + c] = x[i] - if i == c { 1.0 } else { 0.0 };
            }
        }
        let det: f64 = (0..d).map(|i| chol[i * d + i]).product::<f64>().powi(2);
        Ok(Self {
            marginals,
            corr,
            chol,
            rinv_minus_i: rinv,
            inv_sqrt_det: 1.0 / det.sqrt(),
        })
    }

    /// The marginals.
    pub fn marginals(&self) -> &[Arc<dyn Marginal>] {
        &self.marginals
    }
    /// The correlation matrix of the normal scores (row-major).
    pub fn correlation(&self) -> &[f64] {
        &self.corr
    }
}

impl JointLaw for GaussianCopula {
    fn dim(&self) -> usize {
        self.marginals.len()
    }
    /// Nataf map: `x` to independent standard normal variables `y = L^-1 z`.
    fn x_to_standard_normal(&self, x: &[f64], y: &mut [f64]) {
        let d = self.dim();
        for i in 0..d {
            let z = norm_quantile(self.marginals[i].cdf(x[i]));
            let mut s = z;
            for k in 0..i {
                s -= self.chol[i * d + k] * y[k];
            }
            y[i] = s / self.chol[i * d + i];
        }
    }

    /// Inverse Nataf map: independent standard normal `y` to `x`.
    fn standard_normal_to_x(&self, y: &[f64], x: &mut [f64]) {
        let d = self.dim();
        for i in 0..d {
            let z: f64 = (0..=i).map(|k| self.chol[i * d + k] * y[k]).sum();
            x[i] = self.marginals[i].quantile_of_normal(z);
        }
    }

    fn pdf(&self, x: &[f64]) -> f64 {
        let d = self.dim();
        let mut prod = 1.0;
        let mut z = vec![0.0; d];
        for i in 0..d {
            let f = self.marginals[i].pdf(x[i]);
            if f == 0.0 {
                return 0.0;
            }
            prod *= f;
            z[i] = norm_quantile(self.marginals[i].cdf(x[i]));
            if !z[i].is_finite() {
                return 0.0; // on the boundary of the support
            }
        }
        let mut q = 0.0;
        for i in 0..d {
            for j in 0..d {
                q += z[i] * self.rinv_minus_i[i * d + j] * z[j];
            }
        }
        self.inv_sqrt_det * (-0.5 * q).exp() * prod
    }
    fn x_to_unit(&self, x: &[f64], u: &mut [f64]) {
        self.x_to_standard_normal(x, u);
        for v in u.iter_mut() {
            *v = norm_cdf(*v);
        }
    }
    fn unit_to_x(&self, u: &[f64], x: &mut [f64]) {
        let mut buf = [0.0; 16];
        let mut heap;
        let y: &mut [f64] = if u.len() <= 16 {
            &mut buf[..u.len()]
        } else {
            heap = vec![0.0; u.len()];
            &mut heap
        };
        for (yi, &p) in y.iter_mut().zip(u) {
            *yi = norm_quantile(p);
        }
        self.standard_normal_to_x(y, x);
    }
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        self.marginals.iter().map(|m| m.support()).unzip()
    }
}

/// A boxed user density function.
type DensityFn = Box<dyn Fn(&[f64]) -> f64 + Send + Sync>;

/// A user density on a box `[lo, hi]`, given as a closure or as values on a regular grid.
///
/// The isoprobabilistic map (Rosenblatt) and the sampler use a piecewise-constant approximation
/// on `n^d` cells (cell-centre values); `pdf` is the normalised user density.
pub struct BoxDensity {
    lo: Vec<f64>,
    hi: Vec<f64>,
    n: usize,
    density: DensityFn,
    norm: f64,
    /// `partial[k]` has `n^(k+1)` entries: mass of the cells `(i_1..i_{k+1})` summed over the
    /// remaining indices (row-major in `(i_1, .., i_{k+1})`).
    partial: Vec<Vec<f64>>,
}

impl std::fmt::Debug for BoxDensity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BoxDensity")
            .field("lo", &self.lo)
            .field("hi", &self.hi)
            .field("n", &self.n)
            .field("norm", &self.norm)
            .finish()
    }
}

impl BoxDensity {
    /// Density given by a closure (need not be normalised); `n` cells per direction for the
    /// Rosenblatt map (`n^d` must not exceed `2^24`).
    ///
    /// # Errors
    /// If the box is empty, `n == 0`, the grid is too large, or the density has no mass or takes
    /// a negative or non-finite value at a cell centre.
    pub fn from_fn(
        lo: Vec<f64>,
        hi: Vec<f64>,
        n: usize,
        density: impl Fn(&[f64]) -> f64 + Send + Sync + 'static,
    ) -> Result<Self> {
        let what = "box density";
        check_len(what, "hi", lo.len(), hi.len())?;
        let d = lo.len();
        if d == 0 {
            return Err(invalid(what, "dimension", ">= 1", 0.0));
        }
        for j in 0..d {
            if !lo[j].is_finite() {
                return Err(invalid(what, "lo", "finite", lo[j]));
            }
            if !(hi[j].is_finite() && hi[j] > lo[j]) {
                return Err(invalid(what, "hi", "finite and > lo", hi[j]));
            }
        }
        if n == 0 || (n as f64).powi(d as i32) > (1u64 << 24) as f64 {
            return Err(invalid(
                what,
                "cells per direction",
                ">= 1 with n^d <= 2^24",
                n as f64,
            ));
        }
        let total = n.pow(d as u32);
        let mut cell = vec![0.0; total];
        let vol: f64 = (0..d).map(|j| (hi[j] - lo[j]) / n as f64).product();
        let mut x = vec![0.0; d];
        for (c, v) in cell.iter_mut().enumerate() {
            let mut r = c;
            for j in (0..d).rev() {
                let i = r % n;
                r /= n;
                x[j] = lo[j] + (i as f64 + 0.5) * (hi[j] - lo[j]) / n as f64;
            }
            let f = density(&x);
            if !(f.is_finite() && f >= 0.0) {
                return Err(invalid(what, "density value", "finite and >= 0", f));
            }
            *v = f * vol;
        }
        let mass: f64 = cell.iter().sum();
        if !(mass > 0.0) {
            return Err(UqError::Invalid {
                what,
                message: "density has zero mass on the box".into(),
            });
        }
        let mut partial = vec![Vec::new(); d];
        partial[d - 1] = cell;
        for k in (0..d - 1).rev() {
            let next = &partial[k + 1];
            partial[k] = next.chunks_exact(n).map(|c| c.iter().sum()).collect();
        }
        // Normalisation of the user density: composite Gauss-Legendre for d <= 3, the midpoint
        // (cell-centre) mass above.
        let norm = if d <= 3 {
            // Composite rule: 4 Gauss points per direction on a partition of the box.
            let parts = (64 / d).max(4);
            let mut s = 0.0;
            let mut idx = vec![0usize; d];
            loop {
                let clo: Vec<f64> = (0..d)
                    .map(|j| lo[j] + idx[j] as f64 * (hi[j] - lo[j]) / parts as f64)
                    .collect();
                let chi: Vec<f64> = (0..d)
                    .map(|j| lo[j] + (idx[j] + 1) as f64 * (hi[j] - lo[j]) / parts as f64)
                    .collect();
                s += QuadratureRule::gauss_legendre_box(&clo, &chi, 4)?.integrate(&density);
                let mut j = 0;
                while j < d {
                    idx[j] += 1;
                    if idx[j] < parts {
                        break;
                    }
                    idx[j] = 0;
                    j += 1;
                }
                if j == d {
                    break;
                }
            }
            s
        } else {
            mass
        };
        Ok(Self {
            lo,
            hi,
            n,
            density: Box::new(density),
            norm,
            partial,
        })
    }

    /// Density tabulated at the nodes of a regular grid with `m` nodes per direction on the box
    /// (row-major, last index fastest), interpolated multilinearly.
    ///
    /// # Errors
    /// As [`BoxDensity::from_fn`], or if `values.len() != m^d` or `m < 2`.
    pub fn from_grid(lo: Vec<f64>, hi: Vec<f64>, m: usize, values: Vec<f64>) -> Result<Self> {
        let d = lo.len();
        if m < 2 {
            return Err(invalid(
                "box density",
                "grid nodes per direction",
                ">= 2",
                m as f64,
            ));
        }
        check_len("box density", "values", m.pow(d as u32), values.len())?;
        let (l2, h2) = (lo.clone(), hi.clone());
        let interp = move |x: &[f64]| {
            let mut idx = vec![0usize; d];
            let mut t = vec![0.0; d];
            for j in 0..d {
                let s =
                    ((x[j] - l2[j]) / (h2[j] - l2[j]) * (m - 1) as f64).clamp(0.0, (m - 1) as f64);
                let i = (s.floor() as usize).min(m - 2);
                idx[j] = i;
                t[j] = s - i as f64;
            }
            let mut v = 0.0;
            for corner in 0..(1usize << d) {
                let mut w = 1.0;
                let mut flat = 0;
                for j in 0..d {
                    let bit = (corner >> j) & 1;
                    w *= if bit == 1 { t[j] } else { 1.0 - t[j] };
                    flat = flat * m + idx[j] + bit;
                }
                v += w * values[flat];
            }
            v
        };
        Self::from_fn(lo, hi, 4 * (m - 1), interp)
    }

    fn cell_width(&self, j: usize) -> f64 {
        (self.hi[j] - self.lo[j]) / self.n as f64
    }
}

impl JointLaw for BoxDensity {
    fn dim(&self) -> usize {
        self.lo.len()
    }
    fn pdf(&self, x: &[f64]) -> f64 {
        for j in 0..self.dim() {
            if x[j] < self.lo[j] || x[j] > self.hi[j] {
                return 0.0;
            }
        }
        (self.density)(x) / self.norm
    }
    fn x_to_unit(&self, x: &[f64], u: &mut [f64]) {
        let n = self.n;
        let mut prefix = 0usize;
        for j in 0..self.dim() {
            let s = ((x[j] - self.lo[j]) / self.cell_width(j)).clamp(0.0, n as f64);
            let i = (s.floor() as usize).min(n - 1);
            let row = &self.partial[j][prefix * n..(prefix + 1) * n];
            let tot: f64 = row.iter().sum();
            if tot <= 0.0 {
                u[j] = s / n as f64;
            } else {
                let below: f64 = row[..i].iter().sum();
                u[j] = ((below + (s - i as f64) * row[i]) / tot).clamp(0.0, 1.0);
            }
            prefix = prefix * n + i;
        }
    }
    fn unit_to_x(&self, u: &[f64], x: &mut [f64]) {
        let n = self.n;
        let mut prefix = 0usize;
        for j in 0..self.dim() {
            let row = &self.partial[j][prefix * n..(prefix + 1) * n];
            let tot: f64 = row.iter().sum();
            let target = u[j].clamp(0.0, 1.0) * tot;
            let mut acc = 0.0;
            let mut i = 0;
            while i + 1 < n && acc + row[i] < target {
                acc += row[i];
                i += 1;
            }
            while row[i] <= 0.0 && i + 1 < n {
                i += 1;
            }
            let frac = if row[i] > 0.0 {
                ((target - acc) / row[i]).clamp(0.0, 1.0)
            } else {
                0.5
            };
            x[j] = self.lo[j] + (i as f64 + frac) * self.cell_width(j);
            prefix = prefix * n + i;
        }
    }
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        (self.lo.clone(), self.hi.clone())
    }
}
