//! Quasi-velocities and the Gibbs-Appell equations: a rigid body of four particles about a fixed point
//! (Euler's equations), a vertical disk rolling without slipping on an inclined plane (with and without
//! multipliers, and its closed form), a sphere rolling on a turntable and in a bowl.
//!
//! Used by noether-constraints' tests (`tests/it/gibbs_appell.rs`) and the gallery's `gibbs_appell` and
//! `rolling_sphere` examples.

use nalgebra::{Matrix3, Vector3};
use noether_constraints::{
    Constrained, GibbsAppell, GibbsAppellEquations, Nonholonomic, Projected, QuasiVelocities, RigidPart,
};
use noether_core::integrators::Rk4;
use noether_core::{Driver, Dynamics, Lagrangian, Scalar, Solution, State};

/// Quaternion (w, x, y, z) product a ⊗ b.
pub fn qmul<D: Scalar>(a: &[D], b: &[D]) -> [D; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// R(q) ρ for a unit quaternion q (body → space): q ⊗ (0, ρ) ⊗ q̄.
pub fn rotate<D: Scalar>(q: &[D], p: [f64; 3]) -> [D; 3] {
    let zero = D::from(0.0);
    let r = qmul(
        &qmul(q, &[zero, D::from(p[0]), D::from(p[1]), D::from(p[2])]),
        &[q[0], -q[1], -q[2], -q[3]],
    );
    [r[1], r[2], r[3]]
}

/// Body-frame angular velocity ω = 2 vec(q̄ ⊗ q̇)/|q|² (the division keeps ω = Rᵀω_space exact when an
/// integrator lets |q| drift from 1).
pub fn body_omega<D: Scalar>(q: &[D], qdot: &[D]) -> [D; 3] {
    let r = qmul(&[q[0], -q[1], -q[2], -q[3]], qdot);
    let n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    [r[1] * 2.0 / n2, r[2] * 2.0 / n2, r[3] * 2.0 / n2]
}

/// q̇ = ½ q ⊗ (0, ω_body) into `out`.
pub fn quat_rate_body<D: Scalar>(q: &[D], omega: &[D], out: &mut [D]) {
    let r = qmul(q, &[D::from(0.0), omega[0], omega[1], omega[2]]);
    for (o, r) in out.iter_mut().zip(r) {
        *o = r * 0.5;
    }
}

/// q̇ = ½ (0, ω_space) ⊗ q into `out`.
pub fn quat_rate_space<D: Scalar>(q: &[D], omega: &[D], out: &mut [D]) {
    let r = qmul(&[D::from(0.0), omega[0], omega[1], omega[2]], q);
    for (o, r) in out.iter_mut().zip(r) {
        *o = r * 0.5;
    }
}

/// The quaternion divided by its norm.
pub fn unit(q: [f64; 4]) -> [f64; 4] {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    q.map(|x| x / n)
}

/// Particle positions of the four-particle top in body axes.
pub const RHO: [[f64; 3]; 4] = [
    [0.3, 0.1, 0.5],
    [-0.2, 0.4, 0.6],
    [0.1, -0.5, 0.4],
    [0.05, 0.2, 0.9],
];
/// Particle masses of the four-particle top.
pub const MASS: [f64; 4] = [1.0, 2.0, 1.5, 0.7];
/// Gravity.
pub const G: f64 = 9.81;

/// A rigid body of four particles about a fixed point (the origin), in gravity: q the unit quaternion,
/// u = ω in body axes, q̇ = ½ q ⊗ (0, ω).
pub struct ParticleTop;

impl GibbsAppell for ParticleTop {
    fn dof(&self) -> usize {
        4
    }
    fn quasi(&self) -> usize {
        3
    }
    fn velocities<D: Scalar>(&self, _t: D, q: &[D], u: &[D], qdot: &mut [D]) {
        quat_rate_body(q, u, qdot)
    }
    fn particles(&self) -> usize {
        4
    }
    fn mass(&self, i: usize) -> f64 {
        MASS[i]
    }
    fn positions<D: Scalar>(&self, _t: D, q: &[D], r: &mut [D]) {
        for (i, rho) in RHO.iter().enumerate() {
            r[3 * i..3 * i + 3].copy_from_slice(&rotate(q, *rho));
        }
    }
    fn potential<D: Scalar>(&self, _t: D, q: &[D]) -> D {
        let mut v = D::from(0.0);
        for (rho, m) in RHO.iter().zip(MASS) {
            v += rotate(q, *rho)[2] * (m * G);
        }
        v
    }
}

/// The four-particle top's mass, centre of mass (body axes) and inertia tensors about the fixed point
/// and about the centre: I = Σ m (|ρ|² 1 − ρ ρᵀ), I_c = I_o − M (|c|² 1 − c cᵀ) (parallel axes).
pub fn inertia() -> (f64, Vector3<f64>, Matrix3<f64>, Matrix3<f64>) {
    let tensor = |m: f64, p: Vector3<f64>| (Matrix3::identity() * p.norm_squared() - p * p.transpose()) * m;
    let mass: f64 = MASS.iter().sum();
    let mut c = Vector3::zeros();
    let mut i_o = Matrix3::zeros();
    for (rho, m) in RHO.iter().zip(MASS) {
        let p = Vector3::from(*rho);
        c += p * (m / mass);
        i_o += tensor(m, p);
    }
    (mass, c, i_o, i_o - tensor(mass, c))
}

/// Euler's equations of the four-particle top about the fixed point, ω̇ = I_o⁻¹ (N − ω × I_o ω) with
/// N = Σ ρ_i × Rᵀ(−m_i g ẑ) in body axes; `None` if I_o is singular.
pub fn euler_rates(i_o: &Matrix3<f64>, q: &[f64; 4], w: [f64; 3]) -> Option<Vector3<f64>> {
    let omega = Vector3::from(w);
    // Gravity in body axes: Rᵀ ẑ is the third row of R, read off by rotating with q̄.
    let z_body = Vector3::from(rotate(&[q[0], -q[1], -q[2], -q[3]], [0.0, 0.0, 1.0]));
    let torque = RHO.iter().zip(MASS).fold(Vector3::zeros(), |n, (rho, m)| {
        n + Vector3::from(*rho).cross(&(z_body * (-m * G)))
    });
    i_o.lu().solve(&(torque - omega.cross(&(i_o * omega))))
}

/// A rigid body as one rigid part turning about the origin: centre R c, inertia about the centre,
/// ω = 2 vec(q̄ ⊗ q̇)/|q|² from (q, q̇), gravity on the centre.
pub struct BodyTop {
    /// Mass.
    pub mass: f64,
    /// Centre of mass in body axes.
    pub c: [f64; 3],
    /// Inertia about the centre of mass, body axes.
    pub i_c: Matrix3<f64>,
}

impl GibbsAppell for BodyTop {
    fn dof(&self) -> usize {
        4
    }
    fn quasi(&self) -> usize {
        3
    }
    fn velocities<D: Scalar>(&self, _t: D, q: &[D], u: &[D], qdot: &mut [D]) {
        quat_rate_body(q, u, qdot)
    }
    fn bodies(&self) -> usize {
        1
    }
    fn body(&self, _b: usize) -> RigidPart {
        RigidPart::new(self.mass, self.i_c)
    }
    fn centres<D: Scalar>(&self, _t: D, q: &[D], c: &mut [D]) {
        c.copy_from_slice(&rotate(q, self.c));
    }
    fn angular_velocities<D: Scalar>(&self, _t: D, q: &[D], qdot: &[D], omega: &mut [D]) {
        omega.copy_from_slice(&body_omega(q, qdot));
    }
    fn potential<D: Scalar>(&self, _t: D, q: &[D]) -> D {
        rotate(q, self.c)[2] * (self.mass * G)
    }
}

/// The four-particle top's body turning freely about its centre of mass (no torque): [`BodyTop`] with
/// the centre at the fixed point and I_c from [`inertia`]; its energy ½ ω·I_c ω and Casimir |I_c ω| are
/// constants of Euler's equations.
pub fn free_body() -> BodyTop {
    let (mass, _, _, i_c) = inertia();
    BodyTop {
        mass,
        c: [0.0; 3],
        i_c,
    }
}

/// The rolling disk's radius R.
pub const R: f64 = 0.3;
/// The rolling disk's mass m.
pub const M: f64 = 2.0;
/// The slope's share of gravity g' = g sin β: the disk's potential is V = m g' x.
pub const G_TILT: f64 = 9.81 * 0.2;

/// A vertical disk (radius R, mass m) rolling on a plane tilted so that V = m g' x, with multipliers:
/// q = (x, y, θ, φ) (contact point, rolling angle, heading),
/// L = ½ m (ẋ² + ẏ²) + ½ I θ̇² + ½ J φ̇² − m g' x, I = ½ m R², J = ¼ m R².
pub struct DiskL;

impl Lagrangian for DiskL {
    fn dof(&self) -> usize {
        4
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + v[1] * v[1]) * (0.5 * M)
            + v[2] * v[2] * (0.25 * M * R * R)
            + v[3] * v[3] * (0.125 * M * R * R)
            - q[0] * (M * G_TILT)
    }
}

