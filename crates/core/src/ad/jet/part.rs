//! One derivative part of a [`LagrangeJet`](super::LagrangeJet): a row vector (∂/∂q, ∂/∂q̇, ∂²/∂s∂q̇)
//! or the square Hessian ∂²/∂q̇².
//!
//! A part is `None` while it is identically zero (it then costs nothing); a present part is processed
//! whole, in fixed-length loops the compiler unrolls, except for the one operation that dominates the
//! cost of a Hessian: the symmetric outer product u vᵀ + v uᵀ of two gradients in q̇. For parts of at
//! least [`SPAN_MIN`] columns it first scans u and v for their first and last non-zero entries and
//! updates only those columns: a quantity that depends on q̇₁…q̇ₖ only (the running velocity sums of
//! a chain) costs O(k N) there instead of O(N²). Sparsity is so discovered at run time, for any model.

use nalgebra::allocator::Allocator;
use nalgebra::{DefaultAllocator, Dim, OMatrix, U1};
use num_dual::DualNum;
use std::marker::PhantomData;
use std::ops::{Add, AddAssign, DivAssign, MulAssign, Neg, Sub, SubAssign};

/// Parts with at least this many columns restrict outer products to their non-zero columns.
pub const SPAN_MIN: usize = 5;

/// One derivative part of a [`LagrangeJet`](super::LagrangeJet): `None` means identically zero.
#[derive(Debug)]
pub struct Part<T: DualNum<F>, F, R: Dim, C: Dim>(Option<OMatrix<T, R, C>>, PhantomData<F>)
where
    DefaultAllocator: Allocator<R, C>;

impl<T: DualNum<F>, F, R: Dim, C: Dim> Clone for Part<T, F, R, C>
where
    DefaultAllocator: Allocator<R, C>,
{
    #[inline(always)]
    fn clone(&self) -> Self {
        Part(self.0.clone(), PhantomData)
    }
}

impl<T: DualNum<F> + Copy, F: Copy, const R: usize, const C: usize> Copy
    for Part<T, F, nalgebra::Const<R>, nalgebra::Const<C>>
{
}

impl<T: DualNum<F>, F, R: Dim, C: Dim> Part<T, F, R, C>
where
    DefaultAllocator: Allocator<R, C>,
{
    /// A part that is identically zero.
    #[inline(always)]
    pub fn none() -> Self {
        Part(None, PhantomData)
    }

    /// A present part.
    #[inline(always)]
    pub fn some(m: OMatrix<T, R, C>) -> Self {
        Part(Some(m), PhantomData)
    }

    /// The entries (`None` when identically zero).
    #[inline(always)]
    pub fn get(&self) -> Option<&OMatrix<T, R, C>> {
        self.0.as_ref()
    }

    /// `α x`.
    #[inline(always)]
    pub fn scale(x: &Self, alpha: &T) -> Self {
        Part(x.0.as_ref().map(|a| a.map(|ai| ai * alpha.clone())), PhantomData)
    }

    /// `self *= α`.
    #[inline(always)]
    pub fn scale_mut(&mut self, alpha: &T) {
        if let Some(a) = &mut self.0 {
            a.apply(|ai| *ai *= alpha.clone());
        }
    }

    /// `self += α x`.
    #[inline(always)]
    pub fn axpy(&mut self, alpha: &T, x: &Self) {
        if let Some(b) = &x.0 {
            match &mut self.0 {
                Some(a) => a.zip_apply(b, |ai, bi| *ai += bi * alpha.clone()),
                None => *self = Part::scale(x, alpha),
            }
        }
    }

    /// `α x + β y` (either may be absent).
    #[inline(always)]
    pub fn lin(x: &Self, alpha: &T, y: &Self, beta: &T) -> Self {
        match (&x.0, &y.0) {
            (Some(a), Some(b)) => Part::some(a.zip_map(b, |ai, bi| ai * alpha.clone() + bi * beta.clone())),
            (Some(_), None) => Part::scale(x, alpha),
            (None, Some(_)) => Part::scale(y, beta),
            (None, None) => Part::none(),
        }
    }

    /// `x + σ y` (either may be absent).
    #[inline(always)]
    pub fn sum(x: &Self, y: &Self, sign: &T) -> Self {
        match (&x.0, &y.0) {
            (Some(a), Some(b)) => Part::some(a.zip_map(b, |ai, bi| ai + bi * sign.clone())),
            (Some(_), None) => x.clone(),
            (None, Some(_)) => Part::scale(y, sign),
            (None, None) => Part::none(),
        }
    }
}

