//! The constrained equations of motion: accelerations and multipliers from one index-1 system.
//!
//! For a Lagrangian L(t, q, q̇) with mass matrix M = ∂²L/∂q̇², forces
//! f = ∂L/∂q − (∂²L/∂q̇∂q) q̇ − ∂²L/∂q̇∂t + Q, and constraints A(t, q) q̇ + a(t, q) = 0 (for holonomic
//! constraints A = Φ_q), Lagrange's equations with multipliers are
//!
//! ```text
//! M q̈ = f + Aᵀλ,    A q̈ + c = 0     ⇔     ⎡ M  Aᵀ ⎤ ⎡ q̈ ⎤   ⎡  f ⎤
//!                                          ⎣ A  0  ⎦ ⎣ −λ ⎦ = ⎣ −c ⎦
//! ```
//!
//! with c the acceleration bias of [`ConstraintSet`] (for holonomic constraints
//! c = (Φ_q q̇)_q q̇ + 2Φ_qt q̇ + φ_tt). The system is solved as a whole by LU, so M may be singular as
//! long as it is definite on the velocities the constraints allow (a coordinate without kinetic energy
//! that the constraints tie to the others, as in the cycloid example). The generalized constraint force
//! is Aᵀλ.
//!
//! [`Constrained`] implements core's [`Dynamics`], so every continuous integrator of core for a general
//! vector field steps it (Euler, Euler-Cromer, RK4, the adaptive Dormand-Prince pairs; tested); wrap
//! the stepper in [`Projected`](crate::Projected) to stay on the constraint manifold. The split
//! symplectic methods need a separable system, which the constrained field is not: use
//! [`Rattle`](crate::Rattle) for a structure-preserving constrained integrator.

use crate::forces::ConstraintForces;
use crate::holonomic::{Holonomic, HolonomicSet};
use crate::nonholonomic::{Nonholonomic, NonholonomicSet};
use crate::set::ConstraintSet;
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector};
use noether_core::ad::{self, Block, Field};
use noether_core::error::{check_len, check_phase_point, check_positive};
use noether_core::linalg::DenseFactor;
use noether_core::system::LinearizedDynamics;
use noether_core::{Dynamics, Error as CoreError, EulerLagrange, Lagrangian, Scalar, State};
use std::sync::OnceLock;

/// Singular values of A at or below this fraction of the largest count as zero in the rank diagnosis:
/// linalg's one criterion for a singular matrix,
/// [`SINGULAR_PIVOT`](noether_core::linalg::SINGULAR_PIVOT) (1e-10 before it was shared).
pub const RANK_TOLERANCE: f64 = noether_core::linalg::SINGULAR_PIVOT;

/// A Lagrangian seen as core's AD field f(t, x = q, y = q̇).
pub(crate) struct LagrangianField<'a, L: ?Sized>(pub &'a L);

impl<L: Lagrangian + ?Sized> Field for LagrangianField<'_, L> {
    #[inline]
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D]) -> D {
        self.0.lagrangian(t, x, y)
    }
}

/// A Lagrangian system with constraints: the index-1 equations of motion, multipliers, constraint
/// forces, residuals.
///
/// Stepped by a plain integrator (RK4, DOPRI5) the index-1 equations fix only the accelerations, and
/// the state drifts off the constraints; every step starts by checking the state against
/// [`violation_tolerance`](Self::violation_tolerance) (default 1e-8, max-norm of φ and of A q̇ + a) and
/// stops the run with [`Error::ConstraintViolated`] beyond it. Wrap the stepper in
/// [`Projected`](crate::Projected) (or use [`Rattle`](crate::Rattle)) to stay on the constraints.
pub struct Constrained<L, K> {
    el: EulerLagrange<L>,
    set: K,
    constant_mass: OnceLock<DMatrix<f64>>,
    violation: f64,
}

/// Default of [`Constrained::violation_tolerance`].
pub const DEFAULT_VIOLATION: f64 = 1e-8;

