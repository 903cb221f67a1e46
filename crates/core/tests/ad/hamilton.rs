//! Hamilton's equations q̇ = ∂H/∂p, ṗ = −∂H/∂q by AD against hand-derived right-hand sides.

use super::{assert_rel, charge_state, draw, for_states, Sample};
use noether_core::{HamiltonEquations, Hamiltonian, Scalar};
use rand::rngs::StdRng;
use rand::Rng;

/// Kepler in polar coordinates: H = p_r²/(2m) + p_φ²/(2 m r²) − k/r.
#[derive(Debug, Clone, Copy)]
struct KeplerH {
    m: f64,
    k: f64,
}

impl Hamiltonian for KeplerH {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let r = q[0];
        p[0] * p[0] * (0.5 / self.m) + p[1] * p[1] / (r * r) * (0.5 / self.m) - r.recip() * self.k
    }
}

/// Relativistic particle: H = c sqrt(|p|² + m²c²) + ½ k |q|².
#[derive(Debug, Clone, Copy)]
struct RelativisticH {
    m: f64,
    c: f64,
    k: f64,
}

impl Hamiltonian for RelativisticH {
    fn dof(&self) -> usize {
        3
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let p2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
        let q2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
        (p2 + self.m * self.m * self.c * self.c).sqrt() * self.c + q2 * (0.5 * self.k)
    }
}

/// Charge in the field of `systems::ChargeInField`: H = |p − eA|²/(2m) + e φ, A = ½ B(t)(−y, x, 0),
/// φ = ½ κ (x² + y²) + E0 z cos ωt, B(t) = B0 (1 + ε sin ωt) (explicit time dependence).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ChargeH(pub(crate) super::systems::ChargeInField);

impl Hamiltonian for ChargeH {
    fn dof(&self) -> usize {
        3
    }
    fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D]) -> D {
        let s = &self.0;
        let b = ((t * s.omega).sin() * s.eps + 1.0) * s.b0;
        let (px, py) = (p[0] + q[1] * b * (0.5 * s.e), p[1] - q[0] * b * (0.5 * s.e));
        let phi = (q[0] * q[0] + q[1] * q[1]) * (0.5 * s.kappa) + q[2] * (t * s.omega).cos() * s.e0;
        (px * px + py * py + p[2] * p[2]) * (0.5 / s.m) + phi * s.e
    }
}

fn rates<H: Hamiltonian>(h: &HamiltonEquations<H>, t: f64, q: &[f64], p: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let (mut dq, mut dp) = (vec![0.0; q.len()], vec![0.0; q.len()]);
    h.rates(t, q, p, &mut dq, &mut dp).unwrap();
    (dq, dp)
}

/// A Kepler state (0, q, p) with r in [0.5, 3).
fn kepler_state(r: &mut StdRng) -> Sample<2> {
    let q = [r.random_range(0.5..3.0), r.random_range(-3.0..3.0)];
    (0.0, q, draw(r, -2.0, 2.0))
}

#[test]
fn ad_vs_hand_hamilton_kepler() {
    // ṙ = p_r/m, φ̇ = p_φ/(m r²), ṗ_r = p_φ²/(m r³) − k/r², ṗ_φ = 0.
    let sys = KeplerH { m: 1.1, k: 2.7 };
    let h = HamiltonEquations::new(sys);
    for_states(31, 100, kepler_state, |t, q, p| {
        let (dq, dp) = rates(&h, t, q, p);
        let rr = q[0];
        assert_rel("Kepler q̇", &dq, &[p[0] / sys.m, p[1] / (sys.m * rr * rr)], 1.0);
        let hand_dp = [p[1] * p[1] / (sys.m * rr.powi(3)) - sys.k / (rr * rr), 0.0];
        assert_rel("Kepler ṗ", &dp, &hand_dp, 1.0);
    });
}

#[test]
fn ad_vs_hand_hamilton_kepler_hessian() {
    // H_rr = 3 p_φ²/(m r⁴) − 2k/r³, H_{r p_φ} = −2 p_φ/(m r³), H_pp = diag(1/m, 1/(m r²)), others 0.
    let sys = KeplerH { m: 1.1, k: 2.7 };
    let h = HamiltonEquations::new(sys);
    for_states(32, 50, kepler_state, |t, q, p| {
        let hess = h.hessian(t, q, p).unwrap();
        let (rr, m) = (q[0], sys.m);
        let mut hand = nalgebra::DMatrix::<f64>::zeros(4, 4);
        hand[(0, 0)] = 3.0 * p[1] * p[1] / (m * rr.powi(4)) - 2.0 * sys.k / rr.powi(3);
        hand[(0, 3)] = -2.0 * p[1] / (m * rr.powi(3));
        hand[(3, 0)] = hand[(0, 3)];
        hand[(2, 2)] = 1.0 / m;
        hand[(3, 3)] = 1.0 / (m * rr * rr);
        assert_rel("Kepler Hessian", hess.as_slice(), hand.as_slice(), 1.0);
    });
}

#[test]
fn ad_vs_hand_hamilton_relativistic() {
    // q̇ = c p / sqrt(|p|² + m²c²), ṗ = −k q.
    let sys = RelativisticH {
        m: 1.3,
        c: 2.0,
        k: 0.7,
    };
    let h = HamiltonEquations::new(sys);
    let state = |r: &mut StdRng| -> Sample<3> { (0.0, draw(r, -2.0, 2.0), draw(r, -5.0, 5.0)) };
    for_states(33, 100, state, |t, q, p| {
        let (dq, dp) = rates(&h, t, q, p);
        let e = (p.iter().map(|x| x * x).sum::<f64>() + (sys.m * sys.c).powi(2)).sqrt();
        assert_rel("relativistic q̇", &dq, &p.map(|x| sys.c * x / e), 1.0);
        assert_rel("relativistic ṗ", &dp, &q.map(|x| -sys.k * x), 1.0);
    });
}

#[test]
fn ad_vs_hand_hamilton_charge_explicit_time() {
    // π = p − eA; q̇ = π/m; ṗ = (e/m) Σ_j π_j ∂A_j/∂q − e ∇φ with ∂A_x/∂y = −B/2, ∂A_y/∂x = B/2:
    // ṗ_x = (e/m) π_y B/2 − e κ x, ṗ_y = −(e/m) π_x B/2 − e κ y, ṗ_z = −e E0 cos ωt.
    let s = super::systems::ChargeInField::default();
    let h = HamiltonEquations::new(ChargeH(s));
    for_states(34, 100, charge_state::<3>, |t, q, p| {
        let (dq, dp) = rates(&h, t, q, p);
        let (b, _) = s.field(t);
        let pi = [p[0] + 0.5 * s.e * b * q[1], p[1] - 0.5 * s.e * b * q[0], p[2]];
        assert_rel("charge q̇", &dq, &pi.map(|x| x / s.m), 1.0);
        let hand_dp = [
            s.e / s.m * pi[1] * 0.5 * b - s.e * s.kappa * q[0],
            -s.e / s.m * pi[0] * 0.5 * b - s.e * s.kappa * q[1],
            -s.e * s.e0 * (s.omega * t).cos(),
        ];
        assert_rel("charge ṗ", &dp, &hand_dp, 1.0);
    });
}
