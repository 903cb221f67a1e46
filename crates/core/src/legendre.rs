//! The Hamiltonian of any Lagrangian, by the Legendre transform: [`LegendreTransform`].
//!
//! For a Lagrangian L(t, q, q̇) convex in q̇ (mass matrix M = ∂²L/∂q̇² positive definite),
//!
//! ```text
//! H(t, q, p) = p·q̇ − L(t, q, q̇),   q̇ = q̇(t, q, p) the solution of ∂L/∂q̇(t, q, q̇) = p.
//! ```
//!
//! No formula for q̇(p) is needed: [`LegendreTransform`] solves for it and differentiates the
//! solution exactly, so that Gauss-Legendre, the symplectic methods and every other tool built on
//! [`HamiltonEquations`](crate::HamiltonEquations) apply to a Lagrangian written once.
//!
//! **The real solve.** The real part q̇₀ is found by the crate's [`Newton`](crate::Newton) with the
//! AD mass matrix as Jacobian (the inverse Legendre map of [`EulerLagrange`]), then polished by one
//! more Newton step with M(t, q, q̇₀) factored by Cholesky (so q̇₀ is the root to rounding and M is
//! known positive definite at it). Every solve starts from the same point, one Newton step from q̇ = 0,
//!
//! ```text
//! q̇_start = M(t, q, 0)⁻¹ (p − ∂L/∂q̇(t, q, 0))      (halved until L is finite there),
//! ```
//!
//! which is the root itself when L is quadratic in q̇. The result is a function of (t, q, p) alone, to
//! the last bit: not of earlier calls, nor of which thread made them, so a transform shared by the
//! members of an ensemble gives the same bits as one per member on any number of threads. (Until issue
//! 29 the start was the previous solve, kept behind a `Mutex`: results then depended on the order of
//! calls across threads, in the last bits.)
//!
//! **The derivatives, by the implicit-function theorem.** The model is evaluated with a dual scalar
//! D (first derivatives for Hamilton's equations, second for the Jacobians of Gauss-Legendre). The
//! velocities in D are obtained by k chord-Newton steps *evaluated in D*, from q̇₀ and with the real
//! M(t, q, q̇₀)⁻¹:
//!
//! ```text
//! q̇ ← q̇ − M(t₀, q₀, q̇₀)⁻¹ (∂L/∂q̇(t, q, q̇) − p)      (∂L/∂q̇ in D by nested duals)
//! ```
//!
//! If the error of q̇ has no term below derivative order m + 1, a step leaves none below order m + 2
//! (the step's matrix differs from the exact Jacobian only in its derivative parts): after k steps q̇
//! is exact through order k. H is stationary in q̇ (∂H/∂q̇ = p − ∂L/∂q̇ = 0 at the solution), so its
//! error is quadratic in that of q̇: H is exact through order 2k + 1. The number of steps is chosen
//! from the scalar, k = ⌊D::NDERIV / 2⌋: none for f64 and for gradients (∂H/∂p = q̇₀ and
//! ∂H/∂q = −∂L/∂q, the envelope theorem), one for Hessians and third derivatives (H exact through
//! order 3). Every integrator of the workspace asks for at most second derivatives of H. There is
//! no finite difference anywhere: the results are exact to rounding.
//!
//! **Quadratic Lagrangians.** When the Lagrangian declares
//! [`constant_mass_matrix`](Lagrangian::constant_mass_matrix) (so L = ½ q̇ᵀ M q̇ + a(t, q)·q̇ + L₀(t, q)),
//! M is factored and inverted once, q̇₀ = M⁻¹ (p − a) comes from one gradient and no Newton iteration,
//! and the one step in D is exact Newton on a linear equation: q̇ is exact to every order. (The closed
//! form ½ (p − a)ᵀ M(q)⁻¹ (p − a) − L₀ for a q-dependent M is not implemented: it needs M(q) in D, a
//! second derivative in q̇ nested in the caller's scalar, and a linear solve in D; whether that beats
//! the real solve plus one nested gradient has not been measured. The cost of the general path
//! against a hand-written H is in docs/benchmarks.md.)
//!
//! **Errors.** [`Hamiltonian::hamiltonian`] returns a scalar, so a failure (a singular or indefinite
//! mass matrix, Newton not converging, non-finite input) makes it NaN, and
//! [`Hamiltonian::failure`] gives the typed error, which
//! [`HamiltonEquations`](crate::HamiltonEquations) and so every Hamiltonian integrator report:
//! [`Error::SingularMassMatrix`], [`Error::IndefiniteMassMatrix`], [`Error::NewtonDiverged`],
//! [`Error::NonFinite`]. [`LegendreTransform::value`] and [`LegendreTransform::velocities`] are the
//! fallible real paths.
//!
//! ```
//! use noether_core::prelude::*;
//!
//! /// Plane pendulum, L = ½ m l² θ̇² + m g l cos θ; by hand H = p²/(2 m l²) − m g l cos θ.
//! struct Pendulum;
//! impl Lagrangian for Pendulum {
//!     fn dof(&self) -> usize { 1 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         v[0] * v[0] * (0.5 * 2.0) + q[0].cos() * (2.0 * 9.81)
//!     }
//! }
//! let h = HamiltonEquations::new(LegendreTransform::new(Pendulum));
//! let (q, p) = ([0.3], [1.7]);
//! assert!((h.energy(0.0, &q, &p).unwrap() - (1.7 * 1.7 / 4.0 - 2.0 * 9.81 * 0.3f64.cos())).abs() < 1e-14);
//! let (mut dq, mut dp) = ([0.0], [0.0]);
//! h.rates(0.0, &q, &p, &mut dq, &mut dp).unwrap();
//! assert!((dq[0] - 1.7 / 2.0).abs() < 1e-15 && (dp[0] + 2.0 * 9.81 * 0.3f64.sin()).abs() < 1e-14);
//!
//! // Gauss-Legendre on the Hamiltonian of a Lagrangian: one period of small oscillations.
//! let small = State::with_momenta(0.0, [1e-3], [0.0]);
//! let period = 2.0 * std::f64::consts::PI / 9.81f64.sqrt();
//! let mut run = Driver::new(Gauss::gauss4(h), small).unwrap().step_size(period / 200.0).unwrap();
//! assert!((run.run_until(period).unwrap().last().q[0] - 1e-3).abs() < 1e-9);
//! ```

