//! A spherical pendulum through a spherical joint (noether-multibody): a sphere of radius ρ on a rod
//! from a ball-and-socket joint (`noether_testkit::multibody::BallPendulum`), in the joint's
//! exponential coordinates (the rotation vector θ), which are regular at both poles of spherical
//! coordinates (hanging straight down and standing straight up) where the chart (θ, φ) of
//! `spherical_pendulum` is singular. About the pivot the pendulum is a symmetric top with
//! I₁ = m l² + (2/5) m ρ², I₃ = (2/5) m ρ².
//!
//! 1. **Through the bottom.** A swing of amplitude 2.5 rad in a vertical plane passes straight through
//!    the lower pole; its period is the compound pendulum's 4 K(sin(a/2)) / ω₀, ω₀² = m g l / I₁.
//! 2. **Over the top.** Started at the bottom with the rate Ω₀ = 2.4 ω₀, it goes round through both
//!    poles; one revolution takes (4/Ω₀) K(2ω₀/Ω₀). The rotation vector reaches 3π/2 once a
//!    revolution and the joint's chart is renewed there (`Mechanism::chart_event`: θ → θ(1 − 2π/|θ|),
//!    the same rotation), so the run goes on for ever in a regular chart.
//! 3. **Round a cone.** Turned rigidly about the vertical at Ω, it stays on a cone of half-angle α
//!    when Ω² = g/(l cos α) (the symmetric top's steady precession with the spin ω₃ = Ω cos ϑ: the
//!    point-mass conical pendulum's rate, whatever the bob's size).
//! 4. **Tumbling.** From a general state with spin about the rod, the energy, the angular momentum
//!    about the vertical and the spin about the rod stay constant through the chart renewals.
//!
//! Run: `cargo run --release --features examples --example spherical_joint`.

use noether::multibody::rotation_vector_rate;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::multibody::BallPendulum;
use std::process::ExitCode;

const NAME: &str = "spherical_joint";
/// DOP853's tolerances (relative and absolute) for every run here.
const TOLERANCE: f64 = 1e-12;

