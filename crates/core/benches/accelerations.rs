//! AD-derived accelerations against hand-written ones, side by side in one run, for the double pendulum,
//! the heavy symmetric top (Euler angles) and pendulum chains of 10, 20 and 40 links.
//!
//! - `hand`: the hand-derived equations of motion of `noether_testkit::systems` (closed forms; Cramer's rule
//!   for the double pendulum, the cyclic-coordinate closed form for the top, a stack Cholesky of the
//!   hand-built mass matrix for the chain);
//! - `ad`: `EulerLagrange::accelerations` (one Lagrange-jet evaluation and a stack LDLᵀ up to 10 dof;
//!   one taped evaluation and a heap `DenseFactor` beyond: the 20- and 40-link chains);
//! - `ad_split`: the earlier scheme from the public kernels (gradient, one Hessian-vector product, the
//!   Hessian in q̇, a heap `DenseFactor`), kept as the reference point of the optimisation; it was the
//!   path of every system above 12 dof before the tape.
//!
//! A second group, `terms_<system>/{jet,tape}`, times the two fused evaluations of Lagrange's terms
//! (value, ∂L/∂q, p, mixed term, M) side by side: `ad::lagrange_terms` (forward jet) against
//! `ad::lagrange_terms_taped` (reverse sweep); it sets where `EulerLagrange` switches from one to the
//! other.
//!
//! `cargo bench -p noether-core --bench accelerations`; results in docs/benchmarks.md.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::DMatrix;
use noether_core::ad::{self, Block, Field};
use noether_core::{EulerLagrange, Lagrangian, Scalar};
use std::hint::black_box;
use std::time::Duration;

use noether_testkit::systems::{Chain, DoublePendulum, HeavyTop};

struct AsField<L>(L);
impl<L: Lagrangian> Field for AsField<L> {
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D]) -> D {
        self.0.lagrangian(t, x, y)
    }
}

/// The three-kernel scheme in forward mode: M q̈ = ∇_q L − ∇_q̇(∂_t L + q̇·∇_q L), M = ∂²L/∂q̇²
/// (Dual2Vec, or hyper-dual chunk pairs beyond 12), heap factor.
fn ad_split<L: Lagrangian>(f: &AsField<L>, t: f64, q: &[f64], v: &[f64], a: &mut [f64]) {
    let n = q.len();
    ad::gradient_forward(f, t, q, v, Block::X, a);
    let mut mixed = vec![0.0; n];
    ad::directional_gradient_forward(f, t, q, v, (1.0, v, &[]), Block::Y, &mut mixed, None);
    a.iter_mut().zip(&mixed).for_each(|(ai, mi)| *ai -= mi);
    let mut m = DMatrix::zeros(n, n);
    ad::hessian_forward(f, t, q, v, Block::Y, Block::Y, &mut m);
    noether_core::linalg::factor_mass(m, t).unwrap().solve_in_place(a);
}

fn group<L: Lagrangian + Copy, const N: usize>(
    c: &mut Criterion,
    name: &str,
    l: L,
    q: [f64; N],
    v: [f64; N],
    hand: impl Fn(&[f64; N], &[f64; N]) -> [f64; N],
) {
    let el = EulerLagrange::new(l);
    let f = AsField(l);
    let mut g = c.benchmark_group(name);
    g.bench_function("hand", |b| b.iter(|| hand(black_box(&q), black_box(&v))));
    g.bench_function("ad", |b| {
        let mut a = [0.0; N];
        b.iter(|| {
            el.accelerations(black_box(0.0), black_box(&q), black_box(&v), &mut a)
                .unwrap();
            a
        })
    });
    g.bench_function("ad_split", |b| {
        let mut a = [0.0; N];
        b.iter(|| {
            ad_split(&f, black_box(0.0), black_box(&q), black_box(&v), &mut a);
            a
        })
    });
    g.finish();
}

fn bench(c: &mut Criterion) {
    let dp = DoublePendulum::default();
    group(c, "double_pendulum", dp, [0.7, -1.9], [1.3, 0.4], |q, v| {
        dp.hand_accelerations(q, v)
    });
    let top = HeavyTop::default();
    group(c, "heavy_top", top, [0.8, 0.3, -1.2], [0.4, 1.1, 7.5], |q, v| {
        top.hand_accelerations(q, v)
    });
    chain_group::<10>(c, "chain10");
    chain_group::<20>(c, "chain20");
    chain_group::<40>(c, "chain40");
    terms(c, "terms_double_pendulum", dp, [0.7, -1.9], [1.3, 0.4]);
    terms(c, "terms_heavy_top", top, [0.8, 0.3, -1.2], [0.4, 1.1, 7.5]);
    chain_terms::<6>(c, "terms_chain6");
    chain_terms::<8>(c, "terms_chain8");
    chain_terms::<10>(c, "terms_chain10");
    chain_terms::<12>(c, "terms_chain12");
}

/// Lagrange's terms by the forward jet and by the tape, for one system at one state.
fn terms<L: Lagrangian, const N: usize>(c: &mut Criterion, name: &str, l: L, q: [f64; N], v: [f64; N]) {
    let f = AsField(l);
    let mut g = c.benchmark_group(name);
    g.bench_function("jet", |b| {
        b.iter(|| ad::lagrange_terms(&f, 0.0, black_box(&q), black_box(&v)).hess_yy[0])
    });
    g.bench_function("tape", |b| {
        b.iter(|| ad::lagrange_terms_taped(&f, 0.0, black_box(&q), black_box(&v)).hess_yy[0])
    });
    g.finish();
}

fn chain_terms<const N: usize>(c: &mut Criterion, name: &str) {
    let (q, v) = chain_state::<N>();
    terms(c, name, Chain::<N>::default(), q, v);
}

/// The chains' state: moderate angles and rates.
fn chain_state<const N: usize>() -> ([f64; N], [f64; N]) {
    (
        std::array::from_fn(|k| 0.3 * (k as f64).sin() + 0.1),
        std::array::from_fn(|k| 0.5 * (1.7 * k as f64).cos()),
    )
}

/// A chain of N links, hand against AD, at a fixed moderate state.
fn chain_group<const N: usize>(c: &mut Criterion, name: &str) {
    let chain = Chain::<N>::default();
    let (q, v) = chain_state::<N>();
    group(c, name, chain, q, v, |q, v| chain.hand_accelerations(q, v));
}

fn config() -> Criterion {
    // Short runs: the machine is shared. Ratios are what matter, measured in one run.
    Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1500))
        .sample_size(20)
}

criterion_group! { name = benches; config = config(); targets = bench }
criterion_main!(benches);
