//! The derivative of the variational integrators' maps: Ψ = ∂(q_{k+1}, p_{k+1})/∂(q_k, p_k), exact to
//! rounding, by the implicit-function theorem at the converged Newton solution (not by differentiating
//! Newton's iterations). Every [`DiscreteTangentFlow`] is a core
//! [`TangentStepper`](noether_core::TangentStepper) on `State<Momenta>`.
//!
//! # The general integrator ([`VariationalIntegrator`])
//!
//! Without forces the step is defined by p₀ = −D₁L_d(q₀, q₁) (solved for q₁) and p₁ = D₂L_d(q₀, q₁).
//! Differentiating the first equation, −dp₀ = D₁₁L_d dq₀ + D₁₂L_d dq₁, with A = D₁₂L_d (rows q₀,
//! columns q₁: Newton's Jacobian, invertible where the step is defined):
//!
//! ```text
//! ∂q₁/∂q₀ = −A⁻¹ D₁₁L_d,            ∂q₁/∂p₀ = −A⁻¹,
//! ∂p₁/∂q₀ = Aᵀ + D₂₂L_d ∂q₁/∂q₀,    ∂p₁/∂p₀ = D₂₂L_d ∂q₁/∂p₀,
//! ```
//!
//! (D₂₁L_d = Aᵀ), all second derivatives of L_d by dual numbers
//! ([`DiscreteDerivatives`]) at the converged (q₀, q₁). The discrete forces f^± come as plain values
//! without derivatives: a forced integrator refuses the tangent step (`Unsupported`).
//!
//! # The mechanical fast paths
//!
//! [`MechanicalMidpoint`] (L = ½q̇ᵀMq̇ − V, damping C = diag(c)): from
//! F = MΔ/h + (h/2)∇V(m) + CΔ/2 − p₀ = 0 and p₁ = MΔ/h − (h/2)∇V(m) − CΔ/2, Δ = q₁ − q₀,
//! m = (q₀ + q₁)/2, H = ∇²V(m):
//!
//! ```text
//! J = M/h + C/2 + (h/4)H,   K = M/h + C/2 − (h/4)H,   ∂q₁/∂q₀ = J⁻¹K,   ∂q₁/∂p₀ = J⁻¹,
//! P = M/h − C/2 − (h/4)H,   Q = M/h − C/2 + (h/4)H,   ∂p₁/∂q₀ = P ∂q₁/∂q₀ − Q,   ∂p₁/∂p₀ = P ∂q₁/∂p₀.
//! ```
//!
//! [`Verlet`] (explicit): B v = p₀ − (h/2)∇V(q₀), B = M + (h/2)C, q₁ = q₀ + hv,
//! p₁ = (M − (h/2)C)v − (h/2)∇V(q₁), with H₀ = ∇²V(q₀), H₁ = ∇²V(q₁):
//!
//! ```text
//! ∂v/∂q₀ = −(h/2)B⁻¹H₀,   ∂v/∂p₀ = B⁻¹,   ∂q₁/∂· = [I, 0] + h ∂v/∂·,
//! ∂p₁/∂· = (M − (h/2)C) ∂v/∂· − (h/2)H₁ ∂q₁/∂·.
//! ```
//!
//! [`Composition`]: the chain rule over the substeps, Ψ = Ψ_s ⋯ Ψ_1 (substeps of negative size
//! included).
//!
//! ```
//! use nalgebra::DMatrix;
//! use noether_core::prelude::*;
//! use noether_discrete::{Midpoint, VariationalIntegrator};
//!
//! struct Pendulum;
//! impl Lagrangian for Pendulum {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         v[0] * v[0] * 0.5 + q[0].cos()
//!     }
//! }
//!
//! let mut vi = VariationalIntegrator::new(Midpoint::new(Pendulum));
//! let mut s = vi.state_from_velocities(0.0, &[1.0], &[0.5]).unwrap();
//! let mut psi = DMatrix::zeros(2, 2);
//! vi.step_tangent(&mut s, 0.1, &mut psi).unwrap();
//! // A variational integrator is symplectic: in one degree of freedom, det Ψ = 1.
//! assert!((psi.determinant() - 1.0).abs() < 1e-14);
//! ```

