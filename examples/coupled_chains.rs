//! Two coupled mass-spring chains colliding (H. Jacobs, "Momentum and energy transfer between coupled
//! mass-spring chains", 2009; SEEDS part 3), measured the way the paper measures it.
//!
//! Model (`noether::discrete::chains::CoupledChains::paper`): two chains of n = 20 unit masses,
//! springs k1 = 1 of natural length l = 1/20, a Gaussian coupling k2 exp(−(q_t^i − q_b^j)²/(2σ²)) between
//! all 400 top/bottom pairs, k2 = 0.001 (repulsive), σ = 0.1. Integrator: the midpoint discrete
//! Lagrangian L_d = h L((q₀+q₁)/2, (q₁−q₀)/h) solved by Newton, as in the paper's Matlab `model11`: the
//! paper stops Newton at ‖F‖∞ ≤ 1e-8 for F = M(q_{k+1} − 2q_k + q_{k−1})/h² + ½[∇V(m_{k+½}) + ∇V(m_{k−½})];
//! noether's residual is h·F, so the same stop is `residual_tolerance(h·1e-8)`. Step h = min(2π/(10√k1), 0.1)
//! = 0.1, 999 steps (the paper's `step_max = 1000` positions). Start as in `model11(0.1)`: each chain at
//! spring equilibrium, the top chain shifted by −3, q₁ = q₀ + h v0 for the top chain and q₁ = q₀ for the
//! bottom one; the driver's state (q₀, p₀) takes p₀ = −D₁L_d(q₀, q₁), so it produces the paper's q₁.
//!
//! The paper's bookkeeping (`model11`), used for every number below: at each interior position q_k the
//! velocity is the central difference (q_{k+1} − q_{k−1})/(2h), K = ½ vᵀMv, and the potential is the
//! average ½[V((q_{k−1}+q_k)/2) + V((q_k+q_{k+1})/2)] of the two adjacent midpoints.
//!
//! The paper's figures and what this example computes or draws:
//! - Fig. 1 (schematic) and Fig. 9 (the Frenkel-Kontorova diagram): no computation.
//! - Figs. 2, 3 (positions of the masses in the collision v0 = 0.1): `coupled_chains_positions.svg`.
//! - Fig. 4 (energy; "the largest change in total energy is 3.3944e-4 of the largest change in potential
//!   energy"): `coupled_chains_energy.svg` (K, V, E and E − E₁) and the check on that ratio.
//! - Figs. 5–7 (momentum flat at machine precision, each chain in its own centre-of-mass frame, the
//!   momentum of each chain through the collision): the example `coupled_chains_momentum`.
//! - Fig. 8 (the velocity ratio after a collision against v0): the example `coupled_chains_transfer`.
//! - Figs. 10–12 (the "heat" model: positions, energy of each chain, power spectra): the example
//!   `coupled_chains_heat`.
//!
//! Run: `cargo run --release --features examples --example coupled_chains` (the pictures go to `gallery-out/`).

use noether::core::Newton;
use noether::discrete::chains::CoupledChains;
use noether::discrete::{Mass, Mechanical, MechanicalMidpoint};
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use std::process::ExitCode;

const NAME: &str = "coupled_chains";

/// The paper's Newton stop ‖F‖∞ ≤ 1e-8 on its residual F (see the module docs).
pub const PAPER_NEWTON_TOL: f64 = 1e-8;

/// The two chains with coupling `k2` as a mechanical system L = ½q̇ᵀq̇ − V(q) (unit masses).
pub fn system(k2: f64) -> Result<Mechanical<CoupledChains>, BoxError> {
    Ok(Mechanical::new(
        Mass::Diagonal(vec![1.0; 40]),
        CoupledChains::paper(k2),
    )?)
}

