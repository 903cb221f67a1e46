//! Rutherford scattering as a Monte Carlo experiment: a beam of particles with impact parameters spread
//! uniformly over a disc of radius b_max, each orbit integrated through the repulsive Coulomb field
//! V = κ/r (unit mass, energy E = ½ v∞²), the deflection angles counted in bins of Θ, and the counts
//! compared with Rutherford's cross section
//!
//! ```text
//! dσ/dΩ = (κ/(4E))² / sin⁴(Θ/2).
//! ```
//!
//! The members are an ensemble (noether-ensemble): b = b_max √u with u uniform in [0, 1) from member
//! i's own random stream (seed, i), so each member is the same on any thread; each member runs the
//! core driver (DOP853) from distance R until it is back at R (a terminal event), as in the
//! `rutherford` example; the ensemble reduces the angles to a histogram without keeping them.
//!
//! **Expected counts.** Particles with Θ > Θ₁ are those with b < b(Θ₁) = (κ/2E) cot(Θ₁/2), a disc of area
//! σ(Θ > Θ₁) = π (κ/2E)² cot²(Θ₁/2) (which is Rutherford's formula integrated over the solid angle).
//! Of N particles spread over the beam's area π b_max², a bin Θ₁ < Θ < Θ₂ expects
//! N (κ/(2E b_max))² (cot²(Θ₁/2) − cot²(Θ₂/2)) counts; its measured cross section is
//! dσ/dΩ = (count/N) π b_max² / ΔΩ with ΔΩ = 2π (cos Θ₁ − cos Θ₂).
//!
//! **Statistics.** A bin's count is Poisson (strictly binomial, with a slightly smaller variance) with
//! standard deviation √expected, so each bin's measured dσ/dΩ is checked against Rutherford's band
//! average within 4σ (relative 4/√expected), and the whole histogram by Pearson's χ² = Σ (count −
//! expected)²/expected over the bins, which for the K bins follows a χ² law with K degrees of freedom
//! (mean K, standard deviation √(2K)): checked within K ± 5√(2K). The sample is seeded, so the numbers
//! are reproducible; the bounds are the statistical ones, not fitted to them. Measured with the test's
//! 5·10⁴ members: χ² = 9.8 for 12 bins, every bin within 1.5σ (the largest deviation 1.5σ, in the bin
//! Θ ∈ (1.8, 2.0)).
//!
//! **Each member's accuracy.** Each member also returns the error of its angle against the closed form
//! Θ(b) = 2 atan(κ/(2Eb)); the ensemble keeps the largest (a [`Max`] reduction). From R = 10⁴ κ/E the
//! straight asymptotes are missed by 2ε = κb/(2ER²) ≤ 2.5·10⁻⁸ rad, and DOP853 at tolerance 10⁻¹⁰ adds
//! about 10⁻¹⁰: both far below the spread of angles a bin's edge could feel.
//!
//! Run: `cargo run --release --features examples --example scattering_monte_carlo` (10⁵ members; the picture goes to
//! `gallery-out/`). The test runs 5·10⁴.

use noether::ensemble::{Ensemble, Histogram, Map, Max, Sampler};
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::examples::rutherford::Coulomb;
use noether_gallery::{BoxError, Check, Options, Report};
use std::f64::consts::PI;
use std::process::ExitCode;

const NAME: &str = "scattering_monte_carlo";

/// Coulomb strength κ and energy E: κ/(4E) = 0.5.
const KAPPA: f64 = 1.0;
const ENERGY: f64 = 0.5;
/// Radius of the beam: Θ ranges down to 2 atan(κ/(2E b_max)) = 0.199.
const B_MAX: f64 = 10.0;
/// Start and end distance R = 10⁴ κ/E.
const R_FAR: f64 = 2e4;
/// DOP853 tolerances (atol = rtol).
const TOL: f64 = 1e-10;
/// The bins: 12 of width 0.2 over 0.2 < Θ < 2.6 (the last expects 7.7·10⁻⁴ N counts: 77 at N = 10⁵).
const THETA_LO: f64 = 0.2;
const THETA_HI: f64 = 2.6;
const BINS: usize = 12;
/// The seed of the beam.
const SEED: u64 = 1911;
/// Members of the gallery run.
pub const MEMBERS: usize = 100_000;

/// The deflection angle of the orbit at impact parameter `b`: from distance R on the incoming
/// asymptote until the particle is back at R (a terminal event), the angle of the final velocity.
pub fn deflection(b: f64) -> Result<f64, noether::core::Error> {
    let sys = Natural::unit(Coulomb { kappa: KAPPA });
    let v_inf = (2.0 * ENERGY).sqrt();
    // Speed at R from E − κ/R, and the offset that gives the angular momentum b v∞ at that speed.
    let v0 = (2.0 * (ENERGY - KAPPA / R_FAR)).sqrt();
    let b0 = b * v_inf / v0;
    let start = State::new(0.0, [-(R_FAR * R_FAR - b0 * b0).sqrt(), b0], [v0, 0.0]);
    let sol = Driver::new(Dop853::new(&sys).tolerances(TOL, TOL)?, start)?
        .save(Save::End)?
        .event(
            Event::new("back at R", |s: &State| s.q.norm() - R_FAR)
                .rising()
                .terminal(),
        )
        .max_steps(100_000)
        .run_until(4.0 * R_FAR / v_inf)?;
    let end = sol.last();
    Ok(end.v[1].atan2(end.v[0]))
}

