//! Classical explicit methods: forward Euler, Euler-Cromer (semi-implicit Euler) and RK4.
//!
//! All three step any [`Dynamics`] on (q, v), v = q̇ or p, and leave the state untouched on error.

use crate::error::{check_step, check_time_resolution};
use crate::system::LinearizedDynamics;
use crate::tangent::{check_tangent_shape, explicit_rk_tangent, step_then_tangent};
use crate::{Dynamics, Error, Partner, Result, State, StepInfo, Stepper, TangentStepper};
use nalgebra::DMatrix;

/// A pair of work vectors (q-part, v-part) of a one-step method: rates F = (q̇, v̇) or a new state.
struct Pair {
    q: Vec<f64>,
    v: Vec<f64>,
}

impl Pair {
    fn new(n: usize) -> Self {
        Pair {
            q: vec![0.0; n],
            v: vec![0.0; n],
        }
    }

    /// Checks this new (q, v) is finite, then writes it and t + h into `state`.
    fn commit<K: Partner>(&self, state: &mut State<K>, h: f64) -> Result<StepInfo> {
        if self.q.iter().chain(&self.v).any(|x| !x.is_finite()) {
            return Err(Error::NonFiniteResult {
                what: "state after the step",
                t: state.t,
                component: None,
            });
        }
        state.q.as_mut_slice().copy_from_slice(&self.q);
        state.v.as_mut_slice().copy_from_slice(&self.v);
        state.t += h;
        Ok(StepInfo::fixed(h))
    }
}

/// The stage argument y + a·k on both halves: `out = (q + a k_q, v + a k_v)`.
fn shifted(out: &mut Pair, q: &[f64], v: &[f64], a: f64, k: &Pair) {
    for i in 0..q.len() {
        out.q[i] = q[i] + a * k.q[i];
        out.v[i] = v[i] + a * k.v[i];
    }
}

/// A first-order method with one evaluation of the vector field F = (q̇, v̇) per step: [`Euler`] or
/// [`EulerCromer`], by the update rule `R`. Both take v' = v + h v̇(t, q, v); they differ in the
/// velocities q̇ is evaluated at for q' = q + h q̇.
pub struct FirstOrder<S, R> {
    system: S,
    /// The rates F, then the new state.
    y: Pair,
    _rule: std::marker::PhantomData<R>,
}

/// Which of the two first-order updates a [`FirstOrder`] method makes.
pub trait FirstOrderRule {
    /// Short name.
    const NAME: &'static str;
    /// `false`: q' = q + h q̇(t, q, v) (forward Euler); `true`: q' = q + h q̇(t, q, v') with the new
    /// velocities v' (Euler-Cromer).
    const NEW_VELOCITIES: bool;
}

/// Forward Euler, order 1: (q, v) ← (q, v) + h F(t, q, v).
pub type Euler<S> = FirstOrder<S, Forward>;

/// The forward Euler rule (see [`Euler`]).
#[derive(Debug, Clone, Copy)]
pub struct Forward;

impl FirstOrderRule for Forward {
    const NAME: &'static str = "Euler";
    const NEW_VELOCITIES: bool = false;
}

/// Euler-Cromer (semi-implicit, or symplectic, Euler), order 1:
///
/// v_{n+1} = v_n + h v̇(t_n, q_n, v_n),   q_{n+1} = q_n + h q̇(t_n, q_n, v_{n+1}).
///
/// For L = T(q̇) − V(q) (q̇ = v, v̇ depending on q only) and for separable H = T(p) + V(q) this is the
/// symplectic Euler method; on other systems it is an explicit first-order method without that
/// property. It costs one vector field and one [`Dynamics::position_rates`] per step.
pub type EulerCromer<S> = FirstOrder<S, Cromer>;

/// The Euler-Cromer rule (see [`EulerCromer`]).
#[derive(Debug, Clone, Copy)]
pub struct Cromer;

