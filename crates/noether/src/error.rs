//! One error for the whole toolkit: [`Error`] wraps the error of every crate, so a program matches any
//! failure without downcasting.
//!
//! Each crate reports what it alone can get wrong in its own enum (a constraint violated, a rank-deficient
//! constraint Jacobian, a conjugate point, an inertia that is not positive…), and core's
//! [`core::Error`](noether_core::Error) carries the failures every crate shares (dimensions, non-finite
//! numbers, Newton, step-size control, singular matrices). A crate's own error that travelled through
//! core's interfaces (a constraint violated inside a [`Driver`](noether_core::Driver) run) arrives as
//! [`core::Error::Model`](noether_core::Error::Model); the conversions here take it out again, so every
//! failure has exactly one place:
//!
//! - a failure of core's kind is always `Error::Core(..)`, whichever crate reported it
//!   (`constraints::Error::Core(e)` becomes `Error::Core(e)`);
//! - a crate's own failure is always that crate's variant (`Error::Constraints(..)`, `Error::Discrete(..)`,
//!   …), even when it came back from a run as `core::Error::Model`;
//! - only a user's own error type passed through [`core::Error::model`](noether_core::Error::model)
//!   stays `Error::Core(core::Error::Model(..))` (get it with
//!   [`downcast_ref`](noether_core::Error::downcast_ref)).
//!
//! ```
//! use noether::prelude::*;
//! use noether::constraints::{Constrained, Holonomic, Projected};
//! use noether::core::integrators::Rk4;
//!
//! /// A planar pendulum in Cartesian coordinates: L = ½|ṙ|² − g y, with x² + y² = 1 held by a multiplier.
//! struct Free;
//! impl Lagrangian for Free {
//!     fn dof(&self) -> usize { 2 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         (v[0] * v[0] + v[1] * v[1]) * 0.5 - q[1] * 9.81
//!     }
//! }
//! struct Rod;
//! impl Holonomic for Rod {
//!     fn dof(&self) -> usize { 2 }
//!     fn count(&self) -> usize { 1 }
//!     fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
//!         out[0] = (q[0] * q[0] + q[1] * q[1] - 1.0) * 0.5;
//!     }
//! }
//!
//! let sys = Constrained::holonomic(Free, Rod)?;
//! // A start off the constraint (|r| = 1.1) is refused by the constraints crate, inside a run ...
//! let off = State::new(0.0, [0.0, -1.1], [0.0, 0.0]);
//! let run = Driver::with_step(Projected::new(Rk4::new(&sys), sys.constraints()), off, 1e-3)?.run_until(1.0);
//! // ... which reports it through core's interfaces; here it is matched as the constraints crate's own.
//! let e = Error::from(run.unwrap_err());
//! assert!(matches!(e, Error::Constraints(noether::constraints::Error::ConstraintViolated { .. })), "{e}");
//! # Ok::<(), Error>(())
//! ```

use noether_analysis as analysis;
use noether_canonical as canonical;
use noether_compile as compile;
use noether_constraints as constraints;
use noether_core as core;
use noether_discrete as discrete;
#[cfg(feature = "ensemble")]
use noether_ensemble as ensemble;
use noether_multibody as multibody;
use noether_particles as particles;
#[cfg(feature = "plot")]
use noether_plot as plot;
use noether_rigid as rigid;

/// Result with the toolkit's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Every failure of noether, by the crate whose failure it is (the module docs say how each arrives in
/// exactly one variant).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A failure every crate shares: dimensions, non-finite numbers, Newton, step-size control, a
    /// singular matrix, a saved run that cannot be read, a name not recorded; or a user's own error
    /// passed through [`core::Error::model`](noether_core::Error::model).
    #[error(transparent)]
    Core(core::Error),
    /// Discrete mechanics: a conjugate point, a path that is not a minimum, momenta off the primary
    /// constraint, the optimiser.
    #[error(transparent)]
    Discrete(discrete::Error),
    /// Constraints: violated, or a rank-deficient Jacobian.
    #[error(transparent)]
    Constraints(constraints::Error),
    /// Particle systems: unknown or coincident particles, bad masses, interactions.
    #[error(transparent)]
    Particles(particles::Error),
    /// Equilibria, normal modes, periodic orbits, Lyapunov spectra.
    #[error(transparent)]
    Analysis(analysis::Error),
    /// Canonical maps, Hamilton-Jacobi, actions, sections.
    #[error(transparent)]
    Canonical(canonical::Error),
    /// Rigid bodies: quaternions, inertia.
    #[error(transparent)]
    Rigid(rigid::Error),
    /// Multibody systems: a mechanism described wrongly (a mass, an inertia, a parent, an axis).
    #[error(transparent)]
    Multibody(multibody::Error),
    /// Compiled models: a model that cannot be recorded (it reads the value of its scalar).
    #[error(transparent)]
    Compile(compile::Error),
    /// Setting up or collecting an ensemble.
    #[cfg(feature = "ensemble")]
    #[error(transparent)]
    Ensemble(ensemble::Error),
    /// A member of an ensemble panicked (its message); a member's returned error converts to the variant
    /// of its own kind.
    #[cfg(feature = "ensemble")]
    #[error("an ensemble member's run panicked: {message}")]
    MemberPanicked {
        /// The panic's message.
        message: String,
    },
    /// Drawing or writing a picture.
    #[cfg(feature = "plot")]
    #[error(transparent)]
    Plot(plot::Error),
}

