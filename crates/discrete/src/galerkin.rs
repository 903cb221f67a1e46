//! Galerkin variational integrators of orders 4 and 6: the action over a step approximated by a
//! polynomial path and Gauss quadrature.
//!
//! The path over [t₀, t₀ + h] is the polynomial q(t₀ + τh) = Σ_ν ℓ_ν(τ) q^ν of degree s through the
//! control points q^0 = q_k, q^1, …, q^s = q_{k+1} at the equally spaced nodes d_ν = ν/s (ℓ_ν the
//! Lagrange basis), and the action is the s-point Gauss-Legendre quadrature (nodes c_i, weights w_i)
//!
//! ```text
//! S(q^0, …, q^s) = h Σ_i w_i L(t₀ + c_i h, Σ_ν ℓ_ν(c_i) q^ν, (1/h) Σ_ν ℓ'_ν(c_i) q^ν).
//! ```
//!
//! The Galerkin discrete Lagrangian is L_d(q_k, q_{k+1}) = ext over the interior points of S; in
//! position-momentum form one step solves, for the unknowns y = (q^1, …, q^s),
//!
//! ```text
//! p_k + ∂S/∂q^0 = 0,     ∂S/∂q^ν = 0 (ν = 1 … s−1),     then p_{k+1} = ∂S/∂q^s,
//! ```
//!
//! (the interior points are solved for together with q_{k+1}, so this is a stepper of its own rather than
//! a [`DiscreteLagrangian`](crate::DiscreteLagrangian) value, whose L_d would need an inner solve)
//! by the core Newton with the Jacobian from the dual-number Hessian of S (blocks ∂²S/∂q^0∂y and
//! ∂²S/∂y²). With s = 2 (one interior point, 2 Gauss points) the method has order 4, with s = 3 order
//! 6 (Marsden & West 2001, §2.2.6; Hairer, Lubich & Wanner, *Geometric Numerical Integration*, VI.6.3:
//! the Galerkin method with s Gauss points is the s-stage Gauss collocation method, order 2s).
//!
//! Generalized forces Q(t, q, q̇) enter by the discrete Lagrange-d'Alembert principle: the virtual work
//! ∫ Q·δq dt, by the same quadrature on the same path, adds to each equation the force on its control
//! point,
//!
//! ```text
//! F_ν = h Σ_i w_i ℓ_ν(c_i) Q(t₀ + c_i h, q(c_i), q̇(c_i)),
//! p_k + ∂S/∂q^0 + F_0 = 0,   ∂S/∂q^ν + F_ν = 0,   p_{k+1} = ∂S/∂q^s + F_s,
//! ```
//!
//! (Marsden & West 2001, §3.2), and Newton's Jacobian gains ∂F/∂y by dual numbers through the generic
//! [`generalized_force`](noether_core::Lagrangian::generalized_force).
//!
//! ```
//! use noether_core::prelude::*;
//! use noether_discrete::Galerkin;
//!
//! struct Oscillator;
//! impl Lagrangian for Oscillator {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         (v[0] * v[0] - q[0] * q[0]) * 0.5
//!     }
//! }
//!
//! let mut g = Galerkin::order4(Oscillator).unwrap();
//! let mut s = State::with_momenta(0.0, [1.0], [0.0]); // (q, p)
//! for _ in 0..10 {
//!     g.step(&mut s, 0.1).unwrap();
//! }
//! assert!((s.q[0] - 1f64.cos()).abs() < 1e-6); // fourth order: error O(h⁴)
//! ```

use crate::flow::signed_step;
use crate::integrator::{effective_newton, DEFAULT_TOL};
use crate::lagrangian::Scratch;
use crate::quadrature::FromLagrangian;
use nalgebra::DMatrix;
use noether_core::ad::{self, Block, Field};
use noether_core::integrators::composition::step_forward;
use noether_core::integrators::SignedStepper;
use noether_core::newton::{Dense, DenseProblem};
use noether_core::{
    Error, EulerLagrange, Lagrangian, Momenta, Newton, NewtonInfo, Result, Scalar, State, StepInfo, Stepper,
};
use num_dual::Dual64;

/// The Galerkin variational integrator (see the module docs). As a
/// [`Stepper`] it advances states (t, q, p).
pub struct Galerkin<L> {
    el: EulerLagrange<L>,
    /// Degree s of the path.
    s: usize,
    /// Gauss nodes c_i and weights w_i on [0, 1].
    nodes: Vec<f64>,
    weights: Vec<f64>,
    /// ℓ_ν(c_i), row i, column ν.
    basis: DMatrix<f64>,
    /// ℓ'_ν(c_i).
    dbasis: DMatrix<f64>,
    newton: Newton,
    last: NewtonInfo,
}

