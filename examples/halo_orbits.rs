//! Halo orbits of the Earth-Moon system, found the way the astrodynamics catalogues find them: follow
//! the planar Lyapunov family about L1 until a pair of its Floquet multipliers reaches +1, locate that
//! branch point, and switch onto the family that crosses there.
//!
//! ```text
//! H = ½|p|² + y p_x − x p_y − (1 − μ)/r₁ − μ/r₂ = −C/2,   μ = 0.01215 (rotating frame, unit distance)
//! ```
//!
//! A planar orbit's vertical variations decouple (z̈ = −((1 − μ)/r₁³ + μ/r₂³) z along it), so the
//! monodromy of a Lyapunov orbit has a vertical pair of multipliers e^{±iθ} besides the in-plane
//! saddle pair λ, 1/λ (λ ≈ 2600) and the trivial pair at 1. As the family grows, θ shrinks to 0: the
//! pair meets +1, ∏(1 − μ_i) over the non-trivial multipliers changes sign, and two out-of-plane
//! families of the same period branch off, mirror images under z ↦ −z: the northern and southern halo
//! orbits (Breakwell & Brown 1979; Howell 1984). `noether::analysis::Continuation` follows the Lyapunov
//! family by pseudo-arclength in the Jacobi constant, locates the branch point on the arclength, and
//! `switch` starts the halo families along the second null direction of the shooting Jacobian there.
//! The shooting is multiple (6 arcs) with Gauss-Legendre collocation of order 6: symplectic, so the
//! monodromy is symplectic and the energy error stays bounded. One half of the halo family is followed
//! towards the Moon, through the narrow band of stable orbits roughly halfway to it (Breakwell & Brown,
//! *Celest. Mech.* 20 (1979) 389): entered at a fold of the family in C, where a pair of multipliers
//! meets +1 and turns onto the unit circle, and left at a period doubling, where it leaves the circle
//! at −1.
//!
//! **Checks.**
//! - *The branch point* is where the vertical block of M (rows and columns z, p_z) has trace 2, and at
//!   the Jacobi constant C ≈ 3.1743 of the literature for the L1 halo bifurcation (Doedel et al.,
//!   *Int. J. Bifurcation Chaos* 17 (2007) 2625).
//! - *A pitchfork:* C* − C = κ z₀² + O(z₀⁴) along the halo family near it, κ nearly constant.
//! - *Mirror symmetry:* the southern family is the northern one under (z, p_z) ↦ (−z, −p_z).
//! - *The stable band:* every member between the fold and the period doubling is linearly stable
//!   (all multipliers on the unit circle), the members on either side unstable; at the fold the
//!   family's C is extremal and a non-trivial pair sits at +1 (∏(1 − μ_i) ≈ 0, from the monodromy,
//!   while the fold was located from the tangent); at the period doubling a multiplier sits at −1.
//! - *Each orbit is the flow's:* its energy held along it, its monodromy symplectic, its trivial pair
//!   of multipliers at 1, and the largest halo, run once round by DOP853 at tolerance 1e-13, closes.
//!
//! Run: `cargo run --release -- --only halo_orbits --checks --notes` (the families go to
//! `gallery-out/`).

use noether::analysis::periodic::{Energy, FirstIntegral, PeriodicOrbit, Shooting, Stability};
use noether::analysis::{Bifurcation, Branch, Continuation};
use noether::core::integrators::Gauss;
use noether::nalgebra::Complex;
use noether::plot::Figure;
use noether::prelude::*;
use noether_gallery::{BoxError, Check, Options, Report};
use noether_testkit::canonical::relative_symplectic_defect;
use noether_testkit::three_body::{
    energy_drift, flow_closure, l1, l1_spatial_guess, mirror_defect, sample_orbit, SpatialCr3bp,
};
use std::process::ExitCode;

const NAME: &str = "halo_orbits";

