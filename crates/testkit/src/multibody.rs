//! Mechanisms built from bodies and joints (noether-multibody), with the closed forms they are
//! checked against: the double pendulum of [`systems::DoublePendulum`](crate::systems::DoublePendulum)
//! from two hinges, and a planar arm of three uniform rods with its textbook mass matrix and tip.

use crate::systems::DoublePendulum;
use noether_constraints::{Holonomic, Rattle, Reduced};
use noether_core::control::{ClosedLoop, Constant};
use noether_core::{EulerLagrange, Stepper};
use noether_discrete::Midpoint;
use noether_multibody::{Body, Joint, Mechanism, Parent, Placement};

/// An error of any crate, for the runs here (sendable, as the gallery's).
pub type Failure = Box<dyn std::error::Error + Send + Sync>;

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

/// A planar chain of uniform rods (masses m_i, lengths l_i) hinged end to end about z from the origin,
/// each along its body x axis, under gravity g along −y, every joint actuated: the planar arm for
/// any number of links (the benchmarks' 7-link arm).
pub fn rod_chain(masses: &[f64], lengths: &[f64], g: f64) -> Mechanism {
    let built = || -> noether_multibody::Result<Mechanism> {
        let mut arm = Mechanism::new().gravity([0.0, -g, 0.0])?;
        let mut parent = Parent::Ground;
        let mut at = [0.0; 3];
        for (&m, &l) in masses.iter().zip(lengths) {
            let rod = Body::rod(m, [0.0; 3], [l, 0.0, 0.0]);
            let link = arm.attach(parent, Placement::at(at), Joint::revolute(Z), rod)?;
            arm.actuate(link)?;
            (parent, at) = (link.into(), [l, 0.0, 0.0]);
        }
        Ok(arm)
    };
    built().expect("the chain's data are valid")
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
        rod_chain(&self.masses, &self.lengths, self.g)
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

/// A slider-crank: a crank of length r (uniform rod, mass m_c) on a hinge at the origin, a connecting
/// rod of length l > r (uniform, m_r) hinged at the crank pin, a piston (point mass m_p) sliding along
/// x on a spring k towards x₀, the rod's far end pinned to the piston: a loop closed along x and y.
/// q = (θ, φ, x): the crank angle, the rod's angle relative to the crank, the piston's position; the
/// crank is actuated (a torque u).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderCrank {
    /// Crank length r.
    pub crank: f64,
    /// Connecting-rod length l.
    pub rod: f64,
    /// Masses (m_c, m_r, m_p).
    pub masses: [f64; 3],
    /// The piston spring's stiffness k and rest position x₀.
    pub spring: (f64, f64),
}

impl Default for SliderCrank {
    fn default() -> Self {
        SliderCrank {
            crank: 0.3,
            rod: 1.0,
            masses: [0.5, 0.8, 1.5],
            spring: (40.0, 1.1),
        }
    }
}

impl SliderCrank {
    /// The mechanism with its loop closure (the rod's end on the piston, along x and y).
    pub fn mechanism(&self) -> Mechanism {
        let built = || -> noether_multibody::Result<Mechanism> {
            let (r, l, [mc, mr, mp]) = (self.crank, self.rod, self.masses);
            let mut m = Mechanism::new();
            let crank = m.attach(
                Parent::Ground,
                Placement::identity(),
                Joint::revolute(Z),
                Body::rod(mc, [0.0; 3], [r, 0.0, 0.0]),
            )?;
            let rod = m.attach(
                crank,
                Placement::at([r, 0.0, 0.0]),
                Joint::revolute(Z),
                Body::rod(mr, [0.0; 3], [l, 0.0, 0.0]),
            )?;
            let slide = Joint::prismatic([1.0, 0.0, 0.0]).spring(self.spring.0, self.spring.1);
            let piston = m.attach(
                Parent::Ground,
                Placement::identity(),
                slide,
                Body::point(mp, [0.0; 3]),
            )?;
            m.actuate(crank)?;
            m.close_loop(
                (rod.into(), [l, 0.0, 0.0]),
                (piston.into(), [0.0; 3]),
                &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            )?;
            Ok(m)
        };
        built().expect("the slider-crank's data are valid")
    }

