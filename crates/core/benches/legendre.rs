//! The Hamiltonian of a Lagrangian by `LegendreTransform` against a hand-written H, for the double
//! pendulum: one evaluation of Hamilton's equations (∂H/∂p, ∂H/∂q by `HamiltonEquations::rates`) and
//! of the Hessian of H (what Gauss-Legendre's Newton Jacobian needs), side by side in one run. Both
//! sides are differentiated by the same AD kernels; the transform adds the real solve for q̇(p) and,
//! for the Hessian, one chord-Newton step in the dual scalar. Calls alternate between two states 1e-6
//! apart (as the stages of an implicit step do), so that no call sees the state of the one before.
//!
//! `cargo bench -p noether-core --bench legendre`; results in docs/benchmarks.md.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use noether_core::{HamiltonEquations, LegendreTransform};
use std::hint::black_box;
use std::time::Duration;

use noether_testkit::systems::{DoublePendulum, DoublePendulumH};

fn bench(c: &mut Criterion) {
    let sys = DoublePendulum::default();
    let hand = HamiltonEquations::new(DoublePendulumH(sys));
    let from_l = HamiltonEquations::new(LegendreTransform::new(sys));
    let states = [
        ([0.6, -0.4], [1.3, -0.7]),
        ([0.6 + 1e-6, -0.4], [1.3, -0.7 - 1e-6]),
    ];
    let mut g = c.benchmark_group("legendre_rates_double_pendulum");
    g.bench_function("hand", |b| {
        let (mut dq, mut dp) = ([0.0; 2], [0.0; 2]);
        let mut k = 0;
        b.iter(|| {
            k += 1;
            let (q, p) = &states[k % 2];
            hand.rates(0.0, black_box(q), black_box(p), &mut dq, &mut dp)
                .unwrap();
            dq[0] + dp[0]
        })
    });
    g.bench_function("legendre", |b| {
        let (mut dq, mut dp) = ([0.0; 2], [0.0; 2]);
        let mut k = 0;
        b.iter(|| {
            k += 1;
            let (q, p) = &states[k % 2];
            from_l
                .rates(0.0, black_box(q), black_box(p), &mut dq, &mut dp)
                .unwrap();
            dq[0] + dp[0]
        })
    });
    g.finish();
    let mut g = c.benchmark_group("legendre_hessian_double_pendulum");
    g.bench_function("hand", |b| {
        let mut k = 0;
        b.iter(|| {
            k += 1;
            let (q, p) = &states[k % 2];
            hand.hessian(0.0, black_box(q), black_box(p)).unwrap()[(0, 0)]
        })
    });
    g.bench_function("legendre", |b| {
        let mut k = 0;
        b.iter(|| {
            k += 1;
            let (q, p) = &states[k % 2];
            from_l.hessian(0.0, black_box(q), black_box(p)).unwrap()[(0, 0)]
        })
    });
    g.finish();
}

fn config() -> Criterion {
    // Short runs: the machine is shared. Ratios are what matter, measured in one run.
    Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1500))
        .sample_size(20)
}

criterion_group! { name = benches; config = config(); targets = bench }
criterion_main!(benches);