use crate::ad::{self, Block, Buf, MAX_FIXED};
use crate::error::check_phase_point;
use crate::lagrange::LagrangianField;
use crate::linalg::positive_definite_mass as positive_definite;
use crate::newton::max_norm;
use crate::{Error, EulerLagrange, Hamiltonian, Lagrangian, Result, Scalar};
use nalgebra::{Const, DMatrix, DVector, SVector, U1};
use num_dual::{Dual, Dual2Vec};
use std::sync::{Mutex, OnceLock};

/// The Hamiltonian H(t, q, p) = p·q̇ − L(t, q, q̇), ∂L/∂q̇(t, q, q̇) = p, of any [`Lagrangian`] convex
/// in q̇: see the [module documentation](self) for the solve, the exactness of its derivatives
/// (one Newton step in the dual scalar per two derivative orders beyond the first) and its errors.
///
/// Deterministic and `Sync`: every solve starts from the same point computed from (t, q, p) (see the
/// module documentation), so H and its derivatives are functions of their arguments alone, to the
/// last bit, whatever was called before and on whichever thread. The last solve is remembered with
/// the exact (t, q, p) it was made at (behind a `Mutex` taken with `try_lock`) and
/// reused only at that same point: the two gradients of
/// [`HamiltonEquations::rates`](crate::HamiltonEquations::rates) and the three blocks of its Hessian
/// are evaluated at one point. A hit returns what a new solve would, so the memory changes the cost,
/// never the result.
pub struct LegendreTransform<L> {
    equations: EulerLagrange<L>,
    constant_inverse: OnceLock<Result<DMatrix<f64>>>,
    last: Mutex<Option<(Vec<u64>, Solved)>>,
}

/// A real solve: the velocities q̇₀ and, when asked for, M(t, q, q̇₀)⁻¹.
#[derive(Clone)]
struct Solved {
    v: Vec<f64>,
    inverse: Option<DMatrix<f64>>,
}

/// The exact bits of (t, q, p): the key of a remembered solve.
fn key<'a>(t: f64, q: &'a [f64], p: &'a [f64]) -> impl Iterator<Item = u64> + 'a {
    std::iter::once(t)
        .chain(q.iter().copied())
        .chain(p.iter().copied())
        .map(f64::to_bits)
}

impl<L: Lagrangian + Clone> Clone for LegendreTransform<L> {
    /// A transform of a copy of the Lagrangian.
    fn clone(&self) -> Self {
        LegendreTransform::new(self.equations.lagrangian().clone())
    }
}

impl<L: Lagrangian + std::fmt::Debug> std::fmt::Debug for LegendreTransform<L> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LegendreTransform")
            .field("lagrangian", self.equations.lagrangian())
            .finish_non_exhaustive()
    }
}

