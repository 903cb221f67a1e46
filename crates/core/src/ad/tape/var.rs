//! The recording scalar of the [tape](super): a value and the handle of its node, with the
//! number-type boilerplate of num-dual.
//!
//! The elementary functions come from num-dual's `impl_second_derivatives!` (with `powf` at 0 fixed,
//! `ad/derivatives.rs`) through
//! [`Taped::chain_rule`] (one recorded unary operation with φ', φ''); the four arithmetic operators
//! record binary operations with their partials. Adding a constant keeps the node (d(a + c) = da), so
//! offsets cost nothing on the tape.

use super::{record, SINK};
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

/// Where a node's gradient in q̇ lives on the tape: entries `off..off + (hi − lo)` of the gradient
/// store hold ∂/∂q̇_lo … ∂/∂q̇_(hi−1); every other component is zero. Empty when `lo == hi`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Span {
    pub off: u32,
    pub lo: u32,
    pub hi: u32,
}

impl Span {
    /// No dependence on q̇.
    pub const EMPTY: Span = Span { off: 0, lo: 0, hi: 0 };

    #[inline(always)]
    pub fn is_empty(&self) -> bool {
        self.lo == self.hi
    }

    /// The gradient's entries in the store `g`.
    #[inline(always)]
    pub fn of<'a>(&self, g: &'a [f64]) -> &'a [f64] {
        &g[self.off as usize..(self.off + self.hi - self.lo) as usize]
    }
}

/// A node of the tape: what an operation needs of an argument besides its value (its derivative
/// along the flow direction and its gradient) is stored there, under this handle, so that a
/// [`TapeVar`] stays two words and travels in registers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Arg {
    /// The node (the sink for a constant).
    pub id: u32,
}

impl Arg {
    /// A constant: no node, no derivative.
    pub const CONSTANT: Arg = Arg { id: SINK };

    #[inline(always)]
    fn is_constant(&self) -> bool {
        self.id == SINK
    }
}

/// A recording scalar: its value and [`Arg`]. `T` is always `f64` here (the type parameters are the
/// shape num-dual's macros expect); see [`TapeVar`]. Neither `Send` nor `Sync`: its node lives on
/// the tape of the thread that recorded it.
#[derive(Clone, Copy, Debug)]
pub struct Taped<T, F> {
    pub(super) re: T,
    pub(super) arg: Arg,
    f: PhantomData<(F, *const ())>,
}

/// The recording scalar a model is evaluated with on the tape.
pub type TapeVar = Taped<f64, f64>;

/// The value of a `T` as f64 (the identity for the only `T` used, f64).
#[inline(always)]
fn real<T: DualNum<F>, F: Float>(x: &T) -> f64 {
    x.re().to_f64().unwrap_or(f64::NAN)
}

impl<T: DualNum<F>, F> Taped<T, F> {
    /// A value with its node.
    #[inline(always)]
    pub(super) fn with(re: T, arg: Arg) -> Self {
        Taped {
            re,
            arg,
            f: PhantomData,
        }
    }

    /// A constant (not recorded).
    #[inline(always)]
    pub fn from_re(re: T) -> Self {
        Self::with(re, Arg::CONSTANT)
    }
}

impl<T: DualNum<F>, F: Float> Taped<T, F> {
    /// φ(self) from φ, φ', φ'' at the value: one unary node.
    #[inline(always)]
    fn chain_rule(&self, f0: T, f1: T, f2: T) -> Self {
        let arg = record(&self.arg, &Arg::CONSTANT, (real(&f1), 0.0), (real(&f2), 0.0, 0.0));
        Self::with(f0, arg)
    }

    /// c·self for a real c.
    #[inline(always)]
    fn scale(&self, c: T) -> Self {
        let arg = record(&self.arg, &Arg::CONSTANT, (real(&c), 0.0), (0.0, 0.0, 0.0));
        Self::with(self.re.clone() * c, arg)
    }

