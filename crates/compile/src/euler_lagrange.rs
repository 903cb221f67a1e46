//! Lagrange's equations of a recorded Lagrangian: q̈ and the energy as compiled programs.
//!
//! From the graph of L(t, q, q̇), with p = ∂L/∂q̇,
//!
//! ```text
//! M q̈ = b,   M = ∂p/∂q̇ = ∂²L/∂q̇²,   b = ∂L/∂q − (∂p/∂q) q̇ − ∂p/∂t + Q,   h = p·q̇ − L,
//! ```
//!
//! each a graph: ∂L/∂q and p by one reverse accumulation from L; the mixed term (∂p/∂q) q̇ + ∂p/∂t as
//! one derivative of p along the flow direction (δt, δq) = (1, q̇) (forward accumulation); row i of M
//! (its lower triangle) by reverse accumulation from p_i; and q̈ by the unrolled LDLᵀ solve of
//! [`ldlt`]. Generalized forces Q(t, q, q̇) are recorded with L on the same graph (the model's
//! generic [`generalized_force`](noether_core::Lagrangian::generalized_force)), so b, the compiled
//! Jacobian and the printed equations include them.

use crate::derive::{directional, gradient};
use crate::graph::{sign, Graph, Id};
use crate::program::{Backend, Outputs, Program};
use crate::trace::{Guard, Recorded};
use crate::{ldlt, Result};
use nalgebra::DMatrix;
use noether_core::error::check_phase_point;
use noether_core::linalg::{factor_positive_mass, positive_pivots_regular};
use noether_core::system::LinearizedDynamics;
use noether_core::{Dynamics, EulerLagrange, Lagrangian, Velocities};
use std::sync::OnceLock;

/// Operation counts of a compiled system: what the model recorded, how many operations its
/// derivation asked for (before folding, identities and sharing), and what runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Operations {
    /// Nodes of the recorded model (inputs and constants included).
    pub recorded: usize,
    /// Operations built for the model and its derivatives, before simplification and sharing.
    pub requested: usize,
    /// Nodes of the graph after simplification and sharing.
    pub graph: usize,
    /// Operations of the accelerations' program (after dead-code elimination).
    pub accelerations: usize,
    /// Operations of the energy's program.
    pub energy: usize,
}

/// [`EulerLagrange`] compiled: q̈ and the energy from programs built once on the graph of L (see the
/// [module docs](self)); the dual-number system kept for the calls the compiled code cannot take.
///
/// A call falls back to the dual-number path when a guard of a comparison in L fails, when a pivot
/// of the mass matrix is not positive or says singular ([`linalg`](noether_core::linalg)'s criterion),
/// or when a result is not finite: the fallback then gives the right value, or the error the
/// dual-number path gives ([`Error::IndefiniteMassMatrix`](noether_core::Error::IndefiniteMassMatrix),
/// [`Error::NonFiniteResult`](noether_core::Error::NonFiniteResult), …). Within the region where the
/// guards hold, the compiled and the dual-number results agree to rounding.
pub struct CompiledEulerLagrange<L> {
    dual: EulerLagrange<L>,
    graph: Graph,
    outputs: Vec<Id>,
    accelerations: Program,
    energy: Program,
    guards: Vec<f64>,
    operations: Operations,
    terms: (Vec<Id>, Vec<Vec<Id>>),
    jacobian: OnceLock<Program>,
    backend: Backend,
}

/// The largest number of degrees of freedom whose solve M q̈ = b is unrolled into the graph (n³/6
/// multiply-adds as instructions); above it the program gives b and M and one dense factorisation of
/// [`linalg`](noether_core::linalg) solves (as core's dual-number path does above its jet range).
pub const UNROLL_MAX: usize = 12;

