//! The taped evaluation (one recorded evaluation, one reverse sweep, curvatures pulled back by
//! q̇-gradients) against the Lagrange jet and the hand-derived mass matrices: every term of
//! Lagrange's equations, for every test system and for a model that uses each elementary function.

use super::legendre::Relativistic;
use super::systems::*;
use super::{assert_rel, draw, rng};
use noether_core::ad::{self, Field};
use noether_core::{Lagrangian, Scalar};
use rand::Rng;

struct F<L>(L);
impl<L: Lagrangian> Field for F<L> {
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D]) -> D {
        self.0.lagrangian(t, x, y)
    }
}

/// Value, ∂L/∂q, p, mixed term and M from the tape against the jet (1e-12 relative, `TOL`) at
/// `count` states with t, q, q̇ uniform in the given ranges.
fn tape_vs_jet<L: Lagrangian, const N: usize>(model: L, seed: u64, q: (f64, f64), v: (f64, f64)) {
    let f = F(model);
    let mut r = rng(seed);
    for _ in 0..50 {
        let t = r.random_range(-3.0..3.0);
        let (qs, vs) = (draw::<N>(&mut r, q.0, q.1), draw::<N>(&mut r, v.0, v.1));
        let jet = ad::lagrange_terms(&f, t, &qs, &vs);
        let tape = ad::lagrange_terms_taped(&f, t, &qs, &vs);
        assert_rel("value", &[tape.value], &[jet.value], 1.0);
        assert_rel("∂L/∂q", tape.grad_x.as_slice(), jet.grad_x.as_slice(), 1.0);
        assert_rel("p", tape.grad_y.as_slice(), jet.grad_y.as_slice(), 1.0);
        assert_rel("mixed", tape.mixed.as_slice(), jet.mixed.as_slice(), 1.0);
        assert_rel("M", tape.hess_yy.as_slice(), jet.hess_yy.as_slice(), 1.0);
    }
}

#[test]
fn taped_terms_match_jet_textbook_systems() {
    tape_vs_jet::<_, 2>(DoublePendulum::default(), 1, (-3.0, 3.0), (-4.0, 4.0));
    tape_vs_jet::<_, 3>(HeavyTop::default(), 2, (0.3, 2.8), (-5.0, 5.0));
    tape_vs_jet::<_, 3>(ChargeInField::default(), 3, (-2.0, 2.0), (-3.0, 3.0));
    tape_vs_jet::<_, 1>(DrivenOscillator::default(), 4, (-2.0, 2.0), (-3.0, 3.0));
    tape_vs_jet::<_, 2>(SphericalPendulum::default(), 5, (0.3, 2.8), (-3.0, 3.0));
    tape_vs_jet::<_, 2>(KeplerPolar::default(), 6, (0.5, 3.0), (-2.0, 2.0));
    tape_vs_jet::<_, 3>(
        Relativistic {
            m: 1.3,
            c: 2.0,
            k: 0.7,
        },
        7,
        (-2.0, 2.0),
        (-0.6, 0.6),
    );
    tape_vs_jet::<_, 10>(Chain::<10>::default(), 8, (-3.0, 3.0), (-2.0, 2.0));
}

#[test]
fn taped_mass_matrix_matches_hand_chain_40_links() {
    // M_ij = μ_max(i,j) l_i l_j cos(θ_i − θ_j) (systems.rs), beyond every fixed-size path.
    const N: usize = 40;
    let chain = Chain::<N>::default();
    let f = F(chain);
    let mut r = rng(9);
    for _ in 0..5 {
        let (q, v) = (draw::<N>(&mut r, -3.0, 3.0), draw::<N>(&mut r, -2.0, 2.0));
        let m = ad::lagrange_terms_taped(&f, 0.0, &q, &v).hess_yy;
        let hand = chain.hand_mass(&q);
        let hand: Vec<f64> = (0..N * N).map(|k| hand[k % N][k / N]).collect();
        assert_rel("M", m.as_slice(), &hand, 1.0);
    }
}

