//! The Hamiltonian built from a Lagrangian by `LegendreTransform` against hand-written Hamiltonians:
//! values, gradients (Hamilton's equations) and Hessians (the Gauss-Legendre Jacobian) at random
//! states, and whole runs; and the typed errors of a degenerate Lagrangian.
//!
//! Tolerance: `TOL` = 1e-12 relative to the largest component of the hand-side vector or matrix
//! (crate doc). Both sides are exact: the transform solves q̇(p) to rounding and carries the
//! derivatives by the implicit-function theorem, so the two differ by rounding in different
//! operation orders and in the linear solves of well-conditioned mass matrices (measured worst
//! errors in each test). A wrong derivative order (say a Hessian without the Newton step in the dual
//! scalar) is off by O(1).

use super::hamilton::ChargeH;
use super::systems::{ChargeInField, DoublePendulum, DoublePendulumH, HeavyTop};
use super::{charge_state, draw, for_states, Sample, TOL};
use noether_core::integrators::{Dop853, Gauss};
use noether_core::{
    Driver, Error, EulerLagrange, HamiltonEquations, Hamiltonian, Lagrangian, LegendreTransform, Momenta,
    Save, Scalar, Solution, State,
};
use rand::rngs::StdRng;
use rand::Rng;
use std::f64::consts::PI;

/// max_i |a_i − b_i| / max(max_i |b_i|, floor): the error measure of `assert_rel`.
fn rel_err(a: &[f64], b: &[f64], floor: f64) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(floor, |m, x| m.max(x.abs()));
    a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

/// Compares the value, ∂H/∂p, ∂H/∂q and the Hessian of the transform with those of the hand-written
/// H (both differentiated by AD: the hand-written H is a closed form, its AD derivatives exact) at
/// (t, q, p); returns the worst relative error.
fn compare<L: Lagrangian, H: Hamiltonian>(
    what: &str,
    from_l: &HamiltonEquations<LegendreTransform<L>>,
    hand: &HamiltonEquations<H>,
    t: f64,
    q: &[f64],
    p: &[f64],
) -> f64 {
    let n = q.len();
    let (mut dq1, mut dp1, mut dq2, mut dp2) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    from_l.rates(t, q, p, &mut dq1, &mut dp1).unwrap();
    hand.rates(t, q, p, &mut dq2, &mut dp2).unwrap();
    let h1 = from_l.energy(t, q, p).unwrap();
    let h2 = hand.energy(t, q, p).unwrap();
    let (hess1, hess2) = (from_l.hessian(t, q, p).unwrap(), hand.hessian(t, q, p).unwrap());
    let errs = [
        ("H", rel_err(&[h1], &[h2], 1.0)),
        ("∂H/∂p", rel_err(&dq1, &dq2, 1.0)),
        ("∂H/∂q", rel_err(&dp1, &dp2, 1.0)),
        ("Hessian", rel_err(hess1.as_slice(), hess2.as_slice(), 1.0)),
    ];
    for (name, e) in errs {
        assert!(
            e <= TOL,
            "{what} {name} at t = {t}, q = {q:?}, p = {p:?}: relative error {e:e} > {TOL:e}"
        );
    }
    errs.iter().fold(0.0, |m, (_, e)| m.max(*e))
}

// ---------------------------------------------------------------------------------------------------
/// A double-pendulum state: angles in [−π, π), momenta in [−5, 5).
fn pendulum_state(r: &mut StdRng) -> Sample<2> {
    (0.0, draw(r, -PI, PI), draw(r, -5.0, 5.0))
}

