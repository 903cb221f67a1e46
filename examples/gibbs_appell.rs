//! Quasi-velocities and the Gibbs-Appell equations: Euler's equations of a rigid body, and the rolling
//! disk without multipliers.
//!
//! A system is described by k quasi-velocities u with q̇ = W(t, q) u + w(t, q), by where its mass is
//! (particles r_i(t, q), rigid parts with centre, body-frame angular velocity and inertia) and by its
//! forces. noether forms the Gibbs function (acceleration energy)
//! S = Σ ½ m_i |r̈_i|² + Σ_b [½ M |c̈|² + ½ α·I α + α·(ω × I ω)] by dual numbers, and solves the
//! Gibbs-Appell equations ∂S/∂u̇ = Π (Π = Wᵀ Q) for u̇.
//!
//! 1. A rigid body of four particles turning about a fixed point in gravity, q the unit quaternion and
//!    u = ω in body axes (q̇ = ½ q ⊗ (0, ω)): S built from the particles gives exactly Euler's equations
//!    I ω̇ + ω × I ω = N about the fixed point, and so does the rigid-part Gibbs function.
//! 2. A vertical disk rolling without slipping on an inclined plane, q = (x, y, θ, φ), u = (θ̇, φ̇):
//!    q̇ = (R θ̇ cos φ, R θ̇ sin φ, θ̇, φ̇) satisfies the two rolling constraints by construction, so the
//!    equations have 2 unknowns u̇ instead of the multiplier form's 4 accelerations and 2 multipliers.
//!    Both give the same accelerations, and the closed form θ̇(t) = θ̇₀ − 2 g' (sin φ − sin φ₀)/(3 R φ̇)
//!    with φ = φ₀ + φ̇ t (θ̈ = −m g' R cos φ/(m R² + I), I = ½ m R², φ̈ = 0).
//!
//! Run: `cargo run --release --features examples --example gibbs_appell`.

use noether::constraints::{Constrained, Nonholonomic, Projected};
use noether::constraints::{GibbsAppell, GibbsAppellEquations, QuasiVelocities, RigidPart};
use noether::core::integrators::Rk4;
use noether::nalgebra::{Matrix3, Vector3};
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use std::process::ExitCode;

const NAME: &str = "gibbs_appell";

/// Quaternion (w, x, y, z) product a ⊗ b.
fn qmul<D: Scalar>(a: &[D], b: &[D]) -> [D; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// R(q) ρ for a unit quaternion q: q ⊗ (0, ρ) ⊗ q̄.
fn rotate<D: Scalar>(q: &[D], p: [f64; 3]) -> [D; 3] {
    let pure = [D::from(0.0), D::from(p[0]), D::from(p[1]), D::from(p[2])];
    let r = qmul(&qmul(q, &pure), &[q[0], -q[1], -q[2], -q[3]]);
    [r[1], r[2], r[3]]
}

/// Particle positions in body axes and masses.
const RHO: [[f64; 3]; 4] = [
    [0.3, 0.1, 0.5],
    [-0.2, 0.4, 0.6],
    [0.1, -0.5, 0.4],
    [0.05, 0.2, 0.9],
];
const MASS: [f64; 4] = [1.0, 2.0, 1.5, 0.7];
const G: f64 = 9.81;

/// Four particles rigidly fixed to a body that turns about the origin, in gravity.
pub struct ParticleTop;

impl GibbsAppell for ParticleTop {
    fn dof(&self) -> usize {
        4
    }
    fn quasi(&self) -> usize {
        3
    }
    /// q̇ = ½ q ⊗ (0, ω).
    fn velocities<D: Scalar>(&self, _t: D, q: &[D], u: &[D], qdot: &mut [D]) {
        let r = qmul(q, &[D::from(0.0), u[0], u[1], u[2]]);
        for (d, r) in qdot.iter_mut().zip(r) {
            *d = r * 0.5;
        }
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
        RHO.iter()
            .zip(MASS)
            .fold(D::from(0.0), |v, (rho, m)| v + rotate(q, *rho)[2] * (m * G))
    }
}

/// The same body as one rigid part: centre R c, central inertia I_c, ω = 2 vec(q̄ ⊗ q̇)/|q|².
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
    fn velocities<D: Scalar>(&self, t: D, q: &[D], u: &[D], qdot: &mut [D]) {
        ParticleTop.velocities(t, q, u, qdot)
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
        let r = qmul(&[q[0], -q[1], -q[2], -q[3]], qdot);
        let n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
        for k in 0..3 {
            omega[k] = r[k + 1] * 2.0 / n2;
        }
    }
    fn potential<D: Scalar>(&self, _t: D, q: &[D]) -> D {
        rotate(q, self.c)[2] * (self.mass * G)
    }
}

