//! The midpoint variational integrator of a [`Mechanical`] system with a sparse (banded) or dense Newton
//! Jacobian assembled term by term.
//!
//! For L = ½ q̇ᵀMq̇ − V(q) with damping Q = −C q̇ and the midpoint discrete Lagrangian
//! (`L_d = h L((q₀+q₁)/2, (q₁−q₀)/h)`, f⁻ = f⁺ = −C(q₁−q₀)/2), with Δ = q_{k+1} − q_k and
//! m = (q_k + q_{k+1})/2 the step solves
//!
//! ```text
//! F(q_{k+1}) = M Δ/h + (h/2) ∇V(m) + C Δ/2 − p_k = 0,      J = M/h + (h/4) ∇²V(m) + C/2,
//! p_{k+1}    = M Δ/h − (h/2) ∇V(m) − C Δ/2.
//! ```
//!
//! Without damping, eliminating p gives the paper's discrete Euler-Lagrange equation
//! `M (q_{k+1} − 2q_k + q_{k−1})/h² + ½ [∇V((q_{k+1}+q_k)/2) + ∇V((q_k+q_{k−1})/2)] = 0`.
//! The Newton unknown is the increment Δ (q_{k+1} = q_k + Δ), not q_{k+1}: the momenta then carry no
//! rounding from differencing large positions (ε|q|/h per component), and the total momentum of a
//! translation-invariant system stays at rounding level even after the system has travelled far.
//! The factor of J is kept from one step to the next (same h) and reused while it contracts the
//! residual by the Newton `contraction` factor (modified Newton; J changes by O(h ∇³V Δ) per step), so
//! most steps cost residual evaluations and triangular solves only; `Newton::reuse_jacobian(false)`
//! refreshes it at every iteration.
//! J is stored banded (LU with partial pivoting, O(N) for a chain) when the half-bandwidth of M + ∇²V is
//! small against N, dense (LU) otherwise.

use crate::flow::{correct_once, signed_step, Predictor};
use crate::integrator::{default_newton, effective_newton};
use crate::mechanical::{LocalPotential, Mechanical};
use nalgebra::DMatrix;
use noether_core::integrators::composition::step_forward;
use noether_core::integrators::SignedStepper;
use noether_core::linalg::{solve_with, Banded, BandedLu, DenseFactor};
use noether_core::{Error, Momenta, Newton, NewtonInfo, NewtonSystem, Result, State, StepInfo, Stepper};

/// Storage of the Newton Jacobian.
enum Jacobian {
    Dense(DMatrix<f64>, Option<DenseFactor>),
    Banded(usize, Option<BandedLu>),
}

/// Residual and Jacobian of one midpoint step.
struct MidpointSystem<'a, P> {
    sys: &'a Mechanical<P>,
    h: f64,
    q0: &'a [f64],
    p0: &'a [f64],
    mid: &'a mut [f64],
    grad: &'a mut [f64],
    work: &'a mut [f64],
    jac: &'a mut Jacobian,
    /// Step size the factor in `jac` was computed with (NaN when none).
    factor_h: &'a mut f64,
}

impl<P: LocalPotential> MidpointSystem<'_, P> {
    /// m = q₀ + Δ/2.
    fn midpoint(&mut self, d: &[f64]) {
        for ((m, a), di) in self.mid.iter_mut().zip(self.q0).zip(d) {
            *m = a + 0.5 * di;
        }
    }
}

