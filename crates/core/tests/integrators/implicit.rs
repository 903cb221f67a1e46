//! Implicit midpoint and Gauss-Legendre collocation: orders, energy behaviour on separable and
//! non-separable Hamiltonians, the Jacobian against a hand-written one, Newton failure.

use super::conserves::{energy_errors, STEPS};
use super::order::order_tests;
use super::problems::*;
use noether_core::integrators::LinearizedDynamics;
use noether_core::prelude::*;

order_tests! {
    order_implicit_midpoint: "implicit midpoint", order 2, Gauss::implicit_midpoint,
        HamiltonEquations::new(PendulumH), [80, 160, 320],
        HamiltonEquations::new(KeplerH), [320, 640, 1280];
    /// Kepler as a Natural system on (q, q̇): the Jacobian [[0, I], [−∇²V, 0]] path.
    order_gauss4: "Gauss 4", order 4, Gauss::gauss4,
        HamiltonEquations::new(PendulumH), [40, 80, 160],
        Natural::unit(KeplerV), [160, 320, 640];
    /// Kepler as a separable Hamiltonian on (q, p).
    order_gauss6: "Gauss 6", order 6, Gauss::gauss6,
        HamiltonEquations::new(PendulumH), [20, 40, 80],
        SeparableHamiltonian(Natural::unit(KeplerV)), [40, 80, 160];
}

#[test]
fn ad_vs_hand_jacobians() {
    // Pendulum H = ½p² − cos q: J = [[0, 1], [−cos q, 0]] in all three readings (unit mass).
    let (q, p) = (0.7_f64, -0.4);
    let expect = [0.0, 1.0, -q.cos(), 0.0];
    let mut j = nalgebra::DMatrix::zeros(2, 2);
    let assert_expected = |j: &nalgebra::DMatrix<f64>| {
        assert!(
            j.transpose()
                .iter()
                .zip(&expect)
                .all(|(a, b)| (a - b).abs() < 1e-14),
            "{j}"
        )
    };
    HamiltonEquations::new(PendulumH)
        .jacobian(0.0, &[q], &[p], &mut j)
        .unwrap();
    assert_expected(&j);
    SeparableHamiltonian(Natural::unit(PendulumV))
        .jacobian(0.0, &[q], &[p], &mut j)
        .unwrap();
    assert_expected(&j);
    Natural::unit(PendulumV)
        .jacobian(0.0, &[q], &[p], &mut j)
        .unwrap();
    assert_expected(&j);
}

/// A non-separable Hamiltonian H = ½ p² (1 + ½ q²) + ½ q² (a position-dependent mass).
struct NonSeparable;
impl Hamiltonian for NonSeparable {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        p[0] * p[0] * (q[0] * q[0] * 0.5 + 1.0) * 0.5 + q[0] * q[0] * 0.5
    }
}

#[test]
#[cfg_attr(debug_assertions, ignore = "long runs: run with --release")]
fn conserves_energy_gauss_pendulum() {
    // Symplectic and symmetric: the energy error stays O(h^p) without drift (see conserves.rs). The
    // pendulum from θ₀ = 2, 10⁶ steps of h = 0.1 (implicit midpoint) / 0.2 (Gauss 4) / 0.4 (Gauss 6),
    // so that the truncation error stays far above the Newton tolerance and rounding.
    let sys = HamiltonEquations::new(PendulumH);
    let start = || State::with_momenta(0.0, [2.0], [0.0]);
    for (name, h, mut s, bound) in [
        ("implicit midpoint", 0.1, Gauss::implicit_midpoint(&sys), 1e-2),
        ("Gauss 4", 0.2, Gauss::gauss4(&sys), 1e-4),
        ("Gauss 6", 0.4, Gauss::gauss6(&sys), 1e-5),
    ] {
        let (first, last) = energy_errors(&mut s, &sys, start(), STEPS, h);
        eprintln!("{name}: max |ΔE| first tenth {first:.3e}, last tenth {last:.3e}");
        assert!(last <= 1.1 * first + 1e-12, "{name}: {first:e} -> {last:e}");
        assert!(last <= bound, "{name}: {last:e}");
    }
}

#[test]
fn conserves_energy_gauss_non_separable() {
    // Explicit symplectic methods do not apply to this H; Gauss collocation does: bounded energy error
    // over 10⁵ steps of h = 0.3, against RK4's drift (at h = 0.1, where its error starts 10³× smaller
    // than Gauss 4's and still grows ~10× from the first to the last tenth).
    let sys = HamiltonEquations::new(NonSeparable);
    let start = || State::with_momenta(0.0, [1.5], [0.0]);
    let (first, last) = energy_errors(&mut Gauss::gauss4(&sys), &sys, start(), 100_000, 0.3);
    eprintln!("Gauss 4 non-separable: {first:.3e} -> {last:.3e}");
    assert!(last <= 1.1 * first + 1e-12 && last < 1e-3);
    let (f_rk, l_rk) = energy_errors(&mut Rk4::new(&sys), &sys, start(), 100_000, 0.1);
    eprintln!("RK4 non-separable: {f_rk:.3e} -> {l_rk:.3e}");
    assert!(l_rk > 5.0 * f_rk);
}

/// A stiff quartic oscillator H = ½ p² + 10⁴ q⁴ / 4.
struct StiffQuartic;
impl Hamiltonian for StiffQuartic {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        p[0] * p[0] * 0.5 + q[0].powi(4) * 2500.0
    }
}

#[test]
fn bad_input_newton_not_converging() {
    // A step of 10 on an oscillation of period ~0.02: the stage equations have no nearby solution
    // and Newton (cap 20 iterations) gives up with its iteration count and last residual; the state
    // is unchanged.
    let mut s = Gauss::gauss4(HamiltonEquations::new(StiffQuartic));
    // Issue 30 item 12: the error names the time of the step and suggests a smaller one.
    let mut state = State::with_momenta(0.25, [1.0], [0.0]);
    let before = state.clone();
    match s.step(&mut state, 10.0) {
        Err(
            e @ Error::NewtonDiverged {
                iterations,
                residual,
                tolerance,
                t,
            },
        ) => {
            eprintln!("Newton: {iterations} iterations, residual {residual:e}, tolerance {tolerance:e}");
            assert!(iterations == 20 && (residual > tolerance || residual.is_nan()));
            assert_eq!(t, 0.25);
            let msg = e.to_string();
            assert!(
                msg.starts_with("Newton did not converge after 20 iterations at t = 0.25:")
                    && msg.ends_with("try a smaller step"),
                "{msg}"
            );
        }
        other => panic!("expected NewtonDiverged, got {other:?}"),
    }
    assert_eq!(state, before);
    // The same step with h = 1e-4 converges in a few iterations.
    let info = s.step(&mut state, 1e-4).unwrap();
    assert!(info.newton_iterations >= 1 && info.newton_iterations < 10);
}

#[test]
fn bad_input_gauss_stages() {
    assert!(matches!(
        Gauss::new(HamiltonEquations::new(PendulumH), 4),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        Gauss::new(HamiltonEquations::new(PendulumH), 0),
        Err(Error::InvalidParameter { .. })
    ));
}
