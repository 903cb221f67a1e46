//! Errors of noether-ensemble. A member's own failure is not one of these: it is a [`MemberError`]
//! (the run closure's error, or the message of its panic) reported with the member's index (see
//! [`Failure`](crate::Failure)), while the other members complete.

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
    /// A member index at or beyond the number of members.
    #[error("no member {index}: the ensemble has {members} members")]
    NoSuchMember {
        /// The index asked for.
        index: usize,
        /// Number of members.
        members: usize,
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

/// Why one member has no result: its run returned an error, or panicked.
///
/// A member's panic is caught (`std::panic::catch_unwind`; a build with `panic = "abort"` cannot catch
/// it) and becomes this member's failure; the other members run and are kept. The panic's message is
/// also printed on standard error by the default panic hook.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum MemberError<E> {
    /// What the member's run closure returned.
    #[error("{0}")]
    Failed(E),
    /// The member's run (or the construction of its parameters) panicked, with this message.
    #[error("the member's run panicked: {message}")]
    Panicked {
        /// The panic's message (its `&str` or `String` payload; a note when it was neither).
        message: String,
    },
    /// The member does not exist ([`Ensemble::run_member`](crate::Ensemble::run_member) with an index
    /// out of range).
    #[error(transparent)]
    Ensemble(#[from] Error),
}

impl<E> MemberError<E> {
    /// The run closure's own error, if that is what this is.
    pub fn failed(&self) -> Option<&E> {
        match self {
            MemberError::Failed(e) => Some(e),
            _ => None,
        }
    }

    /// The message of a panic, if the member panicked.
    pub fn panicked(&self) -> Option<&str> {
        match self {
            MemberError::Panicked { message } => Some(message),
            _ => None,
        }
    }
}

/// The message of a panic's payload (a `&str` or a `String`, as `panic!` makes them).
pub(crate) fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "(a panic payload that is not a string)".to_string()
    }
}

/// [`Error::NoSuchMember`] unless `index < members`.
pub(crate) fn check_member(index: usize, members: usize) -> Result<()> {
    if index < members {
        Ok(())
    } else {
        Err(Error::NoSuchMember { index, members })
    }
}
