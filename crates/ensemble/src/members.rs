//! The members of an ensemble: a list, a grid (the Cartesian product of axes), or a seeded random
//! sampler. Member `i` is a pure function of `i`, so every member can be built on any thread or rank,
//! in any order, and comes out the same.

use crate::error::check_member;
use crate::{Error, Result};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// The members of an ensemble, indexed 0..len: member `i`'s parameters are a pure function of `i`
/// (the same on every thread and every MPI rank).
pub trait Members: Sync {
    /// The parameters of one member (handed to the run closure by reference).
    type Param: Send;
    /// Number of members.
    fn len(&self) -> usize;
    /// Whether there are no members.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The parameters of member `index`, or [`Error::NoSuchMember`] when `index` ≥
    /// [`len`](Self::len) (never a panic, nor another member's parameters).
    fn member(&self, index: usize) -> Result<Self::Param>;

    /// The members in order, 0 to len − 1: what an ensemble runs, listed back (a sample to plot or
    /// to save next to its outputs). `for p in &sampler` does the same for a [`Sampler`] or a
    /// [`Grid`]. (Not named `iter`: for a `Vec` of members that would hide the slice's own.)
    ///
    /// ```
    /// use noether_ensemble::{rand::Rng, Members, Sampler};
    /// let s = Sampler::new(5, 42, |rng| rng.random_range(0.0..1.0));
    /// let drawn: Vec<f64> = s.members().collect();
    /// assert_eq!(drawn.len(), 5);
    /// assert_eq!(drawn[3], s.member(3)?);
    /// # Ok::<(), noether_ensemble::Error>(())
    /// ```
    fn members(&self) -> MemberIter<'_, Self>
    where
        Self: Sized,
    {
        MemberIter {
            members: self,
            next: 0,
            end: self.len(),
        }
    }
}

/// The members of an ensemble in order ([`Members::members`]).
#[derive(Debug, Clone)]
pub struct MemberIter<'a, M> {
    members: &'a M,
    next: usize,
    end: usize,
}

impl<M: Members> Iterator for MemberIter<'_, M> {
    type Item = M::Param;
    fn next(&mut self) -> Option<M::Param> {
        if self.next >= self.end {
            return None;
        }
        // Every index below len() is a member (the trait's contract); should one fail regardless,
        // the iteration ends there rather than skip it.
        let p = self.members.member(self.next).ok();
        self.next = if p.is_some() { self.next + 1 } else { self.end };
        p
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.end - self.next;
        (left, Some(left))
    }
}

impl<M: Members> ExactSizeIterator for MemberIter<'_, M> {}

impl<M: Members> DoubleEndedIterator for MemberIter<'_, M> {
    fn next_back(&mut self) -> Option<M::Param> {
        if self.next >= self.end {
            return None;
        }
        let p = self.members.member(self.end - 1).ok();
        self.end = if p.is_some() { self.end - 1 } else { self.next };
        p
    }
}

/// A list of members, given one by one.
impl<P: Clone + Send + Sync> Members for Vec<P> {
    type Param = P;
    fn len(&self) -> usize {
        Vec::len(self)
    }
    fn member(&self, index: usize) -> Result<P> {
        check_member(index, self.len())?;
        Ok(self[index].clone())
    }
}

/// A list of members, given one by one (borrowed).
impl<P: Clone + Send + Sync> Members for &[P] {
    type Param = P;
    fn len(&self) -> usize {
        <[P]>::len(self)
    }
    fn member(&self, index: usize) -> Result<P> {
        check_member(index, self.len())?;
        Ok(self[index].clone())
    }
}

/// The values of one axis of a [`Grid`].
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    values: Vec<f64>,
}

impl Axis {
    /// `n` equally spaced values from `lo` to `hi`, both included (`n = 1` gives `lo`):
    /// lo + i (hi − lo)/(n − 1), the last one `hi` itself. Where hi − lo overflows (bounds near ±f64::MAX)
    /// the same points are computed at half scale, 2 (lo/2 + i (hi/2 − lo/2)/(n − 1)), so they stay
    /// finite and in [lo, hi].
    pub fn linspace(lo: f64, hi: f64, n: usize) -> Result<Self> {
        check_range(lo, hi, n)?;
        let at = spacing(lo, hi, n.saturating_sub(1).max(1));
        Ok(Axis {
            values: (0..n)
                .map(|i| if i + 1 == n && n > 1 { hi } else { at(i as f64) })
                .collect(),
        })
    }

