//! Quasi-velocities and the Gibbs-Appell equations: nonholonomic motion without multipliers.
//!
//! The user chooses k quasi-velocities u that describe every motion the constraints allow,
//! q̇ = W(t, q) u + w(t, q) (n coordinates, k ≤ n), and says where the mass is: particles at r_i(t, q)
//! with masses m_i, and rigid parts with their centre c_b(t, q), body-frame angular velocity
//! ω_b(t, q, q̇) (linear in q̇), mass M_b and central inertia tensor I_b in body axes. All of it is
//! generic code ([`GibbsAppell`]); noether forms the accelerations along the motion by dual numbers,
//!
//! ```text
//! q̈ = W u̇ + Ẇ u + ẇ,   r̈_i = J_i q̈ + (d²/ds²) r_i(t + s, q + s q̇),   α_b = (∂ω_b/∂q̇) q̈ + (∂_t + q̇·∂_q) ω_b,
//! ```
//!
//! (Ẇ u + ẇ is one directional derivative of q̇(t, q, u) along (1, q̇) at fixed u; the curvature term of
//! r_i is one second-order directional derivative), and the Gibbs function (acceleration energy)
//!
//! ```text
//! S(t, q, u, u̇) = Σ_i ½ m_i |r̈_i|² + Σ_b [ ½ M_b |c̈_b|² + ½ α_b·I_b α_b + α_b·(ω_b × I_b ω_b) ].
//! ```
//!
//! The rigid-part term is Gibbs' function of a rigid body about its centre of mass in body axes, up to
//! terms free of α (which do not enter the equations): with r = c + R ρ, r̈ = c̈ + R(α × ρ + ω × (ω × ρ)),
//! and Σ ½ m |r̈|² summed over the body gives ½ M |c̈|² + ½ α·Iα + α·(ω × Iω) + (terms in ω only).
//! The Gibbs-Appell equations are ∂S/∂u̇_k = Π_k with Π = Wᵀ Q the generalized forces in the
//! quasi-directions (Q = −∂V/∂q plus the user's generalized forces). S is quadratic in u̇:
//! r̈_i = P_i u̇ + a_i with P_i = J_i W (the partial velocities ∂ṙ_i/∂u) and a_i the acceleration at
//! u̇ = 0, so the equations are the symmetric linear system
//!
//! ```text
//! A u̇ = b,   A = Σ m_i P_iᵀP_i + Σ_b (M_b P_cᵀP_c + P_ωᵀ I_b P_ω),
//!            b = Π − Σ m_i P_iᵀ a_i − Σ_b (M_b P_cᵀ a_c + P_ωᵀ (I_b α₀ + ω × I_b ω)),
//! ```
//!
//! solved by core's dense factorization. No multiplier appears: the velocity constraints are
//! satisfied by the choice of u. Equivalently (Gauss' principle of least constraint) u̇ minimizes
//! S − Π·u̇.
//!
//! [`GibbsAppellEquations`] is a core [`Dynamics`] on the state (t, q, u). A core [`State`] holds two
//! vectors of the same length n, so the partner of q is [`QuasiVelocities`]: its first k entries are u
//! and the trailing n − k entries are the quasi-velocities the constraints hold at zero, which stay
//! exactly 0 (their rates are 0; [`Dynamics::admissible`] refuses a state where they are not). Build
//! states with [`GibbsAppellEquations::state`]; every integrator and the one driver run them.
//!
//! # References
//! - Desloge, *Classical Mechanics*, vol. 2, ch. 67–70 (quasi-coordinates, the Gibbs function of a
//!   rigid body, the Gibbs-Appell equations).

use crate::jets::{self, Block, VectorField};
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use noether_core::ad::{self, Field};
use noether_core::error::{check_finite, check_len, check_phase_point};
use noether_core::linalg::DenseFactor;
use noether_core::{Dynamics, Error as CoreError, Partner, Scalar, State};

