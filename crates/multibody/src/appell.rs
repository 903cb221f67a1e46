//! The Gibbs-Appell form of a mechanism with rolling joints: nonholonomic motion without
//! multipliers, with the kinematics written for you.
//!
//! Rolling without slipping fixes the velocity of each rolling disk's centre along its plane by the
//! other rates: the contact point's velocity relative to the plane, v_c + ω × ρ w
//! ([`rolling`](crate::rolling)), has (ẋ, ẏ) as its in-plane part of v_c and nothing else of them, so
//!
//! ```text
//! (ẋ, ẏ) = −P (ω × ρ w)      (P the projection onto the plane's axes),
//! ```
//!
//! a function of the joint's angle rates. The quasi-velocities u are every coordinate's rate except
//! the rolling disks' (ẋ, ẏ), in the order of q; q̇ = W(q) u fills those two in. The rigid parts are
//! the mechanism's bodies of positive mass, their centres and body-frame angular velocities from the
//! same kinematic pass as L; the potential is gravity's and the springs', the further forces the
//! dampers. noether-constraints' [`GibbsAppellEquations`](noether_constraints::GibbsAppellEquations)
//! turns this into a core `Dynamics` on (q, u) whose motion is the Lagrange-d'Alembert motion with
//! multipliers of [`RollingContacts`](crate::RollingContacts), with no multiplier and no drift off
//! the constraints (they hold by construction).

use crate::frames;
use crate::mechanism::Mechanism;
use crate::Result;
use nalgebra::Matrix3;
use noether_constraints::{GibbsAppell, RigidPart};
use noether_core::{Lagrangian, Scalar};

/// A [`Mechanism`] with rolling joints in quasi-velocities (module docs), for
/// [`GibbsAppellEquations`](noether_constraints::GibbsAppellEquations).
#[derive(Debug, Clone, PartialEq)]
pub struct RollingAppell {
    mechanism: Mechanism,
    /// The coordinates whose rates are the quasi-velocities, in order.
    free: Vec<usize>,
    /// The bodies on rolling joints.
    rolling: Vec<usize>,
    /// The bodies of positive mass (the rigid parts), by index.
    parts: Vec<usize>,
}

impl Mechanism {
    /// The Gibbs-Appell form of this mechanism (module docs). Errors (`InvalidParameter`): no rolling
    /// joint (a holonomic mechanism has its Lagrangian), or no body with mass.
    pub fn gibbs_appell(&self) -> Result<RollingAppell> {
        let rolling = self.rolling_bodies();
        let parts: Vec<usize> = (0..self.bodies())
            .filter(|&b| self.nodes()[b].body.mass > 0.0)
            .collect();
        if rolling.is_empty() || parts.is_empty() {
            return Err(noether_core::Error::InvalidParameter {
                name: "rolling joints and bodies with mass",
                value: rolling.len().min(parts.len()) as f64,
                reason: "at least one of each for the Gibbs-Appell form",
            }
            .into());
        }
        let free = (0..self.dof())
            .filter(|i| {
                !rolling.iter().any(|&b| {
                    let k = self.nodes()[b].offset;
                    *i == k || *i == k + 1
                })
            })
            .collect();
        Ok(RollingAppell {
            mechanism: self.clone(),
            free,
            rolling,
            parts,
        })
    }
}

impl RollingAppell {
    /// The mechanism.
    pub fn mechanism(&self) -> &Mechanism {
        &self.mechanism
    }

    /// The quasi-velocities u of a state's rates q̇ (the rates of every coordinate but the rolling
    /// disks' centres). Errors: q̇ of the wrong length.
    pub fn quasi_velocities(&self, qdot: &[f64]) -> Result<Vec<f64>> {
        noether_core::error::check_len("q̇", qdot, self.mechanism.dof())?;
        Ok(self.free.iter().map(|&i| qdot[i]).collect())
    }
}

impl GibbsAppell for RollingAppell {
    fn dof(&self) -> usize {
        self.mechanism.dof()
    }

    fn quasi(&self) -> usize {
        self.free.len()
    }

    /// q̇ = W u: the free rates from u, each rolling disk's (ẋ, ẏ) from its no-slip condition.
    fn velocities<D: Scalar>(&self, _t: D, q: &[D], u: &[D], qdot: &mut [D]) {
        qdot.fill(D::zero());
        for (&i, &ui) in self.free.iter().zip(u) {
            qdot[i] = ui;
        }
        for &b in &self.rolling {
            // With ẋ = ẏ = 0 the contact slips by −(ẋ, ẏ) of the rolling motion.
            let slip = self.mechanism.slip(b, q, qdot);
            let k = self.mechanism.nodes()[b].offset;
            qdot[k] = -slip[0];
            qdot[k + 1] = -slip[1];
        }
    }

    fn bodies(&self) -> usize {
        self.parts.len()
    }

    fn body(&self, b: usize) -> RigidPart {
        let body = &self.mechanism.nodes()[self.parts[b]].body;
        RigidPart::new(body.mass, Matrix3::from_fn(|i, j| body.inertia[i][j]))
    }

    fn centres<D: Scalar>(&self, _t: D, q: &[D], c: &mut [D]) {
        let poses = self.mechanism.poses(q);
        for (k, &b) in self.parts.iter().enumerate() {
            let (r, p) = &poses[b];
            let centre = frames::add(*p, frames::apply_const(r, self.mechanism.nodes()[b].body.centre));
            c[3 * k..3 * k + 3].copy_from_slice(&centre);
        }
    }

    fn angular_velocities<D: Scalar>(&self, _t: D, q: &[D], qdot: &[D], omega: &mut [D]) {
        let moving = self.mechanism.forward(q, qdot);
        for (k, &b) in self.parts.iter().enumerate() {
            let spin = frames::apply_transpose(&moving[b].r, moving[b].w);
            omega[3 * k..3 * k + 3].copy_from_slice(&spin);
        }
    }

    /// V = −L at rest: gravity's and the springs' potential.
    fn potential<D: Scalar>(&self, t: D, q: &[D]) -> D {
        let rest = vec![D::zero(); q.len()];
        -self.mechanism.lagrangian(t, q, &rest)
    }

    /// The dampers on joints and between points.
    fn forces(&self, t: f64, q: &[f64], qdot: &[f64], out: &mut [f64]) {
        if self.mechanism.has_generalized_force() {
            let mut q_force = vec![0.0; q.len()];
            self.mechanism.generalized_force(t, q, qdot, &mut q_force);
            out.iter_mut().zip(&q_force).for_each(|(o, f)| *o += f);
        }
    }
}
