//! Automatic-differentiation kernels: exact first and second derivatives of a scalar function
//! f(t, x, y) of time and two blocks of variables, by stack-allocated dual numbers of `num-dual`.
//!
//! Every derivative the library needs is one of four kernels:
//! - [`gradient`]: ∇_x f or ∇_y f (`DualSVec64<W>`, one evaluation per chunk of W variables);
//! - [`partial_t`]: ∂f/∂t (`Dual64`);
//! - [`hessian`]: a block ∂²f/∂a∂b with a, b ∈ {x, y} (`Dual2SVec64<W>` for a diagonal block that fits
//!   one chunk, `HyperDualSVec64<W, W>` per pair of chunks otherwise);
//! - [`directional_gradient`]: ∇_b (∂_t f·δt + ∇_x f·δx + ∇_y f·δy), a Hessian-vector product by one
//!   `HyperDualSVec64<1, W>` evaluation per chunk — never forming the Hessian.
//!
//! The chunk width W is chosen at run time from the block length n: W = n up to 6, the next of 8, 10, 12
//! up to 12 (one evaluation, everything on the stack; see `with_width!`), W = 8 with ⌈n/8⌉ chunks
//! beyond. Models of any size therefore use `Copy` duals and no allocation per arithmetic operation.
//!
//! Forward chunks make a gradient cost ⌈n/8⌉ evaluations and a Hessian ⌈n/8⌉² of them, so large blocks
//! go to reverse mode instead: one evaluation recorded on a tape ([`TapeVar`]) and one sweep
//! backwards give the whole gradient ([`gradient_taped`], from n = [`GRADIENT_TAPE_FROM`]), a
//! Hessian-vector product ([`directional_gradient_taped`], from n = [`DIRECTIONAL_TAPE_FROM`]) or a
//! Hessian block ([`hessian_taped`], beyond n = [`MAX_FIXED`]). A FPU chain of 1024
//! particles: gradient 2.85 ms → 0.11 ms; of 256, Hessian 29.5 ms → 0.16 ms.
//!
//! Lagrange's equations need four of these at once (∇_x f, ∇_y f, the mixed term and ∂²f/∂y²), which
//! two fused evaluations deliver:
//! - [`lagrange_terms`]: one evaluation with a [`LagrangeJet`], forward mode, everything on the stack
//!   (`EulerLagrange` uses it up to 10 degrees of freedom);
//! - [`lagrange_terms_taped`]: one evaluation recorded with a [`TapeVar`] and one reverse sweep, for
//!   any number of variables: ∂²f/∂y² is accumulated from the curvature of each nonlinear operation
//!   and the q̇-gradients of its arguments, so its cost follows the model's coupling instead of
//!   carrying an N×N Hessian through every operation (a 40-link chain: 38 µs, against 414 µs for the
//!   chunked kernels above; docs/benchmarks.md).

mod derivatives;
mod grad;
mod jet;
mod tape;

pub use grad::{GradJet, GradJet64};
pub use jet::{LagrangeJet, LagrangeJet64, Part};
pub use tape::{
    directional_gradient_taped, gradient_taped, hessian_taped, lagrange_terms_taped, LagrangeTermsDyn,
    TapeVar,
};

use crate::Scalar;
use nalgebra::{Const, DMatrix, SMatrix, SVector, U1};
use num_dual::{Derivative, Dual2Vec, Dual64, DualNum, DualVec, HyperDualVec};

/// A scalar function f(t, x, y), generic over the scalar type: the shape shared by Lagrangians
/// L(t, q, q̇), Hamiltonians H(t, q, p), discrete Lagrangians L_d(q₀, q₁) and potentials V(q).
pub trait Field {
    /// Evaluates f.
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D]) -> D;
}

/// Which block of variables a derivative is taken with respect to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Block {
    /// The first block (q for L and H, q₀ for L_d).
    X,
    /// The second block (q̇ for L, p for H, q₁ for L_d).
    Y,
}

