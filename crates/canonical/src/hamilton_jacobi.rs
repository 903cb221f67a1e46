//! Hamilton-Jacobi theory: a complete integral S(q, α, t) written as generic code, the residual of
//! the Hamilton-Jacobi equation, and the motion from Jacobi's theorem.
//!
//! S is a complete integral of H when it solves
//!
//! ```text
//! H(q, ∂S/∂q, t) + ∂S/∂t = 0      with det ∂²S/∂q∂α ≠ 0
//! ```
//!
//! for n constants α (ch. 78; S is then an F1 generating function to new variables (α, −β) of a
//! zero Hamiltonian). Jacobi's theorem: along every motion β = ∂S/∂α is constant and p = ∂S/∂q, so
//! the motion is the solution q(t) of the n equations ∂S/∂α(q, α, t) = β. [`constants`] finds
//! (α, β) from an initial state (Newton on ∂S/∂q(q₀, α, t₀) = p₀), [`position`] solves for q(t) (Newton
//! on ∂S/∂α = β), both with core's Newton and the mixed Hessian ∂²S/∂q∂α by core's AD; [`residual`]
//! evaluates the Hamilton-Jacobi equation.

use crate::poisson::check_point;
use crate::{Error, Result};
use nalgebra::DMatrix;
use noether_core::ad::{self, Block, Field};
use noether_core::error::{check_result, finite_result};
use noether_core::newton::{solve_dense, DenseProblem};
use noether_core::{Hamiltonian, Newton, Scalar};

/// A complete integral S(q, α, t) of n = `dof()` coordinates and n constants α, written once as
/// generic code.
pub trait CompleteIntegral {
    /// Number n of coordinates (and of constants α).
    fn dof(&self) -> usize;
    /// Hamilton's principal function S(q, α, t).
    fn principal<D: Scalar>(&self, t: D, q: &[D], alpha: &[D]) -> D;
}

/// S seen as core's AD field f(t, x = q, y = α).
struct SField<'a, S>(&'a S);

impl<S: CompleteIntegral> Field for SField<'_, S> {
    #[inline]
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D]) -> D {
        self.0.principal(t, x, y)
    }
}

fn gradient<S: CompleteIntegral>(s: &S, t: f64, q: &[f64], alpha: &[f64], block: Block) -> Result<Vec<f64>> {
    check_point(s.dof(), t, q, alpha)?;
    let mut out = vec![0.0; s.dof()];
    ad::gradient(&SField(s), t, q, alpha, block, &mut out);
    check_result("gradient of the complete integral", t, &out)?;
    Ok(out)
}

/// The momenta p = ∂S/∂q at (t, q) for the constants α.
pub fn momenta<S: CompleteIntegral>(s: &S, t: f64, q: &[f64], alpha: &[f64]) -> Result<Vec<f64>> {
    gradient(s, t, q, alpha, Block::X)
}

/// β = ∂S/∂α at (t, q) for the constants α (constant along the motion, by Jacobi's theorem).
pub fn betas<S: CompleteIntegral>(s: &S, t: f64, q: &[f64], alpha: &[f64]) -> Result<Vec<f64>> {
    gradient(s, t, q, alpha, Block::Y)
}

/// The residual H(q, ∂S/∂q, t) + ∂S/∂t of the Hamilton-Jacobi equation at (t, q) for the constants
/// α (0 to rounding for a complete integral of H).
pub fn residual<S: CompleteIntegral, H: Hamiltonian>(
    s: &S,
    h: &H,
    t: f64,
    q: &[f64],
    alpha: &[f64],
) -> Result<f64> {
    if h.dof() != s.dof() {
        return Err(Error::PhaseSpaceMismatch {
            first: s.dof(),
            second: h.dof(),
        });
    }
    let p = momenta(s, t, q, alpha)?;
    let st = finite_result("∂S/∂t", t, ad::partial_t(&SField(s), t, q, alpha))?;
    let e = noether_core::HamiltonEquations::new(h).energy(t, q, &p)?;
    Ok(finite_result("Hamilton-Jacobi residual", t, e + st)?)
}

