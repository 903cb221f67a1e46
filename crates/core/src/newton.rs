//! One Newton solver for every implicit equation in noether: implicit integrators, the discrete
//! Euler-Lagrange equations, constraint projections, the inverse Legendre map.
//!
//! Solves F(x) = 0 by x ← x − J⁻¹F(x). The problem supplies the residual and a way to factor and apply
//! its Jacobian ([`NewtonSystem`]); [`Dense`] adapts any problem with a dense Jacobian (LU of
//! [`linalg`](crate::linalg), which also rejects a near-singular Jacobian). A factored
//! Jacobian is reused (modified Newton) while the residual keeps contracting and is refreshed when it
//! does not. The stopping rule is round-off aware (see [`Newton`]): at least one correction, then the
//! residual or step tolerance, or increments that have stopped decreasing at the rounding level.

use crate::error::check_positive;
use crate::linalg::{solve_with, DenseFactor};
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector};

/// A nonlinear system F(x) = 0 with its own Jacobian factorization (dense, banded, sparse, ...).
pub trait NewtonSystem {
    /// Number of unknowns (= number of equations).
    fn dim(&self) -> usize;
    /// F(x) into `r`.
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()>;
    /// Evaluates and factors the Jacobian J = ∂F/∂x at `x`, keeping the factor for [`solve`](Self::solve).
    fn factor_jacobian(&mut self, x: &[f64]) -> Result<()>;
    /// Overwrites `rhs` with J⁻¹ rhs using the last factor.
    fn solve(&mut self, rhs: &mut [f64]) -> Result<()>;
}

/// A nonlinear system with a dense Jacobian; wrap it in [`Dense`] to solve it.
pub trait DenseProblem {
    /// Number of unknowns.
    fn dim(&self) -> usize;
    /// F(x) into `r`.
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()>;
    /// J(x) = ∂F/∂x into `j` (dim × dim).
    fn jacobian(&mut self, x: &[f64], j: &mut DMatrix<f64>) -> Result<()>;
}

/// Adapter giving a [`DenseProblem`] an LU-factored Jacobian.
pub struct Dense<P> {
    /// The problem.
    pub problem: P,
    jac: DMatrix<f64>,
    lu: Option<DenseFactor>,
}

impl<P: DenseProblem> Dense<P> {
    /// Wraps `problem`.
    pub fn new(problem: P) -> Self {
        let n = problem.dim();
        Dense {
            problem,
            jac: DMatrix::zeros(n, n),
            lu: None,
        }
    }
}

impl<P: DenseProblem> NewtonSystem for Dense<P> {
    fn dim(&self) -> usize {
        self.problem.dim()
    }
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()> {
        self.problem.residual(x, r)
    }
    fn factor_jacobian(&mut self, x: &[f64]) -> Result<()> {
        self.problem.jacobian(x, &mut self.jac)?;
        self.lu = None;
        let lu = DenseFactor::lu(self.jac.clone()).map_err(|e| match e {
            // A NaN or infinite entry: the model's non-finite result, as for the residual.
            crate::linalg::FactorError::NonFinite => Error::NonFiniteResult {
                what: "Newton Jacobian",
                t: f64::NAN,
                component: None,
            },
            e => e.in_matrix("Newton Jacobian"),
        })?;
        self.lu = Some(lu);
        Ok(())
    }
    fn solve(&mut self, rhs: &mut [f64]) -> Result<()> {
        solve_with(self.lu.as_ref(), rhs, "Newton Jacobian")
    }
}

