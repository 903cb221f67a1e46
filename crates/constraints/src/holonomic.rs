//! Holonomic constraints φ(t, q) = 0, written once as generic code; Φ_q, φ_t and the acceleration
//! terms come from dual numbers.
//!
//! ```
//! use noether_constraints::{Holonomic, HolonomicSet, ConstraintSet};
//! use noether_core::Scalar;
//!
//! /// A pendulum rod of length l in Cartesian coordinates: φ = (x² + y² − l²)/2.
//! struct Rod { l: f64 }
//! impl Holonomic for Rod {
//!     fn dof(&self) -> usize { 2 }
//!     fn count(&self) -> usize { 1 }
//!     fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
//!         out[0] = (q[0] * q[0] + q[1] * q[1] - self.l * self.l) * 0.5;
//!     }
//! }
//!
//! let rod = HolonomicSet(Rod { l: 2.0 });
//! let mut a = nalgebra::DMatrix::zeros(1, 2);
//! rod.matrix(0.0, &[1.2, -1.6], &[0.0, 0.0], &mut a); // Φ_q = (x, y)
//! assert_eq!((a[(0, 0)], a[(0, 1)]), (1.2, -1.6));
//! let mut c = [0.0];
//! rod.bias(0.0, &[1.2, -1.6], &[0.8, 0.6], &mut c); // (Φ_q q̇)_q q̇ = |q̇|²
//! assert!((c[0] - 1.0).abs() < 1e-15);
//! ```

use crate::jets::{self, Block, VectorField};
use crate::set::ConstraintSet;
use nalgebra::DMatrix;
use noether_core::Scalar;

/// m holonomic constraints φ(t, q) = 0 on n coordinates.
///
/// Write the constraint values into `out` (length `count()`), generic over the scalar type like a
/// Lagrangian. Scale each constraint so that its gradient has a natural size (e.g. (|r|² − l²)/2 for a
/// rod): the multipliers are then forces per unit of that gradient.
pub trait Holonomic {
    /// Number of coordinates n.
    fn dof(&self) -> usize;
    /// Number of constraints m.
    fn count(&self) -> usize;
    /// φ(t, q) into `out`.
    fn constraints<D: Scalar>(&self, t: D, q: &[D], out: &mut [D]);
}

impl<C: Holonomic + ?Sized> Holonomic for &C {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn count(&self) -> usize {
        (**self).count()
    }
    fn constraints<D: Scalar>(&self, t: D, q: &[D], out: &mut [D]) {
        (**self).constraints(t, q, out)
    }
}

/// φ(t, q) seen as the vector field g(t, x = q, y = ·).
struct Field<'a, C: ?Sized>(&'a C);

impl<C: Holonomic + ?Sized> VectorField for Field<'_, C> {
    fn outputs(&self) -> usize {
        self.0.count()
    }
    #[inline]
    fn eval<D: Scalar>(&self, t: D, x: &[D], _y: &[D], out: &mut [D]) {
        self.0.constraints(t, x, out)
    }
}

/// φ(t, q) into `out`.
pub fn values<C: Holonomic + ?Sized>(c: &C, t: f64, q: &[f64], out: &mut [f64]) {
    c.constraints(t, q, out)
}

/// The constraint Jacobian Φ_q (m × n) into `out`.
pub fn jacobian<C: Holonomic + ?Sized>(c: &C, t: f64, q: &[f64], out: &mut DMatrix<f64>) {
    jets::jacobian(&Field(c), t, q, &[], Block::X, out)
}

/// ∂φ/∂t into `out` (zero for scleronomic constraints).
pub fn partial_t<C: Holonomic + ?Sized>(c: &C, t: f64, q: &[f64], out: &mut [f64]) {
    jets::along(&Field(c), t, q, &[], (1.0, &[], &[]), out)
}

/// The velocity residual Φ_q v + φ_t = dφ/dt along q̇ = v, into `out`.
pub fn velocity_residual<C: Holonomic + ?Sized>(c: &C, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
    jets::along(&Field(c), t, q, &[], (1.0, v, &[]), out)
}

/// The acceleration term d²φ/dt² at q̈ = 0, i.e. (Φ_q q̇)_q q̇ + 2 Φ_qt q̇ + φ_tt, into `out`.
pub fn acceleration_bias<C: Holonomic + ?Sized>(c: &C, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
    let mut first = vec![0.0; out.len()];
    jets::along2(&Field(c), t, q, &[], (1.0, v, &[]), &mut first, out)
}

/// Adapter: a [`Holonomic`] constraint set as a [`ConstraintSet`].
#[derive(Debug, Clone, Copy)]
pub struct HolonomicSet<C>(pub C);

impl<C: Holonomic> ConstraintSet for HolonomicSet<C> {
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn count(&self) -> usize {
        self.0.count()
    }
    fn matrix(&self, t: f64, q: &[f64], _v: &[f64], a: &mut DMatrix<f64>) {
        jacobian(&self.0, t, q, a)
    }
    fn velocity_residual(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
        velocity_residual(&self.0, t, q, v, out)
    }
    fn bias(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
        acceleration_bias(&self.0, t, q, v, out)
    }
    fn positions(&self, t: f64, q: &[f64], out: &mut [f64]) -> bool {
        values(&self.0, t, q, out);
        true
    }
}
