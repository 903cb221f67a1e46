//! Periodic orbits by shooting and their Floquet multipliers: the pendulum's libration period against
//! T = 4 sqrt(l/g) K(sin(θ₀/2)), and planar Lyapunov orbits about L1 of the Earth-Moon restricted
//! three-body problem, unstable with a real multiplier pair λ, 1/λ ≈ 2700, 3.7e-4.
//!
//! `noether::analysis::periodic::Shooting` solves y(T; y₀) = y₀ by core's Newton on (y₀, T) plus one
//! unfolding parameter per first integral (the energy, held at a chosen level), with the monodromy
//! matrix M = ∂y(T)/∂y₀ from the exact step Jacobians of RK4 (`TangentStepper`); the Floquet
//! multipliers are the eigenvalues of M. The L1 orbits are continued in amplitude from the linear
//! solution x = x_L − A cos ωt, y = kA sin ωt.
//!
//! Run: `cargo run --release --features examples --example periodic_orbits` (the L1 family goes to `gallery-out/`).

use noether::analysis::periodic::{Energy, FirstIntegral, Shooting, Stability};
use noether::core::integrators::Rk4;
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::closed_form::elliptic_k_complementary;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::three_body::{l1, l1_guess, l1_linear, Cr3bp};
use std::f64::consts::PI;
use std::process::ExitCode;

const NAME: &str = "periodic_orbits";

/// The pendulum H = p²/2 − g cos q (m = l = 1), the model of the action-angle example.
pub use noether_gallery::examples::action_angle::Pendulum;

/// Runs the example.
///
/// Tolerances (measured in `crates/analysis/tests/periodic.rs`): the pendulum's period carries RK4's
/// O(h⁴) error at h = T/2000, 1.6e-12 to 1.0e-11 (relative ≤ 3.1e-12); the L1 orbits close to
/// ≤ 9.6e-13, hold their Jacobi constant to ≤ 4.4e-16, and λ·(1/λ) = 1 to ≤ 6.2e-9 (the rounding of
/// the small multiplier, ε‖M‖/|μ| ≈ 1.5e-9).
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    // The pendulum.
    let g: f64 = 9.81;
    for theta0 in [0.5_f64, 1.5, 2.5] {
        let exact = 4.0 / g.sqrt() * elliptic_k_complementary((0.5 * theta0).cos());
        let rk4 = Rk4::new(HamiltonEquations::new(Pendulum { g }));
        let mut shooting = Shooting::new(rk4, 2000)?.level(Energy(Pendulum { g }), -g * theta0.cos());
        let guess_t = 2.0 * PI / g.sqrt() * (1.0 + theta0 * theta0 / 16.0);
        let orbit = shooting.solve(&State::with_momenta(0.0, [0.95 * theta0], [0.0]), guess_t)?;
        report.checks.push(Check::rel(
            NAME,
            format!("pendulum period (θ0={theta0})"),
            orbit.period,
            exact,
            5e-12,
        ));
    }
    // Lyapunov orbits about L1, Earth-Moon.
    let mu = 0.01215;
    let (xl, c2) = l1(mu);
    let (omega, k) = l1_linear(c2);
    let t0 = 2.0 * PI / omega;
    let energy = Energy(Cr3bp { mu });
    let mut fig = Figure::new("Planar Lyapunov orbits about L1 (Earth-Moon, rotating frame)")
        .x_label("x − x_L1")
        .y_label("y");
    let mut last: Option<(f64, State<Momenta>, f64)> = None;
    let mut before: Option<(f64, State<Momenta>, f64)> = None;
    let mut amplitude = 0.001;
    while amplitude < 0.006 {
        let (guess, t_guess) = l1_guess((xl, omega, k, t0), amplitude, &last, &before);
        let e = energy.value(guess.q.as_slice(), guess.v.as_slice())?;
        let rk4 = Rk4::new(HamiltonEquations::new(Cr3bp { mu }));
        let mut shooting = Shooting::new(rk4, 4000)?
            .level(energy, e)
            .newton(noether::core::Newton::default().reuse_jacobian(false));
        let orbit = shooting.solve(&guess, t_guess)?;
        let tag = format!("A={amplitude:.4}");
        report.checks.push(Check::abs(
            NAME,
            format!("L1 orbit closure ({tag})"),
            orbit.closure,
            0.0,
            2e-12,
        ));
        let c = -2.0 * energy.value(orbit.initial.q.as_slice(), orbit.initial.v.as_slice())?;
        report.checks.push(Check::abs(
            NAME,
            format!("L1 Jacobi constant ({tag})"),
            c,
            -2.0 * e,
            2e-15,
        ));
        let fl = &orbit.floquet;
        let (big, small) = (fl.nontrivial()[0], fl.nontrivial()[1]);
        report.checks.push(Check::abs(
            NAME,
            format!("L1 λ·(1/λ) ({tag})"),
            (big * small).norm(),
            1.0,
            1e-8,
        ));
        // Unstable, with a real pair λ ≫ 1 (measured ≈ 2640-2674; the saddle of L1 alone would give
        // e^(λ_s T) ≈ 2680-2720 over one period).
        let unstable = fl.stability == Stability::Unstable && big.im == 0.0 && big.re > 1000.0;
        report.checks.push(Check::abs(
            NAME,
            format!("L1 unstable, real λ > 1000 ({tag})"),
            f64::from(u8::from(unstable)),
            1.0,
            0.5,
        ));
        // The orbit for the picture.
        let mut rk = Rk4::new(HamiltonEquations::new(Cr3bp { mu }));
        let mut st = orbit.initial.clone();
        let h = orbit.period / orbit.steps as f64;
        let mut pts = vec![(st.q[0] - xl, st.q[1])];
        for i in 0..orbit.steps {
            rk.step(&mut st, h)?;
            if i % 10 == 9 {
                pts.push((st.q[0] - xl, st.q[1]));
            }
        }
        fig = fig.series(format!("A = {amplitude:.4}, T = {:.5}", orbit.period), pts);
        before = last.replace((amplitude, orbit.initial.clone(), orbit.period));
        amplitude *= 1.5;
    }
    report.save(opts, &fig, "periodic_orbits_l1.svg")?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
