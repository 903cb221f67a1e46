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

/// The top of the gallery's heavy-top examples and of the Routh tests: I₁ = 1, I₃ = 1/2, M g ℓ = 1.
pub const GALLERY_TOP: HeavyTop = HeavyTop {
    i1: 1.0,
    i3: 0.5,
    mgl: 1.0,
};

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

/// Four sample points (t, q, q̇) of the heavy top, at which the cyclic angles φ and ψ are checked.
pub fn top_samples() -> Vec<(f64, Vec<f64>, Vec<f64>)> {
    (0..4)
        .map(|i| {
            (
                0.0,
                vec![0.3 + 0.5 * i as f64, 1.0 * i as f64, -2.0 * i as f64],
                vec![0.2, 0.5, 5.0],
            )
        })
        .collect()
}
