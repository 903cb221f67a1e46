//! What the driver does inside a step, on its continuous extension: locating the events that fired
//! and applying the stop or reset of the first one, and sampling the output times.

use super::event::Action;
use super::{observe, Driver, EventRecord, RunState, Save, Solution};
use crate::{DenseOutput, Error, Result, Stepper};

impl<S: Stepper> Driver<'_, S> {
    /// Finds the events that fired in the step just taken (on its continuous extension `d`), records
    /// those up to the first stop or reset, and returns the (time, index) of that stop or reset; g at
    /// the end of the step becomes each event's starting value for the next.
    ///
    /// An event whose g vanishes at the start of the step, or that was just applied there (a reset, or
    /// the terminal stop a continued run starts from), takes its starting sign just after the start,
    /// at t₀ + δ with δ = max(1e-9 h, 64 ε |t₀|): the located root is only known to rounding, so its
    /// own g may have either sign, and a crossing later in the same step must still be seen (a ball
    /// that bounces and lands again within one long step). Only a crossing closer than δ to the point
    /// where the event was applied is not seen, so a reset cannot fire again at once.
    pub(super) fn record_events(
        &mut self,
        d: &DenseOutput<S::Partner>,
        sol: &mut Solution<S::Partner>,
        run: &mut RunState<S::Partner>,
    ) -> Result<Option<(f64, usize)>> {
        let (t0, t1) = (d.t_start(), self.state.t);
        let mut hits = Vec::new();
        for (i, ev) in self.events.iter_mut().enumerate() {
            let g1 = ev.value(&self.state)?;
            let (mut ta, mut ga) = (t0, std::mem::replace(&mut run.g_prev[i], g1));
            if run.just_applied[i] || ga == 0.0 {
                run.just_applied[i] = false;
                ta = t0 + (1e-9 * (t1 - t0)).max(64.0 * f64::EPSILON * t0.abs());
                if ta >= t1 {
                    continue; // a step too short to tell the side: the next one starts from g1
                }
                d.fill_state(ta, &mut run.scratch)?;
                ga = ev.value(&run.scratch)?;
            }
            if ev.direction.fires(ga, g1) {
                let scratch = &mut run.scratch;
                let g = &mut ev.g;
                let tc = crate::roots::bracketed_root(
                    |t| match d.fill_state(t, scratch) {
                        Ok(()) => g(scratch),
                        Err(_) => f64::NAN,
                    },
                    (ta, ga),
                    (t1, g1),
                )
                .map_err(|e| match e {
                    Error::NonFiniteResult { t, .. } => Error::NonFiniteResult {
                        what: "event function inside the step",
                        t,
                        component: None,
                    },
                    e => e,
                })?;
                hits.push((tc, i));
            }
        }
        hits.sort_by(|a, b| a.0.total_cmp(&b.0));
        for &(tc, i) in &hits {
            let state = if tc == t1 {
                self.state.clone()
            } else {
                d.state_at(tc)?
            };
            sol.events.push(EventRecord {
                event: i,
                t: tc,
                state,
            });
            sol.stats.events += 1;
            if !matches!(self.events[i].action, Action::Record) {
                return Ok(Some((tc, i)));
            }
        }
        Ok(None)
    }

    /// Saves the output times inside (t₀, t_out] of the step just taken, from its continuous extension
    /// (the computed state itself at its end). The list of times is read in place: sampling costs
    /// O(steps + times).
    pub(super) fn sample_times(
        &mut self,
        d: &DenseOutput<S::Partner>,
        t_out: f64,
        sol: &mut Solution<S::Partner>,
        run: &mut RunState<S::Partner>,
    ) -> Result<()> {
        let Save::Times(times) = &self.save else {
            return Ok(());
        };
        while let Some(&t) = times.get(run.next_time).filter(|&&t| t <= t_out) {
            if t == self.state.t {
                run.scratch.copy_from(&self.state);
            } else {
                d.fill_state(t, &mut run.scratch)?;
            }
            observe(&mut self.observers, &run.scratch, &mut run.obs_row)?;
            sol.push(&run.scratch, &run.obs_row);
            run.next_time += 1;
        }
        Ok(())
    }

    /// Applies the stop or reset of event `i`, whose record is the last of `sol`: the state becomes
    /// the one at the event, then (a reset) the changed one. Returns `true` when the run stops.
    pub(super) fn apply_event(
        &mut self,
        i: usize,
        sol: &mut Solution<S::Partner>,
        run: &mut RunState<S::Partner>,
    ) -> Result<bool> {
        let at = sol.events.last().expect("the event just recorded").state.clone();
        let save_steps = matches!(self.save, Save::Steps | Save::Every(_));
        if save_steps {
            observe(&mut self.observers, &at, &mut run.obs_row)?;
            sol.push(&at, &run.obs_row);
        }
        self.state = at;
        let n = self.state.dof();
        let reset = match &mut self.events[i].action {
            Action::Stop => {
                self.stopped_at = Some((i, self.state.t));
                return Ok(true);
            }
            Action::Reset(reset) => reset,
            Action::Record => unreachable!("a cut is a stop or a reset"),
        };
        let mut changed = self.state.clone();
        reset(&mut changed)?;
        changed.validate(n)?;
        check_reset_time(self.state.t, changed.t, &self.save, run.next_time)?;
        self.state = changed;
        if save_steps {
            observe(&mut self.observers, &self.state, &mut run.obs_row)?;
            sol.push(&self.state, &run.obs_row);
        }
        (run.origin, run.k) = (self.state.t, 0);
        run.start.f = None;
        run.g_prev = self.event_values()?;
        run.just_applied[i] = true;
        Ok(false)
    }

    /// g of every event at the current state.
    pub(super) fn event_values(&mut self) -> Result<Vec<f64>> {
        let state = &self.state;
        self.events.iter_mut().map(|e| e.value(state)).collect()
    }
}

/// A reset may move t forward (a dead time), not back; an output time inside the interval it skips
/// has no state, so it is an error rather than a row made up from outside any step.
fn check_reset_time(t_event: f64, t_new: f64, save: &Save, next_time: usize) -> Result<()> {
    if t_new < t_event {
        return Err(Error::InvalidParameter {
            name: "t after a reset",
            value: t_new,
            reason: "a reset may not move time backward",
        });
    }
    if let Save::Times(times) = save {
        if let Some(&t) = times.get(next_time).filter(|&&t| t < t_new) {
            return Err(Error::InvalidParameter {
                name: "output time",
                value: t,
                reason:
                    "lies in the interval a reset skipped (it moved t forward): the run has no state there",
            });
        }
    }
    Ok(())
}
