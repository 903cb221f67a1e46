//! A kinematic tree of bodies and joints, and the Lagrangian it has.
//!
//! Bodies are attached in order, each by a [`Joint`] to the ground or to a body attached before it;
//! the coordinates q are the joints' coordinates in that order. For given (q, q̇) one pass from the
//! root outwards forms every body's orientation R_b, origin p_b, angular velocity ω_b and origin
//! velocity v_b in the world frame: with P the parent's (R, p, ω, v), (R₀, t₀) the joint's placement
//! in the parent, (R_j, t_j) the joint's motion and (ω_j, v_j) its rates in the joint frame,
//!
//! ```text
//! R = R_P R₀ R_j,   p = p_P + R_P (t₀ + R₀ t_j),
//! ω = ω_P + R_P R₀ ω_j,   v = v_P + ω_P × (p − p_P) + R_P R₀ v_j,
//! ```
//!
//! and the centre of mass c = p + R c_b moves at v + ω × R c_b. Then
//!
//! ```text
//! L = Σ_b [ ½ m_b |ċ_b|² + ½ (Rᵀω)·I_b (Rᵀω) + m_b g·c_b ] − Σ_joints ½ k (q − q₀)²,
//! ```
//!
//! with I_b the inertia about the centre of mass in body axes and g the gravity vector. All of it is
//! generic code over the scalar, so Lagrange's equations, their Jacobians, variational integrators,
//! linearisations and tangents take exact derivatives of it like of any hand-written L. Joint
//! dampers enter as the generalized force −c q̇, and joints named by [`Mechanism::actuate`] take the
//! inputs u as forces or torques on their coordinates ([`Actuated`]).

use crate::frames::{self, M3, V3};
use crate::joint::{Body, Joint, JointKind, Placement};
use crate::{Error, Result};
use nalgebra::{Matrix3, Vector3};
use noether_core::control::Actuated;
use noether_core::error::{check_finite, check_len};
use noether_core::{Event, Lagrangian, Scalar, State, Velocities};

/// A body of a [`Mechanism`], by the order in which it was attached.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct BodyId(pub usize);

/// What a body is attached to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Parent {
    /// The fixed world frame.
    Ground,
    /// A body attached before.
    Body(BodyId),
}

impl From<BodyId> for Parent {
    fn from(b: BodyId) -> Self {
        Parent::Body(b)
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Node {
    pub(crate) parent: Parent,
    pub(crate) placement: Placement,
    pub(crate) joint: Joint,
    pub(crate) body: Body,
    /// The index of the joint's first coordinate in q.
    pub(crate) offset: usize,
}

/// A kinematic tree of rigid bodies and joints under uniform gravity: a [`Lagrangian`] (module docs).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mechanism {
    nodes: Vec<Node>,
    gravity: [f64; 3],
    dof: usize,
    /// The coordinates the inputs act on, in input order.
    actuated: Vec<usize>,
    /// The joints that close loops ([`close_loop`](Self::close_loop)).
    pub(crate) closures: Vec<crate::closure::Closure>,
    /// Springs and dampers between points ([`spring`](Self::spring), [`damper`](Self::damper)).
    pub(crate) connections: Vec<crate::connections::Connection>,
}

/// A body's pose and velocity in the world frame.
pub(crate) struct Moving<D> {
    pub(crate) r: M3<D>,
    pub(crate) p: V3<D>,
    pub(crate) w: V3<D>,
    pub(crate) v: V3<D>,
}

impl Mechanism {
    /// An empty mechanism without gravity.
    pub fn new() -> Self {
        Self::default()
    }

    /// Uniform gravity g (a vector in the world frame: (0, 0, −9.81) pulls down along z).
    pub fn gravity(mut self, g: [f64; 3]) -> Result<Self> {
        check_finite("gravity", &g)?;
        self.gravity = g;
        Ok(self)
    }

