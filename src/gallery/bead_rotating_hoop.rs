//! A bead on a circular hoop of radius a that rotates at a constant rate ω about its vertical diameter.
//!
//! The bead is a free point mass in Cartesian coordinates r = (x, y, z), L = ½ m |ṙ|² − m g z, held by
//! two constraints, one of them time-dependent:
//!
//! ```text
//! φ₁ = (|r|² − a²)/(2a) = 0          (on the sphere of radius a: gradient r̂)
//! φ₂ = −x sin ωt + y cos ωt = 0      (in the hoop's plane at time t: gradient n̂ = (−sin ωt, cos ωt, 0))
//! ```
//!
//! so the hoop's force on the bead is λ₁ r̂ + λ₂ n̂. The same bead in its angle θ from the downward
//! vertical has one coordinate, L = ½ m a² (θ̇² + ω² sin²θ) + m g a cos θ, and the equation
//! a θ̈ − a ω² sin θ cos θ = −g sin θ.
//!
//! Closed forms checked on the constrained Cartesian simulation:
//! - equilibria θ = 0 and, when a ω² > g, cos θ₀ = g/(a ω²);
//! - small oscillations: Ω² = ω² sin²θ₀ about θ₀ (a ω² > g), Ω² = g/a − ω² about 0 (a ω² < g);
//! - the hoop's force: inward (toward the centre) N = m a (θ̇² + ω² sin²θ) + m g cos θ, and
//!   perpendicular to the hoop's plane N_⊥ = 2 m a ω θ̇ cos θ (the Coriolis force the hoop must supply);
//! - the Jacobi integral E − ω L_z is conserved (E alone is not: the hoop does work).

use super::{Check, Options, Report};
use noether_constraints::prelude::*;

const NAME: &str = "bead_rotating_hoop";

/// A free point mass in 3D, z up: L = ½ m |ṙ|² − m g z.
pub struct Bead {
    /// Mass.
    pub m: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl Lagrangian for Bead {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * (0.5 * self.m) - q[2] * (self.m * self.g)
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}

/// The rotating hoop: on the sphere of radius a and in the vertical plane at angle ωt.
pub struct RotatingHoop {
    /// Radius.
    pub a: f64,
    /// Rotation rate about the vertical.
    pub omega: f64,
}

impl Holonomic for RotatingHoop {
    fn dof(&self) -> usize {
        3
    }
    fn count(&self) -> usize {
        2
    }
    fn constraints<D: Scalar>(&self, t: D, q: &[D], out: &mut [D]) {
        let (x, y, z) = (q[0], q[1], q[2]);
        out[0] = (x * x + y * y + z * z - self.a * self.a) * (0.5 / self.a);
        let wt = t * self.omega;
        out[1] = y * wt.cos() - x * wt.sin();
    }
}

/// The bead in its angle from the downward vertical: L = ½ m a² (θ̇² + ω² sin²θ) + m g a cos θ.
pub struct HoopAngle {
    /// Mass.
    pub m: f64,
    /// Radius.
    pub a: f64,
    /// Rotation rate.
    pub omega: f64,
    /// Gravitational acceleration.
    pub g: f64,
}

impl Lagrangian for HoopAngle {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let s = q[0].sin();
        (v[0] * v[0] + s * s * (self.omega * self.omega)) * (0.5 * self.m * self.a * self.a)
            + q[0].cos() * (self.m * self.g * self.a)
    }
}

/// The Cartesian state of the bead at angle θ, rate θ̇, time t.
pub fn cartesian_state(a: f64, omega: f64, t: f64, theta: f64, rate: f64) -> State {
    let (s, c) = theta.sin_cos();
    let (sw, cw) = (omega * t).sin_cos();
    State::new(
        t,
        [a * s * cw, a * s * sw, -a * c],
        [
            a * rate * c * cw - a * omega * s * sw,
            a * rate * c * sw + a * omega * s * cw,
            a * rate * s,
        ],
    )
}

