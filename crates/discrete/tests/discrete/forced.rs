//! Generalized forces through the variational integrators (the discrete Lagrange-d'Alembert
//! principle), on testkit's damped, driven oscillator m q̈ + c q̇ + k q + β q³ = F cos ωt: Newton with
//! the forces' derivatives in its Jacobian, and the orders of the midpoint, trapezoidal and Galerkin
//! methods against the closed form of the linear (β = 0) oscillator. The forced tangents are in
//! `tangent`.

use noether_core::{Momenta, Stepper};
use noether_discrete::{Galerkin, Midpoint, Trapezoidal, VariationalIntegrator};
use noether_testkit::systems::DrivenOscillator;

type State = noether_core::State<Momenta>;

/// Newton's Jacobian is D₁₂L_d + ∂f⁻/∂q₁. With strong damping (c = 50, m = 0.8, h = 0.1) the force
/// term dominates: for the midpoint rule ∂f⁻/∂q₁ = −c/2 = −25 against D₁₂L_d ≈ −m/h = −8, so Newton
/// without it would multiply the error by 1 − 33/8 ≈ −3 per iteration and diverge. With it, Newton
/// converges quadratically: measured at most 4 iterations per step (predictor error ~1e-3, then
/// ~1e-6, 1e-12, below the 1e-16 tolerance, and the check), where a linear rate would need dozens.
#[test]
fn newton_includes_the_forces_derivatives() {
    let osc = DrivenOscillator {
        c: 50.0,
        ..Default::default()
    };
    let mut vi = VariationalIntegrator::new(Midpoint::new(osc));
    let mut s = State::with_momenta(0.0, [1.2], [0.0]);
    let mut most = 0;
    for _ in 0..50 {
        vi.step(&mut s, 0.1).unwrap();
        most = most.max(vi.last_newton().iterations);
    }
    println!("heavily damped midpoint: at most {most} Newton iterations per step");
    assert!(most <= 4, "{most}");
}

/// The global error at t = 5 of the linear driven, damped oscillator (q(0) = 0.6, q̇(0) = −0.4)
/// against `DrivenOscillator::linear_solution`, for `n` and `2n` steps: the observed order
/// log₂(e_n / e_2n) is within 0.1 of the method's.
fn assert_order<S: Stepper<Partner = Momenta>>(what: &str, make: impl Fn() -> S, n: usize, order: f64) {
    let osc = DrivenOscillator::linear();
    let (t_end, q0, v0) = (5.0, 0.6, -0.4);
    let (exact, _) = osc.linear_solution(t_end, q0, v0);
    let error = |n: usize| {
        let mut stepper = make();
        let mut s = State::with_momenta(0.0, [q0], [osc.m * v0]);
        for _ in 0..n {
            stepper.step(&mut s, t_end / n as f64).unwrap();
        }
        (s.q[0] - exact).abs()
    };
    let (e1, e2) = (error(n), error(2 * n));
    let observed = (e1 / e2).log2();
    println!(
        "{what}: err({n}) = {e1:.3e}, err({}) = {e2:.3e}, order {observed:.3}",
        2 * n
    );
    assert!(
        (observed - order).abs() < 0.1,
        "{what}: order {observed} vs {order}"
    );
}

#[test]
fn order_of_the_forced_midpoint_and_trapezoidal_rules() {
    let osc = DrivenOscillator::linear();
    assert_order(
        "midpoint",
        || VariationalIntegrator::new(Midpoint::new(osc)),
        200,
        2.0,
    );
    assert_order(
        "trapezoidal",
        || VariationalIntegrator::new(Trapezoidal::new(osc)),
        200,
        2.0,
    );
}

/// The forced Galerkin methods keep their orders 4 and 6 (the forces by the same Gauss quadrature on
/// the same polynomial path).
#[test]
fn order_of_the_forced_galerkin_methods() {
    let osc = DrivenOscillator::linear();
    assert_order("Galerkin 4", || Galerkin::order4(osc).unwrap(), 40, 4.0);
    assert_order("Galerkin 6", || Galerkin::order6(osc).unwrap(), 20, 6.0);
}

