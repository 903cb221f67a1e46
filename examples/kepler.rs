//! The Kepler problem, L = ½ m |ṙ|² + k/|r| in the plane, on an orbit of eccentricity 0.6: period,
//! energy, angular momentum and the Runge-Lenz vector after 100 orbits against their closed forms.
//!
//! For semi-major axis a and eccentricity e: T = 2π sqrt(m a³/k), E = −k/(2a),
//! ℓ = sqrt(m k a (1 − e²)), and the Runge-Lenz vector A = p × ℓ ẑ − m k r/|r| = m k e x̂ when the
//! periapsis is on the +x axis (its fixed direction is why Kepler orbits close).
//!
//! The period is measured as an event: y crossing zero upwards (at periapsis), located by the driver
//! inside each fixed step on the cubic Hermite interpolant of the step.
//!
//! Run: `cargo run --release --features examples --example kepler` (the orbit and the energy-error plot go to
//! `gallery-out/`).

use noether::core::integrators::Rk4;
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::measure::{envelope, mean_period};
use noether_gallery::{BoxError, Check, Options, Report};
use std::f64::consts::PI;
use std::process::ExitCode;

/// A body of mass `m` attracted to the origin by the potential V = −k/r.
///
/// The model is the potential; [`Kepler::system`] makes it the natural system
/// L = ½ m |ṙ|² + k/r, which is at once a Lagrangian and the split form explicit symplectic methods need.
#[derive(Debug, Clone, Copy)]
pub struct Kepler {
    /// Mass.
    pub m: f64,
    /// Strength k of the potential −k/r (G M m for gravity).
    pub k: f64,
}

impl Potential for Kepler {
    fn dof(&self) -> usize {
        2
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        -(q[0] * q[0] + q[1] * q[1]).sqrt().recip() * self.k
    }
}

impl Kepler {
    /// L = ½ m |ṙ|² − V(r) as a natural system with M = m I.
    pub fn system(self) -> noether::core::Result<Natural<Kepler>> {
        Natural::diagonal(self, &[self.m, self.m])
    }

    /// Start at periapsis (a(1 − e), 0) moving in +y with the vis-viva speed sqrt(k(1 + e)/(m a(1 − e))).
    pub fn periapsis_state(&self, a: f64, e: f64) -> State {
        let rp = a * (1.0 - e);
        let vp = (self.k * (1.0 + e) / (self.m * a * (1.0 - e))).sqrt();
        State::new(0.0, [rp, 0.0], [0.0, vp])
    }

    /// Angular momentum ℓ = m (x ẏ − y ẋ).
    pub fn angular_momentum(&self, q: &[f64], v: &[f64]) -> f64 {
        self.m * (q[0] * v[1] - q[1] * v[0])
    }

    /// Runge-Lenz vector A = p × ℓ ẑ − m k r̂ = (p_y ℓ − m k x/r, −p_x ℓ − m k y/r).
    pub fn runge_lenz(&self, q: &[f64], v: &[f64]) -> [f64; 2] {
        let l = self.angular_momentum(q, v);
        let r = q[0].hypot(q[1]);
        let (px, py) = (self.m * v[0], self.m * v[1]);
        [
            py * l - self.m * self.k * q[0] / r,
            -px * l - self.m * self.k * q[1] / r,
        ]
    }
}

/// Orbits simulated.
pub const ORBITS: usize = 100;

/// Steps per orbit of the order-8 composition.
const STEPS_PER_ORBIT_HIGH: usize = 250;

/// Steps per orbit of RK4 and Störmer-Verlet.
const STEPS_PER_ORBIT: usize = 4000;

