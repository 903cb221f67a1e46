//! The Jacobian of a run of steps (`run_jacobian`) and tangent vectors carried along (`propagate`).

use super::*;
use noether_core::tangent::{propagate, run_jacobian};

/// Central differences of the N-step map, column j from the runs started at y₀ ± δ_j e_j.
fn run_by_differences<S: Stepper>(
    stepper: &mut S,
    state: &State<S::Partner>,
    h: f64,
    steps: usize,
    rel: f64,
) -> DMatrix<f64> {
    let n = stepper.dof();
    let mut phi = DMatrix::zeros(2 * n, 2 * n);
    for j in 0..2 * n {
        let mut ends = Vec::new();
        for sign in [1.0, -1.0] {
            let mut s = state.clone();
            let y = if j < n { &mut s.q[j] } else { &mut s.v[j - n] };
            let delta = rel * y.abs().max(1.0);
            *y += sign * delta;
            for _ in 0..steps {
                stepper.step(&mut s, h).unwrap();
            }
            ends.push((s, delta));
        }
        for i in 0..2 * n {
            let pick = |s: &State<S::Partner>| if i < n { s.q[i] } else { s.v[i - n] };
            phi[(i, j)] = (pick(&ends[0].0) - pick(&ends[1].0)) / (2.0 * ends[0].1);
        }
    }
    phi
}

#[test]
fn the_jacobian_of_a_run_matches_central_differences_of_the_run() {
    // 20 steps of h = 0.1 on the Hénon-Heiles orbit: Φ of order 1-3.
    let sys = HamiltonEquations::new(HenonHeiles);
    let s0 = henon_heiles_state();
    let mut rk4 = Rk4::new(&sys);
    // Richardson's extrapolation of two central differences, (4 R(δ/2) − R(δ))/3, removes their δ²
    // truncation error: over 20 steps the third derivatives of the map have grown, and the plain
    // difference at δ = 1e-5 is off by 8.5e-11 (measured; R(2δ) − R(δ) = 2.6e-10 ≈ 3× that, the δ² law).
    let coarse = run_by_differences(&mut rk4, &s0, 0.1, 20, FD_REL);
    let fine = run_by_differences(&mut rk4, &s0, 0.1, 20, FD_REL / 2.0);
    let reference = (fine * 4.0 - coarse) / 3.0;
    let mut s = s0.clone();
    let phi = run_jacobian(&mut rk4, &mut s, 0.1, 20).unwrap();
    let mut plain = s0.clone();
    (0..20).for_each(|_| {
        rk4.step(&mut plain, 0.1).unwrap();
    });
    assert_eq!(s, plain, "run_jacobian takes the plain steps");
    let e = (&phi - reference).abs().max();
    println!(
        "|Φ − Φ_fd| over 20 RK4 steps = {e:e}, |Φ| = {:e}",
        phi.abs().max()
    );
    // Measured 2.6e-11: the rounding of the differences (ε/δ per step of a 20-step map, times the
    // extrapolation's weights), the δ² error being gone.
    assert!(e < 5e-11, "{e:e}");
}

#[test]
fn the_run_jacobian_is_the_product_of_the_step_jacobians() {
    let sys = HamiltonEquations::new(HenonHeiles);
    let mut g6 = Gauss::gauss6(&sys);
    let mut s = henon_heiles_state();
    let mut product = DMatrix::identity(4, 4);
    let mut psi = DMatrix::zeros(4, 4);
    for _ in 0..10 {
        g6.step_tangent(&mut s, 0.2, &mut psi).unwrap();
        product = &psi * product;
    }
    let mut s_run = henon_heiles_state();
    let phi = run_jacobian(&mut Gauss::gauss6(&sys), &mut s_run, 0.2, 10).unwrap();
    assert_eq!(s_run, s);
    // Same products in the same order: equal bit for bit.
    assert_eq!(phi, product);
}

#[test]
fn propagated_tangent_vectors_are_the_run_jacobian_applied_to_them() {
    let sys = SeparableHamiltonian(HhSeparable);
    let w0 = DMatrix::from_row_slice(4, 2, &[1.0, 0.0, 0.0, 0.5, 0.0, -1.0, 0.3, 0.0]);
    let mut w = w0.clone();
    let mut s = henon_heiles_state();
    propagate(&mut Composition::yoshida4(&sys), &mut s, 0.1, 30, &mut w).unwrap();
    let mut s_run = henon_heiles_state();
    let phi = run_jacobian(&mut Composition::yoshida4(&sys), &mut s_run, 0.1, 30).unwrap();
    assert_eq!(s, s_run);
    let e = (w - phi * w0).abs().max();
    println!("|W − Φ W₀| = {e:e}");
    // Measured 1.2e-15: the two products associate differently, rounding only.
    assert!(e < 1e-14, "{e:e}");
}

