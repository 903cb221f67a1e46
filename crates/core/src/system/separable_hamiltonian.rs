//! The system traits of [`SeparableHamiltonian`]: H = T(p) + V(q) on (q, p), split as q̇ = ∇T(p),
//! ṗ = −∇V(q), all gradients and Hessians by dual numbers.

use crate::ad::{self, Block, Field};
use crate::error::{check_finite, check_len, check_result, check_shape, finite_result};
use crate::{Result, Scalar, Separable, SeparableHamiltonian};
use nalgebra::DMatrix;

use super::{rates_by_slices, Dynamics, LinearizedDynamics, SplitDynamics, BLOCK};

struct KineticField<'a, S: ?Sized>(&'a S);
impl<S: Separable + ?Sized> Field for KineticField<'_, S> {
    fn eval<D: Scalar>(&self, _t: D, _x: &[D], y: &[D]) -> D {
        self.0.kinetic(y)
    }
}
struct PotentialOf<'a, S: ?Sized>(&'a S);
impl<S: Separable + ?Sized> Field for PotentialOf<'_, S> {
    fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
        self.0.potential(x)
    }
}

/// T(x) as a field of the first block, for [`ad::gradient_exact`] (which differentiates that block).
struct KineticOfX<'a, S: ?Sized>(&'a S);
impl<S: Separable + ?Sized> Field for KineticOfX<'_, S> {
    fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
        self.0.kinetic(x)
    }
}

impl<S: Separable> SeparableHamiltonian<S> {
    /// ∇T(p) (given p) and −∇V(q) (given q) for exactly N = dof ≤ [`ad::MAX_FIXED`] degrees of
    /// freedom, one fixed-width gradient each with every length a constant (the model inlines), zeros
    /// for the half not asked for; `None` when N does not fit or T + V + Σ 0·(rates, q, p) is not
    /// finite, for the general path to name the error.
    #[inline(always)]
    fn rates_fast<const N: usize>(
        &self,
        q: Option<&[f64; N]>,
        p: Option<&[f64; N]>,
    ) -> Option<([f64; N], [f64; N])> {
        if N != self.0.dof() || N > ad::MAX_FIXED {
            return None;
        }
        let (mut dq, mut dp, mut check) = ([0.0; N], [0.0; N], 0.0);
        // q and p enter the test too: T or V need not depend on all of them (the general path
        // checks its input).
        if let Some(p) = p {
            check += ad::gradient_exact(&KineticOfX(&self.0), 0.0, p, &mut dq);
            check = p.iter().fold(check, |c, x| c + x * 0.0);
        }
        if let Some(q) = q {
            check += ad::gradient_exact(&PotentialOf(&self.0), 0.0, q, &mut dp);
            dp = dp.map(|x| -x);
            check = q.iter().fold(check, |c, x| c + x * 0.0);
        }
        let check = dq.iter().chain(&dp).fold(check, |c, x| c + x * 0.0);
        check.is_finite().then_some((dq, dp))
    }

    /// The general path of the fixed-size rates, out of their way.
    #[cold]
    #[inline(never)]
    fn rates_cold<const N: usize>(&self, t: f64, q: [f64; N], p: [f64; N]) -> Result<([f64; N], [f64; N])> {
        rates_by_slices(self, t, q, p)
    }
}

/// Ok when the gradient `out` and the value it was taken of are finite (where T or V is infinite
/// there is no rate to return).
fn finite_or(value: f64, out: &[f64]) -> Result<()> {
    finite_result("forces", f64::NAN, value).and_then(|_| check_result("forces", f64::NAN, out))
}

