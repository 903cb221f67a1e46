//! Lyapunov spectra by Benettin's method (noether_analysis::Lyapunov) on systems whose spectra are
//! known: the harmonic oscillator and a regular Hénon-Heiles orbit (all exponents zero, approached like
//! ln t / t or faster), chaotic Hénon-Heiles at E = 1/6 and the double pendulum released from the
//! horizontal (λ₁ > 0), and the Hamiltonian pairing λ_i + λ_{2n+1−i} = 0, Σλ_i = 0.
//!
//! Method: RK4 with its exact step Jacobians (not symplectic: Σλ_i is RK4's own contraction,
//! ln det Ψ / h per unit time, of order h⁵ — see `oscillator_spectrum_vanishes`).

use noether_analysis::{Error, Lyapunov, Spectrum};
use noether_core::prelude::*;
use noether_testkit::henon_heiles::{on_section, HenonHeiles, UnitDoublePendulum};

/// H = ½(p² + ω² q²).
#[derive(Debug, Clone, Copy)]
struct Oscillator {
    omega: f64,
}
impl Hamiltonian for Oscillator {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        (p[0] * p[0] + q[0] * q[0] * self.omega.powi(2)) * 0.5
    }
}

/// A Hénon-Heiles state with q = (0, q₂), p₂ = `p2` and p₁ > 0 from the energy E.
pub(crate) fn hh_state(e: f64, q2: f64, p2: f64) -> State<Momenta> {
    on_section(e, q2, p2).expect("a point on the energy surface")
}

/// The running estimate at (the re-orthonormalisation nearest to) time t.
fn at(lyap: &Lyapunov<impl TangentStepper>, t: f64) -> Vec<f64> {
    let h = lyap.history();
    let i = h.partition_point(|(s, _)| *s < t - 1e-9);
    h[i.min(h.len() - 1)].1.clone()
}

/// max_i |λ_i(t)| · t / ln t: the constant c of the bound |λ| ≤ c ln t / t.
fn c_of(lambda: &[f64], t: f64) -> f64 {
    lambda.iter().fold(0.0f64, |m, l| m.max(l.abs())) * t / t.ln()
}

/// (λ₁ + λ₄)(t) · t and (λ₂ + λ₃)(t) · t: the pairing defect accumulated up to t.
fn pair_defects(lyap: &Lyapunov<impl TangentStepper>, t: f64) -> [f64; 2] {
    let l = at(lyap, t);
    [(l[0] + l[3]) * t, (l[1] + l[2]) * t]
}

fn print(name: &str, s: &Spectrum) {
    println!(
        "{name}: λ = {:?} ± {:?}, pairs {:?} ± {:?}, Σ = {:e} ± {:e} (t = {})",
        s.exponents, s.errors, s.pair_sums, s.pair_errors, s.sum, s.sum_error, s.time
    );
}

/// The oscillator's flow is a rotation of (ωq, p): a tangent vector's length changes by at most the
/// factor max(ω, 1/ω) between the two axes, so λ₁(t) ≤ ln max(ω, 1/ω) / t — all exponents → 0 like 1/t,
/// faster than ln t / t. Checked at t = 10³ and 10⁴: measured λ₁ t = 0.560 and 0.405 ≤ ln 2 = 0.693
/// (ω = 2), so |λ| ≤ c ln t / t with c = 0.1 (measured 0.081 at 10³, 0.044 at 10⁴).
///
/// The sum λ₁ + λ₂ is RK4's contraction: on a linear system Ψ is the same every step, RK4's
/// stability polynomial of hA, with det Ψ = 1 − x⁶/72 + x⁸/576 (x = hω), so Σλ = ln det Ψ / h exactly
/// up to rounding of the accumulated logs (measured relative difference 8.8e-9; checked to 1e-7).
#[test]
fn oscillator_spectrum_vanishes() {
    let (omega, h) = (2.0, 0.05);
    let rk4 = Rk4::new(HamiltonEquations::new(Oscillator { omega }));
    let mut lyap = Lyapunov::new(rk4, State::with_momenta(0.0, [1.0], [0.0]), 2, h, 10).unwrap();
    lyap.advance_to(1e4).unwrap();
    for t in [1e3, 1e4] {
        let lambda = at(&lyap, t);
        println!(
            "oscillator t = {t}: λ = {lambda:?}, λ₁ t = {}, c = {}",
            lambda[0] * t,
            c_of(&lambda, t)
        );
        assert!(lambda[0] * t <= omega.ln(), "λ₁ t = {} above ln ω", lambda[0] * t);
        assert!(c_of(&lambda, t) < 0.1);
    }
    let s = lyap.spectrum(10).unwrap();
    print("oscillator", &s);
    let x: f64 = h * omega;
    let contraction = (1.0 - x.powi(6) / 72.0 + x.powi(8) / 576.0).ln() / h;
    println!("Σλ = {:e}, ln det Ψ / h = {contraction:e}", s.sum);
    assert!((s.sum - contraction).abs() < 1e-7 * contraction.abs());
}

