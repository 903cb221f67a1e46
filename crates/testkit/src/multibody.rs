//! Mechanisms built from bodies and joints (noether-multibody), with the closed forms they are
//! checked against: the double pendulum of [`systems::DoublePendulum`](crate::systems::DoublePendulum)
//! from two hinges, and a planar arm of three uniform rods with its textbook mass matrix and tip.

use crate::systems::DoublePendulum;
use noether_multibody::{Body, Joint, Mechanism, Parent, Placement};

/// The z axis, about which every hinge here turns.
pub const Z: [f64; 3] = [0.0, 0.0, 1.0];

/// The double pendulum `dp` (bobs m₁, m₂ on rods l₁, l₂, gravity along −y) from two revolute
/// joints about z, in the joints' relative angles q = (θ₁, θ₂ − θ₁) (θ the hand model's absolute
/// angles from the downward vertical).
pub fn joints_double_pendulum(dp: &DoublePendulum) -> Mechanism {
    let built = || -> noether_multibody::Result<Mechanism> {
        let mut m = Mechanism::new().gravity([0.0, -dp.g, 0.0])?;
        let hang = |l: f64| [0.0, -l, 0.0];
        let upper = m.attach(
            Parent::Ground,
            Placement::identity(),
            Joint::revolute(Z),
            Body::point(dp.m1, hang(dp.l1)),
        )?;
        m.attach(
            upper,
            Placement::at(hang(dp.l1)),
            Joint::revolute(Z),
            Body::point(dp.m2, hang(dp.l2)),
        )?;
        Ok(m)
    };
    built().expect("the double pendulum's data are valid")
}

/// A planar arm of three uniform rods (masses m_i, lengths l_i) on hinges about z, each link along
/// its body x axis, in relative joint angles q (q = 0: the arm straight along x), under gravity g
/// along −y, every joint actuated (torques u).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarArm {
    /// Link masses m_i.
    pub masses: [f64; 3],
    /// Link lengths l_i.
    pub lengths: [f64; 3],
    /// Gravity g.
    pub g: f64,
}

impl Default for PlanarArm {
    fn default() -> Self {
        PlanarArm {
            masses: [1.2, 0.9, 0.5],
            lengths: [1.0, 0.8, 0.6],
            g: 9.81,
        }
    }
}

impl PlanarArm {
    /// The mechanism: three rods from hinge to hinge, every joint actuated.
    pub fn mechanism(&self) -> Mechanism {
        let built = || -> noether_multibody::Result<Mechanism> {
            let mut arm = Mechanism::new().gravity([0.0, -self.g, 0.0])?;
            let mut parent = Parent::Ground;
            let mut at = [0.0; 3];
            for (&m, &l) in self.masses.iter().zip(&self.lengths) {
                let rod = Body::rod(m, [0.0; 3], [l, 0.0, 0.0]);
                let link = arm.attach(parent, Placement::at(at), Joint::revolute(Z), rod)?;
                arm.actuate(link)?;
                (parent, at) = (link.into(), [l, 0.0, 0.0]);
            }
            Ok(arm)
        };
        built().expect("the arm's data are valid")
    }

    /// The mass matrix in closed form (Spong, Hutchinson and Vidyasagar, *Robot Modeling and
    /// Control*, §7.4, extended to a third link), with centres r_i = l_i/2 and moments
    /// I_i = m_i l_i²/12 about them, c₂ = cos q₂, c₃ = cos q₃, c₂₃ = cos(q₂ + q₃):
    ///
    /// ```text
    /// M₃₃ = I₃ + m₃ r₃²
    /// M₂₃ = M₃₃ + m₃ l₂ r₃ c₃
    /// M₁₃ = M₂₃ + m₃ l₁ r₃ c₂₃
    /// M₂₂ = I₂ + m₂ r₂² + I₃ + m₃ (l₂² + r₃² + 2 l₂ r₃ c₃)
    /// M₁₂ = M₂₂ + m₂ l₁ r₂ c₂ + m₃ (l₁ l₂ c₂ + l₁ r₃ c₂₃)
    /// M₁₁ = I₁ + m₁ r₁² + M₂₂ + 2 m₂ l₁ r₂ c₂ + m₂ l₁² + m₃ (l₁² + 2 l₁ l₂ c₂ + 2 l₁ r₃ c₂₃)
    /// ```
    pub fn mass_matrix(&self, q: &[f64]) -> [[f64; 3]; 3] {
        let (m, l) = (self.masses, self.lengths);
        let r = l.map(|x| x / 2.0);
        let inertia: [f64; 3] = std::array::from_fn(|i| m[i] * l[i] * l[i] / 12.0);
        let (c2, c3, c23) = (q[1].cos(), q[2].cos(), (q[1] + q[2]).cos());
        let m33 = inertia[2] + m[2] * r[2] * r[2];
        let m23 = m33 + m[2] * l[1] * r[2] * c3;
        let m13 = m23 + m[2] * l[0] * r[2] * c23;
        let m22 = inertia[1]
            + m[1] * r[1] * r[1]
            + inertia[2]
            + m[2] * (l[1] * l[1] + r[2] * r[2] + 2.0 * l[1] * r[2] * c3);
        let m12 = m22 + m[1] * l[0] * r[1] * c2 + m[2] * (l[0] * l[1] * c2 + l[0] * r[2] * c23);
        let m11 = inertia[0]
            + m[0] * r[0] * r[0]
            + m22
            + 2.0 * m[1] * l[0] * r[1] * c2
            + m[1] * l[0] * l[0]
            + m[2] * (l[0] * l[0] + 2.0 * l[0] * l[1] * c2 + 2.0 * l[0] * r[2] * c23);
        [[m11, m12, m13], [m12, m22, m23], [m13, m23, m33]]
    }

    /// The tip (the far end of the third link) in the plane: Σ_i l_i (cos φ_i, sin φ_i) with the
    /// absolute angles φ_i = q₁ + … + q_i.
    pub fn tip(&self, q: &[f64]) -> [f64; 2] {
        let mut phi = 0.0;
        let mut tip = [0.0; 2];
        for (qi, l) in q.iter().zip(&self.lengths) {
            phi += qi;
            tip[0] += l * phi.cos();
            tip[1] += l * phi.sin();
        }
        tip
    }
}
