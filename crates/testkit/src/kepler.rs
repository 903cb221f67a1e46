//! Kepler's problem as the benchmarks run it (μ = 1, a = 1, e = 0.6, from pericentre, 100 orbits).
//!
//! Used by noether-core's `rates`, `nystrom`, `ias15` and `peer_dop853` benchmarks and the gallery's
//! `work_precision` benchmark; the peer's right-hand side is in the module
//! `peer` (feature `peer`).

use noether_core::{Potential, Scalar, Separable, State};

/// V = −1/|q| (μ = 1), with `#[inline]` as the scalar module's docs ask of a model.
pub struct Kepler;
impl Potential for Kepler {
    fn dof(&self) -> usize {
        2
    }
    #[inline]
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        -(q[0] * q[0] + q[1] * q[1]).sqrt().recip()
    }
}

/// H = ½|p|² + V(q) for `SeparableHamiltonian` (with unit mass p = q̇: the same start, the same orbit).
impl Separable for Kepler {
    fn dof(&self) -> usize {
        2
    }
    #[inline]
    fn kinetic<D: Scalar>(&self, p: &[D]) -> D {
        (p[0] * p[0] + p[1] * p[1]) * 0.5
    }
    #[inline]
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        Potential::potential(self, q)
    }
}

/// The eccentricity.
pub const E: f64 = 0.6;
/// 100 periods of the orbit of semi-major axis 1.
pub const T_END: f64 = 200.0 * std::f64::consts::PI;

/// Pericentre with a = 1: q = (1 − e, 0), q̇ = (0, sqrt((1 + e)/(1 − e))).
pub fn start() -> ([f64; 2], [f64; 2]) {
    ([1.0 - E, 0.0], [0.0, ((1.0 + E) / (1.0 - E)).sqrt()])
}

/// [`start`] as a state at t = 0.
pub fn start_state() -> State {
    let (q, v) = start();
    State::new(0.0, q, v)
}
