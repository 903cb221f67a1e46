//! The boundary-value problem of a whole path as one banded Newton system (the discrete
//! Euler-Lagrange equations at the interior nodes, with the path constraint's multipliers), its
//! solve, and the Jacobi operator's conjugate-point test (see the [module](super) docs).

use super::{
    BoundaryValue, Component, ConjugatePoint, DiscreteField, DiscretePath, PathConstraint, Weighted,
};
use crate::lagrangian::{DiscreteDerivatives, DiscreteLagrangian, StepEnd};
use nalgebra::{DMatrix, DVector};
use noether_core::ad::{self, Block};
use noether_core::error::{check_finite, check_len};
use noether_core::linalg::{Banded, BandedLu, DenseFactor};
use noether_core::{Error, NewtonInfo, NewtonSystem, Result};

impl<Ld: DiscreteLagrangian> BoundaryValue<Ld> {
    /// The stationary path from the guess `nodes` (ends kept) under the constraint `c`, by Newton on
    /// the whole-path system; an unconstrained path is then tested for conjugate points (its Morse
    /// index, the conjugate times and the margin recorded, [`ConjugatePoint`] when too close to one).
    /// With forces the path solves the discrete Lagrange-d'Alembert equations
    /// D₂L_d(q_{k−1}, q_k) + f⁺_{k−1} + D₁L_d(q_k, q_{k+1}) + f⁻_k = 0 instead: there is no action to
    /// be stationary, so no Morse index and no conjugate-point test.
    pub(super) fn solve_with<C: PathConstraint>(
        &self,
        c: &C,
        t0: f64,
        t1: f64,
        nodes: &[Vec<f64>],
    ) -> Result<DiscretePath> {
        let mut sys = System::new(&self.ld, c, t0, t1, nodes)?;
        let mut x = sys.initial_unknowns(nodes);
        let newton = self
            .newton
            .residual_floor(8.0 * f64::EPSILON * sys.momentum_scale(&x));
        // The conjugate-point test is that of the second variation of an action: unconstrained and
        // unforced paths only.
        let second_variation = c.count() == 0 && !self.ld.has_discrete_force();
        let info = match newton.solve(&mut sys, &mut x) {
            Ok(info) => info,
            Err(e) if second_variation => {
                // A singular or nearly singular Jacobi operator (Newton cannot reach the tolerance,
                // or its factorisation is refused) at the last iterate: a conjugate point.
                let j = sys.jacobi(&x);
                let margin = sys.margin(&x, j.mu);
                if self.near_conjugate(margin) {
                    return Err(self.conjugate_error(&sys, &j, margin).into());
                }
                return Err(e);
            }
            Err(e) => return Err(e),
        };
        sys.set_interior(&x);
        let mut path = sys.path(&x, info)?;
        if second_variation {
            let j = sys.jacobi(&x);
            let margin = sys.margin(&x, j.mu);
            path.morse_index = j.morse_index;
            path.conjugate_times = j.conjugate_times.iter().copied().filter(|&t| t < t1).collect();
            path.margin = margin;
            if self.near_conjugate(margin) {
                return Err(self.conjugate_error(&sys, &j, margin).into());
            }
        }
        Ok(path)
    }

    /// `true` when the margin is below the conjugate-point tolerance (or NaN).
    fn near_conjugate(&self, margin: f64) -> bool {
        margin.is_nan() || margin.abs() <= self.conjugate_tolerance
    }

    fn conjugate_error<C: PathConstraint>(
        &self,
        sys: &System<'_, Ld, C>,
        j: &JacobiInfo,
        margin: f64,
    ) -> ConjugatePoint {
        let t1 = sys.t0 + sys.h * sys.steps as f64;
        let nearest = j
            .conjugate_times
            .iter()
            .copied()
            .chain(j.end_root)
            .min_by(|a, b| (a - t1).abs().total_cmp(&(b - t1).abs()));
        let t = nearest.unwrap_or(f64::NAN);
        let passed = j.conjugate_times.iter().filter(|&&s| s < t).count();
        ConjugatePoint {
            t,
            t0: sys.t0,
            t1,
            margin: if margin.is_nan() { 0.0 } else { margin },
            tolerance: self.conjugate_tolerance,
            passed,
        }
    }
}

