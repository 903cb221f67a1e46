//! The phase state (t, q, ·) that steppers advance, and what its second half means.
//!
//! A state carries the coordinates q and their partner: the velocities q̇ for Lagrangian dynamics
//! ([`EulerLagrange`](crate::EulerLagrange), [`Natural`](crate::Natural), particles, constraints) or the
//! momenta p for Hamiltonian dynamics ([`HamiltonEquations`](crate::HamiltonEquations), separable
//! Hamiltonians, the variational integrators in position-momentum form). The type says which:
//! `State<Velocities>` (the default, `State`) or `State<Momenta>`. A stepper declares the kind it
//! advances ([`Stepper::Partner`](crate::Stepper::Partner)), so handing a momentum state to a
//! velocity stepper does not compile; the Legendre maps convert at a visible boundary
//! ([`EulerLagrange::to_momenta`](crate::EulerLagrange::to_momenta),
//! [`EulerLagrange::to_velocities`](crate::EulerLagrange::to_velocities)).
//!
//! ```
//! use noether_core::State;
//!
//! let s: State = State::new(0.0, [1.0, 0.0], [0.0, 2.0]); // q̇, by default
//! assert_eq!(s.v[1], 2.0);
//! let p = State::with_momenta(0.0, [1.0, 0.0], [0.0, 4.0]); // a State<Momenta>
//! assert_eq!(p.p()[1], 4.0);
//! ```

use crate::error::check_phase_point;
use crate::Result;
use nalgebra::DVector;
use std::fmt::Debug;
use std::marker::PhantomData;

/// What the second half of a [`State`] holds: [`Velocities`] q̇ or [`Momenta`] p.
pub trait Partner: Copy + Debug + PartialEq + Send + Sync + 'static {
    /// Symbol of a component in names and file headers: `"v"` (q̇) or `"p"`.
    const SYMBOL: &'static str;
    /// What the components are, for messages: `"velocities q̇"` or `"momenta p"`.
    const NAME: &'static str;
}

/// The second half of a state is the velocities q̇ (Lagrangian dynamics).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Velocities;

/// The second half of a state is the momenta p (Hamiltonian dynamics, position-momentum form).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Momenta;

impl Partner for Velocities {
    const SYMBOL: &'static str = "v";
    const NAME: &'static str = "velocities q̇";
}

impl Partner for Momenta {
    const SYMBOL: &'static str = "p";
    const NAME: &'static str = "momenta p";
}

/// A point of the (extended) phase space: time, coordinates q and their partner `v`, which is q̇ in a
/// `State<Velocities>` (the default) and p in a `State<Momenta>` ([`State::p`] reads it by that name).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(bound = ""))]
pub struct State<K = Velocities> {
    /// Time.
    pub t: f64,
    /// Generalized coordinates q.
    pub q: DVector<f64>,
    /// The partner of q: velocities q̇ or momenta p, as `K` says.
    pub v: DVector<f64>,
    #[cfg_attr(feature = "serde", serde(skip))]
    partner: PhantomData<K>,
}

impl State<Velocities> {
    /// A state from time, coordinates and velocities q̇. A state of momenta is
    /// [`State::with_momenta`]: the two constructors have different names so that the kind is never
    /// inferred from where a state goes (a (q, q̇) handed to a Hamiltonian stepper does not compile
    /// rather than silently being read as (q, p)), and `State::new` needs no annotation anywhere.
    pub fn new(t: f64, q: impl Into<Vec<f64>>, v: impl Into<Vec<f64>>) -> Self {
        Self::from_parts(t, q, v)
    }
}

impl State<Momenta> {
    /// A state from time, coordinates and momenta p: the state of a Hamiltonian stepper
    /// ([`HamiltonEquations`](crate::HamiltonEquations), separable Hamiltonians, …).
    pub fn with_momenta(t: f64, q: impl Into<Vec<f64>>, p: impl Into<Vec<f64>>) -> Self {
        Self::from_parts(t, q, p)
    }
}

impl<K: Partner> State<K> {
    /// A state of the kind `K` from time, coordinates and partner, for code generic in the kind
    /// (`State::<S::Partner>::from_parts(t, q, v)` for a stepper `S`); elsewhere [`State::new`] or
    /// [`State::with_momenta`] say which kind they make.
    pub fn from_parts(t: f64, q: impl Into<Vec<f64>>, v: impl Into<Vec<f64>>) -> Self {
        Self::from_vectors(t, DVector::from_vec(q.into()), DVector::from_vec(v.into()))
    }

    /// A state from time and the two vectors (either kind, as the type says).
    pub fn from_vectors(t: f64, q: DVector<f64>, v: DVector<f64>) -> Self {
        State {
            t,
            q,
            v,
            partner: PhantomData,
        }
    }

    /// A state of `dof` zeros at time `t`.
    pub fn zeros(t: f64, dof: usize) -> Self {
        Self::from_vectors(t, DVector::zeros(dof), DVector::zeros(dof))
    }

    /// Number of coordinates.
    pub fn dof(&self) -> usize {
        self.q.len()
    }

    /// Checks dimensions against `dof` and that every number is finite.
    pub fn validate(&self, dof: usize) -> Result<()> {
        check_phase_point(dof, self.t, self.q.as_slice(), self.v.as_slice(), K::SYMBOL)
    }

    /// `true` when every component is finite.
    pub fn is_finite(&self) -> bool {
        // No early exit: a few entries, one vectorised pass (the driver asks after every step).
        let finite = |x: &[f64]| x.iter().fold(true, |ok, v| ok & v.is_finite());
        self.t.is_finite() & finite(self.q.as_slice()) & finite(self.v.as_slice())
    }

    /// Copies `other` into `self` without allocating (same dimensions).
    pub fn copy_from(&mut self, other: &Self) {
        self.t = other.t;
        self.q.copy_from(&other.q);
        self.v.copy_from(&other.v);
    }
}

impl State<Momenta> {
    /// The momenta p.
    pub fn p(&self) -> &DVector<f64> {
        &self.v
    }

    /// The momenta p, to change them.
    pub fn p_mut(&mut self) -> &mut DVector<f64> {
        &mut self.v
    }
}
