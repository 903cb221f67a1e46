//! Boundary-value problems by the discrete Hamilton principle: the discrete path q₀ = a, q₁, …,
//! q_{N−1}, q_N = b on a uniform grid t_k = t₀ + k h, h = (t₁ − t₀)/N, that makes the discrete action
//!
//! ```text
//! S_d = Σ_{k=0}^{N−1} L_d(t_k; q_k, q_{k+1}, h)
//! ```
//!
//! stationary: the discrete Euler-Lagrange equations
//!
//! ```text
//! F_k = D₂L_d(q_{k−1}, q_k) + D₁L_d(q_k, q_{k+1}) = 0,      k = 1, …, N−1,
//! ```
//!
//! solved all at once by the core [`Newton`]. The Jacobian ∂F/∂q is the Hessian of S_d in the interior
//! positions (the discrete Jacobi operator): block tridiagonal, with A_k = D₂₂L_d(q_{k−1}, q_k) +
//! D₁₁L_d(q_k, q_{k+1}) on the diagonal and B_k = D₁₂L_d(q_k, q_{k+1}) (and its transpose) next to it,
//! all from dual numbers ([`DiscreteDerivatives`]). It is stored banded (half-bandwidth 2n − 1 for n
//! coordinates) and factored by core's [`Banded`] LU: O(N n³) per Newton iteration.
//!
//! Holonomic constraints g(q) = 0 ([`PathConstraint`], e.g. a particle on a sphere) are imposed at
//! every interior node by multipliers, as in RATTLE: the stationary points of S_d + Σ_k λ_k·g(q_k) with
//! g(q_k) = 0, a saddle-point (KKT) system in (q_k, λ_k) with the same block-tridiagonal pattern.
//!
//! **Conjugate points.** The Jacobi operator is singular exactly when t₁ is (discretely) conjugate to
//! t₀: a discrete Jacobi field δq_k (a solution of the linearized discrete Euler-Lagrange equations)
//! vanishes at both ends. Near such a point the boundary-value problem is ill posed (the path moves
//! by ~1/margin under a change of the ends), and the solver reports [`ConjugatePoint`] instead of a
//! path. The margin is the smallest-magnitude eigenvalue of the Jacobi operator relative to its
//! largest, normalised by the same ratio for a free particle (tan²(π/2N)): 1 for a free particle,
//! 1 − (ωT/π)² + O(h²) for an oscillator of frequency ω over a time T. Beyond conjugate points the
//! problem is well posed again; the path is then a saddle of S_d, and its Morse index (the number of
//! negative eigenvalues of the Jacobi operator, counted by the inertia of its block LDLᵀ
//! factorisation, Sylvester's law) equals the number of discrete conjugate points in (t₀, t₁) (the
//! discrete Morse index theorem), which the solver also locates: the sign changes of det J_k, J the
//! matrix Jacobi field with J₀ = 0, J₁ = I, interpolated linearly between nodes.
//!
//! [`BoundaryValue::minimize`] instead descends S_d with argmin's L-BFGS from a rough guess (a
//! minimum of the action, where there is one) and polishes the result by Newton.
//!
//! ```
//! use noether_core::prelude::*;
//! use noether_discrete::boundary::BoundaryValue;
//! use noether_discrete::Midpoint;
//!
//! /// Harmonic oscillator L = ½(q̇² − q²).
//! struct Oscillator;
//! impl Lagrangian for Oscillator {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         (v[0] * v[0] - q[0] * q[0]) * 0.5
//!     }
//! }
//!
//! let bvp = BoundaryValue::new(Midpoint::new(Oscillator));
//! // From q(0) = 0 to q(1) = 1: q(t) = sin t / sin 1.
//! let path = bvp.solve(0.0, &[0.0], 1.0, &[1.0], 100).unwrap();
//! let mid = path.q[50][0];
//! assert!((mid - 0.5f64.sin() / 1f64.sin()).abs() < 1e-5); // O(h²)
//! assert_eq!(path.morse_index, Some(0)); // a minimum of the action: no conjugate point before π
//! ```
//!
//! # References
//! J. E. Marsden and M. West, *Discrete mechanics and variational integrators*, Acta Numerica 10
//! (2001), §1.2 and §3; the discrete Morse index theorem: J. Moser and A. P. Veselov, Commun. Math.
//! Phys. 139 (1991), and the Sturm sequence of a symmetric tridiagonal matrix.

use crate::lagrangian::{DiscreteDerivatives, DiscreteLagrangian, Scratch};
use nalgebra::{DMatrix, DVector};
use noether_core::ad::{self, Block, Field};
use noether_core::error::{check_finite, check_len};
use noether_core::linalg::{Banded, BandedLu};
use noether_core::{Error, Newton, NewtonInfo, NewtonSystem, Result, Scalar};

/// Holonomic constraints g(q) = 0 (time-independent) imposed at every interior node of a discrete
/// path by multipliers.
pub trait PathConstraint {
    /// Number of coordinates.
    fn dof(&self) -> usize;
    /// Number of constraints (rows of g).
    fn count(&self) -> usize;
    /// g(q) into `out` (length [`count`](Self::count)), generic over the scalar for its derivatives.
    fn constraints<D: Scalar>(&self, q: &[D], out: &mut [D]);
}

/// No constraint (the unconstrained problem).
struct Free(usize);

impl PathConstraint for Free {
    fn dof(&self) -> usize {
        self.0
    }
    fn count(&self) -> usize {
        0
    }
    fn constraints<D: Scalar>(&self, _q: &[D], _out: &mut [D]) {}
}

