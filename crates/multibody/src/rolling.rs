//! Rolling without slipping: the disks of [rolling joints](crate::JointKind::Rolling) as velocity
//! constraints on the mechanism's coordinates.
//!
//! A rolling joint keeps its disk touching the plane (the centre at height ρ cos θ); rolling without
//! slipping asks more, that the material point of the rim at the contact does not move along the
//! plane. With the joint's rates (ω, v_c) relative to the plane and w the unit vector from the centre
//! to the contact,
//!
//! ```text
//! g(q, q̇) = P (v_c + ω × ρ w) = 0,   P the projection onto the plane's x and y axes,
//! ```
//!
//! two constraints per disk, linear in q̇ and not integrable (the disk can reach any position with any
//! heading): nonholonomic. For one coin they are ẋ = ρ (ω₃ cos ψ + θ̇ cos θ sin ψ),
//! ẏ = ρ (ω₃ sin ψ − θ̇ cos θ cos ψ), ω₃ = φ̇ + ψ̇ sin θ the spin about the axis. The normal component
//! of the contact velocity is the rate of the height constraint the joint holds already. Relative to
//! the joint frame means relative to the parent's surface: a disk on a body rolls on that body.
//! [`RollingContacts`] is a [`Nonholonomic`] set, generic like the Lagrangian, for noether-constraints'
//! multipliers (the Lagrange-d'Alembert principle), projections and constrained linearisation.

use crate::frames::V3;
use crate::mechanism::Mechanism;
use crate::Result;
use noether_constraints::Nonholonomic;
use noether_core::Scalar;

impl Mechanism {
    /// The rolling joints' no-slip conditions as a velocity constraint set (module docs). Errors
    /// (`InvalidParameter`): a mechanism without rolling joints.
    pub fn rolling_contacts(&self) -> Result<RollingContacts> {
        let contacts = self.rolling_bodies();
        if contacts.is_empty() {
            return Err(noether_core::Error::InvalidParameter {
                name: "rolling joints",
                value: 0.0,
                reason: "at least one, for rolling contacts",
            }
            .into());
        }
        Ok(RollingContacts {
            mechanism: self.clone(),
            contacts,
        })
    }

    /// The bodies on rolling joints, in the order of attachment.
    pub(crate) fn rolling_bodies(&self) -> Vec<usize> {
        self.nodes()
            .iter()
            .enumerate()
            .filter(|(_, n)| matches!(n.joint.kind(), crate::JointKind::Rolling { .. }))
            .map(|(i, _)| i)
            .collect()
    }

    /// The velocity of the contact point of `body`'s rolling disk relative to its plane at (q, q̇)
    /// (module docs), from the joint's own coordinates; `body` must be on a rolling joint.
    pub(crate) fn slip<D: Scalar>(&self, body: usize, q: &[D], v: &[D]) -> V3<D> {
        let node = &self.nodes()[body];
        let own = node.offset..node.offset + node.joint.dof();
        node.joint
            .contact_velocity(&q[own.clone()], &v[own])
            .unwrap_or([D::zero(); 3])
    }
}

/// The no-slip conditions of a [`Mechanism`]'s rolling joints as a [`Nonholonomic`] set (module
/// docs): for each rolling joint in the order of attachment, the contact point's velocity along the
/// plane's x and y axes.
#[derive(Debug, Clone, PartialEq)]
pub struct RollingContacts {
    mechanism: Mechanism,
    /// The bodies on rolling joints.
    contacts: Vec<usize>,
}

impl Nonholonomic for RollingContacts {
    fn dof(&self) -> usize {
        noether_core::Lagrangian::dof(&self.mechanism)
    }
    fn count(&self) -> usize {
        2 * self.contacts.len()
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], v: &[D], out: &mut [D]) {
        for (k, &body) in self.contacts.iter().enumerate() {
            let slip = self.mechanism.slip(body, q, v);
            out[2 * k] = slip[0];
            out[2 * k + 1] = slip[1];
        }
    }
}
