//! Loop closures: the joints that close a kinematic loop (a four-bar linkage, a slider-crank) as
//! holonomic constraints on the tree's coordinates.
//!
//! A tree is cut open at one joint of each loop; the cut is closed again by requiring a point of one
//! side to stay on a point of the other, along chosen world directions d_k:
//!
//! ```text
//! φ_k(q) = d_k · (r_a(q) − r_b(q)) = 0,   r = p + R ρ   (ρ the point in its body's frame),
//! ```
//!
//! all three axes for a ball joint in space, the two axes of the plane for a hinge of a planar
//! mechanism (whose third component vanishes identically and would make the constraints redundant).
//! [`LoopClosures`] is a [`Holonomic`] set, generic like the Lagrangian, so noether-constraints'
//! machinery runs the closed mechanism: multipliers and reaction forces (`Constrained`), RATTLE,
//! projection, and the reduction to independent coordinates (`Reduced`, exact derivatives).

use crate::mechanism::{Mechanism, Parent};
use crate::{frames, Error, Result};
use noether_constraints::Holonomic;
use noether_core::Scalar;

/// A cut joint: the point `at_a` of `a` held on the point `at_b` of `b` along `directions`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Closure {
    pub(crate) a: Parent,
    pub(crate) at_a: [f64; 3],
    pub(crate) b: Parent,
    pub(crate) at_b: [f64; 3],
    pub(crate) directions: Vec<[f64; 3]>,
}

impl Mechanism {
    /// Closes a loop: the point `at_a` (in the frame of `a`, or of the world for the ground) stays on
    /// the point `at_b` of `b` along each of the world `directions` (unit vectors after
    /// normalisation; one constraint each). Errors: an unknown body, both sides on the same body or
    /// both on the ground ([`Error::NotALoop`]), a zero or non-finite direction, no direction, a
    /// non-finite point.
    pub fn close_loop(
        &mut self,
        (a, at_a): (Parent, [f64; 3]),
        (b, at_b): (Parent, [f64; 3]),
        directions: &[[f64; 3]],
    ) -> Result<()> {
        for p in [a, b] {
            self.check_parent(p, self.bodies())?;
        }
        if a == b {
            return Err(Error::NotALoop {
                closure: self.closures.len(),
            });
        }
        noether_core::error::check_finite("loop closure point", &at_a)?;
        noether_core::error::check_finite("loop closure point", &at_b)?;
        if directions.is_empty() {
            return Err(noether_core::Error::InvalidParameter {
                name: "loop closure directions",
                value: 0.0,
                reason: "at least one",
            }
            .into());
        }
        let mut unit = Vec::with_capacity(directions.len());
        for d in directions {
            let norm = d.iter().map(|x| x * x).sum::<f64>().sqrt();
            if !(norm.is_finite() && norm > 0.0) {
                return Err(Error::Axis {
                    body: self.bodies(),
                    axis: *d,
                });
            }
            unit.push(d.map(|x| x / norm));
        }
        self.closures.push(Closure {
            a,
            at_a,
            b,
            at_b,
            directions: unit,
        });
        Ok(())
    }

    /// The number of loop-closure constraints.
    pub fn closure_count(&self) -> usize {
        self.closures.iter().map(|c| c.directions.len()).sum()
    }

    /// Checks the loop closures at the configuration q: each must hold (|φ| ≤ 1e-10 of the
    /// mechanism's scale) and each must restrain a motion the others leave free. Errors:
    /// [`Error::RedundantClosure`] naming the first closure and direction whose row of the Jacobian
    /// ∂φ/∂q depends on the rows before it (a planar loop closed along its plane's normal too, or one
    /// loop closed twice), `ConstraintViolated` (noether-constraints') when q is off a closure.
    pub fn check_loops(&self, q: &[f64]) -> Result<()> {
        let closures = self.loop_closures();
        let m = self.closure_count();
        let mut phi = vec![0.0; m];
        noether_constraints::holonomic::values(&closures, 0.0, q, &mut phi)
            .map_err(|e| Error::Core(e.into()))?;
        let scale = q.iter().fold(1.0_f64, |s, x| s.max(x.abs()));
        if let Some(worst) = phi.iter().copied().find(|p| p.abs() > 1e-10 * scale) {
            let violated = noether_constraints::Error::ConstraintViolated {
                what: "position",
                t: 0.0,
                residual: worst.abs(),
                tolerance: 1e-10 * scale,
            };
            return Err(Error::Core(violated.into()));
        }
        let mut jac = nalgebra::DMatrix::zeros(m, noether_core::Lagrangian::dof(self));
        noether_constraints::holonomic::jacobian(&closures, 0.0, q, &mut jac)
            .map_err(|e| Error::Core(e.into()))?;
        let mut row = 0;
        for (index, c) in self.closures.iter().enumerate() {
            for direction in 0..c.directions.len() {
                let (rank, _) = noether_core::linalg::rank(&jac.rows(0, row + 1).into_owned());
                if rank <= row {
                    return Err(Error::RedundantClosure {
                        closure: index,
                        direction,
                        rank,
                    });
                }
                row += 1;
            }
        }
        Ok(())
    }

    /// The reaction force at each cut joint, from the multipliers λ of the loop closures (in the order
    /// of [`loop_closures`](Self::loop_closures), as noether-constraints' `Constrained::multipliers`
    /// gives them: M q̈ = f + (∂φ/∂q)ᵀ λ). The constraint force Σ_k λ_k ∂φ_k/∂q with
    /// φ_k = d_k · (r_a − r_b) is the virtual work of the force F = Σ_k λ_k d_k on the point of `a`
    /// and −F on the point of `b`: one world vector F per closure, the force the joint that was cut
    /// exerts on `a`. Errors: λ of the wrong length or not finite.
    pub fn closure_forces(&self, lambda: &[f64]) -> Result<Vec<[f64; 3]>> {
        noether_core::error::check_len("loop-closure multipliers", lambda, self.closure_count())?;
        noether_core::error::check_finite("loop-closure multipliers", lambda)?;
        let mut rest = lambda;
        Ok(self
            .closures
            .iter()
            .map(|c| {
                let (own, after) = rest.split_at(c.directions.len());
                rest = after;
                let mut force = [0.0; 3];
                for (l, d) in own.iter().zip(&c.directions) {
                    (0..3).for_each(|i| force[i] += l * d[i]);
                }
                force
            })
            .collect())
    }

    /// The loop closures as a holonomic constraint set on this mechanism's coordinates.
    pub fn loop_closures(&self) -> LoopClosures {
        LoopClosures(self.clone())
    }
}

/// The loop closures of a [`Mechanism`] as a [`Holonomic`] constraint set (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct LoopClosures(Mechanism);

impl Holonomic for LoopClosures {
    fn dof(&self) -> usize {
        noether_core::Lagrangian::dof(&self.0)
    }
    fn count(&self) -> usize {
        self.0.closure_count()
    }
    fn constraints<D: Scalar>(&self, _t: D, q: &[D], out: &mut [D]) {
        let poses = self.0.poses(q);
        let point = |p: Parent, at: [f64; 3]| match p {
            Parent::Ground => at.map(D::from),
            Parent::Body(b) => {
                let (r, o) = &poses[b.0];
                frames::add(*o, frames::apply_const(r, at))
            }
        };
        let mut k = 0;
        for c in &self.0.closures {
            let gap = frames::sub(point(c.a, c.at_a), point(c.b, c.at_b));
            for d in &c.directions {
                out[k] = gap[0] * d[0] + gap[1] * d[1] + gap[2] * d[2];
                k += 1;
            }
        }
    }
}
