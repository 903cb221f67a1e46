//! Dormand-Prince 5(4) and 8(5,3): orders (fixed steps), dense output, error control, events.

use super::order::{assert_order, errors, errors_vs, pendulum_start, ECC, THETA0, T_KEPLER};
use super::problems::*;
use noether_core::prelude::*;

// DOPRI5 and DOP853 are built to have tiny principal error coefficients, so on strongly nonlinear
// problems their global errors show pre-asymptotic slopes (DOPRI5 5.1-5.4, DOP853 7.6-9.5 on Kepler
// e = 0.5) until rounding is reached. The h^p term dominates, with errors far above rounding, on the
// pendulum (θ₀ = 1.5 for DOPRI5; θ₀ = 0.3, still nonlinear, for DOP853) and on the harmonic
// oscillator q̈ = −q (closed form q = cos t), where the fitted slopes are within 0.05 of p. Fixed
// steps (no error control) expose the order of the propagated solution.

fn harmonic_errors<S: Stepper>(make: impl FnMut() -> S, ns: &[usize]) -> Vec<(f64, f64)> {
    let t_end = 10.0_f64;
    let exact = (vec![t_end.cos()], vec![-t_end.sin()]);
    errors_vs(make, &State::from_parts(0.0, [1.0], [0.0]), t_end, &exact, ns)
}

#[test]
fn order_dopri5() {
    let e = errors(
        || Dopri5::new(EulerLagrange::new(PendulumL)).fixed_step(true),
        &pendulum_start(),
        super::order::T_PENDULUM,
        &[226, 320, 452],
    );
    assert_order("DOPRI5 / pendulum θ₀ = 1.5", 5, &e);
    let e = harmonic_errors(
        || Dopri5::new(Natural::unit(HarmonicV)).fixed_step(true),
        &[113, 160, 226],
    );
    assert_order("DOPRI5 / harmonic oscillator", 5, &e);
}

#[test]
fn order_dop853() {
    let t_end = 10.0;
    let (q, v) = pendulum_exact(0.3, t_end);
    let e = errors_vs(
        || Dop853::new(EulerLagrange::new(PendulumL)).fixed_step(true),
        &State::new(0.0, [0.3], [0.0]),
        t_end,
        &(vec![q], vec![v]),
        &[14, 20, 28],
    );
    assert_order("DOP853 / pendulum θ₀ = 0.3", 8, &e);
    let e = harmonic_errors(
        || Dop853::new(Natural::unit(HarmonicV)).fixed_step(true),
        &[20, 28, 40],
    );
    assert_order("DOP853 / harmonic oscillator", 8, &e);
}

/// Local error of the dense output at the middle of one step of size h started on the exact Kepler
/// orbit at t₀ = 0.3: O(h^{p*+1}) for a continuous extension of order p*.
fn dense_midpoint_errors<M: EmbeddedPair>(hs: &[f64]) -> Vec<(f64, f64)> {
    let t0 = 0.3;
    let (q0, p0) = kepler_exact(ECC, t0);
    hs.iter()
        .map(|&h| {
            let mut s = Adaptive::<_, M>::new(EulerLagrange::new(KeplerL)).fixed_step(true);
            let mut state = State::new(t0, q0, p0);
            s.step(&mut state, h).unwrap();
            let mid = s.dense_output().unwrap().state_at(t0 + 0.5 * h).unwrap();
            let (q, p) = kepler_exact(ECC, t0 + 0.5 * h);
            (h, distance(&mid, &q, &p))
        })
        .collect()
}

#[test]
fn order_dense_output() {
    // DOPRI5's continuous extension has order 4 (local error h^5), DOP853's order 7 (local error h^8).
    let hs = [0.025, 0.025 / 2f64.sqrt(), 0.0125];
    assert_order(
        "DOPRI5 dense output (local)",
        5,
        &dense_midpoint_errors::<Dp5>(&hs),
    );
    let hs = [0.2 / 2f64.sqrt(), 0.1, 0.1 / 2f64.sqrt()];
    assert_order(
        "DOP853 dense output (local)",
        8,
        &dense_midpoint_errors::<Dp853>(&hs),
    );
}

