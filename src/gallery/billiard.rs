//! A billiard collision of two equal balls (mass m, radius R) with the elastic contact law of the seed:
//! a compressed linear spring of stiffness k when the centres are closer than re = 2R, nothing
//! otherwise (conservative, piecewise smooth).
//!
//! Closed forms: momentum is conserved exactly (the contact force is applied ± to the pair); the
//! kinetic energy after contact equals the one before; in a head-on collision with the target at rest
//! the velocities are exchanged (v1 → 0, v2 → v0; with a linear spring the contact lasts exactly
//! π sqrt(μ/k), μ = m/2); in an oblique one the two outgoing velocities are perpendicular
//! (p and |v|² conservation with equal masses give v1·v2 = 0).

use super::{Check, Options, Report};
use noether_particles::prelude::*;

const NAME: &str = "billiard";

/// Runs the billiard checks.
pub fn run(_opts: &Options) -> Result<Report, Box<dyn std::error::Error + Send + Sync>> {
    let (m, radius, k, v0) = (1.0, 0.5, 1e4, 1.0);
    let re = 2.0 * radius;
    let sys = System::new(vec![Particle::new(m); 2])?.with(Internal::new(Billiard { k, re }, [(0, 1)]))?;
    let contact_time = std::f64::consts::PI * (0.5 * m / k).sqrt();
    // Velocity Verlet with 400 steps per contact: ω h = π/400, the method's energy error during the
    // contact is ~ (ω h)²/8 ≈ 8e-6 of the energy, and after the contact the exit error is of the same
    // order; the checks below allow 1e-4 (a wrong force or a missing ± would be O(1)).
    let h = contact_time / 400.0;
    let tol = 1e-4;
    let mut checks = Vec::new();

    // Head-on: ball 2 at rest, contact at t = 0.5.
    let s0 = sys.state_1d(0.0, &[-1.0, re - 0.5], &[v0, 0.0])?;
    let ke0 = sys.kinetic_energy(s0.v.as_slice());
    let p0 = sys.momentum(s0.v.as_slice());
    let mut traj = sys.evolver(Method::VelocityVerlet, s0, h)?;
    let (mut in_contact, mut t_in, mut t_out) = (false, f64::NAN, f64::NAN);
    let mut worst_p = 0.0_f64;
    let mut end = traj.state().clone();
    while end.t < 1.0 {
        end = traj.next().expect("evolver is infinite")?;
        let gap = end.q[3] - end.q[0];
        if gap < re && !in_contact {
            (in_contact, t_in) = (true, end.t);
        } else if gap >= re && in_contact && t_out.is_nan() {
            t_out = end.t;
        }
        let p = sys.momentum(end.v.as_slice());
        worst_p = worst_p.max((p[0] - p0[0]).abs());
    }
    // Momentum changes only by rounding: each kick adds +F h/2m and −F h/2m.
    checks.push(Check::abs(
        NAME,
        "max |P - P0| / (m v0)",
        worst_p / (m * v0),
        0.0,
        1e-14,
    ));
    let ke = sys.kinetic_energy(end.v.as_slice());
    checks.push(Check::rel(NAME, "kinetic energy after / before", ke, ke0, tol));
    checks.push(Check::abs(
        NAME,
        "head-on: v1 after / v0",
        end.v[0] / v0,
        0.0,
        tol,
    ));
    checks.push(Check::rel(
        NAME,
        "head-on: v2 after / v0",
        end.v[3] / v0,
        1.0,
        tol,
    ));
    // Contact duration π sqrt(μ/k), resolved to a step at each end.
    checks.push(Check::rel(
        NAME,
        "contact time",
        t_out - t_in,
        contact_time,
        2.0 * h / contact_time,
    ));

    // Oblique: impact parameter 0.6 re; the outgoing velocities are perpendicular.
    let s0 = sys.state_2d(0.0, &[[-1.0, 0.0], [0.0, 0.6 * re]], &[[v0, 0.0], [0.0, 0.0]])?;
    let s = sys.run(Method::VelocityVerlet, s0, h, (2.0 / h) as usize)?;
    let (v1, v2) = ([s.v[0], s.v[1]], [s.v[3], s.v[4]]);
    let cos = (v1[0] * v2[0] + v1[1] * v2[1]) / ((v1[0].hypot(v1[1])) * v2[0].hypot(v2[1]));
    checks.push(Check::abs(
        NAME,
        "oblique: cos(angle between v1, v2)",
        cos,
        0.0,
        tol,
    ));
    checks.push(Check::rel(
        NAME,
        "oblique: kinetic energy after / before",
        sys.kinetic_energy(s.v.as_slice()),
        ke0,
        tol,
    ));
    Ok(Report {
        checks,
        figures: vec![],
    })
}
