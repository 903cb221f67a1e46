//! Errors of noether-compile: a model that cannot be recorded, beside core's errors.
//!
//! Running a compiled model fails exactly as the model it came from does (core's errors, through the
//! system traits); only building one can fail in a way of its own.

/// Result alias with this crate's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What can keep a model from being compiled, with its data; core's failures as [`Error::Core`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The model used a value in a way a recorded graph cannot follow: it read the value of a
    /// traced number (`re()`), compared with NaN, or called a function with no derivative rule on the
    /// graph (the remainder, the spherical Bessel functions). Comparisons themselves are fine (they
    /// are guarded); run this model with dual numbers, or write the branch with comparisons of the
    /// scalar instead of its value.
    #[error("the model cannot be compiled: it used {operation} while it was recorded; run it with dual numbers (without compiling), or compare scalars instead of reading their values")]
    Refused {
        /// The operation.
        operation: &'static str,
    },
    /// The Lagrangian is not quadratic in the velocities (its mass matrix ∂²L/∂q̇² depends on q̇), or
    /// it compares q̇: its Legendre transform has no closed form on the graph. `LegendreTransform`
    /// (Newton's method at every call) handles any L convex in q̇.
    #[error("the Lagrangian is not quadratic in the velocities (or compares them): compile its Euler-Lagrange equations, or use LegendreTransform for its Hamiltonian")]
    NotQuadratic,
    /// An error of noether-core (dimensions, non-finite numbers).
    #[error(transparent)]
    Core(noether_core::Error),
}

noether_core::crate_error_conversions!(Error);
