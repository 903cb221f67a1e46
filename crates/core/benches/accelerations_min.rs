//! AD accelerations against hand-written ones under load: the minimum over many short rounds of the
//! time per call (interference from other processes only ever adds time), and fixed call counts for
//! instruction counting with callgrind.
//!
//! - `cargo bench -p noether-core --bench accelerations_min`: min-of-rounds times and ratios;
//! - `valgrind --tool=callgrind <binary> dp|top|chain`: 10 000 calls of each side; the inclusive counts
//!   of `dp_ad`, `dp_hand`, … divided by 10 000 are the instructions per call.
//!
//! Results in docs/benchmarks.md. Complements the criterion bench `accelerations`.

#![allow(clippy::type_complexity)]

use noether_core::EulerLagrange;
use std::hint::black_box;
#[allow(dead_code)]
#[path = "../tests/ad/systems.rs"]
mod systems;
use systems::{Chain, DoublePendulum, HeavyTop};
const IT: usize = 10000;

#[inline(never)]
fn dp_ad(el: &EulerLagrange<DoublePendulum>, q: &[f64; 2], v: &[f64; 2]) -> f64 {
    let mut s = 0.0;
    let mut a = [0.0; 2];
    for _ in 0..IT {
        el.accelerations(black_box(0.0), black_box(q), black_box(v), &mut a)
            .unwrap();
        s += a[0];
    }
    s
}
#[inline(never)]
fn dp_hand(l: &DoublePendulum, q: &[f64; 2], v: &[f64; 2]) -> f64 {
    let mut s = 0.0;
    for _ in 0..IT {
        s += l.hand_accelerations(black_box(q), black_box(v))[0];
    }
    s
}
#[inline(never)]
fn top_ad(el: &EulerLagrange<HeavyTop>, q: &[f64; 3], v: &[f64; 3]) -> f64 {
    let mut s = 0.0;
    let mut a = [0.0; 3];
    for _ in 0..IT {
        el.accelerations(black_box(0.0), black_box(q), black_box(v), &mut a)
            .unwrap();
        s += a[0];
    }
    s
}
#[inline(never)]
fn top_hand(l: &HeavyTop, q: &[f64; 3], v: &[f64; 3]) -> f64 {
    let mut s = 0.0;
    for _ in 0..IT {
        s += l.hand_accelerations(black_box(q), black_box(v))[0];
    }
    s
}
#[inline(never)]
fn chain_ad(el: &EulerLagrange<Chain<10>>, q: &[f64; 10], v: &[f64; 10]) -> f64 {
    let mut s = 0.0;
    let mut a = [0.0; 10];
    for _ in 0..IT {
        el.accelerations(black_box(0.0), black_box(q), black_box(v), &mut a)
            .unwrap();
        s += a[0];
    }
    s
}
#[inline(never)]
fn chain_hand(l: &Chain<10>, q: &[f64; 10], v: &[f64; 10]) -> f64 {
    let mut s = 0.0;
    for _ in 0..IT {
        s += l.hand_accelerations(black_box(q), black_box(v))[0];
    }
    s
}

/// Min over rounds of the time per call (ns): interference from other processes only adds time.
fn min_ns(mut f: impl FnMut() -> f64) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..60 {
        let t0 = std::time::Instant::now();
        black_box(f());
        best = best.min(t0.elapsed().as_nanos() as f64 / IT as f64);
    }
    best
}

/// The same for a slow call: many short rounds of 200 calls.
fn min_ns_short<const N: usize>(mut f: impl FnMut() -> [f64; N]) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..3000 {
        let t0 = std::time::Instant::now();
        for _ in 0..200 {
            black_box(f());
        }
        best = best.min(t0.elapsed().as_nanos() as f64 / 200.0);
    }
    best
}

fn main() {
    // `cargo bench` passes `--bench`; any other first argument selects a callgrind run.
    let w = std::env::args().nth(1).unwrap_or_default();
    if w.is_empty() || w.starts_with('-') {
        let dp = DoublePendulum::default();
        let (dq, dv) = ([0.7, -1.9], [1.3, 0.4]);
        let top = HeavyTop::default();
        let (tq, tv) = ([0.8, 0.3, -1.2], [0.4, 1.1, 7.5]);
        let ch = Chain::<10>::default();
        let cq: [f64; 10] = std::array::from_fn(|k| 0.3 * (k as f64).sin() + 0.1);
        let cv: [f64; 10] = std::array::from_fn(|k| 0.5 * (1.7 * k as f64).cos());
        let (e1, e2, e3) = (
            EulerLagrange::new(dp),
            EulerLagrange::new(top),
            EulerLagrange::new(ch),
        );
        let r = [
            min_ns(|| dp_hand(&dp, &dq, &dv)),
            min_ns(|| dp_ad(&e1, &dq, &dv)),
            min_ns(|| top_hand(&top, &tq, &tv)),
            min_ns(|| top_ad(&e2, &tq, &tv)),
            min_ns_short(|| ch.hand_accelerations(black_box(&cq), black_box(&cv))),
            min_ns_short(|| {
                let mut a = [0.0; 10];
                e3.accelerations(black_box(0.0), black_box(&cq), black_box(&cv), &mut a)
                    .unwrap();
                a
            }),
        ];
        println!(
            "dp hand {:.1} ad {:.1} ({:.2}x) | top hand {:.1} ad {:.1} ({:.2}x) | chain10 hand {:.0} ad {:.0} ({:.2}x)",
            r[0], r[1], r[1] / r[0], r[2], r[3], r[3] / r[2], r[4], r[5], r[5] / r[4]
        );
        return;
    }
    let dp = DoublePendulum::default();
    let (dq, dv) = ([0.7, -1.9], [1.3, 0.4]);
    let top = HeavyTop::default();
    let (tq, tv) = ([0.8, 0.3, -1.2], [0.4, 1.1, 7.5]);
    let ch = Chain::<10>::default();
    let cq: [f64; 10] = std::array::from_fn(|k| 0.3 * (k as f64).sin() + 0.1);
    let cv: [f64; 10] = std::array::from_fn(|k| 0.5 * (1.7 * k as f64).cos());
    let r = match w.as_str() {
        "dp" => dp_ad(&EulerLagrange::new(dp), &dq, &dv) + dp_hand(&dp, &dq, &dv),
        "top" => top_ad(&EulerLagrange::new(top), &tq, &tv) + top_hand(&top, &tq, &tv),
        "chain" => chain_ad(&EulerLagrange::new(ch), &cq, &cv) + chain_hand(&ch, &cq, &cv),
        _ => 0.0,
    };
    println!("{r}");
}