/// The closed form Θ(b) = 2 atan(κ/(2Eb)).
pub fn rutherford_angle(b: f64) -> f64 {
    2.0 * (KAPPA / (2.0 * ENERGY * b)).atan()
}

/// Expected share of the beam in Θ₁ < Θ < Θ₂: (κ/(2E b_max))² (cot²(Θ₁/2) − cot²(Θ₂/2)).
pub fn expected_share(t1: f64, t2: f64) -> f64 {
    let cot2 = |t: f64| (0.5 * t).tan().powi(-2);
    (KAPPA / (2.0 * ENERGY * B_MAX)).powi(2) * (cot2(t1) - cot2(t2))
}

/// Runs the example with `members` particles.
pub fn run_members(members: usize, opts: &Options) -> Result<Report, BoxError> {
    let beam = Sampler::new(members, SEED, |rng| {
        use noether::ensemble::rand::Rng;
        B_MAX * rng.random::<f64>().sqrt()
    });
    // Each member: its angle, and that angle's error against the closed form.
    let ensemble = Ensemble::new(beam, |_, &b: &f64| deflection(b))
        .output(|_, &b, theta| (theta, ((theta - rutherford_angle(b)) / rutherford_angle(b)).abs()));
    let histogram = Histogram::new(THETA_LO, THETA_HI, BINS)?;
    let reducer = (
        Map::new(|x: (f64, f64)| x.0, histogram),
        Map::new(|x: (f64, f64)| x.1, Max),
    );
    let (counts, worst) = ensemble.reduce(&reducer).into_value()?;

    let mut checks = Vec::new();
    let edges = histogram.edges();
    let n = members as f64;
    let mut chi2 = 0.0;
    let (mut measured, mut formula) = (Vec::new(), Vec::new());
    for k in 0..BINS {
        let (t1, t2) = (edges[k], edges[k + 1]);
        let expected = n * expected_share(t1, t2);
        let count = counts.counts[k] as f64;
        chi2 += (count - expected).powi(2) / expected;
        let d_omega = 2.0 * PI * (t1.cos() - t2.cos());
        let area = PI * B_MAX * B_MAX;
        let dsigma = count / n * area / d_omega;
        let band = expected / n * area / d_omega;
        // Poisson: relative standard deviation 1/√expected; 4σ.
        checks.push(Check::rel(
            NAME,
            format!("dσ/dΩ over Θ ∈ ({t1:.1}, {t2:.1}) vs Rutherford ({count} counts)"),
            dsigma,
            band,
            4.0 / expected.sqrt(),
        ));
        let centre = 0.5 * (t1 + t2);
        measured.push((centre, dsigma));
        formula.push((centre, band));
    }
    let dof = BINS as f64;
    checks.push(Check::abs(
        NAME,
        format!("Pearson χ² of the {BINS} bins vs its mean {BINS} (±5√(2K))"),
        chi2,
        dof,
        5.0 * (2.0 * dof).sqrt(),
    ));
    // Every member's angle vs 2 atan(κ/(2Eb)): the miss 2ε/Θ of the asymptotes is largest at b_max,
    // 2ε/Θ = 2.5e-8/0.2 = 1.3e-7 relative (measured worst 1.25e-7 over the beam, as at b = b_max in
    // `rutherford`); DOP853 at 1e-10 adds ~1e-10. Tolerance 2e-7.
    checks.push(Check::abs(
        NAME,
        "worst |Θ − 2 atan(κ/(2Eb))|/Θ over all members",
        worst,
        0.0,
        2e-7,
    ));
    // All members land in the histogram or below it (none above 2.6 rad: b < 0.277 has share 7.7e-4).
    checks.push(Check::abs(
        NAME,
        "members counted (bins, below, above)",
        counts.total() as f64,
        n,
        0.0,
    ));

    let mut report = Report {
        checks,
        ..Default::default()
    };
    if opts.out_dir.is_some() {
        let fine: Vec<(f64, f64)> = (0..=200)
            .map(|i| THETA_LO + (THETA_HI - THETA_LO) * i as f64 / 200.0)
            .map(|t| (t, (KAPPA / (4.0 * ENERGY)).powi(2) / (0.5 * t).sin().powi(4)))
            .collect();
        let fig = Figure::new(format!("Rutherford scattering, {members} particles"))
            .x_label("Θ (rad)")
            .y_label("dσ/dΩ")
            .log_y()
            .series("(κ/4E)² / sin⁴(Θ/2)", fine)
            .dots("counted", measured)
            .dots("band average of the formula", formula);
        report.save(opts, &fig, "scattering_monte_carlo.svg")?;
    }
    Ok(report)
}

/// Runs the example (10⁵ members).
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    run_members(MEMBERS, opts)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
