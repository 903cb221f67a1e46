//! The flip map of the double pendulum: released from rest at every (θ₁, θ₂) of a grid, how long until
//! one of the two rods first flips over the top (either angle reaches ±π)? The answer is a famous fractal
//! picture; here it is an ensemble (noether-ensemble) over a [`Grid`], one driver run per member with a
//! terminal event, drawn as a heat map.
//!
//! The pendulum is made of two equal uniform rods (mass m, length l, pivoted end to end), angles from the
//! downward vertical:
//!
//! ```text
//! L = (m l²/6) (4 θ̇₁² + θ̇₂² + 3 θ̇₁ θ̇₂ cos(θ₁ − θ₂)) + (m g l/2) (3 cos θ₁ + cos θ₂).
//! ```
//!
//! **Where no rod can flip.** Released from rest the energy is E = −(m g l/2)(3 cos θ₁ + cos θ₂), and it is
//! conserved. With the upper rod over the top (θ₁ = π) the potential is (m g l/2)(3 − cos θ₂) ≥ m g l;
//! with the lower one (θ₂ = π) it is −(m g l/2)(3 cos θ₁ − 1) ≥ −m g l. Kinetic energy is never negative,
//! so a flip needs E ≥ −m g l, that is 3 cos θ₁ + cos θ₂ ≤ 2: inside the region 3 cos θ₁ + cos θ₂ > 2
//! no member may flip, however long it runs. The check: none does within the run. (For point masses on
//! massless rods the same argument gives 2 cos θ₁ + cos θ₂ > 1.)
//!
//! **Flip.** Starting with |θᵢ| < π, cos(θᵢ/2) > 0; a flip is the first zero of cos(θ₁/2) or cos(θ₂/2), a
//! terminal event of the driver located on DOP853's continuous extension. Each member also returns its
//! energy error |E(end) − E(0)| (units of m g l), the largest over the grid is checked.
//!
//! **Mirror symmetry.** L is unchanged by (θ₁, θ₂) → (−θ₁, −θ₂), so members at mirrored grid points flip
//! at the same time. The grid's centres are mirrored only to rounding (~10⁻¹⁶), which the chaos
//! amplifies over time, so the check takes the mirror pairs that flip early (t < 10 √(l/g)).
//!
//! Run: `cargo run --release --features examples --example flip_map` (a 90 × 90 grid to t = 30 √(l/g); the picture goes to
//! `gallery-out/`). The test runs a 40 × 40 grid to t = 20.

use noether::ensemble::{Axis, Ensemble, Grid, Members};
use noether::plot::Heatmap;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use std::f64::consts::PI;
use std::process::ExitCode;

const NAME: &str = "flip_map";

/// Two equal uniform rods, m = l = g = 1.
#[derive(Debug, Clone, Copy)]
pub struct RodPendulum;

impl Lagrangian for RodPendulum {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] * 4.0 + v[1] * v[1] + v[0] * v[1] * (q[0] - q[1]).cos() * 3.0) * (1.0 / 6.0)
            + (q[0].cos() * 3.0 + q[1].cos()) * 0.5
    }
}

/// Energy of the rods, E = T + V (units of m g l).
fn energy(q: &[f64], v: &[f64]) -> f64 {
    (4.0 * v[0] * v[0] + v[1] * v[1] + 3.0 * v[0] * v[1] * (q[0] - q[1]).cos()) / 6.0
        - 0.5 * (3.0 * q[0].cos() + q[1].cos())
}

/// DOP853 tolerances (atol = rtol).
const TOL: f64 = 1e-10;

/// Whether the energy forbids a flip from rest at (θ₁, θ₂): 3 cos θ₁ + cos θ₂ > 2.
pub fn no_flip_region(t1: f64, t2: f64) -> bool {
    3.0 * t1.cos() + t2.cos() > 2.0
}

/// Released from rest at (θ₁, θ₂): the time of the first flip (None if none before `t_end`), and the
/// energy error |E(end) − E(0)|.
pub fn first_flip(t1: f64, t2: f64, t_end: f64) -> Result<(Option<f64>, f64), noether::core::Error> {
    let el = EulerLagrange::new(RodPendulum);
    let sol = Driver::new(
        Dop853::new(&el).tolerances(TOL, TOL)?,
        State::new(0.0, [t1, t2], [0.0, 0.0]),
    )?
    .save(Save::End)?
    .event(
        Event::new("upper rod over the top", |s: &State| (0.5 * s.q[0]).cos())
            .falling()
            .terminal(),
    )
    .event(
        Event::new("lower rod over the top", |s: &State| (0.5 * s.q[1]).cos())
            .falling()
            .terminal(),
    )
    .max_steps(10_000_000)
    .run_until(t_end)?;
    let end = sol.last();
    let de = (energy(end.q.as_slice(), end.v.as_slice()) - energy(&[t1, t2], &[0.0, 0.0])).abs();
    let flip = matches!(sol.stop(), Stop::Event(_)).then_some(end.t);
    Ok((flip, de))
}

