//! Implicit midpoint and Gauss-Legendre collocation (s = 1, 2, 3 stages; orders 2, 4, 6): symplectic
//! for every Hamiltonian, separable or not, and symmetric.
//!
//! One step solves the stage equations for Z_i = Y_i − y₀ (i = 1..s, each of length 2n)
//!
//! ```text
//! Z_i = h Σ_j a_ij F(t + c_j h, y₀ + Z_j),        y₁ = y₀ + h Σ_i b_i F(Y_i) = y₀ + Σ_i d_i Z_i,
//! ```
//!
//! with dᵀ = bᵀA⁻¹ (no extra evaluation of F), by the core [`Newton`] solver on the s·2n unknowns with
//! the exact Jacobian δ_ij I − h a_ij J(Y_j), J = ∂F/∂y from [`LinearizedDynamics`] (for a Hamiltonian:
//! J = Ω ∇²H with the Hessian by dual numbers). The LU factor is reused across iterations while the
//! residual contracts well (modified Newton). By default the starting guess extrapolates the
//! collocation polynomial of the previous step (Hairer-Lubich-Wanner VIII.6.1) when the step continues
//! from where the last one ended, and a failed solve from that guess is retried once from the cold
//! guess Z_i = c_i h F(t, y₀) before the step fails (the extrapolation can land outside Newton's basin
//! at large steps where the cold guess does not: pendulum at h = 0.4–0.8, issue 29). With
//! [`Gauss::warm_start`]`(false)` every solve starts from the cold guess, a function of the step
//! (t, y₀, h) alone: a stepper continuing a run and a fresh one from the same state then agree to the
//! last bit, so a run restarted from a saved state continues bit for bit (Newton's converged iterate
//! depends on its start in the last bits). The tolerances of the solver are relative:
//! ‖residual‖∞ ≤ residual_tolerance · (1 + ‖y₀‖∞), and the step tolerance likewise; by default both are
//! 1e-15, a solve to rounding (Newton's round-off-aware stopping rule ends it when the increments stop
//! decreasing), so that quadratic invariants are kept to rounding at every step size.
//!
//! **Which systems.** Any [`LinearizedDynamics`]: [`HamiltonEquations`](crate::HamiltonEquations) on
//! (q, p), a `SeparableHamiltonian` on (q, p), a [`Natural`](crate::Natural) system on (q, q̇), and an
//! [`EulerLagrange`](crate::EulerLagrange) without generalized forces on (q, q̇) (its Jacobian from
//! third derivatives of L, see [`crate::system`]). A general Lagrangian is best written as a
//! Hamiltonian for these methods (collocation applied to (q, q̇) of a Lagrangian with
//! a configuration-dependent mass matrix is not symplectic in any case).
//!
//! A failed Newton solve returns [`Error::NewtonDiverged`] with the iteration count and the last
//! residual norm, and leaves the state untouched.
//!
//! # References
//! - E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., II.1.3 (collocation),
//!   VI.4 (symplecticity), VIII.6 (implementation).
//! - E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, IV.8 (stage values as unknowns).

use crate::error::{check_step, check_time_resolution};
use crate::newton::{max_norm, Dense, DenseProblem, Newton};
use crate::{Error, Result, State, StepInfo, Stepper};
use nalgebra::DMatrix;

/// Re-exported from [`system`](crate::system), where the system traits live.
pub use crate::system::LinearizedDynamics;

/// The last accepted step, for the extrapolated starting guess.
struct LastStep {
    t_end: f64,
    h: f64,
    y_start: Vec<f64>,
    y_end: Vec<f64>,
    /// Stage values Y_j = y_start + Z_j, stage after stage.
    stages: Vec<f64>,
}

/// Gauss-Legendre collocation with s stages (see the [module](self) docs).
pub struct Gauss<S> {
    system: S,
    s: usize,
    a: Vec<f64>,
    c: Vec<f64>,
    d: Vec<f64>,
    newton: Newton,
    warm: bool,
    last: Option<LastStep>,
}

