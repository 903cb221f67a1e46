//! Compiled natural systems (q̈ = −M⁻¹∇V) and the compiled Jacobians of Hamilton's equations against
//! the dual-number systems they come from and against closed forms; the integrators that take them
//! by default; guards and the error contract.

use nalgebra::DMatrix;
use noether_compile::{Compile, CompiledNatural};
use noether_core::integrators::DefaultMethod;
use noether_core::system::LinearizedDynamics;
use noether_core::{Dynamics, HamiltonEquations, Natural, Potential, Scalar, State, Stepper};
use noether_testkit::agreement::{relative, uniform};
use noether_testkit::henon_heiles::{HenonHeiles, UnitDoublePendulum};
use noether_testkit::kepler::Kepler;

/// The agreement bound: the compiled gradient and the dual-number gradient round in a different
/// order, so they agree to a few ulps of the largest term: measured (printed below) 8.9e-16 relative
/// for q̈ (1.1e-15 against the closed forms, whose own rounding differs), 8.1e-16 for the Jacobians of
/// natural systems and 2.7e-16 for Hamilton's; 1e-14 is issue 32's bound.
const AGREE: f64 = 1e-14;

/// Hénon-Heiles and Kepler (unit mass, a diagonal mass and a dense one): q̈ against the dual-number
/// `Natural` and against the closed forms q̈ = (−x − 2xy, −y − x² + y²) (V = ½(x² + y²) + x²y − y³/3)
/// and q̈ = −M⁻¹ q/|q|³ (V = −1/|q|), at 200 random points each.
#[test]
fn accelerations_agree_with_dual_numbers_and_closed_forms() {
    let mut rnd = uniform(3);
    let hh = Natural::unit(HenonHeiles).compile().unwrap();
    let hh_dual = Natural::unit(HenonHeiles);
    let masses = [1.7, 0.6];
    let kepler = Natural::diagonal(Kepler, &masses).unwrap().compile().unwrap();
    let kepler_dual = Natural::diagonal(Kepler, &masses).unwrap();
    let m = DMatrix::from_row_slice(2, 2, &[2.0, 0.5, 0.5, 1.0]);
    let dense = Natural::dense(Kepler, m.clone()).unwrap().compile().unwrap();
    let dense_dual = Natural::dense(Kepler, m.clone()).unwrap();
    let minv = m.try_inverse().unwrap();
    let (mut worst_dual, mut worst_closed) = (0.0_f64, 0.0_f64);
    for _ in 0..200 {
        let q = [rnd(-1.0, 1.0), rnd(-1.0, 1.0)];
        let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
        hh.accelerations(&q, &mut a).unwrap();
        hh_dual.accelerations(&q, &mut b).unwrap();
        let closed = [-q[0] - 2.0 * q[0] * q[1], -q[1] - q[0] * q[0] + q[1] * q[1]];
        worst_dual = worst_dual.max(relative(&a, &b));
        worst_closed = worst_closed.max(relative(&a, &closed));
        let r3 = (q[0] * q[0] + q[1] * q[1]).powf(1.5);
        kepler.accelerations(&q, &mut a).unwrap();
        kepler_dual.accelerations(&q, &mut b).unwrap();
        let closed = [-q[0] / r3 / masses[0], -q[1] / r3 / masses[1]];
        worst_dual = worst_dual.max(relative(&a, &b));
        worst_closed = worst_closed.max(relative(&a, &closed));
        dense.accelerations(&q, &mut a).unwrap();
        dense_dual.accelerations(&q, &mut b).unwrap();
        let f = nalgebra::Vector2::new(-q[0] / r3, -q[1] / r3);
        let closed = &minv * f;
        worst_dual = worst_dual.max(relative(&a, &b));
        worst_closed = worst_closed.max(relative(&a, closed.as_slice()));
    }
    println!("q̈: {worst_dual:e} from dual numbers, {worst_closed:e} from the closed forms");
    assert!(worst_dual <= AGREE && worst_closed <= AGREE);
    // The energy ½ q̇ᵀ M q̇ + V, against the dual-number system's.
    let (q, v) = ([0.3, -0.2], [0.1, 0.4]);
    let (e, f) = (dense.energy(&q, &v).unwrap(), dense_dual.energy(&q, &v).unwrap());
    assert!((e - f).abs() <= AGREE * f.abs());
}

