//! The Rust peer ode_solvers' DOP853 as the benchmarks run it, and Kepler's problem written for it
//! by hand.
//!
//! Used by noether-core's `peer_dop853` benchmark and the gallery's `work_precision` benchmark
//! (feature `peer`: the only module that needs ode_solvers).

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

/// Kepler's problem ([`crate::kepler`]) as a hand-written right-hand side on y = (q, q̇) for the
/// Rust peer ode_solvers: q̈ = −q/|q|³.
pub struct KeplerRhs;
impl ode_solvers::System<f64, SVector<f64, 4>> for KeplerRhs {
    #[inline]
    fn system(&self, _t: f64, y: &SVector<f64, 4>, dy: &mut SVector<f64, 4>) {
        let r2 = y[0] * y[0] + y[1] * y[1];
        let r3 = r2 * r2.sqrt();
        dy[0] = y[2];
        dy[1] = y[3];
        dy[2] = -y[0] / r3;
        dy[3] = -y[1] / r3;
    }
}
