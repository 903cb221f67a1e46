//! The cost of one right-hand side of a small natural system against a hand-written one (issue 16,
//! item 1): Kepler and Hénon-Heiles (2 dof) through `Natural::rates` (q̇ and q̈) and
//! `SplitDynamics::kick_rate` (q̈ alone, what the compositions call), and Kepler as a
//! `SeparableHamiltonian`. Each time is the minimum over 60 rounds of 10⁵ calls (interference only
//! adds time); the calls are independent, so this measures throughput, not latency.
//!
//! The models are written twice, with and without `#[inline]` on the model's method: without it the
//! method may land in another codegen unit than the kernel that calls it and is then not inlined,
//! and the dual numbers travel through memory (the hint gives each unit its own copy).
//!
//! `cargo bench -p noether-core --bench rates`; results in docs/benchmarks.md.

#![allow(missing_docs)]

use noether_core::integrators::SplitDynamics;
use noether_core::prelude::*;
use std::hint::black_box;

const IT: usize = 100_000;

use noether_testkit::henon_heiles::{composition_by_hand, HenonHeiles};
use noether_testkit::kepler::Kepler;
use noether_testkit::timing;

/// The same V without the hint.
struct KeplerPlain;
impl Potential for KeplerPlain {
    fn dof(&self) -> usize {
        2
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        -(q[0] * q[0] + q[1] * q[1]).sqrt().recip()
    }
}

/// The same V without the hint.
struct HenonHeilesPlain;
impl Potential for HenonHeilesPlain {
    fn dof(&self) -> usize {
        2
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        let (x, y) = (q[0], q[1]);
        (x * x + y * y) * 0.5 + x * x * y - y * y * y / 3.0
    }
}

type Hand = fn(&[f64; 2], &[f64; 2], &mut [f64; 2], &mut [f64; 2]);

#[inline(never)]
fn hand_kepler(q: &[f64; 2], v: &[f64; 2], dq: &mut [f64; 2], dv: &mut [f64; 2]) {
    let r2 = q[0] * q[0] + q[1] * q[1];
    let r3 = r2 * r2.sqrt();
    *dq = *v;
    dv[0] = -q[0] / r3;
    dv[1] = -q[1] / r3;
}

#[inline(never)]
fn hand_hh(q: &[f64; 2], v: &[f64; 2], dq: &mut [f64; 2], dv: &mut [f64; 2]) {
    let (x, y) = (q[0], q[1]);
    *dq = *v;
    dv[0] = -x - 2.0 * x * y;
    dv[1] = -y - x * x + y * y;
}

const Q: [f64; 2] = [0.7, -0.4];
const V: [f64; 2] = [0.3, 0.9];

fn time_hand(hand: Hand) -> f64 {
    let (mut dq, mut dv) = ([0.0; 2], [0.0; 2]);
    timing::min_ns(60, IT, || {
        let mut s = 0.0;
        for _ in 0..IT {
            hand(black_box(&Q), black_box(&V), &mut dq, &mut dv);
            s += dv[0];
        }
        s
    })
}

/// (Natural::rates, kick_rate) in ns per call.
fn time_natural<P: Potential>(p: P) -> (f64, f64) {
    let nat = Natural::unit(p);
    let (mut dq, mut dv) = ([0.0; 2], [0.0; 2]);
    let rates = timing::min_ns(60, IT, || {
        let mut s = 0.0;
        for _ in 0..IT {
            Dynamics::rates(&nat, 0.0, black_box(&Q), black_box(&V), &mut dq, &mut dv).unwrap();
            s += dv[0];
        }
        s
    });
    let kick = timing::min_ns(60, IT, || {
        let mut s = 0.0;
        for _ in 0..IT {
            nat.kick_rate(black_box(&Q), &mut dv).unwrap();
            s += dv[0];
        }
        s
    });
    (rates, kick)
}

