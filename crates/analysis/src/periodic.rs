//! Periodic orbits of autonomous systems by shooting, and their Floquet multipliers.
//!
//! A periodic orbit is a fixed point of the flow over one period, φ_T(y₀) = y₀. [`Shooting`] finds it
//! with noether-core's Newton ([`noether_core::newton::solve_dense`]) on the unknowns
//! (y₀, T, λ): the map it shoots with is the numerical one, N fixed steps h = T/N of any
//! [`TangentStepper`], so the orbit found is an exact periodic orbit of the discrete map y ↦ Φ_h^N(y)
//! (the flow's to the method's order, O(h^p)).
//!
//! # The equations
//!
//! ```text
//! Φ_{T/N}^N(y₀) − y₀ + Σ_k λ_k ∇I_k(y₀) = 0     (2n periodicity equations, unfolded)
//! ⟨F(y*), y₀ − y*⟩ = 0                            (phase: y₀ on the plane through the guess y* ⟂ the flow)
//! I_j(y₀) = c_j                                   (fixed levels, e.g. the energy H(y₀) = E)
//! ⟨g_s(y*), y₀ − y*⟩ = 0                          (one phase per continuous symmetry g_s: rotations, ...)
//! ```
//!
//! **Why unfolding.** A first integral I (the energy of a Hamiltonian system) makes periodic orbits
//! come in families, one per level of I, and makes the periodicity equations dependent: one
//! combination of them, the change of I over a period, vanishes identically. Fixing the level,
//! I(y₀) = c, picks one orbit of the family but leaves one equation too many. Following Muñoz-Almaraz,
//! Freire, Galán, Doedel & Vanderbauwhede (*Physica D* 181, 2003, "Continuation of periodic orbits in
//! conservative and Hamiltonian systems") and AUTO, every first integral gets an *unfolding parameter*
//! λ_k, an extra unknown multiplying ∇I_k: the system is square and regular, and for the exact flow
//! λ_k = 0 at every solution (I(φ_T y₀) = I(y₀) forces it). For the discrete map, which conserves the
//! integrals only to O(h^p), λ_k comes out O(h^p) and measures just that: it is the unfolding that
//! lets an exactly periodic orbit of the *discrete* map exist at all (a non-symplectic method breaks
//! the family into isolated orbits or none). Each declared integral pairs with one condition: a fixed
//! level ([`Shooting::level`]), a symmetry phase ([`Shooting::symmetry`], with [`Shooting::unfold`]) or
//! the fixed period ([`Shooting::fixed_period`]: the period is then not an unknown and the energy is
//! free — the other way to pick a member of the family). Without integrals (a limit cycle of a
//! dissipative system) the unknowns are (y₀, T) and the equations periodicity + phase.
//!
//! **The Jacobian.** ∂/∂y₀ of the periodicity equations is M − I, with the monodromy matrix
//! M = Ψ_{N−1} ⋯ Ψ₀, the product of the steps' exact Jacobians ([`TangentStepper`]). The λ-terms'
//! own y₀-derivative Σ λ_k ∇²I_k is left out (λ = O(h^p) at the solution). ∂/∂T is taken as
//! F(y_N), the vector field at the end point: exact for the flow (d/dT φ_T(y₀) = F(φ_T(y₀))), and for
//! the discrete map (∂Φ_h^N/∂h)/N = F(y_N) + O(h^p). Both approximations change only the Jacobian,
//! not the residual, which is evaluated exactly (the same N steps); Newton with a Jacobian within
//! δ = O(h^p) of the true one still converges to the zero of the true residual — the exact discrete
//! periodic orbit — with its quadratic rate degraded to a linear one with ratio O(δ), which at
//! h^p ~ 1e-10 is indistinguishable from quadratic in a handful of iterations.
//!
//! # Multiple shooting
//!
//! With [`Shooting::segments`] m > 1 the period's N steps are cut into m arcs of N_j steps (N/m, the
//! first N mod m one more), each started from a node y_j of its own; the unknowns are (y₀, …, y_{m−1},
//! T, λ) and the periodicity equations become the continuity of the arcs,
//!
//! ```text
//! Φ_h^{N_j}(y_j) − y_{j+1} = 0   (j < m − 1),     Φ_h^{N_{m−1}}(y_{m−1}) − y₀ + Σ_k λ_k ∇I_k(y₀) = 0,
//! ```
//!
//! with the phase, levels and symmetries on y₀ as before. The Jacobian is block-cyclic: M_j (the arc's
//! tangent map) in arc j's rows under y_j, −I under y_{j+1}, F(end of arc j)·N_j/N under T. Each M_j
//! grows an error by only about the m-th root of the largest multiplier, which is what lets Newton
//! converge on strongly unstable orbits (Stoer & Bulirsch, *Introduction to Numerical Analysis* §7.3.5;
//! the shooting of AUTO and of the three-body catalogues). The system is solved densely by core's LU
//! (2nm + 1 + k unknowns: a few hundred at most for the orbits this serves). The solution is the same
//! orbit of the same discrete map as single shooting's; [`PeriodicOrbit::nodes`] lists the nodes and
//! the monodromy is the product M_{m−1} ⋯ M₀ of the arcs' Jacobians at the solution.
//!
//! # Floquet multipliers
//!
//! The eigenvalues of M ([`floquet`]). A periodic orbit always has the multiplier 1 (the flow
//! direction F(y₀) is carried into itself) and each first integral and symmetry adds one more: for a
//! Hamiltonian orbit the pair (time shift, energy) gives a double multiplier 1 (a Jordan block),
//! rotations and angular momentum another pair. [`Shooting`] knows how many to expect
//! (1 + integrals + symmetries), [`floquet`] sets that many aside (those closest to 1) and judges the
//! rest: [`Stability::Unstable`] if one lies outside the unit circle, [`Stability::Stable`] if all lie
//! inside (an attracting limit cycle), [`Stability::Marginal`] when they lie on it (the best a
//! Hamiltonian orbit can do: linear, elliptic stability). A discrete map that is not symplectic moves
//! them off the circle by O(h^p T), and the defective double multiplier 1 splits by O(sqrt(h^p)): the
//! tolerance of the verdict has to be above both.
//!
//! ```
//! use noether_analysis::periodic::{Energy, Shooting, Stability};
//! use noether_core::prelude::*;
//!
//! /// Pendulum H = p²/2 − g cos q.
//! #[derive(Clone, Copy)]
//! struct Pendulum;
//! impl Hamiltonian for Pendulum {
//!     fn dof(&self) -> usize { 1 }
//!     fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
//!         p[0] * p[0] * 0.5 - q[0].cos()
//!     }
//! }
//! // The libration of energy E = −cos 1 (amplitude 1 rad), from a guess at 0.9 rad and period 6.
//! let rk4 = Rk4::new(HamiltonEquations::new(Pendulum));
//! let mut shooting = Shooting::new(rk4, 1000).unwrap().level(Energy(Pendulum), -1f64.cos());
//! let orbit = shooting.solve(&State::with_momenta(0.0, [0.9], [0.0]), 6.0).unwrap();
//! assert!((orbit.initial.q[0] - 1.0).abs() < 1e-12);  // the turning point
//! assert!((orbit.period - 6.6999757).abs() < 1e-6);   // 4 K(sin ½), g = l = 1
//! assert_eq!(orbit.floquet.stability, Stability::Marginal);
//! ```

