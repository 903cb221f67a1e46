//! A natural system L = ½ q̇ᵀ M q̇ − V(q) (constant M) compiled from the graph of its potential:
//!
//! ```text
//! q̈ = −M⁻¹ ∇V(q),   ∂q̈/∂q = −M⁻¹ ∇²V(q),   h = ½ q̇ᵀ M q̇ + V(q),
//! ```
//!
//! ∇V by one reverse accumulation from V, the rows of ∇²V by one reverse accumulation from each
//! entry of ∇V (built on first use, for the implicit methods and tangents), and M⁻¹ folded in as
//! constants (a diagonal M costs one product an entry, a unit M none). This is the force of every
//! splitting method: [`SplitDynamics::kick_rate`] runs the program and nothing else.

use crate::derive::gradient;
use crate::euler_lagrange::{guards_hold, value_or, velocity_rates};
use crate::graph::{Graph, Id};
use crate::program::Program;
use crate::trace::{Guard, Recorded};
use crate::Result;
use nalgebra::DMatrix;
use noether_core::error::check_len;
use noether_core::system::{LinearizedDynamics, SplitDynamics};
use noether_core::{Dynamics, Natural, Potential, Velocities};
use std::sync::OnceLock;

/// [`Natural`] compiled: q̈ = −M⁻¹∇V(q) and V from programs built once on the graph of V (see the
/// [module docs](self)); the dual-number system kept for the calls the compiled code cannot take (a
/// guard of a comparison in V fails, or a result is not finite), which then give the right value or
/// the right error.
#[derive(Clone)]
pub struct CompiledNatural<P> {
    dual: Natural<P>,
    graph: Graph,
    /// The nodes of q, of ∇V and of q̈.
    q: Vec<Id>,
    gradient: Vec<Id>,
    acceleration_nodes: Vec<Id>,
    guard_nodes: Vec<Id>,
    guards: Vec<f64>,
    /// Outputs q̈, then the guards.
    accelerations: Program,
    /// Outputs V, then the guards.
    potential: Program,
    /// Outputs −M⁻¹∇²V by rows, then the guards (built on first use).
    hessian: OnceLock<Program>,
}

/// −M⁻¹ y on the graph, with M⁻¹ = `inverse` as constants (its zeros fold away).
fn apply_inverse_mass(g: &mut Graph, inverse: &DMatrix<f64>, y: &[Id]) -> Vec<Id> {
    (0..y.len())
        .map(|i| {
            let terms: Vec<Id> = (0..y.len()).map(|j| g.scale(inverse[(i, j)], y[j])).collect();
            let s = g.sum(terms);
            g.neg(s)
        })
        .collect()
}

compiled_constructors! {
    CompiledNatural<P: Potential>(Natural<P>), "V", accelerations;
    default "q_i = 0.1 + 0.01 i", (q, _) => &q;
    at "q" (q: &[f64]) => q
}

impl<P: Potential> CompiledNatural<P> {
    /// Records V at q, derives, and builds the programs for `backend`.
    fn build(system: Natural<P>, q: &[f64], backend: crate::Backend) -> Result<Self> {
        let n = system.dof();
        check_len("q", q, n)?;
        noether_core::error::check_finite("q", q)?;
        let model = system.potential_model();
        let mut r = Recorded::new(0.0, q, &[], |_, q, _| model.potential(q))?;
        let guards: Vec<Guard> = r.rec.guards.clone();
        let guard_nodes: Vec<Id> = guards.iter().map(|g| g.node).collect();
        let g = &mut r.rec.graph;
        let grad = gradient(g, r.value, &r.q);
        let acceleration_nodes = apply_inverse_mass(g, &system.inverse_mass_matrix(), &grad);
        let mut outputs = acceleration_nodes.clone();
        outputs.extend(&guard_nodes);
        let mut potential = vec![r.value];
        potential.extend(&guard_nodes);
        Ok(CompiledNatural {
            accelerations: Program::with_backend(g, 1 + n, &outputs, backend),
            potential: Program::with_backend(g, 1 + n, &potential, backend),
            graph: r.rec.graph,
            q: r.q,
            gradient: grad,
            acceleration_nodes,
            guard_nodes,
            guards: guards.iter().map(|g| g.sign).collect(),
            dual: system,
            hessian: OnceLock::new(),
        })
    }

