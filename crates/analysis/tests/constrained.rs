//! Linearisation with constraints in dependent coordinates (noether-constraints' `linearize`): the
//! rolling coin's steady turns (velocity constraints) against their closed-form stability, and the
//! Cartesian cart-pole (a holonomic constraint) against the textbook and the reduced Lagrangian.

use crate::control::{textbook_in_cartesian, CartesianCartPole, Rod};
use noether_analysis::linearize as linearize_free;
use noether_constraints::{linearize, HolonomicSet, NonholonomicSet, Reduced};
use noether_testkit::coin::Coin;
use noether_testkit::control::CartPole;

/// The relative difference |x − y| / |y|.
fn rel(x: f64, y: f64) -> f64 {
    (x - y).abs() / y.abs()
}

/// Steady turns of a uniform coin (a = 0.5, m = 1, g = 9.81) at several tilts and turning rates,
/// with the spin ω₃ of the closed form (`Coin::steady_spin`), linearised in x = (q, ψ̇, θ̇, φ̇) (the
/// contact point's velocities ẋ, ẏ dependent). Checks, each against the closed forms of
/// `noether_testkit::coin` (the classical reduced equations, Routh §244):
/// - the drift is (q̇, 0): the closed-form steady turn is one of noether's equations of motion (the
///   accelerations vanish to rounding, measured ≤ 1.5e-16 against the scale Ω² + ω₃², tolerance
///   1e-14; the velocities are q̇ exactly);
/// - the spectrum: the reduced equations give the characteristic polynomial λ⁶(λ² + ω²) (six zero
///   roots — the cyclic x, y, ψ, φ and the two neighbouring steady turns — and the tilt's
///   oscillation), so tr A = 0, tr A² = −2ω² and tr A⁴ = 2ω⁴ exactly: traces of powers, not
///   eigenvalues, because the zero root is defective and an eigen-solver smears it by ε^{1/k}.
///   A trace of a power is a sum of products of entries that cancel down to ω² (as small as 0.03
///   against ‖A‖²_F ≈ 70 here), so its rounding is relative to ‖A‖²_F (‖A‖⁴_F): measured ≤ 1.5e-17;
///   tolerance 8ε = 1.8e-15.
///
/// Turns with ω² > 0 and with ω² < 0 (a tilted coin turning slowly falls over) are both in the set.
#[test]
fn closed_form_rolling_coin_steady_turns() {
    let coin = Coin::uniform(0.5, 1.0, 9.81);
    let rolling = NonholonomicSet(coin.rolling());
    let mut signs = (0, 0);
    for (theta, omega) in [(0.3, 2.0), (-0.2, -3.0), (0.6, 5.0), (0.1, 0.7), (-0.4, 1.5)] {
        let spin = coin.steady_spin(theta, omega);
        let (q, v) = coin.steady_state(theta, omega, spin);
        let lin = linearize(&coin, &rolling, 0.0, &q, &v, &[], &[2, 3, 4]).unwrap();
        assert_eq!(lin.a.shape(), (8, 8));
        assert_eq!(lin.b.shape(), (8, 0));
        let scale = omega * omega + spin * spin;
        let still = lin.drift.rows(5, 3).amax() / scale;
        let speeds = (0..5).map(|k| (lin.drift[k] - v[k]).abs()).fold(0.0, f64::max);
        let w2 = coin.tilt_frequency_squared(theta, omega, spin);
        let a2 = &lin.a * &lin.a;
        let (t1, t2, t4) = (lin.a.trace(), a2.trace(), (&a2 * &a2).trace());
        // Errors on the scale of the sums the traces are: ‖A‖²_F and ‖A‖⁴_F.
        let f2 = lin.a.norm_squared();
        let (e2, e4) = ((t2 / 2.0 + w2).abs() / f2, (t4 / 2.0 - w2 * w2).abs() / (f2 * f2));
        println!(
            "coin θ {theta} Ω {omega}: ω₃ {spin:.4}, ω² {w2:.6}, accelerations {still:e}, tr A {t1:e}, tr A² {e2:e}, tr A⁴ {e4:e}"
        );
        assert!(still < 1e-14 && speeds < 1e-15, "{still:e} {speeds:e}");
        assert!(t1.abs() < 1e-13 * lin.a.amax(), "{t1:e}");
        assert!(
            e2 < 8.0 * f64::EPSILON && e4 < 8.0 * f64::EPSILON,
            "{e2:e} {e4:e}"
        );
        if w2 > 0.0 {
            signs.0 += 1;
        } else {
            signs.1 += 1;
        }
    }
    assert!(signs.0 > 0 && signs.1 > 0, "{signs:?}");
}