use nalgebra::{Complex, DMatrix, DVector};
use noether_core::ad::{self, Block, Field};
use noether_core::newton::{solve_dense, DenseProblem};
use noether_core::tangent::run_jacobian;
use noether_core::{Hamiltonian, Newton, NewtonInfo, Scalar, State, TangentStepper};

use crate::{Error, Result};

/// A first integral I(q, v) of the system, in the stepper's state coordinates (q with velocities or
/// momenta): its value and gradient. Object-safe, so that one problem can hold several.
pub trait FirstIntegral {
    /// I(q, v).
    fn value(&self, q: &[f64], v: &[f64]) -> Result<f64>;
    /// ∇I into `dq` (∂I/∂q) and `dv` (∂I/∂v); returns I(q, v).
    fn gradient(&self, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<f64>;
}

/// A first integral written once for any scalar as an AD [`Field`] f(t, q, v) (evaluated at t = 0),
/// differentiated by dual numbers.
#[derive(Debug, Clone, Copy)]
pub struct Integral<F>(pub F);

impl<F: Field> FirstIntegral for Integral<F> {
    fn value(&self, q: &[f64], v: &[f64]) -> Result<f64> {
        finite_value("first integral", ad::value(&self.0, 0.0, q, v))
    }
    fn gradient(&self, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<f64> {
        gradient_of(&self.0, q, v, dq, dv)
    }
}

/// The energy H(0, q, p) of an autonomous [`Hamiltonian`], as a [`FirstIntegral`] on (q, p).
#[derive(Debug, Clone, Copy)]
pub struct Energy<H>(pub H);

/// H seen as an AD field.
struct HamiltonianField<'a, H>(&'a H);

impl<H: Hamiltonian> Field for HamiltonianField<'_, H> {
    fn eval<D: Scalar>(&self, t: D, x: &[D], y: &[D]) -> D {
        self.0.hamiltonian(t, x, y)
    }
}

impl<H: Hamiltonian> FirstIntegral for Energy<H> {
    fn value(&self, q: &[f64], p: &[f64]) -> Result<f64> {
        finite_value("energy", ad::value(&HamiltonianField(&self.0), 0.0, q, p))
    }
    fn gradient(&self, q: &[f64], p: &[f64], dq: &mut [f64], dp: &mut [f64]) -> Result<f64> {
        gradient_of(&HamiltonianField(&self.0), q, p, dq, dp)
    }
}

fn finite_value(what: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(noether_core::Error::NonFiniteResult {
            what,
            t: 0.0,
            component: None,
        }
        .into())
    }
}

fn gradient_of<F: Field>(f: &F, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) -> Result<f64> {
    noether_core::error::check_len("first integral gradient ∂I/∂q", dq, q.len())?;
    noether_core::error::check_len("first integral gradient ∂I/∂v", dv, v.len())?;
    let value = ad::gradient(f, 0.0, q, v, Block::X, dq);
    ad::gradient(f, 0.0, q, v, Block::Y, dv);
    if dq.iter().chain(dv.iter()).any(|g| !g.is_finite()) {
        return Err(noether_core::Error::NonFiniteResult {
            what: "first integral gradient",
            t: 0.0,
            component: None,
        }
        .into());
    }
    finite_value("first integral", value)
}

