//! Closure-like shorthands for small models: [`lagrangian!`](crate::lagrangian) and
//! [`hamiltonian!`](crate::hamiltonian).
//!
//! A model must be evaluated with `f64` and with several dual-number types, so its body has to be
//! generic over the scalar `D: Scalar`, which a Rust closure cannot be. The macros take a closure-like
//! body and generate what a user would write by hand: a small struct holding the parameters and an
//! impl of [`Lagrangian`](crate::Lagrangian) (or [`Hamiltonian`](crate::Hamiltonian)) whose generic
//! method is the body, instantiated for every scalar type. The value returned has an anonymous type
//! (like a closure) that implements the trait, so it goes wherever a model goes.
//!
//! ```
//! use noether_core::prelude::*;
//!
//! // Simple pendulum, L = ½ θ̇² + g cos θ (unit mass and length).
//! let pendulum = lagrangian!(dof = 1, |_t, q, v| v[0] * v[0] * 0.5 + q[0].cos() * 9.81);
//!
//! let el = EulerLagrange::new(pendulum);
//! let mut a = [0.0];
//! el.accelerations(0.0, &[0.3], &[0.0], &mut a).unwrap();
//! assert!((a[0] + 9.81 * 0.3f64.sin()).abs() < 1e-14); // θ̈ = −g sin θ
//! ```
//!
//! Parameters are listed with their type and value in `params { … }` and are in scope in the body
//! (they are copied into the struct, so they must be `Copy`: numbers, arrays of numbers). In the body
//! `D` names the scalar type (for `D::from(x)`), and as everywhere in noether the scalar goes on the
//! left of `*` with an `f64` (`q[0] * k`, not `k * q[0]`). `dof` may be any expression of type `usize`,
//! also one known only at run time:
//!
//! ```
//! use noether_core::prelude::*;
//!
//! // A ring of n unit masses joined by springs of stiffness k, L = ½ |q̇|² − ½ k Σ (q_{i+1} − q_i)².
//! let n = 5;
//! let ring = lagrangian!(dof = n, params { k: f64 = 2.0 }, |_t, q, v| {
//!     let mut l = D::from(0.0);
//!     for i in 0..q.len() {
//!         let d = q[(i + 1) % q.len()] - q[i];
//!         l = l + v[i] * v[i] * 0.5 - d * d * (0.5 * k);
//!     }
//!     l
//! });
//! assert_eq!(ring.dof(), 5);
//! let el = EulerLagrange::new(ring);
//! let mut a = vec![0.0; n];
//! el.accelerations(0.0, &[0.1, 0.0, 0.0, 0.0, 0.0], &[0.0; 5], &mut a).unwrap();
//! assert!((a[0] + 2.0 * 2.0 * 0.1).abs() < 1e-14 && (a[1] - 2.0 * 0.1).abs() < 1e-14);
//! ```
//!
//! The same for a Hamiltonian H(t, q, p):
//!
//! ```
//! use noether_core::prelude::*;
//!
//! // Harmonic oscillator H = p²/(2m) + ½ k q².
//! let osc = hamiltonian!(dof = 1, params { m: f64 = 2.0, k: f64 = 8.0 }, |_t, q, p| {
//!     p[0] * p[0] * (0.5 / m) + q[0] * q[0] * (0.5 * k)
//! });
//! let (mut dq, mut dp) = ([0.0], [0.0]);
//! HamiltonEquations::new(osc).rates(0.0, &[0.5], &[1.0], &mut dq, &mut dp).unwrap();
//! assert!((dq[0] - 0.5).abs() < 1e-15 && (dp[0] + 4.0).abs() < 1e-15); // q̇ = p/m, ṗ = −k q
//! ```
//!
//! The shorthand covers the required methods only: a model that declares a constant mass matrix or
//! generalized forces implements the trait by hand.

