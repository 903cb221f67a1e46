//! A sphere rolling without slipping, by the Gibbs-Appell equations: on a turntable and inside a bowl.
//!
//! The uniform sphere (radius a, mass m, I = (2/5) m a²) is one rigid part; the coordinates are its
//! centre's horizontal position and its orientation quaternion, q = (x, y, q_w, q_x, q_y, q_z), and
//! the quasi-velocities are its angular velocity in space axes, u = ω. Rolling fixes the centre's
//! velocity by ω, so q̇ = W(q) u + w(q) holds the no-slip constraints and no multiplier appears.
//!
//! **Turntable** (turning at Ω about the vertical z axis through the origin): the contact point moves
//! with the table, ṙ = Ω ẑ × r + a ω × ẑ. With the friction F at the contact, m v̇ = F and
//! I ω̇ = (−a ẑ) × F; differentiating the no-slip condition gives v̇ = Ω ẑ × v − (m a²/I) v̇, so
//! v̇ = (2/7) Ω ẑ × v: the velocity turns at ν = 2Ω/7 and the centre runs on a circle,
//! r(t) = r₀ + [sin νt v₀ + (1 − cos νt) ẑ × v₀]/ν, with the spin ω_z constant.
//!
//! **Bowl** (a spherical bowl of radius R_b, centre at the origin): the centre stays on the sphere of
//! radius ρ = R_b − a, c = (x, y, −sqrt(ρ² − x² − y²)), and the contact point c + a c/ρ is at rest:
//! ċ = −(a/ρ) ω × c. In a vertical plane the kinetic energy is ½ (7/5) m ρ² θ̇² and V = −m g ρ cos θ,
//! a pendulum of length ρ in the gravity 5g/7: the period is 4 K(sin(θ₀/2)) sqrt(7ρ/(5g)), and small
//! oscillations have the angular frequency sqrt(5g/(7(R_b − a))).
//!
//! Run: `cargo run --release --features examples --example rolling_sphere`.

use noether::constraints::{GibbsAppell, GibbsAppellEquations, RigidPart};
use noether::core::integrators::Rk4;
use noether::prelude::*;
use noether_gallery::closed_form::elliptic_k;
use noether_gallery::measure::mean_period;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::gibbs_appell::{body_omega, quat_rate_space, sphere, turntable_run};
use std::f64::consts::PI;
use std::process::ExitCode;

const NAME: &str = "rolling_sphere";
const G: f64 = 9.81;

/// A sphere of radius `a` rolling inside a spherical bowl of radius `bowl`, in gravity.
pub struct Bowl {
    /// Sphere radius.
    pub a: f64,
    /// Bowl radius.
    pub bowl: f64,
}

impl Bowl {
    /// The centre on the sphere of radius ρ = R_b − a, below the bowl's centre.
    fn centre<D: Scalar>(&self, q: &[D]) -> [D; 3] {
        let rho = self.bowl - self.a;
        [q[0], q[1], -(-(q[0] * q[0]) - q[1] * q[1] + rho * rho).sqrt()]
    }
}

impl GibbsAppell for Bowl {
    fn dof(&self) -> usize {
        6
    }
    fn quasi(&self) -> usize {
        3
    }
    /// ċ = −(a/ρ) ω × c (x and y components), and the quaternion rate.
    fn velocities<D: Scalar>(&self, _t: D, q: &[D], u: &[D], qdot: &mut [D]) {
        let c = self.centre(q);
        let k = -self.a / (self.bowl - self.a);
        qdot[0] = (u[1] * c[2] - u[2] * c[1]) * k;
        qdot[1] = (u[2] * c[0] - u[0] * c[2]) * k;
        quat_rate_space(&q[2..6], u, &mut qdot[2..6]);
    }
    fn bodies(&self) -> usize {
        1
    }
    fn body(&self, _b: usize) -> RigidPart {
        sphere(self.a)
    }
    fn centres<D: Scalar>(&self, _t: D, q: &[D], c: &mut [D]) {
        c.copy_from_slice(&self.centre(q));
    }
    fn angular_velocities<D: Scalar>(&self, _t: D, q: &[D], qdot: &[D], omega: &mut [D]) {
        omega.copy_from_slice(&body_omega(&q[2..6], &qdot[2..6]));
    }
    /// V = m g z of the centre (m = 1).
    fn potential<D: Scalar>(&self, _t: D, q: &[D]) -> D {
        self.centre(q)[2] * G
    }
}

