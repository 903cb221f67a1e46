//! Families of periodic orbits through their bifurcations: the cascade of the Hénon-Heiles y-axis
//! orbit against its published energies, and the halo orbits of the Earth-Moon restricted problem
//! switched onto from the planar Lyapunov family about L1.

use nalgebra::Complex;
use noether_analysis::periodic::{Energy, FirstIntegral, Shooting};
use noether_analysis::{Bifurcation, Continuation, Error};
use noether_core::integrators::Gauss;
use noether_core::prelude::*;
use noether_testkit::canonical::relative_symplectic_defect;
use noether_testkit::henon_heiles::HenonHeiles;
use noether_testkit::three_body::{
    energy_drift, flow_closure, l1_spatial_guess, mirror_defect, SpatialCr3bp,
};

/// Earth-Moon mass ratio of the tests (the 0.01215 of Doedel et al. 2007).
const MU: f64 = 0.01215;

/// The shooting of the halo tests: Gauss-Legendre of order 6 (symplectic), 600 steps a period in 6
/// arcs, the energy held at `e`.
fn halo_shooting(e: f64) -> Shooting<Gauss<HamiltonEquations<SpatialCr3bp>>> {
    let model = SpatialCr3bp { mu: MU };
    Shooting::new(Gauss::gauss6(HamiltonEquations::new(model)), 600)
        .unwrap()
        .segments(6)
        .unwrap()
        .level(Energy(model), e)
}

/// Hénon-Heiles, H = ½(p_x² + p_y² + x² + y²) + x²y − y³/3: the straight-line orbit along the y axis
/// (x = p_x = 0, ÿ = −y + y²) continued in its energy from E = 0.02 towards the escape energy 1/6,
/// 40 members. Its transverse motion obeys Hill's equation ẍ = −(1 + 2y(t)) x, whose monodromy is the
/// x-block of M; the orbit turns alternately unstable and stable in a cascade accumulating at 1/6,
/// where that block's trace passes −2 (period doubling) and +2 (an isochronous pitchfork: a branch
/// point). Published (M. Brack, *Found. Phys.* 31 (2001) 209, Table 1; Brack, Mehta & Tanaka,
/// *J. Phys. A* 34 (2001) 8199): e = 6E = 0.811715, 0.915215, 0.969309 for the first three.
/// Measured: the kinds in that order at 6E = 0.811715516, 0.915214413, 0.969309091 (the same nine
/// digits with 800 steps instead of 400: the method's error is below 5e-10), the trace at each ±2 to
/// 8e-12; 2.6 s. Checked: the kinds, each energy to 1.5e-6 of the published six digits (they differ by
/// 5e-7, 6e-7 and 9e-8: the rounding of the last published digit, a little more for the second),
/// the trace to 1e-9 (the location's width 1e-9 in arclength times the trace's slope along the
/// family, ~1).
#[test]
fn henon_heiles_y_axis_cascade() {
    let e = 0.02;
    let mut shooting = Shooting::new(Gauss::gauss6(HamiltonEquations::new(HenonHeiles)), 400)
        .unwrap()
        .segments(4)
        .unwrap()
        .level(Energy(HenonHeiles), e);
    let guess = State::with_momenta(0.0, [0.0, 0.0], [0.0, (2.0 * e).sqrt()]);
    let start = shooting.solve(&guess, 2.0 * std::f64::consts::PI).unwrap();
    let continuation = Continuation::new(0.02, 1e-6, 0.1).unwrap();
    let branch = continuation.follow(&mut shooting, &start, e, 40, true).unwrap();
    let published = [
        (Bifurcation::PeriodDoubling, 0.811715, -2.0),
        (Bifurcation::PeriodDoubling, 0.915215, -2.0),
        (Bifurcation::BranchPoint, 0.969309, 2.0),
    ];
    assert_eq!(
        branch.special.len(),
        published.len(),
        "{:?}",
        branch.special.iter().map(|p| p.kind).collect::<Vec<_>>()
    );
    for (point, (kind, scaled, trace)) in branch.special.iter().zip(published) {
        let m = &point.orbit.monodromy;
        let x_trace = m[(0, 0)] + m[(2, 2)];
        println!(
            "{:?} at 6E = {:.9} (published {scaled}), T = {:.9}, x-block trace − ({trace:+}) {:.1e}, after member {}",
            point.kind,
            6.0 * point.level,
            point.orbit.period,
            x_trace - trace,
            point.after
        );
        assert_eq!(point.kind, kind);
        assert!((6.0 * point.level - scaled).abs() < 1.5e-6);
        assert!((x_trace - trace).abs() < 1e-9);
        // The orbit stays on the y axis.
        assert!(point.orbit.initial.q[0].abs() < 1e-12 && point.orbit.initial.v[0].abs() < 1e-12);
    }
    // Switching is for branch points only.
    assert!(matches!(
        continuation.switch(&mut shooting, &branch.special[0], 3, true),
        Err(Error::Core(noether_core::Error::InvalidParameter { .. }))
    ));
}

