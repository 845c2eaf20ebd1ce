//! The weights of the surrogate: nodes resolved on runs, evaluation, and the expectations of
//! the weights over a law (cell probabilities, expected weights, second moments).

use super::*;

impl StochasticMesh {
    /// Resolve the weights of every node on runs and cache, per leaf, `(corner, run, coef)`.
    pub(super) fn rebuild(&mut self) -> Result<()> {
        let mut memo: HashMap<Key, Vec<(usize, f64)>> = HashMap::new();
        let d = self.d;
        let mut leaf_terms = vec![(0u32, 0u32); self.cells.len()];
        let mut terms = Vec::new();
        let mut nl = 0;
        for c in 0..self.cells.len() {
            if self.cells[c].first_child.is_some() {
                continue;
            }
            nl += 1;
            let start = terms.len() as u32;
            let o = self.cells[c].origin;
            for corner in 0..(1usize << d) {
                let mut key = o;
                for j in 0..d {
                    if (corner >> j) & 1 == 1 {
                        key[j] += self.size(c, j);
                    }
                }
                let w = self.resolve(&key, &mut memo, 0)?;
                for &(run, coef) in &w {
                    terms.push((corner as u8, run as u32, coef));
                }
            }
            leaf_terms[c] = (start, terms.len() as u32);
        }
        self.leaf_terms = leaf_terms;
        self.terms = terms;
        self.num_leaves = nl;
        Ok(())
    }

    pub(super) fn resolve(
        &self,
        key: &Key,
        memo: &mut HashMap<Key, Vec<(usize, f64)>>,
        depth: u32,
    ) -> Result<Vec<(usize, f64)>> {
        if let Some(v) = memo.get(key) {
            return Ok(v.clone());
        }
        let kind = self
            .nodes
            .get(key)
            .copied()
            .ok_or_else(|| UqError::Invalid {
                what: "stochastic mesh",
                message: "internal error: missing node".into(),
            })?;
        let out = match kind {
            NodeKind::Run(k) => vec![(k, 1.0)],
            NodeKind::Hanging(m) | NodeKind::Fixed(m) => {
                // A guard against cycles: a chain of interpolated nodes has at most a few steps
                // per level and direction.
                if depth > (MAX_LEVEL + 2) * self.d as u32 || m == usize::MAX {
                    return Err(UqError::Invalid {
                        what: "stochastic mesh",
                        message: "internal error: unresolved hanging node".into(),
                    });
                }
                let o = self.cells[m].origin;
                let mut acc: Vec<(usize, f64)> = Vec::new();
                for corner in 0..(1usize << self.d) {
                    let mut phi = 1.0;
                    let mut ck = o;
                    for j in 0..self.d {
                        let t = (key[j] - o[j]) as f64 / self.size(m, j) as f64;
                        if (corner >> j) & 1 == 1 {
                            phi *= t;
                            ck[j] += self.size(m, j);
                        } else {
                            phi *= 1.0 - t;
                        }
                    }
                    if phi == 0.0 {
                        continue;
                    }
                    for (run, w) in self.resolve(&ck, memo, depth + 1)? {
                        match acc.iter_mut().find(|e| e.0 == run) {
                            Some(e) => e.1 += phi * w,
                            None => acc.push((run, phi * w)),
                        }
                    }
                }
                acc
            }
        };
        memo.insert(*key, out.clone());
        Ok(out)
    }

    /// Fast evaluation (no allocation): `sum_k w_k(xi) values[k]`; `NaN` outside the box.
    ///
    /// # Panics
    /// If `values.len() < num_runs()` or `xi.len() < dim()`.
    #[inline]
    pub fn interpolate(&self, xi: &[f64], values: &[f64]) -> f64 {
        let mut t = [0.0; MAX_DIM];
        let Some(c) = self.locate_local(xi, &mut t[..self.d]) else {
            return f64::NAN;
        };
        let mut phi = [0.0; 1 << MAX_DIM];
        self.corner_phi(&t, &mut phi);
        let (a, b) = self.leaf_terms[c];
        self.terms[a as usize..b as usize]
            .iter()
            .map(|&(corner, run, coef)| phi[corner as usize] * coef * values[run as usize])
            .sum()
    }

    #[inline]
    pub(super) fn corner_phi(&self, t: &[f64], phi: &mut [f64; 1 << MAX_DIM]) {
        phi[0] = 1.0;
        let mut n = 1;
        for &tj in t.iter().take(self.d) {
            for c in 0..n {
                phi[c + n] = phi[c] * tj;
                phi[c] *= 1.0 - tj;
            }
            n *= 2;
        }
    }

    /// Probability of each leaf cell under `law` (`(cell, P(xi in cell))`, leaves in id order).
    pub fn cell_probabilities(&self, law: &dyn JointLaw) -> Vec<(CellId, f64)> {
        self.leaves()
            .into_iter()
            .map(|c| {
                let (a, b) = self.cell_bounds(c);
                (c, law.box_probability(&a, &b))
            })
            .collect()
    }

