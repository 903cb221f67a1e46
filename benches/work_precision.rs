//! Work against precision, noether side by side with the Rust peer `ode_solvers` and with hand-written
//! loops (issue 16, item 3). Every time is the minimum over interleaved repetitions (the machine is
//! shared: interference only ever adds time).
//!
//! `cargo bench --bench work_precision` prints the tables and writes `target/work_precision.svg`
//! (error against time, log-log). Results and the command in docs/benchmarks.md.
//!
//! Problems:
//! - Kepler, e = 0.6, μ = 1, 100 orbits (t = 200π), error |q(200π) − q₀| (the orbit is periodic);
//! - Hénon-Heiles, q₀ = (0.1, 0), p₀ = (0, 0.5), Kahan-Li 8 at h = 0.01 for 10⁶ steps, relative energy
//!   error at the end, against the same composition written by hand;
//! - the outer solar system (Hairer-Lubich-Wanner's data, noether-particles gravity), 200 000 days,
//!   error max_i |q_i − q_i,ref| against a reference run (IAS15 at ε = 1e-11);
//! - a planar chain of 40 pendulum links (`EulerLagrange` on the user's L, a mass matrix solve in every
//!   right-hand side), 2 s from rest at moderate angles, error max_k |θ_k − θ_k,ref| against
//!   ode_solvers' DOP853 at tol 1e-14 with the hand-derived equations of motion.
//!
//! The Python peers (REBOUND's IAS15 and WHFast, scipy) on the same problems: `benches/peers.py`.
//!
//! `long` (not run by default: about a minute) is the reliability table of long runs (issue 29): the
//! relative energy error of IAS15 on Kepler e = 0.9 over 10⁴ orbits, of the Lie-group variational
//! integrator on a free asymmetric body over 10⁶ steps and of DPRKN12 on the outer solar system over
//! 10⁵ years, sampled along the run, and how it grows (t¹: a drift, t^½: a random walk of rounding
//! errors, t⁰: bounded).

#![allow(missing_docs)]

use nalgebra::SVector;
use noether::core::integrators::Dprkn8;
use noether::prelude::*;
use std::hint::black_box;
use std::time::Instant;

use noether_testkit::henon_heiles::{composition_by_hand, HenonHeiles};
use noether_testkit::kepler::{start as kepler_start, Kepler};
use noether_testkit::peer::{ode_solvers_end, KeplerRhs};
use noether_testkit::solar::{outer_solar_system as solar_system, BODIES, G as G_SOLAR};

const ORBITS: f64 = 100.0;

/// Minimum over `reps` interleaved runs of each closure, in ms, with the last result of each.
fn race<const K: usize>(reps: usize, mut runs: [&mut dyn FnMut() -> f64; K]) -> [(f64, f64); K] {
    let mut best = [(f64::INFINITY, 0.0); K];
    for _ in 0..reps {
        for (k, run) in runs.iter_mut().enumerate() {
            let t0 = Instant::now();
            let err = black_box(run());
            let ms = t0.elapsed().as_secs_f64() * 1e3;
            best[k] = (best[k].0.min(ms), err);
        }
    }
    best
}

fn kepler_error(q: &[f64]) -> f64 {
    let (q0, _) = kepler_start();
    ((q[0] - q0[0]).powi(2) + (q[1] - q0[1]).powi(2)).sqrt()
}

/// Runs an adaptive stepper on Kepler to t = 200π (no output but the end) and returns the error.
fn kepler_run<S: Stepper<Partner = Velocities>>(stepper: S) -> f64 {
    let (q, v) = kepler_start();
    let t_end = 2.0 * std::f64::consts::PI * ORBITS;
    let sol = Driver::new(stepper, State::new(0.0, q, v))
        .and_then(|d| d.save(Save::End))
        .and_then(|d| d.max_steps(100_000_000).run_until(t_end))
        .expect("run");
    kepler_error(sol.last().q.as_slice())
}

