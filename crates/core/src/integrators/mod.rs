//! Continuous-time integrators. Every one implements [`Stepper`](crate::Stepper) and leaves the state
//! untouched when a step fails.
//!
//! | family | module | methods | systems |
//! |---|---|---|---|
//! | explicit | [`explicit`] | Euler, Euler-Cromer, RK4 | any [`Dynamics`](crate::Dynamics) |
//! | adaptive | [`adaptive`], [`dopri5`], [`dop853`] | Dormand-Prince 5(4) and 8(5,3), error control, dense output | any [`Dynamics`](crate::Dynamics) |
//! | Runge-Kutta-Nyström | [`nystrom`] | Dormand-El-Mikkawy-Prince RKN 6(4), 8(6), 12(10), error control, dense output | [`SplitDynamics`] with q̇ = v: natural L, particles |
//! | Gauss-Radau | [`ias15`] | IAS15: 15th-order predictor-corrector, adaptive steps, dense output | q̈ = f(q): [`SplitDynamics`] with identity drift |
//! | implicit symplectic | [`gauss`] | implicit midpoint, Gauss-Legendre 4 and 6 (Newton) | [`LinearizedDynamics`]: any H, any L |
//! | default | [`default_method`] | the method chosen from what the system declares | every system type |
//! | symplectic | [`symplectic`], [`stormer_verlet`] | symplectic Euler, Störmer-Verlet, compositions of order 4, 6, 8 | [`SplitDynamics`]: separable H or natural L |
//! | composition | [`composition`], [`weights`] | Ψ_h = Φ_{γ_s h} ∘ … ∘ Φ_{γ₁ h} of any [`SignedStepper`] with validated [`Weights`] | Störmer-Verlet, the variational integrators of noether-discrete |

pub mod adaptive;
pub mod composition;
pub mod default_method;
pub mod dop853;
pub mod dopri5;
pub mod explicit;
pub mod gauss;
pub mod ias15;
pub mod nystrom;
mod step_control;
pub mod stormer_verlet;
pub mod symplectic;
pub mod weights;

pub use crate::system::{LinearizedDynamics, SplitDynamics};
pub use adaptive::{Adaptive, Controller, EmbeddedPair, Stages, RTOL_FLOOR};
pub use composition::{Composition, SignedStepper, SignedTangentStepper};
pub use default_method::DefaultMethod;
pub use dop853::{Dop853, Dp853};
pub use dopri5::{Dopri5, Dp5};
pub use explicit::{Euler, EulerCromer, FirstOrder, FirstOrderRule, Rk4};
pub use gauss::Gauss;
pub use ias15::{Ias15, Ias15Control, Ias15System, VelocityDependent};
pub use nystrom::{Dprkn12, Dprkn6, Dprkn8, Nystrom, NystromPair, Rkn12, Rkn6, Rkn8};
pub use stormer_verlet::StormerVerlet;
pub use symplectic::SymplecticEuler;
pub use weights::Weights;
