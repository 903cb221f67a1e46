//! Natural mechanical systems: L = ½ q̇ᵀ M q̇ − V(q) with a constant, symmetric positive definite mass
//! matrix M, equivalently H = ½ pᵀ M⁻¹ p + V(q) with p = M q̇.
//!
//! This is the structure explicit symplectic methods need (a separable Hamiltonian). A [`Natural`]
//! system holds M (diagonal or dense), factors it once, and is at the same time
//! - a [`Lagrangian`] (so [`EulerLagrange`](crate::EulerLagrange) and every Lagrangian tool apply),
//! - a [`Separable`] Hamiltonian T(p) + V(q) (state (q, p) through
//!   [`SeparableHamiltonian`](crate::SeparableHamiltonian)),
//! - a [`Dynamics`](crate::Dynamics) on (q, q̇) itself, with the fast vector field
//!   q̈ = −M⁻¹ ∇V(q) (one gradient of V by dual numbers, no Hessian, no mass matrix by AD).
//!
//! ```
//! use noether_core::prelude::*;
//!
//! /// Pendulum of unit length and mass: V = −g cos θ.
//! struct Gravity { g: f64 }
//! impl Potential for Gravity {
//!     fn dof(&self) -> usize { 1 }
//!     fn potential<D: Scalar>(&self, q: &[D]) -> D { -q[0].cos() * self.g }
//! }
//!
//! let pendulum = Natural::diagonal(Gravity { g: 9.81 }, &[1.0]).unwrap();
//! let mut a = [0.0];
//! pendulum.accelerations(&[0.5], &mut a).unwrap();
//! assert!((a[0] + 9.81 * 0.5_f64.sin()).abs() < 1e-14); // θ̈ = −g sin θ
//! ```

use crate::ad::{self, Block, Field};
use crate::error::{check_finite, check_len, check_result, finite_result};
use crate::{Error, Lagrangian, Result, Scalar, Separable};
use nalgebra::{DMatrix, DVector};

/// A potential energy V(q), generic over the scalar so that its gradient and Hessian come from dual
/// numbers.
pub trait Potential {
    /// Number of coordinates.
    fn dof(&self) -> usize;
    /// V(q).
    fn potential<D: Scalar>(&self, q: &[D]) -> D;
}

impl<P: Potential + ?Sized> Potential for &P {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        (**self).potential(q)
    }
}

/// V(q) seen as the AD field f(t, x = q, y = ∅).
pub(crate) struct PotentialField<'a, P: ?Sized>(pub &'a P);

impl<P: Potential + ?Sized> Field for PotentialField<'_, P> {
    #[inline]
    fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
        self.0.potential(x)
    }
}

/// The constant mass matrix of a [`Natural`] system.
#[derive(Debug, Clone)]
enum Mass {
    /// M = diag(m), M⁻¹ = diag(1/m); `unit` when every mᵢ = 1 (no scaling to do).
    Diagonal {
        m: DVector<f64>,
        inv: DVector<f64>,
        unit: bool,
    },
    /// Dense SPD M with its Cholesky factor and explicit inverse (for T(p) with dual numbers).
    Dense {
        m: DMatrix<f64>,
        chol: nalgebra::Cholesky<f64, nalgebra::Dyn>,
        inv: DMatrix<f64>,
    },
}

/// A natural system L = ½ q̇ᵀ M q̇ − V(q) with constant SPD mass matrix M (see the [module](self) docs).
///
/// Two phase-space readings, both documented where they are used:
/// - as [`Dynamics`](crate::Dynamics) and [`SplitDynamics`](crate::system::SplitDynamics) the state
///   is (q, q̇);
/// - wrapped as `SeparableHamiltonian(natural)` the state is (q, p) with p = M q̇.
#[derive(Debug, Clone)]
pub struct Natural<P> {
    potential: P,
    mass: Mass,
    /// The force kernel for this dof, chosen once (see [`force_kernel`]).
    forces: ForceKernel<P>,
}

/// The force kernel of one dof: out = −∇V(q), times the diagonal M⁻¹ when given; returns V plus
/// Σ 0·outᵢ, which is V when every entry is finite and NaN otherwise (one check of the result). The
/// caller has checked the lengths.
type ForceKernel<P> = fn(&P, &[f64], &mut [f64], Option<&[f64]>) -> f64;

