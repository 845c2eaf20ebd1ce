//! The 3D phase-2 displacement space: vector polynomials of total degree `k` on one element, in
//! scaled physical coordinates, with the rigid-body modes removed.
//!
//! Scalar basis `phi_s`: products of Legendre polynomials `P_a(xi) P_b(eta) P_c(zeta)`,
//! `a + b + c <= k`, of the scaled coordinates `xi = (x - x_c) / h` (`x_c` the centre of the
//! element's bounding box, `h` its half-size), ordered by total degree (index 0 the constant,
//! 1..=3 `xi`, `eta`, `zeta`): `n_s = (k + 1)(k + 2)(k + 3) / 6` functions. The same space serves
//! tetrahedra and (possibly distorted) hexahedra: the complete polynomial space of degree `k` in
//! physical coordinates.
//!
//! Vector basis of `[P_k]^3 / RM` (dimension `3 n_s - 6`): at degree 1 the six symmetric
//! gradients `(xi, 0, 0)`, `(0, eta, 0)`, `(0, 0, zeta)`, `(eta, xi, 0)`, `(zeta, 0, xi)`,
//! `(0, zeta, eta)` (the constants and the three infinitesimal rotations are left out), then
//! `phi_s e_c` for every `c` and every scalar function of degree `>= 2`. Each vector function is a
//! short list of terms `coef phi_s e_c`, so the stiffness and load of a local problem follow from
//! the scalar integrals `G_pq[a][b] = int d_p phi_a d_q phi_b` and `L_c[a] = int t_c phi_a`
//! (see [`super::phase2`]).

use crate::legendre::legendre;

/// Position of the second derivative `d_i d_j` (or of the symmetric pair `(i, j)`) in Voigt
/// order `[xx, yy, zz, yz, xz, xy]`.
#[inline]
pub fn voigt_index(i: usize, j: usize) -> usize {
    match (i.min(j), i.max(j)) {
        (0, 0) => 0,
        (1, 1) => 1,
        (2, 2) => 2,
        (1, 2) => 3,
        (0, 2) => 4,
        _ => 5,
    }
}

/// Largest supported degree.
pub const MAX_DEGREE: usize = 12;

/// One vector basis function: up to two terms `(component, scalar index, coefficient)`.
#[derive(Clone, Copy, Debug)]
pub struct VectorTerm {
    /// Terms.
    pub terms: [(usize, usize, f64); 2],
    /// Number of terms used.
    pub nterms: usize,
}

/// The displacement space of one element.
#[derive(Clone, Debug)]
pub struct PolySpace3 {
    /// Total degree.
    pub degree: usize,
    /// Centre of the scaled coordinates.
    pub center: [f64; 3],
    /// Scale length.
    pub scale: f64,
    /// Exponents `(a, b, c)` of each scalar function.
    pub exponents: Vec<[usize; 3]>,
    /// The vector basis.
    pub funcs: Vec<VectorTerm>,
}

/// Values and derivatives of the scalar basis at one point.
#[derive(Clone, Debug, Default)]
pub struct ScalarPoint {
    /// `phi_s`.
    pub val: Vec<f64>,
    /// `grad phi_s`.
    pub grad: Vec<[f64; 3]>,
    /// Second derivatives `[xx, yy, zz, yz, xz, xy]` (only if requested).
    pub hess: Vec<[f64; 6]>,
}

