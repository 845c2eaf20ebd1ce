//! Fitting the usual marginals to data by maximum likelihood, with goodness-of-fit statistics.
//!
//! | family | maximum-likelihood estimate |
//! |---|---|
//! | normal | `mu = mean(x)`, `sigma^2 = mean((x - mu)^2)` |
//! | lognormal | the normal estimates of `ln x` |
//! | uniform | `[min x, max x]` |
//! | gamma (location 0) | `ln k - psi(k) = ln mean(x) - mean(ln x)` by Newton, `theta = mean(x)/k` |
//! | beta on given `[a, b]` | `psi(alpha) - psi(alpha + beta) = mean ln y`, `psi(beta) - psi(alpha + beta) = mean ln(1 - y)`, `y = (x - a)/(b - a)`, by Newton from the moment estimates |
//!
//! Each fit reports the log-likelihood, `AIC = 2p - 2 ln L`, `BIC = p ln n - 2 ln L`, the
//! Kolmogorov-Smirnov statistic `D = sup |F_n - F|` with the asymptotic p-value
//! `Q(lambda) = 2 sum_{k>=1} (-1)^(k-1) exp(-2 k^2 lambda^2)`,
//! `lambda = (sqrt n + 0.12 + 0.11/sqrt n) D` (Stephens 1970), and the Anderson-Darling statistic
//! `A^2 = -n - (1/n) sum_i (2i - 1) [ln F(x_(i)) + ln(1 - F(x_(n+1-i)))]`. With parameters
//! estimated from the same data the KS p-value is conservative (too large, Lilliefors 1967):
//! use it to reject, compare candidates with the BIC.
//!
//! `psi` (digamma) and `psi'` (trigamma): recurrence up to 12, then their asymptotic series (truncation below 3e-15).

use crate::error::{Result, UqError, invalid};
use crate::law::{Beta, Gamma, LogNormal, Marginal, Normal, Uniform};
use std::sync::Arc;

/// Families that [`fit`] knows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Family {
    /// Normal.
    Normal,
    /// Lognormal.
    LogNormal,
    /// Uniform.
    Uniform,
    /// Gamma with location 0.
    Gamma,
    /// Beta on the given bounds.
    Beta {
        /// Lower bound.
        a: f64,
        /// Upper bound.
        b: f64,
    },
}