use crate::composition::Composition;
use crate::flow::DiscreteFlow;
use crate::integrator::VariationalIntegrator;
use crate::lagrangian::{DiscreteDerivatives, DiscreteLagrangian};
use crate::mechanical::{LocalPotential, Mechanical};
use crate::mechanical_midpoint::MechanicalMidpoint;
use crate::verlet::Verlet;
use nalgebra::DMatrix;
use noether_core::linalg::DenseFactor;
use noether_core::{Error, Momenta, Result, State, StepInfo};

/// A [`DiscreteFlow`] that also gives the Jacobian of its map.
pub trait DiscreteTangentFlow: DiscreteFlow {
    /// Advances `(q, p)` exactly as [`DiscreteFlow::flow`] (signed `h`) and writes
    /// Ψ = ∂(q', p')/∂(q, p), 2n × 2n ordered (q, p), into `psi`. On error `q`, `p` and `psi` are left
    /// exactly as they were. Returns the Newton iterations spent.
    fn flow_tangent(
        &mut self,
        t: f64,
        h: f64,
        q: &mut [f64],
        p: &mut [f64],
        psi: &mut DMatrix<f64>,
    ) -> Result<usize>;
}

impl<F: DiscreteTangentFlow + ?Sized> DiscreteTangentFlow for &mut F {
    fn flow_tangent(
        &mut self,
        t: f64,
        h: f64,
        q: &mut [f64],
        p: &mut [f64],
        psi: &mut DMatrix<f64>,
    ) -> Result<usize> {
        (**self).flow_tangent(t, h, q, p, psi)
    }
}

/// `Dimension` unless `psi` is 2n × 2n.
fn check_shape(psi: &DMatrix<f64>, n: usize) -> Result<()> {
    if psi.nrows() != 2 * n || psi.ncols() != 2 * n {
        return Err(Error::Dimension {
            what: "step Jacobian Ψ (rows and columns)",
            expected: 2 * n,
            got: if psi.nrows() != 2 * n {
                psi.nrows()
            } else {
                psi.ncols()
            },
        });
    }
    Ok(())
}

/// One [`TangentStepper`](noether_core::TangentStepper) step of a tangent flow (a positive step; the
/// state and Ψ left untouched on error).
pub(crate) fn step_state_tangent<F: DiscreteTangentFlow + ?Sized>(
    flow: &mut F,
    state: &mut State<Momenta>,
    h: f64,
    psi: &mut DMatrix<f64>,
) -> Result<StepInfo> {
    noether_core::error::check_step(h)?;
    state.validate(flow.dof())?;
    noether_core::error::check_time_resolution(state.t, h)?;
    check_shape(psi, flow.dof())?;
    let t = state.t;
    let iterations = flow.flow_tangent(t, h, state.q.as_mut_slice(), state.v.as_mut_slice(), psi)?;
    state.t = t + h;
    Ok(StepInfo::fixed(h)
        .with_newton(iterations, 0)
        .with_evaluations(iterations + 1))
}

/// Implements [`noether_core::TangentStepper`] for a type that implements [`DiscreteTangentFlow`].
macro_rules! tangent_via_flow {
    ($ty:ident < $($g:ident : $b:path),* >) => {
        impl<$($g: $b),*> noether_core::TangentStepper for $ty<$($g),*>
        where
            $ty<$($g),*>: $crate::tangent::DiscreteTangentFlow,
        {
            fn step_tangent(
                &mut self,
                state: &mut noether_core::State<noether_core::Momenta>,
                h: f64,
                psi: &mut nalgebra::DMatrix<f64>,
            ) -> noether_core::Result<noether_core::StepInfo> {
                $crate::tangent::step_state_tangent(self, state, h, psi)
            }
        }
    };
}

