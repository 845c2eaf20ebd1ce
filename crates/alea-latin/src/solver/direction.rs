//! The search direction at one interface point: a symmetric stiffness tensor split along the
//! point's normal `n`, `k = k_n n n^T + k_t (I - n n^T)` (isotropic when `k_n = k_t`, the
//! scalar `k` of the thesis). It enters the linear-stage operator `A0 = K0 + sum Pi^T M k Pi`,
//! its right-hand side `Pi^T M (F_hat + k W_hat)`, the linear-stage forces
//! `F = F_hat - k (W - W_hat)`, the coarse problem (module `coarse`), the local stage and the
//! indicator's norm `sum_p m_p (W . k W + F . k^-1 F)`. A run with Young's-modulus factor
//! `alpha` uses `alpha k`. Every product with an isotropic tensor is the scalar product
//! `k v` itself (the same bits).
//!
//! Both sides of a point share its normal, so their tensors commute: the series stiffness
//! `kappa = (k_1^-1 + k_2^-1)^-1` of the local stage is `kappa_n n n^T + kappa_t (I - n n^T)`
//! with `kappa_n = (1/k_n1 + 1/k_n2)^-1` and `kappa_t` alike.

use alea_mesh::vec3::dot;

type V3 = [f64; 3];

/// The search direction at one point (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PointDirection {
    /// Unit normal of the point (side 1's outward normal).
    pub normal: V3,
    /// Normal stiffness `k_n`.
    pub kn: f64,
    /// Tangential stiffness `k_t`.
    pub kt: f64,
}

impl PointDirection {
    /// The isotropic direction `k I`.
    pub fn isotropic(normal: V3, k: f64) -> Self {
        PointDirection {
            normal,
            kn: k,
            kt: k,
        }
    }

    /// True if `k_n = k_t`.
    #[inline]
    pub fn is_isotropic(&self) -> bool {
        self.kn == self.kt
    }

    /// `f(k_n) n n^T + f(k_t) (I - n n^T)` applied to `v` (`f(k) v` itself when isotropic).
    #[inline]
    fn map(&self, kn: f64, kt: f64, v: &V3) -> V3 {
        if self.is_isotropic() {
            return [kt * v[0], kt * v[1], kt * v[2]];
        }
        let n = &self.normal;
        let d = (kn - kt) * dot(n, v);
        [
            kt * v[0] + d * n[0],
            kt * v[1] + d * n[1],
            kt * v[2] + d * n[2],
        ]
    }

    /// `alpha k v`.
    #[inline]
    pub fn apply(&self, alpha: f64, v: &V3) -> V3 {
        self.map(alpha * self.kn, alpha * self.kt, v)
    }

    /// `(alpha k)^-1 v`.
    #[inline]
    pub fn solve(&self, alpha: f64, v: &V3) -> V3 {
        if self.is_isotropic() {
            let k = alpha * self.kt;
            return [v[0] / k, v[1] / k, v[2] / k];
        }
        self.map(1.0 / (alpha * self.kn), 1.0 / (alpha * self.kt), v)
    }

    /// `(s alpha k)^(1/2) v` (`p = 0.5`) or `(s / (alpha k))^(1/2) v` (`p = -0.5`): the
    /// scalings of the acceleration's packed state.
    #[inline]
    pub fn sqrt_scaled(&self, s: f64, alpha: f64, inverse: bool, v: &V3) -> V3 {
        let f = |k: f64| {
            if inverse {
                (s / (alpha * k)).sqrt()
            } else {
                (s * alpha * k).sqrt()
            }
        };
        self.map(f(self.kn), f(self.kt), v)
    }

    /// `v . (alpha k) v`.
    #[inline]
    pub fn energy(&self, alpha: f64, v: &V3) -> f64 {
        dot(v, &self.apply(alpha, v))
    }

    /// `v . (alpha k)^-1 v`.
    #[inline]
    pub fn co_energy(&self, alpha: f64, v: &V3) -> f64 {
        dot(v, &self.solve(alpha, v))
    }
}

/// The series stiffness of the two sides of a point, `(k_1^-1 + k_2^-1)^-1` (module doc), at
/// the sides' `alpha k`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Series {
    pub normal: V3,
    pub kn: f64,
    pub kt: f64,
}

impl Series {
    /// From the sides' directions and Young's-modulus factors.
    pub fn new(d: [&PointDirection; 2], alpha: [f64; 2]) -> Self {
        let s = |a: f64, b: f64| 1.0 / (1.0 / a + 1.0 / b);
        Series {
            normal: d[0].normal,
            kn: s(alpha[0] * d[0].kn, alpha[1] * d[1].kn),
            kt: s(alpha[0] * d[0].kt, alpha[1] * d[1].kt),
        }
    }

    /// `kappa v`.
    pub fn apply(&self, v: &V3) -> V3 {
        PointDirection {
            normal: self.normal,
            kn: self.kn,
            kt: self.kt,
        }
        .apply(1.0, v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_direction_inverts_and_is_isotropic_scalar() {
        let a: f64 = 0.4;
        let n = [a.cos(), a.sin(), 0.0];
        let d = PointDirection {
            normal: n,
            kn: 3.0,
            kt: 0.5,
        };
        let v = [1.0, -2.0, 0.25];
        let back = d.solve(2.0, &d.apply(2.0, &v));
        for c in 0..3 {
            assert!((back[c] - v[c]).abs() < 1e-14);
        }
        let kv = d.apply(1.0, &n);
        for c in 0..3 {
            assert!((kv[c] - 3.0 * n[c]).abs() < 1e-14);
        }
        let h = d.sqrt_scaled(1.0, 2.0, false, &v);
        assert!((dot(&h, &h) - d.energy(2.0, &v)).abs() < 1e-12);
        let iso = PointDirection::isotropic(n, 7.0);
        assert_eq!(iso.apply(0.5, &v), [3.5 * v[0], 3.5 * v[1], 3.5 * v[2]]);
    }
}
