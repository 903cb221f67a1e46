//! What a run returns: the saved states as contiguous arrays, the observed quantities beside them, the
//! events that fired, why the run stopped, and the statistics shared by every method.

use crate::{DenseOutput, Error, Partner, Result, State, Velocities};
use nalgebra::DMatrixView;
use std::borrow::Cow;
use std::time::Duration;

/// Counters of a run, the same for every method.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct Stats {
    /// Accepted steps.
    pub steps: usize,
    /// Rejected trial steps (adaptive methods).
    pub rejected: usize,
    /// Evaluations of the vector field, or of the discrete Euler-Lagrange residual (including those the
    /// driver spends on interpolation).
    pub evaluations: usize,
    /// Newton iterations (implicit and variational methods).
    pub newton_iterations: usize,
    /// Newton solves that failed and were retried.
    pub newton_failures: usize,
    /// Events that fired.
    pub events: usize,
    /// Wall-clock time of the run.
    pub wall_time: Duration,
}

/// Why a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Stop {
    /// It reached the requested end time.
    EndTime,
    /// It took the requested number of steps.
    Steps,
    /// A terminal event fired (its index among the driver's events).
    Event(usize),
}

/// One firing of an event: which event, when, and the state there (interpolated inside the step).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(bound = ""))]
pub struct EventRecord<K = Velocities> {
    /// Index of the event among the driver's events (in the order they were added).
    pub event: usize,
    /// Time at which g crossed zero.
    pub t: f64,
    /// State at that time (before any reset the event applies).
    pub state: State<K>,
}

/// The result of a run: times and states in contiguous row-major arrays (row i holds q or the partner
/// at `t[i]`), observed quantities beside them, events, and statistics.
///
/// ```
/// use noether_core::prelude::*;
/// struct Oscillator;
/// impl Lagrangian for Oscillator {
///     fn dof(&self) -> usize { 1 }
///     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D { (v[0] * v[0] - q[0] * q[0]) * 0.5 }
/// }
/// let el = EulerLagrange::new(Oscillator);
/// let sol = Driver::new(Rk4::new(&el), State::new(0.0, [1.0], [0.0]))?
///     .step_size(1e-3)?
///     .save(Save::Times(vec![0.0, 0.5, 1.0]))?
///     .observe("energy", |s: &State| el.energy(s.t, s.q.as_slice(), s.v.as_slice()))
///     .run_until(1.0)?;
/// assert_eq!(sol.len(), 3);
/// assert!((sol.q(1)[0] - 0.5f64.cos()).abs() < 1e-12); // q = cos t
/// assert!((sol.observed("energy")?[2] - 0.5).abs() < 1e-12);
/// # Ok::<(), noether_core::Error>(())
/// ```
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(bound(serialize = "", deserialize = "K: Partner"), try_from = "Unchecked<K>")
)]
pub struct Solution<K = Velocities> {
    pub(crate) dof: usize,
    pub(crate) method: Cow<'static, str>,
    pub(crate) t: Vec<f64>,
    pub(crate) q: Vec<f64>,
    pub(crate) v: Vec<f64>,
    pub(crate) observer_names: Vec<String>,
    pub(crate) observed: Vec<f64>,
    pub(crate) event_names: Vec<String>,
    pub(crate) events: Vec<EventRecord<K>>,
    pub(crate) stop: Stop,
    pub(crate) stats: Stats,
    pub(crate) interpolation_order: Option<u32>,
    /// The dense output of each step, when kept (not serialized: a deserialized solution has none).
    #[cfg_attr(feature = "serde", serde(skip))]
    pub(crate) segments: Vec<DenseOutput<K>>,
    pub(crate) last: State<K>,
}

impl<K: Partner> Solution<K> {
    pub(crate) fn new(
        dof: usize,
        method: &'static str,
        observer_names: Vec<String>,
        event_names: Vec<String>,
        start: State<K>,
    ) -> Self {
        Solution {
            dof,
            method: method.into(),
            t: Vec::new(),
            q: Vec::new(),
            v: Vec::new(),
            observer_names,
            observed: Vec::new(),
            event_names,
            events: Vec::new(),
            stop: Stop::EndTime,
            stats: Stats::default(),
            interpolation_order: None,
            segments: Vec::new(),
            last: start,
        }
    }

    /// Appends a row (observed values given, one per observer column).
    pub(crate) fn push(&mut self, state: &State<K>, observed: &[f64]) {
        self.t.push(state.t);
        self.q.extend_from_slice(state.q.as_slice());
        self.v.extend_from_slice(state.v.as_slice());
        self.observed.extend_from_slice(observed);
    }

    /// Number of saved states (rows).
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// `true` when no state was saved.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// Number of coordinates.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// Name of the method that produced the run.
    pub fn method(&self) -> &str {
        &self.method
    }

    /// The saved times.
    pub fn times(&self) -> &[f64] {
        &self.t
    }

