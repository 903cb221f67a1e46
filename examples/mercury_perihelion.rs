//! Mercury's relativistic perihelion advance: a test particle around the Sun under Newton's gravity
//! plus the first post-Newtonian (1PN) correction, integrated by IAS15 with velocity-dependent forces,
//! against Einstein's Δϖ = 6πGM/(c² a (1 − e²)) per orbit (43″ per century).
//!
//! The model (the test-particle limit of the Einstein-Infeld-Hoffmann equations in harmonic
//! coordinates, the acceleration of REBOUNDx's `gr` effect with one dominant mass; Anderson et al.,
//! ApJ 200 (1975) 221; Tamayo et al., MNRAS 491 (2020) 2885):
//!
//! ```text
//! a = −GM r/r³ + (GM/(c² r³)) [ (4GM/r − v²) r + 4 (r·v) v ].
//! ```
//!
//! The 1PN term depends on the velocity, so the system is stepped through
//! `VelocityDependent`: IAS15 predicts v at its nodes as well as q.
//!
//! **Closed form.** To first order in ε = GM/(c² p), p = a(1 − e²), the pericentre advances by
//! Δϖ = 6πGM/(c² p) per radial period (Einstein 1915; Weinberg, *Gravitation and Cosmology* (1972)
//! §8.6; Misner, Thorne & Wheeler, *Gravitation* §40.5). The model's exact advance differs from it
//! at the next order, by a relative O(ε): for Mercury ε = 2.7e-8.
//!
//! **Measurement.** At pericentre r·v = 0, so the Laplace-Runge-Lenz vector A = v × (r × v) − GM r/r
//! points exactly at the body: its direction there is the direction of perihelion. The driver
//! locates each passage (r·v crossing zero upwards) on the dense output, and the advance per orbit is
//! the angle of A at the last passage over the number of orbits. A timing error δt of a passage moves
//! that angle only by dϖ/dt δt (the 1PN term turns A slowly), so the angle is as precise as the state.
//!
//! Run: `cargo run --release --features examples --example mercury_perihelion` (the picture goes to
//! `gallery-out/`).

use noether::core::integrators::VelocityDependent;
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use std::f64::consts::PI;
use std::process::ExitCode;

/// GM of the Sun in AU³/day² (Gauss's constant k = 0.01720209895, GM = k²).
pub const GM_SUN: f64 = 0.01720209895 * 0.01720209895;
/// The speed of light in AU/day: 299 792 458 m/s × 86 400 s / 149 597 870 700 m.
pub const C_AU_PER_DAY: f64 = 299_792_458.0 * 86_400.0 / 149_597_870_700.0;
/// Mercury's semi-major axis (AU) and eccentricity (J2000).
pub const MERCURY: (f64, f64) = (0.387_098_93, 0.205_630_69);
/// Orbits integrated (48 years).
pub const ORBITS: usize = 200;

/// A test particle in the plane around a mass GM at the origin, Newton plus the 1PN term at the
/// speed of light c (c = ∞: Newton alone).
#[derive(Debug, Clone, Copy)]
pub struct PostNewtonian {
    /// GM of the central mass.
    pub gm: f64,
    /// The speed of light.
    pub c: f64,
}

impl Dynamics for PostNewtonian {
    type Partner = Velocities;
    fn dof(&self) -> usize {
        2
    }
    fn rates(
        &self,
        _t: f64,
        q: &[f64],
        v: &[f64],
        dq: &mut [f64],
        dv: &mut [f64],
    ) -> noether::core::Result<()> {
        let r2 = q[0] * q[0] + q[1] * q[1];
        let r = r2.sqrt();
        let k = self.gm / (r2 * r);
        let v2 = v[0] * v[0] + v[1] * v[1];
        let rv = q[0] * v[0] + q[1] * v[1];
        let pn = k / (self.c * self.c);
        let radial = 4.0 * self.gm / r - v2;
        for i in 0..2 {
            dq[i] = v[i];
            dv[i] = -k * q[i] + pn * (radial * q[i] + 4.0 * rv * v[i]);
        }
        Ok(())
    }
    /// The Newtonian energy ½v² − GM/r (not conserved by the 1PN flow: it oscillates at O(ε)).
    fn energy(&self, _t: f64, q: &[f64], v: &[f64]) -> noether::core::Result<f64> {
        Ok(0.5 * (v[0] * v[0] + v[1] * v[1]) - self.gm / q[0].hypot(q[1]))
    }
}

