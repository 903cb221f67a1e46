//! A coin rolling on a table: a thin disk that tilts, turns and spins, rolling without slipping, in
//! dependent coordinates with two velocity constraints; its steady turns and their stability in
//! closed form.
//!
//! q = (x, y, ψ, θ, φ): the centre's horizontal position, the heading ψ of the rolling direction,
//! the tilt θ of the disk's plane from the vertical, the spin angle φ. The disk (radius a, mass m,
//! moment A about a diameter, C about its axis) has its centre at height a cos θ and spins about its
//! axis at ω₃ = φ̇ + ψ̇ sin θ, so
//!
//! ```text
//! L = ½ m (ẋ² + ẏ² + a² sin²θ θ̇²) + ½ (A θ̇² + A ψ̇² cos²θ + C ω₃²) − m g a cos θ,
//! ```
//!
//! and the contact point does not slip: ẋ = a ω₃ cos ψ + a θ̇ cos θ sin ψ,
//! ẏ = a ω₃ sin ψ − a θ̇ cos θ cos ψ.
//!
//! Eliminating the multipliers and the cyclic coordinates leaves the classical reduced equations in
//! (θ, Ω = ψ̇, ω₃) (Routh, *Advanced Rigid Dynamics*, §244; O'Reilly, Nonlinear Dynamics 10 (1996);
//! rederived here from L and the constraints by the projection onto the allowed velocities):
//!
//! ```text
//! (A + m a²) θ̈ = F(θ, Ω, ω₃) = (C + m a²) Ω ω₃ cos θ − A Ω² sin θ cos θ + m g a sin θ,
//! A Ω̇ cos θ = θ̇ (2 A Ω sin θ − C ω₃),
//! (C + m a²) ω̇₃ = −m a² Ω θ̇ cos θ.
//! ```
//!
//! A steady turn holds θ, Ω, ω₃ fixed with F = 0 ([`Coin::steady_spin`]). Linearised about it, the
//! last two equations integrate to δΩ = p δθ, δω₃ = r δθ (up to constants that move the motion to a
//! neighbouring steady turn), p = (2AΩ sin θ − Cω₃)/(A cos θ), r = −m a² Ω cos θ/(C + m a²), and the
//! tilt obeys δθ̈ = −ω² δθ with
//!
//! ```text
//! (A + m a²) ω² = −(F_θ + F_Ω p + F_ω₃ r)                                     ([`Coin::tilt_frequency_squared`]):
//! ```
//!
//! the turn is (linearly) stable when ω² > 0. Upright rolling in a straight line (θ = Ω = 0, any ω₃)
//! gives (A + m a²) A ω² = C (C + m a²) ω₃² − m g a A: stable above ω₃² = m g a A/(C (C + m a²)),
//! g/(3a) for the uniform disk (A = m a²/4, C = m a²/2), g/(4a) for a hoop.

use noether_constraints::Nonholonomic;
use noether_core::control::Actuated;
use noether_core::{Lagrangian, Scalar};

/// The coin (module docs): a disk of `radius` a and `mass` m with moments `diametral` A and `axial`
/// C, under gravity `g`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coin {
    /// Radius a.
    pub radius: f64,
    /// Mass m.
    pub mass: f64,
    /// Moment of inertia A about a diameter.
    pub diametral: f64,
    /// Moment of inertia C about the axis.
    pub axial: f64,
    /// Gravitational acceleration g.
    pub g: f64,
}

impl Coin {
    /// A uniform thin disk: A = m a²/4, C = m a²/2.
    pub fn uniform(radius: f64, mass: f64, g: f64) -> Self {
        let ma2 = mass * radius * radius;
        Coin {
            radius,
            mass,
            diametral: ma2 / 4.0,
            axial: ma2 / 2.0,
            g,
        }
    }

    /// The rolling constraints of this coin.
    pub fn rolling(&self) -> CoinRolling {
        CoinRolling(self.radius)
    }

    /// m a².
    fn ma2(&self) -> f64 {
        self.mass * self.radius * self.radius
    }

    /// The spin ω₃ of the steady turn at tilt θ and turning rate Ω ≠ 0: the root of F = 0,
    /// ω₃ = (A Ω² cos θ − m g a) sin θ / ((C + m a²) Ω cos θ).
    pub fn steady_spin(&self, theta: f64, omega: f64) -> f64 {
        let (s, c) = theta.sin_cos();
        (self.diametral * omega * omega * c - self.mass * self.g * self.radius) * s
            / ((self.axial + self.ma2()) * omega * c)
    }

