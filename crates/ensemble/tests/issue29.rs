//! Issue 29: ensembles whose members share a model with internal state are bit-identical to ensembles
//! with one model per member, on 1, 2 and 4 threads; a panicking member is that member's failure; a
//! member index out of range is a typed error; axes and histograms over huge ranges stay finite.

use noether_core::prelude::*;
use noether_ensemble::{Axis, Ensemble, Error, Grid, Histogram, Mean, MemberError, Members, Sampler};
use proptest::prelude::*;

/// A pendulum whose inertia grows with its speed, L = 0.8 (cosh θ̇ − 1) + cos θ (convex in θ̇,
/// p = 0.8 sinh θ̇): through the Legendre transform every evaluation of H solves for θ̇ by Newton in
/// several iterations, so where the solve starts shows in the last bits.
struct StiffPendulum;
impl Lagrangian for StiffPendulum {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0].cosh() - 1.0) * 0.8 + q[0].cos()
    }
}

/// Its energy in (θ, p): H = p θ̇ − L with θ̇ = asinh(p/0.8).
fn energy(q: f64, p: f64) -> f64 {
    let v = (p / 0.8).asinh();
    p * v - 0.8 * (v.cosh() - 1.0) - q.cos()
}

type Model = HamiltonEquations<LegendreTransform<StiffPendulum>>;

fn model() -> Model {
    HamiltonEquations::new(LegendreTransform::new(StiffPendulum))
}

/// `steps` Gauss-4 steps of 0.05 from θ = a, p = 0.3: the bits of the end state.
fn gauss4_end(h: &Model, a: f64, steps: usize) -> Result<[u64; 3], noether_core::Error> {
    let sol = Driver::new(Gauss::gauss4(h), State::with_momenta(0.0, [a], [0.3]))?
        .step_size(0.05)?
        .save(Save::End)?
        .run_until(0.05 * steps as f64)?;
    let s = sol.last();
    Ok([s.t, s.q[0], s.v[0]].map(f64::to_bits))
}

/// The bits of the mean end angle of an ensemble of [`gauss4_end`] runs, by the ensemble's reduction.
fn mean_of_q<F>(ens: &Ensemble<Vec<f64>, F>) -> u64
where
    F: Fn(usize, &f64) -> Result<[u64; 3], noether_core::Error> + Sync,
{
    let q = ens.run().values().expect("every member runs");
    let q: Vec<f64> = q.iter().map(|e| f64::from_bits(e[1])).collect();
    Ensemble::new(q, |_, x: &f64| Ok::<_, ()>(*x))
        .reduce(&Mean)
        .value
        .mean
        .to_bits()
}

/// Runs `f` on a rayon pool of `threads` threads.
fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
        .install(f)
}

/// Issue 29 item 5: 200 Gauss-4 members sharing one `HamiltonEquations<LegendreTransform<L>>` differed
/// from per-member models in 2–18 members by up to 7e-15 (the transform's warm start was shared behind
/// a `Mutex`, so a member's result depended on which member ran before it on its thread). Now every
/// member's end state has the same bits, shared or not, on 1, 2 and 4 threads, and so has the mean.
#[test]
fn regress_shared_legendre_model_is_bit_identical_on_1_2_4_threads() {
    let amplitudes: Vec<f64> = (0..200).map(|i| 0.1 + 0.013 * i as f64).collect();
    let own = Ensemble::new(amplitudes.clone(), |_, a: &f64| gauss4_end(&model(), *a, 40));
    let expected: Vec<[u64; 3]> = on_threads(1, || own.run()).values().expect("every member runs");
    // Gauss-4 keeps the energy (a solution of this model, not of another).
    for (a, e) in amplitudes.iter().zip(&expected) {
        let (q, p) = (f64::from_bits(e[1]), f64::from_bits(e[2]));
        assert_eq!(f64::from_bits(e[0]), 2.0);
        assert!(
            (energy(q, p) - energy(*a, 0.3)).abs() < 1e-6,
            "energy drift at a = {a}"
        );
    }
    let shared = model();
    let together = Ensemble::new(amplitudes, |_, a: &f64| gauss4_end(&shared, *a, 40));
    let reference_mean = on_threads(1, || mean_of_q(&own));
    for threads in [1, 2, 4] {
        let got = on_threads(threads, || together.run())
            .values()
            .expect("every member runs");
        let differ: Vec<usize> = (0..got.len()).filter(|&i| got[i] != expected[i]).collect();
        assert!(differ.is_empty(), "{threads} threads: members {differ:?} differ");
        let again = on_threads(threads, || own.run())
            .values()
            .expect("every member runs");
        assert_eq!(again, expected, "per-member models on {threads} threads");
        assert_eq!(on_threads(threads, || mean_of_q(&together)), reference_mean);
    }
}

