//! Canonical transformations given as maps (Q, P) = φ(t, q, p): the symplectic condition by AD, the
//! fundamental brackets of the new variables, the inverse map by core's Newton, and the check that a
//! proposed K is the new Hamiltonian.
//!
//! With z = (q, p), Z = (Q, P), J = ∂Z/∂z (2n × 2n) and Ω = [[0, I], [−I, 0]], φ is canonical at a
//! point exactly when
//!
//! ```text
//! Jᵀ Ω J = Ω   (the Lagrange brackets [zₐ, z_b] are Ω)   ⇔   J Ω Jᵀ = Ω   (the Poisson brackets
//!                                                              {Zₐ, Z_b} in the old variables are Ω),
//! ```
//!
//! i.e. {Qᵢ, Pⱼ} = δᵢⱼ and {Qᵢ, Qⱼ} = {Pᵢ, Pⱼ} = 0. A motion ż = Ω∇H is carried to Ż = J Ω∇H + ∂φ/∂t,
//! and K is the Hamiltonian of the new variables when that equals Ω∇K at Z = φ(z)
//! ([`new_hamiltonian_defect`]). For a time-independent canonical map K = H∘φ⁻¹; for a
//! time-dependent one K = H + ∂F/∂t with F a generating function of φ (see
//! [`generating`](crate::generating)).
//!
//! ```
//! use noether_canonical::transform::{canonicity, CanonicalMap};
//! use noether_core::Scalar;
//!
//! /// Polar coordinates from Cartesian ones, extended to momenta (a point transformation):
//! /// r, θ and p_r = (x p_x + y p_y)/r, p_θ = x p_y − y p_x.
//! struct Polar;
//! impl CanonicalMap for Polar {
//!     fn dof(&self) -> usize { 2 }
//!     fn map<D: Scalar>(&self, _t: D, q: &[D], p: &[D], nq: &mut [D], np: &mut [D]) {
//!         let r = (q[0] * q[0] + q[1] * q[1]).sqrt();
//!         nq[0] = r;
//!         nq[1] = q[1].atan2(q[0]);
//!         np[0] = (q[0] * p[0] + q[1] * p[1]) / r;
//!         np[1] = q[0] * p[1] - q[1] * p[0];
//!     }
//! }
//! let c = canonicity(&Polar, 0.0, &[0.8, -0.3], &[0.2, 1.1]).unwrap();
//! assert!(c.symplectic < 1e-15 && c.brackets < 1e-15);
//! ```

use crate::poisson::{self, PhaseFunction};
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector};
use noether_core::error::check_result;
use noether_core::newton::{solve_dense, DenseProblem};
use noether_core::{Hamiltonian, Newton, NewtonInfo, Scalar};

/// A transformation of phase space (Q, P) = φ(t, q, p) on n = `dof()` degrees of freedom, written once
/// as generic code.
pub trait CanonicalMap {
    /// Number n of coordinates (old and new).
    fn dof(&self) -> usize;
    /// Writes the new coordinates Q and momenta P (length n each) of the point (t, q, p).
    fn map<D: Scalar>(&self, t: D, q: &[D], p: &[D], new_q: &mut [D], new_p: &mut [D]);
}

/// A [`CanonicalMap`] seen as the phase function z ↦ (Q, P) with 2n outputs, so that
/// [`poisson::bracket`] gives the brackets {Zₐ, Z_b} of the new variables.
#[derive(Debug, Clone, Copy)]
pub struct Components<'a, M>(pub &'a M);

impl<M: CanonicalMap> PhaseFunction for Components<'_, M> {
    fn phase_dof(&self) -> usize {
        self.0.dof()
    }
    fn outputs(&self) -> usize {
        2 * self.0.dof()
    }
    #[inline]
    fn values<D: Scalar>(&self, t: D, q: &[D], p: &[D], out: &mut [D]) {
        let (nq, np) = out.split_at_mut(q.len());
        self.0.map(t, q, p, nq, np);
    }
}

