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
//!
//! # Bifurcations
//!
//! Along the way three test functions are watched at every member, each changing sign at one kind of
//! [`Bifurcation`]:
//!
//! ```text
//! fold:             τ_c                    (the family turns back in the level)
//! branch point:     ∏ (1 − μ_i)            (a pair of multipliers μ, 1/μ crosses +1)
//! period doubling:  ∏ (1 + μ_i)            (a pair crosses −1)
//! ```
//!
//! the products over the non-trivial Floquet multipliers (real: the complex ones come in conjugate
//! pairs). For a pair (μ, 1/μ) the factor (1 − μ)(1 − 1/μ) = 2 − μ − 1/μ is positive on the unit
//! circle and negative on the positive real axis, so ∏(1 − μ_i) changes sign exactly when one pair
//! passes through +1, whichever it is: no pairing of multipliers between members is needed (the test
//! functions of Seydel, *Practical Bifurcation and Stability Analysis* §7.4, and AUTO's for periodic
//! orbits). A conservative family has a pair at +1 at its folds too; a sign change of ∏(1 − μ_i)
//! where τ_c changes sign as well is the fold's and is reported once, as a fold. A sign change is
//! located by the Illinois root finder of core on the arclength between the two members (each trial
//! one corrector solve) to [`Continuation::locate`]'s width, and reported as a [`SpecialPoint`].
//!
//! **Branch switching.** At a branch point the shooting equations' Jacobian [F_x F_c] loses rank:
//! its null space is two-dimensional, spanned by the tangents of the two families crossing there.
//! [`Continuation::switch`] takes the null direction orthogonal to the followed family's tangent (the
//! two smallest right singular vectors of the Jacobian, by core's SVD) and starts the other family
//! along it (Keller 1977; Doedel, Keller & Kernévez 1991). The halo orbits of the restricted
//! three-body problem branch so from the planar Lyapunov family, where its vertical pair of
//! multipliers passes through +1, in two mirror families (z ↦ −z), one for each sign of the
//! direction.

use crate::periodic::{PeriodicOrbit, Problem, Shooting};
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector};
use noether_core::linalg::{smallest_right_singular, DenseFactor};
use noether_core::newton::{solve_dense, DenseProblem};
use noether_core::roots::bracketed_root_within;
use noether_core::{Partner, TangentStepper};

/// The settings of a continuation: the first step Δs and its bounds (in the unknowns' units: nodes,
/// period and level together), and the width to which bifurcations are located.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Continuation {
    step: f64,
    min_step: f64,
    max_step: f64,
    locate: f64,
}

/// The kind of a bifurcation met along a family (see the [module](self) docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bifurcation {
    /// The family turns back in the level: the level has an extremum along it.
    Fold,
    /// A pair of non-trivial multipliers crosses +1 where the family does not turn: another family of
    /// the same period crosses this one (a pitchfork where a symmetry breaks, as the halo orbits
    /// from the planar Lyapunov orbits); [`Continuation::switch`] follows it.
    BranchPoint,
    /// A pair crosses −1: a family of twice the period branches off.
    PeriodDoubling,
}

/// A bifurcation located along a family.
#[derive(Debug, Clone)]
pub struct SpecialPoint<K: Partner> {
    /// Its kind.
    pub kind: Bifurcation,
    /// The level of the first integral there.
    pub level: f64,
    /// The orbit there.
    pub orbit: PeriodicOrbit<K>,
    /// How many members of the [`Branch`] precede it.
    pub after: usize,
    /// Its unknowns z = (nodes, T, λ, c) and the family's tangent there (at a branch point, where
    /// the tangent is not unique, the family's secant across it).
    z: DVector<f64>,
    tangent: DVector<f64>,
}

/// A family followed by [`Continuation::follow`] or [`Continuation::switch`]: its members, each with
/// its level, and the bifurcations located between them, in order.
#[derive(Debug, Clone)]
pub struct Branch<K: Partner> {
    /// The orbits found (not the one started from), each with its level.
    pub members: Vec<(f64, PeriodicOrbit<K>)>,
    /// The bifurcations met, in the order met.
    pub special: Vec<SpecialPoint<K>>,
    /// Why the branch has fewer members than asked for ([`Error::BranchLost`], or the error met
    /// locating a bifurcation or solving for a tangent), `None` when it has them all: a family lost
    /// after some members keeps them.
    pub lost: Option<Error>,
}

/// A point on a family: its unknowns, tangent, orbit and the values of the three test functions
/// (fold, branch point, period doubling; NaN: not watched).
struct Point<K: Partner> {
    z: DVector<f64>,
    tangent: DVector<f64>,
    orbit: PeriodicOrbit<K>,
    tests: [f64; 3],
}

impl<K: Partner> Point<K> {
    fn new(z: DVector<f64>, tangent: DVector<f64>, orbit: PeriodicOrbit<K>) -> Self {
        let tests = test_functions(&orbit, &tangent);
        Point {
            z,
            tangent,
            orbit,
            tests,
        }
    }
}

