//! Störmer-Verlet for a [`Mechanical`] system, L = ½ q̇ᵀMq̇ − V(q) with damping Q = −C q̇, in
//! position-momentum form: the trapezoidal variational integrator, no Newton.
//!
//! The trapezoidal discrete Lagrangian `L_d = (h/2)[L(q₀, v) + L(q₁, v)]`, v = (q₁ − q₀)/h, with
//! discrete damping forces f⁻ = f⁺ = −(h/2) C v, gives a step that is linear in v:
//!
//! ```text
//! (M + (h/2) C) v = p_k − (h/2) ∇V(q_k),     q_{k+1} = q_k + h v,     p_{k+1} = M v − (h/2) ∇V(q_{k+1}) − (h/2) C v.
//! ```
//!
//! - Without damping (C = 0) this is velocity Verlet, kick-drift-kick on the split q̇ = M⁻¹p,
//!   ṗ = −∇V(q): p½ = p_k − (h/2)∇V(q_k), q_{k+1} = q_k + h M⁻¹p½, p_{k+1} = p½ − (h/2)∇V(q_{k+1}),
//!   and the step *is* core's [`StormerVerlet`] on the system (the one Störmer-Verlet of noether;
//!   one gradient per step, ∇V(q_{k+1}) reused by the next step).
//! - With damping the step above is solved with a factor of M + (h/2)C computed once per step size
//!   (the discrete Lagrange-d'Alembert principle; it reduces to the first case at C = 0).

use crate::flow::signed_step;
use crate::mechanical::{LocalPotential, Mass, Mechanical};
use noether_core::integrators::composition::step_forward;
use noether_core::integrators::{SignedStepper, StormerVerlet};
use noether_core::linalg::{self, DenseFactor};
use noether_core::{Error, Momenta, Result, State, StepInfo, Stepper};

/// Störmer-Verlet as the trapezoidal variational integrator of a [`Mechanical`] system (see the
/// [module](self) docs).
pub struct Verlet<P> {
    path: Path<P>,
}

/// The undamped step (core's kick-drift-kick) or the damped one.
enum Path<P> {
    Split(StormerVerlet<Mechanical<P>>),
    Damped(Damped<P>),
}

/// The damped trapezoidal step and its work vectors.
struct Damped<P> {
    sys: Mechanical<P>,
    /// Factor of M + (h/2)C for the step size `factor_h` (only with a dense M).
    factor: Option<(f64, DenseFactor)>,
    /// ∇V at `cached_q` (first-same-as-last).
    cached_q: Vec<f64>,
    cached_grad: Vec<f64>,
    v: Vec<f64>,
    q1: Vec<f64>,
    g1: Vec<f64>,
}

impl<P: LocalPotential> Verlet<P> {
    /// Störmer-Verlet for `sys`.
    pub fn new(sys: Mechanical<P>) -> Self {
        let n = sys.dof();
        let path = if sys.get_damping().is_none() {
            Path::Split(StormerVerlet::new(sys))
        } else {
            Path::Damped(Damped {
                sys,
                factor: None,
                cached_q: Vec::new(),
                cached_grad: vec![0.0; n],
                v: vec![0.0; n],
                q1: vec![0.0; n],
                g1: vec![0.0; n],
            })
        };
        Verlet { path }
    }

    /// The system.
    pub fn system(&self) -> &Mechanical<P> {
        match &self.path {
            Path::Split(sv) => sv.system(),
            Path::Damped(d) => &d.sys,
        }
    }
}