/// The discrete Euler-Lagrange equations of the whole path as one Newton system.
pub(super) struct System<'a, Ld, C> {
    ld: &'a Ld,
    c: &'a C,
    t0: f64,
    h: f64,
    steps: usize,
    n: usize,
    m: usize,
    /// All node positions q₀..q_N, one after the other (interior ones from the last `set_interior`).
    q: Vec<f64>,
    g1: Vec<f64>,
    g2: Vec<f64>,
    cval: Vec<f64>,
    gjac: DMatrix<f64>,
    d11: DMatrix<f64>,
    d22: DMatrix<f64>,
    d12: DMatrix<f64>,
    lhess: DMatrix<f64>,
    /// The discrete forces f⁻, f⁺ of a step and their derivatives in q_k (`df0`) and q_{k+1} (`df1`).
    fm: Vec<f64>,
    fp: Vec<f64>,
    df0: (DMatrix<f64>, DMatrix<f64>),
    df1: (DMatrix<f64>, DMatrix<f64>),
    lu: Option<BandedLu>,
}

/// Iteration cap of the inverse iteration for the smallest eigenvalue of the Jacobi operator (it
/// stops earlier once the eigenvalue has settled to 1e-12).
const INVERSE_ITERATIONS: usize = 200;

const JACOBIAN: &str = "discrete Jacobi operator (boundary-value Newton Jacobian)";

impl<'a, Ld: DiscreteLagrangian, C: PathConstraint> System<'a, Ld, C> {
    pub(super) fn new(ld: &'a Ld, c: &'a C, t0: f64, t1: f64, nodes: &[Vec<f64>]) -> Result<Self> {
        let n = ld.dof();
        let steps = nodes.len().saturating_sub(1);
        if steps < 2 {
            return Err(Error::InvalidParameter {
                name: "boundary-value steps",
                value: steps as f64,
                reason: "at least 2 steps (one interior node): give N + 1 ≥ 3 nodes",
            });
        }
        if !(t0.is_finite() && t1.is_finite() && t1 != t0) {
            return Err(Error::InvalidParameter {
                name: "boundary-value time interval t₁ − t₀",
                value: t1 - t0,
                reason: "t₀ and t₁ must be finite and distinct",
            });
        }
        let mut q = Vec::with_capacity((steps + 1) * n);
        for node in nodes {
            check_len("boundary-value node", node, n)?;
            check_finite("boundary-value node", node)?;
            q.extend_from_slice(node);
        }
        let m = c.count();
        Ok(System {
            ld,
            c,
            t0,
            h: (t1 - t0) / steps as f64,
            steps,
            n,
            m,
            q,
            g1: vec![0.0; n],
            g2: vec![0.0; n],
            cval: vec![0.0; m],
            gjac: DMatrix::zeros(m, n),
            d11: DMatrix::zeros(n, n),
            d22: DMatrix::zeros(n, n),
            d12: DMatrix::zeros(n, n),
            lhess: DMatrix::zeros(n, n),
            fm: vec![0.0; n],
            fp: vec![0.0; n],
            df0: (DMatrix::zeros(n, n), DMatrix::zeros(n, n)),
            df1: (DMatrix::zeros(n, n), DMatrix::zeros(n, n)),
            lu: None,
        })
    }

    /// Unknowns per interior node: q_k and λ_k.
    fn block(&self) -> usize {
        self.n + self.m
    }

    pub(super) fn initial_unknowns(&self, nodes: &[Vec<f64>]) -> Vec<f64> {
        let s = self.block();
        let mut x = vec![0.0; (self.steps - 1) * s];
        for k in 1..self.steps {
            x[(k - 1) * s..(k - 1) * s + self.n].copy_from_slice(&nodes[k]);
        }
        x
    }

    /// Copies the interior positions of the unknowns into the node array.
    pub(super) fn set_interior(&mut self, x: &[f64]) {
        let (n, s) = (self.n, self.block());
        for k in 1..self.steps {
            self.q[k * n..(k + 1) * n].copy_from_slice(&x[(k - 1) * s..(k - 1) * s + n]);
        }
    }

