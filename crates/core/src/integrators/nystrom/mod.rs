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

mod tableaux;

pub use tableaux::{Dprkn12, Dprkn6, Dprkn8, Rkn12, Rkn6, Rkn8};

use super::adaptive::{combine_stages, stage_sum, Controller, StageArgument, Stages};
use super::step_control::{
    check_start, check_tolerances, checked_error, controlled_stepper, error_scale, initial_step_size,
    settings_methods, stage_accelerations, start_accelerations, until_accepted_pi, Settings, Tolerances,
};
use super::SplitDynamics;
use crate::dense::horner_eval;
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
    settings: Settings<Tolerances>,
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
            settings: Settings::new(Tolerances::new(M::CONTROLLER)),
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

    settings_methods!(tolerances, "f");

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
        let (atol, rtol, h2) = (self.settings.control.atol, self.settings.control.rtol, h * h);
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
            if !stage_accelerations(&self.system, &mut self.evaluations, &self.qs, ki)? {
                return Ok(f64::INFINITY);
            }
        }
        let (atol, rtol, h2) = (self.settings.control.atol, self.settings.control.rtol, h * h);
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
            t,
            h,
            order,
            y0,
            coeffs,
            horner_eval,
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

    /// The start of a step from `state`: (q₀, q̇₀) loaded and the first stage k₁ = f(q₀), the last
    /// step's f(q₁) when the step starts at its q₁ (f depends on q alone), evaluated otherwise. When
    /// the step continues the last accepted one (same q and q̇) and a Hermite dense output is wanted,
    /// that step's start (q, q̇, q̈) and size are kept as the third node of the interpolant.
    fn start(&mut self, state: &State<S::Partner>) -> Result<()> {
        let n = self.n;
        let reuse = self.fsal && self.q1 == *state.q.as_slice();
        // q₀, q̇₀ and k₁ still hold the last step's start.
        self.prev = M::HERMITE
            && reuse
            && self.h_last > 0.0
            && self.settings.dense()
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
        if !reuse {
            self.start_acceleration(state.t)?;
        }
        self.k[..n].copy_from_slice(&self.a1);
        Ok(())
    }

    /// a₁ = f(q₀) at the start of a step or a run at t ([`start_accelerations`]: no smaller step
    /// helps, so a non-finite value is an error naming its component).
    fn start_acceleration(&mut self, t: f64) -> Result<()> {
        start_accelerations(&self.system, &mut self.evaluations, t, &self.q0, &mut self.a1)
    }

    /// a₁ = f(q₁) after the accepted trial of size h from t: the last stage of an FSAL pair, else
    /// evaluated when the dense output needs it (and then reused by the next step).
    fn end_acceleration(&mut self, t: f64, h: f64, dense: bool) -> Result<()> {
        let (n, s) = (self.n, M::C.len());
        if M::FSAL {
            self.a1.copy_from_slice(&self.k[(s - 1) * n..s * n]);
            self.fsal = true;
        } else if dense {
            if !stage_accelerations(&self.system, &mut self.evaluations, &self.q1, &mut self.a1)? {
                return Err(Error::NonFiniteResult {
                    what: "accelerations",
                    t: t + h,
                    component: None,
                });
            }
            self.fsal = true;
        }
        Ok(())
    }

    /// Accepts the trial of size h from t: its dense output when `dense`, then `state` = (t + h, q₁, q̇₁).
    fn accept(&mut self, state: &mut State<S::Partner>, t: f64, h: f64, dense: bool) {
        if dense {
            self.build_dense(t, h);
        } else if let Some(d) = self.dense.take() {
            self.spare = Some(d.into_parts());
        }
        state.q.as_mut_slice().copy_from_slice(&self.q1);
        state.v.as_mut_slice().copy_from_slice(&self.v1);
        state.t = t + h;
    }

    /// Hairer's `hinit` on y = (q, q̇), y' = (q̇, f(q)) (see [`Adaptive`](super::Adaptive)); f(q₀) is
    /// kept as the first stage of the first step.
    fn hinit(&mut self, state: &State<S::Partner>) -> Result<f64> {
        let c = self.settings.control;
        check_tolerances(c.atol, c.rtol, self.settings.h_min)?;
        state.validate(self.n)?;
        let n = self.n;
        self.fsal = false;
        self.load(state);
        self.start_acceleration(state.t)?;
        self.h_last = 0.0;
        let mut y0 = vec![0.0; 2 * n];
        y0[..n].copy_from_slice(&self.q0);
        y0[n..].copy_from_slice(&self.v0);
        let mut f0 = vec![0.0; 2 * n];
        f0[..n].copy_from_slice(&self.v0);
        f0[n..].copy_from_slice(&self.a1);
        let (system, evaluations, qs) = (&self.system, &mut self.evaluations, &mut self.qs);
        let h = initial_step_size(M::ORDER, (c.atol, c.rtol), &y0, &f0, |h, d| {
            // F(y₀ + hF₀) − F₀ = (q̇₀ + h f(q₀) − q̇₀, f(q₀ + h q̇₀) − f(q₀)).
            for x in 0..n {
                qs[x] = y0[x] + h * f0[x];
                d[x] = (f0[n + x] * h + y0[n + x]) - f0[x];
            }
            let ok = stage_accelerations(system, evaluations, qs, &mut d[n..])?;
            for (d, f0) in d[n..].iter_mut().zip(&f0[n..]) {
                *d -= f0;
            }
            Ok(ok)
        })?;
        self.q1.copy_from_slice(&self.q0);
        self.fsal = true;
        Ok(h)
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
        check_start(&self.system, self.n, state, h)?;
        let evaluations = self.evaluations;
        let t = state.t;
        self.start(state)?;
        let settings = self.settings;
        let trial = until_accepted_pi(&settings, M::CONTROL_ORDER, (t, h), "accelerations", |h| {
            self.attempt(h)
        })?;
        let dense = settings.dense();
        self.end_acceleration(t, trial.h, dense)?;
        let h_next = trial.next_step(&settings, &mut self.err_prev);
        self.h_last = trial.h;
        self.accept(state, t, trial.h, dense);
        Ok(trial.info(h_next, self.evaluations - evaluations))
    }
    controlled_stepper!(order: M::ORDER, name: M::NAME);
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
