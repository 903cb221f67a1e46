//! The E × B drift: a charge in a uniform magnetic field B = 2 ẑ and an electric field E = 0.5 ŷ
//! perpendicular to it gyrates about a guiding centre that drifts at E × B / B², whatever its charge
//! and mass (the model of the example `charged_particle`, L = ½ m |v|² + e v·A(r) − e φ(r) with
//! A = ½ B × r, φ = −E·r).
//!
//! Checks: over a whole number of gyrations (20) the displacement over the time is the drift velocity,
//! along E × B and zero across it; and the energy h = ½ m |v|² − e E·r, which the electric field
//! exchanges between kinetic and potential, is conserved.
//!
//! Method: Gauss-Legendre 6 on Hamilton's equations of the Legendre transform of L, h = T/100 (see
//! `charged_particle`): on this linear system a step is the diagonal Padé approximant of the exact
//! flow, so the energy, a quadratic invariant, is kept to rounding and only the phase is approximated,
//! with a relative frequency error ≈ 1e-5 (ωh)⁶ = 6e-13 that the drift inherits (measured 6.1e-13
//! along E×B, 2.4e-12 of v_d across: 1e-11 for both, 16x and 4x). The energy: measured 7.1e-15, 2e-14.
//!
//! Run: `cargo run --release --features examples --example exb_drift` (the trajectory goes to `gallery-out/`).

use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::examples::charged_particle::{simulate, ChargedParticle, PERIODS, STEPS_PER_PERIOD};
use noether_gallery::{BoxError, Check, Options, Report};
use std::f64::consts::PI;
use std::process::ExitCode;

const NAME: &str = "exb_drift";

/// Runs the checks and draws five gyrations of the drift.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let ex = NAME;
    let mut report = Report::default();
    // Add E ⊥ B: the guiding centre drifts at E × B / B² = (E_y/B) x̂ here.
    let magnetic = ChargedParticle {
        m: 1.0,
        e: 1.0,
        b: [0.0, 0.0, 2.0],
        efield: [0.0; 3],
    };
    let crossed = ChargedParticle {
        efield: [0.0, 0.5, 0.0],
        ..magnetic
    };
    let period = 2.0 * PI / magnetic.cyclotron_frequency();
    let h = period / STEPS_PER_PERIOD;
    let drift = crossed.drift_velocity();
    let run_e = simulate(crossed, [0.0, 1.0, 0.0], PERIODS * period, h)?;
    // Over a whole number of gyrations the gyration returns to its phase: displacement / time = v_d.
    let r_end = *run_e.r.last().ok_or("empty run")?;
    let t_end_e = *run_e.t.last().ok_or("empty run")?;
    report.checks.push(Check::rel(
        ex,
        "E×B drift v_x",
        r_end[0] / t_end_e,
        drift[0],
        1e-11,
    ));
    report.checks.push(Check::abs(
        ex,
        "E×B drift v_y (/v_d)",
        r_end[1] / t_end_e / drift[0],
        0.0,
        1e-11,
    ));
    // With E the conserved energy is h = ½ m |v|² + e φ = ½ m |v|² − e E·r.
    let el = EulerLagrange::new(crossed);
    let (r0, v0) = (run_e.r[0], run_e.v[0]);
    report.checks.push(Check::rel(
        ex,
        "energy ½mv² − eE·r (E and B)",
        el.energy(t_end_e, &r_end, run_e.v.last().ok_or("empty run")?)?,
        el.energy(0.0, &r0, &v0)?,
        2e-14,
    ));

    let n = (5.0 * STEPS_PER_PERIOD) as usize;
    let fig = Figure::new("Charged particle in uniform B (ẑ) and E = 0.5 ŷ: the E×B drift")
        .x_label("x")
        .y_label("y")
        .equal_aspect()
        .series(
            "E ⊥ B: drift along E×B (5 gyrations)",
            run_e.r.iter().take(n + 1).map(|r| (r[0], r[1])).collect(),
        );
    report.save(opts, &fig, "exb_drift_trajectory.svg")?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
