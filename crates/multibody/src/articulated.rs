//! Forward dynamics of a tree by the articulated-body algorithm: q̈ from (q, q̇, τ) in O(n) per call,
//! on plain f64, without forming or factoring the mass matrix.
//!
//! In Featherstone's spatial notation (*Rigid Body Dynamics Algorithms*, 2008, §7.3 and Table 7.1;
//! vectors (angular; linear), each body's in its own frame), with ^iX_λ the transform from the parent
//! λ(i)'s frame to body i's, S_i the joint's motion subspace, I_i the body's spatial inertia about its
//! origin and a₀ = (0; −g) (gravity as an upward acceleration of the ground):
//!
//! ```text
//! outwards: v_i = ^iX_λ v_λ + S_i q̇_i,   c_i = v_i × S_i q̇_i,   I^A_i = I_i,   p^A_i = v_i ×* I_i v_i,
//! inwards:  U_i = I^A_i S_i,   D_i = S_iᵀ U_i,   u_i = τ_i − S_iᵀ p^A_i,
//!           I^a = I^A_i − U_i U_iᵀ / D_i,   p^a = p^A_i + I^a c_i + U_i u_i / D_i,
//!           I^A_λ += ^iX_λᵀ I^a ^iX_λ,   p^A_λ += ^iX_λᵀ p^a,
//! outwards: a'_i = ^iX_λ a_λ + c_i,   q̈_i = (u_i − U_iᵀ a'_i) / D_i,   a_i = a'_i + S_i q̈_i,
//! ```
//!
//! τ the joints' springs and dampers. A fixed joint has no S: its body's articulated inertia and bias
//! pass to the parent whole. The motion is Lagrange's equations of the [`Mechanism`]'s L (checked
//! against them and against [`NewtonEuler`](crate::NewtonEuler) in the tests; `benches/` compares
//! the three and a hand-written algorithm).

use crate::joint::JointKind;
use crate::mechanism::{Mechanism, Parent};
use crate::Result;
use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};
use noether_core::error::{check_len, check_phase_point, check_result};
use noether_core::{Dynamics, Velocities};

/// What a joint lets its body do, in the body's own frame, with the index of its coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Freedom {
    Turn(Vector3<f64>, usize),
    Slide(Vector3<f64>, usize),
    Weld,
}

/// A body with what the algorithm needs of it, fixed when built.
#[derive(Debug, Clone, PartialEq)]
struct Link {
    parent: Option<usize>,
    /// The joint frame's axes in the parent's frame (R₀) and its origin there (t₀).
    rotation: Matrix3<f64>,
    origin: Vector3<f64>,
    freedom: Freedom,
    /// The spatial inertia about the body's origin in its frame,
    /// [[I_c + m c× c×ᵀ, m c×], [m c×ᵀ, m 1]].
    inertia: Matrix6<f64>,
}

/// A tree [`Mechanism`] of revolute, prismatic and fixed joints stepped by the articulated-body
/// algorithm (module docs): a core [`Dynamics`] on (q, q̇), with the inputs (if any) at zero.
#[derive(Debug, Clone, PartialEq)]
pub struct ArticulatedBody {
    mechanism: Mechanism,
    links: Vec<Link>,
    gravity: Vector3<f64>,
}

/// The transform from a parent's frame to a child's: E the child's axes seen from the parent's
/// (coordinates parent → child), r the child's origin in the parent's frame.
struct Transform {
    e: Matrix3<f64>,
    r: Vector3<f64>,
}

impl Transform {
    /// X m for a motion vector m = (ω; v): (E ω; E (v − r × ω)).
    fn motion(&self, m: &Vector6<f64>) -> Vector6<f64> {
        let (w, v) = (m.fixed_rows::<3>(0), m.fixed_rows::<3>(3));
        let w2 = self.e * w;
        let v2 = self.e * (v - self.r.cross(&w));
        Vector6::new(w2.x, w2.y, w2.z, v2.x, v2.y, v2.z)
    }