/// Newton's method with tolerances, an iteration cap and Jacobian reuse.
///
/// Build it from [`Newton::default`] and the setters, which refuse a NaN, zero or negative tolerance,
/// a contraction outside (0, 1) or an iteration cap of 0 with [`Error::InvalidParameter`]; read the
/// settings back by `get_` and the setting's name.
///
/// **Stopping rule** (round-off aware, after Hairer-Wanner's RADAU5, *Solving ODEs II* IV.8, and
/// GeometricIntegrators.jl). At least one correction Δₖ = J⁻¹F(xₖ₋₁) is always made (unless F(x₀)
/// is exactly zero): a guess that already meets the tolerance is still corrected, so the unconverged
/// remainder of a good predictor does not pile up over many solves. After correction k the iterate is
/// converged when
/// 1. ‖F(xₖ)‖∞ ≤ `residual_tolerance`; or
/// 2. ‖Δₖ‖∞ ≤ `step_tolerance`·(1 + ‖xₖ‖∞) (and ‖F(xₖ)‖∞ ≤ √`residual_tolerance`); or
/// 3. the increments have stopped decreasing (θ ≥ 1) under a Jacobian factored at the previous
///    iterate, at the rounding level: ‖Δₖ‖∞ ≤ √`step_tolerance`·(1 + ‖xₖ‖∞) and
///    ‖F(xₖ)‖∞ ≤ √`residual_tolerance`. Newton with an exact Jacobian cannot improve such an iterate
///    further: the residual is at the rounding floor of its evaluation, above a tolerance set below
///    what rounding allows, and that is not divergence.
///
/// A kept Jacobian factor is used while the residual contracts by `contraction` per correction and
/// refreshed at the current iterate as soon as it does not, so a stale factor never causes a failure.
/// RADAU5's contraction estimate θ/(1 − θ)‖Δₖ‖ (θ = ‖Δₖ‖/‖Δₖ₋₁‖) is deliberately not a stopping test:
/// even with its bound at ε·(1 + ‖x‖) it ends solves one correction early with a remainder of the
/// same sign step after step (measured: the variational midpoint's angular momentum on Kepler drifted
/// 1.6e-12 in 10⁵ steps, against 3.3e-14 without it).
///
/// **Line search** ([`line_search`](Self::line_search), off by default). Far from a root the full
/// correction can overshoot into another basin, or out of the region where the model is sensible.
/// With the line search on, every correction uses the Jacobian at the current iterate and is
/// shortened, x ← x − αΔ with α = 1, ½, ¼, …, until the merit φ = ½‖F‖₂² decreases by Armijo's
/// condition φ(x − αΔ) ≤ (1 − 2·10⁻⁴ α) φ(x) (the Newton direction is a descent direction of φ, with
/// slope −2φ; Dennis & Schnabel, *Numerical Methods for Unconstrained Optimization and Nonlinear
/// Equations*, §6.3). A rough guess then goes to a root downhill in ‖F‖ or stops: when α falls below
/// 2⁻³⁰ without a decrease (a local minimum of ‖F‖ that is not a root) the solve fails with
/// [`Error::NewtonDiverged`] at that iterate. Once ‖F‖∞ ≤ √`residual_tolerance` the full corrections
/// are taken (Newton's local quadratic convergence, and a merit at its rounding floor that need not
/// decrease).
///
/// The solve fails with [`Error::NewtonDiverged`] (iterations, last finite residual) only when the cap
/// `max_iterations` is reached (or a line search finds no decrease), and with
/// [`Error::NonFiniteResult`] (`what` = "Newton residual", t = NaN) when the residual is NaN or
/// infinite at the guess, or stays so after a correction halved 40 times toward the last iterate (a
/// model evaluated outside its domain, e.g. √q at q < 0: the error contract's non-finite result, not
/// a divergence). [`Dense`] reports a NaN or infinite Jacobian
/// entry the same way (`what` = "Newton Jacobian").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Newton {
    residual_tolerance: f64,
    step_tolerance: f64,
    max_iterations: usize,
    reuse_jacobian: bool,
    contraction: f64,
    line_search: bool,
}

impl Default for Newton {
    fn default() -> Self {
        Newton {
            residual_tolerance: 1e-12,
            step_tolerance: 1e-14,
            max_iterations: 50,
            reuse_jacobian: true,
            contraction: 0.25,
            line_search: false,
        }
    }
}

/// Statistics of a converged Newton solve.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NewtonInfo {
    /// Iterations (linear solves) performed.
    pub iterations: usize,
    /// Jacobian evaluations (factorizations).
    pub jacobians: usize,
    /// Final residual norm ‖F‖∞.
    pub residual: f64,
}