/// The action S of one step as an AD field: the step h in the scalar slot, x = q^0, y = (q^1 … q^s).
struct Action<'a, L> {
    g: &'a Galerkin<L>,
    t0: f64,
}

impl<L: Lagrangian> Field for Action<'_, L> {
    fn eval<D: Scalar>(&self, h: D, x: &[D], y: &[D]) -> D {
        let g = self.g;
        let mut s = D::zero();
        for (i, w) in g.weights.iter().enumerate() {
            let q = on_path(x, y, &g.basis, i, D::one());
            let v = on_path(x, y, &g.dbasis, i, h);
            let t = h * g.nodes[i] + self.t0;
            s += g.el.lagrangian().lagrangian(t, &q, &v) * *w;
        }
        s * h
    }
}

impl<L: Lagrangian> Action<'_, L> {
    /// The forces on the control points, F_ν = h Σ_i w_i ℓ_ν(c_i) Q(t₀ + c_i h, q(c_i), q̇(c_i)),
    /// ν = 0 … s, one after the other in `out` (length n(s + 1)).
    fn control_forces<D: Scalar>(&self, h: f64, x: &[D], y: &[D], out: &mut [D]) {
        let (g, n) = (self.g, x.len());
        out.iter_mut().for_each(|o| *o = D::zero());
        let mut qf = vec![D::zero(); n];
        for (i, w) in g.weights.iter().enumerate() {
            let q = on_path(x, y, &g.basis, i, D::one());
            let v = on_path(x, y, &g.dbasis, i, D::from(h));
            let t = D::from(self.t0 + h * g.nodes[i]);
            g.el.lagrangian().generalized_force(t, &q, &v, &mut qf);
            for (nu, f) in out.chunks_exact_mut(n).enumerate() {
                let c = h * w * g.basis[(i, nu)];
                f.iter_mut().zip(&qf).for_each(|(fj, qj)| *fj += *qj * c);
            }
        }
    }
}

/// Σ_ν basis(i, ν) q^ν / divisor with q^0 = x and q^ν = y[(ν−1)n..νn] (n = x.len()): the path (or its
/// derivative, for ℓ') at node i. Generic in D only, not in the model (`noether_core::ad::Buf::new`
/// says why).
fn on_path<D: Scalar>(x: &[D], y: &[D], basis: &DMatrix<f64>, i: usize, divisor: D) -> Scratch<D> {
    let n = x.len();
    let point = |nu: usize, j: usize| if nu == 0 { x[j] } else { y[(nu - 1) * n + j] };
    Scratch::new(n, |j| {
        (0..basis.ncols()).fold(D::zero(), |a, nu| a + point(nu, j) * basis[(i, nu)]) / divisor
    })
}

impl<L: Lagrangian> Galerkin<L> {
    /// Order 4: quadratic path (one interior point), 2-point Gauss quadrature.
    pub fn order4(lagrangian: L) -> Result<Self> {
        Self::new(lagrangian, 2)
    }

    /// Order 6: cubic path (two interior points), 3-point Gauss quadrature.
    pub fn order6(lagrangian: L) -> Result<Self> {
        Self::new(lagrangian, 3)
    }

    fn new(lagrangian: L, s: usize) -> Result<Self> {
        let (c, w) = gauss(s);
        let d: Vec<f64> = (0..=s).map(|nu| nu as f64 / s as f64).collect();
        let basis = DMatrix::from_fn(s, s + 1, |i, nu| lagrange(&d, nu, c[i]));
        let dbasis = DMatrix::from_fn(s, s + 1, |i, nu| lagrange_derivative(&d, nu, c[i]));
        Ok(Galerkin {
            el: EulerLagrange::new(lagrangian),
            s,
            nodes: c[..s].to_vec(),
            weights: w,
            basis,
            dbasis,
            newton: Newton::default().residual_tolerance(DEFAULT_TOL)?,
            last: NewtonInfo::default(),
        })
    }

    /// Replaces the Newton settings (see
    /// [`VariationalIntegrator::newton`](crate::VariationalIntegrator::newton)).
    pub fn newton(mut self, newton: Newton) -> Self {
        self.newton = newton;
        self
    }

    /// Statistics of the last Newton solve.
    pub fn last_newton(&self) -> NewtonInfo {
        self.last
    }
}

