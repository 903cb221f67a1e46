//! Poincaré sections: the points where an orbit pierces a surface g(state) = 0 in one direction,
//! located by the driver's [`Event`]s on the continuous extension of each step.
//!
//! For a two-degree-of-freedom autonomous H the section q₁ = c (crossed with q̇₁ > 0) on the energy
//! surface H = E is a two-dimensional map (q₂, p₂) ↦ (q₂′, p₂′): regular orbits draw closed
//! curves (the traces of their invariant tori), chaotic ones fill areas. Any [`Stepper`] serves, so
//! the accuracy is the integrator's; the points are states on the continuous extension at the
//! crossing time found to rounding by core's [`bracketed_root`](noether_core::roots::bracketed_root).
//!
//! ```
//! use noether_canonical::section::{section, Plane};
//! use noether_core::prelude::*;
//!
//! /// Two uncoupled oscillators, ω = 1 and sqrt 2.
//! struct Two;
//! impl Hamiltonian for Two {
//!     fn dof(&self) -> usize { 2 }
//!     fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
//!         (p[0] * p[0] + p[1] * p[1] + q[0] * q[0] + q[1] * q[1] * 2.0) * 0.5
//!     }
//! }
//! let dop = Dop853::new(HamiltonEquations::new(Two)).tolerances(1e-12, 1e-12)?;
//! let driver = Driver::new(dop, State::with_momenta(0.0, [0.0, 0.3], [1.0, 0.2]))?;
//! let points = section(driver, Plane::coordinate(0, 0.0), 100.0)?;
//! // Each point has q₀ = 0 and lies on the y-oscillator's energy curve (p₁² + 2 q₁²)/2 = 0.11.
//! for s in &points.states {
//!     assert!(s.q[0].abs() < 1e-12);
//!     assert!(((s.v[1] * s.v[1] + 2.0 * s.q[1] * s.q[1]) * 0.5 - 0.11).abs() < 1e-10);
//! }
//! assert_eq!(points.len(), 15); // one crossing per period 2π after the start, up to t = 100
//! # Ok::<(), noether_canonical::Error>(())
//! ```

use crate::Result;
use noether_core::{Direction, Driver, Event, Partner, Save, State, Stats, Stepper};

/// The surface qₖ = `value` crossed in a given direction (default: qₖ increasing).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// The coordinate index k.
    pub coordinate: usize,
    /// The value c of the section qₖ = c.
    pub value: f64,
    /// Which crossings count.
    pub direction: Direction,
}

impl Plane {
    /// The section qₖ = `value`, crossed with qₖ increasing.
    pub fn coordinate(k: usize, value: f64) -> Self {
        Plane {
            coordinate: k,
            value,
            direction: Direction::Rising,
        }
    }

    /// The same plane crossed in `direction`.
    pub fn direction(mut self, direction: Direction) -> Self {
        self.direction = direction;
        self
    }
}

/// The points of a Poincaré section: the crossing times and the states there.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct SectionPoints<K> {
    /// Crossing times.
    pub times: Vec<f64>,
    /// States at the crossings (q and the partner, velocities or momenta).
    pub states: Vec<State<K>>,
    /// Statistics of the run.
    pub stats: Stats,
}

impl<K: Partner> SectionPoints<K> {
    /// Number of points.
    pub fn len(&self) -> usize {
        self.states.len()
    }

    /// `true` when the orbit never crossed.
    pub fn is_empty(&self) -> bool {
        self.states.is_empty()
    }

    /// The points as pairs (q_i, partner_j): for a 2-dof H and the plane q₀ = c, `pairs(1, 1)` is the
    /// usual (q₁, p₁) picture.
    pub fn pairs(&self, i: usize, j: usize) -> Vec<(f64, f64)> {
        self.states.iter().map(|s| (s.q[i], s.v[j])).collect()
    }
}

/// The section of the orbit run by `driver` until `t_end` through the plane `plane`.
pub fn section<'a, S: Stepper>(
    driver: Driver<'a, S>,
    plane: Plane,
    t_end: f64,
) -> Result<SectionPoints<S::Partner>> {
    let dof = driver.stepper().dof();
    if plane.coordinate >= dof {
        return Err(noether_core::Error::Dimension {
            what: "section coordinate (index below dof)",
            expected: dof,
            got: plane.coordinate,
        }
        .into());
    }
    let (k, c) = (plane.coordinate, plane.value);
    section_by(
        driver,
        move |s: &State<S::Partner>| s.q[k] - c,
        plane.direction,
        t_end,
    )
}

/// The section of the orbit run by `driver` until `t_end` through any surface g(state) = 0, crossed
/// in `direction`.
pub fn section_by<'a, S: Stepper>(
    driver: Driver<'a, S>,
    g: impl FnMut(&State<S::Partner>) -> f64 + 'a,
    direction: Direction,
    t_end: f64,
) -> Result<SectionPoints<S::Partner>> {
    let mut driver = driver
        .save(Save::End)?
        .event(Event::new("section", g).direction(direction));
    let sol = driver.run_until(t_end)?;
    let (times, states) = sol.events().iter().map(|e| (e.t, e.state.clone())).unzip();
    Ok(SectionPoints {
        times,
        states,
        stats: *sol.stats(),
    })
}
