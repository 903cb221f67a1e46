//! Input bounds lower ≤ u_k ≤ upper: sequential quadratic programming (SQP) on the KKT structure, with
//! the quadratic subproblems solved by Clarabel (an interior-point solver for convex QPs), an ℓ₁ merit
//! line search, and a polishing Newton solve on the active set (Nocedal & Wright, *Numerical
//! Optimization*, 2nd ed., ch. 18; Fletcher's Sℓ₁QP for inconsistent linearisations).
//!
//! At the iterate z = (q₁, …, q_{N−1}, u₀, …, u_{N−1}) the subproblem in the step d is
//!
//! ```text
//! min ½ dᵀ P d + gᵀd   s.t.   c + J d = 0,   lower ≤ u + d_u ≤ upper,
//! ```
//!
//! with g = ∇J_d, c and J = ∇c read off ∇𝓛 and the KKT matrix at λ = 0 (𝓛 is linear in λ), and the
//! multipliers λ the least-squares ones of ∇J_d + Jᵀλ = 0 on the components no bound holds — they
//! depend on z alone (the subproblem's own multipliers inflate with any convexification, and through
//! W = ∇²_zz 𝓛 the next subproblem: measured, a loop that ran λ from 3e2 to 4e12 in three
//! iterations of the cart-pole swing-up). Clarabel needs P positive semidefinite:
//! P = W + ρJᵀJ where a moderate ρ makes it positive definite (W positive definite on the null space
//! of J, the second-order condition of a minimum), else the cost's curvature ∇²J_d + ρJᵀJ, a
//! Gauss-Newton step (`Subproblem::convexify`: on the swing-up the constraints' curvature λ·∇²c has
//! eigenvalues of ±8e3 against 5e-3 for the reduced Hessian, so the exact W would need ρ ~ 1e6 and a
//! P of condition 1e13). Where the linearisation admits no step within the bounds, the elastic
//! subproblem relaxes c + J d = 0 at the price ν‖c + J d‖₁.
//!
//! The step z + αd is accepted by Armijo's rule on the merit φ = J_d + μ‖c‖₁, μ ≥ ‖λ⁺‖∞ (λ⁺ the
//! subproblem's multipliers). Once the active set stays the same over two iterations (or the step is
//! small), the bounds active in the subproblem (multiplier above slack) are held and core Newton
//! solves the KKT system of the remaining unknowns to its rounding floor: the quadratic end game the
//! Gauss-Newton steps lack. Its result is accepted only if the held inputs' multipliers have the sign
//! of a minimum, the free inputs lie inside their bounds, and its cost is no higher than the merit
//! where SQP stands; otherwise SQP goes on (trying again after 2, 4, 8, … iterations).

use super::kkt::Kkt;
use super::{DiscreteActuated, RunningCost};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT};
use noether_core::linalg::Banded;
use noether_core::{Error, Newton, NewtonInfo, Result};

/// Why a bounded optimal-control problem has no solution path from this guess.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Failure {
    /// SQP came to rest where the discrete equations are still unmet, the least infeasible point its
    /// elastic subproblems find: no inputs within the bounds meet them nearby (for a linear model, as
    /// the double integrator, none at all).
    Infeasible,
    /// The line search found no decrease of the merit function along the step.
    NoDescent,
    /// No convergence within the iteration limit.
    IterationLimit,
    /// The quadratic subproblem solver stopped without a solution (numerical trouble).
    Subproblem,
}

/// A bounded optimal-control problem ([`OptimalControl::input_bounds`](super::OptimalControl::input_bounds))
/// not solved: why, after how many SQP iterations, and how far the discrete equations were from
/// being met (‖c‖∞).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error(
    "bounded optimal control not solved after {iterations} SQP iteration(s): {}; discrete equations \
     met to ‖c‖∞ = {violation:e}",
    describe(*failure)
)]
#[non_exhaustive]
pub struct NoOptimalPath {
    /// What went wrong.
    pub failure: Failure,
    /// SQP iterations performed.
    pub iterations: usize,
    /// ‖c‖∞ of the discrete equations at the last iterate.
    pub violation: f64,
}

