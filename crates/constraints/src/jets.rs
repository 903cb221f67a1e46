//! Derivatives of vector-valued constraint functions by dual numbers.
//!
//! Core's [`ad`](noether_core::ad) kernels differentiate one scalar f(t, x, y). A set of m constraints
//! g(t, x, y) ∈ ℝᵐ is one vector-valued function that the user writes once; evaluating it with dual
//! numbers gives all m rows of a derivative at once, so these kernels lift the same seeding scheme to
//! vector outputs:
//!
//! - [`jacobian`]: ∂g/∂x or ∂g/∂y (m × n), one `DualSVec64<W>` evaluation per chunk of W columns
//!   (W = n for n ≤ 12, chunks of 8 beyond, as in core);
//! - [`along`]: the total derivative d/ds g(t + s δt, x + s δx, y + s δy) at s = 0, one `Dual64`
//!   evaluation (velocity constraints Φ_q q̇ + φ_t, the bias g_t + g_q q̇ of a velocity constraint);
//! - [`along2`]: the first and second derivatives along a straight line, one `Dual2_64` evaluation.
//!   With δ = (1, q̇) the second derivative of φ(t, q) is q̇ᵀφ_qq q̇ + 2 φ_qt q̇ + φ_tt = (Φ_q q̇)_q q̇ + …,
//!   the acceleration term of a holonomic constraint, without forming any Hessian;
//! - [`jacobian_varied`] and [`along_varied`]: the same quantities differentiated once more, along a
//!   variation ε of the point (and of the line's direction), over nested duals: what the exact
//!   Jacobian of the constrained equations of motion needs
//!   ([`Constrained`](crate::Constrained)'s `LinearizedDynamics`).

use nalgebra::{Const, DMatrix, U1};
use noether_core::Scalar;
use num_dual::{Dual, Dual2, Dual2_64, Dual64, DualVec};

/// A vector-valued function g(t, x, y) ∈ ℝᵐ, generic over the scalar type.
pub trait VectorField {
    /// Number of outputs m.
    fn outputs(&self) -> usize;
    /// Writes g(t, x, y) into `out` (length m).
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D], out: &mut [D]);
}

/// Which block of variables a Jacobian is taken with respect to.
pub use noether_core::ad::Block;

/// Buffers of up to 16 lifted scalars live on the stack.
const STACK: usize = 16;
type Buf<D> = noether_core::ad::Buf<D, STACK>;

/// Jacobian ∂g/∂(block) (rows: outputs, columns: the block's variables) into `out`, which must be
/// `outputs() × len(block)`.
pub fn jacobian<F: VectorField>(f: &F, t: f64, x: &[f64], y: &[f64], block: Block, out: &mut DMatrix<f64>) {
    let n = block.pick(x, y).len();
    debug_assert_eq!(out.shape(), (f.outputs(), n));
    if n == 0 || f.outputs() == 0 {
        return;
    }
    noether_core::with_width!(n, jacobian_w::<F>(f, t, x, y, block, out))
}

fn jacobian_w<F: VectorField, const W: usize>(
    f: &F,
    t: f64,
    x: &[f64],
    y: &[f64],
    block: Block,
    out: &mut DMatrix<f64>,
) {
    type D<const W: usize> = DualVec<f64, f64, Const<W>>;
    let (m, n) = out.shape();
    let mut g = Buf::<D<W>>::filled(m, D::<W>::from_re(0.0));
    for c0 in (0..n).step_by(W) {
        let (xs, ys) = noether_core::ad::seed_chunk::<W, STACK>(x, y, block, c0);
        f.eval(D::<W>::from_re(t), &xs, &ys, &mut g);
        let w = W.min(n - c0);
        for (k, gk) in g.iter().enumerate() {
            let e = gk.eps.unwrap_generic(Const::<W>, U1);
            for j in 0..w {
                out[(k, c0 + j)] = e[j];
            }
        }
    }
}

/// The total derivative d/ds g(t + s δt, x + s δx, y + s δy) at s = 0 into `out`; returns nothing
/// else. Empty `δx` or `δy` mean zero.
pub fn along<F: VectorField>(
    f: &F,
    t: f64,
    x: &[f64],
    y: &[f64],
    dir: (f64, &[f64], &[f64]),
    out: &mut [f64],
) {
    let (dt, dx, dy) = dir;
    let (xs, ys) = (Buf::along(x, dx, Dual64::new), Buf::along(y, dy, Dual64::new));
    let mut g = Buf::<Dual64>::filled(out.len(), Dual64::from_re(0.0));
    f.eval(Dual64::new(t, dt), &xs, &ys, &mut g);
    for (o, gk) in out.iter_mut().zip(g.iter()) {
        *o = gk.eps;
    }
}

