//! The ensemble's contract: reductions bit-identical for any number of threads, results in member
//! order, a failing member reported while the others complete, reproducible grids and samplers, and
//! typed errors for bad input.

use noether_core::prelude::*;
use noether_ensemble::rand::Rng;
use noether_ensemble::{
    member_rng, Axis, Counts, Ensemble, Error, Fold, Grid, Histogram, Map, Max, Mean, MemberError, Members,
    Moments, Reducer, Sampler, Wire,
};
use noether_testkit::pendulum;

/// A quarter period of the pendulum released from rest at amplitude `a` (DOP853 at 1e-10, at most 20
/// time units).
fn quarter_period(a: f64) -> Result<f64, noether_core::Error> {
    pendulum::quarter_period(a, 1e-10, 20.0)
}

/// Runs `f` on a rayon pool of `threads` threads.
fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
        .install(f)
}

/// How a member of [`sampled`] draws its amplitude.
type Draw = fn(&mut noether_ensemble::MemberRng) -> f64;
/// How a member of [`sampled`] runs.
type Run = fn(usize, &f64) -> Result<f64, noether_core::Error>;

/// 2000 random amplitudes in (0.1, 2.5) and their quarter periods.
fn sampled() -> Ensemble<Sampler<Draw>, Run> {
    let draw: Draw = |rng| rng.random_range(0.1..2.5);
    let run: Run = |_, a| quarter_period(*a);
    Ensemble::new(Sampler::new(2000, 7, draw), run)
}

#[test]
fn reductions_are_bit_identical_on_1_2_4_threads() {
    let ens = sampled();
    let reducer = (Mean, Histogram::new(1.5, 3.0, 30).expect("histogram"));
    let runs: Vec<(Moments, Counts)> = [1, 2, 4]
        .iter()
        .map(|&k| on_threads(k, || ens.reduce(&reducer).into_value().expect("no member fails")))
        .collect();
    for (k, r) in [2, 4].iter().zip(&runs[1..]) {
        assert_eq!(
            r.0.mean.to_bits(),
            runs[0].0.mean.to_bits(),
            "mean on {k} threads"
        );
        assert_eq!(r.0.m2.to_bits(), runs[0].0.m2.to_bits(), "m2 on {k} threads");
        assert_eq!(r.1, runs[0].1, "histogram on {k} threads");
    }
    assert_eq!(runs[0].0.n, 2000);
    assert_eq!(runs[0].1.total(), 2000);
    // The reduction is the fixed tree over fixed chunks: recompute it by hand, sequentially.
    let outs: Vec<f64> = ens.run().values().expect("no member fails");
    let chunk = ens.chunk();
    assert_eq!(chunk, 2, "⌈2000/1024⌉");
    let mut level: Vec<Moments> = outs
        .chunks(chunk)
        .enumerate()
        .map(|(c, xs)| {
            let mut m = Mean.identity();
            for (j, &x) in xs.iter().enumerate() {
                Mean.fold(&mut m, c * chunk + j, x);
            }
            m
        })
        .collect();
    while level.len() > 1 {
        level = level
            .chunks(2)
            .map(|p| {
                if p.len() == 2 {
                    Mean.merge(p[0], p[1])
                } else {
                    p[0]
                }
            })
            .collect();
    }
    assert_eq!(level[0].mean.to_bits(), runs[0].0.mean.to_bits());
    assert_eq!(level[0].m2.to_bits(), runs[0].0.m2.to_bits());
    // And it is a mean: against the two-pass mean and variance of the same outputs, to rounding
    // (measured 1.3e-15 and 1.7e-15 relative; 1e-14 allows the different order of 2000 additions).
    let two_pass = outs.iter().sum::<f64>() / outs.len() as f64;
    eprintln!(
        "tree mean vs two-pass: {:e} relative",
        (runs[0].0.mean - two_pass).abs() / two_pass
    );
    assert!(
        (runs[0].0.mean - two_pass).abs() < 1e-14 * two_pass,
        "{} vs {two_pass}",
        runs[0].0.mean
    );
    let var = outs.iter().map(|x| (x - two_pass).powi(2)).sum::<f64>() / (outs.len() - 1) as f64;
    eprintln!(
        "variance: {:e} relative",
        (runs[0].0.variance() - var).abs() / var
    );
    assert!((runs[0].0.variance() - var).abs() < 1e-14 * var);
}