/// The boundary-value problem is (nearly) singular: t₁ is close to a discrete conjugate point of t₀
/// (see the module docs). Travels through core's interfaces as [`noether_core::Error::Model`]: get it
/// back as [`crate::Error::ConjugatePoint`] by `noether_discrete::Error::from(e)`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "conjugate point: the discrete Jacobi operator of the path from t₀ = {t0} to t₁ = {t1} is singular \
     (margin {margin:e}, tolerance {tolerance:e}); the nearest discrete conjugate point of t₀ is at t = {t}"
)]
#[non_exhaustive]
pub struct ConjugatePoint {
    /// The discrete conjugate time nearest t₁ (a zero of det J, J the Jacobi field from t₀, linearly
    /// interpolated between nodes, or extrapolated up to one step after t₁; NaN when none was found).
    pub t: f64,
    /// Start time.
    pub t0: f64,
    /// End time of the problem.
    pub t1: f64,
    /// The margin found (0 when the Jacobian could not be factored at all).
    pub margin: f64,
    /// The tolerance it fell below.
    pub tolerance: f64,
    /// Number of conjugate points passed before t (the Morse index of the path just before it).
    pub passed: usize,
}

/// [`BoundaryValue::minimize`] ended on a stationary point that is not a minimum of the action
/// ([`crate::Error::NotMinimum`] by `noether_discrete::Error::from(e)`).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "no minimum of the action: the stationary path has Morse index {morse_index:?} \
     (None: the descent ran away, the action is unbounded below along it, and Newton found no path)"
)]
#[non_exhaustive]
pub struct NotMinimum {
    /// Number of negative eigenvalues of the discrete Jacobi operator at the stationary path found
    /// (by the descent, or by Newton from the guess when the descent ran away); `None` when there is
    /// none.
    pub morse_index: Option<usize>,
}

/// A discrete path that makes the discrete action stationary, with what was learnt on the way.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct DiscretePath {
    /// Node times t_k = t₀ + k h, k = 0..=N.
    pub t: Vec<f64>,
    /// Node positions q_k (q₀ = a, q_N = b).
    pub q: Vec<DVector<f64>>,
    /// Multipliers λ_k of the constraints at the interior nodes k = 1..N−1 (empty without constraints):
    /// D₂L_d(q_{k−1}, q_k) + D₁L_d(q_k, q_{k+1}) + ∇g(q_k)ᵀ λ_k = 0.
    pub multipliers: Vec<DVector<f64>>,
    /// Momentum at the start, p₀ = −D₁L_d(q₀, q₁).
    pub p0: DVector<f64>,
    /// Momentum at the end, p_N = D₂L_d(q_{N−1}, q_N).
    pub p1: DVector<f64>,
    /// The discrete action S_d.
    pub action: f64,
    /// Statistics of the Newton solve.
    pub newton: NewtonInfo,
    /// Number of negative eigenvalues of the discrete Jacobi operator (0: a local minimum of S_d);
    /// `None` for a constrained problem.
    pub morse_index: Option<usize>,
    /// The discrete conjugate points of t₀ in (t₀, t₁) (module docs); empty for a constrained problem.
    pub conjugate_times: Vec<f64>,
    /// The conjugate-point margin of the Jacobi operator (module docs; NaN for a constrained problem).
    pub margin: f64,
}

/// Solver of discrete boundary-value problems q(t₀) = a, q(t₁) = b for a discrete Lagrangian (module
/// docs).
pub struct BoundaryValue<Ld> {
    ld: Ld,
    newton: Newton,
    conjugate_tolerance: f64,
}

/// Default tolerance on the conjugate-point margin: below it the solution would move by more than
/// ~10⁸ times a change of its ends, i.e. lose about 8 of its 16 digits.
pub const DEFAULT_CONJUGATE_TOLERANCE: f64 = 1e-8;

impl<Ld: DiscreteLagrangian> BoundaryValue<Ld> {
    /// The solver for `ld`, Newton solved to rounding (residual tolerance 1e-14 raised to the
    /// rounding floor 8ε max_k |D₁L_d|), at most 50 iterations.
    pub fn new(ld: Ld) -> Self {
        let mut newton = Newton::default();
        newton.tol_residual = 1e-14;
        BoundaryValue {
            ld,
            newton,
            conjugate_tolerance: DEFAULT_CONJUGATE_TOLERANCE,
        }
    }

    /// Replaces the Newton settings (the residual tolerance is still raised to the rounding floor).
    pub fn with_newton(mut self, newton: Newton) -> Self {
        self.newton = newton;
        self
    }

    /// Replaces the conjugate-point tolerance on the margin (finite and positive, else
    /// `InvalidParameter`; default [`DEFAULT_CONJUGATE_TOLERANCE`]).
    pub fn with_conjugate_tolerance(mut self, tol: f64) -> Result<Self> {
        self.conjugate_tolerance = noether_core::error::check_positive("conjugate tolerance", tol)?;
        Ok(self)
    }

    /// The discrete Lagrangian.
    pub fn discrete_lagrangian(&self) -> &Ld {
        &self.ld
    }

    /// The stationary discrete path from q(t₀) = `a` to q(t₁) = `b` in `steps` steps, from the
    /// straight line as initial guess.
    pub fn solve(&self, t0: f64, a: &[f64], t1: f64, b: &[f64], steps: usize) -> Result<DiscretePath> {
        let guess = straight_line(a, b, steps)?;
        self.solve_from(t0, t1, &guess)
    }

    /// The stationary discrete path from t₀ to t₁ from the initial guess `nodes` (N + 1 positions;
    /// the first and last are the boundary values and are kept).
    pub fn solve_from(&self, t0: f64, t1: f64, nodes: &[Vec<f64>]) -> Result<DiscretePath> {
        let free = Free(self.ld.dof());
        self.solve_with(&free, t0, t1, nodes)
    }

    /// The stationary discrete path on the constraint set g(q) = 0 of `constraint`, from the guess
    /// `nodes` (N + 1 positions; the ends, kept, should satisfy the constraint; the interior ones are
    /// pulled onto it by Newton). The multipliers start at zero.
    pub fn solve_constrained<C: PathConstraint>(
        &self,
        constraint: &C,
        t0: f64,
        t1: f64,
        nodes: &[Vec<f64>],
    ) -> Result<DiscretePath> {
        if constraint.dof() != self.ld.dof() {
            return Err(Error::Dimension {
                what: "path constraint",
                expected: self.ld.dof(),
                got: constraint.dof(),
            });
        }
        self.solve_with(constraint, t0, t1, nodes)
    }