    /// The piston's position x(θ) = r cos θ + √(l² − r² sin²θ) (the triangle of crank, rod and slide).
    pub fn piston(&self, theta: f64) -> f64 {
        let (r, l) = (self.crank, self.rod);
        r * theta.cos() + (l * l - (r * theta.sin()).powi(2)).sqrt()
    }

    /// dx/dθ = −r sin θ − r² sin θ cos θ / √(l² − r² sin²θ).
    pub fn piston_rate(&self, theta: f64) -> f64 {
        let (r, l) = (self.crank, self.rod);
        let (s, c) = theta.sin_cos();
        -r * s - r * r * s * c / (l * l - (r * s).powi(2)).sqrt()
    }

    /// The crank torque that holds the mechanism at rest at θ against the piston's spring, by virtual
    /// work: u δθ = k (x − x₀) δx, so u = k (x − x₀) dx/dθ.
    pub fn holding_torque(&self, theta: f64) -> f64 {
        self.spring.0 * (self.piston(theta) - self.spring.1) * self.piston_rate(theta)
    }

    /// The mechanism reduced to its crank angle near θ (`Reduced`, whose Newton solve of the loop is
    /// local: its reference is the closed-form configuration 0.05 rad further on, not the point asked
    /// for).
    pub fn reduced_near(
        &self,
        theta: f64,
    ) -> Result<Reduced<Mechanism, noether_multibody::LoopClosures>, Failure> {
        let mechanism = self.mechanism();
        let closures = mechanism.loop_closures();
        Ok(Reduced::new(
            mechanism,
            closures,
            &[0],
            &self.configuration(theta + 0.05),
        )?)
    }

    /// The crank's acceleration at rest at θ under the torque u (the reduced model's Lagrange
    /// equation): zero under [`holding_torque`](Self::holding_torque).
    pub fn crank_acceleration(&self, theta: f64, u: f64) -> Result<f64, Failure> {
        let reduced = self.reduced_near(theta)?;
        let el = EulerLagrange::new(ClosedLoop::new(&reduced, Constant(vec![u]))?);
        let mut a = [0.0];
        el.accelerations(0.0, &[theta], &[0.0], &mut a)?;
        Ok(a[0])
    }

    /// The configuration on the loop at crank angle θ: the rod from the crank pin (r cos θ, r sin θ)
    /// to the piston (x, 0), its absolute angle β = atan2(−r sin θ, x − r cos θ), φ = β − θ.
    pub fn configuration(&self, theta: f64) -> [f64; 3] {
        let x = self.piston(theta);
        let beta = (-self.crank * theta.sin()).atan2(x - self.crank * theta.cos());
        [theta, beta - theta, x]
    }
}

/// A four-bar linkage in the plane: ground pivots O = (0, 0) and C = (d, 0), a crank of length a from
/// O, a coupler b from the crank's end, a rocker c from C; the coupler's end pinned to the rocker's (a
/// loop closed along x and y). Uniform rods of masses (m_a, m_b, m_c), no gravity. q = (θ, φ, ψ): the
/// crank angle, the coupler's angle relative to the crank, the rocker's angle at C.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FourBar {
    /// Link lengths (ground d, crank a, coupler b, rocker c).
    pub lengths: [f64; 4],
    /// Masses of crank, coupler, rocker.
    pub masses: [f64; 3],
}

impl Default for FourBar {
    fn default() -> Self {
        FourBar {
            lengths: [1.0, 0.3, 1.1, 0.7],
            masses: [0.4, 1.0, 0.6],
        }
    }
}

