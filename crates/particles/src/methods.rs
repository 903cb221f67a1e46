//! The seed's state updates (Euler, Euler-Cromer, RK4), symplectic velocity Verlet and Yoshida's
//! 4th-order composition on the particle system, and the evolver (an iterator of states).
//!
//! With a = F(t, x, v)/m:
//! - Euler: x' = x + h v, v' = v + h a(x, v);
//! - Euler-Cromer (semi-implicit): v' = v + h a(x, v), x' = x + h v';
//! - RK4: core's classical Runge-Kutta on (x, v);
//! - velocity Verlet (kick-drift-kick): v½ = v + (h/2) a(x), x' = x + h v½, v' = v½ + (h/2) a(x');
//!   symplectic, order 2, one force evaluation per step (the last one is reused);
//! - Yoshida 4: three Verlet steps of w₁h, w₀h, w₁h with w₁ = 1/(2 − 2^{1/3}), w₀ = 1 − 2w₁;
//!   symplectic, order 4.
//!
//! Every method leaves the state unchanged when a step fails.

use crate::error::{Error, Result};
use crate::interaction::Interaction;
use crate::system::System;
use noether_core::error::check_step;
use noether_core::integrators::Rk4;
use noether_core::{State, StepInfo, Stepper, Trajectory};

/// A state-update method for particle systems.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Forward Euler (order 1).
    Euler,
    /// Euler-Cromer, semi-implicit Euler (order 1, symplectic for position-only forces).
    EulerCromer,
    /// Classical Runge-Kutta (order 4).
    Rk4,
    /// Velocity Verlet / Störmer-Verlet (order 2, symplectic).
    VelocityVerlet,
    /// Yoshida's triple-jump composition of velocity Verlet (order 4, symplectic).
    Yoshida4,
}

impl Method {
    /// Order of accuracy.
    pub fn order(self) -> u32 {
        match self {
            Method::Euler | Method::EulerCromer => 1,
            Method::VelocityVerlet => 2,
            Method::Rk4 | Method::Yoshida4 => 4,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Method::Euler => "Euler",
            Method::EulerCromer => "Euler-Cromer",
            Method::Rk4 => "RK4",
            Method::VelocityVerlet => "velocity Verlet",
            Method::Yoshida4 => "Yoshida 4",
        }
    }
}

/// A [`Stepper`] for a particle system with one of the [`Method`]s (use it with core's [`Trajectory`]).
pub struct ParticleStepper<'a, I> {
    sys: &'a System<I>,
    method: Method,
    rk4: Option<Rk4<&'a System<I>>>,
    x: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    /// Positions at which `a` holds the accelerations (velocity Verlet reuses its last force).
    a_at: Option<Vec<f64>>,
    /// Number of force evaluations so far.
    pub force_evaluations: usize,
}

impl<'a, I: Interaction> ParticleStepper<'a, I> {
    /// A stepper for `sys` with `method`.
    pub fn new(sys: &'a System<I>, method: Method) -> Self {
        let n = 3 * sys.len();
        ParticleStepper {
            sys,
            method,
            rk4: (method == Method::Rk4).then(|| Rk4::new(sys)),
            x: vec![0.0; n],
            v: vec![0.0; n],
            a: vec![0.0; n],
            a_at: None,
            force_evaluations: 0,
        }
    }