    fn solve_with<C: PathConstraint>(
        &self,
        c: &C,
        t0: f64,
        t1: f64,
        nodes: &[Vec<f64>],
    ) -> Result<DiscretePath> {
        if self.ld.has_discrete_force() {
            return Err(Error::Unsupported(
                "boundary-value problems of a forced discrete Lagrangian (no action to make stationary)",
            ));
        }
        let mut sys = System::new(&self.ld, c, t0, t1, nodes)?;
        let mut x = sys.initial_unknowns(nodes);
        let mut newton = self.newton;
        newton.tol_residual = newton
            .tol_residual
            .max(8.0 * f64::EPSILON * sys.momentum_scale(&x));
        let constrained = c.count() > 0;
        let info = match newton.solve(&mut sys, &mut x) {
            Ok(info) => info,
            Err(e) if !constrained => {
                // A singular or nearly singular Jacobi operator (Newton cannot reach the tolerance,
                // or its factorisation is refused) at the last iterate: a conjugate point.
                let j = sys.jacobi(&x);
                let margin = sys.margin(&x, j.mu);
                if self.near_conjugate(margin) {
                    return Err(self.conjugate_error(&sys, &j, margin).into());
                }
                return Err(e);
            }
            Err(e) => return Err(e),
        };
        sys.set_interior(&x);
        let mut path = sys.path(&x, info)?;
        if !constrained {
            let j = sys.jacobi(&x);
            let margin = sys.margin(&x, j.mu);
            path.morse_index = j.morse_index;
            path.conjugate_times = j.conjugate_times.iter().copied().filter(|&t| t < t1).collect();
            path.margin = margin;
            if self.near_conjugate(margin) {
                return Err(self.conjugate_error(&sys, &j, margin).into());
            }
        }
        Ok(path)
    }

    /// `true` when the margin is below the conjugate-point tolerance (or NaN).
    fn near_conjugate(&self, margin: f64) -> bool {
        margin.is_nan() || margin.abs() <= self.conjugate_tolerance
    }

    fn conjugate_error<C: PathConstraint>(
        &self,
        sys: &System<'_, Ld, C>,
        j: &JacobiInfo,
        margin: f64,
    ) -> ConjugatePoint {
        let t1 = sys.t0 + sys.h * sys.steps as f64;
        let nearest = j
            .conjugate_times
            .iter()
            .copied()
            .chain(j.end_root)
            .min_by(|a, b| (a - t1).abs().total_cmp(&(b - t1).abs()));
        let t = nearest.unwrap_or(f64::NAN);
        let passed = j.conjugate_times.iter().filter(|&&s| s < t).count();
        ConjugatePoint {
            t,
            t0: sys.t0,
            t1,
            margin: if margin.is_nan() { 0.0 } else { margin },
            tolerance: self.conjugate_tolerance,
            passed,
        }
    }

    /// A local minimum of the discrete action from the guess `nodes` (ends kept): argmin's L-BFGS on
    /// S_d in the interior positions until ‖∇S_d‖∞ ≤ 1e-6 (relative to the momentum scale), then
    /// Newton to rounding ([`solve_from`](Self::solve_from)), at most `max_iterations` L-BFGS
    /// iterations. A path that is a saddle of S_d (Morse index > 0), or a descent that runs away
    /// (S_d unbounded below: beyond 10⁶ times the guess), is [`NotMinimum`].
    pub fn minimize(
        &self,
        t0: f64,
        t1: f64,
        nodes: &[Vec<f64>],
        max_iterations: u64,
    ) -> Result<DiscretePath> {
        use argmin::core::Executor;
        use argmin::solver::linesearch::MoreThuenteLineSearch;
        use argmin::solver::quasinewton::LBFGS;
        let free = Free(self.ld.dof());
        let mut sys = System::new(&self.ld, &free, t0, t1, nodes)?;
        let x0 = sys.initial_unknowns(nodes);
        let scale = sys.momentum_scale(&x0).max(f64::MIN_POSITIVE);
        let solver = LBFGS::new(MoreThuenteLineSearch::new(), 8)
            .with_tolerance_grad(1e-6 * scale)
            .and_then(|s| s.with_tolerance_cost(0.0))
            .map_err(|_| Error::InvalidParameter {
                name: "L-BFGS tolerance",
                value: 1e-6 * scale,
                reason: "must be finite and non-negative",
            })?;
        let runaway = RUNAWAY * (1.0 + noether_core::newton::max_norm(&x0));
        let problem = ActionProblem {
            sys: std::cell::RefCell::new(sys),
            runaway,
        };
        let res = Executor::new(problem, solver)
            .configure(|s| s.param(DVector::from_vec(x0)).max_iters(max_iterations))
            .run();
        let res = match res {
            Ok(res) => res,
            Err(e) if e.downcast_ref::<RanAway>().is_some() => {
                // S_d is unbounded below along the descent: report the stationary path Newton finds
                // from the guess (a saddle), if any.
                let morse_index = self.solve_from(t0, t1, nodes).ok().and_then(|p| p.morse_index);
                return Err(NotMinimum { morse_index }.into());
            }
            Err(e) => {
                return Err(crate::Error::Optimizer {
                    reason: e.to_string(),
                }
                .into())
            }
        };
        let state = res.state();
        let x = state
            .best_param
            .as_ref()
            .or(state.param.as_ref())
            .ok_or_else(|| {
                Error::from(crate::Error::Optimizer {
                    reason: "no parameter in the final state".into(),
                })
            })?;
        let mut polished = nodes.to_vec();
        let n = self.ld.dof();
        for (k, node) in polished
            .iter_mut()
            .enumerate()
            .skip(1)
            .take(nodes.len().saturating_sub(2))
        {
            node.copy_from_slice(&x.as_slice()[(k - 1) * n..k * n]);
        }
        let path = self.solve_from(t0, t1, &polished)?;
        match path.morse_index {
            Some(m) if m > 0 => Err(NotMinimum { morse_index: Some(m) }.into()),
            _ => Ok(path),
        }
    }
}

