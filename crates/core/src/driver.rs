//! The driver: one loop that runs any [`Stepper`] — fixed-step or adaptive, explicit, implicit or
//! variational — to an end time or a terminal event, saves states at the times asked for, locates
//! events inside steps, records observed quantities, and counts what the run cost.
//!
//! ```
//! use noether_core::prelude::*;
//!
//! /// Pendulum, L = ½ θ̇² + g cos θ.
//! struct Pendulum;
//! impl Lagrangian for Pendulum {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D { v[0] * v[0] * 0.5 + q[0].cos() * 9.81 }
//! }
//! let el = EulerLagrange::new(Pendulum);
//! let sol = Driver::new(Dop853::new(&el).tolerances(1e-12, 1e-12)?, State::new(0.0, [0.1], [0.0]))?
//!     .save(Save::Times((0..=100).map(|i| 0.05 * i as f64).collect()))?
//!     .event(Event::new("θ = 0 upwards", |s: &State| s.q[0]).rising())
//!     .observe("energy", |s: &State| el.energy(s.t, s.q.as_slice(), s.v.as_slice()))
//!     .run_until(5.0)?;
//! assert_eq!(sol.len(), 101);
//! let up = sol.event_times("θ = 0 upwards")?;
//! let period = up[1] - up[0]; // ≈ 2π sqrt(l/g) (1 + θ₀²/16)
//! assert!((period - 2.0 * std::f64::consts::PI / 9.81f64.sqrt() * (1.0 + 0.01 / 16.0)).abs() < 1e-5);
//! # Ok::<(), noether_core::Error>(())
//! ```
//!
//! # How each output is obtained
//! - **Steps** ([`Save::Steps`], [`Save::Every`]): the states the method computed, exactly.
//! - **Output times** ([`Save::Times`]) and **events**: from the continuous extension of the step that
//!   contains them ([`DenseOutput`]): the method's own where it has one (DOPRI5: order 4, DOP853: order
//!   7), else the cubic Hermite interpolant through the two ends and the vector field there (order 3,
//!   error h⁴‖y⁗‖/384; it costs one evaluation of the vector field per step), else (a method with no
//!   vector field, such as the variational integrator of a user's discrete Lagrangian) the straight line
//!   (order 1, error h²‖y″‖/8). [`Solution::interpolation_order`] says which one a run used. A time that
//!   falls on the end of a step takes the computed state itself.
//! - **The end time** is reached exactly: a fixed-step method takes steps t₀ + kh (so times do not drift
//!   by accumulated rounding) and a last step shortened to land on t_end; an adaptive method stretches
//!   its step by up to 1% to avoid a sliver of a last step. At a time so large that t + h cannot be told
//!   apart from t to 1% of h, the run fails with [`Error::StepBelowTimeResolution`] instead of stalling.
//!
//! The driver validates its input once (state, step, output times, end time) and never changes the
//! state on error: after a failed step [`Driver::state`] is the last good state.

mod csv_io;
mod event;
mod in_step;
mod solution;

pub use event::{Direction, Event, Observation, Reset};
pub use solution::{EventRecord, Solution, Stats, Stop};

use crate::error::{check_finite, check_step};
use crate::{DenseOutput, Error, Result, State, StepInfo, Stepper};
use event::Observer;
use std::time::Instant;

/// The default step limit of a run ([`Driver::max_steps`]): 10¹⁰ steps (`usize::MAX` on targets
/// whose `usize` cannot hold it).
pub const DEFAULT_MAX_STEPS: usize = if usize::BITS >= 64 {
    10_000_000_000u64 as usize
} else {
    usize::MAX
};

/// Which states a run saves.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Save {
    /// The start and every accepted step (the default).
    Steps,
    /// The start, every k-th step and the end.
    Every(usize),
    /// Only the given times, sorted, within [start, end], from the continuous extension.
    Times(Vec<f64>),
    /// Only the end (the solution's rows hold one state).
    End,
}

/// Runs a [`Stepper`] (see the [module](self) docs). Also an iterator of states, one per step.
pub struct Driver<'a, S: Stepper> {
    stepper: S,
    state: State<S::Partner>,
    h: Option<f64>,
    h_proposal: Option<f64>,
    save: Save,
    keep_dense: bool,
    max_steps: usize,
    events: Vec<Event<'a, S::Partner>>,
    observers: Vec<Observer<'a, S::Partner>>,
    steps_taken: usize,
    failed: bool,
    /// The event and time of the terminal stop that ended the last run (see `record_events`).
    stopped_at: Option<(usize, f64)>,
    /// The solution of the last run up to its error.
    partial: Option<Solution<S::Partner>>,
}

