//! Regressions of issue 15 (items 1 and 2): the implicit methods' Newton solves to rounding, so
//! Gauss-Legendre and implicit midpoint keep quadratic invariants to rounding at every step size and
//! their observed order holds down to the rounding floor; Newton never reports divergence for a
//! residual stuck at its rounding floor.

use super::order::fitted_order;
use super::problems::*;
use noether_core::newton::{solve_dense, DenseProblem};
use noether_core::prelude::*;
use noether_core::Newton;
use std::f64::consts::TAU;

/// A charge (m = e = 1) in the field B = 2 ẑ, A = ½ B (−y, x): H = |p − A|²/2, gyration period π.
struct Charge;
impl Hamiltonian for Charge {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let (kx, ky) = (p[0] + q[1], p[1] - q[0]);
        (kx * kx + ky * ky) * 0.5
    }
}

/// The largest relative drift of `invariant` over `steps` steps of size `h` from `start`.
fn max_drift<S: Stepper<Partner = Momenta>>(
    stepper: &mut S,
    mut state: State<Momenta>,
    h: f64,
    steps: usize,
    invariant: impl Fn(&State<Momenta>) -> f64,
) -> f64 {
    let i0 = invariant(&state);
    let mut worst = 0.0_f64;
    for _ in 0..steps {
        stepper.step(&mut state, h).unwrap();
        worst = worst.max(((invariant(&state) - i0) / i0).abs());
    }
    worst
}

/// (step divisor of the period, number of periods): T/100 to T/50000, fewer periods at small h.
const RUNS: [(usize, f64); 4] = [(100, 10.0), (1000, 5.0), (5000, 1.0), (50000, 0.2)];

/// Gauss-Legendre collocation keeps every quadratic invariant exactly (Hairer-Lubich-Wanner IV.2.1):
/// what remains is rounding (ε per step, a random walk: ≤ 5e-14 measured over 10⁴ steps) and the
/// unconverged Newton remainder, which the round-off-aware stopping rule keeps at rounding. Before it,
/// Gauss 6 lost 3.9e-9 (relative) in 10 orbits at T/50000 (a third of the steps took no Newton
/// iteration) and 8e-13 at T/100 (stopped at the loose residual tolerance 1e-14·(1 + ‖y‖)).
#[test]
#[cfg_attr(debug_assertions, ignore = "long runs: run with --release")]
fn regress_gauss_kepler_angular_momentum_small_steps() {
    let sys = HamiltonEquations::new(KeplerH);
    let ang = |s: &State<Momenta>| s.q[0] * s.v[1] - s.q[1] * s.v[0];
    for stages in 1..=3 {
        for (div, orbits) in RUNS {
            let mut g = Gauss::new(&sys, stages).unwrap();
            let steps = (div as f64 * orbits) as usize;
            let d = max_drift(&mut g, kepler_start(0.6), TAU / div as f64, steps, ang);
            eprintln!("{}: T/{div}, {orbits} orbits: max |ΔL/L| = {d:.2e}", g.name());
            // Measured ≤ 5.3e-14 (Gauss 6, T/100, 10 orbits).
            assert!(d <= 1e-13, "{}: T/{div}: {d:e}", g.name());
        }
    }
}

/// The speed of a charge in a uniform B, ½|v|² = H, is a quadratic invariant: kept to rounding. Before
/// the stopping rule, Gauss 6 lost |ΔH| = 1e-9 in 10 turns at T/10000.
#[test]
#[cfg_attr(debug_assertions, ignore = "long runs: run with --release")]
fn regress_gauss_charge_speed_small_steps() {
    let sys = HamiltonEquations::new(Charge);
    let energy = |s: &State<Momenta>| sys.energy(s.t, s.q.as_slice(), s.v.as_slice()).unwrap();
    let period = TAU / 2.0;
    for stages in 1..=3 {
        for (div, turns) in RUNS {
            let mut g = Gauss::new(&sys, stages).unwrap();
            let steps = (div as f64 * turns) as usize;
            let start = State::with_momenta(0.0, [0.0, 0.0], [1.0, 0.0]);
            let d = max_drift(&mut g, start, period / div as f64, steps, energy);
            eprintln!("{}: T/{div}, {turns} turns: max |ΔH/H| = {d:.2e}", g.name());
            assert!(d <= 1e-13, "{}: T/{div}: {d:e}", g.name());
        }
    }
}

