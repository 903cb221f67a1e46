//! A four-bar linkage from bodies and joints (noether-multibody): ground pivots 1 apart, a crank of
//! 0.3, a coupler of 1.1, a rocker of 0.7 (uniform rods, no gravity), the loop cut at the
//! coupler-rocker pin and closed again by a holonomic constraint (`Mechanism::close_loop`), stepped by
//! RATTLE (`noether_testkit::multibody::FourBar`).
//!
//! 1. **Grashof's classification.** s + ℓ ≤ p + q (shortest plus longest link at most the other two):
//!    1.4 ≤ 1.7, and the crank is the shortest link, so the crank turns fully and the rocker rocks.
//! 2. **The loop stays closed** over 2·10⁴ steps of h = 10⁻³, about 19 turns of the crank (RATTLE
//!    solves the closure by Newton at every step): max |φ| at rounding. (noether-multibody's tests run
//!    the same for 10⁵ steps.)
//! 3. **Energy** without drift: RATTLE is symplectic, its error O(h²), of the size (θ̇h)² = 3.6e-5.
//! 4. **The rocker's swing** between the toggle angles ψ = π − γ, cos γ = (d² + c² − e²)/(2dc) with
//!    e = b + a and b − a (crank and coupler collinear): ψ never passes them, and its sampled extremes
//!    come within a step's reach of them.
//!
//! Run: `cargo run --release --features examples --example four_bar`.

use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::multibody::FourBar;
use std::process::ExitCode;

const NAME: &str = "four_bar";

/// Runs the example.
///
/// Tolerances: the closure (measured 1.5e-14; tolerance 1e-12, the target); the energy
/// (measured 3.5e-5; tolerance 1e-4, the bounded O((θ̇h)²) error of a symplectic method); ψ beyond the
/// toggle angles (measured 0; tolerance 1e-12, the closure's); the sampled extremes' distance to them
/// (measured 1.3e-6; tolerance 1e-5: a sample lands within half a step of the toggle, Δθ = θ̇h/2 ≈ 3e-3
/// of crank angle, where ψ is within ½|ψ_θθ|Δθ² ≈ 5e-6 of its extreme).
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let fb = FourBar::default();
    for (name, lengths) in [
        ("crank-rocker (crank shortest)", [1.0, 0.3, 1.1, 0.7]),
        ("double crank (ground shortest)", [0.3, 1.0, 1.1, 0.7]),
        ("non-Grashof (triple rocker)", [1.0, 0.6, 1.1, 0.7]),
    ] {
        let linkage = FourBar { lengths, ..fb };
        report.note(format!(
            "{name}: ground, crank, coupler, rocker {lengths:?}: Grashof {}",
            linkage.grashof()
        ));
    }
    if !fb.grashof() {
        return Err("the default linkage must be Grashof".into());
    }
    let run = fb.spin(6.0, 1e-3, 20_000)?;
    report.note(format!("{:.1} turns of the crank in 2·10⁴ steps", run.turns));
    report.checks.push(Check::abs(
        NAME,
        "Grashof crank-rocker: the crank turns fully (min(turns, 10) in 20 s)",
        run.turns.min(10.0),
        10.0,
        0.0,
    ));
    report.checks.push(Check::abs(
        NAME,
        "max |φ| of the loop closure, 2·10⁴ steps",
        run.closure,
        0.0,
        1e-12,
    ));
    report.checks.push(Check::abs(
        NAME,
        "max |E − E₀|/E₀ (RATTLE, bounded)",
        run.energy,
        0.0,
        1e-4,
    ));
    let (psi_min, psi_max) = fb.rocker_limits();
    // Every state of the run is on the loop, so ψ never passes the toggle angles (up to the closure's
    // rounding), and the samples come within the step's reach of them.
    let outside = (psi_min - run.rocker.0).max(run.rocker.1 - psi_max);
    report.checks.push(Check::abs(
        NAME,
        "rocker beyond the toggle angles (max, ≤ 0)",
        outside.max(0.0),
        0.0,
        1e-12,
    ));
    let reach = (run.rocker.0 - psi_min).max(psi_max - run.rocker.1);
    report.checks.push(Check::abs(
        NAME,
        "rocker's sampled extremes vs the toggle angles",
        reach,
        0.0,
        1e-5,
    ));
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
