//! Adaptive embedded Runge-Kutta pairs with error control and dense output: the engine shared by
//! [`Dopri5`](super::Dopri5) (Dormand-Prince 5(4)) and [`Dop853`](super::Dop853) (Dormand-Prince
//! 8(5,3)).
//!
//! A step of size h computes the stages k_i = F(t + c_i h, y + h Σ_j a_ij k_j) on y = (q, v), the
//! solution y₁ = y + h Σ b_i k_i and an error estimate (the difference to an embedded lower-order
//! solution), measured in the scaled norm
//!
//! ```text
//! err = sqrt( (1/2n) Σ_i ( e_i / (atol + rtol·max(|y_i|, |y₁_i|)) )² ).
//! ```
//!
//! The step is accepted when err ≤ 1. The next step size follows the PI controller of Hairer's codes
//! (Hairer-Nørsett-Wanner I, II.4 and IV.2):
//! h_new = h · clamp(safety · err^(−α) · err_prev^β, fac_min, fac_max), α = 1/q − 0.75β, with q the
//! controller order (5 for DOPRI5, 8 for DOP853). A rejected step is retried with a smaller h; when h
//! falls below `h_min` (or below 10 ulps of t) the step fails with [`Error::StepSizeUnderflow`].
//! Stage values that are not finite count as a rejected step (the step is too large), so a solution
//! running into a singularity ends in a step-size underflow rather than a NaN state. F(t + h, y₁),
//! the first stage of the next step, is evaluated before the error estimate only when the estimate
//! weighs it (DOPRI5); DOP853's does not, and a rejected trial does not pay for it (as in Hairer's
//! code: 11 evaluations per trial, 1 more per accepted step).
//!
//! Systems of up to 6 degrees of freedom are stepped on arrays of their length, the vector field
//! taken by value ([`Dynamics::rates_fixed`]): for [`Natural`](crate::Natural) the model's gradient
//! then inlines into the stage loop and the stages stay in registers. The result is the same to the
//! bit as on vectors (DOP853 on Kepler, 100 orbits at tol 1e-10: 2.11 → 1.42 ms; docs/benchmarks.md).
//!
//! After every accepted step a continuous extension ([`DenseOutput`]) gives y(t) inside the step to
//! the method's dense order (4 for DOPRI5, 7 for DOP853), on which the [`Driver`](crate::Driver)
//! samples output times and locates events. It is built only when the driver needs it (DOP853 spends
//! three more evaluations of the vector field per step on it).

use crate::dense::DenseEval;
use crate::error::{check_step, check_time_resolution};
use crate::{DenseOutput, Dynamics, Error, Result, State, StepInfo, Stepper};

/// The coefficients and formulas of an embedded pair with dense output.
pub trait EmbeddedPair {
    /// Short name.
    const NAME: &'static str;
    /// Order of the propagated solution.
    const ORDER: u32;
    /// Controller order q: the step size scales like err^(−1/q).
    const CONTROL_ORDER: f64;
    /// Default step-size controller.
    const CONTROLLER: Controller;
    /// Nodes c_i of the s main stages.
    const C: &'static [f64];
    /// Rows a_i (length i) of the s main stages.
    const A: &'static [&'static [f64]];
    /// Weights b_i (length s) of the propagated solution.
    const B: &'static [f64];
    /// Extra stages for the dense output, each (c, row over all previous stages incl. F(t+h, y₁)).
    const DENSE_STAGES: &'static [(f64, &'static [f64])];
    /// Number of coefficient vectors of the dense polynomial.
    const DENSE_LEN: usize;
    /// Dense order (of the continuous extension).
    const DENSE_ORDER: u32;
    /// Weights of the error estimates, one or two rows: estimate r is h Σ_j `ERROR[r][j]` k_j over
    /// the s main stages and k_s = F(t + h, y₁).
    const ERROR: &'static [&'static [f64]];
    /// The scaled error norm of a step of size h from the sums S_r = Σ_i (Σ_j `ERROR[r][j]` k_j,i /
    /// sk_i)² over the m components of y, sk_i = atol + rtol·max(|y₀_i|, |y₁_i|).
    fn error_norm(h: f64, sums: [f64; 2], m: usize) -> f64;
    /// Coefficients of the dense polynomial from all stages (main, F(t+h,y₁), dense extra).
    fn dense_coefficients(h: f64, k: Stages<'_>, y0: &[f64], y1: &[f64], out: &mut [Vec<f64>]);
    /// y(t₀ + θh) from the coefficients.
    fn dense_eval(theta: f64, y0: &[f64], coeffs: &[Vec<f64>], out: &mut [f64]);
}

