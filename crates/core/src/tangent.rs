//! The derivative of the numerical flow: the Jacobian of one step of a method,
//!
//! ```text
//! Ψ = ∂y₁/∂y₀,   y = (q, v) ∈ ℝ²ⁿ,
//! ```
//!
//! of the discrete map the method actually computes (not of the exact flow it approximates), exact to
//! rounding. For an explicit Runge-Kutta method it is the stage recursion differentiated,
//! K_i = J(Y_i)(I + h Σ_j a_ij K_j), Ψ = I + h Σ_i b_i K_i, with J = ∂F/∂y from
//! [`LinearizedDynamics`](crate::system::LinearizedDynamics); for a method that solves an implicit
//! equation G(Z, y₀) = 0 by Newton, it is the implicit-function theorem at the converged solution,
//! ∂Z/∂y₀ = −G_Z⁻¹ G_{y₀}, not the derivative of Newton's iterations.
//!
//! Over a run the tangents multiply: ∂y_N/∂y₀ = Ψ_{N−1} ⋯ Ψ₁ Ψ₀ ([`run_jacobian`], and [`propagate`]
//! for a block of tangent vectors).
//!
//! Methods with a Ψ: RK4, Euler, Euler-Cromer, DOPRI5 and DOP853 (h frozen at the step taken), the
//! Gauss methods (implicit-function theorem), symplectic Euler and the Verlet compositions (kick and
//! drift Jacobians), for any [`LinearizedDynamics`](crate::system::LinearizedDynamics): a
//! Hamiltonian, a separable or natural system, or `EulerLagrange` of any Lagrangian (its Jacobian
//! from third derivatives of L, in [`system`](crate::system)).
//!
//! ```
//! use noether_core::prelude::*;
//! use noether_core::TangentStepper;
//! use nalgebra::DMatrix;
//!
//! /// Harmonic oscillator H = ½(p² + q²).
//! struct Oscillator;
//! impl Hamiltonian for Oscillator {
//!     fn dof(&self) -> usize { 1 }
//!     fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
//!         (p[0] * p[0] + q[0] * q[0]) * 0.5
//!     }
//! }
//!
//! let mut rk4 = Rk4::new(HamiltonEquations::new(Oscillator));
//! let mut s = State::with_momenta(0.0, [1.0], [0.0]);
//! let mut psi = DMatrix::zeros(2, 2);
//! rk4.step_tangent(&mut s, 0.1, &mut psi).unwrap();
//! // For a linear system Ψ is RK4's stability polynomial of hA: det Ψ = 1 − h⁶/72 + h⁸/576.
//! let h: f64 = 0.1;
//! assert!((psi.determinant() - (1.0 - h.powi(6) / 72.0 + h.powi(8) / 576.0)).abs() < 1e-15);
//! ```

use crate::{Result, State, StepInfo, Stepper};
use nalgebra::DMatrix;