impl<T: DualNum<F>, F, C: Dim> Part<T, F, U1, C>
where
    DefaultAllocator: Allocator<U1, C>,
{
    /// The unit row vector e_i (a seed).
    #[inline(always)]
    pub fn unit(c: C, i: usize) -> Self {
        let mut m = OMatrix::<T, U1, C>::zeros_generic(U1, c);
        m[i] = T::one();
        Self::some(m)
    }

    /// `[first, last + 1)` of the non-zero entries (empty when all are zero).
    #[inline(always)]
    fn extent(s: &[T]) -> (usize, usize) {
        match s.iter().position(|v| !v.is_zero()) {
            Some(lo) => (
                lo,
                s.len() - s.iter().rev().position(|v| !v.is_zero()).unwrap_or(0),
            ),
            None => (0, 0),
        }
    }
}

impl<T: DualNum<F>, F, C: Dim> Part<T, F, C, C>
where
    DefaultAllocator: Allocator<C, C> + Allocator<U1, C>,
{
    /// `self += α (u vᵀ + v uᵀ)` for row vectors u, v (`v = u` gives 2α u uᵀ); only the columns where
    /// u or v is non-zero are touched (for parts of at least `SPAN_MIN` columns).
    #[inline(always)]
    pub fn sym_outer(&mut self, alpha: &T, u: &Part<T, F, U1, C>, v: &Part<T, F, U1, C>) {
        let (Some(u), Some(v)) = (&u.0, &v.0) else {
            return;
        };
        let (n, c) = (u.ncols(), u.shape_generic().1);
        let m = self.0.get_or_insert_with(|| OMatrix::zeros_generic(c, c));
        let (u, v) = (u.as_slice(), v.as_slice());
        let m = m.as_mut_slice();
        let (lo, hi) = if C::try_to_usize().is_none_or(|n| n >= SPAN_MIN) {
            let (eu, ev) = (Part::<T, F, U1, C>::extent(u), Part::<T, F, U1, C>::extent(v));
            if eu.0 == eu.1 || ev.0 == ev.1 {
                return; // u = 0 or v = 0: nothing to add
            }
            (eu.0.min(ev.0), eu.1.max(ev.1))
        } else {
            (0, n)
        };
        for j in lo..hi {
            let (uj, vj) = (u[j].clone() * alpha.clone(), v[j].clone() * alpha.clone());
            let col = &mut m[j * n..(j + 1) * n];
            for i in 0..n {
                col[i] += u[i].clone() * vj.clone() + v[i].clone() * uj.clone();
            }
        }
    }

    /// The matrix, zero when absent.
    #[inline(always)]
    pub fn matrix(&self, c: C) -> OMatrix<T, C, C> {
        self.0.clone().unwrap_or_else(|| OMatrix::zeros_generic(c, c))
    }
}

impl<T: DualNum<F>, F, R: Dim, C: Dim> Add<&Part<T, F, R, C>> for Part<T, F, R, C>
where
    DefaultAllocator: Allocator<R, C>,
{
    type Output = Self;
    #[inline(always)]
    fn add(self, rhs: &Self) -> Self {
        Part::sum(&self, rhs, &T::one())
    }
}

impl<T: DualNum<F>, F, R: Dim, C: Dim> Sub<&Part<T, F, R, C>> for Part<T, F, R, C>
where
    DefaultAllocator: Allocator<R, C>,
{
    type Output = Self;
    #[inline(always)]
    fn sub(self, rhs: &Self) -> Self {
        Part::sum(&self, rhs, &-T::one())
    }
}

impl<T: DualNum<F>, F, R: Dim, C: Dim> AddAssign for Part<T, F, R, C>
where
    DefaultAllocator: Allocator<R, C>,
{
    #[inline(always)]
    fn add_assign(&mut self, rhs: Self) {
        self.axpy(&T::one(), &rhs);
    }
}

