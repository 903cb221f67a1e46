//! Bad input is a typed error, and a failed step leaves the state as it was.

use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use noether_core::{Momenta, Newton, State, Stepper};
use noether_rigid::{Error, Inertia, Lgvi, RigidBody, UniformGravity};

#[test]
fn non_unit_quaternion_is_an_error_and_the_state_is_kept() {
    let body = RigidBody::free(1.0, 2.0, 3.0).unwrap();
    let mut lgvi = Lgvi::new(body).unwrap();
    let mut s: State<Momenta> = State::with_momenta(0.0, [1.0, 0.1, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]);
    let before = s.clone();
    let e = lgvi.step(&mut s, 1e-2).unwrap_err();
    match Error::from(e) {
        Error::NotUnitQuaternion { norm, .. } => assert!((norm - 1.01f64.sqrt()).abs() < 1e-15),
        other => panic!("{other:?}"),
    }
    assert_eq!(s, before);
    // Within the tolerance: accepted.
    let mut ok: State<Momenta> = State::with_momenta(0.0, [1.0 + 1e-12, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]);
    lgvi.step(&mut ok, 1e-2).unwrap();
}

#[test]
fn singular_or_indefinite_inertia_is_an_error() {
    assert!(matches!(
        Inertia::principal(1.0, 0.0, 1.0),
        Err(Error::InertiaNotPositive { .. })
    ));
    assert!(matches!(
        Inertia::principal(1.0, -2.0, 3.0),
        Err(Error::InertiaNotPositive { .. })
    ));
    let mut j = Matrix3::identity();
    j[(0, 1)] = 0.5;
    assert!(matches!(Inertia::tensor(j), Err(Error::AsymmetricInertia { .. })));
    // A full SPD tensor: its principal moments are the eigenvalues (here 1, 2, 4 rotated).
    let r = UnitQuaternion::from_euler_angles(0.3, 0.2, -0.4)
        .to_rotation_matrix()
        .into_inner();
    let full =
        Inertia::tensor(r * Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 4.0)) * r.transpose()).unwrap();
    let mut m: Vec<f64> = full.principal_moments().iter().copied().collect();
    m.sort_by(f64::total_cmp);
    assert!(
        (m[0] - 1.0).abs() < 1e-14 && (m[1] - 2.0).abs() < 1e-14 && (m[2] - 4.0).abs() < 1e-14,
        "{m:?}"
    );
}

#[test]
fn non_finite_input_is_an_error_and_the_state_is_kept() {
    let body = RigidBody::free(1.0, 2.0, 3.0).unwrap();
    let mut lgvi = Lgvi::new(body).unwrap();
    assert!(matches!(
        Inertia::principal(1.0, f64::NAN, 1.0),
        Err(Error::Core(noether_core::Error::NonFinite { .. }))
    ));
    let mut s: State<Momenta> =
        State::with_momenta(0.0, [1.0, 0.0, 0.0, 0.0], [0.0, f64::INFINITY, 0.0, 0.0]);
    let before = s.clone();
    assert!(matches!(
        lgvi.step(&mut s, 1e-2),
        Err(noether_core::Error::NonFinite { .. })
    ));
    assert_eq!(s.q, before.q);
    let mut good = body.state(0.0, &UnitQuaternion::identity(), &Vector3::new(1.0, 0.0, 0.0));
    let kept = good.clone();
    assert!(matches!(
        lgvi.step(&mut good, -1.0),
        Err(noether_core::Error::InvalidStep { .. })
    ));
    assert_eq!(good, kept);
}

/// A Newton that cannot converge (one iteration, a residual tolerance below rounding) fails the step
/// and leaves the state exactly as it was.
#[test]
fn failed_newton_leaves_the_state() {
    let body = RigidBody::free(1.0, 2.0, 3.0).unwrap();
    let newton = Newton::default()
        .max_iterations(1)
        .unwrap()
        .residual_tolerance(1e-300)
        .unwrap()
        .step_tolerance(1e-300)
        .unwrap();
    let mut lgvi = Lgvi::new(body).unwrap().newton(newton);
    let mut s = body.state(0.0, &UnitQuaternion::identity(), &Vector3::new(1.0, 0.5, 0.8));
    let before = s.clone();
    assert!(matches!(
        lgvi.step(&mut s, 0.1),
        Err(noether_core::Error::NewtonDiverged { .. })
    ));
    assert_eq!(s, before);
}

fn core_err<T: std::fmt::Debug>(r: Result<T, Error>) -> noether_core::Error {
    match r {
        Err(Error::Core(e)) => e,
        other => panic!("expected a core error, got {other:?}"),
    }
}