impl FourBar {
    /// The mechanism with its loop closure.
    pub fn mechanism(&self) -> Mechanism {
        let built = || -> noether_multibody::Result<Mechanism> {
            let ([d, a, b, c], [ma, mb, mc]) = (self.lengths, self.masses);
            let rod = |m: f64, l: f64| Body::rod(m, [0.0; 3], [l, 0.0, 0.0]);
            let mut m = Mechanism::new();
            let crank = m.attach(
                Parent::Ground,
                Placement::identity(),
                Joint::revolute(Z),
                rod(ma, a),
            )?;
            let coupler = m.attach(
                crank,
                Placement::at([a, 0.0, 0.0]),
                Joint::revolute(Z),
                rod(mb, b),
            )?;
            let rocker = m.attach(
                Parent::Ground,
                Placement::at([d, 0.0, 0.0]),
                Joint::revolute(Z),
                rod(mc, c),
            )?;
            m.close_loop(
                (coupler.into(), [b, 0.0, 0.0]),
                (rocker.into(), [c, 0.0, 0.0]),
                &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            )?;
            Ok(m)
        };
        built().expect("the four-bar's data are valid")
    }

    /// Grashof's condition s + ℓ ≤ p + q (shortest plus longest link at most the sum of the other
    /// two): then some link turns fully; with the crank the shortest, the linkage is a crank-rocker.
    pub fn grashof(&self) -> bool {
        let mut l = self.lengths;
        l.sort_by(f64::total_cmp);
        l[0] + l[3] <= l[1] + l[2]
    }

    /// The rocker's extreme angles (ψ_min, ψ_max) of a crank-rocker: at the two toggle positions the
    /// crank and the coupler are collinear, the rocker's pin B is e = b + a or b − a from O, and the
    /// triangle O C B gives the angle γ at C by cos γ = (d² + c² − e²)/(2 d c); ψ = π − γ (B above the
    /// ground line).
    pub fn rocker_limits(&self) -> (f64, f64) {
        let [d, a, b, c] = self.lengths;
        let psi = |e: f64| std::f64::consts::PI - ((d * d + c * c - e * e) / (2.0 * d * c)).acos();
        (psi(b + a), psi(b - a))
    }

    /// The configuration on the loop at crank angle θ with the rocker's pin above the ground line:
    /// the crank's end A = a (cos θ, sin θ), the pin B where the circles |B − A| = b and |B − C| = c
    /// meet (the intersection to the left of the directed line A → C), φ and ψ from A → B and C → B.
    pub fn configuration(&self, theta: f64) -> [f64; 3] {
        let [d, a, b, c] = self.lengths;
        let (ax, ay) = (a * theta.cos(), a * theta.sin());
        let (dx, dy) = (d - ax, -ay);
        let e = (dx * dx + dy * dy).sqrt();
        let along = (b * b - c * c + e * e) / (2.0 * e);
        let across = (b * b - along * along).sqrt();
        let (ux, uy) = (dx / e, dy / e);
        let (bx, by) = (ax + along * ux - across * uy, ay + along * uy + across * ux);
        let beta = (by - ay).atan2(bx - ax);
        [theta, beta - theta, by.atan2(bx - d)]
    }
}

/// What [`FourBar::spin`] measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FourBarRun {
    /// Full turns of the crank.
    pub turns: f64,
    /// max |φ| of the loop closure over the run.
    pub closure: f64,
    /// max |E − E₀|/E₀ over the run.
    pub energy: f64,
    /// The smallest and largest rocker angle ψ sampled at the steps.
    pub rocker: (f64, f64),
}

/// What [`rattle_run`] measured: the largest closure residual |φ| and relative energy error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopRun {
    /// max |φ| of the loop closures over the run.
    pub closure: f64,
    /// max |E − E₀|/E₀ over the run.
    pub energy: f64,
}

