//! The derivative of the variational integrators' maps: Ψ = ∂(q_{k+1}, p_{k+1})/∂(q_k, p_k), exact to
//! rounding, by the implicit-function theorem at the converged Newton solution (not by differentiating
//! Newton's iterations). Every integrator here is a core [`SignedTangentStepper`] (steps of either
//! sign) and so a [`TangentStepper`] on `State<Momenta>`.
//!
//! # The general integrator ([`VariationalIntegrator`])
//!
//! The step is defined by p₀ + D₁L_d(q₀, q₁) + f⁻(q₀, q₁) = 0 (solved for q₁) and
//! p₁ = D₂L_d(q₀, q₁) + f⁺(q₀, q₁). Differentiating the first equation,
//! −dp₀ = (D₁₁L_d + ∂f⁻/∂q₀) dq₀ + A dq₁ with A = D₁₂L_d + ∂f⁻/∂q₁ (rows q₀, columns q₁: Newton's
//! Jacobian, invertible where the step is defined):
//!
//! ```text
//! ∂q₁/∂q₀ = −A⁻¹ (D₁₁L_d + ∂f⁻/∂q₀),                      ∂q₁/∂p₀ = −A⁻¹,
//! ∂p₁/∂q₀ = D₂₁L_d + ∂f⁺/∂q₀ + (D₂₂L_d + ∂f⁺/∂q₁) ∂q₁/∂q₀,   ∂p₁/∂p₀ = (D₂₂L_d + ∂f⁺/∂q₁) ∂q₁/∂p₀,
//! ```
//!
//! (D₂₁L_d = D₁₂L_dᵀ), all second derivatives of L_d and the forces' first derivatives by dual numbers
//! ([`DiscreteDerivatives`]) at the converged (q₀, q₁). Without forces the step is symplectic.
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
//! A [`Composition`](noether_core::integrators::Composition) of any of them: the chain rule over the
//! substeps, Ψ = Ψ_s ⋯ Ψ_1 (substeps of negative size included; core's
//! [`SignedTangentStepper::step_composed_tangent`]).
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

use crate::integrator::VariationalIntegrator;
use crate::lagrangian::{DiscreteDerivatives, DiscreteLagrangian, StepEnd};
use crate::mechanical::{LocalPotential, Mechanical};
use crate::mechanical_midpoint::MechanicalMidpoint;
use crate::verlet::Verlet;
use nalgebra::DMatrix;
use noether_core::integrators::composition::{check_signed_step, step_forward_tangent};
use noether_core::integrators::{SignedStepper, SignedTangentStepper};
use noether_core::linalg::DenseFactor;
use noether_core::{Momenta, Result, State, StepInfo, TangentStepper};