/// The force kernel for exactly W coordinates (see [`ForceKernel`]): the gradient by one
/// [`ad::gradient_exact`] evaluation, negated and scaled in registers.
#[inline]
fn forces_exact<P: Potential, const W: usize>(
    p: &P,
    q: &[f64; W],
    out: &mut [f64; W],
    inv: Option<&[f64]>,
) -> f64 {
    let mut g = [0.0; W];
    let value = ad::gradient_exact::<_, W>(&PotentialField(p), 0.0, q, &mut g);
    match inv.map(<&[f64; W]>::try_from) {
        Some(Ok(inv)) => (0..W).for_each(|i| out[i] = -(g[i] * inv[i])),
        Some(Err(_)) => return f64::NAN,
        None => (0..W).for_each(|i| out[i] = -g[i]),
    }
    out.iter().fold(value, |c, x| c + x * 0.0)
}

/// The force kernel for n degrees of freedom: up to [`ad::MAX_FIXED`], one fixed-width dual
/// evaluation with every length a constant ([`ad::gradient_exact`]), so that the model inlines into
/// it and the arguments, the gradient and the scaling stay in registers; beyond, the general
/// gradient (chunks or the tape). Chosen at construction: a call pays no dispatch on the length
/// (`--bench rates`: the Hénon-Heiles q̈ 23.8 → 4.8 ns, docs/benchmarks.md).
fn force_kernel<P: Potential>(n: usize) -> ForceKernel<P> {
    fn exact<P: Potential, const W: usize>(p: &P, q: &[f64], out: &mut [f64], inv: Option<&[f64]>) -> f64 {
        match (<&[f64; W]>::try_from(q), <&mut [f64; W]>::try_from(out)) {
            (Ok(q), Ok(out)) => forces_exact(p, q, out, inv),
            // Unreachable (chosen for this length, lengths checked first); reported as a
            // non-finite result, never a panic.
            _ => f64::NAN,
        }
    }
    fn general<P: Potential>(p: &P, q: &[f64], out: &mut [f64], inv: Option<&[f64]>) -> f64 {
        let value = ad::gradient(&PotentialField(p), 0.0, q, &[], Block::X, out);
        match inv {
            Some(inv) => out.iter_mut().zip(inv).for_each(|(x, i)| *x = -(*x * i)),
            None => out.iter_mut().for_each(|x| *x = -*x),
        }
        out.iter().fold(value, |c, x| c + x * 0.0)
    }
    macro_rules! widths {
        ($($w:literal)*) => {
            match n {
                $($w => exact::<P, $w>,)*
                _ => general::<P>,
            }
        };
    }
    widths!(1 2 3 4 5 6 7 8 9 10 11 12)
}

impl<P: Potential> Natural<P> {
    /// M = diag(`masses`). Every mass must be finite and positive.
    pub fn diagonal(potential: P, masses: &[f64]) -> Result<Self> {
        check_len("masses", masses, potential.dof())?;
        check_finite("masses", masses)?;
        if let Some(&m) = masses.iter().find(|m| **m <= 0.0) {
            return Err(Error::InvalidParameter {
                name: "mass",
                value: m,
                reason: "masses must be positive",
            });
        }
        let m = DVector::from_column_slice(masses);
        let inv = m.map(|x| 1.0 / x);
        let unit = masses.iter().all(|&m| m == 1.0);
        Ok(Natural {
            forces: force_kernel::<P>(potential.dof()),
            potential,
            mass: Mass::Diagonal { m, inv, unit },
        })
    }

    /// M = I (unit masses).
    pub fn unit(potential: P) -> Self {
        let n = potential.dof();
        Natural {
            forces: force_kernel::<P>(n),
            potential,
            mass: Mass::Diagonal {
                m: DVector::from_element(n, 1.0),
                inv: DVector::from_element(n, 1.0),
                unit: true,
            },
        }
    }

