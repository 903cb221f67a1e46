//! Observed convergence orders: every integrator, on the pendulum (closed form by Jacobi elliptic
//! functions) and on the Kepler problem with e = 0.5 (closed form by Kepler's equation).
//!
//! For each method the global error at the end time is measured at three step sizes h, h/2, h/4
//! chosen in the asymptotic range (errors far above rounding, far below O(1)); the observed order is
//! the least-squares slope of log(error) against log(h) and must be within 0.1 of the nominal order.

use super::problems::*;
use noether_core::prelude::*;

pub const THETA0: f64 = 1.5;
pub const T_PENDULUM: f64 = 10.0;
pub const ECC: f64 = 0.5;
pub const T_KEPLER: f64 = 5.0;

/// Errors against `exact` = (q, v) at t_end for n steps in `ns`.
pub fn errors_vs<S: Stepper>(
    mut make: impl FnMut() -> S,
    start: &State<S::Partner>,
    t_end: f64,
    exact: &(Vec<f64>, Vec<f64>),
    ns: &[usize],
) -> Vec<(f64, f64)> {
    ns.iter()
        .map(|&n| {
            let h = t_end / n as f64;
            let end = run(&mut make(), start.clone(), h, n);
            (h, distance(&end, &exact.0, &exact.1))
        })
        .collect()
}

/// Errors at t_end for n steps in `ns` against the pendulum (θ₀ = [`THETA0`]) or Kepler (e = [`ECC`])
/// closed form, by the dimension of `start`.
pub fn errors<S: Stepper>(
    make: impl FnMut() -> S,
    start: &State<S::Partner>,
    t_end: f64,
    ns: &[usize],
) -> Vec<(f64, f64)> {
    let exact = |t: f64| -> (Vec<f64>, Vec<f64>) {
        if start.q.len() == 1 {
            let (q, v) = pendulum_exact(THETA0, t);
            (vec![q], vec![v])
        } else {
            let (q, p) = kepler_exact(ECC, t);
            (q.to_vec(), p.to_vec())
        }
    };
    errors_vs(make, start, t_end, &exact(t_end), ns)
}

/// Least-squares slope of log(err) against log(h) ([`noether_core::selfcheck::fit_order`]).
pub fn fitted_order(e: &[(f64, f64)]) -> f64 {
    noether_core::selfcheck::fit_order(e)
        .expect("errors to fit")
        .slope
}

pub fn assert_order(what: &str, nominal: u32, e: &[(f64, f64)]) {
    let p = fitted_order(e);
    eprintln!("{what}: observed order {p:.3} (nominal {nominal}); errors {e:?}");
    assert!(
        e.iter().all(|(_, err)| *err > 1e-12),
        "{what}: errors too close to rounding: {e:?}"
    );
    assert!(
        (p - nominal as f64).abs() <= 0.1,
        "{what}: observed order {p:.3}, nominal {nominal}; errors {e:?}"
    );
}

pub fn pendulum_start<K: Partner>() -> State<K> {
    State::from_parts(0.0, [THETA0], [0.0])
}

/// Asserts the observed order on the pendulum (steps `np`) and on Kepler (steps `nk`).
pub fn check_both<S: Stepper, T: Stepper>(
    what: &str,
    nominal: u32,
    pend: impl FnMut() -> S,
    np: &[usize],
    kep: impl FnMut() -> T,
    nk: &[usize],
) {
    let e = errors(pend, &pendulum_start(), T_PENDULUM, np);
    assert_order(&format!("{what} / pendulum"), nominal, &e);
    let e = errors(kep, &kepler_start(ECC), T_KEPLER, nk);
    assert_order(&format!("{what} / Kepler e=0.5"), nominal, &e);
}

/// One `order_*` test per row: `name: "label", order p, constructor, pendulum system [step counts],
/// Kepler system [step counts];` runs [`check_both`] (observed order within 0.1 of p on both).
macro_rules! order_tests {
    ($($(#[$note:meta])* $test:ident: $what:literal, order $p:literal, $new:path,
        $pend:expr, $np:expr, $kep:expr, $nk:expr;)*) => {$(
        $(#[$note])*
        #[test]
        fn $test() {
            $crate::integrators::order::check_both($what, $p, || $new($pend), &$np, || $new($kep), &$nk);
        }
    )*};
}
pub(crate) use order_tests;

/// The Euler-Lagrange equations of a Lagrangian written by the user (AD path).
fn lagrangian<L: Lagrangian>(l: L) -> EulerLagrange<L> {
    EulerLagrange::new(l)
}

/// Symplectic methods: the pendulum as a Natural system on (q, q̇).
fn pend() -> Natural<PendulumV> {
    Natural::unit(PendulumV)
}
/// Symplectic methods: Kepler as a separable Hamiltonian on (q, p) (T(p) differentiated by AD), so
/// both readings are covered.
fn kep() -> SeparableHamiltonian<Natural<KeplerV>> {
    SeparableHamiltonian(Natural::unit(KeplerV))
}

order_tests! {
    order_euler: "Euler", order 1, Euler::new,
        lagrangian(PendulumL), [1280, 2560, 5120], lagrangian(KeplerL), [10240, 20480, 40960];
    order_euler_cromer: "Euler-Cromer", order 1, EulerCromer::new,
        lagrangian(PendulumL), [320, 640, 1280], lagrangian(KeplerL), [2560, 5120, 10240];
    order_rk4: "RK4", order 4, Rk4::new,
        lagrangian(PendulumL), [320, 640, 1280], lagrangian(KeplerL), [1280, 2560, 5120];
    order_symplectic_euler: "symplectic Euler", order 1, SymplecticEuler::new,
        pend(), [320, 640, 1280], kep(), [2560, 5120, 10240];
    order_stormer_verlet: "Störmer-Verlet", order 2, Composition::stormer_verlet,
        pend(), [80, 160, 320], kep(), [320, 640, 1280];
    order_yoshida4: "Yoshida 4", order 4, Composition::yoshida4,
        pend(), [160, 320, 640], kep(), [320, 640, 1280];
    order_suzuki4: "Suzuki 4", order 4, Composition::suzuki4,
        pend(), [80, 160, 320], kep(), [160, 320, 640];
    order_yoshida6: "Yoshida 6", order 6, Composition::yoshida6,
        pend(), [80, 160, 320], kep(), [160, 320, 640];
    order_kahan_li6: "Kahan-Li 6", order 6, Composition::kahan_li6,
        pend(), [40, 80, 160], kep(), [160, 320, 640];
    /// Order 8 reaches rounding fast: step ratios of √2 keep all errors in 1e-7 .. 1e-11.
    order_kahan_li8: "Kahan-Li 8", order 8, Composition::kahan_li8,
        pend(), [24, 34, 48], kep(), [56, 80, 112];
}
