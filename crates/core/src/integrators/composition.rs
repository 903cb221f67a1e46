//! Symmetric composition of a one-step map over a signed step:
//!
//! ```text
//! Ψ_h = Φ_{γ_s h} ∘ … ∘ Φ_{γ₁ h},      Σ γ_i = 1,   γ_i = γ_{s+1−i}   (the [`Weights`]),
//! ```
//!
//! of order p + 2 (and more, by the weights) from a symmetric base Φ of even order p; when Φ is
//! symplectic (a variational integrator, Störmer-Verlet) so is Ψ. Some weights are negative, so the
//! base must step backward too: a [`SignedStepper`]. [`Composition`] composes any of them:
//! - core's kick-drift-kick [`StormerVerlet`](super::StormerVerlet) on a
//!   [`SplitDynamics`](crate::system::SplitDynamics) system ([`Composition::kahan_li8`] and the
//!   other named constructors), which fuses adjacent half kicks ([`SignedStepper::step_composed`]
//!   overridden);
//! - the variational integrators of noether-discrete, substep after substep (the default
//!   [`SignedStepper::step_composed`]), with Ψ by the chain rule Ψ = Ψ_s ⋯ Ψ₁
//!   ([`SignedTangentStepper::step_composed_tangent`]).
//!
//! # References
//! E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., §II.4 and §V.3;
//! H. Yoshida, Phys. Lett. A 150 (1990) 262.

use super::Weights;
use crate::error::{check_step, check_time_resolution};
use crate::tangent::check_tangent_shape;
use crate::{Error, Result, State, StepInfo, Stepper, TangentStepper};
use nalgebra::DMatrix;

/// A one-step map Φ_h defined for steps of either sign: `h` finite and non-zero, a negative `h` runs
/// time backward (a symmetric composition takes backward substeps). Its [`Stepper::step`] is the
/// forward case ([`step_forward`]).
pub trait SignedStepper: Stepper {
    /// Advances `state` (time included: t ← t + h) by the signed step `h`; on error the state is left
    /// exactly as it was. Checks `h` and the state, not the time resolution (a substep is part of a
    /// step whose time resolution the caller checked).
    fn step_signed(&mut self, state: &mut State<Self::Partner>, h: f64) -> Result<StepInfo>;

    /// Ψ_h = Φ_{γ_s h} ∘ … ∘ Φ_{γ₁ h} with the [`Weights`] γ, t ← t + h at the end; on error the state
    /// is left as it was. The default takes the substeps one after another on a copy of the state and
    /// adds up their statistics; a base whose adjacent substeps share work (kick-drift-kick: the half
    /// kicks merge) overrides it.
    fn step_composed(
        &mut self,
        weights: &Weights,
        state: &mut State<Self::Partner>,
        h: f64,
    ) -> Result<StepInfo> {
        let t = state.t;
        let mut work = state.clone();
        let mut total = StepInfo::fixed(h);
        for &g in weights.as_slice() {
            add_counts(&mut total, self.step_signed(&mut work, g * h)?);
        }
        work.t = t + h;
        *state = work;
        Ok(total)
    }
}