impl<L: Lagrangian, C: Holonomic> Constrained<L, HolonomicSet<C>> {
    /// A Lagrangian with holonomic constraints φ(t, q) = 0.
    pub fn holonomic(lagrangian: L, constraints: C) -> Result<Self> {
        Self::new(lagrangian, HolonomicSet(constraints))
    }
}

impl<L: Lagrangian, C: Nonholonomic> Constrained<L, NonholonomicSet<C>> {
    /// A Lagrangian with velocity constraints A(t, q) q̇ + a(t, q) = 0 (Lagrange-d'Alembert).
    pub fn nonholonomic(lagrangian: L, constraints: C) -> Result<Self> {
        Self::new(lagrangian, NonholonomicSet(constraints))
    }
}

/// The numerical rank of a matrix A and its smallest singular value relative to the largest
/// ([`linalg::rank`](noether_core::linalg::rank): singular values by SVD, counted by linalg's one
/// singularity criterion).
pub fn rank(a: &DMatrix<f64>) -> (usize, f64) {
    noether_core::linalg::rank(a)
}

/// The error for a singular constraint matrix at time `t`: rank deficiency when A has lower rank than
/// its number of rows, otherwise `None`.
pub(crate) fn rank_error(a: &DMatrix<f64>, t: f64) -> Option<Error> {
    let (r, ratio) = rank(a);
    (r < a.nrows()).then_some(Error::RankDeficientConstraints {
        t,
        rank: r,
        count: a.nrows(),
        sigma_ratio: ratio,
    })
}

impl<L: Lagrangian, K: ConstraintSet> Constrained<L, K> {
    /// A Lagrangian with any [`ConstraintSet`]; the two must have the same number of coordinates.
    pub fn new(lagrangian: L, constraints: K) -> Result<Self> {
        if constraints.dof() != lagrangian.dof() {
            return Err(CoreError::Dimension {
                what: "coordinates of the constraint set",
                expected: lagrangian.dof(),
                got: constraints.dof(),
            }
            .into());
        }
        Ok(Constrained {
            el: EulerLagrange::new(lagrangian),
            set: constraints,
            constant_mass: OnceLock::new(),
            violation: DEFAULT_VIOLATION,
        })
    }

    /// Sets the largest constraint residual (max-norm of φ and of A q̇ + a) accepted in the state at the
    /// start of a step; finite and positive.
    pub fn violation_tolerance(mut self, tol: f64) -> Result<Self> {
        self.violation = check_positive("violation tolerance", tol)?;
        Ok(self)
    }

    /// The largest constraint residual accepted in the state at the start of a step.
    pub fn get_violation_tolerance(&self) -> f64 {
        self.violation
    }

    /// Number of coordinates n.
    pub fn dof(&self) -> usize {
        self.el.dof()
    }

    /// Number of constraints m.
    pub fn count(&self) -> usize {
        self.set.count()
    }

    /// The unconstrained Euler-Lagrange equations (energy, momenta, mass matrix).
    pub fn euler_lagrange(&self) -> &EulerLagrange<L> {
        &self.el
    }

    /// The constraint set.
    pub fn constraints(&self) -> &K {
        &self.set
    }

    fn check(&self, t: f64, q: &[f64], v: &[f64]) -> Result<()> {
        Ok(check_phase_point(self.dof(), t, q, v, "q̇")?)
    }

    fn mass(&self, t: f64, q: &[f64], v: &[f64]) -> noether_core::Result<DMatrix<f64>> {
        if self.el.lagrangian().constant_mass_matrix() {
            if let Some(m) = self.constant_mass.get() {
                return Ok(m.clone());
            }
            let m = self.el.mass_matrix(t, q, v)?;
            return Ok(self.constant_mass.get_or_init(|| m).clone());
        }
        self.el.mass_matrix(t, q, v)
    }

