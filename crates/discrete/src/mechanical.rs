//! Mechanical systems L = ½ q̇ᵀMq̇ − V(q) with a constant mass matrix and a potential that is a sum of
//! local terms, V(q) = Σ_k V_k(q restricted to the support of term k), with optional linear (Rayleigh)
//! damping Q = −C q̇, C = diag(c).
//!
//! This is the structure the fast variational steppers exploit ([`crate::MechanicalMidpoint`],
//! [`crate::Verlet`]): M is factored once; each term is differentiated on its own with a tiny
//! stack-allocated dual number (a spring or a pair: 2 variables) and scattered into ∇V and a sparse
//! (banded or dense) ∇²V, so a chain of N masses costs O(N) per evaluation. A `Mechanical` is also a
//! plain [`Lagrangian`], usable with every other method of noether.
//!
//! ```
//! use noether_core::Scalar;
//! use noether_discrete::mechanical::{LocalPotential, Mass, Mechanical};
//!
//! /// A chain of n unit masses with nearest-neighbour springs (k = 1, rest length 0).
//! struct Springs { n: usize }
//! impl LocalPotential for Springs {
//!     fn dof(&self) -> usize { self.n }
//!     fn terms(&self) -> usize { self.n - 1 }
//!     fn support(&self, k: usize, idx: &mut Vec<usize>) { idx.extend([k, k + 1]) }
//!     fn term<D: Scalar>(&self, _k: usize, x: &[D]) -> D { (x[1] - x[0]) * (x[1] - x[0]) * 0.5 }
//! }
//!
//! let sys = Mechanical::new(Mass::Diagonal(vec![1.0; 4]), Springs { n: 4 }).unwrap();
//! assert_eq!(sys.bandwidth(), 1);
//! let mut g = [0.0; 4];
//! sys.gradient(&[0.0, 1.0, 1.0, 3.0], &mut g);
//! assert_eq!(g, [-1.0, 1.0, -2.0, 2.0]); // ∂V/∂q_i = (q_i − q_{i−1}) − (q_{i+1} − q_i)
//! ```

use nalgebra::DMatrix;
use nalgebra::{Const, U1};
use noether_core::ad::{self, Block, Field};
use noether_core::error::{check_finite, check_len};
use noether_core::linalg::{self, Banded, DenseFactor};
use noether_core::{Error, Lagrangian, Result, Scalar};
use num_dual::{Dual2Vec, DualVec};

/// Gradient of a two-variable term by one `DualVec<2>` evaluation (the common case: springs, pairs).
#[inline]
fn grad2<P: LocalPotential>(p: &P, k: usize, x: [f64; 2]) -> (f64, [f64; 2]) {
    type D = DualVec<f64, f64, Const<2>>;
    let xs = [D::from_re(x[0]).derivative(0), D::from_re(x[1]).derivative(1)];
    let r = p.term(k, &xs);
    let g = r.eps.unwrap_generic(Const::<2>, U1);
    (r.re, [g[0], g[1]])
}

/// Hessian of a two-variable term by one `Dual2Vec<2>` evaluation.
#[inline]
fn hess2<P: LocalPotential>(p: &P, k: usize, x: [f64; 2]) -> [[f64; 2]; 2] {
    type D = Dual2Vec<f64, f64, Const<2>>;
    let xs = [D::from_re(x[0]).derivative(0), D::from_re(x[1]).derivative(1)];
    let h = p.term(k, &xs).v2.unwrap_generic(Const::<2>, Const::<2>);
    [[h[(0, 0)], h[(0, 1)]], [h[(1, 0)], h[(1, 1)]]]
}

/// A potential that is a sum of terms, each depending on a few coordinates (its support).
pub trait LocalPotential {
    /// Number of coordinates.
    fn dof(&self) -> usize;
    /// Number of terms.
    fn terms(&self) -> usize;
    /// Appends the coordinate indices term `k` depends on to `idx` (called once per term, at
    /// construction of a [`Mechanical`]).
    fn support(&self, k: usize, idx: &mut Vec<usize>);
    /// The value of term `k` at `x`, the values of its support coordinates in the order given by
    /// [`support`](Self::support).
    ///
    /// Mark it `#[inline]`: inlined into the gradient kernel, the dual arithmetic of a small term stays
    /// in registers and unused derivative parts are optimised away (for the coupled chains this halved
    /// the time of a gradient).
    fn term<D: Scalar>(&self, k: usize, x: &[D]) -> D;
}

