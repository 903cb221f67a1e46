//! Routh's reduction: Kepler reduced to r against its closed-form Routhian and Kepler's laws; the
//! heavy top reduced to θ against the full model (turning points, precession per nutation).

use noether_canonical::{Error, Routh};
use noether_core::prelude::*;
use noether_testkit::top::{top_samples, KeplerPolar, GALLERY_TOP};
use std::f64::consts::PI;

#[test]
fn closed_form_kepler_reduced_to_r() {
    let (mu, l) = (1.0, 0.8);
    let routh = Routh::new(KeplerPolar { mu }, &[1], &[l]).unwrap();
    // φ is cyclic (checked by AD at sample points), r is not.
    let points: Vec<_> = (0..5)
        .map(|i| (0.0, vec![0.5 + 0.3 * i as f64, 0.7 * i as f64], vec![0.1, 0.4]))
        .collect();
    assert_eq!(routh.check_cyclic(&points, 0.0).unwrap(), 0.0);
    let wrong = Routh::new(KeplerPolar { mu }, &[0], &[l]).unwrap();
    assert!(matches!(
        wrong.check_cyclic(&points, 1e-12),
        Err(Error::NotCyclic { index: 0, .. })
    ));
    // L_R = ṙ²/2 − ℓ²/(2r²) + μ/r and r̈ = ℓ²/r³ − μ/r² (the centrifugal term), at sample points.
    let el = EulerLagrange::new(&routh);
    let mut worst: f64 = 0.0;
    for (r, dr) in [(0.4, 0.3), (1.0, -0.2), (2.5, 0.05)] {
        let lr = routh.lagrangian(0.0, &[r], &[dr]);
        worst = worst.max((lr - (dr * dr / 2.0 - l * l / (2.0 * r * r) + mu / r)).abs());
        let mut a = [0.0];
        el.accelerations(0.0, &[r], &[dr], &mut a).unwrap();
        let exact = l * l / (r * r * r) - mu / (r * r);
        worst = worst.max(((a[0] - exact) / exact).abs());
    }
    eprintln!("kepler routhian: {worst:e}");
    // Measured 1.2e-15: the real solve is exact to rounding, the Hessian exact by one chord step.
    assert!(worst < 2e-15, "{worst:e}");

    // The reduced run: pericentre passages (ṙ = 0 rising through the minimum of r) one radial period
    // 2π sqrt(a³/μ) apart, and φ reconstructed by quadrature advances by exactly 2π per period (the
    // orbit closes).
    let r0 = 0.5;
    let dphi0 = l / (r0 * r0);
    let e = 0.5 * r0 * r0 * dphi0 * dphi0 - mu / r0;
    let a = -mu / (2.0 * e);
    let period = 2.0 * PI * (a * a * a / mu).sqrt();
    let dop = Dop853::new(EulerLagrange::new(&routh))
        .tolerances(1e-14, 1e-14)
        .unwrap();
    let sol = Driver::new(dop, State::new(0.0, [r0], [0.0]))
        .unwrap()
        .keep_dense_output(true)
        .event(Event::new("pericentre", |s: &State| s.v[0]).rising())
        .run_until(3.2 * period)
        .unwrap();
    let peri = sol.event_times("pericentre").unwrap();
    assert_eq!(peri.len(), 3);
    let err_t = peri
        .iter()
        .enumerate()
        .map(|(k, t)| (t - (k + 1) as f64 * period).abs() / period)
        .fold(0.0, f64::max);
    let phi = routh.reconstruct(&sol, &[0.0], &peri).unwrap();
    let err_phi = phi
        .iter()
        .enumerate()
        .map(|(k, p)| (p[0] - 2.0 * PI * (k + 1) as f64).abs())
        .fold(0.0, f64::max);
    eprintln!("kepler reduced run: period {err_t:e}, φ per period {err_phi:e}");
    // Measured 9.3e-15 (relative) and 1.2e-13 rad after three periods: DOP853's global error at
    // 1e-14 and the events located on its dense output; the quadrature (8 Gauss nodes a step) adds
    // nothing visible.
    assert!(err_t < 5e-14, "{err_t:e}");
    assert!(err_phi < 5e-13, "{err_phi:e}");
}

