//! Errors of noether-discrete: what discrete mechanics alone can get wrong, beside core's errors
//! (dimensions, Newton, singular matrices), which it shares.
//!
//! The steppers and solvers of this crate implement core's traits and return core's
//! [`Result`](noether_core::Result); this crate's own failures travel inside it as
//! [`noether_core::Error::Model`]. [`Error::from`] takes them out again (and the facade's
//! `noether::Error` does the same for every crate):
//!
//! ```
//! use noether_discrete::{Error, OffPrimaryConstraint};
//! fn describe(e: noether_core::Error) -> String {
//!     match Error::from(e) {
//!         Error::ConjugatePoint(c) => format!("conjugate point near t = {}", c.t),
//!         Error::OffPrimaryConstraint(OffPrimaryConstraint { residual, .. }) => format!("off by {residual:e}"),
//!         other => other.to_string(),
//!     }
//! }
//! let optimiser = Error::Optimizer { reason: "no progress".into() };
//! assert_eq!(describe(optimiser.into()), "optimiser: no progress");
//! ```

use crate::boundary::{ConjugatePoint, NotMinimum};
use crate::optimal_control::NoOptimalPath;
use crate::primary::OffPrimaryConstraint;

/// Result alias with this crate's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What discrete mechanics can get wrong, with its data; core's failures as [`Error::Core`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A boundary-value problem (nearly) singular: t₁ close to a discrete conjugate point of t₀.
    #[error(transparent)]
    ConjugatePoint(#[from] ConjugatePoint),
    /// [`BoundaryValue::minimize`](crate::BoundaryValue::minimize) ended on a stationary path that is
    /// not a minimum of the action.
    #[error(transparent)]
    NotMinimum(#[from] NotMinimum),
    /// A state refused by a variational integrator of a degenerate Lagrangian: momenta off the
    /// primary constraint.
    #[error(transparent)]
    OffPrimaryConstraint(#[from] OffPrimaryConstraint),
    /// A bounded optimal-control problem not solved (infeasible, no descent, iteration limit).
    #[error(transparent)]
    NoOptimalPath(#[from] NoOptimalPath),
    /// The optimiser (argmin) of [`BoundaryValue::minimize`](crate::BoundaryValue::minimize) failed.
    #[error("optimiser: {reason}")]
    Optimizer {
        /// Its message.
        reason: String,
    },
    /// An error of noether-core (dimensions, non-finite numbers, Newton, singular matrices).
    #[error(transparent)]
    Core(noether_core::Error),
}

noether_core::crate_error_conversions!(Error);

/// This crate's failures seen through core's interfaces: as [`noether_core::Error::Model`], with
/// their data.
macro_rules! through_core {
    ($($own:ident),*) => {
        $(impl From<$own> for noether_core::Error {
            fn from(e: $own) -> Self {
                Error::$own(e).into()
            }
        })*
    };
}

through_core!(ConjugatePoint, NotMinimum, OffPrimaryConstraint, NoOptimalPath);