#[test]
fn ad_vs_hand_legendre_transform_double_pendulum() {
    let sys = DoublePendulum::default();
    let from_l = HamiltonEquations::new(LegendreTransform::new(sys));
    let hand = HamiltonEquations::new(DoublePendulumH(sys));
    let mut worst = 0.0_f64;
    for_states(41, 100, pendulum_state, |t, q, p| {
        worst = worst.max(compare("double pendulum", &from_l, &hand, t, q, p));
        // And the gradient by hand: with u = M⁻¹ p (= q̇), ∂M/∂θ1 = −∂M/∂θ2 = −m2 l1 l2 sin Δ [[0, 1], [1, 0]],
        // ∂H/∂θ_k = −½ uᵀ (∂M/∂θ_k) u + ∂V/∂θ_k: ∂H/∂θ1 = m2 l1 l2 sin Δ u1 u2 + (m1+m2) g l1 sin θ1,
        // ∂H/∂θ2 = −m2 l1 l2 sin Δ u1 u2 + m2 g l2 sin θ2; ∂H/∂p = u.
        let m = sys.hand_mass(q);
        let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        let u = [
            (m[1][1] * p[0] - m[0][1] * p[1]) / det,
            (m[0][0] * p[1] - m[1][0] * p[0]) / det,
        ];
        let k = sys.m2 * sys.l1 * sys.l2 * (q[0] - q[1]).sin() * u[0] * u[1];
        let dh_dq = [
            k + (sys.m1 + sys.m2) * sys.g * sys.l1 * q[0].sin(),
            -k + sys.m2 * sys.g * sys.l2 * q[1].sin(),
        ];
        let (mut dq, mut dp) = ([0.0; 2], [0.0; 2]);
        from_l.rates(t, q, p, &mut dq, &mut dp).unwrap();
        let e = rel_err(&dq, &u, 1.0).max(rel_err(&dp.map(|x| -x), &dh_dq, 1.0));
        assert!(e <= TOL, "double pendulum gradient by hand: {e:e}");
        worst = worst.max(e);
    });
    // Measured: worst 3.4e-15.
    eprintln!("double pendulum: worst relative error {worst:e}");
}

// ---------------------------------------------------------------------------------------------------
/// Heavy symmetric top by hand (Goldstein §5.7): with s = sin θ, c = cos θ,
/// H = p_θ²/(2 I1) + (p_φ − p_ψ c)²/(2 I1 s²) + p_ψ²/(2 I3) + M g ℓ c.
#[derive(Debug, Clone, Copy)]
struct HeavyTopH(HeavyTop);

impl Hamiltonian for HeavyTopH {
    fn dof(&self) -> usize {
        3
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let s = &self.0;
        let (sn, c) = q[0].sin_cos();
        let w = p[1] - p[2] * c;
        p[0] * p[0] * (0.5 / s.i1) + w * w / (sn * sn) * (0.5 / s.i1) + p[2] * p[2] * (0.5 / s.i3) + c * s.mgl
    }
}

#[test]
fn ad_vs_hand_legendre_transform_heavy_top() {
    let sys = HeavyTop::default();
    let from_l = HamiltonEquations::new(LegendreTransform::new(sys));
    let hand = HamiltonEquations::new(HeavyTopH(sys));
    // θ away from the poles of the chart (sin θ ≥ sin 0.3: M is well conditioned there).
    let state = |r: &mut StdRng| -> Sample<3> {
        let q = [
            r.random_range(0.3..PI - 0.3),
            r.random_range(-PI..PI),
            r.random_range(-PI..PI),
        ];
        (0.0, q, draw(r, -3.0, 3.0))
    };
    let mut worst = 0.0_f64;
    for_states(42, 100, state, |t, q, p| {
        worst = worst.max(compare("heavy top", &from_l, &hand, t, q, p));
    });
    // Measured: worst 1.3e-15.
    eprintln!("heavy top: worst relative error {worst:e}");
}

// ---------------------------------------------------------------------------------------------------
#[test]
fn ad_vs_hand_legendre_transform_charge_in_magnetic_field() {
    let sys = ChargeInField::default();
    let from_l = HamiltonEquations::new(LegendreTransform::new(sys));
    let hand = HamiltonEquations::new(ChargeH(sys));
    let mut worst = 0.0_f64;
    for_states(43, 100, charge_state::<3>, |t, q, p| {
        worst = worst.max(compare("charge", &from_l, &hand, t, q, p));
    });
    // Measured: worst 5.1e-16.
    eprintln!("charge: worst relative error {worst:e}");
}

// ---------------------------------------------------------------------------------------------------
/// A relativistic charge in a uniform magnetic field B ẑ, A = ½ B (−y, x, 0):
/// L = −m c² sqrt(1 − |v|²/c²) + e v·A (not quadratic in v: the transform needs Newton).
#[derive(Debug, Clone, Copy)]
struct RelativisticCharge {
    m: f64,
    c: f64,
    e: f64,
    b: f64,
}

