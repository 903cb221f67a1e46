//! The spherical pendulum in Cartesian coordinates, r = (x, y, z) with |r| = l, against the same
//! pendulum in spherical angles, L = ½ m l² (θ̇² + sin²θ φ̇²) + m g l cos θ (θ from the downward
//! vertical).
//!
//! Checks: the same trajectory; the energy E and the vertical angular momentum L_z = m (x ẏ − y ẋ) are
//! conserved; θ turns between the two roots of the effective energy
//! E = L_z²/(2 m l² sin²θ) − m g l cos θ (θ̇ = 0 there).
//!
//! The same Cartesian model with the constrained variational integrator (RATTLE type, midpoint
//! discrete Lagrangian): the rod holds to rounding at every step, L_z — the discrete Noether momentum
//! of rotations about the vertical, which respect the rod — is conserved to rounding, and the energy
//! error stays bounded (no drift) over many periods.

use super::{Check, Options, Report};
use noether_constraints::prelude::*;
use noether_discrete::momentum::{noether_momentum, PlanarRotation};
use noether_discrete::Midpoint;

const NAME: &str = "spherical_pendulum";

pub use super::bead_rotating_hoop::Bead;

/// A rod of length l from the origin: φ = (|r|² − l²)/(2l) (gradient r̂, multiplier = force along r̂).
pub struct SphericalRod {
    /// Length.
    pub l: f64,
}

impl Holonomic for SphericalRod {
    fn dof(&self) -> usize {
        3
    }
    fn count(&self) -> usize {
        1
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        out[0] = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - self.l * self.l) * (0.5 / self.l);
    }
}

/// The spherical pendulum in angles (θ, φ).
pub struct SphericalAngles {
    /// Mass.
    pub m: f64,
    /// Length.
    pub l: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl Lagrangian for SphericalAngles {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let s = q[0].sin();
        (v[0] * v[0] + s * s * v[1] * v[1]) * (0.5 * self.m * self.l * self.l)
            + q[0].cos() * (self.m * self.g * self.l)
    }
}

/// Cartesian position and velocity of the angle state (θ, φ, θ̇, φ̇).
pub fn to_cartesian(l: f64, s: &State) -> ([f64; 3], [f64; 3]) {
    let (th, ph, dth, dph) = (s.q[0], s.q[1], s.v[0], s.v[1]);
    let (st, ct) = th.sin_cos();
    let (sp, cp) = ph.sin_cos();
    (
        [l * st * cp, l * st * sp, -l * ct],
        [
            l * (ct * cp * dth - st * sp * dph),
            l * (ct * sp * dth + st * cp * dph),
            l * st * dth,
        ],
    )
}

/// Vertex of the parabola through three equally spaced samples (a turning point between samples).
fn vertex(y0: f64, y1: f64, y2: f64) -> f64 {
    let d = y0 - 2.0 * y1 + y2;
    y1 - (y2 - y0).powi(2) / (8.0 * d)
}

