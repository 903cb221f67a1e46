//! The benchmarks' timing rule: on a shared machine interference only adds time, so the least time
//! per call over many rounds is the measurement.

use std::hint::black_box;
use std::time::Instant;

/// The least time per call, in ns, over `rounds` rounds; `round` runs `calls` calls and returns a
/// value (kept from the optimiser by [`black_box`]).
pub fn min_ns(rounds: usize, calls: usize, mut round: impl FnMut() -> f64) -> f64 {
    (0..rounds)
        .map(|_| {
            let t0 = Instant::now();
            black_box(round());
            t0.elapsed().as_nanos() as f64 / calls as f64
        })
        .fold(f64::INFINITY, f64::min)
}
