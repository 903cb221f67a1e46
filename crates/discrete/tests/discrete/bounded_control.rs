//! Optimal control with bounded inputs (SQP with Clarabel's subproblems, polished by Newton on the
//! active set): the double integrator's saturated minimum-effort transfer against its closed form, an
//! infeasible bound refused with its data, the cart-pole swing-up with a bounded force replayed
//! through the forced variational integrator, the pendubot's (a double pendulum with a shoulder motor)
//! likewise, the globalisation of a swing-up where Newton alone
//! diverges, and bad bounds.

use crate::optimal_control::{least_effort, replay, replay_of, swing_up};
use noether_core::Error;
use noether_discrete::optimal_control::{Failure, NoOptimalPath, OptimalPath};
use noether_testkit::control::{CartPole, DoubleIntegrator, Pendubot};
use std::f64::consts::PI;

/// q̈ = u from rest at 0 to rest at 1 in T = 1 with |u| ≤ `bound`, minimum ∫u² dt, N steps.
fn double_integrator(bound: f64, steps: usize) -> noether_core::Result<OptimalPath> {
    least_effort(DoubleIntegrator)
        .input_bounds(&[-bound], &[bound])?
        .solve(0.0, (&[0.0], &[0.0]), 1.0, (&[1.0], &[0.0]), steps)
}

/// The saturated minimum-effort transfer of q̈ = u, |u| ≤ U, from rest at 0 to rest at 1 in time T.
/// Pontryagin's principle gives u = sat_U(−p_v/2) with the costate p_v linear in t, and the symmetry
/// of the problem makes u odd about T/2: u(t) = sat_U(a(T/2 − t)), saturated for |T/2 − t| ≥ s* =
/// U/a. Its end position ∫₀ᵀ (T − t) u dt = ∫₀^{T/2} 2s·min(U, a s) ds = U (T²/4 − s*²/3) = 1 gives
///
///   s*² = 3 (T²/4 − 1/U),   J = ∫u² dt = U² (T − 4s*/3),
///
/// for 4/T² ≤ U ≤ 6/T² (at U = 6/T², s* = T/2 and J = 12/T³, the unbounded optimum; below 4/T² no
/// input reaches the end: bang-bang at U = 4/T² is the fastest transfer). Returns (s*, J).
fn saturated_closed_form(bound: f64, t_end: f64) -> (f64, f64) {
    let s = (3.0 * (t_end * t_end / 4.0 - 1.0 / bound)).sqrt();
    (s, bound * bound * (t_end - 4.0 * s / 3.0))
}

/// With U = 5 (between 4 and 6, T = 1) the bound is active on [0, T/2 − s*] and [T/2 + s*, T]. The
/// discrete optimum (exact dynamics for piecewise-constant u, as for the unbounded problem) converges
/// to J at second order: measured errors 1.081e-3 (N = 100) and 1.075e-5 (N = 1000), order 2.002, so
/// the test asks for order 2 ± 0.05 and the N = 1000 error below 1.1e-5 (h²·10.9, its constant).
/// The inputs the bound holds are exactly ±U (the polishing solve holds them; their count is the
/// closed form's 2(T/2 − s*)/h to ±2, the kinks falling between nodes), and all inputs meet the
/// closed form at the step midpoints to second order too (measured 4.6 h² at N = 100 and 3.9 h² at
/// N = 1000; bound 5 h²). The solve is two SQP iterations and then Newton on the active set.
#[test]
fn double_integrator_meets_the_saturated_closed_form() {
    let (bound, t_end) = (5.0, 1.0);
    let (s_star, cost) = saturated_closed_form(bound, t_end);
    let errors: Vec<f64> = [100, 1000]
        .iter()
        .map(|&steps| {
            let path = double_integrator(bound, steps).unwrap();
            let h = t_end / steps as f64;
            let ramp = bound / s_star;
            let worst = path
                .u
                .iter()
                .enumerate()
                .map(|(k, u)| {
                    let t = (k as f64 + 0.5) * h;
                    (u[0] - (ramp * (t_end / 2.0 - t)).clamp(-bound, bound)).abs()
                })
                .fold(0.0, f64::max);
            let held = path.u.iter().filter(|u| u[0].abs() == bound).count();
            let expected = 2.0 * (t_end / 2.0 - s_star) / h;
            println!(
                "N = {steps}: cost {:.12} vs {cost:.12}, inputs within {worst:.1e}, {held} held at ±U \
                 (closed form {expected:.1}); {} SQP + {} Newton iterations",
                path.cost, path.sqp_iterations, path.newton.iterations
            );
            assert!(worst < 5.0 * h * h, "N = {steps}: inputs off by {worst:e}");
            assert!(
                (held as f64 - expected).abs() <= 2.0,
                "{held} held, {expected} expected"
            );
            assert!(path.u.iter().all(|u| u[0].abs() <= bound));
            path.cost - cost
        })
        .collect();
    let order = (errors[0] / errors[1]).log10();
    println!("errors {:.3e}, {:.3e}: order {order:.3}", errors[0], errors[1]);
    assert!((order - 2.0).abs() < 0.05, "order {order}");
    assert!(errors[1] > 0.0 && errors[1] < 1.1e-5, "{:e}", errors[1]);
}

