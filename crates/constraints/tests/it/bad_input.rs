//! Bad input: clear errors, never a panic or a silent wrong answer.

use crate::models::*;
use noether_constraints::prelude::*;
use noether_core::Error as CoreError;

fn pendulum(copies: usize) -> Constrained<Masses, HolonomicSet<Rod>> {
    Constrained::holonomic(
        Masses {
            n: 1,
            d: 2,
            m: 1.0,
            g: 9.81,
        },
        Rod { d: 2, l: 1.0, copies },
    )
    .unwrap()
}

#[test]
fn bad_input_initial_state_violating_constraints_names_the_residual() {
    let sys = pendulum(1);
    let off = State::new(0.0, [0.0, -1.1], [0.0, 0.0]); // |r| = 1.1: φ = (1.21 − 1)/2 = 0.105
    let err = sys.check_state(&off, 1e-10).unwrap_err();
    match err {
        Error::ConstraintViolated { what, residual, .. } => {
            assert_eq!(what, "position");
            assert!((residual - 0.105).abs() < 1e-12);
        }
        e => panic!("unexpected {e}"),
    }
    let mut run = Driver::with_step(
        Projected::new(Rk4::new(&sys), sys.constraints()),
        off.clone(),
        1e-3,
    )
    .unwrap();
    // Through the driver (core's interface) the error travels as core's `Model` and comes back whole.
    let e = Error::from(run.next().unwrap().unwrap_err());
    assert!(matches!(e, Error::ConstraintViolated { .. }));
    assert!(e.to_string().contains("1.05"), "{e}");
    // A velocity with a radial component is a velocity violation.
    let radial = State::new(0.0, [0.0, -1.0], [0.0, 0.3]);
    assert!(matches!(
        sys.check_state(&radial, 1e-10),
        Err(Error::ConstraintViolated { what: "velocity", .. })
    ));
}

#[test]
fn bad_input_redundant_constraints_reported_with_rank() {
    let sys = pendulum(2); // the same rod twice
    let s = pendulum_state(1.0, 0.3, 0.0);
    let expect = |e: Error| match e {
        Error::RankDeficientConstraints { rank, count, .. } => assert_eq!((rank, count), (1, 2)),
        e => panic!("unexpected {e}"),
    };
    expect(sys.check_state(&s, 1e-10).unwrap_err());
    expect(sys.multipliers(0.0, s.q.as_slice(), s.v.as_slice()).unwrap_err());
    let mut run = Driver::with_step(Rk4::new(&sys), s.clone(), 1e-3).unwrap();
    expect(run.next().unwrap().unwrap_err().into());
    let mut s2 = s.clone();
    expect(project(sys.constraints(), &mut s2, &Projection::default()).unwrap_err());
    assert_eq!(s2, s, "a failed projection leaves the state unchanged");
}

#[test]
fn bad_input_dimensions_and_non_finite() {
    let e = Constrained::holonomic(
        Masses {
            n: 1,
            d: 3,
            m: 1.0,
            g: 1.0,
        },
        Rod {
            d: 2,
            l: 1.0,
            copies: 1,
        },
    )
    .err()
    .unwrap();
    assert!(matches!(
        e,
        Error::Core(CoreError::Dimension {
            expected: 3,
            got: 2,
            ..
        })
    ));
    let sys = pendulum(1);
    assert!(matches!(
        sys.multipliers(0.0, &[0.0, 1.0, 2.0], &[0.0, 0.0]),
        Err(Error::Core(CoreError::Dimension { .. }))
    ));
    assert!(matches!(
        sys.multipliers(0.0, &[f64::NAN, 1.0], &[0.0, 0.0]),
        Err(Error::Core(CoreError::NonFinite { .. }))
    ));
    let mut s = State::new(0.0, [f64::INFINITY, 1.0], [0.0, 0.0]);
    assert!(project(sys.constraints(), &mut s, &Projection::default()).is_err());
}

/// A projection that cannot converge (a point at the centre, where the rod's normal vanishes) reports
/// Newton's failure or the singular constraint, not a NaN state.
#[test]
fn bad_input_projection_from_a_singular_point() {
    let sys = pendulum(1);
    let mut s = State::new(0.0, [0.0, 0.0], [0.0, 0.0]);
    let e = project(sys.constraints(), &mut s, &Projection::default()).unwrap_err();
    assert!(
        matches!(
            e,
            Error::RankDeficientConstraints { rank: 0, .. } | Error::Core(CoreError::NewtonDiverged { .. })
        ),
        "{e}"
    );
    assert_eq!(s.q.as_slice(), &[0.0, 0.0]);
}