fn noether_dop853(tol: f64) -> f64 {
    let dp = Dop853::new(Natural::unit(Kepler))
        .tolerances(tol, tol)
        .expect("tolerances");
    kepler_run(dp.dense_interpolant(false))
}

fn noether_dprkn8(tol: f64) -> f64 {
    let m = Dprkn8::new(Natural::unit(Kepler)).and_then(|m| m.tolerances(tol, tol));
    kepler_run(m.expect("DPRKN8").dense_interpolant(false))
}

fn noether_dprkn12(tol: f64) -> f64 {
    let m = Dprkn12::new(Natural::unit(Kepler)).and_then(|m| m.tolerances(tol, tol));
    kepler_run(m.expect("DPRKN12").dense_interpolant(false))
}

fn noether_ias15(eps: f64) -> f64 {
    let m = Ias15::new(Natural::unit(Kepler)).and_then(|m| m.epsilon(eps));
    kepler_run(m.expect("IAS15").dense_interpolant(false))
}

/// Kahan-Li 8 with a fixed step of T/`per_orbit`.
fn noether_kl8(per_orbit: f64) -> f64 {
    let (q, v) = kepler_start();
    let h = 2.0 * std::f64::consts::PI / per_orbit;
    let steps = (ORBITS * per_orbit).round() as usize;
    let kl8 = Composition::kahan_li8(Natural::unit(Kepler));
    let sol = Driver::with_step(kl8, State::new(0.0, q, v), h)
        .and_then(|d| d.save(Save::End))
        .and_then(|mut d| d.run_steps(steps))
        .expect("run");
    kepler_error(sol.last().q.as_slice())
}

fn ode_solvers_dop853(tol: f64) -> f64 {
    let (q, v) = kepler_start();
    let t_end = 2.0 * std::f64::consts::PI * ORBITS;
    let y0 = SVector::<f64, 4>::new(q[0], q[1], v[0], v[1]);
    let (y, _) = ode_solvers_end(KeplerRhs, y0, t_end, tol);
    kepler_error(&[y[0], y[1]])
}

/// One method's sweep: its name, the parameter's name and values, and the run.
struct Sweep {
    name: &'static str,
    param: &'static str,
    values: Vec<f64>,
    run: fn(f64) -> f64,
}

/// The smallest time among the runs whose error is at most `target` (no interpolation: the first
/// run of the sweep that reaches the target counts).
fn time_to(points: &[(f64, f64)], target: f64) -> Option<f64> {
    points
        .iter()
        .filter(|(_, e)| *e <= target)
        .map(|(ms, _)| *ms)
        .reduce(f64::min)
}

