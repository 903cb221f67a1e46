//! Families of periodic orbits by pseudo-arclength continuation in the level of a first integral.
//!
//! A conservative system's periodic orbits come in one-parameter families, one orbit per level c of
//! the first integral declared with [`Shooting::level`] (the energy, the Jacobi constant). Natural
//! continuation, stepping c and solving at each level, fails where the family turns back in c (a
//! fold) and slows down where the orbits change fast. Pseudo-arclength continuation (Keller 1977;
//! AUTO, BifurcationKit) treats c as one more unknown of the shooting equations F(x; c) = 0 and adds
//! the condition that the new solution z = (x, c) lies a distance Δs along the family's tangent τ from
//! the last one z₀:
//!
//! ```text
//! F(x; c) = 0,      τᵀ (z − z₀) − Δs = 0,      [F_x F_c] τ = 0, |τ| = 1, τᵀ τ_prev > 0,
//! ```
//!
//! a square system regular at folds. The predictor is z₀ + Δs τ; the corrector is core's Newton on
//! the bordered system, whose Jacobian is the shooting Jacobian with the column ∂F/∂c (−1 in the
//! level's row) and the row τᵀ; the tangent at the new point solves the same bordered matrix with
//! right-hand side (0, …, 0, 1). The phase condition of each step is taken at the previous orbit.
//! The step Δs grows by 1.5 after an easy corrector (≤ 4 iterations) and halves after a failed one;
//! a family that cannot be followed with Δs above its floor is [`Error::BranchLost`].

use crate::periodic::{PeriodicOrbit, Problem, Shooting};
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector};
use noether_core::linalg::DenseFactor;
use noether_core::newton::{solve_dense, DenseProblem};
use noether_core::TangentStepper;

/// The settings of a continuation: the first step Δs and its bounds (in the unknowns' units: nodes,
/// period and level together).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Continuation {
    step: f64,
    min_step: f64,
    max_step: f64,
}

impl Continuation {
    /// Continuation with first step `step` and bounds `min_step` ≤ Δs ≤ `max_step` (all finite, 0 <
    /// min ≤ step ≤ max, else `InvalidParameter`).
    pub fn new(step: f64, min_step: f64, max_step: f64) -> Result<Self> {
        let ok = [step, min_step, max_step]
            .iter()
            .all(|x| x.is_finite() && *x > 0.0)
            && min_step <= step
            && step <= max_step;
        if !ok {
            return Err(noether_core::Error::InvalidParameter {
                name: "continuation steps (step, min, max)",
                value: step,
                reason: "finite and positive, min ≤ step ≤ max",
            }
            .into());
        }
        Ok(Continuation {
            step,
            min_step,
            max_step,
        })
    }

    /// Follows the family of `start` (an orbit found by `shooting`, whose first fixed-level integral,
    /// at `level` on `start`, is the family parameter; the period must be free) for `members` more
    /// orbits in the direction of increasing level (or of decreasing level, with `increasing` false).
    /// Returns the members found, `start` not included, each with its level. Errors: a shooting
    /// without a level or with a fixed period (`InvalidParameter`), [`Error::BranchLost`], and the
    /// shooting's own errors at the start.
    pub fn follow<S: TangentStepper>(
        &self,
        shooting: &mut Shooting<S>,
        start: &PeriodicOrbit<S::Partner>,
        level: f64,
        members: usize,
        increasing: bool,
    ) -> Result<Vec<(f64, PeriodicOrbit<S::Partner>)>> {
        shooting.check_family()?;
        let mut z = unknowns(start, level);
        let dim = z.len();
        let mut prev = start.clone();
        // The first tangent: oriented along ±c.
        let mut tangent = DVector::zeros(dim);
        tangent[dim - 1] = if increasing { 1.0 } else { -1.0 };
        tangent = self.tangent(shooting, &prev, &z, &tangent)?;
        let mut ds = self.step;
        let mut family = Vec::with_capacity(members);
        while family.len() < members {
            match self.correct(shooting, &prev, &z, &tangent, ds) {
                Ok((next, orbit)) => {
                    let easy = orbit.newton.iterations <= 4;
                    tangent = self.tangent(shooting, &orbit, &next, &tangent)?;
                    family.push((next[dim - 1], orbit.clone()));
                    z = next;
                    prev = orbit;
                    if easy {
                        ds = (ds * 1.5).min(self.max_step);
                    }
                }
                Err(e) => {
                    ds *= 0.5;
                    if ds < self.min_step {
                        return Err(Error::BranchLost {
                            level: z[dim - 1],
                            step: ds,
                            reason: e.to_string(),
                        });
                    }
                }
            }
        }
        Ok(family)
    }