/// A constant mass matrix.
#[derive(Debug, Clone, PartialEq)]
pub enum Mass {
    /// M = diag(m).
    Diagonal(Vec<f64>),
    /// A full symmetric positive definite M.
    Dense(DMatrix<f64>),
}

/// One term of a [`LocalPotential`] as an AD field of its local coordinates.
struct TermField<'a, P> {
    potential: &'a P,
    k: usize,
}

impl<P: LocalPotential> Field for TermField<'_, P> {
    #[inline]
    fn eval<D: Scalar>(&self, _t: D, x: &[D], _y: &[D]) -> D {
        self.potential.term(self.k, x)
    }
}

/// Where a Hessian is assembled: a dense or a banded matrix.
pub trait Assemble {
    /// Adds `v` to entry (i, j).
    fn add(&mut self, i: usize, j: usize, v: f64);
}

impl Assemble for DMatrix<f64> {
    #[inline]
    fn add(&mut self, i: usize, j: usize, v: f64) {
        self[(i, j)] += v;
    }
}

impl Assemble for Banded {
    #[inline]
    fn add(&mut self, i: usize, j: usize, v: f64) {
        Banded::add(self, i, j, v)
    }
}

/// Checks the mass matrix of n degrees of freedom and factors a dense one: a diagonal M must have
/// length n, be finite, nonsingular and non-negative (so positive definite); a dense M must be n × n,
/// symmetric to 1e-14 of its largest entry, and positive definite (its Cholesky factor, returned).
fn factor_checked(mass: &Mass, n: usize) -> Result<Option<DenseFactor>> {
    match mass {
        Mass::Diagonal(m) => {
            check_len("diagonal mass", m, n)?;
            check_finite("diagonal mass", m)?;
            let pivot_ratio = linalg::diagonal_pivot_ratio(m);
            if linalg::is_singular(pivot_ratio) {
                return Err(Error::SingularMassMatrix { t: 0.0, pivot_ratio });
            }
            if m.iter().any(|v| *v < 0.0) {
                return Err(Error::InvalidParameter {
                    name: "diagonal mass",
                    value: m.iter().fold(f64::INFINITY, |a, v| a.min(*v)),
                    reason: "must be positive definite",
                });
            }
            Ok(None)
        }
        Mass::Dense(m) => {
            if m.shape() != (n, n) {
                return Err(Error::Dimension {
                    what: "mass matrix rows",
                    expected: n,
                    got: m.nrows(),
                });
            }
            if (m - m.transpose()).amax() > 1e-14 * m.amax() {
                return Err(Error::InvalidParameter {
                    name: "mass matrix asymmetry",
                    value: (m - m.transpose()).amax(),
                    reason: "M = ∂²L/∂q̇² must be symmetric",
                });
            }
            linalg::factor_positive_parameter(m.clone(), "mass matrix").map(Some)
        }
    }
}

/// The supports of the potential's terms, gathered: (offsets, indices) with term k's support at
/// `indices[offsets[k]..offsets[k + 1]]`, the largest support, and the largest index distance
/// within a support (the Hessian's bandwidth from the potential); an [`Error::Dimension`] for an
/// index ≥ n.
fn supports<P: LocalPotential>(potential: &P, n: usize) -> Result<(Vec<usize>, Vec<usize>, usize, usize)> {
    let mut offsets = Vec::with_capacity(potential.terms() + 1);
    let mut indices = Vec::new();
    offsets.push(0);
    let (mut max_support, mut bandwidth) = (0, 0);
    for k in 0..potential.terms() {
        let start = indices.len();
        potential.support(k, &mut indices);
        let s = &indices[start..];
        if let Some(&bad) = s.iter().find(|&&i| i >= n) {
            return Err(Error::Dimension {
                what: "support index of a potential term (must be < dof)",
                expected: n,
                got: bad,
            });
        }
        if let (Some(lo), Some(hi)) = (s.iter().min(), s.iter().max()) {
            bandwidth = bandwidth.max(hi - lo);
        }
        max_support = max_support.max(s.len());
        offsets.push(indices.len());
    }
    Ok((offsets, indices, max_support, bandwidth))
}

