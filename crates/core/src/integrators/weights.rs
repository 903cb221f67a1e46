//! The weights of a symmetric composition: the substep fractions γ₁, …, γ_s of
//!
//! ```text
//! Ψ_h = Φ_{γ_s h} ∘ … ∘ Φ_{γ₁ h},      Σ γ_i = 1,   γ_i = γ_{s+1−i},
//! ```
//!
//! which raises a symmetric base method Φ of even order to the order of the weights (the base is
//! Störmer-Verlet for [`Composition::kahan_li8`](super::Composition::kahan_li8) and friends, a
//! variational integrator of noether-discrete otherwise). One set of weights serves every base; each is
//! validated once, with one tolerance ([`WEIGHT_TOLERANCE`]).
//!
//! | weights | order | stages |
//! |---|---|---|
//! | [`Weights::stormer_verlet`] | 2 | 1 (the base itself) |
//! | [`Weights::yoshida4`] | 4 | 3 (triple jump) |
//! | [`Weights::suzuki4`] | 4 | 5 |
//! | [`Weights::yoshida6`] | 6 | 7 |
//! | [`Weights::triple_jump6`] | 6 | 9 (triple jump of the triple jump) |
//! | [`Weights::kahan_li6`] | 6 | 9 |
//! | [`Weights::kahan_li8`] | 8 | 17 |
//! | [`Weights::custom`] | given | any |
//!
//! ```
//! use noether_core::integrators::Weights;
//! let w = Weights::kahan_li8();
//! assert_eq!((w.len(), w.order()), (17, 8));
//! assert!((w.as_slice().iter().sum::<f64>() - 1.0).abs() < 1e-15);
//! assert!(Weights::custom(&[0.3, 0.7], 2).is_err()); // not symmetric
//! ```
//!
//! # References
//! - E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., Springer 2006,
//!   sections II.4 and V.3 (weights (3.9), (3.11), (3.12), (3.14) of V.3.2).
//! - H. Yoshida, Construction of higher order symplectic integrators, Phys. Lett. A 150 (1990) 262.
//! - W. Kahan, R.-C. Li, Composition constants for raising the orders of unconventional schemes for
//!   ordinary differential equations, Math. Comp. 66 (1997) 1089.

use crate::error::check_finite;
use crate::{Error, Result};

/// How far custom weights may be from summing to 1 and from symmetry: |Σγ − 1| ≤ 1e-14 and
/// |γ_i − γ_{s+1−i}| ≤ 1e-14.
pub const WEIGHT_TOLERANCE: f64 = 1e-14;

/// Validated weights of a symmetric composition (see the [module](self) docs), with the nominal order
/// and a name.
#[derive(Debug, Clone, PartialEq)]
pub struct Weights {
    gammas: Vec<f64>,
    /// Merged half kicks a₀ = γ₁/2, a_i = (γ_i + γ_{i+1})/2, a_s = γ_s/2 (for kick-drift-kick bases).
    kicks: Vec<f64>,
    order: u32,
    name: &'static str,
}

/// The triple-jump weights (a, −c a, a), c = 2^{1/(p+1)}, a = 1/(2 − c), raising a symmetric method
/// of even order p to order p + 2 (HLW (V.3.5)).
pub fn triple_jump(p: u32) -> [f64; 3] {
    let c = 2f64.powf(1.0 / (p as f64 + 1.0));
    let a = 1.0 / (2.0 - c);
    [a, -c * a, a]
}

/// Suzuki's fractal (order 4, 5 stages): γ₁ = γ₂ = γ₄ = γ₅ = 1/(4 − 4^{1/3}), γ₃ = 1 − 4γ₁.
fn suzuki4() -> Vec<f64> {
    let g = 1.0 / (4.0 - 4f64.powf(1.0 / 3.0));
    vec![g, g, 1.0 - 4.0 * g, g, g]
}

