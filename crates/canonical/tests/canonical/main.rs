//! Integration tests of noether-canonical: one test binary, one module per part of the crate. Test
//! names say where the truth comes from (`closed_form_*`, `identity_*`, `conserves_*`, `errors_*`).

mod action_angle;
mod generating;
mod hamilton_jacobi;
mod poisson;
mod routh;
mod section;
mod transform;

/// Shared helpers: a small deterministic generator of test points, and the models several modules use.
pub mod common {
    use noether_core::{Hamiltonian, Scalar};

    /// xorshift64*: reproducible pseudo-random test points without a dependency.
    pub struct Rng(pub u64);

    impl Rng {
        /// Uniform in [lo, hi).
        pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            let u = (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64;
            lo + (hi - lo) * u
        }
        /// n values uniform in [lo, hi).
        pub fn vec(&mut self, n: usize, lo: f64, hi: f64) -> Vec<f64> {
            (0..n).map(|_| self.uniform(lo, hi)).collect()
        }
    }

    /// Kepler problem in Cartesian coordinates, H = |p|²/2m − k/|q| (n = 3).
    #[derive(Debug, Clone, Copy)]
    pub struct Kepler3 {
        /// Mass.
        pub m: f64,
        /// Strength of the attraction.
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
}
