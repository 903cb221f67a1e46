//! IAS15: Everhart's 15th-order Gauss-Radau predictor-corrector with the adaptive step-size control of
//! Rein & Spiegel, for second-order systems q̈ = f(t, q, q̇).
//!
//! # The method
//! Over a step [t, t + h] the acceleration is written as a polynomial of degree 7 in θ = (τ − t)/h,
//!
//! ```text
//! a(θ) = a₀ + b₀ θ + b₁ θ² + … + b₆ θ⁷,
//! ```
//!
//! and integrated twice in closed form:
//!
//! ```text
//! v(θ) = v₀ + hθ (a₀ + b₀θ/2 + b₁θ²/3 + … + b₆θ⁷/8),
//! q(θ) = q₀ + hθ v₀ + h²θ² (a₀/2 + b₀θ/6 + b₁θ²/12 + … + b₆θ⁷/72).
//! ```
//!
//! The b_k are fixed by collocation: a(θ) must equal f(t + θh, q(θ), v(θ)) at the eight Gauss-Radau
//! nodes h₀ = 0, h₁, …, h₇ of [0, 1] (the left end and the seven zeros of the Radau polynomial), whose
//! quadrature is exact for polynomials of degree 14, so the step has order 15. They are found by a
//! predictor-corrector (fixed-point) iteration: predict q (and v, when f depends on it) at each node
//! from the current b, evaluate f there, update the divided differences g_k of the Newton form and
//! from them the b_k (Everhart's r, c, d tables), and repeat until the correction of b₆ relative to
//! the acceleration, max|Δb₆|/max|a|, falls below 1e-16 or stops decreasing after the third round
//! (rounding reached; a stall above 1e-8 is a diverging iteration). Twelve rounds without either count as not
//! converged. A step costs one evaluation at its start plus 7 per round; with the predictor below,
//! three rounds are the rule on Kepler orbits (REBOUND takes the same steps and evaluations).
//!
//! **Predictor.** The converged b of the last accepted step, re-expanded about its end and scaled to
//! the new step size (ratio r = h_new/h_old: e₀ = r(b₀ + 2b₁ + … + 7b₆), …, e₆ = r⁷b₆), are the
//! first guess of the next step, corrected by the difference between the converged and the predicted
//! b of the last step (Everhart's correction). They are kept only while the steps follow one another
//! (the state passed to [`step`](crate::Stepper::step) is the one the last step returned); a
//! rejected or failed step leaves them untouched, and for r > 20 the guess starts from zero.
//!
//! **Compensated summation.** The update q₁ = q₀ + …, v₁ = v₀ + … is summed term by term with
//! Kahan's compensation, and the rounding lost is carried to the next step (again only while the
//! steps follow one another), so that rounding errors grow like a random walk (Brouwer's law)
//! rather than linearly. The b are corrected with compensated sums too.
//!
//! **Step-size control** (ε = [`epsilon`](Ias15::epsilon), default 1e-9). After the iteration
//! converges, a new step size is computed from the polynomial ([`Ias15Control`]):
//! - [`Prs23`](Ias15Control::Prs23) (default, REBOUND's since 2024, Pham, Rein & Spiegel 2024): with
//!   the acceleration y₂ = |a(1)|², jerk y₃ = |h ȧ(1)|² and snap y₄ = |h² ä(1)|² at the end of the step,
//!   τ² = 2y₂/(y₃ + √(y₄y₂)) for each block of coordinates and h_new = h √(min τ²) (5040 ε)^{1/7};
//! - [`Global`](Ias15Control::Global) (Rein & Spiegel 2015, REBOUND's default until 2024):
//!   h_new = h (ε / (max|b₆| / max|a|))^{1/7}, the maxima over all coordinates of the blocks that move.
//!
//! The step is *accepted* unless h_new < h/4 (then it is redone with h_new); the next proposal grows
//! by at most a factor 4. The first step of a run (or after the state was changed between steps),
//! whose size is only a guess, is redone as soon as h_new < h. Accelerations that are not finite reject the step and retry with h/4; an
//! iteration that has not converged after 12 rounds rejects it and retries with h/2. Below
//! [`h_min`](Ias15::h_min) (or 10 ulps of t, or what t + h resolves) the step fails with
//! [`Error::StepSizeUnderflow`], the state untouched: the loop of trials and that test are the step
//! control the embedded pairs use. In fixed-step mode ([`fixed_step`](Ias15::fixed_step)) every step
//! takes the size asked for, the predictor-corrector still iterating to convergence; accelerations that are not finite end it with [`Error::NonFiniteResult`], an iteration
//! that does not converge with [`Error::NewtonDiverged`] (12 iterations, the last relative correction
//! of b₆, tolerance 1e-16).
//!
//! **Dense output.** The polynomial q(θ), v(θ) above is the continuous extension: built only when
//! the driver asks for it, it costs no evaluation.
//!
//! # Systems
//! IAS15 steps an [`Ias15System`]: q̇ = v, v̇ = f(t, q, v).
//! - f(q) alone: a [`SplitDynamics`] whose drift is the identity
//!   ([`drift_is_identity`](SplitDynamics::drift_is_identity)), f = [`kick_rate`](SplitDynamics::kick_rate):
//!   [`Natural`](crate::Natural) and noether-particles' `System` (use [`block_size`](Ias15::block_size)
//!   3 there, one block per particle, as REBOUND does). [`Ias15::new`] refuses any other split system
//!   with [`Error::Unsupported`]. Only q is predicted at the nodes.
//! - f(t, q, q̇): any system with velocities wrapped in [`VelocityDependent`], whose
//!   [`rates`](crate::Dynamics::rates) give f. As REBOUND does when forces depend on velocities, the
//!   predictor-corrector then also predicts the velocities at each node from the current b,
//!   `v(h_n) = v₀ + h h_n (a₀ + b₀h_n/2 + b₁h_n²/3 + … + b₆h_n⁷/8)` (compensated like q), and evaluates
//!   f(t + h h_n, q(h_n), v(h_n)); the same fixed-point iteration converges (its contraction factor
//!   is O(h ‖∂f/∂v‖) besides the O(h² ‖∂f/∂q‖) of the position part). Everything else (the
//!   control, the predictor of b, the dense output, the error contract) is the same.
//!
//! # References
//! - E. Everhart, An efficient integrator that uses Gauss-Radau spacings, in *Dynamics of Comets:
//!   Their Origin and Evolution*, IAU Colloq. 83, ASSL 115 (1985) 185.
//! - H. Rein, D. S. Spiegel, IAS15: a fast, adaptive, high-order integrator for gravitational
//!   dynamics, accurate to machine precision over a billion orbits, MNRAS 446 (2015) 1424.
//! - D. Pham, H. Rein, D. S. Spiegel, Dynamical time-step criteria for high-order integrators,
//!   Open J. Astrophys. 7 (2024).
//! - REBOUND's `integrator_ias15.c`, for the constants (given there to 25 digits) and the control.

