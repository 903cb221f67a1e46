//! A binary star: two bodies under universal gravity against the two-body Kepler solution.
//!
//! The relative vector r = r2 − r1 moves on a Kepler ellipse of semi-major axis a and eccentricity e
//! about the focus, with μ = G (m1 + m2): period T = 2π sqrt(a³/μ); at time t after periapsis,
//! M = 2π t/T = E − e sin E (Kepler's equation) and r = a (cos E − e, sqrt(1 − e²) sin E). The centre
//! of mass stays at rest; E = −G m1 m2/(2a) and |L| = m1 m2/(m1 + m2) sqrt(μ a (1 − e²)).
//!
//! Run: `cargo run --release --features examples --example binary_star`.

use noether::particles::laws::Gravity;
use noether::particles::{Internal, Method, Particle, System};
use noether::prelude::*;
use noether_gallery::closed_form::kepler_eccentric_anomaly;
use noether_gallery::{BoxError, Check, Options, Report};
use std::f64::consts::PI;
use std::process::ExitCode;

const NAME: &str = "binary_star";

/// Runs the binary-star checks.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    // Reduced units: G = 1, masses 1 and 0.5, a = 1, e = 0.5.
    let (g, m1, m2, a, e) = (1.0, 1.0, 0.5, 1.0, 0.5);
    let mu = g * (m1 + m2);
    let m = m1 + m2;
    let sys = System::new(vec![Particle::new(m1), Particle::new(m2)])?
        .with(Internal::new(Gravity { g }, [(0, 1)]))?;
    // Periapsis on the x axis, centre of mass at rest at the origin.
    let rp = a * (1.0 - e);
    let vp = (mu * (1.0 + e) / rp).sqrt();
    let s0 = sys.state(
        0.0,
        &[[-m2 / m * rp, 0.0, 0.0], [m1 / m * rp, 0.0, 0.0]],
        &[[0.0, -m2 / m * vp, 0.0], [0.0, m1 / m * vp, 0.0]],
    )?;
    let period = 2.0 * PI * (a * a * a / mu).sqrt();
    let mut report = Report::default();
    let e0 = sys.total_energy(&s0)?;
    report.checks.push(Check::rel(
        NAME,
        "E = -G m1 m2/(2a)",
        e0,
        -g * m1 * m2 / (2.0 * a),
        1e-14,
    ));
    let lz = sys.angular_momentum(s0.q.as_slice(), s0.v.as_slice())?[2];
    let lz_exact = m1 * m2 / m * (mu * a * (1.0 - e * e)).sqrt();
    report.checks.push(Check::rel(
        NAME,
        "L_z = mu_red sqrt(mu a (1-e^2))",
        lz,
        lz_exact,
        1e-14,
    ));

    // Yoshida 4, 4000 steps per period for two periods, every step saved with the centre of mass
    // observed: the periapsis passage (speed √3 at r = 0.5) dominates the error, ~ (h v_p / r_p)⁴ per
    // unit time; measured 4.2e-9 of a (2.6e-10 with 8000 steps per period: the method's h⁴), so 1e-8
    // bounds it with a factor 2.4 to spare.
    let steps_per_period = 4000;
    let h = period / steps_per_period as f64;
    let sol = sys
        .evolver(Method::Yoshida4, s0, h)?
        .observe("|R_cm|", |s: &State| {
            let cm = sys.centre_of_mass(s.q.as_slice())?;
            Ok(cm.iter().fold(0.0_f64, |m, c| m.max(c.abs())))
        })
        .run_steps(2 * steps_per_period)?;
    // The relative vector against Kepler's ellipse every 250 steps.
    let worst_r = (250..sol.len()).step_by(250).fold(0.0_f64, |worst, i| {
        let (x, t) = (sol.q(i), sol.times()[i]);
        let ea = kepler_eccentric_anomaly(2.0 * PI * t / period, e);
        let exact = [a * (ea.cos() - e), a * (1.0 - e * e).sqrt() * ea.sin()];
        let rel = [x[3] - x[0], x[4] - x[1]];
        worst.max((rel[0] - exact[0]).abs().max((rel[1] - exact[1]).abs()))
    });
    report.checks.push(Check::abs(
        NAME,
        "max |r21 - Kepler| / a (2 periods)",
        worst_r / a,
        0.0,
        1e-8,
    ));
    // The centre of mass is at rest: it moves only by rounding (third law by construction).
    let worst_cm = sol.observed("|R_cm|")?.into_iter().fold(0.0_f64, f64::max);
    report
        .checks
        .push(Check::abs(NAME, "max |R_cm| / a", worst_cm / a, 0.0, 1e-14));
    // Yoshida's energy error oscillates with the orbit's phase (symplectic: no drift) and is back near
    // its start after whole periods (measured 4.9e-15): 2e-14.
    let drift = (sys.total_energy(sol.last())? - e0) / e0.abs();
    report.checks.push(Check::abs(
        NAME,
        "energy error after 2 periods",
        drift,
        0.0,
        2e-14,
    ));
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