impl<P: LocalPotential> Damped<P> {
    /// Overwrites `b` with (M + (h/2)C)⁻¹ b.
    fn solve_velocity(&mut self, h: f64, b: &mut [f64]) -> Result<()> {
        match (self.sys.get_damping(), self.sys.mass()) {
            (None, _) => self.sys.mass_solve(b),
            (Some(c), Mass::Diagonal(m)) => {
                // A diagonal matrix: its pivots are its entries, tested as every factorization is.
                let diag = || m.iter().zip(c).map(|(mi, ci)| mi + 0.5 * h * ci);
                let (lo, hi) = linalg::pivot_range(diag());
                let pivot_ratio = linalg::pivot_ratio(lo, hi, hi);
                if linalg::is_singular(pivot_ratio) {
                    return Err(Error::SingularMatrix {
                        what: "M + (h/2)C in the damped Verlet step",
                        pivot_ratio,
                    });
                }
                for (x, d) in b.iter_mut().zip(diag()) {
                    *x /= d;
                }
            }
            (Some(c), Mass::Dense(m)) => {
                if self.factor.as_ref().is_none_or(|(fh, _)| *fh != h) {
                    let mut a = m.clone();
                    for (i, ci) in c.iter().enumerate() {
                        a[(i, i)] += 0.5 * h * ci;
                    }
                    self.factor = Some((h, linalg::factor_mass(a, 0.0)?));
                }
                if let Some((_, f)) = &self.factor {
                    f.solve_in_place(b);
                }
            }
        }
        Ok(())
    }

    /// The damped update (q, p) ← (q', p') from time `t` over the signed step `h` (arguments checked
    /// by the caller); on error `q` and `p` are left as they were. No Newton: returns 0 iterations.
    fn advance(&mut self, t: f64, h: f64, q: &mut [f64], p: &mut [f64]) -> Result<usize> {
        if self.cached_q.as_slice() != q {
            self.sys.gradient(q, &mut self.cached_grad);
            self.cached_q.clear();
            self.cached_q.extend_from_slice(q);
        }
        let mut v = std::mem::take(&mut self.v);
        for ((vi, pi), gi) in v.iter_mut().zip(p.iter()).zip(&self.cached_grad) {
            *vi = pi - 0.5 * h * gi;
        }
        let solved = self.solve_velocity(h, &mut v);
        self.v = v;
        solved?;
        for ((q1, q0), vi) in self.q1.iter_mut().zip(q.iter()).zip(&self.v) {
            *q1 = q0 + h * vi;
        }
        self.sys.gradient(&self.q1, &mut self.g1);
        let mut p1 = vec![0.0; q.len()];
        self.sys.mass_mul(&self.v, &mut p1);
        for (pi, gi) in p1.iter_mut().zip(&self.g1) {
            *pi -= 0.5 * h * gi;
        }
        if let Some(c) = self.sys.get_damping() {
            for ((pi, ci), vi) in p1.iter_mut().zip(c).zip(&self.v) {
                *pi -= 0.5 * h * ci * vi;
            }
        }
        if self.q1.iter().chain(&p1).any(|x| !x.is_finite()) {
            return Err(Error::NonFiniteResult {
                what: "state after the step",
                t,
                component: None,
            });
        }
        q.copy_from_slice(&self.q1);
        p.copy_from_slice(&p1);
        self.cached_q.clear();
        self.cached_q.extend_from_slice(&self.q1);
        std::mem::swap(&mut self.cached_grad, &mut self.g1);
        Ok(0)
    }
}

impl<P: LocalPotential> Stepper for Verlet<P> {
    type Partner = Momenta;
    fn step(&mut self, state: &mut State<Momenta>, h: f64) -> Result<StepInfo> {
        step_forward(self, state, h)
    }
    fn dof(&self) -> usize {
        self.system().dof()
    }
    fn order(&self) -> u32 {
        2
    }
    fn rates(&self, state: &State<Momenta>, dq: &mut [f64], dp: &mut [f64]) -> Option<Result<()>> {
        let (q, p) = (state.q.as_slice(), state.v.as_slice());
        self.system().hamilton_rates(q, p, dq, dp);
        Some(Ok(()))
    }
    fn name(&self) -> &'static str {
        "Störmer-Verlet (trapezoidal variational)"
    }
}

impl<P: LocalPotential> SignedStepper for Verlet<P> {
    fn step_signed(&mut self, state: &mut State<Momenta>, h: f64) -> Result<StepInfo> {
        match &mut self.path {
            Path::Split(sv) => sv.step_signed(state, h),
            Path::Damped(d) => signed_step(d.sys.dof(), state, h, |t, q, p| d.advance(t, h, q, p)),
        }
    }
}
