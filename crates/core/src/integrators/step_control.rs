//! The step-control engine of the adaptive methods: the Dormand-Prince pairs
//! ([`Adaptive`](super::Adaptive)), the Runge-Kutta-Nyström pairs ([`Nystrom`](super::Nystrom)) and
//! [`Ias15`](super::Ias15) share
//!
//! - the settings ([`Settings`]: smallest step, fixed steps, dense output, and the method's own
//!   control, [`Tolerances`] for the pairs) and one builder macro for them, `settings_methods!`;
//! - the accept/reject loop of a step ([`until_accepted`]: trials, rejections, the step-size underflow)
//!   with the pairs' PI controller ([`Controller`], [`until_accepted_pi`]) as one policy and IAS15's
//!   own as the other;
//! - the statistics of a step ([`Accepted::info`]), the checks at its start ([`check_start`]), the
//!   evaluations of the accelerations of a split system ([`stage_accelerations`],
//!   [`start_accelerations`]), Hairer's initial step size ([`initial_step_size`]);
//! - the [`Stepper`](crate::Stepper) methods that read only these (`controlled_stepper!`).

use crate::error::{check_step, check_time_resolution};
use crate::{Dynamics, Error, Result, State, StepInfo};

/// A NaN error norm (from non-finite stages) as ∞: the trial is rejected.
#[inline]
pub(in crate::integrators) fn checked_error(err: f64) -> f64 {
    if err.is_nan() {
        f64::INFINITY
    } else {
        err
    }
}

/// The scale of component i in the error norm, sk_i = atol + rtol·max(|y₀_i|, |y₁_i|).
#[inline]
pub(in crate::integrators) fn error_scale(atol: f64, rtol: f64, y0: f64, y1: f64) -> f64 {
    atol + rtol * y0.abs().max(y1.abs())
}

/// The settings of an adaptive method, set by the builder methods of `settings_methods!`: those every
/// method has, and its own step-size control `C` ([`Tolerances`] for the embedded pairs, ε and the
/// criterion for IAS15).
#[derive(Debug, Clone, Copy)]
pub(in crate::integrators) struct Settings<C> {
    pub(in crate::integrators) h_min: f64,
    /// Fixed steps: no error control.
    pub(in crate::integrators) fixed: bool,
    /// The user allows a dense output (`dense_interpolant`), and the driver asks for one.
    pub(in crate::integrators) dense_allowed: bool,
    pub(in crate::integrators) dense_requested: bool,
    /// The method's own control.
    pub(in crate::integrators) control: C,
}

impl<C> Settings<C> {
    /// h_min = 1e-14, error control on, dense output allowed and requested, and `control`.
    pub(in crate::integrators) fn new(control: C) -> Self {
        Settings {
            h_min: 1e-14,
            fixed: false,
            dense_allowed: true,
            dense_requested: true,
            control,
        }
    }

    /// Whether the step just accepted builds its dense output: allowed and asked for.
    #[inline]
    pub(in crate::integrators) fn dense(&self) -> bool {
        self.dense_allowed && self.dense_requested
    }
}

/// The error control of an embedded pair: the tolerances of the scaled error norm and the PI
/// controller.
#[derive(Debug, Clone, Copy)]
pub(in crate::integrators) struct Tolerances {
    pub(in crate::integrators) atol: f64,
    pub(in crate::integrators) rtol: f64,
    pub(in crate::integrators) controller: Controller,
}

impl Tolerances {
    /// atol = rtol = 1e-9 and `controller`.
    pub(in crate::integrators) fn new(controller: Controller) -> Self {
        Tolerances {
            atol: 1e-9,
            rtol: 1e-9,
            controller,
        }
    }
}

