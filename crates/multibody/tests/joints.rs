//! Mechanisms built from bodies and joints against hand-written Lagrangians and closed forms.

use noether_core::control::Actuated;
use noether_core::prelude::*;
use noether_multibody::{Body, Error, Joint, Mechanism, Parent, Placement};
use noether_testkit::agreement::{relative, uniform};
use noether_testkit::control::CartPole;
use noether_testkit::multibody::{joints_double_pendulum, PlanarArm, Z};
use noether_testkit::systems::DoublePendulum;
use std::f64::consts::PI;

/// The built double pendulum is the hand-written one: with absolute angles θ = J q, J = [[1, 0],
/// [1, 1]] (constant), L_built(q, q̇) = L_hand(J q, J q̇), so M_built = Jᵀ M_hand J and
/// q̈_hand = J q̈_built. At 50 random states (angles in [−π, π], rates in [−3, 3]): L, M and q̈ agree
/// to rounding (measured ≤ 6.6e-16, 4.4e-16, 2.9e-15 relative; tolerance 1e-13, the target: the
/// built L goes through rotation matrices and cross products, the hand one through one cosine).
#[test]
fn double_pendulum_from_joints_is_the_hand_written_one() {
    let dp = DoublePendulum::default();
    let built = EulerLagrange::new(joints_double_pendulum(&dp));
    let hand = EulerLagrange::new(dp);
    let mut draw = uniform(7);
    let mut worst = [0.0_f64; 3];
    for _ in 0..50 {
        let q = [draw(-PI, PI), draw(-PI, PI)];
        let v = [draw(-3.0, 3.0), draw(-3.0, 3.0)];
        let (qa, va) = ([q[0], q[0] + q[1]], [v[0], v[0] + v[1]]);
        let l = built.lagrangian().lagrangian(0.0, &q, &v);
        let lh = dp.lagrangian(0.0, &qa, &va);
        let m = built.mass_matrix(0.0, &q, &v).unwrap();
        let mh = hand.mass_matrix(0.0, &qa, &va).unwrap();
        let j = nalgebra::DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 1.0, 1.0]);
        let mh = j.transpose() * mh * &j;
        let mut a = [0.0; 2];
        built.accelerations(0.0, &q, &v, &mut a).unwrap();
        let ah = dp.hand_accelerations(&qa, &va);
        let errors = [
            relative(&[l], &[lh]),
            relative(m.as_slice(), mh.as_slice()),
            relative(&[a[0], a[0] + a[1]], &ah),
        ];
        for (w, e) in worst.iter_mut().zip(errors) {
            *w = w.max(e);
        }
    }
    println!(
        "double pendulum from joints: L {:e}, M {:e}, q̈ {:e}",
        worst[0], worst[1], worst[2]
    );
    assert!(worst.iter().all(|e| *e < 1e-13), "{worst:?}");
}

/// A planar arm of three uniform rods (`PlanarArm`) on revolute joints about z, in relative angles:
/// its mass matrix against the textbook closed form (`PlanarArm::mass_matrix`, Spong, Hutchinson and
/// Vidyasagar §7.4 extended to a third link) and its tip against Σ l_i (cos φ_i, sin φ_i). At 50
/// random configurations: measured ≤ 4.3e-16 and 6.2e-16 relative; tolerance 1e-13 (the target).
#[test]
fn planar_arm_mass_matrix_and_tip_closed_form() {
    let arm = PlanarArm::default();
    let mechanism = arm.mechanism();
    let el = EulerLagrange::new(mechanism.clone());
    let tip_link = noether_multibody::BodyId(2);
    let mut draw = uniform(11);
    let (mut worst, mut tip_worst) = (0.0_f64, 0.0_f64);
    for _ in 0..50 {
        let q = [draw(-PI, PI), draw(-PI, PI), draw(-PI, PI)];
        let exact: Vec<f64> = arm.mass_matrix(&q).iter().flatten().copied().collect();
        let built = el.mass_matrix(0.0, &q, &[0.0; 3]).unwrap();
        worst = worst.max(relative(built.as_slice(), &exact));
        // The tip is the third link's frame origin moved l₃ along its x axis.
        let (r, p) = mechanism.pose(tip_link, &q).unwrap();
        let tip = p + r.column(0) * arm.lengths[2];
        tip_worst = tip_worst.max(relative(
            &[tip[0], tip[1], tip[2]],
            &[arm.tip(&q)[0], arm.tip(&q)[1], 0.0],
        ));
    }
    println!("planar arm: mass matrix {worst:e}, tip {tip_worst:e}");
    assert!(worst < 1e-13 && tip_worst < 1e-13, "{worst:e} {tip_worst:e}");
}

