//! The velocity-level view of a constraint set that the continuous equations of motion need.
//!
//! Holonomic constraints φ(t, q) = 0 imply Φ_q q̇ + φ_t = 0; nonholonomic (velocity) constraints are
//! A(t, q) q̇ + a(t, q) = 0 from the start. Both are therefore "A q̇ + a = 0" with a matrix A, and both
//! differentiate once more to the acceleration-level constraint
//!
//! ```text
//! A q̈ + c(t, q, q̇) = 0,    c = (∂/∂t + q̇·∂/∂q)(A w + a) |_{w = q̇}
//! ```
//!
//! (for holonomic constraints c = (Φ_q q̇)_q q̇ + 2 Φ_qt q̇ + φ_tt). [`ConstraintSet`] is that shape;
//! [`HolonomicSet`](crate::HolonomicSet) and [`NonholonomicSet`](crate::NonholonomicSet) adapt the
//! user's traits to it.

use nalgebra::DMatrix;

/// A set of m constraints on n coordinates, seen at the velocity level: A(t, q) q̇ + a(t, q) = 0.
///
/// This is the engine's interface, called in the inner loop of every constrained step with buffers
/// that the caller has sized: its methods do not check lengths, and an output of the wrong shape
/// panics (a deliberate exception of docs/error-contract.md §4, as `Solution`'s indexing is).
/// The checked forms, which return typed errors, are [`holonomic::values`](crate::holonomic::values),
/// [`holonomic::velocity_residual`](crate::holonomic::velocity_residual),
/// [`holonomic::acceleration_bias`](crate::holonomic::acceleration_bias),
/// [`holonomic::jacobian`](crate::holonomic::jacobian) and [`Constrained`](crate::Constrained)'s
/// methods.
pub trait ConstraintSet {
    /// Number of coordinates n.
    fn dof(&self) -> usize;
    /// Number of constraints m.
    fn count(&self) -> usize;
    /// The constraint matrix A(t, q) (m × n) into `a` (`v` is only a point at which to evaluate an
    /// affine function of the velocities; A does not depend on it).
    fn matrix(&self, t: f64, q: &[f64], v: &[f64], a: &mut DMatrix<f64>);
    /// The velocity residual A(t, q) v + a(t, q) into `out` (length m).
    fn velocity_residual(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]);
    /// The acceleration bias c(t, q, q̇) with A q̈ + c = 0 into `out` (length m).
    fn bias(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]);
    /// For holonomic sets, φ(t, q) into `out` and `true`; `false` (and `out` untouched) for velocity
    /// constraints, which have no position-level residual.
    fn positions(&self, t: f64, q: &[f64], out: &mut [f64]) -> bool;
    /// The derivatives of A, of the velocity residual A q̇ + a and of the acceleration bias c along a
    /// variation δ = (δq, δq̇) of the state (t, q, q̇), exact by nested dual numbers: the pieces of
    /// the exact Jacobian of the constrained equations of motion and of the tangent space of the
    /// constraint manifold.
    fn derivatives_along(&self, t: f64, q: &[f64], v: &[f64], dir: (&[f64], &[f64])) -> SetDerivatives;
}

/// The derivatives of a [`ConstraintSet`] along a variation of the state
/// ([`ConstraintSet::derivatives_along`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SetDerivatives {
    /// δA (m × n).
    pub matrix: DMatrix<f64>,
    /// δ(A q̇ + a) (length m).
    pub residual: Vec<f64>,
    /// δc (length m).
    pub bias: Vec<f64>,
}

impl SetDerivatives {
    /// Zeros for m constraints on n coordinates.
    pub(crate) fn zeros(m: usize, n: usize) -> Self {
        SetDerivatives {
            matrix: DMatrix::zeros(m, n),
            residual: vec![0.0; m],
            bias: vec![0.0; m],
        }
    }
}

impl<C: ConstraintSet + ?Sized> ConstraintSet for &C {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn count(&self) -> usize {
        (**self).count()
    }
    fn matrix(&self, t: f64, q: &[f64], v: &[f64], a: &mut DMatrix<f64>) {
        (**self).matrix(t, q, v, a)
    }
    fn velocity_residual(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
        (**self).velocity_residual(t, q, v, out)
    }
    fn bias(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
        (**self).bias(t, q, v, out)
    }
    fn positions(&self, t: f64, q: &[f64], out: &mut [f64]) -> bool {
        (**self).positions(t, q, out)
    }
    fn derivatives_along(&self, t: f64, q: &[f64], v: &[f64], dir: (&[f64], &[f64])) -> SetDerivatives {
        (**self).derivatives_along(t, q, v, dir)
    }
}
