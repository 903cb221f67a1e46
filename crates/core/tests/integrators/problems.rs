//! Test problems with closed-form solutions: the pendulum (Jacobi elliptic functions) and the Kepler
//! problem (Kepler's equation), each written as a potential, a Lagrangian and a Hamiltonian.

use noether_core::prelude::*;

/// Pendulum with m = l = g = 1: V(θ) = −cos θ.
pub struct PendulumV;
impl Potential for PendulumV {
    fn dof(&self) -> usize {
        1
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        -q[0].cos()
    }
}

/// Pendulum Lagrangian L = ½ θ̇² + cos θ.
pub struct PendulumL;
impl Lagrangian for PendulumL {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * v[0] * 0.5 + q[0].cos()
    }
}

/// Pendulum Hamiltonian H = ½ p² − cos θ.
pub struct PendulumH;
impl Hamiltonian for PendulumH {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        p[0] * p[0] * 0.5 - q[0].cos()
    }
}

/// Harmonic oscillator V = ½ q² (closed form q = q₀ cos t + v₀ sin t).
pub struct HarmonicV;
impl Potential for HarmonicV {
    fn dof(&self) -> usize {
        1
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        q[0] * q[0] * 0.5
    }
}

/// Kepler problem with μ = m = 1: V(q) = −1/|q|.
pub struct KeplerV;
impl Potential for KeplerV {
    fn dof(&self) -> usize {
        2
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        -(q[0] * q[0] + q[1] * q[1]).sqrt().recip()
    }
}

/// Kepler Lagrangian L = ½ |q̇|² + 1/|q|.
pub struct KeplerL;
impl Lagrangian for KeplerL {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] + v[1] * v[1]) * 0.5 + (q[0] * q[0] + q[1] * q[1]).sqrt().recip()
    }
}

/// Kepler Hamiltonian H = ½ |p|² − 1/|q|.
pub struct KeplerH;
impl Hamiltonian for KeplerH {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        (p[0] * p[0] + p[1] * p[1]) * 0.5 - (q[0] * q[0] + q[1] * q[1]).sqrt().recip()
    }
}

/// Complete elliptic integral K(m) of the parameter m = k² (the testkit's, by the complementary
/// modulus √(1 − m)).
pub fn elliptic_k(m: f64) -> f64 {
    noether_testkit::closed_form::elliptic_k_complementary((1.0 - m).sqrt())
}

/// Pendulum released from rest at θ₀ (|θ₀| < π): sin(θ/2) = k sn(K − t | k²), θ̇ = −2k cn(K − t | k²),
/// with k = sin(θ₀/2). Returns (θ, θ̇) at time t.
pub fn pendulum_exact(theta0: f64, t: f64) -> (f64, f64) {
    let k = (theta0 / 2.0).sin();
    let m = k * k;
    let (sn, cn, _) = noether_testkit::closed_form::jacobi_sn_cn_dn(elliptic_k(m) - t, m, 1.0 - m);
    (2.0 * (k * sn).asin(), -2.0 * k * cn)
}

/// Kepler orbit with semi-major axis 1 and eccentricity e, starting at pericentre on the x axis
/// (q = (1 − e, 0), p = (0, √((1+e)/(1−e)))): solves Kepler's equation E − e sin E = t by Newton and
/// returns (q, p) = ((cos E − e, √(1−e²) sin E), (−sin E, √(1−e²) cos E)/(1 − e cos E)).
pub fn kepler_exact(e: f64, t: f64) -> ([f64; 2], [f64; 2]) {
    let mut big_e = t + e * t.sin();
    for _ in 0..50 {
        let d = (big_e - e * big_e.sin() - t) / (1.0 - e * big_e.cos());
        big_e -= d;
        if d.abs() < 1e-16 {
            break;
        }
    }
    let (s, c) = big_e.sin_cos();
    let w = (1.0 - e * e).sqrt();
    let r = 1.0 - e * c;
    ([c - e, w * s], [-s / r, w * c / r])
}

/// Initial state of [`kepler_exact`].
pub fn kepler_start<K: Partner>(e: f64) -> State<K> {
    let (q, p) = kepler_exact(e, 0.0);
    State::from_parts(0.0, q, p)
}

/// Max-norm distance between a state and (q, v).
pub fn distance<K: Partner>(s: &State<K>, q: &[f64], v: &[f64]) -> f64 {
    s.q.iter()
        .zip(q)
        .chain(s.v.iter().zip(v))
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()))
}

/// Takes `n` steps of size `h` from `state`.
pub fn run<S: Stepper>(stepper: &mut S, mut state: State<S::Partner>, h: f64, n: usize) -> State<S::Partner> {
    for _ in 0..n {
        stepper.step(&mut state, h).expect("step failed");
    }
    state
}

/// Steps `stepper` adaptively from `state` (first step `h`, then each step's proposal) until a step
/// fails, and returns that error, checking that the failing step left the state exactly as it was and
/// that no failure came before `t_end` was passed ("no failure before `what`" otherwise).
pub fn step_until_failure<S: Stepper>(
    stepper: &mut S,
    state: &mut State<S::Partner>,
    mut h: f64,
    t_end: f64,
    what: &str,
) -> Error {
    loop {
        let before = state.clone();
        match stepper.step(state, h) {
            Ok(info) => h = info.h_next,
            Err(e) => {
                assert_eq!(*state, before);
                return e;
            }
        }
        assert!(state.t < t_end, "no failure before {what}");
    }
}

#[test]
fn closed_form_pendulum_reference_is_consistent() {
    // Small amplitude: θ ≈ θ₀ cos t to O(θ₀³); the exact form must also conserve H = ½θ̇² − cos θ
    // to rounding (1e-14) and have period 4K(k²).
    let (th, _) = pendulum_exact(1e-4, 1.3);
    assert!((th - 1e-4 * 1.3f64.cos()).abs() < 1e-12);
    let theta0 = 2.0_f64;
    let e0 = -theta0.cos();
    for i in 0..50 {
        let (q, v) = pendulum_exact(theta0, 0.37 * i as f64);
        assert!((0.5 * v * v - q.cos() - e0).abs() < 1e-14, "energy at sample {i}");
    }
    let period = 4.0 * elliptic_k((theta0 / 2.0).sin().powi(2));
    let (q, v) = pendulum_exact(theta0, period);
    assert!((q - theta0).abs() < 1e-13 && v.abs() < 1e-13);
}

#[test]
fn closed_form_kepler_reference_is_consistent() {
    // Energy −1/2 (a = 1) and angular momentum √(1 − e²) along the exact orbit.
    let e = 0.5;
    for i in 0..20 {
        let (q, p) = kepler_exact(e, 0.41 * i as f64);
        let r = (q[0] * q[0] + q[1] * q[1]).sqrt();
        let energy = 0.5 * (p[0] * p[0] + p[1] * p[1]) - 1.0 / r;
        assert!((energy + 0.5).abs() < 1e-14);
        assert!((q[0] * p[1] - q[1] * p[0] - (1.0 - e * e).sqrt()).abs() < 1e-14);
    }
}