const REL: RelativisticCharge = RelativisticCharge {
    m: 1.3,
    c: 2.0,
    e: -0.8,
    b: 1.7,
};

impl Lagrangian for RelativisticCharge {
    fn dof(&self) -> usize {
        3
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        let va = (v[1] * q[0] - v[0] * q[1]) * (0.5 * self.b);
        -(-v2 / (self.c * self.c) + 1.0).sqrt() * (self.m * self.c * self.c) + va * self.e
    }
}

/// By hand (Jackson §12.1): H = sqrt(m²c⁴ + c² |p − eA|²).
#[derive(Debug, Clone, Copy)]
struct RelativisticChargeH(RelativisticCharge);

impl Hamiltonian for RelativisticChargeH {
    fn dof(&self) -> usize {
        3
    }
    fn hamiltonian<D: Scalar>(&self, _t: D, q: &[D], p: &[D]) -> D {
        let s = &self.0;
        let (px, py) = (p[0] + q[1] * (0.5 * s.e * s.b), p[1] - q[0] * (0.5 * s.e * s.b));
        let pi2 = px * px + py * py + p[2] * p[2];
        (pi2 * (s.c * s.c) + (s.m * s.m * s.c.powi(4))).sqrt()
    }
}

#[test]
fn ad_vs_hand_legendre_transform_relativistic_charge() {
    let from_l = HamiltonEquations::new(LegendreTransform::new(REL));
    let hand = HamiltonEquations::new(RelativisticChargeH(REL));
    // |p − eA| up to ≈ 10 = 3.8 m c: γ up to ≈ 4.
    let state = |r: &mut StdRng| -> Sample<3> { (0.0, draw(r, -2.0, 2.0), draw(r, -5.0, 5.0)) };
    let mut worst = 0.0_f64;
    for_states(44, 100, state, |t, q, p| {
        worst = worst.max(compare("relativistic charge", &from_l, &hand, t, q, p));
    });
    // The free particle (e = 0): H = sqrt(m²c⁴ + c²|p|²).
    let free = RelativisticCharge { e: 0.0, ..REL };
    let (from_l, hand) = (
        HamiltonEquations::new(LegendreTransform::new(free)),
        HamiltonEquations::new(RelativisticChargeH(free)),
    );
    for_states(45, 100, state, |t, q, p| {
        worst = worst.max(compare("relativistic free particle", &from_l, &hand, t, q, p));
    });
    // Measured: worst 4.0e-16.
    eprintln!("relativistic: worst relative error {worst:e}");
}

// ---------------------------------------------------------------------------------------------------
/// Gauss-Legendre of order 6 on Hamilton's equations of `h` from `start`, step `step` up to `t_end`,
/// saving every `every`-th state.
fn run_gauss6<H: Hamiltonian>(
    h: H,
    start: &State<Momenta>,
    step: f64,
    t_end: f64,
    every: usize,
) -> Solution<Momenta> {
    Driver::new(Gauss::gauss6(HamiltonEquations::new(h)), start.clone())
        .unwrap()
        .step_size(step)
        .unwrap()
        .save(Save::Every(every))
        .unwrap()
        .run_until(t_end)
        .unwrap()
}

