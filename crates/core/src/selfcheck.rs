//! Self-checks for any stepper, a user's own included: is its step symplectic, what order does it
//! show, is it reversible. noether's own tests use these same functions.
//!
//! - [`symplecticity`] / [`symplecticity_with_form`]: the defect ‖ΨᵀΩΨ − Ω‖_max of the step's Jacobian
//!   Ψ ([`TangentStepper`]) at sampled states, for the canonical form Ω = [[0, I], [−I, 0]] on (q, p)
//!   or a constant form the user gives (e.g. [`velocity_form`] = [[0, M], [−M, 0]] on (q, q̇) of a
//!   natural Lagrangian with a constant mass matrix M). A symplectic method gives rounding
//!   (≲ 1e-14 on unit-scale problems); RK4 gives O(h⁵) (O(h⁶) on linear problems).
//! - [`observed_order`] / [`observed_order_with`]: errors at a range of step counts against a
//!   reference, and the least-squares slope of log(error) against log(h) with its correlation
//!   coefficient ([`fit_order`], [`OrderFit`]). Any [`Stepper`].
//! - [`reversibility`]: ρ∘Φ_h∘ρ∘Φ_h with the time reversal ρ(q, v) = (q, −v), which is the identity
//!   (to rounding) for a symmetric method on a reversible autonomous system; the distance in ulps of
//!   the state's scale ([`Reversibility`]). Any [`Stepper`].
//!
//! Norm: "max" is the largest absolute entry, ‖A‖_max = max_ij |A_ij| (of a matrix) or
//! max_i |x_i| (of a state vector (q, v)).
//!
//! ```
//! use noether_core::prelude::*;
//! use noether_core::selfcheck;
//!
//! /// Pendulum H = ½p² − cos q.
//! struct Pendulum;
//! impl Hamiltonian for Pendulum {
//!     fn dof(&self) -> usize { 1 }
//!     fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
//!         p[0] * p[0] * 0.5 - q[0].cos()
//!     }
//! }
//!
//! let states = [State::with_momenta(0.0, [0.5], [0.3]), State::with_momenta(0.0, [2.0], [-0.4])];
//! let sys = HamiltonEquations::new(Pendulum);
//! // RK4 is not symplectic: a defect of order h⁵; Euler-Cromer (symplectic Euler here) is.
//! let rk4 = selfcheck::symplecticity(&mut Rk4::new(&sys), &states, 0.2).unwrap();
//! let ec = selfcheck::symplecticity(&mut EulerCromer::new(&sys), &states, 0.2).unwrap();
//! assert!(rk4.worst > 1e-8 && ec.worst < 1e-15);
//! // Its observed order against a finer run of itself is 4.
//! let exact = {
//!     let mut s = states[0].clone();
//!     let mut fine = Rk4::new(&sys);
//!     for _ in 0..4000 { fine.step(&mut s, 1e-3).unwrap(); }
//!     s
//! };
//! let fit = selfcheck::observed_order(&mut Rk4::new(&sys), &states[0], 4.0, &[20, 40, 80], &exact).unwrap();
//! assert!((fit.slope - 4.0).abs() < 0.1 && fit.r > 0.999);
//! ```

use crate::{Error, Momenta, Partner, Result, State, Stepper, TangentStepper};
use nalgebra::DMatrix;

/// The canonical symplectic form Ω = [[0, I], [−I, 0]] of (q, p) ∈ ℝ²ⁿ.
pub fn canonical_form(dof: usize) -> DMatrix<f64> {
    let mut omega = DMatrix::zeros(2 * dof, 2 * dof);
    for i in 0..dof {
        omega[(i, dof + i)] = 1.0;
        omega[(dof + i, i)] = -1.0;
    }
    omega
}

