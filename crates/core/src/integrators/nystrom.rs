//! Runge-Kutta-Nyström pairs with error control for second-order systems q̈ = f(q): the
//! Dormand-El-Mikkawy-Prince methods DPRKN 6(4), 8(6) and 12(10).
//!
//! A Nyström method steps (q, q̇) of q̈ = f(q) with stages on positions only:
//!
//! ```text
//! Q_i = q₀ + h (c_i q̇₀ + h Σ_j a_ij k_j),   k_i = f(Q_i),   i = 1..s,
//! q₁ = q₀ + h (q̇₀ + h Σ_i b_i k_i),          q̇₁ = q̇₀ + h Σ_i b'_i k_i.
//! ```
//!
//! An s-stage Nyström method of order p costs s evaluations of f (the accelerations alone, no
//! velocity rates), where a first-order Runge-Kutta method of the same order needs more stages on
//! twice the unknowns: DPRKN 8(6) takes 9 stages (8 new per step, the last one is f(q₁), reused as the
//! next first stage: FSAL) against DOP853's 12.
//!
//! Error control: the embedded pair gives the local error estimates
//! e_q = h² Σ_i (b_i − b̂_i) k_i on q and e_q̇ = h Σ_i (b'_i − b̂'_i) k_i on q̇, measured like the
//! first-order pairs of [`adaptive`](super::adaptive) (as OrdinaryDiffEq.jl does for these methods),
//!
//! ```text
//! err = sqrt( (1/2n) Σ_i [ (e_q,i / sk_q,i)² + (e_q̇,i / sk_q̇,i)² ] ),  sk = atol + rtol·max(|y₀|, |y₁|),
//! ```
//!
//! with the PI controller, the rejection of non-finite stages and the step-size underflow of
//! [`Adaptive`](super::Adaptive); the controller order is the local order p̂ + 1 of the estimate
//! (5, 7 and 11).
//!
//! Systems: a [`SplitDynamics`] whose drift is the identity, q̇ = v
//! ([`drift_is_identity`](SplitDynamics::drift_is_identity)): [`Natural`](crate::Natural) and
//! noether-particles' systems, with f(q) = [`kick_rate`](SplitDynamics::kick_rate)(q) (which does not
//! depend on t). Any other split system (a separable Hamiltonian on (q, p)) is refused by
//! [`Nystrom::new`] with [`Error::Unsupported`].
//!
//! Dense output (built only when the driver asks for it):
//! - DPRKN 6(4): the published continuous extension of the pair, free (no extra stage), polynomials of
//!   degree 6 in θ for q and 5 for q̇; order 5 measured on Kepler (local error O(h⁶) at θ = 1/4),
//!   for q and q̇ alike;
//! - DPRKN 8(6) and 12(10) (no published extension without extra stages): Hermite interpolation of
//!   q through q, q̇, q̈ = f(q) at the nodes the run has, q̇ being the derivative of the polynomial in
//!   q. When the step continues the previous accepted one (same q and q̇, step ratio in [1/4, 4]) the
//!   polynomial has degree 8 through the previous step's start and both ends of this step: order 8
//!   in q and 7 in q̇, so 7 overall. Otherwise (the first step, after a change of the state between
//!   steps) it is the quintic through both ends of the step: order 5 in q, 4 in q̇ (the quartic
//!   through q̇ and q̈ at both ends with ∫q̇ = q₁ − q₀). The order each step's interpolant has is in
//!   [`DenseOutput::order`]. DPRKN 12(10) spends one more evaluation, f(q₁), on its dense output,
//!   which the next step reuses.
//!
//! The coefficients are OrdinaryDiffEq.jl's exact rationals (and, for DPRKN 6(4), expressions in
//! √8581) evaluated to 60 digits and rounded to f64; the quadrature conditions Σ b_i c_i^k =
//! 1/((k+1)(k+2)) and Σ b'_i c_i^k = 1/(k+1) were checked exactly to the orders of the pair and of its
//! embedded formula when transcribed, and the tests check the row sums Σ_j a_ij = c_i²/2, Σ b = 1/2,
//! Σ b' = 1 and the observed orders.
//!
//! # References
//! - J. R. Dormand, M. E. A. El-Mikkawy, P. J. Prince, Families of Runge-Kutta-Nyström formulae, IMA
//!   J. Numer. Anal. 7 (1987) 235-250 (RKN6(4)6FD, with its dense output).
//! - J. R. Dormand, M. E. A. El-Mikkawy, P. J. Prince, High-order embedded Runge-Kutta-Nyström
//!   formulae, IMA J. Numer. Anal. 7 (1987) 423-430 (RKN8(6)9, RKN12(10)17).
//! - OrdinaryDiffEq.jl, lib/OrdinaryDiffEqRKN/src/rkn_tableaus.jl (`DPRKN6`, `DPRKN8`, `DPRKN12`).
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed., II.14
//!   (Nyström methods, order conditions).

use super::adaptive::{
    check_tolerances, check_underflow, checked_error, combine_stages, error_scale, finite_stage,
    initial_step_size, settings_methods, stage_sum, Controller, Settings, StageArgument, Stages,
};
use super::SplitDynamics;
use crate::error::{check_step, check_time_resolution};
use crate::{DenseOutput, Error, Result, State, StepInfo, Stepper};

