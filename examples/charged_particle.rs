//! A charged particle in uniform electric and magnetic fields, through the velocity-dependent
//! potential of the Lorentz force:
//!
//! L = ½ m |v|² + e v·A(r) − e φ(r),   A = ½ B × r,   φ = −E·r.
//!
//! Lagrange's equations give m r̈ = e (E + v × B). Checks against closed forms: with E = 0 the particle
//! circles at the cyclotron frequency ω = eB/m on a circle of radius m v⊥/(eB), moves uniformly along
//! B, and keeps its kinetic energy. With E ⊥ B its guiding centre drifts at E × B / B²: the example
//! `exb_drift`, which uses this model.
//!
//! The integrator is Gauss-Legendre collocation of order 6, symplectic for any Hamiltonian, on the H
//! that noether builds from L by the Legendre transform (`LegendreTransform`; the mass matrix is
//! constant, so q̇ = (p − eA)/m comes out in one solve): H = |p − eA(r)|²/(2m) + e φ(r), with the
//! canonical momentum p = ∂L/∂v = m v + eA. The system is linear, so the collocation is the diagonal Padé approximant of
//! the exact flow: |v| and the energy are kept to rounding (Gauss methods conserve quadratic invariants)
//! and only the phase is approximated, to O((ωh)⁷) per step.
//!
//! The driver saves every step and an observer records the velocity v = (p − eA)/m beside each state.
//!
//! Run: `cargo run --release --features examples --example charged_particle` (the trajectories go to `gallery-out/`).

use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use std::f64::consts::PI;
use std::process::ExitCode;

/// A particle of mass `m` and charge `e` in the uniform fields `b` (magnetic) and `efield` (electric).
#[derive(Debug, Clone, Copy)]
pub struct ChargedParticle {
    /// Mass.
    pub m: f64,
    /// Charge.
    pub e: f64,
    /// Magnetic field B.
    pub b: [f64; 3],
    /// Electric field E.
    pub efield: [f64; 3],
}

impl ChargedParticle {
    /// The vector potential A = ½ B × r of the uniform field B.
    pub fn vector_potential<D: Scalar>(&self, r: &[D]) -> [D; 3] {
        let [bx, by, bz] = self.b;
        [
            (r[2] * by - r[1] * bz) * 0.5,
            (r[0] * bz - r[2] * bx) * 0.5,
            (r[1] * bx - r[0] * by) * 0.5,
        ]
    }

    /// The scalar potential φ = −E·r of the uniform field E.
    pub fn scalar_potential<D: Scalar>(&self, r: &[D]) -> D {
        -(r[0] * self.efield[0] + r[1] * self.efield[1] + r[2] * self.efield[2])
    }

    /// Velocity v = (p − eA(r))/m from the canonical momentum p.
    pub fn velocity(&self, r: &[f64], p: &[f64]) -> [f64; 3] {
        let a = self.vector_potential(r);
        [0, 1, 2].map(|i| (p[i] - self.e * a[i]) / self.m)
    }
}

impl Lagrangian for ChargedParticle {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, r: &[D], v: &[D]) -> D {
        let a = self.vector_potential(r);
        let v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        v2 * (0.5 * self.m) + (v[0] * a[0] + v[1] * a[1] + v[2] * a[2]) * self.e
            - self.scalar_potential(r) * self.e
    }
    fn constant_mass_matrix(&self) -> bool {
        true // ∂²L/∂v² = m I: v·A is linear in v
    }
}

