//! Compiled models against hand-written equations and the dual-number path, per call of q̈ (issue 32).
//!
//! For each of core's test models with hand-derived equations of motion (the double pendulum, the
//! heavy symmetric top, chains of 10 and 40 links; `crates/testkit/src/systems.rs`): the time of one
//! q̈ by the hand-written closed form; by the compiled model's equations emitted as Rust source
//! (`rust_source`, committed in `benches/generated/` and checked by noether-compile's test
//! `generated`: ahead-of-time compilation by LLVM); by the compiled model run by its interpreter; with
//! the feature `jit`, by the compiled model run as native code (Cranelift); and by `EulerLagrange`
//! (dual numbers). Each time is the minimum per call over interleaved rounds (the machine is shared:
//! interference only adds time). One line per model:
//!
//! ```text
//! ratio <model> <compiled / hand>   (then each time, and the construction time and operation counts)
//! ```
//!
//! where "compiled" is the native code with the feature `jit`, else the ahead-of-time code where it is
//! generated (not for the 40-link chain: 34 000 lines) and the interpreter otherwise.
//!
//! `cargo bench --bench compiled [--features jit]`; results in docs/benchmarks.md.

#![allow(missing_docs)]

use noether::compile::{Backend, Compile, CompiledEulerLagrange};
use noether::core::{EulerLagrange, Lagrangian};
use std::hint::black_box;
use std::time::Instant;

#[allow(dead_code)]
mod generated {
    include!("generated/double_pendulum.rs");
    include!("generated/heavy_top.rs");
    include!("generated/chain10.rs");
}
use noether_testkit::systems::{Chain, DoublePendulum, HeavyTop};

/// Nanoseconds per call of each closure: the minimum over `rounds` interleaved rounds of `calls` calls.
fn race<const K: usize>(rounds: usize, calls: usize, mut runs: [&mut dyn FnMut(); K]) -> [f64; K] {
    let mut best = [f64::INFINITY; K];
    for _ in 0..rounds {
        for (k, run) in runs.iter_mut().enumerate() {
            let t0 = Instant::now();
            for _ in 0..calls {
                run();
            }
            best[k] = best[k].min(t0.elapsed().as_secs_f64() * 1e9 / calls as f64);
        }
    }
    best
}

/// One model: hand, ahead-of-time (if any), interpreter, dual; prints the ratio line.
/// `aot` is the ahead-of-time function: x = (t, q, q̇) in, q̈ first among its outputs.
fn model<
    L: Lagrangian + Clone,
    F: Fn(&[f64; I]) -> [f64; O],
    const N: usize,
    const I: usize,
    const O: usize,
>(
    name: &str,
    l: L,
    hand: impl Fn(&[f64; N], &[f64; N]) -> [f64; N],
    aot: Option<F>,
    (q, v): ([f64; N], [f64; N]),
    calls: usize,
) {
    let mut x = [0.0; I];
    if aot.is_some() {
        x[1..=N].copy_from_slice(&q);
        x[N + 1..=2 * N].copy_from_slice(&v);
    }
    let t0 = Instant::now();
    let compiled = CompiledEulerLagrange::interpreted(EulerLagrange::new(l.clone())).unwrap();
    let build = t0.elapsed();
    // Native code with the feature `jit` (the interpreter again without it).
    let t0 = Instant::now();
    let native = EulerLagrange::new(l.clone()).compile().unwrap();
    let build_native = t0.elapsed();
    let jit = native.backend() == Backend::Native;
    let dual = EulerLagrange::new(l);
    let (mut a, mut b, mut c) = ([0.0; N], [0.0; N], [0.0; N]);
    let [th, ta, tc, tn, td] = race(
        15,
        calls,
        [
            &mut || {
                black_box(hand(black_box(&q), black_box(&v)));
            },
            &mut || {
                if let Some(f) = &aot {
                    black_box(f(black_box(&x)));
                }
            },
            &mut || {
                compiled
                    .accelerations(0.0, black_box(&q), black_box(&v), &mut a)
                    .unwrap();
                black_box(&a);
            },
            &mut || {
                if jit {
                    native
                        .accelerations(0.0, black_box(&q), black_box(&v), &mut c)
                        .unwrap();
                    black_box(&c);
                }
            },
            &mut || {
                dual.accelerations(0.0, black_box(&q), black_box(&v), &mut b)
                    .unwrap();
                black_box(&b);
            },
        ],
    );
    let ops = compiled.operations();
    let best = match (jit, aot.is_some()) {
        (true, _) => tn,
        (false, true) => ta,
        (false, false) => tc,
    };
    println!(
        "ratio {name} {:.2}   (hand {th:.1} ns; ahead-of-time {}; interpreter {tc:.1} ns = {:.2}×; native {}; \
         dual numbers {td:.1} ns = {:.2}×; built in {:.2} ms (native: {}); {} operations from {} requested, \
         L recorded in {})",
        best / th,
        if aot.is_some() { format!("{ta:.1} ns") } else { "not generated".into() },
        tc / th,
        if jit { format!("{tn:.1} ns = {:.2}×", tn / th) } else { "not built (feature jit)".into() },
        td / th,
        build.as_secs_f64() * 1e3,
        if jit { format!("{:.2} ms", build_native.as_secs_f64() * 1e3) } else { "—".into() },
        ops.accelerations,
        ops.requested,
        ops.recorded
    );
}

fn main() {
    let dp = DoublePendulum::default();
    model(
        "double_pendulum",
        dp,
        |q, v| dp.hand_accelerations(q, v),
        Some(generated::double_pendulum_accelerations),
        ([0.7, -0.4], [0.3, 1.1]),
        20_000,
    );
    let top = HeavyTop::default();
    model(
        "heavy_top",
        top,
        |q, v| top.hand_accelerations(q, v),
        Some(generated::heavy_top_accelerations),
        ([0.9, 0.2, -0.3], [0.4, 1.5, 20.0]),
        20_000,
    );
    let c10 = Chain::<10>::default();
    model(
        "chain10",
        c10,
        |q, v| c10.hand_accelerations(q, v),
        Some(generated::chain10_accelerations),
        (
            std::array::from_fn(|i| 0.5 * (0.7 * i as f64).sin()),
            std::array::from_fn(|i| 0.8 * (1.3 * i as f64).cos()),
        ),
        2_000,
    );
    let c40 = Chain::<40>::default();
    model(
        "chain40",
        c40,
        |q, v| c40.hand_accelerations(q, v),
        None::<fn(&[f64; 1]) -> [f64; 1]>,
        (
            std::array::from_fn(|i| 0.5 * (0.7 * i as f64).sin()),
            std::array::from_fn(|i| 0.8 * (1.3 * i as f64).cos()),
        ),
        200,
    );
}
