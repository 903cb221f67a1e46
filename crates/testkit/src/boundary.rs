//! Boundary-value problems by the discrete Hamilton principle: a projectile through a target, the
//! harmonic oscillator and its conjugate points, geodesics of the sphere, the figure-eight as a
//! symmetric choreography.
//!
//! Used by noether-discrete's tests (`tests/discrete/boundary.rs`) and the gallery's `boundary_value`
//! example.

use nalgebra::{DMatrix, DVector};
use noether_core::{Lagrangian, Scalar};
use noether_discrete::boundary::PathConstraint;

/// Projectile L = ½m|q̇|² − m g y in the plane. Through the target b at t = T from a at t = 0:
/// q(t) = a + (b − a) t/T + ½ g t (T − t) ŷ.
pub struct Projectile {
    /// Mass m.
    pub m: f64,
    /// Gravity g.
    pub g: f64,
}

impl Lagrangian for Projectile {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + v[1] * v[1]) * (0.5 * self.m) - q[1] * (self.m * self.g)
    }
}

/// Harmonic oscillator L = ½ m (q̇² − ω² q²); from q(0) = a to q(T) = b it follows [`oscillator_path`].
pub struct Oscillator {
    /// Mass m.
    pub m: f64,
    /// Angular frequency ω.
    pub w: f64,
}

impl Lagrangian for Oscillator {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] - q[0] * q[0] * (self.w * self.w)) * (0.5 * self.m)
    }
}

/// q(t) = (a sin ω(T − t) + b sin ω t)/sin ωT with frequency ω (continuous: ω; discrete: ω_d).
pub fn oscillator_path(w: f64, a: f64, b: f64, t_end: f64, t: f64) -> f64 {
    (a * (w * (t_end - t)).sin() + b * (w * t).sin()) / (w * t_end).sin()
}

/// A free particle L = ½|q̇|² in space (on [`Sphere`], its paths are the great circles).
pub struct FreeParticle;

impl Lagrangian for FreeParticle {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, _q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * 0.5
    }
}

/// The unit sphere |q|² − 1 = 0.
pub struct Sphere;

impl PathConstraint for Sphere {
    fn dof(&self) -> usize {
        3
    }
    fn count(&self) -> usize {
        1
    }
    fn constraints<D: Scalar>(&self, q: &[D], out: &mut [D]) {
        out[0] = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - 1.0;
    }
}

/// The symmetric choreographies of the figure-eight as a linear family (N divisible by 12): one curve
/// x_k (k mod N) carries the three bodies, body i at x_{k + iN/3} (the choreography q_i(t + T/3) =
/// q_{i+1}(t)), with the symmetries of the eight (long axis along e₁): x_{−k} = −x_k (time reversal
/// and point reflection), x_{N/2−k} = R x_k (R the reflection across the long axis), hence x₀ = 0 and
/// x_{N/4} = (s, 0), and x_{k+N/2} = R' x_k (R' across the short axis). Each is a symmetry of the
/// midpoint action (an isometry, an index shift, and L_d(q₀, q₁) = L_d(q₁, q₀)), so a stationary point
/// in the family is one of the full action (Palais); they also remove the translations, the rotation
/// and the time shift, which would make the Hessian singular. Parameters y: x₁, …, x_{N/4−1}, s; the
/// matrices A_k with q_k = A_k y, k = 0..=N.
pub fn figure_eight_family(n: usize) -> Vec<DMatrix<f64>> {
    let quarter = n / 4;
    let d = 2 * (quarter - 1) + 1;
    // x_k = C_k y for k in 0..N.
    let mut curve = vec![DMatrix::<f64>::zeros(2, d); n];
    for (k, c) in curve.iter_mut().enumerate().take(quarter).skip(1) {
        c[(0, 2 * (k - 1))] = 1.0;
        c[(1, 2 * (k - 1) + 1)] = 1.0;
    }
    curve[quarter][(0, d - 1)] = 1.0;
    let reflect_long = DMatrix::from_diagonal(&DVector::from_vec(vec![1.0, -1.0]));
    let reflect_short = DMatrix::from_diagonal(&DVector::from_vec(vec![-1.0, 1.0]));
    for k in quarter + 1..=n / 2 {
        curve[k] = &reflect_long * &curve[n / 2 - k];
    }
    for k in n / 2 + 1..n {
        curve[k] = &reflect_short * &curve[k - n / 2];
    }
    (0..=n)
        .map(|k| {
            let mut a = DMatrix::zeros(6, d);
            for body in 0..3 {
                let c = &curve[(k + body * n / 3) % n];
                a.view_mut((2 * body, 0), (2, d)).copy_from(c);
            }
            a
        })
        .collect()
}
