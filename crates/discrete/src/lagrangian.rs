//! Discrete Lagrangians L_d(q₀, q₁, h) ≈ ∫ L dt over one step, written once as generic code, and
//! their derivatives by dual numbers.
//!
//! A discrete Lagrangian fits the AD field shape f(t, x, y) of [`noether_core::ad`] with the step h in
//! the scalar slot, x = q₀ and y = q₁:
//! - D₁L_d = ∇_x f and D₂L_d = ∇_y f are gradients;
//! - the Newton Jacobian of the discrete Euler-Lagrange residual p_k + D₁L_d(q_k, q_{k+1}) with respect to
//!   q_{k+1} is the mixed Hessian block D₁₂L_d = ∂²f/∂x∂y;
//! - the discrete energy E_d = −∂L_d/∂h is the derivative in the scalar slot.
//!
//! ```
//! use noether_core::Scalar;
//! use noether_discrete::{DiscreteDerivatives, DiscreteLagrangian};
//!
//! /// Free particle of mass m, exact discrete Lagrangian L_d = m (q₁ − q₀)² / (2h).
//! struct Free { m: f64 }
//! impl DiscreteLagrangian for Free {
//!     fn dof(&self) -> usize { 1 }
//!     fn discrete_lagrangian<D: Scalar>(&self, _t0: f64, h: D, q0: &[D], q1: &[D]) -> D {
//!         let dq = q1[0] - q0[0];
//!         dq * dq / h * (0.5 * self.m)
//!     }
//! }
//!
//! let mut p1 = [0.0];
//! Free { m: 2.0 }.d2(0.0, 0.5, &[1.0], &[1.25], &mut p1);
//! assert!((p1[0] - 2.0 * 0.25 / 0.5).abs() < 1e-15); // p₁ = D₂L_d = m (q₁ − q₀)/h
//! ```

use nalgebra::DMatrix;
use noether_core::ad::{self, Block, Field};
use noether_core::{Result, Scalar};
use num_dual::Dual64;

/// A discrete Lagrangian L_d(t₀; q₀, q₁, h): an approximation of the action ∫ L dt from (t₀, q₀) to
/// (t₀ + h, q₁).
///
/// Only [`dof`](Self::dof) and [`discrete_lagrangian`](Self::discrete_lagrangian) are required. Discrete
/// forces (the discrete Lagrange-d'Alembert principle) are optional:
///
/// ```text
/// p_k + D₁L_d(q_k, q_{k+1}) + f⁻(q_k, q_{k+1}) = 0,     p_{k+1} = D₂L_d(q_k, q_{k+1}) + f⁺(q_k, q_{k+1}).
/// ```
pub trait DiscreteLagrangian {
    /// Number of coordinates.
    fn dof(&self) -> usize;

    /// The value of L_d for a step of size `h` (which may be negative inside compositions) starting at
    /// time `t0`, from `q0` to `q1`. Generic over the scalar so that h, q₀ and q₁ can all be dual numbers.
    fn discrete_lagrangian<D: Scalar>(&self, t0: f64, h: D, q0: &[D], q1: &[D]) -> D;

    /// Nominal order of the discrete Lagrangian (the order of the integrator it defines).
    fn order(&self) -> u32 {
        2
    }

    /// Hamilton's vector field (q̇, ṗ) at (t, q, p) of the continuous system this discrete Lagrangian
    /// approximates, when it has one: the driver's cubic Hermite interpolant between steps uses it
    /// (without it, output times and events between steps come from the straight line). `None` by
    /// default; the quadratures of a continuous Lagrangian ([`Midpoint`](crate::Midpoint),
    /// [`Trapezoidal`](crate::Trapezoidal)) provide it.
    fn continuous_rates(
        &self,
        _t: f64,
        _q: &[f64],
        _p: &[f64],
        _dq: &mut [f64],
        _dp: &mut [f64],
    ) -> Option<Result<()>> {
        None
    }

    /// `true` when [`discrete_force`](Self::discrete_force) is not identically zero.
    fn has_discrete_force(&self) -> bool {
        false
    }

    /// Checks that the momenta `p` at (t, q) are ones the continuous system can have: for a degenerate
    /// Lagrangian (∂²L/∂q̇² singular, e.g. L linear in q̇) p must lie on the primary constraint, to the
    /// relative tolerance `tol` (see [`primary`](crate::primary)); otherwise
    /// [`OffPrimaryConstraint`](crate::OffPrimaryConstraint). The variational integrator calls it on
    /// a state it did not produce itself. `Ok` by default (no continuous Lagrangian to check against);
    /// the quadratures of a continuous Lagrangian ([`Midpoint`](crate::Midpoint),
    /// [`Trapezoidal`](crate::Trapezoidal)) check.
    fn check_momenta(&self, _t: f64, _q: &[f64], _p: &[f64], _tol: f64) -> Result<()> {
        Ok(())
    }

