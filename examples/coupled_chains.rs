//! Momentum and energy transfer between two coupled mass-spring chains (SEEDS part 3), integrated with
//! the midpoint variational integrator L_d = h L((q₀+q₁)/2, (q₁−q₀)/h) solved by Newton (tolerance
//! 1e-8 on the residual, as in the paper).
//!
//! Model (`noether::discrete::chains::CoupledChains`): two chains of 20 unit masses, springs k1 = 1 of
//! natural length l = 1/20, Gaussian coupling k2 exp(−(q_t^i − q_b^j)²/(2σ²)) between all 400 top/bottom
//! pairs, σ = 0.1, step h = min(2π/(10√k1), 0.1) = 0.1. The variational integrator works on
//! position-momentum states (q, p), `State<Momenta>`; the quantities checked are observers of the
//! driver, recorded at every step.
//!
//! 1. Collision (k2 = 0.001, repulsive): top chain shifted by −3 moving at v0 = 0.1, bottom at rest.
//!    Checks: the discrete Noether momentum of translations Σ p_i stays at its initial value 20·v0 to
//!    rounding (the residual's component along (1,…,1) is linear in q_{k+1} and vanishes with each
//!    Newton iteration; rounding of 40 momenta per step over 1000 steps: < 1e-13); the energy error
//!    stays a small fraction of the largest potential-energy change (the paper's observation; midpoint
//!    error O(h²) with h = 0.1: measured 1e-4, allowed 1e-3).
//! 2. Momentum transferred to the bottom chain after the collision as a function of v0 (a table);
//!    each run conserves the total (checked to 1e-13).
//! 3. "Heat" (k2 = −0.001, attractive): a stable equilibrium found by weak damping (the discrete
//!    Lagrange-d'Alembert principle, damped Verlet), checked by ‖∇V‖∞ ≤ 1e-8 (the equilibrium condition);
//!    then a random zero-mean perturbation of the top chain's velocities, the energy of each chain over
//!    time, and the power spectrum of the top chain's first position. Checks: total momentum stays 0
//!    (1e-13) and the total energy error stays below 1e-4 of the injected energy (measured 1e-5:
//!    O(h²) oscillation of the midpoint energy for kicks of 0.01).
//!
//! Run: `cargo run --release --example coupled_chains` (the pictures go to `gallery-out/`).

use noether::core::Newton;
use noether::discrete::chains::CoupledChains;
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use rand::{rngs::StdRng, Rng, SeedableRng};
use std::process::ExitCode;

const NAME: &str = "coupled_chains";

/// The two chains with coupling `k2` as a mechanical system L = ½q̇ᵀq̇ − V(q) (unit masses).
fn system(k2: f64) -> Result<Mechanical<CoupledChains>, BoxError> {
    Ok(Mechanical::new(
        Mass::Diagonal(vec![1.0; 40]),
        CoupledChains::paper(k2),
    )?)
}

/// Energy of one chain (kinetic + its own springs), c = 0 top, 1 bottom.
fn chain_energy(ch: &CoupledChains, q: &[f64], p: &[f64], c: usize) -> f64 {
    let n = ch.n;
    let kin: f64 = p[c * n..(c + 1) * n].iter().map(|x| 0.5 * x * x).sum();
    let springs: f64 = (0..n - 1)
        .map(|i| {
            let e = q[c * n + i + 1] - q[c * n + i] - ch.l;
            0.5 * ch.k1 * e * e
        })
        .sum();
    kin + springs
}

/// Total momentum of one chain (c = 0 top, 1 bottom) at a state.
fn chain_momentum(p: &[f64], c: usize) -> f64 {
    p[c * 20..(c + 1) * 20].iter().sum()
}

/// One collision run with initial top velocity `v0` for `steps` steps, saving `save`; observes the
/// total momentum "Σp", the energy "E" and the potential energy "V" at each saved state.
fn collision(v0: f64, steps: usize, save: Save) -> Result<Solution<Momenta>, BoxError> {
    let ch = CoupledChains::paper(0.001);
    let sys = system(0.001)?;
    let p: Vec<f64> = (0..40).map(|k| if k < 20 { v0 } else { 0.0 }).collect();
    let vi = MechanicalMidpoint::new(system(0.001)?).with_newton(Newton::default().tol_residual(1e-8));
    let sol = Driver::with_step(vi, State::new(0.0, ch.collision_start(), p), ch.paper_step())?
        .save(save)?
        .observe("Σp", |s: &State<Momenta>| s.p().sum())
        .observe("E", |s: &State<Momenta>| {
            sys.energy(s.q.as_slice(), s.p().as_slice())
        })
        .observe("V", |s: &State<Momenta>| sys.potential_energy(s.q.as_slice()))
        .run_steps(steps)?;
    Ok(sol)
}

