//! Chaos indicators of one orbit from one tangent vector: MEGNO and the fast Lyapunov indicator, and
//! stability maps of them over a grid of initial conditions.
//!
//! **MEGNO** (mean exponential growth factor of nearby orbits; Cincotta & Simó, *A&AS* 147, 205–228,
//! 2000). A deviation δ(t) carried by the tangent flow grows at the rate δ̇·δ/|δ|² = d ln|δ|/dt; MEGNO
//! weighs that rate with the time and averages twice:
//!
//! ```text
//! Y(t) = (2/t) ∫₀ᵗ s (d ln|δ|/ds) ds,        ⟨Y⟩(t) = (1/t) ∫₀ᵗ Y(s) ds.
//! ```
//!
//! Its limits tell the orbit's kind, with no threshold on a slowly converging exponent: |δ| bounded (a
//! stable periodic orbit of an isochronous system, the harmonic oscillator): ⟨Y⟩ → 0; |δ| growing
//! linearly (a quasi-periodic orbit on a torus whose frequencies depend on the actions, the shear of
//! the torus): ⟨Y⟩ → 2; |δ| ~ e^{λt} (chaos): Y ≈ λt and ⟨Y⟩ ≈ λt/2. A torus shows ⟨Y⟩ ≈ 2 long before
//! a Lyapunov estimate ln|δ|/t has decayed to a convincing zero, which is why MEGNO maps are cheap.
//!
//! **Discrete form.** The orbit is followed by a [`TangentStepper`] with fixed steps h; each step maps δ
//! by the step's Jacobian Ψ, and its growth Δ_k = ln(|Ψδ_{k−1}| / |δ_{k−1}|) enters with the step's mid
//! time s̄_k = s_k − h/2 (s = t − t₀):
//!
//! ```text
//! J_k = J_{k−1} + s̄_k Δ_k,   Y_k = 2 J_k / s_k,   I_k = I_{k−1} + (h/2)(Y_{k−1} + Y_k),   ⟨Y⟩_k = I_k / s_k,
//! ```
//!
//! exact when ln|δ| is linear over each step (pure exponential growth: ⟨Y⟩ = λs/2 to rounding), and
//! otherwise off the continuous integral by O(h²) per unit of ln|δ|'' (the midpoint rule). It is the
//! MEGNO of the numerical map, as Cincotta, Giordano & Simó (*Physica D* 182, 151–178, 2003) define it
//! for maps. δ is renormalised to unit length after every step, so it never overflows.
//!
//! **FLI** (fast Lyapunov indicator; Froeschlé, Lega & Gonczi, *Celest. Mech. Dyn. Astron.* 67, 41–62,
//! 1997): FLI(t) = sup_{s ≤ t} ln|δ(s)| with |δ(0)| = 1 — it grows like ln t on a torus and like λt in
//! chaos.
//!
//! ```
//! use noether_analysis::Megno;
//! use noether_core::prelude::*;
//!
//! /// The inverted oscillator H = ½(p² − q²): a deviation along the unstable direction (1, 1) grows
//! /// like e^t, so ⟨Y⟩(t) = λt/2 with λ RK4's growth rate per unit time, ln R(h)/h.
//! struct Inverted;
//! impl Hamiltonian for Inverted {
//!     fn dof(&self) -> usize { 1 }
//!     fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
//!         (p[0] * p[0] - q[0] * q[0]) * 0.5
//!     }
//! }
//! let h = 0.01;
//! let rk4 = Rk4::new(HamiltonEquations::new(Inverted));
//! let mut megno = Megno::new(rk4, State::with_momenta(0.0, [0.0], [0.0]), h)?
//!     .initial_vector(&[1.0, 1.0])?;
//! megno.advance_to(20.0)?;
//! let lambda = (1.0 + h + h * h / 2.0 + h.powi(3) / 6.0 + h.powi(4) / 24.0).ln() / h;
//! let ind = megno.indicators();
//! assert!((ind.mean_megno - lambda * 20.0 / 2.0).abs() < 1e-10);
//! assert!((ind.fli - lambda * 20.0).abs() < 1e-10);
//! # Ok::<(), noether_analysis::Error>(())
//! ```

use crate::{Error, Result};
use nalgebra::{DMatrix, DVector};
use noether_core::{State, TangentStepper};
#[cfg(feature = "ensemble")]
use noether_ensemble::{Ensemble, Grid, MemberError, Members};

