//! The heavy symmetric top in Euler angles, and Kepler's problem per unit mass in polar coordinates:
//! the two models of Routh's reduction (each has cyclic angles).
//!
//! Used by noether-canonical's tests (`tests/canonical/routh.rs`) and the gallery's `heavy_top` (and
//! through it the other top examples) and `routh_reduction` examples.

use noether_core::{Lagrangian, Scalar};

/// The heavy symmetric top in Euler angles q = (θ, φ, ψ):
/// L = ½ I₁ (θ̇² + φ̇² sin²θ) + ½ I₃ (ψ̇ + φ̇ cos θ)² − M g ℓ cos θ (φ and ψ cyclic).
#[derive(Debug, Clone, Copy)]
pub struct HeavyTop {
    /// Moment of inertia about a transverse axis through the pivot.
    pub i1: f64,
    /// Moment of inertia about the symmetry axis.
    pub i3: f64,
    /// M g ℓ (mass × gravity × pivot-to-centre-of-mass distance).
    pub mgl: f64,
}

impl Lagrangian for HeavyTop {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (th, dth, dphi, dpsi) = (q[0], v[0], v[1], v[2]);
        let (s, c) = (th.sin(), th.cos());
        let w3 = dpsi + dphi * c;
        (dth * dth + dphi * dphi * s * s) * (0.5 * self.i1) + w3 * w3 * (0.5 * self.i3) - c * self.mgl
    }
}

/// Kepler per unit mass in polar coordinates (r, φ), L = (ṙ² + r² φ̇²)/2 + μ/r (φ cyclic).
#[derive(Debug, Clone, Copy)]
pub struct KeplerPolar {
    /// Gravitational parameter μ.
    pub mu: f64,
}

impl Lagrangian for KeplerPolar {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + q[0] * q[0] * v[1] * v[1]) * 0.5 + q[0].recip() * self.mu
    }
}
