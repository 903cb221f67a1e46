//! Bad input gets a clear error, never a panic or a NaN state; on error the state is unchanged.

use super::problems::*;
use noether_core::prelude::*;

/// A pendulum whose potential V = −cos θ + 10⁻³ √(1.5 − θ) is NaN beyond θ = 1.5 (the square root of a
/// negative number), as a careless model would produce mid-run.
struct Fragile;
impl Potential for Fragile {
    fn dof(&self) -> usize {
        1
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        -q[0].cos() + (-q[0] + 1.5).sqrt() * 1e-3
    }
}
impl Lagrangian for Fragile {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * v[0] * 0.5 - Potential::potential(self, q)
    }
}

/// Every core method on a pendulum in velocities (q, q̇).
fn velocity_steppers() -> Vec<Box<dyn Stepper<Partner = Velocities>>> {
    vec![
        Box::new(Euler::new(EulerLagrange::new(PendulumL))),
        Box::new(EulerCromer::new(EulerLagrange::new(PendulumL))),
        Box::new(Rk4::new(EulerLagrange::new(PendulumL))),
        Box::new(SymplecticEuler::new(Natural::unit(PendulumV))),
        Box::new(Composition::stormer_verlet(Natural::unit(PendulumV))),
        Box::new(Dopri5::new(EulerLagrange::new(PendulumL))),
        Box::new(Dop853::new(Natural::unit(PendulumV))),
        Box::new(Gauss::implicit_midpoint(Natural::unit(PendulumV))),
        Box::new(Dprkn6::new(Natural::unit(PendulumV)).unwrap()),
        Box::new(Dprkn8::new(Natural::unit(PendulumV)).unwrap()),
        Box::new(Dprkn12::new(Natural::unit(PendulumV)).unwrap()),
    ]
}

/// The methods that take the pendulum in momenta (q, p).
fn momentum_steppers() -> Vec<Box<dyn Stepper<Partner = Momenta>>> {
    vec![
        Box::new(Composition::kahan_li8(SeparableHamiltonian(Natural::unit(
            PendulumV,
        )))),
        Box::new(Gauss::gauss4(HamiltonEquations::new(PendulumH))),
        Box::new(Rk4::new(HamiltonEquations::new(PendulumH))),
    ]
}

/// Runs `check` on every stepper of both kinds.
macro_rules! for_all_steppers {
    (|$s:ident| $body:block) => {{
        fn run<K: Partner>(steppers: Vec<Box<dyn Stepper<Partner = K>>>) {
            for mut $s in steppers {
                $body
            }
        }
        run(velocity_steppers());
        run(momentum_steppers());
    }};
}

#[test]
fn bad_input_step_zero_negative_nan() {
    for_all_steppers!(|s| {
        for h in [0.0, -0.1, f64::NAN, f64::INFINITY] {
            let mut state = State::<K>::from_parts(0.0, [1.0], [0.0]);
            let before = state.clone();
            let err = s.step(&mut state, h).unwrap_err();
            assert!(
                matches!(err, Error::InvalidStep { .. }),
                "{}: h = {h}: {err}",
                s.name()
            );
            assert_eq!(state, before);
        }
    });
    let err = Driver::new(
        Rk4::new(EulerLagrange::new(PendulumL)),
        State::new(0.0, [1.0], [0.0]),
    )
    .unwrap()
    .step_size(0.0);
    assert!(matches!(err, Err(Error::InvalidStep { .. })));
}

#[test]
fn bad_input_wrong_dimensions() {
    for_all_steppers!(|s| {
        let mut state = State::<K>::from_parts(0.0, [1.0, 2.0], [0.0]);
        let before = state.clone();
        let err = s.step(&mut state, 0.1).unwrap_err();
        assert!(
            matches!(
                err,
                Error::Dimension {
                    expected: 1,
                    got: 2,
                    ..
                }
            ),
            "{}: {err}",
            s.name()
        );
        assert_eq!(state, before);
    });
}

#[test]
fn bad_input_nan_initial_state() {
    for_all_steppers!(|s| {
        let mut state = State::<K>::from_parts(0.0, [f64::NAN], [0.0]);
        let err = s.step(&mut state, 0.1).unwrap_err();
        assert!(
            matches!(err, Error::NonFinite { what: "q", .. }),
            "{}: {err}",
            s.name()
        );
        assert!(state.q[0].is_nan() && state.v[0] == 0.0 && state.t == 0.0);
    });
    let err = Driver::new(
        Composition::stormer_verlet(Natural::unit(PendulumV)),
        State::new(0.0, [0.0], [f64::INFINITY]),
    );
    assert!(matches!(err, Err(Error::NonFinite { what: "v", .. })));
}

