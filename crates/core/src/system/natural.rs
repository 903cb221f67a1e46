//! The system traits of [`Natural`]: L = ½ q̇ᵀ M q̇ − V(q) on (q, q̇), split as q̇ = v,
//! q̈ = −M⁻¹∇V(q).

use crate::ad;
use crate::error::{check_finite, check_len, check_shape};
use crate::natural::{Natural, Potential, PotentialField};
use crate::Result;
use nalgebra::DMatrix;

use super::{Dynamics, LinearizedDynamics, SplitDynamics, BLOCK};

/// State (q, q̇): q̇ = q̇, q̈ = −M⁻¹∇V(q).
impl<P: Potential> Dynamics for Natural<P> {
    type Partner = crate::Velocities;
    fn dof(&self) -> usize {
        Natural::dof(self)
    }
    #[inline]
    fn rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()> {
        check_len("q̇", v, self.dof())?;
        check_len("q̇ (output)", dq, self.dof())?;
        // An element loop: a few entries, no call to memcpy.
        dq.iter_mut().zip(v).for_each(|(d, x)| *d = *x);
        self.accelerations(q, dv).map_err(|e| e.at_time(t))?;
        // q̇ = v is returned as given: one check of it, after the work (the error still names it).
        check_finite("q̇", v)
    }
    /// q̇ = v and q̈ from the fixed-width force kernel, called directly: the same values and errors
    /// as [`rates`](Dynamics::rates).
    #[inline(always)]
    fn rates_fixed<const N: usize>(&self, t: f64, q: [f64; N], v: [f64; N]) -> Result<([f64; N], [f64; N])> {
        // q̇ = v is returned as given: its check joins the kernel's one test.
        match self.accelerations_fast(q, v.iter().fold(0.0, |c, x| c + x * 0.0)) {
            Some(a) => Ok((v, a)),
            None => self.rates_cold(t, q, v),
        }
    }
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> Result<f64> {
        Natural::energy(self, q, v).map_err(|e| e.at_time(t))
    }
    fn position_rates(&self, _t: f64, _q: &[f64], v: &[f64], dq: &mut [f64]) -> Result<()> {
        check_len("q̇", v, self.dof())?;
        dq.copy_from_slice(v);
        Ok(())
    }
}

impl<P: Potential> SplitDynamics for Natural<P> {
    /// q̇ = v, checked (lengths, finite).
    fn drift_rate(&self, v: &[f64], dq: &mut [f64]) -> Result<()> {
        check_len("q̇", v, self.dof())?;
        check_len("q̇ (output)", dq, self.dof())?;
        check_finite("q̇", v)?;
        dq.copy_from_slice(v);
        Ok(())
    }
    #[inline]
    fn drift_rate_fixed<const W: usize>(&self, v: [f64; W]) -> Result<[f64; W]> {
        check_len("q̇", &v, self.dof())?;
        check_finite("q̇", &v)?;
        Ok(v)
    }
    #[inline]
    fn kick_rate(&self, q: &[f64], dv: &mut [f64]) -> Result<()> {
        self.accelerations(q, dv)
    }
    fn drift_is_identity(&self) -> bool {
        true
    }
    #[inline]
    fn kick_rate_fixed<const W: usize>(&self, q: [f64; W]) -> Result<[f64; W]> {
        self.accelerations_fixed(q)
    }
}

/// On (q, q̇): J = [[0, I], [−M⁻¹∇²V(q), 0]].
impl<P: Potential> LinearizedDynamics for Natural<P> {
    fn jacobian(&self, t: f64, q: &[f64], v: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        let n = self.dof();
        let mut block = DMatrix::zeros(n, n);
        self.jacobian_vq(t, q, v, &mut block)?;
        out.fill(0.0);
        out.view_mut((0, n), (n, n)).fill_with_identity();
        out.view_mut((n, 0), (n, n)).copy_from(&block);
        Ok(())
    }
    /// ∂v̇/∂q = −M⁻¹∇²V(q).
    fn jacobian_vq(&self, _t: f64, q: &[f64], _v: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        let n = self.dof();
        check_len("q", q, n)?;
        check_shape(BLOCK, out, n, n)?;
        let mut hess = DMatrix::zeros(n, n);
        ad::hessian(
            &PotentialField(self.potential_model()),
            0.0,
            q,
            &[],
            ad::Block::X,
            ad::Block::X,
            &mut hess,
        );
        out.copy_from(&(-self.inverse_mass_matrix() * hess));
        Ok(())
    }
    /// ∂q̇/∂v = I.
    fn jacobian_qv(&self, _t: f64, _q: &[f64], _v: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        check_shape(BLOCK, out, self.dof(), self.dof())?;
        out.fill_with_identity();
        Ok(())
    }
}
