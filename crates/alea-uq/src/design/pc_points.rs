//! PC collocation points (thesis 2.3; Berveiller, Sudret & Lemaire 2006): the tensor grid of the
//! roots of the orthonormal polynomial of degree `p + 1` of each marginal, of which the `n` points
//! of highest joint density (closest to the mode) are kept, in that order.

use super::Design;
use crate::basis::OrthoPoly;
use crate::error::{Result, invalid};
use crate::law::Marginal;
use std::sync::Arc;

/// `n` collocation points for a PC of degree `degree` (`n <= (degree + 1)^dim`).
///
/// # Errors
/// If `n` exceeds the size of the tensor grid of roots, or polynomial generation fails.
pub fn pc_collocation(marginals: &[Arc<dyn Marginal>], degree: usize, n: usize) -> Result<Design> {
    let d = marginals.len();
    let roots = marginals
        .iter()
        .map(|m| {
            Ok(OrthoPoly::for_marginal(m.as_ref(), degree + 1)?
                .gauss(degree + 1)
                .0)
        })
        .collect::<Result<Vec<_>>>()?;
    let total = (degree + 1).checked_pow(d as u32).filter(|&t| t <= 1 << 26);
    let Some(total) = total else {
        return Err(invalid(
            "PC collocation",
            "degree",
            "such that (degree + 1)^dim <= 2^26",
            degree as f64,
        ));
    };
    if n > total || d == 0 {
        return Err(invalid(
            "PC collocation",
            "number of points",
            "<= (degree + 1)^dim",
            n as f64,
        ));
    }
    let mut cand: Vec<(f64, Vec<f64>)> = Vec::with_capacity(total);
    let mut idx = vec![0usize; d];
    for _ in 0..total {
        let x: Vec<f64> = (0..d).map(|j| roots[j][idx[j]]).collect();
        let lp: f64 = (0..d).map(|j| marginals[j].pdf(x[j]).ln()).sum();
        cand.push((lp, x));
        for j in (0..d).rev() {
            idx[j] += 1;
            if idx[j] <= degree {
                break;
            }
            idx[j] = 0;
        }
    }
    // Highest density first; ties broken by the grid order (stable sort).
    cand.sort_by(|a, b| b.0.total_cmp(&a.0));
    Design::new(d, cand.into_iter().take(n).flat_map(|c| c.1).collect())
}