/// Earth-Moon mass ratio (Doedel et al. 2007's).
const MU: f64 = 0.01215;
/// The Jacobi constant of the L1 halo bifurcation in the literature (four decimals).
const PUBLISHED_C: f64 = 3.1743;

/// The shooting: Gauss-Legendre 6, 600 steps a period in 6 arcs, the energy held at `e`.
type HaloShooting = Shooting<Gauss<HamiltonEquations<SpatialCr3bp>>>;

fn shooting(e: f64) -> Result<HaloShooting, BoxError> {
    let model = SpatialCr3bp { mu: MU };
    Ok(Shooting::new(Gauss::gauss6(HamiltonEquations::new(model)), 600)?
        .segments(6)?
        .level(Energy(model), e))
}

/// The orbit's points (x − x_L1, z) for the picture, every 10th step of the shooting's method.
fn projection(
    stepper: &mut Gauss<HamiltonEquations<SpatialCr3bp>>,
    orbit: &PeriodicOrbit<Momenta>,
    xl: f64,
) -> Result<Vec<(f64, f64)>, BoxError> {
    let points = sample_orbit(stepper, &orbit.initial, (orbit.period, orbit.steps), 10)?;
    Ok(points.iter().map(|st| (st.q[0] - xl, st.q[2])).collect())
}

/// The smallest distance from the Moon over the steps of one period of `orbit` (in the unit distance).
fn perilune(
    stepper: &mut Gauss<HamiltonEquations<SpatialCr3bp>>,
    orbit: &PeriodicOrbit<Momenta>,
) -> Result<f64, BoxError> {
    let points = sample_orbit(stepper, &orbit.initial, (orbit.period, orbit.steps), 1)?;
    Ok(points
        .iter()
        .map(|st| {
            let (x, y, z) = (st.q[0] - 1.0 + MU, st.q[1], st.q[2]);
            (x * x + y * y + z * z).sqrt()
        })
        .fold(f64::INFINITY, f64::min))
}

/// What the halo families measure: over the long half, the largest energy drift, trivial-pair mean
/// offset and symplectic defect, and (C* − C)/z₀² of each member; the largest difference between the
/// short half and the long one mirrored.
struct Halos {
    /// max |H − E| along each orbit and |mean of the trivial pair − 1|, over the first `NEAR` members
    /// and over all.
    drift: (f64, f64),
    trivial: (f64, f64),
    symplectic: f64,
    mirror: f64,
    ratios: Vec<f64>,
}

/// The members nearest the branch point (out to z₀ ≈ 0.11, 41 000 km, far from the Moon), where 600
/// steps a period resolve the orbit well.
const NEAR: usize = 10;

fn measure(
    shooting: &mut HaloShooting,
    long: &Branch<Momenta>,
    short: &Branch<Momenta>,
    c_star: f64,
) -> Result<Halos, BoxError> {
    let model = SpatialCr3bp { mu: MU };
    let mut m = Halos {
        drift: (0.0, 0.0),
        trivial: (0.0, 0.0),
        symplectic: 0.0,
        mirror: 0.0,
        ratios: Vec::new(),
    };
    let worse =
        |(near, all): (f64, f64), x: f64, i: usize| (if i < NEAR { near.max(x) } else { near }, all.max(x));
    for (i, (h, orbit)) in long.members.iter().enumerate() {
        let run = (orbit.period, orbit.steps);
        let drift = energy_drift(&model, shooting.stepper_mut(), &orbit.nodes, run, *h)?;
        m.drift = worse(m.drift, drift, i);
        let mu = &orbit.floquet.multipliers;
        let mean = ((mu[0] + mu[1]) * 0.5 - Complex::new(1.0, 0.0)).norm();
        m.trivial = worse(m.trivial, mean, i);
        m.symplectic = m.symplectic.max(relative_symplectic_defect(&orbit.monodromy));
        m.ratios.push((c_star + 2.0 * h) / orbit.initial.q[2].powi(2));
    }
    for ((h, orbit), (h_mirror, mirror)) in long.members.iter().zip(&short.members) {
        m.mirror = m
            .mirror
            .max(mirror_defect(&orbit.initial, &mirror.initial))
            .max((h - h_mirror).abs());
    }
    Ok(m)
}

