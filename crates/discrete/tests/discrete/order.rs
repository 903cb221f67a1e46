//! Observed orders of the discrete Lagrangians against closed forms: after exactly one period of a
//! periodic orbit the exact flow returns to its start (pendulum: T = 4K(sin(θ₀/2)); Kepler with a = 1:
//! T = 2π), so the error of the discrete state after N = T/h steps is the global error. The observed
//! order is log₂(err(h)/err(h/2)); it must be within 0.1 of the nominal order (the step sizes are chosen
//! in the asymptotic range and with errors far above rounding).

use crate::models::{kepler_start, pendulum_period, Kepler, Pendulum};
use noether_core::{Lagrangian, Stepper};

/// Every state here is in position-momentum form (q, p).
type State = noether_core::State<noether_core::Momenta>;
use noether_core::integrators::{Composition, Weights};
use noether_discrete::{FromLagrangian, Galerkin, Midpoint, Trapezoidal, VariationalIntegrator};

/// Max-norm error of the state after `n` steps of size `period/n` from `start`.
fn period_error<S: Stepper<Partner = noether_core::Momenta>>(
    stepper: &mut S,
    start: &State,
    period: f64,
    n: usize,
) -> f64 {
    let h = period / n as f64;
    let mut s = start.clone();
    for _ in 0..n {
        stepper.step(&mut s, h).unwrap();
    }
    (&s.q - &start.q).amax().max((&s.v - &start.v).amax())
}

fn start_state<L: Lagrangian>(vi: &VariationalIntegrator<Midpoint<L>>, q: &[f64], v: &[f64]) -> State {
    vi.state_from_velocities(0.0, q, v).unwrap()
}

/// Asserts the observed order of `make()` on the orbit from `start` with `n` and `2n` steps per period.
fn assert_order<S: Stepper<Partner = noether_core::Momenta>>(
    mut make: impl FnMut() -> S,
    start: &State,
    period: f64,
    n: usize,
    what: &str,
) {
    let (e1, e2) = (
        period_error(&mut make(), start, period, n),
        period_error(&mut make(), start, period, 2 * n),
    );
    let nominal = make().order() as f64;
    let observed = (e1 / e2).log2();
    eprintln!(
        "{what}: err({n}) = {e1:.3e}, err({}) = {e2:.3e}, observed order {observed:.3}",
        2 * n
    );
    assert!(
        e2 > 1e-11,
        "{what}: error {e2:e} too close to rounding to measure an order"
    );
    assert!(
        (observed - nominal).abs() < 0.1,
        "{what}: observed order {observed} vs nominal {nominal}"
    );
}

fn pendulum_start() -> (State, f64) {
    let vi = VariationalIntegrator::new(Midpoint::new(Pendulum));
    (start_state(&vi, &[1.0], &[0.0]), pendulum_period(1.0))
}

fn kepler_state() -> (State, f64) {
    let vi = VariationalIntegrator::new(Midpoint::new(Kepler));
    let (q, v) = kepler_start(0.5);
    (start_state(&vi, &q, &v), 2.0 * std::f64::consts::PI)
}

#[test]
fn order_midpoint_pendulum() {
    let (s, t) = pendulum_start();
    assert_order(
        || VariationalIntegrator::new(Midpoint::new(Pendulum)),
        &s,
        t,
        64,
        "midpoint/pendulum",
    );
}

#[test]
fn order_trapezoidal_pendulum() {
    let (s, t) = pendulum_start();
    let mk = || VariationalIntegrator::new(Trapezoidal::new(Pendulum));
    assert_order(mk, &s, t, 64, "trapezoidal/pendulum");
}

#[test]
fn order_composition4_pendulum() {
    let (s, t) = pendulum_start();
    let mk = || {
        Composition::new(
            VariationalIntegrator::new(Midpoint::new(Pendulum)),
            Weights::yoshida4(),
        )
    };
    assert_order(mk, &s, t, 32, "composition4(midpoint)/pendulum");
}

#[test]
fn order_composition6_pendulum() {
    let (s, t) = pendulum_start();
    let mk = || {
        Composition::new(
            VariationalIntegrator::new(Midpoint::new(Pendulum)),
            Weights::triple_jump6(),
        )
    };
    assert_order(mk, &s, t, 64, "composition6(midpoint)/pendulum");
}

#[test]
fn order_midpoint_kepler() {
    let (s, t) = kepler_state();
    assert_order(
        || VariationalIntegrator::new(Midpoint::new(Kepler)),
        &s,
        t,
        400,
        "midpoint/kepler",
    );
}

#[test]
fn order_trapezoidal_kepler() {
    let (s, t) = kepler_state();
    let mk = || VariationalIntegrator::new(Trapezoidal::new(Kepler));
    assert_order(mk, &s, t, 400, "trapezoidal/kepler");
}

#[test]
fn order_composition4_kepler() {
    let (s, t) = kepler_state();
    let mk = || {
        Composition::new(
            VariationalIntegrator::new(Trapezoidal::new(Kepler)),
            Weights::yoshida4(),
        )
    };
    assert_order(mk, &s, t, 200, "composition4(trapezoidal)/kepler");
}

#[test]
fn order_composition6_kepler() {
    let (s, t) = kepler_state();
    let mk = || {
        Composition::new(
            VariationalIntegrator::new(Midpoint::new(Kepler)),
            Weights::triple_jump6(),
        )
    };
    assert_order(mk, &s, t, 200, "composition6(midpoint)/kepler");
}

#[test]
fn order_galerkin4_pendulum() {
    let (s, t) = pendulum_start();
    let mk = || Galerkin::order4(Pendulum).unwrap();
    assert_order(mk, &s, t, 16, "galerkin4/pendulum");
}

#[test]
fn order_galerkin6_pendulum() {
    let (s, t) = pendulum_start();
    let mk = || Galerkin::order6(Pendulum).unwrap();
    assert_order(mk, &s, t, 16, "galerkin6/pendulum");
}

#[test]
fn order_galerkin4_kepler() {
    let (s, t) = kepler_state();
    let mk = || Galerkin::order4(Kepler).unwrap();
    assert_order(mk, &s, t, 100, "galerkin4/kepler");
}

#[test]
fn order_galerkin6_kepler() {
    let (s, t) = kepler_state();
    let mk = || Galerkin::order6(Kepler).unwrap();
    assert_order(mk, &s, t, 100, "galerkin6/kepler");
}

#[test]
fn closed_form_pendulum_energy_from_legendre() {
    // E = ½ p² − cos θ at (θ, p) = (1, 0.3): the energy reported along a discrete trajectory is the
    // continuous energy through the inverse Legendre map (exact here: p = θ̇).
    let vi = VariationalIntegrator::new(Midpoint::new(Pendulum));
    let e = vi.energy(&State::with_momenta(0.0, [1.0], [0.3])).unwrap();
    assert!((e - (0.045 - 1f64.cos())).abs() < 1e-15);
    let _ = vi.discrete_lagrangian().continuous();
}
