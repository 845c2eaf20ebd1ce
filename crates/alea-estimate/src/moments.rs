//! The substructure part from weight moments (crate doc, "Substructures"): `M_f = E[f(xi) w
//! w^T]` over a rule ([`weight_moments`]), the exact expectations they give
//! ([`Estimator::substructure_moments`]) and their split cell by cell ([`cell_terms`]).

use rayon::prelude::*;

use crate::estimator::{Estimator, Parameters, Weights};
use crate::{EstimateError, Rule};

/// Weight moments of one substructure: `M_f = E[f(xi) w w^T]`, dense row-major `K x K`, for
/// `f = 1 / alpha_s`, `1` and `alpha_s`.
#[derive(Clone, Debug, PartialEq)]
pub struct SubstructureMoments {
    /// `E[w w^T / alpha]`.
    pub inv_alpha: Vec<f64>,
    /// `E[w w^T]`.
    pub one: Vec<f64>,
    /// `E[alpha w w^T]`.
    pub alpha: Vec<f64>,
}

impl Estimator {
    /// Weight moments of every substructure over `rule` ([`SubstructureMoments`]).
    pub fn moments(
        &self,
        rule: &Rule,
        weights: &dyn Weights,
        params: &dyn Parameters,
    ) -> Vec<SubstructureMoments> {
        weight_moments(rule, weights, params, self.layout.subs.len(), self.k)
    }

    /// The substructure terms from weight moments (exact when the moments are):
    /// `E[e_s^2] = 1/2 [tr(M_{1/alpha} A) - 2 tr(M_1 B D) + tr(M_alpha D C D)]`,
    /// `E[geo_s^2] = 1/2 tr(M_{1/alpha} (A - B - B^T + C))`, `E[||sigma~||^2] =
    /// tr(M_{1/alpha} A)`; returns `[e2, geo2, norm2]` per substructure (zeros when left
    /// out; `[0, 0, tr(M_alpha D C D)]`, the FE energy, without admissible samples).
    ///
    /// # Errors
    /// [`EstimateError::Invalid`] if the moments do not match the runs.
    pub fn substructure_moments(
        &self,
        moments: &[SubstructureMoments],
    ) -> Result<Vec<[f64; 3]>, EstimateError> {
        let k = self.k;
        if moments.len() != self.layout.subs.len()
            || moments.iter().any(|m| {
                m.inv_alpha.len() != k * k || m.one.len() != k * k || m.alpha.len() != k * k
            })
        {
            return Err(EstimateError::Invalid(format!(
                "moments of {} substructures for {} runs",
                moments.len(),
                k
            )));
        }
        Ok(self
            .grams
            .iter()
            .zip(moments)
            .enumerate()
            .map(|(s, (g, m))| {
                let Some(g) = g else {
                    return [0.0; 3];
                };
                let y = &self.young[s];
                if !g.has_admissible() {
                    let mut c = 0.0;
                    for i in 0..k {
                        for j in 0..k {
                            let ij = i * k + j;
                            c += m.alpha[ij] * g.hh[ij] / (y[i] * y[j]);
                        }
                    }
                    return [0.0, 0.0, c];
                }
                let (mut a, mut b, mut c, mut geo) = (0.0, 0.0, 0.0, 0.0);
                for i in 0..k {
                    for j in 0..k {
                        let ij = i * k + j;
                        a += m.inv_alpha[ij] * g.aa[ij];
                        b += m.one[ij] * g.ah[ij] / y[j];
                        c += m.alpha[ij] * g.hh[ij] / (y[i] * y[j]);
                        geo += m.inv_alpha[ij] * (g.aa[ij] - 2.0 * g.ah[ij] + g.hh[ij]);
                    }
                }
                [0.5 * (a - 2.0 * b + c), 0.5 * geo, a]
            })
            .collect())
    }
}

