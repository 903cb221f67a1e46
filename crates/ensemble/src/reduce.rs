//! Reductions of an ensemble's outputs without keeping them: a [`Reducer`] folds the outputs of a
//! chunk of members in member order into an accumulator, and merges accumulators. The ensemble folds
//! fixed chunks and merges them in a fixed tree (see [`Ensemble::reduce`](crate::Ensemble::reduce)),
//! so a floating-point reduction gives the same bits for any number of threads or ranks.

use crate::{Error, Result};
use std::marker::PhantomData;

/// A reduction of member outputs `T` into an accumulator.
///
/// The ensemble calls [`identity`](Self::identity) once per chunk, [`fold`](Self::fold) for each
/// member of the chunk in increasing index, and [`merge`](Self::merge) on neighbouring accumulators
/// (left holds lower member indices than right) in a tree fixed by the number of chunks.
pub trait Reducer<T>: Sync {
    /// What the reduction accumulates.
    type Acc: Send;
    /// The accumulator of no member.
    fn identity(&self) -> Self::Acc;
    /// Adds the output of member `index`.
    fn fold(&self, acc: &mut Self::Acc, index: usize, value: T);
    /// Joins two accumulators; `left` covers lower member indices than `right`.
    fn merge(&self, left: Self::Acc, right: Self::Acc) -> Self::Acc;
}

/// A histogram of scalar outputs: `bins` equal bins over [lo, hi).
///
/// ```
/// use noether_ensemble::{Ensemble, Histogram};
/// let ens = Ensemble::new((0..10).map(|i| i as f64).collect::<Vec<_>>(), |_, x: &f64| Ok::<_, ()>(*x));
/// let h = ens.reduce(&Histogram::new(0.0, 8.0, 4)?);
/// assert_eq!(h.value.counts, vec![2, 2, 2, 2]);
/// assert_eq!(h.value.above, 2);
/// # Ok::<(), noether_ensemble::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Histogram {
    lo: f64,
    hi: f64,
    bins: usize,
}

impl Histogram {
    /// `bins` ≥ 1 equal bins over [lo, hi), lo < hi finite.
    pub fn new(lo: f64, hi: f64, bins: usize) -> Result<Self> {
        if bins == 0 {
            return Err(Error::InvalidParameter {
                name: "histogram bins",
                value: 0.0,
                reason: "a histogram needs at least one bin",
            });
        }
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return Err(Error::InvalidParameter {
                name: "histogram range",
                value: hi - lo,
                reason: "a histogram needs finite bounds lo < hi",
            });
        }
        Ok(Histogram { lo, hi, bins })
    }

    /// The bin edges (bins + 1 values from lo to hi): lo + i (hi − lo)/bins, the last one `hi`. Where
    /// hi − lo overflows (bounds near ±f64::MAX) they are computed at half scale,
    /// 2 (lo/2 + i (hi/2 − lo/2)/bins), which is exact scaling there.
    pub fn edges(&self) -> Vec<f64> {
        (0..=self.bins).map(|i| self.edge(i)).collect()
    }

    /// Edge `i` ≤ bins (see [`edges`](Self::edges)).
    fn edge(&self, i: usize) -> f64 {
        if i >= self.bins {
            self.hi
        } else if (self.hi - self.lo).is_finite() {
            self.lo + (self.hi - self.lo) / self.bins as f64 * i as f64
        } else {
            let w = (0.5 * self.hi - 0.5 * self.lo) / self.bins as f64;
            (2.0 * (0.5 * self.lo + w * i as f64)).clamp(self.lo, self.hi)
        }
    }

    /// The bin of `x`, if it falls in [lo, hi): the `i` with edge i ≤ x < edge i + 1 of
    /// [`edges`](Self::edges). Found as ⌊bins (x − lo)/(hi − lo)⌋ (at half scale,
    /// ⌊bins (x/2 − lo/2)/(hi/2 − lo/2)⌋, where hi − lo overflows), then moved by one where rounding
    /// put it across an edge.
    pub fn bin(&self, x: f64) -> Option<usize> {
        if !(x >= self.lo && x < self.hi) {
            return None;
        }
        let fraction = if (self.hi - self.lo).is_finite() {
            (x - self.lo) / (self.hi - self.lo)
        } else {
            (0.5 * x - 0.5 * self.lo) / (0.5 * self.hi - 0.5 * self.lo)
        };
        let mut i = ((fraction * self.bins as f64) as usize).min(self.bins - 1);
        if i > 0 && x < self.edge(i) {
            i -= 1;
        } else if i + 1 < self.bins && x >= self.edge(i + 1) {
            i += 1;
        }
        Some(i)
    }
}

