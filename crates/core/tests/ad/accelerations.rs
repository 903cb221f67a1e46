//! q̈ by AD (one Lagrange-jet evaluation, or the chunked kernels beyond 12 dof) against the
//! hand-derived equations of motion stated next to each model in `systems.rs`.

use crate::systems::*;
use crate::{assert_rel, draw, rng};
use noether_core::EulerLagrange;
use rand::Rng;

const STATES: usize = 200;

#[test]
fn ad_vs_hand_double_pendulum() {
    let dp = DoublePendulum::default();
    let el = EulerLagrange::new(dp);
    let mut r = rng(1);
    for _ in 0..STATES {
        let (q, v) = (draw::<2>(&mut r, -3.0, 3.0), draw::<2>(&mut r, -4.0, 4.0));
        let mut a = [0.0; 2];
        el.accelerations(0.0, &q, &v, &mut a).unwrap();
        assert_rel("double pendulum q̈", &a, &dp.hand_accelerations(&q, &v), 1.0);
    }
}

#[test]
fn ad_vs_hand_heavy_top() {
    let top = HeavyTop::default();
    let el = EulerLagrange::new(top);
    let mut r = rng(2);
    for _ in 0..STATES {
        // θ away from the chart singularities θ = 0, π (where φ̈ has sin θ in the denominator).
        let q = [
            r.random_range(0.3..2.8),
            r.random_range(-3.0..3.0),
            r.random_range(-3.0..3.0),
        ];
        let v = draw::<3>(&mut r, -5.0, 5.0);
        let mut a = [0.0; 3];
        el.accelerations(0.0, &q, &v, &mut a).unwrap();
        assert_rel("heavy top q̈", &a, &top.hand_accelerations(&q, &v), 1.0);
    }
}

/// A chain of N links through `EulerLagrange` (static path for N ≤ 12, chunked beyond).
fn chain<const N: usize>(seed: u64) {
    let chain = Chain::<N>::default();
    let el = EulerLagrange::new(chain);
    let mut r = rng(seed);
    for _ in 0..STATES / 4 {
        // Moderate angles keep M well conditioned (cond ≲ 1e4), so the two Cholesky solves agree.
        let (q, v) = (draw::<N>(&mut r, -0.8, 0.8), draw::<N>(&mut r, -1.5, 1.5));
        let mut a = [0.0; N];
        el.accelerations(0.0, &q, &v, &mut a).unwrap();
        assert_rel("chain q̈", &a, &chain.hand_accelerations(&q, &v), 1.0);
    }
}

#[test]
fn ad_vs_hand_chain_10_links() {
    chain::<10>(3);
}

#[test]
fn ad_vs_hand_chain_12_links_largest_static() {
    chain::<12>(4);
}

#[test]
fn ad_vs_hand_chain_15_links_chunked() {
    chain::<15>(5);
}

#[test]
fn ad_vs_hand_charge_in_time_dependent_field() {
    // Exercises ∂²L/∂q̇∂t = e ∂A/∂t (the induced electric field −∂A/∂t) and ∂²L/∂q̇∂q.
    let sys = ChargeInField::default();
    let el = EulerLagrange::new(sys);
    let mut r = rng(6);
    for _ in 0..STATES {
        let t = r.random_range(-5.0..5.0);
        let (q, v) = (draw::<3>(&mut r, -2.0, 2.0), draw::<3>(&mut r, -3.0, 3.0));
        let mut a = [0.0; 3];
        el.accelerations(t, &q, &v, &mut a).unwrap();
        assert_rel("charge q̈", &a, &sys.hand_accelerations(t, &q, &v), 1.0);
    }
}

#[test]
fn ad_vs_hand_damped_driven_oscillator() {
    let osc = DrivenOscillator::default();
    let el = EulerLagrange::new(osc);
    let mut r = rng(7);
    for _ in 0..STATES {
        let (t, q, v) = (
            r.random_range(-10.0..10.0),
            r.random_range(-2.0..2.0),
            r.random_range(-3.0..3.0),
        );
        let mut a = [0.0];
        el.accelerations(t, &[q], &[v], &mut a).unwrap();
        assert_rel("oscillator q̈", &a, &[osc.hand_acceleration(t, q, v)], 1.0);
    }
}

#[test]
fn ad_vs_hand_spherical_pendulum() {
    let sp = SphericalPendulum::default();
    let el = EulerLagrange::new(sp);
    let mut r = rng(8);
    for _ in 0..STATES {
        let q = [r.random_range(0.3..2.8), r.random_range(-3.0..3.0)];
        let v = draw::<2>(&mut r, -3.0, 3.0);
        let mut a = [0.0; 2];
        el.accelerations(0.0, &q, &v, &mut a).unwrap();
        assert_rel("spherical pendulum q̈", &a, &sp.hand_accelerations(&q, &v), 1.0);
    }
}

#[test]
fn ad_vs_hand_kepler_polar() {
    let k = KeplerPolar::default();
    let el = EulerLagrange::new(k);
    let mut r = rng(9);
    for _ in 0..STATES {
        let q = [r.random_range(0.5..3.0), r.random_range(-3.0..3.0)];
        let v = draw::<2>(&mut r, -2.0, 2.0);
        let mut a = [0.0; 2];
        el.accelerations(0.0, &q, &v, &mut a).unwrap();
        assert_rel("Kepler q̈", &a, &k.hand_accelerations(&q, &v), 1.0);
    }
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
    fn generalized_force(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
        self.0.generalized_force(t, q, v, out)
    }
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
