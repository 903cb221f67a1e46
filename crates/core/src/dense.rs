//! Continuous extensions of a step: y(t) for t inside [t₀, t₀ + h], on which output times are sampled
//! and events located.
//!
//! One type, [`DenseOutput`], holds every interpolant noether uses, as a polynomial in θ = (t − t₀)/h
//! given by coefficient vectors over y = (q, v):
//! - the method's own continuous extension where it has one: order 4 for DOPRI5 and 7 for DOP853
//!   (Hairer-Nørsett-Wanner I, II.6), built by the adaptive steppers;
//! - the cubic Hermite interpolant [`DenseOutput::hermite`] through the values and the vector field at
//!   both ends of the step, for methods without one that can evaluate their vector field (the explicit,
//!   symplectic, Gauss and particle methods): y(t₀ + θh) = y₀ + θ(r₁ + (1 − θ)(r₂ + θ r₃)) with
//!   r₁ = y₁ − y₀, r₂ = h f₀ − r₁, r₃ = r₁ − h f₁ − r₂; its error is h⁴ max‖y⁗‖/384 (order 3);
//! - the straight line [`DenseOutput::linear`] between the ends, error h² max‖y″‖/8 (order 1), for the
//!   methods that have no vector field to evaluate (a variational integrator of a discrete Lagrangian
//!   given by the user).
//!
//! The [`Driver`](crate::Driver) chooses the first that the stepper offers, and says which in
//! [`Solution::interpolation_order`](crate::Solution::interpolation_order).

use crate::error::check_len;
use crate::roots::bracketed_root;
use crate::{Error, Partner, Result, State, Velocities};
use std::marker::PhantomData;

/// y(t₀ + θh) from θ, y₀ and the coefficient vectors of an interpolant.
pub type DenseEval = fn(f64, &[f64], &[Vec<f64>], &mut [f64]);

/// The continuous extension of one step, valid for t in [t₀, t₀ + h] (see the [module](self) docs),
/// on states of kind `K` (velocities or momenta, like the stepper's).
#[derive(Debug, Clone)]
pub struct DenseOutput<K = Velocities> {
    t0: f64,
    h: f64,
    n: usize,
    order: u32,
    y0: Vec<f64>,
    coeffs: Vec<Vec<f64>>,
    eval: DenseEval,
    partner: PhantomData<K>,
}

impl<K: Partner> DenseOutput<K> {
    /// An interpolant over [t0, t0 + h] on y = (q, v) of length 2n, given y₀, its coefficient vectors and
    /// the formula `eval` that combines them; `order` is its order of accuracy.
    pub fn from_coefficients(
        t0: f64,
        h: f64,
        order: u32,
        y0: Vec<f64>,
        coeffs: Vec<Vec<f64>>,
        eval: DenseEval,
    ) -> Self {
        DenseOutput {
            t0,
            h,
            n: y0.len() / 2,
            order,
            y0,
            coeffs,
            eval,
            partner: PhantomData,
        }
    }

    /// The cubic Hermite interpolant over [t0, t0 + h] through y₀ = (q₀, v₀) with rate f₀ and y₁ with rate
    /// f₁ (each of length 2n, q-part first); order 3. Vectors of different or odd lengths are an
    /// [`Error::Dimension`], a step that is not finite and positive an [`Error::InvalidStep`], and a
    /// value that is not finite an [`Error::NonFinite`].
    pub fn hermite(t0: f64, h: f64, y0: &[f64], f0: &[f64], y1: &[f64], f1: &[f64]) -> Result<Self> {
        check_ends(t0, h, y0, &[("f0", f0), ("y1", y1), ("f1", f1)])?;
        let mut c = vec![vec![0.0; y0.len()]; 3];
        for i in 0..y0.len() {
            let dy = y1[i] - y0[i];
            let r2 = h * f0[i] - dy;
            c[0][i] = dy;
            c[1][i] = r2;
            c[2][i] = dy - h * f1[i] - r2;
        }
        Ok(Self::from_coefficients(t0, h, 3, y0.to_vec(), c, hermite_eval))
    }

