//! # noether-rigid
//!
//! Rigid bodies on the rotation group: the orientation is a unit quaternion (never angles, so no chart
//! has a pole), the motion is stepped by a Lie-group variational integrator that keeps it a rotation to
//! rounding, and the potential V(R) of the orientation is written once as generic code like any model
//! (its torque by dual numbers). [`rattle`] steps the same body in matrix coordinates with RATTLE on
//! the orthogonality constraints RᵀR = I.
//!
//! ```
//! use nalgebra::{UnitQuaternion, Vector3};
//! use noether_core::Driver;
//! use noether_rigid::{Lgvi, RigidBody};
//!
//! // A free asymmetric body spun near its middle axis: it flips, and |L| stays put.
//! let body = RigidBody::free(1.0, 2.0, 3.0).unwrap();
//! let start = body.state(0.0, &UnitQuaternion::identity(), &Vector3::new(1e-3, 1.0, 0.0));
//! let l0 = body.spatial_angular_momentum(&start).unwrap();
//! let mut run = Driver::new(Lgvi::new(body).unwrap(), start).unwrap().step_size(1e-2).unwrap();
//! let sol = run.run_until(20.0).unwrap();
//! let l1 = body.spatial_angular_momentum(sol.last()).unwrap();
//! assert!((l1.norm() - l0.norm()).abs() < 1e-13);
//! ```

pub mod body;
pub mod error;
pub mod lgvi;
pub mod rattle;
pub mod rotation;

pub use body::{Free, Inertia, OrientationPotential, RigidBody, UniformGravity};
pub use error::{Error, Result};
pub use lgvi::Lgvi;
