//! Separable systems of several degrees of freedom: one action per separated coordinate.
//!
//! When the Hamilton-Jacobi equation separates, each coordinate qₖ moves on a curve
//! Hₖ(qₖ, pₖ; α) = αₖ of its own, α the separation constants (the energy among them). The user writes
//! the separated Hamiltonians once, generic in the scalar and in α ([`Separated`]); each action
//! Jₖ(α) = (1/2π) ∮ pₖ dqₖ is a 1-dof action of [`ActionAngle`](super::ActionAngle)'s kind, a
//! libration or a rotation ([`Orbit`]). The frequencies need H as a function of the actions: with the
//! Jacobian ∂Jₖ/∂αⱼ (from ∂pₖ/∂αⱼ = (δₖⱼ − ∂Hₖ/∂αⱼ)/(∂Hₖ/∂pₖ), integrated over the same nodes, with
//! ∂Hₖ/∂αⱼ by a dual number), ω = ∂H/∂J solves (∂J/∂α)ᵀ ω = ∇_α H
//! ([`SeparatedResult::frequencies`]).

use super::{libration_with, rotation_with, velocity, Curve, Libration, Rotation, Settings};
use crate::Result;
use nalgebra::DMatrix;
use noether_core::linalg::DenseFactor;
use noether_core::Scalar;
use num_dual::Dual64;
use std::f64::consts::PI;

/// A system separated into one-degree-of-freedom parts: coordinate k moves on
/// Hₖ(qₖ, pₖ; α) = αₖ, with as many constants α as coordinates.
pub trait Separated {
    /// Number of coordinates (= number of separation constants).
    fn dof(&self) -> usize;
    /// The separated Hamiltonian Hₖ(q, p; α) of coordinate `k`, whose value on the motion is `alpha[k]`.
    fn separated<D: Scalar>(&self, k: usize, alpha: &[D], q: D, p: D) -> D;
}

/// Which kind of periodic motion a separated coordinate performs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Orbit {
    /// A libration in the well around `q_inside`.
    Libration {
        /// A point inside the well.
        q_inside: f64,
    },
    /// A rotation of a coordinate with period `period`, on the branch through (`q0`, ≈ `p_guess`).
    Rotation {
        /// The angle's origin.
        q0: f64,
        /// The coordinate's period (2π for an angle).
        period: f64,
        /// An approximate momentum at q0 (its sign chooses the direction).
        p_guess: f64,
    },
}

/// The separated part k at fixed constants α, as a 1-dof curve.
struct Part<'a, S> {
    system: &'a S,
    k: usize,
    alpha: &'a [f64],
}

impl<S: Separated> Curve for Part<'_, S> {
    fn h<D: Scalar>(&self, q: D, p: D) -> D {
        let alpha: Vec<D> = self.alpha.iter().map(|&a| D::from(a)).collect();
        self.system.separated(self.k, &alpha, q, p)
    }
}

/// Actions of a [`Separated`] system (see the module docs).
#[derive(Debug, Clone)]
pub struct SeparatedActions<S> {
    system: S,
    settings: Settings,
}

/// The actions of a separated system at constants α, their Jacobian and the 1-dof orbits.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct SeparatedResult {
    /// Jₖ, one per coordinate.
    pub actions: Vec<f64>,
    /// ∂Jₖ/∂αⱼ (row k, column j).
    pub jacobian: DMatrix<f64>,
    /// The libration of each coordinate that librates (`None` for a rotation).
    pub librations: Vec<Option<Libration>>,
    /// The rotation of each coordinate that rotates (`None` for a libration).
    pub rotations: Vec<Option<Rotation>>,
}