/// The stages of one step, stage after stage: k_j is the slice k[j·m .. (j+1)·m] for a state of m
/// components, which the vector field writes in place. A weighted sum of stages is an axpy per stage
/// with a nonzero weight; for small m the width is a constant and the sum stays in
/// registers.
#[derive(Debug, Clone, Copy)]
pub struct Stages<'a> {
    k: &'a [f64],
    m: usize,
}

impl<'a> Stages<'a> {
    /// The stages stored one after the other in `k`, each of `m` components.
    #[inline]
    pub fn new(k: &'a [f64], m: usize) -> Self {
        Stages { k, m }
    }
    /// Component `i` of stage `j`, k_j,i.
    #[inline]
    pub fn get(&self, j: usize, i: usize) -> f64 {
        self.k[j * self.m + i]
    }
    /// Σ_j w_j k_j,i: component i of a weighted sum of the stages (j over the weights given, zero
    /// weights left out).
    #[inline]
    pub fn weighted(&self, w: &[f64], i: usize) -> f64 {
        w.iter()
            .zip(self.k[i..].iter().step_by(self.m))
            .filter(|(w, _)| **w != 0.0)
            .fold(0.0, |s, (w, k)| s + w * k)
    }
}

/// The argument of a stage, from the weighted sum σ = Σ_j w_j k_j of the stages before it.
///
/// The last stage k_l of the row (the one just computed) enters after the others: the argument is
/// (y₀ + h Σ_{j<l} w_j k_j) + (h w_l) k_l, so that one multiply and one add separate a stage from
/// the next one's argument, against four for y₀ + h (Σ_{j<l} w_j k_j + w_l k_l): the stages of an
/// explicit method are a chain, each waiting for the last (DOP853 on Kepler, 100 orbits at tol
/// 1e-10: 1.62 → 1.58 ms). The result differs from the textbook order by one rounding at the scale
/// of y (the increment is added in two parts).
#[derive(Debug, Clone, Copy)]
pub(super) enum StageArgument<'a> {
    /// y₀ + h σ (a Runge-Kutta stage on y).
    Y { y0: &'a [f64], h: f64 },
    /// q₀ + h (c q̇₀ + h σ) (a Nyström stage on q, the k_j accelerations).
    Nystrom {
        q0: &'a [f64],
        v0: &'a [f64],
        c: f64,
        h: f64,
    },
}

impl StageArgument<'_> {
    /// The factor of the last stage: h for y, h² for q in a Nyström stage.
    #[inline(always)]
    fn last_factor(&self) -> f64 {
        match *self {
            StageArgument::Y { h, .. } => h,
            StageArgument::Nystrom { h, .. } => h * h,
        }
    }

    /// The argument for M components from the stages k_j = k[j·M .. (j+1)·M] and the weights `w`
    /// (see [`StageArgument`]), in arrays; `None` when a length does not fit M.
    #[inline(always)]
    pub(super) fn fixed<const M: usize>(self, k: &[f64], w: &[f64]) -> Option<[f64; M]> {
        let (&last, rest) = w.split_last()?;
        let sum = stage_sum::<M>(k, rest);
        let k_last = <&[f64; M]>::try_from(k.get(rest.len() * M..w.len() * M)?).ok()?;
        let c = self.last_factor() * last;
        let partial: [f64; M] = match self {
            StageArgument::Y { y0, h } => {
                let y0 = <&[f64; M]>::try_from(y0).ok()?;
                std::array::from_fn(|x| y0[x] + h * sum[x])
            }
            StageArgument::Nystrom { q0, v0, c, h } => {
                let (q0, v0) = (<&[f64; M]>::try_from(q0).ok()?, <&[f64; M]>::try_from(v0).ok()?);
                std::array::from_fn(|x| q0[x] + h * (c * v0[x] + h * sum[x]))
            }
        };
        Some(std::array::from_fn(|x| partial[x] + c * k_last[x]))
    }
}