    #[inline(always)]
    fn add_ref(&self, o: &Self) -> Self {
        let re = self.re.clone() + o.re.clone();
        match (self.arg.is_constant(), o.arg.is_constant()) {
            (_, true) => Self::with(re, self.arg),
            (true, false) => Self::with(re, o.arg),
            (false, false) => Self::with(re, record(&self.arg, &o.arg, (1.0, 1.0), (0.0, 0.0, 0.0))),
        }
    }

    #[inline(always)]
    fn sub_ref(&self, o: &Self) -> Self {
        if o.arg.is_constant() {
            return Self::with(self.re.clone() - o.re.clone(), self.arg);
        }
        let arg = record(&self.arg, &o.arg, (1.0, -1.0), (0.0, 0.0, 0.0));
        Self::with(self.re.clone() - o.re.clone(), arg)
    }

    /// Product rule; ∂²(ab)/∂a∂b = 1 (a square a·a is recorded as a function of one argument).
    #[inline(always)]
    fn mul_ref(&self, o: &Self) -> Self {
        if o.arg.is_constant() {
            return self.scale(o.re.clone());
        }
        if self.arg.is_constant() {
            return o.scale(self.re.clone());
        }
        let (a, b) = (real(&self.re), real(&o.re));
        let arg = if self.arg == o.arg {
            // A square a·a: one argument, d/da = 2a, d²/da² = 2 (one outer product ∇a ∇aᵀ, not two).
            record(&self.arg, &Arg::CONSTANT, (2.0 * a, 0.0), (2.0, 0.0, 0.0))
        } else {
            record(&self.arg, &o.arg, (b, a), (0.0, 1.0, 0.0))
        };
        Self::with(self.re.clone() * o.re.clone(), arg)
    }

    /// a/b: ∂/∂a = 1/b, ∂/∂b = −a/b², ∂²/∂a∂b = −1/b², ∂²/∂b² = 2a/b³.
    #[inline(always)]
    fn div_ref(&self, o: &Self) -> Self {
        if o.arg.is_constant() {
            return self.scale(o.re.recip());
        }
        let re = self.re.clone() / o.re.clone();
        let (q, rec) = (real(&re), real(&o.re).recip());
        let hab = if self.arg.is_constant() { 0.0 } else { -rec * rec };
        let arg = record(
            &self.arg,
            &o.arg,
            (rec, -q * rec),
            (0.0, hab, 2.0 * q * rec * rec),
        );
        Self::with(re, arg)
    }
}

/// The four reference/value combinations of a binary operator.
macro_rules! taped_binop {
    ($trt:ident, $mth:ident, $imp:ident) => {
        impl<T: DualNum<F>, F: Float> $trt<&Taped<T, F>> for &Taped<T, F> {
            type Output = Taped<T, F>;
            #[inline(always)]
            fn $mth(self, o: &Taped<T, F>) -> Taped<T, F> {
                self.$imp(o)
            }
        }
        impl<T: DualNum<F>, F: Float> $trt<Taped<T, F>> for &Taped<T, F> {
            type Output = Taped<T, F>;
            #[inline(always)]
            fn $mth(self, o: Taped<T, F>) -> Taped<T, F> {
                self.$imp(&o)
            }
        }
        impl<T: DualNum<F>, F: Float> $trt<&Taped<T, F>> for Taped<T, F> {
            type Output = Taped<T, F>;
            #[inline(always)]
            fn $mth(self, o: &Taped<T, F>) -> Taped<T, F> {
                self.$imp(o)
            }
        }
        impl<T: DualNum<F>, F: Float> $trt for Taped<T, F> {
            type Output = Taped<T, F>;
            #[inline(always)]
            fn $mth(self, o: Taped<T, F>) -> Taped<T, F> {
                self.$imp(&o)
            }
        }
    };
}

taped_binop!(Add, add, add_ref);
taped_binop!(Sub, sub, sub_ref);
taped_binop!(Mul, mul, mul_ref);
taped_binop!(Div, div, div_ref);

