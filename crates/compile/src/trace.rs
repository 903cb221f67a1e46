//! Recording: the tracing scalar [`Traced`], with which a model written for noether (generic over
//! [`Scalar`](noether_core::Scalar)) is evaluated once to build its [`Graph`].
//!
//! A `Traced` is the value at the point of recording and the node that computes it. Every operation
//! builds its node in the graph of the recording in progress on this thread (a thread-local, installed
//! by [`record`]) and computes its value as f64 does. A constant (anything not computed from an input)
//! builds no node until it meets one.
//!
//! **Branches.** A recording is valid only for the control flow it took. Every way a model can read a
//! value to decide something is caught: a comparison (`<`, `==`, `partial_cmp`, `is_positive`,
//! `is_zero`, …) becomes a [`Guard`] — the sign of a − b that was seen, checked at every run of the
//! compiled code, which falls back to the dual-number path when it differs — and reading the value
//! itself ([`re`](num_dual::DualStruct::re)), whose use cannot be followed, or an operation with no
//! derivative (the remainder, the spherical Bessel functions) is a [refusal](Recording::refusals)
//! named by the operation. `abs` and `signum` are not branches: they are nodes of the graph.

use crate::graph::{Binary, Graph, Id, Unary};
use num_dual::{DualNum, DualStruct, Mappable};
use num_traits::{FloatConst, FromPrimitive, Inv, Num, One, Signed, Zero};
use std::cell::RefCell;
use std::cmp::Ordering;
use std::fmt;
use std::iter::{Product, Sum};
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign};

/// The id of "no node": a constant.
const CONSTANT: Id = Id::MAX;

/// The tracing scalar: the value at the point of recording and its node (none for a constant).
#[derive(Clone, Copy, Debug)]
pub struct Traced {
    value: f64,
    id: Id,
}

/// A comparison seen during the recording: the node a − b and the sign it had (−1, 0 or 1). The
/// compiled code is valid where the node has the same sign.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Guard {
    /// The node a − b.
    pub node: Id,
    /// Its sign at the point of recording.
    pub sign: f64,
}

/// What one evaluation of a model left: the graph, the guards of its comparisons and the operations
/// it could not be recorded through.
#[derive(Debug, Default)]
pub struct Recording {
    /// The expression graph.
    pub graph: Graph,
    /// The comparisons, to be checked at run time.
    pub guards: Vec<Guard>,
    /// Operations that make the recording unusable (the first is reported).
    pub refusals: Vec<&'static str>,
}

thread_local! {
    static ACTIVE: RefCell<Option<Recording>> = const { RefCell::new(None) };
}

/// Runs `f` with `recording` installed as this thread's recording and returns what `f` returned with
/// the recording as `f` left it. Recordings nest: an outer one is put back afterwards.
pub fn record<R>(recording: Recording, f: impl FnOnce() -> R) -> (R, Recording) {
    let outer = ACTIVE.with(|a| a.replace(Some(recording)));
    let r = f();
    let inner = ACTIVE.with(|a| a.replace(outer));
    (r, inner.expect("the recording installed above"))
}

/// Runs `op` on the active recording.
fn with<R>(op: impl FnOnce(&mut Recording) -> R) -> R {
    ACTIVE.with(|a| {
        let mut a = a.borrow_mut();
        op(a.as_mut()
            .expect("a traced value with a node is used only while its recording is active"))
    })
}

/// A function of (t, q, v) recorded: its graph, the nodes of its inputs (t is input 0, q the next n,
/// v the n after), the node of its value and those of the vector recorded with it (a Lagrangian's
/// generalized forces; empty for one value alone).
pub(crate) struct Recorded {
    pub rec: Recording,
    pub t: Id,
    pub q: Vec<Id>,
    pub v: Vec<Id>,
    pub value: Id,
    pub vector: Vec<Id>,
}

