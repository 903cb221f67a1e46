//! The model: a rigid body turning about a fixed point (or its centre of mass), given by its inertia
//! tensor and a potential V(R) that depends on its orientation, written once as generic code.
//!
//! The state of a body is a [`State<Momenta>`] with four coordinates: q = (w, x, y, z), the unit
//! quaternion of the rotation R (body → space), and as its partner the body angular momentum
//! Π = J Ω written as the pure quaternion (0, Π₁, Π₂, Π₃). That partner is ½ q* ⊗ p of the momentum p
//! conjugate to q in ℝ⁴ ([`rotation::quaternion_momentum`] converts); its scalar part would be the
//! gauge ½ q·p of the unit-norm constraint, which carries no motion: it is ignored on input and
//! written 0. Π is stored, not p, so that a step adds no rounding to |Π| beyond the rotation
//! F_kᵀ Π_k itself (through p, the two conversions per step made a free body's |Π| drift 2e-12 in 10⁵
//! steps, measured, against 1e-14). Build a state with [`RigidBody::state`] from the body angular
//! velocity, read it with [`RigidBody::orientation`] and [`RigidBody::body_momentum`].
//!
//! Equations of motion (Euler's equations with a torque, the text's ch. 64): Ṙ = R Ω̂,
//! Π̇ = Π × Ω + M with Ω = J⁻¹ Π and the body-frame torque M = vee(Aᵀ − A), A = Rᵀ ∂V/∂R
//! (δV = −M·η for the variation δR = R η̂; Lee, Leok & McClamroch 2005). ∂V/∂R is taken by dual
//! numbers from the user's V.

use crate::rotation::{self, vee};
use crate::{Error, Result};
use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use noether_core::ad::{gradient, Block, Field};
use noether_core::error::{check_finite, check_result};
use noether_core::{Momenta, Scalar, State};

/// A potential energy that depends on the orientation R of the body (body → space), written once as
/// generic code so that its derivative ∂V/∂R is exact.
///
/// ```
/// use nalgebra::Matrix3;
/// use noether_core::Scalar;
/// use noether_rigid::OrientationPotential;
///
/// /// A satellite's gravity-gradient potential, V = 3μ/(2r³) e_rᵀ R J Rᵀ e_r (the part that turns it).
/// struct GravityGradient { k: f64, j: [f64; 3] }
/// impl OrientationPotential for GravityGradient {
///     fn potential<D: Scalar>(&self, r: &Matrix3<D>) -> D {
///         // e_r = the space x axis; (Rᵀe_r)_i = R_{0i}.
///         (0..3).map(|i| r[(0, i)] * r[(0, i)] * (self.k * self.j[i])).fold(D::zero(), |a, b| a + b)
///     }
/// }
/// ```
pub trait OrientationPotential {
    /// V(R).
    fn potential<D: Scalar>(&self, r: &Matrix3<D>) -> D;
    /// `true` for a body on which no torque acts (the torque is then not evaluated).
    fn is_free(&self) -> bool {
        false
    }
    /// Checks the potential's own parameters (finite masses, fields, positions): called by
    /// [`RigidBody::new`], [`Lgvi::new`](crate::Lgvi::new) and [`rattle`](crate::rattle::rattle), so
    /// that a NaN parameter is refused when the body is built, not reported later as a failed step.
    /// The default accepts everything.
    fn check(&self) -> noether_core::Result<()> {
        Ok(())
    }
}

/// No potential: the free (torque-free) body.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Free;

impl OrientationPotential for Free {
    fn potential<D: Scalar>(&self, _r: &Matrix3<D>) -> D {
        D::zero()
    }
    fn is_free(&self) -> bool {
        true
    }
}

/// Uniform gravity g along −z (space frame) on a body of mass `mass` whose centre of mass sits at
/// `center` (body frame) from the fixed point: V = m g e₃·(R ρ). The heavy top.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UniformGravity {
    /// Mass of the body.
    pub mass: f64,
    /// Gravitational acceleration.
    pub g: f64,
    /// Centre of mass ρ in the body frame, from the fixed point.
    pub center: Vector3<f64>,
}

