//! MEGNO and the fast Lyapunov indicator (noether_analysis::Megno) against closed forms: exponential
//! growth (the inverted oscillator), bounded deviations (the harmonic oscillator), the linear growth of
//! a shear (the free particle); on Hénon-Heiles, ⟨Y⟩ → 2 on a torus and ⟨Y⟩ ≈ λt/2 in the chaotic sea
//! with λ from Benettin's method; stability maps over a grid and the error contract.
//!
//! Method throughout: RK4 with its exact step Jacobians, fixed steps.

use crate::lyapunov::hh_state;
use noether_analysis::{stability_map, Error, Lyapunov, Megno};
use noether_core::prelude::*;
use noether_ensemble::{Axis, Grid, Members};
use noether_testkit::henon_heiles::{on_section, HenonHeiles};
use std::f64::consts::PI;

/// H = ½(p² + k q²): an oscillator of frequency √k for k > 0, inverted (rate √−k) for k < 0, a free
/// particle for k = 0.
#[derive(Debug, Clone, Copy)]
struct Quadratic {
    k: f64,
}
impl Hamiltonian for Quadratic {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        (p[0] * p[0] + q[0] * q[0] * self.k) * 0.5
    }
}

fn megno_of(k: f64, h: f64, deviation: [f64; 2]) -> Megno<Rk4<HamiltonEquations<Quadratic>>> {
    let rk4 = Rk4::new(HamiltonEquations::new(Quadratic { k }));
    Megno::new(rk4, State::with_momenta(0.0, [0.0], [0.0]), h)
        .unwrap()
        .initial_vector(&deviation)
        .unwrap()
}

/// The inverted oscillator ẍ = x: along the unstable eigenvector (1, 1) the deviation grows by RK4's
/// stability polynomial R(h) = 1 + h + h²/2 + h³/6 + h⁴/24 every step (Ψ = R(hA) has the eigenvectors
/// of A), so ln|δ| is exactly linear in time with rate λ_h = ln R(h)/h and the discrete sums are exact:
/// Y = λ_h s, ⟨Y⟩ = λ_h s/2, FLI = λ_h s (module docs of `chaos`). The only error is the rounding of
/// the N = 2000 added logs and of the weights, relative ~N ε: measured relative errors ≤ 3e-15, checked to
/// 1e-13.
#[test]
fn exponential_growth_gives_half_lambda_t() {
    let (h, s) = (0.01, 20.0);
    let mut megno = megno_of(-1.0, h, [1.0, 1.0]);
    megno.advance_to(s).unwrap();
    let ind = megno.indicators();
    let lambda = (1.0 + h + h * h / 2.0 + h.powi(3) / 6.0 + h.powi(4) / 24.0).ln() / h;
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs();
    println!(
        "inverted: Y {:e}, ⟨Y⟩ {:e}, FLI {:e}, λ {:e} (relative errors)",
        rel(ind.megno, lambda * s),
        rel(ind.mean_megno, lambda * s / 2.0),
        rel(ind.fli, lambda * s),
        rel(ind.lyapunov, lambda)
    );
    assert!((ind.elapsed - s).abs() < 1e-12);
    assert!(rel(ind.megno, lambda * s) < 1e-13);
    assert!(rel(ind.mean_megno, lambda * s / 2.0) < 1e-13);
    assert!(rel(ind.fli, lambda * s) < 1e-13);
    assert!(rel(ind.lyapunov, lambda) < 1e-13);
}

/// The inverse tangent integral Ti₂(x) = Σ (−1)^k x^{2k+1}/(2k+1)² for 0 ≤ x ≤ 1.
fn ti2(x: f64) -> f64 {
    (0..200)
        .map(|k| (-1f64).powi(k) * x.powi(2 * k + 1) / f64::from(2 * k + 1).powi(2))
        .sum()
}