/// Runs the spherical pendulum checks.
pub fn run(_opts: &Options) -> Result<Report, Box<dyn std::error::Error + Send + Sync>> {
    let (m, l, g) = (1.0, 1.0, 9.81);
    let angles0 = State::new(0.0, [1.0, 0.0], [0.0, 2.5]);
    let (r0, v0) = to_cartesian(l, &angles0);
    let sys = Constrained::holonomic(Bead { m, g }, SphericalRod { l })?;
    let start = State::new(0.0, r0, v0);
    sys.check_state(&start, 1e-12)?;
    let h = 1e-3;
    let cart = Trajectory::new(
        Projected::new(Rk4::new(&sys), sys.constraints()),
        start.clone(),
        h,
    )?;
    let ang_sys = EulerLagrange::new(SphericalAngles { m, l, g });
    let ang = Trajectory::new(Rk4::new(&ang_sys), angles0.clone(), h)?;

    let energy = |s: &State| 0.5 * m * s.v.norm_squared() + m * g * s.q[2];
    let lz = |s: &State| m * (s.q[0] * s.v[1] - s.q[1] * s.v[0]);
    let (e0, lz0) = (energy(&start), lz(&start));
    let (mut dr, mut de, mut dl) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut thetas = Vec::new();
    for (c, a) in cart.zip(ang).take(5000) {
        let (c, a) = (c?, a?);
        let (r, _) = to_cartesian(l, &a);
        dr = dr.max((0..3).map(|k| (c.q[k] - r[k]).abs()).fold(0.0, f64::max));
        de = de.max((energy(&c) - e0).abs() / e0.abs());
        dl = dl.max((lz(&c) - lz0).abs() / lz0.abs());
        thetas.push(c.q[2].mul_add(-1.0 / l, 0.0).acos());
    }
    // Turning points of θ: the roots of E = L_z²/(2 m l² sin²θ) − m g l cos θ. One is θ₀ = 1 (released
    // with θ̇ = 0); the other is found by bisection on (0, θ₀).
    let veff = |th: f64| lz0 * lz0 / (2.0 * m * l * l * th.sin().powi(2)) - m * g * l * th.cos();
    let (mut lo, mut hi) = (1e-6, 1.0 - 1e-6);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if veff(mid) > e0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let theta_min_expected = 0.5 * (lo + hi);
    let (mut tmin, mut tmax) = (f64::INFINITY, 0.0_f64);
    for w in thetas.windows(3) {
        if w[1] < w[0] && w[1] <= w[2] {
            tmin = tmin.min(vertex(w[0], w[1], w[2]));
        }
        if w[1] > w[0] && w[1] >= w[2] {
            tmax = tmax.max(vertex(w[0], w[1], w[2]));
        }
    }
    // The constrained variational integrator on the same Cartesian model, h = 0.01 for 10⁴ steps (about
    // 70 swings in θ).
    let mut rattle = Rattle::new(Midpoint::new(Bead { m, g }), SphericalRod { l })?;
    let mut s = rattle.state_from_velocities(0.0, &r0, &v0)?;
    let rot = PlanarRotation::new(vec![(0, 1)]);
    let (h_vi, steps) = (0.01, 10_000);
    let (mut worst_phi, mut dl_vi) = (0.0_f64, 0.0_f64);
    let (mut de_first, mut de_last) = (0.0_f64, 0.0_f64);
    for k in 0..steps {
        rattle.step(&mut s, h_vi)?;
        worst_phi = worst_phi.max(rattle.last_step().position_residual);
        dl_vi = dl_vi.max((noether_momentum(&rot, s.q.as_slice(), s.v.as_slice()) - lz0).abs() / lz0.abs());
        let de_k = (rattle.energy(&s)? - e0).abs() / e0.abs();
        if k < steps / 10 {
            de_first = de_first.max(de_k);
        } else if k >= steps - steps / 10 {
            de_last = de_last.max(de_k);
        }
    }
    Ok(Report {
        checks: vec![
            // RK4 h = 1e-3 over 5 s in both coordinates: global errors ~1e-11.
            Check::abs(NAME, "max|r_cartesian − r(θ, φ)| over 5 s", dr, 0.0, 1e-8),
            // RK4's energy and L_z errors are O(h⁴) ~ 1e-12; projection does not change L_z (it moves
            // along r̂, and removes the radial velocity, both of which leave r × v·ẑ unchanged to O(φ)).
            Check::abs(NAME, "max rel. drift of E", de, 0.0, 1e-9),
            Check::abs(NAME, "max rel. drift of L_z", dl, 0.0, 1e-9),
            // Turning points from sampled θ refined by a parabola through three samples (error ~h³).
            Check::abs(NAME, "θ_max (expected θ₀ = 1)", tmax, 1.0, 1e-7),
            Check::abs(
                NAME,
                "θ_min (root of the effective energy)",
                tmin,
                theta_min_expected,
                1e-7,
            ),
            // RATTLE: Newton on (q, Λ) is solved to rounding, so |φ| stays at ~1e-15 each step.
            Check::abs(NAME, "RATTLE max|φ| per step (10⁴ steps)", worst_phi, 0.0, 1e-12),
            // Discrete Noether: each step changes L_z only by rounding (~ε·|q|/h in the momentum residual),
            // accumulating like a random walk: ~1e-13 after 10⁴ steps.
            Check::abs(
                NAME,
                "RATTLE max rel. drift of L_z (10⁴ steps)",
                dl_vi,
                0.0,
                1e-12,
            ),
            // Symplectic: the O(h²) energy error (~3e-4 here) oscillates without drift; the last tenth of
            // the run has the same range as the first tenth (within 5%).
            Check::abs(
                NAME,
                "RATTLE energy error range, last/first tenth − 1",
                de_last / de_first - 1.0,
                0.0,
                0.05,
            ),
        ],
        figures: vec![],
    })
}