    /// Forces f = ∂L/∂q − (∂²L/∂q̇∂q) q̇ − ∂²L/∂q̇∂t + Q into `f`.
    fn forces(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        let lf = LagrangianField(self.el.lagrangian());
        let n = self.dof();
        ad::gradient(&lf, t, q, v, Block::X, f);
        let mut mixed = vec![0.0; n];
        ad::directional_gradient(&lf, t, q, v, (1.0, v, &[]), Block::Y, &mut mixed, None);
        f.iter_mut().zip(&mixed).for_each(|(fi, mi)| *fi -= mi);
        if self.el.lagrangian().has_generalized_force() {
            let mut qf = vec![0.0; n];
            self.el.lagrangian().generalized_force(t, q, v, &mut qf);
            f.iter_mut().zip(&qf).for_each(|(fi, qi)| *fi += qi);
        }
    }

    /// Solves the index-1 system for the accelerations q̈ and the multipliers λ (written into `qdd`
    /// and `lambda`); returns the constraint matrix A used.
    pub fn solve(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        qdd: &mut [f64],
        lambda: &mut [f64],
    ) -> Result<DMatrix<f64>> {
        self.check(t, q, v)?;
        let n = self.dof();
        check_len("q̈ (output)", qdd, n)?;
        check_len("λ (output)", lambda, self.count())?;
        let (_, z, a) = self.saddle(t, q, v)?;
        qdd.copy_from_slice(&z.as_slice()[..n]);
        for (l, x) in lambda.iter_mut().zip(&z.as_slice()[n..]) {
            *l = -x;
        }
        Ok(a)
    }

    /// The saddle-point system [M Aᵀ; A 0] at (t, q, q̇) factored, its solution z = (q̈, −λ) and A
    /// (arguments checked by the caller).
    pub(crate) fn saddle(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
    ) -> Result<(DenseFactor, DVector<f64>, DMatrix<f64>)> {
        let (n, m) = (self.dof(), self.count());
        let mut a = DMatrix::zeros(m, n);
        self.set.matrix(t, q, v, &mut a);
        let mut kkt = DMatrix::zeros(n + m, n + m);
        kkt.view_mut((0, 0), (n, n)).copy_from(&self.mass(t, q, v)?);
        kkt.view_mut((n, 0), (m, n)).copy_from(&a);
        kkt.view_mut((0, n), (n, m)).copy_from(&a.transpose());
        let mut rhs = DVector::zeros(n + m);
        self.forces(t, q, v, &mut rhs.as_mut_slice()[..n]);
        self.set.bias(t, q, v, &mut rhs.as_mut_slice()[n..]);
        rhs.rows_mut(n, m).neg_mut();
        if kkt.iter().chain(rhs.iter()).any(|x| !x.is_finite()) {
            return Err(CoreError::NonFiniteResult {
                what: "constrained equations of motion",
                t,
                component: None,
            }
            .into());
        }
        // The KKT matrix [M Aᵀ; A 0] is symmetric indefinite: LU (core's factorization and pivot test).
        match DenseFactor::lu(kkt) {
            Ok(f) => {
                f.solve_in_place(rhs.as_mut_slice());
                Ok((f, rhs, a))
            }
            // Say why: redundant constraints, or a mass matrix degenerate on the allowed velocities.
            Err(e) => Err(rank_error(&a, t).unwrap_or(e.in_mass_matrix(t).into())),
        }
    }

    /// The multipliers λ at (t, q, q̇).
    pub fn multipliers(&self, t: f64, q: &[f64], v: &[f64]) -> Result<DVector<f64>> {
        let mut qdd = vec![0.0; self.dof()];
        let mut lambda = DVector::zeros(self.count());
        self.solve(t, q, v, &mut qdd, lambda.as_mut_slice())?;
        Ok(lambda)
    }

    /// The constraint forces at (t, q, q̇): multipliers, generalized force Aᵀλ, per-constraint and
    /// (for Cartesian models) per-particle vectors.
    pub fn constraint_forces(&self, t: f64, q: &[f64], v: &[f64]) -> Result<ConstraintForces> {
        let mut qdd = vec![0.0; self.dof()];
        let mut lambda = DVector::zeros(self.count());
        let a = self.solve(t, q, v, &mut qdd, lambda.as_mut_slice())?;
        Ok(ConstraintForces::new(a, lambda))
    }

