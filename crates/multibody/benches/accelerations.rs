//! q̈ of a 7-link planar arm built from bodies and joints (`noether_testkit::multibody::rod_chain`),
//! per call, three ways: Lagrange's equations of the built L by dual numbers (`EulerLagrange`, the
//! generic path), the same equations compiled (`CompiledEulerLagrange`: recorded once, derived on the
//! graph, run by the interpreter), the recursive Newton-Euler algorithm on f64 (`NewtonEuler`), the
//! articulated-body algorithm on f64 (`ArticulatedBody`), and the articulated-body algorithm written
//! by hand for this arm (`hand_aba` below: the same spatial algebra with the arm's structure — a
//! chain, every joint a hinge about z, rods along x — written in, no allocation).
//!
//! A second group times the articulated-body algorithm, Newton-Euler and the dual-number path against
//! the number of links (2 to 28).
//!
//! Run: `cargo bench -p noether-multibody --bench accelerations`

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};
use noether_compile::CompiledEulerLagrange;
use noether_core::prelude::*;
use noether_multibody::{ArticulatedBody, NewtonEuler};
use noether_testkit::multibody::rod_chain;
use std::hint::black_box;
use std::time::Duration;

fn bench(c: &mut Criterion) {
    let n = 7;
    let masses: Vec<f64> = (0..n).map(|i| 1.0 - 0.08 * i as f64).collect();
    let lengths: Vec<f64> = (0..n).map(|i| 0.5 - 0.03 * i as f64).collect();
    let arm = rod_chain(&masses, &lengths, 9.81);
    let q: Vec<f64> = (0..n).map(|i| 0.3 + 0.2 * i as f64).collect();
    let v: Vec<f64> = (0..n).map(|i| 0.5 - 0.15 * i as f64).collect();
    let (mut dq, mut dv) = (vec![0.0; n], vec![0.0; n]);
    let mut group = c.benchmark_group("arm7_accelerations");
    group
        .sample_size(30)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    let el = EulerLagrange::new(arm.clone());
    group.bench_function("euler_lagrange_dual", |b| {
        b.iter(|| {
            el.rates(0.0, black_box(&q), black_box(&v), &mut dq, &mut dv)
                .unwrap()
        })
    });
    let compiled = CompiledEulerLagrange::new(EulerLagrange::new(arm.clone())).unwrap();
    group.bench_function("euler_lagrange_compiled", |b| {
        b.iter(|| {
            compiled
                .rates(0.0, black_box(&q), black_box(&v), &mut dq, &mut dv)
                .unwrap()
        })
    });
    let ne = NewtonEuler::new(arm.clone()).unwrap();
    group.bench_function("newton_euler", |b| {
        b.iter(|| {
            ne.rates(0.0, black_box(&q), black_box(&v), &mut dq, &mut dv)
                .unwrap()
        })
    });
    let aba = ArticulatedBody::new(arm).unwrap();
    group.bench_function("articulated_body", |b| {
        b.iter(|| {
            aba.rates(0.0, black_box(&q), black_box(&v), &mut dq, &mut dv)
                .unwrap()
        })
    });
    let hand = HandArm::new(&masses, &lengths, 9.81);
    let mut by_hand = [0.0; N];
    hand.accelerations(&q, &v, &mut by_hand);
    aba.rates(0.0, &q, &v, &mut dq, &mut dv).unwrap();
    let gap = by_hand
        .iter()
        .zip(&dv)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(
        gap < 1e-12 * dv.iter().fold(1.0_f64, |m, x| m.max(x.abs())),
        "the hand ABA is the arm's: {gap:e}"
    );
    group.bench_function("articulated_body_by_hand", |b| {
        b.iter(|| hand.accelerations(black_box(&q), black_box(&v), &mut by_hand))
    });
    group.finish();
}

/// The arm's number of links.
const N: usize = 7;

/// The articulated-body algorithm written by hand for the arm of `rod_chain` (Featherstone, *Rigid
/// Body Dynamics Algorithms*, Table 7.1): spatial vectors (angular; linear) in each link's frame, the
/// transform from link i − 1 to link i a turn by q_i about z after a shift by l_{i−1} along x, S = e_z
/// for every joint, gravity as an upward acceleration of the ground.
struct HandArm {
    /// Each rod's spatial inertia about its hinge, in its frame.
    inertia: [Matrix6<f64>; N],
    lengths: [f64; N],
    g: f64,
}

impl HandArm {
    fn new(masses: &[f64], lengths: &[f64], g: f64) -> Self {
        let inertia = std::array::from_fn(|i| {
            let (m, l) = (masses[i], lengths[i]);
            // A uniform rod along x from the hinge: centre (l/2, 0, 0), I_c = diag(0, 1, 1) m l²/12.
            let cx = Vector3::new(0.5 * l, 0.0, 0.0).cross_matrix();
            let ic = Matrix3::from_diagonal(&Vector3::new(0.0, 1.0, 1.0)) * (m * l * l / 12.0);
            let mut s = Matrix6::zeros();
            s.fixed_view_mut::<3, 3>(0, 0)
                .copy_from(&(ic + cx * cx.transpose() * m));
            s.fixed_view_mut::<3, 3>(0, 3).copy_from(&(cx * m));
            s.fixed_view_mut::<3, 3>(3, 0).copy_from(&(cx.transpose() * m));
            s.fixed_view_mut::<3, 3>(3, 3)
                .copy_from(&(Matrix3::identity() * m));
            s
        });
        HandArm {
            inertia,
            lengths: std::array::from_fn(|i| lengths[i]),
            g,
        }
    }