/// The cart-pole from a prismatic joint (the cart, a point mass M) and a revolute one about −z (the
/// pole, a point bob m at l, θ from the upward vertical): the hand-written `CartPole` (its L and its
/// input force on the cart) at 50 random states, to rounding (measured ≤ 2.8e-15; tolerance 1e-13).
#[test]
fn cart_pole_from_a_prismatic_and_a_revolute_joint() {
    let cp = CartPole::default();
    let mut m = Mechanism::new().gravity([0.0, -cp.g, 0.0]).unwrap();
    let cart = m
        .attach(
            Parent::Ground,
            Placement::identity(),
            Joint::prismatic([1.0, 0.0, 0.0]),
            Body::point(cp.cart, [0.0; 3]),
        )
        .unwrap();
    m.attach(
        cart,
        Placement::identity(),
        Joint::revolute([0.0, 0.0, -1.0]),
        Body::point(cp.bob, [0.0, cp.l, 0.0]),
    )
    .unwrap();
    m.actuate(cart).unwrap();
    assert_eq!(m.inputs(), 1);
    let mut draw = uniform(3);
    let mut worst = 0.0_f64;
    for _ in 0..50 {
        let (q, v, u) = (
            [draw(-2.0, 2.0), draw(-PI, PI)],
            [draw(-3.0, 3.0), draw(-3.0, 3.0)],
            [draw(-5.0, 5.0)],
        );
        let (mut f, mut fh) = ([0.0; 2], [0.0; 2]);
        m.input_force(0.0, &q, &v, &u, &mut f);
        cp.input_force(0.0, &q, &v, &u, &mut fh);
        assert_eq!(f, fh);
        worst = worst.max(relative(
            &[m.lagrangian(0.0, &q, &v)],
            &[cp.lagrangian(0.0, &q, &v)],
        ));
    }
    println!("cart-pole from joints: L {worst:e}");
    assert!(worst < 1e-13, "{worst:e}");
}

/// A compound pendulum: a body of arbitrary shape (full inertia tensor I_c about its centre c) on a
/// hinge whose frame is placed at a point and turned, so that the axis is a in the body frame. Its
/// moment about the axis is the parallel-axis theorem's J = aᵀ I_c a + m (|c|² − (a·c)²) (the axis
/// through the body origin), and that is the 1 × 1 mass matrix (measured ≤ 6.0e-16; tolerance 1e-14).
#[test]
fn compound_pendulum_obeys_the_parallel_axis_theorem() {
    let (mass, c) = (2.5, [0.3, -0.7, 0.2]);
    let inertia = [[0.4, 0.05, -0.02], [0.05, 0.3, 0.01], [-0.02, 0.01, 0.5]];
    let axis = [1.0, 2.0, 2.0];
    let mut m = Mechanism::new();
    let placement = Placement::at([0.1, 0.2, 0.3]).rotated([0.0, 1.0, 0.0], 0.7);
    m.attach(
        Parent::Ground,
        placement,
        Joint::revolute(axis),
        Body::new(mass, c, inertia),
    )
    .unwrap();
    let a = axis.map(|x| x / 3.0);
    let ac = a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
    let aia: f64 = (0..3)
        .flat_map(|i| (0..3).map(move |k| (i, k)))
        .map(|(i, k)| a[i] * inertia[i][k] * a[k])
        .sum();
    let exact = aia + mass * (c.iter().map(|x| x * x).sum::<f64>() - ac * ac);
    let el = EulerLagrange::new(m);
    let worst = [0.0, 1.3, -2.9]
        .iter()
        .map(|&q| relative(el.mass_matrix(0.0, &[q], &[0.4]).unwrap().as_slice(), &[exact]))
        .fold(0.0_f64, f64::max);
    println!("compound pendulum: {worst:e}");
    assert!(worst < 1e-14, "{worst:e}");
}

/// A slider on a spring and a damper: m q̈ = −k (q − q₀) − c q̇ exactly (measured 0 or 1 ulp;
/// tolerance 1e-15 relative).
#[test]
fn spring_and_damper_on_a_joint() {
    let (mass, k, rest, c) = (2.0, 3.0, 0.5, 0.4);
    let mut m = Mechanism::new();
    let joint = Joint::prismatic([0.0, 3.0, 4.0]).spring(k, rest).damper(c);
    m.attach(
        Parent::Ground,
        Placement::identity(),
        joint,
        Body::point(mass, [0.0; 3]),
    )
    .unwrap();
    let el = EulerLagrange::new(m);
    let (q, v) = (1.7, -0.9);
    let mut a = [0.0];
    el.accelerations(0.0, &[q], &[v], &mut a).unwrap();
    let exact = (-k * (q - rest) - c * v) / mass;
    assert!(relative(&a, &[exact]) < 1e-15, "{} {exact}", a[0]);
}

