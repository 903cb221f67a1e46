//! Action-angle variables of a one-degree-of-freedom H(q, p), numerically: [`ActionAngle`].
//!
//! At energy E the orbit is the level curve H(q, p) = E. Two kinds of periodic motion:
//! - **libration** between two turning points q₋ < q₊: the action is the enclosed area over 2π,
//!   J(E) = (1/2π) ∮ p dq = (1/2π) ∫_{q₋}^{q₊} (p₊ − p₋) dq, with p₊ > p₋ the two roots of
//!   H(q, p) = E ([`Libration`]);
//! - **rotation** of a periodic coordinate q (period Q): J(E) = (1/2π) ∫_{q₀}^{q₀+Q} p dq on one
//!   branch p(q) ([`Rotation`]).
//!
//! The frequency is ω = dE/dJ; since ∂p/∂E = 1/(∂H/∂p), dJ/dE = (1/2π) ∮ dq/(∂H/∂p) = T/2π with T
//! the period, so ω = 2π/T. The angle conjugate to J grows uniformly, θ = ω t, and is computed along
//! the orbit as ω times the time from the angle's origin (the lower turning point of a libration,
//! q₀ for a rotation): t(q) = ∫ dq/(∂H/∂p).
//!
//! **A general H.** Nothing assumes H = T(p) + V(q). At each q the momentum p*(q) where ∂H/∂p = 0
//! (the bottom of H over p, which must be convex in p for a libration) comes from core's
//! [`Newton`] with ∂H/∂p and ∂²H/∂p² by dual numbers; the turning points are the roots of
//! h*(q) − E, h*(q) = H(q, p*(q)), bracketed by a search outwards from a point inside the well and
//! closed by core's [`bracketed_root`]; the two momenta p± are the roots of H(q, ·) = E on either side
//! of p*, bracketed and closed the same way. For a rotation, p(q) comes from Newton warm-started
//! from node to node (so H may even be linear in p).
//!
//! **The quadrature.** Near a simple turning point p₊ − p₋ vanishes like sqrt(q − q₋) and
//! 1/(∂H/∂p) blows up like 1/sqrt(q − q₋): a naive rule converges slowly. The substitution
//! q = c − h cos φ (c, h the centre and half-width of [q₋, q₊], φ ∈ [0, π]) gives dq = h sin φ dφ,
//! and with (p₊ − p₋) = sqrt((q − q₋)(q₊ − q)) g(q) both integrands become
//! h² sin²φ g(c − h cos φ) and g̃(c − h cos φ): smooth functions of φ that are even and 2π-periodic.
//! The midpoint rule on φⱼ = (j + ½)π/N (which is Gauss-Chebyshev quadrature in q) then converges
//! geometrically, like the trapezoid rule for periodic analytic functions, and never evaluates at a
//! turning point. N is doubled from [`ActionAngle::nodes`] until two estimates of J and of T agree
//! to [`ActionAngle::tolerance`] (relative). A rotation's integrands are periodic in q already, and
//! the same midpoint rule applies without a substitution. The angle comes from the cosine (or
//! Fourier) series of the period integrand at the same nodes, integrated term by term.
//!
//! **Accuracy near the turning points.** There E − h*(q) and H(q, p* + δ) − h*(q) are small
//! differences of O(1) values, and the rounding of the user's H (ε times its size) would make
//! 1/(∂H/∂p) lose digits like 1/(E − h*): measured, T drifted by 1e-13 to 1e-10 as N grew. So where
//! E − h*(q) is below 1/20 of the well's depth, or below 1/20 of |E|, both differences are taken as
//! integrals of derivatives that dual numbers give exactly: E − h*(q) = ∫_q^{q_end} ∂H/∂q(x, p*(x)) dx
//! (the envelope theorem; q_end the nearer turning point, the distance to it taken from φ, not from
//! the rounded q) and H(q, p* + δ) − h*(q) = δ² ∫₀¹ (1 − s) ∂²H/∂p²(q, p* + sδ) ds, each by 12-point
//! Gauss-Legendre. What remains is the conditioning of the problem itself: E is a number of size |E|
//! known to ε|E|, so J and T carry a relative error of order ε|E|/(E − min h*) (measured 5e-15 for a
//! pendulum swinging 0.1 rad, where that ratio is 200; a few ulps elsewhere: tests/canonical/
//! action_angle.rs). Close to a separatrix T grows like log(1/|E − E_s|) and more nodes are
//! needed; the doubling stops at [`ActionAngle::max_nodes`] with [`Error::QuadratureNotConverged`].
//!
//! ```
//! use noether_canonical::ActionAngle;
//! use noether_core::{Hamiltonian, Scalar};
//!
//! /// Oscillator H = p²/2 + ω² q²/2 with ω = 3: J = E/ω.
//! struct Osc;
//! impl Hamiltonian for Osc {
//!     fn dof(&self) -> usize { 1 }
//!     fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
//!         p[0] * p[0] * 0.5 + q[0] * q[0] * 4.5
//!     }
//! }
//! let lib = ActionAngle::new(Osc).unwrap().libration(2.0, 0.0).unwrap();
//! assert!((lib.action - 2.0 / 3.0).abs() < 1e-14);
//! assert!((lib.frequency - 3.0).abs() < 1e-13);
//! ```

