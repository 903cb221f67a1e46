//! Errors of noether-core: every failure a user can meet, with the data needed to act on it.

use thiserror::Error;

/// Result alias used throughout noether.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong, with the numbers that say how.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Error {
    /// A vector had the wrong length.
    #[error("dimension mismatch in {what}: expected {expected}, got {got}")]
    Dimension {
        /// Which argument.
        what: &'static str,
        /// Length expected by the model.
        expected: usize,
        /// Length supplied.
        got: usize,
    },
    /// A NaN or infinite value was supplied where a finite one is required.
    #[error("{what} is not finite (NaN or infinite) at component {index}")]
    NonFinite {
        /// Which argument.
        what: &'static str,
        /// First offending component.
        index: usize,
    },
    /// A time step that is zero, negative or not finite.
    #[error("invalid step size h = {h}: it must be finite and positive")]
    InvalidStep {
        /// The step supplied.
        h: f64,
    },
    /// An invalid parameter of a model, a method or a solver.
    #[error("invalid parameter {name} = {value}: {reason}")]
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// The mass matrix ∂²L/∂q̇² is singular: the Lagrangian is degenerate and q̈ is not determined.
    #[error("singular mass matrix ∂²L/∂q̇² (degenerate Lagrangian) at t = {t}: smallest pivot {pivot_ratio:e} relative to the scale of M")]
    SingularMassMatrix {
        /// Time at which it was found.
        t: f64,
        /// Smallest pivot relative to the scale of M ([`linalg::pivot_ratio`](crate::linalg::pivot_ratio);
        /// at most [`SINGULAR_PIVOT`](crate::linalg::SINGULAR_PIVOT)).
        pivot_ratio: f64,
    },
    /// The mass matrix ∂²L/∂q̇² is regular but not positive definite where a Lagrangian convex in q̇
    /// is required (the Legendre transform to a Hamiltonian: p = ∂L/∂q̇ then need not have one
    /// solution q̇).
    #[error("mass matrix ∂²L/∂q̇² is not positive definite at t = {t} (smallest eigenvalue {eigenvalue:e} relative to the largest in magnitude): the Legendre transform needs L convex in q̇")]
    IndefiniteMassMatrix {
        /// Time at which it was found.
        t: f64,
        /// Smallest eigenvalue relative to the largest in magnitude (negative).
        eigenvalue: f64,
    },
    /// A linear system (Newton Jacobian, constraint matrix) is singular.
    #[error("singular matrix in {what}: smallest pivot {pivot_ratio:e} relative to the scale of the matrix")]
    SingularMatrix {
        /// Which system.
        what: &'static str,
        /// Smallest pivot relative to the scale of the matrix
        /// ([`linalg::pivot_ratio`](crate::linalg::pivot_ratio); at most
        /// [`SINGULAR_PIVOT`](crate::linalg::SINGULAR_PIVOT)); NaN when the matrix had a non-finite entry
        /// or there was no factor to solve with, or for a solver that has no pivots (an
        /// eigen-decomposition that did not converge).
        pivot_ratio: f64,
    },
    /// Newton's method did not converge.
    #[error("Newton did not converge after {iterations} iterations: residual norm {residual:e} (tolerance {tolerance:e})")]
    NewtonDiverged {
        /// Iterations performed.
        iterations: usize,
        /// Last residual norm (max-norm).
        residual: f64,
        /// Requested tolerance.
        tolerance: f64,
    },
    /// The model produced NaN or infinity during a run.
    #[error("the model produced a non-finite value at step {step}, t = {t}")]
    NonFiniteState {
        /// Step index (0 for the first step of a stepper call or driver).
        step: usize,
        /// Time at the start of the failing step.
        t: f64,
    },
    /// Adaptive step-size control gave up.
    #[error("step size underflow at t = {t}: h = {h:e} (error estimate {error:e})")]
    StepSizeUnderflow {
        /// Time reached.
        t: f64,
        /// Step size that became too small.
        h: f64,
        /// Last normalised error estimate.
        error: f64,
    },
    /// A step too small for the time axis: at this t, t + h differs from t by less than h (or not at
    /// all); the run cannot advance with this step.
    #[error(
        "step h = {h:e} is below the resolution of the time axis at t = {t:e} (t + h is not t + h to 1%)"
    )]
    StepBelowTimeResolution {
        /// Time of the state.
        t: f64,
        /// Step asked for.
        h: f64,
    },
    /// A run took the largest number of steps it was allowed ([`Driver::max_steps`](crate::Driver::max_steps)).
    #[error("step limit reached: {steps} steps, at t = {t}")]
    StepLimit {
        /// Steps taken.
        steps: usize,
        /// Time reached.
        t: f64,
    },
    /// A saved run could not be written or read: the file system failed, or the CSV is not a saved
    /// solution (header, column count, a value that is not a number).
    #[error("saved run{}: {reason}", line.map(|l| format!(", line {l}")).unwrap_or_default())]
    SavedRun {
        /// Line of the CSV file where it went wrong, when known (1 = the header).
        line: Option<u64>,
        /// What went wrong.
        reason: String,
    },
    /// A method was asked to do what it cannot (e.g. an explicit symplectic method on a non-separable system).
    #[error("unsupported: {0}")]
    Unsupported(&'static str),
    /// A state violates the constraints it must satisfy (positions φ(t, q) = 0 or velocities
    /// A(t, q) q̇ + a(t, q) = 0); project it onto the constraint manifold first.
    #[error("state violates the {what} constraints at t = {t}: residual {residual:e} > tolerance {tolerance:e} (project the state onto the constraints first)")]
    ConstraintViolated {
        /// "position" or "velocity".
        what: &'static str,
        /// Time of the state.
        t: f64,
        /// Residual norm ‖φ‖∞ (or of the velocity constraints).
        residual: f64,
        /// Largest residual accepted.
        tolerance: f64,
    },
    /// The constraint Jacobian has lower rank than the number of constraints: some constraints are
    /// redundant (or the constraint set is singular at this point) and their multipliers are not determined.
    #[error("redundant or rank-deficient constraints at t = {t}: Jacobian rank {rank} < {count} constraints (smallest singular value {sigma_ratio:e} relative to largest)")]
    RankDeficientConstraints {
        /// Time.
        t: f64,
        /// Numerical rank of the constraint Jacobian.
        rank: usize,
        /// Number of constraints.
        count: usize,
        /// Smallest singular value relative to the largest.
        sigma_ratio: f64,
    },
    /// A coordinate chart became singular (e.g. Euler angles near θ = 0 or π).
    #[error("coordinate singularity: {what} at t = {t}")]
    CoordinateSingularity {
        /// Description.
        what: String,
        /// Time.
        t: f64,
    },
}

