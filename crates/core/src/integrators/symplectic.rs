//! Explicit symplectic methods for separable systems: symplectic Euler, Störmer-Verlet and symmetric
//! compositions of Verlet of orders 4, 6 and 8.
//!
//! They need the vector field split as q̇ = D(v) (depending on v only) and v̇ = K(q) (depending on q
//! only): the [`SplitDynamics`] trait. Two kinds of systems provide it:
//! - `SeparableHamiltonian(s)` for any [`Separable`] H = T(p) + V(q): state **(q, p)**,
//!   D(p) = ∇T(p), K(q) = −∇V(q);
//! - [`Natural`] L = ½ q̇ᵀ M q̇ − V(q) with constant M: state **(q, q̇)**, D(q̇) = q̇,
//!   K(q) = −M⁻¹∇V(q) (M factored once). This is the same method as on (q, p = M q̇), written in
//!   velocities.
//!
//! All gradients come from dual numbers ([`ad::gradient`]); no Hessian is formed.
//! A general [`EulerLagrange`](crate::EulerLagrange) or [`HamiltonEquations`](crate::HamiltonEquations)
//! system is not split, so asking an explicit symplectic method to step it does not compile:
//!
//! ```compile_fail
//! use noether_core::prelude::*;
//! struct Top;
//! impl Hamiltonian for Top {
//!     fn dof(&self) -> usize { 1 }
//!     fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D { p[0] * p[0] * q[0].cos() }
//! }
//! let _ = Composition::stormer_verlet(HamiltonEquations::new(Top)); // not SplitDynamics
//! ```
//!
//! # References
//! - E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., Springer 2006,
//!   sections II.5 and V.3 (coefficients (3.9), (3.11), (3.12) of V.3.2).
//! - H. Yoshida, Construction of higher order symplectic integrators, Phys. Lett. A 150 (1990) 262.
//! - W. Kahan, R.-C. Li, Composition constants for raising the orders of unconventional schemes for
//!   ordinary differential equations, Math. Comp. 66 (1997) 1089.

use crate::ad::{self, Block, Field};
use crate::dynamics::{rate_by_slices, rates_by_slices};
use crate::error::{check_finite, check_len, check_result, check_step, check_time_resolution, finite_result};
use crate::integrators::LinearizedDynamics;
use crate::natural::{Natural, Potential};
use crate::tangent::{check_tangent_shape, step_then_tangent};
use crate::{
    Dynamics, Error, Partner, Result, Scalar, Separable, SeparableHamiltonian, State, StepInfo, Stepper,
    TangentStepper,
};
use nalgebra::DMatrix;
use std::ops::AddAssign;

/// A vector field split as q̇ = D(v), v̇ = K(q): what explicit symplectic methods need.
pub trait SplitDynamics: Dynamics {
    /// The drift rate q̇ = D(v) (a function of v alone).
    fn drift_rate(&self, v: &[f64], dq: &mut [f64]) -> Result<()>;
    /// The kick rate v̇ = K(q) (a function of q alone).
    fn kick_rate(&self, q: &[f64], dv: &mut [f64]) -> Result<()>;
    /// `true` when D(v) = v, so the drift needs no call.
    fn drift_is_identity(&self) -> bool {
        false
    }
    /// [`drift_rate`](Self::drift_rate) for exactly W coordinates, by value, and only when every
    /// value is finite (else an error): what the fixed-size loop of [`Composition`] calls when the
    /// drift is not the identity. The default forwards to `drift_rate` and checks;
    /// `SeparableHamiltonian` calls its fixed-width gradient of T directly.
    #[inline]
    fn drift_rate_fixed<const W: usize>(&self, v: [f64; W]) -> Result<[f64; W]>
    where
        Self: Sized,
    {
        rate_by_slices(v, "drift rate", |v, dq| self.drift_rate(v, dq))
    }
    /// [`kick_rate`](Self::kick_rate) for a system of exactly W coordinates, by value, and only when
    /// every value is finite (else an error, [`Error::NonFiniteResult`] when `kick_rate` gave none):
    /// what the fixed-size loops of [`Composition`] and [`Nystrom`](super::Nystrom) call for small
    /// systems. The default forwards to `kick_rate` and checks; [`Natural`] calls its fixed-width
    /// kernel directly, so that the model inlines into the loop, q, v and the force stay in
    /// registers, and one test covers the result.
    #[inline]
    fn kick_rate_fixed<const W: usize>(&self, q: [f64; W]) -> Result<[f64; W]>
    where
        Self: Sized,
    {
        rate_by_slices(q, "kick rate", |q, dv| self.kick_rate(q, dv))
    }
}