/// Mirrors the first half of a symmetric scheme and sets the middle weight to 1 − 2Σ(others), so that
/// Σγ = 1 holds to rounding (the published middle value agrees to ~1e-16).
fn symmetric(half: &[f64]) -> Vec<f64> {
    let mid = 1.0 - 2.0 * half.iter().sum::<f64>();
    let mut g = half.to_vec();
    g.push(mid);
    g.extend(half.iter().rev());
    g
}

/// Yoshida (1990) order 6, 7 stages (HLW (V.3.11)); middle 1.31518632068391121888424973.
#[allow(clippy::excessive_precision)] // the published digits, kept verbatim
const YOSHIDA6: [f64; 3] = [
    0.784_513_610_477_557_263_819_497_63,
    0.235_573_213_359_358_133_684_793_18,
    -1.177_679_984_178_871_006_946_415_68,
];

/// Kahan-Li (1997) s9odr6a, order 6, 9 stages (HLW (V.3.12)); middle 0.79854399093482996339895035.
#[allow(clippy::excessive_precision)] // the published digits, kept verbatim
const KAHAN_LI6: [f64; 4] = [
    0.392_161_444_007_314_139_279_250_56,
    0.332_599_136_789_359_438_599_748_64,
    -0.706_246_172_557_639_359_809_964_82,
    0.082_213_596_293_550_800_231_490_45,
];

/// Kahan-Li (1997) s17odr8a, order 8, 17 stages (HLW (V.3.14)); middle −0.60550853383003451169892108.
#[allow(clippy::excessive_precision)] // the published digits, kept verbatim
const KAHAN_LI8: [f64; 8] = [
    0.130_202_483_088_890_080_878_817_63,
    0.561_162_981_775_108_384_561_964_41,
    -0.389_474_962_644_847_286_408_078_60,
    0.158_841_906_555_155_600_896_210_75,
    -0.395_903_894_133_237_577_336_231_54,
    0.184_539_640_978_315_707_091_832_54,
    0.258_374_387_686_322_047_293_979_11,
    0.295_011_723_609_310_298_870_966_24,
];

impl Weights {
    /// Published weights, taken as they are (each named scheme is checked against the rules of
    /// [`custom`](Self::custom) by a unit test).
    fn named(gammas: Vec<f64>, order: u32, name: &'static str) -> Self {
        let mut kicks = vec![0.0; gammas.len() + 1];
        for (i, g) in gammas.iter().enumerate() {
            kicks[i] += 0.5 * g;
            kicks[i + 1] += 0.5 * g;
        }
        Weights {
            gammas,
            kicks,
            order,
            name,
        }
    }

    /// γ = (1): the base method itself (Störmer-Verlet when the base is kick-drift-kick), order 2.
    pub fn stormer_verlet() -> Self {
        Self::named(vec![1.0], 2, "Störmer-Verlet")
    }
    /// Yoshida's triple jump, order 4, 3 stages: γ₁ = γ₃ = 1/(2 − 2^{1/3}), γ₂ = −2^{1/3} γ₁
    /// ([`triple_jump`] of order 2).
    pub fn yoshida4() -> Self {
        Self::named(triple_jump(2).to_vec(), 4, "Yoshida 4 (triple jump)")
    }
    /// Suzuki's fractal, order 4, 5 stages (a smaller error constant than the triple jump).
    pub fn suzuki4() -> Self {
        Self::named(suzuki4(), 4, "Suzuki 4 (5 stages)")
    }
    /// Yoshida (1990), order 6, 7 stages.
    pub fn yoshida6() -> Self {
        Self::named(symmetric(&YOSHIDA6), 6, "Yoshida 6 (7 stages)")
    }
    /// The triple jump of order 4 applied to [`yoshida4`](Self::yoshida4), order 6, 9 stages:
    /// γ_{3i+j} = b_i a_j with a = [`triple_jump`]`(2)`, b = [`triple_jump`]`(4)`.
    pub fn triple_jump6() -> Self {
        let (a, b) = (triple_jump(2), triple_jump(4));
        let g = b.iter().flat_map(|bi| a.iter().map(move |ai| ai * bi)).collect();
        Self::named(g, 6, "triple jump 6 (9 stages)")
    }
    /// Kahan-Li (1997), order 6, 9 stages.
    pub fn kahan_li6() -> Self {
        Self::named(symmetric(&KAHAN_LI6), 6, "Kahan-Li 6 (9 stages)")
    }
    /// Kahan-Li (1997), order 8, 17 stages.
    pub fn kahan_li8() -> Self {
        Self::named(symmetric(&KAHAN_LI8), 8, "Kahan-Li 8 (17 stages)")
    }