/// A stationary path over a linear family of discrete paths q_k = A_k y ([`BoundaryValue::solve_linear`]).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct LinearPath {
    /// The parameters y.
    pub y: DVector<f64>,
    /// Node times t_k = t₀ + k h, k = 0..=N.
    pub t: Vec<f64>,
    /// Node positions q_k = A_k y.
    pub q: Vec<DVector<f64>>,
    /// The discrete action S_d(y).
    pub action: f64,
    /// Statistics of the Newton solve.
    pub newton: NewtonInfo,
    /// Number of negative eigenvalues of the reduced Hessian ∂²S_d/∂y² (0: a local minimum within the
    /// family).
    pub morse_index: usize,
    /// Its eigenvalues, ascending.
    pub hessian_eigenvalues: DVector<f64>,
}

impl<Ld: DiscreteLagrangian> BoundaryValue<Ld> {
    /// The stationary point of the discrete action over the linear family of paths q_k = A_k y,
    /// k = 0..=N (`maps` = [A₀, …, A_N], each dof × d), from t₀ to t₁, by Newton on
    /// ∇_y S_d = Σ_k A_kᵀ D₁L_d(q_k, q_{k+1}) + A_{k+1}ᵀ D₂L_d(q_k, q_{k+1}) = 0 from `y0`, with the
    /// dense Hessian Σ_k [A_k; A_{k+1}]ᵀ [D₁₁ D₁₂; D₂₁ D₂₂] [A_k; A_{k+1}] as Jacobian.
    ///
    /// The family encodes boundary conditions and symmetries: a loop (A_N = A₀), a loop up to an
    /// isometry (A_N = P A₀: a choreography, q(t + T/3) = P q(t)), or the fixed subspace of a
    /// symmetry group of S_d, whose stationary points are stationary for the full action (Palais'
    /// principle of symmetric criticality). Symmetries of S_d left in the family (a rotation of a
    /// loop) make the Hessian singular and must be removed by the family.
    pub fn solve_linear(&self, t0: f64, t1: f64, maps: &[DMatrix<f64>], y0: &[f64]) -> Result<LinearPath> {
        let n = self.ld.dof();
        let d = y0.len();
        let steps = maps.len().saturating_sub(1);
        if steps < 1 {
            return Err(Error::InvalidParameter {
                name: "linear path maps",
                value: maps.len() as f64,
                reason: "at least two nodes (one step)",
            });
        }
        for a in maps {
            if a.nrows() != n || a.ncols() != d {
                return Err(Error::Dimension {
                    what: "linear path map A_k (dof × parameters)",
                    expected: n * d,
                    got: a.nrows() * a.ncols(),
                });
            }
        }
        check_finite("linear path parameters", y0)?;
        if !(t0.is_finite() && t1.is_finite() && t1 != t0) {
            return Err(Error::InvalidParameter {
                name: "time interval t₁ − t₀",
                value: t1 - t0,
                reason: "t₀ and t₁ must be finite and distinct",
            });
        }
        if self.ld.has_discrete_force() {
            return Err(Error::Unsupported(
                "stationary paths of a forced discrete Lagrangian (no action to make stationary)",
            ));
        }
        let h = (t1 - t0) / steps as f64;
        let problem = LinearFamily {
            ld: &self.ld,
            maps,
            t0,
            h,
        };
        let mut newton = self.newton;
        let scale = problem.momentum_scale(y0);
        newton.tol_residual = newton
            .tol_residual
            .max(8.0 * f64::EPSILON * scale * (d as f64).sqrt());
        let mut sys = noether_core::newton::Dense::new(problem);
        let mut y = y0.to_vec();
        let info = newton.solve(&mut sys, &mut y)?;
        let mut problem = sys.problem;
        let mut hess = DMatrix::zeros(d, d);
        noether_core::newton::DenseProblem::jacobian(&mut problem, &y, &mut hess)?;
        let sym = (&hess + hess.transpose()) * 0.5;
        let mut eig = sym.symmetric_eigenvalues();
        eig.as_mut_slice().sort_by(f64::total_cmp);
        let yv = DVector::from_vec(y);
        let q: Vec<DVector<f64>> = maps.iter().map(|a| a * &yv).collect();
        let action = (0..steps)
            .map(|k| {
                let f = DiscreteField {
                    ld: &self.ld,
                    t0: t0 + k as f64 * h,
                };
                ad::value(&f, h, q[k].as_slice(), q[k + 1].as_slice())
            })
            .sum();
        Ok(LinearPath {
            morse_index: eig.iter().filter(|&&l| l < 0.0).count(),
            hessian_eigenvalues: eig,
            y: yv,
            t: (0..=steps).map(|k| t0 + k as f64 * h).collect(),
            q,
            action,
            newton: info,
        })
    }
}

/// ∇_y S_d = 0 over q_k = A_k y as a dense Newton problem.
struct LinearFamily<'a, Ld> {
    ld: &'a Ld,
    maps: &'a [DMatrix<f64>],
    t0: f64,
    h: f64,
}

impl<Ld: DiscreteLagrangian> LinearFamily<'_, Ld> {
    fn nodes(&self, y: &[f64]) -> Vec<DVector<f64>> {
        let y = DVector::from_column_slice(y);
        self.maps.iter().map(|a| a * &y).collect()
    }

    fn momentum_scale(&self, y: &[f64]) -> f64 {
        let q = self.nodes(y);
        let mut g = vec![0.0; self.ld.dof()];
        let mut scale = 0.0_f64;
        for k in 0..q.len() - 1 {
            self.ld.d1(
                self.t0 + k as f64 * self.h,
                self.h,
                q[k].as_slice(),
                q[k + 1].as_slice(),
                &mut g,
            );
            scale = scale.max(noether_core::newton::max_norm(&g));
        }
        scale
    }
}