impl<T: DualNum<F>, F, R: Dim, C: Dim> SubAssign for Part<T, F, R, C>
where
    DefaultAllocator: Allocator<R, C>,
{
    #[inline(always)]
    fn sub_assign(&mut self, rhs: Self) {
        self.axpy(&-T::one(), &rhs);
    }
}

impl<T: DualNum<F>, F, R: Dim, C: Dim> Neg for Part<T, F, R, C>
where
    DefaultAllocator: Allocator<R, C>,
{
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Part(self.0.map(|a| -a), PhantomData)
    }
}

impl<T: DualNum<F>, F, R: Dim, C: Dim> MulAssign<T> for Part<T, F, R, C>
where
    DefaultAllocator: Allocator<R, C>,
{
    #[inline(always)]
    fn mul_assign(&mut self, rhs: T) {
        *self = Part::scale(self, &rhs);
    }
}

impl<T: DualNum<F>, F, R: Dim, C: Dim> DivAssign<T> for Part<T, F, R, C>
where
    DefaultAllocator: Allocator<R, C>,
{
    #[inline(always)]
    fn div_assign(&mut self, rhs: T) {
        *self = Part::scale(self, &rhs.recip());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Const, SMatrix};

    type Row<const N: usize> = Part<f64, f64, U1, Const<N>>;
    type Square<const N: usize> = Part<f64, f64, Const<N>, Const<N>>;

    /// The dense reference: m + α (u vᵀ + v uᵀ), entry (i, j) rounded as u_i (α v_j) + v_i (α u_j).
    fn dense<const N: usize>(
        m: &SMatrix<f64, N, N>,
        a: f64,
        u: &[f64; N],
        v: &[f64; N],
    ) -> SMatrix<f64, N, N> {
        SMatrix::from_fn(|i, j| m[(i, j)] + (u[i] * (a * v[j]) + v[i] * (a * u[j])))
    }

    fn row<const N: usize>(x: [f64; N]) -> Row<N> {
        Part::some(SMatrix::<f64, 1, N>::from_row_slice(&x))
    }

    /// Sparse gradients (a prefix, a suffix, interior zeros) give the same Hessian update as the dense
    /// outer product, exactly: the skipped columns are those where both u and v vanish.
    #[test]
    fn ad_vs_hand_sym_outer_on_nonzero_columns_equals_dense() {
        let start = SMatrix::<f64, 7, 7>::from_fn(|i, j| 0.1 * (i + j) as f64);
        let cases: [([f64; 7], [f64; 7]); 4] = [
            (
                [1.0, -2.0, 0.5, 0.0, 0.0, 0.0, 0.0],
                [0.3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            ),
            (
                [0.0, 0.0, 0.0, 0.0, 1.5, 0.0, -1.0],
                [0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.7],
            ),
            (
                [0.9, 0.0, 0.0, 0.0, 0.0, 0.0, 0.4],
                [0.9, 0.0, 0.0, 0.0, 0.0, 0.0, 0.4],
            ),
            ([0.0; 7], [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]),
        ];
        for (u, v) in cases {
            let mut m: Square<7> = Part::some(start);
            m.sym_outer(&0.75, &row(u), &row(v));
            assert_eq!(
                m.matrix(Const::<7>),
                dense(&start, 0.75, &u, &v),
                "u = {u:?}, v = {v:?}"
            );
            // Into an absent (zero) part.
            let mut z: Square<7> = Part::none();
            z.sym_outer(&0.75, &row(u), &row(v));
            assert_eq!(z.matrix(Const::<7>), dense(&SMatrix::zeros(), 0.75, &u, &v));
        }
    }

    /// A NaN in a gradient reaches the Hessian (it is not mistaken for a zero entry).
    #[test]
    fn regress_sym_outer_keeps_nan_entries() {
        let mut u = [0.0; 6];
        u[3] = f64::NAN;
        let mut m: Square<6> = Part::none();
        m.sym_outer(&1.0, &row(u), &row(u));
        assert!(m.matrix(Const::<6>)[(3, 3)].is_nan());
    }
}