/// The builder methods of an adaptive method (a struct with fields `settings`, `system` and
/// `evaluations`); `$f` names what is evaluated. With `tolerances` first, also the methods of an
/// embedded pair's [`Tolerances`] (its method type `M` has `CONTROL_ORDER`).
macro_rules! settings_methods {
    (tolerances, $f:literal) => {
        /// Sets the absolute and relative tolerances (atol, rtol): the step is accepted when the error
        /// estimate of each component i is below atol + rtol·max(|y₀ᵢ|, |y₁ᵢ|). atol must be finite and
        /// ≥ 0, rtol finite and ≥ [`RTOL_FLOOR`](crate::integrators::RTOL_FLOOR) = 10 ε ≈ 2.2e-15 (what
        /// f64 can deliver); [`Error::InvalidParameter`] otherwise.
        pub fn tolerances(mut self, atol: f64, rtol: f64) -> Result<Self> {
            $crate::integrators::step_control::check_tolerances(atol, rtol, self.settings.h_min)?;
            self.settings.control.atol = atol;
            self.settings.control.rtol = rtol;
            Ok(self)
        }
        /// Sets the step-size controller (safety in (0, 1], 0 < fac_min ≤ 1 ≤ fac_max < ∞,
        /// 0 ≤ β < 4/(3q)).
        pub fn controller(
            mut self,
            controller: $crate::integrators::step_control::Controller,
        ) -> Result<Self> {
            self.settings.control.controller = controller.checked(M::CONTROL_ORDER)?;
            Ok(self)
        }
        $crate::integrators::step_control::settings_methods!($f);
    };
    ($f:literal) => {
        /// Sets the smallest step size before [`Error::StepSizeUnderflow`] (default 1e-14; finite,
        /// ≥ 0).
        pub fn h_min(mut self, h_min: f64) -> Result<Self> {
            self.settings.h_min = $crate::integrators::step_control::checked_h_min(h_min)?;
            Ok(self)
        }
        /// Fixed steps: every step is accepted with the size asked for (no error control); for
        /// convergence studies and for users who want a plain high-order method.
        pub fn fixed_step(mut self, fixed: bool) -> Self {
            self.settings.fixed = fixed;
            self
        }
        /// Allows (default) or forbids the dense output; without it the driver interpolates output
        /// times and events by cubic Hermite (order 3) instead of the method's own extension.
        pub fn dense_interpolant(mut self, on: bool) -> Self {
            self.settings.dense_allowed = on;
            self
        }
        /// The system stepped.
        pub fn system(&self) -> &S {
            &self.system
        }
        #[doc = concat!("Evaluations of ", $f, " since construction.")]
        pub fn evaluations(&self) -> usize {
            self.evaluations
        }
    };
}
pub(in crate::integrators) use settings_methods;

/// The [`Stepper`](crate::Stepper) methods of an adaptive method that read only its settings and
/// fields (`system`, `settings`, `n`, `dense`, and `hinit`, its initial step size): `dof`, `order`,
/// `name`, `is_adaptive`, `initial_step`, the dense output and the rates.
macro_rules! controlled_stepper {
    (order: $order:expr, name: $name:expr) => {
        fn dof(&self) -> usize {
            self.n
        }
        fn order(&self) -> u32 {
            $order
        }
        fn name(&self) -> &'static str {
            $name
        }
        fn is_adaptive(&self) -> bool {
            !self.settings.fixed
        }
        /// The method's initial step size (Hairer's rule; see its `hinit`).
        fn initial_step(&mut self, state: &State<S::Partner>) -> Result<Option<f64>> {
            self.hinit(state).map(Some)
        }
        fn request_dense_output(&mut self, on: bool) {
            self.settings.dense_requested = on;
        }
        fn dense_output(&self) -> Option<&DenseOutput<S::Partner>> {
            self.dense.as_ref()
        }
        fn rates(&self, state: &State<S::Partner>, dq: &mut [f64], dv: &mut [f64]) -> Option<Result<()>> {
            Some(
                self.system
                    .rates(state.t, state.q.as_slice(), state.v.as_slice(), dq, dv),
            )
        }
    };
}
pub(in crate::integrators) use controlled_stepper;

/// Step-size controller parameters (Hairer's `safe`, `fac1`, `fac2`, `beta`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Controller {
    /// Safety factor (0.9).
    pub safety: f64,
    /// Smallest ratio h_new/h.
    pub fac_min: f64,
    /// Largest ratio h_new/h.
    pub fac_max: f64,
    /// PI stabilisation exponent β (0 gives the standard controller).
    pub beta: f64,
}

impl Controller {
    /// The defaults of Hairer's code DOPRI5 (safe = 0.9, fac1 = 0.2, fac2 = 10, β = 0.04; as distributed
    /// with Hairer-Nørsett-Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.): the
    /// Dormand-Prince 5(4) pair's and DPRKN 6(4)'s.
    pub const DOPRI5: Controller = Controller {
        safety: 0.9,
        fac_min: 0.2,
        fac_max: 10.0,
        beta: 0.04,
    };

