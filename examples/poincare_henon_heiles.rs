//! Poincaré sections of the Hénon-Heiles system,
//!
//! ```text
//! H = (p_x² + p_y²)/2 + (x² + y²)/2 + x² y − y³/3,
//! ```
//!
//! through the plane x = 0 crossed with p_x > 0, at E = 1/12 (almost every orbit regular: the points
//! of one orbit draw a closed curve, the trace of its invariant torus) and E = 1/6 (a chaotic sea with
//! a few regular islands). The section points are the driver's events on DOP853's continuous
//! extension (`noether::canonical::section`). Checks: every point lies on the energy surface H = E
//! and on the plane; for two uncoupled oscillators the points lie on the ellipse their second
//! integral E_y = (p_y² + ω₂² y²)/2 predicts.
//!
//! Run: `cargo run --release --features examples --example poincare_henon_heiles` (two pictures go to `gallery-out/`).

use noether::canonical::section::{section, Plane};
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::henon_heiles::{on_section, HenonHeiles};
use std::process::ExitCode;

const NAME: &str = "poincare_henon_heiles";

/// Two uncoupled oscillators with frequencies 1 and sqrt 2.
#[derive(Debug, Clone, Copy)]
pub struct Uncoupled;

impl Hamiltonian for Uncoupled {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        (p[0] * p[0] + q[0] * q[0] + p[1] * p[1] + q[1] * q[1] * 2.0) * 0.5
    }
}

/// The (y, p_y) points of one orbit's section, the largest |H − E| and the largest |x| there.
type OrbitSection = (Vec<(f64, f64)>, f64, f64);

/// The section of the orbit from `s0` up to `t_end`.
fn orbit_section(s0: State<Momenta>, e: f64, t_end: f64) -> Result<OrbitSection, BoxError> {
    let h = HamiltonEquations::new(HenonHeiles);
    let dop = Dop853::new(HamiltonEquations::new(HenonHeiles)).tolerances(1e-14, 1e-14)?;
    let points = section(Driver::new(dop, s0)?, Plane::coordinate(0, 0.0), t_end)?;
    let (mut de, mut dx): (f64, f64) = (0.0, 0.0);
    for s in &points.states {
        de = de.max((h.energy(s.t, s.q.as_slice(), s.v.as_slice())? - e).abs());
        dx = dx.max(s.q[0].abs());
    }
    Ok((points.pairs(1, 1), de, dx))
}

/// Runs the example.
///
/// Tolerances: DOP853 at atol = rtol = 1e-14 keeps H to ~1e-13 over t = 1000 (measured below), and the
/// crossing is located to rounding on the dense output; the requirement is 1e-12.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    // At E = 1/6 most orbits are chaotic: they are run three times longer, so that their points
    // fill the chaotic sea rather than sprinkle it.
    for (e, label, file, starts, t_end) in [
        (
            1.0 / 12.0,
            "E = 1/12",
            "poincare_henon_heiles_e12.svg",
            &[-0.25, -0.15, -0.05, 0.05, 0.15, 0.25, 0.35][..],
            1000.0,
        ),
        (
            1.0 / 6.0,
            "E = 1/6",
            "poincare_henon_heiles_e6.svg",
            &[-0.3, -0.1, 0.05, 0.2, 0.4][..],
            3000.0,
        ),
    ] {
        let mut fig = Figure::new(format!("Hénon-Heiles, section x = 0 (p_x > 0), {label}"))
            .x_label("y")
            .y_label("p_y");
        let (mut de, mut dx): (f64, f64) = (0.0, 0.0);
        let mut count = 0;
        for &y in starts {
            let Some(s0) = on_section(e, y, 0.0) else { continue };
            let (pts, de1, dx1) = orbit_section(s0, e, t_end)?;
            count += pts.len();
            de = de.max(de1);
            dx = dx.max(dx1);
            fig = fig.dots(format!("y₀ = {y}"), pts);
        }
        // Measured 9.7e-14 (E = 1/12, 1105 points, t = 1000) and 4.1e-13 (E = 1/6, 2304 points,
        // t = 3000): DOP853's energy error grows with the length of the run.
        report.checks.push(Check::abs(
            NAME,
            format!("max |H − E| at {count} section points, {label}"),
            de,
            0.0,
            1e-12,
        ));
        // A crossing is located to the resolution of the time axis, 4 ulps of t (noether_core::roots),
        // so x there is off by up to |ẋ| · 4ε t ≤ √(2E) · 4ε t_end (|ẋ| = |p_x| ≤ √(2E) on the energy
        // surface): 3.6e-13 at E = 1/12, t = 1000 (measured 2.2e-14) and 1.5e-12 at E = 1/6, t = 3000
        // (measured 1.3e-13).
        report.checks.push(Check::abs(
            NAME,
            format!("max |x| at the section points, {label}"),
            dx,
            0.0,
            (2.0 * e).sqrt() * 4.0 * f64::EPSILON * t_end,
        ));
        report.save(opts, &fig, file)?;
    }
    // The separable system: E_y = (p_y² + 2 y²)/2 is conserved, so the points lie on its ellipse.
    let (y0, py0) = (0.4, -0.3);
    let ey = (py0 * py0 + 2.0 * y0 * y0) * 0.5;
    let dop = Dop853::new(HamiltonEquations::new(Uncoupled)).tolerances(1e-14, 1e-14)?;
    let points = section(
        Driver::new(dop, State::with_momenta(0.0, [0.0, y0], [0.8, py0]))?,
        Plane::coordinate(0, 0.0),
        1000.0,
    )?;
    let worst = points
        .states
        .iter()
        .map(|s| ((s.v[1] * s.v[1] + 2.0 * s.q[1] * s.q[1]) * 0.5 - ey).abs() / ey)
        .fold(0.0, f64::max);
    // Measured 6.1e-13: DOP853's global error over 159 periods (≈ 4e-15 each).
    report.checks.push(Check::abs(
        NAME,
        format!(
            "uncoupled: max relative |E_y − E_y(0)| at {} points",
            points.len()
        ),
        worst,
        0.0,
        1.5e-12,
    ));
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