mod coefficients;
mod control;
mod system;

pub use system::{Ias15System, VelocityDependent};

use super::step_control::{
    check_start, controlled_stepper, finite_stage, settings_methods, start_accelerations_by, until_accepted,
    Accepted, Settings, Verdict,
};
#[cfg(doc)]
use super::SplitDynamics;
use crate::dense::{horner_eval, DenseEval};
use crate::{DenseOutput, Error, Result, State, StepInfo, Stepper};
#[cfg(test)]
use coefficients::RR;
use coefficients::{C, D, H, HORNER, RR_INV};

/// Largest shrinking of a step that is still accepted, and largest growth (its inverse).
const SAFETY: f64 = 0.25;
/// Iterations of the predictor-corrector before it counts as not converged.
const MAX_ITERATIONS: usize = 12;
/// Relative correction of b₆ at which the predictor-corrector has converged.
const PC_TOLERANCE: f64 = 1e-16;
/// An iteration that stops before [`PC_TOLERANCE`] (its corrections stall, or 12 rounds pass) counts
/// as converged when its last correction of b₆, relative to the accelerations, is at most this:
/// rounding stalls near 1e-15, a diverging or slowly contracting iteration far above.
const PC_ACCEPT: f64 = 1e-10;
/// Above this ratio of consecutive step sizes the predictor starts from zero.
const PREDICT_MAX_RATIO: f64 = 20.0;

/// The step-size criterion of IAS15 (see the [module](self) docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Ias15Control {
    /// Pham, Rein & Spiegel (2024): h_new = h √(min over blocks of 2y₂/(y₃ + √(y₄y₂))) (5040 ε)^{1/7},
    /// from the acceleration, jerk and snap at the end of the step. REBOUND's default since 2024.
    /// A block whose acceleration passes through zero (one coordinate: an oscillator, a pendulum)
    /// gets a timescale proportional to the step there, and the step underflows: use
    /// [`Global`](Ias15Control::Global) for such systems.
    #[default]
    Prs23,
    /// Rein & Spiegel (2015): h_new = h (ε max|a| / max|b₆|)^{1/7} over all coordinates of the blocks
    /// that move (v²h²/q² ≥ 1e-16). REBOUND's default until 2024.
    Global,
}

/// IAS15's own step-size control, the `control` of its [`Settings`].
#[derive(Debug, Clone, Copy)]
struct Accuracy {
    /// ε ([`Ias15::epsilon`]).
    epsilon: f64,
    /// The step-size criterion ([`Ias15::control`]).
    criterion: Ias15Control,
    /// Coordinates per block of the criterion ([`Ias15::block_size`]).
    block: usize,
}

/// What IAS15 keeps of a trial step the control accepted ([`Ias15::converge`]).
#[derive(Debug, Clone, Copy)]
struct Converged {
    /// The control's proposal for the next step.
    h_next: f64,
    /// The rounds of the predictor-corrector of all trials.
    iterations: usize,
    /// Whether its b started from a prediction.
    predicted: bool,
}

