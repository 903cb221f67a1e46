//! Cyclic coordinates and Routh's reduction. The cyclic coordinates of a Lagrangian (checked by dual
//! numbers at sample points) are eliminated at their conserved momenta β: the Routhian
//! R = β·q̇_c − L, with q̇_c solved from ∂L/∂q̇_c = β inside the generic code, gives the remaining
//! coordinates a Lagrangian L_R = −R of their own (`noether::canonical::Routh`) that every
//! integrator accepts; the cyclic coordinates return by quadrature along the reduced run.
//!
//! - Kepler per unit mass in polar coordinates, φ cyclic with p_φ = ℓ: L_R = ṙ²/2 − ℓ²/(2r²) + μ/r;
//!   the reduced run has the radial period 2π sqrt(a³/μ), and φ, reconstructed, gains 2π per period.
//! - The heavy symmetric top, φ and ψ cyclic: the reduced θ-model nutates between the roots of the
//!   cubic in cos θ and, with φ and ψ reconstructed, reproduces the full three-angle model's turning
//!   points and precession.
//!
//! Run: `cargo run --release --features examples --example routh_reduction` (θ(t) and φ(t) go to `gallery-out/`).

use noether::canonical::Routh;
use noether::core::roots::bracketed_root;
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::top::{top_samples, KeplerPolar, GALLERY_TOP};
use std::f64::consts::PI;
use std::process::ExitCode;

const NAME: &str = "routh_reduction";

fn kepler(report: &mut Report) -> Result<(), BoxError> {
    let (mu, l) = (1.0, 0.8);
    let routh = Routh::new(KeplerPolar { mu }, &[1], &[l])?;
    let samples: Vec<_> = (0..5)
        .map(|i| (0.0, vec![0.5 + 0.3 * i as f64, 0.7 * i as f64], vec![0.1, 0.4]))
        .collect();
    report.checks.push(Check::abs(
        NAME,
        "Kepler: max |∂L/∂φ| at samples",
        routh.check_cyclic(&samples, 0.0)?,
        0.0,
        0.0,
    ));
    let (r, dr) = (1.3, 0.2);
    // The closed-form Routhian; measured 0 (the solve of ℓ = r² φ̇ is exact to rounding).
    report.checks.push(Check::rel(
        NAME,
        "Kepler: L_R(r, ṙ) = ṙ²/2 − ℓ²/(2r²) + μ/r",
        routh.lagrangian(0.0, &[r], &[dr]),
        dr * dr / 2.0 - l * l / (2.0 * r * r) + mu / r,
        4e-16,
    ));
    // The reduced run from the pericentre r₀ = 0.5: pericentre passages and φ per radial period.
    let r0 = 0.5;
    let e = 0.5 * l * l / (r0 * r0) - mu / r0;
    let a = -mu / (2.0 * e);
    let period = 2.0 * PI * (a * a * a / mu).sqrt();
    let dop = Dop853::new(EulerLagrange::new(&routh)).tolerances(1e-14, 1e-14)?;
    let sol = Driver::new(dop, State::new(0.0, [r0], [0.0]))?
        .keep_dense_output(true)
        .event(Event::new("pericentre", |s: &State| s.v[0]).rising())
        .run_until(3.2 * period)?;
    let peri = sol.event_times("pericentre")?;
    let phi = routh.reconstruct(&sol, &[0.0], &peri)?;
    let last = peri.len().checked_sub(1).ok_or("no pericentre passage")?;
    // Measured 2.4e-15 and 1.2e-13 rad after three periods (DOP853's global error at 1e-14).
    report.checks.push(Check::rel(
        NAME,
        "Kepler reduced: 3rd pericentre at 3 · 2π sqrt(a³/μ)",
        peri[last],
        3.0 * period,
        5e-14,
    ));
    report.checks.push(Check::abs(
        NAME,
        "Kepler reduced: φ after 3 radial periods = 6π",
        phi[last][0],
        6.0 * PI,
        5e-13,
    ));
    Ok(())
}

