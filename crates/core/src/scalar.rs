//! The scalar bound every user model is generic over.
//!
//! A model (Lagrangian, Hamiltonian, potential, constraint) is written once as a generic method over
//! `D: Scalar`; noether evaluates it with `f64` and with several stack-allocated dual numbers of
//! `num-dual` to obtain exact first and second derivatives.
//!
//! Two traps to remember when writing a model: `f64 * D` does not compile (write `D * f64`), and a
//! literal that must be a `D` is written `D::from(0.5)`.
//!
//! One habit for speed: mark the model's method `#[inline]`. A generic method without the hint is
//! compiled once, in one codegen unit of your crate, and a derivative kernel in another unit cannot
//! inline it; the dual numbers then go through memory. For a 2-dof potential the hint takes the
//! right-hand side from 27–31 ns to 12–14 ns (`cargo bench -p noether-core --bench rates`,
//! docs/benchmarks.md).

pub use num_dual::DualNum;

/// A real number or a dual number over `f64` that is `Copy` (no heap allocation per operation).
pub trait Scalar: DualNum<f64> + Copy {}

impl<T: DualNum<f64> + Copy> Scalar for T {}
