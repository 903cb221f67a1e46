//! # noether-canonical
//!
//! The Hamiltonian side of the textbook, on a user's own H(t, q, p) written as generic code: Poisson
//! brackets and constants of the motion, canonical transformations and generating functions,
//! Hamilton-Jacobi, action-angle variables, Routh's reduction and Poincaré sections. Every derivative
//! is exact (noether-core's dual numbers); every implicit relation is solved by core's Newton.

pub mod error;
pub mod generating;
pub mod hamilton_jacobi;
pub mod poisson;
pub mod transform;
pub use generating::{GeneratingFunction, Kind};
pub use hamilton_jacobi::CompleteIntegral;
pub use poisson::{bracket, constant_of_motion, time_derivative, PhaseFunction};
pub use transform::CanonicalMap;

pub use error::{Error, Result};
