//! A coin built from a rolling joint against the hand-written coin with its rolling constraints
//! (`noether_testkit::coin`).

use noether_constraints::{Constrained, Nonholonomic};
use noether_core::prelude::*;
use noether_multibody::{Body, Joint, Mechanism, Parent, Placement};
use noether_testkit::agreement::{relative, uniform};
use noether_testkit::coin::Coin;
use noether_testkit::multibody::rolling_coin;

/// The rolling joint's L and no-slip constraints are the hand-written coin's (`Coin`, whose L and
/// constraints are written out in its module docs), and so are the motions with multipliers: at 50
/// random rolling states (tilt up to 1.2 rad) L, M, the constraint rows and the accelerations of
/// Lagrange-d'Alembert agree to rounding (measured ≤ 2.0e-15, 4.3e-17, 5.6e-16 and 3.8e-15
/// relative, the last through two solves with multipliers; tolerance 1e-13).
#[test]
fn coin_from_a_rolling_joint_is_the_hand_written_coin() {
    let coin = Coin::uniform(0.5, 1.3, 9.81);
    let built = rolling_coin(&coin);
    let contacts = built.rolling_contacts().unwrap();
    assert_eq!((contacts.dof(), contacts.count()), (5, 2));
    let (el_built, el_hand) = (EulerLagrange::new(&built), EulerLagrange::new(coin));
    let with_built = Constrained::nonholonomic(&built, contacts.clone()).unwrap();
    let with_hand = Constrained::nonholonomic(coin, coin.rolling()).unwrap();
    let mut draw = uniform(17);
    let mut worst = [0.0_f64; 4];
    for _ in 0..50 {
        let (q, v) = coin.random_rolling_state(&mut draw);
        let l = relative(&[built.lagrangian(0.0, &q, &v)], &[coin.lagrangian(0.0, &q, &v)]);
        let m = relative(
            el_built.mass_matrix(0.0, &q, &v).unwrap().as_slice(),
            el_hand.mass_matrix(0.0, &q, &v).unwrap().as_slice(),
        );
        // Off the constraint (v perturbed) the rows must agree too.
        let off: Vec<f64> = v.iter().map(|x| x + draw(-1.0, 1.0)).collect();
        let (mut gb, mut gh) = ([0.0; 2], [0.0; 2]);
        contacts.constraints(0.0, &q, &off, &mut gb);
        coin.rolling().constraints(0.0, &q, &off, &mut gh);
        let g = relative(&gb, &gh);
        let (mut ab, mut ah, mut lambda) = ([0.0; 5], [0.0; 5], [0.0; 2]);
        with_built.solve(0.0, &q, &v, &mut ab, &mut lambda).unwrap();
        with_hand.solve(0.0, &q, &v, &mut ah, &mut lambda).unwrap();
        for (w, e) in worst.iter_mut().zip([l, m, g, relative(&ab, &ah)]) {
            *w = w.max(e);
        }
    }
    println!(
        "coin from a rolling joint: L {:e}, M {:e}, constraints {:e}, q̈ {:e}",
        worst[0], worst[1], worst[2], worst[3]
    );
    assert!(worst.iter().all(|e| *e < 1e-13), "{worst:?}");
}

/// A radius no disk has, and rolling contacts of a mechanism without rolling joints, are errors.
#[test]
fn bad_rolling_joints_are_typed_errors() {
    let mut m = Mechanism::new();
    for radius in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let bad = m.attach(
            Parent::Ground,
            Placement::identity(),
            Joint::rolling(radius),
            Body::point(1.0, [0.0; 3]),
        );
        assert!(bad.is_err(), "radius {radius}");
    }
    assert_eq!(m.bodies(), 0);
    m.attach(
        Parent::Ground,
        Placement::identity(),
        Joint::revolute([0.0, 0.0, 1.0]),
        Body::point(1.0, [1.0, 0.0, 0.0]),
    )
    .unwrap();
    assert!(m.rolling_contacts().is_err());
}

/// The Gibbs-Appell form built from the rolling joint (quasi-velocities (ψ̇, θ̇, φ̇), the centre's
/// velocity from the no-slip condition, no multipliers) moves as Lagrange-d'Alembert with
/// multipliers does: at 50 random rolling states u̇ = (ψ̈, θ̈, φ̈) agrees with the multiplier model's
/// (measured ≤ 5.3e-15 relative; tolerance 1e-13: two different linear systems, the Gibbs-Appell one
/// 3 × 3, the saddle point 7 × 7), and q̇ = W u gives back the rolling velocities exactly.
#[test]
fn gibbs_appell_form_of_the_rolling_coin_is_lagrange_dalembert() {
    use noether_constraints::GibbsAppellEquations;
    let coin = Coin::uniform(0.5, 1.3, 9.81);
    let built = rolling_coin(&coin);
    let appell = built.gibbs_appell().unwrap();
    let equations = GibbsAppellEquations::new(appell.clone()).unwrap();
    assert_eq!(equations.quasi(), 3);
    let multipliers = Constrained::nonholonomic(coin, coin.rolling()).unwrap();
    let mut draw = uniform(23);
    let mut worst = 0.0_f64;
    for _ in 0..50 {
        let (q, v) = coin.random_rolling_state(&mut draw);
        let u = appell.quasi_velocities(&v).unwrap();
        let mut qdot = [0.0; 5];
        equations.coordinate_rates(0.0, &q, &u, &mut qdot).unwrap();
        assert!(relative(&qdot, &v) < 1e-15, "{qdot:?} {v:?}");
        let mut udot = [0.0; 3];
        equations.accelerations(0.0, &q, &u, &mut udot).unwrap();
        let (mut a, mut lambda) = ([0.0; 5], [0.0; 2]);
        multipliers.solve(0.0, &q, &v, &mut a, &mut lambda).unwrap();
        worst = worst.max(relative(&udot, &a[2..]));
    }
    println!("Gibbs-Appell form vs multipliers: {worst:e}");
    assert!(worst < 1e-13, "{worst:e}");
    assert!(Mechanism::new().gibbs_appell().is_err());
}