/// A [`Lagrangian`](crate::Lagrangian) from a closure-like body `|t, q, v| L`, generic over the scalar.
///
/// Forms: `lagrangian!(dof = N, |t, q, v| body)` and
/// `lagrangian!(dof = N, params { name: Type = value, … }, |t, q, v| body)`. In the body `t: D`,
/// `q: &[D]`, `v: &[D]` (q̇), the parameters are in scope by name and `D` is the scalar type. See the
/// [module docs](crate::shorthand).
///
/// ```
/// use noether_core::prelude::*;
/// // A charge in a uniform magnetic field B ẑ: L = ½ m |v|² + e v·A, A = ½ B (−y, x).
/// let charge = lagrangian!(dof = 2, params { m: f64 = 1.0, e: f64 = 1.0, b: f64 = 2.0 }, |_t, q, v| {
///     (v[0] * v[0] + v[1] * v[1]) * (0.5 * m) + (q[0] * v[1] - q[1] * v[0]) * (0.5 * e * b)
/// });
/// let mut a = [0.0; 2];
/// EulerLagrange::new(charge).accelerations(0.0, &[0.0, 0.0], &[1.0, 0.0], &mut a).unwrap();
/// assert!((a[1] + 2.0).abs() < 1e-14); // m v̇ = e v × B: (1, 0, 0) × (0, 0, 2) = (0, −2, 0)
/// ```
#[macro_export]
macro_rules! lagrangian {
    (dof = $dof:expr, |$t:pat_param, $q:pat_param, $v:pat_param| $body:expr $(,)?) => {
        $crate::lagrangian!(dof = $dof, params {}, |$t, $q, $v| $body)
    };
    (
        dof = $dof:expr,
        params { $($name:ident : $ty:ty = $value:expr),* $(,)? },
        |$t:pat_param, $q:pat_param, $v:pat_param| $body:expr $(,)?
    ) => {
        $crate::__shorthand_model!(
            Lagrangian::lagrangian as ShorthandLagrangian,
            dof = $dof,
            params { $($name: $ty = $value),* },
            |$t, $q, $v| $body
        )
    };
}

/// A [`Hamiltonian`](crate::Hamiltonian) from a closure-like body `|t, q, p| H`, generic over the
/// scalar.
///
/// Forms: `hamiltonian!(dof = N, |t, q, p| body)` and
/// `hamiltonian!(dof = N, params { name: Type = value, … }, |t, q, p| body)`, as for
/// [`lagrangian!`](crate::lagrangian).
///
/// ```
/// use noether_core::prelude::*;
/// // Kepler problem in the plane, H = |p|²/2 − k/|q|.
/// let kepler = hamiltonian!(dof = 2, params { k: f64 = 1.0 }, |_t, q, p| {
///     (p[0] * p[0] + p[1] * p[1]) * 0.5 - (q[0] * q[0] + q[1] * q[1]).sqrt().recip() * k
/// });
/// let eqs = HamiltonEquations::new(kepler);
/// assert!((eqs.energy(0.0, &[1.0, 0.0], &[0.0, 1.0]).unwrap() + 0.5).abs() < 1e-15); // circular orbit
/// ```
#[macro_export]
macro_rules! hamiltonian {
    (dof = $dof:expr, |$t:pat_param, $q:pat_param, $p:pat_param| $body:expr $(,)?) => {
        $crate::hamiltonian!(dof = $dof, params {}, |$t, $q, $p| $body)
    };
    (
        dof = $dof:expr,
        params { $($name:ident : $ty:ty = $value:expr),* $(,)? },
        |$t:pat_param, $q:pat_param, $p:pat_param| $body:expr $(,)?
    ) => {
        $crate::__shorthand_model!(
            Hamiltonian::hamiltonian as ShorthandHamiltonian,
            dof = $dof,
            params { $($name: $ty = $value),* },
            |$t, $q, $p| $body
        )
    };
}

/// The expansion shared by [`lagrangian!`](crate::lagrangian) and [`hamiltonian!`](crate::hamiltonian):
/// a struct holding `dof` and the parameters, and the trait impl whose generic method is the body with
/// the parameters bound by name.
#[doc(hidden)]
#[macro_export]
macro_rules! __shorthand_model {
    (
        $trait_:ident :: $method:ident as $model:ident,
        dof = $dof:expr,
        params { $($name:ident : $ty:ty = $value:expr),* },
        |$t:pat_param, $x:pat_param, $y:pat_param| $body:expr
    ) => {{
        /// The model generated by the shorthand macro.
        #[derive(Debug, Clone, Copy)]
        struct $model {
            shorthand_dof: usize,
            $($name: $ty,)*
        }
        impl $crate::$trait_ for $model {
            fn dof(&self) -> usize {
                self.shorthand_dof
            }
            #[allow(unused_variables)]
            fn $method<D: $crate::Scalar>(&self, $t: D, $x: &[D], $y: &[D]) -> D {
                $(let $name = self.$name;)*
                $body
            }
        }
        $model { shorthand_dof: $dof, $($name: $value,)* }
    }};
}