/// The form Ω = [[0, M], [−M, 0]] on (q, q̇) that the flow of a natural Lagrangian L = ½q̇ᵀMq̇ − V(q)
/// with a constant mass matrix M preserves: the pull-back of the canonical form by the Legendre map
/// p = Mq̇. `Dimension` unless M is square.
pub fn velocity_form(mass: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let n = mass.nrows();
    if mass.ncols() != n {
        return Err(Error::Dimension {
            what: "mass matrix M (columns)",
            expected: n,
            got: mass.ncols(),
        });
    }
    let mut omega = DMatrix::zeros(2 * n, 2 * n);
    omega.view_mut((0, n), (n, n)).copy_from(mass);
    omega.view_mut((n, 0), (n, n)).copy_from(&(-mass));
    Ok(omega)
}

/// ‖ΨᵀΩΨ − Ω‖_max, the largest entry of the defect: zero when the linear map Ψ preserves the form Ω.
pub fn form_defect(psi: &DMatrix<f64>, omega: &DMatrix<f64>) -> f64 {
    (psi.transpose() * omega * psi - omega).abs().max()
}

/// The defect of symplecticity ‖ΨᵀΩΨ − Ω‖_max at each sampled state, and the worst one.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct SymplecticDefect<K: Partner> {
    /// The largest defect over the states, max_k ‖Ψ_kᵀΩΨ_k − Ω‖_max.
    pub worst: f64,
    /// Index (into the states given) of the state with the largest defect.
    pub index: usize,
    /// The state with the largest defect (before the step).
    pub state: State<K>,
    /// The defect at each state, in the order given.
    pub defects: Vec<f64>,
    /// The step size used.
    pub h: f64,
}

/// The defect of symplecticity of one step of size `h` from each of `states` for the canonical form
/// Ω = [[0, I], [−I, 0]] of (q, p): ‖ΨᵀΩΨ − Ω‖_max with Ψ from
/// [`step_tangent`](TangentStepper::step_tangent) (module docs). A symplectic method gives rounding,
/// a non-symplectic one the defect of its local error. Errors of the steps are passed on;
/// `InvalidParameter` when `states` is empty.
pub fn symplecticity<S: TangentStepper<Partner = Momenta>>(
    stepper: &mut S,
    states: &[State<Momenta>],
    h: f64,
) -> Result<SymplecticDefect<Momenta>> {
    let omega = canonical_form(stepper.dof());
    symplecticity_with_form(stepper, states, h, &omega)
}

/// As [`symplecticity`] with a constant form Ω the user gives (2n × 2n, antisymmetric, ordered
/// (q, v) as Ψ), for steppers on any state: e.g. [`velocity_form`] for (q, q̇) of a natural
/// Lagrangian with constant mass matrix. `Dimension` when Ω is not 2n × 2n.
pub fn symplecticity_with_form<S: TangentStepper>(
    stepper: &mut S,
    states: &[State<S::Partner>],
    h: f64,
    omega: &DMatrix<f64>,
) -> Result<SymplecticDefect<S::Partner>> {
    let n = stepper.dof();
    crate::error::check_shape("symplectic form Ω (rows and columns)", omega, 2 * n, 2 * n)?;
    if states.is_empty() {
        return Err(Error::InvalidParameter {
            name: "number of sampled states",
            value: 0.0,
            reason: "give at least one state",
        });
    }
    let mut psi = DMatrix::zeros(2 * n, 2 * n);
    let mut defects = Vec::with_capacity(states.len());
    for s in states {
        let mut end = s.clone();
        stepper.step_tangent(&mut end, h, &mut psi)?;
        defects.push(form_defect(&psi, omega));
    }
    let (index, worst) = defects
        .iter()
        .copied()
        .enumerate()
        .fold(
            (0, f64::NEG_INFINITY),
            |best, (i, d)| if d > best.1 { (i, d) } else { best },
        );
    Ok(SymplecticDefect {
        worst,
        index,
        state: states[index].clone(),
        defects,
        h,
    })
}