impl PolySpace3 {
    /// The space of degree `1 <= degree <= MAX_DEGREE` on the element with node coordinates
    /// `coords`.
    pub fn new(degree: usize, coords: &[[f64; 3]]) -> Self {
        assert!((1..=MAX_DEGREE).contains(&degree), "degree {degree}");
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for x in coords {
            for d in 0..3 {
                lo[d] = lo[d].min(x[d]);
                hi[d] = hi[d].max(x[d]);
            }
        }
        let center = [0, 1, 2].map(|d| 0.5 * (lo[d] + hi[d]));
        let scale = 0.5 * (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
        let mut exponents = Vec::new();
        for deg in 0..=degree {
            for a in (0..=deg).rev() {
                for b in (0..=deg - a).rev() {
                    exponents.push([a, b, deg - a - b]);
                }
            }
        }
        // exponents[1..4] = [1,0,0], [0,1,0], [0,0,1].
        let one = |c: usize, s: usize| VectorTerm {
            terms: [(c, s, 1.0), (0, 0, 0.0)],
            nterms: 1,
        };
        let two = |c1: usize, s1: usize, c2: usize, s2: usize| VectorTerm {
            terms: [(c1, s1, 1.0), (c2, s2, 1.0)],
            nterms: 2,
        };
        let mut funcs = vec![
            one(0, 1),
            one(1, 2),
            one(2, 3),
            two(0, 2, 1, 1),
            two(0, 3, 2, 1),
            two(1, 3, 2, 2),
        ];
        for s in 4..exponents.len() {
            for c in 0..3 {
                funcs.push(one(c, s));
            }
        }
        PolySpace3 {
            degree,
            center,
            scale,
            exponents,
            funcs,
        }
    }

    /// Number of vector basis functions.
    pub fn len(&self) -> usize {
        self.funcs.len()
    }

    /// True if empty (never).
    pub fn is_empty(&self) -> bool {
        self.funcs.is_empty()
    }

    /// Number of scalar functions.
    pub fn num_scalar(&self) -> usize {
        self.exponents.len()
    }

    /// Evaluates the scalar basis at physical point `x` (second derivatives if `hessian`).
    pub fn eval(&self, x: [f64; 3], hessian: bool, out: &mut ScalarPoint) {
        let k = self.degree;
        let h = self.scale;
        let mut p = [[0.0; MAX_DEGREE + 1]; 3];
        let mut dp = [[0.0; MAX_DEGREE + 1]; 3];
        let mut ddp = [[0.0; MAX_DEGREE + 1]; 3];
        for d in 0..3 {
            legendre(
                k,
                (x[d] - self.center[d]) / h,
                &mut p[d],
                &mut dp[d],
                &mut ddp[d],
            );
        }
        let n = self.exponents.len();
        out.val.clear();
        out.grad.clear();
        out.hess.clear();
        let ih = 1.0 / h;
        let ih2 = ih * ih;
        for &[a, b, c] in &self.exponents {
            let (pa, pb, pc) = (p[0][a], p[1][b], p[2][c]);
            let (da, db, dc) = (dp[0][a], dp[1][b], dp[2][c]);
            out.val.push(pa * pb * pc);
            out.grad
                .push([da * pb * pc * ih, pa * db * pc * ih, pa * pb * dc * ih]);
            if hessian {
                out.hess.push([
                    ddp[0][a] * pb * pc * ih2,
                    pa * ddp[1][b] * pc * ih2,
                    pa * pb * ddp[2][c] * ih2,
                    pa * db * dc * ih2,
                    da * pb * dc * ih2,
                    da * db * pc * ih2,
                ]);
            }
        }
        debug_assert_eq!(out.val.len(), n);
    }

    /// Expands vector coefficients `v` (one per basis function) into per-component scalar
    /// coefficients `u[c][s]`: `u = sum_s u[c][s] phi_s e_c`.
    pub fn expand(&self, v: &[f64]) -> [Vec<f64>; 3] {
        let ns = self.exponents.len();
        let mut u = [vec![0.0; ns], vec![0.0; ns], vec![0.0; ns]];
        for (f, &a) in self.funcs.iter().zip(v) {
            for &(c, s, coef) in &f.terms[..f.nterms] {
                u[c][s] += coef * a;
            }
        }
        u
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dimension_derivatives_and_no_rigid_mode() {
        let coords = [
            [0.0, 0.0, 0.0],
            [2.0, 0.5, 0.1],
            [0.3, 1.5, -0.2],
            [0.4, 0.2, 1.2],
        ];
        for k in 1..=6 {
            let s = PolySpace3::new(k, &coords);
            let ns = (k + 1) * (k + 2) * (k + 3) / 6;
            assert_eq!(s.num_scalar(), ns);
            assert_eq!(s.len(), 3 * ns - 6);
        }
        let s = PolySpace3::new(5, &coords);
        assert_eq!(&s.exponents[1..4], &[[1, 0, 0], [0, 1, 0], [0, 0, 1]]);
        let x0 = [0.7, 0.4, 0.3];
        let (mut p, mut pp, mut pm) = Default::default();
        s.eval(x0, true, &mut p);
        let h = 1e-6;
        for d in 0..3 {
            let (mut xp, mut xm) = (x0, x0);
            xp[d] += h;
            xm[d] -= h;
            s.eval(xp, false, &mut pp);
            s.eval(xm, false, &mut pm);
            let pp: &ScalarPoint = &pp;
            let pm: &ScalarPoint = &pm;
            for j in 0..s.num_scalar() {
                let dv = (pp.val[j] - pm.val[j]) / (2.0 * h);
                assert!((dv - p.grad[j][d]).abs() < 1e-6 * (1.0 + dv.abs()));
                // d/dx_d of grad: the hessian column d.
                // Voigt positions written out as a table, independent of `voigt_index`.
                const VOIGT: [[usize; 3]; 3] = [[0, 5, 4], [5, 1, 3], [4, 3, 2]];
                let idx = |a: usize, b: usize| VOIGT[a][b];
                for e in 0..3 {
                    let dg = (pp.grad[j][e] - pm.grad[j][e]) / (2.0 * h);
                    let want = p.hess[j][idx(d, e)];
                    assert!((dg - want).abs() < 1e-5 * (1.0 + want.abs()), "{j} {d} {e}");
                }
            }
        }
        // No rigid mode in the span: the Gram matrix of the strains (symmetric gradients) of the
        // vector basis at random points is non-singular (checked through a Cholesky).
        let n = s.len();
        let mut g = vec![0.0; n * n];
        let mut q = ScalarPoint::default();
        for i in 0..200 {
            let t = i as f64;
            let x = [
                (t * 0.37).sin() * 0.8 + 0.5,
                (t * 0.71).cos() * 0.7 + 0.4,
                (t * 1.13).sin() * 0.6 + 0.2,
            ];
            s.eval(x, false, &mut q);
            let strains: Vec<[f64; 6]> = s
                .funcs
                .iter()
                .map(|f| {
                    let mut gr = [[0.0; 3]; 3];
                    for &(c, sc, coef) in &f.terms[..f.nterms] {
                        for e in 0..3 {
                            gr[c][e] += coef * q.grad[sc][e];
                        }
                    }
                    [
                        gr[0][0],
                        gr[1][1],
                        gr[2][2],
                        gr[1][2] + gr[2][1],
                        gr[0][2] + gr[2][0],
                        gr[0][1] + gr[1][0],
                    ]
                })
                .collect();
            for a in 0..n {
                for b in 0..n {
                    g[a * n + b] += (0..6).map(|c| strains[a][c] * strains[b][c]).sum::<f64>();
                }
            }
        }
        let mut b = vec![1.0; n];
        assert!(crate::linalg::cholesky_solve(&mut g, &mut b, n));
    }
}
