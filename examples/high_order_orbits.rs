//! High-order methods on hard orbits: the adaptive Runge-Kutta-Nyström pairs DPRKN6, DPRKN8 and
//! DPRKN12 (Dormand, El-Mikkawy & Prince) and IAS15 (Everhart's Gauss-Radau predictor-corrector with
//! Rein & Spiegel's control) on a Kepler orbit of eccentricity 0.99 over 100 orbits, against the
//! closed form, and on the outer solar system over 200 000 days, against a reference run.
//!
//! **Kepler, e = 0.99** (μ = 1, a = 1, from pericentre; the speed there is 14 times the mean and the
//! time scale r/v 10⁴ times shorter than at apocentre, so every method must shrink its step by that
//! much and grow it back each orbit). The closed forms: E = −μ/(2a), ℓ = √(μa(1 − e²)), and the
//! position at time t from Kepler's equation M = n t = E − e sin E, x = a(cos E − e),
//! y = a√(1 − e²) sin E (n = √(μ/a³)); the run ends at t = 100.37 T, far from pericentre.
//!
//! **The outer solar system** (Hairer, Lubich & Wanner, *Geometric Numerical Integration* §I.2.4:
//! the Sun, Jupiter, Saturn, Uranus, Neptune, Pluto; the model is testkit's `solar`, which the
//! work-precision benchmark also runs). No closed form: the reference is IAS15 at ε = 1e-11, and the
//! checks are each pair's distance from it (an independent method's agreement bounds both errors),
//! and the reference's own energy and angular momentum.
//!
//! Run: `cargo run --release --features examples --example high_order_orbits` (the picture goes to
//! `gallery-out/`).

use noether::core::integrators::{Dprkn6, Dprkn8};
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::closed_form::kepler_orbit_at;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::kepler::Kepler;
use noether_testkit::solar::outer_solar_system;
use std::f64::consts::PI;
use std::process::ExitCode;

/// Eccentricity of the Kepler orbit.
pub const ECC: f64 = 0.99;
/// Orbits of the Kepler run (it ends 0.37 of an orbit later).
pub const ORBITS: f64 = 100.37;
/// The span of the solar-system run in days.
pub const SOLAR_DAYS: f64 = 200_000.0;

/// What a run of one method on the Kepler orbit gave: |ΔE/E|, |Δℓ/ℓ|, max |Δq| against the closed
/// form at the end, and the steps.
struct KeplerRun {
    energy: f64,
    momentum: f64,
    position: f64,
    steps: usize,
}

fn kepler_run<S: Stepper<Partner = Velocities>>(stepper: S) -> Result<KeplerRun, BoxError> {
    let (q0, v0) = kepler_orbit_at(ECC, 0.0);
    let t_end = ORBITS * 2.0 * PI;
    let sol = Driver::new(stepper, State::new(0.0, q0, v0))?
        .save(Save::End)?
        .max_steps(10_000_000)
        .run_until(t_end)?;
    let s = sol.last();
    let (q, v) = (s.q.as_slice(), s.v.as_slice());
    let (qe, _) = kepler_orbit_at(ECC, t_end);
    let energy = 0.5 * (v[0] * v[0] + v[1] * v[1]) - 1.0 / q[0].hypot(q[1]);
    let ell = (1.0 - ECC * ECC).sqrt();
    let position = (0..2).map(|i| (q[i] - qe[i]).abs()).fold(0.0, f64::max);
    Ok(KeplerRun {
        energy: (energy / -0.5 - 1.0).abs(),
        momentum: ((q[0] * v[1] - q[1] * v[0]) / ell - 1.0).abs(),
        position,
        steps: sol.stats().steps,
    })
}

/// What a run of one method on the outer solar system gave: the end positions, the energy and the
/// angular momentum L_z at the start and the end, and the steps.
struct SolarRun {
    q: Vec<f64>,
    energy: [f64; 2],
    lz: [f64; 2],
    steps: usize,
}