/// Upright rolling in a straight line (θ = Ω = 0) is stable above the spin
/// ω₃² = m g a A / (C (C + m a²)) = g/(3a) for the uniform disk (Routh §244; the module docs of
/// `noether_testkit::coin`): below it the tilt has the real rate √(−ω²) with
/// (A + m a²) A ω² = C (C + m a²) ω₃² − m g a A. At 1.1 and 0.9 times the threshold, the largest
/// eigenvalue of A (nalgebra's QR, backward stable; this root is simple and well separated from the
/// zero cluster) is ±iω or √(−ω²): measured ≤ 4e-15 relative to |ω|, tolerance 1e-13; and
/// tr A² = −2ω² changes sign across it (measured ≤ 8e-16 relative to ω², tolerance 1e-13).
#[test]
fn closed_form_upright_coin_threshold() {
    let coin = Coin::uniform(0.5, 1.0, 9.81);
    let rolling = NonholonomicSet(coin.rolling());
    let critical = (coin.g / (3.0 * coin.radius)).sqrt();
    for factor in [1.1, 0.9] {
        let spin = factor * critical;
        let (q, v) = coin.steady_state(0.0, 0.0, spin);
        let lin = linearize(&coin, &rolling, 0.0, &q, &v, &[], &[2, 3, 4]).unwrap();
        let w2 = coin.tilt_frequency_squared(0.0, 0.0, spin);
        let (a, c, ma2) = (coin.diametral, coin.axial, coin.mass * coin.radius * coin.radius);
        let by_hand = (c * (c + ma2) * spin * spin - coin.mass * coin.g * coin.radius * a) / ((a + ma2) * a);
        assert!(rel(w2, by_hand) < 1e-15, "the two closed forms: {w2} {by_hand}");
        let top = lin
            .a
            .complex_eigenvalues()
            .iter()
            .copied()
            .max_by(|x, y| x.norm().total_cmp(&y.norm()))
            .unwrap();
        let (re, im) = if w2 > 0.0 {
            (0.0, w2.sqrt())
        } else {
            ((-w2).sqrt(), 0.0)
        };
        let err = ((top.re.abs() - re).abs() + (top.im.abs() - im).abs()) / w2.abs().sqrt();
        let e2 = rel(-(&lin.a * &lin.a).trace() / 2.0, w2);
        println!(
            "upright coin at {factor} × threshold: ω² {w2:.6}, eigenvalue {top} ({err:e}), tr A² {e2:e}"
        );
        assert!(err < 1e-13 && e2 < 1e-13, "{err:e} {e2:e}");
        assert_eq!(w2 > 0.0, factor > 1.0);
    }
}

/// The Cartesian cart-pole (bob on a rod, a holonomic constraint) linearised in dependent
/// coordinates by implicit differentiation of the constrained equations, x = (x_c, x_b, ẋ_c, ẋ_b):
/// - upright at rest against the textbook (A, B) in (x, θ) mapped by x_b = x + l sin θ
///   (`textbook_in_cartesian`);
/// - leaning and moving (q̇ ≠ 0, u ≠ 0) against the reduced Lagrangian's linearisation
///   ([`Reduced`], a different route to the same (A, B): implicit function theorem in dual
///   arithmetic and third derivatives of L_r).
///
/// Both exact to rounding: measured ≤ 1.5e-15 relative; bound 64ε = 1.4e-14 for the saddle-point solves
/// and the products with the tangent basis on top of the jets' rounding.
#[test]
fn constrained_cart_pole_in_dependent_coordinates() {
    let cp = CartPole::default();
    let (model, rod) = (CartesianCartPole(cp), HolonomicSet(Rod(cp.l)));
    let lin = linearize(&model, &rod, 0.0, &[0.0, 0.0, cp.l], &[0.0; 3], &[0.0], &[0, 1]).unwrap();
    let (a_exact, b_exact) = textbook_in_cartesian(&cp);
    let ea = (&lin.a - &a_exact).amax() / a_exact.amax();
    let eb = (&lin.b - &b_exact).amax() / b_exact.amax();
    // Leaning and moving: the bob at angle θ from the top, the rod's length kept.
    let (x, th, xd, w, u) = (0.3_f64, 0.5_f64, -0.2, 1.2, 0.4);
    let q = [x, x + cp.l * th.sin(), cp.l * th.cos()];
    let v = [xd, xd + cp.l * th.cos() * w, -cp.l * th.sin() * w];
    let moving = linearize(&model, &rod, 0.0, &q, &v, &[u], &[0, 1]).unwrap();
    let reduced = Reduced::new(CartesianCartPole(cp), Rod(cp.l), &[0, 1], &[0.0, 0.0, cp.l]).unwrap();
    let other = linearize_free(&reduced, 0.0, &q[..2], &v[..2], &[u]).unwrap();
    let em = [
        (&moving.a - &other.a).amax() / other.a.amax(),
        (&moving.b - &other.b).amax() / other.b.amax(),
        (&moving.drift - &other.drift).amax() / other.drift.amax(),
    ];
    println!("cart-pole in dependent coordinates: upright A {ea:e}, B {eb:e}; moving (A, B, drift) {em:?}");
    let bound = 64.0 * f64::EPSILON;
    assert!(ea < bound && eb < bound, "{ea:e} {eb:e}");
    assert!(em.iter().all(|e| *e < bound), "{em:?}");
}

/// Bad requests are typed errors: a point off the constraints, independent coordinates whose
/// dependent block is singular (the contact velocities cannot be solved from ẋ and ψ̇), and a
/// repeated index.
#[test]
fn constrained_linearization_refuses_bad_requests() {
    let coin = Coin::uniform(0.5, 1.0, 9.81);
    let rolling = NonholonomicSet(coin.rolling());
    let (q, mut v) = coin.steady_state(0.3, 2.0, coin.steady_spin(0.3, 2.0));
    // ẋ, ẏ dependent needs a regular 2 × 2 block: choosing ẋ independent leaves (ẏ, one angle).
    let singular = linearize(&coin, &rolling, 0.0, &q, &v, &[], &[0, 1, 3]);
    assert!(
        matches!(
            singular,
            Err(noether_constraints::Error::Core(
                noether_core::Error::SingularMatrix { .. }
            ))
        ),
        "{singular:?}"
    );
    let repeated = linearize(&coin, &rolling, 0.0, &q, &v, &[], &[2, 2, 4]);
    assert!(matches!(
        repeated,
        Err(noether_constraints::Error::Core(
            noether_core::Error::InvalidParameter { .. }
        ))
    ));
    v[0] += 1e-3;
    let off = linearize(&coin, &rolling, 0.0, &q, &v, &[], &[2, 3, 4]);
    assert!(
        matches!(off, Err(noether_constraints::Error::ConstraintViolated { .. })),
        "{off:?}"
    );
}