#[test]
fn bad_input_nan_mid_run_names_step_and_time() {
    // Released at θ = 1.4 from rest with a push θ̇ = 0.5, the pendulum passes θ = 1.5 within the
    // first second; there V is NaN. The driver must stop with the index and time of the failing
    // step, the last good state kept.
    fn check<S: Stepper>(s: S) {
        let name = s.name();
        let h = 0.01;
        let start = State::<S::Partner>::from_parts(0.0, [1.4], [0.5]);
        let mut traj = Driver::new(s, start).unwrap().step_size(h).unwrap();
        let mut good = 0;
        let err = loop {
            match traj.next().unwrap() {
                Ok(_) => good += 1,
                Err(e) => break e,
            }
        };
        match err {
            Error::NonFiniteState { step, t, .. } => {
                assert_eq!(step, good, "{name}");
                assert!((t - good as f64 * h).abs() < 1e-12, "{name}: t = {t}");
                assert!(good > 0 && t < 1.0, "{name}: failed at step {step}");
            }
            other => panic!("{name}: unexpected {other}"),
        }
        assert!(traj.state().is_finite(), "{name}: the last good state is kept");
        assert!(traj.next().is_none(), "a failed trajectory ends");
    }
    check(Euler::new(EulerLagrange::new(Fragile)));
    check(EulerCromer::new(EulerLagrange::new(Fragile)));
    check(Rk4::new(EulerLagrange::new(Fragile)));
    check(SymplecticEuler::new(Natural::unit(Fragile)));
    check(Composition::stormer_verlet(Natural::unit(Fragile)));
    check(Composition::yoshida4(SeparableHamiltonian(Natural::unit(
        Fragile,
    ))));
    check(Gauss::implicit_midpoint(Natural::unit(Fragile)));
    check(Gauss::gauss6(HamiltonEquations::new(SeparableHamiltonian(
        Natural::unit(Fragile),
    ))));
}

