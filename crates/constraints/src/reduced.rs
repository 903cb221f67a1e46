//! A Lagrangian in dependent coordinates with holonomic constraints, seen in independent ones: the
//! reduction SymPy's `Linearizer` and `KanesMethod` make, done by the implicit function theorem in
//! dual arithmetic so that every derivative noether takes of the reduced system is exact.
//!
//! The n coordinates q split into n − m independent q_i (chosen by the user, as in SymPy) and m
//! dependent q_d, tied by φ(t, q) = 0 with ∂φ/∂q_d = Φ_d regular. Near a reference configuration the
//! constraints define q_d(t, q_i), and
//!
//! ```text
//! L_r(t, q_i, q̇_i) = L(t, q, q̇),   q = (q_i, q_d(t, q_i)),   q̇_d = −Φ_d⁻¹ (Φ_i q̇_i + ∂φ/∂t),
//! Q_r = Pᵀ Q,   P = ∂q/∂q_i = [I; −Φ_d⁻¹ Φ_i],
//! ```
//!
//! (the forces by virtual work: Q·δq = Q·P δq_i). [`Reduced`] is an ordinary [`Lagrangian`] (and
//! [`Actuated`] when the model is), so every integrator, linearisation (`noether_analysis::linearize`:
//! (A, B) in the independent coordinates), LQR design and tangent applies to it unchanged.
//!
//! A pendulum written as a point in the plane on a rod, reduced to its horizontal coordinate x: at
//! x = 0.6 (l = 1, at rest) the bob's angle has sin θ = 0.6, θ̈ = −g sin θ, and ẍ = l cos θ θ̈ =
//! −g · 0.6 · 0.8:
//!
//! ```
//! use noether_constraints::{Holonomic, Reduced};
//! use noether_core::prelude::*;
//!
//! /// A unit mass in the plane under gravity: L = ½(ẋ² + ẏ²) − g y.
//! struct Point;
//! impl Lagrangian for Point {
//!     fn dof(&self) -> usize { 2 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         (v[0] * v[0] + v[1] * v[1]) * 0.5 - q[1] * 9.81
//!     }
//! }
//! /// A rod of length 1 to the origin: φ = (x² + y² − 1)/2.
//! struct Rod;
//! impl Holonomic for Rod {
//!     fn dof(&self) -> usize { 2 }
//!     fn count(&self) -> usize { 1 }
//!     fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
//!         out[0] = (q[0] * q[0] + q[1] * q[1] - 1.0) * 0.5;
//!     }
//! }
//!
//! let pendulum = EulerLagrange::new(Reduced::new(Point, Rod, &[0], &[0.0, -1.0])?);
//! let (mut dq, mut dv) = ([0.0], [0.0]);
//! pendulum.rates(0.0, &[0.6], &[0.0], &mut dq, &mut dv)?;
//! assert!((dv[0] + 9.81 * 0.6 * 0.8).abs() < 1e-14);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! How q_d(t, q_i) is evaluated for any scalar: Newton on the real parts from the reference (the f64
//! solution), then three Newton steps q_d ← q_d − Φ_d⁻¹ φ in the scalar's own arithmetic, with Φ_d
//! by one more dual layer. Each step doubles the number of exact Taylor orders (Newton's quadratic
//! convergence acts on the truncated Taylor series as on numbers), so the derivatives of q_d are exact
//! through order 7 — more than the third derivatives of L a Jacobian of Lagrange's equations needs.
//! Where the real Newton solve fails (the constraints have no solution near the reference, or Φ_d
//! is singular) L_r is NaN, which every caller reports as a non-finite result.

use crate::holonomic::Holonomic;
use crate::{Error, Result};
use noether_core::control::Actuated;
use noether_core::error::{check_finite, check_len};
use noether_core::{Lagrangian, Scalar};
use num_dual::Dual;

/// A Lagrangian with holonomic constraints in independent coordinates (module docs).
#[derive(Debug, Clone)]
pub struct Reduced<L, C> {
    model: L,
    constraints: C,
    independent: Vec<usize>,
    dependent: Vec<usize>,
    /// The reference configuration: the start of the real Newton solve for q_d.
    reference: Vec<f64>,
}

