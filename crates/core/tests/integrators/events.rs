//! The driver's promises about events, resets, output times and failed runs (issue 29): each test is
//! named for the defect it guards against.

use super::problems::*;
use noether_core::prelude::*;

const G: f64 = 9.81;
/// Coefficient of restitution of the bouncing ball.
const E: f64 = 0.9;

/// Free fall, V = g y.
struct Fall;
impl Potential for Fall {
    fn dof(&self) -> usize {
        1
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        q[0] * G
    }
}

/// The impact times of a ball dropped from rest at height h₀ up to `t_end`: free fall gives the first
/// impact at t₁ = √(2h₀/g) with speed u = √(2 g h₀); the k-th rebound leaves at speed eᵏu and flies
/// for 2eᵏu/g (kinematics of a parabola and Newton's law of restitution).
fn impacts(h0: f64, t_end: f64) -> Vec<f64> {
    let u = (2.0 * G * h0).sqrt();
    let mut t = (2.0 * h0 / G).sqrt();
    let mut out = Vec::new();
    let mut k = 1;
    while t <= t_end {
        out.push(t);
        t += 2.0 * E.powi(k) * u / G;
        k += 1;
    }
    out
}

/// Runs the ball to t = 3 (four impacts) with a reset v ← −e v at each, and checks every impact time
/// and the final height against the closed form. Any method of order ≥ 2 and any interpolant of order
/// ≥ 2 is exact on a parabola, so what is left is rounding: 1e-12 covers a few ulps per bounce
/// carried through four bounces (measured ≤ 2e-15 s).
fn bounce_to_3<S: Stepper<Partner = Velocities>>(name: &str, driver: Driver<'_, S>) {
    let mut driver = driver.event(
        Event::new("floor", |s: &State| s.q[0])
            .falling()
            .reset(|s| s.v[0] *= -E),
    );
    let sol = driver.run_until(3.0).unwrap();
    let expected = impacts(1.0, 3.0);
    let found = sol.event_times("floor").unwrap();
    assert_eq!(
        found.len(),
        expected.len(),
        "{name}: impacts {found:?} vs {expected:?}"
    );
    for (t, e) in found.iter().zip(&expected) {
        assert!((t - e).abs() < 1e-12, "{name}: impact {t} vs {e}");
    }
    // After the last impact t₄ the ball rises at e⁴u: y(3) = e⁴u τ − g τ²/2 with τ = 3 − t₄.
    let (u, tau) = ((2.0 * G).sqrt(), 3.0 - expected[3]);
    let y = E.powi(4) * u * tau - 0.5 * G * tau * tau;
    assert!(
        (sol.last().q[0] - y).abs() < 1e-11,
        "{name}: y(3) = {} vs {y}",
        sol.last().q[0]
    );
    assert!(
        (0..sol.len()).all(|i| sol.q(i)[0] > -1e-12),
        "{name}: below the floor"
    );
}

#[test]
fn regress_bouncing_ball_every_bounce_with_every_adaptive_method() {
    // Issue 29 item 1: the first step after a reset used to start from g = 0, which never fires, so
    // an adaptive method's long step over the next flight missed the landing (DOP853 found 2 of 4
    // bounces and ended 8.55 m below the floor; DOPRI5 at its defaults found 1).
    let start = || State::new(0.0, [1.0], [0.0]);
    let sys = || Natural::unit(Fall);
    bounce_to_3(
        "DOPRI5 defaults",
        Driver::new(Dopri5::new(sys()), start()).unwrap(),
    );
    bounce_to_3(
        "DOP853 1e-12",
        Driver::new(Dop853::new(sys()).tolerances(1e-12, 1e-12).unwrap(), start()).unwrap(),
    );
    bounce_to_3(
        "DOP853 defaults",
        Driver::new(Dop853::new(sys()), start()).unwrap(),
    );
    bounce_to_3(
        "DPRKN6",
        Driver::new(Dprkn6::new(sys()).unwrap(), start()).unwrap(),
    );
    bounce_to_3(
        "DPRKN8",
        Driver::new(Dprkn8::new(sys()).unwrap(), start()).unwrap(),
    );
    bounce_to_3(
        "DPRKN12",
        Driver::new(Dprkn12::new(sys()).unwrap(), start()).unwrap(),
    );
    bounce_to_3("IAS15", Driver::new(Ias15::new(sys()).unwrap(), start()).unwrap());
    // A fixed step as long as a flight, for the Hermite interpolant.
    bounce_to_3(
        "RK4 h = 0.5",
        Driver::with_step(Rk4::new(sys()), start(), 0.5).unwrap(),
    );
}