/// The coefficients of an embedded Runge-Kutta-Nyström pair for q̈ = f(q) (see the [module](self)
/// docs).
pub trait NystromPair {
    /// Short name.
    const NAME: &'static str;
    /// Order of the propagated solution.
    const ORDER: u32;
    /// Controller order q: the step size scales like err^(−1/q) (the local order of the estimate).
    const CONTROL_ORDER: f64;
    /// Default step-size controller.
    const CONTROLLER: Controller;
    /// Nodes c_i of the s stages.
    const C: &'static [f64];
    /// Rows a_i (length i) of the s stages.
    const A: &'static [&'static [f64]];
    /// Weights b_i of q₁.
    const B: &'static [f64];
    /// Weights b'_i of q̇₁.
    const BP: &'static [f64];
    /// Weights b_i − b̂_i of the error estimate on q.
    const B_ERR: &'static [f64];
    /// Weights b'_i − b̂'_i of the error estimate on q̇.
    const BP_ERR: &'static [f64];
    /// The last stage is f(q₁) (c_s = 1, a_s = b): first stage of the next step.
    const FSAL: bool;
    /// Order of the dense output.
    const DENSE_ORDER: u32;
    /// Number of coefficient vectors of the dense polynomial.
    const DENSE_LEN: usize;
    /// The dense output is the default Hermite interpolant, raised to degree 8 with the previous
    /// step's start when there is one (see the [module](self) docs).
    const HERMITE: bool;

    /// The dense polynomial y(θ) = y₀ + θ Σ_m `out[m]` θ^m on y = (q, q̇) (each `out[m]` of length 2n)
    /// of a step of size h from (q₀, v₀) to (q₁, v₁), from the stages `k` (`k.get(j, x)` is
    /// component x of stage j) and a₁ = f(q₁). The default is the quintic Hermite interpolant of q through q, q̇, q̈ at both ends
    /// and its derivative for q̇ (order 4; see the [module](self) docs).
    #[allow(clippy::too_many_arguments)]
    fn dense_coefficients(
        h: f64,
        k: Stages<'_>,
        q0: &[f64],
        v0: &[f64],
        q1: &[f64],
        v1: &[f64],
        a1: &[f64],
        out: &mut [Vec<f64>],
    ) {
        let n = q0.len();
        let h2 = h * h;
        // q(θ) = q₀ + d₁θ + d₂θ² + d₃θ³ + d₄θ⁴ + d₅θ⁵ with d₁ = h q̇₀, d₂ = h² q̈₀/2 and d₃..d₅ from
        // q(1) = q₁, q'(1) = h q̇₁, q''(1) = h² q̈₁: with the residuals Δ = q₁ − q₀ − d₁ − d₂,
        // V = h(q̇₁ − q̇₀) − h² q̈₀, A = h²(q̈₁ − q̈₀): d₃ = 10Δ − 4V + A/2, d₄ = −15Δ + 7V − A,
        // d₅ = 6Δ − 3V + A/2. q̇(θ) = q'(θ)/h = q̇₀ + θ Σ_{m≥0} (m+2) d_{m+2}/h θ^m.
        for i in 0..n {
            let a0 = k.get(0, i);
            let d1 = h * v0[i];
            let d2 = 0.5 * h2 * a0;
            let delta = q1[i] - q0[i] - d1 - d2;
            let vv = h * (v1[i] - v0[i]) - h2 * a0;
            let aa = h2 * (a1[i] - a0);
            let d3 = 10.0 * delta - 4.0 * vv + 0.5 * aa;
            let d4 = -15.0 * delta + 7.0 * vv - aa;
            let d5 = 6.0 * delta - 3.0 * vv + 0.5 * aa;
            out[0][i] = d1;
            out[1][i] = d2;
            out[2][i] = d3;
            out[3][i] = d4;
            out[4][i] = d5;
            out[0][n + i] = 2.0 * d2 / h;
            out[1][n + i] = 3.0 * d3 / h;
            out[2][n + i] = 4.0 * d4 / h;
            out[3][n + i] = 5.0 * d5 / h;
            out[4][n + i] = 0.0;
            for c in out[5..].iter_mut() {
                c[i] = 0.0;
                c[n + i] = 0.0;
            }
        }
    }
}

/// y(θ) = y₀ + θ Σ_m `c[m]` θ^m (Horner), the evaluation of every Nyström dense output.
fn dense_eval(theta: f64, y0: &[f64], c: &[Vec<f64>], out: &mut [f64]) {
    let last = c.len() - 1;
    for i in 0..y0.len() {
        let mut acc = c[last][i];
        for cm in c[..last].iter().rev() {
            acc = cm[i] + theta * acc;
        }
        out[i] = y0[i] + theta * acc;
    }
}

/// An adaptive Runge-Kutta-Nyström pair `M` stepping a second-order system q̈ = f(q) (see the
/// [module](self) docs): same settings as [`Dop853`](super::Dop853).
///
/// ```
/// use noether_core::prelude::*;
/// struct Spring;
/// impl Potential for Spring {
///     fn dof(&self) -> usize { 1 }
///     fn potential<D: Scalar>(&self, q: &[D]) -> D { q[0] * q[0] * 0.5 }
/// }
/// let rkn = Dprkn8::new(Natural::unit(Spring))?.tolerances(1e-12, 1e-12)?;
/// let sol = Driver::new(rkn, State::new(0.0, [1.0], [0.0]))?
///     .save(Save::Times(vec![1.0, 2.0]))?
///     .run_until(10.0)?;
/// assert!((sol.q(0)[0] - 1f64.cos()).abs() < 1e-9); // q = cos t, from the dense output
/// assert!((sol.last().q[0] - 10f64.cos()).abs() < 1e-10);
/// // A separable Hamiltonian on (q, p) is not q̈ = f(q) in these variables: refused.
/// assert!(Dprkn8::new(SeparableHamiltonian(Natural::unit(Spring))).is_err());
/// # Ok::<(), noether_core::Error>(())
/// ```
pub struct Nystrom<S: SplitDynamics, M> {
    system: S,
    settings: Settings,
    n: usize,
    /// The s stage accelerations one after the other: k[j·n + x] is component x of stage j.
    k: Vec<f64>,
    q0: Vec<f64>,
    v0: Vec<f64>,
    q1: Vec<f64>,
    v1: Vec<f64>,
    /// Stage positions and accelerations.
    qs: Vec<f64>,
    /// f(q₁) after an accepted step (valid when `fsal`).
    a1: Vec<f64>,
    /// Start (q, q̇, q̈) and size of the previous accepted step when the current one continues it
    /// (valid when `prev`): the third node of the degree-8 Hermite dense output.
    qp: Vec<f64>,
    vp: Vec<f64>,
    ap: Vec<f64>,
    hp: f64,
    prev: bool,
    /// Size of the last accepted step.
    h_last: f64,
    fsal: bool,
    err_prev: f64,
    dense: Option<DenseOutput<S::Partner>>,
    /// Buffers of the last dense output, refilled by the next.
    spare: Option<(Vec<f64>, Vec<Vec<f64>>)>,
    evaluations: usize,
    _method: std::marker::PhantomData<M>,
}

