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
//! The jet is NaN-safe in the sense of ForwardDiff's `NANSAFE_MODE`: a gradient entry that is zero
//! stays zero when it is multiplied by a factor that is infinite or NaN. A variable that does not
//! reach a term therefore cannot poison it (issue 15, case 8): for L = ½q̇² − √q at q = 0 the
//! momentum is q̇, not NaN from 0·∞, and V = (q²)^¾ has V′(0) = 0 (the chain rule gives
//! ¾(q²)^(−¼)·2q = ∞·0 there).
//!
//! The number-type boilerplate comes from num-dual's exported macros, as for
//! [`LagrangeJet`](super::LagrangeJet).

use crate::Scalar;
use nalgebra::allocator::Allocator;
use nalgebra::{DefaultAllocator, Dim, OVector};
use num_dual::{chain_rule, first, second, third, zeroth};
use num_dual::{
    impl_assign_ops, impl_comparisons, impl_derivatives, impl_dual_struct, impl_first_derivatives,
    impl_float_const, impl_from_f, impl_from_primitive, impl_inv, impl_iterator, impl_neg, impl_num,
    impl_scalar_op, impl_signed, impl_zero_one,
};
use num_dual::{DualNum, DualNumFloat, DualStruct};
use num_traits::{Float, FloatConst, FromPrimitive, Inv, Num, One, Signed, Zero};
use std::fmt;
use std::iter::{Product, Sum};
use std::marker::PhantomData;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign};

/// Value and gradient with respect to `D` variables, the derivative part always present (the design
/// notes are in the private module `ad::grad`, in the source).
#[derive(Clone, Debug)]
pub struct GradJet<T: DualNum<F>, F, D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    /// Value.
    pub re: T,
    /// Gradient.
    pub eps: OVector<T, D>,
    f: PhantomData<F>,
}

impl<T: DualNum<F> + Copy, F: Copy, const N: usize> Copy for GradJet<T, F, nalgebra::Const<N>> {}

/// The gradient jet over f64 for `N` variables.
pub type GradJet64<const N: usize> = GradJet<f64, f64, nalgebra::Const<N>>;

impl<T: DualNum<F>, F, D: Dim> GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    /// A jet from its value and gradient.
    #[inline(always)]
    pub fn new(re: T, eps: OVector<T, D>) -> Self {
        GradJet {
            re,
            eps,
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
        Self::new(
            re,
            OVector::<T, D>::from_element_generic(d, nalgebra::U1, T::zero()),
        )
    }

    /// The variable with index `i < D`: value `re`, gradient the unit vector eᵢ.
    #[inline(always)]
    pub fn variable(re: T, i: usize) -> Self {
        let mut d = Self::from_re(re);
        d.eps[i] = T::one();
        d
    }
}

/// e·f, but 0 when e = 0 whatever f is (NaN-safe: see the module documentation).
#[inline(always)]
fn scale<T: Zero + Mul<Output = T>>(e: T, f: T) -> T {
    if e.is_zero() {
        e
    } else {
        e * f
    }
}

impl<T: DualNum<F>, F: Float, D: Dim> GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    /// g(a) from g(a.re) and g′(a.re).
    #[inline(always)]
    fn chain_rule(&self, f0: T, f1: T) -> Self {
        Self::new(f0, self.eps.map(|e| scale(e, f1.clone())))
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
        let (a, b) = (self.re.clone(), o.re.clone());
        GradJet::new(
            a.clone() * b.clone(),
            self.eps
                .zip_map(&o.eps, |x, y| scale(x, b.clone()) + scale(y, a.clone())),
        )
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
        let inv = o.re.recip();
        let q = self.re.clone() * inv.clone();
        GradJet::new(
            q.clone(),
            self.eps
                .zip_map(&o.eps, |x, y| scale(x - scale(y, q.clone()), inv.clone())),
        )
    }
}

impl<T: DualNum<F>, F: Float, D: Dim> Add<&GradJet<T, F, D>> for &GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    type Output = GradJet<T, F, D>;
    #[inline(always)]
    fn add(self, o: &GradJet<T, F, D>) -> GradJet<T, F, D> {
        GradJet::new(
            self.re.clone() + o.re.clone(),
            self.eps.zip_map(&o.eps, |x, y| x + y),
        )
    }
}

impl<T: DualNum<F>, F: Float, D: Dim> Sub<&GradJet<T, F, D>> for &GradJet<T, F, D>
where
    DefaultAllocator: Allocator<D>,
{
    type Output = GradJet<T, F, D>;
    #[inline(always)]
    fn sub(self, o: &GradJet<T, F, D>) -> GradJet<T, F, D> {
        GradJet::new(
            self.re.clone() - o.re.clone(),
            self.eps.zip_map(&o.eps, |x, y| x - y),
        )
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

impl_first_derivatives!(GradJet, [eps], [D], [D]);
impl_from_f!(GradJet, [eps], [D], [D]);
impl_zero_one!(GradJet, [D], [D]);
impl_neg!(GradJet, [eps], [D], [D]);
impl_assign_ops!(GradJet, [eps], [D], [D]);
impl_scalar_op!(GradJet, [eps], [D], [D]);
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