/// A least-squares line through (log h, log error): the observed order of a method.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct OrderFit {
    /// The fitted slope of log(error) against log(h): the observed order.
    pub slope: f64,
    /// The fitted intercept: error ≈ e^intercept · h^slope.
    pub intercept: f64,
    /// Pearson's correlation coefficient of log(error) and log(h) (1 for errors exactly on a power
    /// law; well below 1 when the errors are not in the asymptotic range or meet rounding).
    pub r: f64,
    /// The points (h, error) fitted.
    pub points: Vec<(f64, f64)>,
}

/// The least-squares slope of log(error) against log(h) through `points` (h, error), with its
/// correlation coefficient. `InvalidParameter` with fewer than two points, an h or an error that is not
/// finite and positive, or all h equal.
pub fn fit_order(points: &[(f64, f64)]) -> Result<OrderFit> {
    if points.len() < 2 {
        return Err(Error::InvalidParameter {
            name: "number of (h, error) points",
            value: points.len() as f64,
            reason: "a fitted order needs at least two points",
        });
    }
    for &(h, e) in points {
        for (name, x) in [("step size h", h), ("error", e)] {
            if !(x.is_finite() && x > 0.0) {
                return Err(Error::InvalidParameter {
                    name,
                    value: x,
                    reason: "log-log fit: must be finite and positive",
                });
            }
        }
    }
    let logs: Vec<(f64, f64)> = points.iter().map(|(h, e)| (h.ln(), e.ln())).collect();
    let m = logs.len() as f64;
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / m;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / m;
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let syy: f64 = logs.iter().map(|p| (p.1 - my) * (p.1 - my)).sum();
    if sxx == 0.0 {
        return Err(Error::InvalidParameter {
            name: "step sizes h",
            value: points[0].0,
            reason: "a fitted order needs at least two different step sizes",
        });
    }
    let slope = sxy / sxx;
    // Equal errors (syy = 0) lie exactly on the horizontal line: a perfect fit of order 0.
    let r = if syy == 0.0 { 1.0 } else { sxy / (sxx * syy).sqrt() };
    Ok(OrderFit {
        slope,
        intercept: my - slope * mx,
        r,
        points: points.to_vec(),
    })
}

/// The observed order of `stepper`: for each n in `steps`, n fixed steps of size h = (t_end − t₀)/n
/// from `start`, the error ‖y_n − exact‖_max of the end state (q and v) against `exact`, and the fit
/// [`fit_order`] through the points (h, error). `exact` is the reference at t_end: a closed form, or
/// a finer run (of another method). The stepper must not be adaptive (`Unsupported`); errors of the
/// steps are passed on.
pub fn observed_order<S: Stepper>(
    stepper: &mut S,
    start: &State<S::Partner>,
    t_end: f64,
    steps: &[usize],
    exact: &State<S::Partner>,
) -> Result<OrderFit> {
    let n = stepper.dof();
    exact.validate(n)?;
    observed_order_with(stepper, start, t_end, steps, |end| {
        Ok(end
            .q
            .iter()
            .zip(exact.q.iter())
            .chain(end.v.iter().zip(exact.v.iter()))
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs())))
    })
}

/// As [`observed_order`] with the error measured by the user's closure `error(end)` of the end
/// state at t_end (a distance to a closed form, an energy error, …).
pub fn observed_order_with<S: Stepper>(
    stepper: &mut S,
    start: &State<S::Partner>,
    t_end: f64,
    steps: &[usize],
    mut error: impl FnMut(&State<S::Partner>) -> Result<f64>,
) -> Result<OrderFit> {
    if stepper.is_adaptive() {
        return Err(Error::Unsupported(
            "observed order of an adaptive method: its steps are its own choice; fit errors against tolerances instead",
        ));
    }
    start.validate(stepper.dof())?;
    let span = t_end - start.t;
    let mut points = Vec::with_capacity(steps.len());
    for &count in steps {
        if count == 0 {
            return Err(Error::InvalidParameter {
                name: "number of steps",
                value: 0.0,
                reason: "each run needs at least one step",
            });
        }
        let h = span / count as f64;
        let mut s = start.clone();
        for _ in 0..count {
            stepper.step(&mut s, h)?;
        }
        points.push((h, error(&s)?));
    }
    fit_order(&points)
}