    /// A dense mass matrix, which must be symmetric positive definite; it is factored here, once.
    pub fn dense(potential: P, mass: DMatrix<f64>) -> Result<Self> {
        let n = potential.dof();
        crate::error::check_shape("mass matrix (rows × columns)", &mass, n, n)?;
        check_finite("mass matrix", mass.as_slice())?;
        let asym = (&mass - mass.transpose()).amax();
        if asym > 1e-12 * mass.amax() {
            return Err(Error::InvalidParameter {
                name: "mass matrix asymmetry",
                value: asym,
                reason: "the mass matrix must be symmetric",
            });
        }
        let factor = crate::linalg::factor_positive_parameter(mass.clone(), "mass matrix")?;
        // A Cholesky factor by construction (checked once more rather than assumed).
        let chol = factor.cholesky().ok_or(Error::SingularMassMatrix {
            t: 0.0,
            pivot_ratio: f64::NAN,
        })?;
        Ok(Natural {
            forces: force_kernel::<P>(n),
            potential,
            mass: Mass::Dense {
                m: mass,
                chol: chol.clone(),
                inv: chol.inverse(),
            },
        })
    }

    /// The potential.
    pub fn potential_model(&self) -> &P {
        &self.potential
    }

    /// The mass matrix M.
    pub fn mass_matrix(&self) -> DMatrix<f64> {
        match &self.mass {
            Mass::Diagonal { m, .. } => DMatrix::from_diagonal(m),
            Mass::Dense { m, .. } => m.clone(),
        }
    }

    /// Number of degrees of freedom.
    pub fn dof(&self) -> usize {
        self.potential.dof()
    }

    /// The value V(q).
    pub fn potential_energy(&self, q: &[f64]) -> Result<f64> {
        check_len("q", q, self.dof())?;
        check_finite("q", q)?;
        finite_result("potential energy", f64::NAN, self.potential.potential(q))
    }

    /// Forces f = −∇V(q) (one gradient by dual numbers) into `f`.
    pub fn forces(&self, q: &[f64], f: &mut [f64]) -> Result<()> {
        self.force_field(q, f, false)
    }

    /// Accelerations q̈ = −M⁻¹ ∇V(q) into `a`.
    #[inline]
    pub fn accelerations(&self, q: &[f64], a: &mut [f64]) -> Result<()> {
        self.force_field(q, a, true)
    }

    /// [`accelerations`](Self::accelerations) for exactly W coordinates, by value, the kernel called
    /// directly (not through the pointer chosen at construction), so that it inlines into a caller
    /// that knows W and q and q̈ stay in registers: the fixed-size loops of the compositions. Same
    /// result and errors as `accelerations`.
    #[inline]
    pub(crate) fn accelerations_fixed<const W: usize>(&self, q: [f64; W]) -> Result<[f64; W]> {
        match self.accelerations_fast(q, 0.0) {
            Some(a) => Ok(a),
            None => self.accelerations_cold(q),
        }
    }

    /// q̈ by the fixed-width kernel when it applies (a diagonal M, W = n ≤ [`ad::MAX_FIXED`]) and
    /// V + Σ 0·q̈ᵢ + `also` is finite: one test covers the potential, the accelerations and whatever
    /// the caller folds into `also` (0 times the values it returns with q̈). `None` otherwise, for
    /// the cold path to name the error.
    #[inline(always)]
    pub(crate) fn accelerations_fast<const W: usize>(&self, q: [f64; W], also: f64) -> Option<[f64; W]> {
        let inv = match self.diagonal_inverse(true) {
            Some(inv) if W == self.dof() && W <= ad::MAX_FIXED => inv,
            _ => return None,
        };
        let mut a = [0.0; W];
        (forces_exact(&self.potential, &q, &mut a, inv) + also)
            .is_finite()
            .then_some(a)
    }

    /// `accelerations` out of the fixed-size loops' way: a dense M, or the error of a non-finite
    /// result named as the general path names it. Cold, and taking q by value, so that the loop
    /// keeps its variables in registers.
    #[cold]
    #[inline(never)]
    fn accelerations_cold<const W: usize>(&self, q: [f64; W]) -> Result<[f64; W]> {
        crate::system::rate_by_slices(q, "accelerations", |q, a| self.accelerations(q, a))
    }

    /// `rates` out of the fixed-size loops' way (see [`accelerations_cold`](Self::accelerations_cold)).
    #[cold]
    #[inline(never)]
    pub(crate) fn rates_cold<const N: usize>(
        &self,
        t: f64,
        q: [f64; N],
        v: [f64; N],
    ) -> Result<([f64; N], [f64; N])> {
        crate::system::rates_by_slices(self, t, q, v)
    }