use crate::{Error, Result};
use noether_core::newton::{solve_dense, DenseProblem, Newton};
use noether_core::roots::bracketed_root;
use noether_core::{Hamiltonian, Scalar};
use num_dual::{first_derivative, second_derivative, Dual2_64, Dual64};
use std::cell::Cell;

mod rotation;
mod separated;
use rotation::rotation;
pub(crate) use rotation::rotation_with;
pub use separated::{Orbit, Separated, SeparatedActions, SeparatedResult};
use std::f64::consts::PI;

/// A one-degree-of-freedom h(q, p): a 1-dof [`Hamiltonian`] at a fixed time, or one separated part
/// of a multi-dof system at fixed separation constants.
pub(crate) trait Curve {
    /// h(q, p).
    fn h<D: Scalar>(&self, q: D, p: D) -> D;
}

/// A 1-dof Hamiltonian frozen at time t.
struct AtTime<'a, H> {
    h: &'a H,
    t: f64,
}

impl<H: Hamiltonian> Curve for AtTime<'_, H> {
    fn h<D: Scalar>(&self, q: D, p: D) -> D {
        self.h.hamiltonian(D::from(self.t), &[q], &[p])
    }
}

/// Action-angle variables of a one-degree-of-freedom [`Hamiltonian`] (see the module docs): turning
/// points, action, period, frequency and angle of librations and rotations at a given energy.
///
/// Build with [`ActionAngle::new`] and the validating setters.
#[derive(Debug, Clone)]
pub struct ActionAngle<H> {
    hamiltonian: H,
    t: f64,
    nodes: usize,
    max_nodes: usize,
    tolerance: f64,
    search_step: f64,
}

impl<H: Hamiltonian> ActionAngle<H> {
    /// Wraps a Hamiltonian with one degree of freedom (else [`Error::Core`] with a dimension error).
    /// Defaults: evaluated at t = 0, 16 starting nodes doubled up to 16384, relative tolerance 1e-14,
    /// turning-point search step 0.05.
    pub fn new(hamiltonian: H) -> Result<Self> {
        if hamiltonian.dof() != 1 {
            return Err(noether_core::Error::Dimension {
                what: "action-angle Hamiltonian dof",
                expected: 1,
                got: hamiltonian.dof(),
            }
            .into());
        }
        Ok(ActionAngle {
            hamiltonian,
            t: 0.0,
            nodes: 16,
            max_nodes: 16384,
            tolerance: 1e-14,
            search_step: 0.05,
        })
    }

    /// The time at which H is evaluated (H should not depend on it for the actions to mean anything;
    /// for an adiabatic change this is the frozen time). Must be finite.
    pub fn time(mut self, t: f64) -> Result<Self> {
        self.t = finite("action-angle time", t)?;
        Ok(self)
    }

    /// Starting number of quadrature nodes (≥ 2).
    pub fn nodes(mut self, n: usize) -> Result<Self> {
        if n < 2 {
            return Err(invalid("action-angle nodes", n as f64, "at least 2 nodes"));
        }
        self.nodes = n;
        Ok(self)
    }

    /// Largest number of quadrature nodes before [`Error::QuadratureNotConverged`] (≥ 2).
    pub fn max_nodes(mut self, n: usize) -> Result<Self> {
        if n < 2 {
            return Err(invalid("action-angle max_nodes", n as f64, "at least 2 nodes"));
        }
        self.max_nodes = n;
        Ok(self)
    }

