//! PC collocation points (thesis 2.3; Berveiller, Sudret & Lemaire 2006), chosen so that the
//! regression they feed is well posed.
//!
//! **Candidates**: the tensor grid of the roots of the orthonormal polynomial of degree `p + 1`
//! of each marginal, `(p + 1)^d` points. Asked for all of them, [`pc_collocation`] returns the
//! grid, most probable (highest joint density) first.
//!
//! **Fewer points** (`n < (p + 1)^d`): they are chosen among the candidates by a greedy
//! D-optimal selection ([`d_optimal_subset`]) for the total-degree basis of degree `p`
//! (`P` terms, rows `psi(x) = (Psi_alpha(x))_alpha`), each step adding the candidate that
//! increases `log det` of the information matrix `M = sum_{x in S} psi(x) psi(x)^T` of the chosen
//! set `S` the most:
//!
//! 1. while `|S| < P` (`M` singular): the candidate with the largest residual
//!    `r(x) = |psi(x) - Q Q^T psi(x)|^2` off the span `Q` (orthonormal) of the rows already chosen,
//!    the limit of the largest gain of `log det(M + eps I)` as `eps -> 0`; a pivoted
//!    Gram-Schmidt whose `P` points are approximate Fekete points (Bos, De Marchi, Sommariva &
//!    Vianello 2010). After adding `x*` with `q = (I - Q Q^T) psi(x*) / |.|`:
//!    `r(x) -= (q^T psi(x))^2`;
//! 2. then the candidate of largest leverage `l(x) = psi(x)^T M^-1 psi(x)`, since
//!    `det(M + psi psi^T) = det(M) (1 + l(x))`. `M^-1` and the leverages follow by
//!    Sherman-Morrison: with `u = M^-1 psi(x*)`, `l(x) -= (psi(x)^T u)^2 / (1 + l(x*))` and
//!    `M^-1 -= u u^T / (1 + l(x*))`.
//!
//! Scores within a relative `1e-9` of the best are ties, broken by the higher joint density, then
//! by the grid order, so the selection is deterministic. The chosen points are returned most
//! probable first. Above `2^22` entries in the candidate matrix (`(p + 1)^d P`: 6 parameters at
//! degree 5), the candidates are the rank-1 lattice `k s mod (p + 1)^d`, `k < max(2^22 / P, 4 n)`
//! of the grid's linear indices (`s` coprime with `(p + 1)^d`, about `0.618 (p + 1)^d`).
//!
//! Why not simply the `n` most probable candidates (the rule before): with equal densities
//! (uniform laws) or few density levels they fill whole slices of the grid in its order. With
//! three uniform parameters and `p = 3` the first 40 of the 64 candidates hold only 3 of the 4
//! roots of the first parameter, so the cubic `(x_1 - r_1)(x_1 - r_2)(x_1 - r_3)`, a combination
//! of the basis, vanishes at every point and `Psi^T Psi` is singular.

use super::Design;
use crate::basis::{OrthoPoly, PcBasis};
use crate::error::{Result, UqError, invalid};
use crate::law::Marginal;
use crate::linalg::cholesky;
use std::sync::Arc;

/// Largest number of entries of the candidate matrix (candidates x terms) before the candidates
/// are thinned to a lattice of the grid.
const MAX_CANDIDATE_ENTRIES: usize = 1 << 22;

/// Relative width of a tie between scores.
const TIE: f64 = 1e-9;

/// `n` collocation points for a PC of total degree `degree` (`P <= n <= (degree + 1)^dim`
/// when `n < (degree + 1)^dim`, `P` the number of terms): the whole tensor grid of roots, or the
/// greedy D-optimal subset of it (module doc), most probable first.
///
/// # Errors
/// If `n` exceeds the size of the tensor grid of roots, is below `P` while smaller than the grid,
/// the candidates cannot determine the basis, or polynomial generation fails.
pub fn pc_collocation(marginals: &[Arc<dyn Marginal>], degree: usize, n: usize) -> Result<Design> {
    let d = marginals.len();
    let grid = RootGrid::new(marginals, degree)?;
    if n > grid.total || d == 0 {
        return Err(invalid(
            "PC collocation",
            "number of points",
            "<= (degree + 1)^dim",
            n as f64,
        ));
    }
    let chosen: Vec<usize> = if n == grid.total {
        (0..grid.total).collect()
    } else {
        let basis = PcBasis::total_degree(marginals, degree)?;
        if n < basis.len() {
            return Err(UqError::Invalid {
                what: "PC collocation",
                message: format!(
                    "{n} points cannot determine the {} terms of degree {degree}",
                    basis.len()
                ),
            });
        }
        let cand = candidate_indices(grid.total, basis.len(), n)?;
        let points: Vec<f64> = cand.iter().flat_map(|&c| grid.point(c)).collect();
        let psi = basis.design_matrix(&points)?;
        let density: Vec<f64> = cand.iter().map(|&c| grid.log_density(c)).collect();
        d_optimal_subset(&psi, basis.len(), n, &density)?
            .into_iter()
            .map(|k| cand[k])
            .collect()
    };
    let mut ranked: Vec<(f64, usize)> = chosen
        .into_iter()
        .map(|c| (grid.log_density(c), c))
        .collect();
    // Highest density first; ties in the grid order.
    ranked.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    Design::new(
        d,
        ranked.into_iter().flat_map(|r| grid.point(r.1)).collect(),
    )
}

