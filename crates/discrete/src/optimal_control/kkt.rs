//! The KKT system of an optimal-control problem: the terms φ_k of 𝓛 step by step, their gradients and
//! Hessians by core's AD, assembled banded in the unknowns ordered node by node (q_k, λ_k, u_k).

use super::{DiscreteActuated, Endpoint, OptimalControl, OptimalPath, RunningCost};
use crate::lagrangian::{difference_quotient, midpoint, Scratch};
use nalgebra::{DMatrix, DVector};
use noether_core::ad::{self, Block, Field};
use noether_core::linalg::{Banded, BandedLu};
use noether_core::{Error, NewtonInfo, NewtonSystem, Result, Scalar};
use num_dual::Dual;

/// The term φ_k of one step as an AD field of its window (q_k, q_{k+1}, u_k, λ_k, λ_{k+1}) (x block).
struct Stage<'a, M, C> {
    model: &'a M,
    cost: &'a C,
    n: usize,
    m: usize,
    t0: f64,
    h: f64,
}

impl<M: DiscreteActuated, C: RunningCost> Field for Stage<'_, M, C> {
    fn eval<D: Scalar>(&self, _t: D, w: &[D], _y: &[D]) -> D {
        let (n, h) = (self.n, self.h);
        let (qa, rest) = w.split_at(n);
        let (qb, rest) = rest.split_at(n);
        let (u, rest) = rest.split_at(self.m);
        let (la, lb) = rest.split_at(n);
        let (mid, v) = (midpoint(qa, qb), difference_quotient(qa, qb, D::from(h)));
        let running = self.cost.cost(D::from(self.t0 + 0.5 * h), &mid, &v, u) * h;
        // λ_k·D₁L_d + λ_{k+1}·D₂L_d: the derivative of L_d along (λ_k, λ_{k+1}).
        let xa = Scratch::<Dual<D, f64>>::new(n, |i| Dual::new(qa[i], la[i]));
        let xb = Scratch::<Dual<D, f64>>::new(n, |i| Dual::new(qb[i], lb[i]));
        let along = self
            .model
            .discrete_lagrangian(self.t0, Dual::from_re(D::from(h)), &xa, &xb)
            .eps;
        let (mut fm, mut fp) = (Scratch::filled(n, D::zero()), Scratch::filled(n, D::zero()));
        self.model
            .discrete_input_force(self.t0, h, qa, qb, u, &mut fm, &mut fp);
        if self.model.has_discrete_force() {
            let (mut gm, mut gp) = (Scratch::filled(n, D::zero()), Scratch::filled(n, D::zero()));
            self.model.discrete_force(self.t0, h, qa, qb, &mut gm, &mut gp);
            fm.iter_mut().zip(gm.iter()).for_each(|(f, g)| *f += *g);
            fp.iter_mut().zip(gp.iter()).for_each(|(f, g)| *f += *g);
        }
        let work = (0..n).fold(D::zero(), |s, i| s + la[i] * fm[i] + lb[i] * fp[i]);
        running + along + work
    }
}

/// The KKT system ∇𝓛 = 0 of one problem: the unknowns node by node, (q_k if interior, λ_k, u_k if
/// k < N), and the scratch of one step's window.
pub(super) struct Kkt<'a, M, C> {
    problem: &'a OptimalControl<M, C>,
    pub(super) n: usize,
    pub(super) m: usize,
    pub(super) steps: usize,
    t0: f64,
    h: f64,
    ends: [Vec<f64>; 2],
    momenta: [Vec<f64>; 2],
    /// Index of node k's first unknown.
    offsets: Vec<usize>,
    pub(super) dim: usize,
    window: Vec<f64>,
    grad: Vec<f64>,
    hess: DMatrix<f64>,
    lu: Option<BandedLu>,
    /// Inputs held at a value (global index, value): the active bounds of a polishing Newton solve.
    held: Vec<(usize, f64)>,
    /// The global index of each component of q_N that is an unknown (free end position).
    free_end: Vec<Option<usize>>,
    /// The multipliers λ_N^i held at 0 for the coordinates i whose momentum the discrete equations
    /// conserve ([`Kkt::drop_conserved`]).
    pub(super) conserved: Vec<usize>,
}

/// What the KKT matrix is called in its errors.
const KKT_MATRIX: &str = "KKT matrix of the optimal-control problem";

