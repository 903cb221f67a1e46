//! Mass-spring chains as potentials of local terms: the two coupled chains of the momentum-transfer
//! paper (SEEDS part 3) and a single chain with a nonlinear on-site potential (the benchmark of O(N)
//! cost per step).
//!
//! ```
//! use noether_discrete::chains::CoupledChains;
//! use noether_discrete::{Mass, Mechanical, MechanicalMidpoint};
//! use noether_core::Stepper;
//!
//! let chains = CoupledChains::paper(0.001);
//! let q0 = chains.collision_start();
//! let sys = Mechanical::new(Mass::Diagonal(vec![1.0; 40]), chains).unwrap();
//! let mut vi = MechanicalMidpoint::new(sys);
//! let mut s = noether_core::State::with_momenta(0.0, q0, [vec![0.1; 20], vec![0.0; 20]].concat());
//! vi.step(&mut s, 0.1).unwrap();
//! assert!((s.v.iter().sum::<f64>() - 2.0).abs() < 1e-14); // total momentum 20·0.1
//! ```

use crate::mechanical::LocalPotential;
use noether_core::Scalar;

/// Two chains (top t, bottom b) of n masses each on a line, coordinates (q_t¹…q_tⁿ, q_b¹…q_bⁿ):
///
/// ```text
/// V1 = (k1/2) Σ_{i<n} [(q_t^{i+1} − q_t^i − l)² + (q_b^{i+1} − q_b^i − l)²],
/// V2 = k2 Σ_{i,j} exp(−(q_t^i − q_b^j)² / (2σ²))      (k2 > 0 repulsive, k2 < 0 attractive).
/// ```
///
/// Terms: 2(n − 1) springs, then n² Gaussian pairs (top i, bottom j), each of two coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct CoupledChains {
    /// Masses per chain.
    pub n: usize,
    /// Spring constant inside each chain.
    pub k1: f64,
    /// Natural length of the springs.
    pub l: f64,
    /// Strength of the Gaussian coupling.
    pub k2: f64,
    /// Width of the Gaussian coupling.
    pub sigma: f64,
}

impl CoupledChains {
    /// The paper's parameters: n = 20, k1 = 1, l = 1/20, σ = 0.1, coupling `k2` (0.001 in the
    /// collision runs, negative for the attractive "heat" runs).
    pub fn paper(k2: f64) -> Self {
        CoupledChains {
            n: 20,
            k1: 1.0,
            l: 1.0 / 20.0,
            k2,
            sigma: 0.1,
        }
    }

    /// The paper's start of a collision run: each chain at spring equilibrium (spacing l, the bottom
    /// chain from 0), the top chain shifted by −3.
    pub fn collision_start(&self) -> Vec<f64> {
        let top = (0..self.n).map(|i| i as f64 * self.l - 3.0);
        let bottom = (0..self.n).map(|i| i as f64 * self.l);
        top.chain(bottom).collect()
    }

    /// The paper's step h = min(2π/(10√k1), 0.1).
    pub fn paper_step(&self) -> f64 {
        (2.0 * std::f64::consts::PI / (10.0 * self.k1.sqrt())).min(0.1)
    }

    /// Number of spring terms (they come first).
    pub fn springs(&self) -> usize {
        2 * (self.n - 1)
    }
}

impl LocalPotential for CoupledChains {
    fn dof(&self) -> usize {
        2 * self.n
    }
    fn terms(&self) -> usize {
        self.springs() + self.n * self.n
    }
    fn support(&self, k: usize, idx: &mut Vec<usize>) {
        let (n, s) = (self.n, self.springs());
        if k < s {
            let (chain, i) = (k / (n - 1), k % (n - 1));
            idx.extend([chain * n + i, chain * n + i + 1]);
        } else {
            let (i, j) = ((k - s) / n, (k - s) % n);
            idx.extend([i, n + j]);
        }
    }
    #[inline]
    fn term<D: Scalar>(&self, k: usize, x: &[D]) -> D {
        if k < self.springs() {
            let e = x[1] - x[0] - self.l;
            e * e * (0.5 * self.k1)
        } else {
            let d = x[0] - x[1];
            (d * d * (-0.5 / (self.sigma * self.sigma))).exp() * self.k2
        }
    }
}

/// One chain of n masses with nearest-neighbour springs and a quartic on-site potential:
///
/// ```text
/// V = Σ_{i<n} (k/2)(q^{i+1} − q^i)² + Σ_i [(a/2)(q^i)² + (b/4)(q^i)⁴].
/// ```
///
/// Terms: n on-site terms, then n − 1 springs. The Hessian is tridiagonal.
#[derive(Debug, Clone, PartialEq)]
pub struct QuarticChain {
    /// Number of masses.
    pub n: usize,
    /// Spring constant.
    pub k: f64,
    /// Harmonic on-site coefficient.
    pub a: f64,
    /// Quartic on-site coefficient.
    pub b: f64,
}

impl LocalPotential for QuarticChain {
    fn dof(&self) -> usize {
        self.n
    }
    fn terms(&self) -> usize {
        2 * self.n - 1
    }
    fn support(&self, k: usize, idx: &mut Vec<usize>) {
        if k < self.n {
            idx.push(k);
        } else {
            let i = k - self.n;
            idx.extend([i, i + 1]);
        }
    }
    #[inline]
    fn term<D: Scalar>(&self, k: usize, x: &[D]) -> D {
        if k < self.n {
            let q2 = x[0] * x[0];
            q2 * (0.5 * self.a) + q2 * q2 * (0.25 * self.b)
        } else {
            let e = x[1] - x[0];
            e * e * (0.5 * self.k)
        }
    }
}