    /// The straight line over [t0, t0 + h] from y₀ to y₁; order 1 (errors as for
    /// [`hermite`](Self::hermite)).
    pub fn linear(t0: f64, h: f64, y0: &[f64], y1: &[f64]) -> Result<Self> {
        check_ends(t0, h, y0, &[("y1", y1)])?;
        let dy = y1.iter().zip(y0).map(|(b, a)| b - a).collect();
        Ok(Self::from_coefficients(
            t0,
            h,
            1,
            y0.to_vec(),
            vec![dy],
            linear_eval,
        ))
    }

    /// The coefficient vectors, to be refilled for the next step without allocating.
    pub(crate) fn into_coefficients(self) -> Vec<Vec<f64>> {
        self.coeffs
    }

    /// y₀ and the coefficient vectors, to be refilled for the next step without allocating.
    pub(crate) fn into_parts(self) -> (Vec<f64>, Vec<Vec<f64>>) {
        (self.y0, self.coeffs)
    }

    /// Start of the step.
    pub fn t_start(&self) -> f64 {
        self.t0
    }

    /// End of the step.
    pub fn t_end(&self) -> f64 {
        self.t0 + self.h
    }

    /// Order of accuracy of the interpolant (its error is O(h^(order+1)) inside the step).
    pub fn order(&self) -> u32 {
        self.order
    }

    /// Number of coordinates.
    pub fn dof(&self) -> usize {
        self.n
    }

    /// Writes y(t) into `q` and `v`. The interpolant holds inside its step only: a time outside
    /// [t₀, t₀ + h] (beyond the rounding margin of [`contains`](Self::contains)) is an error, not an
    /// extrapolation.
    pub fn eval(&self, t: f64, q: &mut [f64], v: &mut [f64]) -> Result<()> {
        self.check_time(t)?;
        check_len("q (output)", q, self.n)?;
        check_len("v (output)", v, self.n)?;
        self.fill(t, q, v);
        Ok(())
    }

    /// Overwrites `state` with the interpolated state at time `t` (see [`eval`](Self::eval)).
    pub fn eval_state(&self, t: f64, state: &mut State<K>) -> Result<()> {
        self.eval(t, state.q.as_mut_slice(), state.v.as_mut_slice())?;
        state.t = t;
        Ok(())
    }

    /// The interpolated state at time `t` (see [`eval`](Self::eval)).
    pub fn state_at(&self, t: f64) -> Result<State<K>> {
        self.check_time(t)?;
        let mut s = State::zeros(t, self.n);
        self.fill_state(t, &mut s)?;
        Ok(s)
    }

    /// `true` when t lies in the step [t₀, t₀ + h], to a rounding margin of 1e-12 h plus 4 ulps of the
    /// larger end time: t₀ + h itself is rounded, and at large t (t₀ = 1e7, h = 1e-6) the computed end
    /// of a step can differ from the driver's time by more than 1e-12 h.
    pub fn contains(&self, t: f64) -> bool {
        let end = self.t0 + self.h;
        let margin = 1e-12 * self.h.abs() + 4.0 * f64::EPSILON * self.t0.abs().max(end.abs());
        t >= self.t0 - margin && t <= end + margin
    }

    /// An error unless t lies in the step ([`contains`](Self::contains)).
    fn check_time(&self, t: f64) -> Result<()> {
        if self.contains(t) {
            return Ok(());
        }
        Err(Error::InvalidParameter {
            name: "t",
            value: t,
            reason: "outside the step of this dense output (an interpolant does not extrapolate)",
        })
    }

    /// y(t) into `q` and `v`, unchecked (the driver's own calls, inside the step by construction).
    fn fill(&self, t: f64, q: &mut [f64], v: &mut [f64]) {
        let mut y = vec![0.0; 2 * self.n];
        (self.eval)((t - self.t0) / self.h, &self.y0, &self.coeffs, &mut y);
        q.copy_from_slice(&y[..self.n]);
        v.copy_from_slice(&y[self.n..]);
    }

