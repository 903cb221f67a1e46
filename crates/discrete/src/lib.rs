//! # noether-discrete
//!
//! Discrete mechanics: discrete Lagrangians L_d(q₀, q₁, h) written once as generic code (or built from a
//! continuous [`Lagrangian`](noether_core::Lagrangian) by quadrature), the variational integrators they
//! define in position-momentum form
//!
//! ```text
//! p_k = −D₁L_d(q_k, q_{k+1}) − f⁻(q_k, q_{k+1}),      p_{k+1} = D₂L_d(q_k, q_{k+1}) + f⁺(q_k, q_{k+1}),
//! ```
//!
//! solved for the increment q_{k+1} − q_k by the core Newton with Jacobians from dual numbers, discrete Noether momenta, and
//! the discrete Lagrange-d'Alembert principle for forced and dissipative systems (f^±).
//!
//! - [`DiscreteLagrangian`]: the user's (or a rule's) L_d; [`DiscreteDerivatives`]: D₁L_d, D₂L_d, D₁₂L_d.
//! - [`Midpoint`], [`Trapezoidal`]: second-order discrete Lagrangians of a continuous L.
//! - [`VariationalIntegrator`]: the general stepper (dense Newton); [`Galerkin`]: orders 4 and 6 by a
//!   polynomial path and Gauss quadrature. Every integrator here is a core
//!   [`SignedStepper`](noether_core::integrators::SignedStepper) (steps of either sign), so core's
//!   [`Composition`](noether_core::integrators::Composition) raises a symmetric one to order 4, 6 or 8
//!   with validated [`Weights`](noether_core::integrators::Weights):
//!   `Composition::new(VariationalIntegrator::new(Midpoint::new(l)), Weights::yoshida4())`.
//! - [`momentum`]: discrete Noether momenta p·ξ(q).
//! - [`tangent`]: the exact Jacobian Ψ = ∂(q_{k+1}, p_{k+1})/∂(q_k, p_k) of a step
//!   (core's [`SignedTangentStepper`](noether_core::integrators::SignedTangentStepper) and
//!   [`TangentStepper`](noether_core::TangentStepper)) by the
//!   implicit-function theorem at the converged solution.
//! - [`boundary`]: boundary-value problems q(t₀) = a, q(t₁) = b by the discrete Hamilton principle
//!   ([`BoundaryValue`]), with the conjugate points of the discrete Jacobi operator ([`ConjugatePoint`]).
//! - [`optimal_control`]: optimal control by discrete mechanics (DMOC) — the path and piecewise-constant
//!   inputs of an actuated model ([`DiscreteActuated`]) that minimise a running cost between two states,
//!   subject to the forced discrete Euler-Lagrange equations, by Newton on the banded KKT system
//!   ([`OptimalControl`]).
//! - [`primary`]: for a degenerate Lagrangian (linear in q̇), a start whose momenta are off
//!   p = ∂L/∂q̇ is refused ([`OffPrimaryConstraint`]) instead of taking a wild step.
//! - Fast paths for L = ½q̇ᵀMq̇ − Σ_k V_k(q) ([`Mechanical`], a potential of local terms):
//!   [`MechanicalMidpoint`] (Newton with a banded or dense Jacobian assembled term by term, O(N) for
//!   chains) and [`Verlet`] (the trapezoidal rule: explicit, no Newton; without damping it is core's
//!   [`StormerVerlet`](noether_core::integrators::StormerVerlet), `Mechanical` being a core
//!   [`SplitDynamics`](noether_core::integrators::SplitDynamics) in (q, p)).
//!
//! ```
//! use noether_core::prelude::*;
//! use noether_discrete::{momentum, Midpoint, VariationalIntegrator};
//!
//! /// Kepler problem in the plane, L = ½|q̇|² + 1/|q|.
//! struct Kepler;
//! impl Lagrangian for Kepler {
//!     fn dof(&self) -> usize { 2 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         (v[0] * v[0] + v[1] * v[1]) * 0.5 + (q[0] * q[0] + q[1] * q[1]).sqrt().recip()
//!     }
//! }
//!
//! let mut vi = VariationalIntegrator::new(Midpoint::new(Kepler));
//! let mut s = vi.state_from_velocities(0.0, &[1.0, 0.0], &[0.0, 1.2]).unwrap();
//! let rot = momentum::PlanarRotation::new(vec![(0, 1)]);
//! let l0 = momentum::noether_momentum(&rot, s.q.as_slice(), s.v.as_slice());
//! for _ in 0..200 {
//!     vi.step(&mut s, 0.05).unwrap();
//! }
//! let l1 = momentum::noether_momentum(&rot, s.q.as_slice(), s.v.as_slice());
//! assert!((l1 - l0).abs() < 1e-13); // angular momentum: a discrete Noether momentum
//! ```

pub mod boundary;
pub mod chains;
mod error;
mod flow;
pub mod galerkin;
pub mod integrator;
pub mod lagrangian;
pub mod mechanical;
pub mod mechanical_midpoint;
pub mod momentum;
pub mod optimal_control;
pub mod primary;
pub mod quadrature;
pub mod tangent;
pub mod verlet;

pub use boundary::{BoundaryValue, ConjugatePoint, DiscretePath, LinearPath, NotMinimum, PathConstraint};
pub use error::{Error, Result};
pub use galerkin::Galerkin;
pub use integrator::VariationalIntegrator;
pub use lagrangian::{DiscreteDerivatives, DiscreteField, DiscreteLagrangian, StepEnd};
pub use mechanical::{LocalPotential, Mass, Mechanical};
pub use mechanical_midpoint::MechanicalMidpoint;
pub use momentum::{noether_momentum, Symmetry};
pub use optimal_control::{DiscreteActuated, Effort, Endpoint, OptimalControl, OptimalPath, RunningCost};
pub use primary::OffPrimaryConstraint;
pub use quadrature::{FromLagrangian, Midpoint, Trapezoidal};
pub use verlet::Verlet;

/// Everything needed to build and step a discrete model, in one import.
pub mod prelude {
    pub use crate::momentum::{noether_momentum, PlanarRotation, Symmetry, Translation};
    pub use crate::{
        DiscreteDerivatives, DiscreteLagrangian, FromLagrangian, Galerkin, LocalPotential, Mass, Mechanical,
        MechanicalMidpoint, Midpoint, Trapezoidal, VariationalIntegrator, Verlet,
    };
}