/// The stable band of the long half: the fold that opens it and the period doubling that closes it,
/// and what is measured there.
struct Band {
    /// C at the fold and at the period doubling.
    c_fold: f64,
    c_doubling: f64,
    /// Members between them, all of them marginal (linearly stable), and whether the members just
    /// outside are unstable.
    inside: usize,
    all_stable: bool,
    edges_unstable: bool,
    /// The fold is an extremum of C: (C − C_fold) of the members on either side have one sign.
    extremum: bool,
    /// |∏(1 − μ_i)| at the fold over its value at the neighbouring members (a pair at +1: ≈ 0).
    fold_product: f64,
    /// min |μ + 1| over the multipliers at the period doubling.
    doubling_gap: f64,
}

fn stable_band(long: &Branch<Momenta>) -> Result<Band, BoxError> {
    let fold = long
        .special
        .iter()
        .find(|p| p.kind == Bifurcation::Fold)
        .ok_or_else(|| {
            let c: Vec<String> = long
                .members
                .iter()
                .map(|(h, _)| format!("{:.5}", -2.0 * h))
                .collect();
            format!("no fold along the halo family (C: {})", c.join(", "))
        })?;
    let doubling = long.special[..]
        .iter()
        .find(|p| p.kind == Bifurcation::PeriodDoubling && p.after >= fold.after)
        .ok_or_else(|| {
            let c: Vec<String> = long
                .special
                .iter()
                .map(|p| format!("{:?} at {:.5} after {}", p.kind, -2.0 * p.level, p.after))
                .collect();
            format!(
                "no period doubling after the fold ({} members; {})",
                long.members.len(),
                c.join(", ")
            )
        })?;
    let members = &long.members;
    let (a, b) = (fold.after, doubling.after);
    if a == 0 || b >= members.len() || b <= a {
        return Err("the band is not inside the family followed".into());
    }
    let stable = |i: usize| members[i].1.floquet.stability == Stability::Marginal;
    let one = Complex::new(1.0, 0.0);
    let product = |o: &PeriodicOrbit<Momenta>| {
        o.floquet
            .nontrivial()
            .iter()
            .fold(one, |p, m| p * (one - m))
            .norm()
    };
    let level = -2.0 * fold.level;
    let side = |i: usize| (-2.0 * members[i].0 - level).signum();
    Ok(Band {
        c_fold: level,
        c_doubling: -2.0 * doubling.level,
        inside: b - a,
        all_stable: (a..b).all(stable),
        edges_unstable: !stable(a - 1) && !stable(b),
        extremum: side(a - 1) == side(a),
        fold_product: product(&fold.orbit) / product(&members[a - 1].1).max(product(&members[a].1)),
        doubling_gap: doubling
            .orbit
            .floquet
            .multipliers
            .iter()
            .map(|m| (m + one).norm())
            .fold(f64::INFINITY, f64::min),
    })
}

