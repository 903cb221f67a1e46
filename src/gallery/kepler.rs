//! The Kepler problem, L = ½ m |ṙ|² + k/|r| in the plane, on an orbit of eccentricity 0.6: period,
//! energy, angular momentum and the Runge-Lenz vector after 100 orbits against their closed forms.
//!
//! For semi-major axis a and eccentricity e: T = 2π sqrt(m a³/k), E = −k/(2a),
//! ℓ = sqrt(m k a (1 − e²)), and the Runge-Lenz vector A = p × ℓ ẑ − m k r/|r| = m k e x̂ when the
//! periapsis is on the +x axis (its fixed direction is why Kepler orbits close).

use super::measure::UpCrossings;
use super::plot::{BoxError, Figure};
use super::{Check, Options, Report};
use noether_core::prelude::*;
use std::f64::consts::PI;

/// A body of mass `m` attracted to the origin by the potential −k/r.
#[derive(Debug, Clone, Copy)]
pub struct Kepler {
    /// Mass.
    pub m: f64,
    /// Strength k of the potential −k/r (G M m for gravity).
    pub k: f64,
}

impl Lagrangian for Kepler {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let r = (q[0] * q[0] + q[1] * q[1]).sqrt();
        (v[0] * v[0] + v[1] * v[1]) * (0.5 * self.m) + r.recip() * self.k
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}

impl Kepler {
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

/// Steps per orbit.
const STEPS_PER_ORBIT: usize = 4000;

/// Runs the example.
///
/// Method: classical RK4 with h = T/4000. At periapsis (r = 0.4 a, speed 2 sqrt(k/(m a))) the local time
/// scale r/v is T/31, so h is 1/125 of it. RK4 is not symplectic: its energy error drifts linearly in
/// time, ≈ 2e-12 relative per orbit at this step (measured: 2.1e-10 after 100 orbits), and the other
/// invariants drift in the same way. Each tolerance below is ~10x the error measured at this step: as
/// RK4's error scales as h⁴, that margin is crossed by a step only 1.8x larger, so a loss of order or a
/// wrong force shows at once.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let kep = Kepler { m: 1.0, k: 1.0 };
    let (a, e) = (1.0, 0.6);
    let period = 2.0 * PI * (kep.m * a * a * a / kep.k).sqrt();
    let h = period / STEPS_PER_ORBIT as f64;
    let el = EulerLagrange::new(kep);
    let start = kep.periapsis_state(a, e);
    let e0 = el.energy(0.0, start.q.as_slice(), start.v.as_slice())?;
    let mut run = Trajectory::new(Rk4::new(el), start, h)?;

    // y crosses zero upwards once per orbit, at periapsis.
    let mut crossings = UpCrossings::new();
    let mut orbit = Vec::new();
    let mut energy_err = Vec::new();
    for step in 1..=ORBITS * STEPS_PER_ORBIT {
        let s = run.next().ok_or("trajectory ended")??;
        crossings.push(s.t, s.q[1], s.v[1]);
        if step <= STEPS_PER_ORBIT {
            orbit.push((s.q[0], s.q[1]));
        }
        if step % 200 == 0 {
            let en = run
                .stepper()
                .system()
                .energy(s.t, s.q.as_slice(), s.v.as_slice())?;
            energy_err.push((s.t / period, ((en - e0) / e0).abs()));
        }
    }
    let end = run.state().clone();
    let (q, v) = (end.q.as_slice(), end.v.as_slice());
    let mut report = Report::default();
    let ex = "kepler";
    // T = 2π sqrt(m a³/k), the mean over 100 orbits of the periapsis-to-periapsis time. An energy error
    // δE/E shifts T by (3/2) δE/E (T ∝ |E|^(-3/2)): the mean over the drift ≈ 1.5 × 1e-10 (measured
    // 2.2e-10); tolerance 2e-9.
    report.checks.push(Check::rel(
        ex,
        "period (mean of 100 orbits)",
        crossings.period().ok_or("no full orbit")?,
        period,
        2e-9,
    ));
    // E = −k/(2a): RK4's energy drift (measured 2.1e-10); tolerance 2e-9.
    let energy = run.stepper().system().energy(end.t, q, v)?;
    report.checks.push(Check::rel(
        ex,
        "energy after 100 orbits",
        energy,
        -kep.k / (2.0 * a),
        2e-9,
    ));
    // ℓ = sqrt(m k a (1 − e²)): the force is central, but RK4 does not conserve ℓ exactly either
    // (measured 2.3e-11); tolerance 3e-10.
    let l_exact = (kep.m * kep.k * a * (1.0 - e * e)).sqrt();
    report.checks.push(Check::rel(
        ex,
        "angular momentum after 100 orbits",
        kep.angular_momentum(q, v),
        l_exact,
        3e-10,
    ));
    // A = m k e x̂: |A| = m k e, and its direction stays on the periapsis (A_y/|A| is the precession
    // angle of the orbit, which only the integrator's error can create). Measured 1.4e-10 and 1.1e-8;
    // tolerances 1.5e-9 and 1e-7.
    let rl = kep.runge_lenz(q, v);
    report.checks.push(Check::rel(
        ex,
        "Runge-Lenz A_x after 100 orbits",
        rl[0],
        kep.m * kep.k * e,
        1.5e-9,
    ));
    report.checks.push(Check::abs(
        ex,
        "Runge-Lenz angle A_y/|A| after 100 orbits",
        rl[1] / rl[0].hypot(rl[1]),
        0.0,
        1e-7,
    ));

    Figure::new("Kepler orbit, e = 0.6 (first orbit)")
        .x_label("x / a")
        .y_label("y / a")
        .equal_aspect()
        .series("orbit", orbit)
        .series("focus (attracting centre)", cross(0.0, 0.0, 0.05))
        .save_in(opts, "kepler_orbit.svg", &mut report)?;
    Figure::new("Kepler, e = 0.6: relative energy error, RK4 (h = T/4000)")
        .x_label("t / T")
        .y_label("|E − E0| / |E0|")
        .log_y()
        .series("RK4", energy_err)
        .save_in(opts, "kepler_energy_error.svg", &mut report)?;
    Ok(report)
}

/// A small "+" centred at (x, y) drawn as one polyline.
fn cross(x: f64, y: f64, d: f64) -> Vec<(f64, f64)> {
    vec![(x - d, y), (x + d, y), (x, y), (x, y + d), (x, y - d)]
}
