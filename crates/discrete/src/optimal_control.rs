//! Optimal control by discrete mechanics (DMOC: Junge, Marsden and Ober-Blöbaum, IFAC 2005;
//! Ober-Blöbaum, Junge and Marsden, *Discrete mechanics and optimal control: an analysis*, ESAIM: COCV
//! 17, 2011).
//!
//! The inputs u of an actuated model are held constant over each step (u_k on [t_k, t_{k+1}],
//! h = (t₁ − t₀)/N), and the path q₀, …, q_N between given ends is the one that minimises the discrete
//! cost (the midpoint rule of the running cost C)
//!
//! ```text
//! J_d = Σ_{k=0}^{N−1} h C(t_k + h/2, (q_k + q_{k+1})/2, (q_{k+1} − q_k)/h, u_k)
//! ```
//!
//! subject to the discrete Lagrange-d'Alembert equations, with the discrete forces f^±_k(q_k, q_{k+1},
//! u_k) of the quadrature ([`DiscreteActuated`]; the model's own forces Q included) and the momenta
//! p₀, p_N of the given end velocities by the continuous Legendre transform p = ∂L/∂q̇:
//!
//! ```text
//! c₀  = p₀ + D₁L_d(q₀, q₁) + f⁻₀ = 0,
//! c_k = D₂L_d(q_{k−1}, q_k) + f⁺_{k−1} + D₁L_d(q_k, q_{k+1}) + f⁻_k = 0,   k = 1, …, N−1,
//! c_N = D₂L_d(q_{N−1}, q_N) + f⁺_{N−1} − p_N = 0.
//! ```
//!
//! Its first-order (KKT) conditions are the stationary points of 𝓛 = J_d + Σ_k λ_k·c_k in the unknowns
//! (q₁, …, q_{N−1}, u₀, …, u_{N−1}, λ₀, …, λ_N), and 𝓛 is a sum of one term per step:
//!
//! ```text
//! 𝓛 = λ₀·p₀ − λ_N·p_N + Σ_k φ_k,
//! φ_k = h C(…, u_k) + ∂_ε L_d(q_k + ε λ_k, q_{k+1} + ε λ_{k+1}) + λ_k·f⁻_k + λ_{k+1}·f⁺_k,
//! ```
//!
//! each a generic function of its window (q_k, q_{k+1}, u_k, λ_k, λ_{k+1}): λ_k·D₁L_d + λ_{k+1}·D₂L_d is
//! the derivative of L_d along (λ_k, λ_{k+1}), one more dual layer. Newton on ∇𝓛 = 0 takes the gradient
//! and Hessian of each φ_k from core's [`ad`]; the Hessian of 𝓛 is the KKT matrix
//! [[∇²_zz 𝓛, ∇cᵀ], [∇c, 0]], which with the unknowns ordered node by node (q_k, λ_k, u_k) is banded
//! (half-bandwidth 4n + m − 1 for n coordinates and m inputs) and factored by core's banded LU with
//! partial pivoting: O(N (4n + m)³) per iteration, as the boundary-value solver.
//!
//! With C = uᵀRu the problem is the discrete minimum-effort problem. For the double integrator q̈ = u
//! the midpoint rule is exact for piecewise-constant inputs, and the discrete optimum from rest at 0 to
//! rest at 1 in time T has the closed form u_k = u(t_k + h/2)/(1 − (h/T)²), J_d = 12/(T(T² − h²)),
//! where u(t) = (6/T²)(1 − 2t/T), J = 12/T³ is the continuous one: second order in h
//! (`tests/discrete/optimal_control.rs`).
//!
//! ```
//! use noether_core::control::Actuated;
//! use noether_core::prelude::*;
//! use noether_discrete::optimal_control::{Effort, OptimalControl};
//! use noether_discrete::Midpoint;
//!
//! /// q̈ = u: L = ½ q̇², Q_u = u.
//! struct DoubleIntegrator;
//! impl Lagrangian for DoubleIntegrator {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, _q: &[D], v: &[D]) -> D { v[0] * v[0] * 0.5 }
//! }
//! impl Actuated for DoubleIntegrator {
//!     fn inputs(&self) -> usize { 1 }
//!     fn input_force<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], u: &[D], out: &mut [D]) {
//!         out[0] = u[0];
//!     }
//! }
//!
//! // From rest at 0 to rest at 1 in T = 2 with 20 steps: J_d = 12/(T (T² − h²)).
//! let problem = OptimalControl::new(Midpoint::new(DoubleIntegrator), Effort::new(vec![1.0])?);
//! let path = problem.solve(0.0, (&[0.0], &[0.0]), 2.0, (&[1.0], &[0.0]), 20)?;
//! let h: f64 = 0.1;
//! assert!((path.cost - 12.0 / (2.0 * (4.0 - h * h))).abs() < 1e-13);
//! # Ok::<(), noether_core::Error>(())
//! ```

