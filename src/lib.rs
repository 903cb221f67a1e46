//! # noether
//!
//! Lagrangian and Hamiltonian mechanics with automatic differentiation. This facade re-exports the
//! workspace crates; `use noether::prelude::*` brings in what a model and a simulation need.

pub use noether_analysis as analysis;
pub use noether_constraints as constraints;
pub use noether_core as core;
pub use noether_discrete as discrete;
pub use noether_particles as particles;

/// Closure-like shorthands for small models (see [`noether_core::shorthand`]).
pub use noether_core::{hamiltonian, lagrangian};

/// Everything a model and a simulation need, in one import.
pub mod prelude {
    pub use noether_core::prelude::*;
}

pub mod gallery;

/// The README's example, compiled and run as a doctest so that it stays true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// The code blocks of `docs/guide.md` run as doc-tests, so the guide stays true.
#[cfg(doctest)]
#[doc = include_str!("../docs/guide.md")]
pub struct GuideDoctests;