impl Recorded {
    /// Records `f` at (t, q, v) (the point only decides the branches `f` takes); a refused
    /// recording is [`Error::Refused`](crate::Error::Refused) naming the first operation refused.
    pub fn new(
        t0: f64,
        q0: &[f64],
        v0: &[f64],
        f: impl FnOnce(Traced, &[Traced], &[Traced]) -> Traced,
    ) -> crate::Result<Recorded> {
        Self::with_vector(t0, q0, v0, 0, |t, q, v, _| f(t, q, v))
    }

    /// [`new`](Self::new) for a value and a vector of `len` components written by `f` into its
    /// last argument (zeros on entry), recorded together on one graph.
    pub fn with_vector(
        t0: f64,
        q0: &[f64],
        v0: &[f64],
        len: usize,
        f: impl FnOnce(Traced, &[Traced], &[Traced], &mut [Traced]) -> Traced,
    ) -> crate::Result<Recorded> {
        let n = q0.len();
        let mut rec = Recording::default();
        let t = rec.graph.input(0);
        let q: Vec<Id> = (0..n).map(|i| rec.graph.input(1 + i as u32)).collect();
        let v: Vec<Id> = (0..n).map(|i| rec.graph.input((1 + n + i) as u32)).collect();
        let tt = Traced::node(t0, t);
        let qq: Vec<Traced> = q.iter().zip(q0).map(|(&id, &x)| Traced::node(x, id)).collect();
        let vv: Vec<Traced> = v.iter().zip(v0).map(|(&id, &x)| Traced::node(x, id)).collect();
        let mut vector = vec![Traced::constant(0.0); len];
        let (value, mut rec) = record(rec, || f(tt, &qq, &vv, &mut vector));
        if let Some(&operation) = rec.refusals.first() {
            return Err(crate::Error::Refused { operation });
        }
        let mut node = |x: Traced| match x.id() {
            Some(id) => id,
            None => rec.graph.constant(x.value()),
        };
        let value = node(value);
        let vector = vector.into_iter().map(node).collect();
        Ok(Recorded {
            rec,
            t,
            q,
            v,
            value,
            vector,
        })
    }
}

impl Traced {
    /// A constant.
    pub fn constant(value: f64) -> Self {
        Traced { value, id: CONSTANT }
    }

    /// The value `value` of node `id` of the active recording.
    pub fn node(value: f64, id: Id) -> Self {
        Traced { value, id }
    }

    /// The node, if this is not a constant.
    pub fn id(&self) -> Option<Id> {
        (self.id != CONSTANT).then_some(self.id)
    }

    /// The value at the point of recording.
    pub fn value(&self) -> f64 {
        self.value
    }

    /// The node of `self` in `g` (a constant's node is made).
    fn in_graph(&self, g: &mut Graph) -> Id {
        if self.id == CONSTANT {
            g.constant(self.value)
        } else {
            self.id
        }
    }

    /// The result `value` of a node built by `build`; a node that simplified to a constant is one.
    fn built(value: f64, build: impl FnOnce(&mut Graph) -> Id) -> Self {
        with(|r| {
            let id = build(&mut r.graph);
            match r.graph.constant_value(id) {
                Some(c) => Traced::constant(c),
                None => Traced::node(value, id),
            }
        })
    }

    fn unary(&self, f: Unary) -> Self {
        let value = f.apply(self.value);
        if self.id == CONSTANT {
            return Traced::constant(value);
        }
        Self::built(value, |g| g.unary(f, self.id))
    }

    fn binary(&self, op: Binary, o: &Self) -> Self {
        let value = op.apply(self.value, o.value);
        if self.id == CONSTANT && o.id == CONSTANT {
            return Traced::constant(value);
        }
        Self::built(value, |g| {
            let (a, b) = (self.in_graph(g), o.in_graph(g));
            g.binary(op, a, b)
        })
    }