/// Disk radius, mass and the slope's share of gravity g' = g sin β.
const R: f64 = 0.3;
const M: f64 = 2.0;
const G_TILT: f64 = 9.81 * 0.2;

/// The disk with multipliers: L = ½ m (ẋ² + ẏ²) + ½ I θ̇² + ½ J φ̇² − m g' x, I = ½ m R², J = ¼ m R².
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

/// Rolling without slipping: ẋ = R θ̇ cos φ, ẏ = R θ̇ sin φ.
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

/// The disk with quasi-velocities u = (θ̇, φ̇): one rigid part, centre (x, y, R), body axes after
/// R_z(φ) R_y(θ) (axle along body y), ω = (−φ̇ sin θ, θ̇, φ̇ cos θ), I = diag(J, I, J).
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

/// Largest |x| of a series.
fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// Check 1: ω̇ from the particles' and the rigid part's Gibbs function against Euler's equations.
fn euler(checks: &mut Vec<Check>) -> Result<(), BoxError> {
    let tensor = |m: f64, p: Vector3<f64>| (Matrix3::identity() * p.norm_squared() - p * p.transpose()) * m;
    let mass: f64 = MASS.iter().sum();
    let (mut c, mut i_o) = (Vector3::zeros(), Matrix3::zeros());
    for (rho, m) in RHO.iter().zip(MASS) {
        c += Vector3::from(*rho) * (m / mass);
        i_o += tensor(m, Vector3::from(*rho));
    }
    let i_c = i_o - tensor(mass, c);
    let particles = GibbsAppellEquations::new(ParticleTop)?;
    let body = GibbsAppellEquations::new(BodyTop {
        mass,
        c: [c[0], c[1], c[2]],
        i_c,
    })?;
    let q = {
        let q = [0.8_f64, 0.3, -0.4, 0.2];
        let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        q.map(|x| x / n)
    };
    let w = [2.0, 0.7, -1.5];
    let omega = Vector3::from(w);
    // N = Σ ρ_i × Rᵀ(−m_i g ẑ): gravity in body axes is ẑ rotated by q̄.
    let z_body = Vector3::from(rotate(&[q[0], -q[1], -q[2], -q[3]], [0.0, 0.0, 1.0]));
    let torque = RHO.iter().zip(MASS).fold(Vector3::zeros(), |n, (rho, m)| {
        n + Vector3::from(*rho).cross(&(z_body * (-m * G)))
    });
    let exact = i_o
        .lu()
        .solve(&(torque - omega.cross(&(i_o * omega))))
        .ok_or("singular inertia tensor")?;
    let (mut a, mut b) = ([0.0; 3], [0.0; 3]);
    particles.accelerations(0.0, &q, &w, &mut a)?;
    body.accelerations(0.0, &q, &w, &mut b)?;
    let rel = |x: [f64; 3]| (Vector3::from(x) - exact).norm() / exact.norm();
    // Both agree with Euler to rounding (measured 1.1e-16 for both): 2e-15.
    checks.push(Check::abs(
        NAME,
        "|ω̇ − I⁻¹(N − ω × Iω)|/|ω̇|, S from particles",
        rel(a),
        0.0,
        2e-15,
    ));
    checks.push(Check::abs(
        NAME,
        "|ω̇ − I⁻¹(N − ω × Iω)|/|ω̇|, S of a rigid part",
        rel(b),
        0.0,
        2e-15,
    ));

    // Torque-free (centre at the fixed point, no gravity): energy and |L| = |I_c ω| are constant.
    let free = GibbsAppellEquations::new(BodyTop {
        mass,
        c: [0.0; 3],
        i_c,
    })?;
    let w0 = [0.5, -1.0, 3.0];
    let energy = move |w: &[f64]| {
        0.5 * Vector3::from_column_slice(&w[..3]).dot(&(i_c * Vector3::from_column_slice(&w[..3])))
    };
    let casimir = move |w: &[f64]| (i_c * Vector3::from_column_slice(&w[..3])).norm();
    let (e0, l0) = (energy(&w0), casimir(&w0));
    let sol = Driver::with_step(Rk4::new(&free), free.state(0.0, &q, &w0)?, 1e-3)?
        .observe("dE", move |s: &State<QuasiVelocities>| {
            (energy(s.v.as_slice()) - e0) / e0
        })
        .observe("dL", move |s: &State<QuasiVelocities>| {
            (casimir(s.v.as_slice()) - l0) / l0
        })
        .run_until(10.0)?;
    let de = max_abs(&sol.observed("dE")?);
    let dl = max_abs(&sol.observed("dL")?);
    // RK4, h = 1e-3, 10 s: measured 1.5e-14 and 7.9e-15: 5e-14.
    checks.push(Check::abs(
        NAME,
        "free body: max rel. drift of ½ ω·Iω (RK4, 10 s)",
        de,
        0.0,
        5e-14,
    ));
    checks.push(Check::abs(
        NAME,
        "free body: max rel. drift of |Iω| (RK4, 10 s)",
        dl,
        0.0,
        5e-14,
    ));
    Ok(())
}

