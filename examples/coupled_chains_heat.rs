//! The paper's "heat" model (Figs. 10–12 of the coupled-chains paper; SEEDS part 3): the chains of
//! `coupled_chains` with an attractive coupling k2 = −0.001, the top chain resting on the bottom one
//! in a stable equilibrium, then "heated" by a random perturbation; does its energy flow to the bottom
//! chain?
//!
//! As in the paper (section 7): the equilibrium is found by adding weak friction (here the discrete
//! Lagrange-d'Alembert principle with damping C = 0.5, damped Verlet, 3000 steps from the top chain
//! placed between the bottom masses) and checked by ‖∇V‖∞; then q₁ = q₀ + ξ with ξ normal (Box–Muller,
//! seeded) with its mean removed, on the top chain only; the paper does not state the size of ξ, we
//! take standard deviation 0.001 (velocities about 0.01). The run is the paper's integrator (step
//! h = 0.1, Newton stop 1e-8) for 4096 steps, and the energy of each chain is the paper's
//! bookkeeping: central-difference kinetic energy plus the chain's springs averaged over the two
//! adjacent midpoints (the coupling energy belongs to neither chain).
//!
//! Figures: Fig. 10 (positions) → `coupled_chains_heat_positions.svg`; Fig. 11 (energy of each chain)
//! → `coupled_chains_heat_energy.svg`; Fig. 12 (power spectra |q̂_t¹|², |q̂_b¹|² of the first mass of
//! each chain) → `coupled_chains_spectrum.svg`.
//!
//! Run: `cargo run --release --features examples --example coupled_chains_heat` (the pictures go to `gallery-out/`).

use noether::discrete::chains::CoupledChains;
use noether::discrete::Verlet;
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::examples::coupled_chains::{paper_run, paper_samples, system, PaperSample};
use noether_gallery::{BoxError, Check, Options, Report};
use rand::{rngs::StdRng, Rng, SeedableRng};
use std::process::ExitCode;

const NAME: &str = "coupled_chains_heat";

/// The attractive coupling of the heat model.
const K2: f64 = -0.001;