    /// Relative agreement of two successive estimates (N and 2N nodes) that ends the doubling
    /// (finite, > 0).
    pub fn tolerance(mut self, tol: f64) -> Result<Self> {
        self.tolerance = positive("action-angle tolerance", tol)?;
        Ok(self)
    }

    /// Step of the outward search for the turning points (finite, > 0): the search walks in steps of
    /// this length (64 of them, then doubling), so it must be shorter than the narrowest barrier that
    /// should stop it.
    pub fn search_step(mut self, h: f64) -> Result<Self> {
        self.search_step = positive("action-angle search step", h)?;
        Ok(self)
    }

    /// The wrapped Hamiltonian.
    pub fn hamiltonian(&self) -> &H {
        &self.hamiltonian
    }

    fn curve(&self) -> AtTime<'_, H> {
        AtTime {
            h: &self.hamiltonian,
            t: self.t,
        }
    }

    fn settings(&self) -> Settings {
        Settings {
            nodes: self.nodes,
            max_nodes: self.max_nodes,
            tolerance: self.tolerance,
            search_step: self.search_step,
        }
    }

    /// The bottom of H over p at q: (p*, H(q, p*)) with ∂H/∂p(q, p*) = 0, by Newton from `guess`.
    pub fn momentum_minimum(&self, q: f64, guess: f64) -> Result<(f64, f64)> {
        let (p, h, _) = bottom(&self.curve(), q, guess)?;
        Ok((p, h))
    }

    /// The two momenta p₋ ≤ p₊ with H(q, p±) = E at q.
    pub fn momenta(&self, q: f64, energy: f64) -> Result<(f64, f64)> {
        let c = self.curve();
        let (ps, hs, hpp) = bottom(&c, q, 0.0)?;
        momenta(&c, q, energy, ps, hs, hpp)
    }

    /// The turning points q₋ < q₊ of the libration at `energy` around `q_inside` (a point where
    /// min over p of H is below the energy).
    pub fn turning_points(&self, energy: f64, q_inside: f64) -> Result<(f64, f64)> {
        turning_points(&self.curve(), energy, q_inside, self.search_step)
    }

    /// The libration at `energy` in the well around `q_inside`: turning points, action, period,
    /// frequency and the angle along the orbit.
    pub fn libration(&self, energy: f64, q_inside: f64) -> Result<Libration> {
        libration(&self.curve(), energy, q_inside, &self.settings())
    }

    /// The libration of H frozen at time `t` through the phase point (q, p), at the energy H(t, q, p)
    /// in the well around `q_inside`: for a slowly changing H its action is the adiabatic invariant.
    pub fn frozen_libration(&self, t: f64, q: f64, p: f64, q_inside: f64) -> Result<Libration> {
        let c = AtTime {
            h: &self.hamiltonian,
            t: finite("frozen time", t)?,
        };
        libration(&c, c.h(q, p), q_inside, &self.settings())
    }

    /// The angle θ ∈ [0, 2π) of the phase point (q, p) on the libration `lib` (its branch from the sign
    /// of p − p*(q)).
    ///
    /// A NaN or infinite q or p is [`noether_core::Error::NonFinite`].
    pub fn angle(&self, lib: &Libration, q: f64, p: f64) -> Result<f64> {
        noether_core::error::check_finite("q", &[q])?;
        noether_core::error::check_finite("p", &[p])?;
        let (ps, _) = self.momentum_minimum(q, p)?;
        lib.angle(q, p > ps)
    }

    /// The rotation at `energy` of a coordinate periodic with `period` (2π for an angle), on the branch
    /// through (`q0`, p ≈ `p_guess`): the sign of `p_guess` chooses the direction. The angle's origin
    /// is q₀.
    pub fn rotation(&self, energy: f64, q0: f64, period: f64, p_guess: f64) -> Result<Rotation> {
        rotation(&self.curve(), energy, q0, period, p_guess, &self.settings())
    }
}

/// The quadrature settings shared by the 1-dof and the separated actions.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Settings {
    pub(crate) nodes: usize,
    pub(crate) max_nodes: usize,
    pub(crate) tolerance: f64,
    pub(crate) search_step: f64,
}

