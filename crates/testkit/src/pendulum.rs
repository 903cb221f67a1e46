//! The pendulum of the ensembles: L = ½ θ̇² + cos θ (g/l = 1), and its quarter period from rest at an
//! amplitude a, T/4 = K(sin(a/2)), measured by a terminal event.
//!
//! Used by noether-ensemble's tests (`tests/ensemble.rs`) and its `mpi_scan` example.

use noether_core::integrators::Dop853;
use noether_core::{Driver, EulerLagrange, Event, Lagrangian, Save, Scalar, State};

/// Pendulum, L = ½ θ̇² + cos θ (g/l = 1).
pub struct Pendulum;

impl Lagrangian for Pendulum {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * v[0] * 0.5 + q[0].cos()
    }
}

/// A quarter period of the pendulum released from rest at amplitude `a`: the time at which θ first
/// crosses 0 upwards from −a (a terminal event of the driver), by DOP853 at atol = rtol = `tol`, run
/// at most until `t_max`.
pub fn quarter_period(a: f64, tol: f64, t_max: f64) -> Result<f64, noether_core::Error> {
    let el = EulerLagrange::new(Pendulum);
    let sol = Driver::new(
        Dop853::new(&el).tolerances(tol, tol)?,
        State::new(0.0, [-a], [0.0]),
    )?
    .save(Save::End)?
    .event(Event::new("θ = 0", |s: &State| s.q[0]).rising().terminal())
    .run_until(t_max)?;
    Ok(sol.last().t)
}
