//! The derivative of the numerical flow (`TangentStepper`): each method's Ψ = ∂y₁/∂y₀ against central
//! differences of the step itself, on nonlinear problems. One test binary, one module per family.

mod adaptive;
mod explicit;
mod gauss;
mod lagrangian;
mod nystrom;
mod run;
mod selfcheck;
mod symplectic;

use nalgebra::DMatrix;
use noether_core::prelude::*;
use noether_core::tangent::central_difference;
pub use noether_testkit::henon_heiles::HenonHeiles;

/// Hénon-Heiles as a separable H = T(p) + V(q), for the split methods.
#[derive(Debug, Clone, Copy)]
pub struct HhSeparable;

impl Separable for HhSeparable {
    fn dof(&self) -> usize {
        2
    }
    fn kinetic<D: Scalar>(&self, p: &[D]) -> D {
        (p[0] * p[0] + p[1] * p[1]) * 0.5
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        (q[0] * q[0] + q[1] * q[1]) * 0.5 + q[0] * q[0] * q[1] - q[1].powi(3) / 3.0
    }
}

/// A state on a chaotic Hénon-Heiles orbit (E ≈ 0.13).
pub fn henon_heiles_state() -> State<Momenta> {
    State::with_momenta(0.0, [0.1, -0.2], [0.45, 0.1])
}

/// Relative difference step of the reference and the agreement it allows: with δ = 1e-5 the central
/// difference has truncation error of order δ² times third derivatives (≈ 1e-10 h) and rounding
/// ε/δ ≈ 1e-11 on these unit-scale problems: an exact Ψ and the reference agree to about 1e-12
/// (measured per test).
pub const FD_REL: f64 = 1e-5;

/// max |Ψ − Ψ_fd| over the entries, Ψ from `step_tangent` and Ψ_fd from central differences, with the
/// check that the tangent step and a plain step land on the same state bit for bit.
pub fn tangent_vs_differences<S: TangentStepper>(stepper: &mut S, state: &State<S::Partner>, h: f64) -> f64
where
    S::Partner: std::fmt::Debug,
{
    let n = stepper.dof();
    let reference = central_difference(stepper, state, h, FD_REL).expect("finite differences");
    let mut psi = DMatrix::zeros(2 * n, 2 * n);
    let mut s = state.clone();
    stepper.step_tangent(&mut s, h, &mut psi).expect("tangent step");
    let mut plain = state.clone();
    stepper.step(&mut plain, h).expect("plain step");
    assert_eq!(s.q, plain.q, "the tangent step must take the same step");
    assert_eq!(s.v, plain.v, "the tangent step must take the same step");
    (psi - reference).abs().max()
}

/// The error contract of `step_tangent`: a wrongly shaped Ψ, a non-finite state and a non-finite step
/// are typed errors, and each leaves the state and Ψ exactly as they were.
pub fn error_contract<S: TangentStepper>(stepper: &mut S, state: &State<S::Partner>, h: f64)
where
    S::Partner: std::fmt::Debug,
{
    let n = stepper.dof();
    let mut s = state.clone();
    let mut bad = DMatrix::from_element(2 * n + 1, 2 * n, 7.0);
    let err = stepper.step_tangent(&mut s, h, &mut bad).unwrap_err();
    assert!(matches!(err, Error::Dimension { .. }), "{err}");
    assert_eq!(&s, state);
    assert_eq!(bad, DMatrix::from_element(2 * n + 1, 2 * n, 7.0));

    let sentinel = DMatrix::from_element(2 * n, 2 * n, 7.0);
    let mut psi = sentinel.clone();
    let err = stepper.step_tangent(&mut s, f64::NAN, &mut psi).unwrap_err();
    assert!(matches!(err, Error::InvalidStep { .. }), "{err}");
    assert_eq!(&s, state);
    assert_eq!(psi, sentinel);

    let mut nan = state.clone();
    nan.v[0] = f64::NAN;
    let before = nan.clone();
    let err = stepper.step_tangent(&mut nan, h, &mut psi).unwrap_err();
    assert!(
        matches!(err, Error::NonFinite { .. } | Error::NonFiniteState { .. }),
        "{err}"
    );
    assert_eq!(nan.q, before.q);
    assert!(nan.v[0].is_nan() && nan.t == before.t);
    assert_eq!(psi, sentinel);
}

/// max |ΨᵀΩΨ − Ω| with Ω = [[0, I], [−I, 0]] (core's selfcheck): zero for a symplectic map on (q, p).
pub fn symplecticity_defect(psi: &DMatrix<f64>) -> f64 {
    use noether_core::selfcheck::{canonical_form, form_defect};
    form_defect(psi, &canonical_form(psi.nrows() / 2))
}
