//! The AD kernels in forward mode (one dual evaluation per chunk of 8 variables, or per pair of chunks
//! for a Hessian) against the tape (one recorded evaluation, one reverse sweep), side by side for
//! growing block lengths n: where the taped kernels take over (`ad::GRADIENT_TAPE_FROM`,
//! `ad::DIRECTIONAL_TAPE_FROM`, `ad::MAX_FIXED` for Hessians) and what they gain.
//!
//! - gradient and Hessian: the FPU chain V = Σ ½ d² + ¼ β d⁴, d = x_{i+1} − x_i;
//! - Hessian-vector product ∇_q̇(∂_t L + ∇_q L·q̇): coupled rotors,
//!   L = Σ ½ q̇² + ε Σ q̇_i q̇_{i+1} cos(q_i − q_{i+1}) + Σ cos(q_{i+1} − q_i).
//!
//! `cargo bench -p noether-core --bench kernels`; results in docs/benchmarks.md.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::DMatrix;
use noether_core::ad::{self, Block, Field};
use noether_core::Scalar;
use std::hint::black_box;
use std::time::Duration;

struct Fpu;
impl Field for Fpu {
    fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
        x.windows(2).fold(D::zero(), |v, w| {
            let d = w[1] - w[0];
            v + d * d * 0.5 + d.powi(4) * 0.25
        })
    }
}

struct Rotors;
impl Field for Rotors {
    fn eval<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let kinetic = v.iter().fold(D::zero(), |s, &vi| s + vi * vi * 0.5);
        (0..q.len() - 1).fold(kinetic, |s, i| {
            s + v[i] * v[i + 1] * (q[i] - q[i + 1]).cos() * 0.1 + (q[i + 1] - q[i]).cos()
        })
    }
}

fn state(n: usize) -> (Vec<f64>, Vec<f64>) {
    (
        (0..n).map(|i| (i as f64 * 0.3).sin()).collect(),
        (0..n).map(|i| (i as f64 * 0.7).cos()).collect(),
    )
}

/// The kernels' signatures, shared by the forward and the taped variant of each.
type Gradient = fn(&Fpu, f64, &[f64], &[f64], Block, &mut [f64]) -> f64;
type Directional =
    fn(&Rotors, f64, &[f64], &[f64], (f64, &[f64], &[f64]), Block, &mut [f64], Option<&mut [f64]>);
type Hessian = fn(&Fpu, f64, &[f64], &[f64], Block, Block, &mut DMatrix<f64>);

/// One group `name`: the forward kernel against the taped one, side by side.
fn forward_vs_tape(
    c: &mut Criterion,
    name: String,
    mut forward: impl FnMut() -> f64,
    mut tape: impl FnMut() -> f64,
) {
    let mut g = c.benchmark_group(name);
    g.bench_function("forward", |b| b.iter(&mut forward));
    g.bench_function("tape", |b| b.iter(&mut tape));
    g.finish();
}

fn bench(c: &mut Criterion) {
    for n in [16, 32, 64, 1024] {
        let (x, _) = state(n);
        let run = |k: Gradient| {
            let (x, mut out) = (&x, vec![0.0; n]);
            move || k(&Fpu, 0.0, black_box(x), &[], Block::X, &mut out)
        };
        let name = format!("gradient_n{n}");
        forward_vs_tape(c, name, run(ad::gradient_forward), run(ad::gradient_taped));
    }
    for n in [16, 32, 64, 1024] {
        let (q, v) = state(n);
        let run = |k: Directional| {
            let (q, v, mut out) = (&q, &v, vec![0.0; n]);
            move || {
                k(
                    &Rotors,
                    0.0,
                    black_box(q),
                    v,
                    (1.0, v, &[]),
                    Block::Y,
                    &mut out,
                    None,
                );
                out[0]
            }
        };
        let name = format!("directional_n{n}");
        forward_vs_tape(
            c,
            name,
            run(ad::directional_gradient_forward),
            run(ad::directional_gradient_taped),
        );
    }
    for n in [16, 64, 256] {
        let (x, _) = state(n);
        let run = |k: Hessian| {
            let (x, mut h) = (&x, DMatrix::zeros(n, n));
            move || {
                k(&Fpu, 0.0, black_box(x), &[], Block::X, Block::X, &mut h);
                h[0]
            }
        };
        let name = format!("hessian_n{n}");
        forward_vs_tape(c, name, run(ad::hessian_forward), run(ad::hessian_taped));
    }
}

fn config() -> Criterion {
    // Short runs: the machine is shared. Ratios are what matter, measured in one run.
    Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1500))
        .sample_size(10)
}

criterion_group! { name = benches; config = config(); targets = bench }
criterion_main!(benches);
