//! The `DualNum` implementation of noether's own number types ([`LagrangeJet`](super::LagrangeJet),
//! [`GradJet`](super::GradJet), the recording scalar of the tape): num-dual 0.13.7's
//! `impl_derivatives!` macro (MIT OR Apache-2.0, copied unchanged) with one change, `powf` at 0.
//!
//! num-dual forms xⁿ and its derivatives from one power, pow3 = x^(n−3): f⁽ᵏ⁾ = pow3·x^(3−k)·n(n−1)…,
//! which at x = 0 is ∞·0 = NaN for 0 < n < 3, even for the value. So ½v² − q^1.5 had a NaN energy,
//! force and Lagrange equations at q = 0 although V(0) = V′(0) = 0 (issue 29). Here, when the value
//! of x is exactly 0, each f⁽ᵏ⁾ = n(n−1)…(n−k+1)·x^(n−k) is taken as its own power: 0^a = 0 for
//! a > 0, 1 for a = 0, ∞ for a < 0. A derivative that really is infinite (the second of q^1.5 at 0,
//! the first of q^0.5) stays infinite and is refused where it is used; one that the evaluation does
//! not need is never multiplied in (the jets' structurally zero parts). Away from 0 the result is
//! num-dual's to the bit. num-dual's own types (`Dual64`, `Dual2Vec`, `HyperDualVec`: ∂/∂t, Hessians)
//! keep its formula: see docs/error-contract.md §5.

