//! A coin rolling on a table, built from a rolling joint (noether-multibody): a uniform disk of radius
//! a on `Joint::rolling(a)` in the coordinates (x, y, ψ, θ, φ) (centre, heading, tilt, spin), its
//! no-slip conditions written for you by `Mechanism::rolling_contacts`, and the motion by the
//! Lagrange-d'Alembert principle with multipliers (noether-constraints' `Constrained`).
//!
//! 1. **The hand-written coin.** L, the two constraint rows and the accelerations with multipliers
//!    are those of `noether_testkit::coin::Coin` (L and the constraints written out by hand there),
//!    and so are those of the Gibbs-Appell form `Mechanism::gibbs_appell` builds (quasi-velocities
//!    (ψ̇, θ̇, φ̇), no multipliers).
//! 2. **A steady turn.** At tilt θ₀ and turning rate Ω the coin goes round steadily with the spin
//!    ω₃ = (A Ω² cos θ₀ − m g a) sin θ₀ / ((C + m a²) Ω cos θ₀) (Routh, *Advanced Rigid Dynamics*,
//!    §244): θ, Ω and ω₃ stay constant, the centre runs on a circle of radius a ω₃/Ω, and the energy
//!    is conserved (rolling constraints do no work).
//! 3. **Its wobble.** Nudged (θ̇ = 10⁻⁴), the tilt oscillates about the steady turn with the angular
//!    frequency ω of (A + m a²) ω² = −(F_θ + F_Ω p + F_ω₃ r) (`Coin::tilt_frequency_squared`, from
//!    the reduced equations linearised).
//! 4. **Upright rolling.** Rolling straight up it is stable above ω₃² = m g a A/(C (C + m a²)) =
//!    g/(3a) for a uniform disk: nudged at 1.25 × that spin it wobbles at the closed-form ω, at
//!    0.8 × it falls away as (θ̇₀/λ) sinh λt, λ² = −ω².
//!
//! Run: `cargo run --release --features examples --example rolling_coin`.

use noether::constraints::{Constrained, GibbsAppellEquations};
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::agreement::{relative, uniform};
use noether_testkit::coin::Coin;
use noether_testkit::multibody::rolling_coin;
use std::process::ExitCode;

const NAME: &str = "rolling_coin";
/// DOP853's tolerances (relative and absolute).
const TOLERANCE: f64 = 1e-12;
/// The tilt rate θ̇₀ that nudges a steady motion.
const NUDGE: f64 = 1e-4;

/// The state with the angles (ψ, θ, φ) and their rates given and the centre's velocity (ẋ, ẏ) that
/// rolling asks for.
fn rolling(coin: &Coin, q: [f64; 5], angle_rates: [f64; 3]) -> State {
    State::new(0.0, q, coin.rolling_rates(&q, angle_rates))
}