/// The partner of q in a Gibbs-Appell state: the quasi-velocities u, padded with zeros to length n.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct QuasiVelocities;

impl Partner for QuasiVelocities {
    const SYMBOL: &'static str = "u";
    const NAME: &'static str = "quasi-velocities u";
}

/// Mass and central inertia tensor (in body axes) of a rigid part of a [`GibbsAppell`] system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidPart {
    /// Mass M.
    pub mass: f64,
    /// Inertia tensor I about the centre of mass, in the body axes of the angular velocity.
    pub inertia: Matrix3<f64>,
}

impl RigidPart {
    /// A part with principal moments (I₁, I₂, I₃) along its body axes.
    pub fn principal(mass: f64, moments: [f64; 3]) -> Self {
        RigidPart {
            mass,
            inertia: Matrix3::from_diagonal(&Vector3::from(moments)),
        }
    }

    /// A part with a full (symmetric) inertia tensor.
    pub fn new(mass: f64, inertia: Matrix3<f64>) -> Self {
        RigidPart { mass, inertia }
    }
}

/// A system described by quasi-velocities: q̇ = W(t, q) u + w(t, q), particles and rigid parts, forces.
///
/// Every method with a scalar type parameter is evaluated with dual numbers. Positions and centres
/// depend on (t, q) only; angular velocities must be linear in q̇ (plus a term free of it).
pub trait GibbsAppell {
    /// Number of coordinates n.
    fn dof(&self) -> usize;
    /// Number of quasi-velocities k (1 ≤ k ≤ n).
    fn quasi(&self) -> usize;
    /// q̇ = W(t, q) u + w(t, q) into `qdot` (length n); must be affine in `u`.
    fn velocities<D: Scalar>(&self, t: D, q: &[D], u: &[D], qdot: &mut [D]);
    /// Number of particles N (default 0).
    fn particles(&self) -> usize {
        0
    }
    /// Mass of particle `i`.
    fn mass(&self, _i: usize) -> f64 {
        0.0
    }
    /// Positions r_i(t, q) of the particles into `r` (length 3N: x, y, z of each).
    fn positions<D: Scalar>(&self, _t: D, _q: &[D], _r: &mut [D]) {}
    /// Number of rigid parts B (default 0).
    fn bodies(&self) -> usize {
        0
    }
    /// Mass and inertia of rigid part `b`.
    fn body(&self, _b: usize) -> RigidPart {
        RigidPart::principal(0.0, [0.0; 3])
    }
    /// Centres of mass c_b(t, q) of the rigid parts into `c` (length 3B).
    fn centres<D: Scalar>(&self, _t: D, _q: &[D], _c: &mut [D]) {}
    /// Angular velocities ω_b(t, q, q̇) of the rigid parts in their body axes into `omega` (length 3B).
    fn angular_velocities<D: Scalar>(&self, _t: D, _q: &[D], _qdot: &[D], _omega: &mut [D]) {}
    /// Potential energy V(t, q) (default 0); its forces −∂V/∂q come from dual numbers.
    fn potential<D: Scalar>(&self, _t: D, _q: &[D]) -> D {
        D::from(0.0)
    }
    /// Adds further generalized forces Q(t, q, q̇) (on the coordinates, length n) to `out`.
    fn forces(&self, _t: f64, _q: &[f64], _qdot: &[f64], _out: &mut [f64]) {}
}

struct Vel<'a, M>(&'a M);
impl<M: GibbsAppell> VectorField for Vel<'_, M> {
    fn outputs(&self) -> usize {
        self.0.dof()
    }
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D], out: &mut [D]) {
        self.0.velocities(t, x, y, out)
    }
}

struct Pos<'a, M>(&'a M);
impl<M: GibbsAppell> VectorField for Pos<'_, M> {
    fn outputs(&self) -> usize {
        3 * self.0.particles()
    }
    fn eval<D: Scalar>(&self, t: D, x: &[D], _y: &[D], out: &mut [D]) {
        self.0.positions(t, x, out)
    }
}

