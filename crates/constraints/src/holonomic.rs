//! Holonomic constraints φ(t, q) = 0, written once as generic code; Φ_q, φ_t and the acceleration
//! terms come from dual numbers.
//!
//! ```
//! use noether_constraints::{Holonomic, HolonomicSet, ConstraintSet};
//! use noether_core::Scalar;
//!
//! /// A pendulum rod of length l in Cartesian coordinates: φ = (x² + y² − l²)/2.
//! struct Rod { l: f64 }
//! impl Holonomic for Rod {
//!     fn dof(&self) -> usize { 2 }
//!     fn count(&self) -> usize { 1 }
//!     fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
//!         out[0] = (q[0] * q[0] + q[1] * q[1] - self.l * self.l) * 0.5;
//!     }
//! }
//!
//! let phi = &mut [0.0];
//! noether_constraints::holonomic::values(&Rod { l: 2.0 }, 0.0, &[1.2, -1.6], phi)?; // 1.44 + 2.56 − 4
//! assert!(phi[0].abs() < 1e-15);
//! let rod = HolonomicSet(Rod { l: 2.0 });
//! let mut a = nalgebra::DMatrix::zeros(1, 2);
//! rod.matrix(0.0, &[1.2, -1.6], &[0.0, 0.0], &mut a); // Φ_q = (x, y)
//! assert_eq!((a[(0, 0)], a[(0, 1)]), (1.2, -1.6));
//! let mut c = [0.0];
//! rod.bias(0.0, &[1.2, -1.6], &[0.8, 0.6], &mut c); // (Φ_q q̇)_q q̇ = |q̇|²
//! assert!((c[0] - 1.0).abs() < 1e-15);
//! # Ok::<(), noether_constraints::Error>(())
//! ```

use crate::jets::{self, Block, Variation, VectorField};
use crate::set::{ConstraintSet, SetDerivatives};
use crate::Result;
use nalgebra::DMatrix;
use noether_core::error::{check_finite, check_len, check_result};
use noether_core::{Error, Scalar};

/// m holonomic constraints φ(t, q) = 0 on n coordinates.
///
/// Write the constraint values into `out` (length `count()`), generic over the scalar type like a
/// Lagrangian. Scale each constraint so that its gradient has a natural size (e.g. (|r|² − l²)/2 for a
/// rod): the multipliers are then forces per unit of that gradient.
pub trait Holonomic {
    /// Number of coordinates n.
    fn dof(&self) -> usize;
    /// Number of constraints m.
    fn count(&self) -> usize;
    /// φ(t, q) into `out`.
    fn constraints<D: Scalar>(&self, t: D, q: &[D], out: &mut [D]);
}

impl<C: Holonomic + ?Sized> Holonomic for &C {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn count(&self) -> usize {
        (**self).count()
    }
    fn constraints<D: Scalar>(&self, t: D, q: &[D], out: &mut [D]) {
        (**self).constraints(t, q, out)
    }
}

/// φ(t, q) seen as the vector field g(t, x = q, y = ·).
struct Field<'a, C: ?Sized>(&'a C);

impl<C: Holonomic + ?Sized> VectorField for Field<'_, C> {
    fn outputs(&self) -> usize {
        self.0.count()
    }
    #[inline]
    fn eval<D: Scalar>(&self, t: D, x: &[D], _y: &[D], out: &mut [D]) {
        self.0.constraints(t, x, out)
    }
}

// The checked functions below are the public face: lengths first (the user's constraint function
// indexes q and out freely, so it must never see a wrong length), finite input, finite output, and
// `out` written only on success. The crate's own callers, which have checked the lengths once per
// step, use the `*_unchecked` forms inside their Newton loops.

/// Checks (t, q) and the output length m against the constraint set: [`Error::Dimension`] or
/// [`Error::NonFinite`].
fn check_args<C: Holonomic + ?Sized>(c: &C, t: f64, q: &[f64], out_len: usize) -> Result<()> {
    check_len("q", q, c.dof())?;
    if out_len != c.count() {
        return Err(Error::Dimension {
            what: "constraint values (output)",
            expected: c.count(),
            got: out_len,
        }
        .into());
    }
    check_finite("t", &[t])?;
    Ok(check_finite("q", q)?)
}

