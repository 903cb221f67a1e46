//! Spherical (ball) and free joints in exponential coordinates against rigid-body mechanics written
//! by hand, their chart renewal, and their errors.

use nalgebra::{Matrix3, Rotation3, Vector3};
use noether_core::prelude::*;
use noether_multibody::{
    renewed_rotation_vector, rotation_vector_rate, Body, BodyId, Joint, Mechanism, NewtonEuler, Parent,
    Placement,
};
use noether_testkit::agreement::{relative, uniform};
use std::f64::consts::PI;

/// The left Jacobian of SO(3) in exponential coordinates, ω = J(θ) θ̇ for R = exp(\[θ\]×):
/// J = I + b K + c K², K = \[θ\]×, b = (1 − cos x)/x² = 2 sin²(x/2)/x², c = (x − sin x)/x³, x = |θ|
/// (Barfoot, *State Estimation for Robotics*, §7.1.3), written here with nalgebra: b in its
/// half-angle form has no cancellation, and c's (error ε/x²) enters multiplied by K² ~ x².
fn left_jacobian(theta: Vector3<f64>) -> Matrix3<f64> {
    let x = theta.norm();
    let k = theta.cross_matrix();
    let b = 2.0 * (0.5 * x).sin().powi(2) / (x * x);
    let c = (x - x.sin()) / (x * x * x);
    Matrix3::identity() + k * b + k * k * c
}

/// A body of mass m, centre c and inertia I_c (full tensor) on a ball joint placed at (R₀, t₀) in the
/// world, under gravity g: with R = R₀ exp(\[θ\]×) and ω = R₀ J(θ) θ̇, by hand
/// L = ½ ωᵀ I_O ω + m g·(t₀ + R c), I_O = R (I_c + m (|c|² I − c cᵀ)) Rᵀ (the parallel-axis theorem),
/// and M = Jᵀ R₀ᵀ I_O R₀ J. At 9 lengths |θ| from 10⁻⁶ (the series branch) through 1 (where the
/// branches meet) to 5.5 (near the chart's edge 2π), 6 random directions and rates each: L and M
/// agree to rounding (measured ≤ 8.3e-15 and 1.1e-15 relative, L's the larger as gravity's and the
/// kinetic part partly cancel; tolerance 1e-13).
#[test]
fn ball_joint_is_the_rigid_body_about_its_pivot() {
    let (mass, centre) = (2.0, [0.1, -0.2, -0.8]);
    let inertia = [[0.3, 0.02, 0.01], [0.02, 0.25, -0.03], [0.01, -0.03, 0.2]];
    let gravity = [0.0, -1.0, -9.81];
    let at = Placement::at([0.5, 0.0, 1.0]).rotated([0.0, 0.6, 0.8], 0.7);
    let mut m = Mechanism::new().gravity(gravity).unwrap();
    m.attach(
        Parent::Ground,
        at,
        Joint::spherical(),
        Body::new(mass, centre, inertia),
    )
    .unwrap();
    let el = EulerLagrange::new(&m);
    let r0 = Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(Vector3::new(0.0, 0.6, 0.8)), 0.7)
        .into_inner();
    let c = Vector3::from(centre);
    let ic = Matrix3::from_fn(|i, j| inertia[i][j]);
    let i_pivot = ic + (Matrix3::identity() * c.norm_squared() - c * c.transpose()) * mass;
    let mut draw = uniform(11);
    let mut worst = [0.0_f64; 2];
    for x in [1e-6, 1e-3, 0.3, 0.999_999, 1.000_001, 2.0, PI, 4.0, 5.5] {
        for _ in 0..6 {
            let d = Vector3::new(draw(-1.0, 1.0), draw(-1.0, 1.0), draw(-1.0, 1.0)).normalize();
            let theta = d * x;
            let rate = Vector3::new(draw(-3.0, 3.0), draw(-3.0, 3.0), draw(-3.0, 3.0));
            let r = r0 * Rotation3::new(theta).into_inner();
            let j = left_jacobian(theta);
            let omega = r0 * j * rate;
            let i_o = r * i_pivot * r.transpose();
            let g = Vector3::from(gravity);
            let hand = 0.5 * omega.dot(&(i_o * omega)) + mass * g.dot(&(Vector3::new(0.5, 0.0, 1.0) + r * c));
            let mass_hand = j.transpose() * r0.transpose() * i_o * r0 * j;
            let (q, v) = (theta.as_slice(), rate.as_slice());
            let built = el.lagrangian().lagrangian(0.0, q, v);
            let mass_built = el.mass_matrix(0.0, q, v).unwrap();
            worst[0] = worst[0].max(relative(&[built], &[hand]));
            worst[1] = worst[1].max(relative(mass_built.as_slice(), mass_hand.as_slice()));
        }
    }
    println!("ball joint: L {:e}, M {:e}", worst[0], worst[1]);
    assert!(worst.iter().all(|e| *e < 1e-13), "{worst:?}");
}