fn describe(failure: Failure) -> &'static str {
    match failure {
        Failure::Infeasible => {
            "no inputs within the bounds meet the discrete equations near the least infeasible point \
             found: widen the bounds or lengthen the time"
        }
        Failure::NoDescent => "the merit line search found no decrease: try another guess",
        Failure::IterationLimit => "iteration limit reached: try another guess",
        Failure::Subproblem => "the quadratic subproblem solver failed",
    }
}

/// Bounds on the inputs, the same at every step (±∞ allowed).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct InputBounds {
    pub(super) lower: Vec<f64>,
    pub(super) upper: Vec<f64>,
}

/// One finite bound of one input: its global index, the bound, and +1 for an upper bound (−1 lower).
#[derive(Debug, Clone, Copy)]
struct Row {
    j: usize,
    bound: f64,
    sign: f64,
}

/// SQP iterations at most.
const MAX_ITERATIONS: usize = 200;
/// Armijo's sufficient-decrease fraction.
const ARMIJO: f64 = 1e-4;
/// The smallest step fraction of the line search.
const MIN_STEP: f64 = 1e-12;
/// First switch to the polishing solve: ‖d‖∞ ≤ this · max(1, ‖z‖∞); divided by 100 after a rejected
/// polish.
const SWITCH: f64 = 1e-6;

/// Newton iterations of a polishing solve at most (from close to the solution it needs a few).
const POLISH_ITERATIONS: usize = 30;

/// The unknowns' roles: which global indices are z (positions and inputs) and which λ.
struct Layout {
    z: Vec<usize>,
    lambda: Vec<usize>,
    /// Position in z of each global index (`usize::MAX` for a multiplier).
    z_pos: Vec<usize>,
    rows: Vec<Row>,
}

impl Layout {
    fn new<M: DiscreteActuated, C: RunningCost>(kkt: &Kkt<'_, M, C>, bounds: &InputBounds) -> Self {
        let (n, m) = (kkt.n, kkt.m);
        let mut lambda = Vec::new();
        let mut rows = Vec::new();
        for k in 0..=kkt.steps {
            lambda.extend(kkt.lambda_index(k)..kkt.lambda_index(k) + n);
            if k < kkt.steps {
                for i in 0..m {
                    let j = kkt.u_index(k) + i;
                    if bounds.upper[i].is_finite() {
                        rows.push(Row {
                            j,
                            bound: bounds.upper[i],
                            sign: 1.0,
                        });
                    }
                    if bounds.lower[i].is_finite() {
                        rows.push(Row {
                            j,
                            bound: bounds.lower[i],
                            sign: -1.0,
                        });
                    }
                }
            }
        }
        // A conserved momentum's λ_N^i stays 0 and its equation out (Kkt::drop_conserved).
        let mut z_pos = vec![0; kkt.dim];
        lambda.iter().for_each(|&j| z_pos[j] = usize::MAX);
        lambda.retain(|j| !kkt.conserved.contains(j));
        let z: Vec<usize> = (0..kkt.dim).filter(|&j| z_pos[j] != usize::MAX).collect();
        z.iter().enumerate().for_each(|(a, &j)| z_pos[j] = a);
        Layout {
            z,
            lambda,
            z_pos,
            rows,
        }
    }

    fn is_z(&self, j: usize) -> bool {
        self.z_pos[j] != usize::MAX
    }
}

/// Triplets (row, column, value) of a sparse matrix.
type Triplets = (Vec<usize>, Vec<usize>, Vec<f64>);

/// The subproblem's data at one iterate: g = ∇J_d, c, J, and the upper triangles of JᵀJ, of the cost's
/// Hessian ∇²J_d (`cost_curvature`) and of W = ∇²_zz 𝓛 at the multipliers chosen (`curvature`), read
/// off ∇𝓛 and ∇²𝓛 at λ = 0 (where they are g, c, ∇²J_d and J) and ∇²𝓛 at λ.
struct Subproblem {
    g: Vec<f64>,
    c: Vec<f64>,
    jac: Triplets,
    jtj: Triplets,
    cost_curvature: Triplets,
    curvature: Triplets,
}

