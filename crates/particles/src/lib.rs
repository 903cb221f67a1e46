//! # noether-particles
//!
//! Systems of particles (mass, charge, position and velocity in 3D; 1D and 2D as special cases) with
//! external (one-body) and internal (two-body) interactions. An internal interaction is listed once and
//! applied to both particles with opposite signs, so Newton's third law holds by construction.
//!
//! - Potentials are written once as generic code ([`PairPotential`], [`OnePotential`]); their forces
//!   come from 3-slot dual numbers, term by term (cost linear in the number of terms), and their
//!   Hessians are assembled as sparse 3×3 blocks ([`System::hessian`]).
//! - Ready-made laws in [`laws`]: gravity, Coulomb, constant repulsion, springs (also with one end fixed),
//!   central force f(r), billiard contact, Lennard-Jones, the Gaussian coupling, uniform gravity, traps,
//!   linear drag.
//! - Short-range pairs with a cutoff use a cell list ([`ShortRange`]); large systems use rayon with
//!   bit-identical results ([`Parallel`]).
//! - A [`System`] is a core [`Lagrangian`](noether_core::Lagrangian) (every integrator applies) and a
//!   core [`Dynamics`](noether_core::Dynamics) with term-by-term forces; it also has the seed's state
//!   updates by name ([`Method`]: Euler, Euler-Cromer, RK4, velocity Verlet, Yoshida 4, each one of
//!   core's steppers) and an evolver.
//!
//! ```
//! use noether_particles::prelude::*;
//!
//! // Earth-Moon-like binary in reduced units (G = 1): total momentum is conserved exactly by the
//! // third law, whatever the integrator's error.
//! let sys = System::new(vec![Particle::new(1.0), Particle::new(0.01)]).unwrap()
//!     .with(Internal::new(Gravity { g: 1.0 }, [(0, 1)])).unwrap();
//! let s0 = sys.state(0.0, &[[0.0; 3], [1.0, 0.0, 0.0]], &[[0.0, -0.01, 0.0], [0.0, 1.0, 0.0]]).unwrap();
//! let s1 = sys.run(Method::VelocityVerlet, s0.clone(), 1e-3, 1000).unwrap();
//! let (p0, p1) = (sys.momentum(s0.v.as_slice()).unwrap(), sys.momentum(s1.v.as_slice()).unwrap());
//! assert!((p1[1] - p0[1]).abs() < 1e-15);
//! ```

pub mod error;
pub mod hessian;
pub mod interaction;
pub mod laws;
pub mod methods;
pub mod pairs;
pub mod particle;
pub mod potential;
pub mod system;
mod terms;

pub use error::{Error, Result};
pub use hessian::SparseHessian;
pub use interaction::{External, ExternalForce, Interaction, Internal, InternalForce};
pub use laws::*;
pub use methods::{Method, ParticleStepper};
pub use noether_core::Scalar;
pub use pairs::{AllPairs, CellList, ShortRange};
pub use particle::{Particle, Vec3};
pub use potential::{Body, OneBodyForce, OnePotential, PairPotential, TwoBodyForce};
pub use system::{Parallel, System};

/// Everything needed to build and run a particle system.
pub mod prelude {
    pub use crate::laws::*;
    pub use crate::{
        AllPairs, Body, External, ExternalForce, Internal, InternalForce, Method, OneBodyForce, OnePotential,
        PairPotential, Parallel, Particle, Scalar, ShortRange, System, Vec3,
    };
}
