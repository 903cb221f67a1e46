//! Bad input gets a clear error and the state is left untouched.

use crate::models::{Kepler, Pendulum};
use noether_core::{Error, Newton, State, Stepper};
use noether_discrete::{DiscreteFlow, Midpoint, VariationalIntegrator};

#[test]
fn bad_input_step_size() {
    let mut vi = VariationalIntegrator::new(Midpoint::new(Pendulum));
    let mut s = State::new(0.0, [1.0], [0.0]);
    for h in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(vi.step(&mut s, h), Err(Error::InvalidStep { .. })),
            "h = {h}"
        );
    }
    // The signed flow accepts negative steps but not zero.
    let (mut q, mut p) = ([1.0], [0.0]);
    assert!(matches!(
        vi.flow(0.0, 0.0, &mut q, &mut p),
        Err(Error::InvalidStep { .. })
    ));
    assert_eq!(s, State::new(0.0, [1.0], [0.0]));
}

#[test]
fn bad_input_dimensions_and_nan() {
    let mut vi = VariationalIntegrator::new(Midpoint::new(Kepler));
    let mut s = State::new(0.0, [1.0], [0.0, 1.0]);
    assert!(matches!(vi.step(&mut s, 0.1), Err(Error::Dimension { .. })));
    let mut s = State::new(0.0, [1.0, f64::NAN], [0.0, 1.0]);
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
    let mut vi =
        VariationalIntegrator::new(Midpoint::new(Kepler)).with_newton(Newton::default().max_iterations(5));
    let mut s = vi.state_from_velocities(0.0, &[0.1, 0.0], &[0.0, 4.2]).unwrap();
    let before = s.clone();
    match vi.step(&mut s, 50.0) {
        Err(Error::NewtonDiverged {
            iterations,
            residual,
            tolerance,
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