/// The conversions of the crates whose errors wrap core's (each with a `Core` variant), from one list
/// of `crate => variant`:
/// - `From<core::Error>`: core's error as `Error::Core`, except a crate's own failure that came back
///   through core's interfaces as [`core::Error::Model`](noether_core::Error::Model), which is taken out
///   again (by `downcast_ref` to each listed crate's error) into that crate's variant;
/// - `From<crate::Error>` for each listed crate: its `Core` variant goes the way of core's error, the
///   rest to the crate's variant.
macro_rules! from_crates {
    ($($crate_:ident => $variant:ident),*) => {
        impl From<core::Error> for Error {
            /// Core's error, or a crate's own failure when it comes back through core's interfaces as
            /// [`core::Error::Model`](noether_core::Error::Model).
            fn from(e: core::Error) -> Self {
                if !matches!(e, core::Error::Model(_)) {
                    return Error::Core(e);
                }
                $(if let Some(own) = e.downcast_ref::<$crate_::Error>() {
                    return Error::$variant(own.clone());
                })*
                Error::Core(e)
            }
        }

        $(impl From<$crate_::Error> for Error {
            /// This crate's own failure, or core's (as `Error::Core`, or its own crate's variant if
            /// it came through core's interfaces).
            fn from(e: $crate_::Error) -> Self {
                match e {
                    $crate_::Error::Core(c) => Error::from(c),
                    own => Error::$variant(own),
                }
            }
        })*
    };
}

from_crates!(discrete => Discrete, constraints => Constraints, particles => Particles,
             analysis => Analysis, canonical => Canonical, rigid => Rigid,
             multibody => Multibody, compile => Compile);

#[cfg(feature = "ensemble")]
impl From<ensemble::Error> for Error {
    fn from(e: ensemble::Error) -> Self {
        Error::Ensemble(e)
    }
}

#[cfg(feature = "ensemble")]
impl<E: Into<Error>> From<ensemble::MemberError<E>> for Error {
    /// The member's own error as the variant of its kind; a panic as [`Error::MemberPanicked`].
    fn from(e: ensemble::MemberError<E>) -> Self {
        match e {
            ensemble::MemberError::Failed(own) => own.into(),
            ensemble::MemberError::Ensemble(own) => Error::Ensemble(own),
            other => Error::MemberPanicked {
                message: other.panicked().unwrap_or_default().to_owned(),
            },
        }
    }
}

#[cfg(feature = "plot")]
impl From<plot::Error> for Error {
    fn from(e: plot::Error) -> Self {
        Error::Plot(e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each crate's own failure lands in its variant whether it arrives directly or through core's
    /// interfaces, and core's failures land in `Core` whichever crate passed them on.
    #[test]
    fn each_failure_has_one_place() {
        let rigid_own = rigid::Error::NotUnitQuaternion {
            norm: 2.0,
            tolerance: 1e-12,
        };
        assert!(matches!(Error::from(rigid_own.clone()), Error::Rigid(_)));
        let through_core = core::Error::from(rigid_own);
        assert!(matches!(through_core, core::Error::Model(_)));
        assert!(matches!(
            Error::from(through_core),
            Error::Rigid(rigid::Error::NotUnitQuaternion { .. })
        ));

        let shared = core::Error::StepLimit { steps: 3, t: 1.0 };
        let via_analysis = analysis::Error::Core(shared.clone());
        assert!(matches!(
            Error::from(via_analysis),
            Error::Core(core::Error::StepLimit { .. })
        ));
        assert!(matches!(
            Error::from(constraints::Error::Core(shared)),
            Error::Core(_)
        ));

        let optimiser = discrete::Error::Optimizer {
            reason: "line search".into(),
        };
        let back = discrete::Error::from(core::Error::from(optimiser));
        assert!(matches!(back, discrete::Error::Optimizer { .. }));
        assert!(matches!(
            Error::from(back),
            Error::Discrete(discrete::Error::Optimizer { .. })
        ));

        /// A user's own error stays core's `Model`, for `downcast_ref`.
        #[derive(Debug, thiserror::Error)]
        #[error("mine")]
        struct Mine;
        let e = Error::from(core::Error::model(Mine));
        assert!(matches!(&e, Error::Core(c) if c.downcast_ref::<Mine>().is_some()));
    }
}
