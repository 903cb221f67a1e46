//! Linearisation of a constrained actuated system on its constraint manifold, in independent
//! coordinates: what SymPy's `Linearizer` does with its `q_ind` and `u_ind`, for holonomic and for
//! velocity (nonholonomic) constraints written in dependent coordinates.
//!
//! The constrained equations of motion (index 1, [`Constrained`]) are a vector field on all of
//! ℝ²ⁿ whose exact Jacobian J = ∂(q̇, q̈)/∂(q, q̇) noether forms by implicit differentiation of the
//! saddle-point system. The motions allowed by the constraints live on a submanifold 𝓜 that J
//! leaves invariant, and the linearisation that means something is J restricted to the tangent
//! space of 𝓜 at the point, in coordinates of that space. The user names n − m independent
//! coordinates i (the others, d, are dependent: the constraints' block A_d = ∂g/∂q̇_d must be
//! regular there):
//!
//! ```text
//! velocity constraints g = A(t, q) q̇ + a = 0:   state x = (q, q̇_i)   (2n − m entries),
//!     δq̇_d = −A_d⁻¹ (A_i δq̇_i + g_q δq);
//! holonomic constraints φ(t, q) = 0:             state x = (q_i, q̇_i) (2(n − m) entries),
//!     δq_d = −Φ_d⁻¹ Φ_i δq_i,   δq̇_d = −Φ_d⁻¹ (Φ_i δq̇_i + (Φ_q q̇ + φ_t)_q δq).
//! ```
//!
//! The columns T of the tangent space these give (unit steps of each entry of x, the dependent
//! entries filled in) make A = S J T, where S picks the entries of x from a vector of ℝ²ⁿ (J T lies
//! in the tangent space, so its x entries say all of it); B = S ∂(q̇, q̈)/∂u with
//! K [∂q̈/∂u; −∂λ/∂u] = [∂Q_u/∂u; 0], and the drift is S (q̇, q̈). Every piece is exact (dual numbers
//! and one factorization of K), so (A, B) are exact to rounding. For holonomic constraints
//! [`Reduced`](crate::Reduced) gives the same (A, B) by a reduced Lagrangian; this path needs no
//! reference configuration and treats both kinds alike.
//!
//! Steady motions of nonholonomic systems are points with q̇ ≠ 0 and a drift whose q̇_i-part
//! vanishes; their cyclic coordinates show as zero eigenvalues of A. A coin rolling on a table in
//! q = (x, y, ψ, θ, φ), linearised about its steady turns with (ψ̇, θ̇, φ̇) independent, has the tilt
//! frequency of Routh's reduced equations to rounding (`crates/analysis/tests/constrained.rs`).

use crate::dynamics::Constrained;
use crate::reduced::dependent_coordinates;
use crate::set::ConstraintSet;
use crate::Result;
use nalgebra::{DMatrix, DVector};
use noether_core::control::{input_jacobian, Actuated, ClosedLoop, Constant, Linearization};
use noether_core::error::{check_finite, check_len, check_phase_point};
use noether_core::linalg::DenseFactor;
use noether_core::{Dynamics, Error as CoreError};

/// (A, B) and the drift of `model` under `constraints` at (t, q, q̇, u), restricted to the constraint
/// manifold in the state x = (q, q̇_i) for velocity constraints or x = (q_i, q̇_i) for holonomic
/// ones, i = `independent` (module docs). The point must satisfy the constraints (to the
/// [`Constrained`] default tolerance, 1e-8). Errors: dimensions, non-finite input, bad indices, a
/// point off the constraints ([`Error::ConstraintViolated`](crate::Error::ConstraintViolated)), a
/// singular dependent block ([`noether_core::Error::SingularMatrix`]; choose other independent
/// coordinates), and those of the constrained equations of motion there.
pub fn linearize<A: Actuated, K: ConstraintSet>(
    model: &A,
    constraints: &K,
    t: f64,
    q: &[f64],
    v: &[f64],
    u: &[f64],
    independent: &[usize],
) -> Result<Linearization> {
    let (n, m) = (model.dof(), constraints.count());
    check_phase_point(n, t, q, v, "q̇")?;
    check_len("inputs u", u, model.inputs())?;
    check_finite("inputs u", u)?;
    let dependent = dependent_coordinates(n, m, independent)?;
    let held = Constrained::new(ClosedLoop::new(model, Constant(u.to_vec()))?, constraints)?;
    held.admissible(t, q, v)?;
    let (factor, z, a) = held.saddle(t, q, v)?;
    let mut jac = DMatrix::zeros(2 * n, 2 * n);
    held.jacobian_from(t, q, v, (&factor, &z), &mut jac)?;
    let mut rhs = DMatrix::zeros(n + m, u.len());
    rhs.rows_mut(0, n).copy_from(&input_jacobian(model, t, q, v, u));
    let response = factor.solve_matrix(&rhs);
    let holonomic = constraints.positions(t, q, &mut vec![0.0; m]);
    let split = Split {
        independent,
        dependent: &dependent,
        n,
    };
    let rows = split.state_rows(holonomic);
    let basis = split.tangent_basis(constraints, (t, q, v), &a, holonomic)?;
    let moved = &jac * &basis;
    let pick = |r: usize| if r < n { v[r] } else { z[r - n] };
    Ok(Linearization {
        a: DMatrix::from_fn(rows.len(), rows.len(), |r, c| moved[(rows[r], c)]),
        b: DMatrix::from_fn(rows.len(), u.len(), |r, c| {
            if rows[r] < n {
                0.0
            } else {
                response[(rows[r] - n, c)]
            }
        }),
        drift: DVector::from_iterator(rows.len(), rows.iter().map(|&r| pick(r))),
    })
}

