//! A constrained variational integrator (RATTLE type) in position-momentum form.
//!
//! For a discrete Lagrangian L_d(q_k, q_{k+1}, h) (midpoint or trapezoidal rule of noether-discrete)
//! and holonomic constraints φ(t, q) = 0 with Jacobian G = Φ_q, one step (t_k, q_k, p_k) ↦
//! (t_{k+1}, q_{k+1}, p_{k+1}) solves, by Newton in (q_{k+1}, Λ),
//!
//! ```text
//! p_k + D₁L_d(q_k, q_{k+1}) + G(t_k, q_k)ᵀ Λ = 0,      φ(t_{k+1}, q_{k+1}) = 0,
//! ```
//!
//! then, by Newton in (q̇_{k+1}, Μ) (linear, one iteration, when L is quadratic in q̇),
//!
//! ```text
//! ∂L/∂q̇(t_{k+1}, q_{k+1}, q̇_{k+1}) = D₂L_d(q_k, q_{k+1}) + G(t_{k+1}, q_{k+1})ᵀ Μ,
//! G(t_{k+1}, q_{k+1}) q̇_{k+1} + φ_t(t_{k+1}, q_{k+1}) = 0,
//! ```
//!
//! and sets p_{k+1} = D₂L_d + GᵀΜ. Generalized forces Q(t, q, q̇) of the Lagrangian enter by the
//! discrete Lagrange-d'Alembert principle: the discrete forces f⁻ and f⁺ of L_d are added to D₁L_d
//! and D₂L_d, and Newton's Jacobian gains ∂f⁻/∂q_{k+1} (by dual numbers). Positions and momenta stay
//! on the constraint manifold (the second stage is the "hidden" velocity constraint); without forces
//! the map is symplectic on it, and for a symmetry with
//! generator ξ that leaves L_d invariant and is tangent to the constraints (G ξ = 0) the discrete
//! momentum p·ξ(q) is conserved: the multiplier terms vanish along ξ. With the trapezoidal L_d of
//! L = ½ q̇ᵀMq̇ − V this is exactly RATTLE. The discrete multipliers Λ, Μ are impulses over half a step;
//! λ ≈ 2Λ/h ≈ 2Μ/h estimates the continuous multiplier (constraint force Gᵀλ).
//!
//! ```
//! use noether_constraints::prelude::*;
//! use noether_discrete::Midpoint;
//!
//! /// A point mass on a sphere of radius 1 (spherical pendulum), z up.
//! struct Mass;
//! impl Lagrangian for Mass {
//!     fn dof(&self) -> usize { 3 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * 0.5 - q[2] * 9.81
//!     }
//! }
//! struct Sphere;
//! impl Holonomic for Sphere {
//!     fn dof(&self) -> usize { 3 }
//!     fn count(&self) -> usize { 1 }
//!     fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
//!         out[0] = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - 1.0) * 0.5;
//!     }
//! }
//!
//! let mut rattle = Rattle::new(Midpoint::new(Mass), Sphere).unwrap();
//! let mut s = rattle.state_from_velocities(0.0, &[0.6, 0.0, -0.8], &[0.0, 2.0, 0.0]).unwrap();
//! let lz = |s: &State<Momenta>| s.q[0] * s.p()[1] - s.q[1] * s.p()[0]; // discrete Noether momentum of z-rotations
//! let l0 = lz(&s);
//! for _ in 0..1000 {
//!     rattle.step(&mut s, 0.01).unwrap();
//!     assert!(rattle.last_step().position_residual < 1e-12);
//! }
//! assert!((lz(&s) - l0).abs() < 1e-13);
//! ```
//!
//! # References
//! E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., §VII.1.4 (RATTLE);
//! J. E. Marsden and M. West, *Discrete mechanics and variational integrators*, Acta Numerica 10 (2001),
//! §3.4 (constrained variational integrators).