/// A [`SignedStepper`] that also gives the Jacobian Ψ = ∂(q', v')/∂(q, v) of its map (2n × 2n,
/// ordered (q, v)), for steps of either sign.
pub trait SignedTangentStepper: SignedStepper {
    /// Advances `state` exactly as [`SignedStepper::step_signed`] and writes Ψ into `psi`; on error
    /// `state` and `psi` are left exactly as they were.
    fn step_signed_tangent(
        &mut self,
        state: &mut State<Self::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo>;

    /// [`SignedStepper::step_composed`] and its Ψ; the default is the chain rule over the substeps,
    /// Ψ = Ψ_s ⋯ Ψ₁, each Ψ_i at the point its substep starts from.
    fn step_composed_tangent(
        &mut self,
        weights: &Weights,
        state: &mut State<Self::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        let (t, n) = (state.t, self.dof());
        check_tangent_shape(psi, n)?;
        let mut work = state.clone();
        let mut total = DMatrix::identity(2 * n, 2 * n);
        let mut stage = DMatrix::zeros(2 * n, 2 * n);
        let mut sum = StepInfo::fixed(h);
        for &g in weights.as_slice() {
            add_counts(&mut sum, self.step_signed_tangent(&mut work, g * h, &mut stage)?);
            total = &stage * total;
        }
        work.t = t + h;
        *state = work;
        psi.copy_from(&total);
        Ok(sum)
    }
}

/// Adds a substep's evaluations, Newton iterations and Newton failures to the step's.
fn add_counts(total: &mut StepInfo, substep: StepInfo) {
    total.evaluations += substep.evaluations;
    total.newton_iterations += substep.newton_iterations;
    total.newton_failures += substep.newton_failures;
}

/// `InvalidStep` unless the signed step `h` is finite and non-zero; then the state's lengths and
/// finiteness. The checks of [`SignedStepper::step_signed`].
pub fn check_signed_step<P: crate::Partner>(dof: usize, state: &State<P>, h: f64) -> Result<()> {
    if !h.is_finite() || h == 0.0 {
        return Err(Error::InvalidStep { h });
    }
    state.validate(dof)
}

/// [`Stepper::step`] of a [`SignedStepper`]: `h` positive, the state valid, the time axis resolving
/// t + h ([`check_time_resolution`]), then [`SignedStepper::step_signed`].
pub fn step_forward<S: SignedStepper + ?Sized>(
    stepper: &mut S,
    state: &mut State<S::Partner>,
    h: f64,
) -> Result<StepInfo> {
    check_forward(stepper.dof(), state, h)?;
    stepper.step_signed(state, h)
}

/// The checks of a forward step: `h` finite and positive, the state valid, the time axis resolving
/// t + h.
fn check_forward<P: crate::Partner>(dof: usize, state: &State<P>, h: f64) -> Result<()> {
    check_step(h)?;
    state.validate(dof)?;
    check_time_resolution(state.t, h)
}

/// [`TangentStepper::step_tangent`] of a [`SignedTangentStepper`]: the checks of [`step_forward`],
/// Ψ's shape, then [`SignedTangentStepper::step_signed_tangent`].
pub fn step_forward_tangent<S: SignedTangentStepper + ?Sized>(
    stepper: &mut S,
    state: &mut State<S::Partner>,
    h: f64,
    psi: &mut DMatrix<f64>,
) -> Result<StepInfo> {
    check_forward(stepper.dof(), state, h)?;
    check_tangent_shape(psi, stepper.dof())?;
    stepper.step_signed_tangent(state, h, psi)
}

/// The symmetric composition Ψ_h = Φ_{γ_s h} ∘ … ∘ Φ_{γ₁ h} of a signed base method Φ with validated
/// [`Weights`] (see the [module](self) docs). Its order and name are those of the weights.
///
/// ```
/// use noether_core::prelude::*;
/// use noether_core::integrators::{StormerVerlet, Weights};
/// struct Spring;
/// impl Potential for Spring {
///     fn dof(&self) -> usize { 1 }
///     fn potential<D: Scalar>(&self, q: &[D]) -> D { q[0] * q[0] * 0.5 }
/// }
/// let sys = Natural::unit(Spring);
/// // The same method, named or spelled out:
/// let mut a = Composition::yoshida4(&sys);
/// let mut b = Composition::new(StormerVerlet::new(&sys), Weights::yoshida4());
/// let (mut sa, mut sb) = (State::new(0.0, [1.0], [0.0]), State::new(0.0, [1.0], [0.0]));
/// a.step(&mut sa, 0.1)?;
/// b.step(&mut sb, 0.1)?;
/// assert_eq!(sa, sb);
/// assert_eq!((a.order(), a.name()), (4, "Yoshida 4 (triple jump)"));
/// # Ok::<(), noether_core::Error>(())
/// ```
pub struct Composition<B> {
    base: B,
    weights: Weights,
}

impl<B: SignedStepper> Composition<B> {
    /// The composition of `base` with `weights`.
    pub fn new(base: B, weights: Weights) -> Self {
        Composition { base, weights }
    }
    /// The weights γ₁, …, γ_s.
    pub fn weights(&self) -> &Weights {
        &self.weights
    }
    /// The base method Φ.
    pub fn base(&self) -> &B {
        &self.base
    }
    /// The base method Φ, mutably (e.g. to read its last Newton statistics).
    pub fn base_mut(&mut self) -> &mut B {
        &mut self.base
    }
}

impl<B: SignedStepper> Stepper for Composition<B> {
    type Partner = B::Partner;
    fn step(&mut self, state: &mut State<B::Partner>, h: f64) -> Result<StepInfo> {
        check_forward(self.base.dof(), state, h)?;
        self.base.step_composed(&self.weights, state, h)
    }
    fn rates(&self, state: &State<B::Partner>, dq: &mut [f64], dv: &mut [f64]) -> Option<Result<()>> {
        self.base.rates(state, dq, dv)
    }
    fn dof(&self) -> usize {
        self.base.dof()
    }
    fn order(&self) -> u32 {
        self.weights.order()
    }
    fn name(&self) -> &'static str {
        self.weights.name()
    }
}

/// A composition is itself a signed map (Ψ_{−h} is defined when Φ_{−h} is), so it composes again.
impl<B: SignedStepper> SignedStepper for Composition<B> {
    fn step_signed(&mut self, state: &mut State<B::Partner>, h: f64) -> Result<StepInfo> {
        check_signed_step(self.base.dof(), state, h)?;
        self.base.step_composed(&self.weights, state, h)
    }
}

impl<B: SignedTangentStepper> SignedTangentStepper for Composition<B> {
    fn step_signed_tangent(
        &mut self,
        state: &mut State<B::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        check_signed_step(self.base.dof(), state, h)?;
        self.base.step_composed_tangent(&self.weights, state, h, psi)
    }
}

/// Ψ of the composition, from the base's [`SignedTangentStepper::step_composed_tangent`].
impl<B: SignedTangentStepper> TangentStepper for Composition<B> {
    fn step_tangent(
        &mut self,
        state: &mut State<B::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        check_forward(self.base.dof(), state, h)?;
        check_tangent_shape(psi, self.base.dof())?;
        self.base.step_composed_tangent(&self.weights, state, h, psi)
    }
}