    /// Attaches `body` to `parent` by `joint`, whose frame sits at `placement` in the parent's body
    /// frame; returns the new body. Errors: an unknown parent, a zero or non-finite axis, a spring or
    /// damper constant that is negative or not finite, a negative or non-finite mass, an inertia
    /// tensor no rigid body has (not symmetric, a negative moment, a moment above the sum of the other
    /// two).
    pub fn attach(
        &mut self,
        parent: impl Into<Parent>,
        placement: Placement,
        joint: Joint,
        body: Body,
    ) -> Result<BodyId> {
        let (parent, id) = (parent.into(), self.nodes.len());
        self.check_parent(parent, id)?;
        let flat = |m: &[[f64; 3]; 3]| m.iter().flatten().copied().collect::<Vec<_>>();
        check_finite("placement rotation", &flat(&placement.rotation))?;
        check_finite("placement translation", &placement.translation)?;
        if let Some(axis) = joint.axis() {
            if !axis.iter().all(|a| a.is_finite()) || axis.iter().all(|a| *a == 0.0) {
                return Err(Error::Axis { body: id, axis });
            }
        }
        if let JointKind::Rolling { radius } = joint.kind {
            if !(radius.is_finite() && radius > 0.0) {
                return Err(noether_core::Error::InvalidParameter {
                    name: "rolling radius",
                    value: radius,
                    reason: "finite and positive",
                }
                .into());
            }
        }
        for (name, value) in [
            ("joint stiffness", joint.stiffness),
            ("joint damping", joint.damping),
        ] {
            let needs_coordinate = value != 0.0 && joint.dof() != 1;
            if !(value.is_finite() && value >= 0.0) || needs_coordinate {
                return Err(noether_core::Error::InvalidParameter {
                    name,
                    value,
                    reason: "finite and at least 0, on a joint with one coordinate",
                }
                .into());
            }
        }
        check_finite("joint spring rest position", &[joint.rest])?;
        check_body(id, &body)?;
        self.nodes.push(Node {
            parent,
            placement,
            joint: joint.normalised(),
            body,
            offset: self.dof,
        });
        self.dof += joint.dof();
        Ok(BodyId(id))
    }

    /// Makes the coordinates of `body`'s joint inputs: a force (a slide) or torque (a turn) u on
    /// each, in the order of the calls (on a spherical or free joint's rotation vector, the
    /// generalized forces conjugate to θ, Q = Jᵀ τ for a torque τ in the joint frame). Errors: an
    /// unknown body (`UnknownBody`), a joint already actuated or without coordinates
    /// (`InvalidParameter`).
    pub fn actuate(&mut self, body: BodyId) -> Result<()> {
        let node = self.node(body)?;
        let range = node.offset..node.offset + node.joint.dof();
        if range.is_empty() || self.actuated.contains(&range.start) {
            return Err(noether_core::Error::InvalidParameter {
                name: "actuated body",
                value: body.0 as f64,
                reason: "a body whose joint has coordinates, actuated once",
            }
            .into());
        }
        self.actuated.extend(range);
        Ok(())
    }

    /// The number of bodies.
    pub fn bodies(&self) -> usize {
        self.nodes.len()
    }

    /// The coordinates of `body`'s joint: indices into q.
    pub fn coordinates(&self, body: BodyId) -> Result<std::ops::Range<usize>> {
        let node = self.node(body)?;
        Ok(node.offset..node.offset + node.joint.dof())
    }

    /// `UnknownParent` unless `parent` is the ground or one of the bodies attached so far (`body` is the
    /// index the error names).
    pub(crate) fn check_parent(&self, parent: Parent, body: usize) -> Result<()> {
        match parent {
            Parent::Body(BodyId(p)) if p >= self.nodes.len() => Err(Error::UnknownParent {
                body,
                parent: p,
                bodies: self.nodes.len(),
            }),
            _ => Ok(()),
        }
    }

    fn node(&self, body: BodyId) -> Result<&Node> {
        self.nodes.get(body.0).ok_or(Error::UnknownBody {
            body: body.0,
            bodies: self.nodes.len(),
        })
    }

    /// Where in q the rotation vectors of the spherical and free joints start.
    fn rotation_vectors(&self) -> Vec<usize> {
        self.nodes
            .iter()
            .filter_map(|n| n.joint.rotation_vector().map(|k| n.offset + k))
            .collect()
    }