/// How the predictor-corrector of one trial step ended.
#[derive(Debug, Clone, Copy)]
enum Attempt {
    /// Converged after this many iterations.
    Converged(usize),
    /// An acceleration was not finite (after this many iterations, counting the failing one).
    NonFinite(usize),
    /// No convergence within [`MAX_ITERATIONS`]; the last relative correction of b₆.
    NotConverged(f64),
}

/// Kahan's compensated p += x, the lost low part kept in `cs`.
#[inline(always)]
fn add_cs(p: &mut f64, cs: &mut f64, x: f64) {
    let y = x - *cs;
    let t = *p + y;
    *cs = (t - *p) - y;
    *p = t;
}

/// IAS15 stepping q̈ = f(q) (see the [module](self) docs).
///
/// ```
/// use noether_core::prelude::*;
/// struct Kepler;
/// impl Potential for Kepler {
///     fn dof(&self) -> usize { 2 }
///     fn potential<D: Scalar>(&self, q: &[D]) -> D { -(q[0] * q[0] + q[1] * q[1]).sqrt().recip() }
/// }
/// // A Kepler orbit with e = 0.6 from pericentre, 10 periods: back at the start to ~1e-13.
/// let e: f64 = 0.6;
/// let start = State::new(0.0, [1.0 - e, 0.0], [0.0, ((1.0 + e) / (1.0 - e)).sqrt()]);
/// let sol = Driver::new(Ias15::new(Natural::unit(Kepler))?, start.clone())?
///     .save(Save::End)?
///     .run_until(20.0 * std::f64::consts::PI)?;
/// assert!((sol.last().q[0] - start.q[0]).abs() < 1e-11 && sol.last().q[1].abs() < 1e-11);
/// # Ok::<(), noether_core::Error>(())
/// ```
pub struct Ias15<S: Ias15System> {
    system: S,
    settings: Settings<Accuracy>,
    n: usize,
    /// Start of the step: positions, velocities, accelerations.
    x0: Vec<f64>,
    v0: Vec<f64>,
    a0: Vec<f64>,
    /// Positions and velocities at a node (the velocities only when f depends on them), the
    /// accelerations there, and room for the q̇ the rates write besides.
    xs: Vec<f64>,
    vs: Vec<f64>,
    at: Vec<f64>,
    scratch: Vec<f64>,
    /// End of the step and its compensations, before they are committed.
    x1: Vec<f64>,
    v1: Vec<f64>,
    csx1: Vec<f64>,
    csv1: Vec<f64>,
    /// Compensations of q and v carried from the last step.
    csx: Vec<f64>,
    csv: Vec<f64>,
    /// Polynomial coefficients b, divided differences g, the prediction e of b, compensations of b.
    b: Vec<[f64; 7]>,
    g: Vec<[f64; 7]>,
    e: Vec<[f64; 7]>,
    csb: Vec<[f64; 7]>,
    /// Converged b and predicted e of the last accepted step, of size `h_prev` (0: none).
    prev_b: Vec<[f64; 7]>,
    prev_e: Vec<[f64; 7]>,
    h_prev: f64,
    /// The state the last accepted step returned (for the continuity test).
    last_q: Vec<f64>,
    last_v: Vec<f64>,
    have_last: bool,
    /// f at (`cached_t`, `cached_q`, `cached_v`) (from the initial-step choice), reused by a step
    /// starting there (t and v compared only when f depends on them).
    cached_t: f64,
    cached_q: Vec<f64>,
    cached_v: Vec<f64>,
    cached_a: Vec<f64>,
    have_cached: bool,
    dense: Option<DenseOutput<S::Partner>>,
    evaluations: usize,
}

impl<S: Ias15System> Ias15<S> {
    /// IAS15 for `system` with ε = 1e-9, the [`Prs23`](Ias15Control::Prs23) control over one block
    /// (all coordinates), dense output allowed. A split system whose drift is not the identity (a
    /// separable Hamiltonian on (q, p)) is refused with [`Error::Unsupported`].
    pub fn new(system: S) -> Result<Self> {
        system.second_order()?;
        let n = system.dof();
        let z = vec![0.0; n];
        let z7 = vec![[0.0; 7]; n];
        Ok(Ias15 {
            system,
            settings: Settings::new(Accuracy {
                epsilon: 1e-9,
                criterion: Ias15Control::Prs23,
                block: n.max(1),
            }),
            n,
            x0: z.clone(),
            v0: z.clone(),
            a0: z.clone(),
            xs: z.clone(),
            vs: z.clone(),
            at: z.clone(),
            scratch: z.clone(),
            x1: z.clone(),
            v1: z.clone(),
            csx1: z.clone(),
            csv1: z.clone(),
            csx: z.clone(),
            csv: z.clone(),
            b: z7.clone(),
            g: z7.clone(),
            e: z7.clone(),
            csb: z7.clone(),
            prev_b: z7.clone(),
            prev_e: z7,
            h_prev: 0.0,
            last_q: z.clone(),
            last_v: z.clone(),
            have_last: false,
            cached_t: f64::NAN,
            cached_q: z.clone(),
            cached_v: z.clone(),
            cached_a: z,
            have_cached: false,
            dense: None,
            evaluations: 0,
        })
    }