use crate::dynamics::{max_abs, rank_error, within};
use crate::holonomic::{self, Holonomic};
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector};
use noether_core::error::{check_positive, check_step};
use noether_core::linalg::{solve_with, DenseFactor};
use noether_core::newton::{Dense, DenseProblem};
use noether_core::{
    Error as CoreError, EulerLagrange, Lagrangian, Momenta, Newton, NewtonSystem, State, StepInfo, Stepper,
};
use noether_discrete::{DiscreteDerivatives, DiscreteLagrangian, FromLagrangian, StepEnd};

/// What the last step of a [`Rattle`] integrator did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RattleInfo {
    /// ‖φ(t_{k+1}, q_{k+1})‖∞ after the step.
    pub position_residual: f64,
    /// ‖G q̇_{k+1} + φ_t‖∞ after the step.
    pub velocity_residual: f64,
    /// Newton iterations of the position stage.
    pub iterations: usize,
    /// Newton iterations of the momentum stage.
    pub momentum_iterations: usize,
}

/// The constrained variational integrator (see the module docs). As a core [`Stepper`] it advances a
/// [`State`] whose `v` holds the momenta p.
pub struct Rattle<Ld, C> {
    ld: Ld,
    constraints: C,
    newton: Newton,
    violation: f64,
    last: RattleInfo,
    worst: (f64, f64),
    multipliers: (DVector<f64>, DVector<f64>),
    /// The last output (t, q, p) and its velocities: a state equal to it needs no re-validation.
    cache: Option<(State<Momenta>, DVector<f64>)>,
    mass_scale: Option<f64>,
    symmetric: Option<(f64, DVector<f64>)>,
    constant_mass: Option<DMatrix<f64>>,
    /// The factored stage-1 Jacobian of the last step and its step size.
    stage1_lu: Option<(f64, Lu)>,
}

type Lu = DenseFactor;

/// Absolute Newton tolerance on the (scaled) residual, below what rounding allows on purpose: Newton
/// stops when its step reaches rounding level (‖Δx‖∞ ≤ 1e-15 (1 + ‖x‖∞)): a residual
/// merely below a tolerance would leave its component along a symmetry in the discrete Noether momenta.
const DEFAULT_TOL: f64 = 1e-20;

