//! The Galerkin variational integrators of order 4 and 6 on Kepler's problem: their orders, and the
//! angular momentum they keep.
//!
//! A Galerkin discrete Lagrangian takes the path over a step as the polynomial through s + 1 control
//! points and the action as its Gauss quadrature (s = 2 with 3 Gauss points: order 4; s = 3 with 4:
//! order 6; Marsden and West, *Discrete mechanics and variational integrators*, §2.2.6). The orbit
//! (μ = 1, a = 1, e = 0.6, from pericentre; `noether_testkit::kepler`) has period 2π, so after exactly
//! one period the exact state is the start again.
//!
//! Checks:
//! 1. **Orders.** The error after one period with N and 2N steps shrinks by 2⁴ (Galerkin 4) and 2⁶
//!    (Galerkin 6).
//! 2. **Noether's theorem, discretely.** L is invariant under rotations of the plane and the quadrature
//!    is too, so the discrete angular momentum q₀p₁ − q₁p₀ is conserved exactly by both methods (to the
//!    Newton tolerance of each step) over 100 orbits.
//! 3. **No energy drift.** The energy error oscillates with the orbit (larger at pericentre) but does not
//!    grow: its mean over the last 10 of 100 orbits is that over the first 10.
//!
//! Run: `cargo run --release --features examples --example galerkin_orders`.

use noether::discrete::{FromLagrangian, Galerkin};
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::kepler::{self, Kepler};
use std::f64::consts::PI;
use std::process::ExitCode;

const NAME: &str = "galerkin_orders";

/// The Galerkin method of `order` (4 or 6) on Kepler's problem.
fn method(order: u32) -> Result<Galerkin<Natural<Kepler>>, BoxError> {
    Ok(match order {
        4 => Galerkin::order4(Natural::unit(Kepler))?,
        _ => Galerkin::order6(Natural::unit(Kepler))?,
    })
}

/// The run of `periods` orbits with `steps` steps per period (states (q, p), p = q̇).
fn run_orbits(order: u32, steps: usize, periods: usize) -> Result<Solution<Momenta>, BoxError> {
    let galerkin = method(order)?;
    let (q, v) = kepler::start();
    let start = galerkin.state_from_velocities(0.0, &q, &v)?;
    Ok(Driver::with_step(galerkin, start, 2.0 * PI / steps as f64)?.run_steps(steps * periods)?)
}

/// The distance from the start after one period with `steps` steps.
fn period_error(order: u32, steps: usize) -> Result<f64, BoxError> {
    let sol = run_orbits(order, steps, 1)?;
    let (q, v) = kepler::start();
    let last = sol.last();
    Ok((0..2)
        .map(|i| (last.q[i] - q[i]).abs().max((last.v[i] - v[i]).abs()))
        .fold(0.0, f64::max))
}

/// H = ½|p|² − 1/|q|.
fn energy(q: &[f64], p: &[f64]) -> f64 {
    0.5 * (p[0] * p[0] + p[1] * p[1]) - (q[0] * q[0] + q[1] * q[1]).sqrt().recip()
}

/// Runs the example.
///
/// Tolerances: the observed orders are within 0.1 of 4 and 6 (measured 3.992 from 256 and 512 steps
/// per orbit, 6.016 from 128 and 256: where the error is asymptotic and far above rounding; at 64 and
/// 32 steps the pericentre passage is not yet resolved, 3.85 and 6.22). The angular momentum is
/// conserved to the Newton tolerance of each step (measured 2.3e-13 and 7.8e-14 over 100 orbits of 64
/// steps; tolerance 1e-12). The energy error's mean, late over early, is 1 up to how the steps meet
/// the pericentre passages as the orbit precesses (measured 1.015 and 0.971; tolerance 10 %).
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let mut curves = Vec::new();
    // (order, steps per orbit for the order, for the 100-orbit run)
    for (order, steps, long) in [(4_u32, 256_usize, 64_usize), (6, 128, 64)] {
        let (coarse, fine) = (period_error(order, steps)?, period_error(order, 2 * steps)?);
        let observed = (coarse / fine).log2();
        report.note(format!(
            "Galerkin {order}: error after one orbit {coarse:.2e} ({steps} steps), {fine:.2e} ({}), order {observed:.3}",
            2 * steps
        ));
        report.checks.push(Check::abs(
            NAME,
            format!(
                "Galerkin {order}: observed order ({steps}, {} steps per orbit)",
                2 * steps
            ),
            observed,
            order as f64,
            0.1,
        ));

        let sol = run_orbits(order, long, 100)?;
        let (q0, p0) = (sol.q(0), sol.v(0));
        let (l0, e0) = (q0[0] * p0[1] - q0[1] * p0[0], energy(q0, p0));
        let per_orbit = long;
        let (mut drift, mut early, mut late) = (0.0_f64, 0.0_f64, 0.0_f64);
        let mut curve = Vec::new();
        for i in 0..sol.len() {
            let (q, p) = (sol.q(i), sol.v(i));
            drift = drift.max((q[0] * p[1] - q[1] * p[0] - l0).abs());
            let de = (energy(q, p) - e0).abs();
            if i < 10 * per_orbit {
                early += de;
            }
            if i >= 90 * per_orbit {
                late += de;
            }
            if i % per_orbit == 0 {
                curve.push((sol.times()[i] / (2.0 * PI), de.max(1e-18).log10()));
            }
        }
        report.checks.push(Check::abs(
            NAME,
            format!("Galerkin {order}: angular momentum over 100 orbits (largest change)"),
            drift,
            0.0,
            1e-12,
        ));
        report.checks.push(Check::rel(
            NAME,
            format!("Galerkin {order}: mean energy error, orbits 90–100 over orbits 0–10"),
            late / early,
            1.0,
            0.1,
        ));
        curves.push((format!("Galerkin {order} ({long} steps per orbit)"), curve));
    }
    let mut fig = Figure::new("Kepler e = 0.6: energy error at each pericentre, Galerkin 4 and 6")
        .x_label("orbits")
        .y_label("log₁₀ |E − E₀|");
    for (name, curve) in curves {
        fig = fig.series(&name, curve);
    }
    report.save(opts, &fig, "galerkin_orders.svg")?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