/// Steps a mechanism with loop closures by RATTLE on the midpoint discrete Lagrangian from (q, q̇)
/// (on the loop) for `steps` steps of `h`, calling `watch` with q after each step.
pub fn rattle_run(
    mechanism: &Mechanism,
    (q, v): (&[f64], &[f64]),
    (h, steps): (f64, usize),
    mut watch: impl FnMut(&[f64]),
) -> Result<LoopRun, Failure> {
    let closures = mechanism.loop_closures();
    let el = EulerLagrange::new(mechanism.clone());
    let e0 = el.energy(0.0, q, v)?;
    let mut rattle = Rattle::new(Midpoint::new(mechanism.clone()), closures.clone())?;
    let mut state = rattle.state_from_velocities(0.0, q, v)?;
    let mut run = LoopRun {
        closure: 0.0,
        energy: 0.0,
    };
    let mut phi = vec![0.0; closures.count()];
    for _ in 0..steps {
        rattle.step(&mut state, h)?;
        closures.constraints(0.0, state.q.as_slice(), &mut phi);
        run.closure = phi.iter().fold(run.closure, |m, p| m.max(p.abs()));
        let vel = rattle.velocities(&state)?;
        let e = el.energy(0.0, state.q.as_slice(), vel.as_slice())?;
        run.energy = run.energy.max((e - e0).abs() / e0);
        watch(state.q.as_slice());
    }
    Ok(run)
}

impl FourBar {
    /// The linkage set spinning from θ = 0 at crank rate `rate` (the other rates from the loop), no
    /// gravity, stepped by RATTLE for `steps` steps of `h` ([`rattle_run`]).
    pub fn spin(&self, rate: f64, h: f64, steps: usize) -> Result<FourBarRun, Failure> {
        let mechanism = self.mechanism();
        let closures = mechanism.loop_closures();
        let reduced = Reduced::new(mechanism.clone(), closures, &[0], &self.configuration(0.0))?;
        let (q, v) = reduced.state(0.0, &[0.0], &[rate]);
        let (mut rocker, mut crank) = ((f64::INFINITY, f64::NEG_INFINITY), 0.0);
        let run = rattle_run(&mechanism, (&q, &v), (h, steps), |q| {
            rocker = (rocker.0.min(q[2]), rocker.1.max(q[2]));
            crank = q[0];
        })?;
        Ok(FourBarRun {
            turns: crank / std::f64::consts::TAU,
            closure: run.closure,
            energy: run.energy,
            rocker,
        })
    }
}

/// A reaction-wheel pendulum: a uniform rod (mass m_r, length l) on a hinge about z at the origin,
/// upright along +y at θ = 0, under gravity g along −y; at its tip a wheel (a uniform disk of mass m_w
/// and radius ρ, spinning about z) on a motor hinge, q = (θ, φ) with φ the wheel's angle relative to
/// the rod, the motor's torque u acting on φ (the rod feels −u). With J_p = m_r l²/3 + m_w l² (the rod
/// and the wheel's mass about the pivot), J_w = m_w ρ²/2 and m g ℓ = (m_r/2 + m_w) g l,
///
/// ```text
/// L = ½ J_p θ̇² + ½ J_w (θ̇ + φ̇)² − m g ℓ cos θ,
/// ```
///
/// and upright (Åström, Block and Spong, *The Reaction Wheel Pendulum*, 2007, ch. 2):
/// θ̈ = (m g ℓ θ − u)/J_p, φ̈ = ((J_p + J_w) u − J_w m g ℓ θ)/(J_p J_w).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReactionWheelPendulum {
    /// Rod mass m_r and length l.
    pub rod: (f64, f64),
    /// Wheel mass m_w and radius ρ.
    pub wheel: (f64, f64),
    /// Gravity g.
    pub g: f64,
}

impl Default for ReactionWheelPendulum {
    fn default() -> Self {
        ReactionWheelPendulum {
            rod: (0.2, 0.5),
            wheel: (0.3, 0.12),
            g: 9.81,
        }
    }
}