/// The paper's run from two positions (q₀, q₁) with coupling `k2`: `steps` midpoint steps of the paper's
/// size h and Newton stop, every position saved, the discrete Noether momentum Σp observed as "Σp".
/// The start is (q₀, p₀) with p₀ = −D₁L_d(q₀, q₁) = M(q₁ − q₀)/h + (h/2)∇V((q₀+q₁)/2).
pub fn paper_run(k2: f64, q0: &[f64], q1: &[f64], steps: usize) -> Result<Solution<Momenta>, BoxError> {
    let h = CoupledChains::paper(k2).paper_step();
    let sys = system(k2)?;
    let mid: Vec<f64> = q0.iter().zip(q1).map(|(a, b)| 0.5 * (a + b)).collect();
    let mut p0 = vec![0.0; mid.len()];
    sys.gradient(&mid, &mut p0);
    p0.iter_mut()
        .zip(q0.iter().zip(q1))
        .for_each(|(p, (a, b))| *p = (b - a) / h + 0.5 * h * *p);
    let newton = Newton::default().residual_tolerance(h * PAPER_NEWTON_TOL)?;
    let vi = MechanicalMidpoint::new(sys).newton(newton);
    Ok(
        Driver::with_step(vi, State::with_momenta(0.0, q0.to_vec(), p0), h)?
            .save(Save::Steps)?
            .observe("Σp", |s: &State<Momenta>| s.p().sum())
            .run_steps(steps)?,
    )
}

/// The paper's collision run `model11(v0)`: `steps` steps from the start described in the module docs.
pub fn collision(v0: f64, steps: usize) -> Result<Solution<Momenta>, BoxError> {
    let ch = CoupledChains::paper(0.001);
    let q0 = ch.collision_start();
    let h = ch.paper_step();
    let q1: Vec<f64> = (0..40)
        .map(|i| q0[i] + if i < 20 { h * v0 } else { 0.0 })
        .collect();
    paper_run(0.001, &q0, &q1, steps)
}

/// The paper's bookkeeping at one interior position q_k (see the module docs); index 0 is the top
/// chain, 1 the bottom one.
#[derive(Debug, Clone, Copy)]
pub struct PaperSample {
    /// Time of q_k.
    pub t: f64,
    /// Kinetic energy of each chain from central-difference velocities.
    pub kinetic: [f64; 2],
    /// Spring energy of each chain, averaged over the two adjacent midpoints.
    pub springs: [f64; 2],
    /// Total potential energy (springs and coupling), averaged over the two adjacent midpoints.
    pub potential: f64,
    /// Mean central-difference velocity of each chain (the paper's p_t, p_b).
    pub mean_velocity: [f64; 2],
}

impl PaperSample {
    /// Total energy K + V.
    pub fn energy(&self) -> f64 {
        self.kinetic[0] + self.kinetic[1] + self.potential
    }
}

/// Spring energy of chain `c` (0 top, 1 bottom) at positions `q`.
fn springs(ch: &CoupledChains, q: &[f64], c: usize) -> f64 {
    let q = &q[c * ch.n..(c + 1) * ch.n];
    q.windows(2)
        .map(|w| 0.5 * ch.k1 * (w[1] - w[0] - ch.l).powi(2))
        .sum()
}

/// The paper's bookkeeping at every interior position of a run saved at every step.
pub fn paper_samples(sol: &Solution<Momenta>, k2: f64) -> Result<Vec<PaperSample>, BoxError> {
    let (ch, sys) = (CoupledChains::paper(k2), system(k2)?);
    let (h, n) = (ch.paper_step(), ch.n);
    let mids: Vec<(f64, [f64; 2])> = (1..sol.len())
        .map(|k| {
            let m: Vec<f64> = sol
                .q(k - 1)
                .iter()
                .zip(sol.q(k))
                .map(|(a, b)| 0.5 * (a + b))
                .collect();
            (
                sys.potential_energy(&m),
                [springs(&ch, &m, 0), springs(&ch, &m, 1)],
            )
        })
        .collect();
    Ok((1..sol.len().saturating_sub(1))
        .map(|k| {
            let v: Vec<f64> = sol
                .q(k + 1)
                .iter()
                .zip(sol.q(k - 1))
                .map(|(a, b)| (a - b) / (2.0 * h))
                .collect();
            let chain = |c: usize| &v[c * n..(c + 1) * n];
            let kin = |c: usize| chain(c).iter().map(|x| 0.5 * x * x).sum();
            let mean = |c: usize| chain(c).iter().sum::<f64>() / n as f64;
            let (a, b) = (mids[k - 1], mids[k]);
            PaperSample {
                t: sol.times()[k],
                kinetic: [kin(0), kin(1)],
                springs: [0.5 * (a.1[0] + b.1[0]), 0.5 * (a.1[1] + b.1[1])],
                potential: 0.5 * (a.0 + b.0),
                mean_velocity: [mean(0), mean(1)],
            }
        })
        .collect())
}

