//! Actuated models: the cart-pole, the double integrator, the pendubot, a spacecraft's reaction
//! wheel.

use noether_core::control::Actuated;
use noether_core::{Lagrangian, Scalar};

/// The cart-pole: a cart of mass M on a horizontal track pushed by a force u, carrying a point mass m
/// on a massless rod of length l; q = (x, θ), x the cart's position and θ the rod's angle from the
/// upward vertical. The bob is at (x + l sin θ, l cos θ), so
///
/// ```text
/// L = ½(M + m) ẋ² + m l ẋ θ̇ cos θ + ½ m l² θ̇² − m g l cos θ,   Q_u = (u, 0).
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CartPole {
    /// Cart mass M.
    pub cart: f64,
    /// Bob mass m.
    pub bob: f64,
    /// Rod length l.
    pub l: f64,
    /// Gravity g.
    pub g: f64,
}

impl Default for CartPole {
    fn default() -> Self {
        CartPole {
            cart: 1.0,
            bob: 0.3,
            l: 0.8,
            g: 9.81,
        }
    }
}

impl Lagrangian for CartPole {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (big, m, l) = (self.cart, self.bob, self.l);
        v[0] * v[0] * (0.5 * (big + m)) + v[0] * v[1] * q[1].cos() * (m * l) + v[1] * v[1] * (0.5 * m * l * l)
            - q[1].cos() * (m * self.g * l)
    }
}

impl Actuated for CartPole {
    fn inputs(&self) -> usize {
        1
    }
    fn input_force<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], u: &[D], out: &mut [D]) {
        out[0] = u[0];
        out[1] = D::zero();
    }
}

impl CartPole {
    /// The textbook linearisation upright (θ = 0, at rest), state (x, θ, ẋ, θ̇): from
    /// (M + m)ẍ + m l θ̈ = u and m l ẍ + m l² θ̈ − m g l θ = 0,
    /// ẍ = −(m g/M) θ + u/M and θ̈ = (M + m) g θ/(M l) − u/(M l): the rows of ẍ and θ̈ of A
    /// (on θ) and of B.
    pub fn upright_linearization(&self) -> ([[f64; 4]; 4], [f64; 4]) {
        let (big, m, l, g) = (self.cart, self.bob, self.l, self.g);
        let a = [
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
            [0.0, -m * g / big, 0.0, 0.0],
            [0.0, (big + m) * g / (big * l), 0.0, 0.0],
        ];
        (a, [0.0, 0.0, 1.0 / big, -1.0 / (big * l)])
    }
}

/// The double integrator q̈ = u: a unit mass pushed by a force, L = ½ q̇², Q_u = u. The minimum-effort
/// transfer (min ∫ u² dt) from rest at 0 to rest at 1 in time T has the closed form
/// u(t) = (6/T²)(1 − 2t/T), cost 12/T³ (Bryson and Ho, *Applied Optimal Control*, §5.2).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DoubleIntegrator;

impl Lagrangian for DoubleIntegrator {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<D: Scalar>(&self, _t: D, _q: &[D], v: &[D]) -> D {
        v[0] * v[0] * 0.5
    }
}

impl Actuated for DoubleIntegrator {
    fn inputs(&self) -> usize {
        1
    }
    fn input_force<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], u: &[D], out: &mut [D]) {
        out[0] = u[0];
    }
}

/// The pendubot: the double pendulum of [`DoublePendulum`](crate::systems::DoublePendulum) (absolute
/// angles θ1, θ2 from the downward vertical) with a motor at the shoulder only, a torque u between
/// the base and the upper rod: its virtual work u δθ1 gives Q_u = (u, 0). Underactuated: the lower
/// rod moves only through the coupling.
#[derive(Debug, Clone, Copy, Default)]
pub struct Pendubot(pub crate::systems::DoublePendulum);

impl Lagrangian for Pendubot {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
        self.0.lagrangian(t, q, v)
    }
}

impl Actuated for Pendubot {
    fn inputs(&self) -> usize {
        1
    }
    fn input_force<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], u: &[D], out: &mut [D]) {
        out[0] = u[0];
        out[1] = D::zero();
    }
}

/// A spacecraft turned about one axis by a reaction wheel: q = (θ, α), the body's angle and the
/// wheel's angle relative to the body, J the body's moment (without the wheel's axial one) and I_w
/// the wheel's,
///
/// ```text
/// L = ½ J θ̇² + ½ I_w (θ̇ + α̇)²,   Q_u = (0, u),
/// ```
///
/// the motor's torque u on the wheel and −u on the body (internal: its virtual work is u δα). θ is
/// cyclic and unforced, so p_θ = J θ̇ + I_w(θ̇ + α̇), the total angular momentum, is conserved; with
/// ṗ_α = u it gives J θ̈ = −u: the body is a double integrator driven by −u/J.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReactionWheel {
    /// The body's moment J about the axis.
    pub body: f64,
    /// The wheel's axial moment I_w.
    pub wheel: f64,
}

impl Default for ReactionWheel {
    fn default() -> Self {
        ReactionWheel {
            body: 12.0,
            wheel: 0.4,
        }
    }
}

impl Lagrangian for ReactionWheel {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, _q: &[D], v: &[D]) -> D {
        let spin = v[0] + v[1];
        v[0] * v[0] * (0.5 * self.body) + spin * spin * (0.5 * self.wheel)
    }
}

impl Actuated for ReactionWheel {
    fn inputs(&self) -> usize {
        1
    }
    fn input_force<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], u: &[D], out: &mut [D]) {
        out[0] = D::zero();
        out[1] = u[0];
    }
}
