//! Lagrange's equations by dual numbers.
//!
//! For L(t, q, q̇) with mass matrix M = ∂²L/∂q̇² and generalized forces Q, Lagrange's equations
//! `d/dt(∂L/∂q̇) − ∂L/∂q = Q` expand to
//!
//! ```text
//! M q̈ = ∂L/∂q − (∂²L/∂q̇∂q)·q̇ − ∂²L/∂q̇∂t + Q
//! ```
//!
//! [`EulerLagrange`] evaluates the right-hand side without any hand-written derivative:
//! - up to `JET_MAX` (10) degrees of freedom, one evaluation of L with a
//!   [`LagrangeJet`](ad::LagrangeJet) gives ∂L/∂q, the term (∂²L/∂q̇∂q)·q̇ + ∂²L/∂q̇∂t (a
//!   Hessian-vector product, never the full mixed Hessian) and M together, and M q̈ = b is solved by a
//!   square-root-free LDLᵀ factorization on the stack ([`linalg::solve_positive_fixed`]): no heap
//!   allocation, no square root, one division per pivot;
//! - a mass matrix declared constant is factored once and never differentiated again (then only a
//!   gradient and a Hessian-vector product are evaluated);
//! - larger systems record one evaluation of L on a tape ([`ad::lagrange_terms_taped`]): one reverse
//!   sweep gives ∂L/∂q, and the second derivatives (M and the mixed term) are pulled back through
//!   the nonlinear operations only, so their cost follows the model's sparsity in q̇ instead of
//!   carrying an N×N Hessian through every operation; with a constant mass matrix, the chunked
//!   gradient and Hessian-vector product kernels of [`ad`] suffice.
//!
//! M must be positive definite (a positive kinetic energy ½ q̇ᵀ M q̇ for every q̇ ≠ 0): a regular
//! but indefinite M (a negative mass) is [`Error::IndefiniteMassMatrix`] at the time it is met (t = 0
//! for a mass matrix that is negative from the start, not a step-size underflow later), a singular
//! one [`Error::SingularMassMatrix`].

use crate::ad::{self, Block, Field};
use crate::error::{check_finite, check_len, check_phase_point, check_result, finite_result};
use crate::linalg::{self, DenseFactor};
use crate::newton::{DenseProblem, Newton};
use crate::{Error, Lagrangian, Momenta, Result, Scalar, State, Velocities};
use nalgebra::{DMatrix, DVector, SMatrix, SVector};
use std::sync::OnceLock;

/// Largest number of degrees of freedom whose accelerations come from one
/// [`LagrangeJet`](ad::LagrangeJet) evaluation; above it, from one taped evaluation. The jet carries
/// the N×N mass matrix through every operation on q̇, the tape only the q̇-gradients of the arguments
/// of each nonlinear operation: on the pendulum chain the jet is 1.2× faster at 8 links, they are
/// within 10 % at 10 (where the jet's stack solve keeps its path allocation-free), and the tape is
/// 1.7× faster at 12 (docs/benchmarks.md, `terms_chain*`).
const JET_MAX: usize = 10;

/// A Lagrangian seen as the AD field f(t, x = q, y = q̇).
pub(crate) struct LagrangianField<'a, L: ?Sized>(pub &'a L);

impl<L: Lagrangian + ?Sized> Field for LagrangianField<'_, L> {
    #[inline]
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D]) -> D {
        self.0.lagrangian(t, x, y)
    }
}

/// Overwrites `b` with M⁻¹ b for a small mass matrix held on the stack
/// ([`linalg::solve_positive_fixed`]: square-root-free LDLᵀ, M = L D Lᵀ, with linalg's pivot test).
/// An indefinite, singular or non-finite M goes through [`linalg::factor_positive_mass`] for the error
/// it reports (or, for a borderline M that passes its test, the solution by its Cholesky factor).
#[inline]
fn solve_mass_fixed<const N: usize>(m: SMatrix<f64, N, N>, b: &mut SVector<f64, N>, t: f64) -> Result<()> {
    if linalg::solve_positive_fixed(m, b) {
        return Ok(());
    }
    linalg::factor_positive_mass(DMatrix::from_column_slice(N, N, m.as_slice()), t)
        .map(|f| f.solve_in_place(b.as_mut_slice()))
}