/// Euclidean norm.
pub fn norm(x: [f64; 3]) -> f64 {
    (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

impl ChargedParticle {
    /// Cyclotron frequency ω = |e| B / m.
    pub fn cyclotron_frequency(&self) -> f64 {
        self.e.abs() * norm(self.b) / self.m
    }

    /// E × B drift velocity E × B / B².
    pub fn drift_velocity(&self) -> [f64; 3] {
        let b2 = norm(self.b).powi(2);
        cross(self.efield, self.b).map(|c| c / b2)
    }
}

/// A sampled run: times, positions and velocities after every step (initial state included).
pub struct Run {
    /// Times.
    pub t: Vec<f64>,
    /// Positions.
    pub r: Vec<[f64; 3]>,
    /// Velocities v = (p − eA)/m.
    pub v: Vec<[f64; 3]>,
}

/// Gauss-Legendre 6 on Hamilton's equations of the Legendre transform of L from r = 0 with velocity v0 (p = m v0 + eA(0) = m v0),
/// for `t_end / h` steps, every step saved with its velocity.
pub fn simulate(p: ChargedParticle, v0: [f64; 3], t_end: f64, h: f64) -> Result<Run, BoxError> {
    let start = State::with_momenta(0.0, [0.0; 3], v0.map(|v| p.m * v));
    let n = (t_end / h).round() as usize;
    let sol = Driver::with_step(
        Gauss::gauss6(HamiltonEquations::new(LegendreTransform::new(p))),
        start,
        h,
    )?
    .observe_each(["vx", "vy", "vz"], |s: &State<Momenta>, out: &mut [f64]| {
        out.copy_from_slice(&p.velocity(s.q.as_slice(), s.p().as_slice()));
        Ok(())
    })
    .run_steps(n)?;
    let (vx, vy, vz) = (sol.observed("vx")?, sol.observed("vy")?, sol.observed("vz")?);
    Ok(Run {
        t: sol.times().to_vec(),
        r: (0..sol.len())
            .map(|i| [sol.q(i)[0], sol.q(i)[1], sol.q(i)[2]])
            .collect(),
        v: (0..sol.len()).map(|i| [vx[i], vy[i], vz[i]]).collect(),
    })
}

/// Periods of gyration simulated.
pub const PERIODS: f64 = 20.0;
/// Steps per period of gyration.
pub const STEPS_PER_PERIOD: f64 = 100.0;

/// Runs the example.
///
/// Method: Gauss-Legendre 6 (three-stage collocation, symplectic) on Hamilton's equations with
/// h = T/100 (ωh = 2π/100), a tenth of the steps RK4 needed here. On this linear system one step is the
/// (3,3) Padé approximant of the exact rotation: its modulus is exactly 1, so |v|, the radius and the
/// energy are exact up to rounding and the Newton tolerance, and its phase error per step is
/// (3!)²/(6!·7!) (ωh)⁷ ≈ 1e-5 (ωh)⁷, a relative frequency error ≈ 1e-5 (ωh)⁶ = 6e-13 (measured
/// 6.3e-13; RK4 at h = T/1000 had 1.3e-11): tolerance 1e-11 on the frequency. What collocation
/// conserves up to rounding and its Newton residual is held near its measured error: ½m|v|² (measured
/// 2.4e-15: 1e-14), the radius (measured 2.2e-16, one rounding: 1e-15).
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let ex = "charged_particle";
    let mut report = Report::default();
    let magnetic = ChargedParticle {
        m: 1.0,
        e: 1.0,
        b: [0.0, 0.0, 2.0],
        efield: [0.0; 3],
    };
    let omega = magnetic.cyclotron_frequency();
    let period = 2.0 * PI / omega;
    let h = period / STEPS_PER_PERIOD;
    // v⊥ = 1 in the plane normal to B, 0.3 along B: a helix.
    let (v_perp, v_par) = (1.0, 0.3);
    let run = simulate(magnetic, [v_perp, 0.0, v_par], PERIODS * period, h)?;

    // Frequency: the velocity turns about B at ω; sum the signed angle between successive velocities.
    let mut angle = 0.0;
    for w in run.v.windows(2) {
        let (a, b) = (w[0], w[1]);
        angle += (a[0] * b[1] - a[1] * b[0]).atan2(a[0] * b[0] + a[1] * b[1]);
    }
    let t_end = *run.t.last().ok_or("empty run")?;
    // ω = eB/m (a positive charge turns clockwise about B, hence |angle|).
    report.checks.push(Check::rel(
        ex,
        "cyclotron frequency",
        angle.abs() / t_end,
        omega,
        1e-11,
    ));

    // Radius: the guiding centre is the time average of (x, y) over the whole periods simulated (trapezoid
    // rule, exact for a periodic signal); the radius is the RMS distance from it, m v⊥/(eB) in theory.
    let avg = |f: &dyn Fn(usize) -> f64| {
        let n = run.t.len() - 1;
        (0.5 * (f(0) + f(n)) + (1..n).map(f).sum::<f64>()) / n as f64
    };
    let (cx, cy) = (avg(&|i| run.r[i][0]), avg(&|i| run.r[i][1]));
    let rms = avg(&|i| (run.r[i][0] - cx).powi(2) + (run.r[i][1] - cy).powi(2)).sqrt();
    let radius = magnetic.m * v_perp / (magnetic.e.abs() * norm(magnetic.b));
    report
        .checks
        .push(Check::rel(ex, "cyclotron radius", rms, radius, 1e-15));
    // Uniform motion along B: z(t) = v∥ t, exact for any Runge-Kutta method up to rounding in the 2000
    // additions of z and the Newton tolerance (≤ N ε ≈ 2e-13; measured 2.2e-14, the driver's clock
    // t₀ + k h adds no rounding of its own): 1e-13.
    let z_end = run.r.last().ok_or("empty run")?[2];
    report.checks.push(Check::rel(
        ex,
        "z(20T) = v∥ t (free along B)",
        z_end,
        v_par * t_end,
        1e-13,
    ));
    // The magnetic force does no work: ½ m |v|² constant (a quadratic invariant, kept by collocation).
    let v_end = *run.v.last().ok_or("empty run")?;
    let ke = |v: [f64; 3]| 0.5 * magnetic.m * norm(v).powi(2);
    report.checks.push(Check::rel(
        ex,
        "kinetic energy (B only)",
        ke(v_end),
        ke(run.v[0]),
        1e-14,
    ));

    let xy = |run: &Run, periods: f64| -> Vec<(f64, f64)> {
        let n = (periods * STEPS_PER_PERIOD) as usize;
        run.r.iter().take(n + 1).map(|r| (r[0], r[1])).collect()
    };
    let fig = Figure::new("Charged particle in uniform B (ẑ): gyration")
        .x_label("x")
        .y_label("y")
        .equal_aspect()
        .series("B only: circle of radius mv⊥/(eB)", xy(&run, 1.0));
    report.save(opts, &fig, "charged_particle_trajectory.svg")?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main("charged_particle", run)
}
