//! Events (zero crossings of a function of the state, located inside steps) and observers (quantities
//! recorded beside the saved states).

use crate::{Error, Partner, Result, State};

/// An event function g(state), boxed.
type EventFunction<'a, K> = Box<dyn FnMut(&State<K>) -> f64 + 'a>;

/// Which zero crossings of g fire an event.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// g goes from negative to zero or positive.
    Rising,
    /// g goes from positive to zero or negative.
    Falling,
    /// Either.
    Either,
}

impl Direction {
    /// `true` when going from `g0` (at the start of a step) to `g1` (at its end) is a crossing in this
    /// direction. A step that starts exactly on g = 0 never fires (the crossing belongs to the step
    /// that ended there).
    pub fn fires(self, g0: f64, g1: f64) -> bool {
        let rising = g0 < 0.0 && g1 >= 0.0;
        let falling = g0 > 0.0 && g1 <= 0.0;
        match self {
            Direction::Rising => rising,
            Direction::Falling => falling,
            Direction::Either => rising || falling,
        }
    }
}

/// A state change applied when an event fires, after which the run continues.
pub type Reset<'a, K> = Box<dyn FnMut(&mut State<K>) -> Result<()> + 'a>;

pub(crate) enum Action<'a, K> {
    Record,
    Stop,
    Reset(Reset<'a, K>),
}

/// An event: the times at which a scalar function g(t, q, v) of the state crosses zero, located inside
/// the step on the continuous extension to rounding (by [`bracketed_root`](crate::roots::bracketed_root)).
///
/// By default an event is recorded and the run goes on; [`terminal`](Event::terminal) stops the run at
/// the event, and [`reset`](Event::reset) changes the state there and continues (an impact, a
/// switch). Crossings are detected from the sign of g at the ends of each step, so two crossings inside
/// one step cancel out; keep steps shorter than the time between crossings.
///
/// ```
/// use noether_core::prelude::*;
/// // A ball dropped from height 1 (g = 9.81) bouncing with restitution 0.9: y, ẏ as (q, q̇).
/// struct Fall;
/// impl Lagrangian for Fall {
///     fn dof(&self) -> usize { 1 }
///     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D { v[0] * v[0] * 0.5 - q[0] * 9.81 }
/// }
/// let bounce = Event::new("floor", |s: &State| s.q[0]).falling().reset(|s| s.v[0] *= -0.9);
/// let sol = Driver::new(Dop853::new(EulerLagrange::new(Fall)).tolerances(1e-12, 1e-12)?, State::new(0.0, [1.0], [0.0]))?
///     .event(bounce)
///     .run_until(1.0)?;
/// let first = sol.event_times("floor")?[0];
/// assert!((first - (2.0 / 9.81f64).sqrt()).abs() < 1e-12); // t = sqrt(2h/g)
/// # Ok::<(), noether_core::Error>(())
/// ```
pub struct Event<'a, K> {
    pub(crate) name: String,
    pub(crate) g: EventFunction<'a, K>,
    pub(crate) direction: Direction,
    pub(crate) action: Action<'a, K>,
}

impl<'a, K: Partner> Event<'a, K> {
    /// An event named `name` at the zeros of `g`, in either direction, recorded without stopping.
    pub fn new(name: impl Into<String>, g: impl FnMut(&State<K>) -> f64 + 'a) -> Self {
        Event {
            name: name.into(),
            g: Box::new(g),
            direction: Direction::Either,
            action: Action::Record,
        }
    }

    /// Only crossings from negative to positive.
    pub fn rising(mut self) -> Self {
        self.direction = Direction::Rising;
        self
    }

    /// Only crossings from positive to negative.
    pub fn falling(mut self) -> Self {
        self.direction = Direction::Falling;
        self
    }

    /// Crossings in the given direction.
    pub fn direction(mut self, direction: Direction) -> Self {
        self.direction = direction;
        self
    }

    /// The run stops at the event; the solution ends with the state there.
    pub fn terminal(mut self) -> Self {
        self.action = Action::Stop;
        self
    }

    /// At the event the state is changed by `reset` (which may change q, the partner, even t) and the
    /// run continues from the changed state. The solution saves the state before and after.
    pub fn reset(mut self, mut reset: impl FnMut(&mut State<K>) + 'a) -> Self {
        self.action = Action::Reset(Box::new(move |s| {
            reset(s);
            Ok(())
        }));
        self
    }

    /// As [`reset`](Self::reset), with a change that can fail (an impulsive jump solved by Newton, a
    /// projection): an error ends the run with that error, and the driver's state is the one at the
    /// event, before the reset began.
    pub fn try_reset(mut self, reset: impl FnMut(&mut State<K>) -> Result<()> + 'a) -> Self {
        self.action = Action::Reset(Box::new(reset));
        self
    }

    /// The event's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// g at `state`, an error when it is not finite.
    pub(crate) fn value(&mut self, state: &State<K>) -> Result<f64> {
        let g = (self.g)(state);
        if g.is_finite() {
            Ok(g)
        } else {
            Err(Error::NonFinite {
                what: "event function",
                index: 0,
            })
        }
    }
}

/// A value an observer may return: a plain `f64` or a `Result<f64>` (such as
/// [`EulerLagrange::energy`](crate::EulerLagrange::energy)).
pub trait Observation {
    /// The value, or the error that computing it met.
    fn into_result(self) -> Result<f64>;
}

impl Observation for f64 {
    fn into_result(self) -> Result<f64> {
        Ok(self)
    }
}

/// A fallible quantity. A closure that computes it with `?` may use the errors of the crates built on
/// core (noether-constraints' multipliers, noether-particles' energies): they convert into core's
/// [`Error::Model`](crate::Error::Model).
impl Observation for Result<f64> {
    fn into_result(self) -> Result<f64> {
        self
    }
}

/// Computes one or more named quantities from a state.
pub(crate) type ObserveFn<'a, K> = Box<dyn FnMut(&State<K>, &mut [f64]) -> Result<()> + 'a>;

/// Observed quantities with their column names.
pub(crate) struct Observer<'a, K> {
    pub(crate) names: Vec<String>,
    pub(crate) f: ObserveFn<'a, K>,
}

impl<'a, K: Partner> Observer<'a, K> {
    pub(crate) fn scalar<O: Observation>(name: String, mut f: impl FnMut(&State<K>) -> O + 'a) -> Self {
        Observer {
            names: vec![name],
            f: Box::new(move |s, out| {
                out[0] = f(s).into_result()?;
                Ok(())
            }),
        }
    }

    /// Evaluates into `out` (its columns), checking every value is finite.
    pub(crate) fn eval(&mut self, state: &State<K>, out: &mut [f64]) -> Result<()> {
        (self.f)(state, out)?;
        match out.iter().position(|x| !x.is_finite()) {
            Some(index) => Err(Error::NonFinite {
                what: "observed quantity",
                index,
            }),
            None => Ok(()),
        }
    }
}
