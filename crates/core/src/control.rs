//! Inputs: the controls u of a model, the laws that set them, and the closed loop.
//!
//! An [`Actuated`] Lagrangian has m inputs u that act through a generalized force Q_u(t, q, q̇, u),
//! written once over the scalar like L, so Lagrange's equations read
//!
//! ```text
//! d/dt(∂L/∂q̇) − ∂L/∂q = Q(t, q, q̇) + Q_u(t, q, q̇, u),
//! ```
//!
//! with u a block of its own: the linearisation's B = ∂(q̇, q̈)/∂u takes ∂Q_u/∂u by dual numbers
//! (noether-analysis). A [`Policy`] gives u, open-loop u(t) or feedback u(t, q, q̇), also generic, and
//! [`ClosedLoop`] puts the two together as an ordinary [`Lagrangian`] whose generalized force is
//! Q + Q_u(u(t, q, q̇)): every integrator, tangent and Jacobian of noether runs it, the policy's
//! derivatives included.
//!
//! ```
//! use noether_core::control::{Actuated, ClosedLoop, LinearFeedback};
//! use noether_core::prelude::*;
//!
//! /// A mass on a spring pushed by a force u: L = ½ q̇² − ½ q², Q_u = u.
//! struct Pushed;
//! impl Lagrangian for Pushed {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         (v[0] * v[0] - q[0] * q[0]) * 0.5
//!     }
//! }
//! impl Actuated for Pushed {
//!     fn inputs(&self) -> usize { 1 }
//!     fn input_force<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], u: &[D], out: &mut [D]) {
//!         out[0] = u[0];
//!     }
//! }
//!
//! // u = −2 q̇ damps it: q̈ = −q − 2q̇ at (q, q̇) = (1, 0.5) is −2.
//! let feedback = LinearFeedback::new(nalgebra::DMatrix::from_row_slice(1, 2, &[0.0, 2.0]), &[0.0], &[0.0], &[0.0])?;
//! let el = EulerLagrange::new(ClosedLoop::new(Pushed, feedback)?);
//! let mut a = [0.0];
//! el.accelerations(0.0, &[1.0], &[0.5], &mut a)?;
//! assert_eq!(a[0], -2.0);
//! # Ok::<(), noether_core::Error>(())
//! ```

use crate::ad::Buf;
use crate::{Error, Lagrangian, Result, Scalar};
use nalgebra::DMatrix;

/// A Lagrangian with m inputs u acting through the generalized force Q_u(t, q, q̇, u) (see the
/// [module docs](self)).
pub trait Actuated: Lagrangian {
    /// Number of inputs m.
    fn inputs(&self) -> usize;

    /// Q_u(t, q, q̇, u) written into `out` (length `dof()`), with `u` of length [`inputs`](Self::inputs).
    fn input_force<D: Scalar>(&self, t: D, q: &[D], v: &[D], u: &[D], out: &mut [D]);
}

/// ∂Q_u/∂u (n × m) of `model` at (t, q, q̇, u): one `Dual64` evaluation of the input force per
/// input. No checks (the linearisations that call it check their arguments first).
pub fn input_jacobian<A: Actuated + ?Sized>(
    model: &A,
    t: f64,
    q: &[f64],
    v: &[f64],
    u: &[f64],
) -> DMatrix<f64> {
    use num_dual::Dual64;
    let (n, m) = (model.dof(), u.len());
    let (qd, vd) = (Buf::<Dual64, 16>::constants(q), Buf::<Dual64, 16>::constants(v));
    let mut du = DMatrix::zeros(n, m);
    let mut force = vec![Dual64::from(0.0); n];
    for j in 0..m {
        let ud = Buf::<Dual64, 16>::new(m, |k| Dual64::new(u[k], if k == j { 1.0 } else { 0.0 }));
        model.input_force(Dual64::from(t), &qd, &vd, &ud, &mut force);
        for (i, f) in force.iter().enumerate() {
            du[(i, j)] = f.eps;
        }
    }
    du
}