    /// The discrete forces f⁻ (acting at the left end q₀) and f⁺ (at the right end q₁) of one step, whose
    /// sum approximates ∫ Q·δq dt over the step. Only called when
    /// [`has_discrete_force`](Self::has_discrete_force) is `true`. Generic over the scalar like L_d, so
    /// that Newton's Jacobian and the step's tangent include their derivatives
    /// ([`DiscreteDerivatives::force_derivatives`]).
    fn discrete_force<D: Scalar>(
        &self,
        _t0: f64,
        _h: f64,
        _q0: &[D],
        _q1: &[D],
        minus: &mut [D],
        plus: &mut [D],
    ) {
        minus
            .iter_mut()
            .chain(plus.iter_mut())
            .for_each(|x| *x = D::zero());
    }
}

impl<Ld: DiscreteLagrangian + ?Sized> DiscreteLagrangian for &Ld {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn discrete_lagrangian<D: Scalar>(&self, t0: f64, h: D, q0: &[D], q1: &[D]) -> D {
        (**self).discrete_lagrangian(t0, h, q0, q1)
    }
    fn order(&self) -> u32 {
        (**self).order()
    }
    fn has_discrete_force(&self) -> bool {
        (**self).has_discrete_force()
    }
    fn check_momenta(&self, t: f64, q: &[f64], p: &[f64], tol: f64) -> Result<()> {
        (**self).check_momenta(t, q, p, tol)
    }
    fn discrete_force<D: Scalar>(
        &self,
        t0: f64,
        h: f64,
        q0: &[D],
        q1: &[D],
        minus: &mut [D],
        plus: &mut [D],
    ) {
        (**self).discrete_force(t0, h, q0, q1, minus, plus)
    }
    fn continuous_rates(
        &self,
        t: f64,
        q: &[f64],
        p: &[f64],
        dq: &mut [f64],
        dp: &mut [f64],
    ) -> Option<Result<()>> {
        (**self).continuous_rates(t, q, p, dq, dp)
    }
}

/// A discrete Lagrangian seen as the AD field f(h, x = q₀, y = q₁) at a fixed start time t₀.
pub struct DiscreteField<'a, Ld: ?Sized> {
    /// The discrete Lagrangian.
    pub ld: &'a Ld,
    /// Start time of the step.
    pub t0: f64,
}

impl<Ld: DiscreteLagrangian + ?Sized> Field for DiscreteField<'_, Ld> {
    #[inline]
    fn eval<D: Scalar>(&self, h: D, x: &[D], y: &[D]) -> D {
        self.ld.discrete_lagrangian(self.t0, h, x, y)
    }
}

/// Derivatives of every [`DiscreteLagrangian`] by dual numbers (blanket-implemented).
///
/// Lengths are not checked here (debug assertions only): the steppers validate their inputs once.
pub trait DiscreteDerivatives: DiscreteLagrangian {
    /// D₁L_d(q₀, q₁) into `out`; returns L_d.
    fn d1(&self, t0: f64, h: f64, q0: &[f64], q1: &[f64], out: &mut [f64]) -> f64 {
        ad::gradient(&DiscreteField { ld: self, t0 }, h, q0, q1, Block::X, out)
    }

    /// D₂L_d(q₀, q₁) into `out`; returns L_d.
    fn d2(&self, t0: f64, h: f64, q0: &[f64], q1: &[f64], out: &mut [f64]) -> f64 {
        ad::gradient(&DiscreteField { ld: self, t0 }, h, q0, q1, Block::Y, out)
    }

    /// (D₁ + D₂)L_d(q₀, q₁) into `out`: the derivative along a common shift of both ends,
    /// ∂/∂s L_d(q₀ + s, q₁ + s), by one dual evaluation in which the shift cancels exactly from
    /// q₁ − q₀. Unlike the sum of [`d1`](Self::d1) and [`d2`](Self::d2) (each ~ p, summing to a small
    /// force impulse) it carries no cancellation error: it is the momentum change of a step,
    /// p_{k+1} − p_k, to relative rounding.
    fn d1_plus_d2(&self, t0: f64, h: f64, q0: &[f64], q1: &[f64], out: &mut [f64]) {
        let zero = Scratch::<f64>::filled(q0.len(), 0.0);
        let f = ShiftField { ld: self, t0, q0, q1 };
        ad::gradient(&f, h, &zero, &[], Block::X, out);
    }

    /// The mixed block D₁₂L_d = ∂²L_d/∂q₀∂q₁ (rows q₀, columns q₁) into `out` (dof × dof): the Jacobian
    /// of q₁ ↦ D₁L_d(q₀, q₁).
    fn d12(&self, t0: f64, h: f64, q0: &[f64], q1: &[f64], out: &mut DMatrix<f64>) {
        let f = DiscreteField { ld: self, t0 };
        ad::hessian(&f, h, q0, q1, Block::X, Block::Y, out)
    }

