//! Canonical transformations, from maps and from generating functions: the harmonic oscillator to
//! action-angle variables with F₁ = ½ m ω q² cot Q (K = ωP exactly, so Q̇ = ω, Ṗ = 0), polar
//! coordinates as a point transformation (symplectic to rounding, from the map and from
//! F₃ = −(p_x r cos θ + p_y r sin θ)), and the time-dependent transformation to a rotating frame with
//! F₂ = P·R(−ωt) q, whose new Hamiltonian is K = H − ω L_z.
//!
//! Run: `cargo run --release --features examples --example canonical_transformation` (the rotating-frame picture goes to
//! `gallery-out/`).

use noether::canonical::generating::{Generated, GeneratingFunction, Kind, Transformed};
use noether::canonical::transform::{self, canonicity, invert, newton_to_rounding, CanonicalMap};
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use std::f64::consts::PI;
use std::process::ExitCode;

/// The oscillator H = p²/2m + ½ m ω² q².
#[derive(Debug, Clone, Copy)]
pub struct Oscillator {
    /// Mass.
    pub m: f64,
    /// Angular frequency.
    pub w: f64,
}

impl Hamiltonian for Oscillator {
    fn dof(&self) -> usize {
        1
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        p[0] * p[0] * (0.5 / self.m) + q[0] * q[0] * (0.5 * self.m * self.w * self.w)
    }
}

/// F₁(q, Q) = ½ m ω q² cot Q: p = mωq cot Q, P = ½mωq²/sin²Q, i.e. q = sqrt(2P/mω) sin Q,
/// p = sqrt(2mωP) cos Q (degenerate where q = 0).
#[derive(Debug, Clone, Copy)]
pub struct ActionAngle {
    /// Mass.
    pub m: f64,
    /// Angular frequency.
    pub w: f64,
}

impl GeneratingFunction for ActionAngle {
    fn kind(&self) -> Kind {
        Kind::F1
    }
    fn dof(&self) -> usize {
        1
    }
    fn generating<D: Scalar>(&self, _t: D, q: &[D], big_q: &[D]) -> D {
        q[0] * q[0] * big_q[0].tan().recip() * (0.5 * self.m * self.w)
    }
}

/// Polar coordinates as a map: r, θ, p_r = (x p_x + y p_y)/r, p_θ = x p_y − y p_x.
pub struct Polar;

impl CanonicalMap for Polar {
    fn dof(&self) -> usize {
        2
    }
    fn map<D: Scalar>(&self, _t: D, q: &[D], p: &[D], nq: &mut [D], np: &mut [D]) {
        let r = (q[0] * q[0] + q[1] * q[1]).sqrt();
        nq[0] = r;
        nq[1] = q[1].atan2(q[0]);
        np[0] = (q[0] * p[0] + q[1] * p[1]) / r;
        np[1] = q[0] * p[1] - q[1] * p[0];
    }
}

/// Polar coordinates from F₃(p, Q) = −(p_x r cos θ + p_y r sin θ): q = −∂F/∂p, P = −∂F/∂Q.
pub struct PolarF3;

impl GeneratingFunction for PolarF3 {
    fn kind(&self) -> Kind {
        Kind::F3
    }
    fn dof(&self) -> usize {
        2
    }
    fn generating<D: Scalar>(&self, _t: D, p: &[D], big_q: &[D]) -> D {
        let (s, c) = big_q[1].sin_cos();
        -(p[0] * c + p[1] * s) * big_q[0]
    }
}

/// A planar anharmonic oscillator H = |p|²/2m + ½ m ω₀² r² + ε r⁴ (rotationally invariant).
#[derive(Debug, Clone, Copy)]
pub struct Planar {
    /// Mass.
    pub m: f64,
    /// Frequency of the harmonic part.
    pub w0: f64,
    /// Quartic coefficient.
    pub eps: f64,
}

impl Hamiltonian for Planar {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let r2 = q[0] * q[0] + q[1] * q[1];
        (p[0] * p[0] + p[1] * p[1]) * (0.5 / self.m)
            + r2 * (0.5 * self.m * self.w0 * self.w0)
            + r2 * r2 * self.eps
    }
}

/// F₂(q, P, t) = P·R(−ωt) q: coordinates Q = R(−ωt) q and momenta P = R(−ωt) p of a frame rotating
/// at ω; K = H + ∂F₂/∂t = H − ω L_z.
pub struct RotatingFrame {
    /// Angular velocity of the frame.
    pub w: f64,
}

impl GeneratingFunction for RotatingFrame {
    fn kind(&self) -> Kind {
        Kind::F2
    }
    fn dof(&self) -> usize {
        2
    }
    fn generating<D: Scalar>(&self, t: D, q: &[D], big_p: &[D]) -> D {
        let (s, c) = (t * self.w).sin_cos();
        big_p[0] * (c * q[0] + s * q[1]) + big_p[1] * (c * q[1] - s * q[0])
    }
}