#[test]
fn bad_input_mass_matrix_and_coefficients() {
    let singular = nalgebra::DMatrix::from_row_slice(1, 1, &[0.0]);
    assert!(matches!(
        Natural::dense(PendulumV, singular),
        Err(Error::SingularMassMatrix { .. })
    ));
    let negative = nalgebra::DMatrix::from_row_slice(1, 1, &[-1.0]);
    assert!(matches!(
        Natural::dense(PendulumV, negative),
        Err(Error::InvalidParameter { .. })
    ));
    let asym = nalgebra::DMatrix::from_row_slice(2, 2, &[1.0, 0.1, 0.0, 1.0]);
    assert!(matches!(
        Natural::dense(KeplerV, asym),
        Err(Error::InvalidParameter { .. })
    ));
    let wrong = nalgebra::DMatrix::identity(3, 3);
    assert!(matches!(
        Natural::dense(KeplerV, wrong),
        Err(Error::Dimension { .. })
    ));
    assert!(matches!(
        Natural::diagonal(KeplerV, &[1.0, -2.0]),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        Natural::diagonal(KeplerV, &[1.0, f64::NAN]),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        Natural::diagonal(KeplerV, &[1.0]),
        Err(Error::Dimension { .. })
    ));
    let sys = Natural::unit(PendulumV);
    let custom = |w: &[f64]| Weights::custom(w, 2).map(|w| Composition::new(StormerVerlet::new(&sys), w));
    assert!(custom(&[0.5, 0.5]).is_ok());
    assert!(matches!(custom(&[0.5, 0.6]), Err(Error::InvalidParameter { .. })));
    assert!(matches!(custom(&[0.3, 0.7]), Err(Error::InvalidParameter { .. })));
    assert!(matches!(
        custom(&[0.5, 0.0, 0.5]),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(custom(&[]), Err(Error::InvalidParameter { .. })));
}

/// ẏ = y² (on q; v idle): y = 1/(1 − t) blows up at t = 1.
struct BlowUp;
impl Dynamics for BlowUp {
    type Partner = Velocities;
    fn dof(&self) -> usize {
        1
    }
    fn rates(&self, _t: f64, q: &[f64], _v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()> {
        dq[0] = q[0] * q[0];
        dv[0] = 0.0;
        Ok(())
    }
    fn energy(&self, _t: f64, _q: &[f64], _v: &[f64]) -> Result<f64> {
        Ok(0.0)
    }
}

#[test]
fn bad_input_adaptive_step_size_underflow() {
    // Integrating ẏ = y² from y(0) = 1 past the blow-up at t = 1: the steps shrink to h_min and the
    // integration stops with StepSizeUnderflow at t ≈ 1 (the numerical blow-up time agrees with the true
    // one to the tolerance), and the driver keeps the last good state, just before the blow-up.
    fn check<S: Stepper<Partner = Velocities>>(name: &str, s: S) {
        let mut run = Driver::new(s, State::new(0.0, [1.0], [0.0])).unwrap();
        match run.run_until(2.0) {
            Err(Error::StepSizeUnderflow { t, h, .. }) => {
                assert!((t - 1.0).abs() < 1e-3 && h < 1e-13, "{name}: t = {t}, h = {h}");
                assert_eq!(run.state().t, t, "{name}: the last good state is kept");
            }
            other => panic!("{name}: expected underflow, got {other:?}"),
        }
        assert!(run.state().is_finite());
    }
    check("DOPRI5", Dopri5::new(BlowUp).tolerances(1e-8, 1e-8).unwrap());
    check("DOP853", Dop853::new(BlowUp).tolerances(1e-8, 1e-8).unwrap());
    // A model turning NaN mid-run (θ > 1.5) is also met by shrinking steps, never by a NaN state.
    let mut s = Dopri5::new(Natural::unit(Fragile));
    let mut traj_state = State::new(0.0, [1.4], [0.5]);
    let mut h = 0.01;
    let err = loop {
        match s.step(&mut traj_state, h) {
            Ok(info) => h = info.h_next,
            Err(e) => break e,
        }
    };
    assert!(matches!(err, Error::StepSizeUnderflow { .. }), "{err}");
    assert!(traj_state.is_finite() && traj_state.q[0] <= 1.5);
}

#[test]
fn bad_input_nystrom_failed_step_leaves_state() {
    // The fragile pendulum (V NaN beyond θ = 1.5) from θ = 1.4 with θ̇ = 0.5: an adaptive Nyström
    // method meets the NaN stages by shrinking its steps until StepSizeUnderflow; that step leaves
    // the state exactly as it was, finite, short of θ = 1.5. A fixed step into the NaN region fails
    // with NonFiniteResult, the state unchanged too.
    fn check<S: Stepper<Partner = Velocities>>(mut s: S) {
        let name = s.name();
        let mut state = State::new(0.0, [1.4], [0.5]);
        let mut h = 0.01;
        let (err, before) = loop {
            let before = state.clone();
            match s.step(&mut state, h) {
                Ok(info) => h = info.h_next,
                Err(e) => break (e, before),
            }
        };
        assert!(matches!(err, Error::StepSizeUnderflow { .. }), "{name}: {err}");
        assert_eq!(state, before, "{name}");
        assert!(state.is_finite() && state.q[0] <= 1.5, "{name}: {state:?}");
    }
    check(Dprkn6::new(Natural::unit(Fragile)).unwrap());
    check(Dprkn8::new(Natural::unit(Fragile)).unwrap());
    check(Dprkn12::new(Natural::unit(Fragile)).unwrap());
    let mut s = Dprkn8::new(Natural::unit(Fragile)).unwrap().fixed_step(true);
    let mut state = State::new(0.0, [1.4], [0.5]);
    let before = state.clone();
    let err = s.step(&mut state, 0.5).unwrap_err();
    assert!(matches!(err, Error::NonFiniteResult { .. }), "{err}");
    assert_eq!(state, before);
}

#[test]
fn bad_input_adaptive_parameters() {
    // Tolerances are checked when they are set, not at the first step.
    let sys = || Natural::unit(PendulumV);
    for (atol, rtol) in [(0.0, 0.0), (-1.0, 1e-6), (1e-6, f64::NAN)] {
        let err = Dopri5::new(sys()).tolerances(atol, rtol).map(|_| ()).unwrap_err();
        assert!(matches!(err, Error::InvalidParameter { .. }), "{err}");
    }
    assert!(Dopri5::new(sys()).h_min(f64::NAN).is_err());
    // Issue 30 item 12: a relative tolerance below what f64 can deliver (10 ε ≈ 2.2e-15) is refused
    // with the floor in its reason, for every embedded pair; the floor itself and 1e-14 are accepted.
    for rtol in [1e-20, 1e-16, 0.99 * RTOL_FLOOR] {
        let err = Dop853::new(sys())
            .tolerances(1e-20, rtol)
            .map(|_| ())
            .unwrap_err();
        match err {
            Error::InvalidParameter { name, value, reason } => {
                assert_eq!((name, value), ("rtol", rtol));
                assert!(reason.contains("2.2e-15"), "{reason}");
            }
            other => panic!("expected InvalidParameter, got {other:?}"),
        }
        assert!(Dopri5::new(sys()).tolerances(1e-9, rtol).is_err());
        assert!(Dprkn8::new(sys()).unwrap().tolerances(1e-9, rtol).is_err());
    }
    assert_eq!(RTOL_FLOOR, 10.0 * f64::EPSILON);
    assert!(Dop853::new(sys()).tolerances(1e-20, RTOL_FLOOR).is_ok());
    assert!(Dop853::new(sys()).tolerances(1e-14, 1e-14).is_ok());
    // The driver checks its output times and end time before any step.
    let state = State::new(0.0, [1.0], [0.0]);
    let driver = || Driver::new(Dopri5::new(sys()), state.clone()).unwrap();
    let unsorted = driver().save(Save::Times(vec![0.5, 0.2]));
    assert!(matches!(
        unsorted,
        Err(Error::InvalidParameter {
            name: "output time",
            ..
        })
    ));
    let nan_time = driver().save(Save::Times(vec![0.5, f64::NAN]));
    assert!(matches!(nan_time, Err(Error::NonFinite { .. })));
    let mut d = driver().save(Save::Times(vec![1.5])).unwrap();
    assert!(matches!(d.run_until(1.0), Err(Error::InvalidParameter { .. })));
    let backwards = driver().run_until(-1.0);
    assert!(matches!(
        backwards,
        Err(Error::InvalidParameter { name: "t_end", .. })
    ));
    let nan_end = driver().run_until(f64::NAN);
    assert!(matches!(nan_end, Err(Error::NonFinite { .. })));
    assert!(matches!(
        driver().save(Save::Every(0)),
        Err(Error::InvalidParameter { .. })
    ));
    assert_eq!(d.state(), &state);
}

/// A system with no degrees of freedom (an empty model).
struct Nothing;
impl Lagrangian for Nothing {
    fn dof(&self) -> usize {
        0
    }
    fn lagrangian<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D]) -> D {
        D::zero()
    }
}

