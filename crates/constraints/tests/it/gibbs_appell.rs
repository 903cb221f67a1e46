//! Quasi-velocities and the Gibbs-Appell equations: Euler's equations from particles and from the
//! rigid-body Gibbs function, Gauss' principle, the rolling disk against the multiplier form, the
//! sphere on a turntable, bad input.

use nalgebra::{Matrix3, Vector3};
use noether_constraints::prelude::*;

use noether_testkit::gibbs_appell::*;

const STATES: [([f64; 4], [f64; 3]); 3] = [
    ([1.0, 0.0, 0.0, 0.0], [0.5, -1.0, 3.0]),
    ([0.8, 0.3, -0.4, 0.2], [2.0, 0.7, -1.5]),
    ([0.1, -0.6, 0.5, 0.9], [-4.0, 2.5, 6.0]),
];

/// Euler's equations about the fixed point, I ω̇ + ω × Iω = N with N = Σ ρ_i × Rᵀ(−m_i g ẑ) (body
/// axes), come out of the Gibbs function of the particles, and the rigid-part Gibbs function
/// ½ M|c̈|² + ½ α·I_c α + α·(ω × I_c ω) gives the same ω̇. Measured: 2.8e-16 (particles) and 2.8e-16
/// (rigid part) relative to |ω̇|; 2e-15.
#[test]
fn closed_form_euler_equations_from_the_gibbs_function() -> Result<()> {
    let particles = GibbsAppellEquations::new(ParticleTop)?;
    let (mass, c, i_o, i_c) = inertia();
    let body = GibbsAppellEquations::new(BodyTop {
        mass,
        c: [c[0], c[1], c[2]],
        i_c,
    })?;
    let mut worst = (0.0_f64, 0.0_f64);
    for (q, w) in STATES {
        let q = unit(q);
        let euler = euler_rates(&i_o, &q, w).ok_or(Error::Core(noether_core::Error::InvalidParameter {
            name: "I",
            value: 0.0,
            reason: "singular",
        }))?;
        let (mut a, mut b) = ([0.0; 3], [0.0; 3]);
        particles.accelerations(0.0, &q, &w, &mut a)?;
        body.accelerations(0.0, &q, &w, &mut b)?;
        let scale = euler.norm();
        worst.0 = worst.0.max((Vector3::from(a) - euler).norm() / scale);
        worst.1 = worst.1.max((Vector3::from(b) - euler).norm() / scale);
    }
    println!("Euler: particles {:.1e}, rigid part {:.1e}", worst.0, worst.1);
    assert!(worst.0 < 2e-15 && worst.1 < 2e-15, "{worst:?}");
    Ok(())
}

/// Gauss' principle: u̇ minimizes S − Π·u̇, and S is quadratic in u̇ with Hessian A, so
/// S(u̇ + δ) − Π·δ − S(u̇) = ½ δᵀAδ exactly. Measured: 1.2e-16 relative; 1e-15.
#[test]
fn conserves_gauss_principle_of_least_constraint() -> Result<()> {
    let sys = GibbsAppellEquations::new(ParticleTop)?;
    let (q, u) = (unit([0.8, 0.3, -0.4, 0.2]), [2.0, 0.7, -1.5]);
    let mut ud = [0.0; 3];
    sys.accelerations(0.3, &q, &u, &mut ud)?;
    let (a, _) = sys.equations(0.3, &q, &u)?;
    let pi = sys.quasi_forces_at(0.3, &q, &u)?;
    let s0 = sys.gibbs(0.3, &q, &u, &ud)?;
    let mut worst = 0.0_f64;
    for delta in [[1.0, 0.0, 0.0], [0.3, -0.7, 0.2], [-2.0, 1.0, 5.0]] {
        let d = nalgebra::DVector::from_column_slice(&delta);
        let moved: Vec<f64> = ud.iter().zip(delta).map(|(x, y)| x + y).collect();
        let change = sys.gibbs(0.3, &q, &u, &moved)? - pi.dot(&d) - s0;
        let quad = 0.5 * d.dot(&(&a * &d));
        assert!(quad > 0.0);
        worst = worst.max((change - quad).abs() / quad.max(s0.abs()));
    }
    println!("Gauss: {worst:.1e}");
    assert!(worst < 1e-15, "{worst:e}");
    Ok(())
}