    /// The defaults of Hairer's code DOP853 (safe = 0.9, fac1 = 0.333, fac2 = 6, β = 0; as distributed
    /// with Hairer-Nørsett-Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.): DOP853's and
    /// the high-order Nyström pairs' (DPRKN 8(6), DPRKN 12(10)).
    pub const DOP853: Controller = Controller {
        safety: 0.9,
        fac_min: 0.333,
        fac_max: 6.0,
        beta: 0.0,
    };

    /// The controller if its parameters are in range for a method whose step size scales like
    /// err^(−1/`order`): 0 < safety ≤ 1, 0 < fac_min ≤ 1 ≤ fac_max < ∞, and 0 ≤ β < 4/(3·order) so
    /// that the exponent α = 1/order − 0.75β of the error stays positive (with α ≤ 0 a larger error
    /// no longer shrinks the step). An [`Error::InvalidParameter`] otherwise.
    pub(in crate::integrators) fn checked(self, order: f64) -> Result<Self> {
        let c = self;
        let ok = c.safety > 0.0
            && c.safety <= 1.0
            && c.fac_min > 0.0
            && c.fac_min <= 1.0
            && c.fac_max >= 1.0
            && c.fac_max.is_finite()
            && c.beta >= 0.0
            && 1.0 / order - 0.75 * c.beta > 0.0;
        if !ok {
            return Err(Error::InvalidParameter {
                name: "controller",
                value: c.beta,
                reason: "needs 0 < safety ≤ 1, 0 < fac_min ≤ 1 ≤ fac_max < ∞ and 0 ≤ β < 4/(3·order)",
            });
        }
        Ok(self)
    }

    /// h/h_next after a step accepted with error `err` (≤ 1), the previous accepted one `err_prev`:
    /// err^α / err_prev^β / safety, clamped to [1/fac_max, 1/fac_min] (1/fac_max for err = 0).
    pub(in crate::integrators) fn accepted_divisor(&self, err: f64, err_prev: f64, alpha: f64) -> f64 {
        if err == 0.0 {
            1.0 / self.fac_max
        } else {
            // β = 0 (DOP853's default): no second power.
            let pi = if self.beta == 0.0 {
                1.0
            } else {
                err_prev.powf(self.beta)
            };
            let f = power(err, alpha) / pi / self.safety;
            f.clamp(1.0 / self.fac_max, 1.0 / self.fac_min)
        }
    }

    /// h/h_retry after a rejected trial with error `err` (> 1, possibly ∞): Hairer's codes shrink by
    /// err^α / safety (α = 1/q − 0.75β, the accepted step's exponent), at most by 1/fac_min.
    pub(in crate::integrators) fn rejected_divisor(&self, err: f64, alpha: f64) -> f64 {
        if err.is_finite() {
            (power(err, alpha) / self.safety).min(1.0 / self.fac_min)
        } else {
            1.0 / self.fac_min
        }
    }
}

/// x^α for the controller: three square roots for α = 1/8 (DOP853's exponent), `powf` otherwise.
/// The roots are each correctly rounded and land within 1 ulp of `powf` (measured on 1.1·10⁷
/// arguments from 1e-300 to 1e300) in 17 ns instead of 24 ns of latency, which the next trial's
/// stages wait for (DOP853 on Kepler at tol 1e-10: 5 % of the run).
#[inline]
fn power(x: f64, alpha: f64) -> f64 {
    if alpha == 0.125 {
        x.sqrt().sqrt().sqrt()
    } else {
        x.powf(alpha)
    }
}

/// The smallest relative tolerance an adaptive method accepts: 10 ε ≈ 2.2e-15. Rounding alone
/// perturbs each step by a few ε of the state, so a smaller rtol cannot be met and only drives the step
/// size down to underflow. Hairer's RADAU5 refuses `RTOL ≤ 10·UROUND` in the same way ("tolerances are
/// too small"); noether refuses rather than clamps, so a run is never quietly less accurate than asked.
pub const RTOL_FLOOR: f64 = 10.0 * f64::EPSILON;

