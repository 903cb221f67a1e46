//! The equations of motion of a tree by the recursive Newton-Euler algorithm: the same motion as
//! Lagrange's equations of the [`Mechanism`]'s L, in O(n) per inverse-dynamics pass and on plain
//! `f64`, without the third-order jets the generic path carries.
//!
//! Inverse dynamics ID(q, q̇, q̈) = M(q) q̈ + c(q, q̇) − g(q) (the joint forces that make the tree move
//! with q̈) runs outwards, then inwards (Featherstone, *Rigid Body Dynamics Algorithms*, §5.3; Craig,
//! *Introduction to Robotics*, §6.5, in world axes). Outwards, with s the joint axis in the world and
//! P the parent, gravity entering as an acceleration −g of the ground:
//!
//! ```text
//! revolute:  ω = ω_P + s q̇,   α = α_P + s q̈ + ω_P × s q̇,
//! prismatic: ω = ω_P,         α = α_P,
//! a = a_P + α_P × d + ω_P × (ω_P × d)  [+ s q̈ + 2 ω_P × s q̇ for a prismatic joint],  d = p − p_P,
//! a_c = a + α × r_c + ω × (ω × r_c),   r_c = R c_b,
//! ```
//!
//! and inwards each body's net force F = m a_c and moment about its centre N = I α + ω × I ω
//! (I = R I_b Rᵀ) are passed to the parent:
//!
//! ```text
//! f = F + Σ_children f_k,   n = N + r_c × F + Σ_children (n_k + (p_k − p) × f_k),
//! τ = s · n (revolute) or s · f (prismatic).
//! ```
//!
//! Then b = −ID(q, q̇, 0) + Q (Q: springs, dampers), M's columns are ID(q, 0, e_j) without gravity, and
//! q̈ = M⁻¹ b by core's factorisation. Checked against Lagrange's equations of the same mechanism in
//! the tests; `benches/` compares the two.

use crate::frames::{self, V3};
use crate::mechanism::{Mechanism, Moving, Parent};
use crate::Result;
use nalgebra::DMatrix;
use noether_core::error::{check_len, check_phase_point, check_result};
use noether_core::{Dynamics, Lagrangian, Velocities};

/// A tree [`Mechanism`] stepped by the recursive Newton-Euler algorithm (module docs): a core
/// [`Dynamics`] on (q, q̇), with the inputs (if any) at zero.
#[derive(Debug, Clone, PartialEq)]
pub struct NewtonEuler {
    mechanism: Mechanism,
}

impl NewtonEuler {
    /// The tree `mechanism`. Errors (`Unsupported`): a mechanism with loop closures (a closed loop
    /// needs its constraints, noether-constraints' `Constrained` or `Rattle`), with a joint of more
    /// than one coordinate (cylindrical, planar: not yet here; Lagrange's equations take them), or
    /// with springs or dampers between points (Lagrange's equations take them).
    pub fn new(mechanism: Mechanism) -> Result<Self> {
        if let Some(refusal) = mechanism.recursive_refusal() {
            return Err(refusal.into());
        }
        Ok(NewtonEuler { mechanism })
    }

    /// The mechanism.
    pub fn mechanism(&self) -> &Mechanism {
        &self.mechanism
    }

