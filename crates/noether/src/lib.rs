//! # noether
//!
//! Lagrangian and Hamiltonian mechanics with automatic differentiation. Write a Lagrangian
//! L(t, q, q̇) or a Hamiltonian H(t, q, p) once, as generic Rust code; noether derives the equations of
//! motion with dual numbers and integrates them. `use noether::prelude::*` brings in what a first program
//! needs (about thirty names: [`prelude`]); the rest is in the crates re-exported here, and the [`guide`]
//! walks from a first pendulum through all of them:
//!
//! | module | crate | what |
//! |---|---|---|
//! | [`core`] | noether-core | models, equations of motion by AD, Legendre maps, integrators (explicit, adaptive Dormand-Prince, Nyström DPRKN, IAS15, symplectic, Gauss), exact tangents of the flow, the driver, Newton |
//! | [`constraints`] | noether-constraints | holonomic and nonholonomic constraints, multipliers, RATTLE |
//! | [`discrete`] | noether-discrete | discrete Lagrangians and variational integrators, discrete Noether momenta, optimal control by discrete mechanics |
//! | [`particles`] | noether-particles | particle systems from one- and two-body interactions |
//! | [`analysis`] | noether-analysis | equilibria and normal modes, Lyapunov spectra, MEGNO and FLI chaos indicators (stability maps with `ensemble`), sensitivities, periodic orbits (single and multiple shooting) and their families (continuation) |
//! | [`compile`] | noether-compile | compiled models: the model recorded once, its equations derived and simplified on the graph, run without dual numbers (dual numbers as the guarded fallback): by an interpreter, or as native code compiled by Cranelift with the feature `jit` |
//! | [`canonical`] | noether-canonical | Poisson brackets, canonical transformations, Hamilton-Jacobi, action-angle variables, Routh's reduction, Poincaré sections |
//! | [`rigid`] | noether-rigid | rigid bodies on the rotation group: unit quaternions, torques of V(R) by AD, the Lie-group variational integrator |
//! | [`multibody`] | noether-multibody | mechanisms from bodies and joints: the Lagrangian of a kinematic tree written for you |
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
//! # Ok::<(), noether::Error>(())
//! ```

pub use nalgebra;
pub use noether_analysis as analysis;
pub use noether_canonical as canonical;
pub use noether_compile as compile;
pub use noether_constraints as constraints;
pub use noether_core as core;
pub use noether_discrete as discrete;
#[cfg(feature = "ensemble")]
pub use noether_ensemble as ensemble;
pub use noether_multibody as multibody;
pub use noether_particles as particles;
#[cfg(feature = "plot")]
pub use noether_plot as plot;
pub use noether_rigid as rigid;
pub use num_dual;

/// Closure-like shorthands for small models (see [`noether_core::shorthand`]).
pub use noether_core::{hamiltonian, lagrangian};

mod error;
pub use error::{Error, Result};

/// The guide: from a first pendulum to the heavy top, each step with its code (these examples are
/// compiled and run as doc-tests, so they stay true).
#[doc = include_str!("../../../docs/guide.md")]
pub mod guide {}

/// The names a first program needs, in one import: the models, the systems that turn them into equations
/// of motion, states, the driver and what it returns, the recommended integrators, and the toolkit's
/// [`Error`]. Everything else is imported from its crate (`noether::constraints::Rattle`) or from that
/// crate's own prelude (`noether::core::prelude`, `noether::discrete::prelude`,
/// `noether::particles::prelude`, `noether::constraints::prelude`).
pub mod prelude {
    // The user's model, and the shorthands that write one.
    pub use noether_core::{hamiltonian, lagrangian, Hamiltonian, Lagrangian, Potential, Scalar, Separable};
    // The model's equations of motion (Euler-Lagrange, Hamilton, H built from L).
    pub use noether_core::{
        EulerLagrange, HamiltonEquations, LegendreTransform, Natural, SeparableHamiltonian,
    };
    // States, one run, and what it returns.
    pub use noether_core::{
        Direction, Driver, Dynamics, Event, Momenta, Save, Solution, State, Stepper, Stop, Velocities,
    };
    // The recommended integrators: adaptive (DOP853), symplectic for any H (Gauss-Legendre), symplectic
    // compositions and high-order Nyström for natural systems, IAS15 for close encounters, and the
    // variational integrator of the midpoint discrete Lagrangian.
    pub use crate::{Error, Result};
    pub use noether_core::integrators::{Composition, DefaultMethod, Dop853, Dprkn12, Gauss, Ias15};
    pub use noether_discrete::{Midpoint, VariationalIntegrator};
}
