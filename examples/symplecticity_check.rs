//! Self-checks of integrators (`noether::core::selfcheck`): is the step symplectic, which order does
//! it show, is it reversible — the same functions noether's own tests use, here on RK4, Euler-Cromer
//! (symplectic Euler for H = ½|p|² + V) and the midpoint variational integrator (Newton on the
//! discrete Euler-Lagrange equations, step Jacobian by the implicit-function theorem).
//!
//! - Symplecticity: the defect ‖ΨᵀΩΨ − Ω‖_max of the step's Jacobian Ψ. On the oscillator
//!   H = ½(p² + q²) RK4's Ψ is its stability polynomial of hA, and in one degree of freedom
//!   ΨᵀΩΨ = det(Ψ) Ω with det Ψ = 1 − h⁶/72 + h⁸/576: the defect is h⁶/72 − h⁸/576 exactly. On
//!   Hénon-Heiles (nonlinear) the defect is O(h⁵): halving h divides it by 2⁵. Euler-Cromer and the
//!   variational integrator give rounding.
//! - Observed order: the least-squares slope of log(error) against log(h) on the oscillator against
//!   its closed form q = cos t, p = −sin t, with the correlation coefficient r of the fit.
//! - Reversibility: one step, p → −p, one step, p → −p is the identity for a symmetric method on a
//!   reversible system: the midpoint integrator comes back to the start within rounding.
//!
//! Run: `cargo run --release --features examples --example symplecticity_check` (the error-vs-h plot goes to `gallery-out/`).

use noether::core::integrators::{EulerCromer, Rk4};
use noether::core::selfcheck::{observed_order, reversibility, symplecticity};
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::henon_heiles::HenonHeiles;
use std::process::ExitCode;

/// Harmonic oscillator H = ½(p² + q²) (for RK4 and Euler-Cromer).
pub struct Oscillator;
impl Hamiltonian for Oscillator {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        (p[0] * p[0] + q[0] * q[0]) * 0.5
    }
}

/// The same oscillator as L = ½(q̇² − q²) (for the variational integrator).
pub struct OscillatorL;
impl Lagrangian for OscillatorL {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] - q[0] * q[0]) * 0.5
    }
}

/// Hénon-Heiles as L = ½|q̇|² − V (p = q̇).
pub struct HenonHeilesL;
impl Lagrangian for HenonHeilesL {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + v[1] * v[1] - q[0] * q[0] - q[1] * q[1]) * 0.5 - q[0] * q[0] * q[1]
            + q[1].powi(3) / 3.0
    }
}

/// Four Hénon-Heiles states (q, p) of energies 0.02 to 0.16, below the escape energy 1/6.
fn henon_heiles_states() -> Vec<State<Momenta>> {
    vec![
        State::with_momenta(0.0, [0.1, -0.2], [0.45, 0.1]),
        State::with_momenta(0.0, [0.0, 0.0], [0.2, 0.0]),
        State::with_momenta(0.0, [-0.3, 0.1], [0.1, -0.35]),
        State::with_momenta(0.0, [0.2, 0.4], [-0.2, 0.1]),
    ]
}