#[test]
fn ad_vs_hand_legendre_transform_trajectories_double_pendulum() {
    // Gauss-Legendre (order 6, h = 0.01, t ∈ [0, 10]) on the transform and on the hand-written H
    // solve the same equations with the same Newton: they agree to rounding amplified over the run
    // (tolerance 5e-14). The Lagrangian run (DOP853, tolerances 1e-13) mapped to momenta by
    // p = ∂L/∂q̇ agrees to the global errors of the two methods (a different method: tolerance 1e-10,
    // on the measured 8.0e-11; any error of the transform's derivatives would be O(h) and larger).
    let sys = DoublePendulum::default();
    let el = EulerLagrange::new(sys);
    let start_v = State::new(0.0, [0.6, -0.4], [0.3, -0.2]);
    let start_p = el.to_momenta(&start_v).unwrap();
    let (h, t_end, every) = (0.01, 10.0, 100);
    let from_l = run_gauss6(LegendreTransform::new(sys), &start_p, h, t_end, every);
    let hand = run_gauss6(DoublePendulumH(sys), &start_p, h, t_end, every);
    let times = from_l.times().to_vec();
    assert_eq!(times.len(), 11);
    let lagrange = Driver::new(Dop853::new(&el).tolerances(1e-13, 1e-13).unwrap(), start_v)
        .unwrap()
        .save(Save::Times(times.clone()))
        .unwrap()
        .run_until(t_end)
        .unwrap();
    let (mut vs_hand, mut vs_lagrange) = (0.0_f64, 0.0_f64);
    for (i, &t) in times.iter().enumerate() {
        assert_eq!(hand.times()[i], t);
        let y = [from_l.q(i), from_l.v(i)].concat();
        vs_hand = vs_hand.max(rel_err(&y, &[hand.q(i), hand.v(i)].concat(), 1.0));
        let p = el.to_momenta(&lagrange.state(i)).unwrap();
        vs_lagrange = vs_lagrange.max(rel_err(&y, &[p.q.as_slice(), p.v.as_slice()].concat(), 1.0));
    }
    eprintln!("double pendulum runs: vs hand H {vs_hand:e}, vs Lagrangian DOP853 {vs_lagrange:e}");
    // Measured: 6.2e-15 and 8.0e-11.
    assert!(
        vs_hand <= 5e-14,
        "Gauss-6 on LegendreTransform vs hand H: {vs_hand:e}"
    );
    assert!(
        vs_lagrange <= 1e-10,
        "Gauss-6 on LegendreTransform vs DOP853 on L: {vs_lagrange:e}"
    );
}

#[test]
fn ad_vs_hand_legendre_transform_trajectories_relativistic_charge() {
    // Gyration in B: the transform (Newton for q̇(p)) against the closed-form H (rounding: tolerance
    // 5e-14), and against DOP853 on the Lagrangian (the methods' global errors: tolerance 1e-12 on the
    // measured 1.5e-13); h = 0.01 over t ∈ [0, 10] (the cyclotron period 2π γ m/(|e| B) ≈ 8).
    let el = EulerLagrange::new(REL);
    let start_v = State::new(0.0, [0.5, 0.0, 0.1], [0.0, 1.2, 0.3]);
    let start_p = el.to_momenta(&start_v).unwrap();
    let from_l = run_gauss6(LegendreTransform::new(REL), &start_p, 0.01, 10.0, 100);
    let hand = run_gauss6(RelativisticChargeH(REL), &start_p, 0.01, 10.0, 100);
    let times = from_l.times().to_vec();
    let lagrange = Driver::new(Dop853::new(&el).tolerances(1e-13, 1e-13).unwrap(), start_v)
        .unwrap()
        .save(Save::Times(times.clone()))
        .unwrap()
        .run_until(10.0)
        .unwrap();
    let (mut vs_hand, mut vs_lagrange) = (0.0_f64, 0.0_f64);
    for i in 0..times.len() {
        let y = [from_l.q(i), from_l.v(i)].concat();
        vs_hand = vs_hand.max(rel_err(&y, &[hand.q(i), hand.v(i)].concat(), 1.0));
        let p = el.to_momenta(&lagrange.state(i)).unwrap();
        vs_lagrange = vs_lagrange.max(rel_err(&y, &[p.q.as_slice(), p.v.as_slice()].concat(), 1.0));
    }
    eprintln!("relativistic charge runs: vs hand H {vs_hand:e}, vs Lagrangian DOP853 {vs_lagrange:e}");
    // Measured: 5.3e-16 and 1.5e-13.
    assert!(
        vs_hand <= 5e-14,
        "Gauss-6 on LegendreTransform vs hand H: {vs_hand:e}"
    );
    assert!(
        vs_lagrange <= 1e-12,
        "Gauss-6 on LegendreTransform vs DOP853 on L: {vs_lagrange:e}"
    );
}

// ---------------------------------------------------------------------------------------------------
/// A degenerate Lagrangian: L = ½ (q̇₀ + q̇₁)² − ½ |q|², M = [[1, 1], [1, 1]] singular everywhere.
struct Degenerate;