impl<L: Lagrangian> FromLagrangian for Galerkin<L> {
    type L = L;
    fn continuous(&self) -> &EulerLagrange<L> {
        &self.el
    }
}

/// Gauss-Legendre nodes and weights on [0, 1] for s = 2, 3.
fn gauss(s: usize) -> ([f64; 3], Vec<f64>) {
    match s {
        2 => {
            let r = 3f64.sqrt() / 6.0;
            ([0.5 - r, 0.5 + r, 0.0], vec![0.5, 0.5])
        }
        3 => {
            let r = 15f64.sqrt() / 10.0;
            ([0.5 - r, 0.5, 0.5 + r], vec![5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0])
        }
        _ => unreachable!("Galerkin degree is 2 or 3"),
    }
}

/// ℓ_ν(τ) = Π_{m≠ν} (τ − d_m)/(d_ν − d_m).
fn lagrange(d: &[f64], nu: usize, tau: f64) -> f64 {
    (0..d.len())
        .filter(|&m| m != nu)
        .map(|m| (tau - d[m]) / (d[nu] - d[m]))
        .product()
}

/// ℓ'_ν(τ) = Σ_{k≠ν} 1/(d_ν − d_k) Π_{m≠ν,k} (τ − d_m)/(d_ν − d_m).
fn lagrange_derivative(d: &[f64], nu: usize, tau: f64) -> f64 {
    (0..d.len())
        .filter(|&k| k != nu)
        .map(|k| {
            let rest: f64 = (0..d.len())
                .filter(|&m| m != nu && m != k)
                .map(|m| (tau - d[m]) / (d[nu] - d[m]))
                .product();
            rest / (d[nu] - d[k])
        })
        .sum()
}

/// The step equations in the unknowns y = (q^1 … q^s).
struct StepProblem<'a, L> {
    action: Action<'a, L>,
    h: f64,
    q0: &'a [f64],
    p0: &'a [f64],
    gx: Vec<f64>,
    gy: Vec<f64>,
    hyy: DMatrix<f64>,
    hxy: DMatrix<f64>,
    /// The control-point forces F_0 … F_s at the last residual (empty without forces).
    forces: Vec<f64>,
}

impl<L: Lagrangian> DenseProblem for StepProblem<'_, L> {
    fn dim(&self) -> usize {
        self.gy.len()
    }
    fn residual(&mut self, y: &[f64], r: &mut [f64]) -> Result<()> {
        let n = self.q0.len();
        ad::gradient(&self.action, self.h, self.q0, y, Block::X, &mut self.gx);
        ad::gradient(&self.action, self.h, self.q0, y, Block::Y, &mut self.gy);
        for ((ri, pi), gi) in r.iter_mut().zip(self.p0).zip(&self.gx) {
            *ri = pi + gi;
        }
        let m = r.len();
        r[n..].copy_from_slice(&self.gy[..m - n]);
        if !self.forces.is_empty() {
            self.action.control_forces(self.h, self.q0, y, &mut self.forces);
            // F_0 … F_{s−1} into the equations of q^0 … q^{s−1}; F_s goes to p_{k+1}.
            r.iter_mut().zip(&self.forces).for_each(|(ri, fi)| *ri += fi);
        }
        Ok(())
    }
    fn jacobian(&mut self, y: &[f64], j: &mut DMatrix<f64>) -> Result<()> {
        let n = self.q0.len();
        let m = y.len();
        ad::hessian(
            &self.action,
            self.h,
            self.q0,
            y,
            Block::X,
            Block::Y,
            &mut self.hxy,
        );
        ad::hessian(
            &self.action,
            self.h,
            self.q0,
            y,
            Block::Y,
            Block::Y,
            &mut self.hyy,
        );
        j.view_mut((0, 0), (n, m)).copy_from(&self.hxy);
        j.view_mut((n, 0), (m - n, m))
            .copy_from(&self.hyy.view((0, 0), (m - n, m)));
        if !self.forces.is_empty() {
            // ∂F_ν/∂y column by column, over Dual64 seeded along y_c (ν < s: F_s is not an equation).
            let x: Vec<Dual64> = self.q0.iter().map(|&a| Dual64::from(a)).collect();
            let mut f = vec![Dual64::from(0.0); self.forces.len()];
            for c in 0..m {
                let yc: Vec<Dual64> = (0..m)
                    .map(|k| Dual64::new(y[k], if k == c { 1.0 } else { 0.0 }))
                    .collect();
                self.action.control_forces(self.h, &x, &yc, &mut f);
                for (row, fr) in f[..m].iter().enumerate() {
                    j[(row, c)] += fr.eps;
                }
            }
        }
        Ok(())
    }
}