macro_rules! jet_derivatives {
    ($deriv:ident, $nderiv:expr, $struct:ident, [$($im:ident),*]$(, [$($dim:tt),*]$(, [$($ddim:tt),*])*)?) => {
        impl<T: DualNum<F>, F: DualNumFloat$($(, $dim: Dim)*)?> DualNum<F> for $struct<T, F$($(, $dim)*)?>
        where
        // $($(DefaultAllocator: Allocator<$dim> + Allocator<U1, $dim> + Allocator<$dim, $dim>,)*)?
        $($(DefaultAllocator: Allocator<$($ddim,)*>),*)?
        {
            const NDERIV: usize = T::NDERIV + $nderiv;

            #[inline]
            fn recip(&self) -> Self {
                let rec = self.re.recip();
                let f0 = rec.clone();
                first!($deriv, let f1 = -f0.clone() * &rec;);
                second!($deriv, let f2 = f1.clone() * &rec * F::from(-2.0).unwrap(););
                third!($deriv, let f3 = f2.clone() * rec * F::from(-3.0).unwrap(););
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn powi(&self, exp: i32) -> Self {
                match exp {
                    0 => Self::one(),
                    1 => self.clone(),
                    2 => self * self,
                    _ => {
                        let pow3 = self.re.powi(exp - 3);
                        let f0 = pow3.clone() * &self.re * &self.re * &self.re;
                        first!($deriv, let f1 = pow3.clone() * &self.re * &self.re * F::from(exp).unwrap(););
                        second!($deriv, let f2 = pow3.clone() * &self.re * F::from(exp * (exp - 1)).unwrap(););
                        third!($deriv, let f3 = pow3 * F::from(exp * (exp - 1) * (exp - 2)).unwrap(););
                        chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
                    }
                }
            }

            #[inline]
            fn powf(&self, n: F) -> Self {
                if n.is_zero() {
                    Self::one()
                } else if n.is_one() {
                    self.clone()
                } else if (n - F::one() - F::one()).abs() < F::epsilon() {
                    self * self
                } else if self.re.re().is_zero() {
                    // At 0 each derivative n(n−1)…(n−k+1)·re^(n−k) is its own power: 0 for a
                    // positive exponent, ∞ for a negative one, never num-dual's re^(n−3)·re³ = ∞·0.
                    let n1 = n - F::one();
                    let f0 = self.re.powf(n);
                    first!($deriv, let f1 = self.re.powf(n1) * n;);
                    second!($deriv, let f2 = self.re.powf(n1 - F::one()) * n * n1;);
                    third!($deriv, let f3 = self.re.powf(n1 - F::one() - F::one()) * n * n1 * (n1 - F::one()););
                    chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
                } else {
                    let n1 = n - F::one();
                    let n2 = n1 - F::one();
                    let n3 = n2 - F::one();
                    let pow3 = self.re.powf(n3);
                    let f0 = pow3.clone() * &self.re * &self.re * &self.re;
                    first!($deriv, let f1 = pow3.clone() * &self.re * &self.re * n;);
                    second!($deriv, let f2 = pow3.clone() * &self.re * n * n1;);
                    third!($deriv, let f3 = pow3 * n * n1 * n2;);
                    chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
                }
            }

            #[inline]
            fn sqrt(&self) -> Self {
                first!($deriv, let rec = self.re.recip(););
                first!($deriv, let half = F::from(0.5).unwrap(););
                let f0 = self.re.sqrt();
                first!($deriv, let f1 = f0.clone() * &rec * half;);
                second!($deriv, let f2 = -f1.clone() * &rec * half;);
                third!($deriv, let f3 = f2.clone() * rec * (-F::one() - half););
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn cbrt(&self) -> Self {
                first!($deriv, let rec = self.re.recip(););
                first!($deriv, let third = F::from(1.0 / 3.0).unwrap(););
                let f0 = self.re.cbrt();
                first!($deriv, let f1 = f0.clone() * &rec * third;);
                second!($deriv, let f2 = f1.clone() * &rec * (third - F::one()););
                third!($deriv, let f3 = f2.clone() * rec * (third - F::one() - F::one()););
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }


            #[inline]
            fn exp(&self) -> Self {
                let f = self.re.exp();
                chain_rule!($deriv, Self::chain_rule(self, f.clone(), f.clone(), f.clone(), f))
            }

            #[inline]
            fn exp2(&self) -> Self {
                first!($deriv, let ln2 = F::from(2.0).unwrap().ln(););
                let f0 = self.re.exp2();
                first!($deriv, let f1 = f0.clone() * ln2;);
                second!($deriv, let f2 = f1.clone() * ln2;);
                third!($deriv, let f3 = f2.clone() * ln2;);
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn exp_m1(&self) -> Self {
                let f0 = self.re.exp_m1();
                first!($deriv, let f1 = self.re.exp(););
                chain_rule!($deriv, Self::chain_rule(self, f0, f1.clone(), f1.clone(), f1))
            }

            #[inline]
            fn ln(&self) -> Self {
                first!($deriv, let rec = self.re.recip(););
                let f0 = self.re.ln();
                first!($deriv, let f1 = rec.clone(););
                second!($deriv, let f2 = -f1.clone() * &rec;);
                third!($deriv, let f3 = f2.clone() * rec * F::from(-2.0).unwrap(););
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn log(&self, base: F) -> Self {
                first!($deriv, let rec = self.re.recip(););
                let f0 = self.re.log(base);
                first!($deriv, let f1 = rec.clone() / base.ln(););
                second!($deriv, let f2 = -f1.clone() * &rec;);
                third!($deriv, let f3 = f2.clone() * rec * F::from(-2.0).unwrap(););
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn log2(&self) -> Self {
                first!($deriv, let rec = self.re.recip(););
                let f0 = self.re.log2();
                first!($deriv, let f1 = rec.clone() / (F::one() + F::one()).ln(););
                second!($deriv, let f2 = -f1.clone() * &rec;);
                third!($deriv, let f3 = f2.clone() * rec * F::from(-2.0).unwrap(););
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn log10(&self) -> Self {
                first!($deriv, let rec = self.re.recip(););
                let f0 = self.re.log10();
                first!($deriv, let f1 = rec.clone() / F::from(10.0).unwrap().ln(););
                second!($deriv, let f2 = -f1.clone() * &rec;);
                third!($deriv, let f3 = f2.clone() * rec * F::from(-2.0).unwrap(););
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn ln_1p(&self) -> Self {
                first!($deriv, let rec = (self.re.clone() + F::one()).recip(););
                let f0 = self.re.ln_1p();
                first!($deriv, let f1 = rec.clone(););
                second!($deriv, let f2 = -f1.clone() * &rec;);
                third!($deriv, let f3 = f2.clone() * rec * F::from(-2.0).unwrap(););
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn sin(&self) -> Self {
                zeroth!($deriv, let s = self.re.sin(););
                first!($deriv, let (s, c) = self.re.sin_cos(););
                chain_rule!($deriv, Self::chain_rule(self, s.clone(), c.clone(), -s, -c))
            }

            #[inline]
            fn cos(&self) -> Self {
                zeroth!($deriv, let c = self.re.cos(););
                first!($deriv, let (s, c) = self.re.sin_cos(););
                chain_rule!($deriv, Self::chain_rule(self, c.clone(), -s.clone(), -c, s))
            }

            #[inline]
            fn sin_cos(&self) -> (Self, Self) {
                let (s, c) = self.re.sin_cos();
                (
                    chain_rule!($deriv, Self::chain_rule(self, s.clone(), c.clone(), -s.clone(), -c.clone())),
                    chain_rule!($deriv, Self::chain_rule(self, c.clone(), -s.clone(), -c, s)))
            }

            #[inline]
            fn tan(&self) -> Self {
                let (sin, cos) = self.sin_cos();
                sin / cos
            }

            #[inline]
            fn asin(&self) -> Self {
                first!($deriv, let rec = (T::one() - self.re.clone() * &self.re).recip(););
                let f0 = self.re.asin();
                first!($deriv, let f1 = rec.sqrt(););
                second!($deriv, let f2 = self.re.clone() * &f1 * &rec;);
                third!($deriv, let f3 = (self.re.clone() * &self.re * (F::one() + F::one()) + F::one()) * &f1 * &rec * rec;);
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn acos(&self) -> Self {
                first!($deriv, let rec = (T::one() - self.re.clone() * &self.re).recip(););
                let f0 = self.re.acos();
                first!($deriv, let f1 = -rec.sqrt(););
                second!($deriv, let f2 = self.re.clone() * &f1 * &rec;);
                third!($deriv, let f3 = (self.re.clone() * &self.re * (F::one() + F::one()) + F::one()) * &f1 * &rec * rec;);
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn atan(&self) -> Self {
                first!($deriv, let rec = (T::one() + self.re.clone() * &self.re).recip(););
                let f0 = self.re.atan();
                first!($deriv, let f1 = rec.clone(););
                second!($deriv, let two = F::one() + F::one(););
                second!($deriv, let f2 = -self.re.clone() * &f1 * &rec * two;);
                third!($deriv, let f3 = (self.re.clone() * &self.re * F::from(6.0).unwrap() - two) * &f1 * &rec * rec;);
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn atan2(&self, other: Self) -> Self {
                let mut res = (self / other.clone()).atan();
                res.re = self.re.atan2(other.re);
                res
            }

            #[inline]
            fn sinh(&self) -> Self {
                let s = self.re.sinh();
                first!($deriv, let c = self.re.cosh(););
                chain_rule!($deriv, Self::chain_rule(self, s.clone(), c.clone(), s, c))
            }

            #[inline]
            fn cosh(&self) -> Self {
                first!($deriv, let s = self.re.sinh(););
                let c = self.re.cosh();
                chain_rule!($deriv, Self::chain_rule(self, c.clone(), s.clone(), c, s))
            }

            #[inline]
            fn tanh(&self) -> Self {
                self.sinh() / self.cosh()
            }

            #[inline]
            fn asinh(&self) -> Self {
                first!($deriv, let rec = (T::one() + self.re.clone() * &self.re).recip(););
                let f0 = self.re.asinh();
                first!($deriv, let f1 = rec.sqrt(););
                second!($deriv, let f2 = -self.re.clone() * &f1 * &rec;);
                third!($deriv, let f3 = (self.re.clone() * &self.re * (F::one() + F::one()) - F::one()) * &f1 * &rec * rec;);
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn acosh(&self) -> Self {
                first!($deriv, let rec = (self.re.clone() * &self.re - F::one()).recip(););
                let f0 = self.re.acosh();
                first!($deriv, let f1 = rec.sqrt(););
                second!($deriv, let f2 = -self.re.clone() * &f1 * &rec;);
                third!($deriv, let f3 = (self.re.clone() * &self.re * (F::one() + F::one()) + F::one()) * &f1 * &rec * rec;);
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn atanh(&self) -> Self {
                first!($deriv, let rec = (T::one() - self.re.clone() * &self.re).recip(););
                let f0 = self.re.atanh();
                first!($deriv, let f1 = rec.clone(););
                second!($deriv, let two = F::one() + F::one(););
                second!($deriv, let f2 = self.re.clone() * &f1 * &rec * two;);
                third!($deriv, let f3 = (self.re.clone() * &self.re * F::from(6.0).unwrap() + two) * &f1 * &rec * rec;);
                chain_rule!($deriv, Self::chain_rule(self, f0, f1, f2, f3))
            }

            #[inline]
            fn sph_j0(&self) -> Self {
                if self.re() < F::epsilon() {
                    Self::one() - self * self / F::from(6.0).unwrap()
                } else {
                    self.sin() / self
                }
            }

            #[inline]
            fn sph_j1(&self) -> Self {
                if self.re() < F::epsilon() {
                    self.clone() / F::from(3.0).unwrap()
                } else {
                    let (s, c) = self.sin_cos();
                    (s - self * c) / (self * self)
                }
            }

            #[inline]
            fn sph_j2(&self) -> Self {
                if self.re() < F::epsilon() {
                    self * self / F::from(15.0).unwrap()
                } else {
                    let (s, c) = self.sin_cos();
                    let s2 = self * self;
                    ((&s - self * c) * F::from(3.0).unwrap() - &s2 * s) / (s2 * self)
                }
            }
        }
    };
}

pub(crate) use jet_derivatives;