/// MEGNO and the FLI running along one orbit: the stepper, the state, the unit deviation and the sums.
///
/// `Clone` when the stepper is: a clone is a checkpoint, from which the run continues with the same
/// numbers as the original.
#[derive(Debug, Clone)]
pub struct Megno<S: TangentStepper> {
    stepper: S,
    state: State<S::Partner>,
    /// The state a step is tried on (committed only when the step and its tangent are good).
    trial: State<S::Partner>,
    h: f64,
    /// The deviation, unit length.
    delta: DVector<f64>,
    /// Scratch: Ψ δ.
    next: DVector<f64>,
    /// Scratch: Ψ of the last step.
    psi: DMatrix<f64>,
    /// Time at the start of the sums.
    t0: f64,
    /// ln|δ(t)| (with |δ(t₀)| = 1).
    growth: f64,
    /// sup ln|δ(s)|.
    fli: f64,
    /// J = ∫ s d ln|δ|.
    weighted: f64,
    /// Y at the last step.
    y: f64,
    /// ∫ Y ds.
    y_integral: f64,
}

/// The indicators at one time of a [`Megno`] run.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Indicators {
    /// Time since the start of the sums, s = t − t₀.
    pub elapsed: f64,
    /// Y(s) = (2/s) ∫ σ d ln|δ|.
    pub megno: f64,
    /// ⟨Y⟩(s) = (1/s) ∫ Y dσ: → 0 (stable periodic, isochronous), → 2 (torus), ≈ λs/2 (chaos).
    pub mean_megno: f64,
    /// FLI(s) = sup ln|δ(σ)|, σ ≤ s, with |δ(0)| = 1.
    pub fli: f64,
    /// ln|δ(s)| / s: the finite-time estimate of the largest Lyapunov exponent (0 at s = 0).
    pub lyapunov: f64,
}

impl<S: TangentStepper> Megno<S> {
    /// Starts MEGNO at `state` with steps of size `h` and a fixed, generic unit deviation (the
    /// normalised sum of the phase-space axes with distinct weights, so that it lies in no symmetry
    /// plane); [`initial_vector`](Self::initial_vector) sets one's own.
    pub fn new(stepper: S, state: State<S::Partner>, h: f64) -> Result<Self> {
        let n = stepper.dof();
        state.validate(n)?;
        noether_core::error::check_step(h)?;
        let dim = 2 * n;
        let delta = DVector::from_fn(dim, |i, _| 1.0 + 0.618_033_988_749_894_9 * i as f64).normalize();
        Ok(Megno {
            stepper,
            trial: state.clone(),
            t0: state.t,
            state,
            h,
            next: delta.clone(),
            delta,
            psi: DMatrix::zeros(dim, dim),
            growth: 0.0,
            fli: 0.0,
            weighted: 0.0,
            y: 0.0,
            y_integral: 0.0,
        })
    }

    /// Replaces the deviation by `v` (2n entries, (δq, δv) as the stepper's Ψ orders them; normalised
    /// here) and restarts the sums at the current time.
    pub fn initial_vector(mut self, v: &[f64]) -> Result<Self> {
        let dim = self.delta.len();
        noether_core::error::check_len("initial deviation", v, dim)?;
        noether_core::error::check_finite("initial deviation", v)?;
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(Error::DeviationLost {
                t: self.state.t,
                growth: norm,
            });
        }
        self.delta = DVector::from_iterator(dim, v.iter().map(|x| x / norm));
        self.restart();
        Ok(self)
    }

    /// Forgets the sums (keeping the orbit and the deviation's direction, renormalised): the indicators
    /// restart at the current time.
    pub fn restart(&mut self) {
        self.t0 = self.state.t;
        self.growth = 0.0;
        self.fli = 0.0;
        self.weighted = 0.0;
        self.y = 0.0;
        self.y_integral = 0.0;
    }

    /// Takes `steps` steps. A step whose deviation is not finite or vanishes (Ψ overflowed) is
    /// [`Error::DeviationLost`]; on any error the run stays where the last good step left it, state,
    /// deviation and sums.
    pub fn advance(&mut self, steps: usize) -> Result<()> {
        for _ in 0..steps {
            self.step()?;
        }
        Ok(())
    }

    /// Steps until the time is `t_end` (rounded to a whole number of steps; nothing when `t_end` is not
    /// ahead).
    pub fn advance_to(&mut self, t_end: f64) -> Result<()> {
        self.advance(crate::lyapunov::steps_to(self.state.t, t_end, self.h)?)
    }

    /// One step of the orbit and the deviation, and the sums of the module docs.
    fn step(&mut self) -> Result<()> {
        self.trial.clone_from(&self.state);
        self.stepper
            .step_tangent(&mut self.trial, self.h, &mut self.psi)?;
        self.psi.mul_to(&self.delta, &mut self.next);
        let norm = self.next.norm();
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(Error::DeviationLost {
                t: self.trial.t,
                growth: norm,
            });
        }
        let (before, after) = (self.state.t - self.t0, self.trial.t - self.t0);
        let rate = norm.ln();
        self.weighted += 0.5 * (before + after) * rate;
        let y = 2.0 * self.weighted / after;
        self.y_integral += 0.5 * (after - before) * (self.y + y);
        self.y = y;
        self.growth += rate;
        self.fli = self.fli.max(self.growth);
        self.next /= norm;
        std::mem::swap(&mut self.delta, &mut self.next);
        std::mem::swap(&mut self.state, &mut self.trial);
        Ok(())
    }

    /// The indicators now (all zero before the first step: their limits at s → 0).
    pub fn indicators(&self) -> Indicators {
        let s = self.state.t - self.t0;
        let per_time = |x: f64| if s > 0.0 { x / s } else { 0.0 };
        Indicators {
            elapsed: s,
            megno: self.y,
            mean_megno: per_time(self.y_integral),
            fli: self.fli,
            lyapunov: per_time(self.growth),
        }
    }

    /// The current state of the orbit.
    pub fn state(&self) -> &State<S::Partner> {
        &self.state
    }

    /// The current deviation (unit length).
    pub fn deviation(&self) -> &DVector<f64> {
        &self.delta
    }

    /// The stepper.
    pub fn stepper(&self) -> &S {
        &self.stepper
    }
}

