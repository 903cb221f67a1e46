//! Variational integrator speed: one coupled-chains midpoint step (40 dof, 400 Gaussian pairs) by
//! noether (term-by-term AD, Newton; by default the last step's Jacobian factor is reused, and also with
//! a fresh Jacobian every step as the hand code does) against a hand-written midpoint Newton step with
//! the analytic gradient and Hessian of V (a fresh Jacobian every step); and one midpoint step of a quartic chain of N masses (banded Jacobian)
//! for N = 10², 10³, 10⁴, 10⁵ (cost linear in N); and whole optimal-control solves by discrete mechanics
//! (`optimal_control`): the cart-pole swung up in T = 2 with N = 100 steps from the straight line (12
//! Newton iterations on the banded KKT system), the same swing-up with the force bounded by |u| ≤ 12
//! (SQP with Clarabel's subproblems, then Newton on the active set) and in T = 2.5 where only the SQP
//! solve converges (infinite bounds), and the double integrator's minimum-effort transfer with
//! N = 1000 (3 iterations) and with |u| ≤ 5 (T = 1).
//!
//! Run: `cargo bench -p noether-discrete --bench variational`

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::{DMatrix, DVector};
use noether_core::{Newton, State, Stepper};
use noether_discrete::chains::{CoupledChains, QuarticChain};
use noether_discrete::{Mass, Mechanical, MechanicalMidpoint};
use std::hint::black_box;
use std::time::Duration;

/// Hand-written ∇V and ∇²V of the coupled chains.
fn grad_hess(ch: &CoupledChains, q: &[f64], g: &mut [f64], hess: Option<&mut DMatrix<f64>>) {
    let n = ch.n;
    g.iter_mut().for_each(|x| *x = 0.0);
    let mut hm = hess;
    if let Some(h) = hm.as_deref_mut() {
        h.fill(0.0);
    }
    for c in 0..2 {
        for i in 0..n - 1 {
            let (a, b) = (c * n + i, c * n + i + 1);
            let f = ch.k1 * (q[b] - q[a] - ch.l);
            g[b] += f;
            g[a] -= f;
            if let Some(h) = hm.as_deref_mut() {
                h[(a, a)] += ch.k1;
                h[(b, b)] += ch.k1;
                h[(a, b)] -= ch.k1;
                h[(b, a)] -= ch.k1;
            }
        }
    }
    let s2 = ch.sigma * ch.sigma;
    for i in 0..n {
        for j in 0..n {
            let (a, b) = (i, n + j);
            let d = q[a] - q[b];
            let e = ch.k2 * (-0.5 * d * d / s2).exp();
            let f = -d / s2 * e;
            g[a] += f;
            g[b] -= f;
            if let Some(h) = hm.as_deref_mut() {
                let k = (d * d / s2 - 1.0) / s2 * e;
                h[(a, a)] += k;
                h[(b, b)] += k;
                h[(a, b)] -= k;
                h[(b, a)] -= k;
            }
        }
    }
}

/// A hand-written midpoint Newton step on the increment d (same predictor and tolerance as noether's).
fn hand_step(ch: &CoupledChains, q: &mut [f64], p: &mut [f64], d: &mut [f64], h: f64, tol: f64) {
    let n = q.len();
    let (mut g, mut mid, mut r) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut jac = DMatrix::zeros(n, n);
    let mut lu: Option<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>> = None;
    for _ in 0..50 {
        (0..n).for_each(|i| mid[i] = q[i] + 0.5 * d[i]);
        grad_hess(ch, &mid, &mut g, None);
        (0..n).for_each(|i| r[i] = d[i] / h + 0.5 * h * g[i] - p[i]);
        if r.iter().fold(0.0_f64, |m, x| m.max(x.abs())) <= tol {
            break;
        }
        if lu.is_none() {
            grad_hess(ch, &mid, &mut g, Some(&mut jac));
            jac *= 0.25 * h;
            (0..n).for_each(|i| jac[(i, i)] += 1.0 / h);
            lu = Some(jac.clone().lu());
        }
        let dx = lu
            .as_ref()
            .unwrap()
            .solve(&DVector::from_column_slice(&r))
            .unwrap();
        (0..n).for_each(|i| d[i] -= dx[i]);
    }
    (0..n).for_each(|i| {
        p[i] = d[i] / h - 0.5 * h * g[i];
        q[i] += d[i];
    });
}