impl Block {
    /// This block's variables among (x, y).
    #[inline]
    pub fn pick<'a, T>(self, x: &'a [T], y: &'a [T]) -> &'a [T] {
        match self {
            Block::X => x,
            Block::Y => y,
        }
    }
}

/// Largest block length differentiated in a single evaluation.
pub const MAX_FIXED: usize = 12;
/// Block length from which [`gradient`] records one evaluation on the tape ([`gradient_taped`])
/// instead of one forward evaluation per chunk of [`CHUNK`]: measured on a FPU chain, the chunks cost
/// 1.23 against 1.75 µs at n = 16 and 3.81 against 3.54 µs at n = 32 (`--bench kernels`,
/// docs/benchmarks.md).
pub const GRADIENT_TAPE_FROM: usize = 32;
/// Block length from which [`directional_gradient`] takes the tape ([`directional_gradient_taped`]):
/// on a chain of coupled rotors the chunks cost 5.18 against 5.13 µs at n = 16, 19.6 against 10.8 µs
/// at n = 32.
pub const DIRECTIONAL_TAPE_FROM: usize = 16;
/// Chunk width used for blocks longer than [`MAX_FIXED`].
pub const CHUNK: usize = 8;

/// Calls `$f::<…, W>` with the chunk width W for a block of length `$n`: W = n for n ≤ 6, the smallest
/// of 8, 10, 12 that holds n up to [`MAX_FIXED`] (the unused lanes carry zero derivatives), W =
/// [`CHUNK`] beyond. Nine widths, not twelve: every kernel is compiled once per width and model, and
/// the odd widths above 6 cost the gallery's build more than they gain (a Hessian at n = 7, 9, 11 pays
/// at most (8/7)² = 1.3× in its padded jet; docs/benchmarks.md). Exported for the vector-valued kernels
/// of other noether crates.
#[doc(hidden)]
#[macro_export]
macro_rules! with_width {
    ($n:expr, $f:ident :: <$($g:ty),*> ($($a:expr),*)) => {
        match $n {
            0 | 1 => $f::<$($g,)* 1>($($a),*),
            2 => $f::<$($g,)* 2>($($a),*),
            3 => $f::<$($g,)* 3>($($a),*),
            4 => $f::<$($g,)* 4>($($a),*),
            5 => $f::<$($g,)* 5>($($a),*),
            6 => $f::<$($g,)* 6>($($a),*),
            7 | 8 => $f::<$($g,)* 8>($($a),*),
            9 | 10 => $f::<$($g,)* 10>($($a),*),
            11 | 12 => $f::<$($g,)* 12>($($a),*),
            _ => $f::<$($g,)* { $crate::ad::CHUNK }>($($a),*),
        }
    };
}

/// A short buffer of lifted variables: on the stack when its length fits `S`, on the heap otherwise.
/// Derefs to a slice of exactly the requested length. Exported for the vector-valued kernels of other
/// noether crates (which also write into it through `DerefMut`).
pub enum Buf<D, const S: usize> {
    /// Up to `S` entries inline; the `usize` is the length in use.
    Stack([D; S], usize),
    /// More than `S` entries.
    Heap(Vec<D>),
}

impl<D: Scalar, const S: usize> Buf<D, S> {
    /// The buffer `[f(0), …, f(n-1)]`.
    ///
    /// On the stack an index loop into a zeroed array, not `array::from_fn`: this is instantiated for
    /// every dual type, width, model and call site, and `from_fn`'s machinery was a tenth of the
    /// gallery's LLVM IR (`cargo llvm-lines`, docs/benchmarks.md). On the heap `collect`: a `push`
    /// loop or index writes into `vec![zero; n]` made the RATTLE step of the 10-link chain 15–25 %
    /// slower.
    ///
    /// Write `f` in a function that is not generic over the model (or call [`filled`](Self::filled),
    /// [`constants`](Self::constants), [`seed_chunk`]): a closure's type carries every generic
    /// parameter of the function it is written in, so a closure written in a model-generic function
    /// makes a copy of this, and of `collect`'s machinery, for every model and chunk width. Those
    /// copies were 29 % of the gallery's LLVM IR (`cargo llvm-lines`, docs/benchmarks.md).
    #[inline]
    pub fn new(n: usize, mut f: impl FnMut(usize) -> D) -> Self {
        if n <= S {
            let mut a = [D::zero(); S];
            #[allow(clippy::needless_range_loop)] // the iterator form is what this avoids
            for i in 0..n {
                a[i] = f(i);
            }
            Buf::Stack(a, n)
        } else {
            Buf::Heap((0..n).map(f).collect())
        }
    }