/// The disk's rolling without slipping: ẋ = R θ̇ cos φ, ẏ = R θ̇ sin φ.
pub struct Rolling;

impl Nonholonomic for Rolling {
    fn dof(&self) -> usize {
        4
    }
    fn count(&self) -> usize {
        2
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], v: &[D], out: &mut [D]) {
        out[0] = v[0] - v[2] * q[3].cos() * R;
        out[1] = v[1] - v[2] * q[3].sin() * R;
    }
}

/// The same disk with u = (θ̇, φ̇): q̇ = (R θ̇ cos φ, R θ̇ sin φ, θ̇, φ̇), one rigid part with centre
/// (x, y, R), body axes after R_z(φ) R_y(θ) (axle along body y), ω = (−φ̇ sin θ, θ̇, φ̇ cos θ),
/// I = diag(J, I, J).
pub struct DiskGA;

impl GibbsAppell for DiskGA {
    fn dof(&self) -> usize {
        4
    }
    fn quasi(&self) -> usize {
        2
    }
    fn velocities<D: Scalar>(&self, _t: D, q: &[D], u: &[D], qdot: &mut [D]) {
        qdot[0] = u[0] * q[3].cos() * R;
        qdot[1] = u[0] * q[3].sin() * R;
        qdot[2] = u[0];
        qdot[3] = u[1];
    }
    fn bodies(&self) -> usize {
        1
    }
    fn body(&self, _b: usize) -> RigidPart {
        RigidPart::principal(M, [0.25 * M * R * R, 0.5 * M * R * R, 0.25 * M * R * R])
    }
    fn centres<D: Scalar>(&self, _t: D, q: &[D], c: &mut [D]) {
        c[0] = q[0];
        c[1] = q[1];
        c[2] = D::from(R);
    }
    fn angular_velocities<D: Scalar>(&self, _t: D, q: &[D], v: &[D], omega: &mut [D]) {
        omega[0] = -v[3] * q[2].sin();
        omega[1] = v[2];
        omega[2] = v[3] * q[2].cos();
    }
    fn potential<D: Scalar>(&self, _t: D, q: &[D]) -> D {
        q[0] * (M * G_TILT)
    }
}