    /// [`eval_state`](Self::eval_state) into a state the driver made of the right size: the time is
    /// still checked (a reset that moved t must not make the next step's interpolant extrapolate).
    pub(crate) fn fill_state(&self, t: f64, state: &mut State<K>) -> Result<()> {
        self.check_time(t)?;
        self.fill(t, state.q.as_mut_slice(), state.v.as_mut_slice());
        state.t = t;
        Ok(())
    }

    /// A time in the step where `g(state)` vanishes, when g changes sign between the ends of the step,
    /// located to rounding by the one root finder ([`bracketed_root`]); `Ok(None)` when g has the same
    /// sign at both ends. A g that is not finite at an end or at a point the root finder tries is an
    /// error ([`Error::NonFinite`] or [`Error::NonFiniteResult`]), not a guess.
    pub fn locate(&self, mut g: impl FnMut(&State<K>) -> f64) -> Result<Option<f64>> {
        let mut s = State::zeros(self.t0, self.n);
        let mut g_at = |t: f64| {
            self.fill(t, s.q.as_mut_slice(), s.v.as_mut_slice());
            s.t = t;
            g(&s)
        };
        let (a, b) = (self.t0, self.t_end());
        let (ga, gb) = (g_at(a), g_at(b));
        if !(ga.is_finite() && gb.is_finite()) {
            let index = usize::from(ga.is_finite());
            return Err(Error::NonFinite {
                what: "function at the ends of the step",
                index,
            });
        }
        if ga * gb > 0.0 {
            return Ok(None);
        }
        bracketed_root(g_at, (a, ga), (b, gb)).map(Some)
    }
}