    /// Xᵀ f for a force f = (n; f) of the child's, in the parent's frame: (Eᵀ n + r × Eᵀ f; Eᵀ f).
    fn force_back(&self, f: &Vector6<f64>) -> Vector6<f64> {
        let (n, f) = (f.fixed_rows::<3>(0), f.fixed_rows::<3>(3));
        let f2 = self.e.transpose() * f;
        let n2 = self.e.transpose() * n + self.r.cross(&f2);
        Vector6::new(n2.x, n2.y, n2.z, f2.x, f2.y, f2.z)
    }

    /// Xᵀ I X: a child's articulated inertia seen from the parent.
    fn inertia_back(&self, inertia: &Matrix6<f64>) -> Matrix6<f64> {
        let mut x = Matrix6::zeros();
        let er = -self.e * self.r.cross_matrix();
        x.fixed_view_mut::<3, 3>(0, 0).copy_from(&self.e);
        x.fixed_view_mut::<3, 3>(3, 3).copy_from(&self.e);
        x.fixed_view_mut::<3, 3>(3, 0).copy_from(&er);
        x.transpose() * inertia * x
    }
}

/// m₁ ×  m₂ for motion vectors: (ω × ω₂; ω × v₂ + v × ω₂).
fn cross_motion(m: &Vector6<f64>, other: &Vector6<f64>) -> Vector6<f64> {
    let (w, v) = (m.fixed_rows::<3>(0), m.fixed_rows::<3>(3));
    let (w2, v2) = (other.fixed_rows::<3>(0), other.fixed_rows::<3>(3));
    let a = w.cross(&w2);
    let b = w.cross(&v2) + v.cross(&w2);
    Vector6::new(a.x, a.y, a.z, b.x, b.y, b.z)
}

/// m ×* f for a motion m and a force f: (ω × n + v × f; ω × f).
fn cross_force(m: &Vector6<f64>, f: &Vector6<f64>) -> Vector6<f64> {
    let (w, v) = (m.fixed_rows::<3>(0), m.fixed_rows::<3>(3));
    let (n, f) = (f.fixed_rows::<3>(0), f.fixed_rows::<3>(3));
    let a = w.cross(&n) + v.cross(&f);
    let b = w.cross(&f);
    Vector6::new(a.x, a.y, a.z, b.x, b.y, b.z)
}

impl ArticulatedBody {
    /// The tree `mechanism`. Errors (`Unsupported`): loop closures (use noether-constraints'
    /// `Constrained` or `Rattle`), a joint of more than one coordinate (cylindrical, planar,
    /// spherical, free, rolling), or springs or dampers between points (Lagrange's equations take
    /// both).
    pub fn new(mechanism: Mechanism) -> Result<Self> {
        if let Some(refusal) = mechanism.recursive_refusal() {
            return Err(refusal.into());
        }
        let mut links = Vec::with_capacity(mechanism.bodies());
        for node in mechanism.nodes() {
            let k = node.offset;
            let freedom = match node.joint.kind() {
                // The axis was normalised when the body was attached.
                JointKind::Revolute { axis } => Freedom::Turn(Vector3::from(axis), k),
                JointKind::Prismatic { axis } => Freedom::Slide(Vector3::from(axis), k),
                JointKind::Fixed => Freedom::Weld,
                JointKind::Cylindrical { .. }
                | JointKind::Planar { .. }
                | JointKind::Spherical
                | JointKind::Free
                | JointKind::Rolling { .. } => {
                    return Err(noether_core::Error::Unsupported(
                        "the articulated-body algorithm for joints of more than one coordinate (use EulerLagrange)",
                    )
                    .into())
                }
            };
            let body = &node.body;
            let c = Vector3::from(body.centre);
            let cx = c.cross_matrix();
            let inertia_c = Matrix3::from_fn(|i, j| body.inertia[i][j]);
            let mut inertia = Matrix6::zeros();
            inertia
                .fixed_view_mut::<3, 3>(0, 0)
                .copy_from(&(inertia_c + cx * cx.transpose() * body.mass));
            inertia.fixed_view_mut::<3, 3>(0, 3).copy_from(&(cx * body.mass));
            inertia
                .fixed_view_mut::<3, 3>(3, 0)
                .copy_from(&(cx.transpose() * body.mass));
            inertia
                .fixed_view_mut::<3, 3>(3, 3)
                .copy_from(&(Matrix3::identity() * body.mass));
            links.push(Link {
                parent: match node.parent {
                    Parent::Ground => None,
                    Parent::Body(b) => Some(b.0),
                },
                rotation: Matrix3::from_fn(|i, j| node.placement.rotation[i][j]),
                origin: Vector3::from(node.placement.translation),
                freedom,
                inertia,
            });
        }
        let gravity = Vector3::from(mechanism.gravity_vector());
        Ok(ArticulatedBody {
            mechanism,
            links,
            gravity,
        })
    }

