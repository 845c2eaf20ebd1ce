//! Latin hypercube sampling: in the unit cube, `u_ij = (pi_j(i) + v_ij) / n` with independent
//! random permutations `pi_j` and `v_ij ~ U(0, 1)`, then `x_i = T^-1(u_i)`. The maximin variant
//! draws `candidates` hypercubes and keeps the one with the largest minimal pairwise distance
//! (in the unit cube).

use super::Design;
use crate::joint::JointLaw;
use crate::rng::{chunk_rng, open01};
use rand::RngCore;

fn unit_lhs(n: usize, d: usize, rng: &mut dyn RngCore) -> Vec<f64> {
    let mut u = vec![0.0; n * d];
    let mut perm: Vec<usize> = (0..n).collect();
    for j in 0..d {
        for i in (1..n).rev() {
            let k = (rng.next_u64() % (i as u64 + 1)) as usize;
            perm.swap(i, k);
        }
        for i in 0..n {
            u[i * d + j] = (perm[i] as f64 + open01(rng)) / n as f64;
        }
    }
    u
}

fn min_dist2(u: &[f64], n: usize, d: usize) -> f64 {
    let mut m = f64::INFINITY;
    for i in 0..n {
        for k in 0..i {
            let s: f64 = (0..d).map(|j| (u[i * d + j] - u[k * d + j]).powi(2)).sum();
            m = m.min(s);
        }
    }
    m
}

/// Latin hypercube of `n` points of `law`.
pub fn latin_hypercube(law: &dyn JointLaw, n: usize, seed: u64) -> Design {
    let d = law.dim();
    let mut rng = chunk_rng(seed, 0);
    Design {
        dim: d,
        points: unit_lhs(n, d, &mut rng),
    }
    .map_from_unit(law)
}

/// Best of `candidates` Latin hypercubes for the maximin criterion.
pub fn latin_hypercube_maximin(
    law: &dyn JointLaw,
    n: usize,
    seed: u64,
    candidates: usize,
) -> Design {
    let d = law.dim();
    let mut best = Vec::new();
    let mut best_d = -1.0;
    for c in 0..candidates.max(1) {
        let mut rng = chunk_rng(seed, c as u64);
        let u = unit_lhs(n, d, &mut rng);
        let m = min_dist2(&u, n, d);
        if m > best_d {
            best_d = m;
            best = u;
        }
    }
    Design {
        dim: d,
        points: best,
    }
    .map_from_unit(law)
}
