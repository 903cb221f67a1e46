//! Joints: how a body moves relative to the frame it hangs from, with the coordinates that say so,
//! and bodies: mass, centre of mass, inertia.
//!
//! A joint connects a *joint frame* fixed in the parent (its [`Placement`] in the parent's body frame)
//! to the child's body frame, which coincides with the joint frame when the joint's coordinates are
//! zero. A revolute joint turns the child about an axis of the joint frame by its angle q, a prismatic
//! one slides it along an axis by q, a spherical one turns it by a rotation vector (exponential
//! coordinates, [`frames::exponential`]), a free one slides and turns it, a rolling one stands a disk
//! on the joint frame's plane, a fixed one welds it. Springs (V = ½ k (q − q₀)²) and dampers
//! (Q = −c q̇) act on a joint's coordinate when it has one.

use crate::frames::{self, M3, V3};
use noether_core::Scalar;

/// What a joint allows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum JointKind {
    /// Rotation by the angle q about `axis` (of the joint frame; normalised when attached).
    Revolute {
        /// The axis.
        axis: [f64; 3],
    },
    /// Translation by q along `axis` (of the joint frame; normalised when attached).
    Prismatic {
        /// The axis.
        axis: [f64; 3],
    },
    /// Rotation by q₀ about `axis` and translation by q₁ along it (a piston in its cylinder).
    Cylindrical {
        /// The axis.
        axis: [f64; 3],
    },
    /// Motion in the plane normal to `normal`: translation by (q₀, q₁) along the plane's axes e₁, e₂
    /// and rotation by q₂ about the normal n. e₁ is the coordinate axis least aligned with n made
    /// orthogonal to it, e₂ = n × e₁ (for n = z: e₁ = x, e₂ = y).
    Planar {
        /// The plane's normal.
        normal: [f64; 3],
    },
    /// Any rotation about the joint frame's origin (a ball-and-socket joint), in exponential
    /// coordinates: the rotation vector θ = (q₀, q₁, q₂) turns the child by |θ| about θ/|θ|,
    /// R = exp(\[θ\]×). The chart is regular while |θ| < 2π, so it has no pole at the rest position
    /// or anywhere a pendulum swings through; far out it is renewed by
    /// [`Mechanism::rechart`](crate::Mechanism::rechart) (or its event,
    /// [`Mechanism::chart_event`](crate::Mechanism::chart_event)).
    Spherical,
    /// Any motion (a body flying free): translation (q₀, q₁, q₂) along the joint frame's axes, then
    /// the rotation vector (q₃, q₄, q₅) as for [`Spherical`](JointKind::Spherical).
    Free,
    /// A disk of `radius` ρ standing on the joint frame's x-y plane (on its +z side), free to roll,
    /// turn and tilt: coordinates (x, y, ψ, θ, φ), the centre's position along the plane, the heading
    /// ψ of the rolling direction e_r = (cos ψ, sin ψ, 0), the tilt θ of the disk from the vertical
    /// (about e_r) and the spin φ about the disk's axis. The child's frame has its origin at the disk's
    /// centre and the disk's axis along its y axis: R = R_z(ψ) R_x(θ) R_y(φ), the centre at
    /// (x, y, ρ cos θ), so that the lowest point of the rim touches the plane. Rolling without slipping
    /// is two velocity constraints more ([`Mechanism::rolling_contacts`](crate::Mechanism::rolling_contacts)).
    /// The chart is regular while |θ| < π/2 (the disk not lying flat, where ψ and φ turn about the
    /// same axis).
    Rolling {
        /// The disk's radius.
        radius: f64,
    },
    /// No motion: the child is welded to the joint frame.
    Fixed,
}

/// A joint: its kind, with an optional spring and damper on its coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    pub(crate) kind: JointKind,
    pub(crate) stiffness: f64,
    pub(crate) rest: f64,
    pub(crate) damping: f64,
}

impl Joint {
    fn of(kind: JointKind) -> Self {
        Joint {
            kind,
            stiffness: 0.0,
            rest: 0.0,
            damping: 0.0,
        }
    }

    /// A revolute (hinge) joint about `axis`.
    pub fn revolute(axis: [f64; 3]) -> Self {
        Self::of(JointKind::Revolute { axis })
    }

    /// A prismatic (sliding) joint along `axis`.
    pub fn prismatic(axis: [f64; 3]) -> Self {
        Self::of(JointKind::Prismatic { axis })
    }

    /// A cylindrical joint about and along `axis`: coordinates (angle, slide).
    pub fn cylindrical(axis: [f64; 3]) -> Self {
        Self::of(JointKind::Cylindrical { axis })
    }

