//! `LinearizedDynamics` for `EulerLagrange<L>`: the exact Jacobian of Lagrange's equations (third
//! derivatives of L by a Lagrange jet over an inner dual number), and the tangents of the methods
//! that use it.

use super::*;
use noether_core::integrators::LinearizedDynamics;

/// Planar double pendulum (angles from the downward vertical, Δ = θ₁ − θ₂):
/// L = ½(m₁+m₂)l₁²θ̇₁² + ½m₂l₂²θ̇₂² + m₂l₁l₂θ̇₁θ̇₂ cos Δ + (m₁+m₂)gl₁ cos θ₁ + m₂gl₂ cos θ₂.
#[derive(Debug, Clone, Copy)]
pub struct DoublePendulum;
impl Lagrangian for DoublePendulum {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (m1, m2, l1, l2, g) = (1.3, 0.7, 1.1, 0.8, 9.81);
        v[0] * v[0] * (0.5 * (m1 + m2) * l1 * l1)
            + v[1] * v[1] * (0.5 * m2 * l2 * l2)
            + v[0] * v[1] * (q[0] - q[1]).cos() * (m2 * l1 * l2)
            + q[0].cos() * ((m1 + m2) * g * l1)
            + q[1].cos() * (m2 * g * l2)
    }
}

/// Spherical pendulum (m = 1, l = 1.2, g = 9.81) in (θ, φ): L = ½l²(θ̇² + sin²θ φ̇²) + gl cos θ.
#[derive(Debug, Clone, Copy)]
struct SphericalPendulum;
impl Lagrangian for SphericalPendulum {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (l, g) = (1.2, 9.81);
        (v[0] * v[0] + q[0].sin().powi(2) * v[1] * v[1]) * (0.5 * l * l) + q[0].cos() * (g * l)
    }
}

/// A relativistic particle (c = 1) in a harmonic well with a time-dependent gauge term:
/// L = −√(1 − q̇²) − ½q² + q̇ q sin t. The mass matrix (1 − q̇²)^(−3/2) depends on q̇, and the mixed
/// term carries ∂²L/∂q̇∂t = q cos t: every term of Lagrange's equations is exercised.
#[derive(Debug, Clone, Copy)]
struct DrivenRelativistic;
impl Lagrangian for DrivenRelativistic {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        -(D::one() - v[0] * v[0]).sqrt() - q[0] * q[0] * 0.5 + v[0] * q[0] * t.sin()
    }
}

/// max |J − J_fd|: J from `jacobian`, J_fd by central differences of the rates (q̇, q̈) with
/// δ_j = 1e-5·max(1, |y_j|).
fn jacobian_vs_differences<S: LinearizedDynamics>(sys: &S, t: f64, q: &[f64], v: &[f64]) -> f64 {
    let n = q.len();
    let mut jac = DMatrix::zeros(2 * n, 2 * n);
    sys.jacobian(t, q, v, &mut jac).unwrap();
    let mut fd = DMatrix::zeros(2 * n, 2 * n);
    for j in 0..2 * n {
        let mut ends = Vec::new();
        for sign in [1.0, -1.0] {
            let (mut qq, mut vv) = (q.to_vec(), v.to_vec());
            let y = if j < n { &mut qq[j] } else { &mut vv[j - n] };
            let delta = FD_REL * y.abs().max(1.0);
            *y += sign * delta;
            let (mut dq, mut dv) = (vec![0.0; n], vec![0.0; n]);
            sys.rates(t, &qq, &vv, &mut dq, &mut dv).unwrap();
            dq.extend(dv);
            ends.push((dq, delta));
        }
        for i in 0..2 * n {
            fd[(i, j)] = (ends[0].0[i] - ends[1].0[i]) / (2.0 * ends[0].1);
        }
    }
    (jac - fd).abs().max()
}

#[test]
fn lagrangian_jacobians_match_central_differences_of_the_accelerations() {
    let e_dp = jacobian_vs_differences(
        &EulerLagrange::new(DoublePendulum),
        0.0,
        &[0.7, -0.4],
        &[0.3, 1.1],
    );
    let e_sp = jacobian_vs_differences(
        &EulerLagrange::new(SphericalPendulum),
        0.0,
        &[0.8, 0.3],
        &[0.2, 1.5],
    );
    let e_rel = jacobian_vs_differences(&EulerLagrange::new(DrivenRelativistic), 0.4, &[0.6], &[0.5]);
    println!("|J − J_fd|: double pendulum {e_dp:e}, spherical {e_sp:e}, relativistic {e_rel:e}");
    // Measured 6.4e-10, 1.4e-10, 1.2e-10: the central differences' own error, truncation δ²|∂³q̈|/6
    // ≈ 1.7e-11 × third derivatives of q̈ of order g/l ≈ 10-30, plus rounding ε|q̈|/δ ≈ 1e-10.
    assert!(
        e_dp < 1e-9 && e_sp < 3e-10 && e_rel < 3e-10,
        "{e_dp:e} {e_sp:e} {e_rel:e}"
    );
}