impl<S: LinearizedDynamics> Gauss<S> {
    /// Gauss-Legendre collocation with `stages` = 1, 2 or 3 (orders 2, 4, 6).
    pub fn new(system: S, stages: usize) -> Result<Self> {
        let r3 = 3f64.sqrt();
        let r15 = 15f64.sqrt();
        let (a, b, c): (Vec<f64>, Vec<f64>, Vec<f64>) = match stages {
            1 => (vec![0.5], vec![1.0], vec![0.5]),
            2 => (
                vec![0.25, 0.25 - r3 / 6.0, 0.25 + r3 / 6.0, 0.25],
                vec![0.5, 0.5],
                vec![0.5 - r3 / 6.0, 0.5 + r3 / 6.0],
            ),
            3 => (
                vec![
                    5.0 / 36.0,
                    2.0 / 9.0 - r15 / 15.0,
                    5.0 / 36.0 - r15 / 30.0,
                    5.0 / 36.0 + r15 / 24.0,
                    2.0 / 9.0,
                    5.0 / 36.0 - r15 / 24.0,
                    5.0 / 36.0 + r15 / 30.0,
                    2.0 / 9.0 + r15 / 15.0,
                    5.0 / 36.0,
                ],
                vec![5.0 / 18.0, 4.0 / 9.0, 5.0 / 18.0],
                vec![0.5 - r15 / 10.0, 0.5, 0.5 + r15 / 10.0],
            ),
            _ => {
                return Err(Error::InvalidParameter {
                    name: "Gauss stages",
                    value: stages as f64,
                    reason: "Gauss-Legendre collocation is provided with 1, 2 or 3 stages",
                })
            }
        };
        // dᵀ = bᵀ A⁻¹, i.e. Aᵀ d = b.
        let at = DMatrix::from_row_slice(stages, stages, &a).transpose();
        let mut d = b;
        crate::linalg::DenseFactor::lu(at)
            .map_err(|e| e.in_matrix("Gauss matrix A"))?
            .solve_in_place(&mut d);
        Ok(Gauss {
            system,
            s: stages,
            a,
            c,
            d,
            newton: default_newton(),
            warm: true,
            last: None,
        })
    }

    /// The implicit midpoint rule y₁ = y₀ + h F((y₀ + y₁)/2), order 2 (Gauss with one stage).
    pub fn implicit_midpoint(system: S) -> Self {
        Self::new(system, 1).expect("one stage is supported")
    }
    /// Two-stage Gauss-Legendre collocation, order 4.
    pub fn gauss4(system: S) -> Self {
        Self::new(system, 2).expect("two stages are supported")
    }
    /// Three-stage Gauss-Legendre collocation, order 6.
    pub fn gauss6(system: S) -> Self {
        Self::new(system, 3).expect("three stages are supported")
    }

    /// Sets the Newton solver (its `residual_tolerance` and `step_tolerance` are relative to 1 + ‖y₀‖∞).
    pub fn newton(mut self, newton: Newton) -> Self {
        self.newton = newton;
        self
    }

    /// Starts each Newton solve from the extrapolated collocation polynomial of the last step when
    /// the step continues it (`true`), or always from the cold guess Z_i = c_i h F(t, y₀) (`false`:
    /// results independent of the history, bit for bit); the default is `true`. See the
    /// [module](self) docs.
    pub fn warm_start(mut self, on: bool) -> Self {
        self.warm = on;
        self
    }

    /// The system stepped.
    pub fn system(&self) -> &S {
        &self.system
    }

