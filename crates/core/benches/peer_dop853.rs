//! noether's DOP853 against the Rust peer ode_solvers' DOP853 on Kepler e = 0.6 over 100 orbits, at
//! equal tolerances (atol = rtol, Hairer's controller on both sides, no output but the end): both
//! take the same steps to the same errors, so the ratio of times is the cost of a step. The peer's
//! right-hand side is hand-written; noether's is `Natural::unit` of V = −1/|q| by dual numbers.
//!
//! A bench binary of its own, holding nothing else: in `work_precision` (the gallery) the peer's
//! `integrate` is compiled for three systems and LLVM then inlines less into each (its Kepler run
//! took 0.62 ms there at tol 1e-6 against 0.42 ms here), which would flatter noether.
//!
//! `cargo bench -p noether-core --bench peer_dop853`

use nalgebra::SVector;
use noether_core::prelude::*;
use std::hint::black_box;
use std::time::Instant;

use noether_testkit::kepler::{start, Kepler, T_END};
use noether_testkit::peer::{ode_solvers_end, KeplerRhs};

/// (error |q(T) − q₀|, steps accepted + rejected) of noether's DOP853.
fn noether(tol: f64) -> Result<(f64, usize)> {
    let (q0, v0) = start();
    let dp = Dop853::new(Natural::unit(Kepler))
        .tolerances(tol, tol)?
        .dense_interpolant(false);
    let sol = Driver::new(dp, State::new(0.0, q0, v0))?
        .save(Save::End)?
        .run_until(T_END)?;
    let q = sol.last().q.clone();
    let s = sol.stats();
    Ok(((q[0] - q0[0]).hypot(q[1] - q0[1]), s.steps + s.rejected))
}

/// The same for ode_solvers.
fn peer(tol: f64) -> (f64, usize) {
    let (q0, v0) = start();
    let y0 = SVector::<f64, 4>::new(q0[0], q0[1], v0[0], v0[1]);
    let (y, trials) = ode_solvers_end(KeplerRhs, y0, T_END, tol);
    ((y[0] - q0[0]).hypot(y[1] - q0[1]), trials)
}

fn main() -> Result<()> {
    println!("Kepler e = 0.6, 100 orbits, DOP853 at atol = rtol = tol; min of 25 interleaved runs");
    println!("| tol | ode_solvers | noether | ratio | trials (peer / noether) | error (peer / noether) |");
    println!("|---|---|---|---|---|---|");
    for tol in [1e-6, 1e-8, 1e-10, 1e-12] {
        let (mut best_p, mut best_n) = (f64::INFINITY, f64::INFINITY);
        let (mut p, mut n) = ((0.0, 0), (0.0, 0));
        for _ in 0..25 {
            let t = Instant::now();
            p = black_box(peer(tol));
            best_p = best_p.min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            n = black_box(noether(tol)?);
            best_n = best_n.min(t.elapsed().as_secs_f64());
        }
        println!(
            "| {tol:.0e} | {:.3} ms | {:.3} ms | {:.2}× | {} / {} | {:.2e} / {:.2e} |",
            best_p * 1e3,
            best_n * 1e3,
            best_n / best_p,
            p.1,
            n.1,
            p.0,
            n.0
        );
    }
    Ok(())
}
