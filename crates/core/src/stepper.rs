//! Steppers (one step: state → state) and the driver that turns a stepper into an iterator of states.

use crate::error::check_step;
use crate::{Error, Result, State};

/// What a step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepInfo {
    /// Step size actually taken.
    pub h: f64,
    /// Suggested size of the next step (equal to `h` for fixed-step methods).
    pub h_next: f64,
    /// Newton iterations spent (implicit methods), 0 otherwise.
    pub newton_iterations: usize,
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
}

/// A one-step method.
///
/// Contract: `step` advances `state` (time included) by one step of (proposed) size `h`; on error the
/// state is left exactly as it was.
pub trait Stepper {
    /// Advances `state` by one step.
    fn step(&mut self, state: &mut State, h: f64) -> Result<StepInfo>;
    /// Number of degrees of freedom of the system stepped.
    fn dof(&self) -> usize;
    /// Nominal order of accuracy.
    fn order(&self) -> u32;
    /// Short name, e.g. "RK4".
    fn name(&self) -> &'static str;
}

impl<S: Stepper + ?Sized> Stepper for Box<S> {
    fn step(&mut self, state: &mut State, h: f64) -> Result<StepInfo> {
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
}

/// The driver: an iterator of states `stepper` produces from `state` with step `h`.
///
/// Yields `Ok(state)` after each step (the initial state is not repeated); after the first error it
/// yields that error (with the step index and time filled in) and then ends.
pub struct Trajectory<S> {
    stepper: S,
    state: State,
    h: f64,
    step: usize,
    failed: bool,
}

impl<S: Stepper> Trajectory<S> {
    /// Validates the initial state and step, then returns the iterator.
    pub fn new(stepper: S, state: State, h: f64) -> Result<Self> {
        check_step(h)?;
        state.validate(stepper.dof())?;
        Ok(Trajectory {
            stepper,
            state,
            h,
            step: 0,
            failed: false,
        })
    }

    /// The last state reached.
    pub fn state(&self) -> &State {
        &self.state
    }

    /// The stepper.
    pub fn stepper(&self) -> &S {
        &self.stepper
    }

    /// Steps until `t >= t_end` (the last step is shortened to land on `t_end`); returns the final state.
    pub fn run_until(&mut self, t_end: f64) -> Result<State> {
        while self.state.t < t_end {
            let remaining = t_end - self.state.t;
            let h = self.h.min(remaining);
            if remaining <= 1e-14 * t_end.abs().max(1.0) {
                break;
            }
            let nominal = self.h;
            let info = self.advance(h)?;
            // A final step shortened to land on t_end must not become the nominal step of a fixed-step
            // method (which echoes h as h_next): later steps would crawl.
            if h < nominal && info.h_next == info.h {
                self.h = nominal;
            }
        }
        Ok(self.state.clone())
    }

    /// Takes `n` steps; returns the final state.
    pub fn run_steps(&mut self, n: usize) -> Result<State> {
        for _ in 0..n {
            self.advance(self.h)?;
        }
        Ok(self.state.clone())
    }

    fn advance(&mut self, h: f64) -> Result<StepInfo> {
        if self.failed {
            return Err(Error::Unsupported("trajectory already failed"));
        }
        let t = self.state.t;
        let res = self.stepper.step(&mut self.state, h).and_then(|info| {
            if self.state.is_finite() {
                Ok(info)
            } else {
                Err(Error::NonFiniteState { step: self.step, t })
            }
        });
        match res {
            Ok(info) => {
                self.step += 1;
                self.h = if info.h_next.is_finite() && info.h_next > 0.0 {
                    info.h_next
                } else {
                    self.h
                };
                Ok(info)
            }
            Err(e) => {
                self.failed = true;
                Err(match e {
                    Error::NonFiniteState { .. } => Error::NonFiniteState { step: self.step, t },
                    other => other,
                })
            }
        }
    }
}

impl<S: Stepper> Iterator for Trajectory<S> {
    type Item = Result<State>;
    fn next(&mut self) -> Option<Result<State>> {
        if self.failed {
            return None;
        }
        Some(self.advance(self.h).map(|_| self.state.clone()))
    }
}

#[cfg(test)]
mod tests {
    use crate::prelude::*;

    struct Free;
    impl Lagrangian for Free {
        fn dof(&self) -> usize {
            1
        }
        fn lagrangian<D: Scalar>(&self, _t: D, _q: &[D], v: &[D]) -> D {
            v[0] * v[0] * 0.5
        }
    }

    #[test]
    fn regress_run_until_keeps_the_nominal_step() {
        let mut traj = Trajectory::new(
            Rk4::new(EulerLagrange::new(Free)),
            State::new(0.0, [0.0], [1.0]),
            0.1,
        )
        .unwrap();
        // 0.25 needs a shortened last step of 0.05; the next step must again be 0.1.
        let s = traj.run_until(0.25).unwrap();
        assert!((s.t - 0.25).abs() < 1e-15);
        let s = traj.next().unwrap().unwrap();
        assert!((s.t - 0.35).abs() < 1e-14, "t = {}", s.t);
    }
}
