//! Equilibria of a potential V(q): found by minimisation (argmin's trust-region method with the
//! Steihaug subproblem, exact gradient and Hessian by dual numbers) or, for saddles and maxima, as a
//! root of ∇V = 0 (noether-core's Newton with the Hessian as Jacobian); classified by the eigenvalues
//! of the Hessian ∂²V/∂q²:
//!
//! - all non-zero eigenvalues positive: a minimum (stable when there are no zero modes);
//! - some positive, some negative: a saddle; all negative: a maximum;
//! - eigenvalues with |λ| ≤ `zero_tolerance`·max|λ| are zero modes (flat directions such as the
//!   translations and rotations of a free body) and are counted apart.
//!
//! ```
//! use noether_analysis::{EquilibriumFinder, Kind, Potential};
//! use noether_core::Scalar;
//!
//! /// Double well V = (q² − 1)²: minima at q = ±1, a maximum at 0.
//! struct DoubleWell;
//! impl Potential for DoubleWell {
//!     fn dof(&self) -> usize { 1 }
//!     fn potential<D: Scalar>(&self, q: &[D]) -> D {
//!         let s = q[0] * q[0] - 1.0;
//!         s * s
//!     }
//! }
//!
//! let finder = EquilibriumFinder::default();
//! let min = finder.minimize(&DoubleWell, &[0.3]).unwrap();
//! assert!((min.q[0] - 1.0).abs() < 1e-10);
//! assert_eq!(min.kind, Kind::Minimum);
//! assert!((min.eigenvalues[0] - 8.0).abs() < 1e-9); // V'' = 12q² − 4 = 8 at q = 1
//! let top = finder.stationary_point(&DoubleWell, &[0.1]).unwrap();
//! assert_eq!(top.kind, Kind::Maximum);
//! ```

use argmin::core::{
    CostFunction, Executor, Gradient, Hessian, IterState, Problem, Solver, State, TerminationReason,
    TerminationStatus, KV,
};
use argmin::solver::trustregion::{Steihaug, TrustRegion};
use nalgebra::{DMatrix, DVector};
use noether_core::error::check_positive;
use noether_core::newton::{Newton, NewtonSystem};

use crate::potential::{self, check_point, Potential};
use crate::{Error, Result};

/// The kind of a stationary point, from the signs of the Hessian's non-zero eigenvalues.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// No negative eigenvalue (and at least one positive).
    Minimum,
    /// Positive and negative eigenvalues.
    Saddle,
    /// No positive eigenvalue (and at least one negative).
    Maximum,
    /// Every eigenvalue is zero: the second-order test says nothing.
    Flat,
}

/// A stationary point of a potential with its classification.
#[derive(Debug, Clone, PartialEq)]
pub struct Equilibrium {
    /// Coordinates.
    pub q: DVector<f64>,
    /// V(q).
    pub value: f64,
    /// ‖∇V(q)‖∞ (how stationary it is).
    pub gradient_norm: f64,
    /// Hessian ∂²V/∂q².
    pub hessian: DMatrix<f64>,
    /// Eigenvalues of the Hessian, ascending.
    pub eigenvalues: DVector<f64>,
    /// Classification by the signs of the non-zero eigenvalues.
    pub kind: Kind,
    /// Number of eigenvalues with |λ| ≤ zero_tolerance·max|λ|.
    pub zero_modes: usize,
    /// Iterations of the solver that found it (0 for [`classify`]).
    pub iterations: u64,
}

/// The gradient a displacement of the size of the coordinates would produce: ‖H‖max·(1 + ‖q‖∞)
/// (1 when H = 0). Gradient tolerances are relative to it, so they do not depend on units.
pub(crate) fn gradient_scale(h: &DMatrix<f64>, q: &[f64]) -> f64 {
    let s = h.amax() * (1.0 + q.iter().fold(0.0_f64, |m, x| m.max(x.abs())));
    if s > 0.0 && s.is_finite() {
        s
    } else {
        1.0
    }
}

/// Counts (negative, zero, positive) eigenvalues, zero meaning |λ| ≤ tol·max|λ|.
pub(crate) fn signature(eigenvalues: &DVector<f64>, zero_tolerance: f64) -> (usize, usize, usize) {
    let big = eigenvalues.amax();
    let (mut neg, mut zero, mut pos) = (0, 0, 0);
    for &l in eigenvalues.iter() {
        if l.abs() <= zero_tolerance * big || big == 0.0 {
            zero += 1;
        } else if l < 0.0 {
            neg += 1;
        } else {
            pos += 1;
        }
    }
    (neg, zero, pos)
}