/// How an orbit came out of its multipliers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stability {
    /// Every non-trivial multiplier lies inside the unit circle: an attracting (asymptotically stable)
    /// periodic orbit, a limit cycle.
    Stable,
    /// Some multiplier lies outside the unit circle: nearby orbits leave at the rate |μ|^(t/T).
    Unstable,
    /// The non-trivial multipliers lie on the unit circle (within the tolerance): linearly stable but
    /// not attracting, as for an elliptic orbit of a Hamiltonian system.
    Marginal,
}

/// Floquet multipliers of a periodic orbit: the eigenvalues of its monodromy matrix.
#[derive(Debug, Clone, PartialEq)]
pub struct Floquet {
    /// All multipliers, the trivial ones first (nearest to 1 first), then the others by decreasing
    /// modulus.
    pub multipliers: Vec<Complex<f64>>,
    /// How many leading entries of `multipliers` are the trivial ones at 1 (flow direction, integrals,
    /// symmetries).
    pub trivial: usize,
    /// max |μ − 1| over the trivial multipliers: how far the method moved them from 1.
    pub trivial_deviation: f64,
    /// The verdict from the non-trivial multipliers.
    pub stability: Stability,
    /// Largest modulus of a non-trivial multiplier (1 when there is none).
    pub max_modulus: f64,
    /// The tolerance on |μ| used for the verdict.
    pub tolerance: f64,
}

impl Floquet {
    /// The non-trivial multipliers.
    pub fn nontrivial(&self) -> &[Complex<f64>] {
        &self.multipliers[self.trivial..]
    }
}

/// Floquet multipliers of the monodromy matrix `m` with `trivial` multipliers expected at 1, judged
/// with tolerance `tol` on their moduli: outside 1 + tol is unstable, all inside 1 − tol stable, else
/// marginal. Errors: `m` not square, or `trivial` larger than its size ([`Error::Core`] dimension
/// error), `tol` not finite and positive, non-finite entries, eigenvalues that do not converge
/// ([`Error::Eigen`]).
pub fn floquet(m: &DMatrix<f64>, trivial: usize, tol: f64) -> Result<Floquet> {
    noether_core::error::check_positive("Floquet tolerance", tol)?;
    if !m.is_square() {
        return Err(noether_core::Error::Dimension {
            what: "monodromy matrix (columns)",
            expected: m.nrows(),
            got: m.ncols(),
        }
        .into());
    }
    if trivial > m.nrows() {
        return Err(noether_core::Error::Dimension {
            what: "number of trivial Floquet multipliers (at most the dimension)",
            expected: m.nrows(),
            got: trivial,
        }
        .into());
    }
    if m.iter().any(|x| !x.is_finite()) {
        return Err(noether_core::Error::NonFiniteResult {
            what: "monodromy matrix",
            t: 0.0,
            component: None,
        }
        .into());
    }
    let schur = nalgebra::Schur::try_new(m.clone(), f64::EPSILON, 100_000).ok_or(Error::Eigen {
        what: "monodromy matrix (Floquet multipliers)",
    })?;
    let mut all: Vec<Complex<f64>> = schur.complex_eigenvalues().iter().copied().collect();
    let one = Complex::new(1.0, 0.0);
    all.sort_by(|a, b| (a - one).norm().total_cmp(&(b - one).norm()));
    let mut rest = all.split_off(trivial);
    rest.sort_by(|a, b| b.norm().total_cmp(&a.norm()).then(b.im.total_cmp(&a.im)));
    let trivial_deviation = all.iter().map(|z| (z - one).norm()).fold(0.0, f64::max);
    let max_modulus = rest.first().map_or(1.0, |z| z.norm());
    let stability = if max_modulus > 1.0 + tol {
        Stability::Unstable
    } else if !rest.is_empty() && max_modulus < 1.0 - tol {
        Stability::Stable
    } else {
        Stability::Marginal
    };
    all.extend(rest);
    Ok(Floquet {
        multipliers: all,
        trivial,
        trivial_deviation,
        stability,
        max_modulus,
        tolerance: tol,
    })
}

/// A periodic orbit found by [`Shooting::solve`].
#[derive(Debug, Clone)]
pub struct PeriodicOrbit<K: noether_core::Partner> {
    /// The initial state y₀ (at the guess's time), on the phase plane through the guess.
    pub initial: State<K>,
    /// The nodes of multiple shooting, y₀ first, each at its time along the orbit (one node, y₀, for
    /// single shooting).
    pub nodes: Vec<State<K>>,
    /// The period T (of the discrete map: N steps of h = T/N).
    pub period: f64,
    /// The steps per period N.
    pub steps: usize,
    /// The monodromy matrix M = ∂y_N/∂y₀ at the solution, ordered (q, v).
    pub monodromy: DMatrix<f64>,
    /// The unfolding parameters λ_k, one per declared first integral, in the order declared: zero for
    /// the exact flow, O(h^p) for the method (what it fails to conserve over a period).
    pub unfolding: Vec<f64>,
    /// ‖y_N − y₀‖∞ at the solution: how well the discrete orbit closes (the unfolding terms included,
    /// it is the Newton residual; this is without them); with several segments the largest defect
    /// ‖Φ_j(y_j) − y_{j+1}‖∞ of any segment's end against the next node.
    pub closure: f64,
    /// The Floquet multipliers and the verdict.
    pub floquet: Floquet,
    /// Newton's statistics.
    pub newton: NewtonInfo,
}

