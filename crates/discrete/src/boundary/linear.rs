//! Boundary-value problems over a linear family of paths q_k = A_k y (loops, choreographies, the
//! fixed subspaces of symmetries): [`BoundaryValue::solve_linear`](super::BoundaryValue::solve_linear).

use super::{BoundaryValue, DiscreteField};
use crate::lagrangian::{DiscreteDerivatives, DiscreteLagrangian, StepEnd};
use nalgebra::{DMatrix, DVector};
use noether_core::ad;
use noether_core::error::check_finite;
use noether_core::{Error, NewtonInfo, Result};

/// A stationary path over a linear family of discrete paths q_k = A_k y ([`BoundaryValue::solve_linear`]).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct LinearPath {
    /// The parameters y.
    pub y: DVector<f64>,
    /// Node times t_k = t₀ + k h, k = 0..=N.
    pub t: Vec<f64>,
    /// Node positions q_k = A_k y.
    pub q: Vec<DVector<f64>>,
    /// The discrete action S_d(y) (of L_d alone, with forces).
    pub action: f64,
    /// Statistics of the Newton solve.
    pub newton: NewtonInfo,
    /// Number of negative eigenvalues of the reduced Hessian ∂²S_d/∂y² (0: a local minimum within the
    /// family). With forces, of the symmetric part of Newton's Jacobian (there is no action whose
    /// Hessian it would be).
    pub morse_index: usize,
    /// Its eigenvalues, ascending.
    pub hessian_eigenvalues: DVector<f64>,
}

impl<Ld: DiscreteLagrangian> BoundaryValue<Ld> {
    /// The stationary point of the discrete action over the linear family of paths q_k = A_k y,
    /// k = 0..=N (`maps` = [A₀, …, A_N], each dof × d), from t₀ to t₁, by Newton on
    /// ∇_y S_d = Σ_k A_kᵀ D₁L_d(q_k, q_{k+1}) + A_{k+1}ᵀ D₂L_d(q_k, q_{k+1}) = 0 from `y0`, with the
    /// dense Hessian Σ_k [A_k; A_{k+1}]ᵀ [D₁₁ D₁₂; D₂₁ D₂₂] [A_k; A_{k+1}] as Jacobian.
    ///
    /// The family encodes boundary conditions and symmetries: a loop (A_N = A₀), a loop up to an
    /// isometry (A_N = P A₀: a choreography, q(t + T/3) = P q(t)), or the fixed subspace of a
    /// symmetry group of S_d, whose stationary points are stationary for the full action (Palais'
    /// principle of symmetric criticality). Symmetries of S_d left in the family (a rotation of a
    /// loop) make the Hessian singular and must be removed by the family.
    ///
    /// With forces (the model's Q) the path solves the discrete Lagrange-d'Alembert equations over the
    /// family instead, Σ_k A_kᵀ (D₁L_d + f⁻_k) + A_{k+1}ᵀ (D₂L_d + f⁺_k) = 0, with the forces'
    /// derivatives in the Jacobian: a loop family then gives the periodic response of a driven,
    /// damped system.
    pub fn solve_linear(&self, t0: f64, t1: f64, maps: &[DMatrix<f64>], y0: &[f64]) -> Result<LinearPath> {
        let n = self.ld.dof();
        let d = y0.len();
        let steps = maps.len().saturating_sub(1);
        if steps < 1 {
            return Err(Error::InvalidParameter {
                name: "linear path maps",
                value: maps.len() as f64,
                reason: "at least two nodes (one step)",
            });
        }
        for a in maps {
            if a.nrows() != n || a.ncols() != d {
                return Err(Error::Dimension {
                    what: "linear path map A_k (dof × parameters)",
                    expected: n * d,
                    got: a.nrows() * a.ncols(),
                });
            }
        }
        check_finite("linear path parameters", y0)?;
        if !(t0.is_finite() && t1.is_finite() && t1 != t0) {
            return Err(Error::InvalidParameter {
                name: "time interval t₁ − t₀",
                value: t1 - t0,
                reason: "t₀ and t₁ must be finite and distinct",
            });
        }
        let h = (t1 - t0) / steps as f64;
        let problem = LinearFamily {
            ld: &self.ld,
            maps,
            t0,
            h,
        };
        let scale = problem.momentum_scale(y0);
        let newton = self
            .newton
            .residual_floor(8.0 * f64::EPSILON * scale * (d as f64).sqrt());
        let mut sys = noether_core::newton::Dense::new(problem);
        let mut y = y0.to_vec();
        let info = newton.solve(&mut sys, &mut y)?;
        let mut problem = sys.problem;
        let mut hess = DMatrix::zeros(d, d);
        noether_core::newton::DenseProblem::jacobian(&mut problem, &y, &mut hess)?;
        let sym = (&hess + hess.transpose()) * 0.5;
        let mut eig = sym.symmetric_eigenvalues();
        eig.as_mut_slice().sort_by(f64::total_cmp);
        let yv = DVector::from_vec(y);
        let q: Vec<DVector<f64>> = maps.iter().map(|a| a * &yv).collect();
        let action = (0..steps)
            .map(|k| {
                let f = DiscreteField {
                    ld: &self.ld,
                    t0: t0 + k as f64 * h,
                };
                ad::value(&f, h, q[k].as_slice(), q[k + 1].as_slice())
            })
            .sum();
        Ok(LinearPath {
            morse_index: eig.iter().filter(|&&l| l < 0.0).count(),
            hessian_eigenvalues: eig,
            y: yv,
            t: (0..=steps).map(|k| t0 + k as f64 * h).collect(),
            q,
            action,
            newton: info,
        })
    }
}