/// Sorted eigenvalues of a symmetric matrix.
pub(crate) fn sorted_symmetric_eigenvalues(h: &DMatrix<f64>) -> DVector<f64> {
    let sym = (h + h.transpose()) * 0.5;
    let mut ev: Vec<f64> = sym.symmetric_eigenvalues().iter().copied().collect();
    ev.sort_by(|a, b| a.total_cmp(b));
    DVector::from_vec(ev)
}

/// Classifies the point `q` of `pot` (it does not check that q is stationary: see
/// [`Equilibrium::gradient_norm`]).
pub fn classify<P: Potential + ?Sized>(pot: &P, q: &[f64], zero_tolerance: f64) -> Result<Equilibrium> {
    let (value, g) = potential::gradient(pot, q)?;
    let hessian = potential::hessian(pot, q)?;
    let eigenvalues = sorted_symmetric_eigenvalues(&hessian);
    let (neg, zero_modes, pos) = signature(&eigenvalues, zero_tolerance);
    let kind = match (neg > 0, pos > 0) {
        (false, true) => Kind::Minimum,
        (true, true) => Kind::Saddle,
        (true, false) => Kind::Maximum,
        (false, false) => Kind::Flat,
    };
    Ok(Equilibrium {
        q: DVector::from_column_slice(q),
        value,
        gradient_norm: g.amax(),
        hessian,
        eigenvalues,
        kind,
        zero_modes,
        iterations: 0,
    })
}

/// Finds and classifies equilibria. Builder-style setters; `Default` gives sensible tolerances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EquilibriumFinder {
    gradient_tolerance: f64,
    max_iterations: usize,
    zero_tolerance: f64,
}

impl Default for EquilibriumFinder {
    fn default() -> Self {
        EquilibriumFinder {
            gradient_tolerance: 1e-12,
            max_iterations: 200,
            zero_tolerance: 1e-9,
        }
    }
}

impl EquilibriumFinder {
    /// Sets the relative gradient tolerance (default 1e-12): converged when
    /// ‖∇V‖∞ ≤ this · ‖H(q₀)‖max · (1 + ‖q₀‖∞). Finite and positive.
    pub fn gradient_tolerance(mut self, tol: f64) -> Result<Self> {
        self.gradient_tolerance = check_positive("gradient_tolerance", tol)?;
        Ok(self)
    }
    /// Sets the iteration cap of the trust-region or Newton iterations (default 200; at least 1).
    pub fn max_iterations(mut self, n: usize) -> Result<Self> {
        self.max_iterations = noether_core::error::check_iteration_cap("max_iterations", n)?;
        Ok(self)
    }
    /// Sets the relative size below which a Hessian eigenvalue counts as zero (default 1e-9; finite
    /// and positive).
    pub fn zero_tolerance(mut self, tol: f64) -> Result<Self> {
        self.zero_tolerance = check_positive("zero_tolerance", tol)?;
        Ok(self)
    }

    fn tolerance<P: Potential + ?Sized>(&self, pot: &P, q0: &[f64]) -> Result<f64> {
        Ok(self.gradient_tolerance * gradient_scale(&potential::hessian(pot, q0)?, q0))
    }

