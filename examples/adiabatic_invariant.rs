//! The adiabatic invariant: an oscillator whose frequency rises slowly from 1 to 4,
//!
//! ```text
//! H = p²/2 + ω(εt)² q²/2,   ω(τ) = 1 + 3 (1 − cos πτ)/2,  0 ≤ τ = εt ≤ 1,
//! ```
//!
//! gains four times its energy while the action J = E/ω of the Hamiltonian frozen at each instant
//! stays constant to O(ε). J(t) is computed the way it would be for any H: the libration of H frozen
//! at t through the current state, by quadrature (`ActionAngle::frozen_libration`), checked against
//! E/ω. Checks: E grows by ω(end)/ω(0) = 4; the largest excursion of J halves when ε halves (O(ε));
//! what is left after the ramp, where dω/dt vanishes again, falls four-fold (O(ε²)).
//!
//! Run: `cargo run --release --features examples --example adiabatic_invariant` (E(t) and J(t) go to `gallery-out/`).

use noether::canonical::ActionAngle;
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use std::f64::consts::PI;
use std::process::ExitCode;

const NAME: &str = "adiabatic_invariant";

/// The ramped oscillator (see the module docs).
#[derive(Debug, Clone, Copy)]
pub struct Ramp {
    /// The slowness ε: the ramp lasts 1/ε.
    pub eps: f64,
}

impl Ramp {
    /// ω(εt).
    pub fn omega<D: Scalar>(&self, t: D) -> D {
        ((t * (self.eps * PI)).cos() * -1.0 + 1.0) * 1.5 + 1.0
    }
}

impl Hamiltonian for Ramp {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D]) -> D {
        let w = self.omega(t);
        p[0] * p[0] * 0.5 + w * w * q[0] * q[0] * 0.5
    }
}

/// One run: the samples (t, E, J), the largest |J − J₀|, the final |J − J₀|, the largest |J − E/ω|/J.
struct Run {
    samples: Vec<(f64, f64, f64)>,
    excursion: f64,
    last: f64,
    closed: f64,
}

fn ramp_run(eps: f64) -> Result<Run, BoxError> {
    let ramp = Ramp { eps };
    let aa = ActionAngle::new(ramp)?;
    let t_end = 1.0 / eps;
    let times: Vec<f64> = (0..=200).map(|i| i as f64 * t_end / 200.0).collect();
    let dop = Dop853::new(HamiltonEquations::new(ramp)).tolerances(1e-13, 1e-13)?;
    let sol = Driver::new(dop, State::with_momenta(0.0, [1.0], [0.0]))?
        .save(Save::Times(times))?
        .run_until(t_end)?;
    let j0 = 0.5; // E(0)/ω(0)
    let mut run = Run {
        samples: Vec::new(),
        excursion: 0.0,
        last: 0.0,
        closed: 0.0,
    };
    for i in 0..sol.len() {
        let (t, q, p) = (sol.times()[i], sol.q(i)[0], sol.v(i)[0]);
        let lib = aa.frozen_libration(t, q, p, 0.0)?;
        let w: f64 = ramp.omega(t);
        run.closed = run.closed.max(((lib.action - lib.energy / w) / lib.action).abs());
        run.excursion = run.excursion.max((lib.action - j0).abs());
        run.last = (lib.action - j0).abs();
        run.samples.push((t, lib.energy, lib.action));
    }
    Ok(run)
}

/// Runs the example.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let eps = [0.02, 0.01, 0.005];
    let runs: Vec<Run> = eps.iter().map(|&e| ramp_run(e)).collect::<Result<_, _>>()?;
    for (e, r) in eps.iter().zip(&runs) {
        let &(_, e_end, _) = r.samples.last().ok_or("no samples")?;
        // E(end)/E(0) = ω(end)/ω(0) = 4 up to the final change of J: measured 15 ε².
        report.checks.push(Check::abs(
            NAME,
            format!("E(end)/E(0) = 4 (ε = {e})"),
            e_end / 0.5,
            4.0,
            20.0 * e * e,
        ));
        // The frozen action by quadrature against E/ω: measured ≤ 6.6e-16.
        report.checks.push(Check::abs(
            NAME,
            format!("J by quadrature vs E/ω (ε = {e})"),
            r.closed,
            0.0,
            2e-15,
        ));
    }
    for k in 0..2 {
        // Measured 2.004 and 2.018 (the excursion is ≈ 0.43 ε).
        report.checks.push(Check::abs(
            NAME,
            format!("max |ΔJ| ratio for ε = {} → {} (O(ε): 2)", eps[k], eps[k + 1]),
            runs[k].excursion / runs[k + 1].excursion,
            2.0,
            0.1,
        ));
        // Measured 4.10 and 3.92.
        report.checks.push(Check::abs(
            NAME,
            format!("final |ΔJ| ratio for ε = {} → {} (O(ε²): 4)", eps[k], eps[k + 1]),
            runs[k].last / runs[k + 1].last,
            4.0,
            0.5,
        ));
    }
    let slow = &runs[2];
    let fig = Figure::new("Oscillator with ω: 1 → 4 over t = 1/ε (ε = 0.005): E(t)/E(0) and J(t)/J(0)")
        .x_label("t")
        .y_label("ratio")
        .series(
            "E / E(0)",
            slow.samples.iter().map(|&(t, e, _)| (t, e / 0.5)).collect(),
        )
        .series(
            "J / J(0)",
            slow.samples.iter().map(|&(t, _, j)| (t, j / 0.5)).collect(),
        );
    report.save(opts, &fig, "adiabatic_invariant.svg")?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