/// The stage argument (see [`StageArgument`]) into `out`, from the stages k_j = k[j·m .. (j+1)·m]
/// (m = `out.len()`) whose weight w_j is nonzero (the high-order tableaux are sparse: 32 of DOP853's
/// 78 aᵢⱼ are 0). For m up to 12 everything is held in fixed-length arrays, so that the loops over
/// the components are unrolled and vectorised, and the result is stored whole (the vector field loads
/// its arguments as vectors; a vector load of entries stored one by one stalls store forwarding). For
/// a 2-dof system this made DOP853's step a quarter faster than with the closure-based form it
/// replaced (`--bench nystrom`, docs/benchmarks.md).
#[inline]
pub(super) fn combine_stages(k: &[f64], w: &[f64], arg: StageArgument<'_>, out: &mut [f64]) {
    fn any(k: &[f64], w: &[f64], arg: StageArgument<'_>, out: &mut [f64]) {
        let m = out.len();
        let (last, rest) = w.split_last().map_or((0.0, w), |(l, r)| (*l, r));
        out.fill(0.0);
        for (kj, &a) in k.chunks_exact(m.max(1)).zip(rest) {
            if a != 0.0 {
                out.iter_mut().zip(kj).for_each(|(s, k)| *s += a * k);
            }
        }
        match arg {
            StageArgument::Y { y0, h } => out.iter_mut().zip(y0).for_each(|(s, y)| *s = y + h * *s),
            StageArgument::Nystrom { q0, v0, c, h } => {
                for (x, s) in out.iter_mut().enumerate() {
                    *s = q0[x] + h * (c * v0[x] + h * *s);
                }
            }
        }
        let c = arg.last_factor() * last;
        let k_last = k.chunks_exact(m.max(1)).nth(rest.len()).unwrap_or(&[]);
        out.iter_mut().zip(k_last).for_each(|(s, k)| *s += c * k);
    }
    macro_rules! widths {
        ($($m:literal)*) => {
            match out.len() {
                $($m => {
                    if let Ok(o) = <&mut [f64; $m]>::try_from(&mut *out) {
                        if let Some(y) = arg.fixed(k, w) {
                            *o = y;
                            return;
                        }
                    }
                    any(k, w, arg, out)
                })*
                _ => any(k, w, arg, out),
            }
        };
    }
    widths!(1 2 3 4 5 6 8 12)
}

/// σ = Σ_j w_j k_j in an array of M components, over the stages k_j = k[j·M .. (j+1)·M] whose weight
/// is nonzero (the same operations in the same order as the general loop of [`combine_stages`]).
#[inline(always)]
pub(super) fn stage_sum<const M: usize>(k: &[f64], w: &[f64]) -> [f64; M] {
    let mut sum = [0.0; M];
    for (kj, &a) in k.chunks_exact(M.max(1)).zip(w) {
        if a != 0.0 {
            (0..M).for_each(|x| sum[x] += a * kj[x]);
        }
    }
    sum
}

/// A NaN error norm (from non-finite stages) as ∞: the trial is rejected.
#[inline]
pub(super) fn checked_error(err: f64) -> f64 {
    if err.is_nan() {
        f64::INFINITY
    } else {
        err
    }
}

/// The scale of component i in the error norm, sk_i = atol + rtol·max(|y₀_i|, |y₁_i|).
#[inline]
pub(super) fn error_scale(atol: f64, rtol: f64, y0: f64, y1: f64) -> f64 {
    atol + rtol * y0.abs().max(y1.abs())
}

/// The settings the embedded pairs ([`Adaptive`], [`Nystrom`](super::Nystrom)) share, set by the
/// builder methods of `settings_methods!`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Settings {
    pub(super) atol: f64,
    pub(super) rtol: f64,
    pub(super) h_min: f64,
    pub(super) controller: Controller,
    /// Fixed steps: no error control.
    pub(super) fixed: bool,
    /// The user allows a dense output (`with_dense_output`), and the driver asks for one.
    pub(super) dense_allowed: bool,
    pub(super) dense_requested: bool,
}

impl Settings {
    /// atol = rtol = 1e-9, h_min = 1e-14, error control on, dense output allowed and requested.
    pub(super) fn new(controller: Controller) -> Self {
        Settings {
            atol: 1e-9,
            rtol: 1e-9,
            h_min: 1e-14,
            controller,
            fixed: false,
            dense_allowed: true,
            dense_requested: true,
        }
    }
}