    /// The centres of `n` equal cells that tile [lo, hi]: lo + (i + ½)(hi − lo)/n (a heat map's pixels;
    /// at half scale where hi − lo overflows, as in [`linspace`](Self::linspace)).
    pub fn centres(lo: f64, hi: f64, n: usize) -> Result<Self> {
        check_range(lo, hi, n)?;
        let at = spacing(lo, hi, n);
        Ok(Axis {
            values: (0..n).map(|i| at(i as f64 + 0.5)).collect(),
        })
    }

    /// The given values (finite, at least one).
    pub fn values(values: Vec<f64>) -> Result<Self> {
        if values.is_empty() {
            return Err(Error::InvalidParameter {
                name: "axis values",
                value: 0.0,
                reason: "an axis needs at least one value",
            });
        }
        if let Some(&v) = values.iter().find(|v| !v.is_finite()) {
            return Err(Error::InvalidParameter {
                name: "axis value",
                value: v,
                reason: "axis values must be finite",
            });
        }
        Ok(Axis { values })
    }

    /// The values along this axis.
    pub fn as_slice(&self) -> &[f64] {
        &self.values
    }

    /// Number of values.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Always false: an axis has at least one value.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }
}

/// The point lo + s (hi − lo)/cells of [lo, hi] (finite lo ≤ hi, cells ≥ 1, 0 ≤ s ≤ cells): directly
/// while hi − lo is finite, else at half scale (halving is exact there: the numbers are huge), clamped
/// to [lo, hi] against the last rounding.
fn spacing(lo: f64, hi: f64, cells: usize) -> impl Fn(f64) -> f64 {
    let direct = (hi - lo).is_finite();
    let step = if direct {
        (hi - lo) / cells as f64
    } else {
        (0.5 * hi - 0.5 * lo) / cells as f64
    };
    move |s| {
        if direct {
            lo + step * s
        } else {
            (2.0 * (0.5 * lo + step * s)).clamp(lo, hi)
        }
    }
}

fn check_range(lo: f64, hi: f64, n: usize) -> Result<()> {
    if n == 0 {
        return Err(Error::InvalidParameter {
            name: "axis points",
            value: 0.0,
            reason: "an axis needs at least one point",
        });
    }
    for v in [lo, hi] {
        if !v.is_finite() {
            return Err(Error::InvalidParameter {
                name: "axis bound",
                value: v,
                reason: "axis bounds must be finite",
            });
        }
    }
    if hi < lo {
        return Err(Error::InvalidParameter {
            name: "axis upper bound",
            value: hi,
            reason: "the upper bound must not be below the lower one",
        });
    }
    Ok(())
}

/// The Cartesian product of axes: member `i` is the point whose multi-index is `i` in row-major order
/// (the last axis varies fastest), given as a `Vec<f64>` with one coordinate per axis.
///
/// ```
/// use noether_ensemble::{Axis, Grid, Members};
/// let grid = Grid::new(vec![Axis::linspace(0.0, 1.0, 3)?, Axis::values(vec![10.0, 20.0])?])?;
/// assert_eq!(grid.len(), 6);
/// assert_eq!(grid.member(1)?, vec![0.0, 20.0]);
/// assert_eq!(grid.member(4)?, vec![1.0, 10.0]);
/// assert_eq!(grid.multi_index(5)?, vec![2, 1]);
/// assert!(grid.member(6).is_err()); // not member 0 again
/// # Ok::<(), noether_ensemble::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    axes: Vec<Axis>,
    len: usize,
}

impl Grid {
    /// The product of `axes` (at least one; the number of points must fit in a `usize`).
    pub fn new(axes: Vec<Axis>) -> Result<Self> {
        if axes.is_empty() {
            return Err(Error::InvalidParameter {
                name: "grid axes",
                value: 0.0,
                reason: "a grid needs at least one axis",
            });
        }
        let len = axes
            .iter()
            .try_fold(1usize, |n, a| n.checked_mul(a.len()))
            .ok_or(Error::InvalidParameter {
                name: "grid points",
                value: f64::INFINITY,
                reason: "the number of grid points overflows usize",
            })?;
        Ok(Grid { axes, len })
    }

