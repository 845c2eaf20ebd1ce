//! Quadrature rules for expectations `E[g(X)] ~= sum_q w_q g(x_q)` under independent marginals.
//!
//! * [`QuadratureRule::tensor_gauss`]: tensor product of the Gauss rules of each marginal
//!   (Golub-Welsch, see [`OrthoPoly::gauss`]); `n` points per variable integrate exactly the
//!   polynomials of degree `2n - 1` in each variable.
//! * [`QuadratureRule::smolyak`]: Smolyak sparse grid of level `l` built on Gauss rules with
//!   `m(i) = i` points, by the combination technique
//!   `A(l, d) = sum_{l - d + 1 <= |i| <= l} (-1)^(l - |i|) C(d - 1, l - |i|) (Q_{i_1} x ... x Q_{i_d})`,
//!   nodes merged when coincident.
//! * [`QuadratureRule::gauss_legendre_box`]: tensor Gauss-Legendre on a box for plain integrals.

use crate::basis::OrthoPoly;
use crate::error::{Result, UqError};
use crate::law::Marginal;
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

    /// Smolyak sparse grid of level `level >= dim` (level `dim` is the single centre point).
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
        let polys = marginals
            .iter()
            .map(|m| OrthoPoly::for_marginal(m.as_ref(), maxn))
            .collect::<Result<Vec<_>>>()?;
        let rules1d: Vec<Vec<(Vec<f64>, Vec<f64>)>> = polys
            .iter()
            .map(|p| (1..=maxn).map(|n| p.gauss(n)).collect())
            .collect();
        let mut map: HashMap<Vec<u64>, usize> = HashMap::new();
        let mut nodes = Vec::new();
        let mut weights: Vec<f64> = Vec::new();
        let mut idx = vec![1usize; d];
        loop {
            let s: usize = idx.iter().sum();
            if s + d > level && s <= level {
                let k = level - s;
                let coef = if k.is_multiple_of(2) { 1.0 } else { -1.0 } * binom(d - 1, k);
                let rules: Vec<(Vec<f64>, Vec<f64>)> =
                    (0..d).map(|j| rules1d[j][idx[j] - 1].clone()).collect();
                let t = tensor(&rules);
                for q in 0..t.len() {
                    let x = t.node(q);
                    let key: Vec<u64> = x.iter().map(|v| (v + 0.0).to_bits()).collect();
                    let w = coef * t.weights[q];
                    match map.get(&key) {
                        Some(&i) => weights[i] += w,
                        None => {
                            map.insert(key, weights.len());
                            nodes.extend_from_slice(x);
                            weights.push(w);
                        }
                    }
                }
            }
            // next multi-index with entries >= 1 and sum <= level
            let mut j = 0;
            loop {
                if j == d {
                    return Ok(Self {
                        dim: d,
                        nodes,
                        weights,
                    });
                }
                idx[j] += 1;
                if idx.iter().sum::<usize>() <= level {
                    break;
                }
                idx[j] = 1;
                j += 1;
            }
        }
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