    /// The scaling of −∇V that the force kernels apply: `Some(None)` for none (forces, or unit masses),
    /// `Some(Some(M⁻¹))` for a diagonal M, `None` for a dense M (solved afterwards).
    #[inline]
    fn diagonal_inverse(&self, accelerate: bool) -> Option<Option<&[f64]>> {
        match (&self.mass, accelerate) {
            (_, false) | (Mass::Diagonal { unit: true, .. }, true) => Some(None),
            (Mass::Diagonal { inv, .. }, true) => Some(Some(inv.as_slice())),
            (Mass::Dense { .. }, true) => None,
        }
    }

    /// −∇V(q), times M⁻¹ when `accelerate`, into `out`: the hot path of every integrator on a natural
    /// system. Lengths are checked; finiteness only once, on the result and on V (a non-finite q gives
    /// a non-finite V), and only when that check fails are the inputs examined, so that the error
    /// still names a bad q. On error `out` may hold the partial result.
    #[inline]
    fn force_field(&self, q: &[f64], out: &mut [f64], accelerate: bool) -> Result<()> {
        let n = self.dof();
        check_len("q", q, n)?;
        check_len(
            if accelerate {
                "q̈ (output)"
            } else {
                "forces (output)"
            },
            out,
            n,
        )?;
        let scale = self.diagonal_inverse(accelerate);
        let mut check = (self.forces)(&self.potential, q, out, scale.flatten());
        if scale.is_none() {
            self.apply_inverse_mass(out);
            check = out.iter().fold(check, |c, x| c + x * 0.0);
        }
        // The value too: where V itself is infinite there is no force to return.
        if !check.is_finite() {
            check_finite("q", q)?;
            // A natural system does not depend on t: no time to name. The component when a force is
            // not finite (None when only V is).
            return Err(Error::NonFiniteResult {
                what: "potential forces",
                t: f64::NAN,
                component: out.iter().position(|x| !x.is_finite()),
            });
        }
        Ok(())
    }

    /// Overwrites `b` with M⁻¹ b (using the factor computed once).
    pub fn solve_mass(&self, b: &mut [f64]) -> Result<()> {
        check_len("b", b, self.dof())?;
        check_finite("b", b)?;
        self.apply_inverse_mass(b);
        check_result("M⁻¹ b", f64::NAN, b)
    }

    /// M⁻¹ b in place, for `b` of length n.
    pub(crate) fn apply_inverse_mass(&self, b: &mut [f64]) {
        match &self.mass {
            Mass::Diagonal { inv, .. } => b.iter_mut().zip(inv.iter()).for_each(|(x, i)| *x *= i),
            Mass::Dense { chol, .. } => {
                let n = b.len();
                chol.solve_mut(&mut nalgebra::DVectorViewMut::from_slice(b, n));
            }
        }
    }

    /// Momenta p = M q̇ into `p`.
    pub fn momenta(&self, v: &[f64], p: &mut [f64]) -> Result<()> {
        check_len("q̇", v, self.dof())?;
        check_len("p (output)", p, self.dof())?;
        check_finite("q̇", v)?;
        self.apply_mass(v, p);
        check_result("momenta", f64::NAN, p)
    }

    /// M v into `p` (both of length n).
    fn apply_mass(&self, v: &[f64], p: &mut [f64]) {
        match &self.mass {
            Mass::Diagonal { m, .. } => {
                for i in 0..p.len() {
                    p[i] = m[i] * v[i];
                }
            }
            Mass::Dense { m, .. } => {
                for (i, pi) in p.iter_mut().enumerate() {
                    *pi = (0..v.len()).map(|j| m[(i, j)] * v[j]).sum();
                }
            }
        }
    }

    /// Velocities q̇ = M⁻¹ p into `v`.
    pub fn velocities(&self, p: &[f64], v: &mut [f64]) -> Result<()> {
        check_len("p", p, self.dof())?;
        check_len("q̇ (output)", v, self.dof())?;
        check_finite("p", p)?;
        v.copy_from_slice(p);
        self.apply_inverse_mass(v);
        check_result("velocities", f64::NAN, v)
    }

