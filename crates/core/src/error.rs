//! Errors of noether-core: every failure a user can meet, with the data needed to act on it.
//!
//! The crates built on core have error enums of their own (noether-constraints, noether-particles,
//! noether-analysis), each wrapping this one. When one of their errors crosses an interface of core
//! (a [`Dynamics`](crate::Dynamics) model stepped by a core integrator, a [`Driver`](crate::Driver)
//! run) it travels as [`Error::Model`] with all its data, and comes back out with
//! [`Error::downcast_ref`] or the owning crate's `From<noether_core::Error>`.

use std::sync::Arc;
use thiserror::Error;

/// Result alias used throughout noether.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong, with the numbers that say how.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
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
    /// The mass matrix ∂²L/∂q̇² is regular but not positive definite (a negative mass; a kinetic
    /// energy ½ q̇ᵀ M q̇ that is negative for some q̇): Lagrange's equations of
    /// [`EulerLagrange`](crate::EulerLagrange) and the Legendre transform to a Hamiltonian (where
    /// p = ∂L/∂q̇ then need not have one solution q̇) both require L convex in q̇.
    #[error("the mass matrix ∂²L/∂q̇² is not positive definite at t = {t} (smallest eigenvalue {eigenvalue:e} relative to the largest in magnitude): the kinetic energy must be positive for every q̇ ≠ 0; check the signs of the masses and of the kinetic terms of L")]
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
    #[error("Newton did not converge after {iterations} iterations{}: residual norm {residual:e} (tolerance {tolerance:e}); for an implicit step, try a smaller step", at_t(*t))]
    NewtonDiverged {
        /// Iterations performed.
        iterations: usize,
        /// Last residual norm (max-norm).
        residual: f64,
        /// Requested tolerance.
        tolerance: f64,
        /// Time of the step or evaluation that needed the solve, set by the caller that knows it
        /// ([`Error::at_time`]); NaN otherwise.
        t: f64,
    },
    /// A model or a step produced NaN or infinity (a quantity that should be finite, at time `t`).
    /// Model-level code and single steps report this; a [`Driver`](crate::Driver) turns it into
    /// [`NonFiniteState`](Self::NonFiniteState) with the step index.
    #[error("the model gave NaN or ±∞ for its {what}{}{}: check the model's parameters, and that the state is inside the model's domain", component_of(*component), at_t(*t))]
    NonFiniteResult {
        /// The quantity that came out non-finite ("accelerations", "energy", "state after the step", ...).
        what: &'static str,
        /// Time of the evaluation (the start of the step); NaN for a quantity computed without a time
        /// (a kinetic or potential energy of a model that does not depend on t).
        t: f64,
        /// The first component of `what` that is not finite, when it is a vector and known.
        component: Option<usize>,
    },
    /// A run produced NaN or infinity: [`NonFiniteResult`](Self::NonFiniteResult) with the step index
    /// added by the driver.
    #[error("the model gave NaN or ±∞ for its {what}{} at step {step}, t = {t}: check the model's parameters, and that the state is inside the model's domain", component_of(*component))]
    NonFiniteState {
        /// The quantity that came out non-finite.
        what: &'static str,
        /// Index of the failing step in the run (0 for the first).
        step: usize,
        /// Time at the start of the failing step.
        t: f64,
        /// The first component of `what` that is not finite, when known.
        component: Option<usize>,
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
    /// A name that the run does not know: an observer or an event asked of a
    /// [`Solution`](crate::Solution) by a name that was never registered (a typo). Lists the names the
    /// run recorded.
    #[error("no {kind} named {name:?}; the run recorded: {}", quoted_list(known))]
    UnknownName {
        /// What was looked up: "observer" or "event".
        kind: &'static str,
        /// The name asked for.
        name: String,
        /// The names of that kind the run recorded, in registration order.
        known: Vec<String>,
    },
    /// A method was asked to do what it cannot (e.g. an explicit symplectic method on a non-separable system).
    #[error("unsupported: {0}")]
    Unsupported(&'static str),
    /// A coordinate chart became singular (e.g. Euler angles near θ = 0 or π).
    #[error("coordinate singularity: {what} at t = {t}")]
    CoordinateSingularity {
        /// Description.
        what: String,
        /// Time.
        t: f64,
    },
    /// An error of a crate built on core (noether-constraints, noether-particles, a user's model)
    /// carried through core's interfaces with its data; see [`Error::downcast_ref`].
    #[error(transparent)]
    Model(ModelError),
}

impl Error {
    /// Wraps the error of a crate built on core, to pass it through core's interfaces
    /// ([`Dynamics`](crate::Dynamics), [`Stepper`](crate::Stepper), [`Driver`](crate::Driver)).
    pub fn model<E: std::error::Error + Send + Sync + 'static>(error: E) -> Self {
        Error::Model(ModelError(Arc::new(error)))
    }

    /// This error with the time of a [`Error::NonFiniteResult`] or an [`Error::NewtonDiverged`] set
    /// to `t` (a model evaluated by a function without time, or a Newton solve, reports NaN there; the
    /// integrator calling it knows t). Other errors unchanged.
    pub fn at_time(self, t: f64) -> Self {
        match self {
            Error::NonFiniteResult { what, component, .. } => Error::NonFiniteResult { what, t, component },
            Error::NewtonDiverged {
                iterations,
                residual,
                tolerance,
                ..
            } => Error::NewtonDiverged {
                iterations,
                residual,
                tolerance,
                t,
            },
            other => other,
        }
    }

    /// The error of type `E` carried by [`Error::Model`], if this is one.
    ///
    /// ```
    /// # use noether_core::Error;
    /// #[derive(Debug, thiserror::Error, PartialEq)]
    /// #[error("rod {0} broke")]
    /// struct Broken(usize);
    /// let e = Error::model(Broken(3));
    /// assert_eq!(e.downcast_ref::<Broken>(), Some(&Broken(3)));
    /// assert_eq!(e.to_string(), "rod 3 broke");
    /// ```
    pub fn downcast_ref<E: std::error::Error + 'static>(&self) -> Option<&E> {
        match self {
            Error::Model(m) => m.0.downcast_ref::<E>(),
            _ => None,
        }
    }
}

