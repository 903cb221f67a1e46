//! The linear algebra of noether in one place: the dense factorization of mass matrices and Newton
//! Jacobians, the banded LU of chain Jacobians, and the one test that calls a matrix singular.
//!
//! - [`DenseFactor`] wraps nalgebra's factorizations: [`DenseFactor::symmetric`] tries Cholesky (a
//!   mass matrix ∂²L/∂q̇², a Gram matrix) and falls back to LU with partial pivoting when the matrix is
//!   not positive definite; [`DenseFactor::lu`] goes to LU directly (an unsymmetric Newton Jacobian).
//! - [`Banded`] and [`BandedLu`]: a banded matrix and its LU with partial pivoting, O(n) for a chain.
//! - [`solve_positive_fixed`]: a square-root-free LDLᵀ solve of a small positive definite matrix on
//!   the stack (the hot path of Lagrange's accelerations), accepted by [`positive_pivots_regular`];
//!   [`factor_positive_parameter`]: a constant positive definite matrix given as a parameter (a dense
//!   mass matrix); [`rank`]: the numerical rank of a rectangular matrix by its singular values (the
//!   diagnosis of redundant constraints).
//! - Singular means: the smallest pivot is at most [`SINGULAR_PIVOT`] times the scale of the matrix,
//!   the larger of its largest pivot and its largest entry ([`pivot_ratio`]). Every factorization
//!   reports that ratio ([`FactorInfo`]), and a rejected one carries it in its error
//!   ([`FactorError`], turned into core's [`Error`] with the caller's context by
//!   [`FactorError::in_matrix`] or [`FactorError::in_mass_matrix`]). The singular values of
//!   [`rank`] are pivots in the same sense (σ_min/σ_max = 1/cond(A) exactly): one criterion for every
//!   factorization of the workspace, which goes through this module.
//!
//! ```
//! use nalgebra::DMatrix;
//! use noether_core::linalg::{DenseFactor, Method};
//!
//! // Positive definite: Cholesky. [[4, 2], [2, 3]] x = [6, 5]  →  x = [1, 1].
//! let f = DenseFactor::symmetric(DMatrix::from_row_slice(2, 2, &[4.0, 2.0, 2.0, 3.0])).unwrap();
//! assert_eq!(f.info().method, Method::Cholesky);
//! let mut b = [6.0, 5.0];
//! f.solve_in_place(&mut b);
//! assert!(b.iter().all(|x| (x - 1.0).abs() < 1e-15));
//!
//! // Singular: rejected, with the ratio of its pivots (here exactly 0).
//! let e = DenseFactor::symmetric(DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0])).unwrap_err();
//! assert_eq!(e.pivot_ratio(), 0.0);
//! ```

use crate::Error;
use nalgebra::{DMatrix, DVectorViewMut, Dyn, SMatrix, SVector};
use thiserror::Error as ThisError;

/// Relative pivot at or below which a matrix is reported as singular:
/// |smallest pivot| ≤ `SINGULAR_PIVOT` · max(|largest pivot|, max |a_ij|).
///
/// Why 1e-13: the pivot ratio is a lower bound on 1/cond(A) up to modest factors, and a solve loses
/// about log₁₀ cond(A) digits of the 16 that f64 carries. At a ratio of 1e-13 a solution keeps at most
/// ε/1e-13 ≈ 2e-3 relative accuracy, too little for an acceleration or a Newton step to be trusted,
/// while regular systems of noether (mass matrices of chains with mass ratios up to 1e6, midpoint
/// Jacobians M/h + (h/4)∇²V at small h, constraint KKT matrices) stay several orders above it. Below it
/// a degenerate Lagrangian or redundant constraints are far likelier than a meaningful system.
pub const SINGULAR_PIVOT: f64 = 1e-13;

/// The smallest pivot relative to the scale of the matrix: `lo / max(hi, norm)`, with `lo` and `hi`
/// the smallest and largest pivot magnitudes and `norm` the largest entry magnitude; 0 for the zero
/// matrix, NaN when any of them is not finite. The matrix is singular when this is at most
/// [`SINGULAR_PIVOT`] ([`is_singular`]).
#[inline]
pub fn pivot_ratio(lo: f64, hi: f64, norm: f64) -> f64 {
    if !(lo.is_finite() && hi.is_finite() && norm.is_finite()) {
        return f64::NAN;
    }
    let scale = hi.max(norm);
    if scale == 0.0 {
        0.0
    } else {
        lo / scale
    }
}

/// `true` when a [`pivot_ratio`] says singular: at most [`SINGULAR_PIVOT`], or NaN.
#[inline]
pub fn is_singular(ratio: f64) -> bool {
    ratio.is_nan() || ratio <= SINGULAR_PIVOT
}

/// (smallest, largest) magnitude of a sequence of pivots (NaN, NaN when one is NaN), for
/// [`pivot_ratio`].
#[inline]
pub fn pivot_range(pivots: impl Iterator<Item = f64>) -> (f64, f64) {
    pivots.fold((f64::INFINITY, 0.0_f64), |(lo, hi), p| {
        if p.is_nan() || lo.is_nan() {
            (f64::NAN, f64::NAN)
        } else {
            (lo.min(p.abs()), hi.max(p.abs()))
        }
    })
}

/// The pivot ratio of a diagonal matrix with entries `d` (its pivots are its entries).
pub fn diagonal_pivot_ratio(d: &[f64]) -> f64 {
    if d.is_empty() {
        return 1.0;
    }
    let (lo, hi) = pivot_range(d.iter().copied());
    pivot_ratio(lo, hi, hi)
}

/// Why a matrix could not be factored.
#[derive(Debug, Clone, Copy, PartialEq, ThisError)]
pub enum FactorError {
    /// An entry is NaN or infinite.
    #[error("the matrix has a non-finite entry")]
    NonFinite,
    /// The relative-pivot test says singular ([`SINGULAR_PIVOT`]).
    #[error("singular matrix: smallest pivot {pivot_ratio:e} relative to the scale of the matrix")]
    Singular {
        /// The [`pivot_ratio`] found (0 for an exactly singular matrix).
        pivot_ratio: f64,
    },
}

