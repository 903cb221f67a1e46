//! First-order dynamics on phase space, the interface every continuous integrator steps.
//!
//! A phase state is (t, q, v) where the second half `v` is q̇ for Lagrangian dynamics
//! ([`EulerLagrange`]) and p for Hamiltonian dynamics ([`HamiltonEquations`]); the associated type
//! [`Dynamics::Partner`] says which, so the states a system is stepped with carry it in their type.

use crate::{
    EulerLagrange, HamiltonEquations, Hamiltonian, Lagrangian, Momenta, Partner, Result, Velocities,
};

/// A vector field (q̇, v̇) = F(t, q, v) on phase space.
pub trait Dynamics {
    /// What `v` is: [`Velocities`] q̇ or [`Momenta`] p.
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

impl<L: Lagrangian> Dynamics for EulerLagrange<L> {
    type Partner = Velocities;
    fn dof(&self) -> usize {
        EulerLagrange::dof(self)
    }
    fn rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()> {
        self.accelerations(t, q, v, dv)?;
        dq.copy_from_slice(v);
        Ok(())
    }
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> Result<f64> {
        EulerLagrange::energy(self, t, q, v)
    }
    fn position_rates(&self, _t: f64, _q: &[f64], v: &[f64], dq: &mut [f64]) -> Result<()> {
        crate::error::check_len("q̇", v, self.dof())?;
        crate::error::check_len("q̇ (output)", dq, self.dof())?;
        dq.copy_from_slice(v);
        Ok(())
    }
}

impl<H: Hamiltonian> Dynamics for HamiltonEquations<H> {
    type Partner = Momenta;
    fn dof(&self) -> usize {
        HamiltonEquations::dof(self)
    }
    fn rates(&self, t: f64, q: &[f64], p: &[f64], dq: &mut [f64], dp: &mut [f64]) -> Result<()> {
        HamiltonEquations::rates(self, t, q, p, dq, dp)
    }
    fn energy(&self, t: f64, q: &[f64], p: &[f64]) -> Result<f64> {
        HamiltonEquations::energy(self, t, q, p)
    }
    fn position_rates(&self, t: f64, q: &[f64], p: &[f64], dq: &mut [f64]) -> Result<()> {
        HamiltonEquations::velocities(self, t, q, p, dq)
    }
}

// `S: Sized` (no `&dyn Dynamics`): the fixed-size rates forward to the system's own.
impl<S: Dynamics> Dynamics for &S {
    type Partner = S::Partner;
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()> {
        (**self).rates(t, q, v, dq, dv)
    }
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> Result<f64> {
        (**self).energy(t, q, v)
    }
    fn admissible(&self, t: f64, q: &[f64], v: &[f64]) -> Result<()> {
        (**self).admissible(t, q, v)
    }
    fn position_rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64]) -> Result<()> {
        (**self).position_rates(t, q, v, dq)
    }
    #[inline]
    fn rates_fixed<const N: usize>(&self, t: f64, q: [f64; N], v: [f64; N]) -> Result<([f64; N], [f64; N])> {
        (**self).rates_fixed(t, q, v)
    }
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
