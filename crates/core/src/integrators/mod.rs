//! Continuous-time integrators. Every one implements [`Stepper`](crate::Stepper) over a
//! [`Dynamics`](crate::Dynamics) and leaves the state untouched when a step fails.

pub mod explicit;

pub use explicit::Rk4;
