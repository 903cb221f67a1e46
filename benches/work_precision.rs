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
//!   error at the end, against the same composition written by hand.

#![allow(missing_docs)]

use nalgebra::SVector;
use noether::prelude::*;
use std::hint::black_box;
use std::time::Instant;

/// Kepler, μ = 1: V = −1/|q|.
struct Kepler;
impl Potential for Kepler {
    fn dof(&self) -> usize {
        2
    }
    #[inline]
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        -(q[0] * q[0] + q[1] * q[1]).sqrt().recip()
    }
}

/// Hénon-Heiles: V = ½(x² + y²) + x²y − y³/3.
struct HenonHeiles;
impl Potential for HenonHeiles {
    fn dof(&self) -> usize {
        2
    }
    #[inline]
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        let (x, y) = (q[0], q[1]);
        (x * x + y * y) * 0.5 + x * x * y - y * y * y / 3.0
    }
}

const E: f64 = 0.6;
const ORBITS: f64 = 100.0;

/// Kepler's start at pericentre with a = 1: q = (1 − e, 0), q̇ = (0, sqrt((1 + e)/(1 − e))).
fn kepler_start() -> ([f64; 2], [f64; 2]) {
    ([1.0 - E, 0.0], [0.0, ((1.0 + E) / (1.0 - E)).sqrt()])
}

/// The hand-written right-hand side for ode_solvers.
struct KeplerRhs;
impl ode_solvers::System<f64, SVector<f64, 4>> for KeplerRhs {
    fn system(&self, _t: f64, y: &SVector<f64, 4>, dy: &mut SVector<f64, 4>) {
        let r2 = y[0] * y[0] + y[1] * y[1];
        let r3 = r2 * r2.sqrt();
        dy[0] = y[2];
        dy[1] = y[3];
        dy[2] = -y[0] / r3;
        dy[3] = -y[1] / r3;
    }
}

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

fn noether_dop853(tol: f64) -> f64 {
    let (q, v) = kepler_start();
    let t_end = 2.0 * std::f64::consts::PI * ORBITS;
    let dp = Dop853::new(Natural::unit(Kepler))
        .tolerances(tol, tol)
        .expect("tolerances")
        .with_dense_output(false);
    let sol = Driver::new(dp, State::new(0.0, q, v))
        .and_then(|d| d.save(Save::End))
        .and_then(|d| d.max_steps(10_000_000).run_until(t_end))
        .expect("run");
    kepler_error(sol.last().q.as_slice())
}

fn ode_solvers_dop853(tol: f64) -> f64 {
    let (q, v) = kepler_start();
    let t_end = 2.0 * std::f64::consts::PI * ORBITS;
    let y0 = SVector::<f64, 4>::new(q[0], q[1], v[0], v[1]);
    let mut s = ode_solvers::Dop853::from_param(
        KeplerRhs,
        0.0,
        t_end,
        t_end,
        y0,
        tol,
        tol,
        0.9,
        0.0,
        0.333,
        6.0,
        t_end,
        0.0,
        u32::MAX,
        1000,
        ode_solvers::dop_shared::OutputType::Sparse,
    );
    s.integrate().expect("ode_solvers run");
    let y = s.y_out().last().expect("a state");
    kepler_error(&[y[0], y[1]])
}

fn kepler_table(rows: &mut Vec<(String, f64, f64)>) {
    println!("\nKepler e = 0.6, 100 orbits: error |q(200π) − q₀| and time (min of interleaved runs)");
    println!("| tol | ode_solvers DOP853 (hand rhs) | noether DOP853 on Natural | ratio |");
    println!("|---|---|---|---|");
    for tol in [1e-6, 1e-8, 1e-10, 1e-12] {
        let reps = 15;
        let [(ms_o, err_o), (ms_n, err_n)] = race(
            reps,
            [&mut || ode_solvers_dop853(tol), &mut || noether_dop853(tol)],
        );
        println!(
            "| {tol:.0e} | {ms_o:.3} ms, err {err_o:.2e} | {ms_n:.3} ms, err {err_n:.2e} | {:.2} |",
            ms_n / ms_o
        );
        rows.push(("ode_solvers DOP853".into(), ms_o, err_o));
        rows.push(("noether DOP853".into(), ms_n, err_n));
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
    let accel = |q: &[f64; 2]| [-q[0] - 2.0 * q[0] * q[1], -q[1] - q[0] * q[0] + q[1] * q[1]];
    let energy = |q: &[f64; 2], v: &[f64; 2]| {
        0.5 * (v[0] * v[0] + v[1] * v[1]) + 0.5 * (q[0] * q[0] + q[1] * q[1]) + q[0] * q[0] * q[1]
            - q[1] * q[1] * q[1] / 3.0
    };
    // Kick-drift-kick steps of sizes γᵢh with adjacent half kicks merged and the last force reused:
    // as noether's `Composition`, s force evaluations per step.
    let mut kicks = vec![0.0; gammas.len() + 1];
    for (i, g) in gammas.iter().enumerate() {
        kicks[i] += 0.5 * g;
        kicks[i + 1] += 0.5 * g;
    }
    let (mut q, mut v) = ([0.1, 0.0], [0.0, 0.5]);
    let e0 = energy(&q, &v);
    let h = 0.01;
    let mut a = accel(&q);
    for _ in 0..steps {
        for (i, &g) in gammas.iter().enumerate() {
            let c = kicks[i] * h;
            v = [v[0] + c * a[0], v[1] + c * a[1]];
            q = [q[0] + g * h * v[0], q[1] + g * h * v[1]];
            a = accel(&q);
        }
        let c = kicks[gammas.len()] * h;
        v = [v[0] + c * a[0], v[1] + c * a[1]];
    }
    ((energy(&q, &v) - e0) / e0).abs()
}

fn henon_heiles_table() {
    let gammas = Composition::kahan_li8(Natural::unit(HenonHeiles))
        .coefficients()
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

fn main() {
    // `cargo bench` passes `--bench`; a problem's name (kepler, hh) runs only that one.
    let which = std::env::args().nth(1).filter(|a| !a.starts_with('-'));
    let run = |name: &str| which.as_deref().is_none_or(|w| w == name);
    let mut rows = Vec::new();
    if run("kepler") {
        kepler_table(&mut rows);
    }
    if run("hh") {
        henon_heiles_table();
    }
}
