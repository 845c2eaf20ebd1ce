//! The phase-2 displacement space: vector polynomials of total degree `k` on one element, in
//! scaled physical coordinates, with the rigid-body modes removed.
//!
//! Scalar basis: products of Legendre polynomials `P_a(xi) P_b(eta)`, `a + b <= k`, of the
//! scaled coordinates `xi = (x - x_c) / h`, `eta = (y - y_c) / h` (`x_c` the centre of the
//! element's bounding box, `h` its half-size), which keeps the local matrices well conditioned.
//! The same space serves triangles and (possibly distorted) quadrilaterals: it is the complete
//! polynomial space of degree `k` in physical coordinates, hierarchical in `k`.
//!
//! Vector basis of `[P_k]^2 / RM`: `(phi, 0)` and `(0, phi)` for every scalar function of degree
//! `>= 2`; at degree 1 only `(xi, 0)`, `(0, eta)` and the symmetric `(eta, xi)` (the constants and
//! the infinitesimal rotation `(-eta, xi)` are left out). Dimension `(k + 1)(k + 2) - 3`.

use std::sync::{Arc, OnceLock};

use crate::legendre::{legendre, legendre_values};

/// One vector basis function: up to two terms `coef * phi_(a,b)` in component `comp`, with
/// the scalar function's index in [`PolySpace::scalars`] order.
#[derive(Clone, Copy, Debug)]
struct VecFn {
    terms: [(usize, usize, usize, f64); 2],
    scalar: [usize; 2],
    nterms: usize,
}

/// Index of the scalar function `P_a(xi) P_b(eta)` in [`PolySpace::scalars`] order (by total
/// degree, then decreasing `a`).
fn scalar_index(a: usize, b: usize) -> usize {
    let d = a + b;
    d * (d + 1) / 2 + (d - a)
}

/// Largest supported degree (the Legendre buffers hold 16 values).
pub const MAX_DEGREE: usize = 15;

/// The vector basis of degree `degree` (it does not depend on the element: built once per
/// degree and shared by every space).
fn basis(degree: usize) -> Arc<[VecFn]> {
    static BASES: [OnceLock<Arc<[VecFn]>>; MAX_DEGREE + 1] =
        [const { OnceLock::new() }; MAX_DEGREE + 1];
    BASES[degree]
        .get_or_init(|| {
            let one = |c: usize, a: usize, b: usize| VecFn {
                terms: [(c, a, b, 1.0), (0, 0, 0, 0.0)],
                scalar: [scalar_index(a, b), 0],
                nterms: 1,
            };
            let mut funcs = vec![
                one(0, 1, 0),
                one(1, 0, 1),
                VecFn {
                    terms: [(0, 0, 1, 1.0), (1, 1, 0, 1.0)],
                    scalar: [scalar_index(0, 1), scalar_index(1, 0)],
                    nterms: 2,
                },
            ];
            for deg in 2..=degree {
                for a in (0..=deg).rev() {
                    let b = deg - a;
                    funcs.push(one(0, a, b));
                    funcs.push(one(1, a, b));
                }
            }
            funcs.into()
        })
        .clone()
}

/// The displacement space of one element.
#[derive(Clone, Debug)]
pub struct PolySpace {
    /// Total degree.
    pub degree: usize,
    /// Centre of the scaled coordinates.
    pub center: [f64; 2],
    /// Scale length.
    pub scale: f64,
    funcs: Arc<[VecFn]>,
}

/// Values and derivatives of the basis at one point.
#[derive(Clone, Debug, Default)]
pub struct PolyPoint {
    /// `u[j] = [u_x, u_y]` of basis function `j`.
    pub u: Vec<[f64; 2]>,
    /// Voigt strains `[e_xx, e_yy, g_xy]` of basis function `j`.
    pub eps: Vec<[f64; 3]>,
    /// Second derivatives `[[u_xx, u_xy, u_yy], [v_xx, v_xy, v_yy]]` (only if requested).
    pub hess: Vec<[[f64; 3]; 2]>,
}

impl PolySpace {
    /// The space of degree `degree` (`1..=`[`MAX_DEGREE`]) on the element with corner
    /// coordinates `coords`.
    ///
    /// # Panics
    /// If `degree` is 0 or above [`MAX_DEGREE`].
    pub fn new(degree: usize, coords: &[[f64; 3]]) -> Self {
        assert!(
            (1..=MAX_DEGREE).contains(&degree),
            "polynomial degree {degree} out of 1..={MAX_DEGREE}"
        );
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for x in coords {
            for d in 0..2 {
                lo[d] = lo[d].min(x[d]);
                hi[d] = hi[d].max(x[d]);
            }
        }
        let center = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
        let scale = 0.5 * (hi[0] - lo[0]).max(hi[1] - lo[1]);
        PolySpace {
            degree,
            center,
            scale,
            funcs: basis(degree),
        }
    }

    /// Number of basis functions.
    pub fn len(&self) -> usize {
        self.funcs.len()
    }

    /// True if empty (never, for degree >= 1).
    pub fn is_empty(&self) -> bool {
        self.funcs.is_empty()
    }

    /// Number of scalar functions `P_a(xi) P_b(eta)`, `a + b <= degree`.
    pub fn num_scalars(&self) -> usize {
        (self.degree + 1) * (self.degree + 2) / 2
    }

    /// Values of the scalar functions `P_a(xi) P_b(eta)` at physical point `x`, by total degree
    /// then decreasing `a` (`out.len() >= num_scalars()`).
    pub fn scalars(&self, x: [f64; 2], out: &mut [f64]) {
        let k = self.degree;
        let h = self.scale;
        let mut px = [0.0; 16];
        let mut py = [0.0; 16];
        legendre_values(k, (x[0] - self.center[0]) / h, &mut px);
        legendre_values(k, (x[1] - self.center[1]) / h, &mut py);
        let mut i = 0;
        for d in 0..=k {
            for a in (0..=d).rev() {
                out[i] = px[a] * py[d - a];
                i += 1;
            }
        }
    }