/// ∇_y S_d = 0 over q_k = A_k y as a dense Newton problem.
struct LinearFamily<'a, Ld> {
    ld: &'a Ld,
    maps: &'a [DMatrix<f64>],
    t0: f64,
    h: f64,
}

impl<Ld: DiscreteLagrangian> LinearFamily<'_, Ld> {
    fn nodes(&self, y: &[f64]) -> Vec<DVector<f64>> {
        let y = DVector::from_column_slice(y);
        self.maps.iter().map(|a| a * &y).collect()
    }

    fn momentum_scale(&self, y: &[f64]) -> f64 {
        let q = self.nodes(y);
        let mut g = vec![0.0; self.ld.dof()];
        let mut scale = 0.0_f64;
        for k in 0..q.len() - 1 {
            self.ld.d1(
                self.t0 + k as f64 * self.h,
                self.h,
                q[k].as_slice(),
                q[k + 1].as_slice(),
                &mut g,
            );
            scale = scale.max(noether_core::newton::max_norm(&g));
        }
        scale
    }
}

impl<Ld: DiscreteLagrangian> noether_core::newton::DenseProblem for LinearFamily<'_, Ld> {
    fn dim(&self) -> usize {
        self.maps.first().map_or(0, |a| a.ncols())
    }

    fn residual(&mut self, y: &[f64], r: &mut [f64]) -> Result<()> {
        let q = self.nodes(y);
        let n = self.ld.dof();
        let (mut g1, mut g2) = (DVector::zeros(n), DVector::zeros(n));
        let (mut fm, mut fp) = (DVector::zeros(n), DVector::zeros(n));
        let forced = self.ld.has_discrete_force();
        let mut acc = DVector::zeros(y.len());
        for k in 0..q.len() - 1 {
            let t = self.t0 + k as f64 * self.h;
            let (a, b) = (q[k].as_slice(), q[k + 1].as_slice());
            self.ld.d1(t, self.h, a, b, g1.as_mut_slice());
            self.ld.d2(t, self.h, a, b, g2.as_mut_slice());
            if forced {
                self.ld
                    .discrete_force(t, self.h, a, b, fm.as_mut_slice(), fp.as_mut_slice());
                g1 += &fm;
                g2 += &fp;
            }
            acc.gemv_tr(1.0, &self.maps[k], &g1, 1.0);
            acc.gemv_tr(1.0, &self.maps[k + 1], &g2, 1.0);
        }
        r.copy_from_slice(acc.as_slice());
        Ok(())
    }

    fn jacobian(&mut self, y: &[f64], j: &mut DMatrix<f64>) -> Result<()> {
        let q = self.nodes(y);
        let n = self.ld.dof();
        let (mut d11, mut d12, mut d22) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n), DMatrix::zeros(n, n));
        // ∂f⁻/∂q_k, ∂f⁺/∂q_k, ∂f⁻/∂q_{k+1}, ∂f⁺/∂q_{k+1} (zero without forces).
        let mut df: [DMatrix<f64>; 4] = std::array::from_fn(|_| DMatrix::zeros(n, n));
        j.fill(0.0);
        for k in 0..q.len() - 1 {
            let t = self.t0 + k as f64 * self.h;
            let (a, b) = (q[k].as_slice(), q[k + 1].as_slice());
            self.ld.d11(t, self.h, a, b, &mut d11);
            self.ld.d12(t, self.h, a, b, &mut d12);
            self.ld.d22(t, self.h, a, b, &mut d22);
            let [m0, p0, m1, p1] = &mut df;
            self.ld
                .force_derivatives(t, self.h, (a, b), StepEnd::Left, (m0, p0));
            self.ld
                .force_derivatives(t, self.h, (a, b), StepEnd::Right, (m1, p1));
            let (ak, an) = (&self.maps[k], &self.maps[k + 1]);
            // [A_k; A_{k+1}]ᵀ [D₁₁ + ∂f⁻/∂q_k, D₁₂ + ∂f⁻/∂q_{k+1}; D₂₁ + ∂f⁺/∂q_k, D₂₂ + ∂f⁺/∂q_{k+1}] [A_k; A_{k+1}].
            let upper = (&d11 + &df[0]) * ak + (&d12 + &df[2]) * an;
            let lower = (d12.transpose() + &df[1]) * ak + (&d22 + &df[3]) * an;
            j.gemm_tr(1.0, ak, &upper, 1.0);
            j.gemm_tr(1.0, an, &lower, 1.0);
        }
        if j.iter().any(|v| !v.is_finite()) {
            return Err(Error::NonFiniteResult {
                what: "Jacobian of the discrete equations over a linear family",
                t: self.t0,
                component: None,
            });
        }
        Ok(())
    }
}
