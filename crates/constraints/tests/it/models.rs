//! Small models shared by the tests.

use noether_constraints::prelude::*;

/// Point masses in d dimensions under uniform gravity along the last axis:
/// L = Σ ½ m |ṙ_i|² − m g r_i,last.
pub struct Masses {
    pub n: usize,
    pub d: usize,
    pub m: f64,
    pub g: f64,
}

impl Lagrangian for Masses {
    fn dof(&self) -> usize {
        self.n * self.d
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let mut l = D::zero();
        for i in 0..self.n {
            for k in 0..self.d {
                l += v[i * self.d + k] * v[i * self.d + k] * (0.5 * self.m);
            }
            l -= q[i * self.d + self.d - 1] * (self.m * self.g);
        }
        l
    }
    fn constant_mass_matrix(&self) -> bool {
        true
    }
}

/// A rod of length l from the origin to mass 0: φ = (|r|² − l²)/(2l), so Φ_q = r̂ and λ is the
/// force along r̂ (tension T = −λ). `copies` repeats it (a redundant set when > 1).
pub struct Rod {
    pub d: usize,
    pub l: f64,
    pub copies: usize,
}

impl Holonomic for Rod {
    fn dof(&self) -> usize {
        self.d
    }
    fn count(&self) -> usize {
        self.copies
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        let mut r2 = D::zero();
        for x in q {
            r2 += *x * *x;
        }
        for (k, o) in out.iter_mut().enumerate() {
            *o = (r2 - self.l * self.l) * (0.5 / self.l) * (1.0 + k as f64);
        }
    }
}

/// The simple pendulum in its angle from the downward vertical: L = ½ m l² θ̇² + m g l cos θ.
pub struct AnglePendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

impl Lagrangian for AnglePendulum {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        v[0] * v[0] * (0.5 * self.m * self.l * self.l) + q[0].cos() * (self.m * self.g * self.l)
    }
}

/// A model with the linear drag Q = −c q̇ added (a physical drag −c ṙ on Cartesian point masses; for
/// the angle pendulum c l² is the drag on the bob).
pub struct Dragged<L> {
    pub model: L,
    pub c: f64,
}

impl<L: Lagrangian> Lagrangian for Dragged<L> {
    fn dof(&self) -> usize {
        self.model.dof()
    }
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        self.model.lagrangian(t, q, v)
    }
    fn constant_mass_matrix(&self) -> bool {
        self.model.constant_mass_matrix()
    }
    fn has_generalized_force(&self) -> bool {
        true
    }
    fn generalized_force<D: Scalar>(&self, _t: D, _q: &[D], v: &[D], out: &mut [D]) {
        out.iter_mut().zip(v).for_each(|(o, vi)| *o = *vi * -self.c);
    }
}

/// A planar pendulum state at angle θ, rate ω (x = l sin θ, y = −l cos θ).
pub fn pendulum_state(l: f64, theta: f64, omega: f64) -> State {
    State::new(
        0.0,
        [l * theta.sin(), -l * theta.cos()],
        [l * omega * theta.cos(), l * omega * theta.sin()],
    )
}