/// The convexification P = W' + ρJᵀJ + δI of a subproblem, W' = W (`exact`) or ∇²J_d.
#[derive(Debug, Clone, Copy)]
struct Convexified {
    exact: bool,
    rho: f64,
    delta: f64,
}

/// The upper triangle of the zz block of `h` in z order.
fn zz_block(layout: &Layout, h: &Banded) -> Triplets {
    let (_, ku) = h.bandwidths();
    let mut w: Triplets = Default::default();
    for &i in &layout.z {
        for col in i..=(i + ku).min(h.dim() - 1) {
            let v = h.get(i, col);
            if v != 0.0 && layout.is_z(col) {
                w.0.push(layout.z_pos[i]);
                w.1.push(layout.z_pos[col]);
                w.2.push(v);
            }
        }
    }
    w
}

impl Subproblem {
    /// From ∇𝓛 (`r0`) and ∇²𝓛 (`h0`) at λ = 0.
    fn new(layout: &Layout, r0: &[f64], h0: &Banded) -> Self {
        let (kl, ku) = h0.bandwidths();
        let dim = h0.dim();
        let g: Vec<f64> = layout.z.iter().map(|&j| r0[j]).collect();
        let c = layout.lambda.iter().map(|&j| r0[j]).collect();
        let mut jac: Triplets = Default::default();
        let mut jtj: Triplets = Default::default();
        let mut row_entries = Vec::new();
        for (row, &l) in layout.lambda.iter().enumerate() {
            row_entries.clear();
            for col in l.saturating_sub(kl)..=(l + ku).min(dim - 1) {
                let v = h0.get(l, col);
                if v != 0.0 && layout.is_z(col) {
                    jac.0.push(row);
                    jac.1.push(layout.z_pos[col]);
                    jac.2.push(v);
                    row_entries.push((layout.z_pos[col], v));
                }
            }
            for &(a, va) in &row_entries {
                for &(b, vb) in row_entries.iter().filter(|(b, _)| *b >= a) {
                    jtj.0.push(a);
                    jtj.1.push(b);
                    jtj.2.push(va * vb);
                }
            }
        }
        let cost_curvature = zz_block(layout, h0);
        Subproblem {
            g,
            c,
            jac,
            jtj,
            curvature: cost_curvature.clone(),
            cost_curvature,
        }
    }

    /// The least-squares multipliers λ = argmin ‖g_F + J_Fᵀλ‖₂ over the components F of z not held at
    /// a bound (`free`): the solution of J_F J_Fᵀ λ = −J_F g_F, banded. They depend on z alone, not on
    /// the convexification of the last subproblem, whose multipliers a large δ inflates (and they on
    /// through λ·∇²c the next W: a loop that runs away). `None` when J_F J_Fᵀ is singular.
    fn least_squares_multipliers(&self, free: &[bool]) -> Option<Vec<f64>> {
        let neq = self.c.len();
        let mut columns: Vec<Vec<(usize, f64)>> = vec![Vec::new(); free.len()];
        for ((&row, &col), &v) in self.jac.0.iter().zip(&self.jac.1).zip(&self.jac.2) {
            if free[col] {
                columns[col].push((row, v));
            }
        }
        let band = columns
            .iter()
            .flat_map(|c| c.iter().flat_map(|a| c.iter().map(move |b| a.0.abs_diff(b.0))))
            .max()?;
        let mut normal = Banded::zeros(neq, band, band);
        let mut rhs = vec![0.0; neq];
        for (col, entries) in columns.iter().enumerate() {
            for &(a, va) in entries {
                rhs[a] -= va * self.g[col];
                for &(b, vb) in entries {
                    normal.add(a, b, va * vb);
                }
            }
        }
        let lu = normal.factor().ok()?;
        lu.solve(&mut rhs);
        Some(rhs)
    }