/// Issue 15, case 10: DOPRI5 on a system of 0 degrees of freedom reported `StepSizeUnderflow` (its
/// error norm divided 0 by 0). Time alone advances, to the end exactly.
#[test]
fn regress_adaptive_with_no_degrees_of_freedom() {
    let el = EulerLagrange::new(Nothing);
    let start = || State::new(0.0, Vec::<f64>::new(), Vec::<f64>::new());
    let end = Driver::new(Dopri5::new(&el), start())
        .unwrap()
        .run_until(2.0)
        .unwrap();
    assert_eq!(end.last().t, 2.0);
    let end = Driver::new(Dop853::new(&el), start())
        .unwrap()
        .run_until(2.0)
        .unwrap();
    assert_eq!(end.last().t, 2.0);
}

/// Issue 13.5 / 15.10: a NaN, zero, negative or infinite tolerance, a contraction outside (0, 1) or an
/// iteration cap of 0 is `InvalidParameter` naming the setting, from the setters (the fields are
/// private, so no invalid settings reach `solve`), never `NewtonDiverged`.
#[test]
fn bad_input_newton_nan_tolerance() {
    use noether_core::newton::{solve_dense, DenseProblem};
    use noether_core::Newton;
    struct Line;
    impl DenseProblem for Line {
        fn dim(&self) -> usize {
            1
        }
        fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()> {
            r[0] = x[0] - 1.0;
            Ok(())
        }
        fn jacobian(&mut self, _x: &[f64], j: &mut nalgebra::DMatrix<f64>) -> Result<()> {
            j[(0, 0)] = 1.0;
            Ok(())
        }
    }
    let invalid = |r: Result<Newton>, name: &str| match r {
        Err(Error::InvalidParameter { name: n, .. }) => assert_eq!(n, name),
        other => panic!("{name}: expected InvalidParameter, got {other:?}"),
    };
    for bad in [f64::NAN, 0.0, -1e-12, f64::INFINITY] {
        invalid(
            Newton::default().residual_tolerance(bad),
            "Newton residual_tolerance",
        );
        invalid(Newton::default().step_tolerance(bad), "Newton step_tolerance");
    }
    for bad in [f64::NAN, 0.0, 1.0, -0.5] {
        invalid(Newton::default().contraction(bad), "Newton contraction");
    }
    invalid(Newton::default().max_iterations(0), "Newton max_iterations");
    // Valid settings solve it.
    let ok = Newton::default()
        .residual_tolerance(1e-14)
        .unwrap()
        .step_tolerance(1e-15)
        .unwrap();
    let (x, _) = solve_dense(&ok.contraction(0.5).unwrap(), Line, &[3.0]).unwrap();
    assert_eq!(x[0], 1.0);
}