impl<P: LocalPotential> NewtonSystem for MidpointSystem<'_, P> {
    fn dim(&self) -> usize {
        self.q0.len()
    }

    fn residual(&mut self, d: &[f64], r: &mut [f64]) -> Result<()> {
        self.midpoint(d);
        self.sys.gradient(self.mid, self.grad);
        for (w, di) in self.work.iter_mut().zip(d) {
            *w = di / self.h;
        }
        self.sys.mass_mul(self.work, r);
        let hh = 0.5 * self.h;
        for ((ri, gi), pi) in r.iter_mut().zip(self.grad.iter()).zip(self.p0) {
            *ri += hh * gi - pi;
        }
        if let Some(c) = self.sys.get_damping() {
            for ((ri, ci), di) in r.iter_mut().zip(c).zip(d) {
                *ri += 0.5 * ci * di;
            }
        }
        Ok(())
    }

    fn factor_jacobian(&mut self, d: &[f64]) -> Result<()> {
        self.midpoint(d);
        *self.factor_h = f64::NAN;
        let (h, n) = (self.h, self.q0.len());
        let damping = self.sys.get_damping();
        match self.jac {
            Jacobian::Dense(m, lu) => {
                m.fill(0.0);
                self.sys.add_mass(1.0 / h, m);
                self.sys.add_hessian(self.mid, 0.25 * h, m);
                if let Some(c) = damping {
                    (0..n).for_each(|i| m[(i, i)] += 0.5 * c[i]);
                }
                *lu = None;
                let f = DenseFactor::lu(m.clone()).map_err(|e| e.in_matrix("midpoint Newton Jacobian"))?;
                *lu = Some(f);
            }
            Jacobian::Banded(bw, lu) => {
                let mut b = Banded::zeros(n, *bw, *bw);
                self.sys.add_mass(1.0 / h, &mut b);
                self.sys.add_hessian(self.mid, 0.25 * h, &mut b);
                if let Some(c) = damping {
                    (0..n).for_each(|i| b.add(i, i, 0.5 * c[i]));
                }
                *lu = None;
                let f = b
                    .factor()
                    .map_err(|e| e.in_matrix("banded midpoint Newton Jacobian"))?;
                *lu = Some(f);
            }
        }
        *self.factor_h = h;
        Ok(())
    }

    fn solve(&mut self, rhs: &mut [f64]) -> Result<()> {
        match self.jac {
            Jacobian::Dense(_, lu) => solve_with(lu.as_ref(), rhs, "midpoint Newton Jacobian"),
            Jacobian::Banded(_, Some(lu)) => {
                lu.solve(rhs);
                Ok(())
            }
            Jacobian::Banded(_, None) => Err(Error::SingularMatrix {
                what: "banded midpoint Newton Jacobian (not factored)",
                pivot_ratio: f64::NAN,
            }),
        }
    }
}

/// Midpoint variational integrator of a [`Mechanical`] system (see the module docs). As a
/// [`Stepper`] it advances states (t, q, p).
pub struct MechanicalMidpoint<P> {
    sys: Mechanical<P>,
    newton: Newton,
    predictor: Predictor,
    jac: Jacobian,
    /// The increment Δ = q_{k+1} − q_k (Newton's unknown).
    d: Vec<f64>,
    mid: Vec<f64>,
    grad: Vec<f64>,
    work: Vec<f64>,
    last: NewtonInfo,
    /// Step size of the Jacobian factor kept from the last step.
    factor_h: f64,
}

impl<P: LocalPotential> MechanicalMidpoint<P> {
    /// The integrator; the Jacobian is banded when 3·bandwidth < dof, dense otherwise. Newton is
    /// solved to rounding by default (see
    /// [`VariationalIntegrator::newton`](crate::VariationalIntegrator::newton)).
    pub fn new(sys: Mechanical<P>) -> Self {
        let n = sys.dof();
        let bw = sys.bandwidth();
        let jac = if 3 * bw < n {
            Jacobian::Banded(bw, None)
        } else {
            Jacobian::Dense(DMatrix::zeros(n, n), None)
        };
        MechanicalMidpoint {
            sys,
            newton: default_newton(),
            predictor: Predictor::default(),
            jac,
            d: vec![0.0; n],
            mid: vec![0.0; n],
            grad: vec![0.0; n],
            work: vec![0.0; n],
            last: NewtonInfo::default(),
            factor_h: f64::NAN,
        }
    }

    /// Replaces the Newton settings (the paper: `Newton::default().residual_tolerance(1e-8)?`).
    pub fn newton(mut self, newton: Newton) -> Self {
        self.newton = newton;
        self
    }

