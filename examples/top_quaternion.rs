//! The heavy symmetric top with its orientation as a unit quaternion (noether-rigid, LGVI): the same
//! top as the Euler-angle examples `heavy_top` and `top_nutation` (I₁ = 1, I₃ = ½, M g ℓ = 1), with no
//! chart, so that a sleeping top and a top whose axis swings over the vertical θ = 0 run straight
//! through.
//!
//! Closed forms (the graduate text's ch. 64; `heavy_top`): with u = cos θ = R₃₃ the constants
//! p_ψ = Π₃, p_φ = L_z = (RΠ)_z and E give u̇² = f(u), a cubic whose roots u₁ < u₂ in [−1, 1] bound
//! the nutation; one nutation period T and the precession Δφ in it by the quadrature of `heavy_top`.
//! With p_φ = p_ψ the cubic has the root u = 1: θ reaches 0, the axis passes over the vertical.
//!
//! Run: `cargo run --release --features examples --example top_quaternion` (the picture goes to `gallery-out/`).

use noether::nalgebra::{Matrix3, UnitQuaternion, Vector3};
use noether::plot::Figure;
use noether::prelude::*;
use noether::rigid::{Inertia, Lgvi, RigidBody, UniformGravity};
use noether_gallery::examples::heavy_top::{
    constants, cubic_roots, nutating_start, nutation_cubic, nutation_quadrature, GALLERY_TOP,
};
use noether_gallery::{BoxError, Check, Options, Report};
use std::process::ExitCode;

const NAME: &str = "top_quaternion";
/// Step of the LGVI (the spin ψ̇ = 8 makes hω₃ ≈ 1.7e-3 per step).
const H: f64 = 2e-4;

/// The gallery's top as a rigid body: J = diag(I₁, I₁, I₃), V = M g ℓ R₃₃ (centre of mass at ℓ e₃).
fn body() -> Result<RigidBody<UniformGravity>, BoxError> {
    let top = GALLERY_TOP;
    let gravity = UniformGravity {
        mass: 1.0,
        g: top.mgl,
        center: Vector3::new(0.0, 0.0, 1.0),
    };
    Ok(RigidBody::new(
        Inertia::principal(top.i1, top.i1, top.i3)?,
        gravity,
    )?)
}

/// The top at Euler angles (φ, θ, ψ) = (0, θ, 0), R = R_x(θ), with rates (θ̇, φ̇, ψ̇): body
/// Ω = (θ̇, φ̇ sin θ, φ̇ cos θ + ψ̇).
fn start(b: &RigidBody<UniformGravity>, theta: f64, dtheta: f64, dphi: f64, dpsi: f64) -> State<Momenta> {
    let q = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), theta);
    b.state(
        0.0,
        &q,
        &Vector3::new(dtheta, dphi * theta.sin(), dphi * theta.cos() + dpsi),
    )
}

fn rot(b: &RigidBody<UniformGravity>, s: &State<Momenta>) -> Result<Matrix3<f64>, BoxError> {
    Ok(b.orientation(s)?.to_rotation_matrix().into_inner())
}

/// θ = atan2(sin θ, cos θ) of the symmetry axis R e₃, accurate near θ = 0.
fn theta(r: &Matrix3<f64>) -> f64 {
    r[(0, 2)].hypot(r[(1, 2)]).atan2(r[(2, 2)])
}

/// u̇ = d/dt (R e₃)_z = (R (Ω × e₃))_z.
fn u_dot(b: &RigidBody<UniformGravity>, s: &State<Momenta>) -> f64 {
    let (Ok(q), Ok(w)) = (b.orientation(s), b.body_angular_velocity(s)) else {
        return f64::NAN;
    };
    (q * w.cross(&Vector3::z())).z
}

/// (p_φ, p_ψ, E) = ((RΠ)_z, Π₃, ½Π·J⁻¹Π + M g ℓ R₃₃).
fn quaternion_constants(
    b: &RigidBody<UniformGravity>,
    s: &State<Momenta>,
) -> Result<(f64, f64, f64), BoxError> {
    Ok((
        b.spatial_angular_momentum(s)?.z,
        b.body_momentum(s)?.z,
        b.energy(s)?,
    ))
}

const THETA_MAX: &str = "θ maximal (u̇ = 0 up)";
const THETA_MIN: &str = "θ minimal (u̇ = 0 down)";