/// The bandwidth of a square matrix: the largest |i − j| of a nonzero entry (0 for none).
fn matrix_bandwidth(m: &DMatrix<f64>) -> usize {
    let n = m.nrows();
    let mut bandwidth = 0;
    for j in 0..n {
        for i in 0..n {
            if m[(i, j)] != 0.0 {
                bandwidth = bandwidth.max(i.abs_diff(j));
            }
        }
    }
    bandwidth
}

/// L = ½ q̇ᵀMq̇ − Σ_k V_k(q) − with optional damping (see the module docs).
pub struct Mechanical<P> {
    mass: Mass,
    factor: Option<DenseFactor>,
    potential: P,
    damping: Option<Vec<f64>>,
    offsets: Vec<usize>,
    indices: Vec<usize>,
    max_support: usize,
    bandwidth: usize,
}

impl<P: LocalPotential> Mechanical<P> {
    /// The system with mass matrix `mass` and potential `potential`. Checks the dimensions, that M is
    /// finite, symmetric and positive definite (factored here, once), and that every support index is
    /// in range.
    pub fn new(mass: Mass, potential: P) -> Result<Self> {
        let n = potential.dof();
        let factor = factor_checked(&mass, n)?;
        let (offsets, indices, max_support, mut bandwidth) = supports(&potential, n)?;
        if let Mass::Dense(m) = &mass {
            bandwidth = bandwidth.max(matrix_bandwidth(m));
        }
        Ok(Mechanical {
            mass,
            factor,
            potential,
            damping: None,
            offsets,
            indices,
            max_support,
            bandwidth,
        })
    }

    /// Adds linear damping Q = −diag(c) q̇ (each c_i finite and ≥ 0): a Rayleigh dissipation function
    /// ½ q̇ᵀ diag(c) q̇.
    pub fn damping(mut self, c: Vec<f64>) -> Result<Self> {
        check_len("damping", &c, self.dof())?;
        check_finite("damping", &c)?;
        if let Some(bad) = c.iter().find(|v| **v < 0.0) {
            return Err(Error::InvalidParameter {
                name: "damping coefficient",
                value: *bad,
                reason: "must be ≥ 0 (negative damping feeds energy in)",
            });
        }
        self.damping = Some(c);
        Ok(self)
    }

    /// Number of coordinates.
    pub fn dof(&self) -> usize {
        self.potential.dof()
    }

    /// The potential.
    pub fn potential(&self) -> &P {
        &self.potential
    }

    /// The mass matrix.
    pub fn mass(&self) -> &Mass {
        &self.mass
    }

    /// The damping coefficients, if any.
    pub fn get_damping(&self) -> Option<&[f64]> {
        self.damping.as_deref()
    }

    /// Half-bandwidth of ∇²V + M: the largest |i − j| coupled by a term or by M.
    pub fn bandwidth(&self) -> usize {
        self.bandwidth
    }

    /// Largest number of coordinates of one term.
    pub fn max_support(&self) -> usize {
        self.max_support
    }

    /// The support of term k.
    pub fn support(&self, k: usize) -> &[usize] {
        &self.indices[self.offsets[k]..self.offsets[k + 1]]
    }

    /// out = M v.
    pub fn mass_mul(&self, v: &[f64], out: &mut [f64]) {
        match &self.mass {
            Mass::Diagonal(m) => out
                .iter_mut()
                .zip(m.iter().zip(v))
                .for_each(|(o, (a, b))| *o = a * b),
            Mass::Dense(m) => {
                let r = m * nalgebra::DVectorView::from_slice(v, v.len());
                out.copy_from_slice(r.as_slice());
            }
        }
    }