/// ∇_block S − target = 0 for the other block.
struct Jacobi<'a, S> {
    s: &'a S,
    t: f64,
    /// The fixed block's values (q when solving for α, α when solving for q).
    fixed: &'a [f64],
    target: &'a [f64],
    /// `true`: solve ∂S/∂q(q fixed, α) = p for α; `false`: solve ∂S/∂α(q, α fixed) = β for q.
    for_alpha: bool,
}

impl<S: CompleteIntegral> Jacobi<'_, S> {
    fn args<'b>(&'b self, u: &'b [f64]) -> (&'b [f64], &'b [f64]) {
        if self.for_alpha {
            (self.fixed, u)
        } else {
            (u, self.fixed)
        }
    }
}

impl<S: CompleteIntegral> DenseProblem for Jacobi<'_, S> {
    fn dim(&self) -> usize {
        self.s.dof()
    }
    fn residual(&mut self, u: &[f64], r: &mut [f64]) -> noether_core::Result<()> {
        let (q, a) = self.args(u);
        let block = if self.for_alpha { Block::X } else { Block::Y };
        ad::gradient(&SField(self.s), self.t, q, a, block, r);
        for (ri, ti) in r.iter_mut().zip(self.target) {
            *ri -= ti;
        }
        Ok(())
    }
    fn jacobian(&mut self, u: &[f64], j: &mut DMatrix<f64>) -> noether_core::Result<()> {
        let (q, a) = self.args(u);
        let (ra, cb) = if self.for_alpha {
            (Block::X, Block::Y)
        } else {
            (Block::Y, Block::X)
        };
        ad::hessian(&SField(self.s), self.t, q, a, ra, cb, j);
        Ok(())
    }
}

fn solve<S: CompleteIntegral>(newton: &Newton, problem: Jacobi<'_, S>, guess: &[f64]) -> Result<Vec<f64>> {
    let t = problem.t;
    let (u, _) = solve_dense(newton, problem, guess).map_err(|e| match e {
        noether_core::Error::SingularMatrix { pivot_ratio, .. } => {
            Error::DegenerateCompleteIntegral { t, pivot_ratio }
        }
        other => other.into(),
    })?;
    check_result("Jacobi's theorem", t, u.as_slice())?;
    Ok(u.as_slice().to_vec())
}

/// The constants (α, β) of the motion through (q₀, p₀) at t₀: α solves ∂S/∂q(q₀, α, t₀) = p₀ by
/// Newton from `guess_alpha`, then β = ∂S/∂α(q₀, α, t₀).
pub fn constants<S: CompleteIntegral>(
    s: &S,
    t0: f64,
    (q0, p0): (&[f64], &[f64]),
    guess_alpha: &[f64],
    newton: &Newton,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let n = s.dof();
    check_point(n, t0, q0, p0)?;
    check_point(n, t0, q0, guess_alpha)?;
    let problem = Jacobi {
        s,
        t: t0,
        fixed: q0,
        target: p0,
        for_alpha: true,
    };
    let alpha = solve(newton, problem, guess_alpha)?;
    let beta = betas(s, t0, q0, &alpha)?;
    Ok((alpha, beta))
}

/// The state (q, p) at time t of the motion with constants (α, β): q solves ∂S/∂α(q, α, t) = β by
/// Newton from `guess_q` (take the last position along a trajectory), then p = ∂S/∂q.
pub fn position<S: CompleteIntegral>(
    s: &S,
    t: f64,
    (alpha, beta): (&[f64], &[f64]),
    guess_q: &[f64],
    newton: &Newton,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let n = s.dof();
    check_point(n, t, alpha, beta)?;
    check_point(n, t, guess_q, alpha)?;
    let problem = Jacobi {
        s,
        t,
        fixed: alpha,
        target: beta,
        for_alpha: false,
    };
    let q = solve(newton, problem, guess_q)?;
    let p = momenta(s, t, &q, alpha)?;
    Ok((q, p))
}