struct KineticField<'a, S: ?Sized>(&'a S);
impl<S: Separable + ?Sized> Field for KineticField<'_, S> {
    fn eval<D: Scalar>(&self, _t: D, _x: &[D], y: &[D]) -> D {
        self.0.kinetic(y)
    }
}
struct PotentialOf<'a, S: ?Sized>(&'a S);
impl<S: Separable + ?Sized> Field for PotentialOf<'_, S> {
    fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
        self.0.potential(x)
    }
}

/// T(x) as a field of the first block, for [`ad::gradient_exact`] (which differentiates that block).
struct KineticOfX<'a, S: ?Sized>(&'a S);
impl<S: Separable + ?Sized> Field for KineticOfX<'_, S> {
    fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
        self.0.kinetic(x)
    }
}

impl<S: Separable> SeparableHamiltonian<S> {
    /// ∇T(p) (given p) and −∇V(q) (given q) for exactly N = dof ≤ [`ad::MAX_FIXED`] degrees of
    /// freedom, one fixed-width gradient each with every length a constant (the model inlines), zeros
    /// for the half not asked for; `None` when N does not fit or T + V + Σ 0·(rates, q, p) is not
    /// finite, for the general path to name the error.
    #[inline(always)]
    fn rates_fast<const N: usize>(
        &self,
        q: Option<&[f64; N]>,
        p: Option<&[f64; N]>,
    ) -> Option<([f64; N], [f64; N])> {
        if N != self.0.dof() || N > ad::MAX_FIXED {
            return None;
        }
        let (mut dq, mut dp, mut check) = ([0.0; N], [0.0; N], 0.0);
        // q and p enter the test too: T or V need not depend on all of them (the general path
        // checks its input).
        if let Some(p) = p {
            check += ad::gradient_exact(&KineticOfX(&self.0), 0.0, p, &mut dq);
            check = p.iter().fold(check, |c, x| c + x * 0.0);
        }
        if let Some(q) = q {
            check += ad::gradient_exact(&PotentialOf(&self.0), 0.0, q, &mut dp);
            dp = dp.map(|x| -x);
            check = q.iter().fold(check, |c, x| c + x * 0.0);
        }
        let check = dq.iter().chain(&dp).fold(check, |c, x| c + x * 0.0);
        check.is_finite().then_some((dq, dp))
    }

    /// The general path of the fixed-size rates, out of their way.
    #[cold]
    #[inline(never)]
    fn rates_cold<const N: usize>(&self, t: f64, q: [f64; N], p: [f64; N]) -> Result<([f64; N], [f64; N])> {
        rates_by_slices(self, t, q, p)
    }
}

/// Ok when the gradient `out` and the value it was taken of are finite (where T or V is infinite
/// there is no rate to return).
fn finite_or(value: f64, out: &[f64]) -> Result<()> {
    finite_result("forces", f64::NAN, value).and_then(|_| check_result("forces", f64::NAN, out))
}

