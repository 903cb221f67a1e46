//! Sensitivities of whole runs (noether_analysis::parameter_sensitivity, noether_core::tangent::run_jacobian) against
//! central finite differences of whole runs and against the closed form of the oscillator.

use nalgebra::DMatrix;
use noether_analysis::{parameter_sensitivity, Parametric, ParametricHamiltonian};
use noether_core::prelude::*;
use noether_core::tangent::run_jacobian;

/// Pendulum H = p²/(2 m l²) − m g l cos q with θ = (g, l), m = 1.
#[derive(Debug, Clone, Copy)]
struct Pendulum;
impl ParametricHamiltonian for Pendulum {
    fn dof(&self) -> usize {
        1
    }
    fn parameters(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D], theta: &[D]) -> D {
        let (g, l) = (theta[0], theta[1]);
        p[0] * p[0] / (l * l * 2.0) - g * l * q[0].cos()
    }
}

/// Oscillator H = ½(p² + ω² q²) with θ = (ω).
#[derive(Debug, Clone, Copy)]
struct Oscillator;
impl ParametricHamiltonian for Oscillator {
    fn dof(&self) -> usize {
        1
    }
    fn parameters(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D], theta: &[D]) -> D {
        (p[0] * p[0] + theta[0] * theta[0] * q[0] * q[0]) * 0.5
    }
}

/// End point (q, p) of a run of the parametric model with θ, by plain RK4 steps.
fn end_point<P: ParametricHamiltonian + Copy>(
    model: P,
    y0: [f64; 2],
    theta: &[f64],
    h: f64,
    steps: usize,
) -> [f64; 2] {
    let mut rk4 = Rk4::new(HamiltonEquations::new(Parametric::new(model)));
    let mut s = Parametric::new(model)
        .augment(&State::with_momenta(0.0, [y0[0]], [y0[1]]), theta)
        .unwrap();
    for _ in 0..steps {
        rk4.step(&mut s, h).unwrap();
    }
    [s.q[0], s.v[0]]
}

/// Central differences of whole runs: columns for y₀ (q₀, p₀) then θ, step δ = rel · max(1, |x|).
fn differences<P: ParametricHamiltonian + Copy>(
    model: P,
    y0: [f64; 2],
    theta: &[f64],
    h: f64,
    steps: usize,
    rel: f64,
) -> DMatrix<f64> {
    let k = theta.len();
    let mut out = DMatrix::zeros(2, 2 + k);
    for j in 0..2 + k {
        let x = if j < 2 { y0[j] } else { theta[j - 2] };
        let d = rel * x.abs().max(1.0);
        let ends: Vec<[f64; 2]> = [d, -d]
            .iter()
            .map(|&e| {
                let (mut y, mut th) = (y0, theta.to_vec());
                if j < 2 {
                    y[j] += e;
                } else {
                    th[j - 2] += e;
                }
                end_point(model, y, &th, h, steps)
            })
            .collect();
        for i in 0..2 {
            out[(i, j)] = (ends[0][i] - ends[1][i]) / (2.0 * d);
        }
    }
    out
}

/// The exact run Jacobian as one 2 × (2 + k) matrix: ∂(q, p)(T)/∂(q₀, p₀, θ).
fn combined(s: &noether_analysis::Sensitivity<Momenta>) -> DMatrix<f64> {
    let k = s.wrt_parameters.ncols();
    let mut out = DMatrix::zeros(2, 2 + k);
    out.view_mut((0, 0), (2, 2)).copy_from(&s.wrt_initial);
    out.view_mut((0, 2), (2, k)).copy_from(&s.wrt_parameters);
    out
}

