//! # noether
//!
//! Lagrangian and Hamiltonian mechanics with automatic differentiation. Write a Lagrangian
//! L(t, q, q̇) or a Hamiltonian H(t, q, p) once, as generic Rust code; noether derives the equations of
//! motion with dual numbers and integrates them. `use noether::prelude::*` brings in what a model and
//! a simulation need, from every part of the toolkit:
//!
//! | module | crate | what |
//! |---|---|---|
//! | [`core`] | noether-core | models, equations of motion by AD, Legendre maps, integrators, the driver, Newton |
//! | [`constraints`] | noether-constraints | holonomic and nonholonomic constraints, multipliers, RATTLE |
//! | [`discrete`] | noether-discrete | discrete Lagrangians and variational integrators, discrete Noether momenta |
//! | [`particles`] | noether-particles | particle systems from one- and two-body interactions |
//! | [`analysis`] | noether-analysis | equilibria and normal modes |
//! | [`canonical`] | noether-canonical | Poisson brackets, canonical transformations, Hamilton-Jacobi, action-angle variables, Routh's reduction, Poincaré sections |
//! | [`rigid`] | noether-rigid | rigid bodies on the rotation group: unit quaternions, torques of V(R) by AD, the Lie-group variational integrator |
//! | `ensemble` (feature `ensemble`) | noether-ensemble | many runs on every core, and across MPI ranks (feature `mpi`): grids, random samples, reductions bit-identical for any thread count |
//! | `plot` (feature `plot`) | noether-plot | SVG pictures of a run |
//!
//! ```
//! use noether::prelude::*;
//!
//! /// Simple pendulum: L = ½ m l² θ̇² + m g l cos θ.
//! struct Pendulum { m: f64, l: f64, g: f64 }
//! impl Lagrangian for Pendulum {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         v[0] * v[0] * (0.5 * self.m * self.l * self.l) + q[0].cos() * (self.m * self.g * self.l)
//!     }
//! }
//! let el = EulerLagrange::new(Pendulum { m: 1.0, l: 1.0, g: 9.81 });
//! let sol = Driver::new(Dop853::new(&el), State::new(0.0, [0.3], [0.0]))?
//!     .observe("energy", |s: &State| el.energy(s.t, s.q.as_slice(), s.v.as_slice()))
//!     .run_until(10.0)?;
//! let e = sol.observed("energy")?;
//! assert!((e[e.len() - 1] - e[0]).abs() < 1e-8 * e[0].abs());
//! # Ok::<(), noether::core::Error>(())
//! ```

pub use nalgebra;
pub use noether_analysis as analysis;
pub use noether_canonical as canonical;
pub use noether_constraints as constraints;
pub use noether_core as core;
pub use noether_discrete as discrete;
#[cfg(feature = "ensemble")]
pub use noether_ensemble as ensemble;
pub use noether_particles as particles;
#[cfg(feature = "plot")]
pub use noether_plot as plot;
pub use noether_rigid as rigid;
pub use num_dual;

/// Closure-like shorthands for small models (see [`noether_core::shorthand`]).
pub use noether_core::{hamiltonian, lagrangian};

/// Everything a model and a simulation need, in one import: the core prelude (models, integrators, the
/// driver), constraints, discrete mechanics, particles and equilibria. The discrete crate's
/// composition of variational integrators is `DiscreteComposition` here (core's `Composition` is the
/// symmetric composition of Störmer-Verlet).
pub mod prelude {
    pub use noether_analysis::{
        linear_stability, normal_modes, EffectivePotential, Equilibrium, EquilibriumFinder, Kind,
    };
    pub use noether_constraints::{
        project, Constrained, ConstraintForces, ConstraintSet, GibbsAppell, GibbsAppellEquations, Holonomic,
        HolonomicSet, Impact, Nonholonomic, NonholonomicSet, Projected, Projection, Rattle, StruckPoints,
    };
    pub use noether_core::prelude::*;
    pub use noether_discrete::prelude::{
        noether_momentum, DiscreteDerivatives, DiscreteFlow, DiscreteLagrangian, FromLagrangian, Galerkin,
        LocalPotential, Mass, Mechanical, MechanicalMidpoint, Midpoint, PlanarRotation, Symmetry,
        Translation, Trapezoidal, VariationalIntegrator, Verlet,
    };
    pub use noether_discrete::Composition as DiscreteComposition;
    #[cfg(feature = "ensemble")]
    pub use noether_ensemble::{Ensemble, Members, Reducer};
    pub use noether_particles::prelude::{
        AllPairs, Body, External, ExternalForce, Internal, InternalForce, Method, OneBodyForce, OnePotential,
        PairPotential, Parallel, Particle, ShortRange, System, Vec3,
    };
}