/// State (q, p): q̇ = ∇T(p), ṗ = −∇V(q).
impl<S: Separable> Dynamics for SeparableHamiltonian<S> {
    type Partner = crate::Momenta;
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn rates(&self, t: f64, q: &[f64], p: &[f64], dq: &mut [f64], dp: &mut [f64]) -> Result<()> {
        check_len("p", p, self.0.dof())?;
        check_finite("q", q)?;
        check_finite("p", p)?;
        self.drift_rate(p, dq)
            .and_then(|_| self.kick_rate(q, dp))
            .map_err(|e| e.at_time(t))
    }
    fn energy(&self, _t: f64, q: &[f64], p: &[f64]) -> Result<f64> {
        let n = self.0.dof();
        check_len("q", q, n)?;
        check_len("p", p, n)?;
        Ok(self.0.kinetic(p) + self.0.potential(q))
    }
    fn position_rates(&self, t: f64, _q: &[f64], p: &[f64], dq: &mut [f64]) -> Result<()> {
        self.drift_rate(p, dq).map_err(|e| e.at_time(t))
    }
    /// ∇T(p) and −∇V(q) by fixed-width kernels called directly (the same values and errors as
    /// [`rates`](Dynamics::rates)).
    #[inline(always)]
    fn rates_fixed<const N: usize>(&self, t: f64, q: [f64; N], p: [f64; N]) -> Result<([f64; N], [f64; N])> {
        match self.rates_fast(Some(&q), Some(&p)) {
            Some(r) => Ok(r),
            None => self.rates_cold(t, q, p),
        }
    }
}

impl<S: Separable> SplitDynamics for SeparableHamiltonian<S> {
    fn drift_rate(&self, p: &[f64], dq: &mut [f64]) -> Result<()> {
        check_len("p", p, self.0.dof())?;
        check_len("q̇ (output)", dq, self.0.dof())?;
        let value = ad::gradient(&KineticField(&self.0), 0.0, &[], p, Block::Y, dq);
        finite_or(value, dq)
    }
    fn kick_rate(&self, q: &[f64], dp: &mut [f64]) -> Result<()> {
        check_len("q", q, self.0.dof())?;
        check_len("ṗ (output)", dp, self.0.dof())?;
        let value = ad::gradient(&PotentialOf(&self.0), 0.0, q, &[], Block::X, dp);
        dp.iter_mut().for_each(|x| *x = -*x);
        finite_or(value, dp)
    }
    /// ∇T(p) by the fixed-width kernel called directly (the same values and errors as `drift_rate`).
    #[inline]
    fn drift_rate_fixed<const W: usize>(&self, p: [f64; W]) -> Result<[f64; W]> {
        match self.rates_fast(None, Some(&p)) {
            Some((dq, _)) => Ok(dq),
            None => {
                let mut dq = [0.0; W];
                self.drift_rate(&p, &mut dq)?;
                Ok(dq)
            }
        }
    }
    /// −∇V(q) by the fixed-width kernel called directly (the same values and errors as `kick_rate`).
    #[inline]
    fn kick_rate_fixed<const W: usize>(&self, q: [f64; W]) -> Result<[f64; W]> {
        match self.rates_fast(Some(&q), None) {
            Some((_, dp)) => Ok(dp),
            None => {
                let mut dp = [0.0; W];
                self.kick_rate(&q, &mut dp)?;
                Ok(dp)
            }
        }
    }
}

impl<P: Potential> SplitDynamics for Natural<P> {
    /// q̇ = v, checked (lengths, finite).
    fn drift_rate(&self, v: &[f64], dq: &mut [f64]) -> Result<()> {
        check_len("q̇", v, self.dof())?;
        check_len("q̇ (output)", dq, self.dof())?;
        check_finite("q̇", v)?;
        dq.copy_from_slice(v);
        Ok(())
    }
    #[inline]
    fn drift_rate_fixed<const W: usize>(&self, v: [f64; W]) -> Result<[f64; W]> {
        check_len("q̇", &v, self.dof())?;
        check_finite("q̇", &v)?;
        Ok(v)
    }
    #[inline]
    fn kick_rate(&self, q: &[f64], dv: &mut [f64]) -> Result<()> {
        self.accelerations(q, dv)
    }
    fn drift_is_identity(&self) -> bool {
        true
    }
    #[inline]
    fn kick_rate_fixed<const W: usize>(&self, q: [f64; W]) -> Result<[f64; W]> {
        self.accelerations_fixed(q)
    }
}

