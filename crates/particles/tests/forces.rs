//! The velocity-dependent forces against closed forms: the Lorentz force of uniform fields (the
//! cycloid of crossed E and B, and its derivative by dual numbers, which the Jacobian of the equations
//! of motion takes) and a dashpot between two particles.

use noether_core::Lagrangian;
use noether_particles::prelude::*;
use num_dual::Dual64;

/// Crossed fields E = E ŷ, B = B ẑ on a charge e of mass m from rest at the origin, with a velocity
/// w along B: with ω = eB/m the motion is the cycloid x = (E/B)(t − sin ωt/ω), y = (E/(Bω))(1 − cos ωt),
/// z = w t, drifting at E×B/B² (Jackson, *Classical Electrodynamics*, §12.3; from m ẍ = e ẏ B,
/// m ÿ = e(E − ẋB)). RK4 with h = 1e-3 to t = 5 (ω = 2): its global error ~ ωt (ωh)⁴/120 · |r| ≈ 1e-12
/// at most; measured 9.4e-14.
#[test]
fn closed_form_cycloid_in_crossed_fields() {
    let (m, e, ef, bf, w) = (1.5, 0.6, 0.8, 5.0, 0.3);
    let sys = System::new(vec![Particle::charged(m, e)])
        .unwrap()
        .with(ExternalForce::new(
            Lorentz {
                e: [0.0, ef, 0.0],
                b: [0.0, 0.0, bf],
            },
            [0],
        ))
        .unwrap();
    let (t, h) = (5.0, 1e-3);
    let s0 = sys.state(0.0, &[[0.0; 3]], &[[0.0, 0.0, w]]).unwrap();
    let s = sys.run(Method::Rk4, s0, h, (t / h) as usize).unwrap();
    let omega = e * bf / m;
    let drift = ef / bf;
    let exact = [
        drift * (t - (omega * t).sin() / omega),
        drift / omega * (1.0 - (omega * t).cos()),
        w * t,
    ];
    let err = (0..3).map(|i| (s.q[i] - exact[i]).abs()).fold(0.0, f64::max);
    println!("cycloid: |r − r_exact| = {err:e}");
    assert!(err < 3e-13, "{err:e}");
}

/// The Lorentz force differentiated by dual numbers through the system's generic generalized force
/// (what the Jacobian of Lagrange's equations takes): ∂F/∂v = e[·×B], i.e. rows (0, B_z, −B_y),
/// (−B_z, 0, B_x), (B_y, −B_x, 0), and ∂F/∂r = 0, to rounding (measured 0: products with 0 and 1).
#[test]
fn closed_form_lorentz_derivative() {
    let (m, e, b) = (1.5, 0.6, [0.3, -1.1, 2.0]);
    let sys = System::new(vec![Particle::charged(m, e)])
        .unwrap()
        .with(ExternalForce::new(
            Lorentz {
                e: [0.2, 0.0, 0.4],
                b,
            },
            [0],
        ))
        .unwrap();
    let (r, v) = ([0.1, 0.2, 0.3], [0.5, -0.7, 0.9]);
    let cross = [[0.0, b[2], -b[1]], [-b[2], 0.0, b[0]], [b[1], -b[0], 0.0]];
    let mut err: f64 = 0.0;
    for j in 0..6 {
        let seed = |x: &[f64; 3], at: usize| -> Vec<Dual64> {
            (0..3)
                .map(|i| Dual64::new(x[i], if i + at == j { 1.0 } else { 0.0 }))
                .collect()
        };
        let mut f = [Dual64::from(0.0); 3];
        sys.generalized_force(Dual64::from(0.0), &seed(&r, 0), &seed(&v, 3), &mut f);
        for i in 0..3 {
            let exact = if j < 3 { 0.0 } else { e * cross[i][j - 3] };
            err = err.max((f[i].eps - exact).abs());
        }
    }
    println!("Lorentz ∂F/∂(r, v): |error| = {err:e}");
    assert!(err < 4.0 * f64::EPSILON * e * 2.0, "{err:e}");
}

