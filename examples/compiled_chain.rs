//! A chain of 40 pendulums (point masses on rods, angles from the vertical) run twice: compiled and by
//! dual numbers, the same Lagrangian, the same method, agreeing; with the time of each.
//!
//! L = Σ_k ½ m_k (ẋ_k² + ẏ_k²) − Σ_k m_k g y_k, with x_k = Σ_{i≤k} l_i sin θ_i, y_k = −Σ_{i≤k} l_i cos θ_i,
//! written as running sums (O(N) operations, as a user would write it). Its mass matrix is full:
//! M_ij = l_i l_j cos(θ_i − θ_j) Σ_{k ≥ max(i, j)} m_k.
//!
//! `EulerLagrange::new(chain).compile()` records L once, derives M and the force terms of M q̈ = b on the
//! graph and simplifies them; above 12 degrees of freedom the program gives M and b and one dense
//! factorisation solves, as the dual-number path does. DOP853 then runs on the compiled system exactly
//! as on the dual-number one.
//!
//! The checks:
//! - q̈ of the compiled system at the start equals the chain's hand-derived equations (the recursive
//!   form of the test models, `noether_testkit::systems::Chain::hand_accelerations`);
//! - the two runs end at the same state, to the integrator's tolerance;
//! - the energy of the compiled run stays at its start value, to the integrator's tolerance.
//!
//! The times of both runs and their ratio are printed (with the native backend, `--features jit`,
//! the compiled run is faster still; see docs/benchmarks.md, "Compiled models").
//!
//! Run: `cargo run --release --features examples --example compiled_chain`.

use noether::compile::{Backend, Compile};
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::systems::Chain;
use std::process::ExitCode;
use std::time::Instant;

/// Links of the chain.
const N: usize = 40;

/// The integrator's tolerances (atol = rtol).
const TOL: f64 = 1e-10;

/// Length of the run.
const T_END: f64 = 1.0;

/// The start: a gentle wave along the chain, at rest.
fn start() -> State {
    let q: [f64; N] = std::array::from_fn(|i| 0.3 * (0.25 * i as f64).sin());
    State::new(0.0, q, [0.0; N])
}

/// Runs DOP853 at [`TOL`] on `system` from [`start`] to [`T_END`]: the end state and the seconds taken.
fn run_on<S: Dynamics<Partner = Velocities>>(system: S) -> Result<(State, f64), BoxError> {
    let t0 = Instant::now();
    let sol = Driver::new(Dop853::new(system).tolerances(TOL, TOL)?, start())?.run_until(T_END)?;
    Ok((sol.last().clone(), t0.elapsed().as_secs_f64()))
}

/// Runs the example.
///
/// Tolerances. q̈ at the start against the hand-derived equations: 5e-14 relative, the bound of
/// noether-compile's tests for chains (the two round differently through an ill-conditioned M; the
/// hand-derived and the dual-number q̈ differ by as much). The two runs: DOP853 at atol = rtol = 1e-10
/// takes the same steps on both systems up to the last bits of q̈, so the end states differ by rounding
/// amplified along the run, far below the tolerance: measured 3e-14, checked at 1e-9 (the tolerance
/// times 10). The energy: DOP853's error per unit time at this tolerance, measured 2e-11 relative,
/// checked at 1e-9.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let chain = Chain::<N>::default();
    let t0 = Instant::now();
    let compiled = EulerLagrange::new(chain).compile()?;
    let built = t0.elapsed().as_secs_f64();
    let ops = compiled.operations();
    report.note(format!(
        "compiled in {:.1} ms: {} operations requested by the derivation, {} in the program of M and b",
        built * 1e3,
        ops.requested,
        ops.accelerations
    ));

    let s = start();
    let mut a = [0.0; N];
    compiled.accelerations(0.0, s.q.as_slice(), s.v.as_slice(), &mut a)?;
    let q: [f64; N] = std::array::from_fn(|i| s.q[i]);
    let hand = chain.hand_accelerations(&q, &[0.0; N]);
    let scale = hand.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let diff = a
        .iter()
        .zip(&hand)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    report.checks.push(Check::abs(
        "compiled_chain",
        "q̈ at the start vs the hand-derived equations, max relative",
        diff / scale,
        0.0,
        5e-14,
    ));

    let (end_c, time_c) = run_on(&compiled)?;
    let (end_d, time_d) = run_on(EulerLagrange::new(chain))?;
    let gap = (&end_c.q - &end_d.q).amax().max((&end_c.v - &end_d.v).amax());
    report.checks.push(Check::abs(
        "compiled_chain",
        "compiled vs dual-number run: max |Δq|, |Δq̇| at the end",
        gap,
        0.0,
        1e-9,
    ));
    let e0 = compiled.energy(0.0, s.q.as_slice(), s.v.as_slice())?;
    let e1 = compiled.energy(T_END, end_c.q.as_slice(), end_c.v.as_slice())?;
    report.checks.push(Check::abs(
        "compiled_chain",
        "energy of the compiled run, relative change",
        ((e1 - e0) / e0).abs(),
        0.0,
        1e-9,
    ));
    report.note(format!(
        "DOP853 at {TOL:e} to t = {T_END}: compiled {:.0} ms, dual numbers {:.0} ms ({:.1}× faster compiled, {} backend)",
        time_c * 1e3,
        time_d * 1e3,
        time_d / time_c,
        match compiled.backend() {
            Backend::Native => "native",
            Backend::Interpreter => "interpreter",
        }
    ));
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main("compiled_chain", run)
}