#[test]
fn regress_event_with_g_zero_at_the_start() {
    // A ball thrown up from the floor (g = 0 at the start) lands within the first long step: the
    // start's sign is taken just after it, so the landing at t = 2u/g is seen.
    let u = 3.0;
    let sol = Driver::new(Dop853::new(Natural::unit(Fall)), State::new(0.0, [0.0], [u]))
        .unwrap()
        .event(Event::new("floor", |s: &State| s.q[0]).falling().terminal())
        .run_until(10.0)
        .unwrap();
    assert_eq!(sol.stop(), Stop::Event(0));
    // Exact on a parabola to rounding.
    assert!((sol.last().t - 2.0 * u / G).abs() < 1e-13, "{}", sol.last().t);
}

#[test]
fn regress_terminal_event_does_not_fire_again_when_continued() {
    // Issue 29 item 2: the stop state is the located root, which may lie just before the crossing,
    // and the next run_until crossed it again at once (six calls stopped at the same t). The unit
    // pendulum at small amplitude θ₀ = 0.01 crosses θ = 0 downwards at a quarter period and then once
    // per period T = 4K(sin²(θ₀/2)) (Jacobi elliptic functions).
    let s = Rk4::new(Natural::unit(PendulumV));
    let mut driver = Driver::with_step(s, State::new(0.0, [0.01], [0.0]), 0.01)
        .unwrap()
        .event(Event::new("θ = 0 down", |s: &State| s.q[0]).falling().terminal());
    let quarter = elliptic_k((0.005f64).sin().powi(2));
    let mut stops = Vec::new();
    for _ in 0..10 {
        let sol = driver.run_until(20.0).unwrap();
        if sol.stop() == Stop::EndTime {
            break;
        }
        stops.push(sol.last().t);
    }
    // Crossings at K, 5K, 9K < 20 < 13K (K ≈ 1.5708): three stops, then the end.
    assert_eq!(stops.len(), 3, "{stops:?}");
    for (k, t) in stops.iter().enumerate() {
        let exact = quarter * (1 + 4 * k) as f64;
        // RK4 with h = 0.01: a phase error ~ h⁴ t / 180 per unit time and the Hermite interpolant's
        // h⁴/384: 1e-8 covers both with a margin of about 10.
        assert!((t - exact).abs() < 1e-8, "stop {k}: {t} vs {exact}");
    }
    assert_eq!(driver.state().t, 20.0);
}

