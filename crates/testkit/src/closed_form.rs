//! Special functions the closed forms of the gallery and the tests need beyond `std`, written once: the
//! complete elliptic integrals K and E, the Jacobi elliptic functions sn, cn, dn, and Kepler's equation
//! E − e sin E = M; and the free asymmetric top's Ω(t) by them.
//!
//! Used by the gallery (as `noether_gallery::closed_form`, checked by its `tests/closed_forms.rs`) and
//! noether-rigid's tests (the free top).
//!
//! All take the complementary modulus (k′, or the parameter m₁ = 1 − m along with m), so that a
//! caller near k → 1 (a pendulum released near the top, a motion near a separatrix) can pass the small
//! quantity directly: forming sqrt(1 − k²) from k = sin(θ₀/2) loses the digits that tell k from 1
//! (3e-12 relative in K at θ₀ = 3.14).
//!
//! Why not a crate: `ellip` (well kept, accurate) has K and E, but takes the parameter m in its Legendre
//! forms (only Bulirsch's `cel1` takes k′) and has no Jacobi functions nor Kepler's equation; the
//! crates with sn, cn, dn bind C libraries (GSL, Boost). One arithmetic-geometric mean gives all of
//! K, E, sn, cn and dn in a few lines, so they live here.

use std::f64::consts::{FRAC_PI_2, PI};

/// Most AGM / Landen steps taken: convergence is quadratic, 1 − b/a halves its exponent each step, so
/// k′ = 1e-300 needs about 10; the bound only guarantees termination.
const MAX_AGM_STEPS: usize = 40;