impl FactorError {
    /// The pivot ratio (NaN for a non-finite matrix).
    pub fn pivot_ratio(&self) -> f64 {
        match self {
            FactorError::NonFinite => f64::NAN,
            FactorError::Singular { pivot_ratio } => *pivot_ratio,
        }
    }

    /// As [`Error::SingularMatrix`] naming the system `what` (a non-finite matrix has ratio NaN).
    pub fn in_matrix(self, what: &'static str) -> Error {
        Error::SingularMatrix {
            what,
            pivot_ratio: self.pivot_ratio(),
        }
    }

    /// As the error of a mass matrix at time `t`: [`Error::SingularMassMatrix`], or
    /// [`Error::NonFiniteResult`] when the model produced a non-finite entry.
    pub fn in_mass_matrix(self, t: f64) -> Error {
        match self {
            FactorError::NonFinite => Error::NonFiniteResult {
                what: "mass matrix",
                t,
                component: None,
            },
            FactorError::Singular { pivot_ratio } => Error::SingularMassMatrix { t, pivot_ratio },
        }
    }
}

/// Which factorization a [`DenseFactor`] holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// A = L Lᵀ (symmetric positive definite).
    Cholesky,
    /// P A = L U with partial pivoting (indefinite or unsymmetric).
    Lu,
}

/// What a factorization found: its method and its [`pivot_ratio`] (above [`SINGULAR_PIVOT`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FactorInfo {
    /// Cholesky or LU.
    pub method: Method,
    /// Smallest pivot relative to the scale of the matrix (1/cond(A) up to modest factors). For
    /// Cholesky the pivots are those of L D Lᵀ, D = diag(L)², the same as an LU without interchanges.
    pub pivot_ratio: f64,
}

#[derive(Debug, Clone)]
enum Kind {
    Cholesky(nalgebra::Cholesky<f64, Dyn>),
    Lu(nalgebra::LU<f64, Dyn, Dyn>),
}

/// A factored dense square matrix, by nalgebra's Cholesky or LU, accepted by the relative-pivot test.
#[derive(Debug, Clone)]
pub struct DenseFactor {
    kind: Kind,
    info: FactorInfo,
}

/// Largest entry magnitude, or `Err(NonFinite)`.
fn finite_norm(a: &DMatrix<f64>) -> Result<f64, FactorError> {
    if a.iter().any(|v| !v.is_finite()) {
        return Err(FactorError::NonFinite);
    }
    Ok(a.iter().fold(0.0_f64, |m, v| m.max(v.abs())))
}

fn accept(lo: f64, hi: f64, norm: f64) -> Result<f64, FactorError> {
    let ratio = pivot_ratio(lo, hi, norm);
    if is_singular(ratio) {
        Err(FactorError::Singular {
            pivot_ratio: if ratio.is_nan() { 0.0 } else { ratio },
        })
    } else {
        Ok(ratio)
    }
}

impl DenseFactor {
    /// Factors a matrix that is symmetric by construction (a mass matrix, a Gram matrix; only its lower
    /// triangle is read by Cholesky): Cholesky when it is positive definite, else LU of the whole
    /// matrix. Errors when an entry is not finite or the pivot test says singular.
    pub fn symmetric(a: DMatrix<f64>) -> Result<Self, FactorError> {
        let norm = finite_norm(&a)?;
        if !a.is_square() {
            return Err(FactorError::Singular { pivot_ratio: 0.0 });
        }
        if a.nrows() == 0 {
            return Self::lu_checked(a, norm);
        }
        match a.clone().cholesky() {
            Some(ch) => {
                let (lo, hi) = pivot_range(ch.l_dirty().diagonal().iter().map(|l| l * l));
                let pivot_ratio = accept(lo, hi, norm)?;
                Ok(DenseFactor {
                    kind: Kind::Cholesky(ch),
                    info: FactorInfo {
                        method: Method::Cholesky,
                        pivot_ratio,
                    },
                })
            }
            None => Self::lu_checked(a, norm),
        }
    }

    /// Factors a general square matrix (a Newton Jacobian) by LU with partial pivoting. Errors when an
    /// entry is not finite or the pivot test says singular.
    pub fn lu(a: DMatrix<f64>) -> Result<Self, FactorError> {
        let norm = finite_norm(&a)?;
        Self::lu_checked(a, norm)
    }

    fn lu_checked(a: DMatrix<f64>, norm: f64) -> Result<Self, FactorError> {
        if !a.is_square() {
            return Err(FactorError::Singular { pivot_ratio: 0.0 });
        }
        if a.nrows() == 0 {
            return Ok(DenseFactor {
                kind: Kind::Lu(a.lu()),
                info: FactorInfo {
                    method: Method::Lu,
                    pivot_ratio: 1.0,
                },
            });
        }
        let lu = a.lu();
        let (lo, hi) = pivot_range(lu.u().diagonal().iter().copied());
        let pivot_ratio = accept(lo, hi, norm)?;
        Ok(DenseFactor {
            kind: Kind::Lu(lu),
            info: FactorInfo {
                method: Method::Lu,
                pivot_ratio,
            },
        })
    }

    /// Method and pivot ratio.
    pub fn info(&self) -> FactorInfo {
        self.info
    }

    /// The Cholesky factor, when the matrix was positive definite.
    pub fn cholesky(&self) -> Option<&nalgebra::Cholesky<f64, Dyn>> {
        match &self.kind {
            Kind::Cholesky(c) => Some(c),
            Kind::Lu(_) => None,
        }
    }