    /// The blocks x and y lifted entry by entry, entry i of block b as `seed(b, values of b, i)`.
    #[inline]
    pub(crate) fn pair(x: &[f64], y: &[f64], seed: impl Fn(Block, &[f64], usize) -> D) -> (Self, Self) {
        let xs = Self::new(x.len(), |i| seed(Block::X, x, i));
        (xs, Self::new(y.len(), |i| seed(Block::Y, y, i)))
    }

    /// `n` copies of `d`.
    #[inline]
    pub fn filled(n: usize, d: D) -> Self {
        Self::new(n, |_| d)
    }

    /// The reals `x` as constants of D (every derivative part zero).
    #[inline]
    pub fn constants(x: &[f64]) -> Self {
        Self::new(x.len(), |i| D::from(x[i]))
    }

    /// The points x + s δx of a line as `lift(x_i, δx_i)` (δx_i = 0 beyond the length of `dx`, so an
    /// empty `dx` means no motion), for a derivative along the line: `lift` is a function such as
    /// `Dual64::new`, so one copy serves every model.
    #[inline]
    pub fn along(x: &[f64], dx: &[f64], lift: fn(f64, f64) -> D) -> Self {
        Self::new(x.len(), |i| lift(x[i], dx.get(i).copied().unwrap_or(0.0)))
    }
}

impl<D, const S: usize> std::ops::Deref for Buf<D, S> {
    type Target = [D];
    #[inline]
    fn deref(&self) -> &[D] {
        match self {
            Buf::Stack(a, n) => &a[..*n],
            Buf::Heap(v) => v,
        }
    }
}

impl<D, const S: usize> std::ops::DerefMut for Buf<D, S> {
    #[inline]
    fn deref_mut(&mut self) -> &mut [D] {
        match self {
            Buf::Stack(a, n) => &mut a[..*n],
            Buf::Heap(v) => v,
        }
    }
}

/// The arguments (x, y) lifted to `DualVec<W>` for one chunk of a gradient or Jacobian: the variables
/// `c0..c0+W` of `block` carry the unit directions `0..W` (∂/∂block_{c0+k} is derivative k of the
/// result), every other variable is a constant. Buffers hold up to `S` entries on the stack.
#[allow(clippy::type_complexity)]
pub fn seed_chunk<const W: usize, const S: usize>(
    x: &[f64],
    y: &[f64],
    block: Block,
    c0: usize,
) -> (
    Buf<DualVec<f64, f64, Const<W>>, S>,
    Buf<DualVec<f64, f64, Const<W>>, S>,
) {
    let seed = |b: Block, vals: &[f64], i: usize| {
        let d = DualVec::<f64, f64, Const<W>>::from_re(vals[i]);
        if b == block && i >= c0 && i < c0 + W {
            d.derivative(i - c0)
        } else {
            d
        }
    };
    Buf::pair(x, y, seed)
}

/// Value of f at real arguments.
#[inline]
pub fn value<F: Field>(f: &F, t: f64, x: &[f64], y: &[f64]) -> f64 {
    f.eval(t, x, y)
}

/// ∂f/∂t by one `Dual64` evaluation.
pub fn partial_t<F: Field>(f: &F, t: f64, x: &[f64], y: &[f64]) -> f64 {
    with_width!(x.len().max(y.len()), partial_t_w::<F>(f, t, x, y))
}

fn partial_t_w<F: Field, const W: usize>(f: &F, t: f64, x: &[f64], y: &[f64]) -> f64 {
    let (xs, ys) = (Buf::<Dual64, W>::constants(x), Buf::<Dual64, W>::constants(y));
    f.eval(Dual64::new(t, 1.0), &xs, &ys).eps
}

