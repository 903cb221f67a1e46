//! The variational integrator of any [`DiscreteLagrangian`] in position-momentum form, solved by the
//! core Newton with the Jacobian D₁₂L_d from dual numbers.
//!
//! Given (q_k, p_k), solve for the increment Δ = q_{k+1} − q_k
//!
//! ```text
//! F(Δ) = p_k + D₁L_d(q_k, q_k + Δ) + f⁻(q_k, q_k + Δ) = 0,     ∂F/∂Δ = D₁₂L_d(q_k, q_{k+1}),
//! ```
//!
//! then set p_{k+1} = D₂L_d(q_k, q_{k+1}) + f⁺(q_k, q_{k+1}). Without forces this is the discrete
//! Euler-Lagrange equation D₂L_d(q_{k−1}, q_k) + D₁L_d(q_k, q_{k+1}) = 0 written as a symplectic map.
//!
//! How it is evaluated, for conserved momenta at rounding level: the new momentum is accumulated as
//! p_{k+1} = p_k + (D₁ + D₂)L_d + f⁻ + f⁺ (equal to D₂L_d + f⁺ + R, R = F(Δ) the Newton residual),
//! with (D₁ + D₂)L_d, a small impulse, by one dual evaluation along a common shift of q_k and q_{k+1}
//! (no cancellation), and q_{k+1} is stored exactly as the point L_d was evaluated at. For a symmetry
//! ξ (linear in q) of L_d the discrete Noether identity D₁L_d·ξ(q_k) + D₂L_d·ξ(q_{k+1}) = 0 then gives
//! J_{k+1} − J_k = R·ξ(Δ) for J = p·ξ(q), where taking p_{k+1} = D₂L_d gives R·ξ(q_k): the residual,
//! which cannot go below ~ε|q|/h (q_{k+1} is a floating-point number), is weighted by the small
//! increment instead of the position. Newton iterates on Δ, so the unknown carries no ε|q| rounding.
//!
//! A state the integrator did not produce itself (the start of a run, or a state changed between steps)
//! is first checked by [`DiscreteLagrangian::check_momenta`]: for a degenerate Lagrangian (linear in
//! q̇) momenta off the primary constraint p = ∂L/∂q̇ are refused with
//! [`OffPrimaryConstraint`](crate::OffPrimaryConstraint) instead of taking a wild step (see
//! [`primary`](crate::primary)). The steps that continue a run skip the check.
//!
//! With forces the Jacobian is ∂F/∂Δ = D₁₂L_d + ∂f⁻/∂q_{k+1}, the second term by dual numbers through
//! the generic [`DiscreteLagrangian::discrete_force`] ([`DiscreteDerivatives::force_derivatives`]), so
//! Newton converges quadratically however strongly the forces depend on q_{k+1}.
//!
//! ```
//! use noether_core::prelude::*;
//! use noether_discrete::{Midpoint, VariationalIntegrator};
//!
//! struct Oscillator;
//! impl Lagrangian for Oscillator {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         (v[0] * v[0] - q[0] * q[0]) * 0.5
//!     }
//! }
//!
//! let mut vi = VariationalIntegrator::new(Midpoint::new(Oscillator));
//! let start = vi.state_from_velocities(0.0, &[1.0], &[0.0]).unwrap();
//! let mut traj = Driver::with_step(vi, start, 0.01).unwrap();
//! let end = traj.run_steps(100).unwrap().last().clone();
//! // Midpoint is second order: q(1) = cos 1 up to O(h²).
//! assert!((end.q[0] - 1f64.cos()).abs() < 1e-4);
//! ```

use crate::flow::{check_flow_args, correct_once, signed_step, Predictor};
use crate::lagrangian::{DiscreteDerivatives, DiscreteLagrangian, StepEnd};
use crate::quadrature::FromLagrangian;
use nalgebra::{DMatrix, DVector};
use noether_core::error::{check_finite, check_len};
use noether_core::integrators::composition::step_forward;
use noether_core::integrators::SignedStepper;
use noether_core::linalg::{solve_with, DenseFactor};
use noether_core::{Error, Momenta, Newton, NewtonInfo, NewtonSystem, Result, State, StepInfo, Stepper};

/// Default absolute Newton tolerance on the momentum residual.
pub(crate) const DEFAULT_TOL: f64 = 1e-16;

/// The Newton settings for a step from momentum `p`: the residual tolerance raised to the rounding floor
/// 2ε‖p‖∞ when the requested one is below it.
pub(crate) fn effective_newton(newton: &Newton, p: &[f64]) -> Newton {
    let floor = 2.0 * f64::EPSILON * noether_core::newton::max_norm(p);
    newton.residual_floor(floor)
}

