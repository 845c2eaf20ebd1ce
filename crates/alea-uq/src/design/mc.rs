//! Monte Carlo design: `n` i.i.d. draws of a joint law, generated in fixed chunks of
//! [`CHUNK`](crate::rng::CHUNK) points each seeded by `(seed, chunk index)`.

use super::Design;
use crate::joint::JointLaw;
use crate::rng::{CHUNK, chunk_rng, open01};
use rayon::prelude::*;

/// `n` independent draws of `law`; the result depends on `seed` only, not on the thread count.
pub fn monte_carlo(law: &dyn JointLaw, n: usize, seed: u64) -> Design {
    let d = law.dim();
    let mut points = vec![0.0; n * d];
    points
        .par_chunks_mut(CHUNK * d)
        .enumerate()
        .for_each(|(c, block)| {
            let mut rng = chunk_rng(seed, c as u64);
            let mut u = vec![0.0; d];
            for x in block.chunks_exact_mut(d) {
                for v in u.iter_mut() {
                    *v = open01(&mut rng);
                }
                law.unit_to_x(&u, x);
            }
        });
    Design { dim: d, points }
}