/// The two conversions between core's [`Error`](enum@Error) and the error enum of a crate built on core, which
/// must be `Clone + std::error::Error + Send + Sync + 'static` and have a variant `Core(noether_core::Error)`:
/// into core's, the crate's own errors travel as [`Error::Model`] and core's pass through; back from
/// core's, the crate's own come out whole (by [`Error::downcast_ref`]) and the others as `Core`.
///
/// ```
/// #[derive(Debug, Clone, PartialEq, thiserror::Error)]
/// enum Error {
///     #[error("rod {0} broke")]
///     Broken(usize),
///     #[error(transparent)]
///     Core(noether_core::Error),
/// }
/// noether_core::crate_error_conversions!(Error);
///
/// let through_core = noether_core::Error::from(Error::Broken(3));
/// assert_eq!(Error::from(through_core), Error::Broken(3));
/// ```
#[macro_export]
macro_rules! crate_error_conversions {
    ($error:ident) => {
        impl From<$crate::Error> for $error {
            /// Core's error, or this crate's own when it comes back through core's interfaces.
            fn from(e: $crate::Error) -> Self {
                match e.downcast_ref::<$error>() {
                    Some(own) => own.clone(),
                    None => $error::Core(e),
                }
            }
        }

        impl From<$error> for $crate::Error {
            /// This crate's errors seen through core's interfaces: core's pass through, the others
            /// travel as [`Error::Model`](noether_core::Error::Model) with their data.
            fn from(e: $error) -> Self {
                match e {
                    $error::Core(c) => c,
                    own => $crate::Error::model(own),
                }
            }
        }
    };
}

/// The error of a crate built on core inside [`Error::Model`]: shared, so that [`Error`](enum@Error) stays
/// `Clone`; two are equal when they are the same error or print the same.
#[derive(Debug, Clone)]
pub struct ModelError(Arc<dyn std::error::Error + Send + Sync + 'static>);

impl ModelError {
    /// The wrapped error.
    pub fn get(&self) -> &(dyn std::error::Error + Send + Sync + 'static) {
        &*self.0
    }
}

impl std::fmt::Display for ModelError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl std::error::Error for ModelError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.0.source()
    }
}

impl PartialEq for ModelError {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0) || self.0.to_string() == other.0.to_string()
    }
}

