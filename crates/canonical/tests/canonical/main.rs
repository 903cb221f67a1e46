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

    /// The models several modules use, shared with the gallery.
    pub use noether_testkit::canonical::{Kepler3, Planar};
}