/// What bounds a run.
#[derive(Debug, Clone, Copy)]
enum Target {
    Time(f64),
    Steps(usize),
}

/// The interpolation data of the step in progress: y = (q, v) at its start, the vector field there
/// when known, and whether the stepper has a vector field at all.
struct StepStart {
    y: Vec<f64>,
    f: Option<Vec<f64>>,
    has_rates: bool,
}

impl<'a, S: Stepper> Driver<'a, S> {
    /// A driver for `stepper` from `state` (checked against the stepper's dimension and for finite
    /// values). Fixed-step methods need a step size ([`step_size`](Self::step_size)); adaptive ones
    /// choose their own (Hairer's initial-step rule) unless given one.
    pub fn new(stepper: S, state: State<S::Partner>) -> Result<Self> {
        state.validate(stepper.dof())?;
        Ok(Driver {
            stepper,
            state,
            h: None,
            h_proposal: None,
            save: Save::Steps,
            keep_dense: false,
            max_steps: DEFAULT_MAX_STEPS,
            events: Vec::new(),
            observers: Vec::new(),
            steps_taken: 0,
            failed: false,
            stopped_at: None,
            partial: None,
        })
    }

    /// `Driver::new(stepper, state)?.step_size(h)`: the common start of a fixed-step run.
    pub fn with_step(stepper: S, state: State<S::Partner>, h: f64) -> Result<Self> {
        Self::new(stepper, state)?.step_size(h)
    }

    /// The step size (fixed-step methods), or the first step tried (adaptive methods): finite, > 0.
    pub fn step_size(mut self, h: f64) -> Result<Self> {
        check_step(h)?;
        self.h = Some(h);
        self.h_proposal = None;
        Ok(self)
    }

    /// Which states to save (default [`Save::Steps`]); output times must be finite and sorted.
    pub fn save(mut self, save: Save) -> Result<Self> {
        match &save {
            Save::Every(0) => {
                return Err(Error::InvalidParameter {
                    name: "Save::Every",
                    value: 0.0,
                    reason: "save every k-th step needs k ≥ 1",
                })
            }
            Save::Times(times) => {
                check_finite("output times", times)?;
                if let Some(w) = times.windows(2).find(|w| w[1] < w[0]) {
                    return Err(Error::InvalidParameter {
                        name: "output time",
                        value: w[1],
                        reason: "output times must be sorted",
                    });
                }
            }
            _ => {}
        }
        self.save = save;
        Ok(self)
    }

    /// Keeps the continuous extension of every step in the solution, for [`Solution::at`] (memory:
    /// a few state vectors per step).
    pub fn keep_dense_output(mut self, keep: bool) -> Self {
        self.keep_dense = keep;
        self
    }

    /// Fails with [`Error::StepLimit`] after `n` steps of one run (default [`DEFAULT_MAX_STEPS`],
    /// 10¹⁰ on 64-bit targets: far beyond any run that ends in hours, so that a run that could never
    /// finish is refused instead of hanging). A fixed-step run to an end time that needs more than `n`
    /// steps is refused before its first step.
    pub fn max_steps(mut self, n: usize) -> Self {
        self.max_steps = n;
        self
    }

    /// Adds an event (see [`Event`]).
    pub fn event(mut self, event: Event<'a, S::Partner>) -> Self {
        self.events.push(event);
        self
    }

    /// Records the quantity `name` = f(state) at every saved state; `f` returns an `f64` or a
    /// `Result<f64>` (an error or a non-finite value stops the run with an error).
    pub fn observe<O: Observation>(
        mut self,
        name: impl Into<String>,
        f: impl FnMut(&State<S::Partner>) -> O + 'a,
    ) -> Self {
        self.observers.push(Observer::scalar(name.into(), f));
        self
    }

    /// Records several quantities at once (momenta, a vector): `f` writes one value per name.
    pub fn observe_each(
        mut self,
        names: impl IntoIterator<Item = impl Into<String>>,
        f: impl FnMut(&State<S::Partner>, &mut [f64]) -> Result<()> + 'a,
    ) -> Self {
        self.observers.push(Observer {
            names: names.into_iter().map(Into::into).collect(),
            f: Box::new(f),
        });
        self
    }

