//! Generating functions: the oscillator to action-angle variables (F1), polar coordinates (F3), the
//! rotating frame (F2), both directions by Newton, K = H + ∂F/∂t, and the motion in the new variables
//! stepped by core's integrators.

use crate::common::{Planar, Rng};
use noether_canonical::generating::{Generated, Transformed};
use noether_canonical::{transform, Error};
use noether_core::prelude::*;
use noether_testkit::canonical::{ActionAngle, Oscillator, Polar, PolarF3, Rotating, RotatingF2, RotatingK};
use std::f64::consts::PI;

/// The oscillator to action-angle variables with F1 = ½ m ω q² cot Q, at 200 random points with
/// Q ∈ (0.2, π − 0.2) ∪ (π + 0.2, 2π − 0.2) (F1 is degenerate at q = 0): forward by Newton against
/// Q = atan2(mωq, p), P = H/ω (measured worst 1.3e-15 relative; tolerance 3e-15); K = H + ∂F/∂t = ωP
/// exactly (F has no t; K is H at the rounded (q, p): measured worst |K − ωP|/(ωP) 1.3e-15, tolerance
/// 3e-15); back by Newton to (q, p) (measured 3.2e-15 relative, tolerance 6e-15); the generated map
/// symplectic (measured 2.2e-16, tolerance 1e-15) and K its Hamiltonian: J Ω∇H = Ω∇K (measured
/// 4.7e-15 relative to ω, tolerance 1e-14).
#[test]
fn closed_form_oscillator_action_angle() {
    let (m, w) = (1.7, 2.3);
    let (h, gen_) = (Oscillator { m, w }, Generated::new(ActionAngle { m, w }));
    let mut rng = Rng(53);
    let mut worst = [0.0f64; 5];
    for i in 0..200 {
        let big_q = rng.uniform(0.2, PI - 0.2) + if i % 2 == 0 { 0.0 } else { PI };
        let big_p = rng.uniform(0.1, 3.0);
        let q = [(2.0 * big_p / (m * w)).sqrt() * big_q.sin()];
        let p = [(2.0 * m * w * big_p).sqrt() * big_q.cos()];
        let (nq, np) = gen_.forward(0.0, (&q, &p), (&[big_q + 0.1], &[1.0])).unwrap();
        let expected_q = (m * w * q[0]).atan2(p[0]).rem_euclid(2.0 * PI);
        let e = h.hamiltonian(0.0, &q, &p);
        worst[0] = worst[0]
            .max((nq[0] - expected_q).abs() / expected_q)
            .max((np[0] - e / w).abs() / (e / w));
        let k = gen_.new_hamiltonian(&h, 0.0, (&q, &p), (&nq, &np)).unwrap();
        worst[1] = worst[1].max((k - w * np[0]).abs() / (w * np[0]));
        let (bq, bp) = gen_.backward(0.0, (&nq, &np), (&[q[0] * 0.9], &[0.0])).unwrap();
        let scale = q[0].abs().max(p[0].abs() / (m * w));
        worst[2] = worst[2]
            .max((bq[0] - q[0]).abs() / scale)
            .max((bp[0] - p[0]).abs() / (m * w * scale));
        worst[3] = worst[3].max(gen_.symplectic_defect(0.0, (&q, &p), (&nq, &np)).unwrap());
        worst[4] = worst[4].max(
            gen_.new_hamiltonian_defect(&h, 0.0, (&q, &p), (&nq, &np))
                .unwrap()
                / w,
        );
    }
    let tol = [3e-15, 3e-15, 6e-15, 1e-15, 1e-14];
    for k in 0..5 {
        assert!(worst[k] <= tol[k], "check {k}: {:e}", worst[k]);
    }
}

/// F1 is degenerate at q = 0 (∂²F/∂q∂Q = −mωq/sin²Q): a typed error, not a NaN.
#[test]
fn errors_degenerate_generator() {
    let gen_ = Generated::new(ActionAngle { m: 1.0, w: 1.0 });
    let e = gen_.forward(0.0, (&[0.0], &[1.0]), (&[1.0], &[1.0])).unwrap_err();
    assert!(
        matches!(e, Error::DegenerateGenerator { kind: "F1", .. }),
        "{e:?}"
    );
}

