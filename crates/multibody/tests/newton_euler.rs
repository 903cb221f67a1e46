//! The recursive Newton-Euler algorithm and the articulated-body algorithm against Lagrange's
//! equations of the same mechanism.

use noether_core::prelude::*;
use noether_multibody::{ArticulatedBody, Body, Joint, Mechanism, NewtonEuler, Parent, Placement};
use noether_testkit::agreement::{relative, uniform};
use noether_testkit::multibody::{PlanarArm, SliderCrank};
use std::f64::consts::PI;

/// A branching tree in space: five bodies with full inertia tensors on revolute and prismatic
/// joints about skew axes, placements turned and moved, springs and a damper, gravity along −z.
fn branching_tree() -> Mechanism {
    let mut draw = uniform(99);
    let mut m = Mechanism::new().gravity([0.0, 0.0, -9.81]).unwrap();
    // A rigid body's inertia: principal moments (1, 1.2, 1.5) turned by a rotation.
    let mut body = |mass: f64| {
        let turn = Placement::identity().rotated([0.0, 0.6, 0.8], draw(0.0, PI));
        let r = turn_matrix(&turn);
        let d = [0.1, 0.12, 0.15];
        let inertia =
            std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| r[i][k] * d[k] * r[j][k]).sum()));
        Body::new(mass, [draw(-0.3, 0.3), draw(-0.3, 0.3), draw(-0.3, 0.3)], inertia)
    };
    let a = m
        .attach(
            Parent::Ground,
            Placement::identity(),
            Joint::revolute([0.0, 0.0, 1.0]).damper(0.3),
            body(1.0),
        )
        .unwrap();
    let b = m
        .attach(
            a,
            Placement::at([0.5, 0.0, 0.1]).rotated([1.0, 0.0, 0.0], 0.4),
            Joint::revolute([0.3, 1.0, 0.2]),
            body(0.8),
        )
        .unwrap();
    m.attach(
        b,
        Placement::at([0.0, 0.4, 0.0]),
        Joint::prismatic([1.0, 1.0, 0.0]).spring(5.0, 0.1),
        body(0.5),
    )
    .unwrap();
    let c = m
        .attach(
            a,
            Placement::at([-0.3, 0.2, 0.0]),
            Joint::revolute([0.0, 1.0, 0.0]).spring(2.0, -0.2),
            body(0.6),
        )
        .unwrap();
    m.attach(
        c,
        Placement::at([0.0, 0.0, -0.4]).rotated([0.0, 0.0, 1.0], 1.1),
        Joint::revolute([1.0, 0.0, 0.0]),
        body(0.4),
    )
    .unwrap();
    m.attach(c, Placement::at([0.2, 0.0, 0.0]), Joint::fixed(), body(0.3))
        .unwrap();
    m
}

/// The rotation of a placement, read back through its effect on the axes.
fn turn_matrix(p: &Placement) -> [[f64; 3]; 3] {
    let mut m = Mechanism::new();
    m.attach(Parent::Ground, *p, Joint::fixed(), Body::massless())
        .unwrap();
    let (r, _) = m.pose(noether_multibody::BodyId(0), &[]).unwrap();
    std::array::from_fn(|i| std::array::from_fn(|j| r[(i, j)]))
}

/// q̈ by Newton-Euler and by the articulated-body algorithm equal q̈ by Lagrange's equations of the
/// same mechanism's L (third-order jets), at 30 random states of two mechanisms: the planar arm and a
/// branching tree in space (full inertia tensors, skew axes, a prismatic joint, springs, a damper, a
/// fixed body). Three algorithms, one motion: measured ≤ 1.0e-14 (Newton-Euler) and 6.5e-15 (ABA)
/// relative; tolerance 1e-12 (they sum different products; two factor M after different rounding,
/// the third never forms it). A mechanism with a loop closure, or a joint of several coordinates, is
/// refused.
#[test]
fn newton_euler_and_articulated_body_are_lagrange() {
    let mechanisms = [
        ("planar arm", PlanarArm::default().mechanism()),
        ("branching tree", branching_tree()),
    ];
    let mut draw = uniform(5);
    for (name, mechanism) in mechanisms {
        let n = mechanism.dof();
        let ne = NewtonEuler::new(mechanism.clone()).unwrap();
        let aba = ArticulatedBody::new(mechanism.clone()).unwrap();
        let el = EulerLagrange::new(mechanism);
        let (mut worst, mut worst_aba) = (0.0_f64, 0.0_f64);
        for _ in 0..30 {
            let q: Vec<f64> = (0..n).map(|_| draw(-PI, PI)).collect();
            let v: Vec<f64> = (0..n).map(|_| draw(-2.0, 2.0)).collect();
            let (mut dq, mut a, mut b) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            ne.rates(0.0, &q, &v, &mut dq, &mut a).unwrap();
            el.accelerations(0.0, &q, &v, &mut b).unwrap();
            assert_eq!(dq, v);
            worst = worst.max(relative(&a, &b));
            aba.rates(0.0, &q, &v, &mut dq, &mut a).unwrap();
            assert_eq!(dq, v);
            worst_aba = worst_aba.max(relative(&a, &b));
        }
        println!("vs Lagrange, {name}: Newton-Euler {worst:e}, articulated body {worst_aba:e}");
        assert!(
            worst < 1e-12 && worst_aba < 1e-12,
            "{name}: {worst:e} {worst_aba:e}"
        );
    }
    // A closed loop is not a tree; a ball joint has three coordinates.
    assert!(NewtonEuler::new(SliderCrank::default().mechanism()).is_err());
    assert!(ArticulatedBody::new(SliderCrank::default().mechanism()).is_err());
    let ball = noether_testkit::multibody::BallPendulum::default().mechanism();
    assert!(ArticulatedBody::new(ball).is_err());
}

/// `forward_dynamics` takes the articulated-body algorithm for a tree of one-coordinate joints and
/// Lagrange's equations for a ball joint, with the motion of Lagrange's equations either way (the
/// same numbers to rounding, tolerance 1e-12 as above); a loop without its constraints is refused.
#[test]
fn forward_dynamics_is_chosen_by_the_shape() {
    use noether_multibody::ForwardDynamics;
    let ball = noether_testkit::multibody::BallPendulum::default().mechanism();
    for (mechanism, articulated) in [(branching_tree(), true), (ball, false)] {
        let el = EulerLagrange::new(mechanism.clone());
        let forward = mechanism.forward_dynamics().unwrap();
        assert_eq!(matches!(forward, ForwardDynamics::Articulated(_)), articulated);
        let n = forward.dof();
        let q: Vec<f64> = (0..n).map(|i| 0.3 - 0.1 * i as f64).collect();
        let v: Vec<f64> = (0..n).map(|i| 0.2 * i as f64 - 0.4).collect();
        let (mut dq, mut a, mut b) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        forward.rates(0.0, &q, &v, &mut dq, &mut a).unwrap();
        el.accelerations(0.0, &q, &v, &mut b).unwrap();
        assert!(relative(&a, &b) < 1e-12, "{a:?} {b:?}");
        let e = forward.energy(0.0, &q, &v).unwrap();
        assert_eq!(e, el.energy(0.0, &q, &v).unwrap());
    }
    assert!(SliderCrank::default().mechanism().forward_dynamics().is_err());
}