impl<L: Lagrangian> Stepper for Galerkin<L> {
    type Partner = Momenta;
    fn step(&mut self, state: &mut State<Momenta>, h: f64) -> Result<StepInfo> {
        step_forward(self, state, h)
    }
    fn dof(&self) -> usize {
        self.el.dof()
    }
    fn order(&self) -> u32 {
        2 * self.s as u32
    }
    fn rates(&self, state: &State<Momenta>, dq: &mut [f64], dp: &mut [f64]) -> Option<Result<()>> {
        let (t, q, p) = (state.t, state.q.as_slice(), state.v.as_slice());
        Some(self.hamilton_rates(t, q, p, dq, dp))
    }
    fn name(&self) -> &'static str {
        "Galerkin variational (Gauss quadrature)"
    }
}

impl<L: Lagrangian> Galerkin<L> {
    /// The update (q, p) ← (q', p') from time `t` over the signed step `h` (arguments checked by the
    /// caller); on error `q` and `p` are left as they were. Returns the Newton iterations spent.
    fn advance(&mut self, t: f64, h: f64, q: &mut [f64], p: &mut [f64]) -> Result<usize> {
        let n = self.el.dof();
        let s = self.s;
        // Initial guess: the straight path with the velocity of the inverse Legendre map.
        let v = self.el.velocities(t, q, p)?;
        let mut y: Vec<f64> = (1..=s)
            .flat_map(|nu| (0..n).map(move |j| (nu, j)))
            .map(|(nu, j)| q[j] + h * v[j] * nu as f64 / s as f64)
            .collect();
        let newton = effective_newton(&self.newton, p);
        let problem = StepProblem {
            action: Action { g: self, t0: t },
            h,
            q0: q,
            p0: p,
            gx: vec![0.0; n],
            gy: vec![0.0; n * s],
            hyy: DMatrix::zeros(n * s, n * s),
            hxy: DMatrix::zeros(n, n * s),
            forces: if self.el.lagrangian().has_generalized_force() {
                vec![0.0; n * (s + 1)]
            } else {
                Vec::new()
            },
        };
        let mut sys = Dense::new(problem);
        let info = newton.solve(&mut sys, &mut y).map_err(|e| e.at_time(t))?;
        // The last residual was evaluated at the solution: ∂S/∂q^s (+ F_s) is the new momentum.
        let mut p1 = sys.problem.gy[(s - 1) * n..].to_vec();
        if let Some(fs) = sys.problem.forces.get(s * n..) {
            p1.iter_mut().zip(fs).for_each(|(pi, fi)| *pi += fi);
        }
        let q1 = &y[(s - 1) * n..];
        if q1.iter().chain(&p1).any(|x| !x.is_finite()) {
            return Err(Error::NonFiniteResult {
                what: "state after the step",
                t,
                component: None,
            });
        }
        q.copy_from_slice(q1);
        p.copy_from_slice(&p1);
        self.last = info;
        Ok(info.iterations)
    }
}

impl<L: Lagrangian> SignedStepper for Galerkin<L> {
    fn step_signed(&mut self, state: &mut State<Momenta>, h: f64) -> Result<StepInfo> {
        signed_step(self.dof(), state, h, |t, q, p| self.advance(t, h, q, p))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Lagrange basis interpolates polynomials of degree s exactly: Σ_ν ℓ_ν(τ) d_ν^k = τ^k and
    /// Σ_ν ℓ'_ν(τ) d_ν^k = k τ^{k−1} (k ≤ s), to rounding.
    #[test]
    fn closed_form_lagrange_basis() {
        for s in [2, 3] {
            let d: Vec<f64> = (0..=s).map(|nu| nu as f64 / s as f64).collect();
            for k in 0..=s as i32 {
                for tau in [0.1, 0.37, 0.8] {
                    let val: f64 = (0..=s).map(|nu| lagrange(&d, nu, tau) * d[nu].powi(k)).sum();
                    let der: f64 = (0..=s)
                        .map(|nu| lagrange_derivative(&d, nu, tau) * d[nu].powi(k))
                        .sum();
                    assert!((val - tau.powi(k)).abs() < 1e-14);
                    let exact = if k == 0 { 0.0 } else { k as f64 * tau.powi(k - 1) };
                    assert!((der - exact).abs() < 1e-13, "s {s} k {k}: {der} vs {exact}");
                }
            }
        }
    }
}