impl UniformGravity {
    /// Gravity g on a body of mass `mass` with centre of mass `center` (body frame): all finite
    /// (else [`noether_core::Error::NonFinite`]) and m g finite (else
    /// [`noether_core::Error::InvalidParameter`]).
    pub fn new(mass: f64, g: f64, center: Vector3<f64>) -> Result<Self> {
        let gravity = UniformGravity { mass, g, center };
        gravity.check()?;
        Ok(gravity)
    }
}

impl OrientationPotential for UniformGravity {
    #[inline]
    fn potential<D: Scalar>(&self, r: &Matrix3<D>) -> D {
        let c = self.center;
        (r[(2, 0)] * c[0] + r[(2, 1)] * c[1] + r[(2, 2)] * c[2]) * (self.mass * self.g)
    }
    /// m, g and ρ finite, and the weight m g finite.
    fn check(&self) -> noether_core::Result<()> {
        check_finite("mass of the body", &[self.mass])?;
        check_finite("gravitational acceleration g", &[self.g])?;
        check_finite("centre of mass", self.center.as_slice())?;
        let weight = self.mass * self.g;
        if !weight.is_finite() {
            return Err(noether_core::Error::InvalidParameter {
                name: "weight m g",
                value: weight,
                reason: "the product of mass and g overflows",
            });
        }
        Ok(())
    }
}

/// Smallest principal moment accepted, relative to the largest: below it the tensor is singular for
/// the purpose of Ω = J⁻¹Π (a rod without thickness).
pub const INERTIA_PIVOT: f64 = 1e-12;

/// An inertia tensor J about the body's fixed point (or centre of mass): symmetric positive definite,
/// diagonalised once (principal moments and axes), inverted once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertia {
    tensor: Matrix3<f64>,
    inverse: Matrix3<f64>,
    moments: Vector3<f64>,
    axes: Matrix3<f64>,
}

impl Inertia {
    /// The tensor diag(I₁, I₂, I₃) in principal axes.
    pub fn principal(i1: f64, i2: f64, i3: f64) -> Result<Self> {
        Self::tensor(Matrix3::from_diagonal(&Vector3::new(i1, i2, i3)))
    }

    /// A full tensor: finite, symmetric (to 1e-12 of its scale, else [`Error::AsymmetricInertia`])
    /// and positive definite with its smallest principal moment above [`INERTIA_PIVOT`] times the
    /// largest (else [`Error::InertiaNotPositive`]), with principal moments that are normal numbers
    /// and an inverse J⁻¹ that is finite (else [`Error::InertiaOutOfRange`]: a subnormal moment such
    /// as 1e-310 has the reciprocal ∞, and Ω = J⁻¹Π would be NaN).
    pub fn tensor(j: Matrix3<f64>) -> Result<Self> {
        noether_core::error::check_finite("inertia tensor", j.as_slice())?;
        let scale = j.amax();
        let asymmetry = (j - j.transpose()).amax() / scale.max(f64::MIN_POSITIVE);
        if asymmetry > 1e-12 {
            return Err(Error::AsymmetricInertia { asymmetry });
        }
        let sym = (j + j.transpose()) * 0.5;
        let eig = sym.symmetric_eigen();
        let (smallest, largest) = (eig.eigenvalues.min(), eig.eigenvalues.max());
        if !(largest > 0.0 && smallest > INERTIA_PIVOT * largest) {
            return Err(Error::InertiaNotPositive { smallest, largest });
        }
        let inverse = eig.eigenvectors
            * Matrix3::from_diagonal(&eig.eigenvalues.map(|x| 1.0 / x))
            * eig.eigenvectors.transpose();
        if smallest < f64::MIN_POSITIVE || !inverse.iter().all(|x| x.is_finite()) {
            return Err(Error::InertiaOutOfRange { smallest, largest });
        }
        Ok(Inertia {
            tensor: sym,
            inverse,
            moments: eig.eigenvalues,
            axes: eig.eigenvectors,
        })
    }