/// Checks the tolerances (atol finite and ≥ 0, rtol finite and ≥ [`RTOL_FLOOR`]) and the smallest step
/// `h_min` (finite, ≥ 0).
pub(in crate::integrators) fn check_tolerances(atol: f64, rtol: f64, h_min: f64) -> Result<()> {
    let bad = |name, value, reason| Err(Error::InvalidParameter { name, value, reason });
    if !(atol.is_finite() && atol >= 0.0) {
        return bad("atol", atol, "must be finite and non-negative");
    }
    if !(rtol.is_finite() && rtol >= 0.0) {
        return bad("rtol", rtol, "must be finite and non-negative");
    }
    if rtol < RTOL_FLOOR {
        return bad(
            "rtol",
            rtol,
            "is below what f64 arithmetic can deliver: the relative tolerance must be at least \
             10 ε ≈ 2.2e-15 (RTOL_FLOOR)",
        );
    }
    checked_h_min(h_min).map(|_| ())
}

/// The smallest step `h_min` if it is finite and ≥ 0; [`Error::InvalidParameter`] otherwise.
pub(in crate::integrators) fn checked_h_min(h_min: f64) -> Result<f64> {
    if h_min.is_finite() && h_min >= 0.0 {
        Ok(h_min)
    } else {
        Err(Error::InvalidParameter {
            name: "h_min",
            value: h_min,
            reason: "must be finite and non-negative",
        })
    }
}

/// The checks at the start of every step of size h from `state` of a system of n degrees of freedom:
/// h finite and non-zero, the state of n components and finite, t + h resolving h, and the state
/// admissible for the system.
#[inline]
pub(in crate::integrators) fn check_start<S: Dynamics>(
    system: &S,
    n: usize,
    state: &State<S::Partner>,
    h: f64,
) -> Result<()> {
    check_step(h)?;
    state.validate(n)?;
    check_time_resolution(state.t, h)?;
    system.admissible(state.t, state.q.as_slice(), state.v.as_slice())
}

/// [`Error::StepSizeUnderflow`] when a trial step h at t is below `h_min` or below 10 ulps of t
/// (`last_err` is the error estimate of the last rejected trial).
#[inline]
fn check_underflow(t: f64, h: f64, h_min: f64, last_err: f64) -> Result<()> {
    // A trial step that t + h cannot resolve to 1 % (crate::error::check_time_resolution) is an
    // underflow too: the state's time would record another interval than the one integrated.
    if h < h_min || h <= 10.0 * f64::EPSILON * t.abs() || check_time_resolution(t, h).is_err() {
        return Err(Error::StepSizeUnderflow {
            t,
            h,
            error: last_err,
        });
    }
    Ok(())
}

/// What a trial step of the accept/reject loop ([`until_accepted`]) decided.
pub(in crate::integrators) enum Verdict<A> {
    /// Accepted, with what the method keeps of it.
    Accept(A),
    /// Rejected: retry with step size `h`; `error` is what the method measured (reported by a
    /// step-size underflow that follows).
    Retry { h: f64, error: f64 },
}

/// The trial step an accept/reject loop ([`until_accepted`]) accepted.
#[derive(Debug, Clone, Copy)]
pub(in crate::integrators) struct Accepted<A> {
    /// Its size.
    pub(in crate::integrators) h: f64,
    /// The trials rejected before it.
    pub(in crate::integrators) rejected: usize,
    /// What the method keeps of it.
    pub(in crate::integrators) outcome: A,
}

impl<A> Accepted<A> {
    /// The statistics of the step: its size, the rejected trials, the controller's proposal `h_next`
    /// and the `evaluations` it cost.
    #[inline]
    pub(in crate::integrators) fn info(&self, h_next: f64, evaluations: usize) -> StepInfo {
        StepInfo::fixed(self.h)
            .with_control(self.rejected, h_next)
            .with_evaluations(evaluations)
    }
}

/// The accept/reject loop of a step from t: tries h by `attempt(h, rejected)` (`rejected`: the trials
/// rejected so far), which accepts the trial or names the step size of the next one. Every trial step
/// is checked first: [`Error::StepSizeUnderflow`] (with the `error` of the last rejection) when h falls
/// below `h_min` or what t resolves ([`check_underflow`]).
#[inline(always)]
pub(in crate::integrators) fn until_accepted<A>(
    h_min: f64,
    (t, h): (f64, f64),
    mut attempt: impl FnMut(f64, usize) -> Result<Verdict<A>>,
) -> Result<Accepted<A>> {
    let (mut h, mut rejected, mut last_err) = (h, 0, f64::NAN);
    loop {
        check_underflow(t, h, h_min, last_err)?;
        match attempt(h, rejected)? {
            Verdict::Accept(outcome) => return Ok(Accepted { h, rejected, outcome }),
            Verdict::Retry { h: next, error } => {
                rejected += 1;
                last_err = error;
                h = next;
            }
        }
    }
}

