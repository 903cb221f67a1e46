//! Errors of noether-constraints: states off the constraint manifold and constraint sets without full
//! rank, plus core's errors.
//!
//! Through core's interfaces (a [`Constrained`](crate::Constrained) system stepped by a core
//! integrator, a [`Rattle`](crate::Rattle) run by a [`Driver`](noether_core::Driver)) these travel as
//! [`noether_core::Error::Model`]; `Error::from(core_error)` gives them back with their data.

use thiserror::Error;

/// Result alias of noether-constraints.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong with a constrained system, with the numbers that say how.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
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
    /// redundant (or the constraint set is singular at this point) and their multipliers are not
    /// determined.
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
    /// An error of noether-core (dimensions, non-finite input, singular matrices, Newton failures).
    #[error(transparent)]
    Core(noether_core::Error),
}

noether_core::crate_error_conversions!(Error);

#[cfg(test)]
mod tests {
    use super::*;

    /// An error of this crate survives the trip through core's error type with all its data.
    #[test]
    fn error_round_trip_through_core() {
        let e = Error::RankDeficientConstraints {
            t: 1.5,
            rank: 1,
            count: 2,
            sigma_ratio: 1e-17,
        };
        let core = noether_core::Error::from(e.clone());
        assert!(matches!(core, noether_core::Error::Model(_)));
        assert_eq!(core.to_string(), e.to_string());
        assert_eq!(Error::from(core), e);
        let plain = noether_core::Error::InvalidStep { h: -1.0 };
        assert_eq!(Error::from(plain.clone()), Error::Core(plain));
    }
}