// `S: Sized` (no `&dyn SplitDynamics`): the fixed-size kick forwards to the system's own.
impl<S: SplitDynamics> SplitDynamics for &S {
    fn drift_rate(&self, v: &[f64], dq: &mut [f64]) -> Result<()> {
        (**self).drift_rate(v, dq)
    }
    fn kick_rate(&self, q: &[f64], dv: &mut [f64]) -> Result<()> {
        (**self).kick_rate(q, dv)
    }
    fn drift_is_identity(&self) -> bool {
        (**self).drift_is_identity()
    }
    #[inline]
    fn drift_rate_fixed<const W: usize>(&self, v: [f64; W]) -> Result<[f64; W]> {
        (**self).drift_rate_fixed(v)
    }
    #[inline]
    fn kick_rate_fixed<const W: usize>(&self, q: [f64; W]) -> Result<[f64; W]> {
        (**self).kick_rate_fixed(q)
    }
}

fn check_state<K: Partner>(state: &State<K>, n: usize) -> Result<()> {
    state.validate(n)
}

/// Work buffers shared by the split methods.
struct Work {
    q: Vec<f64>,
    v: Vec<f64>,
    f: Vec<f64>,
    dq: Vec<f64>,
}

impl Work {
    fn new(n: usize) -> Self {
        Work {
            q: vec![0.0; n],
            v: vec![0.0; n],
            f: vec![0.0; n],
            dq: vec![0.0; n],
        }
    }
    fn drift<S: SplitDynamics>(&mut self, system: &S, c: f64) -> Result<()> {
        if system.drift_is_identity() {
            self.q.iter_mut().zip(&self.v).for_each(|(q, v)| *q += c * v);
        } else {
            system.drift_rate(&self.v, &mut self.dq)?;
            self.q.iter_mut().zip(&self.dq).for_each(|(q, d)| *q += c * d);
        }
        Ok(())
    }
    fn kick(&mut self, c: f64) {
        self.v.iter_mut().zip(&self.f).for_each(|(v, f)| *v += c * f);
    }
    fn commit<K: Partner>(&self, state: &mut State<K>, h: f64) -> Result<()> {
        if self.q.iter().chain(&self.v).any(|x| !x.is_finite()) {
            return Err(Error::NonFiniteResult {
                what: "state after the step",
                t: state.t,
                component: None,
            });
        }
        state.q.as_mut_slice().copy_from_slice(&self.q);
        state.v.as_mut_slice().copy_from_slice(&self.v);
        state.t += h;
        Ok(())
    }
}

/// Symplectic Euler, order 1: v_{n+1} = v_n + h K(q_n), q_{n+1} = q_n + h D(v_{n+1}).
///
/// On a [`Natural`] system this is the Euler-Cromer method. One force evaluation per step.
pub struct SymplecticEuler<S> {
    system: S,
    work: Work,
}

impl<S: SplitDynamics> SymplecticEuler<S> {
    /// Symplectic Euler for `system`.
    pub fn new(system: S) -> Self {
        let n = system.dof();
        SymplecticEuler {
            system,
            work: Work::new(n),
        }
    }
    /// The system stepped.
    pub fn system(&self) -> &S {
        &self.system
    }
}

impl<S: SplitDynamics> Stepper for SymplecticEuler<S> {
    type Partner = S::Partner;
    fn step(&mut self, state: &mut State<S::Partner>, h: f64) -> Result<StepInfo> {
        check_step(h)?;
        check_state(state, self.system.dof())?;
        check_time_resolution(state.t, h)?;
        let t = state.t;
        let w = &mut self.work;
        w.q.copy_from_slice(state.q.as_slice());
        w.v.copy_from_slice(state.v.as_slice());
        let run = |w: &mut Work| -> Result<()> {
            self.system.kick_rate(&w.q, &mut w.f)?;
            w.kick(h);
            w.drift(&self.system, h)
        };
        run(w).map_err(|e| e.at_time(t))?;
        w.commit(state, h)?;
        Ok(StepInfo::fixed(h).with_evaluations(1))
    }
    fn rates(&self, state: &State<S::Partner>, dq: &mut [f64], dv: &mut [f64]) -> Option<Result<()>> {
        Some(
            self.system
                .rates(state.t, state.q.as_slice(), state.v.as_slice(), dq, dv),
        )
    }
    fn dof(&self) -> usize {
        self.system.dof()
    }
    fn order(&self) -> u32 {
        1
    }
    fn name(&self) -> &'static str {
        "symplectic Euler"
    }
}

