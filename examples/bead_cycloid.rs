//! The tautochrone: a bead sliding without friction on an inverted cycloid
//! x = a (s + sin s), y = a (1 − cos s) under gravity returns in the same time from every release
//! height, with period 4π sqrt(a/g) (Huygens).
//!
//! The model uses three coordinates q = (x, y, s): the bead's Cartesian position and the cycloid's
//! parameter, tied together by two constraints. The parameter carries no kinetic energy, so the mass
//! matrix diag(m, m, 0) is singular — the index-1 system [M Aᵀ; A 0] is regular all the same, because
//! M is definite on the velocities the constraints allow.
//!
//! The period is measured from an event "x crosses zero upwards" (the bead passing the bottom), which
//! the driver locates inside each step.
//!
//! Run: `cargo run --release --features examples --example bead_cycloid`.

use noether::prelude::*;

use noether::constraints::{Constrained, Holonomic, Projected};

use noether::core::integrators::Rk4;
use noether_gallery::examples::bead_rotating_hoop::period;
use noether_gallery::examples::pendulum_cartesian::PlanarMass;
use noether_gallery::{BoxError, Check, Options, Report};
use std::process::ExitCode;

const NAME: &str = "bead_cycloid";

/// L = ½ m (ẋ² + ẏ²) − m g y on q = (x, y, s): the planar mass of the Cartesian pendulum, plus the
/// curve parameter s, which has no kinetic energy.
pub struct BeadWithParameter(pub PlanarMass);

impl Lagrangian for BeadWithParameter {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        self.0.lagrangian(t, &q[..2], &v[..2])
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}

/// The cycloid x = a (s + sin s), y = a (1 − cos s), lowest point at s = 0.
pub struct Cycloid {
    /// Radius of the generating circle.
    pub a: f64,
}

impl Holonomic for Cycloid {
    fn dof(&self) -> usize {
        3
    }
    fn count(&self) -> usize {
        2
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        let s = q[2];
        out[0] = q[0] - (s + s.sin()) * self.a;
        out[1] = q[1] - (-s.cos() + 1.0) * self.a;
    }
}

/// Runs the tautochrone checks.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let (m, g, a) = (1.0_f64, 9.81_f64, 0.5_f64);
    let expected = 4.0 * std::f64::consts::PI * (a / g).sqrt();
    let sys = Constrained::holonomic(BeadWithParameter(PlanarMass { m, g }), Cycloid { a })?;
    let h = 1e-3;
    let t_end = 2.1 * expected; // two upward crossings of x = 0 need 7/4 periods
    let mut checks = Vec::new();
    // Released at rest from heights y = a(1 − cos s₀): 12%, 54% and 90% of the cusp height 2a.
    for s0 in [0.7_f64, 1.65, 2.5] {
        let start = State::new(0.0, [a * (s0 + s0.sin()), a * (1.0 - s0.cos()), s0], [0.0; 3]);
        sys.check_state(&start, 1e-12)?;
        let sol = Driver::with_step(Projected::new(Rk4::new(&sys), sys.constraints()), start, h)?
            .save(Save::End)?
            .event(Event::new("x = 0 upwards", |s: &State| s.q[0]).rising())
            .run_until(t_end)?;
        // The crossing is located on the cubic Hermite interpolant of the RK4 step (error h⁴/384 times
        // the fourth derivative, at the bottom where the bead is fastest); RK4's phase error is ~1e-11.
        // Measured 2.0e-13, 2.0e-13 and 3.1e-12 (highest release: largest speeds and derivatives).
        // Tolerance 1e-11 (it was 1e-8 for crossings interpolated linearly between steps, O(h³)).
        checks.push(Check::rel(
            NAME,
            format!(
                "period released at y = {:.3} (expected 4π sqrt(a/g))",
                a * (1.0 - s0.cos())
            ),
            period(&sol.event_times("x = 0 upwards")?)?,
            expected,
            1e-11,
        ));
    }
    Ok(Report {
        checks,
        ..Default::default()
    })
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