impl Lagrangian for Degenerate {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        let s = v[0] + v[1];
        s * s * 0.5 - (q[0] * q[0] + q[1] * q[1]) * 0.5
    }
}

/// Not convex in q̇: L = ½ q̇₀² − ½ q̇₁² − ½ |q|² (M = diag(1, −1), regular but indefinite).
struct Indefinite;

impl Lagrangian for Indefinite {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
        (v[0] * v[0] - v[1] * v[1]) * 0.5 - (q[0] * q[0] + q[1] * q[1]) * 0.5
    }
}

#[test]
fn bad_input_legendre_transform_typed_errors() {
    // A singular mass matrix: the typed error through the equations and through a Gauss run.
    let h = HamiltonEquations::new(LegendreTransform::new(Degenerate));
    let (mut dq, mut dp) = ([0.0; 2], [0.0; 2]);
    let err = h
        .rates(0.5, &[0.1, 0.2], &[1.0, 1.0], &mut dq, &mut dp)
        .unwrap_err();
    assert!(
        matches!(err, Error::SingularMassMatrix { t, .. } if t == 0.5),
        "{err}"
    );
    assert!(matches!(
        h.energy(0.5, &[0.1, 0.2], &[1.0, 1.0]),
        Err(Error::SingularMassMatrix { .. })
    ));
    assert!(h.hamiltonian().value(0.5, &[0.1, 0.2], &[1.0, 1.0]).is_err());
    // The value itself is NaN (the convention of `Hamiltonian::failure`), never a number.
    assert!(h
        .hamiltonian()
        .hamiltonian(0.5, &[0.1, 0.2], &[1.0, 1.0])
        .is_nan());
    let mut run = Driver::new(Gauss::gauss6(h), State::with_momenta(0.0, [0.1, 0.2], [1.0, 1.0]))
        .unwrap()
        .step_size(0.01)
        .unwrap();
    let err = run.run_until(1.0).unwrap_err();
    assert!(matches!(err, Error::SingularMassMatrix { .. }), "{err}");
    assert_eq!(run.state().t, 0.0);
    // Same with a constant mass matrix declared (the quadratic path).
    struct DegenerateConstant;
    impl Lagrangian for DegenerateConstant {
        fn dof(&self) -> usize {
            2
        }
        fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
            Degenerate.lagrangian(t, q, v)
        }
        fn constant_mass_matrix(&self) -> bool {
            true
        }
    }
    let h = HamiltonEquations::new(LegendreTransform::new(DegenerateConstant));
    let err = h
        .rates(0.0, &[0.1, 0.2], &[1.0, 1.0], &mut dq, &mut dp)
        .unwrap_err();
    assert!(matches!(err, Error::SingularMassMatrix { .. }), "{err}");
    // Indefinite: regular M with eigenvalues ±1, reported with its smallest relative eigenvalue −1.
    let h = HamiltonEquations::new(LegendreTransform::new(Indefinite));
    match h
        .rates(0.0, &[0.1, 0.2], &[1.0, 1.0], &mut dq, &mut dp)
        .unwrap_err()
    {
        Error::IndefiniteMassMatrix { eigenvalue, .. } => assert_eq!(eigenvalue, -1.0),
        other => panic!("expected an indefinite mass matrix, got {other}"),
    }
    // Non-finite input: the input error, naming p.
    let h = HamiltonEquations::new(LegendreTransform::new(DoublePendulum::default()));
    assert!(h
        .hamiltonian()
        .hamiltonian(0.0, &[0.1, 0.2], &[f64::NAN, 1.0])
        .is_nan());
    assert!(matches!(
        h.hamiltonian().value(0.0, &[0.1, 0.2], &[f64::NAN, 1.0]),
        Err(Error::NonFinite { what: "p", index: 0 })
    ));
}

