//! Start here, and copy this file to start a project of your own: it uses nothing but the `noether`
//! crate (`noether = { version = "0.1", features = ["plot"] }` in your Cargo.toml), and the repository
//! builds it as a crate of its own to prove it (`tests/standalone`).
//!
//! A spring pendulum — a mass on a spring that also swings — has no closed-form motion, but two
//! closed forms hold all the same: its energy is conserved, and for small motions it swings at the
//! pendulum frequency sqrt(g / (l₀ + m g / k)) and bounces at the spring frequency sqrt(k/m).
//!
//! Run: `cargo run --release --features examples --example quickstart`.

use noether::prelude::*;
use std::f64::consts::PI;
use std::process::ExitCode;

/// A mass m on a spring of stiffness k and rest length l₀, in polar coordinates (r, θ), θ from the
/// downward vertical: L = ½ m (ṙ² + r² θ̇²) + m g r cos θ − ½ k (r − l₀)².
struct SpringPendulum {
    m: f64,
    k: f64,
    l0: f64,
    g: f64,
}

impl Lagrangian for SpringPendulum {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (r, th) = (q[0], q[1]);
        let stretch = r - self.l0;
        (v[0] * v[0] + r * r * v[1] * v[1]) * (0.5 * self.m) + r * th.cos() * (self.m * self.g)
            - stretch * stretch * (0.5 * self.k)
    }
}

/// Prints a check line in the gallery's format; `true` if it passed.
fn check(quantity: &str, computed: f64, expected: f64, tol: f64) -> bool {
    let err = ((computed - expected) / expected).abs();
    let pass = err <= tol;
    let verdict = if pass { "PASS" } else { "FAIL" };
    println!("check quickstart/{quantity}: computed={computed:.12e} expected={expected:.12e} rel_err={err:.3e} tol={tol:.1e} {verdict}");
    pass
}

fn run() -> noether::core::Result<bool> {
    let sys = SpringPendulum {
        m: 1.0,
        k: 40.0,
        l0: 1.0,
        g: 9.81,
    };
    let r_eq = sys.l0 + sys.m * sys.g / sys.k; // the spring's stretch at rest
    let el = EulerLagrange::new(&sys);

    // 1. Energy: a large swing, DOP853 at 1e-12, the energy function recorded along the run.
    let start = State::new(0.0, [r_eq + 0.2, 1.0], [0.0, 0.0]);
    let big = Driver::new(Dop853::new(&el).tolerances(1e-12, 1e-12)?, start)?
        .observe("energy", |s: &State| {
            el.energy(s.t, s.q.as_slice(), s.v.as_slice())
        })
        .run_until(20.0)?;
    let e = big.observed("energy")?;
    // h is conserved (L has no t); DOP853 at 1e-12 keeps it to ~1e-12 over this run (measured 4.3e-12).
    let mut ok = check("energy(t = 20) / energy(0)", e[e.len() - 1], e[0], 1e-11);

    // 2. Small swings: the period of θ from its upward zero crossings (events on the dense output).
    let small = State::new(0.0, [r_eq, 1e-3], [0.0, 0.0]);
    let swing = Driver::new(Dop853::new(&el).tolerances(1e-12, 1e-12)?, small)?
        .event(Event::new("θ = 0 upwards", |s: &State| s.q[1]).rising())
        .run_until(30.0)?;
    let up = swing.event_times("θ = 0 upwards")?;
    let period = (up[up.len() - 1] - up[0]) / (up.len() - 1) as f64;
    // Pendulum of length r_eq: T = 2π sqrt(r_eq/g) in the limit of small swings (the spring is not
    // excited at first order in θ). The amplitude shifts it at second order: measured 6.1e-5 at
    // θ₀ = 0.01, ≈ 0.6 θ₀² (more than a rigid pendulum's θ₀²/16, because the swing also stretches the
    // spring, near a 2:1 resonance of the two frequencies), so ~6e-7 at θ₀ = 1e-3. Tolerance 2e-6.
    ok &= check(
        "small-swing period",
        period,
        2.0 * PI * (r_eq / sys.g).sqrt(),
        2e-6,
    );

    // 3. Pure bounce: θ = 0 stays 0 and r oscillates at sqrt(k/m) exactly (a linear spring).
    let bounce = State::new(0.0, [r_eq + 0.1, 0.0], [0.0, 0.0]);
    let sol = Driver::new(Dop853::new(&el).tolerances(1e-12, 1e-12)?, bounce)?
        .event(Event::new("r = r_eq upwards", move |s: &State| s.q[0] - r_eq).rising())
        .run_until(10.0)?;
    let up = sol.event_times("r = r_eq upwards")?;
    let period = (up[up.len() - 1] - up[0]) / (up.len() - 1) as f64;
    // Exact harmonic motion: the period is 2π sqrt(m/k) to the integrator's tolerance.
    ok &= check("bounce period", period, 2.0 * PI * (sys.m / sys.k).sqrt(), 1e-10);
    Ok(ok)
}

fn main() -> ExitCode {
    match run() {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(e) => {
            eprintln!("quickstart failed: {e}");
            ExitCode::FAILURE
        }
    }
}
