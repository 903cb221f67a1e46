//! The linear-quadratic regulator: the gain K that minimises ∫ (δxᵀ Q δx + δuᵀ R δu) dt for
//! δẋ = A δx + B δu, from the stabilising solution X of the continuous algebraic Riccati equation
//!
//! ```text
//! AᵀX + XA − X B R⁻¹ Bᵀ X + Q = 0,   K = R⁻¹ Bᵀ X,   δu = −K δx,
//! ```
//!
//! (Anderson & Moore, *Optimal Control: Linear Quadratic Methods*, §3.3). No maintained Rust crate
//! solves it on nalgebra, so this module does, by the matrix sign function of the Hamiltonian matrix
//! (Roberts 1971; Byers 1987; Gardiner & Laub 1986; the method of Drake's
//! `ContinuousAlgebraicRiccatiEquation`):
//!
//! ```text
//! H = [[A, −G], [−Q, −Aᵀ]],  G = B R⁻¹ Bᵀ;   Z ← (Z/c + c Z⁻¹)/2,  c = |det Z|^{1/2n}  until Z = sign(H),
//! [W₁₂; W₂₂ + I] X = −[W₁₁ + I; W₂₁]   (least squares),
//! ```
//!
//! since sign(H) [I; X] = [I; X] sign(A − GX) = −[I; X] for the stabilising X. The result is then
//! refined by Newton-Kleinman steps (each a Lyapunov equation FᵀX + XF = −(Q + XGX), F = A − GX,
//! solved through its Kronecker form), which converge quadratically from the sign function's answer,
//! and accepted when the Riccati residual is at rounding level and every eigenvalue of A − BK has a
//! negative real part.

use crate::{Error, Linearization, Result};
use nalgebra::{Complex, DMatrix};
use noether_core::error::check_finite;
use noether_core::linalg::DenseFactor;

/// An LQR design: the gain, the Riccati solution and the closed loop's eigenvalues.
#[derive(Debug, Clone, PartialEq)]
pub struct Lqr {
    /// K = R⁻¹ Bᵀ X (m × 2n): the feedback δu = −K δx.
    pub gain: DMatrix<f64>,
    /// The stabilising solution X of the Riccati equation (symmetric, positive semidefinite); the
    /// optimal cost from δx₀ is δx₀ᵀ X δx₀.
    pub riccati: DMatrix<f64>,
    /// The eigenvalues of A − BK, every one with a negative real part.
    pub closed_loop: Vec<Complex<f64>>,
}

/// Iteration cap of the sign function (it converges quadratically; 10–20 iterations are typical).
const SIGN_ITERATIONS: usize = 100;
/// Newton-Kleinman refinements after the sign function.
const REFINEMENTS: usize = 3;

/// The LQR design for the linearisation `lin` with weights `q` (2n × 2n, symmetric positive
/// semidefinite) and `r` (m × m, symmetric positive definite). Errors: dimensions and non-finite
/// weights; `R` not positive definite; [`Error::NoStabilizingSolution`] when (A, B) is not
/// stabilisable or (Q, A) not detectable (the Hamiltonian matrix then has eigenvalues on the
/// imaginary axis and the sign iteration does not settle, or the solution does not stabilise).
pub fn lqr(lin: &Linearization, q: &DMatrix<f64>, r: &DMatrix<f64>) -> Result<Lqr> {
    let (a, b) = (&lin.a, &lin.b);
    let (n, m) = (a.nrows(), b.ncols());
    for (what, mat, rows) in [("LQR weight Q", q, n), ("LQR weight R", r, m)] {
        if mat.nrows() != rows || mat.ncols() != rows {
            return Err(noether_core::Error::Dimension {
                what,
                expected: rows,
                got: if mat.nrows() != rows {
                    mat.nrows()
                } else {
                    mat.ncols()
                },
            }
            .into());
        }
        check_finite(what, mat.as_slice())?;
    }
    let r_factor = DenseFactor::symmetric(r.clone()).map_err(|e| e.in_matrix("LQR weight R"))?;
    if r_factor.cholesky().is_none() {
        return Err(noether_core::Error::InvalidParameter {
            name: "LQR weight R",
            value: r.symmetric_eigenvalues().min(),
            reason: "must be positive definite (its smallest eigenvalue is given)",
        }
        .into());
    }
    let rinv_bt = r_factor.solve_matrix(&b.transpose());
    let g = b * &rinv_bt;
    let mut x = sign_solution(a, &g, q)?;
    // The sign function's X must already stabilise (Newton-Kleinman keeps a stabilising X
    // stabilising; from any other its Lyapunov operator may be singular).
    let (residual, worst) = check(a, &g, q, &x);
    if worst.is_nan() || worst >= 0.0 {
        return Err(Error::NoStabilizingSolution {
            residual,
            largest_real_part: worst,
        });
    }
    for _ in 0..REFINEMENTS {
        x = kleinman_step(a, &g, q, &x).map_err(|_| Error::NoStabilizingSolution {
            residual,
            largest_real_part: worst,
        })?;
    }
    let (residual, worst) = check(a, &g, q, &x);
    if !(residual <= 1e-10 && worst < 0.0) {
        return Err(Error::NoStabilizingSolution {
            residual,
            largest_real_part: worst,
        });
    }
    let gain = &rinv_bt * &x;
    let closed_loop: Vec<Complex<f64>> = (a - b * &gain).complex_eigenvalues().iter().copied().collect();
    Ok(Lqr {
        gain,
        riccati: x,
        closed_loop,
    })
}