/// Largest |x| of a series.
fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// The turntable orbit against its closed form.
fn turntable(checks: &mut Vec<Check>) -> Result<(), BoxError> {
    let (a, big_omega) = (0.1, 2.0);
    let (r0, w0) = ([0.5, 0.2], [1.0, -3.0, 4.0]);
    let sol = turntable_run(a, big_omega, r0, w0, 2e-3)?;
    let err = max_abs(&sol.observed("err")?);
    let dwz = max_abs(&sol.observed("wz")?);
    // RK4, h = 2e-3, two orbits: measured 3.2e-13 m (5.7e-12 at h = 4e-3, RK4's h⁴): 1e-12.
    checks.push(Check::abs(
        NAME,
        "turntable: max|r − r_circle(ν = 2Ω/7)| over two orbits [m]",
        err,
        0.0,
        1e-12,
    ));
    // No torque about the vertical: measured 4.4e-15: 2e-14.
    checks.push(Check::abs(
        NAME,
        "turntable: max|ω_z − ω_z(0)| [rad/s]",
        dwz,
        0.0,
        2e-14,
    ));
    Ok(())
}

/// Upward zero crossings of x in a run, by linear interpolation (at x = 0 the acceleration vanishes, so
/// the interpolation error is O(h³)).
fn crossings(t: &[f64], x: &[f64]) -> Vec<f64> {
    (1..x.len())
        .filter(|&i| x[i - 1] < 0.0 && x[i] >= 0.0)
        .map(|i| t[i - 1] + (t[i] - t[i - 1]) * x[i - 1] / (x[i - 1] - x[i]))
        .collect()
}

/// The period of rolling oscillations in the bowl from amplitude θ₀, measured over four periods.
fn bowl_period(bowl: &Bowl, theta0: f64) -> Result<f64, BoxError> {
    let sys = GibbsAppellEquations::new(Bowl { ..*bowl })?;
    let rho = bowl.bowl - bowl.a;
    let start = sys.state(0.0, &[-rho * theta0.sin(), 0.0, 1.0, 0.0, 0.0, 0.0], &[0.0; 3])?;
    let t_end = 4.5 * 2.0 * PI * (7.0 * rho / (5.0 * G)).sqrt();
    let sol = Driver::with_step(Rk4::new(&sys), start, 1e-3)?.run_until(t_end)?;
    let x: Vec<f64> = (0..sol.len()).map(|i| sol.q(i)[0]).collect();
    Ok(mean_period(&crossings(sol.times(), &x)).ok_or("fewer than two crossings")?)
}

/// Periods in the bowl: the exact pendulum period at θ₀ = 0.3 and the small-oscillation frequency.
fn bowl(checks: &mut Vec<Check>) -> Result<(), BoxError> {
    let b = Bowl { a: 0.1, bowl: 1.0 };
    let rho = b.bowl - b.a;
    let theta0 = 0.3_f64;
    let exact = 4.0 * elliptic_k((theta0 / 2.0).sin()) * (7.0 * rho / (5.0 * G)).sqrt();
    // RK4 (h = 1e-3) and the crossing interpolation: measured 1.1e-12: 5e-12.
    checks.push(Check::rel(
        NAME,
        "bowl: period at θ₀ = 0.3 vs 4 K(sin θ₀/2) sqrt(7ρ/5g) [s]",
        bowl_period(&b, theta0)?,
        exact,
        5e-12,
    ));
    // θ₀ = 0.01: the error is the anharmonic shift of the pendulum, −θ₀²/16 = −6.25e-6 (measured
    // 6.250e-6 relative): 1e-5.
    let small = 2.0 * PI / bowl_period(&b, 0.01)?;
    checks.push(Check::rel(
        NAME,
        "bowl: small-oscillation frequency vs sqrt(5g/(7(R_b − a))) [rad/s]",
        small,
        (5.0 * G / (7.0 * rho)).sqrt(),
        1e-5,
    ));
    Ok(())
}

/// Runs the rolling-sphere checks: the turntable orbit and the bowl's periods.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let mut checks = Vec::new();
    turntable(&mut checks)?;
    bowl(&mut checks)?;
    Ok(Report {
        checks,
        ..Default::default()
    })
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
