//! The one-step map of a variational integrator in position-momentum form, (q_k, p_k) ↦ (q_{k+1}, p_{k+1}):
//! every integrator of this crate is a core [`Stepper`](noether_core::Stepper) on a `State<Momenta>`
//! (q, p) and, since the map is defined for steps of either sign (a symmetric composition takes
//! backward substeps), a [`SignedStepper`](noether_core::integrators::SignedStepper) — core's
//! [`Composition`](noether_core::integrators::Composition) composes it with
//! [`Weights`](noether_core::integrators::Weights). This module holds what the integrators share: the
//! signed step around an integrator's update, the increment predictor and the one-correction rule.

use noether_core::error::check_phase_point;
use noether_core::integrators::composition::check_signed_step;
use noether_core::{Error, Momenta, Result, State, StepInfo};

/// Checks the arguments of a map (q₀, p₀) at t over the signed step h given as slices: lengths,
/// finiteness, and a finite non-zero `h`.
pub(crate) fn check_flow_args(dof: usize, t: f64, h: f64, q: &[f64], p: &[f64]) -> Result<()> {
    if !h.is_finite() || h == 0.0 {
        return Err(Error::InvalidStep { h });
    }
    check_phase_point(dof, t, q, p, "p")
}

/// [`SignedStepper::step_signed`](noether_core::integrators::SignedStepper::step_signed) around an
/// integrator's update `advance(t, q, p)` (which leaves q and p as they were on error and returns its
/// Newton iterations): the state and `h` checked, then t ← t + h. One residual evaluation per Newton
/// iteration and one to check the start.
pub(crate) fn signed_step(
    dof: usize,
    state: &mut State<Momenta>,
    h: f64,
    advance: impl FnOnce(f64, &mut [f64], &mut [f64]) -> Result<usize>,
) -> Result<StepInfo> {
    check_signed_step(dof, state, h)?;
    let t = state.t;
    let iterations = advance(t, state.q.as_mut_slice(), state.v.as_mut_slice())?;
    state.t = t + h;
    Ok(StepInfo::fixed(h)
        .with_newton(iterations, 0)
        .with_evaluations(iterations + 1))
}

/// Remembers the last step (end point and increment) to predict the next increment by linear
/// extrapolation, q_{k+1} − q_k ≈ (h/h_prev)(q_k − q_{k−1}), when the next step starts where the last
/// ended.
#[derive(Debug, Clone, Default)]
pub(crate) struct Predictor {
    end: Vec<f64>,
    dq: Vec<f64>,
    h: f64,
}

impl Predictor {
    /// Writes the predicted increment q_{k+1} − q_k for a step from `q` of size `h` into `out` (zero
    /// when the step does not start where the last one ended).
    pub(crate) fn guess_increment(&self, q: &[f64], h: f64, out: &mut [f64]) {
        if self.h != 0.0 && self.end.as_slice() == q {
            let s = h / self.h;
            out.iter_mut().zip(&self.dq).for_each(|(o, d)| *o = s * d);
        } else {
            out.iter_mut().for_each(|o| *o = 0.0);
        }
    }

    /// Records a step from `q0` with increment `dq` ending at `q1`.
    pub(crate) fn record_increment(&mut self, q1: &[f64], dq: &[f64], h: f64) {
        self.end.clear();
        self.end.extend_from_slice(q1);
        self.dq.clear();
        self.dq.extend_from_slice(dq);
        self.h = h;
    }
}

/// One simplified-Newton correction x ← x − J⁻¹F(x) after a Newton solve that took no iteration (the
/// predictor already met the tolerance), with the last Jacobian factor (from the previous step) when
/// `factored`, else a fresh one.
///
/// Why: a translation-invariant system's residual component along ξ = (1,…,1) is linear in q_{k+1}
/// and ξᵀJ = ξᵀM/h for *any* Jacobian of the form M/h + (h/4)∇²V, so one correction removes it
/// exactly and the total momentum stays at rounding level even with a loose tolerance (the paper's
/// 1e-8). Ends with a residual evaluation at the corrected point, so caches of the system (∇V) refer to it.
pub(crate) fn correct_once<S: noether_core::NewtonSystem + ?Sized>(
    sys: &mut S,
    x: &mut [f64],
    factored: bool,
) -> Result<()> {
    if !factored {
        sys.factor_jacobian(x)?;
    }
    let mut r = vec![0.0; x.len()];
    sys.residual(x, &mut r)?;
    sys.solve(&mut r)?;
    x.iter_mut().zip(&r).for_each(|(xi, ri)| *xi -= ri);
    sys.residual(x, &mut r)
}