fn top(opts: &Options, report: &mut Report) -> Result<(), BoxError> {
    let top = GALLERY_TOP;
    let (th0, dphi0, dpsi0) = (0.8, 0.5, 5.0);
    let full = EulerLagrange::new(top);
    let mut p = [0.0; 3];
    full.momenta(0.0, &[th0, 0.0, 0.0], &[0.0, dphi0, dpsi0], &mut p)?;
    let routh = Routh::new(top, &[1, 2], &[p[1], p[2]])?;
    let samples = top_samples();
    report.checks.push(Check::abs(
        NAME,
        "top: max |∂L/∂φ|, |∂L/∂ψ| at samples",
        routh.check_cyclic(&samples, 0.0)?,
        0.0,
        0.0,
    ));
    // The other turning point: the root of the cubic f(u), u = cos θ, next to u₀ = cos θ₀.
    let energy = full.energy(0.0, &[th0, 0.0, 0.0], &[0.0, dphi0, dpsi0])?;
    let e1 = energy - p[2] * p[2] / (2.0 * top.i3);
    let f = |u: f64| {
        (1.0 - u * u) * (2.0 * e1 - 2.0 * top.mgl * u) / top.i1 - ((p[1] - p[2] * u) / top.i1).powi(2)
    };
    let u0 = th0.cos();
    let (a, b) = if f(u0 - 1e-7) > 0.0 {
        (-1.0 + 1e-9, u0 - 1e-7)
    } else {
        (u0 + 1e-7, 1.0 - 1e-9)
    };
    let theta_other = bracketed_root(f, (a, f(a)), (b, f(b)))?.acos();

    let t_end = 12.0;
    let times: Vec<f64> = (0..=600).map(|i| i as f64 * t_end / 600.0).collect();
    let dop = Dop853::new(EulerLagrange::new(top)).tolerances(1e-14, 1e-14)?;
    let sol_full = Driver::new(dop, State::new(0.0, [th0, 0.0, 0.0], [0.0, dphi0, dpsi0]))?
        .save(Save::Times(times.clone()))?
        .event(Event::new("θ̇ = 0", |s: &State| s.v[0]))
        .run_until(t_end)?;
    let dop = Dop853::new(EulerLagrange::new(&routh)).tolerances(1e-14, 1e-14)?;
    let sol_red = Driver::new(dop, State::new(0.0, [th0], [0.0]))?
        .keep_dense_output(true)
        .event(Event::new("θ̇ = 0", |s: &State| s.v[0]))
        .run_until(t_end)?;
    let (ev_full, ev_red) = (sol_full.events(), sol_red.events());
    if ev_full.len() != ev_red.len() || ev_full.len() < 2 {
        return Err(format!("turning points: full {}, reduced {}", ev_full.len(), ev_red.len()).into());
    }
    let turn_times: Vec<f64> = ev_red.iter().map(|e| e.t).collect();
    let angles = routh.reconstruct(&sol_red, &[0.0, 0.0], &turn_times)?;
    let (mut d_t, mut d_theta, mut d_cubic, mut d_phi): (f64, f64, f64, f64) = (0.0, 0.0, 0.0, 0.0);
    for (k, (ef, er)) in ev_full.iter().zip(ev_red).enumerate() {
        d_t = d_t.max((ef.t - er.t).abs());
        d_theta = d_theta.max((ef.state.q[0] - er.state.q[0]).abs());
        d_cubic = d_cubic.max((er.state.q[0] - if k % 2 == 0 { theta_other } else { th0 }).abs());
        d_phi = d_phi
            .max((ef.state.q[1] - angles[k][0]).abs())
            .max((ef.state.q[2] - angles[k][1]).abs());
    }
    // Measured 8.3e-14, 1.8e-14, 4.1e-14 and 4.3e-13 (ψ has turned through 60 rad): both runs carry
    // DOP853's global error at 1e-14.
    let n = ev_full.len();
    report.checks.push(Check::abs(
        NAME,
        format!("top: {n} turning times, reduced vs full"),
        d_t,
        0.0,
        4e-13,
    ));
    report.checks.push(Check::abs(
        NAME,
        "top: θ at the turning points, reduced vs full",
        d_theta,
        0.0,
        1e-13,
    ));
    report.checks.push(Check::abs(
        NAME,
        "top: θ at the turning points vs the cubic's roots",
        d_cubic,
        0.0,
        2e-13,
    ));
    report.checks.push(Check::abs(
        NAME,
        "top: φ, ψ at the turning points, reconstructed vs full",
        d_phi,
        0.0,
        2e-12,
    ));
    // Precession per nutation period (two turning points apart).
    let (full_prec, red_prec) = (
        ev_full[2].state.q[1] - ev_full[0].state.q[1],
        angles[2][0] - angles[0][0],
    );
    // Measured 7.7e-15.
    report.checks.push(Check::rel(
        NAME,
        "top: precession per nutation, reduced vs full",
        red_prec,
        full_prec,
        4e-14,
    ));

    let theta_full: Vec<(f64, f64)> = (0..sol_full.len())
        .map(|i| (sol_full.times()[i], sol_full.q(i)[0]))
        .collect();
    let phi_red = routh.reconstruct(&sol_red, &[0.0, 0.0], &times)?;
    let fig = Figure::new("Heavy top: θ (full model) and θ, φ (reduced to θ, φ by quadrature)")
        .x_label("t")
        .y_label("angle (rad)")
        .series("θ, full", theta_full)
        .series(
            "θ, reduced",
            (0..sol_red.len())
                .map(|i| (sol_red.times()[i], sol_red.q(i)[0]))
                .collect(),
        )
        .series(
            "φ, reconstructed",
            times.iter().zip(&phi_red).map(|(&t, a)| (t, a[0])).collect(),
        );
    report.save(opts, &fig, "routh_reduction_top.svg")?;
    Ok(())
}

/// Runs the example.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    kepler(&mut report)?;
    top(opts, &mut report)?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