impl ReactionWheelPendulum {
    /// The mechanism, the wheel's motor actuated.
    pub fn mechanism(&self) -> Mechanism {
        let built = || -> noether_multibody::Result<Mechanism> {
            let ((mr, l), (mw, rho)) = (self.rod, self.wheel);
            let mut m = Mechanism::new().gravity([0.0, -self.g, 0.0])?;
            let rod = m.attach(
                Parent::Ground,
                Placement::identity(),
                Joint::revolute(Z),
                Body::rod(mr, [0.0; 3], [0.0, l, 0.0]),
            )?;
            let disk = [
                [mw * rho * rho / 4.0, 0.0, 0.0],
                [0.0, mw * rho * rho / 4.0, 0.0],
                [0.0, 0.0, mw * rho * rho / 2.0],
            ];
            let wheel = m.attach(
                rod,
                Placement::at([0.0, l, 0.0]),
                Joint::revolute(Z),
                Body::new(mw, [0.0; 3], disk),
            )?;
            m.actuate(wheel)?;
            Ok(m)
        };
        built().expect("the reaction-wheel pendulum's data are valid")
    }

    /// (J_p, J_w, m g ℓ) of the module docs.
    pub fn constants(&self) -> (f64, f64, f64) {
        let ((mr, l), (mw, rho)) = (self.rod, self.wheel);
        (
            mr * l * l / 3.0 + mw * l * l,
            mw * rho * rho / 2.0,
            (mr / 2.0 + mw) * self.g * l,
        )
    }

    /// The upright linearisation in closed form, state (θ, φ, θ̇, φ̇): (A, B) as rows.
    pub fn upright_linearization(&self) -> ([[f64; 4]; 4], [f64; 4]) {
        let (jp, jw, mgl) = self.constants();
        (
            [
                [0.0, 0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0, 1.0],
                [mgl / jp, 0.0, 0.0, 0.0],
                [-mgl / jp, 0.0, 0.0, 0.0],
            ],
            [0.0, 0.0, -1.0 / jp, (jp + jw) / (jp * jw)],
        )
    }
}

/// A spherical pendulum with a real bob: a uniform sphere of mass m and radius ρ at the end of a
/// massless rod of length l, hung from a spherical joint at the origin, gravity g along −z. Its
/// coordinates are the joint's rotation vector θ (θ = 0: hanging straight down), regular at both
/// poles of the usual spherical coordinates. About the pivot it is a symmetric top with
/// I₁ = m l² + (2/5) m ρ² (across the rod) and I₃ = (2/5) m ρ² (along it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallPendulum {
    /// Bob mass m.
    pub mass: f64,
    /// Bob radius ρ.
    pub radius: f64,
    /// Rod length l (pivot to the bob's centre).
    pub length: f64,
    /// Gravity g.
    pub g: f64,
}

impl Default for BallPendulum {
    fn default() -> Self {
        BallPendulum {
            mass: 1.0,
            radius: 0.1,
            length: 1.0,
            g: 9.81,
        }
    }
}

impl BallPendulum {
    /// The mechanism: one spherical joint at the origin, the bob's centre at −l e_z in the body frame.
    pub fn mechanism(&self) -> Mechanism {
        let i3 = 0.4 * self.mass * self.radius * self.radius;
        let bob = Body::new(
            self.mass,
            [0.0, 0.0, -self.length],
            [[i3, 0.0, 0.0], [0.0, i3, 0.0], [0.0, 0.0, i3]],
        );
        let mut m = Mechanism::new()
            .gravity([0.0, 0.0, -self.g])
            .expect("finite gravity");
        m.attach(Parent::Ground, Placement::identity(), Joint::spherical(), bob)
            .expect("a valid body");
        m
    }

    /// The moments about the pivot (I₁, I₃) = (m l² + (2/5) m ρ², (2/5) m ρ²).
    pub fn moments(&self) -> (f64, f64) {
        let i3 = 0.4 * self.mass * self.radius * self.radius;
        (self.mass * self.length * self.length + i3, i3)
    }

    /// ω₀ = sqrt(m g l / I₁), the small swings' angular frequency.
    pub fn small_swing_rate(&self) -> f64 {
        (self.mass * self.g * self.length / self.moments().0).sqrt()
    }

