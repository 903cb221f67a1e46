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
//!
//! In discrete time, [`linearize_step`] gives (A_d, B_d) of one step of any integrator with a tangent,
//! the inputs held over the step (a zero-order hold), δx_{k+1} = A_d δx_k + B_d δu_k: the inputs become
//! coordinates s whose velocities ṡ = u nothing changes ([`HeldInputs`]), and the step's exact
//! Jacobian then holds B_d in its ṡ columns.

use crate::Result;
use nalgebra::{DMatrix, DVector};
use noether_core::ad::Buf;
use noether_core::control::{Actuated, ClosedLoop, Constant};
use noether_core::error::{check_finite, check_len, check_phase_point};
use noether_core::system::LinearizedDynamics;
use noether_core::{
    Dynamics, EulerLagrange, Lagrangian, Momenta, Partner, Scalar, State, TangentStepper, Velocities,
};

/// The linearisation (A, B) with the drift (core's type): here A = ∂(q̇, q̈)/∂(q, q̇) (2n × 2n),
/// B = ∂(q̇, q̈)/∂u (2n × m), drift ẋ* = (q̇*, q̈*).
pub use noether_core::control::Linearization;

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
    // ∂Q_u/∂u, then M⁻¹.
    let du = noether_core::control::input_jacobian(model, t, q, v, u);
    let m = u.len();
    let mass = held.mass_matrix(t, q, v)?;
    let factor = noether_core::linalg::factor_positive_mass(mass, t)?;
    let mut b = DMatrix::zeros(2 * n, m);
    b.view_mut((n, 0), (n, m)).copy_from(&factor.solve_matrix(&du));
    check_finite("linearisation B", b.as_slice())?;
    Ok(Linearization { a, b, drift })
}

/// An actuated model with its inputs held as coordinates (a zero-order hold): configuration (q, s),
///
/// ```text
/// L'(t, q, s, q̇, ṡ) = L(t, q, q̇) + ½ |ṡ|²,   Q' = (Q(t, q, q̇) + Q_u(t, q, q̇, ṡ), 0),
/// ```
///
/// so nothing acts on s, ṡ keeps its start value u over any step of any integrator, and the model
/// moves under the inputs u = ṡ. The Jacobian of one step of L' with respect to its start state
/// (q, s, q̇, ṡ) so holds ∂x_{k+1}/∂u_k in its ṡ columns ([`linearize_step`]).
pub struct HeldInputs<'a, A: ?Sized>(&'a A);

impl<'a, A: Actuated + ?Sized> HeldInputs<'a, A> {
    /// The inputs of `model` held as coordinates.
    pub fn new(model: &'a A) -> Self {
        HeldInputs(model)
    }
}

impl<A: Actuated + ?Sized> Lagrangian for HeldInputs<'_, A> {
    fn dof(&self) -> usize {
        self.0.dof() + self.0.inputs()
    }
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        let n = self.0.dof();
        v[n..]
            .iter()
            .fold(self.0.lagrangian(t, &q[..n], &v[..n]), |l, w| l + *w * *w * 0.5)
    }
    fn constant_mass_matrix(&self) -> bool {
        self.0.constant_mass_matrix()
    }
    fn has_generalized_force(&self) -> bool {
        true
    }
    fn generalized_force<D: Scalar>(&self, t: D, q: &[D], v: &[D], out: &mut [D]) {
        let n = self.0.dof();
        let (own, held) = out.split_at_mut(n);
        self.0.input_force(t, &q[..n], &v[..n], &v[n..], own);
        if self.0.has_generalized_force() {
            let mut extra = Buf::<D, 16>::filled(n, D::zero());
            self.0.generalized_force(t, &q[..n], &v[..n], &mut extra);
            own.iter_mut().zip(extra.iter()).for_each(|(o, f)| *o += *f);
        }
        held.iter_mut().for_each(|x| *x = D::zero());
    }
}

/// The linearisation of one step x_{k+1} = Φ_h(x_k, u_k), with the inputs held over the step:
/// δx_{k+1} = A_d δx_k + B_d δu_k, x the stepper's own state, (q, q̇) or (q, p).
#[derive(Debug, Clone, PartialEq)]
pub struct StepLinearization {
    /// A_d = ∂x_{k+1}/∂x_k, 2n × 2n.
    pub a: DMatrix<f64>,
    /// B_d = ∂x_{k+1}/∂u_k, 2n × m.
    pub b: DMatrix<f64>,
    /// x_{k+1} after the step: the start again at a rest point.
    pub next: DVector<f64>,
    /// The step h.
    pub h: f64,
}