/// The disk's q̈ = W u̇ + Ẇ u from the Gibbs-Appell u̇ = (θ̈, φ̈) at heading φ = `q[3]`.
pub fn disk_qdd(q: &[f64; 4], u: &[f64; 2], ud: &[f64; 2]) -> [f64; 4] {
    let (s, c) = q[3].sin_cos();
    [
        R * (ud[0] * c - u[0] * u[1] * s),
        R * (ud[0] * s + u[0] * u[1] * c),
        ud[0],
        ud[1],
    ]
}

/// The disk's q̈ at (q, u) both ways: with multipliers ([`DiskL`], [`Rolling`], at q̇ = W u) and from
/// the Gibbs-Appell u̇ of [`DiskGA`] through [`disk_qdd`]; the two agree to rounding.
pub fn disk_both_ways(q: &[f64; 4], u: &[f64; 2]) -> noether_constraints::Result<([f64; 4], [f64; 4])> {
    let mult = Constrained::nonholonomic(DiskL, Rolling)?;
    let ga = GibbsAppellEquations::new(DiskGA)?;
    let qdot = [R * u[0] * q[3].cos(), R * u[0] * q[3].sin(), u[0], u[1]];
    let (mut dq, mut qdd) = ([0.0; 4], [0.0; 4]);
    Dynamics::rates(&mult, 0.0, q, &qdot, &mut dq, &mut qdd)?;
    let mut ud = [0.0; 2];
    ga.accelerations(0.0, q, u, &mut ud)?;
    Ok((qdd, disk_qdd(q, u, &ud)))
}

