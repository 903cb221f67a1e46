//! Impulsive motion: Lagrange's equations across an instant (a blow, a catch, an impact).
//!
//! Integrate Lagrange's equations d/dt(∂L/∂q̇) − ∂L/∂q = Q over an interval of length τ → 0 in which
//! large forces F_i act at the points r_i(t, q). The positions do not move, finite forces give nothing,
//! and what is left is a jump of the momenta by the generalized impulse:
//!
//! ```text
//! p(t, q, q̇⁺) − p(t, q, q̇⁻) = Ĝ + Φ_qᵀ λ̂,        Ĝ_j = Σ_i F̂_i · ∂r_i/∂q_j,   F̂_i = ∫ F_i dt,
//! Φ_q q̇⁺ + φ_t = −e (Φ_q q̇⁻ + φ_t),
//! ```
//!
//! (Desloge, ch. 57). The second line is the impact law of the constraints φ(t, q) that act during the
//! instant, with their impulsive reactions λ̂: a point suddenly fixed or caught (e = 0, its velocity
//! is zero after the catch), a rebound from a wall (φ the distance to it, restitution coefficient
//! 0 ≤ e ≤ 1; e = 1 keeps the kinetic energy). Constraints that are already in force before and after
//! the instant belong in the same set with e = 0 (their velocity residual is zero on both sides).
//!
//! The unknowns (q̇⁺, λ̂) solve these n + m equations by core's Newton, with the Jacobian
//! [M(q, q̇⁺) −Φ_qᵀ; Φ_q 0] from dual numbers (M = ∂²L/∂q̇²). For a Lagrangian quadratic in q̇ (every
//! mechanical system) the equations are linear and one Newton step solves them; any regular L works.
//!
//! Use it as the action of a driver event: [`Event::try_reset`](noether_core::Event::try_reset) with
//! [`Impact::apply`] stops at the event, jumps the velocities and goes on.
//!
//! ```
//! use noether_constraints::prelude::*;
//! use noether_constraints::impulse::{Impact, StruckPoints};
//!
//! /// A uniform rod (mass m, length l) free in the plane: centre (x, y), angle θ.
//! struct Rod { m: f64, l: f64 }
//! impl Lagrangian for Rod {
//!     fn dof(&self) -> usize { 3 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, _q: &[D], v: &[D]) -> D {
//!         let i = self.m * self.l * self.l / 12.0;
//!         (v[0] * v[0] + v[1] * v[1]) * (0.5 * self.m) + v[2] * v[2] * (0.5 * i)
//!     }
//! }
//! /// The end of the rod at (x + l/2 cos θ, y + l/2 sin θ).
//! struct End { l: f64 }
//! impl StruckPoints for End {
//!     fn dof(&self) -> usize { 3 }
//!     fn dim(&self) -> usize { 2 }
//!     fn positions<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
//!         out[0] = q[0] + q[2].cos() * (0.5 * self.l);
//!         out[1] = q[1] + q[2].sin() * (0.5 * self.l);
//!     }
//! }
//! // A blow J across the end of a rod at rest along x: the centre moves at J/m, the rod turns at
//! // 6J/(m l) (the impulse's moment J l/2 over m l²/12).
//! let (m, l, j) = (2.0, 1.5, 0.3);
//! let rod = EulerLagrange::new(Rod { m, l });
//! let end = End { l };
//! let impulse = Impact::new(&rod).blow(&end, &[0.0, j])?;
//! let after = impulse.velocities(0.0, &[0.0, 0.0, 0.0], &[0.0, 0.0, 0.0])?;
//! assert!((after.v[1] - j / m).abs() < 1e-15 && (after.v[2] - 6.0 * j / (m * l)).abs() < 1e-15);
//! # Ok::<(), noether_constraints::Error>(())
//! ```