/// Copies finite accelerations into `a`; a non-finite one is the model's failure, reported as such.
#[inline]
fn finish(b: &[f64], a: &mut [f64], t: f64) -> Result<()> {
    check_result("accelerations", t, b)?;
    a.copy_from_slice(b);
    Ok(())
}

/// The Euler-Lagrange equations of a [`Lagrangian`]: accelerations, momenta, energy, Legendre maps.
pub struct EulerLagrange<L> {
    lagrangian: L,
    constant_mass: OnceLock<std::result::Result<DenseFactor, Error>>,
}

impl<L: Lagrangian> EulerLagrange<L> {
    /// Wraps a Lagrangian.
    pub fn new(lagrangian: L) -> Self {
        EulerLagrange {
            lagrangian,
            constant_mass: OnceLock::new(),
        }
    }

    /// The wrapped Lagrangian.
    pub fn lagrangian(&self) -> &L {
        &self.lagrangian
    }

    /// Number of degrees of freedom.
    pub fn dof(&self) -> usize {
        self.lagrangian.dof()
    }

    fn check(&self, t: f64, q: &[f64], v: &[f64]) -> Result<()> {
        let n = self.dof();
        check_len("q", q, n)?;
        check_len("q̇", v, n)?;
        check_finite("t", &[t])?;
        check_finite("q", q)?;
        check_finite("q̇", v)
    }

    /// The value of L.
    pub fn value(&self, t: f64, q: &[f64], v: &[f64]) -> Result<f64> {
        self.check(t, q, v)?;
        finite_result("Lagrangian", t, self.lagrangian.lagrangian(t, q, v))
    }

    /// Mass matrix M = ∂²L/∂q̇².
    pub fn mass_matrix(&self, t: f64, q: &[f64], v: &[f64]) -> Result<DMatrix<f64>> {
        self.check(t, q, v)?;
        let n = self.dof();
        let f = LagrangianField(&self.lagrangian);
        if n > JET_MAX {
            // One taped evaluation instead of one wide Dual2 or ⌈n/8⌉² hyper-dual evaluations.
            let m = ad::lagrange_terms_taped(&f, t, q, v).hess_yy;
            check_result("mass matrix", t, m.as_slice())?;
            return Ok(m);
        }
        let mut m = DMatrix::zeros(n, n);
        ad::hessian(&f, t, q, v, Block::Y, Block::Y, &mut m);
        check_result("mass matrix", t, m.as_slice())?;
        Ok(m)
    }

    /// The factored mass matrix at (t, q, q̇); computed once when the Lagrangian declares it constant.
    pub fn mass_factor(&self, t: f64, q: &[f64], v: &[f64]) -> Result<DenseFactor> {
        if self.lagrangian.constant_mass_matrix() {
            return self.constant_factor(t, q, v).cloned();
        }
        linalg::factor_positive_mass(self.mass_matrix(t, q, v)?, t)
    }

    fn constant_factor(&self, t: f64, q: &[f64], v: &[f64]) -> Result<&DenseFactor> {
        self.constant_mass
            .get_or_init(|| linalg::factor_positive_mass(self.mass_matrix(t, q, v)?, t))
            .as_ref()
            .map_err(Clone::clone)
    }

    /// Overwrites `b` with x = M(t, q, q̇)⁻¹ b, the solution of M x = b (no copy of a constant factor).
    ///
    /// `q`, `q̇` and `b` must have the model's length n ([`Error::Dimension`]) and be finite
    /// ([`Error::NonFinite`]); an x that is not finite (M⁻¹ b overflows) is
    /// [`Error::NonFiniteResult`]. On any error `b` is left as it was.
    pub fn solve_mass(&self, t: f64, q: &[f64], v: &[f64], b: &mut [f64]) -> Result<()> {
        self.check(t, q, v)?;
        check_len("b (right-hand side of M x = b)", b, self.dof())?;
        check_finite("b (right-hand side of M x = b)", b)?;
        let mut x = b.to_vec();
        if self.lagrangian.constant_mass_matrix() {
            self.constant_factor(t, q, v)?.solve_in_place(&mut x);
        } else {
            linalg::factor_positive_mass(self.mass_matrix(t, q, v)?, t)?.solve_in_place(&mut x);
        }
        check_result("M⁻¹ b", t, &x)?;
        b.copy_from_slice(&x);
        Ok(())
    }