    /// The extrapolated starting guess for Z at step (t, y0, h) from the last step, when warm starts
    /// are on and the step continues the last one: `true` when `z` holds it.
    fn warm_guess(&self, t: f64, y0: &[f64], h: f64, z: &mut [f64]) -> bool {
        let (s, m) = (self.s, y0.len());
        if !self.warm {
            return false;
        }
        if let Some(last) = self.last.as_ref().filter(|l| l.t_end == t && l.y_end == y0) {
            // u(τ) through (0, y_start), (c_j, Y_j); Z_i = u(1 + c_i h/h_old) − y₀.
            let mut nodes = vec![0.0];
            nodes.extend(&self.c);
            for i in 0..s {
                let tau = 1.0 + self.c[i] * h / last.h;
                let zi = &mut z[i * m..(i + 1) * m];
                zi.iter_mut().zip(y0).for_each(|(z, y)| *z = -y);
                for (k, xk) in nodes.iter().enumerate() {
                    let w: f64 = nodes
                        .iter()
                        .enumerate()
                        .filter(|(l, _)| *l != k)
                        .map(|(_, xl)| (tau - xl) / (xk - xl))
                        .product();
                    let vals = if k == 0 {
                        &last.y_start[..]
                    } else {
                        &last.stages[(k - 1) * m..k * m]
                    };
                    zi.iter_mut().zip(vals).for_each(|(z, v)| *z += w * v);
                }
            }
            return z.iter().all(|x| x.is_finite());
        }
        false
    }

    /// The cold starting guess Z_i = c_i h F(t, y₀): a function of the step alone.
    fn cold_guess(&self, t: f64, y0: &[f64], h: f64, z: &mut [f64]) -> Result<()> {
        let (s, m) = (self.s, y0.len());
        let n = m / 2;
        let mut f = vec![0.0; m];
        let (fq, fv) = f.split_at_mut(n);
        self.system.rates(t, &y0[..n], &y0[n..], fq, fv)?;
        for i in 0..s {
            for k in 0..m {
                z[i * m + k] = self.c[i] * h * f[k];
            }
        }
        Ok(())
    }
}

/// The default solver of [`Gauss`]: residual and step tolerances 1e-15 (relative to 1 + ‖y₀‖∞, about
/// 4.5 ε: the stage values are solved to rounding, so that the quadratic invariants are kept to
/// rounding at every step size), at most 20 iterations.
fn default_newton() -> Newton {
    let limits = |n: Newton| {
        n.residual_tolerance(1e-15)?
            .step_tolerance(1e-15)?
            .max_iterations(20)
    };
    limits(Newton::default()).expect("positive tolerances and a cap of 20")
}

/// The stage equations of one step as a Newton problem in Z.
struct Stages<'a, S> {
    system: &'a S,
    t: f64,
    h: f64,
    y0: &'a [f64],
    a: &'a [f64],
    c: &'a [f64],
    s: usize,
    f: Vec<f64>,
    y: Vec<f64>,
    jac: DMatrix<f64>,
}

impl<S: LinearizedDynamics> Stages<'_, S> {
    /// Y_j = y₀ + Z_j into self.y.
    fn stage(&mut self, z: &[f64], j: usize) {
        let m = self.y0.len();
        self.y
            .iter_mut()
            .enumerate()
            .for_each(|(k, y)| *y = self.y0[k] + z[j * m + k]);
    }
}

impl<S: LinearizedDynamics> DenseProblem for Stages<'_, S> {
    fn dim(&self) -> usize {
        self.s * self.y0.len()
    }
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<()> {
        let (s, m, n) = (self.s, self.y0.len(), self.y0.len() / 2);
        for j in 0..s {
            self.stage(z, j);
            let (fq, fv) = self.f[j * m..(j + 1) * m].split_at_mut(n);
            self.system
                .rates(self.t + self.c[j] * self.h, &self.y[..n], &self.y[n..], fq, fv)?;
        }
        for i in 0..s {
            for k in 0..m {
                let sum: f64 = (0..s).map(|j| self.a[i * s + j] * self.f[j * m + k]).sum();
                r[i * m + k] = z[i * m + k] - self.h * sum;
            }
        }
        Ok(())
    }
    fn jacobian(&mut self, z: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        let (s, m, n) = (self.s, self.y0.len(), self.y0.len() / 2);
        out.fill_with_identity();
        for j in 0..s {
            self.stage(z, j);
            self.system.jacobian(
                self.t + self.c[j] * self.h,
                &self.y[..n],
                &self.y[n..],
                &mut self.jac,
            )?;
            for i in 0..s {
                let w = -self.h * self.a[i * s + j];
                let mut blk = out.view_mut((i * m, j * m), (m, m));
                blk += &self.jac * w;
            }
        }
        Ok(())
    }
}