use crate::lagrangian::{difference_quotient, midpoint, DiscreteLagrangian, Scratch};
use crate::quadrature::{midpoint_forces, trapezoidal_forces, FromLagrangian, Midpoint, Trapezoidal};
use nalgebra::{DMatrix, DVector};
use noether_core::ad::{self, Block, Field};
use noether_core::control::Actuated;
use noether_core::error::{check_finite, check_len};
use noether_core::linalg::{Banded, BandedLu};
use noether_core::{Error, Newton, NewtonInfo, NewtonSystem, Result, Scalar};
use num_dual::Dual;

/// A discrete Lagrangian with inputs: the discrete forces f⁻, f⁺ of inputs u held constant over a step,
/// by the same quadrature as L_d, and the continuous Legendre transform at the ends of a path.
pub trait DiscreteActuated: DiscreteLagrangian {
    /// Number of inputs m.
    fn inputs(&self) -> usize;

    /// The discrete input forces f⁻ (at q₀) and f⁺ (at q₁) of a step from (t₀, q₀) to (t₀ + h, q₁) with
    /// the inputs `u`, written into `minus` and `plus`; the model's own forces are
    /// [`discrete_force`](DiscreteLagrangian::discrete_force)'s.
    #[allow(clippy::too_many_arguments)] // one step's ends, its input and the two forces
    fn discrete_input_force<D: Scalar>(
        &self,
        t0: f64,
        h: f64,
        q0: &[D],
        q1: &[D],
        u: &[D],
        minus: &mut [D],
        plus: &mut [D],
    );

    /// The momenta p = ∂L/∂q̇ at (t, q, q̇): the boundary conditions of a path in velocities.
    fn momenta(&self, t: f64, q: &[f64], v: &[f64], p: &mut [f64]) -> Result<()>;
}

impl<L: Actuated> DiscreteActuated for Midpoint<L> {
    fn inputs(&self) -> usize {
        self.continuous().lagrangian().inputs()
    }

    /// f⁻ = f⁺ = (h/2) Q_u(t₀ + h/2, (q₀ + q₁)/2, (q₁ − q₀)/h, u).
    fn discrete_input_force<D: Scalar>(
        &self,
        t0: f64,
        h: f64,
        q0: &[D],
        q1: &[D],
        u: &[D],
        minus: &mut [D],
        plus: &mut [D],
    ) {
        let model = self.continuous().lagrangian();
        midpoint_forces(t0, h, (q0, q1), (minus, plus), |t, q, v, out| {
            model.input_force(t, q, v, u, out)
        });
    }

    fn momenta(&self, t: f64, q: &[f64], v: &[f64], p: &mut [f64]) -> Result<()> {
        self.continuous().momenta(t, q, v, p)
    }
}

impl<L: Actuated> DiscreteActuated for Trapezoidal<L> {
    fn inputs(&self) -> usize {
        self.continuous().lagrangian().inputs()
    }

    /// f⁻ = (h/2) Q_u(t₀, q₀, v, u), f⁺ = (h/2) Q_u(t₀ + h, q₁, v, u), v = (q₁ − q₀)/h.
    fn discrete_input_force<D: Scalar>(
        &self,
        t0: f64,
        h: f64,
        q0: &[D],
        q1: &[D],
        u: &[D],
        minus: &mut [D],
        plus: &mut [D],
    ) {
        let model = self.continuous().lagrangian();
        trapezoidal_forces(t0, h, (q0, q1), (minus, plus), |t, q, v, out| {
            model.input_force(t, q, v, u, out)
        });
    }