impl<Ld: DiscreteLagrangian> noether_core::newton::DenseProblem for LinearFamily<'_, Ld> {
    fn dim(&self) -> usize {
        self.maps.first().map_or(0, |a| a.ncols())
    }

    fn residual(&mut self, y: &[f64], r: &mut [f64]) -> Result<()> {
        let q = self.nodes(y);
        let n = self.ld.dof();
        let (mut g1, mut g2) = (DVector::zeros(n), DVector::zeros(n));
        let mut acc = DVector::zeros(y.len());
        for k in 0..q.len() - 1 {
            let t = self.t0 + k as f64 * self.h;
            self.ld
                .d1(t, self.h, q[k].as_slice(), q[k + 1].as_slice(), g1.as_mut_slice());
            self.ld
                .d2(t, self.h, q[k].as_slice(), q[k + 1].as_slice(), g2.as_mut_slice());
            acc.gemv_tr(1.0, &self.maps[k], &g1, 1.0);
            acc.gemv_tr(1.0, &self.maps[k + 1], &g2, 1.0);
        }
        r.copy_from_slice(acc.as_slice());
        Ok(())
    }

    fn jacobian(&mut self, y: &[f64], j: &mut DMatrix<f64>) -> Result<()> {
        let q = self.nodes(y);
        let n = self.ld.dof();
        let (mut d11, mut d12, mut d22) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n), DMatrix::zeros(n, n));
        j.fill(0.0);
        for k in 0..q.len() - 1 {
            let t = self.t0 + k as f64 * self.h;
            let (a, b) = (q[k].as_slice(), q[k + 1].as_slice());
            self.ld.d11(t, self.h, a, b, &mut d11);
            self.ld.d12(t, self.h, a, b, &mut d12);
            self.ld.d22(t, self.h, a, b, &mut d22);
            let (ak, an) = (&self.maps[k], &self.maps[k + 1]);
            // [A_k; A_{k+1}]ᵀ [D₁₁ D₁₂; D₂₁ D₂₂] [A_k; A_{k+1}].
            let upper = &d11 * ak + &d12 * an;
            let lower = d12.transpose() * ak + &d22 * an;
            j.gemm_tr(1.0, ak, &upper, 1.0);
            j.gemm_tr(1.0, an, &lower, 1.0);
        }
        if j.iter().any(|v| !v.is_finite()) {
            return Err(Error::NonFiniteResult {
                what: "Hessian of the discrete action over a linear family",
                t: self.t0,
                component: None,
            });
        }
        Ok(())
    }
}

/// The nodes of the straight line from `a` to `b` in `steps` steps.
pub fn straight_line(a: &[f64], b: &[f64], steps: usize) -> Result<Vec<Vec<f64>>> {
    check_len("boundary value b", b, a.len())?;
    check_finite("boundary value a", a)?;
    check_finite("boundary value b", b)?;
    if steps < 2 {
        return Err(Error::InvalidParameter {
            name: "boundary-value steps",
            value: steps as f64,
            reason: "at least 2 steps (one interior node)",
        });
    }
    Ok((0..=steps)
        .map(|k| {
            let s = k as f64 / steps as f64;
            a.iter().zip(b).map(|(x, y)| x + s * (y - x)).collect()
        })
        .collect())
}

/// The discrete Euler-Lagrange equations of the whole path as one Newton system.
struct System<'a, Ld, C> {
    ld: &'a Ld,
    c: &'a C,
    t0: f64,
    h: f64,
    steps: usize,
    n: usize,
    m: usize,
    /// All node positions q₀..q_N, one after the other (interior ones from the last `set_interior`).
    q: Vec<f64>,
    g1: Vec<f64>,
    g2: Vec<f64>,
    cval: Vec<f64>,
    gjac: DMatrix<f64>,
    d11: DMatrix<f64>,
    d22: DMatrix<f64>,
    d12: DMatrix<f64>,
    lhess: DMatrix<f64>,
    lu: Option<BandedLu>,
}

/// Iteration cap of the inverse iteration for the smallest eigenvalue of the Jacobi operator (it
/// stops earlier once the eigenvalue has settled to 1e-12).
const INVERSE_ITERATIONS: usize = 200;

const JACOBIAN: &str = "discrete Jacobi operator (boundary-value Newton Jacobian)";

impl<'a, Ld: DiscreteLagrangian, C: PathConstraint> System<'a, Ld, C> {
    fn new(ld: &'a Ld, c: &'a C, t0: f64, t1: f64, nodes: &[Vec<f64>]) -> Result<Self> {
        let n = ld.dof();
        let steps = nodes.len().saturating_sub(1);
        if steps < 2 {
            return Err(Error::InvalidParameter {
                name: "boundary-value steps",
                value: steps as f64,
                reason: "at least 2 steps (one interior node): give N + 1 ≥ 3 nodes",
            });
        }
        if !(t0.is_finite() && t1.is_finite() && t1 != t0) {
            return Err(Error::InvalidParameter {
                name: "boundary-value time interval t₁ − t₀",
                value: t1 - t0,
                reason: "t₀ and t₁ must be finite and distinct",
            });
        }
        let mut q = Vec::with_capacity((steps + 1) * n);
        for node in nodes {
            check_len("boundary-value node", node, n)?;
            check_finite("boundary-value node", node)?;
            q.extend_from_slice(node);
        }
        let m = c.count();
        Ok(System {
            ld,
            c,
            t0,
            h: (t1 - t0) / steps as f64,
            steps,
            n,
            m,
            q,
            g1: vec![0.0; n],
            g2: vec![0.0; n],
            cval: vec![0.0; m],
            gjac: DMatrix::zeros(m, n),
            d11: DMatrix::zeros(n, n),
            d22: DMatrix::zeros(n, n),
            d12: DMatrix::zeros(n, n),
            lhess: DMatrix::zeros(n, n),
            lu: None,
        })
    }

