//! # noether-canonical
//!
//! The Hamiltonian side of the textbook, on a user's own H(t, q, p) written as generic code: Poisson
//! brackets and constants of the motion, canonical transformations and generating functions,
//! Hamilton-Jacobi, action-angle variables, Routh's reduction and Poincaré sections. Every derivative
//! is exact (noether-core's dual numbers); every implicit relation is solved by core's Newton.

pub mod error;

pub use error::{Error, Result};

pub mod action_angle;

pub use action_angle::{
    ActionAngle, Libration, Orbit, Rotation, Separated, SeparatedActions, SeparatedResult,
};
pub mod section;

pub use section::{section, section_by, Plane, SectionPoints};
pub mod routh;

pub use routh::Routh;
