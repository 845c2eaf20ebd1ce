//! Sobol' low-discrepancy sequence, Gray-code order, with the direction numbers of Joe & Kuo
//! (SIAM J. Sci. Comput. 30, 2008, file `new-joe-kuo-6.21201`) for dimensions 2 to 40; dimension
//! 1 is the van der Corput sequence.
//!
//! Direction numbers: `V_k = m_k 2^(32-k)` for `k <= s`, then
//! `V_k = V_{k-s} ^ (V_{k-s} >> s) ^ XOR_{i=1}^{s-1} a_i V_{k-i}`; point `i` is
//! `XOR_{k : bit k of gray(i)} V_{k+1}`, `gray(i) = i ^ (i >> 1)`.
//!
//! Scrambling (Matousek 1998): a random lower-triangular binary matrix with unit diagonal applied
//! to the digits of every coordinate (linear matrix scramble) followed by a random digital shift;
//! both keep the `(t, m, s)`-net structure and make the estimator unbiased. Unscrambled sequences
//! skip the origin (index 0); coordinates are returned as `(x + 1/2) 2^-32` so they lie in `(0, 1)`.

use super::Design;
use crate::error::{Result, invalid};
use crate::joint::JointLaw;
use crate::rng::chunk_rng;
use rand::RngCore;

/// `(s, a, m_1..m_s)` for dimensions 2..=40.
const JOE_KUO: [(u32, u32, [u32; 8]); 39] = [
    (1, 0, [1, 0, 0, 0, 0, 0, 0, 0]),
    (2, 1, [1, 3, 0, 0, 0, 0, 0, 0]),
    (3, 1, [1, 3, 1, 0, 0, 0, 0, 0]),
    (3, 2, [1, 1, 1, 0, 0, 0, 0, 0]),
    (4, 1, [1, 1, 3, 3, 0, 0, 0, 0]),
    (4, 4, [1, 3, 5, 13, 0, 0, 0, 0]),
    (5, 2, [1, 1, 5, 5, 17, 0, 0, 0]),
    (5, 4, [1, 1, 5, 5, 5, 0, 0, 0]),
    (5, 7, [1, 1, 7, 11, 19, 0, 0, 0]),
    (5, 11, [1, 1, 5, 1, 1, 0, 0, 0]),
    (5, 13, [1, 1, 1, 3, 11, 0, 0, 0]),
    (5, 14, [1, 3, 5, 5, 31, 0, 0, 0]),
    (6, 1, [1, 3, 3, 9, 7, 49, 0, 0]),
    (6, 13, [1, 1, 1, 15, 21, 21, 0, 0]),
    (6, 16, [1, 3, 1, 13, 27, 49, 0, 0]),
    (6, 19, [1, 1, 1, 15, 7, 5, 0, 0]),
    (6, 22, [1, 3, 1, 15, 13, 25, 0, 0]),
    (6, 25, [1, 1, 5, 5, 19, 61, 0, 0]),
    (7, 1, [1, 3, 7, 11, 23, 15, 103, 0]),
    (7, 4, [1, 3, 7, 13, 13, 15, 69, 0]),
    (7, 7, [1, 1, 3, 13, 7, 35, 63, 0]),
    (7, 8, [1, 3, 5, 9, 1, 25, 53, 0]),
    (7, 14, [1, 3, 1, 13, 9, 35, 107, 0]),
    (7, 19, [1, 3, 1, 5, 27, 61, 31, 0]),
    (7, 21, [1, 1, 5, 11, 19, 41, 61, 0]),
    (7, 28, [1, 3, 5, 3, 3, 13, 69, 0]),
    (7, 31, [1, 1, 7, 13, 1, 19, 1, 0]),
    (7, 32, [1, 3, 7, 5, 13, 19, 59, 0]),
    (7, 37, [1, 1, 3, 9, 25, 29, 41, 0]),
    (7, 41, [1, 3, 5, 13, 23, 1, 55, 0]),
    (7, 42, [1, 3, 7, 3, 13, 59, 17, 0]),
    (7, 50, [1, 3, 1, 3, 5, 53, 69, 0]),
    (7, 55, [1, 1, 5, 5, 23, 33, 13, 0]),
    (7, 56, [1, 1, 7, 7, 1, 61, 123, 0]),
    (7, 59, [1, 1, 7, 9, 13, 61, 49, 0]),
    (7, 62, [1, 3, 3, 5, 3, 55, 33, 0]),
    (8, 14, [1, 3, 1, 15, 31, 13, 49, 245]),
    (8, 21, [1, 3, 5, 15, 31, 59, 63, 97]),
    (8, 22, [1, 3, 1, 11, 11, 11, 77, 249]),
];

