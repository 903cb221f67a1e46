//! What IAS15 asks of a system (see the [module](super) docs): a second-order system q̇ = v,
//! v̇ = f(t, q, v), through [`Ias15System`], either velocity- and time-independent (every split
//! system whose drift is the identity, f = K(q)) or general ([`VelocityDependent`]).

use crate::system::{Dynamics, SplitDynamics};
use crate::{Error, Result, Velocities};

/// A second-order system q̇ = v, v̇ = f(t, q, v) that [`Ias15`](super::Ias15) steps.
///
/// Implemented for every [`SplitDynamics`] (f = [`kick_rate`](SplitDynamics::kick_rate)(q), a function
/// of q alone: IAS15's fast path, the one REBOUND takes for gravity) and for [`VelocityDependent`]
/// (f = the v̇ of [`rates`](Dynamics::rates) at (t, q, v): drag, the Lorentz force, radiation forces,
/// post-Newtonian corrections, explicit time dependence).
pub trait Ias15System: Dynamics {
    /// `true` when f may depend on t and v: IAS15 then predicts v at every node from the current b,
    /// v(θ) = v₀ + hθ (a₀ + b₀θ/2 + … + b₆θ⁷/8), and evaluates f(t + θh, q(θ), v(θ)). `false` (the
    /// split systems) compiles that prediction away.
    const VELOCITY_DEPENDENT: bool;

    /// `Ok` when the system has the form q̇ = v that IAS15 integrates; [`Error::Unsupported`] otherwise
    /// (a split system whose drift is not the identity: a separable Hamiltonian on (q, p)).
    fn second_order(&self) -> Result<()>;

    /// Writes f(t, q, v) into `out`. `scratch` (n entries) receives what the system's rates write
    /// besides (q̇ = v); the split systems leave it alone.
    fn accelerations(&self, t: f64, q: &[f64], v: &[f64], scratch: &mut [f64], out: &mut [f64])
        -> Result<()>;
}

impl<S: SplitDynamics> Ias15System for S {
    const VELOCITY_DEPENDENT: bool = false;

    fn second_order(&self) -> Result<()> {
        if self.drift_is_identity() {
            Ok(())
        } else {
            Err(Error::Unsupported(
                "IAS15 integrates q̈ = f(t, q, q̇): it needs a split system whose drift is the identity \
                 (Natural, particle systems) or a system with velocities (VelocityDependent), not a \
                 separable Hamiltonian on (q, p)",
            ))
        }
    }

    #[inline(always)]
    fn accelerations(
        &self,
        _t: f64,
        q: &[f64],
        _v: &[f64],
        _scratch: &mut [f64],
        out: &mut [f64],
    ) -> Result<()> {
        self.kick_rate(q, out)
    }
}

/// A system with velocities (q̇ = v) whose accelerations f(t, q, v) may depend on time and on the
/// velocities, for [`Ias15`](super::Ias15): `Ias15::new(VelocityDependent(system))`.
///
/// Its rates are the system's (any [`Dynamics`] on (q, q̇): an
/// [`EulerLagrange`](crate::EulerLagrange) with a generalized force, noether-particles' `System` with
/// drag or the Lorentz force, a hand-written vector field); IAS15 evaluates them at the node times
/// and at the positions and velocities it predicts there (see the [module](super) docs). A system
/// whose forces depend on q alone runs faster as it is, through its [`SplitDynamics`].
///
/// ```
/// use noether_core::prelude::*;
/// use noether_core::integrators::VelocityDependent;
/// // q̈ = −q − 2γq̇ (damped, γ = 0.1) in the plane, a hand-written vector field on (q, q̇).
/// struct Damped;
/// impl Dynamics for Damped {
///     type Partner = Velocities;
///     fn dof(&self) -> usize { 2 }
///     fn rates(&self, _t: f64, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()> {
///         for i in 0..2 {
///             dq[i] = v[i];
///             dv[i] = -q[i] - 0.2 * v[i];
///         }
///         Ok(())
///     }
///     fn energy(&self, _t: f64, q: &[f64], v: &[f64]) -> Result<f64> {
///         Ok(0.5 * (v[0] * v[0] + v[1] * v[1] + q[0] * q[0] + q[1] * q[1]))
///     }
/// }
/// // From q = (1, 0), q̇ = (−γ, ω_d): the spiral q(t) = e^{−γt} (cos ω_d t, sin ω_d t), ω_d = √(1 − γ²).
/// let (g, wd) = (0.1_f64, 0.99_f64.sqrt());
/// let sol = Driver::new(Ias15::new(VelocityDependent(Damped))?, State::new(0.0, [1.0, 0.0], [-g, wd]))?
///     .save(Save::End)?
///     .run_until(10.0)?;
/// let r = (-g * 10.0).exp();
/// assert!((sol.last().q[0] - r * (wd * 10.0).cos()).abs() < 1e-13);
/// assert!((sol.last().q[1] - r * (wd * 10.0).sin()).abs() < 1e-13);
/// # Ok::<(), noether_core::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct VelocityDependent<S>(pub S);

impl<S: Dynamics<Partner = Velocities>> Dynamics for VelocityDependent<S> {
    type Partner = Velocities;
    fn dof(&self) -> usize {
        self.0.dof()
    }
    #[inline]
    fn rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()> {
        self.0.rates(t, q, v, dq, dv)
    }
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> Result<f64> {
        self.0.energy(t, q, v)
    }
    #[inline]
    fn rates_fixed<const N: usize>(&self, t: f64, q: [f64; N], v: [f64; N]) -> Result<([f64; N], [f64; N])> {
        self.0.rates_fixed(t, q, v)
    }
    fn admissible(&self, t: f64, q: &[f64], v: &[f64]) -> Result<()> {
        self.0.admissible(t, q, v)
    }
    fn position_rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64]) -> Result<()> {
        self.0.position_rates(t, q, v, dq)
    }
}

impl<S: Dynamics<Partner = Velocities>> Ias15System for VelocityDependent<S> {
    const VELOCITY_DEPENDENT: bool = true;

    /// Always `Ok`: the partner [`Velocities`] says that q̇ = v.
    fn second_order(&self) -> Result<()> {
        Ok(())
    }

    #[inline]
    fn accelerations(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        scratch: &mut [f64],
        out: &mut [f64],
    ) -> Result<()> {
        self.0.rates(t, q, v, scratch, out)
    }
}
