//! The inverse Legendre map q̇(p) by Newton on a Lagrangian that is not quadratic in q̇.

use super::{assert_rel, draw, for_states, Sample};
use noether_core::{EulerLagrange, Lagrangian, Scalar};
use rand::rngs::StdRng;
use rand::Rng;

/// Free relativistic particle in a harmonic well: L = −m c² sqrt(1 − |v|²/c²) − ½ k |q|².
#[derive(Debug, Clone, Copy)]
pub struct Relativistic {
    pub m: f64,
    pub c: f64,
    pub k: f64,
}

impl Lagrangian for Relativistic {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        let q2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
        -(-v2 / (self.c * self.c) + 1.0).sqrt() * (self.m * self.c * self.c) - q2 * (0.5 * self.k)
    }
}

const SYS: Relativistic = Relativistic {
    m: 1.3,
    c: 2.0,
    k: 0.7,
};

/// A random velocity with speed up to 0.95 c.
fn velocity(r: &mut StdRng) -> [f64; 3] {
    loop {
        let v = draw::<3>(r, -0.95 * SYS.c, 0.95 * SYS.c);
        if (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() < 0.95 * SYS.c {
            return v;
        }
    }
}

/// A state (0, q, v) with |q_i| < 2 and speed below 0.95 c.
fn state(r: &mut StdRng) -> Sample<3> {
    (0.0, draw(r, -2.0, 2.0), velocity(r))
}

/// The Lorentz factor γ = 1/sqrt(1 − |v|²/c²).
fn gamma(v: &[f64; 3]) -> f64 {
    let v2: f64 = v.iter().map(|x| x * x).sum();
    1.0 / (1.0 - v2 / (SYS.c * SYS.c)).sqrt()
}

#[test]
fn ad_vs_hand_relativistic_momenta_and_energy() {
    // p = γ m v, h = γ m c² + ½ k |q|², γ = 1/sqrt(1 − v²/c²).
    let el = EulerLagrange::new(SYS);
    for_states(21, 50, state, |t, q, v| {
        let gamma = gamma(v);
        let mut p = [0.0; 3];
        el.momenta(t, q, v, &mut p).unwrap();
        assert_rel("relativistic p", &p, &v.map(|x| gamma * SYS.m * x), 1.0);
        let q2: f64 = q.iter().map(|x| x * x).sum();
        let h = gamma * SYS.m * SYS.c * SYS.c + 0.5 * SYS.k * q2;
        assert_rel("relativistic h", &[el.energy(t, q, v).unwrap()], &[h], 1.0);
    });
}

#[test]
fn ad_vs_hand_relativistic_inverse_legendre_round_trip() {
    // velocities(momenta(v)) = v, and against the closed form v = p / (m sqrt(1 + |p|²/(m c)²)).
    // Newton's residual tolerance is 1e-13·(1 + |p|∞) on p; with dp/dv ≥ m the velocity error is of
    // the same order relative to |v|, inside 1e-12 · (1 + |v|∞).
    let el = EulerLagrange::new(SYS);
    for_states(22, 50, state, |t, q, v| {
        let mut p = [0.0; 3];
        el.momenta(t, q, v, &mut p).unwrap();
        let back = el.velocities(t, q, &p).unwrap();
        assert_rel("round trip q̇(p(q̇))", back.as_slice(), v, 1.0);
        let p2: f64 = p.iter().map(|x| x * x).sum();
        let denom = SYS.m * (1.0 + p2 / (SYS.m * SYS.c).powi(2)).sqrt();
        assert_rel("closed-form q̇(p)", back.as_slice(), &p.map(|x| x / denom), 1.0);
    });
}

#[test]
fn ad_vs_hand_relativistic_accelerations() {
    // d/dt(γ m v) = −k q gives M q̈ = −k q with M = γ m (I + γ² v vᵀ/c²), whose inverse is
    // (1/(γ m)) (I − v vᵀ/c²): q̈ = −(k/(γ m)) (q − (v·q) v / c²).
    let el = EulerLagrange::new(SYS);
    // One extra draw after each state keeps the states of the original sequence.
    let state = |r: &mut StdRng| {
        let s = state(r);
        let _ = r.random::<f64>();
        s
    };
    for_states(23, 50, state, |t, q, v| {
        let gamma = gamma(v);
        let vq: f64 = v.iter().zip(q).map(|(a, b)| a * b).sum();
        let hand: [f64; 3] =
            std::array::from_fn(|i| -SYS.k / (gamma * SYS.m) * (q[i] - vq * v[i] / (SYS.c * SYS.c)));
        let mut a = [0.0; 3];
        el.accelerations(t, q, v, &mut a).unwrap();
        assert_rel("relativistic q̈", &a, &hand, 1.0);
    });
}