struct Cen<'a, M>(&'a M);
impl<M: GibbsAppell> VectorField for Cen<'_, M> {
    fn outputs(&self) -> usize {
        3 * self.0.bodies()
    }
    fn eval<D: Scalar>(&self, t: D, x: &[D], _y: &[D], out: &mut [D]) {
        self.0.centres(t, x, out)
    }
}

struct Omg<'a, M>(&'a M);
impl<M: GibbsAppell> VectorField for Omg<'_, M> {
    fn outputs(&self) -> usize {
        3 * self.0.bodies()
    }
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D], out: &mut [D]) {
        self.0.angular_velocities(t, x, y, out)
    }
}

struct Pot<'a, M>(&'a M);
impl<M: GibbsAppell> Field for Pot<'_, M> {
    fn eval<D: Scalar>(&self, t: D, x: &[D], _y: &[D]) -> D {
        self.0.potential(t, x)
    }
}

/// Points with mass: partial velocities P = ∂ṙ/∂u (3m × k), velocities ṙ and accelerations at u̇ = 0.
struct Points {
    p: DMatrix<f64>,
    vel: Vec<f64>,
    acc0: DVector<f64>,
}

/// Everything at one (t, q, u) that S and its equations need.
struct Kinematics {
    qdot: Vec<f64>,
    w: DMatrix<f64>,
    particles: Points,
    centres: Points,
    /// P_ω = (∂ω/∂q̇) W (3B × k), ω and α₀ (α at u̇ = 0).
    p_omega: DMatrix<f64>,
    omega: Vec<f64>,
    alpha0: DVector<f64>,
}

/// The Gibbs-Appell equations of a [`GibbsAppell`] model, as a core [`Dynamics`] on (t, q, u).
#[derive(Debug, Clone)]
pub struct GibbsAppellEquations<M> {
    model: M,
    parts: Vec<RigidPart>,
    masses: Vec<f64>,
}

impl<M: GibbsAppell> GibbsAppellEquations<M> {
    /// The equations of `model`; errors when k is not in 1..=n, a mass is not finite and positive, or
    /// an inertia tensor is not finite, symmetric and positive semidefinite.
    pub fn new(model: M) -> Result<Self> {
        let (n, k) = (model.dof(), model.quasi());
        if k == 0 || k > n {
            return Err(CoreError::InvalidParameter {
                name: "number of quasi-velocities k",
                value: k as f64,
                reason: "must be at least 1 and at most the number of coordinates n",
            }
            .into());
        }
        let masses: Vec<f64> = (0..model.particles()).map(|i| model.mass(i)).collect();
        let parts: Vec<RigidPart> = (0..model.bodies()).map(|b| model.body(b)).collect();
        for &m in masses.iter().chain(parts.iter().map(|p| &p.mass)) {
            noether_core::error::check_positive("mass", m)?;
        }
        for p in &parts {
            let i = &p.inertia;
            let scale = i.amax();
            let bad = |value: f64, reason| CoreError::InvalidParameter {
                name: "inertia tensor",
                value,
                reason,
            };
            if !i.iter().all(|x| x.is_finite()) {
                return Err(bad(f64::NAN, "must be finite").into());
            }
            if (i - i.transpose()).amax() > 1e-12 * scale {
                return Err(bad((i - i.transpose()).amax(), "must be symmetric").into());
            }
            let low = i.symmetric_eigenvalues().min();
            if low < -1e-12 * scale {
                return Err(bad(low, "must be positive semidefinite (an eigenvalue is negative)").into());
            }
        }
        Ok(GibbsAppellEquations { model, parts, masses })
    }

    /// The model.
    pub fn model(&self) -> &M {
        &self.model
    }

    /// Number of quasi-velocities k.
    pub fn quasi(&self) -> usize {
        self.model.quasi()
    }

