//! Bad input gets a clear error and the state is left untouched.

use crate::models::{Kepler, Pendulum};
use noether_core::{Error, Newton, Stepper};

/// Every state here is in position-momentum form (q, p).
type State = noether_core::State<noether_core::Momenta>;
use noether_core::integrators::SignedStepper;
use noether_discrete::{Galerkin, Midpoint, VariationalIntegrator};

#[test]
fn bad_input_step_size() {
    let mut vi = VariationalIntegrator::new(Midpoint::new(Pendulum));
    let mut s = State::with_momenta(0.0, [1.0], [0.0]);
    for h in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(vi.step(&mut s, h), Err(Error::InvalidStep { .. })),
            "h = {h}"
        );
    }
    // The signed step accepts negative steps but not zero.
    assert!(matches!(
        vi.step_signed(&mut s, 0.0),
        Err(Error::InvalidStep { .. })
    ));
    assert_eq!(s, State::with_momenta(0.0, [1.0], [0.0]));
}

#[test]
fn bad_input_dimensions_and_nan() {
    let mut vi = VariationalIntegrator::new(Midpoint::new(Kepler));
    let mut s = State::with_momenta(0.0, [1.0], [0.0, 1.0]);
    assert!(matches!(vi.step(&mut s, 0.1), Err(Error::Dimension { .. })));
    let mut s = State::with_momenta(0.0, [1.0, f64::NAN], [0.0, 1.0]);
    assert!(matches!(vi.step(&mut s, 0.1), Err(Error::NonFinite { .. })));
    assert!(matches!(
        vi.state_from_positions(0.0, 0.1, &[1.0, 0.0], &[1.0]),
        Err(Error::Dimension { .. })
    ));
    assert!(matches!(
        vi.state_from_velocities(0.0, &[1.0, 0.0], &[f64::INFINITY, 0.0]),
        Err(Error::NonFinite { .. })
    ));
}

/// A step far too large for Newton (h = 50 on a Kepler orbit through the pericentre, capped at
/// 5 iterations) returns `NewtonDiverged` with the iterations and the last residual, and the state
/// before the failed step is kept intact.
#[test]
fn bad_input_newton_not_converging_keeps_state() {
    let mut vi = VariationalIntegrator::new(Midpoint::new(Kepler))
        .newton(Newton::default().max_iterations(5).unwrap());
    let mut s = vi.state_from_velocities(0.0, &[0.1, 0.0], &[0.0, 4.2]).unwrap();
    let before = s.clone();
    match vi.step(&mut s, 50.0) {
        Err(Error::NewtonDiverged {
            iterations,
            residual,
            tolerance,
            ..
        }) => {
            assert_eq!(iterations, 5);
            assert!(
                residual > tolerance,
                "residual {residual:e} tolerance {tolerance:e}"
            );
        }
        other => panic!("expected a Newton failure, got {other:?}"),
    }
    assert_eq!(s, before);
}

/// The Galerkin integrator: zero/negative/NaN steps and wrong dimensions are refused, a Lagrangian
/// with a generalized force is refused at construction (discrete forces are not supported), and
/// Newton capped at one iteration on a large step (h = 50 near the pericentre, where one iteration
/// from the straight-path guess cannot reach the rounding-level tolerance) returns `NewtonDiverged`
/// with the iterations and the residual, the state intact.
#[test]
fn bad_input_galerkin() {
    let mut g = Galerkin::order6(Kepler)
        .unwrap()
        .newton(Newton::default().max_iterations(1).unwrap());
    let mut s = State::with_momenta(0.0, [0.1, 0.0], [0.0, 4.2]);
    let before = s.clone();
    for h in [0.0, -0.1, f64::NAN] {
        assert!(matches!(g.step(&mut s, h), Err(Error::InvalidStep { .. })));
    }
    let mut short = State::with_momenta(0.0, [1.0], [0.0, 1.0]);
    assert!(matches!(g.step(&mut short, 0.1), Err(Error::Dimension { .. })));
    match g.step(&mut s, 50.0) {
        Err(Error::NewtonDiverged {
            iterations,
            residual,
            tolerance,
            ..
        }) => {
            assert_eq!(iterations, 1);
            assert!(residual > tolerance);
        }
        other => panic!("expected a Newton failure, got {other:?}"),
    }
    assert_eq!(s, before);
}

/// Issue 29 item 7: a variational step that does not move t (t = 1e20, h = 1e-3) is refused with
/// `StepBelowTimeResolution`, by the step and by the tangent step, the state unchanged; before, both
/// returned Ok with t unchanged.
#[test]
fn regress_variational_step_below_time_resolution() {
    use noether_core::TangentStepper;
    let mut vi = VariationalIntegrator::new(Midpoint::new(Pendulum));
    let mut s = State::with_momenta(1e20, [1.0], [0.0]);
    let err = vi.step(&mut s, 1e-3).unwrap_err();
    assert_eq!(err, Error::StepBelowTimeResolution { t: 1e20, h: 1e-3 });
    let mut psi = nalgebra::DMatrix::zeros(2, 2);
    let err = vi.step_tangent(&mut s, 1e-3, &mut psi).unwrap_err();
    assert_eq!(err, Error::StepBelowTimeResolution { t: 1e20, h: 1e-3 });
    assert_eq!(s, State::with_momenta(1e20, [1.0], [0.0]));
    let mut g = Galerkin::order6(Pendulum).unwrap();
    let err = g.step(&mut s, 1e-3).unwrap_err();
    assert_eq!(err, Error::StepBelowTimeResolution { t: 1e20, h: 1e-3 });
    assert_eq!(s, State::with_momenta(1e20, [1.0], [0.0]));
}
