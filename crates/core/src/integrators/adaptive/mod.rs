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

mod stages;

use super::step_control::{
    check_start, check_tolerances, checked_error, controlled_stepper, error_scale, finite_stage,
    initial_step_size, rates_error, settings_methods, until_accepted_pi, Settings, Tolerances,
};
pub use super::step_control::{Controller, RTOL_FLOOR};
pub use stages::Stages;
pub(super) use stages::{combine_stages, stage_sum, StageArgument};
use stages::{join_halves, split_halves};

use crate::dense::DenseEval;
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
    settings: Settings<Tolerances>,
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
            settings: Settings::new(Tolerances::new(M::CONTROLLER)),
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

    settings_methods!(tolerances, "the vector field");

    fn check_parameters(&self) -> Result<()> {
        let c = self.settings.control;
        check_tolerances(c.atol, c.rtol, self.settings.h_min)
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
        let (atol, rtol) = (self.settings.control.atol, self.settings.control.rtol);
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
        let (atol, rtol, k) = (
            self.settings.control.atol,
            self.settings.control.rtol,
            self.stages(),
        );
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
        let last = M::C.len() + M::DENSE_STAGES.len();
        let tolerances = (self.settings.control.atol, self.settings.control.rtol);
        let h = initial_step_size(M::ORDER, tolerances, &y0, &k0, |h, d| {
            self.tmp
                .iter_mut()
                .enumerate()
                .for_each(|(i, y)| *y = y0[i] + h * k0[i]);
            let ok = self.eval(last, state.t + h, true)?;
            for ((d, f1), f0) in d.iter_mut().zip(self.stage(last)).zip(&k0) {
                *d = f1 - f0;
            }
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

    /// The start of a step from `state`: y₀ loaded and its first stage F(t, y₀), the last step's
    /// F(t + h, y₁) when the step starts where that one ended (FSAL), evaluated otherwise.
    fn start(&mut self, state: &State<S::Partner>) -> Result<()> {
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
        Ok(())
    }

    /// Accepts the trial of size h from t: its dense output when the driver wants one, then
    /// `state` = (t + h, y₁), whose F is the first stage of the next step.
    fn accept(&mut self, state: &mut State<S::Partner>, t: f64, h: f64) -> Result<()> {
        if self.settings.dense() {
            self.build_dense(t, h)?;
        } else {
            self.dense = None;
        }
        state.q.as_mut_slice().copy_from_slice(&self.y1[..self.n]);
        state.v.as_mut_slice().copy_from_slice(&self.y1[self.n..]);
        state.t = t + h;
        self.fsal = Some(state.t);
        Ok(())
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
        check_start(&self.system, self.n, state, h)?;
        let evaluations = self.evaluations;
        let t = state.t;
        self.start(state)?;
        let settings = self.settings;
        let trial = until_accepted_pi(&settings, M::CONTROL_ORDER, (t, h), "rates", |h| {
            self.attempt(t, h)
        })?;
        let h_next = trial.next_step(&settings, &mut self.err_prev);
        self.accept(state, t, trial.h)?;
        Ok(trial.info(h_next, self.evaluations - evaluations))
    }
    controlled_stepper!(order: M::ORDER, name: M::NAME);
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