/// `Newton::default()` with the residual tolerance [`DEFAULT_TOL`].
pub(crate) fn default_newton() -> Newton {
    Newton::default()
        .residual_tolerance(DEFAULT_TOL)
        .expect("DEFAULT_TOL is finite and positive")
}

/// The discrete Euler-Lagrange equation of one step as a Newton system in the increment
/// Δ = q_{k+1} − q_k.
struct DelSystem<'a, Ld: ?Sized> {
    ld: &'a Ld,
    t0: f64,
    h: f64,
    q0: &'a [f64],
    p0: &'a [f64],
    /// q₀ + Δ.
    q1: &'a mut [f64],
    jac: &'a mut DMatrix<f64>,
    lu: &'a mut Option<DenseFactor>,
    fm: &'a mut [f64],
    fp: &'a mut [f64],
}

const JACOBIAN: &str = "discrete Euler-Lagrange Jacobian D₁₂L_d + ∂f⁻/∂q₁";

impl<Ld: DiscreteLagrangian + ?Sized> DelSystem<'_, Ld> {
    fn end(&mut self, d: &[f64]) {
        for ((q1, q0), di) in self.q1.iter_mut().zip(self.q0).zip(d) {
            *q1 = q0 + di;
        }
    }
}

impl<Ld: DiscreteLagrangian + ?Sized> NewtonSystem for DelSystem<'_, Ld> {
    fn dim(&self) -> usize {
        self.q0.len()
    }
    fn residual(&mut self, d: &[f64], r: &mut [f64]) -> Result<()> {
        self.end(d);
        self.ld.d1(self.t0, self.h, self.q0, self.q1, r);
        r.iter_mut().zip(self.p0).for_each(|(ri, pi)| *ri += pi);
        if self.ld.has_discrete_force() {
            self.ld
                .discrete_force(self.t0, self.h, self.q0, self.q1, self.fm, self.fp);
            r.iter_mut().zip(self.fm.iter()).for_each(|(ri, fi)| *ri += fi);
        }
        Ok(())
    }
    fn factor_jacobian(&mut self, d: &[f64]) -> Result<()> {
        self.end(d);
        self.ld.d12(self.t0, self.h, self.q0, self.q1, self.jac);
        if self.ld.has_discrete_force() {
            let n = self.q0.len();
            let (mut dm, mut dp) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
            let ends = (self.q0, &*self.q1);
            self.ld
                .force_derivatives(self.t0, self.h, ends, StepEnd::Right, (&mut dm, &mut dp));
            *self.jac += dm;
        }
        *self.lu = None;
        let f = DenseFactor::lu(self.jac.clone()).map_err(|e| e.in_matrix(JACOBIAN))?;
        *self.lu = Some(f);
        Ok(())
    }
    fn solve(&mut self, rhs: &mut [f64]) -> Result<()> {
        solve_with(self.lu.as_ref(), rhs, JACOBIAN)
    }
}

/// The variational integrator of a discrete Lagrangian, in position-momentum form (see the module docs).
///
/// As a [`Stepper`] it advances a [`State`] whose `v` holds the momenta p.
pub struct VariationalIntegrator<Ld> {
    ld: Ld,
    newton: Newton,
    predictor: Predictor,
    /// The increment Δ = q_{k+1} − q_k (Newton's unknown).
    d: Vec<f64>,
    q1: Vec<f64>,
    dp: Vec<f64>,
    fm: Vec<f64>,
    fp: Vec<f64>,
    jac: DMatrix<f64>,
    lu: Option<DenseFactor>,
    last: NewtonInfo,
    /// Step size of the Jacobian factor kept from the last step.
    factor_h: f64,
    /// Relative tolerance of the primary-constraint check.
    primary_tol: f64,
    /// The state (q, p) the last step ended at, one after the other: a step from it skips the check.
    end: Vec<f64>,
}

impl<Ld: DiscreteLagrangian> VariationalIntegrator<Ld> {
    /// The integrator of `ld`, with Newton solved to rounding: residual ‖p_k + D₁L_d + f⁻‖∞ at most
    /// max(1e-16, 2ε‖p_k‖∞) (see [`newton`](Self::newton)), at most 50 iterations.
    pub fn new(ld: Ld) -> Self {
        let n = ld.dof();
        VariationalIntegrator {
            ld,
            newton: default_newton(),
            predictor: Predictor::default(),
            d: vec![0.0; n],
            q1: vec![0.0; n],
            dp: vec![0.0; n],
            fm: vec![0.0; n],
            fp: vec![0.0; n],
            jac: DMatrix::zeros(n, n),
            lu: None,
            last: NewtonInfo::default(),
            factor_h: f64::NAN,
            primary_tol: crate::primary::DEFAULT_TOLERANCE,
            end: Vec::new(),
        }
    }

