//! Bad input is a typed error, and a failed step leaves the state as it was.

use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use noether_core::{Momenta, Newton, State, Stepper};
use noether_rigid::{Error, Inertia, Lgvi, RigidBody};

#[test]
fn non_unit_quaternion_is_an_error_and_the_state_is_kept() {
    let body = RigidBody::free(1.0, 2.0, 3.0).unwrap();
    let mut lgvi = Lgvi::new(body);
    let mut s: State<Momenta> = State::new(0.0, [1.0, 0.1, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]);
    let before = s.clone();
    let e = lgvi.step(&mut s, 1e-2).unwrap_err();
    match Error::from(e) {
        Error::NotUnitQuaternion { norm, .. } => assert!((norm - 1.01f64.sqrt()).abs() < 1e-15),
        other => panic!("{other:?}"),
    }
    assert_eq!(s, before);
    // Within the tolerance: accepted.
    let mut ok: State<Momenta> = State::new(0.0, [1.0 + 1e-12, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]);
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
    let mut lgvi = Lgvi::new(body);
    assert!(matches!(
        Inertia::principal(1.0, f64::NAN, 1.0),
        Err(Error::Core(noether_core::Error::NonFinite { .. }))
    ));
    let mut s: State<Momenta> = State::new(0.0, [1.0, 0.0, 0.0, 0.0], [0.0, f64::INFINITY, 0.0, 0.0]);
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
        .tol_residual(1e-300)
        .unwrap()
        .tol_step(1e-300)
        .unwrap();
    let mut lgvi = Lgvi::new(body).newton(newton);
    let mut s = body.state(0.0, &UnitQuaternion::identity(), &Vector3::new(1.0, 0.5, 0.8));
    let before = s.clone();
    assert!(matches!(
        lgvi.step(&mut s, 0.1),
        Err(noether_core::Error::NewtonDiverged { .. })
    ));
    assert_eq!(s, before);
}