    /// Overwrites `b` with A⁻¹ b. (Cannot fail: the pivot test has excluded zero pivots.)
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let n = b.len();
        let mut v = DVectorViewMut::from_slice(b, n);
        match &self.kind {
            Kind::Cholesky(c) => c.solve_mut(&mut v),
            Kind::Lu(l) => {
                // `false` only for a zero pivot, which the pivot test has rejected.
                let _ = l.solve_mut(&mut v);
            }
        }
    }

    /// A⁻¹ B for a matrix B of n rows.
    pub fn solve_matrix(&self, b: &DMatrix<f64>) -> DMatrix<f64> {
        let mut x = b.clone();
        match &self.kind {
            Kind::Cholesky(c) => c.solve_mut(&mut x),
            Kind::Lu(l) => {
                // As in `solve_in_place`: no zero pivot gets past the test.
                let _ = l.solve_mut(&mut x);
            }
        }
        x
    }
}

/// Factors a mass matrix M = ∂²L/∂q̇² found at time `t` ([`DenseFactor::symmetric`]), with its
/// failures as [`Error::SingularMassMatrix`] or [`Error::NonFiniteResult`].
pub fn factor_mass(m: DMatrix<f64>, t: f64) -> crate::Result<DenseFactor> {
    DenseFactor::symmetric(m).map_err(|e| e.in_mass_matrix(t))
}

/// Factors a mass matrix M = ∂²L/∂q̇² found at time `t` that must be positive definite (the kinetic
/// energy ½ q̇ᵀ M q̇ > 0 for every q̇ ≠ 0: Lagrange's equations stepped by
/// [`EulerLagrange`](crate::EulerLagrange), the Legendre transform): its Cholesky factor, or why there
/// is none: [`Error::SingularMassMatrix`] (the pivot test), [`Error::NonFiniteResult`] (a non-finite
/// entry), or [`Error::IndefiniteMassMatrix`] with the smallest eigenvalue relative to the largest in
/// magnitude (regular with a negative eigenvalue, e.g. a negative mass; the eigenvalues are computed
/// only in that case).
pub fn factor_positive_mass(m: DMatrix<f64>, t: f64) -> crate::Result<DenseFactor> {
    let f = factor_mass(m.clone(), t)?;
    match f.kind {
        Kind::Cholesky(_) => Ok(f),
        Kind::Lu(_) => {
            let eig = m.symmetric_eigenvalues();
            let (lo, hi) = eig.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), e| {
                (lo.min(*e), hi.max(e.abs()))
            });
            // LU accepted M as regular, so its smallest eigenvalue in magnitude is not zero; the one
            // below zero is what makes it indefinite.
            Err(Error::IndefiniteMassMatrix {
                t,
                eigenvalue: lo / hi,
            })
        }
    }
}

/// Factors a constant matrix given as a parameter that must be positive definite (a dense mass matrix
/// of a natural system or a discrete mechanical one): its Cholesky factor by [`factor_mass`] (so
/// [`Error::SingularMassMatrix`] at t = 0 by the pivot test), or [`Error::InvalidParameter`] named
/// `name` ("must be positive definite") when it is regular but indefinite.
pub fn factor_positive_parameter(m: DMatrix<f64>, name: &'static str) -> crate::Result<DenseFactor> {
    let f = factor_mass(m, 0.0)?;
    match f.kind {
        Kind::Cholesky(_) => Ok(f),
        Kind::Lu(_) => Err(Error::InvalidParameter {
            name,
            value: f64::NAN,
            reason: "must be positive definite",
        }),
    }
}

/// `true` when the pivots d_j of M = L D Lᵀ (L unit lower triangular, D = diag(d_j)) show M positive
/// definite and regular: every d_j > 0 and their [`pivot_ratio`] against `norm` (the largest entry
/// magnitude of M, or its largest diagonal entry, which bounds every entry of a positive definite M:
/// |m_ij| ≤ √(m_ii m_jj)) not singular by [`is_singular`]. The d_j are the squared diagonal of the
/// Cholesky factor, so this is the test [`DenseFactor::symmetric`] applies to its Cholesky pivots. The
/// acceptance of every square-root-free LDLᵀ solve of the workspace: [`solve_positive_fixed`] and the
/// unrolled solve of compiled models (noether-compile).
#[inline]
pub fn positive_pivots_regular(pivots: impl Iterator<Item = f64>, norm: f64) -> bool {
    let mut positive = true;
    let (lo, hi) = pivot_range(pivots.inspect(|&d| positive &= d > 0.0));
    positive && !is_singular(pivot_ratio(lo, hi, norm))
}

/// Overwrites `b` with M⁻¹ b for a small symmetric positive definite M held on the stack (no heap
/// allocation), by the square-root-free Cholesky factorization M = L D Lᵀ (L unit lower triangular,
/// D = diag(d_j); only the lower triangle of M is read):
///
/// ```text
/// d_j  = m_jj − Σ_{k<j} l_jk (l_jk d_k)
/// l_ij = (m_ij − Σ_{k<j} l_ik (l_jk d_k)) · (1/d_j)                  i > j
/// y_i  = b_i − Σ_{k<i} l_ik y_k,   x_i = y_i · (1/d_i) − Σ_{k>i} l_ki x_k
/// ```
///
/// (Golub & Van Loan, *Matrix Computations*, 4th ed., §4.1.2): no square root, and one reciprocal per
/// pivot, reused by the column of L and by the diagonal solve, so that the dependent chain of a small
/// solve holds N divisions and no square root (Cholesky's L_jj = √d_j adds N square roots and a
/// division per row and per substitution step). Accepted by [`positive_pivots_regular`] with the
/// largest diagonal entry as the scale, as in the compiled models' LDLᵀ; for a positive definite M it
/// is the largest entry (|m_ij| ≤ √(m_ii m_jj)), so this is the test of [`DenseFactor::symmetric`]
/// (d_j = L_jj², scale max(d_max, max |m_ij|)) without a pass over the upper triangle. `false`, with
/// `b` untouched, when a pivot is not positive, the pivots are singular by that test, or an entry of
/// the lower triangle is not finite (a NaN pivot follows, or an infinite one, whose ratio is NaN; an
/// infinite l_ij makes a later pivot −∞). The caller then reports why, e.g. by
/// [`factor_positive_mass`].
#[inline]
pub fn solve_positive_fixed<const N: usize>(m: SMatrix<f64, N, N>, b: &mut SVector<f64, N>) -> bool {
    let Some((l, d, inv)) = ldlt_fixed(&m) else {
        return false;
    };
    let norm = (0..N).fold(0.0_f64, |n, j| n.max(m[(j, j)]));
    if !positive_pivots_regular(d.iter().copied(), norm) {
        return false;
    }
    // L y = b, then Lᵀ x = D⁻¹ y, in place.
    for i in 0..N {
        let mut s = b[i];
        for k in 0..i {
            s -= l[(i, k)] * b[k];
        }
        b[i] = s;
    }
    for i in (0..N).rev() {
        let mut s = b[i] * inv[i];
        for k in i + 1..N {
            s -= l[(k, i)] * b[k];
        }
        b[i] = s;
    }
    true
}

