//! The native backend (feature `jit`) against the interpreter, bit for bit: every operation of the
//! graph at random and special arguments, and the compiled test models (q̈, the energy, the
//! Jacobian, Hamilton's rates) at random states. Also the construction times and the time per call of
//! the two backends, printed (not asserted).

#![cfg(feature = "jit")]

use nalgebra::DMatrix;
use noether_compile::graph::{Binary, Graph, Id, Unary};
use noether_compile::{
    Backend, Compile, CompiledEulerLagrange, CompiledHamiltonEquations, CompiledNatural, Program,
};
use noether_core::system::LinearizedDynamics;
use noether_core::{hamiltonian, Dynamics, EulerLagrange, HamiltonEquations, Lagrangian, Natural};
use noether_testkit::agreement::uniform;
use noether_testkit::henon_heiles::HenonHeiles;
use noether_testkit::systems::{Chain, DoublePendulum, HeavyTop};
use std::time::Instant;

/// Equal bits, or both NaN (a NaN's payload is the hardware's or the library's, the same on both
/// paths here, but not part of the contract).
fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

const UNARY: [Unary; 22] = [
    Unary::Neg,
    Unary::Recip,
    Unary::Sqrt,
    Unary::Cbrt,
    Unary::Exp,
    Unary::ExpM1,
    Unary::Ln,
    Unary::Ln1p,
    Unary::Sin,
    Unary::Cos,
    Unary::Tan,
    Unary::Asin,
    Unary::Acos,
    Unary::Atan,
    Unary::Sinh,
    Unary::Cosh,
    Unary::Tanh,
    Unary::Asinh,
    Unary::Acosh,
    Unary::Atanh,
    Unary::Abs,
    Unary::Sign,
];

/// Every operation of the graph, one output each, in one program: native and interpreted agree bit
/// for bit on random arguments of several scales and on the special values (±0, ±∞, NaN, ±1).
#[test]
fn every_operation_bit_for_bit() {
    let mut g = Graph::new();
    let (x, y) = (g.input(0), g.input(1));
    let mut outputs: Vec<Id> = UNARY.iter().map(|&f| g.unary(f, x)).collect();
    for op in [Binary::Add, Binary::Sub, Binary::Mul, Binary::Div, Binary::Atan2] {
        outputs.push(g.binary(op, x, y));
    }
    for n in [-7, -3, -2, 3, 4, 5, 8, 13, 64] {
        outputs.push(g.powi(x, n));
    }
    for e in [0.37, -1.5, 2.5, 1e-3] {
        outputs.push(g.powf(x, e));
    }
    // An output that is an input, and one output twice.
    outputs.extend([y, outputs[3]]);
    let native = Program::new(&g, 2, &outputs);
    let interpreted = Program::interpreted(&g, 2, &outputs);
    assert_eq!(native.backend(), Backend::Native);
    assert_eq!(interpreted.backend(), Backend::Interpreter);
    assert_eq!(native.operations(), interpreted.operations());
    let special = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        1e-310,
        710.0,
    ];
    let mut rng = uniform(5);
    let mut points: Vec<[f64; 2]> = Vec::new();
    for a in special {
        for b in special {
            points.push([a, b]);
        }
    }
    for scale in [1e-8, 0.5, 1.0, 3.0, 1e3, 1e300] {
        for _ in 0..200 {
            points.push([rng(-scale, scale), rng(-scale, scale)]);
        }
    }
    let (mut a, mut b) = (vec![0.0; outputs.len()], vec![0.0; outputs.len()]);
    for p in &points {
        native.run(p, &mut a).unwrap();
        interpreted.run(p, &mut b).unwrap();
        for (k, (u, v)) in a.iter().zip(&b).enumerate() {
            assert!(
                same(*u, *v),
                "output {k} at {p:?}: native {u:e}, interpreter {v:e}"
            );
        }
    }
}

/// The two backends of one Lagrangian: q̈, the energy and the Jacobian bit for bit at `states`
/// random states drawn by `draw`.
fn lagrangian_bit_for_bit<L: Lagrangian + Clone>(
    l: &L,
    states: usize,
    draw: &mut impl FnMut() -> (Vec<f64>, Vec<f64>),
) {
    let native = EulerLagrange::new(l.clone()).compile().unwrap();
    let interpreted = CompiledEulerLagrange::interpreted(EulerLagrange::new(l.clone())).unwrap();
    assert_eq!(native.backend(), Backend::Native);
    assert_eq!(interpreted.backend(), Backend::Interpreter);
    let n = native.dof();
    for _ in 0..states {
        let (q, v) = draw();
        let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
        native.accelerations(0.3, &q, &v, &mut a).unwrap();
        interpreted.accelerations(0.3, &q, &v, &mut b).unwrap();
        assert!(a.iter().zip(&b).all(|(x, y)| same(*x, *y)), "{a:?} vs {b:?}");
        let (h, k) = (
            native.energy(0.3, &q, &v).unwrap(),
            interpreted.energy(0.3, &q, &v).unwrap(),
        );
        assert!(same(h, k), "{h} vs {k}");
        let (mut ja, mut jb) = (DMatrix::zeros(2 * n, 2 * n), DMatrix::zeros(2 * n, 2 * n));
        native.jacobian(0.3, &q, &v, &mut ja).unwrap();
        interpreted.jacobian(0.3, &q, &v, &mut jb).unwrap();
        assert!(ja.iter().zip(jb.iter()).all(|(x, y)| same(*x, *y)));
    }
}