    fn node(&self, k: usize) -> &[f64] {
        &self.q[k * self.n..(k + 1) * self.n]
    }

    fn tk(&self, k: usize) -> f64 {
        self.t0 + k as f64 * self.h
    }

    /// max_k ‖D₁L_d(q_k, q_{k+1})‖∞ at the unknowns `x`: the scale of the residual's rounding.
    pub(super) fn momentum_scale(&mut self, x: &[f64]) -> f64 {
        self.set_interior(x);
        let mut scale = 0.0_f64;
        let mut g = vec![0.0; self.n];
        for k in 0..self.steps {
            self.ld
                .d1(self.tk(k), self.h, self.node(k), self.node(k + 1), &mut g);
            scale = scale.max(noether_core::newton::max_norm(&g));
        }
        scale
    }

    /// The discrete action at the current nodes.
    pub(super) fn action(&self) -> f64 {
        (0..self.steps)
            .map(|k| {
                let f = DiscreteField {
                    ld: self.ld,
                    t0: self.tk(k),
                };
                ad::value(&f, self.h, self.node(k), self.node(k + 1))
            })
            .sum()
    }

    /// The discrete forces f⁻, f⁺ of step k (from node k to node k + 1) into `fm`, `fp`.
    fn step_forces(&mut self, k: usize) {
        let n = self.n;
        let (q0, q1) = (&self.q[k * n..(k + 1) * n], &self.q[(k + 1) * n..(k + 2) * n]);
        self.ld
            .discrete_force(self.tk(k), self.h, q0, q1, &mut self.fm, &mut self.fp);
    }

    /// ∇g(q) (m × n) into `gjac`, g(q) into `cval`.
    fn constraint_jacobian(&mut self, k: usize) {
        let (n, m) = (self.n, self.m);
        let q = self.q[k * n..(k + 1) * n].to_vec();
        let mut row = vec![0.0; n];
        for i in 0..m {
            let f = Component { c: self.c, i };
            self.cval[i] = ad::gradient(&f, 0.0, &q, &[], Block::X, &mut row);
            for (j, r) in row.iter().enumerate() {
                self.gjac[(i, j)] = *r;
            }
        }
    }

    fn path(&mut self, x: &[f64], info: NewtonInfo) -> Result<DiscretePath> {
        let (n, s, steps) = (self.n, self.block(), self.steps);
        let mut p0 = vec![0.0; n];
        let mut p1 = vec![0.0; n];
        // p₀ = −D₁L_d(q₀, q₁) − f⁻₀ and p_N = D₂L_d(q_{N−1}, q_N) + f⁺_{N−1}.
        self.ld
            .d1(self.tk(0), self.h, self.node(0), self.node(1), &mut p0);
        self.ld.d2(
            self.tk(steps - 1),
            self.h,
            self.node(steps - 1),
            self.node(steps),
            &mut p1,
        );
        if self.ld.has_discrete_force() {
            self.step_forces(0);
            p0.iter_mut().zip(&self.fm).for_each(|(p, f)| *p += f);
            self.step_forces(steps - 1);
            p1.iter_mut().zip(&self.fp).for_each(|(p, f)| *p += f);
        }
        p0.iter_mut().for_each(|p| *p = -*p);
        let action = self.action();
        check_finite("end momenta of the boundary-value path", &p0)?;
        check_finite("end momenta of the boundary-value path", &p1)?;
        let multipliers = if self.m == 0 {
            Vec::new()
        } else {
            (1..steps)
                .map(|k| DVector::from_column_slice(&x[(k - 1) * s + n..k * s]))
                .collect()
        };
        Ok(DiscretePath {
            t: (0..=steps).map(|k| self.tk(k)).collect(),
            q: (0..=steps)
                .map(|k| DVector::from_column_slice(self.node(k)))
                .collect(),
            multipliers,
            p0: DVector::from_vec(p0),
            p1: DVector::from_vec(p1),
            action,
            newton: info,
            morse_index: None,
            conjugate_times: Vec::new(),
            margin: f64::NAN,
        })
    }

