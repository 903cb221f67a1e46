//! Classical explicit methods.

use crate::error::check_step;
use crate::{Dynamics, Error, Result, State, StepInfo, Stepper};

/// Classical fourth-order Runge-Kutta method on (q, v).
///
/// k₁ = F(t, y), k₂ = F(t + h/2, y + h k₁/2), k₃ = F(t + h/2, y + h k₂/2), k₄ = F(t + h, y + h k₃),
/// y ← y + h (k₁ + 2k₂ + 2k₃ + k₄)/6.
pub struct Rk4<S> {
    system: S,
    k: [Vec<f64>; 8],
    tmp_q: Vec<f64>,
    tmp_v: Vec<f64>,
}

impl<S: Dynamics> Rk4<S> {
    /// RK4 for `system`.
    pub fn new(system: S) -> Self {
        let n = system.dof();
        Rk4 {
            system,
            k: std::array::from_fn(|_| vec![0.0; n]),
            tmp_q: vec![0.0; n],
            tmp_v: vec![0.0; n],
        }
    }

    /// The system stepped.
    pub fn system(&self) -> &S {
        &self.system
    }
}

impl<S: Dynamics> Stepper for Rk4<S> {
    fn step(&mut self, state: &mut State, h: f64) -> Result<StepInfo> {
        check_step(h)?;
        let n = self.system.dof();
        let (t, q, v) = (state.t, state.q.as_slice(), state.v.as_slice());
        let [k1q, k1v, k2q, k2v, k3q, k3v, k4q, k4v] = &mut self.k;
        self.system.rates(t, q, v, k1q, k1v)?;
        for i in 0..n {
            self.tmp_q[i] = q[i] + 0.5 * h * k1q[i];
            self.tmp_v[i] = v[i] + 0.5 * h * k1v[i];
        }
        self.system
            .rates(t + 0.5 * h, &self.tmp_q, &self.tmp_v, k2q, k2v)?;
        for i in 0..n {
            self.tmp_q[i] = q[i] + 0.5 * h * k2q[i];
            self.tmp_v[i] = v[i] + 0.5 * h * k2v[i];
        }
        self.system
            .rates(t + 0.5 * h, &self.tmp_q, &self.tmp_v, k3q, k3v)?;
        for i in 0..n {
            self.tmp_q[i] = q[i] + h * k3q[i];
            self.tmp_v[i] = v[i] + h * k3v[i];
        }
        self.system.rates(t + h, &self.tmp_q, &self.tmp_v, k4q, k4v)?;
        for i in 0..n {
            self.tmp_q[i] = q[i] + h / 6.0 * (k1q[i] + 2.0 * (k2q[i] + k3q[i]) + k4q[i]);
            self.tmp_v[i] = v[i] + h / 6.0 * (k1v[i] + 2.0 * (k2v[i] + k3v[i]) + k4v[i]);
        }
        if self.tmp_q.iter().chain(&self.tmp_v).any(|x| !x.is_finite()) {
            return Err(Error::NonFiniteState { step: 0, t });
        }
        state.q.as_mut_slice().copy_from_slice(&self.tmp_q);
        state.v.as_mut_slice().copy_from_slice(&self.tmp_v);
        state.t = t + h;
        Ok(StepInfo::fixed(h))
    }
    fn dof(&self) -> usize {
        self.system.dof()
    }
    fn order(&self) -> u32 {
        4
    }
    fn name(&self) -> &'static str {
        "RK4"
    }
}
