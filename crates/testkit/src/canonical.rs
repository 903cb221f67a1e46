//! Canonical maps, generating functions and phase functions with the Hamiltonians they act on: the
//! oscillator and its action-angle variables, polar coordinates (as a map and from F₃), the rotating
//! frame (as a map and from F₂) with its K = H − ω L_z, a planar anharmonic oscillator, and Kepler's
//! problem with its angular momentum and Runge-Lenz vector, and separated in polar coordinates.
//!
//! Used by noether-canonical's tests (`tests/canonical/`) and the gallery's `canonical_transformation`,
//! `poisson_brackets` and `action_angle` examples.

use noether_canonical::generating::{GeneratingFunction, Kind};
use noether_canonical::poisson::PhaseFunction;
use noether_canonical::transform::CanonicalMap;
use noether_canonical::{Orbit, Separated};
use noether_core::{Hamiltonian, Scalar};
use std::f64::consts::PI;

/// The oscillator H = p²/2m + ½ m ω² q².
#[derive(Debug, Clone, Copy)]
pub struct Oscillator {
    /// Mass.
    pub m: f64,
    /// Angular frequency.
    pub w: f64,
}

impl Hamiltonian for Oscillator {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        p[0] * p[0] * (0.5 / self.m) + q[0] * q[0] * (0.5 * self.m * self.w * self.w)
    }
}

/// F₁(q, Q) = ½ m ω q² cot Q: p = m ω q cot Q, P = ½ m ω q²/sin² Q, so q = sqrt(2P/mω) sin Q,
/// p = sqrt(2mωP) cos Q and H = ωP (the oscillator's action-angle variables; P = E/ω; degenerate where
/// q = 0).
#[derive(Debug, Clone, Copy)]
pub struct ActionAngle {
    /// Mass.
    pub m: f64,
    /// Angular frequency.
    pub w: f64,
}

impl GeneratingFunction for ActionAngle {
    fn kind(&self) -> Kind {
        Kind::F1
    }
    fn dof(&self) -> usize {
        1
    }
    fn generating<D: Scalar>(&self, _t: D, q: &[D], big_q: &[D]) -> D {
        q[0] * q[0] * big_q[0].tan().recip() * (0.5 * self.m * self.w)
    }
}

/// Polar coordinates (r, θ) with their conjugate momenta p_r = (x p_x + y p_y)/r, p_θ = x p_y − y p_x:
/// the point transformation extended to momenta (p = (∂Q/∂q)ᵀ P).
pub struct Polar;

impl CanonicalMap for Polar {
    fn dof(&self) -> usize {
        2
    }
    fn map<D: Scalar>(&self, _t: D, q: &[D], p: &[D], nq: &mut [D], np: &mut [D]) {
        let r = (q[0] * q[0] + q[1] * q[1]).sqrt();
        nq[0] = r;
        nq[1] = q[1].atan2(q[0]);
        np[0] = (q[0] * p[0] + q[1] * p[1]) / r;
        np[1] = q[0] * p[1] - q[1] * p[0];
    }
}

/// F₃(p, Q) = −(p_x r cos θ + p_y r sin θ) with Q = (r, θ): q = −∂F/∂p = (r cos θ, r sin θ) and
/// P = −∂F/∂Q = (p_x cos θ + p_y sin θ, r(p_y cos θ − p_x sin θ)): polar coordinates as a point
/// transformation.
pub struct PolarF3;

impl GeneratingFunction for PolarF3 {
    fn kind(&self) -> Kind {
        Kind::F3
    }
    fn dof(&self) -> usize {
        2
    }
    fn generating<D: Scalar>(&self, _t: D, p: &[D], big_q: &[D]) -> D {
        let (s, c) = big_q[1].sin_cos();
        -(p[0] * c + p[1] * s) * big_q[0]
    }
}

/// Coordinates in a frame rotating at angular velocity ω: Q = R(−ωt) q, P = R(−ωt) p.
pub struct Rotating {
    /// Angular velocity of the frame.
    pub w: f64,
}

impl CanonicalMap for Rotating {
    fn dof(&self) -> usize {
        2
    }
    fn map<D: Scalar>(&self, t: D, q: &[D], p: &[D], nq: &mut [D], np: &mut [D]) {
        let (s, c) = (t * self.w).sin_cos();
        nq[0] = c * q[0] + s * q[1];
        nq[1] = c * q[1] - s * q[0];
        np[0] = c * p[0] + s * p[1];
        np[1] = c * p[1] - s * p[0];
    }
}

/// F₂(q, P, t) = P·R(−ωt) q: Q = R(−ωt) q, p = R(ωt) P (the coordinates and momenta of a frame rotating
/// at ω); K = H + ∂F₂/∂t = H − ω L_z.
pub struct RotatingF2 {
    /// Angular velocity of the frame.
    pub w: f64,
}

impl GeneratingFunction for RotatingF2 {
    fn kind(&self) -> Kind {
        Kind::F2
    }
    fn dof(&self) -> usize {
        2
    }
    fn generating<D: Scalar>(&self, t: D, q: &[D], big_p: &[D]) -> D {
        let (s, c) = (t * self.w).sin_cos();
        big_p[0] * (c * q[0] + s * q[1]) + big_p[1] * (c * q[1] - s * q[0])
    }
}

/// The planar oscillator H = |p|²/2m + ½ m ω² |q|² plus a quartic ε|q|⁴ (rotationally invariant,
/// not separable when ε ≠ 0), n = 2.
#[derive(Debug, Clone, Copy)]
pub struct Planar {
    /// Mass.
    pub m: f64,
    /// Frequency of the harmonic part.
    pub w: f64,
    /// Quartic coefficient.
    pub eps: f64,
}