/// The angle θ of a Cartesian state (signed within the hoop's plane).
pub fn angle_of(omega: f64, s: &State) -> f64 {
    let (sw, cw) = (omega * s.t).sin_cos();
    (s.q[0] * cw + s.q[1] * sw).atan2(-s.q[2])
}

/// Times at which the samples `(t, y)` cross zero upwards (linear interpolation between samples).
pub fn upward_crossings(samples: &[(f64, f64)]) -> Vec<f64> {
    samples
        .windows(2)
        .filter(|w| w[0].1 < 0.0 && w[1].1 >= 0.0)
        .map(|w| w[0].0 + (w[1].0 - w[0].0) * (-w[0].1) / (w[1].1 - w[0].1))
        .collect()
}

/// Mean period between the first and last of several upward crossings.
pub fn period(samples: &[(f64, f64)]) -> Result<f64, Box<dyn std::error::Error + Send + Sync>> {
    let c = upward_crossings(samples);
    if c.len() < 2 {
        return Err(format!("only {} upward crossings: run too short", c.len()).into());
    }
    Ok((c[c.len() - 1] - c[0]) / (c.len() - 1) as f64)
}

/// The bead on the rotating hoop in Cartesian coordinates.
pub type HoopSystem = Constrained<Bead, HolonomicSet<RotatingHoop>>;

/// Runs the Cartesian constrained bead from (θ, θ̇) for `steps` steps; returns the states.
#[allow(clippy::too_many_arguments)]
fn simulate(
    m: f64,
    a: f64,
    omega: f64,
    g: f64,
    theta: f64,
    rate: f64,
    h: f64,
    steps: usize,
) -> Result<(Vec<State>, HoopSystem), noether_core::Error> {
    let sys = Constrained::holonomic(Bead { m, g }, RotatingHoop { a, omega })?;
    let start = cartesian_state(a, omega, 0.0, theta, rate);
    sys.check_state(&start, 1e-12)?;
    let states = Trajectory::new(Projected::new(Rk4::new(&sys), sys.constraints()), start, h)?
        .take(steps)
        .collect::<Result<Vec<_>, _>>()?;
    Ok((states, sys))
}