/// The tensor grid of the roots of the degree `p + 1` orthonormal polynomials.
struct RootGrid<'a> {
    marginals: &'a [Arc<dyn Marginal>],
    roots: Vec<Vec<f64>>,
    /// `(p + 1)^d`.
    total: usize,
}

impl<'a> RootGrid<'a> {
    fn new(marginals: &'a [Arc<dyn Marginal>], degree: usize) -> Result<Self> {
        let roots = marginals
            .iter()
            .map(|m| {
                Ok(OrthoPoly::for_marginal(m.as_ref(), degree + 1)?
                    .gauss(degree + 1)
                    .0)
            })
            .collect::<Result<Vec<_>>>()?;
        let total = (degree + 1)
            .checked_pow(marginals.len() as u32)
            .filter(|&t| t <= 1 << 26)
            .ok_or_else(|| {
                invalid(
                    "PC collocation",
                    "degree",
                    "such that (degree + 1)^dim <= 2^26",
                    degree as f64,
                )
            })?;
        Ok(Self {
            marginals,
            roots,
            total,
        })
    }

    /// Point of linear index `c` (the last parameter's root index varies fastest).
    fn point(&self, mut c: usize) -> Vec<f64> {
        let mut x = vec![0.0; self.roots.len()];
        for (xj, r) in x.iter_mut().zip(&self.roots).rev() {
            *xj = r[c % r.len()];
            c /= r.len();
        }
        x
    }

    fn log_density(&self, c: usize) -> f64 {
        self.point(c)
            .iter()
            .zip(self.marginals)
            .map(|(&x, m)| m.pdf(x).ln())
            .sum()
    }
}

/// Linear indices of the candidates: the whole grid, or a rank-1 lattice of it when the
/// candidate matrix would exceed [`MAX_CANDIDATE_ENTRIES`] (module doc).
fn candidate_indices(total: usize, terms: usize, n: usize) -> Result<Vec<usize>> {
    if total.saturating_mul(terms) <= MAX_CANDIDATE_ENTRIES {
        return Ok((0..total).collect());
    }
    let count = (MAX_CANDIDATE_ENTRIES / terms).max(4 * n).min(total);
    if count.saturating_mul(terms) > 8 * MAX_CANDIDATE_ENTRIES {
        return Err(UqError::Invalid {
            what: "PC collocation",
            message: format!(
                "choosing {n} points for {terms} terms needs {count} candidates of {terms} values: too large"
            ),
        });
    }
    let mut s = (0.618_033_988_75 * total as f64) as usize;
    while gcd(s, total) != 1 {
        s += 1;
    }
    Ok((0..count).map(|k| (k * s) % total).collect())
}

