//! Work against precision of the Runge-Kutta-Nyström pairs next to DOP853 on the same `Natural`
//! system: Kepler e = 0.6 over 100 periods from pericentre, error |y(200π) − y₀| (max norm over q
//! and q̇; the exact orbit returns to its start), wall time of the run (minimum over repetitions),
//! steps, rejected steps and evaluations of the accelerations, at atol = rtol = tol, dense output off
//! (`Save::End`).
//!
//! `cargo bench -p noether-core --bench nystrom`

use noether_core::prelude::*;
use std::time::{Duration, Instant};

use noether_testkit::kepler::{start, Kepler, E};

/// (error, time, stats) of one method, the fastest of several repetitions.
fn measure<S: Stepper>(make: impl Fn() -> S) -> Result<(f64, Duration, noether_core::Stats)> {
    let t_end = 200.0 * std::f64::consts::PI;
    let (q, v) = start();
    let y0 = State::<S::Partner>::from_parts(0.0, q, v);
    let mut best = Duration::MAX;
    let mut out = None;
    let clock = Instant::now();
    let mut reps = 0;
    while reps < 3 || (clock.elapsed() < Duration::from_millis(300) && reps < 200) {
        let t = Instant::now();
        let sol = Driver::new(make(), y0.clone())?
            .save(Save::End)?
            .run_until(t_end)?;
        best = best.min(t.elapsed());
        let end = sol.last();
        let err = end
            .q
            .iter()
            .zip(y0.q.iter())
            .chain(end.v.iter().zip(y0.v.iter()))
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        out = Some((err, *sol.stats()));
        reps += 1;
    }
    let (err, stats) = out.ok_or(Error::Unsupported("no run"))?;
    Ok((err, best, stats))
}

fn main() -> Result<()> {
    println!(
        "Kepler e = {E}, 100 periods, dense output off; error |y(200π) − y₀|, time (min of repetitions); \
         DOP853 on (q, q̇) by `Natural` and on (q, p) by `SeparableHamiltonian`"
    );
    println!("| tol | method | error | time | steps | rejected | evaluations |");
    println!("|---|---|---|---|---|---|---|");
    let sys = || Natural::unit(Kepler);
    for tol in [1e-6, 1e-8, 1e-10, 1e-12, 1e-13] {
        let rows = [
            (
                "DOP853",
                measure(|| Dop853::new(sys()).tolerances(tol, tol).unwrap())?,
            ),
            (
                "DOP853 on (q, p)",
                measure(|| {
                    Dop853::new(SeparableHamiltonian(Kepler))
                        .tolerances(tol, tol)
                        .unwrap()
                })?,
            ),
            (
                "DPRKN6",
                measure(|| Dprkn6::new(sys()).unwrap().tolerances(tol, tol).unwrap())?,
            ),
            (
                "DPRKN8",
                measure(|| Dprkn8::new(sys()).unwrap().tolerances(tol, tol).unwrap())?,
            ),
            (
                "DPRKN12",
                measure(|| Dprkn12::new(sys()).unwrap().tolerances(tol, tol).unwrap())?,
            ),
        ];
        for (name, (err, time, st)) in rows {
            println!(
                "| {tol:.0e} | {name} | {err:.2e} | {:.3} ms | {} | {} | {} |",
                time.as_secs_f64() * 1e3,
                st.steps,
                st.rejected,
                st.evaluations
            );
        }
    }
    Ok(())
}
