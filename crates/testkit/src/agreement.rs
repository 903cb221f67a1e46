//! How two computations of one quantity are compared: the difference of two vectors relative to the
//! size of the reference, at reproducible pseudo-random states.

/// max_i |a_i − b_i| / max_i |b_i|: the error of a vector relative to its size (NaN for a zero
/// reference).
pub fn relative(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

/// A uniform pseudo-random number in [lo, hi) at each call, from a 64-bit linear congruential
/// generator (Knuth's MMIX constants) seeded with `seed`, the top 53 bits as the fraction: the same
/// sequence on every machine, so that a test's states are reproducible.
pub fn uniform(seed: u64) -> impl FnMut(f64, f64) -> f64 {
    let mut s = seed;
    move |lo, hi| {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        lo + (hi - lo) * ((s >> 11) as f64 / (1u64 << 53) as f64)
    }
}