/// Finds periodic orbits by shooting with N fixed steps of a [`TangentStepper`] (see the
/// [module documentation](self) for the equations and the treatment of first integrals and symmetries).
///
/// Build with [`new`](Self::new), declare the integrals ([`level`](Self::level) for a fixed level,
/// [`unfold`](Self::unfold) for a free one) and symmetries ([`symmetry`](Self::symmetry)), then
/// [`solve`](Self::solve) from a guess. The counts must balance (checked, [`Error::ShootingSetup`]):
/// each integral pairs with a fixed level, a symmetry phase, or the fixed period.
pub struct Shooting<S> {
    stepper: S,
    steps: usize,
    newton: Newton,
    integrals: Vec<(Box<dyn FirstIntegral>, Option<f64>)>,
    symmetries: Vec<Vec<f64>>,
    fixed_period: bool,
    phase_coordinate: Option<(usize, f64)>,
    floquet_tol: f64,
    segments: usize,
}

impl<S: TangentStepper> Shooting<S> {
    /// Shooting with `steps` steps per period of `stepper` (an adaptive stepper is rejected: the step
    /// count must be fixed). Newton: core's defaults (residual 1e-12, step 1e-14, round-off aware stop) with 40 iterations; Floquet
    /// tolerance 1e-6.
    pub fn new(stepper: S, steps: usize) -> Result<Self> {
        if steps == 0 {
            return Err(noether_core::Error::InvalidParameter {
                name: "shooting steps per period",
                value: 0.0,
                reason: "at least one step per period",
            }
            .into());
        }
        if stepper.is_adaptive() {
            return Err(noether_core::Error::Unsupported(
                "shooting needs a fixed-step method: the period is cut into N equal steps",
            )
            .into());
        }
        let newton = Newton::default().max_iterations(40)?;
        Ok(Shooting {
            stepper,
            steps,
            newton,
            integrals: Vec::new(),
            symmetries: Vec::new(),
            fixed_period: false,
            phase_coordinate: None,
            floquet_tol: 1e-6,
            segments: 1,
        })
    }

    /// Multiple shooting: the period is cut into `segments` ≥ 1 arcs of (nearly) equal step counts,
    /// each started from a node of its own (see the module docs); 1 (the default) is single shooting.
    /// At most one segment per step, else `InvalidParameter`.
    pub fn segments(mut self, segments: usize) -> Result<Self> {
        if segments == 0 || segments > self.steps {
            return Err(noether_core::Error::InvalidParameter {
                name: "shooting segments",
                value: segments as f64,
                reason: "between 1 and the number of steps per period",
            }
            .into());
        }
        self.segments = segments;
        Ok(self)
    }

    /// The steps of each segment: N/m, the first N mod m one more.
    fn segment_steps(&self) -> Vec<usize> {
        let (m, n) = (self.segments, self.steps);
        (0..m).map(|j| n / m + usize::from(j < n % m)).collect()
    }

    /// Replaces the Newton settings.
    pub fn newton(mut self, newton: Newton) -> Self {
        self.newton = newton;
        self
    }

    /// Sets the tolerance on |μ| of the stability verdict (default 1e-6; finite, > 0, else
    /// `InvalidParameter`).
    pub fn floquet_tolerance(mut self, tol: f64) -> Result<Self> {
        self.floquet_tol = noether_core::error::check_positive("Floquet tolerance", tol)?;
        Ok(self)
    }

    /// Declares a first integral held at the level I(y₀) = `value` (e.g. the energy), with its
    /// unfolding parameter.
    pub fn level(mut self, integral: impl FirstIntegral + 'static, value: f64) -> Self {
        self.integrals.push((Box::new(integral), Some(value)));
        self
    }

    /// Declares a first integral whose level is left free (it pairs with a symmetry phase, e.g. the
    /// angular momentum with the rotations, or with the fixed period), with its unfolding parameter.
    pub fn unfold(mut self, integral: impl FirstIntegral + 'static) -> Self {
        self.integrals.push((Box::new(integral), None));
        self
    }

    /// Declares a continuous symmetry by its generator g at the guess (length 2n, ordered (q, v)): the
    /// phase condition ⟨g, y₀ − y*⟩ = 0 fixes where on the symmetry group's orbit the solution sits
    /// (e.g. g = (1, 0, 1, 0, …; 0, …) for translations along x: the centre of mass stays put).
    pub fn symmetry(mut self, generator: impl Into<Vec<f64>>) -> Self {
        self.symmetries.push(generator.into());
        self
    }

    /// Replaces the phase condition ⟨F(y*), y₀ − y*⟩ = 0 by y₀\[index\] = `value` (index into (q, v)):
    /// the orbit is started where that coordinate takes that value (a Poincaré section; the flow must
    /// cross it, ∂y_index/∂t ≠ 0 there, or the Jacobian is singular). Checked at `solve`: index < 2n.
    pub fn phase_coordinate(mut self, index: usize, value: f64) -> Self {
        self.phase_coordinate = Some((index, value));
        self
    }

    /// Holds the period at the guessed value instead of solving for it (then one declared integral
    /// has its level free: the family is cut by the period instead).
    pub fn fixed_period(mut self) -> Self {
        self.fixed_period = true;
        self
    }

    /// The Newton settings.
    pub(crate) fn newton_settings(&self) -> Newton {
        self.newton
    }