/// The linearisation (A, B) of an actuated system at an operating point, with the drift there:
/// δẋ = A δx + B δu about x*, u*, where ẋ* = `drift`. Made by `noether_analysis::linearize` (x = (q, q̇))
/// and, for constrained models in independent coordinates, `noether_constraints::linearize`.
#[derive(Debug, Clone, PartialEq)]
pub struct Linearization {
    /// A = ∂ẋ/∂x.
    pub a: DMatrix<f64>,
    /// B = ∂ẋ/∂u.
    pub b: DMatrix<f64>,
    /// ẋ* at the point: zero at an equilibrium.
    pub drift: nalgebra::DVector<f64>,
}

impl<A: Actuated + ?Sized> Actuated for &A {
    fn inputs(&self) -> usize {
        (**self).inputs()
    }
    fn input_force<D: Scalar>(&self, t: D, q: &[D], v: &[D], u: &[D], out: &mut [D]) {
        (**self).input_force(t, q, v, u, out)
    }
}

/// A law that sets the inputs: u(t, q, q̇), generic over the scalar so that a closed loop can be
/// differentiated (its Jacobian, its tangents) with the policy's derivatives.
pub trait Policy {
    /// Number of inputs it sets.
    fn inputs(&self) -> usize;

    /// u(t, q, q̇) written into `u`.
    fn control<D: Scalar>(&self, t: D, q: &[D], v: &[D], u: &mut [D]);
}

impl<P: Policy + ?Sized> Policy for &P {
    fn inputs(&self) -> usize {
        (**self).inputs()
    }
    fn control<D: Scalar>(&self, t: D, q: &[D], v: &[D], u: &mut [D]) {
        (**self).control(t, q, v, u)
    }
}

/// Constant inputs u (an operating point's, or none at all).
#[derive(Debug, Clone, PartialEq)]
pub struct Constant(pub Vec<f64>);

impl Policy for Constant {
    fn inputs(&self) -> usize {
        self.0.len()
    }
    fn control<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], u: &mut [D]) {
        u.iter_mut().zip(&self.0).for_each(|(ui, ci)| *ui = D::from(*ci));
    }
}

/// Open-loop inputs u(t) from a function of time (a schedule, a table). Its values enter as constants:
/// the derivatives in q and q̇ are zero, as they are.
pub struct OpenLoop<F> {
    inputs: usize,
    schedule: F,
}

impl<F: Fn(f64, &mut [f64])> OpenLoop<F> {
    /// `inputs` inputs set by `schedule(t, u)`.
    pub fn new(inputs: usize, schedule: F) -> Self {
        OpenLoop { inputs, schedule }
    }
}

impl<F: Fn(f64, &mut [f64])> Policy for OpenLoop<F> {
    fn inputs(&self) -> usize {
        self.inputs
    }
    fn control<D: Scalar>(&self, t: D, _q: &[D], _v: &[D], u: &mut [D]) {
        // On the stack for small models: this runs at every evaluation of a closed loop's force.
        let mut values = Buf::<f64, 16>::filled(self.inputs, 0.0);
        (self.schedule)(t.re(), &mut values);
        u.iter_mut()
            .zip(values.iter())
            .for_each(|(ui, x)| *ui = D::from(*x));
    }
}

/// Linear state feedback about an operating point (q*, q̇*, u*):
/// u = u* − K [q − q*; q̇ − q̇*], K of size m × 2n (an LQR gain, say).
#[derive(Debug, Clone, PartialEq)]
pub struct LinearFeedback {
    gain: DMatrix<f64>,
    point: Vec<f64>,
    input: Vec<f64>,
}