    /// Sets the accuracy parameter ε of the step-size control (default 1e-9, finite and positive):
    /// the step is chosen so that the last term of the acceleration polynomial is ≈ ε times the
    /// acceleration. The error per step scales like ε^{15/7}; 1e-9 gives steps converged to machine
    /// precision on smooth problems.
    pub fn epsilon(mut self, epsilon: f64) -> Result<Self> {
        if !(epsilon.is_finite() && epsilon > 0.0) {
            return Err(Error::InvalidParameter {
                name: "epsilon",
                value: epsilon,
                reason: "must be finite and positive (for fixed steps use fixed_step(true))",
            });
        }
        self.settings.control.epsilon = epsilon;
        Ok(self)
    }

    /// Sets the step-size criterion (default [`Ias15Control::Prs23`]).
    pub fn control(mut self, control: Ias15Control) -> Self {
        self.settings.control.criterion = control;
        self
    }

    /// Groups the coordinates into consecutive blocks of `size` for the step-size criterion (one
    /// timescale per block, the smallest wins): 3 for particles in space, 2 in the plane. The default
    /// is one block of all coordinates. `size` must be positive and divide the number of coordinates.
    pub fn block_size(mut self, size: usize) -> Result<Self> {
        if size == 0 || !self.n.is_multiple_of(size) {
            return Err(Error::InvalidParameter {
                name: "block_size",
                value: size as f64,
                reason: "must be positive and divide the number of coordinates",
            });
        }
        self.settings.control.block = size;
        Ok(self)
    }

    settings_methods!("f");

    /// The first guess of b (and the prediction e it came from) for a step of size h; `false` when
    /// there is nothing to predict from (b = e = 0).
    fn predict(&mut self, h: f64) -> bool {
        let ratio = if self.h_prev > 0.0 {
            h / self.h_prev
        } else {
            f64::INFINITY
        };
        if ratio > PREDICT_MAX_RATIO {
            self.b.iter_mut().for_each(|b| *b = [0.0; 7]);
            self.e.iter_mut().for_each(|e| *e = [0.0; 7]);
            return false;
        }
        let q1 = ratio;
        let q2 = q1 * q1;
        let q3 = q1 * q2;
        let q4 = q2 * q2;
        let q5 = q2 * q3;
        let q6 = q3 * q3;
        let q7 = q3 * q4;
        for k in 0..self.n {
            let p = &self.prev_b[k];
            let pe = &self.prev_e[k];
            let e = [
                q1 * (p[6] * 7.0 + p[5] * 6.0 + p[4] * 5.0 + p[3] * 4.0 + p[2] * 3.0 + p[1] * 2.0 + p[0]),
                q2 * (p[6] * 21.0 + p[5] * 15.0 + p[4] * 10.0 + p[3] * 6.0 + p[2] * 3.0 + p[1]),
                q3 * (p[6] * 35.0 + p[5] * 20.0 + p[4] * 10.0 + p[3] * 4.0 + p[2]),
                q4 * (p[6] * 35.0 + p[5] * 15.0 + p[4] * 5.0 + p[3]),
                q5 * (p[6] * 21.0 + p[5] * 6.0 + p[4]),
                q6 * (p[6] * 7.0 + p[5]),
                q7 * p[6],
            ];
            let b = &mut self.b[k];
            for j in 0..7 {
                b[j] = e[j] + (p[j] - pe[j]);
            }
            self.e[k] = e;
        }
        true
    }

    /// g from b (the Newton form of the acceleration polynomial).
    fn g_from_b(&mut self) {
        for (g, b) in self.g.iter_mut().zip(&self.b) {
            *g = [
                b[6] * D[15] + b[5] * D[10] + b[4] * D[6] + b[3] * D[3] + b[2] * D[1] + b[1] * D[0] + b[0],
                b[6] * D[16] + b[5] * D[11] + b[4] * D[7] + b[3] * D[4] + b[2] * D[2] + b[1],
                b[6] * D[17] + b[5] * D[12] + b[4] * D[8] + b[3] * D[5] + b[2],
                b[6] * D[18] + b[5] * D[13] + b[4] * D[9] + b[3],
                b[6] * D[19] + b[5] * D[14] + b[4],
                b[6] * D[20] + b[5],
                b[6],
            ];
        }
    }