    /// The current state (the last good one after an error).
    pub fn state(&self) -> &State<S::Partner> {
        &self.state
    }

    /// The current state, to change it between runs (a stop, a kick, a restart).
    pub fn state_mut(&mut self) -> &mut State<S::Partner> {
        &mut self.state
    }

    /// The stepper.
    pub fn stepper(&self) -> &S {
        &self.stepper
    }

    /// The stepper, to change its settings between runs.
    pub fn stepper_mut(&mut self) -> &mut S {
        &mut self.stepper
    }

    /// The stepper and the current state.
    pub fn into_parts(self) -> (S, State<S::Partner>) {
        (self.stepper, self.state)
    }

    /// Runs until `t_end` (reached exactly) or a terminal event.
    pub fn run_until(&mut self, t_end: f64) -> Result<Solution<S::Partner>> {
        check_finite("t_end", &[t_end])?;
        if t_end < self.state.t {
            return Err(Error::InvalidParameter {
                name: "t_end",
                value: t_end,
                reason: "precedes the state's time: runs go forward",
            });
        }
        if let Save::Times(times) = &self.save {
            if let Some(&t) = times.iter().find(|&&t| t < self.state.t || t > t_end) {
                return Err(Error::InvalidParameter {
                    name: "output time",
                    value: t,
                    reason: "output times must lie within [start, t_end]",
                });
            }
        }
        self.run(Target::Time(t_end))
    }

    /// Takes `n` steps (or stops earlier at a terminal event). Output times are not available here
    /// (the end time is not known in advance): save steps.
    pub fn run_steps(&mut self, n: usize) -> Result<Solution<S::Partner>> {
        if matches!(self.save, Save::Times(_)) {
            return Err(Error::Unsupported(
                "output times need an end time: use run_until, or save steps",
            ));
        }
        self.run(Target::Steps(n))
    }

    /// The fixed step size, or an error naming what is missing.
    fn fixed_h(&self) -> Result<f64> {
        self.h.ok_or(Error::InvalidParameter {
            name: "h",
            value: f64::NAN,
            reason: "a fixed-step method needs a step size: call Driver::step_size(h)",
        })
    }

    /// The next proposal of an adaptive method.
    fn adaptive_h(&mut self) -> Result<f64> {
        if let Some(h) = self.h_proposal.or(self.h) {
            return Ok(h);
        }
        let h = self.stepper.initial_step(&self.state)?;
        h.ok_or(Error::Unsupported("the adaptive method proposed no initial step"))
    }

    /// One step of size `h` (a proposal for adaptive methods) with the state unchanged on error; the
    /// step index goes into a non-finite-state error.
    fn advance(&mut self, h: f64) -> Result<StepInfo> {
        let t = self.state.t;
        // A step the grid or the controller shrank to nothing is below the resolution too.
        if h <= 0.0 {
            return Err(Error::StepBelowTimeResolution { t, h });
        }
        crate::error::check_time_resolution(t, h)?;
        let step = self.steps_taken;
        let res = self.stepper.step(&mut self.state, h).and_then(|info| {
            if self.state.is_finite() {
                Ok(info)
            } else {
                Err(Error::NonFiniteResult {
                    what: "state after the step",
                    t,
                    component: None,
                })
            }
        });
        match res {
            Ok(info) => {
                self.steps_taken += 1;
                if self.stepper.is_adaptive() && info.h_next.is_finite() && info.h_next > 0.0 {
                    self.h_proposal = Some(info.h_next);
                }
                Ok(info)
            }
            // The model says what failed and when; the driver adds which step of the run.
            Err(Error::NonFiniteResult { what, component, .. }) => Err(Error::NonFiniteState {
                what,
                step,
                t,
                component,
            }),
            Err(e) => Err(e),
        }
    }

    /// The continuous extension of the step just taken from `start` (at time `t0`): the stepper's own,
    /// else cubic Hermite from the vector field at both ends, else linear (see the module docs).
    fn extension(
        &self,
        t0: f64,
        start: &mut StepStart,
        stats: &mut Stats,
    ) -> Result<DenseOutput<S::Partner>> {
        let n = self.state.dof();
        if let Some(d) = self
            .stepper
            .dense_output()
            .filter(|d| d.t_start() == t0 && d.dof() == n)
        {
            start.f = None;
            return Ok(d.clone());
        }
        let (t1, y1) = (self.state.t, concat(&self.state));
        if start.has_rates && start.f.is_none() {
            let s0 = State::from_parts(t0, &start.y[..n], &start.y[n..]);
            start.f = self.rates_at(&s0, stats)?;
            start.has_rates = start.f.is_some();
        }
        if let (true, Some(f0)) = (start.has_rates, start.f.take()) {
            if let Some(f1) = self.rates_at(&self.state, stats)? {
                let d = DenseOutput::hermite(t0, t1 - t0, &start.y, &f0, &y1, &f1)?;
                start.f = Some(f1);
                return Ok(d);
            }
            start.has_rates = false;
        }
        DenseOutput::linear(t0, t1 - t0, &start.y, &y1)
    }