/// How far ρ∘Φ_h∘ρ∘Φ_h lands from the start, ρ(q, v) = (q, −v) the time reversal.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Reversibility<K: Partner> {
    /// ‖ρΦ_hρΦ_h(y₀) − y₀‖_max over q and v.
    pub distance: f64,
    /// `distance` relative to the state's scale ‖y₀‖_max (1 when y₀ = 0).
    pub relative: f64,
    /// `distance` in units in the last place of the state's scale: distance / ulp(‖y₀‖_max).
    pub ulps: f64,
    /// The state the round trip ended at (time restored to the start).
    pub end: State<K>,
}

/// The reversibility of one step: from y₀, a step Φ_h, the time reversal ρ(q, v) = (q, −v), a
/// second step Φ_h, ρ again; for a symmetric (self-adjoint) method on a reversible autonomous system
/// (ρ∘φ_t∘ρ = φ_{−t}, e.g. L or H even in the velocities or momenta) this is the identity, up to
/// rounding and the solver tolerance of an implicit method: a few ulps of the state's scale. A
/// non-symmetric method misses by its local error (Euler-Cromer O(h²), RK4 O(h⁵)). Steppers refuse
/// h < 0, so ρ stands in for the backward step. The time of the state goes forward twice and is
/// restored to the start in [`Reversibility::end`]: the check is meant for autonomous systems.
pub fn reversibility<S: Stepper>(
    stepper: &mut S,
    state: &State<S::Partner>,
    h: f64,
) -> Result<Reversibility<S::Partner>> {
    let n = stepper.dof();
    state.validate(n)?;
    let mut s = state.clone();
    stepper.step(&mut s, h)?;
    s.v.neg_mut();
    stepper.step(&mut s, h)?;
    s.v.neg_mut();
    s.t = state.t;
    let distance =
        s.q.iter()
            .zip(state.q.iter())
            .chain(s.v.iter().zip(state.v.iter()))
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    let scale = state
        .q
        .iter()
        .chain(state.v.iter())
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    let scale = if scale > 0.0 { scale } else { 1.0 };
    Ok(Reversibility {
        distance,
        relative: distance / scale,
        ulps: distance / ulp(scale),
        end: s,
    })
}

/// The spacing of the floating-point numbers at |x| (x finite and non-zero): next_up(|x|) − |x|.
fn ulp(x: f64) -> f64 {
    let a = x.abs();
    f64::from_bits(a.to_bits() + 1) - a
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fit_of_an_exact_power_law() {
        let pts: Vec<(f64, f64)> = [0.1, 0.05, 0.025]
            .iter()
            .map(|&h: &f64| (h, 3.0 * h.powi(4)))
            .collect();
        let f = fit_order(&pts).unwrap();
        assert!((f.slope - 4.0).abs() < 1e-12 && (f.r - 1.0).abs() < 1e-12);
        assert!((f.intercept - 3f64.ln()).abs() < 1e-11);
        assert!(fit_order(&pts[..1]).is_err());
        assert!(fit_order(&[(0.1, 1.0), (0.1, 2.0)]).is_err());
        assert!(fit_order(&[(0.1, 0.0), (0.2, 2.0)]).is_err());
    }

    #[test]
    fn ulp_of_one_is_epsilon() {
        assert_eq!(ulp(1.0), f64::EPSILON);
        assert_eq!(ulp(-3.0), 2.0 * f64::EPSILON);
    }

    #[test]
    fn forms() {
        let o = canonical_form(2);
        assert_eq!(o[(0, 2)], 1.0);
        assert_eq!(o[(3, 1)], -1.0);
        let m = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 3.0]);
        let v = velocity_form(&m).unwrap();
        assert_eq!(v[(1, 2)], 1.0);
        assert_eq!(v[(3, 1)], -3.0);
        assert!(velocity_form(&DMatrix::zeros(2, 3)).is_err());
    }
}
