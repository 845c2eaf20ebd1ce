//! Orthonormal polynomials of one variable, defined by their three-term recurrence.
//!
//! With the monic recurrence coefficients `(a_k, b_k)` of a probability measure (`b_0 = 1`),
//! the orthonormal polynomials in the standard variable `t` are
//!
//! ```text
//! p_0 = 1,  sqrt(b_1) p_1 = (t - a_0) p_0,
//! sqrt(b_{k+1}) p_{k+1} = (t - a_k) p_k - sqrt(b_k) p_{k-1},      E[p_i p_j] = delta_ij.
//! ```
//!
//! Families (Gautschi, *Orthogonal Polynomials*, Table 1.1):
//! * Hermite (`N(0,1)`): `a_k = 0`, `b_k = k`.
//! * Legendre (`U(-1,1)`): `a_k = 0`, `b_k = k^2 / (4k^2 - 1)`.
//! * Jacobi (weight `(1-t)^p (1+t)^q` on `[-1,1]`, the beta law with `p = beta - 1`,
//!   `q = alpha - 1`): `a_k = (q^2 - p^2) / ((2k+p+q)(2k+p+q+2))`,
//!   `b_k = 4k(k+p)(k+q)(k+p+q) / ((2k+p+q)^2 (2k+p+q+1)(2k+p+q-1))`.
//! * Laguerre (weight `t^s e^-t`, the gamma law with `s = k - 1`): `a_k = 2k + s + 1`,
//!   `b_k = k (k + s)`.
//! * Any other marginal: the Stieltjes procedure on a discretisation of the law by composite
//!   Gauss-Legendre quadrature (panels of equal probability, geometric tail panels) of its pdf, in
//!   the standardised variable `t = (x - mean)/std`.
//!
//! Gauss rules come from the same coefficients by Golub-Welsch: the nodes are the eigenvalues of
//! the Jacobi matrix `J = tridiag(sqrt(b_k), a_k, sqrt(b_k))`, the weights the squared first
//! components of its normalised eigenvectors. The nodes of the `n`-point rule are the roots of
//! `p_n`: the thesis's PC collocation points.

use crate::error::{Result, UqError};
use crate::law::{Marginal, PolyFamily};
use crate::linalg::tridiagonal_eigen;

/// Which family generated the recurrence.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum PolyKind {
    /// Probabilists' Hermite.
    Hermite,
    /// Legendre.
    Legendre,
    /// Jacobi.
    Jacobi,
    /// Generalised Laguerre.
    Laguerre,
    /// Generated numerically by the Stieltjes procedure.
    Stieltjes,
}

/// Orthonormal polynomials of a marginal law up to a maximal degree.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct OrthoPoly {
    kind: PolyKind,
    /// `a_0 .. a_{N-1}`.
    a: Vec<f64>,
    /// `b_0 .. b_{N-1}`, `b_0 = 1`.
    b: Vec<f64>,
    /// `t = (x - shift) / scale`.
    shift: f64,
    scale: f64,
}

impl OrthoPoly {
    /// Orthonormal polynomials of `law` up to degree `max_degree` (the recurrence is kept up to
    /// `max_degree + 1`, so `gauss(max_degree + 1)` is available).
    ///
    /// # Errors
    /// If the numerical generation fails (law with too few support points).
    pub fn for_marginal(law: &dyn Marginal, max_degree: usize) -> Result<Self> {
        let n = max_degree + 2;
        Ok(match law.poly_family() {
            Some(PolyFamily::Hermite { mean, std }) => Self::hermite(n, mean, std),
            Some(PolyFamily::Legendre { a, b }) => Self::legendre(n, a, b),
            Some(PolyFamily::Jacobi { alpha, beta, a, b }) => Self::jacobi(n, alpha, beta, a, b),
            Some(PolyFamily::Laguerre { shape, scale, loc }) => {
                Self::laguerre(n, shape, scale, loc)
            }
            None => Self::stieltjes(law, n)?,
        })
    }

    /// Hermite polynomials of `N(mean, std^2)` with `n` recurrence terms.
    pub fn hermite(n: usize, mean: f64, std: f64) -> Self {
        Self {
            kind: PolyKind::Hermite,
            a: vec![0.0; n],
            b: (0..n)
                .map(|k| if k == 0 { 1.0 } else { k as f64 })
                .collect(),
            shift: mean,
            scale: std,
        }
    }