/// The pendulum (m = 1, θ = (g, l) = (9.81, 1), from q₀ = 1 at rest, RK4 with h = 0.01 to T = 10, about
/// five swings): ∂(q, p)(T)/∂(q₀, p₀, g, l) by the augmented run against central differences of whole
/// runs. Plain central differences err by δ² (measured 1.4e-5 at δ = 1e-4, 1.4e-7 at 1e-5: the δ²
/// scaling says the exact Jacobian is their limit); the reference is their Richardson extrapolation
/// (4 D(δ/2) − D(δ))/3, truncation O(δ⁴) (2.3e-8 at δ = 1e-3, so ~1e-12 at 1e-4) plus the rounding
/// noise of the runs over δ (~1e-10 at δ = 1e-4, entries up to 18). Measured max |Δ| = 9.8e-11 at
/// δ = 1e-4; checked to 3e-10. The parameters ride along unchanged: θ̇ = ∂H/∂p_θ = 0 exactly, so the
/// augmented run ends with θ bit for bit.
#[test]
fn pendulum_against_differences() {
    let (h, steps) = (1e-2, 1000);
    let theta = [9.81, 1.0];
    let y0 = [1.0, 0.0];
    let mut rk4 = Rk4::new(HamiltonEquations::new(Parametric::new(Pendulum)));
    let start = State::with_momenta(0.0, [y0[0]], [y0[1]]);
    let s = parameter_sensitivity(&mut rk4, &start, &theta, h, steps).unwrap();
    let exact = combined(&s);
    let rel = 1e-4;
    let fd = differences(Pendulum, y0, &theta, h, steps, rel);
    let fd2 = differences(Pendulum, y0, &theta, h, steps, rel / 2.0);
    let richardson = (fd2 * 4.0 - fd) / 3.0;
    let err = (&exact - &richardson).abs().max();
    println!("pendulum: J = {exact}, max |J − J_fd| = {err:e}");
    assert!(err < 3e-10);
    // The end state is the plain run's, and θ does not move.
    assert_eq!(
        [s.state.q[0], s.state.v[0]],
        end_point(Pendulum, y0, &theta, h, steps)
    );
    let mut aug = Parametric::new(Pendulum).augment(&start, &theta).unwrap();
    let _ = run_jacobian(&mut rk4, &mut aug, h, steps).unwrap();
    assert_eq!(aug.q.as_slice()[1..], theta);
    assert!((aug.t - 10.0).abs() < 1e-12);
}

/// The oscillator H = ½(p² + ω²q²), θ = (ω), from (q₀, p₀) = (1, 0): the exact flow gives
/// q(T) = q₀ cos ωT, p(T) = −q₀ ω sin ωT, so ∂q/∂ω = −q₀ T sin ωT, ∂p/∂ω = −q₀ (sin ωT + ωT cos ωT) and
/// ∂y(T)/∂y₀ = [[cos ωT, sin ωT / ω], [−ω sin ωT, cos ωT]]. The numerical sensitivities are those of
/// RK4's map, which differs from the exact flow by O(h⁴): at ω = 1.5 to T = 2 the largest error is
/// 1.30e-7, 8.08e-9, 5.04e-10 at h = 0.02, 0.01, 0.005 (ratios 16.1 and 16.0 = 2⁴: checked in [14, 18]),
/// and 1.24e-12 at h = 0.001 (checked < 5e-12; there rounding of the 2000 steps starts to show).
#[test]
fn oscillator_closed_form() {
    let omega = 1.5;
    let t_end = 2.0;
    let error = |h: f64| {
        let steps = (t_end / h).round() as usize;
        let mut rk4 = Rk4::new(HamiltonEquations::new(Parametric::new(Oscillator)));
        let s = parameter_sensitivity(
            &mut rk4,
            &State::with_momenta(0.0, [1.0], [0.0]),
            &[omega],
            h,
            steps,
        )
        .unwrap();
        let (sn, cs) = (omega * t_end).sin_cos();
        let closed = DMatrix::from_row_slice(
            2,
            3,
            &[
                cs,
                sn / omega,
                -t_end * sn,
                -omega * sn,
                cs,
                -sn - omega * t_end * cs,
            ],
        );
        (combined(&s) - closed).abs().max()
    };
    let errors: Vec<f64> = [0.02, 0.01, 0.005, 0.001].into_iter().map(error).collect();
    println!(
        "oscillator: errors {errors:?}, ratios {} {}",
        errors[0] / errors[1],
        errors[1] / errors[2]
    );
    for w in errors[..3].windows(2) {
        assert!((14.0..18.0).contains(&(w[0] / w[1])));
    }
    assert!(errors[3] < 5e-12);
}

/// A stepper whose dof is not n + k and non-finite parameters are typed errors; zero steps give the
/// identity.
#[test]
fn bad_input() {
    let mut rk4 = Rk4::new(HamiltonEquations::new(Parametric::new(Pendulum)));
    let start = State::with_momenta(0.0, [1.0], [0.0]);
    let e = parameter_sensitivity(&mut rk4, &start, &[9.81], 0.01, 10).unwrap_err();
    assert!(matches!(
        e,
        noether_analysis::Error::Core(noether_core::Error::Dimension {
            expected: 2,
            got: 3,
            ..
        })
    ));
    let e = parameter_sensitivity(&mut rk4, &start, &[f64::NAN, 1.0], 0.01, 10).unwrap_err();
    assert!(matches!(
        e,
        noether_analysis::Error::Core(noether_core::Error::NonFinite { .. })
    ));
    let s = parameter_sensitivity(&mut rk4, &start, &[9.81, 1.0], 0.01, 0).unwrap();
    assert_eq!(s.wrt_initial, DMatrix::identity(2, 2));
    assert_eq!(s.wrt_parameters, DMatrix::zeros(2, 2));
}
