//! The product of independent blocks of variables: `X = (X_1, .., X_B)` with the blocks
//! mutually independent and each block `X_b` of any joint law (a copula, a density, independent
//! marginals). It is how a study joins the copula of its `[[parameter]]`s to the independent
//! standard normal KL variables of its random fields.
//!
//! With `x = (x_1, .., x_B)` split by the blocks' dimensions:
//!
//! ```text
//! f(x) = prod_b f_b(x_b),    T(x) = (T_1(x_1), .., T_B(x_B)),
//! ```
//!
//! for the maps to the unit cube and to independent standard normal variables alike (each block
//! keeps its own: the Nataf map of a Gaussian copula stays the Nataf map), and the probability of
//! a box is the product of the blocks' probabilities.

use std::sync::Arc;

use rand::RngCore;

use super::JointLaw;
use crate::error::{Result, invalid};

/// Mutually independent blocks of variables, each with its own joint law.
#[derive(Debug, Clone)]
pub struct ProductJoint {
    blocks: Vec<Arc<dyn JointLaw>>,
    /// `offsets[b]..offsets[b + 1]`: the variables of block `b`.
    offsets: Vec<usize>,
}

impl ProductJoint {
    /// # Errors
    /// If there is no block or a block has no variable.
    pub fn new(blocks: Vec<Arc<dyn JointLaw>>) -> Result<Self> {
        if blocks.is_empty() {
            return Err(invalid("product joint law", "blocks", "at least one", 0.0));
        }
        let mut offsets = vec![0];
        for b in &blocks {
            if b.dim() == 0 {
                return Err(invalid("product joint law", "block dimension", ">= 1", 0.0));
            }
            offsets.push(offsets.last().copied().unwrap_or(0) + b.dim());
        }
        Ok(Self { blocks, offsets })
    }

    /// The blocks.
    pub fn blocks(&self) -> &[Arc<dyn JointLaw>] {
        &self.blocks
    }

    fn range(&self, b: usize) -> std::ops::Range<usize> {
        self.offsets[b]..self.offsets[b + 1]
    }
}

