//! Quadrature rules for expectations `E[g(X)] ~= sum_q w_q g(x_q)` under independent marginals.
//!
//! * [`QuadratureRule::tensor_gauss`]: tensor product of the Gauss rules of each marginal
//!   (Golub-Welsch, see [`OrthoPoly::gauss`]); `n` points per variable integrate exactly the
//!   polynomials of degree `2n - 1` in each variable.
//! * [`QuadratureRule::smolyak`]: Smolyak sparse grid of level `l` built on Gauss rules with
//!   `m(i) = i` points, by the combination technique
//!   `A(l, d) = sum_{l - d + 1 <= |i| <= l} (-1)^(l - |i|) C(d - 1, l - |i|) (Q_{i_1} x ... x Q_{i_d})`,
//!   coincident nodes merged within a tolerance (the centres of odd Gauss rules);
//! * [`QuadratureRule::smolyak_nested`]: the same on nested rules (Clenshaw-Curtis for uniform,
//!   Genz-Keister for normal marginals, see [`clenshaw_curtis`], [`genz_keister`]), far fewer
//!   nodes for the same level since coarse nodes are re-used.
//! * [`QuadratureRule::gauss_legendre_box`]: tensor Gauss-Legendre on a box for plain integrals.

mod nested;

pub use nested::{
    GENZ_KEISTER_LEVELS, clenshaw_curtis, clenshaw_curtis_size, genz_keister, genz_keister_size,
};

use crate::basis::OrthoPoly;
use crate::error::{Result, UqError};
use crate::law::{Marginal, PolyFamily};
use std::collections::HashMap;
use std::sync::Arc;