impl<'a, M: DiscreteActuated, C: RunningCost> Kkt<'a, M, C> {
    pub(super) fn new(
        problem: &'a OptimalControl<M, C>,
        (t0, t1): (f64, f64),
        ((qa, va), (qb, vb)): (Endpoint<'_>, Endpoint<'_>),
        steps: usize,
    ) -> Result<Self> {
        let (n, m) = (problem.model.dof(), problem.model.inputs());
        let (mut pa, mut pb) = (vec![0.0; n], vec![0.0; n]);
        problem.model.momenta(t0, qa, va, &mut pa)?;
        problem.model.momenta(t1, qb, vb, &mut pb)?;
        let mut offsets = Vec::with_capacity(steps + 1);
        let mut dim = 0;
        for k in 0..=steps {
            offsets.push(dim);
            dim += n + if k > 0 && k < steps { n } else { 0 } + if k < steps { m } else { 0 };
        }
        // The free components of q_N follow λ_N.
        let mut free_end = vec![None; n];
        for (i, &c) in problem.free_end.iter().enumerate() {
            free_end[c] = Some(dim + i);
        }
        dim += problem.free_end.len();
        let width = 4 * n + m;
        Ok(Kkt {
            problem,
            n,
            m,
            steps,
            t0,
            h: (t1 - t0) / steps as f64,
            ends: [qa.to_vec(), qb.to_vec()],
            momenta: [pa, pb],
            offsets,
            dim,
            window: vec![0.0; width],
            grad: vec![0.0; width],
            hess: DMatrix::zeros(width, width),
            lu: None,
            held: Vec::new(),
            free_end,
            conserved: Vec::new(),
        })
    }

    pub(super) fn interior(&self, k: usize) -> bool {
        k > 0 && k < self.steps
    }

    /// Global index of q_k (interior nodes only).
    pub(super) fn q_index(&self, k: usize) -> Option<usize> {
        self.interior(k).then(|| self.offsets[k])
    }

    pub(super) fn lambda_index(&self, k: usize) -> usize {
        self.offsets[k] + if self.interior(k) { self.n } else { 0 }
    }

    pub(super) fn u_index(&self, k: usize) -> usize {
        self.lambda_index(k) + self.n
    }

    /// The global index of entry `i` of step k's window (`None` for the fixed ends q₀, q_N, but for
    /// the free components of q_N).
    fn global(&self, k: usize, i: usize) -> Option<usize> {
        let (n, m) = (self.n, self.m);
        match i {
            i if i < n => self.q_index(k).map(|j| j + i),
            i if i < 2 * n => match self.q_index(k + 1) {
                Some(j) => Some(j + i - n),
                None => self.free_end[i - n],
            },
            i if i < 2 * n + m => Some(self.u_index(k) + i - 2 * n),
            i if i < 3 * n + m => Some(self.lambda_index(k) + i - 2 * n - m),
            i => Some(self.lambda_index(k + 1) + i - 3 * n - m),
        }
    }

    /// q_k at the unknowns `x` into `out`.
    fn q_into(&self, x: &[f64], k: usize, out: &mut [f64]) {
        match self.q_index(k) {
            Some(j) => out.copy_from_slice(&x[j..j + self.n]),
            None if k == 0 => out.copy_from_slice(&self.ends[0]),
            None => {
                out.copy_from_slice(&self.ends[1]);
                for (o, j) in out.iter_mut().zip(&self.free_end) {
                    if let Some(j) = *j {
                        *o = x[j];
                    }
                }
            }
        }
    }

    /// q_k at the unknowns `x`.
    fn q(&self, x: &[f64], k: usize) -> Vec<f64> {
        let mut q = vec![0.0; self.n];
        self.q_into(x, k, &mut q);
        q
    }

    /// Step k's window at the unknowns `x` into `self.window`.
    fn fill_window(&mut self, x: &[f64], k: usize) {
        let (n, m) = (self.n, self.m);
        let mut w = std::mem::take(&mut self.window);
        let (qa, rest) = w.split_at_mut(n);
        self.q_into(x, k, qa);
        self.q_into(x, k + 1, &mut rest[..n]);
        let (u, la, lb) = (self.u_index(k), self.lambda_index(k), self.lambda_index(k + 1));
        w[2 * n..2 * n + m].copy_from_slice(&x[u..u + m]);
        w[2 * n + m..3 * n + m].copy_from_slice(&x[la..la + n]);
        w[3 * n + m..].copy_from_slice(&x[lb..lb + n]);
        self.window = w;
    }

