//! Springs and dampers between points: a point of one body (or of the ground) tied to a point of
//! another by a linear spring along the line between them, a damper along it, or both.
//!
//! With r_a, r_b the two points in the world, Δ = r_a − r_b and d = |Δ| their distance, a spring of
//! stiffness k and rest length d₀ stores
//!
//! ```text
//! V = ½ k (d − d₀)²        (½ k |Δ|² for d₀ = 0, smooth where the points meet),
//! ```
//!
//! which enters L like gravity. A damper of constant c pulls the points together or apart with
//! the force c ḋ along the line, whose virtual work gives the generalized force
//!
//! ```text
//! Q_i = −c ḋ ∂d/∂q_i,   ḋ = Δ·Δ̇/d,   ∂d/∂q_i = (Δ/d) · ∂Δ/∂q_i,
//! ```
//!
//! and since every joint's velocities are linear in q̇, ∂Δ/∂q_i is Δ̇ at the unit rate e_i: one pass
//! of the kinematics per coordinate, generic like L (so Jacobians of the forced equations carry the
//! damper too). A damper needs the points apart (d > 0), where its line is defined.

use crate::frames::{self, V3};
use crate::mechanism::{Mechanism, Moving, Parent};
use crate::Result;
use noether_core::error::check_finite;
use noether_core::Scalar;

/// A spring and/or damper between two points.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Connection {
    a: Parent,
    at_a: [f64; 3],
    b: Parent,
    at_b: [f64; 3],
    stiffness: f64,
    rest: f64,
    damping: f64,
}

impl Mechanism {
    /// A linear spring of `stiffness` k and `rest` length d₀ between the point `at_a` of `a` and
    /// `at_b` of `b` (each in its body's frame, or in the world for the ground): V = ½ k (d − d₀)²
    /// (module docs). Errors: an unknown body, a non-finite point, k or d₀ negative or not finite.
    pub fn spring(
        &mut self,
        a: (Parent, [f64; 3]),
        b: (Parent, [f64; 3]),
        stiffness: f64,
        rest: f64,
    ) -> Result<()> {
        self.connect(
            a,
            b,
            &[("spring stiffness", stiffness), ("spring rest length", rest)],
        )?;
        self.connections.push(Connection {
            a: a.0,
            at_a: a.1,
            b: b.0,
            at_b: b.1,
            stiffness,
            rest,
            damping: 0.0,
        });
        Ok(())
    }

    /// A linear damper of constant c between the point `at_a` of `a` and `at_b` of `b`: the force
    /// c ḋ along the line between them (module docs). Errors: an unknown body, a non-finite point, c
    /// negative or not finite.
    pub fn damper(&mut self, a: (Parent, [f64; 3]), b: (Parent, [f64; 3]), damping: f64) -> Result<()> {
        self.connect(a, b, &[("damper constant", damping)])?;
        self.connections.push(Connection {
            a: a.0,
            at_a: a.1,
            b: b.0,
            at_b: b.1,
            stiffness: 0.0,
            rest: 0.0,
            damping,
        });
        Ok(())
    }

    /// Checks a connection's points and constants.
    fn connect(
        &self,
        (a, at_a): (Parent, [f64; 3]),
        (b, at_b): (Parent, [f64; 3]),
        constants: &[(&'static str, f64)],
    ) -> Result<()> {
        for p in [a, b] {
            self.check_parent(p, self.bodies())?;
        }
        check_finite("connection point", &at_a)?;
        check_finite("connection point", &at_b)?;
        for &(name, value) in constants {
            if !(value.is_finite() && value >= 0.0) {
                return Err(noether_core::Error::InvalidParameter {
                    name,
                    value,
                    reason: "finite and at least 0",
                }
                .into());
            }
        }
        Ok(())
    }

    /// Whether the mechanism has springs or dampers between points.
    pub(crate) fn has_connections(&self) -> bool {
        !self.connections.is_empty()
    }

    /// Whether it has dampers between points.
    pub(crate) fn has_point_dampers(&self) -> bool {
        self.connections.iter().any(|c| c.damping != 0.0)
    }

    /// Σ ½ k (d − d₀)² over the springs, at the bodies' poses `frames`.
    pub(crate) fn connection_energy<D: Scalar>(&self, frames: &[Moving<D>]) -> D {
        let mut v = D::zero();
        for c in self.connections.iter().filter(|c| c.stiffness != 0.0) {
            let gap = frames::sub(point(frames, c.a, c.at_a), point(frames, c.b, c.at_b));
            let square = frames::dot(gap, gap);
            let stretch = if c.rest == 0.0 {
                square
            } else {
                let s = square.sqrt() - c.rest;
                s * s
            };
            v += stretch * (0.5 * c.stiffness);
        }
        v
    }

    /// Adds the point dampers' generalized forces (module docs) into `out`, the bodies moving as
    /// `frames` (at q, q̇).
    pub(crate) fn add_damper_forces<D: Scalar>(&self, q: &[D], frames: &[Moving<D>], out: &mut [D]) {
        let dampers: Vec<&Connection> = self.connections.iter().filter(|c| c.damping != 0.0).collect();
        if dampers.is_empty() {
            return;
        }
        // Per damper: the unit line Δ/d and the pull −c ḋ.
        let lines: Vec<(V3<D>, D)> = dampers
            .iter()
            .map(|c| {
                let gap = frames::sub(point(frames, c.a, c.at_a), point(frames, c.b, c.at_b));
                let d = frames::dot(gap, gap).sqrt();
                let unit = gap.map(|x| x / d);
                let rate = frames::dot(unit, velocity(frames, c.a, c.at_a, c.b, c.at_b));
                (unit, -rate * c.damping)
            })
            .collect();
        let mut unit_rate = vec![D::zero(); q.len()];
        for i in 0..q.len() {
            unit_rate[i] = D::one();
            let moving = self.forward(q, &unit_rate);
            unit_rate[i] = D::zero();
            for (c, (unit, pull)) in dampers.iter().zip(&lines) {
                let along = frames::dot(*unit, velocity(&moving, c.a, c.at_a, c.b, c.at_b));
                out[i] += *pull * along;
            }
        }
    }
}

/// The world position of the point `at` of `p` (of the world for the ground).
fn point<D: Scalar>(frames: &[Moving<D>], p: Parent, at: [f64; 3]) -> V3<D> {
    match p {
        Parent::Ground => at.map(D::from),
        Parent::Body(b) => {
            let f = &frames[b.0];
            frames::add(f.p, frames::apply_const(&f.r, at))
        }
    }
}

/// Δ̇ = ṙ_a − ṙ_b for the points `at_a` of `a` and `at_b` of `b`, ṙ = v + ω × R at.
fn velocity<D: Scalar>(frames: &[Moving<D>], a: Parent, at_a: [f64; 3], b: Parent, at_b: [f64; 3]) -> V3<D> {
    let of = |p: Parent, at: [f64; 3]| match p {
        Parent::Ground => frames::zero(),
        Parent::Body(body) => {
            let f = &frames[body.0];
            frames::add(f.v, frames::cross(f.w, frames::apply_const(&f.r, at)))
        }
    };
    frames::sub(of(a, at_a), of(b, at_b))
}