    /// Accelerations q̈ = M⁻¹ (∂L/∂q − (∂²L/∂q̇∂q)·q̇ − ∂²L/∂q̇∂t + Q), written into `a`.
    ///
    /// Up to `JET_MAX` (10) degrees of freedom everything comes from one evaluation of L with a
    /// [`LagrangeJet`](ad::LagrangeJet) and M is factored on the stack by a square-root-free LDLᵀ (no
    /// heap allocation); larger systems take one taped evaluation of L ([`ad::lagrange_terms_taped`])
    /// and linalg's dense factor (nalgebra's Cholesky).
    pub fn accelerations(&self, t: f64, q: &[f64], v: &[f64], a: &mut [f64]) -> Result<()> {
        self.check(t, q, v)?;
        check_len("q̈ (output)", a, self.dof())?;
        match self.dof() {
            0 => Ok(()),
            1 => self.accelerations_fixed::<1>(t, q, v, a),
            2 => self.accelerations_fixed::<2>(t, q, v, a),
            3 => self.accelerations_fixed::<3>(t, q, v, a),
            4 => self.accelerations_fixed::<4>(t, q, v, a),
            5 => self.accelerations_fixed::<5>(t, q, v, a),
            6 => self.accelerations_fixed::<6>(t, q, v, a),
            7 => self.accelerations_fixed::<7>(t, q, v, a),
            8 => self.accelerations_fixed::<8>(t, q, v, a),
            9 => self.accelerations_fixed::<9>(t, q, v, a),
            10 => self.accelerations_fixed::<10>(t, q, v, a),
            _ => self.accelerations_dyn(t, q, v, a),
        }
    }

    /// The static path: one jet evaluation, stack LDLᵀ.
    #[inline]
    fn accelerations_fixed<const N: usize>(&self, t: f64, q: &[f64], v: &[f64], a: &mut [f64]) -> Result<()> {
        let (Ok(qn), Ok(vn)) = (<&[f64; N]>::try_from(q), <&[f64; N]>::try_from(v)) else {
            unreachable!("lengths checked by the caller")
        };
        let f = LagrangianField(&self.lagrangian);
        if self.lagrangian.constant_mass_matrix() {
            // M is factored once: no second derivative in q̇ at all, only ∂L/∂q (one gradient) and the
            // mixed term (one Hessian-vector product), both with small stack duals.
            let (mut g, mut mixed) = ([0.0; N], [0.0; N]);
            ad::gradient(&f, t, q, v, Block::X, &mut g);
            ad::directional_gradient(&f, t, q, v, (1.0, v, &[]), Block::Y, &mut mixed, None);
            let mut b = SVector::from(g) - SVector::from(mixed);
            self.add_generalized_force(t, q, v, &mut b);
            self.constant_factor(t, q, v)?.solve_in_place(b.as_mut_slice());
            return finish(b.as_slice(), a, t);
        }
        let terms = ad::lagrange_terms(&f, t, qn, vn);
        let mut b = terms.grad_x - terms.mixed;
        self.add_generalized_force(t, q, v, &mut b);
        solve_mass_fixed(terms.hess_yy, &mut b, t)?;
        finish(b.as_slice(), a, t)
    }

    /// b += Q(t, q, q̇) when the model has generalized forces.
    #[inline]
    fn add_generalized_force<const N: usize>(&self, t: f64, q: &[f64], v: &[f64], b: &mut SVector<f64, N>) {
        if self.lagrangian.has_generalized_force() {
            let mut qf = [0.0; N];
            self.lagrangian.generalized_force(t, q, v, &mut qf);
            *b += SVector::from(qf);
        }
    }