impl<S: SplitDynamics, M: NystromPair> Nystrom<S, M> {
    /// The method for `system` with atol = rtol = 1e-9, dense output allowed; [`Error::Unsupported`]
    /// unless the system's drift is q̇ = v.
    pub fn new(system: S) -> Result<Self> {
        if !system.drift_is_identity() {
            return Err(Error::Unsupported(
                "Runge-Kutta-Nyström methods need q̇ = v (a Natural or particle system), not a drift q̇ = D(p)",
            ));
        }
        let n = system.dof();
        let s = M::C.len();
        Ok(Nystrom {
            system,
            settings: Settings::new(M::CONTROLLER),
            n,
            k: vec![0.0; s * n],
            q0: vec![0.0; n],
            v0: vec![0.0; n],
            q1: vec![0.0; n],
            v1: vec![0.0; n],
            qs: vec![0.0; n],
            a1: vec![0.0; n],
            qp: vec![0.0; n],
            vp: vec![0.0; n],
            ap: vec![0.0; n],
            hp: 0.0,
            prev: false,
            h_last: 0.0,
            fsal: false,
            err_prev: 1e-4,
            dense: None,
            spare: Some((vec![0.0; 2 * n], vec![vec![0.0; 2 * n]; M::DENSE_LEN])),
            evaluations: 0,
            _method: std::marker::PhantomData,
        })
    }

    settings_methods!("f");

    /// f(q) into `out`; Ok(false) when not finite.
    #[inline]
    fn accel(system: &S, evaluations: &mut usize, q: &[f64], out: &mut [f64]) -> Result<bool> {
        *evaluations += 1;
        finite_stage(system.kick_rate(q, out), out)
    }

    /// One trial step of size h from (q₀, v₀) with k₁ = f(q₀) in place: fills q₁, v₁ and returns the
    /// error norm (∞ for non-finite stages or results, 0 in fixed-step mode). Up to 6 degrees of
    /// freedom on arrays of that length ([`attempt_fixed`](Self::attempt_fixed)), otherwise on the
    /// vectors.
    fn attempt(&mut self, h: f64) -> Result<f64> {
        macro_rules! dofs {
            ($($n:literal)*) => {
                match self.n {
                    $($n => self.attempt_fixed::<$n>(h),)*
                    _ => self.attempt_any(h),
                }
            };
        }
        dofs!(1 2 3 4 5 6)
    }

    /// [`attempt_any`](Self::attempt_any) for N degrees of freedom, q₀, q̇₀, the stage positions and
    /// the sums in arrays and f by [`SplitDynamics::kick_rate_fixed`]: the same operations in the
    /// same order (the same bits), with everything in registers and `Natural`'s kernel inlined.
    fn attempt_fixed<const N: usize>(&mut self, h: f64) -> Result<f64> {
        let s = M::C.len();
        let (q0, v0) = match (
            <[f64; N]>::try_from(self.q0.as_slice()),
            <[f64; N]>::try_from(self.v0.as_slice()),
        ) {
            (Ok(q0), Ok(v0)) if self.k.len() >= s * N => (q0, v0),
            _ => return self.attempt_any(h),
        };
        let mut qs = q0;
        for i in 1..s {
            let arg = StageArgument::Nystrom {
                q0: &q0,
                v0: &v0,
                c: M::C[i],
                h,
            };
            qs = match arg.fixed::<N>(&self.k, M::A[i]) {
                Some(q) => q,
                None => return self.attempt_any(h),
            };
            self.evaluations += 1;
            let ki = match self.system.kick_rate_fixed(qs) {
                Ok(k) => k,
                Err(Error::NonFiniteResult { .. } | Error::NonFinite { .. }) => return Ok(f64::INFINITY),
                Err(e) => return Err(e),
            };
            self.k[i * N..(i + 1) * N].copy_from_slice(&ki);
        }
        let [b, bp, be, bpe] = [M::B, M::BP, M::B_ERR, M::BP_ERR].map(|w| stage_sum::<N>(&self.k, w));
        let (atol, rtol, h2) = (self.settings.atol, self.settings.rtol, h * h);
        let (mut q1, mut v1, mut sq) = ([0.0; N], [0.0; N], 0.0);
        for x in 0..N {
            // FSAL: the last stage was evaluated at q₀ + h(q̇₀ + h Σ b_j k_j) = q₁, computed so.
            q1[x] = if M::FSAL {
                qs[x]
            } else {
                q0[x] + h * (v0[x] + h * b[x])
            };
            v1[x] = v0[x] + h * bp[x];
            let eq = h2 * be[x] / error_scale(atol, rtol, q0[x], q1[x]);
            let ev = h * bpe[x] / error_scale(atol, rtol, v0[x], v1[x]);
            sq += eq * eq + ev * ev;
        }
        self.q1.copy_from_slice(&q1);
        self.v1.copy_from_slice(&v1);
        self.error_from(sq)
    }

    /// The error norm from Σ (scaled estimates)² over q₁ and q̇₁ in place: ∞ when q₁, q̇₁ or the norm
    /// are not finite, 0 in fixed-step mode.
    fn error_from(&self, sq: f64) -> Result<f64> {
        let n = self.n;
        if self.q1.iter().chain(&self.v1).any(|x| !x.is_finite()) {
            return Ok(f64::INFINITY);
        }
        if self.settings.fixed || n == 0 {
            return Ok(0.0);
        }
        Ok(checked_error((sq / (2 * n) as f64).sqrt()))
    }

    /// One trial step on the vectors (any number of degrees of freedom).
    fn attempt_any(&mut self, h: f64) -> Result<f64> {
        let n = self.n;
        let s = M::C.len();
        // Stage i's argument q₀ + h(cᵢ q̇₀ + h Σ_j a_ij k_j) by `combine_stages` (fixed width for small
        // n), and f written in place as stage i.
        for i in 1..s {
            let (a, c) = (M::A[i], M::C[i]);
            let arg = StageArgument::Nystrom {
                q0: &self.q0,
                v0: &self.v0,
                c,
                h,
            };
            combine_stages(&self.k, a, arg, &mut self.qs);
            let ki = &mut self.k[i * n..(i + 1) * n];
            if !Self::accel(&self.system, &mut self.evaluations, &self.qs, ki)? {
                return Ok(f64::INFINITY);
            }
        }
        let (atol, rtol, h2) = (self.settings.atol, self.settings.rtol, h * h);
        let mut sq = 0.0;
        for x in 0..n {
            // The four sums of the solution and the estimate in one pass over the stages.
            let kx = self.k[x..].iter().step_by(n.max(1));
            let (mut b, mut bp, mut be, mut bpe) = (0.0, 0.0, 0.0, 0.0);
            let weights = M::B.iter().zip(M::BP).zip(M::B_ERR).zip(M::BP_ERR);
            // Zero weights left out, as in `stage_sum` (the same bits as the fixed-size path).
            let add = |sum: &mut f64, w: f64, k: f64| {
                if w != 0.0 {
                    *sum += w * k
                }
            };
            for (k, (((wb, wbp), wbe), wbpe)) in kx.zip(weights) {
                add(&mut b, *wb, *k);
                add(&mut bp, *wbp, *k);
                add(&mut be, *wbe, *k);
                add(&mut bpe, *wbpe, *k);
            }
            // FSAL: the last stage was evaluated at q₀ + h(q̇₀ + h Σ b_j k_j) = q₁, computed so.
            let q1 = if M::FSAL {
                self.qs[x]
            } else {
                self.q0[x] + h * (self.v0[x] + h * b)
            };
            let v1 = self.v0[x] + h * bp;
            self.q1[x] = q1;
            self.v1[x] = v1;
            let eq = h2 * be / error_scale(atol, rtol, self.q0[x], q1);
            let ev = h * bpe / error_scale(atol, rtol, self.v0[x], v1);
            sq += eq * eq + ev * ev;
        }
        self.error_from(sq)
    }