    /// The vector field (q̇, v̇) at `state`, `None` when the stepper has none.
    fn rates_at(&self, state: &State<S::Partner>, stats: &mut Stats) -> Result<Option<Vec<f64>>> {
        let n = state.dof();
        let mut f = vec![0.0; 2 * n];
        let (dq, dv) = f.split_at_mut(n);
        match self.stepper.rates(state, dq, dv) {
            None => Ok(None),
            Some(r) => {
                r?;
                stats.evaluations += 1;
                Ok(Some(f))
            }
        }
    }

    /// The solution of the last run up to the error that ended it (the rows saved, the events that
    /// fired, the statistics), taken out of the driver; `None` after a run that succeeded. With
    /// [`state`](Self::state), the last good state, it is everything the failed run computed.
    pub fn take_partial_solution(&mut self) -> Option<Solution<S::Partner>> {
        self.partial.take()
    }

    fn run(&mut self, target: Target) -> Result<Solution<S::Partner>> {
        let clock = Instant::now();
        let mut sol = Solution::new(
            self.state.dof(),
            self.stepper.name(),
            self.observers.iter().flat_map(|o| o.names.clone()).collect(),
            self.events.iter().map(|e| e.name.clone()).collect(),
            self.state.clone(),
        );
        let result = self.run_into(&mut sol, target);
        sol.last = self.state.clone();
        sol.stats.wall_time = clock.elapsed();
        match result {
            Ok(()) => {
                self.partial = None;
                Ok(sol)
            }
            Err(e) => {
                self.partial = Some(sol);
                Err(e)
            }
        }
    }

    /// The run proper: steps until the target or a terminal event, filling `sol` as it goes (so that
    /// after an error `sol` holds the run up to it).
    fn run_into(&mut self, sol: &mut Solution<S::Partner>, target: Target) -> Result<()> {
        let interpolate = matches!(self.save, Save::Times(_)) || !self.events.is_empty();
        self.stepper.request_dense_output(interpolate || self.keep_dense);
        let adaptive = self.stepper.is_adaptive();
        let h_fixed = if adaptive { 0.0 } else { self.fixed_h()? };
        if let (Target::Time(t_end), false) = (target, adaptive) {
            self.check_step_count(t_end, h_fixed)?;
        }
        let plan = Plan {
            target,
            adaptive,
            h_fixed,
            dense: interpolate || self.keep_dense,
        };
        let mut run = self.begin_run(sol)?;
        loop {
            let t0 = self.state.t;
            let Some((h_try, last)) = self.next_step_size(target, adaptive, h_fixed, &run)? else {
                if matches!(target, Target::Steps(_)) {
                    sol.stop = Stop::Steps;
                }
                break;
            };
            if run.stepped >= self.max_steps {
                return Err(Error::StepLimit {
                    steps: run.stepped,
                    t: t0,
                });
            }
            self.take_step(plan, (h_try, last), &mut run, &mut sol.stats)?;
            if let Some(i) = self.output_step(t0, plan, sol, &mut run)? {
                sol.stop = Stop::Event(i);
                break;
            }
        }
        if matches!(self.save, Save::End) {
            observe(&mut self.observers, &self.state, &mut run.obs_row)?;
            sol.push(&self.state, &run.obs_row);
        }
        Ok(())
    }