    /// A state (t, q, u): u (length k) padded with n − k zeros.
    pub fn state(&self, t: f64, q: &[f64], u: &[f64]) -> Result<State<QuasiVelocities>> {
        let (n, k) = (self.model.dof(), self.quasi());
        check_len("q", q, n)?;
        check_len("u", u, k)?;
        let mut v = vec![0.0; n];
        v[..k].copy_from_slice(u);
        let s = State::from_parts(t, q, v);
        s.validate(n)?;
        Ok(s)
    }

    /// The coordinate rates q̇ = W u + w at (t, q, u) into `qdot`.
    pub fn coordinate_rates(&self, t: f64, q: &[f64], u: &[f64], qdot: &mut [f64]) -> Result<()> {
        self.check(t, q, u)?;
        check_len("q̇ (output)", qdot, self.model.dof())?;
        self.model.velocities(t, q, u, qdot);
        Ok(())
    }

    fn check(&self, t: f64, q: &[f64], u: &[f64]) -> Result<()> {
        check_len("q", q, self.model.dof())?;
        check_len("u", u, self.quasi())?;
        check_finite("t", &[t])?;
        check_finite("q", q)?;
        check_finite("u", u)?;
        Ok(())
    }

    fn points<F: VectorField>(f: &F, t: f64, q: &[f64], k: &Kin0) -> Points {
        let (rows, n) = (f.outputs(), q.len());
        let mut jq = DMatrix::zeros(rows, n);
        jets::jacobian(f, t, q, &[], Block::X, &mut jq);
        let (mut vel, mut curv) = (vec![0.0; rows], vec![0.0; rows]);
        jets::along2(f, t, q, &[], (1.0, &k.qdot, &[]), &mut vel, &mut curv);
        Points {
            p: &jq * &k.w,
            acc0: jq * DVector::from_column_slice(&k.qdd0) + DVector::from_vec(curv),
            vel,
        }
    }

    fn kinematics(&self, t: f64, q: &[f64], u: &[f64]) -> Kinematics {
        let m = &self.model;
        let (n, k) = (m.dof(), self.quasi());
        let mut qdot = vec![0.0; n];
        m.velocities(t, q, u, &mut qdot);
        let mut w = DMatrix::zeros(n, k);
        jets::jacobian(&Vel(m), t, q, u, Block::Y, &mut w);
        // Ẇ u + ẇ: q̇(t, q, u) differentiated along (1, q̇) at fixed u.
        let mut qdd0 = vec![0.0; n];
        jets::along(&Vel(m), t, q, u, (1.0, &qdot, &[]), &mut qdd0);
        let k0 = Kin0 { qdot, w, qdd0 };
        let particles = Self::points(&Pos(m), t, q, &k0);
        let centres = Self::points(&Cen(m), t, q, &k0);
        let rows = 3 * self.parts.len();
        let mut jw = DMatrix::zeros(rows, n);
        jets::jacobian(&Omg(m), t, q, &k0.qdot, Block::Y, &mut jw);
        let mut omega = vec![0.0; rows];
        m.angular_velocities(t, q, &k0.qdot, &mut omega);
        // (∂_t + q̇·∂_q) ω at fixed q̇: direction (1, q̇, 0).
        let mut drift = vec![0.0; rows];
        jets::along(&Omg(m), t, q, &k0.qdot, (1.0, &k0.qdot, &[]), &mut drift);
        let alpha0 = &jw * DVector::from_column_slice(&k0.qdd0) + DVector::from_vec(drift);
        Kinematics {
            p_omega: &jw * &k0.w,
            omega,
            alpha0,
            particles,
            centres,
            qdot: k0.qdot,
            w: k0.w,
        }
    }

    /// Π = Wᵀ Q with Q = −∂V/∂q + the model's forces.
    fn quasi_forces(&self, t: f64, q: &[f64], kin: &Kinematics) -> DVector<f64> {
        let n = q.len();
        let mut grad = vec![0.0; n];
        ad::gradient(&Pot(&self.model), t, q, &[], ad::Block::X, &mut grad);
        let mut force: Vec<f64> = grad.iter().map(|g| -g).collect();
        self.model.forces(t, q, &kin.qdot, &mut force);
        kin.w.tr_mul(&DVector::from_vec(force))
    }