/// Every elementary function of num-dual's `DualNum` that a model may call, in q and in q̇, with
/// products, quotients and compositions of q̇-dependent quantities.
struct Elementary;
impl Lagrangian for Elementary {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        let (a, b, c) = (v[0], v[1], v[2]);
        let s = q[0] * a + q[1] * b + (t * 0.3).sin() * c;
        let trig = a.sin() * b.cos() + (c * 0.3).tan() + (a * 0.2).sin_cos().0 * (b * 0.2).sin_cos().1;
        let inverse = (a * 0.1).asin() + (b * 0.1).acos() + (c * 0.5).atan() + a.atan2(b * b + 2.0);
        let hyper = (a * 0.3).sinh() + (b * 0.3).cosh() + (c * 0.3).tanh();
        let ahyper = (a * 0.3).asinh() + (b * b + 2.0).acosh() + (c * 0.1).atanh();
        let exps = (a * 0.2).exp() + (b * 0.2).exp2() + (c * 0.2).exp_m1();
        let logs = (a * a + 1.0).ln() + (b * b + 1.0).log(3.0) + (c * c + 1.0).log2() + (a * a + 2.0).log10();
        let logs = logs + (b * b).ln_1p();
        let pows = (a * a + 1.0).sqrt() + (b * b + 1.0).cbrt() + (c * c + 1.0).powf(1.7) + a.powi(3);
        let ratio = (a + q[2]) / (b * b + c * c + 1.0) + (a * b + 3.0).recip().abs();
        let mixed = (q[0] * a).sin() * q[1].exp() + q[2] * q[2] * (b / (q[0] * q[0] + 1.0));
        s + trig + inverse + hyper + ahyper + exps + logs + pows + ratio + mixed + a * b * c - (-a) * (c - b)
    }
}

#[test]
fn taped_terms_match_jet_every_elementary_function() {
    tape_vs_jet::<_, 3>(Elementary, 10, (-1.5, 1.5), (0.4, 1.5));
}

#[test]
fn taped_evaluations_nest() {
    // A model that itself evaluates another model on the tape (same thread): the inner evaluation
    // truncates back to where it started, so the outer terms are unchanged.
    struct Nesting;
    impl Lagrangian for Nesting {
        fn dof(&self) -> usize {
            2
        }
        fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
            let (q0, v0) = ([0.3, -0.4], [1.1, 0.2]);
            let k = ad::lagrange_terms_taped(&F(DoublePendulum::default()), 0.0, &q0, &v0).value;
            DoublePendulum::default().lagrangian(t, q, v) * (1.0 + 1e-3 * k.tanh())
        }
    }
    tape_vs_jet::<_, 2>(Nesting, 11, (-3.0, 3.0), (-4.0, 4.0));
}

/// FPU chain, V = Σ_i ½ d_i² + ¼ β d_i⁴ with d_i = x_{i+1} − x_i: the hand-derived gradient
/// ∂V/∂x_i = F(d_{i−1}) − F(d_i) and tridiagonal Hessian H_ii = k(d_{i−1}) + k(d_i),
/// H_{i,i+1} = −k(d_i), with F(d) = d + β d³, k(d) = 1 + 3β d² (terms beyond the ends absent).
struct Fpu {
    beta: f64,
}
impl Field for Fpu {
    fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
        x.windows(2).fold(D::zero(), |v, w| {
            let d = w[1] - w[0];
            v + d * d * 0.5 + d.powi(4) * (0.25 * self.beta)
        })
    }
}

#[test]
fn taped_gradient_and_hessian_match_hand_fpu_chain() {
    // n = 1000 takes ad::gradient onto the tape (n ≥ GRADIENT_TAPE_FROM), n = 100 ad::hessian
    // (n > MAX_FIXED). Tolerance 1e-12 relative to the largest entry (TOL): one rounding per term.
    let fpu = Fpu { beta: 0.7 };
    let mut r = rng(12);
    for n in [1000, 100] {
        let x: Vec<f64> = (0..n).map(|_| r.random_range(-1.0..1.0)).collect();
        let d: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let beta = fpu.beta;
        let force = |i: usize| d.get(i).map_or(0.0, |&d| d + beta * d.powi(3));
        let stiff = |i: usize| d.get(i).map_or(0.0, |&d| 1.0 + 3.0 * beta * d * d);
        let hand: Vec<f64> = (0..n)
            .map(|i| (if i == 0 { 0.0 } else { force(i - 1) }) - force(i))
            .collect();
        let mut g = vec![0.0; n];
        ad::gradient(&fpu, 0.0, &x, &[], ad::Block::X, &mut g);
        assert_rel("∇V", &g, &hand, 1.0);
        if n <= 100 {
            let mut h = nalgebra::DMatrix::zeros(n, n);
            ad::hessian(&fpu, 0.0, &x, &[], ad::Block::X, ad::Block::X, &mut h);
            let hand = nalgebra::DMatrix::from_fn(n, n, |i, j| match i.abs_diff(j) {
                0 => (if i == 0 { 0.0 } else { stiff(i - 1) }) + stiff(i),
                1 => -stiff(i.min(j)),
                _ => 0.0,
            });
            assert_rel("∇²V", h.as_slice(), hand.as_slice(), 1.0);
        }
    }
}