impl<Ld, C> Rattle<Ld, C>
where
    Ld: DiscreteLagrangian + FromLagrangian,
    C: Holonomic,
{
    /// The integrator of the discrete Lagrangian `ld` (built from a continuous Lagrangian, e.g.
    /// `Midpoint::new(l)`) with holonomic `constraints`.
    pub fn new(ld: Ld, constraints: C) -> Result<Self> {
        if constraints.dof() != ld.dof() {
            return Err(CoreError::Dimension {
                what: "coordinates of the constraints",
                expected: ld.dof(),
                got: constraints.dof(),
            }
            .into());
        }
        let m = constraints.count();
        Ok(Rattle {
            ld,
            constraints,
            newton: Newton::default()
                .residual_tolerance(DEFAULT_TOL)?
                .step_tolerance(1e-15)?,
            violation: 1e-9,
            last: RattleInfo::default(),
            worst: (0.0, 0.0),
            multipliers: (DVector::zeros(m), DVector::zeros(m)),
            cache: None,
            mass_scale: None,
            symmetric: None,
            constant_mass: None,
            stage1_lu: None,
        })
    }

    /// Replaces the Newton settings of both stages.
    pub fn newton(mut self, newton: Newton) -> Self {
        self.newton = newton;
        self
    }

    /// Sets the largest constraint residual accepted in an incoming state (default 1e-9; finite and
    /// positive).
    pub fn violation_tolerance(mut self, tol: f64) -> Result<Self> {
        self.violation = check_positive("violation tolerance", tol)?;
        Ok(self)
    }

    /// The discrete Lagrangian.
    pub fn discrete_lagrangian(&self) -> &Ld {
        &self.ld
    }

    /// The constraints.
    pub fn constraints(&self) -> &C {
        &self.constraints
    }

    /// What the last step did.
    pub fn last_step(&self) -> RattleInfo {
        self.last
    }

    /// Largest (position, velocity) constraint residual after any step so far.
    pub fn max_residual(&self) -> (f64, f64) {
        self.worst
    }

    /// First-order estimates of the continuous multipliers λ at the start and at the end of the last
    /// step, 2Λ/h and 2Μ/h (the constraint force is Gᵀλ).
    pub fn multipliers(&self) -> (&DVector<f64>, &DVector<f64>) {
        (&self.multipliers.0, &self.multipliers.1)
    }

    /// The second-order estimate of λ at the start t_k of the last step, (Μ_{k−1} + Λ_k)/h: the
    /// impulses of the half steps on either side of t_k. `None` until two consecutive steps were taken.
    pub fn multipliers_symmetric(&self) -> Option<(f64, &DVector<f64>)> {
        self.symmetric.as_ref().map(|(t, l)| (*t, l))
    }

    /// The state (t, q, p = ∂L/∂q̇) of positions and velocities; both must satisfy the constraints
    /// (see [`check_state`](Self::check_state)).
    pub fn state_from_velocities(&self, t: f64, q: &[f64], v: &[f64]) -> Result<State<Momenta>> {
        Ok(self.ld.state_from_velocities(t, q, v)?)
    }

    /// The velocities q̇ of a state (t, q, p) by the inverse Legendre map.
    pub fn velocities(&self, state: &State<Momenta>) -> Result<DVector<f64>> {
        Ok(self.ld.velocities_at(state)?)
    }

    /// The energy h = q̇·∂L/∂q̇ − L of the continuous system at a state (t, q, p).
    pub fn energy(&self, state: &State<Momenta>) -> Result<f64> {
        Ok(self.ld.energy_at(state)?)
    }

    /// Checks that a state (t, q, p) lies on the constraint manifold to within the violation tolerance:
    /// φ(t, q) = 0 and G q̇ + φ_t = 0 with q̇ from p; returns q̇. The error names the residual.
    pub fn check_state(&self, state: &State<Momenta>) -> Result<DVector<f64>> {
        state.validate(self.ld.dof())?;
        let (t, q) = (state.t, state.q.as_slice());
        let mut r = vec![0.0; self.constraints.count()];
        holonomic::values_unchecked(&self.constraints, t, q, &mut r);
        let res = max_abs(&r);
        if !within(res, self.violation) {
            return Err(Error::ConstraintViolated {
                what: "position",
                t,
                residual: res,
                tolerance: self.violation,
            });
        }
        let v = self.velocities(state)?;
        holonomic::velocity_residual_unchecked(&self.constraints, t, q, v.as_slice(), &mut r);
        let res = max_abs(&r);
        if !within(res, self.violation) {
            return Err(Error::ConstraintViolated {
                what: "velocity",
                t,
                residual: res,
                tolerance: self.violation,
            });
        }
        Ok(v)
    }

    /// The size of the largest mass-matrix entry (computed at the first step and kept: it only scales
    /// the momentum residual, whose difference quotient (q₁ − q₀)/h loses ε‖q‖/h and is multiplied by
    /// M, to position units).
    fn mass_scale(&mut self, t: f64, q: &[f64], v: &[f64]) -> noether_core::Result<f64> {
        if let Some(s) = self.mass_scale {
            return Ok(s);
        }
        let mass = self.ld.continuous().mass_matrix(t, q, v)?;
        let s = mass.amax();
        self.mass_scale = Some(s);
        if self.ld.continuous().lagrangian().constant_mass_matrix() {
            self.constant_mass = Some(mass);
        }
        Ok(s)
    }

    /// One step from (t, q, p) with incoming velocities `v0`; returns the new (q, p, q̇).
    fn advance(
        &mut self,
        state: &State<Momenta>,
        v0: &DVector<f64>,
        h: f64,
        continued: bool,
    ) -> noether_core::Result<(State<Momenta>, DVector<f64>)> {
        let t0 = state.t;
        let (q1, big_lambda, iterations) = self.position_stage(state, v0, h)?;
        let (v1, big_mu, end) = self.momentum_stage(state, &q1, h)?;
        let (p1, (pos, vel)) = (end.p1, end.residuals);
        if !q1.iter().chain(p1.iter()).all(|z| z.is_finite()) || !pos.is_finite() {
            return Err(CoreError::NonFiniteResult {
                what: "state after the step",
                t: t0,
                component: None,
            });
        }
        self.last = RattleInfo {
            position_residual: pos,
            velocity_residual: vel,
            iterations,
            momentum_iterations: end.iterations,
        };
        self.worst = (self.worst.0.max(pos), self.worst.1.max(vel));
        let start = big_lambda * (2.0 / h);
        // Μ_{k−1}/h from the previous step (stored as 2Μ/h) plus Λ_k/h.
        self.symmetric = continued.then(|| (t0, (&self.multipliers.1 + &start) * 0.5));
        self.multipliers = (start, big_mu * (2.0 / h));
        Ok((State::from_vectors(t0 + h, q1, p1), v1))
    }

    /// Stage 1, the positions: (q₁, Λ) from p₀ + D₁L_d(q₀, q₁) + G(t₀, q₀)ᵀΛ = 0, φ(t₁, q₁) = 0 by
    /// Newton from (q₀ + h q̇₀, the last step's Λ), with the Jacobian's factor kept across steps of
    /// the same h. Returns q₁, Λ and the Newton iterations.
    fn position_stage(
        &mut self,
        state: &State<Momenta>,
        v0: &DVector<f64>,
        h: f64,
    ) -> noether_core::Result<(DVector<f64>, DVector<f64>, usize)> {
        let (n, m) = (self.ld.dof(), self.constraints.count());
        let t0 = state.t;
        let (q0, p0) = (state.q.as_slice(), state.v.as_slice());
        let mut g0 = DMatrix::zeros(m, n);
        holonomic::jacobian_unchecked(&self.constraints, t0, q0, &mut g0);
        // Momentum rows scaled by w = h/s (s: mass scale) and Λ' = wΛ: both blocks then read in units
        // of q, with rounding floor ~ε‖q‖, so the constraint rows converge to rounding as well.
        let w = h / self.mass_scale(t0, q0, v0.as_slice())?;
        let mut x = vec![0.0; n + m];
        for i in 0..n {
            x[i] = q0[i] + h * v0[i];
        }
        x[n..].copy_from_slice(self.multipliers.1.as_slice());
        x[n..].iter_mut().for_each(|l| *l *= 0.5 * h * w);
        let stage1 = PositionStage {
            ld: &self.ld,
            c: &self.constraints,
            t0,
            h,
            w,
            q0,
            p0,
            g0: &g0,
            d12: DMatrix::zeros(n, n),
            g1: DMatrix::zeros(m, n),
        };
        let newton1 = self.newton;
        let reuse =
            self.newton.get_reuse_jacobian() && self.stage1_lu.as_ref().is_some_and(|(hh, _)| *hh == h);
        let mut sys = AcrossSteps {
            problem: stage1,
            jac: DMatrix::zeros(n + m, n + m),
            lu: &mut self.stage1_lu,
            h,
            may_reuse: reuse,
        };
        let mut info1 = newton1
            .solve(&mut sys, &mut x)
            .map_err(|e| singular_as_rank(e, &g0, t0))?;
        // A reused factor converges linearly and stops with an error ~ρ·(last step); two more cheap
        // iterations with the same factor bring the residual along any symmetry down to rounding, as
        // quadratic convergence would.
        if reuse {
            let mut r = vec![0.0; n + m];
            for _ in 0..2 {
                sys.residual(&x, &mut r)?;
                sys.solve(&mut r)?;
                x.iter_mut().zip(&r).for_each(|(xi, ri)| *xi -= ri);
                info1.iterations += 1;
            }
        }
        let q1 = DVector::from_column_slice(&x[..n]);
        let big_lambda = DVector::from_column_slice(&x[n..]) / w;
        Ok((q1, big_lambda, info1.iterations))
    }

    /// Stage 2, the velocities and momenta: (q̇₁, Μ) from ∂L/∂q̇(t₁, q₁, q̇₁) = D₂L_d(q₀, q₁) +
    /// G(t₁, q₁)ᵀΜ, G(t₁, q₁) q̇₁ + φ_t = 0 by Newton from (q₁ − q₀)/h; p₁ = D₂L_d + G₁ᵀΜ. Returns
    /// q̇₁, Μ, and p₁ with the residuals |φ|, |G₁q̇₁ + φ_t| (max norms) left on the manifold.
    fn momentum_stage(
        &mut self,
        state: &State<Momenta>,
        q1: &DVector<f64>,
        h: f64,
    ) -> noether_core::Result<(DVector<f64>, DVector<f64>, MomentumEnd)> {
        let (n, m) = (self.ld.dof(), self.constraints.count());
        let (t0, t1) = (state.t, state.t + h);
        let q0 = state.q.as_slice();
        let mut d2 = vec![0.0; n];
        self.ld.d2(t0, h, q0, q1.as_slice(), &mut d2);
        if self.ld.has_discrete_force() {
            // D₂L_d + f⁺ in place of D₂L_d.
            let (mut fm, mut fp) = (vec![0.0; n], vec![0.0; n]);
            self.ld.discrete_force(t0, h, q0, q1.as_slice(), &mut fm, &mut fp);
            d2.iter_mut().zip(&fp).for_each(|(d, f)| *d += f);
        }
        let mut g1 = DMatrix::zeros(m, n);
        holonomic::jacobian_unchecked(&self.constraints, t1, q1.as_slice(), &mut g1);
        let mut phi_t = vec![0.0; m];
        holonomic::partial_t_unchecked(&self.constraints, t1, q1.as_slice(), &mut phi_t);
        let mut y = vec![0.0; n + m];
        for i in 0..n {
            y[i] = (q1[i] - q0[i]) / h;
        }
        let stage2 = MomentumStage {
            el: self.ld.continuous(),
            mass: self.constant_mass.as_ref(),
            t1,
            q1: q1.as_slice(),
            d2: &d2,
            g1: &g1,
            phi_t: &phi_t,
        };
        let mut sys = Dense::new(stage2);
        let info2 = self
            .newton
            .solve(&mut sys, &mut y)
            .map_err(|e| singular_as_rank(e, &g1, t1))?;
        let v1 = DVector::from_column_slice(&y[..n]);
        let big_mu = DVector::from_column_slice(&y[n..]);
        let p1 = DVector::from_column_slice(&d2) + g1.tr_mul(&big_mu);
        // Residuals left on the manifold.
        let mut r = vec![0.0; m];
        holonomic::values_unchecked(&self.constraints, t1, q1.as_slice(), &mut r);
        let pos = max_abs(&r);
        let gv = &g1 * &v1;
        let vel = gv
            .iter()
            .zip(&phi_t)
            .fold(0.0_f64, |a, (x, y)| a.max((x + y).abs()));
        let end = MomentumEnd {
            p1,
            residuals: (pos, vel),
            iterations: info2.iterations,
        };
        Ok((v1, big_mu, end))
    }
}