    /// One step with the crate's full error (core's [`Stepper::step`] converts it).
    pub fn advance(&mut self, state: &mut State, h: f64) -> Result<()> {
        check_step(h)?;
        state.validate(3 * self.sys.len())?;
        let t = state.t;
        self.x.copy_from_slice(state.q.as_slice());
        self.v.copy_from_slice(state.v.as_slice());
        match self.method {
            Method::Euler => {
                self.sys.accelerations(t, &self.x, &self.v, &mut self.a)?;
                self.force_evaluations += 1;
                for k in 0..self.x.len() {
                    self.x[k] += h * self.v[k];
                    self.v[k] += h * self.a[k];
                }
            }
            Method::EulerCromer => {
                self.sys.accelerations(t, &self.x, &self.v, &mut self.a)?;
                self.force_evaluations += 1;
                for k in 0..self.x.len() {
                    self.v[k] += h * self.a[k];
                    self.x[k] += h * self.v[k];
                }
            }
            Method::Rk4 => {
                let rk = self.rk4.as_mut().expect("RK4 stepper built for Method::Rk4");
                rk.step(state, h)?;
                self.force_evaluations += 4;
                return Ok(());
            }
            Method::VelocityVerlet => self.verlet(t, h)?,
            Method::Yoshida4 => {
                let c = 2f64.powf(1.0 / 3.0);
                let w1 = 1.0 / (2.0 - c);
                let w0 = 1.0 - 2.0 * w1;
                self.verlet(t, w1 * h)?;
                self.verlet(t + w1 * h, w0 * h)?;
                self.verlet(t + (w1 + w0) * h, w1 * h)?;
            }
        }
        if self.x.iter().chain(&self.v).any(|c| !c.is_finite()) {
            return Err(noether_core::Error::NonFiniteState { step: 0, t }.into());
        }
        state.q.as_mut_slice().copy_from_slice(&self.x);
        state.v.as_mut_slice().copy_from_slice(&self.v);
        state.t = t + h;
        Ok(())
    }

    /// One kick-drift-kick step on the working copies `x`, `v`.
    fn verlet(&mut self, t: f64, h: f64) -> Result<()> {
        if self.sys.has_nonpotential_forces() {
            return Err(noether_core::Error::Unsupported(
                "velocity Verlet/Yoshida need position-only potential forces; use RK4 with drag",
            )
            .into());
        }
        if self.a_at.as_deref() != Some(&self.x[..]) {
            self.sys.potential_accelerations(t, &self.x, &mut self.a)?;
            self.force_evaluations += 1;
        }
        for k in 0..self.x.len() {
            self.v[k] += 0.5 * h * self.a[k];
            self.x[k] += h * self.v[k];
        }
        let res = self.sys.potential_accelerations(t + h, &self.x, &mut self.a);
        self.force_evaluations += 1;
        if let Err(e) = res {
            self.a_at = None;
            return Err(e);
        }
        for k in 0..self.x.len() {
            self.v[k] += 0.5 * h * self.a[k];
        }
        match &mut self.a_at {
            Some(p) => p.copy_from_slice(&self.x),
            None => self.a_at = Some(self.x.clone()),
        }
        Ok(())
    }
}

impl<I: Interaction> Stepper for ParticleStepper<'_, I> {
    fn step(&mut self, state: &mut State, h: f64) -> noether_core::Result<StepInfo> {
        self.advance(state, h)?;
        Ok(StepInfo::fixed(h))
    }
    fn dof(&self) -> usize {
        3 * self.sys.len()
    }
    fn order(&self) -> u32 {
        self.method.order()
    }
    fn name(&self) -> &'static str {
        self.method.name()
    }
}

impl<I: Interaction> System<I> {
    /// Advances `state` by one step `h` of `method` (state unchanged on error).
    pub fn step(&self, method: Method, state: &mut State, h: f64) -> Result<()> {
        ParticleStepper::new(self, method).advance(state, h)
    }

    /// Takes `n` steps of `method`; returns the final state.
    pub fn run(&self, method: Method, mut state: State, h: f64, n: usize) -> Result<State> {
        let mut st = ParticleStepper::new(self, method);
        for _ in 0..n {
            st.advance(&mut state, h)?;
        }
        Ok(state)
    }

    /// The evolver of the seed: the (infinite) sequence of states after each step of `method`.
    pub fn evolver(
        &self,
        method: Method,
        state: State,
        h: f64,
    ) -> Result<Trajectory<ParticleStepper<'_, I>>> {
        Trajectory::new(ParticleStepper::new(self, method), state, h).map_err(Error::from)
    }
}