impl SeparatedResult {
    /// The frequencies ωₖ = ∂H/∂Jₖ for a Hamiltonian H(α) with gradient `energy_gradient` = ∇_α H
    /// ((1, 0, …) when α₀ is the energy): the solution of (∂J/∂α)ᵀ ω = ∇_α H.
    pub fn frequencies(&self, energy_gradient: &[f64]) -> Result<Vec<f64>> {
        let n = self.actions.len();
        noether_core::error::check_len("energy gradient", energy_gradient, n)?;
        let lu = DenseFactor::lu(self.jacobian.transpose()).map_err(|e| e.in_matrix("∂J/∂α"))?;
        let mut w = energy_gradient.to_vec();
        lu.solve_in_place(&mut w);
        Ok(w)
    }
}

impl<S: Separated> SeparatedActions<S> {
    /// Wraps the system, with [`ActionAngle`](super::ActionAngle)'s default quadrature settings.
    pub fn new(system: S) -> Self {
        SeparatedActions {
            system,
            settings: Settings {
                nodes: 16,
                max_nodes: 16384,
                tolerance: 1e-14,
                search_step: 0.05,
            },
        }
    }

    /// The separated system.
    pub fn system(&self) -> &S {
        &self.system
    }

    /// The actions at constants `alpha`, each coordinate moving as `orbits` says.
    pub fn actions(&self, alpha: &[f64], orbits: &[Orbit]) -> Result<SeparatedResult> {
        let n = self.system.dof();
        noether_core::error::check_len("separation constants", alpha, n)?;
        if orbits.len() != n {
            return Err(noether_core::Error::Dimension {
                what: "separated orbits",
                expected: n,
                got: orbits.len(),
            }
            .into());
        }
        let mut result = SeparatedResult {
            actions: vec![0.0; n],
            jacobian: DMatrix::zeros(n, n),
            librations: vec![None; n],
            rotations: vec![None; n],
        };
        for (k, orbit) in orbits.iter().enumerate() {
            let part = Part {
                system: &self.system,
                k,
                alpha,
            };
            // ∂pₖ/∂αⱼ = (δₖⱼ − ∂Hₖ/∂αⱼ)/(∂Hₖ/∂p), integrated with J so that it converges with it.
            let dp: Vec<Box<dyn Fn(f64, f64) -> f64 + '_>> = (0..n)
                .map(|j| {
                    let part = &part;
                    Box::new(move |q: f64, p: f64| {
                        let delta = if j == k { 1.0 } else { 0.0 };
                        (delta - self.d_separated(part, j, q, p)) / velocity(part, q, p)
                    }) as Box<dyn Fn(f64, f64) -> f64>
                })
                .collect();
            let extras: Vec<&dyn Fn(f64, f64) -> f64> = dp.iter().map(|f| f.as_ref()).collect();
            let integrals = match *orbit {
                Orbit::Libration { q_inside } => {
                    let (lib, integrals) =
                        libration_with(&part, alpha[k], q_inside, &self.settings, &extras)?;
                    result.actions[k] = lib.action;
                    result.librations[k] = Some(lib);
                    integrals
                }
                Orbit::Rotation { q0, period, p_guess } => {
                    let (rot, integrals) =
                        rotation_with(&part, alpha[k], q0, period, p_guess, &self.settings, &extras)?;
                    result.actions[k] = rot.action;
                    result.rotations[k] = Some(rot);
                    integrals
                }
            };
            for (j, x) in integrals.into_iter().enumerate() {
                result.jacobian[(k, j)] = x / (2.0 * PI);
            }
        }
        Ok(result)
    }

    /// ∂Hₖ/∂αⱼ at (q, p), by a dual number in αⱼ.
    fn d_separated(&self, part: &Part<'_, S>, j: usize, q: f64, p: f64) -> f64 {
        let alpha: Vec<Dual64> = part
            .alpha
            .iter()
            .enumerate()
            .map(|(i, &a)| {
                if i == j {
                    Dual64::from(a).derivative()
                } else {
                    Dual64::from(a)
                }
            })
            .collect();
        self.system
            .separated(part.k, &alpha, Dual64::from(q), Dual64::from(p))
            .eps
    }
}