    /// Legendre polynomials of `U(a, b)`.
    pub fn legendre(n: usize, a: f64, b: f64) -> Self {
        Self {
            kind: PolyKind::Legendre,
            a: vec![0.0; n],
            b: (0..n)
                .map(|k| {
                    let k = k as f64;
                    if k == 0.0 {
                        1.0
                    } else {
                        k * k / (4.0 * k * k - 1.0)
                    }
                })
                .collect(),
            shift: 0.5 * (a + b),
            scale: 0.5 * (b - a),
        }
    }

    /// Jacobi polynomials of the beta law with shapes `alpha`, `beta` on `[a, b]`.
    pub fn jacobi(n: usize, alpha: f64, beta: f64, a: f64, b: f64) -> Self {
        let p = beta - 1.0;
        let q = alpha - 1.0;
        let mut ra = vec![0.0; n];
        let mut rb = vec![1.0; n];
        for k in 0..n {
            let kf = k as f64;
            let s = 2.0 * kf + p + q;
            ra[k] = if k == 0 {
                (q - p) / (p + q + 2.0)
            } else {
                (q * q - p * p) / (s * (s + 2.0))
            };
            if k == 1 {
                rb[k] = 4.0 * (1.0 + p) * (1.0 + q) / ((2.0 + p + q).powi(2) * (3.0 + p + q));
            } else if k >= 2 {
                rb[k] =
                    4.0 * kf * (kf + p) * (kf + q) * (kf + p + q) / (s * s * (s + 1.0) * (s - 1.0));
            }
        }
        Self {
            kind: PolyKind::Jacobi,
            a: ra,
            b: rb,
            shift: 0.5 * (a + b),
            scale: 0.5 * (b - a),
        }
    }

    /// Laguerre polynomials of the gamma law (shape, scale, location).
    pub fn laguerre(n: usize, shape: f64, scale: f64, loc: f64) -> Self {
        let s = shape - 1.0;
        Self {
            kind: PolyKind::Laguerre,
            a: (0..n).map(|k| 2.0 * k as f64 + s + 1.0).collect(),
            b: (0..n)
                .map(|k| {
                    if k == 0 {
                        1.0
                    } else {
                        k as f64 * (k as f64 + s)
                    }
                })
                .collect(),
            shift: loc,
            scale,
        }
    }

    /// Numerically generated polynomials (Stieltjes procedure) with `n` recurrence terms.
    ///
    /// # Errors
    /// If the discretised measure has fewer than `n` distinct points of positive mass.
    pub fn stieltjes(law: &dyn Marginal, n: usize) -> Result<Self> {
        let mean = law.mean();
        let std = law.std();
        let (t, w) = discretise(law, mean, std);
        let m = t.len();
        let mut a = vec![0.0; n];
        let mut b = vec![0.0; n];
        let mut p_prev = vec![0.0; m];
        let mut p = vec![1.0; m];
        let mut norm_prev = 1.0;
        for k in 0..n {
            let norm: f64 = p.iter().zip(&w).map(|(v, w)| w * v * v).sum();
            if !(norm > 1e-300) {
                return Err(UqError::Invalid {
                    what: "orthogonal polynomials",
                    message: format!(
                        "Stieltjes procedure for the {} law breaks down at degree {k}",
                        law.name()
                    ),
                });
            }
            let tn: f64 = p
                .iter()
                .zip(&w)
                .zip(&t)
                .map(|((v, w), t)| w * t * v * v)
                .sum();
            a[k] = tn / norm;
            b[k] = if k == 0 { 1.0 } else { norm / norm_prev };
            // monic p_{k+1} = (t - a_k) p_k - b_k p_{k-1}
            for j in 0..m {
                let next = (t[j] - a[k]) * p[j] - if k == 0 { 0.0 } else { b[k] * p_prev[j] };
                p_prev[j] = p[j];
                p[j] = next;
            }
            norm_prev = norm;
            // Rescale to avoid overflow: the ratios stay exact if both are scaled alike.
            let s = norm.sqrt();
            for j in 0..m {
                p[j] /= s;
                p_prev[j] /= s;
            }
            norm_prev /= norm;
        }
        Ok(Self {
            kind: PolyKind::Stieltjes,
            a,
            b,
            shift: mean,
            scale: std,
        })
    }