/// Störmer-Verlet (γ = [1], order 2), Yoshida's triple jump (order 4).
fn yoshida4() -> Vec<f64> {
    let c = 2f64.powf(1.0 / 3.0);
    let g1 = 1.0 / (2.0 - c);
    vec![g1, -c * g1, g1]
}

/// Suzuki's fractal (order 4, 5 stages): γ₁ = γ₂ = γ₄ = γ₅ = 1/(4 − 4^{1/3}), γ₃ = 1 − 4γ₁.
fn suzuki4() -> Vec<f64> {
    let g = 1.0 / (4.0 - 4f64.powf(1.0 / 3.0));
    vec![g, g, 1.0 - 4.0 * g, g, g]
}

/// Mirrors the first half of a symmetric scheme and sets the middle coefficient to 1 − 2Σ(others), so
/// that Σγ = 1 holds to rounding (the published middle value agrees to ~1e-16).
fn symmetric(half: &[f64]) -> Vec<f64> {
    let mid = 1.0 - 2.0 * half.iter().sum::<f64>();
    let mut g = half.to_vec();
    g.push(mid);
    g.extend(half.iter().rev());
    g
}

/// Yoshida (1990) order 6, 7 stages (HLW (V.3.11)); middle 1.31518632068391121888424973.
#[allow(clippy::excessive_precision)] // the published digits, kept verbatim
const YOSHIDA6: [f64; 3] = [
    0.784_513_610_477_557_263_819_497_63,
    0.235_573_213_359_358_133_684_793_18,
    -1.177_679_984_178_871_006_946_415_68,
];

/// Kahan-Li (1997) s9odr6a, order 6, 9 stages (HLW (V.3.12)); middle 0.79854399093482996339895035.
#[allow(clippy::excessive_precision)] // the published digits, kept verbatim
const KAHAN_LI6: [f64; 4] = [
    0.392_161_444_007_314_139_279_250_56,
    0.332_599_136_789_359_438_599_748_64,
    -0.706_246_172_557_639_359_809_964_82,
    0.082_213_596_293_550_800_231_490_45,
];

/// Kahan-Li (1997) s17odr8a, order 8, 17 stages (HLW (V.3.14)); middle −0.60550853383003451169892108.
#[allow(clippy::excessive_precision)] // the published digits, kept verbatim
const KAHAN_LI8: [f64; 8] = [
    0.130_202_483_088_890_080_878_817_63,
    0.561_162_981_775_108_384_561_964_41,
    -0.389_474_962_644_847_286_408_078_60,
    0.158_841_906_555_155_600_896_210_75,
    -0.395_903_894_133_237_577_336_231_54,
    0.184_539_640_978_315_707_091_832_54,
    0.258_374_387_686_322_047_293_979_11,
    0.295_011_723_609_310_298_870_966_24,
];

/// Symmetric composition of Störmer-Verlet (kick-drift-kick) steps with sizes γ₁h, …, γ_s h:
///
/// Φ_h = V_{γ_s h} ∘ … ∘ V_{γ₁ h},   V_h = K_{h/2} ∘ D_h ∘ K_{h/2},
///
/// where K_c: v ← v + c K(q) and D_c: q ← q + c D(v). Adjacent half kicks are merged, and the force at
/// the end of a step is reused at the start of the next one when the state was not changed in between,
/// so a step costs s force evaluations. Symmetric coefficients (γ_i = γ_{s+1−i}) with Σγ = 1 give a
/// symmetric, symplectic method of even order.
pub struct Composition<S> {
    system: S,
    name: &'static str,
    order: u32,
    /// Kick coefficients a_0..a_s and drift coefficients b_1..b_s.
    kicks: Vec<f64>,
    drifts: Vec<f64>,
    work: Work,
    cache_q: Vec<f64>,
    cache_f: Vec<f64>,
    cached: bool,
}

impl<S: SplitDynamics> Composition<S> {
    fn build(system: S, gammas: Vec<f64>, order: u32, name: &'static str) -> Self {
        let n = system.dof();
        let s = gammas.len();
        let mut kicks = vec![0.0; s + 1];
        for (i, g) in gammas.iter().enumerate() {
            kicks[i] += 0.5 * g;
            kicks[i + 1] += 0.5 * g;
        }
        Composition {
            system,
            name,
            order,
            kicks,
            drifts: gammas,
            work: Work::new(n),
            cache_q: vec![0.0; n],
            cache_f: vec![0.0; n],
            cached: false,
        }
    }

