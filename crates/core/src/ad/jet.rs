//! A dual number that carries, in one evaluation of L(t, q, q̇), every derivative Lagrange's equations
//! need — and nothing else.
//!
//! L is evaluated at (t + s, q + s·q̇ + x, q̇ + w) around s = 0, x = 0, w = 0, truncated to
//!
//! ```text
//! L + ∇ₓL·x + ∂ₛL s + ∇_wL·w + s (∂²L/∂s∂w)·w + ½ wᵀ (∂²L/∂w²) w
//! ```
//!
//! so that one evaluation yields ∂L/∂q (`gx`), the momenta ∂L/∂q̇ (`gw`), the mixed term
//! (∂²L/∂q̇∂q)·q̇ + ∂²L/∂q̇∂t (`hsw`, a Hessian-vector product) and the mass matrix ∂²L/∂q̇² (`hww`).
//! Compared with three separate evaluations (gradient, directional derivative, Hessian), every
//! transcendental function of the model is computed once, and the second-order parts exist only
//! where the model needs them: each part is `None` until an operation makes it non-zero (a function
//! of q alone never carries a w-part, a term linear in q̇ never carries a Hessian).
//!
//! The number-type boilerplate (conversions, assignment operators, `DualNum` and its elementary
//! functions) comes from num-dual's exported macros; the product, quotient and chain rules are
//! written here as fused loops.

use crate::Scalar;
use nalgebra::allocator::Allocator;
use nalgebra::{DefaultAllocator, Dim, U1};
use num_dual::{chain_rule, first, second, third, zeroth};
use num_dual::{
    impl_assign_ops, impl_comparisons, impl_dual_struct, impl_float_const, impl_from_f, impl_from_primitive,
    impl_inv, impl_iterator, impl_neg, impl_num, impl_signed, impl_zero_one,
};
use num_dual::{DualNum, DualNumFloat, DualStruct};
use num_traits::{Float, FloatConst, FromPrimitive, Inv, Num, One, Signed, Zero};
use std::fmt;
use std::iter::{Product, Sum};
use std::marker::PhantomData;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign};

mod part;

pub use part::Part;

/// The Lagrange jet: value, ∂/∂x (first order), ∂/∂s, ∂/∂w, ∂²/∂s∂w and ∂²/∂w² of a scalar (see the
/// module documentation). `D` is the number of degrees of freedom.
#[derive(Clone, Debug)]
pub struct LagrangeJet<T: DualNum<F>, F, D: Dim>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
{
    /// Value.
    pub re: T,
    /// ∂/∂x: the gradient in q (first order only).
    pub gx: Part<T, F, U1, D>,
    /// ∂/∂s: the derivative along the flow direction (δt, δq) = (1, q̇).
    pub gs: T,
    /// ∂/∂w: the gradient in q̇.
    pub gw: Part<T, F, U1, D>,
    /// ∂²/∂s∂w: the mixed term (∂²L/∂q̇∂q)·q̇ + ∂²L/∂q̇∂t.
    pub hsw: Part<T, F, U1, D>,
    /// ∂²/∂w²: the Hessian in q̇ (the mass matrix).
    pub hww: Part<T, F, D, D>,
    f: PhantomData<F>,
}

impl<T: DualNum<F> + Copy, F: Copy, const N: usize> Copy for LagrangeJet<T, F, nalgebra::Const<N>> {}

/// The jet over f64 with `N` degrees of freedom.
pub type LagrangeJet64<const N: usize> = LagrangeJet<f64, f64, nalgebra::Const<N>>;

impl<T: DualNum<F>, F, D: Dim> LagrangeJet<T, F, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
{
    /// A jet from its parts.
    #[inline(always)]
    pub fn new(
        re: T,
        gx: Part<T, F, U1, D>,
        gs: T,
        gw: Part<T, F, U1, D>,
        hsw: Part<T, F, U1, D>,
        hww: Part<T, F, D, D>,
    ) -> Self {
        LagrangeJet {
            re,
            gx,
            gs,
            gw,
            hsw,
            hww,
            f: PhantomData,
        }
    }

    /// A constant.
    #[inline(always)]
    pub fn from_re(re: T) -> Self {
        Self::new(
            re,
            Part::none(),
            T::zero(),
            Part::none(),
            Part::none(),
            Part::none(),
        )
    }
}

impl<T: DualNum<F>, F: Float, D: Dim> LagrangeJet<T, F, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
{
    /// g(a) from g(a.re), g'(a.re), g''(a.re).
    #[inline(always)]
    fn chain_rule(&self, f0: T, f1: T, f2: T) -> Self {
        let mut hsw = Part::scale(&self.hsw, &f1);
        hsw.axpy(&(f2.clone() * self.gs.clone()), &self.gw);
        let mut hww = Part::scale(&self.hww, &f1);
        hww.sym_outer(&(f2 * F::from(0.5).unwrap()), &self.gw, &self.gw);
        Self::new(
            f0,
            Part::scale(&self.gx, &f1),
            self.gs.clone() * f1.clone(),
            Part::scale(&self.gw, &f1),
            hsw,
            hww,
        )
    }
}