impl Newton {
    /// Sets the residual tolerance (default 1e-12): converged when ‖F(x)‖∞ ≤ this after a correction.
    /// Finite and positive, else [`Error::InvalidParameter`].
    pub fn residual_tolerance(mut self, tol: f64) -> Result<Self> {
        self.residual_tolerance = check_positive("Newton residual_tolerance", tol)?;
        Ok(self)
    }
    /// Sets the step tolerance (default 1e-14): converged when a correction Δ, or the estimated
    /// distance θ/(1 − θ)‖Δ‖ to the root, satisfies ‖·‖∞ ≤ this · (1 + ‖x‖∞) (near the machine
    /// precision for a solve to rounding). Finite and positive, else [`Error::InvalidParameter`].
    pub fn step_tolerance(mut self, tol: f64) -> Result<Self> {
        self.step_tolerance = check_positive("Newton step_tolerance", tol)?;
        Ok(self)
    }
    /// Sets the iteration cap (default 50): at least 1, else [`Error::InvalidParameter`].
    pub fn max_iterations(mut self, n: usize) -> Result<Self> {
        self.max_iterations = crate::error::check_iteration_cap("Newton max_iterations", n)?;
        Ok(self)
    }
    /// Sets the contraction factor (default 0.25) that ‖F‖ must show per iteration for a Jacobian
    /// factor to be kept: in (0, 1), else [`Error::InvalidParameter`].
    pub fn contraction(mut self, factor: f64) -> Result<Self> {
        self.contraction = check_contraction(factor)?;
        Ok(self)
    }
    /// Enables (default) or disables the reuse of the last Jacobian factor while ‖F‖ contracts.
    pub fn reuse_jacobian(mut self, reuse: bool) -> Self {
        self.reuse_jacobian = reuse;
        self
    }
    /// Enables or disables (default) the backtracking line search on ½‖F‖₂² (see the type's
    /// documentation); with it every correction uses a fresh Jacobian.
    pub fn line_search(mut self, on: bool) -> Self {
        self.line_search = on;
        self
    }
    /// The settings with the residual tolerance raised to at least `floor` (what the caller knows
    /// rounding allows for its residual, e.g. a few ε times its scale); a `floor` that is not finite
    /// and positive changes nothing.
    pub fn residual_floor(mut self, floor: f64) -> Self {
        if floor.is_finite() && floor > 0.0 {
            self.residual_tolerance = self.residual_tolerance.max(floor);
        }
        self
    }
    /// The settings with both tolerances multiplied by `factor` (finite and positive, else
    /// unchanged): the tolerances of a residual measured in units `factor` times larger.
    pub(crate) fn scaled(mut self, factor: f64) -> Self {
        if factor.is_finite() && factor > 0.0 {
            self.residual_tolerance *= factor;
            self.step_tolerance *= factor;
        }
        self
    }

    /// The residual tolerance.
    pub fn get_residual_tolerance(&self) -> f64 {
        self.residual_tolerance
    }
    /// The step tolerance.
    pub fn get_step_tolerance(&self) -> f64 {
        self.step_tolerance
    }
    /// The iteration cap.
    pub fn get_max_iterations(&self) -> usize {
        self.max_iterations
    }
    /// Whether a Jacobian factor is reused while ‖F‖ contracts.
    pub fn get_reuse_jacobian(&self) -> bool {
        self.reuse_jacobian
    }
    /// The contraction factor required to keep a Jacobian factor.
    pub fn get_contraction(&self) -> f64 {
        self.contraction
    }
    /// Whether corrections are shortened by the line search.
    pub fn get_line_search(&self) -> bool {
        self.line_search
    }

    /// Solves `sys` starting from `x` (overwritten by the solution). On failure `x` holds the last
    /// iterate and the error carries the iteration count and the last residual norm.
    pub fn solve<S: NewtonSystem + ?Sized>(&self, sys: &mut S, x: &mut [f64]) -> Result<NewtonInfo> {
        self.solve_reusing(sys, x, false)
    }

