//! The models that noether's tests, benchmarks and gallery share, each written once, with their
//! closed forms and hand-derived reference equations.
//!
//! A model checked both by a crate's integration tests and by an example of the gallery (or measured
//! by a benchmark) lives here, so the two check the same code. Each item keeps the formula it encodes
//! and where that comes from; the tolerances stay with the tests and examples that use them. Not
//! published: the library crates take it as a dev-dependency only, the gallery as a dependency.
//!
//! Modules that need a crate beyond `noether-core` are behind a feature of that crate's name.

#[cfg(feature = "discrete")]
pub mod boundary;
#[cfg(feature = "canonical")]
pub mod canonical;
pub mod closed_form;
#[cfg(feature = "constraints")]
pub mod gibbs_appell;
#[cfg(feature = "canonical")]
pub mod hamilton_jacobi;
pub mod henon_heiles;
pub mod kepler;
#[cfg(feature = "peer")]
pub mod peer;
pub mod pendulum;
pub mod systems;
pub mod three_body;
pub mod top;
