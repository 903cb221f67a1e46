//! The method noether picks when none is named, from what the system declares:
//!
//! | system | default | why |
//! |---|---|---|
//! | [`Natural`] (L = ½ q̇ᵀ M q̇ − V(q), constant M) | [`Composition::kahan_li8`] | separable: explicit, symplectic, order 8 — bounded energy error over long runs at the cost of force evaluations only |
//! | [`SeparableHamiltonian`] (H = T(p) + V(q)) | [`Composition::kahan_li8`] | the same |
//! | [`HamiltonEquations`] (any H) | [`Gauss::gauss6`] | not separable: the implicit Gauss-Legendre method of order 6 is symplectic for any H |
//! | [`EulerLagrange`] (any L) | [`Dop853`], atol = rtol = 1e-9 (its default) | velocities are not canonical, so no symplectic method applies to q̇ directly: error control at a stated tolerance (Legendre-transform the model for a long run) |
//!
//! A fixed-step default needs a step size (`Driver::step_size`); the adaptive one chooses its own. To
//! ask for a tolerance instead, name the method: `Dop853::new(system).tolerances(atol, rtol)?`. Every
//! default is overridden by naming the method directly.
//!
//! `default_method` is implemented for each system and for a reference to it: `sys.default_method()`
//! moves the system into the stepper, `(&sys).default_method()` borrows it, so the system stays at hand
//! for an observer (the energy below) or a second run. Write the borrow as `(&sys)`: method-call syntax
//! picks the owned form first when the system is a local value.
//!
//! ```
//! use noether_core::prelude::*;
//! /// Harmonic oscillator as a natural system: V = ½ q².
//! struct Spring;
//! impl Potential for Spring {
//!     fn dof(&self) -> usize { 1 }
//!     fn potential<D: Scalar>(&self, q: &[D]) -> D { q[0] * q[0] * 0.5 }
//! }
//! let sys = Natural::diagonal(Spring, &[1.0])?;
//! // Borrowed: the energy observer uses `sys` after the stepper was built on it.
//! let sol = Driver::new((&sys).default_method(), State::new(0.0, [1.0], [0.0]))?
//!     .step_size(0.1)?
//!     .observe("energy", |s: &State| sys.energy(s.q.as_slice(), s.v.as_slice()))
//!     .run_until(100.0)?;
//! assert_eq!(sol.method(), "Kahan-Li 8 (17 stages)");
//! assert!((sol.last().q[0] - 100.0f64.cos()).abs() < 1e-9);
//! // h = ½ q̇² + ½ q² = ½ stays within the symplectic method's bounded error.
//! assert!(sol.observed("energy")?.iter().all(|h| (h - 0.5).abs() < 1e-9));
//! // Owned: the stepper keeps the system.
//! let moved = Driver::new(sys.default_method(), State::new(0.0, [1.0], [0.0]))?.step_size(0.1)?.run_until(1.0)?;
//! assert!((moved.last().q[0] - 1.0f64.cos()).abs() < 1e-12);
//! # Ok::<(), noether_core::Error>(())
//! ```

use super::{Composition, Dop853, Gauss, StormerVerlet};
use crate::{EulerLagrange, HamiltonEquations, Hamiltonian, Lagrangian, Natural, Potential, Separable};
use crate::{SeparableHamiltonian, Stepper};

/// The method noether picks for a system when none is named (see the [module](self) table);
/// implemented for each system `S` (the stepper owns it) and for `&S` (the stepper borrows it).
pub trait DefaultMethod: Sized {
    /// The stepper chosen.
    type Method: Stepper;
    /// That stepper on this system.
    fn default_method(self) -> Self::Method;
}

impl<P: Potential> DefaultMethod for Natural<P> {
    type Method = Composition<StormerVerlet<Natural<P>>>;
    fn default_method(self) -> Self::Method {
        Composition::kahan_li8(self)
    }
}

impl<S: Separable> DefaultMethod for SeparableHamiltonian<S> {
    type Method = Composition<StormerVerlet<SeparableHamiltonian<S>>>;
    fn default_method(self) -> Self::Method {
        Composition::kahan_li8(self)
    }
}

impl<H: Hamiltonian> DefaultMethod for HamiltonEquations<H> {
    type Method = Gauss<HamiltonEquations<H>>;
    fn default_method(self) -> Self::Method {
        Gauss::gauss6(self)
    }
}

impl<L: Lagrangian> DefaultMethod for EulerLagrange<L> {
    type Method = Dop853<EulerLagrange<L>>;
    fn default_method(self) -> Self::Method {
        Dop853::new(self)
    }
}

impl<'a, P: Potential> DefaultMethod for &'a Natural<P> {
    type Method = Composition<StormerVerlet<&'a Natural<P>>>;
    fn default_method(self) -> Self::Method {
        Composition::kahan_li8(self)
    }
}

impl<'a, S: Separable> DefaultMethod for &'a SeparableHamiltonian<S> {
    type Method = Composition<StormerVerlet<&'a SeparableHamiltonian<S>>>;
    fn default_method(self) -> Self::Method {
        Composition::kahan_li8(self)
    }
}

impl<'a, H: Hamiltonian> DefaultMethod for &'a HamiltonEquations<H> {
    type Method = Gauss<&'a HamiltonEquations<H>>;
    fn default_method(self) -> Self::Method {
        Gauss::gauss6(self)
    }
}

impl<'a, L: Lagrangian> DefaultMethod for &'a EulerLagrange<L> {
    type Method = Dop853<&'a EulerLagrange<L>>;
    fn default_method(self) -> Self::Method {
        Dop853::new(self)
    }
}
