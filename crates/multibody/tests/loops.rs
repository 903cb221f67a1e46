//! Closed loops: a slider-crank and a four-bar linkage built from bodies, joints and a loop closure,
//! against the closed forms of their kinematics and statics.

use noether_testkit::multibody::{FourBar, SliderCrank};

/// The slider-crank reduced to its crank angle θ (`SliderCrank::reduced_near`: the rod angle and the
/// piston solved from the loop closure by Newton in dual arithmetic):
/// - the piston is at x(θ) = r cos θ + √(l² − r² sin²θ) and moves at ẋ = (dx/dθ) θ̇ (measured 0
///   and 2e-15 relative — the speed relative to ẋ, small near the dead centres —; tolerance 1e-14);
/// - the crank torque u = k (x − x₀) dx/dθ (virtual work against the piston's spring) holds it at
///   rest: the accelerations under that torque vanish to rounding (measured ≤ 7e-16 of those under no
///   torque; tolerance 1e-13).
#[test]
fn slider_crank_piston_and_crank_torque_closed_forms() {
    let sc = SliderCrank::default();
    let (mut place, mut speed, mut held) = (0.0_f64, 0.0_f64, 0.0_f64);
    for theta in [0.4, 1.0, 2.2, 3.0, -0.7, -2.4] {
        let (q, v) = sc.reduced_near(theta).unwrap().state(0.0, &[theta], &[0.7]);
        place = place.max((q[2] - sc.piston(theta)).abs() / sc.piston(theta));
        let rate = sc.piston_rate(theta) * 0.7;
        speed = speed.max((v[2] - rate).abs() / rate.abs());
        let holding = sc.crank_acceleration(theta, sc.holding_torque(theta)).unwrap();
        held = held.max(holding.abs() / sc.crank_acceleration(theta, 0.0).unwrap().abs());
    }
    println!("slider-crank: piston {place:e}, its speed {speed:e}, held by the closed-form torque {held:e}");
    assert!(place < 1e-14 && speed < 1e-14, "{place:e} {speed:e}");
    assert!(held < 1e-13, "{held:e}");
}

/// The four-bar (ground 1, crank 0.3, coupler 1.1, rocker 0.7: Grashof, s + ℓ = 1.4 ≤ p + q = 1.7,
/// with the crank the shortest link, so a crank-rocker) set spinning at θ̇ = 6 without gravity and
/// stepped by RATTLE (midpoint rule, h = 10⁻³) for 10⁵ steps (`FourBar::spin`), about 90 turns of the
/// crank:
/// - the loop stays closed: max |φ| ≤ 1e-12 (RATTLE solves the closure at every step by Newton;
///   measured 1.2e-13);
/// - the energy has no drift: RATTLE is symplectic, its error O(h²) and bounded, of the size
///   (θ̇ h)² = 3.6e-5 (measured 3.5e-5 relative over the whole run; tolerance 1e-4);
/// - the crank turns fully and the rocker swings between the toggle angles ψ = π − γ with
///   cos γ = (d² + c² − e²)/(2dc), e = b ± a (`FourBar::rocker_limits`): ψ never passes them (every
///   state is on the loop; tolerance 1e-12) and its sampled extremes come within a step's reach,
///   ½|ψ_θθ|(θ̇h/2)² ≈ 5e-6 (measured 4e-10 over 90 turns; tolerance 1e-5).
#[test]
fn four_bar_crank_rocker_keeps_its_loop_and_energy() {
    let fb = FourBar::default();
    assert!(fb.grashof());
    let run = fb.spin(6.0, 1e-3, 100_000).unwrap();
    let (psi_min, psi_max) = fb.rocker_limits();
    let outside = (psi_min - run.rocker.0).max(run.rocker.1 - psi_max);
    let limits = (run.rocker.0 - psi_min).abs().max((run.rocker.1 - psi_max).abs());
    println!(
        "four-bar: {:.1} turns, closure {:e}, energy {:e}, rocker limits {limits:e}",
        run.turns, run.closure, run.energy
    );
    assert!(run.turns > 50.0, "{}", run.turns);
    assert!(run.closure < 1e-12, "{:e}", run.closure);
    assert!(run.energy < 1e-4, "{:e}", run.energy);
    assert!(outside < 1e-12 && limits < 1e-5, "{outside:e} {limits:e}");
}

