//! The derivative of the numerical flow (`TangentStepper`): each method's Ψ = ∂y₁/∂y₀ against central
//! differences of the step itself, on nonlinear problems. One test binary, one module per family.

mod explicit;
mod selfcheck;

use nalgebra::DMatrix;
use noether_core::prelude::*;
use noether_core::tangent::central_difference;

/// Hénon-Heiles, H = ½(p₁² + p₂²) + ½(q₁² + q₂²) + q₁²q₂ − q₂³/3: nonlinear, non-separable in no way
/// that matters here, with third derivatives of unit size.
#[derive(Debug, Clone, Copy)]
pub struct HenonHeiles;

impl Hamiltonian for HenonHeiles {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        (p[0] * p[0] + p[1] * p[1] + q[0] * q[0] + q[1] * q[1]) * 0.5 + q[0] * q[0] * q[1]
            - q[1].powi(3) / 3.0
    }
}

/// A state on a chaotic Hénon-Heiles orbit (E ≈ 0.13).
pub fn henon_heiles_state() -> State<Momenta> {
    State::new(0.0, [0.1, -0.2], [0.45, 0.1])
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