    /// A local minimum of V from `q0` by argmin's trust-region method (Steihaug subproblem, exact
    /// Hessian): it descends from any start, through regions where the Hessian is indefinite. A run
    /// that ends on a saddle or a maximum (a start exactly there, where the gradient vanishes) is
    /// [`Error::NotMinimum`]; one that does not reach the gradient tolerance is
    /// [`Error::NotConverged`].
    ///
    /// A cost-based method cannot resolve ∇V much below sqrt(ε)·scale (the decrease of V is lost in
    /// rounding), so argmin stops at ‖∇V‖∞ ≤ sqrt(`gradient_tolerance`)·scale and Newton's method on ∇V = 0
    /// polishes the last digits (quadratic convergence, no comparison of V values).
    pub fn minimize<P: Potential + ?Sized>(&self, pot: &P, q0: &[f64]) -> Result<Equilibrium> {
        check_point(q0, pot.dof())?;
        let tol = self.tolerance(pot, q0)?;
        let coarse = tol * self.gradient_tolerance.sqrt().recip().max(1.0);
        let solver = UntilGradient {
            inner: TrustRegion::new(Steihaug::new().with_max_iters(10 * pot.dof().max(1) as u64)),
            tol: coarse,
        };
        let res = Executor::new(ArgminPotential(pot), solver)
            .configure(|s| {
                s.param(DVector::from_column_slice(q0))
                    .max_iters(self.max_iterations as u64)
            })
            .ctrlc(false)
            .run()
            .map_err(|e| Error::Optimizer(e.to_string()))?;
        let state = res.state();
        let iterations = state.get_iter();
        let q = state
            .get_best_param()
            .or(state.get_param())
            .ok_or_else(|| Error::Optimizer("no parameter in the final state".into()))?
            .clone();
        let (_, g) = potential::gradient(pot, q.as_slice())?;
        let not_converged = |gradient_norm| Error::NotConverged {
            iterations,
            gradient_norm,
            tolerance: tol,
        };
        if g.amax().is_nan() || g.amax() > coarse {
            return Err(not_converged(g.amax()));
        }
        let newton = self.newton(tol)?;
        let (q, info) = newton_root(&newton, pot, q.as_slice(), self.zero_tolerance)
            .map_err(|_| not_converged(g.amax()))?;
        let mut eq = classify(pot, q.as_slice(), self.zero_tolerance)?;
        if matches!(eq.kind, Kind::Saddle | Kind::Maximum) {
            return Err(Error::NotMinimum {
                kind: eq.kind,
                point: eq.q.as_slice().to_vec(),
            });
        }
        eq.iterations = iterations + info.iterations as u64;
        Ok(eq)
    }

    fn newton(&self, tol: f64) -> noether_core::Result<Newton> {
        Newton::default()
            .residual_tolerance(tol)?
            .max_iterations(self.max_iterations)
    }

    /// A stationary point ∇V = 0 near `q0` of any kind (minimum, saddle, maximum) by Newton's method
    /// with the exact Hessian as Jacobian (zero modes of the Hessian are left out of each step). Newton converges to the nearest root of ∇V, so start near
    /// the point you want.
    pub fn stationary_point<P: Potential + ?Sized>(&self, pot: &P, q0: &[f64]) -> Result<Equilibrium> {
        check_point(q0, pot.dof())?;
        let tol = self.tolerance(pot, q0)?;
        let (q, info) = newton_root(&self.newton(tol)?, pot, q0, self.zero_tolerance)?;
        let mut eq = classify(pot, q.as_slice(), self.zero_tolerance)?;
        eq.iterations = info.iterations as u64;
        Ok(eq)
    }
}

/// ∇V = 0 as a Newton problem with the Hessian as Jacobian, solved through its symmetric
/// eigen-decomposition with the zero modes dropped (a minimum-norm Newton step): flat directions such as
/// the free translations of a body make the Hessian singular, and a plain LU step would throw the
/// iterate along them.
struct GradientRoot<'a, P: ?Sized> {
    pot: &'a P,
    zero_tolerance: f64,
    eigen: Option<nalgebra::SymmetricEigen<f64, nalgebra::Dyn>>,
}

impl<'a, P: Potential + ?Sized> GradientRoot<'a, P> {
    fn new(pot: &'a P, zero_tolerance: f64) -> Self {
        GradientRoot {
            pot,
            zero_tolerance,
            eigen: None,
        }
    }
}

