//! Issue 29 item 7: the Lie-group variational integrator refuses a step that does not move t.

use noether_core::{Error, Momenta, State, Stepper};
use noether_rigid::{Lgvi, RigidBody};

/// At t = 1e20 a step of 1e-3 does not move t: `StepBelowTimeResolution`, the state unchanged
/// (before: Ok with t unchanged).
#[test]
fn regress_lgvi_step_below_time_resolution() {
    let mut lgvi = Lgvi::new(RigidBody::free(1.0, 2.0, 3.0).unwrap()).unwrap();
    let mut s: State<Momenta> = State::with_momenta(1e20, [1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.5, 0.0]);
    let before = s.clone();
    let err = lgvi.step(&mut s, 1e-3).unwrap_err();
    assert_eq!(err, Error::StepBelowTimeResolution { t: 1e20, h: 1e-3 });
    assert_eq!(s, before);
    // At t = 0 the same step is taken.
    let mut s: State<Momenta> = State::with_momenta(0.0, [1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.5, 0.0]);
    lgvi.step(&mut s, 1e-3).unwrap();
    assert_eq!(s.t, 1e-3);
}
