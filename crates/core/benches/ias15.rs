//! IAS15 against DOP853 on the same `Natural` Kepler problem (μ = 1, a = 1, e = 0.6, from pericentre
//! as REBOUND sets it up), 100 orbits, error |q(200π) − q₀| (issue 16's measure), dense output off
//! (`Save::End`). IAS15 at ε = 1e-5 .. 1e-9 (1e-9 is the default), DOP853 at atol = rtol = 1e-8 ..
//! 1e-14 (the tightest decade the step controller accepts: rtol ≥ `RTOL_FLOOR` = 10 ε ≈ 2.2e-15), one
//! evaluation of the force alone (`kick_rate`), and IAS15 at ε = 1e-9 through `VelocityDependent`
//! (the velocity-dependent path on the same orbit). Before timing, one line per run on stderr: error,
//! steps, rejected steps, evaluations of the force (and predictor-corrector rounds for IAS15).
//!
//! `cargo bench -p noether-core --bench ias15`.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use noether_core::integrators::VelocityDependent;
use noether_core::prelude::*;
use std::hint::black_box;
use std::time::Duration;

use noether_testkit::kepler::{start_state as start, Kepler, T_END};

/// Runs `stepper` over 100 orbits: (error |q(200π) − q₀|, stats).
fn run<S: Stepper<Partner = Velocities>>(stepper: S) -> (f64, noether_core::Stats) {
    let s0 = start();
    let sol = Driver::new(stepper, s0.clone())
        .and_then(|d| d.save(Save::End))
        .and_then(|mut d| d.run_until(T_END))
        .expect("run");
    ((sol.last().q.clone() - s0.q).norm(), *sol.stats())
}

fn ias15(eps: f64) -> Ias15<Natural<Kepler>> {
    Ias15::new(Natural::unit(Kepler))
        .and_then(|s| s.epsilon(eps))
        .expect("IAS15")
}

fn dop853(tol: f64) -> Dop853<Natural<Kepler>> {
    Dop853::new(Natural::unit(Kepler))
        .tolerances(tol, tol)
        .expect("DOP853")
}

const EPSILONS: [f64; 5] = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9];
/// DOP853's tolerances, down to the tightest decade above [`RTOL_FLOOR`] (a tolerance below it is an
/// `InvalidParameter`, which `dop853` would turn into a panic).
const TOLERANCES: [f64; 7] = [1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14];
const _: () = assert!(TOLERANCES[TOLERANCES.len() - 1] >= RTOL_FLOOR);

fn bench(c: &mut Criterion) {
    for eps in EPSILONS {
        let (err, st) = run(ias15(eps));
        eprintln!(
            "IAS15  eps {eps:.0e}: error {err:.2e}, {} steps, {} rejected, {} evaluations, {} rounds",
            st.steps, st.rejected, st.evaluations, st.newton_iterations
        );
    }
    for tol in TOLERANCES {
        let (err, st) = run(dop853(tol));
        eprintln!(
            "DOP853 tol {tol:.0e}: error {err:.2e}, {} steps, {} rejected, {} evaluations",
            st.steps, st.rejected, st.evaluations
        );
    }
    let mut g = c.benchmark_group("kepler_e06_100_orbits");
    for eps in EPSILONS {
        g.bench_function(format!("ias15_eps{eps:.0e}"), |b| {
            b.iter(|| run(ias15(black_box(eps))).0)
        });
    }
    // The same orbit through the velocity-dependent path (VelocityDependent: v predicted at the nodes,
    // f from the rates at (t, q, v)): the same steps, so the ratio is that path's own cost.
    g.bench_function("ias15_velocity_path_eps1e-9", |b| {
        b.iter(|| run(Ias15::new(VelocityDependent(Natural::unit(Kepler))).expect("IAS15")).0)
    });
    for tol in TOLERANCES {
        g.bench_function(format!("dop853_tol{tol:.0e}"), |b| {
            b.iter(|| run(dop853(black_box(tol))).0)
        });
    }
    // One evaluation of f alone, to split a run's time into evaluations and the method's own work.
    let natural = Natural::unit(Kepler);
    let (q, mut a) = ([0.4, 0.1], [0.0; 2]);
    g.bench_function("kick_rate", |b| {
        b.iter(|| natural.kick_rate(black_box(&q), &mut a).map(|()| a[0]))
    });
    g.finish();
}

fn config() -> Criterion {
    // Short runs: the machine is shared. Ratios are what matter, measured in one run.
    Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1500))
        .sample_size(10)
}

criterion_group! { name = benches; config = config(); targets = bench }
criterion_main!(benches);