/// Runs the heat experiment.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let ch = CoupledChains::paper(K2);

    // The equilibrium by weak damping; checked by the equilibrium condition ‖∇V‖∞ ≤ 1e-15 (measured
    // 2.0e-16: the damped motion has decayed to rounding).
    let damped = system(K2)?.damping(vec![0.5; 40])?;
    let mut q = ch.collision_start();
    q.iter_mut().take(20).for_each(|x| *x += 3.0 + 0.025); // top chain between the bottom masses
    let settled = Driver::with_step(
        Verlet::new(damped),
        State::with_momenta(0.0, q, vec![0.0; 40]),
        0.1,
    )?
    .save(Save::End)?
    .run_steps(3000)?;
    let q0 = settled.last().q.as_slice().to_vec();
    let sys = system(K2)?;
    let mut g = vec![0.0; 40];
    let v_eq = sys.gradient(&q0, &mut g);
    let gmax = g.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    report.checks.push(Check::abs(
        NAME,
        "equilibrium ‖∇V‖∞ after damping",
        gmax,
        0.0,
        1e-15,
    ));

    // The perturbation ξ (normal, mean removed) of the top chain's positions.
    let mut rng = StdRng::seed_from_u64(42);
    let mut normal = || {
        let (u, v): (f64, f64) = (1.0 - rng.random::<f64>(), rng.random());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    };
    let mut xi: Vec<f64> = (0..20).map(|_| 0.001 * normal()).collect();
    let mean = xi.iter().sum::<f64>() / 20.0;
    xi.iter_mut().for_each(|x| *x -= mean);
    let q1: Vec<f64> = q0
        .iter()
        .enumerate()
        .map(|(i, x)| x + if i < 20 { xi[i] } else { 0.0 })
        .collect();
    let warm = paper_run(K2, &q0, &q1, 4096)?;
    let samples = paper_samples(&warm, K2)?;

    // Total momentum: ξ has zero mean, so Σp = 0 up to the rounding of (q₁ − q₀)/h, and the midpoint
    // step keeps it (the residual’s component along (1,…,1) is linear): measured 2.1e-15.
    let p = warm.observed("Σp")?;
    let worst_p = p.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    report
        .checks
        .push(Check::abs(NAME, "max |Σp|", worst_p, 0.0, 1e-14));
    // Energy with the paper's bookkeeping against the injected energy E₁ − V(q_eq). Its oscillation
    // is dominated by the central-difference velocities: in a mode of frequency ω they carry the
    // factor sin(ωh)/(ωh), so K is low by (ωh)²/3; the fastest mode of a free chain has ω = 2√k1 = 2,
    // bound (2h)²/3 = 1.33e-2. Measured 9.5e-3.
    let energy: Vec<f64> = samples.iter().map(PaperSample::energy).collect();
    let worst_e = energy.iter().fold(0.0_f64, |m, e| m.max((e - energy[0]).abs()));
    let injected = energy[0] - v_eq;
    report.note(format!(
        "injected energy {injected:.6e}, largest |E − E₁| {worst_e:.3e}"
    ));
    let bound = (2.0 * ch.paper_step()).powi(2) / 3.0;
    report.checks.push(Check::abs(
        NAME,
        "paper's max |E − E₁| / injected",
        worst_e / injected,
        0.0,
        bound,
    ));
    // The same run measured with the integrator's own energy H(q_k, p_k): the midpoint rule's O(h²)
    // oscillation only, measured 1.6e-5 of the injected energy (tolerance 3e-5).
    let h0 = sys.energy(warm.q(0), warm.v(0));
    let worst_h = (0..warm.len()).fold(0.0_f64, |m, k| {
        m.max((sys.energy(warm.q(k), warm.v(k)) - h0).abs())
    });
    report.checks.push(Check::abs(
        NAME,
        "max |H − H₀| / injected",
        worst_h / injected,
        0.0,
        3e-5,
    ));

    if opts.out_dir.is_some() {
        let t: Vec<f64> = samples.iter().map(|s| s.t).collect();
        let series = |y: &mut dyn Iterator<Item = f64>| t.iter().copied().zip(y).collect::<Vec<_>>();
        let mut fig = Figure::new("Fig. 10: heat model, positions")
            .x_label("t")
            .y_label("q");
        for (name, j) in [("top 1", 0), ("top 20", 19), ("bottom 1", 20), ("bottom 20", 39)] {
            fig = fig.series(name, series(&mut (1..=t.len()).map(|k| warm.q(k)[j])));
        }
        report.save(opts, &fig, "coupled_chains_heat_positions.svg")?;
        let chain = |c: usize| series(&mut samples.iter().map(move |s| s.kinetic[c] + s.springs[c]));
        let fig = Figure::new("Fig. 11: energy of each chain (kinetic + its springs)")
            .x_label("t")
            .y_label("energy")
            .series("top (hot)", chain(0))
            .series("bottom (cold)", chain(1));
        report.save(opts, &fig, "coupled_chains_heat_energy.svg")?;
        // Power spectrum |Σ_k x(t_k) e^{−iωt_k}|² of the mean-removed first position of each chain.
        let spectrum = |j: usize| -> Vec<(f64, f64)> {
            let x = warm.q_series(j);
            let m = x.iter().sum::<f64>() / x.len() as f64;
            (1..300)
                .map(|i| {
                    let w = i as f64 * 0.01;
                    let (re, im) = warm.times().iter().zip(&x).fold((0.0, 0.0), |(a, b), (t, x)| {
                        (a + (x - m) * (w * t).cos(), b - (x - m) * (w * t).sin())
                    });
                    (w, re * re + im * im)
                })
                .collect()
        };
        let fig = Figure::new("Fig. 12: power spectrum of the first mass of each chain")
            .x_label("ω")
            .y_label("power")
            .log_y()
            .series("|q̂_t¹|²", spectrum(0))
            .series("|q̂_b¹|²", spectrum(20));
        report.save(opts, &fig, "coupled_chains_spectrum.svg")?;
    }
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