    /// The coordinates q at row `i`. Indexing: panics if `i >= len()`, as slice indexing does (the
    /// error contract's one stated exception); [`get`](Self::get) is the checked form.
    pub fn q(&self, i: usize) -> &[f64] {
        &self.q[i * self.dof..(i + 1) * self.dof]
    }

    /// The partner (q̇ or p, as `K` says) at row `i`. Indexing: panics if `i >= len()` (see
    /// [`q`](Self::q)).
    pub fn v(&self, i: usize) -> &[f64] {
        &self.v[i * self.dof..(i + 1) * self.dof]
    }

    /// The saved state at row `i`. Indexing: panics if `i >= len()` (see [`q`](Self::q)).
    pub fn state(&self, i: usize) -> State<K> {
        State::from_parts(self.t[i], self.q(i), self.v(i))
    }

    /// The saved state at row `i`, `None` if `i >= len()`.
    pub fn get(&self, i: usize) -> Option<State<K>> {
        (i < self.len()).then(|| self.state(i))
    }

    /// All saved coordinates as a matrix view, one column per saved time (dof × len).
    pub fn q_matrix(&self) -> DMatrixView<'_, f64> {
        DMatrixView::from_slice(&self.q, self.dof, self.len())
    }

    /// All saved partners (q̇ or p) as a matrix view, one column per saved time (dof × len).
    pub fn v_matrix(&self) -> DMatrixView<'_, f64> {
        DMatrixView::from_slice(&self.v, self.dof, self.len())
    }

    /// Component `j` of q over all saved times. Indexing: panics if `j >= dof()` (see [`q`](Self::q)).
    pub fn q_series(&self, j: usize) -> Vec<f64> {
        assert!(j < self.dof, "coordinate {j} of {}", self.dof);
        self.q.iter().skip(j).step_by(self.dof.max(1)).copied().collect()
    }

    /// Component `j` of the partner (q̇ or p) over all saved times. Indexing: panics if `j >= dof()`.
    pub fn v_series(&self, j: usize) -> Vec<f64> {
        assert!(j < self.dof, "coordinate {j} of {}", self.dof);
        self.v.iter().skip(j).step_by(self.dof.max(1)).copied().collect()
    }

    /// The state where the run ended (also when it was not saved).
    pub fn last(&self) -> &State<K> {
        &self.last
    }

    /// The names of the observed quantities, in column order.
    pub fn observer_names(&self) -> &[String] {
        &self.observer_names
    }

    /// The observed quantity `name` at every saved time (the column of the observer registered as
    /// `name` by [`Driver::observe`](crate::Driver::observe)).
    ///
    /// A name that no observer has (a typo) is [`Error::UnknownName`] listing the observers the run
    /// recorded.
    pub fn observed(&self, name: &str) -> Result<Vec<f64>> {
        let j = self.observer_index(name)?;
        let m = self.observer_names.len();
        Ok(self.observed.iter().skip(j).step_by(m).copied().collect())
    }

    /// The column of the observer `name`, or [`Error::UnknownName`].
    fn observer_index(&self, name: &str) -> Result<usize> {
        name_index("observer", &self.observer_names, name)
    }

    /// The observed values at row `i`, in column order. Indexing: panics if `i >= len()`.
    pub fn observed_row(&self, i: usize) -> &[f64] {
        let m = self.observer_names.len();
        &self.observed[i * m..(i + 1) * m]
    }

    /// Every event that fired, in time order.
    pub fn events(&self) -> &[EventRecord<K>] {
        &self.events
    }

    /// The firings of the event called `name` (as registered by
    /// [`Driver::event`](crate::Driver::event)), in time order; empty when it never fired.
    ///
    /// A name that no event has (a typo) is [`Error::UnknownName`] listing the events of the run.
    pub fn events_named(&self, name: &str) -> Result<impl Iterator<Item = &EventRecord<K>> + '_> {
        let idx = name_index("event", &self.event_names, name)?;
        Ok(self.events.iter().filter(move |e| e.event == idx))
    }

    /// The times at which the event called `name` fired, in order; empty when it never fired.
    ///
    /// A name that no event has (a typo) is [`Error::UnknownName`] listing the events of the run.
    pub fn event_times(&self, name: &str) -> Result<Vec<f64>> {
        Ok(self.events_named(name)?.map(|e| e.t).collect())
    }

    /// Why the run ended.
    pub fn stop(&self) -> Stop {
        self.stop
    }

    /// The run's statistics.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// Order of the interpolant used for output times and events (`None` when the run needed none):
    /// the method's dense output (4 for DOPRI5, 7 for DOP853), 3 for the cubic Hermite interpolant, 1
    /// for the linear one (see [`DenseOutput`]).
    pub fn interpolation_order(&self) -> Option<u32> {
        self.interpolation_order
    }

    /// The state at any time of the run from the kept continuous extensions (the driver must have been
    /// asked to keep them: [`Driver::keep_dense_output`](crate::Driver::keep_dense_output)).
    pub fn at(&self, t: f64) -> Result<State<K>> {
        let (Some(first), Some(last)) = (self.segments.first(), self.segments.last()) else {
            return Err(Error::Unsupported(
                "Solution::at needs the continuous extensions: run with Driver::keep_dense_output(true)",
            ));
        };
        if !(t >= first.t_start() && t <= last.t_end()) {
            return Err(Error::InvalidParameter {
                name: "t",
                value: t,
                reason: "outside the time span of the run",
            });
        }
        let i = self.segments.partition_point(|s| s.t_end() < t);
        self.segments[i.min(self.segments.len() - 1)].state_at(t)
    }

    /// Appends `other`, a later run of the same model (for runs continued after a stop).
    pub fn extend(&mut self, other: Solution<K>) -> Result<()> {
        if other.dof != self.dof || other.observer_names != self.observer_names {
            return Err(Error::Unsupported(
                "Solution::extend needs runs with the same dimension and observers",
            ));
        }
        let shift = if other.event_names == self.event_names {
            0
        } else {
            let offset = self.event_names.len();
            self.event_names.extend(other.event_names.iter().cloned());
            offset
        };
        self.t.extend(other.t);
        self.q.extend(other.q);
        self.v.extend(other.v);
        self.observed.extend(other.observed);
        self.events.extend(other.events.into_iter().map(|mut e| {
            e.event += shift;
            e
        }));
        self.segments.extend(other.segments);
        let s = &mut self.stats;
        let o = other.stats;
        s.steps += o.steps;
        s.rejected += o.rejected;
        s.evaluations += o.evaluations;
        s.newton_iterations += o.newton_iterations;
        s.newton_failures += o.newton_failures;
        s.events += o.events;
        s.wall_time += o.wall_time;
        self.stop = other.stop;
        self.last = other.last;
        self.interpolation_order = self.interpolation_order.or(other.interpolation_order);
        Ok(())
    }
}

