//! The system traits of `&S`: a borrowed system is the same system.

use crate::Result;
use nalgebra::DMatrix;

use super::{Dynamics, LinearizedDynamics, SplitDynamics};

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

// `S: Sized` (no `&dyn SplitDynamics`): the fixed-size kick forwards to the system's own.
impl<S: SplitDynamics> SplitDynamics for &S {
    fn drift_rate(&self, v: &[f64], dq: &mut [f64]) -> Result<()> {
        (**self).drift_rate(v, dq)
    }
    fn kick_rate(&self, q: &[f64], dv: &mut [f64]) -> Result<()> {
        (**self).kick_rate(q, dv)
    }
    fn drift_is_identity(&self) -> bool {
        (**self).drift_is_identity()
    }
    #[inline]
    fn drift_rate_fixed<const W: usize>(&self, v: [f64; W]) -> Result<[f64; W]> {
        (**self).drift_rate_fixed(v)
    }
    #[inline]
    fn kick_rate_fixed<const W: usize>(&self, q: [f64; W]) -> Result<[f64; W]> {
        (**self).kick_rate_fixed(q)
    }
}

impl<S: LinearizedDynamics> LinearizedDynamics for &S {
    fn jacobian(&self, t: f64, q: &[f64], v: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        (**self).jacobian(t, q, v, out)
    }
    fn jacobian_vq(&self, t: f64, q: &[f64], v: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        (**self).jacobian_vq(t, q, v, out)
    }
    fn jacobian_qv(&self, t: f64, q: &[f64], v: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        (**self).jacobian_qv(t, q, v, out)
    }
}