/// Runs the example.
///
/// Tolerances: the built coin agrees with the hand-written one to rounding (measured 6.1e-15;
/// tolerance 1e-13). The runs are DOP853 at tolerance 10⁻¹²: the steady turn holds θ to 1.3e-14 and
/// the energy to 5.2e-14 relative (tolerances 1e-12), its circle and its closure after three turns
/// to 3.5e-12 and 3.1e-12 of a 5.3 m radius (3e-11). The wobbles' periods (measured 1.8e-9 and
/// 8.4e-10 relative; tolerance 1e-8) are those of the linearised motion up to the nudge's own
/// nonlinearity and the run's error on an oscillation 10⁻⁴ of the motion's size: a nudge of 10⁻⁶
/// left 3e-6 (the run's error dominates), 10⁻³ left 2e-7 (the nonlinearity does). The fall is timed
/// at a tilt of 10⁻³, where the cubic terms the sinh leaves out still shift it (measured 1.0e-7;
/// tolerance 1e-6).
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let coin = Coin::uniform(0.5, 1.0, 9.81);
    let mechanism = rolling_coin(&coin);
    let contacts = mechanism.rolling_contacts()?;
    let built = Constrained::nonholonomic(&mechanism, contacts)?;
    let hand = Constrained::nonholonomic(coin, coin.rolling())?;
    let appell = mechanism.gibbs_appell()?;
    let quasi = GibbsAppellEquations::new(appell.clone())?;

    // 1. The built coin is the hand-written one.
    let mut draw = uniform(29);
    let mut worst = 0.0_f64;
    for _ in 0..50 {
        let (q, v) = coin.random_rolling_state(&mut draw);
        let (q, v) = (&q[..], &v[..]);
        let (mut ab, mut ah, mut lambda) = ([0.0; 5], [0.0; 5], [0.0; 2]);
        built.solve(0.0, q, v, &mut ab, &mut lambda)?;
        hand.solve(0.0, q, v, &mut ah, &mut lambda)?;
        let l = relative(&[mechanism.lagrangian(0.0, q, v)], &[coin.lagrangian(0.0, q, v)]);
        let mut udot = [0.0; 3];
        quasi.accelerations(0.0, q, &appell.quasi_velocities(v)?, &mut udot)?;
        worst = worst
            .max(l)
            .max(relative(&ab, &ah))
            .max(relative(&udot, &ah[2..]));
    }
    report.checks.push(Check::abs(
        NAME,
        "L, q̈ with multipliers and by Gibbs-Appell vs the hand-written coin (50 random rolling states)",
        worst,
        0.0,
        1e-13,
    ));

    // 2. A steady turn.
    let (theta, omega) = (0.2, 0.5);
    let spin = coin.steady_spin(theta, omega);
    let (q0, v0) = coin.steady_state(theta, omega, spin);
    let w2 = coin.tilt_frequency_squared(theta, omega, spin);
    let period = std::f64::consts::TAU / omega;
    let radius = coin.radius * spin / omega;
    let start = State::new(0.0, q0, v0);
    let e0 = built.energy(0.0, &q0, &v0)?;
    let sol =
        Driver::new(Dop853::new(&built).tolerances(TOLERANCE, TOLERANCE)?, start)?.run_until(3.0 * period)?;
    let (mut tilt, mut circle, mut energy) = (0.0_f64, 0.0_f64, 0.0_f64);
    for i in 0..sol.len() {
        let (q, v) = (sol.q(i), sol.v(i));
        tilt = tilt.max((q[3] - theta).abs());
        circle = circle.max(((q[0] * q[0] + (q[1] - radius).powi(2)).sqrt() - radius.abs()).abs());
        energy = energy.max((built.energy(0.0, q, v)? - e0).abs() / e0.abs());
    }
    let last = sol.last();
    let closure = (last.q[0] - q0[0]).abs().max((last.q[1] - q0[1]).abs());
    report.note(format!(
        "steady turn θ₀ = {theta}, Ω = {omega}: ω₃ = {spin:.6}, circle radius a ω₃/Ω = {radius:.6}, \
         ω² = {w2:.4} (stable)"
    ));
    report.checks.push(Check::abs(
        NAME,
        "steady turn: max |θ − θ₀| over 3 turns",
        tilt,
        0.0,
        1e-12,
    ));
    report.checks.push(Check::abs(
        NAME,
        "steady turn: the centre's distance from the circle's centre − a ω₃/Ω",
        circle,
        0.0,
        3e-11,
    ));
    report.checks.push(Check::abs(
        NAME,
        "steady turn: back where it started after 3 turns of 2π/Ω",
        closure,
        0.0,
        3e-11,
    ));
    report.checks.push(Check::abs(
        NAME,
        "steady turn: max relative energy drift",
        energy,
        0.0,
        1e-12,
    ));

    // 3. The wobble about it, and 4. upright rolling above the threshold: θ̇ crosses zero twice an
    // oscillation.
    let critical = (coin.g / (3.0 * coin.radius)).sqrt();
    let upright = 1.25 * critical;
    for (what, q, rates, w2) in [
        ("wobble about the steady turn", q0, [omega, NUDGE, v0[4]], w2),
        (
            "upright at 1.25 × sqrt(g/(3a)): wobble",
            [0.0; 5],
            [0.0, NUDGE, upright],
            coin.tilt_frequency_squared(0.0, 0.0, upright),
        ),
    ] {
        let expected = std::f64::consts::TAU / w2.sqrt();
        let sol = Driver::new(
            Dop853::new(&built).tolerances(TOLERANCE, TOLERANCE)?,
            rolling(&coin, q, rates),
        )?
        .event(Event::new("tilt turns", |s: &State| s.v[3]))
        .run_until(10.2 * expected)?;
        let turns = sol.event_times("tilt turns")?;
        let measured = 2.0 * (turns[turns.len() - 1] - turns[0]) / (turns.len() - 1) as f64;
        report.note(format!(
            "{what}: {} turning points, period {measured:.9} (closed form 2π/ω = {expected:.9})",
            turns.len()
        ));
        report.checks.push(Check::rel(
            NAME,
            format!("{what}: period vs 2π/ω"),
            measured,
            expected,
            1e-8,
        ));
    }

    // 4. Below the threshold the upright coin falls away: θ = (θ̇₀/λ) sinh λt, λ² = −ω² > 0, reaches
    // 10⁻³ at t* = asinh(10⁻³ λ/θ̇₀)/λ.
    let slow = 0.8 * critical;
    let growth = (-coin.tilt_frequency_squared(0.0, 0.0, slow)).sqrt();
    let reach = 1e-3;
    let expected = (reach * growth / NUDGE).asinh() / growth;
    let sol = Driver::new(
        Dop853::new(&built).tolerances(TOLERANCE, TOLERANCE)?,
        rolling(&coin, [0.0; 5], [0.0, NUDGE, slow]),
    )?
    .event(
        Event::new("tilted", move |s: &State| s.q[3].abs() - reach)
            .rising()
            .terminal(),
    )
    .run_until(10.0 * expected)?;
    let measured = sol.event_times("tilted")?.first().copied().unwrap_or(f64::NAN);
    report.note(format!(
        "upright at 0.8 × sqrt(g/(3a)) = {slow:.4}: falls away at λ = {growth:.4}/s, tilt 10⁻³ at \
         t = {measured:.9} (closed form {expected:.9})"
    ));
    report.checks.push(Check::rel(
        NAME,
        "upright at 0.8 × sqrt(g/(3a)): time to tilt 10⁻³ vs asinh(10⁻³ λ/θ̇₀)/λ",
        measured,
        expected,
        1e-6,
    ));
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