    /// Integral of `f` over each leaf cell with an `order`-point tensor Gauss-Legendre rule
    /// (`(cell, int_cell f)`), e.g. `f = error density * pdf` for the refinement criterion.
    ///
    /// # Errors
    /// If `order == 0`.
    pub fn integrate_cells(
        &self,
        f: impl Fn(&[f64]) -> f64 + Sync,
        order: usize,
    ) -> Result<Vec<(CellId, f64)>> {
        use rayon::prelude::*;
        self.leaves()
            .into_par_iter()
            .map(|c| {
                let (a, b) = self.cell_bounds(c);
                Ok((
                    c,
                    QuadratureRule::gauss_legendre_box(&a, &b, order)?.integrate(&f),
                ))
            })
            .collect()
    }

    /// Expected weights `E[w_k(xi)] = int w_k(x) f(x) dx` under a density `pdf` on the box, by
    /// an `order`-point Gauss-Legendre rule per leaf, so that `E[q~] = sum_k E[w_k] q_k`.
    ///
    /// # Errors
    /// If `order == 0`.
    pub fn expected_weights(
        &self,
        pdf: impl Fn(&[f64]) -> f64 + Sync,
        order: usize,
    ) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.num_runs()];
        self.for_each_leaf_point(pdf, order, |f, w| {
            for &(k, wk) in w {
                out[k] += f * wk;
            }
        })?;
        Ok(out)
    }

    /// Second moments of the weights, `M_kl = E[w_k(xi) w_l(xi)] = int w_k w_l f dx`, under a
    /// density `pdf` on the box (`order`-point Gauss-Legendre per leaf; `order = 2` is exact for
    /// a piecewise-constant density). Returned sparse, as `(k, l, M_kl)` with `k <= l`, sorted.
    /// Then `E[q~^2] = sum_kl M_kl q_k q_l` and, for a field or an energy with Gram matrix
    /// `G_kl = <u_k, u_l>`, `E[||u~||^2] = sum_kl M_kl G_kl` (counting `k != l` twice).
    ///
    /// # Errors
    /// If `order == 0`.
    pub fn weight_second_moments(
        &self,
        pdf: impl Fn(&[f64]) -> f64 + Sync,
        order: usize,
    ) -> Result<Vec<(usize, usize, f64)>> {
        let mut acc: HashMap<(usize, usize), f64> = HashMap::new();
        self.for_each_leaf_point(pdf, order, |f, w| {
            for &(k, wk) in w {
                for &(l, wl) in w {
                    if k <= l {
                        *acc.entry((k, l)).or_insert(0.0) += f * wk * wl;
                    }
                }
            }
        })?;
        let mut out: Vec<(usize, usize, f64)> =
            acc.into_iter().map(|((k, l), v)| (k, l, v)).collect();
        out.sort_unstable_by_key(|e| (e.0, e.1));
        Ok(out)
    }

    /// Visits every point of an `order`-point Gauss-Legendre rule per leaf where
    /// `f = rule weight * pdf(x)` is not zero, with `f` and the weights `w_k(x)` there.
    fn for_each_leaf_point(
        &self,
        pdf: impl Fn(&[f64]) -> f64,
        order: usize,
        mut visit: impl FnMut(f64, &[(usize, f64)]),
    ) -> Result<()> {
        let mut w = Vec::new();
        for c in self.leaves() {
            let (a, b) = self.cell_bounds(c);
            let r = QuadratureRule::gauss_legendre_box(&a, &b, order)?;
            for q in 0..r.len() {
                let x = r.node(q);
                let f = r.weights()[q] * pdf(x);
                if f == 0.0 {
                    continue;
                }
                self.cell_weights(c, x, &mut w);
                visit(f, &w);
            }
        }
        Ok(())
    }

    pub(super) fn cell_weights(&self, c: CellId, xi: &[f64], w: &mut Vec<(usize, f64)>) {
        w.clear();
        let o = self.cells[c].origin;
        let mut t = [0.0; MAX_DIM];
        let hi = self.far_corner(c);
        let (pl, ph) = (self.key_point(&o), self.key_point(&hi));
        for j in 0..self.d {
            t[j] = ((xi[j] - pl[j]) / (ph[j] - pl[j])).clamp(0.0, 1.0);
        }
        let mut phi = [0.0; 1 << MAX_DIM];
        self.corner_phi(&t[..self.d], &mut phi);
        let (a, b) = self.leaf_terms[c];
        for &(corner, run, coef) in &self.terms[a as usize..b as usize] {
            let v = phi[corner as usize] * coef;
            if v == 0.0 {
                continue;
            }
            match w.iter_mut().find(|e| e.0 == run as usize) {
                Some(e) => e.1 += v,
                None => w.push((run as usize, v)),
            }
        }
    }
}