    /// The run-time-sized path (more than `JET_MAX` (10) degrees of freedom). A mass matrix
    /// declared constant is factored once, and only ∂L/∂q and the mixed term are evaluated (chunked
    /// gradient and Hessian-vector product); otherwise one taped evaluation of L
    /// ([`ad::lagrange_terms_taped`]) gives ∂L/∂q, the mixed term and M together, and M is factored
    /// densely.
    fn accelerations_dyn(&self, t: f64, q: &[f64], v: &[f64], a: &mut [f64]) -> Result<()> {
        let f = LagrangianField(&self.lagrangian);
        let n = self.dof();
        // b = ∂L/∂q − mixed (+ Q below), then M⁻¹ b; `a` is written only on success.
        let (mut b, varying) = if self.lagrangian.constant_mass_matrix() {
            let (mut g, mut mixed) = (vec![0.0; n], vec![0.0; n]);
            ad::gradient(&f, t, q, v, Block::X, &mut g);
            ad::directional_gradient(&f, t, q, v, (1.0, v, &[]), Block::Y, &mut mixed, None);
            g.iter_mut().zip(&mixed).for_each(|(gi, mi)| *gi -= mi);
            (g, None)
        } else {
            let terms = ad::lagrange_terms_taped(&f, t, q, v);
            let b = (terms.grad_x - terms.mixed).data.into();
            (b, Some(linalg::factor_positive_mass(terms.hess_yy, t)?))
        };
        if self.lagrangian.has_generalized_force() {
            let mut qf = vec![0.0; n];
            self.lagrangian.generalized_force(t, q, v, &mut qf);
            b.iter_mut().zip(&qf).for_each(|(bi, qi)| *bi += qi);
        }
        match varying {
            Some(factor) => factor.solve_in_place(&mut b),
            None => self.constant_factor(t, q, v)?.solve_in_place(&mut b),
        }
        finish(&b, a, t)
    }

    /// Generalized momenta p = ∂L/∂q̇ (the Legendre map), written into `p`.
    pub fn momenta(&self, t: f64, q: &[f64], v: &[f64], p: &mut [f64]) -> Result<()> {
        self.check(t, q, v)?;
        check_len("p (output)", p, self.dof())?;
        let mut out = vec![0.0; self.dof()];
        self.momenta_unchecked(t, q, v, &mut out);
        check_result("momenta", t, &out)?;
        p.copy_from_slice(&out);
        Ok(())
    }

    /// ∂L/∂q̇ into `p` (lengths right), NaN where q̇ lies outside the model's domain: the inverse
    /// Legendre map's Newton uses that to pull its iterate back in.
    fn momenta_unchecked(&self, t: f64, q: &[f64], v: &[f64], p: &mut [f64]) {
        ad::gradient(&LagrangianField(&self.lagrangian), t, q, v, Block::Y, p);
    }

    /// The energy function h = q̇·∂L/∂q̇ − L (conserved when L does not depend on t explicitly and Q = 0).
    pub fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> Result<f64> {
        self.check(t, q, v)?;
        let mut p = vec![0.0; self.dof()];
        let l = ad::gradient(&LagrangianField(&self.lagrangian), t, q, v, Block::Y, &mut p);
        finite_result(
            "energy",
            t,
            p.iter().zip(v).map(|(pi, vi)| pi * vi).sum::<f64>() - l,
        )
    }

    /// ∂L/∂q (the generalized force of the potential part).
    pub fn gradient_q(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) -> Result<()> {
        self.check(t, q, v)?;
        check_len("∂L/∂q (output)", out, self.dof())?;
        let mut g = vec![0.0; self.dof()];
        ad::gradient(&LagrangianField(&self.lagrangian), t, q, v, Block::X, &mut g);
        check_result("∂L/∂q", t, &g)?;
        out.copy_from_slice(&g);
        Ok(())
    }

