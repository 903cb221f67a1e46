//! Compiled models: a model recorded once as an expression graph, its equations of motion derived
//! and simplified on the graph, and run without dual numbers.
//!
//! The dual-number path of noether-core differentiates the model at every call. Here the model — the
//! same generic code, unchanged — is evaluated once with the tracing scalar [`Traced`], which
//! records every operation into a [`Graph`]; the derivatives that the equations of motion need are
//! built on that graph by the chain rule ([`derive`](mod@derive): reverse accumulation for gradients, forward
//! for derivatives along the flow), the linear solve is unrolled into it ([`ldlt`]), and every node
//! is simplified and shared as it is built (constant folding, algebraic identities, one node per
//! common subexpression across all outputs). The outputs then run as a flat [`Program`] over
//! registers: interpreted, or with the feature `jit` compiled once to native code by Cranelift
//! (bit for bit the same results; [`Backend`] tells which). This is automatic differentiation done once, as CasADi and JAX do it, not derivatives
//! by hand.
//!
//! A compiled system implements the same system traits as the one it came from, so every integrator
//! and the driver run on it unchanged:
//!
//! ```
//! use noether_compile::Compile;
//! use noether_core::{lagrangian, Dynamics, EulerLagrange};
//! // A pendulum: L = ½ m l² θ̇² + m g l cos θ.
//! let pendulum = lagrangian!(dof = 1, params { m: f64 = 1.0, l: f64 = 2.0, g: f64 = 9.81 }, |_t, q, v| {
//!     v[0] * v[0] * (0.5 * m * l * l) + q[0].cos() * (m * g * l)
//! });
//! let compiled = EulerLagrange::new(pendulum).compile().unwrap();
//! let (mut dq, mut dv) = ([0.0], [0.0]);
//! compiled.rates(0.0, &[0.5], &[0.0], &mut dq, &mut dv).unwrap();
//! assert!((dv[0] + 9.81 / 2.0 * 0.5_f64.sin()).abs() < 1e-15); // θ̈ = −(g/l) sin θ
//! ```
//!
//! **Branches.** A recording holds for the control flow it took. Comparisons in the model are
//! recorded as guards, checked at every call; where one fails (and wherever the compiled result is
//! not usable: a non-positive pivot of the mass matrix, a non-finite value) the call goes to the
//! dual-number path, which gives the right answer or the right error. A model that reads the value
//! of a traced number is refused ([`Error::Refused`]).

#[macro_use]
mod constructors;
mod default_method;
pub mod derive;
mod error;
pub mod euler_lagrange;
pub mod graph;
pub mod hamilton_equations;
pub mod ldlt;
pub mod legendre;
#[cfg(feature = "jit")]
mod native;
pub mod natural;
mod program;
pub mod show;
mod trace;

pub use error::{Error, Result};
pub use euler_lagrange::{CompiledEulerLagrange, Operations, UNROLL_MAX};
pub use graph::Graph;
pub use hamilton_equations::CompiledHamiltonEquations;
pub use natural::CompiledNatural;
pub use program::{Backend, Outputs, Program};
pub use show::{Equations, Notation, Term};
pub use trace::{record, Guard, Recording, Traced};

/// Turns a system into its compiled form, with one call.
pub trait Compile {
    /// The compiled system.
    type Compiled;
    /// Records the model, derives its equations on the graph and builds the program.
    fn compile(self) -> Result<Self::Compiled>;
}
