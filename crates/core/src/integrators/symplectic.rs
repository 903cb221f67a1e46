//! Explicit symplectic methods for separable systems: symplectic Euler here, Störmer-Verlet and its
//! symmetric compositions of orders 4, 6 and 8 in [`stormer_verlet`](super::stormer_verlet) (weights in
//! [`weights`](super::weights)).
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
//! E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., Springer 2006,
//! sections II.5 and V.3.

use crate::error::{check_result, check_step, check_time_resolution};
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
pub(super) struct Work {
    pub(super) q: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) f: Vec<f64>,
    dq: Vec<f64>,
}

impl Work {
    pub(super) fn new(n: usize) -> Self {
        Work {
            q: vec![0.0; n],
            v: vec![0.0; n],
            f: vec![0.0; n],
            dq: vec![0.0; n],
        }
    }
    pub(super) fn drift<S: SplitDynamics>(&mut self, system: &S, c: f64) -> Result<()> {
        if system.drift_is_identity() {
            self.q.iter_mut().zip(&self.v).for_each(|(q, v)| *q += c * v);
        } else {
            system.drift_rate(&self.v, &mut self.dq)?;
            self.q.iter_mut().zip(&self.dq).for_each(|(q, d)| *q += c * d);
        }
        Ok(())
    }
    pub(super) fn kick(&mut self, c: f64) {
        self.v.iter_mut().zip(&self.f).for_each(|(v, f)| *v += c * f);
    }
    pub(super) fn commit<K: Partner>(&self, state: &mut State<K>, h: f64) -> Result<()> {
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

/// The replay of a split method's kicks and drifts from (t, q₀, v₀), carrying Ψ along:
///
/// ```text
/// kick  K_c: v ← v + c K(q),  Ψ ← [[I, 0], [c ∂K/∂q(q), I]] Ψ   at the current q;
/// drift D_c: q ← q + c D(v),  Ψ ← [[I, c ∂D/∂v(v)], [0, I]] Ψ   at the current v,
/// ```
///
/// the blocks ∂K/∂q and ∂D/∂v of J = [[0, ∂D/∂v], [∂K/∂q, 0]], each asked of [`LinearizedDynamics`]
/// alone ([`jacobian_vq`](LinearizedDynamics::jacobian_vq), [`jacobian_qv`](LinearizedDynamics::jacobian_qv);
/// for H = T(p) + V(q): ∂D/∂p = ∇²T, ∂K/∂q = −∇²V, one Hessian each; on a natural system ∂D/∂v = I
/// needs no call).
pub(super) struct SplitTangent<'a, S> {
    system: &'a S,
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    f: Vec<f64>,
    dq: Vec<f64>,
    /// ∂v̇/∂q in a kick, ∂q̇/∂v in a drift: the one block of J each needs.
    block: DMatrix<f64>,
    psi: DMatrix<f64>,
}

impl<'a, S: SplitDynamics + LinearizedDynamics> SplitTangent<'a, S> {
    pub(super) fn new(system: &'a S, state: &State<S::Partner>) -> Self {
        let n = system.dof();
        SplitTangent {
            system,
            t: state.t,
            q: state.q.as_slice().to_vec(),
            v: state.v.as_slice().to_vec(),
            f: vec![0.0; n],
            dq: vec![0.0; n],
            block: DMatrix::zeros(n, n),
            psi: DMatrix::identity(2 * n, 2 * n),
        }
    }
    pub(super) fn kick(&mut self, c: f64) -> Result<()> {
        let n = self.q.len();
        self.system.kick_rate(&self.q, &mut self.f)?;
        self.system
            .jacobian_vq(self.t, &self.q, &self.v, &mut self.block)?;
        add_block_product(&mut self.psi, &self.block, (n, 0), c);
        self.v.iter_mut().zip(&self.f).for_each(|(v, f)| *v += c * f);
        Ok(())
    }
    pub(super) fn drift(&mut self, c: f64) -> Result<()> {
        let n = self.q.len();
        if self.system.drift_is_identity() {
            let dq = self.psi.rows(n, n) * c;
            self.psi.rows_mut(0, n).add_assign(&dq);
            self.q.iter_mut().zip(&self.v).for_each(|(q, v)| *q += c * v);
        } else {
            self.system.drift_rate(&self.v, &mut self.dq)?;
            self.system
                .jacobian_qv(self.t, &self.q, &self.v, &mut self.block)?;
            add_block_product(&mut self.psi, &self.block, (0, n), c);
            self.q.iter_mut().zip(&self.dq).for_each(|(q, d)| *q += c * d);
        }
        Ok(())
    }
    /// Ψ into `out` when finite.
    pub(super) fn finish(self, out: &mut DMatrix<f64>) -> Result<()> {
        check_result("step Jacobian Ψ", self.t, self.psi.as_slice())?;
        out.copy_from(&self.psi);
        Ok(())
    }
}

/// Ψ's rows `to..to + n` += (B Ψ's rows `from..from + n`) c, B = `block` (n × n). Up to 5 rows
/// in place, each entry's sum over k in ascending order, then × c, then added: the bits of nalgebra's
/// `&block * psi.rows(from, n) * c` added after, without its two temporaries; above 5 nalgebra's
/// product itself (blocked, where the temporaries cost nothing beside it).
fn add_block_product(psi: &mut DMatrix<f64>, block: &DMatrix<f64>, (to, from): (usize, usize), c: f64) {
    let n = block.nrows();
    if n > 5 {
        let d = block * psi.rows(from, n) * c;
        psi.rows_mut(to, n).add_assign(&d);
        return;
    }
    for j in 0..psi.ncols() {
        for i in 0..n {
            let mut s = block[(i, 0)] * psi[(from, j)];
            for k in 1..n {
                s += block[(i, k)] * psi[(from + k, j)];
            }
            psi[(to + i, j)] += s * c;
        }
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