    /// Störmer-Verlet / leapfrog (kick-drift-kick), order 2.
    pub fn stormer_verlet(system: S) -> Self {
        Self::build(system, vec![1.0], 2, "Störmer-Verlet")
    }
    /// Yoshida's triple jump, order 4, 3 stages: γ₁ = γ₃ = 1/(2 − 2^{1/3}), γ₂ = 1 − 2γ₁.
    pub fn yoshida4(system: S) -> Self {
        Self::build(system, yoshida4(), 4, "Yoshida 4 (triple jump)")
    }
    /// Suzuki's fractal, order 4, 5 stages (smaller error constant than the triple jump).
    pub fn suzuki4(system: S) -> Self {
        Self::build(system, suzuki4(), 4, "Suzuki 4 (5 stages)")
    }
    /// Yoshida (1990), order 6, 7 stages.
    pub fn yoshida6(system: S) -> Self {
        Self::build(system, symmetric(&YOSHIDA6), 6, "Yoshida 6 (7 stages)")
    }
    /// Kahan-Li (1997), order 6, 9 stages.
    pub fn kahan_li6(system: S) -> Self {
        Self::build(system, symmetric(&KAHAN_LI6), 6, "Kahan-Li 6 (9 stages)")
    }
    /// Kahan-Li (1997), order 8, 17 stages.
    pub fn kahan_li8(system: S) -> Self {
        Self::build(system, symmetric(&KAHAN_LI8), 8, "Kahan-Li 8 (17 stages)")
    }

    /// A custom symmetric composition of Verlet with step fractions `gammas` of nominal order `order`.
    /// The coefficients must be finite, symmetric and sum to 1 (to 1e-14).
    pub fn with_coefficients(system: S, gammas: &[f64], order: u32) -> Result<Self> {
        check_finite("composition coefficients", gammas)?;
        let sum: f64 = gammas.iter().sum();
        if gammas.is_empty() || (sum - 1.0).abs() > 1e-14 {
            return Err(Error::InvalidParameter {
                name: "sum of composition coefficients",
                value: sum,
                reason: "the coefficients must sum to 1",
            });
        }
        let s = gammas.len();
        if let Some(i) = (0..s).find(|&i| (gammas[i] - gammas[s - 1 - i]).abs() > 1e-15) {
            return Err(Error::InvalidParameter {
                name: "composition coefficient",
                value: gammas[i],
                reason: "the coefficients must be symmetric (γ_i = γ_{s+1−i})",
            });
        }
        Ok(Self::build(system, gammas.to_vec(), order, "custom composition"))
    }

    /// The Verlet step fractions γ₁, …, γ_s.
    pub fn coefficients(&self) -> &[f64] {
        &self.drifts
    }

    /// The system stepped.
    pub fn system(&self) -> &S {
        &self.system
    }

    /// The stages of one step on the work vectors: for up to 6 coordinates on arrays of that fixed
    /// length ([`run_fixed`](Self::run_fixed)), otherwise on the vectors.
    fn run(&mut self, h: f64) -> Result<()> {
        macro_rules! widths {
            ($($w:literal)*) => {
                match self.work.q.len() {
                    $($w => self.run_fixed::<$w>(h),)*
                    _ => self.run_any(h),
                }
            };
        }
        widths!(1 2 3 4 5 6)
    }