/// The symplectic matrix Ω = [[0, I], [−I, 0]] of n degrees of freedom (2n × 2n).
pub fn omega(n: usize) -> DMatrix<f64> {
    DMatrix::from_fn(2 * n, 2 * n, |i, j| {
        if j == i + n {
            1.0
        } else if i == j + n {
            -1.0
        } else {
            0.0
        }
    })
}

/// ‖Jᵀ Ω J − Ω‖_max of a square 2n × 2n Jacobian (0 exactly for a canonical linearisation).
pub fn symplectic_defect(j: &DMatrix<f64>) -> f64 {
    let o = omega(j.nrows() / 2);
    (j.transpose() * &o * j - o).amax()
}

/// The new point (Q, P) = φ(t, q, p), checked (dimensions, finite input and output).
pub fn apply<M: CanonicalMap>(m: &M, t: f64, q: &[f64], p: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
    let z = poisson::values(&Components(m), t, q, p)?;
    let n = m.dof();
    Ok((z[..n].to_vec(), z[n..].to_vec()))
}

/// The Jacobian J = ∂(Q, P)/∂(q, p) (2n × 2n, columns q then p), exact by dual numbers.
pub fn jacobian<M: CanonicalMap>(m: &M, t: f64, q: &[f64], p: &[f64]) -> Result<DMatrix<f64>> {
    let (zq, zp) = poisson::jacobians(&Components(m), t, q, p)?;
    let n = m.dof();
    let mut j = DMatrix::zeros(2 * n, 2 * n);
    j.view_mut((0, 0), (2 * n, n)).copy_from(&zq);
    j.view_mut((0, n), (2 * n, n)).copy_from(&zp);
    Ok(j)
}

/// ∂φ/∂t at fixed (q, p) (length 2n: ∂Q/∂t then ∂P/∂t), one `Dual64` evaluation.
pub fn partial_t<M: CanonicalMap>(m: &M, t: f64, q: &[f64], p: &[f64]) -> Result<Vec<f64>> {
    let n = m.dof();
    poisson::check_point(n, t, q, p)?;
    let zero = vec![0.0; n];
    let mut out = vec![0.0; 2 * n];
    poisson::along(&Components(m), (t, q, p), (1.0, &zero, &zero), &mut out);
    check_result("∂φ/∂t", t, &out)?;
    Ok(out)
}

/// How far φ is from canonical at one point, by two independent measures.
#[derive(Debug, Clone, PartialEq)]
pub struct Canonicity {
    /// ‖Jᵀ Ω J − Ω‖_max (the Lagrange brackets of the old variables against Ω).
    pub symplectic: f64,
    /// ‖{Z, Z} − Ω‖_max: the Poisson brackets {Qᵢ, Pⱼ} − δᵢⱼ, {Qᵢ, Qⱼ}, {Pᵢ, Pⱼ} in the old variables.
    pub brackets: f64,
    /// The bracket matrix {Zₐ, Z_b} itself (2n × 2n, Q first).
    pub bracket_matrix: DMatrix<f64>,
    /// The Jacobian J = ∂(Q, P)/∂(q, p).
    pub jacobian: DMatrix<f64>,
}

/// The symplectic condition of φ at (t, q, p): the defects ‖JᵀΩJ − Ω‖ and ‖{Z, Z} − Ω‖ (0 to rounding
/// for a canonical map), the bracket matrix and J.
pub fn canonicity<M: CanonicalMap>(m: &M, t: f64, q: &[f64], p: &[f64]) -> Result<Canonicity> {
    let j = jacobian(m, t, q, p)?;
    let c = Components(m);
    let b = poisson::bracket(&c, &c, t, q, p)?;
    let o = omega(m.dof());
    Ok(Canonicity {
        symplectic: symplectic_defect(&j),
        brackets: (&b - o).amax(),
        bracket_matrix: b,
        jacobian: j,
    })
}

/// Core's Newton with tolerances set below what rounding allows (residual 1e-15, step 1e-16), so that
/// it stops on its round-off rule (increments no longer decreasing at the rounding level): the
/// solutions of implicit relations here are then exact to rounding, as the derivatives are. The
/// default of [`Generated`](crate::generating::Generated) and what the tests and examples pass to
/// [`invert`] and the Hamilton-Jacobi solves. (Core's default, residual 1e-12, leaves errors ~1e-12.)
pub fn newton_to_rounding() -> Newton {
    let limits = |n: Newton| n.residual_tolerance(1e-15)?.step_tolerance(1e-16);
    limits(Newton::default()).expect("positive tolerances")
}