/// Runs the example.
///
/// Method for the checks: Kahan-Li's order-8 symmetric composition of Störmer-Verlet with h = T/250
/// (17 force evaluations per step). Symplectic, so the energy error stays bounded over the 100 orbits
/// instead of drifting; and, like every composition of Störmer-Verlet, it conserves the angular
/// momentum of a central force exactly (ℓ = m (x ẏ − y ẋ) is a quadratic invariant such methods keep), so
/// only rounding remains in ℓ. A fixed step has to resolve periapsis (r = 0.4 a, local time scale r/v =
/// T/31, so 8 steps there). RK4 and Störmer-Verlet at h = T/4000 are run for the energy-error picture.
///
/// Errors measured at this step are given with each check. Where the method's error shows (period,
/// precession angle), the tolerance is ~10x the measured error: as that error scales as h⁸ (measured:
/// the angle drops 276x when h is halved), a step only 1.35x larger, a loss of order or a wrong force
/// crosses the margin. Where it is below rounding (energy, |A|, ℓ), the tolerance is 1e-12: rounding
/// errors of either sign over N = 2.5·10⁴ steps × 17 stages add up like a random walk, sqrt(17 N) ε ≈ 7e-14.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let kep = Kepler { m: 1.0, k: 1.0 };
    let (a, e) = (1.0, 0.6);
    let period = 2.0 * PI * (kep.m * a * a * a / kep.k).sqrt();
    let system = kep.system()?;
    let start = kep.periapsis_state(a, e);
    let e0 = system.energy(start.q.as_slice(), start.v.as_slice())?;
    let rel_energy_error = |s: &State| Ok(((system.energy(s.q.as_slice(), s.v.as_slice())? - e0) / e0).abs());

    // y crosses zero upwards once per orbit, at periapsis.
    let sol8 = Driver::with_step(
        Composition::kahan_li8(system.clone()),
        start.clone(),
        period / STEPS_PER_ORBIT_HIGH as f64,
    )?
    .event(Event::new("periapsis", |s: &State| s.q[1]).rising())
    .observe("energy error", rel_energy_error)
    .run_steps(ORBITS * STEPS_PER_ORBIT_HIGH)?;
    let orbit: Vec<(f64, f64)> = (0..=STEPS_PER_ORBIT_HIGH)
        .map(|i| (sol8.q(i)[0], sol8.q(i)[1]))
        .collect();
    let end = sol8.last();
    let (q, v) = (end.q.as_slice(), end.v.as_slice());
    let mut report = Report::default();
    let ex = "kepler";
    // T = 2π sqrt(m a³/k), the mean over 100 orbits of the periapsis-to-periapsis time (measured 1.3e-12,
    // tolerance 2e-11).
    report.checks.push(Check::rel(
        ex,
        "period (mean of 100 orbits)",
        mean_period(&sol8.event_times("periapsis")?).ok_or("no full orbit")?,
        period,
        TOL_PERIOD,
    ));
    // E = −k/(2a); bounded error, below rounding at this step (measured 8.0e-14, tolerance 1e-12).
    report.checks.push(Check::rel(
        ex,
        "energy after 100 orbits",
        system.energy(q, v)?,
        -kep.k / (2.0 * a),
        TOL_ENERGY,
    ));
    // ℓ = sqrt(m k a (1 − e²)), conserved exactly by the method: only rounding (measured 5.6e-14,
    // tolerance 1e-12).
    report.checks.push(Check::rel(
        ex,
        "angular momentum after 100 orbits",
        kep.angular_momentum(q, v),
        (kep.m * kep.k * a * (1.0 - e * e)).sqrt(),
        1e-12,
    ));
    // A = m k e x̂: |A| = m k e, and its direction stays on the periapsis (A_y/|A| is the precession
    // angle of the orbit, which only the integrator's error creates, growing linearly). Measured 2.9e-14
    // (|A|, tolerance 1e-12) and 4.0e-10 (angle, tolerance 4e-9).
    let rl = kep.runge_lenz(q, v);
    report.checks.push(Check::rel(
        ex,
        "Runge-Lenz A_x after 100 orbits",
        rl[0],
        kep.m * kep.k * e,
        TOL_RL,
    ));
    report.checks.push(Check::abs(
        ex,
        "Runge-Lenz angle A_y/|A| after 100 orbits",
        rl[1] / rl[0].hypot(rl[1]),
        0.0,
        TOL_ANGLE,
    ));

    // Non-symplectic against symplectic: RK4 and Störmer-Verlet at the same step.
    let h = period / STEPS_PER_ORBIT as f64;
    let n = ORBITS * STEPS_PER_ORBIT;
    let sol_rk4 = Driver::with_step(Rk4::new(system.clone()), start.clone(), h)?
        .observe("energy error", rel_energy_error)
        .run_steps(n)?;
    let sol_sv = Driver::with_step(Composition::stormer_verlet(system.clone()), start, h)?
        .observe("energy error", rel_energy_error)
        .run_steps(n)?;

    let orbit_fig = Figure::new("Kepler orbit, e = 0.6 (first orbit)")
        .x_label("x / a")
        .y_label("y / a")
        .equal_aspect()
        .series("orbit", orbit)
        .series("focus (attracting centre)", cross(0.0, 0.0, 0.05));
    report.save(opts, &orbit_fig, "kepler_orbit.svg")?;
    let energy_fig = Figure::new("Kepler, e = 0.6: energy error (largest in each orbit)")
        .x_label("t / T")
        .y_label("max |E − E0| / |E0| over the orbit")
        .log_y()
        .series(
            "RK4, h = T/4000 (drifts)",
            energy_envelope(&sol_rk4, period, STEPS_PER_ORBIT)?,
        )
        .series(
            "Störmer-Verlet, h = T/4000 (bounded)",
            energy_envelope(&sol_sv, period, STEPS_PER_ORBIT)?,
        )
        .series(
            format!("Kahan-Li order 8, h = T/{STEPS_PER_ORBIT_HIGH}"),
            energy_envelope(&sol8, period, STEPS_PER_ORBIT_HIGH)?,
        );
    report.save(opts, &energy_fig, "kepler_energy_error.svg")?;
    Ok(report)
}

const TOL_PERIOD: f64 = 2e-11;
const TOL_ENERGY: f64 = 1e-12;
const TOL_RL: f64 = 1e-12;
const TOL_ANGLE: f64 = 4e-9;

/// A small "+" centred at (x, y) drawn as one polyline.
fn cross(x: f64, y: f64, d: f64) -> Vec<(f64, f64)> {
    vec![(x - d, y), (x + d, y), (x, y), (x, y + d), (x, y - d)]
}

/// The envelope of the observed energy error of `sol`, one point per orbit (the largest error over the
/// orbit's `steps_per_orbit` steps), against t/T.
fn energy_envelope(sol: &Solution, period: f64, steps_per_orbit: usize) -> Result<Vec<(f64, f64)>, BoxError> {
    let err = sol.observed("energy error")?;
    // Row 0 is the start; the windows are the steps 1..=n, one orbit each.
    let t: Vec<f64> = sol.times()[1..].iter().map(|t| t / period).collect();
    Ok(envelope(&t, &err[1..], steps_per_orbit))
}

fn main() -> ExitCode {
    noether_gallery::example_main("kepler", run)
}