    fn momenta(&self, t: f64, q: &[f64], v: &[f64], p: &mut [f64]) -> Result<()> {
        self.continuous().momenta(t, q, v, p)
    }
}

/// A running cost C(t, q, q̇, u), written once over the scalar like L: the optimal-control solver
/// takes its first and second derivatives by dual numbers.
pub trait RunningCost {
    /// C(t, q, q̇, u).
    fn cost<D: Scalar>(&self, t: D, q: &[D], v: &[D], u: &[D]) -> D;

    /// The number of inputs the cost is written for, when it says (checked against the model's at
    /// solve time); `None` by default.
    fn inputs(&self) -> Option<usize> {
        None
    }
}

/// The control effort C = uᵀ R u with R = diag(r) positive: ∫ C dt is the classical minimum-energy
/// cost (∫ u² dt for one input of weight 1).
#[derive(Debug, Clone, PartialEq)]
pub struct Effort {
    weights: Vec<f64>,
}

impl Effort {
    /// The effort of weights r (one per input), each finite and positive, else
    /// [`Error::InvalidParameter`].
    pub fn new(weights: Vec<f64>) -> Result<Self> {
        if let Some(&w) = weights.iter().find(|w| !(w.is_finite() && **w > 0.0)) {
            return Err(Error::InvalidParameter {
                name: "effort weight",
                value: w,
                reason: "finite and positive",
            });
        }
        Ok(Effort { weights })
    }
}

impl RunningCost for Effort {
    fn inputs(&self) -> Option<usize> {
        Some(self.weights.len())
    }
    fn cost<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], u: &[D]) -> D {
        u.iter()
            .zip(&self.weights)
            .fold(D::zero(), |c, (ui, ri)| c + *ui * *ui * *ri)
    }
}

/// One end of a path: (q, q̇).
pub type Endpoint<'a> = (&'a [f64], &'a [f64]);

/// An optimal path of [`OptimalControl`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct OptimalPath {
    /// Node times t_k = t₀ + k h, k = 0..=N.
    pub t: Vec<f64>,
    /// Node positions q_k (q₀ and q_N as given).
    pub q: Vec<DVector<f64>>,
    /// Inputs u_k on [t_k, t_{k+1}], k = 0..N−1.
    pub u: Vec<DVector<f64>>,
    /// Multipliers λ_k of the discrete equations c_k, k = 0..=N (the discrete adjoint).
    pub multipliers: Vec<DVector<f64>>,
    /// The discrete cost J_d.
    pub cost: f64,
    /// Statistics of the Newton solve.
    pub newton: NewtonInfo,
}

/// Discrete mechanics and optimal control: the path and piecewise-constant inputs that minimise a
/// running cost between given states, subject to the forced discrete Euler-Lagrange equations (see the
/// [module docs](self)).
pub struct OptimalControl<M, C> {
    model: M,
    cost: C,
    newton: Newton,
}

impl<M: DiscreteActuated, C: RunningCost> OptimalControl<M, C> {
    /// The problem of the discrete actuated model `model` (e.g. [`Midpoint`] of an
    /// [`Actuated`] Lagrangian) and the running cost `cost`.
    pub fn new(model: M, cost: C) -> Self {
        OptimalControl {
            model,
            cost,
            newton: Newton::default()
                .residual_tolerance(1e-15)
                .and_then(|n| n.max_iterations(100))
                .map(|n| n.reuse_jacobian(false))
                .expect("valid settings"),
        }
    }

    /// The Newton settings of the KKT solve. The default asks for a residual of 1e-15 (at most 100
    /// iterations), so that Newton goes on to the rounding floor of the KKT matrix (core's stopping
    /// rule 3): its condition grows as 1/h², and the default 1e-12 stopped the double integrator at
    /// N = 100 after one correction with inputs 1e-13 off the closed form (3e-16 after the second).
    pub fn newton(mut self, newton: Newton) -> Self {
        self.newton = newton;
        self
    }