/// The builder methods of an embedded pair (a struct with fields `settings`, `system` and
/// `evaluations`, and a method type `M` with `CONTROL_ORDER`); `$f` names what is evaluated.
macro_rules! settings_methods {
    ($f:literal) => {
        /// Sets the absolute and relative tolerances (atol, rtol): the step is accepted when the error
        /// estimate of each component i is below atol + rtol·max(|y₀ᵢ|, |y₁ᵢ|). atol must be finite and
        /// ≥ 0, rtol finite and ≥ [`RTOL_FLOOR`](crate::integrators::RTOL_FLOOR) = 10 ε ≈ 2.2e-15 (what
        /// f64 can deliver); [`Error::InvalidParameter`] otherwise.
        pub fn tolerances(mut self, atol: f64, rtol: f64) -> Result<Self> {
            super::adaptive::check_tolerances(atol, rtol, self.settings.h_min)?;
            self.settings.atol = atol;
            self.settings.rtol = rtol;
            Ok(self)
        }
        /// Sets the smallest step size before [`Error::StepSizeUnderflow`] (default 1e-14; finite,
        /// ≥ 0).
        pub fn h_min(mut self, h_min: f64) -> Result<Self> {
            super::adaptive::check_tolerances(self.settings.atol, self.settings.rtol, h_min)?;
            self.settings.h_min = h_min;
            Ok(self)
        }
        /// Sets the step-size controller (safety in (0, 1], 0 < fac_min ≤ 1 ≤ fac_max < ∞,
        /// 0 ≤ β < 4/(3q)).
        pub fn controller(mut self, controller: super::adaptive::Controller) -> Result<Self> {
            self.settings.controller = controller.checked(M::CONTROL_ORDER)?;
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
        pub fn with_dense_output(mut self, on: bool) -> Self {
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
pub(super) use settings_methods;

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
    /// The controller if its parameters are in range for a method whose step size scales like
    /// err^(−1/`order`): 0 < safety ≤ 1, 0 < fac_min ≤ 1 ≤ fac_max < ∞, and 0 ≤ β < 4/(3·order) so
    /// that the exponent α = 1/order − 0.75β of the error stays positive (with α ≤ 0 a larger error
    /// no longer shrinks the step). An [`Error::InvalidParameter`] otherwise.
    pub(super) fn checked(self, order: f64) -> Result<Self> {
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
    pub(super) fn accepted_divisor(&self, err: f64, err_prev: f64, alpha: f64) -> f64 {
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
    pub(super) fn rejected_divisor(&self, err: f64, alpha: f64) -> f64 {
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
pub(super) fn check_tolerances(atol: f64, rtol: f64, h_min: f64) -> Result<()> {
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
    if !(h_min.is_finite() && h_min >= 0.0) {
        return bad("h_min", h_min, "must be finite and non-negative");
    }
    Ok(())
}

/// [`Error::StepSizeUnderflow`] when a trial step h at t is below `h_min` or below 10 ulps of t
/// (`last_err` is the error estimate of the last rejected trial).
#[inline]
pub(super) fn check_underflow(t: f64, h: f64, h_min: f64, last_err: f64) -> Result<()> {
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

/// The outcome of one stage evaluation writing `out`: Ok(true) when it succeeded with finite
/// values, Ok(false) when the model or the values were not finite (the trial step is rejected as
/// too large), the model's error otherwise.
#[inline]
pub(super) fn finite_stage(r: Result<()>, out: &[f64]) -> Result<bool> {
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
pub(super) fn rates_error<K: crate::Partner>(t: f64, k: &[f64]) -> Error {
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
/// h₀ = 0.01 ‖y₀‖/‖F₀‖ (10⁻⁶ when either norm is ≤ 10⁻⁵), an estimate of ‖y″‖ from
/// F₁ = F(t + h₀, y₀ + h₀F₀) written by `eval(h₀, F₁)`, and h = min(100h₀, (0.01/max(‖y″‖, ‖F₀‖))^(1/order)).
/// When `eval` reports a non-finite F₁ (Ok(false)) the answer is 10⁻³h₀.
pub(super) fn initial_step_size(
    order: u32,
    atol: f64,
    rtol: f64,
    y0: &[f64],
    f0: &[f64],
    f1: &mut [f64],
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
    if !eval(h, f1)? {
        return Ok(h * 1e-3);
    }
    let der2 = norm(&mut (0..y0.len()).map(|i| (f1[i] - f0[i]) / sk(i))) / h;
    let der12 = der2.abs().max(dnf);
    let h1 = if der12 <= 1e-15 {
        (h * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(1.0 / (order as f64))
    };
    Ok((100.0 * h).min(h1))
}

/// An adaptive embedded Runge-Kutta method `M` (see the [module](self) docs) stepping a [`Dynamics`].
///
/// ```
/// use noether_core::prelude::*;
/// struct Oscillator;
/// impl Lagrangian for Oscillator {
///     fn dof(&self) -> usize { 1 }
///     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D { (v[0] * v[0] - q[0] * q[0]) * 0.5 }
/// }
/// let dp = Dopri5::new(EulerLagrange::new(Oscillator)).tolerances(1e-10, 1e-10)?;
/// let sol = Driver::new(dp, State::new(0.0, [1.0], [0.0]))?
///     .save(Save::Times(vec![1.0, 2.0, 3.0]))?
///     .run_until(10.0)?;
/// for i in 0..sol.len() {
///     assert!((sol.q(i)[0] - sol.times()[i].cos()).abs() < 1e-8); // q = cos t, from the dense output
/// }
/// assert!(sol.last().t == 10.0 && (sol.last().q[0] - 10f64.cos()).abs() < 1e-8);
/// # Ok::<(), noether_core::Error>(())
/// ```
pub struct Adaptive<S: Dynamics, M> {
    system: S,
    settings: Settings,
    n: usize,
    /// The stages one after the other (see [`Stages`]): k[j·2n + x] is component x of stage j, for
    /// the main stages, F(t + h, y₁) and the dense stages.
    k: Vec<f64>,
    y0: Vec<f64>,
    y1: Vec<f64>,
    tmp: Vec<f64>,
    err_prev: f64,
    fsal: Option<f64>,
    dense: Option<DenseOutput<S::Partner>>,
    evaluations: usize,
    _method: std::marker::PhantomData<M>,
}

impl<S: Dynamics, M: EmbeddedPair> Adaptive<S, M> {
    /// The method for `system` with atol = rtol = 1e-9, dense output on.
    pub fn new(system: S) -> Self {
        let n = system.dof();
        let stages = M::C.len() + 1 + M::DENSE_STAGES.len();
        Adaptive {
            system,
            settings: Settings::new(M::CONTROLLER),
            n,
            k: vec![0.0; 2 * n * stages],
            y0: vec![0.0; 2 * n],
            y1: vec![0.0; 2 * n],
            tmp: vec![0.0; 2 * n],
            err_prev: 1e-4,
            fsal: None,
            dense: None,
            evaluations: 0,
            _method: std::marker::PhantomData,
        }
    }

    settings_methods!("the vector field");

    fn check_parameters(&self) -> Result<()> {
        check_tolerances(self.settings.atol, self.settings.rtol, self.settings.h_min)
    }

    /// Why the rates at the start of a step (t, y₀) are not finite: no smaller step can help there,
    /// so the model's own error is returned (evaluated once more, on this error path only), or, when
    /// the model returned NaN or ±∞ without one, [`rates_error`] naming the quantity and component.
    #[cold]
    fn start_error(&mut self, t: f64) -> Error {
        let n = self.n;
        let mut k = vec![0.0; 2 * n];
        let (dq, dv) = k.split_at_mut(n);
        match self.system.rates(t, &self.y0[..n], &self.y0[n..], dq, dv) {
            Err(e) => e.at_time(t),
            Ok(()) => rates_error::<S::Partner>(t, &k),
        }
    }

    /// The stages of the current step.
    fn stages(&self) -> Stages<'_> {
        Stages::new(&self.k, 2 * self.n)
    }

    /// F at (t, y) into stage j; Ok(false) when the value is not finite.
    /// F at (t, y) written in place as stage j; Ok(false) when the value is not finite.
    fn eval(&mut self, j: usize, t: f64, from_tmp: bool) -> Result<bool> {
        let (n, m) = (self.n, 2 * self.n);
        let y = if from_tmp { &self.tmp } else { &self.y0 };
        let kj = &mut self.k[j * m..(j + 1) * m];
        let (dq, dv) = kj.split_at_mut(n);
        self.evaluations += 1;
        let r = self.system.rates(t, &y[..n], &y[n..], dq, dv);
        finite_stage(r, kj)
    }

    /// Stage j.
    fn stage(&self, j: usize) -> &[f64] {
        let m = 2 * self.n;
        &self.k[j * m..(j + 1) * m]
    }

    /// tmp = y0 + h Σ_j row_j k_j.
    fn combine(&mut self, h: f64, row: &[f64]) {
        let arg = StageArgument::Y { y0: &self.y0, h };
        combine_stages(&self.k, row, arg, &mut self.tmp);
    }

    /// One trial step of size h from (t, y0); returns the error norm (∞ for non-finite stages). Up to
    /// 6 degrees of freedom on arrays of that fixed length ([`attempt_fixed`](Self::attempt_fixed)),
    /// otherwise on the vectors.
    fn attempt(&mut self, t: f64, h: f64) -> Result<f64> {
        macro_rules! dofs {
            ($(($n:literal, $w:literal))*) => {
                match self.n {
                    $($n => self.attempt_fixed::<$n, $w>(t, h),)*
                    _ => self.attempt_any(t, h),
                }
            };
        }
        dofs!((1, 2)(2, 4)(3, 6)(4, 8)(5, 10)(6, 12))
    }

    /// [`attempt_any`](Self::attempt_any) for N degrees of freedom, y and every stage in arrays of
    /// W = 2N components and the vector field by [`Dynamics::rates_fixed`]: the same operations in
    /// the same order (the same bits), but the stage arguments, the stages and the error sums stay in
    /// registers, and a system whose fixed-size rates inline (`Natural`) is evaluated in place.
    fn attempt_fixed<const N: usize, const W: usize>(&mut self, t: f64, h: f64) -> Result<f64> {
        let s = M::C.len();
        let y0 = match <[f64; W]>::try_from(self.y0.as_slice()) {
            Ok(y0) if W == 2 * N && self.k.len() >= (s + 1) * W => y0,
            _ => return self.attempt_any(t, h),
        };
        let mut y = y0;
        for i in 1..=s {
            let (row, c) = if i < s { (M::A[i], M::C[i]) } else { (M::B, 1.0) };
            let arg = StageArgument::Y { y0: &y0, h };
            y = match arg.fixed(&self.k, row) {
                Some(y) => y,
                None => return self.attempt_any(t, h),
            };
            if i < s && !self.eval_fixed::<N, W>(i, t + c * h, y)? {
                return Ok(f64::INFINITY);
            }
        }
        // The last argument is y₁; F(t + h, y₁) first when the error estimate needs it.
        self.y1.copy_from_slice(&y);
        let fsal_first = Self::fsal_in_error() || self.settings.fixed;
        if fsal_first && !self.eval_fixed::<N, W>(s, t + h, y)? {
            return Ok(f64::INFINITY);
        }
        if self.settings.fixed {
            return Ok(0.0);
        }
        let (atol, rtol) = (self.settings.atol, self.settings.rtol);
        let mut sums = [0.0; 2];
        for (sum, row) in sums.iter_mut().zip(M::ERROR) {
            let e = stage_sum::<W>(&self.k, row);
            for x in 0..W {
                let z = e[x] / error_scale(atol, rtol, y0[x], y[x]);
                *sum += z * z;
            }
        }
        let err = checked_error(M::error_norm(h, sums, W));
        if err <= 1.0 && !fsal_first && !self.eval_fixed::<N, W>(s, t + h, y)? {
            return Ok(f64::INFINITY);
        }
        Ok(err)
    }

    /// F(t, y) by [`Dynamics::rates_fixed`] (which checks that it is finite) written as stage j;
    /// Ok(false) when it is not finite.
    #[inline(always)]
    fn eval_fixed<const N: usize, const W: usize>(&mut self, j: usize, t: f64, y: [f64; W]) -> Result<bool> {
        self.evaluations += 1;
        let (q, v) = split_halves::<N, W>(&y);
        let (dq, dv) = match self.system.rates_fixed::<N>(t, q, v) {
            Ok(r) => r,
            Err(Error::NonFiniteResult { .. } | Error::NonFinite { .. }) => return Ok(false),
            Err(e) => return Err(e),
        };
        self.k[j * W..(j + 1) * W].copy_from_slice(&join_halves::<N, W>(&dq, &dv));
        Ok(true)
    }

    /// Whether the error estimate weighs F(t + h, y₁) (DOPRI5's does, DOP853's does not): only then
    /// is it evaluated before the step is accepted; otherwise a rejected trial does not pay for it,
    /// as in Hairer's codes.
    fn fsal_in_error() -> bool {
        M::ERROR.iter().any(|row| row.len() > M::C.len())
    }

    /// One trial step on the vectors (any number of degrees of freedom).
    fn attempt_any(&mut self, t: f64, h: f64) -> Result<f64> {
        let s = M::C.len();
        for i in 1..s {
            self.combine(h, M::A[i]);
            if !self.eval(i, t + M::C[i] * h, true)? {
                return Ok(f64::INFINITY);
            }
        }
        self.combine(h, M::B);
        self.y1.copy_from_slice(&self.tmp);
        let fsal_first = Self::fsal_in_error() || self.settings.fixed;
        if fsal_first && !self.eval(s, t + h, true)? {
            return Ok(f64::INFINITY);
        }
        if self.settings.fixed {
            return Ok(0.0);
        }
        let (atol, rtol, k) = (self.settings.atol, self.settings.rtol, self.stages());
        let mut sums = [0.0; 2];
        for x in 0..self.y0.len() {
            let sk = error_scale(atol, rtol, self.y0[x], self.y1[x]);
            for (sum, row) in sums.iter_mut().zip(M::ERROR) {
                let z = k.weighted(row, x) / sk;
                *sum += z * z;
            }
        }
        let err = checked_error(M::error_norm(h, sums, self.y0.len()));
        if err <= 1.0 && !fsal_first && !self.eval(s, t + h, true)? {
            return Ok(f64::INFINITY);
        }
        Ok(err)
    }

    fn build_dense(&mut self, t: f64, h: f64) -> Result<()> {
        let s = M::C.len();
        for (j, (c, row)) in M::DENSE_STAGES.iter().enumerate() {
            self.combine(h, row);
            if !self.eval(s + 1 + j, t + c * h, true)? {
                return Err(Error::NonFiniteResult {
                    what: "rates",
                    t,
                    component: None,
                });
            }
        }
        let mut coeffs = match self.dense.take() {
            Some(d) => d.into_coefficients(),
            None => Vec::new(),
        };
        if coeffs.len() != M::DENSE_LEN {
            coeffs = vec![vec![0.0; 2 * self.n]; M::DENSE_LEN];
        }
        M::dense_coefficients(h, self.stages(), &self.y0, &self.y1, &mut coeffs);
        let eval: DenseEval = M::dense_eval;
        self.dense = Some(DenseOutput::from_coefficients(
            t,
            h,
            M::DENSE_ORDER,
            self.y0.clone(),
            coeffs,
            eval,
        ));
        Ok(())
    }

    /// An initial step size for (t, state) by Hairer's `hinit`: h such that the explicit Euler step
    /// and the second derivative estimate give a local error ≈ 0.01 in the scaled norm.
    fn hinit<K: crate::Partner>(&mut self, state: &State<K>) -> Result<f64> {
        self.check_parameters()?;
        state.validate(self.n)?;
        let n2 = 2 * self.n;
        self.load(state);
        self.fsal = None;
        if !self.eval(0, state.t, false)? {
            return Err(self.start_error(state.t));
        }
        let y0 = self.y0.clone();
        let k0 = self.stage(0).to_vec();
        let mut f1 = vec![0.0; n2];
        let last = M::C.len() + M::DENSE_STAGES.len();
        let (atol, rtol) = (self.settings.atol, self.settings.rtol);
        let h = initial_step_size(M::ORDER, atol, rtol, &y0, &k0, &mut f1, |h, f1| {
            self.tmp
                .iter_mut()
                .enumerate()
                .for_each(|(i, y)| *y = y0[i] + h * k0[i]);
            let ok = self.eval(last, state.t + h, true)?;
            f1.copy_from_slice(self.stage(last));
            Ok(ok)
        })?;
        // F(t, y₀) is the first stage of the first step (as in Hairer's codes, which evaluate it
        // once): keep it where a step looks for the FSAL stage.
        let s = M::C.len();
        self.k[s * n2..(s + 1) * n2].copy_from_slice(&k0);
        self.y1.copy_from_slice(&self.y0);
        self.fsal = Some(state.t);
        Ok(h)
    }

    fn load<K: crate::Partner>(&mut self, state: &State<K>) {
        let n = self.n;
        self.y0[..n].copy_from_slice(state.q.as_slice());
        self.y0[n..].copy_from_slice(state.v.as_slice());
    }
}

impl<S: Dynamics, M: EmbeddedPair> Stepper for Adaptive<S, M> {
    type Partner = S::Partner;
    /// One accepted step, trying `h` first (shrinking it after rejections). `StepInfo::h` is the
    /// step taken, `h_next` the controller's proposal, `rejected` the rejected trials.
    fn step(&mut self, state: &mut State<S::Partner>, h: f64) -> Result<StepInfo> {
        check_step(h)?;
        state.validate(self.n)?;
        check_time_resolution(state.t, h)?;
        self.system
            .admissible(state.t, state.q.as_slice(), state.v.as_slice())?;
        let evaluations = self.evaluations;
        let t = state.t;
        let reuse = self.fsal == Some(t)
            && self.y1[..self.n] == *state.q.as_slice()
            && self.y1[self.n..] == *state.v.as_slice();
        self.load(state);
        if reuse {
            let (s, m) = (M::C.len(), 2 * self.n);
            self.k.copy_within(s * m..(s + 1) * m, 0);
        } else if !self.eval(0, t, false)? {
            return Err(self.start_error(t));
        }
        self.fsal = None;
        let c = self.settings.controller;
        let alpha = 1.0 / M::CONTROL_ORDER - 0.75 * c.beta;
        let (mut h, mut rejected, mut last_err) = (h, 0, f64::NAN);
        loop {
            check_underflow(t, h, self.settings.h_min, last_err)?;
            let err = self.attempt(t, h)?;
            if err <= 1.0 {
                let mut h_next = if self.settings.fixed {
                    h
                } else {
                    h / c.accepted_divisor(err, self.err_prev, alpha)
                };
                if rejected > 0 {
                    h_next = h_next.min(h);
                }
                self.err_prev = err.max(1e-4);
                if self.settings.dense_allowed && self.settings.dense_requested {
                    self.build_dense(t, h)?;
                } else {
                    self.dense = None;
                }
                state.q.as_mut_slice().copy_from_slice(&self.y1[..self.n]);
                state.v.as_mut_slice().copy_from_slice(&self.y1[self.n..]);
                state.t = t + h;
                self.fsal = Some(state.t);
                return Ok(StepInfo::fixed(h)
                    .with_control(rejected, h_next)
                    .with_evaluations(self.evaluations - evaluations));
            }
            if self.settings.fixed {
                return Err(Error::NonFiniteResult {
                    what: "rates",
                    t,
                    component: None,
                });
            }
            rejected += 1;
            last_err = err;
            h /= c.rejected_divisor(err, alpha);
        }
    }
    fn dof(&self) -> usize {
        self.n
    }
    fn order(&self) -> u32 {
        M::ORDER
    }
    fn name(&self) -> &'static str {
        M::NAME
    }
    fn is_adaptive(&self) -> bool {
        !self.settings.fixed
    }
    /// Hairer's `hinit`: h such that the explicit Euler step and the second-derivative estimate give a
    /// local error ≈ 0.01 in the scaled norm.
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
}

/// Ψ of the accepted step with its step size h frozen (the derivative of y₀ ↦ y₁ at the h taken, after
/// any rejected trials): the method's main stages differentiated as an explicit Runge-Kutta method,
/// K_i = J(t + c_i h, Y_i)(I + h Σ_{j<i} a_ij K_j), Ψ = I + h Σ_i b_i K_i, with the tableau of
/// [`EmbeddedPair`] ([`EmbeddedPair::A`], [`EmbeddedPair::B`], [`EmbeddedPair::C`]). The controller's
/// dependence of h on y₀ (through the error estimate) is not part of Ψ.
impl<S: crate::integrators::LinearizedDynamics, M: EmbeddedPair> crate::TangentStepper for Adaptive<S, M> {
    fn step_tangent(
        &mut self,
        state: &mut State<S::Partner>,
        h: f64,
        psi: &mut nalgebra::DMatrix<f64>,
    ) -> Result<StepInfo> {
        crate::tangent::check_tangent_shape(psi, self.n)?;
        crate::tangent::step_then_tangent(self, state, h, |m, s, info| {
            crate::tangent::explicit_rk_tangent(
                &m.system,
                (s.t, s.q.as_slice(), s.v.as_slice()),
                info.h,
                (M::A, M::B, M::C),
                psi,
            )
        })
    }
}

/// (y[..N], y[N..2N]) as arrays, in a function generic in the lengths only, not in the
/// model (`array::from_fn` in a model-generic method is a copy of its machinery per model).
#[inline(always)]
fn split_halves<const N: usize, const W: usize>(y: &[f64; W]) -> ([f64; N], [f64; N]) {
    let (mut a, mut b) = ([0.0; N], [0.0; N]);
    a.copy_from_slice(&y[..N]);
    b.copy_from_slice(&y[N..2 * N]);
    (a, b)
}

/// [a, b] in one array of W = 2N entries (the inverse of [`split_halves`]).
#[inline(always)]
fn join_halves<const N: usize, const W: usize>(a: &[f64; N], b: &[f64; N]) -> [f64; W] {
    let mut y = [0.0; W];
    y[..N].copy_from_slice(a);
    y[N..2 * N].copy_from_slice(b);
    y
}