/// At θ = 0 (the series branch at its centre, where every closed form is 0/0) the second derivatives
/// of L are exact too: there J = I and dJ/dt θ̇ = b θ̇ × θ̇ = 0, so θ̈ = ω̇ and Lagrange's equations
/// must be Euler's, I_O ω̇ = m c × g − ω × I_O ω (about the pivot, world = body axes there). At 20
/// random rates: measured ≤ 6.5e-15 relative (the two solves of M with different factorisations);
/// tolerance 1e-13.
#[test]
fn ball_joint_at_rest_orientation_obeys_eulers_equations() {
    let (mass, centre) = (1.5, [0.2, 0.1, -0.7]);
    let inertia = [[0.4, -0.05, 0.0], [-0.05, 0.3, 0.02], [0.0, 0.02, 0.2]];
    let g = [0.3, 0.0, -9.81];
    let mut m = Mechanism::new().gravity(g).unwrap();
    m.attach(
        Parent::Ground,
        Placement::identity(),
        Joint::spherical(),
        Body::new(mass, centre, inertia),
    )
    .unwrap();
    let el = EulerLagrange::new(&m);
    let c = Vector3::from(centre);
    let i_o = Matrix3::from_fn(|i, j| inertia[i][j])
        + (Matrix3::identity() * c.norm_squared() - c * c.transpose()) * mass;
    let mut draw = uniform(5);
    let mut worst = 0.0_f64;
    for _ in 0..20 {
        let w = Vector3::new(draw(-4.0, 4.0), draw(-4.0, 4.0), draw(-4.0, 4.0));
        let torque = c.cross(&Vector3::from(g)) * mass - w.cross(&(i_o * w));
        let euler = i_o.lu().solve(&torque).unwrap();
        let mut a = [0.0; 3];
        el.accelerations(0.0, &[0.0; 3], w.as_slice(), &mut a).unwrap();
        worst = worst.max(relative(&a, euler.as_slice()));
    }
    println!("ball joint at θ = 0 vs Euler's equations: {worst:e}");
    assert!(worst < 1e-13, "{worst}");
}

