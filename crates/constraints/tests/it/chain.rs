//! A planar chain of N point masses on massless rods, hanging from a pivot at the origin, in two
//! formulations: Cartesian (2N coordinates, N rod constraints) and angles (N coordinates, no
//! constraints). Shared by the tests and the benchmark.

use noether_constraints::prelude::*;

/// N masses in the plane under gravity (y up): L = Σ ½ m |ṙ_i|² − m g y_i, q = (x₁, y₁, …, x_N, y_N).
pub struct CartesianChain {
    pub n: usize,
    pub m: f64,
    pub g: f64,
}

impl Lagrangian for CartesianChain {
    fn dof(&self) -> usize {
        2 * self.n
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let mut l = D::zero();
        for i in 0..self.n {
            l += (v[2 * i] * v[2 * i] + v[2 * i + 1] * v[2 * i + 1]) * (0.5 * self.m);
            l -= q[2 * i + 1] * (self.m * self.g);
        }
        l
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}

/// The rods: φ₁ = (|r₁|² − l²)/(2l), φ_i = (|r_i − r_{i−1}|² − l²)/(2l).
pub struct Rods {
    pub n: usize,
    pub l: f64,
}

impl Holonomic for Rods {
    fn dof(&self) -> usize {
        2 * self.n
    }
    fn count(&self) -> usize {
        self.n
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        for i in 0..self.n {
            let (mut dx, mut dy) = (q[2 * i], q[2 * i + 1]);
            if i > 0 {
                dx -= q[2 * i - 2];
                dy -= q[2 * i - 1];
            }
            out[i] = (dx * dx + dy * dy - self.l * self.l) * (0.5 / self.l);
        }
    }
}

/// The same chain in the angles θ_i of the rods from the downward vertical:
/// x_i = l Σ_{j≤i} sin θ_j, y_i = −l Σ_{j≤i} cos θ_j.
pub struct AngleChain {
    pub n: usize,
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

impl Lagrangian for AngleChain {
    fn dof(&self) -> usize {
        self.n
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (mut vx, mut vy, mut y) = (D::zero(), D::zero(), D::zero());
        let mut l = D::zero();
        for i in 0..self.n {
            let (s, c) = (q[i].sin(), q[i].cos());
            vx += c * v[i] * self.l;
            vy += s * v[i] * self.l;
            y -= c * self.l;
            l += (vx * vx + vy * vy) * (0.5 * self.m) - y * (self.m * self.g);
        }
        l
    }
}

/// Angles and rates of a bent, moving chain, and the same state in Cartesian coordinates.
pub fn chain_states(n: usize, l: f64) -> (State, State) {
    let th: Vec<f64> = (0..n).map(|i| 0.3 + 0.1 * i as f64).collect();
    let om: Vec<f64> = (0..n).map(|i| 0.2 - 0.05 * i as f64).collect();
    let (mut q, mut v) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
    let (mut x, mut y, mut vx, mut vy) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..n {
        x += l * th[i].sin();
        y -= l * th[i].cos();
        vx += l * th[i].cos() * om[i];
        vy += l * th[i].sin() * om[i];
        q[2 * i] = x;
        q[2 * i + 1] = y;
        v[2 * i] = vx;
        v[2 * i + 1] = vy;
    }
    (State::new(0.0, th, om), State::new(0.0, q, v))
}