    /// The state in momenta: (t, q, q̇) ↦ (t, q, p = ∂L/∂q̇), the Legendre map at a visible boundary
    /// between Lagrangian steppers and Hamiltonian or variational ones.
    pub fn to_momenta(&self, state: &State<Velocities>) -> Result<State<Momenta>> {
        let mut p = DVector::zeros(self.dof());
        self.momenta(state.t, state.q.as_slice(), state.v.as_slice(), p.as_mut_slice())?;
        Ok(State::from_vectors(state.t, state.q.clone(), p))
    }

    /// The state in velocities: (t, q, p) ↦ (t, q, q̇) by the inverse Legendre map
    /// ([`velocities`](Self::velocities)).
    pub fn to_velocities(&self, state: &State<Momenta>) -> Result<State<Velocities>> {
        state.validate(self.dof())?;
        let v = self.velocities(state.t, state.q.as_slice(), state.v.as_slice())?;
        Ok(State::from_vectors(state.t, state.q.clone(), v))
    }

    /// Inverse Legendre map: the velocities q̇ with ∂L/∂q̇(t, q, q̇) = p, by Newton's method with the
    /// mass matrix as Jacobian, started from q̇ = M(t, q, 0)⁻¹ p (exact when L is quadratic in q̇),
    /// halved toward 0 while the momenta there are not finite (a start outside the model's domain).
    pub fn velocities(&self, t: f64, q: &[f64], p: &[f64]) -> Result<DVector<f64>> {
        let v0 = self.velocity_start(t, q, p)?;
        self.velocities_from(t, q, p, &v0)
    }

    /// The start of [`velocities`](Self::velocities): q̇ = M(t, q, 0)⁻¹ p, halved toward 0 while the
    /// momenta there are not finite.
    pub(crate) fn velocity_start(&self, t: f64, q: &[f64], p: &[f64]) -> Result<Vec<f64>> {
        let n = self.dof();
        check_len("p", p, n)?;
        check_finite("p", p)?;
        let zero = vec![0.0; n];
        let mut v0 = p.to_vec();
        self.solve_mass(t, q, &zero, &mut v0)?;
        // Pull the start back into the model's domain if it lies outside (p/m may exceed c).
        let mut r = vec![0.0; n];
        for _ in 0..60 {
            self.momenta_unchecked(t, q, &v0, &mut r);
            if r.iter().all(|x| x.is_finite()) {
                break;
            }
            v0.iter_mut().for_each(|x| *x *= 0.5);
        }
        Ok(v0)
    }

    /// Newton's method for ∂L/∂q̇(t, q, q̇) = p from the start `v0` (residual tolerance
    /// 1e-13·(1 + ‖p‖∞)).
    pub(crate) fn velocities_from(&self, t: f64, q: &[f64], p: &[f64], v0: &[f64]) -> Result<DVector<f64>> {
        check_phase_point(self.dof(), t, q, p, "p")?;
        check_len("q̇ (start)", v0, self.dof())?;
        struct InverseLegendre<'a, L> {
            el: &'a EulerLagrange<L>,
            t: f64,
            q: &'a [f64],
            p: &'a [f64],
        }
        impl<L: Lagrangian> DenseProblem for InverseLegendre<'_, L> {
            fn dim(&self) -> usize {
                self.p.len()
            }
            fn residual(&mut self, v: &[f64], r: &mut [f64]) -> Result<()> {
                // Non-finite outside the model's domain: Newton halves its step back in.
                self.el.momenta_unchecked(self.t, self.q, v, r);
                r.iter_mut().zip(self.p).for_each(|(ri, pi)| *ri -= pi);
                Ok(())
            }
            fn jacobian(&mut self, v: &[f64], j: &mut DMatrix<f64>) -> Result<()> {
                *j = self.el.mass_matrix(self.t, self.q, v)?;
                Ok(())
            }
        }
        let scale = 1.0 + crate::newton::max_norm(p);
        let newton = Newton::default().residual_tolerance(1e-13 * scale)?;
        let (v, _) = crate::newton::solve_dense(&newton, InverseLegendre { el: self, t, q, p }, v0)?;
        Ok(v)
    }
}
