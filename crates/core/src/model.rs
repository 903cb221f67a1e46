//! The user's models: a Lagrangian L(t, q, q̇) or a Hamiltonian H(t, q, p), written once as generic code.
//!
//! ```
//! use noether_core::{Lagrangian, Scalar};
//!
//! /// Simple pendulum, L = ½ m l² θ̇² + m g l cos θ.
//! struct Pendulum { m: f64, l: f64, g: f64 }
//!
//! impl Lagrangian for Pendulum {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         v[0] * v[0] * (0.5 * self.m * self.l * self.l) + q[0].cos() * (self.m * self.g * self.l)
//!     }
//! }
//! ```

use crate::{Error, Scalar};

/// A Lagrangian L(t, q, q̇) with `dof()` generalized coordinates.
///
/// Only [`dof`](Lagrangian::dof) and [`lagrangian`](Lagrangian::lagrangian) are required. The other
/// methods describe structure that lets noether skip work (a constant mass matrix is factored once) and
/// non-potential generalized forces Q(t, q, q̇) entering Lagrange's equations
/// `d/dt(∂L/∂q̇) − ∂L/∂q = Q`.
pub trait Lagrangian {
    /// Number of generalized coordinates.
    fn dof(&self) -> usize;

    /// The value of L at time `t`, coordinates `q` and velocities `v = q̇` (both of length `dof()`).
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D;

    /// `true` when the mass matrix M = ∂²L/∂q̇² depends on neither t, q nor q̇ (then it is computed and
    /// factored once). Declaring it wrongly gives wrong dynamics; the default `false` is always safe.
    fn constant_mass_matrix(&self) -> bool {
        false
    }

    /// `true` when [`generalized_force`](Lagrangian::generalized_force) is not identically zero.
    fn has_generalized_force(&self) -> bool {
        false
    }

    /// Non-potential generalized forces Q(t, q, q̇) (damping, driving), written into `out` (length
    /// `dof()`). Only called when [`has_generalized_force`](Lagrangian::has_generalized_force) returns
    /// `true`.
    ///
    /// Generic over the scalar like [`lagrangian`](Lagrangian::lagrangian), so every derivative noether
    /// takes of the equations of motion includes ∂Q/∂q and ∂Q/∂q̇ exactly: the Jacobian of Lagrange's
    /// equations (so implicit Runge-Kutta methods and the tangents of the flow), the Newton Jacobians and
    /// tangents of forced variational integrators. A force from data rather than a formula (a measured
    /// wind, a table) that depends on t only is written `D::from(table(t.re()))`: its derivatives in q
    /// and q̇ are zero, as they should be. A force that reads q or q̇ through `re()` would have wrong
    /// derivatives: write it with the scalar's arithmetic instead.
    fn generalized_force<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], out: &mut [D]) {
        out.iter_mut().for_each(|x| *x = D::zero());
    }
}

/// A Hamiltonian H(t, q, p) with `dof()` coordinates and as many conjugate momenta.
pub trait Hamiltonian {
    /// Number of coordinates (half the phase-space dimension).
    fn dof(&self) -> usize;

    /// The value of H at time `t`, coordinates `q` and momenta `p`.
    fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D]) -> D;

    /// Why H is not finite at (t, q, p), for a model that can fail there (a Hamiltonian computed by
    /// a solve, e.g. [`LegendreTransform`](crate::LegendreTransform)): a model signals failure by a
    /// non-finite value of [`hamiltonian`](Self::hamiltonian), and [`HamiltonEquations`](crate::HamiltonEquations)
    /// (so every Hamiltonian integrator) then reports the error returned here, or
    /// [`Error::NonFiniteResult`] when it is `None` (the default).
    fn failure(&self, _t: f64, _q: &[f64], _p: &[f64]) -> Option<Error> {
        None
    }
}

/// A separable Hamiltonian H = T(p) + V(q): the split that explicit symplectic methods need.
///
/// Every `Separable` is a [`Hamiltonian`] through [`SeparableHamiltonian`].
pub trait Separable {
    /// Number of coordinates.
    fn dof(&self) -> usize;
    /// Kinetic energy T(p).
    fn kinetic<D: Scalar>(&self, p: &[D]) -> D;
    /// Potential energy V(q).
    fn potential<D: Scalar>(&self, q: &[D]) -> D;
}

/// Adapter: a [`Separable`] viewed as a [`Hamiltonian`] H = T(p) + V(q).
#[derive(Debug, Clone, Copy)]
pub struct SeparableHamiltonian<S>(pub S);

impl<S: Separable> Hamiltonian for SeparableHamiltonian<S> {
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        self.0.kinetic(p) + self.0.potential(q)
    }
}

impl<L: Lagrangian + ?Sized> Lagrangian for &L {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        (**self).lagrangian(t, q, v)
    }
    fn constant_mass_matrix(&self) -> bool {
        (**self).constant_mass_matrix()
    }
    fn has_generalized_force(&self) -> bool {
        (**self).has_generalized_force()
    }
    fn generalized_force<D: Scalar>(&self, t: D, q: &[D], v: &[D], out: &mut [D]) {
        (**self).generalized_force(t, q, v, out)
    }
}

impl<H: Hamiltonian + ?Sized> Hamiltonian for &H {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D]) -> D {
        (**self).hamiltonian(t, q, p)
    }
    fn failure(&self, t: f64, q: &[f64], p: &[f64]) -> Option<Error> {
        (**self).failure(t, q, p)
    }
}

impl<S: Separable + ?Sized> Separable for &S {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn kinetic<D: Scalar>(&self, p: &[D]) -> D {
        (**self).kinetic(p)
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        (**self).potential(q)
    }
}
