//! The fast top: a heavy symmetric top spun fast (ω₃ = 80) and released at rest with its axis tilted
//! (θ₀ = 0.5, θ̇ = φ̇ = 0) precesses slowly, at M g ℓ/(I₃ ω₃) on average to first order in
//! I₁ M g ℓ/(I₃ ω₃)² (the gyroscope's rate), and exactly at Δφ/T, the precession per nutation over the
//! nutation period that quadrature of the cubic u̇² = f(u) gives.
//!
//! The model (Euler angles, the Lagrangian written once), its constants, the nutation cubic and its
//! quadrature are the example `heavy_top`'s; this example runs them on the fast top. The run is
//! DOP853 at tolerances 1e-14 with the minima of θ as events θ̇ = 0 on its dense output, so the mean
//! rate is measured over whole nutations between exact turning times.
//!
//! Run: `cargo run --release --features examples --example fast_top`.

use noether::prelude::*;
use noether_gallery::examples::heavy_top::{
    constants, cubic_roots, nutation_cubic, nutation_quadrature, run_euler, HeavyTop, GALLERY_TOP, THETA_MIN,
};
use noether_gallery::{BoxError, Check, Options, Report};
use std::process::ExitCode;

const NAME: &str = "fast_top";

/// A fast top released at rest (θ₀ = 0.5, θ̇ = φ̇ = 0, ω₃ = 80): slow precession, at the mean
/// rate over whole nutations against the quadrature and against M g ℓ/(I₃ ω₃).
fn fast_top(top: HeavyTop, report: &mut Report) -> Result<(), BoxError> {
    let el = EulerLagrange::new(top);
    let omega3 = 80.0;
    let start = State::new(0.0, [0.5, 0.0, 0.0], [0.0, 0.0, omega3]);
    let (pf, pp, e) = constants(&el, &start)?;
    let fast = run_euler(top, start, 3.2)?;
    let minima: Vec<(f64, f64)> = fast
        .events_named(THETA_MIN)?
        .map(|r| (r.t, r.state.q[1]))
        .collect();
    let (Some(&(t_first, phi_first)), Some(&(t_last, phi_last)), true) =
        (minima.first(), minima.last(), minima.len() >= 5)
    else {
        return Err("the fast top made fewer than 5 nutations".into());
    };
    let mean_rate = (phi_last - phi_first) / (t_last - t_first);
    let cubic = nutation_cubic(&top, pf, pp, e);
    let roots = cubic_roots(cubic).ok_or("the nutation cubic has one real root")?;
    let (period, dphi_cycle) = nutation_quadrature(&top, cubic, roots, pf, pp);
    // Exact mean precession Δφ/T per nutation from quadrature; the run averages over whole nutations
    // between two events θ̇ = 0, with φ read off the dense output there (no interpolation between
    // samples, which cost ~1e-8 of the rate with fixed steps; measured 3.7e-10): 1e-8.
    report.checks.push(Check::rel(
        NAME,
        "fast top mean φ̇ vs quadrature Δφ/T",
        mean_rate,
        dphi_cycle / period,
        1e-8,
    ));
    // The fast-top formula M g ℓ/(I₃ ω₃) drops terms of relative size I₁ M g ℓ/(I₃ ω₃)² = 6e-4: 3e-3.
    let approx = top.mgl / (top.i3 * omega3);
    report.checks.push(Check::rel(
        NAME,
        "fast top mean φ̇ vs M g ℓ/(I₃ ω₃)",
        mean_rate,
        approx,
        3e-3,
    ));
    Ok(())
}

/// Runs the fast-top checks.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let top = GALLERY_TOP;
    let mut report = Report::default();
    fast_top(top, &mut report)?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
