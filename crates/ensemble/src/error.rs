//! Errors of noether-ensemble. A member's own failure is not one of these: it is reported with the
//! member's index and the run closure's error type (see [`Failure`](crate::Failure)), while the other
//! members complete.

use thiserror::Error;

/// Result alias of noether-ensemble.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong in setting up or collecting an ensemble.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter out of its domain (an axis with no point, a chunk of size 0, a histogram with
    /// lo ≥ hi).
    #[error("invalid {name} = {value}: {reason}")]
    InvalidParameter {
        /// Which parameter.
        name: &'static str,
        /// The value supplied (or a number that shows what was wrong).
        value: f64,
        /// Why it is invalid.
        reason: &'static str,
    },
    /// Members failed where every member's result was required: the first failure and how many.
    #[error("{failed} member(s) failed; the first, member {index}: {message}")]
    MemberFailed {
        /// Index of the first failed member.
        index: usize,
        /// Number of failed members.
        failed: usize,
        /// Its error, as text.
        message: String,
    },
    /// Bytes received from another MPI rank could not be decoded (a mismatch of builds or ranks).
    #[error("malformed message from another rank: {0}")]
    Decode(&'static str),
    /// The MPI ranks disagree on the ensemble (different member counts or chunk sizes).
    #[error("the MPI ranks disagree: {0}")]
    Mpi(String),
}