    /// The dense output of the accepted step [t, t + h] (q₁, v₁ and a₁ = f(q₁) in place).
    fn build_dense(&mut self, t: f64, h: f64) {
        let n = self.n;
        let (mut y0, mut coeffs) = match (self.dense.take(), self.spare.take()) {
            (Some(d), _) => d.into_parts(),
            (None, Some(parts)) => parts,
            (None, None) => (vec![0.0; 2 * n], vec![vec![0.0; 2 * n]; M::DENSE_LEN]),
        };
        y0[..n].copy_from_slice(&self.q0);
        y0[n..].copy_from_slice(&self.v0);
        M::dense_coefficients(
            h,
            Stages::new(&self.k, n),
            &self.q0,
            &self.v0,
            &self.q1,
            &self.v1,
            &self.a1,
            &mut coeffs,
        );
        let r = self.hp / h;
        let order = if M::HERMITE && self.prev && (0.25..=4.0).contains(&r) {
            self.raise_hermite(h, &mut coeffs);
            7
        } else {
            M::DENSE_ORDER
        };
        self.dense = Some(DenseOutput::from_coefficients(
            t, h, order, y0, coeffs, dense_eval,
        ));
    }

    /// Raises the quintic Hermite polynomial in `c` (through q, q̇, q̈ at θ = 0 and 1) to the degree-8
    /// polynomial that also passes through q, q̇, q̈ at the previous step's start θₚ = −hₚ/h:
    /// q(θ) = H₅(θ) + w(θ) p(θ) with w = θ³(θ − 1)³ and p quadratic, p, p′, p″ at θₚ solved from the
    /// three conditions there. Order 8 in q and 7 in q̇ (its derivative), for step ratios hₚ/h in
    /// [1/4, 4] (outside, the divisions by w(θₚ) would amplify the data's rounding).
    fn raise_hermite(&self, h: f64, c: &mut [Vec<f64>]) {
        let n = self.n;
        let tp = -self.hp / h;
        let (u, u1) = (tp, tp - 1.0);
        let w = u.powi(3) * u1.powi(3);
        let w1 = 3.0 * u * u * u1.powi(3) + 3.0 * u.powi(3) * u1 * u1;
        let w2 = 6.0 * u * u1.powi(3) + 18.0 * u * u * u1 * u1 + 6.0 * u.powi(3) * u1;
        // w(θ) = θ⁶ − 3θ⁵ + 3θ⁴ − θ³: coefficients of θ³..θ⁶.
        const W: [f64; 4] = [-1.0, 3.0, -3.0, 1.0];
        for x in 0..n {
            // d[k]: coefficient of θ^k of q(θ) − q₀, k = 1..8 (d[0] = 0).
            let mut d = [0.0; 9];
            for k in 1..=5 {
                d[k] = c[k - 1][x];
            }
            let (mut hv, mut hd1, mut hd2) = (0.0, 0.0, 0.0);
            for k in (1..=5).rev() {
                hv = hv * tp + d[k];
            }
            hv *= tp;
            for k in (1..=5).rev() {
                hd1 = hd1 * tp + k as f64 * d[k];
            }
            for k in (2..=5).rev() {
                hd2 = hd2 * tp + (k * (k - 1)) as f64 * d[k];
            }
            let target = self.qp[x] - self.q0[x];
            let p0 = (target - hv) / w;
            let p1 = (h * self.vp[x] - hd1 - w1 * p0) / w;
            let p2 = (h * h * self.ap[x] - hd2 - w2 * p0 - 2.0 * w1 * p1) / w;
            // p(θ) = p0 + p1 (θ − θₚ) + p2/2 (θ − θₚ)² in powers of θ.
            let pm = [p0 - p1 * tp + 0.5 * p2 * tp * tp, p1 - p2 * tp, 0.5 * p2];
            for (j, wj) in W.iter().enumerate() {
                for (i, pi) in pm.iter().enumerate() {
                    d[3 + j + i] += wj * pi;
                }
            }
            for k in 1..=8 {
                c[k - 1][x] = d[k];
            }
            for m in 0..7 {
                c[m][n + x] = (m + 2) as f64 * d[m + 2] / h;
            }
            c[7][n + x] = 0.0;
        }
    }

    fn load<K: crate::Partner>(&mut self, state: &State<K>) {
        self.q0.copy_from_slice(state.q.as_slice());
        self.v0.copy_from_slice(state.v.as_slice());
    }
}

