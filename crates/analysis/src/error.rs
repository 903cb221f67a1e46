//! Errors of noether-analysis: the core errors plus what can go wrong when looking for equilibria and
//! small oscillations.

use thiserror::Error;

/// Result alias of noether-analysis.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong, with the numbers that say how.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// An error of noether-core (dimensions, non-finite input, singular mass matrix, Newton failure).
    #[error(transparent)]
    Core(noether_core::Error),
    /// Normal modes or a linearisation were asked about a point where the generalized force does not vanish.
    #[error(
        "not an equilibrium: the gradient of the effective potential has max-norm {gradient_norm:e}, \
         above the tolerance {tolerance:e} (find the equilibrium first, e.g. with `minimize` or `stationary_point`)"
    )]
    NotEquilibrium {
        /// ‖∇U(q)‖∞ at the point supplied.
        gradient_norm: f64,
        /// The tolerance it was compared with.
        tolerance: f64,
    },
    /// The minimiser stopped before the gradient became small enough.
    #[error("minimisation did not converge after {iterations} iterations: ‖∇V‖∞ = {gradient_norm:e} (tolerance {tolerance:e})")]
    NotConverged {
        /// Iterations performed.
        iterations: u64,
        /// Final ‖∇V‖∞.
        gradient_norm: f64,
        /// Requested tolerance.
        tolerance: f64,
    },
    /// The minimiser stopped at a stationary point that is not a minimum (it was started exactly on a
    /// maximum or a saddle, where the gradient vanishes and no descent direction is taken).
    #[error("the minimiser stopped at a {kind:?}, not a minimum, at q = {point:?} (start elsewhere, or use stationary_point to find any kind)")]
    NotMinimum {
        /// What the point is.
        kind: crate::Kind,
        /// Where.
        point: Vec<f64>,
    },
    /// The optimiser (argmin) reported an error.
    #[error("optimiser failed: {0}")]
    Optimizer(String),
    /// The Lagrangian has gyroscopic (velocity-coupling) terms at the equilibrium: the symmetric normal
    /// mode problem does not apply; use [`linear_stability`](crate::linear_stability).
    #[error(
        "gyroscopic terms ∂²L/∂q̇∂q − (∂²L/∂q̇∂q)ᵀ of max-norm {norm:e} at the equilibrium: normal modes of \
         K x = ω² M x do not describe this system, use linear_stability"
    )]
    Gyroscopic {
        /// Max-norm of the antisymmetric part.
        norm: f64,
    },
    /// The Riccati equation of an LQR design has no stabilising solution: (A, B) is not stabilisable or
    /// (Q, A) not detectable (the Hamiltonian matrix has eigenvalues on the imaginary axis).
    #[error(
        "no stabilising solution of the Riccati equation (relative residual {residual:e}, largest real part of the closed loop's eigenvalues, of their logarithms for a discrete design: {largest_real_part:e}): is (A, B) stabilisable and (Q, A) detectable?"
    )]
    NoStabilizingSolution {
        /// The relative residual of the best solution found (∞ when the sign iteration failed).
        residual: f64,
        /// The largest real part of the eigenvalues λ of A − BK, for the discrete equation of
        /// [`dlqr`](crate::dlqr) of ln λ (ln |λ|: negative when stable in both cases); NaN when no
        /// gain was formed.
        largest_real_part: f64,
    },
    /// An eigenvalue iteration did not converge.
    #[error("eigenvalue computation did not converge for {what}")]
    Eigen {
        /// Which matrix.
        what: &'static str,
    },

    // ---- periodic orbits (periodic.rs) ----
    /// A period that is not finite and positive (a guess, or where Newton drove it).
    #[error("invalid period T = {period}: it must be finite and positive (a better guess of the period, or more steps per period)")]
    InvalidPeriod {
        /// The period.
        period: f64,
    },
    /// The guess, or the point Newton converged to, is an equilibrium (a rest point is a trivial
    /// solution of the periodicity equations for any period).
    #[error(
        "equilibrium instead of a periodic orbit (‖F(y)‖∞ = {rate_norm:e}): start on the orbit, and declare the \
         first integrals (energy) of a conservative system"
    )]
    Equilibrium {
        /// ‖F(y)‖∞ at the guess or the converged point.
        rate_norm: f64,
    },
    /// The declared first integrals, symmetries and period do not give as many equations as unknowns.
    #[error(
        "shooting set-up has {unknowns} unknowns (y₀, T unless fixed, one unfolding parameter per first integral) \
         but {equations} equations (periodicity, phase, one per fixed level and per symmetry): each first \
         integral pairs with a fixed level, a symmetry or the fixed period"
    )]
    ShootingSetup {
        /// Number of unknowns.
        unknowns: usize,
        /// Number of equations.
        equations: usize,
    },
    /// The shooting Jacobian is singular at an iterate.
    #[error(
        "singular shooting Jacobian (smallest pivot {pivot_ratio:e} relative to its scale): a first integral or \
         symmetry not declared, a degenerate orbit (a non-trivial multiplier at 1), or a guess too far off"
    )]
    DegenerateOrbit {
        /// Smallest pivot relative to the scale of the Jacobian.
        pivot_ratio: f64,
    },
    /// Newton did not find a periodic orbit.
    #[error("no periodic orbit found: Newton stopped after {iterations} iterations with residual {residual:e} (tolerance {tolerance:e}); try a closer guess")]
    ShootingDiverged {
        /// Iterations performed.
        iterations: usize,
        /// Last residual max-norm.
        residual: f64,
        /// Requested tolerance.
        tolerance: f64,
    },
    // ---- end periodic orbits ----
    // --- Lyapunov spectra and sensitivities (issue 19, helper B1) ---
    /// The number of tangent vectors asked for is not between 1 and the phase-space dimension 2n.
    #[error("{requested} tangent vectors asked for: a Lyapunov spectrum takes 1 to {dimension} (the phase-space dimension 2n)")]
    TangentVectors {
        /// Vectors asked for.
        requested: usize,
        /// The phase-space dimension 2n.
        dimension: usize,
    },
    /// The re-orthonormalisation interval m is zero.
    #[error("re-orthonormalisation every {every} steps: the interval must be at least one step")]
    ReorthonormalizationInterval {
        /// The interval asked for.
        every: usize,
    },
    /// A diagonal entry R_ii of the QR factorisation of the tangent vectors is not finite, or below 1e-10
    /// times the largest vector: the vectors overflowed or collapsed onto each other (to rounding)
    /// between two re-orthonormalisations, or were given dependent.
    #[error(
        "tangent vector {index} collapsed at t = {t}: |R_ii| = {r:e} in the QR factorisation \
         (re-orthonormalise more often, or take a smaller step)"
    )]
    TangentCollapse {
        /// Time of the re-orthonormalisation.
        t: f64,
        /// Which vector (0-based).
        index: usize,
        /// The offending diagonal entry of R.
        r: f64,
    },
    /// The run is too short for the statistics asked of it.
    #[error("{reorthonormalizations} re-orthonormalisations recorded: too few to split into {blocks} blocks (run longer or ask for fewer blocks, at least 2)")]
    TooShort {
        /// Re-orthonormalisations recorded so far.
        reorthonormalizations: usize,
        /// Blocks asked for.
        blocks: usize,
    },

    // ---- chaos indicators (chaos.rs) ----
    /// The deviation of a MEGNO run is no longer a finite, nonzero vector after a step (the step's
    /// Jacobian overflowed, or was given a zero deviation).
    #[error(
        "the deviation was lost at t = {t}: its length after the step is {growth:e} (a step too large for \
         the orbit, or an orbit running off to infinity)"
    )]
    DeviationLost {
        /// Time of the step.
        t: f64,
        /// |Ψδ| (or |δ| given).
        growth: f64,
    },
    /// A continuation could not follow its family: the corrector failed with the arclength step below
    /// its floor.
    #[error("the family was lost at level {level}: no orbit with the arclength step {step:e} above its floor (last failure: {reason})")]
    BranchLost {
        /// The level of the last orbit found.
        level: f64,
        /// The step that failed.
        step: f64,
        /// The corrector's last error.
        reason: String,
    },
    /// A stability map where no grid point has an orbit.
    #[error(
        "none of the {members} grid points has an orbit (the grid misses the energy surface, or is empty)"
    )]
    NoValidMember {
        /// Number of grid points.
        members: usize,
    },
}

noether_core::crate_error_conversions!(Error);