/// Largest |x_k − x_0| of a series.
fn max_change(x: &[f64]) -> f64 {
    x.iter().map(|v| (v - x[0]).abs()).fold(0.0, f64::max)
}

/// Runs the paper's main collision (v0 = 0.1) and checks its energy (Fig. 4).
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let v0 = 0.1;
    let traj = collision(v0, 999)?;
    let samples = paper_samples(&traj, 0.001)?;
    let energy: Vec<f64> = samples.iter().map(PaperSample::energy).collect();
    let pot: Vec<f64> = samples.iter().map(|s| s.potential).collect();

    // Fig. 4: max_k |E_k − E_1| / max_k |V_k − V_1| (the same with max − min). The paper: 3.3944e-4.
    // Measured 3.394650e-4 (7.4e-5 relative); with Newton to rounding 3.394557e-4 (4.6e-5). The
    // ratio depends on where Newton stops at the 1e-8 level: stopping at h·1e-8 instead of rounding
    // moves it by 2.7e-5 relative, at h·1e-7 by 3.2e-4. The paper's Matlab loop takes one update past
    // its stop with a Jacobian whose coupling block differs from ∇²V, so its final residual lies
    // somewhere below 1e-8: its value is known to that band only. Tolerance 1e-4 relative (3.4e-8).
    let ratio = max_change(&energy) / max_change(&pot);
    report.checks.push(Check::rel(
        NAME,
        "Fig. 4: max |ΔE| / max |ΔV| (paper 3.3944e-4)",
        ratio,
        3.3944e-4,
        1e-4,
    ));

    if opts.out_dir.is_some() {
        let t: Vec<f64> = samples.iter().map(|s| s.t).collect();
        let series = |y: &mut dyn Iterator<Item = f64>| t.iter().copied().zip(y).collect::<Vec<_>>();
        let masses = [("top 1", 0), ("top 20", 19), ("bottom 1", 20), ("bottom 20", 39)];
        let mut fig = Figure::new("Figs. 2-3: positions (first and last mass of each chain), v0 = 0.1")
            .x_label("t")
            .y_label("q");
        for (name, j) in masses {
            fig = fig.series(name, series(&mut (1..=t.len()).map(|k| traj.q(k)[j])));
        }
        report.save(opts, &fig, "coupled_chains_positions.svg")?;
        let fig = Figure::new("Fig. 4: energies (central-difference K, averaged midpoint V)")
            .x_label("t")
            .y_label("energy")
            .series("E", series(&mut energy.iter().copied()))
            .series(
                "K",
                series(&mut samples.iter().map(|s| s.kinetic[0] + s.kinetic[1])),
            )
            .series("V", series(&mut pot.iter().copied()));
        report.save(opts, &fig, "coupled_chains_energy.svg")?;
        let fig = Figure::new("Fig. 4: total energy change E − E₁")
            .x_label("t")
            .y_label("E − E₁")
            .series("E − E₁", series(&mut energy.iter().map(|e| e - energy[0])));
        report.save(opts, &fig, "coupled_chains_energy_change.svg")?;
    }
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
