//! Complete integrals of the Hamilton-Jacobi equation: the free particle, the oscillator, and Kepler's
//! problem separated in polar coordinates, each next to its Hamiltonian.
//!
//! Used by noether-canonical's tests (`tests/canonical/hamilton_jacobi.rs`) and the gallery's
//! `hamilton_jacobi` example.

use noether_canonical::hamilton_jacobi::CompleteIntegral;
use noether_core::{Hamiltonian, Scalar};

/// The free particle in the plane, H = |p|²/2m.
#[derive(Debug, Clone, Copy)]
pub struct Free {
    /// Mass.
    pub m: f64,
}
impl Hamiltonian for Free {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, _q: &[D], p: &[D]) -> D {
        (p[0] * p[0] + p[1] * p[1]) * (0.5 / self.m)
    }
}

/// S = α·q − |α|² t/2m: p = α, β = q − α t/m (so q = β + α t/m).
#[derive(Debug, Clone, Copy)]
pub struct FreeS {
    /// Mass.
    pub m: f64,
}
impl CompleteIntegral for FreeS {
    fn dof(&self) -> usize {
        2
    }
    fn principal<D: Scalar>(&self, t: D, q: &[D], a: &[D]) -> D {
        a[0] * q[0] + a[1] * q[1] - (a[0] * a[0] + a[1] * a[1]) * t * (0.5 / self.m)
    }
}

/// The oscillator H = p²/2m + ½ k q².
#[derive(Debug, Clone, Copy)]
pub struct Oscillator {
    /// Mass.
    pub m: f64,
    /// Spring constant.
    pub k: f64,
}
impl Hamiltonian for Oscillator {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        p[0] * p[0] * (0.5 / self.m) + q[0] * q[0] * (0.5 * self.k)
    }
}

/// S = W(q, E) − E t with W = ∫ sqrt(2m(E − ½kq²)) dq = ½ sqrt(mk) [q sqrt(A² − q²) + A² asin(q/A)],
/// A² = 2E/k (the branch p > 0); β = ∂S/∂E = asin(q/A)/ω − t, so q = A sin(ω(t + β)).
#[derive(Debug, Clone, Copy)]
pub struct OscillatorS {
    /// Mass.
    pub m: f64,
    /// Spring constant.
    pub k: f64,
}
impl CompleteIntegral for OscillatorS {
    fn dof(&self) -> usize {
        1
    }
    fn principal<D: Scalar>(&self, t: D, q: &[D], a: &[D]) -> D {
        let e = a[0];
        let a2 = e * (2.0 / self.k);
        let w = (q[0] * (a2 - q[0] * q[0]).sqrt() + a2 * (q[0] / a2.sqrt()).asin())
            * (0.5 * (self.m * self.k).sqrt());
        w - e * t
    }
}

/// Kepler in polar coordinates (r, θ), H = p_r²/2m + p_θ²/2mr² − k/r.
#[derive(Debug, Clone, Copy)]
pub struct KeplerPolar {
    /// Mass.
    pub m: f64,
    /// Strength of the attraction.
    pub k: f64,
}
impl Hamiltonian for KeplerPolar {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let r = q[0];
        p[0] * p[0] * (0.5 / self.m) + p[1] * p[1] / (r * r) * (0.5 / self.m) - r.recip() * self.k
    }
}

/// The separated complete integral S = −E t + L θ + W_r(r; E, L) of [`KeplerPolar`] for bound orbits
/// (E < 0) with L > 0, on the outgoing branch p_r > 0. W_r = ∫ sqrt(R)/r dr with R = a r² + b r + c,
/// a = 2mE, b = 2mk, c = −L², Δ = b² − 4ac, in closed form:
/// W_r = sqrt(R) − b/(2 sqrt(−a)) asin((2ar + b)/sqrt(Δ)) − L asin((br + 2c)/(r sqrt(Δ))).
/// (Its derivative is sqrt(R)/r; the closed form is exact and differentiable by duals in E and L,
/// where a quadrature would need derivatives under an integral with square-root endpoints.)
#[derive(Debug, Clone, Copy)]
pub struct KeplerS {
    /// Mass.
    pub m: f64,
    /// Strength of the attraction.
    pub k: f64,
}
impl CompleteIntegral for KeplerS {
    fn dof(&self) -> usize {
        2
    }
    fn principal<D: Scalar>(&self, t: D, q: &[D], al: &[D]) -> D {
        let (r, th, e, l) = (q[0], q[1], al[0], al[1]);
        let a = e * (2.0 * self.m);
        let b = 2.0 * self.m * self.k;
        let c = -(l * l);
        let sd = (a * c * (-4.0) + b * b).sqrt();
        let big_r = a * r * r + r * b + c;
        let wr = big_r.sqrt()
            - (-a).sqrt().recip() * (0.5 * b) * ((a * r * 2.0 + b) / sd).asin()
            - l * ((r * b + c * 2.0) / (r * sd)).asin();
        wr + l * th - e * t
    }
}