    /// Records the comparison of `self` with `o` as a guard and returns its outcome.
    fn compare(&self, o: &Self) -> Option<Ordering> {
        let outcome = self.value.partial_cmp(&o.value);
        if self.id != CONSTANT || o.id != CONSTANT {
            with(|r| {
                let (a, b) = (self.in_graph(&mut r.graph), o.in_graph(&mut r.graph));
                let node = r.graph.sub(a, b);
                match outcome {
                    Some(ord) => r.guards.push(Guard {
                        node,
                        sign: ord as i8 as f64,
                    }),
                    None => r.refusals.push("a comparison with NaN"),
                }
            });
        }
        outcome
    }

    /// Records that the value was used in a way the graph cannot follow.
    fn refuse(&self, operation: &'static str) {
        if self.id != CONSTANT {
            with(|r| r.refusals.push(operation));
        }
    }
}

macro_rules! binop {
    ($trt:ident, $mth:ident, $op:expr) => {
        impl $trt for Traced {
            type Output = Traced;
            #[inline]
            fn $mth(self, o: Traced) -> Traced {
                self.binary($op, &o)
            }
        }
        impl $trt<&Traced> for Traced {
            type Output = Traced;
            #[inline]
            fn $mth(self, o: &Traced) -> Traced {
                self.binary($op, o)
            }
        }
        impl $trt<Traced> for &Traced {
            type Output = Traced;
            #[inline]
            fn $mth(self, o: Traced) -> Traced {
                self.binary($op, &o)
            }
        }
        impl $trt<&Traced> for &Traced {
            type Output = Traced;
            #[inline]
            fn $mth(self, o: &Traced) -> Traced {
                self.binary($op, o)
            }
        }
        impl $trt<f64> for Traced {
            type Output = Traced;
            #[inline]
            fn $mth(self, o: f64) -> Traced {
                self.binary($op, &Traced::constant(o))
            }
        }
    };
}

binop!(Add, add, Binary::Add);
binop!(Sub, sub, Binary::Sub);
binop!(Mul, mul, Binary::Mul);
binop!(Div, div, Binary::Div);

macro_rules! assignop {
    ($trt:ident, $mth:ident, $op:tt) => {
        impl $trt for Traced {
            #[inline]
            fn $mth(&mut self, o: Traced) {
                *self = *self $op o;
            }
        }
        impl $trt<f64> for Traced {
            #[inline]
            fn $mth(&mut self, o: f64) {
                *self = *self $op o;
            }
        }
    };
}

assignop!(AddAssign, add_assign, +);
assignop!(SubAssign, sub_assign, -);
assignop!(MulAssign, mul_assign, *);
assignop!(DivAssign, div_assign, /);
assignop!(RemAssign, rem_assign, %);

/// The remainder has no derivative: refused (its value is computed, the recording is not usable).
macro_rules! remop {
    ($($lhs:ty, $rhs:ty);*) => {$(
        impl Rem<$rhs> for $lhs {
            type Output = Traced;
            fn rem(self, o: $rhs) -> Traced {
                let o: Traced = Traced::from(o);
                self.refuse("the remainder %");
                o.refuse("the remainder %");
                Traced::constant(self.value % o.value)
            }
        }
    )*};
}
remop!(Traced, Traced; Traced, &Traced; &Traced, Traced; &Traced, &Traced; Traced, f64);

impl From<&Traced> for Traced {
    fn from(x: &Traced) -> Self {
        *x
    }
}

impl Neg for Traced {
    type Output = Traced;
    #[inline]
    fn neg(self) -> Traced {
        self.unary(Unary::Neg)
    }
}

impl Neg for &Traced {
    type Output = Traced;
    #[inline]
    fn neg(self) -> Traced {
        self.unary(Unary::Neg)
    }
}

impl From<f64> for Traced {
    fn from(x: f64) -> Self {
        Traced::constant(x)
    }
}

impl Zero for Traced {
    fn zero() -> Self {
        Traced::constant(0.0)
    }
    fn is_zero(&self) -> bool {
        self.compare(&Traced::zero()) == Some(Ordering::Equal)
    }
}

impl One for Traced {
    fn one() -> Self {
        Traced::constant(1.0)
    }
    fn is_one(&self) -> bool {
        self.compare(&Traced::one()) == Some(Ordering::Equal)
    }
}