    /// Check a recurrence read from a file: equal lengths (at least 1), finite `a_k`, `b_k > 0`,
    /// finite shift and positive scale.
    pub(crate) fn check(&self) -> Result<()> {
        let bad = |m: String| UqError::Invalid {
            what: "orthogonal polynomials",
            message: m,
        };
        if self.a.is_empty() || self.a.len() != self.b.len() {
            return Err(bad(format!(
                "recurrence lengths {} and {}",
                self.a.len(),
                self.b.len()
            )));
        }
        if self.a.iter().any(|v| !v.is_finite())
            || self.b.iter().any(|v| !(*v > 0.0 && v.is_finite()))
        {
            return Err(bad(
                "recurrence coefficients must be finite with b_k > 0".into()
            ));
        }
        if !(self.shift.is_finite() && self.scale > 0.0 && self.scale.is_finite()) {
            return Err(bad(format!(
                "shift {} / scale {} invalid",
                self.shift, self.scale
            )));
        }
        Ok(())
    }

    /// Family that generated the polynomials.
    pub fn kind(&self) -> PolyKind {
        self.kind
    }

    /// Highest degree that [`OrthoPoly::eval_all`] can evaluate.
    pub fn max_degree(&self) -> usize {
        self.a.len() - 1
    }

    /// Standard variable `t = (x - shift)/scale`.
    #[inline]
    pub fn standardise(&self, x: f64) -> f64 {
        (x - self.shift) / self.scale
    }

    /// Values `p_0(x), ..., p_{out.len()-1}(x)` of the orthonormal polynomials.
    ///
    /// # Panics
    /// If `out.len() > max_degree() + 1`.
    #[inline]
    pub fn eval_all(&self, x: f64, out: &mut [f64]) {
        assert!(
            out.len() <= self.a.len(),
            "degree above the recurrence length"
        );
        let t = self.standardise(x);
        if out.is_empty() {
            return;
        }
        out[0] = 1.0;
        if out.len() > 1 {
            out[1] = (t - self.a[0]) / self.b[1].sqrt();
        }
        for k in 1..out.len().saturating_sub(1) {
            out[k + 1] =
                ((t - self.a[k]) * out[k] - self.b[k].sqrt() * out[k - 1]) / self.b[k + 1].sqrt();
        }
    }

    /// `n`-point Gauss rule of the law: nodes in the physical variable, weights summing to 1.
    /// The nodes are the roots of `p_n`.
    ///
    /// # Panics
    /// If `n == 0` or `n > max_degree() + 1`.
    pub fn gauss(&self, n: usize) -> (Vec<f64>, Vec<f64>) {
        assert!(n >= 1 && n <= self.a.len(), "Gauss rule size out of range");
        let d = self.a[..n].to_vec();
        let e: Vec<f64> = (0..n)
            .map(|k| if k == 0 { 0.0 } else { self.b[k].sqrt() })
            .collect();
        let (nodes, z) = tridiagonal_eigen(d, e);
        let x = nodes.iter().map(|t| self.shift + self.scale * t).collect();
        let w = z.iter().map(|v| v * v).collect();
        (x, w)
    }
}

