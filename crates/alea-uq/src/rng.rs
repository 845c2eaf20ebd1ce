//! Reproducible random streams.
//!
//! Parallel sampling is split into chunks of a fixed size ([`CHUNK`]); chunk `c` of a computation
//! seeded with `seed` draws from `ChaCha8Rng::seed_from_u64(seed)` on stream `c`. The result of a
//! parallel computation therefore depends only on the seed, never on the number of threads.

use rand::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Number of samples per independently seeded chunk.
pub const CHUNK: usize = 4096;

/// The random stream of chunk `chunk` for a computation seeded with `seed`.
pub fn chunk_rng(seed: u64, chunk: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(chunk);
    rng
}

/// A uniform number in the open interval `(0, 1)`: `(k + 1/2) 2^-53`, `k` uniform on 53 bits.
#[inline]
pub fn open01(rng: &mut dyn RngCore) -> f64 {
    ((rng.next_u64() >> 11) as f64 + 0.5) * (1.0 / 9_007_199_254_740_992.0)
}
