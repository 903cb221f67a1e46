//! Sensitivities of a run: how the end point y(T) = (q, p)(T) of a numerical run depends on its
//! initial point y₀ and on the model's parameters θ, exact to rounding for the map the method computes.
//!
//! **Initial conditions.** ∂y_N/∂y₀ = Ψ_{N−1} ⋯ Ψ₁ Ψ₀, the product of the step Jacobians of a
//! [`TangentStepper`] (core's [`run_jacobian`]).
//!
//! **Parameters.** A model that declares its parameters differentiable implements
//! [`ParametricHamiltonian`]: H(t, q, p; θ) generic over the scalar in θ as in q and p. The adapter
//! [`Parametric`] makes it an ordinary [`Hamiltonian`] of n + k degrees of freedom whose extra
//! coordinates are θ and whose extra momenta p_θ do not enter H:
//!
//! ```text
//! H̃(q, θ; p, p_θ) = H(q, p; θ),   θ̇ = ∂H̃/∂p_θ = 0 (exactly: θ stays put),   ṗ_θ = −∂H/∂θ (a dummy).
//! ```
//!
//! Any method applied to H̃ takes, in the (q, p) block, the very steps it takes on H with θ frozen (each
//! stage sees the same θ), so ∂y(T)/∂θ is the θ-columns of the augmented run's Jacobian
//! ([`parameter_sensitivity`]). This is forward-mode sensitivity analysis of the discrete map: the
//! variational equations of the method, not a finite difference, and at the cost of a run of 2(n + k)
//! tangent directions.
//!
//! ```
//! use noether_analysis::{parameter_sensitivity, Parametric, ParametricHamiltonian};
//! use noether_core::prelude::*;
//!
//! /// H = ½(p² + ω² q²) with the parameter θ = (ω).
//! struct Oscillator;
//! impl ParametricHamiltonian for Oscillator {
//!     fn dof(&self) -> usize { 1 }
//!     fn parameters(&self) -> usize { 1 }
//!     fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D], theta: &[D]) -> D {
//!         (p[0] * p[0] + theta[0] * theta[0] * q[0] * q[0]) * 0.5
//!     }
//! }
//! let mut rk4 = Rk4::new(HamiltonEquations::new(Parametric::new(Oscillator)));
//! let (t_end, h): (f64, f64) = (2.0, 1e-3);
//! let s = parameter_sensitivity(&mut rk4, &State::with_momenta(0.0, [1.0], [0.0]), &[1.5], h, 2000).unwrap();
//! // q(T) = q₀ cos ωT: ∂q(T)/∂ω = −q₀ T sin ωT.
//! assert!((s.wrt_parameters[(0, 0)] + t_end * (1.5 * t_end).sin()).abs() < 1e-10);
//! ```

use crate::Result;
use nalgebra::DMatrix;
use noether_core::tangent::run_jacobian;
use noether_core::{Hamiltonian, Scalar, State, TangentStepper};

/// A Hamiltonian H(t, q, p; θ) with k parameters θ it is differentiable in: written once, generic over
/// the scalar, θ included.
pub trait ParametricHamiltonian {
    /// Number of coordinates n.
    fn dof(&self) -> usize;
    /// Number of parameters k.
    fn parameters(&self) -> usize;
    /// The value H(t, q, p; θ).
    fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D], theta: &[D]) -> D;
}

/// A [`ParametricHamiltonian`] as a [`Hamiltonian`] of n + k degrees of freedom: coordinates (q, θ),
/// momenta (p, p_θ), with H̃ = H(t, q, p; θ) independent of p_θ, so that θ̇ = 0 exactly.
#[derive(Debug, Clone, Copy, Default)]
pub struct Parametric<P>(pub P);

impl<P: ParametricHamiltonian> Parametric<P> {
    /// Wraps a parametric model.
    pub fn new(model: P) -> Self {
        Parametric(model)
    }

    /// The augmented state ((q, θ), (p, 0)) at time t from a state of the model and the parameters.
    pub fn augment<K: noether_core::Partner>(&self, state: &State<K>, theta: &[f64]) -> Result<State<K>> {
        augment(state, theta, self.0.dof())
    }
}

impl<P: ParametricHamiltonian> Hamiltonian for Parametric<P> {
    fn dof(&self) -> usize {
        self.0.dof() + self.0.parameters()
    }
    #[inline]
    fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D]) -> D {
        let n = self.0.dof();
        self.0.hamiltonian(t, &q[..n], &p[..n], &q[n..])
    }
}

/// The end of a run and its sensitivities.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Sensitivity<K: noether_core::Partner> {
    /// The model's state at the end of the run (n degrees of freedom).
    pub state: State<K>,
    /// ∂y(T)/∂y₀, 2n × 2n, rows and columns ordered (q, p).
    pub wrt_initial: DMatrix<f64>,
    /// ∂y(T)/∂θ, 2n × k, rows ordered (q, p).
    pub wrt_parameters: DMatrix<f64>,
}

/// ∂y(T)/∂y₀ and ∂y(T)/∂θ of a run of `steps` steps of size `h`, for a stepper built on
/// [`Parametric`] (so of n + k degrees of freedom, n = `state.dof()`, k = `theta.len()`).
///
/// The θ-columns of the augmented run's Jacobian, restricted to the rows of (q, p); see the
/// [module documentation](self).
pub fn parameter_sensitivity<S: TangentStepper>(
    stepper: &mut S,
    state: &State<S::Partner>,
    theta: &[f64],
    h: f64,
    steps: usize,
) -> Result<Sensitivity<S::Partner>> {
    let n = state.dof();
    let k = theta.len();
    let big = stepper.dof();
    if big != n + k {
        return Err(noether_core::Error::Dimension {
            what: "stepper degrees of freedom (the model's n plus the k parameters)",
            expected: n + k,
            got: big,
        }
        .into());
    }
    let mut s = augment(state, theta, n)?;
    let jac = run_jacobian(stepper, &mut s, h, steps)?;
    // Rows and columns of (q, p) in the augmented ordering (q, θ, p, p_θ).
    let idx: Vec<usize> = (0..n).chain(big..big + n).collect();
    let wrt_initial = DMatrix::from_fn(2 * n, 2 * n, |i, j| jac[(idx[i], idx[j])]);
    let wrt_parameters = DMatrix::from_fn(2 * n, k, |i, j| jac[(idx[i], n + j)]);
    let end = State::from_parts(s.t, &s.q.as_slice()[..n], &s.v.as_slice()[..n]);
    Ok(Sensitivity {
        state: end,
        wrt_initial,
        wrt_parameters,
    })
}

/// ((q, θ), (v, 0)).
fn augment<K: noether_core::Partner>(state: &State<K>, theta: &[f64], n: usize) -> Result<State<K>> {
    state.validate(n)?;
    noether_core::error::check_finite("parameters θ", theta)?;
    let q: Vec<f64> = state.q.iter().chain(theta).copied().collect();
    let v: Vec<f64> = state
        .v
        .iter()
        .copied()
        .chain(std::iter::repeat_n(0.0, theta.len()))
        .collect();
    Ok(State::from_parts(state.t, q, v))
}
