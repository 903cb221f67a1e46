//! AD against hand-derived mechanics: accelerations, momenta, energy, mass matrices, the inverse
//! Legendre map and Hamilton's equations of textbook systems, for random states; and the errors that
//! bad input must produce.
//!
//! Tolerance: 1e-12 relative to the largest component of the hand-derived vector (or matrix). Both
//! sides are exact formulas evaluated in f64; they differ only by rounding in different operation
//! orders (and, for the accelerations, different linear solves of well-conditioned mass matrices),
//! which stays within a few hundred ulps — far below 1e-12 — while any wrong derivative term is O(1).

mod accelerations;
mod bad_input;
mod hamilton;
mod legendre;
mod legendre_transform;
mod momenta;
mod taped;

use noether_testkit::systems;

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The relative tolerance of every `ad_vs_hand_*` check (see the crate doc).
pub const TOL: f64 = 1e-12;

/// A seeded generator: every run draws the same states.
pub fn rng(seed: u64) -> StdRng {
    StdRng::seed_from_u64(seed)
}

/// N uniform draws in [lo, hi).
pub fn draw<const N: usize>(rng: &mut StdRng, lo: f64, hi: f64) -> [f64; N] {
    std::array::from_fn(|_| rng.random_range(lo..hi))
}

/// A drawn state (t, q, v).
pub type Sample<const N: usize> = (f64, [f64; N], [f64; N]);

/// A state of charges in a field (q and q̇ of one or more charges, or their momenta p in place of
/// q̇): t ∈ [−5, 5), q ∈ [−2, 2)ᴺ, q̇ ∈ [−3, 3)ᴺ.
pub fn charge_state<const N: usize>(r: &mut StdRng) -> Sample<N> {
    (r.random_range(-5.0..5.0), draw(r, -2.0, 2.0), draw(r, -3.0, 3.0))
}

/// Calls `check(t, q, v)` at `count` states drawn by `state` from a generator seeded with `seed`.
pub fn for_states<const N: usize>(
    seed: u64,
    count: usize,
    mut state: impl FnMut(&mut StdRng) -> Sample<N>,
    mut check: impl FnMut(f64, &[f64; N], &[f64; N]),
) {
    let mut r = rng(seed);
    for _ in 0..count {
        let (t, q, v) = state(&mut r);
        check(t, &q, &v);
    }
}

/// Asserts max_i |ad_i − hand_i| ≤ TOL · max(max_i |hand_i|, floor).
#[track_caller]
pub fn assert_rel(what: &str, ad: &[f64], hand: &[f64], floor: f64) {
    assert_eq!(ad.len(), hand.len(), "{what}: lengths");
    let scale = hand.iter().fold(floor, |m, h| m.max(h.abs()));
    let err = ad
        .iter()
        .zip(hand)
        .fold(0.0_f64, |m, (a, h)| m.max((a - h).abs()));
    assert!(
        err <= TOL * scale,
        "{what}: AD {ad:?} vs hand {hand:?}: error {err:e} > {TOL:e} × scale {scale:e}"
    );
}