/// Runs the example: the Lyapunov family for 8 members from amplitude 0.001, then one half of the halo
/// family for `members` and the other for 6.
pub fn run_members(members: usize, opts: &Options) -> Result<Report, BoxError> {
    let (guess, period) = l1_spatial_guess(MU, 0.001);
    let e = Energy(SpatialCr3bp { mu: MU }).value(guess.q.as_slice(), guess.v.as_slice())?;
    let mut shooting = shooting(e)?;
    let start = shooting.solve(&guess, period)?;
    let lyapunov = Continuation::new(0.01, 1e-5, 0.05)?.follow(&mut shooting, &start, e, 8, true)?;
    let bp = lyapunov
        .special
        .iter()
        .find(|p| p.kind == Bifurcation::BranchPoint)
        .ok_or("no branch point along the Lyapunov family")?;
    let c_star = -2.0 * bp.level;
    let m = &bp.orbit.monodromy;
    let vertical = m[(2, 2)] + m[(5, 5)];
    let halo = Continuation::new(0.01, 1e-5, 0.1)?;
    let long = halo.switch(&mut shooting, bp, members, true)?;
    let short = halo.switch(&mut shooting, bp, 6, false)?;
    if let Some(lost) = &long.lost {
        return Err(format!("the halo family was lost: {lost}").into());
    }
    let halos = measure(&mut shooting, &long, &short, c_star)?;
    let band = stable_band(&long)?;
    let (c_end, last) = long.members.last().ok_or("no halo found")?;
    let closure = flow_closure(SpatialCr3bp { mu: MU }, &last.initial, last.period, 1e-13)?;
    let nearest = perilune(shooting.stepper_mut(), last)?;
    let km = |x: f64| x.abs() * 384_400.0;

    let mut report = Report::default();
    report.note(format!(
        "Lyapunov family C {:.5} → {:.5}, special points {:?}; branch point at C* = {c_star:.8}, T = {:.7}",
        -2.0 * e,
        -2.0 * lyapunov.members.last().map_or(e, |(h, _)| *h),
        lyapunov.special.iter().map(|p| p.kind).collect::<Vec<_>>(),
        bp.orbit.period,
    ));
    report.note(format!(
        "halo family ({}) to C = {:.5}, z₀ = {:.4} ({:.0} km), T = {:.5}, perilune {:.0} km from the \
         Moon's centre; special points {:?}",
        if last.initial.q[2] > 0.0 { "north" } else { "south" },
        -2.0 * c_end,
        last.initial.q[2],
        km(last.initial.q[2]),
        last.period,
        km(nearest),
        long.special
            .iter()
            .map(|p| (p.kind, -2.0 * p.level))
            .collect::<Vec<_>>()
    ));
    report.note(format!(
        "stable band from the fold at C = {:.8} to the period doubling at C = {:.8}: {} members",
        band.c_fold, band.c_doubling, band.inside
    ));
    report.note(format!("(C* − C)/z₀², first members: {:.4?}", &halos.ratios[..3]));
    let yes = |b: bool| f64::from(u8::from(b));
    report.checks = vec![
        // The located point: one special point, a branch point; the vertical block's trace is 2
        // there to the location's width 1e-9 in arclength times the trace's slope (~3): measured
        // 5.3e-15; tolerance 1e-8.
        Check::abs(
            NAME,
            "special points along the Lyapunov family",
            lyapunov.special.len() as f64,
            1.0,
            0.5,
        ),
        Check::abs(NAME, "vertical trace at the branch point", vertical, 2.0, 1e-8),
        // The literature's four decimals: half a unit of the last, 5e-5 (measured 4.7e-5).
        Check::abs(
            NAME,
            "C at the branch point (published 3.1743)",
            c_star,
            PUBLISHED_C,
            5e-5,
        ),
        // A pitchfork: (C* − C)/z₀² settles to κ as z₀ → 0; over the first three members (z₀ up to
        // 0.012) it changes by 0.34 % (measured); tolerance 1 %.
        Check::rel(
            NAME,
            "(C* − C)/z₀², third member against first",
            halos.ratios[2],
            halos.ratios[0],
            0.01,
        ),
        // Mirror images to rounding accumulated through Newton: measured 4.9e-15.
        Check::abs(
            NAME,
            "other half − mirrored first half (states, levels)",
            halos.mirror,
            0.0,
            2e-14,
        ),
        // The band: every member inside stable, those at its edges unstable; the fold an extremum.
        Check::abs(
            NAME,
            "members in the stable band all stable",
            yes(band.all_stable && band.inside > 0),
            1.0,
            0.5,
        ),
        Check::abs(
            NAME,
            "members at the band's edges unstable",
            yes(band.edges_unstable),
            1.0,
            0.5,
        ),
        Check::abs(NAME, "the fold an extremum of C", yes(band.extremum), 1.0, 0.5),
        // At the fold a pair sits at +1: ∏(1 − μ) falls to a small fraction of its value at the
        // neighbouring members (measured 3.9e-5); tolerance 1e-3.
        Check::abs(
            NAME,
            "|∏(1 − μ)| at the fold / at its neighbours",
            band.fold_product,
            0.0,
            1e-3,
        ),
        // At the period doubling a multiplier sits at −1 (measured 2.6e-7); tolerance 1e-6.
        Check::abs(
            NAME,
            "min |μ + 1| at the period doubling",
            band.doubling_gap,
            0.0,
            1e-6,
        ),
        // Gauss-Legendre 6 at h ≈ T/600: the energy error is O(h⁶) and bounded. Near the branch point
        // measured 1.3e-13 (tolerance 1e-12); over the whole family 2.2e-10: the last members pass a few
        // thousand km from the Moon's surface (the note gives the perilune), where the orbit's time
        // scale is far shorter than at L1 and uniform steps resolve it worst (tolerance 1e-9).
        Check::abs(
            NAME,
            format!("max |H − E| along each of the first {NEAR} halos"),
            halos.drift.0,
            0.0,
            1e-12,
        ),
        Check::abs(NAME, "max |H − E| along each halo", halos.drift.1, 0.0, 1e-9),
        // A Jordan block at 1: the two trivial multipliers split by the square root of the error
        // (up to 5.7e-7), their mean stays at 1: measured 1.6e-13 near the branch point, 7.2e-10
        // over the family (the same loss of resolution near the Moon).
        Check::abs(
            NAME,
            format!("mean of the trivial pair − 1, first {NEAR}"),
            halos.trivial.0,
            0.0,
            1e-12,
        ),
        Check::abs(NAME, "mean of the trivial pair − 1", halos.trivial.1, 0.0, 3e-9),
        // Gauss is symplectic: MᵀJM = J to rounding and the collocation's Newton tolerance, relative
        // to ‖M‖²: measured 1.9e-15.
        Check::abs(
            NAME,
            "symplectic defect of the monodromies",
            halos.symplectic,
            0.0,
            1e-14,
        ),
        // The map's orbit is the flow's to Gauss-Legendre 6's O(h⁶) error, amplified along the orbit
        // (the last member is the nearest the Moon): measured 6.5e-10.
        Check::abs(
            NAME,
            "last halo, once round by DOP853: |y(T) − y₀|",
            closure,
            0.0,
            3e-9,
        ),
    ];
    if opts.out_dir.is_some() {
        let (xl, _) = l1(MU);
        let mut fig = Figure::new("Earth-Moon L1: the Lyapunov orbit at the branch point and halo orbits")
            .x_label("x − x_L1")
            .y_label("z");
        fig = fig.series(
            format!("Lyapunov at the branch point, C = {c_star:.5}"),
            projection(shooting.stepper_mut(), &bp.orbit, xl)?,
        );
        let shown = long.members.iter().step_by(4).chain(short.members.last());
        for (h, orbit) in shown {
            let pts = projection(shooting.stepper_mut(), orbit, xl)?;
            fig = fig.series(format!("halo, C = {:.4}", -2.0 * h), pts);
        }
        report.save(opts, &fig, "halo_orbits.svg")?;
    }
    Ok(report)
}

/// Runs the example (40 halo members one way, past the stable band).
pub fn run(opts: &Options) -> Result<Report, BoxError> {
    run_members(40, opts)
}

fn main() -> ExitCode {
    noether_gallery::example_main(NAME, run)
}
