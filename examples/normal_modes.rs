//! Equilibria and small oscillations with noether-analysis: each system is written once as a
//! Lagrangian; its equilibrium is found by minimising the effective potential U(q) = −L(q, 0) (argmin's
//! trust region, exact Hessian by dual numbers, Newton polish), classified by the Hessian's eigenvalues,
//! and its normal modes solve K X = ω² M X with M = ∂²L/∂q̇² and K = ∂²U/∂q² (Cholesky of M).
//!
//! Tolerances: M and K are exact, so the frequencies carry only the rounding of the symmetric
//! eigen-solver (a few ulps times the condition number of M) and of the polished equilibrium. Each
//! tolerance is 2–5× the error measured (given beside it).
//!
//! Systems: two coupled pendula, a chain of ten masses, a triangle of springs (with its three zero
//! modes). The bead on a rotating hoop, whose bottom turns from a minimum into a maximum, is the example
//! `hoop_equilibria`.
//!
//! Run: `cargo run --release --features examples --example normal_modes`.

use noether::prelude::*;

use noether::analysis::{normal_modes, EffectivePotential, EquilibriumFinder};
use noether_gallery::{BoxError, Check, Options, Report};
use std::f64::consts::PI;
use std::process::ExitCode;

const NAME: &str = "normal_modes";

/// Two pendula (mass m, length l) whose bobs are joined by a spring k: L = ½ m l² (θ̇₁² + θ̇₂²)
/// + m g l (cos θ₁ + cos θ₂) − ½ k l² (sin θ₁ − sin θ₂)².
pub struct CoupledPendula {
    /// Bob mass.
    pub m: f64,
    /// Length.
    pub l: f64,
    /// Gravity.
    pub g: f64,
    /// Spring constant.
    pub k: f64,
}

impl Lagrangian for CoupledPendula {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (m, l) = (self.m, self.l);
        let stretch = (q[0].sin() - q[1].sin()) * l;
        (v[0] * v[0] + v[1] * v[1]) * (0.5 * m * l * l) + (q[0].cos() + q[1].cos()) * (m * self.g * l)
            - stretch * stretch * (0.5 * self.k)
    }
}

/// N masses on a line between walls at 0 and (N+1)a, joined by springs k of natural length a.
pub struct Chain {
    /// Number of masses.
    pub n: usize,
    /// Mass.
    pub m: f64,
    /// Spring constant.
    pub k: f64,
    /// Natural length.
    pub a: f64,
}

impl Lagrangian for Chain {
    fn dof(&self) -> usize {
        self.n
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let kinetic = v.iter().fold(D::zero(), |s, vi| s + *vi * *vi) * (0.5 * self.m);
        let wall = D::from((self.n + 1) as f64 * self.a);
        let mut prev = D::zero();
        let mut pot = D::zero();
        for x in q.iter().copied().chain(std::iter::once(wall)) {
            let s = x - prev - self.a;
            pot += s * s;
            prev = x;
        }
        kinetic - pot * (0.5 * self.k)
    }
}

/// Three equal masses in the plane joined pairwise by equal springs of natural length a.
pub struct Triangle {
    /// Mass.
    pub m: f64,
    /// Spring constant.
    pub k: f64,
    /// Natural length.
    pub a: f64,
}

impl Lagrangian for Triangle {
    fn dof(&self) -> usize {
        6
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let kinetic = v.iter().fold(D::zero(), |s, vi| s + *vi * *vi) * (0.5 * self.m);
        let mut pot = D::zero();
        for (i, j) in [(0, 1), (1, 2), (2, 0)] {
            let (dx, dy) = (q[2 * i] - q[2 * j], q[2 * i + 1] - q[2 * j + 1]);
            let s = (dx * dx + dy * dy).sqrt() - self.a;
            pot += s * s;
        }
        kinetic - pot * (0.5 * self.k)
    }
}