#[test]
fn lagrangian_jacobian_of_a_natural_system_agrees_with_natural() {
    // A natural L = ½|q̇|² − V(q) written as a general Lagrangian: J must be Natural's
    // [[0, I], [−∇²V, 0]] (Hessian by dual numbers) to rounding.
    #[derive(Clone, Copy)]
    struct HhLagrangian;
    impl Lagrangian for HhLagrangian {
        fn dof(&self) -> usize {
            2
        }
        fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
            (v[0] * v[0] + v[1] * v[1]) * 0.5
                - ((q[0] * q[0] + q[1] * q[1]) * 0.5 + q[0] * q[0] * q[1] - q[1].powi(3) / 3.0)
        }
    }
    let (q, v) = ([0.1, -0.2], [0.45, 0.1]);
    let mut jac = DMatrix::zeros(4, 4);
    EulerLagrange::new(HhLagrangian)
        .jacobian(0.0, &q, &v, &mut jac)
        .unwrap();
    // ∇²V = [[1 + 2q₂, 2q₁], [2q₁, 1 − 2q₂]].
    let expected = DMatrix::from_row_slice(
        4,
        4,
        &[
            0.0,
            0.0,
            1.0,
            0.0, //
            0.0,
            0.0,
            0.0,
            1.0, //
            -(1.0 + 2.0 * q[1]),
            -2.0 * q[0],
            0.0,
            0.0, //
            -2.0 * q[0],
            -(1.0 - 2.0 * q[1]),
            0.0,
            0.0,
        ],
    );
    let e = (jac - expected).abs().max();
    println!("natural as a Lagrangian: |J − J_exact| = {e:e}");
    // Measured 0: the jet's arithmetic on a polynomial is exact here.
    assert!(e < 1e-15, "{e:e}");
}

#[test]
fn tangents_of_lagrangian_steps_match_central_differences() {
    let sys = EulerLagrange::new(DoublePendulum);
    let s = State::new(0.0, [0.7, -0.4], [0.3, 1.1]);
    let e_rk4 = tangent_vs_differences(&mut Rk4::new(&sys), &s, 0.01);
    let e_g4 = tangent_vs_differences(&mut Gauss::gauss4(&sys), &s, 0.01);
    let e_dp = tangent_vs_differences(&mut Dop853::new(&sys).fixed_step(true), &s, 0.01);
    println!("double pendulum: RK4 {e_rk4:e}, Gauss 4 {e_g4:e}, DOP853 {e_dp:e}");
    // Measured 9.7e-12, 7.1e-12, 8.2e-12: the reference's error (ε/δ rounding of the unit-size Ψ
    // entries, 1e-11; the truncation part is h times that of the Jacobian above).
    assert!(
        e_rk4 < 2e-11 && e_g4 < 2e-11 && e_dp < 2e-11,
        "{e_rk4:e} {e_g4:e} {e_dp:e}"
    );
}

/// Generalized forces are differentiated with L: for testkit's damped, driven Duffing oscillator
/// (m q̈ = −kq − βq³ − cq̇ + F cos ωt) the Jacobian is J = [[0, 1], [−(k + 3βq²)/m, −c/m]] in closed
/// form, and the tangents of RK4 and of Gauss 4 (whose Newton uses J) match differences of the step.
#[test]
fn forced_jacobian_closed_form_and_tangents() {
    let osc = noether_testkit::systems::DrivenOscillator::default();
    let sys = EulerLagrange::new(osc);
    let (t, q, v) = (0.3, 0.8, -0.5);
    let mut jac = DMatrix::zeros(2, 2);
    sys.jacobian(t, &[q], &[v], &mut jac).unwrap();
    let (m, k, beta, c) = (osc.m, osc.k, osc.beta, osc.c);
    let exact = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -(k + 3.0 * beta * q * q) / m, -c / m]);
    let e = (&jac - &exact).abs().max() / exact.abs().max();
    let s = State::new(t, [q], [v]);
    let e_rk4 = tangent_vs_differences(&mut Rk4::new(&sys), &s, 0.01);
    let e_g4 = tangent_vs_differences(&mut Gauss::gauss4(&sys), &s, 0.01);
    println!("forced Duffing: |J − J_exact|/|J| = {e:e}; tangents RK4 {e_rk4:e}, Gauss 4 {e_g4:e}");
    // J: rounding of the jet's few operations and one division by m (measured 3.3e-16 = 1.5ε).
    // Tangents: the reference's error as for the double pendulum above (measured 5.4e-12, 7.9e-12).
    assert!(e < 4.0 * f64::EPSILON, "{e:e}");
    assert!(e_rk4 < 2e-11 && e_g4 < 2e-11, "{e_rk4:e} {e_g4:e}");
}

#[test]
fn lagrangian_tangent_error_contract() {
    let sys = EulerLagrange::new(DoublePendulum);
    error_contract(
        &mut Rk4::new(&sys),
        &State::new(0.0, [0.7, -0.4], [0.3, 1.1]),
        0.01,
    );
}