    /// The 6 × 6 transform X from link i − 1's frame to link i's: E = R_z(q)ᵀ, r = (shift, 0, 0).
    fn transform(q: f64, shift: f64) -> Matrix6<f64> {
        let (s, c) = q.sin_cos();
        let e = Matrix3::new(c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0);
        let mut x = Matrix6::zeros();
        x.fixed_view_mut::<3, 3>(0, 0).copy_from(&e);
        x.fixed_view_mut::<3, 3>(3, 3).copy_from(&e);
        x.fixed_view_mut::<3, 3>(3, 0)
            .copy_from(&(-e * Vector3::new(shift, 0.0, 0.0).cross_matrix()));
        x
    }

    fn accelerations(&self, q: &[f64], v: &[f64], out: &mut [f64; N]) {
        let cross_motion = |m: &Vector6<f64>, o: &Vector6<f64>| {
            let (w, u) = (m.fixed_rows::<3>(0), m.fixed_rows::<3>(3));
            let (w2, u2) = (o.fixed_rows::<3>(0), o.fixed_rows::<3>(3));
            let (a, b) = (w.cross(&w2), w.cross(&u2) + u.cross(&w2));
            Vector6::new(a.x, a.y, a.z, b.x, b.y, b.z)
        };
        let cross_force = |m: &Vector6<f64>, f: &Vector6<f64>| {
            let (w, u) = (m.fixed_rows::<3>(0), m.fixed_rows::<3>(3));
            let (n, f) = (f.fixed_rows::<3>(0), f.fixed_rows::<3>(3));
            let (a, b) = (w.cross(&n) + u.cross(&f), w.cross(&f));
            Vector6::new(a.x, a.y, a.z, b.x, b.y, b.z)
        };
        let z = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
        let mut x = [Matrix6::zeros(); N];
        let mut vel = [Vector6::zeros(); N];
        let mut c = [Vector6::zeros(); N];
        let mut ia = self.inertia;
        let mut pa = [Vector6::zeros(); N];
        for i in 0..N {
            x[i] = Self::transform(q[i], if i == 0 { 0.0 } else { self.lengths[i - 1] });
            let joint = z * v[i];
            vel[i] = if i == 0 { joint } else { x[i] * vel[i - 1] + joint };
            c[i] = cross_motion(&vel[i], &joint);
            pa[i] = cross_force(&vel[i], &(self.inertia[i] * vel[i]));
        }
        let (mut u, mut d, mut torque) = ([Vector6::zeros(); N], [0.0; N], [0.0; N]);
        for i in (0..N).rev() {
            u[i] = ia[i].column(2).into_owned();
            d[i] = u[i][2];
            torque[i] = -pa[i][2];
            if i > 0 {
                let a = ia[i] - u[i] * u[i].transpose() / d[i];
                let p = pa[i] + a * c[i] + u[i] * (torque[i] / d[i]);
                ia[i - 1] += x[i].transpose() * a * x[i];
                pa[i - 1] += x[i].transpose() * p;
            }
        }
        let mut acc = Vector6::new(0.0, 0.0, 0.0, 0.0, self.g, 0.0);
        for i in 0..N {
            let a = x[i] * acc + c[i];
            out[i] = (torque[i] - u[i].dot(&a)) / d[i];
            acc = a + z * out[i];
        }
    }
}

/// q̈ against the number of links n of the chain: the articulated-body algorithm is O(n), Newton-Euler
/// forming M by n passes O(n²) (then an O(n³) factorisation), Lagrange's equations by dual numbers
/// O(n³) and more (every second derivative of L through the whole chain).
fn scaling(c: &mut Criterion) {
    let mut group = c.benchmark_group("chain_accelerations_by_links");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_secs(1));
    for n in [2, 4, 7, 14, 28] {
        let masses: Vec<f64> = (0..n).map(|i| 1.0 - 0.02 * i as f64).collect();
        let lengths: Vec<f64> = (0..n).map(|i| 0.5 - 0.01 * i as f64).collect();
        let arm = rod_chain(&masses, &lengths, 9.81);
        let q: Vec<f64> = (0..n).map(|i| 0.3 + 0.2 * i as f64).collect();
        let v: Vec<f64> = (0..n).map(|i| 0.5 - 0.05 * i as f64).collect();
        let (mut dq, mut dv) = (vec![0.0; n], vec![0.0; n]);
        let aba = ArticulatedBody::new(arm.clone()).unwrap();
        group.bench_function(format!("articulated_body/{n}"), |b| {
            b.iter(|| {
                aba.rates(0.0, black_box(&q), black_box(&v), &mut dq, &mut dv)
                    .unwrap()
            })
        });
        let ne = NewtonEuler::new(arm.clone()).unwrap();
        group.bench_function(format!("newton_euler/{n}"), |b| {
            b.iter(|| {
                ne.rates(0.0, black_box(&q), black_box(&v), &mut dq, &mut dv)
                    .unwrap()
            })
        });
        let el = EulerLagrange::new(arm);
        group.bench_function(format!("euler_lagrange_dual/{n}"), |b| {
            b.iter(|| {
                el.rates(0.0, black_box(&q), black_box(&v), &mut dq, &mut dv)
                    .unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench, scaling);
criterion_main!(benches);
