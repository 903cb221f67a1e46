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
use noether_core::{HamiltonEquations, Hamiltonian, LegendreTransform, Scalar};
use std::hint::black_box;
use std::time::Duration;

#[allow(dead_code)]
#[path = "../tests/ad/systems.rs"]
mod systems;
use systems::DoublePendulum;

/// Double pendulum by hand: H = ½ pᵀ M(q)⁻¹ p − (m1+m2) g l1 cos θ1 − m2 g l2 cos θ2 (the 2×2 inverse
/// by its adjugate), as in the `ad` tests.
struct DoublePendulumH(DoublePendulum);

impl Hamiltonian for DoublePendulumH {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let s = &self.0;
        let a11 = (s.m1 + s.m2) * s.l1 * s.l1;
        let a22 = s.m2 * s.l2 * s.l2;
        let a12 = (q[0] - q[1]).cos() * (s.m2 * s.l1 * s.l2);
        let det = -a12 * a12 + a11 * a22;
        (p[0] * p[0] * a22 - p[0] * p[1] * a12 * 2.0 + p[1] * p[1] * a11) / (det * 2.0)
            - q[0].cos() * ((s.m1 + s.m2) * s.g * s.l1)
            - q[1].cos() * (s.m2 * s.g * s.l2)
    }
}

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