/// Adaptive run on Kepler e = 0.5 over 5 periods at tolerances 1e-10: (largest error at the ends of
/// the accepted steps, largest error of the dense output at θ = 1/4, 1/2, 3/4 inside them).
fn endpoint_and_interior_errors<M: EmbeddedPair>() -> (f64, f64, usize) {
    let mut s = Adaptive::<_, M>::new(EulerLagrange::new(KeplerL))
        .tolerances(1e-10, 1e-10)
        .unwrap();
    let mut state = kepler_start(ECC);
    let mut h = s.initial_step(&state).unwrap().unwrap();
    let mut steps = 0;
    let (mut end_err, mut mid_err) = (0.0_f64, 0.0_f64);
    let err = |st: &State| {
        let (q, p) = kepler_exact(ECC, st.t);
        distance(st, &q, &p)
    };
    while state.t < 10.0 * std::f64::consts::PI {
        h = s.step(&mut state, h).unwrap().h_next;
        steps += 1;
        end_err = end_err.max(err(&state));
        let d = s.dense_output().unwrap();
        for theta in [0.25, 0.5, 0.75] {
            mid_err = mid_err.max(err(&d
                .state_at(d.t_start() + theta * (d.t_end() - d.t_start()))
                .unwrap()));
        }
    }
    (end_err, mid_err, steps)
}

#[test]
fn closed_form_dense_output_as_accurate_as_steps() {
    // Kepler's equation gives the exact orbit. The dense output adds an interpolation error of the
    // size of one step's local error (~tol) to the global error, which after 5 periods is far larger:
    // inside the steps the error must stay within 1.5× the largest error at the step ends. Tightening
    // the tolerance is checked to shrink the global error in `closed_form_error_control_tracks_tolerance`;
    // here it must be below 1e4·tol = 1e-6 (a loose sanity bound: ~10³ steps, linear phase growth).
    for (name, (end, mid, steps)) in [
        ("DOPRI5", endpoint_and_interior_errors::<Dp5>()),
        ("DOP853", endpoint_and_interior_errors::<Dp853>()),
    ] {
        eprintln!("{name}: step ends {end:.2e}, inside steps {mid:.2e}, {steps} steps");
        assert!(
            mid <= 1.5 * end,
            "{name}: dense output {mid:e} vs step ends {end:e}"
        );
        assert!(end < 1e-6, "{name}: {end:e}");
    }
}

#[test]
fn closed_form_driver_samples_requested_times() {
    // The driver returns exactly the requested times (from the dense output), lands on t_end, and
    // agrees with the exact orbit as well as the step ends do (see above: < 1e-6 at tol 1e-10).
    let times: Vec<f64> = (0..=100).map(|i| i as f64 * 0.1).collect();
    let s = Dopri5::new(EulerLagrange::new(KeplerL))
        .tolerances(1e-10, 1e-10)
        .unwrap();
    let sol = Driver::new(s, kepler_start(ECC))
        .unwrap()
        .save(Save::Times(times.clone()))
        .unwrap()
        .run_until(12.0)
        .unwrap();
    assert_eq!(sol.times(), &times[..]);
    assert_eq!(sol.last().t, 12.0);
    assert_eq!(sol.interpolation_order(), Some(4));
    for st in (0..sol.len())
        .map(|i| sol.state(i))
        .chain(std::iter::once(sol.last().clone()))
    {
        let (q, p) = kepler_exact(ECC, st.t);
        assert!(distance(&st, &q, &p) < 1e-6, "t = {}", st.t);
    }
    assert_eq!(sol.state(0), kepler_start(ECC));
}

#[test]
fn closed_form_error_control_tracks_tolerance() {
    // Tightening the tolerance 1000× must shrink the global error by between 100× and 10⁵× (the
    // error is proportional to the tolerance up to the step-count factor) and take more steps.
    let run = |tol: f64| {
        let s = Dopri5::new(EulerLagrange::new(KeplerL))
            .tolerances(tol, tol)
            .unwrap();
        let sol = Driver::new(s, kepler_start(ECC))
            .unwrap()
            .save(Save::End)
            .unwrap()
            .run_until(T_KEPLER)
            .unwrap();
        let (q, p) = kepler_exact(ECC, T_KEPLER);
        (distance(sol.last(), &q, &p), *sol.stats())
    };
    let (e1, s1) = run(1e-6);
    let (e2, s2) = run(1e-9);
    eprintln!("tol 1e-6: {e1:.2e} {s1:?}; tol 1e-9: {e2:.2e} {s2:?}");
    assert!(e1 / e2 > 100.0 && e1 / e2 < 1e5, "{e1:e} {e2:e}");
    assert!(s2.steps > s1.steps);
    // DOPRI5 is FSAL: six new evaluations per accepted or rejected step (the first stage of the
    // first step is F(t₀, y₀) from the initial-step choice, counted there, as in Hairer's code).
    for st in [s1, s2] {
        assert_eq!(st.evaluations, 6 * (st.steps + st.rejected), "{st:?}");
    }
}

#[test]
fn closed_form_rejections_counted() {
    // A first step of 1.0 on Kepler e = 0.9 near pericentre is far too large: it is rejected (and
    // counted) until the error estimate passes, and the step actually taken is smaller.
    let mut s = Dopri5::new(EulerLagrange::new(KeplerL))
        .tolerances(1e-8, 1e-8)
        .unwrap();
    let mut state = kepler_start(0.9);
    let info = s.step(&mut state, 1.0).unwrap();
    assert!(info.rejected > 0 && info.h < 1.0 && state.t == info.h);
    assert_eq!(info.evaluations, 1 + 6 * (info.rejected + 1));
}