/// A regular Hénon-Heiles orbit at E = 1/12 (q = (0, 0.1), p₂ = 0, on a torus): tangent vectors grow
/// linearly by the shear of the torus and λ_i(t) → 0 like ln t / t. Measured max_i |λ_i| t / ln t =
/// 0.65 at t = 2·10³ and 0.70 at t = 2·10⁴ (the constant is ln of the shear rate, an O(1) number):
/// checked with c = 1.
#[test]
fn regular_henon_heiles_vanishes() {
    let rk4 = Rk4::new(HamiltonEquations::new(HenonHeiles));
    let mut lyap = Lyapunov::new(rk4, hh_state(1.0 / 12.0, 0.1, 0.0), 4, 0.05, 10).unwrap();
    lyap.advance_to(2e4).unwrap();
    for t in [2e3, 2e4] {
        let lambda = at(&lyap, t);
        println!("regular HH t = {t}: λ = {lambda:?}, c = {}", c_of(&lambda, t));
        assert!(c_of(&lambda, t) < 1.0);
    }
}

/// Classical two-trajectory Benettin estimate of λ₁: a shadow orbit d₀ = 1e-9 away, both stepped by
/// plain RK4 steps, the separation measured and rescaled to d₀ every `every` steps.
fn two_trajectory(state: &State<Momenta>, h: f64, every: usize, t_end: f64) -> f64 {
    let mut rk4 = Rk4::new(HamiltonEquations::new(HenonHeiles));
    let d0 = 1e-9;
    let mut a = state.clone();
    let mut b = state.clone();
    b.q[0] += d0;
    let mut sum = 0.0;
    let steps = (t_end / h).round() as usize;
    for i in 1..=steps {
        rk4.step(&mut a, h).unwrap();
        rk4.step(&mut b, h).unwrap();
        if i % every == 0 {
            let d = ((&b.q - &a.q).norm_squared() + (&b.v - &a.v).norm_squared()).sqrt();
            sum += (d / d0).ln();
            b.q = &a.q + (&b.q - &a.q) * (d0 / d);
            b.v = &a.v + (&b.v - &a.v) * (d0 / d);
        }
    }
    sum / (steps as f64 * h)
}

