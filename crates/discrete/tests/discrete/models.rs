//! Models shared by the tests, with their closed forms.

use noether_core::{Lagrangian, Scalar};

/// Simple pendulum with m = l = g = 1: L = ½ θ̇² + cos θ.
pub struct Pendulum;
impl Lagrangian for Pendulum {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * v[0] * 0.5 + q[0].cos()
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}

/// Period of the pendulum released from rest at θ₀: T = 4 K(sin(θ₀/2)) (with √(l/g) = 1).
pub fn pendulum_period(theta0: f64) -> f64 {
    4.0 * noether_testkit::closed_form::elliptic_k((0.5 * theta0).sin())
}

/// Kepler problem with μ = 1 in the plane: L = ½|q̇|² + 1/|q|.
pub struct Kepler;
impl Lagrangian for Kepler {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + v[1] * v[1]) * 0.5 + (q[0] * q[0] + q[1] * q[1]).sqrt().recip()
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}

/// Initial pericentre state of a Kepler orbit with a = 1, eccentricity e (period 2π):
/// q = (1 − e, 0), q̇ = (0, √((1 + e)/(1 − e))).
pub fn kepler_start(e: f64) -> ([f64; 2], [f64; 2]) {
    ([1.0 - e, 0.0], [0.0, ((1.0 + e) / (1.0 - e)).sqrt()])
}

/// The paper's two coupled chains (SEEDS part 3) as a plain Lagrangian: n unit masses per chain,
/// coordinates q = (q_t¹…q_tⁿ, q_b¹…q_bⁿ),
/// `V = (k1/2) Σ_{i<n} [(q_t^{i+1} − q_t^i − l)² + (q_b^{i+1} − q_b^i − l)²] + k2 Σ_{i,j} exp(−(q_t^i − q_b^j)²/(2σ²))`.
pub struct Chains {
    pub n: usize,
    pub k1: f64,
    pub k2: f64,
    pub sigma: f64,
}

impl Chains {
    pub fn paper() -> Self {
        Chains {
            n: 20,
            k1: 1.0,
            k2: 0.001,
            sigma: 0.1,
        }
    }

    /// ∇V written out by hand.
    pub fn grad_v(&self, q: &[f64]) -> Vec<f64> {
        let (n, l) = (self.n, 1.0 / self.n as f64);
        let mut g = vec![0.0; 2 * n];
        for c in 0..2 {
            for i in 0..n - 1 {
                let (a, b) = (c * n + i, c * n + i + 1);
                let f = self.k1 * (q[b] - q[a] - l);
                g[b] += f;
                g[a] -= f;
            }
        }
        for i in 0..n {
            for j in 0..n {
                let d = q[i] - q[n + j];
                let f = -self.k2 * d / (self.sigma * self.sigma)
                    * (-d * d / (2.0 * self.sigma * self.sigma)).exp();
                g[i] += f;
                g[n + j] -= f;
            }
        }
        g
    }

    /// The paper's start: both chains at spring equilibrium (spacing l), the top one shifted by −3.
    pub fn start(&self) -> Vec<f64> {
        let l = 1.0 / self.n as f64;
        (0..2 * self.n)
            .map(|k| {
                if k < self.n {
                    k as f64 * l - 3.0
                } else {
                    (k - self.n) as f64 * l
                }
            })
            .collect()
    }
}

impl Lagrangian for Chains {
    fn dof(&self) -> usize {
        2 * self.n
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (n, l) = (self.n, 1.0 / self.n as f64);
        let mut t = D::zero();
        for vi in v {
            t += *vi * *vi * 0.5;
        }
        let mut pot = D::zero();
        for c in 0..2 {
            for i in 0..n - 1 {
                let s = q[c * n + i + 1] - q[c * n + i] - l;
                pot += s * s * (0.5 * self.k1);
            }
        }
        for i in 0..n {
            for j in 0..n {
                let d = q[i] - q[n + j];
                pot += (-(d * d) / (2.0 * self.sigma * self.sigma)).exp() * self.k2;
            }
        }
        t - pot
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}