/// φ(z) − Z* = 0 for z, with the AD Jacobian.
struct Inverse<'a, M> {
    map: &'a M,
    t: f64,
    target: Vec<f64>,
}

impl<M: CanonicalMap> DenseProblem for Inverse<'_, M> {
    fn dim(&self) -> usize {
        2 * self.map.dof()
    }
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> noether_core::Result<()> {
        let n = self.map.dof();
        let (nq, np) = r.split_at_mut(n);
        self.map.map(self.t, &z[..n], &z[n..], nq, np);
        for (ri, ti) in r.iter_mut().zip(&self.target) {
            *ri -= ti;
        }
        Ok(())
    }
    fn jacobian(&mut self, z: &[f64], j: &mut DMatrix<f64>) -> noether_core::Result<()> {
        let n = self.map.dof();
        let jz = jacobian(self.map, self.t, &z[..n], &z[n..]).map_err(noether_core::Error::from)?;
        j.copy_from(&jz);
        Ok(())
    }
}

/// The inverse map: the old point (q, p) with φ(t, q, p) = (Q, P), by core's Newton from the guess
/// (q₀, p₀) with the Jacobian by AD. Returns q, p and Newton's statistics; a singular Jacobian
/// (φ not invertible there) or no convergence is an error.
pub fn invert<M: CanonicalMap>(
    m: &M,
    t: f64,
    (new_q, new_p): (&[f64], &[f64]),
    (guess_q, guess_p): (&[f64], &[f64]),
    newton: &Newton,
) -> Result<(Vec<f64>, Vec<f64>, NewtonInfo)> {
    let n = m.dof();
    poisson::check_point(n, t, new_q, new_p)?;
    poisson::check_point(n, t, guess_q, guess_p)?;
    let target = [new_q, new_p].concat();
    let guess = [guess_q, guess_p].concat();
    let (z, info) = solve_dense(newton, Inverse { map: m, t, target }, &guess)?;
    check_result("inverse canonical map", t, z.as_slice())?;
    Ok((z.as_slice()[..n].to_vec(), z.as_slice()[n..].to_vec(), info))
}

/// The defect of K as the Hamiltonian of the new variables at the old point z = (q, p):
/// ‖J Ω∇H(z) + ∂φ/∂t − Ω∇K(φ(z))‖_max, the difference between the motion of H carried over by φ
/// and the motion K generates (0 to rounding when K is the new Hamiltonian; valid for
/// time-dependent maps, where K ≠ H∘φ⁻¹). H is a function of (t, q, p), K of (t, Q, P).
pub fn new_hamiltonian_defect<M, H, K>(m: &M, h: &H, k: &K, t: f64, q: &[f64], p: &[f64]) -> Result<f64>
where
    M: CanonicalMap,
    H: Hamiltonian,
    K: Hamiltonian,
{
    let n = m.dof();
    for d in [h.dof(), k.dof()] {
        if d != n {
            return Err(Error::PhaseSpaceMismatch { first: n, second: d });
        }
    }
    let carried = carried_rates(m, h, t, q, p)?;
    let (nq, np) = apply(m, t, q, p)?;
    let (kq, kp) = poisson::hamilton_field(k, t, &nq, &np)?;
    let kz = DVector::from_vec([kq, kp].concat());
    Ok((carried - kz).amax())
}

/// Ż = J Ω∇H + ∂φ/∂t: the motion of H seen in the new variables.
pub fn carried_rates<M: CanonicalMap, H: Hamiltonian>(
    m: &M,
    h: &H,
    t: f64,
    q: &[f64],
    p: &[f64],
) -> Result<DVector<f64>> {
    let j = jacobian(m, t, q, p)?;
    let (dq, dp) = poisson::hamilton_field(h, t, q, p)?;
    let zt = partial_t(m, t, q, p)?;
    Ok(j * DVector::from_vec([dq, dp].concat()) + DVector::from_vec(zt))
}
