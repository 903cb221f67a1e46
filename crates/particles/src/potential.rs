//! The user's interactions: one-body and two-body potentials written once as generic code, and
//! non-conservative forces; the dual-number kernels that turn a potential into forces and Hessians.
//!
//! By-on convention (separation r21 = r2 − r1 points from particle 1 to particle 2): for a two-body
//! potential U(r21), the force on particle 2 is `F21 = −∇_{r21} U` and the force on particle 1 is
//! `F12 = +∇_{r21} U = −F21`. The library applies both from one evaluation, so Newton's third law holds
//! by construction. Gradients come from one `DualSVec64<3>` evaluation (three derivative slots on the
//! stack), Hessian blocks from one `Dual2SVec64<3>` evaluation.
//!
//! ```
//! use noether_core::Scalar;
//! use noether_particles::{Particle, PairPotential};
//!
//! /// A Morse bond U(r) = De (1 − e^{−a (r − re)})².
//! struct Morse { de: f64, a: f64, re: f64 }
//! impl PairPotential for Morse {
//!     fn energy<D: Scalar>(&self, r: [D; 3], _p1: &Particle, _p2: &Particle) -> D {
//!         let d = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
//!         let e = D::one() - ((d - self.re) * (-self.a)).exp();
//!         e * e * self.de
//!     }
//! }
//! let p = Particle::new(1.0);
//! let (u, g) = noether_particles::potential::pair_gradient(&Morse { de: 2.0, a: 1.5, re: 1.0 }, [1.0, 0.0, 0.0], &p, &p);
//! assert_eq!(u, 0.0);
//! assert!(g.iter().all(|x| x.abs() < 1e-15)); // no force at the bond length
//! ```

use crate::particle::{Particle, Vec3};
use nalgebra::{Const, U1};
use noether_core::Scalar;
use num_dual::{Dual2SVec64, Dual64, DualSVec64};

/// A two-body potential energy U(r21; particle 1, particle 2), generic over the scalar.
///
/// It may depend on the two particles' parameters (masses for gravity, charges for Coulomb). It must be
/// symmetric under exchange: U(r21; p1, p2) = U(−r21; p2, p1) (true of every central potential).
pub trait PairPotential: Sync + Send {
    /// U at separation `r` = r2 − r1.
    fn energy<D: Scalar>(&self, r: [D; 3], p1: &Particle, p2: &Particle) -> D;

    /// `true` for a central potential U(|r21|): forces then come from one `Dual64` evaluation of
    /// [`radial`](PairPotential::radial) in s = |r21|² (∇U = 2 U'(s) r21), the fast path.
    const RADIAL: bool = false;

    /// A central potential as a function of s = |r21|². The default evaluates
    /// [`energy`](PairPotential::energy) at r21 = (√s, 0, 0); the ready-made laws write their physics
    /// here once and let `energy` call it.
    #[inline(always)]
    fn radial<D: Scalar>(&self, s: D, p1: &Particle, p2: &Particle) -> D {
        self.energy([s.sqrt(), D::zero(), D::zero()], p1, p2)
    }

    /// Distance beyond which U = 0 exactly (required by [`ShortRange`](crate::ShortRange)).
    fn cutoff(&self) -> Option<f64> {
        None
    }
}

/// A one-body potential energy V(t, r; particle), generic over the scalar (uniform gravity, a trap,
/// a spring to a fixed point).
pub trait OnePotential: Sync + Send {
    /// `true` when V depends on t explicitly (symplectic split methods then refuse the system).
    const TIME_DEPENDENT: bool = false;

    /// For a potential of the distance to a fixed centre c, V = V(t, |r − c|²): the centre. Forces then
    /// come from one `Dual64` evaluation of [`radial`](OnePotential::radial) (the fast path).
    fn center(&self) -> Option<Vec3> {
        None
    }

    /// V as a function of s = |r − c|² (used when [`center`](OnePotential::center) is `Some(c)`). The
    /// default evaluates [`energy`](OnePotential::energy) at r = c + (√s, 0, 0).
    #[inline(always)]
    fn radial<D: Scalar>(&self, t: f64, s: D, p: &Particle) -> D {
        let c = self.center().unwrap_or([0.0; 3]);
        self.energy(t, [s.sqrt() + c[0], D::from(c[1]), D::from(c[2])], p)
    }

    /// V at time `t` and position `r` of a particle with parameters `p`.
    fn energy<D: Scalar>(&self, t: f64, r: [D; 3], p: &Particle) -> D;
}

/// A one-body force F(t, r, v; particle) that is not the gradient of a potential (drag, driving, the
/// Lorentz force). It enters Lagrange's equations as a generalized force. Generic over the scalar like
/// a potential, so that the Jacobians of the equations of motion include its derivatives.
pub trait OneBodyForce: Sync + Send {
    /// The force on a particle at position `r` with velocity `v`.
    fn force<D: Scalar>(&self, t: f64, r: [D; 3], v: [D; 3], p: &Particle) -> [D; 3];
}