/// A loop closed wrongly is named: the four-bar closed along z as well (its third component vanishes
/// for every planar configuration) is redundant at closure 0, direction 2; a configuration off the
/// loop is refused; the right closure passes.
#[test]
fn redundant_and_violated_closures_are_typed_errors() {
    use noether_multibody::{Body, Error, Joint, Mechanism, Parent, Placement};
    let fb = FourBar::default();
    let q = fb.configuration(0.7);
    assert!(fb.mechanism().check_loops(&q).is_ok());
    let [d, a, b, c] = fb.lengths;
    let z = [0.0, 0.0, 1.0];
    let rod = |l: f64| Body::rod(1.0, [0.0; 3], [l, 0.0, 0.0]);
    let mut m = Mechanism::new();
    let crank = m
        .attach(Parent::Ground, Placement::identity(), Joint::revolute(z), rod(a))
        .unwrap();
    let coupler = m
        .attach(crank, Placement::at([a, 0.0, 0.0]), Joint::revolute(z), rod(b))
        .unwrap();
    let rocker = m
        .attach(
            Parent::Ground,
            Placement::at([d, 0.0, 0.0]),
            Joint::revolute(z),
            rod(c),
        )
        .unwrap();
    m.close_loop(
        (coupler.into(), [b, 0.0, 0.0]),
        (rocker.into(), [c, 0.0, 0.0]),
        &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    )
    .unwrap();
    let redundant = m.check_loops(&q);
    assert!(
        matches!(
            redundant,
            Err(Error::RedundantClosure {
                closure: 0,
                direction: 2,
                rank: 2
            })
        ),
        "{redundant:?}"
    );
    let off = fb.mechanism().check_loops(&[q[0] + 0.1, q[1], q[2]]);
    assert!(matches!(off, Err(Error::Core(_))), "{off:?}");
    // A body closed to itself, or the ground to the ground, closes no loop.
    let x = [[1.0, 0.0, 0.0]];
    let itself = m.close_loop((crank.into(), [0.0; 3]), (crank.into(), [0.1, 0.0, 0.0]), &x);
    assert!(
        matches!(itself, Err(Error::NotALoop { closure: 1 })),
        "{itself:?}"
    );
    assert!(matches!(
        m.close_loop((Parent::Ground, [0.0; 3]), (Parent::Ground, [1.0, 0.0, 0.0]), &x),
        Err(Error::NotALoop { .. })
    ));
    assert!(m
        .close_loop((crank.into(), [0.0; 3]), (Parent::Ground, [0.0; 3]), &[])
        .is_err());
    assert!(m
        .close_loop((crank.into(), [0.0; 3]), (Parent::Ground, [0.0; 3]), &[[0.0; 3]])
        .is_err());
}

/// The reaction at a cut joint from the multipliers: a uniform rod (m = 2, l = 1.5) hinged at the
/// origin about z and lying along x, its tip held on a ground roller that lets it slide only
/// perpendicular to d = (sin β, cos β, 0) (a loop closed along d), gravity g along −y. At rest the
/// moments about the hinge balance, l F_y = m g l/2, and the roller pushes only along d, so
/// F = m g/(2 cos β) d: F_y = m g/2 (each support carries half, the textbook simply supported
/// beam) and F_x = (m g/2) tan β. Measured exact in these numbers (tolerance 1e-14, rounding) for
/// β = 0 and 0.3; the rod does not move (q̈ = 0 to rounding). λ of the wrong length is an error.
#[test]
fn reaction_at_a_cut_joint_is_the_textbook_support_force() {
    use noether_constraints::Constrained;
    use noether_core::prelude::*;
    use noether_multibody::{Body, Joint, Mechanism, Parent, Placement};
    let (m, l, g) = (2.0, 1.5, 9.81);
    for beta in [0.0_f64, 0.3] {
        let mut rod = Mechanism::new().gravity([0.0, -g, 0.0]).unwrap();
        let link = rod
            .attach(
                Parent::Ground,
                Placement::identity(),
                Joint::revolute([0.0, 0.0, 1.0]),
                Body::rod(m, [0.0; 3], [l, 0.0, 0.0]),
            )
            .unwrap();
        let d = [beta.sin(), beta.cos(), 0.0];
        rod.close_loop(
            (link.into(), [l, 0.0, 0.0]),
            (Parent::Ground, [l, 0.0, 0.0]),
            &[d],
        )
        .unwrap();
        let held = Constrained::holonomic(rod.clone(), rod.loop_closures()).unwrap();
        let lambda = held.multipliers(0.0, &[0.0], &[0.0]).unwrap();
        let force = rod.closure_forces(lambda.as_slice()).unwrap();
        let expected = d.map(|di| m * g / (2.0 * beta.cos()) * di);
        let error = (0..3)
            .map(|i| (force[0][i] - expected[i]).abs())
            .fold(0.0, f64::max)
            / (m * g);
        let mut a = [0.0];
        held.rates(0.0, &[0.0], &[0.0], &mut [0.0], &mut a).unwrap();
        println!(
            "roller at β = {beta}: F = {:?}, error {error:e}, q̈ {:e}",
            force[0], a[0]
        );
        assert!(error < 1e-14 && a[0].abs() < 1e-14, "{error:e} {}", a[0]);
        assert!(rod.closure_forces(&[]).is_err());
    }
}