/// Runs the checks.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let finder = EquilibriumFinder::default();
    let mut checks = Vec::new();

    // Coupled pendula: ω² = g/l (in phase) and g/l + 2k/m (out of phase).
    let p = CoupledPendula {
        m: 0.7,
        l: 1.3,
        g: 9.81,
        k: 2.5,
    };
    let eq = finder.minimize(&EffectivePotential::new(&p), &[0.4, -0.2])?;
    // Newton lands on θ = 0, where doubles are dense (measured 4.0e-28): 2e-27.
    checks.push(Check::abs(
        NAME,
        "pendula: equilibrium |θ|",
        eq.q.amax(),
        0.0,
        2e-27,
    ));
    let modes = normal_modes(&p, eq.q.as_slice())?;
    // Measured 2.4e-16 and 3.6e-16 (ω₂²): 1e-15.
    checks.push(Check::rel(
        NAME,
        "pendula: ω₁² vs g/l",
        modes.omega2[0],
        p.g / p.l,
        1e-15,
    ));
    checks.push(Check::rel(
        NAME,
        "pendula: ω₂² vs g/l + 2k/m",
        modes.omega2[1],
        p.g / p.l + 2.0 * p.k / p.m,
        1e-15,
    ));

    // Chain of N = 10 masses with fixed ends, started away from equilibrium:
    // ω_j = 2 sqrt(k/m) sin(jπ / (2(N+1))).
    let c = Chain {
        n: 10,
        m: 0.5,
        k: 3.0,
        a: 0.25,
    };
    let q0: Vec<f64> = (1..=c.n)
        .map(|i| i as f64 * c.a + 0.08 * (i as f64).sin())
        .collect();
    let eq = finder.minimize(&EffectivePotential::new(&c), &q0)?;
    let spacing_err =
        eq.q.iter()
            .enumerate()
            .map(|(i, x)| (x - (i + 1) as f64 * c.a).abs())
            .fold(0.0, f64::max);
    // Measured 0 (x ≤ 2.5, a few ulps is ~1e-15): 1e-15.
    checks.push(Check::abs(
        NAME,
        "chain: equilibrium max |x_i − i a|",
        spacing_err,
        0.0,
        1e-15,
    ));
    let w = normal_modes(&c, eq.q.as_slice())?.frequencies();
    for j in [1, 2, 5, 10] {
        let exact = 2.0 * (c.k / c.m).sqrt() * (j as f64 * PI / (2.0 * (c.n + 1) as f64)).sin();
        // Measured 4.8e-15 for ω₁ (the smallest, most amplified by the eigen-solver's rounding),
        // ≤ 4.2e-16 for the others: 1e-14.
        checks.push(Check::rel(
            NAME,
            format!("chain N=10: ω_{j} vs 2 sqrt(k/m) sin(jπ/(2(N+1)))"),
            w[j - 1],
            exact,
            1e-14,
        ));
    }

    // Triangle of equal masses and springs: 3 zero modes (2 translations, 1 rotation); the vibrations
    // are the doubly degenerate ω² = 3k/(2m) and the breathing mode ω² = 3k/m.
    let tri = Triangle {
        m: 2.0,
        k: 5.0,
        a: 1.5,
    };
    let eq = finder.minimize(&EffectivePotential::new(&tri), &[0.1, -0.2, 1.7, 0.1, 0.6, 1.2])?;
    let modes = normal_modes(&tri, eq.q.as_slice())?;
    checks.push(Check::abs(
        NAME,
        "triangle: number of zero modes",
        modes.zero_modes as f64,
        3.0,
        0.0,
    ));
    let top = modes.omega2[5];
    let zero = (0..3).map(|k| modes.omega2[k].abs()).fold(0.0, f64::max) / top;
    // Measured 1.8e-16: 1e-15.
    checks.push(Check::abs(
        NAME,
        "triangle: max |ω²| of zero modes / ω²_max",
        zero,
        0.0,
        1e-15,
    ));
    let (m, k) = (tri.m, tri.k);
    // Measured 4.7e-16, 2.4e-16, 2.4e-16 (ω₄², ω₅², ω₆²): 2e-15.
    checks.push(Check::rel(
        NAME,
        "triangle: ω₄² vs 3k/(2m)",
        modes.omega2[3],
        1.5 * k / m,
        2e-15,
    ));
    checks.push(Check::rel(
        NAME,
        "triangle: ω₅² vs 3k/(2m)",
        modes.omega2[4],
        1.5 * k / m,
        2e-15,
    ));
    checks.push(Check::rel(
        NAME,
        "triangle: ω₆² vs 3k/m (breathing)",
        modes.omega2[5],
        3.0 * k / m,
        2e-15,
    ));
    Ok(Report {
        checks,
        ..Default::default()
    })
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