/// Runs `eval` into scratch space, checks the result finite (else [`Error::NonFiniteResult`] naming
/// `what`) and only then copies it into `out`.
fn into_checked(what: &'static str, t: f64, out: &mut [f64], eval: impl FnOnce(&mut [f64])) -> Result<()> {
    let mut r = vec![0.0; out.len()];
    eval(&mut r);
    check_result(what, t, &r)?;
    out.copy_from_slice(&r);
    Ok(())
}

/// φ(t, q) into `out` (length m).
///
/// q must have n = `dof()` entries and `out` m = `count()` ([`Error::Dimension`], checked before the
/// constraint function is called); t and q finite ([`Error::NonFinite`]); a non-finite φ is
/// [`Error::NonFiniteResult`]. On error `out` is left as it was.
pub fn values<C: Holonomic + ?Sized>(c: &C, t: f64, q: &[f64], out: &mut [f64]) -> Result<()> {
    check_args(c, t, q, out.len())?;
    into_checked("constraint values φ(t, q)", t, out, |r| {
        values_unchecked(c, t, q, r)
    })
}

/// φ(t, q) into `out`, lengths unchecked (the caller has checked them).
pub(crate) fn values_unchecked<C: Holonomic + ?Sized>(c: &C, t: f64, q: &[f64], out: &mut [f64]) {
    c.constraints(t, q, out)
}

/// The constraint Jacobian Φ_q = ∂φ/∂q (m × n) into `out`.
///
/// `out` must be exactly m × n ([`Error::Dimension`] naming its rows or columns: a smaller matrix
/// would hold only part of Φ_q); the other checks and the state of `out` on error as in [`values`].
pub fn jacobian<C: Holonomic + ?Sized>(c: &C, t: f64, q: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
    let (m, n) = (c.count(), c.dof());
    if out.nrows() != m || out.ncols() != n {
        let rows = out.nrows() != m;
        return Err(Error::Dimension {
            what: if rows {
                "rows of Φ_q (output)"
            } else {
                "columns of Φ_q (output)"
            },
            expected: if rows { m } else { n },
            got: if rows { out.nrows() } else { out.ncols() },
        }
        .into());
    }
    check_args(c, t, q, m)?;
    let mut j = DMatrix::zeros(m, n);
    jacobian_unchecked(c, t, q, &mut j);
    check_result("constraint Jacobian Φ_q", t, j.as_slice())?;
    out.copy_from(&j);
    Ok(())
}

/// Φ_q into `out`, shape unchecked (the caller has made it m × n).
pub(crate) fn jacobian_unchecked<C: Holonomic + ?Sized>(c: &C, t: f64, q: &[f64], out: &mut DMatrix<f64>) {
    jets::jacobian(&Field(c), t, q, &[], Block::X, out)
}

/// ∂φ/∂t into `out` (zero for scleronomic constraints); checks as in [`values`].
pub fn partial_t<C: Holonomic + ?Sized>(c: &C, t: f64, q: &[f64], out: &mut [f64]) -> Result<()> {
    check_args(c, t, q, out.len())?;
    into_checked("constraint rate ∂φ/∂t", t, out, |r| {
        partial_t_unchecked(c, t, q, r)
    })
}

/// ∂φ/∂t into `out`, lengths unchecked.
pub(crate) fn partial_t_unchecked<C: Holonomic + ?Sized>(c: &C, t: f64, q: &[f64], out: &mut [f64]) {
    jets::along(&Field(c), t, q, &[], (1.0, &[], &[]), out)
}

/// `unchecked(c, t, q, v, ·)` into `out` as `what` (see [`into_checked`]), after the checks of
/// [`velocity_residual`]: those of [`values`], and v of length n and finite.
fn along_velocity<C: Holonomic + ?Sized>(
    c: &C,
    (t, q, v): (f64, &[f64], &[f64]),
    out: &mut [f64],
    what: &'static str,
    unchecked: impl FnOnce(&C, f64, &[f64], &[f64], &mut [f64]),
) -> Result<()> {
    check_args(c, t, q, out.len())?;
    check_len("q̇", v, c.dof())?;
    check_finite("q̇", v)?;
    into_checked(what, t, out, |r| unchecked(c, t, q, v, r))
}