/// Runs the example on an `n` × `n` grid of cell centres over (−π, π)², each member to `t_end`.
pub fn run_grid(n: usize, t_end: f64, opts: &Options) -> Result<Report, BoxError> {
    let grid = Grid::new(vec![Axis::centres(-PI, PI, n)?, Axis::centres(-PI, PI, n)?])?;
    let ensemble = Ensemble::new(grid.clone(), |_, p: &Vec<f64>| first_flip(p[0], p[1], t_end));
    let out = ensemble.run().values()?;

    let mut inside = 0usize;
    let mut inside_flipped = 0usize;
    let mut flipped = 0usize;
    let mut worst_energy = 0.0_f64;
    let mut worst_mirror = 0.0_f64;
    let mut pairs = 0usize;
    for (i, &(flip, de)) in out.iter().enumerate() {
        let p = grid.member(i)?;
        worst_energy = worst_energy.max(de);
        flipped += usize::from(flip.is_some());
        if no_flip_region(p[0], p[1]) {
            inside += 1;
            inside_flipped += usize::from(flip.is_some());
        }
        let m = grid.multi_index(i)?;
        let mirror = grid
            .index_of(&[n - 1 - m[0], n - 1 - m[1]])
            .ok_or("mirror outside the grid")?;
        if let (Some(a), Some(b)) = (flip, out[mirror].0) {
            if mirror > i && a < 10.0 && b < 10.0 {
                worst_mirror = worst_mirror.max((a - b).abs());
                pairs += 1;
            }
        }
    }
    if inside == 0 {
        return Err("no grid point in the energy-forbidden region: the grid is too coarse".into());
    }
    let checks = vec![
        // Energy conservation forbids any flip there (see the module docs): an exact count.
        Check::abs(
            NAME,
            format!(
                "flips among the {inside} members with 3cosθ₁ + cosθ₂ > 2 ({flipped} of {} flip in all)",
                out.len()
            ),
            inside_flipped as f64,
            0.0,
            0.0,
        ),
        // DOP853 at 1e-10 over up to t_end: the energy error of a member grows with its steps, largest
        // for the members that never flip and whirl until t_end (measured worst 1.7e-9 over the 40 × 40
        // grid to t = 20); tolerance 1e-8.
        Check::abs(
            NAME,
            "worst |E(end) − E(0)| over the grid (m g l)",
            worst_energy,
            0.0,
            2e-8,
        ),
        // Mirror pairs flipping before t = 10: the same time up to the rounding of the grid's centres
        // amplified by the chaos (measured worst 1.1e-12 over the 412 pairs of the 40 × 40 test grid);
        // tolerance 1e-10, room for the example's finer grid, whose pairs lie closer to the chaotic edges.
        Check::abs(
            NAME,
            format!("mirror pairs' flip times differ ({pairs} pairs flipping before t = 10)"),
            worst_mirror,
            0.0,
            1e-10,
        ),
    ];
    let mut report = Report {
        checks,
        ..Default::default()
    };
    if opts.out_dir.is_some() {
        let centres = grid.axes()[0].as_slice().to_vec();
        let values: Vec<f64> = out.iter().map(|(f, _)| f.unwrap_or(f64::NAN)).collect();
        let map = Heatmap::new(
            format!("Double pendulum (rods): time to first flip, {n} × {n} released from rest"),
            centres.clone(),
            centres,
            values,
        )?
        .x_label("θ₁ (rad)")
        .y_label("θ₂ (rad)")
        .bar_label("time to first flip (√(l/g)); white: none")
        .log_scale();
        if let Some(dir) = &opts.out_dir {
            std::fs::create_dir_all(dir)?;
            report.figures.push(map.save(dir.join("flip_map.svg"))?);
        }
    }
    Ok(report)
}

/// Runs the example (90 × 90 to t = 30).
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    run_grid(90, 30.0, opts)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
