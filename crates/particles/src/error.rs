//! Errors of noether-particles: bad systems and singular configurations, plus core's errors.

use thiserror::Error;

/// Result alias of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong in building or evaluating a particle system.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
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
    /// A mass that is zero, negative or not finite, or so small that 1/m overflows.
    #[error("particle {index} has mass {mass:e}: masses must be finite and positive, with a finite 1/m")]
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
    /// A pair interaction that is not finite although the particles are apart: a parameter of the
    /// law is not finite (G = NaN), or the particles are so close that the law overflows.
    #[error("the interaction of particles {a} and {b} is not finite at distance {distance:e} (a parameter of the law is not finite, or the particles are too close)")]
    NonFiniteInteraction {
        /// First particle.
        a: usize,
        /// Second particle.
        b: usize,
        /// Their distance.
        distance: f64,
    },
    /// A quantity that needs at least one particle, asked of an empty system.
    #[error("{what} of a system without particles")]
    Empty {
        /// The quantity asked for.
        what: &'static str,
    },
    /// An error of noether-core (dimensions, non-finite input, step size, ...).
    #[error(transparent)]
    Core(noether_core::Error),
}

noether_core::crate_error_conversions!(Error);

impl Error {
    /// The error for a pair (a, b) at separation `r` whose interaction is not finite: the particles
    /// coincide (distance 0), or the law is not finite there.
    pub(crate) fn pair(a: usize, b: usize, r: crate::Vec3) -> Self {
        let distance = crate::potential::norm(r);
        if distance == 0.0 {
            Error::Coincident { a, b, distance }
        } else {
            Error::NonFiniteInteraction { a, b, distance }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Coincident particles keep their indices through core's error type.
    #[test]
    fn error_round_trip_through_core() {
        let e = Error::Coincident {
            a: 3,
            b: 7,
            distance: 0.0,
        };
        let core = noether_core::Error::from(e.clone());
        assert_eq!(core.downcast_ref::<Error>(), Some(&e));
        assert_eq!(Error::from(core), e);
    }
}