/// The m dependent coordinates left by n − m `independent` ones (indices into q, each once, in
/// range), in increasing order. Errors: the wrong count (`Dimension`), a repeated or out-of-range
/// index (`InvalidParameter`).
pub(crate) fn dependent_coordinates(n: usize, m: usize, independent: &[usize]) -> Result<Vec<usize>> {
    if independent.len() != n.saturating_sub(m) {
        return Err(noether_core::Error::Dimension {
            what: "independent coordinates (n − m)",
            expected: n.saturating_sub(m),
            got: independent.len(),
        }
        .into());
    }
    for (k, &i) in independent.iter().enumerate() {
        if i >= n || independent[..k].contains(&i) {
            return Err(noether_core::Error::InvalidParameter {
                name: "independent coordinate index",
                value: i as f64,
                reason: "below the number of coordinates, each once",
            }
            .into());
        }
    }
    Ok((0..n).filter(|i| !independent.contains(i)).collect())
}

/// Newton steps in the scalar's arithmetic after the real solve (exact derivatives through order
/// 2³ − 1 = 7).
const DUAL_STEPS: usize = 3;
/// Real Newton iterations at most.
const MAX_ITERATIONS: usize = 50;

impl<L: Lagrangian, C: Holonomic> Reduced<L, C> {
    /// `model` with `constraints` in the coordinates `independent` (indices into q, n − m of them,
    /// each once), near the configuration `reference` (all n coordinates, on the constraints to 1e-10
    /// of their scale). Errors: dimensions, non-finite data, repeated or out-of-range indices, a
    /// reference off the constraints, or ∂φ/∂q_d singular there ([`Error::Core`] with
    /// `SingularMatrix`).
    pub fn new(model: L, constraints: C, independent: &[usize], reference: &[f64]) -> Result<Self> {
        let (n, m) = (model.dof(), constraints.count());
        if constraints.dof() != n {
            return Err(noether_core::Error::Dimension {
                what: "constraint coordinates",
                expected: n,
                got: constraints.dof(),
            }
            .into());
        }
        let dependent = dependent_coordinates(n, m, independent)?;
        check_len("reference configuration", reference, n)?;
        check_finite("reference configuration", reference)?;
        let reduced = Reduced {
            model,
            constraints,
            independent: independent.to_vec(),
            dependent,
            reference: reference.to_vec(),
        };
        let mut phi = vec![0.0; m];
        reduced.constraints.constraints(0.0, reference, &mut phi);
        let scale = reference.iter().fold(1.0_f64, |s, q| s.max(q.abs()));
        if let Some(&worst) = phi.iter().find(|p| p.is_nan() || p.abs() > 1e-10 * scale) {
            return Err(noether_core::Error::InvalidParameter {
                name: "constraint value at the reference configuration",
                value: worst,
                reason: "zero: the reference must satisfy the constraints",
            }
            .into());
        }
        let (_, phi_d) = reduced.jacobians(0.0, reference);
        if solve_in_place(phi_d, &mut vec![0.0; m]).is_none() {
            return Err(Error::Core(noether_core::Error::SingularMatrix {
                what: "∂φ/∂q_d at the reference (choose other independent coordinates)",
                pivot_ratio: 0.0,
            }));
        }
        Ok(reduced)
    }

    /// The full configuration q = (q_i, q_d(t, q_i)) (NaN where the constraints have no solution near
    /// the reference).
    pub fn configuration(&self, t: f64, qi: &[f64]) -> Vec<f64> {
        self.complete(t, qi)
    }

    /// The full configuration and velocity of the reduced state (t, q_i, q̇_i).
    pub fn state(&self, t: f64, qi: &[f64], vi: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (q, v, _) = self.lift(t, qi, vi);
        (q, v)
    }