    /// The axes.
    pub fn axes(&self) -> &[Axis] {
        &self.axes
    }

    /// The number of values on each axis.
    pub fn shape(&self) -> Vec<usize> {
        self.axes.iter().map(Axis::len).collect()
    }

    /// The multi-index (one index per axis) of member `index`, or [`Error::NoSuchMember`] when it is
    /// not in the grid.
    pub fn multi_index(&self, index: usize) -> Result<Vec<usize>> {
        check_member(index, self.len)?;
        let mut rest = index;
        let mut idx = vec![0; self.axes.len()];
        for (k, a) in self.axes.iter().enumerate().rev() {
            idx[k] = rest % a.len();
            rest /= a.len();
        }
        Ok(idx)
    }

    /// The member index of a multi-index (`None` if it is out of the grid or of the wrong length).
    pub fn index_of(&self, multi: &[usize]) -> Option<usize> {
        if multi.len() != self.axes.len() {
            return None;
        }
        let mut i = 0usize;
        for (&m, a) in multi.iter().zip(&self.axes) {
            if m >= a.len() {
                return None;
            }
            i = i * a.len() + m;
        }
        Some(i)
    }
}

impl Members for Grid {
    type Param = Vec<f64>;
    fn len(&self) -> usize {
        self.len
    }
    fn member(&self, index: usize) -> Result<Vec<f64>> {
        Ok(self
            .multi_index(index)?
            .iter()
            .zip(&self.axes)
            .map(|(&m, a)| a.values[m])
            .collect())
    }
}

/// The random number generator a [`Sampler`] hands to its closure: ChaCha8 keyed by the sampler's
/// seed, on the member's own stream (stream = member index). Its output is fixed by (seed, index)
/// alone — not by the thread, the rank or the order members run in — and is portable across
/// platforms and versions of rand_chacha (unlike `StdRng`).
pub type MemberRng = ChaCha8Rng;

/// `n` random members: member `i` is `draw(rng)` with `rng` the [`MemberRng`] of (seed, i).
///
/// ```
/// use noether_ensemble::{rand::Rng, Members, Sampler};
/// let s = Sampler::new(1000, 42, |rng| rng.random_range(0.0..1.0));
/// assert_eq!(s.member(7)?, s.member(7)?); // a function of (seed, index)
/// assert_ne!(s.member(7)?, s.member(8)?);
/// # Ok::<(), noether_ensemble::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Sampler<F> {
    n: usize,
    seed: u64,
    draw: F,
}

impl<P: Send, F: Fn(&mut MemberRng) -> P + Sync> Sampler<F> {
    /// `n` members drawn by `draw` from the seed `seed`.
    pub fn new(n: usize, seed: u64, draw: F) -> Self {
        Sampler { n, seed, draw }
    }

    /// The seed.
    pub fn seed(&self) -> u64 {
        self.seed
    }
}

/// The generator of member `index` of an ensemble seeded with `seed`: ChaCha8 keyed by `seed`, on
/// stream `index` (what a [`Sampler`] hands its closure; also for members that draw random numbers
/// while they run).
pub fn member_rng(seed: u64, index: usize) -> MemberRng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(index as u64);
    rng
}

impl<P: Send, F: Fn(&mut MemberRng) -> P + Sync> Members for Sampler<F> {
    type Param = P;
    fn len(&self) -> usize {
        self.n
    }
    fn member(&self, index: usize) -> Result<P> {
        check_member(index, self.n)?;
        Ok((self.draw)(&mut member_rng(self.seed, index)))
    }
}

impl<'a, P: Send, F: Fn(&mut MemberRng) -> P + Sync> IntoIterator for &'a Sampler<F> {
    type Item = P;
    type IntoIter = MemberIter<'a, Sampler<F>>;
    fn into_iter(self) -> Self::IntoIter {
        self.members()
    }
}

impl<'a> IntoIterator for &'a Grid {
    type Item = Vec<f64>;
    type IntoIter = MemberIter<'a, Grid>;
    fn into_iter(self) -> Self::IntoIter {
        self.members()
    }
}