/// Coupled rotors, L = Σ ½ q̇_i² + ε Σ q̇_i q̇_{i+1} cos(q_i − q_{i+1}) + Σ cos(q_{i+1} − q_i), whose
/// momenta p_j = q̇_j + ε [q̇_{j+1} cos(q_j − q_{j+1}) + q̇_{j−1} cos(q_{j−1} − q_j)] give the mixed
/// term d/ds p_j(q + s q̇) = −ε [q̇_{j+1} sin(q_j − q_{j+1}) (q̇_j − q̇_{j+1})
/// + q̇_{j−1} sin(q_{j−1} − q_j) (q̇_{j−1} − q̇_j)].
struct Rotors {
    eps: f64,
}
impl Lagrangian for Rotors {
    fn dof(&self) -> usize {
        40
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let kinetic = v.iter().fold(D::zero(), |s, &vi| s + vi * vi * 0.5);
        (0..q.len() - 1).fold(kinetic, |s, i| {
            s + v[i] * v[i + 1] * (q[i] - q[i + 1]).cos() * self.eps + (q[i + 1] - q[i]).cos()
        })
    }
}

#[test]
fn taped_directional_gradient_matches_hand_coupled_rotors() {
    // 40 velocities: ad::directional_gradient takes the tape (n ≥ DIRECTIONAL_TAPE_FROM).
    let f = F(Rotors { eps: 0.3 });
    let mut r = rng(13);
    for _ in 0..10 {
        let (q, v) = (draw::<40>(&mut r, -3.0, 3.0), draw::<40>(&mut r, -2.0, 2.0));
        let (mut mixed, mut p) = ([0.0; 40], [0.0; 40]);
        ad::directional_gradient(
            &f,
            0.0,
            &q,
            &v,
            (1.0, &v, &[]),
            ad::Block::Y,
            &mut mixed,
            Some(&mut p),
        );
        let e = f.0.eps;
        let hand_p: Vec<f64> = (0..40)
            .map(|j| {
                let next = if j + 1 < 40 {
                    v[j + 1] * (q[j] - q[j + 1]).cos()
                } else {
                    0.0
                };
                let prev = if j > 0 {
                    v[j - 1] * (q[j - 1] - q[j]).cos()
                } else {
                    0.0
                };
                v[j] + e * (next + prev)
            })
            .collect();
        let hand_mixed: Vec<f64> = (0..40)
            .map(|j| {
                let next = if j + 1 < 40 {
                    v[j + 1] * (q[j] - q[j + 1]).sin() * (v[j] - v[j + 1])
                } else {
                    0.0
                };
                let prev = if j > 0 {
                    v[j - 1] * (q[j - 1] - q[j]).sin() * (v[j - 1] - v[j])
                } else {
                    0.0
                };
                -e * (next + prev)
            })
            .collect();
        assert_rel("p", &p, &hand_p, 1.0);
        assert_rel("mixed", &mixed, &hand_mixed, 1.0);
    }
}

/// Every Hessian block of L(t, q, q̇) by the tape against forward duals (one `Dual2Vec`
/// evaluation or hyper-dual chunk pairs): the 15-link chain (dense, trigonometric coupling of q
/// and q̇) and the model that calls every elementary function.
fn hessian_blocks_tape_vs_forward<L: Lagrangian, const N: usize>(model: L, seed: u64, v: (f64, f64)) {
    use ad::Block::{X, Y};
    let f = F(model);
    let mut r = rng(seed);
    for _ in 0..10 {
        let t = r.random_range(-3.0..3.0);
        let (q, qd) = (draw::<N>(&mut r, -1.5, 1.5), draw::<N>(&mut r, v.0, v.1));
        for (a, b) in [(X, X), (Y, Y), (X, Y), (Y, X)] {
            let (mut tape, mut fwd) = (nalgebra::DMatrix::zeros(N, N), nalgebra::DMatrix::zeros(N, N));
            ad::hessian_taped(&f, t, &q, &qd, a, b, &mut tape);
            ad::hessian_forward(&f, t, &q, &qd, a, b, &mut fwd);
            assert_rel(&format!("∂²L/∂{a:?}∂{b:?}"), tape.as_slice(), fwd.as_slice(), 1.0);
        }
    }
}

#[test]
fn taped_hessian_blocks_match_forward() {
    hessian_blocks_tape_vs_forward::<_, 15>(Chain::<15>::default(), 14, (-2.0, 2.0));
    hessian_blocks_tape_vs_forward::<_, 3>(Elementary, 15, (0.4, 1.5));
}