/// Maximal dimension of [`SobolSequence`].
pub const SOBOL_MAX_DIM: usize = 40;

/// A (possibly scrambled) Sobol' sequence in the unit cube.
#[derive(Debug, Clone, PartialEq)]
pub struct SobolSequence {
    dim: usize,
    /// `v[j][k]` = direction number `V_{k+1}` of dimension `j`.
    v: Vec<[u32; 32]>,
    shift: Vec<u32>,
    scrambled: bool,
}

impl SobolSequence {
    /// Unscrambled sequence.
    ///
    /// # Errors
    /// If `dim` is 0 or above [`SOBOL_MAX_DIM`].
    pub fn new(dim: usize) -> Result<Self> {
        if dim == 0 || dim > SOBOL_MAX_DIM {
            return Err(invalid("Sobol' sequence", "dim", "in 1..=40", dim as f64));
        }
        let mut v = Vec::with_capacity(dim);
        let mut first = [0u32; 32];
        for (k, e) in first.iter_mut().enumerate() {
            *e = 1u32 << (31 - k);
        }
        v.push(first);
        for &(s, a, m) in JOE_KUO.iter().take(dim - 1) {
            let s = s as usize;
            let mut d = [0u32; 32];
            for k in 0..32 {
                if k < s {
                    d[k] = m[k] << (31 - k);
                } else {
                    let mut x = d[k - s] ^ (d[k - s] >> s);
                    for i in 1..s {
                        if (a >> (s - 1 - i)) & 1 == 1 {
                            x ^= d[k - i];
                        }
                    }
                    d[k] = x;
                }
            }
            v.push(d);
        }
        Ok(Self {
            dim,
            v,
            shift: vec![0; dim],
            scrambled: false,
        })
    }

    /// Scrambled sequence (linear matrix scramble + digital shift) seeded by `seed`.
    ///
    /// # Errors
    /// As [`SobolSequence::new`].
    pub fn scrambled(dim: usize, seed: u64) -> Result<Self> {
        let mut s = Self::new(dim)?;
        let mut rng = chunk_rng(seed, 0);
        for j in 0..dim {
            // rows[r]: mask over input digits c <= r (digit c is bit 31 - c).
            let mut rows = [0u32; 32];
            for (r, row) in rows.iter_mut().enumerate() {
                let below = if r == 0 {
                    0
                } else {
                    (rng.next_u32() >> (32 - r)) << (32 - r)
                };
                *row = below | (1u32 << (31 - r));
            }
            for k in 0..32 {
                let x = s.v[j][k];
                let mut y = 0u32;
                for (r, row) in rows.iter().enumerate() {
                    if (row & x).count_ones() % 2 == 1 {
                        y |= 1u32 << (31 - r);
                    }
                }
                s.v[j][k] = y;
            }
            s.shift[j] = rng.next_u32();
        }
        s.scrambled = true;
        Ok(s)
    }