/// State (q, p): q̇ = ∇T(p), ṗ = −∇V(q).
impl<S: Separable> Dynamics for SeparableHamiltonian<S> {
    type Partner = crate::Momenta;
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn rates(&self, t: f64, q: &[f64], p: &[f64], dq: &mut [f64], dp: &mut [f64]) -> Result<()> {
        check_len("p", p, self.0.dof())?;
        check_finite("q", q)?;
        check_finite("p", p)?;
        self.drift_rate(p, dq)
            .and_then(|_| self.kick_rate(q, dp))
            .map_err(|e| e.at_time(t))
    }
    fn energy(&self, _t: f64, q: &[f64], p: &[f64]) -> Result<f64> {
        let n = self.0.dof();
        check_len("q", q, n)?;
        check_len("p", p, n)?;
        Ok(self.0.kinetic(p) + self.0.potential(q))
    }
    fn position_rates(&self, t: f64, _q: &[f64], p: &[f64], dq: &mut [f64]) -> Result<()> {
        self.drift_rate(p, dq).map_err(|e| e.at_time(t))
    }
    /// ∇T(p) and −∇V(q) by fixed-width kernels called directly (the same values and errors as
    /// [`rates`](Dynamics::rates)).
    #[inline(always)]
    fn rates_fixed<const N: usize>(&self, t: f64, q: [f64; N], p: [f64; N]) -> Result<([f64; N], [f64; N])> {
        match self.rates_fast(Some(&q), Some(&p)) {
            Some(r) => Ok(r),
            None => self.rates_cold(t, q, p),
        }
    }
}

impl<S: Separable> SplitDynamics for SeparableHamiltonian<S> {
    fn drift_rate(&self, p: &[f64], dq: &mut [f64]) -> Result<()> {
        check_len("p", p, self.0.dof())?;
        check_len("q̇ (output)", dq, self.0.dof())?;
        let value = ad::gradient(&KineticField(&self.0), 0.0, &[], p, Block::Y, dq);
        finite_or(value, dq)
    }
    fn kick_rate(&self, q: &[f64], dp: &mut [f64]) -> Result<()> {
        check_len("q", q, self.0.dof())?;
        check_len("ṗ (output)", dp, self.0.dof())?;
        let value = ad::gradient(&PotentialOf(&self.0), 0.0, q, &[], Block::X, dp);
        dp.iter_mut().for_each(|x| *x = -*x);
        finite_or(value, dp)
    }
    /// ∇T(p) by the fixed-width kernel called directly (the same values and errors as `drift_rate`).
    #[inline]
    fn drift_rate_fixed<const W: usize>(&self, p: [f64; W]) -> Result<[f64; W]> {
        match self.rates_fast(None, Some(&p)) {
            Some((dq, _)) => Ok(dq),
            None => {
                let mut dq = [0.0; W];
                self.drift_rate(&p, &mut dq)?;
                Ok(dq)
            }
        }
    }
    /// −∇V(q) by the fixed-width kernel called directly (the same values and errors as `kick_rate`).
    #[inline]
    fn kick_rate_fixed<const W: usize>(&self, q: [f64; W]) -> Result<[f64; W]> {
        match self.rates_fast(Some(&q), None) {
            Some((_, dp)) => Ok(dp),
            None => {
                let mut dp = [0.0; W];
                self.kick_rate(&q, &mut dp)?;
                Ok(dp)
            }
        }
    }
}

/// J = [[0, ∇²T(p)], [−∇²V(q), 0]]; each block alone is one Hessian.
impl<S: Separable> LinearizedDynamics for SeparableHamiltonian<S> {
    fn jacobian(&self, t: f64, q: &[f64], p: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        let n = self.0.dof();
        let mut block = DMatrix::zeros(n, n);
        out.fill(0.0);
        self.jacobian_qv(t, q, p, &mut block)?;
        out.view_mut((0, n), (n, n)).copy_from(&block);
        self.jacobian_vq(t, q, p, &mut block)?;
        out.view_mut((n, 0), (n, n)).copy_from(&block);
        Ok(())
    }
    /// ∂ṗ/∂q = −∇²V(q).
    fn jacobian_vq(&self, _t: f64, q: &[f64], _p: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        check_len("q", q, self.0.dof())?;
        check_shape(BLOCK, out, q.len(), q.len())?;
        ad::hessian(&PotentialOf(&self.0), 0.0, q, &[], Block::X, Block::X, out);
        out.neg_mut();
        Ok(())
    }
    /// ∂q̇/∂p = ∇²T(p).
    fn jacobian_qv(&self, _t: f64, _q: &[f64], p: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        check_len("p", p, self.0.dof())?;
        check_shape(BLOCK, out, p.len(), p.len())?;
        ad::hessian(&KineticOfX(&self.0), 0.0, p, &[], Block::X, Block::X, out);
        Ok(())
    }
}