impl<S: SplitDynamics, M: NystromPair> Stepper for Nystrom<S, M> {
    type Partner = S::Partner;
    /// One accepted step, trying `h` first (shrinking it after rejections). `StepInfo::h` is the
    /// step taken, `h_next` the controller's proposal, `rejected` the rejected trials.
    fn step(&mut self, state: &mut State<S::Partner>, h: f64) -> Result<StepInfo> {
        check_step(h)?;
        state.validate(self.n)?;
        check_time_resolution(state.t, h)?;
        self.system
            .admissible(state.t, state.q.as_slice(), state.v.as_slice())?;
        let n = self.n;
        let evaluations = self.evaluations;
        let t = state.t;
        // f depends on q alone: f(q₁) of the last step is the first stage when the step starts there.
        let reuse = self.fsal && self.q1 == *state.q.as_slice();
        let s = M::C.len();
        // This step continues the last accepted one (same q and q̇): keep that step's start for the
        // dense output (q₀, q̇₀ and k₁ still hold it).
        self.prev = M::HERMITE
            && reuse
            && self.h_last > 0.0
            && self.settings.dense_allowed
            && self.settings.dense_requested
            && self.v1 == *state.v.as_slice();
        if self.prev {
            self.qp.copy_from_slice(&self.q0);
            self.vp.copy_from_slice(&self.v0);
            self.ap.copy_from_slice(&self.k[..n]);
            self.hp = self.h_last;
        }
        self.fsal = false;
        self.h_last = 0.0;
        self.load(state);
        if !reuse && !Self::accel(&self.system, &mut self.evaluations, &self.q0, &mut self.a1)? {
            return Err(Error::NonFiniteResult {
                what: "accelerations",
                t,
                component: None,
            });
        }
        self.k[..n].copy_from_slice(&self.a1);
        let c = self.settings.controller;
        let alpha = 1.0 / M::CONTROL_ORDER - 0.75 * c.beta;
        let (mut h, mut rejected, mut last_err) = (h, 0, f64::NAN);
        loop {
            check_underflow(t, h, self.settings.h_min, last_err)?;
            let err = self.attempt(h)?;
            if err <= 1.0 {
                let dense = self.settings.dense_allowed && self.settings.dense_requested;
                if M::FSAL {
                    self.a1.copy_from_slice(&self.k[(s - 1) * n..s * n]);
                    self.fsal = true;
                } else if dense {
                    if !Self::accel(&self.system, &mut self.evaluations, &self.q1, &mut self.a1)? {
                        return Err(Error::NonFiniteResult {
                            what: "accelerations",
                            t: t + h,
                            component: None,
                        });
                    }
                    self.fsal = true;
                }
                let mut h_next = if self.settings.fixed {
                    h
                } else {
                    h / c.accepted_divisor(err, self.err_prev, alpha)
                };
                if rejected > 0 {
                    h_next = h_next.min(h);
                }
                self.err_prev = err.max(1e-4);
                self.h_last = h;
                if dense {
                    self.build_dense(t, h);
                } else if let Some(d) = self.dense.take() {
                    self.spare = Some(d.into_parts());
                }
                state.q.as_mut_slice().copy_from_slice(&self.q1);
                state.v.as_mut_slice().copy_from_slice(&self.v1);
                state.t = t + h;
                return Ok(StepInfo::fixed(h)
                    .with_control(rejected, h_next)
                    .with_evaluations(self.evaluations - evaluations));
            }
            if self.settings.fixed {
                return Err(Error::NonFiniteResult {
                    what: "accelerations",
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
    /// Hairer's `hinit` on y = (q, q̇), y' = (q̇, f(q)) (see [`Adaptive`](super::Adaptive)); f(q₀) is
    /// kept as the first stage of the first step.
    fn initial_step(&mut self, state: &State<S::Partner>) -> Result<Option<f64>> {
        check_tolerances(self.settings.atol, self.settings.rtol, self.settings.h_min)?;
        state.validate(self.n)?;
        let n = self.n;
        self.fsal = false;
        self.load(state);
        if !Self::accel(&self.system, &mut self.evaluations, &self.q0, &mut self.a1)? {
            return Err(Error::NonFiniteResult {
                what: "accelerations",
                t: state.t,
                component: None,
            });
        }
        self.h_last = 0.0;
        let mut y0 = vec![0.0; 2 * n];
        y0[..n].copy_from_slice(&self.q0);
        y0[n..].copy_from_slice(&self.v0);
        let mut f0 = vec![0.0; 2 * n];
        f0[..n].copy_from_slice(&self.v0);
        f0[n..].copy_from_slice(&self.a1);
        let mut f1 = vec![0.0; 2 * n];
        let (system, evaluations, qs) = (&self.system, &mut self.evaluations, &mut self.qs);
        let h = initial_step_size(
            M::ORDER,
            self.settings.atol,
            self.settings.rtol,
            &y0,
            &f0,
            &mut f1,
            |h, f1| {
                // F(y₀ + hF₀) = (q̇₀ + h f(q₀), f(q₀ + h q̇₀)).
                for x in 0..n {
                    qs[x] = y0[x] + h * f0[x];
                    f1[x] = f0[n + x] * h + y0[n + x];
                }
                Self::accel(system, evaluations, qs, &mut f1[n..])
            },
        )?;
        self.q1.copy_from_slice(&self.q0);
        self.fsal = true;
        Ok(Some(h))
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

/// The DPRKN 6(4) tableau (see the [module](self) docs).
#[derive(Debug, Clone, Copy)]
pub struct Rkn6;

/// Dormand-El-Mikkawy-Prince RKN 6(4): 6 stages (the last is f(q₁): FSAL, 5 new per step), sixth-order
/// solution, fourth-order embedded estimate, a free dense output of order 5.
pub type Dprkn6<S> = Nystrom<S, Rkn6>;

/// Dense-output weights of DPRKN 6(4): b_i(θ) = Σ_m `R6[i][m]` θ^m (q₁ at θ = 1 has weights b_i),
/// b'_i(θ) = Σ_m RP[i][m] θ^m; row 2 is zero (k₂ does not enter).
const R6: [[f64; 5]; 6] = [
    [
        0.5,
        -1.245014245014245,
        1.5161443494776827,
        -0.9066951566951567,
        0.21367521367521367,
    ],
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [
        0.0,
        1.9859371988705032,
        -3.577652872294921,
        2.5384011164109506,
        -0.6583937017967658,
    ],
    [
        0.0,
        -1.8559358276926614,
        5.547586751052329,
        -5.164133553908094,
        1.5949081677229964,
    ],
    [
        0.0,
        2.178649237472767,
        -6.926987319144182,
        7.273336685101391,
        -2.513826043237808,
    ],
    [
        0.0,
        -1.0636363636363637,
        3.440909090909091,
        -3.7409090909090907,
        1.3636363636363635,
    ],
];
/// See [`R6`].
const RP6: [[f64; 5]; 6] = [
    [
        1.0,
        -3.735042735042735,
        6.064577397910731,
        -4.533475783475783,
        1.2820512820512822,
    ],
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [
        0.0,
        5.95781159661151,
        -14.310611489179683,
        12.692005582054751,
        -3.950362210780595,
    ],
    [
        0.0,
        -5.567807483077984,
        22.190347004209315,
        -25.820667769540467,
        9.56944900633798,
    ],
    [
        0.0,
        6.5359477124183005,
        -27.707949276576727,
        36.366683425506956,
        -15.082956259426847,
    ],
    [
        0.0,
        -3.190909090909091,
        13.763636363636364,
        -18.704545454545453,
        8.181818181818182,
    ],
];
impl NystromPair for Rkn6 {
    const NAME: &'static str = "DPRKN 6(4)";
    const ORDER: u32 = 6;
    const CONTROL_ORDER: f64 = 5.0;
    const CONTROLLER: Controller = Controller {
        safety: 0.9,
        fac_min: 0.2,
        fac_max: 10.0,
        beta: 0.04,
    };
    const C: &'static [f64] = &[
        0.0,
        0.12929590313670442,
        0.25859180627340883,
        0.67029708261548,
        0.9,
        1.0,
    ];
    const A: &'static [&'static [f64]] = &[
        &[],
        &[0.008358715283968025],
        &[0.011144953711957367, 0.022289907423914734],
        &[0.1454747428010918, -0.22986064052264749, 0.3090349872029675],
        &[
            -0.20766826295078997,
            0.6863667842925143,
            -0.19954927787234925,
            0.12585075653062489,
        ],
        &[
            0.07811016144349478,
            0.0,
            0.2882917411897668,
            0.12242553717457041,
            0.011172560192168035,
        ],
    ];
    const B: &'static [f64] = &[
        0.07811016144349478,
        0.0,
        0.2882917411897668,
        0.12242553717457041,
        0.011172560192168035,
        0.0,
    ];
    const BP: &'static [f64] = &[
        0.07811016144349478,
        0.0,
        0.3888434787059826,
        0.3713207579288423,
        0.11172560192168035,
        0.05,
    ];
    const B_ERR: &'static [f64] = &[
        -0.9807490989269235,
        2.406751371924452,
        -1.559600370364267,
        0.12242553717457041,
        0.011172560192168035,
        0.0,
    ];
    const BP_ERR: &'static [f64] = &[
        0.023504273504273504,
        0.0,
        -0.07242330719764424,
        0.17543989844952962,
        -0.2765208647561589,
        0.15,
    ];
    const FSAL: bool = true;
    const DENSE_ORDER: u32 = 5;
    const DENSE_LEN: usize = 6;
    const HERMITE: bool = false;

    /// q(θ) = q₀ + hθ(q̇₀ + hθ Σ_i b_i(θ) k_i), q̇(θ) = q̇₀ + hθ Σ_i b'_i(θ) k_i (k₆ = f(q₁)).
    fn dense_coefficients(
        h: f64,
        k: Stages<'_>,
        _q0: &[f64],
        v0: &[f64],
        _q1: &[f64],
        _v1: &[f64],
        _a1: &[f64],
        out: &mut [Vec<f64>],
    ) {
        let n = v0.len();
        let h2 = h * h;
        for x in 0..n {
            out[0][x] = h * v0[x];
            out[5][n + x] = 0.0;
            for m in 0..5 {
                let (mut bq, mut bv) = (0.0, 0.0);
                for i in 0..6 {
                    let ki = k.get(i, x);
                    bq += R6[i][m] * ki;
                    bv += RP6[i][m] * ki;
                }
                out[m + 1][x] = h2 * bq;
                out[m][n + x] = h * bv;
            }
        }
    }
}

/// The DPRKN 8(6) tableau (see the [module](self) docs).
#[derive(Debug, Clone, Copy)]
pub struct Rkn8;

/// Dormand-El-Mikkawy-Prince RKN 8(6): 9 stages (the last is f(q₁): FSAL, 8 new per step), eighth-order
/// solution, sixth-order embedded estimate; quintic Hermite dense output (order 4).
pub type Dprkn8<S> = Nystrom<S, Rkn8>;
impl NystromPair for Rkn8 {
    const NAME: &'static str = "DPRKN 8(6)";
    const ORDER: u32 = 8;
    const CONTROL_ORDER: f64 = 7.0;
    const CONTROLLER: Controller = Controller {
        safety: 0.9,
        fac_min: 0.333,
        fac_max: 6.0,
        beta: 0.0,
    };
    const C: &'static [f64] = &[0.0, 0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0, 1.0];
    const A: &'static [&'static [f64]] = &[
        &[],
        &[0.00125],
        &[0.0016666666666666668, 0.0033333333333333335],
        &[0.045, -0.09, 0.09],
        &[
            -0.3379798532571243,
            0.8611516478170984,
            -0.48613644655235316,
            0.0879646519923791,
        ],
        &[
            0.7461462641043086,
            -1.804347430246737,
            1.2761518285888953,
            -0.031220932716737166,
            0.05827027027027027,
        ],
        &[
            -1.2551623461807584,
            3.257463187064823,
            -2.068866619575089,
            0.4206478455603251,
            -0.018382978723404254,
            0.06930091185410335,
        ],
        &[
            3.772901830095941,
            -9.669613121677195,
            6.7991544547851674,
            -0.8490343907823893,
            0.4671734865470852,
            -0.04939742152466368,
            0.028815162556053812,
        ],
        &[
            0.028092718568909044,
            0.0,
            0.1457093253968254,
            0.1529431216931217,
            0.09151785714285714,
            0.06554705215419501,
            0.01618992504409171,
            0.0,
        ],
    ];
    const B: &'static [f64] = &[
        0.028092718568909044,
        0.0,
        0.1457093253968254,
        0.1529431216931217,
        0.09151785714285714,
        0.06554705215419501,
        0.01618992504409171,
        0.0,
        0.0,
    ];
    const BP: &'static [f64] = &[
        0.028092718568909044,
        0.0,
        0.1618992504409171,
        0.2184901738473167,
        0.18303571428571427,
        0.2184901738473167,
        0.1618992504409171,
        0.028092718568909044,
        0.0,
    ];
    const B_ERR: &'static [f64] = &[
        -0.044557986852984274,
        0.0,
        0.10965442077101599,
        -0.14620589436135464,
        0.1315853049252192,
        -0.06265966901200913,
        0.012183824530112887,
        0.0,
        0.0,
    ];
    const BP_ERR: &'static [f64] = &[
        -0.044557986852984274,
        0.0,
        0.12183824530112887,
        -0.2088655633733638,
        0.2631706098504384,
        -0.2088655633733638,
        0.12183824530112887,
        0.10544201314701572,
        -0.15,
    ];
    const FSAL: bool = true;
    const DENSE_ORDER: u32 = 4;
    const DENSE_LEN: usize = 8;
    const HERMITE: bool = true;
}