/// First and second derivatives d/ds g, d²/ds² g of g(t + s δt, x + s δx, y + s δy) at s = 0.
pub fn along2<F: VectorField>(
    f: &F,
    t: f64,
    x: &[f64],
    y: &[f64],
    dir: (f64, &[f64], &[f64]),
    first: &mut [f64],
    second: &mut [f64],
) {
    let (dt, dx, dy) = dir;
    let lift = |v, d| Dual2_64::new(v, d, 0.0);
    let (xs, ys) = (Buf::along(x, dx, lift), Buf::along(y, dy, lift));
    let mut g = Buf::<Dual2_64>::filled(first.len(), Dual2_64::from_re(0.0));
    f.eval(Dual2_64::new(t, dt, 0.0), &xs, &ys, &mut g);
    for ((a, b), gk) in first.iter_mut().zip(second.iter_mut()).zip(g.iter()) {
        *a = gk.v1;
        *b = gk.v2;
    }
}

/// A variation of a point (x, y) and of a line's direction (δx, δy) through it: the point moves to
/// (x + ε ex, y + ε ey) and the direction to (δx + ε edx, δy + ε edy). Empty slices mean zero.
#[derive(Debug, Clone, Copy, Default)]
pub struct Variation<'a> {
    /// ∂x/∂ε.
    pub ex: &'a [f64],
    /// ∂y/∂ε.
    pub ey: &'a [f64],
    /// ∂(δx)/∂ε.
    pub edx: &'a [f64],
    /// ∂(δy)/∂ε.
    pub edy: &'a [f64],
}

/// `d[i]`, or 0 beyond the length of `d`.
fn at(d: &[f64], i: usize) -> f64 {
    d.get(i).copied().unwrap_or(0.0)
}

/// ∂/∂ε of the Jacobian ∂g/∂(block) at (t, x + ε ex, y + ε ey) into `out` (outputs × len(block)):
/// one evaluation per column over `Dual<Dual64>` (outer part: the column's unit direction, inner: ε).
pub fn jacobian_varied<F: VectorField>(
    f: &F,
    t: f64,
    (x, y): (&[f64], &[f64]),
    var: Variation<'_>,
    block: Block,
    out: &mut DMatrix<f64>,
) {
    type D = Dual<Dual64, f64>;
    let mut g = Buf::<D>::filled(f.outputs(), D::from_re(Dual64::from_re(0.0)));
    for j in 0..block.pick(x, y).len() {
        let (ux, uy) = match block {
            Block::X => (Some(j), None),
            Block::Y => (None, Some(j)),
        };
        let xs = nested(x, var.ex, ux);
        let ys = nested(y, var.ey, uy);
        f.eval(D::from_re(Dual64::from_re(t)), &xs, &ys, &mut g);
        for (k, gk) in g.iter().enumerate() {
            out[(k, j)] = gk.eps.eps;
        }
    }
}

/// The point x + ε e as `Dual<Dual64>` with the outer part seeded on entry `unit` (if any).
fn nested(x: &[f64], e: &[f64], unit: Option<usize>) -> Buf<Dual<Dual64, f64>> {
    Buf::new(x.len(), |i| {
        let seed = if unit == Some(i) { 1.0 } else { 0.0 };
        Dual::new(Dual64::new(x[i], at(e, i)), Dual64::from_re(seed))
    })
}

/// ∂/∂ε of g, of dg/ds and of d²g/ds² at s = ε = 0 for g(t + s δt, x(s, ε), y(s, ε)) along the line
/// x(s, ε) = x + ε ex + s (δx + ε edx) (and y likewise) into `out` (each of length `outputs()`): one
/// evaluation over `Dual2<Dual64>` (outer: s to second order, inner: ε). With δ = (1, q̇) the three
/// are the derivatives of a velocity constraint's residual and acceleration bias with respect to the
/// state, the direction q̇ varied with it.
pub fn along_varied<F: VectorField>(
    f: &F,
    t: f64,
    (x, y): (&[f64], &[f64]),
    dir: (f64, &[f64], &[f64]),
    var: Variation<'_>,
    out: [&mut [f64]; 3],
) {
    type D = Dual2<Dual64, f64>;
    let (dt, dx, dy) = dir;
    let xs = line_varied(x, dx, var.ex, var.edx);
    let ys = line_varied(y, dy, var.ey, var.edy);
    let mut g = Buf::<D>::filled(f.outputs(), D::from_re(Dual64::from_re(0.0)));
    let tt = D::new(Dual64::from_re(t), Dual64::from_re(dt), Dual64::from_re(0.0));
    f.eval(tt, &xs, &ys, &mut g);
    let [value, first, second] = out;
    for (k, gk) in g.iter().enumerate() {
        value[k] = gk.re.eps;
        first[k] = gk.v1.eps;
        second[k] = gk.v2.eps;
    }
}

