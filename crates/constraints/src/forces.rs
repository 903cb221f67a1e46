//! Constraint forces: the multipliers as generalized forces Aᵀλ and, in Cartesian models, as physical
//! force vectors on each particle.

use crate::Result;
use nalgebra::{DMatrix, DVector};
use noether_core::Error as CoreError;

/// The constraint forces at one state.
///
/// The generalized constraint force is Q_c = Aᵀλ = Σ_k λ_k ∇φ_k (for holonomic constraints A = Φ_q).
/// When the coordinates are Cartesian, particle i's coordinates are `dim·i .. dim·(i+1)` and the
/// matching components of Q_c are the physical force the constraints exert on it.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintForces {
    /// The constraint matrix A (m × n) at the state.
    pub matrix: DMatrix<f64>,
    /// The multipliers λ (length m).
    pub lambda: DVector<f64>,
    /// The generalized constraint force Aᵀλ (length n).
    pub generalized: DVector<f64>,
}

impl ConstraintForces {
    /// From the constraint matrix and the multipliers.
    pub fn new(matrix: DMatrix<f64>, lambda: DVector<f64>) -> Self {
        let generalized = matrix.tr_mul(&lambda);
        ConstraintForces {
            matrix,
            lambda,
            generalized,
        }
    }

    /// The generalized force of constraint k alone, λ_k A_kᵀ (length n).
    pub fn of_constraint(&self, k: usize) -> Result<DVector<f64>> {
        self.constraint_index(k)?;
        Ok(self.matrix.row(k).transpose() * self.lambda[k])
    }

    /// The physical force of all constraints on particle i of a Cartesian model with `dim` coordinates
    /// per particle.
    pub fn on_particle(&self, i: usize, dim: usize) -> Result<&[f64]> {
        let range = self.particle_range(i, dim)?;
        Ok(&self.generalized.as_slice()[range])
    }

    /// The physical force of constraint k on particle i (Cartesian model, `dim` coordinates per particle).
    pub fn of_constraint_on_particle(&self, k: usize, i: usize, dim: usize) -> Result<Vec<f64>> {
        self.constraint_index(k)?;
        Ok(self
            .particle_range(i, dim)?
            .map(|j| self.matrix[(k, j)] * self.lambda[k])
            .collect())
    }

    /// An error unless k names a constraint.
    fn constraint_index(&self, k: usize) -> Result<()> {
        if k < self.lambda.len() {
            return Ok(());
        }
        Err(CoreError::InvalidParameter {
            name: "constraint index",
            value: k as f64,
            reason: "no such constraint",
        }
        .into())
    }

    /// The coordinates dim·i .. dim·(i + 1) of particle i, or an error when they do not exist.
    fn particle_range(&self, i: usize, dim: usize) -> Result<std::ops::Range<usize>> {
        let n = self.generalized.len();
        match (dim.checked_mul(i), dim.checked_mul(i + 1)) {
            (Some(a), Some(b)) if dim > 0 && b <= n => Ok(a..b),
            _ => Err(CoreError::InvalidParameter {
                name: "particle index",
                value: i as f64,
                reason: "no such particle (or a dimension of 0) in the Cartesian coordinates",
            }
            .into()),
        }
    }
}