#[test]
fn ad_vs_hand_legendre_transform_quadratic_path() {
    // The charge declares nothing; the same Lagrangian declaring its constant mass matrix m I takes
    // the one-gradient path (no Newton) and gives the same H, gradients and Hessian.
    #[derive(Debug, Clone, Copy)]
    struct ChargeConstant(ChargeInField);
    impl Lagrangian for ChargeConstant {
        fn dof(&self) -> usize {
            3
        }
        fn lagrangian<D: Scalar>(&self, t: D, q: &[D], v: &[D]) -> D {
            self.0.lagrangian(t, q, v)
        }
        fn constant_mass_matrix(&self) -> bool {
            true
        }
    }
    let sys = ChargeInField::default();
    let from_l = HamiltonEquations::new(LegendreTransform::new(ChargeConstant(sys)));
    let hand = HamiltonEquations::new(ChargeH(sys));
    let mut worst = 0.0_f64;
    for_states(46, 100, charge_state::<3>, |t, q, p| {
        worst = worst.max(compare("charge (constant M)", &from_l, &hand, t, q, p));
    });
    // Measured: worst 6.7e-16.
    eprintln!("charge, constant M: worst relative error {worst:e}");
}

/// Issue 29 item 5: the transform's solve for q̇ was warm-started from the last solve (shared behind a
/// `Mutex`), so H and its derivatives at a point depended in the last bits on what had been evaluated
/// before, and on which thread. Now every point gives the bits of a fresh transform, after any
/// history and on any thread (L = 0.8 (cosh θ̇₁ − 1) + ½ θ̇₂² + θ̇₁ θ̇₂ cos θ₁/4 + cos θ₁: Newton needs
/// several iterations).
#[test]
fn regress_legendre_transform_is_independent_of_call_history_and_threads() {
    #[derive(Clone, Copy)]
    struct Stiff;
    impl Lagrangian for Stiff {
        fn dof(&self) -> usize {
            2
        }
        fn lagrangian<D: Scalar>(&self, _t: D, q: &[D], v: &[D]) -> D {
            (v[0].cosh() - 1.0) * 0.8 + v[1] * v[1] * 0.5 + v[0] * v[1] * q[0].cos() * 0.25 + q[0].cos()
        }
    }
    let points: Vec<([f64; 2], [f64; 2])> = (0..60)
        .map(|i| {
            let s = i as f64;
            (
                [0.3 * (0.7 * s).sin(), 0.1 * s],
                [1.5 * (0.37 * s).cos(), 0.2 - 0.01 * s],
            )
        })
        .collect();
    let bits = |h: &HamiltonEquations<LegendreTransform<Stiff>>, (q, p): &([f64; 2], [f64; 2])| {
        let (mut dq, mut dp) = ([0.0; 2], [0.0; 2]);
        h.rates(0.0, q, p, &mut dq, &mut dp).unwrap();
        let hess = h.hessian(0.0, q, p).unwrap();
        let e = h.energy(0.0, q, p).unwrap();
        let mut out: Vec<u64> = [e, dq[0], dq[1], dp[0], dp[1]]
            .iter()
            .map(|x| x.to_bits())
            .collect();
        out.extend(hess.iter().map(|x| x.to_bits()));
        out
    };
    let expected: Vec<Vec<u64>> = points
        .iter()
        .map(|x| bits(&HamiltonEquations::new(LegendreTransform::new(Stiff)), x))
        .collect();
    let shared = HamiltonEquations::new(LegendreTransform::new(Stiff));
    let differ = |got: &[Vec<u64>]| {
        (0..got.len())
            .filter(|&i| got[i] != expected[i])
            .collect::<Vec<_>>()
    };
    let forward: Vec<Vec<u64>> = points.iter().map(|x| bits(&shared, x)).collect();
    assert_eq!(differ(&forward), Vec::<usize>::new(), "after the previous point");
    let mut backward: Vec<Vec<u64>> = points.iter().rev().map(|x| bits(&shared, x)).collect();
    backward.reverse();
    assert_eq!(differ(&backward), Vec::<usize>::new(), "after the next point");
    // Four threads on the shared transform, each point evaluated by each thread in its own order.
    let threaded: Vec<Vec<Vec<u64>>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..4)
            .map(|k| {
                let (points, bits, shared) = (&points, &bits, &shared);
                s.spawn(move || {
                    let mut out = vec![Vec::new(); points.len()];
                    for j in 0..points.len() {
                        let i = (j * [1, 7, 11, 13][k] + k) % points.len();
                        out[i] = bits(shared, &points[i]);
                    }
                    out
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for (k, got) in threaded.iter().enumerate() {
        assert_eq!(differ(got), Vec::<usize>::new(), "thread {k}");
    }
}