impl FirstOrderRule for Cromer {
    const NAME: &'static str = "Euler-Cromer";
    const NEW_VELOCITIES: bool = true;
}

/// x + h·ẋ in place: `rate` holds ẋ on entry and the advanced value on exit.
fn advance(rate: &mut [f64], x: &[f64], h: f64) {
    rate.iter_mut().zip(x).for_each(|(d, x)| *d = x + h * *d);
}

impl<S: Dynamics, R: FirstOrderRule> FirstOrder<S, R> {
    /// The method for `system`.
    pub fn new(system: S) -> Self {
        FirstOrder {
            y: Pair::new(system.dof()),
            system,
            _rule: std::marker::PhantomData,
        }
    }

    /// The system stepped.
    pub fn system(&self) -> &S {
        &self.system
    }
}

impl<S: Dynamics, R: FirstOrderRule> Stepper for FirstOrder<S, R> {
    type Partner = S::Partner;
    fn step(&mut self, state: &mut State<S::Partner>, h: f64) -> Result<StepInfo> {
        check_step(h)?;
        state.validate(self.system.dof())?;
        check_time_resolution(state.t, h)?;
        let (t, q, v) = (state.t, state.q.as_slice(), state.v.as_slice());
        self.system.admissible(t, q, v)?;
        let y = &mut self.y;
        self.system.rates(t, q, v, &mut y.q, &mut y.v)?;
        advance(&mut y.v, v, h); // v' = v + h v̇(t, q, v)
        if R::NEW_VELOCITIES {
            // Euler-Cromer: q̇ at the new velocities v'.
            if y.v.iter().any(|x| !x.is_finite()) {
                return Err(Error::NonFiniteResult {
                    what: "velocities",
                    t,
                    component: None,
                });
            }
            self.system.position_rates(t, q, &y.v, &mut y.q)?;
        }
        advance(&mut y.q, q, h); // q' = q + h q̇
        Ok(y.commit(state, h)?.with_evaluations(1))
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
        1
    }
    fn name(&self) -> &'static str {
        R::NAME
    }
}

/// Classical fourth-order Runge-Kutta method on (q, v).
///
/// k₁ = F(t, y), k₂ = F(t + h/2, y + h k₁/2), k₃ = F(t + h/2, y + h k₂/2), k₄ = F(t + h, y + h k₃),
/// y ← y + h (k₁ + 2k₂ + 2k₃ + k₄)/6.
pub struct Rk4<S> {
    system: S,
    k: [Pair; 4],
    /// The stage arguments y + a h k, then the new state.
    y: Pair,
}

impl<S: Dynamics> Rk4<S> {
    /// RK4 for `system`.
    pub fn new(system: S) -> Self {
        let n = system.dof();
        Rk4 {
            system,
            k: std::array::from_fn(|_| Pair::new(n)),
            y: Pair::new(n),
        }
    }

    /// The system stepped.
    pub fn system(&self) -> &S {
        &self.system
    }
}

impl<S: Dynamics> Stepper for Rk4<S> {
    type Partner = S::Partner;
    fn step(&mut self, state: &mut State<S::Partner>, h: f64) -> Result<StepInfo> {
        check_step(h)?;
        state.validate(self.system.dof())?;
        check_time_resolution(state.t, h)?;
        let (t, q, v) = (state.t, state.q.as_slice(), state.v.as_slice());
        self.system.admissible(t, q, v)?;
        let (sys, y) = (&self.system, &mut self.y);
        let [k1, k2, k3, k4] = &mut self.k;
        sys.rates(t, q, v, &mut k1.q, &mut k1.v)?;
        shifted(y, q, v, 0.5 * h, k1);
        sys.rates(t + 0.5 * h, &y.q, &y.v, &mut k2.q, &mut k2.v)?;
        shifted(y, q, v, 0.5 * h, k2);
        sys.rates(t + 0.5 * h, &y.q, &y.v, &mut k3.q, &mut k3.v)?;
        shifted(y, q, v, h, k3);
        sys.rates(t + h, &y.q, &y.v, &mut k4.q, &mut k4.v)?;
        for i in 0..q.len() {
            y.q[i] = q[i] + h / 6.0 * (k1.q[i] + 2.0 * (k2.q[i] + k3.q[i]) + k4.q[i]);
            y.v[i] = v[i] + h / 6.0 * (k1.v[i] + 2.0 * (k2.v[i] + k3.v[i]) + k4.v[i]);
        }
        Ok(y.commit(state, h)?.with_evaluations(4))
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
        4
    }
    fn name(&self) -> &'static str {
        "RK4"
    }
}