#[test]
fn a_different_chunk_size_is_still_the_same_reduction_to_rounding() {
    let ens = sampled().chunk_size(37).expect("chunk");
    let a = on_threads(2, || ens.reduce(&Mean)).into_value().expect("ok");
    let b = on_threads(1, || sampled().reduce(&Mean))
        .into_value()
        .expect("ok");
    assert_eq!(a.n, b.n);
    // Another tree over other chunks: equal to rounding (measured 0 here; 1e-14 is a few ulps of 2000 sums).
    eprintln!(
        "chunk 37 vs default: {:e} relative",
        (a.mean - b.mean).abs() / b.mean
    );
    assert!((a.mean - b.mean).abs() < 1e-14 * b.mean);
    // Bit-identical across thread counts for this chunk size too.
    let c = on_threads(4, || ens.reduce(&Mean)).into_value().expect("ok");
    assert_eq!(a.mean.to_bits(), c.mean.to_bits());
}

#[test]
fn results_come_in_member_order() {
    // Members of very different cost (amplitude near π takes long), so they finish out of order.
    let amplitudes: Vec<f64> = (0..200)
        .map(|i| if i % 7 == 0 { 3.1 } else { 0.1 + 0.01 * i as f64 })
        .collect();
    let ens = Ensemble::new(amplitudes.clone(), |i, a: &f64| {
        quarter_period(*a).map(|t| (i, t))
    });
    let runs = on_threads(4, || ens.run());
    assert_eq!(runs.len(), 200);
    for (i, r) in runs.results().iter().enumerate() {
        let (j, t) = r.as_ref().expect("member runs");
        assert_eq!(*j, i);
        assert_eq!(
            t.to_bits(),
            quarter_period(amplitudes[i]).expect("runs").to_bits()
        );
    }
    // The collected per-member scalars through a reducer, also in order.
    let collect = Fold::new(
        Vec::new,
        |v: &mut Vec<usize>, i, _x: (usize, f64)| v.push(i),
        |mut l: Vec<usize>, r| {
            l.extend(r);
            l
        },
    );
    let order = on_threads(4, || ens.reduce(&collect)).value;
    assert_eq!(order, (0..200).collect::<Vec<_>>());
    // Member 1 (a = 0.11) against the series of the quarter period, π/2 (1 + a²/16 + 11a⁴/3072 + O(a⁶))
    // (from K(sin(a/2))): the next term is 173a⁶/737280 ≈ 4e-10 relative, DOP853 at 1e-10 adds less
    // (measured 2.0e-10); tolerance 1e-9.
    let t0 = runs.results()[1].as_ref().expect("runs").1;
    let a: f64 = 0.11;
    let series = std::f64::consts::FRAC_PI_2 * (1.0 + a * a / 16.0 + 11.0 * a.powi(4) / 3072.0);
    eprintln!(
        "quarter period vs series: {:e} relative",
        (t0 - series).abs() / series
    );
    assert!((t0 - series).abs() < 1e-9 * series, "{t0} vs {series}");
}

#[test]
fn a_failing_member_is_reported_while_the_others_complete() {
    // Members 3 and 11 start from a NaN angle: the driver refuses them (Error::NonFinite).
    let amplitudes: Vec<f64> = (0..16)
        .map(|i| if i == 3 || i == 11 { f64::NAN } else { 0.5 })
        .collect();
    let ens = Ensemble::new(amplitudes, |_, a: &f64| quarter_period(*a))
        .chunk_size(4)
        .expect("chunk");
    let runs = on_threads(2, || ens.run());
    let failed: Vec<usize> = runs.failures().map(|(i, _)| i).collect();
    assert_eq!(failed, vec![3, 11]);
    assert!(matches!(
        runs.failures().next().map(|f| f.1),
        Some(MemberError::Failed(noether_core::Error::NonFinite { .. }))
    ));
    assert_eq!(runs.successes().count(), 14);
    match runs.clone().values() {
        Err(Error::MemberFailed {
            index: 3,
            failed: 2,
            message,
        }) => assert!(message.contains("not finite")),
        other => panic!("expected MemberFailed, got {other:?}"),
    }
    let reduced = on_threads(2, || ens.reduce(&Mean));
    assert_eq!(reduced.value.n, 14);
    assert_eq!(reduced.members, 16);
    assert_eq!(
        reduced.failures.iter().map(|f| f.index).collect::<Vec<_>>(),
        vec![3, 11]
    );
    assert!(matches!(
        reduced.clone().into_value(),
        Err(Error::MemberFailed {
            index: 3,
            failed: 2,
            ..
        })
    ));
    // The others all completed with the same value.
    let t = quarter_period(0.5).expect("runs");
    assert!(runs.successes().all(|(_, &x)| x.to_bits() == t.to_bits()));
}

