//! Cyclic coordinates and Routh's reduction: [`Routh`].
//!
//! A coordinate q_c that L does not contain (∂L/∂q_c = 0) is cyclic, and its momentum
//! p_c = ∂L/∂q̇_c is a constant β_c of the motion. Routh's procedure eliminates it: with the
//! remaining coordinates r, the Routhian
//!
//! ```text
//! R(t, r, ṙ; β) = Σ_c β_c q̇_c − L(t, r, q_c, ṙ, q̇_c),   q̇_c = q̇_c(t, r, ṙ; β) solving ∂L/∂q̇_c = β_c,
//! ```
//!
//! gives the motion of r by Lagrange's equations of L_R = −R. [`Routh`] *is* that L_R, a
//! [`Lagrangian`] in the remaining coordinates, so every integrator, the Legendre transform and every
//! other tool accepts it; the cyclic coordinates come back by quadrature,
//! q_c(t) = q_c(t₀) + ∫ q̇_c dt along the reduced solution ([`Routh::reconstruct`]).
//! [`Routh::check_cyclic`] checks a declaration of cyclic coordinates by dual numbers at sample
//! points (|∂L/∂q_c| ≤ a tolerance).
//!
//! **Solving for q̇_c inside generic code** is done as [`LegendreTransform`](noether_core::LegendreTransform)
//! does for q̇(p): the real velocities u₀ = q̇_c by core's [`Newton`] on
//! ∂L/∂q̇_c − β = 0 (from u = 0 at every call, so that L_R is a function of its arguments alone, to the
//! last bit, whatever was evaluated before and on whichever thread: a `Routh` shared by the members of
//! an ensemble gives the same bits as one per member), with the mass block M_cc = ∂²L/∂q̇_c² by
//! dual numbers; then, in the caller's scalar D, k = ⌊D::NDERIV/2⌋ chord steps
//! u ← u − M_cc(u₀)⁻¹ (∂L/∂q̇_c(u) − β), ∂L/∂q̇_c in D by nested duals `Dual<D, f64>` (a `Dual<D, f64>`
//! is itself a `DualNum<f64> + Copy`, so core's [`Scalar`] covers it). Each step makes u exact to one
//! more derivative order, and L_R is stationary in u (∂(L − β·u)/∂u = 0 at the solution), so its error
//! is quadratic in u's: values and gradients need no step, Hessians (what the integrators ask of a
//! Lagrangian at most) one. Exact to rounding, no finite difference.
//!
//! **Generalized forces** of the full model carry over when they do not act on the cyclic coordinates
//! (Q_c = 0, or p_c would change; [`Routh::check_cyclic`] checks): the reduced model's force is
//! Q_r(t, r, 0, ṙ, q̇_c), with q̇_c exact to all of D's derivatives (D::NDERIV chord steps, since Q,
//! unlike L_R, is not stationary in q̇_c).
//!
//! **Limitation.** M_cc must be regular (L strictly convex in the cyclic velocities near the solve):
//! otherwise Newton fails and L_R is NaN (an integrator then reports a non-finite result). The values
//! of the cyclic coordinates are irrelevant to L (that is what cyclic means) and are set to 0 when L is
//! evaluated; a wrong declaration is caught only by [`Routh::check_cyclic`].
//!
//! ```
//! use noether_canonical::Routh;
//! use noether_core::prelude::*;
//!
//! /// Kepler per unit mass in polar coordinates (r, φ): φ is cyclic, p_φ = r² φ̇ = ℓ.
//! struct Kepler;
//! impl Lagrangian for Kepler {
//!     fn dof(&self) -> usize { 2 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         (v[0] * v[0] + q[0] * q[0] * v[1] * v[1]) * 0.5 + q[0].recip()
//!     }
//! }
//! let routh = Routh::new(Kepler, &[1], &[0.9])?;
//! // L_R = ṙ²/2 − ℓ²/(2r²) + 1/r.
//! let (r, dr) = (1.3, 0.2);
//! let lr = routh.lagrangian(0.0, &[r], &[dr]);
//! assert!((lr - (dr * dr / 2.0 - 0.81 / (2.0 * r * r) + 1.0 / r)).abs() < 1e-15);
//! # Ok::<(), noether_canonical::Error>(())
//! ```

use crate::action_angle::gauss_legendre;
use crate::{Error, Result};
use nalgebra::DMatrix;
use noether_core::linalg::DenseFactor;
use noether_core::newton::{solve_dense, DenseProblem, Newton};
use noether_core::{EulerLagrange, Lagrangian, Partner, Scalar, Solution};
use num_dual::Dual;