/// x + ε e + s (δx + ε eδx) as `Dual2<Dual64>`.
fn line_varied(x: &[f64], dx: &[f64], e: &[f64], edx: &[f64]) -> Buf<Dual2<Dual64, f64>> {
    Buf::new(x.len(), |i| {
        Dual2::new(
            Dual64::new(x[i], at(e, i)),
            Dual64::new(at(dx, i), at(edx, i)),
            Dual64::from_re(0.0),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// g(t, x) = (x₀² x₁ + sin t, x₀ x₁ t): all derivatives known by hand.
    struct G;
    impl VectorField for G {
        fn outputs(&self) -> usize {
            2
        }
        fn eval<D: Scalar>(&self, t: D, x: &[D], _y: &[D], out: &mut [D]) {
            out[0] = x[0] * x[0] * x[1] + t.sin();
            out[1] = x[0] * x[1] * t;
        }
    }

    #[test]
    fn ad_vs_hand_jacobian_and_line_derivatives() {
        let (t, x) = (0.7, [1.3, -0.4]);
        let mut j = DMatrix::zeros(2, 2);
        jacobian(&G, t, &x, &[], Block::X, &mut j);
        let hand = DMatrix::from_row_slice(2, 2, &[2.0 * x[0] * x[1], x[0] * x[0], x[1] * t, x[0] * t]);
        assert!((j - hand).amax() < 1e-15);
        // Along (1, v): d/ds and d²/ds² of g(t+s, x+s v).
        let v = [0.3, 2.0];
        let (mut d1, mut d2) = ([0.0; 2], [0.0; 2]);
        along2(&G, t, &x, &[], (1.0, &v, &[]), &mut d1, &mut d2);
        let h1 = [
            2.0 * x[0] * x[1] * v[0] + x[0] * x[0] * v[1] + t.cos(),
            x[1] * t * v[0] + x[0] * t * v[1] + x[0] * x[1],
        ];
        // second: x0² x1 → 2 v0² x1 + 4 x0 v0 v1; sin t → −sin t; x0 x1 t → 2 v0 v1 t + 2 (x0 v1 + v0 x1)
        let h2 = [
            2.0 * v[0] * v[0] * x[1] + 4.0 * x[0] * v[0] * v[1] - t.sin(),
            2.0 * v[0] * v[1] * t + 2.0 * (x[0] * v[1] + v[0] * x[1]),
        ];
        let mut d1b = [0.0; 2];
        along(&G, t, &x, &[], (1.0, &v, &[]), &mut d1b);
        for k in 0..2 {
            assert!((d1[k] - h1[k]).abs() < 1e-14);
            assert!((d1b[k] - h1[k]).abs() < 1e-14);
            assert!((d2[k] - h2[k]).abs() < 1e-14);
        }
    }

    /// A chain of 20 variables differentiated in chunks equals the one-chunk result.
    struct Chain;
    impl VectorField for Chain {
        fn outputs(&self) -> usize {
            19
        }
        fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D], out: &mut [D]) {
            for k in 0..19 {
                out[k] = (x[k + 1] - x[k]).powi(2) * x[k];
            }
        }
    }

    #[test]
    fn ad_vs_hand_chunked_jacobian() {
        let x: Vec<f64> = (0..20).map(|i| 0.1 * i as f64 + (i as f64).sin()).collect();
        let mut j = DMatrix::zeros(19, 20);
        jacobian(&Chain, 0.0, &x, &[], Block::X, &mut j);
        let mut hand = DMatrix::zeros(19, 20);
        for k in 0..19 {
            let d = x[k + 1] - x[k];
            hand[(k, k)] = -2.0 * d * x[k] + d * d;
            hand[(k, k + 1)] = 2.0 * d * x[k];
        }
        assert!((j - hand).amax() < 1e-14);
    }
}
