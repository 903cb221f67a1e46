//! The free rigid body stepped by the LGVI against its closed forms: the asymmetric top's ω(t) by
//! Jacobi's elliptic functions and its period from K(k), the symmetric body's precession of ω, the
//! Casimir |L|, the energy and the orthogonality of R over long runs, and the observed order.

use nalgebra::{UnitQuaternion, Vector3};
use noether_core::{Driver, Momenta, State, Stepper};
use noether_rigid::{Lgvi, RigidBody};
use noether_testkit::closed_form::FreeTop;

const I: [f64; 3] = [1.0, 2.0, 3.0];
/// Ω(0) = (1, 0, 0.8): L² = 6.76 > 2EI₂ = 5.84, k² = 0.24.
const OMEGA0: (f64, f64) = (1.0, 0.8);

fn free_start(body: &RigidBody<noether_rigid::Free>) -> State<Momenta> {
    body.state(
        0.0,
        &UnitQuaternion::from_euler_angles(0.4, -0.3, 1.2),
        &Vector3::new(OMEGA0.0, 0.0, OMEGA0.1),
    )
}

/// Largest |Ω(t) − Ω_exact(t)| over n steps of size h.
fn omega_error(h: f64, n: usize) -> f64 {
    let body = RigidBody::free(I[0], I[1], I[2]).unwrap();
    let top = FreeTop::new(I, OMEGA0.0, OMEGA0.1).expect("L² > 2EI₂");
    let mut lgvi = Lgvi::new(body).unwrap();
    let mut s = free_start(&body);
    let mut worst: f64 = 0.0;
    for _ in 0..n {
        lgvi.step(&mut s, h).unwrap();
        let w = body.body_angular_velocity(&s).unwrap();
        let exact = top.omega(s.t);
        worst = worst.max((0..3).map(|i| (w[i] - exact[i]).abs()).fold(0.0, f64::max));
    }
    worst
}

/// ω(t) of the free asymmetric top against Landau-Lifshitz (37.10) over one period T = 4K(k)/(dτ/dt)
/// (≈ 9.36), at h = 1e-3: the LGVI's global error is O(h²) (measured 2.46e-6; tolerance 3e-6).
#[test]
fn closed_form_free_asymmetric_top_omega() {
    let top = FreeTop::new(I, OMEGA0.0, OMEGA0.1).expect("L² > 2EI₂");
    let n = (top.period() / 1e-3).round() as usize;
    let err = omega_error(1e-3, n);
    eprintln!("free top: max |Ω − Ω_exact| over one period = {err:e}");
    assert!(err < 3e-6, "{err:e}");
}

/// The period: Ω₂ crosses zero upwards every T = 4K(k)/(dτ/dt) (K by the AGM). Measured as the time
/// between the first and the fifth upward crossing after t = 0 (events on the driver's cubic Hermite interpolant),
/// h = 1e-3: relative error O(h²) (measured 3.29e-7 relative; tolerance 4e-7).
#[test]
fn closed_form_free_asymmetric_top_period() {
    let body = RigidBody::free(I[0], I[1], I[2]).unwrap();
    let top = FreeTop::new(I, OMEGA0.0, OMEGA0.1).expect("L² > 2EI₂");
    let omega2 = move |s: &State<Momenta>| body.body_angular_velocity(s).map(|w| w[1]).unwrap_or(f64::NAN);
    let mut run = Driver::new(Lgvi::new(body).unwrap(), free_start(&body))
        .unwrap()
        .step_size(1e-3)
        .unwrap()
        .event(noether_core::Event::new("Ω₂ = 0 up", omega2).rising());
    let sol = run.run_until(5.5 * top.period()).unwrap();
    let times: Vec<f64> = sol.event_times("Ω₂ = 0 up").unwrap();
    assert!(times.len() >= 5, "{times:?}");
    let period = (times[4] - times[0]) / 4.0;
    let rel = (period - top.period()).abs() / top.period();
    eprintln!(
        "free top: period {period} vs 4K/rate {} (rel {rel:e})",
        top.period()
    );
    assert!(rel < 4e-7, "{rel:e}");
}

