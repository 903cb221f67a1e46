//! Long runs: the energy error of symplectic methods stays bounded (no drift) over 10⁶ steps of the
//! pendulum, while RK4's drifts.
//!
//! Backward error analysis (Hairer-Lubich-Wanner, Thm IX.8.1): a symplectic method of order p applied
//! with step h conserves a modified energy H̃ = H + O(h^p) for exponentially long times, so |H − H₀|
//! oscillates at O(h^p) with no secular growth. We compare the largest energy error over the first
//! tenth of the run with that over the last tenth: bounded means the two agree (ratio close to 1);
//! drift means the last tenth is much larger.

use super::problems::*;
use noether_core::prelude::*;

pub const STEPS: usize = 1_000_000;
pub const H: f64 = 0.1;
pub const THETA0: f64 = 2.0;

/// (max |ΔE| over the first tenth, over the last tenth) of `steps` steps of size `h`.
pub fn energy_errors<S: Stepper, D: Dynamics<Partner = S::Partner>>(
    stepper: &mut S,
    sys: &D,
    start: State<S::Partner>,
    steps: usize,
    h: f64,
) -> (f64, f64) {
    let mut state = start;
    let e0 = sys
        .energy(state.t, state.q.as_slice(), state.v.as_slice())
        .unwrap();
    let tenth = steps / 10;
    let (mut first, mut last) = (0.0_f64, 0.0_f64);
    for i in 0..steps {
        stepper.step(&mut state, h).unwrap();
        let de = (sys
            .energy(state.t, state.q.as_slice(), state.v.as_slice())
            .unwrap()
            - e0)
            .abs();
        if i < tenth {
            first = first.max(de);
        } else if i >= steps - tenth {
            last = last.max(de);
        }
    }
    (first, last)
}

fn start<K: Partner>() -> State<K> {
    State::from_parts(0.0, [THETA0], [0.0])
}

/// Asserts a bounded energy error: last-tenth maximum within 10% of the first-tenth maximum (plus a
/// rounding allowance of 1e-12, the size of a random walk of 10⁶ roundings of an O(1) energy), and
/// below `bound`.
fn assert_bounded(name: &str, (first, last): (f64, f64), bound: f64) {
    eprintln!("{name}: max |ΔE| first tenth {first:.3e}, last tenth {last:.3e}");
    assert!(
        last <= 1.1 * first + 1e-12,
        "{name}: energy error grows: {first:e} -> {last:e}"
    );
    assert!(
        first.max(last) <= bound,
        "{name}: energy error {:e} above {bound:e}",
        first.max(last)
    );
}

#[test]
#[cfg_attr(debug_assertions, ignore = "10^6 steps per method: run with --release")]
fn conserves_energy_symplectic_explicit() {
    let sys = Natural::unit(PendulumV);
    let run = |s: &mut dyn FnMut() -> (f64, f64)| s();
    let r = run(&mut || energy_errors(&mut SymplecticEuler::new(&sys), &sys, start(), STEPS, H));
    assert_bounded("symplectic Euler", r, 0.1);
    let r = run(&mut || energy_errors(&mut Composition::stormer_verlet(&sys), &sys, start(), STEPS, H));
    assert_bounded("Störmer-Verlet", r, 1e-2);
    let r = run(&mut || energy_errors(&mut Composition::yoshida4(&sys), &sys, start(), STEPS, H));
    assert_bounded("Yoshida 4", r, 1e-3);
    // At h = 0.1 the order-6 and order-8 errors are near rounding (1e-9, 1e-13); larger steps keep
    // the truncation error, whose boundedness is the point, well above the rounding random walk.
    let r = run(&mut || energy_errors(&mut Composition::kahan_li6(&sys), &sys, start(), STEPS, 0.2));
    assert_bounded("Kahan-Li 6 (h = 0.2)", r, 1e-6);
    let r = run(&mut || energy_errors(&mut Composition::kahan_li8(&sys), &sys, start(), STEPS, 0.4));
    assert_bounded("Kahan-Li 8 (h = 0.4)", r, 1e-6);
}

#[test]
#[cfg_attr(debug_assertions, ignore = "10^6 steps: run with --release")]
fn conserves_energy_rk4_drifts_in_contrast() {
    // RK4 is not symplectic: its energy error grows linearly in time, so the largest error of the last
    // tenth (reached at the end, t = T) is about 10× that of the first tenth (reached at t = T/10).
    let sys = Natural::unit(PendulumV);
    let (first, last) = energy_errors(&mut Rk4::new(&sys), &sys, start(), STEPS, H);
    eprintln!("RK4: max |ΔE| first tenth {first:.3e}, last tenth {last:.3e}");
    assert!(
        last > 8.0 * first,
        "RK4 energy error should drift: {first:e} -> {last:e}"
    );
}

#[test]
fn conserves_natural_same_flow_in_velocities_and_momenta() {
    // A Natural system with a dense mass matrix stepped on (q, q̇) and, as a separable Hamiltonian, on
    // (q, p): the Verlet steps are the same map written in p = M q̇, so after 1000 steps the two
    // trajectories agree to rounding (1e-12 relative to O(1) values). Energy is conserved to O(h²).
    struct Coupled;
    impl Potential for Coupled {
        fn dof(&self) -> usize {
            2
        }
        fn potential<D: Scalar>(&self, q: &[D]) -> D {
            -q[0].cos() * 2.0 - q[1].cos() + (q[0] - q[1]) * (q[0] - q[1]) * 0.3
        }
    }
    let m = nalgebra::DMatrix::from_row_slice(2, 2, &[2.0, 0.5, 0.5, 1.0]);
    let nat = Natural::dense(Coupled, m.clone()).unwrap();
    let ham = SeparableHamiltonian(Natural::dense(Coupled, m.clone()).unwrap());
    let v0 = [0.3, -0.7];
    let p0 = m * nalgebra::DVector::from_column_slice(&v0);
    let mut a = State::new(0.0, [1.0, 0.2], v0);
    let mut b = State::with_momenta(0.0, [1.0, 0.2], [p0[0], p0[1]]);
    let (mut sa, mut sb) = (Composition::yoshida4(&nat), Composition::yoshida4(&ham));
    for _ in 0..1000 {
        sa.step(&mut a, 0.01).unwrap();
        sb.step(&mut b, 0.01).unwrap();
    }
    let mut pa = [0.0; 2];
    nat.momenta(a.v.as_slice(), &mut pa).unwrap();
    assert!((&a.q - &b.q).amax() < 1e-12);
    assert!((pa[0] - b.v[0]).abs() < 1e-12 && (pa[1] - b.v[1]).abs() < 1e-12);
    let e0 = nat.energy(&[1.0, 0.2], &v0).unwrap();
    assert!((nat.energy(a.q.as_slice(), a.v.as_slice()).unwrap() - e0).abs() < 1e-6);
}
