//! Momentum and energy transfer between two coupled mass-spring chains (SEEDS part 3), integrated with
//! the midpoint variational integrator L_d = h L((q₀+q₁)/2, (q₁−q₀)/h) solved by Newton (tolerance
//! 1e-8 on the residual, as in the paper).
//!
//! Model (`noether_discrete::chains::CoupledChains`): two chains of 20 unit masses, springs k1 = 1 of
//! natural length l = 1/20, Gaussian coupling k2 exp(−(q_t^i − q_b^j)²/(2σ²)) between all 400 top/bottom
//! pairs, σ = 0.1, step h = min(2π/(10√k1), 0.1) = 0.1.
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

use super::plot::Figure;
use super::{Check, Options, Report};
use noether_core::{Newton, State, Stepper};
use noether_discrete::chains::CoupledChains;
use noether_discrete::{DiscreteFlow, Mass, Mechanical, MechanicalMidpoint, Verlet};
use rand::{rngs::StdRng, Rng, SeedableRng};

const NAME: &str = "coupled_chains";
type BoxError = Box<dyn std::error::Error + Send + Sync>;

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

/// One collision run with initial top velocity `v0` for `steps` steps; returns the trajectory samples
/// (t, q, p) every `every` steps.
fn collision(v0: f64, steps: usize, every: usize) -> Result<Vec<State>, BoxError> {
    let ch = CoupledChains::paper(0.001);
    let h = ch.paper_step();
    let p: Vec<f64> = (0..40).map(|k| if k < 20 { v0 } else { 0.0 }).collect();
    let mut s = State::new(0.0, ch.collision_start(), p);
    let mut vi = MechanicalMidpoint::new(system(0.001)?).with_newton(Newton::default().tol_residual(1e-8));
    let mut out = vec![s.clone()];
    for k in 1..=steps {
        vi.step(&mut s, h)?;
        if k % every == 0 {
            out.push(s.clone());
        }
    }
    Ok(out)
}

