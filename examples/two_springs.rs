//! Two masses and two springs on a line, wall − k1 − m1 − k2 − m2, against the normal-mode solution.
//!
//! With displacements u from equilibrium (x1 = l1, x2 = l1 + l2) the motion is linear:
//! M ü + K u = 0, M = diag(m1, m2), K = [[k1 + k2, −k2], [−k2, k2]]. The normal frequencies solve
//! det(K − ω² M) = 0:
//! ω±² = ½ [a ± sqrt(a² − 4 k1 k2/(m1 m2))], a = (k1 + k2)/m1 + k2/m2,
//! with mode shapes φ = (k2, k1 + k2 − m1 ω²). Released from rest, u(t) = Σ c± φ± cos(ω± t).
//! The springs are two-body [`Spring`]s; the wall spring is the same law with one end fixed
//! ([`FixedEnd`], the seed's `one_from_two`).
//!
//! Run: `cargo run --release --features examples --example two_springs`.

use noether::particles::laws::{FixedEnd, Spring};
use noether::particles::{External, Internal, Method, Particle, System};
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use std::process::ExitCode;

const NAME: &str = "two_springs";

/// Runs the two-spring checks.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let (m1, m2, k1, k2, l1, l2) = (1.0, 2.0, 3.0, 1.5, 1.0, 1.0);
    let sys = System::new(vec![Particle::new(m1), Particle::new(m2)])?
        .with(External::new(
            FixedEnd::new(Spring { k: k1, re: l1 }, [0.0; 3]),
            [0],
        ))?
        .with(Internal::new(Spring { k: k2, re: l2 }, [(0, 1)]))?;
    let mut report = Report::default();

    // The term-by-term Hessian at equilibrium is K in the x components (exact up to rounding).
    let h = sys.hessian(0.0, &[l1, 0.0, 0.0, l1 + l2, 0.0, 0.0])?;
    report
        .checks
        .push(Check::rel(NAME, "K11 = k1 + k2", h.get(0, 0), k1 + k2, 1e-14));
    report
        .checks
        .push(Check::rel(NAME, "K12 = -k2", h.get(0, 3), -k2, 1e-14));
    report
        .checks
        .push(Check::rel(NAME, "K22 = k2", h.get(3, 3), k2, 1e-14));

    // Closed-form frequencies and modes.
    let a = (k1 + k2) / m1 + k2 / m2;
    let disc = (a * a - 4.0 * k1 * k2 / (m1 * m2)).sqrt();
    let w = [(0.5 * (a + disc)).sqrt(), (0.5 * (a - disc)).sqrt()];
    let phi = w.map(|wk| [k2, k1 + k2 - m1 * wk * wk]);
    // det(K − ω² M) = 0 for both (a check on the formula, relative to the scale k1 k2): rounding in
    // the O(1) terms that cancel (measured 9.9e-17 and 0): 5e-16.
    for (k, wk) in w.iter().enumerate() {
        let w2 = wk * wk;
        let det = (k1 + k2 - m1 * w2) * (k2 - m2 * w2) - k2 * k2;
        report.checks.push(Check::abs(
            NAME,
            format!("det(K - w{k}^2 M)/(k1 k2)"),
            det / (k1 * k2),
            0.0,
            5e-16,
        ));
    }

    // Release from rest at u0 and compare with the modal solution at t = 5, 10, 15, 20.
    let u0 = [0.1, -0.05];
    let det = phi[0][0] * phi[1][1] - phi[1][0] * phi[0][1];
    let c = [
        (u0[0] * phi[1][1] - phi[1][0] * u0[1]) / det,
        (phi[0][0] * u0[1] - u0[0] * phi[0][1]) / det,
    ];
    let exact = |t: f64| -> [f64; 2] {
        std::array::from_fn(|i| c[0] * phi[0][i] * (w[0] * t).cos() + c[1] * phi[1][i] * (w[1] * t).cos())
    };
    let start = sys.state_1d(0.0, &[l1 + u0[0], l1 + l2 + u0[1]], &[0.0, 0.0])?;
    // Yoshida 4 with h = 1e-3: global error ~ (ω h)⁴ ω t ≈ 1e-11 × 40 over t = 20 (measured 5.4e-11
    // of the amplitude 0.1): 2e-10.
    // The states compared are the computed ones (every 5000th step), not interpolated.
    let sol = sys
        .evolver(Method::Yoshida4, start, 1e-3)?
        .save(Save::Every(5000))?
        .run_steps(20_000)?;
    let worst = (1..sol.len()).fold(0.0_f64, |m, i| {
        let (q, ex) = (sol.q(i), exact(sol.times()[i]));
        m.max((q[0] - l1 - ex[0]).abs().max((q[3] - l1 - l2 - ex[1]).abs()))
    });
    report.checks.push(Check::abs(
        NAME,
        "max |u - modal solution| (t<=20)",
        worst / 0.1,
        0.0,
        2e-10,
    ));
    // The motion stays on the line (1D is the special case y = z = 0 of the 3D system).
    let off_line = sol
        .last()
        .q
        .iter()
        .enumerate()
        .filter(|(k, _)| k % 3 != 0)
        .fold(0.0_f64, |m, (_, v)| m.max(v.abs()));
    report
        .checks
        .push(Check::abs(NAME, "max |y|, |z|", off_line, 0.0, 0.0));
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