impl<L: Lagrangian> LegendreTransform<L> {
    /// The Hamiltonian of `lagrangian`.
    pub fn new(lagrangian: L) -> Self {
        LegendreTransform {
            equations: EulerLagrange::new(lagrangian),
            constant_inverse: OnceLock::new(),
            last: Mutex::new(None),
        }
    }

    /// The wrapped Lagrangian.
    pub fn lagrangian(&self) -> &L {
        self.equations.lagrangian()
    }

    /// The Lagrangian's equations (momenta, energy, the Legendre maps between states in velocities
    /// and in momenta).
    pub fn equations(&self) -> &EulerLagrange<L> {
        &self.equations
    }

    /// The velocities q̇(t, q, p) solving ∂L/∂q̇ = p, to rounding, or the error that makes H undefined
    /// there.
    pub fn velocities(&self, t: f64, q: &[f64], p: &[f64]) -> Result<DVector<f64>> {
        Ok(DVector::from_vec(self.solve(t, q, p, false)?.v))
    }

    /// H(t, q, p), or the error that makes it undefined there.
    pub fn value(&self, t: f64, q: &[f64], p: &[f64]) -> Result<f64> {
        let v = self.solve(t, q, p, false)?.v;
        let h = p.iter().zip(&v).map(|(a, b)| a * b).sum::<f64>() - self.lagrangian().lagrangian(t, q, &v);
        if !h.is_finite() {
            return Err(Error::NonFiniteResult {
                what: "Hamiltonian",
                t,
                component: None,
            });
        }
        Ok(h)
    }

    /// The real solve at (t, q, p); `inverse` asks for M(t, q, q̇₀)⁻¹ as well.
    fn solve(&self, t: f64, q: &[f64], p: &[f64], inverse: bool) -> Result<Solved> {
        let n = self.lagrangian().dof();
        check_phase_point(n, t, q, p, "p")?;
        if self.lagrangian().constant_mass_matrix() {
            return self.solve_quadratic(t, q, p, inverse);
        }
        // The same point as the last solve (and the inverse, if asked for, kept): its result.
        if let Ok(last) = self.last.try_lock() {
            if let Some((k, solved)) = last.as_ref() {
                if (solved.inverse.is_some() || !inverse) && k.iter().copied().eq(key(t, q, p)) {
                    return Ok(Solved {
                        v: solved.v.clone(),
                        inverse: inverse.then(|| solved.inverse.clone()).flatten(),
                    });
                }
            }
        }
        let (mut v, mut g, mut m) = self.start(t, q, p)?;
        let scale = 1.0 + max_norm(p);
        // The residual ∂L/∂q̇ − p; Newton unless the start already solves to the inverse map's tolerance.
        if residual(&mut g, p) > 1e-13 * scale {
            v = self.equations.velocities_from(t, q, p, &v)?.data.into();
            (g, m) = self.momenta_and_mass(t, q, &v);
            residual(&mut g, p);
        }
        // Polish: one Newton step with M at q̇₀ itself (positive definite, or the error).
        let chol = positive_definite(m, t)?;
        let mut dv = DVector::from_vec(g);
        chol.solve_mut(&mut dv);
        v.iter_mut().zip(dv.iter()).for_each(|(vi, di)| *vi -= di);
        if v.iter().any(|x| !x.is_finite()) {
            return Err(Error::NonFiniteResult {
                what: "velocities q̇ from p",
                t,
                component: None,
            });
        }
        let solved = Solved {
            v,
            inverse: inverse.then(|| chol.inverse()),
        };
        if let Ok(mut last) = self.last.try_lock() {
            *last = Some((key(t, q, p).collect(), solved.clone()));
        }
        Ok(solved)
    }

    /// The start of the real solve, a function of (t, q, p) alone: one Newton step from q̇ = 0,
    /// q̇ = M(t, q, 0)⁻¹ (p − ∂L/∂q̇(t, q, 0)), halved until ∂L/∂q̇ and M are finite there (p/m may lie
    /// outside the model's domain, |q̇| < c say); with ∂L/∂q̇ and M at it. Where M(t, q, 0) is not
    /// positive definite, the inverse Legendre map's own start M(t, q, 0)⁻¹ p.
    fn start(&self, t: f64, q: &[f64], p: &[f64]) -> Result<(Vec<f64>, Vec<f64>, DMatrix<f64>)> {
        let n = p.len();
        let step = if n <= MAX_FIXED {
            crate::with_width!(n, start_w::<L>(self.lagrangian(), t, q, p))
        } else {
            let (g0, m0) = self.momenta_and_mass(t, q, &vec![0.0; n]);
            positive_definite(m0, t).ok().map(|chol| {
                let mut r = DVector::from_iterator(n, p.iter().zip(&g0).map(|(pi, gi)| pi - gi));
                chol.solve_mut(&mut r);
                r.data.into()
            })
        };
        let mut v = match step {
            Some(v) if v.iter().all(|x: &f64| x.is_finite()) => v,
            _ => self.equations.velocity_start(t, q, p)?,
        };
        let (mut g, mut m) = self.momenta_and_mass(t, q, &v);
        for _ in 0..60 {
            if g.iter().chain(m.iter()).all(|x| x.is_finite()) {
                break;
            }
            v.iter_mut().for_each(|x| *x *= 0.5);
            (g, m) = self.momenta_and_mass(t, q, &v);
        }
        Ok((v, g, m))
    }