fn gcd(mut a: usize, mut b: usize) -> usize {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// Greedy D-optimal choice of `n` rows of the row-major `m x terms` candidate matrix `psi`
/// (module doc: pivoted Gram-Schmidt up to `terms` rows, then the largest leverage). Ties within
/// a relative `1e-9` go to the larger `preference`, then to the lower row. Returns the chosen
/// rows in the order they were chosen.
///
/// # Errors
/// [`UqError::Invalid`] if `n > m` or `n < terms`; [`UqError::Singular`] if the candidates
/// cannot determine the `terms` functions (no residual above `1e-12` of the largest row norm;
/// `pivot` is the number of rows chosen by then).
pub fn d_optimal_subset(
    psi: &[f64],
    terms: usize,
    n: usize,
    preference: &[f64],
) -> Result<Vec<usize>> {
    let m = preference.len();
    if psi.len() != m * terms || n > m || n < terms {
        return Err(UqError::Invalid {
            what: "D-optimal selection",
            message: format!(
                "{n} rows of {m} candidates of {terms} terms ({} values)",
                psi.len()
            ),
        });
    }
    let mut taken = vec![false; m];
    let mut chosen = fekete_rows(psi, terms, preference, &mut taken)?;
    if n > terms {
        augment_by_leverage(psi, terms, n, preference, &mut taken, &mut chosen)?;
    }
    Ok(chosen)
}

fn row(psi: &[f64], terms: usize, k: usize) -> &[f64] {
    &psi[k * terms..(k + 1) * terms]
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The untaken row of best score (ties: preference, then lower index).
fn best(score: &[f64], taken: &[bool], preference: &[f64]) -> usize {
    let top = score
        .iter()
        .zip(taken)
        .filter(|(_, t)| !**t)
        .fold(f64::NEG_INFINITY, |a, (s, _)| a.max(*s));
    let floor = top - TIE * top.abs();
    let mut pick = usize::MAX;
    for (k, (&s, &t)) in score.iter().zip(taken).enumerate() {
        if !t && s >= floor && (pick == usize::MAX || preference[k] > preference[pick]) {
            pick = k;
        }
    }
    pick
}

/// Phase 1: `terms` rows by pivoted Gram-Schmidt (largest residual off the chosen span).
fn fekete_rows(
    psi: &[f64],
    terms: usize,
    preference: &[f64],
    taken: &mut [bool],
) -> Result<Vec<usize>> {
    let m = preference.len();
    let mut resid: Vec<f64> = (0..m)
        .map(|k| dot(row(psi, terms, k), row(psi, terms, k)))
        .collect();
    let scale = resid.iter().fold(0.0f64, |a, &v| a.max(v));
    let mut basis: Vec<Vec<f64>> = Vec::with_capacity(terms);
    let mut chosen = Vec::with_capacity(terms);
    while chosen.len() < terms {
        let k = best(&resid, taken, preference);
        if !(resid[k] > 1e-12 * scale) {
            return Err(UqError::Singular {
                what: "D-optimal selection",
                pivot: chosen.len(),
                size: terms,
            });
        }
        let mut q = row(psi, terms, k).to_vec();
        for _ in 0..2 {
            for b in &basis {
                let c = dot(&q, b);
                q.iter_mut().zip(b).for_each(|(v, bv)| *v -= c * bv);
            }
        }
        let norm = dot(&q, &q).sqrt();
        q.iter_mut().for_each(|v| *v /= norm);
        for (c, r) in resid.iter_mut().enumerate() {
            let t = dot(row(psi, terms, c), &q);
            *r -= t * t;
        }
        taken[k] = true;
        chosen.push(k);
        basis.push(q);
    }
    Ok(chosen)
}

/// Phase 2: rows of largest leverage until `n` are chosen (Sherman-Morrison updates).
fn augment_by_leverage(
    psi: &[f64],
    terms: usize,
    n: usize,
    preference: &[f64],
    taken: &mut [bool],
    chosen: &mut Vec<usize>,
) -> Result<()> {
    let m = preference.len();
    let mut info = vec![0.0; terms * terms];
    for &k in chosen.iter() {
        let r = row(psi, terms, k);
        for i in 0..terms {
            for j in 0..terms {
                info[i * terms + j] += r[i] * r[j];
            }
        }
    }
    let l = cholesky("D-optimal selection", &info, terms)?;
    let linv = lower_inverse(&l, terms);
    let mut minv = vec![0.0; terms * terms];
    for i in 0..terms {
        for j in 0..terms {
            // (L^-T L^-1)_ij = sum_k Linv_ki Linv_kj, k >= max(i, j).
            minv[i * terms + j] = (i.max(j)..terms)
                .map(|k| linv[k * terms + i] * linv[k * terms + j])
                .sum();
        }
    }
    let mut lev: Vec<f64> = (0..m)
        .map(|c| {
            let r = row(psi, terms, c);
            (0..terms)
                .map(|k| dot(&linv[k * terms..k * terms + k + 1], &r[..=k]).powi(2))
                .sum()
        })
        .collect();
    let mut u = vec![0.0; terms];
    while chosen.len() < n {
        let k = best(&lev, taken, preference);
        let r = row(psi, terms, k);
        for (i, ui) in u.iter_mut().enumerate() {
            *ui = dot(&minv[i * terms..(i + 1) * terms], r);
        }
        let denom = 1.0 + dot(r, &u);
        for (c, lc) in lev.iter_mut().enumerate() {
            let t = dot(row(psi, terms, c), &u);
            *lc -= t * t / denom;
        }
        for i in 0..terms {
            for j in 0..terms {
                minv[i * terms + j] -= u[i] * u[j] / denom;
            }
        }
        taken[k] = true;
        chosen.push(k);
    }
    Ok(())
}

/// Inverse of a lower-triangular row-major `n x n` matrix (lower-triangular).
fn lower_inverse(l: &[f64], n: usize) -> Vec<f64> {
    let mut inv = vec![0.0; n * n];
    for j in 0..n {
        inv[j * n + j] = 1.0 / l[j * n + j];
        for i in (j + 1)..n {
            let s: f64 = (j..i).map(|k| l[i * n + k] * inv[k * n + j]).sum();
            inv[i * n + j] = -s / l[i * n + i];
        }
    }
    inv
}
