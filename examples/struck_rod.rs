//! Impulsive motion of a rod (Desloge ch. 57): Lagrange's equations across an instant, where the momenta
//! jump by the generalized impulse, p⁺ − p⁻ = Ĝ + Φ_qᵀλ̂, and constraints that act for the instant
//! impose their impact law with impulsive reactions λ̂ (`noether::constraints::Impact`).
//!
//! 1. A free rod at rest struck across one end by a blow J: its centre moves at J/m and it turns at
//!    6J/(m l) (the blow's moment J l/2 over m l²/12).
//! 2. A rod translating at u across itself has one end suddenly caught: it turns about that end at
//!    ω = 3u/(2l) (angular momentum about the end), keeping 3/4 of its kinetic energy.
//! 3. A rod pivoted at one end is released horizontal, swings down (integrated: the driver stops at the
//!    vertical) and strikes a peg at distance d below the pivot, which stops it. The peg's impulse is
//!    m l² ω/(3d) and the pivot's m ω l (1/2 − l/(3d)): it vanishes when the peg sits at the centre of
//!    percussion d = 2l/3, the point where a bat does not sting the hands.
//!
//! In 2 and 3 the rod is the free rod of 1 (centre (x, y), angle θ from the x axis) and the pivot, the
//! caught end and the peg are constraints that act during the instant.
//!
//! Run: `cargo run --release --features examples --example struck_rod`.

use noether::constraints::impulse::{Impact, StruckPoints};
use noether::constraints::Holonomic;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use std::process::ExitCode;

const NAME: &str = "struck_rod";

/// A uniform rod of mass m and length l free in the plane: L = ½ m (ẋ² + ẏ²) + ½ (m l²/12) θ̇².
#[derive(Debug, Clone, Copy)]
pub struct Rod {
    /// Mass.
    pub m: f64,
    /// Length.
    pub l: f64,
}

impl Lagrangian for Rod {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, _q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + v[1] * v[1]) * (0.5 * self.m) + v[2] * v[2] * (self.m * self.l * self.l / 24.0)
    }
}

/// The point of the rod at distance s from its centre, (x + s cos θ, y + s sin θ).
#[derive(Debug, Clone, Copy)]
pub struct Point {
    /// Signed distance from the centre along the rod.
    pub s: f64,
}

impl Point {
    fn at<D: Scalar>(&self, q: &[D]) -> [D; 2] {
        [q[0] + q[2].cos() * self.s, q[1] + q[2].sin() * self.s]
    }
}

impl StruckPoints for Point {
    fn dof(&self) -> usize {
        3
    }
    fn dim(&self) -> usize {
        2
    }
    fn positions<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        out.copy_from_slice(&self.at(q));
    }
}

/// The point at s held at `at` (two constraints), and optionally a peg: the point at `peg` stopped in
/// the x direction (one constraint).
#[derive(Debug, Clone, Copy)]
pub struct Held {
    /// The held point.
    pub point: Point,
    /// Where it is held.
    pub at: [f64; 2],
    /// A peg touching the rod at this point, stopping it across (x).
    pub peg: Option<Point>,
}

impl Holonomic for Held {
    fn dof(&self) -> usize {
        3
    }
    fn count(&self) -> usize {
        2 + usize::from(self.peg.is_some())
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        let r = self.point.at(q);
        out[0] = r[0] - self.at[0];
        out[1] = r[1] - self.at[1];
        if let Some(peg) = self.peg {
            out[2] = peg.at(q)[0];
        }
    }
}

/// The rod pivoted at its top end, swinging in the vertical plane: θ from the downward vertical,
/// L = ½ (m l²/3) θ̇² + m g (l/2) cos θ.
struct Pivoted {
    rod: Rod,
    g: f64,
}

impl Lagrangian for Pivoted {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (m, l) = (self.rod.m, self.rod.l);
        v[0] * v[0] * (m * l * l / 6.0) + q[0].cos() * (0.5 * m * self.g * l)
    }
}