use crate::dynamics::rank_error;
use crate::holonomic::{jacobian_unchecked as jacobian, velocity_residual_unchecked as velocity_residual};
use crate::jets::{self, VectorField};
use crate::{Holonomic, Result};
use nalgebra::{DMatrix, DVector};
use noether_core::ad::Block;
use noether_core::error::{check_finite, check_len, check_result};
use noether_core::newton::{solve_dense, DenseProblem, Newton};
use noether_core::{EulerLagrange, Lagrangian, Scalar, State};

/// Points of a system where impulses act, r(t, q) stacked (`dim` numbers: 2 or 3 per point), written
/// as generic code like a Lagrangian.
pub trait StruckPoints {
    /// Number of coordinates n.
    fn dof(&self) -> usize;
    /// Length of the stacked positions.
    fn dim(&self) -> usize;
    /// r(t, q) into `out`.
    fn positions<D: Scalar>(&self, t: D, q: &[D], out: &mut [D]);
}

/// r(t, q) seen as a vector field of (t, x = q).
struct PointField<'a, P: ?Sized>(&'a P);

impl<P: StruckPoints + ?Sized> VectorField for PointField<'_, P> {
    fn outputs(&self) -> usize {
        self.0.dim()
    }
    fn eval<D: Scalar>(&self, t: D, x: &[D], _y: &[D], out: &mut [D]) {
        self.0.positions(t, x, out)
    }
}

/// The generalized impulse Ĝ_j = Σ_i F̂_i · ∂r_i/∂q_j of the impulses `impulses` (stacked like the
/// positions) applied at the points `points` at (t, q), into `out`: Ĝ = (∂r/∂q)ᵀ F̂ by dual numbers.
pub fn generalized_impulse<P: StruckPoints + ?Sized>(
    points: &P,
    t: f64,
    q: &[f64],
    impulses: &[f64],
    out: &mut [f64],
) -> Result<()> {
    let n = points.dof();
    check_len("q", q, n)?;
    check_len("impulses", impulses, points.dim())?;
    check_len("generalized impulse (output)", out, n)?;
    check_finite("q", q)?;
    check_finite("impulses", impulses)?;
    let mut j = DMatrix::zeros(points.dim(), n);
    jets::jacobian(&PointField(points), t, q, &[], Block::X, &mut j);
    let g = j.transpose() * DVector::from_column_slice(impulses);
    check_result("generalized impulse", t, g.as_slice())?;
    out.copy_from_slice(g.as_slice());
    Ok(())
}

/// The velocities just after an impulsive instant, with the impulsive reactions and the energy change.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct ImpactResult {
    /// q̇⁺.
    pub v: Vec<f64>,
    /// The impulsive reactions λ̂ of the constraints, one per constraint (Φ_qᵀ λ̂ is their generalized
    /// impulse).
    pub reactions: Vec<f64>,
    /// E(t, q, q̇⁺) − E(t, q, q̇⁻): the energy change (kinetic, as q does not move); ≤ 0 for a catch.
    pub energy_change: f64,
}

/// No constraints acting during the instant.
#[derive(Debug, Clone, Copy)]
pub struct Free(usize);

impl Holonomic for Free {
    fn dof(&self) -> usize {
        self.0
    }
    fn count(&self) -> usize {
        0
    }
    fn constraints<D: Scalar>(&self, _t: D, _q: &[D], _out: &mut [D]) {}
}

/// A blow: its generalized impulse at (t, q), into the last argument.
type Blow<'a> = Box<dyn Fn(f64, &[f64], &mut [f64]) -> Result<()> + 'a>;

/// An impulsive instant on a Lagrangian system (see the [module](self) docs): generalized impulses,
/// blows at points, and constraints that act during it with a coefficient of restitution.
pub struct Impact<'a, L, C> {
    lagrangian: &'a EulerLagrange<L>,
    impulse: Vec<f64>,
    blows: Vec<Blow<'a>>,
    constraints: C,
    restitution: f64,
}

