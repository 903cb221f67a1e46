//! Coordinate charts and their singularities: a stepper wrapper that stops a run with
//! [`Error::CoordinateSingularity`] when the state leaves the region where the coordinates are valid.
//!
//! Generalized coordinates are often a chart that breaks down somewhere: Euler angles and spherical
//! coordinates at the poles θ = 0, π, where the mass matrix ∂²L/∂q̇² loses rank (det M ∝ sin²θ) and
//! the equations of motion divide by sin θ. Near such a point the integrator does not fail loudly: it
//! loses accuracy like 1/sin²θ and returns garbage. [`ChartGuard`] checks every state (before and after
//! each step) and turns the approach into an error; the last accepted state stays in the chart.
//!
//! ```
//! use noether_core::prelude::*;
//! use noether_core::ChartGuard;
//!
//! // A particle sliding at unit speed toward x = 0, in a chart valid for x > 0.1.
//! struct Slide;
//! impl Lagrangian for Slide {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, _q: &[D], v: &[D]) -> D { v[0] * v[0] * 0.5 }
//! }
//! let guarded = ChartGuard::new(Rk4::new(EulerLagrange::new(Slide)), |s: &State| {
//!     (s.q[0] <= 0.1).then(|| format!("x = {} left the chart x > 0.1", s.q[0]))
//! });
//! let mut run = Driver::new(guarded, State::new(0.0, [1.0], [-1.0])).unwrap().step_size(0.01).unwrap();
//! let err = run.run_until(2.0).unwrap_err();
//! assert!(matches!(err, Error::CoordinateSingularity { .. }));
//! assert!(run.state().q[0] > 0.1 && (run.state().t - 0.9).abs() < 0.011);
//! ```

use crate::{DenseOutput, Error, Result, State, StepInfo, Stepper};

/// A chart test: `None` while the state is inside the chart, `Some(description)` when it has left it.
pub type ChartCheck<K> = Box<dyn Fn(&State<K>) -> Option<String> + Send + Sync>;

/// A stepper that refuses to step out of (or from outside) a coordinate chart.
pub struct ChartGuard<S: Stepper> {
    stepper: S,
    check: ChartCheck<S::Partner>,
    saved_q: Vec<f64>,
    saved_v: Vec<f64>,
}

impl<S: Stepper> ChartGuard<S> {
    /// Guards `stepper` with the chart test `check`.
    pub fn new(
        stepper: S,
        check: impl Fn(&State<S::Partner>) -> Option<String> + Send + Sync + 'static,
    ) -> Self {
        let n = stepper.dof();
        ChartGuard {
            stepper,
            check: Box::new(check),
            saved_q: vec![0.0; n],
            saved_v: vec![0.0; n],
        }
    }

    /// The usual chart of a polar angle (Euler angle θ, spherical θ): valid while |sin q\[index\]| ≥
    /// `min_sin`. Near θ = 0 or π the Euler-angle mass matrix has det ∝ sin²θ, so relative errors grow
    /// like 1/sin²θ: `min_sin` = 1e-2 keeps the amplification below 10⁴. The index must name a
    /// coordinate and `min_sin` lie in (0, 1).
    pub fn polar_angle(stepper: S, index: usize, name: &'static str, min_sin: f64) -> Result<Self> {
        if index >= stepper.dof() {
            return Err(Error::InvalidParameter {
                name: "polar angle index",
                value: index as f64,
                reason: "no such coordinate",
            });
        }
        if !(min_sin > 0.0 && min_sin < 1.0) {
            return Err(Error::InvalidParameter {
                name: "min_sin",
                value: min_sin,
                reason: "must lie in (0, 1)",
            });
        }
        Ok(Self::new(stepper, move |s: &State<S::Partner>| {
            let th = s.q[index];
            (th.sin().abs() < min_sin).then(|| {
                format!(
                    "{name} = {th:.6} is within asin({min_sin:e}) of a pole (θ = 0 or π), where the chart \
                     is singular (det ∂²L/∂q̇² ∝ sin²θ); use a chart regular there"
                )
            })
        }))
    }

    /// The wrapped stepper.
    pub fn inner(&self) -> &S {
        &self.stepper
    }
}

