//! Regressions against equations written out by hand.

use crate::models::Chains;
use nalgebra::DMatrix;
use noether_core::{Lagrangian, Scalar, Stepper};
use noether_discrete::{DiscreteDerivatives, DiscreteLagrangian, Midpoint, VariationalIntegrator};

/// The midpoint variational integrator on the paper's coupled chains (L = ½|q̇|² − V, unit masses)
/// satisfies the paper's discrete Euler-Lagrange equation written out by hand with a hand-written ∇V:
///
/// `(q_{k+1} − 2q_k + q_{k−1})/h + (h/2) [∇V((q_{k+1}+q_k)/2) + ∇V((q_k+q_{k−1})/2)] = 0`
///
/// (the paper's equation times h, in momentum units). Tolerance 1e-13: the second difference of
/// positions of size 3 divided by h = 0.1 carries ~4·3ε/h ≈ 3e-14 of rounding.
#[test]
fn regress_paper_del() {
    let chains = Chains::paper();
    let h = 0.1;
    let n = chains.dof();
    let q0 = chains.start();
    let v0: Vec<f64> = (0..n).map(|k| if k < chains.n { 0.1 } else { 0.0 }).collect();
    let mut vi = VariationalIntegrator::new(Midpoint::new(Chains::paper()));
    let mut s = vi.state_from_velocities(0.0, &q0, &v0).unwrap();
    let mut qs = vec![q0.clone()];
    for _ in 0..30 {
        vi.step(&mut s, h).unwrap();
        qs.push(s.q.as_slice().to_vec());
    }
    let mut worst = 0.0_f64;
    for k in 1..qs.len() - 1 {
        let (qm, q, qp) = (&qs[k - 1], &qs[k], &qs[k + 1]);
        let mid = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| 0.5 * (x + y)).collect::<Vec<_>>();
        let (g1, g0) = (chains.grad_v(&mid(qp, q)), chains.grad_v(&mid(q, qm)));
        for i in 0..n {
            let del = (qp[i] - 2.0 * q[i] + qm[i]) / h + 0.5 * h * (g1[i] + g0[i]);
            worst = worst.max(del.abs());
        }
    }
    eprintln!("paper DEL residual: {worst:.3e}");
    assert!(worst < 1e-13, "paper DEL residual {worst:e}");
}

/// A user-written discrete Lagrangian (exact L_d of the harmonic oscillator q̈ = −ω²q,
/// `L_d = ω/(2 sin ωh) [(q₀² + q₁²) cos ωh − 2 q₀ q₁]`): D₁, D₂ and D₁₂ by dual numbers against the
/// derivatives written by hand, to rounding.
#[test]
fn ad_vs_hand_exact_oscillator_discrete_lagrangian() {
    struct ExactOscillator {
        w: f64,
    }
    impl DiscreteLagrangian for ExactOscillator {
        fn dof(&self) -> usize {
            1
        }
        fn discrete_lagrangian<D: Scalar>(&self, _t0: f64, h: D, q0: &[D], q1: &[D]) -> D {
            let wh = h * self.w;
            ((q0[0] * q0[0] + q1[0] * q1[0]) * wh.cos() - q0[0] * q1[0] * 2.0) * self.w / (wh.sin() * 2.0)
        }
    }
    let (w, h, a, b) = (1.3, 0.2, 0.7, -0.4);
    let ld = ExactOscillator { w };
    let (s, c) = ((w * h).sin(), (w * h).cos());
    let (mut d1, mut d2, mut d12) = ([0.0], [0.0], DMatrix::zeros(1, 1));
    ld.d1(0.0, h, &[a], &[b], &mut d1);
    ld.d2(0.0, h, &[a], &[b], &mut d2);
    ld.d12(0.0, h, &[a], &[b], &mut d12);
    assert!((d1[0] - w / s * (a * c - b)).abs() < 1e-14);
    assert!((d2[0] - w / s * (b * c - a)).abs() < 1e-14);
    assert!((d12[(0, 0)] + w / s).abs() < 1e-14);
    // The exact discrete Lagrangian gives the exact flow: one step from (q, p) = (a, 0) lands on
    // q = a cos ωh, p = −a ω sin ωh.
    let mut vi = VariationalIntegrator::new(ExactOscillator { w });
    let mut st = noether_core::State::with_momenta(0.0, [a], [0.0]);
    vi.step(&mut st, h).unwrap();
    assert!((st.q[0] - a * c).abs() < 1e-15);
    assert!((st.v[0] + a * w * s).abs() < 1e-15);
}