    /// Replaces the relative tolerance τ of the check of a starting state's momenta against the primary
    /// constraint of a degenerate Lagrangian (default [`primary::DEFAULT_TOLERANCE`](crate::primary::DEFAULT_TOLERANCE)
    /// = 1e-8; see [`primary`](crate::primary)). `InvalidParameter` unless τ is finite and positive.
    pub fn primary_tolerance(mut self, tol: f64) -> Result<Self> {
        if !(tol.is_finite() && tol > 0.0) {
            return Err(Error::InvalidParameter {
                name: "primary-constraint tolerance",
                value: tol,
                reason: "must be finite and positive",
            });
        }
        self.primary_tol = tol;
        Ok(self)
    }

    /// The relative tolerance of the primary-constraint check.
    pub fn get_primary_tolerance(&self) -> f64 {
        self.primary_tol
    }

    /// Replaces the Newton settings (iteration cap, Jacobian reuse, and the absolute tolerance τ on the
    /// residual). A step is solved to ‖p_k + D₁L_d + f⁻‖∞ ≤ max(τ, 2ε‖p_k‖∞): the second bound is the
    /// rounding floor of the residual. A conserved Noether momentum J = p·ξ(q) changes per step by
    /// R·ξ(Δ) (module docs), so a loose τ (the paper uses 1e-8) lets an angular momentum drift by up to
    /// τ|Δ| per step; for translations (ξ constant) one Newton iteration already removes the residual's
    /// component along ξ, which is linear in Δ.
    pub fn newton(mut self, newton: Newton) -> Self {
        self.newton = newton;
        self
    }

    /// The Newton settings.
    pub fn get_newton(&self) -> &Newton {
        &self.newton
    }

    /// The discrete Lagrangian.
    pub fn discrete_lagrangian(&self) -> &Ld {
        &self.ld
    }

    /// Statistics of the last successful Newton solve.
    pub fn last_newton(&self) -> NewtonInfo {
        self.last
    }

    /// The state at `t0 + h` reached from two positions q₀ (at t₀) and q₁ (at t₀ + h), as the paper
    /// starts: p₁ = D₂L_d(q₀, q₁) + f⁺(q₀, q₁).
    pub fn state_from_positions(&self, t0: f64, h: f64, q0: &[f64], q1: &[f64]) -> Result<State<Momenta>> {
        check_flow_args(self.ld.dof(), t0, h, q0, q1)?;
        let n = self.ld.dof();
        let mut p1 = vec![0.0; n];
        self.ld.d2(t0, h, q0, q1, &mut p1);
        if self.ld.has_discrete_force() {
            let (mut fm, mut fp) = (vec![0.0; n], vec![0.0; n]);
            self.ld.discrete_force(t0, h, q0, q1, &mut fm, &mut fp);
            p1.iter_mut().zip(&fp).for_each(|(p, f)| *p += f);
        }
        check_finite("p₁ = D₂L_d(q₀, q₁)", &p1)?;
        Ok(State::with_momenta(t0 + h, q1.to_vec(), p1))
    }

    /// The discrete momentum of a step, p_k = −D₁L_d(q_k, q_{k+1}) − f⁻: the left end of the discrete
    /// Legendre transform (equal to the state's p when q_{k+1} is the step taken from it).
    pub fn momentum_minus(&self, t0: f64, h: f64, q0: &[f64], q1: &[f64]) -> Result<DVector<f64>> {
        check_flow_args(self.ld.dof(), t0, h, q0, q1)?;
        let n = self.ld.dof();
        let mut p = vec![0.0; n];
        self.ld.d1(t0, h, q0, q1, &mut p);
        if self.ld.has_discrete_force() {
            let (mut fm, mut fp) = (vec![0.0; n], vec![0.0; n]);
            self.ld.discrete_force(t0, h, q0, q1, &mut fm, &mut fp);
            p.iter_mut().zip(&fm).for_each(|(p, f)| *p += f);
        }
        Ok(DVector::from_iterator(n, p.into_iter().map(|x| -x)))
    }
}

impl<Ld: DiscreteLagrangian + FromLagrangian> VariationalIntegrator<Ld> {
    /// The state (t, q, p) from positions and velocities through the continuous Legendre map
    /// p = ∂L/∂q̇(t, q, q̇).
    pub fn state_from_velocities(&self, t: f64, q: &[f64], v: &[f64]) -> Result<State<Momenta>> {
        self.ld.state_from_velocities(t, q, v)
    }