/// The end of the momentum stage: p₁, the residuals (|φ(t₁, q₁)|, |G₁q̇₁ + φ_t|) in the max norm
/// left on the manifold, and the stage's Newton iterations.
struct MomentumEnd {
    p1: DVector<f64>,
    residuals: (f64, f64),
    iterations: usize,
}

/// A singular Newton Jacobian is reported as rank-deficient constraints when G has low rank.
fn singular_as_rank(e: CoreError, g: &DMatrix<f64>, t: f64) -> CoreError {
    match e {
        CoreError::SingularMatrix { .. } => rank_error(g, t).map_or(e, CoreError::from),
        e => e,
    }
}

/// A dense Newton system whose factored Jacobian is kept from one step to the next (modified Newton
/// across steps): the first factorization a solve asks for is the previous step's, which the core
/// Newton keeps while the residual contracts by its factor and refreshes otherwise.
struct AcrossSteps<'a, P> {
    problem: P,
    jac: DMatrix<f64>,
    lu: &'a mut Option<(f64, Lu)>,
    h: f64,
    may_reuse: bool,
}

impl<P: DenseProblem> NewtonSystem for AcrossSteps<'_, P> {
    fn dim(&self) -> usize {
        self.problem.dim()
    }
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> noether_core::Result<()> {
        self.problem.residual(x, r)
    }
    fn factor_jacobian(&mut self, x: &[f64]) -> noether_core::Result<()> {
        if std::mem::take(&mut self.may_reuse) && self.lu.is_some() {
            return Ok(());
        }
        *self.lu = None;
        self.problem.jacobian(x, &mut self.jac)?;
        let lu = DenseFactor::lu(self.jac.clone())
            .map_err(|e| e.in_matrix("constrained variational Jacobian [D₁₂L_d G₀ᵀ; G₁ 0]"))?;
        *self.lu = Some((self.h, lu));
        Ok(())
    }
    fn solve(&mut self, rhs: &mut [f64]) -> noether_core::Result<()> {
        let lu = self.lu.as_ref().map(|(_, lu)| lu);
        solve_with(lu, rhs, "constrained variational Jacobian")
    }
}

