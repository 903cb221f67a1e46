//! Poisson brackets: fundamental brackets, the angular-momentum algebra, Kepler's constants of the
//! motion, Jacobi's identity, and the error contract.

use crate::common::{Kepler3, Rng};
use nalgebra::DMatrix;
use noether_canonical::poisson::{self, BracketOf};
use noether_canonical::{bracket, constant_of_motion, time_derivative, Error};
use noether_core::{Hamiltonian, Scalar};
use noether_testkit::canonical::{AngularMomentum, Coordinates, RungeLenz};
use proptest::prelude::*;

/// The symplectic matrix Ω of n degrees of freedom.
fn omega(n: usize) -> DMatrix<f64> {
    noether_canonical::transform::omega(n)
}

/// {qᵢ, pⱼ} = δᵢⱼ, {qᵢ, qⱼ} = {pᵢ, pⱼ} = 0: the bracket matrix of z = (q, p) is Ω. The Jacobians are
/// exact 0s and 1s and the sums have one nonzero term, so the result is Ω exactly (error 0).
#[test]
fn identity_fundamental_brackets() {
    let mut rng = Rng(7);
    for n in [1, 3, 13] {
        let (q, p) = (rng.vec(n, -2.0, 2.0), rng.vec(n, -2.0, 2.0));
        let b = bracket(&Coordinates(n), &Coordinates(n), 0.3, &q, &p).unwrap();
        assert_eq!(b, omega(n), "n = {n}");
    }
}

/// {L_x, L_y} = L_z and cyclic, at 200 random points of [−2, 2]⁶. Each entry is a sum of products
/// of the Jacobian entries (themselves exact: ±qᵢ, ±pᵢ, 0) that reproduces L_z's own two products:
/// measured worst error 0 (the same products in the same order); tolerance 1e-15 (one rounding of a
/// product of size |q||p| ≲ 12 would be ~1e-15).
#[test]
fn identity_angular_momentum_algebra() {
    let mut rng = Rng(11);
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let (q, p) = (rng.vec(3, -2.0, 2.0), rng.vec(3, -2.0, 2.0));
        let l = poisson::values(&AngularMomentum, 0.0, &q, &p).unwrap();
        let b = bracket(&AngularMomentum, &AngularMomentum, 0.0, &q, &p).unwrap();
        // {L_i, L_j} = ε_ijk L_k.
        let expected = DMatrix::from_row_slice(3, 3, &[0.0, l[2], -l[1], -l[2], 0.0, l[0], l[1], -l[0], 0.0]);
        worst = worst.max((b - expected).amax());
    }
    assert!(worst <= 1e-15, "worst {worst:e}");
}

/// Kepler: L and the Runge-Lenz vector A commute with H (closed form: both are conserved; Pauli's
/// so(4)). At 1000 random points (|q| ∈ [0.2, 3.5], |p| ≲ 3) the worst |{f, H}| is at the rounding of
/// the terms that cancel (scale = Σ|∂f/∂z · ż| at the worst point). Measured: A 3.6e-15 at scale
/// 12.4 (ratio 2.9e-16 = 1.3ε), L 4.4e-16 at scale 4.6 (ratio 9.7e-17), H 3.6e-15 at scale 83 (ratio
/// 4.3e-17); tolerance 4ε·scale.
#[test]
fn conserves_kepler_angular_momentum_and_runge_lenz() {
    let kepler = Kepler3 { m: 1.3, k: 2.1 };
    let mut rng = Rng(3);
    let samples: Vec<(f64, Vec<f64>, Vec<f64>)> = (0..1000)
        .map(|_| {
            let mut q = rng.vec(3, -2.0, 2.0);
            while q.iter().map(|x| x * x).sum::<f64>() < 0.04 {
                q = rng.vec(3, -2.0, 2.0);
            }
            (0.0, q, rng.vec(3, -1.7, 1.7))
        })
        .collect();
    for (name, c) in [
        (
            "L",
            constant_of_motion(&AngularMomentum, &kepler, samples.iter().cloned()).unwrap(),
        ),
        (
            "A",
            constant_of_motion(&RungeLenz(kepler), &kepler, samples.iter().cloned()).unwrap(),
        ),
    ] {
        assert!(c.worst <= 4.0 * f64::EPSILON * c.scale, "{name}: {c:?}");
        assert!(c.scale > 0.0);
    }
    // H itself: {H, H} = 0 exactly in exact arithmetic; the single-product cancellation is exact here.
    let c = constant_of_motion(&kepler, &kepler, samples.iter().cloned()).unwrap();
    assert!(c.worst <= 4.0 * f64::EPSILON * c.scale, "{c:?}");
}

