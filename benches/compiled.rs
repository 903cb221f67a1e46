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
//! Then Hamilton's equations of the double pendulum's H built from L (`LegendreTransform::new(l)
//! .compile()`: the transform in closed form on the graph) against the same equations written by
//! hand and against `LegendreTransform` by dual numbers (Newton per call): `ratio
//! legendre_double_pendulum <compiled / hand>`.
//!
//! Then Kahan-Li 8 on Hénon-Heiles (q₀ = (0.1, 0), q̇₀ = (0, 0.5), h = 0.01, 2·10⁴ steps): the
//! composition written by hand in closed form against `Composition::kahan_li8` on the compiled
//! `Natural` and on `Natural` by dual numbers, per stage (`ratio henon_heiles_kl8 <compiled / hand>`,
//! with the distance of each end point to the hand loop's).
//!
//! `cargo bench --bench compiled --features jit` (the native column needs the feature); results in
//! docs/benchmarks.md.

#![allow(missing_docs)]

use noether::compile::{Backend, Compile, CompiledEulerLagrange};
use noether::core::integrators::Composition;
use noether::core::{
    Dynamics, EulerLagrange, HamiltonEquations, Lagrangian, LegendreTransform, Natural, State, Stepper,
    Velocities,
};
use std::hint::black_box;
use std::time::Instant;

#[allow(dead_code)]
mod generated {
    include!("generated/double_pendulum.rs");
    include!("generated/heavy_top.rs");
    include!("generated/chain10.rs");
}
use noether_testkit::henon_heiles::{composition_by_hand, HenonHeiles};
use noether_testkit::systems::{Chain, DoublePendulum, DoublePendulumH, HeavyTop};

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

/// Hamilton's equations of the double pendulum's H from L: by hand, compiled, by dual numbers.
fn legendre_double_pendulum() {
    let dp = DoublePendulum::default();
    let hand = DoublePendulumH(dp);
    let t0 = Instant::now();
    let compiled = LegendreTransform::new(dp).compile().unwrap();
    let build = t0.elapsed();
    let dual = HamiltonEquations::new(LegendreTransform::new(dp));
    let (q, p) = ([0.6, -0.4], [1.3, -0.7]);
    let (mut dq, mut dp_) = ([0.0; 2], [0.0; 2]);
    let (mut eq, mut ep) = ([0.0; 2], [0.0; 2]);
    let [th, tc, td] = race(
        15,
        20_000,
        [
            &mut || {
                black_box(hand.hand_rates(black_box(&q), black_box(&p)));
            },
            &mut || {
                compiled
                    .rates(0.0, black_box(&q), black_box(&p), &mut dq, &mut dp_)
                    .unwrap();
                black_box((&dq, &dp_));
            },
            &mut || {
                dual.rates(0.0, black_box(&q), black_box(&p), &mut eq, &mut ep)
                    .unwrap();
                black_box((&eq, &ep));
            },
        ],
    );
    println!(
        "ratio legendre_double_pendulum {:.2}   (hand {th:.1} ns; compiled {tc:.1} ns; LegendreTransform by \
         dual numbers {td:.1} ns = {:.2}×; built in {:.2} ms, {} operations)",
        tc / th,
        td / th,
        build.as_secs_f64() * 1e3,
        compiled.operations()
    );
}

/// Kahan-Li 8 on Hénon-Heiles: the hand loop, the compiled `Natural`, the dual-number `Natural`.
fn henon_heiles_kl8() {
    const STEPS: usize = 20_000;
    let t0 = Instant::now();
    let compiled = Natural::unit(HenonHeiles).compile().unwrap();
    let build = t0.elapsed();
    let mut kl8 = Composition::kahan_li8(compiled);
    let mut dual = Composition::kahan_li8(Natural::unit(HenonHeiles));
    let gammas = kl8.weights().as_slice().to_vec();
    let stages = (STEPS * gammas.len()) as f64;
    let (mut qh, mut qc, mut qd) = ([0.0; 2], [0.0; 2], [0.0; 2]);
    fn run<S: Stepper<Partner = Velocities>>(stepper: &mut S) -> [f64; 2] {
        let mut s = State::new(0.0, black_box([0.1, 0.0]), [0.0, 0.5]);
        for _ in 0..STEPS {
            stepper.step(&mut s, 0.01).unwrap();
        }
        [s.q[0], s.q[1]]
    }
    let [th, tc, td] = race(
        15,
        1,
        [
            &mut || {
                qh = black_box(composition_by_hand(
                    &gammas,
                    STEPS,
                    0.01,
                    black_box([0.1, 0.0]),
                    [0.0, 0.5],
                ))
                .0
            },
            &mut || qc = run(&mut kl8),
            &mut || qd = run(&mut dual),
        ],
    )
    .map(|t| t / stages);
    let dist = |a: [f64; 2]| (qh[0] - a[0]).abs().max((qh[1] - a[1]).abs());
    println!(
        "ratio henon_heiles_kl8 {:.2}   (per stage: hand {th:.2} ns; compiled {tc:.2} ns; dual numbers {td:.2} ns = \
         {:.2}×; |Δq| to the hand loop {:.1e} compiled, {:.1e} dual; built in {:.2} ms, {} operations)",
        tc / th,
        td / th,
        dist(qc),
        dist(qd),
        build.as_secs_f64() * 1e3,
        kl8.base().system().operations()
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
    legendre_double_pendulum();
    henon_heiles_kl8();
}
