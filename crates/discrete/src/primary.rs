//! The primary constraint of a degenerate Lagrangian, checked at the start of a variational run.
//!
//! Where the mass matrix M = ∂²L/∂q̇² is singular, the momenta p = ∂L/∂q̇ cannot take every value at a
//! position q: for L = ½q̇ᵀMq̇ + a(q)·q̇ − V(q) (L linear in q̇ when M = 0: a point vortex, a guiding
//! centre) p − a(q) lies in the range of M, and the component of p along the null space of M is fixed,
//! p·u = a(q)·u for every u with Mu = 0 (the primary constraint). A state (q₀, p₀) off it has no motion,
//! yet the discrete Legendre map p₀ = −D₁L_d(q₀, q₁) can still be solved for q₁: the step then jumps by
//! about 2Ω⁻¹(p₀ − a(q₀)) (Ω = Da − Daᵀ) whatever h is, and the offset persists with alternating sign
//! (the parasitic mode of variational integrators of degenerate Lagrangians; Rowley & Marsden,
//! *Variational integrators for degenerate Lagrangians, with application to point vortices*, CDC 2002).
//!
//! [`check`] measures the residual ‖Uᵀ(p − ∂L/∂q̇(t, q, 0))‖₂, U an orthonormal basis of the null
//! space of M(t, q, 0) (eigenvalues at most [`SINGULAR_PIVOT`] times the largest, all of them when
//! M = 0), and refuses the state with [`OffPrimaryConstraint`] when it exceeds τ·max(‖p‖₂,
//! ‖∂L/∂q̇(t, q, 0)‖₂). Evaluating at q̇ = 0 is exact for L at most quadratic in q̇ (p − ∂L/∂q̇(q, 0) =
//! Mq̇ then); for other degenerate Lagrangians it is the constraint at rest.

use nalgebra::{DVector, SymmetricEigen};
use noether_core::linalg::{self, SINGULAR_PIVOT};
use noether_core::{EulerLagrange, Lagrangian, Result};

/// Default relative tolerance τ of the primary-constraint check: a state is refused when its momenta
/// are off the constraint by more than τ·max(‖p‖₂, ‖∂L/∂q̇(t, q, 0)‖₂).
///
/// Why 1e-8: momenta built by the Legendre map ([`state_from_velocities`](crate::VariationalIntegrator::state_from_velocities))
/// and the momenta of a midpoint run are on the constraint to rounding (~1e-16 relative); an offset δ
/// moves the next position by ~2|δ|/|Ω| whatever the step, so 1e-8 of the momentum (the default
/// constraint tolerance of noether-constraints) bounds that jump at 1e-8 of the scale of a(q).
pub const DEFAULT_TOLERANCE: f64 = 1e-8;

/// A state whose momenta are off the primary constraint of a degenerate Lagrangian (see the module
/// docs), refused by a variational integrator before its step. Travels through core's interfaces as
/// [`noether_core::Error::Model`]: get it back as [`crate::Error::OffPrimaryConstraint`] by
/// `noether_discrete::Error::from(e)`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "momenta off the primary constraint of a degenerate Lagrangian at t = {t}: ‖p − ∂L/∂q̇(q, 0)‖ = {residual:e} \
     along the {null_directions} direction(s) where ∂²L/∂q̇² is singular (tolerance {tolerance:e}); \
     a state from the Legendre map p = ∂L/∂q̇(t, q, q̇) is on it"
)]
#[non_exhaustive]
pub struct OffPrimaryConstraint {
    /// Time of the state.
    pub t: f64,
    /// ‖Uᵀ(p − ∂L/∂q̇(t, q, 0))‖₂, U an orthonormal basis of the null space of ∂²L/∂q̇².
    pub residual: f64,
    /// The absolute bound it exceeded: τ·max(‖p‖₂, ‖∂L/∂q̇(t, q, 0)‖₂).
    pub tolerance: f64,
    /// Dimension of the null space of ∂²L/∂q̇² at (t, q, 0).
    pub null_directions: usize,
}

/// Checks that the momenta `p` at (t, q) lie on the primary constraint of `el`'s Lagrangian to the
/// relative tolerance `tol` (module docs). A regular Lagrangian passes at the cost of one mass matrix
/// and its factorization (none when it declares a constant mass matrix: the cached factor is reused);
/// where M(t, q, 0) is not defined (non-finite) there is nothing to check against and the state passes.
pub fn check<L: Lagrangian>(el: &EulerLagrange<L>, t: f64, q: &[f64], p: &[f64], tol: f64) -> Result<()> {
    let zero = vec![0.0; q.len()];
    if el.lagrangian().constant_mass_matrix() && el.mass_factor(t, q, &zero).is_ok() {
        return Ok(());
    }
    let Ok(m) = el.mass_matrix(t, q, &zero) else {
        return Ok(());
    };
    if linalg::factor_mass(m.clone(), t).is_ok() {
        return Ok(());
    }
    let eig = SymmetricEigen::new(m);
    let scale = eig.eigenvalues.amax();
    let null: Vec<usize> = (0..q.len())
        .filter(|&i| eig.eigenvalues[i].abs() <= SINGULAR_PIVOT * scale)
        .collect();
    if null.is_empty() {
        return Ok(());
    }
    let mut pi0 = vec![0.0; q.len()];
    el.momenta(t, q, &zero, &mut pi0)?;
    let (p, pi0) = (DVector::from_column_slice(p), DVector::from_vec(pi0));
    let d = &p - &pi0;
    let residual = null
        .iter()
        .map(|&i| eig.eigenvectors.column(i).dot(&d).powi(2))
        .sum::<f64>()
        .sqrt();
    let tolerance = tol * p.norm().max(pi0.norm());
    if residual > tolerance {
        return Err(OffPrimaryConstraint {
            t,
            residual,
            tolerance,
            null_directions: null.len(),
        }
        .into());
    }
    Ok(())
}
