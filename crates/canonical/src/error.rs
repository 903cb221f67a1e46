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
    /// Two functions (a bracket's f and g, a function and a Hamiltonian, a map and a Hamiltonian) are
    /// defined on phase spaces of different dimensions.
    #[error("phase-space mismatch: {first} degrees of freedom against {second}")]
    PhaseSpaceMismatch {
        /// Degrees of freedom of the first function.
        first: usize,
        /// Degrees of freedom of the second.
        second: usize,
    },
    /// A check over sampled points was given no sample (its worst case would be meaningless).
    #[error("no sample points were given")]
    NoSamples,
    /// A generating function whose mixed Hessian ∂²F/∂x∂X (old against new variables) is singular
    /// where the transformation is asked for: it generates no transformation there.
    #[error(
        "generating function {kind} is degenerate at t = {t}: det ∂²F/∂x∂X = 0 (pivot ratio {pivot_ratio:e})"
    )]
    DegenerateGenerator {
        /// Its kind ("F1", "F2", "F3", "F4").
        kind: &'static str,
        /// Time of the evaluation.
        t: f64,
        /// Smallest pivot of the mixed Hessian relative to its scale (NaN for a non-finite Hessian).
        pivot_ratio: f64,
    },
    /// A complete integral S(q, α, t) whose mixed Hessian ∂²S/∂q∂α is singular at the point asked
    /// for: Jacobi's theorem cannot be solved for q (or α) there (a turning point, a bad α).
    #[error("complete integral is degenerate at t = {t}: det ∂²S/∂q∂α = 0 (pivot ratio {pivot_ratio:e})")]
    DegenerateCompleteIntegral {
        /// Time of the evaluation.
        t: f64,
        /// Smallest pivot of ∂²S/∂q∂α relative to its scale (NaN for a non-finite Hessian).
        pivot_ratio: f64,
    },
    // ---- action-angle variables, Routh's reduction, Poincaré sections ----

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
    /// A coordinate declared cyclic is not: ∂L/∂q_c ≠ 0, or a generalized force Q_c ≠ 0 acts on it,
    /// at a sample point (either makes its momentum change).
    #[error("coordinate {index} is not cyclic: {what} = {value:e} at t = {t}")]
    NotCyclic {
        /// The coordinate's index.
        index: usize,
        /// Time of the sample point.
        t: f64,
        /// What is not zero: "∂L/∂q" or "Q".
        what: &'static str,
        /// Its value there.
        value: f64,
    },
    /// The quadrature of an orbit gave a period that is not finite and positive, or an action that is
    /// not finite: the orbit is beyond what f64 resolves (turning points or momenta that underflow or
    /// overflow). Never returned as an `Ok` with ω = ∞ or T = 0.
    #[error("degenerate orbit at energy {energy}: period {period}, action {action}")]
    DegenerateOrbit {
        /// The energy E.
        energy: f64,
        /// The period T computed (|T| for a rotation).
        period: f64,
        /// The action J computed.
        action: f64,
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