    /// New g_J (J = node − 1) from the accelerations `at` at node J + 1, and the b it changes: with
    /// r the node differences ([`RR_INV`] their inverses) and c the Newton-to-power conversion ([`C`]),
    ///
    /// ```text
    /// g_J = ((…((at − a₀)/r_J0 − g₀)/r_J1 − …) − g_{J−1})/r_J,J−1,   Δg = g_J − g_J,old,
    /// b_m += c_Jm Δg (m < J),   b_J += Δg        (Kahan-compensated).
    /// ```
    ///
    /// At the last node (J = 6) it returns the correction of b₆ relative to the accelerations,
    /// max |Δb₆| / max |a| (over the components where each is a normal number; 0 when no Δb₆ is), the
    /// convergence measure of the predictor-corrector; 0 at the other nodes, where the comparisons are
    /// compiled away (J is a constant).
    #[inline(always)]
    fn update_node<const J: usize>(&mut self) -> f64 {
        let r0 = J * (J + 1) / 2;
        let c0 = if J == 0 { 0 } else { (J - 1) * J / 2 };
        let (mut max_a, mut max_db) = (0.0_f64, 0.0_f64);
        let (at, a0) = (&self.at[..], &self.a0[..]);
        for ((((g, b), cs), at), a0) in self
            .g
            .iter_mut()
            .zip(&mut self.b)
            .zip(&mut self.csb)
            .zip(at)
            .zip(a0)
        {
            let mut val = (at - a0) * RR_INV[r0];
            for m in 0..J {
                val = (val - g[m]) * RR_INV[r0 + 1 + m];
            }
            let dg = val - g[J];
            g[J] = val;
            for m in 0..J {
                add_cs(&mut b[m], &mut cs[m], dg * C[c0 + m]);
            }
            add_cs(&mut b[J], &mut cs[J], dg);
            if J == 6 {
                let (a, d) = (at.abs(), dg.abs());
                if a.is_normal() && a > max_a {
                    max_a = a;
                }
                if d.is_normal() && d > max_db {
                    max_db = d;
                }
            }
        }
        if max_db == 0.0 {
            0.0
        } else {
            max_db / max_a
        }
    }

    /// The predictor-corrector for a step of size h from (t, x0, v0, a0), starting from the current b.
    fn iterate(&mut self, t: f64, h: f64) -> Result<Attempt> {
        self.g_from_b();
        self.csb.iter_mut().for_each(|c| *c = [0.0; 7]);
        let (mut pc_err, mut pc_last) = (f64::INFINITY, 2.0);
        let mut iterations = 0;
        loop {
            if pc_err < PC_TOLERANCE {
                return Ok(Attempt::Converged(iterations));
            }
            if iterations > 2 && pc_last <= pc_err {
                // The corrections stopped shrinking: at rounding (converged) or diverging (not).
                return Ok(if pc_err <= PC_ACCEPT {
                    Attempt::Converged(iterations)
                } else {
                    Attempt::NotConverged(pc_err)
                });
            }
            if iterations >= MAX_ITERATIONS {
                return Ok(if pc_err <= PC_ACCEPT {
                    Attempt::Converged(iterations)
                } else {
                    Attempt::NotConverged(pc_err)
                });
            }
            pc_last = pc_err;
            iterations += 1;
            for node in 1..8 {
                let f = &HORNER[node];
                let s = h * H[node];
                // Local slices: the buffers' pointers stay in registers through the loop.
                let (b, a0, v0, x0, csx) = (
                    &self.b[..],
                    &self.a0[..],
                    &self.v0[..],
                    &self.x0[..],
                    &self.csx[..],
                );
                for ((((xs, b), a0), v0), (x0, csx)) in
                    self.xs.iter_mut().zip(b).zip(a0).zip(v0).zip(x0.iter().zip(csx))
                {
                    let poly = (((((((b[6] * f[0] + b[5]) * f[1] + b[4]) * f[2] + b[3]) * f[3] + b[2])
                        * f[4]
                        + b[1])
                        * f[5]
                        + b[0])
                        * f[6]
                        + a0)
                        * s
                        / 2.0
                        + v0;
                    *xs = (poly * s - csx) + x0;
                }
                if S::VELOCITY_DEPENDENT {
                    self.predict_velocities(node, s);
                }
                if !self.stage(t + s)? {
                    return Ok(Attempt::NonFinite(iterations));
                }
                let correction = match node {
                    1 => self.update_node::<0>(),
                    2 => self.update_node::<1>(),
                    3 => self.update_node::<2>(),
                    4 => self.update_node::<3>(),
                    5 => self.update_node::<4>(),
                    6 => self.update_node::<5>(),
                    _ => self.update_node::<6>(),
                };
                if node == 7 {
                    pc_err = correction;
                }
            }
        }
    }
}