    /// Unknowns per interior node: q_k and λ_k.
    fn block(&self) -> usize {
        self.n + self.m
    }

    fn initial_unknowns(&self, nodes: &[Vec<f64>]) -> Vec<f64> {
        let s = self.block();
        let mut x = vec![0.0; (self.steps - 1) * s];
        for k in 1..self.steps {
            x[(k - 1) * s..(k - 1) * s + self.n].copy_from_slice(&nodes[k]);
        }
        x
    }

    /// Copies the interior positions of the unknowns into the node array.
    fn set_interior(&mut self, x: &[f64]) {
        let (n, s) = (self.n, self.block());
        for k in 1..self.steps {
            self.q[k * n..(k + 1) * n].copy_from_slice(&x[(k - 1) * s..(k - 1) * s + n]);
        }
    }

    fn node(&self, k: usize) -> &[f64] {
        &self.q[k * self.n..(k + 1) * self.n]
    }

    fn tk(&self, k: usize) -> f64 {
        self.t0 + k as f64 * self.h
    }

    /// max_k ‖D₁L_d(q_k, q_{k+1})‖∞ at the unknowns `x`: the scale of the residual's rounding.
    fn momentum_scale(&mut self, x: &[f64]) -> f64 {
        self.set_interior(x);
        let mut scale = 0.0_f64;
        let mut g = vec![0.0; self.n];
        for k in 0..self.steps {
            self.ld
                .d1(self.tk(k), self.h, self.node(k), self.node(k + 1), &mut g);
            scale = scale.max(noether_core::newton::max_norm(&g));
        }
        scale
    }

    /// The discrete action at the current nodes.
    fn action(&self) -> f64 {
        (0..self.steps)
            .map(|k| {
                let f = DiscreteField {
                    ld: self.ld,
                    t0: self.tk(k),
                };
                ad::value(&f, self.h, self.node(k), self.node(k + 1))
            })
            .sum()
    }

    /// ∇g(q) (m × n) into `gjac`, g(q) into `cval`.
    fn constraint_jacobian(&mut self, k: usize) {
        let (n, m) = (self.n, self.m);
        let q = self.q[k * n..(k + 1) * n].to_vec();
        let mut row = vec![0.0; n];
        for i in 0..m {
            let f = Component { c: self.c, i };
            self.cval[i] = ad::gradient(&f, 0.0, &q, &[], Block::X, &mut row);
            for (j, r) in row.iter().enumerate() {
                self.gjac[(i, j)] = *r;
            }
        }
    }

    fn path(&mut self, x: &[f64], info: NewtonInfo) -> Result<DiscretePath> {
        let (n, s, steps) = (self.n, self.block(), self.steps);
        let mut p0 = vec![0.0; n];
        let mut p1 = vec![0.0; n];
        self.ld
            .d1(self.tk(0), self.h, self.node(0), self.node(1), &mut p0);
        p0.iter_mut().for_each(|p| *p = -*p);
        self.ld.d2(
            self.tk(steps - 1),
            self.h,
            self.node(steps - 1),
            self.node(steps),
            &mut p1,
        );
        let action = self.action();
        check_finite("end momenta of the boundary-value path", &p0)?;
        check_finite("end momenta of the boundary-value path", &p1)?;
        let multipliers = if self.m == 0 {
            Vec::new()
        } else {
            (1..steps)
                .map(|k| DVector::from_column_slice(&x[(k - 1) * s + n..k * s]))
                .collect()
        };
        Ok(DiscretePath {
            t: (0..=steps).map(|k| self.tk(k)).collect(),
            q: (0..=steps)
                .map(|k| DVector::from_column_slice(self.node(k)))
                .collect(),
            multipliers,
            p0: DVector::from_vec(p0),
            p1: DVector::from_vec(p1),
            action,
            newton: info,
            morse_index: None,
            conjugate_times: Vec::new(),
            margin: f64::NAN,
        })
    }

    /// The blocks A_k (k = 1..N−1) and B_k = D₁₂L_d(q_k, q_{k+1}) (k = 0..N−1) of the Jacobi operator
    /// at the current nodes.
    fn jacobi_blocks(&mut self) -> (Vec<DMatrix<f64>>, Vec<DMatrix<f64>>) {
        let (n, steps, h) = (self.n, self.steps, self.h);
        let mut a = vec![DMatrix::zeros(n, n); steps + 1];
        let mut b = Vec::with_capacity(steps);
        for k in 0..steps {
            let (q0, q1) = (self.node(k).to_vec(), self.node(k + 1).to_vec());
            self.ld.d11(self.tk(k), h, &q0, &q1, &mut self.d11);
            self.ld.d22(self.tk(k), h, &q0, &q1, &mut self.d22);
            self.ld.d12(self.tk(k), h, &q0, &q1, &mut self.d12);
            a[k] += &self.d11;
            a[k + 1] += &self.d22;
            b.push(self.d12.clone());
        }
        (a, b)
    }