impl<P: Potential + ?Sized> NewtonSystem for GradientRoot<'_, P> {
    fn dim(&self) -> usize {
        self.pot.dof()
    }
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> noether_core::Result<()> {
        let (_, g) = potential::gradient(self.pot, x).map_err(noether_core::Error::from)?;
        r.copy_from_slice(g.as_slice());
        Ok(())
    }
    fn factor_jacobian(&mut self, x: &[f64]) -> noether_core::Result<()> {
        let h = potential::hessian(self.pot, x).map_err(noether_core::Error::from)?;
        let h = (&h + h.transpose()) * 0.5;
        let eig = h
            .try_symmetric_eigen(f64::EPSILON, 10_000)
            .ok_or(noether_core::Error::SingularMatrix {
                what: "Hessian of V (eigen-decomposition did not converge)",
                pivot_ratio: f64::NAN,
            })?;
        // A pseudo-inverse (directions with |λ| ≤ zero_tolerance·max|λ| are dropped in `solve`), so
        // only the zero or non-finite Hessian is singular here; the ratio reported is that of the
        // eigenvalues.
        if eig.eigenvalues.amax() == 0.0 || !eig.eigenvalues.iter().all(|l| l.is_finite()) {
            let (lo, hi) = noether_core::linalg::pivot_range(eig.eigenvalues.iter().copied());
            return Err(noether_core::Error::SingularMatrix {
                what: "Hessian of V",
                pivot_ratio: noether_core::linalg::pivot_ratio(lo, hi, hi),
            });
        }
        self.eigen = Some(eig);
        Ok(())
    }
    fn solve(&mut self, rhs: &mut [f64]) -> noether_core::Result<()> {
        let eig = self.eigen.as_ref().ok_or(noether_core::Error::SingularMatrix {
            what: "Hessian of V (not factored)",
            pivot_ratio: f64::NAN,
        })?;
        let cut = self.zero_tolerance * eig.eigenvalues.amax();
        let b = DVector::from_column_slice(rhs);
        let mut c = eig.eigenvectors.tr_mul(&b);
        for (ci, &l) in c.iter_mut().zip(eig.eigenvalues.iter()) {
            *ci = if l.abs() > cut { *ci / l } else { 0.0 };
        }
        rhs.copy_from_slice((&eig.eigenvectors * c).as_slice());
        Ok(())
    }
}

/// Runs Newton on ∇V = 0 from `q0`.
fn newton_root<P: Potential + ?Sized>(
    newton: &Newton,
    pot: &P,
    q0: &[f64],
    zero_tolerance: f64,
) -> noether_core::Result<(DVector<f64>, noether_core::NewtonInfo)> {
    let mut sys = GradientRoot::new(pot, zero_tolerance);
    let mut x = q0.to_vec();
    let info = newton.solve(&mut sys, &mut x)?;
    Ok((DVector::from_vec(x), info))
}

/// A potential as an argmin problem on nalgebra vectors.
struct ArgminPotential<'a, P: ?Sized>(&'a P);

impl<P: Potential + ?Sized> CostFunction for ArgminPotential<'_, P> {
    type Param = DVector<f64>;
    type Output = f64;
    fn cost(&self, q: &DVector<f64>) -> std::result::Result<f64, argmin::core::Error> {
        check_point(q.as_slice(), self.0.dof())?;
        Ok(self.0.potential(q.as_slice()))
    }
}

impl<P: Potential + ?Sized> Gradient for ArgminPotential<'_, P> {
    type Param = DVector<f64>;
    type Gradient = DVector<f64>;
    fn gradient(&self, q: &DVector<f64>) -> std::result::Result<DVector<f64>, argmin::core::Error> {
        Ok(potential::gradient(self.0, q.as_slice())?.1)
    }
}

impl<P: Potential + ?Sized> Hessian for ArgminPotential<'_, P> {
    type Param = DVector<f64>;
    type Hessian = DMatrix<f64>;
    fn hessian(&self, q: &DVector<f64>) -> std::result::Result<DMatrix<f64>, argmin::core::Error> {
        Ok(potential::hessian(self.0, q.as_slice())?)
    }
}

type TrState = IterState<DVector<f64>, DVector<f64>, (), DMatrix<f64>, (), f64>;

/// Wraps an argmin solver and stops it once ‖∇V‖∞ ≤ tol (argmin's trust region has no gradient test).
#[derive(Clone)]
struct UntilGradient<S> {
    inner: S,
    tol: f64,
}

impl<O, S: Solver<O, TrState>> Solver<O, TrState> for UntilGradient<S> {
    fn name(&self) -> &str {
        self.inner.name()
    }
    fn init(
        &mut self,
        problem: &mut Problem<O>,
        state: TrState,
    ) -> std::result::Result<(TrState, Option<KV>), argmin::core::Error> {
        self.inner.init(problem, state)
    }
    fn next_iter(
        &mut self,
        problem: &mut Problem<O>,
        state: TrState,
    ) -> std::result::Result<(TrState, Option<KV>), argmin::core::Error> {
        self.inner.next_iter(problem, state)
    }
    fn terminate(&mut self, state: &TrState) -> TerminationStatus {
        match state.get_gradient() {
            Some(g) if g.amax() <= self.tol => {
                TerminationStatus::Terminated(TerminationReason::SolverConverged)
            }
            _ => self.inner.terminate(state),
        }
    }
}