    /// As [`solve`](Self::solve); when `factored` (and [`reuse_jacobian`](Self::reuse_jacobian) is on)
    /// the system already holds a Jacobian factor from an earlier solve (say the last time step) and the
    /// first iterations use it, until the residual fails to contract by `contraction` (then the
    /// Jacobian is refreshed at the current iterate, as in `solve`). The last residual evaluated is
    /// always the one at the returned iterate.
    pub fn solve_reusing<S: NewtonSystem + ?Sized>(
        &self,
        sys: &mut S,
        x: &mut [f64],
        factored: bool,
    ) -> Result<NewtonInfo> {
        let n = sys.dim();
        crate::error::check_len("Newton initial guess", x, n)?;
        let mut r = vec![0.0; n];
        let mut dx = vec![0.0; n];
        let mut info = NewtonInfo::default();
        sys.residual(x, &mut r)?;
        let mut rnorm = max_norm(&r);
        if !rnorm.is_finite() {
            return Err(non_finite_residual());
        }
        if rnorm == 0.0 {
            // Exactly on the root: every correction would be exactly zero.
            return Ok(info);
        }
        let reuse = self.reuse_jacobian && !self.line_search;
        let mut factored = factored && reuse;
        let mut keep = factored;
        let mut merit = half_squared(&r);
        // ‖Δ‖∞ of the last correction.
        let mut last_step: Option<f64> = None;
        loop {
            if info.iterations >= self.max_iterations {
                return Err(self.diverged(info.iterations, rnorm));
            }
            // The factor used for this correction was computed at the iterate it is applied to.
            let exact = !factored || !reuse || !keep;
            if exact {
                sys.factor_jacobian(x)?;
                info.jacobians += 1;
                factored = true;
            }
            dx.copy_from_slice(&r);
            sys.solve(&mut dx)?;
            for (xi, di) in x.iter_mut().zip(&dx) {
                *xi -= di;
            }
            info.iterations += 1;
            let search = self.line_search && rnorm > self.residual_tolerance.sqrt();
            let new_norm = match shorten(sys, x, &mut dx, &mut r, search.then_some(merit))? {
                Some(norm) => norm,
                None => return Err(self.diverged(info.iterations, rnorm)),
            };
            merit = half_squared(&r);
            // Keep the factor only while it contracts the residual well.
            keep = new_norm <= self.contraction * rnorm;
            rnorm = new_norm;
            info.residual = rnorm;
            let step = max_norm(&dx);
            let scale = 1.0 + max_norm(x);
            let small_residual = rnorm <= self.residual_tolerance.sqrt();
            // 1. and 2. of the stopping rule.
            if rnorm <= self.residual_tolerance || (step <= self.step_tolerance * scale && small_residual) {
                return Ok(info);
            }
            if let Some(previous) = last_step {
                let theta = step / previous;
                // 3. Stalled at the rounding floor under an exact Jacobian.
                if theta >= 1.0 && exact && small_residual && step <= self.step_tolerance.sqrt() * scale {
                    return Ok(info);
                }
            }
            last_step = Some(step);
        }
    }

    fn diverged(&self, iterations: usize, residual: f64) -> Error {
        debug_assert!(residual.is_finite());
        Error::NewtonDiverged {
            iterations,
            residual,
            tolerance: self.residual_tolerance,
            t: f64::NAN,
        }
    }
}

/// After the correction x ← x − Δ (`dx` = Δ): the residual there into `r` and its max-norm. A step that
/// leaves the model's domain (non-finite residual, e.g. a speed above c in a relativistic Lagrangian)
/// is halved back toward the last iterate, up to 40 times; with the line search (`merit` = φ at the
/// last iterate: near the root, ‖F‖∞ ≤ √tolerance, the caller passes none, as the full step is
/// Newton's local quadratic one and the merit may sit at its rounding floor) so is one that does not
/// meet Armijo's condition with α = 2^−halvings. `None` when the line search finds no decrease (a
/// local minimum of ‖F‖, not a root): `x` is then back at the last iterate. On return `dx` is the
/// correction taken.
fn shorten<S: NewtonSystem + ?Sized>(
    sys: &mut S,
    x: &mut [f64],
    dx: &mut [f64],
    r: &mut [f64],
    merit: Option<f64>,
) -> Result<Option<f64>> {
    sys.residual(x, r)?;
    let mut norm = max_norm(r);
    let decreased = |r: &[f64], halvings: i32| {
        merit.is_none_or(|m| half_squared(r) <= (1.0 - 2.0 * ARMIJO * 0.5f64.powi(halvings)) * m)
    };
    let mut halvings = 0;
    while (!norm.is_finite() && halvings < 40)
        || (norm.is_finite() && !decreased(r, halvings) && halvings < LINE_SEARCH_HALVINGS)
    {
        halvings += 1;
        for (xi, di) in x.iter_mut().zip(dx.iter_mut()) {
            *di *= 0.5;
            *xi += *di;
        }
        sys.residual(x, r)?;
        norm = max_norm(r);
    }
    if !norm.is_finite() {
        return Err(non_finite_residual());
    }
    if !decreased(r, halvings) {
        for (xi, di) in x.iter_mut().zip(dx.iter()) {
            *xi += di;
        }
        return Ok(None);
    }
    Ok(Some(norm))
}

