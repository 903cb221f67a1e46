//! q̈ by AD (one Lagrange-jet evaluation up to 10 dof, one taped evaluation beyond) against the
//! hand-derived equations of motion stated next to each model in `systems.rs`.

use super::systems::*;
use super::{assert_rel, charge_state, draw, for_states, rng, Sample};
use noether_core::{EulerLagrange, Lagrangian};
use rand::rngs::StdRng;
use rand::Rng;

const STATES: usize = 200;

/// q̈ of `model` by AD against `hand(t, q, v)` at `count` states drawn by `state` (seeded with `seed`).
fn check_accelerations<L: Lagrangian, const N: usize>(
    what: &str,
    model: L,
    (seed, count): (u64, usize),
    state: impl FnMut(&mut StdRng) -> Sample<N>,
    hand: impl Fn(f64, &[f64; N], &[f64; N]) -> [f64; N],
) {
    let el = EulerLagrange::new(model);
    for_states(seed, count, state, |t, q, v| {
        let mut a = [0.0; N];
        el.accelerations(t, q, v, &mut a).unwrap();
        assert_rel(what, &a, &hand(t, q, v), 1.0);
    });
}

#[test]
fn ad_vs_hand_double_pendulum() {
    let dp = DoublePendulum::default();
    let state = |r: &mut StdRng| (0.0, draw(r, -3.0, 3.0), draw(r, -4.0, 4.0));
    check_accelerations("double pendulum q̈", dp, (1, STATES), state, |_, q, v| {
        dp.hand_accelerations(q, v)
    });
}

#[test]
fn ad_vs_hand_heavy_top() {
    let top = HeavyTop::default();
    // θ away from the chart singularities θ = 0, π (where φ̈ has sin θ in the denominator).
    let state = |r: &mut StdRng| {
        let q = [
            r.random_range(0.3..2.8),
            r.random_range(-3.0..3.0),
            r.random_range(-3.0..3.0),
        ];
        (0.0, q, draw(r, -5.0, 5.0))
    };
    check_accelerations("heavy top q̈", top, (2, STATES), state, |_, q, v| {
        top.hand_accelerations(q, v)
    });
}

/// A chain of N links through `EulerLagrange` (one jet evaluation for N ≤ 10, taped beyond).
fn chain<const N: usize>(seed: u64) {
    let chain = Chain::<N>::default();
    // Moderate angles keep M well conditioned (cond ≲ 1e4), so the two Cholesky solves agree.
    let state = |r: &mut StdRng| (0.0, draw(r, -0.8, 0.8), draw(r, -1.5, 1.5));
    check_accelerations("chain q̈", chain, (seed, STATES / 4), state, |_, q, v| {
        chain.hand_accelerations(q, v)
    });
}

#[test]
fn ad_vs_hand_chain_10_links_largest_jet() {
    chain::<10>(3);
}

#[test]
fn ad_vs_hand_chain_12_links_taped() {
    chain::<12>(4);
}

#[test]
fn ad_vs_hand_chain_15_links_taped() {
    chain::<15>(5);
}

#[test]
fn ad_vs_hand_chain_40_links_taped() {
    // cond(M) grows with N; both sides solve with Cholesky, and the 1e-12 relative tolerance (TOL)
    // is the same as at 10 links.
    chain::<40>(11);
}

/// `K` independent copies of a model side by side: L = Σ_c L(t, q_c, q̇_c), Q = (Q(q_c, q̇_c))_c, so
/// q̈ is the hand-derived q̈ of each copy. Takes small models past 10 dof onto the taped path with
/// everything they exercise (explicit time, velocity-dependent potentials, generalized forces).
#[derive(Clone, Copy)]
struct Copies<L, const K: usize>(L);

impl<L: Lagrangian, const K: usize> Lagrangian for Copies<L, K> {
    fn dof(&self) -> usize {
        K * self.0.dof()
    }
    fn lagrangian<D: noether_core::Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        let n = self.0.dof();
        (0..K).fold(D::zero(), |s, c| {
            s + self
                .0
                .lagrangian(t, &q[c * n..(c + 1) * n], &v[c * n..(c + 1) * n])
        })
    }
    fn has_generalized_force(&self) -> bool {
        self.0.has_generalized_force()
    }
    fn generalized_force<D: noether_core::Scalar>(&self, t: D, q: &[D], v: &[D], out: &mut [D]) {
        let n = self.0.dof();
        for c in 0..K {
            let r = c * n..(c + 1) * n;
            self.0
                .generalized_force(t, &q[r.clone()], &v[r.clone()], &mut out[r]);
        }
    }
}

/// The hand-derived q̈ of `Copies::<ChargeInField, K>` (N = 3K): each charge's own.
fn charges_hand<const N: usize>(sys: &ChargeInField, t: f64, q: &[f64; N], v: &[f64; N]) -> [f64; N] {
    let mut a = [0.0; N];
    for ((ac, qc), vc) in a
        .chunks_exact_mut(3)
        .zip(q.chunks_exact(3))
        .zip(v.chunks_exact(3))
    {
        let (qc, vc) = (qc.try_into().unwrap(), vc.try_into().unwrap());
        ac.copy_from_slice(&sys.hand_accelerations(t, qc, vc));
    }
    a
}

