//! Nonholonomic constraints linear in the velocities, A(t, q) q̇ + a(t, q) = 0 (Lagrange-d'Alembert).
//!
//! The user writes g(t, q, v) = A(t, q) v + a(t, q) as generic code; A = ∂g/∂v and the acceleration
//! bias c = g_t + g_q q̇ (at fixed v = q̇) come from dual numbers. The constraint forces Aᵀλ do no
//! virtual work on velocities allowed by the constraints (d'Alembert's principle), which is not the
//! same as the variational (vakonomic) equations: noether implements Lagrange-d'Alembert.
//!
//! ```
//! use noether_constraints::{Nonholonomic, NonholonomicSet, ConstraintSet};
//! use noether_core::Scalar;
//!
//! /// A knife edge (skate) in the plane, q = (x, y, φ): no velocity across the blade,
//! /// −ẋ sin φ + ẏ cos φ = 0.
//! struct Skate;
//! impl Nonholonomic for Skate {
//!     fn dof(&self) -> usize { 3 }
//!     fn count(&self) -> usize { 1 }
//!     fn constraints<D: Scalar>(&self, _t: D, q: &[D], v: &[D], out: &mut [D]) {
//!         out[0] = -v[0] * q[2].sin() + v[1] * q[2].cos();
//!     }
//! }
//! let set = NonholonomicSet(Skate);
//! let mut a = nalgebra::DMatrix::zeros(1, 3);
//! set.matrix(0.0, &[0.0, 0.0, 0.0], &[0.0; 3], &mut a);
//! assert_eq!(a.as_slice(), &[0.0, 1.0, 0.0]);
//! ```

use crate::jets::{self, Block, Variation, VectorField};
use crate::set::{ConstraintSet, SetDerivatives};
use nalgebra::DMatrix;
use noether_core::Scalar;

/// m velocity constraints g(t, q, v) = A(t, q) v + a(t, q) = 0 on n coordinates.
///
/// `constraints` must be affine in `v` (linear plus a term free of v); the equations of motion assume
/// it. The generic method is evaluated with dual numbers for A and the bias.
pub trait Nonholonomic {
    /// Number of coordinates n.
    fn dof(&self) -> usize;
    /// Number of constraints m.
    fn count(&self) -> usize;
    /// g(t, q, v) = A(t, q) v + a(t, q) into `out`.
    fn constraints<D: Scalar>(&self, t: D, q: &[D], v: &[D], out: &mut [D]);
}

struct Field<'a, C: ?Sized>(&'a C);

impl<C: Nonholonomic + ?Sized> VectorField for Field<'_, C> {
    fn outputs(&self) -> usize {
        self.0.count()
    }
    #[inline]
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D], out: &mut [D]) {
        self.0.constraints(t, x, y, out)
    }
}

/// Adapter: a [`Nonholonomic`] constraint set as a [`ConstraintSet`].
#[derive(Debug, Clone, Copy)]
pub struct NonholonomicSet<C>(pub C);

impl<C: Nonholonomic> ConstraintSet for NonholonomicSet<C> {
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn count(&self) -> usize {
        self.0.count()
    }
    fn matrix(&self, t: f64, q: &[f64], v: &[f64], a: &mut DMatrix<f64>) {
        jets::jacobian(&Field(&self.0), t, q, v, Block::Y, a)
    }
    fn velocity_residual(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
        self.0.constraints(t, q, v, out)
    }
    fn bias(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
        // (∂/∂t + q̇·∂/∂q) g at fixed v = q̇: direction (1, q̇, 0).
        jets::along(&Field(&self.0), t, q, v, (1.0, v, &[]), out)
    }
    fn positions(&self, _t: f64, _q: &[f64], _out: &mut [f64]) -> bool {
        false
    }
    /// δA = δ(∂g/∂v) from the mixed second derivatives of g; g itself and
    /// c = (d/ds) g(t + s, q + s q̇, q̇) varied with (q, q̇) in one `Dual2<Dual64>` evaluation.
    fn derivatives_along(&self, t: f64, q: &[f64], v: &[f64], (dq, dv): (&[f64], &[f64])) -> SetDerivatives {
        let mut d = SetDerivatives::zeros(self.0.count(), self.0.dof());
        let point = Variation {
            ex: dq,
            ey: dv,
            edx: dv,
            edy: &[],
        };
        jets::jacobian_varied(&Field(&self.0), t, (q, v), point, Block::Y, &mut d.matrix);
        let mut unused = vec![0.0; self.0.count()];
        let out = [&mut d.residual[..], &mut d.bias[..], &mut unused[..]];
        jets::along_varied(&Field(&self.0), t, (q, v), (1.0, v, &[]), point, out);
        d
    }
}