/// Armijo's sufficient-decrease constant of the line search.
const ARMIJO: f64 = 1e-4;
/// The line search's halvings before it gives up (α = 2⁻³⁰).
const LINE_SEARCH_HALVINGS: i32 = 30;

/// ½‖r‖₂², the merit of the line search.
fn half_squared(r: &[f64]) -> f64 {
    0.5 * r.iter().map(|x| x * x).sum::<f64>()
}

/// The error of a residual that is NaN or infinite (at the guess, or after a correction halved 40
/// times back toward the last iterate): the model left its domain, which is not a divergence of
/// Newton's method. `t` is NaN here; a caller that knows the time sets it with
/// [`Error::at_time`].
fn non_finite_residual() -> Error {
    Error::NonFiniteResult {
        what: "Newton residual",
        t: f64::NAN,
        component: None,
    }
}

fn check_contraction(factor: f64) -> Result<f64> {
    if factor > 0.0 && factor < 1.0 {
        Ok(factor)
    } else {
        Err(Error::InvalidParameter {
            name: "Newton contraction",
            value: factor,
            reason: "a Jacobian factor is kept while the residual shrinks by this factor in (0, 1)",
        })
    }
}

/// ‖x‖∞ (NaN-propagating).
pub fn max_norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| {
        if v.is_nan() || m.is_nan() {
            f64::NAN
        } else {
            m.max(v.abs())
        }
    })
}

