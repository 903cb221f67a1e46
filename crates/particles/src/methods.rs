//! The seed's state updates on a particle system and its evolver: a run-time name for each of core's
//! steppers on a [`System`].
//!
//! [`Method`] is a thin alias over core's types, not a method of its own: each variant builds one core
//! stepper on the system (borrowed), with a = F(t, x, v)/m from the forces term by term ([`System`]'s
//! [`Dynamics`](noether_core::Dynamics)):
//!
//! | variant | core stepper | update |
//! |---|---|---|
//! | [`Method::Euler`] | [`Euler`] | x' = x + h v, v' = v + h a(x, v) |
//! | [`Method::EulerCromer`] | [`EulerCromer`] | v' = v + h a(x, v), x' = x + h v' |
//! | [`Method::Rk4`] | [`Rk4`] | the classical Runge-Kutta method on (x, v) |
//! | [`Method::VelocityVerlet`] | [`Composition::stormer_verlet`] | v½ = v + (h/2) a(x), x' = x + h v½, v' = v½ + (h/2) a(x') |
//! | [`Method::Yoshida4`] | [`Composition::yoshida4`] | the triple jump of velocity Verlet, order 4 |
//!
//! It stays (rather than asking for the types) because it is a value: a test or a program loops over
//! methods, or reads one from its input, and gets one stepper type ([`ParticleStepper`]) for all of
//! them, without boxing. To use any other core method, pass the system (`&System`, a core
//! [`Dynamics`](noether_core::Dynamics) and [`SplitDynamics`]) to it directly:
//! `Composition::kahan_li8(&sys)`, `Dop853::new(&sys)`.
//!
//! The symplectic methods use the system's [`SplitDynamics`] (kicks from the potential forces only):
//! they refuse systems with non-potential forces or time-dependent potentials. Every method leaves the
//! state unchanged when a step fails.

use crate::error::{Error, Result};
use crate::interaction::Interaction;
use crate::system::System;
use noether_core::integrators::{Composition, Euler, EulerCromer, Rk4, SplitDynamics, StormerVerlet};
use noether_core::{Driver, State, StepInfo, Stepper, Velocities};

/// A state-update method for particle systems: a run-time name for a core stepper (see the
/// [module](self) table).
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
}

enum Inner<'a, I> {
    Euler(Euler<&'a System<I>>),
    EulerCromer(EulerCromer<&'a System<I>>),
    Rk4(Rk4<&'a System<I>>),
    Split(Composition<StormerVerlet<&'a System<I>>>),
}

/// A [`Stepper`] for a particle system with one of the [`Method`]s (run it with core's [`Driver`]).
pub struct ParticleStepper<'a, I> {
    sys: &'a System<I>,
    inner: Inner<'a, I>,
}

impl<'a, I: Interaction> ParticleStepper<'a, I> {
    /// A stepper for `sys` with `method`.
    pub fn new(sys: &'a System<I>, method: Method) -> Self {
        let inner = match method {
            Method::Euler => Inner::Euler(Euler::new(sys)),
            Method::EulerCromer => Inner::EulerCromer(EulerCromer::new(sys)),
            Method::Rk4 => Inner::Rk4(Rk4::new(sys)),
            Method::VelocityVerlet => Inner::Split(Composition::stormer_verlet(sys)),
            Method::Yoshida4 => Inner::Split(Composition::yoshida4(sys)),
        };
        ParticleStepper { sys, inner }
    }

    fn stepper(&mut self) -> &mut dyn Stepper<Partner = Velocities> {
        match &mut self.inner {
            Inner::Euler(s) => s,
            Inner::EulerCromer(s) => s,
            Inner::Rk4(s) => s,
            Inner::Split(s) => s,
        }
    }

    fn stepper_ref(&self) -> &dyn Stepper<Partner = Velocities> {
        match &self.inner {
            Inner::Euler(s) => s,
            Inner::EulerCromer(s) => s,
            Inner::Rk4(s) => s,
            Inner::Split(s) => s,
        }
    }
}

impl<I: Interaction> Stepper for ParticleStepper<'_, I> {
    type Partner = Velocities;
    fn step(&mut self, state: &mut State, h: f64) -> noether_core::Result<StepInfo> {
        if matches!(self.inner, Inner::Split(_)) {
            self.sys.check_split()?;
        }
        self.stepper().step(state, h)
    }
    fn dof(&self) -> usize {
        3 * self.sys.len()
    }
    fn order(&self) -> u32 {
        self.stepper_ref().order()
    }
    fn name(&self) -> &'static str {
        self.stepper_ref().name()
    }
    fn rates(&self, state: &State, dq: &mut [f64], dv: &mut [f64]) -> Option<noether_core::Result<()>> {
        self.stepper_ref().rates(state, dq, dv)
    }
}

impl<I: Interaction> System<I> {
    /// Advances `state` by one step `h` of `method` (state unchanged on error).
    pub fn step(&self, method: Method, state: &mut State, h: f64) -> Result<()> {
        ParticleStepper::new(self, method).step(state, h)?;
        Ok(())
    }

    /// Takes `n` steps of `method`; returns the final state.
    pub fn run(&self, method: Method, mut state: State, h: f64, n: usize) -> Result<State> {
        let mut st = ParticleStepper::new(self, method);
        for _ in 0..n {
            st.step(&mut state, h)?;
        }
        Ok(state)
    }

    /// The evolver of the seed: the (infinite) sequence of states after each step of `method`.
    pub fn evolver(
        &self,
        method: Method,
        state: State,
        h: f64,
    ) -> Result<Driver<'_, ParticleStepper<'_, I>>> {
        Driver::with_step(ParticleStepper::new(self, method), state, h).map_err(Error::from)
    }

    /// Symplectic (split) methods need potential forces that depend on positions only.
    fn check_split(&self) -> noether_core::Result<()> {
        if self.has_nonpotential_forces() {
            return Err(noether_core::Error::Unsupported(
                "symplectic split methods need potential forces only; use RK4 with drag or given forces",
            ));
        }
        if !self.interactions().autonomous() {
            return Err(noether_core::Error::Unsupported(
                "symplectic split methods need time-independent potentials",
            ));
        }
        Ok(())
    }
}

/// q̇ = v (drift), v̇ = −M⁻¹∇V(x) (kick, term by term): core's Störmer-Verlet and compositions apply.
impl<I: Interaction> SplitDynamics for System<I> {
    fn drift_rate(&self, v: &[f64], dq: &mut [f64]) -> noether_core::Result<()> {
        dq.copy_from_slice(v);
        Ok(())
    }
    fn kick_rate(&self, q: &[f64], dv: &mut [f64]) -> noether_core::Result<()> {
        self.check_split()?;
        self.potential_accelerations(0.0, q, dv)?;
        Ok(())
    }
    fn drift_is_identity(&self) -> bool {
        true
    }
}