    /// A planar joint in the plane normal to `normal`: coordinates (x, y, angle) (see
    /// [`JointKind::Planar`] for the plane's axes).
    pub fn planar(normal: [f64; 3]) -> Self {
        Self::of(JointKind::Planar { normal })
    }

    /// A spherical (ball-and-socket) joint: coordinates the rotation vector (see
    /// [`JointKind::Spherical`]).
    pub fn spherical() -> Self {
        Self::of(JointKind::Spherical)
    }

    /// A free joint: coordinates the translation, then the rotation vector (see [`JointKind::Free`]).
    pub fn free() -> Self {
        Self::of(JointKind::Free)
    }

    /// A disk of `radius` rolling on the joint frame's x-y plane: coordinates (x, y, ψ, θ, φ) (see
    /// [`JointKind::Rolling`]; the radius is checked finite and positive when attached).
    pub fn rolling(radius: f64) -> Self {
        Self::of(JointKind::Rolling { radius })
    }

    /// A fixed joint (no coordinates).
    pub fn fixed() -> Self {
        Self::of(JointKind::Fixed)
    }

    /// A spring on the coordinate: V = ½ k (q − q₀)² (checked finite and k ≥ 0 when attached, on a
    /// joint of one coordinate).
    pub fn spring(mut self, stiffness: f64, rest: f64) -> Self {
        self.stiffness = stiffness;
        self.rest = rest;
        self
    }

    /// A damper on the coordinate: Q = −c q̇ (checked finite and c ≥ 0 when attached, on a joint of
    /// one coordinate).
    pub fn damper(mut self, damping: f64) -> Self {
        self.damping = damping;
        self
    }

    /// The kind of joint.
    pub fn kind(&self) -> JointKind {
        self.kind
    }

    /// Its number of coordinates.
    pub fn dof(&self) -> usize {
        match self.kind {
            JointKind::Revolute { .. } | JointKind::Prismatic { .. } => 1,
            JointKind::Cylindrical { .. } => 2,
            JointKind::Planar { .. } | JointKind::Spherical => 3,
            JointKind::Rolling { .. } => 5,
            JointKind::Free => 6,
            JointKind::Fixed => 0,
        }
    }

    /// Whether the joint turns (else it slides or is fixed).
    pub(crate) fn is_revolute(&self) -> bool {
        matches!(self.kind, JointKind::Revolute { .. })
    }

    /// The axis (or the plane's normal), if the joint has one.
    pub(crate) fn axis(&self) -> Option<[f64; 3]> {
        match self.kind {
            JointKind::Revolute { axis }
            | JointKind::Prismatic { axis }
            | JointKind::Cylindrical { axis }
            | JointKind::Planar { normal: axis } => Some(axis),
            JointKind::Spherical | JointKind::Free | JointKind::Rolling { .. } | JointKind::Fixed => None,
        }
    }

    /// The same joint with its axis made a unit vector.
    pub(crate) fn normalised(mut self) -> Self {
        if let JointKind::Revolute { axis }
        | JointKind::Prismatic { axis }
        | JointKind::Cylindrical { axis }
        | JointKind::Planar { normal: axis } = &mut self.kind
        {
            let norm = axis.iter().map(|a| a * a).sum::<f64>().sqrt();
            axis.iter_mut().for_each(|a| *a /= norm);
        }
        self
    }

    /// The child's frame in the joint frame at the coordinates q: rotation and translation.
    pub(crate) fn motion<D: Scalar>(&self, q: &[D]) -> (M3<D>, V3<D>) {
        match self.kind {
            JointKind::Revolute { axis } => (frames::rotation(axis, q[0]), frames::zero()),
            JointKind::Prismatic { axis } => (frames::identity(), frames::scaled(axis, q[0])),
            JointKind::Cylindrical { axis } => (frames::rotation(axis, q[0]), frames::scaled(axis, q[1])),
            JointKind::Planar { normal } => {
                let (e1, e2) = plane_axes(normal);
                let slide = frames::add(frames::scaled(e1, q[0]), frames::scaled(e2, q[1]));
                (frames::rotation(normal, q[2]), slide)
            }
            JointKind::Spherical => (frames::exponential([q[0], q[1], q[2]]), frames::zero()),
            JointKind::Free => (frames::exponential([q[3], q[4], q[5]]), [q[0], q[1], q[2]]),
            JointKind::Rolling { radius } => {
                let heading = frames::rotation(Z, q[2]);
                let tilted = frames::compose(&heading, &frames::rotation(X, q[3]));
                let r = frames::compose(&tilted, &frames::rotation(Y, q[4]));
                (r, [q[0], q[1], q[3].cos() * radius])
            }
            JointKind::Fixed => (frames::identity(), frames::zero()),
        }
    }