#[test]
fn double_pendulum_bit_for_bit() {
    let mut rng = uniform(11);
    lagrangian_bit_for_bit(&DoublePendulum::default(), 300, &mut || {
        let q = vec![rng(-3.0, 3.0), rng(-3.0, 3.0)];
        let v = vec![rng(-3.0, 3.0), rng(-3.0, 3.0)];
        (q, v)
    });
}

#[test]
fn heavy_top_bit_for_bit() {
    let mut rng = uniform(12);
    lagrangian_bit_for_bit(&HeavyTop::default(), 300, &mut || {
        let q = vec![rng(0.3, 2.8), rng(-3.0, 3.0), rng(-3.0, 3.0)];
        let v = (0..3).map(|_| rng(-3.0, 3.0)).collect();
        (q, v)
    });
}

#[test]
fn chain_of_ten_bit_for_bit() {
    let mut rng = uniform(13);
    lagrangian_bit_for_bit(&Chain::<10>::default(), 100, &mut || {
        let q = (0..10).map(|_| rng(-1.0, 1.0)).collect();
        let v = (0..10).map(|_| rng(-1.0, 1.0)).collect();
        (q, v)
    });
}

/// Hamilton's rates and H of a time-dependent, non-separable H, bit for bit.
#[test]
fn hamilton_equations_bit_for_bit() {
    let h = hamiltonian!(dof = 2, params { w0: f64 = 0.7 }, |t, q, p| {
        let w = (t * 0.3).sin() * w0;
        let r2 = q[0] * q[0] + q[1] * q[1];
        (p[0] * p[0] + p[1] * p[1]) * 0.5 + (q[1] * p[0] - q[0] * p[1]) * w + r2 * r2 * 0.25
            - (q[0] * q[1]).cos()
    });
    let native = HamiltonEquations::new(h).compile().unwrap();
    let interpreted = CompiledHamiltonEquations::interpreted(HamiltonEquations::new(h)).unwrap();
    assert_eq!(native.backend(), Backend::Native);
    assert_eq!(interpreted.backend(), Backend::Interpreter);
    let mut rng = uniform(14);
    for _ in 0..300 {
        let t = rng(0.0, 4.0);
        let (q, p) = ([rng(-2.0, 2.0), rng(-2.0, 2.0)], [rng(-2.0, 2.0), rng(-2.0, 2.0)]);
        let (mut a, mut b) = ([0.0; 4], [0.0; 4]);
        let (dq, dp) = a.split_at_mut(2);
        native.rates(t, &q, &p, dq, dp).unwrap();
        let (dq, dp) = b.split_at_mut(2);
        interpreted.rates(t, &q, &p, dq, dp).unwrap();
        assert!(a.iter().zip(&b).all(|(x, y)| same(*x, *y)), "{a:?} vs {b:?}");
        let (e, f) = (
            native.energy(t, &q, &p).unwrap(),
            interpreted.energy(t, &q, &p).unwrap(),
        );
        assert!(same(e, f));
    }
}

/// A natural system's accelerations and their Jacobian −M⁻¹∇²V (Hénon-Heiles, V = ½(x² + y²) + x²y −
/// y³/3), native against interpreted, bit for bit.
#[test]
fn natural_bit_for_bit() {
    let native = Natural::unit(HenonHeiles).compile().unwrap();
    let interpreted = CompiledNatural::interpreted(Natural::unit(HenonHeiles)).unwrap();
    assert_eq!(native.backend(), Backend::Native);
    assert_eq!(interpreted.backend(), Backend::Interpreter);
    let mut rng = uniform(15);
    for _ in 0..300 {
        let (q, v) = ([rng(-1.0, 1.0), rng(-1.0, 1.0)], [rng(-1.0, 1.0), rng(-1.0, 1.0)]);
        let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
        native.accelerations(&q, &mut a).unwrap();
        interpreted.accelerations(&q, &mut b).unwrap();
        assert!(a.iter().zip(&b).all(|(x, y)| same(*x, *y)), "{a:?} vs {b:?}");
        let (mut ja, mut jb) = (DMatrix::zeros(4, 4), DMatrix::zeros(4, 4));
        native.jacobian(0.0, &q, &v, &mut ja).unwrap();
        interpreted.jacobian(0.0, &q, &v, &mut jb).unwrap();
        assert!(
            ja.iter().zip(jb.iter()).all(|(x, y)| same(*x, *y)),
            "{ja} vs {jb}"
        );
    }
}