impl PostNewtonian {
    /// Starts at perihelion (a(1 − e), 0) moving in +y at the vis-viva speed √(GM(1 + e)/(a(1 − e))):
    /// the osculating (Newtonian) elements there are a and e.
    pub fn perihelion_state(&self, a: f64, e: f64) -> State {
        State::new(
            0.0,
            [a * (1.0 - e), 0.0],
            [0.0, (self.gm * (1.0 + e) / (a * (1.0 - e))).sqrt()],
        )
    }

    /// The direction of the Laplace-Runge-Lenz vector A = v × (r × v) − GM r/r = (v² − GM/r) r −
    /// (r·v) v, as an angle.
    pub fn perihelion_angle(&self, q: &[f64], v: &[f64]) -> f64 {
        let r = q[0].hypot(q[1]);
        let (v2, rv) = (v[0] * v[0] + v[1] * v[1], q[0] * v[0] + q[1] * v[1]);
        let w = v2 - self.gm / r;
        (w * q[1] - rv * v[1]).atan2(w * q[0] - rv * v[0])
    }

    /// The perihelion angle at each perihelion passage over `orbits` orbits (the start, then one
    /// per orbit), with IAS15 at the default ε.
    pub fn perihelia(&self, (a, e): (f64, f64), orbits: usize) -> Result<Vec<f64>, BoxError> {
        let period = 2.0 * PI * (a * a * a / self.gm).sqrt();
        let start = self.perihelion_state(a, e);
        let sol = Driver::new(Ias15::new(VelocityDependent(*self))?, start.clone())?
            .save(Save::End)?
            .event(Event::new("perihelion", |s: &State| s.q[0] * s.v[0] + s.q[1] * s.v[1]).rising())
            .run_until((orbits as f64 + 0.5) * period)?;
        let mut angles = vec![self.perihelion_angle(start.q.as_slice(), start.v.as_slice())];
        for ev in sol.events_named("perihelion")? {
            angles.push(self.perihelion_angle(ev.state.q.as_slice(), ev.state.v.as_slice()));
        }
        if angles.len() != orbits + 1 {
            return Err(format!("{} perihelion passages in {orbits} orbits", angles.len() - 1).into());
        }
        // Unwrap (the angle stays far below π here, but a larger c⁻² would wrap it).
        for i in 1..angles.len() {
            angles[i] = angles[i - 1] + (angles[i] - angles[i - 1] + PI).rem_euclid(2.0 * PI) - PI;
        }
        Ok(angles)
    }
}

/// Einstein's advance per orbit, 6πGM/(c² a (1 − e²)).
pub fn einstein_advance(gm: f64, c: f64, (a, e): (f64, f64)) -> f64 {
    6.0 * PI * gm / (c * c * a * (1.0 - e * e))
}