impl Hamiltonian for Planar {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let r2 = q[0] * q[0] + q[1] * q[1];
        (p[0] * p[0] + p[1] * p[1]) * (0.5 / self.m)
            + r2 * (0.5 * self.m * self.w * self.w)
            + r2 * r2 * self.eps
    }
}

/// K = H − ω L_z of a rotationally invariant H in the rotating frame, written out as an ordinary
/// Hamiltonian (closed form: K = H + ∂F₂/∂t with F₂ = P·R(−ωt) q, ∂F₂/∂t = ω(P₁Q₂ − P₂Q₁)).
pub struct RotatingK {
    /// The Hamiltonian of the inertial frame.
    pub h: Planar,
    /// Angular velocity of the frame.
    pub w: f64,
}

impl Hamiltonian for RotatingK {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D]) -> D {
        self.h.hamiltonian(t, q, p) - (q[0] * p[1] - q[1] * p[0]) * self.w
    }
}

/// Kepler problem in Cartesian coordinates, H = |p|²/2m − k/|q| (n = 3).
#[derive(Debug, Clone, Copy)]
pub struct Kepler3 {
    /// Mass.
    pub m: f64,
    /// Strength of the attraction (G M m).
    pub k: f64,
}

impl Hamiltonian for Kepler3 {
    fn dof(&self) -> usize {
        3
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let r = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
        (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) * (0.5 / self.m) - r.recip() * self.k
    }
}

/// z = (q, p) itself as a phase function of n degrees of freedom (2n outputs): its bracket matrix is Ω.
pub struct Coordinates(pub usize);

impl PhaseFunction for Coordinates {
    fn phase_dof(&self) -> usize {
        self.0
    }
    fn outputs(&self) -> usize {
        2 * self.0
    }
    fn values<D: Scalar>(&self, _t: D, q: &[D], p: &[D], out: &mut [D]) {
        out[..self.0].copy_from_slice(q);
        out[self.0..].copy_from_slice(p);
    }
}

/// The angular momentum L = q × p (three outputs): {L_x, L_y} = L_z and cyclic.
pub struct AngularMomentum;

impl PhaseFunction for AngularMomentum {
    fn phase_dof(&self) -> usize {
        3
    }
    fn outputs(&self) -> usize {
        3
    }
    fn values<D: Scalar>(&self, _t: D, q: &[D], p: &[D], out: &mut [D]) {
        out[0] = q[1] * p[2] - q[2] * p[1];
        out[1] = q[2] * p[0] - q[0] * p[2];
        out[2] = q[0] * p[1] - q[1] * p[0];
    }
}

/// The Runge-Lenz vector A = p × L − m k q/|q| of [`Kepler3`]: {A, H} = 0, {A_x, A_y} = −2mH L_z.
pub struct RungeLenz(pub Kepler3);

impl PhaseFunction for RungeLenz {
    fn phase_dof(&self) -> usize {
        3
    }
    fn outputs(&self) -> usize {
        3
    }
    fn values<D: Scalar>(&self, t: D, q: &[D], p: &[D], out: &mut [D]) {
        let mut l = [D::zero(); 3];
        AngularMomentum.values(t, q, p, &mut l);
        let r = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
        let c = r.recip() * (self.0.m * self.0.k);
        out[0] = p[1] * l[2] - p[2] * l[1] - q[0] * c;
        out[1] = p[2] * l[0] - p[0] * l[2] - q[1] * c;
        out[2] = p[0] * l[1] - p[1] * l[0] - q[2] * c;
    }
}

/// Kepler per unit mass in polar coordinates (r, φ), separated with α = (E, L):
/// H_r = p_r²/2 + α₁²/(2r²) − μ/r = α₀ and H_φ = p_φ = α₁. Its radial action is
/// J_r = μ/sqrt(−2E) − L.
#[derive(Debug, Clone, Copy)]
pub struct KeplerSeparated {
    /// Gravitational parameter μ.
    pub mu: f64,
}

impl Separated for KeplerSeparated {
    fn dof(&self) -> usize {
        2
    }
    fn separated<D: Scalar>(&self, k: usize, alpha: &[D], q: D, p: D) -> D {
        match k {
            0 => p * p * 0.5 + alpha[1] * alpha[1] / (q * q * 2.0) - q.recip() * self.mu,
            _ => p,
        }
    }
}

/// The orbits of [`KeplerSeparated`] at angular momentum `l`: r librates about the circular radius
/// l²/μ, φ rotates with period 2π (p_φ = l).
pub fn kepler_orbits(mu: f64, l: f64) -> [Orbit; 2] {
    [
        Orbit::Libration { q_inside: l * l / mu },
        Orbit::Rotation {
            q0: 0.0,
            period: 2.0 * PI,
            p_guess: l,
        },
    ]
}

/// ‖MᵀΩM − Ω‖_max / ‖M‖∞² of a square 2n × 2n matrix (noether-canonical's
/// [`symplectic_defect`](noether_canonical::transform::symplectic_defect) relative to M's size): how
/// far a monodromy matrix with multipliers in the thousands is from symplectic, at the scale of its
/// own rounding.
pub fn relative_symplectic_defect(m: &nalgebra::DMatrix<f64>) -> f64 {
    let norm = m.abs().row_sum().max();
    noether_canonical::transform::symplectic_defect(m) / (norm * norm)
}