/// The arithmetic-geometric mean of a, b > 0: iterate a ← (a+b)/2, b ← sqrt(ab) until they agree
/// (quadratic convergence: a handful of iterations reach machine precision).
pub fn agm(mut a: f64, mut b: f64) -> f64 {
    for _ in 0..MAX_AGM_STEPS {
        if (a - b).abs() <= 1e-16 * a.abs() {
            break;
        }
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    a
}

/// Complete elliptic integrals of the first and second kind, (K, E), given the complementary modulus
/// 0 < k′ ≤ 1 (k² = 1 − k′²): K = ∫₀^{π/2} dφ / sqrt(1 − k² sin²φ), E = ∫₀^{π/2} sqrt(1 − k² sin²φ) dφ.
///
/// Gauss's AGM (DLMF 19.8.1, 19.8.6; A&S 17.6): a₀ = 1, b₀ = k′, c₀ = k, a_{n+1} = (a_n + b_n)/2,
/// b_{n+1} = sqrt(a_n b_n), c_{n+1} = (a_n − b_n)/2; K = π/(2 a_N), E = K (1 − Σ 2^{n−1} c_n²).
/// c₀² = (1 − k′)(1 + k′) keeps the digits of k′ that 1 − k′² would lose.
pub fn elliptic_ke_complementary(k_prime: f64) -> (f64, f64) {
    let (mut a, mut b) = (1.0_f64, k_prime);
    let mut sum = 0.5 * (1.0 - k_prime) * (1.0 + k_prime); // 2^{−1} c₀²
    let mut weight = 0.5;
    for _ in 0..MAX_AGM_STEPS {
        if (a - b).abs() <= 1e-16 * a {
            break;
        }
        let c = 0.5 * (a - b);
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
        weight *= 2.0;
        sum += weight * c * c;
    }
    let k = FRAC_PI_2 / a;
    (k, k * (1.0 - sum))
}

/// Complete elliptic integral of the first kind K given the complementary modulus 0 < k′ ≤ 1, by
/// Gauss's formula K = π / (2 AGM(1, k′)).
///
/// Near k = 1 pass k′ computed directly, e.g. k′ = cos(θ₀/2) for the pendulum.
pub fn elliptic_k_complementary(k_prime: f64) -> f64 {
    FRAC_PI_2 / agm(1.0, k_prime)
}

/// K(k) for a modulus 0 ≤ k < 1 away from 1 (k′ = sqrt((1 − k)(1 + k)), which keeps the digits
/// 1 − k² would lose); see [`elliptic_k_complementary`] near k = 1.
pub fn elliptic_k(k: f64) -> f64 {
    elliptic_k_complementary(((1.0 - k) * (1.0 + k)).sqrt())
}

/// Jacobi elliptic functions (sn, cn, dn)(u | m) for real u, given the parameter 0 ≤ m ≤ 1 and its
/// complement m₁ = 1 − m (pass m₁ computed directly when m is near 1: the descending sequence starts
/// from sqrt(m₁)).
///
/// Descending Landen / AGM (A&S 16.4, DLMF 22.20(ii)): a₀ = 1, b₀ = sqrt(m₁), c₀ = sqrt(m), the AGM
/// steps until c_N ≈ 0, then φ_N = 2^N a_N u and φ_{n−1} = ½ (φ_n + asin((c_n/a_n) sin φ_n));
/// sn = sin φ₀, cn = cos φ₀, and dn = sqrt(m₁ + m cn²) (= sqrt(1 − m sn²) without its cancellation,
/// and without the 0/0 of A&S's cos φ₀ / cos(φ₁ − φ₀) at u = K). At m₁ = 0 the limit sn = tanh u,
/// cn = dn = sech u (DLMF 22.5.iv).
pub fn jacobi_sn_cn_dn(u: f64, m: f64, m1: f64) -> (f64, f64, f64) {
    if m1 <= 0.0 {
        let sech = 1.0 / u.cosh();
        return (u.tanh(), sech, sech);
    }
    let mut a = [0.0_f64; MAX_AGM_STEPS + 1];
    let mut c = [0.0_f64; MAX_AGM_STEPS + 1];
    let (mut an, mut bn) = (1.0_f64, m1.sqrt());
    a[0] = an;
    c[0] = m.max(0.0).sqrt();
    let mut n = 0;
    while n < MAX_AGM_STEPS && c[n].abs() > 1e-16 * an {
        let cn = 0.5 * (an - bn);
        (an, bn) = (0.5 * (an + bn), (an * bn).sqrt());
        n += 1;
        a[n] = an;
        c[n] = cn;
    }
    let mut phi = 2.0_f64.powi(n as i32) * an * u;
    for j in (1..=n).rev() {
        phi = 0.5 * (phi + (c[j] / a[j] * phi.sin()).asin());
    }
    let (sn, cn) = phi.sin_cos();
    (sn, cn, (m1 + m * cn * cn).sqrt())
}

/// (q, q̇) on the Kepler orbit of μ = 1, a = 1 and eccentricity e (0 ≤ e < 1) at time t from
/// pericentre, from Kepler's equation: E − e sin E = t, q = (cos E − e, √(1 − e²) sin E),
/// q̇ = Ė (−sin E, √(1 − e²) cos E) with Ė = 1/(1 − e cos E).
pub fn kepler_orbit_at(e: f64, t: f64) -> ([f64; 2], [f64; 2]) {
    let ea = kepler_eccentric_anomaly(t, e);
    let (s, c) = ea.sin_cos();
    let b = (1.0 - e * e).sqrt();
    let edot = 1.0 / (1.0 - e * c);
    ([c - e, b * s], [-s * edot, b * c * edot])
}

/// The eccentric anomaly E solving Kepler's equation E − e sin E = M for an ellipse, 0 ≤ e < 1.
///
/// M is reduced to (−π, π] and E is returned on the same branch (E − M is 2π-periodic in M).
/// f(E) = E − e sin E − M increases (f′ = 1 − e cos E ≥ 1 − e > 0) and |E − M| = e |sin E| ≤ e, so the
/// root lies in [M − e, M + e]: Newton from Danby's start E₀ = M + 0.85 e sign(sin M), kept inside the
/// bracket (a step that would leave it bisects instead), at most 100 iterations; it stops when a Newton
/// step moves E by less than 4 ulps of π (or f(E) = 0).
pub fn kepler_eccentric_anomaly(mean_anomaly: f64, e: f64) -> f64 {
    let turns = ((mean_anomaly + PI) / (2.0 * PI)).floor();
    let shift = turns * 2.0 * PI;
    let m = mean_anomaly - shift;
    let (mut lo, mut hi) = (m - e, m + e);
    let mut ea = (m + 0.85 * e * m.sin().signum()).clamp(lo, hi);
    for _ in 0..100 {
        let f = ea - e * ea.sin() - m;
        if f == 0.0 {
            break;
        }
        if f > 0.0 {
            hi = ea;
        } else {
            lo = ea;
        }
        let newton = ea - f / (1.0 - e * ea.cos());
        if (lo..=hi).contains(&newton) {
            let step = (newton - ea).abs();
            ea = newton;
            // Quadratic convergence: after a Newton step this small, E is exact to rounding.
            if step <= 4.0 * f64::EPSILON * PI {
                break;
            }
        } else {
            ea = 0.5 * (lo + hi);
        }
    }
    ea + shift
}

/// The free asymmetric top I₁ < I₂ < I₃ on the side L² > 2EI₂ of the separatrix, started at
/// Ω = (Ω₁₀, 0, Ω₃₀), Ω₁₀, Ω₃₀ > 0: Landau-Lifshitz's solution (37.10) (Landau & Lifshitz, *Mechanics*
/// §37):
/// Ω₁ = sqrt((2EI₃ − L²)/(I₁(I₃ − I₁))) cn τ, Ω₂ = sqrt((2EI₃ − L²)/(I₂(I₃ − I₂))) sn τ,
/// Ω₃ = sqrt((L² − 2EI₁)/(I₃(I₃ − I₁))) dn τ, τ = t sqrt((I₃ − I₂)(L² − 2EI₁)/(I₁I₂I₃)),
/// k² = (I₂ − I₁)(2EI₃ − L²)/((I₃ − I₂)(L² − 2EI₁)); the period of Ω is 4K(k)/(dτ/dt).
#[derive(Debug, Clone, Copy)]
pub struct FreeTop {
    /// Principal moments I₁ < I₂ < I₃.
    pub i: [f64; 3],
    /// Twice the energy, 2E = Ω·JΩ.
    pub two_e: f64,
    /// L² = |JΩ|².
    pub l2: f64,
}

impl FreeTop {
    /// The top with moments `i` started at Ω = (`omega1`, 0, `omega3`); `None` unless
    /// I₁ < I₂ < I₃ and L² > 2EI₂ (the case the formulas describe).
    pub fn new(i: [f64; 3], omega1: f64, omega3: f64) -> Option<Self> {
        let two_e = i[0] * omega1 * omega1 + i[2] * omega3 * omega3;
        let l2 = (i[0] * omega1).powi(2) + (i[2] * omega3).powi(2);
        (i[0] < i[1] && i[1] < i[2] && l2 > two_e * i[1]).then_some(FreeTop { i, two_e, l2 })
    }

    /// dτ/dt = sqrt((I₃ − I₂)(L² − 2EI₁)/(I₁I₂I₃)).
    pub fn rate(&self) -> f64 {
        let [i1, i2, i3] = self.i;
        ((i3 - i2) * (self.l2 - self.two_e * i1) / (i1 * i2 * i3)).sqrt()
    }

    /// (m, m₁) = (k², 1 − k²), with m₁ = (I₃ − I₁)(L² − 2EI₂)/((I₃ − I₂)(L² − 2EI₁)) from its own closed
    /// form, so that it keeps its digits near the separatrix (m₁ → 0).
    pub fn parameter(&self) -> (f64, f64) {
        let [i1, i2, i3] = self.i;
        let den = (i3 - i2) * (self.l2 - self.two_e * i1);
        (
            (i2 - i1) * (self.two_e * i3 - self.l2) / den,
            (i3 - i1) * (self.l2 - self.two_e * i2) / den,
        )
    }

    /// The period of Ω(t), T = 4K(k)/(dτ/dt) (K from the complementary modulus k′ = sqrt(m₁)).
    pub fn period(&self) -> f64 {
        4.0 * elliptic_k_complementary(self.parameter().1.sqrt()) / self.rate()
    }

    /// Ω(t) in the body frame.
    pub fn omega(&self, t: f64) -> [f64; 3] {
        let [i1, i2, i3] = self.i;
        let (m, m1) = self.parameter();
        let (sn, cn, dn) = jacobi_sn_cn_dn(self.rate() * t, m, m1);
        let a = self.two_e * i3 - self.l2;
        [
            (a / (i1 * (i3 - i1))).sqrt() * cn,
            (a / (i2 * (i3 - i2))).sqrt() * sn,
            ((self.l2 - self.two_e * i1) / (i3 * (i3 - i1))).sqrt() * dn,
        ]
    }
}