    /// The bookkeeping of a run from the current state, whose start is saved into `sol`; an event
    /// that stopped the previous run here counts as just applied.
    fn begin_run(&mut self, sol: &mut Solution<S::Partner>) -> Result<RunState<S::Partner>> {
        let n = self.state.dof();
        let mut run = RunState {
            obs_row: vec![0.0; sol.observer_names.len()],
            next_time: 0,
            stepped: 0,
            origin: self.state.t,
            k: 0,
            g_prev: self.event_values()?,
            // A terminal stop of the previous run is the located root: its sign may still be the one
            // before the crossing, so the sign is taken just after it (issue 29 item 2).
            just_applied: vec![false; self.events.len()],
            start: StepStart {
                y: vec![0.0; 2 * n],
                f: None,
                has_rates: true,
            },
            scratch: self.state.clone(),
        };
        if let Some((i, t)) = self.stopped_at.take() {
            if t == self.state.t && i < run.just_applied.len() {
                run.just_applied[i] = true;
            }
        }
        self.save_start(sol, &mut run)?;
        Ok(run)
    }

    /// One step of the run, trying h (`last`: it ends the run at t_end when taken whole): y at its
    /// start kept for the interpolation, the stepper's step, then t set exactly to t_end after the
    /// last step, and to the grid t_k = origin + k h after a fixed step (no drift from summing h).
    fn take_step(
        &mut self,
        plan: Plan,
        (h_try, last): (f64, bool),
        run: &mut RunState<S::Partner>,
        stats: &mut Stats,
    ) -> Result<()> {
        if plan.dense {
            let n = self.state.dof();
            run.start.y[..n].copy_from_slice(self.state.q.as_slice());
            run.start.y[n..].copy_from_slice(self.state.v.as_slice());
        }
        let info = self.advance(h_try)?;
        run.stepped += 1;
        run.k += 1;
        if last && info.h == h_try {
            if let Target::Time(t_end) = plan.target {
                self.state.t = t_end;
            }
        } else if !plan.adaptive {
            self.state.t = run.origin + run.k as f64 * plan.h_fixed;
        }
        add_step(stats, &info);
        Ok(())
    }

    /// The output of the step just taken from t₀: on its continuous extension (when the run needs
    /// one) the events are located and the output times sampled, up to the first stop or reset; the
    /// extension is kept when asked for; then the step is saved, or the event that cut it applied.
    /// Returns the index of a terminal event that ends the run.
    fn output_step(
        &mut self,
        t0: f64,
        plan: Plan,
        sol: &mut Solution<S::Partner>,
        run: &mut RunState<S::Partner>,
    ) -> Result<Option<usize>> {
        let dense = if plan.dense {
            let d = self.extension(t0, &mut run.start, &mut sol.stats)?;
            let order = sol.interpolation_order.map_or(d.order(), |o| o.min(d.order()));
            sol.interpolation_order = Some(order);
            Some(d)
        } else {
            None
        };
        let cut = match &dense {
            Some(d) => {
                let cut = self.record_events(d, sol, run)?;
                self.sample_times(d, cut.map_or(self.state.t, |c| c.0), sol, run)?;
                cut
            }
            None => None,
        };
        if let Some(d) = dense.filter(|_| self.keep_dense) {
            sol.segments.push(d);
        }
        match cut {
            None => {
                self.save_step(plan.target, sol, run)?;
                Ok(None)
            }
            Some((_, i)) => Ok(self.apply_event(i, sol, run)?.then_some(i)),
        }
    }

    /// Saves the state after a step that no event cut, when the [`Save`] mode asks for it (every
    /// step, every m-th and the last).
    fn save_step(
        &mut self,
        target: Target,
        sol: &mut Solution<S::Partner>,
        run: &mut RunState<S::Partner>,
    ) -> Result<()> {
        let save_step = match self.save {
            Save::Steps => true,
            Save::Every(every) => run.stepped.is_multiple_of(every) || self.is_done(target, run.stepped),
            _ => false,
        };
        if save_step {
            observe(&mut self.observers, &self.state, &mut run.obs_row)?;
            sol.push(&self.state, &run.obs_row);
        }
        Ok(())
    }

    /// Refuses a fixed-step run to `t_end` that needs more steps than the step limit allows (it could
    /// never finish: h = 5e-324 asks for 10³²³ steps), before taking any.
    fn check_step_count(&self, t_end: f64, h: f64) -> Result<()> {
        let needed = ((t_end - self.state.t) / h).ceil();
        if needed > self.max_steps as f64 {
            return Err(Error::InvalidParameter {
                name: "h",
                value: h,
                reason:
                    "(t_end − t)/h exceeds the step limit (Driver::max_steps): the run could never finish",
            });
        }
        Ok(())
    }

