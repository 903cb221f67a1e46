//! Ready-made interactions (force laws of ../shared/SEEDS.md part 1), with r21 = r2 − r1, r = |r21|,
//! r̂ = r21/r and the force on particle 2 written F21 (the force on particle 1 is −F21).
//!
//! Two-body potentials: [`Gravity`], [`Coulomb`], [`ConstantRepulsion`], [`Spring`], [`Billiard`],
//! [`LennardJones`], [`GaussianCoupling`]. Two-body force: [`CentralForce`] (any scalar law f(r)).
//! One-body potentials: [`UniformGravity`], [`Trap`], [`FixedEnd`] (a two-body potential with the other
//! end at a fixed point: the seed's `one_from_two`). One-body force: [`LinearDrag`].

use crate::particle::{Particle, Vec3};
use crate::potential::{Body, OneBodyForce, OnePotential, PairPotential, TwoBodyForce};
use noether_core::Scalar;

/// Newton's gravitational constant G in N m²/kg² (the seed's value).
pub const G_NEWTON: f64 = 6.67408e-11;

#[inline(always)]
fn r2<D: Scalar>(r: &[D; 3]) -> D {
    r[0] * r[0] + r[1] * r[1] + r[2] * r[2]
}

/// Implements [`PairPotential`] for a central law written once, as a function of s = |r21|² (the
/// body, with `self`, `s` and the two particles named at the call): `energy` evaluates it at
/// s = r21·r21 and forces take the one-`Dual64` radial path. An optional `cutoff: |self| …` gives
/// [`PairPotential::cutoff`].
macro_rules! central {
    ($law:ty, |$this:ident, $s:ident, $p1:pat_param, $p2:pat_param| $body:expr
        $(, cutoff: |$c:ident| $cut:expr)? $(,)?) => {
        impl PairPotential for $law {
            const RADIAL: bool = true;
            #[inline(always)]
            fn energy<D: Scalar>(&self, r: [D; 3], p1: &Particle, p2: &Particle) -> D {
                self.radial(r2(&r), p1, p2)
            }
            #[inline(always)]
            fn radial<D: Scalar>(&$this, $s: D, $p1: &Particle, $p2: &Particle) -> D {
                $body
            }
            $(
                fn cutoff(&$c) -> Option<f64> {
                    $cut
                }
            )?
        }
    };
}

/// Universal gravity U = −G m1 m2 / r, F21 = −G m1 m2 r21 / r³.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gravity {
    /// Gravitational constant (use [`G_NEWTON`] in SI units, 1 in reduced units).
    pub g: f64,
}

central! { Gravity, |self, s, p1, p2| s.sqrt().recip() * (-self.g * p1.mass * p2.mass) }

/// Coulomb U = k e1 e2 / r, F21 = k e1 e2 r21 / r³ (charges from the particles).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coulomb {
    /// Coulomb constant k = 1/(4π ε0) (8.9875517923e9 N m²/C² in SI units).
    pub k: f64,
}

central! { Coulomb, |self, s, p1, p2| s.sqrt().recip() * (self.k * p1.charge * p2.charge) }

/// Constant repulsive force of magnitude F: F21 = F r̂, U = −F r.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConstantRepulsion {
    /// Magnitude F.
    pub f: f64,
}

central! { ConstantRepulsion, |self, s, _, _| s.sqrt() * (-self.f) }

/// Linear spring U = ½ k (r − re)², F21 = −k (r − re) r̂. With re = 0 it is U = ½ k r² (smooth at r = 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spring {
    /// Spring constant k.
    pub k: f64,
    /// Equilibrium length re.
    pub re: f64,
}

central! { Spring, |self, s, _, _| {
    if self.re == 0.0 {
        s * (0.5 * self.k)
    } else {
        let d = s.sqrt() - self.re;
        d * d * (0.5 * self.k)
    }
}}

/// Elastic billiard contact between balls whose radii add up to re: U = ½ k (r − re)² for r < re
/// (a compressed linear spring), U = 0 for r ≥ re. Conservative, piecewise smooth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Billiard {
    /// Contact stiffness k.
    pub k: f64,
    /// Contact distance re (sum of the two radii).
    pub re: f64,
}