impl<'a, L: Lagrangian> Impact<'a, L, Free> {
    /// No impulse and no constraint yet: add them with [`blow`](Self::blow),
    /// [`generalized`](Self::generalized) and [`constraints`](Self::constraints).
    pub fn new(lagrangian: &'a EulerLagrange<L>) -> Self {
        let n = lagrangian.dof();
        Impact {
            lagrangian,
            impulse: vec![0.0; n],
            blows: Vec::new(),
            constraints: Free(n),
            restitution: 0.0,
        }
    }
}

impl<'a, L: Lagrangian, C: Holonomic> Impact<'a, L, C> {
    fn check_dof(&self, what: &'static str, got: usize) -> Result<()> {
        if got != self.impulse.len() {
            return Err(noether_core::Error::Dimension {
                what,
                expected: self.impulse.len(),
                got,
            }
            .into());
        }
        Ok(())
    }

    /// Adds a generalized impulse Ĝ (n numbers).
    pub fn generalized(mut self, impulse: &[f64]) -> Result<Self> {
        check_len("generalized impulse", impulse, self.impulse.len())?;
        check_finite("generalized impulse", impulse)?;
        self.impulse.iter_mut().zip(impulse).for_each(|(g, x)| *g += x);
        Ok(self)
    }

    /// Adds the impulses F̂ (stacked like the positions) struck at `points`. Their generalized impulse
    /// (∂r/∂q)ᵀ F̂ is taken where the instant happens, at the state given to [`velocities`](Self::velocities).
    pub fn blow<P: StruckPoints + 'a>(mut self, points: &'a P, impulses: &[f64]) -> Result<Self> {
        self.check_dof("coordinates of the struck points", points.dof())?;
        check_len("impulses", impulses, points.dim())?;
        check_finite("impulses", impulses)?;
        let impulses = impulses.to_vec();
        self.blows.push(Box::new(move |t, q, out| {
            generalized_impulse(points, t, q, &impulses, out)
        }));
        Ok(self)
    }

    /// The constraints acting during the instant, with coefficient of restitution e ∈ [0, 1] (0: a
    /// catch, 1: an elastic rebound). Replaces the constraints given before.
    pub fn constraints<K: Holonomic>(self, constraints: K, restitution: f64) -> Result<Impact<'a, L, K>> {
        self.check_dof("coordinates of the impact constraints", constraints.dof())?;
        if !(0.0..=1.0).contains(&restitution) {
            return Err(noether_core::Error::InvalidParameter {
                name: "restitution",
                value: restitution,
                reason: "the coefficient of restitution lies in [0, 1]",
            }
            .into());
        }
        Ok(Impact {
            lagrangian: self.lagrangian,
            impulse: self.impulse,
            blows: self.blows,
            constraints,
            restitution,
        })
    }

    /// The velocities q̇⁺ after the instant at (t, q) for the velocities `v` = q̇⁻ before it, the
    /// impulsive reactions and the energy change. Errors: dimensions, non-finite input, redundant
    /// impact constraints ([`Error::RankDeficientConstraints`](crate::Error::RankDeficientConstraints)), a failed solve.
    pub fn velocities(&self, t: f64, q: &[f64], v: &[f64]) -> Result<ImpactResult> {
        let (n, m) = (self.impulse.len(), self.constraints.count());
        check_len("q", q, n)?;
        check_len("q̇", v, n)?;
        check_finite("q", q)?;
        check_finite("q̇", v)?;
        // Ĝ + p⁻: the momenta the new velocities must have before the reactions.
        let mut target = vec![0.0; n];
        self.lagrangian.momenta(t, q, v, &mut target)?;
        let mut g = vec![0.0; n];
        for (x, y) in target.iter_mut().zip(&self.impulse) {
            *x += y;
        }
        for blow in &self.blows {
            blow(t, q, &mut g)?;
            target.iter_mut().zip(&g).for_each(|(x, y)| *x += y);
        }
        // Φ_q and the velocity law Φ_q q̇⁺ = −φ_t − e (Φ_q q̇⁻ + φ_t).
        let mut phi_q = DMatrix::zeros(m, n);
        let mut law = vec![0.0; m];
        if m > 0 {
            jacobian(&self.constraints, t, q, &mut phi_q);
            check_result("impact constraint Jacobian", t, phi_q.as_slice())?;
            if let Some(e) = rank_error(&phi_q, t) {
                return Err(e);
            }
            let (mut before, mut phi_t) = (vec![0.0; m], vec![0.0; m]);
            velocity_residual(&self.constraints, t, q, v, &mut before);
            velocity_residual(&self.constraints, t, q, &vec![0.0; n], &mut phi_t);
            for k in 0..m {
                law[k] = -phi_t[k] - self.restitution * before[k];
            }
            check_result("impact velocity law", t, &law)?;
        }
        let problem = Jump {
            lagrangian: self.lagrangian,
            t,
            q,
            target: &target,
            phi_q: &phi_q,
            law: &law,
        };
        let mut x0 = v.to_vec();
        x0.resize(n + m, 0.0);
        let (x, _) = solve_dense(&Newton::default(), problem, &x0)?;
        let v_after = x.as_slice()[..n].to_vec();
        let energy_change = self.lagrangian.energy(t, q, &v_after)? - self.lagrangian.energy(t, q, v)?;
        Ok(ImpactResult {
            v: v_after,
            reactions: x.as_slice()[n..].to_vec(),
            energy_change,
        })
    }

    /// Applies the instant to `state` (its velocities jump; t and q stay): the action of a driver
    /// event, `Event::try_reset(|s| impact.apply(s).map(|_| ()))`. On an error `state` is unchanged.
    pub fn apply(&self, state: &mut State) -> noether_core::Result<ImpactResult> {
        let r = self
            .velocities(state.t, state.q.as_slice(), state.v.as_slice())
            .map_err(noether_core::Error::from)?;
        state.v.as_mut_slice().copy_from_slice(&r.v);
        Ok(r)
    }
}

