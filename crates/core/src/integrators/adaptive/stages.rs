//! The stages of an embedded pair's step and their weighted sums, the stage arguments of the
//! Runge-Kutta ([`Adaptive`](super::Adaptive)) and Nyström ([`Nystrom`](crate::integrators::Nystrom))
//! steps.

/// The stages of one step, stage after stage: k_j is the slice k[j·m .. (j+1)·m] for a state of m
/// components, which the vector field writes in place. A weighted sum of stages is an axpy per stage
/// with a nonzero weight; for small m the width is a constant and the sum stays in
/// registers.
#[derive(Debug, Clone, Copy)]
pub struct Stages<'a> {
    k: &'a [f64],
    m: usize,
}

impl<'a> Stages<'a> {
    /// The stages stored one after the other in `k`, each of `m` components.
    #[inline]
    pub fn new(k: &'a [f64], m: usize) -> Self {
        Stages { k, m }
    }
    /// Component `i` of stage `j`, k_j,i.
    #[inline]
    pub fn get(&self, j: usize, i: usize) -> f64 {
        self.k[j * self.m + i]
    }
    /// Σ_j w_j k_j,i: component i of a weighted sum of the stages (j over the weights given, zero
    /// weights left out).
    ///
    /// Index loops here and below, not iterator adapters: the same operations in the same order,
    /// and no call left to an adapter where the caller is built at a low opt-level (the gallery's
    /// Rutherford ensemble at opt-level 1 spent a fifth of its time in `Zip`, `ChunksExact` and
    /// `array::from_fn`'s closures).
    #[inline]
    pub fn weighted(&self, w: &[f64], i: usize) -> f64 {
        let mut s = 0.0;
        for (j, &wj) in w.iter().enumerate() {
            let Some(&kj) = self.k.get(i + j * self.m) else {
                break;
            };
            if wj != 0.0 {
                s += wj * kj;
            }
        }
        s
    }
}

/// The argument of a stage, from the weighted sum σ = Σ_j w_j k_j of the stages before it.
///
/// The last stage k_l of the row (the one just computed) enters after the others: the argument is
/// (y₀ + h Σ_{j<l} w_j k_j) + (h w_l) k_l, so that one multiply and one add separate a stage from
/// the next one's argument, against four for y₀ + h (Σ_{j<l} w_j k_j + w_l k_l): the stages of an
/// explicit method are a chain, each waiting for the last (DOP853 on Kepler, 100 orbits at tol
/// 1e-10: 1.62 → 1.58 ms). The result differs from the textbook order by one rounding at the scale
/// of y (the increment is added in two parts).
#[derive(Debug, Clone, Copy)]
pub(in crate::integrators) enum StageArgument<'a> {
    /// y₀ + h σ (a Runge-Kutta stage on y).
    Y { y0: &'a [f64], h: f64 },
    /// q₀ + h (c q̇₀ + h σ) (a Nyström stage on q, the k_j accelerations).
    Nystrom {
        q0: &'a [f64],
        v0: &'a [f64],
        c: f64,
        h: f64,
    },
}

impl StageArgument<'_> {
    /// The factor of the last stage: h for y, h² for q in a Nyström stage.
    #[inline(always)]
    fn last_factor(&self) -> f64 {
        match *self {
            StageArgument::Y { h, .. } => h,
            StageArgument::Nystrom { h, .. } => h * h,
        }
    }

    /// The argument for M components from the stages k_j = k[j·M .. (j+1)·M] and the weights `w`
    /// (see [`StageArgument`]), in arrays; `None` when a length does not fit M.
    #[inline(always)]
    pub(in crate::integrators) fn fixed<const M: usize>(self, k: &[f64], w: &[f64]) -> Option<[f64; M]> {
        let (&last, rest) = w.split_last()?;
        let sum = stage_sum::<M>(k, rest);
        let k_last = <&[f64; M]>::try_from(k.get(rest.len() * M..w.len() * M)?).ok()?;
        let c = self.last_factor() * last;
        let mut y = [0.0; M];
        match self {
            StageArgument::Y { y0, h } => {
                let y0 = <&[f64; M]>::try_from(y0).ok()?;
                for x in 0..M {
                    y[x] = y0[x] + h * sum[x];
                }
            }
            StageArgument::Nystrom { q0, v0, c, h } => {
                let (q0, v0) = (<&[f64; M]>::try_from(q0).ok()?, <&[f64; M]>::try_from(v0).ok()?);
                for x in 0..M {
                    y[x] = q0[x] + h * (c * v0[x] + h * sum[x]);
                }
            }
        }
        for x in 0..M {
            y[x] += c * k_last[x];
        }
        Some(y)
    }
}