/// A solution as read by serde, before its arrays are checked to agree.
#[cfg(feature = "serde")]
#[derive(serde::Deserialize)]
#[serde(bound = "")]
struct Unchecked<K> {
    dof: usize,
    method: Cow<'static, str>,
    t: Vec<f64>,
    q: Vec<f64>,
    v: Vec<f64>,
    observer_names: Vec<String>,
    observed: Vec<f64>,
    event_names: Vec<String>,
    events: Vec<EventRecord<K>>,
    stop: Stop,
    stats: Stats,
    interpolation_order: Option<u32>,
    last: State<K>,
}

/// A deserialized solution is accepted only when its arrays agree: one time per row, dof values of q
/// and of the partner per row, one value per observer per row, every value finite, events naming
/// events of the run, states of the run's dimension.
#[cfg(feature = "serde")]
impl<K: Partner> TryFrom<Unchecked<K>> for Solution<K> {
    type Error = Error;

    fn try_from(u: Unchecked<K>) -> Result<Self> {
        let bad = |reason: String| Err(Error::SavedRun { line: None, reason });
        let rows = u.t.len();
        if u.dof == 0 {
            return bad("a solution of 0 coordinates".into());
        }
        for (what, len, per_row) in [
            ("q", u.q.len(), u.dof),
            ("the partner", u.v.len(), u.dof),
            ("observed", u.observed.len(), u.observer_names.len()),
        ] {
            if len != rows * per_row {
                return bad(format!(
                    "{len} values of {what} for {rows} times of {per_row} values each"
                ));
            }
        }
        let all = u.t.iter().chain(&u.q).chain(&u.v).chain(&u.observed);
        if let Some(x) = all.copied().find(|x| !x.is_finite()) {
            return bad(format!("a value that is not finite ({x})"));
        }
        let events = u.events.iter().map(|e| e.event);
        let stopped = match u.stop {
            Stop::Event(i) => Some(i),
            _ => None,
        };
        if let Some(i) = events.chain(stopped).find(|&i| i >= u.event_names.len()) {
            return bad(format!("event {i} of a run with {} events", u.event_names.len()));
        }
        let states = u.events.iter().map(|e| &e.state).chain([&u.last]);
        if let Some(s) = states.into_iter().find(|s| s.validate(u.dof).is_err()) {
            return bad(format!("a state of {} coordinates or not finite", s.dof()));
        }
        Ok(Solution {
            dof: u.dof,
            method: u.method,
            t: u.t,
            q: u.q,
            v: u.v,
            observer_names: u.observer_names,
            observed: u.observed,
            event_names: u.event_names,
            events: u.events,
            stop: u.stop,
            stats: u.stats,
            interpolation_order: u.interpolation_order,
            segments: Vec::new(),
            last: u.last,
        })
    }
}

/// The position of `name` among the `names` of one `kind` ("observer", "event"), or
/// [`Error::UnknownName`] listing them.
fn name_index(kind: &'static str, names: &[String], name: &str) -> Result<usize> {
    names
        .iter()
        .position(|n| n == name)
        .ok_or_else(|| Error::UnknownName {
            kind,
            name: name.into(),
            known: names.to_vec(),
        })
}