/// Issue 15, case 3: a constrained system stepped by a plain integrator (no projection) from a state
/// off its rod (|r| = 1.1, φ = (1.21 − 1)/2 = 0.105) used to run to the end with Ok and |r| = 1.1
/// throughout. Every step now checks the state it starts from: the first step fails, naming the
/// residual, and the state is unchanged.
#[test]
fn regress_plain_integrator_from_a_state_off_the_constraints() {
    let sys = pendulum(1);
    let off = State::new(0.0, [0.0, -1.1], [0.0, 0.0]);
    fn first_error<S: Stepper<Partner = Velocities>>(mut run: Driver<S>, start: &State) -> Error {
        let e = Error::from(run.run_until(1.0).unwrap_err());
        assert_eq!(run.state(), start, "the state is unchanged");
        e
    }
    for e in [
        first_error(
            Driver::with_step(Rk4::new(&sys), off.clone(), 1e-3).unwrap(),
            &off,
        ),
        first_error(Driver::new(Dopri5::new(&sys), off.clone()).unwrap(), &off),
    ] {
        match e {
            Error::ConstraintViolated { what, residual, .. } => {
                assert_eq!(what, "position");
                assert!((residual - 0.105).abs() < 1e-15, "{residual}");
            }
            e => panic!("unexpected {e}"),
        }
    }
    // The tolerance is the user's to set, and is validated when set.
    assert!(matches!(
        pendulum(1).violation_tolerance(f64::NAN),
        Err(Error::Core(CoreError::InvalidParameter { .. }))
    ));
    let loose = pendulum(1).violation_tolerance(0.2).unwrap();
    let mut run = Driver::with_step(Rk4::new(&loose), off, 1e-3).unwrap();
    assert!(run.run_until(0.01).is_ok());
}

/// Issue 15, case 9: `ConstraintForces::on_particle` with an index out of range was a panic.
#[test]
fn regress_constraint_force_indices() {
    let sys = pendulum(1);
    let f = sys.constraint_forces(0.0, &[0.0, -1.0], &[0.0, 0.0]).unwrap();
    // Hanging at rest the rod holds the weight: the force on the bob is (0, m g), g = 9.81.
    assert_eq!(f.on_particle(0, 2).unwrap(), &[0.0, 9.81]);
    for (i, dim) in [(1, 2), (0, 3), (0, 0), (usize::MAX, 2)] {
        assert!(
            matches!(
                f.on_particle(i, dim),
                Err(Error::Core(CoreError::InvalidParameter { .. }))
            ),
            "particle {i}, dim {dim}"
        );
    }
    assert!(f.of_constraint(1).is_err());
    assert!(f.of_constraint_on_particle(0, 1, 2).is_err());
}

/// A rod φ = (q₀² + q₁² − l²)/2 written as a user would: indexing q[0], q[1] and out[0] directly
/// (a short q or out panics inside this code if noether passes one through), and √q₀ so that it has a
/// domain (q₀ < 0 gives NaN).
struct IndexingRod;
impl Holonomic for IndexingRod {
    fn dof(&self) -> usize {
        2
    }
    fn count(&self) -> usize {
        1
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        out[0] = (q[0] * q[0] + q[1] * q[1] - 1.0) * 0.5 + q[0].sqrt() * 0.0;
    }
}

/// Issue 29, item 11: `holonomic::values` (and the other holonomic evaluations) passed an unchecked q
/// or output to the user's constraint function, which then panicked on `q[1]`; now `Dimension`
/// before the call, `NonFinite` for NaN input, `NonFiniteResult` outside the domain, and the output
/// untouched on error.
#[test]
fn regress_holonomic_values_unchecked_lengths() {
    use noether_constraints::holonomic::{acceleration_bias, partial_t, values, velocity_residual};
    let c = IndexingRod;
    let dim = |r: Result<()>| {
        assert!(
            matches!(r, Err(Error::Core(CoreError::Dimension { .. }))),
            "{r:?}"
        )
    };
    let mut out = [7.0];
    dim(values(&c, 0.0, &[0.6], &mut out));
    dim(values(&c, 0.0, &[0.6, 0.8, 0.0], &mut out));
    dim(values(&c, 0.0, &[0.6, 0.8], &mut []));
    dim(values(&c, 0.0, &[0.6, 0.8], &mut [0.0, 0.0]));
    dim(partial_t(&c, 0.0, &[0.6], &mut out));
    dim(velocity_residual(&c, 0.0, &[0.6, 0.8], &[1.0], &mut out));
    dim(velocity_residual(&c, 0.0, &[0.6], &[1.0, 0.0], &mut out));
    dim(acceleration_bias(
        &c,
        0.0,
        &[0.6, 0.8],
        &[1.0, 0.0, 0.0],
        &mut out,
    ));
    dim(acceleration_bias(&c, 0.0, &[0.6, 0.8], &[1.0, 0.0], &mut []));
    assert_eq!(out, [7.0]);
    let r = values(&c, 0.0, &[f64::NAN, 0.8], &mut out);
    assert!(
        matches!(r, Err(Error::Core(CoreError::NonFinite { .. }))),
        "{r:?}"
    );
    let r = values(&c, 0.0, &[-0.6, 0.8], &mut out);
    assert!(
        matches!(r, Err(Error::Core(CoreError::NonFiniteResult { .. }))),
        "{r:?}"
    );
    assert_eq!(out, [7.0], "nothing written on error");
    values(&c, 0.0, &[0.6, 0.8], &mut out).unwrap();
    assert!(out[0].abs() < 1e-16);
    // Φ_q q̇ for q̇ ⟂ q is 0; (Φ_q q̇)_q q̇ = |q̇|².
    velocity_residual(&c, 0.0, &[0.6, 0.8], &[0.8, -0.6], &mut out).unwrap();
    assert!(out[0].abs() < 1e-16);
    acceleration_bias(&c, 0.0, &[0.6, 0.8], &[0.8, -0.6], &mut out).unwrap();
    assert!((out[0] - 1.0).abs() < 1e-15);
}