/// The motion in action-angle variables, stepped by DOP853 on [`Transformed`] (Newton inverts the
/// map at every stage): Q(t) = Q₀ + ωt, P = P₀ (closed form) over Q ∈ [0.3, π − 0.3] (the map is
/// degenerate at q = 0). The rates are (ω, 0) to rounding, so DOP853 (tolerances 1e-14) has no method
/// error to make; what remains is the rounding of the Newton-inverted rates accumulated over the run.
/// Measured |Q − Q₀ − ωt| 8.9e-16 (tolerance 4e-15), |P − P₀|/P₀ 2.2e-14 and |K − ωP₀|/ωP₀ 2.2e-14
/// (tolerance 5e-14).
#[test]
fn closed_form_action_angle_motion_by_dop853() {
    let (m, w) = (1.7, 2.3);
    let h = Oscillator { m, w };
    let p0 = 2.0f64;
    let gen_ = Generated::new(ActionAngle { m, w });
    let (nq, np) = gen_.forward(0.0, (&[0.8], &[p0]), (&[0.5], &[1.0])).unwrap();
    let system = Transformed::new(h, gen_, (&[0.8], &[p0])).unwrap();
    let t_end = (PI - 0.3 - nq[0]) / w;
    assert!(t_end > 0.3);
    let dop = Dop853::new(&system).tolerances(1e-14, 1e-14).unwrap();
    let sol = Driver::new(dop, State::with_momenta(0.0, nq.clone(), np.clone()))
        .unwrap()
        .run_until(t_end)
        .unwrap();
    let last = sol.last();
    let dq = (last.q[0] - nq[0] - w * t_end).abs();
    let dp = (last.p()[0] - np[0]).abs() / np[0];
    assert!(dq <= 4e-15 && dp <= 5e-14, "{dq:e} {dp:e}");
    // K along the run is ωP (the energy of the transformed system).
    let k = system
        .energy(last.t, last.q.as_slice(), last.p().as_slice())
        .unwrap();
    assert!((k - w * np[0]).abs() <= 5e-14 * k);
}

/// Polar coordinates from F3 = −(p_x r cos θ + p_y r sin θ): forward by Newton against the closed
/// form (r, θ, p_r, p_θ) (measured 4.6e-16 relative; tolerance 1e-15), the generated Jacobian (by the
/// implicit-function theorem) equal to the direct map's AD Jacobian (measured 1.6e-15 relative;
/// tolerance 4e-15), and K = H (F has no t) equal to the polar Hamiltonian p_r²/2m + p_θ²/2mr² + V(r)
/// (measured 1.9e-15 relative; tolerance 4e-15).
#[test]
fn closed_form_polar_from_f3() {
    let h = Planar {
        m: 1.3,
        w: 0.9,
        eps: 0.2,
    };
    let gen_ = Generated::new(PolarF3);
    let mut rng = Rng(59);
    let mut worst = [0.0f64; 3];
    for _ in 0..200 {
        let (r, th) = (rng.uniform(0.3, 2.8), rng.uniform(-3.0, 3.0));
        let q = [r * th.cos(), r * th.sin()];
        let p = rng.vec(2, -2.0, 2.0);
        let (nq, np) = gen_
            .forward(0.0, (&q, &p), (&[r * 1.1, th - 0.1], &[0.0, 0.0]))
            .unwrap();
        let (eq, ep) = transform::apply(&Polar, 0.0, &q, &p).unwrap();
        let scale = 1.0 + r + p[0].abs() + p[1].abs();
        for i in 0..2 {
            worst[0] = worst[0]
                .max((nq[i] - eq[i]).abs() / scale)
                .max((np[i] - ep[i]).abs() / scale);
        }
        let jd = gen_.derivatives(0.0, (&q, &p), (&nq, &np)).unwrap().jacobian;
        let ja = transform::jacobian(&Polar, 0.0, &q, &p).unwrap();
        worst[1] = worst[1].max((jd - &ja).amax() / ja.amax());
        let k = gen_.new_hamiltonian(&h, 0.0, (&q, &p), (&nq, &np)).unwrap();
        let (rr, pr, pt) = (nq[0], np[0], np[1]);
        let polar = pr * pr / (2.0 * h.m)
            + pt * pt / (2.0 * h.m * rr * rr)
            + 0.5 * h.m * h.w * h.w * rr * rr
            + h.eps * rr.powi(4);
        worst[2] = worst[2].max((k - polar).abs() / polar.abs().max(1.0));
    }
    let tol = [1e-15, 4e-15, 4e-15];
    for k in 0..3 {
        assert!(worst[k] <= tol[k], "check {k}: {:e}", worst[k]);
    }
}