/// A libration between two turning points (see the module docs).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Libration {
    /// The energy E.
    pub energy: f64,
    /// Lower turning point q₋.
    pub q_min: f64,
    /// Upper turning point q₊.
    pub q_max: f64,
    /// The action J = (1/2π) ∮ p dq.
    pub action: f64,
    /// The period T = ∮ dq/(∂H/∂p) = 2π dJ/dE.
    pub period: f64,
    /// The frequency ω = dE/dJ = 2π/T.
    pub frequency: f64,
    /// Quadrature nodes of the result.
    pub nodes: usize,
    /// |J(N) − J(N/2)|: an upper bound on the quadrature error of J (the N/2 estimate is the worse).
    pub action_change: f64,
    /// Cosine coefficients in φ of the time integrand on the upper branch (p = p₊).
    upper: Vec<f64>,
    /// The same on the lower branch.
    lower: Vec<f64>,
}

impl Libration {
    /// The time to go from q₋ to `q` on the upper branch (p > p*): ∫_{q₋}^{q} dq/(∂H/∂p). A q
    /// outside [q₋, q₊] is taken at the nearer turning point; a NaN or infinite q is
    /// [`noether_core::Error::NonFinite`] (it was a silent NaN before).
    pub fn time_upper(&self, q: f64) -> Result<f64> {
        let t = cosine_integral(&self.upper, self.phi(q)?);
        Ok(noether_core::error::finite_result("libration time", f64::NAN, t)?)
    }

    /// The time to go from q₊ back to `q` on the lower branch (p < p*) (q as in
    /// [`time_upper`](Self::time_upper)).
    pub fn time_lower(&self, q: f64) -> Result<f64> {
        let t = cosine_integral(&self.lower, PI) - cosine_integral(&self.lower, self.phi(q)?);
        Ok(noether_core::error::finite_result("libration time", f64::NAN, t)?)
    }

    /// The angle θ ∈ [0, 2π) at coordinate `q` of this orbit: ω times the time since the lower turning
    /// point, on the upper branch (p > p*(q)) when `upper` and on the lower one otherwise
    /// ([`ActionAngle::angle`] decides the branch from p). A NaN or infinite q is
    /// [`noether_core::Error::NonFinite`], never a NaN angle.
    pub fn angle(&self, q: f64, upper: bool) -> Result<f64> {
        let t = if upper {
            self.time_upper(q)?
        } else {
            cosine_integral(&self.upper, PI) + self.time_lower(q)?
        };
        let theta = (self.frequency * t).rem_euclid(2.0 * PI);
        Ok(noether_core::error::finite_result(
            "libration angle",
            f64::NAN,
            theta,
        )?)
    }

    /// φ ∈ [0, π] with q = c − h cos φ (q finite, else [`noether_core::Error::NonFinite`]).
    fn phi(&self, q: f64) -> Result<f64> {
        noether_core::error::check_finite("q", &[q])?;
        let c = 0.5 * (self.q_min + self.q_max);
        let h = 0.5 * (self.q_max - self.q_min);
        Ok(((c - q) / h).clamp(-1.0, 1.0).acos())
    }
}

/// ∫₀^φ g for g(φ) = a₀/2 + Σ aₖ cos kφ.
fn cosine_integral(a: &[f64], phi: f64) -> f64 {
    let mut s = 0.5 * a[0] * phi;
    for (k, ak) in a.iter().enumerate().skip(1) {
        s += ak * (k as f64 * phi).sin() / k as f64;
    }
    s
}

/// Cosine coefficients aₖ, k < N, of g sampled at φⱼ = (j + ½)π/N (a DCT-II).
fn cosine_coefficients(g: &[f64]) -> Vec<f64> {
    let n = g.len();
    (0..n)
        .map(|k| {
            let s: f64 = g
                .iter()
                .enumerate()
                .map(|(j, gj)| gj * (k as f64 * (j as f64 + 0.5) * PI / n as f64).cos())
                .sum();
            2.0 * s / n as f64
        })
        .collect()
}

/// A rotation of a periodic coordinate (see the module docs).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Rotation {
    /// The energy E.
    pub energy: f64,
    /// The angle's origin q₀.
    pub q0: f64,
    /// The coordinate's period Q.
    pub coordinate_period: f64,
    /// The action J = (1/2π) ∫_{q₀}^{q₀+Q} p dq (negative for a rotation towards decreasing q).
    pub action: f64,
    /// The period T > 0 of the motion.
    pub period: f64,
    /// The frequency ω = dE/dJ = ±2π/T (the sign of the motion).
    pub frequency: f64,
    /// Quadrature nodes of the result.
    pub nodes: usize,
    /// |J(N) − J(N/2)|.
    pub action_change: f64,
    /// Fourier coefficients (cos, sin) of the time integrand in s = 2π(q − q₀)/Q.
    series: (Vec<f64>, Vec<f64>),
}