#[test]
fn symplectic_runs_keep_phase_volume() {
    // Liouville for the numerical map: det Φ = 1 over 200 steps of the symplectic methods.
    let sys = SeparableHamiltonian(HhSeparable);
    let hs = HamiltonEquations::new(HenonHeiles);
    let dets = [
        run_jacobian(
            &mut Composition::stormer_verlet(&sys),
            &mut henon_heiles_state(),
            0.1,
            200,
        )
        .unwrap()
        .determinant(),
        run_jacobian(
            &mut Composition::kahan_li8(&sys),
            &mut henon_heiles_state(),
            0.1,
            200,
        )
        .unwrap()
        .determinant(),
        run_jacobian(&mut Gauss::gauss4(&hs), &mut henon_heiles_state(), 0.1, 200)
            .unwrap()
            .determinant(),
    ];
    println!("det Φ − 1 over 200 steps: {:?}", dets.map(|d| d - 1.0));
    // Measured det Φ − 1 = 1.0e-14, −4.6e-15, −9.2e-15: the rounding of 200 products (about ε per
    // step, √200·ε to 200ε).
    for d in dets {
        assert!((d - 1.0).abs() < 3e-14, "{d}");
    }
}

/// A 1D particle falling into √q: H = ½p² + √q reaches q = 0 at a finite time, after which the
/// force −1/(2√q) is NaN: a run that fails in the middle.
struct Sink;
impl Hamiltonian for Sink {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        p[0] * p[0] * 0.5 + q[0].sqrt()
    }
}

#[test]
fn run_errors_are_typed_and_leave_state_and_tangents_unchanged() {
    let sys = HamiltonEquations::new(HenonHeiles);
    let s0 = henon_heiles_state();
    let mut rk4 = Rk4::new(&sys);
    let mut s = s0.clone();
    let mut w = DMatrix::from_element(3, 1, 1.0);
    let err = propagate(&mut rk4, &mut s, 0.1, 5, &mut w).unwrap_err();
    assert!(
        matches!(
            err,
            Error::Dimension {
                expected: 4,
                got: 3,
                ..
            }
        ),
        "{err}"
    );
    let mut w = DMatrix::from_element(4, 2, 1.0);
    w[(2, 1)] = f64::INFINITY;
    let err = propagate(&mut rk4, &mut s, 0.1, 5, &mut w).unwrap_err();
    assert!(matches!(err, Error::NonFinite { index: 6, .. }), "{err}");
    assert_eq!(s, s0);
    let err = run_jacobian(&mut rk4, &mut s, -0.1, 5).unwrap_err();
    assert!(matches!(err, Error::InvalidStep { .. }), "{err}");
    assert_eq!(s, s0);

    // A failure after some good steps: nothing is committed.
    let mut sink = Rk4::new(HamiltonEquations::new(Sink));
    let start = State::with_momenta(0.0, [1.0], [0.0]);
    let (mut s, mut w) = (start.clone(), DMatrix::from_element(2, 1, 1.0));
    let err = propagate(&mut sink, &mut s, 0.1, 100, &mut w).unwrap_err();
    println!("mid-run failure: {err}");
    assert!(
        matches!(err, Error::NonFiniteResult { .. } | Error::NonFinite { .. }),
        "{err}"
    );
    assert_eq!(s, start);
    assert_eq!(w, DMatrix::from_element(2, 1, 1.0));
}

/// Issue 29 item 7: `run_jacobian` and `propagate` from t = 1e20 (t + h == t) are refused with
/// `StepBelowTimeResolution`, state and tangent vectors unchanged; before, they returned Ok with t
/// never moving.
#[test]
fn regress_run_jacobian_step_below_time_resolution() {
    let mut rk4 = Rk4::new(HamiltonEquations::new(HenonHeiles));
    let mut s = State::with_momenta(1e20, [0.0, 0.1], [0.3, 0.0]);
    let before = s.clone();
    let err = run_jacobian(&mut rk4, &mut s, 1e-3, 10).unwrap_err();
    assert_eq!(err, Error::StepBelowTimeResolution { t: 1e20, h: 1e-3 });
    assert_eq!(s, before);
    let mut w = DMatrix::identity(4, 2);
    let err = propagate(&mut rk4, &mut s, 1e-3, 10, &mut w).unwrap_err();
    assert_eq!(err, Error::StepBelowTimeResolution { t: 1e20, h: 1e-3 });
    assert_eq!((s, w), (before, DMatrix::identity(4, 2)));
}
