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
//! all from dual numbers ([`DiscreteDerivatives`](crate::lagrangian::DiscreteDerivatives)). It is
//! stored banded (half-bandwidth 2n − 1 for n coordinates) and factored by core's
//! [`Banded`](noether_core::linalg::Banded) LU: O(N n³) per Newton iteration.
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

mod linear;
mod system;

pub use linear::LinearPath;

use crate::lagrangian::{DiscreteLagrangian, Scratch};
use nalgebra::DVector;
use noether_core::ad::Field;
use noether_core::error::{check_finite, check_len};
use noether_core::{Error, Newton, NewtonInfo, NewtonSystem, Result, Scalar};
use system::System;

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
        BoundaryValue {
            ld,
            newton: Newton::default()
                .residual_tolerance(1e-14)
                .expect("a positive tolerance"),
            conjugate_tolerance: DEFAULT_CONJUGATE_TOLERANCE,
        }
    }

    /// Replaces the Newton settings (the residual tolerance is still raised to the rounding floor).
    pub fn newton(mut self, newton: Newton) -> Self {
        self.newton = newton;
        self
    }

    /// Replaces the conjugate-point tolerance on the margin (finite and positive, else
    /// `InvalidParameter`; default [`DEFAULT_CONJUGATE_TOLERANCE`]).
    pub fn conjugate_tolerance(mut self, tol: f64) -> Result<Self> {
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