/// Issue 29 item 7: a step that does not move t (t = 1e20, h = 1e-3: t + h == t) or moves it by not
/// ~h (t = 1e15, h = 1e-3: t + h − t = 0 or 0.125) is refused by every bare stepper with
/// `StepBelowTimeResolution`, the state unchanged; before, RK4 and the others returned Ok with t
/// unchanged (or moved by 0.125 while integrating over 1e-3).
#[test]
fn regress_step_below_time_resolution_bare_steppers() {
    fn check<K: Partner>(s: &mut dyn Stepper<Partner = K>) {
        for (t, h) in [(1e20, 1e-3), (1e15, 1e-3), (-1e15, 1e-3)] {
            let mut state = State::<K>::from_parts(t, [1.0], [0.0]);
            let before = state.clone();
            let err = s.step(&mut state, h).unwrap_err();
            assert_eq!(
                err,
                Error::StepBelowTimeResolution { t, h },
                "{}: t = {t}",
                s.name()
            );
            assert_eq!(state, before);
        }
        // A step the axis resolves is taken, at the same large t (above the adaptive methods' floor
        // of 10 ulps of t, 2.2 here), from the equilibrium so that no error estimate shrinks it.
        let mut state = State::<K>::from_parts(1e15, [0.0], [0.0]);
        s.step(&mut state, 100.0).unwrap();
        assert_eq!(state.t, 1e15 + 100.0, "{}", s.name());
    }
    for_all_steppers!(|s| {
        check(&mut *s);
    });
    check(&mut Ias15::new(Natural::unit(PendulumV)).unwrap());
    check(
        &mut Ias15::new(noether_core::integrators::VelocityDependent(Natural::unit(
            PendulumV,
        )))
        .unwrap(),
    );
}

/// The shared test itself (`noether_core::error::check_time_resolution`, used by every stepper and
/// the driver): its boundary at 1 %, a negative step, and NaN or zero input.
#[test]
fn regress_check_time_resolution_boundaries() {
    use noether_core::error::check_time_resolution as check;
    assert!(check(0.0, 1e-300).is_ok());
    assert!(check(1e15, 1.0).is_ok());
    assert!(check(-1e15, -1.0).is_ok());
    // ulp(1e15) = 0.125: a step of 12.55 is rounded by 0.05 = 0.4 %, a step of 0.3 by 0.05 = 17 %.
    assert!(check(1e15, 12.55).is_ok());
    assert!(matches!(
        check(1e15, 0.3),
        Err(Error::StepBelowTimeResolution { .. })
    ));
    assert!(matches!(
        check(1e20, 1e-3),
        Err(Error::StepBelowTimeResolution { .. })
    ));
    assert!(matches!(
        check(1e20, -1e-3),
        Err(Error::StepBelowTimeResolution { .. })
    ));
    assert!(matches!(check(0.0, f64::NAN), Err(Error::InvalidStep { .. })));
    assert!(matches!(check(0.0, 0.0), Err(Error::InvalidStep { .. })));
    assert!(matches!(
        check(f64::NAN, 1.0),
        Err(Error::NonFinite { what: "t", .. })
    ));
    assert!(matches!(check(f64::INFINITY, 1.0), Err(Error::NonFinite { .. })));
}

