//! A forward dual number for gradients whose derivative part is always present: value and ∂/∂x for
//! `D` variables as a plain vector.
//!
//! num-dual's `DualVec` keeps its derivative part as an `Option` so that constants cost nothing. For
//! the small gradients of the right-hand sides integrators call millions of times, the branch on that
//! `Option` in every operation costs more than the arithmetic: it bloats each operation, so the
//! model is no longer inlined into the kernel and its arguments travel through memory. For the
//! 2-dof Hénon-Heiles potential a gradient took 23 ns with `DualSVec64<2>` against 3.3 ns for two
//! passes with the scalar `Dual64` (`--bench rates`, docs/benchmarks.md). [`GradJet`] has the layout
//! of two `Dual64`s side by side: a constant carries a zero vector, and every operation is straight
//! fixed-length arithmetic the compiler unrolls.
//!
//! ```text
//! (a, ∇a) · (b, ∇b) = (a b, b ∇a + a ∇b),     g(a, ∇a) = (g(a), g′(a) ∇a).
//! ```
//!
//! A flag records whether the gradient is structurally zero (the value depends on no variable: a
//! constant, or a function of constants only). Such a gradient is never multiplied, so an infinite or
//! NaN factor cannot poison it: the semantics of num-dual's `None` derivative, kept. For L = ½q̇² − √q
//! at q = 0 the momentum is q̇ (q is a constant there), not NaN from 0·∞. A gradient that is zero only
//! numerically (x² at x = 0) is multiplied as usual, so a singular derivative of a variable still
//! shows as NaN (−1/|q| at q = 0) instead of a silent finite force.
//!
//! The number-type boilerplate comes from num-dual's exported macros, as for
//! [`LagrangeJet`](super::LagrangeJet).

use crate::Scalar;
use nalgebra::allocator::Allocator;
use nalgebra::{DefaultAllocator, Dim, OVector};
use num_dual::{chain_rule, first, second, third, zeroth};
use num_dual::{
    impl_comparisons, impl_dual_struct, impl_float_const, impl_from_f, impl_from_primitive, impl_inv,
    impl_iterator, impl_num, impl_signed, impl_zero_one,
};
use num_dual::{DualNum, DualNumFloat, DualStruct};
use num_traits::{Float, FloatConst, FromPrimitive, Inv, Num, One, Signed, Zero};
use std::fmt;
use std::iter::{Product, Sum};
use std::marker::PhantomData;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign};

/// Value and gradient with respect to `D` variables: forward mode with a dense gradient part, whose
/// structurally zero gradients (constants) are never multiplied, so that an infinite factor cannot
/// poison them.
#[derive(Clone, Debug)]
pub struct GradJet<T: DualNum<F>, F, D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    /// Value.
    pub re: T,
    /// Gradient.
    pub eps: OVector<T, D>,
    /// `false` while the gradient is structurally zero (see the module documentation).
    pub active: bool,
    f: PhantomData<F>,
}

impl<T: DualNum<F> + Copy, F: Copy, const N: usize> Copy for GradJet<T, F, nalgebra::Const<N>> {}

/// The gradient jet over f64 for `N` variables.
pub type GradJet64<const N: usize> = GradJet<f64, f64, nalgebra::Const<N>>;

impl<T: DualNum<F>, F, D: Dim> GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    /// A jet from its value and gradient, which may be non-zero.
    #[inline(always)]
    pub fn new(re: T, eps: OVector<T, D>) -> Self {
        Self::with_flag(re, eps, true)
    }

    #[inline(always)]
    fn with_flag(re: T, eps: OVector<T, D>, active: bool) -> Self {
        GradJet {
            re,
            eps,
            active,
            f: PhantomData,
        }
    }
}

impl<T: DualNum<F>, F, D: Dim> GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    /// A constant (zero gradient). The length of the gradient is the static dimension `D`; a jet is
    /// only ever built with a static one (`GradJet64<N>`), a dynamic `D` gives an empty gradient.
    #[inline(always)]
    pub fn from_re(re: T) -> Self {
        let d = D::from_usize(D::try_to_usize().unwrap_or(0));
        let zero = OVector::<T, D>::from_element_generic(d, nalgebra::U1, T::zero());
        Self::with_flag(re, zero, false)
    }

    /// The variable with index `i < D`: value `re`, gradient the unit vector eᵢ.
    #[inline(always)]
    pub fn variable(re: T, i: usize) -> Self {
        let mut d = Self::from_re(re);
        d.eps[i] = T::one();
        d.active = true;
        d
    }
}

impl<T: DualNum<F>, F: Float, D: Dim> GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    /// g(a) from g(a.re) and g′(a.re).
    #[inline(always)]
    fn chain_rule(&self, f0: T, f1: T) -> Self {
        let active = self.active;
        let eps = self.eps.map(|e| if active { e * f1.clone() } else { e });
        Self::with_flag(f0, eps, active)
    }

    /// α ∇a + β ∇b over the active gradients only: an inactive gradient is left out, not multiplied
    /// (written as selects per entry, which compile without branches).
    #[inline(always)]
    fn lin(a: &Self, alpha: T, b: &Self, beta: T) -> (OVector<T, D>, bool) {
        let (ua, ub) = (a.active, b.active);
        let eps = a.eps.zip_map(&b.eps, |x, y| {
            let xa = if ua { x * alpha.clone() } else { T::zero() };
            let yb = if ub { y * beta.clone() } else { T::zero() };
            xa + yb
        });
        (eps, ua || ub)
    }
}