    /// (Φ_i, Φ_d) = (∂φ/∂q_i, ∂φ/∂q_d) at (t, q), m × (n − m) and m × m, row-major, by one dual layer
    /// per column.
    fn jacobians<D: Scalar>(&self, t: D, q: &[D]) -> (Vec<Vec<D>>, Vec<Vec<D>>) {
        let m = self.constraints.count();
        let column = |j: usize| -> Vec<D> {
            let qd: Vec<Dual<D, f64>> = q
                .iter()
                .enumerate()
                .map(|(k, &x)| Dual::new(x, if k == j { D::one() } else { D::zero() }))
                .collect();
            let mut out = vec![Dual::from_re(D::zero()); m];
            self.constraints.constraints(Dual::from_re(t), &qd, &mut out);
            out.iter().map(|o| o.eps).collect()
        };
        let rows = |cols: &[usize]| -> Vec<Vec<D>> {
            let columns: Vec<Vec<D>> = cols.iter().map(|&j| column(j)).collect();
            (0..m).map(|r| columns.iter().map(|c| c[r]).collect()).collect()
        };
        (rows(&self.independent), rows(&self.dependent))
    }

    /// q = (q_i, q_d) for any scalar (module docs).
    fn complete<D: Scalar>(&self, t: D, qi: &[D]) -> Vec<D> {
        let m = self.constraints.count();
        let mut q: Vec<D> = self.reference.iter().map(|&x| D::from(x)).collect();
        for (&i, &x) in self.independent.iter().zip(qi) {
            q[i] = x;
        }
        // The real solve, from the reference.
        let mut real: Vec<f64> = q.iter().map(|x| x.re()).collect();
        let mut phi = vec![0.0; m];
        let mut converged = false;
        for _ in 0..MAX_ITERATIONS {
            self.constraints.constraints(t.re(), &real, &mut phi);
            let (_, phi_d) = self.jacobians(t.re(), &real);
            let Some(()) = solve_in_place(phi_d, &mut phi) else {
                break;
            };
            let step = phi.iter().fold(0.0_f64, |s, x| s.max(x.abs()));
            for (&d, dx) in self.dependent.iter().zip(&phi) {
                real[d] -= dx;
            }
            let scale = real.iter().fold(1.0_f64, |s, x| s.max(x.abs()));
            if step <= 4.0 * f64::EPSILON * scale {
                converged = true;
                break;
            }
        }
        if !converged {
            return vec![D::from(f64::NAN); q.len()];
        }
        for &d in &self.dependent {
            q[d] = D::from(real[d]);
        }
        // Newton in the scalar's arithmetic: the derivatives of q_d.
        let mut phi = vec![D::zero(); m];
        for _ in 0..DUAL_STEPS {
            self.constraints.constraints(t, &q, &mut phi);
            let (_, phi_d) = self.jacobians(t, &q);
            if solve_in_place(phi_d, &mut phi).is_none() {
                return vec![D::from(f64::NAN); q.len()];
            }
            for (&d, dx) in self.dependent.iter().zip(&phi) {
                q[d] -= *dx;
            }
        }
        q
    }

    /// The full state (q, q̇) of the reduced one (t, q_i, q̇_i) with the constraint Jacobians (Φ_i, Φ_d)
    /// at q: q by [`complete`](Self::complete), q̇ = (q̇_i, −Φ_d⁻¹ (Φ_i q̇_i + ∂φ/∂t)).
    #[allow(clippy::type_complexity)] // the state and the two Jacobians, computed once
    fn lift<D: Scalar>(&self, t: D, qi: &[D], vi: &[D]) -> (Vec<D>, Vec<D>, (Vec<Vec<D>>, Vec<Vec<D>>)) {
        let q = self.complete(t, qi);
        let m = self.constraints.count();
        let (phi_i, phi_d) = self.jacobians(t, &q);
        let qt: Vec<Dual<D, f64>> = q.iter().map(|&x| Dual::from_re(x)).collect();
        let mut rate = vec![Dual::from_re(D::zero()); m];
        self.constraints
            .constraints(Dual::new(t, D::one()), &qt, &mut rate);
        let mut rhs: Vec<D> = (0..m)
            .map(|r| rate[r].eps + phi_i[r].iter().zip(vi).fold(D::zero(), |s, (a, v)| s + *a * *v))
            .collect();
        let mut v = vec![D::from(f64::NAN); q.len()];
        if solve_in_place(phi_d.clone(), &mut rhs).is_some() {
            for (&i, &x) in self.independent.iter().zip(vi) {
                v[i] = x;
            }
            for (&d, x) in self.dependent.iter().zip(&rhs) {
                v[d] = -*x;
            }
        }
        (q, v, (phi_i, phi_d))
    }

