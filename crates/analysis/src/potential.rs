//! Potentials V(q), written once as generic code like a Lagrangian, and their exact gradients and
//! Hessians by dual numbers (the kernels of [`noether_core::ad`]).
//!
//! A Lagrangian L(t, q, q̇) without explicit time dependence is at rest at q exactly when
//! ∂L/∂q(q, 0) = 0: the equilibria are the stationary points of the effective potential
//! `U(q) = −L(t, q, 0)` ([`EffectivePotential`]). For L = T − V with T quadratic in q̇, U = V; in a
//! rotating frame U also holds the centrifugal term.

use nalgebra::{DMatrix, DVector};
use noether_core::ad::{self, Block, Field};
use noether_core::error::{check_finite, check_len};
use noether_core::{Lagrangian, Scalar};

use crate::Result;

/// A potential energy V(q) with `dof()` coordinates: noether-core's trait (the one natural systems and
/// symplectic methods use), re-exported so that one model serves both.
///
/// ```
/// use noether_analysis::Potential;
/// use noether_core::Scalar;
///
/// /// Double well V = (q² − 1)².
/// struct DoubleWell;
/// impl Potential for DoubleWell {
///     fn dof(&self) -> usize { 1 }
///     fn potential<D: Scalar>(&self, q: &[D]) -> D {
///         let s = q[0] * q[0] - 1.0;
///         s * s
///     }
/// }
/// ```
pub use noether_core::Potential;

/// The effective potential U(q) = −L(t, q, 0) of a Lagrangian at a fixed time `t`.
#[derive(Debug, Clone, Copy)]
pub struct EffectivePotential<L> {
    /// The Lagrangian.
    pub lagrangian: L,
    /// The time at which it is frozen (irrelevant for autonomous L).
    pub t: f64,
}

impl<L: Lagrangian> EffectivePotential<L> {
    /// U(q) = −L(0, q, 0).
    pub fn new(lagrangian: L) -> Self {
        EffectivePotential { lagrangian, t: 0.0 }
    }
}

impl<L: Lagrangian> Potential for EffectivePotential<L> {
    fn dof(&self) -> usize {
        self.lagrangian.dof()
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        let zero = vec![D::zero(); q.len()];
        -self.lagrangian.lagrangian(D::from(self.t), q, &zero)
    }
}

/// A potential as the AD field f(t, x = q, y = ∅).
struct PotentialField<'a, P: ?Sized>(&'a P);

impl<P: Potential + ?Sized> Field for PotentialField<'_, P> {
    #[inline]
    fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
        self.0.potential(x)
    }
}

/// Checks that `q` has the model's length and finite entries.
pub(crate) fn check_point(q: &[f64], dof: usize) -> Result<()> {
    check_len("q", q, dof)?;
    check_finite("q", q)?;
    Ok(())
}

/// V(q) and ∇V(q) (one dual-number evaluation per chunk of coordinates).
pub fn gradient<P: Potential + ?Sized>(pot: &P, q: &[f64]) -> Result<(f64, DVector<f64>)> {
    check_point(q, pot.dof())?;
    let mut g = DVector::zeros(q.len());
    let v = ad::gradient(&PotentialField(pot), 0.0, q, &[], Block::X, g.as_mut_slice());
    Ok((v, g))
}

/// The Hessian ∂²V/∂q² (exact, by second-order dual numbers).
pub fn hessian<P: Potential + ?Sized>(pot: &P, q: &[f64]) -> Result<DMatrix<f64>> {
    check_point(q, pot.dof())?;
    let n = q.len();
    let mut h = DMatrix::zeros(n, n);
    ad::hessian(&PotentialField(pot), 0.0, q, &[], Block::X, Block::X, &mut h);
    Ok(h)
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Quartic;
    impl Potential for Quartic {
        fn dof(&self) -> usize {
            2
        }
        fn potential<D: Scalar>(&self, q: &[D]) -> D {
            q[0].powi(4) + q[0] * q[1] * 3.0 + q[1].sin()
        }
    }

    #[test]
    fn ad_vs_hand_gradient_and_hessian() {
        let q = [0.7, -0.4];
        let (v, g) = gradient(&Quartic, &q).unwrap();
        assert!((v - (0.7f64.powi(4) + 3.0 * 0.7 * -0.4 + (-0.4f64).sin())).abs() < 1e-15);
        assert!((g[0] - (4.0 * 0.343 + 3.0 * -0.4)).abs() < 1e-14);
        assert!((g[1] - (3.0 * 0.7 + (-0.4f64).cos())).abs() < 1e-14);
        let h = hessian(&Quartic, &q).unwrap();
        assert!((h[(0, 0)] - 12.0 * 0.49).abs() < 1e-13);
        assert!((h[(0, 1)] - 3.0).abs() < 1e-14 && (h[(1, 0)] - 3.0).abs() < 1e-14);
        assert!((h[(1, 1)] + (-0.4f64).sin()).abs() < 1e-14);
    }

    #[test]
    fn bad_input_wrong_length_and_nan() {
        assert!(matches!(
            gradient(&Quartic, &[1.0]),
            Err(crate::Error::Core(noether_core::Error::Dimension { .. }))
        ));
        assert!(matches!(
            hessian(&Quartic, &[1.0, f64::NAN]),
            Err(crate::Error::Core(noether_core::Error::NonFinite { .. }))
        ));
    }
}