/// Per-cell expectations of one substructure's terms, `(E[geo_E^2], E[e_E^2])` for every cell
/// `E` (the sums over the cells are the substructure's `geo2` and `e2` when the moments come
/// from the same rule): `1/2 sum_kl M_{1/alpha,kl} d_k . d_l` on the cell for the space part
/// (`d_k = y(sigma_hat_k) - y(sigma_h,k)`) and the crate doc's quadratic form for the total.
/// `admissible[k]`, `fe[k]`: run `k`'s sample vectors; `young[k]`: its Young's factor;
/// `cell_offsets`: the layout's. Entries of the moments below `1e-300` in absolute value are
/// skipped (a piecewise-linear surrogate couples only neighbouring runs).
///
/// # Panics
/// If the lengths do not match (`K` runs, `K x K` moments, samples covering the offsets).
pub fn cell_terms(
    admissible: &[&[f64]],
    fe: &[&[f64]],
    young: &[f64],
    cell_offsets: &[usize],
    moments: &SubstructureMoments,
) -> Vec<(f64, f64)> {
    let k = admissible.len();
    assert!(fe.len() == k && young.len() == k && moments.one.len() == k * k);
    let pairs: Vec<(usize, usize)> = (0..k)
        .flat_map(|i| (0..k).map(move |j| (i, j)))
        .filter(|&(i, j)| {
            let ij = i * k + j;
            moments.inv_alpha[ij].abs() > 1e-300
                || moments.one[ij].abs() > 1e-300
                || moments.alpha[ij].abs() > 1e-300
        })
        .collect();
    let ncell = cell_offsets.len().saturating_sub(1);
    (0..ncell)
        .into_par_iter()
        .map(|c| {
            let r = cell_offsets[c]..cell_offsets[c + 1];
            let (mut geo, mut e) = (0.0, 0.0);
            for &(i, j) in &pairs {
                let ij = i * k + j;
                let (ai, aj) = (&admissible[i][r.clone()], &admissible[j][r.clone()]);
                let (hi, hj) = (&fe[i][r.clone()], &fe[j][r.clone()]);
                let (mut aa, mut ah, mut hh, mut dd) = (0.0, 0.0, 0.0, 0.0);
                for q in 0..ai.len() {
                    aa += ai[q] * aj[q];
                    ah += ai[q] * hj[q];
                    hh += hi[q] * hj[q];
                    dd += (ai[q] - hi[q]) * (aj[q] - hj[q]);
                }
                geo += moments.inv_alpha[ij] * dd;
                e += moments.inv_alpha[ij] * aa - 2.0 * moments.one[ij] * ah / young[j]
                    + moments.alpha[ij] * hh / (young[i] * young[j]);
            }
            (0.5 * geo, 0.5 * e)
        })
        .collect()
}

/// Weight moments `M_f = E[f(xi) w w^T]` (`f = 1/alpha_s, 1, alpha_s`) of `num_subs`
/// substructures for a surrogate of `k` runs, over `rule`.
pub fn weight_moments(
    rule: &Rule,
    weights: &dyn Weights,
    params: &dyn Parameters,
    num_subs: usize,
    k: usize,
) -> Vec<SubstructureMoments> {
    let mut out: Vec<SubstructureMoments> = (0..num_subs)
        .map(|_| SubstructureMoments {
            inv_alpha: vec![0.0; k * k],
            one: vec![0.0; k * k],
            alpha: vec![0.0; k * k],
        })
        .collect();
    let mut w = Vec::new();
    let mut alpha = vec![1.0; num_subs];
    for q in 0..rule.len() {
        let xi = rule.point(q);
        let om = rule.weight(q);
        weights.weights(xi, &mut w);
        params.young(xi, &mut alpha);
        for (s, m) in out.iter_mut().enumerate() {
            for &(i, wi) in &w {
                for &(j, wj) in &w {
                    let v = om * wi * wj;
                    m.inv_alpha[i * k + j] += v / alpha[s];
                    m.one[i * k + j] += v;
                    m.alpha[i * k + j] += v * alpha[s];
                }
            }
        }
    }
    out
}