/// Runs the example.
///
/// Tolerances: every run is DOP853 at tolerance 10⁻¹², so the closed forms are met to its global
/// error, not to rounding: the swing's period measured 2.4e-12 relative (tolerance 2e-11), ten
/// revolutions 6.0e-13 (1e-11), the cone's height 6.3e-13 of l and its closure after three turns
/// 1.1e-12 (1e-11 both), the tumbling invariants over 20 s and 20 renewals 2.4e-11 (E), 3.1e-11
/// (L_z) and 1.2e-11 (L₃) relative (2e-10). The revolutions and renewals are counted exactly.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let pendulum = BallPendulum::default();
    let mechanism = pendulum.mechanism();
    let el = EulerLagrange::new(&mechanism);
    let stepper = || Dop853::new(&el).tolerances(TOLERANCE, TOLERANCE);

    // 1. A swing in the y-z plane (about x) through the bottom: θ = 0 crossed twice a period.
    let amplitude = 2.5;
    let swing = pendulum.swing_period(amplitude);
    let sol = Driver::new(stepper()?, State::new(0.0, [amplitude, 0.0, 0.0], [0.0; 3]))?
        .event(Event::new("bottom", |s: &State| s.q[0]))
        .run_until(5.2 * swing)?;
    let bottoms = sol.event_times("bottom")?;
    let measured = 2.0 * (bottoms[bottoms.len() - 1] - bottoms[0]) / (bottoms.len() - 1) as f64;
    report.note(format!(
        "swing of 2.5 rad: {} passes through the bottom, period {measured:.12} (closed form {swing:.12})",
        bottoms.len()
    ));
    report.checks.push(Check::rel(
        NAME,
        "swing through the bottom: period vs 4 K(sin(a/2))/ω₀",
        measured,
        swing,
        2e-11,
    ));

    // 2. Over the top: from the bottom at Ω₀ = 2.4 ω₀; the bottom again once a revolution.
    let rate = 2.4 * pendulum.small_swing_rate();
    let revolution = pendulum.revolution_period(rate);
    let turns = 10;
    let sol = Driver::new(stepper()?, State::new(0.0, [0.0; 3], [rate, 0.0, 0.0]))?
        .event(mechanism.chart_event())
        .event(Event::new("bottom", |s: &State| s.q[0]).rising())
        .run_until((turns as f64 + 0.5) * revolution)?;
    let bottoms = sol.event_times("bottom")?;
    let renewals = sol.event_times("rechart")?.len();
    report.note(format!(
        "over the top at Ω₀ = 2.4 ω₀: {} revolutions, {renewals} chart renewals, the last bottom at \
         {:.12} (closed form {:.12})",
        bottoms.len(),
        bottoms[bottoms.len() - 1],
        turns as f64 * revolution
    ));
    report.checks.push(Check::abs(
        NAME,
        "over the top: revolutions and chart renewals",
        (bottoms.len() as f64 - turns as f64).abs() + (renewals as f64 - turns as f64).abs(),
        0.0,
        0.0,
    ));
    report.checks.push(Check::rel(
        NAME,
        "over the top: time of 10 revolutions vs (4/Ω₀) K(2ω₀/Ω₀)",
        bottoms[bottoms.len() - 1] / turns as f64,
        revolution,
        1e-11,
    ));

    // 3. Round a cone of half-angle α: tilted by α about x, turning rigidly about z at Ω.
    let alpha = 0.6_f64;
    let spin = pendulum.conical_rate(alpha);
    let tilt = [alpha, 0.0, 0.0];
    let start_rate = rotation_vector_rate(tilt, [0.0, 0.0, spin])?;
    let period = std::f64::consts::TAU / spin;
    let times: Vec<f64> = (0..=300).map(|k| k as f64 * 3.0 * period / 300.0).collect();
    let sol = Driver::new(stepper()?, State::new(0.0, tilt, start_rate))?
        .event(mechanism.chart_event())
        .save(Save::Times(times))?
        .run_until(3.0 * period)?;
    let bob = noether::multibody::BodyId(0);
    let height = |q: &[f64]| -> Result<f64, BoxError> {
        let (r, _) = mechanism.pose(bob, q)?;
        Ok(-pendulum.length * r[(2, 2)])
    };
    let cone = -pendulum.length * alpha.cos();
    let mut worst = 0.0_f64;
    for i in 0..sol.len() {
        worst = worst.max((height(sol.q(i))? - cone).abs() / pendulum.length);
    }
    let (r_end, _) = mechanism.pose(bob, sol.last().q.as_slice())?;
    let (r_start, _) = mechanism.pose(bob, &tilt)?;
    let closure = (r_end - r_start).amax();
    report.note(format!(
        "cone of half-angle {alpha}: Ω = {spin:.6}, {} chart renewals in 3 turns",
        sol.event_times("rechart")?.len()
    ));
    report.checks.push(Check::abs(
        NAME,
        "cone: max |z_c − (−l cos α)| / l over 3 turns at Ω² = g/(l cos α)",
        worst,
        0.0,
        1e-11,
    ));
    report.checks.push(Check::abs(
        NAME,
        "cone: orientation after 3 turns of 2π/Ω vs the start (max |ΔR|)",
        closure,
        0.0,
        1e-11,
    ));

    // 4. Tumbling with spin about the rod: E, L_z and L₃ through the chart renewals.
    let theta = [0.4, -0.3, 0.2];
    let rate = rotation_vector_rate(theta, [2.0, -1.5, 6.0])?;
    let start = pendulum.invariants(theta, rate);
    let sol = Driver::new(stepper()?, State::new(0.0, theta, rate))?
        .event(mechanism.chart_event())
        .run_until(20.0)?;
    let mut drift = [0.0_f64; 3];
    for i in 0..sol.len() {
        let q = sol.q(i);
        let v = sol.v(i);
        let now = pendulum.invariants([q[0], q[1], q[2]], [v[0], v[1], v[2]]);
        for k in 0..3 {
            drift[k] = drift[k].max((now[k] - start[k]).abs() / start[k].abs());
        }
    }
    report.note(format!(
        "tumbling for 20 s: E = {:.6}, L_z = {:.6}, L₃ = {:.6}; {} chart renewals; drifts {:.2e} {:.2e} {:.2e}",
        start[0],
        start[1],
        start[2],
        sol.event_times("rechart")?.len(),
        drift[0],
        drift[1],
        drift[2]
    ));
    for (k, name) in ["energy", "L_z", "L₃"].iter().enumerate() {
        report.checks.push(Check::abs(
            NAME,
            format!("tumbling: max relative drift of {name} over 20 s"),
            drift[k],
            0.0,
            2e-10,
        ));
    }
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