/// The free particle H = p²/2 is the pure shear of the tori: δ₀ = (0, 1) in (q, p) becomes (s, 1),
/// f = ln|δ| = ½ ln(1 + s²). Closed forms: J = ∫ σ f′ dσ = s − arctan s, so Y(s) = 2 − 2 arctan(s)/s, and
/// ⟨Y⟩(s) = 2 − (2/s) ∫₀ˢ arctan(σ)/σ dσ = 2 − (2/s)[(π/2) ln s + Ti₂(1/s)] (s ≥ 1; Ti₂(x) − Ti₂(1/x) =
/// (π/2) ln x) → 2 like ln s / s.
///
/// RK4 is exact on this flow, so the only error is the midpoint weighting of the discrete sums: per
/// step ∫(σ − s̄) f′ dσ = h³ f″(s̄)/12, which adds up to Y_disc − Y = −(h²/6) f′(s)/s = −h²/(6(1 + s²))
/// and ⟨Y⟩_disc − ⟨Y⟩ = −(h²/(6s)) ∫₀ˢ f′(σ)/σ dσ = −h² arctan(s)/(6s) (about 2.6e-7 at h = 0.01), plus
/// higher orders. Checked at h = 0.01 and 0.005: Y against the corrected closed form (remainder
/// measured 2e-13, checked to 1e-11), and the remainder of ⟨Y⟩ after the h² correction, which is
/// O(h³) (measured 8.6e-10 and 1.1e-10: 0.86 h³ and 0.88 h³, ratio 7.8): checked below h³ and falling
/// by more than 6 when h halves, so the h² term is the whole leading error.
#[test]
fn shear_of_a_torus_gives_two() {
    let s: f64 = 100.0;
    let exact_y = 2.0 - 2.0 * s.atan() / s;
    let exact_mean = 2.0 - (2.0 / s) * (0.5 * PI * s.ln() + ti2(1.0 / s));
    let mut remainders = Vec::new();
    for h in [0.01_f64, 0.005] {
        let mut megno = megno_of(0.0, h, [0.0, 1.0]);
        megno.advance_to(s).unwrap();
        let ind = megno.indicators();
        let y_model = exact_y - h * h / (6.0 * (1.0 + s * s));
        let mean_model = exact_mean - h * h * s.atan() / (6.0 * s);
        println!(
            "shear h = {h}: Y {} (closed form {exact_y}, remainder {:e}), ⟨Y⟩ {} (closed form {exact_mean}, \
             remainder {:e}), FLI {}",
            ind.megno,
            ind.megno - y_model,
            ind.mean_megno,
            ind.mean_megno - mean_model,
            ind.fli
        );
        assert!((ind.megno - y_model).abs() < 1e-11);
        assert!((ind.mean_megno - mean_model).abs() < h.powi(3));
        // FLI = sup ln|δ| = ½ ln(1 + s²): |δ| grows monotonically here, and RK4 is exact.
        assert!((ind.fli - 0.5 * (1.0 + s * s).ln()).abs() < 1e-12);
        remainders.push(ind.mean_megno - mean_model);
    }
    println!("⟨Y⟩ remainder ratio h → h/2: {}", remainders[0] / remainders[1]);
    assert!(remainders[0] / remainders[1] > 6.0);
}

/// The harmonic oscillator H = ½(p² + ω²q²), ω = 2: isochronous, the deviation stays bounded. With δ₀ =
/// (1, 0), |δ|² = cos²ωs + ω² sin²ωs, f = ln|δ| ∈ [0, ln ω], whose mean over a period π/ω is
/// m = ln((1 + ω)/2) (∫ ln(a + b cos θ) dθ/2π = ln((a + √(a² − b²))/2)). At whole periods f = 0 and the
/// mean of f so far is m, so Y = 2(f − f̄) = −2 ln((1 + ω)/2) = −0.8109 exactly: Y does not tend to 0
/// but oscillates, and ⟨Y⟩ → 0 like ln s/s: |⟨Y⟩| ≤ (2/s)[max|P| (1 + ln s) + ln ω] with
/// P(σ) = ∫₀^σ (f − m), |P| ≤ (π/ω) ln ω (bounded, as f − m is periodic with zero mean).
///
/// RK4 with h = (π/ω)/160 ≈ 0.01 (x = hω ≈ 0.02; whole periods are whole steps): its contraction ln|R(ix)|/h ≈ −x⁶/(72h) ~ −10⁻⁹ per unit time and
/// the midpoint weighting O(h²) = 10⁻⁴ of f″ leave Y at whole periods off by ~1e-5 (measured 4e-6): checked to
/// 1e-4, and the ⟨Y⟩ bound at s = 10³ (measured |⟨Y⟩| = 2e-4 against the bound 0.019).
#[test]
fn bounded_deviation_gives_zero() {
    let omega = 2.0_f64;
    let period = PI / omega;
    let h = period / 160.0;
    let mut megno = megno_of(omega * omega, h, [1.0, 0.0]);
    let whole = -2.0 * ((1.0 + omega) / 2.0).ln();
    for k in [10, 100, 500] {
        megno.advance_to(k as f64 * period).unwrap();
        let ind = megno.indicators();
        println!(
            "oscillator at {k} periods: Y = {} (closed form {whole})",
            ind.megno
        );
        assert!((ind.megno - whole).abs() < 1e-4);
    }
    let s = 1e3;
    megno.advance_to(s).unwrap();
    let ind = megno.indicators();
    let bound = (2.0 / s) * ((PI / omega) * omega.ln() * (1.0 + s.ln()) + omega.ln());
    println!("oscillator ⟨Y⟩({s}) = {:e}, bound {bound}", ind.mean_megno);
    assert!(ind.mean_megno.abs() < bound);
    assert!(ind.fli <= omega.ln() + 1e-9);
}