/// Gradient of f with respect to `block`, written into `out`; returns the value of f. Forward duals
/// ([`gradient_forward`]) below [`GRADIENT_TAPE_FROM`] variables, the tape ([`gradient_taped`]) from
/// there on.
pub fn gradient<F: Field>(f: &F, t: f64, x: &[f64], y: &[f64], block: Block, out: &mut [f64]) -> f64 {
    if block.pick(x, y).len() >= GRADIENT_TAPE_FROM {
        return gradient_taped(f, t, x, y, block, out);
    }
    gradient_forward(f, t, x, y, block, out)
}

/// [`gradient`] by forward duals for any block length: one [`GradJet64<W>`] evaluation with all
/// arguments on the stack when both blocks have at most [`MAX_FIXED`] entries (W = the longer one),
/// one evaluation per chunk of [`CHUNK`] variables otherwise.
pub fn gradient_forward<F: Field>(f: &F, t: f64, x: &[f64], y: &[f64], block: Block, out: &mut [f64]) -> f64 {
    let n = block.pick(x, y).len();
    debug_assert_eq!(out.len(), n);
    if n == 0 {
        return f.eval(t, x, y);
    }
    let w = x.len().max(y.len());
    if w <= MAX_FIXED {
        return with_width!(w, gradient_once::<F>(f, t, x, y, block, out));
    }
    gradient_chunks::<F, CHUNK>(f, t, x, y, block, out)
}

/// One evaluation with both blocks (of at most W entries) lifted into arrays on the stack. Its own
/// function for each W, kept out of the dispatch, so that the model inlines into it: together with the
/// dense jet this took a 2-dof gradient from 36 to ~6 ns (`--bench rates`).
#[inline(never)]
fn gradient_once<F: Field, const W: usize>(
    f: &F,
    t: f64,
    x: &[f64],
    y: &[f64],
    block: Block,
    out: &mut [f64],
) -> f64 {
    type D<const W: usize> = GradJet64<W>;
    // One block alone, of exactly W variables (a potential V(q), a kinetic energy T(p)): every length
    // a constant (see `gradient_exact`).
    let (alone, other) = match block {
        Block::X => (x, y),
        Block::Y => (y, x),
    };
    if let (true, Ok(va), Ok(oa)) = (
        other.is_empty(),
        <&[f64; W]>::try_from(alone),
        <&mut [f64; W]>::try_from(&mut *out),
    ) {
        return gradient_alone::<F, W>(f, t, va, block, oa);
    }
    // Each argument is written whole (value and gradient in one store each): the model reads the
    // gradient as one vector, and a vector load of entries stored one by one stalls store forwarding.
    let n = out.len();
    let xs = lift_gradient::<W>(x, block == Block::X, n);
    let ys = lift_gradient::<W>(y, block == Block::Y, n);
    let r = f.eval(D::<W>::from_re(t), &xs[..x.len()], &ys[..y.len()]);
    // An element loop, not `copy_from_slice`: a few entries, no call to memcpy.
    for (o, g) in out.iter_mut().zip(r.eps.iter()) {
        *o = *g;
    }
    r.re
}

/// The entries of `v` as [`GradJet64<W>`] in an array, entry i < n seeded with the unit direction i
/// when `seeded`. Generic in W only, not in the model ([`Buf::new`] says why).
#[inline]
fn lift_gradient<const W: usize>(v: &[f64], seeded: bool, n: usize) -> [GradJet64<W>; W] {
    let mut a = [GradJet64::<W>::from_re(0.0); W];
    for (i, (d, v)) in a.iter_mut().zip(v).enumerate() {
        *d = if seeded && i < n {
            GradJet64::<W>::new(*v, SVector::from_fn(|k, _| if k == i { 1.0 } else { 0.0 }))
        } else {
            GradJet64::<W>::from_re(*v)
        };
    }
    a
}