    /// The mechanism.
    pub fn mechanism(&self) -> &Mechanism {
        &self.mechanism
    }

    /// The transform from link `l`'s parent to it at the coordinates q.
    fn transform(l: &Link, q: &[f64]) -> Transform {
        let (turn, slide) = match l.freedom {
            Freedom::Turn(a, k) => (
                nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_unchecked(a), q[k]).into_inner(),
                Vector3::zeros(),
            ),
            Freedom::Slide(a, k) => (Matrix3::identity(), a * q[k]),
            Freedom::Weld => (Matrix3::identity(), Vector3::zeros()),
        };
        let r = l.rotation * turn;
        Transform {
            e: r.transpose(),
            r: l.origin + l.rotation * slide,
        }
    }
}

/// S for a link (zero for a weld) and its coordinate.
fn subspace(f: Freedom) -> Option<(Vector6<f64>, usize)> {
    match f {
        Freedom::Turn(a, k) => Some((Vector6::new(a.x, a.y, a.z, 0.0, 0.0, 0.0), k)),
        Freedom::Slide(a, k) => Some((Vector6::new(0.0, 0.0, 0.0, a.x, a.y, a.z), k)),
        Freedom::Weld => None,
    }
}

/// What the passes keep of one body.
struct Pass {
    x: Transform,
    v: Vector6<f64>,
    c: Vector6<f64>,
    ia: Matrix6<f64>,
    pa: Vector6<f64>,
    u: Vector6<f64>,
    d: f64,
    torque: f64,
    a: Vector6<f64>,
}

impl Dynamics for ArticulatedBody {
    type Partner = Velocities;

    fn dof(&self) -> usize {
        noether_core::Lagrangian::dof(&self.mechanism)
    }

    /// q̇ = v and q̈ by the three passes (module docs).
    fn rates(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        dq: &mut [f64],
        dv: &mut [f64],
    ) -> noether_core::Result<()> {
        let n = self.dof();
        check_phase_point(n, t, q, v, "q̇")?;
        check_len("q̈ (output)", dv, n)?;
        self.mechanism.joint_forces(q, v, dv);
        let mut passes: Vec<Pass> = Vec::with_capacity(self.links.len());
        for l in &self.links {
            let x = Self::transform(l, q);
            let carried = l.parent.map_or(Vector6::zeros(), |p| x.motion(&passes[p].v));
            let joint = subspace(l.freedom).map_or(Vector6::zeros(), |(s, k)| s * v[k]);
            let vel = carried + joint;
            let momentum = l.inertia * vel;
            passes.push(Pass {
                c: cross_motion(&vel, &joint),
                ia: l.inertia,
                pa: cross_force(&vel, &momentum),
                x,
                v: vel,
                u: Vector6::zeros(),
                d: 0.0,
                torque: 0.0,
                a: Vector6::zeros(),
            });
        }
        for i in (0..self.links.len()).rev() {
            let l = &self.links[i];
            let p = &mut passes[i];
            let (ia, pa) = match subspace(l.freedom) {
                Some((s, k)) => {
                    p.u = p.ia * s;
                    p.d = s.dot(&p.u);
                    p.torque = dv[k] - s.dot(&p.pa);
                    let ia = p.ia - p.u * p.u.transpose() / p.d;
                    let pa = p.pa + ia * p.c + p.u * (p.torque / p.d);
                    (ia, pa)
                }
                None => (p.ia, p.pa + p.ia * p.c),
            };
            if let Some(parent) = l.parent {
                let (ia, pa) = (p.x.inertia_back(&ia), p.x.force_back(&pa));
                passes[parent].ia += ia;
                passes[parent].pa += pa;
            }
        }
        let fall = Vector6::new(0.0, 0.0, 0.0, -self.gravity.x, -self.gravity.y, -self.gravity.z);
        for i in 0..self.links.len() {
            let l = &self.links[i];
            let from = l.parent.map_or(fall, |p| passes[p].a);
            let p = &passes[i];
            let mut a = p.x.motion(&from) + p.c;
            if let Some((s, k)) = subspace(l.freedom) {
                dv[k] = (p.torque - p.u.dot(&a)) / p.d;
                a += s * dv[k];
            }
            passes[i].a = a;
        }
        dq.copy_from_slice(v);
        check_result("articulated-body accelerations", t, dv)
    }