// The product and quotient rules use the other operators by nature.
#[allow(clippy::suspicious_arithmetic_impl)]
impl<T: DualNum<F>, F: Float, D: Dim> Mul<&GradJet<T, F, D>> for &GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    type Output = GradJet<T, F, D>;
    #[inline(always)]
    fn mul(self, o: &GradJet<T, F, D>) -> GradJet<T, F, D> {
        let (eps, active) = GradJet::lin(self, o.re.clone(), o, self.re.clone());
        GradJet::with_flag(self.re.clone() * o.re.clone(), eps, active)
    }
}

#[allow(clippy::suspicious_arithmetic_impl)]
impl<T: DualNum<F>, F: Float, D: Dim> Div<&GradJet<T, F, D>> for &GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    type Output = GradJet<T, F, D>;
    #[inline(always)]
    fn div(self, o: &GradJet<T, F, D>) -> GradJet<T, F, D> {
        // (a/b)′ = a′/b − b′·(a/b)/b.
        let inv = o.re.recip();
        let q = self.re.clone() * inv.clone();
        let (eps, active) = GradJet::lin(self, inv.clone(), o, -(q.clone() * inv));
        GradJet::with_flag(q, eps, active)
    }
}

impl<T: DualNum<F>, F: Float, D: Dim> Add<&GradJet<T, F, D>> for &GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    type Output = GradJet<T, F, D>;
    #[inline(always)]
    fn add(self, o: &GradJet<T, F, D>) -> GradJet<T, F, D> {
        let (eps, active) = GradJet::lin(self, T::one(), o, T::one());
        GradJet::with_flag(self.re.clone() + o.re.clone(), eps, active)
    }
}

impl<T: DualNum<F>, F: Float, D: Dim> Sub<&GradJet<T, F, D>> for &GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    type Output = GradJet<T, F, D>;
    #[inline(always)]
    fn sub(self, o: &GradJet<T, F, D>) -> GradJet<T, F, D> {
        let (eps, active) = GradJet::lin(self, T::one(), o, -T::one());
        GradJet::with_flag(self.re.clone() - o.re.clone(), eps, active)
    }
}

impl<T: DualNum<F>, F: Float, D: Dim> Neg for &GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    type Output = GradJet<T, F, D>;
    #[inline(always)]
    fn neg(self) -> GradJet<T, F, D> {
        GradJet::with_flag(-self.re.clone(), self.eps.map(|e| -e), self.active)
    }
}

impl<T: DualNum<F>, F: Float, D: Dim> Neg for GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    type Output = GradJet<T, F, D>;
    #[inline(always)]
    fn neg(self) -> GradJet<T, F, D> {
        -&self
    }
}

/// The compound assignments, through the binary operators (so that the flag follows).
macro_rules! assign_op {
    ($trt:ident, $mth:ident, $op:tt) => {
        impl<T: DualNum<F>, F: Float, D: Dim> $trt for GradJet<T, F, D>
        where
            DefaultAllocator: Allocator<D>,
        {
            #[inline(always)]
            fn $mth(&mut self, o: Self) {
                *self = &*self $op &o;
            }
        }
    };
}

assign_op!(AddAssign, add_assign, +);
assign_op!(SubAssign, sub_assign, -);
assign_op!(MulAssign, mul_assign, *);
assign_op!(DivAssign, div_assign, /);

impl<T: DualNum<F>, F, D: Dim> RemAssign for GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    fn rem_assign(&mut self, _o: Self) {
        unimplemented!("remainder of a dual number")
    }
}

impl<T: DualNum<F>, F, D: Dim> Rem<&GradJet<T, F, D>> for &GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    type Output = GradJet<T, F, D>;
    fn rem(self, _o: &GradJet<T, F, D>) -> GradJet<T, F, D> {
        unimplemented!("remainder of a dual number")
    }
}

/// The by-value forms of a binary operator, forwarded to the by-reference one and forced inline.
macro_rules! forward_binop {
    ($trt:ident, $mth:ident) => {
        impl<T: DualNum<F>, F: Float, D: Dim> $trt<GradJet<T, F, D>> for &GradJet<T, F, D>
        where
            DefaultAllocator: Allocator<D>,
        {
            type Output = GradJet<T, F, D>;
            #[inline(always)]
            fn $mth(self, o: GradJet<T, F, D>) -> GradJet<T, F, D> {
                self.$mth(&o)
            }
        }
        impl<T: DualNum<F>, F: Float, D: Dim> $trt<&GradJet<T, F, D>> for GradJet<T, F, D>
        where
            DefaultAllocator: Allocator<D>,
        {
            type Output = GradJet<T, F, D>;
            #[inline(always)]
            fn $mth(self, o: &GradJet<T, F, D>) -> GradJet<T, F, D> {
                (&self).$mth(o)
            }
        }
        impl<T: DualNum<F>, F: Float, D: Dim> $trt for GradJet<T, F, D>
        where
            DefaultAllocator: Allocator<D>,
        {
            type Output = GradJet<T, F, D>;
            #[inline(always)]
            fn $mth(self, o: GradJet<T, F, D>) -> GradJet<T, F, D> {
                (&self).$mth(&o)
            }
        }
    };
}

