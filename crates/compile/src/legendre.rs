//! The Hamiltonian of a Lagrangian quadratic in the velocities, built on the graph: the Legendre
//! transform in closed form, with the linear solve unrolled, instead of a Newton iteration per call.
//!
//! Every mechanical Lagrangian has the form
//!
//! ```text
//! L(t, q, q̇) = ½ q̇ᵀ M(t, q) q̇ + a(t, q)·q̇ + L₀(t, q),
//! ```
//!
//! (kinetic energy, gyroscopic or magnetic terms, minus the potential). Then p = M q̇ + a, so
//! q̇ = M⁻¹(p − a), and
//!
//! ```text
//! H(t, q, p) = p·q̇ − L = ½ (p − a)ᵀ M⁻¹ (p − a) − L₀.
//! ```
//!
//! On the graph of L: M = ∂²L/∂q̇² (its rows by reverse accumulation from p), a = p at q̇ = 0 and
//! L₀ = L at q̇ = 0 (the graph rebuilt with q̇ set to zero, every term with a factor q̇ folding away);
//! then y = p − a, q̇ = M⁻¹y by the unrolled LDLᵀ solve of [`ldlt`], H = ½ y·q̇ − L₀,
//! and Hamilton's equations q̇ = ∂H/∂p (which is that q̇), ṗ = −∂H/∂q by reverse accumulation
//! through the solve. A Lagrangian is quadratic in q̇ exactly when M does not depend on q̇ — checked
//! on the graph; otherwise, and for comparisons of q̇ in L, compiling refuses
//! ([`Error::NotQuadratic`]) and `LegendreTransform`'s Newton path is the
//! one to use.

use crate::derive::{dependents, gradient};
use crate::euler_lagrange::{default_point, mass_rows};
use crate::graph::Id;
use crate::hamilton_equations::Checks;
use crate::trace::Recorded;
use crate::{ldlt, CompiledHamiltonEquations, Error, Result, UNROLL_MAX};
use noether_core::error::check_phase_point;
use noether_core::{HamiltonEquations, Lagrangian, LegendreTransform};

impl<L: Lagrangian> CompiledHamiltonEquations<LegendreTransform<L>> {
    /// Hamilton's equations of `lagrangian`'s Hamiltonian, built on the graph of L (see the
    /// [module docs](crate::legendre)), L recorded at a point chosen only for the branches it takes
    /// there (as [`CompiledEulerLagrange::new`](crate::CompiledEulerLagrange::new)). Falls back, where
    /// the compiled result is not usable, to `LegendreTransform` by dual numbers.
    ///
    /// Errors: [`Error::NotQuadratic`] for an L not quadratic in q̇ or that compares q̇; a dimension
    /// error above [`UNROLL_MAX`] degrees of freedom (the solve is unrolled).
    pub fn legendre(lagrangian: L) -> Result<Self> {
        let n = lagrangian.dof();
        let (q, v) = default_point(n);
        Self::legendre_at(lagrangian, 0.0, &q, &v)
    }

    /// [`legendre`](Self::legendre), L recorded at (t, q, q̇).
    pub fn legendre_at(lagrangian: L, t: f64, q: &[f64], v: &[f64]) -> Result<Self> {
        let n = lagrangian.dof();
        check_phase_point(n, t, q, v, "q̇")?;
        if n > UNROLL_MAX {
            return Err(Error::Core(noether_core::Error::Dimension {
                what: "degrees of freedom of a Legendre transform compiled (the solve is unrolled)",
                expected: UNROLL_MAX,
                got: n,
            }));
        }
        let mut r = Recorded::new(t, q, v, |t, q, v| lagrangian.lagrangian(t, q, v))?;
        let g = &mut r.rec.graph;
        let p = gradient(g, r.value, &r.v);
        let m = mass_rows(g, &p, &r.v);
        // Quadratic in q̇: M and the guards free of q̇.
        let checked: Vec<Id> = (m.iter().flatten().copied())
            .chain(r.rec.guards.iter().map(|g| g.node))
            .collect();
        let last = checked.iter().copied().max().unwrap_or(0);
        let on_v = dependents(g, last, &r.v);
        if checked.iter().any(|&x| on_v[x as usize]) {
            return Err(Error::NotQuadratic);
        }
        // a = p and L₀ = L at q̇ = 0; the inputs of q̇ then carry p.
        let zero = g.constant(0.0);
        let pairs: Vec<(Id, Id)> = r.v.iter().map(|&x| (x, zero)).collect();
        let mut at_rest = p.clone();
        at_rest.push(r.value);
        let at_rest = g.substitute(&at_rest, &pairs);
        let (a, l0) = (&at_rest[..n], at_rest[n]);
        let y: Vec<Id> = (0..n).map(|i| g.sub(r.v[i], a[i])).collect();
        let (x, d) = ldlt::solve(g, &m, &y);
        let yx: Vec<Id> = y.iter().zip(&x).map(|(&y, &x)| g.mul(y, x)).collect();
        let s = g.sum(yx);
        let half = g.scale(0.5, s);
        r.value = g.sub(half, l0);
        let checks = Checks {
            pivots: d,
            diagonal: (0..n).map(|i| m[i][i]).collect(),
            guards: r.rec.guards.clone(),
        };
        let system = HamiltonEquations::new(LegendreTransform::new(lagrangian));
        Ok(Self::assemble(system, r, checks, crate::Backend::Native))
    }
}

/// `LegendreTransform::new(l).compile()`: the same as
/// [`CompiledHamiltonEquations::legendre`], from the transform's Lagrangian.
impl<L: Lagrangian + Clone> crate::Compile for LegendreTransform<L> {
    type Compiled = CompiledHamiltonEquations<LegendreTransform<L>>;
    fn compile(self) -> Result<Self::Compiled> {
        CompiledHamiltonEquations::legendre(self.lagrangian().clone())
    }
}