#[cfg(test)]
mod tests {
    use crate::prelude::*;

    /// A pendulum (mass m, length l) hanging from a cart (mass M) on a horizontal rail, q = (x, θ),
    /// written by hand as a trait impl: L = ½ (M + m) ẋ² + m l ẋ θ̇ cos θ + ½ m l² θ̇² + m g l cos θ.
    struct CartPendulum {
        big_m: f64,
        m: f64,
        l: f64,
        g: f64,
    }
    impl Lagrangian for CartPendulum {
        fn dof(&self) -> usize {
            2
        }
        fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
            let Self { big_m, m, l, g } = *self;
            v[0] * v[0] * (0.5 * (big_m + m))
                + v[0] * v[1] * q[1].cos() * (m * l)
                + v[1] * v[1] * (0.5 * m * l * l)
                + q[1].cos() * (m * g * l)
        }
    }

    #[test]
    fn macro_vs_trait_cart_pendulum_accelerations() {
        let (big_m, m, l, g) = (2.5, 0.7, 1.1, 9.81);
        let hand = EulerLagrange::new(CartPendulum { big_m, m, l, g });
        // The same body (a configuration-dependent mass matrix); the parameters come in by value from
        // the surrounding scope.
        let short = EulerLagrange::new(lagrangian!(
            dof = 2,
            params {
                big_m: f64 = big_m,
                m: f64 = m,
                l: f64 = l,
                g: f64 = g
            },
            |_t, q, v| {
                v[0] * v[0] * (0.5 * (big_m + m))
                    + v[0] * v[1] * q[1].cos() * (m * l)
                    + v[1] * v[1] * (0.5 * m * l * l)
                    + q[1].cos() * (m * g * l)
            }
        ));
        for (q, v) in [
            ([0.3, -1.2], [0.5, 2.0]),
            ([2.0, 2.0], [0.0, 0.0]),
            ([-0.7, 3.0], [-4.0, 1.5]),
        ] {
            let (mut a_hand, mut a_short) = ([0.0; 2], [0.0; 2]);
            hand.accelerations(0.0, &q, &v, &mut a_hand).unwrap();
            short.accelerations(0.0, &q, &v, &mut a_short).unwrap();
            // The same code instantiated at the same types: equal to the last bit.
            assert_eq!(a_hand, a_short);
            assert_eq!(
                hand.energy(0.0, &q, &v).unwrap(),
                short.energy(0.0, &q, &v).unwrap()
            );
        }
    }

    #[test]
    fn closed_form_macro_driven_oscillator() {
        // Explicit time dependence through t: a driven oscillator L = ½ q̇² − ½ ω² q² + F cos(Ωt) q,
        // q̈ = −ω² q + F cos(Ωt).
        let driven = lagrangian!(
            dof = 1,
            params {
                w: f64 = 2.0,
                f: f64 = 0.5,
                big_w: f64 = 3.0
            },
            |t, q, v| v[0] * v[0] * 0.5 - q[0] * q[0] * (0.5 * w * w) + (t * big_w).cos() * q[0] * f
        );
        let el = EulerLagrange::new(driven);
        let mut a = [0.0];
        el.accelerations(0.4, &[0.3], &[1.0], &mut a).unwrap();
        let expected = -4.0 * 0.3 + 0.5 * (3.0f64 * 0.4).cos();
        assert!((a[0] - expected).abs() < 1e-14, "{} vs {expected}", a[0]);
    }

    #[test]
    fn macro_vs_trait_hamiltonian_rates() {
        struct Pendulum;
        impl Hamiltonian for Pendulum {
            fn dof(&self) -> usize {
                1
            }
            fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
                p[0] * p[0] * 0.5 - q[0].cos() * 9.81
            }
        }
        let short =
            HamiltonEquations::new(hamiltonian!(dof = 1, |_t, q, p| p[0] * p[0] * 0.5 - q[0].cos() * 9.81));
        let hand = HamiltonEquations::new(Pendulum);
        let (mut dq1, mut dp1, mut dq2, mut dp2) = ([0.0], [0.0], [0.0], [0.0]);
        short.rates(0.0, &[1.1], &[-0.4], &mut dq1, &mut dp1).unwrap();
        hand.rates(0.0, &[1.1], &[-0.4], &mut dq2, &mut dp2).unwrap();
        assert_eq!((dq1, dp1), (dq2, dp2));
        assert!((dp1[0] + 9.81 * 1.1f64.sin()).abs() < 1e-14);
    }
}
