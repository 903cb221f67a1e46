//! A particle's fixed parameters (mass, charge) and 3-vectors.

use crate::{Error, Result};

/// A point in space or a velocity, `[x, y, z]` (1D and 2D motion keep the unused components at 0).
pub type Vec3 = [f64; 3];

/// The fixed parameters of a particle: mass m > 0 and charge e. Its position and velocity live in the
/// system's state (contiguous arrays of length 3N).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Particle {
    /// Mass m (finite, > 0).
    pub mass: f64,
    /// Charge e (finite; 0 for neutral particles).
    pub charge: f64,
}

impl Particle {
    /// A neutral particle of mass `mass`.
    pub fn new(mass: f64) -> Self {
        Particle { mass, charge: 0.0 }
    }

    /// A particle of mass `mass` and charge `charge`.
    pub fn charged(mass: f64, charge: f64) -> Self {
        Particle { mass, charge }
    }

    /// Checks m finite and > 0 with 1/m finite, e finite (particle number `index` for the message).
    pub fn validate(&self, index: usize) -> Result<()> {
        if !(self.mass.is_finite() && self.mass > 0.0 && self.mass.recip().is_finite()) {
            return Err(Error::InvalidMass {
                index,
                mass: self.mass,
            });
        }
        if !self.charge.is_finite() {
            return Err(Error::Core(noether_core::Error::NonFinite {
                what: "charge",
                index,
            }));
        }
        Ok(())
    }
}

/// Particle `i` of a flat array of length 3N (one bounds check for the three components).
#[inline(always)]
pub(crate) fn get3<T: Copy>(x: &[T], i: usize) -> [T; 3] {
    let a = &x[3 * i..3 * i + 3];
    [a[0], a[1], a[2]]
}

/// Adds `f` to particle `i` of a flat array.
#[inline(always)]
pub(crate) fn add3<T: Copy + std::ops::AddAssign>(out: &mut [T], i: usize, f: [T; 3]) {
    let o = &mut out[3 * i..3 * i + 3];
    o[0] += f[0];
    o[1] += f[1];
    o[2] += f[2];
}

/// Subtracts `f` from particle `i` of a flat array.
#[inline(always)]
pub(crate) fn sub3<T: Copy + std::ops::SubAssign>(out: &mut [T], i: usize, f: [T; 3]) {
    let o = &mut out[3 * i..3 * i + 3];
    o[0] -= f[0];
    o[1] -= f[1];
    o[2] -= f[2];
}