/// Descriptions no mechanism has are typed errors, naming the body.
#[test]
fn bad_mechanisms_are_typed_errors() {
    let mut m = Mechanism::new();
    let hinge = || Joint::revolute(Z);
    let at = Placement::identity();
    let unknown = m.attach(
        Parent::Body(noether_multibody::BodyId(0)),
        at,
        hinge(),
        Body::point(1.0, [1.0, 0.0, 0.0]),
    );
    assert!(
        matches!(
            unknown,
            Err(Error::UnknownParent {
                body: 0,
                parent: 0,
                bodies: 0
            })
        ),
        "{unknown:?}"
    );
    let skew = Body::new(1.0, [0.0; 3], [[1.0, 0.2, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    assert!(matches!(
        m.attach(Parent::Ground, at, hinge(), skew),
        Err(Error::Inertia { body: 0, .. })
    ));
    // 3 > 1 + 1: no mass distribution has these moments.
    let impossible = Body::new(1.0, [0.0; 3], [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 3.0]]);
    assert!(matches!(
        m.attach(Parent::Ground, at, hinge(), impossible),
        Err(Error::Inertia { .. })
    ));
    let negative = Body::new(
        1.0,
        [0.0; 3],
        [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    );
    assert!(matches!(
        m.attach(Parent::Ground, at, hinge(), negative),
        Err(Error::Inertia { .. })
    ));
    assert!(matches!(
        m.attach(Parent::Ground, at, hinge(), Body::point(-1.0, [0.0; 3])),
        Err(Error::Mass { mass: -1.0, .. })
    ));
    assert!(matches!(
        m.attach(
            Parent::Ground,
            at,
            Joint::revolute([0.0; 3]),
            Body::point(1.0, [0.0; 3])
        ),
        Err(Error::Axis { .. })
    ));
    assert!(m
        .attach(
            Parent::Ground,
            at,
            Joint::fixed().spring(1.0, 0.0),
            Body::point(1.0, [0.0; 3])
        )
        .is_err());
    assert!(m
        .attach(
            Parent::Ground,
            at,
            hinge().damper(f64::NAN),
            Body::point(1.0, [0.0; 3])
        )
        .is_err());
    // Nothing was attached by the failed calls; a good body still is.
    assert_eq!(m.bodies(), 0);
    assert!(matches!(
        m.actuate(noether_multibody::BodyId(3)),
        Err(Error::UnknownBody { body: 3, bodies: 0 })
    ));
    let rod = m
        .attach(
            Parent::Ground,
            at,
            hinge(),
            Body::rod(1.0, [0.0; 3], [1.0, 0.0, 0.0]),
        )
        .unwrap();
    assert_eq!(m.coordinates(rod).unwrap(), 0..1);
    m.actuate(rod).unwrap();
    assert!(m.actuate(rod).is_err(), "actuated twice");
}

/// A joint of several coordinates is the chain of one-coordinate joints it abbreviates, through
/// massless links: a cylindrical joint about a (angle θ, slide s) is a revolute joint about a then a
/// prismatic one along a (turning about an axis and sliding along it commute); a planar joint with
/// normal z (x, y, θ) is prismatic along x, prismatic along y, revolute about z. The same body (full
/// inertia tensor, off-centre) hangs from each, on a turned placement, under gravity: L agrees at 30
/// random states (measured ≤ 6e-16 relative; tolerance 1e-14). Springs need a joint of one coordinate.
#[test]
fn cylindrical_and_planar_joints_are_their_chains() {
    let body = Body::new(
        1.3,
        [0.2, -0.1, 0.3],
        [[0.3, 0.02, 0.0], [0.02, 0.25, -0.01], [0.0, -0.01, 0.4]],
    );
    let at = Placement::at([0.1, 0.2, -0.3]).rotated([1.0, 0.0, 0.0], 0.5);
    let axis = [0.0, 0.6, 0.8];
    let chain = |joints: &[Joint]| {
        let mut m = Mechanism::new().gravity([0.0, 0.0, -9.81]).unwrap();
        let mut parent = Parent::Ground;
        for (k, joint) in joints.iter().enumerate() {
            let (place, carried) = if k == 0 {
                (at, Body::massless())
            } else {
                (Placement::identity(), Body::massless())
            };
            let carried = if k + 1 == joints.len() { body } else { carried };
            parent = m.attach(parent, place, *joint, carried).unwrap().into();
        }
        m
    };
    let pairs = [
        (
            chain(&[Joint::cylindrical(axis)]),
            chain(&[Joint::revolute(axis), Joint::prismatic(axis)]),
            "cylindrical",
        ),
        (
            chain(&[Joint::planar(Z)]),
            chain(&[
                Joint::prismatic([1.0, 0.0, 0.0]),
                Joint::prismatic([0.0, 1.0, 0.0]),
                Joint::revolute(Z),
            ]),
            "planar",
        ),
    ];
    let mut draw = uniform(17);
    for (joint, links, name) in pairs {
        let n = joint.dof();
        assert_eq!(n, links.dof());
        let mut worst = 0.0_f64;
        for _ in 0..30 {
            let q: Vec<f64> = (0..n).map(|_| draw(-PI, PI)).collect();
            let v: Vec<f64> = (0..n).map(|_| draw(-2.0, 2.0)).collect();
            let (a, b) = (joint.lagrangian(0.0, &q, &v), links.lagrangian(0.0, &q, &v));
            worst = worst.max(relative(&[a], &[b]));
        }
        println!("{name} joint vs its chain: L {worst:e}");
        assert!(worst < 1e-14, "{name}: {worst:e}");
    }
    let mut m = Mechanism::new();
    assert!(m
        .attach(
            Parent::Ground,
            at,
            Joint::cylindrical(axis).spring(1.0, 0.0),
            body
        )
        .is_err());
}
