//! The index-1 equations with core's integrators: agreement with unconstrained formulations and
//! closed forms.

use crate::models::*;
use noether_constraints::prelude::*;

/// Cartesian pendulum (x, y) with the rod vs the angle formulation, both RK4 with h = 1e-3 over 5 s:
/// RK4's global error is O(h⁴) ~ 1e-12 for this smooth motion, so the angles agree to 1e-9; the tension
/// T = m g cos θ + m l θ̇² (radial Newton's law for circular motion) from the multiplier matches the
/// angle run to 1e-9 relative to m g.
#[test]
fn closed_form_cartesian_pendulum_matches_angle_and_tension() {
    let (m, l, g) = (1.5, 0.8, 9.81);
    let sys = Constrained::holonomic(Masses { n: 1, d: 2, m, g }, Rod { d: 2, l, copies: 1 }).unwrap();
    let angle = EulerLagrange::new(AnglePendulum { m, l, g });
    let (th0, om0) = (1.2, 0.7);
    let h = 1e-3;
    let cart = Driver::with_step(
        Projected::new(Rk4::new(&sys), sys.constraints()),
        pendulum_state(l, th0, om0),
        h,
    )
    .unwrap();
    let ang = Driver::with_step(Rk4::new(&angle), State::new(0.0, [th0], [om0]), h).unwrap();
    let (mut worst_angle, mut worst_tension) = (0.0_f64, 0.0_f64);
    for (c, a) in cart.zip(ang).take(5000) {
        let (c, a) = (c.unwrap(), a.unwrap());
        let theta = c.q[0].atan2(-c.q[1]);
        worst_angle = worst_angle.max((theta - a.q[0]).abs());
        let f = sys
            .constraint_forces(c.t, c.q.as_slice(), c.v.as_slice())
            .unwrap();
        let tension = -f.lambda[0];
        let expected = m * g * a.q[0].cos() + m * l * a.v[0] * a.v[0];
        worst_tension = worst_tension.max((tension - expected).abs() / (m * g));
        // The physical force on the bob is T along −r̂.
        let fb = f.on_particle(0, 2).unwrap();
        assert!((fb[0] + tension * c.q[0] / l).abs() < 1e-9 * m * g);
    }
    assert!(worst_angle < 1e-9, "angle difference {worst_angle:e}");
    assert!(worst_tension < 1e-9, "tension error {worst_tension:e}");
}

/// Projection keeps the RK4 trajectory on the circle to rounding level (the reported residual).
#[test]
fn conserves_constraint_with_projection() {
    let pendulum = || {
        let (m, g, l) = (1.0, 9.81, 1.0);
        Constrained::holonomic(Masses { n: 1, d: 2, m, g }, Rod { d: 2, l, copies: 1 }).unwrap()
    };
    let sys = pendulum();
    let mut run = Driver::with_step(
        Projected::new(Rk4::new(&sys), sys.constraints()),
        pendulum_state(1.0, 2.5, 0.0),
        1e-2,
    )
    .unwrap();
    run.run_until(20.0).unwrap();
    let (pos, vel) = run.stepper().max_residual();
    assert!(pos < 1e-14 && vel < 1e-13, "residuals {pos:e} {vel:e}");
    let rep = run.stepper().last_projection();
    assert!(rep.position_correction > 0.0 && rep.position_correction < 1e-6);
    // Without projection, RK4 drifts off the circle (the index-1 system only fixes accelerations) ...
    let loose = pendulum().violation_tolerance(1.0).unwrap();
    let mut free = Driver::with_step(Rk4::new(&loose), pendulum_state(1.0, 2.5, 0.0), 1e-2).unwrap();
    let end = free.run_until(20.0).unwrap().last().clone();
    let drift = (end.q.norm() - 1.0).abs();
    assert!(drift > 1e-10, "{drift:e}");
    // ... and with the default tolerance the run stops once the drift passes it, naming the residual.
    let mut free = Driver::with_step(Rk4::new(&sys), pendulum_state(1.0, 2.5, 0.0), 1e-2).unwrap();
    let e = noether_constraints::Error::from(free.run_until(20.0).unwrap_err());
    // (Measured: |r| − 1 = 2.8e-4 after 20 s with the loose tolerance; with the default 1e-8 the run
    // stops at t = 0.14 on a velocity residual of 1.07e-8.)
    assert!(
        matches!(e, noether_constraints::Error::ConstraintViolated { residual, .. } if residual > 1e-8),
        "{e}"
    );
}