    /// The child's angular velocity and the velocity of its origin relative to the joint frame, in
    /// the joint frame, at the rates q̇.
    pub(crate) fn rates<D: Scalar>(&self, q: &[D], v: &[D]) -> (V3<D>, V3<D>) {
        match self.kind {
            JointKind::Revolute { axis } => (frames::scaled(axis, v[0]), frames::zero()),
            JointKind::Prismatic { axis } => (frames::zero(), frames::scaled(axis, v[0])),
            JointKind::Cylindrical { axis } => (frames::scaled(axis, v[0]), frames::scaled(axis, v[1])),
            JointKind::Planar { normal } => {
                let (e1, e2) = plane_axes(normal);
                let slide = frames::add(frames::scaled(e1, v[0]), frames::scaled(e2, v[1]));
                (frames::scaled(normal, v[2]), slide)
            }
            JointKind::Spherical => (frames::exponential_rate(q3(q), q3(v)), frames::zero()),
            JointKind::Free => (frames::exponential_rate(q3(&q[3..]), q3(&v[3..])), q3(v)),
            JointKind::Rolling { radius } => {
                let (sp, cp, st, ct) = (q[2].sin(), q[2].cos(), q[3].sin(), q[3].cos());
                // ω = ψ̇ e_z + θ̇ e_r + φ̇ u, u = cos θ e_a + sin θ e_z the disk's axis,
                // e_r = (cos ψ, sin ψ, 0), e_a = (−sin ψ, cos ψ, 0).
                let spin = v[4] * ct;
                let w = [v[3] * cp - spin * sp, v[3] * sp + spin * cp, v[2] + v[4] * st];
                (w, [v[0], v[1], -(st * v[3]) * radius])
            }
            JointKind::Fixed => (frames::zero(), frames::zero()),
        }
    }

    /// For a rolling joint, the velocity of the material point of the rim touching the plane,
    /// relative to the joint frame: v_c + ω × ρ w, with w = sin θ e_a − cos θ e_z pointing from the
    /// centre to the contact (module docs of [`JointKind::Rolling`]); `None` for other joints.
    pub(crate) fn contact_velocity<D: Scalar>(&self, q: &[D], v: &[D]) -> Option<V3<D>> {
        let JointKind::Rolling { radius } = self.kind else {
            return None;
        };
        let (w, centre) = self.rates(q, v);
        let (sp, cp, st, ct) = (q[2].sin(), q[2].cos(), q[3].sin(), q[3].cos());
        let arm = [-(st * sp) * radius, (st * cp) * radius, -ct * radius];
        Some(frames::add(centre, frames::cross(w, arm)))
    }

    /// Where this joint's rotation vector starts among its coordinates (3 for a free joint, 0 for
    /// a spherical one), if it has one.
    pub(crate) fn rotation_vector(&self) -> Option<usize> {
        match self.kind {
            JointKind::Spherical => Some(0),
            JointKind::Free => Some(3),
            _ => None,
        }
    }
}

/// The coordinate axes.
const X: [f64; 3] = [1.0, 0.0, 0.0];
const Y: [f64; 3] = [0.0, 1.0, 0.0];
const Z: [f64; 3] = [0.0, 0.0, 1.0];

/// The first three entries of a slice as a 3-vector.
fn q3<D: Copy>(x: &[D]) -> [D; 3] {
    [x[0], x[1], x[2]]
}

/// The new coordinates of a rotation vector θ with x = |θ| > π in the other chart of the same
/// rotation, θ' = θ (1 − 2π/x) (|θ'| = 2π − x < π, pointing the other way), and its rate
/// θ̇' = (1 − 2π/x) θ̇ + 2π θ (θ·θ̇)/x³ (the derivative of the map: R and ω are unchanged). `None`
/// while x ≤ π.
pub fn renewed_rotation_vector(theta: [f64; 3], rate: [f64; 3]) -> Option<([f64; 3], [f64; 3])> {
    let x = frames::dot(theta, theta).sqrt();
    if x <= std::f64::consts::PI {
        return None;
    }
    let tau = 2.0 * std::f64::consts::PI;
    let shrink = 1.0 - tau / x;
    let along = tau * frames::dot(theta, rate) / (x * x * x);
    Some((
        theta.map(|t| t * shrink),
        [0, 1, 2].map(|i| shrink * rate[i] + along * theta[i]),
    ))
}

