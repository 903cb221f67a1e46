//! Discrete Lagrangians from a continuous [`Lagrangian`] by quadrature of the action over one step
//! (second order): the midpoint rule and the trapezoidal rule.
//!
//! With v = (q₁ − q₀)/h:
//! - midpoint: `L_d = h L(t₀ + h/2, (q₀ + q₁)/2, v)`; discrete forces f⁻ = f⁺ = (h/2) Q(t₀ + h/2, (q₀+q₁)/2, v);
//! - trapezoidal: `L_d = (h/2) [L(t₀, q₀, v) + L(t₀ + h, q₁, v)]`; f⁻ = (h/2) Q(t₀, q₀, v),
//!   f⁺ = (h/2) Q(t₀ + h, q₁, v).
//!
//! For L = ½ q̇ᵀMq̇ − V(q) the midpoint rule gives the implicit midpoint method and the trapezoidal rule
//! gives Störmer-Verlet (see [`crate::Verlet`] for the explicit fast path).
//!
//! # References
//! J. E. Marsden and M. West, *Discrete mechanics and variational integrators*, Acta Numerica 10 (2001),
//! §2.2 and §3.2.

use crate::lagrangian::{difference_quotient, midpoint, DiscreteLagrangian};
use crate::optimal_control::DiscreteActuated;
use nalgebra::DVector;
use noether_core::control::Actuated;
use noether_core::{EulerLagrange, Lagrangian, Momenta, Result, Scalar, State};

/// A discrete Lagrangian built from a continuous Lagrangian: gives access to the continuous equations
/// (Legendre map, energy) so a discrete trajectory can be started from velocities and reported in the
/// continuous system's energy.
pub trait FromLagrangian {
    /// The continuous Lagrangian.
    type L: Lagrangian;
    /// The continuous Euler-Lagrange equations (mass factor cached there).
    fn continuous(&self) -> &EulerLagrange<Self::L>;

    /// The state (t, q, p) from positions and velocities through the continuous Legendre map
    /// p = ∂L/∂q̇(t, q, q̇).
    fn state_from_velocities(&self, t: f64, q: &[f64], v: &[f64]) -> Result<State<Momenta>> {
        let mut p = vec![0.0; q.len()];
        self.continuous().momenta(t, q, v, &mut p)?;
        Ok(State::with_momenta(t, q.to_vec(), p))
    }

    /// The velocities q̇ of a state (t, q, p) through the inverse continuous Legendre map.
    fn velocities_at(&self, state: &State<Momenta>) -> Result<DVector<f64>> {
        self.continuous()
            .velocities(state.t, state.q.as_slice(), state.v.as_slice())
    }

    /// The energy h = q̇·∂L/∂q̇ − L of the continuous system at a state (t, q, p), with q̇ from the
    /// inverse Legendre map.
    fn energy_at(&self, state: &State<Momenta>) -> Result<f64> {
        let v = self.velocities_at(state)?;
        self.continuous()
            .energy(state.t, state.q.as_slice(), v.as_slice())
    }

    /// Hamilton's vector field of the continuous system at (t, q, p): q̇ from the inverse Legendre map
    /// and ṗ = ∂L/∂q(t, q, q̇) (the Euler-Lagrange equation d/dt ∂L/∂q̇ = ∂L/∂q).
    fn hamilton_rates(&self, t: f64, q: &[f64], p: &[f64], dq: &mut [f64], dp: &mut [f64]) -> Result<()> {
        let v = self.continuous().velocities(t, q, p)?;
        dq.copy_from_slice(v.as_slice());
        self.continuous().gradient_q(t, q, v.as_slice(), dp)
    }
}