/// ` at t = 0.5` for a known time, nothing for NaN (a quantity computed without one).
fn at_t(t: f64) -> String {
    if t.is_nan() {
        String::new()
    } else {
        format!(" at t = {t}")
    }
}

/// ` (component 1)` for a known component, nothing otherwise.
fn component_of(component: Option<usize>) -> String {
    component.map(|i| format!(" (component {i})")).unwrap_or_default()
}

/// `"a", "b"` for the names a, b; `(none)` for none.
fn quoted_list(names: &[String]) -> String {
    if names.is_empty() {
        "(none)".into()
    } else {
        names
            .iter()
            .map(|n| format!("{n:?}"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Checks that the matrix `m` is rows × cols: `Dimension` naming the rows when they differ, else
/// the columns.
pub fn check_shape(what: &'static str, m: &nalgebra::DMatrix<f64>, rows: usize, cols: usize) -> Result<()> {
    if m.nrows() == rows && m.ncols() == cols {
        return Ok(());
    }
    let (expected, got) = if m.nrows() != rows {
        (rows, m.nrows())
    } else {
        (cols, m.ncols())
    };
    Err(Error::Dimension { what, expected, got })
}

/// Checks that `x` has length `n`.
#[inline]
pub fn check_len<T>(what: &'static str, x: &[T], n: usize) -> Result<()> {
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
    not_finite(what, x)
}

/// The error of [`check_finite`], out of the way of the fast path.
#[cold]
fn not_finite(what: &'static str, x: &[f64]) -> Result<()> {
    match x.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(Error::NonFinite { what, index }),
        None => Ok(()),
    }
}

/// The output twin of [`check_finite`]: Ok when every entry of a computed `x` is finite, else
/// [`Error::NonFiniteResult`] naming the quantity `what` at time `t` (NaN for a quantity computed
/// without one) and, for a vector of more than one entry, the first component that is not finite.
#[inline]
pub fn check_result(what: &'static str, t: f64, x: &[f64]) -> Result<()> {
    if x.iter().fold(true, |ok, v| ok & v.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFiniteResult {
            what,
            t,
            component: x.iter().position(|v| !v.is_finite()).filter(|_| x.len() > 1),
        })
    }
}

/// [`check_result`] for one computed value: `x` when it is finite.
#[inline]
pub fn finite_result(what: &'static str, t: f64, x: f64) -> Result<f64> {
    check_result(what, t, &[x]).map(|()| x)
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

/// Checks that a step of size `h` from time `t` moves the time axis by h: Ok when t + h, as rounded,
/// differs from t by h to 1 %,
///
/// ```text
/// t + h ≠ t   and   |(t + h) − t − h| ≤ 0.01 |h|   (in floating point),
/// ```
///
/// else [`Error::StepBelowTimeResolution`] (at t = 1e20 a step of 1e-3 does not move t at all; at
/// t = 1e15 a step of 1e-3 moves it by 0 or 0.125). Every stepper of noether checks its step with
/// it, and so does the [`Driver`](crate::Driver), so a method never integrates over one interval while
/// the state's time records another. A NaN or zero `h` is [`Error::InvalidStep`], a non-finite `t`
/// [`Error::NonFinite`] (so the order of the checks does not matter). `h` may be negative (a
/// backward step); for h > 0 the test is the driver's `t + h <= t || (t + h).is_nan() ||
/// (t + h - t - h).abs() > 0.01 * h`.
#[inline]
pub fn check_time_resolution(t: f64, h: f64) -> Result<()> {
    if !h.is_finite() || h == 0.0 {
        return Err(Error::InvalidStep { h });
    }
    if !t.is_finite() {
        return Err(Error::NonFinite { what: "t", index: 0 });
    }
    let end = t + h;
    // Written so that a NaN fails: both comparisons are false for NaN.
    if end != t && (end - t - h).abs() <= 0.01 * h.abs() {
        Ok(())
    } else {
        Err(Error::StepBelowTimeResolution { t, h })
    }
}

/// Checks that an iteration cap allows at least one iteration; returns it.
pub fn check_iteration_cap(name: &'static str, n: usize) -> Result<usize> {
    if n == 0 {
        return Err(Error::InvalidParameter {
            name,
            value: 0.0,
            reason: "at least one iteration is needed",
        });
    }
    Ok(n)
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
