//! The one-step map of a variational integrator in position-momentum form, (q_k, p_k) ↦ (q_{k+1}, p_{k+1}),
//! as a [`DiscreteFlow`]; every flow is also a core [`Stepper`](noether_core::Stepper) on a
//! `State<Momenta>` (q, p).

use noether_core::error::{check_phase_point, check_step, check_time_resolution};
use noether_core::{Error, Momenta, Result, State, StepInfo};

/// A discrete flow (q, p) ↦ (q', p') over a step h, the discrete Hamiltonian map of a discrete Lagrangian.
///
/// Unlike [`Stepper::step`](noether_core::Stepper::step), `h` may be negative (symmetric compositions
/// take backward substeps); it must be finite and non-zero.
pub trait DiscreteFlow {
    /// Number of coordinates.
    fn dof(&self) -> usize;
    /// Nominal order.
    fn order(&self) -> u32;
    /// Short name.
    fn name(&self) -> &'static str;
    /// Advances `(q, p)` from time `t` by the signed step `h`; on error `q` and `p` are left exactly as
    /// they were. Returns the Newton iterations spent.
    fn flow(&mut self, t: f64, h: f64, q: &mut [f64], p: &mut [f64]) -> Result<usize>;

    /// Hamilton's vector field (q̇, ṗ) of the continuous system the flow discretizes, when it has one
    /// (for the driver's Hermite interpolant between steps); `None` otherwise.
    fn rates(&self, _t: f64, _q: &[f64], _p: &[f64], _dq: &mut [f64], _dp: &mut [f64]) -> Option<Result<()>> {
        None
    }
}

impl<F: DiscreteFlow + ?Sized> DiscreteFlow for &mut F {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn order(&self) -> u32 {
        (**self).order()
    }
    fn name(&self) -> &'static str {
        (**self).name()
    }
    fn flow(&mut self, t: f64, h: f64, q: &mut [f64], p: &mut [f64]) -> Result<usize> {
        (**self).flow(t, h, q, p)
    }
    fn rates(&self, t: f64, q: &[f64], p: &[f64], dq: &mut [f64], dp: &mut [f64]) -> Option<Result<()>> {
        (**self).rates(t, q, p, dq, dp)
    }
}

/// Checks the arguments of a flow call: lengths, finiteness, and a finite non-zero signed step.
pub(crate) fn check_flow_args(dof: usize, t: f64, h: f64, q: &[f64], p: &[f64]) -> Result<()> {
    if !h.is_finite() || h == 0.0 {
        return Err(Error::InvalidStep { h });
    }
    check_phase_point(dof, t, q, p, "p")
}

/// One [`Stepper`](noether_core::Stepper) step of a flow: a positive step, the state left untouched on error.
pub(crate) fn step_state<F: DiscreteFlow + ?Sized>(
    flow: &mut F,
    state: &mut State<Momenta>,
    h: f64,
) -> Result<StepInfo> {
    check_step(h)?;
    state.validate(flow.dof())?;
    check_time_resolution(state.t, h)?;
    let t = state.t;
    let iterations = flow.flow(t, h, state.q.as_mut_slice(), state.v.as_mut_slice())?;
    state.t = t + h;
    // One residual evaluation per Newton iteration and one to check the start.
    Ok(StepInfo::fixed(h)
        .with_newton(iterations, 0)
        .with_evaluations(iterations + 1))
}

/// Implements [`noether_core::Stepper`] for a type that implements [`DiscreteFlow`].
macro_rules! stepper_via_flow {
    ($ty:ident < $($g:ident : $b:path),* >) => {
        impl<$($g: $b),*> noether_core::Stepper for $ty<$($g),*> {
            type Partner = noether_core::Momenta;
            fn step(
                &mut self,
                state: &mut noether_core::State<noether_core::Momenta>,
                h: f64,
            ) -> noether_core::Result<noether_core::StepInfo> {
                $crate::flow::step_state(self, state, h)
            }
            fn rates(
                &self,
                state: &noether_core::State<noether_core::Momenta>,
                dq: &mut [f64],
                dp: &mut [f64],
            ) -> Option<noether_core::Result<()>> {
                $crate::DiscreteFlow::rates(self, state.t, state.q.as_slice(), state.v.as_slice(), dq, dp)
            }
            fn dof(&self) -> usize {
                $crate::DiscreteFlow::dof(self)
            }
            fn order(&self) -> u32 {
                $crate::DiscreteFlow::order(self)
            }
            fn name(&self) -> &'static str {
                $crate::DiscreteFlow::name(self)
            }
        }
    };
}
pub(crate) use stepper_via_flow;

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
