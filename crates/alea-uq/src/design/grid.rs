//! Deterministic designs on a box `[lo, hi]`: regular tensor grids and "corners + centre".

use super::Design;
use crate::error::{Result, check_len, invalid};

/// Tensor grid with `counts[j] >= 2` equispaced nodes in direction `j` (bounds included); the
/// last direction varies fastest. `counts[j] == 1` puts the single node at the centre.
///
/// # Errors
/// If lengths differ, a count is 0 or `lo[j] > hi[j]`.
pub fn tensor_grid(lo: &[f64], hi: &[f64], counts: &[usize]) -> Result<Design> {
    check_len("tensor grid", "hi", lo.len(), hi.len())?;
    check_len("tensor grid", "counts", lo.len(), counts.len())?;
    let d = lo.len();
    for j in 0..d {
        if counts[j] == 0 {
            return Err(invalid("tensor grid", "count", ">= 1", 0.0));
        }
        if !(hi[j] >= lo[j]) {
            return Err(invalid("tensor grid", "hi", ">= lo", hi[j]));
        }
    }
    let Some(total) = counts
        .iter()
        .try_fold(1usize, |acc, &c| acc.checked_mul(c))
        .filter(|&t| t <= 1 << 28)
    else {
        return Err(crate::UqError::Invalid {
            what: "tensor grid",
            message: format!("too many points: {counts:?}"),
        });
    };
    let mut points = Vec::with_capacity(total * d);
    let mut idx = vec![0usize; d];
    for _ in 0..total {
        for j in 0..d {
            points.push(if counts[j] == 1 {
                0.5 * (lo[j] + hi[j])
            } else {
                lo[j] + (hi[j] - lo[j]) * idx[j] as f64 / (counts[j] - 1) as f64
            });
        }
        for j in (0..d).rev() {
            idx[j] += 1;
            if idx[j] < counts[j] {
                break;
            }
            idx[j] = 0;
        }
    }
    Design::new(d, points)
}

/// The `2^d` corners of the box followed by its centre.
///
/// # Errors
/// As [`tensor_grid`].
pub fn corners_and_centre(lo: &[f64], hi: &[f64]) -> Result<Design> {
    let mut g = tensor_grid(lo, hi, &vec![2; lo.len()])?;
    let c: Vec<f64> = lo.iter().zip(hi).map(|(a, b)| 0.5 * (a + b)).collect();
    g.points.extend_from_slice(&c);
    Ok(g)
}