/// Renewing the chart changes the coordinates, not the motion: for |θ| in (π, 2π) the renewed
/// θ' = θ (1 − 2π/|θ|) has |θ'| = 2π − |θ|, the same pose, and with the renewed rate the same L (so
/// the same velocities) to rounding (measured ≤ 1.2e-15 and 4.8e-15; tolerance 1e-13: 2π/|θ| rounds).
/// Inside |θ| ≤ π nothing changes; wrong lengths are errors.
#[test]
fn chart_renewal_keeps_the_motion() {
    let mut m = Mechanism::new().gravity([0.0, 0.0, -9.81]).unwrap();
    let upper = m
        .attach(
            Parent::Ground,
            Placement::identity(),
            Joint::spherical(),
            Body::new(
                1.0,
                [0.0, 0.0, -1.0],
                [[0.01, 0.0, 0.0], [0.0, 0.02, 0.0], [0.0, 0.0, 0.015]],
            ),
        )
        .unwrap();
    let lower = m
        .attach(
            upper,
            Placement::at([0.0, 0.0, -1.0]),
            Joint::free(),
            Body::new(
                0.5,
                [0.1, 0.0, -0.5],
                [[0.02, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.02]],
            ),
        )
        .unwrap();
    assert_eq!(m.coordinates(lower).unwrap(), 3..9);
    let mut draw = uniform(3);
    let mut worst = [0.0_f64; 2];
    for _ in 0..30 {
        let mut q: Vec<f64> = (0..9).map(|_| draw(-0.5, 0.5)).collect();
        let v: Vec<f64> = (0..9).map(|_| draw(-2.0, 2.0)).collect();
        // Both rotation vectors (q[0..3] and q[6..9]) stretched to lengths in (π, 2π − 0.2).
        for k in [0, 6] {
            let x = (q[k] * q[k] + q[k + 1] * q[k + 1] + q[k + 2] * q[k + 2]).sqrt();
            let want = draw(PI + 1e-3, 2.0 * PI - 0.2);
            q[k..k + 3].iter_mut().for_each(|t| *t *= want / x);
        }
        let (mut q2, mut v2) = (q.clone(), v.clone());
        assert_eq!(m.rechart(&mut q2, &mut v2).unwrap(), 2);
        for k in [0, 6] {
            let (x, x2) = (
                Vector3::new(q[k], q[k + 1], q[k + 2]).norm(),
                Vector3::new(q2[k], q2[k + 1], q2[k + 2]).norm(),
            );
            assert!((x + x2 - 2.0 * PI).abs() < 1e-14 && x2 < PI, "{x} {x2}");
        }
        for body in [upper, lower] {
            let (r, p) = m.pose(body, &q).unwrap();
            let (r2, p2) = m.pose(body, &q2).unwrap();
            worst[0] = worst[0].max((r - r2).amax()).max((p - p2).amax());
        }
        let l = m.lagrangian(0.0, &q, &v);
        worst[1] = worst[1].max(relative(&[m.lagrangian(0.0, &q2, &v2)], &[l]));
        // Renewed once, the joints are inside: a second renewal changes nothing.
        let (mut q3, mut v3) = (q2.clone(), v2.clone());
        assert_eq!(m.rechart(&mut q3, &mut v3).unwrap(), 0);
        assert_eq!((q3, v3), (q2, v2));
    }
    println!("chart renewal: pose {:e}, L {:e}", worst[0], worst[1]);
    assert!(worst.iter().all(|e| *e < 1e-13), "{worst:?}");
    assert!(m.rechart(&mut [0.0; 8], &mut [0.0; 9]).is_err());
    assert!(m.rechart(&mut [f64::NAN; 9], &mut [0.0; 9]).is_err());
    assert!(renewed_rotation_vector([3.0, 0.0, 0.0], [1.0, 0.0, 0.0]).is_none());
}

