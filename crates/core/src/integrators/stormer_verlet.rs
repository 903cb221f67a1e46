//! Störmer-Verlet (leapfrog, kick-drift-kick) on a split system q̇ = D(v), v̇ = K(q), and its
//! symmetric compositions of orders 4, 6 and 8:
//!
//! ```text
//! V_h = K_{h/2} ∘ D_h ∘ K_{h/2},      K_c: v ← v + c K(q),   D_c: q ← q + c D(v),
//! Φ_h = V_{γ_s h} ∘ … ∘ V_{γ₁ h} = K_{a_s h} ∘ D_{γ_s h} ∘ … ∘ K_{a₁ h} ∘ D_{γ₁ h} ∘ K_{a₀ h},
//! ```
//!
//! with the [`Weights`] γ and the merged half kicks a₀ = γ₁/2, a_i = (γ_i + γ_{i+1})/2, a_s = γ_s/2.
//! The force at the end of a step is reused at the start of the next one when the state was not
//! changed in between, so a step costs s force evaluations. The one Störmer-Verlet of noether: the
//! named compositions ([`Composition::kahan_li8`], …) and particles' velocity Verlet are this base.

use super::symplectic::{SplitTangent, Work};
use super::{Composition, SignedStepper, SignedTangentStepper, Weights};
use crate::integrators::composition::{check_signed_step, step_forward, step_forward_tangent};
use crate::system::{LinearizedDynamics, SplitDynamics};
use crate::tangent::check_tangent_shape;
use crate::{Result, State, StepInfo, Stepper, TangentStepper};
use nalgebra::DMatrix;

/// Störmer-Verlet, kick-drift-kick, order 2: the base of the explicit symplectic compositions
/// ([`Composition::stormer_verlet`], [`Composition::kahan_li8`], …; see the [module](self) docs).
/// Symmetric and symplectic; steps of either sign.
pub struct StormerVerlet<S> {
    system: S,
    work: Work,
    cache_q: Vec<f64>,
    cache_f: Vec<f64>,
    cached: bool,
}

/// The merged kicks and drifts of the base alone (γ = [1]).
const ONE_KICKS: [f64; 2] = [0.5, 0.5];
const ONE_DRIFT: [f64; 1] = [1.0];

impl<S: SplitDynamics> StormerVerlet<S> {
    /// Störmer-Verlet for `system`.
    pub fn new(system: S) -> Self {
        let n = system.dof();
        StormerVerlet {
            system,
            work: Work::new(n),
            cache_q: vec![0.0; n],
            cache_f: vec![0.0; n],
            cached: false,
        }
    }

    /// The system stepped.
    pub fn system(&self) -> &S {
        &self.system
    }

    /// Φ_h with the kicks a₀..a_s and drifts γ₁..γ_s, the first force reused when the step starts
    /// where the last one ended; the state committed when every stage succeeded.
    fn kick_drift_kick(
        &mut self,
        (kicks, drifts): (&[f64], &[f64]),
        state: &mut State<S::Partner>,
        h: f64,
    ) -> Result<StepInfo> {
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
        self.run(kicks, drifts, h).map_err(|e| e.at_time(t))?;
        self.work.commit(state, h)?;
        self.cache_q.copy_from_slice(&self.work.q);
        self.cache_f.copy_from_slice(&self.work.f);
        self.cached = true;
        let evaluations = drifts.len() + usize::from(!reused);
        Ok(StepInfo::fixed(h).with_evaluations(evaluations))
    }

    /// The stages of one step on the work vectors: for up to 6 coordinates on arrays of that fixed
    /// length ([`run_fixed`](Self::run_fixed)), otherwise on the vectors.
    fn run(&mut self, kicks: &[f64], drifts: &[f64], h: f64) -> Result<()> {
        macro_rules! widths {
            ($($w:literal)*) => {
                match self.work.q.len() {
                    $($w => self.run_fixed::<$w>(kicks, drifts, h),)*
                    _ => self.run_any(kicks, drifts, h),
                }
            };
        }
        widths!(1 2 3 4 5 6)
    }

    /// [`run_any`](Self::run_any) with q, v and the force held in arrays of length W, the kick from
    /// [`SplitDynamics::kick_rate_fixed`]: the same operations in the same order (the same bits),
    /// but the whole stage stays in registers when the system's kernel inlines (Hénon-Heiles,
    /// Kahan-Li 8: 19.7 → 14.1 ns per stage, `--bench rates`, docs/benchmarks.md).
    fn run_fixed<const W: usize>(&mut self, kicks: &[f64], drifts: &[f64], h: f64) -> Result<()> {
        let w = &mut self.work;
        let (Ok(mut q), Ok(mut v), Ok(mut f)) = (
            <[f64; W]>::try_from(w.q.as_slice()),
            <[f64; W]>::try_from(w.v.as_slice()),
            <[f64; W]>::try_from(w.f.as_slice()),
        ) else {
            return self.run_any(kicks, drifts, h);
        };
        let identity = self.system.drift_is_identity();
        // An error returns at once (the step then leaves the state as it was): nothing of q, v or
        // the force lives on the error path, so they need not be kept in memory.
        for (a, b) in kicks.iter().zip(drifts) {
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
        let c = kicks[kicks.len() - 1] * h;
        (0..W).for_each(|i| v[i] += c * f[i]);
        w.q.copy_from_slice(&q);
        w.v.copy_from_slice(&v);
        w.f.copy_from_slice(&f);
        Ok(())
    }

    fn run_any(&mut self, kicks: &[f64], drifts: &[f64], h: f64) -> Result<()> {
        let w = &mut self.work;
        for (a, b) in kicks.iter().zip(drifts) {
            w.kick(a * h);
            w.drift(&self.system, b * h)?;
            self.system.kick_rate(&w.q, &mut w.f)?;
        }
        w.kick(kicks[kicks.len() - 1] * h);
        Ok(())
    }
}

impl<S: SplitDynamics> Stepper for StormerVerlet<S> {
    type Partner = S::Partner;
    fn step(&mut self, state: &mut State<S::Partner>, h: f64) -> Result<StepInfo> {
        step_forward(self, state, h)
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
        2
    }
    fn name(&self) -> &'static str {
        "Störmer-Verlet"
    }
}

