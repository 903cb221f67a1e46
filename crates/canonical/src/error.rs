//! Errors of noether-canonical: the core errors plus what can go wrong on the Hamiltonian side
//! (a transformation that is not canonical, an energy with no bounded orbit, ...).

use thiserror::Error;

/// Result alias of noether-canonical.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong, with the numbers that say how.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// An error of noether-core (dimensions, non-finite input or result, Newton failure).
    #[error(transparent)]
    Core(noether_core::Error),
    // ---- brackets, canonical transformations, generating functions, Hamilton-Jacobi ----

    // ---- action-angle variables, Routh's reduction, Poincaré sections ----
}

noether_core::crate_error_conversions!(Error);
