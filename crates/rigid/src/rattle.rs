//! RATTLE on the orthogonality constraints: the rigid body with the nine entries of R as coordinates,
//! held on the rotation group by the six constraints RᵀR = I, stepped by noether-constraints'
//! [`Rattle`] on the trapezoidal discrete Lagrangian of noether-discrete.
//!
//! With R ∈ ℝ³ˣ³ free, the kinetic energy of a body with inertia tensor J is
//!
//! ```text
//! T = ½ tr(Ṙ J_d Ṙᵀ),   J_d = ½ tr(J) I − J,
//! ```
//!
//! (for Ṙ = R Ω̂ this is ½ Ω·JΩ), so L = T − V(R) has a constant mass matrix J_d ⊗ I₃ and the
//! trapezoidal rule with the constraints is RATTLE (Hairer-Lubich-Wanner VII.5, McLachlan & Scovel).
//! The momentum conjugate to R is P = Ṙ J_d; the body angular momentum is Π = vee(RᵀP − PᵀR) (since
//! Ω̂J_d + J_dΩ̂ = (JΩ)^). Positions and momenta stay on the constraint manifold to the Newton tolerance,
//! the map is symplectic there, and the spatial angular momentum R Π (the discrete Noether momentum of
//! rotations) is kept by a free body. [`Lgvi`](crate::Lgvi) keeps the orientation on SO(3) by
//! construction instead and solves 3 unknowns per step instead of 15.
//!
//! ```
//! use nalgebra::{UnitQuaternion, Vector3};
//! use noether_core::Stepper;
//! use noether_rigid::rattle::{body_momentum, matrix_state, rattle};
//! use noether_rigid::RigidBody;
//!
//! let body = RigidBody::free(1.0, 2.0, 2.5)?;
//! let mut stepper = rattle(body)?;
//! let mut s = matrix_state(&stepper, 0.0, &UnitQuaternion::identity(), &Vector3::new(1.0, 0.0, 0.8))?;
//! let pi0 = body_momentum(&s)?;
//! for _ in 0..100 {
//!     stepper.step(&mut s, 1e-2)?;
//! }
//! // |Π| is a Casimir of the free body: kept to the Newton tolerance.
//! assert!((body_momentum(&s)?.norm() - pi0.norm()).abs() < 1e-12);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::body::{OrientationPotential, RigidBody, INERTIA_PIVOT};
use crate::rotation::{hat, vee};
use crate::{Error, Result};
use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use noether_constraints::{Holonomic, Rattle};
use noether_core::{Lagrangian, Momenta, Scalar, State};
use noether_discrete::Trapezoidal;

/// The body with the entries of R (row-major) as its nine coordinates:
/// L = ½ tr(Ṙ J_d Ṙᵀ) − V(R) (see the [module](self) docs).
#[derive(Debug, Clone, Copy)]
pub struct MatrixBody<V> {
    body: RigidBody<V>,
    jd: Matrix3<f64>,
}

impl<V: OrientationPotential> MatrixBody<V> {
    /// The body in matrix coordinates.
    pub fn new(body: RigidBody<V>) -> Self {
        let j = *body.inertia.matrix();
        MatrixBody {
            body,
            jd: Matrix3::identity() * (0.5 * j.trace()) - j,
        }
    }
}

impl<V: OrientationPotential> Lagrangian for MatrixBody<V> {
    fn dof(&self) -> usize {
        9
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        // Σ_ab (J_d)_ab (column a of Ṙ)·(column b of Ṙ), row-major entries Ṙ_ia = v[3i + a].
        let mut t = D::zero();
        for a in 0..3 {
            for b in 0..3 {
                let dot = v[a] * v[b] + v[3 + a] * v[3 + b] + v[6 + a] * v[6 + b];
                t += dot * (0.5 * self.jd[(a, b)]);
            }
        }
        t - self.body.potential.potential(&Matrix3::from_row_slice(q))
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}

/// RᵀR = I as six constraints on the row-major entries of R: c_a·c_b − δ_ab for a ≤ b (c_a the columns).
#[derive(Debug, Clone, Copy, Default)]
pub struct Orthogonality;

impl Holonomic for Orthogonality {
    fn dof(&self) -> usize {
        9
    }
    fn count(&self) -> usize {
        6
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        let pairs = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
        for (k, (a, b)) in pairs.into_iter().enumerate() {
            let dot = q[a] * q[b] + q[3 + a] * q[3 + b] + q[6 + a] * q[6 + b];
            out[k] = if a == b { dot - 1.0 } else { dot };
        }
    }
}

/// RATTLE for a rigid body in matrix coordinates.
pub type RigidRattle<V> = Rattle<Trapezoidal<MatrixBody<V>>, Orthogonality>;

/// RATTLE on the orthogonality constraints for `body` (see the [module](self) docs).
/// [`Error::FlatBody`] when J_d = ½ tr(J) I − J is not positive definite (to the pivot
/// [`INERTIA_PIVOT`] of the inertia check): the mass matrix of the matrix coordinates is then singular.
/// The potential is checked as in [`Lgvi::new`](crate::Lgvi::new).
pub fn rattle<V: OrientationPotential>(body: RigidBody<V>) -> Result<RigidRattle<V>> {
    body.potential.check()?;
    let m = MatrixBody::new(body);
    let eig = m.jd.symmetric_eigenvalues();
    let (smallest, largest) = (eig.min(), eig.max());
    if smallest.is_nan() || smallest <= INERTIA_PIVOT * largest {
        return Err(Error::FlatBody { smallest, largest });
    }
    Rattle::new(Trapezoidal::new(m), Orthogonality).map_err(|e| noether_core::Error::from(e).into())
}

/// The state at time `t` of orientation `q` (body → space) and body angular velocity `omega`, in the
/// matrix coordinates of [`rattle`]: R, and P = Ṙ J_d with Ṙ = R Ω̂.
pub fn matrix_state<V: OrientationPotential>(
    stepper: &RigidRattle<V>,
    t: f64,
    q: &UnitQuaternion<f64>,
    omega: &Vector3<f64>,
) -> Result<State<Momenta>> {
    let r = *q.to_rotation_matrix().matrix();
    let rdot = r * hat(omega);
    let (rq, rv) = (row_major(&r), row_major(&rdot));
    stepper
        .state_from_velocities(t, &rq, &rv)
        .map_err(|e| noether_core::Error::from(e).into())
}

/// The body angular momentum Π = vee(RᵀP − PᵀR) of a state in matrix coordinates: nine finite
/// entries of R and of P (else `Dimension` / `NonFinite`), and Π finite (else `NonFiniteResult`
/// at the state's t: entries near 1e308 overflow).
pub fn body_momentum(state: &State<Momenta>) -> Result<Vector3<f64>> {
    state.validate(9)?;
    let r = Matrix3::from_row_slice(state.q.as_slice());
    let p = Matrix3::from_row_slice(state.v.as_slice());
    let pi = vee(&(r.transpose() * p - p.transpose() * r));
    noether_core::error::check_result("body angular momentum Π", state.t, pi.as_slice())?;
    Ok(pi)
}

/// The rotation matrix R of a state in matrix coordinates, as stored (not re-orthogonalised): the
/// state checked as in [`body_momentum`].
pub fn rotation(state: &State<Momenta>) -> Result<Matrix3<f64>> {
    state.validate(9)?;
    Ok(Matrix3::from_row_slice(state.q.as_slice()))
}

fn row_major(m: &Matrix3<f64>) -> [f64; 9] {
    std::array::from_fn(|k| m[(k / 3, k % 3)])
}