/// Runs the example.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let ex = "symplecticity_check";
    let mut report = Report::default();

    // 1. RK4 on the oscillator: defect h⁶/72 − h⁸/576 exactly. The computed defect is that number plus
    // the rounding of ΨᵀΩΨ (entries of unit size, ~ε): relative 1e-16/8.9e-7 ≈ 1e-10 at h = 0.2
    // (measured: see the check). Tolerance 1e-9 relative.
    let osc = HamiltonEquations::new(Oscillator);
    let h: f64 = 0.2;
    let start = State::with_momenta(0.0, [1.0], [0.0]);
    let d = symplecticity(&mut Rk4::new(&osc), std::slice::from_ref(&start), h)?;
    report.checks.push(Check::rel(
        ex,
        "RK4 defect on the oscillator, h = 0.2 (= h⁶/72 − h⁸/576)",
        d.worst,
        h.powi(6) / 72.0 - h.powi(8) / 576.0,
        1e-9,
    ));

    // 2. Hénon-Heiles at four states, h = 0.1: RK4 fails by O(h⁵) (log₂ of the ratio at h and h/2 is 5
    // up to the next order: measured 5.13, tolerance 0.3), Euler-Cromer and the midpoint integrator
    // pass to rounding (measured worst 6.6e-18 and 2.2e-16, a few ε; tolerance 1e-14).
    let hh = HamiltonEquations::new(HenonHeiles);
    let states = henon_heiles_states();
    let rk4 = symplecticity(&mut Rk4::new(&hh), &states, 0.1)?;
    let rk4_half = symplecticity(&mut Rk4::new(&hh), &states, 0.05)?;
    let ec = symplecticity(&mut EulerCromer::new(&hh), &states, 0.1)?;
    let vi = symplecticity(
        &mut VariationalIntegrator::new(Midpoint::new(HenonHeilesL)),
        &states,
        0.1,
    )?;
    for (name, s) in [
        ("RK4", &rk4),
        ("Euler-Cromer", &ec),
        ("midpoint variational", &vi),
    ] {
        let d: Vec<String> = s.defects.iter().map(|d| format!("{d:.2e}")).collect();
        report.note(format!(
            "{name}: defects at the four Hénon-Heiles states (h = 0.1): {}",
            d.join(", ")
        ));
    }
    report.checks.push(Check::abs(
        ex,
        "RK4 on Hénon-Heiles: log₂(defect(h)/defect(h/2)) (= 5, O(h⁵))",
        (rk4.worst / rk4_half.worst).log2(),
        5.0,
        0.3,
    ));
    report.checks.push(Check::abs(
        ex,
        "Euler-Cromer on Hénon-Heiles: worst ‖ΨᵀΩΨ − Ω‖_max (= 0)",
        ec.worst,
        0.0,
        1e-14,
    ));
    report.checks.push(Check::abs(
        ex,
        "midpoint variational on Hénon-Heiles: worst ‖ΨᵀΩΨ − Ω‖_max (= 0)",
        vi.worst,
        0.0,
        1e-14,
    ));

    // 3. Observed orders on the oscillator over t = 5 against q = cos t, p = −sin t: slopes within 0.02
    // of the nominal order (the fits' next-order terms: measured RK4 4.0085, Euler-Cromer 1.0017 with
    // r = 1 − 1.4e-7 and 1 − 1.3e-7 in core's tangent tests), r within 1e-5 of 1.
    let t_end: f64 = 5.0;
    let exact = State::with_momenta(t_end, [t_end.cos()], [-t_end.sin()]);
    let fits = [
        (
            "RK4",
            4.0,
            observed_order(&mut Rk4::new(&osc), &start, t_end, &[50, 100, 200, 400], &exact)?,
        ),
        (
            "Euler-Cromer",
            1.0,
            observed_order(
                &mut EulerCromer::new(&osc),
                &start,
                t_end,
                &[500, 1000, 2000, 4000],
                &exact,
            )?,
        ),
        (
            "midpoint variational",
            2.0,
            observed_order(
                &mut VariationalIntegrator::new(Midpoint::new(OscillatorL)),
                &start,
                t_end,
                &[100, 200, 400, 800],
                &exact,
            )?,
        ),
    ];
    let mut fig = Figure::new("Observed order on the oscillator: error at t = 5 against the step")
        .x_label("log₁₀ h")
        .y_label("max |y − y_exact|")
        .log_y();
    for (name, p, fit) in &fits {
        report.checks.push(Check::abs(
            ex,
            format!("{name}: observed order"),
            fit.slope,
            *p,
            0.02,
        ));
        report.checks.push(Check::abs(
            ex,
            format!("{name}: correlation r of the fit"),
            fit.r,
            1.0,
            1e-5,
        ));
        let pts = fit.points.iter().map(|(h, e)| (h.log10(), *e)).collect();
        fig = fig.series(format!("{name} (slope {:.3})", fit.slope), pts);
    }

    // 4. Reversibility of the midpoint integrator on Hénon-Heiles: within 4 ulps of the state's scale.
    let rev = reversibility(
        &mut VariationalIntegrator::new(Midpoint::new(HenonHeilesL)),
        &states[0],
        0.1,
    )?;
    let rev_rk4 = reversibility(&mut Rk4::new(&hh), &states[0], 0.1)?;
    report.note(format!(
        "round trip ρΦρΦ: midpoint variational {:.1} ulps, RK4 {:.2e} relative",
        rev.ulps, rev_rk4.relative
    ));
    report.checks.push(Check::abs(
        ex,
        "midpoint variational: ρΦ_hρΦ_h − id in ulps (= 0)",
        rev.ulps,
        0.0,
        4.0,
    ));
    report.save(opts, &fig, "symplecticity_check_orders.svg")?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main("symplecticity_check", run)
}