    /// P = W' + ρJᵀJ + δI positive definite by the banded LDLᵀ test: W' = W with the first ρ of
    /// (0, ρ₀, 10ρ₀, …, 10⁶ρ₀), ρ₀ = 10⁻³ max|W_ii| / max (JᵀJ)_ii, and δ = 0 — W positive definite on
    /// the null space of J (the second-order condition of a minimum) makes W + ρJᵀJ so for ρ large
    /// enough (Debreu's lemma), and the term ½ρ‖Jd + c‖² it adds to the subproblem's objective
    /// vanishes on its feasible set. Where that fails (W indefinite on the null space: far from a
    /// minimum, where the constraints' curvature λ·∇²c dominates), W' = ∇²J_d, the cost's curvature
    /// alone (a Gauss-Newton step: linear convergence, but a descent direction), with ρ likewise, and
    /// δ > 0 only if that fails too.
    fn convexify(&self, nz: usize) -> Convexified {
        let banded = |t: &Triplets, scale: f64, out: &mut Banded| {
            for ((&a, &b), &v) in t.0.iter().zip(&t.1).zip(&t.2) {
                out.add(a, b, scale * v);
                if a != b {
                    out.add(b, a, scale * v);
                }
            }
        };
        let band = [&self.curvature, &self.cost_curvature, &self.jtj]
            .iter()
            .flat_map(|t| t.0.iter().zip(&t.1).map(|(a, b)| b - a))
            .max()
            .unwrap_or(0);
        let diag = |t: &Triplets| {
            t.0.iter()
                .zip(&t.1)
                .zip(&t.2)
                .filter(|((a, b), _)| a == b)
                .fold(0.0_f64, |m, (_, v)| m.max(v.abs()))
        };
        let j_scale = diag(&self.jtj).max(f64::MIN_POSITIVE);
        let positive = |w: &Triplets, rho: f64, delta: f64| {
            let mut p = Banded::zeros(nz, band, band);
            banded(w, 1.0, &mut p);
            banded(&self.jtj, rho, &mut p);
            (0..nz).for_each(|a| p.add(a, a, delta));
            p.positive_definite()
        };
        for (exact, w) in [(true, &self.curvature), (false, &self.cost_curvature)] {
            let rho0 = 1e-3 * diag(w).max(1.0) / j_scale;
            if let Some(rho) = std::iter::once(0.0)
                .chain((0..=6).map(|k| rho0 * 10f64.powi(k)))
                .find(|&rho| positive(w, rho, 0.0))
            {
                return Convexified {
                    exact,
                    rho,
                    delta: 0.0,
                };
            }
        }
        let rho = 1e3 * diag(&self.cost_curvature).max(1.0) / j_scale;
        let mut delta = 1e-4 * diag(&self.cost_curvature).max(1.0);
        while !positive(&self.cost_curvature, rho, delta) && delta.is_finite() {
            delta *= 8.0;
        }
        Convexified {
            exact: false,
            rho,
            delta,
        }
    }

    /// The objective ½ dᵀPd + qᵀd, P = W' + ρJᵀJ + δI (W' by `convex`) and q = g + ρJᵀc, over d and
    /// `ns` elastic variables of weight ν = `elastic` each.
    fn objective(
        &self,
        nz: usize,
        ns: usize,
        convex: Convexified,
        elastic: f64,
    ) -> (CscMatrix<f64>, Vec<f64>) {
        let Convexified { exact, rho, delta } = convex;
        let (mut pi, mut pj, mut pv) = if exact {
            self.curvature.clone()
        } else {
            self.cost_curvature.clone()
        };
        pi.extend(self.jtj.0.iter().copied().chain(0..nz));
        pj.extend(self.jtj.1.iter().copied().chain(0..nz));
        pv.extend(
            self.jtj
                .2
                .iter()
                .map(|v| rho * v)
                .chain(std::iter::repeat_n(delta, nz)),
        );
        let p = CscMatrix::new_from_triplets(nz + ns, nz + ns, pi, pj, pv);
        let mut q = self.g.clone();
        for ((&row, &col), &v) in self.jac.0.iter().zip(&self.jac.1).zip(&self.jac.2) {
            q[col] += rho * v * self.c[row];
        }
        q.extend(std::iter::repeat_n(elastic, ns));
        (p, q)
    }