/// Position error after one Kepler orbit (e = 0.6, closed form by Kepler's equation) for n steps.
fn kepler_errors<S: Stepper<Partner = Momenta>>(make: impl Fn() -> S, ns: &[usize]) -> Vec<(f64, f64)> {
    ns.iter()
        .map(|&n| {
            let h = TAU / n as f64;
            let end = run(&mut make(), kepler_start(0.6), h, n);
            let (q, p) = kepler_exact(0.6, end.t);
            (h, distance(&end, &q, &p))
        })
        .collect()
}

/// The observed order of Gauss 4 and 6 holds until the error meets the rounding floor of one orbit
/// (≈ 1.5e-11 measured: rounding random-walks the energy, whose error turns into a phase error
/// growing with time), and the error stays at that floor for smaller steps. Before, it rose again at
/// small h: Gauss 6 reached 7e-9 at T/25600, because unconverged Newton remainders piled up.
#[test]
#[cfg_attr(debug_assertions, ignore = "long runs: run with --release")]
fn regress_gauss_order_down_to_rounding_floor() {
    let sys = HamiltonEquations::new(KeplerH);
    for (name, stages, order, asymptotic) in [
        ("Gauss 4", 2, 4.0, &[400usize, 800, 1600, 3200, 6400][..]),
        ("Gauss 6", 3, 6.0, &[200usize, 400, 800][..]),
    ] {
        let e = kepler_errors(|| Gauss::new(&sys, stages).unwrap(), asymptotic);
        let p = fitted_order(&e);
        eprintln!("{name}: observed order {p:.3} over {e:?}");
        assert!((p - order).abs() <= 0.1, "{name}: {p}: {e:?}");
        let floor = kepler_errors(|| Gauss::new(&sys, stages).unwrap(), &[12800, 25600]);
        eprintln!("{name}: at the floor {floor:?}");
        // Measured ≤ 1.45e-11; a pile-up of Newton remainders grows with the number of steps.
        assert!(floor.iter().all(|(_, err)| *err <= 3e-11), "{name}: {floor:?}");
    }
}

/// Issue 15 item 2: Gauss 6 on the pendulum at h = 0.8, 40 trajectories θ₀ ∈ (0, 3), p₀ = 0, 100 steps,
/// converges at every step, both with the default tolerances and with tolerances far below what
/// rounding allows (1e-20: the solver ends when the increments stop decreasing, at the rounding
/// floor, and agrees with the default solve to rounding).
#[test]
fn regress_gauss6_pendulum_large_steps_converge() {
    let sys = HamiltonEquations::new(PendulumH);
    let tight = Newton::default()
        .residual_tolerance(1e-20)
        .unwrap()
        .step_tolerance(1e-20)
        .unwrap()
        .max_iterations(20)
        .unwrap();
    let mut worst = 0.0_f64;
    for i in 0..40 {
        let th0 = 3.0 * (i as f64 + 0.5) / 40.0;
        let start = State::with_momenta(0.0, [th0], [0.0]);
        let a = run(&mut Gauss::gauss6(&sys), start.clone(), 0.8, 100);
        let b = run(&mut Gauss::gauss6(&sys).newton(tight), start, 0.8, 100);
        worst = worst.max(distance(&a, b.q.as_slice(), b.v.as_slice()));
    }
    // Both solve each step to rounding; 100 large steps near the separatrix (θ₀ → 3) amplify the
    // rounding differences (measured 3.4e-11).
    eprintln!("Gauss 6, h = 0.8: default vs tolerance 1e-20 differ by {worst:.2e}");
    assert!(worst < 1e-10, "{worst:e}");
}