/// M = L D Lᵀ of [`solve_positive_fixed`]: L in the strict lower triangle of the matrix returned (the
/// rest holds M), the pivots d_j and their reciprocals; `None` at the first pivot that is not positive
/// (or NaN).
#[inline]
fn ldlt_fixed<const N: usize>(m: &SMatrix<f64, N, N>) -> Option<(SMatrix<f64, N, N>, [f64; N], [f64; N])> {
    let mut l = *m;
    let (mut d, mut inv) = ([0.0; N], [0.0; N]);
    for j in 0..N {
        // w_k = l_jk d_k for k < j (row j of L D), shared by the pivot and by column j of L.
        let mut w = [0.0; N];
        let mut dj = m[(j, j)];
        for k in 0..j {
            w[k] = l[(j, k)] * d[k];
            dj -= l[(j, k)] * w[k];
        }
        if dj.is_nan() || dj <= 0.0 {
            return None;
        }
        let r = 1.0 / dj;
        (d[j], inv[j]) = (dj, r);
        for i in j + 1..N {
            let mut s = m[(i, j)];
            for k in 0..j {
                s -= l[(i, k)] * w[k];
            }
            l[(i, j)] = s * r;
        }
    }
    Some((l, d, inv))
}

/// The numerical rank of an m × n matrix A and its smallest singular value relative to the largest,
/// σ_min/σ_max (0 when there are more rows than columns, or for A = 0; 1 without rows), by the
/// singular value decomposition: σ_i counts when σ_i/σ_max is not singular by [`is_singular`] (above
/// [`SINGULAR_PIVOT`]), the criterion of every factorization here; at most min(m, n). Singular values
/// rather than the eigenvalues of A Aᵀ, which would square the condition number.
pub fn rank(a: &DMatrix<f64>) -> (usize, f64) {
    if a.nrows() == 0 {
        return (0, 1.0);
    }
    let s = a.clone().svd(false, false).singular_values;
    let hi = s.iter().fold(0.0_f64, |m, v| m.max(*v));
    let rank = s.iter().filter(|v| !is_singular(**v / hi)).count();
    let lo = if a.nrows() > a.ncols() {
        0.0
    } else {
        s.iter().fold(f64::INFINITY, |m, v| m.min(*v))
    };
    (rank.min(a.ncols()), if hi > 0.0 { lo / hi } else { 0.0 })
}

/// The right singular vectors of the `k` smallest singular values of an m × n matrix A (k ≤ n, else
/// fewer), as the columns of an n × k matrix, with those singular values in increasing order. A wide A
/// (m < n) is padded with zero rows, so its n − m directions that no row sees come first with σ = 0.
/// When those σ are negligible against the largest ([`is_singular`]), the columns are an orthonormal
/// basis of A's numerical null space: the tangent plane at a branch point of a family, where two
/// branches cross. `None` when A has entries that are not finite or the SVD does not converge.
pub fn smallest_right_singular(a: &DMatrix<f64>, k: usize) -> Option<(DMatrix<f64>, Vec<f64>)> {
    let (m, n) = a.shape();
    if a.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let mut square = DMatrix::zeros(m.max(n), n);
    square.view_mut((0, 0), (m, n)).copy_from(a);
    let svd = nalgebra::SVD::try_new(square, false, true, f64::EPSILON, 1000)?;
    let vt = svd.v_t?;
    let mut order: Vec<usize> = (0..svd.singular_values.len()).collect();
    order.sort_by(|&i, &j| svd.singular_values[i].total_cmp(&svd.singular_values[j]));
    order.truncate(k.min(n));
    let vectors = DMatrix::from_fn(n, order.len(), |r, c| vt[(order[c], r)]);
    Some((vectors, order.iter().map(|&i| svd.singular_values[i]).collect()))
}

/// The Cholesky factor of a mass matrix that must be positive definite (the Legendre transform, normal
/// modes), or why there is none, as [`factor_positive_mass`].
pub fn positive_definite_mass(m: DMatrix<f64>, t: f64) -> crate::Result<nalgebra::Cholesky<f64, Dyn>> {
    match factor_positive_mass(m, t)?.kind {
        Kind::Cholesky(c) => Ok(c),
        // factor_positive_mass returns only Cholesky factors.
        Kind::Lu(_) => Err(Error::SingularMassMatrix {
            t,
            pivot_ratio: f64::NAN,
        }),
    }
}

/// Overwrites `rhs` with A⁻¹ rhs by a kept factor; [`Error::SingularMatrix`] naming `what` (pivot
/// ratio NaN) when there is none (a solve before the first factorization, or after a failed one).
pub fn solve_with(factor: Option<&DenseFactor>, rhs: &mut [f64], what: &'static str) -> crate::Result<()> {
    let f = factor.ok_or(Error::SingularMatrix {
        what,
        pivot_ratio: f64::NAN,
    })?;
    f.solve_in_place(rhs);
    Ok(())
}