/// The outer solar system over [`SOLAR_DAYS`] by `stepper`.
fn solar_run<S: Stepper<Partner = Velocities>>(stepper: S) -> Result<SolarRun, BoxError> {
    let (sys, s0) = outer_solar_system();
    let sol = Driver::new(stepper, s0.clone())?
        .save(Save::End)?
        .max_steps(10_000_000)
        .run_until(SOLAR_DAYS)?;
    let s = sol.last();
    let lz = |st: &State| -> Result<f64, BoxError> {
        Ok(sys.angular_momentum(st.q.as_slice(), st.v.as_slice())?[2])
    };
    Ok(SolarRun {
        q: s.q.as_slice().to_vec(),
        energy: [sys.total_energy(&s0)?, sys.total_energy(s)?],
        lz: [lz(&s0)?, lz(s)?],
        steps: sol.stats().steps,
    })
}

/// Runs the example.
///
/// Methods and settings: DPRKN6 at tolerance 1e-10, DPRKN8 at 1e-12, DPRKN12 at 1e-14, IAS15 at its
/// default ε = 1e-9 (machine precision per step). The tolerances of the checks are a few times what
/// was measured (the measured values are in the notes and beside each constant below): each method's
/// error is its own truncation error at its tolerance, so a lost order or a wrong coefficient moves it
/// by orders of magnitude, while rounding alone stays far below.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let ex = "high_order_orbits";
    let mut report = Report::default();
    let sys = || Natural::unit(Kepler);
    let runs = [
        (
            "DPRKN6",
            kepler_run(Dprkn6::new(sys())?.tolerances(1e-10, 1e-10)?)?,
            KEPLER_TOL[0],
        ),
        (
            "DPRKN8",
            kepler_run(Dprkn8::new(sys())?.tolerances(1e-12, 1e-12)?)?,
            KEPLER_TOL[1],
        ),
        (
            "DPRKN12",
            kepler_run(Dprkn12::new(sys())?.tolerances(1e-14, 1e-14)?)?,
            KEPLER_TOL[2],
        ),
        ("IAS15", kepler_run(Ias15::new(sys())?)?, KEPLER_TOL[3]),
    ];
    for (name, r, (tol_e, tol_l, tol_q)) in &runs {
        report.note(format!(
            "Kepler e = 0.99, {ORBITS} orbits, {name}: {} steps, |ΔE/E| {:.1e}, |Δℓ/ℓ| {:.1e}, position {:.1e}",
            r.steps, r.energy, r.momentum, r.position
        ));
        report.checks.push(Check::abs(
            ex,
            format!("Kepler e = 0.99, {name}: |ΔE/E|"),
            r.energy,
            0.0,
            *tol_e,
        ));
        report.checks.push(Check::abs(
            ex,
            format!("Kepler e = 0.99, {name}: |Δℓ/ℓ|"),
            r.momentum,
            0.0,
            *tol_l,
        ));
        report.checks.push(Check::abs(
            ex,
            format!("Kepler e = 0.99, {name}: |q − q(Kepler's equation)|"),
            r.position,
            0.0,
            *tol_q,
        ));
    }

    let (sys, _) = outer_solar_system();
    let SolarRun {
        q: reference,
        energy,
        lz,
        steps: ref_steps,
    } = solar_run(Ias15::new(&sys)?.block_size(3)?.epsilon(1e-11)?)?;
    report.note(format!(
        "outer solar system, {SOLAR_DAYS} days, reference IAS15 ε = 1e-11: {ref_steps} steps, \
         |ΔE/E| {:.1e}, |ΔL_z/L_z| {:.1e}",
        (energy[1] / energy[0] - 1.0).abs(),
        (lz[1] / lz[0] - 1.0).abs()
    ));
    report.checks.push(Check::rel(
        ex,
        "solar system, IAS15: energy",
        energy[1],
        energy[0],
        SOLAR_CONSERVED,
    ));
    report.checks.push(Check::rel(
        ex,
        "solar system, IAS15: L_z",
        lz[1],
        lz[0],
        SOLAR_CONSERVED,
    ));
    let solar = [
        (
            "DPRKN6",
            solar_run(Dprkn6::new(&sys)?.tolerances(1e-10, 1e-10)?)?,
            SOLAR_TOL[0],
        ),
        (
            "DPRKN8",
            solar_run(Dprkn8::new(&sys)?.tolerances(1e-12, 1e-12)?)?,
            SOLAR_TOL[1],
        ),
        (
            "DPRKN12",
            solar_run(Dprkn12::new(&sys)?.tolerances(1e-14, 1e-14)?)?,
            SOLAR_TOL[2],
        ),
        (
            "IAS15 (ε = 1e-9)",
            solar_run(Ias15::new(&sys)?.block_size(3)?)?,
            SOLAR_TOL[3],
        ),
    ];
    let mut bars = Vec::new();
    for (i, (name, run, tol)) in solar.iter().enumerate() {
        let steps = run.steps;
        let err = run
            .q
            .iter()
            .zip(&reference)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        report.note(format!(
            "outer solar system, {name}: {steps} steps, max |q − q_ref| {err:.1e} AU"
        ));
        report.checks.push(Check::abs(
            ex,
            format!("solar system, {name}: max |q − q_ref| (AU)"),
            err,
            0.0,
            *tol,
        ));
        bars.push((i as f64, err.max(1e-16)));
    }
    let figure = Figure::new("Kepler e = 0.99 (100 orbits) and the outer solar system (200 000 days)")
        .x_label("method: DPRKN6, DPRKN8, DPRKN12, IAS15")
        .y_label("error")
        .log_y()
        .dots(
            "Kepler: |q − q(Kepler's equation)|",
            runs.iter()
                .enumerate()
                .map(|(i, r)| (i as f64, r.1.position.max(1e-16)))
                .collect(),
        )
        .dots("solar system: max |q − q_ref| (AU)", bars);
    report.save(opts, &figure, "high_order_orbits.svg")?;
    Ok(report)
}