/// Runs the hoop checks.
pub fn run(_opts: &Options) -> Result<Report, Box<dyn std::error::Error + Send + Sync>> {
    let (m, a, g) = (1.0_f64, 1.0_f64, 9.81_f64);
    let h = 1e-3;
    let mut checks = Vec::new();

    // --- Fast hoop, a ω² = 25 > g: the bottom is unstable, θ₀ = arccos(g/(a ω²)) is stable.
    let omega = 5.0;
    let theta0 = (g / (a * omega * omega)).acos();
    // A large oscillation from θ = 0.3 at rest in the hoop: Cartesian vs θ-equation, hoop force.
    let (cart, sys) = simulate(m, a, omega, g, 0.3, 0.0, h, 4000)?;
    let one = EulerLagrange::new(HoopAngle { m, a, omega, g });
    let angle = Trajectory::new(Rk4::new(&one), State::new(0.0, [0.3], [0.0]), h)?;
    let jacobi = |s: &State| {
        let e = 0.5 * m * s.v.norm_squared() + m * g * s.q[2];
        e - omega * m * (s.q[0] * s.v[1] - s.q[1] * s.v[0])
    };
    let j0 = jacobi(&cartesian_state(a, omega, 0.0, 0.3, 0.0));
    let (mut d_theta, mut d_n, mut d_perp, mut d_jacobi) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    for (c, s) in cart.iter().zip(angle) {
        let s = s?;
        let (th, rate) = (s.q[0], s.v[0]);
        d_theta = d_theta.max((angle_of(omega, c) - th).abs());
        let f = sys.constraint_forces(c.t, c.q.as_slice(), c.v.as_slice())?;
        let inward = m * a * (rate * rate + omega * omega * th.sin().powi(2)) + m * g * th.cos();
        let perp = 2.0 * m * a * omega * rate * th.cos();
        d_n = d_n.max((-f.lambda[0] - inward).abs() / (m * g));
        d_perp = d_perp.max((f.lambda[1] - perp).abs() / (m * g));
        d_jacobi = d_jacobi.max((jacobi(c) - j0).abs() / j0.abs());
    }
    // RK4 with h = 1e-3 over 4 s: global error ~1e-11 in both formulations, so 1e-8 is safe.
    checks.push(Check::abs(
        NAME,
        "max|θ_cartesian − θ_1dof| (ω=5, 4 s)",
        d_theta,
        0.0,
        1e-8,
    ));
    checks.push(Check::abs(
        NAME,
        "max|N_in − (m a(θ̇²+ω²sin²θ) + m g cos θ)|/(m g)",
        d_n,
        0.0,
        1e-8,
    ));
    checks.push(Check::abs(
        NAME,
        "max|N_perp − 2 m a ω θ̇ cos θ|/(m g)",
        d_perp,
        0.0,
        1e-8,
    ));
    // E − ω L_z: RK4's energy error is O(h⁴) per unit time, ~1e-12 here.
    checks.push(Check::abs(
        NAME,
        "max rel. drift of Jacobi integral E − ω L_z",
        d_jacobi,
        0.0,
        1e-9,
    ));

    // Equilibria: released at rest in the hoop at θ₀ (or at the bottom), the bead stays there.
    // The largest |θ − θ_rest| over `steps` steps released at rest at θ_rest.
    let stays = |theta_rest: f64, steps| -> Result<f64, noether_core::Error> {
        let (states, _) = simulate(m, a, omega, g, theta_rest, 0.0, h, steps)?;
        Ok(states
            .iter()
            .map(|s| (angle_of(omega, s) - theta_rest).abs())
            .fold(0.0, f64::max))
    };
    let stay = stays(theta0, 3000)?;
    // Rounding drives the stable equilibrium by at most ~1e-12 (the Ω-oscillation it excites stays there).
    checks.push(Check::abs(
        NAME,
        "max|θ − θ₀|, released at cos θ₀ = g/(aω²)",
        stay,
        0.0,
        1e-10,
    ));
    let stay0 = stays(0.0, 1000)?;
    checks.push(Check::abs(
        NAME,
        "max|θ|, released at the bottom θ = 0",
        stay0,
        0.0,
        1e-14,
    ));

    // Small oscillations about θ₀: Ω = ω sin θ₀. Amplitude ε = 1e-4 makes the anharmonic shift of the
    // frequency O(ε²) ~ 1e-8; crossings are interpolated linearly (error O(h³)); tolerance 1e-6.
    let eps = 1e-4;
    let (osc, _) = simulate(m, a, omega, g, theta0 + eps, 0.0, h, 6000)?;
    let samples: Vec<(f64, f64)> = osc.iter().map(|s| (s.t, angle_of(omega, s) - theta0)).collect();
    let big_omega = 2.0 * std::f64::consts::PI / period(&samples)?;
    checks.push(Check::rel(
        NAME,
        "Ω about θ₀ (expected ω sin θ₀)",
        big_omega,
        omega * theta0.sin(),
        1e-6,
    ));

    // --- Slow hoop, a ω² = 4 < g: the bottom is stable with Ω² = g/a − ω².
    let slow = 2.0;
    let (osc, _) = simulate(m, a, slow, g, eps, 0.0, h, 9000)?;
    let samples: Vec<(f64, f64)> = osc.iter().map(|s| (s.t, angle_of(slow, s))).collect();
    let big_omega = 2.0 * std::f64::consts::PI / period(&samples)?;
    let expected = (g / a - slow * slow).sqrt();
    checks.push(Check::rel(
        NAME,
        "Ω about 0 (expected sqrt(g/a − ω²), ω=2)",
        big_omega,
        expected,
        1e-6,
    ));

    Ok(Report {
        checks,
        figures: vec![],
    })
}