/// A free body (centre at the joint's origin, asymmetric inertia) thrown spinning about its middle
/// axis under gravity: its centre falls on the parabola p₀ + v₀ t + ½ g t² (translation and rotation
/// decouple), and with no torque about the centre its angular momentum in the world, R I_c Rᵀ ω, is
/// constant while it tumbles (the Dzhanibekov flip) through chart renewals. DOP853 at 10⁻¹² for
/// 12 s: measured 3.7e-16 (centre, relative to the distance fallen: DOP853 integrates a quadratic
/// exactly) and 3.3e-12 (momentum, relative, through 2 renewals); tolerances 1e-14 and 5e-11.
#[test]
fn free_joint_falls_and_tumbles() {
    let inertia = [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 3.0]];
    let g = [0.0, 0.0, -9.81];
    let mut m = Mechanism::new().gravity(g).unwrap();
    let body = m
        .attach(
            Parent::Ground,
            Placement::identity(),
            Joint::free(),
            Body::new(2.0, [0.0; 3], inertia),
        )
        .unwrap();
    let (p0, v0) = ([1.0, -2.0, 3.0], [0.5, 0.2, 8.0]);
    let theta0 = [0.1, 0.2, -0.1];
    let omega0 = [0.01, 3.0, 0.02];
    let rate0 = rotation_vector_rate(theta0, omega0).unwrap();
    let q0: Vec<f64> = p0.iter().chain(&theta0).copied().collect();
    let v0s: Vec<f64> = v0.iter().chain(&rate0).copied().collect();
    let el = EulerLagrange::new(&m);
    let momentum = |q: &[f64], v: &[f64]| {
        let (r, _) = m.pose(body, q).unwrap();
        let theta = [q[3], q[4], q[5]];
        let omega = Vector3::from(noether_multibody::frames::exponential_rate(
            theta,
            [v[3], v[4], v[5]],
        ));
        let ic = Matrix3::from_fn(|i, j| inertia[i][j]);
        r * ic * r.transpose() * omega
    };
    let l0 = momentum(&q0, &v0s);
    let end = 12.0;
    let sol = Driver::new(
        Dop853::new(&el).tolerances(1e-12, 1e-12).unwrap(),
        State::new(0.0, q0, v0s),
    )
    .unwrap()
    .event(m.chart_event())
    .run_until(end)
    .unwrap();
    let renewals = sol.event_times("rechart").unwrap().len();
    let mut drift = 0.0_f64;
    for i in 0..sol.len() {
        drift = drift.max((momentum(sol.q(i), sol.v(i)) - l0).amax() / l0.amax());
    }
    let last = sol.last();
    let parabola: Vec<f64> = (0..3)
        .map(|i| p0[i] + v0[i] * end + 0.5 * g[i] * end * end)
        .collect();
    let fallen = (0..3).map(|i| (parabola[i] - p0[i]).abs()).fold(0.0, f64::max);
    let centre = (0..3)
        .map(|i| (last.q[i] - parabola[i]).abs())
        .fold(0.0, f64::max)
        / fallen;
    // The flip: the body's middle axis (y) turns over, so its world y-component changes sign.
    let (r, _) = m.pose(body, last.q.as_slice()).unwrap();
    println!(
        "free joint: centre {centre:e}, momentum {drift:e}, {renewals} renewals, R_yy(end) {:.3}",
        r[(1, 1)]
    );
    assert!(renewals > 0, "the tumble renews the chart");
    assert!(centre < 1e-14 && drift < 5e-11, "{centre} {drift}");
    assert!(
        NewtonEuler::new(m.clone()).is_err(),
        "Newton-Euler takes one-coordinate joints"
    );
    assert!(m.coordinates(BodyId(0)).unwrap() == (0..6));
}

/// The rate for an angular velocity inverts J: J(θ) θ̇ = ω to rounding; at |θ| = 2π (J singular) and
/// for non-finite data it is an error.
#[test]
fn rotation_vector_rate_inverts_the_jacobian_and_refuses_the_chart_edge() {
    let mut draw = uniform(9);
    for _ in 0..20 {
        let theta = [draw(-3.0, 3.0), draw(-3.0, 3.0), draw(-3.0, 3.0)];
        let omega = [draw(-2.0, 2.0), draw(-2.0, 2.0), draw(-2.0, 2.0)];
        let rate = rotation_vector_rate(theta, omega).unwrap();
        let back = noether_multibody::frames::exponential_rate(theta, rate);
        assert!(relative(&back, &omega) < 1e-14, "{back:?} {omega:?}");
    }
    assert!(rotation_vector_rate([2.0 * PI, 0.0, 0.0], [1.0, 0.0, 0.0]).is_err());
    assert!(rotation_vector_rate([0.0, f64::NAN, 0.0], [1.0, 0.0, 0.0]).is_err());
}
