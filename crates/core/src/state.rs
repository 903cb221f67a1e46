//! The phase state (t, q, v) that steppers advance.

use crate::error::check_phase_point;
use crate::Result;
use nalgebra::DVector;

/// A point of the (extended) phase space: time, coordinates and their partner.
///
/// `v` is q̇ for Lagrangian dynamics and p for Hamiltonian (and discrete, position-momentum) dynamics;
/// [`State::p`] names the second reading.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Time.
    pub t: f64,
    /// Generalized coordinates q.
    pub q: DVector<f64>,
    /// Velocities q̇ or momenta p.
    pub v: DVector<f64>,
}

impl State {
    /// A state from time, coordinates and velocities (or momenta).
    pub fn new(t: f64, q: impl Into<Vec<f64>>, v: impl Into<Vec<f64>>) -> Self {
        State {
            t,
            q: DVector::from_vec(q.into()),
            v: DVector::from_vec(v.into()),
        }
    }

    /// The momenta, for Hamiltonian states.
    pub fn p(&self) -> &DVector<f64> {
        &self.v
    }

    /// Checks dimensions against `dof` and that every number is finite.
    pub fn validate(&self, dof: usize) -> Result<()> {
        check_phase_point(dof, self.t, self.q.as_slice(), self.v.as_slice(), "v")
    }

    /// `true` when every component is finite.
    pub fn is_finite(&self) -> bool {
        self.t.is_finite() && self.q.iter().chain(self.v.iter()).all(|x| x.is_finite())
    }
}