/// The jump equations in x = (q̇⁺, λ̂): p(t, q, q̇⁺) − Φ_qᵀ λ̂ = p⁻ + Ĝ and Φ_q q̇⁺ = law.
struct Jump<'a, L> {
    lagrangian: &'a EulerLagrange<L>,
    t: f64,
    q: &'a [f64],
    target: &'a [f64],
    phi_q: &'a DMatrix<f64>,
    law: &'a [f64],
}

impl<L: Lagrangian> DenseProblem for Jump<'_, L> {
    fn dim(&self) -> usize {
        self.target.len() + self.law.len()
    }
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> noether_core::Result<()> {
        let n = self.target.len();
        let (v, lambda) = x.split_at(n);
        let (r1, r2) = r.split_at_mut(n);
        self.lagrangian.momenta(self.t, self.q, v, r1)?;
        let reaction = self.phi_q.transpose() * DVector::from_column_slice(lambda);
        for i in 0..n {
            r1[i] -= self.target[i] + reaction[i];
        }
        let constrained = self.phi_q * DVector::from_column_slice(v);
        for k in 0..self.law.len() {
            r2[k] = constrained[k] - self.law[k];
        }
        Ok(())
    }
    fn jacobian(&mut self, x: &[f64], j: &mut DMatrix<f64>) -> noether_core::Result<()> {
        let n = self.target.len();
        let m = self.law.len();
        let mass = self.lagrangian.mass_matrix(self.t, self.q, &x[..n])?;
        j.fill(0.0);
        j.view_mut((0, 0), (n, n)).copy_from(&mass);
        j.view_mut((0, n), (n, m)).copy_from(&(-self.phi_q.transpose()));
        j.view_mut((n, 0), (m, n)).copy_from(self.phi_q);
        Ok(())
    }
}