/// J = [[0, I], [−M⁻¹∇²V, 0]] from the compiled Hessian against the dual-number one (Kepler, dense
/// M; Hénon-Heiles), and ∇²V of Hénon-Heiles against its closed form [[1 + 2y, 2x], [2x, 1 − 2y]].
#[test]
fn jacobians_of_natural_systems_agree() {
    let mut rnd = uniform(5);
    let m = DMatrix::from_row_slice(2, 2, &[2.0, 0.5, 0.5, 1.0]);
    let kepler = Natural::dense(Kepler, m.clone()).unwrap();
    let compiled = Natural::dense(Kepler, m).unwrap().compile().unwrap();
    let hh = Natural::unit(HenonHeiles).compile().unwrap();
    let (mut a, mut b) = (DMatrix::zeros(4, 4), DMatrix::zeros(4, 4));
    let mut worst = 0.0_f64;
    for _ in 0..100 {
        let (q, v) = ([rnd(0.3, 1.0), rnd(-1.0, 1.0)], [rnd(-1.0, 1.0), rnd(-1.0, 1.0)]);
        compiled.jacobian(0.0, &q, &v, &mut a).unwrap();
        kepler.jacobian(0.0, &q, &v, &mut b).unwrap();
        worst = worst.max((&a - &b).amax() / b.amax());
        hh.jacobian(0.0, &q, &v, &mut a).unwrap();
        let (x, y) = (q[0], q[1]);
        let closed = [[-(1.0 + 2.0 * y), -2.0 * x], [-2.0 * x, -(1.0 - 2.0 * y)]];
        for i in 0..2 {
            assert_eq!(a[(i, 2 + i)], 1.0);
            for j in 0..2 {
                worst = worst.max((a[(2 + i, j)] - closed[i][j]).abs() / 3.0);
            }
        }
    }
    println!("Jacobians of natural systems: {worst:e}");
    assert!(worst <= AGREE);
}

/// Kahan-Li 8, the default method of a natural system, on the compiled Hénon-Heiles against the
/// same method on the dual-number system: 1000 steps of h = 0.01 on a regular orbit (E = 0.05) end
/// at the same point to 1e-14 (the two forces differ by an ulp or so where they differ, and a regular
/// orbit adds such differences about linearly; measured 4.1e-16), and the energy error of the
/// compiled run is at rounding level, as an order-8 method's is at this step (measured 9.2e-16;
/// bound 1e-14).
#[test]
fn kahan_li8_runs_on_the_compiled_force() {
    let compiled = Natural::unit(HenonHeiles).compile().unwrap();
    let h0 = compiled.energy(&[0.1, 0.0], &[0.0, 0.3]).unwrap();
    let mut a = compiled.default_method();
    let mut b = Natural::unit(HenonHeiles).default_method();
    assert_eq!(a.name(), b.name());
    let (mut s, mut u) = (
        State::new(0.0, [0.1, 0.0], [0.0, 0.3]),
        State::new(0.0, [0.1, 0.0], [0.0, 0.3]),
    );
    for _ in 0..1000 {
        a.step(&mut s, 0.01).unwrap();
        b.step(&mut u, 0.01).unwrap();
    }
    let d = (s.q[0] - u.q[0]).abs().max((s.q[1] - u.q[1]).abs());
    let dh = (a.base().system().energy(s.q.as_slice(), s.v.as_slice()).unwrap() - h0).abs();
    println!("Kahan-Li 8, compiled against dual numbers: |Δq| = {d:e}; |ΔE| = {dh:e}");
    assert!(d <= 1e-14 && dh < 1e-14);
}