/// Lagrange's equations M q̈ = b on the graph of L: b, and M by its lower triangle.
fn lagrange_terms(r: &mut Recorded) -> (Vec<Id>, Vec<Vec<Id>>) {
    let n = r.q.len();
    let g: &mut Graph = &mut r.rec.graph;
    let vars: Vec<Id> = r.q.iter().chain(&r.v).copied().collect();
    let grad = gradient(g, r.value, &vars);
    let (gq, p) = grad.split_at(n);
    let one = g.constant(1.0);
    let seeds: Vec<(Id, Id)> = std::iter::once((r.t, one))
        .chain(r.q.iter().zip(&r.v).map(|(&q, &v)| (q, v)))
        .collect();
    let mixed = directional(g, p, &seeds);
    let m = mass_rows(g, p, &r.v);
    let b: Vec<Id> = (0..n)
        .map(|i| {
            let bi = g.sub(gq[i], mixed[i]);
            match r.vector.get(i) {
                Some(&qi) => g.add(bi, qi),
                None => bi,
            }
        })
        .collect();
    (b, m)
}

/// The lower triangle of M = ∂p/∂q̇ by rows: row i by reverse accumulation from p_i (to q̇_0..q̇_i).
pub(crate) fn mass_rows(g: &mut Graph, p: &[Id], v: &[Id]) -> Vec<Vec<Id>> {
    (0..p.len()).map(|i| gradient(g, p[i], &v[..=i])).collect()
}

/// The outputs of the accelerations' program: (q̈, the pivots of M, the diagonal of M) with the solve
/// unrolled, or (b, M's lower triangle by rows) above [`UNROLL_MAX`].
fn accelerations_outputs(g: &mut Graph, (b, m): (&[Id], &[Vec<Id>])) -> Vec<Id> {
    if b.len() > UNROLL_MAX {
        return b.iter().chain(m.iter().flatten()).copied().collect();
    }
    let (x, d) = ldlt::solve(g, m, b);
    let diagonal = (0..b.len()).map(|i| m[i][i]);
    x.into_iter().chain(d).chain(diagonal).collect()
}

/// The output h = p·q̇ − L.
fn energy_output(r: &mut Recorded) -> Id {
    let g = &mut r.rec.graph;
    let p = gradient(g, r.value, &r.v);
    let pv: Vec<Id> = p.iter().zip(&r.v).map(|(&p, &v)| g.mul(p, v)).collect();
    let s = g.sum(pv);
    g.sub(s, r.value)
}

/// The value of a one-output `program` (an energy) at the inputs `parts` when every guard holds and it
/// is finite, else `fallback()` (the dual-number path: the right value or the right error).
pub(crate) fn value_or(
    program: &Program,
    guards: &[f64],
    parts: &[&[f64]],
    fallback: impl FnOnce() -> noether_core::Result<f64>,
) -> noether_core::Result<f64> {
    let compiled = program.run_with(parts, |o| {
        (guards_hold(&o, 1, guards) && o.get(0).is_finite()).then(|| o.get(0))
    })?;
    compiled.map_or_else(fallback, Ok)
}

/// The point a model is recorded at when none is given: t = 0, q_i = 0.1 + 0.01 i, v_i = 0.2 + 0.01 i
/// (it only decides the branches the recording takes).
pub(crate) fn default_point(n: usize) -> (Vec<f64>, Vec<f64>) {
    let q = (0..n).map(|i| 0.1 + 0.01 * i as f64).collect();
    let v = (0..n).map(|i| 0.2 + 0.01 * i as f64).collect();
    (q, v)
}

/// The position rates q̇ = v of a system on (q, q̇) with `n` degrees of freedom, into `dq` (both
/// checked to have n entries).
pub(crate) fn velocity_rates(n: usize, v: &[f64], dq: &mut [f64]) -> noether_core::Result<()> {
    noether_core::error::check_len("q̇", v, n)?;
    noether_core::error::check_len("q̇ (output)", dq, n)?;
    dq.copy_from_slice(v);
    Ok(())
}

/// `true` when every guard holds: the outputs from `offset` on have the signs recorded.
#[inline]
pub(crate) fn guards_hold(o: &Outputs<'_>, offset: usize, signs: &[f64]) -> bool {
    signs
        .iter()
        .enumerate()
        .all(|(k, &s)| sign(o.get(offset + k)) == s)
}

