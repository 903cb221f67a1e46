//! Measuring things on a simulated trajectory: a driver loop with an observer, zero crossings located
//! between steps, periods, and the complete elliptic integral K used by the pendulum's closed form.

use super::plot::BoxError;
use noether_core::integrators::{Adaptive, DenseOutput, EmbeddedPair};
use noether_core::{Dynamics, State, Stepper, Trajectory};

/// Takes `n` steps of size `h` with `stepper` from `start`, calling `observe(step, state)` after each
/// (step = 1, …, n); returns the final state.
pub fn drive<S: Stepper>(
    stepper: S,
    start: State,
    h: f64,
    n: usize,
    mut observe: impl FnMut(usize, &State, &S) -> Result<(), BoxError>,
) -> Result<State, BoxError> {
    let mut run = Trajectory::new(stepper, start, h)?;
    for step in 1..=n {
        let s = run.next().ok_or("trajectory ended")??;
        observe(step, &s, run.stepper())?;
    }
    Ok(run.state().clone())
}

/// Steps the adaptive method `stepper` from `start` to `t_end` (its own initial step by Hairer's
/// `hinit`, then the controller's steps, the last one shortened to land on `t_end`), calling
/// `observe(state, dense)` with the state and the continuous extension of every accepted step; returns
/// the final state.
/// The extension is what events and uniform samples are taken from (see [`up_crossing`]).
pub fn drive_dense<S: Dynamics, M: EmbeddedPair>(
    mut stepper: Adaptive<S, M>,
    start: State,
    t_end: f64,
    mut observe: impl FnMut(&State, &DenseOutput) -> Result<(), BoxError>,
) -> Result<State, BoxError> {
    let mut state = start;
    let mut h = stepper.initial_step(&state)?;
    while t_end - state.t > 1e-14 * t_end.abs().max(1.0) {
        let h_try = h.min(t_end - state.t);
        let info = stepper.step(&mut state, h_try)?;
        observe(
            &state,
            stepper
                .dense_output()
                .ok_or("the adaptive method has no dense output")?,
        )?;
        h = info.h_next;
    }
    Ok(state)
}

/// The time in the step of `dense` at which `g` crosses zero upwards (g < 0 at the start of the step,
/// ≥ 0 at its end), located on the continuous extension ([`DenseOutput::locate`]); `None` otherwise.
pub fn up_crossing(dense: &DenseOutput, g: impl Fn(&State) -> f64) -> Option<f64> {
    let (a, b) = (
        g(&dense.state_at(dense.t_start())),
        g(&dense.state_at(dense.t_end())),
    );
    (a < 0.0 && b >= 0.0).then(|| dense.locate(&g)).flatten()
}

/// The largest value of a sampled signal in each window of `window` samples: the envelope of an
/// oscillating error, which is what a plot of "bounded" against "drifting" should show.
#[derive(Debug, Clone)]
pub struct Envelope {
    window: usize,
    max: f64,
    /// (x at the end of each window, largest value in it).
    pub points: Vec<(f64, f64)>,
}

impl Envelope {
    /// Windows of `window` samples (at least 1).
    pub fn new(window: usize) -> Self {
        Envelope {
            window: window.max(1),
            max: f64::NEG_INFINITY,
            points: Vec::new(),
        }
    }

    /// Adds sample number `i` (counting from 1) at abscissa `x` with value `y`.
    pub fn push(&mut self, i: usize, x: f64, y: f64) {
        self.max = self.max.max(y);
        if i.is_multiple_of(self.window) {
            self.points.push((x, self.max));
            self.max = f64::NEG_INFINITY;
        }
    }
}

/// Upward zero crossings of a signal x(t) sampled at the ends of each step together with its time
/// derivative ẋ(t).
///
/// On a step [t₀, t₁] with x(t₀) < 0 ≤ x(t₁) the crossing is the root of the cubic Hermite
/// interpolant of (x₀, ẋ₀, x₁, ẋ₁) (found by bisection). The interpolant's error is
/// h⁴ max|x⁗| / 384, so with the small steps of a fixed-step method it adds nothing visible to the
/// integrator's own error (linear interpolation would add O(h²)).
#[derive(Debug, Clone, Default)]
pub struct UpCrossings {
    prev: Option<(f64, f64, f64)>,
    /// Crossing times found so far.
    pub times: Vec<f64>,
}