    /// The blocks A_k (k = 1..N−1) and B_k = D₁₂L_d(q_k, q_{k+1}) (k = 0..N−1) of the Jacobi operator
    /// at the current nodes.
    fn jacobi_blocks(&mut self) -> (Vec<DMatrix<f64>>, Vec<DMatrix<f64>>) {
        let (n, steps, h) = (self.n, self.steps, self.h);
        let mut a = vec![DMatrix::zeros(n, n); steps + 1];
        let mut b = Vec::with_capacity(steps);
        for k in 0..steps {
            let (q0, q1) = (self.node(k).to_vec(), self.node(k + 1).to_vec());
            self.ld.d11(self.tk(k), h, &q0, &q1, &mut self.d11);
            self.ld.d22(self.tk(k), h, &q0, &q1, &mut self.d22);
            self.ld.d12(self.tk(k), h, &q0, &q1, &mut self.d12);
            a[k] += &self.d11;
            a[k + 1] += &self.d22;
            b.push(self.d12.clone());
        }
        (a, b)
    }

    /// Morse index and conjugate times of the (unconstrained) Jacobi operator at the nodes of `x`.
    fn jacobi(&mut self, x: &[f64]) -> JacobiInfo {
        self.set_interior(x);
        let (a, b) = self.jacobi_blocks();
        let (n, steps) = (self.n, self.steps);
        // Inertia of the block LDLᵀ: D₁ = A₁, D_k = A_k − B_{k−1}ᵀ D_{k−1}⁻¹ B_{k−1}.
        let mut morse = Some(0usize);
        let mut d: Option<DMatrix<f64>> = None;
        for k in 1..steps {
            let mut dk = a[k].clone();
            if let Some(prev) = &d {
                match DenseFactor::lu(prev.clone()) {
                    Ok(f) => dk -= b[k - 1].transpose() * f.solve_matrix(&b[k - 1]),
                    Err(_) => {
                        morse = None;
                        break;
                    }
                }
            }
            let sym = (&dk + dk.transpose()) * 0.5;
            let neg = sym.symmetric_eigenvalues().iter().filter(|&&l| l < 0.0).count();
            morse = morse.map(|m| m + neg);
            d = Some(dk);
        }
        // Matrix Jacobi field J₀ = 0, J₁ = I: B_{k−1}ᵀ J_{k−1} + A_k J_k + B_k J_{k+1} = 0.
        let mut conjugate_times = Vec::new();
        let mut jm = DMatrix::<f64>::zeros(n, n);
        let mut j = DMatrix::<f64>::identity(n, n);
        let mut end_root = None;
        for k in 1..steps {
            let rhs = -(&a[k] * &j + b[k - 1].transpose() * &jm);
            let Ok(next) = DenseFactor::lu(b[k].clone()).map(|f| f.solve_matrix(&rhs)) else {
                break;
            };
            let (dk, dn) = (j.determinant(), next.determinant());
            if dk != 0.0 && (dn == 0.0 || dk.signum() != dn.signum()) {
                conjugate_times.push(self.tk(k) + self.h * dk / (dk - dn));
            } else if k + 1 == steps && dk != dn {
                // No zero in the last step: the zero of the secant through it, when it falls within
                // one step beyond t₁ (a conjugate point just after the end).
                let t = self.tk(k) + self.h * dk / (dk - dn);
                if t > self.tk(k + 1) && t <= self.tk(k + 1) + self.h {
                    end_root = Some(t);
                }
            }
            let s = next.amax().max(j.amax());
            if !(s.is_finite() && s > 0.0) {
                break;
            }
            jm = j / s;
            j = next / s;
        }
        // μ: the smallest eigenvalue of the diagonal blocks (the largest magnitude if none is positive).
        let eig: Vec<f64> = (1..steps)
            .flat_map(|k| {
                ((&a[k] + a[k].transpose()) * 0.5)
                    .symmetric_eigenvalues()
                    .as_slice()
                    .to_vec()
            })
            .collect();
        let pos = eig
            .iter()
            .copied()
            .filter(|&l| l > 0.0)
            .fold(f64::INFINITY, f64::min);
        let mu = if pos.is_finite() {
            pos
        } else {
            eig.iter().fold(0.0_f64, |m, l| m.max(l.abs()))
        };
        JacobiInfo {
            morse_index: morse,
            conjugate_times,
            end_root,
            mu,
        }
    }