    /// The constraints A (d, s⁺, s⁻) + slack = b with their cones: J d − s⁺ + s⁻ = −c (zero cone),
    /// then the bounds sign·(u + d_u) ≤ sign·bound and −s± ≤ 0 (nonnegative cone); `ns` = 0 without
    /// elastic variables.
    fn constraints(
        &self,
        layout: &Layout,
        x: &[f64],
        ns: usize,
    ) -> (CscMatrix<f64>, Vec<f64>, Vec<SupportedConeT<f64>>) {
        let (nz, neq, nb) = (layout.z.len(), layout.lambda.len(), layout.rows.len());
        let (mut ai, mut aj, mut av) = self.jac.clone();
        let mut b: Vec<f64> = self.c.iter().map(|c| -c).collect();
        if ns > 0 {
            for l in 0..neq {
                ai.extend([l, l, neq + nb + l, neq + nb + neq + l]);
                aj.extend([nz + l, nz + neq + l, nz + l, nz + neq + l]);
                av.extend([-1.0, 1.0, -1.0, -1.0]);
            }
        }
        for (k, row) in layout.rows.iter().enumerate() {
            ai.push(neq + k);
            aj.push(layout.z_pos[row.j]);
            av.push(row.sign);
            b.push(row.sign * (row.bound - x[row.j]));
        }
        b.extend(std::iter::repeat_n(0.0, ns));
        let a = CscMatrix::new_from_triplets(neq + nb + ns, nz + ns, ai, aj, av);
        let mut cones = vec![SupportedConeT::ZeroConeT(neq)];
        if nb + ns > 0 {
            cones.push(SupportedConeT::NonnegativeConeT(nb + ns));
        }
        (a, b, cones)
    }

    /// Clarabel's solution of the subproblem with P = W' + ρJᵀJ + δI: the step d, the new
    /// multipliers λ⁺ (Clarabel's for c + J d = s, s the elastic variable), and which bounds it holds
    /// active. Without `elastic`, s = 0; with the weight ν, s = s⁺ − s⁻ (s± ≥ 0) is free at the cost
    /// ν 1ᵀ(s⁺ + s⁻): the ℓ₁ subproblem that stays feasible where the linearisation is inconsistent
    /// (Fletcher's Sℓ₁QP, SNOPT's elastic mode).
    fn solve(
        &self,
        layout: &Layout,
        x: &[f64],
        convex: Convexified,
        elastic: Option<f64>,
    ) -> std::result::Result<Step, Failure> {
        let (nz, neq, nb) = (layout.z.len(), layout.lambda.len(), layout.rows.len());
        let ns = if elastic.is_some() { 2 * neq } else { 0 };
        let (p, q) = self.objective(nz, ns, convex, elastic.unwrap_or(0.0));
        let (a, b, cones) = self.constraints(layout, x, ns);
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .tol_gap_abs(1e-10)
            .tol_gap_rel(1e-10)
            .tol_feas(1e-10)
            .build()
            .map_err(|_| Failure::Subproblem)?;
        let mut solver =
            DefaultSolver::new(&p, &q, &a, &b, &cones, settings).map_err(|_| Failure::Subproblem)?;
        solver.solve();
        let s = &solver.solution;
        match s.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => {
                let d = s.x[..nz].to_vec();
                let mut residual = self.c.clone();
                for ((&row, &col), &v) in self.jac.0.iter().zip(&self.jac.1).zip(&self.jac.2) {
                    residual[row] += v * d[col];
                }
                Ok(Step {
                    elastic: ns > 0,
                    lambda: s.z[..neq].to_vec(),
                    linear_violation: residual.iter().map(|r| r.abs()).sum(),
                    d,
                    active: (0..nb).map(|k| s.z[neq + k] > s.s[neq + k]).collect(),
                })
            }
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => Err(Failure::Infeasible),
            _ => Err(Failure::Subproblem),
        }
    }
}

/// A subproblem's solution: the step, the new multipliers, ‖c + J d‖₁, and which bounds it holds
/// active.
struct Step {
    d: Vec<f64>,
    /// Whether it solved the elastic subproblem.
    elastic: bool,
    lambda: Vec<f64>,
    linear_violation: f64,
    active: Vec<bool>,
}