    /// J.
    pub fn matrix(&self) -> &Matrix3<f64> {
        &self.tensor
    }
    /// J⁻¹.
    pub fn inverse(&self) -> &Matrix3<f64> {
        &self.inverse
    }
    /// The principal moments (eigenvalues of J, in the order of [`axes`](Self::axes)).
    pub fn principal_moments(&self) -> Vector3<f64> {
        self.moments
    }
    /// The principal axes: column i is the axis of moment i (body frame).
    pub fn axes(&self) -> &Matrix3<f64> {
        &self.axes
    }
}

/// A rigid body: its inertia tensor and the potential V(R) acting on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBody<V> {
    /// Inertia tensor about the fixed point (or the centre of mass).
    pub inertia: Inertia,
    /// Potential energy of the orientation.
    pub potential: V,
}

impl RigidBody<Free> {
    /// A free body with principal moments I₁, I₂, I₃.
    pub fn free(i1: f64, i2: f64, i3: f64) -> Result<Self> {
        RigidBody::new(Inertia::principal(i1, i2, i3)?, Free)
    }
}

/// A core error of a quantity computed without a time, given the time `t` of the state it came from.
fn at_time(e: Error, t: f64) -> Error {
    match e {
        Error::Core(c) => Error::Core(c.at_time(t)),
        other => other,
    }
}

/// Π from the partner (0, Π₁, Π₂, Π₃) of a state of the right length.
pub(crate) fn partner_momentum(state: &State<Momenta>) -> Vector3<f64> {
    Vector3::new(state.v[1], state.v[2], state.v[3])
}

/// ∂V/∂R through core's gradient kernel: the nine entries of R (row-major) as one block.
struct OnMatrix<'a, V>(&'a V);

impl<V: OrientationPotential> Field for OnMatrix<'_, V> {
    #[inline]
    fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
        self.0.potential(&Matrix3::from_row_slice(x))
    }
}

impl<V: OrientationPotential> RigidBody<V> {
    /// A body of inertia `inertia` in the potential `potential`, whose parameters are checked
    /// ([`OrientationPotential::check`]: a NaN g is refused here, not met as a failed step later).
    pub fn new(inertia: Inertia, potential: V) -> Result<Self> {
        potential.check()?;
        Ok(RigidBody { inertia, potential })
    }

    /// Body angular velocity Ω = J⁻¹ Π: Π finite (else [`noether_core::Error::NonFinite`]) and Ω
    /// finite (else [`noether_core::Error::NonFiniteResult`] with t = NaN: a huge Π overflows).
    pub fn angular_velocity(&self, pi: &Vector3<f64>) -> Result<Vector3<f64>> {
        check_finite("body angular momentum Π", pi.as_slice())?;
        let omega = self.inertia.inverse * pi;
        check_result("angular velocity Ω = J⁻¹Π", f64::NAN, omega.as_slice())?;
        Ok(omega)
    }

    /// Kinetic energy T = ½ Π·J⁻¹Π: Π finite, and T finite (Π = 1e200 overflows to ∞:
    /// [`noether_core::Error::NonFiniteResult`] with t = NaN).
    pub fn kinetic_energy(&self, pi: &Vector3<f64>) -> Result<f64> {
        let t = 0.5 * pi.dot(&self.angular_velocity(pi)?);
        check_result("kinetic energy", f64::NAN, &[t])?;
        Ok(t)
    }

    /// V(R): R finite (else [`noether_core::Error::NonFinite`]) and V finite (else
    /// [`noether_core::Error::NonFiniteResult`] with t = NaN).
    pub fn potential_energy(&self, r: &Matrix3<f64>) -> Result<f64> {
        check_finite("rotation matrix R", r.as_slice())?;
        let v = self.potential.potential(r);
        check_result("potential energy", f64::NAN, &[v])?;
        Ok(v)
    }

    /// Energy E = ½ Π·J⁻¹Π + V(R) at a state (see the module's layout): the state checked as in
    /// [`orientation`](Self::orientation), and E finite (else
    /// [`noether_core::Error::NonFiniteResult`] at the state's t).
    pub fn energy(&self, state: &State<Momenta>) -> Result<f64> {
        let q = self.orientation(state)?;
        let pi = self.body_momentum(state)?;
        let t = state.t;
        let kinetic = self.kinetic_energy(&pi).map_err(|e| at_time(e, t))?;
        let potential = self
            .potential_energy(&q.to_rotation_matrix().into_inner())
            .map_err(|e| at_time(e, t))?;
        let e = kinetic + potential;
        check_result("energy", t, &[e])?;
        Ok(e)
    }