/// ∇ₓf(t, x) for a field of x alone (y = ∅) with exactly W variables, written into `out`; returns the
/// value: one [`GradJet64<W>`] evaluation. Every length is a constant here, so the lifted arguments
/// are an array built with constant indices that stays in registers when the model inlines (no
/// round trip through the stack, no store-forwarding stall on a vector load of entries written one
/// by one). This took the Hénon-Heiles gradient from 23.8 to 8.6 ns (`--bench rates`). A caller with a
/// fixed dof picks `gradient_exact::<_, W>` once (as [`Natural`](crate::Natural) does at
/// construction) and skips the dispatch on the length.
#[inline]
pub fn gradient_exact<F: Field, const W: usize>(f: &F, t: f64, x: &[f64; W], out: &mut [f64; W]) -> f64 {
    gradient_alone(f, t, x, Block::X, out)
}

/// Entry i of `v` as the variable i of a [`GradJet64<W>`]. An index loop in a function generic in W
/// only: `array::from_fn` in the model-generic caller was a copy of its machinery per model
/// ([`Buf::new`] says why).
#[inline(always)]
fn variables<const W: usize>(v: &[f64; W]) -> [GradJet64<W>; W] {
    let mut vs = [GradJet64::<W>::from_re(0.0); W];
    for i in 0..W {
        vs[i] = GradJet64::<W>::variable(v[i], i);
    }
    vs
}

/// [`gradient_exact`] for a field of either block alone (the other one empty).
#[inline(always)]
fn gradient_alone<F: Field, const W: usize>(
    f: &F,
    t: f64,
    v: &[f64; W],
    block: Block,
    out: &mut [f64; W],
) -> f64 {
    let vs = variables::<W>(v);
    let t = GradJet64::<W>::from_re(t);
    let r = match block {
        Block::X => f.eval(t, &vs, &[]),
        Block::Y => f.eval(t, &[], &vs),
    };
    *out = r.eps.into();
    r.re
}

/// One evaluation per chunk of W variables of `block`, the arguments on the heap.
fn gradient_chunks<F: Field, const W: usize>(
    f: &F,
    t: f64,
    x: &[f64],
    y: &[f64],
    block: Block,
    out: &mut [f64],
) -> f64 {
    type D<const W: usize> = GradJet64<W>;
    let n = out.len();
    let mut val = 0.0;
    for c0 in (0..n).step_by(W) {
        let seed = |b: Block, vals: &[f64], i: usize| {
            if b == block && i >= c0 && i < c0 + W {
                D::<W>::variable(vals[i], i - c0)
            } else {
                D::<W>::from_re(vals[i])
            }
        };
        let xs: Vec<D<W>> = (0..x.len()).map(|i| seed(Block::X, x, i)).collect();
        let ys: Vec<D<W>> = (0..y.len()).map(|i| seed(Block::Y, y, i)).collect();
        let r = f.eval(D::<W>::from_re(t), &xs, &ys);
        val = r.re;
        let m = W.min(n - c0);
        out[c0..c0 + m].copy_from_slice(&r.eps.as_slice()[..m]);
    }
    val
}

/// Hessian block ∂²f/∂a∂b (rows: block `a`, columns: block `b`) written into `out`. Blocks longer than
/// [`MAX_FIXED`] come from the tape ([`hessian_taped`]), shorter ones from forward duals
/// ([`hessian_forward`]).
pub fn hessian<F: Field>(f: &F, t: f64, x: &[f64], y: &[f64], a: Block, b: Block, out: &mut DMatrix<f64>) {
    if a.pick(x, y).len().max(b.pick(x, y).len()) > MAX_FIXED {
        // One taped evaluation instead of ⌈n/8⌉² hyper-dual chunk pairs.
        return hessian_taped(f, t, x, y, a, b, out);
    }
    hessian_forward(f, t, x, y, a, b, out)
}

