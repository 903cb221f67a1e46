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
    /// The energy condition h(q, p*(q)) = E (p* the momentum where ∂H/∂p = 0) has no sign change on
    /// one side of the starting point within the search: the orbit is not a libration there.
    #[error(
        "no turning point at energy {energy} on the {side} side of q = {from}: searched to q = {reached}"
    )]
    NoTurningPoint {
        /// The energy E.
        energy: f64,
        /// Where the search started.
        from: f64,
        /// "lower" or "upper".
        side: &'static str,
        /// The farthest point searched.
        reached: f64,
    },
    /// The energy is below the least value of H over p at this q: no real momentum there.
    #[error("energy {energy} is below min over p of H = {minimum} at q = {q}: no real momentum")]
    EnergyBelowMinimum {
        /// The energy E.
        energy: f64,
        /// The coordinate.
        q: f64,
        /// min over p of H(q, p).
        minimum: f64,
    },
    /// H(q, p) = E could not be solved for p at this q (no bracket of a root found).
    #[error("no momentum p with H(q, p) = {energy} at q = {q}")]
    NoMomentum {
        /// The energy E.
        energy: f64,
        /// The coordinate.
        q: f64,
    },
    /// A coordinate declared cyclic is not: ∂L/∂q_c ≠ 0 at a sample point.
    #[error("coordinate {index} is not cyclic: ∂L/∂q = {derivative:e} at t = {t}")]
    NotCyclic {
        /// The coordinate's index.
        index: usize,
        /// Time of the sample point.
        t: f64,
        /// ∂L/∂q_c there.
        derivative: f64,
    },
    /// A quadrature did not settle to its tolerance within the largest number of nodes.
    #[error(
        "quadrature of {what} not converged with {nodes} nodes: last two estimates {previous} and {estimate}"
    )]
    QuadratureNotConverged {
        /// Which integral.
        what: &'static str,
        /// Nodes of the last estimate.
        nodes: usize,
        /// The estimate with half as many nodes.
        previous: f64,
        /// The last estimate.
        estimate: f64,
    },
}

noether_core::crate_error_conversions!(Error);