/// Stage 1: F(q₁, Λ') = (w (p₀ + D₁L_d(q₀, q₁)) + G₀ᵀΛ', φ(t₁, q₁)) with Λ' = wΛ.
struct PositionStage<'a, Ld, C> {
    ld: &'a Ld,
    c: &'a C,
    t0: f64,
    h: f64,
    w: f64,
    q0: &'a [f64],
    p0: &'a [f64],
    g0: &'a DMatrix<f64>,
    d12: DMatrix<f64>,
    g1: DMatrix<f64>,
}

impl<Ld: DiscreteLagrangian, C: Holonomic> DenseProblem for PositionStage<'_, Ld, C> {
    fn dim(&self) -> usize {
        self.q0.len() + self.c.count()
    }
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> noether_core::Result<()> {
        let n = self.q0.len();
        let (q1, lam) = x.split_at(n);
        let (ra, rb) = r.split_at_mut(n);
        self.ld.d1(self.t0, self.h, self.q0, q1, ra);
        if self.ld.has_discrete_force() {
            let (mut fm, mut fp) = (vec![0.0; n], vec![0.0; n]);
            self.ld
                .discrete_force(self.t0, self.h, self.q0, q1, &mut fm, &mut fp);
            ra.iter_mut().zip(&fm).for_each(|(ri, fi)| *ri += fi);
        }
        for (i, ri) in ra.iter_mut().enumerate() {
            let gl: f64 = (0..lam.len()).map(|k| self.g0[(k, i)] * lam[k]).sum();
            *ri = self.w * (*ri + self.p0[i]) + gl;
        }
        holonomic::values_unchecked(self.c, self.t0 + self.h, q1, rb);
        Ok(())
    }
    fn jacobian(&mut self, x: &[f64], j: &mut DMatrix<f64>) -> noether_core::Result<()> {
        let n = self.q0.len();
        let m = self.c.count();
        let q1 = &x[..n];
        self.ld.d12(self.t0, self.h, self.q0, q1, &mut self.d12);
        if self.ld.has_discrete_force() {
            let (mut dm, mut dp) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
            let ends = (self.q0, q1);
            self.ld
                .force_derivatives(self.t0, self.h, ends, StepEnd::Right, (&mut dm, &mut dp));
            self.d12 += dm;
        }
        holonomic::jacobian_unchecked(self.c, self.t0 + self.h, q1, &mut self.g1);
        j.fill(0.0);
        j.view_mut((0, 0), (n, n)).copy_from(&(&self.d12 * self.w));
        j.view_mut((0, n), (n, m)).copy_from(&self.g0.transpose());
        j.view_mut((n, 0), (m, n)).copy_from(&self.g1);
        Ok(())
    }
}

