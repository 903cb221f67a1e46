//! Property tests of the error contract (docs/error-contract.md) over noether-rigid's public API:
//! random inertias, potentials, states of any size and steps, drawn from numbers that break code
//! (0, −0, NaN, ±∞, subnormal, huge). Every call returns Ok with finite values or a typed error, never
//! panics, and a failed step leaves the state exactly as it was.

use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use noether_core::{Momenta, State, Stepper};
use noether_rigid::rattle::{body_momentum, matrix_state, rattle, rotation};
use noether_rigid::{Inertia, Lgvi, RigidBody, UniformGravity};
use proptest::prelude::*;

/// Mostly ordinary numbers, often the ones that break code.
fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -3.0..3.0f64,
        1 => prop_oneof![
            Just(0.0),
            Just(-0.0),
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(f64::NEG_INFINITY),
            Just(5e-324),
            Just(1e-310),
            Just(f64::MIN_POSITIVE),
            Just(1e-300),
            Just(1e20),
            Just(1e200),
            Just(1e300),
            Just(f64::MAX),
        ],
    ]
}

/// Positive moments, mostly ordinary, sometimes extreme.
fn moment() -> impl Strategy<Value = f64> {
    prop_oneof![4 => 0.2..3.0f64, 1 => number()]
}

fn vec_of(len: std::ops::Range<usize>) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(number(), len)
}

/// A state of 4 coordinates, near a unit quaternion most of the time, or of any size.
fn state() -> impl Strategy<Value = State<Momenta>> {
    prop_oneof![
        3 => (number(), number(), number(), vec_of(3..4), number()).prop_map(|(a, b, c, pi, t)| {
            let q = UnitQuaternion::from_euler_angles(a.clamp(-4.0, 4.0), b.clamp(-4.0, 4.0), c.clamp(-4.0, 4.0));
            let q = if q.coords.iter().all(|x| x.is_finite()) { q } else { UnitQuaternion::identity() };
            let q = q.quaternion();
            State::with_momenta(t, [q.w, q.i, q.j, q.k], [0.0, pi[0], pi[1], pi[2]])
        }),
        1 => (vec_of(0..7), vec_of(0..7), number()).prop_map(|(q, v, t)| State::with_momenta(t, q, v)),
    ]
}

fn step() -> impl Strategy<Value = f64> {
    prop_oneof![3 => 1e-3..0.5f64, 1 => number()]
}

/// Bit-for-bit equality of two states (NaN entries included).
fn same(a: &State<Momenta>, b: &State<Momenta>) -> bool {
    let bits = |s: &State<Momenta>| {
        std::iter::once(s.t)
            .chain(s.q.iter().copied())
            .chain(s.v.iter().copied())
            .map(f64::to_bits)
            .collect::<Vec<_>>()
    };
    a.q.len() == b.q.len() && a.v.len() == b.v.len() && bits(a) == bits(b)
}

/// Ok with finite contents, or any typed error.
fn finite_or_err<T>(r: &Result<T, noether_rigid::Error>, entries: impl Fn(&T) -> Vec<f64>) -> bool {
    match r {
        Ok(x) => entries(x).iter().all(|v| v.is_finite()),
        Err(_) => true,
    }
}