/// A [`Stepper`] that also gives the Jacobian of its step.
///
/// Contract: `step_tangent(state, h, psi)` takes exactly the step [`Stepper::step`] would take from
/// `state` with `h` (same new state, same [`StepInfo`]) and writes Ψ = ∂(q₁, v₁)/∂(q₀, v₀) into the
/// 2n × 2n matrix `psi`, rows and columns ordered (q, v). For an adaptive method the step size is
/// held fixed at the one taken (the derivative of the map y₀ ↦ y₁ at that h). On error both `state`
/// and `psi` are left exactly as they were.
pub trait TangentStepper: Stepper {
    /// Advances `state` by one step and writes the step's Jacobian Ψ into `psi`.
    fn step_tangent(
        &mut self,
        state: &mut State<Self::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo>;
}

impl<S: TangentStepper + ?Sized> TangentStepper for Box<S> {
    fn step_tangent(
        &mut self,
        state: &mut State<S::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        (**self).step_tangent(state, h, psi)
    }
}

/// Checks that `psi` is 2n × 2n for a system of `dof` degrees of freedom: the one check of a step
/// Jacobian's shape, for every tangent stepper of the workspace.
pub fn check_tangent_shape(psi: &DMatrix<f64>, dof: usize) -> Result<()> {
    crate::error::check_shape("step Jacobian Ψ (rows and columns)", psi, 2 * dof, 2 * dof)
}

/// Ψ of one step of the explicit Runge-Kutta method (A strictly lower triangular, b, c) from (t, q, v)
/// with step h, by the differentiated stage recursion
///
/// ```text
/// Y_i = y₀ + h Σ_{j<i} a_ij k_j,   k_i = F(t + c_i h, Y_i),
/// K_i = ∂k_i/∂y₀ = J(t + c_i h, Y_i) (I + h Σ_{j<i} a_ij K_j),   Ψ = I + h Σ_i b_i K_i.
/// ```
///
/// Evaluates F and J once per stage; `a[i]` holds the coefficients a_ij for j < i. The new state
/// itself is not formed here (the stepper's own step is the one taken).
pub(crate) fn explicit_rk_tangent<S: crate::system::LinearizedDynamics>(
    system: &S,
    (t, q, v): (f64, &[f64], &[f64]),
    h: f64,
    (a, b, c): (&[&[f64]], &[f64], &[f64]),
    psi: &mut DMatrix<f64>,
) -> Result<()> {
    let n = q.len();
    let s = b.len();
    let mut k: Vec<(Vec<f64>, Vec<f64>)> = Vec::with_capacity(s);
    let mut dk: Vec<DMatrix<f64>> = Vec::with_capacity(s);
    let (mut yq, mut yv) = (q.to_vec(), v.to_vec());
    let mut jac = DMatrix::zeros(2 * n, 2 * n);
    let mut out = DMatrix::identity(2 * n, 2 * n);
    for i in 0..s {
        // Y_i and ∂Y_i/∂y₀.
        yq.copy_from_slice(q);
        yv.copy_from_slice(v);
        let mut dy = DMatrix::identity(2 * n, 2 * n);
        for (j, &aij) in a[i].iter().enumerate() {
            if aij != 0.0 {
                for m in 0..n {
                    yq[m] += h * aij * k[j].0[m];
                    yv[m] += h * aij * k[j].1[m];
                }
                dy += h * aij * &dk[j];
            }
        }
        let ti = t + c[i] * h;
        let (mut kq, mut kv) = (vec![0.0; n], vec![0.0; n]);
        system.rates(ti, &yq, &yv, &mut kq, &mut kv)?;
        system.jacobian(ti, &yq, &yv, &mut jac)?;
        let dki = &jac * dy;
        out += h * b[i] * &dki;
        k.push((kq, kv));
        dk.push(dki);
    }
    crate::error::check_result("step Jacobian Ψ", t, out.as_slice())?;
    psi.copy_from(&out);
    Ok(())
}

/// Takes `stepper`'s step on a copy of `state`, then `tangent(stepper, start state, step info)`;
/// commits the new state only when both succeed (so a failure leaves `state`, and Ψ when `tangent`
/// writes it last, as they were).
pub(crate) fn step_then_tangent<St: Stepper>(
    stepper: &mut St,
    state: &mut State<St::Partner>,
    h: f64,
    tangent: impl FnOnce(&St, &State<St::Partner>, &StepInfo) -> Result<()>,
) -> Result<StepInfo> {
    let mut next = state.clone();
    let info = stepper.step(&mut next, h)?;
    tangent(stepper, state, &info)?;
    *state = next;
    Ok(info)
}

/// Ψ by central differences of the step itself, column j from the two steps of `stepper` started at
/// y₀ ± δ_j e_j, δ_j = `rel` · max(1, |y₀_j|): the reference a [`TangentStepper`] is checked against
/// (a user's own included). Its error is O(δ²) truncation plus O(ε/δ) rounding: with `rel` = 1e-5
/// about 1e-10 on a smooth problem of unit scale.
pub fn central_difference<S: Stepper>(
    stepper: &mut S,
    state: &State<S::Partner>,
    h: f64,
    rel: f64,
) -> Result<DMatrix<f64>> {
    let n = stepper.dof();
    state.validate(n)?;
    crate::error::check_step(h)?;
    if !(rel.is_finite() && rel > 0.0) {
        return Err(crate::Error::InvalidParameter {
            name: "rel",
            value: rel,
            reason: "the relative difference step must be finite and positive",
        });
    }
    let mut psi = DMatrix::zeros(2 * n, 2 * n);
    for j in 0..2 * n {
        let y0 = if j < n { state.q[j] } else { state.v[j - n] };
        let delta = rel * y0.abs().max(1.0);
        let mut ends = [state.clone(), state.clone()];
        for (end, sign) in ends.iter_mut().zip([1.0, -1.0]) {
            if j < n {
                end.q[j] = y0 + sign * delta;
            } else {
                end.v[j - n] = y0 + sign * delta;
            }
            stepper.step(end, h)?;
        }
        for i in 0..2 * n {
            let (plus, minus) = if i < n {
                (ends[0].q[i], ends[1].q[i])
            } else {
                (ends[0].v[i - n], ends[1].v[i - n])
            };
            psi[(i, j)] = (plus - minus) / (2.0 * delta);
        }
    }
    Ok(psi)
}

/// Advances `state` by `steps` steps of `stepper` with step `h` and carries the tangent vectors `w`
/// (the 2n × k block of columns W, rows ordered (q, v)) along:
///
/// ```text
/// W ← Ψ_{N−1} ⋯ Ψ₁ Ψ₀ W,   Ψ_k = ∂y_{k+1}/∂y_k the Jacobian of step k (TangentStepper::step_tangent),
/// ```
///
/// so that on return W holds ∂y_N/∂y₀ · W₀: the linearized flow of the numerical map applied to W₀
/// (k = 1: a tangent vector; k = 2n with W₀ = I: the whole Jacobian, see [`run_jacobian`]). Each step
/// costs one `step_tangent` and one 2n × 2n × k product. An adaptive method takes whatever step its
/// controller accepts (Ψ is that of the step taken); for N steps of exactly h use its fixed-step mode.
///
/// Errors: `w` without 2n rows ([`Error::Dimension`](crate::Error::Dimension)), a non-finite entry
/// of `w` ([`Error::NonFinite`](crate::Error::NonFinite)), and any error of a step (the step's own
/// typed error, e.g. an invalid h or a non-finite state). On error `state` and `w` are left as they
/// were (the run works on copies and commits both at the end).
///
/// ```
/// use noether_core::prelude::*;
/// use noether_core::tangent::propagate;
/// use nalgebra::DMatrix;
///
/// /// Harmonic oscillator H = ½(p² + q²).
/// struct Oscillator;
/// impl Hamiltonian for Oscillator {
///     fn dof(&self) -> usize { 1 }
///     fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
///         (p[0] * p[0] + q[0] * q[0]) * 0.5
///     }
/// }
///
/// // The implicit midpoint rule maps y' = Ay (A = [[0, 1], [−1, 0]]) by the Cayley transform of hA:
/// // a rotation by θ = 2 atan(h/2). After N steps a tangent vector δy₀ = (1, 0) has turned by Nθ.
/// let (h, n) = (0.1, 50);
/// let mut midpoint = Gauss::implicit_midpoint(HamiltonEquations::new(Oscillator));
/// let mut s = State::with_momenta(0.0, [1.0], [0.0]);
/// let mut w = DMatrix::from_column_slice(2, 1, &[1.0, 0.0]);
/// propagate(&mut midpoint, &mut s, h, n, &mut w)?;
/// let angle = n as f64 * 2.0 * (h / 2.0).atan();
/// assert!((w[(0, 0)] - angle.cos()).abs() < 1e-13 && (w[(1, 0)] + angle.sin()).abs() < 1e-13);
/// # Ok::<(), noether_core::Error>(())
/// ```
pub fn propagate<S: TangentStepper>(
    stepper: &mut S,
    state: &mut State<S::Partner>,
    h: f64,
    steps: usize,
    w: &mut DMatrix<f64>,
) -> Result<()> {
    let n = stepper.dof();
    if w.nrows() != 2 * n {
        return Err(crate::Error::Dimension {
            what: "tangent vectors W (rows)",
            expected: 2 * n,
            got: w.nrows(),
        });
    }
    crate::error::check_finite("tangent vectors W", w.as_slice())?;
    let mut s = state.clone();
    let mut out = w.clone();
    // W ← ΨW into a second buffer and swap: no allocation per step on this hot path.
    let mut next = w.clone();
    let mut psi = DMatrix::zeros(2 * n, 2 * n);
    for _ in 0..steps {
        stepper.step_tangent(&mut s, h, &mut psi)?;
        psi.mul_to(&out, &mut next);
        std::mem::swap(&mut out, &mut next);
    }
    *state = s;
    w.copy_from(&out);
    Ok(())
}

/// The Jacobian of `steps` steps of `stepper` with step `h` from `state`,
///
/// ```text
/// Φ = ∂y_N/∂y₀ = Ψ_{N−1} ⋯ Ψ₁ Ψ₀   (2n × 2n, rows and columns ordered (q, v)),
/// ```
///
/// advancing `state` to y_N: [`propagate`] with W₀ = I. The monodromy matrix of a periodic orbit, the
/// sensitivity of a shot to its start, the tangent map whose singular values give finite-time
/// Lyapunov exponents. Errors as [`propagate`]; on error `state` is left as it was.
///
/// ```
/// use noether_core::prelude::*;
/// use noether_core::tangent::run_jacobian;
///
/// struct Oscillator;
/// impl Hamiltonian for Oscillator {
///     fn dof(&self) -> usize { 1 }
///     fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
///         (p[0] * p[0] + q[0] * q[0]) * 0.5
///     }
/// }
///
/// // Gauss 4 is symplectic: det Φ = 1 over the whole run (Liouville).
/// let mut g4 = Gauss::gauss4(HamiltonEquations::new(Oscillator));
/// let mut s = State::with_momenta(0.0, [1.0], [0.0]);
/// let phi = run_jacobian(&mut g4, &mut s, 0.1, 100)?;
/// assert!((phi.determinant() - 1.0).abs() < 1e-13);
/// // For a linear system Φ maps y₀ to y_N: here (1, 0) to the state itself.
/// assert!((phi[(0, 0)] - s.q[0]).abs() < 1e-13 && (phi[(1, 0)] - s.v[0]).abs() < 1e-13);
/// # Ok::<(), noether_core::Error>(())
/// ```
pub fn run_jacobian<S: TangentStepper>(
    stepper: &mut S,
    state: &mut State<S::Partner>,
    h: f64,
    steps: usize,
) -> Result<DMatrix<f64>> {
    let n = stepper.dof();
    let mut phi = DMatrix::identity(2 * n, 2 * n);
    propagate(stepper, state, h, steps, &mut phi)?;
    Ok(phi)
}