/// Takes the map's signed step, then Ψ from its [`StepJacobian`]; when that fails, the state is put
/// back and `psi` is not written.
fn step_then_jacobian<F: StepJacobian>(
    map: &mut F,
    state: &mut State<Momenta>,
    h: f64,
    psi: &mut DMatrix<f64>,
) -> Result<StepInfo> {
    check_signed_step(map.dof(), state, h)?;
    noether_core::tangent::check_tangent_shape(psi, map.dof())?;
    let (t, q0, p0) = (state.t, state.q.as_slice().to_vec(), state.v.as_slice().to_vec());
    let info = map.step_signed(state, h)?;
    match map.step_jacobian(t, h, &q0, state.q.as_slice()).and_then(|m| {
        noether_core::error::check_result("step Jacobian Ψ", t, m.as_slice())?;
        Ok(m)
    }) {
        Ok(m) => {
            psi.copy_from(&m);
            Ok(info)
        }
        Err(e) => {
            state.q.as_mut_slice().copy_from_slice(&q0);
            state.v.as_mut_slice().copy_from_slice(&p0);
            state.t = t;
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

/// The step Jacobian of a map: Ψ at the converged step of size `h` from (t, q₀, p₀) to q₁, by the
/// formulas of the [module docs](self).
trait StepJacobian: SignedStepper<Partner = Momenta> {
    /// Ψ of the step of size `h` from time `t` and q₀ to q₁.
    fn step_jacobian(&self, t: f64, h: f64, q0: &[f64], q1: &[f64]) -> Result<DMatrix<f64>>;
}

impl<Ld: DiscreteLagrangian> StepJacobian for VariationalIntegrator<Ld> {
    fn step_jacobian(&self, t: f64, h: f64, q0: &[f64], q1: &[f64]) -> Result<DMatrix<f64>> {
        let ld = self.discrete_lagrangian();
        let n = q0.len();
        let zero = || DMatrix::zeros(n, n);
        let (mut d12, mut d11, mut d22) = (zero(), zero(), zero());
        ld.d12(t, h, q0, q1, &mut d12);
        ld.d11(t, h, q0, q1, &mut d11);
        ld.d22(t, h, q0, q1, &mut d22);
        // The forces' derivatives (zero without forces): ∂f±/∂q₀ and ∂f±/∂q₁.
        let (mut m0, mut p0, mut m1, mut p1) = (zero(), zero(), zero(), zero());
        ld.force_derivatives(t, h, (q0, q1), StepEnd::Left, (&mut m0, &mut p0));
        ld.force_derivatives(t, h, (q0, q1), StepEnd::Right, (&mut m1, &mut p1));
        let a = &d12 + m1;
        let lu = DenseFactor::lu(a).map_err(|e| e.in_matrix("D₁₂L_d + ∂f⁻/∂q₁ in the step Jacobian"))?;
        let qq = -lu.solve_matrix(&(d11 + m0));
        let qp = -lu.solve_matrix(&DMatrix::identity(n, n));
        let d22 = d22 + p1;
        let pq = d12.transpose() + p0 + &d22 * &qq;
        let pp = &d22 * &qp;
        Ok(blocks(&qq, &qp, &pq, &pp))
    }
}

/// M scaled by `s`, and c as a diagonal matrix scaled by `s_c` (zero without damping).
fn mass_and_damping<P: LocalPotential>(
    sys: &Mechanical<P>,
    s: f64,
    s_c: f64,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let n = sys.dof();
    let mut m = DMatrix::zeros(n, n);
    sys.add_mass(s, &mut m);
    let mut c = DMatrix::zeros(n, n);
    if let Some(d) = sys.get_damping() {
        d.iter().enumerate().for_each(|(i, ci)| c[(i, i)] = s_c * ci);
    }
    (m, c)
}

impl<P: LocalPotential> StepJacobian for MechanicalMidpoint<P> {
    fn step_jacobian(&self, _t: f64, h: f64, q0: &[f64], q1: &[f64]) -> Result<DMatrix<f64>> {
        let sys = self.system();
        let n = q0.len();
        let mid: Vec<f64> = q0.iter().zip(q1).map(|(a, b)| 0.5 * (a + b)).collect();
        let (m, c) = mass_and_damping(sys, 1.0 / h, 0.5);
        let mut hq = DMatrix::zeros(n, n);
        sys.add_hessian(&mid, 0.25 * h, &mut hq);
        let j = &m + &c + &hq;
        let k = &m + &c - &hq;
        let pm = &m - &c - &hq;
        let qm = &m - &c + &hq;
        let lu =
            DenseFactor::lu(j).map_err(|e| e.in_matrix("midpoint Newton Jacobian in the step Jacobian"))?;
        let qq = lu.solve_matrix(&k);
        let qp = lu.solve_matrix(&DMatrix::identity(n, n));
        let pq = &pm * &qq - qm;
        let pp = &pm * &qp;
        Ok(blocks(&qq, &qp, &pq, &pp))
    }
}

impl<P: LocalPotential> StepJacobian for Verlet<P> {
    fn step_jacobian(&self, _t: f64, h: f64, q0: &[f64], q1: &[f64]) -> Result<DMatrix<f64>> {
        let sys = self.system();
        let n = q0.len();
        let (m, c) = mass_and_damping(sys, 1.0, 0.5 * h);
        let (mut h0, mut h1) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
        sys.add_hessian(q0, 0.5 * h, &mut h0);
        sys.add_hessian(q1, 0.5 * h, &mut h1);
        let lu =
            DenseFactor::lu(&m + &c).map_err(|e| e.in_matrix("M + (h/2)C in the Verlet step Jacobian"))?;
        let vq = -lu.solve_matrix(&h0);
        let vp = lu.solve_matrix(&DMatrix::identity(n, n));
        let qq = DMatrix::identity(n, n) + h * &vq;
        let qp = h * &vp;
        let r = &m - &c;
        let pq = &r * &vq - &h1 * &qq;
        let pp = &r * &vp - &h1 * &qp;
        Ok(blocks(&qq, &qp, &pq, &pp))
    }
}

/// [`SignedTangentStepper`] of each map (its signed step, then its [`StepJacobian`] by
/// [`step_then_jacobian`]) and [`TangentStepper`] (the forward step of the former).
macro_rules! tangent_steppers {
    ($($ty:ident<$g:ident: $b:path>),*) => {$(
        impl<$g: $b> SignedTangentStepper for $ty<$g> {
            fn step_signed_tangent(
                &mut self,
                state: &mut State<Momenta>,
                h: f64,
                psi: &mut DMatrix<f64>,
            ) -> Result<StepInfo> {
                step_then_jacobian(self, state, h, psi)
            }
        }

        impl<$g: $b> TangentStepper for $ty<$g> {
            fn step_tangent(
                &mut self,
                state: &mut State<Momenta>,
                h: f64,
                psi: &mut DMatrix<f64>,
            ) -> Result<StepInfo> {
                step_forward_tangent(self, state, h, psi)
            }
        }
    )*};
}
tangent_steppers!(VariationalIntegrator<Ld: DiscreteLagrangian>, MechanicalMidpoint<P: LocalPotential>, Verlet<P: LocalPotential>);
