//! # noether-analysis
//!
//! What a Lagrangian system does near rest: its equilibria (stationary points of the effective
//! potential U(q) = −L(t, q, 0), found with argmin or Newton, classified by the Hessian), its normal
//! modes (K X = ω² M X with M and K by dual numbers) and the linear stability of equilibria with
//! gyroscopic terms (rotating frames). Every derivative is exact (noether-core's AD kernels).
//!
//! And what a system does along its orbits, from the exact tangents of the numerical flow: Lyapunov
//! spectra ([`lyapunov`]), the chaos indicators MEGNO and FLI and their stability maps over a grid of
//! initial conditions ([`chaos`]; the maps with the feature `ensemble`), periodic orbits by single and
//! multiple shooting and their Floquet multipliers ([`periodic`]), their families by pseudo-arclength
//! continuation through folds, branch points and period doublings, with branch switching
//! ([`continuation`]), sensitivities to parameters ([`sensitivity`]), and
//! linearisation with LQR for control ([`linearize`](mod@linearize), [`lqr`](mod@lqr)).
//!
//! ```
//! use noether_analysis::{normal_modes, EffectivePotential, EquilibriumFinder, Kind};
//! use noether_core::{Lagrangian, Scalar};
//!
//! /// Bead on a hoop of radius a spinning at ω about its vertical diameter:
//! /// L = ½ m a² (θ̇² + ω² sin²θ) + m g a cos θ.
//! struct Hoop { a: f64, g: f64, omega: f64 }
//! impl Lagrangian for Hoop {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         let s = q[0].sin();
//!         (v[0] * v[0] + s * s * self.omega.powi(2)) * (0.5 * self.a * self.a) + q[0].cos() * (self.g * self.a)
//!     }
//! }
//! let hoop = Hoop { a: 1.0, g: 9.81, omega: 5.0 };
//! // aω² > g: the bottom is unstable and the bead rides at cos θ₀ = g/(aω²).
//! let eq = EquilibriumFinder::default().minimize(&EffectivePotential::new(&hoop), &[0.3]).unwrap();
//! assert_eq!(eq.kind, Kind::Minimum);
//! assert!((eq.q[0].cos() - 9.81 / 25.0).abs() < 1e-12);
//! let modes = normal_modes(&hoop, eq.q.as_slice()).unwrap();
//! assert!((modes.omega2[0] - 25.0 * eq.q[0].sin().powi(2)).abs() < 1e-10); // ω² sin²θ₀
//! ```

pub mod chaos;
pub mod continuation;
pub mod equilibria;
pub mod error;
pub mod linearize;
pub mod lqr;
pub mod lyapunov;
pub mod modes;
pub mod periodic;
pub mod potential;
pub mod sensitivity;

#[cfg(feature = "ensemble")]
pub use chaos::{stability_map, StabilityMap};
pub use chaos::{Indicators, Megno};
pub use continuation::{Bifurcation, Branch, Continuation, SpecialPoint};
pub use equilibria::{classify, Equilibrium, EquilibriumFinder, Kind};
pub use error::{Error, Result};
pub use linearize::{linearize, linearize_step, HeldInputs, HeldStart, Linearization, StepLinearization};
pub use lqr::{dlqr, lqr, tvlqr, Lqr, TimeVaryingLqr};
pub use lyapunov::{Lyapunov, Spectrum};
pub use modes::{linear_stability, normal_modes, LinearStability, NormalModes, SmallOscillations};
pub use periodic::{floquet, Floquet, PeriodicOrbit, Shooting, Stability};
pub use potential::{EffectivePotential, Potential};
pub use sensitivity::{parameter_sensitivity, Parametric, ParametricHamiltonian, Sensitivity};