/// A one-sided wall V = ½ k (x − 1)² for x > 1, else 0, recorded inside (x < 1): one guard; beyond the
/// wall the guard fails and the dual-number path answers with the wall's force −k (x − 1).
#[test]
fn a_branch_of_the_potential_is_guarded() {
    struct Wall;
    impl Potential for Wall {
        fn dof(&self) -> usize {
            1
        }
        fn potential<D: Scalar>(&self, q: &[D]) -> D {
            let d = q[0] - 1.0;
            if d > D::from(0.0) {
                d * d * 50.0
            } else {
                d * 0.0
            }
        }
    }
    let compiled = CompiledNatural::at(Natural::unit(Wall), &[0.5]).unwrap();
    assert_eq!(compiled.guards(), 1);
    let mut a = [0.0];
    compiled.accelerations(&[0.2], &mut a).unwrap();
    assert_eq!(a[0], 0.0);
    compiled.accelerations(&[1.2], &mut a).unwrap();
    assert!((a[0] + 100.0 * 0.2).abs() < 1e-12, "{a:?}");
}

/// The error contract: a non-finite q gives the dual-number path's error, wrong lengths a dimension
/// error, and neither panics.
#[test]
fn errors_are_those_of_the_dual_path() {
    let compiled = Natural::unit(Kepler).compile().unwrap();
    let dual = Natural::unit(Kepler);
    let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
    for q in [[f64::NAN, 0.0], [0.0, 0.0]] {
        let ec = compiled.accelerations(&q, &mut a).unwrap_err();
        let ed = dual.accelerations(&q, &mut b).unwrap_err();
        // (Compared as text: the error carries t = NaN, a time it does not know.)
        assert_eq!(format!("{ec:?}"), format!("{ed:?}"));
    }
    assert!(matches!(
        compiled.accelerations(&[0.1], &mut a),
        Err(noether_core::Error::Dimension { .. })
    ));
    let (mut dq, mut dv) = ([0.0; 2], [0.0; 3]);
    assert!(compiled
        .rates(0.0, &[0.3, 0.2], &[0.1, 0.0], &mut dq, &mut dv)
        .is_err());
}

/// The compiled Jacobian of Hamilton's equations, J = [[H_pq, H_pp], [−H_qq, −H_qp]], against the
/// dual-number one for the unit double pendulum (H not separable) at 100 random states, and Gauss 6
/// (the default method of any H, Newton on that Jacobian) on the compiled system against the same
/// method on the dual-number one: 200 steps of h = 0.05 end at the same point to 1e-14 (the Newton
/// iterations see the same rates to an ulp and stop on the same test; measured 3.1e-16).
#[test]
fn hamiltonian_jacobian_and_gauss6() {
    let mut rnd = uniform(11);
    let h = UnitDoublePendulum { g: 9.81 };
    let compiled = HamiltonEquations::new(h).compile().unwrap();
    let dual = HamiltonEquations::new(h);
    let (mut a, mut b) = (DMatrix::zeros(4, 4), DMatrix::zeros(4, 4));
    let mut worst = 0.0_f64;
    for _ in 0..100 {
        let (q, p) = ([rnd(-2.0, 2.0), rnd(-2.0, 2.0)], [rnd(-2.0, 2.0), rnd(-2.0, 2.0)]);
        compiled.jacobian(0.0, &q, &p, &mut a).unwrap();
        dual.jacobian(0.0, &q, &p, &mut b).unwrap();
        worst = worst.max((&a - &b).amax() / b.amax());
    }
    let mut gc = compiled.default_method();
    let mut gd = dual.default_method();
    let (mut s, mut u) = (
        State::with_momenta(0.0, [0.5, -0.3], [0.2, 0.1]),
        State::with_momenta(0.0, [0.5, -0.3], [0.2, 0.1]),
    );
    for _ in 0..200 {
        gc.step(&mut s, 0.05).unwrap();
        gd.step(&mut u, 0.05).unwrap();
    }
    let d = (s.q[0] - u.q[0]).abs().max((s.q[1] - u.q[1]).abs());
    println!("Hamiltonian Jacobian: {worst:e}; Gauss 6 compiled against dual numbers: |Δq| = {d:e}");
    assert!(worst <= AGREE && d <= 1e-14);
}