    /// A family is continued in the level of the first fixed-level integral, with the period free:
    /// `InvalidParameter` otherwise.
    pub(crate) fn check_family(&self) -> Result<()> {
        if self.fixed_period || !self.integrals.iter().any(|(_, c)| c.is_some()) {
            return Err(noether_core::Error::InvalidParameter {
                name: "continuation",
                value: f64::NAN,
                reason: "the family is followed in the level of a first integral declared with `level`, with the period free",
            }
            .into());
        }
        Ok(())
    }

    /// The stepper (to inspect or reconfigure it).
    pub fn stepper_mut(&mut self) -> &mut S {
        &mut self.stepper
    }

    /// Number of trivial multipliers at 1 expected from the declarations: 1 (the flow) + one per first
    /// integral + one per symmetry.
    pub fn trivial_multipliers(&self) -> usize {
        1 + self.integrals.len() + self.symmetries.len()
    }

    /// The end state y_N of N steps from `initial` over `period` and the monodromy matrix M.
    pub fn monodromy(
        &mut self,
        initial: &State<S::Partner>,
        period: f64,
    ) -> Result<(State<S::Partner>, DMatrix<f64>)> {
        check_period(period)?;
        initial.validate(self.stepper.dof())?;
        run(
            &mut self.stepper,
            self.steps,
            initial,
            period / self.steps as f64,
            true,
        )
    }

    /// Finds the periodic orbit near `guess` (a state y*) with period near `period`. With several
    /// [`segments`](Self::segments) the other nodes start where the guess's own run with the guessed
    /// period reaches them; [`solve_nodes`](Self::solve_nodes) takes them from elsewhere.
    ///
    /// Errors: a non-positive or non-finite period ([`Error::InvalidPeriod`], also when Newton drives
    /// T there), a guess of the wrong size or not finite, a guess at an equilibrium (F(y*) = 0,
    /// [`Error::Equilibrium`], also when Newton converges to one: for an undeclared integral the discrete map's only nearby "periodic orbit" is often the rest point inside the family), unbalanced declarations ([`Error::ShootingSetup`]), a symmetry
    /// generator of the wrong length, a singular shooting Jacobian ([`Error::DegenerateOrbit`]: an
    /// undeclared integral or symmetry, or a degenerate orbit), no convergence
    /// ([`Error::ShootingDiverged`] with the iteration count and residual), and the stepper's errors.
    pub fn solve(&mut self, guess: &State<S::Partner>, period: f64) -> Result<PeriodicOrbit<S::Partner>> {
        self.check_setup(guess, period)?;
        let h = period / self.steps as f64;
        let mut nodes = vec![guess.clone()];
        for &steps in &self.segment_steps()[..self.segments - 1] {
            let (next, _) = run(&mut self.stepper, steps, &nodes[nodes.len() - 1], h, false)?;
            nodes.push(next);
        }
        self.solve_nodes(&nodes, period)
    }

    /// Finds the periodic orbit through nodes near `nodes` (one per segment, in order along the orbit,
    /// the first the guess y* that the phase conditions refer to) with period near `period`: the
    /// start of a strongly unstable orbit from a guess of the whole orbit (a linearisation, or the
    /// previous member of a family). Errors as [`solve`](Self::solve), and a count of nodes other than
    /// the segments' (`Dimension`).
    pub fn solve_nodes(
        &mut self,
        nodes: &[State<S::Partner>],
        period: f64,
    ) -> Result<PeriodicOrbit<S::Partner>> {
        let n = self.stepper.dof();
        noether_core::error::check_len("multiple-shooting nodes (one per segment)", nodes, self.segments)?;
        let guess = &nodes[0];
        self.check_setup(guess, period)?;
        for node in nodes {
            node.validate(n)?;
        }
        let mut x0: Vec<f64> = nodes
            .iter()
            .flat_map(|y| y.q.iter().chain(y.v.iter()).copied().collect::<Vec<_>>())
            .collect();
        if !self.fixed_period {
            x0.push(period);
        }
        x0.extend(std::iter::repeat_n(0.0, self.integrals.len()));
        let newton = self.newton;
        let (problem, speed) = self.equations(guess, period)?;
        let (x, info) = solve_dense(&newton, problem, &x0).map_err(|e| shooting_error(Error::from(e)))?;
        self.orbit_at(x.as_slice(), guess.t, period, speed, info)
    }

    /// The shooting equations with the phase conditions at `guess` (and the period held at `period`
    /// when it is fixed), and the largest rate |F| at the guess.
    pub(crate) fn equations(
        &mut self,
        guess: &State<S::Partner>,
        period: f64,
    ) -> Result<(Problem<'_, S>, f64)> {
        let (speed, reference, phase) = self.phase_plane(guess)?;
        let segment_steps = self.segment_steps();
        let problem = Problem {
            n: self.stepper.dof(),
            stepper: &mut self.stepper,
            steps: self.steps,
            segment_steps,
            t0: guess.t,
            fixed_period: self.fixed_period.then_some(period),
            integrals: &self.integrals,
            symmetries: &self.symmetries,
            reference,
            phase,
            level: None,
        };
        Ok((problem, speed))
    }

