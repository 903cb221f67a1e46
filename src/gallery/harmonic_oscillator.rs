//! The harmonic oscillator L = ½ m q̇² − ½ k q² over 1000 periods against its exact solution
//! q(t) = q₀ cos ωt + (v₀/ω) sin ωt, ω = sqrt(k/m).

use super::plot::{BoxError, Figure};
use super::{Check, Options, Report};
use noether_core::prelude::*;
use std::f64::consts::PI;

/// Mass `m` on a spring of stiffness `k`.
#[derive(Debug, Clone, Copy)]
pub struct Oscillator {
    /// Mass.
    pub m: f64,
    /// Spring constant.
    pub k: f64,
}

impl Lagrangian for Oscillator {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * v[0] * (0.5 * self.m) - q[0] * q[0] * (0.5 * self.k)
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}

impl Oscillator {
    /// Angular frequency ω = sqrt(k/m).
    pub fn omega(&self) -> f64 {
        (self.k / self.m).sqrt()
    }

    /// Exact solution (q(t), q̇(t)) from (q₀, v₀) at t = 0.
    pub fn exact(&self, q0: f64, v0: f64, t: f64) -> (f64, f64) {
        let w = self.omega();
        let (s, c) = (w * t).sin_cos();
        (q0 * c + v0 / w * s, -q0 * w * s + v0 * c)
    }
}

/// Number of periods simulated.
pub const PERIODS: usize = 1000;

/// Steps per period.
const STEPS_PER_PERIOD: usize = 400;

/// Runs the example.
///
/// Method: classical RK4, h = T/400 (ωh = π/200). Its amplification factor per step,
/// R(iωh) = 1 − (ωh)²/2 + (ωh)⁴/24 + i(ωh − (ωh)³/6), has modulus 1 − (ωh)⁶/144 and phase error
/// (ωh)⁵/120 per step; over N = 4·10⁵ steps that is an amplitude loss of N(ωh)⁶/144 ≈ 4.2e-8 and a phase
/// lag of N(ωh)⁵/120 ≈ 3.2e-6 rad. The tolerances below are these leading-order predictions × ~3.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let osc = Oscillator {
        m: 1.0,
        k: 4.0 * PI * PI, // ω = 2π: one period per unit time
    };
    let (q0, v0) = (1.0, 0.5);
    let w = osc.omega();
    let amplitude = (q0 * q0 + (v0 / w) * (v0 / w)).sqrt();
    let period = 2.0 * PI / w;
    let h = period / STEPS_PER_PERIOD as f64;
    let el = EulerLagrange::new(osc);
    let e0 = el.energy(0.0, &[q0], &[v0])?;
    let mut run = Trajectory::new(Rk4::new(el), State::new(0.0, [q0], [v0]), h)?;

    let mut max_err = 0.0_f64;
    let mut errors = Vec::new();
    let mut energy_err = Vec::new();
    for step in 1..=PERIODS * STEPS_PER_PERIOD {
        let s = run.next().ok_or("trajectory ended")??;
        let (qe, _) = osc.exact(q0, v0, s.t);
        let err = (s.q[0] - qe).abs() / amplitude;
        max_err = max_err.max(err);
        if step % STEPS_PER_PERIOD == 0 {
            errors.push((s.t / period, err));
            let e = run
                .stepper()
                .system()
                .energy(s.t, s.q.as_slice(), s.v.as_slice())?;
            energy_err.push((s.t / period, ((e - e0) / e0).abs()));
        }
    }
    let end = run.state().clone();
    let (qe, ve) = osc.exact(q0, v0, end.t);
    let mut report = Report::default();
    // q(1000 T) = q₀ exactly; error dominated by the phase lag ≈ 3.2e-6 rad × amplitude → 1e-5.
    report.checks.push(Check::abs(
        "harmonic_oscillator",
        "q(1000T)/A",
        end.q[0] / amplitude,
        qe / amplitude,
        1e-5,
    ));
    report.checks.push(Check::abs(
        "harmonic_oscillator",
        "q̇(1000T)/(ωA)",
        end.v[0] / (w * amplitude),
        ve / (w * amplitude),
        1e-5,
    ));
    // max_t |q(t) − q_exact(t)| / A over all 4·10⁵ steps: the phase lag grows linearly, so its maximum
    // is at the end, ≈ 3.2e-6.
    report.checks.push(Check::abs(
        "harmonic_oscillator",
        "max |q − q_exact|/A over 1000 periods",
        max_err,
        0.0,
        1e-5,
    ));
    // Energy ½ m q̇² + ½ k q² decays as the squared modulus: 2 × 4.2e-8 ≈ 8.3e-8; tolerance 3e-7.
    let e_end = run
        .stepper()
        .system()
        .energy(end.t, end.q.as_slice(), end.v.as_slice())?;
    report.checks.push(Check::rel(
        "harmonic_oscillator",
        "energy(1000T)",
        e_end,
        e0,
        3e-7,
    ));
    Figure::new("Harmonic oscillator, RK4 (h = T/400): error against the exact solution")
        .x_label("t / T")
        .y_label("error")
        .log_y()
        .series("|q − q_exact| / A", errors)
        .series("|E − E0| / E0", energy_err)
        .save_in(opts, "harmonic_oscillator_error.svg", &mut report)?;
    Ok(report)
}