/// A torque-free asymmetric body (no gravity) run by RK4: energy ½ ω·Iω and |L| = |I ω| are
/// constants of Euler's equations. RK4 with h = 1e-3 over 10 s: measured drifts 1.5e-14 and 7.9e-15
/// (relative) with ω normalized by |q|²; 5e-14.
#[test]
fn conserves_energy_and_casimir_of_the_free_body() -> Result<()> {
    let (_, _, _, i_c) = inertia();
    let sys = GibbsAppellEquations::new(free_body())?;
    let w0 = [0.5, -1.0, 3.0];
    let start = sys.state(0.0, &unit([0.8, 0.3, -0.4, 0.2]), &w0)?;
    let l = |w: &[f64]| (i_c * Vector3::from_column_slice(&w[..3])).norm();
    let e = |w: &[f64]| {
        let w = Vector3::from_column_slice(&w[..3]);
        0.5 * w.dot(&(i_c * w))
    };
    let (e0, l0) = (e(&w0), l(&w0));
    let sol = Driver::with_step(Rk4::new(&sys), start, 1e-3)?
        .observe("dE", move |s: &State<QuasiVelocities>| {
            (e(s.v.as_slice()) - e0) / e0
        })
        .observe("dL", move |s: &State<QuasiVelocities>| {
            (l(s.v.as_slice()) - l0) / l0
        })
        .run_until(10.0)?;
    let max = |name| {
        sol.observed(name)
            .map(|v| v.iter().fold(0.0_f64, |m, x| m.max(x.abs())))
            .unwrap_or(f64::NAN)
    };
    let (de, dl) = (max("dE"), max("dL"));
    println!(
        "free body: dE {de:.1e}, d|L| {dl:.1e}, padding {}",
        sol.last().v[3]
    );
    assert!(de < 5e-14 && dl < 5e-14, "{de:e} {dl:e}");
    assert_eq!(sol.last().v[3], 0.0);
    Ok(())
}

/// Pointwise, the Gibbs-Appell u̇ = (θ̈, φ̈) and q̈ = W u̇ + Ẇ u equal the multiplier form's q̈
/// (Lagrange-d'Alembert, 4 accelerations and 2 multipliers) to rounding (measured 4.9e-16 relative:
/// 4e-15). Along a run (RK4, h = 1e-3, 10 s) both follow the closed form
/// θ̇(t) = θ̇₀ − 2 g' (sin φ − sin φ₀)/(3 R φ̇), φ = φ₀ + φ̇ t (θ̈ = −m g' R cos φ/(m R² + I)):
/// measured 4.1e-13 for both (RK4's truncation of the same ODE for θ̇); 1e-12. The two runs' q at the
/// end differ by 1.9e-14 (rounding): 1e-13.
#[test]
fn closed_form_rolling_disk_agrees_with_the_multiplier_form() -> Result<()> {
    let mut worst = 0.0_f64;
    for (q, u) in [
        ([0.1_f64, -0.4, 0.3, 0.9], [6.0_f64, 0.8]),
        ([1.0, 2.0, -2.0, 2.5], [-3.0, 1.7]),
        ([0.0, 0.0, 0.0, -1.2], [0.5, -4.0]),
    ] {
        let (qdd, from_ga) = disk_both_ways(&q, &u)?;
        let scale = qdd.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        for (a, b) in qdd.iter().zip(from_ga) {
            worst = worst.max((a - b).abs() / scale);
        }
    }
    println!("disk pointwise: {worst:.1e}");
    assert!(worst < 4e-15, "{worst:e}");

    let (th0, ph0, phd) = (6.0, 0.4, 0.8);
    let (ga_sol, m_sol) = disk_runs(th0, ph0, phd)?;
    let max = |v: noether_core::Result<Vec<f64>>| {
        v.map(|v| v.iter().fold(0.0_f64, |m, x| m.max(x.abs())))
            .unwrap_or(f64::NAN)
    };
    let (e_ga, e_m) = (max(ga_sol.observed("err")), max(m_sol.observed("err")));
    let dq = (&ga_sol.last().q - &m_sol.last().q).amax();
    println!("disk run: θ̇ error GA {e_ga:.1e}, multipliers {e_m:.1e}, |Δq| at the end {dq:.1e}");
    assert!(e_ga < 1e-12 && e_m < 1e-12, "{e_ga:e} {e_m:e}");
    assert!(dq < 1e-13, "{dq:e}");
    Ok(())
}