central! { Billiard, |self, s, _, _| {
    if s.re() >= self.re * self.re {
        D::zero()
    } else {
        let d = s.sqrt() - self.re;
        d * d * (0.5 * self.k)
    }
}, cutoff: |self| Some(self.re) }

/// Lennard-Jones U = De [(re/r)¹² − 2 (re/r)⁶] (minimum −De at r = re). With a cutoff rc the potential
/// is truncated and shifted, U − U(rc) for r < rc and 0 beyond (continuous energy).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LennardJones {
    /// Dissociation energy De.
    pub de: f64,
    /// Equilibrium length re.
    pub re: f64,
    rc: Option<f64>,
    shift: f64,
}

impl LennardJones {
    /// Lennard-Jones without cutoff.
    pub fn new(de: f64, re: f64) -> Self {
        LennardJones {
            de,
            re,
            rc: None,
            shift: 0.0,
        }
    }

    /// Truncated and shifted at `rc` (use with [`ShortRange`](crate::ShortRange)).
    pub fn with_cutoff(de: f64, re: f64, rc: f64) -> Self {
        let s3 = (re * re / (rc * rc)).powi(3);
        LennardJones {
            de,
            re,
            rc: Some(rc),
            shift: de * (s3 * s3 - 2.0 * s3),
        }
    }
}

central! { LennardJones, |self, s, _, _| {
    if let Some(rc) = self.rc {
        if s.re() >= rc * rc {
            return D::zero();
        }
    }
    let s3 = (s.recip() * (self.re * self.re)).powi(3);
    (s3 * s3 - s3 * 2.0) * self.de - self.shift
}, cutoff: |self| self.rc }

/// The Gaussian coupling of the chains paper, U = k2 exp(−r² / (2σ²)) (repulsive for k2 > 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussianCoupling {
    /// Strength k2 (negative: attractive).
    pub k2: f64,
    /// Width σ.
    pub sigma: f64,
}

central! { GaussianCoupling, |self, s, _, _| (s * (-0.5 / (self.sigma * self.sigma))).exp() * self.k2 }

/// A central force of the power law f(r) = k rⁿ: F21 = f(r) r̂ (k > 0 repulsive). Given as a force, not a
/// potential, so it enters the Lagrangian as a generalized force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CentralForce {
    /// Strength k.
    pub k: f64,
    /// Exponent n.
    pub n: f64,
}

impl TwoBodyForce for CentralForce {
    #[inline]
    fn force<D: Scalar>(&self, _t: f64, by: Body<'_, D>, on: Body<'_, D>) -> [D; 3] {
        let r = [on.r[0] - by.r[0], on.r[1] - by.r[1], on.r[2] - by.r[2]];
        let d = r2(&r).sqrt();
        // f(r)/r = k r^(n − 1)
        let s = d.powf(self.n - 1.0) * self.k;
        [r[0] * s, r[1] * s, r[2] * s]
    }
}

/// A dashpot between two particles: the force on `on` is F = −c ((v_on − v_by)·r̂) r̂, r̂ the unit vector
/// from `by` to `on` (damps the rate of change of their distance only, c ≥ 0; a velocity-dependent
/// two-body force, so a generalized force).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dashpot {
    /// Damping coefficient c.
    pub c: f64,
}

impl TwoBodyForce for Dashpot {
    #[inline]
    fn force<D: Scalar>(&self, _t: f64, by: Body<'_, D>, on: Body<'_, D>) -> [D; 3] {
        let r = [on.r[0] - by.r[0], on.r[1] - by.r[1], on.r[2] - by.r[2]];
        let w = [on.v[0] - by.v[0], on.v[1] - by.v[1], on.v[2] - by.v[2]];
        // −c (w·r) r / |r|²
        let s = (w[0] * r[0] + w[1] * r[1] + w[2] * r[2]) / r2(&r) * (-self.c);
        [r[0] * s, r[1] * s, r[2] * s]
    }
}