impl<T: DualNum<F>, F: Float, D: Dim> LagrangeJet<T, F, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
{
    /// Product rule, second-order terms only between s and w.
    #[inline(always)]
    fn mul_ref(&self, o: &Self) -> Self {
        let (a, b) = (self, o);
        let mut hsw = Part::lin(&a.hsw, &b.re, &b.hsw, &a.re);
        hsw.axpy(&a.gs, &b.gw);
        hsw.axpy(&b.gs, &a.gw);
        let mut hww = Part::lin(&a.hww, &b.re, &b.hww, &a.re);
        hww.sym_outer(&T::one(), &a.gw, &b.gw);
        LagrangeJet::new(
            a.re.clone() * b.re.clone(),
            Part::lin(&a.gx, &b.re, &b.gx, &a.re),
            a.gs.clone() * b.re.clone() + b.gs.clone() * a.re.clone(),
            Part::lin(&a.gw, &b.re, &b.gw, &a.re),
            hsw,
            hww,
        )
    }

    /// a / b = a · (1/b), with 1/b by the chain rule.
    #[inline(always)]
    fn div_ref(&self, o: &Self) -> Self {
        let rec = o.re.recip();
        let f1 = -rec.clone() * rec.clone();
        let f2 = f1.clone() * rec.clone() * F::from(-2.0).unwrap();
        self.mul_ref(&o.chain_rule(rec, f1, f2))
    }

    #[inline(always)]
    fn add_ref(&self, o: &Self) -> Self {
        let one = T::one();
        Self::new(
            self.re.clone() + o.re.clone(),
            Part::sum(&self.gx, &o.gx, &one),
            self.gs.clone() + o.gs.clone(),
            Part::sum(&self.gw, &o.gw, &one),
            Part::sum(&self.hsw, &o.hsw, &one),
            Part::sum(&self.hww, &o.hww, &one),
        )
    }

    #[inline(always)]
    fn sub_ref(&self, o: &Self) -> Self {
        let m1 = -T::one();
        Self::new(
            self.re.clone() - o.re.clone(),
            Part::sum(&self.gx, &o.gx, &m1),
            self.gs.clone() - o.gs.clone(),
            Part::sum(&self.gw, &o.gw, &m1),
            Part::sum(&self.hsw, &o.hsw, &m1),
            Part::sum(&self.hww, &o.hww, &m1),
        )
    }

    #[inline(always)]
    fn scale_by(&self, f: &T) -> Self {
        Self::new(
            self.re.clone() * f.clone(),
            Part::scale(&self.gx, f),
            self.gs.clone() * f.clone(),
            Part::scale(&self.gw, f),
            Part::scale(&self.hsw, f),
            Part::scale(&self.hww, f),
        )
    }
}

/// The four reference/value combinations of a binary operator, all forced inline so that the
/// compiler sees through the `None` parts of a model's straight-line code.
macro_rules! jet_binop {
    ($trt:ident, $mth:ident, $imp:ident) => {
        impl<T: DualNum<F>, F: Float, D: Dim> $trt<&LagrangeJet<T, F, D>> for &LagrangeJet<T, F, D>
        where
            DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
        {
            type Output = LagrangeJet<T, F, D>;
            #[inline(always)]
            fn $mth(self, o: &LagrangeJet<T, F, D>) -> LagrangeJet<T, F, D> {
                self.$imp(o)
            }
        }
        impl<T: DualNum<F>, F: Float, D: Dim> $trt<LagrangeJet<T, F, D>> for &LagrangeJet<T, F, D>
        where
            DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
        {
            type Output = LagrangeJet<T, F, D>;
            #[inline(always)]
            fn $mth(self, o: LagrangeJet<T, F, D>) -> LagrangeJet<T, F, D> {
                self.$imp(&o)
            }
        }
        impl<T: DualNum<F>, F: Float, D: Dim> $trt<&LagrangeJet<T, F, D>> for LagrangeJet<T, F, D>
        where
            DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
        {
            type Output = LagrangeJet<T, F, D>;
            #[inline(always)]
            fn $mth(self, o: &LagrangeJet<T, F, D>) -> LagrangeJet<T, F, D> {
                self.$imp(o)
            }
        }
        impl<T: DualNum<F>, F: Float, D: Dim> $trt for LagrangeJet<T, F, D>
        where
            DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
        {
            type Output = LagrangeJet<T, F, D>;
            #[inline(always)]
            fn $mth(self, o: LagrangeJet<T, F, D>) -> LagrangeJet<T, F, D> {
                self.$imp(&o)
            }
        }
    };
}

jet_binop!(Add, add, add_ref);
jet_binop!(Sub, sub, sub_ref);
jet_binop!(Mul, mul, mul_ref);
jet_binop!(Div, div, div_ref);