fn main() {
    println!("| system | hand-written | Natural::rates | kick_rate | rates, model without #[inline] |");
    println!("|---|---|---|---|---|");
    for _ in 0..2 {
        let h = time_hand(hand_kepler);
        let (r, k) = time_natural(Kepler);
        let (rp, _) = time_natural(KeplerPlain);
        println!(
            "| Kepler | {h:.2} ns | {r:.2} ns ({:.2}×) | {k:.2} ns ({:.2}×) | {rp:.2} ns ({:.2}×) |",
            r / h,
            k / h,
            rp / h
        );
        let h = time_hand(hand_hh);
        let (r, k) = time_natural(HenonHeiles);
        let (rp, _) = time_natural(HenonHeilesPlain);
        println!(
            "| Hénon-Heiles | {h:.2} ns | {r:.2} ns ({:.2}×) | {k:.2} ns ({:.2}×) | {rp:.2} ns ({:.2}×) |",
            r / h,
            k / h,
            rp / h
        );
    }
    let sep = SeparableHamiltonian(Kepler);
    let (mut dq, mut dp) = ([0.0; 2], [0.0; 2]);
    let s = timing::min_ns(60, IT, || {
        let mut s = 0.0;
        for _ in 0..IT {
            Dynamics::rates(&sep, 0.0, black_box(&Q), black_box(&V), &mut dq, &mut dp).unwrap();
            s += dp[0];
        }
        s
    });
    println!("Kepler as SeparableHamiltonian, rates (two gradients): {s:.2} ns");
    composition_stage();
}

/// Kahan-Li 8 on Hénon-Heiles (q₀ = (0.1, 0), v₀ = (0, 0.5), h = 0.01), ns per stage (17 per step):
/// `Composition::step` on `Natural` against the same composition written by hand (adjacent half
/// kicks merged, the last force reused, as `Composition` does). Each stage depends on the one before,
/// so this measures latency. Minimum over 15 runs of 2·10⁴ steps, interleaved.
fn composition_stage() {
    use noether_core::integrators::Composition;
    const STEPS: usize = 20_000;
    let mut kl8 = Composition::kahan_li8(Natural::unit(HenonHeiles));
    let gammas = kl8.weights().as_slice().to_vec();
    let stages = (STEPS * gammas.len()) as f64;
    let hand = || composition_by_hand(&gammas, STEPS, 0.01, black_box([0.1, 0.0]), [0.0, 0.5]);
    let mut noether = || {
        let mut s = State::new(0.0, black_box([0.1, 0.0]), [0.0, 0.5]);
        for _ in 0..STEPS {
            kl8.step(&mut s, 0.01).unwrap();
        }
        s
    };
    // The same on (q, p) with H = ½|p|² + V: the drift is ∇T(p) by a gradient of its own.
    let mut kl8_sep = Composition::kahan_li8(SeparableHamiltonian(HenonHeiles));
    let mut separable = || {
        let mut s = State::with_momenta(0.0, black_box([0.1, 0.0]), [0.0, 0.5]);
        for _ in 0..STEPS {
            kl8_sep.step(&mut s, 0.01).unwrap();
        }
        s
    };
    let (mut th, mut tn, mut ts) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    let (mut qh, mut qn, mut qs) = ([0.0; 2], [0.0; 2], [0.0; 2]);
    for _ in 0..15 {
        let t0 = std::time::Instant::now();
        qh = black_box(hand()).0;
        th = th.min(t0.elapsed().as_nanos() as f64 / stages);
        let t0 = std::time::Instant::now();
        let s = black_box(noether());
        tn = tn.min(t0.elapsed().as_nanos() as f64 / stages);
        qn = [s.q[0], s.q[1]];
        let t0 = std::time::Instant::now();
        let s = black_box(separable());
        ts = ts.min(t0.elapsed().as_nanos() as f64 / stages);
        qs = [s.q[0], s.q[1]];
    }
    let dist = |a: [f64; 2]| (qh[0] - a[0]).abs().max((qh[1] - a[1]).abs());
    println!(
        "Kahan-Li 8 on Hénon-Heiles, per stage: hand-written {th:.2} ns, Composition on Natural {tn:.2} ns \
         ({:.2}×), on SeparableHamiltonian {ts:.2} ns ({:.2}×); |Δq| to the hand loop {:.1e}, {:.1e}",
        tn / th,
        ts / th,
        dist(qn),
        dist(qs)
    );
}
