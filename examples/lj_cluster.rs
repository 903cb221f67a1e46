//! A Lennard-Jones cluster of 100 atoms, U = De [(re/r)¹² − 2 (re/r)⁶] between all pairs, integrated
//! for 10⁵ velocity-Verlet steps: the energy error stays bounded (no drift), as a symplectic method's
//! must, and momentum is conserved to rounding.
//!
//! Set-up (reduced units De = re = m = 1): the 100 fcc sites (nearest-neighbour distance re) closest
//! to the centre, random velocities of temperature ~0.05 De with the centre-of-mass velocity removed.
//! Time step h = 0.002: the stiffest motion, a bond vibration with ω = sqrt(U''(re)/μ) = 12,
//! has ω h = 0.024.
//!
//! Checks: max |E − E0| / |E0| over the run, bounded by the modified-energy estimate of Verlet
//! (~ (ω h)² × kinetic energy / |E0| ≈ 1e-5; measured 1.2e-6 over 10⁵ steps and 1.9e-6 over the
//! test's 2·10⁴, sampled at other steps: 5e-6); the drift, mean of E over the last tenth minus the
//! first tenth, is far smaller (measured 1.1e-7 and 2.6e-7, the shorter run averaging over shorter
//! tenths: 6e-7 of |E0|); momentum changes only by rounding (measured 1.7e-15 and 5.6e-16 of
//! Σ m|v|: 5e-15).
//! The energy is an observer of the driver, recorded at 1000 evenly spaced steps.
//!
//! Run: `cargo run --release --features examples --example lj_cluster` (10⁵ steps, ~4 s on an idle core; the test suite
//! calls [`run_steps`] with 2·10⁴).

use noether::particles::laws::LennardJones;
use noether::particles::{AllPairs, Method, Particle, System, Vec3};
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use rand::{rngs::StdRng, Rng, SeedableRng};
use std::process::ExitCode;

const NAME: &str = "lj_cluster";

/// The `n` fcc sites (nearest-neighbour distance `d`) closest to the origin.
pub fn fcc_ball(n: usize, d: f64) -> Vec<Vec3> {
    let a = d * std::f64::consts::SQRT_2; // cube edge
    let mut pts = Vec::new();
    let basis = [[0.0, 0.0, 0.0], [0.5, 0.5, 0.0], [0.5, 0.0, 0.5], [0.0, 0.5, 0.5]];
    for i in -4..=4 {
        for j in -4..=4 {
            for k in -4..=4 {
                for b in basis {
                    // Offset so the ball is centred on an octahedral hole, not an atom.
                    pts.push([
                        (i as f64 + b[0] - 0.25) * a,
                        (j as f64 + b[1] - 0.25) * a,
                        (k as f64 + b[2] - 0.25) * a,
                    ]);
                }
            }
        }
    }
    let r2 = |p: &Vec3| p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    pts.sort_by(|p, q| r2(p).total_cmp(&r2(q)));
    pts.truncate(n);
    pts
}

/// Runs the cluster with `steps` steps; returns the checks.
pub fn run_steps(steps: usize) -> Result<Report, BoxError> {
    let n = 100;
    let sys = System::new(vec![Particle::new(1.0); n])?.with(AllPairs::new(LennardJones::new(1.0, 1.0)))?;
    let x = fcc_ball(n, 1.0);
    let mut rng = StdRng::seed_from_u64(7);
    let temperature: f64 = 0.05;
    let mut v: Vec<Vec3> = (0..n)
        .map(|_| {
            std::array::from_fn(|_| temperature.sqrt() * (rng.random::<f64>() * 2.0 - 1.0) * 3f64.sqrt())
        })
        .collect();
    let mean: Vec3 = std::array::from_fn(|k| v.iter().map(|w| w[k]).sum::<f64>() / n as f64);
    v.iter_mut().for_each(|w| (0..3).for_each(|k| w[k] -= mean[k]));
    let s0 = sys.state(0.0, &x, &v)?;
    let e0 = sys.total_energy(&s0)?;
    let p0 = sys.momentum(s0.v.as_slice())?;
    let h = 0.002;
    let samples = 1000;
    let every = steps / samples;
    let sol = sys
        .evolver(Method::VelocityVerlet, s0, h)?
        .save(Save::Every(every))?
        .observe("energy", |s: &State| {
            sys.total_energy(s).map_err(noether::core::Error::from)
        })
        .run_steps(samples * every)?;
    // The energy after each `every` steps (the first saved row is the start).
    let observed = sol.observed("energy")?;
    let energies = observed
        .get(1..)
        .filter(|es| es.len() == samples)
        .ok_or("expected 1000 samples")?;
    let s = sol.last();
    let worst = energies.iter().fold(0.0_f64, |m, e| m.max((e - e0).abs())) / e0.abs();
    let tenth = samples / 10;
    let mean_of = |es: &[f64]| es.iter().sum::<f64>() / es.len() as f64;
    let drift = (mean_of(&energies[samples - tenth..]) - mean_of(&energies[..tenth])) / e0.abs();
    let p = sys.momentum(s.v.as_slice())?;
    let dp = (0..3).fold(0.0_f64, |m, k| m.max((p[k] - p0[k]).abs()));
    let scale: f64 = s.v.iter().map(|w| w.abs()).sum();
    let label = format!("{steps} steps");
    Ok(Report {
        checks: vec![
            Check::abs(NAME, format!("max |E - E0| / |E0| ({label})"), worst, 0.0, 5e-6),
            Check::abs(
                NAME,
                format!("energy drift last-first tenth / |E0| ({label})"),
                drift,
                0.0,
                6e-7,
            ),
            Check::abs(NAME, format!("|dP| / sum m|v| ({label})"), dp / scale, 0.0, 5e-15),
        ],
        ..Default::default()
    })
}

/// Runs the full 10⁵-step cluster.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    run_steps(100_000)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
