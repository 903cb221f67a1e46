//! Evaluation of lists of terms: the serial and parallel paths (bit-identical, see the
//! [`interaction`](crate::interaction) module docs) and the streaming serial paths of chains
//! (s, s+1), (s+1, s+2), … and of one-body terms on a range of particles, which walk through the
//! position and force arrays in order, without index lists and without a bounds check per term.

use crate::interaction::CHUNK;
use crate::particle::{sub3, Particle, Vec3};
use crate::potential::{one_gradient, pair_gradient, OnePotential, PairPotential};
use rayon::prelude::*;
use std::sync::Mutex;

/// Evaluates `eval` on every term and applies the result with `apply`, serially or on rayon's pool,
/// with bit-identical results (see the module docs); the value is the sum of the energies. A macro, so
/// that each path gets its own copy of the closure (a closure with two call sites is not inlined).
macro_rules! run_terms {
    ($terms:expr, $eval:expr, $apply:expr, $parallel:expr, $scratch:expr $(,)?) => {
        if $parallel {
            $crate::terms::run_parallel($terms, $eval, $apply, $scratch)
        } else {
            $crate::terms::run_serial($terms, $eval, $apply)
        }
    };
}
pub(crate) use run_terms;

/// The parallel path of `run_terms!`: fixed chunks evaluated on the pool, then applied in order.
pub(crate) fn run_parallel<T: Sync>(
    terms: &[T],
    eval: impl Fn(&T) -> (f64, Vec3) + Sync,
    mut apply: impl FnMut(&T, Vec3),
    scratch: &Mutex<Vec<Vec3>>,
) -> f64 {
    let mut buf = scratch.lock().unwrap_or_else(|e| e.into_inner());
    buf.resize(terms.len(), [0.0; 3]);
    let energies: Vec<f64> = buf
        .par_chunks_mut(CHUNK)
        .zip(terms.par_chunks(CHUNK))
        .map(|(b, c)| {
            let mut e = 0.0;
            for (slot, t) in b.iter_mut().zip(c) {
                let (u, g) = eval(t);
                e += u;
                *slot = g;
            }
            e
        })
        .collect();
    for (t, g) in terms.iter().zip(buf.iter()) {
        apply(t, *g);
    }
    energies.iter().fold(0.0, |a, e| a + e)
}

/// The serial path of `run_terms!`: chunk energies summed in the same order as the parallel path.
#[inline(always)]
pub(crate) fn run_serial<T>(
    terms: &[T],
    eval: impl Fn(&T) -> (f64, Vec3),
    mut apply: impl FnMut(&T, Vec3),
) -> f64 {
    let mut total = 0.0;
    for chunk in terms.chunks(CHUNK) {
        let mut e = 0.0;
        for t in chunk {
            let (u, g) = eval(t);
            e += u;
            apply(t, g);
        }
        total += e;
    }
    total
}

/// The first index s when `pairs` is the chain (s, s+1), (s+1, s+2), …: such a list is evaluated by
/// streaming through the arrays ([`chain_forces`]).
pub(crate) fn chain_start(pairs: &[[u32; 2]]) -> Option<usize> {
    let s = u64::from(pairs.first()?[0]);
    let chain = (s..)
        .zip(pairs)
        .all(|(k, &[i, j])| u64::from(i) == k && u64::from(j) == k + 1);
    chain.then_some(s as usize)
}

/// The first index s when `indices` is the range s, s+1, …
pub(crate) fn range_start(indices: &[u32]) -> Option<usize> {
    let s = u64::from(*indices.first()?);
    let range = (s..).zip(indices).all(|(k, &i)| u64::from(i) == k);
    range.then_some(s as usize)
}

/// Particles s, …, s+m−1 of the position array, the particle list and the force array.
#[inline(always)]
pub(crate) fn span<'a>(
    x: &'a [f64],
    ps: &'a [Particle],
    f: &'a mut [f64],
    s: usize,
    m: usize,
) -> (&'a [f64], &'a [Particle], &'a mut [f64]) {
    (&x[3 * s..3 * (s + m)], &ps[s..s + m], &mut f[3 * s..3 * (s + m)])
}

/// The serial path of a chain of pairs (0, 1), (1, 2), … over the particles of `x`, `ps` and `f` (a
/// [`span`]), streaming through positions, particles and forces (no index list, no bounds check per
/// term). Each particle receives the same additions in the same order as over the list,
/// (f − ∇U_{k−1}) + ∇U_k, and the energies are summed per chunk of [`CHUNK`] terms and then over the
/// chunks, as on the parallel path, so the result is bit-identical.
///
/// Not inlined on purpose: as arguments of their own function, `pot` and `f` are known not to alias,
/// so the potential's parameters stay in registers instead of being reloaded after every store to `f`.
#[inline(never)]
pub(crate) fn chain_forces<P: PairPotential>(pot: &P, x: &[f64], ps: &[Particle], f: &mut [f64]) -> f64 {
    let pairs = ps.len() - 1;
    let mut total = 0.0;
    // ∇U of the previous pair, still to be subtracted from the current particle.
    let mut carry = [0.0; 3];
    for c in (0..pairs).step_by(CHUNK) {
        let n = CHUNK.min(pairs - c);
        let (x, ps, f) = span(x, ps, f, c, n + 1);
        let mut energy = 0.0;
        for ((((a, b), fa), p1), p2) in x
            .chunks_exact(3)
            .zip(x[3..].chunks_exact(3))
            .zip(f.chunks_exact_mut(3))
            .zip(ps)
            .zip(&ps[1..])
        {
            let (u, g) = pair_gradient(pot, [b[0] - a[0], b[1] - a[1], b[2] - a[2]], p1, p2);
            energy += u;
            for k in 0..3 {
                fa[k] = fa[k] - carry[k] + g[k];
            }
            carry = g;
        }
        total += energy;
    }
    sub3(f, pairs, carry);
    total
}

/// The serial path of one-body terms on every particle of `x`, `ps` and `f` (a [`span`]), streaming
/// through the arrays (not inlined, for the reason given at [`chain_forces`]).
#[inline(never)]
pub(crate) fn range_forces<P: OnePotential>(
    pot: &P,
    t: f64,
    x: &[f64],
    ps: &[Particle],
    f: &mut [f64],
) -> f64 {
    let mut total = 0.0;
    for ((x, f), ps) in x
        .chunks(3 * CHUNK)
        .zip(f.chunks_mut(3 * CHUNK))
        .zip(ps.chunks(CHUNK))
    {
        let mut energy = 0.0;
        for ((r, fa), p) in x.chunks_exact(3).zip(f.chunks_exact_mut(3)).zip(ps) {
            let (u, g) = one_gradient(pot, t, [r[0], r[1], r[2]], p);
            energy += u;
            for k in 0..3 {
                fa[k] -= g[k];
            }
        }
        total += energy;
    }
    total
}