/// K = H − ω L_z written out, as an ordinary Hamiltonian model.
pub struct RotatingK {
    /// H of the inertial frame.
    pub h: Planar,
    /// Angular velocity of the frame.
    pub w: f64,
}

impl Hamiltonian for RotatingK {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<D: Scalar>(&self, t: D, q: &[D], p: &[D]) -> D {
        self.h.hamiltonian(t, q, p) - (q[0] * p[1] - q[1] * p[0]) * self.w
    }
}

/// R(−ωt) applied to a planar vector.
fn to_rotating(w: f64, t: f64, v: &[f64]) -> [f64; 2] {
    let (s, c) = (w * t).sin_cos();
    [c * v[0] + s * v[1], c * v[1] - s * v[0]]
}

/// Runs the example.
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    const EX: &str = "canonical_transformation";
    let mut report = Report::default();

    // 1. Oscillator → action-angle. At (q, p) = (0.8, 2): Q = atan2(mωq, p), P = E/ω (closed form),
    // forward by Newton (measured 0 and 2.5e-16 relative; tolerance 2e-15), K = H + ∂F/∂t = ωP exactly
    // (F has no t; measured 2.2e-16; tolerance 2e-15), the generated map symplectic (measured 0,
    // tolerance 1e-15).
    let (m, w) = (1.7, 2.3);
    let osc = Oscillator { m, w };
    let aa = Generated::new(ActionAngle { m, w });
    let (q0, p0) = ([0.8], [2.0]);
    let (nq, np) = aa.forward(0.0, (&q0, &p0), (&[0.5], &[1.0]))?;
    let e = osc.hamiltonian(0.0, &q0, &p0);
    report.checks.push(Check::rel(
        EX,
        "oscillator: Q = atan2(mωq, p)",
        nq[0],
        (m * w * q0[0]).atan2(p0[0]),
        2e-15,
    ));
    report
        .checks
        .push(Check::rel(EX, "oscillator: P = E/ω", np[0], e / w, 2e-15));
    let k = aa.new_hamiltonian(&osc, 0.0, (&q0, &p0), (&nq, &np))?;
    report
        .checks
        .push(Check::rel(EX, "oscillator: K = ωP", k, w * np[0], 2e-15));
    let defect = aa.symplectic_defect(0.0, (&q0, &p0), (&nq, &np))?;
    report.checks.push(Check::abs(
        EX,
        "oscillator: ‖JᵀΩJ − Ω‖ of F1's map",
        defect,
        0.0,
        1e-15,
    ));
    // The motion in (Q, P) by DOP853 on K (Newton inverts the map at each stage): Q(t) = Q₀ + ωt,
    // P = P₀ until Q = π − 0.3 (F₁ degenerates at q = 0, Q = π). Measured 8.9e-16 and 2.2e-14
    // relative (rounding of the inverted rates accumulated); tolerances 4e-15 and 5e-14.
    let system = Transformed::new(osc, aa, (&q0, &p0))?;
    let t_end = (PI - 0.3 - nq[0]) / w;
    let sol = Driver::new(
        Dop853::new(&system).tolerances(1e-14, 1e-14)?,
        State::with_momenta(0.0, nq.clone(), np.clone()),
    )?
    .run_until(t_end)?;
    report.checks.push(Check::abs(
        EX,
        "oscillator: Q(t) − Q0 − ωt by DOP853 on K",
        sol.last().q[0] - nq[0] - w * t_end,
        0.0,
        4e-15,
    ));
    report.checks.push(Check::rel(
        EX,
        "oscillator: P(t) = P0 by DOP853 on K",
        sol.last().p()[0],
        np[0],
        5e-14,
    ));

    // 2. Polar coordinates: ‖JᵀΩJ − Ω‖ and ‖{Z, Z} − Ω‖ of the map at a point (measured 4.4e-16;
    // tolerance 2e-15); the inverse by Newton from a guess 10% off (measured 1.1e-16; tolerance 1e-15);
    // the map generated by F₃ equals the direct one (measured 4.4e-16; tolerance 1e-15).
    let (x, px) = ([0.9, -1.3], [0.4, 0.7]);
    let c = canonicity(&Polar, 0.0, &x, &px)?;
    report.checks.push(Check::abs(
        EX,
        "polar: max(‖JᵀΩJ − Ω‖, ‖{Z,Z} − Ω‖)",
        c.symplectic.max(c.brackets),
        0.0,
        2e-15,
    ));
    let (rq, rp) = transform::apply(&Polar, 0.0, &x, &px)?;
    let (bq, bp, _) = invert(
        &Polar,
        0.0,
        (&rq, &rp),
        (&[1.0, -1.2], &[0.35, 0.8]),
        &newton_to_rounding(),
    )?;
    let back = (0..2)
        .map(|i| (bq[i] - x[i]).abs().max((bp[i] - px[i]).abs()))
        .fold(0.0, f64::max);
    report
        .checks
        .push(Check::abs(EX, "polar: inverse by Newton", back, 0.0, 1e-15));
    let (gq, gp) = Generated::new(PolarF3).forward(0.0, (&x, &px), (&[1.7, -1.0], &[0.0, 0.0]))?;
    let same = (0..2)
        .map(|i| (gq[i] - rq[i]).abs().max((gp[i] - rp[i]).abs()))
        .fold(0.0, f64::max);
    report.checks.push(Check::abs(
        EX,
        "polar: F3's map = the direct map",
        same,
        0.0,
        1e-15,
    ));

    // 3. The rotating frame (time-dependent). K = H + ∂F₂/∂t against H − ωL_z at (t, q, p)
    // (measured 3.7e-16; tolerance 2e-15 relative), then the motion three ways over t ∈ [0, 20]: DOP853
    // on H in the inertial frame (rotated afterwards), on K through the generating function, and on
    // K = H − ωL_z as an ordinary model. Measured max difference 1.0e-13 (each route carries DOP853's
    // global error at 1e-14 over ~3 orbits); tolerance 2e-13.
    let h = Planar {
        m: 1.0,
        w0: 1.0,
        eps: 0.1,
    };
    let wf = 0.5;
    let rot = Generated::new(RotatingFrame { w: wf });
    let (t1, q1, p1) = (1.3, [1.0, 0.2], [0.1, 0.9]);
    let (rq1, rp1) = rot.forward(t1, (&q1, &p1), (&[0.0, 0.0], &[0.0, 0.0]))?;
    let k1 = rot.new_hamiltonian(&h, t1, (&q1, &p1), (&rq1, &rp1))?;
    let k_model = RotatingK { h, w: wf };
    report.checks.push(Check::rel(
        EX,
        "rotating frame: K = H − ω L_z",
        k1,
        k_model.hamiltonian(t1, &rq1, &rp1),
        2e-15,
    ));
    let t_end = 20.0;
    let times: Vec<f64> = (0..=400).map(|i| t_end * i as f64 / 400.0).collect();
    let inertial = Driver::new(
        Dop853::new(HamiltonEquations::new(h)).tolerances(1e-14, 1e-14)?,
        State::with_momenta(0.0, q1, p1),
    )?
    .save(Save::Times(times.clone()))?
    .run_until(t_end)?;
    let (nq1, np1) = (to_rotating(wf, 0.0, &q1), to_rotating(wf, 0.0, &p1));
    let through_f2 = Transformed::new(h, Generated::new(RotatingFrame { w: wf }), (&q1, &p1))?;
    let in_k = Driver::new(
        Dop853::new(&through_f2).tolerances(1e-14, 1e-14)?,
        State::with_momenta(0.0, nq1, np1),
    )?
    .save(Save::Times(times.clone()))?
    .run_until(t_end)?;
    let as_model = Driver::new(
        Dop853::new(HamiltonEquations::new(k_model)).tolerances(1e-14, 1e-14)?,
        State::with_momenta(0.0, nq1, np1),
    )?
    .save(Save::Times(times))?
    .run_until(t_end)?;
    let mut diff: f64 = 0.0;
    let (mut path_inertial, mut path_rotating) = (Vec::new(), Vec::new());
    for i in 0..inertial.len() {
        let t = inertial.times()[i];
        let (rq, rp) = (
            to_rotating(wf, t, inertial.q(i)),
            to_rotating(wf, t, inertial.v(i)),
        );
        for j in 0..2 {
            diff = diff
                .max((in_k.q(i)[j] - rq[j]).abs())
                .max((in_k.v(i)[j] - rp[j]).abs());
            diff = diff
                .max((as_model.q(i)[j] - rq[j]).abs())
                .max((as_model.v(i)[j] - rp[j]).abs());
        }
        path_inertial.push((inertial.q(i)[0], inertial.q(i)[1]));
        path_rotating.push((in_k.q(i)[0], in_k.q(i)[1]));
    }
    report.checks.push(Check::abs(
        EX,
        "rotating frame: three routes agree",
        diff,
        0.0,
        2e-13,
    ));
    let fig = Figure::new("One orbit seen from the inertial frame and from a frame rotating at ω = 0.5")
        .x_label("x, X")
        .y_label("y, Y")
        .equal_aspect()
        .series("inertial (H)", path_inertial)
        .series("rotating (K = H − ω L_z)", path_rotating);
    report.save(opts, &fig, "canonical_transformation_rotating.svg")?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main("canonical_transformation", run)
}