/// Chaotic Hénon-Heiles at E = 1/6 from q = (0, −0.1), p₂ = 0 (in the chaotic sea of the section
/// q₁ = 0): λ₁ clearly positive. Measured over t = 2·10⁴ (h = 0.05, m = 10, 10 blocks):
/// λ = (0.1253 ± 0.0045, 0.0004 ± 0.0003, −0.0004 ± 0.0003, −0.1253 ± 0.0045). (The 0.04–0.05 often quoted
/// for Hénon-Heiles is at E = 1/8; the sea at E = 1/6 is more unstable.) Checked: λ₁ > 20 σ and
/// λ₁ ∈ [0.10, 0.16]; the two middle exponents (flow direction and energy gradient) → 0 like a regular
/// orbit's: measured max(|λ₂|, |λ₃|) = 1.05 ln t / t, checked ≤ 2 ln t / t.
///
/// Cross-check by the classical two-trajectory method (a shadow orbit 1e-9 away, renormalised every 10
/// steps) on the same orbit: the two estimates differ by the shadow's finite size and the directions'
/// transients, O(1/t); measured difference 6e-5, checked to 0.005 (about the statistical error).
///
/// Pairing: λ₁ + λ₄ and λ₂ + λ₃ are zero within 3 of their block errors (measured |pair| ≈ 1.6e-5 =
/// 1.0 σ). The defect is not noise but the start-up transient of the initial frame, a fixed amount D
/// (D = −0.3137, +0.3129) in the sums, all of it in the first block (hence |pair| = σ exactly: one block
/// of ten nonzero): D = (λ_i + λ_{2n+1−i}) t is the same at t/2 and t to 1e-2 (measured 1.9e-3, the
/// later steps pair to rounding), and it vanishes when the transient is discarded. And Σλ is RK4's contraction (not a statistical error: det Ψ < 1 by O(h⁶) every step), measured
/// −4.0e-8, checked |Σλ| < 1e-7 (with a symplectic method it would be rounding).
#[test]
fn chaotic_henon_heiles() {
    let (h, t_end) = (0.05, 2e4);
    let start = hh_state(1.0 / 6.0, -0.1, 0.0);
    let rk4 = Rk4::new(HamiltonEquations::new(HenonHeiles));
    let mut lyap = Lyapunov::new(rk4, start.clone(), 4, h, 10).unwrap();
    lyap.advance_to(t_end).unwrap();
    let s = lyap.spectrum(10).unwrap();
    print("chaotic HH", &s);
    assert!(s.exponents[0] > 20.0 * s.errors[0]);
    assert!((0.10..0.16).contains(&s.exponents[0]));
    let bound = 2.0 * t_end.ln() / t_end;
    assert!(s.exponents[1].abs() < bound && s.exponents[2].abs() < bound);
    for (pair, err) in s.pair_sums.iter().zip(&s.pair_errors) {
        assert!(pair.abs() < 3.0 * err, "pair sum {pair:e} vs error {err:e}");
    }
    assert!(s.sum.abs() < 1e-7);
    let (half, full) = (pair_defects(&lyap, t_end / 2.0), pair_defects(&lyap, t_end));
    println!("HH pair defects · t at t/2: {half:?}, at t: {full:?}");
    for (a, b) in half.iter().zip(full) {
        assert!((a - b).abs() < 1e-2 * b.abs());
    }
    let classical = two_trajectory(&start, h, 10, t_end);
    println!(
        "two-trajectory λ₁ = {classical}, difference {:e}",
        classical - s.exponents[0]
    );
    assert!((classical - s.exponents[0]).abs() < 0.005);
}

/// The double pendulum (unit masses and rods, g = 9.81) released at rest from the horizontal,
/// θ₁ = θ₂ = π/2 (energy 0, the lower bob can flip): chaotic. RK4 with h = 2e-3 (the fast phases have
/// time scale sqrt(l/g) ≈ 0.3; energy drift below 1e-6 over the run) to t = 400, m = 5, 10 blocks.
/// Measured λ = (0.935 ± 0.048, 0.017 ± 0.016, −0.020 ± 0.018, −0.931 ± 0.049), Σ = −3.0e-9 (RK4's
/// contraction), energy error −7.8e-6 at the end. Checked: λ₁ > 10 σ (measured 19 σ); pairing within 3
/// block errors (measured 1.0 σ: the whole defect is the start-up transient, D = 1.3266 = pair · t at
/// t = 100, 200 and 400 to 1e-6 — checked to 1e-3 between t/2 and t); after discarding the transient
/// (the first 20 time units) the pairs of the rest of the run, λ = (0.946, 0.0094, −0.0094, −0.946), are
/// zero to RK4's own contraction Σ = −3.1e-9: measured −8.4e-9 and 5.3e-9, checked < 3e-8 (with a
/// symplectic method both would be rounding).
#[test]
fn double_pendulum_from_horizontal() {
    let h = 2e-3;
    let half = std::f64::consts::FRAC_PI_2;
    let rk4 = || Rk4::new(HamiltonEquations::new(UnitDoublePendulum { g: 9.81 }));
    let start = State::with_momenta(0.0, [half, half], [0.0, 0.0]);
    let mut lyap = Lyapunov::new(rk4(), start.clone(), 4, h, 5).unwrap();
    lyap.advance_to(400.0).unwrap();
    // The same run with the first 20 time units discarded.
    let mut settled = Lyapunov::new(rk4(), start, 4, h, 5).unwrap();
    settled.advance_to(20.0).unwrap();
    settled.discard_transient().unwrap();
    settled.advance_to(400.0).unwrap();
    let rest = settled.spectrum(10).unwrap();
    print("double pendulum after t = 20", &rest);
    assert!(rest.pair_sums.iter().all(|p| p.abs() < 3e-8));
    let s = lyap.spectrum(10).unwrap();
    print("double pendulum", &s);
    let end = lyap.state();
    let energy = HamiltonEquations::new(UnitDoublePendulum { g: 9.81 })
        .energy(end.t, end.q.as_slice(), end.v.as_slice())
        .unwrap();
    println!("energy at the end {energy:e}");
    let (half, full) = (pair_defects(&lyap, 200.0), pair_defects(&lyap, 400.0));
    println!("DP pair defects · t at t/2: {half:?}, at t: {full:?}");
    for (a, b) in half.iter().zip(full) {
        assert!((a - b).abs() < 1e-3 * b.abs());
    }
    assert!(s.exponents[0] > 10.0 * s.errors[0]);
    for (pair, err) in s.pair_sums.iter().zip(&s.pair_errors) {
        assert!(pair.abs() < 3.0 * err, "pair sum {pair:e} vs error {err:e}");
    }
}

