//! Errors of noether-particles: bad systems and singular configurations, plus core's errors.

use thiserror::Error;

/// Result alias of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong in building or evaluating a particle system.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Error {
    /// An interaction names a particle that does not exist.
    #[error("interaction {interaction} names particle {index}, but the system has {n} particles")]
    UnknownParticle {
        /// Which interaction term (position in its list).
        interaction: usize,
        /// The particle index given.
        index: usize,
        /// Number of particles.
        n: usize,
    },
    /// An internal (two-body) interaction of a particle with itself.
    #[error("internal interaction {interaction} couples particle {index} with itself")]
    SelfInteraction {
        /// Which interaction term.
        interaction: usize,
        /// The particle.
        index: usize,
    },
    /// A mass that is zero, negative or not finite.
    #[error("particle {index} has mass {mass}: masses must be finite and positive")]
    InvalidMass {
        /// The particle.
        index: usize,
        /// Its mass.
        mass: f64,
    },
    /// Two particles at the same position under a potential that is singular there (gravity, LJ, ...).
    #[error("particles {a} and {b} coincide (|r21| = {distance:e}) under a potential singular at r = 0")]
    Coincident {
        /// First particle.
        a: usize,
        /// Second particle.
        b: usize,
        /// Their distance.
        distance: f64,
    },
    /// An error of noether-core (dimensions, non-finite input, step size, ...).
    #[error(transparent)]
    Core(#[from] noether_core::Error),
}

impl From<Error> for noether_core::Error {
    /// Particle errors seen through core's [`Dynamics`](noether_core::Dynamics) interface: core errors
    /// pass through, the others become `InvalidParameter`/`NonFiniteState` with the numbers kept.
    fn from(e: Error) -> Self {
        match e {
            Error::Core(c) => c,
            Error::InvalidMass { mass, .. } => noether_core::Error::InvalidParameter {
                name: "mass",
                value: mass,
                reason: "masses must be finite and positive",
            },
            Error::Coincident { distance, .. } => noether_core::Error::InvalidParameter {
                name: "|r21|",
                value: distance,
                reason: "two particles coincide under a potential singular at r = 0",
            },
            Error::UnknownParticle { index, .. } => noether_core::Error::InvalidParameter {
                name: "particle index",
                value: index as f64,
                reason: "no such particle",
            },
            Error::SelfInteraction { index, .. } => noether_core::Error::InvalidParameter {
                name: "particle index",
                value: index as f64,
                reason: "internal interaction of a particle with itself",
            },
        }
    }
}