#[test]
fn regress_heavy_top_reduced_to_theta_matches_the_full_model() {
    let top = GALLERY_TOP;
    let (th0, dphi0, dpsi0) = (0.8, 0.5, 5.0);
    let full = EulerLagrange::new(top);
    let mut p = [0.0; 3];
    full.momenta(0.0, &[th0, 0.0, 0.0], &[0.0, dphi0, dpsi0], &mut p)
        .unwrap();
    let (p_phi, p_psi) = (p[1], p[2]);
    let routh = Routh::new(top, &[1, 2], &[p_phi, p_psi]).unwrap();
    let samples = top_samples();
    assert_eq!(routh.check_cyclic(&samples, 0.0).unwrap(), 0.0);
    // The turning points from the closed form: the roots of the cubic in u = cos θ,
    // f(u) = (1 − u²)(2E′ − 2Mgℓu)/I₁ − ((p_φ − p_ψ u)/I₁)², E′ = E − p_ψ²/(2I₃).
    let energy = full.energy(0.0, &[th0, 0.0, 0.0], &[0.0, dphi0, dpsi0]).unwrap();
    let e1 = energy - p_psi * p_psi / (2.0 * top.i3);
    let f = |u: f64| {
        (1.0 - u * u) * (2.0 * e1 - 2.0 * top.mgl * u) / top.i1 - ((p_phi - p_psi * u) / top.i1).powi(2)
    };
    let u0 = th0.cos();
    // θ₀ is one root (θ̇₀ = 0); the other lies on the side where f > 0 next to it.
    let (a, b) = if f(u0 - 1e-7) > 0.0 {
        (-1.0 + 1e-9, u0 - 1e-7)
    } else {
        (u0 + 1e-7, 1.0 - 1e-9)
    };
    assert!(f(a) * f(b) < 0.0);
    let u1 = noether_core::roots::bracketed_root(f, (a, f(a)), (b, f(b))).unwrap();
    let theta_other = u1.acos();

    // The full model and the reduced one, both DOP853 at 1e-14, turning points θ̇ = 0 as events.
    let t_end = 12.0;
    let dop = Dop853::new(EulerLagrange::new(top))
        .tolerances(1e-14, 1e-14)
        .unwrap();
    let sol_full = Driver::new(dop, State::new(0.0, [th0, 0.0, 0.0], [0.0, dphi0, dpsi0]))
        .unwrap()
        .save(Save::End)
        .unwrap()
        .event(Event::new("θ̇ = 0", |s: &State| s.v[0]))
        .run_until(t_end)
        .unwrap();
    let dop = Dop853::new(EulerLagrange::new(&routh))
        .tolerances(1e-14, 1e-14)
        .unwrap();
    let sol_red = Driver::new(dop, State::new(0.0, [th0], [0.0]))
        .unwrap()
        .keep_dense_output(true)
        .event(Event::new("θ̇ = 0", |s: &State| s.v[0]))
        .run_until(t_end)
        .unwrap();
    let ev_full = sol_full.events();
    let ev_red = sol_red.events();
    assert_eq!(ev_full.len(), ev_red.len());
    assert!(ev_full.len() >= 6, "{}", ev_full.len());
    let times: Vec<f64> = ev_red.iter().map(|e| e.t).collect();
    let phi = routh.reconstruct(&sol_red, &[0.0, 0.0], &times).unwrap();
    let (mut d_t, mut d_theta, mut d_closed, mut d_phi): (f64, f64, f64, f64) = (0.0, 0.0, 0.0, 0.0);
    for (k, (ef, er)) in ev_full.iter().zip(ev_red).enumerate() {
        d_t = d_t.max((ef.t - er.t).abs());
        d_theta = d_theta.max((ef.state.q[0] - er.state.q[0]).abs());
        // Alternate turning points, the other root first (the run starts at θ₀).
        let closed = if k % 2 == 0 { theta_other } else { th0 };
        d_closed = d_closed.max((er.state.q[0] - closed).abs());
        d_phi = d_phi
            .max((ef.state.q[1] - phi[k][0]).abs())
            .max((ef.state.q[2] - phi[k][1]).abs());
    }
    eprintln!(
        "heavy top: {} turning points; times {d_t:e}, θ {d_theta:e}, θ vs cubic {d_closed:e}, φ and ψ {d_phi:e}",
        ev_full.len()
    );
    // Measured: turning times 8.3e-14 apart, θ there 1.8e-14, θ against the cubic's roots 4.1e-14
    // (a turning point is an extremum: its θ is insensitive to its time), φ and ψ 4.3e-13 (ψ has turned
    // through 60 rad: 7e-15 relative). Both runs carry DOP853's global error at 1e-14 over ~7
    // half-nutations; the tolerances are 4-5 times the measured values.
    assert!(d_t < 4e-13 && d_theta < 1e-13, "{d_t:e} {d_theta:e}");
    assert!(d_closed < 2e-13, "{d_closed:e}");
    assert!(d_phi < 2e-12, "{d_phi:e}");
}