/// The independent and dependent coordinates of n.
struct Split<'a> {
    independent: &'a [usize],
    dependent: &'a [usize],
    n: usize,
}

impl Split<'_> {
    /// The entries of (q, q̇) ∈ ℝ²ⁿ that make the state x, in order.
    fn state_rows(&self, holonomic: bool) -> Vec<usize> {
        let velocities = self.independent.iter().map(|i| self.n + i);
        if holonomic {
            self.independent.iter().copied().chain(velocities).collect()
        } else {
            (0..self.n).chain(velocities).collect()
        }
    }

    /// The columns of [`state_rows`](Self::state_rows) made tangent to the constraint manifold: each
    /// a unit step of one entry of x with the dependent entries solved for (module docs).
    fn tangent_basis<K: ConstraintSet>(
        &self,
        constraints: &K,
        (t, q, v): (f64, &[f64], &[f64]),
        a: &DMatrix<f64>,
        holonomic: bool,
    ) -> Result<DMatrix<f64>> {
        let n = self.n;
        let block = |cols: &[usize]| a.select_columns(cols);
        let dependent = DenseFactor::lu(block(self.dependent)).map_err(|e| {
            e.in_matrix("the constraints' block of the dependent coordinates (choose other independent ones)")
        })?;
        let independent = block(self.independent);
        let rows = self.state_rows(holonomic);
        let mut basis = DMatrix::zeros(2 * n, rows.len());
        for (c, &r) in rows.iter().enumerate() {
            let (mut dq, mut dv) = (vec![0.0; n], vec![0.0; n]);
            if r < n {
                dq[r] = 1.0;
            } else {
                dv[r - n] = 1.0;
            }
            if holonomic && r < n {
                self.fill_dependent(&dependent, &independent, &mut dq, &[0.0; 0]);
            }
            // g_q δq, for a step of the coordinates (a step of the velocities alone leaves it 0).
            let bend = if r < n {
                constraints
                    .derivatives_along(t, q, v, (&dq, &vec![0.0; n]))
                    .residual
            } else {
                Vec::new()
            };
            self.fill_dependent(&dependent, &independent, &mut dv, &bend);
            basis.view_mut((0, c), (n, 1)).copy_from_slice(&dq);
            basis.view_mut((n, c), (n, 1)).copy_from_slice(&dv);
        }
        if basis.iter().any(|x| !x.is_finite()) {
            return Err(CoreError::NonFiniteResult {
                what: "tangent space of the constraint manifold",
                t,
                component: None,
            }
            .into());
        }
        Ok(basis)
    }

    /// x_d = −A_d⁻¹ (A_i x_i + extra) for a vector x of n entries (its independent ones set; `extra`
    /// empty means zero).
    fn fill_dependent(&self, a_d: &DenseFactor, a_i: &DMatrix<f64>, x: &mut [f64], extra: &[f64]) {
        let xi = DVector::from_iterator(self.independent.len(), self.independent.iter().map(|&i| x[i]));
        let mut rhs = a_i * xi;
        for (r, e) in rhs.iter_mut().zip(extra) {
            *r += e;
        }
        rhs.neg_mut();
        a_d.solve_in_place(rhs.as_mut_slice());
        for (&d, value) in self.dependent.iter().zip(rhs.iter()) {
            x[d] = *value;
        }
    }
}