/// A negative mass: L = −½ q̇² − ½ q², M = ∂²L/∂q̇² = −1 (Lagrange's equations q̈ = q are regular, but
/// the kinetic energy is negative).
struct NegativeMass;
impl Lagrangian for NegativeMass {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        -(v[0] * v[0] + q[0] * q[0]) * 0.5
    }
}

/// Two coordinates, one of them with a negative mass: M = diag(2, −1), indefinite; the taped path of
/// a large system is the same code below `JET_MAX`, so the dense solve is checked by `mass_factor`.
struct MixedMass;
impl Lagrangian for MixedMass {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * v[0] - v[1] * v[1] * 0.5 - q[0] * q[0] * 0.5
    }
}

#[test]
fn bad_input_negative_mass_is_an_indefinite_mass_matrix_at_t0() {
    // Issue 30 item 10: a negative mass was solved by LU and met later as `step size underflow`.
    // DOP853 on L = −½ q̇² − ½ q² now fails at its first evaluation, t = 0, with
    // IndefiniteMassMatrix (M = −1: smallest eigenvalue relative to the largest in magnitude −1),
    // and the driver keeps the start state.
    let el = EulerLagrange::new(NegativeMass);
    let start = State::new(0.0, [1.0], [0.0]);
    let mut run = Driver::new(Dop853::new(&el), start.clone()).unwrap();
    let err = run.run_until(1.0).unwrap_err();
    match &err {
        Error::IndefiniteMassMatrix { t, eigenvalue } => {
            assert_eq!((*t, *eigenvalue), (0.0, -1.0), "{err}");
        }
        other => panic!("expected IndefiniteMassMatrix, got {other:?}"),
    }
    let msg = err.to_string();
    assert!(
        msg.contains("∂²L/∂q̇² is not positive definite at t = 0") && msg.contains("masses"),
        "{msg}"
    );
    assert_eq!(run.state(), &start);
    // The same from the accelerations, and for an indefinite M = diag(2, −1) from the factor.
    let mut a = [0.0];
    let acc = el.accelerations(0.5, &[1.0], &[0.0], &mut a).unwrap_err();
    assert!(
        matches!(acc, Error::IndefiniteMassMatrix { t, .. } if t == 0.5),
        "{acc}"
    );
    let mixed = EulerLagrange::new(MixedMass);
    let f = mixed
        .mass_factor(0.0, &[0.0, 0.0], &[0.0, 0.0])
        .map(|_| ())
        .unwrap_err();
    // Eigenvalues 2 and −1: the smallest relative to the largest in magnitude is −1/2.
    assert!(
        matches!(f, Error::IndefiniteMassMatrix { eigenvalue, .. } if eigenvalue == -0.5),
        "{f}"
    );
}

/// Two oscillators, the first with a stiffness k that is NaN (a parameter the user forgot to set):
/// L = ½ (q̇₀² + q̇₁²) − ½ k q₀² − ½ q₁².
struct NanStiffness {
    k: f64,
}
impl Lagrangian for NanStiffness {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + v[1] * v[1] - q[0] * q[0] * self.k - q[1] * q[1]) * 0.5
    }
}