/// A quadrature rule of a continuous Lagrangian: the struct around its Euler-Lagrange equations,
/// `new`, [`FromLagrangian`], and the parts of [`DiscreteLagrangian`] and
/// [`DiscreteActuated`](crate::DiscreteActuated) every rule shares (the continuous rates, dof, the
/// primary-constraint check, the model's forces and input forces by the rule's `forces` function),
/// around the rule's own `discrete_lagrangian` and the formulas of its forces.
macro_rules! quadrature_rule {
    (
        $(#[$doc:meta])*
        $rule:ident, $name:literal, $forces:ident;
        force $force_doc:literal;
        input_force $input_force_doc:literal;
        $discrete_lagrangian:item
    ) => {
        $(#[$doc])*
        pub struct $rule<L> {
            el: EulerLagrange<L>,
        }

        impl<L: Lagrangian> $rule<L> {
            #[doc = concat!("The ", $name, " rule applied to `lagrangian`.")]
            pub fn new(lagrangian: L) -> Self {
                $rule {
                    el: EulerLagrange::new(lagrangian),
                }
            }
        }

        impl<L: Lagrangian> FromLagrangian for $rule<L> {
            type L = L;
            fn continuous(&self) -> &EulerLagrange<L> {
                &self.el
            }
        }

        impl<L: Lagrangian> DiscreteLagrangian for $rule<L> {
            fn continuous_rates(
                &self,
                t: f64,
                q: &[f64],
                p: &[f64],
                dq: &mut [f64],
                dp: &mut [f64],
            ) -> Option<Result<()>> {
                Some(self.hamilton_rates(t, q, p, dq, dp))
            }
            fn dof(&self) -> usize {
                self.el.dof()
            }

            $discrete_lagrangian

            fn has_discrete_force(&self) -> bool {
                self.el.lagrangian().has_generalized_force()
            }

            fn check_momenta(&self, t: f64, q: &[f64], p: &[f64], tol: f64) -> Result<()> {
                crate::primary::check(&self.el, t, q, p, tol)
            }

            #[doc = $force_doc]
            fn discrete_force<D: Scalar>(
                &self,
                t0: f64,
                h: f64,
                q0: &[D],
                q1: &[D],
                minus: &mut [D],
                plus: &mut [D],
            ) {
                let l = self.el.lagrangian();
                $forces(t0, h, (q0, q1), (minus, plus), |t, q, v, out| {
                    l.generalized_force(t, q, v, out)
                });
            }
        }

        impl<L: Actuated> DiscreteActuated for $rule<L> {
            fn inputs(&self) -> usize {
                self.el.lagrangian().inputs()
            }

            #[doc = $input_force_doc]
            fn discrete_input_force<D: Scalar>(
                &self,
                t0: f64,
                h: f64,
                q0: &[D],
                q1: &[D],
                u: &[D],
                minus: &mut [D],
                plus: &mut [D],
            ) {
                let model = self.el.lagrangian();
                $forces(t0, h, (q0, q1), (minus, plus), |t, q, v, out| {
                    model.input_force(t, q, v, u, out)
                });
            }

            fn momenta(&self, t: f64, q: &[f64], v: &[f64], p: &mut [f64]) -> Result<()> {
                self.el.momenta(t, q, v, p)
            }
        }
    };
}

quadrature_rule! {
    /// The midpoint discrete Lagrangian `L_d = h L(t₀ + h/2, (q₀ + q₁)/2, (q₁ − q₀)/h)`.
    Midpoint, "midpoint", midpoint_forces;
    force "f⁻ = f⁺ = (h/2) Q(t₀ + h/2, (q₀ + q₁)/2, (q₁ − q₀)/h).";
    input_force "f⁻ = f⁺ = (h/2) Q_u(t₀ + h/2, (q₀ + q₁)/2, (q₁ − q₀)/h, u).";
    fn discrete_lagrangian<D: Scalar>(&self, t0: f64, h: D, q0: &[D], q1: &[D]) -> D {
        let half = D::from(0.5);
        let (mid, v) = (midpoint(q0, q1), difference_quotient(q0, q1, h));
        self.el.lagrangian().lagrangian(h * half + t0, &mid, &v) * h
    }
}

quadrature_rule! {
    /// The trapezoidal discrete Lagrangian `L_d = (h/2) [L(t₀, q₀, v) + L(t₀ + h, q₁, v)]`, v = (q₁ − q₀)/h.
    Trapezoidal, "trapezoidal", trapezoidal_forces;
    force "f⁻ = (h/2) Q(t₀, q₀, v), f⁺ = (h/2) Q(t₀ + h, q₁, v), v = (q₁ − q₀)/h.";
    input_force "f⁻ = (h/2) Q_u(t₀, q₀, v, u), f⁺ = (h/2) Q_u(t₀ + h, q₁, v, u), v = (q₁ − q₀)/h.";
    fn discrete_lagrangian<D: Scalar>(&self, t0: f64, h: D, q0: &[D], q1: &[D]) -> D {
        let v = difference_quotient(q0, q1, h);
        let l = self.el.lagrangian();
        let t = D::from(t0);
        (l.lagrangian(t, q0, &v) + l.lagrangian(t + h, q1, &v)) * h * 0.5
    }
}

/// The midpoint rule's discrete forces of a force law F(t, q, q̇) written into its last argument (the
/// model's generalized force, or its input force at given inputs):
/// f⁻ = f⁺ = (h/2) F(t₀ + h/2, (q₀ + q₁)/2, (q₁ − q₀)/h).
pub(crate) fn midpoint_forces<D: Scalar>(
    t0: f64,
    h: f64,
    (q0, q1): (&[D], &[D]),
    (minus, plus): (&mut [D], &mut [D]),
    force: impl FnOnce(D, &[D], &[D], &mut [D]),
) {
    let (mid, v) = (midpoint(q0, q1), difference_quotient(q0, q1, D::from(h)));
    force(D::from(t0 + 0.5 * h), &mid, &v, minus);
    for (m, p) in minus.iter_mut().zip(plus.iter_mut()) {
        *m *= 0.5 * h;
        *p = *m;
    }
}

/// The trapezoidal rule's discrete forces of a force law F(t, q, q̇) (see [`midpoint_forces`]):
/// f⁻ = (h/2) F(t₀, q₀, v), f⁺ = (h/2) F(t₀ + h, q₁, v), v = (q₁ − q₀)/h.
pub(crate) fn trapezoidal_forces<D: Scalar>(
    t0: f64,
    h: f64,
    (q0, q1): (&[D], &[D]),
    (minus, plus): (&mut [D], &mut [D]),
    mut force: impl FnMut(D, &[D], &[D], &mut [D]),
) {
    let v = difference_quotient(q0, q1, D::from(h));
    force(D::from(t0), q0, &v, minus);
    force(D::from(t0 + h), q1, &v, plus);
    minus
        .iter_mut()
        .chain(plus.iter_mut())
        .for_each(|x| *x *= 0.5 * h);
}
