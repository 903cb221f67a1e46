//! Springs and dampers between points against the same forces written by hand.

use noether_core::prelude::*;
use noether_multibody::{
    ArticulatedBody, Body, BodyId, ForwardDynamics, Joint, Mechanism, NewtonEuler, Parent, Placement,
};
use noether_testkit::agreement::{relative, uniform};

/// A slider along x tied to the ground point (−1, 0, 0) by a spring of rest length 1 and a damper is
/// the slider with the same spring and damper on its joint (d = 1 + q, so ½ k (d − 1)² = ½ k q² and
/// c ḋ = c q̇): at 20 random states L and q̈ agree (measured ≤ 1.7e-16 and 1.6e-15 relative;
/// tolerance 1e-14: d goes through a square root).
#[test]
fn point_spring_on_a_slider_is_the_joint_spring() {
    let (k, c) = (5.0, 0.7);
    let body = || {
        Body::new(
            2.0,
            [0.1, 0.0, 0.0],
            [[0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.1]],
        )
    };
    let mut by_points = Mechanism::new();
    let slider = by_points
        .attach(
            Parent::Ground,
            Placement::identity(),
            Joint::prismatic([1.0, 0.0, 0.0]),
            body(),
        )
        .unwrap();
    let (anchor, pin) = (
        (Parent::Ground, [-1.0, 0.0, 0.0]),
        (Parent::from(slider), [0.0; 3]),
    );
    by_points.spring(anchor, pin, k, 1.0).unwrap();
    by_points.damper(anchor, pin, c).unwrap();
    let mut on_joint = Mechanism::new();
    on_joint
        .attach(
            Parent::Ground,
            Placement::identity(),
            Joint::prismatic([1.0, 0.0, 0.0]).spring(k, 0.0).damper(c),
            body(),
        )
        .unwrap();
    let (a, b) = (EulerLagrange::new(&by_points), EulerLagrange::new(&on_joint));
    let mut draw = uniform(41);
    let mut worst = [0.0_f64; 2];
    for _ in 0..20 {
        let (q, v) = ([draw(-0.5, 0.5)], [draw(-2.0, 2.0)]);
        let (mut qa, mut qb) = ([0.0], [0.0]);
        a.accelerations(0.0, &q, &v, &mut qa).unwrap();
        b.accelerations(0.0, &q, &v, &mut qb).unwrap();
        worst[0] = worst[0].max(relative(
            &[by_points.lagrangian(0.0, &q, &v)],
            &[on_joint.lagrangian(0.0, &q, &v)],
        ));
        worst[1] = worst[1].max(relative(&qa, &qb));
    }
    println!(
        "point spring and damper on a slider: L {:e}, q̈ {:e}",
        worst[0], worst[1]
    );
    assert!(worst.iter().all(|e| *e < 1e-14), "{worst:?}");
}