/// Checks every reader of a body at one state: never Ok(non-finite).
fn readers<V: noether_rigid::OrientationPotential>(body: &RigidBody<V>, s: &State<Momenta>) {
    let v3 = |x: &Vector3<f64>| x.as_slice().to_vec();
    assert!(finite_or_err(&body.energy(s), |e| vec![*e]));
    assert!(finite_or_err(&body.orientation(s), |q| q
        .coords
        .as_slice()
        .to_vec()));
    assert!(finite_or_err(&body.body_momentum(s), v3));
    assert!(finite_or_err(&body.body_angular_velocity(s), v3));
    assert!(finite_or_err(&body.spatial_angular_momentum(s), v3));
    let pi = Vector3::new(
        s.v.get(1).copied().unwrap_or(0.0),
        s.v.get(2).copied().unwrap_or(0.0),
        s.v.get(3).copied().unwrap_or(0.0),
    );
    assert!(finite_or_err(&body.kinetic_energy(&pi), |e| vec![*e]));
    assert!(finite_or_err(&body.angular_velocity(&pi), v3));
    let r = body
        .orientation(s)
        .map(|q| q.to_rotation_matrix().into_inner())
        .unwrap_or(Matrix3::from_element(pi[0]));
    assert!(finite_or_err(&body.torque(&r), v3));
    assert!(finite_or_err(&body.potential_energy(&r), |e| vec![*e]));
    assert!(finite_or_err(&body.euler_rates(&r, &pi), |(w, d)| [v3(w), v3(d)].concat()));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    /// Inertias: accepted only with a finite tensor, inverse and moments; never a panic.
    #[test]
    fn inertia_is_finite_or_refused(i in prop::array::uniform3(moment()), off in number()) {
        if let Ok(j) = Inertia::principal(i[0], i[1], i[2]) {
            prop_assert!(j.inverse().iter().chain(j.matrix().iter()).all(|x| x.is_finite()));
            prop_assert!(j.principal_moments().iter().all(|x| x.is_finite() && *x > 0.0));
        }
        let mut m = Matrix3::from_diagonal(&Vector3::from(i));
        m[(0, 1)] = off;
        m[(1, 0)] = off;
        if let Ok(j) = Inertia::tensor(m) {
            prop_assert!(j.inverse().iter().all(|x| x.is_finite()));
        }
    }

    /// A free body and a heavy top with random parameters: every reader at a random state is Ok and
    /// finite or a typed error; a step of the LGVI is Ok with a finite state or an error that leaves
    /// the state as it was.
    #[test]
    fn lgvi_and_readers_keep_the_contract(
        i in prop::array::uniform3(moment()),
        g in prop::array::uniform5(number()),
        s in state(),
        h in step(),
    ) {
        let Ok(inertia) = Inertia::principal(i[0], i[1], i[2]) else { return Ok(()) };
        let free = RigidBody::new(inertia, noether_rigid::Free).unwrap();
        readers(&free, &s);
        let mut lgvi = Lgvi::new(free).unwrap();
        let mut x = s.clone();
        match lgvi.step(&mut x, h) {
            Ok(_) => prop_assert!(x.is_finite()),
            Err(e) => {
                prop_assert!(!matches!(e, noether_core::Error::NewtonDiverged { residual, .. } if !residual.is_finite()), "{e:?}");
                prop_assert!(same(&x, &s));
            }
        }
        let gravity = UniformGravity { mass: g[0], g: g[1], center: Vector3::new(g[2], g[3], g[4]) };
        match RigidBody::new(inertia, gravity) {
            Ok(top) => {
                prop_assert!(UniformGravity::new(g[0], g[1], gravity.center).is_ok());
                readers(&top, &s);
                let mut lgvi = Lgvi::new(top).unwrap();
                let mut x = s.clone();
                match lgvi.step(&mut x, h) {
                    Ok(_) => prop_assert!(x.is_finite()),
                    Err(e) => {
                        prop_assert!(!matches!(e, noether_core::Error::NewtonDiverged { residual, .. } if !residual.is_finite()), "{e:?}");
                        prop_assert!(same(&x, &s));
                    }
                }
            }
            Err(_) => {
                // Refused at construction, and again by the integrators when the fields are set after.
                let mut top = RigidBody::new(inertia, UniformGravity::new(1.0, 1.0, Vector3::z()).unwrap()).unwrap();
                top.potential = gravity;
                prop_assert!(Lgvi::new(top).is_err());
                prop_assert!(rattle(top).is_err());
            }
        }
    }

    /// The matrix-coordinate readers on states of any size, and a RATTLE step from a state built by
    /// `matrix_state`: Ok and finite, or an error with the state unchanged.
    #[test]
    fn rattle_keeps_the_contract(
        q in vec_of(0..11),
        p in vec_of(0..11),
        w in prop::array::uniform3(number()),
        h in step(),
    ) {
        let s = State::with_momenta(0.0, q, p);
        prop_assert!(finite_or_err(&body_momentum(&s), |x| x.as_slice().to_vec()));
        prop_assert!(finite_or_err(&rotation(&s), |x| x.as_slice().to_vec()));
        let body = RigidBody::free(1.0, 2.0, 2.5).unwrap();
        let mut stepper = rattle(body).unwrap();
        let Ok(mut x) = matrix_state(&stepper, 0.0, &UnitQuaternion::identity(), &Vector3::from(w)) else {
            return Ok(());
        };
        let before = x.clone();
        match stepper.step(&mut x, h) {
            Ok(_) => prop_assert!(x.is_finite()),
            Err(_) => prop_assert!(same(&x, &before)),
        }
    }
}
