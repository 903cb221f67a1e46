//! Hénon-Heiles and the unit double pendulum as Hamiltonians: the nonlinear and chaotic models of the
//! tangent-flow tests, the Lyapunov spectra and the integrators' self-checks.
//!
//! Used by noether-core's tangent tests (`tests/tangent/`), noether-analysis' Lyapunov and chaos
//! tests, and the gallery's `symplecticity_check`, `lyapunov_spectrum`, `poincare_henon_heiles` and
//! `megno_map` examples.

use noether_core::{Hamiltonian, Momenta, Potential, Scalar, Separable, State};

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

/// Its potential V = ½(q₁² + q₂²) + q₁²q₂ − q₂³/3, for `Natural::unit(HenonHeiles)` (L = ½|q̇|² − V).
impl Potential for HenonHeiles {
    fn dof(&self) -> usize {
        2
    }
    #[inline]
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        let (x, y) = (q[0], q[1]);
        (x * x + y * y) * 0.5 + x * x * y - y * y * y / 3.0
    }
}

/// H = ½|p|² + V(q) as T(p) + V(q), for `SeparableHamiltonian(HenonHeiles)` on (q, p).
impl Separable for HenonHeiles {
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

/// The point (y, p_y) of the surface of section x = 0 on the energy surface H = E, crossed with
/// p_x = √(2E − p_y² − y² + 2y³/3) > 0, as a state at t = 0; `None` where that root is not real and
/// positive (off the energy surface).
pub fn on_section(e: f64, y: f64, py: f64) -> Option<State<Momenta>> {
    let px2 = 2.0 * e - py * py - y * y + 2.0 * y * y * y / 3.0;
    (px2 > 0.0).then(|| State::with_momenta(0.0, [0.0, y], [px2.sqrt(), py]))
}

/// The kicks of a composition of kick-drift-kick steps with drift weights `gammas`, adjacent half kicks
/// merged: a₀ = γ₁/2, a_i = (γ_i + γ_{i+1})/2, a_s = γ_s/2.
pub fn merged_kicks(gammas: &[f64]) -> Vec<f64> {
    let mut kicks = vec![0.0; gammas.len() + 1];
    for (i, g) in gammas.iter().enumerate() {
        kicks[i] += 0.5 * g;
        kicks[i + 1] += 0.5 * g;
    }
    kicks
}

/// A symmetric composition of Störmer-Verlet steps with drift weights `gammas` (Kahan-Li 8's, say)
/// on Hénon-Heiles, written by hand: q̈ = (−q₁ − 2q₁q₂, −q₂ − q₁² + q₂²) in closed form, adjacent
/// half kicks merged and the last force reused, as `Composition` does. `steps` steps of size h from
/// (q, v); returns the end (q, v). The reference the benchmarks time a composition against.
pub fn composition_by_hand(
    gammas: &[f64],
    steps: usize,
    h: f64,
    q: [f64; 2],
    v: [f64; 2],
) -> ([f64; 2], [f64; 2]) {
    let kicks = merged_kicks(gammas);
    let accel = |q: &[f64; 2]| [-q[0] - 2.0 * q[0] * q[1], -q[1] - q[0] * q[0] + q[1] * q[1]];
    let (mut q, mut v) = (q, v);
    let mut a = accel(&q);
    for _ in 0..steps {
        for (i, &g) in gammas.iter().enumerate() {
            let c = kicks[i] * h;
            v = [v[0] + c * a[0], v[1] + c * a[1]];
            q = [q[0] + g * h * v[0], q[1] + g * h * v[1]];
            a = accel(&q);
        }
        let c = kicks[gammas.len()] * h;
        v = [v[0] + c * a[0], v[1] + c * a[1]];
    }
    (q, v)
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