/// The reduced Lagrangian L_R = −R of a Lagrangian with cyclic coordinates at given conserved momenta
/// (see the module docs).
pub struct Routh<L> {
    equations: EulerLagrange<L>,
    cyclic: Vec<usize>,
    rest: Vec<usize>,
    momenta: Vec<f64>,
}

impl<L: Lagrangian + std::fmt::Debug> std::fmt::Debug for Routh<L> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Routh")
            .field("lagrangian", self.equations.lagrangian())
            .field("cyclic", &self.cyclic)
            .field("momenta", &self.momenta)
            .finish_non_exhaustive()
    }
}

impl<L: Lagrangian> Routh<L> {
    /// The reduction of `lagrangian` by the cyclic coordinates `cyclic` (distinct indices below its
    /// dof, at least one coordinate left) at the conserved momenta `momenta` (finite, one each).
    pub fn new(lagrangian: L, cyclic: &[usize], momenta: &[f64]) -> Result<Self> {
        let n = lagrangian.dof();
        noether_core::error::check_len("cyclic momenta", momenta, cyclic.len())?;
        if let Some(i) = momenta.iter().position(|x| !x.is_finite()) {
            return Err(noether_core::Error::NonFinite {
                what: "cyclic momenta",
                index: i,
            }
            .into());
        }
        for (k, &c) in cyclic.iter().enumerate() {
            if c >= n || cyclic[..k].contains(&c) {
                return Err(noether_core::Error::InvalidParameter {
                    name: "cyclic coordinate index",
                    value: c as f64,
                    reason: "indices must be distinct and below the Lagrangian's dof",
                }
                .into());
            }
        }
        if cyclic.len() >= n {
            return Err(noether_core::Error::InvalidParameter {
                name: "number of cyclic coordinates",
                value: cyclic.len() as f64,
                reason: "at least one coordinate must remain",
            }
            .into());
        }
        let rest = (0..n).filter(|i| !cyclic.contains(i)).collect();
        Ok(Routh {
            equations: EulerLagrange::new(lagrangian),
            cyclic: cyclic.to_vec(),
            rest,
            momenta: momenta.to_vec(),
        })
    }

    /// The full Lagrangian.
    pub fn full(&self) -> &L {
        self.equations.lagrangian()
    }

    /// The cyclic coordinates' indices in the full model.
    pub fn cyclic(&self) -> &[usize] {
        &self.cyclic
    }

    /// The remaining coordinates' indices in the full model (the reduced model's coordinates, in order).
    pub fn remaining(&self) -> &[usize] {
        &self.rest
    }

    /// The conserved momenta β of the cyclic coordinates.
    pub fn momenta(&self) -> &[f64] {
        &self.momenta
    }

    /// Checks the declaration at sample points (t, q, q̇) of the full model: the largest |∂L/∂q_c| and
    /// |Q_c| (a generalized force on a cyclic coordinate would change its momentum too) over the points
    /// and the cyclic coordinates, or [`Error::NotCyclic`] at the first that exceeds `tol`.
    pub fn check_cyclic(&self, points: &[(f64, Vec<f64>, Vec<f64>)], tol: f64) -> Result<f64> {
        let n = self.full().dof();
        let (mut g, mut force) = (vec![0.0; n], vec![0.0; n]);
        let mut worst: f64 = 0.0;
        for (t, q, v) in points {
            self.equations.gradient_q(*t, q, v, &mut g)?;
            if self.full().has_generalized_force() {
                self.full().generalized_force(*t, q, v, &mut force);
            }
            for &c in &self.cyclic {
                for (what, value) in [("∂L/∂q", g[c]), ("Q", force[c])] {
                    if value.abs() > tol || value.is_nan() {
                        return Err(Error::NotCyclic {
                            index: c,
                            t: *t,
                            what,
                            value,
                        });
                    }
                    worst = worst.max(value.abs());
                }
            }
        }
        Ok(worst)
    }

    /// The full (q, q̇) at reduced (r, ṙ), with the cyclic coordinates at `q_cyclic` and their
    /// velocities solved from β.
    pub fn full_state(
        &self,
        t: f64,
        r: &[f64],
        dr: &[f64],
        q_cyclic: &[f64],
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        noether_core::error::check_len("cyclic coordinates", q_cyclic, self.cyclic.len())?;
        let u = self.cyclic_velocities(t, r, dr)?;
        let (mut q, v) = self.assemble(r, dr, &u);
        for (k, &c) in self.cyclic.iter().enumerate() {
            q[c] = q_cyclic[k];
        }
        Ok((q, v))
    }

    /// The cyclic velocities q̇_c(t, r, ṙ) solving ∂L/∂q̇_c = β, to rounding.
    pub fn cyclic_velocities(&self, t: f64, r: &[f64], dr: &[f64]) -> Result<Vec<f64>> {
        Ok(self.solve(t, r, dr)?.0)
    }

