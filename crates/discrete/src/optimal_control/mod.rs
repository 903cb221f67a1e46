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
//! and Hessian of each φ_k from core's [`ad`](noether_core::ad); the Hessian of 𝓛 is the KKT matrix
//! [[∇²_zz 𝓛, ∇cᵀ], [∇c, 0]], which with the unknowns ordered node by node (q_k, λ_k, u_k) is banded
//! (half-bandwidth 4n + m − 1 for n coordinates and m inputs) and factored by core's banded LU with
//! partial pivoting: O(N (4n + m)³) per iteration, as the boundary-value solver.
//!
//! Bounds lower ≤ u_k ≤ upper ([`OptimalControl::input_bounds`]) turn the KKT equations into
//! inequalities: the problem is then solved by SQP, each quadratic subproblem by Clarabel's
//! interior-point method on the same sparse structure, globalised by an ℓ₁ merit line search and
//! finished by Newton on the active set to the same rounding floor (the `sqp` module's docs say how
//! and why). SQP also solves unbounded problems from guesses where Newton alone diverges (infinite
//! bounds). The double integrator with |u| ≤ U has a closed form as well (u saturated near both
//! ends, a ramp between), met at second order (`tests/discrete/bounded_control.rs`).
//!
//! End positions can be left free ([`OptimalControl::free_end_positions`]: a reaction wheel's angle
//! after a slew). A coordinate whose momentum the discrete equations conserve (cyclic, and no force
//! on it: a spacecraft's attitude angle about a fixed axis) makes one of them redundant, and the KKT
//! matrix singular; when Newton meets that singular matrix the solver looks for such coordinates at
//! the guess (the bounded solve looks first), drops their last equation and starts again, or refuses
//! ends that ask the conserved momentum to change.
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

mod kkt;
mod sqp;

pub use sqp::{Failure, NoOptimalPath};

use crate::lagrangian::DiscreteLagrangian;
use kkt::Kkt;
use nalgebra::DVector;
use noether_core::error::{check_finite, check_len};
use noether_core::{Error, Newton, NewtonInfo, Result, Scalar};
use sqp::InputBounds;

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

// The quadratures of a continuous Lagrangian ([`Midpoint`](crate::Midpoint),
// [`Trapezoidal`](crate::Trapezoidal)) implement `DiscreteActuated` with their rule's forces
// (`quadrature_rule!` in quadrature.rs).

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
    /// Node positions q_k (q₀ as given, q_N too but for its free entries, `free_end_positions`).
    pub q: Vec<DVector<f64>>,
    /// Inputs u_k on [t_k, t_{k+1}], k = 0..N−1.
    pub u: Vec<DVector<f64>>,
    /// Multipliers λ_k of the discrete equations c_k, k = 0..=N (the discrete adjoint).
    pub multipliers: Vec<DVector<f64>>,
    /// The discrete cost J_d.
    pub cost: f64,
    /// Statistics of the Newton solve (with input bounds: of the polishing solve on the active set).
    pub newton: NewtonInfo,
    /// SQP iterations before the polishing solve (0 without input bounds).
    pub sqp_iterations: usize,
}

/// Discrete mechanics and optimal control: the path and piecewise-constant inputs that minimise a
/// running cost between given states, subject to the forced discrete Euler-Lagrange equations (see the
/// [module docs](self)).
pub struct OptimalControl<M, C> {
    model: M,
    cost: C,
    newton: Newton,
    bounds: Option<InputBounds>,
    free_end: Vec<usize>,
}

