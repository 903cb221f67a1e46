//! One step of the constrained variational integrator on the 10-link Cartesian pendulum chain
//! (20 coordinates, 10 rod constraints) against one step of the unconstrained variational integrator
//! on the same chain in angle coordinates (10 coordinates), both with the midpoint discrete Lagrangian
//! and Newton to rounding. Both trajectories keep moving (each iteration continues from the last state).
//!
//! Run: `cargo bench -p noether-constraints --bench chain_step`

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use noether_constraints::prelude::*;
use noether_discrete::{Midpoint, VariationalIntegrator};
use std::hint::black_box;
use std::time::Duration;

#[path = "../tests/it/chain.rs"]
#[allow(dead_code)]
mod chain;
use chain::*;

fn bench(c: &mut Criterion) {
    let (n, m, l, g, h) = (10, 1.0, 0.5, 9.81, 1e-3);
    let (angles, cart) = chain_states(n, l);
    let mut group = c.benchmark_group("chain10_step");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(4));

    let mut rattle = Rattle::new(Midpoint::new(CartesianChain { n, m, g }), Rods { n, l }).unwrap();
    let mut s = rattle
        .state_from_velocities(0.0, cart.q.as_slice(), cart.v.as_slice())
        .unwrap();
    group.bench_function("rattle_cartesian_20q_10c", |b| {
        b.iter(|| {
            rattle.step(black_box(&mut s), h).unwrap();
        })
    });

    let mut vi = VariationalIntegrator::new(Midpoint::new(AngleChain { n, m, l, g }));
    let mut a = vi
        .state_from_velocities(0.0, angles.q.as_slice(), angles.v.as_slice())
        .unwrap();
    group.bench_function("variational_angles_10q", |b| {
        b.iter(|| {
            vi.step(black_box(&mut a), h).unwrap();
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