    fn system(&self, t: f64, q: &[f64], kin: &Kinematics) -> (DMatrix<f64>, DVector<f64>) {
        let k = self.quasi();
        let mut a = DMatrix::zeros(k, k);
        let mut b = self.quasi_forces(t, q, kin);
        let block = |m: &DMatrix<f64>, i: usize| m.rows(3 * i, 3).into_owned();
        let seg = |v: &DVector<f64>, i: usize| v.rows(3 * i, 3).into_owned();
        for (i, &mass) in self.masses.iter().enumerate() {
            let p = block(&kin.particles.p, i);
            a += p.tr_mul(&p) * mass;
            b -= p.tr_mul(&seg(&kin.particles.acc0, i)) * mass;
        }
        for (i, part) in self.parts.iter().enumerate() {
            let pc = block(&kin.centres.p, i);
            a += pc.tr_mul(&pc) * part.mass;
            b -= pc.tr_mul(&seg(&kin.centres.acc0, i)) * part.mass;
            let pw = block(&kin.p_omega, i);
            let om = Vector3::from_column_slice(&kin.omega[3 * i..3 * i + 3]);
            let inertia = DMatrix::from_column_slice(3, 3, part.inertia.as_slice());
            a += pw.tr_mul(&(&inertia * &pw));
            let torque = part.inertia * Vector3::from_iterator(seg(&kin.alpha0, i).iter().copied())
                + om.cross(&(part.inertia * om));
            b -= pw.tr_mul(&DVector::from_column_slice(torque.as_slice()));
        }
        (a, b)
    }

    /// The Gibbs-Appell system A u̇ = b at (t, q, u): A = ∂²S/∂u̇² and b = Π − ∂S/∂u̇ at u̇ = 0.
    pub fn equations(&self, t: f64, q: &[f64], u: &[f64]) -> Result<(DMatrix<f64>, DVector<f64>)> {
        self.check(t, q, u)?;
        Ok(self.system(t, q, &self.kinematics(t, q, u)))
    }

    /// The quasi-accelerations u̇ at (t, q, u) into `udot` (length k).
    pub fn accelerations(&self, t: f64, q: &[f64], u: &[f64], udot: &mut [f64]) -> Result<()> {
        check_len("u̇ (output)", udot, self.quasi())?;
        let (a, mut b) = self.equations(t, q, u)?;
        let f = DenseFactor::symmetric(a).map_err(|e| e.in_matrix("Gibbs-Appell matrix ∂²S/∂u̇²"))?;
        f.solve_in_place(b.as_mut_slice());
        noether_core::error::check_result("quasi-accelerations u̇", t, b.as_slice())?;
        udot.copy_from_slice(b.as_slice());
        Ok(())
    }

    /// The Gibbs function S(t, q, u, u̇) (for rigid parts up to terms free of u̇, see the module docs).
    pub fn gibbs(&self, t: f64, q: &[f64], u: &[f64], udot: &[f64]) -> Result<f64> {
        self.check(t, q, u)?;
        check_len("u̇", udot, self.quasi())?;
        let kin = self.kinematics(t, q, u);
        let ud = DVector::from_column_slice(udot);
        let acc = |pts: &Points| &pts.p * &ud + &pts.acc0;
        let (rp, rc) = (acc(&kin.particles), acc(&kin.centres));
        let alpha = &kin.p_omega * &ud + &kin.alpha0;
        let mut s = 0.0;
        for (i, m) in self.masses.iter().enumerate() {
            s += 0.5 * m * rp.rows(3 * i, 3).norm_squared();
        }
        for (i, part) in self.parts.iter().enumerate() {
            let al = Vector3::from_iterator(alpha.rows(3 * i, 3).iter().copied());
            let om = Vector3::from_column_slice(&kin.omega[3 * i..3 * i + 3]);
            s += 0.5 * part.mass * rc.rows(3 * i, 3).norm_squared()
                + 0.5 * al.dot(&(part.inertia * al))
                + al.dot(&om.cross(&(part.inertia * om)));
        }
        Ok(s)
    }

