//! A slider-crank from bodies and joints (noether-multibody): a crank of 0.3 on a hinge, a connecting
//! rod of 1 hinged at the crank pin, a piston sliding along x on a spring, the rod's end pinned to the
//! piston by a loop closure (`noether_testkit::multibody::SliderCrank`).
//!
//! 1. **The piston's position** x(θ) = r cos θ + √(l² − r² sin²θ) (the triangle of crank, rod and
//!    slide): the loop solved for the rod angle and the piston at 12 crank angles over a turn.
//! 2. **The crank torque** that holds the mechanism against the piston's spring, by virtual work
//!    u = k (x − x₀) dx/dθ with dx/dθ = −r sin θ − r² sin θ cos θ/√(l² − r² sin²θ): under it the
//!    crank's acceleration at rest vanishes, at the same 12 angles.
//! 3. **Released**, the mechanism oscillates about the spring's rest; RATTLE (h = 10⁻³, 10⁴ steps)
//!    keeps the loop closed and the piston on x(θ(t)) along the whole run, the energy bounded.
//!
//! Run: `cargo run --release --features examples --example slider_crank`.

use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::multibody::{rattle_run, SliderCrank};
use std::process::ExitCode;

const NAME: &str = "slider_crank";

/// The worst relative errors of the piston's position and of the holding torque over 12 angles.
fn statics(sc: &SliderCrank) -> Result<(f64, f64), BoxError> {
    let (mut place, mut held) = (0.0_f64, 0.0_f64);
    for k in 0..12 {
        let theta = -3.0 + 0.5 * k as f64;
        let (q, _) = sc.reduced_near(theta)?.state(0.0, &[theta], &[0.0]);
        place = place.max((q[2] - sc.piston(theta)).abs() / sc.piston(theta));
        let holding = sc.crank_acceleration(theta, sc.holding_torque(theta))?;
        held = held.max(holding.abs() / sc.crank_acceleration(theta, 0.0)?.abs());
    }
    Ok((place, held))
}

/// Runs the example.
///
/// Tolerances: the statics to rounding (measured 1.3e-16 for x, 1.4e-15 for the acceleration under the
/// closed-form torque relative to that under none; tolerance 1e-13); the released run's closure and
/// its piston against x(θ) (measured 4.4e-16 each; tolerance 1e-12, the target), the energy
/// (measured 3.9e-7; tolerance 1e-5, the O(h²) bounded error of a symplectic method).
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let sc = SliderCrank::default();
    let (place, held) = statics(&sc)?;
    report.checks.push(Check::abs(
        NAME,
        "piston x vs r cos θ + √(l² − r² sin²θ), 12 angles",
        place,
        0.0,
        1e-13,
    ));
    report.checks.push(Check::abs(
        NAME,
        "crank at rest under u = k(x − x₀) dx/dθ: θ̈ (relative)",
        held,
        0.0,
        1e-13,
    ));

    let (q, v) = sc.reduced_near(0.5)?.state(0.0, &[0.5], &[0.0]);
    let (mut off, mut lo, mut hi) = (0.0_f64, f64::INFINITY, f64::NEG_INFINITY);
    let run = rattle_run(&sc.mechanism(), (&q, &v), (1e-3, 10_000), |q| {
        off = off.max((q[2] - sc.piston(q[0])).abs());
        (lo, hi) = (lo.min(q[0]), hi.max(q[0]));
    })?;
    let (gap, energy) = (run.closure, run.energy);
    report.note(format!(
        "released at θ = 0.5: the crank swings over [{lo:.4}, {hi:.4}] in 10 s"
    ));
    report.checks.push(Check::abs(
        NAME,
        "released: max |φ| of the loop, 10⁴ RATTLE steps",
        gap,
        0.0,
        1e-12,
    ));
    report.checks.push(Check::abs(
        NAME,
        "released: max |x − x(θ)| along the run",
        off,
        0.0,
        1e-12,
    ));
    report.checks.push(Check::abs(
        NAME,
        "released: max |E − E₀|/E₀ (bounded)",
        energy,
        0.0,
        1e-5,
    ));
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