type Curve = (&'static str, Vec<(f64, f64)>);

fn kepler_table() -> Vec<Curve> {
    let tols = vec![1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15];
    let sweeps = [
        Sweep {
            name: "ode_solvers DOP853 (hand-written rhs)",
            param: "tol",
            values: tols.clone(),
            run: ode_solvers_dop853,
        },
        Sweep {
            name: "noether DOP853",
            param: "tol",
            values: tols.clone(),
            run: noether_dop853,
        },
        Sweep {
            name: "noether DPRKN8",
            param: "tol",
            values: tols.clone(),
            run: noether_dprkn8,
        },
        Sweep {
            name: "noether DPRKN12",
            param: "tol",
            values: tols,
            run: noether_dprkn12,
        },
        Sweep {
            name: "noether IAS15",
            param: "ε",
            values: vec![1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-9],
            run: noether_ias15,
        },
        Sweep {
            name: "noether Kahan-Li 8 (fixed h = T/n)",
            param: "n",
            values: vec![100.0, 200.0, 400.0, 800.0, 1600.0],
            run: noether_kl8,
        },
    ];
    println!("\nKepler e = 0.6, 100 orbits: error |q(200π) − q₀| and time (min of 7 interleaved runs)");
    let mut curves = Vec::new();
    for sw in &sweeps {
        println!("\n{}\n| {} | error | time |\n|---|---|---|", sw.name, sw.param);
        let mut pts = Vec::new();
        for &x in &sw.values {
            // Interleaved with the peer at a middle setting, so that both see the same load.
            let [(ms, err), _] = race(7, [&mut || (sw.run)(x), &mut || ode_solvers_dop853(1e-10)]);
            println!("| {x:.0e} | {err:.2e} | {ms:.3} ms |");
            pts.push((ms, err));
        }
        curves.push((sw.name, pts));
    }
    print_time_to(&curves);
    curves
}

/// The time each method takes to reach 1e-6 and 1e-10, and its ratio to the first curve (the peer).
fn print_time_to(curves: &[Curve]) {
    println!("\nTime to reach an error (the fastest run at or below it), and the ratio to ode_solvers:");
    println!("| method | to 1e-6 | to 1e-10 |\n|---|---|---|");
    let peer = curves[0].1.clone();
    for (name, pts) in curves {
        let cell = |target| match (time_to(pts, target), time_to(&peer, target)) {
            (Some(t), Some(p)) => format!("{t:.3} ms ({:.2}×)", t / p),
            (Some(t), None) => format!("{t:.3} ms (the peer does not reach it)"),
            _ => "not reached".to_string(),
        };
        println!("| {name} | {} | {} |", cell(1e-6), cell(1e-10));
    }
}

/// Kahan-Li 8 coefficients, from noether's own composition (the same numbers for both loops).
fn hh_noether(steps: usize) -> f64 {
    let nat = Natural::unit(HenonHeiles);
    let e0 = nat.energy(&[0.1, 0.0], &[0.0, 0.5]).expect("energy");
    let kl8 = Composition::kahan_li8(Natural::unit(HenonHeiles));
    let mut d = Driver::with_step(kl8, State::new(0.0, [0.1, 0.0], [0.0, 0.5]), 0.01)
        .and_then(|d| d.save(Save::End))
        .expect("driver");
    let sol = d.run_steps(steps).expect("run");
    let s = sol.last();
    ((nat.energy(s.q.as_slice(), s.v.as_slice()).expect("energy") - e0) / e0).abs()
}

fn hh_hand(steps: usize, gammas: &[f64]) -> f64 {
    let nat = Natural::unit(HenonHeiles);
    let energy = |q: &[f64; 2], v: &[f64; 2]| nat.energy(q, v).expect("energy");
    let (q0, v0) = ([0.1, 0.0], [0.0, 0.5]);
    let (q, v) = composition_by_hand(gammas, steps, 0.01, q0, v0);
    ((energy(&q, &v) - energy(&q0, &v0)) / energy(&q0, &v0)).abs()
}

fn henon_heiles_table() {
    let gammas = Composition::kahan_li8(Natural::unit(HenonHeiles))
        .weights()
        .as_slice()
        .to_vec();
    let steps = 1_000_000;
    let [(ms_h, err_h), (ms_n, err_n)] =
        race(5, [&mut || hh_hand(steps, &gammas), &mut || hh_noether(steps)]);
    println!("\nHénon-Heiles, Kahan-Li 8, h = 0.01, 10⁶ steps: relative energy error and time");
    println!("| hand-written loop | noether on Natural | ratio |");
    println!("|---|---|---|");
    println!(
        "| {ms_h:.1} ms, err {err_h:.2e} | {ms_n:.1} ms, err {err_n:.2e} | {:.2} |",
        ms_n / ms_h
    );
}

// ---- The outer solar system ----

/// The time span in days (Hairer-Lubich-Wanner, GNI I.2.4); the model is testkit's `solar`.
const SOLAR_T: f64 = 200_000.0;

/// The end positions of a run of `stepper` to 200 000 days.
fn solar_run<S: Stepper<Partner = Velocities>>(stepper: S, s0: State) -> Vec<f64> {
    let sol = Driver::new(stepper, s0)
        .and_then(|d| d.save(Save::End))
        .and_then(|d| d.max_steps(100_000_000).run_until(SOLAR_T))
        .expect("run");
    sol.last().q.as_slice().to_vec()
}

fn solar_error(q: &[f64], reference: &[f64]) -> f64 {
    q.chunks(3)
        .zip(reference.chunks(3))
        .map(|(a, b)| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt())
        .fold(0.0, f64::max)
}

/// The hand-written right-hand side for ode_solvers: y = (q₀..q₅, v₀..v₅), each a 3-vector.
struct SolarRhs {
    gm: [f64; 6],
}
impl ode_solvers::System<f64, SVector<f64, 36>> for SolarRhs {
    #[inline]
    fn system(&self, _t: f64, y: &SVector<f64, 36>, dy: &mut SVector<f64, 36>) {
        for k in 0..18 {
            dy[k] = y[18 + k];
            dy[18 + k] = 0.0;
        }
        for i in 0..6 {
            for j in i + 1..6 {
                let d = [
                    y[3 * j] - y[3 * i],
                    y[3 * j + 1] - y[3 * i + 1],
                    y[3 * j + 2] - y[3 * i + 2],
                ];
                let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                let inv3 = 1.0 / (r2 * r2.sqrt());
                for c in 0..3 {
                    dy[18 + 3 * i + c] += self.gm[j] * inv3 * d[c];
                    dy[18 + 3 * j + c] -= self.gm[i] * inv3 * d[c];
                }
            }
        }
    }
}

fn solar_ode_solvers(tol: f64, reference: &[f64]) -> f64 {
    let mut y0 = SVector::<f64, 36>::zeros();
    for (i, (_, q, v)) in BODIES.iter().enumerate() {
        for c in 0..3 {
            y0[3 * i + c] = q[c];
            y0[18 + 3 * i + c] = v[c];
        }
    }
    let gm = BODIES.map(|b| G_SOLAR * b.0);
    let (y, _) = ode_solvers_end(SolarRhs { gm }, y0, SOLAR_T, tol);
    solar_error(&y.as_slice()[..18], reference)
}

fn solar_noether(method: &str, x: f64, reference: &[f64]) -> f64 {
    let (sys, s0) = solar_system();
    let q = match method {
        "DOP853" => solar_run(
            Dop853::new(sys)
                .tolerances(x, x)
                .expect("tol")
                .dense_interpolant(false),
            s0,
        ),
        "DPRKN8" => solar_run(
            Dprkn8::new(sys)
                .and_then(|m| m.tolerances(x, x))
                .expect("DPRKN8")
                .dense_interpolant(false),
            s0,
        ),
        "DPRKN12" => solar_run(
            Dprkn12::new(sys)
                .and_then(|m| m.tolerances(x, x))
                .expect("DPRKN12")
                .dense_interpolant(false),
            s0,
        ),
        "IAS15" => solar_run(
            Ias15::new(sys)
                .and_then(|m| m.epsilon(x))
                .expect("IAS15")
                .dense_interpolant(false),
            s0,
        ),
        _ => {
            // Kahan-Li 8 with x steps over the span.
            let steps = x as usize;
            let sol = Driver::with_step(Composition::kahan_li8(sys), s0, SOLAR_T / x)
                .and_then(|d| d.save(Save::End))
                .and_then(|mut d| d.run_steps(steps))
                .expect("run");
            sol.last().q.as_slice().to_vec()
        }
    };
    solar_error(&q, reference)
}

fn solar_table() -> Vec<Curve> {
    let reference = {
        let (sys, s0) = solar_system();
        solar_run(Ias15::new(sys).and_then(|m| m.epsilon(1e-11)).expect("IAS15"), s0)
    };
    println!(
        "\nOuter solar system, 200 000 days: error max_i |q_i − q_i,ref| in AU (min of 5 interleaved runs)"
    );
    println!("reference (IAS15, ε = 1e-11) end positions:");
    for b in reference.chunks(3) {
        println!("  {:+.15e} {:+.15e} {:+.15e}", b[0], b[1], b[2]);
    }
    let check = solar_noether("DPRKN12", 1e-16, &reference);
    println!("DPRKN12 at tol 1e-16 differs from the reference by {check:.2e} AU");
    let tols = vec![1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14];
    let sweeps: [(&'static str, &str, Vec<f64>); 6] = [
        ("ode_solvers DOP853 (hand-written rhs)", "tol", tols.clone()),
        ("noether DOP853", "tol", tols.clone()),
        ("noether DPRKN8", "tol", tols.clone()),
        ("noether DPRKN12", "tol", tols),
        ("noether IAS15", "ε", vec![1e-4, 1e-5, 1e-6, 1e-7, 1e-9]),
        (
            "noether Kahan-Li 8",
            "steps",
            vec![1000.0, 2000.0, 4000.0, 8000.0, 16000.0],
        ),
    ];
    let mut curves = Vec::new();
    for (name, param, values) in sweeps {
        println!("\n{name}\n| {param} | error | time |\n|---|---|---|");
        let method = name
            .trim_start_matches("noether ")
            .split(' ')
            .next()
            .unwrap_or("");
        let mut pts = Vec::new();
        for &x in &values {
            let r = &reference;
            let mut run = || {
                if name.starts_with("ode_solvers") {
                    solar_ode_solvers(x, r)
                } else {
                    solar_noether(method, x, r)
                }
            };
            let [(ms, err), _] = race(5, [&mut run, &mut || solar_ode_solvers(1e-10, r)]);
            println!("| {x:.0e} | {err:.2e} | {ms:.3} ms |");
            pts.push((ms, err));
        }
        curves.push((name, pts));
    }
    print_time_to(&curves);
    curves
}

// ---- A chain of 40 pendulum links ----

use noether_testkit::systems::Chain;

const LINKS: usize = 40;
const CHAIN_T: f64 = 2.0;

fn chain_start() -> [f64; LINKS] {
    std::array::from_fn(|k| 0.3 * (k as f64).sin() + 0.1)
}

/// The hand-derived equations of motion (Cholesky of the hand-built mass matrix) for ode_solvers.
struct ChainRhs(Chain<LINKS>);
impl ode_solvers::System<f64, SVector<f64, { 2 * LINKS }>> for ChainRhs {
    #[inline]
    fn system(&self, _t: f64, y: &SVector<f64, { 2 * LINKS }>, dy: &mut SVector<f64, { 2 * LINKS }>) {
        let q: [f64; LINKS] = std::array::from_fn(|k| y[k]);
        let v: [f64; LINKS] = std::array::from_fn(|k| y[LINKS + k]);
        let a = self.0.hand_accelerations(&q, &v);
        for k in 0..LINKS {
            dy[k] = v[k];
            dy[LINKS + k] = a[k];
        }
    }
}

fn chain_ode_solvers(tol: f64) -> Vec<f64> {
    let mut y0 = SVector::<f64, { 2 * LINKS }>::zeros();
    for (k, q) in chain_start().iter().enumerate() {
        y0[k] = *q;
    }
    let (y, _) = ode_solvers_end(ChainRhs(Chain::default()), y0, CHAIN_T, tol);
    y.as_slice()[..LINKS].to_vec()
}

fn chain_noether(tol: f64) -> Vec<f64> {
    let el = EulerLagrange::new(Chain::<LINKS>::default());
    let dp = Dop853::new(el)
        .tolerances(tol, tol)
        .expect("tol")
        .dense_interpolant(false);
    let sol = Driver::new(dp, State::new(0.0, chain_start(), [0.0; LINKS]))
        .and_then(|d| d.save(Save::End))
        .and_then(|mut d| d.run_until(CHAIN_T))
        .expect("run");
    sol.last().q.as_slice().to_vec()
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

fn chain_table() -> Vec<Curve> {
    let reference = chain_ode_solvers(1e-14);
    println!("\nChain of {LINKS} pendulum links, {CHAIN_T} s: error max_k |θ_k − θ_k,ref| (min of 3 interleaved runs)");
    println!(
        "reference: ode_solvers DOP853 at tol 1e-14; noether's DOP853 at tol 1e-14 lies {:.2e} from it",
        max_diff(&chain_noether(1e-14), &reference)
    );
    let tols = [1e-6, 1e-8, 1e-10, 1e-12];
    type Run = fn(f64) -> Vec<f64>;
    let runs: [(&'static str, Run); 2] = [
        (
            "ode_solvers DOP853 (hand-written equations of motion)",
            chain_ode_solvers,
        ),
        ("noether DOP853 (EulerLagrange on L)", chain_noether),
    ];
    let mut curves = Vec::new();
    for (name, run) in runs {
        println!("\n{name}\n| tol | error | time |\n|---|---|---|");
        let mut pts = Vec::new();
        for &tol in &tols {
            let r = &reference;
            let [(ms, err), _] = race(
                3,
                [&mut || max_diff(&run(tol), r), &mut || {
                    max_diff(&chain_ode_solvers(1e-8), r)
                }],
            );
            println!("| {tol:.0e} | {err:.2e} | {ms:.3} ms |");
            pts.push((ms, err));
        }
        curves.push((name, pts));
    }
    print_time_to(&curves);
    curves
}

fn main() {
    // `cargo bench` passes `--bench`; a problem's name (kepler, hh) runs only that one.
    let which = std::env::args().nth(1).filter(|a| !a.starts_with('-'));
    let run = |name: &str| which.as_deref().is_none_or(|w| w == name);
    if run("kepler") {
        let curves = kepler_table();
        picture(
            "Kepler e = 0.6, 100 orbits",
            "error |q(200π) − q₀|",
            "work_precision",
            curves,
        );
    }
    if run("hh") {
        henon_heiles_table();
    }
    if run("chain") {
        let curves = chain_table();
        picture(
            "chain of 40 links, 2 s",
            "error max |θ − θ_ref|",
            "work_precision_chain",
            curves,
        );
    }
    if which.as_deref() == Some("long") {
        long_runs();
    }
    if run("solar") {
        let curves = solar_table();
        picture(
            "outer solar system, 200 000 days",
            "error max |q − q_ref| [AU]",
            "work_precision_solar",
            curves,
        );
    }
}

// ---- Long runs: the reliability table (issue 29) ----

/// One row of the table from the largest relative energy error |E − E₀|/|E₀| up to each of ten
/// equally spaced checkpoints (errors[k] up to t = (k + 1) T/10) and the wall time of the run.
fn long_row(name: &str, span: &str, errors: &[f64], seconds: f64) {
    let (tenth, half, end) = (errors[0], errors[4], errors[9]);
    // Growth exponent between T/10 and T of the running maximum: 1 for a linear drift, ½ for a
    // random walk, 0 for a bounded error.
    let exponent = (end / tenth).log10();
    println!("| {name} | {span} | {tenth:.1e} | {half:.1e} | {end:.1e} | {exponent:.2} | {seconds:.1} s |");
}

/// The running maximum of |E − E₀|/|E₀| at ten equally spaced checkpoints, from `per_checkpoint`
/// samples between consecutive ones: `energy_at(j)` advances the run to sample j (1, 2, …) and
/// returns the energy there.
fn energy_errors(e0: f64, per_checkpoint: usize, mut energy_at: impl FnMut(usize) -> f64) -> Vec<f64> {
    let mut worst: f64 = 0.0;
    (1..=10)
        .map(|k| {
            for j in (k - 1) * per_checkpoint + 1..=k * per_checkpoint {
                worst = worst.max(((energy_at(j) - e0) / e0).abs());
            }
            worst
        })
        .collect()
}

fn long_runs() {
    println!("| run | span | max rel. energy error to T/10 | to T/2 | to T | growth exponent | time |");
    println!("|---|---|---|---|---|---|---|");
    // IAS15, Kepler e = 0.9 from pericentre, 10⁴ orbits (μ = a = 1, period 2π), ε = 1e-9 (REBOUND's
    // default); the energy is sampled every 10 orbits.
    {
        let e: f64 = 0.9;
        let sys = Natural::unit(Kepler);
        let (q0, v0): ([f64; 2], [f64; 2]) = ([1.0 - e, 0.0], [0.0, ((1.0 + e) / (1.0 - e)).sqrt()]);
        let e0 = sys.energy(&q0, &v0).expect("energy");
        let ias = Ias15::new(Natural::unit(Kepler))
            .expect("IAS15")
            .dense_interpolant(false);
        let mut d = Driver::new(ias, State::new(0.0, q0, v0))
            .and_then(|d| d.save(Save::End))
            .expect("driver")
            .max_steps(1_000_000_000);
        let clock = Instant::now();
        let period = 2.0 * std::f64::consts::PI;
        let errors = energy_errors(e0, 100, |j| {
            d.run_until(10.0 * j as f64 * period).expect("IAS15 run");
            let s = d.state();
            sys.energy(s.q.as_slice(), s.v.as_slice()).expect("energy")
        });
        long_row(
            "IAS15, Kepler e = 0.9",
            "10⁴ orbits",
            &errors,
            clock.elapsed().as_secs_f64(),
        );
    }
    // The Lie-group variational integrator on the free asymmetric body of the gallery's
    // free_rigid_body (I = 1, 2, 3, Ω₀ = (1, 0, 0.8)), h = 10⁻², 10⁶ steps; energy every 10³ steps.
    {
        use nalgebra::{UnitQuaternion, Vector3};
        use noether::rigid::{Lgvi, RigidBody};
        let body = RigidBody::free(1.0, 2.0, 3.0).expect("body");
        let q0 = UnitQuaternion::from_euler_angles(0.4, -0.3, 1.2);
        let mut s = body.state(0.0, &q0, &Vector3::new(1.0, 0.0, 0.8));
        let e0 = body.energy(&s).expect("energy");
        let mut lgvi = Lgvi::new(body).expect("LGVI");
        let clock = Instant::now();
        let errors = energy_errors(e0, 100, |_| {
            for _ in 0..1000 {
                lgvi.step(&mut s, 1e-2).expect("LGVI step");
            }
            body.energy(&s).expect("energy")
        });
        long_row(
            "LGVI, free body I = (1, 2, 3)",
            "10⁶ steps",
            &errors,
            clock.elapsed().as_secs_f64(),
        );
    }
    // DPRKN12 at tol 1e-12 on the outer solar system, 10⁵ years; energy every 100 years.
    {
        let (sys, s0) = solar_system();
        let e0 = sys.total_energy(&s0).expect("energy");
        let m = Dprkn12::new(sys)
            .and_then(|m| m.tolerances(1e-12, 1e-12))
            .expect("DPRKN12")
            .dense_interpolant(false);
        let (sys, _) = solar_system();
        let mut d = Driver::new(m, s0)
            .and_then(|d| d.save(Save::End))
            .expect("driver")
            .max_steps(1_000_000_000);
        let clock = Instant::now();
        let year = 365.25;
        let errors = energy_errors(e0, 100, |j| {
            d.run_until(100.0 * j as f64 * year).expect("DPRKN12 run");
            sys.total_energy(d.state()).expect("energy")
        });
        long_row(
            "DPRKN12 tol 1e-12, outer solar system",
            "10⁵ years",
            &errors,
            clock.elapsed().as_secs_f64(),
        );
    }
}

/// Error against log₁₀ time, one series per method, to `target/<file>.svg`.
fn picture(title: &str, y_label: &str, file: &str, curves: Vec<Curve>) {
    let mut fig = noether::plot::Figure::new(format!("{title}: work against precision"))
        .x_label("log₁₀ time [ms]")
        .y_label(y_label)
        .log_y();
    for (name, pts) in curves {
        fig = fig.series(name, pts.iter().map(|(ms, e)| (ms.log10(), *e)).collect());
    }
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("target/{file}.svg"));
    match fig.save(&path) {
        Ok(p) => println!("\nwrote {}", p.display()),
        Err(e) => println!("\nno picture: {e}"),
    }
}