fn coupled_chains(c: &mut Criterion) {
    let ch = CoupledChains::paper(0.001);
    let h = ch.paper_step();
    let p0: Vec<f64> = (0..40).map(|k| if k < 20 { 0.1 } else { 0.0 }).collect();
    // Start in the collision (t = 20), where the coupling acts.
    let sys = Mechanical::new(Mass::Diagonal(vec![1.0; 40]), ch.clone()).unwrap();
    let mut vi = MechanicalMidpoint::new(sys).newton(Newton::default().residual_tolerance(1e-8).unwrap());
    let mut s = State::with_momenta(0.0, ch.collision_start(), p0);
    for _ in 0..200 {
        vi.step(&mut s, h).unwrap();
    }
    let mut group = c.benchmark_group("coupled_chains_step");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_secs(1));
    let start = s.clone();
    group.bench_function("noether", |b| {
        let mut st = start.clone();
        b.iter(|| {
            if st.t > start.t + 20.0 {
                st = start.clone();
            }
            vi.step(black_box(&mut st), h).unwrap();
        })
    });
    // The same algorithm as the hand-written step: a fresh Jacobian at every step.
    let sys = Mechanical::new(Mass::Diagonal(vec![1.0; 40]), ch.clone()).unwrap();
    let newton = Newton::default()
        .residual_tolerance(1e-8)
        .unwrap()
        .reuse_jacobian(false);
    let mut fresh = MechanicalMidpoint::new(sys).newton(newton);
    group.bench_function("noether_fresh_jacobian", |b| {
        let mut st = start.clone();
        b.iter(|| {
            if st.t > start.t + 20.0 {
                st = start.clone();
            }
            fresh.step(black_box(&mut st), h).unwrap();
        })
    });
    group.bench_function("hand", |b| {
        let (mut q, mut p) = (start.q.as_slice().to_vec(), start.v.as_slice().to_vec());
        let mut d: Vec<f64> = p.iter().map(|x| x * h).collect();
        let mut k = 0;
        b.iter(|| {
            k += 1;
            if k % 200 == 0 {
                q.copy_from_slice(start.q.as_slice());
                p.copy_from_slice(start.v.as_slice());
            }
            hand_step(&ch, black_box(&mut q), &mut p, &mut d, h, 1e-8);
        })
    });
    group.finish();
}

fn quartic_chain(c: &mut Criterion) {
    let mut group = c.benchmark_group("quartic_chain_step");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    for n in [100, 1_000, 10_000, 100_000] {
        let chain = QuarticChain {
            n,
            k: 1.0,
            a: 0.5,
            b: 1.0,
        };
        let sys = Mechanical::new(Mass::Diagonal(vec![1.0; n]), chain).unwrap();
        let mut vi = MechanicalMidpoint::new(sys);
        let q: Vec<f64> = (0..n).map(|i| 0.3 * (0.01 * i as f64).sin()).collect();
        let mut s = State::with_momenta(0.0, q, vec![0.0; n]);
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| vi.step(black_box(&mut s), 0.1).unwrap())
        });
    }
    group.finish();
}

fn optimal_control(c: &mut Criterion) {
    use noether_discrete::optimal_control::{Effort, OptimalControl};
    use noether_discrete::Midpoint;
    use noether_testkit::control::{CartPole, DoubleIntegrator};
    use std::f64::consts::PI;
    let mut group = c.benchmark_group("optimal_control");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    let swing = OptimalControl::new(
        Midpoint::new(CartPole::default()),
        Effort::new(vec![1.0]).unwrap(),
    );
    group.bench_function("cart_pole_swing_up_N100", |b| {
        b.iter(|| {
            swing
                .solve(
                    0.0,
                    (&[0.0, PI], &[0.0, 0.0]),
                    2.0,
                    (&[0.0, 0.0], &[0.0, 0.0]),
                    black_box(100),
                )
                .unwrap()
        })
    });
    for (name, t_end, bound) in [
        ("cart_pole_swing_up_N100_bounded", 2.0, 12.0),
        ("cart_pole_swing_up_T2.5_N100_sqp", 2.5, f64::INFINITY),
    ] {
        let bounded = OptimalControl::new(
            Midpoint::new(CartPole::default()),
            Effort::new(vec![1.0]).unwrap(),
        )
        .input_bounds(&[-bound], &[bound])
        .unwrap();
        group.bench_function(name, |b| {
            b.iter(|| {
                bounded
                    .solve(
                        0.0,
                        (&[0.0, PI], &[0.0, 0.0]),
                        t_end,
                        (&[0.0, 0.0], &[0.0, 0.0]),
                        black_box(100),
                    )
                    .unwrap()
            })
        });
    }
    let transfer = OptimalControl::new(Midpoint::new(DoubleIntegrator), Effort::new(vec![1.0]).unwrap());
    let saturated = OptimalControl::new(Midpoint::new(DoubleIntegrator), Effort::new(vec![1.0]).unwrap())
        .input_bounds(&[-5.0], &[5.0])
        .unwrap();
    group.bench_function("double_integrator_N1000_bounded", |b| {
        b.iter(|| {
            saturated
                .solve(0.0, (&[0.0], &[0.0]), 1.0, (&[1.0], &[0.0]), black_box(1000))
                .unwrap()
        })
    });
    group.bench_function("double_integrator_N1000", |b| {
        b.iter(|| {
            transfer
                .solve(0.0, (&[0.0], &[0.0]), 2.0, (&[1.0], &[0.0]), black_box(1000))
                .unwrap()
        })
    });
    group.finish();
}

criterion_group!(benches, coupled_chains, quartic_chain, optimal_control);
criterion_main!(benches);
