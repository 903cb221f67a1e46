//! Continuous-time integrators. Every one implements [`Stepper`](crate::Stepper) and leaves the state
//! untouched when a step fails.
//!
//! | family | module | methods | systems |
//! |---|---|---|---|
//! | explicit | [`explicit`] | Euler, Euler-Cromer, RK4 | any [`Dynamics`](crate::Dynamics) |
//! | symplectic | [`symplectic`] | symplectic Euler, Störmer-Verlet, compositions of order 4, 6, 8 | [`SplitDynamics`]: separable H or natural L |

pub mod explicit;
pub mod symplectic;

pub use explicit::{Euler, EulerCromer, Rk4};
pub use symplectic::{Composition, SplitDynamics, SymplecticEuler};