impl Num for Traced {
    type FromStrRadixErr = <f64 as Num>::FromStrRadixErr;
    fn from_str_radix(s: &str, radix: u32) -> Result<Self, Self::FromStrRadixErr> {
        f64::from_str_radix(s, radix).map(Traced::constant)
    }
}

impl Signed for Traced {
    fn abs(&self) -> Self {
        self.unary(Unary::Abs)
    }
    fn abs_sub(&self, other: &Self) -> Self {
        if self.compare(other) == Some(Ordering::Greater) {
            *self - *other
        } else {
            Traced::zero()
        }
    }
    fn signum(&self) -> Self {
        self.unary(Unary::Sign)
    }
    fn is_positive(&self) -> bool {
        self.compare(&Traced::zero()) == Some(Ordering::Greater)
    }
    fn is_negative(&self) -> bool {
        self.compare(&Traced::zero()) == Some(Ordering::Less)
    }
}

impl Inv for Traced {
    type Output = Traced;
    fn inv(self) -> Traced {
        self.unary(Unary::Recip)
    }
}

impl Sum for Traced {
    fn sum<I: Iterator<Item = Traced>>(iter: I) -> Self {
        iter.fold(Traced::zero(), |acc, x| acc + x)
    }
}

impl<'a> Sum<&'a Traced> for Traced {
    fn sum<I: Iterator<Item = &'a Traced>>(iter: I) -> Self {
        iter.fold(Traced::zero(), |acc, x| acc + x)
    }
}

impl Product for Traced {
    fn product<I: Iterator<Item = Traced>>(iter: I) -> Self {
        iter.fold(Traced::one(), |acc, x| acc * x)
    }
}

impl<'a> Product<&'a Traced> for Traced {
    fn product<I: Iterator<Item = &'a Traced>>(iter: I) -> Self {
        iter.fold(Traced::one(), |acc, x| acc * x)
    }
}

impl FromPrimitive for Traced {
    fn from_i64(n: i64) -> Option<Self> {
        Some(Traced::constant(n as f64))
    }
    fn from_u64(n: u64) -> Option<Self> {
        Some(Traced::constant(n as f64))
    }
    fn from_f64(n: f64) -> Option<Self> {
        Some(Traced::constant(n))
    }
}

impl DualStruct<Traced, f64> for Traced {
    type Real = f64;
    type Inner = f64;
    /// The value at the point of recording. Reading it is a branch the graph cannot follow, so a
    /// recording in which a traced value (not a constant) is read is refused.
    fn re(&self) -> f64 {
        self.refuse("re() (reading the value of a traced number)");
        self.value
    }
    fn from_inner(inner: &f64) -> Self {
        Traced::constant(*inner)
    }
}

impl Mappable<Traced> for Traced {
    type Output<O> = O;
    fn map_dual<G: Fn(Traced) -> O, O>(self, g: G) -> O {
        g(self)
    }
}

impl fmt::Display for Traced {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self.id() {
            Some(id) => write!(f, "{} (node {id})", self.value),
            None => write!(f, "{}", self.value),
        }
    }
}

impl PartialEq for Traced {
    fn eq(&self, o: &Traced) -> bool {
        self.compare(o) == Some(Ordering::Equal)
    }
}

impl PartialEq<f64> for Traced {
    fn eq(&self, o: &f64) -> bool {
        self.compare(&Traced::constant(*o)) == Some(Ordering::Equal)
    }
}

impl PartialOrd for Traced {
    fn partial_cmp(&self, o: &Traced) -> Option<Ordering> {
        self.compare(o)
    }
}

impl PartialOrd<f64> for Traced {
    fn partial_cmp(&self, o: &f64) -> Option<Ordering> {
        self.compare(&Traced::constant(*o))
    }
}

macro_rules! float_consts {
    ($($name:ident),*) => {
        impl FloatConst for Traced {
            $(
                fn $name() -> Self {
                    Traced::constant(f64::$name())
                }
            )*
        }
    };
}