/// Kick-drift-kick with the half kicks of adjacent substeps merged (the same bits as the substeps
/// written out with merged kicks, s force evaluations per step).
impl<S: SplitDynamics> SignedStepper for StormerVerlet<S> {
    fn step_signed(&mut self, state: &mut State<S::Partner>, h: f64) -> Result<StepInfo> {
        check_signed_step(self.system.dof(), state, h)?;
        self.kick_drift_kick((&ONE_KICKS, &ONE_DRIFT), state, h)
    }
    fn step_composed(
        &mut self,
        weights: &Weights,
        state: &mut State<S::Partner>,
        h: f64,
    ) -> Result<StepInfo> {
        self.kick_drift_kick((weights.kicks(), weights.as_slice()), state, h)
    }
}

impl<S: SplitDynamics + LinearizedDynamics> StormerVerlet<S> {
    /// The step with the kicks and drifts given, then Ψ by replaying them from the start
    /// (`SplitTangent`); the state is committed when both succeed.
    fn kick_drift_kick_tangent(
        &mut self,
        (kicks, drifts): (&[f64], &[f64]),
        state: &mut State<S::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        check_tangent_shape(psi, self.system.dof())?;
        let mut next = state.clone();
        let info = self.kick_drift_kick((kicks, drifts), &mut next, h)?;
        let mut w = SplitTangent::new(&self.system, state);
        for (a, b) in kicks.iter().zip(drifts) {
            w.kick(a * h)?;
            w.drift(b * h)?;
        }
        w.kick(kicks[kicks.len() - 1] * h)?;
        w.finish(psi)?;
        *state = next;
        Ok(info)
    }
}

/// Ψ of a composition of Störmer-Verlet steps: the product of the kick and drift Jacobians in the
/// order the step applies them (K_{a₀h}, D_{γ₁h}, K_{a₁h}, …, D_{γ_s h}, K_{a_s h}), each at the
/// point where the step evaluates it. For a [`SeparableHamiltonian`](crate::SeparableHamiltonian)
/// every factor is symplectic, so det Ψ = 1 to rounding. Needs `S: LinearizedDynamics` (second
/// derivatives; a separable Hamiltonian and a natural system are both).
impl<S: SplitDynamics + LinearizedDynamics> SignedTangentStepper for StormerVerlet<S> {
    fn step_signed_tangent(
        &mut self,
        state: &mut State<S::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        check_signed_step(self.system.dof(), state, h)?;
        self.kick_drift_kick_tangent((&ONE_KICKS, &ONE_DRIFT), state, h, psi)
    }
    fn step_composed_tangent(
        &mut self,
        weights: &Weights,
        state: &mut State<S::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        self.kick_drift_kick_tangent((weights.kicks(), weights.as_slice()), state, h, psi)
    }
}

impl<S: SplitDynamics + LinearizedDynamics> TangentStepper for StormerVerlet<S> {
    fn step_tangent(
        &mut self,
        state: &mut State<S::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        step_forward_tangent(self, state, h, psi)
    }
}

/// The named explicit symplectic compositions of Störmer-Verlet on a split system.
impl<S: SplitDynamics> Composition<StormerVerlet<S>> {
    /// Störmer-Verlet / leapfrog (kick-drift-kick), order 2.
    pub fn stormer_verlet(system: S) -> Self {
        Self::new(StormerVerlet::new(system), Weights::stormer_verlet())
    }
    /// Yoshida's triple jump, order 4, 3 stages ([`Weights::yoshida4`]).
    pub fn yoshida4(system: S) -> Self {
        Self::new(StormerVerlet::new(system), Weights::yoshida4())
    }
    /// Suzuki's fractal, order 4, 5 stages ([`Weights::suzuki4`]).
    pub fn suzuki4(system: S) -> Self {
        Self::new(StormerVerlet::new(system), Weights::suzuki4())
    }
    /// Yoshida (1990), order 6, 7 stages ([`Weights::yoshida6`]).
    pub fn yoshida6(system: S) -> Self {
        Self::new(StormerVerlet::new(system), Weights::yoshida6())
    }
    /// Kahan-Li (1997), order 6, 9 stages ([`Weights::kahan_li6`]).
    pub fn kahan_li6(system: S) -> Self {
        Self::new(StormerVerlet::new(system), Weights::kahan_li6())
    }
    /// Kahan-Li (1997), order 8, 17 stages ([`Weights::kahan_li8`]).
    pub fn kahan_li8(system: S) -> Self {
        Self::new(StormerVerlet::new(system), Weights::kahan_li8())
    }
    /// The system stepped.
    pub fn system(&self) -> &S {
        self.base().system()
    }
}