/// The state of one particle seen by a two-body force (`D` the scalar: `f64`, or a dual number when
/// the force is differentiated).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body<'a, D = f64> {
    /// Position.
    pub r: [D; 3],
    /// Velocity.
    pub v: [D; 3],
    /// Mass and charge.
    pub p: &'a Particle,
}

/// A two-body force in the by-on convention: `force(t, by, on)` is the force produced by `by` and acting
/// on `on`. The system applies `+force` to `on` and `−force` to `by` (Newton's third law by
/// construction), so only one evaluation per pair is needed.
pub trait TwoBodyForce: Sync + Send {
    /// Force produced by `by`, acting on `on`.
    fn force<D: Scalar>(&self, t: f64, by: Body<'_, D>, on: Body<'_, D>) -> [D; 3];
}

/// U(r) and ∇_r U by one `DualSVec64<3>` evaluation (one `Dual64` evaluation in s = |r|² for
/// [`RADIAL`](PairPotential::RADIAL) potentials). The force on particle 2 is −∇U, on particle 1 +∇U.
#[inline(always)]
pub fn pair_gradient<P: PairPotential + ?Sized>(
    pot: &P,
    r: Vec3,
    p1: &Particle,
    p2: &Particle,
) -> (f64, Vec3) {
    if P::RADIAL {
        let s = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
        let u = pot.radial(Dual64::new(s, 1.0), p1, p2);
        let c = 2.0 * u.eps;
        return (u.re, [c * r[0], c * r[1], c * r[2]]);
    }
    let s = |k: usize| DualSVec64::<3>::from_re(r[k]).derivative(k);
    let u = pot.energy([s(0), s(1), s(2)], p1, p2);
    let g = u.eps.unwrap_generic(Const::<3>, U1);
    (u.re, [g[0], g[1], g[2]])
}

/// The 3×3 Hessian ∂²U/∂r∂r (row-major) by one `Dual2SVec64<3>` evaluation.
#[inline]
pub fn pair_hessian<P: PairPotential + ?Sized>(
    pot: &P,
    r: Vec3,
    p1: &Particle,
    p2: &Particle,
) -> [[f64; 3]; 3] {
    let s = |k: usize| Dual2SVec64::<3>::from_re(r[k]).derivative(k);
    let u = pot.energy([s(0), s(1), s(2)], p1, p2);
    let h = u.v2.unwrap_generic(Const::<3>, Const::<3>);
    std::array::from_fn(|i| std::array::from_fn(|j| h[(i, j)]))
}

/// V(t, r) and ∇_r V by one `DualSVec64<3>` evaluation (one `Dual64` in |r − c|² for potentials with a
/// [`center`](OnePotential::center)).
#[inline(always)]
pub fn one_gradient<P: OnePotential + ?Sized>(pot: &P, t: f64, r: Vec3, p: &Particle) -> (f64, Vec3) {
    if let Some(c) = pot.center() {
        let d = [r[0] - c[0], r[1] - c[1], r[2] - c[2]];
        let u = pot.radial(t, Dual64::new(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0), p);
        let k = 2.0 * u.eps;
        return (u.re, [k * d[0], k * d[1], k * d[2]]);
    }
    let s = |k: usize| DualSVec64::<3>::from_re(r[k]).derivative(k);
    let u = pot.energy(t, [s(0), s(1), s(2)], p);
    let g = u.eps.unwrap_generic(Const::<3>, U1);
    (u.re, [g[0], g[1], g[2]])
}

/// The 3×3 Hessian ∂²V/∂r∂r of a one-body potential.
#[inline]
pub fn one_hessian<P: OnePotential + ?Sized>(pot: &P, t: f64, r: Vec3, p: &Particle) -> [[f64; 3]; 3] {
    let s = |k: usize| Dual2SVec64::<3>::from_re(r[k]).derivative(k);
    let u = pot.energy(t, [s(0), s(1), s(2)], p);
    let h = u.v2.unwrap_generic(Const::<3>, Const::<3>);
    std::array::from_fn(|i| std::array::from_fn(|j| h[(i, j)]))
}

/// r2 − r1 for particles `i`, `j` of a flat array (generic: used by the Lagrangian path).
#[inline(always)]
pub(crate) fn sep<D: Scalar>(x: &[D], i: usize, j: usize) -> [D; 3] {
    [
        x[3 * j] - x[3 * i],
        x[3 * j + 1] - x[3 * i + 1],
        x[3 * j + 2] - x[3 * i + 2],
    ]
}

/// r2 − r1 for particles `i`, `j` of a flat `f64` array.
#[inline(always)]
pub(crate) fn sep64(x: &[f64], i: usize, j: usize) -> Vec3 {
    [
        x[3 * j] - x[3 * i],
        x[3 * j + 1] - x[3 * i + 1],
        x[3 * j + 2] - x[3 * i + 2],
    ]
}

/// |r|.
#[inline(always)]
pub(crate) fn norm(r: Vec3) -> f64 {
    (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt()
}