fn run_top(
    b: RigidBody<UniformGravity>,
    s: State<Momenta>,
    t_end: f64,
) -> Result<Solution<Momenta>, BoxError> {
    let ud = move |s: &State<Momenta>| u_dot(&b, s);
    Ok(Driver::new(Lgvi::new(b)?, s)?
        .step_size(H)?
        .save(Save::Every(50))?
        .event(Event::new(THETA_MAX, ud).rising())
        .event(Event::new(THETA_MIN, ud).falling())
        .run_until(t_end)?)
}

/// Runs the example.
///
/// Tolerances (LGVI, h = 2·10⁻⁴, O(h²) global error; turning points are events on the driver's cubic
/// Hermite interpolant, θ computed there):
/// - the constants of the quaternion state against the Euler-angle model's at the same start: rounding
///   (measured 0; tolerance 1e-14);
/// - the nutating top: θ at every turning point against acos u₂ (measured 4.33e-8 relative; tolerance
///   5e-8) and acos u₁ (θ₀ itself: measured 6.6e-13; tolerance 1e-12); the nutation period and the
///   precession per nutation against the quadrature (measured 3.19e-7 and 3.37e-7 relative; tolerance
///   4e-7); p_φ and p_ψ kept by the discrete Noether theorem up to the rounding of 60 000 steps
///   (measured 4.4e-13 relative; tolerance 6e-13);
/// - the sleeping top (vertical, spinning): θ stays 0 exactly (measured 0; tolerance 1e-15);
/// - the top over the vertical (p_φ = p_ψ): θ_max at each swing against θ₀ = acos of the cubic's root
///   (measured 2.7e-13 relative; tolerance 4e-13), θ_min against the root u = 1, i.e. θ = 0 (measured
///   3.6e-13 rad; tolerance 5e-13), p_φ − p_ψ stays 0 (measured 2.6e-13; tolerance 4e-13).
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    let mut report = Report::default();
    let b = body()?;
    let top = GALLERY_TOP;

    // 1. The nutating top of `top_nutation`: θ₀ = 0.8, θ̇₀ = 0, φ̇₀ = 0.5, ψ̇₀ = 8.
    let s0 = start(&b, 0.8, 0.0, 0.5, 8.0);
    let (pf, pp, e) = quaternion_constants(&b, &s0)?;
    let (pf_e, pp_e, e_e) = constants(&EulerLagrange::new(top), &nutating_start())?;
    let agree = [(pf - pf_e).abs(), (pp - pp_e).abs(), (e - e_e).abs()]
        .into_iter()
        .fold(0.0, f64::max);
    report.checks.push(Check::abs(
        NAME,
        "(p_φ, p_ψ, E) quaternion vs Euler-angle model",
        agree,
        0.0,
        1e-14,
    ));
    let cubic = nutation_cubic(&top, pf, pp, e);
    let roots = cubic_roots(cubic).ok_or("the nutation cubic has one real root")?;
    let (theta_min, theta_max) = (roots[1].acos(), roots[0].acos());
    let (period, dphi) = nutation_quadrature(&top, cubic, roots, pf, pp);
    let sol = run_top(b, s0, 12.0)?;
    let mut worst_max: f64 = 0.0;
    let mut worst_min: f64 = 0.0;
    let mut maxima = vec![];
    for rec in sol.events_named(THETA_MAX)? {
        let r = rot(&b, &rec.state)?;
        worst_max = worst_max.max((theta(&r) - theta_max).abs() / theta_max);
        maxima.push((rec.state.t, r[(0, 2)].atan2(-r[(1, 2)])));
    }
    for rec in sol.events_named(THETA_MIN)? {
        worst_min = worst_min.max((theta(&rot(&b, &rec.state)?) - theta_min).abs() / theta_min);
    }
    if maxima.len() < 3 {
        return Err(format!("expected several nutations, saw {}", maxima.len()).into());
    }
    report.checks.push(Check::abs(
        NAME,
        "θ_min vs acos u₂ (worst, relative)",
        worst_min,
        0.0,
        5e-8,
    ));
    report.checks.push(Check::abs(
        NAME,
        "θ_max vs acos u₁ (worst, relative)",
        worst_max,
        0.0,
        1e-12,
    ));
    // The azimuth φ of the axis at successive maxima, unwrapped.
    let n = maxima.len() - 1;
    let mut advance = 0.0;
    for w in maxima.windows(2) {
        let d = w[1].1 - w[0].1;
        advance += d - (d / std::f64::consts::TAU).round() * std::f64::consts::TAU;
    }
    let measured_t = (maxima[n].0 - maxima[0].0) / n as f64;
    report.checks.push(Check::rel(
        NAME,
        "nutation period vs quadrature",
        measured_t,
        period,
        4e-7,
    ));
    report.checks.push(Check::rel(
        NAME,
        "precession Δφ per nutation vs quadrature",
        advance / n as f64,
        dphi,
        4e-7,
    ));
    let last = sol.last();
    let (pf1, pp1, _) = quaternion_constants(&b, last)?;
    let drift = ((pf1 - pf) / pf).abs().max(((pp1 - pp) / pp).abs());
    report
        .checks
        .push(Check::abs(NAME, "p_φ, p_ψ kept (relative)", drift, 0.0, 6e-13));
    let mut fig = Figure::new("Heavy top in quaternions: the apex of the axis (x, y)")
        .x_label("x")
        .y_label("y");
    let apex: Vec<(f64, f64)> = (0..sol.times().len())
        .filter_map(|i| rot(&b, &sol.state(i)).ok().map(|r| (r[(0, 2)], r[(1, 2)])))
        .collect();
    fig = fig.series("nutating top", apex);

    // 2. The sleeping top: vertical, spinning at ω₃ = 8 (above I₃²ω₃² = 4 I₁ M g ℓ).
    let sleeping = run_top(b, start(&b, 0.0, 0.0, 0.0, 8.0), 5.0)?;
    let mut tilt: f64 = 0.0;
    for i in 0..sleeping.times().len() {
        tilt = tilt.max(theta(&rot(&b, &sleeping.state(i))?));
    }
    report
        .checks
        .push(Check::abs(NAME, "sleeping top: max θ", tilt, 0.0, 1e-15));

    // 3. Over the vertical: θ₀ = 0.8, θ̇₀ = 0, ω₃ = 5, φ̇₀ = p_ψ/(I₁(1 + cos θ₀)) so that p_φ = p_ψ.
    let (th0, w3) = (0.8_f64, 5.0);
    let dphi0 = top.i3 * w3 / (top.i1 * (1.0 + th0.cos()));
    let s0 = start(&b, th0, 0.0, dphi0, w3 - dphi0 * th0.cos());
    let (pf, pp, e) = quaternion_constants(&b, &s0)?;
    let roots = cubic_roots(nutation_cubic(&top, pf, pp, e)).ok_or("the cubic has one real root")?;
    // The roots: cos θ₀ and 1 (p_φ = p_ψ), and the third (> 1, or the double root 1).
    let theta_top = roots[0].acos();
    let over = run_top(b, s0, 12.0)?;
    let (mut worst_max, mut worst_min): (f64, f64) = (0.0, 0.0);
    let (mut n_max, mut n_min) = (0, 0);
    for rec in over.events_named(THETA_MAX)? {
        worst_max = worst_max.max((theta(&rot(&b, &rec.state)?) - theta_top).abs() / theta_top);
        n_max += 1;
    }
    for rec in over.events_named(THETA_MIN)? {
        worst_min = worst_min.max(theta(&rot(&b, &rec.state)?));
        n_min += 1;
    }
    if n_max < 2 || n_min < 2 {
        return Err(
            format!("expected swings over the vertical, saw {n_max} maxima and {n_min} minima").into(),
        );
    }
    report.checks.push(Check::abs(
        NAME,
        "over the vertical: θ_max vs θ₀ = acos u₁ (relative)",
        worst_max,
        0.0,
        4e-13,
    ));
    report.checks.push(Check::abs(
        NAME,
        "over the vertical: θ_min vs 0 (root u = 1)",
        worst_min,
        0.0,
        5e-13,
    ));
    let (pf1, pp1, _) = quaternion_constants(&b, over.last())?;
    report.checks.push(Check::abs(
        NAME,
        "over the vertical: p_φ − p_ψ",
        pf1 - pp1,
        0.0,
        4e-13,
    ));
    let apex: Vec<(f64, f64)> = (0..over.times().len())
        .filter_map(|i| rot(&b, &over.state(i)).ok().map(|r| (r[(0, 2)], r[(1, 2)])))
        .collect();
    fig = fig.series("over the vertical (p_φ = p_ψ)", apex);
    report.save(opts, &fig, "top_quaternion_apex.svg")?;
    Ok(report)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