impl Rotation {
    /// The angle θ at `q` (any real q, not reduced modulo Q): ω ∫_{q₀}^{q} dq/(∂H/∂p), growing by
    /// ±2π per turn.
    pub fn angle(&self, q: f64) -> f64 {
        let s = 2.0 * PI * (q - self.q0) / self.coordinate_period;
        self.frequency * fourier_integral(&self.series, s) * self.coordinate_period / (2.0 * PI)
    }
}

/// Newton on ∂h/∂p = 0: (p*, h(q, p*), ∂²h/∂p²(q, p*)).
pub(crate) fn bottom<C: Curve>(c: &C, q: f64, guess: f64) -> Result<(f64, f64, f64)> {
    struct Stationary<'a, C> {
        c: &'a C,
        q: f64,
    }
    impl<C: Curve> DenseProblem for Stationary<'_, C> {
        fn dim(&self) -> usize {
            1
        }
        fn residual(&mut self, x: &[f64], r: &mut [f64]) -> noether_core::Result<()> {
            r[0] = first_derivative(|p: Dual64| self.c.h(Dual64::from(self.q), p), x[0]).1;
            Ok(())
        }
        fn jacobian(&mut self, x: &[f64], j: &mut nalgebra::DMatrix<f64>) -> noether_core::Result<()> {
            j[(0, 0)] = second_derivative(|p: Dual2_64| self.c.h(Dual2_64::from(self.q), p), x[0]).2;
            Ok(())
        }
    }
    let (x, _) = solve_dense(&Newton::default(), Stationary { c, q }, &[guess])?;
    // Polish: Newton stops at |∂H/∂p| ≤ 1e-12; one more step (quadratic convergence) takes p* to
    // rounding, which the end corrections (Taylor's remainder about p*) rely on.
    let (_, hp, hpp) = second_derivative(|p: Dual2_64| c.h(Dual2_64::from(q), p), x[0]);
    let p = if hpp != 0.0 && hpp.is_finite() {
        x[0] - hp / hpp
    } else {
        x[0]
    };
    let (h, _, hpp) = second_derivative(|p: Dual2_64| c.h(Dual2_64::from(q), p), p);
    Ok((p, h, hpp))
}

/// The two roots p₋ ≤ p₊ of h(q, p) = E on either side of the bottom p* (value hs, curvature hpp).
pub(crate) fn momenta<C: Curve>(c: &C, q: f64, e: f64, ps: f64, hs: f64, hpp: f64) -> Result<(f64, f64)> {
    if hs >= e || hs.is_nan() {
        return Err(Error::EnergyBelowMinimum {
            energy: e,
            q,
            minimum: hs,
        });
    }
    // The quadratic model's root distance, widened until the bracket holds a sign change.
    let d0 = if hpp > 0.0 && hpp.is_finite() {
        (2.0 * (e - hs) / hpp).sqrt()
    } else {
        1.0
    };
    let f = |p: f64| c.h(q, p) - e;
    let side = |s: f64| -> Result<f64> {
        let mut d = 1.25 * d0;
        for _ in 0..200 {
            let fp = f(ps + s * d);
            if fp >= 0.0 {
                return Ok(bracketed_root(f, (ps, hs - e), (ps + s * d, fp))?);
            }
            if !fp.is_finite() {
                break;
            }
            d *= 2.0;
        }
        Err(Error::NoMomentum { energy: e, q })
    };
    let minus = side(-1.0)?;
    let plus = side(1.0)?;
    Ok((minus, plus))
}

/// ∂h/∂p at (q, p).
pub(crate) fn velocity<C: Curve>(c: &C, q: f64, p: f64) -> f64 {
    first_derivative(|p: Dual64| c.h(Dual64::from(q), p), p).1
}