    /// Body-frame torque M = vee(Aᵀ − A), A = Rᵀ ∂V/∂R, with ∂V/∂R by dual numbers (zero for a free
    /// body). R finite (else [`noether_core::Error::NonFinite`]); a non-finite M (V or its
    /// derivative outside its domain) is [`noether_core::Error::NonFiniteResult`] with t = NaN.
    pub fn torque(&self, r: &Matrix3<f64>) -> Result<Vector3<f64>> {
        if self.potential.is_free() {
            return Ok(Vector3::zeros());
        }
        check_finite("rotation matrix R", r.as_slice())?;
        let x: Vec<f64> = r.transpose().as_slice().to_vec(); // row-major entries of R
        let mut g = [0.0; 9];
        gradient(&OnMatrix(&self.potential), 0.0, &x, &[], Block::X, &mut g);
        let dv = Matrix3::from_row_slice(&g);
        let a = r.transpose() * dv;
        let m = vee(&(a.transpose() - a));
        check_result("torque", f64::NAN, m.as_slice())?;
        Ok(m)
    }

    /// The state at time `t` of the body in orientation `q` turning with body angular velocity
    /// `omega` (Π = J Ω).
    pub fn state(&self, t: f64, q: &UnitQuaternion<f64>, omega: &Vector3<f64>) -> State<Momenta> {
        self.state_from_momentum(t, q, &(self.inertia.tensor * omega))
    }

    /// The state at time `t` in orientation `q` with body angular momentum `pi`.
    pub fn state_from_momentum(&self, t: f64, q: &UnitQuaternion<f64>, pi: &Vector3<f64>) -> State<Momenta> {
        State::with_momenta(
            t,
            rotation::wxyz(q.quaternion()).to_vec(),
            vec![0.0, pi[0], pi[1], pi[2]],
        )
    }

    /// The orientation of a state, checked ([`rotation::unit_quaternion`]).
    pub fn orientation(&self, state: &State<Momenta>) -> Result<UnitQuaternion<f64>> {
        state.validate(4)?;
        rotation::unit_quaternion(state.q.as_slice())
    }

    /// The body angular momentum Π of a state.
    pub fn body_momentum(&self, state: &State<Momenta>) -> Result<Vector3<f64>> {
        self.orientation(state)?;
        Ok(partner_momentum(state))
    }

    /// The body angular velocity Ω = J⁻¹Π of a state.
    pub fn body_angular_velocity(&self, state: &State<Momenta>) -> Result<Vector3<f64>> {
        self.angular_velocity(&self.body_momentum(state)?)
            .map_err(|e| at_time(e, state.t))
    }

    /// The spatial angular momentum L = R Π of a state (constant for a free body, whose Casimir
    /// |L| = |Π| the Lie-group integrator keeps to rounding). A Π near the largest float can
    /// overflow in the rotation: [`noether_core::Error::NonFiniteResult`] at the state's t.
    pub fn spatial_angular_momentum(&self, state: &State<Momenta>) -> Result<Vector3<f64>> {
        let q = self.orientation(state)?;
        let l = q * partner_momentum(state);
        check_result("spatial angular momentum L = RΠ", state.t, l.as_slice())?;
        Ok(l)
    }

    /// The rates (Ω, Π̇) at (R, Π): Π̇ = Π × Ω + M; errors as in
    /// [`angular_velocity`](Self::angular_velocity) and [`torque`](Self::torque), and a non-finite
    /// Π̇ is [`noether_core::Error::NonFiniteResult`] with t = NaN.
    pub fn euler_rates(&self, r: &Matrix3<f64>, pi: &Vector3<f64>) -> Result<(Vector3<f64>, Vector3<f64>)> {
        let omega = self.angular_velocity(pi)?;
        let dpi = pi.cross(&omega) + self.torque(r)?;
        check_result("rate of the body angular momentum Π̇", f64::NAN, dpi.as_slice())?;
        Ok((omega, dpi))
    }
}