/// The explicit projection helper moves a perturbed state back and reports the correction it made.
#[test]
fn closed_form_projection_of_a_perturbed_state() {
    let rod = HolonomicSet(Rod {
        d: 2,
        l: 2.0,
        copies: 1,
    });
    // r = 2.2 (0.6, −0.8): the nearest point on the circle of radius 2 is 2 (0.6, −0.8), a move of 0.2.
    let mut s = State::new(0.0, [1.32, -1.76], [1.0, 0.5]);
    let rep = project(&rod, &mut s, &Projection::default()).unwrap();
    assert!((rep.position_correction - 0.2 * 0.8).abs() < 1e-14); // largest component of 0.2 (0.6, 0.8)
    assert!((s.q[0] - 1.2).abs() < 1e-14 && (s.q[1] + 1.6).abs() < 1e-14);
    assert!(rep.position_residual.0 > 0.1 && rep.position_residual.1 < 1e-14);
    // Velocity: the radial part of (1, 0.5) along r̂ = (0.6, −0.8) is 0.2 r̂; removing it leaves
    // (0.88, 0.66).
    assert!((s.v[0] - 0.88).abs() < 1e-14 && (s.v[1] - 0.66).abs() < 1e-14);
    assert!(rep.velocity_residual.1 < 1e-14);
}

/// Every continuous integrator of core that steps a generic `Dynamics` (Euler, Euler-Cromer, RK4)
/// steps the constrained system; with projection the residual stays at rounding, and the error against
/// the angle formulation (RK4, h = 1e-4) shrinks with the method's order when h is halved.
#[test]
fn order_every_explicit_integrator_with_projection() {
    let (m, l, g) = (1.0, 1.0, 9.81);
    let sys = Constrained::holonomic(Masses { n: 1, d: 2, m, g }, Rod { d: 2, l, copies: 1 }).unwrap();
    let reference = {
        let el = EulerLagrange::new(AnglePendulum { m, l, g });
        let mut tr = Driver::with_step(Rk4::new(el), State::new(0.0, [1.0], [0.0]), 1e-4).unwrap();
        tr.run_until(1.0).unwrap().last().q[0]
    };
    fn error<S: Stepper<Partner = Velocities>>(
        stepper: S,
        h: f64,
        reference: f64,
        sys_set: impl ConstraintSet,
    ) -> (f64, f64) {
        let mut tr =
            Driver::with_step(Projected::new(stepper, sys_set), pendulum_state(1.0, 1.0, 0.0), h).unwrap();
        let end = tr.run_until(1.0).unwrap().last().clone();
        (
            (end.q[0].atan2(-end.q[1]) - reference).abs(),
            tr.stepper().max_residual().0,
        )
    }
    let cases: [(&str, f64, f64); 3] = [
        ("Euler", 1.0, 0.02),
        ("Euler-Cromer", 1.0, 0.02),
        ("RK4", 4.0, 0.01),
    ];
    for (name, order, h) in cases {
        let run = |h: f64| match name {
            "Euler" => error(Euler::new(&sys), h, reference, sys.constraints()),
            "Euler-Cromer" => error(EulerCromer::new(&sys), h, reference, sys.constraints()),
            _ => error(Rk4::new(&sys), h, reference, sys.constraints()),
        };
        let ((e1, r1), (e2, r2)) = (run(h), run(h / 2.0));
        let observed = (e1 / e2).log2();
        assert!(r1 < 1e-14 && r2 < 1e-14, "{name}: residuals {r1:e} {r2:e}");
        assert!(
            (observed - order).abs() < 0.3,
            "{name}: errors {e1:e} {e2:e}, order {observed}"
        );
    }
}

/// The adaptive embedded pairs of core (Dormand-Prince 5(4) and 8(5,3)) step the constrained system as
/// well: with projection after every accepted step and tolerances 1e-10, the Cartesian pendulum agrees
/// with the angle formulation (RK4, h = 1e-4) to 1e-7 after 3 s and the rod holds to rounding.
#[test]
fn closed_form_adaptive_integrators_with_projection() {
    let (m, l, g) = (1.0, 1.0, 9.81);
    let sys = Constrained::holonomic(Masses { n: 1, d: 2, m, g }, Rod { d: 2, l, copies: 1 }).unwrap();
    let reference = {
        let el = EulerLagrange::new(AnglePendulum { m, l, g });
        let mut tr = Driver::with_step(Rk4::new(el), State::new(0.0, [1.0], [0.0]), 1e-4).unwrap();
        tr.run_until(3.0).unwrap().last().q[0]
    };
    fn check<S: Stepper<Partner = Velocities>>(stepper: S, sys_set: impl ConstraintSet, reference: f64) {
        let mut tr = Driver::with_step(
            Projected::new(stepper, sys_set),
            pendulum_state(1.0, 1.0, 0.0),
            1e-2,
        )
        .unwrap();
        let end = tr.run_until(3.0).unwrap().last().clone();
        let err = (end.q[0].atan2(-end.q[1]) - reference).abs();
        assert!(err < 1e-7, "{}: error {err:e}", tr.stepper().name());
        assert!(tr.stepper().max_residual().0 < 1e-14);
    }
    check(
        Dopri5::new(&sys).tolerances(1e-10, 1e-10).unwrap(),
        sys.constraints(),
        reference,
    );
    check(
        Dop853::new(&sys).tolerances(1e-10, 1e-10).unwrap(),
        sys.constraints(),
        reference,
    );
}