impl<S: Ias15System> Ias15<S> {
    /// The velocities at node n (θ = h_n, s = h h_n) from the current b into `vs`, compensated like
    /// the positions: v = v₀ + s (a₀ + b₀θ/2 + b₁θ²/3 + … + b₆θ⁷/8), by Horner's scheme
    /// ((((b₆·7θ/8 + b₅)·6θ/7 + b₄)·5θ/6 + …)·θ/2 + a₀)·s + v₀ (REBOUND's, for velocity-dependent
    /// forces).
    #[inline(always)]
    fn predict_velocities(&mut self, node: usize, s: f64) {
        let th = H[node];
        let f = [
            7.0 * th / 8.0,
            6.0 * th / 7.0,
            5.0 * th / 6.0,
            4.0 * th / 5.0,
            3.0 * th / 4.0,
            2.0 * th / 3.0,
            th / 2.0,
        ];
        let (b, a0, v0, csv) = (&self.b[..], &self.a0[..], &self.v0[..], &self.csv[..]);
        for (((vs, b), (a0, v0)), csv) in self.vs.iter_mut().zip(b).zip(a0.iter().zip(v0)).zip(csv) {
            let poly = ((((((b[6] * f[0] + b[5]) * f[1] + b[4]) * f[2] + b[3]) * f[3] + b[2]) * f[4] + b[1])
                * f[5]
                + b[0])
                * f[6]
                + a0;
            *vs = (poly * s - csv) + v0;
        }
    }

    /// f at a node at time t from the positions `xs` (and the velocities `vs` when f depends on
    /// them) into `at`, counted in `evaluations`: Ok(false) when it is not finite ([`finite_stage`]:
    /// the trial is retried smaller); other errors of the model pass through.
    #[inline(always)]
    fn stage(&mut self, t: f64) -> Result<bool> {
        self.evaluations += 1;
        let r = self
            .system
            .accelerations(t, &self.xs, &self.vs, &mut self.scratch, &mut self.at);
        finite_stage(r, &self.at)
    }
}

/// Polynomial degree of the dense output in θ (q: h θ v₀ + h² θ² (a₀/2 + … + b₆ θ⁷/72)).
const DENSE_LEN: usize = 9;
/// Order of the dense output (its local error inside a step is O(h^{order+1})); measured in the tests.
const DENSE_ORDER: u32 = 8;

impl<S: Ias15System> Ias15<S> {
    /// The start of a step from `state`: q₀, v₀ and a₀ = f(q₀) (the one the initial-step choice
    /// evaluated when the step starts there). The predictor's data and the compensations of q and v
    /// carry over only when the step continues the last accepted one; they are reset otherwise.
    fn start(&mut self, state: &State<S::Partner>) -> Result<()> {
        let (q, v) = (state.q.as_slice(), state.v.as_slice());
        if !(self.have_last && self.last_q == q && self.last_v == v) {
            self.have_last = false;
            self.h_prev = 0.0;
            self.csx.iter_mut().for_each(|c| *c = 0.0);
            self.csv.iter_mut().for_each(|c| *c = 0.0);
        }
        self.x0.copy_from_slice(q);
        self.v0.copy_from_slice(v);
        let cached = self.have_cached
            && self.cached_q == q
            && (!S::VELOCITY_DEPENDENT || (self.cached_t == state.t && self.cached_v == v));
        if cached {
            self.a0.copy_from_slice(&self.cached_a);
        } else {
            let (system, scratch) = (&self.system, &mut self.scratch);
            start_accelerations_by(&mut self.evaluations, state.t, &mut self.a0, |out| {
                system.accelerations(state.t, q, v, scratch, out)
            })?;
        }
        self.have_cached = false;
        Ok(())
    }

    /// Trial steps from t, trying h first, until the predictor-corrector converges on a step the
    /// control accepts ([`until_accepted`], IAS15's policy). A trial whose accelerations are not finite
    /// is retried with h·[`SAFETY`], one whose iteration does not converge with h/2 (in fixed-step mode
    /// both are errors), and a converged one is redone with the control's proposal when that is far
    /// smaller (< h/4), or smaller at all on the first trial of a run (its size is a guess, and a step
    /// 4× too large has a local error 4¹⁶ times the control's). [`Error::StepSizeUnderflow`] when h
    /// falls below `h_min` or what t resolves, with the error of the last rejection: ∞ after
    /// non-finite accelerations, the last correction of b₆ after a diverging iteration, h/h_new after
    /// the control's.
    fn converge(&mut self, t: f64, h: f64) -> Result<Accepted<Converged>> {
        let mut iterations = 0;
        until_accepted(self.settings.h_min, (t, h), |h, rejected| {
            let predicted = self.predict(h);
            let attempt = self.iterate(t, h)?;
            iterations += match attempt {
                Attempt::Converged(it) | Attempt::NonFinite(it) => it,
                Attempt::NotConverged(_) => MAX_ITERATIONS,
            };
            if let Some((factor, error)) = self.retry(t, attempt)? {
                return Ok(Verdict::Retry { h: h * factor, error });
            }
            let h_next = if self.settings.fixed {
                h
            } else {
                let proposal = self.proposal(h);
                let fresh = self.h_prev == 0.0 && rejected == 0;
                if proposal < SAFETY * h || (fresh && proposal < h) {
                    // Smaller than the step just done allows: redo it with the proposal.
                    return Ok(Verdict::Retry {
                        h: proposal,
                        error: h / proposal,
                    });
                }
                proposal.min(h / SAFETY)
            };
            Ok(Verdict::Accept(Converged {
                h_next,
                iterations,
                predicted,
            }))
        })
    }