/// Bad settings are typed errors: k outside 1..=2n, m = 0, a run too short for its blocks, a step
/// that is not finite.
#[test]
fn bad_settings() {
    let rk4 = || Rk4::new(HamiltonEquations::new(HenonHeiles));
    let s = hh_state(1.0 / 12.0, 0.1, 0.0);
    assert!(matches!(
        Lyapunov::new(rk4(), s.clone(), 5, 0.05, 10),
        Err(Error::TangentVectors {
            requested: 5,
            dimension: 4
        })
    ));
    assert!(matches!(
        Lyapunov::new(rk4(), s.clone(), 0, 0.05, 10),
        Err(Error::TangentVectors { requested: 0, .. })
    ));
    assert!(matches!(
        Lyapunov::new(rk4(), s.clone(), 2, 0.05, 0),
        Err(Error::ReorthonormalizationInterval { every: 0 })
    ));
    assert!(matches!(
        Lyapunov::new(rk4(), s.clone(), 2, f64::NAN, 1),
        Err(Error::Core(_))
    ));
    let mut lyap = Lyapunov::new(rk4(), s, 2, 0.05, 10).unwrap();
    lyap.advance(25).unwrap();
    assert_eq!(lyap.reorthonormalizations(), 2);
    assert!(matches!(
        lyap.spectrum(3),
        Err(Error::TooShort {
            reorthonormalizations: 2,
            blocks: 3
        })
    ));
    assert!(lyap.spectrum(2).is_ok());
    // Own tangent vectors: the wrong number of rows, or dependent columns, are refused.
    let own = |w| {
        Lyapunov::new(rk4(), hh_state(1.0 / 12.0, 0.1, 0.0), 2, 0.05, 10)
            .unwrap()
            .initial_vectors(w)
    };
    assert!(matches!(own(nalgebra::DMatrix::zeros(3, 2)), Err(Error::Core(_))));
    assert!(matches!(
        own(nalgebra::DMatrix::from_element(4, 2, 1.0)),
        Err(Error::TangentCollapse { index: 1, .. })
    ));
    let mut mine = own(nalgebra::DMatrix::identity(4, 1)).unwrap();
    mine.advance(10).unwrap();
    assert_eq!((mine.k(), mine.reorthonormalizations()), (1, 1));
}

/// Issue 29 item 7: from t₀ = 1e20 a step of 0.05 does not move t; the spectrum was ±inf (every block
/// logged with zero elapsed time). Now the first step is refused with `StepBelowTimeResolution`.
#[test]
fn regress_lyapunov_step_below_time_resolution() {
    let rk4 = Rk4::new(HamiltonEquations::new(Oscillator { omega: 2.0 }));
    let mut lyap = Lyapunov::new(rk4, State::with_momenta(1e20, [1.0], [0.0]), 2, 0.05, 10).unwrap();
    let err = lyap.advance(20).unwrap_err();
    assert_eq!(
        err,
        Error::Core(noether_core::Error::StepBelowTimeResolution { t: 1e20, h: 0.05 }),
        "{err}"
    );
}
