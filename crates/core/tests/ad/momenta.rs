//! Momenta p = ∂L/∂q̇, the energy function h = q̇·p − L and the mass matrix M = ∂²L/∂q̇² by AD against
//! the hand formulas stated in `systems.rs`.

use super::systems::*;
use super::{assert_rel, charge_state, draw, for_states, rng, Sample};
use noether_core::{EulerLagrange, Lagrangian};
use rand::rngs::StdRng;
use rand::Rng;

/// Momenta and energy of `model` by AD against `hand(t, q, v) = (p, h)` at 50 states drawn by
/// `state` (seeded with `seed`).
fn check_momenta_energy<L: Lagrangian, const N: usize>(
    what: &str,
    model: L,
    seed: u64,
    state: impl FnMut(&mut StdRng) -> Sample<N>,
    hand: impl Fn(f64, &[f64; N], &[f64; N]) -> ([f64; N], f64),
) {
    let el = EulerLagrange::new(model);
    for_states(seed, 50, state, |t, q, v| {
        let mut p = [0.0; N];
        el.momenta(t, q, v, &mut p).unwrap();
        let (hp, hh) = hand(t, q, v);
        let h = el.energy(t, q, v).unwrap();
        assert_rel(&format!("{what} momenta"), &p, &hp, 1.0);
        assert_rel(&format!("{what} energy"), &[h], &[hh], 1.0);
    });
}

#[test]
fn ad_vs_hand_momenta_energy_double_pendulum() {
    let dp = DoublePendulum::default();
    let state = |r: &mut StdRng| (0.0, draw(r, -3.0, 3.0), draw(r, -4.0, 4.0));
    check_momenta_energy("double pendulum", dp, 11, state, |_, q, v| {
        dp.hand_momenta_energy(q, v)
    });
}

#[test]
fn ad_vs_hand_momenta_energy_heavy_top() {
    let top = HeavyTop::default();
    let state = |r: &mut StdRng| (0.0, draw(r, -3.0, 3.0), draw(r, -5.0, 5.0));
    check_momenta_energy("heavy top", top, 12, state, |_, q, v| {
        top.hand_momenta_energy(q, v)
    });
}

#[test]
fn ad_vs_hand_momenta_energy_charge_in_field() {
    let sys = ChargeInField::default();
    check_momenta_energy("charge", sys, 13, charge_state, |t, q, v| {
        sys.hand_momenta_energy(t, q, v)
    });
}

#[test]
fn ad_vs_hand_momenta_energy_kepler() {
    let k = KeplerPolar::default();
    let state = |r: &mut StdRng| {
        let q = [r.random_range(0.5..3.0), r.random_range(-3.0..3.0)];
        (0.0, q, draw(r, -2.0, 2.0))
    };
    check_momenta_energy("Kepler", k, 14, state, |_, q, v| k.hand_momenta_energy(q, v));
}

/// Column-major flattening of a hand matrix, to compare with nalgebra's storage.
fn flat<const N: usize>(m: &[[f64; N]; N]) -> Vec<f64> {
    (0..N).flat_map(|j| (0..N).map(move |i| m[i][j])).collect()
}

#[test]
fn ad_vs_hand_mass_matrix() {
    let mut r = rng(15);
    let dp = DoublePendulum::default();
    let top = HeavyTop::default();
    let chain = Chain::<10>::default();
    for _ in 0..20 {
        let (q, v) = (draw::<2>(&mut r, -3.0, 3.0), draw::<2>(&mut r, -4.0, 4.0));
        let m = EulerLagrange::new(dp).mass_matrix(0.0, &q, &v).unwrap();
        assert_rel("double pendulum M", m.as_slice(), &flat(&dp.hand_mass(&q)), 1.0);

        let (q, v) = (draw::<3>(&mut r, -3.0, 3.0), draw::<3>(&mut r, -5.0, 5.0));
        let m = EulerLagrange::new(top).mass_matrix(0.0, &q, &v).unwrap();
        assert_rel("heavy top M", m.as_slice(), &flat(&top.hand_mass(&q)), 1.0);

        let (q, v) = (draw::<10>(&mut r, -3.0, 3.0), draw::<10>(&mut r, -2.0, 2.0));
        let m = EulerLagrange::new(chain).mass_matrix(0.0, &q, &v).unwrap();
        assert_rel("chain M", m.as_slice(), &flat(&chain.hand_mass(&q)), 1.0);
    }
}

#[test]
fn ad_vs_hand_lagrange_terms_match_separate_kernels() {
    // The one-evaluation Lagrange jet against the gradient/Hessian kernels and the hand mass matrix.
    use noether_core::ad::{self, Block, Field};
    use noether_core::{Lagrangian, Scalar};
    struct F(Chain<7>);
    impl Field for F {
        fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D]) -> D {
            self.0.lagrangian(t, x, y)
        }
    }
    let f = F(Chain::default());
    let mut r = rng(16);
    for _ in 0..20 {
        let (q, v) = (draw::<7>(&mut r, -3.0, 3.0), draw::<7>(&mut r, -2.0, 2.0));
        let terms = ad::lagrange_terms(&f, 0.0, &q, &v);
        let (mut gx, mut gy) = ([0.0; 7], [0.0; 7]);
        let val = ad::gradient(&f, 0.0, &q, &v, Block::X, &mut gx);
        ad::gradient(&f, 0.0, &q, &v, Block::Y, &mut gy);
        let mut mixed = [0.0; 7];
        ad::directional_gradient(&f, 0.0, &q, &v, (1.0, &v, &[]), Block::Y, &mut mixed, None);
        assert_rel("value", &[terms.value], &[val], 1.0);
        assert_rel("∂L/∂q", terms.grad_x.as_slice(), &gx, 1.0);
        assert_rel("p", terms.grad_y.as_slice(), &gy, 1.0);
        assert_rel("mixed", terms.mixed.as_slice(), &mixed, 1.0);
        assert_rel("M", terms.hess_yy.as_slice(), &flat(&f.0.hand_mass(&q)), 1.0);
    }
}
