//! Explicit symplectic methods for separable systems: symplectic Euler, Störmer-Verlet and symmetric
//! compositions of Verlet of orders 4, 6 and 8.
//!
//! They need the vector field split as q̇ = D(v) (depending on v only) and v̇ = K(q) (depending on q
//! only): the [`SplitDynamics`] trait. Two kinds of systems provide it:
//! - `SeparableHamiltonian(s)` for any [`Separable`](crate::Separable) H = T(p) + V(q): state **(q, p)**,
//!   D(p) = ∇T(p), K(q) = −∇V(q);
//! - [`Natural`](crate::Natural) L = ½ q̇ᵀ M q̇ − V(q) with constant M: state **(q, q̇)**, D(q̇) = q̇,
//!   K(q) = −M⁻¹∇V(q) (M factored once). This is the same method as on (q, p = M q̇), written in
//!   velocities.
//!
//! All gradients come from dual numbers ([`ad::gradient`](crate::ad::gradient)); no Hessian is formed.
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

use crate::error::{check_finite, check_result, check_step, check_time_resolution};
use crate::system::LinearizedDynamics;
use crate::tangent::{check_tangent_shape, step_then_tangent};
use crate::{Error, Partner, Result, State, StepInfo, Stepper, TangentStepper};
use nalgebra::DMatrix;
use std::ops::AddAssign;

/// Re-exported from [`system`](crate::system), where the system traits live.
pub use crate::system::SplitDynamics;

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
/// On a [`Natural`](crate::Natural) system this is the Euler-Cromer method. One force evaluation per step.
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
/// point where the step evaluates it. For a [`SeparableHamiltonian`](crate::SeparableHamiltonian)
/// every factor is symplectic, so det Ψ = 1 to rounding. Needs `S: LinearizedDynamics` (as
/// [`SymplecticEuler`]).
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
