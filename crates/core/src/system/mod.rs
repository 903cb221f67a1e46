//! The system traits: what a continuous integrator asks of the system it steps, and their impls for
//! core's system types, one file per type.
//!
//! A system is a first-order vector field on phase space. A phase state is (t, q, v) where the second
//! half `v` is q̇ for Lagrangian dynamics ([`EulerLagrange`](crate::EulerLagrange)) and p for
//! Hamiltonian dynamics ([`HamiltonEquations`](crate::HamiltonEquations)); the associated type
//! [`Dynamics::Partner`] says which, so the states a system is stepped with carry it in their type.
//! A system trait is a capability of such a vector field that some integrators need:
//!
//! | trait | provides | needed by |
//! |---|---|---|
//! | [`Dynamics`] | the rates (q̇, v̇) = F(t, q, v), the energy, admissible states | every continuous integrator: [`explicit`](crate::integrators::explicit), [`adaptive`](crate::integrators::adaptive) ([`dopri5`](crate::integrators::dopri5), [`dop853`](crate::integrators::dop853)) |
//! | [`SplitDynamics`] | the split q̇ = D(v), v̇ = K(q) | [`symplectic`](crate::integrators::symplectic), [`nystrom`](crate::integrators::nystrom) and [`ias15`](crate::integrators::ias15) (the last two with D(v) = v; IAS15 also steps any [`Dynamics`] on (q, q̇) wrapped in [`VelocityDependent`](crate::integrators::VelocityDependent)) |
//! | [`LinearizedDynamics`] | the Jacobian J = ∂F/∂y | [`gauss`](crate::integrators::gauss), and the step Jacobians of [`TangentStepper`](crate::TangentStepper) (see [`tangent`](crate::tangent)) |
//!
//! Which system type has which, each in its own file with all its impls:
//!
//! | system type | state | [`Dynamics`] | [`SplitDynamics`] | [`LinearizedDynamics`] | file |
//! |---|---|---|---|---|---|
//! | [`EulerLagrange`](crate::EulerLagrange) | (q, q̇) | yes | no | yes (third derivatives of L) | `euler_lagrange.rs` |
//! | [`HamiltonEquations`](crate::HamiltonEquations) | (q, p) | yes | no | yes | `hamilton_equations.rs` |
//! | [`SeparableHamiltonian`](crate::SeparableHamiltonian) | (q, p) | yes | yes | yes | `separable_hamiltonian.rs` |
//! | [`Natural`](crate::Natural) | (q, q̇) | yes | yes (D(v) = v) | yes | `natural.rs` |
//! | `&S` for a system `S` | as `S` | as `S` | as `S` | as `S` | `reference.rs` |
//!
//! A Hamiltonian from a Lagrangian by [`LegendreTransform`](crate::LegendreTransform) is stepped as
//! `HamiltonEquations<LegendreTransform<L>>`. The types themselves, with their equations (momenta,
//! accelerations, Hessians), stay in their modules ([`lagrange`](crate::lagrange),
//! [`hamilton`](crate::hamilton), [`model`](crate::model), [`natural`](crate::natural)); the other
//! crates implement these traits for their own systems (constraints, particles, rigid bodies).

mod euler_lagrange;
mod hamilton_equations;
mod natural;
mod reference;
mod separable_hamiltonian;

use crate::{Partner, Result};
use nalgebra::DMatrix;

/// A vector field (q̇, v̇) = F(t, q, v) on phase space.
pub trait Dynamics {
    /// What `v` is: [`Velocities`](crate::Velocities) q̇ or [`Momenta`](crate::Momenta) p.
    type Partner: Partner;

    /// Number of degrees of freedom (length of q and of v).
    fn dof(&self) -> usize;

    /// Writes the time derivatives of q and v into `dq` and `dv`.
    fn rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()>;

    /// The conserved energy of autonomous systems: h = q̇·∂L/∂q̇ − L, or H.
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> Result<f64>;

    /// (q̇, v̇) of [`rates`](Dynamics::rates) for a system of exactly N degrees of freedom, by value,
    /// and only when every value is finite (else an error, [`Error::NonFiniteResult`](crate::Error)
    /// when `rates` gave none): what the fixed-size trial step of the adaptive Runge-Kutta methods
    /// calls for small systems. The default forwards to `rates` and checks; [`Natural`](crate::Natural)
    /// calls its fixed-width force kernel directly, so that the model inlines into the step, the
    /// stages stay in registers and one test covers the result.
    #[inline]
    fn rates_fixed<const N: usize>(&self, t: f64, q: [f64; N], v: [f64; N]) -> Result<([f64; N], [f64; N])>
    where
        Self: Sized,
    {
        rates_by_slices(self, t, q, v)
    }

    /// Checks that (t, q, v) is a state this system may be stepped from. Every continuous stepper of
    /// core calls it on the state at the start of a step (not on its intermediate stages). The
    /// default accepts every state; a system with constraints (noether-constraints' `Constrained`)
    /// refuses one off its constraints, so that a plain integrator cannot run on from a state the
    /// equations of motion do not describe.
    fn admissible(&self, _t: f64, _q: &[f64], _v: &[f64]) -> Result<()> {
        Ok(())
    }

    /// Writes only q̇ into `dq` (used by semi-implicit methods that update v first). The default calls
    /// [`rates`](Dynamics::rates); systems where q̇ is cheap (q̇ = v, or ∂H/∂p alone) override it.
    fn position_rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64]) -> Result<()> {
        let mut dv = vec![0.0; v.len()];
        self.rates(t, q, v, dq, &mut dv)
    }
}