impl<T: DualNum<F>, F, D: Dim> Rem<&LagrangeJet<T, F, D>> for &LagrangeJet<T, F, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
{
    type Output = LagrangeJet<T, F, D>;
    fn rem(self, _o: &LagrangeJet<T, F, D>) -> LagrangeJet<T, F, D> {
        unimplemented!("remainder of a dual number")
    }
}
impl<T: DualNum<F>, F, D: Dim> Rem<LagrangeJet<T, F, D>> for &LagrangeJet<T, F, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
{
    type Output = LagrangeJet<T, F, D>;
    fn rem(self, _o: LagrangeJet<T, F, D>) -> LagrangeJet<T, F, D> {
        unimplemented!("remainder of a dual number")
    }
}
impl<T: DualNum<F>, F, D: Dim> Rem<&LagrangeJet<T, F, D>> for LagrangeJet<T, F, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
{
    type Output = LagrangeJet<T, F, D>;
    fn rem(self, _o: &LagrangeJet<T, F, D>) -> LagrangeJet<T, F, D> {
        unimplemented!("remainder of a dual number")
    }
}
impl<T: DualNum<F>, F, D: Dim> Rem for LagrangeJet<T, F, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
{
    type Output = LagrangeJet<T, F, D>;
    fn rem(self, _o: LagrangeJet<T, F, D>) -> LagrangeJet<T, F, D> {
        unimplemented!("remainder of a dual number")
    }
}

/// Operations with a real number `F`.
macro_rules! jet_scalar_op {
    ($trt:ident, $mth:ident, $atrt:ident, $amth:ident, |$a:ident, $f:ident| $body:expr) => {
        impl<T: DualNum<F>, F: DualNumFloat, D: Dim> $trt<F> for LagrangeJet<T, F, D>
        where
            DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
        {
            type Output = Self;
            #[inline(always)]
            fn $mth(self, $f: F) -> Self {
                let $a = self;
                $body
            }
        }
        impl<T: DualNum<F>, F: DualNumFloat, D: Dim> $atrt<F> for LagrangeJet<T, F, D>
        where
            DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
        {
            #[inline(always)]
            fn $amth(&mut self, $f: F) {
                let $a = self.clone();
                *self = $body;
            }
        }
    };
}

jet_scalar_op!(Mul, mul, MulAssign, mul_assign, |a, f| a.scale_by(&T::from(f)));
jet_scalar_op!(Div, div, DivAssign, div_assign, |a, f| a
    .scale_by(&T::from(f.recip())));
jet_scalar_op!(Add, add, AddAssign, add_assign, |a, f| {
    let mut a = a;
    a.re += f;
    a
});
jet_scalar_op!(Sub, sub, SubAssign, sub_assign, |a, f| {
    let mut a = a;
    a.re -= f;
    a
});

impl<T: DualNum<F>, F, D: Dim> Rem<F> for LagrangeJet<T, F, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
{
    type Output = Self;
    fn rem(self, _f: F) -> Self {
        unimplemented!("remainder of a dual number")
    }
}
impl<T: DualNum<F>, F, D: Dim> RemAssign<F> for LagrangeJet<T, F, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
{
    fn rem_assign(&mut self, _f: F) {
        unimplemented!("remainder of a dual number")
    }
}

impl<T: DualNum<F>, F: fmt::Display, D: Dim> fmt::Display for LagrangeJet<T, F, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
{
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "{} + {}ε_s + …", self.re, self.gs)
    }
}

crate::ad::derivatives::jet_derivatives!(
    second,
    2,
    LagrangeJet,
    [gx, gs, gw, hsw, hww],
    [D],
    [U1, D],
    [D, D]
);
impl_from_f!(LagrangeJet, [gx, gs, gw, hsw, hww], [D], [U1, D], [D, D]);
impl_zero_one!(LagrangeJet, [D], [U1, D], [D, D]);
impl_neg!(LagrangeJet, [gx, gs, gw, hsw, hww], [D], [U1, D], [D, D]);
impl_assign_ops!(LagrangeJet, [gx, gs, gw, hsw, hww], [D], [U1, D], [D, D]);
impl_inv!(LagrangeJet, [D], [U1, D], [D, D]);
impl_iterator!(LagrangeJet, [D], [U1, D], [D, D]);
impl_from_primitive!(LagrangeJet, [D], [U1, D], [D, D]);
impl_signed!(LagrangeJet, [D], [U1, D], [D, D]);
impl_num!(LagrangeJet, [D], [U1, D], [D, D]);
impl_float_const!(LagrangeJet, [D], [U1, D], [D, D]);
impl_dual_struct!(LagrangeJet, [D], [U1, D], [D, D]);
impl_comparisons!(LagrangeJet, [D], [U1, D], [D, D]);

// Compile-time check that the jet is a `Scalar` (a model can be evaluated with it).
const _: fn() = || {
    fn is_scalar<S: Scalar>() {}
    is_scalar::<LagrangeJet64<3>>();
};