    /// The conjugate-point margin (module docs) of the Jacobi operator H at `x`: its smallest-magnitude
    /// eigenvalue (signed, by inverse iteration on the banded factor) over the one of a free particle
    /// with the same diagonal blocks, 2 sin²(π/2N) μ, μ the smallest eigenvalue of the diagonal blocks
    /// A_k (for L_d = ½ (q₁ − q₀)ᵀM(q₁ − q₀)/h, H = tridiag(−M, 2M, −M)/h and the margin is exactly 1).
    /// 0 when H cannot be factored.
    fn margin(&mut self, x: &[f64], mu: f64) -> f64 {
        if self.factor_jacobian(x).is_err() {
            return 0.0;
        }
        let Some(lu) = self.lu.as_ref() else {
            return 0.0;
        };
        let dim = (self.steps - 1) * self.block();
        let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
        // A deterministic start with every mode present.
        let mut v: Vec<f64> = (0..dim).map(|i| 1.0 + 0.1 * ((i * 7919) % 13) as f64).collect();
        let mut small = f64::NAN;
        for _ in 0..INVERSE_ITERATIONS {
            let nv = norm(&v);
            v.iter_mut().for_each(|a| *a /= nv);
            let mut w = v.clone();
            lu.solve(&mut w);
            // Rayleigh quotient of H⁻¹: 1/λ, with its sign.
            let r: f64 = v.iter().zip(&w).map(|(a, b)| a * b).sum();
            let next = 1.0 / r;
            let done = (next - small).abs() <= 1e-12 * next.abs();
            small = next;
            v = w;
            if done {
                break;
            }
        }
        let free = 2.0 * (std::f64::consts::PI / (2.0 * self.steps as f64)).sin().powi(2) * mu;
        small / free
    }

    /// The banded Jacobian at `x`.
    fn assemble(&mut self, x: &[f64]) -> Banded {
        self.set_interior(x);
        let (n, m, s, steps, h) = (self.n, self.m, self.block(), self.steps, self.h);
        let bw = 2 * s - 1;
        let mut jac = Banded::zeros((steps - 1) * s, bw, bw);
        for k in 0..steps {
            let (q0, q1) = (self.node(k).to_vec(), self.node(k + 1).to_vec());
            self.ld.d11(self.tk(k), h, &q0, &q1, &mut self.d11);
            self.ld.d22(self.tk(k), h, &q0, &q1, &mut self.d22);
            self.ld.d12(self.tk(k), h, &q0, &q1, &mut self.d12);
            if self.ld.has_discrete_force() {
                // f⁻ joins D₁L_d in the rows of node k, f⁺ joins D₂L_d in those of node k+1.
                let (t, ends) = (self.tk(k), (&q0[..], &q1[..]));
                let (m0, p0) = (&mut self.df0.0, &mut self.df0.1);
                self.ld.force_derivatives(t, h, ends, StepEnd::Left, (m0, p0));
                let (m1, p1) = (&mut self.df1.0, &mut self.df1.1);
                self.ld.force_derivatives(t, h, ends, StepEnd::Right, (m1, p1));
                self.d11 += &self.df0.0;
                self.d22 += &self.df1.1;
            }
            // Rows of node k get D₁₁ (and D₁₂ toward node k+1); rows of node k+1 get D₂₂ (and D₂₁);
            // with forces, ∂f⁻/∂q_{k+1} and ∂f⁺/∂q_k join the off-diagonal blocks.
            let forced = self.ld.has_discrete_force();
            let off = |i: usize, j: usize, d: &DMatrix<f64>, f: &DMatrix<f64>| {
                d[(i, j)] + if forced { f[(i, j)] } else { 0.0 }
            };
            for i in 0..n {
                for j in 0..n {
                    if k >= 1 {
                        let r = (k - 1) * s + i;
                        jac.add(r, (k - 1) * s + j, self.d11[(i, j)]);
                        if k + 1 < steps {
                            jac.add(r, k * s + j, off(i, j, &self.d12, &self.df1.0));
                        }
                    }
                    if k + 1 < steps {
                        let r = k * s + i;
                        jac.add(r, k * s + j, self.d22[(i, j)]);
                        if k >= 1 {
                            let d21 = self.d12[(j, i)];
                            jac.add(
                                r,
                                (k - 1) * s + j,
                                d21 + if forced { self.df0.1[(i, j)] } else { 0.0 },
                            );
                        }
                    }
                }
            }
        }
        if m > 0 {
            for k in 1..steps {
                self.constraint_jacobian(k);
                let base = (k - 1) * s;
                let lambda = x[base + n..base + s].to_vec();
                let f = Weighted {
                    c: self.c,
                    lambda: &lambda,
                };
                let q = self.node(k).to_vec();
                ad::hessian(&f, 0.0, &q, &[], Block::X, Block::X, &mut self.lhess);
                for i in 0..n {
                    for j in 0..n {
                        jac.add(base + i, base + j, self.lhess[(i, j)]);
                    }
                }
                for r in 0..m {
                    for j in 0..n {
                        let g = self.gjac[(r, j)];
                        jac.add(base + j, base + n + r, g);
                        jac.add(base + n + r, base + j, g);
                    }
                }
            }
        }
        jac
    }
}