/// RK4's tableau (A by rows below the diagonal, b, c).
const RK4_TABLEAU: (&[&[f64]], &[f64], &[f64]) = (
    &[&[], &[0.5], &[0.0, 0.5], &[0.0, 0.0, 1.0]],
    &[1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
    &[0.0, 0.5, 0.5, 1.0],
);

/// Ψ of RK4 by its differentiated stages (see [`crate::tangent`]).
impl<S: LinearizedDynamics> TangentStepper for Rk4<S> {
    fn step_tangent(
        &mut self,
        state: &mut State<S::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        check_tangent_shape(psi, self.system.dof())?;
        step_then_tangent(self, state, h, |m, s, _| {
            explicit_rk_tangent(
                &m.system,
                (s.t, s.q.as_slice(), s.v.as_slice()),
                h,
                RK4_TABLEAU,
                psi,
            )
        })
    }
}

/// Ψ of forward Euler, I + hJ(y₀), and of Euler-Cromer,
///
/// ```text
/// ∂v₁/∂y₀ = [0 I] + h J_v(t, q₀, v₀),   ∂q₁/∂y₀ = [I 0] + h (J_qq(t, q₀, v₁) [I 0] + J_qv(t, q₀, v₁) ∂v₁/∂y₀),
/// ```
///
/// with J_v the v-rows of J and J_qq, J_qv the q-rows of J split by columns.
impl<S: LinearizedDynamics, R: FirstOrderRule> TangentStepper for FirstOrder<S, R> {
    fn step_tangent(
        &mut self,
        state: &mut State<S::Partner>,
        h: f64,
        psi: &mut DMatrix<f64>,
    ) -> Result<StepInfo> {
        let n = self.system.dof();
        check_tangent_shape(psi, n)?;
        step_then_tangent(self, state, h, |m, s, _| {
            let (t, q, v) = (s.t, s.q.as_slice(), s.v.as_slice());
            if !R::NEW_VELOCITIES {
                return explicit_rk_tangent(&m.system, (t, q, v), h, (&[&[]], &[1.0], &[0.0]), psi);
            }
            let mut jac = DMatrix::zeros(2 * n, 2 * n);
            m.system.jacobian(t, q, v, &mut jac)?;
            let mut out = DMatrix::identity(2 * n, 2 * n);
            // v-rows: [0 I] + h J_v(y₀).
            let dv1 = out.rows(n, n) + h * jac.rows(n, n);
            // q-rows at (q₀, v₁), v₁ = v₀ + h v̇(y₀).
            let (mut dq, mut v1) = (vec![0.0; n], vec![0.0; n]);
            m.system.rates(t, q, v, &mut dq, &mut v1)?;
            v1.iter_mut().zip(v).for_each(|(a, v)| *a = v + h * *a);
            m.system.jacobian(t, q, &v1, &mut jac)?;
            let dq1 = out.rows(0, n)
                + h * (jac.view((0, 0), (n, n)) * out.rows(0, n) + jac.view((0, n), (n, n)) * &dv1);
            out.rows_mut(0, n).copy_from(&dq1);
            out.rows_mut(n, n).copy_from(&dv1);
            crate::error::check_result("step Jacobian Ψ", t, out.as_slice())?;
            psi.copy_from(&out);
            Ok(())
        })
    }
}