/// Hénon-Heiles on the torus of `regular_henon_heiles_vanishes` (E = 1/12, q = (0, 0.1), p₂ = 0): ⟨Y⟩ → 2.
/// The deviation's length is the shear's linear growth times a bounded oscillation along the torus
/// (the two of `shear_of_a_torus_gives_two` and `bounded_deviation_gives_zero` at once): Y itself keeps
/// oscillating (1.5–1.8 here) and ⟨Y⟩ approaches 2 slowly, not monotonically. Measured
/// |⟨Y⟩ − 2| = 0.025, 0.014, 0.0087 at t = 10³, 10⁴, 3·10⁴ (and 0.0037 at 10⁵), h = 0.05: checked that
/// the gap shrinks from 10⁴ to 3·10⁴ and is below 0.01 at 3·10⁴, a chaotic orbit being at ⟨Y⟩ ~ 10³
/// by then (next test).
#[test]
fn henon_heiles_torus_gives_two() {
    let rk4 = Rk4::new(HamiltonEquations::new(HenonHeiles));
    let mut megno = Megno::new(rk4, hh_state(1.0 / 12.0, 0.1, 0.0), 0.05).unwrap();
    let mut gaps = Vec::new();
    for t in [1e3_f64, 1e4, 3e4] {
        megno.advance_to(t).unwrap();
        let ind = megno.indicators();
        println!(
            "HH torus t = {t}: ⟨Y⟩ = {}, Y = {}, FLI = {}",
            ind.mean_megno, ind.megno, ind.fli
        );
        gaps.push((ind.mean_megno - 2.0).abs());
    }
    assert!(gaps[2] < gaps[1] && gaps[2] < 0.01, "|⟨Y⟩ − 2| = {gaps:?}");
}

/// Chaotic Hénon-Heiles (E = 1/6, q = (0, −0.1), p₂ = 0; the orbit of `chaotic_henon_heiles`): ln|δ|
/// grows at λ₁, so ⟨Y⟩ ≈ λ₁t/2 and its slope over the second half of the run, 2(⟨Y⟩(t) − ⟨Y⟩(t/2))/(t/2),
/// estimates λ₁. Against Benettin's λ₁ on the same orbit (four vectors, t = 2·10⁴, 10 blocks: measured
/// 0.1253 ± 0.0045): measured slope estimate 0.1322, 1.5 σ off; checked to 3 σ of Benettin's error. (⟨Y⟩
/// is 1281 at t = 2·10⁴, against 2 on a torus.)
///
/// And the plumbing: with one Benettin vector started along the same deviation, Benettin's λ₁ and
/// MEGNO's ln|δ|/t are the same numbers computed two ways (a product of Ψ's renormalised every 10 steps
/// against every step): equal to rounding, measured 3e-16 relative, checked to 1e-12.
#[test]
fn henon_heiles_chaos_gives_half_lambda_t() {
    let (h, t_end) = (0.05, 2e4);
    let start = hh_state(1.0 / 6.0, -0.1, 0.0);
    let rk4 = || Rk4::new(HamiltonEquations::new(HenonHeiles));
    let mut megno = Megno::new(rk4(), start.clone(), h).unwrap();
    megno.advance_to(t_end / 2.0).unwrap();
    let half = megno.indicators();
    megno.advance_to(t_end).unwrap();
    let full = megno.indicators();
    let slope: f64 = 2.0 * (full.mean_megno - half.mean_megno) / (t_end / 2.0);

    let mut lyap = Lyapunov::new(rk4(), start.clone(), 4, h, 10).unwrap();
    lyap.advance_to(t_end).unwrap();
    let spectrum = lyap.spectrum(10).unwrap();
    println!(
        "HH chaos: ⟨Y⟩ = {} at t/2, {} at t, λ from its slope {slope}, Benettin λ₁ = {} ± {}, FLI/t = {}",
        half.mean_megno,
        full.mean_megno,
        spectrum.exponents[0],
        spectrum.errors[0],
        full.fli / t_end
    );
    assert!((slope - spectrum.exponents[0]).abs() < 3.0 * spectrum.errors[0]);

    let v = Megno::new(rk4(), start.clone(), h).unwrap().deviation().clone();
    let mut one = Lyapunov::new(rk4(), start, 1, h, 10)
        .unwrap()
        .initial_vectors(nalgebra::DMatrix::from_column_slice(4, 1, v.as_slice()))
        .unwrap();
    one.advance_to(t_end).unwrap();
    let benettin = one.spectrum(2).unwrap().exponents[0];
    println!("ln|δ|/t = {}, Benettin (k = 1) = {benettin}", full.lyapunov);
    assert!((full.lyapunov - benettin).abs() < 1e-12 * benettin);
}