    /// Residuals of a state: (‖φ(t, q)‖∞ for holonomic sets (`None` otherwise), ‖A q̇ + a‖∞).
    ///
    /// q and q̇ must have n entries ([`CoreError::Dimension`], checked before the constraint
    /// functions see them) and be finite ([`CoreError::NonFinite`]); a residual that comes out NaN or
    /// infinite (a constraint evaluated outside its domain) is [`CoreError::NonFiniteResult`], never a
    /// NaN norm.
    pub fn residuals(&self, t: f64, q: &[f64], v: &[f64]) -> Result<(Option<f64>, f64)> {
        self.check(t, q, v)?;
        let (pos, vel) = self.residuals_unchecked(t, q, v);
        if pos.is_some_and(|p| !p.is_finite()) {
            return Err(CoreError::NonFiniteResult {
                what: "position constraint residual φ(t, q)",
                t,
                component: None,
            }
            .into());
        }
        if !vel.is_finite() {
            return Err(CoreError::NonFiniteResult {
                what: "velocity constraint residual A q̇ + a",
                t,
                component: None,
            }
            .into());
        }
        Ok((pos, vel))
    }

    /// [`residuals`](Self::residuals) without the checks (lengths checked by the caller).
    fn residuals_unchecked(&self, t: f64, q: &[f64], v: &[f64]) -> (Option<f64>, f64) {
        let m = self.count();
        let mut r = vec![0.0; m];
        let pos = self.set.positions(t, q, &mut r).then(|| max_abs(&r));
        self.set.velocity_residual(t, q, v, &mut r);
        (pos, max_abs(&r))
    }