/// The observed series `name` of a run.
fn observed<K: Partner>(sol: &Solution<K>, name: &str) -> Result<Vec<f64>, BoxError> {
    Ok(sol.observed(name).ok_or(format!("no {name} observed"))?)
}

/// Runs the three experiments.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let ch = CoupledChains::paper(0.001);

    // 1. The main collision run, v0 = 0.1, t ∈ [0, 100], every step saved.
    let traj = collision(0.1, 1000, Save::Steps)?;
    let p_total = observed(&traj, "Σp")?;
    let dp = p_total.iter().map(|p| (p - 2.0).abs()).fold(0.0, f64::max);
    report
        .checks
        .push(Check::abs(NAME, "max |Σp − 20 v0| (v0=0.1)", dp, 0.0, 1e-13));
    let energy = observed(&traj, "E")?;
    let pot = observed(&traj, "V")?;
    let de = energy.iter().map(|e| (e - energy[0]).abs()).fold(0.0, f64::max);
    let dv = pot.iter().map(|v| (v - pot[0]).abs()).fold(0.0, f64::max);
    report.checks.push(Check::abs(
        NAME,
        "max |ΔE| / max |ΔV| (v0=0.1)",
        de / dv,
        0.0,
        1e-3,
    ));
    let last = traj.last().p().as_slice();
    let (pt, pb) = (chain_momentum(last, 0), chain_momentum(last, 1));
    println!("coupled_chains: after the collision p_top = {pt:.6}, p_bottom = {pb:.6} (t = 100)");

    // 2. Momentum transferred vs v0: run until the chains have separated (t = 5/v0 + 40).
    let mut table = Vec::new();
    for v0 in [0.05, 0.1, 0.2, 0.4] {
        let steps = ((5.0 / v0 + 40.0) / ch.paper_step()).round() as usize;
        let end = collision(v0, steps, Save::End)?;
        let p = end.last().p().as_slice();
        let (pt, pb) = (chain_momentum(p, 0), chain_momentum(p, 1));
        println!(
            "coupled_chains: v0 = {v0:.2}: p_top = {pt:.6e}, p_bottom = {pb:.6e}, transferred {:.3e}",
            pb
        );
        report.checks.push(Check::abs(
            NAME,
            format!("Σp conserved (v0={v0})"),
            pt + pb,
            20.0 * v0,
            1e-13,
        ));
        table.push((v0, pb / (20.0 * v0)));
    }

    // 3. Heat: equilibrium of the attractive coupling by weak damping, then a random perturbation.
    let k2 = -0.001;
    let damped = system(k2)?.with_damping(vec![0.5; 40])?;
    let mut q = ch.collision_start();
    q.iter_mut().take(20).for_each(|x| *x += 3.0 + 0.025); // top chain between the bottom masses
    let settled = Driver::with_step(Verlet::new(damped), State::new(0.0, q, vec![0.0; 40]), 0.1)?
        .save(Save::End)?
        .run_steps(3000)?;
    let q = settled.last().q.as_slice().to_vec();
    let heat = system(k2)?;
    let mut g = vec![0.0; 40];
    heat.gradient(&q, &mut g);
    let gmax = g.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    report.checks.push(Check::abs(
        NAME,
        "equilibrium ‖∇V‖∞ after damping",
        gmax,
        0.0,
        1e-8,
    ));
    let mut rng = StdRng::seed_from_u64(42);
    let mut kick: Vec<f64> = (0..20)
        .map(|_| 0.01 * (rng.random::<f64>() * 2.0 - 1.0))
        .collect();
    let mean = kick.iter().sum::<f64>() / 20.0;
    kick.iter_mut().for_each(|x| *x -= mean);
    let e_eq = heat.energy(&q, &[0.0; 40]);
    let p: Vec<f64> = kick.iter().copied().chain([0.0; 20]).collect();
    let e0 = heat.energy(&q, &p);
    let vi = MechanicalMidpoint::new(system(k2)?).with_newton(Newton::default().tol_residual(1e-10));
    let chains = CoupledChains::paper(k2);
    let warm = Driver::with_step(vi, State::new(0.0, q, p), 0.1)?
        .observe("E top", |s: &State<Momenta>| {
            chain_energy(&chains, s.q.as_slice(), s.p().as_slice(), 0)
        })
        .observe("E bottom", |s: &State<Momenta>| {
            chain_energy(&chains, s.q.as_slice(), s.p().as_slice(), 1)
        })
        .observe("E", |s: &State<Momenta>| {
            heat.energy(s.q.as_slice(), s.p().as_slice())
        })
        .observe("Σp", |s: &State<Momenta>| s.p().sum())
        .run_steps(4096)?;
    let worst_p = observed(&warm, "Σp")?
        .into_iter()
        .fold(0.0_f64, |m, p| m.max(p.abs()));
    let worst_e = observed(&warm, "E")?
        .into_iter()
        .fold(0.0_f64, |m, e| m.max((e - e0).abs()));
    report
        .checks
        .push(Check::abs(NAME, "heat: max |Σp|", worst_p, 0.0, 1e-13));
    report.checks.push(Check::abs(
        NAME,
        "heat: max |ΔE| / injected",
        worst_e / (e0 - e_eq),
        0.0,
        1e-4,
    ));

    if opts.out_dir.is_some() {
        let series = |sol: &Solution<Momenta>, v: &[f64]| {
            sol.times()
                .iter()
                .copied()
                .zip(v.iter().copied())
                .collect::<Vec<_>>()
        };
        let mut fig = Figure::new("Coupled chains: positions (first and last mass of each chain)")
            .x_label("t")
            .y_label("q");
        for (name, j) in [("top 1", 0), ("top 20", 19), ("bottom 1", 20), ("bottom 20", 39)] {
            fig = fig.series(name, series(&traj, &traj.q_series(j)));
        }
        report.save(opts, &fig, "coupled_chains_positions.svg")?;
        let kin: Vec<f64> = energy.iter().zip(&pot).map(|(e, v)| e - v).collect();
        let fig = Figure::new("Coupled chains: energies")
            .x_label("t")
            .y_label("energy")
            .series("total", series(&traj, &energy))
            .series("kinetic", series(&traj, &kin))
            .series("potential", series(&traj, &pot));
        report.save(opts, &fig, "coupled_chains_energy.svg")?;
        let dps: Vec<f64> = p_total.iter().map(|p| p - 2.0).collect();
        let fig = Figure::new("Coupled chains: total discrete momentum − 20 v0")
            .x_label("t")
            .y_label("Σp − 2")
            .series("Σp − 2", series(&traj, &dps));
        report.save(opts, &fig, "coupled_chains_momentum.svg")?;
        let per_chain =
            |c: usize| -> Vec<f64> { (0..traj.len()).map(|i| chain_momentum(traj.v(i), c)).collect() };
        let fig = Figure::new("Coupled chains: momentum of each chain")
            .x_label("t")
            .y_label("p")
            .series("top", series(&traj, &per_chain(0)))
            .series("bottom", series(&traj, &per_chain(1)));
        report.save(opts, &fig, "coupled_chains_chain_momenta.svg")?;
        let fig = Figure::new("Momentum transferred to the bottom chain / 20 v0")
            .x_label("v0")
            .y_label("p_bottom / (20 v0)")
            .series("transfer", table);
        report.save(opts, &fig, "coupled_chains_transfer.svg")?;
        let fig = Figure::new("Heat: energy of each chain (kinetic + springs)")
            .x_label("t")
            .y_label("energy")
            .series("top", series(&warm, &observed(&warm, "E top")?))
            .series("bottom", series(&warm, &observed(&warm, "E bottom")?));
        report.save(opts, &fig, "coupled_chains_heat_energy.svg")?;
        // Power spectrum |Σ x(t_k) e^{−iωt_k}|² of the mean-removed first top position.
        let x1 = warm.q_series(0);
        let m = x1.iter().sum::<f64>() / x1.len() as f64;
        let spectrum: Vec<(f64, f64)> = (1..200)
            .map(|j| {
                let w = j as f64 * 0.01;
                let (re, im) = warm.times().iter().zip(&x1).fold((0.0, 0.0), |(a, b), (t, x)| {
                    let ph = w * t;
                    (a + (x - m) * ph.cos(), b - (x - m) * ph.sin())
                });
                (w, re * re + im * im)
            })
            .collect();
        let fig = Figure::new("Heat: power spectrum of the first top position")
            .x_label("ω")
            .y_label("power")
            .log_y()
            .series("|X(ω)|²", spectrum);
        report.save(opts, &fig, "coupled_chains_spectrum.svg")?;
    }
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
