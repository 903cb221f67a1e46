//! Hénon-Heiles and the unit double pendulum as Hamiltonians: the nonlinear and chaotic models of the
//! tangent-flow tests, the Lyapunov spectra and the integrators' self-checks.
//!
//! Used by noether-core's tangent tests (`tests/tangent/`), noether-analysis' Lyapunov tests, and the
//! gallery's `symplecticity_check` and `lyapunov_spectrum` examples.

use noether_core::{Hamiltonian, Scalar};

/// Hénon-Heiles, H = ½(p₁² + p₂²) + ½(q₁² + q₂²) + q₁²q₂ − q₂³/3: nonlinear, with third derivatives of
/// unit size; chaotic above E ≈ 1/8.
#[derive(Debug, Clone, Copy)]
pub struct HenonHeiles;

impl Hamiltonian for HenonHeiles {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        (p[0] * p[0] + p[1] * p[1] + q[0] * q[0] + q[1] * q[1]) * 0.5 + q[0] * q[0] * q[1]
            - q[1].powi(3) / 3.0
    }
}

/// Double pendulum with unit masses and rods in gravity g, angles from the downward vertical, in closed
/// form: the Legendre transform of L = θ̇₁² + ½θ̇₂² + θ̇₁θ̇₂ cos Δ + 2g cos θ₁ + g cos θ₂ (Δ = θ₁ − θ₂),
/// H = (p₁² + 2p₂² − 2p₁p₂ cos Δ) / (2(1 + sin²Δ)) − 2g cos θ₁ − g cos θ₂.
#[derive(Debug, Clone, Copy)]
pub struct UnitDoublePendulum {
    /// Gravitational acceleration.
    pub g: f64,
}

impl Hamiltonian for UnitDoublePendulum {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let d = q[0] - q[1];
        let s = d.sin();
        (p[0] * p[0] + p[1] * p[1] * 2.0 - p[0] * p[1] * d.cos() * 2.0) / ((s * s + 1.0) * 2.0)
            - q[0].cos() * (2.0 * self.g)
            - q[1].cos() * self.g
    }
}