/// A fitted law and its goodness of fit.
#[derive(Debug, Clone)]
pub struct Fitted {
    /// The family.
    pub family: Family,
    /// The law with the estimated parameters.
    pub law: Arc<dyn Marginal>,
    /// Parameter names and values.
    pub parameters: Vec<(&'static str, f64)>,
    /// Log-likelihood at the estimate.
    pub log_likelihood: f64,
    /// Akaike information criterion.
    pub aic: f64,
    /// Bayesian information criterion.
    pub bic: f64,
    /// Kolmogorov-Smirnov statistic.
    pub ks: f64,
    /// Asymptotic KS p-value (conservative with estimated parameters).
    pub ks_pvalue: f64,
    /// Anderson-Darling statistic.
    pub anderson_darling: f64,
}

/// Digamma function `psi(x) = Gamma'(x)/Gamma(x)`, `x > 0`.
pub fn digamma(mut x: f64) -> f64 {
    let mut r = 0.0;
    while x < 12.0 {
        r -= 1.0 / x;
        x += 1.0;
    }
    let f = 1.0 / (x * x);
    r + x.ln()
        - 0.5 / x
        - f * (1.0 / 12.0 - f * (1.0 / 120.0 - f * (1.0 / 252.0 - f * (1.0 / 240.0 - f / 132.0))))
}

/// Trigamma function `psi'(x)`, `x > 0`.
pub fn trigamma(mut x: f64) -> f64 {
    let mut r = 0.0;
    while x < 12.0 {
        r += 1.0 / (x * x);
        x += 1.0;
    }
    let f = 1.0 / (x * x);
    r + 1.0 / x
        + f / 2.0
        + f / x
            * (1.0 / 6.0 - f * (1.0 / 30.0 - f * (1.0 / 42.0 - f * (1.0 / 30.0 - f * 5.0 / 66.0))))
}

/// Kolmogorov-Smirnov statistic, its asymptotic p-value and the Anderson-Darling statistic of
/// the sorted data against `law`.
pub fn goodness_of_fit(sorted: &[f64], law: &dyn Marginal) -> (f64, f64, f64) {
    let n = sorted.len();
    let nf = n as f64;
    let mut d: f64 = 0.0;
    let mut ad = 0.0;
    let cdf: Vec<f64> = sorted.iter().map(|&x| law.cdf(x)).collect();
    for (i, &f) in cdf.iter().enumerate() {
        d = d
            .max(((i + 1) as f64 / nf - f).abs())
            .max((f - i as f64 / nf).abs());
        let lo = f.clamp(1e-300, 1.0);
        let hi = (1.0 - cdf[n - 1 - i]).clamp(1e-300, 1.0);
        ad += (2 * i + 1) as f64 * (lo.ln() + hi.ln());
    }
    let ad = -nf - ad / nf;
    let lambda = (nf.sqrt() + 0.12 + 0.11 / nf.sqrt()) * d;
    let p = if lambda < 0.2 {
        1.0
    } else {
        let mut s = 0.0;
        for k in 1..=100 {
            let kf = k as f64;
            let t = (-2.0 * kf * kf * lambda * lambda).exp();
            s += if k % 2 == 1 { t } else { -t };
            if t < 1e-16 {
                break;
            }
        }
        (2.0 * s).clamp(0.0, 1.0)
    };
    (d, p, ad)
}

/// Fit `family` to `data` by maximum likelihood and report its goodness of fit.
///
/// # Errors
/// If fewer than 3 values, a value is not finite or outside the family's support, the data
/// are constant, or the likelihood equations do not converge.
pub fn fit(data: &[f64], family: Family) -> Result<Fitted> {
    let what = "maximum-likelihood fit";
    let n = data.len();
    if n < 3 {
        return Err(invalid(what, "sample size", ">= 3", n as f64));
    }
    if let Some(v) = data.iter().find(|v| !v.is_finite()) {
        return Err(invalid(what, "value", "finite", *v));
    }
    let nf = n as f64;
    let mean = data.iter().sum::<f64>() / nf;
    let var = data.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / nf;
    if !(var > 0.0) {
        return Err(UqError::Invalid {
            what,
            message: "the data are constant".into(),
        });
    }
    let positive = || -> Result<()> {
        match data.iter().find(|&&v| v <= 0.0) {
            Some(v) => Err(invalid(what, "value", "> 0 for this family", *v)),
            None => Ok(()),
        }
    };
    let (law, parameters): (Arc<dyn Marginal>, Vec<(&'static str, f64)>) = match family {
        Family::Normal => {
            let s = var.sqrt();
            (
                Arc::new(Normal::new(mean, s)?),
                vec![("mean", mean), ("std", s)],
            )
        }
        Family::LogNormal => {
            positive()?;
            let l: Vec<f64> = data.iter().map(|v| v.ln()).collect();
            let mu = l.iter().sum::<f64>() / nf;
            let s = (l.iter().map(|v| (v - mu).powi(2)).sum::<f64>() / nf).sqrt();
            (
                Arc::new(LogNormal::new(mu, s)?),
                vec![("mu", mu), ("sigma", s)],
            )
        }
        Family::Uniform => {
            let lo = data.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = data.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (Arc::new(Uniform::new(lo, hi)?), vec![("a", lo), ("b", hi)])
        }
        Family::Gamma => {
            positive()?;
            let mlog = data.iter().map(|v| v.ln()).sum::<f64>() / nf;
            let s = mean.ln() - mlog;
            // Start: Minka's approximation, then Newton on ln k - psi(k) = s.
            let mut k = (3.0 - s + ((s - 3.0).powi(2) + 24.0 * s).sqrt()) / (12.0 * s);
            for _ in 0..100 {
                let f = k.ln() - digamma(k) - s;
                let df = 1.0 / k - trigamma(k);
                let step = f / df;
                k = (k - step).max(0.5 * k);
                if step.abs() < 1e-14 * k {
                    break;
                }
            }
            let theta = mean / k;
            (
                Arc::new(Gamma::new(k, theta, 0.0)?),
                vec![("shape", k), ("scale", theta)],
            )
        }
        Family::Beta { a, b } => {
            if !(a.is_finite() && b.is_finite() && b > a) {
                return Err(invalid(what, "beta bounds", "finite with a < b", b));
            }
            if let Some(v) = data.iter().find(|&&v| v <= a || v >= b) {
                return Err(invalid(what, "value", "inside the open beta bounds", *v));
            }
            let y: Vec<f64> = data.iter().map(|v| (v - a) / (b - a)).collect();
            let l1 = y.iter().map(|v| v.ln()).sum::<f64>() / nf;
            let l2 = y.iter().map(|v| (1.0 - v).ln()).sum::<f64>() / nf;
            let (m, v) = ((mean - a) / (b - a), var / (b - a).powi(2));
            let c = (m * (1.0 - m) / v - 1.0).max(0.1);
            let (mut al, mut be) = (m * c, (1.0 - m) * c);
            let mut converged = false;
            for _ in 0..200 {
                let ps = digamma(al + be);
                let (f1, f2) = (digamma(al) - ps - l1, digamma(be) - ps - l2);
                let ts = trigamma(al + be);
                let (j11, j22, j12) = (trigamma(al) - ts, trigamma(be) - ts, -ts);
                let det = j11 * j22 - j12 * j12;
                let (d1, d2) = ((j22 * f1 - j12 * f2) / det, (j11 * f2 - j12 * f1) / det);
                al = (al - d1).max(0.5 * al);
                be = (be - d2).max(0.5 * be);
                if d1.abs() < 1e-13 * al && d2.abs() < 1e-13 * be {
                    converged = true;
                    break;
                }
            }
            if !converged {
                return Err(UqError::Invalid {
                    what,
                    message: "beta likelihood equations did not converge".into(),
                });
            }
            (
                Arc::new(Beta::new(al, be, a, b)?),
                vec![("alpha", al), ("beta", be)],
            )
        }
    };
    let ll: f64 = data.iter().map(|&x| law.pdf(x).ln()).sum();
    let p = parameters.len() as f64;
    let mut sorted = data.to_vec();
    sorted.sort_by(f64::total_cmp);
    let (ks, ks_pvalue, anderson_darling) = goodness_of_fit(&sorted, law.as_ref());
    Ok(Fitted {
        family,
        law,
        parameters,
        log_likelihood: ll,
        aic: 2.0 * p - 2.0 * ll,
        bic: p * nf.ln() - 2.0 * ll,
        ks,
        ks_pvalue,
        anderson_darling,
    })
}

/// Fit every candidate that applies to the data (families whose support excludes a value are
/// skipped) and sort by increasing BIC.
///
/// # Errors
/// If no candidate can be fitted.
pub fn fit_best(data: &[f64], candidates: &[Family]) -> Result<Vec<Fitted>> {
    let mut out: Vec<Fitted> = candidates
        .iter()
        .filter_map(|&f| fit(data, f).ok())
        .collect();
    if out.is_empty() {
        return Err(UqError::Invalid {
            what: "maximum-likelihood fit",
            message: "no candidate family fits the data".into(),
        });
    }
    out.sort_by(|a, b| a.bic.total_cmp(&b.bic));
    Ok(out)
}
