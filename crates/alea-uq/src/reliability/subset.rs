//! Subset simulation (Au & Beck, Probab. Eng. Mech. 16, 2001).
//!
//! `P_f = P(F_1) prod_{j>1} P(F_j | F_{j-1})` with nested domains `F_j = {G(u) <= b_j}`: each
//! level keeps the `N_c = p0 N` samples of smallest `G` (threshold `b_j` halfway between the
//! `N_c`-th and the next value) as seeds of `N_c` Markov chains of length `N_s = 1/p0` in
//! `F_j`, grown by the preconditioned Crank-Nicolson proposal `v = rho u + sqrt(1 - rho^2) xi`
//! (reversible for `N(0, I)`, accepted if `G(v) <= b_j`; Papaioannou et al., Probab. Eng.
//! Mech. 41, 2015), until `b_j <= 0`; the last factor is the fraction of the population in
//! `G <= 0`. Coefficient of variation (Au & Beck eqs. (29)-(30)):
//! `delta^2 = sum_j (1 - p_j)/(N p_j) (1 + gamma_j)`,
//! `gamma_j = 2 sum_{k=1}^{N_s - 1} (1 - k/N_s) rho_j(k)` from the correlation of the failure
//! indicators along the chains (`gamma_1 = 0` for the i.i.d. first level). Interval:
//! `P exp(± z delta)` (log-normal). Chain `c` of level `j` draws from stream
//! `(j + 1) 2^32 + c` of the seed: reproducible for any thread count.

use super::{Estimate, LimitState};
use crate::error::{Result, UqError, invalid};
use crate::rng::{CHUNK, chunk_rng, open01};
use crate::special::norm_quantile;
use rayon::prelude::*;

/// Options of [`subset_simulation`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SubsetOptions {
    /// Samples per level `N` (default 2000); `p0 N` must be an integer dividing `N`.
    pub samples_per_level: usize,
    /// Conditional probability of each intermediate level (default 0.1).
    pub p0: f64,
    /// Correlation of the Crank-Nicolson proposal (default 0.8).
    pub rho: f64,
    /// Largest number of levels (default 30).
    pub max_levels: usize,
    /// Confidence level of the interval (default 0.95).
    pub level: f64,
    /// Seed.
    pub seed: u64,
}

impl Default for SubsetOptions {
    fn default() -> Self {
        Self {
            samples_per_level: 2000,
            p0: 0.1,
            rho: 0.8,
            max_levels: 30,
            level: 0.95,
            seed: 1,
        }
    }
}

/// Samples of one level: chains of states in the standard normal space with their `G`.
pub(crate) struct Population {
    /// Row-major `N x d` states, chain by chain (`n_s` consecutive states per chain).
    pub u: Vec<f64>,
    /// `G` of each state.
    pub g: Vec<f64>,
    /// States per chain.
    pub chain_len: usize,
}

/// Subset simulation of `P(G(u) <= 0)`. If the failure domain is not reached within
/// `max_levels` levels the estimate is 0 with upper bound `p0^max_levels`.
///
/// # Errors
/// If the options are inconsistent.
pub fn subset_simulation(ls: &LimitState, opts: &SubsetOptions) -> Result<Estimate> {
    run(ls, opts, |_| {}).map(|r| r.0)
}