/// Checks the data of an interpolant built from its ends: h finite and positive, t₀ finite, y₀ of even
/// length 2n and finite, and each other vector of y₀'s length and finite.
fn check_ends(t0: f64, h: f64, y0: &[f64], others: &[(&'static str, &[f64])]) -> Result<()> {
    crate::error::check_step(h)?;
    crate::error::check_finite("t0", &[t0])?;
    if !y0.len().is_multiple_of(2) {
        return Err(Error::Dimension {
            what: "y0 (q then the partner)",
            expected: y0.len() + 1,
            got: y0.len(),
        });
    }
    crate::error::check_finite("y0", y0)?;
    for &(what, x) in others {
        check_len(what, x, y0.len())?;
        crate::error::check_finite(what, x)?;
    }
    Ok(())
}

/// y₀ + θ(r₁ + (1 − θ)(r₂ + θ r₃)).
fn hermite_eval(theta: f64, y0: &[f64], c: &[Vec<f64>], out: &mut [f64]) {
    let s = 1.0 - theta;
    for i in 0..y0.len() {
        out[i] = y0[i] + theta * (c[0][i] + s * (c[1][i] + theta * c[2][i]));
    }
}

/// y(θ) = y₀ + θ Σ_m `c[m]` θ^m = y₀ + θ(c₀ + θ(c₁ + … + θ c_last)) by Horner's rule: the evaluation
/// of the dense outputs stored as plain power series ([`Nystrom`](crate::integrators::Nystrom),
/// [`Ias15`](crate::integrators::Ias15)).
pub(crate) fn horner_eval(theta: f64, y0: &[f64], c: &[Vec<f64>], out: &mut [f64]) {
    let last = c.len() - 1;
    for i in 0..y0.len() {
        let mut acc = c[last][i];
        for cm in c[..last].iter().rev() {
            acc = cm[i] + theta * acc;
        }
        out[i] = y0[i] + theta * acc;
    }
}

/// y₀ + θ r₁.
fn linear_eval(theta: f64, y0: &[f64], c: &[Vec<f64>], out: &mut [f64]) {
    for i in 0..y0.len() {
        out[i] = y0[i] + theta * c[0][i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_form_hermite_reproduces_cubics() {
        // y = (t³ − 2t, 3t² − 2) with its exact rates (3t² − 2, 6t) is a cubic: reproduced exactly.
        let y = |t: f64| [t * t * t - 2.0 * t, 3.0 * t * t - 2.0];
        let f = |t: f64| [3.0 * t * t - 2.0, 6.0 * t];
        let (t0, h) = (0.5, 0.75);
        let d: DenseOutput = DenseOutput::hermite(t0, h, &y(t0), &f(t0), &y(t0 + h), &f(t0 + h)).unwrap();
        for t in [0.5, 0.6, 0.9, 1.25] {
            let s = d.state_at(t).unwrap();
            let e = y(t);
            // Rounding of a few operations on O(1) values.
            assert!(
                (s.q[0] - e[0]).abs() < 1e-15 && (s.v[0] - e[1]).abs() < 1e-14,
                "t = {t}"
            );
        }
        assert_eq!(d.order(), 3);
        // Issue 15, case 10: outside its step the interpolant used to extrapolate silently.
        for t in [0.4, 1.3, f64::NAN] {
            assert!(
                matches!(d.state_at(t), Err(Error::InvalidParameter { name: "t", .. })),
                "t = {t}"
            );
        }
        let (mut q, mut v) = ([0.0; 2], [0.0]);
        assert!(matches!(
            d.eval(1.0, &mut q, &mut v),
            Err(Error::Dimension { .. })
        ));
    }

    #[test]
    fn closed_form_locate_on_hermite() {
        // q = sin t over one step [2.6, 3.6] by Hermite: its root π is found within the interpolant's
        // error bound h⁴/384 ≈ 2.6e-3 (|sin⁗| ≤ 1, |q̇| ≈ 1 at the root).
        let (t0, h) = (2.6f64, 1.0);
        let y = |t: f64| [t.sin(), t.cos()];
        let f = |t: f64| [t.cos(), -t.sin()];
        let d: DenseOutput = DenseOutput::hermite(t0, h, &y(t0), &f(t0), &y(t0 + h), &f(t0 + h)).unwrap();
        let r = d.locate(|s| s.q[0]).unwrap().unwrap();
        assert!((r - std::f64::consts::PI).abs() < 2.6e-3, "{r}");
        assert!(d.locate(|s| s.q[0] + 2.0).unwrap().is_none());
        // Issue 29 item 4: g NaN inside the step (finite at both ends) is an error, not a root 0.02 off.
        let nan_inside = |s: &State| {
            if (2.9..3.3).contains(&s.t) {
                f64::NAN
            } else {
                s.q[0]
            }
        };
        assert!(matches!(d.locate(nan_inside), Err(Error::NonFiniteResult { .. })));
    }

    #[test]
    fn bad_input_interpolant_from_mismatched_or_non_finite_ends() {
        // Issue 29 items 11 and 12: these used to panic (lengths) or return an interpolant of NaN.
        let (y, f) = ([1.0, 0.0], [0.0, -1.0]);
        let short = [1.0];
        assert!(matches!(
            DenseOutput::<Velocities>::hermite(0.0, 0.1, &y, &f, &short, &f),
            Err(Error::Dimension { .. })
        ));
        assert!(matches!(
            DenseOutput::<Velocities>::linear(0.0, 0.1, &y, &short),
            Err(Error::Dimension { .. })
        ));
        assert!(matches!(
            DenseOutput::<Velocities>::linear(0.0, 0.1, &y, &[f64::NAN, 0.0]),
            Err(Error::NonFinite { what: "y1", .. })
        ));
        assert!(matches!(
            DenseOutput::<Velocities>::linear(0.0, f64::NAN, &y, &y),
            Err(Error::InvalidStep { .. })
        ));
    }

    #[test]
    fn regress_step_end_accepted_at_large_times() {
        // Issue 29 item 14: at t₀ = 1e7 with h = 1e-6 the rounding of t₀ + h (ulp 1.9e-9) is far above
        // 1e-12 h; the step's own end, and the driver's time one ulp past it, must be accepted.
        let (t0, h) = (1e7, 1e-6);
        let d: DenseOutput = DenseOutput::linear(t0, h, &[0.0, 1.0], &[1e-6, 1.0]).unwrap();
        let end = d.t_end();
        for t in [t0, end, end.next_up(), t0.next_down()] {
            assert!(d.state_at(t).is_ok(), "t = {t}");
        }
        // Eight ulps past the end is outside (the margin is four).
        let mut far = end;
        for _ in 0..8 {
            far = far.next_up();
        }
        assert!(d.state_at(far).is_err());
    }
}