/// The compiled systems are shared across threads (ensembles run them on rayon's): native code runs
/// on several threads at once, each with its own scratch buffer, and gives the same bits.
#[test]
fn send_sync_and_threads() {
    fn send_sync<T: Send + Sync>() {}
    send_sync::<Program>();
    send_sync::<CompiledEulerLagrange<DoublePendulum>>();
    send_sync::<CompiledHamiltonEquations<noether_testkit::systems::DoublePendulum>>();
    let c = EulerLagrange::new(DoublePendulum::default()).compile().unwrap();
    let mut reference = [0.0; 2];
    c.accelerations(0.0, &[0.4, -0.2], &[0.1, 0.3], &mut reference)
        .unwrap();
    std::thread::scope(|s| {
        for _ in 0..4 {
            s.spawn(|| {
                for _ in 0..1000 {
                    let mut a = [0.0; 2];
                    c.accelerations(0.0, &[0.4, -0.2], &[0.1, 0.3], &mut a).unwrap();
                    assert_eq!(a.map(f64::to_bits), reference.map(f64::to_bits));
                }
            });
        }
    });
    // A clone of a program shares its code and outlives the original.
    let mut g = Graph::new();
    let x = g.input(0);
    let s = g.unary(Unary::Sin, x);
    let p = Program::new(&g, 1, &[s]);
    let q = p.clone();
    drop(p);
    let mut out = [0.0];
    q.run(&[0.5], &mut out).unwrap();
    assert_eq!(out[0], 0.5_f64.sin());
}

/// Nanoseconds per call of `f`: the minimum over 7 rounds of `calls` calls.
fn per_call(calls: usize, mut f: impl FnMut()) -> f64 {
    (0..7)
        .map(|_| {
            let t0 = Instant::now();
            for _ in 0..calls {
                f();
            }
            t0.elapsed().as_secs_f64() * 1e9 / calls as f64
        })
        .fold(f64::INFINITY, f64::min)
}

/// Construction and per-call times of the two backends, printed: the double pendulum and the 40-link
/// chain (record + derive + simplify + compile), and q̈ per call. Not an assertion (the machine is
/// shared); `cargo test -p noether-compile --release --features jit --test compiled -- --ignored
/// --nocapture timings`.
#[test]
#[ignore]
fn timings() {
    fn build<L: Lagrangian + Clone>(name: &str, l: &L) {
        let t0 = Instant::now();
        let i = CompiledEulerLagrange::interpreted(EulerLagrange::new(l.clone())).unwrap();
        let ti = t0.elapsed();
        let t0 = Instant::now();
        let c = EulerLagrange::new(l.clone()).compile().unwrap();
        let tn = t0.elapsed();
        println!(
            "{name}: built in {:.1} ms interpreted, {:.1} ms native (opt_level speed); {} operations",
            ti.as_secs_f64() * 1e3,
            tn.as_secs_f64() * 1e3,
            c.operations().accelerations + c.operations().energy
        );
        let _ = i;
    }
    build("double pendulum", &DoublePendulum::default());
    build("10-link chain", &Chain::<10>::default());
    build("40-link chain", &Chain::<40>::default());
    let (q, v) = ([0.4, -0.3], [0.2, 0.7]);
    let native = EulerLagrange::new(DoublePendulum::default()).compile().unwrap();
    let interpreted =
        CompiledEulerLagrange::interpreted(EulerLagrange::new(DoublePendulum::default())).unwrap();
    let mut a = [0.0; 2];
    let calls = 200_000;
    let tn = per_call(calls, || {
        native
            .accelerations(0.0, std::hint::black_box(&q), &v, &mut a)
            .unwrap()
    });
    let ti = per_call(calls, || {
        interpreted
            .accelerations(0.0, std::hint::black_box(&q), &v, &mut a)
            .unwrap()
    });
    println!("double pendulum q̈: {ti:.1} ns/call interpreted, {tn:.1} ns/call native");
    let te = per_call(calls, || {
        std::hint::black_box(native.energy(0.0, std::hint::black_box(&q), &v).unwrap());
    });
    let m = DoublePendulum::default();
    let th = per_call(calls, || {
        std::hint::black_box(m.hand_accelerations(std::hint::black_box(&q), &v));
    });
    println!("double pendulum: energy {te:.1} ns/call native; hand-written q̈ {th:.1} ns/call");
    let q: [f64; 10] = std::array::from_fn(|i| 0.3 * (i as f64).sin());
    let native = EulerLagrange::new(Chain::<10>::default()).compile().unwrap();
    let interpreted = CompiledEulerLagrange::interpreted(EulerLagrange::new(Chain::<10>::default())).unwrap();
    let mut a = [0.0; 10];
    let calls = 5_000;
    let tn = per_call(calls, || {
        native
            .accelerations(0.0, std::hint::black_box(&q), &q, &mut a)
            .unwrap()
    });
    let ti = per_call(calls, || {
        interpreted
            .accelerations(0.0, std::hint::black_box(&q), &q, &mut a)
            .unwrap()
    });
    println!("10-link chain q̈: {ti:.1} ns/call interpreted, {tn:.1} ns/call native");
}