    /// L quadratic in q̇ with a constant M: q̇₀ = M⁻¹ (p − ∂L/∂q̇(t, q, 0)), M inverted once.
    fn solve_quadratic(&self, t: f64, q: &[f64], p: &[f64], inverse: bool) -> Result<Solved> {
        let n = p.len();
        let minv = self
            .constant_inverse
            .get_or_init(|| {
                let zero = vec![0.0; n];
                let m = self.equations.mass_matrix(t, q, &zero)?;
                Ok(positive_definite(m, t)?.inverse())
            })
            .as_ref()
            .map_err(Clone::clone)?;
        let zero = vec![0.0; n];
        let mut a = vec![0.0; n];
        ad::gradient(&LagrangianField(self.lagrangian()), t, q, &zero, Block::Y, &mut a);
        let r = DVector::from_iterator(n, p.iter().zip(&a).map(|(pi, ai)| pi - ai));
        let v: Vec<f64> = (minv * r).data.into();
        if v.iter().any(|x| !x.is_finite()) {
            return Err(Error::NonFiniteResult {
                what: "velocities q̇ from p",
                t,
                component: None,
            });
        }
        Ok(Solved {
            v,
            inverse: inverse.then(|| minv.clone()),
        })
    }

    /// ∂L/∂q̇ and M = ∂²L/∂q̇² at (t, q, q̇): one `Dual2Vec` evaluation up to [`MAX_FIXED`] degrees of
    /// freedom, the gradient and Hessian kernels of [`ad`] beyond.
    fn momenta_and_mass(&self, t: f64, q: &[f64], v: &[f64]) -> (Vec<f64>, DMatrix<f64>) {
        let n = v.len();
        let f = LagrangianField(self.lagrangian());
        if n == 0 {
            return (Vec::new(), DMatrix::zeros(0, 0));
        }
        if n > MAX_FIXED {
            let mut g = vec![0.0; n];
            ad::gradient(&f, t, q, v, Block::Y, &mut g);
            let mut m = DMatrix::zeros(n, n);
            ad::hessian(&f, t, q, v, Block::Y, Block::Y, &mut m);
            return (g, m);
        }
        crate::with_width!(n, momenta_and_mass_w::<L>(self.lagrangian(), t, q, v))
    }
}

/// [`LegendreTransform::momenta_and_mass`] for n ≤ W: one evaluation with `Dual2Vec<W>` seeded on q̇.
fn momenta_and_mass_w<L: Lagrangian, const W: usize>(
    l: &L,
    t: f64,
    q: &[f64],
    v: &[f64],
) -> (Vec<f64>, DMatrix<f64>) {
    type D2<const W: usize> = Dual2Vec<f64, f64, Const<W>>;
    let n = v.len();
    let (qs, vs) = crate::ad::seed_second::<W>(q, v, Block::Y);
    let r = l.lagrangian(D2::<W>::from_re(t), &qs, &vs);
    let g = r.v1.unwrap_generic(U1, Const::<W>);
    let h = r.v2.unwrap_generic(Const::<W>, Const::<W>);
    (
        g.as_slice()[..n].to_vec(),
        DMatrix::from_fn(n, n, |i, j| h[(i, j)]),
    )
}

