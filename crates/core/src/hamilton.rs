//! Hamilton's equations by dual numbers: q̇ = ∂H/∂p, ṗ = −∂H/∂q.

use crate::ad::{self, Block, Field};
use crate::error::{check_len, check_phase_point};
use crate::{Error, Hamiltonian, Result, Scalar};
use nalgebra::DMatrix;

/// A Hamiltonian seen as the AD field f(t, x = q, y = p).
pub(crate) struct HamiltonianField<'a, H: ?Sized>(pub &'a H);

impl<H: Hamiltonian + ?Sized> Field for HamiltonianField<'_, H> {
    #[inline]
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D]) -> D {
        self.0.hamiltonian(t, x, y)
    }
}

/// Hamilton's equations of a [`Hamiltonian`].
#[derive(Debug, Clone)]
pub struct HamiltonEquations<H> {
    hamiltonian: H,
}

impl<H: Hamiltonian> HamiltonEquations<H> {
    /// Wraps a Hamiltonian.
    pub fn new(hamiltonian: H) -> Self {
        HamiltonEquations { hamiltonian }
    }

    /// The wrapped Hamiltonian.
    pub fn hamiltonian(&self) -> &H {
        &self.hamiltonian
    }

    /// Number of degrees of freedom.
    pub fn dof(&self) -> usize {
        self.hamiltonian.dof()
    }

    fn check(&self, t: f64, q: &[f64], p: &[f64]) -> Result<()> {
        check_phase_point(self.dof(), t, q, p, "p")
    }

    /// The error for a non-finite result at (t, q, p): the model's own
    /// ([`Hamiltonian::failure`]) or [`Error::NonFiniteResult`].
    fn failure(&self, t: f64, q: &[f64], p: &[f64]) -> Error {
        self.hamiltonian
            .failure(t, q, p)
            .unwrap_or(Error::NonFiniteResult {
                what: "Hamiltonian or its derivatives",
                t,
                component: None,
            })
    }

    /// The value H(t, q, p) (the energy when H has no explicit time dependence).
    pub fn energy(&self, t: f64, q: &[f64], p: &[f64]) -> Result<f64> {
        self.check(t, q, p)?;
        let h = self.hamiltonian.hamiltonian(t, q, p);
        if !h.is_finite() {
            return Err(self.failure(t, q, p));
        }
        Ok(h)
    }

    /// q̇ = ∂H/∂p and ṗ = −∂H/∂q.
    pub fn rates(&self, t: f64, q: &[f64], p: &[f64], dq: &mut [f64], dp: &mut [f64]) -> Result<()> {
        self.check(t, q, p)?;
        check_len("q̇ (output)", dq, self.dof())?;
        check_len("ṗ (output)", dp, self.dof())?;
        let f = HamiltonianField(&self.hamiltonian);
        ad::gradient(&f, t, q, p, Block::Y, dq);
        ad::gradient(&f, t, q, p, Block::X, dp);
        dp.iter_mut().for_each(|x| *x = -*x);
        if dq.iter().chain(dp.iter()).any(|x| !x.is_finite()) {
            return Err(self.failure(t, q, p));
        }
        Ok(())
    }

    /// q̇ = ∂H/∂p alone.
    pub fn velocities(&self, t: f64, q: &[f64], p: &[f64], dq: &mut [f64]) -> Result<()> {
        self.check(t, q, p)?;
        check_len("q̇ (output)", dq, self.dof())?;
        ad::gradient(&HamiltonianField(&self.hamiltonian), t, q, p, Block::Y, dq);
        if dq.iter().any(|x| !x.is_finite()) {
            return Err(self.failure(t, q, p));
        }
        Ok(())
    }

    /// The Hessian of H in (q, p) as a 2n × 2n matrix [[H_qq, H_qp], [H_pq, H_pp]].
    pub fn hessian(&self, t: f64, q: &[f64], p: &[f64]) -> Result<DMatrix<f64>> {
        self.check(t, q, p)?;
        let n = self.dof();
        let f = HamiltonianField(&self.hamiltonian);
        let mut hqq = DMatrix::zeros(n, n);
        let mut hqp = DMatrix::zeros(n, n);
        let mut hpp = DMatrix::zeros(n, n);
        ad::hessian(&f, t, q, p, Block::X, Block::X, &mut hqq);
        ad::hessian(&f, t, q, p, Block::X, Block::Y, &mut hqp);
        ad::hessian(&f, t, q, p, Block::Y, Block::Y, &mut hpp);
        let mut h = DMatrix::zeros(2 * n, 2 * n);
        h.view_mut((0, 0), (n, n)).copy_from(&hqq);
        h.view_mut((0, n), (n, n)).copy_from(&hqp);
        h.view_mut((n, 0), (n, n)).copy_from(&hqp.transpose());
        h.view_mut((n, n), (n, n)).copy_from(&hpp);
        if h.iter().any(|x| !x.is_finite()) {
            return Err(self.failure(t, q, p));
        }
        Ok(h)
    }
}
