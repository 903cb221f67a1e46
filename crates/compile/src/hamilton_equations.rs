//! Hamilton's equations of a recorded Hamiltonian as a compiled program:
//!
//! ```text
//! q̇ = ∂H/∂p,   ṗ = −∂H/∂q
//! ```
//!
//! both from one reverse accumulation from H on its graph; the energy is H itself. H is recorded from
//! a [`Hamiltonian`], or built on the graph from a Lagrangian quadratic in q̇ ([`crate::legendre`]).

use crate::derive::gradient;
use crate::euler_lagrange::{guards_hold, mass_usable};
use crate::graph::{Graph, Id};
use crate::program::{Backend, Outputs, Program};
use crate::trace::{Guard, Recorded};
use crate::Result;
use nalgebra::DMatrix;
use noether_core::error::{check_len, check_phase_point};
use noether_core::system::LinearizedDynamics;
use noether_core::{Dynamics, HamiltonEquations, Hamiltonian, Momenta};
use std::sync::OnceLock;

/// [`HamiltonEquations`] compiled: the rates and H from programs built once on the graph of H; the
/// dual-number system kept for the calls the compiled code cannot take (a guard of a comparison in H
/// fails, or a result is not finite), which then give the right value or the right error.
#[derive(Clone)]
pub struct CompiledHamiltonEquations<H> {
    dual: HamiltonEquations<H>,
    graph: Graph,
    /// The nodes of (q, p), and of the rates (q̇, ṗ) then the checks (see [`Checks`]).
    vars: Vec<Id>,
    outputs: Vec<Id>,
    rates: Program,
    /// Outputs H, then the checks.
    energy: Program,
    guards: Vec<f64>,
    /// The number of pivots of a mass matrix among the checks (0 for a recorded H).
    pivots: usize,
    /// Outputs ∂(q̇, ṗ)/∂(q, p) by rows, then the guards (built on first use).
    jacobian: OnceLock<Program>,
}

compiled_constructors! {
    CompiledHamiltonEquations<H: Hamiltonian>(HamiltonEquations<H>), "H", rates;
    default "t = 0, q_i = 0.1 + 0.01 i, p_i = 0.2 + 0.01 i", (q, p) => (0.0, &q, &p);
    at "(t, q, p)" (t: f64, q: &[f64], p: &[f64]) => (t, q, p)
}

impl<H: Hamiltonian> CompiledHamiltonEquations<H> {
    /// Records at (t, q, p), derives, and builds the programs for `backend`.
    fn build(
        system: HamiltonEquations<H>,
        (t, q, p): (f64, &[f64], &[f64]),
        backend: Backend,
    ) -> Result<Self> {
        let n = system.dof();
        check_phase_point(n, t, q, p, "p")?;
        let model = system.hamiltonian();
        let r = Recorded::new(t, q, p, |t, q, p| model.hamiltonian(t, q, p))?;
        let checks = Checks {
            pivots: Vec::new(),
            diagonal: Vec::new(),
            guards: r.rec.guards.clone(),
        };
        Ok(Self::assemble(system, r, checks, backend))
    }

    /// The compiled system of the recording `r` whose value is H (inputs t, q, p), its rates from
    /// one reverse accumulation, and `checks` after the rates and after H; programs for `backend`.
    pub(crate) fn assemble(
        system: HamiltonEquations<H>,
        mut r: Recorded,
        checks: Checks,
        backend: Backend,
    ) -> Self {
        let n = r.q.len();
        let g = &mut r.rec.graph;
        let vars: Vec<Id> = r.q.iter().chain(&r.v).copied().collect();
        let grad = gradient(g, r.value, &vars);
        let mut outputs: Vec<Id> = grad[n..].to_vec();
        outputs.extend(grad[..n].iter().map(|&x| g.neg(x)));
        let check_nodes: Vec<Id> = (checks.pivots.iter().chain(&checks.diagonal).copied())
            .chain(checks.guards.iter().map(|g| g.node))
            .collect();
        outputs.extend(&check_nodes);
        let mut energy = vec![r.value];
        energy.extend(&check_nodes);
        CompiledHamiltonEquations {
            rates: Program::with_backend(g, 1 + 2 * n, &outputs, backend),
            energy: Program::with_backend(g, 1 + 2 * n, &energy, backend),
            dual: system,
            graph: r.rec.graph,
            vars,
            outputs,
            guards: checks.guards.iter().map(|g| g.sign).collect(),
            pivots: checks.pivots.len(),
            jacobian: OnceLock::new(),
        }
    }