/// The counts of a [`Histogram`].
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Counts {
    /// Members in each bin.
    pub counts: Vec<u64>,
    /// Members below the range.
    pub below: u64,
    /// Members at or above the upper end.
    pub above: u64,
    /// Members whose output was NaN.
    pub nan: u64,
}

impl Counts {
    /// All members counted (in the bins, outside, NaN).
    pub fn total(&self) -> u64 {
        self.counts.iter().sum::<u64>() + self.below + self.above + self.nan
    }
}

impl Reducer<f64> for Histogram {
    type Acc = Counts;
    fn identity(&self) -> Counts {
        Counts {
            counts: vec![0; self.bins],
            ..Counts::default()
        }
    }
    fn fold(&self, acc: &mut Counts, _index: usize, x: f64) {
        match self.bin(x) {
            Some(i) => acc.counts[i] += 1,
            None if x.is_nan() => acc.nan += 1,
            None if x < self.lo => acc.below += 1,
            None => acc.above += 1,
        }
    }
    fn merge(&self, mut left: Counts, right: Counts) -> Counts {
        for (l, r) in left.counts.iter_mut().zip(&right.counts) {
            *l += r;
        }
        left.below += right.below;
        left.above += right.above;
        left.nan += right.nan;
        left
    }
}

/// Mean and variance of scalar outputs (Welford within a chunk, Chan et al.'s pairwise update across
/// chunks: stable, and through the fixed tree bit-identical for any thread count).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Mean;

/// What [`Mean`] accumulates.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Moments {
    /// Number of values.
    pub n: u64,
    /// Their mean (0 if none).
    pub mean: f64,
    /// Sum of squared deviations from the mean.
    pub m2: f64,
}

impl Moments {
    /// The sample variance m2/(n − 1) (NaN below two values).
    pub fn variance(&self) -> f64 {
        if self.n < 2 {
            f64::NAN
        } else {
            self.m2 / (self.n - 1) as f64
        }
    }

    /// The standard error of the mean, sqrt(variance / n).
    pub fn standard_error(&self) -> f64 {
        (self.variance() / self.n as f64).sqrt()
    }
}

impl Reducer<f64> for Mean {
    type Acc = Moments;
    fn identity(&self) -> Moments {
        Moments::default()
    }
    fn fold(&self, acc: &mut Moments, _index: usize, x: f64) {
        acc.n += 1;
        let d = x - acc.mean;
        acc.mean += d / acc.n as f64;
        acc.m2 += d * (x - acc.mean);
    }
    fn merge(&self, a: Moments, b: Moments) -> Moments {
        if a.n == 0 {
            return b;
        }
        if b.n == 0 {
            return a;
        }
        let n = a.n + b.n;
        let d = b.mean - a.mean;
        let w = b.n as f64 / n as f64;
        Moments {
            n,
            mean: a.mean + d * w,
            m2: a.m2 + b.m2 + d * d * a.n as f64 * w,
        }
    }
}

/// The largest of scalar outputs (−∞ if none); a NaN output makes the result NaN (an error bound that
/// met a NaN is not a bound).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Max;

impl Max {
    fn larger(a: f64, b: f64) -> f64 {
        if a.is_nan() || b.is_nan() {
            f64::NAN
        } else {
            a.max(b)
        }
    }
}

impl Reducer<f64> for Max {
    type Acc = f64;
    fn identity(&self) -> f64 {
        f64::NEG_INFINITY
    }
    fn fold(&self, acc: &mut f64, _index: usize, x: f64) {
        *acc = Max::larger(*acc, x);
    }
    fn merge(&self, left: f64, right: f64) -> f64 {
        Max::larger(left, right)
    }
}