    fn stage(&self, k: usize) -> Stage<'a, M, C> {
        Stage {
            model: &self.problem.model,
            cost: &self.problem.cost,
            n: self.n,
            m: self.m,
            t0: self.t0 + k as f64 * self.h,
            h: self.h,
        }
    }

    /// The unknowns of the guess: interior nodes, inputs, zero multipliers.
    pub(super) fn initial_unknowns(&self, nodes: &[Vec<f64>], inputs: &[Vec<f64>]) -> Vec<f64> {
        let mut x = vec![0.0; self.dim];
        for k in 0..=self.steps {
            if let Some(j) = self.q_index(k) {
                x[j..j + self.n].copy_from_slice(&nodes[k]);
            }
            if k < self.steps {
                let j = self.u_index(k);
                x[j..j + self.m].copy_from_slice(&inputs[k]);
            }
        }
        for (c, j) in self.free_end.iter().enumerate() {
            if let Some(j) = *j {
                x[j] = nodes[self.steps][c];
            }
        }
        x
    }

    /// Whether the end momenta p_N, taken at the given end position, hold at the solved one `x`
    /// (free end positions): the relative change of p(t₁, q_N, q̇_N), `None` if nothing is free.
    pub(super) fn end_momenta_change(&self, x: &[f64], t1: f64, v_end: &[f64]) -> Result<Option<f64>> {
        if self.free_end.iter().all(Option::is_none) {
            return Ok(None);
        }
        let mut p = vec![0.0; self.n];
        self.problem
            .model
            .momenta(t1, &self.q(x, self.steps), v_end, &mut p)?;
        let scale = self.momenta[1].iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        let change = p
            .iter()
            .zip(&self.momenta[1])
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        Ok(Some(change / scale))
    }

    pub(super) fn path(&self, x: &[f64], newton: NewtonInfo, sqp_iterations: usize) -> OptimalPath {
        let (n, m) = (self.n, self.m);
        let u: Vec<_> = (0..self.steps)
            .map(|k| DVector::from_column_slice(&x[self.u_index(k)..self.u_index(k) + m]))
            .collect();
        OptimalPath {
            t: (0..=self.steps).map(|k| self.t0 + k as f64 * self.h).collect(),
            q: (0..=self.steps)
                .map(|k| DVector::from_vec(self.q(x, k)))
                .collect(),
            u,
            multipliers: (0..=self.steps)
                .map(|k| DVector::from_column_slice(&x[self.lambda_index(k)..self.lambda_index(k) + n]))
                .collect(),
            cost: self.cost(x),
            newton,
            sqp_iterations,
        }
    }

    /// The discrete cost J_d at the unknowns `x`.
    pub(super) fn cost(&self, x: &[f64]) -> f64 {
        (0..self.steps)
            .map(|k| {
                let (qa, qb) = (self.q(x, k), self.q(x, k + 1));
                let (mid, v) = (midpoint(&qa, &qb), difference_quotient(&qa, &qb, self.h));
                let t = self.t0 + (k as f64 + 0.5) * self.h;
                let u = self.u_index(k);
                self.problem.cost.cost(t, &mid, &v, &x[u..u + self.m]) * self.h
            })
            .sum()
    }

    /// ∇𝓛 at `x` into `r`: the step terms' gradients, and ±p at λ₀ and λ_N (the held inputs' rows
    /// as they are; [`NewtonSystem::residual`] replaces them).
    pub(super) fn gradient(&mut self, x: &[f64], r: &mut [f64]) {
        r.iter_mut().for_each(|ri| *ri = 0.0);
        for k in 0..self.steps {
            self.fill_window(x, k);
            let stage = self.stage(k);
            ad::gradient(&stage, 0.0, &self.window, &[], Block::X, &mut self.grad);
            for (i, g) in self.grad.iter().enumerate() {
                if let Some(j) = self.global(k, i) {
                    r[j] += g;
                }
            }
        }
        let (l0, ln) = (self.lambda_index(0), self.lambda_index(self.steps));
        for i in 0..self.n {
            r[l0 + i] += self.momenta[0][i];
            r[ln + i] -= self.momenta[1][i];
        }
    }

    /// The KKT matrix ∇²𝓛 at `x` from the step terms' Hessians, banded (half-bandwidth 4n + m − 1).
    pub(super) fn hessian(&mut self, x: &[f64]) -> Banded {
        let bw = (4 * self.n + self.m - 1).min(self.dim.saturating_sub(1));
        let mut kkt = Banded::zeros(self.dim, bw, bw);
        for k in 0..self.steps {
            self.fill_window(x, k);
            let stage = self.stage(k);
            ad::hessian(&stage, 0.0, &self.window, &[], Block::X, Block::X, &mut self.hess);
            for i in 0..self.window.len() {
                let Some(gi) = self.global(k, i) else { continue };
                for j in 0..self.window.len() {
                    if let Some(gj) = self.global(k, j) {
                        kkt.add(gi, gj, self.hess[(i, j)]);
                    }
                }
            }
        }
        kkt
    }

    /// The unknowns held fixed, with their values: held inputs, and the conserved momenta's λ_N^i at 0.
    fn fixed(&self) -> impl Iterator<Item = (usize, f64)> + '_ {
        self.held
            .iter()
            .copied()
            .chain(self.conserved.iter().map(|&j| (j, 0.0)))
    }

    /// Finds the coordinates i whose momentum the discrete equations conserve — a cyclic coordinate
    /// no force acts on, such as a spacecraft's yaw: then Σ_k c_k^i = p₀^i − p_N^i whatever the path
    /// (the D₁L_d + D₂L_d = h ∂L/∂q_i of each step vanish), one equation is implied by the others and
    /// the KKT matrix is singular. Such an i shows at the guess `x` as a sum of the rows ∇c_k^i that
    /// vanishes (to 1e-12 of their entries). Its last equation c_N^i is then dropped and λ_N^i held at
    /// 0 — unless p₀^i ≠ p_N^i: the ends ask the conserved momentum to change, and no path does
    /// ([`Error::InvalidParameter`] with the change). `true` when it found one.
    pub(super) fn drop_conserved(&mut self, x: &[f64]) -> Result<bool> {
        let h = self.hessian(x);
        let (kl, ku) = h.bandwidths();
        let mut is_lambda = vec![false; self.dim];
        for k in 0..=self.steps {
            let l = self.lambda_index(k);
            is_lambda[l..l + self.n].iter_mut().for_each(|b| *b = true);
        }
        let mut sum = vec![0.0; self.dim];
        for i in 0..self.n {
            sum.iter_mut().for_each(|s| *s = 0.0);
            let mut largest = 0.0_f64;
            for k in 0..=self.steps {
                let row = self.lambda_index(k) + i;
                for col in row.saturating_sub(kl)..=(row + ku).min(self.dim - 1) {
                    if !is_lambda[col] {
                        sum[col] += h.get(row, col);
                        largest = largest.max(h.get(row, col).abs());
                    }
                }
            }
            if largest == 0.0 || sum.iter().any(|s| s.abs() > 1e-12 * largest) {
                continue;
            }
            let change = self.momenta[1][i] - self.momenta[0][i];
            let scale = self.momenta[0][i].abs().max(self.momenta[1][i].abs()).max(1.0);
            if change.abs() > 1e-12 * scale {
                return Err(Error::InvalidParameter {
                    name: "change of a conserved momentum between the ends (p_N − p₀ of a cyclic, unforced coordinate)",
                    value: change,
                    reason: "zero: the discrete equations conserve this momentum",
                });
            }
            self.conserved.push(self.lambda_index(self.steps) + i);
        }
        Ok(!self.conserved.is_empty())
    }

    /// Holds the inputs at the global indices `held` at their values (rows u_j − value = 0 replace
    /// their stationarity conditions): the active bounds of a polishing solve.
    pub(super) fn hold(&mut self, held: Vec<(usize, f64)>) {
        self.held = held;
    }
}

