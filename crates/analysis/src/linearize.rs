//! Linearisation of an actuated Lagrangian system about an operating point: the state-space matrices
//! (A, B) of
//!
//! ```text
//! δẋ = A δx + B δu,   x = (q, q̇),   A = ∂(q̇, q̈)/∂(q, q̇),   B = ∂(q̇, q̈)/∂u = [0; M⁻¹ ∂Q_u/∂u],
//! ```
//!
//! at any (t, q*, q̇*, u*): a rest point, or a steady motion with q̇* ≠ 0 (then the drift
//! ẋ* = (q̇*, q̈*) is reported beside A and B, and A is the linearisation along it). A is the exact
//! Jacobian of Lagrange's equations (third derivatives of L and the derivatives of every generalized
//! force, by dual numbers: noether-core's `LinearizedDynamics` of [`EulerLagrange`]), B one dual
//! evaluation of the input force Q_u per input (q̈ = M⁻¹ b and b depends on u through Q_u alone).
//! Nothing is differenced: both are exact to rounding.

use crate::Result;
use nalgebra::{DMatrix, DVector};
use noether_core::ad::Buf;
use noether_core::control::{Actuated, ClosedLoop, Constant};
use noether_core::error::{check_finite, check_len, check_phase_point};
use noether_core::system::LinearizedDynamics;
use noether_core::{Dynamics, EulerLagrange};
use num_dual::Dual64;

/// The linearisation (A, B) of an actuated system at an operating point, with the drift there.
#[derive(Debug, Clone, PartialEq)]
pub struct Linearization {
    /// A = ∂(q̇, q̈)/∂(q, q̇), 2n × 2n.
    pub a: DMatrix<f64>,
    /// B = ∂(q̇, q̈)/∂u, 2n × m.
    pub b: DMatrix<f64>,
    /// ẋ* = (q̇*, q̈*) at the point: zero at an equilibrium.
    pub drift: DVector<f64>,
}

/// (A, B) of `model` at (t, q, q̇, u) (module docs). Errors: dimensions, non-finite input, and the
/// errors of Lagrange's equations there (a singular mass matrix, more than 10 degrees of freedom for
/// A).
pub fn linearize<A: Actuated>(model: &A, t: f64, q: &[f64], v: &[f64], u: &[f64]) -> Result<Linearization> {
    let n = model.dof();
    check_phase_point(n, t, q, v, "q̇")?;
    check_len("inputs u", u, model.inputs())?;
    check_finite("inputs u", u)?;
    let held = EulerLagrange::new(ClosedLoop::new(model, Constant(u.to_vec()))?);
    let mut a = DMatrix::zeros(2 * n, 2 * n);
    held.jacobian(t, q, v, &mut a)?;
    let mut drift = DVector::zeros(2 * n);
    let (dq, dv) = drift.as_mut_slice().split_at_mut(n);
    held.rates(t, q, v, dq, dv)?;
    // ∂Q_u/∂u column by column, then M⁻¹.
    let m = u.len();
    let (qd, vd) = (Buf::<Dual64, 16>::constants(q), Buf::<Dual64, 16>::constants(v));
    let mut du = DMatrix::zeros(n, m);
    let mut force = vec![Dual64::from(0.0); n];
    for j in 0..m {
        let ud: Vec<Dual64> = (0..m)
            .map(|k| Dual64::new(u[k], if k == j { 1.0 } else { 0.0 }))
            .collect();
        model.input_force(Dual64::from(t), &qd, &vd, &ud, &mut force);
        for i in 0..n {
            du[(i, j)] = force[i].eps;
        }
    }
    let mass = held.mass_matrix(t, q, v)?;
    let factor = noether_core::linalg::factor_positive_mass(mass, t)?;
    let mut b = DMatrix::zeros(2 * n, m);
    b.view_mut((n, 0), (n, m)).copy_from(&factor.solve_matrix(&du));
    check_finite("linearisation B", b.as_slice())?;
    Ok(Linearization { a, b, drift })
}