/// A reduction from three closures: `identity()`, `fold(&mut acc, index, value)`, `merge(left, right)`.
///
/// ```
/// use noether_ensemble::{Ensemble, Fold};
/// // Largest output and the member that gave it (the first such member on ties).
/// let best = Fold::new(
///     || (f64::NEG_INFINITY, usize::MAX),
///     |acc: &mut (f64, usize), i, x: f64| if x > acc.0 { *acc = (x, i) },
///     |l: (f64, usize), r: (f64, usize)| if r.0 > l.0 { r } else { l },
/// );
/// let ens = Ensemble::new(vec![3.0, 9.0, 1.0, 9.0], |_, x: &f64| Ok::<_, ()>(*x));
/// assert_eq!(ens.reduce(&best).value, (9.0, 1));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Fold<I, F, M> {
    identity: I,
    fold: F,
    merge: M,
}

impl<I, F, M> Fold<I, F, M> {
    /// The reduction with these three parts.
    pub fn new(identity: I, fold: F, merge: M) -> Self {
        Fold {
            identity,
            fold,
            merge,
        }
    }
}

impl<T, A, I, F, M> Reducer<T> for Fold<I, F, M>
where
    A: Send,
    I: Fn() -> A + Sync,
    F: Fn(&mut A, usize, T) + Sync,
    M: Fn(A, A) -> A + Sync,
{
    type Acc = A;
    fn identity(&self) -> A {
        (self.identity)()
    }
    fn fold(&self, acc: &mut A, index: usize, value: T) {
        (self.fold)(acc, index, value)
    }
    fn merge(&self, left: A, right: A) -> A {
        (self.merge)(left, right)
    }
}

/// Two reductions of the same outputs at once (a histogram and a mean, say).
impl<T: Clone, R1: Reducer<T>, R2: Reducer<T>> Reducer<T> for (R1, R2) {
    type Acc = (R1::Acc, R2::Acc);
    fn identity(&self) -> Self::Acc {
        (self.0.identity(), self.1.identity())
    }
    fn fold(&self, acc: &mut Self::Acc, index: usize, value: T) {
        self.0.fold(&mut acc.0, index, value.clone());
        self.1.fold(&mut acc.1, index, value);
    }
    fn merge(&self, l: Self::Acc, r: Self::Acc) -> Self::Acc {
        (self.0.merge(l.0, r.0), self.1.merge(l.1, r.1))
    }
}

/// Another reduction of a function of the outputs: `Map::new(|x: (f64, f64)| x.0, Histogram::new(..)?)`
/// histograms the first of two numbers each member returns.
#[derive(Debug, Clone, Copy)]
pub struct Map<G, R, U> {
    map: G,
    reducer: R,
    // The mapped type (`fn() -> U`: Send and Sync whatever U is).
    _mapped: PhantomData<fn() -> U>,
}

impl<G, R, U> Map<G, R, U> {
    /// `reducer` applied to `map(output)`.
    pub fn new(map: G, reducer: R) -> Self {
        Map {
            map,
            reducer,
            _mapped: PhantomData,
        }
    }
}

impl<T, U, G: Fn(T) -> U + Sync, R: Reducer<U>> Reducer<T> for Map<G, R, U> {
    type Acc = R::Acc;
    fn identity(&self) -> R::Acc {
        self.reducer.identity()
    }
    fn fold(&self, acc: &mut R::Acc, index: usize, value: T) {
        self.reducer.fold(acc, index, (self.map)(value))
    }
    fn merge(&self, left: R::Acc, right: R::Acc) -> R::Acc {
        self.reducer.merge(left, right)
    }
}

/// Merges accumulators given in member order in the fixed tree: neighbours (0,1), (2,3), … at each
/// level, an odd last one carried up unchanged, until one is left.
pub(crate) fn tree<T, R: Reducer<T>>(r: &R, mut accs: Vec<R::Acc>) -> R::Acc {
    while accs.len() > 1 {
        let mut next = Vec::with_capacity(accs.len().div_ceil(2));
        let mut it = accs.into_iter();
        while let Some(a) = it.next() {
            match it.next() {
                Some(b) => next.push(r.merge(a, b)),
                None => next.push(a),
            }
        }
        accs = next;
    }
    accs.pop().unwrap_or_else(|| r.identity())
}