    /// Adds to `l[j]` the integral weight of the vector basis function `j` against a vector
    /// given through its scalar parts: `l[j] += sum_terms coef * value(component, scalar)`,
    /// e.g. `value(c, s) = w t_c psi_s(x)` for a point load `w t` at `x` (`t . phi_j(x)`).
    #[inline]
    pub fn accumulate(&self, l: &mut [f64], value: impl Fn(usize, usize) -> f64) {
        for (lj, f) in l.iter_mut().zip(self.funcs.iter()) {
            let mut v = f.terms[0].3 * value(f.terms[0].0, f.scalar[0]);
            if f.nterms == 2 {
                v += f.terms[1].3 * value(f.terms[1].0, f.scalar[1]);
            }
            *lj += v;
        }
    }

    /// Evaluates the basis at physical point `x` (second derivatives if `hessian`).
    pub fn eval(&self, x: [f64; 3], hessian: bool, out: &mut PolyPoint) {
        let k = self.degree;
        let h = self.scale;
        let xi = (x[0] - self.center[0]) / h;
        let eta = (x[1] - self.center[1]) / h;
        let mut px = [0.0; 16];
        let mut dpx = [0.0; 16];
        let mut ddpx = [0.0; 16];
        let mut py = [0.0; 16];
        let mut dpy = [0.0; 16];
        let mut ddpy = [0.0; 16];
        legendre(k, xi, &mut px, &mut dpx, &mut ddpx);
        legendre(k, eta, &mut py, &mut dpy, &mut ddpy);
        let n = self.funcs.len();
        out.u.clear();
        out.u.resize(n, [0.0; 2]);
        out.eps.clear();
        out.eps.resize(n, [0.0; 3]);
        out.hess.clear();
        if hessian {
            out.hess.resize(n, [[0.0; 3]; 2]);
        }
        let ih = 1.0 / h;
        for (j, f) in self.funcs.iter().enumerate() {
            // grad[c] = [d/dx, d/dy] of component c.
            let mut grad = [[0.0; 2]; 2];
            for &(c, a, b, coef) in &f.terms[..f.nterms] {
                out.u[j][c] += coef * px[a] * py[b];
                grad[c][0] += coef * dpx[a] * py[b] * ih;
                grad[c][1] += coef * px[a] * dpy[b] * ih;
                if hessian {
                    let hh = &mut out.hess[j][c];
                    hh[0] += coef * ddpx[a] * py[b] * ih * ih;
                    hh[1] += coef * dpx[a] * dpy[b] * ih * ih;
                    hh[2] += coef * px[a] * ddpy[b] * ih * ih;
                }
            }
            out.eps[j] = [grad[0][0], grad[1][1], grad[0][1] + grad[1][0]];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dimension_and_derivatives() {
        let coords = [[0.0, 0.0, 0.0], [2.0, 0.5, 0.0], [0.3, 1.5, 0.0]];
        for k in 1..=6 {
            let s = PolySpace::new(k, &coords);
            assert_eq!(s.len(), (k + 1) * (k + 2) - 3);
        }
        let s = PolySpace::new(5, &coords);
        let x0 = [0.7, 0.4, 0.0];
        let mut p = PolyPoint::default();
        let mut pp = PolyPoint::default();
        let mut pm = PolyPoint::default();
        s.eval(x0, true, &mut p);
        let h = 1e-6;
        for d in 0..2 {
            let mut xp = x0;
            let mut xm = x0;
            xp[d] += h;
            xm[d] -= h;
            s.eval(xp, false, &mut pp);
            s.eval(xm, false, &mut pm);
            for j in 0..s.len() {
                let du: Vec<f64> = (0..2)
                    .map(|c| (pp.u[j][c] - pm.u[j][c]) / (2.0 * h))
                    .collect();
                // d/dx u_x = e_xx, d/dy u_y = e_yy.
                if d == 0 {
                    assert!((du[0] - p.eps[j][0]).abs() < 1e-6);
                } else {
                    assert!((du[1] - p.eps[j][1]).abs() < 1e-6);
                }
                // Second derivatives from the strains' differences.
                let dexx = (pp.eps[j][0] - pm.eps[j][0]) / (2.0 * h);
                let want = if d == 0 {
                    p.hess[j][0][0]
                } else {
                    p.hess[j][0][1]
                };
                assert!((dexx - want).abs() < 1e-5 * (1.0 + want.abs()));
            }
        }
        // No rigid mode in the span: the strain of every basis function is non-zero, and the
        // Gram matrix of strains is non-singular (checked through a Cholesky).
        let n = s.len();
        let mut g = vec![0.0; n * n];
        let q = alea_fem::Quadrature::triangle(12);
        for xi in &q.points {
            let x = [
                coords[0][0]
                    + xi[0] * (coords[1][0] - coords[0][0])
                    + xi[1] * (coords[2][0] - coords[0][0]),
                coords[0][1]
                    + xi[0] * (coords[1][1] - coords[0][1])
                    + xi[1] * (coords[2][1] - coords[0][1]),
                0.0,
            ];
            s.eval(x, false, &mut p);
            for i in 0..n {
                for j in 0..n {
                    g[i * n + j] += (0..3).map(|c| p.eps[i][c] * p.eps[j][c]).sum::<f64>();
                }
            }
        }
        let mut b = vec![1.0; n];
        assert!(crate::linalg::cholesky_solve(&mut g, &mut b, n));
    }
}