    /// The state in momenta, (t, q, q̇) ↦ (t, q, M q̇).
    pub fn to_momenta(&self, state: &crate::State) -> crate::Result<crate::State<crate::Momenta>> {
        state.validate(self.dof())?;
        let mut s = crate::State::from_vectors(state.t, state.q.clone(), state.v.clone());
        self.apply_mass(state.v.as_slice(), s.v.as_mut_slice());
        Ok(s)
    }

    /// The state in velocities, (t, q, p) ↦ (t, q, M⁻¹ p).
    pub fn to_velocities(&self, state: &crate::State<crate::Momenta>) -> crate::Result<crate::State> {
        state.validate(self.dof())?;
        let mut s = crate::State::from_vectors(state.t, state.q.clone(), state.v.clone());
        self.apply_inverse_mass(s.v.as_mut_slice());
        Ok(s)
    }

    /// Kinetic energy ½ q̇ᵀ M q̇ in terms of velocities.
    pub fn kinetic_energy(&self, v: &[f64]) -> Result<f64> {
        check_len("q̇", v, self.dof())?;
        check_finite("q̇", v)?;
        finite_result("kinetic energy", f64::NAN, quadratic(&self.mass_as(false), v))
    }

    /// The energy ½ q̇ᵀ M q̇ + V(q).
    pub fn energy(&self, q: &[f64], v: &[f64]) -> Result<f64> {
        finite_result(
            "energy",
            f64::NAN,
            self.kinetic_energy(v)? + self.potential_energy(q)?,
        )
    }

    /// Hessian ∇²V(q) (for implicit methods; explicit methods never form it) into the n × n `out`.
    pub fn potential_hessian(&self, q: &[f64], out: &mut DMatrix<f64>) -> Result<()> {
        let n = self.dof();
        check_len("q", q, n)?;
        check_finite("q", q)?;
        crate::error::check_shape("Hessian (output) rows and columns", out, n, n)?;
        ad::hessian(
            &PotentialField(&self.potential),
            0.0,
            q,
            &[],
            Block::X,
            Block::X,
            out,
        );
        // A natural system does not depend on t: no time to name.
        check_result("potential Hessian", f64::NAN, out.as_slice())
    }

    fn mass_as(&self, inverse: bool) -> MatRef<'_> {
        match (&self.mass, inverse) {
            (Mass::Diagonal { m, .. }, false) => MatRef::Diag(m),
            (Mass::Diagonal { inv, .. }, true) => MatRef::Diag(inv),
            (Mass::Dense { m, .. }, false) => MatRef::Dense(m),
            (Mass::Dense { inv, .. }, true) => MatRef::Dense(inv),
        }
    }

    /// M⁻¹ as a dense matrix.
    pub fn inverse_mass_matrix(&self) -> DMatrix<f64> {
        match &self.mass {
            Mass::Diagonal { inv, .. } => DMatrix::from_diagonal(inv),
            Mass::Dense { inv, .. } => inv.clone(),
        }
    }
}

enum MatRef<'a> {
    Diag(&'a DVector<f64>),
    Dense(&'a DMatrix<f64>),
}

/// ½ xᵀ A x for a diagonal or dense A, generic over the scalar.
fn quadratic<D: Scalar>(a: &MatRef<'_>, x: &[D]) -> D {
    let mut s = D::zero();
    match a {
        MatRef::Diag(d) => {
            for (i, xi) in x.iter().enumerate() {
                s += *xi * *xi * d[i];
            }
        }
        MatRef::Dense(m) => {
            for i in 0..x.len() {
                let mut row = D::zero();
                for (j, xj) in x.iter().enumerate() {
                    row += *xj * m[(i, j)];
                }
                s += x[i] * row;
            }
        }
    }
    s * 0.5
}

impl<P: Potential> Lagrangian for Natural<P> {
    fn dof(&self) -> usize {
        self.potential.dof()
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        quadratic(&self.mass_as(false), v) - self.potential.potential(q)
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}

impl<P: Potential> Separable for Natural<P> {
    fn dof(&self) -> usize {
        self.potential.dof()
    }
    /// T(p) = ½ pᵀ M⁻¹ p.
    fn kinetic<D: Scalar>(&self, p: &[D]) -> D {
        quadratic(&self.mass_as(true), p)
    }
    fn potential<D: Scalar>(&self, q: &[D]) -> D {
        self.potential.potential(q)
    }
}