/// A non-conserved quantity is reported with where: q₀ for Kepler has dq₀/dt = p₀/m, largest at the
/// sample with the largest |p₀| (closed form).
#[test]
fn closed_form_worst_violation_and_where() {
    struct Q0;
    impl Hamiltonian for Q0 {
        fn dof(&self) -> usize {
            3
        }
        fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], _p: &[D]) -> D {
            q[0]
        }
    }
    let kepler = Kepler3 { m: 2.0, k: 1.0 };
    let samples = [
        (0.0, [1.0, 0.0, 0.0], [0.5, 0.0, 0.0]),
        (0.0, [1.0, 1.0, 0.0], [-3.0, 1.0, 0.0]),
        (0.0, [0.0, 1.0, 0.0], [1.0, 2.0, 0.0]),
    ];
    let c = constant_of_motion(&Q0, &kepler, samples).unwrap();
    assert_eq!((c.sample, c.component), (1, 0));
    assert_eq!(c.worst, 1.5);
    assert_eq!(c.p, vec![-3.0, 1.0, 0.0]);
}

/// df/dt = {f, H} + ∂f/∂t for an explicitly time-dependent f = q cos ωt − (p/mω) sin ωt of the
/// oscillator (the initial position, a constant of the motion): {f, H} and ∂f/∂t are each of size
/// ~1 and cancel: measured worst 4.4e-16 over 100 points; tolerance 1e-15. And {f, H} alone equals
/// −∂f/∂t (closed form above): measured worst 8.9e-16; tolerance 2e-15.
#[test]
fn closed_form_time_dependent_constant() {
    struct Osc;
    impl Hamiltonian for Osc {
        fn dof(&self) -> usize {
            1
        }
        fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
            p[0] * p[0] * (0.5 / 2.0) + q[0] * q[0] * (0.5 * 2.0 * 9.0)
        }
    }
    /// q₀(t, q, p) with m = 2, ω = 3.
    struct InitialPosition;
    impl Hamiltonian for InitialPosition {
        fn dof(&self) -> usize {
            1
        }
        fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D]) -> D {
            let wt = t * 3.0;
            q[0] * wt.cos() - p[0] * wt.sin() * (1.0 / 6.0)
        }
    }
    let mut rng = Rng(5);
    for _ in 0..100 {
        let (t, q, p) = (
            rng.uniform(-3.0, 3.0),
            rng.vec(1, -1.0, 1.0),
            rng.vec(1, -3.0, 3.0),
        );
        let d = time_derivative(&InitialPosition, &Osc, t, &q, &p).unwrap();
        assert!(d[0].abs() <= 1e-15, "{d:?}");
        let b = poisson::bracket_with(&InitialPosition, &Osc, t, &q, &p).unwrap();
        // ∂f/∂t = −3 q sin 3t − (p/2) cos 3t.
        let ft = -3.0 * q[0] * (3.0 * t).sin() - 0.5 * p[0] * (3.0 * t).cos();
        assert!((b[0] + ft).abs() < 2e-15);
    }
}

/// A family of smooth functions of (q, p) on n = 2 with random coefficients: polynomial and
/// trigonometric terms coupling every variable.
#[derive(Debug, Clone, Copy)]
struct Random([f64; 6]);
impl Hamiltonian for Random {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D]) -> D {
        let c = self.0;
        (q[0] * p[1]).sin() * c[0]
            + q[1] * q[1] * p[0] * c[1]
            + (q[0] * c[2] + p[0]).cos() * p[1] * p[1]
            + (q[1] * p[1] * c[3]).exp() * c[4]
            + q[0] * q[1] * p[0] * p[1] * c[5]
            + t * q[0] * c[0]
    }
}

/// Jacobi's identity {f, {g, h}} + {g, {h, f}} + {h, {f, g}} = 0, with the inner brackets computed
/// exactly as phase functions ([`BracketOf`], nested duals). Measured worst |sum| / (sum of the three
/// terms' sizes) = 9.3e-16 (4.2ε) over 100 points; tolerance 8ε (relative to the terms).
fn jacobi_sum(f: Random, g: Random, h: Random, t: f64, q: &[f64], p: &[f64]) -> (f64, f64) {
    let a = bracket(&f, &BracketOf(&g, &h), t, q, p).unwrap()[(0, 0)];
    let b = bracket(&g, &BracketOf(&h, &f), t, q, p).unwrap()[(0, 0)];
    let c = bracket(&h, &BracketOf(&f, &g), t, q, p).unwrap()[(0, 0)];
    ((a + b + c).abs(), a.abs() + b.abs() + c.abs())
}

#[test]
fn identity_jacobi_on_random_functions() {
    let mut rng = Rng(23);
    let mut coeffs = || {
        let v = rng.vec(6, -1.0, 1.0);
        Random([v[0], v[1], v[2], v[3], v[4], v[5]])
    };
    let (f, g, h) = (coeffs(), coeffs(), coeffs());
    let mut rng = Rng(29);
    for _ in 0..100 {
        let (t, q, p) = (
            rng.uniform(-1.0, 1.0),
            rng.vec(2, -1.0, 1.0),
            rng.vec(2, -1.0, 1.0),
        );
        let (sum, size) = jacobi_sum(f, g, h, t, &q, &p);
        assert!(
            sum <= 8.0 * f64::EPSILON * size.max(1e-300),
            "{sum:e} of {size:e}"
        );
    }
}