    /// `true` when the checks from output `at` on hold: the pivots of the mass matrix (if any) are
    /// positive and regular, and every guard has its recorded sign.
    fn usable(&self, o: &Outputs<'_>, at: usize) -> bool {
        let k = self.pivots;
        (k == 0 || mass_usable(o, at, k)) && guards_hold(o, at + 2 * k, &self.guards)
    }

    /// The dual-number system it was compiled from (and falls back to).
    pub fn dual(&self) -> &HamiltonEquations<H> {
        &self.dual
    }

    /// The number of operations of the rates' program.
    pub fn operations(&self) -> usize {
        self.rates.operations()
    }

    /// Hamilton's equations q̇ = ∂H/∂p ([`Term::Velocity`](crate::show::Term::Velocity)) and
    /// ṗ = −∂H/∂q ([`Term::MomentumRate`](crate::show::Term::MomentumRate)) as formulas, simplified;
    /// see [`Equations`](crate::show::Equations) to print them as text or LaTeX.
    pub fn equations(&self) -> crate::show::Equations {
        use crate::show::Term;
        let n = self.dual.dof();
        let rows = (0..n)
            .map(|i| (Term::Velocity(i), self.outputs[i]))
            .chain((0..n).map(|i| (Term::MomentumRate(i), self.outputs[n + i])))
            .collect();
        crate::show::Equations::new(self.graph.clone(), rows, n, true)
    }

    /// The program of J = ∂(q̇, ṗ)/∂(q, p) by rows (row i by reverse accumulation from rate i:
    /// [[H_pq, H_pp], [−H_qq, −H_qp]]), then the guards; built on first use.
    fn jacobian_program(&self) -> &Program {
        self.jacobian.get_or_init(|| {
            let n2 = self.vars.len();
            let mut g = self.graph.clone();
            let mut outputs: Vec<Id> = Vec::with_capacity(n2 * n2 + self.guards.len());
            for &rate in &self.outputs[..n2] {
                outputs.extend(gradient(&mut g, rate, &self.vars));
            }
            outputs.extend(&self.outputs[n2..]);
            Program::with_backend(&g, 1 + n2, &outputs, self.rates.backend())
        })
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
            if !self.usable(&o, 2 * n) {
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
        let value = self.energy.run_with(&[&[t], q, p], |o| {
            (self.usable(&o, 1) && o.get(0).is_finite()).then(|| o.get(0))
        })?;
        value.map_or_else(|| self.dual.energy(t, q, p), Ok)
    }
}

/// J = [[H_pq, H_pp], [−H_qq, −H_qp]] from the compiled graph, or the dual-number path's where the
/// program's result is not usable.
impl<H: Hamiltonian> LinearizedDynamics for CompiledHamiltonEquations<H> {
    fn jacobian(&self, t: f64, q: &[f64], p: &[f64], out: &mut DMatrix<f64>) -> noether_core::Result<()> {
        let n2 = 2 * self.dual.dof();
        check_phase_point(self.dual.dof(), t, q, p, "p")?;
        let shaped = out.nrows() == n2 && out.ncols() == n2;
        let ok = self.jacobian_program().run_with(&[&[t], q, p], |o| {
            if !shaped || !self.usable(&o, n2 * n2) {
                return false;
            }
            for i in 0..n2 {
                for j in 0..n2 {
                    out[(i, j)] = o.get(i * n2 + j);
                }
            }
            out.iter().all(|x| x.is_finite())
        })?;
        if ok {
            return Ok(());
        }
        self.dual.jacobian(t, q, p, out)
    }
}

/// What a compiled Hamiltonian checks at every call, beside finite results: the pivots of the mass
/// matrix whose solve is unrolled into it (with the diagonal of that matrix, which bounds it), and the
/// guards of the comparisons recorded.
pub(crate) struct Checks {
    pub pivots: Vec<Id>,
    pub diagonal: Vec<Id>,
    pub guards: Vec<Guard>,
}