/// The stage argument (see [`StageArgument`]) into `out`, from the stages k_j = k[j·m .. (j+1)·m]
/// (m = `out.len()`) whose weight w_j is nonzero (the high-order tableaux are sparse: 32 of DOP853's
/// 78 aᵢⱼ are 0). For m up to 12 everything is held in fixed-length arrays, so that the loops over
/// the components are unrolled and vectorised, and the result is stored whole (the vector field loads
/// its arguments as vectors; a vector load of entries stored one by one stalls store forwarding). For
/// a 2-dof system this made DOP853's step a quarter faster than with the closure-based form it
/// replaced (`--bench nystrom`, docs/benchmarks.md).
#[inline]
pub(in crate::integrators) fn combine_stages(k: &[f64], w: &[f64], arg: StageArgument<'_>, out: &mut [f64]) {
    fn any(k: &[f64], w: &[f64], arg: StageArgument<'_>, out: &mut [f64]) {
        let m = out.len();
        let (last, rest) = w.split_last().map_or((0.0, w), |(l, r)| (*l, r));
        out.fill(0.0);
        for (kj, &a) in k.chunks_exact(m.max(1)).zip(rest) {
            if a != 0.0 {
                out.iter_mut().zip(kj).for_each(|(s, k)| *s += a * k);
            }
        }
        match arg {
            StageArgument::Y { y0, h } => out.iter_mut().zip(y0).for_each(|(s, y)| *s = y + h * *s),
            StageArgument::Nystrom { q0, v0, c, h } => {
                for (x, s) in out.iter_mut().enumerate() {
                    *s = q0[x] + h * (c * v0[x] + h * *s);
                }
            }
        }
        let c = arg.last_factor() * last;
        let k_last = k.chunks_exact(m.max(1)).nth(rest.len()).unwrap_or(&[]);
        out.iter_mut().zip(k_last).for_each(|(s, k)| *s += c * k);
    }
    macro_rules! widths {
        ($($m:literal)*) => {
            match out.len() {
                $($m => {
                    if let Ok(o) = <&mut [f64; $m]>::try_from(&mut *out) {
                        if let Some(y) = arg.fixed(k, w) {
                            *o = y;
                            return;
                        }
                    }
                    any(k, w, arg, out)
                })*
                _ => any(k, w, arg, out),
            }
        };
    }
    widths!(1 2 3 4 5 6 8 12)
}

/// σ = Σ_j w_j k_j in an array of M components, over the stages k_j = k[j·M .. (j+1)·M] whose weight
/// is nonzero (the same operations in the same order as the general loop of [`combine_stages`]).
#[inline(always)]
pub(in crate::integrators) fn stage_sum<const M: usize>(k: &[f64], w: &[f64]) -> [f64; M] {
    let mut sum = [0.0; M];
    if M == 0 {
        return sum;
    }
    for (j, &a) in w.iter().enumerate().take(k.len() / M) {
        if a != 0.0 {
            // A fixed-length view: the loop below has no bounds checks to keep.
            let Ok(kj) = <&[f64; M]>::try_from(&k[j * M..(j + 1) * M]) else {
                continue;
            };
            for x in 0..M {
                sum[x] += a * kj[x];
            }
        }
    }
    sum
}

/// (y[..N], y[N..2N]) as arrays, in a function generic in the lengths only, not in the
/// model (`array::from_fn` in a model-generic method is a copy of its machinery per model).
#[inline(always)]
pub(super) fn split_halves<const N: usize, const W: usize>(y: &[f64; W]) -> ([f64; N], [f64; N]) {
    let (mut a, mut b) = ([0.0; N], [0.0; N]);
    a.copy_from_slice(&y[..N]);
    b.copy_from_slice(&y[N..2 * N]);
    (a, b)
}

/// [a, b] in one array of W = 2N entries (the inverse of [`split_halves`]).
#[inline(always)]
pub(super) fn join_halves<const N: usize, const W: usize>(a: &[f64; N], b: &[f64; N]) -> [f64; W] {
    let mut y = [0.0; W];
    y[..N].copy_from_slice(a);
    y[N..2 * N].copy_from_slice(b);
    y
}
