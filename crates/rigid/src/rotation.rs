//! Kinematics of the rotation group SO(3) in the forms the integrators use: the hat map, the Cayley
//! map, unit quaternions checked on input, and the momentum conjugate to a quaternion.
//!
//! Conventions. A unit quaternion q = (w, x, y, z) (scalar first, as in a state vector; nalgebra's
//! [`UnitQuaternion`] stores it as `[x, y, z, w]` internally) represents the rotation matrix R that
//! takes body-frame vectors to the space frame: v_space = R v_body. The body-frame angular velocity Ω
//! is defined by Ṙ = R Ω̂, i.e. q̇ = ½ q ⊗ (0, Ω).
//!
//! The Cayley map cay(f) = (I + f̂)(I − f̂)⁻¹ = I + 2/(1 + |f|²) (f̂ + f̂²) is the rotation by the
//! angle θ = 2 atan|f| about f/|f|, whose quaternion is (1, f)/sqrt(1 + |f|²) (Lee, Leok & McClamroch
//! use it to solve the implicit equation of their Lie-group variational integrator).
//!
//! Momentum of a quaternion. With L(q, q̇) = ½ Ωᵀ J Ω, Ω = 2 vec(q* ⊗ q̇), the momentum conjugate to q
//! in ℝ⁴ is p = ∂L/∂q̇ = 2 q ⊗ (0, Π) with Π = J Ω the body angular momentum; conversely
//! Π = ½ vec(q* ⊗ p), and q·p = 0 (the component of p along q is the gauge of the unit-norm
//! constraint and carries no motion) (Miller, Eleftheriou, Pattnaik, Ndirango, Newns & Martyna,
//! J. Chem. Phys. 116, 8649 (2002)). A body's state holds ½ q* ⊗ p = (0, Π) ([`crate::body`]).

use crate::{Error, Result};
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3, Vector4};
use noether_core::Scalar;

/// Largest |‖q‖ − 1| accepted for an orientation given as four numbers: a quaternion computed from
/// angles or read back from a file is unit to ~1e-15; one that was never normalised is off by far
/// more than 1e-9. Accepted quaternions are normalised before use.
pub const UNIT_QUATERNION_TOLERANCE: f64 = 1e-9;

/// The hat map: the skew matrix v̂ with v̂ u = v × u.
pub fn hat<D: Scalar>(v: &Vector3<D>) -> Matrix3<D> {
    let z = D::zero();
    Matrix3::new(z, -v[2], v[1], v[2], z, -v[0], -v[1], v[0], z)
}

/// The inverse of the hat map on the skew part: vee(X) = (X₃₂, X₁₃, X₂₁), so vee(v̂) = v.
pub fn vee(x: &Matrix3<f64>) -> Vector3<f64> {
    Vector3::new(x[(2, 1)], x[(0, 2)], x[(1, 0)])
}

/// The Cayley map as a unit quaternion: (1, f)/sqrt(1 + |f|²), the rotation cay(f).
pub fn cayley(f: &Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::new_normalize(Quaternion::new(1.0, f[0], f[1], f[2]))
}

/// The Cayley map as a matrix: cay(f) = I + 2/(1 + |f|²)(f̂ + f̂²).
pub fn cayley_matrix(f: &Vector3<f64>) -> Matrix3<f64> {
    let fh = hat(f);
    Matrix3::identity() + (fh + fh * fh) * (2.0 / (1.0 + f.norm_squared()))
}

/// The orientation given as (w, x, y, z): finite (else [`noether_core::Error::NonFinite`]) and of
/// norm 1 within [`UNIT_QUATERNION_TOLERANCE`] (else [`Error::NotUnitQuaternion`]); returned
/// normalised.
pub fn unit_quaternion(q: &[f64]) -> Result<UnitQuaternion<f64>> {
    noether_core::error::check_len("orientation quaternion", q, 4)?;
    noether_core::error::check_finite("orientation quaternion", q)?;
    let quat = Quaternion::new(q[0], q[1], q[2], q[3]);
    let norm = quat.norm();
    if (norm - 1.0).abs() > UNIT_QUATERNION_TOLERANCE {
        return Err(Error::NotUnitQuaternion {
            norm,
            tolerance: UNIT_QUATERNION_TOLERANCE,
        });
    }
    Ok(UnitQuaternion::new_normalize(quat))
}

/// The four numbers (w, x, y, z) of a quaternion, the order of a state vector.
pub fn wxyz(q: &Quaternion<f64>) -> [f64; 4] {
    [q.w, q.i, q.j, q.k]
}

/// The momentum conjugate to the quaternion q for the body angular momentum Π: p = 2 q ⊗ (0, Π),
/// as (w, x, y, z).
pub fn quaternion_momentum(q: &UnitQuaternion<f64>, pi: &Vector3<f64>) -> Vector4<f64> {
    let p = q.quaternion() * Quaternion::from_imag(*pi) * 2.0;
    Vector4::new(p.w, p.i, p.j, p.k)
}

/// The body angular momentum Π = ½ vec(q* ⊗ p)/|q|² from the momentum p = (w, x, y, z) conjugate to
/// q, for q as stored (unit to rounding).
///
/// Dividing by |q|² makes this the inverse of [`quaternion_momentum`] without the bias of a
/// renormalised q (whose norm rounds to the same side every time).
pub fn body_momentum(q: &Quaternion<f64>, p: &[f64]) -> Vector3<f64> {
    let p = Quaternion::new(p[0], p[1], p[2], p[3]);
    (q.conjugate() * p).imag() * (0.5 / q.norm_squared())
}

/// The largest entry of |RᵀR − I|: how far R is from a rotation (rounding, ~1e-16, for a matrix from
/// a unit quaternion).
pub fn orthogonality_defect(r: &Matrix3<f64>) -> f64 {
    (r.transpose() * r - Matrix3::identity()).amax()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Cayley quaternion (1, f)/sqrt(1 + |f|²) is the matrix I + 2(f̂ + f̂²)/(1 + |f|²) (both are the
    /// rotation by 2 atan|f| about f), to rounding.
    #[test]
    fn closed_form_cayley_quaternion_is_the_cayley_matrix() {
        let f = Vector3::new(0.3, -0.7, 1.1);
        let from_q = cayley(&f).to_rotation_matrix().into_inner();
        let m = cayley_matrix(&f);
        assert!((from_q - m).amax() < 1e-15, "{}", (from_q - m).amax());
        let fh = hat(&f);
        let direct = (Matrix3::identity() + fh) * (Matrix3::identity() - fh).try_inverse().unwrap();
        assert!((direct - m).amax() < 1e-15);
        assert!((vee(&fh) - f).amax() == 0.0);
    }

    /// p = 2 q ⊗ (0, Π) and back: Π again to rounding, and q·p = 0.
    #[test]
    fn quaternion_momentum_round_trip() {
        let q = UnitQuaternion::from_euler_angles(0.3, -1.2, 2.0);
        let pi = Vector3::new(1.5, -0.25, 3.0);
        let p = quaternion_momentum(&q, &pi);
        assert!((body_momentum(q.quaternion(), p.as_slice()) - pi).amax() < 1e-15);
        let qv = Vector4::from(wxyz(q.quaternion()));
        assert!(qv.dot(&p).abs() < 1e-15);
    }
}
