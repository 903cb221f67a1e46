//! A ball dropped from rest at height h₀ bounces on the floor with restitution e: every impact reverses
//! and shrinks its velocity, ẏ ← −e ẏ. Between impacts it falls freely, L = ½ m ẏ² − m g y. The impacts
//! are events of the driver: "y crosses zero downwards", located inside the step, with a reset of the
//! state, after which the run goes on.
//!
//! Closed forms (free fall between impacts): the impact speed is v₁ = sqrt(2 g h₀), the first impact at
//! t₁ = sqrt(2 h₀ / g), and the n-th bounce lasts 2 eⁿ v₁ / g, so the (n+1)-th impact is at
//! tₙ₊₁ = t₁ + 2 (v₁/g) (e + e² + … + eⁿ); the n-th apex is at height e²ⁿ h₀; all impacts end at
//! t∞ = t₁ (1 + e)/(1 − e).
//!
//! Run: `cargo run --release --features examples --example bouncing_ball` (the height against time goes to `gallery-out/`).

use noether::core::integrators::Rk4;
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use std::process::ExitCode;

/// Height y of a ball of mass m in uniform gravity g: L = ½ m ẏ² − m g y.
#[derive(Debug, Clone, Copy)]
pub struct Fall {
    /// Mass.
    pub m: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl Lagrangian for Fall {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * v[0] * (0.5 * self.m) - q[0] * (self.m * self.g)
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}

/// Coefficient of restitution.
const E: f64 = 0.8;
/// Release height.
const H0: f64 = 2.0;
/// Impacts checked.
const IMPACTS: usize = 10;

/// Time of the n-th impact (n = 1, 2, …): t₁ + 2 (v₁/g) Σ_{k=1}^{n−1} eᵏ.
fn impact_time(fall: &Fall, n: usize) -> f64 {
    let t1 = (2.0 * H0 / fall.g).sqrt();
    let v1 = fall.g * t1;
    t1 + 2.0 * v1 / fall.g * (1..n).map(|k| E.powi(k as i32)).sum::<f64>()
}

/// Runs the example.
///
/// Method: RK4 with h = 1e-3. Free fall has a quadratic y(t), which RK4 integrates exactly and the
/// driver's cubic Hermite interpolant reproduces exactly, so the event times are exact but for
/// rounding: the Illinois root finder stops at a relative bracket of ~1e-15, and each impact time is
/// the sum of the previous ones, so rounding accumulates over the impacts (measured: ≤ 2e-15 relative
/// on the impact times, ≤ 9e-15 on the apex heights, the energy and the remaining time t∞ − t₁₀).
/// Tolerance 2e-14 relative on all of them: rounding over ten impacts (2.3x the largest, 8.7e-15).
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let fall = Fall { m: 0.3, g: 9.81 };
    let el = EulerLagrange::new(fall);
    let mut report = Report::default();
    let t_end =
        impact_time(&fall, IMPACTS) + 0.5 * (impact_time(&fall, IMPACTS + 1) - impact_time(&fall, IMPACTS));

    // 1. Bounce as an event with a reset: stop, change the state, continue — inside one run.
    let sol = Driver::with_step(Rk4::new(&el), State::new(0.0, [H0], [0.0]), 1e-3)?
        .event(
            Event::new("impact", |s: &State| s.q[0])
                .falling()
                .reset(|s| s.v[0] *= -E),
        )
        .event(Event::new("apex", |s: &State| s.v[0]).falling())
        .observe("energy", |s: &State| {
            el.energy(s.t, s.q.as_slice(), s.v.as_slice())
        })
        .run_until(t_end)?;
    let impacts = sol.event_times("impact")?;
    report.checks.push(Check::abs(
        "bouncing_ball",
        "number of impacts",
        impacts.len() as f64,
        IMPACTS as f64,
        0.0,
    ));
    for (n, t) in impacts.iter().enumerate().map(|(i, t)| (i + 1, *t)) {
        if n == 1 || n == IMPACTS {
            // tₙ = t₁ + 2 (v₁/g) Σ eᵏ (free fall between impacts); tolerance above.
            report.checks.push(Check::rel(
                "bouncing_ball",
                format!("t(impact {n})"),
                t,
                impact_time(&fall, n),
                2e-14,
            ));
        }
    }
    // The apexes between impacts: y = e²ⁿ h₀ (the energy ½ m (e v)² after the n-th impact rises to m g y).
    let apexes: Vec<f64> = sol.events_named("apex")?.map(|r| r.state.q[0]).collect();
    for (n, y) in apexes.iter().enumerate().take(3).map(|(i, y)| (i + 1, *y)) {
        report.checks.push(Check::rel(
            "bouncing_ball",
            format!("apex height {n}"),
            y,
            E.powi(2 * n as i32) * H0,
            2e-14,
        ));
    }

    // Energy after the last impact: each impact keeps e² of it, h = e²ⁿ m g h₀ (n = 10).
    let energy = sol.observed("energy")?;
    report.checks.push(Check::rel(
        "bouncing_ball",
        format!("energy after {IMPACTS} impacts"),
        energy[energy.len() - 1],
        E.powi(2 * IMPACTS as i32) * fall.m * fall.g * H0,
        2e-14,
    ));

    // 2. A terminal event: stop at the first impact, change the state by hand, continue with the same
    // stepper — what a user does when the change depends on more than the state.
    let mut first = Driver::with_step(Rk4::new(&el), State::new(0.0, [H0], [0.0]), 1e-3)?
        .event(Event::new("floor", |s: &State| s.q[0]).falling().terminal());
    let stopped = first.run_until(t_end)?;
    report.checks.push(Check::abs(
        "bouncing_ball",
        "terminal event stops the run",
        f64::from(u8::from(stopped.stop() == Stop::Event(0))),
        1.0,
        0.0,
    ));
    let (stepper, mut state) = first.into_parts();
    state.v[0] *= -E;
    let second = Driver::with_step(stepper, state, 1e-3)?
        .event(Event::new("floor", |s: &State| s.q[0]).falling().terminal())
        .run_until(t_end)?;
    report.checks.push(Check::rel(
        "bouncing_ball",
        "t(impact 2), by stop and restart",
        second.last().t,
        impact_time(&fall, 2),
        2e-14,
    ));

    // The limit t∞ = t₁ (1 + e)/(1 − e): the impact times converge geometrically to it.
    let t_inf = (2.0 * H0 / fall.g).sqrt() * (1.0 + E) / (1.0 - E);
    let gap = t_inf - impacts[IMPACTS - 1];
    // t∞ − tₙ = 2 (v₁/g) eⁿ/(1 − e): the remaining time after n impacts, a geometric tail.
    report.checks.push(Check::rel(
        "bouncing_ball",
        format!("t∞ − t(impact {IMPACTS})"),
        gap,
        2.0 * (2.0 * fall.g * H0).sqrt() / fall.g * E.powi(IMPACTS as i32) / (1.0 - E),
        2e-14,
    ));

    let fig = Figure::new("Bouncing ball (e = 0.8): height against time")
        .x_label("t (s)")
        .y_label("y (m)")
        .series("y(t)", sol.times().iter().copied().zip(sol.q_series(0)).collect());
    report.save(opts, &fig, "bouncing_ball.svg")?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main("bouncing_ball", run)
}