impl<S: LinearizedDynamics> Gauss<S> {
    /// The stage equations of the step (t, y₀, h) as a Newton problem.
    fn stage_problem<'a>(&'a self, t: f64, h: f64, y0: &'a [f64]) -> Stages<'a, S> {
        let m = y0.len();
        Stages {
            system: &self.system,
            t,
            h,
            y0,
            a: &self.a,
            c: &self.c,
            s: self.s,
            f: vec![0.0; self.s * m],
            y: vec![0.0; m],
            jac: DMatrix::zeros(m, m),
        }
    }

    /// Solves the stage equations of one step from `state`: (y₀, converged Z, Newton iterations,
    /// failed solves). A solve from the warm guess that fails is retried from the cold guess.
    fn solve_stages(&self, state: &State<S::Partner>, h: f64) -> Result<(Vec<f64>, Vec<f64>, usize, usize)> {
        check_step(h)?;
        let n = self.system.dof();
        state.validate(n)?;
        check_time_resolution(state.t, h)?;
        let (s, m, t) = (self.s, 2 * n, state.t);
        let mut y0 = Vec::with_capacity(m);
        y0.extend_from_slice(state.q.as_slice());
        y0.extend_from_slice(state.v.as_slice());
        let mut z = vec![0.0; s * m];
        // Both tolerances relative to 1 + ‖y₀‖∞ (Z is an increment of y₀).
        let newton = self.newton.scaled(1.0 + max_norm(&y0));
        let mut sys = Dense::new(self.stage_problem(t, h, &y0));
        let (mut iterations, mut failures) = (0, 0);
        if self.warm_guess(t, &y0, h, &mut z) {
            match newton.solve(&mut sys, &mut z) {
                Ok(info) => return Ok((y0, z, info.iterations, 0)),
                // Whatever went wrong from the extrapolated guess (no convergence, a singular
                // Jacobian or a non-finite residual on the way), the cold guess decides.
                Err(e) => {
                    failures = 1;
                    if let Error::NewtonDiverged { iterations: k, .. } = e {
                        iterations = k;
                    }
                }
            }
        }
        self.cold_guess(t, &y0, h, &mut z)?;
        let info = newton.solve(&mut sys, &mut z).map_err(|e| e.at_time(t))?;
        Ok((y0, z, iterations + info.iterations, failures))
    }

    /// y₁ = y₀ + Σ d_i Z_i, checked finite.
    fn new_state(&self, t: f64, y0: &[f64], z: &[f64]) -> Result<Vec<f64>> {
        let m = y0.len();
        let mut y1 = y0.to_vec();
        for i in 0..self.s {
            for k in 0..m {
                y1[k] += self.d[i] * z[i * m + k];
            }
        }
        if y1.iter().any(|x| !x.is_finite()) {
            return Err(Error::NonFiniteResult {
                what: "state after the step",
                t,
                component: None,
            });
        }
        Ok(y1)
    }

    /// Writes y₁ into `state`, remembers the step for the next starting guess.
    fn commit(
        &mut self,
        state: &mut State<S::Partner>,
        h: f64,
        (y0, y1, z): (Vec<f64>, Vec<f64>, &[f64]),
        (iterations, failures): (usize, usize),
    ) -> StepInfo {
        let (s, m) = (self.s, y0.len());
        let n = m / 2;
        state.q.as_mut_slice().copy_from_slice(&y1[..n]);
        state.v.as_mut_slice().copy_from_slice(&y1[n..]);
        state.t += h;
        if self.warm {
            let stages = (0..s * m).map(|k| y0[k % m] + z[k]).collect();
            self.last = Some(LastStep {
                t_end: state.t,
                h,
                y_start: y0,
                y_end: y1,
                stages,
            });
        }
        // One vector field per stage and residual (the start guess costs one more on a fresh start).
        StepInfo::fixed(h)
            .with_evaluations(s * (iterations + 1 + failures))
            .with_newton(iterations, failures)
    }

