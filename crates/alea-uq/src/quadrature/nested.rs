//! Nested one-dimensional rules for sparse grids: every node of level `l` is a node of level
//! `l + 1`, so a Smolyak grid built on them re-uses its runs.
//!
//! * **Clenshaw-Curtis** for `U(-1, 1)`: `m(0) = 1`, `m(l) = 2^l + 1` nodes
//!   `x_k = cos(k pi / (m - 1))` (computed as `sin(pi (m - 1 - 2k) / (2 (m - 1)))` so that the
//!   centre is exactly 0), probability weights (Waldvogel 2006 / Trefethen 2008)
//!   `w_k = c_k / (2n) (1 - sum_{j=1}^{n/2} b_j cos(2 j k pi / n) / (4 j^2 - 1))`, `n = m - 1`,
//!   `c_0 = c_n = 1`, `c_k = 2` otherwise, `b_{n/2} = 1`, `b_j = 2` otherwise.
//!   Exact for degree `m - 1` (`m` for odd `m`).
//! * **Genz-Keister** for `N(0, 1)` (Genz & Keister, J. Comput. Appl. Math. 71, 1996, the
//!   `1 + 2 + 6 + 10 + 16` family): sizes 1, 3, 9, 19, 35, degrees of exactness 1, 5, 15, 29,
//!   51. The positive nodes below are the published abscissae for the weight `exp(-x^2)`,
//!   scaled by `sqrt 2`; the weights are *not* tabulated but computed here as the interpolatory
//!   weights of the nodes (for a symmetric rule, `sum_q w_q He_2i(x_q) / sqrt((2i)!) = delta_i0`
//!   for `i = 0 .. number of positive nodes`, a small square system in the orthonormal Hermite
//!   polynomials solved by Householder QR); the tests check the stated degrees of exactness.

use crate::basis::OrthoPoly;
use crate::error::{Result, UqError};
use crate::linalg::least_squares_projector;

/// Number of Genz-Keister levels available (sizes 1, 3, 9, 19, 35).
pub const GENZ_KEISTER_LEVELS: usize = 5;

/// Positive Genz-Keister abscissae for the weight `exp(-x^2)`, with the level at which each
/// enters the nested family (0 is the centre at level 0).
// Published abscissae kept verbatim.
#[allow(clippy::excessive_precision)]
const GK_NODES: [(f64, usize); 17] = [
    (1.224_744_871_391_588_9, 1), // sqrt(3/2): the 3-point Gauss-Hermite node
    (0.524_033_547_486_957_63, 2),
    (2.023_230_191_100_515_7, 2),
    (2.959_210_779_063_838, 2),
    (0.870_040_895_352_902_85, 3),
    (1.835_707_975_175_186_8, 3),
    (2.266_513_262_056_787_6, 3),
    (3.667_774_215_946_337_8, 3),
    (4.499_599_398_310_388_1, 3),
    (0.176_064_142_082_008_93, 4),
    (1.579_412_134_846_767_1, 4),
    (2.570_558_376_584_296_8, 4),
    (3.349_163_953_713_194_5, 4),
    (4.029_220_140_504_371_3, 4),
    (5.036_089_944_473_094, 4),
    (5.643_257_857_885_744_9, 4),
    (6.375_939_270_982_235_6, 4),
];

/// Number of nodes of the Clenshaw-Curtis rule of level `l`: 1, 3, 5, 9, 17, ...
pub fn clenshaw_curtis_size(level: usize) -> usize {
    if level == 0 { 1 } else { (1 << level) + 1 }
}

/// Number of nodes of the Genz-Keister rule of level `l < 5`: 1, 3, 9, 19, 35.
pub fn genz_keister_size(level: usize) -> usize {
    [1, 3, 9, 19, 35][level.min(GENZ_KEISTER_LEVELS - 1)]
}

/// Clenshaw-Curtis rule of level `level` for `U(-1, 1)`: ascending nodes and probability
/// weights (summing to 1).
pub fn clenshaw_curtis(level: usize) -> (Vec<f64>, Vec<f64>) {
    let m = clenshaw_curtis_size(level);
    if m == 1 {
        return (vec![0.0], vec![1.0]);
    }
    let n = m - 1;
    let nf = n as f64;
    let pi = std::f64::consts::PI;
    // Ascending: x_k = -cos(k pi / n) = sin(pi (2k - n) / (2n)).
    let x: Vec<f64> = (0..m)
        .map(|k| (pi * (2.0 * k as f64 - nf) / (2.0 * nf)).sin())
        .collect();
    let w: Vec<f64> = (0..m)
        .map(|k| {
            let c = if k == 0 || k == n { 1.0 } else { 2.0 };
            let mut s = 1.0;
            for j in 1..=n / 2 {
                let b = if 2 * j == n { 1.0 } else { 2.0 };
                let jf = j as f64;
                s -= b * (2.0 * jf * k as f64 * pi / nf).cos() / (4.0 * jf * jf - 1.0);
            }
            c * s / (2.0 * nf)
        })
        .collect();
    (x, w)
}

/// Genz-Keister rule of level `level` (0..5) for `N(0, 1)`: ascending nodes and probability
/// weights.
///
/// # Errors
/// If `level >= 5` (the family stops at 35 nodes).
pub fn genz_keister(level: usize) -> Result<(Vec<f64>, Vec<f64>)> {
    if level >= GENZ_KEISTER_LEVELS {
        return Err(UqError::Invalid {
            what: "Genz-Keister rule",
            message: format!(
                "level {level} does not exist (levels 0 to {} have 1, 3, 9, 19, 35 nodes)",
                GENZ_KEISTER_LEVELS - 1
            ),
        });
    }
    let mut pos: Vec<f64> = GK_NODES
        .iter()
        .filter(|(_, l)| *l <= level)
        .map(|(x, _)| x * std::f64::consts::SQRT_2)
        .collect();
    pos.sort_by(f64::total_cmp);
    // Unknowns: centre weight and the weight of each +-x pair (2 w); equations: the even
    // orthonormal Hermite polynomials p_0, p_2, ..., p_{2 m} integrate to delta_i0.
    let m = pos.len() + 1;
    let he = OrthoPoly::hermite(2 * m + 1, 0.0, 1.0);
    let mut vals = vec![0.0; 2 * m - 1];
    // Row-major m x m matrix V[i][j] = p_2i(node_j).
    let mut v = vec![0.0; m * m];
    for (j, &x) in std::iter::once(&0.0).chain(pos.iter()).enumerate() {
        he.eval_all(x, &mut vals);
        for i in 0..m {
            v[i * m + j] = vals[2 * i];
        }
    }
    // V w = e_0  <=>  w = V^-1 e_0: the projector of the square V is its inverse.
    let inv = least_squares_projector("Genz-Keister weights", &v, m, m)?;
    let wpair: Vec<f64> = (0..m).map(|j| inv.a[j * m]).collect();
    let mut nodes = Vec::with_capacity(2 * m - 1);
    let mut weights = Vec::with_capacity(2 * m - 1);
    for (x, w) in pos.iter().zip(&wpair[1..]).rev() {
        nodes.push(-x);
        weights.push(0.5 * w);
    }
    nodes.push(0.0);
    weights.push(wpair[0]);
    for (x, w) in pos.iter().zip(&wpair[1..]) {
        nodes.push(*x);
        weights.push(0.5 * w);
    }
    Ok((nodes, weights))
}