    /// The optimal path from (q, q̇) = `start` at `t0` to `end` at `t1` in `steps` steps, from the
    /// straight line between the ends with zero inputs.
    pub fn solve(
        &self,
        t0: f64,
        start: Endpoint<'_>,
        t1: f64,
        end: Endpoint<'_>,
        steps: usize,
    ) -> Result<OptimalPath> {
        check_len("start position", start.0, self.model.dof())?;
        check_len("end position", end.0, self.model.dof())?;
        let nodes: Vec<Vec<f64>> = (0..=steps)
            .map(|k| {
                let s = k as f64 / steps.max(1) as f64;
                start.0.iter().zip(end.0).map(|(a, b)| a + s * (b - a)).collect()
            })
            .collect();
        let inputs = vec![vec![0.0; self.model.inputs()]; steps];
        self.solve_from(t0, start, t1, end, &nodes, &inputs)
    }

    /// As [`solve`](Self::solve) from the guess `nodes` (N + 1 positions; the first and last are
    /// replaced by the ends) and `inputs` (N input vectors), N ≥ 1 steps. Wrong lengths are
    /// [`Error::Dimension`], non-finite data [`Error::NonFinite`], t₁ ≤ t₀
    /// [`Error::InvalidParameter`]; a singular KKT matrix [`Error::SingularMatrix`], no convergence
    /// [`Error::NewtonDiverged`].
    pub fn solve_from(
        &self,
        t0: f64,
        start: Endpoint<'_>,
        t1: f64,
        end: Endpoint<'_>,
        nodes: &[Vec<f64>],
        inputs: &[Vec<f64>],
    ) -> Result<OptimalPath> {
        let (n, m) = (self.model.dof(), self.model.inputs());
        if !t0.is_finite() {
            return Err(Error::InvalidParameter {
                name: "optimal-control start time t₀",
                value: t0,
                reason: "finite",
            });
        }
        if !(t1.is_finite() && t1 > t0) {
            return Err(Error::InvalidParameter {
                name: "optimal-control final time t₁",
                value: t1,
                reason: "finite and after t₀",
            });
        }
        if let Some(k) = self.cost.inputs().filter(|&k| k != m) {
            return Err(Error::Dimension {
                what: "inputs of the running cost",
                expected: m,
                got: k,
            });
        }
        let steps = inputs.len();
        if steps == 0 {
            return Err(Error::InvalidParameter {
                name: "optimal-control steps",
                value: 0.0,
                reason: "at least one step (one input vector)",
            });
        }
        if nodes.len() != steps + 1 {
            return Err(Error::Dimension {
                what: "optimal-control guess nodes (one more than the inputs)",
                expected: steps + 1,
                got: nodes.len(),
            });
        }
        for (what, x) in [
            ("start position", start.0),
            ("start velocity", start.1),
            ("end position", end.0),
            ("end velocity", end.1),
        ] {
            check_len(what, x, n)?;
            check_finite(what, x)?;
        }
        for q in nodes {
            check_len("optimal-control guess node", q, n)?;
            check_finite("optimal-control guess node", q)?;
        }
        for u in inputs {
            check_len("optimal-control guess inputs", u, m)?;
            check_finite("optimal-control guess inputs", u)?;
        }
        let mut kkt = Kkt::new(self, (t0, t1), (start, end), steps)?;
        let mut x = kkt.initial_unknowns(nodes, inputs);
        let info = self.newton.solve(&mut kkt, &mut x)?;
        Ok(kkt.path(&x, info))
    }
}

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
struct Kkt<'a, M, C> {
    problem: &'a OptimalControl<M, C>,
    n: usize,
    m: usize,
    steps: usize,
    t0: f64,
    h: f64,
    ends: [Vec<f64>; 2],
    momenta: [Vec<f64>; 2],
    /// Index of node k's first unknown.
    offsets: Vec<usize>,
    dim: usize,
    window: Vec<f64>,
    grad: Vec<f64>,
    hess: DMatrix<f64>,
    lu: Option<BandedLu>,
}