    /// Q_r = Pᵀ Q for a force `full` on the n coordinates, P = [I; −Φ_d⁻¹ Φ_i], with the Jacobians
    /// (Φ_i, Φ_d) of [`lift`](Self::lift).
    fn project<D: Scalar>(&self, (phi_i, phi_d): &(Vec<Vec<D>>, Vec<Vec<D>>), full: &[D], out: &mut [D]) {
        // Pᵀ Q = Q_i − Φ_iᵀ (Φ_d⁻ᵀ Q_d).
        let m = phi_d.len();
        let transposed: Vec<Vec<D>> = (0..m).map(|r| (0..m).map(|c| phi_d[c][r]).collect()).collect();
        let mut w: Vec<D> = self.dependent.iter().map(|&d| full[d]).collect();
        if solve_in_place(transposed, &mut w).is_none() {
            out.iter_mut().for_each(|o| *o = D::from(f64::NAN));
            return;
        }
        for (k, (&i, o)) in self.independent.iter().zip(out.iter_mut()).enumerate() {
            *o = full[i] - (0..m).fold(D::zero(), |s, r| s + phi_i[r][k] * w[r]);
        }
    }
}

impl<L: Lagrangian, C: Holonomic> Lagrangian for Reduced<L, C> {
    fn dof(&self) -> usize {
        self.independent.len()
    }

    fn lagrangian<D: Scalar>(&self, t: D, qi: &[D], vi: &[D]) -> D {
        let (q, v, _) = self.lift(t, qi, vi);
        self.model.lagrangian(t, &q, &v)
    }

    fn has_generalized_force(&self) -> bool {
        self.model.has_generalized_force()
    }

    fn generalized_force<D: Scalar>(&self, t: D, qi: &[D], vi: &[D], out: &mut [D]) {
        let (q, v, jacobians) = self.lift(t, qi, vi);
        let mut full = vec![D::zero(); q.len()];
        self.model.generalized_force(t, &q, &v, &mut full);
        self.project(&jacobians, &full, out);
    }
}

impl<A: Actuated, C: Holonomic> Actuated for Reduced<A, C> {
    fn inputs(&self) -> usize {
        self.model.inputs()
    }

    fn input_force<D: Scalar>(&self, t: D, qi: &[D], vi: &[D], u: &[D], out: &mut [D]) {
        let (q, v, jacobians) = self.lift(t, qi, vi);
        let mut full = vec![D::zero(); q.len()];
        self.model.input_force(t, &q, &v, u, &mut full);
        self.project(&jacobians, &full, out);
    }
}

/// Overwrites `b` with A⁻¹ b for a small square A (rows), by Gaussian elimination with partial
/// pivoting on the real parts; `None` when a pivot's real part is not finite or singular by core's
/// test ([`SINGULAR_PIVOT`](noether_core::linalg::SINGULAR_PIVOT) of the largest entry).
fn solve_in_place<D: Scalar>(mut a: Vec<Vec<D>>, b: &mut [D]) -> Option<()> {
    let m = b.len();
    let norm = a.iter().flatten().fold(0.0_f64, |s, x| s.max(x.re().abs()));
    for k in 0..m {
        let p = (k..m).max_by(|&i, &j| a[i][k].re().abs().total_cmp(&a[j][k].re().abs()))?;
        let pivot = a[p][k].re();
        if !pivot.is_finite() || pivot.abs() <= noether_core::linalg::SINGULAR_PIVOT * norm {
            return None;
        }
        a.swap(k, p);
        b.swap(k, p);
        let (top, rest) = a.split_at_mut(k + 1);
        let row_k = &top[k];
        for (offset, row) in rest.iter_mut().enumerate() {
            let l = row[k] / row_k[k];
            for (x, &y) in row[k..].iter_mut().zip(&row_k[k..]) {
                *x -= l * y;
            }
            let bk = b[k];
            b[k + 1 + offset] -= l * bk;
        }
    }
    for k in (0..m).rev() {
        let s = (k + 1..m).fold(b[k], |s, j| s - a[k][j] * b[j]);
        b[k] = s / a[k][k];
    }
    Some(())
}