/// Runs the three experiments.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let ch = CoupledChains::paper(0.001);
    let sys = system(0.001)?;

    // 1. The main collision run, v0 = 0.1, t ∈ [0, 100].
    let traj = collision(0.1, 1000, 1)?;
    let p_total: Vec<f64> = traj.iter().map(|s| s.v.iter().sum()).collect();
    let dp = p_total.iter().map(|p| (p - 2.0).abs()).fold(0.0, f64::max);
    report
        .checks
        .push(Check::abs(NAME, "max |Σp − 20 v0| (v0=0.1)", dp, 0.0, 1e-13));
    let energy: Vec<f64> = traj
        .iter()
        .map(|s| sys.energy(s.q.as_slice(), s.v.as_slice()))
        .collect();
    let pot: Vec<f64> = traj
        .iter()
        .map(|s| sys.potential_energy(s.q.as_slice()))
        .collect();
    let de = energy.iter().map(|e| (e - energy[0]).abs()).fold(0.0, f64::max);
    let dv = pot.iter().map(|v| (v - pot[0]).abs()).fold(0.0, f64::max);
    report.checks.push(Check::abs(
        NAME,
        "max |ΔE| / max |ΔV| (v0=0.1)",
        de / dv,
        0.0,
        1e-3,
    ));
    let last = traj.last().expect("non-empty");
    let (pt, pb): (f64, f64) = (last.v.rows(0, 20).sum(), last.v.rows(20, 20).sum());
    println!("coupled_chains: after the collision p_top = {pt:.6}, p_bottom = {pb:.6} (t = 100)");

    // 2. Momentum transferred vs v0: run until the chains have separated (t = 5/v0 + 40).
    let mut table = Vec::new();
    for v0 in [0.05, 0.1, 0.2, 0.4] {
        let steps = ((5.0 / v0 + 40.0) / ch.paper_step()).round() as usize;
        let tr = collision(v0, steps, steps)?;
        let end = tr.last().expect("non-empty");
        let (pt, pb): (f64, f64) = (end.v.rows(0, 20).sum(), end.v.rows(20, 20).sum());
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
    let mut settle = Verlet::new(damped);
    let mut q = ch.collision_start();
    q.iter_mut().take(20).for_each(|x| *x += 3.0 + 0.025); // top chain between the bottom masses
    let mut p = vec![0.0; 40];
    for _ in 0..3000 {
        settle.flow(0.0, 0.1, &mut q, &mut p)?;
    }
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
    let e_eq = heat.energy(&q, &vec![0.0; 40]);
    p.iter_mut()
        .zip(kick.iter().chain([0.0; 20].iter()))
        .for_each(|(pi, ki)| *pi = *ki);
    let e0 = heat.energy(&q, &p);
    let mut vi = MechanicalMidpoint::new(heat).with_newton(Newton::default().tol_residual(1e-10));
    let chains = CoupledChains::paper(k2);
    let (mut e_top, mut e_bot, mut x1, mut worst_e, mut worst_p) = (vec![], vec![], vec![], 0.0_f64, 0.0_f64);
    let steps = 4096;
    for k in 0..steps {
        vi.flow(k as f64 * 0.1, 0.1, &mut q, &mut p)?;
        let t = (k + 1) as f64 * 0.1;
        e_top.push((t, chain_energy(&chains, &q, &p, 0)));
        e_bot.push((t, chain_energy(&chains, &q, &p, 1)));
        x1.push(q[0]);
        worst_e = worst_e.max((vi.system().energy(&q, &p) - e0).abs());
        worst_p = worst_p.max(p.iter().sum::<f64>().abs());
    }
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
        let series = |idx: usize| traj.iter().map(|s| (s.t, s.q[idx])).collect::<Vec<_>>();
        Figure::new("Coupled chains: positions (first and last mass of each chain)")
            .x_label("t")
            .y_label("q")
            .series("top 1", series(0))
            .series("top 20", series(19))
            .series("bottom 1", series(20))
            .series("bottom 20", series(39))
            .save_in(opts, "coupled_chains_positions.svg", &mut report)?;
        let ts = |v: &[f64]| traj.iter().zip(v).map(|(s, y)| (s.t, *y)).collect::<Vec<_>>();
        let kin: Vec<f64> = energy.iter().zip(&pot).map(|(e, v)| e - v).collect();
        Figure::new("Coupled chains: energies")
            .x_label("t")
            .y_label("energy")
            .series("total", ts(&energy))
            .series("kinetic", ts(&kin))
            .series("potential", ts(&pot))
            .save_in(opts, "coupled_chains_energy.svg", &mut report)?;
        let dps: Vec<f64> = p_total.iter().map(|p| p - 2.0).collect();
        Figure::new("Coupled chains: total discrete momentum − 20 v0")
            .x_label("t")
            .y_label("Σp − 2")
            .series("Σp − 2", ts(&dps))
            .save_in(opts, "coupled_chains_momentum.svg", &mut report)?;
        let pt: Vec<f64> = traj.iter().map(|s| s.v.rows(0, 20).sum()).collect();
        let pb: Vec<f64> = traj.iter().map(|s| s.v.rows(20, 20).sum()).collect();
        Figure::new("Coupled chains: momentum of each chain")
            .x_label("t")
            .y_label("p")
            .series("top", ts(&pt))
            .series("bottom", ts(&pb))
            .save_in(opts, "coupled_chains_chain_momenta.svg", &mut report)?;
        Figure::new("Momentum transferred to the bottom chain / 20 v0")
            .x_label("v0")
            .y_label("p_bottom / (20 v0)")
            .series("transfer", table.clone())
            .save_in(opts, "coupled_chains_transfer.svg", &mut report)?;
        Figure::new("Heat: energy of each chain (kinetic + springs)")
            .x_label("t")
            .y_label("energy")
            .series("top", e_top.clone())
            .series("bottom", e_bot.clone())
            .save_in(opts, "coupled_chains_heat_energy.svg", &mut report)?;
        // Power spectrum |Σ x(t_k) e^{−iωt_k}|² of the mean-removed first top position.
        let m = x1.iter().sum::<f64>() / x1.len() as f64;
        let spectrum: Vec<(f64, f64)> = (1..200)
            .map(|j| {
                let w = j as f64 * 0.01;
                let (re, im) = x1.iter().enumerate().fold((0.0, 0.0), |(a, b), (k, x)| {
                    let ph = w * k as f64 * 0.1;
                    (a + (x - m) * ph.cos(), b - (x - m) * ph.sin())
                });
                (w, re * re + im * im)
            })
            .collect();
        Figure::new("Heat: power spectrum of the first top position")
            .x_label("ω")
            .y_label("power")
            .log_y()
            .series("|X(ω)|²", spectrum)
            .save_in(opts, "coupled_chains_spectrum.svg", &mut report)?;
    }
    Ok(report)
}