    /// ω² of the tilt's small oscillation about the steady motion (θ, Ω, ω₃) (module docs).
    pub fn tilt_frequency_squared(&self, theta: f64, omega: f64, spin: f64) -> f64 {
        let (a, c, ma2, mga) = (
            self.diametral,
            self.axial,
            self.ma2(),
            self.mass * self.g * self.radius,
        );
        let (sn, cs) = theta.sin_cos();
        let f_theta = -(c + ma2) * omega * spin * sn - a * omega * omega * (2.0 * theta).cos() + mga * cs;
        let f_omega = (c + ma2) * spin * cs - 2.0 * a * omega * sn * cs;
        let f_spin = (c + ma2) * omega * cs;
        let p = (2.0 * a * omega * sn - c * spin) / (a * cs);
        let r = -ma2 * omega * cs / (c + ma2);
        -(f_theta + f_omega * p + f_spin * r) / (a + ma2)
    }

    /// The rates q̇ at q with the angles' rates (ψ̇, θ̇, φ̇) given and the centre's (ẋ, ẏ) that rolling
    /// asks for (the constraints at ẋ = ẏ = 0 are −(ẋ, ẏ)).
    pub fn rolling_rates(&self, q: &[f64; 5], angles: [f64; 3]) -> [f64; 5] {
        let mut v = [0.0, 0.0, angles[0], angles[1], angles[2]];
        let mut g = [0.0; 2];
        self.rolling().constraints(0.0, q, &v, &mut g);
        v[0] = -g[0];
        v[1] = -g[1];
        v
    }

    /// A random rolling state from `draw` (uniform in [lo, hi), e.g. `agreement::uniform`): the centre
    /// in [−1, 1]², the heading and spin angles and the three angle rates in [−3, 3], the tilt within
    /// 1.2 rad of upright, and the centre's velocity that rolling asks for.
    pub fn random_rolling_state(&self, draw: &mut impl FnMut(f64, f64) -> f64) -> ([f64; 5], [f64; 5]) {
        let q = [
            draw(-1.0, 1.0),
            draw(-1.0, 1.0),
            draw(-3.0, 3.0),
            draw(-1.2, 1.2),
            draw(-3.0, 3.0),
        ];
        let v = self.rolling_rates(&q, [draw(-3.0, 3.0), draw(-3.0, 3.0), draw(-3.0, 3.0)]);
        (q, v)
    }

    /// The state (q, q̇) of the steady motion (θ, Ω, ω₃) heading along x from the origin:
    /// q = (0, 0, 0, θ, 0), q̇ = (a ω₃, 0, Ω, 0, ω₃ − Ω sin θ).
    pub fn steady_state(&self, theta: f64, omega: f64, spin: f64) -> ([f64; 5], [f64; 5]) {
        (
            [0.0, 0.0, 0.0, theta, 0.0],
            [self.radius * spin, 0.0, omega, 0.0, spin - omega * theta.sin()],
        )
    }
}

impl Lagrangian for Coin {
    fn dof(&self) -> usize {
        5
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let (s, c) = (q[3].sin(), q[3].cos());
        let spin = v[4] + v[2] * s;
        let a2 = self.radius * self.radius;
        let translation = (v[0] * v[0] + v[1] * v[1] + v[3] * v[3] * s * s * a2) * (0.5 * self.mass);
        let rotation =
            (v[3] * v[3] + v[2] * v[2] * c * c) * (0.5 * self.diametral) + spin * spin * (0.5 * self.axial);
        translation + rotation - c * (self.mass * self.g * self.radius)
    }
}

/// No inputs: the coin rolls free (so the linearisations of `Actuated` models take it).
impl Actuated for Coin {
    fn inputs(&self) -> usize {
        0
    }
    fn input_force<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], _u: &[D], out: &mut [D]) {
        out.fill(D::zero());
    }
}

/// Rolling without slipping for a coin of radius a: the contact point's velocity vanishes,
/// ẋ − a ω₃ cos ψ − a θ̇ cos θ sin ψ = 0 and ẏ − a ω₃ sin ψ + a θ̇ cos θ cos ψ = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoinRolling(pub f64);

impl Nonholonomic for CoinRolling {
    fn dof(&self) -> usize {
        5
    }
    fn count(&self) -> usize {
        2
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], v: &[D], out: &mut [D]) {
        let (sp, cp) = (q[2].sin(), q[2].cos());
        let spin = v[4] + v[2] * q[3].sin();
        let tilt = v[3] * q[3].cos();
        out[0] = v[0] - (spin * cp + tilt * sp) * self.0;
        out[1] = v[1] - (spin * sp - tilt * cp) * self.0;
    }
}
