//! Projection of a state back onto the constraint manifold, and a stepper wrapper that projects after
//! every step of any continuous integrator.
//!
//! Positions (holonomic sets): the nearest point along the constraint normals at the drifted point q̃,
//!
//! ```text
//! q = q̃ − Φ_q(t, q̃)ᵀ μ,    φ(t, q̃ − Φ_q(t, q̃)ᵀ μ) = 0   (Newton in the m unknowns μ),
//! ```
//!
//! then velocities, the orthogonal projection onto A(t, q) q̇ + a(t, q) = 0:
//!
//! ```text
//! q̇ ← q̇ − Aᵀ (A Aᵀ)⁻¹ (A q̇ + a).
//! ```
//!
//! The Euclidean metric needs no mass matrix, so singular mass matrices (coordinates without kinetic
//! energy) project as well. Each projection reports the correction and the residual it leaves.

use crate::dynamics::{max_abs, rank_error, within};
use crate::set::ConstraintSet;
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector};
use noether_core::error::check_positive;
use noether_core::linalg::DenseFactor;
use noether_core::newton::{DenseProblem, Newton};
use noether_core::{Error as CoreError, State, StepInfo, Stepper, Velocities};

/// Settings of a projection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    tolerance: f64,
    max_iterations: usize,
    violation_tolerance: f64,
}

impl Default for Projection {
    fn default() -> Self {
        Projection {
            tolerance: 1e-14,
            max_iterations: 20,
            violation_tolerance: 1e-8,
        }
    }
}

impl Projection {
    /// Sets the tolerance (default 1e-14): Newton stops when ‖φ‖∞ ≤ this (or when its step reaches
    /// rounding level). Finite and positive, else `InvalidParameter`.
    pub fn tolerance(mut self, tol: f64) -> Result<Self> {
        self.tolerance = check_positive("projection tolerance", tol)?;
        Ok(self)
    }
    /// Sets the Newton iteration cap (default 20; at least 1, else `InvalidParameter`).
    pub fn max_iterations(mut self, n: usize) -> Result<Self> {
        self.max_iterations = noether_core::error::check_iteration_cap("max_iterations", n)?;
        Ok(self)
    }
    /// Sets the violation tolerance (default 1e-8): [`Projected`] refuses an incoming state whose
    /// residual exceeds it (a state that was never on the manifold; project it explicitly with
    /// [`project`] first). Finite and positive, else `InvalidParameter`.
    pub fn violation_tolerance(mut self, tol: f64) -> Result<Self> {
        self.violation_tolerance = check_positive("violation tolerance", tol)?;
        Ok(self)
    }
}

/// What a projection did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ProjectionReport {
    /// ‖Δq‖∞ of the position correction.
    pub position_correction: f64,
    /// ‖Δq̇‖∞ of the velocity correction.
    pub velocity_correction: f64,
    /// ‖φ‖∞ before and after (zero for velocity constraints, which have none).
    pub position_residual: (f64, f64),
    /// ‖A q̇ + a‖∞ before and after.
    pub velocity_residual: (f64, f64),
    /// Newton iterations of the position projection.
    pub iterations: usize,
}

struct PositionProblem<'a, K> {
    set: &'a K,
    t: f64,
    q0: &'a [f64],
    /// Φ_q(t, q̃)ᵀ (n × m), the fixed directions.
    dirs: DMatrix<f64>,
    q: Vec<f64>,
    a: DMatrix<f64>,
}

impl<K: ConstraintSet> PositionProblem<'_, K> {
    fn point(&mut self, mu: &[f64]) {
        let mu = DVector::from_column_slice(mu);
        let dq = &self.dirs * mu;
        for ((qi, q0), d) in self.q.iter_mut().zip(self.q0).zip(dq.iter()) {
            *qi = q0 - d;
        }
    }
}

impl<K: ConstraintSet> DenseProblem for PositionProblem<'_, K> {
    fn dim(&self) -> usize {
        self.set.count()
    }
    fn residual(&mut self, mu: &[f64], r: &mut [f64]) -> noether_core::Result<()> {
        self.point(mu);
        self.set.positions(self.t, &self.q, r);
        Ok(())
    }
    fn jacobian(&mut self, mu: &[f64], j: &mut DMatrix<f64>) -> noether_core::Result<()> {
        self.point(mu);
        let zero = vec![0.0; self.q.len()];
        self.set.matrix(self.t, &self.q, &zero, &mut self.a);
        *j = -(&self.a * &self.dirs);
        Ok(())
    }
}