/// The rotating frame from F2 = P·R(−ωt) q: K = H + ∂F/∂t = H − ω L_z (closed form) at random points
/// and times (measured 7.1e-16 relative; tolerance 2e-15), the generated map equal to the direct one
/// (measured 6.7e-16; tolerance 1.5e-15), and the motion: DOP853 on [`Transformed`] from the mapped
/// initial state, against DOP853 on H in the inertial frame mapped to the rotating one, and on
/// K = H − ωL_z as an ordinary Hamiltonian model (three routes; DOP853 tolerances 1e-14; measured max
/// difference 2.5e-14 at t = 10; tolerance 1e-13).
#[test]
fn closed_form_rotating_frame_from_f2() {
    let h = Planar {
        m: 1.1,
        w: 1.3,
        eps: 0.15,
    };
    let w = 0.6;
    let gen_ = Generated::new(RotatingF2 { w });
    let k_model = RotatingK { h, w };
    let mut rng = Rng(61);
    let mut worst = [0.0f64; 2];
    for _ in 0..200 {
        let t = rng.uniform(-5.0, 5.0);
        let (q, p) = (rng.vec(2, -1.5, 1.5), rng.vec(2, -1.5, 1.5));
        let (nq, np) = gen_.forward(t, (&q, &p), (&[0.0, 0.0], &[0.0, 0.0])).unwrap();
        let (eq, ep) = transform::apply(&Rotating { w }, t, &q, &p).unwrap();
        for i in 0..2 {
            worst[1] = worst[1].max((nq[i] - eq[i]).abs()).max((np[i] - ep[i]).abs());
        }
        let k = gen_.new_hamiltonian(&h, t, (&q, &p), (&nq, &np)).unwrap();
        let expected = k_model.hamiltonian(t, &nq, &np);
        worst[0] = worst[0].max((k - expected).abs() / expected.abs().max(1.0));
    }
    assert!(worst[0] <= 2e-15 && worst[1] <= 1.5e-15, "{worst:?}");

    // The motion three ways.
    let (q0, p0) = ([1.0, 0.2], [0.1, 0.9]);
    let t_end = 10.0;
    let tol = 1e-14;
    let inertial = Driver::new(
        Dop853::new(HamiltonEquations::new(h))
            .tolerances(tol, tol)
            .unwrap(),
        State::with_momenta(0.0, q0, p0),
    )
    .unwrap()
    .run_until(t_end)
    .unwrap();
    let (nq0, np0) = transform::apply(&Rotating { w }, 0.0, &q0, &p0).unwrap();
    let system = Transformed::new(h, gen_, (&q0, &p0)).unwrap();
    let in_k = Driver::new(
        Dop853::new(&system).tolerances(tol, tol).unwrap(),
        State::with_momenta(0.0, nq0.clone(), np0.clone()),
    )
    .unwrap()
    .run_until(t_end)
    .unwrap();
    let as_model = Driver::new(
        Dop853::new(HamiltonEquations::new(k_model))
            .tolerances(tol, tol)
            .unwrap(),
        State::with_momenta(0.0, nq0, np0),
    )
    .unwrap()
    .run_until(t_end)
    .unwrap();
    let (a, b, c) = (inertial.last(), in_k.last(), as_model.last());
    let (eq, ep) = transform::apply(&Rotating { w }, t_end, a.q.as_slice(), a.p().as_slice()).unwrap();
    let mut diff: f64 = 0.0;
    for i in 0..2 {
        diff = diff.max((b.q[i] - eq[i]).abs()).max((b.p()[i] - ep[i]).abs());
        diff = diff.max((c.q[i] - eq[i]).abs()).max((c.p()[i] - ep[i]).abs());
    }
    assert!(diff <= 1e-13, "{diff:e}");
}