/// A bound that does not bind (U = 10 > max |u| = 6/T²) changes nothing: the bounded solve meets the
/// unbounded discrete optimum J_d = 12/(T(T² − h²)) to rounding (bound 1e-14 relative, as for the
/// unbounded solve in `optimal_control.rs`).
#[test]
fn inactive_bounds_leave_the_optimum_unchanged() {
    for steps in [10, 100] {
        let path = double_integrator(10.0, steps).unwrap();
        let h = 1.0 / steps as f64;
        let cost = 12.0 / (1.0 - h * h);
        println!(
            "N = {steps}: relative error {:.1e}",
            (path.cost - cost).abs() / cost
        );
        assert!(
            (path.cost - cost).abs() < 1e-14 * cost,
            "N = {steps}: {} vs {cost}",
            path.cost
        );
    }
}

/// Below U = 4/T² no input within the bounds reaches the end at rest (for even N the discrete
/// bang-bang input is exact: q(T) = U T²/4 < 1): the typed error `Infeasible`, with how far the
/// discrete equations stay from being met at the least-infeasible point SQP stops at (measured
/// ‖c‖∞ = 0.025000000007; the test asks 0.025 to 1e-6).
#[test]
fn infeasible_bounds_are_a_typed_error_with_their_data() {
    let err = double_integrator(3.9, 100).unwrap_err();
    println!("{err}");
    match noether_discrete::Error::from(err) {
        noether_discrete::Error::NoOptimalPath(NoOptimalPath {
            failure: Failure::Infeasible,
            iterations,
            violation,
            ..
        }) => {
            assert!(iterations >= 1);
            assert!((violation - 0.025).abs() < 1e-6, "{violation}");
        }
        other => panic!("expected an infeasible problem, got {other:?}"),
    }
}

/// The cart-pole swing-up of `optimal_control.rs` (T = 2, N = 100) with the cart's force bounded by
/// |u| ≤ 12 (the unbounded optimum reaches 15.8): the optimum holds the force at the bound on some
/// steps, costs more than the unbounded one (measured 111.008 against 107.700), and is a motion of
/// the forced variational integrator (replayed open loop: nodes within 2e-14, end velocity 8e-14;
/// bound 1e-13 and 1e-12, the two Newton solves' floors as in `optimal_control.rs`). With an
/// infinite bound the SQP solve finds the unbounded Newton solution (the same KKT point, to 1e-12).
#[test]
fn cart_pole_swing_up_with_a_bounded_force() {
    let swing = |bound: f64| {
        let problem = least_effort(CartPole::default())
            .input_bounds(&[-bound], &[bound])
            .unwrap();
        swing_up(&problem, 2.0).unwrap()
    };
    let free = swing_up(&least_effort(CartPole::default()), 2.0).unwrap();
    let unbounded = swing(f64::INFINITY);
    assert!((unbounded.cost - free.cost).abs() < 1e-12 * free.cost);
    let bounded = swing(12.0);
    let held = bounded.u.iter().filter(|u| u[0].abs() == 12.0).count();
    let (worst, v_end) = replay(&bounded, &[0.0, 0.0]);
    println!(
        "bounded swing-up: cost {:.6} (unbounded {:.6}), {held} steps at the bound, {} SQP + {} Newton \
         iterations; replay within {worst:.1e}, end velocity {v_end:.1e}",
        bounded.cost, free.cost, bounded.sqp_iterations, bounded.newton.iterations
    );
    assert!(held > 0 && bounded.u.iter().all(|u| u[0].abs() <= 12.0));
    assert!(bounded.cost > free.cost);
    assert!(worst < 1e-13 && v_end < 1e-12, "{worst:e} {v_end:e}");
}