/// The Earth-Moon L1 Lyapunov family in the spatial problem, from the orbit of amplitude 0.001, and
/// its branch point where the halo family bifurcates, followed both ways (north and south) for 10
/// members each. Along the planar family the vertical pair of multipliers e^{±iθ} closes on +1 and
/// turns real; there ∏(1 − μ_i) changes sign and the branch point is located. Measured: one special
/// point in 8 members (C 3.1883 → 3.1378), a branch point at C = 3.1743470, T = 2.7429993 (the
/// literature's 3.1743 for the L1 halo bifurcation of the Earth-Moon system, e.g. Doedel et al.,
/// *Int. J. Bifurcation Chaos* 17 (2007) 2625, at this μ), where the vertical block of M (z, p_z: the
/// vertical variational equation of a planar orbit decouples) has trace 2 to 5e-15. The halo members:
/// C falls from 3.17429 to 3.1368 while z₀ grows to 0.070 (27 000 km); (C* − C)/z₀² = 8.615, 8.608,
/// 8.586 over the first three (a pitchfork: C* − C = κz₀² + O(z₀⁴)); the southern family is the
/// northern one mirrored (z, p_z) ↦ (−z, −p_z) to 7e-16; H conserved along every orbit to 1.3e-13
/// (Gauss-Legendre 6, h ≈ 0.0046); the trivial pair of multipliers averages to 1 within 1.6e-13 (a
/// Jordan block: each splits from 1 by the square root of the rounding, measured up to 5.7e-7);
/// MᵀJM = J to 2.4e-17 of ‖M‖² (Gauss is symplectic); the last member, stepped once round by DOP853 at
/// tolerance 1e-13 from its first node, closes to 1.3e-11 (the flow's orbit, not only the map's); 4 s.
/// Checked to 2–10× these.
#[test]
fn halo_family_from_the_lyapunov_family() {
    let (guess, t_guess) = l1_spatial_guess(MU, 0.001);
    let model = SpatialCr3bp { mu: MU };
    let e = Energy(model)
        .value(guess.q.as_slice(), guess.v.as_slice())
        .unwrap();
    let mut shooting = halo_shooting(e);
    let start = shooting.solve(&guess, t_guess).unwrap();
    let continuation = Continuation::new(0.01, 1e-5, 0.05).unwrap();
    let lyapunov = continuation.follow(&mut shooting, &start, e, 8, true).unwrap();
    assert_eq!(lyapunov.special.len(), 1);
    let bp = &lyapunov.special[0];
    let m = &bp.orbit.monodromy;
    let vertical = m[(2, 2)] + m[(5, 5)];
    println!(
        "branch point at C = {:.10}, T = {:.10}, vertical trace − 2 = {:.1e}, after member {}",
        -2.0 * bp.level,
        bp.orbit.period,
        vertical - 2.0,
        bp.after
    );
    assert_eq!(bp.kind, Bifurcation::BranchPoint);
    assert!((-2.0 * bp.level - 3.1743).abs() < 1e-4);
    // The location's width 1e-9 in arclength times the trace's slope along the family (~3).
    assert!((vertical - 2.0).abs() < 1e-8);

    let north = continuation.switch(&mut shooting, bp, 10, true).unwrap();
    let south = continuation.switch(&mut shooting, bp, 10, false).unwrap();
    let (mut drift, mut mean, mut symplectic, mut mirror) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    let mut ratios = Vec::new();
    let mut last = (-2.0 * bp.level, 0.0);
    for ((h, orbit), (h_south, south)) in north.members.iter().zip(&south.members) {
        let (c, z0) = (-2.0 * h, orbit.initial.q[2]);
        let run = (orbit.period, orbit.steps);
        drift = drift.max(energy_drift(&model, shooting.stepper_mut(), &orbit.nodes, run, *h).unwrap());
        let fl = &orbit.floquet;
        mean = mean.max(((fl.multipliers[0] + fl.multipliers[1]) * 0.5 - Complex::new(1.0, 0.0)).norm());
        symplectic = symplectic.max(relative_symplectic_defect(&orbit.monodromy));
        mirror = mirror
            .max(mirror_defect(&orbit.initial, &south.initial))
            .max((h - h_south).abs());
        ratios.push((-2.0 * bp.level - c) / (z0 * z0));
        assert!(c < last.0 && z0.abs() > last.1, "C {c} after {}, z₀ {z0}", last.0);
        last = (c, z0.abs());
    }
    let end = &north.members.last().unwrap().1;
    let closure = flow_closure(model, &end.initial, end.period, 1e-13).unwrap();
    println!(
        "halo to C = {:.6}, z₀ = {:.4}: (C* − C)/z₀² {:.4?}, H drift {drift:.1e}, trivial mean {mean:.1e}, \
         symplectic {symplectic:.1e}, mirror {mirror:.1e}, closure by DOP853 {closure:.1e}",
        last.0,
        last.1,
        &ratios[..3]
    );
    assert!(last.1 > 0.06);
    assert!((ratios[2] / ratios[0] - 1.0).abs() < 0.01);
    assert!(drift < 1e-12 && mean < 1e-12 && symplectic < 1e-16);
    assert!(mirror < 2e-14);
    assert!(closure < 1e-10);
}