/// Torque-free precession of a symmetric body I₁ = I₂: the body-frame Ω⊥ turns about the symmetry axis
/// at Ω = (I₃ − I₁)/I₁ ω₃, Ω₁ + iΩ₂ = Ω⊥ e^{iΩt} (Euler's equations; the text's ch. 64), ω₃ constant.
/// After 10 time units at h = 1e-3 the angle of Ω⊥ is off by O(h²) (measured 1.13e-5 rad; tolerance
/// 1.3e-5), ω₃ and |Ω⊥| are kept to rounding (measured 9.4e-16; tolerance 2e-15).
#[test]
fn closed_form_symmetric_body_precession() {
    let (i1, i3, w3, wp) = (1.0, 1.6, 2.0, 0.5);
    let body = RigidBody::free(i1, i1, i3).unwrap();
    let rate = (i3 - i1) / i1 * w3;
    let mut lgvi = Lgvi::new(body).unwrap();
    let mut s = body.state(
        0.0,
        &UnitQuaternion::from_euler_angles(1.0, 0.2, -0.5),
        &Vector3::new(wp, 0.0, w3),
    );
    let (h, n) = (1e-3, 10_000);
    for _ in 0..n {
        lgvi.step(&mut s, h).unwrap();
    }
    let w = body.body_angular_velocity(&s).unwrap();
    let angle = w[1].atan2(w[0]);
    let exact =
        (rate * s.t + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI;
    let err = (angle - exact).abs();
    let drift = ((w[2] - w3).abs()).max((w.xy().norm() - wp).abs());
    eprintln!("precession: angle error {err:e}, ω₃/|Ω⊥| drift {drift:e}");
    assert!(err < 1.3e-5, "{err:e}");
    assert!(drift < 2e-15, "{drift:e}");
}

/// Over 10⁵ steps of h = 1e-2 (≈ 100 periods): |L| (the Casimir) to rounding (measured 1.5e-14
/// relative, a random walk of ~1e-16 per step; tolerance 3e-14); the spatial vector L (measured 9.9e-14;
/// tolerance 2e-13); RᵀR − I at rounding (measured 1.1e-15; tolerance 2e-15). The energy: bounded with
/// no drift, as a symplectic method's should be; for the free body the LGVI (the discrete
/// Moser-Veselov flow) in fact keeps it to rounding (measured 2.7e-14 relative, tolerance 5e-14). The
/// mean over the last tenth of the run against the first: measured 4.4e-15 with full Newton (1.4e-15
/// with the chord iterations `Lgvi` used before); rounding alone, a random walk of ≲ ε per step, allows
/// up to about ε√N = 7e-14 at N = 10⁵ (in practice far less), while a steady drift of 2e-19 per step
/// (2e-14 over the run: a non-symplectic method's, or an unconverged solve's) fails the tolerance 1e-14.
/// The chord iterations' drift was not steady: it shows over 10⁶ steps (docs/benchmarks.md "Long runs").
#[test]
fn conserves_casimir_energy_orthogonality_long_run() {
    let body = RigidBody::free(I[0], I[1], I[2]).unwrap();
    let mut lgvi = Lgvi::new(body).unwrap();
    let mut s = free_start(&body);
    let l0 = body.spatial_angular_momentum(&s).unwrap();
    let e0 = body.energy(&s).unwrap();
    let n = 100_000;
    let (mut casimir, mut energy, mut ortho, mut lvec): (f64, f64, f64, f64) = (0.0, 0.0, 0.0, 0.0);
    let (mut first, mut last) = (0.0, 0.0);
    for k in 0..n {
        lgvi.step(&mut s, 1e-2).unwrap();
        let l = body.spatial_angular_momentum(&s).unwrap();
        let e = body.energy(&s).unwrap();
        casimir = casimir.max((l.norm() - l0.norm()).abs() / l0.norm());
        lvec = lvec.max((l - l0).amax() / l0.norm());
        energy = energy.max((e - e0).abs() / e0);
        if k < n / 10 {
            first += e / (n / 10) as f64;
        }
        if k >= n - n / 10 {
            last += e / (n / 10) as f64;
        }
        let q = body.orientation(&s).unwrap();
        ortho = ortho.max(noether_rigid::rotation::orthogonality_defect(
            &q.to_rotation_matrix().into_inner(),
        ));
    }
    let mean_drift = (last - first).abs() / e0;
    eprintln!(
        "10⁵ steps: |L| {casimir:e}, L vector {lvec:e}, energy {energy:e} (mean drift {mean_drift:e}), RᵀR − I {ortho:e}"
    );
    assert!(casimir < 3e-14, "{casimir:e}");
    assert!(lvec < 2e-13, "{lvec:e}");
    assert!(energy < 5e-14, "{energy:e}");
    assert!(mean_drift < 1e-14, "{mean_drift:e}");
    assert!(ortho < 2e-15, "{ortho:e}");
}

/// Observed order of the LGVI on the free asymmetric top: errors of Ω at t = 2 against the closed form
/// for h = 0.02, 0.01, 0.005; log₂ of successive ratios is 2 (measured 2.00026, 2.00007; tolerance
/// ±1e-3).
#[test]
fn order_free_top() {
    let errs: Vec<f64> = [0.02, 0.01, 0.005]
        .iter()
        .map(|&h| omega_error(h, (2.0 / h).round() as usize))
        .collect();
    for w in errs.windows(2) {
        let p = (w[0] / w[1]).log2();
        eprintln!("free top order {p}");
        assert!((p - 2.0).abs() < 1e-3, "{errs:?}");
    }
}