/// The same as rates written by hand, with the NaN in the second acceleration only:
/// q̇ = v, v̇ = (−q₀, −k q₁).
struct NanRates {
    k: f64,
}
impl Dynamics for NanRates {
    type Partner = Velocities;
    fn dof(&self) -> usize {
        2
    }
    fn rates(&self, _t: f64, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<()> {
        dq.copy_from_slice(v);
        dv[0] = -q[0];
        dv[1] = -self.k * q[1];
        Ok(())
    }
    fn energy(&self, _t: f64, q: &[f64], v: &[f64]) -> Result<f64> {
        Ok(0.5 * (v[0] * v[0] + v[1] * v[1] + q[0] * q[0] + self.k * q[1] * q[1]))
    }
}

#[test]
fn bad_input_nan_parameter_names_quantity_component_and_hint() {
    // Issue 30 item 11: "the model produced a non-finite rates at t = 0". A NaN parameter gives NaN
    // rates at the start of the first step, which no smaller step can cure: DOP853 reports the
    // model's own error at once, naming the quantity, its first non-finite component and the time,
    // with a hint.
    let el = EulerLagrange::new(NanStiffness { k: f64::NAN });
    let start = State::new(0.0, [1.0, 1.0], [0.0, 0.0]);
    let mut state = start.clone();
    let err = Dop853::new(&el).step(&mut state, 0.1).unwrap_err();
    assert_eq!(
        err,
        Error::NonFiniteResult {
            what: "accelerations",
            t: 0.0,
            component: Some(0),
        }
    );
    assert_eq!(
        err.to_string(),
        "the model gave NaN or ±∞ for its accelerations (component 0) at t = 0: check the model's \
         parameters, and that the state is inside the model's domain"
    );
    assert_eq!(state, start);
    // Under a driver the failure comes from the first step-size estimate, before any step: the same
    // error, and the start state kept.
    let mut run = Driver::new(Dop853::new(&el), start.clone()).unwrap();
    assert_eq!(run.run_until(1.0).unwrap_err(), err);
    assert_eq!(run.state(), &start);
    // Rates that come back Ok but NaN: the stepper finds the component itself (q̈₁), for DOPRI5 too.
    for mut s in [
        Box::new(Dop853::new(NanRates { k: f64::NAN })) as Box<dyn Stepper<Partner = Velocities>>,
        Box::new(Dopri5::new(NanRates { k: f64::NAN })),
    ] {
        let mut state = start.clone();
        let err = s.step(&mut state, 0.1).unwrap_err();
        assert_eq!(
            err,
            Error::NonFiniteResult {
                what: "accelerations",
                t: 0.0,
                component: Some(1),
            },
            "{}",
            s.name()
        );
    }
}

/// V = ½q₀² + f(q₁), f(q₁) = ½k q₁²: a spring on q₁ alone whose stiffness k is a parameter.
///
/// The bad parameter must reach one force only. A NaN k cannot: forward-mode AD carries ∂/∂q₀ of
/// f as 0 · k, and 0 · NaN = NaN, so both forces come out NaN (the reason the first version of this
/// test, expecting component 1, was reverted). A finite k = 10³⁰⁸ does: ∂f/∂q₀ = 0 · k = 0 stays
/// finite while ∂f/∂q₁ = k q₁ overflows to ∞ for q₁ = 10, so −∇V = (−q₀, −∞).
struct StiffSpring {
    k: f64,
}

impl Potential for StiffSpring {
    fn dof(&self) -> usize {
        2
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        q[0] * q[0] * 0.5 + q[1] * q[1] * self.k * 0.5
    }
}

#[test]
fn bad_input_overflowing_parameter_nystrom_and_ias15_name_the_component() {
    // Issue 30: the Nyström pairs and IAS15 reported "accelerations" without a component. With
    // k = 10³⁰⁸ and q₁ = 10 the force −k q₁ overflows in component 1 alone: the model's own error names
    // the first non-finite force, so component 1 there says component 0 stayed finite (checked first,
    // so that the integrators' component is not 1 by accident). At the start of a step no
    // smaller step helps, so the error comes at once, naming t, the quantity and the component, the
    // state kept.
    let model = || Natural::unit(StiffSpring { k: 1e308 });
    let start = State::new(0.0, [1.0, 10.0], [0.0, 0.0]);
    let mut a = [0.0; 2];
    // (t is NaN, no time to name, so a match rather than ==.)
    let err = model().accelerations(start.q.as_slice(), &mut a).unwrap_err();
    assert!(
        matches!(
            err,
            Error::NonFiniteResult {
                what: "potential forces",
                component: Some(1),
                ..
            }
        ),
        "{err:?}"
    );
    let expected = Error::NonFiniteResult {
        what: "accelerations",
        t: 0.0,
        component: Some(1),
    };
    for mut s in [
        Box::new(Dprkn6::new(model()).unwrap()) as Box<dyn Stepper<Partner = Velocities>>,
        Box::new(Dprkn8::new(model()).unwrap()),
        Box::new(Dprkn12::new(model()).unwrap()),
        Box::new(Ias15::new(model()).unwrap()),
        Box::new(Ias15::new(noether_core::integrators::VelocityDependent(model())).unwrap()),
    ] {
        let mut state = start.clone();
        assert_eq!(s.step(&mut state, 0.1).unwrap_err(), expected, "{}", s.name());
        assert_eq!(state, start, "{}", s.name());
    }
}