/// An n × n matrix with `kl` sub-diagonals and `ku` super-diagonals, stored by rows with room for the
/// kl extra super-diagonals that pivoting fills in; factored by [`Banded::factor`].
///
/// Elimination with row interchanges, as LAPACK's `dgbtrf`: with kl sub- and ku super-diagonals, U has
/// kl + ku super-diagonals after pivoting, and the factorization costs O(n·kl·(kl + ku)), linear in n.
/// (nalgebra has no banded LU, and nalgebra-sparse only a Cholesky factorization, which needs a positive
/// definite matrix; the midpoint Jacobian M/h + (h/4)∇²V is indefinite for non-convex potentials at
/// large steps.)
///
/// ```
/// use noether_core::linalg::Banded;
///
/// // [[2, 1, 0], [1, 2, 1], [0, 1, 2]] x = [3, 4, 3]  →  x = [1, 1, 1]
/// let mut a = Banded::zeros(3, 1, 1);
/// for i in 0..3 {
///     a.add(i, i, 2.0);
///     if i + 1 < 3 {
///         a.add(i, i + 1, 1.0);
///         a.add(i + 1, i, 1.0);
///     }
/// }
/// let lu = a.factor().unwrap();
/// let mut b = [3.0, 4.0, 3.0];
/// lu.solve(&mut b);
/// assert!(b.iter().all(|x| (x - 1.0).abs() < 1e-15));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Banded {
    n: usize,
    kl: usize,
    ku: usize,
    /// Row i holds columns i − kl ..= i + kl + ku at offsets 0 ..= 2kl + ku.
    data: Vec<f64>,
}

impl Banded {
    /// The zero matrix of size n with bandwidths (kl, ku).
    pub fn zeros(n: usize, kl: usize, ku: usize) -> Self {
        Banded {
            n,
            kl,
            ku,
            data: vec![0.0; n * (2 * kl + ku + 1)],
        }
    }

    /// Size n.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// (kl, ku).
    pub fn bandwidths(&self) -> (usize, usize) {
        (self.kl, self.ku)
    }

    fn width(&self) -> usize {
        2 * self.kl + self.ku + 1
    }

    /// Sets every entry to zero.
    pub fn fill_zero(&mut self) {
        self.data.iter_mut().for_each(|x| *x = 0.0);
    }

    /// `true` when (i, j) lies inside the band.
    pub fn in_band(&self, i: usize, j: usize) -> bool {
        i < self.n && j < self.n && j + self.kl >= i && j <= i + self.ku
    }

    #[inline]
    fn at(&self, i: usize, j: usize) -> usize {
        i * self.width() + (j + self.kl - i)
    }

    /// Adds `v` to entry (i, j), which must lie inside the band (panics otherwise: an assembly bug).
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        assert!(
            self.in_band(i, j),
            "entry ({i}, {j}) outside the band ({}, {})",
            self.kl,
            self.ku
        );
        let k = self.at(i, j);
        self.data[k] += v;
    }

    /// Entry (i, j) (zero outside the band).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        if self.in_band(i, j) {
            self.data[self.at(i, j)]
        } else {
            0.0
        }
    }

    /// y = A x.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        for (i, yi) in y.iter_mut().enumerate().take(self.n) {
            let lo = i.saturating_sub(self.kl);
            let hi = (i + self.ku).min(self.n - 1);
            *yi = (lo..=hi).map(|j| self.data[self.at(i, j)] * x[j]).sum();
        }
    }

    /// LU factorization with partial pivoting (consumes the matrix; the storage becomes the factor).
    /// Errors when an entry is not finite or the pivot test ([`SINGULAR_PIVOT`]) says singular, as for
    /// [`DenseFactor`]: the pivots are the diagonal of U, the scale the larger of the largest pivot and
    /// the largest entry of A.
    pub fn factor(mut self) -> Result<BandedLu, FactorError> {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        if self.data.iter().any(|v| !v.is_finite()) {
            return Err(FactorError::NonFinite);
        }
        let norm = self.data.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let mut piv = vec![0usize; n];
        let mut mult = vec![0.0; n * kl];
        let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
        for k in 0..n {
            let last_row = (k + kl).min(n - 1);
            let last_col = (k + kl + ku).min(n - 1);
            let mut p = k;
            let mut best = self.data[self.at(k, k)].abs();
            for i in k + 1..=last_row {
                let v = self.data[self.at(i, k)].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            (lo, hi) = (lo.min(best), hi.max(best));
            // A pivot already below the test makes the matrix singular whatever follows (the scale only
            // grows); stop before dividing by it.
            if is_singular(pivot_ratio(lo, hi, norm)) {
                return Err(FactorError::Singular {
                    pivot_ratio: pivot_ratio(lo, hi, norm).max(0.0),
                });
            }
            piv[k] = p;
            if p != k {
                for j in k..=last_col {
                    let (a, b) = (self.at(k, j), self.at(p, j));
                    self.data.swap(a, b);
                }
            }
            let d = self.data[self.at(k, k)];
            for i in k + 1..=last_row {
                let ik = self.at(i, k);
                let l = self.data[ik] / d;
                self.data[ik] = 0.0;
                mult[k * kl + (i - k - 1)] = l;
                if l != 0.0 {
                    for j in k + 1..=last_col {
                        let kj = self.data[self.at(k, j)];
                        let ij = self.at(i, j);
                        self.data[ij] -= l * kj;
                    }
                }
            }
        }
        // Growth of later pivots can raise `hi`: the final test on all of them.
        let pivot_ratio = accept(lo, hi, norm)?;
        Ok(BandedLu {
            u: self,
            piv,
            mult,
            pivot_ratio,
        })
    }

    /// `true` when the symmetric matrix whose lower band this is (kl read; the upper band ignored) is
    /// positive definite and regular by [`positive_pivots_regular`]: the square-root-free Cholesky
    /// factorisation A = L D Lᵀ restricted to the band (L inherits A's lower bandwidth), O(n kl²),
    ///
    /// ```text
    /// d_j  = a_jj − Σ_k l_jk² d_k,    l_ij = (a_ij − Σ_k l_ik l_jk d_k) / d_j,   j − kl ≤ k < j.
    /// ```
    ///
    /// The test of an inertia correction: is H + δI positive definite for the δ tried?
    pub fn positive_definite(&self) -> bool {
        let (n, kl) = (self.n, self.kl);
        if self.data.iter().any(|v| !v.is_finite()) {
            return false;
        }
        let norm = (0..n).fold(0.0_f64, |m, i| m.max(self.get(i, i).abs()));
        // l[i * (kl + 1) + (j + kl − i)] = l_ij for i − kl ≤ j ≤ i (the diagonal slot holds d_i).
        let w = kl + 1;
        let mut l = vec![0.0; n * w];
        let at = |i: usize, j: usize| i * w + (j + kl - i);
        let mut pivots = Vec::with_capacity(n);
        for j in 0..n {
            let first = j.saturating_sub(kl);
            let d = self.get(j, j)
                - (first..j)
                    .map(|k| l[at(j, k)] * l[at(j, k)] * l[at(k, k)])
                    .sum::<f64>();
            if d.is_nan() || d <= 0.0 {
                return false;
            }
            l[at(j, j)] = d;
            pivots.push(d);
            for i in j + 1..=(j + kl).min(n.saturating_sub(1)) {
                let first = i.saturating_sub(kl);
                let s: f64 = (first..j).map(|k| l[at(i, k)] * l[at(j, k)] * l[at(k, k)]).sum();
                l[at(i, j)] = (self.get(i, j) - s) / d;
            }
        }
        positive_pivots_regular(pivots.into_iter(), norm)
    }
}