/// Projects `state` (a Lagrangian state, v = q̇) onto the constraints of `set` in place and reports
/// the correction. On error the state is unchanged.
pub fn project<K: ConstraintSet>(set: &K, state: &mut State, opts: &Projection) -> Result<ProjectionReport> {
    let (n, m) = (set.dof(), set.count());
    state.validate(n)?;
    let t = state.t;
    let mut rep = ProjectionReport::default();
    let mut r = vec![0.0; m];
    let mut q = state.q.clone();
    let mut a = DMatrix::zeros(m, n);
    if set.positions(t, q.as_slice(), &mut r) {
        rep.position_residual.0 = max_abs(&r);
        set.matrix(t, q.as_slice(), state.v.as_slice(), &mut a);
        let prob = PositionProblem {
            set,
            t,
            q0: state.q.as_slice(),
            dirs: a.transpose(),
            q: vec![0.0; n],
            a: DMatrix::zeros(m, n),
        };
        let mut mu = vec![0.0; m];
        let newton = Newton::default()
            .residual_tolerance(opts.tolerance)?
            .step_tolerance(1e-15)?
            .max_iterations(opts.max_iterations)?;
        let mut sys = noether_core::newton::Dense::new(prob);
        let info = newton.solve(&mut sys, &mut mu).map_err(|e| match e {
            CoreError::SingularMatrix { .. } => rank_error(&a, t).unwrap_or(e.into()),
            e => e.into(),
        })?;
        rep.iterations = info.iterations;
        let prob = &mut sys.problem;
        prob.point(&mu);
        q.as_mut_slice().copy_from_slice(&prob.q);
        set.positions(t, q.as_slice(), &mut r);
        rep.position_residual.1 = max_abs(&r);
        rep.position_correction = max_abs((&q - &state.q).as_slice());
    }
    // Velocities at the projected positions.
    set.matrix(t, q.as_slice(), state.v.as_slice(), &mut a);
    set.velocity_residual(t, q.as_slice(), state.v.as_slice(), &mut r);
    rep.velocity_residual.0 = max_abs(&r);
    let gram = &a * a.transpose();
    // Core's factorization and pivot test (Cholesky: A Aᵀ is positive definite when A has full rank);
    // its pivots are squared singular values of A, so the test rejects σ_min/σ_max ≲ 3e-7.
    let chol = DenseFactor::symmetric(gram)
        .map_err(|e| rank_error(&a, t).unwrap_or(e.in_matrix("constraint Gram matrix A Aᵀ").into()))?;
    let mut y = DVector::from_column_slice(&r);
    chol.solve_in_place(y.as_mut_slice());
    let dv = a.tr_mul(&y);
    let v = &state.v - &dv;
    set.velocity_residual(t, q.as_slice(), v.as_slice(), &mut r);
    rep.velocity_residual.1 = max_abs(&r);
    rep.velocity_correction = max_abs(dv.as_slice());
    if !q.iter().chain(v.iter()).all(|x| x.is_finite()) {
        return Err(CoreError::NonFiniteResult {
            what: "projected state",
            t,
            component: None,
        }
        .into());
    }
    state.q = q;
    state.v = v;
    Ok(rep)
}

/// Any continuous stepper followed by a projection onto the constraints after every step.
///
/// Before a step the incoming state must satisfy the constraints to within
/// [`Projection::violation_tolerance`] (otherwise [`Error::ConstraintViolated`] names the residual);
/// after the step positions and velocities are projected back, and the report of the last projection
/// and the largest residual left over the run are kept. On any error the state is unchanged.
pub struct Projected<S, K> {
    stepper: S,
    set: K,
    options: Projection,
    last: ProjectionReport,
    worst: (f64, f64),
}

impl<S: Stepper<Partner = Velocities>, K: ConstraintSet> Projected<S, K> {
    /// Wraps `stepper`, projecting onto `set` (often `system.constraints()` of the
    /// [`Constrained`](crate::Constrained) system the stepper integrates).
    pub fn new(stepper: S, set: K) -> Self {
        Projected {
            stepper,
            set,
            options: Projection::default(),
            last: ProjectionReport::default(),
            worst: (0.0, 0.0),
        }
    }

    /// Sets the projection settings (default [`Projection::default`]).
    pub fn options(mut self, options: Projection) -> Self {
        self.options = options;
        self
    }

    /// The wrapped stepper.
    pub fn inner(&self) -> &S {
        &self.stepper
    }

    /// The report of the last projection.
    pub fn last_projection(&self) -> &ProjectionReport {
        &self.last
    }

    /// Largest (position, velocity) residual left after a projection so far.
    pub fn max_residual(&self) -> (f64, f64) {
        self.worst
    }
}

impl<S: Stepper<Partner = Velocities>, K: ConstraintSet> Stepper for Projected<S, K> {
    type Partner = Velocities;
    fn step(&mut self, state: &mut State, h: f64) -> noether_core::Result<StepInfo> {
        let (t, n, m) = (state.t, self.set.dof(), self.set.count());
        state.validate(n)?;
        let mut r = vec![0.0; m];
        for (what, holds) in [("position", true), ("velocity", false)] {
            let has = if holds {
                self.set.positions(t, state.q.as_slice(), &mut r)
            } else {
                self.set
                    .velocity_residual(t, state.q.as_slice(), state.v.as_slice(), &mut r);
                true
            };
            let res = max_abs(&r);
            if has && !within(res, self.options.violation_tolerance) {
                return Err(Error::ConstraintViolated {
                    what,
                    t,
                    residual: res,
                    tolerance: self.options.violation_tolerance,
                }
                .into());
            }
        }
        let saved = state.clone();
        let info = self.stepper.step(state, h)?;
        match project(&self.set, state, &self.options) {
            Ok(rep) => {
                self.last = rep;
                self.worst.0 = self.worst.0.max(rep.position_residual.1);
                self.worst.1 = self.worst.1.max(rep.velocity_residual.1);
                Ok(info)
            }
            Err(e) => {
                *state = saved;
                Err(e.into())
            }
        }
    }
    // The inner method's own extension ends at the unprojected state: the driver interpolates by
    // cubic Hermite between the projected states instead.
    noether_core::__forward_stepper!(stepper);
}