/// Nodes (row-major `len x dim`) and weights.
#[derive(Debug, Clone, PartialEq)]
pub struct QuadratureRule {
    dim: usize,
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl QuadratureRule {
    /// Build from raw nodes and weights.
    ///
    /// # Errors
    /// If the lengths are inconsistent.
    pub fn new(dim: usize, nodes: Vec<f64>, weights: Vec<f64>) -> Result<Self> {
        crate::error::check_len("quadrature rule", "nodes", weights.len() * dim, nodes.len())?;
        Ok(Self {
            dim,
            nodes,
            weights,
        })
    }

    /// Tensor product of `orders[j]`-point Gauss rules of the marginals.
    ///
    /// # Errors
    /// If lengths differ, an order is 0, or polynomial generation fails.
    pub fn tensor_gauss(marginals: &[Arc<dyn Marginal>], orders: &[usize]) -> Result<Self> {
        crate::error::check_len("tensor Gauss rule", "orders", marginals.len(), orders.len())?;
        let rules = marginals
            .iter()
            .zip(orders)
            .map(|(m, &n)| {
                if n == 0 {
                    return Err(crate::error::invalid(
                        "tensor Gauss rule",
                        "order",
                        ">= 1",
                        0.0,
                    ));
                }
                Ok(OrthoPoly::for_marginal(m.as_ref(), n)?.gauss(n))
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(tensor(&rules))
    }

    /// Smolyak sparse grid of level `level >= dim` on Gauss rules with `m(i) = i` points
    /// (level `dim` is the single centre point); exact for total degree `2 (level - dim) + 1`.
    ///
    /// # Errors
    /// If `level < dim` or polynomial generation fails.
    pub fn smolyak(marginals: &[Arc<dyn Marginal>], level: usize) -> Result<Self> {
        let d = marginals.len();
        if level < d || d == 0 {
            return Err(crate::error::invalid(
                "Smolyak rule",
                "level",
                ">= dimension",
                level as f64,
            ));
        }
        let maxn = level - d + 1;
        let rules1d = marginals
            .iter()
            .map(|m| {
                let p = OrthoPoly::for_marginal(m.as_ref(), maxn)?;
                Ok((1..=maxn).map(|n| p.gauss(n)).collect())
            })
            .collect::<Result<Vec<Vec<Rule1d>>>>()?;
        Ok(smolyak_combination(&rules1d, level - d))
    }

    /// Smolyak sparse grid of level `level >= 0` (0 is the single centre point) on **nested**
    /// rules: Clenshaw-Curtis (1, 3, 5, 9, 17, ... nodes) for uniform marginals, Genz-Keister
    /// (1, 3, 9, 19, 35 nodes, so `level <= 4` when a marginal is normal) for normal ones. The
    /// grid is the union of the nodes of its tensor rules with nothing duplicated; its size is
    /// `sum_{|l| <= level} prod_j (m(l_j) - m(l_j - 1))`.
    ///
    /// # Errors
    /// If a marginal is neither uniform nor normal, or `level` exceeds the Genz-Keister family.
    pub fn smolyak_nested(marginals: &[Arc<dyn Marginal>], level: usize) -> Result<Self> {
        if marginals.is_empty() {
            return Err(crate::error::invalid(
                "nested Smolyak rule",
                "dimension",
                ">= 1",
                0.0,
            ));
        }
        let rules1d = marginals
            .iter()
            .map(|m| match m.poly_family() {
                Some(PolyFamily::Legendre { a, b }) => Ok((0..=level)
                    .map(|l| {
                        let (x, w) = nested::clenshaw_curtis(l);
                        (
                            x.iter()
                                .map(|t| 0.5 * (a + b) + 0.5 * (b - a) * t)
                                .collect(),
                            w,
                        )
                    })
                    .collect()),
                Some(PolyFamily::Hermite { mean, std }) => (0..=level)
                    .map(|l| {
                        let (x, w) = nested::genz_keister(l)?;
                        Ok((x.iter().map(|t| mean + std * t).collect(), w))
                    })
                    .collect::<Result<Vec<Rule1d>>>(),
                _ => Err(UqError::Invalid {
                    what: "nested Smolyak rule",
                    message: format!(
                        "no nested rule for the {} law (uniform: Clenshaw-Curtis, normal: \
                         Genz-Keister; use `smolyak` with Gauss rules otherwise)",
                        m.name()
                    ),
                }),
            })
            .collect::<Result<Vec<Vec<Rule1d>>>>()?;
        Ok(smolyak_combination(&rules1d, level))
    }

    /// Tensor Gauss-Legendre rule with `n` points per direction on the box `[lo, hi]`; the
    /// weights sum to the volume of the box.
    ///
    /// # Errors
    /// If `lo` and `hi` differ in length or `n == 0`.
    pub fn gauss_legendre_box(lo: &[f64], hi: &[f64], n: usize) -> Result<Self> {
        crate::error::check_len("Gauss-Legendre box rule", "hi", lo.len(), hi.len())?;
        if n == 0 {
            return Err(UqError::Invalid {
                what: "Gauss-Legendre box rule",
                message: "needs at least one point".into(),
            });
        }
        let rules: Vec<(Vec<f64>, Vec<f64>)> = lo
            .iter()
            .zip(hi)
            .map(|(&a, &b)| {
                let (x, w) = OrthoPoly::legendre(n, a, b).gauss(n);
                (x, w.iter().map(|v| v * (b - a)).collect())
            })
            .collect();
        Ok(tensor(&rules))
    }

    /// The rule without the nodes whose weight vanishes (`|w_q| <= rel_tol sum |w|`), and the
    /// number removed. Sparse grids can have such nodes (the centre of the 3-D Clenshaw-Curtis
    /// grid of level 1: `3 (2/3) - 2 = 0`); a model run there adds nothing to a projection.
    pub fn without_zero_weights(&self, rel_tol: f64) -> (Self, usize) {
        let wsum: f64 = self.weights.iter().map(|w| w.abs()).sum();
        let mut nodes = Vec::with_capacity(self.nodes.len());
        let mut weights = Vec::with_capacity(self.weights.len());
        for q in 0..self.len() {
            if self.weights[q].abs() > rel_tol * wsum {
                nodes.extend_from_slice(self.node(q));
                weights.push(self.weights[q]);
            }
        }
        let removed = self.len() - weights.len();
        (
            Self {
                dim: self.dim,
                nodes,
                weights,
            },
            removed,
        )
    }

    /// Number of variables.
    pub fn dim(&self) -> usize {
        self.dim
    }
    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.weights.len()
    }
    /// `true` if there are no nodes.
    pub fn is_empty(&self) -> bool {
        self.weights.is_empty()
    }
    /// Node `q`.
    pub fn node(&self, q: usize) -> &[f64] {
        &self.nodes[q * self.dim..(q + 1) * self.dim]
    }
    /// All nodes, row-major `len x dim`.
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }
    /// Weights.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }
    /// `sum_q w_q f(x_q)`.
    pub fn integrate(&self, f: impl Fn(&[f64]) -> f64) -> f64 {
        (0..self.len())
            .map(|q| self.weights[q] * f(self.node(q)))
            .sum()
    }
}

/// One-dimensional rule: nodes and weights.
type Rule1d = (Vec<f64>, Vec<f64>);

/// Smolyak combination of the one-dimensional rule sequences `rules[j][l]` (level `l = 0, 1,
/// ...` in variable `j`) at level `big_l`:
/// `A = sum_{big_l - d + 1 <= |l| <= big_l} (-1)^(big_l - |l|) C(d - 1, big_l - |l|) Q_l1 x ... x Q_ld`.
///
/// Coincident nodes are merged in each variable first: the one-dimensional nodes of all levels
/// are sorted and those closer than `1e-10` times the spread of the nodes share an index (so
/// the centre of odd Gauss rules, `-3e-16` in one rule and `0` in another, is one node); a
/// multi-dimensional node is the tuple of these indices. The coordinates kept are those first
/// met, in level order. Nodes whose weights cancel are kept (the known grid sizes count them);
/// [`QuadratureRule::without_zero_weights`] removes them.
fn smolyak_combination(rules: &[Vec<Rule1d>], big_l: usize) -> QuadratureRule {
    let d = rules.len();
    // Per-variable node ids, in level order of first appearance.
    let mut ids: Vec<Vec<Vec<u32>>> = Vec::with_capacity(d);
    let mut reps: Vec<Vec<f64>> = Vec::with_capacity(d);
    for seq in rules {
        let all: Vec<(f64, usize)> = seq
            .iter()
            .take(big_l + 1)
            .flat_map(|r| r.0.iter().copied())
            .enumerate()
            .map(|(i, x)| (x, i))
            .collect();
        let lo = all.iter().map(|a| a.0).fold(f64::INFINITY, f64::min);
        let hi = all.iter().map(|a| a.0).fold(f64::NEG_INFINITY, f64::max);
        let tol = 1e-10 * (hi - lo).max(f64::MIN_POSITIVE);
        let mut sorted = all.clone();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        // Cluster, labelled by the smallest first-appearance position in the cluster.
        let mut label = vec![0usize; all.len()];
        let mut start = 0;
        while start < sorted.len() {
            let mut end = start + 1;
            while end < sorted.len() && sorted[end].0 - sorted[end - 1].0 <= tol {
                end += 1;
            }
            let first = sorted[start..end].iter().map(|a| a.1).min().unwrap_or(0);
            for a in &sorted[start..end] {
                label[a.1] = first;
            }
            start = end;
        }
        // Compact ids in order of first appearance.
        let mut compact = std::collections::HashMap::new();
        let mut rep = Vec::new();
        let mut pos = 0;
        let mut per_level = Vec::new();
        for r in seq.iter().take(big_l + 1) {
            let mut v = Vec::with_capacity(r.0.len());
            for _ in 0..r.0.len() {
                let l = label[pos];
                let id = *compact.entry(l).or_insert_with(|| {
                    rep.push(all[l].0);
                    rep.len() as u32 - 1
                });
                v.push(id);
                pos += 1;
            }
            per_level.push(v);
        }
        ids.push(per_level);
        reps.push(rep);
    }
    let mut map: HashMap<Vec<u32>, usize> = HashMap::new();
    let mut keys: Vec<Vec<u32>> = Vec::new();
    let mut weights: Vec<f64> = Vec::new();
    let mut l = vec![0usize; d];
    loop {
        let s: usize = l.iter().sum();
        if s + d > big_l {
            let k = big_l - s;
            let coef = if k.is_multiple_of(2) { 1.0 } else { -1.0 } * binom(d - 1, k);
            // Tensor product of the rules l_j, as id tuples.
            let sizes: Vec<usize> = (0..d).map(|j| rules[j][l[j]].1.len()).collect();
            let total: usize = sizes.iter().product();
            let mut idx = vec![0usize; d];
            for _ in 0..total {
                let mut w = coef;
                let key: Vec<u32> = (0..d)
                    .map(|j| {
                        w *= rules[j][l[j]].1[idx[j]];
                        ids[j][l[j]][idx[j]]
                    })
                    .collect();
                match map.get(&key) {
                    Some(&i) => weights[i] += w,
                    None => {
                        map.insert(key.clone(), weights.len());
                        keys.push(key);
                        weights.push(w);
                    }
                }
                for j in (0..d).rev() {
                    idx[j] += 1;
                    if idx[j] < sizes[j] {
                        break;
                    }
                    idx[j] = 0;
                }
            }
        }
        // Next multi-index with |l| <= big_l.
        let mut j = 0;
        loop {
            if j == d {
                let mut nodes = Vec::with_capacity(keys.len() * d);
                for key in &keys {
                    nodes.extend(key.iter().enumerate().map(|(j, &id)| reps[j][id as usize]));
                }
                return QuadratureRule {
                    dim: d,
                    nodes,
                    weights,
                };
            }
            l[j] += 1;
            if l.iter().sum::<usize>() <= big_l {
                break;
            }
            l[j] = 0;
            j += 1;
        }
    }
}

fn binom(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

fn tensor(rules: &[(Vec<f64>, Vec<f64>)]) -> QuadratureRule {
    let d = rules.len();
    let total: usize = rules.iter().map(|r| r.1.len()).product();
    let mut nodes = Vec::with_capacity(total * d);
    let mut weights = Vec::with_capacity(total);
    let mut idx = vec![0usize; d];
    for _ in 0..total {
        let mut w = 1.0;
        for j in 0..d {
            nodes.push(rules[j].0[idx[j]]);
            w *= rules[j].1[idx[j]];
        }
        weights.push(w);
        for j in (0..d).rev() {
            idx[j] += 1;
            if idx[j] < rules[j].1.len() {
                break;
            }
            idx[j] = 0;
        }
    }
    QuadratureRule {
        dim: d,
        nodes,
        weights,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::{Normal, Uniform};

    #[test]
    fn smolyak_integrates_polynomials() {
        let m: Vec<Arc<dyn Marginal>> = vec![
            Arc::new(Normal::new(0.0, 1.0).unwrap()),
            Arc::new(Uniform::new(-1.0, 1.0).unwrap()),
            Arc::new(Normal::new(0.0, 1.0).unwrap()),
        ];
        // Level 3 + 3: exact for total degree 2*3 - 1 = 5 polynomials.
        let r = QuadratureRule::smolyak(&m, 6).unwrap();
        assert!((r.weights().iter().sum::<f64>() - 1.0).abs() < 1e-13);
        let v = r.integrate(|x| x[0].powi(4) + x[1].powi(2) * x[2].powi(2) + x[0] * x[1]);
        assert!((v - (3.0 + 1.0 / 3.0)).abs() < 1e-12, "{v}");
        // In 5 variables the sparse grid exact to total degree 5 is much smaller than the
        // tensor rule exact to degree 5 per variable.
        let m5: Vec<Arc<dyn Marginal>> = (0..5)
            .map(|_| Arc::new(Uniform::new(0.0, 1.0).unwrap()) as Arc<dyn Marginal>)
            .collect();
        let r5 = QuadratureRule::smolyak(&m5, 7).unwrap();
        assert!(r5.len() < 3usize.pow(5) / 2, "{}", r5.len());
        let v = r5.integrate(|x| x[0].powi(3) * x[1] * x[4] + x[2].powi(5));
        assert!((v - (1.0 / 16.0 + 1.0 / 6.0)).abs() < 1e-13);
    }
}