    /// How a trial that did not converge is retried: the factor of its step size ([`SAFETY`] after
    /// accelerations that were not finite, 1/2 after an iteration that did not converge) and the
    /// error it reports (∞, or the last relative correction of b₆); `None` for a converged trial.
    /// In fixed-step mode such a trial is an error: [`Error::NonFiniteResult`] or
    /// [`Error::NewtonDiverged`].
    fn retry(&self, t: f64, attempt: Attempt) -> Result<Option<(f64, f64)>> {
        match attempt {
            Attempt::Converged(_) => Ok(None),
            Attempt::NonFinite(_) if self.settings.fixed => Err(Error::NonFiniteResult {
                what: "accelerations",
                t,
                component: None,
            }),
            Attempt::NonFinite(_) => Ok(Some((SAFETY, f64::INFINITY))),
            Attempt::NotConverged(err) if self.settings.fixed => Err(Error::NewtonDiverged {
                iterations: MAX_ITERATIONS,
                residual: err,
                tolerance: PC_TOLERANCE,
                t,
            }),
            Attempt::NotConverged(err) => Ok(Some((0.5, err))),
        }
    }

    /// Commits the step of size h from t: `state` = (t + h, q₁, v₁), the compensations of q₁ and v₁,
    /// and the predictor's data for the next step (its b, and the prediction e when there was one).
    fn commit(&mut self, state: &mut State<S::Partner>, t: f64, h: f64, predicted: bool) {
        state.q.as_mut_slice().copy_from_slice(&self.x1);
        state.v.as_mut_slice().copy_from_slice(&self.v1);
        state.t = t + h;
        std::mem::swap(&mut self.csx, &mut self.csx1);
        std::mem::swap(&mut self.csv, &mut self.csv1);
        self.last_q.copy_from_slice(&self.x1);
        self.last_v.copy_from_slice(&self.v1);
        self.have_last = true;
        std::mem::swap(&mut self.prev_b, &mut self.b);
        if predicted {
            std::mem::swap(&mut self.prev_e, &mut self.e);
        } else {
            // No prediction to correct: the next one starts from the converged b alone.
            self.prev_e.copy_from_slice(&self.prev_b);
        }
        self.h_prev = h;
    }

    /// The end of a converged step of size h into x1, v1 and their compensations (Kahan sums of the
    /// terms of q(1), v(1), smallest first).
    fn finish(&mut self, h: f64) {
        for k in 0..self.n {
            let b = &self.b[k];
            let (mut x, mut cx) = (self.x0[k], self.csx[k]);
            add_cs(&mut x, &mut cx, b[6] / 72.0 * h * h);
            add_cs(&mut x, &mut cx, b[5] / 56.0 * h * h);
            add_cs(&mut x, &mut cx, b[4] / 42.0 * h * h);
            add_cs(&mut x, &mut cx, b[3] / 30.0 * h * h);
            add_cs(&mut x, &mut cx, b[2] / 20.0 * h * h);
            add_cs(&mut x, &mut cx, b[1] / 12.0 * h * h);
            add_cs(&mut x, &mut cx, b[0] / 6.0 * h * h);
            add_cs(&mut x, &mut cx, self.a0[k] / 2.0 * h * h);
            add_cs(&mut x, &mut cx, self.v0[k] * h);
            let (mut v, mut cv) = (self.v0[k], self.csv[k]);
            add_cs(&mut v, &mut cv, b[6] / 8.0 * h);
            add_cs(&mut v, &mut cv, b[5] / 7.0 * h);
            add_cs(&mut v, &mut cv, b[4] / 6.0 * h);
            add_cs(&mut v, &mut cv, b[3] / 5.0 * h);
            add_cs(&mut v, &mut cv, b[2] / 4.0 * h);
            add_cs(&mut v, &mut cv, b[1] / 3.0 * h);
            add_cs(&mut v, &mut cv, b[0] / 2.0 * h);
            add_cs(&mut v, &mut cv, self.a0[k] * h);
            self.x1[k] = x;
            self.csx1[k] = cx;
            self.v1[k] = v;
            self.csv1[k] = cv;
        }
    }

    /// The dense output of the step of size h from t just converged (reusing the last one's vectors).
    fn build_dense(&mut self, t: f64, h: f64) {
        let n = self.n;
        let (mut y0, mut c) = match self.dense.take() {
            Some(d) => d.into_parts(),
            None => (Vec::new(), Vec::new()),
        };
        if y0.len() != 2 * n {
            y0 = vec![0.0; 2 * n];
        }
        if c.len() != DENSE_LEN || c.iter().any(|c| c.len() != 2 * n) {
            c = vec![vec![0.0; 2 * n]; DENSE_LEN];
        }
        y0[..n].copy_from_slice(&self.x0);
        y0[n..].copy_from_slice(&self.v0);
        for k in 0..n {
            let b = &self.b[k];
            c[0][k] = h * self.v0[k];
            c[1][k] = h * h * self.a0[k] / 2.0;
            c[0][n + k] = h * self.a0[k];
            for j in 0..7 {
                let jf = j as f64;
                c[2 + j][k] = h * h * b[j] / ((jf + 2.0) * (jf + 3.0));
                c[1 + j][n + k] = h * b[j] / (jf + 2.0);
            }
            c[8][n + k] = 0.0;
        }
        let eval: DenseEval = horner_eval;
        self.dense = Some(DenseOutput::from_coefficients(t, h, DENSE_ORDER, y0, c, eval));
    }
}

