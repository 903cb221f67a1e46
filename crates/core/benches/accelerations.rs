//! AD-derived accelerations against hand-written ones, side by side in one run, for the double pendulum,
//! the heavy symmetric top (Euler angles) and a 10-link pendulum chain.
//!
//! `cargo bench -p noether-core --bench accelerations`; results in docs/benchmarks.md.

use criterion::{criterion_group, criterion_main, Criterion};
use noether_core::EulerLagrange;
use std::hint::black_box;
use std::time::Duration;

#[allow(dead_code)]
#[path = "../tests/ad/systems.rs"]
mod systems;
use systems::{Chain, DoublePendulum, HeavyTop};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("double_pendulum");
    let dp = DoublePendulum::default();
    let el = EulerLagrange::new(dp);
    let (q, v) = ([0.7, -1.9], [1.3, 0.4]);
    g.bench_function("hand", |b| {
        b.iter(|| dp.hand_accelerations(black_box(&q), black_box(&v)))
    });
    g.bench_function("ad", |b| {
        let mut a = [0.0; 2];
        b.iter(|| {
            el.accelerations(black_box(0.0), black_box(&q), black_box(&v), &mut a)
                .unwrap();
            a
        })
    });
    g.finish();

    let mut g = c.benchmark_group("heavy_top");
    let top = HeavyTop::default();
    let el = EulerLagrange::new(top);
    let (q, v) = ([0.8, 0.3, -1.2], [0.4, 1.1, 7.5]);
    g.bench_function("hand", |b| {
        b.iter(|| top.hand_accelerations(black_box(&q), black_box(&v)))
    });
    g.bench_function("ad", |b| {
        let mut a = [0.0; 3];
        b.iter(|| {
            el.accelerations(black_box(0.0), black_box(&q), black_box(&v), &mut a)
                .unwrap();
            a
        })
    });
    g.finish();

    let mut g = c.benchmark_group("chain10");
    let chain = Chain::<10>::default();
    let el = EulerLagrange::new(chain);
    let q: [f64; 10] = std::array::from_fn(|k| 0.3 * (k as f64).sin() + 0.1);
    let v: [f64; 10] = std::array::from_fn(|k| 0.5 * (1.7 * k as f64).cos());
    g.bench_function("hand", |b| {
        b.iter(|| chain.hand_accelerations(black_box(&q), black_box(&v)))
    });
    g.bench_function("ad", |b| {
        let mut a = [0.0; 10];
        b.iter(|| {
            el.accelerations(black_box(0.0), black_box(&q), black_box(&v), &mut a)
                .unwrap();
            a
        })
    });
    g.finish();
}

fn config() -> Criterion {
    // Short runs: the machine is shared. Ratios are what matter, measured in one run.
    Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1200))
        .sample_size(20)
}

criterion_group! { name = benches; config = config(); targets = bench }
criterion_main!(benches);