/// Issue 29 item 11: a member whose closure panicked took the whole ensemble down (rayon re-raised the
/// panic in the caller). Now it is that member's failure, with the panic's message; the other members'
/// results are kept, in `run` and in `reduce`, and in `run_member`.
#[test]
fn regress_a_panicking_member_is_its_own_failure() {
    let xs: Vec<f64> = (0..16).map(f64::from).collect();
    let ens = Ensemble::new(xs, |i, x: &f64| {
        if i == 3 {
            panic!("member {i} exploded");
        }
        if i == 11 {
            let v: Vec<f64> = Vec::new();
            return Ok(v[i]); // an index out of bounds: a panic with a formatted String payload
        }
        if i == 7 {
            return Err("a returned error".to_string());
        }
        Ok(*x)
    })
    .chunk_size(4)
    .expect("chunk");
    let runs = on_threads(2, || ens.run());
    assert_eq!(runs.len(), 16);
    let failed: Vec<usize> = runs.failures().map(|(i, _)| i).collect();
    assert_eq!(failed, vec![3, 7, 11]);
    let errors: Vec<&MemberError<String>> = runs.failures().map(|(_, e)| e).collect();
    assert_eq!(errors[0].panicked(), Some("member 3 exploded"));
    assert_eq!(errors[1], &MemberError::Failed("a returned error".to_string()));
    assert!(errors[2]
        .panicked()
        .expect("a panic")
        .contains("index out of bounds"));
    assert!(runs
        .successes()
        .all(|(i, &x)| x == i as f64 && ![3, 7, 11].contains(&i)));
    assert_eq!(runs.successes().count(), 13);
    let reduced = on_threads(4, || ens.reduce(&Mean));
    assert_eq!(reduced.value.n, 13);
    assert_eq!(
        reduced.failures.iter().map(|f| f.index).collect::<Vec<_>>(),
        vec![3, 7, 11]
    );
    match reduced.into_value() {
        Err(Error::MemberFailed {
            index: 3,
            failed: 3,
            message,
        }) => assert!(message.contains("member 3 exploded"), "{message}"),
        other => panic!("expected MemberFailed, got {other:?}"),
    }
    assert!(matches!(ens.run_member(3), Err(MemberError::Panicked { .. })));
    assert_eq!(ens.run_member(4), Ok(4.0));
    // A sampler whose draw panics: the member fails, the others run.
    let sampler = Sampler::new(5, 1, |rng: &mut noether_ensemble::MemberRng| {
        use noether_ensemble::rand::Rng;
        let x: f64 = rng.random();
        assert!(x < 2.0, "never");
        x
    });
    let draws = Ensemble::new(sampler, |i, x: &f64| {
        assert_ne!(i, 2, "member 2 refuses");
        Ok::<_, ()>(*x)
    });
    let runs = draws.run();
    assert_eq!(runs.failures().map(|(i, _)| i).collect::<Vec<_>>(), vec![2]);
    assert!(runs
        .failures()
        .all(|(_, e)| e.panicked().is_some_and(|m| m.contains("member 2 refuses"))));
}

/// Issue 29 items 6 and 11: `Grid::member` wrapped an index out of range (member 6 of a 6-point grid
/// was member 0), and `Members::member` of a list or `Ensemble::run_member` out of range panicked.
#[test]
fn bad_input_member_index_out_of_range() {
    fn no<T>(index: usize, members: usize) -> Result<T, Error> {
        Err(Error::NoSuchMember { index, members })
    }
    let grid = Grid::new(vec![
        Axis::linspace(0.0, 1.0, 3).expect("axis"),
        Axis::values(vec![10.0, 20.0]).expect("axis"),
    ])
    .expect("grid");
    assert_eq!(grid.member(5), Ok(vec![1.0, 20.0]));
    assert_eq!(grid.member(6), no(6, 6));
    assert_eq!(grid.member(usize::MAX), no(usize::MAX, 6));
    assert_eq!(grid.multi_index(6), no(6, 6));
    let list = vec![1.5, 2.5];
    assert_eq!(list.member(1), Ok(2.5));
    assert_eq!(list.member(2), no(2, 2));
    assert_eq!(list.as_slice().member(7), no(7, 2));
    let sampler = Sampler::new(3, 0, |_: &mut noether_ensemble::MemberRng| 1.0);
    assert_eq!(sampler.member(3), no(3, 3));
    let ens = Ensemble::new(list, |_, x: &f64| Ok::<_, String>(*x));
    assert_eq!(ens.run_member(1), Ok(2.5));
    assert_eq!(
        ens.run_member(2),
        Err(MemberError::Ensemble(Error::NoSuchMember {
            index: 2,
            members: 2
        }))
    );
    let text = ens.run_member(9).expect_err("no member 9").to_string();
    assert!(text.contains("no member 9"), "{text}");
}

