//! The system traits of [`HamiltonEquations`]: Hamilton's equations on (q, p).

use crate::{HamiltonEquations, Hamiltonian, Momenta, Result};
use nalgebra::DMatrix;

use super::{Dynamics, LinearizedDynamics};

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

/// J = [[H_pq, H_pp], [−H_qq, −H_qp]] for q̇ = ∂H/∂p, ṗ = −∂H/∂q.
impl<H: Hamiltonian> LinearizedDynamics for HamiltonEquations<H> {
    fn jacobian(&self, t: f64, q: &[f64], p: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        let n = self.dof();
        let hess = self.hessian(t, q, p)?;
        for i in 0..n {
            for j in 0..n {
                out[(i, j)] = hess[(n + i, j)];
                out[(i, n + j)] = hess[(n + i, n + j)];
                out[(n + i, j)] = -hess[(i, j)];
                out[(n + i, n + j)] = -hess[(i, n + j)];
            }
        }
        Ok(())
    }
}