    /// The dual-number system it was compiled from (and falls back to).
    pub fn dual(&self) -> &Natural<P> {
        &self.dual
    }

    /// The number of operations of the accelerations' program.
    pub fn operations(&self) -> usize {
        self.accelerations.operations()
    }

    /// The number of comparisons in V that the compiled code checks at every call.
    pub fn guards(&self) -> usize {
        self.guards.len()
    }

    /// The number of degrees of freedom.
    pub fn dof(&self) -> usize {
        self.dual.dof()
    }

    /// q̈ = −M⁻¹∇V(q) into `a`: from the program, or from the dual-number path where the program's
    /// result is not usable (which then gives the right value or the right error).
    #[inline]
    pub fn accelerations(&self, q: &[f64], a: &mut [f64]) -> noether_core::Result<()> {
        let n = self.dual.dof();
        check_len("q", q, n)?;
        check_len("q̈ (output)", a, n)?;
        let ok = self.accelerations.run_with(&[&[0.0], q], |o| {
            if !guards_hold(&o, n, &self.guards) {
                return false;
            }
            for (i, ai) in a.iter_mut().enumerate() {
                *ai = o.get(i);
            }
            a.iter().all(|x| x.is_finite())
        })?;
        if ok {
            return Ok(());
        }
        self.dual.accelerations(q, a)
    }

    /// q̈ by the native code alone, on the stack, for W = n < 16 coordinates: `None` where there is
    /// no native code, V has guards, or an entry is not finite (the callers then take the checked
    /// path).
    #[inline]
    #[allow(clippy::needless_range_loop, clippy::manual_memcpy)] // a few values: no call of memcpy
    fn fixed_accelerations<const W: usize>(&self, q: [f64; W]) -> Option<[f64; W]> {
        if W >= 16 || !self.guards.is_empty() {
            return None;
        }
        // Element loops (a few values: no call of memcpy, no iterator adapters).
        let mut x = [0.0; 16];
        for i in 0..W {
            x[1 + i] = q[i];
        }
        let mut a = [0.0; W];
        if !self.accelerations.call(&x[..=W], &mut a) {
            return None;
        }
        let mut finite = true;
        for i in 0..W {
            finite &= q[i].is_finite() & a[i].is_finite();
        }
        finite.then_some(a)
    }

    /// V(q).
    pub fn potential_energy(&self, q: &[f64]) -> noether_core::Result<f64> {
        check_len("q", q, self.dual.dof())?;
        value_or(&self.potential, &self.guards, &[&[0.0], q], || {
            self.dual.potential_energy(q)
        })
    }

    /// The energy ½ q̇ᵀ M q̇ + V(q).
    pub fn energy(&self, q: &[f64], v: &[f64]) -> noether_core::Result<f64> {
        let h = self.dual.kinetic_energy(v)? + self.potential_energy(q)?;
        noether_core::error::finite_result("energy", f64::NAN, h)
    }

    /// The equations of motion q̈ = −M⁻¹∇V(q) ([`Term::Acceleration`](crate::show::Term::Acceleration))
    /// as formulas, simplified; see [`Equations`](crate::show::Equations) to print them as text or
    /// LaTeX.
    pub fn equations(&self) -> crate::show::Equations {
        let rows = (self.acceleration_nodes.iter().enumerate())
            .map(|(i, &y)| (crate::show::Term::Acceleration(i), y))
            .collect();
        crate::show::Equations::new(self.graph.clone(), rows, self.dof(), false)
    }

    /// The program of −M⁻¹∇²V (rows of ∇²V by reverse accumulation from each entry of ∇V), then
    /// the guards; built on first use.
    fn hessian_program(&self) -> &Program {
        self.hessian.get_or_init(|| {
            let n = self.q.len();
            let mut g = self.graph.clone();
            let rows: Vec<Vec<Id>> = self
                .gradient
                .iter()
                .map(|&d| gradient(&mut g, d, &self.q))
                .collect();
            let inverse = self.dual.inverse_mass_matrix();
            let mut outputs = Vec::with_capacity(n * n + self.guards.len());
            for j in 0..n {
                let column: Vec<Id> = rows.iter().map(|row| row[j]).collect();
                outputs.extend(apply_inverse_mass(&mut g, &inverse, &column));
            }
            outputs.extend(&self.guard_nodes);
            Program::with_backend(&g, 1 + n, &outputs, self.accelerations.backend())
        })
    }
}

