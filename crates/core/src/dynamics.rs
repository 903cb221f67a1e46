//! First-order dynamics on phase space, the interface every continuous integrator steps: the
//! [`Dynamics`] trait, which lives in [`system`](crate::system) with the other system traits and its
//! impls (re-exported here so that `noether_core::dynamics::Dynamics` keeps working).

pub use crate::system::Dynamics;