    /// The periodic orbit of the unknowns `x` (nodes, T unless fixed at `period`, λ) that Newton found:
    /// its nodes at their times from `t0`, the arcs' monodromy and defects, the Floquet verdict.
    /// [`Error::Equilibrium`] when its largest rate is below 1e-8 of `speed`, the guess's.
    pub(crate) fn orbit_at(
        &mut self,
        x: &[f64],
        t0: f64,
        period: f64,
        speed: f64,
        info: NewtonInfo,
    ) -> Result<PeriodicOrbit<S::Partner>> {
        let (n, m, k) = (self.stepper.dof(), self.segments, self.integrals.len());
        let period = if self.fixed_period { period } else { x[2 * n * m] };
        let h = period / self.steps as f64;
        let segment_steps = self.segment_steps();
        let mut nodes = Vec::with_capacity(m);
        let mut before = 0;
        for (j, &steps) in segment_steps.iter().enumerate() {
            let y = &x[2 * n * j..2 * n * (j + 1)];
            nodes.push(State::from_parts(t0 + before as f64 * h, &y[..n], &y[n..]));
            before += steps;
        }
        self.check_not_at_rest(&nodes[0], speed)?;
        let (monodromy, closure) = self.arcs_at(&nodes, &segment_steps, h)?;
        let floquet = floquet(
            &monodromy,
            self.trivial_multipliers().min(2 * n),
            self.floquet_tol,
        )?;
        Ok(PeriodicOrbit {
            initial: nodes[0].clone(),
            nodes,
            period,
            steps: self.steps,
            monodromy,
            unfolding: x[x.len() - k..].to_vec(),
            closure,
            floquet,
            newton: info,
        })
    }

    /// The arcs at the solution: M = M_{m−1} ⋯ M₀ and the largest continuity defect
    /// ‖Φ_h^{N_j}(y_j) − y_{j+1}‖∞ (the last arc against y₀).
    fn arcs_at(
        &mut self,
        nodes: &[State<S::Partner>],
        segment_steps: &[usize],
        h: f64,
    ) -> Result<(DMatrix<f64>, f64)> {
        let d = 2 * self.stepper.dof();
        let mut monodromy = DMatrix::identity(d, d);
        let mut closure = 0.0_f64;
        for (j, &steps) in segment_steps.iter().enumerate() {
            let (end, mj) = run(&mut self.stepper, steps, &nodes[j], h, true)?;
            monodromy = mj * monodromy;
            let next = &nodes[(j + 1) % nodes.len()];
            closure = end
                .q
                .iter()
                .chain(end.v.iter())
                .zip(next.q.iter().chain(next.v.iter()))
                .fold(closure, |c, (a, b)| c.max((a - b).abs()));
        }
        Ok((monodromy, closure))
    }

    /// Checks the input of [`solve`](Self::solve): the period, the guess, the symmetry generators'
    /// lengths (2n), and that the unknowns (y₀, T unless fixed, one unfolding parameter per integral)
    /// balance the equations (closure, phase, the integrals' levels, one per symmetry).
    fn check_setup(&self, guess: &State<S::Partner>, period: f64) -> Result<()> {
        let n = self.stepper.dof();
        check_period(period)?;
        guess.validate(n)?;
        for g in &self.symmetries {
            noether_core::error::check_len("symmetry generator (length 2n)", g, 2 * n)?;
        }
        let k = self.integrals.len();
        let levels = self.integrals.iter().filter(|(_, c)| c.is_some()).count();
        let unknowns = 2 * n + usize::from(!self.fixed_period) + k;
        let equations = 2 * n + 1 + levels + self.symmetries.len();
        if unknowns != equations {
            return Err(Error::ShootingSetup { unknowns, equations });
        }
        Ok(())
    }

    /// The phase condition at the guess y*: the largest rate |F(y*)| (an [`Error::Equilibrium`] when
    /// it is 0), y* itself, and the phase plane ⟨normal, y₀ − point⟩ = 0 as (normal, point): the plane
    /// through y* normal to the flow F(y*), or, with a phase coordinate (i, value), the plane
    /// y₀,i = value (normal e_i, y* with its i-th entry replaced by the value).
    #[allow(clippy::type_complexity)]
    fn phase_plane(&self, guess: &State<S::Partner>) -> Result<(f64, Vec<f64>, (Vec<f64>, Vec<f64>))> {
        let n = self.stepper.dof();
        let (mut fq, mut fv) = (vec![0.0; n], vec![0.0; n]);
        vector_field(&self.stepper, guess, &mut fq, &mut fv)?;
        let flow: Vec<f64> = fq.into_iter().chain(fv).collect();
        let speed = flow.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        if speed == 0.0 {
            return Err(Error::Equilibrium { rate_norm: speed });
        }
        let reference: Vec<f64> = guess.q.iter().chain(guess.v.iter()).copied().collect();
        let plane = match self.phase_coordinate {
            None => (flow, reference.clone()),
            Some((i, value)) => {
                if i >= 2 * n || !value.is_finite() {
                    return Err(noether_core::Error::InvalidParameter {
                        name: "phase coordinate (index into (q, v), finite value)",
                        value: i as f64,
                        reason: "the index must be below 2n and the value finite",
                    }
                    .into());
                }
                let mut e = vec![0.0; 2 * n];
                e[i] = 1.0;
                let mut r = reference.clone();
                r[i] = value;
                (e, r)
            }
        };
        Ok((speed, reference, plane))
    }