    /// Renews the chart of every spherical or free joint whose rotation vector has left the ball
    /// |θ| ≤ π: θ becomes θ (1 − 2π/|θ|), the same rotation with |θ'| = 2π − |θ| < π, and θ̇ changes
    /// with it so that every body's motion is the same
    /// ([`renewed_rotation_vector`](crate::joint::renewed_rotation_vector)). Returns how many joints it
    /// renewed. Exponential coordinates are regular for |θ| < 2π; call this (or run with
    /// [`chart_event`](Self::chart_event)) before a joint turns that far. Errors: q, q̇ of the wrong
    /// length or not finite.
    pub fn rechart(&self, q: &mut [f64], v: &mut [f64]) -> Result<usize> {
        noether_core::error::check_phase_point(self.dof, 0.0, q, v, "q̇")?;
        Ok(renew(&self.rotation_vectors(), q, v))
    }

    /// An event for the [`Driver`](noether_core::Driver) that keeps the spherical and free joints in
    /// the regular part of their chart: g = max_j |θ_j| − 3π/2 rises through zero when a rotation
    /// vector reaches 3π/2 (where the smallest singular value of its Jacobian,
    /// sin(3π/4)/(3π/4) = 0.30, is still far from the singularity at 2π), and the reset
    /// [`rechart`](Self::rechart)s, which brings it back to π/2. Named `"rechart"`; without such
    /// joints g = −3π/2 and it never fires. It fires on crossings: start the run inside (every
    /// |θ| ≤ π, which [`rechart`](Self::rechart) of the initial state ensures).
    pub fn chart_event(&self) -> Event<'static, Velocities> {
        let starts = self.rotation_vectors();
        let watched = starts.clone();
        let limit = 1.5 * std::f64::consts::PI;
        Event::new("rechart", move |s: &State| {
            watched
                .iter()
                .map(|&k| (s.q[k].powi(2) + s.q[k + 1].powi(2) + s.q[k + 2].powi(2)).sqrt())
                .fold(0.0, f64::max)
                - limit
        })
        .rising()
        .reset(move |s: &mut State| {
            renew(&starts, s.q.as_mut_slice(), s.v.as_mut_slice());
        })
    }

    /// The orientation R and the origin p of `body`'s frame in the world at the configuration q.
    pub fn pose(&self, body: BodyId, q: &[f64]) -> Result<(Matrix3<f64>, Vector3<f64>)> {
        check_len("q", q, self.dof)?;
        check_finite("q", q)?;
        self.node(body)?;
        let (r, p) = self.poses(q)[body.0];
        Ok((Matrix3::from_fn(|i, j| r[i][j]), Vector3::from(p)))
    }

    /// Every body's orientation and origin at q, root outwards (the positions of
    /// [`forward`](Self::forward) without its velocities).
    pub(crate) fn poses<D: Scalar>(&self, q: &[D]) -> Vec<(M3<D>, V3<D>)> {
        let mut out: Vec<(M3<D>, V3<D>)> = Vec::with_capacity(self.nodes.len());
        for node in &self.nodes {
            let parent = match node.parent {
                Parent::Ground => (frames::identity(), frames::zero()),
                Parent::Body(BodyId(p)) => out[p],
            };
            let (_, r, p) = self.place(node, &parent, q);
            out.push((r, p));
        }
        out
    }

    /// A body's joint frame orientation R_P R₀ in the world, and its own orientation R and origin p,
    /// from its parent's (R_P, p_P) and the configuration q (module docs).
    fn place<D: Scalar>(&self, node: &Node, (pr, pp): &(M3<D>, V3<D>), q: &[D]) -> (M3<D>, M3<D>, V3<D>) {
        let (rj, tj) = node.joint.motion(&q[node.offset..node.offset + node.joint.dof()]);
        let placed = frames::compose_const(pr, &node.placement.rotation);
        let origin = frames::add(*pp, frames::apply_const(pr, node.placement.translation));
        let p = frames::add(origin, frames::apply(&placed, tj));
        (placed, frames::compose(&placed, &rj), p)
    }