/// The turntable orbit. With friction F at the contact, m v̇ = F and I ω̇ = (−a ẑ) × F; differentiating
/// the no-slip condition v = Ω ẑ × r + a ω × ẑ gives v̇ = Ω ẑ × v − (m a²/I) v̇, so
/// v̇ = (2/7) Ω ẑ × v: the velocity turns at ν = 2Ω/7 and the centre runs on a circle,
/// r(t) = r₀ + [sin νt v₀ + (1 − cos νt) ẑ × v₀]/ν; ω_z stays constant. RK4 with h = 2e-3 over two
/// orbits (t = 2·2π/ν): measured 3.2e-13 m (5.7e-12 at h = 4e-3: RK4's h⁴); 1e-12. ω_z: measured
/// 4.4e-15; 2e-14. (Without the 1/|q|² in ω the drift of |q| under RK4, 1e-6 here, changes the
/// sphere's effective inertia and the error is 4e-5 m.)
#[test]
fn closed_form_sphere_on_a_turntable() -> Result<()> {
    let (a, big_omega) = (0.1, 2.0);
    let (r0, w0) = ([0.5, 0.2], [1.0, -3.0, 4.0]);
    let sol = turntable_run(a, big_omega, r0, w0, 2e-3)?;
    let max = |v: noether_core::Result<Vec<f64>>| {
        v.map(|v| v.iter().fold(0.0_f64, |m, x| m.max(x.abs())))
            .unwrap_or(f64::NAN)
    };
    let (err, dwz) = (max(sol.observed("err")), max(sol.observed("wz")));
    println!("turntable: position error {err:.1e} m, ω_z drift {dwz:.1e}");
    assert!(err < 1e-12, "{err:e}");
    assert!(dwz < 2e-14, "{dwz:e}");
    Ok(())
}

/// More quasi-velocities than coordinates, a negative mass, a non-symmetric inertia tensor, and a
/// state whose padding is not zero are typed errors.
#[test]
fn bad_input_is_an_error() -> Result<()> {
    struct TooMany;
    impl GibbsAppell for TooMany {
        fn dof(&self) -> usize {
            1
        }
        fn quasi(&self) -> usize {
            2
        }
        fn velocities<D: Scalar>(&self, _t: D, _q: &[D], u: &[D], qdot: &mut [D]) {
            qdot[0] = u[0] + u[1];
        }
    }
    assert!(matches!(
        GibbsAppellEquations::new(TooMany),
        Err(Error::Core(noether_core::Error::InvalidParameter { .. }))
    ));
    struct Skewed(f64, f64);
    impl GibbsAppell for Skewed {
        fn dof(&self) -> usize {
            1
        }
        fn quasi(&self) -> usize {
            1
        }
        fn velocities<D: Scalar>(&self, _t: D, _q: &[D], u: &[D], qdot: &mut [D]) {
            qdot[0] = u[0];
        }
        fn bodies(&self) -> usize {
            1
        }
        fn body(&self, _b: usize) -> RigidPart {
            let mut i = Matrix3::identity();
            i[(0, 1)] = self.1;
            RigidPart::new(self.0, i)
        }
    }
    for bad in [Skewed(-1.0, 0.0), Skewed(1.0, 0.5)] {
        assert!(matches!(
            GibbsAppellEquations::new(bad),
            Err(Error::Core(noether_core::Error::InvalidParameter { .. }))
        ));
    }
    let sys = GibbsAppellEquations::new(DiskGA)?;
    let mut start = sys.state(0.0, &[0.0; 4], &[1.0, 1.0])?;
    start.v[3] = 1e-9;
    let err = Driver::with_step(Rk4::new(&sys), start, 1e-3)?.run_until(0.1);
    match err.map_err(Error::from) {
        Err(Error::ConstraintViolated { residual, .. }) => assert_eq!(residual, 1e-9),
        other => panic!("expected ConstraintViolated, got {other:?}"),
    }
    Ok(())
}