/// Assignment operators with another `Taped` or with a real `F`.
macro_rules! taped_assign {
    ($trt:ident, $mth:ident, $op:tt) => {
        impl<T: DualNum<F>, F: DualNumFloat> $trt for Taped<T, F> {
            #[inline(always)]
            fn $mth(&mut self, o: Self) {
                *self = self.clone() $op o;
            }
        }
        impl<T: DualNum<F>, F: DualNumFloat> $trt<F> for Taped<T, F> {
            #[inline(always)]
            fn $mth(&mut self, o: F) {
                *self = self.clone() $op o;
            }
        }
    };
}

taped_assign!(AddAssign, add_assign, +);
taped_assign!(SubAssign, sub_assign, -);
taped_assign!(MulAssign, mul_assign, *);
taped_assign!(DivAssign, div_assign, /);

impl<T: DualNum<F>, F: DualNumFloat> Add<F> for Taped<T, F> {
    type Output = Self;
    #[inline(always)]
    fn add(self, f: F) -> Self {
        Self::with(self.re + f, self.arg)
    }
}
impl<T: DualNum<F>, F: DualNumFloat> Sub<F> for Taped<T, F> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, f: F) -> Self {
        Self::with(self.re - f, self.arg)
    }
}
impl<T: DualNum<F>, F: DualNumFloat> Mul<F> for Taped<T, F> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, f: F) -> Self {
        self.scale(T::from(f))
    }
}
impl<T: DualNum<F>, F: DualNumFloat> Div<F> for Taped<T, F> {
    type Output = Self;
    #[inline(always)]
    fn div(self, f: F) -> Self {
        self.scale(T::from(f.recip()))
    }
}

impl<T: DualNum<F>, F: Float> Neg for Taped<T, F> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        -&self
    }
}
impl<T: DualNum<F>, F: Float> Neg for &Taped<T, F> {
    type Output = Taped<T, F>;
    #[inline(always)]
    fn neg(self) -> Taped<T, F> {
        self.scale(-T::one())
    }
}

/// The remainder has no derivative here, as in num-dual's own types.
macro_rules! taped_rem {
    ($($lhs:ty, $rhs:ty);*) => {$(
        impl<T: DualNum<F>, F> Rem<$rhs> for $lhs {
            type Output = Taped<T, F>;
            fn rem(self, _o: $rhs) -> Taped<T, F> {
                unimplemented!("remainder of a dual number")
            }
        }
    )*};
}
taped_rem!(Taped<T, F>, Taped<T, F>; Taped<T, F>, &Taped<T, F>; &Taped<T, F>, Taped<T, F>;
    &Taped<T, F>, &Taped<T, F>; Taped<T, F>, F);

impl<T: DualNum<F>, F> RemAssign for Taped<T, F> {
    fn rem_assign(&mut self, _o: Self) {
        unimplemented!("remainder of a dual number")
    }
}
impl<T: DualNum<F>, F> RemAssign<F> for Taped<T, F> {
    fn rem_assign(&mut self, _o: F) {
        unimplemented!("remainder of a dual number")
    }
}

impl<T: DualNum<F>, F: fmt::Display> fmt::Display for Taped<T, F> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "{} (node {})", self.re, self.arg.id)
    }
}

crate::ad::derivatives::jet_derivatives!(second, 2, Taped, [arg]);
impl_from_f!(Taped, [arg]);
impl_zero_one!(Taped);
impl_inv!(Taped);
impl_iterator!(Taped);
impl_from_primitive!(Taped);
impl_signed!(Taped);
impl_num!(Taped);
impl_float_const!(Taped);
impl_dual_struct!(Taped);
impl_comparisons!(Taped);

// Compile-time check that the recording scalar is a `Scalar` (a model can be evaluated with it).
const _: fn() = || {
    fn is_scalar<S: crate::Scalar>() {}
    is_scalar::<TapeVar>();
};