    /// The unit tangent of the family at z (phase conditions at `orbit`), oriented along `previous`.
    fn tangent<S: TangentStepper>(
        &self,
        shooting: &mut Shooting<S>,
        orbit: &PeriodicOrbit<S::Partner>,
        z: &DVector<f64>,
        previous: &DVector<f64>,
    ) -> Result<DVector<f64>> {
        let (problem, _) = shooting.equations(&orbit.initial, orbit.period)?;
        let mut bordered = Bordered::new(problem, previous.clone(), DVector::zeros(z.len()), 0.0);
        let mut j = DMatrix::zeros(z.len(), z.len());
        bordered.jacobian(z.as_slice(), &mut j)?;
        let mut t = DVector::zeros(z.len());
        t[z.len() - 1] = 1.0;
        let lu = DenseFactor::lu(j).map_err(|e| e.in_matrix("bordered continuation Jacobian"))?;
        lu.solve_in_place(t.as_mut_slice());
        let t = t.normalize();
        Ok(if t.dot(previous) < 0.0 { -t } else { t })
    }

    /// The corrector from the predictor z + Δs τ: the new unknowns and the orbit.
    fn correct<S: TangentStepper>(
        &self,
        shooting: &mut Shooting<S>,
        prev: &PeriodicOrbit<S::Partner>,
        z: &DVector<f64>,
        tangent: &DVector<f64>,
        ds: f64,
    ) -> Result<(DVector<f64>, PeriodicOrbit<S::Partner>)> {
        let predicted = z + tangent * ds;
        let newton = shooting.newton_settings();
        let (problem, speed) = shooting.equations(&prev.initial, prev.period)?;
        let bordered = Bordered::new(problem, tangent.clone(), z.clone(), ds);
        let (next, info) = solve_dense(&newton, bordered, predicted.as_slice())?;
        let dim = next.len();
        let orbit = shooting.orbit_at(
            &next.as_slice()[..dim - 1],
            prev.initial.t,
            prev.period,
            speed,
            info,
        )?;
        Ok((next, orbit))
    }
}

/// The unknowns of a found orbit (nodes, T, λ) and its level c, as one vector z.
fn unknowns<K: noether_core::Partner>(orbit: &PeriodicOrbit<K>, level: f64) -> DVector<f64> {
    let mut z: Vec<f64> = orbit
        .nodes
        .iter()
        .flat_map(|y| y.q.iter().chain(y.v.iter()).copied())
        .collect();
    z.push(orbit.period);
    z.extend(&orbit.unfolding);
    z.push(level);
    DVector::from_vec(z)
}

/// The shooting equations with the level as an unknown, bordered by the arclength row
/// τᵀ(z − z₀) − Δs.
struct Bordered<'a, S> {
    problem: Problem<'a, S>,
    tangent: DVector<f64>,
    origin: DVector<f64>,
    ds: f64,
}

impl<'a, S: TangentStepper> Bordered<'a, S> {
    fn new(problem: Problem<'a, S>, tangent: DVector<f64>, origin: DVector<f64>, ds: f64) -> Self {
        Bordered {
            problem,
            tangent,
            origin,
            ds,
        }
    }
}

impl<S: TangentStepper> DenseProblem for Bordered<'_, S> {
    fn dim(&self) -> usize {
        self.tangent.len()
    }
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> noether_core::Result<()> {
        let d = z.len() - 1;
        self.problem.level = Some(z[d]);
        self.problem.residual(&z[..d], &mut r[..d])?;
        r[d] = (0..=d)
            .map(|i| self.tangent[i] * (z[i] - self.origin[i]))
            .sum::<f64>()
            - self.ds;
        Ok(())
    }
    fn jacobian(&mut self, z: &[f64], j: &mut DMatrix<f64>) -> noether_core::Result<()> {
        let d = z.len() - 1;
        self.problem.level = Some(z[d]);
        let mut inner = DMatrix::zeros(d, d);
        self.problem.jacobian(&z[..d], &mut inner)?;
        j.fill(0.0);
        j.view_mut((0, 0), (d, d)).copy_from(&inner);
        // ∂(I(y₀) − c)/∂c = −1 in the level's row (the first after the phase row).
        j[(self.problem.level_row(), d)] = -1.0;
        for i in 0..=d {
            j[(d, i)] = self.tangent[i];
        }
        Ok(())
    }
}