/// State (q, q̇): q̇ = q̇, q̈ = −M⁻¹∇V(q).
impl<P: Potential> Dynamics for CompiledNatural<P> {
    type Partner = Velocities;
    fn dof(&self) -> usize {
        self.dual.dof()
    }
    #[inline]
    fn rates(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        dq: &mut [f64],
        dv: &mut [f64],
    ) -> noether_core::Result<()> {
        check_len("q̇", v, self.dof())?;
        check_len("q̇ (output)", dq, self.dof())?;
        noether_core::error::check_finite("q̇", v)?;
        self.accelerations(q, dv).map_err(|e| e.at_time(t))?;
        dq.copy_from_slice(v);
        Ok(())
    }
    /// q̇ = v and q̈ from the native code on the stack where it can take the call (see
    /// [`kick_rate_fixed`](SplitDynamics::kick_rate_fixed)), else through [`rates`](Self::rates).
    #[inline]
    fn rates_fixed<const N: usize>(
        &self,
        t: f64,
        q: [f64; N],
        v: [f64; N],
    ) -> noether_core::Result<([f64; N], [f64; N])> {
        let v_finite = v.iter().fold(true, |ok, x| ok & x.is_finite());
        match self.fixed_accelerations(q) {
            Some(a) if v_finite => Ok((v, a)),
            _ => {
                let (mut dq, mut dv) = ([0.0; N], [0.0; N]);
                self.rates(t, &q, &v, &mut dq, &mut dv)?;
                Ok((dq, dv))
            }
        }
    }
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> noether_core::Result<f64> {
        CompiledNatural::energy(self, q, v).map_err(|e| e.at_time(t))
    }
    fn position_rates(&self, _t: f64, _q: &[f64], v: &[f64], dq: &mut [f64]) -> noether_core::Result<()> {
        velocity_rates(self.dof(), v, dq)
    }
}

/// The drift q̇ = v and the kick q̈ = −M⁻¹∇V(q), for the splitting methods.
impl<P: Potential> SplitDynamics for CompiledNatural<P> {
    fn drift_rate(&self, v: &[f64], dq: &mut [f64]) -> noether_core::Result<()> {
        self.dual.drift_rate(v, dq)
    }
    #[inline]
    fn drift_rate_fixed<const W: usize>(&self, v: [f64; W]) -> noether_core::Result<[f64; W]> {
        self.dual.drift_rate_fixed(v)
    }
    #[inline]
    fn kick_rate(&self, q: &[f64], dv: &mut [f64]) -> noether_core::Result<()> {
        self.accelerations(q, dv)
    }
    /// The kick of the fixed-size loops of the splitting methods: the native code called on a copy
    /// of q on the stack, its result returned when it has no guards to check and every entry is
    /// finite; otherwise (and without native code) through [`kick_rate`](Self::kick_rate), which
    /// gives the same values and the errors.
    #[inline]
    fn kick_rate_fixed<const W: usize>(&self, q: [f64; W]) -> noether_core::Result<[f64; W]> {
        if let Some(a) = self.fixed_accelerations(q) {
            return Ok(a);
        }
        let mut a = [0.0; W];
        self.kick_rate(&q, &mut a)?;
        Ok(a)
    }
    fn drift_is_identity(&self) -> bool {
        true
    }
}

/// On (q, q̇): J = [[0, I], [−M⁻¹∇²V(q), 0]], ∇²V from the compiled graph, or the dual-number path's
/// where the program's result is not usable.
impl<P: Potential> LinearizedDynamics for CompiledNatural<P> {
    fn jacobian(&self, t: f64, q: &[f64], v: &[f64], out: &mut DMatrix<f64>) -> noether_core::Result<()> {
        let n = self.dof();
        check_len("q", q, n)?;
        check_len("q̇", v, n)?;
        let shaped = out.nrows() == 2 * n && out.ncols() == 2 * n;
        let run = self.hessian_program().run_with(&[&[0.0], q], |o| {
            if !shaped || !guards_hold(&o, n * n, &self.guards) {
                return false;
            }
            out.fill(0.0);
            for i in 0..n {
                out[(i, n + i)] = 1.0;
                for j in 0..n {
                    out[(n + i, j)] = o.get(j * n + i);
                }
            }
            out.iter().all(|x| x.is_finite())
        })?;
        if run {
            return Ok(());
        }
        self.dual.jacobian(t, q, v, out)
    }
}