/// A planar particle with a velocity-dependent inertia in φ, L = ṙ²/2 + r² (cosh φ̇ − 1) + 1/r: φ is
/// cyclic, p_φ = r² sinh φ̇, so Newton for φ̇ = asinh(β/r²) takes several iterations (not one, as for
/// a quadratic L), and where it starts shows in its last iterate.
#[derive(Clone, Copy)]
struct StiffPlanar;
impl Lagrangian for StiffPlanar {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * v[0] * 0.5 + q[0] * q[0] * (v[1].cosh() - 1.0) + q[0].recip()
    }
}

/// Issue 29 item 5: Routh's solve for the cyclic velocities was warm-started from the last solve
/// (shared, behind a `Mutex`), so L_R and its derivatives depended on what had been evaluated before
/// (and, in an ensemble sharing one `Routh`, on which thread ran what). Now every point gives the
/// same bits as a fresh `Routh`, after any history and on any thread.
#[test]
fn regress_routh_is_independent_of_call_history_and_threads() {
    let beta = 2.7;
    let points: Vec<(f64, f64)> = (0..200)
        .map(|i| (0.6 + 0.013 * i as f64, 0.3 * (0.37 * i as f64).sin()))
        .collect();
    let fresh = |&(r, dr): &(f64, f64)| {
        let routh = Routh::new(StiffPlanar, &[1], &[beta]).unwrap();
        let el = EulerLagrange::new(&routh);
        let mut a = [0.0];
        el.accelerations(0.0, &[r], &[dr], &mut a).unwrap();
        let u = routh.cyclic_velocities(0.0, &[r], &[dr]).unwrap()[0];
        [routh.lagrangian(0.0, &[r], &[dr]), a[0], u].map(f64::to_bits)
    };
    let expected: Vec<[u64; 3]> = points.iter().map(fresh).collect();
    // The solve converges to asinh(β/r²) (to Newton's tolerance).
    for (&(r, dr), e) in points.iter().zip(&expected) {
        let u = f64::from_bits(e[2]);
        assert!(
            (u - (beta / (r * r)).asinh()).abs() < 1e-12,
            "u = {u} at r = {r}, ṙ = {dr}"
        );
    }
    // One shared Routh: the points in order, in reverse, and interleaved on four threads.
    let shared = Routh::new(StiffPlanar, &[1], &[beta]).unwrap();
    let el = EulerLagrange::new(&shared);
    let eval = |&(r, dr): &(f64, f64)| {
        let mut a = [0.0];
        el.accelerations(0.0, &[r], &[dr], &mut a).unwrap();
        let u = shared.cyclic_velocities(0.0, &[r], &[dr]).unwrap()[0];
        [shared.lagrangian(0.0, &[r], &[dr]), a[0], u].map(f64::to_bits)
    };
    let forward: Vec<[u64; 3]> = points.iter().map(eval).collect();
    let mut backward: Vec<[u64; 3]> = points.iter().rev().map(eval).collect();
    backward.reverse();
    let differ = |got: &[[u64; 3]]| {
        (0..got.len())
            .filter(|&i| got[i] != expected[i])
            .collect::<Vec<_>>()
    };
    assert_eq!(
        differ(&forward),
        Vec::<usize>::new(),
        "points that differ after the previous point"
    );
    assert_eq!(
        differ(&backward),
        Vec::<usize>::new(),
        "points that differ after the next point"
    );
    let threaded: Vec<Vec<(usize, [u64; 3])>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..4)
            .map(|k| {
                let (points, eval) = (&points, &eval);
                s.spawn(move || {
                    (k..points.len())
                        .step_by(4)
                        .map(|i| (i, eval(&points[i])))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for (i, bits) in threaded.into_iter().flatten() {
        assert_eq!(bits, expected[i], "point {i} on a thread");
    }
}

/// Kepler (μ = 1) with the generalized force Q_r = −c ṙ + κ φ̇ on r only (a radial drag and a push
/// proportional to the angular rate; no force on φ, so p_φ = ℓ is still conserved). The reduced model
/// carries Q_r with φ̇ = ℓ/r² solved from ℓ: r̈ = ℓ²/r³ − μ/r² − c ṙ + κ ℓ/r², and the force's
/// derivative ∂Q_R/∂r = −2κℓ/r³ comes through φ̇(r): it needs q̇_c exact to first order (the chord step
/// the force takes and L_R does not), checked on the force at a dual r. A force on φ is caught by
/// `check_cyclic`.
#[test]
fn closed_form_forced_kepler_reduced_to_r() {
    struct Forced {
        c: f64,
        kappa: f64,
        on_phi: f64,
    }
    impl Lagrangian for Forced {
        fn dof(&self) -> usize {
            2
        }
        fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
            KeplerPolar { mu: 1.0 }.lagrangian(t, q, v)
        }
        fn has_generalized_force(&self) -> bool {
            true
        }
        fn generalized_force<D: Scalar>(&self, _t: D, _q: &[D], v: &[D], out: &mut [D]) {
            out[0] = v[0] * -self.c + v[1] * self.kappa;
            out[1] = v[0] * self.on_phi;
        }
    }
    let (l, c, kappa) = (0.8, 0.3, 0.2);
    let routh = Routh::new(
        Forced {
            c,
            kappa,
            on_phi: 0.0,
        },
        &[1],
        &[l],
    )
    .unwrap();
    let points = vec![(0.0, vec![0.7, 0.3], vec![0.2, 0.5])];
    assert_eq!(routh.check_cyclic(&points, 0.0).unwrap(), 0.0);
    let pushed = Routh::new(
        Forced {
            c,
            kappa,
            on_phi: 0.1,
        },
        &[1],
        &[l],
    )
    .unwrap();
    assert!(matches!(
        pushed.check_cyclic(&points, 1e-12),
        Err(Error::NotCyclic {
            index: 1,
            what: "Q",
            ..
        })
    ));
    let el = EulerLagrange::new(&routh);
    let mut worst: f64 = 0.0;
    for (r, dr) in [(0.4, 0.3), (1.0, -0.2), (2.5, 0.05)] {
        let mut a = [0.0];
        el.accelerations(0.0, &[r], &[dr], &mut a).unwrap();
        let exact = l * l / r.powi(3) - 1.0 / (r * r) - c * dr + kappa * l / (r * r);
        worst = worst.max(((a[0] - exact) / exact).abs());
        let mut force = [num_dual::Dual64::from(0.0)];
        let (rd, drd) = (num_dual::Dual64::new(r, 1.0), num_dual::Dual64::from(dr));
        routh.generalized_force(num_dual::Dual64::from(0.0), &[rd], &[drd], &mut force);
        let (q_r, dq_r) = (-c * dr + kappa * l / (r * r), -2.0 * kappa * l / r.powi(3));
        worst = worst.max(((force[0].re - q_r) / q_r).abs());
        worst = worst.max(((force[0].eps - dq_r) / dq_r).abs());
    }
    eprintln!("forced kepler routhian: {worst:e}");
    // Measured 3.8e-16: the real solve exact to rounding, one chord step for the force's derivative.
    assert!(worst < 2e-15, "{worst:e}");
}
