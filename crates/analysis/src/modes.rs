//! Small oscillations about an equilibrium of a Lagrangian L(t, q, q̇).
//!
//! Expanding L to second order about a point q₀ at rest (q = q₀ + x, ∂L/∂q(q₀, 0) = 0) gives
//!
//! ```text
//! L₂ = ½ ẋᵀ M ẋ + ẋᵀ C x − ½ xᵀ K x,   M = ∂²L/∂q̇²,  C = ∂²L/∂q̇∂q,  K = −∂²L/∂q²   (at (q₀, 0)),
//! M ẍ + G ẋ + K x = 0,                  G = C − Cᵀ (gyroscopic, antisymmetric).
//! ```
//!
//! Without gyroscopic terms (G = 0, the usual L = T − V) the motions are normal modes x = X cos(ωt):
//! the generalized symmetric eigenproblem `K X = ω² M X`, solved through the Cholesky factor
//! M = L Lᵀ as the ordinary symmetric problem (L⁻¹ K L⁻ᵀ) Y = ω² Y with X = L⁻ᵀ Y, so the mode shapes
//! come out M-orthonormal, Xᵀ M X = 1 ([`normal_modes`]). With gyroscopic terms (rotating frames,
//! magnetic fields) the first-order system (ẋ, v̇) = (v, −M⁻¹(K x + G v)) is examined instead: it is
//! linearly stable when no eigenvalue has a positive real part ([`linear_stability`]).
//!
//! All matrices are exact second derivatives by dual numbers.
//!
//! ```
//! use noether_analysis::normal_modes;
//! use noether_core::{Lagrangian, Scalar};
//!
//! /// Two unit masses between three unit springs, fixed ends: ω² = 1 and 3.
//! struct Chain2;
//! impl Lagrangian for Chain2 {
//!     fn dof(&self) -> usize { 2 }
//!     fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
//!         let (a, b, c) = (q[0], q[1] - q[0], q[1]);
//!         (v[0] * v[0] + v[1] * v[1]) * 0.5 - (a * a + b * b + c * c) * 0.5
//!     }
//! }
//! let modes = normal_modes(&Chain2, &[0.0, 0.0]).unwrap();
//! assert!((modes.omega2[0] - 1.0).abs() < 1e-12 && (modes.omega2[1] - 3.0).abs() < 1e-12);
//! ```

use nalgebra::{Complex, DMatrix, DVector};
use noether_core::ad::{self, Block, Field};
use noether_core::error::check_positive;
use noether_core::{EulerLagrange, Lagrangian, Scalar};

use crate::equilibria::{gradient_scale, signature};
use crate::potential::{self, check_point, EffectivePotential};
use crate::{Error, Result};

/// The normal modes of a Lagrangian about an equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct NormalModes {
    /// The equilibrium.
    pub q: DVector<f64>,
    /// Mass matrix M = ∂²L/∂q̇² at (q₀, 0).
    pub mass: DMatrix<f64>,
    /// Stiffness matrix K = −∂²L/∂q² at (q₀, 0).
    pub stiffness: DMatrix<f64>,
    /// Squared frequencies ω², ascending (negative: an unstable direction, growth rate sqrt(−ω²)).
    pub omega2: DVector<f64>,
    /// Mode shapes, column j belonging to `omega2[j]`, normalised to Xᵀ M X = 1.
    pub shapes: DMatrix<f64>,
    /// Number of ω² with |ω²| ≤ zero_tolerance·max|ω²| (free translations, rotations, ...).
    pub zero_modes: usize,
    /// Number of ω² below −zero_tolerance·max|ω²|.
    pub unstable_modes: usize,
}

impl NormalModes {
    /// Angular frequencies ω = sqrt(ω²); an unstable mode is reported as −sqrt(−ω²) (minus its
    /// exponential growth rate) and a zero mode as 0.
    pub fn frequencies(&self) -> DVector<f64> {
        self.omega2
            .map(|w2| if w2 >= 0.0 { w2.sqrt() } else { -(-w2).sqrt() })
    }

    /// `true` when no mode is unstable (zero modes allowed).
    pub fn is_stable(&self) -> bool {
        self.unstable_modes == 0
    }
}