/// Uniform gravity along −z: V = m g z, F = −m g ẑ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UniformGravity {
    /// Acceleration of gravity g (9.81 m/s² near the Earth's surface).
    pub g: f64,
}

impl OnePotential for UniformGravity {
    #[inline(always)]
    fn energy<D: Scalar>(&self, _t: f64, r: [D; 3], p: &Particle) -> D {
        r[2] * (p.mass * self.g)
    }
}

/// An on-site potential V = ½ k2 d² + ¼ k4 d⁴ with d = |r − c| (harmonic for k4 = 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trap {
    /// Quadratic stiffness k2.
    pub k2: f64,
    /// Quartic stiffness k4.
    pub k4: f64,
    /// Centre c.
    pub center: Vec3,
}

impl OnePotential for Trap {
    #[inline(always)]
    fn energy<D: Scalar>(&self, t: f64, r: [D; 3], p: &Particle) -> D {
        let c = self.center;
        self.radial(t, r2(&[r[0] - c[0], r[1] - c[1], r[2] - c[2]]), p)
    }
    fn center(&self) -> Option<Vec3> {
        Some(self.center)
    }
    #[inline(always)]
    fn radial<D: Scalar>(&self, _t: f64, s: D, _p: &Particle) -> D {
        s * (s * (0.25 * self.k4) + 0.5 * self.k2)
    }
}

/// A two-body potential whose particle 1 is a fixed point (the seed's `one_from_two`): a spring tied to
/// a wall is `FixedEnd::new(Spring { k, re }, wall)`. V(r) = U(r − anchor; anchor, p).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedEnd<P> {
    /// The two-body potential.
    pub potential: P,
    /// The fixed point (particle 1).
    pub anchor: Vec3,
    /// Parameters of the fixed particle (mass of a fixed attracting body, say).
    pub anchor_particle: Particle,
}

impl<P> FixedEnd<P> {
    /// `potential` with particle 1 fixed at `anchor` (unit mass, no charge).
    pub fn new(potential: P, anchor: Vec3) -> Self {
        FixedEnd {
            potential,
            anchor,
            anchor_particle: Particle::new(1.0),
        }
    }
}

impl<P: PairPotential> OnePotential for FixedEnd<P> {
    #[inline(always)]
    fn energy<D: Scalar>(&self, _t: f64, r: [D; 3], p: &Particle) -> D {
        let a = self.anchor;
        self.potential
            .energy([r[0] - a[0], r[1] - a[1], r[2] - a[2]], &self.anchor_particle, p)
    }
    fn center(&self) -> Option<Vec3> {
        P::RADIAL.then_some(self.anchor)
    }
    #[inline(always)]
    fn radial<D: Scalar>(&self, _t: f64, s: D, p: &Particle) -> D {
        self.potential.radial(s, &self.anchor_particle, p)
    }
}

/// Linear drag F = −b v (non-conservative: a generalized force).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearDrag {
    /// Drag coefficient b ≥ 0.
    pub b: f64,
}

impl OneBodyForce for LinearDrag {
    #[inline]
    fn force<D: Scalar>(&self, _t: f64, _r: [D; 3], v: [D; 3], _p: &Particle) -> [D; 3] {
        [v[0] * -self.b, v[1] * -self.b, v[2] * -self.b]
    }
}

/// The Lorentz force of uniform fields, F = e (E + v × B) (e the particle's charge): a velocity-dependent
/// force, so a generalized force (the magnetic part does no work).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lorentz {
    /// Electric field E.
    pub e: Vec3,
    /// Magnetic field B.
    pub b: Vec3,
}

impl OneBodyForce for Lorentz {
    #[inline]
    fn force<D: Scalar>(&self, _t: f64, _r: [D; 3], v: [D; 3], p: &Particle) -> [D; 3] {
        let (e, b, q) = (self.e, self.b, p.charge);
        [
            (v[1] * b[2] - v[2] * b[1] + e[0]) * q,
            (v[2] * b[0] - v[0] * b[2] + e[1]) * q,
            (v[0] * b[1] - v[1] * b[0] + e[2]) * q,
        ]
    }
}