/// The DPRKN 12(10) tableau (see the [module](self) docs).
#[derive(Debug, Clone, Copy)]
pub struct Rkn12;

/// Dormand-El-Mikkawy-Prince RKN 12(10): 17 stages (16 new per step, plus f(q₁) for the next step),
/// twelfth-order solution, tenth-order embedded estimate; quintic Hermite dense output (order 4).
pub type Dprkn12<S> = Nystrom<S, Rkn12>;
impl NystromPair for Rkn12 {
    const NAME: &'static str = "DPRKN 12(10)";
    const ORDER: u32 = 12;
    const CONTROL_ORDER: f64 = 11.0;
    const CONTROLLER: Controller = Controller {
        safety: 0.9,
        fac_min: 0.333,
        fac_max: 6.0,
        beta: 0.0,
    };
    const C: &'static [f64] = &[
        0.0,
        0.02,
        0.04,
        0.1,
        0.13333333333333333,
        0.16,
        0.05,
        0.2,
        0.25,
        0.3333333333333333,
        0.5,
        0.5555555555555556,
        0.75,
        0.8571428571428571,
        0.9452162222720143,
        1.0,
        1.0,
    ];
    const A: &'static [&'static [f64]] = &[
        &[],
        &[0.0002],
        &[0.0002666666666666667, 0.0005333333333333334],
        &[0.002916666666666667, -0.004166666666666667, 0.00625],
        &[
            0.0016460905349794238,
            0.0,
            0.0054869684499314125,
            0.0017558299039780521,
        ],
        &[
            0.0019456,
            0.0,
            0.007151746031746032,
            0.0029127111111111113,
            0.0007899428571428571,
        ],
        &[
            0.00056640625,
            0.0,
            0.0008809730489417989,
            -0.0004369212962962963,
            0.00033900669642857143,
            -9.946469907407407e-05,
        ],
        &[
            0.0030833333333333333,
            0.0,
            0.0,
            0.0017777777777777779,
            0.0027,
            0.0015782828282828283,
            0.01086060606060606,
        ],
        &[
            0.00365183937480113,
            0.0,
            0.003965171714072343,
            0.0031972582629306284,
            0.008221467306855435,
            -0.0013130926959572379,
            0.009771586968064868,
            0.003755769069232834,
        ],
        &[
            0.003707241068718501,
            0.0,
            0.005082045854555286,
            0.001174708002175412,
            -0.021147629915126993,
            0.06010463698107881,
            0.02010573476850619,
            -0.02835075012293358,
            0.014879568918581932,
        ],
        &[
            0.03512537656073344,
            0.0,
            -0.008615749195138479,
            -0.005791448051007917,
            1.945554823782616,
            -3.4351238674565137,
            -0.10930701107475221,
            2.3496383118995166,
            -0.7560094086870229,
            0.10952897222156927,
        ],
        &[
            0.020527792537482496,
            0.0,
            -0.00728644676448018,
            -0.0021153556079618403,
            0.9275807968723522,
            -1.6522824844257367,
            -0.02107956300568657,
            1.2065364326207872,
            -0.4137144770010661,
            0.09079873982809654,
            0.005355552600533985,
        ],
        &[
            -0.14324078875545515,
            0.0,
            0.012528703773091817,
            0.006826019163969827,
            -4.799555395574387,
            5.6986250439519415,
            0.7553430369523645,
            -0.12755487858281084,
            -1.9605926051117384,
            0.9185609056635262,
            -0.23880085505284432,
            0.15911081357234216,
        ],
        &[
            0.8045019205520489,
            0.0,
            -0.016658527067011247,
            -0.021415834042629735,
            16.827235928962466,
            -11.172835357176098,
            -3.377159297226324,
            -15.243326655360846,
            17.179835738215417,
            -5.437719239823995,
            1.3878671618364655,
            -0.5925827732652812,
            0.029603873171297354,
        ],
        &[
            -0.913296766697358,
            0.0,
            0.0024112725757805178,
            0.01765812269386174,
            -14.851649779720384,
            2.1589708670045757,
            3.99791558311788,
            28.434151800232232,
            -25.2593643549416,
            7.733878542362238,
            -1.8913028948478674,
            1.0014845070224718,
            0.004641199599109052,
            0.011218755022148957,
        ],
        &[
            -0.27519629720559396,
            0.0,
            0.03661188877915492,
            0.009789519688231562,
            -12.293062345886211,
            14.207226453937903,
            1.5866476906789537,
            2.4577735327595946,
            -8.935193694403273,
            4.373672731613407,
            -1.8347181765449492,
            1.1592085289061491,
            -0.017290253165383924,
            0.019325977904460768,
            0.005204442937554993,
        ],
        &[
            1.3076391847404059,
            0.0,
            0.017364109189745843,
            -0.018544456454265796,
            14.811522032867726,
            9.38317630848247,
            -5.2284261999445425,
            -48.95128052584765,
            38.297096034337926,
            -10.58738133697598,
            2.4332304376226275,
            -1.0453406042575444,
            0.0717732095086726,
            0.0021622109708082783,
            0.007009595759602514,
            0.0,
        ],
    ];
    const B: &'static [f64] = &[
        0.012127868517185414,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.08629746251568875,
        0.2525469581187147,
        -0.1974186799326823,
        0.2031869190789726,
        -0.020775808077714918,
        0.10967804874502014,
        0.038065132526466504,
        0.01163406880432423,
        0.0046580297040248785,
        0.0,
        0.0,
    ];
    const BP: &'static [f64] = &[
        0.012127868517185414,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.09083943422704079,
        0.3156836976483934,
        -0.2632249065769097,
        0.3047803786184589,
        -0.041551616155429835,
        0.2467756096762953,
        0.15226053010586602,
        0.08143848163026961,
        0.08502571193890811,
        -0.009155189630077963,
        0.025,
    ];
    const B_ERR: &'static [f64] = &[
        -0.004880833389821577,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.014038126584857338,
        -0.11947921920803832,
        0.20440246507662121,
        -0.1322681492223791,
        0.11053069299761689,
        -0.07975385787102851,
        0.011224330486437457,
        -0.004671596801593694,
        0.0008580413473282841,
        0.0,
        0.0,
    ];
    const BP_ERR: &'static [f64] = &[
        -0.004880833389821577,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.014776975352481408,
        -0.1493490240100479,
        0.2725366201021616,
        -0.19840222383356862,
        0.22106138599523378,
        -0.17944618020981415,
        0.04489732194574983,
        -0.03270117761115586,
        0.015662325288859434,
        -0.029155189630077964,
        0.025,
    ];

    const FSAL: bool = false;
    const DENSE_ORDER: u32 = 4;
    const DENSE_LEN: usize = 8;
    const HERMITE: bool = true;
}