/// The start state of a step with held inputs in a stepper's own coordinates (see
/// [`linearize_step`]): (q, s = 0, q̇, ṡ = u) for velocities; (q, s = 0, p, p_s = u) for momenta, with
/// p = ∂L/∂q̇ (L' is L plus ½|ṡ|², so p_s = ṡ = u and p does not depend on u).
pub trait HeldStart: Partner + Sized {
    /// The start state at `t` from (q, q̇) and the inputs `u`.
    fn held_start<A: Actuated>(model: &A, t: f64, q: &[f64], v: &[f64], u: &[f64]) -> Result<State<Self>>;
}

/// (q, s = 0): the configuration part of a held start.
fn held_configuration(q: &[f64], m: usize) -> Vec<f64> {
    q.iter().copied().chain(std::iter::repeat_n(0.0, m)).collect()
}

impl HeldStart for Velocities {
    fn held_start<A: Actuated>(_model: &A, t: f64, q: &[f64], v: &[f64], u: &[f64]) -> Result<State<Self>> {
        Ok(State::new(t, held_configuration(q, u.len()), [v, u].concat()))
    }
}

impl HeldStart for Momenta {
    fn held_start<A: Actuated>(model: &A, t: f64, q: &[f64], v: &[f64], u: &[f64]) -> Result<State<Self>> {
        let mut p = vec![0.0; q.len()];
        EulerLagrange::new(model).momenta(t, q, v, &mut p)?;
        Ok(State::with_momenta(
            t,
            held_configuration(q, u.len()),
            [&p[..], u].concat(),
        ))
    }
}

/// The discrete-time linearisation (A_d, B_d) of one step of size `h` from (t, q, q̇) with the inputs u
/// held over the step, for the integrator that `method` builds from the model with held inputs
/// ([`HeldInputs`]): `|l| Rk4::new(EulerLagrange::new(l))`, or a variational integrator
/// `|l| VariationalIntegrator::new(Midpoint::new(l))`. A_d and B_d are the exact Jacobian of the step
/// (the integrator's tangent, [`TangentStepper`]) in the stepper's own state, (q, q̇) or (q, p), B_d
/// from its ṡ (or p_s = u) columns. At a rest point the step's Jacobian is the method applied to the
/// continuous linearisation (for RK4 A_d = Σ_{k≤4} (Ah)^k/k!; for the midpoint variational integrator
/// the Cayley transform of h times the (q, p) linearisation). Errors: dimensions, non-finite input, a
/// step h that is zero or not finite, and the step's own errors.
pub fn linearize_step<'m, A, S, F>(
    model: &'m A,
    method: F,
    t: f64,
    (q, v): (&[f64], &[f64]),
    u: &[f64],
    h: f64,
) -> Result<StepLinearization>
where
    A: Actuated,
    F: FnOnce(HeldInputs<'m, A>) -> S,
    S: TangentStepper,
    S::Partner: HeldStart,
{
    let (n, m) = (model.dof(), model.inputs());
    check_phase_point(n, t, q, v, "q̇")?;
    check_len("inputs u", u, m)?;
    check_finite("inputs u", u)?;
    if !(h.is_finite() && h != 0.0) {
        return Err(noether_core::Error::InvalidStep { h }.into());
    }
    let mut state = S::Partner::held_start(model, t, q, v, u)?;
    let mut stepper = method(HeldInputs(model));
    let size = 2 * (n + m);
    let mut psi = DMatrix::zeros(size, size);
    stepper.step_tangent(&mut state, h, &mut psi)?;
    // Rows and columns of the model's state in (q, s, ·, ·), and the columns of the inputs.
    let x: Vec<usize> = (0..n).chain(n + m..2 * n + m).collect();
    let a = DMatrix::from_fn(2 * n, 2 * n, |i, j| psi[(x[i], x[j])]);
    let b = DMatrix::from_fn(2 * n, m, |i, j| psi[(x[i], 2 * n + m + j)]);
    let next = DVector::from_iterator(
        2 * n,
        x.iter()
            .map(|&i| if i < n + m { state.q[i] } else { state.v[i - n - m] }),
    );
    Ok(StepLinearization { a, b, next, h })
}