/// Runs the checks of this example (see the module docs).
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let rod = Rod { m: 2.0, l: 1.2 };
    let (m, l) = (rod.m, rod.l);
    let free = EulerLagrange::new(rod);
    let mut checks = Vec::new();
    // The jump equations are linear for this L: the answers are exact but for the rounding of one
    // 3×3 (or 5×5) solve; 1e-14 relative.
    let tol = 1e-14;

    // 1. A blow J across the end of a rod at rest along x.
    let j = 0.3;
    let end = Point { s: 0.5 * l };
    let r = Impact::new(&free)
        .blow(&end, &[0.0, j])?
        .velocities(0.0, &[0.0; 3], &[0.0; 3])?;
    checks.push(Check::rel(
        NAME,
        "struck at the end: v_cm = J/m",
        r.v[1],
        j / m,
        tol,
    ));
    checks.push(Check::rel(
        NAME,
        "struck at the end: ω = 6J/(m l)",
        r.v[2],
        6.0 * j / (m * l),
        tol,
    ));

    // 2. Translating at u across itself (along y), the end at s = l/2 is caught.
    let u = 1.5;
    let caught = Held {
        point: end,
        at: [0.5 * l, 0.0],
        peg: None,
    };
    let r = Impact::new(&free)
        .constraints(caught, 0.0)?
        .velocities(0.0, &[0.0; 3], &[0.0, u, 0.0])?;
    checks.push(Check::rel(
        NAME,
        "caught at the end: |ω| = 3u/(2l)",
        r.v[2].abs(),
        3.0 * u / (2.0 * l),
        tol,
    ));
    checks.push(Check::rel(
        NAME,
        "caught at the end: kinetic energy lost = 1/4 of ½ m u²",
        -r.energy_change,
        0.125 * m * u * u,
        tol,
    ));

    // 3. The pivoted rod swings down from horizontal; the driver stops it at the vertical.
    let g = 9.81;
    let pendulum = EulerLagrange::new(Pivoted { rod, g });
    let sol = Driver::new(
        Dop853::new(&pendulum).tolerances(1e-13, 1e-13)?,
        State::new(0.0, [std::f64::consts::FRAC_PI_2], [0.0]),
    )?
    .event(Event::new("vertical", |s: &State| s.q[0]).falling().terminal())
    .run_until(10.0)?;
    // Swinging down, θ decreases: ω = −θ̇ at the vertical.
    let omega = -sol.last().v[0];
    // Energy: m g l/2 = ½ (m l²/3) ω². DOP853 at tolerance 1e-13; measured 1.3e-14 relative.
    checks.push(Check::rel(
        NAME,
        "at the vertical: ω = sqrt(3g/l)",
        omega,
        (3.0 * g / l).sqrt(),
        1e-13,
    ));
    // The free rod hanging from the pivot at the origin: centre (0, −l/2), θ = −π/2 (the top end at
    // s = −l/2 is the pivot). The mirror image of the swing, which the same numbers describe: the
    // centre moving at ω l/2 along +x, the rod turning at θ̇ = +ω, the pivot at rest.
    let q = [0.0, -0.5 * l, -std::f64::consts::FRAC_PI_2];
    let v = [omega * 0.5 * l, 0.0, omega];
    for d in [2.0 * l / 3.0, 0.9 * l, 0.5 * l] {
        let held = Held {
            point: Point { s: -0.5 * l },
            at: [0.0, 0.0],
            peg: Some(Point { s: d - 0.5 * l }),
        };
        let r = Impact::new(&free)
            .constraints(held, 0.0)?
            .velocities(0.0, &q, &v)?;
        // Zero to the rounding of ω ≈ 5 (measured ≤ 8.9e-16 = 0.8 ulp of ω): 4 ulps of ω.
        let ulps = 4.0 * f64::EPSILON * omega;
        checks.push(Check::abs(
            NAME,
            format!("peg at d = {d:.2}: the rod stops"),
            r.v[2],
            0.0,
            ulps,
        ));
        // The reactions λ̂ are the impulses on the rod along the constraints: the peg's along −x.
        let peg = -r.reactions[2];
        let pivot = -r.reactions[0];
        checks.push(Check::rel(
            NAME,
            format!("peg at d = {d:.2}: impulse m l² ω/(3d)"),
            peg,
            m * l * l * omega / (3.0 * d),
            tol,
        ));
        let expected = m * omega * l * (0.5 - l / (3.0 * d));
        let quantity = format!("peg at d = {d:.2}: pivot impulse m ω l (1/2 − l/(3d))");
        checks.push(if expected.abs() < 1e-12 {
            // The centre of percussion: the pivot feels nothing (to rounding of m ω l ≈ 10).
            Check::abs(NAME, quantity, pivot, 0.0, 1e-14)
        } else {
            Check::rel(NAME, quantity, pivot, expected, tol)
        });
    }
    Ok(Report {
        checks,
        ..Default::default()
    })
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