/// The indicators at the end of one run per member of a grid: a MEGNO stability map (feature
/// `ensemble`).
#[cfg(feature = "ensemble")]
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct StabilityMap {
    /// The grid of initial conditions.
    pub grid: Grid,
    /// Per member (in the grid's order), its indicators at the end; `None` for a member without an
    /// orbit (outside the energy surface, say) or one whose run failed.
    pub indicators: Vec<Option<Indicators>>,
    /// Number of members with an orbit.
    pub valid: usize,
    /// The members whose run failed: index and error (or panic message).
    pub failures: Vec<(usize, MemberError<Error>)>,
}

#[cfg(feature = "ensemble")]
impl StabilityMap {
    /// ⟨Y⟩ per member, NaN where there is none (drawn white by `noether_plot::Heatmap`).
    pub fn mean_megno(&self) -> Vec<f64> {
        self.field(|i| i.mean_megno)
    }

    /// FLI per member, NaN where there is none.
    pub fn fli(&self) -> Vec<f64> {
        self.field(|i| i.fli)
    }

    fn field(&self, f: impl Fn(&Indicators) -> f64) -> Vec<f64> {
        self.indicators
            .iter()
            .map(|i| i.as_ref().map_or(f64::NAN, &f))
            .collect()
    }

    /// The fraction of the members with an orbit whose ⟨Y⟩ exceeds `threshold` (chaotic by MEGNO: a
    /// torus gives ⟨Y⟩ → 2, chaos ⟨Y⟩ ≈ λt/2; the members that failed count as not chaotic, and are
    /// listed in `failures`).
    pub fn chaotic_fraction(&self, threshold: f64) -> f64 {
        let chaotic = self
            .indicators
            .iter()
            .flatten()
            .filter(|i| i.mean_megno > threshold)
            .count();
        chaotic as f64 / self.valid as f64
    }
}

/// Runs MEGNO for every member of `grid` (feature `ensemble`: on every core, through noether-ensemble) until the time
/// `t_end`: `start` gives a member's run set up at its initial condition, or `None` when the grid point
/// has no orbit (a point of a Poincaré section outside the energy surface).
///
/// A member whose set-up or run fails is listed in [`StabilityMap::failures`] and the others complete;
/// a grid where no member has an orbit is [`Error::NoValidMember`].
#[cfg(feature = "ensemble")]
pub fn stability_map<S, F>(grid: &Grid, t_end: f64, start: F) -> Result<StabilityMap>
where
    S: TangentStepper,
    F: Fn(&[f64]) -> Result<Option<Megno<S>>> + Sync,
{
    let run = |_: usize, p: &Vec<f64>| -> Result<Option<Indicators>> {
        match start(p)? {
            Some(mut megno) => {
                megno.advance_to(t_end)?;
                Ok(Some(megno.indicators()))
            }
            None => Ok(None),
        }
    };
    let runs = Ensemble::new(grid.clone(), run).run();
    let mut indicators = Vec::with_capacity(runs.len());
    let mut failures = Vec::new();
    let mut valid = 0;
    for (i, r) in runs.into_results().into_iter().enumerate() {
        match r {
            Ok(ind) => {
                valid += usize::from(ind.is_some());
                indicators.push(ind);
            }
            Err(e) => {
                valid += 1;
                failures.push((i, e));
                indicators.push(None);
            }
        }
    }
    if valid == 0 {
        return Err(Error::NoValidMember { members: grid.len() });
    }
    Ok(StabilityMap {
        grid: grid.clone(),
        indicators,
        valid,
        failures,
    })
}