impl UpCrossings {
    /// No sample yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds the sample (t, x, ẋ); records a crossing if x went from negative to non-negative.
    pub fn push(&mut self, t: f64, x: f64, dx: f64) {
        if let Some((t0, x0, d0)) = self.prev {
            if x0 < 0.0 && x >= 0.0 && t > t0 {
                self.times.push(hermite_root(t0, x0, d0, t, x, dx));
            }
        }
        self.prev = Some((t, x, dx));
    }

    /// The mean period (last − first crossing) / (count − 1); `None` with fewer than two crossings.
    pub fn period(&self) -> Option<f64> {
        match self.times.as_slice() {
            [first, .., last] => Some((last - first) / (self.times.len() - 1) as f64),
            _ => None,
        }
    }
}

/// The root in [t₀, t₁] of the cubic Hermite interpolant through (t₀, x₀, ẋ₀) and (t₁, x₁, ẋ₁), where
/// x₀ < 0 ≤ x₁.
pub fn hermite_root(t0: f64, x0: f64, d0: f64, t1: f64, x1: f64, d1: f64) -> f64 {
    let h = t1 - t0;
    let p = |s: f64| {
        let (s2, s3) = (s * s, s * s * s);
        (2.0 * s3 - 3.0 * s2 + 1.0) * x0
            + (s3 - 2.0 * s2 + s) * h * d0
            + (-2.0 * s3 + 3.0 * s2) * x1
            + (s3 - s2) * h * d1
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if p(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    t0 + 0.5 * (lo + hi) * h
}

/// The arithmetic-geometric mean of a, b > 0: iterate a ← (a+b)/2, b ← sqrt(ab) until they agree
/// (quadratic convergence: a handful of iterations reach machine precision).
pub fn agm(mut a: f64, mut b: f64) -> f64 {
    for _ in 0..64 {
        if (a - b).abs() <= 1e-16 * a.abs() {
            break;
        }
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    a
}

/// Complete elliptic integral of the first kind K(k) = ∫₀^{π/2} dφ / sqrt(1 − k² sin²φ) (modulus k,
/// 0 ≤ k < 1), by Gauss's formula K(k) = π / (2 AGM(1, sqrt(1 − k²))).
pub fn elliptic_k(k: f64) -> f64 {
    std::f64::consts::FRAC_PI_2 / agm(1.0, (1.0 - k * k).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn closed_form_elliptic_k() {
        // K(0) = π/2; K(1/√2) = Γ(1/4)² / (4 √π) with Γ(1/4) = 3.625609908221908311930685...
        assert!((elliptic_k(0.0) - PI / 2.0).abs() < 1e-15);
        let gamma_quarter = 3.625_609_908_221_908_f64;
        let expected = gamma_quarter * gamma_quarter / (4.0 * PI.sqrt());
        assert!((elliptic_k(0.5_f64.sqrt()) - expected).abs() < 1e-14 * expected);
        // Series K(k) = π/2 (1 + k²/4 + 9k⁴/64 + 25k⁶/256 + …) for small k.
        let k: f64 = 0.01;
        let series = PI / 2.0 * (1.0 + k * k / 4.0 + 9.0 * k.powi(4) / 64.0 + 25.0 * k.powi(6) / 256.0);
        assert!((elliptic_k(k) - series).abs() < 1e-15);
    }

    #[test]
    fn closed_form_crossings_of_a_sine() {
        // x = sin(2π t/T): upward crossings at t = n T exactly; sampled coarsely (20 points per period).
        let period = 1.7;
        let w = 2.0 * PI / period;
        let mut c = UpCrossings::new();
        for i in 0..=200 {
            let t = 0.013 + i as f64 * period / 20.0;
            c.push(t, (w * t).sin(), w * (w * t).cos());
        }
        assert_eq!(c.times.len(), 10);
        assert!((c.times[3] - 4.0 * period).abs() < 1e-4 * period);
        assert!((c.period().unwrap() - period).abs() < 1e-5 * period);
    }
}