    /// A rest point solves the shooting equations too (with any period): [`Error::Equilibrium`] when
    /// the largest rate |F| at the converged `initial` is below 1e-8 of `speed`, the one at the guess.
    fn check_not_at_rest(&self, initial: &State<S::Partner>, speed: f64) -> Result<()> {
        let n = self.stepper.dof();
        let (mut fq, mut fv) = (vec![0.0; n], vec![0.0; n]);
        vector_field(&self.stepper, initial, &mut fq, &mut fv)?;
        let rate = fq.iter().chain(fv.iter()).fold(0.0_f64, |m, x| m.max(x.abs()));
        if rate <= 1e-8 * speed {
            return Err(Error::Equilibrium { rate_norm: rate });
        }
        Ok(())
    }
}

/// The shooting Newton's failures as the orbit's: no convergence is [`Error::ShootingDiverged`], a
/// singular Jacobian [`Error::DegenerateOrbit`]; other errors pass unchanged.
fn shooting_error(e: Error) -> Error {
    match e {
        Error::Core(noether_core::Error::NewtonDiverged {
            iterations,
            residual,
            tolerance,
            ..
        }) => Error::ShootingDiverged {
            iterations,
            residual,
            tolerance,
        },
        Error::Core(noether_core::Error::SingularMatrix { pivot_ratio, .. }) => {
            Error::DegenerateOrbit { pivot_ratio }
        }
        other => other,
    }
}

fn check_period(period: f64) -> Result<()> {
    if period.is_finite() && period > 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidPeriod { period })
    }
}

/// F(y) from the stepper, or an error when it has no vector field.
fn vector_field<S: TangentStepper>(
    stepper: &S,
    state: &State<S::Partner>,
    fq: &mut [f64],
    fv: &mut [f64],
) -> Result<()> {
    match stepper.rates(state, fq, fv) {
        Some(r) => Ok(r?),
        None => Err(noether_core::Error::Unsupported(
            "shooting needs the vector field F(y) (Stepper::rates) for the phase condition and ∂y(T)/∂T",
        )
        .into()),
    }
}

/// `steps` steps of h from `initial`; with `tangent`, also M = Ψ_{N−1} ⋯ Ψ₀ (else M is empty).
fn run<S: TangentStepper>(
    stepper: &mut S,
    steps: usize,
    initial: &State<S::Partner>,
    h: f64,
    tangent: bool,
) -> Result<(State<S::Partner>, DMatrix<f64>)> {
    let mut state = initial.clone();
    if !tangent {
        for _ in 0..steps {
            stepper.step(&mut state, h)?;
        }
        return Ok((state, DMatrix::zeros(0, 0)));
    }
    let m = run_jacobian(stepper, &mut state, h, steps)?;
    Ok((state, m))
}

/// The shooting equations as a dense Newton problem; unknowns (y₀, …, y_{m−1}, [T], λ).
pub(crate) struct Problem<'a, S> {
    stepper: &'a mut S,
    /// Steps per period N (h = T/N).
    steps: usize,
    /// Steps of each segment (m of them, summing to N).
    segment_steps: Vec<usize>,
    n: usize,
    t0: f64,
    fixed_period: Option<f64>,
    integrals: &'a [(Box<dyn FirstIntegral>, Option<f64>)],
    symmetries: &'a [Vec<f64>],
    reference: Vec<f64>,
    /// The time-phase row: normal and reference point.
    phase: (Vec<f64>, Vec<f64>),
    /// When set, the level of the first fixed-level integral instead of the declared one (the family
    /// parameter of a continuation).
    pub(crate) level: Option<f64>,
}