/// Runs the example.
///
/// Method: IAS15 at its default ε = 1e-9 (machine precision per step) on the 1PN model, 200 orbits,
/// and on Newton's model (c = ∞) for the floor of the measurement: whatever precession the
/// integrator adds, its rounding. The checks:
/// - the advance per orbit against 6πGM/(c²a(1 − e²)) to 1e-6 relative (the issue's demand):
///   measured 9.2e-8, which is the model's next-order term, not an error (below);
/// - the same in arcseconds per Julian century (42.98″, the anomaly Le Verrier found);
/// - the next-order term: the relative difference over ε = GM/(c²p), (Δϖ/Δϖ₁ₚₙ − 1)/ε, is a
///   coefficient of the model's orbit (measured −3.4664 with the real c, ε = 2.66e-8); a run with c
///   lowered to ε = 1e-5, where the difference is 400 times larger and the measurement's floor
///   negligible, finds the same coefficient (−3.4647) up to O(ε) and the floor of the real-c run:
///   Newton's drift 4.4e-15 rad is 4.4e-11 of the 200 orbits' advance (1.0e-4 rad), 1.7e-3 of the
///   coefficient once divided by ε. Measured 4.7e-4 relative, checked at 5e-3. So the 1PN advance
///   and the size of the deviation from it are both what the model gives;
/// - Newton's model (c = ∞): the perihelion angle after 200 orbits is rounding, checked at 1e-11 rad
///   (measured 4.4e-15): the integrator adds no precession of its own at this level.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let ex = "mercury_perihelion";
    let (a, e) = MERCURY;
    let model = PostNewtonian {
        gm: GM_SUN,
        c: C_AU_PER_DAY,
    };
    let expected = einstein_advance(GM_SUN, C_AU_PER_DAY, MERCURY);
    let angles = model.perihelia(MERCURY, ORBITS)?;
    let advance = (angles[ORBITS] - angles[0]) / ORBITS as f64;
    let newton = PostNewtonian {
        gm: GM_SUN,
        c: f64::INFINITY,
    }
    .perihelia(MERCURY, ORBITS)?;
    let newton_drift = newton[ORBITS] - newton[0];
    let period = 2.0 * PI * (a * a * a / GM_SUN).sqrt();
    let arcsec_per_century = |rad_per_orbit: f64| rad_per_orbit * (36_525.0 / period) * 180.0 / PI * 3600.0;
    let p = a * (1.0 - e * e);
    let eps = GM_SUN / (C_AU_PER_DAY * C_AU_PER_DAY * p);
    // The next-order term, (Δϖ/Δϖ₁ₚₙ − 1)/ε, at the real c and at a c for which ε = EPS_LARGE.
    let coefficient = (advance / expected - 1.0) / eps;
    let large = PostNewtonian {
        gm: GM_SUN,
        c: (GM_SUN / (p * EPS_LARGE)).sqrt(),
    };
    let angles_large = large.perihelia(MERCURY, ORBITS)?;
    let advance_large = (angles_large[ORBITS] - angles_large[0]) / ORBITS as f64;
    let coefficient_large = (advance_large / einstein_advance(GM_SUN, large.c, MERCURY) - 1.0) / EPS_LARGE;
    let mut report = Report::default();
    report.note(format!(
        "Mercury, {ORBITS} orbits (T = {period:.3} d): advance {advance:.10e} rad/orbit, Einstein \
         {expected:.10e}, relative difference {:.1e} (ε = GM/(c²p) = {eps:.2e}); Newton's model: \
         {newton_drift:.1e} rad after {ORBITS} orbits; (Δϖ/Δϖ₁ₚₙ − 1)/ε = {coefficient:.4} (real c), \
         {coefficient_large:.4} (ε = {EPS_LARGE:e})",
        (advance / expected - 1.0).abs()
    ));
    report.checks.push(Check::rel(
        ex,
        "perihelion advance per orbit (rad) vs 6πGM/(c²a(1 − e²))",
        advance,
        expected,
        TOL_ADVANCE,
    ));
    report.checks.push(Check::rel(
        ex,
        "perihelion advance (″ per century) vs 42.98″",
        arcsec_per_century(advance),
        arcsec_per_century(expected),
        TOL_ADVANCE,
    ));
    report.checks.push(Check::rel(
        ex,
        "next-order term (Δϖ/Δϖ₁ₚₙ − 1)/ε: real c vs ε = 1e-5",
        coefficient,
        coefficient_large,
        TOL_COEFFICIENT,
    ));
    report.checks.push(Check::abs(
        ex,
        "Newton's model: perihelion angle after 200 orbits (rad)",
        newton_drift,
        0.0,
        TOL_NEWTON,
    ));
    let figure = Figure::new("Mercury: perihelion angle, 1PN (IAS15) and Einstein's 6πGM/(c²a(1 − e²))")
        .x_label("orbits")
        .y_label("ϖ (arcseconds)")
        .dots(
            "measured at each perihelion",
            angles
                .iter()
                .enumerate()
                .map(|(k, w)| (k as f64, w * 180.0 / PI * 3600.0))
                .collect(),
        )
        .series(
            "Einstein",
            vec![
                (0.0, 0.0),
                (ORBITS as f64, ORBITS as f64 * expected * 180.0 / PI * 3600.0),
            ],
        );
    report.save(opts, &figure, "mercury_perihelion.svg")?;
    Ok(report)
}

const TOL_ADVANCE: f64 = 1e-6;
const TOL_NEWTON: f64 = 1e-11;
/// ε = GM/(c²p) of the run with an exaggerated 1PN term.
const EPS_LARGE: f64 = 1e-5;
const TOL_COEFFICIENT: f64 = 5e-3;

fn main() -> ExitCode {
    noether_gallery::example_main("mercury_perihelion", run)
}