    /// Morse index and conjugate times of the (unconstrained) Jacobi operator at the nodes of `x`.
    fn jacobi(&mut self, x: &[f64]) -> JacobiInfo {
        self.set_interior(x);
        let (a, b) = self.jacobi_blocks();
        let (n, steps) = (self.n, self.steps);
        // Inertia of the block LDLᵀ: D₁ = A₁, D_k = A_k − B_{k−1}ᵀ D_{k−1}⁻¹ B_{k−1}.
        let mut morse = Some(0usize);
        let mut d: Option<DMatrix<f64>> = None;
        for k in 1..steps {
            let mut dk = a[k].clone();
            if let Some(prev) = &d {
                match prev.clone().lu().solve(&b[k - 1]) {
                    Some(y) => dk -= b[k - 1].transpose() * y,
                    None => {
                        morse = None;
                        break;
                    }
                }
            }
            let sym = (&dk + dk.transpose()) * 0.5;
            let neg = sym.symmetric_eigenvalues().iter().filter(|&&l| l < 0.0).count();
            morse = morse.map(|m| m + neg);
            d = Some(dk);
        }
        // Matrix Jacobi field J₀ = 0, J₁ = I: B_{k−1}ᵀ J_{k−1} + A_k J_k + B_k J_{k+1} = 0.
        let mut conjugate_times = Vec::new();
        let mut jm = DMatrix::<f64>::zeros(n, n);
        let mut j = DMatrix::<f64>::identity(n, n);
        let mut end_root = None;
        for k in 1..steps {
            let rhs = -(&a[k] * &j + b[k - 1].transpose() * &jm);
            let Some(next) = b[k].clone().lu().solve(&rhs) else {
                break;
            };
            let (dk, dn) = (j.determinant(), next.determinant());
            if dk != 0.0 && (dn == 0.0 || dk.signum() != dn.signum()) {
                conjugate_times.push(self.tk(k) + self.h * dk / (dk - dn));
            } else if k + 1 == steps && dk != dn {
                // No zero in the last step: the zero of the secant through it, when it falls within
                // one step beyond t₁ (a conjugate point just after the end).
                let t = self.tk(k) + self.h * dk / (dk - dn);
                if t > self.tk(k + 1) && t <= self.tk(k + 1) + self.h {
                    end_root = Some(t);
                }
            }
            let s = next.amax().max(j.amax());
            if !(s.is_finite() && s > 0.0) {
                break;
            }
            jm = j / s;
            j = next / s;
        }
        // μ: the smallest eigenvalue of the diagonal blocks (the largest magnitude if none is positive).
        let eig: Vec<f64> = (1..steps)
            .flat_map(|k| {
                ((&a[k] + a[k].transpose()) * 0.5)
                    .symmetric_eigenvalues()
                    .as_slice()
                    .to_vec()
            })
            .collect();
        let pos = eig
            .iter()
            .copied()
            .filter(|&l| l > 0.0)
            .fold(f64::INFINITY, f64::min);
        let mu = if pos.is_finite() {
            pos
        } else {
            eig.iter().fold(0.0_f64, |m, l| m.max(l.abs()))
        };
        JacobiInfo {
            morse_index: morse,
            conjugate_times,
            end_root,
            mu,
        }
    }

    /// The conjugate-point margin (module docs) of the Jacobi operator H at `x`: its smallest-magnitude
    /// eigenvalue (signed, by inverse iteration on the banded factor) over the one of a free particle
    /// with the same diagonal blocks, 2 sin²(π/2N) μ, μ the smallest eigenvalue of the diagonal blocks
    /// A_k (for L_d = ½ (q₁ − q₀)ᵀM(q₁ − q₀)/h, H = tridiag(−M, 2M, −M)/h and the margin is exactly 1).
    /// 0 when H cannot be factored.
    fn margin(&mut self, x: &[f64], mu: f64) -> f64 {
        if self.factor_jacobian(x).is_err() {
            return 0.0;
        }
        let Some(lu) = self.lu.as_ref() else {
            return 0.0;
        };
        let dim = (self.steps - 1) * self.block();
        let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
        // A deterministic start with every mode present.
        let mut v: Vec<f64> = (0..dim).map(|i| 1.0 + 0.1 * ((i * 7919) % 13) as f64).collect();
        let mut small = f64::NAN;
        for _ in 0..INVERSE_ITERATIONS {
            let nv = norm(&v);
            v.iter_mut().for_each(|a| *a /= nv);
            let mut w = v.clone();
            lu.solve(&mut w);
            // Rayleigh quotient of H⁻¹: 1/λ, with its sign.
            let r: f64 = v.iter().zip(&w).map(|(a, b)| a * b).sum();
            let next = 1.0 / r;
            let done = (next - small).abs() <= 1e-12 * next.abs();
            small = next;
            v = w;
            if done {
                break;
            }
        }
        let free = 2.0 * (std::f64::consts::PI / (2.0 * self.steps as f64)).sin().powi(2) * mu;
        small / free
    }

    /// The banded Jacobian at `x`.
    fn assemble(&mut self, x: &[f64]) -> Banded {
        self.set_interior(x);
        let (n, m, s, steps, h) = (self.n, self.m, self.block(), self.steps, self.h);
        let bw = 2 * s - 1;
        let mut jac = Banded::zeros((steps - 1) * s, bw, bw);
        for k in 0..steps {
            let (q0, q1) = (self.node(k).to_vec(), self.node(k + 1).to_vec());
            self.ld.d11(self.tk(k), h, &q0, &q1, &mut self.d11);
            self.ld.d22(self.tk(k), h, &q0, &q1, &mut self.d22);
            self.ld.d12(self.tk(k), h, &q0, &q1, &mut self.d12);
            // Rows of node k get D₁₁ (and D₁₂ toward node k+1); rows of node k+1 get D₂₂ (and D₂₁).
            for i in 0..n {
                for j in 0..n {
                    if k >= 1 {
                        let r = (k - 1) * s + i;
                        jac.add(r, (k - 1) * s + j, self.d11[(i, j)]);
                        if k + 1 < steps {
                            jac.add(r, k * s + j, self.d12[(i, j)]);
                        }
                    }
                    if k + 1 < steps {
                        let r = k * s + i;
                        jac.add(r, k * s + j, self.d22[(i, j)]);
                        if k >= 1 {
                            jac.add(r, (k - 1) * s + j, self.d12[(j, i)]);
                        }
                    }
                }
            }
        }
        if m > 0 {
            for k in 1..steps {
                self.constraint_jacobian(k);
                let base = (k - 1) * s;
                let lambda = x[base + n..base + s].to_vec();
                let f = Weighted {
                    c: self.c,
                    lambda: &lambda,
                };
                let q = self.node(k).to_vec();
                ad::hessian(&f, 0.0, &q, &[], Block::X, Block::X, &mut self.lhess);
                for i in 0..n {
                    for j in 0..n {
                        jac.add(base + i, base + j, self.lhess[(i, j)]);
                    }
                }
                for r in 0..m {
                    for j in 0..n {
                        let g = self.gjac[(r, j)];
                        jac.add(base + j, base + n + r, g);
                        jac.add(base + n + r, base + j, g);
                    }
                }
            }
        }
        jac
    }
}