struct JacobiInfo {
    morse_index: Option<usize>,
    conjugate_times: Vec<f64>,
    /// A zero of det J extrapolated within one step after t₁ (a conjugate point just beyond the end).
    end_root: Option<f64>,
    /// Smallest eigenvalue of the diagonal blocks A_k (module docs: the margin's scale).
    mu: f64,
}

impl<Ld: DiscreteLagrangian, C: PathConstraint> NewtonSystem for System<'_, Ld, C> {
    fn dim(&self) -> usize {
        (self.steps - 1) * self.block()
    }

    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Result<()> {
        self.set_interior(x);
        let (n, m, s, steps, h) = (self.n, self.m, self.block(), self.steps, self.h);
        r.iter_mut().for_each(|v| *v = 0.0);
        let forced = self.ld.has_discrete_force();
        for k in 0..steps {
            if forced {
                self.step_forces(k);
            }
            let (t, q0, q1) = (
                self.tk(k),
                &self.q[k * n..(k + 1) * n],
                &self.q[(k + 1) * n..(k + 2) * n],
            );
            if k >= 1 {
                self.ld.d1(t, h, q0, q1, &mut self.g1);
                if forced {
                    self.g1.iter_mut().zip(&self.fm).for_each(|(g, f)| *g += f);
                }
                let base = (k - 1) * s;
                r[base..base + n]
                    .iter_mut()
                    .zip(&self.g1)
                    .for_each(|(a, b)| *a += b);
            }
            if k + 1 < steps {
                self.ld.d2(t, h, q0, q1, &mut self.g2);
                if forced {
                    self.g2.iter_mut().zip(&self.fp).for_each(|(g, f)| *g += f);
                }
                let base = k * s;
                r[base..base + n]
                    .iter_mut()
                    .zip(&self.g2)
                    .for_each(|(a, b)| *a += b);
            }
        }
        if m > 0 {
            for k in 1..steps {
                self.constraint_jacobian(k);
                let base = (k - 1) * s;
                // D₂L_d + D₁L_d + ∇gᵀλ = 0 (stationary points of S_d + Σ_k λ_k·g(q_k)), g = 0.
                for j in 0..n {
                    let gl: f64 = (0..m).map(|i| self.gjac[(i, j)] * x[base + n + i]).sum();
                    r[base + j] += gl;
                }
                r[base + n..base + s].copy_from_slice(&self.cval);
            }
        }
        Ok(())
    }

    fn factor_jacobian(&mut self, x: &[f64]) -> Result<()> {
        self.lu = None;
        let jac = self.assemble(x);
        let lu = jac.factor().map_err(|e| e.in_matrix(JACOBIAN))?;
        self.lu = Some(lu);
        Ok(())
    }

    fn solve(&mut self, rhs: &mut [f64]) -> Result<()> {
        match &self.lu {
            Some(lu) => {
                lu.solve(rhs);
                Ok(())
            }
            None => Err(Error::SingularMatrix {
                what: JACOBIAN,
                pivot_ratio: f64::NAN,
            }),
        }
    }
}