/// A vector field split as q̇ = D(v), v̇ = K(q): what explicit symplectic methods need.
pub trait SplitDynamics: Dynamics {
    /// The drift rate q̇ = D(v) (a function of v alone).
    fn drift_rate(&self, v: &[f64], dq: &mut [f64]) -> Result<()>;
    /// The kick rate v̇ = K(q) (a function of q alone).
    fn kick_rate(&self, q: &[f64], dv: &mut [f64]) -> Result<()>;
    /// `true` when D(v) = v, so the drift needs no call.
    fn drift_is_identity(&self) -> bool {
        false
    }
    /// [`drift_rate`](Self::drift_rate) for exactly W coordinates, by value, and only when every
    /// value is finite (else an error): what the fixed-size loop of
    /// [`Composition`](crate::integrators::Composition) calls when the drift is not the identity. The
    /// default forwards to `drift_rate` and checks; `SeparableHamiltonian` calls its fixed-width
    /// gradient of T directly.
    #[inline]
    fn drift_rate_fixed<const W: usize>(&self, v: [f64; W]) -> Result<[f64; W]>
    where
        Self: Sized,
    {
        rate_by_slices(v, "drift rate", |v, dq| self.drift_rate(v, dq))
    }
    /// [`kick_rate`](Self::kick_rate) for a system of exactly W coordinates, by value, and only when
    /// every value is finite (else an error, [`Error::NonFiniteResult`](crate::Error::NonFiniteResult)
    /// when `kick_rate` gave none): what the fixed-size loops of
    /// [`Composition`](crate::integrators::Composition) and [`Nystrom`](crate::integrators::Nystrom)
    /// call for small systems. The default forwards to `kick_rate` and checks;
    /// [`Natural`](crate::Natural) calls its fixed-width kernel directly, so that the model inlines
    /// into the loop, q, v and the force stay in registers, and one test covers the result.
    #[inline]
    fn kick_rate_fixed<const W: usize>(&self, q: [f64; W]) -> Result<[f64; W]>
    where
        Self: Sized,
    {
        rate_by_slices(q, "kick rate", |q, dv| self.kick_rate(q, dv))
    }
}

/// A [`Dynamics`] that also provides the Jacobian of its vector field.
pub trait LinearizedDynamics: Dynamics {
    /// J = ∂(q̇, v̇)/∂(q, v) at (t, q, v), written into the 2n × 2n matrix `out`.
    fn jacobian(&self, t: f64, q: &[f64], v: &[f64], out: &mut DMatrix<f64>) -> Result<()>;

    /// J's lower-left block ∂v̇/∂q (n × n) at (t, q, v), into `out`: for a split system the
    /// Jacobian of the kick, −M⁻¹∇²V(q) — all that a kick's tangent needs. The default takes it
    /// from [`jacobian`](Self::jacobian); a system that computes the block alone for less (one
    /// Hessian instead of J's two) overrides it with the same values.
    fn jacobian_vq(&self, t: f64, q: &[f64], v: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        jacobian_block(self, (t, q, v), (q.len(), 0), out)
    }

    /// J's upper-right block ∂q̇/∂v (n × n) at (t, q, v), into `out`: for a split system the
    /// Jacobian of the drift (∇²T(p) for H = T(p) + V(q)). The default takes it from
    /// [`jacobian`](Self::jacobian), as [`jacobian_vq`](Self::jacobian_vq)'s does.
    fn jacobian_qv(&self, t: f64, q: &[f64], v: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        jacobian_block(self, (t, q, v), (0, q.len()), out)
    }
}

/// What a block of J is called in a shape error.
pub(crate) const BLOCK: &str = "block of the Jacobian J (rows and columns)";

/// The n × n block of J at `corner` (the defaults of [`LinearizedDynamics::jacobian_vq`] and
/// [`jacobian_qv`](LinearizedDynamics::jacobian_qv)).
fn jacobian_block<S: LinearizedDynamics + ?Sized>(
    system: &S,
    (t, q, v): (f64, &[f64], &[f64]),
    corner: (usize, usize),
    out: &mut DMatrix<f64>,
) -> Result<()> {
    let n = q.len();
    crate::error::check_shape(BLOCK, out, n, n)?;
    let mut j = DMatrix::zeros(2 * n, 2 * n);
    system.jacobian(t, q, v, &mut j)?;
    out.copy_from(&j.view(corner, (n, n)));
    Ok(())
}

/// The general path of the fixed-size rates: [`Dynamics::rates`] on slices into arrays, `Ok` only
/// when every value is finite (else [`Error::NonFiniteResult`](crate::Error) at t).
#[inline]
pub(crate) fn rates_by_slices<S: Dynamics + ?Sized, const N: usize>(
    system: &S,
    t: f64,
    q: [f64; N],
    v: [f64; N],
) -> Result<([f64; N], [f64; N])> {
    let (mut dq, mut dv) = ([0.0; N], [0.0; N]);
    system.rates(t, &q, &v, &mut dq, &mut dv)?;
    crate::error::check_result("rates", t, &dq)?;
    crate::error::check_result("rates", t, &dv)?;
    Ok((dq, dv))
}

/// The same for one rate of one block (a drift, a kick, accelerations): `rate` on slices into an
/// array, `Ok` only when every value is finite (else [`Error::NonFiniteResult`](crate::Error)
/// naming `what`, at no time).
#[inline]
pub(crate) fn rate_by_slices<const W: usize>(
    x: [f64; W],
    what: &'static str,
    rate: impl FnOnce(&[f64], &mut [f64]) -> Result<()>,
) -> Result<[f64; W]> {
    let mut out = [0.0; W];
    rate(&x, &mut out)?;
    crate::error::check_result(what, f64::NAN, &out)?;
    Ok(out)
}