struct JacobiInfo {
    morse_index: Option<usize>,
    conjugate_times: Vec<f64>,
    /// A zero of det J extrapolated within one step after t₁ (a conjugate point just beyond the end).
    end_root: Option<f64>,
    /// Smallest eigenvalue of the diagonal blocks A_k (module docs: the margin's scale).
    mu: f64,
}

impl<Ld: DiscreteLagrangian, C: PathConstraint> NewtonSystem for System<'_, Ld, C> {
    fn dim(&self) -> usize {
        (self.steps - 1) * self.block()
    }

    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()> {
        self.set_interior(x);
        let (n, m, s, steps, h) = (self.n, self.m, self.block(), self.steps, self.h);
        r.iter_mut().for_each(|v| *v = 0.0);
        for k in 0..steps {
            let (t, q0, q1) = (
                self.tk(k),
                &self.q[k * n..(k + 1) * n],
                &self.q[(k + 1) * n..(k + 2) * n],
            );
            if k >= 1 {
                self.ld.d1(t, h, q0, q1, &mut self.g1);
                let base = (k - 1) * s;
                r[base..base + n]
                    .iter_mut()
                    .zip(&self.g1)
                    .for_each(|(a, b)| *a += b);
            }
            if k + 1 < steps {
                self.ld.d2(t, h, q0, q1, &mut self.g2);
                let base = k * s;
                r[base..base + n]
                    .iter_mut()
                    .zip(&self.g2)
                    .for_each(|(a, b)| *a += b);
            }
        }
        if m > 0 {
            for k in 1..steps {
                self.constraint_jacobian(k);
                let base = (k - 1) * s;
                // D₂L_d + D₁L_d + ∇gᵀλ = 0 (stationary points of S_d + Σ_k λ_k·g(q_k)), g = 0.
                for j in 0..n {
                    let gl: f64 = (0..m).map(|i| self.gjac[(i, j)] * x[base + n + i]).sum();
                    r[base + j] += gl;
                }
                r[base + n..base + s].copy_from_slice(&self.cval);
            }
        }
        Ok(())
    }

    fn factor_jacobian(&mut self, x: &[f64]) -> Result<()> {
        self.lu = None;
        let jac = self.assemble(x);
        let lu = jac.factor().map_err(|e| e.in_matrix(JACOBIAN))?;
        self.lu = Some(lu);
        Ok(())
    }

    fn solve(&mut self, rhs: &mut [f64]) -> Result<()> {
        match &self.lu {
            Some(lu) => {
                lu.solve(rhs);
                Ok(())
            }
            None => Err(Error::SingularMatrix {
                what: JACOBIAN,
                pivot_ratio: f64::NAN,
            }),
        }
    }
}

/// A discrete Lagrangian as an AD field (value only).
struct DiscreteField<'a, Ld> {
    ld: &'a Ld,
    t0: f64,
}

impl<Ld: DiscreteLagrangian> Field for DiscreteField<'_, Ld> {
    fn eval<D: Scalar>(&self, h: D, x: &[D], y: &[D]) -> D {
        self.ld.discrete_lagrangian(self.t0, h, x, y)
    }
}

/// Component i of g(q) as an AD field.
struct Component<'a, C> {
    c: &'a C,
    i: usize,
}

impl<C: PathConstraint> Field for Component<'_, C> {
    fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
        let mut out = Scratch::filled(self.c.count(), D::zero());
        self.c.constraints(x, &mut out);
        out[self.i]
    }
}

/// λ·g(q) as an AD field.
struct Weighted<'a, C> {
    c: &'a C,
    lambda: &'a [f64],
}

impl<C: PathConstraint> Field for Weighted<'_, C> {
    fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
        let mut out = Scratch::filled(self.c.count(), D::zero());
        self.c.constraints(x, &mut out);
        out.iter()
            .zip(self.lambda)
            .fold(D::zero(), |acc, (g, l)| acc + *g * *l)
    }
}

/// S_d in the interior positions as an argmin problem.
struct ActionProblem<'a, Ld> {
    sys: std::cell::RefCell<System<'a, Ld, Free>>,
    /// ‖x‖∞ beyond which the descent is taken to run away (S_d unbounded below along it).
    runaway: f64,
}

/// A descent of S_d is taken to run away beyond this many times 1 + ‖guess‖∞.
const RUNAWAY: f64 = 1e6;

/// The descent of S_d left every bound (S_d unbounded below along it).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("the descent of the discrete action ran away")]
struct RanAway;

impl<Ld: DiscreteLagrangian> argmin::core::CostFunction for ActionProblem<'_, Ld> {
    type Param = DVector<f64>;
    type Output = f64;
    fn cost(&self, x: &DVector<f64>) -> std::result::Result<f64, argmin::core::Error> {
        let size = noether_core::newton::max_norm(x.as_slice());
        if size.is_nan() || size > self.runaway {
            return Err(RanAway.into());
        }
        let mut sys = self.sys.borrow_mut();
        sys.set_interior(x.as_slice());
        let s = sys.action();
        if s.is_finite() {
            Ok(s)
        } else {
            Err(RanAway.into())
        }
    }
}

impl<Ld: DiscreteLagrangian> argmin::core::Gradient for ActionProblem<'_, Ld> {
    type Param = DVector<f64>;
    type Gradient = DVector<f64>;
    fn gradient(&self, x: &DVector<f64>) -> std::result::Result<DVector<f64>, argmin::core::Error> {
        let mut sys = self.sys.borrow_mut();
        let mut r = vec![0.0; sys.dim()];
        sys.residual(x.as_slice(), &mut r)?;
        Ok(DVector::from_vec(r))
    }
}
