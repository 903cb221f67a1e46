//! RATTLE on the orthogonality constraints (matrix coordinates) against the closed form of the free
//! asymmetric top and against the LGVI: ω(t) by Jacobi's elliptic functions, |Π| and the spatial L,
//! RᵀR = I, and the observed order 2.

use nalgebra::{UnitQuaternion, Vector3};
use noether_core::{Momenta, State, Stepper};
use noether_rigid::rattle::{body_momentum, matrix_state, rattle, rotation, RigidRattle};
use noether_rigid::{Free, RigidBody};
use noether_testkit::closed_form::FreeTop;

/// Not free_body.rs's (1, 2, 3): that body is a lamina (I₃ = I₁ + I₂), too flat for matrix coordinates
/// (J_d singular, see `bad_input_flat_body`).
const I: [f64; 3] = [1.0, 2.0, 2.5];
/// Ω(0) = (1, 0, 1.2): L² = 10 > 2EI₂ = 9.2, the case the closed form of
/// `noether_testkit::closed_form::FreeTop` covers.
const OMEGA0: (f64, f64) = (1.0, 1.2);

fn start() -> (RigidRattle<Free>, State<Momenta>) {
    let body = RigidBody::free(I[0], I[1], I[2]).unwrap();
    let stepper = rattle(body).unwrap();
    // The closed form starts at the body-frame ω (1, 0, 0.8); the orientation does not enter it.
    let s = matrix_state(
        &stepper,
        0.0,
        &UnitQuaternion::from_euler_angles(0.4, -0.3, 1.2),
        &Vector3::new(OMEGA0.0, 0.0, OMEGA0.1),
    )
    .unwrap();
    (stepper, s)
}

/// Largest |Ω(t) − Ω_exact(t)| over n steps of size h, with the largest drift of |Π|, of the spatial
/// L = RΠ and of RᵀR − I.
fn run(h: f64, n: usize) -> [f64; 4] {
    let top = FreeTop::new(I, OMEGA0.0, OMEGA0.1).expect("L² > 2EI₂");
    let (mut stepper, mut s) = start();
    let (pi0, l0) = (
        body_momentum(&s).unwrap(),
        rotation(&s).unwrap() * body_momentum(&s).unwrap(),
    );
    let mut worst = [0.0_f64; 4];
    for _ in 0..n {
        stepper.step(&mut s, h).unwrap();
        let (r, pi) = (rotation(&s).unwrap(), body_momentum(&s).unwrap());
        let exact = top.omega(s.t);
        let w = [pi[0] / I[0], pi[1] / I[1], pi[2] / I[2]];
        worst[0] = worst[0].max((0..3).map(|i| (w[i] - exact[i]).abs()).fold(0.0, f64::max));
        worst[1] = worst[1].max((pi.norm() - pi0.norm()).abs());
        worst[2] = worst[2].max((r * pi - l0).amax());
        worst[3] = worst[3].max((r.transpose() * r - nalgebra::Matrix3::identity()).amax());
    }
    worst
}

/// ω(t) over one period at h = 1e-3: order 2 like the LGVI, measured 5.04e-6 (tolerance 6e-6). |Π|
/// and L = RΠ are kept to the Newton tolerance of the two solves per step, not to rounding: measured
/// drifts 4.2e-12 and 5.6e-12 over the period (tolerances 6e-12, 8e-12; the LGVI keeps |Π| to 1.8e-14).
/// RᵀR − I: 4.4e-16 (tolerance 1e-15).
#[test]
fn closed_form_rattle_free_asymmetric_top() {
    let top = FreeTop::new(I, OMEGA0.0, OMEGA0.1).expect("L² > 2EI₂");
    let n = (top.period() / 1e-3).round() as usize;
    let [omega, casimir, spatial, ortho] = run(1e-3, n);
    eprintln!("RATTLE free top: ω {omega:e}, |Π| {casimir:e}, L {spatial:e}, RᵀR − I {ortho:e}");
    assert!(omega < 6e-6, "{omega:e}");
    assert!(casimir < 6e-12, "{casimir:e}");
    assert!(spatial < 8e-12, "{spatial:e}");
    assert!(ortho < 1e-15, "{ortho:e}");
}

/// Observed order from ω at t = 2 against the closed form for h = 0.02, 0.01, 0.005: measured 2.00045
/// and 2.00011 (tolerance ±2e-3).
#[test]
fn order_rattle_free_top() {
    let errs: Vec<f64> = [0.02, 0.01, 0.005]
        .iter()
        .map(|&h| run(h, (2.0 / h).round() as usize)[0])
        .collect();
    for w in errs.windows(2) {
        let p = (w[0] / w[1]).log2();
        eprintln!("RATTLE order {p} ({errs:?})");
        assert!((p - 2.0).abs() < 2e-3, "{errs:?}");
    }
}

/// A lamina (I₃ = I₁ + I₂) has J_d = diag(2, 1, 0): a typed error, not a singular solve later.
#[test]
fn bad_input_flat_body() {
    let lamina = RigidBody::free(1.0, 2.0, 3.0).unwrap();
    let e = rattle(lamina).err().unwrap();
    assert!(
        matches!(e, noether_rigid::Error::FlatBody { smallest, .. } if smallest.abs() < 1e-15),
        "{e}"
    );
}