fn max_abs(v: impl IntoIterator<Item = f64>) -> f64 {
    v.into_iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// The subproblem at `x`: ∇𝓛 and ∇²𝓛 at λ = 0 give g, c, J and ∇²J_d; the multipliers are then set
/// to the least-squares ones of the components `free` (zero if J_F J_Fᵀ is singular) and W is ∇²_zz 𝓛
/// there.
fn subproblem<M: DiscreteActuated, C: RunningCost>(
    kkt: &mut Kkt<'_, M, C>,
    x: &mut [f64],
    layout: &Layout,
    free: &[bool],
    r: &mut [f64],
) -> Result<Subproblem> {
    layout.lambda.iter().for_each(|&j| x[j] = 0.0);
    kkt.gradient(x, r);
    if let Some(j) = r.iter().position(|v| !v.is_finite()) {
        return Err(Error::NonFiniteResult {
            what: "gradient of the optimal-control Lagrangian",
            t: f64::NAN,
            component: Some(j),
        });
    }
    let mut sub = Subproblem::new(layout, r, &kkt.hessian(x));
    if let Some(lambda) = sub.least_squares_multipliers(free) {
        layout.lambda.iter().zip(&lambda).for_each(|(&j, &l)| x[j] = l);
        sub.curvature = zz_block(layout, &kkt.hessian(x));
    }
    Ok(sub)
}

/// Armijo's backtracking on the ℓ₁ merit φ = J_d + μ‖c‖₁ from `x` along `step` (z only): the step
/// fraction α taken, with `x` moved, or `None` below [`MIN_STEP`] (`x` unchanged). The directional
/// derivative of φ along d is at most gᵀd − μ(‖c‖₁ − ‖c + J d‖₁).
fn line_search<M: DiscreteActuated, C: RunningCost>(
    kkt: &mut Kkt<'_, M, C>,
    x: &mut [f64],
    layout: &Layout,
    (sub, step): (&Subproblem, &Step),
    (mu, start): (f64, f64),
) -> Option<f64> {
    let c1: f64 = sub.c.iter().map(|c| c.abs()).sum();
    let slope =
        sub.g.iter().zip(&step.d).map(|(g, d)| g * d).sum::<f64>() - mu * (c1 - step.linear_violation);
    let (mut trial, mut r) = (x.to_vec(), vec![0.0; x.len()]);
    let mut alpha = 1.0;
    while alpha >= MIN_STEP {
        for (a, &j) in layout.z.iter().enumerate() {
            trial[j] = x[j] + alpha * step.d[a];
        }
        kkt.gradient(&trial, &mut r);
        let merit = kkt.cost(&trial) + mu * layout.lambda.iter().map(|&j| r[j].abs()).sum::<f64>();
        if merit.is_finite() && merit <= start + ARMIJO * alpha * slope.min(0.0) {
            layout.z.iter().for_each(|&j| x[j] = trial[j]);
            return Some(alpha);
        }
        alpha *= 0.5;
    }
    None
}

/// Solves the bounded problem from `x` (inputs already inside the bounds): SQP, then the polishing
/// Newton solve `newton` on the active set. Returns the polish's statistics and the SQP iterations.
pub(super) fn solve<M: DiscreteActuated, C: RunningCost>(
    kkt: &mut Kkt<'_, M, C>,
    x: &mut [f64],
    bounds: &InputBounds,
    newton: &Newton,
) -> Result<(NewtonInfo, usize)> {
    let layout = Layout::new(kkt, bounds);
    let mut r = vec![0.0; kkt.dim];
    let (mut mu, mut switch, mut violation) = (0.0_f64, SWITCH, f64::NAN);
    let mut free = vec![true; layout.z.len()];
    let (mut last_active, mut next_try, mut wait) = (Vec::new(), 0, 2);
    let fail = |failure, iterations, violation| -> Error {
        crate::Error::from(NoOptimalPath {
            failure,
            iterations,
            violation,
        })
        .into()
    };
    for iteration in 1..=MAX_ITERATIONS {
        let sub = subproblem(kkt, x, &layout, &free, &mut r)?;
        violation = max_abs(sub.c.iter().copied());
        let convex = sub.convexify(layout.z.len());
        // An inconsistent linearisation: the elastic subproblem with the weight μ ≥ 100 (1 + ‖g‖∞).
        let step = match sub.solve(&layout, x, convex, None) {
            Err(Failure::Infeasible) => {
                mu = mu.max(1e2 * (1.0 + max_abs(sub.g.iter().copied())));
                sub.solve(&layout, x, convex, Some(mu))
            }
            other => other,
        }
        .map_err(|f| fail(f, iteration, violation))?;
        let scale = max_abs(layout.z.iter().map(|&j| x[j])).max(1.0);
        let small = max_abs(step.d.iter().copied()) <= switch * scale;
        // At rest with the discrete equations still unmet: a stationary point of the infeasibility.
        if small && step.elastic && violation > switch * scale {
            return Err(fail(Failure::Infeasible, iteration, violation));
        }
        mu = mu.max(1.1 * max_abs(step.lambda.iter().copied()) + 1e-12);
        let start = kkt.cost(x) + mu * sub.c.iter().map(|c| c.abs()).sum::<f64>();
        // Polish when the step is small, or early once the active set stays (backing off after a
        // rejected try: 2, 4, 8, … iterations).
        if small || (step.active == last_active && iteration >= next_try) {
            match polish(kkt, x, &layout, &step, newton, start) {
                Some(info) => return Ok((info, iteration)),
                None if small => switch /= 100.0,
                None => (next_try, wait) = (iteration + wait, 2 * wait),
            }
        }
        free.iter_mut().for_each(|f| *f = true);
        for (row, &active) in layout.rows.iter().zip(&step.active) {
            free[layout.z_pos[row.j]] &= !active;
        }
        line_search(kkt, x, &layout, (&sub, &step), (mu, start))
            .ok_or_else(|| fail(Failure::NoDescent, iteration, violation))?;
        last_active = step.active;
    }
    Err(fail(Failure::IterationLimit, MAX_ITERATIONS, violation))
}

/// Holds the bounds active in `step`, solves the KKT system of the rest by Newton from `x`, and
/// checks the result (module docs). On success `x` is the solution; otherwise (`None`: Newton failed,
/// or the active set was not the optimal one) `x` is unchanged.
fn polish<M: DiscreteActuated, C: RunningCost>(
    kkt: &mut Kkt<'_, M, C>,
    x: &mut [f64],
    layout: &Layout,
    step: &Step,
    newton: &Newton,
    ceiling: f64,
) -> Option<NewtonInfo> {
    let mut held: Vec<(usize, f64)> = layout
        .rows
        .iter()
        .zip(&step.active)
        .filter(|(_, a)| **a)
        .map(|(row, _)| (row.j, row.bound))
        .collect();
    held.dedup_by_key(|(j, _)| *j);
    let mut y = x.to_vec();
    kkt.hold(held.clone());
    let capped = (*newton)
        .max_iterations(newton.get_max_iterations().min(POLISH_ITERATIONS))
        .ok()?;
    let solved = capped.solve(kkt, &mut y);
    kkt.hold(Vec::new());
    let info = solved.ok()?;
    // The held inputs' multipliers −sign·∂𝓛/∂u_j ≥ 0; the free inputs inside their bounds.
    let mut r = vec![0.0; kkt.dim];
    kkt.gradient(&y, &mut r);
    let scale = max_abs(layout.lambda.iter().map(|&j| y[j])).max(1.0);
    for row in &layout.rows {
        let is_held = held.iter().any(|&(j, b)| j == row.j && b == row.bound);
        let ok = if is_held {
            -row.sign * r[row.j] >= -1e-8 * scale
        } else {
            row.sign * (y[row.j] - row.bound) <= 1e-9 * row.bound.abs().max(1.0)
        };
        if !ok {
            return None;
        }
    }
    // A stationary point no better than where SQP stands (by the merit) is not the minimum sought.
    if kkt.cost(&y) > ceiling + 1e-12 * ceiling.abs() {
        return None;
    }
    x.copy_from_slice(&y);
    Some(info)
}
