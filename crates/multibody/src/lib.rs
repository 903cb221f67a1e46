//! # noether-multibody
//!
//! Multibody systems from bodies and joints: describe a mechanism — rigid bodies (mass, centre of
//! mass, inertia) attached to the ground or to each other by revolute, prismatic, cylindrical,
//! planar, spherical, free, rolling and fixed joints, with springs and dampers on joints or between
//! points, and actuated joints — and get its Lagrangian written for you. Spherical and free joints
//! turn by a rotation vector (exponential coordinates, renewed by [`Mechanism::chart_event`] before
//! they reach the chart's edge); a rolling joint's disk rolls without slipping under the velocity
//! constraints [`RollingContacts`]. [`Mechanism`] is an
//! ordinary [`Lagrangian`](noether_core::Lagrangian) (and [`Actuated`](noether_core::control::Actuated)),
//! so every integrator, the driver, linearisation and LQR, variational integrators, tangents and
//! ensembles run it unchanged, with exact derivatives by dual numbers. Closed loops (a four-bar, a
//! slider-crank) are cut at a joint and closed again by [`Mechanism::close_loop`]: holonomic
//! constraints ([`LoopClosures`]) for noether-constraints' multipliers, RATTLE and reduction. A tree
//! of one-coordinate joints also runs as [`ArticulatedBody`], the articulated-body algorithm on f64
//! ([`Mechanism::forward_dynamics`] chooses it), or [`NewtonEuler`], the recursive Newton-Euler
//! algorithm.
//!
//! ```
//! use noether_core::prelude::*;
//! use noether_multibody::{Body, Joint, Mechanism, Parent, Placement};
//!
//! // A double pendulum in the x-y plane, gravity along −y: two hinges about z, point bobs.
//! let z = [0.0, 0.0, 1.0];
//! let mut pendulum = Mechanism::new().gravity([0.0, -9.81, 0.0])?;
//! let upper = pendulum.attach(Parent::Ground, Placement::identity(), Joint::revolute(z), Body::point(1.0, [0.0, -1.0, 0.0]))?;
//! pendulum.attach(upper, Placement::at([0.0, -1.0, 0.0]), Joint::revolute(z), Body::point(1.0, [0.0, -1.0, 0.0]))?;
//! // Hanging straight down it is at rest. In the joints' (relative) angles the mass matrix there is
//! // [[m₁l₁² + m₂(l₁ + l₂)², m₂(l₂² + l₁l₂)], [·, m₂l₂²]] = [[5, 2], [2, 1]] for m = l = 1.
//! let el = EulerLagrange::new(pendulum);
//! let m = el.mass_matrix(0.0, &[0.0, 0.0], &[0.0, 0.0])?;
//! assert!((m[(0, 0)] - 5.0).abs() < 1e-14 && (m[(0, 1)] - 2.0).abs() < 1e-14 && (m[(1, 1)] - 1.0).abs() < 1e-14);
//! let mut a = [0.0; 2];
//! el.accelerations(0.0, &[0.0, 0.0], &[0.0, 0.0], &mut a)?;
//! assert_eq!(a, [0.0, 0.0]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod appell;
pub mod articulated;
pub mod closure;
pub mod connections;
pub mod error;
pub mod frames;
pub mod joint;
pub mod mechanism;
pub mod newton_euler;
pub mod rolling;

pub use appell::RollingAppell;
pub use articulated::{ArticulatedBody, ForwardDynamics};
pub use closure::LoopClosures;
pub use error::{Error, Result};
pub use joint::{renewed_rotation_vector, rotation_vector_rate, Body, Joint, JointKind, Placement};
pub use mechanism::{BodyId, Mechanism, Parent};
pub use newton_euler::NewtonEuler;
pub use rolling::RollingContacts;