/// The disk's closed form: θ̈ = −m g' R cos φ/(m R² + I) with φ = φ₀ + φ̇ t, so
/// θ̇(t) = θ̇₀ − 2 g' (sin φ − sin φ₀)/(3 R φ̇).
pub fn disk_theta_dot(th0: f64, ph0: f64, phd: f64) -> impl Fn(f64) -> f64 + Copy {
    move |t: f64| th0 - 2.0 * G_TILT * ((ph0 + phd * t).sin() - ph0.sin()) / (3.0 * R * phd)
}

/// A uniform sphere of mass 1 and radius `a` as a rigid part: I = (2/5) a².
pub fn sphere(a: f64) -> RigidPart {
    RigidPart::principal(1.0, [0.4 * a * a; 3])
}

/// A uniform sphere (radius a, I = (2/5) m a²) rolling without slipping on a table turning at Ω about
/// the vertical z axis through the origin. q = (x, y, quaternion), u = ω in space axes;
/// no slip at the contact: ṙ = Ω ẑ × r + a ω × ẑ.
pub struct Turntable {
    /// Sphere radius.
    pub a: f64,
    /// The table's angular velocity Ω.
    pub omega: f64,
}

impl GibbsAppell for Turntable {
    fn dof(&self) -> usize {
        6
    }
    fn quasi(&self) -> usize {
        3
    }
    fn velocities<D: Scalar>(&self, _t: D, q: &[D], u: &[D], qdot: &mut [D]) {
        qdot[0] = u[1] * self.a - q[1] * self.omega;
        qdot[1] = -u[0] * self.a + q[0] * self.omega;
        quat_rate_space(&q[2..6], u, &mut qdot[2..6]);
    }
    fn bodies(&self) -> usize {
        1
    }
    fn body(&self, _b: usize) -> RigidPart {
        sphere(self.a)
    }
    fn centres<D: Scalar>(&self, _t: D, q: &[D], c: &mut [D]) {
        c[0] = q[0];
        c[1] = q[1];
        c[2] = D::from(self.a);
    }
    fn angular_velocities<D: Scalar>(&self, _t: D, q: &[D], qdot: &[D], omega: &mut [D]) {
        omega.copy_from_slice(&body_omega(&q[2..6], &qdot[2..6]));
    }
}

