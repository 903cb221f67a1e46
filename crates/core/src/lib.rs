//! # noether-core
//!
//! Lagrangians L(t, q, q̇) and Hamiltonians H(t, q, p) written once as generic Rust code; their
//! equations of motion, momenta, energy and Legendre maps by dual numbers (`num-dual`); continuous
//! integrators; one Newton solver for every implicit equation.
//!
//! ```
//! use noether_core::prelude::*;
//!
//! /// Harmonic oscillator, L = ½ m q̇² − ½ k q².
//! struct Oscillator { m: f64, k: f64 }
//! impl Lagrangian for Oscillator {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         v[0] * v[0] * (0.5 * self.m) - q[0] * q[0] * (0.5 * self.k)
//!     }
//! }
//!
//! let el = EulerLagrange::new(Oscillator { m: 2.0, k: 8.0 });
//! let mut a = [0.0];
//! el.accelerations(0.0, &[0.5], &[0.0], &mut a).unwrap();
//! assert!((a[0] - (-8.0 * 0.5 / 2.0)).abs() < 1e-14); // q̈ = −(k/m) q
//!
//! // One period 2π sqrt(m/k) = π with RK4 returns to the start.
//! let mut run = Driver::new(Rk4::new(el), State::new(0.0, [0.5], [0.0])).unwrap().step_size(1e-3).unwrap();
//! let sol = run.run_until(std::f64::consts::PI).unwrap();
//! assert!((sol.last().q[0] - 0.5).abs() < 1e-10);
//! ```

pub mod ad;
pub mod chart;
pub mod control;
pub mod dense;
pub mod driver;
pub mod dynamics;
pub mod error;
pub mod hamilton;
pub mod integrators;
pub mod lagrange;
pub mod legendre;
pub mod linalg;
pub mod model;
pub mod natural;
pub mod newton;
pub mod roots;
pub mod scalar;
pub mod selfcheck;
pub mod shorthand;
pub mod state;
pub mod stepper;
pub mod system;
pub mod tangent;

pub use chart::ChartGuard;
pub use dense::DenseOutput;
pub use driver::{Direction, Driver, Event, EventRecord, Save, Solution, Stats, Stop};
pub use error::{Error, Result};
pub use hamilton::HamiltonEquations;
pub use lagrange::EulerLagrange;
pub use legendre::LegendreTransform;
pub use linalg::DenseFactor;
pub use model::{Hamiltonian, Lagrangian, Separable, SeparableHamiltonian};
pub use natural::{Natural, Potential};
pub use newton::{Newton, NewtonInfo, NewtonSystem};
pub use scalar::Scalar;
pub use state::{Momenta, Partner, State, Velocities};
pub use stepper::{StepInfo, Stepper};
pub use system::Dynamics;
pub use tangent::TangentStepper;

/// Everything a model and a simulation need, in one import.
pub mod prelude {
    pub use crate::integrators::*;
    pub use crate::{hamiltonian, lagrangian};
    pub use crate::{
        Direction, Driver, Dynamics, Error, EulerLagrange, Event, HamiltonEquations, Hamiltonian, Lagrangian,
        LegendreTransform, Momenta, Natural, Partner, Potential, Result, Save, Scalar, Separable,
        SeparableHamiltonian, Solution, State, StepInfo, Stepper, Stop, TangentStepper, Velocities,
    };
}