/// The factor P A = L U of a [`Banded`] matrix.
#[derive(Debug, Clone)]
pub struct BandedLu {
    u: Banded,
    piv: Vec<usize>,
    mult: Vec<f64>,
    pivot_ratio: f64,
}

impl BandedLu {
    /// Method (LU) and pivot ratio, as for a [`DenseFactor`].
    pub fn info(&self) -> FactorInfo {
        FactorInfo {
            method: Method::Lu,
            pivot_ratio: self.pivot_ratio,
        }
    }

    /// Overwrites `b` with A⁻¹ b.
    pub fn solve(&self, b: &mut [f64]) {
        let (n, kl, ku) = (self.u.n, self.u.kl, self.u.ku);
        for k in 0..n {
            let p = self.piv[k];
            if p != k {
                b.swap(k, p);
            }
            let bk = b[k];
            let last = (k + kl).min(n - 1);
            for (bi, l) in b[k + 1..=last].iter_mut().zip(&self.mult[k * kl..]) {
                *bi -= l * bk;
            }
        }
        for k in (0..n).rev() {
            let last_col = (k + kl + ku).min(n - 1);
            let mut s = b[k];
            for (j, bj) in b.iter().enumerate().take(last_col + 1).skip(k + 1) {
                s -= self.u.data[self.u.at(k, j)] * bj;
            }
            b[k] = s / self.u.data[self.u.at(k, k)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DVector;

    #[test]
    fn smallest_right_singular_spans_the_null_space() {
        // A wide matrix: the direction no row sees (e₃) has σ = 0, the next σ is 1.
        let a = DMatrix::from_row_slice(2, 3, &[1.0, 0.0, 0.0, 0.0, 2.0, 0.0]);
        let (v, s) = smallest_right_singular(&a, 2).unwrap();
        assert!(s[0].abs() < 1e-15 && (s[1] - 1.0).abs() < 1e-15, "{s:?}");
        assert!((v.column(0).abs() - DVector::from_vec(vec![0.0, 0.0, 1.0])).amax() < 1e-15);
        assert!((v.column(1).abs() - DVector::from_vec(vec![1.0, 0.0, 0.0])).amax() < 1e-15);
        // A square matrix of rank one: its null vector (1, −1)/√2 to rounding.
        let b = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0]);
        let (v, s) = smallest_right_singular(&b, 1).unwrap();
        assert!(s[0] < 1e-15 && (v[(0, 0)] + v[(1, 0)]).abs() < 1e-15);
        assert!((v[(0, 0)].abs() - 0.5f64.sqrt()).abs() < 1e-15);
        // Entries that are not finite have no decomposition.
        let c = DMatrix::from_row_slice(1, 2, &[f64::NAN, 1.0]);
        assert!(smallest_right_singular(&c, 1).is_none());
    }

    /// A small deterministic generator in [−½, ½) (no rand in core's unit tests).
    fn lcg(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        }
    }

    /// Q diag(1, 1e-17) Qᵀ with Q a rotation: symmetric positive semidefinite in exact arithmetic up to
    /// the 1e-17 eigenvalue, whose pivot ratio (1e-17 up to rounding of the entries, ~1e-16 absolute)
    /// lies far below SINGULAR_PIVOT. Rejected by both the symmetric and the LU path, with its ratio.
    #[test]
    fn bad_input_near_singular_rejected_with_ratio() {
        let (c, s) = (0.6_f64, 0.8_f64);
        let q = DMatrix::from_row_slice(2, 2, &[c, -s, s, c]);
        let a = &q * DMatrix::from_diagonal(&DVector::from_vec(vec![1.0, 1e-17])) * q.transpose();
        for r in [DenseFactor::symmetric(a.clone()), DenseFactor::lu(a.clone())] {
            match r {
                Err(FactorError::Singular { pivot_ratio }) => {
                    // Rounding of the entries (ε·‖A‖ ≈ 1e-16) dominates the exact 1e-17: the ratio found
                    // is at most a few ε (measured 1.7e-16 on both paths), far below SINGULAR_PIVOT.
                    assert!((0.0..=1e-15).contains(&pivot_ratio), "{pivot_ratio:e}");
                }
                other => panic!("expected Singular, got {other:?}"),
            }
        }
        // Exactly the ratio when it is representable: diag(1, 1e-17) itself.
        let d = DMatrix::from_diagonal(&DVector::from_vec(vec![1.0, 1e-17]));
        let e = DenseFactor::symmetric(d.clone()).unwrap_err();
        assert_eq!(e.pivot_ratio(), 1e-17);
        assert_eq!(DenseFactor::lu(d).unwrap_err().pivot_ratio(), 1e-17);
        assert_eq!(
            e.in_mass_matrix(0.5),
            Error::SingularMassMatrix {
                t: 0.5,
                pivot_ratio: 1e-17
            }
        );
        // The banded LU applies the same test.
        let mut b = Banded::zeros(2, 1, 1);
        b.add(0, 0, 1.0);
        b.add(1, 1, 1e-17);
        assert_eq!(b.factor().unwrap_err().pivot_ratio(), 1e-17);
        // Non-finite entries and the zero matrix.
        let nan = DMatrix::from_row_slice(1, 1, &[f64::NAN]);
        assert_eq!(DenseFactor::lu(nan).unwrap_err(), FactorError::NonFinite);
        assert_eq!(
            DenseFactor::symmetric(DMatrix::zeros(3, 3))
                .unwrap_err()
                .pivot_ratio(),
            0.0
        );
        assert_eq!(Banded::zeros(4, 1, 1).factor().unwrap_err().pivot_ratio(), 0.0);
    }