/// The error estimate of a trial an embedded pair accepted ([`until_accepted_pi`]).
#[derive(Debug, Clone, Copy)]
pub(in crate::integrators) struct Estimate {
    /// Its error norm (≤ 1).
    err: f64,
    /// The controller's exponent α = 1/q − 0.75β.
    alpha: f64,
}

impl Accepted<Estimate> {
    /// The step size the controller proposes after this step, and `err_prev` updated to its error:
    /// h_next = h / [`accepted_divisor`](Controller::accepted_divisor)(err, err_prev, α) (h itself in
    /// fixed-step mode), no larger than h after a rejection; err_prev = max(err, 10⁻⁴).
    #[inline(always)]
    pub(in crate::integrators) fn next_step(
        &self,
        settings: &Settings<Tolerances>,
        err_prev: &mut f64,
    ) -> f64 {
        let c = settings.control.controller;
        let (h, e) = (self.h, self.outcome);
        let mut h_next = if settings.fixed {
            h
        } else {
            h / c.accepted_divisor(e.err, *err_prev, e.alpha)
        };
        if self.rejected > 0 {
            h_next = h_next.min(h);
        }
        *err_prev = e.err.max(1e-4);
        h_next
    }
}

/// [`until_accepted`] with the PI controller of the embedded pairs: `attempt` returns the trial's
/// error norm, a trial with err ≤ 1 is accepted, and a rejected one is retried with
/// h / [`rejected_divisor`](Controller::rejected_divisor)(err, α), α = 1/q − 0.75β for the controller
/// order q = `control_order`. In fixed-step mode a rejected trial (non-finite stages: the error is 0
/// otherwise) is [`Error::NonFiniteResult`] of `what` at t.
#[inline(always)]
pub(in crate::integrators) fn until_accepted_pi(
    settings: &Settings<Tolerances>,
    control_order: f64,
    (t, h): (f64, f64),
    what: &'static str,
    mut attempt: impl FnMut(f64) -> Result<f64>,
) -> Result<Accepted<Estimate>> {
    let c = settings.control.controller;
    let alpha = 1.0 / control_order - 0.75 * c.beta;
    until_accepted(settings.h_min, (t, h), |h, _| {
        let err = attempt(h)?;
        if err <= 1.0 {
            return Ok(Verdict::Accept(Estimate { err, alpha }));
        }
        if settings.fixed {
            return Err(Error::NonFiniteResult {
                what,
                t,
                component: None,
            });
        }
        Ok(Verdict::Retry {
            h: h / c.rejected_divisor(err, alpha),
            error: err,
        })
    })
}

/// The outcome of one stage evaluation writing `out`: Ok(true) when it succeeded with finite
/// values, Ok(false) when the model or the values were not finite (the trial step is rejected as
/// too large), the model's error otherwise.
#[inline]
pub(in crate::integrators) fn finite_stage(r: Result<()>, out: &[f64]) -> Result<bool> {
    match r {
        // No early exit: a few entries, one vectorised pass.
        Ok(()) => Ok(out.iter().fold(true, |ok, x| ok & x.is_finite())),
        Err(Error::NonFiniteResult { .. }) | Err(Error::NonFinite { .. }) => Ok(false),
        Err(e) => Err(e),
    }
}

/// [`Error::NonFiniteResult`] for rates k = (q̇, then v̇ or ṗ) at t that are not all finite: the
/// first such component, named as a rate of q ("velocities dq/dt") or of the partner
/// ("accelerations" of q̇, "momentum rates dp/dt" of p), with its index within that half.
pub(in crate::integrators) fn rates_error<K: crate::Partner>(t: f64, k: &[f64]) -> Error {
    let n = k.len() / 2;
    let Some(i) = k.iter().position(|x| !x.is_finite()) else {
        return Error::NonFiniteResult {
            what: "rates",
            t,
            component: None,
        };
    };
    let what = match (i < n, K::SYMBOL) {
        (true, _) => "velocities dq/dt",
        (false, "v") => "accelerations",
        (false, _) => "momentum rates dp/dt",
    };
    Error::NonFiniteResult {
        what,
        t,
        component: Some(if i < n { i } else { i - n }),
    }
}

