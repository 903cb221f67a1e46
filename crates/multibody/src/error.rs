//! The errors of noether-multibody: a mechanism described wrongly, caught when it is built.

use thiserror::Error;

/// This crate's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What can go wrong describing or evaluating a mechanism.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// An error of noether-core (dimensions, non-finite data, the equations of motion).
    #[error(transparent)]
    Core(noether_core::Error),
    /// A body whose mass is negative or not finite.
    #[error("body {body}: mass {mass} must be finite and at least 0")]
    Mass {
        /// The body's index (in the order of attachment).
        body: usize,
        /// The mass given.
        mass: f64,
    },
    /// A body whose inertia tensor about its centre of mass cannot belong to a rigid body: not
    /// symmetric, a negative principal moment, or a moment above the sum of the other two (the triangle
    /// inequality every mass distribution obeys).
    #[error("body {body}: inertia tensor {reason} (worst value {value:e})")]
    Inertia {
        /// The body's index.
        body: usize,
        /// What is wrong with it.
        reason: &'static str,
        /// The offending value: the asymmetry, the smallest moment, or the excess of one moment over
        /// the sum of the other two, relative to the largest.
        value: f64,
    },
    /// A body attached to a parent that does not exist (yet): bodies are attached in order, each to
    /// the ground or to one attached before it.
    #[error("body {body}: its parent {parent} is not among the {bodies} bodies attached before it")]
    UnknownParent {
        /// The body being attached.
        body: usize,
        /// The parent named.
        parent: usize,
        /// How many bodies were attached before.
        bodies: usize,
    },
    /// A loop closure whose constraint depends on those before it at the configuration checked
    /// ([`Mechanism::check_loops`](crate::Mechanism::check_loops)): it restrains nothing the others do
    /// not, and the multipliers of the closed mechanism would not be determined.
    #[error(
        "loop closure {closure}, direction {direction}: redundant (the closures before it already have \
         rank {rank}); drop it, or close a planar loop along the plane's two directions only"
    )]
    RedundantClosure {
        /// The closure (in the order of `close_loop`).
        closure: usize,
        /// Its direction (in the order given).
        direction: usize,
        /// The rank of the closures' Jacobian up to and including it.
        rank: usize,
    },
    /// A loop closure between a body and itself, or between the ground and the ground: the two
    /// points move together whatever q is, so it closes no loop (it holds always, or never).
    #[error("loop closure {closure}: both sides are on the same body (or both on the ground), which closes no loop")]
    NotALoop {
        /// The closure (in the order of `close_loop`).
        closure: usize,
    },
    /// A body named that the mechanism does not have (in `actuate`, `coordinates`, `pose`).
    #[error("no body {body}: the mechanism has {bodies}")]
    UnknownBody {
        /// The body named.
        body: usize,
        /// How many bodies the mechanism has.
        bodies: usize,
    },
    /// A joint axis that is zero or not finite.
    #[error("body {body}: joint axis {axis:?} must be finite and nonzero")]
    Axis {
        /// The body whose joint it is.
        body: usize,
        /// The axis given.
        axis: [f64; 3],
    },
}

noether_core::crate_error_conversions!(Error);
