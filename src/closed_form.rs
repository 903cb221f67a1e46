//! Closed forms the examples are checked against that need more than `std`: the complete elliptic
//! integral of the first kind (the pendulum's period) by the arithmetic-geometric mean.

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

/// Complete elliptic integral of the first kind K(k) = ∫₀^{π/2} dφ / sqrt(1 − k² sin²φ) (modulus k,
/// 0 ≤ k < 1), by Gauss's formula K(k) = π / (2 AGM(1, sqrt(1 − k²))).
pub fn elliptic_k(k: f64) -> f64 {
    std::f64::consts::FRAC_PI_2 / agm(1.0, (1.0 - k * k).sqrt())
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
}