/// The Riccati residual ‖AᵀX + XA − XGX + Q‖ relative to the scale of its terms, and the largest
/// real part of the eigenvalues of A − GX (= A − BK).
fn check(a: &DMatrix<f64>, g: &DMatrix<f64>, q: &DMatrix<f64>, x: &DMatrix<f64>) -> (f64, f64) {
    let residual = (a.transpose() * x + x * a - x * g * x + q).amax();
    let scale = (a.amax() * x.amax()).max(q.amax()).max(f64::MIN_POSITIVE);
    let worst = (a - g * x)
        .complex_eigenvalues()
        .iter()
        .map(|l| l.re)
        .fold(f64::NEG_INFINITY, f64::max);
    (residual / scale, worst)
}

/// X from the sign of the Hamiltonian matrix (module docs).
fn sign_solution(a: &DMatrix<f64>, g: &DMatrix<f64>, q: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let n = a.nrows();
    let mut z = DMatrix::zeros(2 * n, 2 * n);
    z.view_mut((0, 0), (n, n)).copy_from(a);
    z.view_mut((0, n), (n, n)).copy_from(&(-g));
    z.view_mut((n, 0), (n, n)).copy_from(&(-q));
    z.view_mut((n, n), (n, n)).copy_from(&(-a.transpose()));
    let no_solution = |residual: f64| Error::NoStabilizingSolution {
        residual,
        largest_real_part: f64::NAN,
    };
    let mut settled = false;
    for _ in 0..SIGN_ITERATIONS {
        let lu = z.clone().lu();
        // ln |det Z| from the pivots (det itself overflows for large n).
        let log_det: f64 = lu.u().diagonal().iter().map(|d| d.abs().ln()).sum();
        let Some(inv) = lu.try_inverse().filter(|_| log_det.is_finite()) else {
            // An eigenvalue of H at 0: on the imaginary axis.
            return Err(no_solution(f64::INFINITY));
        };
        let c = (log_det / (2 * n) as f64).exp();
        let next = (&z / c + inv * c) * 0.5;
        let change = (&next - &z).amax() / next.amax();
        z = next;
        if change <= 1e-13 {
            settled = true;
            break;
        }
    }
    if !settled {
        return Err(no_solution(f64::INFINITY));
    }
    let identity = DMatrix::<f64>::identity(n, n);
    let mut lhs = DMatrix::zeros(2 * n, n);
    lhs.view_mut((0, 0), (n, n)).copy_from(&z.view((0, n), (n, n)));
    lhs.view_mut((n, 0), (n, n))
        .copy_from(&(z.view((n, n), (n, n)) + &identity));
    let mut rhs = DMatrix::zeros(2 * n, n);
    rhs.view_mut((0, 0), (n, n))
        .copy_from(&(-(z.view((0, 0), (n, n)) + &identity)));
    rhs.view_mut((n, 0), (n, n)).copy_from(&(-z.view((n, 0), (n, n))));
    let x = lhs
        .svd(true, true)
        .solve(&rhs, f64::EPSILON)
        .map_err(|_| no_solution(f64::INFINITY))?;
    Ok((&x + x.transpose()) * 0.5)
}

/// One Newton-Kleinman step: X' solving FᵀX' + X'F = −(Q + XGX), F = A − GX, by its Kronecker form
/// (I ⊗ Fᵀ + Fᵀ ⊗ I) vec X' = −vec(Q + XGX) (n² unknowns: the linearisations here are small).
fn kleinman_step(
    a: &DMatrix<f64>,
    g: &DMatrix<f64>,
    q: &DMatrix<f64>,
    x: &DMatrix<f64>,
) -> Result<DMatrix<f64>> {
    let n = a.nrows();
    let f = a - g * x;
    let c = -(q + x * g * x);
    let ft = f.transpose();
    let identity = DMatrix::<f64>::identity(n, n);
    let kron = identity.kronecker(&ft) + ft.kronecker(&identity);
    let factor =
        DenseFactor::lu(kron).map_err(|e| e.in_matrix("Lyapunov operator of the Newton-Kleinman step"))?;
    let mut v = c.as_slice().to_vec();
    factor.solve_in_place(&mut v);
    let next = DMatrix::from_column_slice(n, n, &v);
    Ok((&next + next.transpose()) * 0.5)
}