    /// [`run_any`](Self::run_any) with q, v and the force held in arrays of length W, the kick from
    /// [`SplitDynamics::kick_rate_fixed`]: the same operations in the same order (the same bits),
    /// but the whole stage stays in registers when the system's kernel inlines (Hénon-Heiles,
    /// Kahan-Li 8: 19.7 → 14.1 ns per stage, `--bench rates`, docs/benchmarks.md).
    fn run_fixed<const W: usize>(&mut self, h: f64) -> Result<()> {
        let w = &mut self.work;
        let (Ok(mut q), Ok(mut v), Ok(mut f)) = (
            <[f64; W]>::try_from(w.q.as_slice()),
            <[f64; W]>::try_from(w.v.as_slice()),
            <[f64; W]>::try_from(w.f.as_slice()),
        ) else {
            return self.run_any(h);
        };
        let identity = self.system.drift_is_identity();
        // An error returns at once (the step then leaves the state as it was): nothing of q, v or
        // the force lives on the error path, so they need not be kept in memory.
        for (a, b) in self.kicks.iter().zip(&self.drifts) {
            let c = a * h;
            (0..W).for_each(|i| v[i] += c * f[i]);
            let c = b * h;
            if identity {
                (0..W).for_each(|i| q[i] += c * v[i]);
            } else {
                let dq = self.system.drift_rate_fixed(v)?;
                (0..W).for_each(|i| q[i] += c * dq[i]);
            }
            f = self.system.kick_rate_fixed(q)?;
        }
        let c = self.kicks[self.kicks.len() - 1] * h;
        (0..W).for_each(|i| v[i] += c * f[i]);
        w.q.copy_from_slice(&q);
        w.v.copy_from_slice(&v);
        w.f.copy_from_slice(&f);
        Ok(())
    }

    fn run_any(&mut self, h: f64) -> Result<()> {
        let w = &mut self.work;
        for (a, b) in self.kicks.iter().zip(&self.drifts) {
            w.kick(a * h);
            w.drift(&self.system, b * h)?;
            self.system.kick_rate(&w.q, &mut w.f)?;
        }
        w.kick(self.kicks[self.kicks.len() - 1] * h);
        Ok(())
    }
}

impl<S: SplitDynamics> Stepper for Composition<S> {
    type Partner = S::Partner;
    fn step(&mut self, state: &mut State<S::Partner>, h: f64) -> Result<StepInfo> {
        check_step(h)?;
        check_state(state, self.system.dof())?;
        check_time_resolution(state.t, h)?;
        let t = state.t;
        self.work.q.copy_from_slice(state.q.as_slice());
        self.work.v.copy_from_slice(state.v.as_slice());
        let reused = self.cached && self.cache_q == self.work.q;
        if reused {
            self.work.f.copy_from_slice(&self.cache_f);
        } else {
            self.cached = false;
            self.system
                .kick_rate(&self.work.q, &mut self.work.f)
                .map_err(|e| e.at_time(t))?;
        }
        self.run(h).map_err(|e| e.at_time(t))?;
        self.work.commit(state, h)?;
        self.cache_q.copy_from_slice(&self.work.q);
        self.cache_f.copy_from_slice(&self.work.f);
        self.cached = true;
        let kicks = self.drifts.len() + usize::from(!reused);
        Ok(StepInfo::fixed(h).with_evaluations(kicks))
    }
    fn rates(&self, state: &State<S::Partner>, dq: &mut [f64], dv: &mut [f64]) -> Option<Result<()>> {
        Some(
            self.system
                .rates(state.t, state.q.as_slice(), state.v.as_slice(), dq, dv),
        )
    }
    fn dof(&self) -> usize {
        self.system.dof()
    }
    fn order(&self) -> u32 {
        self.order
    }
    fn name(&self) -> &'static str {
        self.name
    }
}

/// The replay of a split method's kicks and drifts from (t, q₀, v₀), carrying Ψ along:
///
/// ```text
/// kick  K_c: v ← v + c K(q),  Ψ ← [[I, 0], [c ∂K/∂q(q), I]] Ψ   at the current q;
/// drift D_c: q ← q + c D(v),  Ψ ← [[I, c ∂D/∂v(v)], [0, I]] Ψ   at the current v,
/// ```
///
/// the blocks ∂K/∂q and ∂D/∂v taken from J = [[0, ∂D/∂v], [∂K/∂q, 0]] of [`LinearizedDynamics`]
/// (for H = T(p) + V(q): ∂D/∂p = ∇²T, ∂K/∂q = −∇²V; on a natural system ∂D/∂v = I needs no call).
struct SplitTangent<'a, S> {
    system: &'a S,
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    f: Vec<f64>,
    dq: Vec<f64>,
    jac: DMatrix<f64>,
    psi: DMatrix<f64>,
}