    /// Ψ of the step (t, y₀, h) with converged stage increments `z`, by the implicit-function theorem
    /// (see the [`TangentStepper`] impl).
    fn stage_tangent(&self, t: f64, h: f64, y0: &[f64], z: &[f64]) -> Result<DMatrix<f64>> {
        let (s, m) = (self.s, y0.len());
        let mut gz = DMatrix::zeros(s * m, s * m);
        self.stage_problem(t, h, y0).jacobian(z, &mut gz)?;
        // −G_{y₀} block i = h Σ_j a_ij J(Y_j) = I − Σ_j G_Z(i, j): the blocks of G_Z already hold it.
        let mut rhs = DMatrix::zeros(s * m, m);
        for i in 0..s {
            let mut bi = rhs.view_mut((i * m, 0), (m, m));
            bi.fill_with_identity();
            for j in 0..s {
                bi -= gz.view((i * m, j * m), (m, m));
            }
        }
        let dz = crate::linalg::DenseFactor::lu(gz)
            .map_err(|e| e.in_matrix("Gauss stage Jacobian (tangent)"))?
            .solve_matrix(&rhs);
        let mut psi = DMatrix::identity(m, m);
        for i in 0..s {
            psi += self.d[i] * dz.view((i * m, 0), (m, m));
        }
        crate::error::check_result("step Jacobian Ψ", t, psi.as_slice())?;
        Ok(psi)
    }
}

impl<S: LinearizedDynamics> Stepper for Gauss<S> {
    type Partner = S::Partner;
    fn step(&mut self, state: &mut State<S::Partner>, h: f64) -> Result<StepInfo> {
        let (y0, z, iterations, failures) = self.solve_stages(state, h)?;
        let y1 = self.new_state(state.t, &y0, &z)?;
        Ok(self.commit(state, h, (y0, y1, &z), (iterations, failures)))
    }
    fn rates(&self, state: &State<S::Partner>, dq: &mut [f64], dv: &mut [f64]) -> Option<Result<()>> {
        Some(
            self.system
                .rates(state.t, state.q.as_slice(), state.v.as_slice(), dq, dv),
        )
    }
    fn dof(&self) -> usize {
        self.system.dof()
    }
    fn order(&self) -> u32 {
        2 * self.s as u32
    }
    fn name(&self) -> &'static str {
        match self.s {
            1 => "implicit midpoint",
            2 => "Gauss-Legendre 4 (2 stages)",
            _ => "Gauss-Legendre 6 (3 stages)",
        }
    }
}

/// Ψ of a Gauss step by the implicit-function theorem at the converged stages (not by differentiating
/// Newton's iterations). With G(Z, y₀)_i = Z_i − h Σ_j a_ij F(y₀ + Z_j) = 0,
///
/// ```text
/// G_Z = [δ_ij I − h a_ij J(Y_j)],   G_{y₀} = [−h Σ_j a_ij J(Y_j)]_i,
/// ∂Z/∂y₀ = −G_Z⁻¹ G_{y₀},           Ψ = I + Σ_i d_i ∂Z_i/∂y₀,
/// ```
///
/// G_Z being the exact Jacobian of the stage equations at the converged Z (evaluated once more there
/// and factored by the one LU of [`linalg`](crate::linalg)). The stages carry the Newton tolerance
/// (1e-15 relative by default), so Ψ is the derivative of the exactly solved step to about that
/// level times ‖∂Ψ/∂Z‖.
impl<S: LinearizedDynamics> crate::TangentStepper for Gauss<S> {
    fn step_tangent(
        &mut self,
        state: &mut State<S::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        crate::tangent::check_tangent_shape(psi, self.system.dof())?;
        let (y0, z, iterations, failures) = self.solve_stages(state, h)?;
        let y1 = self.new_state(state.t, &y0, &z)?;
        let out = self.stage_tangent(state.t, h, &y0, &z)?;
        psi.copy_from(&out);
        Ok(self.commit(state, h, (y0, y1, &z), (iterations, failures)))
    }
}