    /// The velocities q̇ of a state (t, q, p) through the inverse continuous Legendre map.
    pub fn velocities(&self, state: &State<Momenta>) -> Result<DVector<f64>> {
        self.ld.velocities_at(state)
    }

    /// The energy h = q̇·∂L/∂q̇ − L of the continuous system at a discrete state (t, q, p), with q̇ from
    /// the inverse Legendre map.
    pub fn energy(&self, state: &State<Momenta>) -> Result<f64> {
        self.ld.energy_at(state)
    }
}

impl<Ld: DiscreteLagrangian> Stepper for VariationalIntegrator<Ld> {
    type Partner = Momenta;
    fn step(&mut self, state: &mut State<Momenta>, h: f64) -> Result<StepInfo> {
        step_forward(self, state, h)
    }
    fn dof(&self) -> usize {
        self.ld.dof()
    }
    fn order(&self) -> u32 {
        self.ld.order()
    }
    fn rates(&self, state: &State<Momenta>, dq: &mut [f64], dp: &mut [f64]) -> Option<Result<()>> {
        let (t, q, p) = (state.t, state.q.as_slice(), state.v.as_slice());
        self.ld.continuous_rates(t, q, p, dq, dp)
    }
    fn name(&self) -> &'static str {
        "variational (position-momentum)"
    }
}

impl<Ld: DiscreteLagrangian> VariationalIntegrator<Ld> {
    /// The update (q, p) ← (q', p') from time `t` over the signed step `h` (arguments checked by the
    /// caller); on error `q` and `p` are left as they were. Returns the Newton iterations spent.
    fn advance(&mut self, t: f64, h: f64, q: &mut [f64], p: &mut [f64]) -> Result<usize> {
        let n = self.ld.dof();
        check_len("q₁ (workspace)", &self.q1, n)?;
        let continues = self.end.len() == 2 * n && self.end[..n] == *q && self.end[n..] == *p;
        if !continues {
            self.ld.check_momenta(t, q, p, self.primary_tol)?;
        }
        self.predictor.guess_increment(q, h, &mut self.d);
        let mut sys = DelSystem {
            ld: &self.ld,
            t0: t,
            h,
            q0: q,
            p0: p,
            q1: &mut self.q1,
            jac: &mut self.jac,
            lu: &mut self.lu,
            fm: &mut self.fm,
            fp: &mut self.fp,
        };
        let newton = effective_newton(&self.newton, p);
        let info = newton.solve(&mut sys, &mut self.d).map_err(|e| e.at_time(t))?;
        if info.iterations > 0 {
            self.factor_h = h;
        }
        if info.iterations == 0 {
            let factored = self.factor_h == h && sys.lu.is_some();
            self.factor_h = h;
            correct_once(&mut sys, &mut self.d, factored)?;
        }
        // p_{k+1} = D₂L_d + f⁺ = p_k + (D₁ + D₂)L_d + f⁻ + f⁺ − R, R the Newton residual; the
        // increment form drops R, so that a symmetry ξ (linear in q) changes p·ξ(q) per step by R·ξ(Δ)
        // only, instead of R·ξ(q_k).
        self.ld.d1_plus_d2(t, h, q, &self.q1, &mut self.dp);
        if self.ld.has_discrete_force() {
            self.ld
                .discrete_force(t, h, q, &self.q1, &mut self.fm, &mut self.fp);
            for ((dp, fm), fp) in self.dp.iter_mut().zip(&self.fm).zip(&self.fp) {
                *dp += fm + fp;
            }
        }
        if self.d.iter().chain(&self.dp).any(|x| !x.is_finite()) {
            return Err(Error::NonFiniteResult {
                what: "state after the step",
                t,
                component: None,
            });
        }
        // q_{k+1} is the point L_d was evaluated at, so the discrete Noether identity
        // D₁L_d·ξ(q_k) + D₂L_d·ξ(q_{k+1}) = 0 holds for the state as stored.
        q.copy_from_slice(&self.q1);
        p.iter_mut().zip(&self.dp).for_each(|(pi, di)| *pi += di);
        self.predictor.record_increment(q, &self.d, h);
        self.end.clear();
        self.end.extend_from_slice(q);
        self.end.extend_from_slice(p);
        self.last = info;
        Ok(info.iterations)
    }
}

impl<Ld: DiscreteLagrangian> SignedStepper for VariationalIntegrator<Ld> {
    fn step_signed(&mut self, state: &mut State<Momenta>, h: f64) -> Result<StepInfo> {
        signed_step(self.dof(), state, h, |t, q, p| self.advance(t, h, q, p))
    }
}