/// What the KKT matrix is called in its errors.
const KKT_MATRIX: &str = "KKT matrix of the optimal-control problem";

impl<'a, M: DiscreteActuated, C: RunningCost> Kkt<'a, M, C> {
    fn new(
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
        })
    }

    fn interior(&self, k: usize) -> bool {
        k > 0 && k < self.steps
    }

    /// Global index of q_k (interior nodes only).
    fn q_index(&self, k: usize) -> Option<usize> {
        self.interior(k).then(|| self.offsets[k])
    }

    fn lambda_index(&self, k: usize) -> usize {
        self.offsets[k] + if self.interior(k) { self.n } else { 0 }
    }

    fn u_index(&self, k: usize) -> usize {
        self.lambda_index(k) + self.n
    }

    /// The global index of entry `i` of step k's window (`None` for the fixed ends q₀, q_N).
    fn global(&self, k: usize, i: usize) -> Option<usize> {
        let (n, m) = (self.n, self.m);
        match i {
            i if i < n => self.q_index(k).map(|j| j + i),
            i if i < 2 * n => self.q_index(k + 1).map(|j| j + i - n),
            i if i < 2 * n + m => Some(self.u_index(k) + i - 2 * n),
            i if i < 3 * n + m => Some(self.lambda_index(k) + i - 2 * n - m),
            i => Some(self.lambda_index(k + 1) + i - 3 * n - m),
        }
    }

    /// q_k at the unknowns `x`.
    fn q<'x>(&'x self, x: &'x [f64], k: usize) -> &'x [f64] {
        match self.q_index(k) {
            Some(j) => &x[j..j + self.n],
            None if k == 0 => &self.ends[0],
            None => &self.ends[1],
        }
    }

    /// Step k's window at the unknowns `x` into `self.window`.
    fn fill_window(&mut self, x: &[f64], k: usize) {
        let (n, m) = (self.n, self.m);
        let mut w = std::mem::take(&mut self.window);
        w[..n].copy_from_slice(self.q(x, k));
        w[n..2 * n].copy_from_slice(self.q(x, k + 1));
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
    fn initial_unknowns(&self, nodes: &[Vec<f64>], inputs: &[Vec<f64>]) -> Vec<f64> {
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
        x
    }

    fn path(&self, x: &[f64], newton: NewtonInfo) -> OptimalPath {
        let (n, m) = (self.n, self.m);
        let u: Vec<_> = (0..self.steps)
            .map(|k| DVector::from_column_slice(&x[self.u_index(k)..self.u_index(k) + m]))
            .collect();
        let cost = (0..self.steps)
            .map(|k| {
                let (qa, qb) = (self.q(x, k), self.q(x, k + 1));
                let (mid, v) = (midpoint(qa, qb), difference_quotient(qa, qb, self.h));
                let t = self.t0 + (k as f64 + 0.5) * self.h;
                self.problem.cost.cost(t, &mid, &v, u[k].as_slice()) * self.h
            })
            .sum();
        OptimalPath {
            t: (0..=self.steps).map(|k| self.t0 + k as f64 * self.h).collect(),
            q: (0..=self.steps)
                .map(|k| DVector::from_column_slice(self.q(x, k)))
                .collect(),
            u,
            multipliers: (0..=self.steps)
                .map(|k| DVector::from_column_slice(&x[self.lambda_index(k)..self.lambda_index(k) + n]))
                .collect(),
            cost,
            newton,
        }
    }
}

impl<M: DiscreteActuated, C: RunningCost> NewtonSystem for Kkt<'_, M, C> {
    fn dim(&self) -> usize {
        self.dim
    }

    /// ∇𝓛: the step terms' gradients, and ±p at λ₀ and λ_N.
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()> {
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
        // A NaN or infinite entry is core Newton's to report (the model's non-finite result).
        Ok(())
    }

    /// The KKT matrix ∇²𝓛 from the step terms' Hessians, banded, and its LU.
    fn factor_jacobian(&mut self, x: &[f64]) -> Result<()> {
        self.lu = None;
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