/// Stage 2: F(q̇₁, Μ) = (∂L/∂q̇(t₁, q₁, q̇₁) − D₂L_d − G₁ᵀΜ, G₁ q̇₁ + φ_t).
struct MomentumStage<'a, L> {
    el: &'a EulerLagrange<L>,
    /// The mass matrix when the Lagrangian declares it constant.
    mass: Option<&'a DMatrix<f64>>,
    t1: f64,
    q1: &'a [f64],
    d2: &'a [f64],
    g1: &'a DMatrix<f64>,
    phi_t: &'a [f64],
}

impl<L: Lagrangian> DenseProblem for MomentumStage<'_, L> {
    fn dim(&self) -> usize {
        self.q1.len() + self.phi_t.len()
    }
    fn residual(&mut self, y: &[f64], r: &mut [f64]) -> noether_core::Result<()> {
        let n = self.q1.len();
        let (v, mu) = y.split_at(n);
        let (ra, rb) = r.split_at_mut(n);
        self.el.momenta(self.t1, self.q1, v, ra)?;
        for (i, ri) in ra.iter_mut().enumerate() {
            let gm: f64 = (0..mu.len()).map(|k| self.g1[(k, i)] * mu[k]).sum();
            *ri -= self.d2[i] + gm;
        }
        for (k, rk) in rb.iter_mut().enumerate() {
            *rk = (0..n).map(|i| self.g1[(k, i)] * v[i]).sum::<f64>() + self.phi_t[k];
        }
        Ok(())
    }
    fn jacobian(&mut self, y: &[f64], j: &mut DMatrix<f64>) -> noether_core::Result<()> {
        let n = self.q1.len();
        let m = self.phi_t.len();
        j.fill(0.0);
        match self.mass {
            Some(mass) => j.view_mut((0, 0), (n, n)).copy_from(mass),
            None => {
                let mass = self.el.mass_matrix(self.t1, self.q1, &y[..n])?;
                j.view_mut((0, 0), (n, n)).copy_from(&mass);
            }
        }
        j.view_mut((0, n), (n, m)).copy_from(&(-self.g1.transpose()));
        j.view_mut((n, 0), (m, n)).copy_from(self.g1);
        Ok(())
    }
}

impl<Ld, C> Stepper for Rattle<Ld, C>
where
    Ld: DiscreteLagrangian + FromLagrangian,
    C: Holonomic,
{
    type Partner = Momenta;
    fn step(&mut self, state: &mut State<Momenta>, h: f64) -> noether_core::Result<StepInfo> {
        check_step(h)?;
        noether_core::error::check_time_resolution(state.t, h)?;
        // A state that is exactly the last output is on the manifold; anything else is checked.
        let (v0, continued) = match &self.cache {
            Some((s, v)) if s == state => (v.clone(), true),
            _ => {
                let v = self.check_state(state)?;
                self.multipliers.1.fill(0.0);
                (v, false)
            }
        };
        let (next, v1) = self.advance(state, &v0, h, continued)?;
        *state = next;
        self.cache = Some((state.clone(), v1));
        let iterations = self.last.iterations + self.last.momentum_iterations;
        Ok(StepInfo::fixed(h)
            .with_newton(iterations, 0)
            .with_evaluations(iterations + 2))
    }
    fn dof(&self) -> usize {
        self.ld.dof()
    }
    fn order(&self) -> u32 {
        self.ld.order()
    }
    fn name(&self) -> &'static str {
        "constrained variational (RATTLE)"
    }
}