/// `true` when the n pivots of M = LDLᵀ at outputs `at..at + n` (the diagonal of M after them) are
/// positive and regular by
/// [`linalg::positive_pivots_regular`](noether_core::linalg::positive_pivots_regular), the test of the
/// dual-number path's stack LDLᵀ (the pivot ratio against the largest pivot or diagonal entry, which
/// bounds every entry of a positive definite M).
#[inline]
pub(crate) fn mass_usable(o: &Outputs<'_>, at: usize, n: usize) -> bool {
    let norm = (at + n..at + 2 * n).fold(0.0_f64, |m, j| m.max(o.get(j).abs()));
    positive_pivots_regular((at..at + n).map(|j| o.get(j)), norm)
}

/// q̈ = M⁻¹ b from the outputs (b, M's lower triangle by rows) by
/// [`linalg::factor_positive_mass`](noether_core::linalg::factor_positive_mass): `false` when M is not
/// usable (the dual-number path then reports why) or q̈ is not finite.
fn dense_solve(o: &Outputs<'_>, n: usize, t: f64, a: &mut [f64]) -> bool {
    let mut m = DMatrix::zeros(n, n);
    let mut k = n;
    for i in 0..n {
        for j in 0..=i {
            m[(i, j)] = o.get(k);
            m[(j, i)] = o.get(k);
            k += 1;
        }
        a[i] = o.get(i);
    }
    let Ok(factor) = factor_positive_mass(m, t) else {
        return false;
    };
    factor.solve_in_place(a);
    a.iter().all(|x| x.is_finite())
}

compiled_constructors! {
    CompiledEulerLagrange<L: Lagrangian>(EulerLagrange<L>), "L", accelerations;
    default "t = 0, q_i = 0.1 + 0.01 i, q̇_i = 0.2 + 0.01 i", (q, v) => (0.0, &q, &v);
    at "(t, q, q̇)" (t: f64, q: &[f64], v: &[f64]) => (t, q, v)
}

impl<L: Lagrangian> CompiledEulerLagrange<L> {
    /// Records at (t, q, q̇), derives, and builds the programs for `backend`.
    fn build(system: EulerLagrange<L>, (t, q, v): (f64, &[f64], &[f64]), backend: Backend) -> Result<Self> {
        let n = system.dof();
        check_phase_point(n, t, q, v, "q̇")?;
        let model = system.lagrangian();
        let forces = if model.has_generalized_force() { n } else { 0 };
        let mut r = Recorded::with_vector(t, q, v, forces, |t, q, v, f| {
            if forces > 0 {
                model.generalized_force(t, q, v, f);
            }
            model.lagrangian(t, q, v)
        })?;
        let recorded = r.rec.graph.len();
        let guards: Vec<Guard> = r.rec.guards.clone();
        let terms = lagrange_terms(&mut r);
        let mut outputs = accelerations_outputs(&mut r.rec.graph, (&terms.0, &terms.1));
        outputs.extend(guards.iter().map(|g| g.node));
        let h = energy_output(&mut r);
        let mut energy_outputs = vec![h];
        energy_outputs.extend(guards.iter().map(|g| g.node));
        let accelerations = Program::with_backend(&r.rec.graph, 1 + 2 * n, &outputs, backend);
        let energy = Program::with_backend(&r.rec.graph, 1 + 2 * n, &energy_outputs, backend);
        let operations = Operations {
            recorded,
            requested: r.rec.graph.requested(),
            graph: r.rec.graph.len(),
            accelerations: accelerations.operations(),
            energy: energy.operations(),
        };
        Ok(CompiledEulerLagrange {
            dual: system,
            graph: r.rec.graph,
            outputs,
            accelerations,
            energy,
            guards: guards.iter().map(|g| g.sign).collect(),
            operations,
            terms,
            jacobian: OnceLock::new(),
            backend,
        })
    }

    /// The program of q̈ (for the measurements of the tests).
    #[cfg(all(test, feature = "jit"))]
    pub(crate) fn accelerations_program(&self) -> &Program {
        &self.accelerations
    }