/// The test functions at an orbit with family tangent `tangent`: τ_c, Re ∏(1 − μ_i), Re ∏(1 + μ_i)
/// over the non-trivial multipliers.
fn test_functions<K: Partner>(orbit: &PeriodicOrbit<K>, tangent: &DVector<f64>) -> [f64; 3] {
    let one = nalgebra::Complex::new(1.0, 0.0);
    let product = |sign: f64| {
        orbit
            .floquet
            .nontrivial()
            .iter()
            .fold(one, |p, m| p * (one + m * sign))
            .re
    };
    [tangent[tangent.len() - 1], product(-1.0), product(1.0)]
}

impl Continuation {
    /// Continuation with first step `step` and bounds `min_step` ≤ Δs ≤ `max_step` (all finite, 0 <
    /// min ≤ step ≤ max, else `InvalidParameter`); bifurcations are located to 1e-9 in arclength.
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
            locate: 1e-9,
        })
    }

    /// Locates bifurcations to `width` in arclength (finite and positive, else `InvalidParameter`):
    /// each halving of the bracket costs about one corrector solve.
    pub fn locate(mut self, width: f64) -> Result<Self> {
        noether_core::error::check_positive("bifurcation location width", width)?;
        self.locate = width;
        Ok(self)
    }

    /// Follows the family of `start` (an orbit found by `shooting`, whose first fixed-level integral,
    /// at `level` on `start`, is the family parameter; the period must be free) for `members` more
    /// orbits in the direction of increasing level (or of decreasing level, with `increasing` false),
    /// locating the bifurcations it passes. A family lost on the way ends the [`Branch`] early with
    /// the reason in its `lost`. Errors: a shooting without a level or with a fixed period
    /// (`InvalidParameter`), [`Error::BranchLost`] when not even one member is found, and the
    /// shooting's own errors at the start.
    pub fn follow<S: TangentStepper>(
        &self,
        shooting: &mut Shooting<S>,
        start: &PeriodicOrbit<S::Partner>,
        level: f64,
        members: usize,
        increasing: bool,
    ) -> Result<Branch<S::Partner>> {
        shooting.check_family()?;
        let z = unknowns(start, level);
        let dim = z.len();
        // The first tangent: oriented along ±c.
        let mut along = DVector::zeros(dim);
        along[dim - 1] = if increasing { 1.0 } else { -1.0 };
        let tangent = self.tangent(shooting, start, &z, &along)?;
        self.run(shooting, Point::new(z, tangent, start.clone()), members)
    }

    /// Follows the other family through the branch point `point` (found by [`follow`](Self::follow)
    /// with the same `shooting`) for `members` orbits, along the null direction of the shooting
    /// Jacobian orthogonal to the first family (see the [module](self) docs), oriented so that its
    /// largest component is positive (`positive`) or negative: the two halves of the new family
    /// (for a symmetry-breaking pitchfork, mirror images). Lost on the way, the branch ends early as
    /// in [`follow`](Self::follow). Errors: a point that is not a [`Bifurcation::BranchPoint`]
    /// (`InvalidParameter`), [`Error::BranchLost`] when the Jacobian there has no second null
    /// direction or not even one member is found, and the shooting's errors.
    pub fn switch<S: TangentStepper>(
        &self,
        shooting: &mut Shooting<S>,
        point: &SpecialPoint<S::Partner>,
        members: usize,
        positive: bool,
    ) -> Result<Branch<S::Partner>> {
        shooting.check_family()?;
        if point.kind != Bifurcation::BranchPoint {
            return Err(noether_core::Error::InvalidParameter {
                name: "branch switching point",
                value: point.level,
                reason: "only a branch point has a second family through it",
            }
            .into());
        }
        let lost = |reason: String| Error::BranchLost {
            level: point.level,
            step: 0.0,
            reason,
        };
        let (problem, _) = shooting.equations(&point.orbit.initial, point.orbit.period)?;
        let d = point.z.len() - 1;
        let mut bordered = Bordered::new(problem, point.tangent.clone(), point.z.clone(), 0.0);
        let mut j = DMatrix::zeros(d + 1, d + 1);
        bordered.jacobian(point.z.as_slice(), &mut j)?;
        let (null, _) = smallest_right_singular(&j.rows(0, d).into_owned(), 2)
            .ok_or_else(|| lost("the SVD of the shooting Jacobian did not converge".into()))?;
        let (v1, v2) = (null.column(0), null.column(1));
        let old = &point.tangent;
        // The combination of the null basis orthogonal to the old tangent.
        let other = v1 * old.dot(&v2) - v2 * old.dot(&v1);
        let norm = other.norm();
        if norm.is_nan() || norm <= 1e-8 {
            return Err(lost(
                "no null direction apart from the family's own tangent".into(),
            ));
        }
        let mut tangent = other / norm;
        let largest = tangent.iamax();
        if (tangent[largest] > 0.0) != positive {
            tangent = -tangent;
        }
        let start = Point {
            z: point.z.clone(),
            tangent,
            orbit: point.orbit.clone(),
            // Not watched on the first step: the branch point's own test values are zero to rounding.
            tests: [f64::NAN; 3],
        };
        self.run(shooting, start, members)
    }

    /// The predictor-corrector loop from `from` with step control and bifurcation detection: the
    /// branch, ended early with its `lost` error when a member cannot be found (an error outright
    /// when not even the first can).
    fn run<S: TangentStepper>(
        &self,
        shooting: &mut Shooting<S>,
        mut from: Point<S::Partner>,
        members: usize,
    ) -> Result<Branch<S::Partner>> {
        let mut ds = self.step;
        let mut branch = Branch {
            members: Vec::with_capacity(members),
            special: Vec::new(),
            lost: None,
        };
        while branch.members.len() < members {
            if let Err(e) = self.advance(shooting, &mut from, &mut ds, &mut branch) {
                if branch.members.is_empty() {
                    return Err(e);
                }
                branch.lost = Some(e);
                break;
            }
        }
        Ok(branch)
    }

    /// One member after `from`: the corrector with Δs halved until it succeeds (below the floor:
    /// [`Error::BranchLost`]), the bifurcations between them located, Δs grown after an easy one.
    fn advance<S: TangentStepper>(
        &self,
        shooting: &mut Shooting<S>,
        from: &mut Point<S::Partner>,
        ds: &mut f64,
        branch: &mut Branch<S::Partner>,
    ) -> Result<()> {
        let dim = from.z.len();
        let (next, orbit) = loop {
            match self.correct(shooting, from, *ds) {
                Ok(found) => break found,
                Err(e) => {
                    *ds *= 0.5;
                    if *ds < self.min_step {
                        return Err(Error::BranchLost {
                            level: from.z[dim - 1],
                            step: *ds,
                            reason: e.to_string(),
                        });
                    }
                }
            }
        };
        let easy = orbit.newton.iterations <= 4;
        let tangent = self.tangent(shooting, &orbit, &next, &from.tangent)?;
        let to = Point::new(next, tangent, orbit);
        self.detect(shooting, from, &to, *ds, branch)?;
        branch.members.push((to.z[dim - 1], to.orbit.clone()));
        *from = to;
        if easy {
            *ds = (*ds * 1.5).min(self.max_step);
        }
        Ok(())
    }

    /// Locates the bifurcations whose test function changes sign between `from` and `to` (a step Δs
    /// apart) and appends them to `branch`.
    fn detect<S: TangentStepper>(
        &self,
        shooting: &mut Shooting<S>,
        from: &Point<S::Partner>,
        to: &Point<S::Partner>,
        ds: f64,
        branch: &mut Branch<S::Partner>,
    ) -> Result<()> {
        let kinds = [
            Bifurcation::Fold,
            Bifurcation::BranchPoint,
            Bifurcation::PeriodDoubling,
        ];
        let crosses = |i: usize| from.tests[i] * to.tests[i] < 0.0;
        for (i, kind) in kinds.into_iter().enumerate() {
            if !crosses(i) || (kind == Bifurcation::BranchPoint && crosses(0)) {
                continue;
            }
            let lost = |reason: String| Error::BranchLost {
                level: from.z[from.z.len() - 1],
                step: ds,
                reason: format!("locating a {kind:?}: {reason}"),
            };
            // The tangent there: solved only for a fold (where the bordered Jacobian stays regular);
            // at a branch point, where it does not, the secant from `from` to `to` stands for it.
            let secant = (&to.z - &from.z).normalize();
            let mut at = |s: f64| -> Result<Point<S::Partner>> {
                let (z, orbit) = self.correct(shooting, from, s)?;
                let tangent = match kind {
                    Bifurcation::Fold => self.tangent(shooting, &orbit, &z, &from.tangent)?,
                    _ => secant.clone(),
                };
                Ok(Point::new(z, tangent, orbit))
            };
            let s = bracketed_root_within(
                |s| at(s).map_or(f64::NAN, |p| p.tests[i]),
                (0.0, from.tests[i]),
                (ds, to.tests[i]),
                self.locate,
            )
            .map_err(|e| lost(e.to_string()))?;
            let point = at(s).map_err(|e| lost(e.to_string()))?;
            branch.special.push(SpecialPoint {
                kind,
                level: point.z[point.z.len() - 1],
                orbit: point.orbit,
                after: branch.members.len(),
                z: point.z,
                tangent: point.tangent,
            });
        }
        Ok(())
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

    /// The corrector from the predictor z + Δs τ of `from`: the new unknowns and the orbit.
    fn correct<S: TangentStepper>(
        &self,
        shooting: &mut Shooting<S>,
        from: &Point<S::Partner>,
        ds: f64,
    ) -> Result<(DVector<f64>, PeriodicOrbit<S::Partner>)> {
        let predicted = &from.z + &from.tangent * ds;
        let newton = shooting.newton_settings();
        let prev = &from.orbit;
        let (problem, speed) = shooting.equations(&prev.initial, prev.period)?;
        let bordered = Bordered::new(problem, from.tangent.clone(), from.z.clone(), ds);
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
