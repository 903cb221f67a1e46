//! The double pendulum: two bobs on massless rods, angles θ₁, θ₂ from the downward vertical,
//!
//! L = ½ (m₁ + m₂) l₁² θ̇₁² + ½ m₂ l₂² θ̇₂² + m₂ l₁ l₂ θ̇₁ θ̇₂ cos(θ₁ − θ₂)
//!     + (m₁ + m₂) g l₁ cos θ₁ + m₂ g l₂ cos θ₂.
//!
//! Released from θ₁ = θ₂ = 2 rad the motion is chaotic (the lower bob flips over the top irregularly),
//! yet the energy h = Σ θ̇ ∂L/∂θ̇ − L is a constant of the motion since L has no explicit t.
//!
//! The mass matrix M(θ₁ − θ₂) depends on the configuration, so the system is not separable and the
//! explicit symplectic compositions do not apply; Gauss-Legendre collocation does (symplectic for any
//! Hamiltonian). It integrates Hamilton's equations of the H that noether builds from L by the Legendre
//! transform (`LegendreTransform`: q̇ from p by Newton on the AD mass matrix, H = p·q̇ − L, its
//! derivatives exact by the implicit-function theorem), so no Hamiltonian is written by hand; the
//! example checks that H(q, ∂L/∂q̇) equals the energy function h of the Lagrangian.
//!
//! The driver records the energy with an observer every 0.01 time units and counts the lower rod's
//! flips over the top with an event (θ₂ passing an odd multiple of π, where cos(θ₂/2) changes sign).
//!
//! Run: `cargo run --release --features examples --example double_pendulum` (the path and the energy error go to
//! `gallery-out/`).

use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use std::process::ExitCode;

/// The double pendulum, L = ½(m1+m2) l1² θ̇1² + ½ m2 l2² θ̇2² + m2 l1 l2 θ̇1 θ̇2 cos(θ1 − θ2)
/// + (m1+m2) g l1 cos θ1 + m2 g l2 cos θ2 (the model of core's AD tests).
pub use noether_testkit::systems::DoublePendulum;

/// Position of the lower bob (x to the right, y up, pivot at the origin).
pub fn lower_bob(dp: &DoublePendulum, q: &[f64]) -> (f64, f64) {
    (
        dp.l1 * q[0].sin() + dp.l2 * q[1].sin(),
        -dp.l1 * q[0].cos() - dp.l2 * q[1].cos(),
    )
}

/// Length of the run.
pub const T_END: f64 = 60.0;

/// Runs the example.
///
/// Method: Gauss-Legendre 6 (three-stage collocation, symplectic, Newton with the exact AD Jacobian)
/// on Hamilton's equations with h = 4e-3. A symplectic method keeps the energy error bounded, oscillating
/// instead of drifting; its size is O(h⁶) and is set by the fast phases (the lower bob whipping over the
/// top). Measured: max |ΔE|/|E₀| = 4.6e-10 over the run (RK4 at h = 5e-4, 8x the steps, drifted to
/// 6.7e-10 in 20 % more CPU time). Tolerance 5e-9 (tightened from 1e-8): ten times the measurement, room
/// for the chaotic trajectory to differ between platforms (rounding differences change which chaotic path
/// is followed, and the energy error depends on the path by a factor of a few).
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let dp = DoublePendulum {
        m1: 1.0,
        m2: 1.0,
        l1: 1.0,
        l2: 1.0,
        g: 9.81,
    };
    let h = 4e-3;
    let el = EulerLagrange::new(dp);
    let (q0, v0) = ([2.0, 2.0], [0.0, 0.0]);
    let e0 = el.energy(0.0, &q0, &v0)?;
    // The Hamiltonian is the Legendre transform of L: H(q, p) with p = ∂L/∂q̇ equals h(q, q̇). Checked at
    // a generic moving state (the start is at rest, where the kinetic part vanishes).
    let ham = HamiltonEquations::new(LegendreTransform::new(dp));
    let (qt, vt) = ([0.7, -1.9], [1.3, -2.1]);
    let mut pt = [0.0; 2];
    el.momenta(0.0, &qt, &vt, &mut pt)?;
    let legendre = (ham.energy(0.0, &qt, &pt)?, el.energy(0.0, &qt, &vt)?);
    let mut p0 = [0.0; 2];
    el.momenta(0.0, &q0, &v0, &mut p0)?;
    let steps = (T_END / h).round() as usize;
    let sample = (0.01 / h).round().max(1.0) as usize;
    let sol = Driver::with_step(Gauss::gauss6(&ham), State::with_momenta(0.0, q0, p0), h)?
        .save(Save::Every(sample))?
        .observe("energy error", |s: &State<Momenta>| {
            ham.energy(s.t, s.q.as_slice(), s.p().as_slice())
                .map(|en| ((en - e0) / e0).abs())
        })
        // The lower rod flips over the top when θ₂ passes an odd multiple of π: cos(θ₂/2) = 0.
        .event(Event::new("flip", |s: &State<Momenta>| (0.5 * s.q[1]).cos()))
        .run_steps(steps)?;
    let errors = sol.observed("energy error")?;
    let max_err = errors.iter().fold(0.0_f64, |m, &e| m.max(e));
    // Row 0 is the start (error 0, off a log axis).
    let energy_err: Vec<(f64, f64)> = sol.times()[1..]
        .iter()
        .copied()
        .zip(errors[1..].iter().copied())
        .collect();
    let path: Vec<(f64, f64)> = (1..sol.len())
        .filter(|&i| sol.times()[i] <= 20.0)
        .map(|i| lower_bob(&dp, sol.q(i)))
        .collect();
    let flips = sol.event_times("flip")?.len();
    let mut report = Report::default();
    // H(q, ∂L/∂q̇) = h(q, q̇) = q̇·∂L/∂q̇ − L: the same number computed two ways (rounding: 1e-14).
    report.checks.push(Check::rel(
        "double_pendulum",
        "H(q, ∂L/∂q̇) vs energy function h(q, q̇) of L",
        legendre.0,
        legendre.1,
        1e-14,
    ));
    // h is conserved: E(t) = E(0) for all t. Max over the run (sampled every 0.01); tolerance above.
    report.checks.push(Check::abs(
        "double_pendulum",
        format!("max |E − E0|/|E0| over t ≤ {T_END}"),
        max_err,
        0.0,
        5e-9,
    ));
    let path_fig = Figure::new("Double pendulum from θ1 = θ2 = 2 rad: path of the lower bob, t ≤ 20")
        .x_label("x / l")
        .y_label("y / l")
        .equal_aspect()
        .series(
            format!("lower bob ({flips} flips over the top by t = {T_END})"),
            path,
        );
    report.save(opts, &path_fig, "double_pendulum_path.svg")?;
    let energy_fig = Figure::new(format!(
        "Double pendulum: relative energy error, Gauss-Legendre 6 (h = {h})"
    ))
    .x_label("t")
    .y_label("|E − E0| / |E0|")
    .log_y()
    .series("Gauss-Legendre 6", energy_err);
    report.save(opts, &energy_fig, "double_pendulum_energy_error.svg")?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main("double_pendulum", run)
}