/// H = ½p² − q⁴: from q = 1 the particle runs to infinity in finite time (∫ dq/√(2q⁴) = 1/√2 from q = 1).
#[derive(Debug, Clone, Copy)]
struct Runaway;
impl Hamiltonian for Runaway {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        p[0] * p[0] * 0.5 - q[0].powi(4)
    }
}

/// Bad input is a typed error; a failing step leaves the run (state, deviation, indicators) as the
/// last good step left it, and fails again the same way.
#[test]
fn error_contract() {
    let rk4 = || Rk4::new(HamiltonEquations::new(Quadratic { k: 1.0 }));
    let start = State::with_momenta(0.0, [0.0], [1.0]);
    assert!(Megno::new(rk4(), start.clone(), 0.0).is_err());
    assert!(Megno::new(rk4(), start.clone(), f64::NAN).is_err());
    assert!(Megno::new(rk4(), State::with_momenta(0.0, [f64::NAN], [1.0]), 0.1).is_err());
    let m = || Megno::new(rk4(), start.clone(), 0.1).unwrap();
    assert!(matches!(
        m().initial_vector(&[1.0]),
        Err(Error::Core(noether_core::Error::Dimension {
            got: 1,
            expected: 2,
            ..
        }))
    ));
    assert!(matches!(
        m().initial_vector(&[0.0, 0.0]),
        Err(Error::DeviationLost { .. })
    ));
    assert!(m().initial_vector(&[f64::INFINITY, 0.0]).is_err());
    assert!(m().advance_to(f64::NAN).is_err());

    let rk4 = Rk4::new(HamiltonEquations::new(Runaway));
    let mut megno = Megno::new(rk4, State::with_momenta(0.0, [1.0], [2f64.sqrt()]), 0.01).unwrap();
    let err = megno.advance_to(10.0).unwrap_err();
    println!("runaway: {err}");
    let (state, ind, dev) = (
        megno.state().clone(),
        megno.indicators(),
        megno.deviation().clone(),
    );
    assert!(state.q[0].is_finite() && state.t < 1.0 && ind.fli.is_finite() && ind.mean_megno.is_finite());
    assert_eq!(megno.advance(1).unwrap_err(), err);
    assert_eq!(megno.state(), &state);
    assert_eq!(megno.indicators(), ind);
    assert_eq!(megno.deviation(), &dev);
}

/// A stability map over a grid equals the members run one by one; grid points without an orbit are
/// NaN and left out of the fraction; a grid with no orbit at all is a typed error. The grid: Hénon-Heiles
/// at E = 1/8 on the section q₁ = 0 over (q₂, p₂), p₁ > 0 from the energy (no orbit where the potential
/// alone exceeds E).
#[test]
fn stability_map_over_a_grid() {
    let e = 1.0 / 8.0;
    let start = |p: &[f64]| -> noether_analysis::Result<Option<Megno<_>>> {
        on_section(e, p[0], p[1])
            .map(|s| Megno::new(Rk4::new(HamiltonEquations::new(HenonHeiles)), s, 0.05))
            .transpose()
    };
    let grid = Grid::new(vec![
        Axis::centres(-0.5, 0.7, 6).unwrap(),
        Axis::centres(-0.6, 0.6, 6).unwrap(),
    ])
    .unwrap();
    let map = stability_map(&grid, 200.0, start).unwrap();
    let y = map.mean_megno();
    let mut valid = 0;
    for (i, p) in grid.members().enumerate() {
        match start(&p).unwrap() {
            Some(mut m) => {
                valid += 1;
                m.advance_to(200.0).unwrap();
                assert_eq!(y[i].to_bits(), m.indicators().mean_megno.to_bits());
            }
            None => assert!(y[i].is_nan()),
        }
    }
    assert_eq!(map.valid, valid);
    assert!(valid > 0 && valid < grid.len() && map.failures.is_empty());
    let fraction = map.chaotic_fraction(4.0);
    let count = y.iter().filter(|v| **v > 4.0).count();
    assert_eq!(fraction, count as f64 / valid as f64);

    let outside = Grid::new(vec![
        Axis::linspace(-2.0, -1.5, 3).unwrap(),
        Axis::linspace(-1.0, 1.0, 3).unwrap(),
    ])
    .unwrap();
    assert!(matches!(
        stability_map(&outside, 200.0, start),
        Err(Error::NoValidMember { members: 9 })
    ));
}