/// The swing-up in T = 2.5 from the straight line: Newton on the KKT system alone diverges (or meets
/// a singular matrix), the SQP solve (infinite bounds) reaches the optimum (measured 7 SQP + 6 Newton
/// iterations), a motion of the forced variational integrator as above.
#[test]
fn sqp_globalises_a_swing_up_newton_cannot_solve() {
    assert!(swing_up(&least_effort(CartPole::default()), 2.5).is_err());
    let globalised = least_effort(CartPole::default())
        .input_bounds(&[f64::NEG_INFINITY], &[f64::INFINITY])
        .unwrap();
    let path = swing_up(&globalised, 2.5).unwrap();
    let (worst, v_end) = replay(&path, &[0.0, 0.0]);
    println!(
        "T = 2.5: cost {:.6}, {} SQP + {} Newton iterations; replay within {worst:.1e}, end velocity \
         {v_end:.1e}",
        path.cost, path.sqp_iterations, path.newton.iterations
    );
    assert!(worst < 1e-13 && v_end < 1e-12, "{worst:e} {v_end:e}");
}

/// Bounds of the wrong length, NaN, a lower bound above the upper one, or +∞ below are refused with
/// their data.
#[test]
fn bad_bounds_are_refused() {
    let problem = || least_effort(DoubleIntegrator);
    assert!(matches!(
        problem().input_bounds(&[0.0, 1.0], &[1.0]).err(),
        Some(Error::Dimension {
            expected: 1,
            got: 2,
            ..
        })
    ));
    for (lo, hi, value) in [
        (f64::NAN, 1.0, f64::NAN),
        (2.0, 1.0, 2.0),
        (f64::INFINITY, f64::INFINITY, f64::INFINITY),
        (0.0, f64::NEG_INFINITY, f64::NEG_INFINITY),
    ] {
        match problem().input_bounds(&[lo], &[hi]).err() {
            Some(Error::InvalidParameter { value: v, .. }) => {
                assert!(v == value || (v.is_nan() && value.is_nan()), "{v} vs {value}")
            }
            other => panic!("({lo}, {hi}): {other:?}"),
        }
    }
}

/// The double pendulum swung up by a bounded shoulder torque (the pendubot, underactuated: the
/// lower rod follows through the coupling only) from hanging at rest to upright at rest in T = 3,
/// N = 100, |u| ≤ 20 (the unbounded optimum needs 40.8): SQP from the straight line between the two
/// rests (measured 17 SQP + 5 Newton iterations, cost 490.49 against 441.90 unbounded), the torque at
/// its bound on some steps and never beyond, and the replay through the forced variational
/// integrator upright at rest: measured nodes within 4.1e-13 and end velocity 2.3e-12, ten times the
/// cart-pole's because the replay is an initial-value run along a motion that ends on the unstable
/// upright equilibrium of a chaotic system, which amplifies the replay's per-step Newton residual
/// (1e-12) and rounding; bounds 1e-12 and 1e-11.
#[test]
fn pendubot_swing_up_with_a_bounded_torque() {
    let bound = 20.0;
    let path = least_effort(Pendubot::default())
        .input_bounds(&[-bound], &[bound])
        .unwrap()
        .solve(
            0.0,
            (&[0.0, 0.0], &[0.0, 0.0]),
            3.0,
            (&[PI, PI], &[0.0, 0.0]),
            100,
        )
        .unwrap();
    let peak = path.u.iter().map(|u| u[0].abs()).fold(0.0, f64::max);
    let (worst, v_end) = replay_of(Pendubot::default(), &path, &[0.0, 0.0]);
    println!(
        "pendubot: cost {:.4}, {} SQP + {} Newton iterations, largest |u| {peak}; replay within \
         {worst:.1e}, end velocity {v_end:.1e}",
        path.cost, path.sqp_iterations, path.newton.iterations
    );
    assert_eq!(peak, bound);
    assert!(worst < 1e-12 && v_end < 1e-11, "{worst:e} {v_end:e}");
    assert_eq!(path.q[100].as_slice(), &[PI, PI]);
}