#[test]
fn ad_vs_hand_charges_and_driven_oscillators_taped() {
    // 5 charges (15 dof: ∂²L/∂q̇∂t, ∂²L/∂q̇∂q) and 13 damped driven oscillators (Q(t, q, q̇)).
    let sys = ChargeInField::default();
    check_accelerations(
        "5 charges q̈",
        Copies::<_, 5>(sys),
        (12, 50),
        charge_state,
        |t, q, v| charges_hand::<15>(&sys, t, q, v),
    );
    let osc = DrivenOscillator::default();
    let state = |r: &mut StdRng| {
        (
            r.random_range(-10.0..10.0),
            draw(r, -2.0, 2.0),
            draw(r, -3.0, 3.0),
        )
    };
    check_accelerations::<_, 13>(
        "13 oscillators q̈",
        Copies::<_, 13>(osc),
        (13, 50),
        state,
        |t, q, v| std::array::from_fn(|c| osc.hand_acceleration(t, q[c], v[c])),
    );
}

#[test]
fn ad_vs_hand_charge_in_time_dependent_field() {
    // Exercises ∂²L/∂q̇∂t = e ∂A/∂t (the induced electric field −∂A/∂t) and ∂²L/∂q̇∂q.
    let sys = ChargeInField::default();
    check_accelerations("charge q̈", sys, (6, STATES), charge_state, |t, q, v| {
        sys.hand_accelerations(t, q, v)
    });
}

#[test]
fn ad_vs_hand_damped_driven_oscillator() {
    let osc = DrivenOscillator::default();
    let state = |r: &mut StdRng| {
        let t = r.random_range(-10.0..10.0);
        let q = r.random_range(-2.0..2.0);
        (t, [q], [r.random_range(-3.0..3.0)])
    };
    check_accelerations("oscillator q̈", osc, (7, STATES), state, |t, q, v| {
        [osc.hand_acceleration(t, q[0], v[0])]
    });
}

#[test]
fn ad_vs_hand_spherical_pendulum() {
    let sp = SphericalPendulum::default();
    let state = |r: &mut StdRng| {
        let q = [r.random_range(0.3..2.8), r.random_range(-3.0..3.0)];
        (0.0, q, draw(r, -3.0, 3.0))
    };
    check_accelerations("spherical pendulum q̈", sp, (8, STATES), state, |_, q, v| {
        sp.hand_accelerations(q, v)
    });
}

#[test]
fn ad_vs_hand_kepler_polar() {
    let k = KeplerPolar::default();
    let state = |r: &mut StdRng| {
        let q = [r.random_range(0.5..3.0), r.random_range(-3.0..3.0)];
        (0.0, q, draw(r, -2.0, 2.0))
    };
    check_accelerations("Kepler q̈", k, (9, STATES), state, |_, q, v| {
        k.hand_accelerations(q, v)
    });
}

/// A model that declares its (truly constant) mass matrix: `accelerations` then skips ∂²L/∂q̇²
/// and factors M once.
struct ConstMass<L>(L);

impl<L: noether_core::Lagrangian> noether_core::Lagrangian for ConstMass<L> {
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn lagrangian<D: noether_core::Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        self.0.lagrangian(t, q, v)
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
    fn has_generalized_force(&self) -> bool {
        self.0.has_generalized_force()
    }
    fn generalized_force<D: noether_core::Scalar>(&self, t: D, q: &[D], v: &[D], out: &mut [D]) {
        self.0.generalized_force(t, q, v, out)
    }
}

#[test]
fn ad_vs_hand_constant_mass_path_chunked_15_dof() {
    // 5 charges (15 dof) declared constant-mass: chunked gradient and Hessian-vector product.
    let sys = ChargeInField::default();
    let model = ConstMass(Copies::<_, 5>(sys));
    check_accelerations(
        "5 charges q̈ (constant M)",
        model,
        (14, 50),
        charge_state,
        |t, q, v| charges_hand::<15>(&sys, t, q, v),
    );
}

#[test]
fn ad_vs_hand_constant_mass_path_taped_33_dof() {
    // 11 charges declared constant-mass: the Hessian-vector product (with its explicit-time part
    // ∂²L/∂q̇∂t) and the gradient ∂L/∂q by the tape (n ≥ DIRECTIONAL_TAPE_FROM, GRADIENT_TAPE_FROM).
    let sys = ChargeInField::default();
    let model = ConstMass(Copies::<_, 11>(sys));
    check_accelerations(
        "11 charges q̈ (constant M)",
        model,
        (15, 50),
        charge_state,
        |t, q, v| charges_hand::<33>(&sys, t, q, v),
    );
}

#[test]
fn ad_vs_hand_constant_mass_path() {
    // M = m I for the charge and m for the oscillator: the constant-mass path (gradient +
    // Hessian-vector product, M factored once) must give the same hand-derived q̈, including the
    // explicit-time term ∂²L/∂q̇∂t and the generalized force Q.
    let sys = ChargeInField::default();
    let el = EulerLagrange::new(ConstMass(sys));
    let osc = DrivenOscillator::default();
    let el_osc = EulerLagrange::new(ConstMass(osc));
    let mut r = rng(10);
    for _ in 0..STATES {
        let t = r.random_range(-5.0..5.0);
        let (q, v) = (draw::<3>(&mut r, -2.0, 2.0), draw::<3>(&mut r, -3.0, 3.0));
        let mut a = [0.0; 3];
        el.accelerations(t, &q, &v, &mut a).unwrap();
        assert_rel(
            "charge q̈ (constant M)",
            &a,
            &sys.hand_accelerations(t, &q, &v),
            1.0,
        );
        let mut a = [0.0];
        el_osc.accelerations(t, &q[..1], &v[..1], &mut a).unwrap();
        assert_rel(
            "oscillator q̈ (constant M)",
            &a,
            &[osc.hand_acceleration(t, q[0], v[0])],
            1.0,
        );
    }
}