    /// Custom weights γ₁, …, γ_s of nominal order `order`: at least one, each finite and non-zero,
    /// summing to 1 and symmetric, both to [`WEIGHT_TOLERANCE`]; else [`Error::InvalidParameter`] or
    /// [`Error::NonFinite`].
    pub fn custom(gammas: &[f64], order: u32) -> Result<Self> {
        check_finite("composition weights", gammas)?;
        if let Some(&g) = gammas.iter().find(|g| **g == 0.0) {
            return Err(Error::InvalidParameter {
                name: "composition weight",
                value: g,
                reason: "a weight must be non-zero (a substep of size 0 is no step)",
            });
        }
        let sum: f64 = gammas.iter().sum();
        if gammas.is_empty() || (sum - 1.0).abs() > WEIGHT_TOLERANCE {
            return Err(Error::InvalidParameter {
                name: "sum of composition weights",
                value: sum,
                reason: "the weights must sum to 1",
            });
        }
        let s = gammas.len();
        if let Some(i) = (0..s).find(|&i| (gammas[i] - gammas[s - 1 - i]).abs() > WEIGHT_TOLERANCE) {
            return Err(Error::InvalidParameter {
                name: "composition weight",
                value: gammas[i],
                reason: "the weights must be symmetric (γ_i = γ_{s+1−i})",
            });
        }
        Ok(Self::named(gammas.to_vec(), order, "custom composition"))
    }

    /// The weights γ₁, …, γ_s.
    pub fn as_slice(&self) -> &[f64] {
        &self.gammas
    }
    /// The number of stages s.
    pub fn len(&self) -> usize {
        self.gammas.len()
    }
    /// `false`: validated weights hold at least one stage (for clippy's `len_without_is_empty`).
    pub fn is_empty(&self) -> bool {
        self.gammas.is_empty()
    }
    /// The nominal order of the composition of a symmetric second-order base.
    pub fn order(&self) -> u32 {
        self.order
    }
    /// The scheme's name (the composition's [`Stepper::name`](crate::Stepper::name)).
    pub fn name(&self) -> &'static str {
        self.name
    }
    /// The merged half kicks a₀ = γ₁/2, a_i = (γ_i + γ_{i+1})/2, a_s = γ_s/2 of a kick-drift-kick base.
    pub(crate) fn kicks(&self) -> &[f64] {
        &self.kicks
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every named scheme passes the checks of `custom`, and `custom` keeps the weights as given.
    #[test]
    fn named_weights_are_valid() {
        for w in [
            Weights::stormer_verlet(),
            Weights::yoshida4(),
            Weights::suzuki4(),
            Weights::yoshida6(),
            Weights::triple_jump6(),
            Weights::kahan_li6(),
            Weights::kahan_li8(),
        ] {
            let c = Weights::custom(w.as_slice(), w.order()).unwrap();
            assert_eq!(
                (c.as_slice(), c.kicks()),
                (w.as_slice(), w.kicks()),
                "{}",
                w.name()
            );
        }
    }

    #[test]
    fn custom_weights_refused() {
        assert!(Weights::custom(&[], 2).is_err());
        assert!(Weights::custom(&[0.5, 0.0, 0.5], 2).is_err());
        assert!(Weights::custom(&[0.5, f64::NAN, 0.5], 2).is_err());
        assert!(Weights::custom(&[0.5, 0.6], 2).is_err());
        assert!(Weights::custom(&[0.3, 0.7], 2).is_err());
        assert!(Weights::custom(&[0.5, 0.5], 2).is_ok());
    }
}