/// [`LegendreTransform::start`] for n ≤ W: one `Dual2Vec<W>` evaluation at q̇ = 0 for ∂L/∂q̇ and M,
/// and M(t, q, 0)⁻¹ (p − ∂L/∂q̇(t, q, 0)) by a square-root-free LDLᵀ factorization on the stack
/// ([`linalg::solve_positive_fixed`](crate::linalg::solve_positive_fixed), M padded to W × W with
/// max |m_ij| on the diagonal, so that the padding leaves the pivot test's ratio that of M); `None`
/// where M(t, q, 0) is not positive definite or singular by that test.
fn start_w<L: Lagrangian, const W: usize>(l: &L, t: f64, q: &[f64], p: &[f64]) -> Option<Vec<f64>> {
    type D2<const W: usize> = Dual2Vec<f64, f64, Const<W>>;
    let n = p.len();
    let (qs, vs) = crate::ad::seed_second::<W>(q, &[0.0; W][..n], Block::Y);
    let r = l.lagrangian(D2::<W>::from_re(t), &qs, &vs);
    let g = r.v1.unwrap_generic(U1, Const::<W>);
    let mut m = r.v2.unwrap_generic(Const::<W>, Const::<W>);
    let scale = m.amax();
    let mut b = SVector::<f64, W>::zeros();
    for i in 0..W {
        if i < n {
            b[i] = p[i] - g[i];
        } else {
            m[(i, i)] = scale;
        }
    }
    crate::linalg::solve_positive_fixed(m, &mut b).then(|| b.as_slice()[..n].to_vec())
}

/// The entries of `x` lifted to nested duals `Dual<D>` (constants); generic in D only.
fn nested<D: Scalar>(x: &[D]) -> Buf<Dual<D, f64>, 12> {
    Buf::new(x.len(), |i| Dual::from_re(x[i]))
}

/// The real parts of `x`; generic in D only.
fn real_parts<D: Scalar>(x: &[D]) -> Buf<f64, 12> {
    Buf::new(x.len(), |i| x[i].re())
}

/// g ← g − p; returns ‖g − p‖∞.
fn residual(g: &mut [f64], p: &[f64]) -> f64 {
    g.iter_mut().zip(p).for_each(|(gi, pi)| *gi -= pi);
    max_norm(g)
}

/// ∂L/∂q̇(t, q, v) in the scalar D, by nested duals `Dual<D>`: one evaluation per component (one
/// instantiation per scalar; a `DualVec<D, W>` per chunk width would multiply the code generated for
/// every scalar the integrators use by the number of widths, for about the same arithmetic).
fn momenta_in<L: Lagrangian, D: Scalar>(l: &L, t: D, q: &[D], v: &[D], out: &mut [D]) {
    // Nested duals are twice the size of D: on the stack for up to 12 degrees of freedom.
    let (ts, qs, mut vs) = (Dual::from_re(t), nested(q), nested(v));
    for (k, o) in out.iter_mut().enumerate() {
        vs[k] = Dual::from_re(v[k]).derivative();
        *o = l.lagrangian(ts, &qs, &vs).eps;
        vs[k] = Dual::from_re(v[k]);
    }
}

impl<L: Lagrangian> Hamiltonian for LegendreTransform<L> {
    fn dof(&self) -> usize {
        self.lagrangian().dof()
    }

    /// p·q̇ − L(t, q, q̇) with q̇ from the real solve and ⌊D::NDERIV / 2⌋ chord-Newton steps in D (the
    /// [module documentation](self)); NaN (value and derivative parts) where the transform fails
    /// ([`failure`](Hamiltonian::failure) says why).
    fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D]) -> D {
        let n = self.dof();
        let (q0, p0) = (real_parts(q), real_parts(p));
        let steps = if self.lagrangian().constant_mass_matrix() {
            // One step is exact Newton on an equation linear in q̇.
            usize::from(D::NDERIV >= 2)
        } else {
            D::NDERIV / 2
        };
        let Ok(solved) = self.solve(t.re(), &q0, &p0, steps > 0) else {
            // NaN in the value and in every derivative part that the caller seeded.
            return q.iter().chain(p).fold(t, |s, x| s + *x) * f64::NAN;
        };
        let mut v = Buf::<D, 12>::constants(&solved.v[..n]);
        if let Some(minv) = &solved.inverse {
            let mut r = Buf::<D, 12>::filled(n, D::zero());
            for _ in 0..steps {
                momenta_in(self.lagrangian(), t, q, &v, &mut r);
                r.iter_mut().zip(p).for_each(|(ri, pi)| *ri -= *pi);
                for i in 0..n {
                    let mut dv = D::zero();
                    for j in 0..n {
                        dv += r[j] * minv[(i, j)];
                    }
                    v[i] -= dv;
                }
            }
        }
        let mut pv = D::zero();
        for i in 0..n {
            pv += p[i] * v[i];
        }
        pv - self.lagrangian().lagrangian(t, q, &v)
    }

    /// The error of the real solve at (t, q, p) (non-finite input, a singular or indefinite mass
    /// matrix, Newton not converging), or `None` when it succeeds.
    fn failure(&self, t: f64, q: &[f64], p: &[f64]) -> Option<Error> {
        self.solve(t, q, p, false).err()
    }
}