    /// The energy T + V (h of the mechanism's L, whose kinetic energy is quadratic in q̇).
    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> noether_core::Result<f64> {
        noether_core::EulerLagrange::new(&self.mechanism).energy(t, q, v)
    }

    fn position_rates(&self, _t: f64, _q: &[f64], v: &[f64], dq: &mut [f64]) -> noether_core::Result<()> {
        check_len("q̇", v, self.dof())?;
        dq.copy_from_slice(v);
        Ok(())
    }
}

/// A mechanism's forward dynamics by the fastest path this crate has for its shape
/// ([`Mechanism::forward_dynamics`]): the articulated-body algorithm for a tree of revolute,
/// prismatic and fixed joints, Lagrange's equations of its L by dual numbers for anything else
/// (joints of several coordinates, springs and dampers between points). Both are a core
/// [`Dynamics`] on (q, q̇) with the inputs at zero, and the same motion to rounding.
#[allow(clippy::large_enum_variant)]
pub enum ForwardDynamics {
    /// The articulated-body algorithm (O(n) on f64; on the 7-link arm of the benchmarks 1.3× a
    /// hand-written one and a thirty-fourth of the dual-number path).
    Articulated(ArticulatedBody),
    /// Lagrange's equations of the mechanism's L by dual numbers.
    Lagrange(noether_core::EulerLagrange<Mechanism>),
}

impl Mechanism {
    /// The mechanism's forward dynamics by the fastest path for its shape ([`ForwardDynamics`]).
    /// Errors (`Unsupported`): loop closures, which need their constraints (noether-constraints'
    /// `Constrained` or `Rattle` with [`loop_closures`](Self::loop_closures)).
    pub fn forward_dynamics(self) -> Result<ForwardDynamics> {
        if self.closure_count() > 0 {
            return Err(noether_core::Error::Unsupported(
                "forward dynamics of a mechanism with loop closures without its constraints (use Constrained or Rattle)",
            )
            .into());
        }
        let tree = self.recursive_refusal().is_none();
        Ok(if tree {
            ForwardDynamics::Articulated(ArticulatedBody::new(self)?)
        } else {
            ForwardDynamics::Lagrange(noether_core::EulerLagrange::new(self))
        })
    }
}

impl Dynamics for ForwardDynamics {
    type Partner = Velocities;

    fn dof(&self) -> usize {
        match self {
            ForwardDynamics::Articulated(a) => a.dof(),
            ForwardDynamics::Lagrange(l) => l.dof(),
        }
    }

    fn rates(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        dq: &mut [f64],
        dv: &mut [f64],
    ) -> noether_core::Result<()> {
        match self {
            ForwardDynamics::Articulated(a) => a.rates(t, q, v, dq, dv),
            ForwardDynamics::Lagrange(l) => l.rates(t, q, v, dq, dv),
        }
    }

    fn energy(&self, t: f64, q: &[f64], v: &[f64]) -> noether_core::Result<f64> {
        match self {
            ForwardDynamics::Articulated(a) => a.energy(t, q, v),
            ForwardDynamics::Lagrange(l) => l.energy(t, q, v),
        }
    }

    fn admissible(&self, t: f64, q: &[f64], v: &[f64]) -> noether_core::Result<()> {
        match self {
            ForwardDynamics::Articulated(a) => a.admissible(t, q, v),
            ForwardDynamics::Lagrange(l) => l.admissible(t, q, v),
        }
    }

    fn position_rates(&self, t: f64, q: &[f64], v: &[f64], dq: &mut [f64]) -> noether_core::Result<()> {
        match self {
            ForwardDynamics::Articulated(a) => a.position_rates(t, q, v, dq),
            ForwardDynamics::Lagrange(l) => l.position_rates(t, q, v, dq),
        }
    }
}
