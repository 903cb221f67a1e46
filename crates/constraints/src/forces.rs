//! Constraint forces: the multipliers as generalized forces Aᵀλ and, in Cartesian models, as physical
//! force vectors on each particle.

use nalgebra::{DMatrix, DVector};

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
    pub fn of_constraint(&self, k: usize) -> DVector<f64> {
        self.matrix.row(k).transpose() * self.lambda[k]
    }

    /// The physical force of all constraints on particle i of a Cartesian model with `dim` coordinates
    /// per particle.
    pub fn on_particle(&self, i: usize, dim: usize) -> &[f64] {
        &self.generalized.as_slice()[dim * i..dim * (i + 1)]
    }

    /// The physical force of constraint k on particle i (Cartesian model, `dim` coordinates per particle).
    pub fn of_constraint_on_particle(&self, k: usize, i: usize, dim: usize) -> Vec<f64> {
        (dim * i..dim * (i + 1))
            .map(|j| self.matrix[(k, j)] * self.lambda[k])
            .collect()
    }
}
