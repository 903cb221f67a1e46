//! q̈ of a 7-link planar arm built from bodies and joints (`noether_testkit::multibody::rod_chain`),
//! per call, three ways: Lagrange's equations of the built L by dual numbers (`EulerLagrange`, the
//! generic path), the same equations compiled (`CompiledEulerLagrange`: recorded once, derived on the
//! graph, run by the interpreter), and the recursive Newton-Euler algorithm on f64 (`NewtonEuler`).
//!
//! Run: `cargo bench -p noether-multibody --bench accelerations`

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use noether_compile::CompiledEulerLagrange;
use noether_core::prelude::*;
use noether_multibody::NewtonEuler;
use noether_testkit::multibody::rod_chain;
use std::hint::black_box;
use std::time::Duration;

fn bench(c: &mut Criterion) {
    let n = 7;
    let masses: Vec<f64> = (0..n).map(|i| 1.0 - 0.08 * i as f64).collect();
    let lengths: Vec<f64> = (0..n).map(|i| 0.5 - 0.03 * i as f64).collect();
    let arm = rod_chain(&masses, &lengths, 9.81);
    let q: Vec<f64> = (0..n).map(|i| 0.3 + 0.2 * i as f64).collect();
    let v: Vec<f64> = (0..n).map(|i| 0.5 - 0.15 * i as f64).collect();
    let (mut dq, mut dv) = (vec![0.0; n], vec![0.0; n]);
    let mut group = c.benchmark_group("arm7_accelerations");
    group
        .sample_size(30)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    let el = EulerLagrange::new(arm.clone());
    group.bench_function("euler_lagrange_dual", |b| {
        b.iter(|| {
            el.rates(0.0, black_box(&q), black_box(&v), &mut dq, &mut dv)
                .unwrap()
        })
    });
    let compiled = CompiledEulerLagrange::new(EulerLagrange::new(arm.clone())).unwrap();
    group.bench_function("euler_lagrange_compiled", |b| {
        b.iter(|| {
            compiled
                .rates(0.0, black_box(&q), black_box(&v), &mut dq, &mut dv)
                .unwrap()
        })
    });
    let ne = NewtonEuler::new(arm).unwrap();
    group.bench_function("newton_euler", |b| {
        b.iter(|| {
            ne.rates(0.0, black_box(&q), black_box(&v), &mut dq, &mut dv)
                .unwrap()
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