    /// Forces a dense Jacobian (for comparisons).
    pub fn dense(mut self) -> Self {
        let n = self.sys.dof();
        self.jac = Jacobian::Dense(DMatrix::zeros(n, n), None);
        self.factor_h = f64::NAN;
        self
    }

    /// `true` when the Jacobian is stored banded.
    pub fn is_banded(&self) -> bool {
        matches!(self.jac, Jacobian::Banded(..))
    }

    /// The system.
    pub fn system(&self) -> &Mechanical<P> {
        &self.sys
    }

    /// Statistics of the last Newton solve.
    pub fn last_newton(&self) -> NewtonInfo {
        self.last
    }
}

impl<P: LocalPotential> Stepper for MechanicalMidpoint<P> {
    type Partner = Momenta;
    fn step(&mut self, state: &mut State<Momenta>, h: f64) -> Result<StepInfo> {
        step_forward(self, state, h)
    }
    fn dof(&self) -> usize {
        self.sys.dof()
    }
    fn order(&self) -> u32 {
        2
    }
    fn rates(&self, state: &State<Momenta>, dq: &mut [f64], dp: &mut [f64]) -> Option<Result<()>> {
        let (q, p) = (state.q.as_slice(), state.v.as_slice());
        self.sys.hamilton_rates(q, p, dq, dp);
        Some(Ok(()))
    }
    fn name(&self) -> &'static str {
        "variational midpoint (mechanical)"
    }
}

impl<P: LocalPotential> MechanicalMidpoint<P> {
    /// The update (q, p) ← (q', p') from time `t` over the signed step `h` (arguments checked by the
    /// caller); on error `q` and `p` are left as they were. Returns the Newton iterations spent.
    fn advance(&mut self, t: f64, h: f64, q: &mut [f64], p: &mut [f64]) -> Result<usize> {
        let n = self.sys.dof();
        self.predictor.guess_increment(q, h, &mut self.d);
        let newton = effective_newton(&self.newton, p);
        let mut system = MidpointSystem {
            sys: &self.sys,
            h,
            q0: q,
            p0: p,
            mid: &mut self.mid,
            grad: &mut self.grad,
            work: &mut self.work,
            jac: &mut self.jac,
            factor_h: &mut self.factor_h,
        };
        // A factor of the last step's Jacobian (same h) is reused while it contracts the residual.
        let factored = *system.factor_h == h;
        let info = newton
            .solve_reusing(&mut system, &mut self.d, factored)
            .map_err(|e| e.at_time(t))?;
        if info.iterations == 0 {
            let factored = *system.factor_h == h;
            correct_once(&mut system, &mut self.d, factored)?;
        }
        // The last residual was evaluated at the solution: ∇V(m) is in `grad`, Δ/h in `work`.
        let mut p1 = vec![0.0; n];
        self.sys.mass_mul(&self.work, &mut p1);
        for (pi, gi) in p1.iter_mut().zip(&self.grad) {
            *pi -= 0.5 * h * gi;
        }
        if let Some(c) = self.sys.get_damping() {
            for ((pi, ci), di) in p1.iter_mut().zip(c).zip(&self.d) {
                *pi -= 0.5 * ci * di;
            }
        }
        if self.d.iter().chain(&p1).any(|x| !x.is_finite()) {
            return Err(Error::NonFiniteResult {
                what: "state after the step",
                t,
                component: None,
            });
        }
        q.iter_mut().zip(&self.d).for_each(|(qi, di)| *qi += di);
        self.predictor.record_increment(q, &self.d, h);
        p.copy_from_slice(&p1);
        self.last = info;
        Ok(info.iterations)
    }
}

impl<P: LocalPotential> SignedStepper for MechanicalMidpoint<P> {
    fn step_signed(&mut self, state: &mut State<Momenta>, h: f64) -> Result<StepInfo> {
        signed_step(self.dof(), state, h, |t, q, p| self.advance(t, h, q, p))
    }
}