tangent_via_flow!(VariationalIntegrator<Ld: DiscreteLagrangian>);
tangent_via_flow!(MechanicalMidpoint<P: LocalPotential>);
tangent_via_flow!(Verlet<P: LocalPotential>);
tangent_via_flow!(Composition<F: DiscreteTangentFlow>);

/// Takes the flow's step, then Ψ from `jacobian(q₀, p₀, q₁, p₁)`; when that fails, (q, p) are put
/// back and `psi` is not written.
fn step_then_jacobian<F: DiscreteFlow + ?Sized>(
    flow: &mut F,
    (t, h): (f64, f64),
    q: &mut [f64],
    p: &mut [f64],
    psi: &mut DMatrix<f64>,
    jacobian: impl FnOnce(&F, &[f64], &[f64], &[f64]) -> Result<DMatrix<f64>>,
) -> Result<usize> {
    let n = flow.dof();
    check_shape(psi, n)?;
    let (q0, p0) = (q.to_vec(), p.to_vec());
    let iterations = flow.flow(t, h, q, p)?;
    match jacobian(flow, &q0, &p0, q).and_then(|m| {
        noether_core::error::check_result("step Jacobian Ψ", t, m.as_slice())?;
        Ok(m)
    }) {
        Ok(m) => {
            psi.copy_from(&m);
            Ok(iterations)
        }
        Err(e) => {
            q.copy_from_slice(&q0);
            p.copy_from_slice(&p0);
            Err(e)
        }
    }
}

/// Assembles Ψ from its four n × n blocks.
fn blocks(qq: &DMatrix<f64>, qp: &DMatrix<f64>, pq: &DMatrix<f64>, pp: &DMatrix<f64>) -> DMatrix<f64> {
    let n = qq.nrows();
    let mut psi = DMatrix::zeros(2 * n, 2 * n);
    psi.view_mut((0, 0), (n, n)).copy_from(qq);
    psi.view_mut((0, n), (n, n)).copy_from(qp);
    psi.view_mut((n, 0), (n, n)).copy_from(pq);
    psi.view_mut((n, n), (n, n)).copy_from(pp);
    psi
}

impl<Ld: DiscreteLagrangian> DiscreteTangentFlow for VariationalIntegrator<Ld> {
    fn flow_tangent(
        &mut self,
        t: f64,
        h: f64,
        q: &mut [f64],
        p: &mut [f64],
        psi: &mut DMatrix<f64>,
    ) -> Result<usize> {
        if self.discrete_lagrangian().has_discrete_force() {
            return Err(Error::Unsupported(
                "step Jacobian of a forced variational integrator: the discrete forces f± come without derivatives",
            ));
        }
        step_then_jacobian(self, (t, h), q, p, psi, |vi, q0, _p0, q1| {
            let ld = vi.discrete_lagrangian();
            let n = q0.len();
            let (mut a, mut d11, mut d22) =
                (DMatrix::zeros(n, n), DMatrix::zeros(n, n), DMatrix::zeros(n, n));
            ld.d12(t, h, q0, q1, &mut a);
            ld.d11(t, h, q0, q1, &mut d11);
            ld.d22(t, h, q0, q1, &mut d22);
            let lu = DenseFactor::lu(a.clone()).map_err(|e| e.in_matrix("D₁₂L_d in the step Jacobian"))?;
            let qq = -lu.solve_matrix(&d11);
            let qp = -lu.solve_matrix(&DMatrix::identity(n, n));
            let pq = a.transpose() + &d22 * &qq;
            let pp = &d22 * &qp;
            Ok(blocks(&qq, &qp, &pq, &pp))
        })
    }
}

/// c as a diagonal matrix scaled by `s` (zero without damping).
fn damping_matrix<P: LocalPotential>(sys: &Mechanical<P>, s: f64) -> DMatrix<f64> {
    let n = sys.dof();
    let mut c = DMatrix::zeros(n, n);
    if let Some(d) = sys.damping() {
        d.iter().enumerate().for_each(|(i, ci)| c[(i, i)] = s * ci);
    }
    c
}

