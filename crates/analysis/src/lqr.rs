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
//!
//! [`dlqr`] is the same design for a sampled system δx_{k+1} = A δx_k + B δu_k (one step of an
//! integrator, [`linearize_step`](crate::linearize_step)): the discrete Riccati equation by
//! structure-preserving doubling, refined by Hewer's Newton steps, accepted by the same rule with the
//! closed loop's eigenvalues inside the unit circle.

use crate::{Error, Linearization, Result, StepLinearization};
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

impl Lqr {
    /// The design of gain K and Riccati solution X, with the eigenvalues of A − BK.
    fn new(a: &DMatrix<f64>, b: &DMatrix<f64>, gain: DMatrix<f64>, riccati: DMatrix<f64>) -> Self {
        let closed_loop = (a - b * &gain).complex_eigenvalues().iter().copied().collect();
        Lqr {
            gain,
            riccati,
            closed_loop,
        }
    }
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
    let (rinv_bt, g) = weights(a.nrows(), b, q, r)?;
    let x = refine(
        sign_solution(a, &g, q)?,
        |x| check(a, &g, q, x),
        |x| kleinman_step(a, &g, q, x),
    )?;
    Ok(Lqr::new(a, b, &rinv_bt * &x, x))
}

/// The first solution X₀ of a Riccati equation refined by `REFINEMENTS` Newton steps (`newton`), and
/// accepted when `check` (the relative residual and the largest real part, or ln |λ|, of the closed
/// loop) says it stabilises and solves the equation to rounding. X₀ must already stabilise: Newton's
/// steps keep a stabilising X stabilising, and from any other their linear operator may be singular.
fn refine(
    first: DMatrix<f64>,
    check: impl Fn(&DMatrix<f64>) -> (f64, f64),
    newton: impl Fn(&DMatrix<f64>) -> Result<DMatrix<f64>>,
) -> Result<DMatrix<f64>> {
    let refused = |(residual, largest_real_part): (f64, f64)| Error::NoStabilizingSolution {
        residual,
        largest_real_part,
    };
    let first_check = check(&first);
    if first_check.1.is_nan() || first_check.1 >= 0.0 {
        return Err(refused(first_check));
    }
    let mut x = first;
    for _ in 0..REFINEMENTS {
        x = newton(&x).map_err(|_| refused(first_check))?;
    }
    let (residual, worst) = check(&x);
    if !(residual <= 1e-10 && worst < 0.0) {
        return Err(refused((residual, worst)));
    }
    Ok(x)
}