impl<S: Stepper> Stepper for ChartGuard<S> {
    type Partner = S::Partner;
    fn step(&mut self, state: &mut State<S::Partner>, h: f64) -> Result<StepInfo> {
        // The chart test may index the state: check its size first.
        state.validate(self.saved_q.len())?;
        if let Some(what) = (self.check)(state) {
            return Err(Error::CoordinateSingularity { what, t: state.t });
        }
        self.saved_q.copy_from_slice(state.q.as_slice());
        self.saved_v.copy_from_slice(state.v.as_slice());
        let t0 = state.t;
        let info = self.stepper.step(state, h)?;
        if let Some(what) = (self.check)(state) {
            let t = state.t;
            state.q.as_mut_slice().copy_from_slice(&self.saved_q);
            state.v.as_mut_slice().copy_from_slice(&self.saved_v);
            state.t = t0;
            return Err(Error::CoordinateSingularity { what, t });
        }
        Ok(info)
    }
    /// The wrapped method's own extension (the guard does not change the states it computes).
    fn dense_output(&self) -> Option<&DenseOutput<S::Partner>> {
        self.stepper.dense_output()
    }
    crate::__forward_stepper!(stepper);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prelude::*;

    /// Spherical pendulum L = ½ (θ̇² + sin²θ φ̇²) + cos θ (m = l = g = 1), in the chart (θ, φ).
    struct Spherical;
    impl Lagrangian for Spherical {
        fn dof(&self) -> usize {
            2
        }
        fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
            let s = q[0].sin();
            (v[0] * v[0] + s * s * v[1] * v[1]) * 0.5 + q[0].cos()
        }
    }

    #[test]
    fn bad_input_chart_singularity_is_an_error_and_state_stays_valid() {
        // Released from θ = 0.5 toward the bottom with no azimuthal momentum: it swings through θ = 0,
        // the pole of the chart, after t ≈ quarter period ≈ 1.6.
        let guarded = ChartGuard::polar_angle(Rk4::new(EulerLagrange::new(Spherical)), 0, "θ", 1e-2).unwrap();
        let mut traj = Driver::new(guarded, State::new(0.0, [0.5, 0.0], [0.0, 0.0]))
            .unwrap()
            .step_size(1e-3)
            .unwrap();
        let err = traj.run_until(10.0).unwrap_err();
        match &err {
            Error::CoordinateSingularity { what, t } => {
                assert!(what.contains("θ"), "{what}");
                assert!(*t > 1.0 && *t < 2.0, "t = {t}");
            }
            other => panic!("expected a coordinate singularity, got {other}"),
        }
        let s = traj.state();
        assert!(s.is_finite() && s.q[0].sin().abs() >= 1e-2);
        // A run started at the pole is refused before any step.
        let guarded = ChartGuard::polar_angle(Rk4::new(EulerLagrange::new(Spherical)), 0, "θ", 1e-2).unwrap();
        let mut traj = Driver::new(guarded, State::new(0.0, [0.0, 0.0], [0.1, 0.0]))
            .unwrap()
            .step_size(1e-3)
            .unwrap();
        assert!(matches!(
            traj.run_steps(1),
            Err(Error::CoordinateSingularity { t, .. }) if t == 0.0
        ));
    }

    /// Issue 15, case 9: a state of the wrong size and an angle index out of range were panics.
    #[test]
    fn bad_input_chart_guard_sizes_and_index() {
        let stepper = || Rk4::new(EulerLagrange::new(Spherical));
        assert!(matches!(
            ChartGuard::polar_angle(stepper(), 2, "θ", 1e-2),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(matches!(
            ChartGuard::polar_angle(stepper(), 0, "θ", f64::NAN),
            Err(Error::InvalidParameter { .. })
        ));
        let mut guarded = ChartGuard::polar_angle(stepper(), 1, "φ", 1e-2).unwrap();
        let mut short = State::new(0.0, [0.5], [0.0]);
        let before = short.clone();
        assert!(matches!(
            guarded.step(&mut short, 1e-3),
            Err(Error::Dimension {
                expected: 2,
                got: 1,
                ..
            })
        ));
        assert_eq!(short, before);
    }
}