/// The rate θ̇ of a rotation vector θ (|θ| < 2π) at which the rotation exp(\[θ\]×) turns with the
/// angular velocity ω (in the fixed frame): the solution of J(θ) θ̇ = ω
/// ([`frames::exponential_rate`]), by LU with partial pivoting. For setting up initial conditions.
pub fn rotation_vector_rate(theta: [f64; 3], omega: [f64; 3]) -> crate::Result<[f64; 3]> {
    noether_core::error::check_finite("rotation vector", &theta)?;
    noether_core::error::check_finite("angular velocity", &omega)?;
    let x = frames::dot(theta, theta).sqrt();
    let outside = || noether_core::Error::InvalidParameter {
        name: "rotation vector length",
        value: x,
        reason: "below 2π, where exponential coordinates are regular",
    };
    // J(θ) has the singular values 1 and |sin(x/2)/(x/2)| (twice): singular at x = 2π.
    if 2.0 * std::f64::consts::PI - x <= 1e-8 {
        return Err(outside().into());
    }
    let columns = [0, 1, 2].map(|j| {
        let mut e = [0.0; 3];
        e[j] = 1.0;
        frames::exponential_rate(theta, e)
    });
    let jacobian = nalgebra::Matrix3::from_fn(|i, j| columns[j][i]);
    let rate = jacobian.lu().solve(&nalgebra::Vector3::from(omega));
    rate.map(|r| [r[0], r[1], r[2]]).ok_or_else(|| outside().into())
}

/// The in-plane axes (e₁, e₂) of a planar joint with unit normal n: e₁ the coordinate axis least
/// aligned with n, made orthogonal to it and normalised; e₂ = n × e₁.
pub(crate) fn plane_axes(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let k = (0..3)
        .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .unwrap_or(0);
    let mut e1 = [0.0; 3];
    e1[k] = 1.0;
    let along = n[k];
    let e1: [f64; 3] = std::array::from_fn(|i| e1[i] - along * n[i]);
    let norm = e1.iter().map(|x| x * x).sum::<f64>().sqrt();
    let e1 = e1.map(|x| x / norm);
    let e2 = [
        n[1] * e1[2] - n[2] * e1[1],
        n[2] * e1[0] - n[0] * e1[2],
        n[0] * e1[1] - n[1] * e1[0],
    ];
    (e1, e2)
}

/// Where a joint frame sits in its parent's body frame (or in the world, for the ground): a rotation
/// and a translation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    pub(crate) rotation: [[f64; 3]; 3],
    pub(crate) translation: [f64; 3],
}

impl Placement {
    /// The parent's own frame.
    pub fn identity() -> Self {
        Placement {
            rotation: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            translation: [0.0; 3],
        }
    }

    /// The parent's axes, moved to the point `at` of the parent's frame.
    pub fn at(at: [f64; 3]) -> Self {
        Placement {
            translation: at,
            ..Self::identity()
        }
    }

    /// This placement turned by `angle` about the unit `axis` (of the placement's own frame).
    pub fn rotated(self, axis: [f64; 3], angle: f64) -> Self {
        let turn = frames::rotation(axis, angle);
        Placement {
            rotation: frames::compose_const(&self.rotation, &turn),
            ..self
        }
    }
}

/// A rigid body: its mass, its centre of mass in its body frame and its inertia tensor about the
/// centre of mass in body axes. Point masses (zero inertia) and thin rods (an axis of zero moment) are
/// bodies too.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    pub(crate) mass: f64,
    pub(crate) centre: [f64; 3],
    pub(crate) inertia: [[f64; 3]; 3],
}

impl Body {
    /// A body of `mass` with its centre of mass at `centre` and the inertia tensor `inertia` about it
    /// (checked when attached: symmetric, its principal moments at least 0 and each at most the sum of
    /// the other two).
    pub fn new(mass: f64, centre: [f64; 3], inertia: [[f64; 3]; 3]) -> Self {
        Body {
            mass,
            centre,
            inertia,
        }
    }

    /// A point mass at `at`.
    pub fn point(mass: f64, at: [f64; 3]) -> Self {
        Self::new(mass, at, [[0.0; 3]; 3])
    }

    /// A uniform thin rod of `mass` from `from` to `to`: centre at the midpoint, inertia
    /// (m ℓ²/12)(I − e eᵀ) about it, e the rod's unit direction and ℓ its length.
    pub fn rod(mass: f64, from: [f64; 3], to: [f64; 3]) -> Self {
        let d: [f64; 3] = std::array::from_fn(|i| to[i] - from[i]);
        let length2 = d.iter().map(|x| x * x).sum::<f64>();
        let k = mass / 12.0;
        let inertia = std::array::from_fn(|i| {
            std::array::from_fn(|j| k * (if i == j { length2 } else { 0.0 } - d[i] * d[j]))
        });
        Self::new(mass, std::array::from_fn(|i| 0.5 * (from[i] + to[i])), inertia)
    }

    /// A frame without mass (a link that only carries others).
    pub fn massless() -> Self {
        Self::point(0.0, [0.0; 3])
    }

    /// The mass.
    pub fn mass(&self) -> f64 {
        self.mass
    }
}