    /// The dual-number system it was compiled from (and falls back to).
    pub fn dual(&self) -> &EulerLagrange<L> {
        &self.dual
    }

    /// The operation counts.
    pub fn operations(&self) -> Operations {
        self.operations
    }

    /// The accelerations as Rust source, `pub fn <name>(x: &[f64; I]) -> [f64; O]` (see
    /// [`show`](crate::show)): x = (t, q, q̇), the outputs
    /// (q̈, the pivots d of M = LDLᵀ, the diagonal of M, then one value per guard; above
    /// [`UNROLL_MAX`] degrees of freedom b and M's lower triangle instead of q̈ and M's pivots). The compiled
    /// q̈ is valid where every pivot is positive (and their ratio above
    /// [`SINGULAR_PIVOT`](noether_core::linalg::SINGULAR_PIVOT)) and every guard has the sign
    /// recorded ([`guard_signs`](Self::guard_signs)).
    pub fn rust_source(&self, name: &str) -> String {
        let n = self.dual.dof();
        let layout = format!(
            "x = (t, q[{n}], q̇[{n}]); out = (q̈[{n}], pivots of M[{n}], diagonal of M[{n}], guards[{}]).",
            self.guards.len()
        );
        let doc = [
            "Lagrange's equations, generated by noether-compile from the recorded Lagrangian.",
            layout.as_str(),
        ];
        crate::show::rust_function(&self.graph, 1 + 2 * n, &self.outputs, name, &doc)
    }

    /// Lagrange's equations M(q, q̇) q̈ = b(t, q, q̇) as formulas: M's lower triangle by rows
    /// ([`Term::Mass`](crate::show::Term::Mass)), then b ([`Term::Force`](crate::show::Term::Force)),
    /// simplified; see [`Equations`](crate::show::Equations) to print them as text or LaTeX.
    pub fn equations(&self) -> crate::show::Equations {
        use crate::show::Term;
        let (b, m) = &self.terms;
        let mut rows: Vec<(Term, Id)> = Vec::new();
        for (i, row) in m.iter().enumerate() {
            rows.extend(row.iter().enumerate().map(|(j, &y)| (Term::Mass(i, j), y)));
        }
        rows.extend(b.iter().enumerate().map(|(i, &y)| (Term::Force(i), y)));
        crate::show::Equations::new(self.graph.clone(), rows, self.dual.dof(), false)
    }

    /// The sign each guard had when L was recorded (the compiled code holds where each has it).
    pub fn guard_signs(&self) -> &[f64] {
        &self.guards
    }

    /// The number of comparisons in L that the compiled code checks at every call.
    pub fn guards(&self) -> usize {
        self.guards.len()
    }

    /// q̈ from the program, when it is usable (guards hold, M positive definite and regular, q̈
    /// finite): `false` otherwise, with `a` unspecified.
    fn compiled_accelerations(&self, t: f64, q: &[f64], v: &[f64], a: &mut [f64]) -> bool {
        let n = q.len();
        let guards_at = self.outputs.len() - self.guards.len();
        let run = self.accelerations.run_with(&[&[t], q, v], |o| {
            if !guards_hold(&o, guards_at, &self.guards) {
                return false;
            }
            if n > UNROLL_MAX {
                return dense_solve(&o, n, t, a);
            }
            if !mass_usable(&o, n, n) {
                return false;
            }
            for (i, ai) in a.iter_mut().enumerate() {
                *ai = o.get(i);
            }
            a.iter().all(|x| x.is_finite())
        });
        run.unwrap_or(false)
    }

    /// q̈ = M⁻¹ b (see the [module docs](self)), written into `a`: from the compiled program, or
    /// from the dual-number path where the program's result is not usable.
    pub fn accelerations(&self, t: f64, q: &[f64], v: &[f64], a: &mut [f64]) -> noether_core::Result<()> {
        let n = self.dual.dof();
        check_phase_point(n, t, q, v, "q̇")?;
        noether_core::error::check_len("q̈ (output)", a, n)?;
        if self.compiled_accelerations(t, q, v, a) {
            return Ok(());
        }
        self.dual.accelerations(t, q, v, a)
    }