/// Issue 29 item 12: `Axis::linspace`/`centres` gave non-finite values when hi − lo overflows.
#[test]
fn regress_axis_over_a_range_that_overflows_stays_finite() {
    let a = Axis::linspace(-1e308, 1e308, 5).expect("axis");
    assert_eq!(a.as_slice(), &[-1e308, -5e307, 0.0, 5e307, 1e308]);
    let c = Axis::centres(-1e308, 1e308, 4).expect("axis");
    assert_eq!(c.as_slice(), &[-7.5e307, -2.5e307, 2.5e307, 7.5e307]);
    for (ax, n, centred) in [
        (Axis::linspace(-f64::MAX, f64::MAX, 7).expect("axis"), 7, false),
        (Axis::centres(-f64::MAX, f64::MAX, 7).expect("axis"), 7, true),
        (Axis::linspace(-f64::MAX, f64::MAX, 2).expect("axis"), 2, false),
        (Axis::centres(-f64::MAX, f64::MAX, 1).expect("axis"), 1, true),
    ] {
        let v = ax.as_slice();
        assert!(v.iter().all(|x| x.is_finite()), "{v:?}");
        assert!(v.windows(2).all(|w| w[0] < w[1]), "{v:?}");
        // At the exact points −1 + 2s/cells of the range (in units of f64::MAX), to rounding.
        let cells = if centred { n } else { n - 1 } as f64;
        for (i, x) in v.iter().enumerate() {
            let s = i as f64 + if centred { 0.5 } else { 0.0 };
            let exact = -1.0 + 2.0 * s / cells;
            assert!((x / f64::MAX - exact).abs() < 1e-15, "{i}: {x} vs {exact}·MAX");
        }
    }
    // Ordinary ranges keep their bits.
    assert_eq!(
        Axis::linspace(0.0, 1.0, 5).expect("axis").as_slice(),
        &[0.0, 0.25, 0.5, 0.75, 1.0]
    );
    assert_eq!(
        Axis::centres(0.0, 1.0, 4).expect("axis").as_slice(),
        &[0.125, 0.375, 0.625, 0.875]
    );
}

/// Issue 29 item 6: a histogram over ±1e308 put every value in bin 0 (the width hi − lo overflowed).
#[test]
fn regress_histogram_over_a_range_that_overflows_bins_correctly() {
    let h = Histogram::new(-1e308, 1e308, 4).expect("histogram");
    assert_eq!(h.edges(), vec![-1e308, -5e307, 0.0, 5e307, 1e308]);
    assert_eq!(h.bin(-1e308), Some(0));
    assert_eq!(h.bin(-6e307), Some(0));
    assert_eq!(h.bin(-4e307), Some(1));
    assert_eq!(h.bin(0.0), Some(2));
    assert_eq!(h.bin(4.9e307), Some(2));
    assert_eq!(h.bin(5e307), Some(3));
    assert_eq!(h.bin(9.9e307), Some(3));
    assert_eq!(h.bin(1e308), None);
    let full = Histogram::new(-f64::MAX, f64::MAX, 2).expect("histogram");
    assert_eq!(full.edges(), vec![-f64::MAX, 0.0, f64::MAX]);
    assert_eq!((full.bin(-1.0), full.bin(1.0)), (Some(0), Some(1)));
    let xs = vec![-9e307, -1e307, 1e307, 9e307, f64::MAX, f64::NAN, -f64::MAX];
    let c = Ensemble::new(xs, |_, x: &f64| Ok::<_, ()>(*x)).reduce(&h).value;
    assert_eq!(c.counts, vec![1, 1, 1, 1]);
    assert_eq!((c.below, c.above, c.nan), (1, 1, 1));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, failure_persistence: None, ..ProptestConfig::default() })]

    /// Issue 29: random member counts, chunk sizes and thread counts, members sharing one model with
    /// a Newton solve inside (the Legendre transform): every member's result and the reduction are
    /// bit-identical to per-member models on one thread.
    #[test]
    fn prop_shared_model_reduction_is_bit_identical_on_any_thread_count(
        n in 1usize..48,
        chunk in 1usize..9,
        threads in prop::sample::select(vec![1usize, 2, 4]),
        a0 in 0.05..1.5f64,
    ) {
        let amplitudes: Vec<f64> = (0..n).map(|i| a0 + 0.029 * i as f64).collect();
        let shared = model();
        let together = Ensemble::new(amplitudes.clone(), |_, a: &f64| {
            gauss4_end(&shared, *a, 6).map(|e| f64::from_bits(e[1]))
        })
        .chunk_size(chunk)
        .expect("chunk");
        let own = Ensemble::new(amplitudes, |_, a: &f64| {
            gauss4_end(&model(), *a, 6).map(|e| f64::from_bits(e[1]))
        })
        .chunk_size(chunk)
        .expect("chunk");
        let reference = on_threads(1, || own.reduce(&Mean)).into_value().expect("every member runs");
        let got = on_threads(threads, || together.reduce(&Mean)).into_value().expect("every member runs");
        prop_assert_eq!(got.n, n as u64);
        prop_assert_eq!(got.mean.to_bits(), reference.mean.to_bits());
        prop_assert_eq!(got.m2.to_bits(), reference.m2.to_bits());
        let runs = on_threads(threads, || together.run()).values().expect("every member runs");
        let solo = on_threads(1, || own.run()).values().expect("every member runs");
        prop_assert!(runs.iter().zip(&solo).all(|(x, y)| x.to_bits() == y.to_bits()));
    }
}