/// The boundary-value problem of the linear driven, damped oscillator from q(0) = 0.6 to q(4) = −0.3
/// by the discrete Lagrange-d'Alembert equations (midpoint rule), against the closed form: the
/// solution through q(0) whose initial velocity v₀ is fixed by q(4), found from
/// `linear_solution`, which is affine in v₀ (q(T; v₀) = q(T; 0) + v₀ (q(T; 1) − q(T; 0))). The node
/// error is second order: the ratio for N = 100 → 200 within 0.1 of 4 in log₂, i.e. order 2.
#[test]
fn closed_form_forced_boundary_value_problem() {
    let osc = DrivenOscillator::linear();
    let (t_end, a, b) = (4.0, 0.6, -0.3);
    let at_end = |v0: f64| osc.linear_solution(t_end, a, v0).0;
    let v0 = (b - at_end(0.0)) / (at_end(1.0) - at_end(0.0));
    let bvp = noether_discrete::BoundaryValue::new(Midpoint::new(osc));
    let error = |n: usize| {
        let path = bvp.solve(0.0, &[a], t_end, &[b], n).unwrap();
        assert!(path.morse_index.is_none() && path.margin.is_nan());
        let nodes = path.t.iter().zip(&path.q);
        let worst = nodes
            .map(|(&t, q)| (q[0] - osc.linear_solution(t, a, v0).0).abs())
            .fold(0.0, f64::max);
        // The end momentum p_N = D₂L_d + f⁺ approximates m q̇(T) to second order as well.
        let p_end = osc.m * osc.linear_solution(t_end, a, v0).1;
        (worst, (path.p1[0] - p_end).abs())
    };
    let ((e1, p1), (e2, p2)) = (error(100), error(200));
    let (order, order_p) = ((e1 / e2).log2(), (p1 / p2).log2());
    println!("forced BVP: node errors {e1:.3e} → {e2:.3e} (order {order:.3}), end momentum {p1:.3e} → {p2:.3e} (order {order_p:.3})");
    assert!(
        (order - 2.0).abs() < 0.1 && (order_p - 2.0).abs() < 0.1,
        "{order} {order_p}"
    );
}

/// The periodic response of the linear driven, damped oscillator as a loop: over one drive period
/// T = 2π/ω with N steps, the family q_k = y_k (k < N), q_N = y₀ and the discrete Lagrange-d'Alembert
/// equations over it (`BoundaryValue::solve_linear` with forces). The continuous steady response is
/// A cos ωt + B sin ωt with (A, B) = F (k − mω², cω)/((k − mω²)² + (cω)²) (`linear_solution` with the
/// transient removed); the discrete loop converges to it at the midpoint rule's second order
/// (measured node errors 2.8e-2 and 7.0e-3 at N = 64 and 128 — large, as the drive ω = 1.9 is near
/// resonance, √(k/m) = 1.94, where the midpoint rule's frequency error counts most — order 2.003; the
/// test asks order 2 ± 0.05). The equations are linear in y: Newton's first correction solves them,
/// and it stops within 3 iterations (measured 3) at its rounding floor.
#[test]
fn periodic_response_of_the_driven_oscillator_as_a_loop() {
    use nalgebra::DMatrix;
    let osc = DrivenOscillator::linear();
    let period = 2.0 * std::f64::consts::PI / osc.omega;
    let det = (osc.k - osc.m * osc.omega.powi(2)).powi(2) + (osc.c * osc.omega).powi(2);
    let (a, b) = (
        osc.f * (osc.k - osc.m * osc.omega.powi(2)) / det,
        osc.f * osc.c * osc.omega / det,
    );
    let bvp = noether_discrete::BoundaryValue::new(Midpoint::new(osc));
    let error = |n: usize| {
        let maps: Vec<DMatrix<f64>> = (0..=n)
            .map(|k| {
                let mut m = DMatrix::zeros(1, n);
                m[(0, k % n)] = 1.0;
                m
            })
            .collect();
        let path = bvp.solve_linear(0.0, period, &maps, &vec![0.0; n]).unwrap();
        assert!(path.newton.iterations <= 3, "{}", path.newton.iterations);
        path.t
            .iter()
            .zip(&path.q)
            .map(|(&t, q)| (q[0] - (a * (osc.omega * t).cos() + b * (osc.omega * t).sin())).abs())
            .fold(0.0, f64::max)
    };
    let (e1, e2) = (error(64), error(128));
    let order = (e1 / e2).log2();
    println!("periodic response: node errors {e1:.2e} → {e2:.2e}, order {order:.3}");
    assert!((order - 2.0).abs() < 0.05, "{order}");
}
