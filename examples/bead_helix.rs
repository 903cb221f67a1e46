//! A bead on a helical wire ρ = b, z = a φ under gravity, in Cartesian coordinates with the two
//! constraints x = b cos(z/a), y = b sin(z/a).
//!
//! Closed forms: the bead's vertical acceleration is constant, z̈ = −g a²/(a² + b²) (gravity's
//! component along the tangent, projected back on the vertical), whatever the speed; the wire's force
//! has an inward part m b φ̇² (centripetal) and a part m g b/sqrt(a² + b²) along the binormal, so
//! |N|² = (m b φ̇²)² + m² g² b²/(a² + b²).
//!
//! Run: `cargo run --release --features examples --example bead_helix`.

use noether::prelude::*;

use noether::constraints::{Constrained, Holonomic, Projected};

use noether::core::integrators::Rk4;
/// A point mass in 3D, z up: L = ½ m |ṙ|² − m g z.
pub use noether_gallery::examples::bead_rotating_hoop::Bead;
use noether_gallery::{BoxError, Check, Options, Report};
use std::process::ExitCode;

const NAME: &str = "bead_helix";

/// The helical wire x = b cos(z/a), y = b sin(z/a).
pub struct Helix {
    /// Rise per radian of turn (z = a φ).
    pub a: f64,
    /// Radius.
    pub b: f64,
}

impl Holonomic for Helix {
    fn dof(&self) -> usize {
        3
    }
    fn count(&self) -> usize {
        2
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        let phi = q[2] * (1.0 / self.a);
        out[0] = q[0] - phi.cos() * self.b;
        out[1] = q[1] - phi.sin() * self.b;
    }
}

/// The state on the helix at height z moving with vertical speed w.
pub fn helix_state(a: f64, b: f64, z: f64, w: f64) -> State {
    let (s, c) = (z / a).sin_cos();
    let rate = w / a; // φ̇
    State::new(0.0, [b * c, b * s, z], [-b * s * rate, b * c * rate, w])
}

/// Largest |x| of a series.
fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// Runs the helix checks.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let (m, g, a, b) = (0.5, 9.81, 0.3, 0.7);
    let accel = -g * a * a / (a * a + b * b);
    let sys = Constrained::holonomic(Bead { m, g }, Helix { a, b })?;
    let mut checks = Vec::new();

    // The index-1 solve gives z̈ directly, at rest and at high speed alike (rounding level).
    let mut worst = 0.0_f64;
    for (z, w) in [(0.0, 0.0), (1.3, 4.0), (-2.0, -9.0)] {
        let s = helix_state(a, b, z, w);
        let (mut qdd, mut lambda) = ([0.0; 3], [0.0; 2]);
        sys.solve(0.0, s.q.as_slice(), s.v.as_slice(), &mut qdd, &mut lambda)?;
        worst = worst.max((qdd[2] - accel).abs() / accel.abs());
    }
    checks.push(Check::abs(
        NAME,
        "max rel. error of z̈ = −g a²/(a²+b²) from the solve",
        worst,
        0.0,
        1e-12,
    ));

    // A trajectory thrown upward: z(t) = w t + ½ z̈ t², and the wire's force along the way.
    let (w0, h) = (3.0, 1e-3);
    let start = helix_state(a, b, 0.0, w0);
    sys.check_state(&start, 1e-12)?;
    let sol = Driver::with_step(Projected::new(Rk4::new(&sys), sys.constraints()), start, h)?
        .observe("z error", |s: &State| {
            s.q[2] - (w0 * s.t + 0.5 * accel * s.t * s.t)
        })
        .observe("|N| error", |s: &State| {
            let f = sys.constraint_forces(s.t, s.q.as_slice(), s.v.as_slice())?;
            let rate = s.v[2] / a;
            let n2 = (m * b * rate * rate).powi(2) + (m * g * b).powi(2) / (a * a + b * b);
            Ok((f.generalized.norm() - n2.sqrt()) / (m * g))
        })
        .run_until(2.0)?;
    let dz = max_abs(&sol.observed("z error")?);
    let dn = max_abs(&sol.observed("|N| error")?);
    // RK4 (h = 1e-3, 2 s) on a motion with φ̇ up to 10 rad/s: global error ~ (φ̇ h)⁴ t ~ 1e-11.
    checks.push(Check::abs(
        NAME,
        "max|z − (w t + ½ z̈ t²)| over 2 s [m]",
        dz,
        0.0,
        1e-9,
    ));
    // The force is algebraic in the state and the speed along the wire is exact to rounding
    // (z is quadratic in t, which RK4 integrates exactly): measured 2.9e-15, 1e-14.
    checks.push(Check::abs(
        NAME,
        "max| |N| − sqrt((m b φ̇²)² + (m g b)²/(a²+b²)) |/(m g)",
        dn,
        0.0,
        1e-14,
    ));
    Ok(Report {
        checks,
        ..Default::default()
    })
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
