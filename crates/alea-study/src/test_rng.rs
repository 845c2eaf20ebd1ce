//! A deterministic uniform generator for the unit tests of this crate (no dependency).

/// The next number in `[0, 1)` of a 64-bit linear congruential generator (Knuth's MMIX
/// constants), the top 53 bits of its state.
pub(crate) fn lcg(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*state >> 11) as f64 / (1u64 << 53) as f64
}