/// The turntable orbit. With friction F at the contact, m v̇ = F and I ω̇ = (−a ẑ) × F; differentiating
/// the no-slip condition v = Ω ẑ × r + a ω × ẑ gives v̇ = Ω ẑ × v − (m a²/I) v̇, so
/// v̇ = (2/7) Ω ẑ × v: the velocity turns at ν = 2Ω/7 and the centre runs on a circle,
/// r(t) = r₀ + [sin νt v₀ + (1 − cos νt) ẑ × v₀]/ν, v₀ = Ω ẑ × r₀ + a ω₀ × ẑ; ω_z stays constant.
/// Returns ν and r(t).
pub fn turntable_orbit(
    a: f64,
    big_omega: f64,
    r0: [f64; 2],
    w0: [f64; 3],
) -> (f64, impl Fn(f64) -> [f64; 2] + Copy) {
    let v0 = [a * w0[1] - big_omega * r0[1], -a * w0[0] + big_omega * r0[0]];
    let nu = 2.0 * big_omega / 7.0;
    let exact = move |t: f64| {
        let (s, c) = (nu * t).sin_cos();
        [
            r0[0] + (s * v0[0] - (1.0 - c) * v0[1]) / nu,
            r0[1] + (s * v0[1] + (1.0 - c) * v0[0]) / nu,
        ]
    };
    (nu, exact)
}

/// The sphere of radius `a` on the turntable at Ω = `big_omega`, from the centre r₀ = `r0` and
/// ω₀ = `w0` (orientation the identity) over two orbits (t = 2·2π/ν) by RK4 with step `h`, observing
/// `err` = |r − r(t)| against [`turntable_orbit`] and `wz` = ω_z − ω_z(0).
pub fn turntable_run(
    a: f64,
    big_omega: f64,
    r0: [f64; 2],
    w0: [f64; 3],
    h: f64,
) -> noether_constraints::Result<Solution<QuasiVelocities>> {
    let sys = GibbsAppellEquations::new(Turntable { a, omega: big_omega })?;
    let (nu, exact) = turntable_orbit(a, big_omega, r0, w0);
    let start = sys.state(0.0, &[r0[0], r0[1], 1.0, 0.0, 0.0, 0.0], &w0)?;
    let sol = Driver::with_step(Rk4::new(&sys), start, h)?
        .observe("err", move |s: &State<QuasiVelocities>| {
            let e = exact(s.t);
            (s.q[0] - e[0]).hypot(s.q[1] - e[1])
        })
        .observe("wz", move |s: &State<QuasiVelocities>| s.v[2] - w0[2])
        .run_until(2.0 * 2.0 * std::f64::consts::PI / nu)?;
    Ok(sol)
}

/// The rolling disk from q₀ = (1, −0.5, 0, φ₀) with θ̇₀, φ̇ over 10 s by RK4 (h = 1e-3), once by
/// Gibbs-Appell ([`DiskGA`]) and once with multipliers ([`DiskL`], [`Rolling`], projected onto the
/// constraints); each run observes `err` = θ̇ − [`disk_theta_dot`].
pub fn disk_runs(
    th0: f64,
    ph0: f64,
    phd: f64,
) -> noether_constraints::Result<(Solution<QuasiVelocities>, Solution)> {
    let mult = Constrained::nonholonomic(DiskL, Rolling)?;
    let ga = GibbsAppellEquations::new(DiskGA)?;
    let closed = disk_theta_dot(th0, ph0, phd);
    let q0 = [1.0, -0.5, 0.0, ph0];
    let ga_sol = Driver::with_step(Rk4::new(&ga), ga.state(0.0, &q0, &[th0, phd])?, 1e-3)?
        .observe("err", move |s: &State<QuasiVelocities>| s.v[0] - closed(s.t))
        .run_until(10.0)?;
    let start = State::new(0.0, q0, [R * th0 * ph0.cos(), R * th0 * ph0.sin(), th0, phd]);
    let m_sol = Driver::with_step(Projected::new(Rk4::new(&mult), mult.constraints()), start, 1e-3)?
        .observe("err", move |s: &State| s.v[2] - closed(s.t))
        .run_until(10.0)?;
    Ok((ga_sol, m_sol))
}