/// (|ΔE/E|, |Δℓ/ℓ|, max |q − q_exact|) tolerances on the Kepler run, ~4× the measured errors:
/// - DPRKN6 at 1e-10: measured 2.7e-9, 7.4e-12, 2.6e-7 (66 680 steps);
/// - DPRKN8 at 1e-12: 2.8e-11, 9.1e-15, 2.6e-9 (32 867 steps);
/// - DPRKN12 at 1e-14: 1.5e-13, 1.2e-14, 1.6e-11 (10 942 steps);
/// - IAS15 at ε = 1e-9: 3.6e-14, 2.2e-16, 1.6e-11 (16 010 steps). Rounding: E is a difference of
///   terms 200 times |E| at pericentre, and the phase error its random walk drives grows like
///   t^{3/2} (Brouwer); ℓ's bound is the random walk √N ε_mach = 1.4e-14.
///
/// The pairs' errors are truncation errors at their tolerances (DPRKN6's energy error is 100 times
/// DPRKN8's at a tolerance 100 times looser): a lost order moves them by decades.
const KEPLER_TOL: [(f64, f64, f64); 4] = [
    (1e-8, 3e-11, 1e-6),
    (1e-10, 4e-14, 1e-8),
    (6e-13, 5e-14, 6e-11),
    (1.5e-13, 1.4e-14, 6e-11),
];
/// Distance from the reference of the solar-system runs (AU): DPRKN6 (measured 1.8e-9), DPRKN8
/// (4.6e-11), DPRKN12 (4.7e-12), IAS15 at ε = 1e-9 (3.6e-12), ~3.5× each. DPRKN12 and IAS15, two
/// independent methods, agree with the reference to 4e-12 AU: the reference is that good.
const SOLAR_TOL: [f64; 4] = [6e-9, 1.6e-10, 1.6e-11, 1.2e-11];
/// Energy and L_z of the reference run, relative: rounding over N = 3262 steps, √N ε_mach = 6.3e-15
/// (measured 6.7e-16 and 0).
const SOLAR_CONSERVED: f64 = 6.3e-15;

fn main() -> ExitCode {
    noether_gallery::example_main("high_order_orbits", run)
}