/// [`hessian`] by forward duals for any block lengths: one `Dual2SVec64<n>` evaluation for a diagonal
/// block of n ≤ [`MAX_FIXED`], one `HyperDualSVec64<W, W>` evaluation per pair of chunks otherwise.
pub fn hessian_forward<F: Field>(
    f: &F,
    t: f64,
    x: &[f64],
    y: &[f64],
    a: Block,
    b: Block,
    out: &mut DMatrix<f64>,
) {
    let (na, nb) = (a.pick(x, y).len(), b.pick(x, y).len());
    debug_assert_eq!(out.shape(), (na, nb));
    if na == 0 || nb == 0 {
        return;
    }
    if a == b && na <= MAX_FIXED {
        with_width!(na, hessian_diag_w::<F>(f, t, x, y, a, out))
    } else if a != b && na.max(nb) <= MAX_FIXED {
        // A small mixed block (e.g. ∂²L_d/∂q₀∂q₁): one evaluation with width max(na, nb).
        with_width!(na.max(nb), hessian_blocks::<F>(f, t, x, y, a, b, out))
    } else {
        hessian_blocks::<F, CHUNK>(f, t, x, y, a, b, out)
    }
}

fn hessian_diag_w<F: Field, const W: usize>(
    f: &F,
    t: f64,
    x: &[f64],
    y: &[f64],
    a: Block,
    out: &mut DMatrix<f64>,
) {
    type D<const W: usize> = Dual2Vec<f64, f64, Const<W>>;
    let (xs, ys) = seed_second::<W>(x, y, a);
    let r = f.eval(D::<W>::from_re(t), &xs, &ys);
    let h = r.v2.unwrap_generic(Const::<W>, Const::<W>);
    let n = out.nrows();
    for j in 0..n {
        for i in 0..n {
            out[(i, j)] = h[(i, j)];
        }
    }
}

/// (x, y) lifted to `Dual2Vec<W>` with the variables of `block` seeded as the directions 0..: generic
/// in W only, not in the model ([`Buf::new`] says why).
#[allow(clippy::type_complexity)]
pub(crate) fn seed_second<const W: usize>(
    x: &[f64],
    y: &[f64],
    block: Block,
) -> (
    Buf<Dual2Vec<f64, f64, Const<W>>, W>,
    Buf<Dual2Vec<f64, f64, Const<W>>, W>,
) {
    type D<const W: usize> = Dual2Vec<f64, f64, Const<W>>;
    let seed = |b: Block, vals: &[f64], i: usize| {
        let d = D::<W>::from_re(vals[i]);
        if b == block {
            d.derivative(i)
        } else {
            d
        }
    };
    Buf::pair(x, y, seed)
}

/// (x, y) lifted to `HyperDualVec<W, W>` for the chunk (ca.., cb..) of the mixed Hessian: variable
/// ca + k of block `a` carries ε₁ direction k, variable cb + k of block `b` ε₂ direction k. Generic
/// in W only, not in the model ([`Buf::new`] says why).
#[allow(clippy::type_complexity)]
fn seed_pair<const W: usize>(
    x: &[f64],
    y: &[f64],
    (a, ca): (Block, usize),
    (b, cb): (Block, usize),
) -> (
    Buf<HyperDualVec<f64, f64, Const<W>, Const<W>>, W>,
    Buf<HyperDualVec<f64, f64, Const<W>, Const<W>>, W>,
) {
    type D<const W: usize> = HyperDualVec<f64, f64, Const<W>, Const<W>>;
    let seed = |blk: Block, vals: &[f64], i: usize| {
        let mut d = D::<W>::from_re(vals[i]);
        if blk == a && i >= ca && i < ca + W {
            d = d.derivative1(i - ca);
        }
        if blk == b && i >= cb && i < cb + W {
            d = d.derivative2(i - cb);
        }
        d
    };
    Buf::pair(x, y, seed)
}

