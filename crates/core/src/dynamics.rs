//! First-order dynamics on phase space, the interface every continuous integrator steps.
//!
//! A phase state is (t, q, v) where the second half `v` is q̇ for Lagrangian dynamics
//! ([`EulerLagrange`]) and p for Hamiltonian dynamics ([`HamiltonEquations`]).

use crate::{EulerLagrange, HamiltonEquations, Hamiltonian, Lagrangian, Result};

/// A vector field (q̇, v̇) = F(t, q, v) on phase space.
pub trait Dynamics {
    /// Number of degrees of freedom (length of q and of v).
    fn dof(&self) -> usize;

    /// Writes the time derivatives of q and v into `dq` and `dv`.
    fn rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()>;

    /// The conserved energy of autonomous systems: h = q̇·∂L/∂q̇ − L, or H.
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> Result<f64>;
}

impl<L: Lagrangian> Dynamics for EulerLagrange<L> {
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
}

impl<H: Hamiltonian> Dynamics for HamiltonEquations<H> {
    fn dof(&self) -> usize {
        HamiltonEquations::dof(self)
    }
    fn rates(&self, t: f64, q: &[f64], p: &[f64], dq: &mut [f64], dp: &mut [f64]) -> Result<()> {
        HamiltonEquations::rates(self, t, q, p, dq, dp)
    }
    fn energy(&self, t: f64, q: &[f64], p: &[f64]) -> Result<f64> {
        HamiltonEquations::energy(self, t, q, p)
    }
}

impl<S: Dynamics + ?Sized> Dynamics for &S {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()> {
        (**self).rates(t, q, v, dq, dv)
    }
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> Result<f64> {
        (**self).energy(t, q, v)
    }
}
