//! Quasi-velocities and the Gibbs-Appell equations: Euler's equations of a rigid body, and the rolling
//! disk without multipliers.
//!
//! A system is described by k quasi-velocities u with q̇ = W(t, q) u + w(t, q), by where its mass is
//! (particles r_i(t, q), rigid parts with centre, body-frame angular velocity and inertia) and by its
//! forces. noether forms the Gibbs function (acceleration energy)
//! S = Σ ½ m_i |r̈_i|² + Σ_b [½ M |c̈|² + ½ α·I α + α·(ω × I ω)] by dual numbers, and solves the
//! Gibbs-Appell equations ∂S/∂u̇ = Π (Π = Wᵀ Q) for u̇.
//!
//! 1. A rigid body of four particles turning about a fixed point in gravity, q the unit quaternion and
//!    u = ω in body axes (q̇ = ½ q ⊗ (0, ω)): S built from the particles gives exactly Euler's equations
//!    I ω̇ + ω × I ω = N about the fixed point, and so does the rigid-part Gibbs function.
//! 2. A vertical disk rolling without slipping on an inclined plane, q = (x, y, θ, φ), u = (θ̇, φ̇):
//!    q̇ = (R θ̇ cos φ, R θ̇ sin φ, θ̇, φ̇) satisfies the two rolling constraints by construction, so the
//!    equations have 2 unknowns u̇ instead of the multiplier form's 4 accelerations and 2 multipliers.
//!    Both give the same accelerations, and the closed form θ̇(t) = θ̇₀ − 2 g' (sin φ − sin φ₀)/(3 R φ̇)
//!    with φ = φ₀ + φ̇ t (θ̈ = −m g' R cos φ/(m R² + I), I = ½ m R², φ̈ = 0).
//!
//! Run: `cargo run --release --features examples --example gibbs_appell`.

use noether::constraints::{GibbsAppellEquations, QuasiVelocities};
use noether::core::integrators::Rk4;
use noether::nalgebra::Vector3;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::gibbs_appell::*;
use std::process::ExitCode;

const NAME: &str = "gibbs_appell";

/// Largest |x| of a series.
fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// Check 1: ω̇ from the particles' and the rigid part's Gibbs function against Euler's equations.
fn euler(checks: &mut Vec<Check>) -> Result<(), BoxError> {
    let (mass, c, i_o, i_c) = inertia();
    let particles = GibbsAppellEquations::new(ParticleTop)?;
    let body = GibbsAppellEquations::new(BodyTop {
        mass,
        c: [c[0], c[1], c[2]],
        i_c,
    })?;
    let q = unit([0.8_f64, 0.3, -0.4, 0.2]);
    let w = [2.0, 0.7, -1.5];
    // N = Σ ρ_i × Rᵀ(−m_i g ẑ): gravity in body axes is ẑ rotated by q̄.
    let exact = euler_rates(&i_o, &q, w).ok_or("singular inertia tensor")?;
    let (mut a, mut b) = ([0.0; 3], [0.0; 3]);
    particles.accelerations(0.0, &q, &w, &mut a)?;
    body.accelerations(0.0, &q, &w, &mut b)?;
    let rel = |x: [f64; 3]| (Vector3::from(x) - exact).norm() / exact.norm();
    // Both agree with Euler to rounding (measured 1.1e-16 for both): 2e-15.
    checks.push(Check::abs(
        NAME,
        "|ω̇ − I⁻¹(N − ω × Iω)|/|ω̇|, S from particles",
        rel(a),
        0.0,
        2e-15,
    ));
    checks.push(Check::abs(
        NAME,
        "|ω̇ − I⁻¹(N − ω × Iω)|/|ω̇|, S of a rigid part",
        rel(b),
        0.0,
        2e-15,
    ));

    // Torque-free (centre at the fixed point, no gravity): energy and |L| = |I_c ω| are constant.
    let free = GibbsAppellEquations::new(free_body())?;
    let w0 = [0.5, -1.0, 3.0];
    let energy = move |w: &[f64]| {
        0.5 * Vector3::from_column_slice(&w[..3]).dot(&(i_c * Vector3::from_column_slice(&w[..3])))
    };
    let casimir = move |w: &[f64]| (i_c * Vector3::from_column_slice(&w[..3])).norm();
    let (e0, l0) = (energy(&w0), casimir(&w0));
    let sol = Driver::with_step(Rk4::new(&free), free.state(0.0, &q, &w0)?, 1e-3)?
        .observe("dE", move |s: &State<QuasiVelocities>| {
            (energy(s.v.as_slice()) - e0) / e0
        })
        .observe("dL", move |s: &State<QuasiVelocities>| {
            (casimir(s.v.as_slice()) - l0) / l0
        })
        .run_until(10.0)?;
    let de = max_abs(&sol.observed("dE")?);
    let dl = max_abs(&sol.observed("dL")?);
    // RK4, h = 1e-3, 10 s: measured 1.5e-14 and 7.9e-15: 5e-14.
    checks.push(Check::abs(
        NAME,
        "free body: max rel. drift of ½ ω·Iω (RK4, 10 s)",
        de,
        0.0,
        5e-14,
    ));
    checks.push(Check::abs(
        NAME,
        "free body: max rel. drift of |Iω| (RK4, 10 s)",
        dl,
        0.0,
        5e-14,
    ));
    Ok(())
}

/// Check 2: the rolling disk, Gibbs-Appell against the multiplier form and the closed form.
fn disk(checks: &mut Vec<Check>) -> Result<(), BoxError> {
    let (q, u) = ([0.1_f64, -0.4, 0.3, 0.9], [6.0_f64, 0.8]);
    // q̈ with multipliers, and q̈ = W u̇ + Ẇ u from the Gibbs-Appell u̇.
    let (qdd, from_ga) = disk_both_ways(&q, &u)?;
    let diff = qdd
        .iter()
        .zip(from_ga)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()))
        / max_abs(&qdd);
    // The same accelerations to rounding (measured 4.9e-16): 4e-15.
    checks.push(Check::abs(
        NAME,
        "disk: max|q̈ (Gibbs-Appell) − q̈ (multipliers)|/|q̈|",
        diff,
        0.0,
        4e-15,
    ));

    let (th0, ph0, phd) = (6.0, 0.4, 0.8);
    let (ga_sol, m_sol) = disk_runs(th0, ph0, phd)?;
    let err = max_abs(&ga_sol.observed("err")?);
    let dq = (&ga_sol.last().q - &m_sol.last().q).amax();
    // RK4, h = 1e-3, 10 s: θ̇ measured 4.1e-13 (truncation): 1e-12; the two runs' q at the end differ by
    // 1.9e-14 (rounding): 1e-13.
    checks.push(Check::abs(
        NAME,
        "disk: max|θ̇ − closed form| over 10 s [rad/s]",
        err,
        0.0,
        1e-12,
    ));
    checks.push(Check::abs(
        NAME,
        "disk: |q(10 s), Gibbs-Appell − multipliers|∞",
        dq,
        0.0,
        1e-13,
    ));
    Ok(())
}

/// Runs the Gibbs-Appell checks: Euler's equations and the rolling disk.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let mut checks = Vec::new();
    euler(&mut checks)?;
    disk(&mut checks)?;
    Ok(Report {
        checks,
        ..Default::default()
    })
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