/// Steps until the dense output shows θ crossing 0; returns the located time.
fn first_zero_of_theta<M: EmbeddedPair>() -> f64 {
    let mut s = Adaptive::<_, M>::new(Natural::unit(PendulumV))
        .tolerances(1e-12, 1e-12)
        .unwrap();
    let mut state = pendulum_start();
    let mut h = 0.01;
    loop {
        h = s.step(&mut state, h).unwrap().h_next;
        if let Some(t) = s.dense_output().unwrap().locate(|st: &State| st.q[0]).unwrap() {
            return t;
        }
        assert!(state.t < 10.0, "no crossing found");
    }
}

#[test]
fn closed_form_event_quarter_period() {
    // Pendulum from rest at θ₀ = 1.5: θ first crosses 0 at a quarter period, t = K(sin²(θ₀/2)).
    // Tolerances 1e-12 and a root located to 1e-14 on the dense output: agreement to 1e-9.
    let expected = elliptic_k((THETA0 / 2.0).sin().powi(2));
    for (name, t) in [
        ("DOPRI5", first_zero_of_theta::<Dp5>()),
        ("DOP853", first_zero_of_theta::<Dp853>()),
    ] {
        assert!((t - expected).abs() < 1e-9, "{name}: {t} vs {expected}");
    }
}

#[test]
fn closed_form_event_quarter_period_by_the_driver() {
    // The same event through the driver: θ = 0 falling, terminal; the run stops there.
    let expected = elliptic_k((THETA0 / 2.0).sin().powi(2));
    let s = Dop853::new(Natural::unit(PendulumV))
        .tolerances(1e-12, 1e-12)
        .unwrap();
    let sol = Driver::new(s, pendulum_start())
        .unwrap()
        .event(Event::new("θ = 0", |s: &State| s.q[0]).falling().terminal())
        .run_until(10.0)
        .unwrap();
    assert_eq!(sol.stop(), Stop::Event(0));
    assert!(
        (sol.last().t - expected).abs() < 1e-9,
        "{} vs {expected}",
        sol.last().t
    );
    assert!(sol.last().q[0].abs() < 1e-12 && sol.event_times("θ = 0").unwrap() == vec![sol.last().t]);
}

#[test]
fn closed_form_driver_uses_adaptive_steps() {
    // The driver follows h_next: harmonic-like pendulum at small amplitude, q ≈ 0.01 cos t.
    let s = Dopri5::new(Natural::unit(PendulumV))
        .tolerances(1e-12, 1e-12)
        .unwrap();
    let sol = Driver::new(s, State::new(0.0, [0.01], [0.0]))
        .unwrap()
        .step_size(1e-3)
        .unwrap()
        .run_until(3.0)
        .unwrap();
    let (q, _) = pendulum_exact(0.01, 3.0);
    let end = sol.last();
    assert!(end.t == 3.0 && (end.q[0] - q).abs() < 1e-11);
    assert!(sol.stats().steps < 200, "{:?}", sol.stats());
    assert_eq!(sol.len(), sol.stats().steps + 1);
}

#[test]
fn bad_input_failing_reset_ends_the_run_with_its_error() {
    // A reset that fails half-way (it changes v, then reports an error) ends the run with that
    // error, and the driver's state is the state at the event, as it was before the reset began.
    let s = Dop853::new(Natural::unit(PendulumV))
        .tolerances(1e-12, 1e-12)
        .unwrap();
    let mut driver = Driver::new(s, pendulum_start()).unwrap().event(
        Event::new("θ = 0", |s: &State| s.q[0]).falling().try_reset(|s| {
            s.v[0] = 1e3;
            Err(Error::Unsupported("a reset that fails"))
        }),
    );
    let e = driver.run_until(10.0).unwrap_err();
    assert_eq!(e, Error::Unsupported("a reset that fails"));
    let at = driver.state();
    let expected = elliptic_k((THETA0 / 2.0).sin().powi(2));
    // At the event (located to 1e-14 on the dense output; the run's tolerance gives 1e-9 in t), with
    // the velocity the pendulum had there, not the reset's 1e3: |θ̇| = 2 sin(θ₀/2) at the bottom (unit
    // pendulum, energy).
    assert!(at.q[0].abs() < 1e-12 && (at.t - expected).abs() < 1e-9, "{at:?}");
    assert!(
        (at.v[0].abs() - 2.0 * (THETA0 / 2.0).sin()).abs() < 1e-9,
        "{at:?}"
    );
}
