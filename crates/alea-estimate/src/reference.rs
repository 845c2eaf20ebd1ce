//! The true error of a surrogate against a reference solution, the denominator of the
//! stochastic efficiency index (thesis 3.3.3):
//!
//! ```text
//! nu = ( e~^2 / E[ sum_s ||sigma_ref,s(xi) - sigma_h1,s(xi)||^2_{K_s(xi)^-1} ] )^(1/2)
//! ```
//!
//! with `e~^2` the estimate (3.28) and `sigma_h1(xi) = K(xi) eps(u~(xi))` the stress of the
//! surrogate's interpolated displacement (crate doc), whose constitutive-relation error `e~`
//! measures. The reference is a study on a finer space mesh and a finer stochastic grid; its
//! stress is built the same way, `sigma_ref(xi) = K(xi) eps(sum_m r_m(xi) u_ref,m)` with its own
//! weights `r_m`. The two fields live on different meshes: both are sampled at the quadrature
//! points of the reference mesh (the coarse field located there, `alea_fem::locate`) in
//! energy coordinates of the reference material, `z(u) = (w_q |J_q| t)^(1/2) R^T eps(u)(x_q)`
//! with `D0 = R R^T`, so that `int eps(u) : D0 : eps(v) = z(u) . z(v)` and, for Young's factor
//! `alpha` (`K = alpha D0`), `||K eps(u)||^2_{K^-1} = alpha |z(u)|^2`. Then per substructure
//!
//! ```text
//! E[alpha(xi) |sum_m r_m(xi) z_ref,m - sum_k w_k(xi) z_h,k|^2]
//!   = E[alpha (r^T A r - 2 r^T C w + w^T B w)]
//! ```
//!
//! with the Gram blocks `A = Z_ref^T Z_ref`, `C = Z_ref^T Z_h`, `B = Z_h^T Z_h`
//! ([`crate::gram::CrossGram`], accumulated over blocks of sample rows), and the expectation
//! over a [`crate::Rule`] whose cells follow the kinks of both weight families (e.g.
//! [`crate::Rule::product_cells`] of the union of both grids' breakpoints): exact for
//! piecewise-multilinear weights up to the density's quadrature.
//!
//! Which index: the thesis's (3.3.3), `e~` over the reference distance, both without the factor
//! 2 of Prager-Synge (3.19): `||sigma_ex - sigma_h||^2 <= 2 e^2` in the deterministic linear case,
//! so `nu >= 1 / sqrt(2)` is what a guaranteed bound promises and `sqrt(2) nu >= 1` the bound
//! itself ([`efficiency`] returns both).

use rayon::prelude::*;

use crate::gram::CrossGram;
use crate::{Parameters, Rule, Weights};

/// `E[alpha_s(xi) |sum_m r_m z_ref,m - sum_k w_k z_h,k|^2]` for every substructure `s` with a
/// Gram block (module doc); `reference` gives the `r_m`, `surrogate` the `w_k`, `params` the
/// Young's factors. Substructures without a block get 0.
///
/// # Panics
/// If a block's sizes do not match the weights' run indices.
pub fn expected_distances(
    rule: &Rule,
    reference: &dyn Weights,
    surrogate: &dyn Weights,
    params: &dyn Parameters,
    grams: &[Option<CrossGram>],
) -> Vec<f64> {
    let ns = grams.len();
    const CHUNK: usize = 512;
    let starts: Vec<usize> = (0..rule.len()).step_by(CHUNK).collect();
    let parts: Vec<Vec<f64>> = starts
        .par_iter()
        .map(|&q0| {
            let mut acc = vec![0.0; ns];
            let (mut r, mut w) = (Vec::new(), Vec::new());
            let mut alpha = vec![1.0; ns];
            for q in q0..(q0 + CHUNK).min(rule.len()) {
                let xi = rule.point(q);
                reference.weights(xi, &mut r);
                surrogate.weights(xi, &mut w);
                params.young(xi, &mut alpha);
                for (s, g) in grams.iter().enumerate() {
                    let Some(g) = g else { continue };
                    let (ka, kb) = (g.ka, g.kb);
                    let mut v = 0.0;
                    for &(i, ri) in &r {
                        let (row_a, row_c) =
                            (&g.aa[i * ka..(i + 1) * ka], &g.ab[i * kb..(i + 1) * kb]);
                        let mut t = 0.0;
                        for &(j, rj) in &r {
                            t += row_a[j] * rj;
                        }
                        for &(j, wj) in &w {
                            t -= 2.0 * row_c[j] * wj;
                        }
                        v += ri * t;
                    }
                    for &(i, wi) in &w {
                        let row = &g.bb[i * kb..(i + 1) * kb];
                        let mut t = 0.0;
                        for &(j, wj) in &w {
                            t += row[j] * wj;
                        }
                        v += wi * t;
                    }
                    acc[s] += rule.weight(q) * alpha[s] * v;
                }
            }
            acc
        })
        .collect();
    let mut out = vec![0.0; ns];
    for p in &parts {
        for (o, v) in out.iter_mut().zip(p) {
            *o += v;
        }
    }
    out
}

/// The efficiency index of an estimate `e2 = e~^2` against the reference distance
/// `distance2 = E[sum_s ||sigma_ref - sigma_h1||^2]` (module doc): `(nu, sqrt(2) nu)`, the
/// thesis's index and the Prager-Synge one; `None` if the distance is not positive.
pub fn efficiency(e2: f64, distance2: f64) -> Option<(f64, f64)> {
    (distance2 > 0.0 && e2 >= 0.0).then(|| {
        let nu = (e2 / distance2).sqrt();
        (nu, std::f64::consts::SQRT_2 * nu)
    })
}