#[test]
fn grids_and_samplers_are_reproducible() {
    let grid = Grid::new(vec![
        Axis::linspace(-1.0, 1.0, 5).expect("axis"),
        Axis::centres(0.0, 1.0, 4).expect("axis"),
        Axis::values(vec![7.0, 8.0]).expect("axis"),
    ])
    .expect("grid");
    assert_eq!(grid.len(), 40);
    assert_eq!(grid.shape(), vec![5, 4, 2]);
    for i in 0..grid.len() {
        assert_eq!(grid.index_of(&grid.multi_index(i).expect("in the grid")), Some(i));
    }
    assert_eq!(grid.member(0), Ok(vec![-1.0, 0.125, 7.0]));
    assert_eq!(grid.member(39), Ok(vec![1.0, 0.875, 8.0]));
    assert_eq!(grid.member(2 * 8 + 3 * 2 + 1), Ok(vec![0.0, 0.875, 8.0]));
    assert_eq!(grid.index_of(&[5, 0, 0]), None);
    assert_eq!(grid.index_of(&[0, 0]), None);
    // Members through the ensemble, on several threads, match the grid and come in order.
    let ens = Ensemble::new(grid.clone(), |i, p: &Vec<f64>| Ok::<_, String>((i, p.clone())));
    let out = on_threads(3, || ens.run()).values().expect("no failure");
    assert!(out
        .iter()
        .enumerate()
        .all(|(i, (j, p))| i == *j && Ok(p.clone()) == grid.member(i)));

    // A sampler's member i depends on (seed, i) only: not on the number of members, nor the thread.
    let draw = |rng: &mut noether_ensemble::MemberRng| [rng.random::<f64>(), rng.random::<f64>()];
    let small = Sampler::new(10, 99, draw);
    let large = Sampler::new(100_000, 99, draw);
    let other = Sampler::new(10, 100, draw);
    for i in 0..10 {
        assert_eq!(small.member(i), large.member(i));
        assert_ne!(small.member(i), other.member(i));
    }
    assert_ne!(small.member(0), small.member(1));
    // Issue 30 item 9: the members list themselves back, in order, exactly as `member(i)` gives them,
    // from either end; an empty sampler lists nothing.
    let listed: Vec<[f64; 2]> = (&small).into_iter().collect();
    assert_eq!(listed.len(), 10);
    assert!(listed.iter().enumerate().all(|(i, p)| Ok(*p) == small.member(i)));
    assert_eq!(small.members().len(), 10);
    assert_eq!(small.members().next_back(), Some(listed[9]));
    assert_eq!(Sampler::new(0, 1, draw).members().next(), None);
    let cells: Vec<Vec<f64>> = (&grid).into_iter().collect();
    assert_eq!(cells.len(), 40);
    assert_eq!(cells[39], vec![1.0, 0.875, 8.0]);
    let sum = |threads| {
        on_threads(threads, || {
            Ensemble::new(Sampler::new(5000, 3, draw), |_, p: &[f64; 2]| {
                Ok::<_, ()>(p[0] + p[1])
            })
            .reduce(&Mean)
        })
        .value
    };
    let (s1, s4) = (sum(1), sum(4));
    assert_eq!(s1.mean.to_bits(), s4.mean.to_bits());
    // Uniform draws: the mean of u₁ + u₂ is 1 with standard error sqrt(1/6 / 5000) = 0.0058 (measured
    // deviation 1.7e-3); 4σ.
    eprintln!("sampler mean − 1 = {:e}", s1.mean - 1.0);
    assert!(
        (s1.mean - 1.0).abs() < 4.0 * (1.0 / 6.0 / 5000.0_f64).sqrt(),
        "{}",
        s1.mean
    );
    // The generator a sampler hands out is member_rng(seed, i).
    let mut rng = member_rng(99, 4);
    assert_eq!(small.member(4), Ok([rng.random::<f64>(), rng.random::<f64>()]));
}

#[test]
fn histogram_edges_and_bins() {
    let h = Histogram::new(0.0, 1.0, 4).expect("histogram");
    assert_eq!(h.edges(), vec![0.0, 0.25, 0.5, 0.75, 1.0]);
    assert_eq!(h.bin(0.0), Some(0));
    assert_eq!(h.bin(0.25), Some(1));
    assert_eq!(h.bin(0.999_999_999_999_999_9), Some(3));
    assert_eq!(h.bin(1.0), None);
    assert_eq!(h.bin(f64::NAN), None);
    let xs = vec![-1.0, 0.1, 0.3, 0.3, 2.0, f64::NAN, 0.9];
    let c = Ensemble::new(xs, |_, x: &f64| Ok::<_, ()>(*x)).reduce(&h).value;
    assert_eq!(c.counts, vec![1, 2, 0, 1]);
    assert_eq!((c.below, c.above, c.nan, c.total()), (1, 1, 1, 7));
}