impl<S: Ias15System> Stepper for Ias15<S> {
    type Partner = S::Partner;

    /// One accepted step, trying `h` first. `StepInfo::h` is the step taken, `h_next` the control's
    /// proposal, `rejected` the rejected trials, `evaluations` the evaluations of f, and
    /// `newton_iterations` the rounds of the predictor-corrector (7 evaluations each) of all trials.
    /// A [`Error::StepSizeUnderflow`] carries as `error` the ratio h/h_new of the last rejection by the
    /// control (∞ after accelerations that were not finite, the relative correction of b₆ after an
    /// iteration that did not converge).
    fn step(&mut self, state: &mut State<S::Partner>, h: f64) -> Result<StepInfo> {
        check_start(&self.system, self.n, state, h)?;
        let t = state.t;
        let evaluations = self.evaluations;
        self.start(state)?;
        let trial = self.converge(t, h)?;
        let h = trial.h;
        self.finish(h);
        if !self
            .x1
            .iter()
            .chain(&self.v1)
            .fold(true, |ok, x| ok & x.is_finite())
        {
            return Err(Error::NonFiniteResult {
                what: "state after the step",
                t,
                component: None,
            });
        }
        if self.settings.dense() {
            self.build_dense(t, h);
        } else {
            self.dense = None;
        }
        let c = trial.outcome;
        self.commit(state, t, h, c.predicted);
        Ok(trial
            .info(c.h_next, self.evaluations - evaluations)
            .with_newton(c.iterations, 0))
    }
    controlled_stepper!(order: 15, name: "IAS15");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[allow(clippy::needless_range_loop)] // Everhart's recurrences, written by index as published
    fn closed_form_constants() {
        // The nodes: with the weights w_i of REBOUND's table (for the interval [−1, 1]; 2/n² at the
        // fixed end), Gauss-Radau quadrature at x_i = 2h_i − 1 integrates x^m exactly
        // for m ≤ 2·8 − 2 = 14: Σ w_i x_i^m = (1 − (−1)^{m+1})/(m + 1), to rounding (1e-15).
        #[allow(clippy::excessive_precision)]
        const W: [f64; 8] = [
            0.03125,
            0.185358154802979278540728972807180754479812609,
            0.304130620646785128975743291458180383736715043,
            0.376517545389118556572129261157225608762708603,
            0.391572167452493593082499533303669362149363727,
            0.347014795634501068709955597003528601733139176,
            0.249647901329864963257869294715235590174262844,
            0.114508814744257199342353731044292225247093225,
        ];
        let mut worst_quadrature = 0.0_f64;
        for m in 0..=14 {
            let sum: f64 = (0..8).map(|i| W[i] * (2.0 * H[i] - 1.0).powi(m)).sum();
            let exact = if m % 2 == 0 { 2.0 / (m as f64 + 1.0) } else { 0.0 };
            worst_quadrature = worst_quadrature.max((sum - exact).abs());
        }
        // Measured 1.1e-16 (the sums of terms up to 2 carry rounding of a few 1e-16).
        assert!(worst_quadrature < 5e-16, "{worst_quadrature:e}");
        // r, c, d follow from the nodes by Everhart's recurrences (computed here in f64: agreement
        // with the 25-digit tables to a few ulps of the largest entry, 2.9; measured 4.4e-16 for both).
        let mut l = 0;
        for j in 1..8 {
            for k in 0..j {
                // One rounding of the difference: half an ulp of numbers below 1, 1.1e-16.
                assert!((RR[l] - (H[j] - H[k])).abs() <= 1.2e-16, "r[{l}]");
                l += 1;
            }
        }
        let (mut c, mut d) = ([0.0; 21], [0.0; 21]);
        c[0] = -H[1];
        d[0] = H[1];
        let mut l = 0;
        for j in 2..7 {
            l += 1;
            c[l] = -H[j] * c[l + 1 - j];
            d[l] = H[1] * d[l + 1 - j];
            for k in 2..j {
                l += 1;
                c[l] = c[l - j] - H[j] * c[l + 1 - j];
                d[l] = d[l - j] + H[k] * d[l + 1 - j];
            }
            l += 1;
            c[l] = c[l - j] - H[j];
            d[l] = d[l - j] + H[j];
        }
        let worst_c = (0..21).map(|i| (c[i] - C[i]).abs()).fold(0.0, f64::max);
        let worst_d = (0..21).map(|i| (d[i] - D[i]).abs()).fold(0.0, f64::max);
        assert!(worst_c < 1.5e-15 && worst_d < 1.5e-15, "{worst_c:e} {worst_d:e}");
    }
}