    /// D₂₂L_d = ∂²L_d/∂q₁² into `out` (dof × dof): the Jacobian of q₁ ↦ D₂L_d(q₀, q₁).
    fn d22(&self, t0: f64, h: f64, q0: &[f64], q1: &[f64], out: &mut DMatrix<f64>) {
        let f = DiscreteField { ld: self, t0 };
        ad::hessian(&f, h, q0, q1, Block::Y, Block::Y, out)
    }

    /// D₁₁L_d = ∂²L_d/∂q₀² into `out` (dof × dof).
    fn d11(&self, t0: f64, h: f64, q0: &[f64], q1: &[f64], out: &mut DMatrix<f64>) {
        let f = DiscreteField { ld: self, t0 };
        ad::hessian(&f, h, q0, q1, Block::X, Block::X, out)
    }

    /// The discrete energy E_d = −∂L_d/∂h (q₀, q₁ fixed).
    fn discrete_energy(&self, t0: f64, h: f64, q0: &[f64], q1: &[f64]) -> f64 {
        -ad::partial_t(&DiscreteField { ld: self, t0 }, h, q0, q1)
    }

    /// The Jacobians of the discrete forces with respect to one end, q₀ (`end` = [`StepEnd::Left`]) or q₁
    /// ([`StepEnd::Right`]): ∂f⁻/∂q_end into `minus` and ∂f⁺/∂q_end into `plus` (dof × dof), column j from
    /// one evaluation of [`discrete_force`](DiscreteLagrangian::discrete_force) over `Dual64` seeded
    /// along e_j. Both are zero without forces.
    fn force_derivatives(
        &self,
        t0: f64,
        h: f64,
        (q0, q1): (&[f64], &[f64]),
        end: StepEnd,
        (minus, plus): (&mut DMatrix<f64>, &mut DMatrix<f64>),
    ) {
        minus.fill(0.0);
        plus.fill(0.0);
        if !self.has_discrete_force() {
            return;
        }
        let n = q0.len();
        let (mut fm, mut fp) = (vec![Dual64::from(0.0); n], vec![Dual64::from(0.0); n]);
        for j in 0..n {
            let seed = |q: &[f64], at: StepEnd| -> Vec<Dual64> {
                let dir = if at == end { 1.0 } else { 0.0 };
                (0..n)
                    .map(|i| Dual64::new(q[i], if i == j { dir } else { 0.0 }))
                    .collect()
            };
            let (a, b) = (seed(q0, StepEnd::Left), seed(q1, StepEnd::Right));
            self.discrete_force(t0, h, &a, &b, &mut fm, &mut fp);
            for i in 0..n {
                minus[(i, j)] = fm[i].eps;
                plus[(i, j)] = fp[i].eps;
            }
        }
    }
}

/// One end of a step: q₀ (left) or q₁ (right).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepEnd {
    /// The start q₀.
    Left,
    /// The end q₁.
    Right,
}

impl<Ld: DiscreteLagrangian + ?Sized> DiscreteDerivatives for Ld {}

/// s ↦ L_d(q₀ + s, q₁ + s) as an AD field (x = s, the step h in the scalar slot).
struct ShiftField<'a, Ld: ?Sized> {
    ld: &'a Ld,
    t0: f64,
    q0: &'a [f64],
    q1: &'a [f64],
}

impl<Ld: DiscreteLagrangian + ?Sized> Field for ShiftField<'_, Ld> {
    #[inline]
    fn eval<D: Scalar>(&self, h: D, s: &[D], _y: &[D]) -> D {
        let (a, b) = (shifted(s, self.q0), shifted(s, self.q1));
        self.ld.discrete_lagrangian(self.t0, h, &a, &b)
    }
}

/// A short vector of scalars on the stack (up to 16), on the heap beyond: scratch space for generic
/// model code that must not allocate per evaluation for small systems.
pub(crate) type Scratch<D> = noether_core::ad::Buf<D, 16>;

/// s + q. Like the other small builders of scratch vectors here, generic in D only, not in the model
/// (`noether_core::ad::Buf::new` says why).
fn shifted<D: Scalar>(s: &[D], q: &[f64]) -> Scratch<D> {
    Scratch::new(s.len(), |i| s[i] + q[i])
}

/// (q0 + q1)/2.
pub(crate) fn midpoint<D: Scalar>(q0: &[D], q1: &[D]) -> Scratch<D> {
    Scratch::new(q0.len(), |i| (q0[i] + q1[i]) * 0.5)
}

/// (q1 − q0)/h.
pub(crate) fn difference_quotient<D: Scalar>(q0: &[D], q1: &[D], h: D) -> Scratch<D> {
    Scratch::new(q0.len(), |i| (q1[i] - q0[i]) / h)
}