    /// Overwrites `b` with M⁻¹ b (M factored once).
    pub fn mass_solve(&self, b: &mut [f64]) {
        match (&self.mass, &self.factor) {
            (Mass::Diagonal(m), _) => b.iter_mut().zip(m).for_each(|(x, mi)| *x /= mi),
            (Mass::Dense(_), Some(f)) => f.solve_in_place(b),
            (Mass::Dense(_), None) => unreachable!("a dense mass is factored at construction"),
        }
    }

    /// V(q).
    pub fn potential_energy(&self, q: &[f64]) -> f64 {
        let mut x = Vec::with_capacity(self.max_support);
        (0..self.potential.terms())
            .map(|k| {
                x.clear();
                x.extend(self.support(k).iter().map(|&i| q[i]));
                self.potential.term(k, &x)
            })
            .sum()
    }

    /// ∇V(q) into `out`; returns V(q).
    pub fn gradient(&self, q: &[f64], out: &mut [f64]) -> f64 {
        out.iter_mut().for_each(|g| *g = 0.0);
        let (mut x, mut g) = (vec![0.0; self.max_support], vec![0.0; self.max_support]);
        let mut v = 0.0;
        for k in 0..self.potential.terms() {
            let s = self.support(k);
            let m = s.len();
            if m == 2 {
                let (val, gk) = grad2(&self.potential, k, [q[s[0]], q[s[1]]]);
                v += val;
                out[s[0]] += gk[0];
                out[s[1]] += gk[1];
                continue;
            }
            for (xi, &i) in x.iter_mut().zip(s) {
                *xi = q[i];
            }
            let f = TermField {
                potential: &self.potential,
                k,
            };
            v += ad::gradient(&f, 0.0, &x[..m], &[], Block::X, &mut g[..m]);
            for (gi, &i) in g.iter().zip(s) {
                out[i] += gi;
            }
        }
        v
    }

    /// Adds `scale`·∇²V(q) to `out` (dense or banded), term by term.
    pub fn add_hessian<A: Assemble>(&self, q: &[f64], scale: f64, out: &mut A) {
        let mut x = vec![0.0; self.max_support];
        let mut blocks: Vec<DMatrix<f64>> = (0..=self.max_support).map(|m| DMatrix::zeros(m, m)).collect();
        for k in 0..self.potential.terms() {
            let s = self.support(k);
            let m = s.len();
            if m == 2 {
                let hk = hess2(&self.potential, k, [q[s[0]], q[s[1]]]);
                for (a, &i) in s.iter().enumerate() {
                    for (b, &j) in s.iter().enumerate() {
                        out.add(i, j, scale * hk[a][b]);
                    }
                }
                continue;
            }
            for (xi, &i) in x.iter_mut().zip(s) {
                *xi = q[i];
            }
            let f = TermField {
                potential: &self.potential,
                k,
            };
            let hk = &mut blocks[m];
            ad::hessian(&f, 0.0, &x[..m], &[], Block::X, Block::X, hk);
            for (a, &i) in s.iter().enumerate() {
                for (b, &j) in s.iter().enumerate() {
                    out.add(i, j, scale * hk[(a, b)]);
                }
            }
        }
    }

    /// Adds `scale`·M to `out`.
    pub fn add_mass<A: Assemble>(&self, scale: f64, out: &mut A) {
        match &self.mass {
            Mass::Diagonal(m) => m.iter().enumerate().for_each(|(i, mi)| out.add(i, i, scale * mi)),
            Mass::Dense(m) => {
                for j in 0..m.ncols() {
                    for i in 0..m.nrows() {
                        if m[(i, j)] != 0.0 {
                            out.add(i, j, scale * m[(i, j)]);
                        }
                    }
                }
            }
        }
    }

    /// Hamilton's vector field with the damping force: q̇ = M⁻¹p, ṗ = −∇V(q) − diag(c) q̇.
    pub fn hamilton_rates(&self, q: &[f64], p: &[f64], dq: &mut [f64], dp: &mut [f64]) {
        dq.copy_from_slice(p);
        self.mass_solve(dq);
        self.gradient(q, dp);
        dp.iter_mut().for_each(|g| *g = -*g);
        if let Some(c) = self.get_damping() {
            dp.iter_mut()
                .zip(c)
                .zip(dq.iter())
                .for_each(|((f, ci), v)| *f -= ci * v);
        }
    }

