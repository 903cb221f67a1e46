//! Classical explicit methods: forward Euler, Euler-Cromer (semi-implicit Euler) and RK4.
//!
//! All three step any [`Dynamics`] on (q, v), v = q̇ or p, and leave the state untouched on error.

use crate::error::check_step;
use crate::{Dynamics, Error, Result, State, StepInfo, Stepper};

/// Checks `q`, `v` are finite, then writes them and t + h into `state`.
fn commit(state: &mut State, q: &[f64], v: &[f64], h: f64) -> Result<StepInfo> {
    if q.iter().chain(v).any(|x| !x.is_finite()) {
        return Err(Error::NonFiniteState { step: 0, t: state.t });
    }
    state.q.as_mut_slice().copy_from_slice(q);
    state.v.as_mut_slice().copy_from_slice(v);
    state.t += h;
    Ok(StepInfo::fixed(h))
}

/// Checks the dimensions of `state` against the system.
fn check_state(state: &State, n: usize) -> Result<()> {
    state.validate(n)
}

/// Forward Euler, order 1: (q, v) ← (q, v) + h F(t, q, v).
pub struct Euler<S> {
    system: S,
    dq: Vec<f64>,
    dv: Vec<f64>,
}

impl<S: Dynamics> Euler<S> {
    /// Forward Euler for `system`.
    pub fn new(system: S) -> Self {
        let n = system.dof();
        Euler {
            system,
            dq: vec![0.0; n],
            dv: vec![0.0; n],
        }
    }

    /// The system stepped.
    pub fn system(&self) -> &S {
        &self.system
    }
}

impl<S: Dynamics> Stepper for Euler<S> {
    fn step(&mut self, state: &mut State, h: f64) -> Result<StepInfo> {
        check_step(h)?;
        check_state(state, self.system.dof())?;
        let (t, q, v) = (state.t, state.q.as_slice(), state.v.as_slice());
        self.system.rates(t, q, v, &mut self.dq, &mut self.dv)?;
        self.dq.iter_mut().zip(q).for_each(|(d, x)| *d = x + h * *d);
        self.dv.iter_mut().zip(v).for_each(|(d, x)| *d = x + h * *d);
        let (nq, nv) = (std::mem::take(&mut self.dq), std::mem::take(&mut self.dv));
        let res = commit(state, &nq, &nv, h);
        (self.dq, self.dv) = (nq, nv);
        res
    }
    fn dof(&self) -> usize {
        self.system.dof()
    }
    fn order(&self) -> u32 {
        1
    }
    fn name(&self) -> &'static str {
        "Euler"
    }
}

/// Euler-Cromer (semi-implicit, or symplectic, Euler), order 1:
///
/// v_{n+1} = v_n + h v̇(t_n, q_n, v_n),   q_{n+1} = q_n + h q̇(t_n, q_n, v_{n+1}).
///
/// For L = T(q̇) − V(q) (q̇ = v, v̇ depending on q only) and for separable H = T(p) + V(q) this is the
/// symplectic Euler method; on other systems it is an explicit first-order method without that
/// property. It costs one vector field and one [`Dynamics::position_rates`] per step.
pub struct EulerCromer<S> {
    system: S,
    dq: Vec<f64>,
    dv: Vec<f64>,
}

impl<S: Dynamics> EulerCromer<S> {
    /// Euler-Cromer for `system`.
    pub fn new(system: S) -> Self {
        let n = system.dof();
        EulerCromer {
            system,
            dq: vec![0.0; n],
            dv: vec![0.0; n],
        }
    }

    /// The system stepped.
    pub fn system(&self) -> &S {
        &self.system
    }
}

impl<S: Dynamics> Stepper for EulerCromer<S> {
    fn step(&mut self, state: &mut State, h: f64) -> Result<StepInfo> {
        check_step(h)?;
        check_state(state, self.system.dof())?;
        let (t, q, v) = (state.t, state.q.as_slice(), state.v.as_slice());
        self.system.rates(t, q, v, &mut self.dq, &mut self.dv)?;
        self.dv.iter_mut().zip(v).for_each(|(d, x)| *d = x + h * *d);
        if self.dv.iter().any(|x| !x.is_finite()) {
            return Err(Error::NonFiniteState { step: 0, t });
        }
        self.system.position_rates(t, q, &self.dv, &mut self.dq)?;
        self.dq.iter_mut().zip(q).for_each(|(d, x)| *d = x + h * *d);
        let (nq, nv) = (std::mem::take(&mut self.dq), std::mem::take(&mut self.dv));
        let res = commit(state, &nq, &nv, h);
        (self.dq, self.dv) = (nq, nv);
        res
    }
    fn dof(&self) -> usize {
        self.system.dof()
    }
    fn order(&self) -> u32 {
        1
    }
    fn name(&self) -> &'static str {
        "Euler-Cromer"
    }
}

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
        check_state(state, n)?;
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