/// Ψ of the accepted Nyström step with its step size h frozen (as for [`Adaptive`](super::Adaptive)):
/// the stages differentiated,
///
/// ```text
/// ∂Q_i/∂y₀ = [I, c_i h I] + h² Σ_j a_ij K_j,   K_i = ∂k_i/∂y₀ = f_q(Q_i) ∂Q_i/∂y₀,
/// ∂q₁/∂y₀ = [I, h I] + h² Σ_i b_i K_i,          ∂q̇₁/∂y₀ = [0, I] + h Σ_i b'_i K_i,
/// ```
///
/// with f_q = ∂K/∂q the lower-left block of the [`LinearizedDynamics`](super::LinearizedDynamics)
/// Jacobian (−M⁻¹∇²V for a natural system). The stages are evaluated again from y₀ (s more force
/// evaluations and s Jacobians).
impl<S: SplitDynamics + super::LinearizedDynamics, M: NystromPair> crate::TangentStepper for Nystrom<S, M> {
    fn step_tangent(
        &mut self,
        state: &mut State<S::Partner>,
        h: f64,
        psi: &mut nalgebra::DMatrix<f64>,
    ) -> Result<StepInfo> {
        use nalgebra::DMatrix;
        let n = self.n;
        crate::tangent::check_tangent_shape(psi, n)?;
        crate::tangent::step_then_tangent(self, state, h, |m, st, info| {
            let (h, t) = (info.h, st.t);
            let (q0, v0) = (st.q.as_slice(), st.v.as_slice());
            let s = M::C.len();
            let mut jac = DMatrix::zeros(2 * n, 2 * n);
            let mut ks: Vec<Vec<f64>> = Vec::with_capacity(s);
            let mut dks: Vec<DMatrix<f64>> = Vec::with_capacity(s);
            let mut qs = vec![0.0; n];
            for i in 0..s {
                let (a, c) = (M::A[i], M::C[i]);
                let mut dq = DMatrix::zeros(n, 2 * n);
                dq.view_mut((0, 0), (n, n)).fill_with_identity();
                dq.view_mut((0, n), (n, n)).fill_diagonal(c * h);
                for x in 0..n {
                    let sum: f64 = a.iter().zip(&ks).map(|(aij, k)| aij * k[x]).sum();
                    qs[x] = q0[x] + h * (c * v0[x] + h * sum);
                }
                for (aij, dk) in a.iter().zip(&dks) {
                    dq += dk * (h * h * aij);
                }
                let mut k = vec![0.0; n];
                m.system.kick_rate(&qs, &mut k)?;
                m.system.jacobian(t, &qs, v0, &mut jac)?;
                dks.push(jac.view((n, 0), (n, n)) * dq);
                ks.push(k);
            }
            let mut out = DMatrix::identity(2 * n, 2 * n);
            out.view_mut((0, n), (n, n)).fill_diagonal(h);
            for ((dk, b), bp) in dks.iter().zip(M::B).zip(M::BP) {
                let mut top = out.rows_mut(0, n);
                top += dk * (h * h * b);
                let mut bottom = out.rows_mut(n, n);
                bottom += dk * (h * bp);
            }
            crate::error::check_result("step Jacobian Ψ", t, out.as_slice())?;
            psi.copy_from(&out);
            Ok(())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Σ_j a_ij = c_i²/2 (the stage positions are exact for q̈ = const), Σ b_i = 1/2, Σ b'_i = 1 and
    /// the same for the embedded weights (Σ (b − b̂) = 0, Σ (b' − b̂') = 0); the coefficients are
    /// sums of a few f64 of size ≤ 50, so 1e-13 bounds their rounding.
    fn conditions<M: NystromPair>() {
        let s = M::C.len();
        for w in [
            M::A.len(),
            M::B.len(),
            M::BP.len(),
            M::B_ERR.len(),
            M::BP_ERR.len(),
        ] {
            assert_eq!(w, s, "{}", M::NAME);
        }
        for i in 0..s {
            assert_eq!(M::A[i].len(), i);
            let sum: f64 = M::A[i].iter().sum();
            let want = 0.5 * M::C[i] * M::C[i];
            assert!((sum - want).abs() < 1e-13, "{} row {i}: {sum} vs {want}", M::NAME);
        }
        let b: f64 = M::B.iter().sum();
        let bp: f64 = M::BP.iter().sum();
        let be: f64 = M::B_ERR.iter().sum();
        let bpe: f64 = M::BP_ERR.iter().sum();
        assert!((b - 0.5).abs() < 1e-14 && (bp - 1.0).abs() < 1e-14, "{}", M::NAME);
        assert!(be.abs() < 1e-13 && bpe.abs() < 1e-13, "{}: {be} {bpe}", M::NAME);
        // Σ b'_i c_i = 1/2 and Σ b_i c_i = 1/6: the next conditions, as cheap.
        let bpc: f64 = M::BP.iter().zip(M::C).map(|(b, c)| b * c).sum();
        let bc: f64 = M::B.iter().zip(M::C).map(|(b, c)| b * c).sum();
        assert!(
            (bpc - 0.5).abs() < 1e-14 && (bc - 1.0 / 6.0).abs() < 1e-14,
            "{}",
            M::NAME
        );
        if M::FSAL {
            assert_eq!(M::C[s - 1], 1.0);
            assert_eq!(M::A[s - 1], &M::B[..s - 1]);
            assert_eq!(M::B[s - 1], 0.0);
        }
    }

    #[test]
    fn nystrom_order_conditions() {
        conditions::<Rkn6>();
        conditions::<Rkn8>();
        conditions::<Rkn12>();
        // The dense output of DPRKN 6(4) ends on the step's weights: b_i(1) = b_i, b'_i(1) = b'_i.
        for i in 0..6 {
            let (bq, bv): (f64, f64) = (R6[i].iter().sum(), RP6[i].iter().sum());
            assert!(
                (bq - Rkn6::B[i]).abs() < 1e-14 && (bv - Rkn6::BP[i]).abs() < 1e-14,
                "{i}"
            );
        }
    }
}