    /// The energy H(q, p) = ½ pᵀM⁻¹p + V(q) of a position-momentum state.
    pub fn energy(&self, q: &[f64], p: &[f64]) -> f64 {
        self.kinetic_energy(p) + self.potential_energy(q)
    }

    /// The kinetic energy ½ pᵀM⁻¹p.
    pub fn kinetic_energy(&self, p: &[f64]) -> f64 {
        let mut v = p.to_vec();
        self.mass_solve(&mut v);
        0.5 * v.iter().zip(p).map(|(a, b)| a * b).sum::<f64>()
    }
}

impl<P: LocalPotential> Lagrangian for Mechanical<P> {
    fn dof(&self) -> usize {
        self.potential.dof()
    }

    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let mut t = D::zero();
        match &self.mass {
            Mass::Diagonal(m) => {
                for (vi, mi) in v.iter().zip(m) {
                    t += *vi * *vi * (0.5 * mi);
                }
            }
            Mass::Dense(m) => {
                for j in 0..m.ncols() {
                    for i in 0..m.nrows() {
                        if m[(i, j)] != 0.0 {
                            t += v[i] * v[j] * (0.5 * m[(i, j)]);
                        }
                    }
                }
            }
        }
        let mut x: Vec<D> = Vec::with_capacity(self.max_support);
        let mut pot = D::zero();
        for k in 0..self.potential.terms() {
            x.clear();
            x.extend(self.support(k).iter().map(|&i| q[i]));
            pot += self.potential.term(k, &x);
        }
        t - pot
    }

    fn constant_mass_matrix(&self) -> bool {
        true
    }

    fn has_generalized_force(&self) -> bool {
        self.damping.is_some()
    }

    fn generalized_force<D: Scalar>(&self, _t: D, _q: &[D], v: &[D], out: &mut [D]) {
        match &self.damping {
            Some(c) => out
                .iter_mut()
                .zip(c.iter().zip(v))
                .for_each(|(o, (ci, vi))| *o = *vi * (-ci)),
            None => out.iter_mut().for_each(|o| *o = D::zero()),
        }
    }
}

/// Hamilton's equations of a [`Mechanical`] system in position-momentum form,
/// q̇ = M⁻¹p, ṗ = −∇V(q) − diag(c) M⁻¹p ([`Mechanical::hamilton_rates`]): every core integrator
/// steps a `State<Momenta>` of it.
impl<P: LocalPotential> noether_core::Dynamics for Mechanical<P> {
    type Partner = noether_core::Momenta;
    fn dof(&self) -> usize {
        Mechanical::dof(self)
    }
    fn rates(&self, _t: f64, q: &[f64], p: &[f64], dq: &mut [f64], dp: &mut [f64]) -> Result<()> {
        self.hamilton_rates(q, p, dq, dp);
        Ok(())
    }
    fn energy(&self, _t: f64, q: &[f64], p: &[f64]) -> Result<f64> {
        Ok(Mechanical::energy(self, q, p))
    }
}

/// Without damping, the split q̇ = D(p) = M⁻¹p, ṗ = K(q) = −∇V(q) of core's explicit symplectic
/// methods: [`Verlet`](crate::Verlet) of an undamped system is core's
/// [`StormerVerlet`](noether_core::integrators::StormerVerlet) on it. A damped system has no such
/// split (its force depends on p): the kick refuses it.
impl<P: LocalPotential> noether_core::integrators::SplitDynamics for Mechanical<P> {
    fn drift_rate(&self, p: &[f64], dq: &mut [f64]) -> Result<()> {
        dq.copy_from_slice(p);
        self.mass_solve(dq);
        Ok(())
    }
    fn kick_rate(&self, q: &[f64], dp: &mut [f64]) -> Result<()> {
        if self.get_damping().is_some() {
            return Err(Error::Unsupported(
                "a split (kick-drift) method on a damped Mechanical system: the damping force depends on p; use Verlet or MechanicalMidpoint",
            ));
        }
        self.gradient(q, dp);
        dp.iter_mut().for_each(|g| *g = -*g);
        Ok(())
    }
}