/// Convenience: solve a dense problem from `x0`, returning the solution and statistics.
pub fn solve_dense<P: DenseProblem>(
    newton: &Newton,
    problem: P,
    x0: &[f64],
) -> Result<(DVector<f64>, NewtonInfo)> {
    let mut sys = Dense::new(problem);
    let mut x = x0.to_vec();
    let info = newton.solve(&mut sys, &mut x)?;
    Ok((DVector::from_vec(x), info))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// F(x) = x² − c.
    struct Square {
        c: f64,
    }

    impl DenseProblem for Square {
        fn dim(&self) -> usize {
            1
        }
        fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()> {
            r[0] = x[0] * x[0] - self.c;
            Ok(())
        }
        fn jacobian(&mut self, x: &[f64], j: &mut DMatrix<f64>) -> Result<()> {
            j[(0, 0)] = 2.0 * x[0];
            Ok(())
        }
    }

    /// A factor kept from an earlier solve: reused (no new Jacobian) when it still contracts the
    /// residual, refreshed when it does not; both converge to the root √c (closed form) to rounding.
    #[test]
    fn closed_form_solve_reusing_keeps_or_refreshes_the_factor() {
        // ‖F‖ ≤ 1e-15 puts x within 1e-15/(2√2) of the root, plus rounding (the step tolerance is set
        // below it, so that the residual criterion ends the solves).
        let newton = Newton::default()
            .residual_tolerance(1e-15)
            .unwrap()
            .step_tolerance(1e-16)
            .unwrap();
        let mut sys = Dense::new(Square { c: 2.0 });
        let mut x = [1.5];
        let first = newton.solve(&mut sys, &mut x).unwrap();
        assert!(first.jacobians >= 1);
        assert!((x[0] - 2f64.sqrt()).abs() < 1e-15);
        // A nearby problem: the old factor 2·x (last refreshed near √2) contracts by ~|1 − x/√c| ≪ ¼.
        sys.problem.c = 2.0001;
        let info = newton.solve_reusing(&mut sys, &mut x, true).unwrap();
        assert_eq!(info.jacobians, 0, "{info:?}");
        assert!((x[0] - 2.0001f64.sqrt()).abs() < 1e-15);
        // A far one: the stale slope (≈ 2.8 against 20) overshoots, the residual does not contract
        // by ¼, and the Jacobian is refreshed.
        sys.problem.c = 100.0;
        let mut y = [9.0];
        let info = newton.solve_reusing(&mut sys, &mut y, true).unwrap();
        assert!(info.jacobians >= 1, "{info:?}");
        // (Rounding floor of F here: ε·100 ≈ 2e-14; the step criterion ends it, |Δx| ≤ 1.1e-13.)
        assert!((y[0] - 10.0).abs() < 2e-14);
        // Without a kept factor, solve_reusing(.., false) is solve.
        let (mut a, mut b) = ([9.0], [9.0]);
        let i1 = newton.solve_reusing(&mut sys, &mut a, false).unwrap();
        let i2 = newton.solve(&mut sys, &mut b).unwrap();
        assert_eq!((a, i1), (b, i2));
    }

    /// F(x) = arctan x, root 0. Plain Newton x ← x − (1 + x²) arctan x diverges from |x₀| > 1.3917
    /// (the root of 2|x| = (1 + x²) arctan|x|: each step overshoots to a larger |x| of the other sign);
    /// with the line search the first correction is halved until |arctan| decreases, and it converges.
    struct Arctan;
    impl DenseProblem for Arctan {
        fn dim(&self) -> usize {
            1
        }
        fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()> {
            r[0] = x[0].atan();
            Ok(())
        }
        fn jacobian(&mut self, x: &[f64], j: &mut DMatrix<f64>) -> Result<()> {
            j[(0, 0)] = 1.0 / (1.0 + x[0] * x[0]);
            Ok(())
        }
    }

    /// F(x, y) = (x² + 1 − y, y): ‖F‖₂² = (x² + 1 − y)² + y² has its minimum 1/2 at (0, 1/2), not a
    /// root (the two equations require y = 0 and x² = −1).
    struct NoRoot;
    impl DenseProblem for NoRoot {
        fn dim(&self) -> usize {
            2
        }
        fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()> {
            r[0] = x[0] * x[0] + 1.0 - x[1];
            r[1] = x[1];
            Ok(())
        }
        fn jacobian(&mut self, x: &[f64], j: &mut DMatrix<f64>) -> Result<()> {
            j[(0, 0)] = 2.0 * x[0];
            j[(0, 1)] = -1.0;
            j[(1, 0)] = 0.0;
            j[(1, 1)] = 1.0;
            Ok(())
        }
    }

    #[test]
    fn line_search_rescues_an_overshooting_guess_and_stops_without_a_root() {
        let plain = Newton::default().max_iterations(30).unwrap();
        let guarded = plain.line_search(true);
        // From x₀ = 3 plain Newton runs away (|x| grows every step) until the slope 1/(1 + x²)
        // underflows: a singular Jacobian.
        assert!(matches!(
            solve_dense(&plain, Arctan, &[3.0]),
            Err(Error::SingularMatrix { .. } | Error::NewtonDiverged { .. })
        ));
        let (x, info) = solve_dense(&guarded, Arctan, &[3.0]).unwrap();
        assert!(x[0].abs() < 1e-12, "{x} after {info:?}");
        // No root: the line search ends at a point where the Newton direction gives no decrease,
        // a typed failure well before the cap, not a hang or NaN.
        match solve_dense(&guarded, NoRoot, &[1.0, 0.0]) {
            Err(Error::NewtonDiverged {
                iterations, residual, ..
            }) => {
                assert!(iterations < 30 && residual.is_finite(), "{iterations} {residual}");
            }
            Err(Error::SingularMatrix { .. }) => {}
            other => panic!("expected a typed failure, got {other:?}"),
        }
    }
}