/// Issue 29, item 12: `Inertia::principal(1e-310, …)` was accepted with a NaN J⁻¹ (1/1e-310 = ∞, and
/// ∞·0 in the eigenvector product); now `InertiaOutOfRange`. A merely small but normal body keeps
/// working.
#[test]
fn regress_subnormal_inertia_refused() {
    let e = Inertia::principal(1e-310, 1e-310, 1e-310).unwrap_err();
    assert!(
        matches!(e, Error::InertiaOutOfRange { smallest, .. } if smallest == 1e-310),
        "{e:?}"
    );
    assert!(matches!(
        RigidBody::free(5e-324, 5e-324, 5e-324),
        Err(Error::InertiaOutOfRange { .. })
    ));
    // 1e-310 next to 1 is the pivot test's case (a rod without thickness).
    assert!(matches!(
        Inertia::principal(1e-310, 1.0, 1.0),
        Err(Error::InertiaNotPositive { .. })
    ));
    let tiny = Inertia::principal(1e-300, 2e-300, 3e-300).unwrap();
    assert!(tiny.inverse().iter().all(|x| x.is_finite()));
    assert!((tiny.inverse()[(0, 0)] / 1e300 - 1.0).abs() < 1e-15);
}

/// Issue 29, item 12: `RigidBody::energy` returned Ok(∞) for Π = 1e200 (and `kinetic_energy`,
/// `torque`, having no `Result`, returned ∞ or NaN silently); now `NonFiniteResult` at the state's t,
/// `NonFinite` for NaN input.
#[test]
fn regress_energy_non_finite_is_an_error() {
    let body = RigidBody::free(1.0, 2.0, 3.0).unwrap();
    let huge = body.state_from_momentum(2.5, &UnitQuaternion::identity(), &Vector3::new(1e200, 0.0, 0.0));
    let e = core_err(body.energy(&huge));
    assert!(
        matches!(e, noether_core::Error::NonFiniteResult { t, .. } if t == 2.5),
        "{e:?}"
    );
    let e = core_err(body.kinetic_energy(&Vector3::new(1e200, 0.0, 0.0)));
    assert!(matches!(e, noether_core::Error::NonFiniteResult { .. }), "{e:?}");
    let e = core_err(body.kinetic_energy(&Vector3::new(f64::NAN, 0.0, 0.0)));
    assert!(matches!(e, noether_core::Error::NonFinite { .. }), "{e:?}");
    let e = core_err(body.angular_velocity(&Vector3::new(f64::INFINITY, 0.0, 0.0)));
    assert!(matches!(e, noether_core::Error::NonFinite { .. }), "{e:?}");
    // Ordinary values: T = ½ (1²/1 + 2²/2 + 3²/3) = 3, exactly.
    assert_eq!(body.kinetic_energy(&Vector3::new(1.0, 2.0, 3.0)), Ok(3.0));

    let top = RigidBody::new(
        Inertia::principal(1.0, 1.0, 0.5).unwrap(),
        UniformGravity::new(1.0, 9.81, Vector3::new(0.0, 0.0, 1.0)).unwrap(),
    )
    .unwrap();
    let mut r = Matrix3::identity();
    r[(1, 2)] = f64::NAN;
    let e = core_err(top.torque(&r));
    assert!(matches!(e, noether_core::Error::NonFinite { .. }), "{e:?}");
    let e = core_err(top.potential_energy(&r));
    assert!(matches!(e, noether_core::Error::NonFinite { .. }), "{e:?}");
    let e = core_err(top.euler_rates(&r, &Vector3::zeros()));
    assert!(matches!(e, noether_core::Error::NonFinite { .. }), "{e:?}");
    // g changed to NaN after the body was built (its fields are public): energy and torque refuse.
    let mut bad = top;
    bad.potential.g = f64::NAN;
    let s = bad.state(1.0, &UnitQuaternion::identity(), &Vector3::new(0.0, 0.0, 1.0));
    let e = core_err(bad.energy(&s));
    assert!(
        matches!(e, noether_core::Error::NonFiniteResult { what: "potential energy", t, .. } if t == 1.0),
        "{e:?}"
    );
    let tilted = UnitQuaternion::from_euler_angles(0.3, 0.0, 0.0)
        .to_rotation_matrix()
        .into_inner();
    let e = core_err(bad.torque(&tilted));
    assert!(
        matches!(e, noether_core::Error::NonFiniteResult { what: "torque", .. }),
        "{e:?}"
    );
    // V = m g (R ρ)_z = 9.81 at R = I; the torque of the upright top is 0.
    assert_eq!(top.potential_energy(&Matrix3::identity()), Ok(9.81));
    assert_eq!(top.torque(&Matrix3::identity()), Ok(Vector3::zeros()));
}