    /// A symmetric indefinite, well-conditioned matrix (eigenvalues ±1, ±2, 3 rotated by a random
    /// orthogonal Q): Cholesky fails, LU takes over, and A x = b is solved against the known x.
    /// Backward-stable LU gives ‖x̂ − x‖ ≲ cond(A)·n·ε ≈ 3·5·2.2e-16 = 3e-15 relative.
    #[test]
    fn closed_form_indefinite_falls_back_to_lu() {
        let n = 5;
        let mut rnd = lcg(7);
        let m = DMatrix::from_fn(n, n, |_, _| rnd());
        let q = m.qr().q();
        let lambda = DVector::from_vec(vec![1.0, -1.0, 2.0, -2.0, 3.0]);
        let a = &q * DMatrix::from_diagonal(&lambda) * q.transpose();
        let a = (&a + a.transpose()) * 0.5;
        let x = DVector::from_fn(n, |i, _| 1.0 + i as f64);
        let b = &a * &x;
        let f = DenseFactor::symmetric(a.clone()).unwrap();
        assert_eq!(f.info().method, Method::Lu);
        assert!(f.cholesky().is_none());
        assert!(f.info().pivot_ratio > 1e-2, "{:?}", f.info());
        let mut y = b.as_slice().to_vec();
        f.solve_in_place(&mut y);
        let err = (DVector::from_vec(y) - &x).amax() / x.amax();
        // Measured 6.7e-16 (pivot ratio 0.31); the 1e-14 bound is the brief's, ~5× the estimate above.
        assert!(err < 1e-14, "{err:e}");
        // The same matrix with its spectrum made positive goes through Cholesky.
        let spd = &q * DMatrix::from_diagonal(&lambda.map(f64::abs)) * q.transpose();
        let g = DenseFactor::symmetric((&spd + spd.transpose()) * 0.5).unwrap();
        assert_eq!(g.info().method, Method::Cholesky);
    }