/// An elastic pendulum in the plane: a disk (m, moment I) on a planar joint (x, y, φ), hung from the
/// origin by a spring of stiffness k and rest length d₀ and a damper c, both tied to the point a
/// e_x of the disk (so they also turn it), gravity along −y. By hand, with r_b = (x + a cos φ,
/// y + a sin φ) and d = |r_b|,
///
/// ```text
/// L = ½ m (ẋ² + ẏ²) + ½ I φ̇² − ½ k (d − d₀)² − m g y,   Q_i = −c ḋ ∂d/∂q_i,  ḋ = r_b·ṙ_b/d.
/// ```
///
/// At 30 random states q̈ agree (measured ≤ 4.0e-16 relative; tolerance 1e-13: the damper's forces
/// are summed over one pass of the kinematics per coordinate).
#[test]
fn elastic_pendulum_from_a_point_spring_and_damper() {
    let (m, inertia, k, rest, c, arm, g) = (1.5, 0.05, 40.0, 0.8, 0.9, 0.2, 9.81);
    let mut built = Mechanism::new().gravity([0.0, -g, 0.0]).unwrap();
    let disk = built
        .attach(
            Parent::Ground,
            Placement::identity(),
            Joint::planar([0.0, 0.0, 1.0]),
            Body::new(
                m,
                [0.0; 3],
                [[inertia, 0.0, 0.0], [0.0, inertia, 0.0], [0.0, 0.0, inertia]],
            ),
        )
        .unwrap();
    let ends = ((Parent::Ground, [0.0; 3]), (Parent::from(disk), [arm, 0.0, 0.0]));
    built.spring(ends.0, ends.1, k, rest).unwrap();
    built.damper(ends.0, ends.1, c).unwrap();
    let el = EulerLagrange::new(&built);
    let mut draw = uniform(43);
    let mut worst = 0.0_f64;
    for _ in 0..30 {
        let q = [draw(-1.0, 1.0), draw(-1.5, -0.5), draw(-3.0, 3.0)];
        let v = [draw(-2.0, 2.0), draw(-2.0, 2.0), draw(-3.0, 3.0)];
        let (s, co) = q[2].sin_cos();
        let r = [q[0] + arm * co, q[1] + arm * s];
        let dr = [[1.0, 0.0, -arm * s], [0.0, 1.0, arm * co]];
        let rate = [v[0] - arm * s * v[2], v[1] + arm * co * v[2]];
        let d = (r[0] * r[0] + r[1] * r[1]).sqrt();
        let d_dot = (r[0] * rate[0] + r[1] * rate[1]) / d;
        // M q̈ = −∂V/∂q + Q with M = diag(m, m, I): ∂V/∂q_i = k (d − d₀) ∂d/∂q_i, plus gravity on y.
        let by_hand: Vec<f64> = (0..3)
            .map(|i| {
                let dd = (r[0] * dr[0][i] + r[1] * dr[1][i]) / d;
                let force = -k * (d - rest) * dd - c * d_dot * dd - if i == 1 { m * g } else { 0.0 };
                force / if i == 2 { inertia } else { m }
            })
            .collect();
        let mut a = [0.0; 3];
        el.accelerations(0.0, &q, &v, &mut a).unwrap();
        worst = worst.max(relative(&a, &by_hand));
    }
    println!("elastic pendulum from a point spring and damper: q̈ {worst:e}");
    assert!(worst < 1e-13, "{worst:e}");
    // The fast paths do not take point forces: forward dynamics falls back on Lagrange's equations.
    assert!(NewtonEuler::new(built.clone()).is_err());
    assert!(ArticulatedBody::new(built.clone()).is_err());
    assert!(matches!(
        built.forward_dynamics().unwrap(),
        ForwardDynamics::Lagrange(_)
    ));
}

/// Bad springs and dampers are typed errors and attach nothing.
#[test]
fn bad_connections_are_typed_errors() {
    let mut m = Mechanism::new();
    let ground = (Parent::Ground, [0.0; 3]);
    assert!(m
        .spring(ground, (Parent::Body(BodyId(0)), [0.0; 3]), 1.0, 0.0)
        .is_err());
    let b = m
        .attach(
            Parent::Ground,
            Placement::identity(),
            Joint::prismatic([1.0, 0.0, 0.0]),
            Body::point(1.0, [0.0; 3]),
        )
        .unwrap();
    let pin = (Parent::from(b), [0.0; 3]);
    assert!(m.spring(ground, pin, -1.0, 0.0).is_err());
    assert!(m.spring(ground, pin, 1.0, f64::NAN).is_err());
    assert!(m.damper(ground, pin, f64::INFINITY).is_err());
    assert!(m
        .damper((Parent::Ground, [f64::NAN, 0.0, 0.0]), pin, 1.0)
        .is_err());
    // None of them was added: the slider is free.
    let mut a = [0.0];
    EulerLagrange::new(&m)
        .accelerations(0.0, &[0.3], &[0.0], &mut a)
        .unwrap();
    assert_eq!(a, [0.0]);
}
