//! Errors of noether-rigid: the core errors plus what is wrong with a body or an orientation.

use thiserror::Error;

/// Result alias of noether-rigid.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong, with the numbers that say how.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// An error of noether-core (dimensions, non-finite input, step size, Newton failure).
    #[error(transparent)]
    Core(noether_core::Error),
    /// An orientation quaternion whose norm is not 1 within the stated tolerance.
    #[error("orientation quaternion has norm {norm} (|‖q‖ − 1| must be at most {tolerance:e}): normalise it first")]
    NotUnitQuaternion {
        /// Its norm.
        norm: f64,
        /// The tolerance on |‖q‖ − 1|.
        tolerance: f64,
    },
    /// An inertia tensor that is not symmetric.
    #[error("inertia tensor is not symmetric: largest |J − Jᵀ| = {asymmetry:e} relative to its scale")]
    AsymmetricInertia {
        /// max |J_ij − J_ji| / max |J_ij|.
        asymmetry: f64,
    },
    /// An inertia tensor that is singular or not positive definite (a zero or negative principal
    /// moment, or one negligible against the largest).
    #[error("inertia tensor is not positive definite: smallest principal moment {smallest:e}, largest {largest:e}")]
    InertiaNotPositive {
        /// Smallest principal moment (eigenvalue).
        smallest: f64,
        /// Largest principal moment.
        largest: f64,
    },
    /// An inertia tensor whose principal moments are not normal numbers or whose inverse J⁻¹ is not
    /// finite (a subnormal moment such as 1e-310, whose reciprocal overflows): Ω = J⁻¹Π could not be
    /// computed.
    #[error(
        "inertia tensor out of range: principal moments {smallest:e} to {largest:e} (each must be at \
         least {min:e} and J⁻¹ finite)",
        min = f64::MIN_POSITIVE
    )]
    InertiaOutOfRange {
        /// Smallest principal moment.
        smallest: f64,
        /// Largest principal moment.
        largest: f64,
    },
    /// A body too flat for matrix coordinates: the kinetic energy ½ tr(Ṙ J_d Ṙᵀ) needs
    /// J_d = ½ tr(J) I − J positive definite, i.e. every principal moment below the sum of the other
    /// two (a lamina has I₃ = I₁ + I₂). The LGVI has no such restriction.
    #[error(
        "body too flat for matrix coordinates: ½ tr(J) − I_k = {smallest:e} against {largest:e} (each \
         principal moment must be below the sum of the other two); use the LGVI"
    )]
    FlatBody {
        /// Smallest eigenvalue of J_d.
        smallest: f64,
        /// Largest eigenvalue of J_d.
        largest: f64,
    },
}

noether_core::crate_error_conversions!(Error);