/// The velocity residual Φ_q v + φ_t = dφ/dt along q̇ = v, into `out`; v of length n, finite, and
/// the other checks as in [`values`].
pub fn velocity_residual<C: Holonomic + ?Sized>(
    c: &C,
    t: f64,
    q: &[f64],
    v: &[f64],
    out: &mut [f64],
) -> Result<()> {
    let what = "constraint velocity residual Φ_q q̇ + φ_t";
    along_velocity(c, (t, q, v), out, what, velocity_residual_unchecked)
}

/// Φ_q v + φ_t into `out`, lengths unchecked.
pub(crate) fn velocity_residual_unchecked<C: Holonomic + ?Sized>(
    c: &C,
    t: f64,
    q: &[f64],
    v: &[f64],
    out: &mut [f64],
) {
    jets::along(&Field(c), t, q, &[], (1.0, v, &[]), out)
}

/// The acceleration term d²φ/dt² at q̈ = 0, i.e. (Φ_q q̇)_q q̇ + 2 Φ_qt q̇ + φ_tt, into `out`; checks as
/// in [`velocity_residual`].
pub fn acceleration_bias<C: Holonomic + ?Sized>(
    c: &C,
    t: f64,
    q: &[f64],
    v: &[f64],
    out: &mut [f64],
) -> Result<()> {
    along_velocity(
        c,
        (t, q, v),
        out,
        "constraint acceleration bias",
        acceleration_bias_unchecked,
    )
}

/// The acceleration term into `out`, lengths unchecked.
pub(crate) fn acceleration_bias_unchecked<C: Holonomic + ?Sized>(
    c: &C,
    t: f64,
    q: &[f64],
    v: &[f64],
    out: &mut [f64],
) {
    let mut first = vec![0.0; out.len()];
    jets::along2(&Field(c), t, q, &[], (1.0, v, &[]), &mut first, out)
}

/// Adapter: a [`Holonomic`] constraint set as a [`ConstraintSet`].
#[derive(Debug, Clone, Copy)]
pub struct HolonomicSet<C>(pub C);

impl<C: Holonomic> ConstraintSet for HolonomicSet<C> {
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn count(&self) -> usize {
        self.0.count()
    }
    fn matrix(&self, t: f64, q: &[f64], _v: &[f64], a: &mut DMatrix<f64>) {
        jacobian_unchecked(&self.0, t, q, a)
    }
    fn velocity_residual(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
        velocity_residual_unchecked(&self.0, t, q, v, out)
    }
    fn bias(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
        acceleration_bias_unchecked(&self.0, t, q, v, out)
    }
    fn positions(&self, t: f64, q: &[f64], out: &mut [f64]) -> bool {
        values_unchecked(&self.0, t, q, out);
        true
    }
    /// δA = δ(Φ_q) from the mixed second derivatives of φ; A q̇ + a = (d/ds) φ(t + s, q + s q̇) and
    /// c = (d²/ds²) φ(t + s, q + s q̇) varied with (q, q̇) in one `Dual2<Dual64>` evaluation.
    fn derivatives_along(&self, t: f64, q: &[f64], v: &[f64], (dq, dv): (&[f64], &[f64])) -> SetDerivatives {
        let mut d = SetDerivatives::zeros(self.0.count(), self.0.dof());
        let point = Variation {
            ex: dq,
            edx: dv,
            ..Variation::default()
        };
        jets::jacobian_varied(&Field(&self.0), t, (q, &[]), point, Block::X, &mut d.matrix);
        let mut value = vec![0.0; self.0.count()];
        let out = [&mut value[..], &mut d.residual[..], &mut d.bias[..]];
        jets::along_varied(&Field(&self.0), t, (q, &[]), (1.0, v, &[]), point, out);
        d
    }
}