impl JointLaw for ProductJoint {
    fn dim(&self) -> usize {
        self.offsets[self.blocks.len()]
    }
    fn pdf(&self, x: &[f64]) -> f64 {
        let mut p = 1.0;
        for (b, law) in self.blocks.iter().enumerate() {
            p *= law.pdf(&x[self.range(b)]);
            if p == 0.0 {
                return 0.0;
            }
        }
        p
    }
    fn x_to_unit(&self, x: &[f64], u: &mut [f64]) {
        for (b, law) in self.blocks.iter().enumerate() {
            let r = self.range(b);
            law.x_to_unit(&x[r.clone()], &mut u[r]);
        }
    }
    fn unit_to_x(&self, u: &[f64], x: &mut [f64]) {
        for (b, law) in self.blocks.iter().enumerate() {
            let r = self.range(b);
            law.unit_to_x(&u[r.clone()], &mut x[r]);
        }
    }
    fn x_to_standard_normal(&self, x: &[f64], y: &mut [f64]) {
        for (b, law) in self.blocks.iter().enumerate() {
            let r = self.range(b);
            law.x_to_standard_normal(&x[r.clone()], &mut y[r]);
        }
    }
    fn standard_normal_to_x(&self, y: &[f64], x: &mut [f64]) {
        for (b, law) in self.blocks.iter().enumerate() {
            let r = self.range(b);
            law.standard_normal_to_x(&y[r.clone()], &mut x[r]);
        }
    }
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        let (mut lo, mut hi) = (Vec::new(), Vec::new());
        for law in &self.blocks {
            let (a, b) = law.bounds();
            lo.extend(a);
            hi.extend(b);
        }
        (lo, hi)
    }
    fn is_independent(&self) -> bool {
        self.blocks.iter().all(|b| b.is_independent())
    }
    fn sample(&self, rng: &mut dyn RngCore, x: &mut [f64]) {
        for (b, law) in self.blocks.iter().enumerate() {
            law.sample(rng, &mut x[self.range(b)]);
        }
    }
    fn box_probability(&self, lo: &[f64], hi: &[f64]) -> f64 {
        self.blocks
            .iter()
            .enumerate()
            .map(|(b, law)| law.box_probability(&lo[self.range(b)], &hi[self.range(b)]))
            .product()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::joint::{GaussianCopula, Independent};
    use crate::law::{Marginal, Normal, Uniform};
    use crate::special::norm_cdf;

    fn blocks() -> (Arc<dyn JointLaw>, Arc<dyn JointLaw>) {
        let m: Vec<Arc<dyn Marginal>> = vec![
            Arc::new(Uniform::new(1.0, 3.0).unwrap()),
            Arc::new(Normal::new(2.0, 0.5).unwrap()),
        ];
        let copula = GaussianCopula::new(m, vec![1.0, 0.6, 0.6, 1.0]).unwrap();
        let normals: Vec<Arc<dyn Marginal>> = vec![
            Arc::new(Normal::new(0.0, 1.0).unwrap()),
            Arc::new(Normal::new(0.0, 1.0).unwrap()),
            Arc::new(Normal::new(0.0, 1.0).unwrap()),
        ];
        (
            Arc::new(copula),
            Arc::new(Independent::new(normals).unwrap()),
        )
    }

    /// Density, maps and box probabilities are the blocks' own, concatenated or multiplied.
    #[test]
    fn a_product_is_its_blocks_side_by_side() {
        let (a, b) = blocks();
        let p = ProductJoint::new(vec![a.clone(), b.clone()]).unwrap();
        assert_eq!(p.dim(), 5);
        assert!(!p.is_independent());
        let x = [1.7, 2.4, -0.3, 1.1, 0.2];
        assert_eq!(p.pdf(&x), a.pdf(&x[..2]) * b.pdf(&x[2..]));
        let (mut y, mut ya, mut yb) = ([0.0; 5], [0.0; 2], [0.0; 3]);
        p.x_to_standard_normal(&x, &mut y);
        a.x_to_standard_normal(&x[..2], &mut ya);
        b.x_to_standard_normal(&x[2..], &mut yb);
        assert_eq!(&y[..2], &ya);
        assert_eq!(&y[2..], &yb);
        let mut back = [0.0; 5];
        p.standard_normal_to_x(&y, &mut back);
        for (u, v) in back.iter().zip(&x) {
            assert!((u - v).abs() < 1e-12, "{back:?} {x:?}");
        }
        let mut u = [0.0; 5];
        p.x_to_unit(&x, &mut u);
        p.unit_to_x(&u, &mut back);
        for (u, v) in back.iter().zip(&x) {
            assert!((u - v).abs() < 1e-12);
        }
        // The KL block's box probability is exact: prod (Phi(b) - Phi(a)).
        let (lo, hi) = ([1.0, 0.0, -1.0, -1.0, -1.0], [3.0, 4.0, 1.0, 1.0, 1.0]);
        let normal_part = (norm_cdf(1.0) - norm_cdf(-1.0)).powi(3);
        let pb = p.box_probability(&lo, &hi);
        assert!((pb - a.box_probability(&lo[..2], &hi[..2]) * normal_part).abs() < 1e-12);
        assert!(ProductJoint::new(vec![]).is_err());
    }

    /// Draws: the copula block keeps its correlation, the blocks are uncorrelated.
    #[test]
    fn draws_keep_the_blocks_dependence_and_nothing_across_them() {
        use rand::SeedableRng;
        let (a, b) = blocks();
        let p = ProductJoint::new(vec![a, b]).unwrap();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let n = 40_000;
        let mut z = vec![[0.0; 5]; n];
        for row in z.iter_mut() {
            let mut x = [0.0; 5];
            p.sample(&mut rng, &mut x);
            // Back to the normal scores of the copula block (Phi^-1(F(x))) and the KL normals.
            p.x_to_unit(&x, row);
            for v in row.iter_mut() {
                *v = crate::special::norm_quantile(*v);
            }
            // x_to_unit of the Gaussian copula gives Phi(L^-1 z): undo L^-1 on the first block.
            let l10 = 0.6;
            let l11 = (1.0f64 - 0.36).sqrt();
            row[1] = l10 * row[0] + l11 * row[1];
        }
        let corr = |i: usize, j: usize| {
            let (mi, mj) = (
                z.iter().map(|r| r[i]).sum::<f64>() / n as f64,
                z.iter().map(|r| r[j]).sum::<f64>() / n as f64,
            );
            let c: f64 = z.iter().map(|r| (r[i] - mi) * (r[j] - mj)).sum();
            let si: f64 = z.iter().map(|r| (r[i] - mi).powi(2)).sum();
            let sj: f64 = z.iter().map(|r| (r[j] - mj).powi(2)).sum();
            c / (si * sj).sqrt()
        };
        // Standard error of a sample correlation near 0: 1 / sqrt(n) = 0.005.
        assert!((corr(0, 1) - 0.6).abs() < 0.02, "{}", corr(0, 1));
        for i in 0..2 {
            for j in 2..5 {
                assert!(corr(i, j).abs() < 0.025, "corr({i}, {j}) = {}", corr(i, j));
            }
        }
    }
}