    /// Checks that `state` satisfies the constraints to within `tol` (max-norm, positions and
    /// velocities) and that they are independent there; the error names the residual.
    pub fn check_state(&self, state: &State, tol: f64) -> Result<()> {
        state.validate(self.dof())?;
        let (t, q, v) = (state.t, state.q.as_slice(), state.v.as_slice());
        self.check_residuals(t, q, v, tol)?;
        let mut a = DMatrix::zeros(self.count(), self.dof());
        self.set.matrix(t, q, v, &mut a);
        match rank_error(&a, t) {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// [`Error::ConstraintViolated`] when a residual of (t, q, q̇) exceeds `tol`.
    fn check_residuals(&self, t: f64, q: &[f64], v: &[f64], tol: f64) -> Result<()> {
        let (pos, vel) = self.residuals(t, q, v)?;
        if let Some(p) = pos.filter(|p| !within(*p, tol)) {
            return Err(Error::ConstraintViolated {
                what: "position",
                t,
                residual: p,
                tolerance: tol,
            });
        }
        if !within(vel, tol) {
            return Err(Error::ConstraintViolated {
                what: "velocity",
                t,
                residual: vel,
                tolerance: tol,
            });
        }
        Ok(())
    }
}

/// `x ≤ tol`, false for NaN.
pub(crate) fn within(x: f64, tol: f64) -> bool {
    x <= tol
}

/// ‖x‖∞ (NaN gives NaN).
pub(crate) fn max_abs(x: &[f64]) -> f64 {
    noether_core::newton::max_norm(x)
}

impl<L: Lagrangian, K: ConstraintSet> Dynamics for Constrained<L, K> {
    type Partner = noether_core::Velocities;
    fn dof(&self) -> usize {
        Constrained::dof(self)
    }
    fn rates(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        dq: &mut [f64],
        dv: &mut [f64],
    ) -> noether_core::Result<()> {
        let mut lambda = vec![0.0; self.count()];
        self.solve(t, q, v, dv, &mut lambda)?;
        dq.copy_from_slice(v);
        Ok(())
    }
    /// The state at the start of a step must satisfy the constraints to within
    /// [`violation_tolerance`](Constrained::violation_tolerance).
    fn admissible(&self, t: f64, q: &[f64], v: &[f64]) -> noether_core::Result<()> {
        self.check(t, q, v)?;
        Ok(self.check_residuals(t, q, v, self.violation)?)
    }
    /// The energy function h = q̇·∂L/∂q̇ − L (constraint forces of scleronomic constraints do no work,
    /// so h is conserved when neither L nor the constraints depend on t).
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> noether_core::Result<f64> {
        self.el.energy(t, q, v)
    }
}

/// The exact Jacobian J = ∂(q̇, q̈)/∂(q, q̇) of the constrained equations of motion, by implicit
/// differentiation of the saddle-point system. With z = (q̈, −λ) solving K z = r, K = [M Aᵀ; A 0], the
/// residual R = (E − Aᵀλ, A q̈ + c) (E = M q̈ − b the Euler-Lagrange residual) vanishes along the
/// solution, so along a variation δ of the state
///
/// ```text
/// K δz = −(δE − (δA)ᵀλ, (δA) q̈ + δc)      (q̈, λ held in δE, δA, δc),
/// ```
///
/// with δE from core's [`EulerLagrange::residual_jacobian`] (third derivatives of L) and δA, δc from
/// [`ConstraintSet::derivatives_along`] (nested duals): one factorization of K for all 2n columns,
/// nothing differenced. Valid for holonomic and velocity constraints alike; the Jacobian is that of
/// the index-1 vector field on all of ℝ²ⁿ, which leaves the constraint manifold invariant (restricted
/// to the manifold in independent coordinates by [`linearize`](crate::linearize())). Errors: those
/// of [`Constrained::solve`] and of the residual Jacobian (more than 10 coordinates).
impl<L: Lagrangian, K: ConstraintSet> LinearizedDynamics for Constrained<L, K> {
    fn jacobian(&self, t: f64, q: &[f64], v: &[f64], out: &mut DMatrix<f64>) -> noether_core::Result<()> {
        self.check(t, q, v)?;
        let n = self.dof();
        noether_core::error::check_shape(
            "Jacobian of the constrained equations (rows and columns)",
            out,
            2 * n,
            2 * n,
        )?;
        let (factor, z, _) = self.saddle(t, q, v)?;
        self.jacobian_from(t, q, v, (&factor, &z), out)
    }
}

impl<L: Lagrangian, K: ConstraintSet> Constrained<L, K> {
    /// The Jacobian of the `LinearizedDynamics` impl from the factored saddle-point system and its
    /// solution z = (q̈, −λ) at (t, q, q̇) ([`saddle`](Self::saddle)), for callers that need them too;
    /// arguments checked by the caller.
    pub(crate) fn jacobian_from(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        (factor, z): (&DenseFactor, &DVector<f64>),
        out: &mut DMatrix<f64>,
    ) -> noether_core::Result<()> {
        let n = self.dof();
        let (qdd, neg_lambda) = z.as_slice().split_at(n);
        let mut de = DMatrix::zeros(n, 2 * n);
        self.el.residual_jacobian(t, q, v, qdd, &mut de)?;
        let mut rhs = DMatrix::zeros(z.len(), 2 * n);
        let zeros = vec![0.0; n];
        for j in 0..2 * n {
            let mut e = vec![0.0; n];
            e[j % n] = 1.0;
            let dir = if j < n {
                (&e[..], &zeros[..])
            } else {
                (&zeros[..], &e[..])
            };
            let d = self.set.derivatives_along(t, q, v, dir);
            // −δE + (δA)ᵀλ with λ = −z₂, and −((δA) q̈ + δc).
            let lift = d.matrix.tr_mul(&DVector::from_column_slice(neg_lambda));
            for r in 0..n {
                rhs[(r, j)] = -de[(r, j)] - lift[r];
            }
            let bend = &d.matrix * DVector::from_column_slice(qdd);
            for (r, (b, c)) in bend.iter().zip(&d.bias).enumerate() {
                rhs[(n + r, j)] = -(b + c);
            }
        }
        let dz = factor.solve_matrix(&rhs);
        out.fill(0.0);
        out.view_mut((0, n), (n, n)).fill_with_identity();
        out.view_mut((n, 0), (n, 2 * n)).copy_from(&dz.rows(0, n));
        noether_core::error::check_result("Jacobian of the constrained equations", t, out.as_slice())
    }
}