impl<'a, S: SplitDynamics + LinearizedDynamics> SplitTangent<'a, S> {
    fn new(system: &'a S, state: &State<S::Partner>) -> Self {
        let n = system.dof();
        SplitTangent {
            system,
            t: state.t,
            q: state.q.as_slice().to_vec(),
            v: state.v.as_slice().to_vec(),
            f: vec![0.0; n],
            dq: vec![0.0; n],
            jac: DMatrix::zeros(2 * n, 2 * n),
            psi: DMatrix::identity(2 * n, 2 * n),
        }
    }
    fn kick(&mut self, c: f64) -> Result<()> {
        let n = self.q.len();
        self.system.kick_rate(&self.q, &mut self.f)?;
        self.system.jacobian(self.t, &self.q, &self.v, &mut self.jac)?;
        let dv = self.jac.view((n, 0), (n, n)) * self.psi.rows(0, n) * c;
        self.psi.rows_mut(n, n).add_assign(&dv);
        self.v.iter_mut().zip(&self.f).for_each(|(v, f)| *v += c * f);
        Ok(())
    }
    fn drift(&mut self, c: f64) -> Result<()> {
        let n = self.q.len();
        if self.system.drift_is_identity() {
            let dq = self.psi.rows(n, n) * c;
            self.psi.rows_mut(0, n).add_assign(&dq);
            self.q.iter_mut().zip(&self.v).for_each(|(q, v)| *q += c * v);
        } else {
            self.system.drift_rate(&self.v, &mut self.dq)?;
            self.system.jacobian(self.t, &self.q, &self.v, &mut self.jac)?;
            let dq = self.jac.view((0, n), (n, n)) * self.psi.rows(n, n) * c;
            self.psi.rows_mut(0, n).add_assign(&dq);
            self.q.iter_mut().zip(&self.dq).for_each(|(q, d)| *q += c * d);
        }
        Ok(())
    }
    /// Ψ into `out` when finite.
    fn finish(self, out: &mut DMatrix<f64>) -> Result<()> {
        check_result("step Jacobian Ψ", self.t, self.psi.as_slice())?;
        out.copy_from(&self.psi);
        Ok(())
    }
}

/// Ψ of symplectic Euler, kick then drift: Ψ = [[I, h D_v(v₁)], [0, I]] [[I, 0], [h K_q(q₀), I]]
/// (see `SplitTangent` in the source for the blocks). Needs second derivatives: `S` must also be
/// [`LinearizedDynamics`] (a separable Hamiltonian and a natural system are both).
impl<S: SplitDynamics + LinearizedDynamics> TangentStepper for SymplecticEuler<S> {
    fn step_tangent(
        &mut self,
        state: &mut State<S::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        check_tangent_shape(psi, self.system.dof())?;
        step_then_tangent(self, state, h, |m, s, _| {
            let mut w = SplitTangent::new(&m.system, s);
            w.kick(h)?;
            w.drift(h)?;
            w.finish(psi)
        })
    }
}

/// Ψ of a composition of Störmer-Verlet steps: the product of the kick and drift Jacobians in the
/// order the step applies them (K_{a₀h}, D_{b₁h}, K_{a₁h}, …, D_{b_s h}, K_{a_s h}), each at the
/// point where the step evaluates it. For a [`SeparableHamiltonian`] every factor is symplectic, so
/// det Ψ = 1 to rounding. Needs `S: LinearizedDynamics` (as [`SymplecticEuler`]).
impl<S: SplitDynamics + LinearizedDynamics> TangentStepper for Composition<S> {
    fn step_tangent(
        &mut self,
        state: &mut State<S::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        check_tangent_shape(psi, self.system.dof())?;
        step_then_tangent(self, state, h, |m, s, _| {
            let mut w = SplitTangent::new(&m.system, s);
            for (a, b) in m.kicks.iter().zip(&m.drifts) {
                w.kick(a * h)?;
                w.drift(b * h)?;
            }
            w.kick(m.kicks[m.kicks.len() - 1] * h)?;
            w.finish(psi)
        })
    }
}