/// Check 2: the rolling disk, Gibbs-Appell against the multiplier form and the closed form.
fn disk(checks: &mut Vec<Check>) -> Result<(), BoxError> {
    let mult = Constrained::nonholonomic(DiskL, Rolling)?;
    let ga = GibbsAppellEquations::new(DiskGA)?;
    let (q, u) = ([0.1_f64, -0.4, 0.3, 0.9], [6.0_f64, 0.8]);
    let qdot = [R * u[0] * q[3].cos(), R * u[0] * q[3].sin(), u[0], u[1]];
    let (mut dq, mut qdd) = ([0.0; 4], [0.0; 4]);
    Dynamics::rates(&mult, 0.0, &q, &qdot, &mut dq, &mut qdd)?;
    let mut ud = [0.0; 2];
    ga.accelerations(0.0, &q, &u, &mut ud)?;
    let (s, c) = q[3].sin_cos();
    // q̈ = W u̇ + Ẇ u.
    let from_ga = [
        R * (ud[0] * c - u[0] * u[1] * s),
        R * (ud[0] * s + u[0] * u[1] * c),
        ud[0],
        ud[1],
    ];
    let diff = qdd
        .iter()
        .zip(from_ga)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()))
        / max_abs(&qdd);
    // The same accelerations to rounding (measured 4.9e-16): 4e-15.
    checks.push(Check::abs(
        NAME,
        "disk: max|q̈ (Gibbs-Appell) − q̈ (multipliers)|/|q̈|",
        diff,
        0.0,
        4e-15,
    ));

    let (th0, ph0, phd) = (6.0, 0.4, 0.8);
    let closed = move |t: f64| th0 - 2.0 * G_TILT * ((ph0 + phd * t).sin() - ph0.sin()) / (3.0 * R * phd);
    let q0 = [1.0, -0.5, 0.0, ph0];
    let ga_sol = Driver::with_step(Rk4::new(&ga), ga.state(0.0, &q0, &[th0, phd])?, 1e-3)?
        .observe("err", move |s: &State<QuasiVelocities>| s.v[0] - closed(s.t))
        .run_until(10.0)?;
    let start = State::new(0.0, q0, [R * th0 * ph0.cos(), R * th0 * ph0.sin(), th0, phd]);
    let m_sol = Driver::with_step(Projected::new(Rk4::new(&mult), mult.constraints()), start, 1e-3)?
        .run_until(10.0)?;
    let err = max_abs(&ga_sol.observed("err")?);
    let dq = (&ga_sol.last().q - &m_sol.last().q).amax();
    // RK4, h = 1e-3, 10 s: θ̇ measured 4.1e-13 (truncation): 1e-12; the two runs' q at the end differ by
    // 1.9e-14 (rounding): 1e-13.
    checks.push(Check::abs(
        NAME,
        "disk: max|θ̇ − closed form| over 10 s [rad/s]",
        err,
        0.0,
        1e-12,
    ));
    checks.push(Check::abs(
        NAME,
        "disk: |q(10 s), Gibbs-Appell − multipliers|∞",
        dq,
        0.0,
        1e-13,
    ));
    Ok(())
}

/// Runs the Gibbs-Appell checks: Euler's equations and the rolling disk.
pub fn run(_opts: &Options) -> Result<Report, BoxError> {
    let mut checks = Vec::new();
    euler(&mut checks)?;
    disk(&mut checks)?;
    Ok(Report {
        checks,
        ..Default::default()
    })
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