impl<M: DiscreteActuated, C: RunningCost> NewtonSystem for Kkt<'_, M, C> {
    fn dim(&self) -> usize {
        self.dim
    }

    /// ∇𝓛, with u_j − value for a held input and λ_N^i for a conserved momentum.
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()> {
        self.gradient(x, r);
        for (j, value) in self.fixed() {
            r[j] = x[j] - value;
        }
        // A NaN or infinite entry is core Newton's to report (the model's non-finite result).
        Ok(())
    }

    /// The KKT matrix (a held input's row the unit row) and its banded LU.
    fn factor_jacobian(&mut self, x: &[f64]) -> Result<()> {
        self.lu = None;
        let mut kkt = self.hessian(x);
        let (kl, ku) = kkt.bandwidths();
        let fixed: Vec<usize> = self.fixed().map(|(j, _)| j).collect();
        for j in fixed {
            for c in j.saturating_sub(kl)..=(j + ku).min(self.dim - 1) {
                let v = kkt.get(j, c);
                kkt.add(j, c, f64::from(c == j) - v);
            }
        }
        self.lu = Some(kkt.factor().map_err(|e| match e {
            noether_core::linalg::FactorError::NonFinite => Error::NonFiniteResult {
                what: KKT_MATRIX,
                t: f64::NAN,
                component: None,
            },
            e => e.in_matrix(KKT_MATRIX),
        })?);
        Ok(())
    }

    fn solve(&mut self, rhs: &mut [f64]) -> Result<()> {
        let lu = self.lu.as_ref().ok_or(Error::Unsupported(
            "an optimal-control KKT solve before its factorisation",
        ))?;
        lu.solve(rhs);
        Ok(())
    }
}