fn hessian_blocks<F: Field, const W: usize>(
    f: &F,
    t: f64,
    x: &[f64],
    y: &[f64],
    a: Block,
    b: Block,
    out: &mut DMatrix<f64>,
) {
    type D<const W: usize> = HyperDualVec<f64, f64, Const<W>, Const<W>>;
    let (na, nb) = out.shape();
    for ca in (0..na).step_by(W) {
        for cb in (0..nb).step_by(W) {
            if a == b && cb < ca {
                continue; // symmetric: mirrored below
            }
            let (xs, ys) = seed_pair::<W>(x, y, (a, ca), (b, cb));
            let r = f.eval(D::<W>::from_re(t), &xs, &ys);
            let h = r.eps1eps2.unwrap_generic(Const::<W>, Const::<W>);
            for i in 0..W.min(na - ca) {
                for j in 0..W.min(nb - cb) {
                    out[(ca + i, cb + j)] = h[(i, j)];
                    if a == b {
                        out[(cb + j, ca + i)] = h[(i, j)];
                    }
                }
            }
        }
    }
}

/// Directional gradient: `out_j = ∂/∂b_j [∂_t f·δt + ∇_x f·δx + ∇_y f·δy]` (a Hessian-vector product
/// without the Hessian). Pass an empty slice for δx or δy to mean zero. Returns ∇_b f in `grad_b` if
/// given (it comes for free). Forward duals ([`directional_gradient_forward`]) below
/// [`DIRECTIONAL_TAPE_FROM`] variables in b, the tape ([`directional_gradient_taped`]) from there on.
#[allow(clippy::too_many_arguments)]
pub fn directional_gradient<F: Field>(
    f: &F,
    t: f64,
    x: &[f64],
    y: &[f64],
    dir: (f64, &[f64], &[f64]),
    b: Block,
    out: &mut [f64],
    grad_b: Option<&mut [f64]>,
) {
    if out.len() >= DIRECTIONAL_TAPE_FROM {
        return directional_gradient_taped(f, t, x, y, dir, b, out, grad_b);
    }
    directional_gradient_forward(f, t, x, y, dir, b, out, grad_b)
}

/// [`directional_gradient`] by forward duals for any block length: one `HyperDualSVec64<1, W>`
/// evaluation per chunk.
#[allow(clippy::too_many_arguments)]
pub fn directional_gradient_forward<F: Field>(
    f: &F,
    t: f64,
    x: &[f64],
    y: &[f64],
    dir: (f64, &[f64], &[f64]),
    b: Block,
    out: &mut [f64],
    grad_b: Option<&mut [f64]>,
) {
    let n = out.len();
    if n == 0 {
        return;
    }
    with_width!(n, directional_gradient_w::<F>(f, (t, x, y), dir, b, out, grad_b))
}

/// [`directional_gradient`] with chunk width W at the point `at` = (t, x, y).
fn directional_gradient_w<F: Field, const W: usize>(
    f: &F,
    at: (f64, &[f64], &[f64]),
    dir: (f64, &[f64], &[f64]),
    b: Block,
    out: &mut [f64],
    mut grad_b: Option<&mut [f64]>,
) {
    let n = out.len();
    let t = at.0;
    for c0 in (0..n).step_by(W) {
        let (xs, ys) = seed_directional::<W>(at, dir, b, c0);
        let r = f.eval(lift_directional::<W>(t, dir.0), &xs, &ys);
        let m = W.min(n - c0);
        let h = r.eps1eps2.unwrap_generic(Const::<1>, Const::<W>);
        for j in 0..m {
            out[c0 + j] = h[(0, j)];
        }
        if let Some(g) = grad_b.as_deref_mut() {
            let e = r.eps2.unwrap_generic(U1, Const::<W>);
            for j in 0..m {
                g[c0 + j] = e[(0, j)];
            }
        }
    }
}

/// v + d ε₁ as a `HyperDualVec<1, W>`.
#[inline]
fn lift_directional<const W: usize>(v: f64, d: f64) -> HyperDualVec<f64, f64, Const<1>, Const<W>> {
    if d == 0.0 {
        HyperDualVec::from_re(v)
    } else {
        HyperDualVec::new(
            v,
            Derivative::some(SVector::from([d])),
            Derivative::none(),
            Derivative::none(),
        )
    }
}