impl LinearFeedback {
    /// The feedback of gain K (m × 2n) about (q*, q̇*) with inputs u* there. `Dimension` unless K has
    /// 2n columns for n = q*.len() = q̇*.len() and m = u*.len() rows; non-finite entries are refused.
    pub fn new(gain: DMatrix<f64>, q: &[f64], v: &[f64], u: &[f64]) -> Result<Self> {
        let n = q.len();
        crate::error::check_len("operating point q̇*", v, n)?;
        if gain.ncols() != 2 * n || gain.nrows() != u.len() {
            return Err(Error::Dimension {
                what: "feedback gain K (m × 2n)",
                expected: if gain.ncols() != 2 * n { 2 * n } else { u.len() },
                got: if gain.ncols() != 2 * n {
                    gain.ncols()
                } else {
                    gain.nrows()
                },
            });
        }
        crate::error::check_finite("feedback gain K", gain.as_slice())?;
        let point: Vec<f64> = q.iter().chain(v).copied().collect();
        crate::error::check_finite("operating point (q*, q̇*)", &point)?;
        crate::error::check_finite("operating inputs u*", u)?;
        Ok(LinearFeedback {
            gain,
            point,
            input: u.to_vec(),
        })
    }

    /// The gain K.
    pub fn gain(&self) -> &DMatrix<f64> {
        &self.gain
    }
}

impl Policy for LinearFeedback {
    fn inputs(&self) -> usize {
        self.input.len()
    }
    fn control<D: Scalar>(&self, _t: D, q: &[D], v: &[D], u: &mut [D]) {
        let n = q.len();
        for (i, ui) in u.iter_mut().enumerate() {
            let mut s = D::from(self.input[i]);
            for (j, xj) in q.iter().chain(v).enumerate().take(2 * n) {
                s -= (*xj - self.point[j]) * self.gain[(i, j)];
            }
            *ui = s;
        }
    }
}

/// An [`Actuated`] model with its inputs set by a [`Policy`]: a [`Lagrangian`] whose generalized
/// force is Q(t, q, q̇) + Q_u(t, q, q̇, u(t, q, q̇)).
#[derive(Debug, Clone)]
pub struct ClosedLoop<A, P> {
    model: A,
    policy: P,
}

impl<A: Actuated, P: Policy> ClosedLoop<A, P> {
    /// `model` driven by `policy`; `Dimension` unless the policy sets as many inputs as the model has.
    pub fn new(model: A, policy: P) -> Result<Self> {
        if policy.inputs() != model.inputs() {
            return Err(Error::Dimension {
                what: "inputs set by the policy",
                expected: model.inputs(),
                got: policy.inputs(),
            });
        }
        Ok(ClosedLoop { model, policy })
    }

    /// The model.
    pub fn model(&self) -> &A {
        &self.model
    }

    /// The policy.
    pub fn policy(&self) -> &P {
        &self.policy
    }

    /// The inputs u(t, q, q̇) the policy sets (to record them along a run, e.g. with
    /// [`Driver::observe`](crate::Driver::observe)).
    pub fn inputs_at(&self, t: f64, q: &[f64], v: &[f64]) -> Vec<f64> {
        let mut u = vec![0.0; self.model.inputs()];
        self.policy.control(t, q, v, &mut u);
        u
    }
}

impl<A: Actuated, P: Policy> Lagrangian for ClosedLoop<A, P> {
    fn dof(&self) -> usize {
        self.model.dof()
    }
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        self.model.lagrangian(t, q, v)
    }
    fn constant_mass_matrix(&self) -> bool {
        self.model.constant_mass_matrix()
    }
    fn has_generalized_force(&self) -> bool {
        true
    }
    fn generalized_force<D: Scalar>(&self, t: D, q: &[D], v: &[D], out: &mut [D]) {
        // On the stack for small models: this runs at every evaluation of the equations of motion.
        let mut u = Buf::<D, 16>::filled(self.model.inputs(), D::zero());
        self.policy.control(t, q, v, &mut u);
        self.model.input_force(t, q, v, &u, out);
        if self.model.has_generalized_force() {
            let mut own = Buf::<D, 16>::filled(out.len(), D::zero());
            self.model.generalized_force(t, q, v, &mut own);
            out.iter_mut().zip(own.iter()).for_each(|(o, f)| *o += *f);
        }
    }
}