/// Checks the weights Q (n × n) and R (m × m, positive definite) and returns (R⁻¹Bᵀ, G = BR⁻¹Bᵀ).
fn weights(
    n: usize,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
    let m = b.ncols();
    for (what, mat, rows) in [("LQR weight Q", q, n), ("LQR weight R", r, m)] {
        noether_core::error::check_shape(what, mat, rows, rows)?;
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
    Ok((rinv_bt, g))
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

/// The discrete-time LQR: the gain K that minimises Σ_k (δx_kᵀ Q δx_k + δu_kᵀ R δu_k) for
/// δx_{k+1} = A δx_k + B δu_k (a [`StepLinearization`]), from the stabilising solution X of the
/// discrete algebraic Riccati equation
///
/// ```text
/// X = AᵀXA − AᵀXB (R + BᵀXB)⁻¹ BᵀXA + Q = AᵀX (I + GX)⁻¹ A + Q,   G = B R⁻¹ Bᵀ,
/// K = (R + BᵀXB)⁻¹ BᵀXA,   δu_k = −K δx_k
/// ```
///
/// (Anderson & Moore §2.4), by the structure-preserving doubling algorithm (Chu, Fan, Lin and Wang,
/// *Linear Algebra Appl.* 396, 2005), which converges quadratically:
///
/// ```text
/// A₀ = A, G₀ = G, H₀ = Q;   W_k = I + G_k H_k,
/// A_{k+1} = A_k W_k⁻¹ A_k,   G_{k+1} = G_k + A_k W_k⁻¹ G_k A_kᵀ,   H_{k+1} = H_k + A_kᵀ H_k W_k⁻¹ A_k → X,
/// ```
///
/// then refined by Hewer's Newton steps (each a Stein equation FᵀX'F − X' = −(Q + KᵀRK), F = A − BK,
/// through its Kronecker form). Accepted when the Riccati residual is at rounding level and every
/// eigenvalue of A − BK lies inside the unit circle. A sampled design with step h approaches the
/// continuous [`lqr`] with weights Q h and R h as h → 0. [`Error::NoStabilizingSolution`] carries, for
/// this discrete equation, the largest ln |λ| of A − BK (negative when stable, as the real parts of the
/// continuous case: λ = e^{sh}).
pub fn dlqr(lin: &StepLinearization, q: &DMatrix<f64>, r: &DMatrix<f64>) -> Result<Lqr> {
    let (a, b) = (&lin.a, &lin.b);
    let (_, g) = weights(a.nrows(), b, q, r)?;
    let x = refine(
        doubling(a, &g, q)?,
        |x| check_discrete(a, &g, q, x),
        |x| hewer_step(a, b, q, r, x),
    )?;
    Ok(Lqr::new(a, b, discrete_gain(a, b, r, &x)?, x))
}

/// K = (R + BᵀXB)⁻¹ BᵀXA.
fn discrete_gain(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    r: &DMatrix<f64>,
    x: &DMatrix<f64>,
) -> Result<DMatrix<f64>> {
    let btx = b.transpose() * x;
    let factor = DenseFactor::symmetric(r + &btx * b).map_err(|e| e.in_matrix("R + BᵀXB"))?;
    Ok(factor.solve_matrix(&(btx * a)))
}

/// The residual ‖AᵀX(I + GX)⁻¹A + Q − X‖ relative to the scale of its terms, and the largest ln |λ| of
/// the closed loop (I + GX)⁻¹A = A − BK.
fn check_discrete(a: &DMatrix<f64>, g: &DMatrix<f64>, q: &DMatrix<f64>, x: &DMatrix<f64>) -> (f64, f64) {
    let n = a.nrows();
    let Some(w_inv) = (DMatrix::identity(n, n) + g * x).try_inverse() else {
        return (f64::INFINITY, f64::NAN);
    };
    let closed = &w_inv * a;
    let residual = (a.transpose() * x * &closed + q - x).amax();
    let scale = (a.amax() * a.amax() * x.amax())
        .max(q.amax())
        .max(x.amax())
        .max(f64::MIN_POSITIVE);
    let worst = closed
        .complex_eigenvalues()
        .iter()
        .map(|l| l.norm().ln())
        .fold(f64::NEG_INFINITY, f64::max);
    (residual / scale, worst)
}

/// X by structure-preserving doubling (see [`dlqr`]).
fn doubling(a: &DMatrix<f64>, g: &DMatrix<f64>, q: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let n = a.nrows();
    let (mut ak, mut gk, mut hk) = (a.clone(), g.clone(), q.clone());
    for _ in 0..SIGN_ITERATIONS {
        let w = DenseFactor::lu(DMatrix::identity(n, n) + &gk * &hk).map_err(|_| {
            Error::NoStabilizingSolution {
                residual: f64::INFINITY,
                largest_real_part: f64::NAN,
            }
        })?;
        let wa = w.solve_matrix(&ak);
        let wg = w.solve_matrix(&gk);
        let next_h = &hk + ak.transpose() * &hk * &wa;
        gk = &gk + &ak * wg * ak.transpose();
        ak = &ak * wa;
        let change = (&next_h - &hk).amax() / next_h.amax().max(f64::MIN_POSITIVE);
        hk = (&next_h + next_h.transpose()) * 0.5;
        if change <= 1e-14 || ak.amax() <= f64::EPSILON * hk.amax() {
            return Ok(hk);
        }
    }
    Err(Error::NoStabilizingSolution {
        residual: f64::INFINITY,
        largest_real_part: f64::NAN,
    })
}

/// One Hewer step: X' solving FᵀX'F − X' = −(Q + KᵀRK), F = A − BK, K the gain of X, by its Kronecker
/// form (Fᵀ ⊗ Fᵀ − I) vec X' = −vec(Q + KᵀRK).
fn hewer_step(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    x: &DMatrix<f64>,
) -> Result<DMatrix<f64>> {
    let n = a.nrows();
    let k = discrete_gain(a, b, r, x)?;
    let f = a - b * &k;
    let c = -(q + k.transpose() * r * &k);
    let ft = f.transpose();
    let stein = ft.kronecker(&ft) - DMatrix::<f64>::identity(n * n, n * n);
    let factor = DenseFactor::lu(stein).map_err(|e| e.in_matrix("Stein operator of the Hewer step"))?;
    let mut v = c.as_slice().to_vec();
    factor.solve_in_place(&mut v);
    let next = DMatrix::from_column_slice(n, n, &v);
    Ok((&next + next.transpose()) * 0.5)
}

/// A finite-horizon, time-varying LQR design along a trajectory ([`tvlqr`]).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct TimeVaryingLqr {
    /// K_k (m × 2n), k = 0..N−1: the feedback δu_k = −K_k δx_k over step k.
    pub gains: Vec<DMatrix<f64>>,
    /// P_k, k = 0..=N: the optimal cost-to-go from δx_k is δx_kᵀ P_k δx_k.
    pub cost_to_go: Vec<DMatrix<f64>>,
}

/// The time-varying LQR gains along a trajectory of N steps, each linearised by
/// [`linearize_step`](crate::linearize_step) (δx_{k+1} = A_k δx_k + B_k δu_k, the inputs held over a
/// step): the feedback δu_k = −K_k δx_k that minimises
/// Σ_k (δx_kᵀ Q δx_k + δu_kᵀ R δu_k) + δx_Nᵀ Q_N δx_N, by the backward Riccati recursion
///
/// ```text
/// P_N = Q_N,   K_k = (R + B_kᵀ P_{k+1} B_k)⁻¹ B_kᵀ P_{k+1} A_k,   P_k = Q + A_kᵀ P_{k+1} (A_k − B_k K_k),
/// ```
///
/// (P_k symmetrised at each step against rounding). The tracking controller of a planned motion (a
/// DMOC path: linearise its steps about the path's nodes and inputs), and, for steps all alike and a
/// long horizon, the recursion that converges to [`dlqr`]'s stationary gain. Errors: no steps,
/// dimensions, non-finite or indefinite weights (R positive definite, Q and Q_N symmetric positive
/// semidefinite as given), R + BᵀPB singular.
pub fn tvlqr(
    steps: &[StepLinearization],
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    q_final: &DMatrix<f64>,
) -> Result<TimeVaryingLqr> {
    let first = steps.first().ok_or(noether_core::Error::InvalidParameter {
        name: "time-varying LQR steps",
        value: 0.0,
        reason: "at least one step",
    })?;
    let (n, m) = (first.a.nrows(), first.b.ncols());
    weights(n, &first.b, q, r)?;
    weights(n, &first.b, q_final, r)?;
    for step in steps {
        for (what, mat, rows, cols) in [
            ("time-varying LQR step matrix A_k", &step.a, n, n),
            ("time-varying LQR step matrix B_k", &step.b, n, m),
        ] {
            noether_core::error::check_shape(what, mat, rows, cols)?;
            check_finite(what, mat.as_slice())?;
        }
    }
    let mut cost_to_go = vec![q_final.clone()];
    let mut gains = Vec::with_capacity(steps.len());
    for step in steps.iter().rev() {
        let p = cost_to_go.last().expect("P_N first");
        let k = discrete_gain(&step.a, &step.b, r, p)?;
        let next = q + step.a.transpose() * p * (&step.a - &step.b * &k);
        cost_to_go.push((&next + next.transpose()) * 0.5);
        gains.push(k);
    }
    gains.reverse();
    cost_to_go.reverse();
    Ok(TimeVaryingLqr { gains, cost_to_go })
}