/// Issue 29, item 13: the LGVI with g = NaN failed every step with
/// `NewtonDiverged { iterations: 0, residual: NaN }`; now the NaN is refused where the body is built
/// (`RigidBody::new`, `UniformGravity::new`) and again by `Lgvi::new` and `rattle` (the fields are
/// public). A body so light that the step's rotation overflows is `NonFiniteResult`, not a
/// divergence.
#[test]
fn regress_lgvi_non_finite_parameters_refused() {
    let inertia = Inertia::principal(0.9, 1.1, 0.4).unwrap();
    let nan_g = UniformGravity {
        mass: 1.0,
        g: f64::NAN,
        center: Vector3::new(0.0, 0.0, 1.0),
    };
    let non_finite = |r: Result<(), Error>| {
        assert!(
            matches!(r, Err(Error::Core(noether_core::Error::NonFinite { .. }))),
            "{r:?}"
        )
    };
    non_finite(RigidBody::new(inertia, nan_g).map(|_| ()));
    non_finite(UniformGravity::new(1.0, f64::NAN, Vector3::z()).map(|_| ()));
    non_finite(UniformGravity::new(f64::INFINITY, 1.0, Vector3::z()).map(|_| ()));
    non_finite(UniformGravity::new(1.0, 1.0, Vector3::new(0.0, f64::NAN, 1.0)).map(|_| ()));
    assert!(matches!(
        UniformGravity::new(1e200, 1e200, Vector3::z()),
        Err(Error::Core(noether_core::Error::InvalidParameter { .. }))
    ));
    let mut body = RigidBody::new(inertia, UniformGravity::new(1.0, 1.0, Vector3::z()).unwrap()).unwrap();
    body.potential.g = f64::NAN;
    non_finite(Lgvi::new(body).map(|_| ()));
    non_finite(noether_rigid::rattle::rattle(body).map(|_| ()));

    // J = 1e-300: Ω = J⁻¹Π = 1e300, the Cayley start (h/2) J⁻¹ a overflows in |f|².
    let light = RigidBody::free(1e-300, 2e-300, 3e-300).unwrap();
    let mut lgvi = Lgvi::new(light).unwrap();
    let mut s = light.state_from_momentum(0.5, &UnitQuaternion::identity(), &Vector3::new(1.0, 0.5, 0.8));
    let before = s.clone();
    let r = lgvi.step(&mut s, 1e-2);
    assert!(
        matches!(r, Err(noether_core::Error::NonFiniteResult { t, .. }) if t == 0.5),
        "{r:?}"
    );
    assert_eq!(s, before);
}

/// Issue 29, item 11: `rattle::body_momentum` and `rattle::rotation` indexed a state of the wrong size
/// (a panic in `Matrix3::from_row_slice`); now `Dimension`, and `NonFinite` for NaN entries.
#[test]
fn regress_rattle_readers_wrong_size() {
    use noether_rigid::rattle::{body_momentum, rotation};
    let short: State<Momenta> = State::with_momenta(0.0, [1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]);
    let dim = |e: Error| {
        assert!(
            matches!(e, Error::Core(noether_core::Error::Dimension { .. })),
            "{e:?}"
        )
    };
    dim(body_momentum(&short).unwrap_err());
    dim(rotation(&short).unwrap_err());
    let eye = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    let mixed: State<Momenta> = State::with_momenta(0.0, eye, [0.0; 4]);
    dim(body_momentum(&mixed).unwrap_err());
    let mut p = [0.0; 9];
    p[1] = f64::NAN;
    let nan: State<Momenta> = State::with_momenta(0.0, eye, p);
    assert!(matches!(
        body_momentum(&nan),
        Err(Error::Core(noether_core::Error::NonFinite { .. }))
    ));
    // R = I, P = Ṙ J_d with Ω̂ for Ω = e₃ and J_d = diag(½,½,½) (J = I): Π = J Ω = e₃.
    let mut p = [0.0; 9];
    p[1] = -0.5; // (R Ω̂ J_d)_01 = −Ω₃/2
    p[3] = 0.5;
    let ok: State<Momenta> = State::with_momenta(0.0, eye, p);
    assert_eq!(body_momentum(&ok).unwrap(), Vector3::new(0.0, 0.0, 1.0));
    assert_eq!(rotation(&ok).unwrap(), Matrix3::identity());
}

/// Found by the property tests (issue 29): `spatial_angular_momentum` returned Ok(∞) when rotating a
/// Π near the largest float overflowed; now `NonFiniteResult` at the state's t.
#[test]
fn regress_spatial_angular_momentum_overflow() {
    let body = RigidBody::free(1.0, 2.0, 3.0).unwrap();
    let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_4);
    let s = body.state_from_momentum(3.0, &q, &Vector3::new(f64::MAX, f64::MAX, 0.0));
    let e = core_err(body.spatial_angular_momentum(&s));
    assert!(
        matches!(e, noether_core::Error::NonFiniteResult { t, .. } if t == 3.0),
        "{e:?}"
    );
    let s = body.state_from_momentum(3.0, &q, &Vector3::new(1.0, 0.0, 0.0));
    let l = body.spatial_angular_momentum(&s).unwrap();
    assert!((l - Vector3::new(0.5f64.sqrt(), 0.5f64.sqrt(), 0.0)).amax() < 1e-15);
}