    /// Number of variables.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Point number `i` (0-based; unscrambled sequences skip the origin) into `u`. The
    /// direction numbers have 32 bits: the sequence is defined for `i < 2^32`.
    ///
    /// # Panics
    /// If `u.len() < dim()`.
    pub fn point(&self, i: u64, u: &mut [f64]) {
        let i = if self.scrambled { i } else { i + 1 };
        let g = i ^ (i >> 1);
        for j in 0..self.dim {
            let mut x = self.shift[j];
            let mut bits = g;
            let mut k = 0;
            while bits != 0 && k < 32 {
                if bits & 1 == 1 {
                    x ^= self.v[j][k];
                }
                bits >>= 1;
                k += 1;
            }
            u[j] = (x as f64 + 0.5) * (1.0 / 4_294_967_296.0);
        }
    }
}

/// First `n` points of the Sobol' sequence mapped through `law` (scrambled when `scramble_seed`
/// is given).
///
/// # Errors
/// If `law.dim()` exceeds [`SOBOL_MAX_DIM`].
pub fn sobol(law: &dyn JointLaw, n: usize, scramble_seed: Option<u64>) -> Result<Design> {
    let d = law.dim();
    let seq = match scramble_seed {
        Some(s) => SobolSequence::scrambled(d, s)?,
        None => SobolSequence::new(d)?,
    };
    let mut u = vec![0.0; n * d];
    for (i, p) in u.chunks_exact_mut(d).enumerate() {
        seq.point(i as u64, p);
    }
    Ok(Design { dim: d, points: u }.map_from_unit(law))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first 2^m points of each pair of the first dimensions fill every elementary box of
    /// volume 2^-m... checked here on the weaker 1D property: each coordinate of the first 2^m
    /// points (scrambled, origin included) hits each interval [k/2^m, (k+1)/2^m) exactly once.
    #[test]
    fn stratification_in_each_dimension() {
        let s = SobolSequence::scrambled(40, 7).unwrap();
        let m = 8;
        let n = 1usize << m;
        let mut hit = vec![vec![0u32; n]; 40];
        let mut u = vec![0.0; 40];
        for i in 0..n {
            s.point(i as u64, &mut u);
            for j in 0..40 {
                hit[j][(u[j] * n as f64) as usize] += 1;
            }
        }
        assert!(hit.iter().all(|h| h.iter().all(|&c| c == 1)));
    }

    #[test]
    fn known_first_points() {
        // Unscrambled Sobol' (Joe-Kuo), skipping the origin: 0.5, then (0.75, 0.25), (0.25, 0.75).
        let s = SobolSequence::new(2).unwrap();
        let mut u = [0.0; 2];
        let half = 0.5 / 4_294_967_296.0;
        s.point(0, &mut u);
        assert!((u[0] - 0.5 - half).abs() < 1e-15 && (u[1] - 0.5 - half).abs() < 1e-15);
        s.point(1, &mut u);
        assert!((u[0] - 0.75 - half).abs() < 1e-15 && (u[1] - 0.25 - half).abs() < 1e-15);
        s.point(2, &mut u);
        assert!((u[0] - 0.25 - half).abs() < 1e-15 && (u[1] - 0.75 - half).abs() < 1e-15);
    }

    /// (0, m, 2)-net property of dimensions 1 and 2: every 2^a x 2^(m-a) box holds one point.
    #[test]
    fn two_dimensional_net_property() {
        let s = SobolSequence::new(2).unwrap();
        let m = 6;
        let n = 1usize << m;
        let mut pts = vec![[0.0; 2]; n];
        for i in 0..n {
            // index n-1 .. includes origin when shifted: use i-1 for i>=1, origin separately
            if i == 0 {
                pts[i] = [0.0, 0.0];
            } else {
                s.point(i as u64 - 1, &mut pts[i]);
            }
        }
        for a in 0..=m {
            let (nx, ny) = (1usize << a, 1usize << (m - a));
            let mut cnt = vec![0u32; n];
            for p in &pts {
                let ix = (p[0] * nx as f64) as usize;
                let iy = (p[1] * ny as f64) as usize;
                cnt[ix * ny + iy] += 1;
            }
            assert!(cnt.iter().all(|&c| c == 1), "a = {a}");
        }
    }
}