/// Eigenvalues λ of the linearised first-order dynamics about an equilibrium (x ∝ e^{λt}).
#[derive(Debug, Clone, PartialEq)]
pub struct LinearStability {
    /// The equilibrium.
    pub q: DVector<f64>,
    /// The 2n eigenvalues λ of [[0, I], [−M⁻¹K, −M⁻¹G]], sorted by real part (descending).
    pub eigenvalues: Vec<Complex<f64>>,
    /// max Re λ (the fastest exponential growth rate; ≈ 0 for a stable conservative system).
    pub growth_rate: f64,
    /// Max-norm of the gyroscopic matrix G = C − Cᵀ.
    pub gyroscopic_norm: f64,
    /// `true` when every Re λ ≤ zero_tolerance · max|λ| (spectral stability).
    pub stable: bool,
}

/// Settings of the linearisation: the time at which L is frozen and the tolerances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmallOscillations {
    t: f64,
    equilibrium_tolerance: f64,
    zero_tolerance: f64,
}

impl Default for SmallOscillations {
    fn default() -> Self {
        SmallOscillations {
            t: 0.0,
            equilibrium_tolerance: 1e-8,
            zero_tolerance: 1e-9,
        }
    }
}

/// Normal modes about `q0` with default settings (see [`SmallOscillations::normal_modes`]).
pub fn normal_modes<L: Lagrangian>(lagrangian: &L, q0: &[f64]) -> Result<NormalModes> {
    SmallOscillations::default().normal_modes(lagrangian, q0)
}

/// Linear stability about `q0` with default settings (see [`SmallOscillations::linear_stability`]).
pub fn linear_stability<L: Lagrangian>(lagrangian: &L, q0: &[f64]) -> Result<LinearStability> {
    SmallOscillations::default().linear_stability(lagrangian, q0)
}

/// A Lagrangian as the AD field f(t, x = q, y = q̇).
struct LagrangianField<'a, L>(&'a L);

impl<L: Lagrangian> Field for LagrangianField<'_, L> {
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D]) -> D {
        self.0.lagrangian(t, x, y)
    }
}

/// M, K and G at (t, q₀, 0), after checking that q₀ is an equilibrium.
struct Linearised {
    mass: DMatrix<f64>,
    stiffness: DMatrix<f64>,
    gyroscopic: DMatrix<f64>,
}

impl SmallOscillations {
    /// Sets the time t at which L(t, q, q̇) is evaluated (default 0, irrelevant for an autonomous L;
    /// finite).
    pub fn t(mut self, t: f64) -> Result<Self> {
        noether_core::error::check_finite("t", &[t])?;
        self.t = t;
        Ok(self)
    }
    /// Sets the equilibrium tolerance (default 1e-8; finite and positive): a point is accepted as an
    /// equilibrium when ‖∂L/∂q(q₀, 0)‖∞ ≤ this · ‖K‖max · (1 + ‖q₀‖∞).
    pub fn equilibrium_tolerance(mut self, tol: f64) -> Result<Self> {
        self.equilibrium_tolerance = check_positive("equilibrium_tolerance", tol)?;
        Ok(self)
    }
    /// Sets the relative size below which ω² (or Re λ) counts as zero (default 1e-9; finite and
    /// positive).
    pub fn zero_tolerance(mut self, tol: f64) -> Result<Self> {
        self.zero_tolerance = check_positive("zero_tolerance", tol)?;
        Ok(self)
    }

    fn linearise<L: Lagrangian>(&self, lagrangian: &L, q0: &[f64]) -> Result<Linearised> {
        let n = lagrangian.dof();
        check_point(q0, n)?;
        let pot = EffectivePotential {
            lagrangian,
            t: self.t,
        };
        let (_, grad) = potential::gradient(&pot, q0)?;
        let stiffness = potential::hessian(&pot, q0)?;
        let tolerance = self.equilibrium_tolerance * gradient_scale(&stiffness, q0);
        let gradient_norm = grad.amax();
        if gradient_norm.is_nan() || gradient_norm > tolerance {
            return Err(Error::NotEquilibrium {
                gradient_norm,
                tolerance,
            });
        }
        let zero = vec![0.0; n];
        let mass = EulerLagrange::new(lagrangian).mass_matrix(self.t, q0, &zero)?;
        let mut c = DMatrix::zeros(n, n);
        ad::hessian(
            &LagrangianField(lagrangian),
            self.t,
            q0,
            &zero,
            Block::Y,
            Block::X,
            &mut c,
        );
        let gyroscopic = &c - c.transpose();
        Ok(Linearised {
            mass,
            stiffness,
            gyroscopic,
        })
    }

