//! Force-evaluation benchmarks of noether-particles against hand-written loops (docs/benchmarks.md).
//!
//! `cargo bench -p noether-particles --bench forces` (all groups, ~1 minute), or one group with a filter,
//! e.g. `cargo bench -p noether-particles --bench forces -- chain_1e5`.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use noether_particles::prelude::*;
use std::hint::black_box;
use std::time::Duration;

const K: f64 = 1.0;
const RE: f64 = 1.0;
const K2: f64 = 0.5;
const K4: f64 = 0.1;

/// A chain along x, slightly perturbed, in the flat 3N layout.
fn chain_positions(n: usize) -> Vec<f64> {
    (0..n)
        .flat_map(|i| {
            let s = (i as f64 * 0.7).sin();
            [i as f64 * RE + 0.1 * s, 0.05 * s, -0.03 * s]
        })
        .collect()
}

fn chain_system(n: usize) -> System<impl noether_particles::Interaction> {
    // Nearest-neighbour springs and an on-site potential ½ k2 d² + ¼ k4 d⁴ (d = |r|) on every mass.
    System::new(vec![Particle::new(1.0); n])
        .unwrap()
        .with(Internal::chain(Spring { k: K, re: RE }, n))
        .unwrap()
        .with(External::new(
            Trap {
                k2: K2,
                k4: K4,
                center: [0.0; 3],
            },
            0..n,
        ))
        .unwrap()
        .parallel(Parallel::Serial)
}

/// The same forces written by hand: springs −k (r − re) r̂ between neighbours, on-site −(k2 + k4 d²) d.
#[inline(never)]
fn chain_hand(x: &[f64], f: &mut [f64]) -> f64 {
    let n = x.len() / 3;
    f.iter_mut().for_each(|a| *a = 0.0);
    let mut e = 0.0;
    for i in 1..n {
        let r = [
            x[3 * i] - x[3 * i - 3],
            x[3 * i + 1] - x[3 * i - 2],
            x[3 * i + 2] - x[3 * i - 1],
        ];
        let d = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        let s = K * (d - RE);
        e += 0.5 * s * (d - RE);
        let c = s / d;
        for k in 0..3 {
            f[3 * i - 3 + k] += c * r[k];
            f[3 * i + k] -= c * r[k];
        }
    }
    for i in 0..n {
        let d2 = x[3 * i] * x[3 * i] + x[3 * i + 1] * x[3 * i + 1] + x[3 * i + 2] * x[3 * i + 2];
        e += 0.5 * K2 * d2 + 0.25 * K4 * d2 * d2;
        let c = K2 + K4 * d2;
        for k in 0..3 {
            f[3 * i + k] -= c * x[3 * i + k];
        }
    }
    e
}

fn chain(c: &mut Criterion) {
    let mut g = c.benchmark_group("chain_1e5");
    g.sample_size(20).measurement_time(Duration::from_secs(3));
    let n = 100_000;
    let x = chain_positions(n);
    let sys = chain_system(n);
    let mut f = vec![0.0; 3 * n];
    g.bench_function("noether", |b| {
        b.iter(|| sys.potential_forces(0.0, black_box(&x), &mut f).unwrap())
    });
    g.bench_function("hand", |b| b.iter(|| chain_hand(black_box(&x), &mut f)));
    g.finish();

    let mut g = c.benchmark_group("chain_scaling");
    g.sample_size(10).measurement_time(Duration::from_secs(2));
    for n in [1_000, 10_000, 100_000, 1_000_000] {
        let x = chain_positions(n);
        let sys = chain_system(n);
        let mut f = vec![0.0; 3 * n];
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| sys.potential_forces(0.0, black_box(&x), &mut f).unwrap())
        });
    }
    g.finish();
}

#[inline(never)]
fn gravity_hand(x: &[f64], m: &[f64], f: &mut [f64]) -> f64 {
    let n = m.len();
    f.iter_mut().for_each(|a| *a = 0.0);
    let mut e = 0.0;
    for i in 0..n {
        for j in i + 1..n {
            let r = [
                x[3 * j] - x[3 * i],
                x[3 * j + 1] - x[3 * i + 1],
                x[3 * j + 2] - x[3 * i + 2],
            ];
            let d2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
            let d = d2.sqrt();
            let gm = m[i] * m[j];
            e -= gm / d;
            let c = gm / (d2 * d);
            for k in 0..3 {
                f[3 * i + k] += c * r[k];
                f[3 * j + k] -= c * r[k];
            }
        }
    }
    e
}

fn gravity(c: &mut Criterion) {
    let mut g = c.benchmark_group("gravity_1000");
    g.sample_size(20).measurement_time(Duration::from_secs(3));
    let n = 1000;
    let x: Vec<f64> = (0..3 * n)
        .map(|k| ((k as f64) * 0.618_033_988_7).fract() * 10.0)
        .collect();
    let m: Vec<f64> = (0..n).map(|i| 1.0 + (i % 7) as f64 * 0.1).collect();
    let sys = System::new(m.iter().map(|&mi| Particle::new(mi)).collect())
        .unwrap()
        .with(AllPairs::new(Gravity { g: 1.0 }))
        .unwrap()
        .parallel(Parallel::Serial);
    let mut f = vec![0.0; 3 * n];
    g.bench_function("noether", |b| {
        b.iter(|| sys.potential_forces(0.0, black_box(&x), &mut f).unwrap())
    });
    g.bench_function("hand", |b| b.iter(|| gravity_hand(black_box(&x), &m, &mut f)));
    g.finish();
}

/// A simple cubic lattice of spacing re, jittered by 5%, side ⌈N^{1/3}⌉ (first N points).
fn lattice(n: usize) -> Vec<f64> {
    let side = (n as f64).cbrt().ceil() as usize;
    (0..n)
        .flat_map(|i| {
            let (a, b, c) = (i % side, (i / side) % side, i / (side * side));
            let j = |s: f64| 0.05 * ((i as f64 + s) * 1.618_033_988_7).fract();
            [a as f64 + j(0.1), b as f64 + j(0.2), c as f64 + j(0.3)]
        })
        .collect()
}

fn lennard_jones(c: &mut Criterion) {
    let mut g = c.benchmark_group("lj_cutoff");
    g.sample_size(10).measurement_time(Duration::from_secs(2));
    // Cutoff 2.5σ with σ = re/2^{1/6}.
    let rc = 2.5 / 2f64.powf(1.0 / 6.0);
    for n in [10_000, 100_000, 1_000_000] {
        let x = lattice(n);
        let mut f = vec![0.0; 3 * n];
        for (name, par) in [("serial", Parallel::Serial), ("rayon", Parallel::Rayon)] {
            let sys = System::new(vec![Particle::new(1.0); n])
                .unwrap()
                .with(ShortRange::new(LennardJones::with_cutoff(1.0, 1.0, rc)).unwrap())
                .unwrap()
                .parallel(par);
            g.bench_with_input(BenchmarkId::new(name, n), &n, |b, _| {
                b.iter(|| sys.potential_forces(0.0, black_box(&x), &mut f).unwrap())
            });
        }
    }
    g.finish();
}

criterion_group!(benches, chain, gravity, lennard_jones);
criterion_main!(benches);