#[allow(non_snake_case)]
mod consts {
    use super::*;
    float_consts!(
        E,
        FRAC_1_PI,
        FRAC_1_SQRT_2,
        FRAC_2_PI,
        FRAC_2_SQRT_PI,
        FRAC_PI_2,
        FRAC_PI_3,
        FRAC_PI_4,
        FRAC_PI_6,
        FRAC_PI_8,
        LN_10,
        LN_2,
        LOG10_E,
        LOG2_E,
        PI,
        SQRT_2
    );
}

impl DualNum<f64> for Traced {
    const NDERIV: usize = usize::MAX;

    fn recip(&self) -> Self {
        self.unary(Unary::Recip)
    }
    fn powi(&self, n: i32) -> Self {
        let value = self.value.powi(n);
        if self.id == CONSTANT {
            return Traced::constant(value);
        }
        Self::built(value, |g| g.powi(self.id, n))
    }
    fn powf(&self, e: f64) -> Self {
        let value = self.value.powf(e);
        if self.id == CONSTANT {
            return Traced::constant(value);
        }
        Self::built(value, |g| g.powf(self.id, e))
    }
    fn sqrt(&self) -> Self {
        self.unary(Unary::Sqrt)
    }
    fn cbrt(&self) -> Self {
        self.unary(Unary::Cbrt)
    }
    fn exp(&self) -> Self {
        self.unary(Unary::Exp)
    }
    /// 2ˣ = e^(x ln 2).
    fn exp2(&self) -> Self {
        (*self * std::f64::consts::LN_2).exp()
    }
    fn exp_m1(&self) -> Self {
        self.unary(Unary::ExpM1)
    }
    fn ln(&self) -> Self {
        self.unary(Unary::Ln)
    }
    /// log_b x = ln x / ln b.
    fn log(&self, base: f64) -> Self {
        self.ln() / base.ln()
    }
    fn log2(&self) -> Self {
        self.ln() / std::f64::consts::LN_2
    }
    fn log10(&self) -> Self {
        self.ln() / std::f64::consts::LN_10
    }
    fn ln_1p(&self) -> Self {
        self.unary(Unary::Ln1p)
    }
    fn sin(&self) -> Self {
        self.unary(Unary::Sin)
    }
    fn cos(&self) -> Self {
        self.unary(Unary::Cos)
    }
    fn tan(&self) -> Self {
        self.unary(Unary::Tan)
    }
    fn sin_cos(&self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
    fn asin(&self) -> Self {
        self.unary(Unary::Asin)
    }
    fn acos(&self) -> Self {
        self.unary(Unary::Acos)
    }
    fn atan(&self) -> Self {
        self.unary(Unary::Atan)
    }
    fn atan2(&self, other: Self) -> Self {
        self.binary(Binary::Atan2, &other)
    }
    fn sinh(&self) -> Self {
        self.unary(Unary::Sinh)
    }
    fn cosh(&self) -> Self {
        self.unary(Unary::Cosh)
    }
    fn tanh(&self) -> Self {
        self.unary(Unary::Tanh)
    }
    fn asinh(&self) -> Self {
        self.unary(Unary::Asinh)
    }
    fn acosh(&self) -> Self {
        self.unary(Unary::Acosh)
    }
    fn atanh(&self) -> Self {
        self.unary(Unary::Atanh)
    }
    fn sph_j0(&self) -> Self {
        self.refuse("sph_j0");
        Traced::constant(DualNum::sph_j0(&self.value))
    }
    fn sph_j1(&self) -> Self {
        self.refuse("sph_j1");
        Traced::constant(DualNum::sph_j1(&self.value))
    }
    fn sph_j2(&self) -> Self {
        self.refuse("sph_j2");
        Traced::constant(DualNum::sph_j2(&self.value))
    }
}

// Compile-time check that the tracing scalar is a `Scalar` (every model can be recorded with it).
const _: fn() = || {
    fn is_scalar<S: noether_core::Scalar>() {}
    is_scalar::<Traced>();
};