impl<M: DiscreteActuated, C: RunningCost> OptimalControl<M, C> {
    /// The problem of the discrete actuated model `model` (e.g. [`Midpoint`](crate::Midpoint) of an
    /// [`Actuated`](noether_core::control::Actuated) Lagrangian) and the running cost `cost`.
    pub fn new(model: M, cost: C) -> Self {
        OptimalControl {
            model,
            cost,
            newton: Newton::default()
                .residual_tolerance(1e-15)
                .and_then(|n| n.max_iterations(100))
                .map(|n| n.reuse_jacobian(false))
                .expect("valid settings"),
            bounds: None,
            free_end: Vec::new(),
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

    /// Bounds lower ≤ u_k ≤ upper on the inputs, componentwise and the same at every step (±∞ for an
    /// unbounded side). The problem is then solved by SQP with Clarabel's interior-point method for the
    /// quadratic subproblems, an ℓ₁ merit line search, and a polishing Newton solve on the active set
    /// (see [`NoOptimalPath`] for its failures); the guess's inputs are clipped into the bounds. SQP
    /// is also the globalised solver of an unbounded problem whose Newton solve diverges: give infinite
    /// bounds. Wrong lengths are [`Error::Dimension`]; a NaN, a lower bound above its upper one, or
    /// an infinite bound of the wrong sign is [`Error::InvalidParameter`].
    pub fn input_bounds(mut self, lower: &[f64], upper: &[f64]) -> Result<Self> {
        let m = self.model.inputs();
        check_len("lower input bounds", lower, m)?;
        check_len("upper input bounds", upper, m)?;
        for (&lo, &hi) in lower.iter().zip(upper) {
            for (name, value, ok) in [
                ("lower input bound", lo, lo < f64::INFINITY),
                ("upper input bound", hi, hi > f64::NEG_INFINITY),
            ] {
                if value.is_nan() || !ok {
                    return Err(Error::InvalidParameter {
                        name,
                        value,
                        reason: "a number, −∞ allowed below and +∞ above",
                    });
                }
            }
            if lo > hi {
                return Err(Error::InvalidParameter {
                    name: "lower input bound",
                    value: lo,
                    reason: "at most the upper bound",
                });
            }
        }
        self.bounds = Some(InputBounds {
            lower: lower.to_vec(),
            upper: upper.to_vec(),
        });
        Ok(self)
    }

    /// Leaves the end positions of the coordinates `components` free: q_N's entries there become
    /// unknowns (the end position given to `solve` holds their guess), the end velocities still hold.
    /// For a coordinate whose end value does not matter — a reaction wheel's angle after a slew, the
    /// cart's position after a swing-up. The end momenta p_N = ∂L/∂q̇ are taken at the given end
    /// position, so they must not depend on the free entries (as at rest for an L quadratic in q̇, or
    /// for cyclic coordinates); `solve` checks this at the solution and reports
    /// [`Error::Unsupported`] otherwise. A component ≥ n or repeated is [`Error::InvalidParameter`].
    pub fn free_end_positions(mut self, components: &[usize]) -> Result<Self> {
        let n = self.model.dof();
        for (i, &c) in components.iter().enumerate() {
            if c >= n || components[..i].contains(&c) {
                return Err(Error::InvalidParameter {
                    name: "free end position component",
                    value: c as f64,
                    reason: "a coordinate index below the number of coordinates, each once",
                });
            }
        }
        self.free_end = components.to_vec();
        Ok(self)
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
    /// replaced by the ends, but for the free end positions, whose guess the last holds) and `inputs` (N input vectors), N ≥ 1 steps. Wrong lengths are
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
        self.check(t0, (start, end), t1, nodes, inputs)?;
        let (m, steps) = (self.model.inputs(), inputs.len());
        let mut kkt = Kkt::new(self, (t0, t1), (start, end), steps)?;
        let mut x = kkt.initial_unknowns(nodes, inputs);
        let (info, iterations) = match &self.bounds {
            // A conserved momentum makes the KKT matrix singular: looked for only then (its test
            // costs a Hessian), and the solve restarted without the redundant equation.
            None => {
                let mut y = x.clone();
                match self.newton.solve(&mut kkt, &mut y) {
                    Err(Error::SingularMatrix { .. }) if kkt.drop_conserved(&x)? => {
                        (self.newton.solve(&mut kkt, &mut x)?, 0)
                    }
                    solved => {
                        x = y;
                        (solved?, 0)
                    }
                }
            }
            Some(bounds) => {
                kkt.drop_conserved(&x)?;
                for k in 0..steps {
                    let j = kkt.u_index(k);
                    for (i, u) in x[j..j + m].iter_mut().enumerate() {
                        *u = u.clamp(bounds.lower[i], bounds.upper[i]);
                    }
                }
                sqp::solve(&mut kkt, &mut x, bounds, &self.newton)?
            }
        };
        if kkt
            .end_momenta_change(&x, t1, end.1)?
            .is_some_and(|change| change > 1e-12)
        {
            return Err(Error::Unsupported(
                "free end positions on which the end momenta p = ∂L/∂q̇ depend",
            ));
        }
        Ok(kkt.path(&x, info, iterations))
    }

    /// The errors of [`solve_from`](Self::solve_from)'s data.
    fn check(
        &self,
        t0: f64,
        ends: (Endpoint<'_>, Endpoint<'_>),
        t1: f64,
        nodes: &[Vec<f64>],
        inputs: &[Vec<f64>],
    ) -> Result<()> {
        let (n, m) = (self.model.dof(), self.model.inputs());
        let (start, end) = ends;
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
        Ok(())
    }
}
