//! Higher order by symmetric composition of a symmetric second-order discrete flow:
//!
//! ```text
//! Ψ_h = Φ_{γ_s h} ∘ … ∘ Φ_{γ_1 h},      Σ γ_i = 1,  γ_i = γ_{s+1−i}.
//! ```
//!
//! Each Φ is the discrete Hamiltonian map of L_d(·, ·, γ_i h); the composition is the map of the composed
//! discrete Lagrangian `ext_{q¹…q^{s−1}} Σ_i L_d(q^{i−1}, q^i, γ_i h)` and so is still variational and
//! symplectic, with the same discrete Noether momenta.
//!
//! - [`Composition::order4`]: Yoshida's triple jump γ = (a, 1 − 2a, a), a = 1/(2 − 2^{1/3}) (3 stages).
//! - [`Composition::order6`]: the triple jump applied to the order-4 method, b = 1/(2 − 2^{1/5})
//!   (9 stages).
//!
//! # References
//! H. Yoshida, *Construction of higher order symplectic integrators*, Phys. Lett. A 150 (1990) 262-268;
//! E. Hairer, C. Lubich, G. Wanner, *Geometric Numerical Integration*, 2nd ed., §II.4 and §V.3.

use crate::flow::{check_flow_args, stepper_via_flow, DiscreteFlow};
use noether_core::{Error, Result};

/// A symmetric composition of a discrete flow (see the module docs).
pub struct Composition<F> {
    flow: F,
    gammas: Vec<f64>,
    order: u32,
    q: Vec<f64>,
    p: Vec<f64>,
}

/// The triple-jump weights (a, 1 − 2a, a) with a = 1/(2 − 2^{1/(p+1)}) raising a symmetric method of
/// even order p to order p + 2.
pub fn triple_jump(p: u32) -> [f64; 3] {
    let a = 1.0 / (2.0 - 2f64.powf(1.0 / (p as f64 + 1.0)));
    [a, 1.0 - 2.0 * a, a]
}

impl<F: DiscreteFlow> Composition<F> {
    /// The composition of `flow` with the given substep weights and nominal order. The weights must
    /// be finite, non-zero, sum to 1 and be palindromic (a symmetric method).
    pub fn new(flow: F, gammas: Vec<f64>, order: u32) -> Result<Self> {
        let sum: f64 = gammas.iter().sum();
        if gammas.is_empty() || gammas.iter().any(|g| !g.is_finite() || *g == 0.0) {
            return Err(Error::InvalidParameter {
                name: "composition weights",
                value: f64::NAN,
                reason: "need at least one finite, non-zero weight",
            });
        }
        if (sum - 1.0).abs() > 1e-12 {
            return Err(Error::InvalidParameter {
                name: "sum of composition weights",
                value: sum,
                reason: "must be 1",
            });
        }
        let s = gammas.len();
        if (0..s).any(|i| (gammas[i] - gammas[s - 1 - i]).abs() > 1e-14) {
            return Err(Error::InvalidParameter {
                name: "composition weights",
                value: f64::NAN,
                reason: "must be palindromic (symmetric composition)",
            });
        }
        let n = flow.dof();
        Ok(Composition {
            flow,
            gammas,
            order,
            q: vec![0.0; n],
            p: vec![0.0; n],
        })
    }

    /// Order 4 from a symmetric order-2 flow (Yoshida's triple jump, 3 stages).
    pub fn order4(flow: F) -> Self {
        Self::check_base(&flow, 2);
        Composition::new(flow, triple_jump(2).to_vec(), 4).expect("triple jump weights are valid")
    }

    /// Order 6 from a symmetric order-2 flow (triple jump of the triple jump, 9 stages).
    pub fn order6(flow: F) -> Self {
        Self::check_base(&flow, 2);
        let (a, b) = (triple_jump(2), triple_jump(4));
        let g: Vec<f64> = b.iter().flat_map(|bi| a.iter().map(move |ai| ai * bi)).collect();
        Composition::new(flow, g, 6).expect("triple jump weights are valid")
    }

    fn check_base(flow: &F, order: u32) {
        debug_assert_eq!(flow.order(), order, "compose a symmetric flow of order {order}");
    }

    /// The substep weights γ_i.
    pub fn weights(&self) -> &[f64] {
        &self.gammas
    }

    /// The composed flow.
    pub fn inner(&self) -> &F {
        &self.flow
    }

    /// The composed flow, mutably (e.g. to read its last Newton statistics).
    pub fn inner_mut(&mut self) -> &mut F {
        &mut self.flow
    }
}

impl<F: DiscreteFlow> DiscreteFlow for Composition<F> {
    fn dof(&self) -> usize {
        self.flow.dof()
    }
    fn order(&self) -> u32 {
        self.order
    }
    fn rates(&self, t: f64, q: &[f64], p: &[f64], dq: &mut [f64], dp: &mut [f64]) -> Option<Result<()>> {
        self.inner().rates(t, q, p, dq, dp)
    }
    fn name(&self) -> &'static str {
        "symmetric composition"
    }
    fn flow(&mut self, t: f64, h: f64, q: &mut [f64], p: &mut [f64]) -> Result<usize> {
        check_flow_args(self.flow.dof(), t, h, q, p)?;
        self.q.copy_from_slice(q);
        self.p.copy_from_slice(p);
        let mut tau = t;
        let mut iterations = 0;
        for &g in &self.gammas {
            iterations += self.flow.flow(tau, g * h, &mut self.q, &mut self.p)?;
            tau += g * h;
        }
        q.copy_from_slice(&self.q);
        p.copy_from_slice(&self.p);
        Ok(iterations)
    }
}

stepper_via_flow!(Composition<F: DiscreteFlow>);