#[test]
fn max_and_map() {
    let pairs = vec![(1.0, 0.5), (3.0, -1.0), (2.0, 7.0)];
    let ens = Ensemble::new(pairs, |_, p: &(f64, f64)| Ok::<_, String>(*p));
    let r = (
        Map::new(|p: (f64, f64)| p.0, Max),
        Map::new(|p: (f64, f64)| p.1, Mean),
    );
    let (max, mean) = on_threads(2, || ens.reduce(&r)).into_value().expect("no failure");
    assert_eq!(max, 3.0);
    assert_eq!(mean.n, 3);
    assert!((mean.mean - 6.5 / 3.0).abs() < 1e-15);
    let with_nan = Ensemble::new(vec![1.0, f64::NAN, 2.0], |_, x: &f64| Ok::<_, String>(*x)).chunk_size(1);
    assert!(with_nan.expect("chunk").reduce(&Max).value.is_nan());
    assert_eq!(
        Ensemble::new(Vec::<f64>::new(), |_, x: &f64| Ok::<_, String>(*x))
            .reduce(&Max)
            .value,
        f64::NEG_INFINITY
    );
}

#[test]
fn the_error_contract() {
    let bad = |r: Result<Axis, Error>| matches!(r, Err(Error::InvalidParameter { .. }));
    assert!(bad(Axis::linspace(0.0, 1.0, 0)));
    assert!(bad(Axis::linspace(f64::NAN, 1.0, 3)));
    assert!(bad(Axis::linspace(0.0, f64::INFINITY, 3)));
    assert!(bad(Axis::linspace(1.0, 0.0, 3)));
    assert!(bad(Axis::centres(0.0, 1.0, 0)));
    assert!(bad(Axis::values(vec![])));
    assert!(bad(Axis::values(vec![1.0, f64::NAN])));
    assert!(Axis::linspace(2.0, 2.0, 1).is_ok());
    assert!(matches!(Grid::new(vec![]), Err(Error::InvalidParameter { .. })));
    let huge = Axis::linspace(0.0, 1.0, 1 << 20).expect("axis");
    assert!(matches!(
        Grid::new(vec![huge.clone(), huge.clone(), huge.clone(), huge]),
        Err(Error::InvalidParameter {
            name: "grid points",
            ..
        })
    ));
    let ens = Ensemble::new(vec![1.0], |_, x: &f64| Ok::<_, ()>(*x));
    assert!(matches!(
        ens.clone().chunk_size(0),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        Histogram::new(0.0, 1.0, 0),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        Histogram::new(1.0, 1.0, 3),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        Histogram::new(0.0, f64::NAN, 3),
        Err(Error::InvalidParameter { .. })
    ));
    // An empty ensemble reduces to the identity and collects nothing.
    let empty = Ensemble::new(Vec::<f64>::new(), |_, x: &f64| Ok::<_, ()>(*x));
    assert_eq!(empty.reduce(&Mean).value, Moments::default());
    assert!(empty.run().is_empty());
    assert_eq!(empty.chunks(), 0);
    // Bytes between ranks: round trip bit for bit, and truncated messages are errors, not panics.
    let m = Moments {
        n: 3,
        mean: 0.1 + 0.2,
        m2: f64::MIN_POSITIVE,
    };
    let c = Counts {
        counts: vec![1, 2, 3],
        below: 4,
        above: 5,
        nan: 6,
    };
    let mut buf = Vec::new();
    (m, c.clone()).encode(&mut buf);
    vec![Some("ä".to_string()), None].encode(&mut buf);
    let mut rd = buf.as_slice();
    assert_eq!(<(Moments, Counts)>::decode(&mut rd).expect("decodes"), (m, c));
    assert_eq!(
        Vec::<Option<String>>::decode(&mut rd).expect("decodes"),
        vec![Some("ä".to_string()), None]
    );
    assert!(rd.is_empty());
    for cut in 0..buf.len() - 1 {
        let mut rd = &buf[..cut];
        let r = <(Moments, Counts)>::decode(&mut rd).and_then(|_| Vec::<Option<String>>::decode(&mut rd));
        assert!(matches!(r, Err(Error::Decode(_))), "cut at {cut}");
    }
}
