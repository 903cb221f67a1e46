//! Steppers: one step of a method, state → state. The [`Driver`](crate::Driver) runs any stepper.

use crate::{DenseOutput, Partner, Result, State};

/// What a step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub struct StepInfo {
    /// Step size actually taken.
    pub h: f64,
    /// Suggested size of the next step (equal to `h` for fixed-step methods).
    pub h_next: f64,
    /// Evaluations of the vector field (or of the discrete Euler-Lagrange residual) spent.
    pub evaluations: usize,
    /// Newton iterations spent (implicit methods), 0 otherwise.
    pub newton_iterations: usize,
    /// Newton solves that failed and were retried (with a fresh Jacobian), 0 otherwise.
    pub newton_failures: usize,
    /// Rejected trial steps (adaptive methods), 0 otherwise.
    pub rejected: usize,
}

impl StepInfo {
    /// Info of a fixed step of size `h`.
    pub fn fixed(h: f64) -> Self {
        StepInfo {
            h,
            h_next: h,
            ..Default::default()
        }
    }

    /// The same info with `n` evaluations of the vector field.
    pub fn with_evaluations(mut self, n: usize) -> Self {
        self.evaluations = n;
        self
    }

    /// The same info with `iterations` Newton iterations and `failures` failed Newton solves.
    pub fn with_newton(mut self, iterations: usize, failures: usize) -> Self {
        self.newton_iterations = iterations;
        self.newton_failures = failures;
        self
    }

    /// The same info with `rejected` rejected trial steps and the proposal `h_next`.
    pub fn with_control(mut self, rejected: usize, h_next: f64) -> Self {
        self.rejected = rejected;
        self.h_next = h_next;
        self
    }
}

/// A one-step method.
///
/// Contract: `step` advances `state` (time included) by one step of (proposed) size `h > 0`; on
/// error the state is left exactly as it was. A step that the time axis cannot resolve at `state.t`
/// (t + h not t + h to 1 %, [`check_time_resolution`](crate::error::check_time_resolution)) is
/// refused with [`Error::StepBelowTimeResolution`](crate::Error::StepBelowTimeResolution): every
/// stepper of noether checks it at its entry, so its direct callers (a [`Driver`](crate::Driver),
/// [`tangent::run_jacobian`](crate::tangent::run_jacobian), Lyapunov spectra, shooting) all get it.
/// A stepper written outside noether should call the same function. The other methods let the [`Driver`](crate::Driver)
/// choose step sizes and interpolate between steps; their defaults describe a fixed-step method
/// without a continuous extension or a vector field.
pub trait Stepper {
    /// What the second half of the state holds: [`Velocities`](crate::Velocities) or
    /// [`Momenta`](crate::Momenta).
    type Partner: Partner;

    /// Advances `state` by one step.
    fn step(&mut self, state: &mut State<Self::Partner>, h: f64) -> Result<StepInfo>;
    /// Number of degrees of freedom of the system stepped.
    fn dof(&self) -> usize;
    /// Nominal order of accuracy.
    fn order(&self) -> u32;
    /// Short name, e.g. "RK4".
    fn name(&self) -> &'static str;

    /// `true` when the method chooses its own step sizes: `h` is then a proposal, [`StepInfo::h`] the
    /// step taken and [`StepInfo::h_next`] the next proposal.
    fn is_adaptive(&self) -> bool {
        false
    }

    /// A first step size for an adaptive method at `state` (`None` for fixed-step methods).
    fn initial_step(&mut self, _state: &State<Self::Partner>) -> Result<Option<f64>> {
        Ok(None)
    }

    /// Asks the method to build (`true`) or skip (`false`) its continuous extension on the next steps;
    /// the driver asks for it only when it samples output times or locates events.
    fn request_dense_output(&mut self, _on: bool) {}

    /// The method's own continuous extension of the last step, when it has one.
    fn dense_output(&self) -> Option<&DenseOutput<Self::Partner>> {
        None
    }

    /// The vector field (q̇, v̇) at `state` into `dq`, `dv`, for the driver's cubic Hermite interpolant
    /// ([`DenseOutput::hermite`]); `None` for methods without a vector field (the driver then
    /// interpolates linearly).
    fn rates(&self, _state: &State<Self::Partner>, _dq: &mut [f64], _dv: &mut [f64]) -> Option<Result<()>> {
        None
    }
}

/// Forwards every method of [`Stepper`] to `$field` (a wrapper that changes only `step`).
#[macro_export]
#[doc(hidden)]
macro_rules! __forward_stepper {
    ($field:ident) => {
        fn dof(&self) -> usize {
            self.$field.dof()
        }
        fn order(&self) -> u32 {
            self.$field.order()
        }
        fn name(&self) -> &'static str {
            self.$field.name()
        }
        fn is_adaptive(&self) -> bool {
            self.$field.is_adaptive()
        }
        fn initial_step(&mut self, state: &$crate::State<Self::Partner>) -> $crate::Result<Option<f64>> {
            self.$field.initial_step(state)
        }
        fn request_dense_output(&mut self, on: bool) {
            self.$field.request_dense_output(on)
        }
        fn rates(
            &self,
            state: &$crate::State<Self::Partner>,
            dq: &mut [f64],
            dv: &mut [f64],
        ) -> Option<$crate::Result<()>> {
            self.$field.rates(state, dq, dv)
        }
    };
}

impl<S: Stepper + ?Sized> Stepper for Box<S> {
    type Partner = S::Partner;
    fn step(&mut self, state: &mut State<S::Partner>, h: f64) -> Result<StepInfo> {
        (**self).step(state, h)
    }
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn order(&self) -> u32 {
        (**self).order()
    }
    fn name(&self) -> &'static str {
        (**self).name()
    }
    fn is_adaptive(&self) -> bool {
        (**self).is_adaptive()
    }
    fn initial_step(&mut self, state: &State<S::Partner>) -> Result<Option<f64>> {
        (**self).initial_step(state)
    }
    fn request_dense_output(&mut self, on: bool) {
        (**self).request_dense_output(on)
    }
    fn dense_output(&self) -> Option<&DenseOutput<S::Partner>> {
        (**self).dense_output()
    }
    fn rates(&self, state: &State<S::Partner>, dq: &mut [f64], dv: &mut [f64]) -> Option<Result<()>> {
        (**self).rates(state, dq, dv)
    }
}