forward_binop!(Add, add);
forward_binop!(Sub, sub);
forward_binop!(Mul, mul);
forward_binop!(Div, div);
forward_binop!(Rem, rem);

impl<T: DualNum<F>, F: fmt::Display, D: Dim> fmt::Display for GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "{} + {:?}ε", self.re, self.eps.as_slice())
    }
}

crate::ad::derivatives::jet_derivatives!(first, 1, GradJet, [eps], [D], [D]);
impl_from_f!(GradJet, [eps], [D], [D]);
impl_zero_one!(GradJet, [D], [D]);

/// Arithmetic with a plain number c, written out rather than taken from num-dual's macro for two
/// reasons: a structurally zero gradient is left alone (not multiplied by c, which may be infinite),
/// and a division scales the gradient by 1/c, one reciprocal and multiplies instead of a division per
/// entry. The value is still divided, so f64 and the jet agree on it; the gradient is within an
/// ulp of the quotient's. A model's `x / 3.0` then costs one multiply per entry (Hénon-Heiles'
/// −y³/3 put a 13-cycle division on every stage of a Kahan-Li step; `--bench rates`,
/// docs/benchmarks.md).
macro_rules! scalar_op {
    ($trt:ident, $mth:ident, $atrt:ident, $amth:ident, |$s:ident, $c:ident| $body:block) => {
        impl<T: DualNum<F>, F: DualNumFloat, D: Dim> $atrt<F> for GradJet<T, F, D>
        where
            DefaultAllocator: Allocator<D>,
        {
            #[inline(always)]
            fn $amth(&mut self, $c: F) {
                let $s = self;
                $body
            }
        }
        impl<T: DualNum<F>, F: DualNumFloat, D: Dim> $trt<F> for GradJet<T, F, D>
        where
            DefaultAllocator: Allocator<D>,
        {
            type Output = Self;
            #[inline(always)]
            fn $mth(mut self, c: F) -> Self {
                self.$amth(c);
                self
            }
        }
    };
}

scalar_op!(Add, add, AddAssign, add_assign, |s, c| {
    s.re += c;
});
scalar_op!(Sub, sub, SubAssign, sub_assign, |s, c| {
    s.re -= c;
});
scalar_op!(Mul, mul, MulAssign, mul_assign, |s, c| {
    s.re *= c;
    if s.active {
        s.eps *= T::from(c);
    }
});
scalar_op!(Div, div, DivAssign, div_assign, |s, c| {
    s.re /= c;
    if s.active {
        s.eps *= T::from(F::one() / c);
    }
});
scalar_op!(Rem, rem, RemAssign, rem_assign, |_s, _c| {
    unimplemented!("remainder of a dual number")
});
impl_inv!(GradJet, [D], [D]);
impl_iterator!(GradJet, [D], [D]);
impl_from_primitive!(GradJet, [D], [D]);
impl_signed!(GradJet, [D], [D]);
impl_num!(GradJet, [D], [D]);
impl_float_const!(GradJet, [D], [D]);
impl_dual_struct!(GradJet, [D], [D]);
impl_comparisons!(GradJet, [D], [D]);

// Compile-time check that the jet is a `Scalar` (a model can be evaluated with it).
const _: fn() = || {
    fn is_scalar<S: Scalar>() {}
    is_scalar::<GradJet64<2>>();
};

#[cfg(test)]
mod tests {
    use super::GradJet64;

    /// Arithmetic with a plain number: x/c scales the gradient by the rounded 1/c (within an ulp of
    /// the quotient 1/c itself, here equal to it), x·c by c, x ± c leaves it; a constant's gradient
    /// stays structurally zero even when c is infinite or c = 0 is divided by (no 0·∞ = NaN).
    #[test]
    fn scalar_operations_on_the_gradient() {
        let x = GradJet64::<2>::variable(0.7, 0);
        let q = x / 3.0;
        assert_eq!((q.re, q.eps[0], q.eps[1]), (0.7 / 3.0, 1.0 / 3.0, 0.0));
        let p = x * 3.0 + 1.0 - 2.0;
        assert_eq!((p.re, p.eps[0], p.eps[1]), (0.7 * 3.0 + 1.0 - 2.0, 3.0, 0.0));
        let c = GradJet64::<2>::from_re(2.0);
        for d in [c * f64::INFINITY, c / 0.0] {
            assert!(
                d.re.is_infinite() && !d.active && d.eps.iter().all(|e| *e == 0.0),
                "{d}"
            );
        }
        // A variable's gradient is still multiplied: d(x·∞) is infinite, not hidden.
        assert!((x * f64::INFINITY).eps[0].is_infinite());
    }
}