    /// Normal modes about the equilibrium `q0`: K X = ω² M X by the Cholesky factor of M.
    ///
    /// Errors: [`Error::NotEquilibrium`] (with the gradient norm) when q0 is not at rest,
    /// `SingularMassMatrix` when M is singular, `IndefiniteMassMatrix` when it is regular but not
    /// positive definite, [`Error::Gyroscopic`] when L couples
    /// velocities and coordinates (use [`linear_stability`](Self::linear_stability)).
    pub fn normal_modes<L: Lagrangian>(&self, lagrangian: &L, q0: &[f64]) -> Result<NormalModes> {
        let lin = self.linearise(lagrangian, q0)?;
        let gyro = lin.gyroscopic.amax();
        if gyro > 1e-12 * lin.mass.amax().max(lin.stiffness.amax()) {
            return Err(Error::Gyroscopic { norm: gyro });
        }
        let chol = cholesky(&lin.mass, self.t)?;
        let l = chol.l();
        // A = L⁻¹ K L⁻ᵀ = L⁻¹ (L⁻¹ K)ᵀ since K is symmetric.
        // L passed the pivot test: a triangular solve with it cannot meet a zero diagonal.
        let singular = || noether_core::Error::SingularMatrix {
            what: "Cholesky factor of M",
            pivot_ratio: f64::NAN,
        };
        let lk = l.solve_lower_triangular(&lin.stiffness).ok_or_else(singular)?;
        let a = l.solve_lower_triangular(&lk.transpose()).ok_or_else(singular)?;
        let a = (&a + a.transpose()) * 0.5;
        let eig = a.try_symmetric_eigen(f64::EPSILON, 10_000).ok_or(Error::Eigen {
            what: "L⁻¹ K L⁻ᵀ"
        })?;
        let n = q0.len();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
        let omega2 = DVector::from_iterator(n, order.iter().map(|&i| eig.eigenvalues[i]));
        let mut y = DMatrix::zeros(n, n);
        for (k, &i) in order.iter().enumerate() {
            y.set_column(k, &eig.eigenvectors.column(i));
        }
        let shapes = l.transpose().solve_upper_triangular(&y).ok_or_else(singular)?;
        let (unstable_modes, zero_modes, _) = signature(&omega2, self.zero_tolerance);
        Ok(NormalModes {
            q: DVector::from_column_slice(q0),
            mass: lin.mass,
            stiffness: lin.stiffness,
            omega2,
            shapes,
            zero_modes,
            unstable_modes,
        })
    }

    /// Eigenvalues of the linearised dynamics M ẍ + G ẋ + K x = 0 about the equilibrium `q0`
    /// (gyroscopic terms included): the system is linearly (spectrally) stable when no eigenvalue has a
    /// positive real part. Same errors as [`normal_modes`](Self::normal_modes) except `Gyroscopic`.
    pub fn linear_stability<L: Lagrangian>(&self, lagrangian: &L, q0: &[f64]) -> Result<LinearStability> {
        let lin = self.linearise(lagrangian, q0)?;
        let chol = cholesky(&lin.mass, self.t)?;
        let n = q0.len();
        let mk = chol.solve(&lin.stiffness);
        let mg = chol.solve(&lin.gyroscopic);
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        a.view_mut((0, n), (n, n)).fill_with_identity();
        a.view_mut((n, 0), (n, n)).copy_from(&(-mk));
        a.view_mut((n, n), (n, n)).copy_from(&(-mg));
        let schur = nalgebra::Schur::try_new(a, f64::EPSILON, 100_000).ok_or(Error::Eigen {
            what: "linearised dynamics",
        })?;
        let mut eigenvalues: Vec<Complex<f64>> = schur.complex_eigenvalues().iter().copied().collect();
        eigenvalues.sort_by(|x, y| y.re.total_cmp(&x.re));
        let growth_rate = eigenvalues.first().map_or(0.0, |l| l.re);
        let big = eigenvalues.iter().fold(0.0_f64, |m, l| m.max(l.norm()));
        Ok(LinearStability {
            q: DVector::from_column_slice(q0),
            eigenvalues,
            growth_rate,
            gyroscopic_norm: lin.gyroscopic.amax(),
            stable: growth_rate <= self.zero_tolerance.max(1e-12) * big.max(f64::MIN_POSITIVE),
        })
    }
}

/// Cholesky factor of a mass matrix by noether-core's factorization and pivot test: singular M is
/// `SingularMassMatrix`, regular indefinite M `IndefiniteMassMatrix`.
fn cholesky(m: &DMatrix<f64>, t: f64) -> Result<nalgebra::Cholesky<f64, nalgebra::Dyn>> {
    Ok(noether_core::linalg::positive_definite_mass(m.clone(), t)?)
}
