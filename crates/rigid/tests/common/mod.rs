//! Closed forms the tests share: the complete elliptic integral K and Jacobi's sn, cn, dn (AGM and the
//! descending Landen transformation, A&S 17.6 and 16.4, DLMF 19.8.1 and 22.20(ii)), and the free
//! asymmetric top's ω(t) (Landau & Lifshitz, *Mechanics* §37; the text's ch. 64).

#![allow(dead_code)]

use std::f64::consts::FRAC_PI_2;

/// K(m) = π / (2 AGM(1, sqrt(1 − m))), parameter m = k², given m₁ = 1 − m.
pub fn elliptic_k(m1: f64) -> f64 {
    let (mut a, mut b) = (1.0_f64, m1.sqrt());
    for _ in 0..40 {
        if (a - b).abs() <= 1e-16 * a {
            break;
        }
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    FRAC_PI_2 / a
}

/// (sn, cn, dn)(u | m) given m and m₁ = 1 − m, by the descending Landen / AGM scheme: a₀ = 1,
/// b₀ = sqrt(m₁), c₀ = sqrt(m); AGM until c_N ≈ 0; φ_N = 2^N a_N u,
/// φ_{n−1} = ½(φ_n + asin((c_n/a_n) sin φ_n)); sn = sin φ₀, cn = cos φ₀, dn = sqrt(m₁ + m cn²).
pub fn sn_cn_dn(u: f64, m: f64, m1: f64) -> (f64, f64, f64) {
    let mut a = [0.0_f64; 41];
    let mut c = [0.0_f64; 41];
    let (mut an, mut bn) = (1.0_f64, m1.sqrt());
    a[0] = an;
    c[0] = m.sqrt();
    let mut n = 0;
    while n < 40 && c[n].abs() > 1e-16 * an {
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

/// The free asymmetric top I₁ < I₂ < I₃ with L² > 2 E I₂ (rotation about the axis of I₃ side of the
/// separatrix), started at Ω = (Ω₁₀, 0, Ω₃₀) with Ω₁₀, Ω₃₀ > 0 (Landau & Lifshitz §37, eqs. (37.10)):
/// Ω₁ = sqrt((2EI₃ − L²)/(I₁(I₃ − I₁))) cn τ, Ω₂ = sqrt((2EI₃ − L²)/(I₂(I₃ − I₂))) sn τ,
/// Ω₃ = sqrt((L² − 2EI₁)/(I₃(I₃ − I₁))) dn τ, τ = t sqrt((I₃ − I₂)(L² − 2EI₁)/(I₁I₂I₃)),
/// k² = (I₂ − I₁)(2EI₃ − L²)/((I₃ − I₂)(L² − 2EI₁)); the period of Ω is 4K(k)/(dτ/dt).
#[derive(Debug, Clone, Copy)]
pub struct FreeTop {
    pub i: [f64; 3],
    /// 2E.
    pub two_e: f64,
    /// L².
    pub l2: f64,
}

impl FreeTop {
    pub fn new(i: [f64; 3], omega1: f64, omega3: f64) -> Self {
        let two_e = i[0] * omega1 * omega1 + i[2] * omega3 * omega3;
        let l2 = (i[0] * omega1).powi(2) + (i[2] * omega3).powi(2);
        assert!(l2 > two_e * i[1], "the closed form below is for L² > 2EI₂");
        FreeTop { i, two_e, l2 }
    }
    /// dτ/dt.
    pub fn rate(&self) -> f64 {
        let [i1, i2, i3] = self.i;
        ((i3 - i2) * (self.l2 - self.two_e * i1) / (i1 * i2 * i3)).sqrt()
    }
    /// (m, m₁) = (k², 1 − k²); m₁ formed from its own closed form
    /// m₁ = (I₃ − I₁)(L² − 2EI₂)/((I₃ − I₂)(L² − 2EI₁)) so that it keeps its digits near the separatrix.
    pub fn parameter(&self) -> (f64, f64) {
        let [i1, i2, i3] = self.i;
        let den = (i3 - i2) * (self.l2 - self.two_e * i1);
        (
            (i2 - i1) * (self.two_e * i3 - self.l2) / den,
            (i3 - i1) * (self.l2 - self.two_e * i2) / den,
        )
    }
    /// The period of Ω(t): 4K(k)/(dτ/dt).
    pub fn period(&self) -> f64 {
        4.0 * elliptic_k(self.parameter().1) / self.rate()
    }
    /// Ω(t).
    pub fn omega(&self, t: f64) -> [f64; 3] {
        let [i1, i2, i3] = self.i;
        let (m, m1) = self.parameter();
        let (sn, cn, dn) = sn_cn_dn(self.rate() * t, m, m1);
        let a = self.two_e * i3 - self.l2;
        [
            (a / (i1 * (i3 - i1))).sqrt() * cn,
            (a / (i2 * (i3 - i2))).sqrt() * sn,
            ((self.l2 - self.two_e * i1) / (i3 * (i3 - i1))).sqrt() * dn,
        ]
    }
}