    /// Why the recursive algorithms on f64 ([`NewtonEuler`](crate::NewtonEuler),
    /// [`ArticulatedBody`](crate::ArticulatedBody)) cannot run this mechanism, if they cannot: a loop
    /// closure (it needs its constraints), a joint of several coordinates or springs and dampers
    /// between points (Lagrange's equations take both). `None` for a tree of revolute, prismatic and
    /// fixed joints.
    pub(crate) fn recursive_refusal(&self) -> Option<noether_core::Error> {
        let reason = if self.closure_count() > 0 {
            "the recursive algorithms (Newton-Euler, articulated body) for a mechanism with loop closures (use Constrained or Rattle)"
        } else if self
            .nodes
            .iter()
            .any(|n| n.joint.dof() > 1 || n.joint.rotation_vector().is_some())
        {
            "the recursive algorithms (Newton-Euler, articulated body) for joints of more than one coordinate (use EulerLagrange)"
        } else if self.has_connections() {
            "the recursive algorithms (Newton-Euler, articulated body) with springs or dampers between points (use EulerLagrange)"
        } else {
            return None;
        };
        Some(noether_core::Error::Unsupported(reason))
    }

    /// The bodies in the order of attachment.
    pub(crate) fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The gravity vector g.
    pub(crate) fn gravity_vector(&self) -> [f64; 3] {
        self.gravity
    }

    /// Body `i`'s joint axis in the world (R_i a: a turn about a or a slide along it leaves a where it
    /// is) and the index of its coordinate, for a joint with an axis.
    pub(crate) fn world_axis(&self, i: usize, frames: &[Moving<f64>]) -> Option<([f64; 3], usize)> {
        let node = &self.nodes[i];
        node.joint
            .axis()
            .map(|a| (frames::apply_const(&frames[i].r, a), node.offset))
    }

    /// The joints' springs and dampers as generalized forces, −k (q − q₀) − c q̇, into `out`.
    pub(crate) fn joint_forces(&self, q: &[f64], v: &[f64], out: &mut [f64]) {
        out.fill(0.0);
        for n in self.nodes.iter().filter(|n| n.joint.dof() == 1) {
            let k = n.offset;
            out[k] = -n.joint.stiffness * (q[k] - n.joint.rest) - n.joint.damping * v[k];
        }
    }

    /// Every body's pose and velocity at (q, q̇), root outwards (module docs).
    pub(crate) fn forward<D: Scalar>(&self, q: &[D], v: &[D]) -> Vec<Moving<D>> {
        let mut out: Vec<Moving<D>> = Vec::with_capacity(self.nodes.len());
        for node in &self.nodes {
            let (pose, w_p, v_p) = match node.parent {
                Parent::Ground => (
                    (frames::identity(), frames::zero()),
                    frames::zero(),
                    frames::zero(),
                ),
                Parent::Body(BodyId(b)) => ((out[b].r, out[b].p), out[b].w, out[b].v),
            };
            let (placed, r, p) = self.place(node, &pose, q);
            let own = node.offset..node.offset + node.joint.dof();
            let (wj, vj) = node.joint.rates(&q[own.clone()], &v[own]);
            out.push(Moving {
                r,
                w: frames::add(w_p, frames::apply(&placed, wj)),
                v: frames::add(
                    frames::add(v_p, frames::cross(w_p, frames::sub(p, pose.1))),
                    frames::apply(&placed, vj),
                ),
                p,
            });
        }
        out
    }
}

/// Renews every rotation vector starting at one of `starts` in q whose length is above π
/// ([`renewed_rotation_vector`](crate::joint::renewed_rotation_vector)); returns how many.
fn renew(starts: &[usize], q: &mut [f64], v: &mut [f64]) -> usize {
    let mut renewed = 0;
    for &k in starts {
        let (theta, rate) = ([q[k], q[k + 1], q[k + 2]], [v[k], v[k + 1], v[k + 2]]);
        if let Some((theta, rate)) = crate::joint::renewed_rotation_vector(theta, rate) {
            q[k..k + 3].copy_from_slice(&theta);
            v[k..k + 3].copy_from_slice(&rate);
            renewed += 1;
        }
    }
    renewed
}

