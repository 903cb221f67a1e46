//! AD accelerations against hand-written ones under load: the minimum over many short rounds of the
//! time per call (interference from other processes only ever adds time), and fixed call counts for
//! instruction counting with callgrind.
//!
//! - `cargo bench -p noether-core --bench accelerations_min`: min-of-rounds times and ratios, and the
//!   time of L alone in f64 (the floor under any method that evaluates L);
//! - `valgrind --tool=callgrind <binary> dp|top|chain`: 10 000 calls of each side; the inclusive counts
//!   of `ad_calls::<…>` and `hand_calls::<…>` divided by 10 000 are the instructions per call.
//!
//! Results in docs/benchmarks.md. Complements the criterion bench `accelerations`.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use noether_core::{EulerLagrange, Lagrangian};
use noether_testkit::systems::{Chain, DoublePendulum, HeavyTop};
use noether_testkit::timing;
use std::hint::black_box;

/// Calls per round (and per callgrind run).
const IT: usize = 10000;

/// A test system with its hand-derived accelerations and the benchmark's state.
/// `H` is the hand function's own (zero-sized) type, so that it is inlined as a direct call would be.
struct Case<L, H, const N: usize> {
    el: EulerLagrange<L>,
    hand: H,
    q: [f64; N],
    v: [f64; N],
}

impl<L: Lagrangian, H: Fn(&L, &[f64; N], &[f64; N]) -> [f64; N], const N: usize> Case<L, H, N> {
    fn new(l: L, hand: H, q: [f64; N], v: [f64; N]) -> Self {
        Case {
            el: EulerLagrange::new(l),
            hand,
            q,
            v,
        }
    }
}

/// `IT` AD evaluations of q̈ (one function per system, so callgrind counts it apart).
#[inline(never)]
fn ad_calls<L: Lagrangian, H, const N: usize>(c: &Case<L, H, N>) -> f64 {
    let (mut s, mut a) = (0.0, [0.0; N]);
    for _ in 0..IT {
        c.el.accelerations(black_box(0.0), black_box(&c.q), black_box(&c.v), &mut a)
            .unwrap();
        s += a[0];
    }
    s
}

/// `IT` hand-written evaluations of q̈.
#[inline(never)]
fn hand_calls<L: Lagrangian, H: Fn(&L, &[f64; N], &[f64; N]) -> [f64; N], const N: usize>(
    c: &Case<L, H, N>,
) -> f64 {
    let mut s = 0.0;
    for _ in 0..IT {
        s += (c.hand)(c.el.lagrangian(), black_box(&c.q), black_box(&c.v))[0];
    }
    s
}

/// `IT` evaluations of L itself in f64: no derivative at all, the floor under any method that
/// evaluates L (AD by any scheme needs at least this, plus the solve with M).
#[inline(never)]
fn value_calls<L: Lagrangian, H, const N: usize>(c: &Case<L, H, N>) -> f64 {
    let mut s = 0.0;
    for _ in 0..IT {
        s +=
            c.el.lagrangian()
                .lagrangian(black_box(0.0), black_box(&c.q), black_box(&c.v));
    }
    s
}

/// Prints (or, for callgrind, only runs) hand and AD side by side for one system.
fn run<L: Lagrangian, H: Fn(&L, &[f64; N], &[f64; N]) -> [f64; N], const N: usize>(
    name: &str,
    c: &Case<L, H, N>,
    timed: bool,
) {
    if timed {
        let (h, a) = (
            timing::min_ns(60, IT, || hand_calls(c)),
            timing::min_ns(60, IT, || ad_calls(c)),
        );
        let l = timing::min_ns(60, IT, || value_calls(c));
        println!(
            "{name}: hand {h:.1} ns, ad {a:.1} ns ({:.2}x); L alone in f64 {l:.1} ns ({:.2}x hand)",
            a / h,
            l / h
        );
    } else {
        println!("{}", ad_calls(c) + hand_calls(c) + value_calls(c));
    }
}

fn main() {
    let dp = Case::new(
        DoublePendulum::default(),
        DoublePendulum::hand_accelerations,
        [0.7, -1.9],
        [1.3, 0.4],
    );
    let top = Case::new(
        HeavyTop::default(),
        HeavyTop::hand_accelerations,
        [0.8, 0.3, -1.2],
        [0.4, 1.1, 7.5],
    );
    let chain = Case::new(
        Chain::<10>::default(),
        Chain::<10>::hand_accelerations,
        std::array::from_fn(|k| 0.3 * (k as f64).sin() + 0.1),
        std::array::from_fn(|k| 0.5 * (1.7 * k as f64).cos()),
    );
    // `cargo bench` passes `--bench`: time all three; a system's name selects a callgrind run.
    let which = std::env::args().nth(1).unwrap_or_default();
    let timed = which.is_empty() || which.starts_with('-');
    if timed || which == "dp" {
        run("double pendulum", &dp, timed);
    }
    if timed || which == "top" {
        run("heavy top", &top, timed);
    }
    if timed || which == "chain" {
        run("10-link chain", &chain, timed);
    }
}