/// Checks that `x` has length `n`.
#[inline]
pub fn check_len(what: &'static str, x: &[f64], n: usize) -> Result<()> {
    if x.len() != n {
        return Err(Error::Dimension {
            what,
            expected: n,
            got: x.len(),
        });
    }
    Ok(())
}

/// Checks that every component of `x` is finite.
#[inline]
pub fn check_finite(what: &'static str, x: &[f64]) -> Result<()> {
    // Fast path without an early exit (the loop vectorises); the position only when one fails.
    if x.iter().fold(true, |ok, v| ok & v.is_finite()) {
        return Ok(());
    }
    match x.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(Error::NonFinite { what, index }),
        None => Ok(()),
    }
}

/// Checks a phase point (t, q, v): q and v of length `dof` (q first), then t, q, v finite. `v_name`
/// names the second half in the error ("q̇", "p", "v").
#[inline]
pub fn check_phase_point(dof: usize, t: f64, q: &[f64], v: &[f64], v_name: &'static str) -> Result<()> {
    check_len("q", q, dof)?;
    check_len(v_name, v, dof)?;
    check_finite("t", &[t])?;
    check_finite("q", q)?;
    check_finite(v_name, v)
}

/// Checks that a step size is finite and positive.
pub fn check_step(h: f64) -> Result<()> {
    if h.is_finite() && h > 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidStep { h })
    }
}

/// Checks that a setting (a tolerance, a scale) is finite and positive; returns it.
pub fn check_positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            reason: "must be finite and positive",
        })
    }
}