/// F(x) = x − 1 + 10⁻¹² n(x), with n a deterministic "rounding noise" in [−½, ½) of the bits of x: a
/// residual whose floor (10⁻¹²) is far above the tolerance asked for.
struct Noisy;
impl DenseProblem for Noisy {
    fn dim(&self) -> usize {
        1
    }
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()> {
        let bits = x[0].to_bits().wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 11;
        r[0] = x[0] - 1.0 + 1e-12 * (bits as f64 / (1u64 << 53) as f64 - 0.5);
        Ok(())
    }
    fn jacobian(&mut self, _x: &[f64], j: &mut nalgebra::DMatrix<f64>) -> Result<()> {
        j[(0, 0)] = 1.0;
        Ok(())
    }
}

/// A residual stuck at its rounding floor above the tolerance is converged (the increments stopped
/// decreasing under an exact Jacobian), not `NewtonDiverged` (the old rule iterated to the cap).
#[test]
fn regress_newton_residual_floor_above_tolerance_is_converged() {
    let newton = Newton::default().residual_tolerance(1e-14).unwrap();
    for x0 in [3.0, 1.0 + 1e-12, 1.0 - 3e-13] {
        let (x, info) = solve_dense(&newton, Noisy, &[x0]).unwrap();
        eprintln!("from {x0}: x − 1 = {:.2e} in {info:?}", x[0] - 1.0);
        // Within the noise of the root: |x − 1| ≤ ½·10⁻¹² + the last increment (≤ 10⁻¹²).
        assert!((x[0] - 1.0).abs() <= 1.5e-12 && info.iterations <= 10, "{info:?}");
    }
}

/// F(x) = x² + 1 has no real root: the increments never become small, and the solve fails at the
/// iteration cap with its count and residual.
#[test]
fn regress_newton_no_root_still_diverges() {
    let newton = Newton::default().max_iterations(30).unwrap();
    struct NoRoot;
    impl DenseProblem for NoRoot {
        fn dim(&self) -> usize {
            1
        }
        fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()> {
            r[0] = x[0] * x[0] + 1.0;
            Ok(())
        }
        fn jacobian(&mut self, x: &[f64], j: &mut nalgebra::DMatrix<f64>) -> Result<()> {
            j[(0, 0)] = 2.0 * x[0];
            Ok(())
        }
    }
    match solve_dense(&newton, NoRoot, &[0.5]) {
        Err(Error::NewtonDiverged {
            iterations, residual, ..
        }) => assert!(iterations == 30 && residual >= 1.0),
        other => panic!("expected NewtonDiverged, got {other:?}"),
    }
}

/// A guess that already meets the residual tolerance is still corrected once (the remainder of a
/// good predictor must not pile up over many solves): x² = 2 from √2 + 10⁻¹³ (‖F‖ = 2.8e-13 below
/// the default 1e-12) ends within an ulp of √2.
#[test]
fn regress_newton_corrects_a_guess_within_tolerance() {
    struct Square;
    impl DenseProblem for Square {
        fn dim(&self) -> usize {
            1
        }
        fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()> {
            r[0] = x[0] * x[0] - 2.0;
            Ok(())
        }
        fn jacobian(&mut self, x: &[f64], j: &mut nalgebra::DMatrix<f64>) -> Result<()> {
            j[(0, 0)] = 2.0 * x[0];
            Ok(())
        }
    }
    let (x, info) = solve_dense(&Newton::default(), Square, &[2f64.sqrt() + 1e-13]).unwrap();
    assert!(info.iterations >= 1, "{info:?}");
    assert!((x[0] - 2f64.sqrt()).abs() <= 2.3e-16, "{}", x[0] - 2f64.sqrt());
}

/// The three Gauss methods on the pendulum H = ½p² − cos q, with or without warm starts.
fn pendulum_gauss(stages: usize, warm: bool) -> Gauss<HamiltonEquations<PendulumH>> {
    Gauss::new(HamiltonEquations::new(PendulumH), stages)
        .unwrap()
        .warm_start(warm)
}