    /// Saves the start of the run: the initial state for saved steps, and every output time equal to
    /// the start time.
    fn save_start(&mut self, sol: &mut Solution<S::Partner>, run: &mut RunState<S::Partner>) -> Result<()> {
        if !matches!(self.save, Save::End | Save::Times(_)) {
            observe(&mut self.observers, &self.state, &mut run.obs_row)?;
            sol.push(&self.state, &run.obs_row);
        }
        if let Save::Times(times) = &self.save {
            while run.next_time < times.len() && times[run.next_time] == self.state.t {
                run.next_time += 1;
            }
            if run.next_time > 0 {
                observe(&mut self.observers, &self.state, &mut run.obs_row)?;
                for _ in 0..run.next_time {
                    sol.push(&self.state, &run.obs_row);
                }
            }
        }
        Ok(())
    }

    /// The size of the next step and whether it is the last, `None` when the target is reached.
    fn next_step_size(
        &mut self,
        target: Target,
        adaptive: bool,
        h_fixed: f64,
        run: &RunState<S::Partner>,
    ) -> Result<Option<(f64, bool)>> {
        let t0 = self.state.t;
        let grid = run.origin + (run.k + 1) as f64 * h_fixed;
        Ok(Some(match target {
            Target::Time(t_end) if t0 >= t_end => return Ok(None),
            Target::Steps(m) if run.stepped >= m => return Ok(None),
            Target::Time(t_end) if adaptive => {
                let h = self.adaptive_h()?;
                if t0 + 1.01 * h >= t_end {
                    (t_end - t0, true)
                } else {
                    (h, false)
                }
            }
            Target::Time(t_end) => {
                if grid >= t_end || t_end - grid <= 4.0 * f64::EPSILON * t_end.abs() {
                    (t_end - t0, true)
                } else {
                    (grid - t0, false)
                }
            }
            Target::Steps(_) if adaptive => (self.adaptive_h()?, false),
            Target::Steps(_) => (grid - t0, false),
        }))
    }

    /// `true` when the run will stop after this step (for [`Save::Every`] to save the end).
    fn is_done(&self, target: Target, stepped: usize) -> bool {
        match target {
            Target::Time(t_end) => self.state.t >= t_end,
            Target::Steps(m) => stepped >= m,
        }
    }
}

/// What a run does at every step: its target, whether the stepper is adaptive (else the size of its
/// fixed steps), and whether each step's continuous extension is needed.
#[derive(Debug, Clone, Copy)]
struct Plan {
    target: Target,
    adaptive: bool,
    h_fixed: f64,
    dense: bool,
}

/// The bookkeeping of one run between its steps.
struct RunState<K: crate::Partner> {
    /// The observed values of the row being saved.
    obs_row: Vec<f64>,
    /// Index of the next output time.
    next_time: usize,
    /// Steps of this run.
    stepped: usize,
    /// The fixed-step grid t_k = origin + k h (restarted after a reset).
    origin: f64,
    k: usize,
    /// g of each event at the start of the step.
    g_prev: Vec<f64>,
    /// Events applied at the start of the step (a reset, a terminal stop continued from).
    just_applied: Vec<bool>,
    start: StepStart,
    /// A state to interpolate into.
    scratch: State<K>,
}

/// Evaluates every observer at `state` into `row`.
fn observe<K: crate::Partner>(
    observers: &mut [Observer<'_, K>],
    state: &State<K>,
    row: &mut [f64],
) -> Result<()> {
    let mut j = 0;
    for o in observers {
        let m = o.names.len();
        o.eval(state, &mut row[j..j + m])?;
        j += m;
    }
    Ok(())
}

/// y = (q, v) of a state as one vector.
fn concat<K: crate::Partner>(state: &State<K>) -> Vec<f64> {
    state.q.iter().chain(state.v.iter()).copied().collect()
}

fn add_step(stats: &mut Stats, info: &StepInfo) {
    stats.steps += 1;
    stats.rejected += info.rejected;
    stats.evaluations += info.evaluations;
    stats.newton_iterations += info.newton_iterations;
    stats.newton_failures += info.newton_failures;
}

impl<S: Stepper> Iterator for Driver<'_, S> {
    type Item = Result<State<S::Partner>>;

    /// One step of the nominal size (the controller's proposal for adaptive methods); after the first
    /// error, that error and then `None`.
    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        let h = if self.stepper.is_adaptive() {
            self.adaptive_h()
        } else {
            self.fixed_h()
        };
        let r = h.and_then(|h| self.advance(h)).map(|_| self.state.clone());
        self.failed = r.is_err();
        Some(r)
    }
}