    /// (q, q̇) of the full model from r, ṙ and the cyclic velocities u (cyclic coordinates at 0).
    fn assemble<T: Copy + From<f64>>(&self, r: &[T], dr: &[T], u: &[T]) -> (Vec<T>, Vec<T>) {
        let n = self.full().dof();
        let mut q = vec![T::from(0.0); n];
        let mut v = vec![T::from(0.0); n];
        for (k, &i) in self.rest.iter().enumerate() {
            q[i] = r[k];
            v[i] = dr[k];
        }
        for (k, &c) in self.cyclic.iter().enumerate() {
            v[c] = u[k];
        }
        (q, v)
    }

    /// The real solve: u = q̇_c and M_cc(u)⁻¹, Newton from u = 0 (the same start at every call: the
    /// result depends on (t, r, ṙ) alone).
    fn solve(&self, t: f64, r: &[f64], dr: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
        let m = self.cyclic.len();
        noether_core::error::check_len("reduced coordinates", r, self.rest.len())?;
        noether_core::error::check_len("reduced velocities", dr, self.rest.len())?;
        let start = vec![0.0; m];
        let problem = CyclicMomenta {
            routh: self,
            t,
            r,
            dr,
        };
        let (u, _) = solve_dense(&Newton::default(), problem, &start)?;
        let u: Vec<f64> = u.data.into();
        let (q, v) = self.assemble(r, dr, &u);
        let mass = self.equations.mass_matrix(t, &q, &v)?;
        let block = DMatrix::from_fn(m, m, |i, j| mass[(self.cyclic[i], self.cyclic[j])]);
        // Symmetric: Cholesky (LU when indefinite) with linalg's pivot test.
        let factor = DenseFactor::symmetric(block).map_err(|e| e.in_matrix("cyclic mass block ∂²L/∂q̇_c²"))?;
        Ok((u, factor.solve_matrix(&DMatrix::identity(m, m))))
    }

    /// The cyclic coordinates at the sorted `times` along a reduced solution, from `q_cyclic0` at the
    /// solution's first time, by quadrature of q̇_c(t, r, ṙ): 8-point Gauss-Legendre on every piece
    /// between consecutive saved times of `sol` and requested times, on the run's continuous extension
    /// (the run must keep it: [`Driver::keep_dense_output`](noether_core::Driver::keep_dense_output);
    /// save the steps, the default, so that each piece is at most one step).
    pub fn reconstruct<K: Partner>(
        &self,
        sol: &Solution<K>,
        q_cyclic0: &[f64],
        times: &[f64],
    ) -> Result<Vec<Vec<f64>>> {
        noether_core::error::check_len("initial cyclic coordinates", q_cyclic0, self.cyclic.len())?;
        let saved = sol.times();
        let (Some(&t0), Some(&t1)) = (saved.first(), saved.last()) else {
            return Ok(Vec::new());
        };
        if let Some(&bad) = times.iter().find(|&&t| !(t >= t0 && t <= t1)) {
            return Err(noether_core::Error::InvalidParameter {
                name: "reconstruction time",
                value: bad,
                reason: "outside the time span of the reduced solution",
            }
            .into());
        }
        if times.windows(2).any(|w| w[1] < w[0]) {
            return Err(noether_core::Error::InvalidParameter {
                name: "reconstruction times",
                value: f64::NAN,
                reason: "must be sorted",
            }
            .into());
        }
        let rule = gauss_legendre(8);
        let mut rows = Vec::with_capacity(times.len());
        let mut qc = q_cyclic0.to_vec();
        let (mut at, mut next_saved) = (t0, 1);
        for &target in times {
            while at < target {
                while next_saved < saved.len() && saved[next_saved] <= at {
                    next_saved += 1;
                }
                let b = saved.get(next_saved).map_or(target, |&s| s.min(target));
                for &(s, wt) in &rule {
                    let t = at + s * (b - at);
                    let state = sol.at(t)?;
                    let u = self.cyclic_velocities(t, state.q.as_slice(), state.v.as_slice())?;
                    qc.iter_mut().zip(&u).for_each(|(x, ui)| *x += wt * (b - at) * ui);
                }
                at = b;
            }
            rows.push(qc.clone());
        }
        Ok(rows)
    }
}

/// ∂L/∂q̇_c − β as a function of u = q̇_c, with the block M_cc as Jacobian.
struct CyclicMomenta<'a, L> {
    routh: &'a Routh<L>,
    t: f64,
    r: &'a [f64],
    dr: &'a [f64],
}