    /// The program of the Jacobian's lower half, built on first use: column j is the derivative of q̈
    /// (the solve unrolled, whatever the number of degrees of freedom) along input j of (q, q̇) by
    /// forward accumulation; then the pivots, the diagonal of M and the guards.
    fn jacobian_program(&self) -> &Program {
        self.jacobian.get_or_init(|| {
            let n = self.dual.dof();
            let mut g = self.graph.clone();
            let (b, m) = &self.terms;
            let (x, d) = ldlt::solve(&mut g, m, b);
            let one = g.constant(1.0);
            let mut outputs = Vec::with_capacity(2 * n * n + 3 * n + self.guards.len());
            for j in 0..2 * n {
                let y = g.input(1 + j as u32);
                outputs.extend(directional(&mut g, &x, &[(y, one)]));
            }
            outputs.extend(d.into_iter().chain((0..n).map(|i| m[i][i])));
            outputs.extend(&self.outputs[self.outputs.len() - self.guards.len()..]);
            Program::with_backend(&g, 1 + 2 * n, &outputs, self.backend)
        })
    }

    /// J = ∂(q̇, q̈)/∂(q, q̇) from the program, when it is usable (see
    /// [`compiled_accelerations`](Self::compiled_accelerations)).
    fn compiled_jacobian(&self, t: f64, q: &[f64], v: &[f64], out: &mut DMatrix<f64>) -> bool {
        let n = q.len();
        let m = 2 * n * n;
        let run = self.jacobian_program().run_with(&[&[t], q, v], |o| {
            if !guards_hold(&o, m + 2 * n, &self.guards) || !mass_usable(&o, m, n) {
                return false;
            }
            out.fill(0.0);
            for i in 0..n {
                out[(i, n + i)] = 1.0;
                for j in 0..2 * n {
                    out[(n + i, j)] = o.get(j * n + i);
                }
            }
            out.iter().all(|x| x.is_finite())
        });
        run.unwrap_or(false)
    }

    /// The energy h = p·q̇ − L.
    pub fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> noether_core::Result<f64> {
        check_phase_point(self.dual.dof(), t, q, v, "q̇")?;
        value_or(&self.energy, &self.guards, &[&[t], q, v], || {
            self.dual.energy(t, q, v)
        })
    }
}

impl<L: Lagrangian> Dynamics for CompiledEulerLagrange<L> {
    type Partner = Velocities;
    fn dof(&self) -> usize {
        self.dual.dof()
    }
    fn rates(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        dq: &mut [f64],
        dv: &mut [f64],
    ) -> noether_core::Result<()> {
        noether_core::error::check_len("q̇ (output)", dq, self.dual.dof())?;
        self.accelerations(t, q, v, dv)?;
        dq.copy_from_slice(v);
        Ok(())
    }
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> noether_core::Result<f64> {
        CompiledEulerLagrange::energy(self, t, q, v)
    }
    fn position_rates(&self, _t: f64, _q: &[f64], v: &[f64], dq: &mut [f64]) -> noether_core::Result<()> {
        velocity_rates(self.dual.dof(), v, dq)
    }
}

/// The exact Jacobian of Lagrange's equations from the compiled graph (any number of degrees of
/// freedom: forward accumulation through the unrolled solve; generalized forces included), or the
/// dual-number path's where the program's result is not usable.
impl<L: Lagrangian> LinearizedDynamics for CompiledEulerLagrange<L> {
    fn jacobian(&self, t: f64, q: &[f64], v: &[f64], out: &mut DMatrix<f64>) -> noether_core::Result<()> {
        let n = self.dual.dof();
        check_phase_point(n, t, q, v, "q̇")?;
        let shaped = out.nrows() == 2 * n && out.ncols() == 2 * n;
        if shaped && self.compiled_jacobian(t, q, v, out) {
            return Ok(());
        }
        self.dual.jacobian(t, q, v, out)
    }
}
