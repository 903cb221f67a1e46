//! # noether-canonical
//!
//! The Hamiltonian side of the textbook, on a user's own H(t, q, p) written as generic code: Poisson
//! brackets and constants of the motion, canonical transformations and generating functions,
//! Hamilton-Jacobi, action-angle variables, Routh's reduction and Poincaré sections. Every derivative
//! is exact (noether-core's dual numbers); every implicit relation is solved by core's Newton.

pub mod action_angle;
pub mod error;
pub mod generating;
pub mod hamilton_jacobi;
pub mod poisson;
pub mod routh;
pub mod section;
pub mod transform;

pub use action_angle::{
    ActionAngle, Libration, Orbit, Rotation, Separated, SeparatedActions, SeparatedResult,
};
pub use error::{Error, Result};
pub use generating::{GeneratingFunction, Kind};
pub use hamilton_jacobi::CompleteIntegral;
pub use poisson::{bracket, constant_of_motion, time_derivative, PhaseFunction};
pub use routh::Routh;
pub use section::{section, section_by, Plane, SectionPoints};
pub use transform::CanonicalMap;
