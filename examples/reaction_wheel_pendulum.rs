//! A reaction-wheel pendulum from bodies and joints (noether-multibody): a rod on a hinge, a wheel on a
//! motor at its tip (`noether_testkit::multibody::ReactionWheelPendulum`), balanced upright by spinning
//! the wheel.
//!
//! 1. **Linearised upright** by dual numbers through the built L: against the closed form
//!    θ̈ = (m g ℓ θ − u)/J_p, φ̈ = ((J_p + J_w) u − J_w m g ℓ θ)/(J_p J_w) (Åström, Block and Spong,
//!    *The Reaction Wheel Pendulum*, ch. 2), J_p = m_r l²/3 + m_w l², J_w = m_w ρ²/2,
//!    m g ℓ = (m_r/2 + m_w) g l.
//! 2. **Balanced** by LQR (Q = diag(10, 0.01, 1, 0.1) on (θ, φ, θ̇, φ̇), R = 1; the wheel's angle weighted
//!    lightly, but weighted: an unweighted free angle is a mode at 0 that the cost cannot see, and the
//!    Riccati equation then has no stabilising solution): from a 0.2 rad lean the nonlinear closed loop
//!    comes upright, the wheel spun up and back down.
//! 3. **Momentum.** Nothing outside acts about the pivot but gravity, so d/dt of the total angular
//!    momentum about the pivot, J_p θ̇ + J_w (θ̇ + φ̇), is the gravity torque m g ℓ sin θ: integrated
//!    along the balance run, the two sides agree.
//!
//! Run: `cargo run --release --features examples --example reaction_wheel_pendulum`.

use noether::analysis::{linearize, lqr};
use noether::core::control::{ClosedLoop, LinearFeedback};
use noether::nalgebra::{DMatrix, DVector};
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::multibody::ReactionWheelPendulum;
use std::process::ExitCode;

const NAME: &str = "reaction_wheel_pendulum";

/// Runs the example.
///
/// Tolerances: (A, B) to rounding (measured 3.3e-16 relative; tolerance 1e-13); the balance within
/// 1e-6 rad after 40 s (measured 7e-9: the slowest closed-loop mode decays at 0.32/s, the lightly
/// weighted wheel angle's); the momentum balance, H(t) − H(0) against ∫ m g ℓ sin θ dt by Simpson's
/// rule on states saved every Δt = 10⁻³ (measured 1.6e-8 relative to the largest change of H, which
/// the trapezoidal rule left at 9e-6; tolerance 1e-7: what is left is the run's own error, DOP853 at
/// tolerance 10⁻¹² over 40 s with the saved states from its dense output, not the rule's O(Δt⁴)).
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let rw = ReactionWheelPendulum::default();
    let mechanism = rw.mechanism();
    let lin = linearize(&mechanism, 0.0, &[0.0, 0.0], &[0.0, 0.0], &[0.0])?;
    let (a, b) = rw.upright_linearization();
    let a = DMatrix::from_fn(4, 4, |i, j| a[i][j]);
    let b = DMatrix::from_column_slice(4, 1, &b);
    let error = ((&lin.a - &a).amax() / a.amax()).max((&lin.b - &b).amax() / b.amax());
    report.checks.push(Check::abs(
        NAME,
        "(A, B) upright vs the closed form",
        error,
        0.0,
        1e-13,
    ));

    let weights = DMatrix::from_diagonal(&DVector::from_column_slice(&[10.0, 0.01, 1.0, 0.1]));
    let design = lqr(&lin, &weights, &DMatrix::from_element(1, 1, 1.0))?;
    let slowest = design
        .closed_loop
        .iter()
        .map(|l| l.re)
        .fold(f64::NEG_INFINITY, f64::max);
    report.note(format!(
        "K = {:.4?}; slowest closed-loop eigenvalue's real part {slowest:.4}",
        design.gain.as_slice()
    ));
    let feedback = LinearFeedback::new(design.gain.clone(), &[0.0, 0.0], &[0.0, 0.0], &[0.0])?;
    let closed = EulerLagrange::new(ClosedLoop::new(mechanism, feedback)?);
    let sol = Driver::new(
        Dop853::new(&closed).tolerances(1e-12, 1e-12)?,
        State::new(0.0, [0.2, 0.0], [0.0, 0.0]),
    )?
    .save(Save::Times((0..=40_000).map(|k| k as f64 * 1e-3).collect()))?
    .run_until(40.0)?;
    let last = sol.last();
    report.checks.push(Check::abs(
        NAME,
        "balanced: |θ| after 40 s",
        last.q[0].abs(),
        0.0,
        1e-6,
    ));
    let peak = (0..sol.len()).map(|i| sol.v(i)[1].abs()).fold(0.0, f64::max);
    report.note(format!(
        "the wheel's peak speed {peak:.2} rad/s, {:.2e} rad/s at the end",
        last.v[1]
    ));

    let (jp, jw, mgl) = rw.constants();
    let momentum = |i: usize| jp * sol.v(i)[0] + jw * (sol.v(i)[0] + sol.v(i)[1]);
    let torque = |i: usize| mgl * sol.q(i)[0].sin();
    // H(t) − H(0) against ∫₀ᵗ m g ℓ sin θ dt (Simpson's rule on the states saved every 10⁻³), worst
    // over the run relative to the largest change of H.
    let (mut integral, mut worst, mut scale) = (0.0_f64, 0.0_f64, 0.0_f64);
    for i in (2..sol.len()).step_by(2) {
        let dt = sol.times()[i] - sol.times()[i - 1];
        integral += dt / 3.0 * (torque(i - 2) + 4.0 * torque(i - 1) + torque(i));
        let change = momentum(i) - momentum(0);
        worst = worst.max((change - integral).abs());
        scale = scale.max(change.abs());
    }
    report.checks.push(Check::abs(
        NAME,
        "max |H(t) − H(0) − ∫ m g ℓ sin θ dt| / max |H(t) − H(0)|",
        worst / scale,
        0.0,
        1e-7,
    ));
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