/// Subset simulation that hands every level's population (after its threshold is set) to
/// `visit`; returns the estimate and the thresholds `b_j`.
pub(crate) fn run(
    ls: &LimitState,
    opts: &SubsetOptions,
    mut visit: impl FnMut(&Population),
) -> Result<(Estimate, Vec<f64>)> {
    let what = "subset simulation";
    let n = opts.samples_per_level;
    if !(opts.p0 > 0.0 && opts.p0 <= 0.5) {
        return Err(invalid(what, "p0", "in (0, 0.5]", opts.p0));
    }
    let nc = (opts.p0 * n as f64).round() as usize;
    if nc == 0 || (nc as f64 - opts.p0 * n as f64).abs() > 1e-9 || !n.is_multiple_of(nc) {
        return Err(UqError::Invalid {
            what,
            message: format!(
                "p0 N = {} must be a whole number dividing N = {n}",
                opts.p0 * n as f64
            ),
        });
    }
    if !(opts.rho >= 0.0 && opts.rho < 1.0) {
        return Err(invalid(what, "rho", "in [0, 1)", opts.rho));
    }
    if !(opts.level > 0.0 && opts.level < 1.0) {
        return Err(invalid(what, "level", "in (0, 1)", opts.level));
    }
    let ns = n / nc;
    let d = ls.dim();
    let start = ls.calls();
    // Level 0: i.i.d. standard normal draws in fixed chunks.
    let mut u = vec![0.0; n * d];
    let mut g = vec![0.0; n];
    u.par_chunks_mut(CHUNK * d)
        .zip(g.par_chunks_mut(CHUNK))
        .enumerate()
        .for_each(|(c, (ub, gb))| {
            let mut rng = chunk_rng(opts.seed, c as u64);
            for (ui, gi) in ub.chunks_exact_mut(d).zip(gb.iter_mut()) {
                for v in ui.iter_mut() {
                    *v = norm_quantile(open01(&mut rng));
                }
                *gi = ls.eval_u(ui);
            }
        });
    let mut pop = Population { u, g, chain_len: 1 };
    let mut p = 1.0;
    let mut delta2 = 0.0;
    let mut thresholds = Vec::new();
    let sqrt1 = (1.0 - opts.rho * opts.rho).sqrt();
    for level in 0..opts.max_levels {
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| pop.g[a].total_cmp(&pop.g[b]).then(a.cmp(&b)));
        let b = 0.5 * (pop.g[order[nc - 1]] + pop.g[order[nc]]);
        let last = b <= 0.0;
        let b = if last { 0.0 } else { b };
        thresholds.push(b);
        visit(&pop);
        let inside: Vec<bool> = pop.g.iter().map(|&v| v <= b).collect();
        let count = inside.iter().filter(|&&v| v).count();
        let pj = count as f64 / n as f64;
        delta2 += level_cov2(&inside, pj, pop.chain_len);
        if last {
            p *= pj;
            let delta = delta2.sqrt();
            let z = norm_quantile(0.5 + 0.5 * opts.level);
            let (lower, upper) = if p > 0.0 {
                (p * (-z * delta).exp(), p * (z * delta).exp())
            } else {
                (0.0, 0.0)
            };
            return Ok((
                Estimate {
                    p,
                    lower,
                    upper,
                    cov: if p > 0.0 { delta } else { f64::INFINITY },
                    evaluations: ls.calls() - start,
                    level: opts.level,
                },
                thresholds,
            ));
        }
        p *= opts.p0;
        // Grow N_c chains of N_s states from the N_c best samples.
        let seeds: Vec<usize> = order[..nc].to_vec();
        let chains: Vec<(Vec<f64>, Vec<f64>)> = seeds
            .par_iter()
            .enumerate()
            .map(|(c, &s)| {
                let mut rng = chunk_rng(opts.seed, ((level as u64 + 1) << 32) + c as u64);
                let mut cu = Vec::with_capacity(ns * d);
                let mut cg = Vec::with_capacity(ns);
                let mut cur = pop.u[s * d..(s + 1) * d].to_vec();
                let mut gcur = pop.g[s];
                cu.extend_from_slice(&cur);
                cg.push(gcur);
                let mut cand = vec![0.0; d];
                for _ in 1..ns {
                    for (v, c0) in cand.iter_mut().zip(&cur) {
                        *v = opts.rho * c0 + sqrt1 * norm_quantile(open01(&mut rng));
                    }
                    let gc = ls.eval_u(&cand);
                    if gc <= b {
                        cur.copy_from_slice(&cand);
                        gcur = gc;
                    }
                    cu.extend_from_slice(&cur);
                    cg.push(gcur);
                }
                (cu, cg)
            })
            .collect();
        pop = Population {
            u: chains.iter().flat_map(|c| c.0.iter().copied()).collect(),
            g: chains.iter().flat_map(|c| c.1.iter().copied()).collect(),
            chain_len: ns,
        };
    }
    // Failure domain not reached: P_f is below the product of the level probabilities.
    Ok((
        Estimate {
            p: 0.0,
            lower: 0.0,
            upper: p,
            cov: f64::INFINITY,
            evaluations: ls.calls() - start,
            level: opts.level,
        },
        thresholds,
    ))
}

/// `(1 - p)/(N p) (1 + gamma)` for indicators stored chain by chain (`len` states per chain).
fn level_cov2(inside: &[bool], p: f64, len: usize) -> f64 {
    let n = inside.len();
    if p <= 0.0 {
        return 0.0;
    }
    let nc = n / len;
    let r0 = p * (1.0 - p);
    let mut gamma = 0.0;
    if r0 > 0.0 {
        for k in 1..len {
            let mut s = 0.0;
            for c in 0..nc {
                let ch = &inside[c * len..(c + 1) * len];
                for l in 0..(len - k) {
                    if ch[l] && ch[l + k] {
                        s += 1.0;
                    }
                }
            }
            let rk = s / (n - k * nc) as f64 - p * p;
            gamma += 2.0 * (1.0 - k as f64 / len as f64) * rk / r0;
        }
    }
    (1.0 - p) / (n as f64 * p) * (1.0 + gamma.max(0.0))
}