impl<L: Lagrangian> DenseProblem for CyclicMomenta<'_, L> {
    fn dim(&self) -> usize {
        self.routh.cyclic.len()
    }
    fn residual(&mut self, x: &[f64], out: &mut [f64]) -> noether_core::Result<()> {
        let (q, v) = self.routh.assemble(self.r, self.dr, x);
        let mut p = vec![0.0; q.len()];
        self.routh.equations.momenta(self.t, &q, &v, &mut p)?;
        for (k, &c) in self.routh.cyclic.iter().enumerate() {
            out[k] = p[c] - self.routh.momenta[k];
        }
        Ok(())
    }
    fn jacobian(&mut self, x: &[f64], j: &mut DMatrix<f64>) -> noether_core::Result<()> {
        let (q, v) = self.routh.assemble(self.r, self.dr, x);
        let mass = self.routh.equations.mass_matrix(self.t, &q, &v)?;
        let c = &self.routh.cyclic;
        for a in 0..c.len() {
            for b in 0..c.len() {
                j[(a, b)] = mass[(c[a], c[b])];
            }
        }
        Ok(())
    }
}

impl<L: Lagrangian> Lagrangian for Routh<L> {
    fn dof(&self) -> usize {
        self.rest.len()
    }

    /// L_R = L(t, r, 0, ṙ, u) − β·u with u = q̇_c from the real solve and ⌊D::NDERIV/2⌋ chord steps in
    /// D (module docs); NaN where the solve fails.
    fn lagrangian<D: Scalar>(&self, t: D, r: &[D], dr: &[D]) -> D {
        let Some(u) = self.cyclic_velocities_in(t, r, dr, D::NDERIV / 2) else {
            return r.iter().chain(dr).fold(t, |s, x| s + *x) * f64::NAN;
        };
        let (q, v) = self.assemble(r, dr, &u);
        let bu = u
            .iter()
            .zip(&self.momenta)
            .fold(D::zero(), |s, (x, b)| s + *x * *b);
        self.full().lagrangian(t, &q, &v) - bu
    }

    fn has_generalized_force(&self) -> bool {
        self.full().has_generalized_force()
    }

    /// The full model's force on the remaining coordinates, Q_r(t, r, 0, ṙ, u), with u = q̇_c exact to
    /// all of D's derivatives (D::NDERIV chord steps: Q, unlike L_R, is not stationary in u). The
    /// forces on the cyclic coordinates must vanish, or their momenta would change
    /// ([`check_cyclic`](Routh::check_cyclic) checks); NaN where the solve fails.
    fn generalized_force<D: Scalar>(&self, t: D, r: &[D], dr: &[D], out: &mut [D]) {
        let Some(u) = self.cyclic_velocities_in(t, r, dr, D::NDERIV) else {
            out.iter_mut().for_each(|o| *o = t * f64::NAN);
            return;
        };
        let (q, v) = self.assemble(r, dr, &u);
        let mut full = vec![D::zero(); q.len()];
        self.full().generalized_force(t, &q, &v, &mut full);
        for (o, &i) in out.iter_mut().zip(&self.rest) {
            *o = full[i];
        }
    }
}

impl<L: Lagrangian> Routh<L> {
    /// u = q̇_c(t, r, ṙ) in the caller's scalar: the real solve, then `steps` chord steps in D, each
    /// making u exact to one more derivative order (module docs); `None` where the solve fails.
    fn cyclic_velocities_in<D: Scalar>(&self, t: D, r: &[D], dr: &[D], steps: usize) -> Option<Vec<D>> {
        let re = |x: &[D]| x.iter().map(|y| y.re()).collect::<Vec<f64>>();
        let (u0, minv) = self.solve(t.re(), &re(r), &re(dr)).ok()?;
        let m = self.cyclic.len();
        let mut u: Vec<D> = u0.iter().map(|&x| D::from(x)).collect();
        for _ in 0..steps {
            // ∂L/∂q̇_c in D by nested duals, one cyclic velocity at a time.
            let lift = |x: &[D]| x.iter().map(|&y| Dual::from_re(y)).collect::<Vec<Dual<D, f64>>>();
            let mut res = vec![D::zero(); m];
            for (k, rk) in res.iter_mut().enumerate() {
                let mut ud = lift(&u);
                ud[k] = ud[k].derivative();
                let (q, v) = self.assemble(&lift(r), &lift(dr), &ud);
                *rk = self.full().lagrangian(Dual::from_re(t), &q, &v).eps - self.momenta[k];
            }
            for (i, x) in u.iter_mut().enumerate() {
                *x -= (0..m).fold(D::zero(), |s, j| s + res[j] * minv[(i, j)]);
            }
        }
        Some(u)
    }
}