    /// The banded LU against nalgebra's dense LU (through `DenseFactor::lu`) on a random unsymmetric
    /// banded matrix whose small diagonal forces row interchanges. Both are backward stable, so they
    /// agree to cond(A)·ε; measured 7.7e-16 (relative to 1 + |x|), bound 1e-13 (the brief's).
    #[test]
    fn regress_banded_lu_vs_dense() {
        let (n, kl, ku) = (23, 2, 3);
        let mut a = Banded::zeros(n, kl, ku);
        let mut dense = DMatrix::zeros(n, n);
        let mut rnd = lcg(12345);
        for i in 0..n {
            for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                let v = if i == j { 1e-3 * rnd() } else { rnd() };
                a.add(i, j, v);
                dense[(i, j)] = v;
            }
        }
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut x = b.clone();
        let banded = a.clone().factor().unwrap();
        banded.solve(&mut x);
        let mut xd = b.clone();
        let df = DenseFactor::lu(dense).unwrap();
        df.solve_in_place(&mut xd);
        let worst = (0..n).fold(0.0_f64, |m, i| m.max((x[i] - xd[i]).abs() / (1.0 + xd[i].abs())));
        assert!(worst < 1e-13, "banded vs dense: {worst:e}");
        let mut y = vec![0.0; n];
        a.mul_vec(&x, &mut y);
        for i in 0..n {
            assert!((y[i] - b[i]).abs() < 1e-12);
        }
        // Same pivots up to rounding, same ratio.
        let (rb, rd) = (banded.info().pivot_ratio, df.info().pivot_ratio);
        assert!((rb - rd).abs() < 1e-12 * rd, "{rb:e} vs {rd:e}");
    }

    /// The banded positive-definiteness test against the spectrum: a random symmetric banded A
    /// (n = 30, half-bandwidth 3) shifted to A + σI with σ = −λ_min(A) + s·(λ_max − λ_min) is
    /// positive definite exactly when s > 0. The test must say yes from s = 1e-6 up (the smallest
    /// pivot then stays far above the 1e-13 singularity threshold) and no for s ≤ −1e-6 (a negative
    /// eigenvalue makes some LDLᵀ pivot negative, Sylvester's law of inertia).
    #[test]
    fn banded_positive_definite_matches_spectrum() {
        let (n, kl) = (30, 3);
        let mut rnd = lcg(777);
        let mut dense = DMatrix::zeros(n, n);
        for i in 0..n {
            for j in i.saturating_sub(kl)..=i {
                let v = rnd();
                dense[(i, j)] = v;
                dense[(j, i)] = v;
            }
        }
        let eig = dense.clone().symmetric_eigenvalues();
        let (lo, hi) = (eig.min(), eig.max());
        for s in [-0.5, -1e-3, -1e-6, 1e-6, 1e-3, 0.5] {
            let mut a = Banded::zeros(n, kl, kl);
            for i in 0..n {
                for j in i.saturating_sub(kl)..=(i + kl).min(n - 1) {
                    let shift = if i == j { -lo + s * (hi - lo) } else { 0.0 };
                    a.add(i, j, dense[(i, j)] + shift);
                }
            }
            assert_eq!(a.positive_definite(), s > 0.0, "shift fraction {s}");
        }
        let mut bad = Banded::zeros(2, 1, 1);
        bad.add(0, 0, f64::NAN);
        assert!(!bad.positive_definite());
    }

    /// M = B Bᵀ + I with B random in [−½, ½)^{N×N}: symmetric positive definite, eigenvalues in
    /// [1, 1 + N²/4], and b random; x by [`solve_positive_fixed`] and by nalgebra's Cholesky of the same
    /// static matrix. Returns ‖x_ldlt − x_chol‖∞ / ‖x_chol‖∞ divided by the bound below.
    fn ldlt_against_cholesky<const N: usize>(rnd: &mut impl FnMut() -> f64) -> f64 {
        let b_mat = SMatrix::<f64, N, N>::from_fn(|_, _| rnd());
        let m = b_mat * b_mat.transpose() + SMatrix::<f64, N, N>::identity();
        let b = SVector::<f64, N>::from_fn(|_, _| rnd());
        let mut x = b;
        assert!(solve_positive_fixed(m, &mut x), "N = {N}: rejected {m}");
        let xc = m.cholesky().unwrap().solve(&b);
        let eig = DMatrix::from_column_slice(N, N, m.as_slice()).symmetric_eigenvalues();
        let cond = eig.max() / eig.min();
        // Both are backward stable (Cholesky and LDLᵀ without pivoting on a positive definite M,
        // Higham §10.1): each x̂ solves (M + ΔM) x̂ = b with ‖ΔM‖ ≲ c N ε ‖M‖, so each lies within
        // ≈ c N cond(M) ε of x relative, and they differ by at most twice that. c = 4 covers the
        // constants of the factorization and of the two substitutions.
        let bound = 2.0 * 4.0 * N as f64 * cond * f64::EPSILON;
        (x - xc).amax() / xc.amax() / bound
    }

    /// The LDLᵀ solve agrees with nalgebra's Cholesky solve on random positive definite matrices
    /// N = 1..8 (20 each) within the bound of `ldlt_against_cholesky`, 8 N cond(M) ε relative (at most
    /// 2.4e-13 here, as cond(M) ≤ 1 + N²/4 ≤ 17): a bound from backward stability rather than a fixed
    /// number, so that it stays tight for the well-conditioned small N (measured: 0.12 of it at worst).
    #[test]
    fn ldlt_fixed_agrees_with_cholesky() {
        let mut rnd = lcg(2026);
        let mut worst = 0.0_f64;
        for _ in 0..20 {
            worst = worst
                .max(ldlt_against_cholesky::<1>(&mut rnd))
                .max(ldlt_against_cholesky::<2>(&mut rnd))
                .max(ldlt_against_cholesky::<3>(&mut rnd))
                .max(ldlt_against_cholesky::<4>(&mut rnd))
                .max(ldlt_against_cholesky::<5>(&mut rnd))
                .max(ldlt_against_cholesky::<6>(&mut rnd))
                .max(ldlt_against_cholesky::<7>(&mut rnd))
                .max(ldlt_against_cholesky::<8>(&mut rnd));
        }
        assert!(worst <= 1.0, "LDLᵀ against Cholesky: {worst} of the bound");
    }

    /// Indefinite, singular, near-singular and non-finite matrices are rejected with b untouched
    /// (bit for bit), and the acceptance threshold is that of `DenseFactor::symmetric`.
    #[test]
    fn ldlt_fixed_rejects_with_b_untouched() {
        let b0 = SVector::<f64, 3>::new(1.0, -2.0, 3.0);
        let reject = |m: SMatrix<f64, 3, 3>, why: &str| {
            let mut b = b0;
            assert!(!solve_positive_fixed(m, &mut b), "{why}: accepted");
            assert_eq!(b.map(f64::to_bits), b0.map(f64::to_bits), "{why}: b changed");
        };
        let spd = SMatrix::<f64, 3, 3>::new(4.0, 1.0, 2.0, 1.0, 5.0, -1.0, 2.0, -1.0, 6.0);
        let mut b = b0;
        assert!(solve_positive_fixed(spd, &mut b));
        assert!((spd * b - b0).amax() < 1e-14);
        // Indefinite: eigenvalues 3, −1, 1 (the second pivot is 1 − 4 = −3).
        reject(
            SMatrix::<f64, 3, 3>::new(1.0, 2.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, 1.0),
            "indefinite",
        );
        reject(-spd, "negative definite");
        // Singular: rank 1 (second pivot exactly 0), and the zero matrix.
        reject(SMatrix::<f64, 3, 3>::from_element(1.0), "rank one");
        reject(SMatrix::<f64, 3, 3>::zeros(), "zero");
        // Near singular: positive pivots, ratio 1e-14 ≤ SINGULAR_PIVOT.
        reject(
            SMatrix::<f64, 3, 3>::from_diagonal(&SVector::<f64, 3>::new(1.0, 1.0, 1e-14)),
            "ratio 1e-14",
        );
        // Non-finite: NaN on the diagonal and in the lower triangle (only the lower triangle is read),
        // ±∞ on the diagonal and off it, and NaN everywhere.
        for (i, j, v) in [
            (1, 1, f64::NAN),
            (2, 0, f64::NAN),
            (2, 1, f64::NAN),
            (1, 0, f64::INFINITY),
            (2, 1, f64::NEG_INFINITY),
            (0, 0, f64::INFINITY),
            (2, 2, f64::INFINITY),
        ] {
            let mut m = spd;
            m[(i, j)] = v;
            reject(m, &format!("{v} at ({i}, {j})"));
        }
        reject(SMatrix::<f64, 3, 3>::from_element(f64::NAN), "all NaN");
        // The threshold is that of DenseFactor::symmetric: diag(1, 1, r) on either side of it.
        for r in [1e-12, 2e-13, 1e-13, 5e-14] {
            let m = SMatrix::<f64, 3, 3>::from_diagonal(&SVector::<f64, 3>::new(1.0, 1.0, r));
            let mut b = b0;
            let dense = DenseFactor::symmetric(DMatrix::from_column_slice(3, 3, m.as_slice()));
            assert_eq!(solve_positive_fixed(m, &mut b), dense.is_ok(), "r = {r:e}");
        }
    }
}