    /// The joint forces ID(q, q̇, q̈) that move the tree with the accelerations q̈ (module docs), with
    /// or without gravity, into `tau`.
    fn inverse(&self, frames: &[Moving<f64>], (v, qdd): (&[f64], &[f64]), gravity: bool, tau: &mut [f64]) {
        let nodes = self.mechanism.nodes();
        let fall = if gravity {
            self.mechanism.gravity_vector().map(|g| -g)
        } else {
            [0.0; 3]
        };
        // Outwards: angular and linear accelerations of every body's origin.
        let mut acc: Vec<(V3<f64>, V3<f64>)> = Vec::with_capacity(nodes.len());
        for (i, node) in nodes.iter().enumerate() {
            let (f, (alpha_p, a_p, w_p, p_p)) = (
                &frames[i],
                match node.parent {
                    Parent::Ground => ([0.0; 3], fall, [0.0; 3], [0.0; 3]),
                    Parent::Body(b) => (acc[b.0].0, acc[b.0].1, frames[b.0].w, frames[b.0].p),
                },
            );
            let d = frames::sub(f.p, p_p);
            let mut alpha = alpha_p;
            let mut a = frames::add(
                a_p,
                frames::add(
                    frames::cross(alpha_p, d),
                    frames::cross(w_p, frames::cross(w_p, d)),
                ),
            );
            if let Some((axis, k)) = self.mechanism.world_axis(i, frames) {
                let (rate, accel) = (v[k], qdd[k]);
                let spin = axis.map(|s| s * rate);
                if node.joint.is_revolute() {
                    alpha = frames::add(
                        alpha,
                        frames::add(axis.map(|s| s * accel), frames::cross(w_p, spin)),
                    );
                } else {
                    a = frames::add(
                        a,
                        frames::add(axis.map(|s| s * accel), frames::cross(w_p, spin).map(|x| 2.0 * x)),
                    );
                }
            }
            acc.push((alpha, a));
        }
        // Inwards: forces and moments (about each origin) passed to the parents.
        let mut force = vec![([0.0; 3], [0.0; 3]); nodes.len()];
        tau.fill(0.0);
        for i in (0..nodes.len()).rev() {
            let (f, body) = (&frames[i], &nodes[i].body);
            let (alpha, a) = acc[i];
            let rc = frames::apply_const(&f.r, body.centre);
            let ac = frames::add(
                a,
                frames::add(
                    frames::cross(alpha, rc),
                    frames::cross(f.w, frames::cross(f.w, rc)),
                ),
            );
            let net = ac.map(|x| x * body.mass);
            let spin = inertia_times(&f.r, &body.inertia, f.w);
            let moment = frames::add(
                inertia_times(&f.r, &body.inertia, alpha),
                frames::cross(f.w, spin),
            );
            let (mut total, mut about) = force[i];
            total = frames::add(total, net);
            about = frames::add(about, frames::add(moment, frames::cross(rc, net)));
            if let Some((axis, k)) = self.mechanism.world_axis(i, frames) {
                let carried = if nodes[i].joint.is_revolute() {
                    about
                } else {
                    total
                };
                tau[k] = frames::dot(axis, carried);
            }
            if let Parent::Body(b) = nodes[i].parent {
                let lever = frames::sub(f.p, frames[b.0].p);
                let (pf, pn) = &mut force[b.0];
                *pf = frames::add(*pf, total);
                *pn = frames::add(*pn, frames::add(about, frames::cross(lever, total)));
            }
        }
    }
}

/// (R I_b Rᵀ) x.
fn inertia_times(r: &[[f64; 3]; 3], inertia: &[[f64; 3]; 3], x: V3<f64>) -> V3<f64> {
    let body = frames::apply_transpose(r, x);
    let turned: V3<f64> = std::array::from_fn(|i| (0..3).map(|k| inertia[i][k] * body[k]).sum());
    frames::apply(r, turned)
}

impl Dynamics for NewtonEuler {
    type Partner = Velocities;

    fn dof(&self) -> usize {
        self.mechanism.dof()
    }

    /// q̇ = v and q̈ = M⁻¹ (Q − ID(q, q̇, 0)), M by n inverse-dynamics passes at rest without gravity.
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
        let moving = self.mechanism.forward(q, v);
        let mut b = vec![0.0; n];
        let zeros = vec![0.0; n];
        self.inverse(&moving, (v, &zeros), true, &mut b);
        let mut joint = vec![0.0; n];
        self.mechanism.joint_forces(q, v, &mut joint);
        b.iter_mut().zip(&joint).for_each(|(b, q)| *b = q - *b);
        // The same poses at rest: M's columns are the inverse dynamics without velocities.
        let still: Vec<Moving<f64>> = moving
            .iter()
            .map(|m| Moving {
                r: m.r,
                p: m.p,
                w: [0.0; 3],
                v: [0.0; 3],
            })
            .collect();
        let mut mass = DMatrix::zeros(n, n);
        let mut e = vec![0.0; n];
        let mut column = vec![0.0; n];
        for j in 0..n {
            e[j] = 1.0;
            self.inverse(&still, (&zeros, &e), false, &mut column);
            mass.column_mut(j).copy_from_slice(&column);
            e[j] = 0.0;
        }
        let factor = noether_core::linalg::factor_positive_mass(mass, t)?;
        factor.solve_in_place(&mut b);
        dv.copy_from_slice(&b);
        dq.copy_from_slice(v);
        check_result("Newton-Euler accelerations", t, dv)
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