impl<S: TangentStepper> Problem<'_, S> {
    /// The row of the first fixed level (after the arcs' rows and the phase row).
    pub(crate) fn level_row(&self) -> usize {
        2 * self.n * self.segment_steps.len() + 1
    }

    /// The period and the unfolding parameters from the unknowns.
    fn split<'x>(&self, x: &'x [f64]) -> Result<(f64, &'x [f64])> {
        let nodes = 2 * self.n * self.segment_steps.len();
        let (period, lambda) = match self.fixed_period {
            Some(t) => (t, &x[nodes..]),
            None => (x[nodes], &x[nodes + 1..]),
        };
        check_period(period)?;
        Ok((period, lambda))
    }

    /// The arcs' rows: Φ_h^{N_j}(y_j) − y_{j+1} into `r`; with `jac` (zeroed), their blocks M_j, −I and
    /// ∂/∂T = F(end)·N_j/N.
    fn arcs(
        &mut self,
        x: &[f64],
        period: f64,
        r: &mut [f64],
        mut jac: Option<&mut DMatrix<f64>>,
    ) -> Result<()> {
        let (n, m) = (self.n, self.segment_steps.len());
        let d = 2 * n;
        let h = period / self.steps as f64;
        let node = |j: usize| &x[d * j..d * (j + 1)];
        let t_col = d * m;
        let mut start = self.t0;
        for (seg, &steps) in self.segment_steps.iter().enumerate() {
            let y = node(seg);
            let y_next = node((seg + 1) % m);
            let from = State::from_parts(start, &y[..n], &y[n..]);
            let (end, mj) = run(self.stepper, steps, &from, h, jac.is_some())?;
            start += h * steps as f64;
            let rows = d * seg;
            for i in 0..n {
                r[rows + i] = end.q[i] - y_next[i];
                r[rows + n + i] = end.v[i] - y_next[n + i];
            }
            let Some(j) = jac.as_deref_mut() else { continue };
            let next_cols = d * ((seg + 1) % m);
            for a in 0..d {
                for b in 0..d {
                    j[(rows + a, d * seg + b)] += mj[(a, b)];
                }
                j[(rows + a, next_cols + a)] -= 1.0;
            }
            if self.fixed_period.is_none() {
                // ∂ end / ∂T = F(end) · (the segment's share of the period, steps/N).
                let (mut fq, mut fv) = (vec![0.0; n], vec![0.0; n]);
                vector_field(self.stepper, &end, &mut fq, &mut fv)?;
                let share = steps as f64 / self.steps as f64;
                for i in 0..n {
                    j[(rows + i, t_col)] = fq[i] * share;
                    j[(rows + n + i, t_col)] = fv[i] * share;
                }
            }
        }
        Ok(())
    }

    /// The residual; with `jac`, also the Jacobian. Rows: the segments' continuity
    /// Φ_j(y_j) − y_{j+1} (the last closing on y₀, with the unfolding terms), the phase, the levels,
    /// the symmetries; columns: the nodes, T, λ.
    fn evaluate(&mut self, x: &[f64], r: &mut [f64], mut jac: Option<&mut DMatrix<f64>>) -> Result<()> {
        let (n, m) = (self.n, self.segment_steps.len());
        let d = 2 * n;
        let (period, lambda) = match self.split(x) {
            Ok(split) => split,
            // A correction that drives T to zero or below leaves the problem's domain: a non-finite
            // residual, which Newton halves back toward the last iterate (the Jacobian is only asked
            // for at accepted iterates, whose period is valid).
            Err(Error::InvalidPeriod { .. }) if jac.is_none() => {
                r.fill(f64::NAN);
                return Ok(());
            }
            Err(e) => return Err(e),
        };
        if let Some(j) = jac.as_deref_mut() {
            j.fill(0.0);
        }
        self.arcs(x, period, r, jac.as_deref_mut())?;
        let y0v = &x[..d];
        // Integrals at y₀: unfolding terms in the closing segment's rows, levels as their own rows.
        let y0 = State::<S::Partner>::from_parts(self.t0, &y0v[..n], &y0v[n..]);
        let closing = d * (m - 1);
        let mut grads = Vec::with_capacity(self.integrals.len());
        let (mut gq, mut gv) = (vec![0.0; n], vec![0.0; n]);
        let mut row = d * m + 1;
        for ((integral, level), &l) in self.integrals.iter().zip(lambda) {
            let value = integral.gradient(y0.q.as_slice(), y0.v.as_slice(), &mut gq, &mut gv)?;
            let g: Vec<f64> = gq.iter().chain(gv.iter()).copied().collect();
            for (ri, gi) in r[closing..closing + d].iter_mut().zip(&g) {
                *ri += l * gi;
            }
            if let Some(c) = level {
                // The first level is the family parameter when a continuation sets it.
                let c = if row == d * m + 1 {
                    self.level.unwrap_or(*c)
                } else {
                    *c
                };
                r[row] = value - c;
                row += 1;
            }
            grads.push((g, level.is_some()));
        }
        // Phase rows.
        r[d * m] = dot_diff(&self.phase.0, y0v, &self.phase.1);
        for g in self.symmetries {
            r[row] = dot_diff(g, y0v, &self.reference);
            row += 1;
        }
        let Some(j) = jac else { return Ok(()) };
        // The unfolding columns follow the nodes' and T's (if T is an unknown).
        let first_lambda = d * m + usize::from(self.fixed_period.is_none());
        let mut row = d * m + 1;
        for (col, (g, is_level)) in (first_lambda..).zip(&grads) {
            for (a, gi) in g.iter().enumerate() {
                j[(closing + a, col)] = *gi;
                if *is_level {
                    j[(row, a)] = *gi;
                }
            }
            if *is_level {
                row += 1;
            }
        }
        for (b, fb) in self.phase.0.iter().enumerate() {
            j[(d * m, b)] = *fb;
        }
        for g in self.symmetries {
            for (b, gb) in g.iter().enumerate() {
                j[(row, b)] = *gb;
            }
            row += 1;
        }
        Ok(())
    }
}

fn dot_diff(a: &[f64], y: &[f64], y_ref: &[f64]) -> f64 {
    a.iter()
        .zip(y.iter().zip(y_ref))
        .map(|(ai, (yi, ri))| ai * (yi - ri))
        .sum()
}

impl<S: TangentStepper> DenseProblem for Problem<'_, S> {
    fn dim(&self) -> usize {
        2 * self.n * self.segment_steps.len()
            + usize::from(self.fixed_period.is_none())
            + self.integrals.len()
    }
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> noether_core::Result<()> {
        Ok(self.evaluate(x, r, None)?)
    }
    fn jacobian(&mut self, x: &[f64], j: &mut DMatrix<f64>) -> noether_core::Result<()> {
        let mut r = vec![0.0; self.dim()];
        Ok(self.evaluate(x, &mut r, Some(j))?)
    }
}

/// The state vector (q, v) of a state, as one vector.
pub fn state_vector<K: noether_core::Partner>(state: &State<K>) -> DVector<f64> {
    DVector::from_iterator(2 * state.dof(), state.q.iter().chain(state.v.iter()).copied())
}
