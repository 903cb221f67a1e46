//! Closed forms the examples are checked against that need more than `std`: the complete elliptic
//! integral of the first kind (the pendulum's period) by the arithmetic-geometric mean, in the
//! complementary-modulus form that stays accurate as k → 1.

/// The arithmetic-geometric mean of a, b > 0: iterate a ← (a+b)/2, b ← sqrt(ab) until they agree
/// (quadratic convergence: a handful of iterations reach machine precision).
pub fn agm(mut a: f64, mut b: f64) -> f64 {
    for _ in 0..64 {
        if (a - b).abs() <= 1e-16 * a.abs() {
            break;
        }
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    a
}

/// Complete elliptic integral of the first kind K(k) = ∫₀^{π/2} dφ / sqrt(1 − k² sin²φ) given the
/// complementary modulus k′ = sqrt(1 − k²) (0 < k′ ≤ 1), by Gauss's formula K = π / (2 AGM(1, k′)).
///
/// Near k = 1 (a pendulum released near the top) pass k′ computed directly, e.g. k′ = cos(θ₀/2) for
/// the pendulum: forming sqrt(1 − k²) from k = sin(θ₀/2) loses the digits that tell k from 1
/// (3e-12 relative in K at θ₀ = 3.14).
pub fn elliptic_k_complementary(k_prime: f64) -> f64 {
    std::f64::consts::FRAC_PI_2 / agm(1.0, k_prime)
}

/// K(k) for a modulus 0 ≤ k < 1 away from 1 (k′ = sqrt((1 − k)(1 + k)), which keeps the digits
/// 1 − k² would lose); see [`elliptic_k_complementary`] near k = 1.
pub fn elliptic_k(k: f64) -> f64 {
    elliptic_k_complementary(((1.0 - k) * (1.0 + k)).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn closed_form_elliptic_k() {
        // K(0) = π/2; K(1/√2) = Γ(1/4)² / (4 √π) with Γ(1/4) = 3.625609908221908311930685...
        assert!((elliptic_k(0.0) - PI / 2.0).abs() < 1e-15);
        let gamma_quarter = 3.625_609_908_221_908_f64;
        let expected = gamma_quarter * gamma_quarter / (4.0 * PI.sqrt());
        assert!((elliptic_k(0.5_f64.sqrt()) - expected).abs() < 1e-14 * expected);
        // Series K(k) = π/2 (1 + k²/4 + 9k⁴/64 + 25k⁶/256 + …) for small k.
        let k: f64 = 0.01;
        let series = PI / 2.0 * (1.0 + k * k / 4.0 + 9.0 * k.powi(4) / 64.0 + 25.0 * k.powi(6) / 256.0);
        assert!((elliptic_k(k) - series).abs() < 1e-15);
    }

    #[test]
    fn closed_form_elliptic_k_near_one() {
        // K ≈ ln(4/k′) + (k′²/4)(ln(4/k′) − 1) as k′ → 0 (Abramowitz & Stegun 17.3.26); at
        // k′ = 1e-6 the neglected terms are O(k′⁴ ln k′) ~ 1e-23.
        let kp: f64 = 1e-6;
        let l = (4.0 / kp).ln();
        let expected = l + kp * kp / 4.0 * (l - 1.0);
        assert!((elliptic_k_complementary(kp) - expected).abs() < 4e-15 * expected);
    }
}
