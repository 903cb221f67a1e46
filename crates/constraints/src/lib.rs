//! # noether-constraints
//!
//! Holonomic constraints φ(t, q) = 0 and velocity (nonholonomic) constraints A(t, q) q̇ + a(t, q) = 0,
//! written once as generic code like a Lagrangian; their derivatives come from dual numbers.
//!
//! - [`Constrained`]: the index-1 equations [M Aᵀ; A 0][q̈; −λ] = [f; −c] for accelerations and
//!   multipliers; it is a core [`Dynamics`](noether_core::Dynamics), so every continuous integrator
//!   steps it, and [`Projected`] keeps the steps on the constraint manifold.
//! - [`ConstraintForces`]: the multipliers as generalized forces Aᵀλ and as physical vectors.
//! - [`project`]: puts a state on the manifold and reports the correction.
//! - [`Rattle`]: the constrained variational integrator (discrete Euler-Lagrange equations with
//!   multipliers, positions and momenta on the manifold, discrete Noether momenta conserved) on a
//!   discrete Lagrangian of noether-discrete.
//! - Nonholonomic constraints A(t, q) q̇ + a(t, q) = 0 ([`Nonholonomic`]) in the continuous equations
//!   (Lagrange-d'Alembert).
//! - [`GibbsAppellEquations`]: quasi-velocities u with q̇ = W u + w and the Gibbs-Appell equations
//!   ∂S/∂u̇ = Π from the acceleration energy S of particles and rigid parts, by dual numbers; no
//!   multipliers (a core [`Dynamics`](noether_core::Dynamics) on (t, q, u)).
//! - [`Impact`]: impulsive motion, the jump of the momenta by a generalized impulse and the impulsive
//!   reactions of constraints that act for an instant (a blow, a catch, a rebound with restitution).
//!
//! Bad input is an error, never a panic: a state off the constraints ([`Error::ConstraintViolated`],
//! naming the residual), redundant constraints ([`Error::RankDeficientConstraints`], with the rank),
//! Newton failures as in core. Through core's interfaces (a driver's run) these arrive as
//! [`noether_core::Error::Model`]; [`Error::from`] gives them back.
//!
//! ```
//! use noether_constraints::prelude::*;
//!
//! /// A point mass in the vertical plane, L = ½ m (ẋ² + ẏ²) − m g y ...
//! struct Mass { m: f64, g: f64 }
//! impl Lagrangian for Mass {
//!     fn dof(&self) -> usize { 2 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, _q: &[D], v: &[D]) -> D {
//!         (v[0] * v[0] + v[1] * v[1]) * (0.5 * self.m) - _q[1] * (self.m * self.g)
//!     }
//! }
//! /// ... on a rod of length l: φ = (x² + y² − l²)/2.
//! struct Rod { l: f64 }
//! impl Holonomic for Rod {
//!     fn dof(&self) -> usize { 2 }
//!     fn count(&self) -> usize { 1 }
//!     fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
//!         out[0] = (q[0] * q[0] + q[1] * q[1] - self.l * self.l) * 0.5;
//!     }
//! }
//!
//! let sys = Constrained::holonomic(Mass { m: 1.0, g: 9.81 }, Rod { l: 1.0 })?;
//! // Hanging at rest: the rod carries the weight, T = m g (the force on the bob points up).
//! let f = sys.constraint_forces(0.0, &[0.0, -1.0], &[0.0, 0.0])?;
//! assert!((f.on_particle(0, 2)?[1] - 9.81).abs() < 1e-12);
//!
//! // RK4 with a projection after every step stays on the circle.
//! let stepper = Projected::new(Rk4::new(&sys), sys.constraints());
//! let start = State::new(0.0, [0.6, -0.8], [0.8, 0.6]);
//! let mut run = Driver::with_step(stepper, start, 1e-3)?;
//! let end = run.run_until(1.0)?.last().clone();
//! assert!((end.q.norm() - 1.0).abs() < 1e-13);
//! # Ok::<(), noether_constraints::Error>(())
//! ```

pub mod dynamics;
pub mod error;
pub mod forces;
pub mod gibbs_appell;
pub mod holonomic;
pub mod impulse;
pub mod linearize;
// The vector-valued AD kernels: unchecked, for this crate's own checked functions only.
pub(crate) mod jets;
pub mod nonholonomic;
pub mod projection;
pub mod rattle;
pub mod reduced;
pub mod set;

pub use dynamics::Constrained;
pub use error::{Error, Result};
pub use forces::ConstraintForces;
pub use gibbs_appell::{GibbsAppell, GibbsAppellEquations, QuasiVelocities, RigidPart};
pub use holonomic::{Holonomic, HolonomicSet};
pub use impulse::{generalized_impulse, Impact, ImpactResult, StruckPoints};
pub use linearize::linearize;
pub use nonholonomic::{Nonholonomic, NonholonomicSet};
pub use projection::{project, Projected, Projection, ProjectionReport};
pub use rattle::{Rattle, RattleInfo};
pub use reduced::Reduced;
pub use set::{ConstraintSet, SetDerivatives};

/// Models, constraints, and the integrators to step them, in one import. `Error` and `Result` here
/// are this crate's (which wrap core's and convert from it with `?`).
pub mod prelude {
    pub use crate::{
        project, Constrained, ConstraintForces, ConstraintSet, Error, GibbsAppell, GibbsAppellEquations,
        Holonomic, HolonomicSet, Nonholonomic, NonholonomicSet, Projected, Projection, ProjectionReport,
        QuasiVelocities, Rattle, RattleInfo, Result, RigidPart,
    };
    pub use noether_core::prelude::*;
}