    /// The generalized forces in the quasi-directions Π = Wᵀ Q at (t, q, u) (length k).
    pub fn quasi_forces_at(&self, t: f64, q: &[f64], u: &[f64]) -> Result<DVector<f64>> {
        self.check(t, q, u)?;
        Ok(self.quasi_forces(t, q, &self.kinematics(t, q, u)))
    }

    /// Kinetic energy T = Σ ½ m_i |ṙ_i|² + Σ_b (½ M_b |ċ_b|² + ½ ω_b·I_b ω_b).
    pub fn kinetic_energy(&self, t: f64, q: &[f64], u: &[f64]) -> Result<f64> {
        self.check(t, q, u)?;
        let kin = self.kinematics(t, q, u);
        let half_sq = |v: &[f64]| 0.5 * v.iter().map(|x| x * x).sum::<f64>();
        let mut e = 0.0;
        for (i, m) in self.masses.iter().enumerate() {
            e += m * half_sq(&kin.particles.vel[3 * i..3 * i + 3]);
        }
        for (i, part) in self.parts.iter().enumerate() {
            let om = Vector3::from_column_slice(&kin.omega[3 * i..3 * i + 3]);
            e += part.mass * half_sq(&kin.centres.vel[3 * i..3 * i + 3]) + 0.5 * om.dot(&(part.inertia * om));
        }
        Ok(e)
    }
}

/// q̇, W and Ẇu + ẇ at one point.
struct Kin0 {
    qdot: Vec<f64>,
    w: DMatrix<f64>,
    qdd0: Vec<f64>,
}

impl<M: GibbsAppell> Dynamics for GibbsAppellEquations<M> {
    type Partner = QuasiVelocities;
    fn dof(&self) -> usize {
        self.model.dof()
    }
    /// q̇ = W u + w and (u̇, 0): the padding entries of the partner have zero rate.
    fn rates(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        dq: &mut [f64],
        dv: &mut [f64],
    ) -> noether_core::Result<()> {
        let (n, k) = (self.model.dof(), self.quasi());
        check_phase_point(n, t, q, v, "u")?;
        check_len("q̇ (output)", dq, n)?;
        check_len("u̇ (output)", dv, n)?;
        self.accelerations(t, q, &v[..k], &mut dv[..k])?;
        dv[k..].iter_mut().for_each(|x| *x = 0.0);
        self.model.velocities(t, q, &v[..k], dq);
        Ok(())
    }
    /// T + V (conserved when neither the model nor W, w depend on t and the forces do no work).
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> noether_core::Result<f64> {
        let (n, k) = (self.model.dof(), self.quasi());
        check_phase_point(n, t, q, v, "u")?;
        Ok(self.kinetic_energy(t, q, &v[..k])? + self.model.potential(t, q))
    }
    /// Refuses a state whose padding entries (the n − k quasi-velocities the constraints hold at zero)
    /// are not exactly 0.
    fn admissible(&self, t: f64, _q: &[f64], v: &[f64]) -> noether_core::Result<()> {
        let k = self.quasi();
        let residual = v.iter().skip(k).fold(0.0_f64, |m, x| m.max(x.abs()));
        if residual != 0.0 {
            return Err(Error::ConstraintViolated {
                what: "quasi-velocity (padding of u must be 0)",
                t,
                residual,
                tolerance: 0.0,
            }
            .into());
        }
        Ok(())
    }
    fn position_rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64]) -> noether_core::Result<()> {
        let (n, k) = (self.model.dof(), self.quasi());
        check_phase_point(n, t, q, v, "u")?;
        check_len("q̇ (output)", dq, n)?;
        self.model.velocities(t, q, &v[..k], dq);
        Ok(())
    }
}