/// Issue 29 item 10: with warm starts (the extrapolated collocation polynomial of the last step),
/// implicit midpoint and Gauss 4/6 failed with `NewtonDiverged` at residuals 1.6–140× the tolerance
/// where a fresh stepper from the same state converged (pendulum, h = 0.4–0.8: 18–35 failures in 40
/// starts × 200 steps). A failed warm solve is now retried from the cold guess: wherever a fresh
/// stepper takes the step, the warm one takes it too.
#[test]
fn regress_gauss_warm_start_retries_from_the_cold_guess() {
    for stages in 1..=3 {
        for h in [0.4, 0.6, 0.8] {
            let (mut retried, mut steps) = (0, 0);
            for k in 1..=40 {
                let mut warm = pendulum_gauss(stages, true);
                let mut s = State::with_momenta(0.0, [0.075 * k as f64], [0.5]);
                for _ in 0..200 {
                    let mut fresh_state = s.clone();
                    let fresh = pendulum_gauss(stages, false).step(&mut fresh_state, h);
                    let before = s.clone();
                    match warm.step(&mut s, h) {
                        Ok(info) => retried += info.newton_failures,
                        Err(e) => {
                            assert!(fresh.is_err(), "{stages} stages, h = {h}: warm {e}, fresh Ok");
                            assert_eq!(s, before);
                            break;
                        }
                    }
                    steps += 1;
                }
            }
            eprintln!("{stages} stages, h = {h}: {steps} steps, {retried} retried from the cold guess");
        }
    }
}

/// Issue 29 item 10: with `warm_start(false)` the starting guess depends on the step alone, so a stepper that
/// continues a run and a fresh stepper from the same state give the same new state to the last bit
/// (a run restarted from a saved state continues bit for bit); Kepler e = 0.6 at T/100 and the
/// pendulum at h = 0.5. With warm starts (the default) the guess extrapolates the last step and the
/// two differ in the last bits.
#[test]
fn regress_gauss_continued_and_fresh_steppers_agree_bitwise() {
    fn check<S: Stepper<Partner = Momenta>>(mk: impl Fn() -> S, start: State<Momenta>, h: f64) {
        let mut run = mk();
        let mut s = start;
        for _ in 0..300 {
            let mut restarted = s.clone();
            mk().step(&mut restarted, h).unwrap();
            run.step(&mut s, h).unwrap();
            assert_eq!(s, restarted, "{}", run.name());
        }
    }
    for stages in 1..=3 {
        let sys = HamiltonEquations::new(KeplerH);
        check(
            || Gauss::new(&sys, stages).unwrap().warm_start(false),
            kepler_start(0.6),
            TAU / 100.0,
        );
        check(
            || pendulum_gauss(stages, false),
            State::with_momenta(0.0, [2.0], [0.0]),
            0.5,
        );
    }
}

/// The cost of history-free starting guesses (run with --nocapture): Newton iterations per step,
/// cold against warm, Kepler e = 0.6 over 10 orbits at T/100, T/1000 and the pendulum at h = 0.1.
#[test]
fn regress_gauss_iterations_cold_against_warm() {
    fn iterations<S: Stepper<Partner = Momenta>>(mut st: S, mut s: State<Momenta>, h: f64, n: usize) -> f64 {
        let mut total = 0;
        for _ in 0..n {
            total += st.step(&mut s, h).unwrap().newton_iterations;
        }
        total as f64 / n as f64
    }
    let sys = HamiltonEquations::new(KeplerH);
    for stages in 1..=3 {
        for div in [100, 1000] {
            let h = TAU / div as f64;
            let mk = |warm| Gauss::new(&sys, stages).unwrap().warm_start(warm);
            let cold = iterations(mk(false), kepler_start(0.6), h, 10 * div);
            let warm = iterations(mk(true), kepler_start(0.6), h, 10 * div);
            eprintln!(
                "Gauss {stages} stages, Kepler T/{div}: {cold:.2} iterations per step cold, {warm:.2} warm"
            );
            assert!(cold <= 2.0 * warm + 2.0);
        }
        let start = State::with_momenta(0.0, [2.0], [0.0]);
        let cold = iterations(pendulum_gauss(stages, false), start.clone(), 0.1, 1000);
        let warm = iterations(pendulum_gauss(stages, true), start, 0.1, 1000);
        eprintln!("Gauss {stages} stages, pendulum h = 0.1: {cold:.2} cold, {warm:.2} warm");
    }
}