/// The inner bracket as a phase function agrees with the f64 bracket (same numbers, other route).
#[test]
fn identity_bracket_of_as_function() {
    let (f, g) = (
        Random([0.3, -0.7, 1.1, 0.2, 0.5, -0.4]),
        Random([-0.6, 0.1, 0.9, -0.3, 0.8, 0.25]),
    );
    let (q, p) = ([0.4, -0.9], [0.7, 0.2]);
    let direct = bracket(&f, &g, 0.5, &q, &p).unwrap()[(0, 0)];
    let as_function = poisson::values(&BracketOf(&f, &g), 0.5, &q, &p).unwrap()[0];
    assert!((direct - as_function).abs() <= 2.0 * f64::EPSILON * direct.abs().max(1.0));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Antisymmetry {f, g} = −{g, f} (to rounding of the sums) and {f, f} = 0, Jacobi's identity, for
    /// random coefficients and points.
    #[test]
    fn property_antisymmetry_and_jacobi(
        cf in prop::array::uniform6(-1.0f64..1.0),
        cg in prop::array::uniform6(-1.0f64..1.0),
        ch in prop::array::uniform6(-1.0f64..1.0),
        z in prop::array::uniform5(-1.0f64..1.0),
    ) {
        let (f, g, h) = (Random(cf), Random(cg), Random(ch));
        let (t, q, p) = (z[0], [z[1], z[2]], [z[3], z[4]]);
        let fg = bracket(&f, &g, t, &q, &p).unwrap()[(0, 0)];
        let gf = bracket(&g, &f, t, &q, &p).unwrap()[(0, 0)];
        prop_assert!((fg + gf).abs() <= 4.0 * f64::EPSILON * fg.abs().max(1.0));
        prop_assert_eq!(bracket(&f, &f, t, &q, &p).unwrap()[(0, 0)], 0.0);
        let (sum, size) = jacobi_sum(f, g, h, t, &q, &p);
        prop_assert!(sum <= 8.0 * f64::EPSILON * size.max(1.0), "{:e} of {:e}", sum, size);
    }

    /// Error contract: a point that does not fit, or is not finite, is an error, never a panic or a
    /// NaN; so is a function that is not finite there.
    #[test]
    fn property_errors_not_panics(n in 0usize..5, bad in 0usize..4, x in -1.0f64..1.0) {
        let kepler = Kepler3 { m: 1.0, k: 1.0 };
        let mut q = vec![x; n];
        let mut p = vec![0.5; 3];
        if bad == 1 && n == 3 { q[1] = f64::NAN; }
        if bad == 2 { p[0] = f64::INFINITY; }
        if bad == 3 { q = vec![0.0; 3]; } // |q| = 0: H = −∞
        let r = bracket(&AngularMomentum, &kepler, 0.0, &q, &p);
        let fine = n == 3 && bad == 0;
        match r {
            Ok(b) => {
                prop_assert!(fine, "accepted a bad point");
                prop_assert!(b.iter().all(|v| v.is_finite()));
            }
            Err(e) => prop_assert!(!fine || x == 0.0, "{e}"),
        }
    }
}

/// Typed errors: the wrong dimension, non-finite input and output, mismatched spaces, no samples.
#[test]
fn errors_typed() {
    let kepler = Kepler3 { m: 1.0, k: 1.0 };
    let e = bracket(&AngularMomentum, &kepler, 0.0, &[1.0, 0.0], &[0.0, 1.0, 0.0]).unwrap_err();
    assert!(matches!(
        e,
        Error::Core(noether_core::Error::Dimension {
            what: "q",
            expected: 3,
            got: 2
        })
    ));
    let e = bracket(&AngularMomentum, &kepler, 0.0, &[1.0, f64::NAN, 0.0], &[0.0; 3]).unwrap_err();
    assert!(matches!(
        e,
        Error::Core(noether_core::Error::NonFinite { what: "q", index: 1 })
    ));
    let e = bracket(&AngularMomentum, &kepler, 0.0, &[0.0; 3], &[0.0, 1.0, 0.0]).unwrap_err();
    assert!(
        matches!(e, Error::Core(noether_core::Error::NonFiniteResult { .. })),
        "{e:?}"
    );
    let e = bracket(&AngularMomentum, &Coordinates(2), 0.0, &[0.0; 3], &[0.0; 3]).unwrap_err();
    assert_eq!(e, Error::PhaseSpaceMismatch { first: 3, second: 2 });
    let none: [(f64, [f64; 3], [f64; 3]); 0] = [];
    assert_eq!(
        constant_of_motion(&AngularMomentum, &kepler, none).unwrap_err(),
        Error::NoSamples
    );
}