impl<P: LocalPotential> DiscreteTangentFlow for MechanicalMidpoint<P> {
    fn flow_tangent(
        &mut self,
        t: f64,
        h: f64,
        q: &mut [f64],
        p: &mut [f64],
        psi: &mut DMatrix<f64>,
    ) -> Result<usize> {
        step_then_jacobian(self, (t, h), q, p, psi, |mm, q0, _p0, q1| {
            let sys = mm.system();
            let n = q0.len();
            let mid: Vec<f64> = q0.iter().zip(q1).map(|(a, b)| 0.5 * (a + b)).collect();
            let mut m = DMatrix::zeros(n, n);
            sys.add_mass(1.0 / h, &mut m);
            let mut hq = DMatrix::zeros(n, n);
            sys.add_hessian(&mid, 0.25 * h, &mut hq);
            let c = damping_matrix(sys, 0.5);
            let j = &m + &c + &hq;
            let k = &m + &c - &hq;
            let pm = &m - &c - &hq;
            let qm = &m - &c + &hq;
            let lu = DenseFactor::lu(j)
                .map_err(|e| e.in_matrix("midpoint Newton Jacobian in the step Jacobian"))?;
            let qq = lu.solve_matrix(&k);
            let qp = lu.solve_matrix(&DMatrix::identity(n, n));
            let pq = &pm * &qq - qm;
            let pp = &pm * &qp;
            Ok(blocks(&qq, &qp, &pq, &pp))
        })
    }
}

impl<P: LocalPotential> DiscreteTangentFlow for Verlet<P> {
    fn flow_tangent(
        &mut self,
        t: f64,
        h: f64,
        q: &mut [f64],
        p: &mut [f64],
        psi: &mut DMatrix<f64>,
    ) -> Result<usize> {
        step_then_jacobian(self, (t, h), q, p, psi, |v, q0, _p0, q1| {
            let sys = v.system();
            let n = q0.len();
            let mut m = DMatrix::zeros(n, n);
            sys.add_mass(1.0, &mut m);
            let c = damping_matrix(sys, 0.5 * h);
            let (mut h0, mut h1) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
            sys.add_hessian(q0, 0.5 * h, &mut h0);
            sys.add_hessian(q1, 0.5 * h, &mut h1);
            let lu = DenseFactor::lu(&m + &c)
                .map_err(|e| e.in_matrix("M + (h/2)C in the Verlet step Jacobian"))?;
            let vq = -lu.solve_matrix(&h0);
            let vp = lu.solve_matrix(&DMatrix::identity(n, n));
            let qq = DMatrix::identity(n, n) + h * &vq;
            let qp = h * &vp;
            let r = &m - &c;
            let pq = &r * &vq - &h1 * &qq;
            let pp = &r * &vp - &h1 * &qp;
            Ok(blocks(&qq, &qp, &pq, &pp))
        })
    }
}

impl<F: DiscreteTangentFlow> DiscreteTangentFlow for Composition<F> {
    fn flow_tangent(
        &mut self,
        t: f64,
        h: f64,
        q: &mut [f64],
        p: &mut [f64],
        psi: &mut DMatrix<f64>,
    ) -> Result<usize> {
        let n = DiscreteFlow::dof(self);
        check_shape(psi, n)?;
        crate::flow::check_flow_args(n, t, h, q, p)?;
        let (mut qs, mut ps) = (q.to_vec(), p.to_vec());
        let mut total = DMatrix::identity(2 * n, 2 * n);
        let mut stage = DMatrix::zeros(2 * n, 2 * n);
        let mut tau = t;
        let mut iterations = 0;
        let gammas = self.weights().to_vec();
        for g in gammas {
            iterations += self
                .inner_mut()
                .flow_tangent(tau, g * h, &mut qs, &mut ps, &mut stage)?;
            total = &stage * total;
            tau += g * h;
        }
        q.copy_from_slice(&qs);
        p.copy_from_slice(&ps);
        psi.copy_from(&total);
        Ok(iterations)
    }
}