/// Roots of h*(q) − E on both sides of `q_inside`.
pub(crate) fn turning_points<C: Curve>(c: &C, e: f64, q_inside: f64, step: f64) -> Result<(f64, f64)> {
    let (p0, h0, _) = bottom(c, q_inside, 0.0)?;
    if h0 >= e || h0.is_nan() {
        return Err(Error::EnergyBelowMinimum {
            energy: e,
            q: q_inside,
            minimum: h0,
        });
    }
    let last = Cell::new(p0);
    let g = |q: f64| match bottom(c, q, last.get()) {
        Ok((p, h, _)) => {
            last.set(p);
            h - e
        }
        Err(_) => f64::NAN,
    };
    let mut ends = [0.0; 2];
    for (end, (s, name)) in ends.iter_mut().zip([(-1.0, "lower"), (1.0, "upper")]) {
        last.set(p0);
        let (mut a, mut ga) = (q_inside, h0 - e);
        let mut h = step;
        let mut found = None;
        let mut k = 0;
        // 64 steps of `step`, then doubling: 0.05·2¹⁰³⁰ passes f64::MAX, so the search reaches any
        // finite turning point (the oscillator at E = 1e300 has them at ±1.4e150; a cap of 128 steps
        // stopped at 1.8e18).
        while k < 64 + 1100 {
            let b = a + s * h;
            if !b.is_finite() {
                break;
            }
            let gb = g(b);
            if !gb.is_finite() {
                // Outside the model's domain: come closer.
                h *= 0.5;
                if h < f64::EPSILON * (1.0 + a.abs()) {
                    break;
                }
                continue;
            }
            if gb >= 0.0 {
                found = Some((b, gb));
                break;
            }
            (a, ga) = (b, gb);
            k += 1;
            if k >= 64 {
                h *= 2.0;
            }
        }
        let Some((b, gb)) = found else {
            return Err(Error::NoTurningPoint {
                energy: e,
                from: q_inside,
                side: name,
                reached: a,
            });
        };
        last.set(p0);
        *end = bracketed_root(g, (a, ga), (b, gb))?;
    }
    Ok((ends[0], ends[1]))
}