/// (x, y) lifted to `HyperDualVec<1, W>` with the direction (δx, δy) on ε₁ and the variables
/// c0..c0+W of `block` on ε₂: generic in W only, not in the model ([`Buf::new`] says why).
#[allow(clippy::type_complexity)]
fn seed_directional<const W: usize>(
    (_, x, y): (f64, &[f64], &[f64]),
    (_, dx, dy): (f64, &[f64], &[f64]),
    block: Block,
    c0: usize,
) -> (
    Buf<HyperDualVec<f64, f64, Const<1>, Const<W>>, W>,
    Buf<HyperDualVec<f64, f64, Const<1>, Const<W>>, W>,
) {
    let seed = |blk: Block, vals: &[f64], dirs: &[f64], i: usize| {
        let d = lift_directional::<W>(vals[i], dirs.get(i).copied().unwrap_or(0.0));
        if blk == block && i >= c0 && i < c0 + W {
            d.derivative2(i - c0)
        } else {
            d
        }
    };
    (
        Buf::new(x.len(), |i| seed(Block::X, x, dx, i)),
        Buf::new(y.len(), |i| seed(Block::Y, y, dy, i)),
    )
}

/// Everything Lagrange's equations need from f(t, x, y) at one point, from one evaluation with a
/// [`LagrangeJet`]: f, ∇_x f, ∇_y f, the mixed term ∇_y(∂_t f + ∇_x f·y) and the Hessian ∂²f/∂y².
///
/// For a Lagrangian (x = q, y = q̇) these are L, ∂L/∂q, the momenta p, the term
/// (∂²L/∂q̇∂q)·q̇ + ∂²L/∂q̇∂t of Lagrange's equations and the mass matrix M.
#[derive(Debug, Clone, Copy)]
pub struct LagrangeTerms<const N: usize> {
    /// f.
    pub value: f64,
    /// ∇_x f (∂L/∂q).
    pub grad_x: SVector<f64, N>,
    /// ∇_y f (the momenta ∂L/∂q̇).
    pub grad_y: SVector<f64, N>,
    /// ∇_y(∂_t f + ∇_x f·y): (∂²L/∂q̇∂q)·q̇ + ∂²L/∂q̇∂t.
    pub mixed: SVector<f64, N>,
    /// ∂²f/∂y² (the mass matrix ∂²L/∂q̇²).
    pub hess_yy: SMatrix<f64, N, N>,
}

/// [`LagrangeTerms`] of f at (t, x, y) by one evaluation of f with a [`LagrangeJet64<N>`] seeded at
/// (t + s, x + s·y + δx, y + δy): no heap allocation, every transcendental function evaluated once.
#[inline(always)]
pub fn lagrange_terms<F: Field, const N: usize>(
    f: &F,
    t: f64,
    x: &[f64; N],
    y: &[f64; N],
) -> LagrangeTerms<N> {
    type J<const N: usize> = LagrangeJet64<N>;
    let unit = |i: usize| Part::unit(Const::<N>, i);
    // Absent parts stay `None`: a function of q alone never carries a q̇-part, and so on.
    let (zero, zero_h) = (Part::none, Part::none);
    let mut xs = [J::<N>::from_re(0.0); N];
    let mut ys = [J::<N>::from_re(0.0); N];
    for i in 0..N {
        xs[i] = J::new(x[i], unit(i), y[i], zero(), zero(), zero_h());
        ys[i] = J::new(y[i], zero(), 0.0, unit(i), zero(), zero_h());
    }
    let tt = J::new(t, zero(), 1.0, zero(), zero(), zero_h());
    let r = f.eval(tt, &xs, &ys);
    let row = |p: &Part<f64, f64, U1, Const<N>>| p.get().map_or_else(SVector::zeros, |m| m.transpose());
    LagrangeTerms {
        value: r.re,
        grad_x: row(&r.gx),
        grad_y: row(&r.gw),
        mixed: row(&r.hsw),
        hess_yy: r.hww.matrix(Const::<N>),
    }
}

/// The real part of any scalar (for models that branch on values).
#[inline]
pub fn re<D: DualNum<f64>>(x: &D) -> f64 {
    x.re()
}