/// A body's data checked (the variant of [`Error`] says what is wrong).
fn check_body(id: usize, body: &Body) -> Result<()> {
    if !(body.mass.is_finite() && body.mass >= 0.0) {
        return Err(Error::Mass {
            body: id,
            mass: body.mass,
        });
    }
    check_finite("centre of mass", &body.centre)?;
    let j = Matrix3::from_fn(|i, k| body.inertia[i][k]);
    check_finite("inertia tensor", j.as_slice())?;
    let scale = j.amax().max(f64::MIN_POSITIVE);
    let bad = |reason, value| {
        Err(Error::Inertia {
            body: id,
            reason,
            value,
        })
    };
    let asymmetry = (j - j.transpose()).amax() / scale;
    if asymmetry > 1e-12 {
        return bad("is not symmetric", asymmetry);
    }
    let moments = j.symmetric_eigen().eigenvalues;
    let (smallest, total) = (moments.min(), moments.sum());
    if smallest < -1e-12 * scale {
        return bad("has a negative principal moment", smallest / scale);
    }
    let excess = moments
        .iter()
        .map(|m| 2.0 * m - total)
        .fold(f64::NEG_INFINITY, f64::max)
        / scale;
    if excess > 1e-12 {
        return bad("has a principal moment above the sum of the other two", excess);
    }
    Ok(())
}

impl Lagrangian for Mechanism {
    fn dof(&self) -> usize {
        self.dof
    }

    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let frames = self.forward(q, v);
        let gravity = self.gravity.map(D::from);
        let mut l = D::zero();
        for (node, f) in self.nodes.iter().zip(&frames) {
            let body = &node.body;
            let arm = frames::apply_const(&f.r, body.centre);
            let centre_velocity = frames::add(f.v, frames::cross(f.w, arm));
            let spin = frames::apply_transpose(&f.r, f.w);
            let momentum = angular_momentum(&body.inertia, spin);
            let height = frames::dot(frames::add(f.p, arm), gravity);
            l += (frames::dot(centre_velocity, centre_velocity) * body.mass + frames::dot(spin, momentum))
                * 0.5
                + height * body.mass;
            if node.joint.stiffness != 0.0 {
                let stretch = q[node.offset] - node.joint.rest;
                l -= stretch * stretch * (0.5 * node.joint.stiffness);
            }
        }
        l - self.connection_energy(&frames)
    }

    fn has_generalized_force(&self) -> bool {
        self.nodes.iter().any(|n| n.joint.damping != 0.0) || self.has_point_dampers()
    }

    /// The joints' dampers, Q = −c q̇ on each damped coordinate, and the dampers between points
    /// ([`connections`](crate::connections)).
    fn generalized_force<D: Scalar>(&self, _t: D, q: &[D], v: &[D], out: &mut [D]) {
        out.fill(D::zero());
        for n in self.nodes.iter().filter(|n| n.joint.damping != 0.0) {
            out[n.offset] = -v[n.offset] * n.joint.damping;
        }
        if self.has_point_dampers() {
            self.add_damper_forces(q, &self.forward(q, v), out);
        }
    }
}

/// The inputs act on the coordinates of the joints named by [`Mechanism::actuate`]: Q_u = u there.
impl Actuated for Mechanism {
    fn inputs(&self) -> usize {
        self.actuated.len()
    }

    fn input_force<D: Scalar>(&self, _t: D, _q: &[D], _v: &[D], u: &[D], out: &mut [D]) {
        out.fill(D::zero());
        for (&c, &uk) in self.actuated.iter().zip(u) {
            out[c] += uk;
        }
    }
}

/// I ω in the body frame, (I ω)_i = Σ_k I_ik ω_k summed from zero in the order k = 0, 1, 2 (a function
/// of D alone, not of the model: no closure instantiated per model and dual type).
fn angular_momentum<D: Scalar>(inertia: &[[f64; 3]; 3], spin: V3<D>) -> V3<D> {
    let mut l = [D::zero(); 3];
    for (li, row) in l.iter_mut().zip(inertia) {
        *li = D::zero() + spin[0] * row[0] + spin[1] * row[1] + spin[2] * row[2];
    }
    l
}