/// Hairer's `hinit` for y' = F(t, y) of a method of order `order`: with sk_i = atol + rtol·|y₀_i|,
/// h₀ = 0.01 ‖y₀‖/‖F₀‖ (10⁻⁶ when either norm is ≤ 10⁻⁵), an estimate ‖y″‖ ≈ ‖F₁ − F₀‖/h₀ from
/// F₁ = F(t + h₀, y₀ + h₀F₀), whose difference F₁ − F₀ `eval(h₀, d)` writes into d, and
/// h = min(100h₀, (0.01/max(‖y″‖, ‖F₀‖))^(1/order)). When `eval` reports a non-finite F₁ (Ok(false))
/// the answer is 10⁻³h₀.
pub(in crate::integrators) fn initial_step_size(
    order: u32,
    (atol, rtol): (f64, f64),
    y0: &[f64],
    f0: &[f64],
    mut eval: impl FnMut(f64, &mut [f64]) -> Result<bool>,
) -> Result<f64> {
    let sk = |i: usize| atol + rtol * y0[i].abs();
    let norm = |x: &mut dyn Iterator<Item = f64>| x.map(|v| v * v).sum::<f64>().sqrt();
    let dnf = norm(&mut (0..y0.len()).map(|i| f0[i] / sk(i)));
    let dny = norm(&mut (0..y0.len()).map(|i| y0[i] / sk(i)));
    let h = if dnf <= 1e-5 || dny <= 1e-5 {
        1e-6
    } else {
        0.01 * dny / dnf
    };
    let mut d = vec![0.0; y0.len()];
    if !eval(h, &mut d)? {
        return Ok(h * 1e-3);
    }
    let der2 = norm(&mut (0..y0.len()).map(|i| d[i] / sk(i))) / h;
    let der12 = der2.abs().max(dnf);
    let h1 = if der12 <= 1e-15 {
        (h * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(1.0 / (order as f64))
    };
    Ok((100.0 * h).min(h1))
}

/// f(q) of a split system into `out` at a stage of a trial step, counted in `evaluations`: Ok(false)
/// when it is not finite (an error of the model that says so, or a value that is not: the trial is
/// rejected as too large, [`finite_stage`]); other errors of the model pass through.
#[inline]
pub(in crate::integrators) fn stage_accelerations<S: crate::system::SplitDynamics>(
    system: &S,
    evaluations: &mut usize,
    q: &[f64],
    out: &mut [f64],
) -> Result<bool> {
    *evaluations += 1;
    finite_stage(system.kick_rate(q, out), out)
}

/// The accelerations f(q) of a split system at the start of a step or a run, where no smaller step
/// helps: `Ok` when f(q) is finite; otherwise [`Error::NonFiniteResult`] for "accelerations" at t, with
/// the component the model named or the first component of f(q) that is not finite (issue 30: the
/// Nyström pairs and IAS15 named none). Other errors of the model pass through.
pub(in crate::integrators) fn start_accelerations<S: crate::system::SplitDynamics>(
    system: &S,
    evaluations: &mut usize,
    t: f64,
    q: &[f64],
    out: &mut [f64],
) -> Result<()> {
    start_accelerations_by(evaluations, t, out, |out| system.kick_rate(q, out))
}

/// [`start_accelerations`] for accelerations that `eval` writes into `out` (IAS15's f(t, q, v) of
/// a system whose forces depend on the velocities): the same test and the same error.
pub(in crate::integrators) fn start_accelerations_by(
    evaluations: &mut usize,
    t: f64,
    out: &mut [f64],
    eval: impl FnOnce(&mut [f64]) -> Result<()>,
) -> Result<()> {
    *evaluations += 1;
    let component = match eval(out) {
        Ok(()) => match out.iter().position(|x| !x.is_finite()) {
            None => return Ok(()),
            first => first,
        },
        Err(Error::NonFiniteResult { component, .. }) => component,
        Err(Error::NonFinite { .. }) => None,
        Err(e) => return Err(e),
    };
    Err(Error::NonFiniteResult {
        what: "accelerations",
        t,
        component,
    })
}
