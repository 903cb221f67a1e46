//! The Rust peer ode_solvers' DOP853 as the benchmarks run it, included by path into core's
//! `peer_dop853` and the gallery's `work_precision`.

use nalgebra::SVector;

/// ode_solvers' DOP853 from y0 at t = 0 to `t_end` with atol = rtol = `tol` and Hairer's default
/// controller (the one noether's DOP853 uses: safety 0.9, step ratios 0.333..6, β = 0), no output
/// but the end: the state at `t_end` and the trial steps (accepted and rejected).
pub fn ode_solvers_end<F, const N: usize>(
    rhs: F,
    y0: SVector<f64, N>,
    t_end: f64,
    tol: f64,
) -> (SVector<f64, N>, usize)
where
    F: ode_solvers::System<f64, SVector<f64, N>>,
{
    let mut s = ode_solvers::Dop853::from_param(
        rhs,
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
    let stats = s.integrate().expect("ode_solvers run");
    let trials = (stats.accepted_steps + stats.rejected_steps) as usize;
    (*s.y_out().last().expect("a state"), trials)
}