/// Discretise a law in its standardised variable: nodes `t` and probabilities `w` (sum 1).
fn discretise(law: &dyn Marginal, mean: f64, std: f64) -> (Vec<f64>, Vec<f64>) {
    // Panel boundaries: 200 equal-probability panels, geometric tails down to 1e-15 (the
    // smallest probability whose complement is representable), then for an unbounded side 8
    // extension panels of the width of the last tail panel (the high moments x^2p f(x) of an
    // unbounded law need the far tails).
    let (lo, hi) = law.support();
    let tails: Vec<f64> = [15, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3]
        .iter()
        .map(|&e| 10f64.powi(-e))
        .collect();
    let mut u: Vec<f64> = Vec::new();
    u.extend(tails.iter().copied());
    let panels = 200;
    for i in 1..panels {
        let v = i as f64 / panels as f64;
        if v > 1e-3 && v < 1.0 - 1e-3 {
            u.push(v);
        }
    }
    u.extend(tails.iter().rev().map(|v| 1.0 - v));
    let mut xb: Vec<f64> = u.iter().map(|&p| law.quantile(p)).collect();
    if lo.is_finite() {
        xb.insert(0, lo);
    } else {
        let (x0, w) = (xb[0], xb[1] - xb[0]);
        for i in 1..=8 {
            xb.insert(0, x0 - i as f64 * w);
        }
    }
    if hi.is_finite() {
        xb.push(hi);
    } else {
        let n = xb.len();
        let (x0, w) = (xb[n - 1], xb[n - 1] - xb[n - 2]);
        for i in 1..=8 {
            xb.push(x0 + i as f64 * w);
        }
    }
    xb.retain(|v| v.is_finite());
    xb.dedup_by(|a, b| (*a - *b).abs() <= 1e-14 * (1.0 + b.abs()));
    let gl = OrthoPoly::legendre(12, -1.0, 1.0);
    let (gx, gw) = gl.gauss(12);
    let mut t = Vec::new();
    let mut w = Vec::new();
    for win in xb.windows(2) {
        let (a, b) = (win[0], win[1]);
        if !(b > a) {
            continue;
        }
        for (x, wq) in gx.iter().zip(&gw) {
            let xq = 0.5 * (a + b) + 0.5 * (b - a) * x;
            let f = law.pdf(xq);
            if f > 0.0 && f.is_finite() {
                t.push((xq - mean) / std);
                w.push(wq * (b - a) * f);
            }
        }
    }
    let total: f64 = w.iter().sum();
    for v in &mut w {
        *v /= total;
    }
    (t, w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::{Normal, TruncatedNormal, Uniform};

    fn check_orthonormal(p: &OrthoPoly, deg: usize) {
        let (x, w) = p.gauss(deg + 1);
        let mut v = vec![0.0; deg + 1];
        let mut g = vec![0.0; (deg + 1) * (deg + 1)];
        for (xq, wq) in x.iter().zip(&w) {
            p.eval_all(*xq, &mut v);
            for i in 0..=deg {
                for j in 0..=deg {
                    g[i * (deg + 1) + j] += wq * v[i] * v[j];
                }
            }
        }
        for i in 0..=deg {
            for j in 0..=deg {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!(
                    (g[i * (deg + 1) + j] - e).abs() < 1e-10,
                    "{:?} G[{i},{j}]",
                    p.kind
                );
            }
        }
    }

    #[test]
    fn families_are_orthonormal() {
        check_orthonormal(&OrthoPoly::hermite(10, 1.0, 2.0), 8);
        check_orthonormal(&OrthoPoly::legendre(10, -3.0, 5.0), 8);
        check_orthonormal(&OrthoPoly::jacobi(10, 2.0, 3.5, 0.0, 1.0), 8);
        check_orthonormal(&OrthoPoly::jacobi(10, 0.5, 0.5, -1.0, 1.0), 8);
        check_orthonormal(&OrthoPoly::laguerre(10, 1.5, 2.0, 0.0), 8);
        let tn = TruncatedNormal::new(0.0, 1.0, -1.0, 2.0).unwrap();
        check_orthonormal(&OrthoPoly::for_marginal(&tn, 8).unwrap(), 8);
    }

    #[test]
    fn gauss_legendre_and_hermite_known_nodes() {
        let (x, w) = OrthoPoly::legendre(3, -1.0, 1.0).gauss(3);
        assert!((x[2] - 0.6f64.sqrt()).abs() < 1e-14 && x[1].abs() < 1e-14);
        assert!((w[1] - 8.0 / 18.0).abs() < 1e-14 && (w[0] - 5.0 / 18.0).abs() < 1e-14);
        let (x, w) = OrthoPoly::hermite(3, 0.0, 1.0).gauss(3);
        assert!((x[2] - 3f64.sqrt()).abs() < 1e-14 && (w[1] - 2.0 / 3.0).abs() < 1e-14);
    }

    #[test]
    fn stieltjes_reproduces_classical_recurrences() {
        // Generated polynomials of the normal and uniform laws equal Hermite/Legendre.
        let n = Normal::new(0.0, 1.0).unwrap();
        let s = OrthoPoly::stieltjes(&n, 8).unwrap();
        for k in 0..8 {
            assert!(s.a[k].abs() < 1e-9, "a_{k} = {} b_{k} = {}", s.a[k], s.b[k]);
            assert!((s.b[k] - if k == 0 { 1.0 } else { k as f64 }).abs() < 1e-8 * (k as f64 + 1.0));
        }
        let u = Uniform::new(-1.0, 1.0).unwrap();
        let s = OrthoPoly::stieltjes(&u, 8).unwrap();
        let l = OrthoPoly::legendre(8, -1.0, 1.0);
        // Standardised variable of U(-1,1) is x*sqrt(3): b scales by 3.
        for k in 1..8 {
            assert!((s.b[k] / 3.0 - l.b[k]).abs() < 1e-12);
        }
    }
}