#[test]
fn regress_reset_that_moves_time_forward() {
    // Issue 29 item 3: a reset that moved t forward filled the output times it skipped from the next
    // step's interpolant outside its step (q = −3 for a ball that never goes below 0). Now such a time
    // is an error naming it, with the run up to the event kept; times after the gap are sampled
    // from the steps that contain them, and a reset may not move time backward.
    let dead_time = |s: &mut State| {
        s.v[0] *= -E;
        s.t += 0.5;
    };
    let ball = || {
        Driver::new(Dop853::new(Natural::unit(Fall)), State::new(0.0, [1.0], [0.0]))
            .unwrap()
            .event(Event::new("floor", |s: &State| s.q[0]).falling().reset(dead_time))
    };
    let t1 = (2.0 / G).sqrt();
    let mut driver = ball().save(Save::Times(vec![0.1, 0.7, 1.2])).unwrap();
    let err = driver.run_until(1.5).unwrap_err();
    assert!(
        matches!(err, Error::InvalidParameter { name: "output time", value, .. } if value == 0.7),
        "{err}"
    );
    let partial = driver.take_partial_solution().unwrap();
    assert_eq!(partial.times(), &[0.1]);
    assert!((driver.state().t - t1).abs() < 1e-13, "{:?}", driver.state());

    // Times after the gap: the ball leaves the floor at t₁ + 0.5 with speed e u.
    let times = vec![0.1, t1 + 0.6, t1 + 0.8];
    let sol = ball()
        .save(Save::Times(times.clone()))
        .unwrap()
        .run_until(1.5)
        .unwrap();
    assert_eq!(sol.times(), &times[..]);
    let u = (2.0 * G).sqrt();
    for (i, tau) in [(1, 0.1), (2, 0.3)] {
        let y = E * u * tau - 0.5 * G * tau * tau;
        assert!((sol.q(i)[0] - y).abs() < 1e-12, "row {i}: {} vs {y}", sol.q(i)[0]);
    }

    let backward = Event::new("floor", |s: &State| s.q[0])
        .falling()
        .reset(|s| s.t -= 0.1);
    let err = Driver::new(Dop853::new(Natural::unit(Fall)), State::new(0.0, [1.0], [0.0]))
        .unwrap()
        .event(backward)
        .run_until(1.0)
        .unwrap_err();
    assert!(
        matches!(
            err,
            Error::InvalidParameter {
                name: "t after a reset",
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn regress_event_function_not_finite_inside_a_step() {
    // Issue 29 item 4: g finite at both ends of a step but NaN around its root ended with Ok and the
    // event 0.02 off. q = cos t crosses 0.7 at t = acos 0.7 ≈ 0.7954, inside the RK4 step (0.7, 0.8];
    // g is NaN on (0.78, 0.8).
    let mut driver = Driver::with_step(
        Rk4::new(Natural::unit(HarmonicV)),
        State::new(0.0, [1.0], [0.0]),
        0.1,
    )
    .unwrap()
    .event(Event::new("q = 0.7", |s: &State| {
        if s.t > 0.78 && s.t < 0.8 {
            f64::NAN
        } else {
            s.q[0] - 0.7
        }
    }));
    let err = driver.run_until(1.0).unwrap_err();
    assert!(
        matches!(err, Error::NonFiniteResult { t, .. } if t > 0.78 && t < 0.8),
        "{err}"
    );
    // The state is the last good one: the end of the step that contains the NaN.
    assert!((driver.state().t - 0.8).abs() < 1e-15, "{:?}", driver.state());
}

#[test]
fn regress_run_that_could_never_finish_is_refused() {
    // Issue 29 item 8: h = 5e-324 asked for 2e323 steps and hung. A fixed-step run needing more steps
    // than the limit (10¹⁰ by default) is refused before its first step; the limit can be raised.
    let sys = || Natural::unit(HarmonicV);
    let start = || State::new(0.0, [1.0], [0.0]);
    let err = Driver::with_step(Rk4::new(sys()), start(), 5e-324)
        .unwrap()
        .run_until(1.0)
        .unwrap_err();
    assert!(matches!(err, Error::InvalidParameter { name: "h", .. }), "{err}");
    let mut d = Driver::with_step(Rk4::new(sys()), start(), 0.01)
        .unwrap()
        .max_steps(50);
    assert!(matches!(
        d.run_until(1.0),
        Err(Error::InvalidParameter { name: "h", .. })
    ));
    assert_eq!(d.state().t, 0.0);
    let mut d = Driver::with_step(Rk4::new(sys()), start(), 0.01)
        .unwrap()
        .max_steps(100);
    assert_eq!(d.run_until(1.0).unwrap().stats().steps, 100);
}

#[test]
fn regress_output_times_read_in_place() {
    // Issue 29 item 9: the list of output times was cloned at every step (10⁶ times over 10⁵ steps:
    // 27 s). Now read in place; the rows agree with q = cos t to the method's error.
    let n = 100_000;
    let times: Vec<f64> = (0..=n).map(|i| i as f64 * 1e-4).collect();
    let sol = Driver::with_step(
        Rk4::new(Natural::unit(HarmonicV)),
        State::new(0.0, [1.0], [0.0]),
        1e-3,
    )
    .unwrap()
    .save(Save::Times(times.clone()))
    .unwrap()
    .run_until(10.0)
    .unwrap();
    assert_eq!(sol.times(), &times[..]);
    // RK4's global error at h = 1e-3 over t = 10 is ~1e-13, the Hermite interpolant's h⁴/384 ≈ 3e-15.
    let worst = (0..sol.len())
        .map(|i| (sol.q(i)[0] - times[i].cos()).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-11, "{worst}");
}

#[test]
fn regress_solution_at_every_saved_time_of_a_long_run() {
    // Issue 29 item 14: the dense output refused a time more than 1e-12 h past its step, less than
    // the rounding of t at large t (the unit test `regress_step_end_accepted_at_large_times` in
    // dense.rs shows the margin). Here, from t₀ = 1e6 (ulp 1.2e-10, steps of 1e-3 at pericentre),
    // every step's end and every saved time of Solution::at must be accepted and give the computed
    // state. The time itself is known to an ulp, so the state at "t" differs from the saved
    // one by up to |ẏ| times a few ulps of t:
    // ẏ = (v, −q/r³), |v̇| = 1/r²; the tolerance is 8 ulps of t times that, plus 1e-13 of the state
    // for the interpolant's own rounding.
    let mut s = Dop853::new(Natural::unit(KeplerV))
        .tolerances(1e-14, 1e-14)
        .unwrap();
    s.request_dense_output(true);
    let t0 = 1e6;
    let mut state = kepler_start(0.9);
    state.t = t0;
    let mut h = 1e-3;
    while state.t < t0 + 10.0 * std::f64::consts::TAU {
        h = s.step(&mut state, h).unwrap().h_next;
        let at = s.dense_output().unwrap().state_at(state.t);
        assert!(at.is_ok(), "t = {}", state.t);
    }
    let mut start = kepler_start(0.9);
    start.t = t0;
    let sol = Driver::new(s, start)
        .unwrap()
        .keep_dense_output(true)
        .run_until(t0 + 10.0 * std::f64::consts::TAU)
        .unwrap();
    assert!(sol.len() > 1000);
    for i in 0..sol.len() {
        let t = sol.times()[i];
        let at = sol.at(t).unwrap_or_else(|e| panic!("row {i}, t = {t}: {e}"));
        let (q, v) = (sol.q(i), sol.v(i));
        let r2 = q[0] * q[0] + q[1] * q[1];
        let speed = v[0].hypot(v[1]);
        let scale = 1.0 + q.iter().chain(v).fold(0.0f64, |m, x| m.max(x.abs()));
        let tol = 8.0 * f64::EPSILON * t * (speed + 1.0 / r2) + 1e-13 * scale;
        let diff = distance(&at, q, v);
        assert!(diff < tol, "row {i}: {diff} > {tol}");
    }
}

#[test]
fn regress_failed_run_keeps_its_partial_solution() {
    // Issue 29 item 15 (contract §3): after an error the driver holds the solution up to it. An
    // observer that fails from t = 0.5 on ends an RK4 run with h = 0.1 after the row at t = 0.4.
    let mut driver = Driver::with_step(
        Rk4::new(Natural::unit(HarmonicV)),
        State::new(0.0, [1.0], [0.0]),
        0.1,
    )
    .unwrap()
    .observe("q until 0.5", |s: &State| {
        if s.t < 0.45 {
            Ok(s.q[0])
        } else {
            Err(Error::Unsupported("past 0.5"))
        }
    });
    assert_eq!(driver.run_until(1.0).unwrap_err(), Error::Unsupported("past 0.5"));
    let partial = driver.take_partial_solution().unwrap();
    assert_eq!(partial.len(), 5);
    assert!((partial.times()[4] - 0.4).abs() < 1e-15);
    assert_eq!(partial.observed("q until 0.5").unwrap()[4], partial.q(4)[0]);
    assert_eq!(partial.stats().steps, 5);
    assert!(driver.take_partial_solution().is_none());
    assert!(partial.get(5).is_none() && partial.get(4).is_some());
}

#[test]
fn bad_input_unknown_observer_or_event_name_lists_the_recorded_ones() {
    // Issue 30 item 7: a typo in an observer or event name was silent (`observed` gave None,
    // `event_times` an empty list). It is UnknownName with the names the run recorded; a known event
    // that never fired is still an empty list, not an error.
    let sol = Driver::with_step(
        Rk4::new(Natural::unit(HarmonicV)),
        State::new(0.0, [1.0], [0.0]),
        0.1,
    )
    .unwrap()
    .observe("energy", |s: &State| 0.5 * (s.q[0] * s.q[0] + s.v[0] * s.v[0]))
    .observe("momentum", |s: &State| s.v[0])
    .event(Event::new("q = 0", |s: &State| s.q[0]))
    .event(Event::new("q = 2", |s: &State| s.q[0] - 2.0))
    .run_until(3.0)
    .unwrap();
    assert_eq!(sol.observed("energy").unwrap().len(), sol.len());
    let err = sol.observed("Energy").unwrap_err();
    assert_eq!(
        err,
        Error::UnknownName {
            kind: "observer",
            name: "Energy".into(),
            known: vec!["energy".into(), "momentum".into()],
        }
    );
    assert_eq!(
        err.to_string(),
        r#"no observer named "Energy"; the run recorded: "energy", "momentum""#
    );
    // q = cos t crosses 0 once before t = 3 (at π/2); q = 2 never.
    assert_eq!(sol.event_times("q = 0").unwrap().len(), 1);
    assert_eq!(sol.event_times("q = 2").unwrap(), Vec::<f64>::new());
    let err = sol.event_times("θ2=0").unwrap_err();
    assert_eq!(
        err.to_string(),
        r#"no event named "θ2=0"; the run recorded: "q = 0", "q = 2""#
    );
    assert!(matches!(
        sol.events_named("q=0").map(|e| e.count()),
        Err(Error::UnknownName { kind: "event", .. })
    ));
    // A run without observers says so.
    let bare = Driver::with_step(
        Rk4::new(Natural::unit(HarmonicV)),
        State::new(0.0, [1.0], [0.0]),
        0.1,
    )
    .unwrap()
    .run_until(0.2)
    .unwrap();
    assert_eq!(
        bare.observed("energy").unwrap_err().to_string(),
        r#"no observer named "energy"; the run recorded: (none)"#
    );
}
