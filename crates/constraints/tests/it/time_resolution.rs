//! Issue 29 item 7: RATTLE refuses a step that does not move t.

use noether_constraints::prelude::*;
use noether_discrete::Midpoint;

/// A point mass on the unit sphere (spherical pendulum), z up.
struct Mass;
impl Lagrangian for Mass {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * 0.5 - q[2] * 9.81
    }
}
struct Sphere;
impl Holonomic for Sphere {
    fn dof(&self) -> usize {
        3
    }
    fn count(&self) -> usize {
        1
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        out[0] = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - 1.0) * 0.5;
    }
}

/// At t = 1e20 a step of 1e-2 does not move t: `StepBelowTimeResolution`, the state unchanged
/// (before: Ok with t unchanged).
#[test]
fn regress_rattle_step_below_time_resolution() {
    let mut rattle = Rattle::new(Midpoint::new(Mass), Sphere).unwrap();
    let mut s = rattle
        .state_from_velocities(1e20, &[0.6, 0.0, -0.8], &[0.0, 2.0, 0.0])
        .unwrap();
    let before = s.clone();
    let err = rattle.step(&mut s, 1e-2).unwrap_err();
    assert_eq!(
        err,
        noether_core::Error::StepBelowTimeResolution { t: 1e20, h: 1e-2 }
    );
    assert_eq!(s, before);
}