/// Two particles (m₁ = 1, m₂ = 3, reduced mass μ = 3/4) joined by a dashpot only, separating along x:
/// μ r̈ = −c ṙ for their distance r, so ṙ = ṙ₀ e^{−ct/μ} and r = r₀ + (μ ṙ₀/c)(1 − e^{−ct/μ}), while
/// the total momentum stays m₁v₁ + m₂v₂ (the pair of forces is equal and opposite). RK4 with
/// h = 1e-3 (c/μ = 0.8): its global error t (ch/μ)⁴/120 ≈ 1e-14 at most; measured 0 and 7e-17, and a
/// momentum change of 1.1e-15 (rounding of the 6000 updates of a momentum ≈ 1.6).
#[test]
fn closed_form_dashpot_pair() {
    let (m1, m2, c) = (1.0, 3.0, 0.6);
    let mu = m1 * m2 / (m1 + m2);
    let sys = System::new(vec![Particle::new(m1), Particle::new(m2)])
        .unwrap()
        .with(InternalForce::new(Dashpot { c }, [(0, 1)]))
        .unwrap();
    let (x0, v0) = ([0.0, 1.0], [-0.5, 0.7]);
    let (t, h) = (3.0, 1e-3);
    let s0 = sys.state_1d(0.0, &x0, &v0).unwrap();
    let s = sys.run(Method::Rk4, s0, h, (t / h) as usize).unwrap();
    let (r0, w0) = (x0[1] - x0[0], v0[1] - v0[0]);
    let decay = (-c * t / mu).exp();
    let r = r0 + mu * w0 / c * (1.0 - decay);
    let err_r = (s.q[3] - s.q[0] - r).abs();
    let err_w = (s.v[3] - s.v[0] - w0 * decay).abs();
    let momentum = m1 * s.v[0] + m2 * s.v[3] - (m1 * v0[0] + m2 * v0[1]);
    println!("dashpot: |r − r_exact| = {err_r:e}, |ṙ − ṙ_exact| = {err_w:e}, momentum change {momentum:e}");
    assert!(err_r < 1e-14 && err_w < 1e-14, "{err_r:e} {err_w:e}");
    assert!(momentum.abs() < 4e-15, "{momentum:e}");
}

/// Core's IAS15 with a velocity-dependent force (through `VelocityDependent`): a charge e of mass m
/// in a uniform B = B ẑ from the origin with velocity (u, 0, w) gyrates with ω = eB/m on a circle of
/// radius r = m u/(eB) about (0, −r) while drifting along B, period T = 2πm/(eB):
/// x = r sin ωt, y = r (cos ωt − 1), z = w t (from m v̇ = e v × B; Jackson, *Classical
/// Electrodynamics*, §12.2). Compared at T/8, 2T/8, … over 20 periods at the default ε = 1e-9 (one
/// block of 3 coordinates): IAS15 converges each step to machine precision, so the error is rounding,
/// walking over the N = 800 steps (40 per period), and the phase error it drives,
/// δx ~ r ω t ε_mach √N = 1.4e-13 at t = 20T. Measured max |r − r_exact| 2.1e-14, checked at 1e-13.
/// The speed holds to rounding (the magnetic force does no work): measured |Δ|v|| 2.2e-16, checked
/// at the random walk √N ε_mach |v| = 2.3e-15.
#[test]
fn closed_form_ias15_gyration_in_a_magnetic_field() {
    use noether_core::integrators::VelocityDependent;
    use noether_core::prelude::{Driver, Ias15, Save};
    let (m, e, bf, u, w) = (1.5, 0.6, 5.0, 0.7, 0.2);
    let sys = System::new(vec![Particle::charged(m, e)])
        .unwrap()
        .with(ExternalForce::new(
            Lorentz {
                e: [0.0; 3],
                b: [0.0, 0.0, bf],
            },
            [0],
        ))
        .unwrap();
    let (omega, radius) = (e * bf / m, m * u / (e * bf));
    let period = 2.0 * std::f64::consts::PI / omega;
    let s0 = sys.state(0.0, &[[0.0; 3]], &[[u, 0.0, w]]).unwrap();
    let ias = Ias15::new(VelocityDependent(&sys))
        .unwrap()
        .block_size(3)
        .unwrap();
    let mut d = Driver::new(ias, s0).unwrap().save(Save::End).unwrap();
    let (mut worst, mut worst_speed, mut steps) = (0.0_f64, 0.0_f64, 0);
    for k in 1..=160 {
        let t = k as f64 * period / 8.0;
        let sol = d.run_until(t).unwrap();
        steps += sol.stats().steps;
        let s = sol.last();
        let exact = [
            radius * (omega * t).sin(),
            radius * ((omega * t).cos() - 1.0),
            w * t,
        ];
        worst = (0..3).map(|i| (s.q[i] - exact[i]).abs()).fold(worst, f64::max);
        let speed = s.v.norm();
        worst_speed = worst_speed.max((speed - (u * u + w * w).sqrt()).abs());
    }
    println!(
        "IAS15 gyration, 20 periods: |r − r_exact| = {worst:.2e}, |Δ|v|| = {worst_speed:.1e}, {steps} steps"
    );
    assert!(
        worst < 1e-13 && worst_speed < 2.3e-15,
        "{worst:e} {worst_speed:e}"
    );
}