/// Issue 29, item 6: `holonomic::jacobian` into a matrix smaller than m × n silently wrote only part
/// of Φ_q (and a larger one read past q); now `Dimension` naming the rows or columns, `out` untouched.
#[test]
fn regress_holonomic_jacobian_truncates() {
    use nalgebra::DMatrix;
    use noether_constraints::holonomic::jacobian;
    let c = Rod {
        d: 3,
        l: 1.0,
        copies: 2,
    };
    for (rows, cols) in [(1, 3), (2, 2), (0, 0), (3, 3), (2, 4)] {
        let mut j = DMatrix::from_element(rows, cols, 7.0);
        let r = jacobian(&c, 0.0, &[0.6, 0.8, 0.0], &mut j);
        match r {
            Err(Error::Core(CoreError::Dimension { what, expected, got })) => {
                if rows != 2 {
                    assert_eq!((what, expected, got), ("rows of Φ_q (output)", 2, rows));
                } else {
                    assert_eq!((what, expected, got), ("columns of Φ_q (output)", 3, cols));
                }
            }
            other => panic!("{rows}×{cols}: {other:?}"),
        }
        assert!(j.iter().all(|x| *x == 7.0));
    }
    let mut j = DMatrix::zeros(2, 3);
    let r = jacobian(&c, 0.0, &[0.6, 0.8], &mut j);
    assert!(
        matches!(r, Err(Error::Core(CoreError::Dimension { what: "q", .. }))),
        "{r:?}"
    );
    jacobian(&c, 0.0, &[0.6, 0.8, 0.0], &mut j).unwrap();
    // Row k is (1 + k) q / l.
    assert_eq!(j.row(0).iter().copied().collect::<Vec<_>>(), [0.6, 0.8, 0.0]);
    assert_eq!(j.row(1).iter().copied().collect::<Vec<_>>(), [1.2, 1.6, 0.0]);
}

/// Issue 29, items 11 and 12: `Constrained::residuals` passed an unchecked q to the user's code (a
/// panic on a short q) and returned a NaN norm outside the constraint's domain; now a `Result`.
#[test]
fn regress_constrained_residuals_checked() {
    let sys = Constrained::holonomic(
        Masses {
            n: 1,
            d: 2,
            m: 1.0,
            g: 9.81,
        },
        IndexingRod,
    )
    .unwrap();
    let r = sys.residuals(0.0, &[0.6], &[0.0, 0.0]);
    assert!(
        matches!(r, Err(Error::Core(CoreError::Dimension { .. }))),
        "{r:?}"
    );
    let r = sys.residuals(0.0, &[0.6, 0.8], &[0.0]);
    assert!(
        matches!(r, Err(Error::Core(CoreError::Dimension { .. }))),
        "{r:?}"
    );
    let r = sys.residuals(0.0, &[0.6, f64::INFINITY], &[0.0, 0.0]);
    assert!(
        matches!(r, Err(Error::Core(CoreError::NonFinite { .. }))),
        "{r:?}"
    );
    let r = sys.residuals(0.0, &[-0.6, 0.8], &[0.0, 0.0]);
    assert!(
        matches!(r, Err(Error::Core(CoreError::NonFiniteResult { .. }))),
        "{r:?}"
    );
    // On the circle, moving along it: both residuals 0; off it by 0.105 and moving radially.
    let (pos, vel) = sys.residuals(0.0, &[0.6, 0.8], &[0.8, -0.6]).unwrap();
    assert!(pos.unwrap().abs() < 1e-15 && vel.abs() < 1e-15);
    let (pos, vel) = sys.residuals(0.0, &[0.66, 0.88], &[0.6, 0.8]).unwrap();
    assert!((pos.unwrap() - 0.105).abs() < 1e-15 && (vel - 1.1).abs() < 1e-15);
}