    /// The period of a swing in a vertical plane through the bottom with amplitude a < π: the
    /// compound pendulum's T = 4 K(sin(a/2)) / ω₀ (the planar pendulum of moment I₁).
    pub fn swing_period(&self, amplitude: f64) -> f64 {
        4.0 * crate::closed_form::elliptic_k((0.5 * amplitude).sin()) / self.small_swing_rate()
    }

    /// The time of one revolution of a pendulum going over the top in a vertical plane, with the
    /// rate Ω₀ at the bottom: from θ̇² = Ω₀² − 4 ω₀² sin²(θ/2), T = ∫₀^{2π} dθ/θ̇ = (4/Ω₀) K(κ),
    /// κ = 2 ω₀/Ω₀ < 1 (the energy above the top).
    pub fn revolution_period(&self, bottom_rate: f64) -> f64 {
        let kappa = 2.0 * self.small_swing_rate() / bottom_rate;
        4.0 / bottom_rate * crate::closed_form::elliptic_k(kappa)
    }

    /// The rate Ω at which the pendulum turned rigidly about the vertical (no spin relative to that
    /// turn) goes round a cone of half-angle α from the downward vertical: the symmetric top's steady
    /// precession I₁ Ω² cos ϑ − I₃ ω₃ Ω + m g l = 0 (ϑ = π − α from the upward vertical) with
    /// ω₃ = Ω cos ϑ gives Ω² = m g l / ((I₁ − I₃) cos α) = g / (l cos α): the point-mass conical
    /// pendulum's rate, whatever the bob's size.
    pub fn conical_rate(&self, alpha: f64) -> f64 {
        (self.g / (self.length * alpha.cos())).sqrt()
    }

    /// The constants of the motion at a state (θ, θ̇) from the body's pose and angular velocity:
    /// the energy E = ½ ωᵀ I_O ω + m g z_c, the angular momentum about the vertical
    /// L_z = e_z · I_O ω and about the rod L₃ = (R e_z) · I_O ω (I_O the inertia about the pivot in
    /// world axes, z_c the bob's height). L_z is conserved because gravity's torque about the pivot
    /// is horizontal, L₃ because the bob is symmetric about the rod (Euler's equation
    /// I₃ ω̇₃ = (I₁ − I₁) ω₁ ω₂ = 0).
    pub fn invariants(&self, theta: [f64; 3], rate: [f64; 3]) -> [f64; 3] {
        use nalgebra::{Matrix3, Rotation3, Vector3};
        let r = Rotation3::new(Vector3::from(theta)).into_inner();
        let omega = Vector3::from(noether_multibody::frames::exponential_rate(theta, rate));
        let (i1, i3) = self.moments();
        let body = Matrix3::from_diagonal(&Vector3::new(i1, i1, i3));
        let momentum = r * body * r.transpose() * omega;
        let axis = r * Vector3::z();
        let height = -self.length * axis.z;
        [
            0.5 * omega.dot(&momentum) + self.mass * self.g * height,
            momentum.z,
            axis.dot(&momentum),
        ]
    }
}

/// The coin of [`Coin`](crate::coin::Coin) built from a rolling joint: a body of mass m with the
/// moments diag(A, C, A) (the disk's axis along the body's y axis) on `Joint::rolling(a)` on the
/// plane z = 0, gravity −g e_z. Its coordinates are the hand-written coin's (x, y, ψ, θ, φ), and
/// `rolling_contacts()` its two no-slip constraints.
pub fn rolling_coin(coin: &crate::coin::Coin) -> Mechanism {
    let (a, c) = (coin.diametral, coin.axial);
    let disk = Body::new(coin.mass, [0.0; 3], [[a, 0.0, 0.0], [0.0, c, 0.0], [0.0, 0.0, a]]);
    let mut m = Mechanism::new()
        .gravity([0.0, 0.0, -coin.g])
        .expect("finite gravity");
    m.attach(
        Parent::Ground,
        Placement::identity(),
        Joint::rolling(coin.radius),
        disk,
    )
    .expect("a valid disk");
    m
}
