//! Hamilton's equations of a recorded Hamiltonian as a compiled program:
//!
//! ```text
//! q̇ = ∂H/∂p,   ṗ = −∂H/∂q
//! ```
//!
//! both from one reverse accumulation from H on its graph; the energy is H itself.

use crate::derive::gradient;
use crate::euler_lagrange::{default_point, guards_hold, value_or};
use crate::graph::Id;
use crate::program::{Backend, Program};
use crate::trace::{Guard, Recorded};
use crate::{Compile, Result};
use noether_core::error::{check_len, check_phase_point};
use noether_core::{Dynamics, HamiltonEquations, Hamiltonian, Momenta};

/// [`HamiltonEquations`] compiled: the rates and H from programs built once on the graph of H; the
/// dual-number system kept for the calls the compiled code cannot take (a guard of a comparison in H
/// fails, or a result is not finite), which then give the right value or the right error.
pub struct CompiledHamiltonEquations<H> {
    dual: HamiltonEquations<H>,
    rates: Program,
    energy: Program,
    guards: Vec<f64>,
}

impl<H: Hamiltonian> CompiledHamiltonEquations<H> {
    /// Compiles `system`, recording H at a point chosen only for the branches H takes there (t = 0,
    /// q_i = 0.1 + 0.01 i, p_i = 0.2 + 0.01 i); see [`at`](Self::at) to choose it.
    pub fn new(system: HamiltonEquations<H>) -> Result<Self> {
        let (q, p) = default_point(system.dof());
        Self::at(system, 0.0, &q, &p)
    }

    /// Compiles `system`, recording H at (t, q, p).
    pub fn at(system: HamiltonEquations<H>, t: f64, q: &[f64], p: &[f64]) -> Result<Self> {
        Self::build(system, (t, q, p), Backend::Native)
    }

    /// Compiles `system` as [`new`](Self::new) does, its programs run by the interpreter even with the
    /// feature `jit`.
    pub fn interpreted(system: HamiltonEquations<H>) -> Result<Self> {
        let (q, p) = default_point(system.dof());
        Self::build(system, (0.0, &q, &p), Backend::Interpreter)
    }

    /// What runs the programs ([`Backend::Native`] with the feature `jit`, unless built by
    /// [`interpreted`](Self::interpreted) or Cranelift failed).
    pub fn backend(&self) -> Backend {
        self.rates.backend()
    }

    /// Records at (t, q, p), derives, and builds the programs for `backend`.
    fn build(
        system: HamiltonEquations<H>,
        (t, q, p): (f64, &[f64], &[f64]),
        backend: Backend,
    ) -> Result<Self> {
        let n = system.dof();
        check_phase_point(n, t, q, p, "p")?;
        let model = system.hamiltonian();
        let mut r = Recorded::new(t, q, p, |t, q, p| model.hamiltonian(t, q, p))?;
        let guards: Vec<Guard> = r.rec.guards.clone();
        let g = &mut r.rec.graph;
        let vars: Vec<Id> = r.q.iter().chain(&r.v).copied().collect();
        let grad = gradient(g, r.value, &vars);
        let mut outputs: Vec<Id> = grad[n..].to_vec();
        outputs.extend(grad[..n].iter().map(|&x| g.neg(x)));
        outputs.extend(guards.iter().map(|g| g.node));
        let mut energy = vec![r.value];
        energy.extend(guards.iter().map(|g| g.node));
        Ok(CompiledHamiltonEquations {
            rates: Program::with_backend(g, 1 + 2 * n, &outputs, backend),
            energy: Program::with_backend(g, 1 + 2 * n, &energy, backend),
            dual: system,
            guards: guards.iter().map(|g| g.sign).collect(),
        })
    }

    /// The dual-number system it was compiled from (and falls back to).
    pub fn dual(&self) -> &HamiltonEquations<H> {
        &self.dual
    }

    /// The number of operations of the rates' program.
    pub fn operations(&self) -> usize {
        self.rates.operations()
    }
}

impl<H: Hamiltonian> Compile for HamiltonEquations<H> {
    type Compiled = CompiledHamiltonEquations<H>;
    fn compile(self) -> Result<CompiledHamiltonEquations<H>> {
        CompiledHamiltonEquations::new(self)
    }
}

impl<H: Hamiltonian> Dynamics for CompiledHamiltonEquations<H> {
    type Partner = Momenta;
    fn dof(&self) -> usize {
        self.dual.dof()
    }
    /// q̇ = ∂H/∂p, ṗ = −∂H/∂q from the program, or from the dual-number path where the program's result
    /// is not usable.
    fn rates(
        &self,
        t: f64,
        q: &[f64],
        p: &[f64],
        dq: &mut [f64],
        dp: &mut [f64],
    ) -> noether_core::Result<()> {
        let n = self.dual.dof();
        check_phase_point(n, t, q, p, "p")?;
        check_len("q̇ (output)", dq, n)?;
        check_len("ṗ (output)", dp, n)?;
        let ok = self.rates.run_with(&[&[t], q, p], |o| {
            if !guards_hold(&o, 2 * n, &self.guards) {
                return false;
            }
            for i in 0..n {
                dq[i] = o.get(i);
                dp[i] = o.get(n + i);
            }
            dq.iter().chain(dp.iter()).all(|x| x.is_finite())
        })?;
        if ok {
            return Ok(());
        }
        self.dual.rates(t, q, p, dq, dp)
    }
    fn energy(&self, t: f64, q: &[f64], p: &[f64]) -> noether_core::Result<f64> {
        check_phase_point(self.dual.dof(), t, q, p, "p")?;
        value_or(&self.energy, &self.guards, (t, q, p), || {
            self.dual.energy(t, q, p)
        })
    }
}