/// Gauss-Legendre nodes and weights on [0, 1] (m points; Newton on Pₘ from Chebyshev guesses).
pub(crate) fn gauss_legendre(m: usize) -> Vec<(f64, f64)> {
    (0..m)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (m as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                // P_m(x) and P_m'(x) by the three-term recurrence.
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=m {
                    let kf = k as f64;
                    (p0, p1) = (p1, ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf);
                }
                dp = m as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() <= 1e-16 {
                    break;
                }
            }
            (0.5 * (1.0 - x), 1.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// What a libration pass needs besides the curve: the energy, the turning points, the depth
/// E − h*(c) at the centre and the Gauss-Legendre rule of the end corrections.
struct Well<'a> {
    e: f64,
    qa: f64,
    qb: f64,
    depth: f64,
    rule: &'a [(f64, f64)],
}

/// Near a turning point E − h*(q) and H(q, p* + δ) − h*(q) are small differences of O(1) numbers:
/// both are computed as integrals of derivatives (exact by duals) instead.
/// - E − h*(q) = h*(q_end) − h*(q) = ∫_q^{q_end} ∂H/∂q(x, p*(x)) dx (the envelope theorem: dh*/dq =
///   ∂H/∂q at p*), q_end the nearer turning point (where h* = E);
/// - H(q, p* + δ) − h*(q) = δ² ∫₀¹ (1 − s) ∂²H/∂p²(q, p* + sδ) ds (Taylor's remainder, ∂H/∂p = 0 at p*).
///
/// The momenta p* + δ± solve the second = the first. Returns (p₋, p₊).
fn momenta_near_end<C: Curve>(c: &C, w: &Well, phi: f64, ps: f64) -> Result<(f64, f64)> {
    // The distance to the nearer turning point from φ directly (q = c − h cos φ rounds it away).
    let half = 0.5 * (w.qb - w.qa);
    let (q_end, dist, dir) = if phi < 0.5 * PI {
        (w.qa, 2.0 * half * (0.5 * phi).sin().powi(2), 1.0)
    } else {
        (w.qb, 2.0 * half * (0.5 * phi).cos().powi(2), -1.0)
    };
    let q = q_end + dir * dist;
    let mut guess = ps;
    let mut depth = 0.0;
    for &(s, wt) in w.rule {
        let x = q_end + dir * s * dist;
        let (px, _, _) = bottom(c, x, guess)?;
        guess = px;
        let hq = first_derivative(|x: Dual64| c.h(x, Dual64::from(px)), x).1;
        depth += wt * hq;
    }
    // E − h*(q) = ∫_q^{q_end} ∂H/∂q dx.
    depth *= -dir * dist;
    if depth <= 0.0 || depth.is_nan() {
        return Err(Error::EnergyBelowMinimum {
            energy: w.e,
            q,
            minimum: w.e - depth,
        });
    }
    let rise = |d: f64| -> f64 {
        let k: f64 = w
            .rule
            .iter()
            .map(|&(s, wt)| {
                wt * (1.0 - s) * second_derivative(|p: Dual2_64| c.h(Dual2_64::from(q), p), ps + s * d).2
            })
            .sum();
        d * d * k - depth
    };
    let hpp = second_derivative(|p: Dual2_64| c.h(Dual2_64::from(q), p), ps).2;
    let d0 = if hpp > 0.0 && hpp.is_finite() {
        (2.0 * depth / hpp).sqrt()
    } else {
        1.0
    };
    let mut ends = [0.0; 2];
    for (end, sign) in ends.iter_mut().zip([-1.0, 1.0]) {
        let f = |d: f64| rise(sign * d);
        let mut d = 1.25 * d0;
        let mut found = None;
        for _ in 0..200 {
            let fd = f(d);
            if fd >= 0.0 {
                found = Some((d, fd));
                break;
            }
            if !fd.is_finite() {
                break;
            }
            d *= 2.0;
        }
        let Some((d, fd)) = found else {
            return Err(Error::NoMomentum { energy: w.e, q });
        };
        *end = ps + sign * bracketed_root(f, (0.0, -depth), (d, fd))?;
    }
    Ok((ends[0], ends[1]))
}

/// One midpoint-rule pass over N nodes of a libration: (J, T, upper integrand, lower integrand).
fn libration_pass<C: Curve>(c: &C, w: &Well, n: usize, extras: Extras) -> Result<Pass> {
    let (mid, half) = (0.5 * (w.qa + w.qb), 0.5 * (w.qb - w.qa));
    let (mut gu, mut gl) = (vec![0.0; n], vec![0.0; n]);
    let mut extra = vec![(0.0, 0.0); extras.len()];
    let mut area = 0.0;
    let mut guess = 0.0;
    for j in 0..n {
        let phi = (j as f64 + 0.5) * PI / n as f64;
        let q = mid - half * phi.cos();
        let wq = half * phi.sin();
        let (ps, hs, hpp) = bottom(c, q, guess)?;
        guess = ps;
        // Within 1/20 of the well's depth of the energy, or where E − h* is below 1/20 of the size
        // of E and h* (a small well high up), the differences are taken by integrals.
        let (pm, pp) = if w.e - hs < 0.05 * w.depth || w.e.abs().max(hs.abs()) > 20.0 * (w.e - hs) {
            momenta_near_end(c, w, phi, ps)?
        } else {
            momenta(c, q, w.e, ps, hs, hpp)?
        };
        area += (pp - pm) * wq;
        for (x, f) in extra.iter_mut().zip(extras) {
            let v = wq * (f(q, pp) - f(q, pm));
            *x = (x.0 + v, x.1 + v.abs());
        }
        gu[j] = wq / velocity(c, q, pp);
        gl[j] = -wq / velocity(c, q, pm);
    }
    let dphi = PI / n as f64;
    let period = dphi * (gu.iter().sum::<f64>() + gl.iter().sum::<f64>());
    Ok(Pass {
        action: area * dphi / (2.0 * PI),
        period,
        upper: gu,
        lower: gl,
        extras: extra.into_iter().map(|(a, b)| (a * dphi, b * dphi)).collect(),
    })
}

/// Further integrands f(q, p) whose integrals ∮ f dq over the orbit are taken with J and T (and
/// converge with them): a libration sums f(q, p₊) − f(q, p₋), a rotation f(q, p).
pub(crate) type Extras<'a> = &'a [&'a dyn Fn(f64, f64) -> f64];

/// Two passes agree: |x₁ − x₀| ≤ tol · scale.
fn settled(x0: f64, x1: f64, scale: f64, tol: f64) -> bool {
    (x1 - x0).abs() <= tol * scale
}

/// One quadrature pass: J, T (signed for a rotation), the time integrands, the further integrals
/// with the integrals of their absolute values (their scale).
struct Pass {
    action: f64,
    period: f64,
    upper: Vec<f64>,
    lower: Vec<f64>,
    extras: Vec<(f64, f64)>,
}

impl Pass {
    /// This pass agrees with `earlier` to `tol`: J and T relative, the extras against their scales.
    fn settled(&self, earlier: &Pass, tol: f64) -> bool {
        settled(earlier.action, self.action, self.action.abs(), tol)
            && settled(earlier.period, self.period, self.period.abs(), tol)
            && self
                .extras
                .iter()
                .zip(&earlier.extras)
                .all(|(a, b)| settled(b.0, a.0, a.1, tol))
    }
}

pub(crate) fn libration<C: Curve>(c: &C, e: f64, q_inside: f64, s: &Settings) -> Result<Libration> {
    Ok(libration_with(c, e, q_inside, s, &[])?.0)
}

/// The libration and the integrals ∮ f dq of the `extras`.
pub(crate) fn libration_with<C: Curve>(
    c: &C,
    e: f64,
    q_inside: f64,
    s: &Settings,
    extras: Extras,
) -> Result<(Libration, Vec<f64>)> {
    finite("action-angle energy", e)?;
    finite("action-angle q_inside", q_inside)?;
    let (qa, qb) = turning_points(c, e, q_inside, s.search_step)?;
    let (_, hc, _) = bottom(c, 0.5 * (qa + qb), 0.0)?;
    let rule = gauss_legendre(12);
    let well = Well {
        e,
        qa,
        qb,
        depth: e - hc,
        rule: &rule,
    };
    let mut n = s.nodes;
    let mut last = libration_pass(c, &well, n, extras)?;
    loop {
        n *= 2;
        if n > s.max_nodes {
            return Err(Error::QuadratureNotConverged {
                what: "libration action and period",
                nodes: n / 2,
                previous: f64::NAN,
                estimate: last.action,
            });
        }
        let pass = libration_pass(c, &well, n, extras)?;
        let (j1, t1) = (pass.action, pass.period);
        let change = (j1 - last.action).abs();
        if pass.settled(&last, s.tolerance) {
            check_orbit(e, t1, j1)?;
            let lib = Libration {
                energy: e,
                q_min: qa,
                q_max: qb,
                action: j1,
                period: t1,
                frequency: 2.0 * PI / t1,
                nodes: n,
                action_change: change,
                upper: cosine_coefficients(&pass.upper),
                lower: cosine_coefficients(&pass.lower),
            };
            return Ok((lib, pass.extras.iter().map(|x| x.0).collect()));
        }
        last = pass;
    }
}

/// Fourier coefficients (aₖ, bₖ), k < N/2, of g sampled at sⱼ = 2π(j + ½)/N.
fn fourier(g: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = g.len();
    let m = n / 2;
    let (mut a, mut b) = (vec![0.0; m], vec![0.0; m]);
    for k in 0..m {
        for (j, gj) in g.iter().enumerate() {
            let x = k as f64 * 2.0 * PI * (j as f64 + 0.5) / n as f64;
            a[k] += gj * x.cos();
            b[k] += gj * x.sin();
        }
        a[k] *= 2.0 / n as f64;
        b[k] *= 2.0 / n as f64;
    }
    (a, b)
}

/// ∫₀^s g for g = a₀/2 + Σ (aₖ cos ks + bₖ sin ks).
fn fourier_integral((a, b): &(Vec<f64>, Vec<f64>), s: f64) -> f64 {
    let mut t = 0.5 * a[0] * s;
    for k in 1..a.len() {
        let kf = k as f64;
        t += (a[k] * (kf * s).sin() + b[k] * (1.0 - (kf * s).cos())) / kf;
    }
    t
}

/// The last check of an orbit: T finite and > 0 (so ω = 2π/T finite and > 0), J finite; else
/// [`Error::DegenerateOrbit`] with the values.
fn check_orbit(energy: f64, period: f64, action: f64) -> Result<()> {
    let frequency = 2.0 * PI / period;
    if period.is_finite() && period > 0.0 && frequency.is_finite() && action.is_finite() {
        Ok(())
    } else {
        Err(Error::DegenerateOrbit {
            energy,
            period,
            action,
        })
    }
}

fn invalid(name: &'static str, value: f64, reason: &'static str) -> Error {
    noether_core::Error::InvalidParameter { name, value, reason }.into()
}

fn finite(name: &'static str, x: f64) -> Result<f64> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(invalid(name, x, "must be finite"))
    }
}

fn positive(name: &'static str, x: f64) -> Result<f64> {
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(invalid(name, x, "must be finite and positive"))
    }
}
